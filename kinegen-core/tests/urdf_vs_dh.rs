//! The same robot from its URDF and from its DH table gives the same kinematics: the UR5
//! (`robots/urdf/ur5.urdf`, base turned by π about z from the DH frame) and the Panda
//! (`robots/urdf/panda.urdf`, origins that reproduce Craig's modified DH table) against
//! `robots/ur5.toml` and `robots/panda.toml` — FK and Jacobian to 1e-12, the UR5's
//! determinant with the same three singular factors, operation counts within 10 %.

use kinegen_core::chain::urdf::Selection;
use kinegen_core::front::toml_file::load_str;
use kinegen_core::front::urdf::Urdf;
use kinegen_core::{derive, generate, numeric, Chain, Derived, ItemHeader, Stats};

mod common;

fn urdf_chain(file: &str, base: &str, tip: &str, params: &[(&str, &str)]) -> Chain {
    let urdf = Urdf::load_file(&common::robots_dir().join("urdf").join(file)).unwrap();
    let sel = Selection {
        base: Some(base.into()),
        tip: Some(tip.into()),
        params: params
            .iter()
            .map(|(n, e)| (n.to_string(), e.to_string()))
            .collect(),
        ..Selection::default()
    };
    urdf.chain(&sel).unwrap_or_else(|e| panic!("{e}"))
}

/// The DH robot of `robots/<file>`, with `extra` TOML appended (a base frame).
fn dh_chain(file: &str, extra: &str) -> Chain {
    let src = std::fs::read_to_string(common::robots_dir().join(file)).unwrap();
    let (robot, _) = load_str(&format!("{src}\n{extra}"), file).unwrap();
    robot.chain()
}

fn stats(chain: &Chain) -> Stats {
    generate(chain, &ItemHeader::public("Robot"), &Default::default()).stats
}

/// FK and Jacobian of the two at 200 configurations, 1e-12.
fn same_kinematics(a: (&Chain, &Derived), b: (&Chain, &Derived), dof: usize) {
    for q in numeric::configurations(1414, 200, dof) {
        let fa = a.1.model.eval(a.0, &q, &a.1.model.fk_rows.concat());
        let fb = b.1.model.eval(b.0, &q, &b.1.model.fk_rows.concat());
        for (x, y) in fa.iter().zip(&fb) {
            assert!((x - y).abs() < 1e-12, "fk at {q:?}: {x} vs {y}");
        }
        let ja = a.1.model.eval(a.0, &q, &a.1.model.jacobian.concat());
        let jb = b.1.model.eval(b.0, &q, &b.1.model.jacobian.concat());
        for (x, y) in ja.iter().zip(&jb) {
            assert!((x - y).abs() < 1e-12, "J at {q:?}: {x} vs {y}");
        }
    }
}

/// Operation counts within 10 % (`fk` + `jacobian`, each).
fn counts_close(name: &str, urdf: &Stats, dh: &Stats) {
    eprintln!(
        "{name}: fk {} (URDF) vs {} (DH), jacobian {} vs {}, det {:?} vs {:?}",
        urdf.fk.total(),
        dh.fk.total(),
        urdf.jacobian.total(),
        dh.jacobian.total(),
        urdf.det.map(|d| d.total()),
        dh.det.map(|d| d.total()),
    );
    for (what, u, d) in [
        ("fk", urdf.fk.total(), dh.fk.total()),
        ("jacobian", urdf.jacobian.total(), dh.jacobian.total()),
    ] {
        assert!(
            (u as f64) <= 1.1 * d as f64 && (d as f64) <= 1.1 * u as f64,
            "{name} {what}: {u} operations from the URDF, {d} from the DH table"
        );
    }
}

const UR5_PARAMS: &[(&str, &str)] = &[
    ("d1", "shoulder_pan_joint.origin.z"),
    ("a2", "elbow_joint.origin.x"),
    ("a3", "wrist_1_joint.origin.x"),
    ("d4", "wrist_1_joint.origin.z"),
    ("d5", "wrist_2_joint.origin.y"),
    ("d6", "wrist_3_joint.origin.y"),
];

