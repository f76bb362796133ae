//! The `FORMULAS` constant: every output of `fk`, `jacobian` and the determinant is
//! there once, with text and LaTeX, and agrees with the other constants.

use kinegen_robots::{PlanarRr, Ur5};

fn of<'a>(all: &'a [kinegen::Formula], function: &str) -> Vec<&'a kinegen::Formula> {
    all.iter().filter(|f| f.function == function).collect()
}

#[test]
fn every_output_has_a_formula() {
    let f = Ur5::FORMULAS;
    for (function, prefix, rows, cols) in [("fk", "T", 3, 4), ("jacobian", "J", 6, 6)] {
        let entries = of(f, function);
        for r in 0..rows {
            for c in 0..cols {
                let name = format!("{prefix}[{r}][{c}]");
                let hits: Vec<_> = entries.iter().filter(|e| e.name == name).collect();
                assert_eq!(hits.len(), 1, "{function} {name}");
                assert!(!hits[0].text.is_empty() && !hits[0].latex.is_empty());
            }
        }
        // Intermediates are defined before use and are named like the code's (`nc23`
        // is −c23).
        for e in entries.iter().filter(|e| !e.name.contains('[')) {
            assert!(
                e.name.trim_start_matches('n').starts_with(['t', 's', 'c']),
                "{}",
                e.name
            );
        }
    }
    // Angular rows of joint 1 are the base z axis.
    let j = of(f, "jacobian");
    let get = |n: &str| j.iter().find(|e| e.name == n).unwrap().text;
    assert_eq!(get("J[5][0]"), "1.0");
    assert_eq!(get("J[3][0]"), "0.0");
}

#[test]
fn determinant_and_factors_match_det_and_singularities() {
    for (all, det, sing) in [
        (PlanarRr::FORMULAS, PlanarRr::DET, PlanarRr::SINGULARITIES),
        (Ur5::FORMULAS, Ur5::DET, Ur5::SINGULARITIES),
    ] {
        let d = of(all, "jacobian_det");
        assert_eq!(d.len(), 1);
        assert_eq!(d[0].text, det);
        let factors = of(all, "singular_factors");
        assert_eq!(factors.len(), sing.len());
        for (f, s) in factors.iter().zip(sing) {
            assert_eq!(format!("{} = 0", f.text), s.condition);
            assert_eq!(format!("{} = 0", f.latex), s.latex);
        }
    }
    assert_eq!(
        of(PlanarRr::FORMULAS, "jacobian_det")[0].text,
        "L1*L2*sin(q2)"
    );
}

#[test]
fn latex_uses_textbook_subscripts() {
    let t = of(PlanarRr::FORMULAS, "fk");
    let x = t.iter().find(|e| e.name == "T[0][3]").unwrap();
    assert!(x.latex.contains("c_{1}"), "{}", x.latex);
    assert!(!x.latex.contains('*'), "{}", x.latex);
}
