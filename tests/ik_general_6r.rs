//! The general 6R solver (`kinegen::ik::families::general_6r`) on random arms whose axes
//! are in no special position (random twists, lengths and offsets: no two axes parallel
//! or meeting), IKFast's self-test as `ik_closed_form.rs` runs it on the robots, and the
//! number of real solutions checked against an independent method: Newton's method from
//! many seeded starts, its converged points merged.

use core::f64::consts::{FRAC_PI_2, PI, TAU};
use kinegen::ik::families::{general_6r, Hint};
use kinegen::ik::geometry::{rot, Geometry, Pose, M3, V3};
use kinegen::ik::polish::{hadamard_ratio, polish};
use kinegen::ik::solutions::Candidates;
use kinegen::ik::XorShift64;

/// Standard DH rows `[a, α, d, θ offset]` to the zero-configuration geometry.
fn from_dh(rows: &[[f64; 4]; 6]) -> Geometry<6> {
    let (mut r, mut p) = (M3::identity(), V3::zeros());
    let mut h = [V3::z(); 6];
    let mut points = [V3::zeros(); 6];
    for (i, [a, alpha, d, theta]) in rows.iter().enumerate() {
        h[i] = r * V3::z();
        points[i] = p;
        let rz = rot(&V3::z(), *theta);
        p += r * (rz * V3::new(*a, 0.0, 0.0) + V3::new(0.0, 0.0, *d));
        r = r * rz * rot(&V3::x(), *alpha);
    }
    Geometry {
        h,
        p: points,
        prismatic: [false; 6],
        r_tool: r,
        p_tool: p,
    }
}

/// A random arm: link lengths 0.05–0.45 m, offsets within ±0.3 m, twists 0.3–1.3 rad
/// or their supplements (never parallel, never meeting a neighbour), random home angles.
fn random_arm(rng: &mut XorShift64) -> (Geometry<6>, f64) {
    let mut rows = [[0.0; 4]; 6];
    let mut reach = 0.0;
    for row in rows.iter_mut() {
        let a = 0.05 + 0.4 * rng.next_f64();
        let twist = 0.3 + 1.0 * rng.next_f64();
        let alpha = if rng.next_f64() < 0.5 {
            twist
        } else {
            PI - twist
        };
        let d = 0.6 * rng.next_f64() - 0.3;
        *row = [a, alpha, d, TAU * rng.next_f64() - PI];
        reach += a + d.abs();
    }
    (from_dh(&rows), reach)
}

/// A configuration in (−π, π] with 20 % of the joints snapped to −π/2, 0 or π/2.
fn configuration(rng: &mut XorShift64) -> [f64; 6] {
    core::array::from_fn(|_| {
        let q = TAU * rng.next_f64() - PI;
        if rng.next_f64() < 0.2 {
            [-FRAC_PI_2, 0.0, FRAC_PI_2][(rng.next_u64() % 3) as usize]
        } else {
            q
        }
    })
}

/// `max |fk(q) − pose|` over the rotation's and the position's entries.
fn miss(g: &Geometry<6>, q: &[f64; 6], pose: &Pose) -> f64 {
    let at = g.fk(q);
    (at.r - pose.r).amax().max((at.p - pose.p).amax())
}

fn gap(a: &[f64; 6], b: &[f64; 6]) -> f64 {
    (0..6)
        .map(|i| {
            let d = a[i] - b[i];
            (d - TAU * (d / TAU).round()).abs()
        })
        .fold(0.0, f64::max)
}

/// The exact solutions (within 1e-10 of the pose, relative to the arm's reach) the
/// solver returns for `pose`.
fn exact(g: &Geometry<6>, pose: &Pose, reach: f64, hint: &Hint) -> Vec<[f64; 6]> {
    let mut out = Candidates::<6, 16>::default();
    general_6r(g, pose, &[0.0; 6], hint, &mut out);
    out.as_slice()
        .iter()
        .map(|c| c.q)
        .filter(|q| miss(g, q, pose) <= 1e-10 * reach.max(1.0))
        .collect()
}

