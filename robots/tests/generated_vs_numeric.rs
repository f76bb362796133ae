//! Every generated robot against the numeric reference of kinegen-core (DH matrix
//! products, `z × (p − o)` columns, LU determinant) at random configurations.

use kinegen::{Kinematics, TaskKinematics};
use kinegen_core::numeric::{self, NumericRobot};
use kinegen_robots::*;
use proptest::prelude::*;
#[path = "../../kinegen-core/tests/common/fixed_seed.rs"]
mod fixed_seed;
use fixed_seed::fixed_seed;

fn load(file: &str) -> kinegen_core::Robot {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(file);
    kinegen_core::front::toml_file::load_file(&path).unwrap().0
}

fn close(a: f64, b: f64, what: &str) {
    assert!(
        (a - b).abs() <= 1e-9 * (1.0 + b.abs()),
        "{what}: generated {a} vs reference {b}"
    );
}

fn check<const N: usize, K: Kinematics<N>>(robot: &K, file: &str, q: [f64; N]) {
    let model = load(file);
    let num = NumericRobot::new(&model).unwrap();
    let t = robot.fk(&q);
    let tr = num.fk(&q).unwrap();
    for r in 0..4 {
        for c in 0..4 {
            close(t[r][c], tr[(r, c)], &format!("{file} fk[{r}][{c}]"));
        }
    }
    let frames = robot.frames(&q);
    let fr = num.frames(&q).unwrap();
    for i in 0..N {
        for r in 0..4 {
            for c in 0..4 {
                close(
                    frames[i][r][c],
                    fr[i][(r, c)],
                    &format!("{file} frames[{i}]"),
                );
            }
        }
    }
    let (j, jee) = (robot.jacobian(&q), robot.jacobian_ee(&q));
    let (jr, jeer) = (num.jacobian(&q).unwrap(), num.jacobian_ee(&q).unwrap());
    let (t2, j2) = robot.fk_and_jacobian(&q);
    assert_eq!(t2, t, "{file}: fk_and_jacobian pose");
    assert_eq!(j2, j, "{file}: fk_and_jacobian jacobian");
    for r in 0..6 {
        for c in 0..N {
            close(j[r][c], jr[(r, c)], &format!("{file} J[{r}][{c}]"));
            close(jee[r][c], jeer[(r, c)], &format!("{file} Jee[{r}][{c}]"));
        }
    }
    if N == 6 {
        let d = robot
            .jacobian_det(&q)
            .expect("6-joint robots have jacobian_det");
        let dr = numeric::det6(&jr).unwrap();
        // det J moves by a cofactor (≤ the product of the other columns' norms, Hadamard)
        // per unit change of an entry; entries err by a few ε times their column's norm:
        // so 64ε times the product of the column norms bounds both computations' rounding.
        let hadamard: f64 = (0..N).map(|c| jr.column(c).norm().max(1.0)).product();
        let tol = 64.0 * f64::EPSILON * hadamard;
        assert!(
            (d - dr).abs() <= tol,
            "{file} det: generated {d} vs reference {dr}"
        );
    }
}

fn check_task<const N: usize, const M: usize, K: TaskKinematics<N, M>>(
    robot: &K,
    file: &str,
    q: [f64; N],
) {
    let model = load(file);
    let jt = robot.task_jacobian(&q);
    let jr = numeric::task_jacobian(&model, &q).unwrap();
    for r in 0..M {
        for c in 0..N {
            close(jt[r][c], jr[(r, c)], &format!("{file} Jt[{r}][{c}]"));
        }
    }
    if M == N {
        let d = robot
            .task_jacobian_det(&q)
            .expect("square task Jacobian has a det");
        let dr = numeric::det(&jr).unwrap();
        close(d, dr, &format!("{file} det task"));
    }
}

/// The 6-joint arms (and the Stanford arm, its prismatic joint mapped to metres).
fn six_axis_arms_at(q: [f64; 6]) {
    check(&Ur3::default(), "ur3.toml", q);
    check(&Ur5::default(), "ur5.toml", q);
    check(&Ur10::default(), "ur10.toml", q);
    check(&Ur5e::default(), "ur5e.toml", q);
    check(&Ur10e::default(), "ur10e.toml", q);
    check(&Puma560::default(), "puma560.toml", q);
    check(&KukaKr6R900::default(), "kuka_kr6_r900.toml", q);
    check(&AbbIrb120::default(), "abb_irb120.toml", q);
    check(&AbbIrb140::default(), "abb_irb140.toml", q);
    check(&KinovaJaco::default(), "kinova_jaco.toml", q);
    let mut qs = q;
    qs[2] = 0.2 + q[2].abs() / 4.0; // prismatic: metres
    check(&Stanford::default(), "stanford.toml", qs);
}

