//! `symbolic` URDF chains: every length named (`d1`, `a2`…, Craig's numbering), the
//! formulas in those names, and the numbers those names stand for exactly the file's.
//!
//! The UR5's file (`robots/urdf/ur5.urdf`) gives the DH table's determinant up to the
//! sign of `d5` (the file's is −0.09465); the Yaskawa MH5's (ROS-Industrial) a
//! determinant with no decimal in it.

use kinegen_core::chain::urdf::Selection;
use kinegen_core::front::urdf::Urdf;
use kinegen_core::{derive, numeric, Chain};

mod common;

fn chain(file: &str, base: Option<&str>, tip: Option<&str>, symbolic: bool) -> Chain {
    let urdf = Urdf::load_file(&common::robots_dir().join("urdf").join(file)).unwrap();
    let sel = Selection {
        base: base.map(Into::into),
        tip: tip.map(Into::into),
        symbolic,
        ..Selection::default()
    };
    urdf.chain(&sel).unwrap_or_else(|e| panic!("{e}"))
}

fn det_text(chain: &Chain) -> String {
    let d = derive(chain, &Default::default());
    d.det.unwrap().unwrap().text
}

/// FK, J and det J of the named chain (at the parameters' defaults) against the plain
/// one at 200 configurations. Not bit for bit: the plain chain folds products of
/// lengths exactly at expansion time, the named one multiplies them at run time, so
/// they agree to rounding (1e-14 of the arm's reach).
fn same_numbers(named: &Chain, plain: &Chain, reach: f64) {
    let (dn, dp) = (
        derive(named, &Default::default()),
        derive(plain, &Default::default()),
    );
    let outputs = |d: &kinegen_core::Derived| {
        let mut ids = d.model.fk_rows.concat();
        ids.extend(d.model.jacobian.concat());
        ids.push(d.det.as_ref().unwrap().as_ref().unwrap().node);
        ids
    };
    for q in numeric::configurations(7, 200, plain.dof()) {
        let a = dn.model.eval(named, &q, &outputs(&dn));
        let b = dp.model.eval(plain, &q, &outputs(&dp));
        for (k, (x, y)) in a.iter().zip(&b).enumerate() {
            assert!(
                (x - y).abs() <= 1e-14 * reach.powi(3).max(1.0),
                "{}: output {k} at {q:?}: {x} vs {y}",
                plain.name
            );
        }
    }
}

#[test]
fn ur5_from_its_urdf_reads_like_its_dh_table() {
    let named = chain("ur5.urdf", Some("base_link"), Some("tool0"), true);
    let names: Vec<(String, f64)> = named
        .params
        .iter()
        .map(|p| (p.name.clone(), named.eval(&p.value)))
        .collect();
    assert_eq!(
        names,
        [
            ("d1", 0.089159),
            ("a2", -0.425),
            ("a3", -0.39225),
            ("d4", 0.10915),
            ("d5", -0.09465),
            ("d6", 0.0823)
        ]
        .map(|(n, v)| (n.to_string(), v))
    );
    assert_eq!(
        det_text(&named),
        "a2*a3*sin(q3)*sin(q5)*(a2*cos(q2) + a3*cos(q2+q3) - d5*sin(q2+q3+q4))"
    );
    let plain = chain("ur5.urdf", Some("base_link"), Some("tool0"), false);
    same_numbers(&named, &plain, 1.0);
    // The lengths are listed with where the file writes them.
    assert!(
        named.summary.iter().any(
            |l| l.starts_with("| d4 | 0.10915 | `wrist_1_joint.origin.z`, ")
                && l.ends_with("ur5.urdf:64 |")
        ),
        "{:#?}",
        named.summary
    );
}

#[test]
fn mh5_det_has_no_decimal() {
    let named = chain("yaskawaMotomanMH5.urdf", None, None, true);
    let det = det_text(&named);
    assert!(!det.chars().any(|c| c == '.'), "{det}");
    assert!(det.starts_with("a2*sin(q5)*("), "{det}");
    let plain = chain("yaskawaMotomanMH5.urdf", None, None, false);
    same_numbers(&named, &plain, 1.0);
}

/// A name the user gave is kept; the other lengths are named around it.
#[test]
fn given_names_are_kept() {
    let urdf = Urdf::load_file(&common::robots_dir().join("urdf").join("ur5.urdf")).unwrap();
    let sel = Selection {
        base: Some("base_link".into()),
        tip: Some("tool0".into()),
        params: vec![("upper_arm".into(), "elbow_joint.origin.x".into())],
        symbolic: true,
        ..Selection::default()
    };
    let c = urdf.chain(&sel).unwrap();
    let names: Vec<&str> = c.params.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["upper_arm", "d1", "a3", "d4", "d5", "d6"]);
}
