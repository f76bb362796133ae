//! Run time of the generated second-order kinematics (issue 16; results and how to read
//! them in BENCHMARKS.md), UR5 and Panda:
//!
//! - `generated`: `jacobian`, `jdot_qdot`, `hessian`, `jacobian_dot` as `kinematics!`
//!   generates them (`kinegen_robots::{Ur5, Panda}`);
//! - `numeric_reference`: the textbook algorithm on fixed-size nalgebra types — the lean
//!   DH loop of `benches/kinematics.rs` for the Jacobian, the Hessian from cross products
//!   of its columns (`[z_j × v_i; z_j × z_i]`, Haviland & Corke), and `J̇ q̇` contracted
//!   from that Hessian (`Σ_j q̇_j H[j] q̇`).
//!
//! The targets: `jdot_qdot` at most 1.5× the time of `jacobian`, `hessian` at most 3×.
//! Every contender is checked against the generated code at start. Inputs cycle through
//! 1024 random configurations (and rates) inside the joint limits. `cargo bench --bench
//! second_order` ends by printing this run's medians with their ratios, then the same
//! ratios from interleaved batches.

mod common;

use common::{configurations, median, DhLoop, CONFIGS};
use criterion::{criterion_group, Bencher, Criterion};
use kinegen::SecondOrderKinematics;
use kinegen_robots::{Panda, Ur5};
use std::hint::black_box;
use std::time::{Duration, SystemTime};

/// Configurations and rates, cycled through together.
fn inputs<const N: usize>(limits: &[[f64; 2]; N]) -> Vec<([f64; N], [f64; N])> {
    let qs = configurations(limits, 0x5EC0_0D00 ^ N as u64);
    let rates = configurations(&[[-2.0, 2.0]; N], 0x0D07 ^ N as u64);
    qs.into_iter().zip(rates).collect()
}

fn cycle<const N: usize, R>(
    b: &mut Bencher,
    xs: &[([f64; N], [f64; N])],
    mut f: impl FnMut(&[f64; N], &[f64; N]) -> R,
) {
    let mut i = 0;
    b.iter(|| {
        let (q, qd) = black_box(xs[i]);
        i = (i + 1) & (CONFIGS - 1);
        f(&q, &qd)
    })
}

/// The generated values equal the reference's (|Δ| ≤ 1e-12 relative to max(1, |x|)).
fn check<const N: usize, K: SecondOrderKinematics<N>>(
    name: &str,
    robot: &K,
    lean: &DhLoop<N>,
    xs: &[([f64; N], [f64; N])],
) {
    let near = |a: f64, b: f64, what: &str| {
        assert!(
            (a - b).abs() <= 1e-12 * b.abs().max(1.0),
            "{name} {what}: generated {a} vs reference {b}"
        )
    };
    for (q, qd) in xs.iter().take(8) {
        let (h, hl) = (robot.hessian(q), lean.hessian(q));
        for k in 0..N {
            for r in 0..6 {
                for c in 0..N {
                    near(h[k][r][c], hl[k][(r, c)], &format!("H[{k}][{r}][{c}]"));
                }
            }
        }
        let (a, al) = (robot.jdot_qdot(q, qd), lean.jdot_qdot(q, qd));
        for r in 0..6 {
            near(a[r], al[r], &format!("J̇q̇[{r}]"));
        }
    }
}

fn bench_robot<const N: usize, K: SecondOrderKinematics<N>>(
    c: &mut Criterion,
    group: &str,
    robot: &K,
    file: &str,
) {
    let lean = DhLoop::<N>::new(&common::load(file));
    let xs = inputs(&robot.limits());
    check(group, robot, &lean, &xs);
    let mut g = c.benchmark_group(format!("{group}_second_order"));
    g.bench_function("generated/jacobian", |b| {
        cycle(b, &xs, |q, _| robot.jacobian(q))
    });
    g.bench_function("generated/jdot_qdot", |b| {
        cycle(b, &xs, |q, qd| robot.jdot_qdot(q, qd))
    });
    g.bench_function("numeric_reference/jdot_qdot", |b| {
        cycle(b, &xs, |q, qd| lean.jdot_qdot(q, qd))
    });
    g.bench_function("generated/hessian", |b| {
        cycle(b, &xs, |q, _| robot.hessian(q))
    });
    g.bench_function("numeric_reference/hessian", |b| {
        cycle(b, &xs, |q, _| lean.hessian(q))
    });
    g.bench_function("generated/jacobian_dot", |b| {
        cycle(b, &xs, |q, qd| robot.jacobian_dot(q, qd))
    });
    g.finish();
}

