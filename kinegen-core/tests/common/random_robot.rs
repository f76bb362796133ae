//! A random DH table as a proptest strategy: each joint revolute or prismatic, twists
//! mixing exact angles and arbitrary ones, lengths partly named, both conventions, base
//! and tool frames or none. Shared by the tests that compare the engine with the numeric
//! reference on random robots (`#[path]`-included: it needs proptest, which not every
//! includer of `common/mod.rs` has).

use kinegen_core::model::{
    raw::{RawJoint, RawRobot, RawValue},
    validate::validate,
};
use kinegen_core::Robot;
use proptest::prelude::*;

fn text(s: String) -> RawValue {
    RawValue::Text(s)
}

/// A random robot: each joint revolute or prismatic, twists from a set mixing exact
/// angles and arbitrary ones, lengths partly named.
pub fn robot_strategy() -> impl Strategy<Value = Robot> {
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
