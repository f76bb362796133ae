//! Inputs that broke the front end or the engine, kept as regression tests (issue 8),
//! replayed through the fuzz targets' own oracle (`fuzz/src/check.rs`): load; if it
//! loads, generate without an internal error and without a shadowed local, and compute
//! what the numeric reference computes.

#[allow(dead_code)]
#[path = "../../fuzz/src/check.rs"]
mod check;

use check::Outcome;

const Q: [f64; 8] = [0.3, -1.1, 0.7, 2.0, -0.4, 1.3, 0.2, -2.5];

/// The planar RR table with its two link-length parameters renamed.
fn planar_rr(l1: &str, l2: &str) -> String {
    format!(
        "name = \"planar RR\"\nconvention = \"standard\"\ntask = [\"x\", \"y\"]\n\
         [params]\n{l1} = 1.0\n{l2} = 0.5\n\
         [[joints]]\ntype = \"revolute\"\na = \"{l1}\"\nalpha = 0\nd = 0\n\
         [[joints]]\ntype = \"revolute\"\na = \"{l2}\"\nalpha = 0\nd = 0\n"
    )
}

#[test]
fn the_oracle_accepts_ordinary_names() {
    assert_eq!(check::toml(&planar_rr("L1", "L2"), &Q), Outcome::Checked);
}

#[test]
fn the_shadowing_check_sees_a_rebound_local() {
    let code = "pub fn f(&self, q: &[f64; 2]) -> f64 {\nlet s2 = self.s2;\nlet (s2, _) = sin_cos(q[1]);\ns2\n}\n\
                pub fn g(&self, q: &[f64; 2]) -> f64 {\nlet s2 = self.s2;\nlet (s1, c1) = sin_cos(q[0]);\ns2\n}";
    assert_eq!(
        check::shadowed_locals(code),
        vec![("f".to_string(), "s2".to_string())]
    );
}

/// A parameter named like a generated intermediate (`s2 = sin(q2)`, `c2`, `t1`, `s12`)
/// once gave `let s2 = self.s2; let (s2, _) = sin_cos(q[1]);` — the parameter shadowed
/// by sin(q2), the determinant silently wrong. Such names are now rejected up front, as
/// are the joint rates' (`qd`, `qd2`).
#[test]
fn parameters_named_like_generated_locals() {
    for (l1, l2) in [
        ("s2", "c2"),
        ("t1", "t2"),
        ("s12", "c12"),
        ("c1", "L2"),
        ("s_k1", "L2"),
        ("nc23", "L2"),
        // The joint rates of `jdot_qdot(q, qd)`: `let qd2 = qd[1];`.
        ("qd", "L2"),
        ("qd2", "L2"),
    ] {
        assert_eq!(
            check::toml(&planar_rr(l1, l2), &Q),
            Outcome::Rejected,
            "{l1}"
        );
    }
    // Look-alikes that the code never binds stay usable.
    for (l1, l2) in [
        ("s", "c"),
        ("t", "cx"),
        ("sa1", "c_bar"),
        ("n1", "nt2"),
        ("qdx", "qd_2"),
    ] {
        assert_eq!(
            check::toml(&planar_rr(l1, l2), &Q),
            Outcome::Checked,
            "{l1}"
        );
    }
}

/// A parameter named by a Rust keyword passes validation, and the generated code does
/// not parse: `compile_error!("kinegen internal error: generated code does not parse:
/// expected identifier, found keyword `fn`")` instead of a located front-end error.
#[test]
fn parameters_named_by_rust_keywords() {
    for name in ["fn", "type", "self", "loop", "match"] {
        let outcome = check::toml(&planar_rr(name, "L2"), &Q);
        // Either a front-end error, or correct code (e.g. raw identifiers).
        assert!(
            matches!(outcome, Outcome::Rejected | Outcome::Checked),
            "{name}"
        );
    }
}

/// From the engine target (fuzz/src/check.rs compared the determinant with the task rows):
/// a 6-joint arm with five task rows has `jacobian_det` of the full 6×6 Jacobian, and the
/// task Jacobian is the five rows. The UR5 table with such a task replays the shape.
#[test]
fn six_joints_with_five_task_rows() {
    let ur5 = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../robots/ur5.toml"),
    )
    .unwrap();
    let src = ur5.replacen(
        "convention = \"standard\"",
        "convention = \"standard\"\ntask = [\"y\", \"z\", \"rx\", \"ry\", \"rz\"]",
        1,
    );
    assert_eq!(check::toml(&src, &Q), Outcome::Checked);
}
