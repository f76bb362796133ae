//! The engine's symbolic FK and Jacobians, evaluated node by node, equal the numeric
//! reference (DH matrix products, `z × (p − o)` columns) on random tables and
//! configurations: both conventions, prismatic joints, arbitrary twists, base and tool.

#[path = "common/random_robot.rs"]
mod random_robot;
use random_robot::robot_strategy;

use kinegen_core::numeric::NumericRobot;
use kinegen_core::simplify::order;
use kinegen_core::Deadline;
use kinegen_core::{Options, Robot};
use proptest::prelude::*;
#[path = "common/fixed_seed.rs"]
mod fixed_seed;
use fixed_seed::fixed_seed;

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
