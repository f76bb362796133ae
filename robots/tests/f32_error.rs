//! Single precision, measured: every robot of this crate generated a second time with
//! `scalar: f32` (the macro's file form, same TOML file) and compared with the f64
//! generated code over many random configurations within the joint limits.
//!
//! Both sides get the *same* joint values (`q` rounded to f32 first, then widened back to
//! f64 for the reference), so the numbers measure the arithmetic of the f32 code (and its
//! parameters rounded to f32), not the rounding of the inputs. The error that rounding
//! `q` adds on top is measured too and printed as `pos(q)`.
//!
//! Run with `cargo test -p kinegen-robots --test f32_error -- --nocapture` to see the table
//! that `robots/README.md` ("Single precision") quotes.

// Parameter names follow the DH tables (`L1`, `a2`).
#![allow(non_snake_case)]

use kinegen_robots::*;

/// Random configurations per robot.
const SAMPLES: usize = 20_000;

/// The f32 twins: the same TOML files with `scalar: f32` overriding the file's scalar.
/// (Their closed-form IK is generated too, so the arms without one get the same
/// compile-time note as their f64 originals: allowed, as in `src/lib.rs`.)
macro_rules! f32_twin {
    ($($name:ident = $file:literal;)*) => {$(
        kinegen::kinematics! {
            #[allow(deprecated)]
            struct $name = $file;
            scalar: f32,
        }
    )*};
}

f32_twin! {
    PlanarRr32 = "planar_rr.toml";
    PlanarRrr32 = "planar_rrr.toml";
    Ur3_32 = "ur3.toml";
    Ur5_32 = "ur5.toml";
    Ur10_32 = "ur10.toml";
    Ur5e32 = "ur5e.toml";
    Ur10e32 = "ur10e.toml";
    Puma560_32 = "puma560.toml";
    Stanford32 = "stanford.toml";
    Panda32 = "panda.toml";
    KukaIiwa14_32 = "kuka_iiwa14.toml";
    KukaKr6R900_32 = "kuka_kr6_r900.toml";
    AbbIrb120_32 = "abb_irb120.toml";
    AbbIrb140_32 = "abb_irb140.toml";
    Scara32 = "scara.toml";
    CylindricalRpp32 = "cylindrical_rpp.toml";
}

/// splitmix64: a fixed seed keeps the measured maxima reproducible.
struct Rng(u64);

