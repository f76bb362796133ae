//! `kinegen report`: the page of the UR5, the PUMA 560 and a URDF arm parses as HTML5
//! with zero errors, holds every formula `show` prints (each as MathML beside its text),
//! every picture draws something, nothing is fetched or scripted; bad input exits 2
//! and leaves no file.

use std::cell::RefCell;
use std::path::{Path, PathBuf};

use assert_cmd::Command;
use html5ever::tendril::TendrilSink;
use html5ever::tokenizer::TokenizerOpts;
use html5ever::tree_builder::TreeBuilderOpts;
use html5ever::{parse_document, ParseOpts};
use markup5ever_rcdom::{Handle, NodeData, RcDom};

fn kinegen() -> Command {
    Command::cargo_bin("kinegen").unwrap()
}

fn repo(rel: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join(rel)
        .display()
        .to_string()
}

/// A fresh directory for one test's files.
fn scratch(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("report-{name}"));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The robots the page is checked on: two shipped tables and a URDF whose third joint
/// turns the other way.
fn robots() -> Vec<(&'static str, Vec<String>)> {
    vec![
        ("ur5", vec!["ur5".into()]),
        ("puma560", vec!["puma560".into()]),
        (
            "fanuc",
            vec![
                repo("robots/urdf/fanucLRMate200ib.urdf"),
                "--tip".into(),
                "tool0".into(),
            ],
        ),
    ]
}

fn report(name: &str, robot: &[String]) -> String {
    let out = scratch(name).join(format!("{name}.html"));
    kinegen()
        .arg("report")
        .args(robot)
        .arg("-o")
        .arg(&out)
        .assert()
        .success();
    std::fs::read_to_string(&out).unwrap()
}

/// Parse with every parse error reported (not only the first of a kind).
fn parse(html: &str) -> RcDom {
    let opts = ParseOpts {
        tokenizer: TokenizerOpts {
            exact_errors: true,
            ..Default::default()
        },
        tree_builder: TreeBuilderOpts {
            exact_errors: true,
            ..Default::default()
        },
    };
    parse_document(RcDom::default(), opts)
        .from_utf8()
        .read_from(&mut html.as_bytes())
        .unwrap()
}

/// Every element under `h` (itself included), depth first.
fn elements(h: &Handle, out: &mut Vec<Handle>) {
    if let NodeData::Element { .. } = h.data {
        out.push(h.clone());
    }
    for c in h.children.borrow().iter() {
        elements(c, out);
    }
}

fn tag(h: &Handle) -> String {
    match &h.data {
        NodeData::Element { name, .. } => name.local.to_string(),
        _ => String::new(),
    }
}

fn attr(h: &Handle, key: &str) -> Option<String> {
    match &h.data {
        NodeData::Element { attrs, .. } => attrs
            .borrow()
            .iter()
            .find(|a| &*a.name.local == key)
            .map(|a| a.value.to_string()),
        _ => None,
    }
}

fn text(h: &Handle) -> String {
    let s = RefCell::new(String::new());
    fn walk(h: &Handle, s: &RefCell<String>) {
        if let NodeData::Text { contents } = &h.data {
            s.borrow_mut().push_str(&contents.borrow());
        }
        for c in h.children.borrow().iter() {
            walk(c, s);
        }
    }
    walk(h, &s);
    s.into_inner()
}

/// `show`'s formula lines (`T[0][3] = …`, `c23 = cos(q2 + q3) = …`, `det J = …`),
/// without headers and the singularity list (printed with its meaning on the page).
fn show_lines(robot: &[String]) -> Vec<String> {
    let mut lines = Vec::new();
    for what in ["fk", "jacobian", "det"] {
        let out = kinegen()
            .arg("show")
            .args(robot)
            .args(["--what", what])
            .assert()
            .success();
        let s = String::from_utf8(out.get_output().stdout.clone()).unwrap();
        for l in s.lines().skip(1) {
            let l = l.trim();
            if l.contains(" = ") && !l.starts_with("==") && !l.starts_with("parameters:") {
                lines.push(l.to_string());
            }
        }
    }
    lines
}