fn ur5(c: &mut Criterion) {
    bench_robot(c, "ur5", &Ur5::default(), "ur5.toml");
}

fn panda(c: &mut Criterion) {
    bench_robot(c, "panda", &Panda::default(), "panda.toml");
}

fn config() -> Criterion {
    Criterion::default()
        .sample_size(40)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
}

criterion_group! {
    name = benches;
    config = config();
    targets = ur5, panda
}

/// This run's medians and their ratios, as BENCHMARKS.md shows them.
fn summary(since: SystemTime) {
    let fmt = |x: Option<f64>| x.map_or("–".to_string(), |v| format!("{v:.1}"));
    let ratio = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) => format!("{:.2}×", a / b),
        _ => "–".to_string(),
    };
    println!("\n## Second order: medians of this run (ns) and ratios\n");
    println!("| robot | jacobian | jdot_qdot | hessian | jacobian_dot | reference jdot_qdot | reference hessian | jdot_qdot / jacobian | hessian / jacobian | reference / generated jdot_qdot | reference / generated hessian |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for robot in ["ur5", "panda"] {
        let m = |id: &str| median(&format!("{robot}_second_order"), id, since);
        let (j, a, h, jd) = (
            m("generated/jacobian"),
            m("generated/jdot_qdot"),
            m("generated/hessian"),
            m("generated/jacobian_dot"),
        );
        let (ra, rh) = (
            m("numeric_reference/jdot_qdot"),
            m("numeric_reference/hessian"),
        );
        if j.is_none() {
            continue;
        }
        println!(
            "| {robot} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            fmt(j),
            fmt(a),
            fmt(h),
            fmt(jd),
            fmt(ra),
            fmt(rh),
            ratio(a, j),
            ratio(h, j),
            ratio(ra, a),
            ratio(rh, h)
        );
    }
}

/// `a / b` from interleaved batches (median of 41 rounds, see `common::paired`) on
/// configuration/rate pairs.
fn paired_pairs<const N: usize, R, S>(
    xs: &[([f64; N], [f64; N])],
    mut a: impl FnMut(&[f64; N], &[f64; N]) -> R,
    mut b: impl FnMut(&[f64; N], &[f64; N]) -> S,
) -> f64 {
    // `common::paired` cycles one array: pack q and q̇ side by side in its index space.
    let idx: Vec<[f64; 1]> = (0..CONFIGS).map(|i| [i as f64]).collect();
    let at = |x: [f64; 1]| &xs[x[0] as usize];
    let fa = |x: [f64; 1]| {
        let (q, qd) = at(x);
        a(q, qd)
    };
    let fb = |x: [f64; 1]| {
        let (q, qd) = at(x);
        b(q, qd)
    };
    common::paired(&idx, fa, fb)
}

fn paired_row<const N: usize, K: SecondOrderKinematics<N>>(name: &str, robot: &K, file: &str) {
    let lean = DhLoop::<N>::new(&common::load(file));
    let xs = inputs(&robot.limits());
    let r = [
        paired_pairs(
            &xs,
            |q, qd| robot.jdot_qdot(q, qd),
            |q, _| robot.jacobian(q),
        ),
        paired_pairs(&xs, |q, _| robot.hessian(q), |q, _| robot.jacobian(q)),
        paired_pairs(
            &xs,
            |q, qd| lean.jdot_qdot(q, qd),
            |q, qd| robot.jdot_qdot(q, qd),
        ),
        paired_pairs(&xs, |q, _| lean.hessian(q), |q, _| robot.hessian(q)),
    ];
    println!(
        "| {name} | {:.2}× | {:.2}× | {:.2}× | {:.2}× |",
        r[0], r[1], r[2], r[3]
    );
}

fn paired_table() {
    println!("\n## Second order: ratios from interleaved batches (median of 41 rounds)\n");
    println!("| robot | jdot_qdot / jacobian | hessian / jacobian | reference / generated jdot_qdot | reference / generated hessian |");
    println!("|---|---:|---:|---:|---:|");
    paired_row("ur5", &Ur5::default(), "ur5.toml");
    paired_row("panda", &Panda::default(), "panda.toml");
}

// `KINEGEN_BENCH_PAIRED=1 cargo bench --bench second_order`: the interleaved ratios only.
fn main() {
    common::bench_main(benches, summary, paired_table);
}
