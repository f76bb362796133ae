//! The `kinegen` command: a robot's closed-form kinematics for people and tools.
//!
//! - `kinegen show ROBOT [--what fk|jacobian|det|singularities|all|model] [--latex]`
//! - `kinegen rust ROBOT` — the code `kinematics!` generates, pretty-printed
//! - `kinegen eval ROBOT --q 0.1,0.2,… [--qd 0.3,…] [--json]`
//! - `kinegen stats ROBOT [--json]`
//! - `kinegen ik ROBOT --pose m00,…,m33 [--near q1,…] [--json]` or `--poses FILE.json
//!   [--near FILE.json]` — every closed-form IK solution
//! - `kinegen reach ROBOT [--resolution 0.08] [--orientations 50|DxR] [-o map.npz]
//!   [--slices DIR]` — a reachability map; `--inverse TASK.json` — base placement
//! - `kinegen report ROBOT [-o FILE.html]` — one self-contained HTML page: the formulas
//!   as MathML, the singularity map, the IK solutions and a trajectory as SVG, the stats
//!
//! ROBOT is a TOML file (`robots/ur5.toml`), a URDF file (`arm.urdf`, with `--base`,
//! `--tip`, `--snap`; without them the root link and the only leaf after a moving
//! joint) or the name of a shipped robot (`ur5`).
//! Every command is a thin caller of `kinegen_core`; [`run`] returns the text to print,
//! so it is testable without a process.

pub mod colour;
pub mod det_hook;
pub mod error;
pub mod eval;
pub mod formulas;
pub mod ik;
pub mod model;
pub mod reach;
pub mod report;
pub mod robots;
pub mod stats;

use clap::{Parser, Subcommand};
use kinegen_core::{derive, generate, ItemHeader};

pub use error::CliError;
pub use formulas::What;
pub use robots::UrdfArgs;