/// Generating configurations this close to singular (Hadamard's ratio of the Jacobian)
/// count as singular: their solutions merge.
const SINGULAR: f64 = 1e-9;

#[test]
fn random_general_arms_self_test() {
    let mut rng = XorShift64::new(6);
    let (mut cases, mut regular_missed, mut singular_cases, mut solutions) = (0, 0, 0, 0);
    for _ in 0..20 {
        let (g, reach) = random_arm(&mut rng);
        let hint = Hint::new();
        for _ in 0..500 {
            let q = configuration(&mut rng);
            let pose = g.fk(&q);
            let sols = exact(&g, &pose, reach, &hint);
            for (i, a) in sols.iter().enumerate() {
                for b in &sols[i + 1..] {
                    assert!(gap(a, b) > 1e-9, "duplicate solutions for {q:?}");
                }
            }
            cases += 1;
            solutions += sols.len();
            if hadamard_ratio(&g, &q) < SINGULAR {
                singular_cases += 1;
                continue;
            }
            regular_missed += usize::from(!sols.iter().any(|s| gap(s, &q) <= 1e-7));
        }
    }
    eprintln!(
        "random general 6R: {cases} poses ({singular_cases} singular), {solutions} exact solutions, \
         generating configuration missed at {regular_missed} regular poses"
    );
    assert_eq!(regular_missed, 0, "generating configurations missed");
}

/// Newton's method (damped Gauss–Newton on `fk`, `kinegen::ik::polish`) from [`STARTS`] seeded
/// starts per pose, its converged points merged: every solution it finds is among the
/// solver's (no solution dropped), and the counts are equal but where Newton missed one.
#[test]
fn solution_counts_match_many_newton_starts() {
    let mut rng = XorShift64::new(16);
    let (mut poses, mut equal, mut newton_total, mut solver_total) = (0, 0, 0, 0);
    for arm in 0..12 {
        let (g, reach) = random_arm(&mut rng);
        let hint = Hint::new();
        for _ in 0..20 {
            let pose = g.fk(&configuration(&mut rng));
            let sols = exact(&g, &pose, reach, &hint);
            let mut newton: Vec<[f64; 6]> = Vec::new();
            for _ in 0..STARTS {
                let start: [f64; 6] = core::array::from_fn(|_| TAU * rng.next_f64() - PI);
                let q = polish(&g, start, &pose);
                if miss(&g, &q, &pose) <= 1e-10 * reach.max(1.0)
                    && !newton.iter().any(|n| gap(n, &q) <= 1e-6)
                {
                    newton.push(q);
                }
            }
            for n in &newton {
                assert!(
                    sols.iter().any(|s| gap(s, n) <= 1e-6),
                    "arm {arm}: Newton's solution {n:?} is not among the solver's {sols:?}"
                );
            }
            poses += 1;
            equal += usize::from(newton.len() == sols.len());
            newton_total += newton.len();
            solver_total += sols.len();
        }
    }
    eprintln!(
        "{poses} poses: Newton found {newton_total} solutions, the solver {solver_total}; equal counts at {equal}"
    );
    // Where the counts differ the solver has more (every one of them exact, checked on
    // `fk` in `exact`): solutions whose basins 2000 random starts missed. Measured: 2 of 240.
    assert!(
        poses - equal <= 2,
        "Newton from {STARTS} starts and the solver disagree on counts at {} poses",
        poses - equal
    );
}

/// Newton starts per pose.
const STARTS: usize = 2000;

