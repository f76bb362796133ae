//! `kinegen report ROBOT [-o FILE.html]`: one self-contained HTML page — no script, no
//! network — with everything the engine knows about a robot: the description and its
//! snaps, FK, the Jacobian, det J and its singular factors, the IK family and its
//! steps, the second order, as MathML Core; the pictures as inline SVG; the numbers of
//! `stats`.
//!
//! One module per section or picture, in the page's order:
//! [`robot`] (the table as read, the chain, the snaps), [`formulas`] (FK, Jacobian, det
//! and singular factors, second order), [`ik`] (the family, its steps, the solutions
//! of one pose), [`stick_figures`] (those solutions drawn in two views),
//! [`singularity_map`] (|det J| over two joints), [`trajectory`] (a quintic between two
//! solutions), [`reach`] (the reachability map's plane through the base, with
//! `--reach`), [`stats`] (operation counts and engine time). [`html`] is the page
//! around them, [`svg`] the drawing helpers, [`frames`] the joint positions drawn.
//! The formulas are printed by `kinegen_core::emit::mathml` (the page only arranges).

pub mod formulas;
pub mod frames;
pub mod html;
pub mod ik;
pub mod reach;
pub mod robot;
pub mod singularity_map;
pub mod stats;
pub mod stick_figures;
pub mod svg;
pub mod trajectory;

use std::io::Write;
use std::path::Path;

use kinegen_core::{Chain, Derived};

use crate::error::CliError;

/// The page of a chain from what [`crate::stats::measured`] gives (its derivation,
/// determinants, operation counts and engine time); `map` its reachability map where
/// one was asked for (or why none).
pub fn page(
    chain: &Chain,
    measured: &crate::stats::Measured,
    map: Option<&Result<crate::reach::Map, String>>,
) -> String {
    let crate::stats::Measured {
        derived,
        dets,
        stats,
    } = measured;
    let solutions = ik::Solutions::of(chain, derived);
    let mut sections = vec![
        robot::section(chain),
        formulas::first_order(chain, derived, dets),
        formulas::singular_factors(dets),
        singularity_map::section(chain, derived, dets, &solutions),
        ik::section(chain, derived, &solutions),
        stick_figures::section(chain, &solutions),
        trajectory::section(chain, &solutions),
        formulas::second_order(chain, derived),
        reach::section(map),
    ];
    sections.push(stats::section(chain, stats, &dets.missing));
    html::page(chain, &sections)
}

/// Build the report of `chain` and write it to `output` (default `<name>.html` in the
/// current directory), through a temporary file renamed into place: a failure leaves
/// no partial page. With `reach`, the reachability map at that voxel spacing
/// (Reuleaux's cube and 50 poses per voxel, every core) is on the page. Returns the line
/// to print.
pub fn run(
    chain: &Chain,
    options: &kinegen_core::Options,
    output: Option<&Path>,
    reach: Option<f64>,
) -> Result<String, CliError> {
    if let Some(r) = reach {
        crate::reach::grid::check_resolution(r)
            .map_err(|e| CliError::Usage(e.to_string().replacen("--resolution", "--reach", 1)))?;
    }
    let default = format!("{}.html", file_stem(&chain.name));
    let path = output.map_or_else(|| Path::new(&default).to_path_buf(), Path::to_path_buf);
    let measured = crate::stats::measured(chain, options);
    let map = reach.map(|r| reach_map(chain, &measured.derived, r));
    let text = page(chain, &measured, map.as_ref());
    crate::reach::write_atomically(&path, |f| {
        f.write_all(text.as_bytes()).map_err(|e| e.to_string())
    })?;
    Ok(format!("wrote {} ({} bytes)\n", path.display(), text.len()))
}

/// The map `kinegen reach --resolution r` computes with its other options at their
/// defaults, or why there is none (a robot without a closed-form IK).
fn reach_map(chain: &Chain, derived: &Derived, r: f64) -> Result<crate::reach::Map, String> {
    let settings = crate::reach::Settings {
        grid: crate::reach::Grid::reuleaux(r).map_err(|e| e.to_string())?,
        orientations: crate::reach::Orientations::parse(crate::reach::DEFAULT_ORIENTATIONS)
            .map_err(|e| e.to_string())?,
        free_samples: crate::reach::DEFAULT_FREE_SAMPLES,
        skip: true,
        threads: None,
        progress: false,
        roll_symmetry: true,
    };
    crate::reach::map::compute(chain, derived, &settings).map_err(|e| e.to_string())
}

/// `UR5` → `ur5`, `PUMA 560` → `puma_560`: a file name from a robot's name.
fn file_stem(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() {
        "report".into()
    } else {
        s
    }
}
