#![allow(dead_code)]
//! Shared by the tests that go over every robot table (also `#[path]`-included by
//! kinegen-cli's determinism test).

use std::path::{Path, PathBuf};

/// The `robots/` folder of the workspace.
pub fn robots_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../robots")
}

/// Every robot file in `robots/` (DH tables and files naming a URDF), sorted.
pub fn all_robot_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(robots_dir())
        .expect("robots/ exists")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml") && !p.ends_with("Cargo.toml"))
        .collect();
    files.sort();
    files
}

/// Every DH table in `robots/` (the files that do not name a URDF), sorted.
pub fn robot_files() -> Vec<PathBuf> {
    all_robot_files()
        .into_iter()
        .filter(|p| {
            let src = std::fs::read_to_string(p).unwrap();
            !src.lines().any(|l| l.starts_with("urdf ="))
        })
        .collect()
}
