//! kinegen's generated closed-form `ik` against the `ik-geo` crate (IK-Geo, Elias & Wen,
//! subproblem decomposition), all solutions per call, on the same 1 000 poses (fk of
//! configurations within the limits, the seed of `benches/ik_closed_form.rs`).
//!
//! ik-geo is given the very geometry kinegen derives (`ik_geometry()`: joint axes and
//! points at q = 0, in ik-geo's product-of-exponentials form) and the same family
//! (three parallel + two intersecting for the UR5, spherical wrist + two parallel for the
//! PUMA 560). A one-off report checks that both forward kinematics agree, and counts the
//! solutions each returns, the exact ones (kinegen's fk within 1e-9 of the pose) and how
//! often the generating configuration is among them.
//!
//! kinegen returns a least-squares branch only for a pose no branch reaches; ik-geo
//! returns every branch, flagged least squares where it misses. On the UR5 the two sets
//! differ (the other elbow out of reach on some poses), so a second group times both on
//! the poses where ik-geo's every branch reaches — the same solutions from both.
//!
//! Run (needs CMake for NLopt): `cargo bench --manifest-path benches/ik-geo/Cargo.toml`.

use std::hint::black_box;

#[path = "../../common/ik.rs"]
#[allow(dead_code)]
mod ik_common;
use ik_common::{miss, poses, same};

use criterion::{criterion_group, criterion_main, Criterion};
use ik_geo::nalgebra::{Matrix3, Matrix3x6, SMatrix, Vector3, Vector6};

type Matrix3x7 = SMatrix<f64, 3, 7>;
use ik_geo::robot::{spherical_two_parallel, three_parallel_two_intersecting, IKSolver, Robot};
use kinegen::ik::geometry::Geometry;
use kinegen::Kinematics;
use kinegen_robots::{FanucCrx10iaL, KinovaJaco, Puma560, Ur5};

const POSES: usize = 1000;

/// kinegen's zero-configuration geometry as ik-geo's (H, P): P₀ = p₁, Pᵢ = pᵢ₊₁ − pᵢ,
/// P₆ = p_tool − p₆. ik-geo's fk has no tool rotation: its R is kinegen's R · R_toolᵀ.
///
/// A spherical wrist's three axes get one point, the wrist centre (ik-geo's spherical
/// families read `P₄ = P₅ = 0`; kinegen's points are any points on the axes).
fn poe(g: &Geometry<6>, spherical_wrist: bool) -> (Matrix3x6<f64>, Matrix3x7) {
    let mut g = *g;
    if spherical_wrist {
        let (c, _) =
            kinegen::ik::geometry::closest_points(&g.p[3], &g.h[3], &g.p[4], &g.h[4], 1e-12)
                .expect("axes 4 and 5 of a spherical wrist meet");
        g.p[3] = c;
        g.p[4] = c;
        g.p[5] = c;
    }
    let h = Matrix3x6::from_fn(|r, c| g.h[c][r]);
    let p = Matrix3x7::from_fn(|r, c| match c {
        0 => g.p[0][r],
        6 => g.p_tool[r] - g.p[5][r],
        _ => g.p[c][r] - g.p[c - 1][r],
    });
    (h, p)
}

/// kinegen's pose → ik-geo's (R, t).
fn target(g: &Geometry<6>, pose: &[[f64; 4]; 4]) -> (Matrix3<f64>, Vector3<f64>) {
    let r = Matrix3::from_fn(|i, j| pose[i][j]);
    let rt = Matrix3::from_fn(|i, j| g.r_tool[(i, j)]);
    (
        r * rt.transpose(),
        Vector3::new(pose[0][3], pose[1][3], pose[2][3]),
    )
}

fn check_fk(
    name: &str,
    robot: &Robot,
    g: &Geometry<6>,
    set: &[([[f64; 4]; 4], [f64; 6])],
    shift: &[f64; 6],
) {
    for (pose, q) in set {
        let q: [f64; 6] = std::array::from_fn(|i| q[i] - shift[i]);
        let (r, t) = robot.fk(&q);
        let (r0, t0) = target(g, pose);
        let d = (r - r0).amax() + (t - t0).amax();
        assert!(
            d < 1e-9,
            "{name}: ik-geo's fk differs from kinegen's at {q:?} by {d:e}"
        );
    }
}