impl Rng {
    fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Largest differences between the f32 and the f64 generated code for one robot.
#[derive(Debug, Default)]
struct Errors {
    name: &'static str,
    /// Largest `|p64|` seen (m): the scale of the position error.
    reach: f64,
    /// `‖p32 − p64‖` (m), same joint values.
    pos: f64,
    /// `‖p32(q as f32) − p64(q)‖` (m): with the rounding of the joint values.
    pos_q: f64,
    /// Largest rotation-matrix entry difference.
    rot: f64,
    /// Linear rows of the Jacobian (m/rad or m/m).
    jac_lin: f64,
    /// Angular rows of the Jacobian (dimensionless).
    jac_ang: f64,
    /// Largest `|det64|` seen (0 when there is no determinant).
    det_scale: f64,
    /// `|det32 − det64|`.
    det: f64,
}

/// Joint ranges to sample: the table's limits; where it gives none, `[-π, π]` for
/// revolute joints and `prismatic` (metres) for prismatic ones.
fn ranges<const N: usize>(
    limits: [[f64; 2]; N],
    prismatic: &[usize],
    stroke: [f64; 2],
) -> [[f64; 2]; N] {
    let mut r = limits;
    for (i, lim) in r.iter_mut().enumerate() {
        if !lim[0].is_finite() || !lim[1].is_finite() {
            *lim = if prismatic.contains(&i) {
                stroke
            } else {
                [-core::f64::consts::PI, core::f64::consts::PI]
            };
        }
    }
    r
}

type Det<'a, const N: usize> = (&'a dyn Fn(&[f64; N]) -> f64, &'a dyn Fn(&[f32; N]) -> f32);

#[allow(clippy::too_many_arguments)]
fn measure<const N: usize>(
    name: &'static str,
    ranges: [[f64; 2]; N],
    seed: u64,
    fk: &dyn Fn(&[f64; N]) -> [[f64; 4]; 4],
    fk32: &dyn Fn(&[f32; N]) -> [[f32; 4]; 4],
    jac: &dyn Fn(&[f64; N]) -> [[f64; N]; 6],
    jac32: &dyn Fn(&[f32; N]) -> [[f32; N]; 6],
    det: Option<Det<'_, N>>,
) -> Errors {
    let mut rng = Rng(seed);
    let mut e = Errors {
        name,
        ..Errors::default()
    };
    for _ in 0..SAMPLES {
        let mut q_exact = [0.0f64; N];
        for (q, [lo, hi]) in q_exact.iter_mut().zip(ranges) {
            *q = lo + (hi - lo) * rng.next_f64();
        }
        let q32 = q_exact.map(|x| x as f32);
        let q = q32.map(f64::from);

        let (t, t32, t_exact) = (fk(&q), fk32(&q32), fk(&q_exact));
        let dist = |a: [f64; 3]| (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        let p = [t[0][3], t[1][3], t[2][3]];
        let d = |r: usize, t: &[[f64; 4]; 4]| f64::from(t32[r][3]) - t[r][3];
        e.reach = e.reach.max(dist(p));
        e.pos = e.pos.max(dist([d(0, &t), d(1, &t), d(2, &t)]));
        e.pos_q = e
            .pos_q
            .max(dist([d(0, &t_exact), d(1, &t_exact), d(2, &t_exact)]));
        for r in 0..3 {
            for c in 0..3 {
                e.rot = e.rot.max((f64::from(t32[r][c]) - t[r][c]).abs());
            }
        }

        let (j, j32) = (jac(&q), jac32(&q32));
        for r in 0..6 {
            for c in 0..N {
                let diff = (f64::from(j32[r][c]) - j[r][c]).abs();
                if r < 3 {
                    e.jac_lin = e.jac_lin.max(diff);
                } else {
                    e.jac_ang = e.jac_ang.max(diff);
                }
            }
        }

        if let Some((det, det32)) = det {
            let d64 = det(&q);
            e.det_scale = e.det_scale.max(d64.abs());
            e.det = e.det.max((f64::from(det32(&q32)) - d64).abs());
        }
        assert!(
            t32.iter().flatten().all(|x| x.is_finite())
                && j32.iter().flatten().all(|x| x.is_finite()),
            "{name}: f32 result not finite at q = {q32:?}"
        );
    }
    e
}

/// One robot: its f64 type, its f32 twin, which joints are prismatic, and whether it has
/// a determinant (6 joints, or a square task Jacobian).
macro_rules! robot {
    ($f64:ident, $f32:ident, $seed:literal, prismatic $pris:expr, det) => {{
        let (a, b) = ($f64::default(), $f32::default());
        measure(
            $f64::NAME,
            ranges($f64::LIMITS, &$pris, [0.1, 1.0]),
            $seed,
            &|q| a.fk(q),
            &|q| b.fk(q),
            &|q| a.jacobian(q),
            &|q| b.jacobian(q),
            Some((&|q| a.jacobian_det(q), &|q| b.jacobian_det(q))),
        )
    }};
    ($f64:ident, $f32:ident, $seed:literal, prismatic $pris:expr) => {{
        let (a, b) = ($f64::default(), $f32::default());
        measure(
            $f64::NAME,
            ranges($f64::LIMITS, &$pris, [0.1, 1.0]),
            $seed,
            &|q| a.fk(q),
            &|q| b.fk(q),
            &|q| a.jacobian(q),
            &|q| b.jacobian(q),
            None,
        )
    }};
}

fn all_robots() -> Vec<Errors> {
    vec![
        robot!(PlanarRr, PlanarRr32, 1, prismatic [], det),
        robot!(PlanarRrr, PlanarRrr32, 2, prismatic [], det),
        robot!(Ur3, Ur3_32, 3, prismatic [], det),
        robot!(Ur5, Ur5_32, 4, prismatic [], det),
        robot!(Ur10, Ur10_32, 5, prismatic [], det),
        robot!(Ur5e, Ur5e32, 6, prismatic [], det),
        robot!(Ur10e, Ur10e32, 7, prismatic [], det),
        robot!(Puma560, Puma560_32, 8, prismatic [], det),
        robot!(Stanford, Stanford32, 9, prismatic[2], det),
        robot!(Panda, Panda32, 10, prismatic []),
        robot!(KukaIiwa14, KukaIiwa14_32, 11, prismatic []),
        robot!(KukaKr6R900, KukaKr6R900_32, 12, prismatic [], det),
        robot!(AbbIrb120, AbbIrb120_32, 13, prismatic [], det),
        robot!(AbbIrb140, AbbIrb140_32, 14, prismatic [], det),
        robot!(Scara, Scara32, 15, prismatic[2], det),
        robot!(CylindricalRpp, CylindricalRpp32, 16, prismatic [1, 2], det),
    ]
}

#[test]
fn f32_code_agrees_with_f64_code_on_every_robot() {
    let errors = all_robots();
    println!(
        "{:<22} {:>7} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}",
        "robot", "reach", "pos", "pos(q)", "rot", "J lin", "J ang", "|det|max", "det"
    );
    for e in &errors {
        println!(
            "{:<22} {:>7.3} {:>9.2e} {:>9.2e} {:>9.2e} {:>9.2e} {:>9.2e} {:>9.2e} {:>9.2e}",
            e.name, e.reach, e.pos, e.pos_q, e.rot, e.jac_lin, e.jac_ang, e.det_scale, e.det
        );
    }

    // Bounds from the measured maxima (see the table and robots/README.md), with 2–3×
    // headroom, in units of f32::EPSILON (1.19e-7) times the robot's scale: measured at
    // most 1.7 ε·reach (position, linear Jacobian rows), 2.1 ε (rotation, angular rows),
    // 2.6 ε·max|det| (det).
    let eps = f64::from(f32::EPSILON);
    let mut failures = Vec::new();
    for e in &errors {
        let mut check = |what: &str, err: f64, bound: f64| {
            if err.is_nan() || err > bound {
                failures.push(format!(
                    "{}: {what} error {err:.3e} > bound {bound:.3e}",
                    e.name
                ));
            }
        };
        check("position (m)", e.pos, 4.0 * eps * e.reach);
        if e.reach <= 2.0 {
            // The absolute figure for the ~1 m arms people put on microcontrollers.
            check("position (m)", e.pos, 1e-6);
        }
        check("rotation entry", e.rot, 4.0 * eps);
        check("Jacobian linear entry", e.jac_lin, 4.0 * eps * e.reach);
        check("Jacobian angular entry", e.jac_ang, 4.0 * eps);
        check("det", e.det, 8.0 * eps * e.det_scale);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The measurement can fail: a deliberately wrong f32 twin (UR5 with `a2` off by 10 µm,
/// an error no larger than a sloppy datasheet transcription) exceeds the position bound.
#[test]
fn a_10_micrometre_slip_is_caught() {
    let (a, mut b) = (Ur5::default(), Ur5_32::default());
    b.a2 += 10e-6;
    let e = measure(
        "UR5 (a2 + 10 µm)",
        Ur5::LIMITS,
        4,
        &|q| a.fk(q),
        &|q| b.fk(q),
        &|q| a.jacobian(q),
        &|q| b.jacobian(q),
        None,
    );
    assert!(e.pos > 1e-6, "position error {:.3e} not detected", e.pos);
}
