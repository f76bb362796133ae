use std::f64::consts::PI;

use nalgebra::Rotation3;
use proptest::prelude::*;
#[path = "../../tests/common/fixed_seed.rs"]
mod fixed_seed;
use fixed_seed::fixed_seed;

use super::*;
use crate::model::raw::{RawJoint, RawRobot, RawValue};
use crate::model::validate::validate;

fn t(s: &str) -> RawValue {
    RawValue::Text(s.to_string())
}

fn n(x: f64) -> RawValue {
    RawValue::Number(x)
}

/// A joint row: kind, then (column, value) pairs.
fn row(kind: &str, fields: &[(&str, RawValue)]) -> RawJoint {
    RawJoint {
        kind: Some(kind.into()),
        fields: fields
            .iter()
            .map(|(k, v)| (k.to_string(), v.clone()))
            .collect(),
    }
}

fn frame(xyz: [f64; 3], rpy: [RawValue; 3]) -> Option<Vec<(String, RawValue)>> {
    Some(vec![
        (
            "xyz".into(),
            RawValue::List(xyz.iter().map(|&x| n(x)).collect()),
        ),
        ("rpy".into(), RawValue::List(rpy.to_vec())),
    ])
}

fn planar_rr(l1: f64, l2: f64) -> Robot {
    let r = |a: &str| row("revolute", &[("a", t(a)), ("alpha", n(0.0)), ("d", n(0.0))]);
    validate(&RawRobot {
        name: Some("RR".into()),
        convention: Some("standard".into()),
        params: vec![("L1".into(), n(l1)), ("L2".into(), n(l2))],
        joints: vec![r("L1"), r("L2")],
        task: Some(vec![t("x"), t("y")]),
        ..Default::default()
    })
    .unwrap()
}

/// A UR5-like 6R arm (standard DH) on a tilted, shifted base with a rotated tool.
fn ur_like() -> Robot {
    let r = |a: RawValue, alpha: &str, d: RawValue| {
        row("revolute", &[("a", a), ("alpha", t(alpha)), ("d", d)])
    };
    validate(&RawRobot {
        name: Some("UR-like".into()),
        convention: Some("standard".into()),
        params: vec![
            ("d1".into(), n(0.089159)),
            ("a2".into(), n(-0.425)),
            ("a3".into(), n(-0.39225)),
            ("d4".into(), n(0.10915)),
            ("d5".into(), n(0.09465)),
            ("d6".into(), n(0.0823)),
        ],
        joints: vec![
            r(n(0.0), "pi/2", t("d1")),
            r(t("a2"), "0", n(0.0)),
            r(t("a3"), "0", n(0.0)),
            r(n(0.0), "pi/2", t("d4")),
            r(n(0.0), "-pi/2", t("d5")),
            r(n(0.0), "0", t("d6")),
        ],
        base: frame([0.1, -0.2, 0.3], [n(0.2), n(-0.4), t("pi/3")]),
        tool: frame([0.01, 0.02, 0.15], [t("pi/2"), n(0.1), n(-0.7)]),
        ..Default::default()
    })
    .unwrap()
}

/// Standard DH with a prismatic joint, offsets and twists that are not multiples of π/2.
fn standard_mixed() -> Robot {
    validate(&RawRobot {
        convention: Some("standard".into()),
        joints: vec![
            row(
                "revolute",
                &[
                    ("a", n(0.1)),
                    ("alpha", n(0.7)),
                    ("d", n(0.3)),
                    ("offset", n(0.2)),
                ],
            ),
            row(
                "prismatic",
                &[
                    ("a", n(0.05)),
                    ("alpha", t("-pi/3")),
                    ("theta", n(0.4)),
                    ("offset", n(0.25)),
                ],
            ),
            row(
                "revolute",
                &[
                    ("a", n(0.4)),
                    ("alpha", n(1.1)),
                    ("d", n(-0.12)),
                    ("theta", t("pi/6")),
                ],
            ),
            row(
                "prismatic",
                &[("a", n(0.0)), ("alpha", n(0.0)), ("theta", n(-0.3))],
            ),
            row(
                "revolute",
                &[("a", n(0.2)), ("alpha", t("pi/2")), ("d", n(0.07))],
            ),
        ],
        base: frame([0.5, 0.0, -0.1], [n(0.3), n(0.2), n(0.1)]),
        tool: frame([0.0, 0.1, 0.2], [n(-0.5), n(0.6), n(0.7)]),
        ..Default::default()
    })
    .unwrap()
}

