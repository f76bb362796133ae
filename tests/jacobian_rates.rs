//! `kinegen::jacobian_rates`: the second order from the Jacobian's columns at run time.
//! On the shipped robots it equals the closed forms the macro derives; a chain longer
//! than the engine derives in closed form (24 joints, some prismatic) gets methods that
//! call it, checked here against central differences of its own generated Jacobians.

use kinegen::ik::XorShift64;
use kinegen::jacobian_rates::{hessian, jacobian_dot, jacobian_ee_dot, jdot_qdot};
use kinegen::SecondOrderKinematics;
use kinegen_robots::{Panda, Scara, Stanford, Ur5};

fn vector<const N: usize>(rng: &mut XorShift64, lo: f64, hi: f64) -> [f64; N] {
    core::array::from_fn(|_| lo + (hi - lo) * rng.next_f64())
}

fn close(got: f64, want: f64, scale: f64, what: &str) {
    assert!(
        (got - want).abs() <= 1e-12 * scale.max(1.0),
        "{what}: {got} vs {want}"
    );
}

/// The run-time formulas against the generated closed forms, 200 configurations.
fn equals_the_closed_forms<const N: usize, R: SecondOrderKinematics<N>>(robot: &R, seed: u64) {
    let mut rng = XorShift64::new(seed);
    for _ in 0..200 {
        let (q, qd) = (
            vector::<N>(&mut rng, -3.0, 3.0),
            vector::<N>(&mut rng, -2.0, 2.0),
        );
        let (j, ee) = (robot.jacobian(&q), robot.jacobian_ee(&q));
        let scale = j.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        let (h, want) = (hessian(&j), robot.hessian(&q));
        let (jd, jd_want) = (jacobian_dot(&j, &qd), robot.jacobian_dot(&q, &qd));
        let (ed, ed_want) = (jacobian_ee_dot(&ee, &qd), robot.jacobian_ee_dot(&q, &qd));
        let (b, b_want) = (jdot_qdot(&j, &qd), robot.jdot_qdot(&q, &qd));
        let rates = scale * 4.0 * N as f64;
        for r in 0..6 {
            for i in 0..N {
                for k in 0..N {
                    close(
                        h[k][r][i],
                        want[k][r][i],
                        scale,
                        &format!("{} H[{k}][{r}][{i}]", R::NAME),
                    );
                }
                close(
                    jd[r][i],
                    jd_want[r][i],
                    rates,
                    &format!("{} Jdot[{r}][{i}]", R::NAME),
                );
                close(
                    ed[r][i],
                    ed_want[r][i],
                    rates,
                    &format!("{} Jee_dot[{r}][{i}]", R::NAME),
                );
            }
            close(
                b[r],
                b_want[r],
                rates * 4.0 * N as f64,
                &format!("{} Jdot qdot[{r}]", R::NAME),
            );
        }
    }
}

#[test]
fn run_time_formulas_equal_the_closed_forms() {
    equals_the_closed_forms(&Ur5::default(), 1);
    equals_the_closed_forms(&Panda::default(), 2);
    // Prismatic joints: ω_i = 0 in their columns.
    equals_the_closed_forms(&Stanford::default(), 3);
    equals_the_closed_forms(&Scara::default(), 4);
}

