//! The generated code is the same in another process (issue 8): `kinegen rust ROBOT`,
//! a separate process with its own hash seeds, prints byte for byte what `generate`
//! gives in this one, for every robot of `robots/`.

#[path = "../../kinegen-core/tests/common/mod.rs"]
mod common;
use common::robot_files;

use std::process::{Command, Stdio};

use kinegen_core::{front::toml_file, generate, ItemHeader};

#[test]
fn the_cli_prints_the_same_code_as_this_process() {
    let files = robot_files();
    assert!(files.len() >= 16, "{files:?}");
    let bin = assert_cmd::cargo::cargo_bin("kinegen");
    // Start every process first (they run while this one generates), then compare.
    let children: Vec<_> = files
        .iter()
        .map(|path| {
            Command::new(&bin)
                .arg("rust")
                .arg(path)
                .stdout(Stdio::piped())
                .stderr(Stdio::piped())
                .spawn()
                .unwrap()
        })
        .collect();
    for (path, child) in files.iter().zip(children) {
        let (robot, options) = toml_file::load_file(path).unwrap();
        let here = generate(&robot.chain(), &ItemHeader::public(&robot.name), &options).pretty();
        let out = child.wait_with_output().unwrap();
        assert!(
            out.status.success(),
            "{}: {}",
            path.display(),
            String::from_utf8_lossy(&out.stderr)
        );
        let there = String::from_utf8(out.stdout).unwrap();
        assert!(
            here == there,
            "{}: the CLI's code differs from this process's at byte {}",
            path.display(),
            here.bytes()
                .zip(there.bytes())
                .take_while(|(a, b)| a == b)
                .count()
        );
    }
}
