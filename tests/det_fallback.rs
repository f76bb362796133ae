//! Over budget, `jacobian_det` is a numeric LU determinant on a stack array (issue 3):
//! it still equals the determinant of the Jacobian, and stays finite at singularities.
//!
//! Two arms take the fallback: a general 6R arm with every length and twist a named
//! parameter (non-special twists) and a tiny `nodes` budget, and the UR5 table with
//! `nodes: 1`, whose singular configurations are known (and whose closed form,
//! `kinegen_robots::Ur5`, is the reference there).

use std::any::{Any, TypeId};

mod common;

use common::configurations;
use kinegen::Kinematics;
use kinegen_core::numeric::{self, NumericRobot};

kinegen::kinematics! {
    /// A general 6R arm, fully symbolic: the closed-form determinant is out of budget.
    // Over budget on purpose: its notes (compiler warnings) are expected.
    #[allow(deprecated)]
    pub struct General6r;
    name: "general 6R",
    convention: standard,
    params: {
        a1: 0.1, d1: 0.06, al1: 0.5,
        a2: 0.2, d2: 0.11, al2: 0.7,
        a3: 0.3, d3: 0.16, al3: 0.9,
        a4: 0.4, d4: 0.21, al4: 1.1,
        a5: 0.5, d5: 0.26, al5: 1.3,
        a6: 0.6, d6: 0.31, al6: 1.5,
    },
    joints: [
        revolute { a: a1, alpha: al1, d: d1 },
        revolute { a: a2, alpha: al2, d: d2 },
        revolute { a: a3, alpha: al3, d: d3 },
        revolute { a: a4, alpha: al4, d: d4 },
        revolute { a: a5, alpha: al5, d: d5 },
        revolute { a: a6, alpha: al6, d: d6 },
    ],
    budget: { nodes: 50 },
}

/// The same table for the numeric reference.
const GENERAL_6R_TOML: &str = r#"
name = "general 6R"
convention = "standard"
[params]
a1 = 0.1
d1 = 0.06
al1 = 0.5
a2 = 0.2
d2 = 0.11
al2 = 0.7
a3 = 0.3
d3 = 0.16
al3 = 0.9
a4 = 0.4
d4 = 0.21
al4 = 1.1
a5 = 0.5
d5 = 0.26
al5 = 1.3
a6 = 0.6
d6 = 0.31
al6 = 1.5
[[joints]]
type = "revolute"
a = "a1"
alpha = "al1"
d = "d1"
[[joints]]
type = "revolute"
a = "a2"
alpha = "al2"
d = "d2"
[[joints]]
type = "revolute"
a = "a3"
alpha = "al3"
d = "d3"
[[joints]]
type = "revolute"
a = "a4"
alpha = "al4"
d = "d4"
[[joints]]
type = "revolute"
a = "a5"
alpha = "al5"
d = "d5"
[[joints]]
type = "revolute"
a = "a6"
alpha = "al6"
d = "d6"
"#;

kinegen::kinematics! {
    /// UR5 with a budget too small for any closed form.
    #[allow(deprecated)]
    pub struct Ur5Lu = "robots/ur5.toml";
    budget: { nodes: 1 },
}

/// What `x.singular_factors(q)` resolves to when the type has no inherent
/// `singular_factors` (inherent methods win over trait methods): the closed form, which
/// alone has factors, was not emitted.
struct NoFactors;

trait SingularFactorsFallback {
    fn singular_factors(&self, _q: &[f64; 6]) -> NoFactors {
        NoFactors
    }
}

impl<T> SingularFactorsFallback for T {}

fn is_no_factors<T: Any>(_: &T) -> bool {
    TypeId::of::<T>() == TypeId::of::<NoFactors>()
}

/// Hadamard's bound `Π |column|`: the scale `|det J|` is measured against.
fn hadamard(j: &[[f64; 6]; 6]) -> f64 {
    (0..6)
        .map(|c| (0..6).map(|r| j[r][c] * j[r][c]).sum::<f64>().sqrt())
        .product()
}

#[test]
fn the_fallback_was_taken() {
    let q = [0.1; 6];
    assert!(is_no_factors(&General6r::default().singular_factors(&q)));
    assert!(is_no_factors(&Ur5Lu::default().singular_factors(&q)));
    // The closed-form UR5 has them: the detection above can tell the two apart.
    assert!(!is_no_factors(
        &kinegen_robots::Ur5::default().singular_factors(&q)
    ));
}

