//! Generated calls never touch the heap: a counting global allocator sees zero
//! allocations across fk, frames, jacobian, jacobian_ee, task_jacobian and the determinant.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use kinegen_robots::{Panda, PlanarRrr, Ur5};

struct Counting;

static ALLOCS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCS.fetch_add(1, Ordering::SeqCst);
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
    let before = ALLOCS.load(Ordering::SeqCst);
    let mut acc = 0.0;
    for _ in 0..100 {
        acc += ur5.fk(&q6)[0][3] + ur5.jacobian(&q6)[0][0] + ur5.jacobian_ee(&q6)[1][1];
        acc += ur5.frames(&q6)[2][0][3] + ur5.jacobian_det(&q6) + ur5.singular_factors(&q6)[4];
        acc += ur5.fk_and_jacobian(&q6).1[2][2];
        acc += panda.fk(&q7)[2][3] + panda.jacobian(&q7)[5][6];
        acc += rrr.task_jacobian(&q3)[2][2] + rrr.jacobian_det(&q3);
    }
    let after = ALLOCS.load(Ordering::SeqCst);
    assert!(acc.is_finite());
    assert_eq!(after - before, 0, "generated code allocated");
}
