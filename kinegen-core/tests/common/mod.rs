#![allow(dead_code)]
//! Shared by the tests that go over every robot table (also `#[path]`-included by
//! kinegen-cli's determinism test).

use std::path::{Path, PathBuf};

/// The `robots/` folder of the workspace.
pub fn robots_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../robots")
}

/// Every robot table in `robots/`, sorted.
pub fn robot_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(robots_dir())
        .expect("robots/ exists")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml") && !p.ends_with("Cargo.toml"))
        .collect();
    files.sort();
    files
}