/// Modified DH (Craig), 7 joints with a prismatic one, odd twists, base and tool.
fn modified_mixed() -> Robot {
    validate(&RawRobot {
        convention: Some("modified".into()),
        joints: vec![
            row(
                "revolute",
                &[("a", n(0.0)), ("alpha", n(0.0)), ("d", n(0.333))],
            ),
            row(
                "revolute",
                &[("a", n(0.0)), ("alpha", t("-pi/2")), ("d", n(0.0))],
            ),
            row(
                "prismatic",
                &[
                    ("a", n(0.1)),
                    ("alpha", n(0.9)),
                    ("theta", n(0.3)),
                    ("offset", n(0.2)),
                ],
            ),
            row(
                "revolute",
                &[
                    ("a", n(0.0825)),
                    ("alpha", t("pi/2")),
                    ("d", n(0.0)),
                    ("offset", n(-0.4)),
                ],
            ),
            row(
                "revolute",
                &[("a", n(-0.0825)), ("alpha", t("-pi/2")), ("d", n(0.384))],
            ),
            row(
                "revolute",
                &[("a", n(0.0)), ("alpha", n(0.4)), ("d", n(0.0))],
            ),
            row(
                "revolute",
                &[("a", n(0.088)), ("alpha", t("pi/2")), ("d", n(0.0))],
            ),
        ],
        base: frame([0.0, 0.3, 0.2], [n(0.0), n(0.0), n(1.0)]),
        tool: frame([0.0, 0.0, 0.2104], [n(0.0), n(0.0), t("-pi/4")]),
        ..Default::default()
    })
    .unwrap()
}

fn robots() -> Vec<Robot> {
    vec![
        planar_rr(1.3, 0.7),
        ur_like(),
        standard_mixed(),
        modified_mixed(),
    ]
}

#[test]
fn planar_rr_closed_form() {
    let (l1, l2) = (1.3, 0.7);
    let robot = planar_rr(l1, l2);
    for &(q1, q2) in &[(0.0, 0.0), (0.3, -1.2), (2.5, 0.9), (-1.0, PI)] {
        let q = [q1, q2];
        let (s1, c1, s12, c12) = (q1.sin(), q1.cos(), (q1 + q2).sin(), (q1 + q2).cos());
        let t = fk(&robot, &q).unwrap();
        assert!((t[(0, 3)] - (l1 * c1 + l2 * c12)).abs() < 1e-14);
        assert!((t[(1, 3)] - (l1 * s1 + l2 * s12)).abs() < 1e-14);
        assert!(t[(2, 3)].abs() < 1e-15);
        let j = jacobian(&robot, &q).unwrap();
        let want = [
            [-l1 * s1 - l2 * s12, -l2 * s12],
            [l1 * c1 + l2 * c12, l2 * c12],
            [0.0, 0.0],
            [0.0, 0.0],
            [0.0, 0.0],
            [1.0, 1.0],
        ];
        for (r, wr) in want.iter().enumerate() {
            for (c, w) in wr.iter().enumerate() {
                assert!(
                    (j[(r, c)] - w).abs() < 1e-14,
                    "J[{r}][{c}] = {} ≠ {w}",
                    j[(r, c)]
                );
            }
        }
        let jt = task_jacobian(&robot, &q).unwrap();
        assert_eq!(jt.shape(), (2, 2));
        let d = det(&jt).unwrap();
        assert!((d - l1 * l2 * q2.sin()).abs() < 1e-14, "det {d}");
        assert!((manipulability(&jt) - (l1 * l2 * q2.sin()).abs()).abs() < 1e-14);
    }
}

