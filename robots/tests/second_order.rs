//! The generated second-order methods of every robot of this crate — `hessian`,
//! `jacobian_dot`, `jdot_qdot`, `jacobian_ee_dot`, `det_gradient`,
//! `singular_factor_gradients`, `manipulability_gradient`, `manipulability_task_gradient`
//! — against the numeric reference of kinegen-core (cross products of the DH frames' joint
//! axes, recursive velocity/acceleration propagation, central differences, nalgebra's
//! SVD), at 200 configurations per robot within the joint limits (fixed seed).
//!
//! Tolerances, with `s = max(1, |reference|)`: closed forms against closed forms
//! `1e-10·s`; against central differences (`h = 1e-5`) `1e-6·s` (truncation and rounding
//! both ≈ 2e-11 on these metre-sized arms); the manipulability gradient, an SVD on each
//! side, `1e-9·(m + |∂m/∂q|)` where the condition number is below 10⁴.

// Parameter names follow the DH tables (`L1`, `a2`).
#![allow(non_snake_case)]

use kinegen::ik::XorShift64;
use kinegen::SecondOrderKinematics;
use kinegen_core::numeric::{self, Jacobian, NumericRobot};
use kinegen_robots::*;
use nalgebra::DMatrix;

const CONFIGURATIONS: usize = 200;
const CLOSED: f64 = 1e-10;
const FD: f64 = 1e-6;
const H: f64 = 1e-5;

fn load(file: &str) -> kinegen_core::Robot {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(file);
    kinegen_core::front::toml_file::load_file(&path).unwrap().0
}

fn close(got: f64, want: f64, tol: f64, what: &dyn Fn() -> String) {
    assert!(
        (got - want).abs() <= tol * want.abs().max(1.0),
        "{}: generated {got} vs reference {want}",
        what()
    );
}

fn matrix<const N: usize>(m: &[[f64; N]; 6]) -> Jacobian {
    Jacobian::from_fn(N, |r, c| m[r][c])
}

/// A gradient the generated type has as an inherent method only.
type Gradient<'a, const N: usize> = &'a dyn Fn(&[f64; N]) -> [f64; N];

/// The methods only some robots have, as closures.
struct Extras<'a, const N: usize> {
    det_gradient: Option<Gradient<'a, N>>,
    /// `(task rows, manipulability_task_gradient)`.
    task: Option<(Vec<usize>, Gradient<'a, N>)>,
}

fn check<const N: usize, K: SecondOrderKinematics<N>>(
    robot: &K,
    file: &str,
    extras: &Extras<N>,
    seed: u64,
) {
    let table = load(file);
    let num = NumericRobot::new(&table).unwrap();
    let mut rng = XorShift64::new(seed);
    let limits = robot.limits();
    for _ in 0..CONFIGURATIONS {
        let mut q = [0.0; N];
        let mut qd = [0.0; N];
        for i in 0..N {
            let [lo, hi] = match limits[i] {
                [lo, hi] if lo.is_finite() && hi.is_finite() => [lo, hi],
                _ => [-3.0, 3.0],
            };
            q[i] = lo + (hi - lo) * rng.next_f64();
            qd[i] = 4.0 * rng.next_f64() - 2.0;
        }
        let at = |what: &str| format!("{file} {what} at q = {q:?}, qd = {qd:?}");
        let h = robot.hessian(&q);
        let h_ref = num.hessian(&q).unwrap();
        let mut sum = Jacobian::zeros(N);
        for k in 0..N {
            let hk = matrix(&h[k]);
            sum += &hk * qd[k];
            for r in 0..6 {
                for c in 0..N {
                    close(h[k][r][c], h_ref[k][(r, c)], CLOSED, &|| {
                        at(&format!("H[{k}][{r}][{c}]"))
                    });
                }
            }
        }
        let jd = matrix(&robot.jacobian_dot(&q, &qd));
        let jd_fd = num.jacobian_dot_fd(&q, &qd, H).unwrap();
        let jee_dot = matrix(&robot.jacobian_ee_dot(&q, &qd));
        let jee_fd = num.jacobian_ee_dot_fd(&q, &qd, H).unwrap();
        for r in 0..6 {
            for c in 0..N {
                let rc = || format!("[{r}][{c}]");
                close(jd[(r, c)], sum[(r, c)], CLOSED, &|| {
                    at(&format!("J̇{} vs ΣHq̇", rc()))
                });
                close(jd[(r, c)], jd_fd[(r, c)], FD, &|| {
                    at(&format!("J̇{} vs FD", rc()))
                });
                close(jee_dot[(r, c)], jee_fd[(r, c)], FD, &|| {
                    at(&format!("J̇_ee{}", rc()))
                });
            }
        }
        let a = robot.jdot_qdot(&q, &qd);
        let a_ref = num.jdot_qdot_propagation(&q, &qd).unwrap();
        let jdq = &jd * nalgebra::DVector::from_column_slice(&qd);
        for r in 0..6 {
            close(a[r], a_ref[r], CLOSED, &|| {
                at(&format!("J̇q̇[{r}] vs propagation"))
            });
            close(a[r], jdq[r], CLOSED, &|| at(&format!("J̇q̇[{r}] vs J̇·q̇")));
        }
        check_gradients(robot, &num, extras, &q, &at);
    }
}

