//! Generated calls never touch the heap: a counting global allocator sees zero
//! allocations across fk, frames, jacobian, jacobian_ee, task_jacobian, the determinant and
//! the closed-form IK.

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
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn generated_calls_do_not_allocate() {
    let (ur5, panda, rrr) = (Ur5::default(), Panda::default(), PlanarRrr::default());
    let q6 = [0.1, -1.2, 1.4, -0.3, 1.1, 0.2];
    let q7 = [0.1, -0.4, 0.2, -2.0, 0.3, 1.6, 0.7];
    let q3 = [0.3, 0.4, -0.2];
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
    }
    let after = ALLOCS.load(Ordering::SeqCst);
    COUNTING.with(|c| c.set(false));
    assert!(acc.is_finite());
    assert_eq!(after - before, 0, "generated code allocated");
}