/// Closed-form robot kinematics from DH tables.
#[derive(Debug, Parser)]
#[command(name = "kinegen", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Show the closed forms (terminal text, or a LaTeX document body).
    Show {
        /// A TOML or URDF file, or a shipped robot's name (ur5, puma560, planar_rr, …).
        robot: String,
        /// Which chain of a URDF, and how to snap its numbers.
        #[command(flatten)]
        urdf: UrdfArgs,
        /// Which outputs.
        #[arg(long, value_enum, default_value = "all")]
        what: What,
        /// Print a LaTeX document body (amsmath `align*`) instead of text.
        #[arg(long)]
        latex: bool,
        /// For a 7-joint arm: the joint (1-based) the closed-form IK leaves free (default:
        /// the engine's choice, said in the derivation; a TOML file may say `ik_free`).
        #[arg(long)]
        free: Option<usize>,
    },
    /// Print the Rust code `kinematics!` generates for the robot (`pub struct <Name>`).
    Rust {
        /// A TOML or URDF file, or a shipped robot's name.
        robot: String,
        /// Which chain of a URDF, and how to snap its numbers.
        #[command(flatten)]
        urdf: UrdfArgs,
        /// For a 7-joint arm: the joint (1-based) the closed-form IK leaves free (default:
        /// the engine's choice, said in the derivation; a TOML file may say `ik_free`).
        #[arg(long)]
        free: Option<usize>,
    },
    /// Evaluate the generated formulas at a configuration.
    Eval {
        /// A TOML or URDF file, or a shipped robot's name.
        robot: String,
        /// Which chain of a URDF, and how to snap its numbers.
        #[command(flatten)]
        urdf: UrdfArgs,
        /// Joint values, comma-separated (radians / metres), one per joint.
        #[arg(long, allow_hyphen_values = true)]
        q: String,
        /// Joint rates, comma-separated (rad/s / m/s), one per joint: for `jacobian_dot`
        /// and `jdot_qdot` (null without).
        #[arg(long, allow_hyphen_values = true)]
        qd: Option<String>,
        /// Print JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
    /// Operation counts of the generated code and the engine's time.
    Stats {
        /// A TOML or URDF file, or a shipped robot's name.
        robot: String,
        /// Which chain of a URDF, and how to snap its numbers.
        #[command(flatten)]
        urdf: UrdfArgs,
        /// Print JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
    /// Every closed-form inverse-kinematics solution of a pose (or of a file of poses).
    Ik {
        /// A TOML or URDF file, or a shipped robot's name.
        robot: String,
        /// Which chain of a URDF, and how to snap its numbers.
        #[command(flatten)]
        urdf: UrdfArgs,
        /// The pose: 16 numbers, row-major 4×4 (`m00,m01,…,m33`).
        #[arg(long, allow_hyphen_values = true, conflicts_with = "poses")]
        pose: Option<String>,
        /// A JSON file holding an array of 4×4 poses (arrays of 4 rows of 4 numbers).
        #[arg(long)]
        poses: Option<std::path::PathBuf>,
        /// The current configuration: with `--pose`, `q1,…,qN`; with `--poses`, a JSON
        /// file of one joint vector per pose. Adds `near`, the answer of `ik_near`.
        #[arg(long, allow_hyphen_values = true)]
        near: Option<String>,
        /// For a 7-joint arm: the locked joint's value (else taken from `--near`).
        #[arg(long, allow_hyphen_values = true)]
        locked: Option<f64>,
        /// For a 7-joint S-R-S arm (the iiwa): every solution at this arm angle (radians)
        /// instead of with a joint locked.
        #[arg(long, allow_hyphen_values = true)]
        arm_angle: Option<f64>,
        /// For a 7-joint arm: the joint (1-based) the closed-form IK leaves free (default:
        /// the engine's choice, said in the derivation; a TOML file may say `ik_free`).
        #[arg(long)]
        free: Option<usize>,

        /// Print JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
    /// A reachability map: every pose of every voxel solved in closed form, all
    /// solutions; per voxel the reachability index, solutions within limits, the best
    /// manipulability and each singular factor's smallest |value|. The `.npz` holds
    /// `spheres` (V×4: x, y, z, reachability %, Reuleaux's sphere table), `poses` (P×10
    /// f32: centre, position, quaternion x y z w of each reachable pose; Reuleaux's pose
    /// table, with `--orientations 50`), `solutions_min`, `solutions_mean`,
    /// `manipulability`, `factor_min`, `factor_best` (V×K), `factor_names`,
    /// `resolution`, `box`, `dims`; the `.h5` has Reuleaux's `/Spheres/sphere_dataset`
    /// (with `Resolution`) and `/Poses/poses_dataset`, the rest in `/kinegen`.
    Reach {
        /// A TOML or URDF file, or a shipped robot's name.
        robot: String,
        /// Which chain of a URDF, and how to snap its numbers.
        #[command(flatten)]
        urdf: UrdfArgs,
        /// Voxel spacing in metres (Reuleaux's default 0.08).
        #[arg(long, default_value_t = 0.08, allow_hyphen_values = true)]
        resolution: f64,
        /// Poses per voxel: 50 (Reuleaux's, on a sphere of radius one voxel) or DxR (D
        /// approach directions times R rolls about each, at the centre; 200x12 is the
        /// Zacharias density).
        #[arg(long, default_value = reach::DEFAULT_ORIENTATIONS)]
        orientations: String,
        /// The box of voxel centres, `xmin,ymin,zmin,xmax,ymax,zmax` in metres (default:
        /// Reuleaux's 3 m cube, ±1.5 m around the base).
        #[arg(long = "box", allow_hyphen_values = true, value_delimiter = ',')]
        bounds: Option<Vec<f64>>,
        /// For a 7-joint arm: values of the locked joint tried per pose (evenly spaced
        /// over its limits).
        #[arg(long, default_value_t = reach::DEFAULT_FREE_SAMPLES)]
        free_samples: usize,
        /// Solve the voxels outside the arm's reach sphere too (the map is the same).
        #[arg(long)]
        no_skip: bool,
        /// With DxR orientations: solve every roll, also where the last joint turns the
        /// tool about its approach axis (by default one roll per direction then stands
        /// for all: the same solutions with the last joint turned).
        #[arg(long)]
        every_roll: bool,
        /// Worker threads (default: every core).
        #[arg(long)]
        threads: Option<usize>,
        /// Write the map (`.h5` in Reuleaux's layout, or `.npz`), or with --inverse the
        /// ranked bases (`.json`).
        #[arg(short, long)]
        output: Option<std::path::PathBuf>,
        /// Write PNG slices of the map into this directory.
        #[arg(long)]
        slices: Option<std::path::PathBuf>,
        /// Heights (m) of the xy slices, comma-separated (default: joint 1's shoulder).
        #[arg(long, allow_hyphen_values = true, value_delimiter = ',')]
        slice_z: Option<Vec<f64>>,
        /// Base placement: a JSON array of the task's 4×4 poses; prints the base
        /// positions on the plane --plane-z that reach all of them, best first.
        #[arg(long)]
        inverse: Option<std::path::PathBuf>,
        /// The height of the plane the base stands on (--inverse).
        #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
        plane_z: f64,
        /// For a 7-joint arm: the joint (1-based) the closed-form IK leaves free.
        #[arg(long)]
        free: Option<usize>,
    },
    /// One self-contained HTML page (no script, no network): the robot as read, the
    /// closed forms as MathML, det J and its singular factors, the IK family and the
    /// solutions of one pose, the second order, pictures as SVG, the operation counts.
    Report {
        /// A TOML or URDF file, or a shipped robot's name.
        robot: String,
        /// Which chain of a URDF, and how to snap its numbers.
        #[command(flatten)]
        urdf: UrdfArgs,
        /// The page to write (default: `<robot name>.html` in the current directory).
        #[arg(short, long)]
        output: Option<std::path::PathBuf>,
        /// For a 7-joint arm: the joint (1-based) the closed-form IK leaves free.
        #[arg(long)]
        free: Option<usize>,
        /// Add the reachability map's plane through the base, computed at this voxel
        /// spacing in metres (as `kinegen reach --resolution`; 0.08 takes about a second
        /// for a 6-joint arm).
        #[arg(long, value_name = "RESOLUTION")]
        reach: Option<f64>,
    },
}

/// Run a parsed command; `Ok` is the text for stdout.
pub fn run(cli: &Cli) -> Result<String, CliError> {
    match &cli.command {
        Command::Show {
            robot,
            urdf,
            what,
            latex,
            free,
        } => {
            let (chain, options) = robots::load(robot, urdf)?;
            let options = with_free(options, &chain, *free)?;
            if *what == What::Model {
                return Ok(model::show(&chain));
            }
            let derived = derive(&chain, &options);
            if *what == What::Ik {
                return Ok(ik::show(&chain, &derived));
            }
            let dets = det_hook::determinants(&chain, &derived);
            Ok(formulas::show(&chain, &derived.model, &dets, *what, *latex))
        }
        Command::Rust { robot, urdf, free } => {
            let (chain, options) = robots::load(robot, urdf)?;
            let options = with_free(options, &chain, *free)?;
            // Exactly the macro's call for `pub struct <Name>` (kinegen-macro's expand).
            Ok(generate(&chain, &ItemHeader::public(&chain.name), &options).pretty())
        }
        Command::Eval {
            robot,
            urdf,
            q,
            qd,
            json,
        } => {
            let (chain, options) = robots::load(robot, urdf)?;
            let q = eval::parse_q(q, chain.dof())?;
            let qd = qd
                .as_ref()
                .map(|qd| eval::parse_joint_values(qd, chain.dof(), "--qd"))
                .transpose()?;
            let derived = derive(&chain, &options);
            let dets = det_hook::determinants(&chain, &derived);
            let v = eval::values(&chain, &derived, &dets, &q, qd.as_deref());
            Ok(if *json {
                format!("{}\n", eval::to_json(&v))
            } else {
                eval::to_table(&chain, &q, &v, &dets.missing)
            })
        }
        Command::Stats { robot, urdf, json } => {
            let (chain, options) = robots::load(robot, urdf)?;
            let m = stats::measured(&chain, &options);
            Ok(if *json {
                format!("{}\n", stats::to_json(&m.stats))
            } else {
                stats::to_table(&chain, &m.stats, &m.dets.missing)
            })
        }
        Command::Ik {
            robot,
            urdf,
            pose,
            poses,
            near,
            locked,
            arm_angle,
            free,
            json,
        } => {
            let (chain, options) = robots::load(robot, urdf)?;
            let options = with_free(options, &chain, *free)?;
            let derived = derive(&chain, &options);
            let request = ik::Request {
                pose: pose.as_deref(),
                poses: poses.as_deref(),
                near: near.as_deref(),
                locked: *locked,
                arm_angle: *arm_angle,
                json: *json,
            };
            ik::run(&chain, &derived, &request)
        }
        Command::Reach {
            robot,
            urdf,
            resolution,
            orientations,
            bounds,
            free_samples,
            no_skip,
            every_roll,
            threads,
            output,
            slices,
            slice_z,
            inverse,
            plane_z,
            free,
        } => {
            let (chain, options) = robots::load(robot, urdf)?;
            let options = with_free(options, &chain, *free)?;
            let derived = derive(&chain, &options);
            let request = reach::Request {
                resolution: *resolution,
                orientations: orientations.clone(),
                bounds: bounds.clone(),
                free_samples: *free_samples,
                no_skip: *no_skip,
                every_roll: *every_roll,
                threads: *threads,
                output: output.clone(),
                slices: slices.clone(),
                slice_z: slice_z.clone(),
                inverse: inverse.clone(),
                plane_z: *plane_z,
                progress: true,
            };
            reach::run(&chain, &derived, &request)
        }
        Command::Report {
            robot,
            urdf,
            output,
            free,
            reach,
        } => {
            let (chain, options) = robots::load(robot, urdf)?;
            let options = with_free(options, &chain, *free)?;
            report::run(&chain, &options, output.as_deref(), *reach)
        }
    }
}

/// `options` with `--free k` (1-based) checked against the robot: exit 2 when the arm
/// has no joint to leave free or no joint `k`.
fn with_free(
    mut options: kinegen_core::Options,
    chain: &kinegen_core::Chain,
    free: Option<usize>,
) -> Result<kinegen_core::Options, CliError> {
    if let Some(k) = free {
        let k = kinegen_core::model::input::check_ik_free(k, chain.dof())
            .map_err(|e| CliError::Usage(format!("--free: {}", e.replace("`ik_free`", "it"))))?;
        options.ik_free = Some(k);
    }
    Ok(options)
}
