//! `TABLES` and `URDFS` list exactly the TOML and URDF files of this crate, with their
//! contents.

#[test]
fn tables_are_the_toml_files() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|f| f.ends_with(".toml") && f != "Cargo.toml")
        .collect();
    files.sort();
    let listed: Vec<String> = kinegen_robots::TABLES
        .iter()
        .map(|(name, _, _)| format!("{name}.toml"))
        .collect();
    assert_eq!(
        listed, files,
        "add the new table to TABLES in robots/src/lib.rs"
    );
    for (name, label, source) in kinegen_robots::TABLES {
        assert_eq!(*label, format!("robots/{name}.toml"));
        let on_disk = std::fs::read_to_string(dir.join(format!("{name}.toml"))).unwrap();
        assert_eq!(*source, on_disk, "{name}");
    }
}

#[test]
fn urdfs_are_the_urdf_files() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("urdf");
    let mut files: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|f| f.ends_with(".urdf"))
        .collect();
    files.sort();
    let listed: Vec<String> = kinegen_robots::URDFS
        .iter()
        .map(|(rel, _, _)| rel.trim_start_matches("urdf/").to_string())
        .collect();
    assert_eq!(
        listed, files,
        "add the new URDF to URDFS in robots/src/lib.rs"
    );
    for (rel, label, source) in kinegen_robots::URDFS {
        assert_eq!(*label, format!("robots/{rel}"));
        let on_disk = std::fs::read_to_string(dir.join(rel.trim_start_matches("urdf/"))).unwrap();
        assert_eq!(*source, on_disk, "{rel}");
    }
}
