//! Issue 8: a wrong rewrite rule injected into the e-graph polish is caught by the
//! check against the unsimplified expression; the emitted formulas stay correct.

use kinegen_core::numeric::NumericRobot;
use kinegen_core::simplify::order;
use kinegen_core::{front::toml_file, generate, ItemHeader};

fn load(name: &str) -> (kinegen_core::Robot, kinegen_core::Options) {
    let path = format!("{}/../robots/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    toml_file::load_file(std::path::Path::new(&path)).unwrap()
}

/// Wrong rules that make expressions cheaper — exactly what an extraction prefers.
fn wrong_rules() -> Vec<(String, String)> {
    vec![
        ("(+ ?a ?b)".into(), "?a".into()),
        ("(- ?a (* ?b ?c))".into(), "(- ?a ?b)".into()),
    ]
}

#[test]
fn wrong_rules_are_rejected_and_reported() {
    for name in ["ur5", "puma560", "planar_rrr", "stanford"] {
        let (robot, mut options) = load(name);
        options.extra_rewrites = wrong_rules();
        let chain = robot.chain();
        let model = order::build(&chain, &options);
        assert!(model.polish.rejected > 0, "{name}: {:?}", model.polish);
        let g = generate(&robot.chain(), &ItemHeader::public(&robot.name), &options);
        assert!(
            g.notes.iter().any(|n| n.contains("failed the check")),
            "{name}: {:?}",
            g.notes
        );
        // The model (what is emitted) still equals the numeric reference.
        let num = NumericRobot::new(&robot).unwrap();
        let n = robot.dof();
        for k in 0..20 {
            let q: Vec<f64> = (0..n)
                .map(|i| ((k * 7 + i * 3) as f64 * 0.37).sin() * 2.5)
                .collect();
            let t = num.fk(&q).unwrap();
            let j = num.jacobian(&q).unwrap();
            let fk: Vec<_> = model.fk_rows.iter().flatten().copied().collect();
            let got = model.eval(&chain, &q, &fk);
            for r in 0..3 {
                for c in 0..4 {
                    assert!((got[r * 4 + c] - t[(r, c)]).abs() < 1e-9, "{name} fk");
                }
            }
            let ids: Vec<_> = model.jacobian.iter().flatten().copied().collect();
            let got = model.eval(&chain, &q, &ids);
            for r in 0..6 {
                for c in 0..n {
                    assert!(
                        (got[r * n + c] - j[(r, c)]).abs() < 1e-9,
                        "{name} J[{r}][{c}]"
                    );
                }
            }
        }
    }
}

#[test]
fn the_same_code_without_the_wrong_rules() {
    // Rejected rewrites leave no trace: the code equals the code built without them.
    let (robot, options) = load("ur5");
    let mut wrong = options.clone();
    wrong.extra_rewrites = wrong_rules();
    let header = ItemHeader::public(&robot.name);
    let a = generate(&robot.chain(), &header, &options).pretty();
    let b = generate(&robot.chain(), &header, &wrong).pretty();
    assert_eq!(a, b);
}

#[test]
fn a_malformed_rule_is_reported_not_fatal() {
    let (robot, mut options) = load("planar_rr");
    options.extra_rewrites = vec![("(+ ?a".into(), "?a".into())];
    let g = generate(&robot.chain(), &ItemHeader::public(&robot.name), &options);
    assert!(
        g.notes.iter().any(|n| n.contains("extra rewrite ignored")),
        "{:?}",
        g.notes
    );
}
