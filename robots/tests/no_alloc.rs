//! Generated calls never touch the heap: a counting global allocator sees zero
//! allocations across fk, frames, jacobian, jacobian_ee, task_jacobian, the determinant,
//! the closed-form IK, and the second-order methods (hessian, jacobian_dot, jdot_qdot,
//! jacobian_ee_dot, det_gradient, singular_factor_gradients and the manipulability
//! gradients, whose SVD runs on the stack).

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};

use kinegen_robots::{Panda, PlanarRrr, Ur5};

struct Counting;

static ALLOCS: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    // Only the measuring thread counts: the test harness's own threads allocate too
    // (progress output, timers), and counting them made this test fail under load.
    static COUNTING: Cell<bool> = const { Cell::new(false) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if COUNTING.with(Cell::get) {
            ALLOCS.fetch_add(1, Ordering::SeqCst);
        }
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if COUNTING.with(Cell::get) {
            ALLOCS.fetch_add(1, Ordering::SeqCst);
        }
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn generated_calls_do_not_allocate() {
    let (ur5, panda, rrr) = (Ur5::default(), Panda::default(), PlanarRrr::default());
    let q6 = [0.1, -1.2, 1.4, -0.3, 1.1, 0.2];
    let q7 = [0.1, -0.4, 0.2, -2.0, 0.3, 1.6, 0.7];
    let q3 = [0.3, 0.4, -0.2];
    // The counter does count.
    COUNTING.with(|c| c.set(true));
    let v = vec![1u8; 16];
    COUNTING.with(|c| c.set(false));
    assert_eq!(ALLOCS.load(Ordering::SeqCst), 1);
    drop(v);
    COUNTING.with(|c| c.set(true));
    let before = ALLOCS.load(Ordering::SeqCst);
    let mut acc = 0.0;
    for _ in 0..100 {
        acc += ur5.fk(&q6)[0][3] + ur5.jacobian(&q6)[0][0] + ur5.jacobian_ee(&q6)[1][1];
        acc += ur5.frames(&q6)[2][0][3] + ur5.jacobian_det(&q6) + ur5.singular_factors(&q6)[4];
        acc += ur5.fk_and_jacobian(&q6).1[2][2];
        acc += panda.fk(&q7)[2][3] + panda.jacobian(&q7)[5][6];
        acc += rrr.task_jacobian(&q3)[2][2] + rrr.jacobian_det(&q3);
        // Closed-form IK: every solution, the nearest, a task-row (planar) solve.
        let pose = ur5.fk(&q6);
        acc += ur5.ik(&pose).len() as f64 + ur5.ik_near(&pose, &q6).map_or(0.0, |q| q[0]);
        acc += rrr.ik(&rrr.fk(&q3)).len() as f64;
        acc += ur5.hessian(&q6)[1][0][2] + ur5.jdot_qdot(&q6, &q6)[3];
        acc += ur5.jacobian_dot(&q6, &q6)[0][1] + ur5.jacobian_ee_dot(&q6, &q6)[4][5];
        acc += ur5.det_gradient(&q6)[2] + ur5.singular_factor_gradients(&q6)[4][1];
        acc += ur5.manipulability_gradient(&q6)[3];
        acc += panda.hessian(&q7)[6][2][0] + panda.jdot_qdot(&q7, &q7)[0];
        acc += panda.jacobian_dot(&q7, &q7)[1][1] + panda.manipulability_gradient(&q7)[6];
        acc += rrr.manipulability_task_gradient(&q3)[1] + rrr.det_gradient(&q3)[0];
    }
    let after = ALLOCS.load(Ordering::SeqCst);
    COUNTING.with(|c| c.set(false));
    assert!(acc.is_finite());
    assert_eq!(after - before, 0, "generated code allocated");
}