fn report<R: Kinematics<6>>(
    name: &str,
    robot: &R,
    ours: impl Fn(&[[f64; 4]; 4]) -> Vec<([f64; 6], bool)>,
    geo: &Robot,
    g: &Geometry<6>,
    set: &[([[f64; 4]; 4], [f64; 6])],
    shift: &[f64; 6],
) {
    check_fk(name, geo, g, set, shift);
    let mut tally = [[0usize; 4]; 2]; // solutions, flagged exact, exact by fk, generating q found
    for (pose, q0) in set {
        let (r, t) = target(g, pose);
        let theirs: Vec<([f64; 6], bool)> = geo
            .ik(r, t)
            .into_iter()
            .map(|(q, ls): (Vector6<f64>, bool)| (std::array::from_fn(|i| q[i] + shift[i]), !ls))
            .collect();
        for (k, sols) in [ours(pose), theirs].iter().enumerate() {
            tally[k][0] += sols.len();
            tally[k][1] += sols.iter().filter(|s| s.1).count();
            tally[k][2] += sols
                .iter()
                .filter(|s| miss(robot, &s.0, pose) < 1e-9)
                .count();
            tally[k][3] += sols.iter().any(|s| same(&s.0, q0)) as usize;
        }
    }
    for (k, who) in ["kinegen", "ik-geo"].iter().enumerate() {
        let [n, flagged, exact, found] = tally[k];
        println!(
            "{name} {who:<8} {n:>5} solutions, {flagged:>5} flagged exact, {exact:>5} exact by fk (1e-9), generating q among them for {found}/{}",
            set.len()
        );
    }
}

fn bench(c: &mut Criterion) {
    let ur5 = Ur5::default();
    let puma = Puma560::default();
    let (gu, gp) = (ur5.ik_geometry(), puma.ik_geometry());
    let (hu, pu) = poe(&gu, false);
    let (hp, pp) = poe(&gp, true);
    let geo_ur5 = three_parallel_two_intersecting(hu, pu);
    let geo_puma = spherical_two_parallel(hp, pp);
    let ur5_set = poses(&ur5, 2026, POSES);
    let puma_set = poses(&puma, 2026, POSES);
    report(
        "UR5     ",
        &ur5,
        |p| ur5.ik(p).iter().map(|b| (b.q, b.exact)).collect(),
        &geo_ur5,
        &gu,
        &ur5_set,
        &[0.0; 6],
    );
    report(
        "PUMA 560",
        &puma,
        |p| puma.ik(p).iter().map(|b| (b.q, b.exact)).collect(),
        &geo_puma,
        &gp,
        &puma_set,
        &[0.0; 6],
    );
    let ur5_targets: Vec<_> = ur5_set.iter().map(|(p, _)| target(&gu, p)).collect();
    let puma_targets: Vec<_> = puma_set.iter().map(|(p, _)| target(&gp, p)).collect();
    let mut g = c.benchmark_group("ik_all_solutions_1000_poses");
    g.bench_function("ur5_kinegen_ik", |b| {
        b.iter(|| {
            for (pose, _) in &ur5_set {
                black_box(ur5.ik(black_box(pose)));
            }
        })
    });
    g.bench_function("ur5_ik_geo", |b| {
        b.iter(|| {
            for (r, t) in &ur5_targets {
                black_box(geo_ur5.ik(black_box(*r), black_box(*t)));
            }
        })
    });
    g.bench_function("puma560_kinegen_ik", |b| {
        b.iter(|| {
            for (pose, _) in &puma_set {
                black_box(puma.ik(black_box(pose)));
            }
        })
    });
    g.bench_function("puma560_ik_geo", |b| {
        b.iter(|| {
            for (r, t) in &puma_targets {
                black_box(geo_puma.ik(black_box(*r), black_box(*t)));
            }
        })
    });
    g.finish();
    // The UR5 poses on which both return the same set: ik-geo's every branch exact.
    let reached: Vec<_> = ur5_set
        .iter()
        .zip(&ur5_targets)
        .filter(|(_, (r, t))| geo_ur5.ik(*r, *t).iter().all(|(_, ls)| !ls))
        .collect();
    let same_sets = reached
        .iter()
        .filter(|((pose, _), (r, t))| ur5.ik(pose).len() == geo_ur5.ik(*r, *t).len())
        .count();
    println!(
        "UR5 poses every ik-geo branch reaches: {} of {POSES}; the same number of \
         solutions from both on {same_sets} of them",
        reached.len()
    );
    let mut g = c.benchmark_group(format!(
        "ik_ur5_{}_poses_every_branch_reaches",
        reached.len()
    ));
    g.bench_function("ur5_kinegen_ik", |b| {
        b.iter(|| {
            for ((pose, _), _) in &reached {
                black_box(ur5.ik(black_box(pose)));
            }
        })
    });
    g.bench_function("ur5_ik_geo", |b| {
        b.iter(|| {
            for (_, (r, t)) in &reached {
                black_box(geo_ur5.ik(black_box(*r), black_box(*t)));
            }
        })
    });
    g.finish();
}

