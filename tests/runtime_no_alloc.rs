//! The runtime never allocates: a counting global allocator (in its own test binary, one
//! test, counting only this thread) sees zero allocations across inverse velocity
//! kinematics, pseudo-inverses, DLS, manipulability and its gradient, IK (single and
//! multi-start), control steps, resolved-acceleration control and gradient projection.

mod common;

use common::*;
use kinegen::acceleration::{resolved_acceleration, resolved_acceleration_step, Gains, Reference};
use kinegen::adapters::{fk_isometry, jacobian_matrix};
use kinegen::control::{cartesian_p_step_pose, cartesian_p_step_task};
use kinegen::ik::{solve, solve_nearest, IkMethod, IkOptions, IkTarget, MultiStart};
use kinegen::manipulability::{manipulability_gradient, measures};
use kinegen::redundancy::{gradient_projection, Projection};
use kinegen::trajectory::{CartesianLine, ThroughVias};
use kinegen::velocity::*;
use nalgebra::{SVector, Vector3};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::hint::black_box;
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    static ARMED: Cell<bool> = const { Cell::new(false) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if ARMED.with(|a| a.get()) {
            ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        }
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if ARMED.with(|a| a.get()) {
            ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        }
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn count<T>(f: impl FnOnce() -> T) -> (usize, T) {
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    ARMED.with(|a| a.set(true));
    let out = f();
    ARMED.with(|a| a.set(false));
    (ALLOCATIONS.load(Ordering::SeqCst) - before, out)
}

#[test]
fn runtime_does_not_allocate() {
    let robot = ur5();
    let q = [0.3, -1.1, 1.2, -0.4, 0.9, 0.2];
    let singular = [0.3, -1.1, 0.0, -0.4, 0.9, 0.2];
    let xdot = SVector::<f64, 6>::new(0.1, -0.2, 0.05, 0.3, 0.0, -0.1);
    let target = IkTarget::Pose(fk_isometry(&robot, &[0.5, -1.4, 1.3, 0.2, 1.1, -0.3]));
    // The counter does count.
    let (n, v) = count(|| vec![1u8; 16]);
    assert_eq!(n, 1);
    drop(v);

    let (n, ok) = count(|| {
        let j = jacobian_matrix(&robot, black_box(&q));
        let js = jacobian_matrix(&robot, black_box(&singular));
        let mut fine = inverse_velocity(&j, &xdot, DEFAULT_TOLERANCE).is_ok();
        fine &= inverse_velocity(&js, &xdot, DEFAULT_TOLERANCE).is_err();
        fine &= dls_velocity(&js, &xdot, &Damping::default()).is_ok();
        fine &= pinv_velocity(&j, &xdot, 1e-12).is_ok();
        fine &= pinv_svd(&js, 1e-12).is_ok();
        fine &= pinv_right(&j, DEFAULT_TOLERANCE).is_ok();
        fine &= transpose_velocity(&j, &xdot, 0.1).is_ok();
        fine &= measures(&j).is_ok();
        for method in [
            IkMethod::NewtonRaphson,
            IkMethod::DampedLeastSquares(Damping::default()),
            IkMethod::LevenbergMarquardt { initial_mu: 1e-2 },
        ] {
            let opts = IkOptions {
                method,
                ..IkOptions::default()
            };
            fine &= solve(&robot, &target, black_box(&q), &opts).is_ok();
        }
        fine &= solve_nearest(
            &robot,
            &target,
            &q,
            &IkOptions::default(),
            &MultiStart::default(),
        )
        .is_ok();
        fine &= solve(
            &robot,
            &IkTarget::Position(Vector3::new(0.3, 0.2, 0.4)),
            &q,
            &IkOptions::default(),
        )
        .is_ok();
        // Failure paths too: out of reach, invalid input.
        fine &= solve(
            &robot,
            &IkTarget::Position(Vector3::new(3.0, 0.0, 0.0)),
            &q,
            &IkOptions::default(),
        )
        .is_err();
        fine &= solve(
            &robot,
            &IkTarget::Position(Vector3::new(f64::NAN, 0.0, 0.0)),
            &q,
            &IkOptions::default(),
        )
        .is_err();
        if let IkTarget::Pose(iso) = target {
            fine &= cartesian_p_step_pose(&robot, &q, &iso, 0.5).is_ok();
        }
        fine &= cartesian_p_step_task(
            &planar_rrr(),
            &[0.3, 0.9, -0.4],
            &SVector::<f64, 3>::new(4.0, 3.0, 0.2),
            0.5,
        )
        .is_ok();
        // Generated redundant arm (6×7 normal-equation and SVD paths), IK line tracking
        // and limit-fitted via-point cubics.
        let panda = kinegen_robots::Panda::default();
        let q7 = [0.1, -0.4, 0.2, -2.0, 0.3, 1.6, 0.7];
        let goal = IkTarget::Pose(fk_isometry(&panda, &[0.2, -0.3, 0.1, -1.8, 0.2, 1.5, 0.6]));
        fine &= solve(&panda, &goal, black_box(&q7), &IkOptions::default()).is_ok();
        let ur5 = kinegen_robots::Ur5::default();
        let a = fk_isometry(&ur5, &q);
        let b = nalgebra::Translation3::new(0.05, 0.0, 0.0) * a;
        let line = CartesianLine::with_limits(a, b, 0.25, 1.0, 1.0, 2.0).unwrap();
        fine &= line
            .track_ik(&ur5, 500.0, q, &IkOptions::default(), 0.05)
            .unwrap()
            .all(|s| s.is_ok());
        fine &= ThroughVias::with_limits([0.0, 1.0, 3.0, 2.0], 1.0, 2.0).is_ok();
        // Second order: resolved acceleration (and tracking), gradient projection, the
        // manipulability gradient's SVD.
        let xdd = SVector::<f64, 6>::new(0.1, 0.0, -0.2, 0.0, 0.3, 0.0);
        fine &= resolved_acceleration(&ur5, &q, &[0.2; 6], &xdd, &Damping::default()).is_ok();
        let reference = Reference {
            pose: b,
            twist: SVector::zeros(),
            acceleration: SVector::zeros(),
        };
        fine &= resolved_acceleration_step(
            &ur5,
            &q,
            &[0.1; 6],
            &reference,
            &Gains::critical(5.0),
            &Damping::default(),
        )
        .is_ok();
        fine &= gradient_projection(&panda, &q7, &xdot, &Projection::default()).is_ok();
        fine &= manipulability_gradient(&ur5.jacobian(&q), &ur5.hessian(&q)).is_ok();
        fine
    });
    assert!(ok, "some call did not give the expected result");
    assert_eq!(n, 0, "the runtime allocated {n} times");
}