/// The FANUC CRX-10iA/L at poses where several solutions share a value of the eigen
/// joint (q2 = 0 with the wrist at right angles, from `ik_closed_form.rs`'s self-test,
/// where the solver once missed them): whichever formulation the hint starts with, the
/// generating configuration is among the exact solutions, none of them is flagged a
/// double root (the poses are regular), and every start gives the same solutions.
#[test]
fn crx_shared_eigen_joint_values() {
    use kinegen::ik::families::FORMULATIONS;
    use kinegen::ik::subproblems::Fit;
    use kinegen_robots::FanucCrx10iaL;
    let robot = FanucCrx10iaL::default();
    let g = robot.ik_geometry();
    for q in [
        [
            FRAC_PI_2,
            0.0,
            0.0,
            0.678_946_906_232_560_8,
            -2.800_283_048_412_051,
            -2.760_315_372_254_539,
        ],
        [
            -0.527_229_029_656_112,
            0.0,
            0.579_813_191_650_912_6,
            -3.120_396_038_672_816_5,
            -2.976_207_655_169_290_4,
            FRAC_PI_2,
        ],
        [
            3.107_278_794_555_800_7,
            0.0,
            -1.448_846_604_316_554_7,
            -0.821_505_651_765_158,
            -0.147_260_428_000_934_86,
            -2.401_211_812_487_998_6,
        ],
    ] {
        assert!(hadamard_ratio(&g, &q) > SINGULAR, "{q:?} is regular");
        // The generated fk's pose, as the self-test gives it (its rounding matters here).
        let pose = Pose::from_matrix(&robot.fk(&q));
        let mut first: Option<Vec<[f64; 6]>> = None;
        for k in 0..FORMULATIONS.len() {
            let mut out = Candidates::<6, 16>::default();
            general_6r(&g, &pose, &[0.0; 6], &Hint::at(k), &mut out);
            let exact: Vec<_> = out
                .as_slice()
                .iter()
                .filter(|c| miss(&g, &c.q, &pose) <= 1e-10)
                .collect();
            assert!(
                exact.iter().any(|c| gap(&c.q, &q) <= 1e-7),
                "{q:?}, hint {k}: the generating configuration is not among {exact:?}"
            );
            assert!(
                exact.iter().all(|c| c.fit != Fit::Double),
                "{q:?}, hint {k}: a regular solution flagged a double root"
            );
            assert_eq!(
                exact.len() % 2,
                0,
                "{q:?}, hint {k}: an odd number of solutions"
            );
            let qs: Vec<[f64; 6]> = exact.iter().map(|c| c.q).collect();
            match &first {
                None => first = Some(qs),
                Some(f) => assert!(
                    f.len() == qs.len() && f.iter().all(|a| qs.iter().any(|b| gap(a, b) <= 1e-7)),
                    "{q:?}, hint {k}: {qs:?} against hint 0's {f:?}"
                ),
            }
        }
    }
}

/// The CRX-10iA/L's example of the subproblem-polynomial work (Elias and Wen; their
/// `examples_paper/CRX`): the arm in the product-of-exponentials form they define it in
/// (axes z, x, x, y, x, y; 0.71 m along z to joint 3, 0.15 m along x and 0.54 m along y
/// to joint 5, base and flange offsets left out, the tool frame the base frame at q = 0),
/// at R = I, p = (0.25, 0.25, 0.25) m. Their resultant in x4 = tan(q4/2) has degree 48 and
/// factors into degrees 16 and 32; the degree-16 factor has 8 real roots, which they
/// publish, and these are the arm's 8 solutions. The solver must find exactly 8 exact
/// solutions, none flagged singular, whose tan(q4/2) are those roots.
#[test]
fn crx_published_example() {
    use kinegen::ik::subproblems::Fit;
    let (x, y, z) = (V3::x(), V3::y(), V3::z());
    let wrist = V3::new(0.15, 0.54, 0.71);
    let g = Geometry {
        h: [z, x, x, y, x, y],
        p: [V3::zeros(), V3::zeros(), 0.71 * z, 0.71 * z, wrist, wrist],
        prismatic: [false; 6],
        r_tool: M3::identity(),
        p_tool: wrist,
    };
    let pose = Pose {
        r: M3::identity(),
        p: V3::new(0.25, 0.25, 0.25),
    };
    // The 8 real roots of the degree-16 factor, as published (their `crx.m`).
    let published = [
        -3.074_284_874_899_49,
        -1.742_909_025_191_248_5,
        -0.641_072_221_954_236_3,
        -0.216_896_163_521_709_46,
        0.325_278_899_221_300_6,
        0.573_753_411_994_794_5,
        1.559_886_648_888_970_4,
        4.610_501_097_682_664,
    ];
    let mut out = Candidates::<6, 16>::default();
    general_6r(&g, &pose, &[0.0; 6], &Hint::new(), &mut out);
    let exact: Vec<_> = out
        .as_slice()
        .iter()
        .filter(|c| miss(&g, &c.q, &pose) <= 1e-10)
        .collect();
    assert_eq!(exact.len(), 8, "{exact:?}");
    assert!(exact.iter().all(|c| c.fit != Fit::Double), "{exact:?}");
    let mut x4: Vec<f64> = exact.iter().map(|c| (c.q[3] / 2.0).tan()).collect();
    x4.sort_by(f64::total_cmp);
    for (ours, theirs) in x4.iter().zip(published) {
        // Published to 15–17 digits; measured agreement 8e-14.
        assert!(
            (ours - theirs).abs() <= 1e-12 * (1.0 + theirs.abs()),
            "tan(q4/2): {x4:?} against {published:?}"
        );
    }
}

