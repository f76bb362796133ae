//! The regular-pose solvers in lanes (`kinegen::ik::regular`) against the branch-by-branch
//! solvers of their families, which `ik` falls back to: on the robots of `robots/` in the
//! three families (the UR, the PUMA, and h1 ∩ h2: the iiwa with joint 3 locked and the
//! Panda with joint 7 locked, read from the tool) and on random variations of the UR5, the
//! PUMA 560 and the Panda (link lengths of either sign, base and tool frames), with random
//! configurations (fixed seeds), 20 % of
//! the joints snapped to −π/2, 0 or π/2 (singular poses, which the lanes must hand back),
//! and every fifth pose moved 0.3 m (branches out of reach: least-squares lanes).
//!
//! Wherever the lanes solve a pose they must give the same candidates, in the same order,
//! with the same fits, and joint values equal to rounding — except the least-squares
//! branches they leave out, which must miss a pose another branch reaches by more than
//! `NEAR_MISS` (measured here with the geometry's forward kinematics), so that `finish`
//! would leave them out too; and they must solve the regular poses — a fallback that
//! always ran would pass the comparison unseen. For a caller keeping only reaching
//! solutions (a reachability map) the lanes may leave out such branches at poses no
//! branch reaches too: the same candidates otherwise, bit for bit.

use core::f64::consts::{FRAC_PI_2, PI};
use kinegen::ik::families::{self, WristPair};
use kinegen::ik::geometry::{rot, Geometry, Pose, V3};
use kinegen::ik::regular;
use kinegen::ik::solutions::{pose_matrix, residual, Candidates, NEAR_MISS};
use kinegen::ik::subproblems::{wrap, Fit};
use kinegen::ik::XorShift64;
use kinegen_robots::*;

/// Poses per geometry.
const POSES: usize = 1_000;

/// The lanes and the branch-by-branch solve compute the same subproblems with the same
/// formulas, grouped differently: their joint values differ by rounding, amplified by the
/// conditioning of the pose. At every candidate of this file where the Jacobian's
/// smallest singular value is at least [`WELL_CONDITIONED`], the difference measured was
/// below 1e-13.
const SAME: f64 = 1e-12;

/// Below this smallest singular value (of the 6×6 Jacobian, by central differences) a
/// candidate is near a singular configuration: rounding errors of 1e-16 grow by up to
/// `1 / σ²` at a double root, and the subproblems' relative tests (SP1's lengths agree to
/// 1e-9) can go either way between the two solves. There the joints must still agree to
/// [`NEAR_SINGULAR_SAME`] (the largest difference measured was 2.1e-11 here, and 2.9e-9
/// at σ = 1e-11 with twice these poses),
/// and a fit may differ between exact and least squares (which `finish` then settles by
/// the forward kinematics).
const WELL_CONDITIONED: f64 = 1e-2;

/// See [`WELL_CONDITIONED`].
const NEAR_SINGULAR_SAME: f64 = 1e-6;

/// The smallest singular value of the geometry's 6×6 Jacobian at `q` (central
/// differences of the pose: position, and the rotation's change as an axis).
fn sigma_min(g: &Geometry<6>, q: &[f64; 6]) -> f64 {
    let step = 1e-6;
    let mut j = nalgebra::Matrix6::<f64>::zeros();
    for c in 0..6 {
        let (mut qp, mut qm) = (*q, *q);
        qp[c] += step;
        qm[c] -= step;
        let (a, b) = (g.fk(&qp), g.fk(&qm));
        let dp = (a.p - b.p) / (2.0 * step);
        // The angular velocity: the skew part of dR Rᵀ.
        let w = (a.r - b.r) / (2.0 * step) * g.fk(q).r.transpose();
        let dw = V3::new(
            w[(2, 1)] - w[(1, 2)],
            w[(0, 2)] - w[(2, 0)],
            w[(1, 0)] - w[(0, 1)],
        ) * 0.5;
        for r in 0..3 {
            j[(r, c)] = dp[r];
            j[(r + 3, c)] = dw[r];
        }
    }
    j.singular_values().min()
}

