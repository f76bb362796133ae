//! The determinant's consumers (`show --what det|singularities`, `eval`'s `det_task`,
//! `stats`' `det`) before the engine provides determinants: fed a hand-built
//! determinant of the planar RR's task Jacobian (`Jt00·Jt11 − Jt01·Jt10` in the model's
//! graph), they show, evaluate and count it.

use kinegen_cli::det_hook::{Determinant, Determinants, Factor};
use kinegen_cli::{eval, formulas, robots, stats, What};
use kinegen_core::kinematics::second_order::second_order;
use kinegen_core::simplify::order;
use kinegen_core::{generate, numeric, Derived, ItemHeader};

#[test]
fn a_determinant_from_the_hook_is_shown_evaluated_and_counted() {
    let (chain, options) = robots::load("planar_rr", &Default::default()).unwrap();
    // The model without the engine's own determinant, so the hand-built one is new.
    let mut model = order::build(&chain, &options);
    let t = model.task.clone();
    let g = &mut model.sym.graph;
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
                meaning: "axes 1, 2 and 3 are parallel and in one plane".into(),
            }],
        }),
        missing: "not available".into(),
    };
    let shown = formulas::show(&chain, &model, &dets, What::Det, false);
    assert!(shown.contains("det Jt = L1*L2*sin(q2)"), "{shown}");
    let sing = formulas::show(&chain, &model, &dets, What::Singularities, true);
    assert!(sing.contains(r"s_{2} &= 0"), "{sing}");

    let q = [0.3, -1.1];
    let second = second_order(&chain, &mut model);
    let derived = Derived {
        model,
        det: None,
        second,
        det_gradient: None,
        ik: Err("not derived in this test".into()),
        times: Default::default(),
    };
    let v = eval::values(&chain, &derived, &dets, &q, None);
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../robots/planar_rr.toml");
    let (robot, _) = kinegen_core::front::toml_file::load_file(path.as_ref()).unwrap();
    let reference = numeric::det(&numeric::task_jacobian(&robot, &q).unwrap()).unwrap();
    let got = v.det_task.unwrap();
    assert!((got - reference).abs() < 1e-12, "{got} vs {reference}");
    assert!((got - (-1.1f64).sin()).abs() < 1e-12);
    assert!(v.det.is_none());

    let generated = generate(&chain, &ItemHeader::public(&chain.name), &options);
    let s = stats::stats(&chain, &derived.model, &dets, &generated, 1.0);
    let ops = s.det.unwrap();
    assert!(ops.mul >= 2 && ops.add >= 1 && ops.trig == 2, "{ops:?}");
    assert!(stats::to_json(&s)["det"]["total"].is_u64());
}