/// The CRX-10iA/L with q2 = 0 and q3 = −π/2: axes 1 and 4 coincide, and the pose's
/// solutions include a continuum (q1 + q4 fixed, each alone free). The solver keeps one
/// point of it, not a crowd of samples that would push the isolated solutions out of the
/// 16 places; `ik_near` stays at the caller's configuration on it.
#[test]
fn crx_self_motion_kept_once() {
    use kinegen_robots::FanucCrx10iaL;
    let robot = FanucCrx10iaL::default();
    let g = robot.ik_geometry();
    for (q1, q4, q5, q6) in [
        (-0.859_756, -0.531_613, -1.769_135, -0.548_257),
        (0.4, 1.1, 0.7, -2.0),
        (2.5, -0.3, -2.2, 1.2),
    ] {
        let q = [q1, 0.0, -FRAC_PI_2, q4, q5, q6];
        let pose = Pose::from_matrix(&robot.fk(&q));
        let sols = robot.ik(&robot.fk(&q));
        let exact: Vec<[f64; 6]> = sols
            .exact()
            .map(|b| b.q)
            .filter(|s| miss(&g, s, &pose) <= 1e-10)
            .collect();
        // On the continuum to rounding: q2 = 0, q3 = −π/2, q1 + q4 that of the generating
        // one. (Where it crosses q4 = 0 or π, another branch of solutions crosses it:
        // Newton's points there stop anywhere from ~1e-12 to ~1e-5 off it and still meet
        // the pose to 1e-15 — a contact of higher order; those are not merged with it,
        // and the points within 1e-3 rad of the crossing are not counted here.)
        let on_it = exact
            .iter()
            .filter(|s| {
                s[3].sin().abs() > 1e-3
                    && s[1].abs() < 1e-9
                    && (s[2] + FRAC_PI_2).abs() < 1e-9
                    && gap(
                        &[s[0] + s[3], 0.0, 0.0, 0.0, 0.0, 0.0],
                        &[q1 + q4, 0.0, 0.0, 0.0, 0.0, 0.0],
                    ) < 1e-6
            })
            .count();
        assert_eq!(on_it, 1, "{q:?}: {exact:?}");
        let near = robot.ik_near(&robot.fk(&q), &q).expect("reached");
        assert!(gap(&near, &q) <= 1e-9, "{q:?}: ik_near moved to {near:?}");
    }
}