type Lanes = fn(&Geometry<6>, &Pose, &mut Candidates<6, 8>) -> Option<()>;
type ByBranch = fn(&Geometry<6>, &Pose, &[f64; 6], WristPair, &mut Candidates<6, 8>);

fn configuration(rng: &mut XorShift64) -> [f64; 6] {
    core::array::from_fn(|_| {
        if rng.next_f64() < 0.2 {
            [-FRAC_PI_2, 0.0, FRAC_PI_2][(rng.next_u64() % 3) as usize]
        } else {
            PI * (2.0 * rng.next_f64() - 1.0)
        }
    })
}

fn unit(rng: &mut XorShift64) -> V3 {
    V3::new(
        rng.next_f64() - 0.5,
        rng.next_f64() - 0.5,
        rng.next_f64() - 0.5,
    )
    .normalize()
}

/// The geometry in another base frame, with another tool.
fn moved(g: &Geometry<6>, rng: &mut XorShift64) -> Geometry<6> {
    let r = rot(&unit(rng), PI * rng.next_f64());
    let t = unit(rng) * 0.3;
    let tool = rot(&unit(rng), PI * rng.next_f64());
    Geometry {
        h: g.h.map(|h| r * h),
        p: g.p.map(|p| r * p + t),
        prismatic: g.prismatic,
        r_tool: r * g.r_tool * tool,
        p_tool: r * g.p_tool + t + r * g.r_tool * unit(rng) * 0.1,
    }
}

/// Compares the lanes with the branch-by-branch solve on `POSES` poses of `g`; panics
/// where they disagree, and where the lanes leave too many regular poses to the fallback.
/// Also solves each pose for a caller keeping only reaching solutions
/// ([`Candidates::reaching_only`]), which must give the same candidates bit for bit but
/// for least-squares branches that miss the pose by more than `NEAR_MISS` — so that
/// `finish` could not have called them exact. Returns how many branches the lanes left
/// out, and how many more they left out for such a caller at poses no branch reaches.
fn compare(
    name: &str,
    g: &Geometry<6>,
    (lanes, by_branch): (Lanes, ByBranch),
    seed: u64,
) -> (usize, usize) {
    let mut rng = XorShift64::new(seed);
    let (mut solved, mut candidates, mut near_singular, mut left_out) = (0, 0, 0, 0);
    let mut left_out_unreached = 0;
    for n in 0..POSES {
        let mut pose = g.fk(&configuration(&mut rng));
        if n % 5 == 4 {
            pose.p += unit(&mut rng) * 0.3;
        }
        let mut fast = Candidates::default();
        if lanes(g, &pose, &mut fast).is_none() {
            assert!(
                fast.as_slice().is_empty(),
                "{name}, pose {n}: not regular, but {fast:?}"
            );
            continue;
        }
        solved += 1;
        let mut slow = Candidates::default();
        by_branch(g, &pose, &[0.0; 6], WristPair::HalfTurn, &mut slow);
        let (fast, slow) = (fast.as_slice(), slow.as_slice());
        let reached = slow.iter().any(|b| b.fit == Fit::Exact);
        let mut only = Candidates::reaching_only();
        assert!(
            lanes(g, &pose, &mut only).is_some(),
            "{name}, pose {n}: regular, but not for a caller keeping reaching solutions only"
        );
        let mut kept = only.as_slice().iter().peekable();
        for a in fast {
            if kept.next_if(|b| b.q == a.q && b.fit == a.fit).is_some() {
                continue;
            }
            let e = residual(&pose_matrix(&g.fk(&a.q)), &pose);
            assert!(
                a.fit == Fit::LeastSquares && e > NEAR_MISS,
                "{name}, pose {n}: {a:?} (residual {e:e}) left out of {only:?}"
            );
            if !reached {
                left_out_unreached += 1;
            }
        }
        assert!(
            kept.next().is_none(),
            "{name}, pose {n}: reaching only {only:?}, all {fast:?}"
        );
        let mut next = fast.iter().peekable();
        for b in slow {
            let gap = |a: &kinegen::ik::solutions::Candidate<6>| {
                (0..6)
                    .map(|i| wrap(a.q[i] - b.q[i]).abs())
                    .fold(0.0, f64::max)
            };
            let Some(a) = next.next_if(|a| gap(a) <= NEAR_SINGULAR_SAME) else {
                // Left out by the lanes: a branch that misses a pose another reaches.
                // `finish`'s residual, on the geometry's own forward kinematics.
                let e = residual(&pose_matrix(&g.fk(&b.q)), &pose);
                assert!(
                    reached && b.fit == Fit::LeastSquares && e > NEAR_MISS,
                    "{name}, pose {n}: {b:?} (residual {e:e}) left out of {fast:?}"
                );
                left_out += 1;
                continue;
            };
            candidates += 1;
            let gap = gap(a);
            if gap <= SAME && a.fit == b.fit {
                continue;
            }
            // Only near a singular configuration may they differ more.
            let sigma = sigma_min(g, &b.q);
            assert!(
                sigma < WELL_CONDITIONED && gap <= NEAR_SINGULAR_SAME,
                "{name}, pose {n}: {gap:e} (σ_min {sigma:e})\n{a:?}\n{b:?}"
            );
            near_singular += 1;
        }
        assert!(
            next.next().is_none(),
            "{name}, pose {n}: lanes {fast:?}, branch by branch {slow:?}"
        );
    }
    println!(
        "{name}: the lanes solved {solved} of {POSES} poses, left out {left_out} branches \
         that miss a pose another reaches; {near_singular} of {candidates} candidates near a \
         singular configuration differ by more than {SAME:e}"
    );
    // Snapped joints make about a quarter of the poses singular (handed back to the
    // branch-by-branch solve); the rest are regular and must take the lanes.
    assert!(
        solved * 10 >= POSES * 6,
        "{name}: the lanes solved {solved} of {POSES}"
    );
    // Near a singular configuration only by chance: a small share.
    assert!(
        near_singular * 20 <= candidates,
        "{name}: {near_singular} of {candidates}"
    );
    (left_out, left_out_unreached)
}