#[test]
fn pages_are_valid_html5_with_every_formula_as_mathml_and_pictures_drawn() {
    for (name, robot) in robots() {
        let html = report(name, &robot);
        let dom = parse(&html);
        let errors = dom.errors.clone();
        assert!(errors.is_empty(), "{name}: HTML parse errors: {errors:?}");
        let mut all = Vec::new();
        elements(&dom.document, &mut all);

        // Self-contained: nothing scripted, nothing fetched.
        for e in &all {
            let n = tag(e);
            assert!(
                !["script", "iframe", "img", "link", "object"].contains(&n.as_str()),
                "{name}: <{n}>"
            );
            assert!(attr(e, "src").is_none(), "{name}: <{n} src>");
            if let Some(h) = attr(e, "href") {
                assert!(h.starts_with('#'), "{name}: href {h}");
            }
        }

        // Every formula of `show` is on the page as text, and each text line has its
        // MathML twin just before it.
        let texts: Vec<String> = all
            .iter()
            .filter(|e| attr(e, "class").as_deref() == Some("text"))
            .map(text)
            .collect();
        let eqs: Vec<&Handle> = all
            .iter()
            .filter(|e| attr(e, "class").as_deref() == Some("eq"))
            .collect();
        assert_eq!(eqs.len(), texts.len(), "{name}");
        let lines = show_lines(&robot);
        assert!(lines.len() > 20, "{name}: {lines:?}");
        for l in &lines {
            assert!(texts.contains(l), "{name}: `{l}` is not on the page");
        }
        for eq in &eqs {
            let maths: Vec<Handle> = eq
                .children
                .borrow()
                .iter()
                .filter(|c| tag(c) == "math")
                .cloned()
                .collect();
            assert_eq!(maths.len(), 1, "{name}: one <math> per formula");
            let mut inside = Vec::new();
            elements(&maths[0], &mut inside);
            // Rendered MathML, not the Rust syntax: tokens, no `*`, no `self.`.
            assert!(
                inside
                    .iter()
                    .any(|e| ["mi", "mn"].contains(&tag(e).as_str())),
                "{name}"
            );
            let t = text(&maths[0]);
            assert!(!t.contains('*') && !t.contains("self."), "{name}: {t}");
        }
        // The singular factors, each `= 0`, with the joints they involve.
        let factors = texts
            .iter()
            .filter(|t| t.contains(" = 0") && t.contains("depends on"))
            .count();
        assert!(factors >= 2, "{name}: {factors} singular factors");
        // The second order: J̇q̇, J̇ and the Hessian, each entry named as FORMULAS names it.
        for prefix in ["Jdot_qdot[", "Jdot[", "H["] {
            assert!(
                texts.iter().any(|t| t.starts_with(prefix)),
                "{name}: {prefix}"
            );
        }

        // Four pictures, each drawing: the map's cells, the stick figures' lines, the
        // trajectory's curves.
        let svgs: Vec<&Handle> = all.iter().filter(|e| tag(e) == "svg").collect();
        assert_eq!(
            svgs.len(),
            4,
            "{name}: singularity map, two views, trajectory"
        );
        for s in &svgs {
            let mut inside = Vec::new();
            elements(s, &mut inside);
            let drawn = inside
                .iter()
                .filter(|e| {
                    ["rect", "polyline", "circle", "line", "path"].contains(&tag(e).as_str())
                })
                .count();
            assert!(
                drawn >= 10,
                "{name}: an <svg> with {drawn} drawing elements"
            );
        }
        // The IK table lists solutions that reach the pose.
        assert!(html.contains("max |fk(q) − pose|"), "{name}");
    }
}

/// Every shipped robot — planar arms, a SCARA, 7-joint arms, robots without a square
/// Jacobian — gets a page that parses without an error, whose pictures draw (or a note
/// says why there is none), and that has its closed forms as MathML.
#[test]
fn every_shipped_robot_has_a_valid_page() {
    for robot in kinegen_cli::robots::names() {
        let html = report(&format!("all-{robot}"), &[robot.to_string()]);
        let dom = parse(&html);
        assert!(dom.errors.is_empty(), "{robot}: {:?}", dom.errors);
        let mut all = Vec::new();
        elements(&dom.document, &mut all);
        assert!(
            all.iter().filter(|e| tag(e) == "math").count() > 10,
            "{robot}"
        );
        for s in all.iter().filter(|e| tag(e) == "svg") {
            let mut inside = Vec::new();
            elements(s, &mut inside);
            let drawn = inside
                .iter()
                .filter(|e| ["rect", "polyline", "circle", "line"].contains(&tag(e).as_str()))
                .count();
            assert!(
                drawn >= 10,
                "{robot}: an <svg> with {drawn} drawing elements"
            );
        }
    }
}

