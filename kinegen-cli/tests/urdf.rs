//! The `kinegen` command on URDF files: every command takes one, `--base`/`--tip`/
//! `--snap` choose the chain, `show --what model` reports the snaps, and bad input exits
//! 2 with the file's line.

use std::path::PathBuf;

use assert_cmd::Command;
use serde_json::Value;

mod common;
use common::solutions_and_flags;

fn kinegen() -> Command {
    Command::cargo_bin("kinegen").unwrap()
}

fn urdf(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../robots/urdf")
        .join(name)
        .display()
        .to_string()
}

fn stdout(args: &[&str]) -> String {
    let out = kinegen().args(args).assert().success();
    String::from_utf8(out.get_output().stdout.clone()).unwrap()
}

/// Exit 2, nothing on stdout, `kinegen: error:` lines, no panic.
fn fails(args: &[&str]) -> String {
    let out = kinegen().args(args).assert().code(2).stdout("");
    let err = String::from_utf8(out.get_output().stderr.clone()).unwrap();
    assert!(!err.contains("panicked"), "{err}");
    assert!(err.starts_with("kinegen: error: "), "{err}");
    err
}

/// A directory of a test's temporary files (not in the repository), removed with them
/// when the test ends, passed or failed.
struct TempDir(std::path::PathBuf);

