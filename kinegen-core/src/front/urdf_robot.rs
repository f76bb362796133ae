//! A URDF with the options a robot description gives it — which chain (`base`, `tip`),
//! how to snap (`snap`), which lengths to name (`params`), `task`, `scalar`, `name` — as
//! the engine's [`Chain`]. The TOML loader and the `kinematics!` macro both read their
//! options into [`UrdfOptions`] and report the [`Problem`]s: at the option (a line of
//! the TOML file, a span in the macro) or at the URDF's own line.
//!
//! ```
//! use kinegen_core::front::urdf::Urdf;
//! use kinegen_core::front::urdf_robot::{chain, UrdfOptions};
//! use kinegen_core::model::raw::RawValue;
//! let urdf = Urdf::parse(r#"<robot name="r"><link name="a"/><link name="b"/>
//!   <joint name="j" type="continuous"><parent link="a"/><child link="b"/>
//!   <origin xyz="0.5 0 0"/><axis xyz="0 0 1"/></joint></robot>"#, "r.urdf").unwrap();
//! let options = UrdfOptions {
//!     params: vec![("L".into(), RawValue::Text("j.origin.x".into()))],
//!     ..Default::default()
//! };
//! let c = chain(&urdf, &options).unwrap();
//! assert_eq!(c.to_string(), "link 1: Tx(L) Rz(q1)\n");
//! ```

use crate::chain::urdf::{Selection, DEFAULT_SNAP};
use crate::chain::Chain;
use crate::front::located::LocatedError;
use crate::front::urdf::Urdf;
use crate::model::raw::{DhError, Path, PathSeg, RawRobot, RawValue};
use crate::model::validate::task_and_scalar;

/// Top-level keys of a description that names a URDF.
pub const URDF_KEYS: &[&str] = &[
    "name", "urdf", "base", "tip", "snap", "params", "task", "scalar", "budget", "ik_free",
];

/// Keys the builder's errors may point at instead of the URDF's line.
const OPTION_KEYS: &[&str] = &["base", "tip", "snap", "params"];

/// What a description says about its URDF, as written.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct UrdfOptions {
    /// Display name (default: the URDF's `<robot name>`).
    pub name: Option<String>,
    /// Base link.
    pub base: Option<String>,
    /// Tip link.
    pub tip: Option<String>,
    /// Snap tolerance (default [`DEFAULT_SNAP`]).
    pub snap: Option<f64>,
    /// Named lengths: `(name, "joint.origin.z")`.
    pub params: Vec<(String, RawValue)>,
    /// `params: auto` / `params = "auto"`: every length named ([`Selection::symbolic`]).
    pub symbolic: bool,
    /// Task rows.
    pub task: Option<Vec<RawValue>>,
    /// `f64` / `f32`.
    pub scalar: Option<String>,
}

/// A problem with a URDF description.
#[derive(Clone, Debug, PartialEq)]
pub enum Problem {
    /// In the options, at a path (`tip`, `params.d1`, `task[2]`).
    Option(DhError),
    /// In the URDF file, at its line.
    File(LocatedError),
}

/// The chain the options select from `urdf`, or every problem.
pub fn chain(urdf: &Urdf, o: &UrdfOptions) -> Result<Chain, Vec<Problem>> {
    let mut problems = Vec::new();
    let mut params = Vec::new();
    for (name, v) in &o.params {
        match v {
            RawValue::Text(t) => params.push((name.clone(), t.clone())),
            _ => problems.push(Problem::Option(DhError {
                path: Path::root().key("params").key(name),
                message: format!(
                    "a URDF's parameter names one of its lengths: `{name} = \"JOINT.origin.z\"`"
                ),
            })),
        }
    }
    let raw = RawRobot {
        task: o.task.clone(),
        scalar: o.scalar.clone(),
        ..RawRobot::default()
    };
    let checked = task_and_scalar(&raw).map_err(|errs| {
        problems.extend(errs.into_iter().map(Problem::Option));
    });
    let selection = Selection {
        base: o.base.clone(),
        tip: o.tip.clone(),
        snap: o.snap.unwrap_or(DEFAULT_SNAP),
        params,
        symbolic: o.symbolic,
    };
    let built = urdf.chain(&selection).map_err(|e| {
        problems.extend(e.errors.into_iter().map(|e| match e.path.0.first() {
            Some(PathSeg::Key(k)) if OPTION_KEYS.contains(&k.as_str()) => {
                Problem::Option(DhError {
                    path: e.path,
                    message: e.message,
                })
            }
            _ => Problem::File(e),
        }));
    });
    match (built, checked) {
        (Ok(mut c), Ok((task, scalar))) if problems.is_empty() => {
            if let Some(name) = &o.name {
                c.name = name.clone();
            }
            c.task = task;
            c.scalar = scalar;
            Ok(c)
        }
        _ => Err(problems),
    }
}