#[test]
fn ur5_from_urdf_is_ur5_from_dh() {
    let urdf = urdf_chain("ur5.urdf", "base_link", "tool0", UR5_PARAMS);
    assert_eq!(urdf.dof(), 6);
    // The DH frame 0 is base_link turned by π about z.
    let dh = dh_chain("ur5.toml", "[base]\nrpy = [0, 0, \"pi\"]\n");
    let (du, dd) = (
        derive(&urdf, &Default::default()),
        derive(&dh, &Default::default()),
    );
    same_kinematics((&urdf, &du), (&dh, &dd), 6);
    // The snaps: the π/2 and π written as decimals, the 1e-11 z noise.
    assert!(urdf.snaps.iter().any(|s| s.written == "1.570796327"));
    assert!(urdf.snaps.iter().any(|s| s.written == "-1.9413e-11"));

    let (det_u, det_d) = (
        du.det.as_ref().unwrap().as_ref().unwrap(),
        dd.det.as_ref().unwrap().as_ref().unwrap(),
    );
    eprintln!("UR5 det J from the URDF: {}", det_u.text);
    eprintln!("UR5 det J from the DH table: {}", det_d.text);
    let moving = |d: &kinegen_core::kinematics::det::closed_form::DetModel| {
        d.factors
            .iter()
            .filter(|f| !f.joints.is_empty())
            .map(|f| f.node)
            .collect::<Vec<_>>()
    };
    let (fu, fd) = (moving(det_u), moving(det_d));
    assert_eq!(fu.len(), 3, "{}", det_u.text);
    assert_eq!(fd.len(), 3, "{}", det_d.text);
    // Each URDF factor is a constant multiple of one DH factor (names and signs of the
    // parameters differ: the URDF's d5 is the y of wrist_2's origin, −d5 of the table).
    let qs = numeric::configurations(5, 20, 6);
    let values = |chain: &Chain, d: &Derived, ids: &[_]| -> Vec<Vec<f64>> {
        qs.iter().map(|q| d.model.eval(chain, q, ids)).collect()
    };
    let (vu, vd) = (values(&urdf, &du, &fu), values(&dh, &dd, &fd));
    for i in 0..3 {
        let matched = (0..3).any(|k| {
            let ratio = vu[0][i] / vd[0][k];
            vu.iter()
                .zip(&vd)
                .all(|(u, d)| (u[i] - ratio * d[k]).abs() < 1e-12 * (1.0 + u[i].abs()))
        });
        assert!(matched, "URDF factor {i} of {} has no DH twin", det_u.text);
    }
    counts_close("UR5", &stats(&urdf), &stats(&dh));
    // Every snap is in the generated type's rustdoc.
    let code = generate(&urdf, &ItemHeader::public("Ur5"), &Default::default()).pretty();
    assert!(code.contains("Snapped to exact values (12)"), "{code}");
    assert!(code.contains("`wrist_2_joint.origin.z`: `-1.9413e-11` → `0`"));
}

#[test]
fn panda_from_urdf_is_panda_from_dh() {
    let params = [
        ("d1", "panda_joint1.origin.z"),
        ("a4", "panda_joint4.origin.x"),
        ("a5", "panda_joint5.origin.x"),
        ("a7", "panda_joint7.origin.x"),
    ];
    let urdf = urdf_chain("panda.urdf", "panda_link0", "panda_hand_tcp", &params);
    assert_eq!(urdf.dof(), 7);
    let dh = dh_chain("panda.toml", "");
    let (du, dd) = (
        derive(&urdf, &Default::default()),
        derive(&dh, &Default::default()),
    );
    same_kinematics((&urdf, &du), (&dh, &dd), 7);
    counts_close("Panda", &stats(&urdf), &stats(&dh));
}