/// The robots of `robots/` in one family, each with its own seed. Each family has robots
/// with poses some branches reach and others do not (a UR's elbow target depends on the
/// wrist's branch; the KR 6 and the IRB 140 have a shoulder offset — not the PUMA 560,
/// whose offset d3 runs along the parallel axes, nor the IRB 120; the Panda's shoulder,
/// read from the tool, misses where its SP2's circles do — not the iiwa's): the lanes must
/// leave out some branches, and for a caller keeping reaching solutions only, some more
/// at poses out of reach.
fn robots(robots: &[(&str, Geometry<6>)], solvers: (Lanes, ByBranch), seed: u64) {
    let (mut left_out, mut left_out_unreached) = (0, 0);
    for (k, (name, g)) in robots.iter().enumerate() {
        let (a, b) = compare(name, g, solvers, seed + k as u64);
        left_out += a;
        left_out_unreached += b;
    }
    println!("{left_out} branches left out; {left_out_unreached} more when reaching only");
    assert!(left_out > 0, "no branch left out");
    assert!(left_out_unreached > 0, "none left out for reaching only");
}

#[test]
fn universal_robots() {
    let family = [
        ("UR3", Ur3::default().ik_geometry()),
        ("UR5", Ur5::default().ik_geometry()),
        ("UR10", Ur10::default().ik_geometry()),
        ("UR5e", Ur5e::default().ik_geometry()),
        ("UR10e", Ur10e::default().ik_geometry()),
    ];
    robots(&family, three_parallel_two_intersecting(), 100);
}

#[test]
fn spherical_wrist_robots() {
    let family = [
        ("PUMA 560", Puma560::default().ik_geometry()),
        ("KR 6 R900", KukaKr6R900::default().ik_geometry()),
        ("IRB 120", AbbIrb120::default().ik_geometry()),
        ("IRB 140", AbbIrb140::default().ik_geometry()),
    ];
    robots(&family, spherical_two_parallel(), 200);
}

fn length(rng: &mut XorShift64) -> f64 {
    let x = 0.05 + 0.5 * rng.next_f64();
    if rng.next_f64() < 0.5 {
        -x
    } else {
        x
    }
}