impl TempDir {
    fn new(test: &str) -> TempDir {
        let dir =
            std::env::temp_dir().join(format!("kinegen-cli-urdf-{}-{test}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        TempDir(dir)
    }

    /// `src` written to the file `name` in the directory.
    fn file(&self, name: &str, src: &str) -> String {
        let p = self.0.join(name);
        std::fs::write(&p, src).unwrap();
        p.display().to_string()
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

#[test]
fn every_command_takes_a_urdf() {
    let ur5 = urdf("ur5.urdf");
    let chain = ["--base", "base_link", "--tip", "tool0"];
    let q = "0.1,-0.7,1.3,0.4,-2.2,0.9";
    let show = stdout(&[&["show", &ur5][..], &chain, &["--what", "det"]].concat());
    assert!(
        show.contains("a2*a3*sin(q3)*sin(q5)") || show.contains("sin(q3)*sin(q5)"),
        "{show}"
    );
    let rust = stdout(&[&["rust", &ur5][..], &chain].concat());
    assert!(rust.contains("pub struct Ur5"), "{rust}");
    let stats = stdout(&[&["stats", &ur5][..], &chain].concat());
    assert!(stats.contains("jacobian"), "{stats}");
    // Same JSON fields as a TOML robot; the shipped ur5_urdf (UR5 by its URDF) is the
    // DH UR5 turned by π about z: the same det J.
    let json = |args: &[&str]| -> Value {
        serde_json::from_str(&stdout(&[args, &["--q", q, "--json"]].concat())).unwrap()
    };
    let from_urdf = json(&[&["eval", &ur5][..], &chain].concat());
    let from_dh = json(&["eval", "ur5"]);
    let keys = |v: &Value| v.as_object().unwrap().keys().cloned().collect::<Vec<_>>();
    assert_eq!(keys(&from_urdf), keys(&from_dh));
    let shipped = json(&["eval", "ur5_urdf"]);
    let (a, b) = (
        shipped["det"].as_f64().unwrap(),
        from_dh["det"].as_f64().unwrap(),
    );
    assert!((a - b).abs() < 1e-12, "{a} vs {b}");
}

#[test]
fn show_model_lists_the_chain_and_every_snap() {
    let ur5 = urdf("ur5.urdf");
    let model = stdout(&["show", &ur5, "--tip", "tool0", "--what", "model"]);
    assert!(model.contains("link 2: Rx(pi/2) Rz(q2)"), "{model}");
    assert!(
        model.contains("`shoulder_lift_joint.origin.roll`: `1.570796327` → `pi/2` (δ = 2.1e-10)"),
        "{model}"
    );
    assert!(
        model.contains("together (first order): tool position within"),
        "{model}"
    );
    // --snap 0: every decimal as written, nothing snapped.
    let literal = stdout(&[
        "show", &ur5, "--tip", "tool0", "--snap", "0", "--what", "model",
    ]);
    assert!(
        literal.contains("link 2: Rx(1.570796327) Rz(q2)"),
        "{literal}"
    );
    assert!(
        literal.contains("none: the chain is the description as written"),
        "{literal}"
    );
    insta::assert_snapshot!(
        "show_model_kinova_urdf",
        stdout(&["show", &urdf("kinova_j2s6s.urdf"), "--what", "model"])
            .replace(&urdf(""), "robots/urdf/")
    );
    // A DH robot has no snaps.
    assert!(stdout(&["show", "ur5", "--what", "model"]).contains("none:"));
}

/// The Panda's file ends in a hand with a TCP frame and two prismatic fingers: the arm
/// ends at the TCP without `--tip`, and its closed-form IK answers a pose of that frame.
#[test]
fn the_pandas_tip_is_its_hand_tcp() {
    let panda = urdf("panda.urdf");
    let model = stdout(&["show", &panda, "--what", "model"]);
    assert!(
        model
            .lines()
            .next()
            .unwrap()
            .ends_with("`panda_link0` → `panda_hand_tcp`"),
        "{model}"
    );
    let q = "0.3,-0.5,0.2,-2.0,0.4,1.6,0.7";
    let t: Value = serde_json::from_str(&stdout(&["eval", &panda, "--q", q, "--json"])).unwrap();
    let pose: Vec<String> = t["fk"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|r| r.as_array().unwrap().iter().map(|x| x.to_string()))
        .collect();
    let out: Value = serde_json::from_str(&stdout(&[
        "ik",
        &panda,
        "--pose",
        &pose.join(","),
        "--locked",
        "0.7",
        "--json",
    ]))
    .unwrap();
    let q: Vec<f64> = q.split(',').map(|x| x.parse().unwrap()).collect();
    let (solutions, exact) = solutions_and_flags(&out);
    let found = solutions
        .iter()
        .zip(exact)
        .any(|(x, e)| e && x.iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-9));
    assert!(found, "{out}");
}

#[test]
fn several_leaves_and_unknown_links_exit_2_with_the_line() {
    let ur5 = urdf("ur5.urdf");
    let e = fails(&["show", &ur5]);
    assert!(
        e.contains("ur5.urdf:10: --tip: the tree has 3 leaves, 2 of them after a moving joint; name the tip link: `tool0` and `ee_link`"),
        "{e}"
    );
    let e = fails(&["eval", &ur5, "--tip", "tool1", "--q", "0,0,0,0,0,0"]);
    assert!(
        e.contains("ur5.urdf:10: --tip: no link `tool1` (the tip)"),
        "{e}"
    );
    let e = fails(&["stats", &ur5, "--base", "tool0", "--tip", "base_link"]);
    assert!(
        e.contains("--tip: tip link `base_link` is not below base link `tool0`"),
        "{e}"
    );
    let e = fails(&["show", "ur5", "--tip", "tool0"]);
    assert!(
        e.contains("--base, --tip, --snap, --symbolic and --task select the chain of a .urdf file"),
        "{e}"
    );
    let e = fails(&["show", "ur5", "--symbolic"]);
    assert!(e.contains("`params = \"auto\"` for --symbolic"), "{e}");
}

/// `--symbolic`: the UR5's det in the data sheet's names, each listed with its line.
#[test]
fn symbolic_names_every_length() {
    let ur5 = urdf("ur5.urdf");
    let show = |what: &str| {
        stdout(&[
            "show",
            &ur5,
            "--base",
            "base_link",
            "--tip",
            "tool0",
            "--symbolic",
            "--what",
            what,
        ])
    };
    let det = show("det");
    assert!(
        det.contains(
            "det J = a2*a3*sin(q3)*sin(q5)*(a2*cos(q2) + a3*cos(q2+q3) - d5*sin(q2+q3+q4))"
        ),
        "{det}"
    );
    let model = show("model");
    assert!(
        model.contains("| a2 | -0.425 | `elbow_joint.origin.x`, ")
            && model.contains("ur5.urdf:57 |"),
        "{model}"
    );
    // A TOML file says it with `params = "auto"`.
    let dir = TempDir::new("symbolic");
    let toml = dir.file(
        "mh5.toml",
        &format!(
            "urdf = {:?}\nparams = \"auto\"\n",
            urdf("yaskawaMotomanMH5.urdf")
        ),
    );
    let det = stdout(&["show", &toml, "--what", "det"]);
    assert!(det.contains("det J = a2*sin(q5)*("), "{det}");
}

#[test]
fn bad_files_exit_2_with_the_line() {
    let dir = TempDir::new("bad_files");
    let e = fails(&["show", "/nonexistent/arm.urdf"]);
    assert!(
        e.contains("/nonexistent/arm.urdf: cannot read the file"),
        "{e}"
    );
    let xacro = dir.file(
        "arm.urdf",
        "<robot name=\"r\">\n<xacro:include filename=\"x.xacro\"/>\n</robot>\n",
    );
    let e = fails(&["rust", &xacro]);
    assert!(
        e.contains("arm.urdf:2: this is an unexpanded xacro file: run `xacro"),
        "{e}"
    );
    let not_xml = dir.file(
        "broken.urdf",
        "<robot name=\"r\">\n<link name=\"a\">\n</robot>\n",
    );
    let e = fails(&["show", &not_xml]);
    assert!(e.contains("broken.urdf:3: not an XML file"), "{e}");
    let floating = dir.file(
        "floating.urdf",
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/>\n\
         <joint name=\"free\" type=\"floating\"><parent link=\"a\"/><child link=\"b\"/></joint>\n</robot>\n",
    );
    let e = fails(&["show", &floating]);
    assert!(
        e.contains("floating.urdf:2: free: joint `free` on the chain `a` → `b` is floating"),
        "{e}"
    );
}