/// The Kinova Gen3 with joint 7 locked, at the two poses of `ik_closed_form.rs`'s
/// self-test with q2 = 0 and q4 = q5 = π/2: every formulation of the elimination
/// degenerates there, and the solutions come from poses moved off it, tracked back. Of
/// their twelve solutions the solver once returned five and four, the generating one
/// missing (close pairs, |det J| ~1e-6, on which Gauss–Newton's tracking stalled).
/// Every solution Newton finds from [`STARTS`] starts is among the solver's, and the
/// generating configuration is.
#[test]
fn gen3_degenerate_poses_keep_every_solution() {
    use kinegen_robots::KinovaGen3;
    let g7 = KinovaGen3.ik_geometry();
    let mut rng = XorShift64::new(33);
    for q in [
        [
            2.1469569132712953,
            0.0,
            3.1241695260137483,
            FRAC_PI_2,
            FRAC_PI_2,
            0.5154782318919469,
            FRAC_PI_2,
        ],
        [
            -2.4653128038613956,
            0.0,
            0.08475138804902116,
            FRAC_PI_2,
            FRAC_PI_2,
            0.12335675709875416,
            -0.6025862110893505,
        ],
    ] {
        let g: Geometry<6> = g7.lock(6, q[6]);
        let q6: [f64; 6] = core::array::from_fn(|i| q[i]);
        let pose = g.fk(&q6);
        let sols = exact(&g, &pose, 1.0, &Hint::new());
        assert!(
            sols.iter().any(|s| gap(s, &q6) <= 1e-7),
            "{q:?}: generating configuration missed: {sols:?}"
        );
        let mut newton: Vec<[f64; 6]> = Vec::new();
        for _ in 0..STARTS {
            let start: [f64; 6] = core::array::from_fn(|_| TAU * rng.next_f64() - PI);
            let s = polish(&g, start, &pose);
            if miss(&g, &s, &pose) <= 1e-10 && !newton.iter().any(|n| gap(n, &s) <= 1e-6) {
                newton.push(s);
            }
        }
        eprintln!(
            "Gen3 at {q:?}: Newton {} solutions, the solver {}",
            newton.len(),
            sols.len()
        );
        for n in &newton {
            assert!(
                sols.iter().any(|s| gap(s, n) <= 1e-6),
                "{q:?}: Newton's solution {n:?} is not among the solver's {sols:?}"
            );
        }
    }
}

/// A pose's solutions are a function of the pose: the same bits whether the hint kept for
/// the arm has solved other poses before (in either order) or none. Special poses (joints
/// snapped to right angles, 40 % of them) are where the formulation is chosen pose by pose:
/// a hint that followed the last such pose's formulation gave the next pose's solutions
/// another formulation's rounding, or at a degenerate pose other solutions. The hint is
/// handed three arms in turn.
#[test]
fn solutions_do_not_depend_on_the_poses_before() {
    use kinegen::ik::subproblems::Fit;
    use kinegen_robots::{FanucCrx10iaL, KinovaJaco};
    type Solved = Vec<([f64; 6], Fit)>;
    let solve = |g: &Geometry<6>, pose: &Pose, hint: &Hint| -> Solved {
        let mut out = Candidates::<6, 16>::default();
        general_6r(g, pose, &[0.0; 6], hint, &mut out);
        out.as_slice().iter().map(|c| (c.q, c.fit)).collect()
    };
    let mut rng = XorShift64::new(30);
    // The Jaco and the CRX share their regular formulations (two of twelve); a random arm
    // has all twelve, and starts with another.
    let arms = [
        KinovaJaco::default().ik_geometry(),
        FanucCrx10iaL::default().ik_geometry(),
        random_arm(&mut rng).0,
    ];
    // One hint for all three, as a middle joint locked at another value hands it other
    // axes: each arm's formulations are read again.
    let kept = Hint::new();
    for g in arms {
        let poses: Vec<Pose> = (0..60)
            .map(|_| {
                let q: [f64; 6] = core::array::from_fn(|_| {
                    if rng.next_f64() < 0.4 {
                        [-FRAC_PI_2, 0.0, FRAC_PI_2][(rng.next_u64() % 3) as usize]
                    } else {
                        TAU * rng.next_f64() - PI
                    }
                });
                g.fk(&q)
            })
            .collect();
        let first: Vec<Solved> = poses.iter().map(|p| solve(&g, p, &kept)).collect();
        for (pose, solved) in poses.iter().zip(&first) {
            assert_eq!(&solve(&g, pose, &Hint::new()), solved, "{pose:?}");
        }
        for (pose, solved) in poses.iter().zip(&first).rev() {
            assert_eq!(&solve(&g, pose, &kept), solved, "{pose:?}, reversed");
        }
    }
}