/// Twenty random tables of a family: `table` makes the robot's geometry from random link
/// lengths, then it gets random base and tool frames.
fn random_tables(
    family: &str,
    solvers: (Lanes, ByBranch),
    seed: u64,
    table: impl Fn(&mut XorShift64) -> Geometry<6>,
) {
    let mut rng = XorShift64::new(seed);
    for k in 0..20 {
        let g = moved(&table(&mut rng), &mut rng);
        compare(&format!("{family} table {k}"), &g, solvers, 100 * seed + k);
    }
}

#[test]
fn random_universal_robots() {
    random_tables("UR-like", three_parallel_two_intersecting(), 7, |rng| {
        let mut l = || length(rng);
        let (d1, a2, a3, d4, d5, d6) = (l(), l(), l(), l(), l(), l());
        Ur5 {
            d1,
            a2,
            a3,
            d4,
            d5,
            d6,
        }
        .ik_geometry()
    });
}

#[test]
fn random_spherical_wrist_robots() {
    random_tables("PUMA-like", spherical_two_parallel(), 8, |rng| {
        let mut l = || length(rng);
        let (a2, a3, d3, d4) = (l(), l(), l(), l());
        Puma560 { a2, a3, d3, d4 }.ik_geometry()
    });
}

/// The Franka Panda (joint 7 locked, read from the tool) and the KUKA iiwa 14 (joint 3
/// locked), each at three values of its locked joint.
#[test]
fn spherical_shoulder_robots() {
    let (panda, iiwa) = (
        Panda::default().ik_geometry(),
        KukaIiwa14::default().ik_geometry(),
    );
    let family = [
        ("Panda, q7 = -1.3", panda.lock::<6>(6, -1.3).reversed()),
        ("Panda, q7 = 0.4", panda.lock::<6>(6, 0.4).reversed()),
        ("Panda, q7 = 2.2", panda.lock::<6>(6, 2.2).reversed()),
        ("iiwa, q3 = -1.3", iiwa.lock::<6>(2, -1.3)),
        ("iiwa, q3 = 0.4", iiwa.lock::<6>(2, 0.4)),
        ("iiwa, q3 = 2.2", iiwa.lock::<6>(2, 2.2)),
    ];
    robots(&family, spherical_two_intersecting(), 300);
}

#[test]
fn random_spherical_shoulder_robots() {
    random_tables("Panda-like", spherical_two_intersecting(), 9, |rng| {
        let panda = {
            let mut l = || length(rng);
            let (d1, d3, a4, a5, d5, a7, d_flange) = (l(), l(), l(), l(), l(), l(), l());
            Panda {
                d1,
                d3,
                a4,
                a5,
                d5,
                a7,
                d_flange,
            }
        };
        let q7 = 6.0 * rng.next_f64() - 3.0;
        panda.ik_geometry().lock::<6>(6, q7).reversed()
    });
}

fn three_parallel_two_intersecting() -> (Lanes, ByBranch) {
    (
        regular::three_parallel_two_intersecting,
        families::three_parallel_two_intersecting_by_branch,
    )
}

fn spherical_two_intersecting() -> (Lanes, ByBranch) {
    (
        regular::spherical_two_intersecting,
        families::spherical_two_intersecting_by_branch,
    )
}

fn spherical_two_parallel() -> (Lanes, ByBranch) {
    (
        regular::spherical_two_parallel,
        families::spherical_two_parallel_by_branch,
    )
}

/// The generated `ik` goes through the lanes: a pose of each family, solved by the
/// lanes, gives the generated solutions (after `finish`) of the lanes' candidates.
#[test]
fn generated_ik_takes_the_lanes() {
    let robot = Ur5::default();
    let q = [0.3, -1.1, 1.4, -0.6, 0.9, 2.0];
    let pose = robot.fk(&q);
    let mut lanes = Candidates::default();
    let target = Pose::from_matrix(&pose);
    regular::three_parallel_two_intersecting(&robot.ik_geometry(), &target, &mut lanes)
        .expect("a regular pose");
    let solutions = robot.ik(&pose);
    assert_eq!(solutions.len(), lanes.as_slice().len());
    for (s, c) in solutions.iter().zip(lanes.as_slice()) {
        assert_eq!(s.q, c.q);
    }
}
