//! The engine's symbolic FK and Jacobians, evaluated node by node, equal the numeric
//! reference (DH matrix products, `z × (p − o)` columns) on random tables and
//! configurations: both conventions, prismatic joints, arbitrary twists, base and tool.

use kinegen_core::model::{
    raw::{RawJoint, RawRobot, RawValue},
    validate::validate,
};
use kinegen_core::numeric::NumericRobot;
use kinegen_core::simplify::order;
use kinegen_core::Deadline;
use kinegen_core::{Options, Robot};
use proptest::prelude::*;
#[path = "common/fixed_seed.rs"]
mod fixed_seed;
use fixed_seed::fixed_seed;

fn text(s: String) -> RawValue {
    RawValue::Text(s)
}

/// A random robot: each joint revolute or prismatic, twists from a set mixing exact
/// angles and arbitrary ones, lengths partly named.
fn robot_strategy() -> impl Strategy<Value = Robot> {
    let twist = prop_oneof![
        Just("0".to_string()),
        Just("pi/2".to_string()),
        Just("-pi/2".to_string()),
        Just("pi".to_string()),
        Just("pi/3".to_string()),
        Just("3*pi/4".to_string()),
        (-3.0f64..3.0).prop_map(|x| format!("{x:.3}")),
    ];
    let joint = (
        any::<bool>(),
        -1.0f64..1.0,
        twist.clone(),
        -1.0f64..1.0,
        twist,
        any::<bool>(),
    );
    (
        prop::collection::vec(joint, 1..7),
        any::<bool>(),
        any::<bool>(),
        (-1.0f64..1.0, -3.0f64..3.0),
    )
        .prop_map(|(joints, modified, with_frames, (x, ang))| {
            let mut params = Vec::new();
            let rows = joints
                .into_iter()
                .enumerate()
                .map(|(i, (prismatic, a, alpha, d, theta, named))| {
                    let a = if named {
                        params.push((
                            format!("a{i}"),
                            RawValue::Number((a * 1000.0).round() / 1000.0),
                        ));
                        format!("a{i}")
                    } else {
                        format!("{a:.3}")
                    };
                    RawJoint {
                        kind: Some(if prismatic { "prismatic" } else { "revolute" }.into()),
                        fields: vec![
                            ("a".into(), text(a)),
                            ("alpha".into(), text(alpha)),
                            ("d".into(), text(format!("{d:.3}"))),
                            ("theta".into(), text(theta)),
                        ],
                    }
                })
                .collect();
            let frame = |k: f64| {
                vec![
                    (
                        "xyz".into(),
                        RawValue::List(vec![
                            RawValue::Number(k),
                            RawValue::Number(0.1),
                            RawValue::Number(-k),
                        ]),
                    ),
                    (
                        "rpy".into(),
                        RawValue::List(vec![
                            text(format!("{ang:.3}")),
                            text("pi/2".into()),
                            RawValue::Number(0.25),
                        ]),
                    ),
                ]
            };
            validate(&RawRobot {
                name: Some("random".into()),
                convention: Some(if modified { "modified" } else { "standard" }.into()),
                params,
                joints: rows,
                base: with_frames.then(|| frame(x)),
                tool: with_frames.then(|| frame(-x / 2.0)),
                ..Default::default()
            })
            .expect("generated tables are valid")
        })
}

/// Every evaluation order (plain chain, or the tail built in middle frame `pivot`)
/// must give the reference values; cases cycle through them.
fn check(robot: &Robot, q: &[f64], pivot: usize) {
    let pivot = (pivot > 0).then_some(pivot);
    let chain = robot.chain();
    let options = Options::default();
    let model = order::variant(&chain, &options, pivot, Deadline::start(&options.budget));
    let num = NumericRobot::new(robot).unwrap();
    let n = robot.dof();
    let t = num.fk(q).unwrap();
    let fk: Vec<_> = model.fk_rows.iter().flatten().copied().collect();
    let got = model.eval(&chain, q, &fk);
    for r in 0..3 {
        for c in 0..4 {
            assert!((got[r * 4 + c] - t[(r, c)]).abs() < 1e-9, "fk[{r}][{c}]");
        }
    }
    let frames = num.frames(q).unwrap();
    for (i, rows) in model.frame_rows.iter().enumerate() {
        let ids: Vec<_> = rows.iter().flatten().copied().collect();
        let got = model.eval(&chain, q, &ids);
        for r in 0..3 {
            for c in 0..4 {
                let want = frames[i][(r, c)];
                assert!(
                    (got[r * 4 + c] - want).abs() < 1e-9,
                    "frame {i} [{r}][{c}] (pivot {pivot:?})"
                );
            }
        }
    }
    let j = num.jacobian(q).unwrap();
    let jee = num.jacobian_ee(q).unwrap();
    for (rows, reference) in [(&model.jacobian, &j), (&model.jacobian_ee, &jee)] {
        let ids: Vec<_> = rows.iter().flatten().copied().collect();
        let got = model.eval(&chain, q, &ids);
        for r in 0..6 {
            for c in 0..n {
                assert!(
                    (got[r * n + c] - reference[(r, c)]).abs() < 1e-9,
                    "J[{r}][{c}]: {} vs {} (pivot {pivot:?})",
                    got[r * n + c],
                    reference[(r, c)]
                );
            }
        }
    }
}

proptest! {
    #![proptest_config(fixed_seed(64))]
    #[test]
    fn symbolic_equals_numeric(
        robot in robot_strategy(),
        seed in prop::collection::vec(-3.0f64..3.0, 7),
        pivot in 0usize..7,
    ) {
        let q = &seed[..robot.dof()];
        check(&robot, q, pivot);
    }
}
