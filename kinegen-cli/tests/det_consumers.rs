//! The determinant's consumers (`show --what det|singularities`, `eval`'s `det_task`,
//! `stats`' `det`) before the engine provides determinants: fed a hand-built
//! determinant of the planar RR's task Jacobian (`Jt00·Jt11 − Jt01·Jt10` in the model's
//! graph), they show, evaluate and count it.

use kinegen_cli::det_hook::{Determinant, Determinants, Factor};
use kinegen_cli::{eval, formulas, robots, stats, What};
use kinegen_core::model::Model;
use kinegen_core::{generate, numeric, ItemHeader};

#[test]
fn a_determinant_from_the_hook_is_shown_evaluated_and_counted() {
    let (robot, options) = robots::load("planar_rr").unwrap();
    let mut model = Model::build(&robot, &options);
    let t = model.task.clone();
    let g = &mut model.chain.graph;
    let (a, b) = (g.mul(t[0][0], t[1][1]), g.mul(t[0][1], t[1][0]));
    let node = g.sub(a, b);
    let dets = Determinants {
        det: None,
        det_task: Some(Determinant {
            node,
            text: "L1*L2*sin(q2)".into(),
            latex: r"L_{1}\,L_{2}\,s_{2}".into(),
            factors: vec![Factor {
                text: "sin(q2)".into(),
                latex: r"s_{2}".into(),
                power: 1,
                joints: vec![2],
            }],
        }),
        missing: "not available".into(),
    };
    let shown = formulas::show(&robot, &model, &dets, What::Det, false);
    assert!(shown.contains("det Jt = L1*L2*sin(q2)"), "{shown}");
    let sing = formulas::show(&robot, &model, &dets, What::Singularities, true);
    assert!(sing.contains(r"s_{2} &= 0"), "{sing}");

    let q = [0.3, -1.1];
    let v = eval::values(&robot, &model, &dets, &q);
    let reference = numeric::det(&numeric::task_jacobian(&robot, &q).unwrap()).unwrap();
    let got = v.det_task.unwrap();
    assert!((got - reference).abs() < 1e-12, "{got} vs {reference}");
    assert!((got - (-1.1f64).sin()).abs() < 1e-12);
    assert!(v.det.is_none());

    let generated = generate(&robot, &ItemHeader::public(&robot.name), &options);
    let s = stats::stats(&robot, &model, &dets, &generated, 1.0);
    let ops = s.det.unwrap();
    assert!(ops.mul >= 2 && ops.add >= 1 && ops.trig == 2, "{ops:?}");
    assert!(stats::to_json(&s)["det"]["total"].is_u64());
}
