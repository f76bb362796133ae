//! What the CLI tests share: running the binary and the robot files.
#![allow(dead_code)] // each test file uses a part of it

use std::path::PathBuf;

use assert_cmd::Command;
use serde_json::Value;

/// The `kinegen` binary of this build.
pub fn kinegen() -> Command {
    Command::cargo_bin("kinegen").unwrap()
}

/// `robots/NAME.toml` of the workspace.
pub fn robot_file(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../robots")
        .join(format!("{name}.toml"))
}

/// stdout of a successful invocation.
pub fn stdout(args: &[&str]) -> String {
    let out = kinegen()
        .args(args)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    String::from_utf8(out).unwrap()
}

/// A failing invocation: exit 2, nothing on stdout, one `kinegen: error:` line on stderr
/// (returned), and no panic.
pub fn fails(args: &[&str]) -> String {
    let out = kinegen()
        .args(args)
        .assert()
        .code(2)
        .stdout("")
        .get_output()
        .stderr
        .clone();
    let err = String::from_utf8(out).unwrap();
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("kinegen: error: "), "{err}");
    err
}

/// A JSON array of numbers.
pub fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// A pose's result from `kinegen ik --json`: its solutions and their `exact` flags.
pub fn solutions_and_flags(r: &Value) -> (Vec<Vec<f64>>, Vec<bool>) {
    let solutions = r["solutions"]
        .as_array()
        .unwrap()
        .iter()
        .map(floats)
        .collect();
    let exact = r["exact"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b.as_bool().unwrap())
        .collect();
    (solutions, exact)
}
