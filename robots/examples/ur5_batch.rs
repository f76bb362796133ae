//! The generated UR5's `fk`, `jacobian` and `ik` over a batch, timed in the process: the
//! compiled side of the Python module's benchmark (`kinegen-py/bench/bench.py` runs it
//! on the configurations and poses it times itself, and checks the values equal).
//!
//! `ur5_batch Q.bin POSES.bin OUT.bin REPEATS`: `Q.bin` holds M×6 joint vectors and
//! `POSES.bin` M row-major 4×4 poses, little-endian f64. Writes `fk` (M×16) then
//! `jacobian` (M×36) to `OUT.bin`, and prints the best of `REPEATS` runs of each loop in
//! µs per item: `fk JACOBIAN IK SOLUTIONS` (IK: all solutions of each pose by `ik`; the
//! last field counts the exact ones, for a check against the Python side).

use std::hint::black_box;
use std::time::Instant;

use kinegen_robots::Ur5;

fn read(path: &str) -> Vec<f64> {
    let bytes = std::fs::read(path).unwrap_or_else(|e| fail(&format!("{path}: {e}")));
    bytes
        .chunks_exact(8)
        .map(|b| f64::from_le_bytes(b.try_into().expect("8 bytes")))
        .collect()
}

fn fail(why: &str) -> ! {
    eprintln!("ur5_batch: {why}");
    std::process::exit(2)
}

/// Best time per item (µs) of `repeats` runs of `f` over `m` items.
fn best(repeats: usize, m: usize, mut f: impl FnMut()) -> f64 {
    (0..repeats)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64() * 1e6 / m as f64
        })
        .fold(f64::INFINITY, f64::min)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() != 5 {
        fail("usage: ur5_batch Q.bin POSES.bin OUT.bin REPEATS");
    }
    let q: Vec<[f64; 6]> = read(&args[1])
        .chunks_exact(6)
        .map(|c| c.try_into().expect("6 values"))
        .collect();
    let poses: Vec<[[f64; 4]; 4]> = read(&args[2])
        .chunks_exact(16)
        .map(|c| core::array::from_fn(|i| core::array::from_fn(|j| c[4 * i + j])))
        .collect();
    let repeats: usize = args[4]
        .parse()
        .unwrap_or_else(|_| fail("REPEATS: a number"));
    let ur5 = Ur5::default();
    let mut fk = vec![[[0.0; 4]; 4]; q.len()];
    let mut jacobian = vec![[[0.0; 6]; 6]; q.len()];
    let t_fk = best(repeats, q.len(), || {
        for (x, out) in q.iter().zip(fk.iter_mut()) {
            *out = ur5.fk(black_box(x));
        }
    });
    let t_jacobian = best(repeats, q.len(), || {
        for (x, out) in q.iter().zip(jacobian.iter_mut()) {
            *out = ur5.jacobian(black_box(x));
        }
    });
    let mut exact = 0;
    let t_ik = best(repeats, poses.len(), || {
        exact = 0;
        for p in &poses {
            exact += black_box(ur5.ik(black_box(p)))
                .iter()
                .filter(|b| b.exact)
                .count();
        }
    });
    let mut bytes = Vec::with_capacity(8 * 52 * q.len());
    for t in &fk {
        bytes.extend(t.iter().flatten().flat_map(|v| v.to_le_bytes()));
    }
    for j in &jacobian {
        bytes.extend(j.iter().flatten().flat_map(|v| v.to_le_bytes()));
    }
    std::fs::write(&args[3], bytes).unwrap_or_else(|e| fail(&format!("{}: {e}", args[3])));
    println!("{t_fk} {t_jacobian} {t_ik} {exact}");
}