/// The 7-joint arms, and the planar, SCARA and cylindrical arms on the first joints.
fn redundant_and_reduced_arms_at(q: [f64; 7]) {
    check(&Panda::default(), "panda.toml", q);
    check(&KukaIiwa14::default(), "kuka_iiwa14.toml", q);
    let rr = [q[0], q[1]];
    check(&PlanarRr::default(), "planar_rr.toml", rr);
    check_task(&PlanarRr::default(), "planar_rr.toml", rr);
    let rrr = [q[0], q[1], q[2]];
    check(&PlanarRrr::default(), "planar_rrr.toml", rrr);
    check_task(&PlanarRrr::default(), "planar_rrr.toml", rrr);
    let scara = [q[0], q[1], q[2].abs() / 10.0, q[3]];
    check(&Scara::default(), "scara.toml", scara);
    check_task(&Scara::default(), "scara.toml", scara);
    let rpp = [q[0], 0.1 + q[1].abs() / 10.0, 0.1 + q[2].abs() / 10.0];
    check(&CylindricalRpp::default(), "cylindrical_rpp.toml", rpp);
}

proptest! {
    #![proptest_config(fixed_seed(200))]
    #[test]
    fn six_axis_arms(q in prop::array::uniform6(-3.2f64..3.2)) {
        six_axis_arms_at(q);
    }

    #[test]
    fn redundant_and_reduced_arms(q in prop::array::uniform7(-3.0f64..3.0)) {
        redundant_and_reduced_arms_at(q);
    }
}

/// Cases proptest once found (formerly `generated_vs_numeric.proptest-regressions`).
#[test]
fn former_regressions() {
    six_axis_arms_at([0.0, 0.0, -2.894642166470365, 0.0, 0.0, 0.0]);
    redundant_and_reduced_arms_at([
        0.0,
        0.0,
        -2.667993754914764,
        2.3736794458731234,
        1.0298831098982448,
        0.0,
        0.0,
    ]);
}

#[test]
fn textbook_determinants() {
    assert_eq!(PlanarRr::DET, "L1*L2*sin(q2)");
    assert_eq!(
        Ur5::DET,
        "a2*a3*sin(q3)*sin(q5)*(a2*cos(q2) + a3*cos(q2+q3) + d5*sin(q2+q3+q4))"
    );
    assert_eq!(
        Puma560::DET,
        "a2*sin(q5)*(a3*sin(q3) + d4*cos(q3))*(a2*cos(q2) + a3*cos(q2+q3) - d4*sin(q2+q3))"
    );
    assert_eq!(Scara::DET, "a1*a2*sin(q2)");
    let labels: Vec<&str> = Ur5::SINGULARITIES.iter().map(|s| s.condition).collect();
    assert_eq!(
        labels,
        [
            "a2 = 0",
            "a3 = 0",
            "sin(q3) = 0",
            "sin(q5) = 0",
            "a2*cos(q2) + a3*cos(q2+q3) + d5*sin(q2+q3+q4) = 0"
        ]
    );
}

#[test]
fn singular_factors_vanish_at_the_singularities() {
    let ur5 = Ur5::default();
    // Elbow (q3 = 0), wrist (q5 = 0), and the shoulder: q1 free, q2 chosen so that
    // a2 c2 + a3 c23 + d5 s234 = 0 with q3 = 0.3, q4 = 0.
    for q in [
        [0.3, -1.0, 0.0, 0.2, 1.0, 0.0],
        [0.3, -1.0, 1.2, 0.2, 0.0, 0.0],
    ] {
        assert!(ur5.jacobian_det(&q).abs() < 1e-15);
    }
    let (a2, a3, d5) = (ur5.a2, ur5.a3, ur5.d5);
    let f = |q2: f64| a2 * q2.cos() + a3 * (q2 + 0.3).cos() + d5 * (q2 + 0.3).sin();
    // Bisection for the shoulder root.
    let (mut lo, mut hi) = (0.0, 3.0);
    assert!(f(lo) * f(hi) < 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(lo) * f(mid) <= 0.0 {
            hi = mid
        } else {
            lo = mid
        }
    }
    let q = [0.7, lo, 0.3, 0.0, 1.0, 0.4];
    let sf = ur5.singular_factors(&q);
    assert!(sf[4].abs() < 1e-12, "shoulder factor {}", sf[4]);
    let num = numeric::det6(&numeric::jacobian(&load("ur5.toml"), &q).unwrap()).unwrap();
    assert!(num.abs() < 1e-12);
}