/// Exit 2 with the reason on stderr, nothing on stdout.
fn fails(args: &[&str]) -> String {
    let out = kinegen().args(args).assert().code(2).stdout("");
    String::from_utf8(out.get_output().stderr.clone()).unwrap()
}

fn files(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn an_unwritable_path_exits_2_and_leaves_no_file() {
    let dir = scratch("unwritable");
    // A directory that does not exist.
    let missing = dir.join("no/such/dir/ur5.html");
    let e = fails(&["report", "ur5", "-o", missing.to_str().unwrap()]);
    assert!(e.contains("cannot write"), "{e}");
    assert!(!missing.exists());
    // A path that is a directory: the page is written beside it first, then the
    // rename fails; the temporary file is gone too.
    let target = dir.join("taken");
    std::fs::create_dir(&target).unwrap();
    let e = fails(&["report", "ur5", "-o", target.to_str().unwrap()]);
    assert!(e.contains("cannot write"), "{e}");
    assert!(target.is_dir());
    assert_eq!(files(&dir), ["taken"]);
    assert!(files(&target).is_empty());
}

#[test]
fn a_robot_that_does_not_load_exits_2_and_writes_nothing() {
    let dir = scratch("bad-robot");
    let out = dir.join("page.html");
    let bad = dir.join("bad.toml");
    std::fs::write(
        &bad,
        "name = \"x\"\nconvention = \"standard\"\n[[joints]]\ntype = \"wobbly\"\n",
    )
    .unwrap();
    let e = fails(&["report", bad.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert!(e.contains("bad.toml:4"), "{e}");
    let e = fails(&["report", "ur7", "-o", out.to_str().unwrap()]);
    assert!(e.contains("unknown robot `ur7`"), "{e}");
    let e = fails(&[
        "report",
        &repo("robots/urdf/fanucLRMate200ib.urdf"),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(e.contains("--tip"), "{e}");
    assert_eq!(files(&dir), ["bad.toml"]);
}

/// The parser above does report errors (the validity check can fail).
#[test]
fn the_validity_check_sees_errors() {
    let page = |body: &str| {
        format!("<!DOCTYPE html><html><head><title>t</title></head><body>{body}</body></html>")
    };
    assert!(!parse(&page("<p>a</b>")).errors.is_empty());
    assert!(parse(&page("<p>a</p>")).errors.is_empty());
}

/// `--reach`: the reachability map's plane through the base on the page — the
/// reachability index and one picture per singular factor, each drawing reachable
/// (coloured) and unreachable (grey) voxels; the page stays valid. A bad spacing exits 2
/// before anything is written.
#[test]
fn the_reachability_map_is_on_the_page_when_asked() {
    let plain = report("no-reach", &["ur5".into()]);
    assert!(
        plain.contains("--reach 0.08"),
        "the page says how to add it"
    );
    let html = report("reach", &["ur5".into(), "--reach".into(), "0.25".into()]);
    let dom = parse(&html);
    assert!(dom.errors.is_empty(), "{:?}", dom.errors);
    let mut all = Vec::new();
    elements(&dom.document, &mut all);
    let section = all
        .iter()
        .find(|e| attr(e, "id").as_deref() == Some("reachability"))
        .expect("a reachability section");
    let mut inside = Vec::new();
    elements(section, &mut inside);
    let svgs: Vec<_> = inside.iter().filter(|e| tag(e) == "svg").collect();
    // The index and the UR5's three joint-dependent factors.
    assert_eq!(svgs.len(), 4, "{}", text(section));
    for s in svgs {
        let mut cells = Vec::new();
        elements(s, &mut cells);
        let fills: Vec<String> = cells
            .iter()
            .filter(|e| tag(e) == "rect")
            .filter_map(|e| attr(e, "fill"))
            .collect();
        assert!(fills.iter().any(|f| f == "#e1e1e1"), "no unreachable voxel");
        assert!(
            fills
                .iter()
                .filter(|f| *f != "#e1e1e1" && *f != "white" && *f != "#fff")
                .count()
                >= 10,
            "too few reachable voxels: {fills:?}"
        );
    }
    let dir = scratch("reach-bad");
    let out = dir.join("ur5.html");
    let e = fails(&["report", "ur5", "--reach", "0", "-o", out.to_str().unwrap()]);
    assert!(e.contains("--reach 0: must be a positive number"), "{e}");
    assert!(files(&dir).is_empty());
}