/// `g` with joint `j`'s zero turned by `phi`: every axis, point and the tool after it
/// turned about axis `j` by `phi`, so that the new geometry at `q` is the old one at `q`
/// with `q_j + phi`.
fn rezeroed(g: &Geometry<6>, j: usize, phi: f64) -> Geometry<6> {
    let r = kinegen::ik::geometry::rot(&g.h[j], phi);
    let o = g.p[j];
    let mut out = *g;
    for k in j + 1..6 {
        out.h[k] = r * g.h[k];
        out.p[k] = r * (g.p[k] - o) + o;
    }
    out.r_tool = r * g.r_tool;
    out.p_tool = r * (g.p_tool - o) + o;
    out
}

/// The general 6R (issue 28): kinegen's `ik` (Raghavan–Roth elimination, an
/// eigenproblem) against ik-geo's 1-D search for arms with h2 ∥ h3 (`two_parallel`: a
/// search over q1 for sign changes of an error function — both the Jaco and the
/// CRX-10iA/L have h2 ∥ h3) on 100 poses, and its 2-D search for any 6R (`gen_six_dof`)
/// on 10.
fn bench_general(c: &mut Criterion) {
    let jaco = KinovaJaco::default();
    let crx = FanucCrx10iaL::default();
    // Both arms have h4 ∥ h6 at q = 0, where ik-geo's SP6 (about h4 and h6) degenerates
    // and it finds nothing: it is given the geometry with joint 5's zero turned by π/2
    // (its q5 = ours − π/2), its answers mapped back.
    let shift = [0.0, 0.0, 0.0, 0.0, std::f64::consts::FRAC_PI_2, 0.0];
    let (gj, gc) = (
        rezeroed(&jaco.ik_geometry(), 4, shift[4]),
        rezeroed(&crx.ik_geometry(), 4, shift[4]),
    );
    let (hj, pj) = poe(&gj, false);
    let (hc, pc) = poe(&gc, false);
    let jaco_1d = ik_geo::robot::two_parallel(hj, pj);
    let crx_1d = ik_geo::robot::two_parallel(hc, pc);
    let jaco_2d = ik_geo::robot::gen_six_dof(hj, pj);
    let crx_2d = ik_geo::robot::gen_six_dof(hc, pc);
    // ik-geo's 1-D search panics on some poses (`auxiliary.rs:154`, an `unwrap` on a NaN
    // comparison); those are counted and left out of both sides' sets.
    let survives = |geo: &Robot, g: &Geometry<6>, pose: &[[f64; 4]; 4]| {
        let (r, t) = target(g, pose);
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| geo.ik(r, t))).is_ok()
    };
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let keep = |set: Vec<([[f64; 4]; 4], [f64; 6])>, geo: &Robot, g: &Geometry<6>, name: &str| {
        let before = set.len();
        let kept: Vec<_> = set
            .into_iter()
            .filter(|(p, _)| survives(geo, g, p))
            .collect();
        println!(
            "{name}: ik-geo's two_parallel panicked on {} of {before} poses (left out)",
            before - kept.len()
        );
        kept
    };
    let jaco_set = keep(poses(&jaco, 28, 100), &jaco_1d, &gj, "Jaco");
    let crx_set = keep(poses(&crx, 28, 100), &crx_1d, &gc, "CRX");
    std::panic::set_hook(hook);
    let ours_jaco = |p: &[[f64; 4]; 4]| jaco.ik(p).iter().map(|b| (b.q, b.exact)).collect();
    let ours_crx = |p: &[[f64; 4]; 4]| crx.ik(p).iter().map(|b| (b.q, b.exact)).collect();
    report(
        "Jaco, ik-geo 1-D",
        &jaco,
        ours_jaco,
        &jaco_1d,
        &gj,
        &jaco_set,
        &shift,
    );
    report(
        "CRX,  ik-geo 1-D",
        &crx,
        ours_crx,
        &crx_1d,
        &gc,
        &crx_set,
        &shift,
    );
    report(
        "Jaco, ik-geo 2-D",
        &jaco,
        ours_jaco,
        &jaco_2d,
        &gj,
        &jaco_set[..10],
        &shift,
    );
    report(
        "CRX,  ik-geo 2-D",
        &crx,
        ours_crx,
        &crx_2d,
        &gc,
        &crx_set[..10],
        &shift,
    );
    println!(
        "timed: {} Jaco poses, {} CRX poses (1-D); the first 10 of each (2-D)",
        jaco_set.len(),
        crx_set.len()
    );
    let tj: Vec<_> = jaco_set.iter().map(|(p, _)| target(&gj, p)).collect();
    let tc: Vec<_> = crx_set.iter().map(|(p, _)| target(&gc, p)).collect();
    let mut g = c.benchmark_group("ik_general_6r_1d");
    g.sample_size(10);
    let jaco_ik = |p: &[[f64; 4]; 4]| jaco.ik(p);
    let crx_ik = |p: &[[f64; 4]; 4]| crx.ik(p);
    side_by_side(
        &mut g,
        "jaco",
        "ik_geo_two_parallel_1d",
        &jaco_set,
        jaco_ik,
        &jaco_1d,
        &tj,
    );
    side_by_side(
        &mut g,
        "crx",
        "ik_geo_two_parallel_1d",
        &crx_set,
        crx_ik,
        &crx_1d,
        &tc,
    );
    g.finish();
    let mut g = c.benchmark_group("ik_general_6r_2d_10_poses");
    g.sample_size(10);
    let (j10, c10) = (&jaco_set[..10], &crx_set[..10]);
    side_by_side(
        &mut g,
        "jaco",
        "ik_geo_gen_six_dof_2d",
        j10,
        jaco_ik,
        &jaco_2d,
        &tj[..10],
    );
    side_by_side(
        &mut g,
        "crx",
        "ik_geo_gen_six_dof_2d",
        c10,
        crx_ik,
        &crx_2d,
        &tc[..10],
    );
    g.finish();
}

/// Times `{name}_kinegen_ik` (`ours` on every pose of `set`) and `{name}_{contender}`
/// (`geo` on the same poses as ik-geo's targets) in `group`.
fn side_by_side<T>(
    group: &mut criterion::BenchmarkGroup<criterion::measurement::WallTime>,
    name: &str,
    contender: &str,
    set: &[([[f64; 4]; 4], [f64; 6])],
    ours: impl Fn(&[[f64; 4]; 4]) -> T,
    geo: &Robot,
    targets: &[(Matrix3<f64>, Vector3<f64>)],
) {
    group.bench_function(format!("{name}_kinegen_ik"), |b| {
        b.iter(|| {
            for (pose, _) in set {
                black_box(ours(black_box(pose)));
            }
        })
    });
    group.bench_function(format!("{name}_{contender}"), |b| {
        b.iter(|| {
            for (r, t) in targets {
                black_box(geo.ik(black_box(*r), black_box(*t)));
            }
        })
    });
}

criterion_group!(benches, bench, bench_general);
criterion_main!(benches);
