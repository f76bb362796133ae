//! Bad `kinematics!` inputs fail to compile with a clear message under the offending
//! entry; and the engine's notes are compiler warnings, pinned as errors under
//! `#![deny(deprecated)]` in `notes_are_warnings.rs`. The expected output of each `tests/ui/*.rs` is pinned in its `.stderr`;
//! regenerate with `TRYBUILD=overwrite cargo test -p kinegen-macro --test compile_fail` and review
//! every changed file like code.

use std::path::{Path, PathBuf};

#[test]
fn ui() {
    stage_data_files();
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/*.rs");
}

/// trybuild compiles the UI tests as a crate of its own under
/// `<target>/tests/trybuild/kinegen-macro`, so the file form's paths (relative to
/// `CARGO_MANIFEST_DIR`) resolve there: put `tests/ui/data` where they look for it.
fn stage_data_files() {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    let project = target_dir(manifest).join("tests/trybuild/kinegen-macro");
    let (from, to) = (
        manifest.join("tests/ui/data"),
        project.join("tests/ui/data"),
    );
    std::fs::create_dir_all(&to).unwrap();
    for entry in std::fs::read_dir(&from).unwrap() {
        let entry = entry.unwrap();
        std::fs::copy(entry.path(), to.join(entry.file_name())).unwrap();
    }
}

/// Cargo's target directory: the ancestor of this test binary that cargo marked with
/// `CACHEDIR.TAG` (the same directory trybuild builds in).
fn target_dir(manifest: &Path) -> PathBuf {
    std::env::current_exe()
        .ok()
        .and_then(|exe| {
            exe.ancestors()
                .find(|d| d.join("CACHEDIR.TAG").is_file())
                .map(Path::to_path_buf)
        })
        .unwrap_or_else(|| manifest.join("target"))
}