/// The same planar RR written in modified DH (tool = Tx(L2)) has the same FK and Jacobian.
#[test]
fn modified_planar_rr_matches_standard() {
    let r = |a: f64| row("revolute", &[("a", n(a)), ("alpha", n(0.0)), ("d", n(0.0))]);
    let modified = validate(&RawRobot {
        convention: Some("modified".into()),
        joints: vec![r(0.0), r(1.3)],
        tool: frame([0.7, 0.0, 0.0], [n(0.0), n(0.0), n(0.0)]),
        ..Default::default()
    })
    .unwrap();
    let standard = planar_rr(1.3, 0.7);
    let q = [0.4, -2.1];
    assert!((fk(&modified, &q).unwrap() - fk(&standard, &q).unwrap()).amax() < 1e-15);
    let d = jacobian(&modified, &q).unwrap() - jacobian(&standard, &q).unwrap();
    assert!(d.amax() < 1e-15);
}

#[test]
fn rpy_matches_nalgebra_euler_angles() {
    let (r, p, y) = (0.3, -1.1, 2.4);
    let m = rpy_transform([1.0, 2.0, 3.0], [r, p, y]);
    let want = Rotation3::from_euler_angles(r, p, y);
    assert!((rotation(&m) - want.matrix()).amax() < 1e-15);
    assert_eq!(position(&m), Vector3::new(1.0, 2.0, 3.0));
}

#[test]
fn dh_matrix_closed_forms() {
    // Standard DH closed form (Spong): rows [cθ, −sθ cα, sθ sα, a cθ], …
    let (a, al, d, th): (f64, f64, f64, f64) = (0.3, 0.7, -0.2, 1.9);
    let (st, ct, sa, ca) = (th.sin(), th.cos(), al.sin(), al.cos());
    let std_want = Matrix4::new(
        ct,
        -st * ca,
        st * sa,
        a * ct, //
        st,
        ct * ca,
        -ct * sa,
        a * st, //
        0.0,
        sa,
        ca,
        d, //
        0.0,
        0.0,
        0.0,
        1.0,
    );
    assert!((dh_matrix(Convention::Standard, a, al, d, th) - std_want).amax() < 1e-15);
    // Modified DH closed form (Craig 3.6).
    let mod_want = Matrix4::new(
        ct,
        -st,
        0.0,
        a, //
        st * ca,
        ct * ca,
        -sa,
        -sa * d, //
        st * sa,
        ct * sa,
        ca,
        ca * d, //
        0.0,
        0.0,
        0.0,
        1.0,
    );
    assert!((dh_matrix(Convention::Modified, a, al, d, th) - mod_want).amax() < 1e-15);
}

#[test]
fn frames_end_at_fk_without_tool() {
    let robot = ur_like();
    let m = NumericRobot::new(&robot).unwrap();
    let q = [0.1, -0.5, 1.2, 0.3, -0.8, 2.0];
    let frames = m.frames(&q).unwrap();
    assert_eq!(frames.len(), 6);
    assert!((frames[5] * m.tool - m.fk(&q).unwrap()).amax() < 1e-15);
    assert!((frames[0] - m.base * m.link(0, q[0])).amax() < 1e-15);
}

#[test]
fn ee_jacobian_is_world_jacobian_rotated() {
    for robot in robots() {
        let m = NumericRobot::new(&robot).unwrap();
        let q: Vec<f64> = (0..m.dof()).map(|i| 0.3 * i as f64 - 0.5).collect();
        let r = rotation(&m.fk(&q).unwrap());
        let je = m.jacobian_ee(&q).unwrap();
        let j = m.jacobian(&q).unwrap();
        assert!((r * je.fixed_rows::<3>(0) - j.fixed_rows::<3>(0)).amax() < 1e-14);
        assert!((r * je.fixed_rows::<3>(3) - j.fixed_rows::<3>(3)).amax() < 1e-14);
    }
}

