//! The one place the CLI gets Jacobian determinants from the engine.
//!
//! HOOK(issue 3): the closed-form determinant is being added to `kinegen_core::model`
//! (`Model::determinant`). Until it lands, [`determinants`] returns no determinant and
//! the reason, and every consumer prints `null` / "not available": `show --what det`,
//! `show --what singularities`, `eval`'s `det` and `det_task`, `stats`' `det`. To
//! connect it, fill [`Determinants::det`] (square 6×6 world Jacobian) and
//! [`Determinants::det_task`] (square task Jacobian) here; nothing else changes.

use kinegen_core::graph::Id;
use kinegen_core::model::Model;
use kinegen_core::Robot;

/// A closed-form determinant, as the CLI shows it.
#[derive(Clone, Debug)]
pub struct Determinant {
    /// The node computing the whole determinant (in the model's graph).
    pub node: Id,
    /// Plain text (`a2*a3*sin(q3)*…`).
    pub text: String,
    /// LaTeX.
    pub latex: String,
    /// The non-constant factors: the Jacobian is singular where one of them is zero.
    pub factors: Vec<Factor>,
}

/// One factor of a determinant.
#[derive(Clone, Debug)]
pub struct Factor {
    /// Plain text (`sin(q3)`).
    pub text: String,
    /// LaTeX.
    pub latex: String,
    /// Multiplicity in the determinant.
    pub power: u32,
    /// Joints it depends on (1-based).
    pub joints: Vec<usize>,
}

/// The determinants of a robot, where the engine has them.
#[derive(Clone, Debug, Default)]
pub struct Determinants {
    /// det J of the 6×6 world-frame Jacobian (six-joint robots).
    pub det: Option<Determinant>,
    /// det of the task Jacobian (when its rows make it square).
    pub det_task: Option<Determinant>,
    /// Why a determinant is missing (shown instead of it).
    pub missing: String,
}

/// The determinants of `robot`. Takes the model mutably: the engine adds the
/// determinant's nodes to the model's graph, so they evaluate like every other output.
pub fn determinants(robot: &Robot, model: &mut Model) -> Determinants {
    let Some(rows) = kinegen_core::det::square_rows(robot) else {
        return Determinants {
            det: None,
            det_task: None,
            missing: "not available: the Jacobian is not square (see manipulability)".into(),
        };
    };
    match model.determinant(robot) {
        Ok(d) => {
            let det = Determinant {
                node: d.node,
                text: d.text,
                latex: d.latex,
                factors: d
                    .factors
                    .into_iter()
                    .map(|f| Factor {
                        text: f.text,
                        latex: f.latex,
                        power: f.power,
                        joints: f.joints,
                    })
                    .collect(),
            };
            // The 6×6 world Jacobian, or the square task Jacobian (its rows).
            let full = rows.len() == 6 && rows == (0..6).collect::<Vec<_>>();
            let task_square = robot.task.as_ref().is_some_and(|t| t.len() == robot.dof());
            Determinants {
                det: full.then(|| det.clone()),
                det_task: task_square.then_some(det),
                missing: String::new(),
            }
        }
        Err(why) => Determinants {
            det: None,
            det_task: None,
            missing: format!("not available: {why}"),
        },
    }
}
