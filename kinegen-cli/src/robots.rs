//! The robot argument: a TOML file, or the name of a robot shipped in `robots/`.

use std::path::Path;

use kinegen_core::{Chain, Options};

use crate::error::CliError;

/// The shipped robots, `(name, label, TOML source)`, from the `kinegen-robots` crate (so
/// they travel with the published package, not only with this workspace).
const ROBOTS: &[(&str, &str, &str)] = kinegen_robots::TABLES;

/// Names of the shipped robots (`ur5`, `puma560`, …).
pub fn names() -> impl Iterator<Item = &'static str> {
    ROBOTS.iter().map(|(n, _, _)| *n)
}

/// Load `arg`: an existing file (or anything that looks like a path) is read as TOML;
/// otherwise a shipped robot by file name (`ur5`), case-insensitively.
pub fn load(arg: &str) -> Result<(Chain, Options), CliError> {
    use kinegen_core::front::toml_file::{load_file, load_str};
    let chain = |(robot, options): (kinegen_core::Robot, Options)| (robot.chain(), options);
    let looks_like_path = arg.ends_with(".toml") || arg.contains(['/', '\\']);
    if looks_like_path || Path::new(arg).is_file() {
        return load_file(Path::new(arg)).map(chain).map_err(CliError::Load);
    }
    let key = arg.to_ascii_lowercase();
    match ROBOTS.iter().find(|(n, _, _)| *n == key) {
        Some((_, label, src)) => load_str(src, label).map(chain).map_err(CliError::Load),
        None => Err(CliError::Usage(format!(
            "unknown robot `{arg}`: not a file, and not one of {}",
            names().collect::<Vec<_>>().join(", ")
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_shipped_robot_loads() {
        assert!(ROBOTS.len() >= 3);
        for name in names() {
            let (robot, _) = load(name).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(robot.dof() > 0);
        }
    }

    #[test]
    fn names_are_case_insensitive_and_unknown_names_are_listed() {
        assert_eq!(load("UR5").unwrap().0.name, "UR5");
        let e = load("ur7").unwrap_err().to_string();
        assert!(
            e.starts_with("unknown robot `ur7`: not a file, and not one of "),
            "{e}"
        );
        assert!(e.contains("planar_rr") && e.contains("ur5"), "{e}");
    }
}