#[test]
fn general_6r_lu_determinant_equals_the_numeric_one() {
    let (robot, _) =
        kinegen_core::front::toml_file::load_str(GENERAL_6R_TOML, "general_6r.toml").unwrap();
    let num = NumericRobot::new(&robot).unwrap();
    let arm = General6r::default();
    for q in configurations::<6>(6, 200) {
        // Same table: same pose.
        let t = arm.fk(&q);
        let tr = num.fk(&q).unwrap();
        for r in 0..3 {
            for c in 0..4 {
                assert!((t[r][c] - tr[(r, c)]).abs() < 1e-12, "fk differs at {q:?}");
            }
        }
        let want = numeric::det6(&num.jacobian(&q).unwrap()).unwrap();
        let got = arm.jacobian_det(&q);
        assert!(
            (got - want).abs() <= 1e-9 * want.abs() + 1e-15 * hadamard(&arm.jacobian(&q)),
            "q = {q:?}: generated {got} vs numeric {want}"
        );
        // The trait method is the same function.
        assert_eq!(Kinematics::jacobian_det(&arm, &q), Some(got));
    }
}

#[test]
fn lu_determinant_is_finite_and_right_at_and_near_singularities() {
    let lu = Ur5Lu::default();
    let closed = kinegen_robots::Ur5::default();
    let robot = kinegen_core::front::toml_file::load_file(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("robots/ur5.toml"),
    )
    .unwrap()
    .0;
    let num = NumericRobot::new(&robot).unwrap();
    // Shoulder singularity: a2 c2 + a3 c23 + d5 s234 = 0. With q3 = 1 and
    // q4 = -(q2 + q3) (so s234 = 0) it is a2 c2 + a3 cos(q2 + 1) = 0, i.e.
    // tan q2 = (a2 + a3 cos 1) / (a3 sin 1).
    let (a2, a3) = (closed.a2, closed.a3);
    let q2s = ((a2 + a3 * 1f64.cos()) / (a3 * 1f64.sin())).atan();
    let shoulder = |e: f64| [0.3, q2s + e, 1.0, -(q2s + 1.0), 1.1, 0.2];
    assert!(closed
        .singular_factors(&shoulder(0.0))
        .iter()
        .any(|f| f.abs() < 1e-15));
    let singular = [
        [0.3, -1.0, 0.0, 0.4, 1.1, 0.2], // elbow, sin(q3) = 0
        [0.3, -1.0, std::f64::consts::PI, 0.4, 1.1, 0.2], // elbow folded back
        [0.3, -1.0, 1.2, 0.4, 0.0, 0.2], // wrist, sin(q5) = 0
        shoulder(0.0),                   // shoulder
        [0.0; 6],                        // elbow and wrist at once
    ];
    for q in singular {
        let got = lu.jacobian_det(&q);
        let scale = hadamard(&lu.jacobian(&q));
        assert!(
            closed.jacobian_det(&q).abs() <= 1e-12 * scale,
            "q = {q:?} is not singular"
        );
        assert!(got.is_finite(), "q = {q:?}: {got}");
        assert!(
            got.abs() <= 1e-12 * scale,
            "q = {q:?}: det {got} is not ~0 (scale {scale})"
        );
    }
    for eps in [1e-3, 1e-6, 1e-9] {
        let near = [
            [0.3, -1.0, eps, 0.4, 1.1, 0.2],
            [0.3, -1.0, 1.2, 0.4, eps, 0.2],
            shoulder(eps),
        ];
        for q in near {
            let got = lu.jacobian_det(&q);
            let want = closed.jacobian_det(&q);
            let reference = numeric::det6(&num.jacobian(&q).unwrap()).unwrap();
            assert!(got.is_finite() && want != 0.0, "q = {q:?}: {got}");
            // Near a singularity one column is nearly dependent: the rounding error of
            // any numeric determinant grows like eps·scale, not like |det|.
            let tol = 1e-6 * want.abs() + 1e-15 * hadamard(&lu.jacobian(&q));
            assert!(
                (got - want).abs() <= tol,
                "q = {q:?}: LU {got} vs closed form {want}"
            );
            assert!(
                (reference - want).abs() <= tol,
                "q = {q:?}: numeric {reference} vs closed form {want}"
            );
        }
    }
}