fn check_gradients<const N: usize, K: SecondOrderKinematics<N>>(
    robot: &K,
    num: &NumericRobot,
    extras: &Extras<N>,
    q: &[f64; N],
    at: &dyn Fn(&str) -> String,
) {
    // The determinant's gradient against central differences of the reference's det.
    let det_fn = |q: &[f64]| {
        let jt = num.task_jacobian(q).unwrap();
        if jt.nrows() == jt.ncols() {
            numeric::det(&jt).unwrap()
        } else {
            numeric::det6(&num.jacobian(q).unwrap()).unwrap()
        }
    };
    let grad = extras.det_gradient.map(|f| f(q));
    assert_eq!(
        robot.det_gradient(q).is_some(),
        N == 6,
        "{}",
        at("trait det_gradient")
    );
    if let (Some(g), Some(t)) = (grad, robot.det_gradient(q)) {
        assert_eq!(g, t, "{}", at("trait and inherent det_gradient"));
    }
    for (k, gk) in grad.iter().flat_map(|g| g.iter().enumerate()) {
        close(*gk, fd(q, k, &det_fn), FD, &|| {
            at(&format!("∂det/∂q{}", k + 1))
        });
    }
    // Manipulability gradients: the generated (runtime SVD) against nalgebra's.
    let h = robot.hessian(q);
    let j = robot.jacobian(q);
    let mut sets = vec![(
        (0..6).collect::<Vec<usize>>(),
        robot.manipulability_gradient(q),
    )];
    if let Some((rows, f)) = &extras.task {
        sets.push((rows.clone(), f(q)));
    }
    for (rows, got) in sets {
        let pick = |m: &[[f64; N]; 6]| DMatrix::from_fn(rows.len(), N, |r, c| m[rows[r]][c]);
        let jt = pick(&j);
        if jt.nrows() > jt.ncols() {
            // √det(J Jᵀ) is identically 0 with more rows than joints: so is the gradient.
            assert!(got.iter().all(|&g| g == 0.0), "{}: {got:?}", at("∂m/∂q"));
            continue;
        }
        let sv = jt.singular_values();
        if sv.max() > 1e4 * sv.min() {
            continue;
        }
        let hs: Vec<DMatrix<f64>> = h.iter().map(pick).collect();
        let want = numeric::manipulability_gradient(&jt, &hs);
        let m: f64 = sv.iter().product();
        for k in 0..N {
            let scale = m + want[k].abs();
            assert!(
                (got[k] - want[k]).abs() <= 1e-9 * scale,
                "{}: {} vs {}",
                at(&format!("∂m/∂q{} (rows {rows:?})", k + 1)),
                got[k],
                want[k]
            );
        }
    }
}

fn fd<const N: usize>(q: &[f64; N], k: usize, f: &dyn Fn(&[f64]) -> f64) -> f64 {
    let (mut plus, mut minus) = (*q, *q);
    plus[k] += H;
    minus[k] -= H;
    (f(&plus) - f(&minus)) / (2.0 * H)
}

macro_rules! six_axis {
    ($($test:ident: $ty:ident = $file:literal),* $(,)?) => {$(
        #[test]
        fn $test() {
            let r = $ty::default();
            let det = |q: &[f64; 6]| r.det_gradient(q);
            let extras = Extras { det_gradient: Some(&det), task: None };
            check(&r, $file, &extras, 0x5EC0_0D01);
        }
    )*};
}

six_axis! {
    ur3: Ur3 = "ur3.toml",
    ur5: Ur5 = "ur5.toml",
    ur10: Ur10 = "ur10.toml",
    ur5e: Ur5e = "ur5e.toml",
    ur10e: Ur10e = "ur10e.toml",
    puma560: Puma560 = "puma560.toml",
    stanford: Stanford = "stanford.toml",
    kuka_kr6_r900: KukaKr6R900 = "kuka_kr6_r900.toml",
    abb_irb120: AbbIrb120 = "abb_irb120.toml",
    abb_irb140: AbbIrb140 = "abb_irb140.toml",
    // Joint 1 flipped (RTB's `flip=True`), which the reference implements on its own.
    kinova_jaco: KinovaJaco = "kinova_jaco.toml",
}

