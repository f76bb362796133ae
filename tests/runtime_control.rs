//! Proportional motion control: joint space and Cartesian space (planar task and full pose).

mod common;

use common::*;
use kinegen::adapters::fk_isometry;
use kinegen::control::*;
use kinegen::pose_error::wrap_angle;
use kinegen::{Kinematics, SolveError};
use nalgebra::{SVector, Vector3};
use proptest::prelude::*;
#[path = "../kinegen-core/tests/common/fixed_seed.rs"]
mod fixed_seed;
use fixed_seed::fixed_seed;
use std::f64::consts::PI;

proptest! {
    #![proptest_config(fixed_seed(256))]

    #[test]
    fn wrap_angle_lands_in_half_open_interval(a in -1e3..1e3f64) {
        let w = wrap_angle(a);
        prop_assert!(w > -PI && w <= PI);
        let turns = (a - w) / (2.0 * PI);
        prop_assert!((turns - turns.round()).abs() < 1e-9);
    }

    #[test]
    fn joint_p_step_contracts_geometrically(q in [-3.0..3.0f64, -3.0..3.0, -3.0..3.0], qd in [-3.0..3.0f64, -3.0..3.0, -3.0..3.0], kp in 0.05..1.0f64) {
        let mut x = q;
        for _ in 0..10 {
            x = joint_p_step(&x, &qd, kp).unwrap();
        }
        for i in 0..3 {
            let expected = (1.0 - kp).powi(10) * (q[i] - qd[i]);
            prop_assert!(((x[i] - qd[i]) - expected).abs() < 1e-12);
        }
    }
}

#[test]
fn planar_rrr_cartesian_control_converges() {
    let robot = planar_rrr();
    let mut q = [0.4, 0.9, -0.6];
    let x_d = SVector::<f64, 3>::new(4.0, 4.0, 0.3);
    let mut errors = Vec::new();
    for _ in 0..60 {
        q = cartesian_p_step_task(&robot, &q, &x_d, 0.3).unwrap();
        errors.push((task_coordinates(&robot, &q) - x_d).norm());
    }
    assert!(errors[59] < 1e-8, "final error {}", errors[59]);
    // Proportional: the error shrinks by about (1 − Kp) per step once linearisation holds.
    let ratio = errors[30] / errors[29];
    assert!((ratio - 0.7).abs() < 0.01, "ratio {ratio}");
}

#[test]
fn angle_error_takes_the_short_way_round() {
    let robot = planar_rrr();
    // θ(q) = q1 + q2 + q3 = π − 0.05; the target θ = −π + 0.05 is 0.1 rad away, not 2π − 0.1.
    let q = [0.5, 1.0, PI - 0.05 - 1.5];
    let x = task_coordinates(&robot, &q);
    assert!((x[2] - (PI - 0.05)).abs() < 1e-12);
    let x_d = SVector::<f64, 3>::new(x[0], x[1], -PI + 0.05);
    let e = task_error(&[0, 1, 5], &x_d, &x);
    assert!((e[2] - 0.1).abs() < 1e-12, "{e}");
    let q1 = cartesian_p_step_task(&robot, &q, &x_d, 1.0).unwrap();
    let dtheta: f64 = q1.iter().sum::<f64>() - q.iter().sum::<f64>();
    assert!((dtheta - 0.1).abs() < 1e-9, "{dtheta}");
}

#[test]
fn cartesian_control_refuses_singular_and_bad_input() {
    let robot = planar_rrr();
    let x_d = SVector::<f64, 3>::new(1.0, 1.0, 0.0);
    assert!(matches!(
        cartesian_p_step_task(&robot, &[0.2, 0.0, 0.3], &x_d, 0.5),
        Err(SolveError::Singular { .. })
    ));
    assert_eq!(
        cartesian_p_step_task(&robot, &[f64::NAN, 0.5, 0.3], &x_d, 0.5),
        Err(SolveError::NonFinite)
    );
    assert_eq!(
        joint_p_step(&[0.0, 1.0], &[f64::INFINITY, 0.0], 0.5),
        Err(SolveError::NonFinite)
    );
    let ur = ur5();
    let target = fk_isometry(&ur, &[0.1, -1.2, 1.0, 0.3, 0.8, 0.0]);
    assert!(matches!(
        cartesian_p_step_pose(&ur, &[0.1, -1.2, 0.0, 0.3, 0.8, 0.0], &target, 0.5),
        Err(SolveError::Singular { .. })
    ));
}

#[test]
fn ur5_pose_control_converges() {
    let robot = ur5();
    let q_goal = [0.3, -1.3, 1.4, -0.4, 1.1, 0.6];
    let target = fk_isometry(&robot, &q_goal);
    let mut q = [0.2, -1.1, 1.2, -0.3, 1.0, 0.9];
    for _ in 0..80 {
        q = cartesian_p_step_pose(&robot, &q, &target, 0.3).unwrap();
    }
    let reached = fk_isometry(&robot, &q);
    assert!((reached.translation.vector - target.translation.vector).norm() < 1e-9);
    assert!(reached.rotation.angle_to(&target.rotation) < 1e-6);
    let _ = Vector3::<f64>::zeros();
    let _ = robot.limits();
}