kinegen::kinematics! {
    /// 24 joints, one in four prismatic: its Hessian's 3 456 entries are over what the
    /// engine derives in closed form, so its second order is computed at run time.
    // Twists in no special position: its normal-form note (a compiler warning) is expected.
    #[allow(deprecated)]
    struct Long;
    convention: standard,
    joints: [
        revolute { a: 0.05, alpha: 0.3, d: 0.0 },
        revolute { a: 0.12, alpha: -1.1, d: 0.1 },
        revolute { a: 0.08, alpha: 0.7, d: 0.02 },
        prismatic { a: 0.15, alpha: pi/2, theta: 0.3 },
        revolute { a: 0.11, alpha: -0.4, d: 0.04 },
        revolute { a: 0.07, alpha: 1.3, d: 0.14 },
        revolute { a: 0.14, alpha: pi/3, d: 0.06 },
        prismatic { a: 0.1, alpha: -pi/2, theta: 0.2 },
        revolute { a: 0.06, alpha: 0.3, d: 0.08 },
        revolute { a: 0.13, alpha: -1.1, d: 0.0 },
        revolute { a: 0.09, alpha: 0.7, d: 0.1 },
        prismatic { a: 0.05, alpha: pi/2, theta: 0.1 },
        revolute { a: 0.12, alpha: -0.4, d: 0.12 },
        revolute { a: 0.08, alpha: 1.3, d: 0.04 },
        revolute { a: 0.15, alpha: pi/3, d: 0.14 },
        prismatic { a: 0.11, alpha: -pi/2, theta: 0.0 },
        revolute { a: 0.07, alpha: 0.3, d: 0.16 },
        revolute { a: 0.14, alpha: -1.1, d: 0.08 },
        revolute { a: 0.1, alpha: 0.7, d: 0.0 },
        prismatic { a: 0.06, alpha: pi/2, theta: 0.4 },
        revolute { a: 0.13, alpha: -0.4, d: 0.02 },
        revolute { a: 0.09, alpha: 1.3, d: 0.12 },
        revolute { a: 0.05, alpha: pi/3, d: 0.04 },
        prismatic { a: 0.12, alpha: -pi/2, theta: 0.3 },
    ],
}

/// `(f(x + h) − f(x − h)) / 2h` of a 6×24 matrix function along direction `d`.
fn central(
    f: impl Fn(&[f64; 24]) -> [[f64; 24]; 6],
    q: &[f64; 24],
    d: &[f64; 24],
) -> [[f64; 24]; 6] {
    let h = 1e-6;
    let at = |s: f64| f(&core::array::from_fn(|i| q[i] + s * h * d[i]));
    let (p, m) = (at(1.0), at(-1.0));
    core::array::from_fn(|r| core::array::from_fn(|c| (p[r][c] - m[r][c]) / (2.0 * h)))
}

#[test]
fn a_long_chain_gets_its_second_order_at_run_time() {
    let arm = Long;
    let mut rng = XorShift64::new(24);
    for _ in 0..20 {
        let (q, qd) = (
            vector::<24>(&mut rng, -2.0, 2.0),
            vector::<24>(&mut rng, -1.0, 1.0),
        );
        let jac = |q: &[f64; 24]| arm.jacobian(q);
        let h = arm.hessian(&q);
        // Central differences are good to ~1e-8 here (h = 1e-6, reach ~4 m).
        let tol = 1e-6;
        for (k, hk) in h.iter().enumerate() {
            let e: [f64; 24] = core::array::from_fn(|i| if i == k { 1.0 } else { 0.0 });
            let fd = central(jac, &q, &e);
            for r in 0..6 {
                for i in 0..24 {
                    assert!((hk[r][i] - fd[r][i]).abs() < tol, "H[{k}][{r}][{i}]");
                }
            }
        }
        let (jd, fd) = (arm.jacobian_dot(&q, &qd), central(jac, &q, &qd));
        let ed = arm.jacobian_ee_dot(&q, &qd);
        let ed_fd = central(|q| arm.jacobian_ee(q), &q, &qd);
        let b = arm.jdot_qdot(&q, &qd);
        for r in 0..6 {
            let row: f64 = (0..24).map(|i| fd[r][i] * qd[i]).sum();
            assert!((b[r] - row).abs() < tol * 24.0, "Jdot qdot[{r}]");
            for i in 0..24 {
                assert!((jd[r][i] - fd[r][i]).abs() < tol, "Jdot[{r}][{i}]");
                assert!((ed[r][i] - ed_fd[r][i]).abs() < tol, "Jee_dot[{r}][{i}]");
            }
        }
        // The manipulability gradient reads the run-time Hessian too.
        assert!(arm
            .manipulability_gradient(&q)
            .iter()
            .all(|x| x.is_finite()));
    }
}
