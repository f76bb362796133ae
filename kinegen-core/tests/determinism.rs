//! The generated code is a function of the table alone (issue 8): `generate` run twice
//! on every robot of `robots/` gives byte-identical pretty-printed code and notes, and
//! the item parses as Rust.
//!
//! Each `HashMap` in the engine gets its own random hash seed (per process and per map),
//! so two runs in one process already differ in every hash-map iteration order; the
//! second process is in `kinegen-cli/tests/determinism.rs`.

mod common;
use common::robot_files;

use std::path::Path;

use kinegen_core::{front::toml_file, generate, ItemHeader};

/// Code and notes of one run.
fn run(path: &Path) -> (String, Vec<String>) {
    let (robot, options) = toml_file::load_file(path).unwrap_or_else(|e| panic!("{e}"));
    let g = generate(&robot.chain(), &ItemHeader::public(&robot.name), &options);
    // The engine only lexes the item it prints; here it must parse as Rust.
    if let Err(e) = syn::parse2::<syn::File>(g.tokens.clone()) {
        panic!("{}: generated code does not parse: {e}", path.display());
    }
    (g.pretty(), g.notes)
}

#[test]
fn every_robot_generates_the_same_code_twice() {
    let files = robot_files();
    assert!(files.len() >= 16, "{files:?}");
    // Two threads: the robots are independent, and the machine has two cores.
    let (even, odd): (Vec<_>, Vec<_>) = files.iter().enumerate().partition(|(i, _)| i % 2 == 0);
    std::thread::scope(|s| {
        for part in [even, odd] {
            s.spawn(move || {
                for (_, path) in part {
                    let first = run(path);
                    let second = run(path);
                    assert!(!first.0.contains("compile_error"), "{}", path.display());
                    assert!(
                        first == second,
                        "{}: two runs differ at byte {}",
                        path.display(),
                        first
                            .0
                            .bytes()
                            .zip(second.0.bytes())
                            .take_while(|(a, b)| a == b)
                            .count()
                    );
                }
            });
        }
    });
}
