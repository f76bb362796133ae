//! Embeds the robots of `robots/*.toml` (and the URDFs of `robots/urdf/` they may name) into the binary, so `kinegen show ur5` works from
//! any directory: writes `$OUT_DIR/robots.rs` with one `(name, label, source)` per file.

use std::fmt::Write;
use std::path::PathBuf;

fn main() {
    let dir = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo"))
        .join("..")
        .join("robots");
    let files = files_of(&dir, "toml");
    let mut out = String::from("/// Robots of `robots/`: `(name, label, TOML source)`, sorted by name.\npub const ROBOTS: &[(&str, &str, &str)] = &[\n");
    for f in &files {
        let stem = f
            .file_stem()
            .and_then(|s| s.to_str())
            .expect("UTF-8 file name");
        let path = f.canonicalize().expect("file exists");
        println!("cargo:rerun-if-changed={}", path.display());
        let _ = writeln!(
            out,
            "    ({stem:?}, {:?}, include_str!({:?})),",
            format!("robots/{stem}.toml"),
            path.display().to_string()
        );
    }
    out.push_str("];\n");
    // The URDFs those robots may name (`urdf = "urdf/ur5.urdf"`).
    let urdfs = files_of(&dir.join("urdf"), "urdf");
    out.push_str("/// URDFs of `robots/urdf/`: `(path relative to robots/, label, source)`.\npub const URDFS: &[(&str, &str, &str)] = &[\n");
    for f in &urdfs {
        let name = f
            .file_name()
            .and_then(|s| s.to_str())
            .expect("UTF-8 file name");
        let path = f.canonicalize().expect("file exists");
        println!("cargo:rerun-if-changed={}", path.display());
        let _ = writeln!(
            out,
            "    ({:?}, {:?}, include_str!({:?})),",
            format!("urdf/{name}"),
            format!("robots/urdf/{name}"),
            path.display().to_string()
        );
    }
    out.push_str("];\n");
    let dest = PathBuf::from(std::env::var_os("OUT_DIR").expect("set by cargo")).join("robots.rs");
    std::fs::write(dest, out).expect("OUT_DIR is writable");
}

/// The files of `dir` ending in `.ext` (not `Cargo.toml`), sorted; cargo reruns this
/// script when `dir` changes.
fn files_of(dir: &std::path::Path, ext: &str) -> Vec<PathBuf> {
    println!("cargo:rerun-if-changed={}", dir.display());
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == ext) && !p.ends_with("Cargo.toml"))
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    files
}