/// The robots built from a URDF have no DH table for the numeric reference; their
/// Jacobian is checked against a URDF evaluator (`urdf_generated.rs`), and their second
/// order here against that Jacobian: `H[k]` against its central differences along `q_k`,
/// `J̇` against its derivative along `q + t q̇`, `J̇ q̇` against `J̇·q̇` (tolerances as above).
fn check_against_own_jacobian<const N: usize, K: SecondOrderKinematics<N>>(
    robot: &K,
    name: &str,
    seed: u64,
) {
    let mut rng = XorShift64::new(seed);
    let limits = robot.limits();
    let jacobian_at = |q: &[f64; N], dir: &[f64; N], t: f64| {
        let q: [f64; N] = std::array::from_fn(|i| q[i] + t * dir[i]);
        matrix(&robot.jacobian(&q))
    };
    for _ in 0..CONFIGURATIONS {
        let q: [f64; N] = std::array::from_fn(|i| {
            let [lo, hi] = limits[i];
            lo + (hi - lo) * rng.next_f64()
        });
        let qd: [f64; N] = std::array::from_fn(|_| 4.0 * rng.next_f64() - 2.0);
        let at = |what: &str| format!("{name} {what} at q = {q:?}, qd = {qd:?}");
        let h = robot.hessian(&q);
        for (k, hk) in h.iter().enumerate() {
            let e: [f64; N] = std::array::from_fn(|i| f64::from(u8::from(i == k)));
            let fd = (jacobian_at(&q, &e, H) - jacobian_at(&q, &e, -H)) / (2.0 * H);
            for r in 0..6 {
                for c in 0..N {
                    close(hk[r][c], fd[(r, c)], FD, &|| {
                        at(&format!("H[{k}][{r}][{c}]"))
                    });
                }
            }
        }
        let jd = matrix(&robot.jacobian_dot(&q, &qd));
        let fd = (jacobian_at(&q, &qd, H) - jacobian_at(&q, &qd, -H)) / (2.0 * H);
        for r in 0..6 {
            for c in 0..N {
                close(jd[(r, c)], fd[(r, c)], FD, &|| at(&format!("J̇[{r}][{c}]")));
            }
        }
        let a = robot.jdot_qdot(&q, &qd);
        let jdq = &jd * nalgebra::DVector::from_column_slice(&qd);
        for r in 0..6 {
            close(a[r], jdq[r], CLOSED, &|| at(&format!("J̇q̇[{r}]")));
        }
    }
}

#[test]
fn robots_from_urdf() {
    check_against_own_jacobian(&Ur5Urdf::default(), "ur5_urdf.toml", 11);
    check_against_own_jacobian(&PandaUrdf::default(), "panda_urdf.toml", 12);
}

#[test]
fn seven_axis_arms() {
    let none = Extras {
        det_gradient: None,
        task: None,
    };
    check(&Panda::default(), "panda.toml", &none, 7);
    check(&KukaIiwa14::default(), "kuka_iiwa14.toml", &none, 8);
}

#[test]
fn arms_with_task_rows() {
    let rr = PlanarRr::default();
    let (d, m) = (
        |q: &[f64; 2]| rr.det_gradient(q),
        |q: &[f64; 2]| rr.manipulability_task_gradient(q),
    );
    let extras = Extras {
        det_gradient: Some(&d),
        task: Some((vec![0, 1], &m)),
    };
    check(&rr, "planar_rr.toml", &extras, 2);
    let rrr = PlanarRrr::default();
    let (d, m) = (
        |q: &[f64; 3]| rrr.det_gradient(q),
        |q: &[f64; 3]| rrr.manipulability_task_gradient(q),
    );
    let extras = Extras {
        det_gradient: Some(&d),
        task: Some((vec![0, 1, 5], &m)),
    };
    check(&rrr, "planar_rrr.toml", &extras, 3);
    let scara = Scara::default();
    let (d, m) = (
        |q: &[f64; 4]| scara.det_gradient(q),
        |q: &[f64; 4]| scara.manipulability_task_gradient(q),
    );
    let extras = Extras {
        det_gradient: Some(&d),
        task: Some((vec![0, 1, 2, 5], &m)),
    };
    check(&scara, "scara.toml", &extras, 4);
    let none = Extras {
        det_gradient: None,
        task: None,
    };
    check(&CylindricalRpp::default(), "cylindrical_rpp.toml", &none, 5);
}

/// At a singular configuration the gradients are finite; the manipulability's is 0
/// (not differentiable there: the least element of the generalised gradient), the
/// determinant's is not (it points off the singular set).
#[test]
fn gradients_at_singular_configurations() {
    let ur5 = Ur5::default();
    for q in [
        [0.3, -1.0, 0.0, 0.2, 1.0, 0.0], // elbow: sin q3 = 0
        [0.3, -1.0, 1.2, 0.2, 0.0, 0.0], // wrist: sin q5 = 0
    ] {
        assert!(ur5.jacobian_det(&q).abs() < 1e-15);
        let g = ur5.manipulability_gradient(&q);
        assert!(g.iter().all(|x| x.is_finite() && x.abs() < 1e-12), "{g:?}");
        let d = ur5.det_gradient(&q);
        assert!(d.iter().all(|x| x.is_finite()));
        assert!(d.iter().any(|x| x.abs() > 1e-4), "{d:?}");
    }
    let nan = [f64::NAN; 6];
    assert!(ur5.manipulability_gradient(&nan).iter().all(|x| x.is_nan()));
}
