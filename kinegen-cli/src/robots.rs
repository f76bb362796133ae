//! The robot argument: a TOML or URDF file, or the name of a robot shipped in `robots/`.

use std::path::Path;

use kinegen_core::chain::urdf::{Selection, DEFAULT_SNAP};
use kinegen_core::front::toml_file::{
    load_description_file, load_description_str, Description, LoadError,
};
use kinegen_core::front::urdf::Urdf;
use kinegen_core::model::raw::PathSeg;
use kinegen_core::model::robot::TaskRow;
use kinegen_core::{Chain, Options};

use crate::error::CliError;

/// The shipped robots, `(name, label, TOML source)`, from the `kinegen-robots` crate (so
/// they travel with the published package, not only with this workspace).
const ROBOTS: &[(&str, &str, &str)] = kinegen_robots::TABLES;

/// The URDFs those robots may name, `(path relative to robots/, label, source)`.
const URDFS: &[(&str, &str, &str)] = kinegen_robots::URDFS;

/// Names of the shipped robots (`ur5`, `puma560`, …).
pub fn names() -> impl Iterator<Item = &'static str> {
    ROBOTS.iter().map(|(n, _, _)| *n)
}

/// Which chain of a URDF file, and how to read its numbers (`--base`, `--tip`, `--snap`).
#[derive(Clone, Debug, Default, PartialEq, clap::Args)]
pub struct UrdfArgs {
    /// URDF: the base link (default: the root link).
    #[arg(long)]
    pub base: Option<String>,
    /// URDF: the tip link (default: the only leaf after a moving joint, or the one before
    /// a parallel gripper's fingers).
    #[arg(long)]
    pub tip: Option<String>,
    /// URDF: snap angles within this many radians of a multiple of π/12, and lengths
    /// within this many metres of 0, to the exact value (default 1e-4; 0 keeps every
    /// decimal as written).
    #[arg(long)]
    pub snap: Option<f64>,
    /// URDF: name every length of the chain (`d1`, `a2`…, listed with where the file
    /// writes them in `show --what model`) and keep the names in every formula.
    #[arg(long)]
    pub symbolic: bool,
    /// URDF: the task rows an arm with fewer than six joints solves, and whose Jacobian
    /// `show` gives (`--task x,y,z,rz` for a SCARA); a TOML robot says `task = [...]`.
    #[arg(long, value_delimiter = ',')]
    pub task: Option<Vec<String>>,
}

impl UrdfArgs {
    fn given(&self) -> bool {
        self.base.is_some()
            || self.tip.is_some()
            || self.snap.is_some()
            || self.symbolic
            || self.task.is_some()
    }

    /// The rows `--task` names, each once, or why not.
    fn task_rows(&self) -> Result<Option<Vec<TaskRow>>, CliError> {
        let Some(names) = &self.task else {
            return Ok(None);
        };
        let mut rows = Vec::new();
        for name in names {
            let row = TaskRow::next_in_list(name, &rows)
                .map_err(|m| CliError::Usage(format!("--task: {m}")))?;
            rows.push(row);
        }
        Ok(Some(rows))
    }
}

/// Load `arg`: a `.urdf` file (the chain `urdf` selects); an existing file (or anything
/// that looks like a path) as TOML, a DH table or a file naming a URDF; otherwise a
/// shipped robot by file name (`ur5`), case-insensitively.
pub fn load(arg: &str, urdf: &UrdfArgs) -> Result<(Chain, Options), CliError> {
    if arg.ends_with(".urdf") {
        return load_urdf(Path::new(arg), urdf).map(|c| (c, Options::default()));
    }
    if urdf.given() {
        return Err(CliError::Usage(
            "--base, --tip, --snap, --symbolic and --task select the chain of a .urdf file; a TOML robot says them in the file (`params = \"auto\"` for --symbolic, `task = [...]`)"
                .into(),
        ));
    }
    let chain = |(d, options): (Description, Options)| (d.chain(), options);
    let looks_like_path = arg.ends_with(".toml") || arg.contains(['/', '\\']);
    if looks_like_path || Path::new(arg).is_file() {
        return load_description_file(Path::new(arg))
            .map(chain)
            .map_err(CliError::Load);
    }
    let key = arg.to_ascii_lowercase();
    let read = |rel: &str| match URDFS.iter().find(|(r, _, _)| *r == rel) {
        Some((_, label, src)) => Ok((label.to_string(), src.to_string())),
        None => Err(format!("`{rel}` is not a URDF shipped in robots/")),
    };
    match ROBOTS.iter().find(|(n, _, _)| *n == key) {
        Some((_, label, src)) => load_description_str(src, label, &read)
            .map(chain)
            .map_err(CliError::Load),
        None => Err(CliError::Usage(format!(
            "unknown robot `{arg}`: not a file, and not one of {}",
            names().collect::<Vec<_>>().join(", ")
        ))),
    }
}

/// The chain of a URDF file.
fn load_urdf(path: &Path, args: &UrdfArgs) -> Result<Chain, CliError> {
    urdf_chain(&Urdf::load_file(path).map_err(CliError::Load)?, args)
}

/// The chain of a parsed URDF that `--base`, `--tip` and `--snap` select, as `kinegen`
/// loads a `.urdf` file (after [`Urdf::load_file`]).
pub fn urdf_chain(urdf: &Urdf, args: &UrdfArgs) -> Result<Chain, CliError> {
    let selection = Selection {
        base: args.base.clone(),
        tip: args.tip.clone(),
        snap: args.snap.unwrap_or(DEFAULT_SNAP),
        params: Vec::new(),
        symbolic: args.symbolic,
    };
    let task = args.task_rows()?;
    let mut chain = urdf.chain(&selection).map_err(|e| {
        // Name the option an error is about (`--tip`), after the file's line.
        CliError::Load(LoadError {
            errors: e
                .errors
                .into_iter()
                .map(|mut e| {
                    if let Some(PathSeg::Key(k)) = e.path.0.first() {
                        if ["base", "tip", "snap"].contains(&k.as_str()) {
                            e.message = format!("--{k}: {}", e.message);
                            e.path = kinegen_core::model::raw::Path::root();
                        }
                    }
                    e
                })
                .collect(),
        })
    })?;
    if task.is_some() {
        chain.task = task;
    }
    Ok(chain)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_shipped_robot_loads() {
        assert!(ROBOTS.len() >= 3);
        for name in names() {
            let (robot, _) =
                load(name, &UrdfArgs::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(robot.dof() > 0);
        }
    }

    #[test]
    fn names_are_case_insensitive_and_unknown_names_are_listed() {
        assert_eq!(load("UR5", &UrdfArgs::default()).unwrap().0.name, "UR5");
        let e = load("ur7", &UrdfArgs::default()).unwrap_err().to_string();
        assert!(
            e.starts_with("unknown robot `ur7`: not a file, and not one of "),
            "{e}"
        );
        assert!(e.contains("planar_rr") && e.contains("ur5"), "{e}");
    }
}