#[test]
fn det6_and_manipulability_agree() {
    let robot = ur_like();
    let m = NumericRobot::new(&robot).unwrap();
    let q = [0.1, -0.5, 1.2, 0.3, -0.8, 2.0];
    let j = m.jacobian(&q).unwrap();
    let d = det6(&j).unwrap();
    assert!(d.abs() > 1e-4, "regular pose expected, det {d}");
    assert!((manipulability6(&j) - d.abs()).abs() < 1e-12 * d.abs().max(1.0));
    // Wrist singularity: q5 = 0 aligns joints 4 and 6.
    let j = m.jacobian(&[0.1, -0.5, 1.2, 0.3, 0.0, 2.0]).unwrap();
    assert!(det6(&j).unwrap().abs() < 1e-15);
    // UR closed form (DESIGN.md): det = a2 a3 s3 s5 (a2 c2 + a3 c23 + d5 s234).
    let (a2, a3, d5) = (-0.425, -0.39225, 0.09465);
    let [_, q2, q3, q4, q5, _] = q;
    let want = a2
        * a3
        * q3.sin()
        * q5.sin()
        * (a2 * q2.cos() + a3 * (q2 + q3).cos() + d5 * (q2 + q3 + q4).sin());
    assert!((d - want).abs() < 1e-14, "{d} vs {want}");
}

#[test]
fn bad_input_is_an_error() {
    let robot = ur_like();
    let m = NumericRobot::new(&robot).unwrap();
    assert_eq!(
        m.fk(&[0.0; 5]).unwrap_err(),
        NumericError::JointCount {
            expected: 6,
            found: 5
        }
    );
    assert!(matches!(
        m.jacobian(&[0.0, f64::NAN, 0.0, 0.0, 0.0, 0.0]),
        Err(NumericError::NonFinite(_))
    ));
    assert_eq!(
        m.jacobian_fd(&[0.0; 6], 0.0).unwrap_err(),
        NumericError::BadStep(0.0)
    );
    assert!(det6(&jacobian(&planar_rr(1.0, 1.0), &[0.0, 0.0]).unwrap()).is_err());
    assert!(det(&DMatrix::zeros(2, 3)).is_err());
    let bad = NumericRobot::with_params(&robot, &|name| {
        if name == "a3" {
            f64::INFINITY
        } else {
            0.1
        }
    });
    assert!(matches!(bad, Err(NumericError::NonFinite(s)) if s == "joints[2].a"));
}

#[test]
fn parameter_override_changes_the_model() {
    let robot = planar_rr(1.0, 1.0);
    let m =
        NumericRobot::with_params(&robot, &|name| if name == "L1" { 2.0 } else { 0.5 }).unwrap();
    let t = m.fk(&[0.0, 0.0]).unwrap();
    assert_eq!(t[(0, 3)], 2.5);
}

fn check_agreement(robot: &Robot, q: &[f64]) -> Result<(), TestCaseError> {
    let m = NumericRobot::new(robot).unwrap();
    let j = m.jacobian(q).unwrap();
    let fd = m.jacobian_fd(q, 1e-5).unwrap();
    let prop = m.jacobian_propagation(q).unwrap();
    let e_fd = (&j - &fd).amax();
    let e_prop = (&j - &prop).amax();
    prop_assert!(
        e_fd < 1e-7,
        "{}: FD differs by {e_fd:e}\nJ = {j}\nFD = {fd}",
        robot.name
    );
    prop_assert!(
        e_prop < 1e-12,
        "{}: propagation differs by {e_prop:e}",
        robot.name
    );
    Ok(())
}

proptest! {
    #![proptest_config(fixed_seed(200))]

    #[test]
    fn three_jacobians_agree(
        which in 0usize..4,
        q in proptest::collection::vec(-PI..PI, 7),
    ) {
        let robot = &robots()[which];
        check_agreement(robot, &q[..robot.dof()])?;
    }
}

/// The case proptest once found (formerly `proptest-regressions/numeric/tests.txt`).
#[test]
fn former_regression_three_jacobians_at_zero() {
    let robot = &robots()[3];
    check_agreement(robot, &[0.0; 7][..robot.dof()]).unwrap();
}
