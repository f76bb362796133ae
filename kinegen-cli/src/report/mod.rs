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
//! solutions), [`stats`] (operation counts and engine time). [`html`] is the page
//! around them, [`svg`] the drawing helpers, [`frames`] the joint positions drawn.
//! The formulas are printed by `kinegen_core::emit::mathml` (the page only arranges).

pub mod formulas;
pub mod frames;
pub mod html;
pub mod ik;
pub mod robot;
pub mod singularity_map;
pub mod stats;
pub mod stick_figures;
pub mod svg;
pub mod trajectory;

use std::io::Write;
use std::path::Path;

use kinegen_core::{generate, Chain, Derived, ItemHeader};

use crate::det_hook;
use crate::error::CliError;

/// The page of `chain`; `stats` are the operation counts and engine time of its
/// generated code.
pub fn page(chain: &Chain, derived: &Derived, stats: &crate::stats::Stats) -> String {
    let dets = det_hook::determinants(chain, derived);
    let solutions = ik::Solutions::of(chain, derived);
    let mut sections = vec![
        robot::section(chain),
        formulas::first_order(chain, derived, &dets),
        formulas::singular_factors(chain, &dets),
        singularity_map::section(chain, derived, &dets, &solutions),
        ik::section(chain, derived, &solutions),
        stick_figures::section(chain, &solutions),
        trajectory::section(chain, &solutions),
        formulas::second_order(chain, derived),
    ];
    sections.push(stats::section(chain, stats, &dets.missing));
    html::page(chain, &sections)
}

/// Build the report of `chain` and write it to `output` (default `<name>.html` in the
/// current directory), through a temporary file renamed into place: a failure leaves
/// no partial page. Returns the line to print.
pub fn run(
    chain: &Chain,
    options: &kinegen_core::Options,
    output: Option<&Path>,
) -> Result<String, CliError> {
    let default = format!("{}.html", file_stem(&chain.name));
    let path = output.map_or_else(|| Path::new(&default).to_path_buf(), Path::to_path_buf);
    let t = std::time::Instant::now();
    let generated = generate(chain, &ItemHeader::public(&chain.name), options);
    let time_ms = t.elapsed().as_secs_f64() * 1e3;
    let derived = kinegen_core::derive(chain, options);
    let dets = det_hook::determinants(chain, &derived);
    let s = crate::stats::stats(chain, &derived.model, &dets, &generated, time_ms);
    let text = page(chain, &derived, &s);
    crate::reach::write_atomically(&path, |f| {
        f.write_all(text.as_bytes()).map_err(|e| e.to_string())
    })?;
    Ok(format!("wrote {} ({} bytes)\n", path.display(), text.len()))
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
