//! Joints that turn the other way keep the factorisation: where a URDF joint's axis is
//! −y after one about +y, the tool moves by q2 − q3, and the determinant, its singular
//! factors and the named intermediates read `cos(q2-q3)` (`c2m3`), with no more
//! operations than the same file with every axis turned to its positive sense.
//!
//! The files are ROS-Industrial's FANUC LR Mate 200iB and Yaskawa MH5 (copied unchanged
//! into `robots/urdf/`) and the Kinova-style `kinova_j2s6s.urdf`, whose frames are turned
//! by π instead.

use kinegen_core::chain::urdf::Selection;
use kinegen_core::emit::code::OpCount;
use kinegen_core::front::urdf::Urdf;
use kinegen_core::{derive, generate, numeric, Chain, ItemHeader, Stats};
use nalgebra::Matrix6;

mod common;

fn chain_of(src: &str, label: &str, tip: Option<&str>) -> Chain {
    let urdf = Urdf::parse(src, label).unwrap_or_else(|e| panic!("{e}"));
    let sel = Selection {
        tip: tip.map(str::to_string),
        ..Selection::default()
    };
    urdf.chain(&sel).unwrap_or_else(|e| panic!("{e}"))
}

fn file(name: &str) -> String {
    std::fs::read_to_string(common::robots_dir().join("urdf").join(name)).unwrap()
}

fn stats(chain: &Chain) -> Stats {
    generate(chain, &ItemHeader::public("Robot"), &Default::default()).stats
}

/// The same file with every axis along −x, −y or −z turned to its positive sense.
fn positive_axes(src: &str) -> String {
    src.replace(r#"xyz="0 -1 0""#, r#"xyz="0 1 0""#)
        .replace(r#"xyz="-1 0 0""#, r#"xyz="1 0 0""#)
        .replace(r#"xyz="0 0 -1""#, r#"xyz="0 0 1""#)
}

/// The determinant's text, and its closed form's value against the determinant of the
/// engine's own Jacobian at 100 configurations (relative to the largest |det| seen);
/// the Jacobian of every URDF file is checked against a numeric evaluator in
/// `robots/tests/urdf_generated.rs`.
fn det_text_checked(chain: &Chain) -> String {
    let derived = derive(chain, &Default::default());
    let det = derived.det.as_ref().unwrap().as_ref().unwrap();
    let values: Vec<(f64, f64)> = numeric::configurations(29, 100, chain.dof())
        .iter()
        .map(|q| {
            let engine = derived.model.eval(chain, q, &[det.node])[0];
            let j = derived
                .model
                .eval(chain, q, &derived.model.jacobian.concat());
            (engine, Matrix6::from_row_slice(&j).determinant())
        })
        .collect();
    let scale = values.iter().map(|(_, r)| r.abs()).fold(0.0, f64::max);
    for (engine, reference) in values {
        assert!(
            (engine - reference).abs() <= 1e-12 * scale,
            "{}: det {engine} vs det of J {reference}",
            chain.name
        );
    }
    det.text.clone()
}

/// `add+mul (neg)` of one output.
fn counts(o: &OpCount) -> String {
    format!("{} ({} neg)", o.add + o.mul + o.div, o.neg)
}

#[test]
fn urdf_joints_against_their_axes_read_as_angle_differences() {
    let mut table = String::from("arm | fk | jacobian | det | det J\n");
    for (name, tip, factor) in [
        (
            "fanucLRMate200ib.urdf",
            Some("tool0"),
            "30 + 50*sin(q2) + 58*cos(q2-q3) + 15*sin(q2-q3)",
        ),
        (
            "yaskawaMotomanMH5.urdf",
            None,
            "sin(q2) + 3050*cos(q2-q3) + 399*sin(q2-q3)",
        ),
        ("kinova_j2s6s.urdf", None, "8200*sin(q2) - 6221*sin(q2-q3)"),
    ] {
        let src = file(name);
        let chain = chain_of(&src, name, tip);
        let text = det_text_checked(&chain);
        assert!(text.contains(factor), "{name}: det J = {text}");
        assert!(!text.contains("q2+q3"), "{name}: det J = {text}");
        let ours = stats(&chain);
        let row = |label: &str, s: &Stats, det: &str| {
            format!(
                "{label} | {} | {} | {} | {det}\n",
                counts(&s.fk),
                counts(&s.jacobian),
                counts(s.det.as_ref().unwrap())
            )
        };
        table.push_str(&row(name, &ours, &text));
        // The Kinova file turns its frames by π instead: it has no twin by axis signs.
        if src == positive_axes(&src) {
            continue;
        }
        // The same arm with every axis turned positive: the same adds and
        // multiplications (negations may differ: the twin is another function of q).
        let turned = chain_of(&positive_axes(&src), name, tip);
        let twin = stats(&turned);
        let twin_text = det_text_checked(&turned);
        table.push_str(&row(&format!("{name}, axes positive"), &twin, &twin_text));
        let work = |o: &OpCount| o.add + o.mul + o.div;
        for (what, a, b) in [
            ("fk", &ours.fk, &twin.fk),
            ("jacobian", &ours.jacobian, &twin.jacobian),
            (
                "det",
                ours.det.as_ref().unwrap(),
                twin.det.as_ref().unwrap(),
            ),
        ] {
            assert!(
                work(a) <= work(b),
                "{name}: {what} {a:?} against {b:?} with positive axes"
            );
        }
    }
    insta::assert_snapshot!("reversed_axes_counts", table);
}

#[test]
fn generated_code_names_the_differences() {
    let chain = chain_of(
        &file("fanucLRMate200ib.urdf"),
        "fanucLRMate200ib.urdf",
        Some("tool0"),
    );
    let code = generate(&chain, &ItemHeader::public("LrMate"), &Default::default())
        .tokens
        .to_string();
    for name in ["s2m3", "c2m3"] {
        assert!(code.contains(name), "no `{name}` in the generated code");
    }
    assert!(!code.contains("c23 "), "a sum where the joints turn apart");
}
