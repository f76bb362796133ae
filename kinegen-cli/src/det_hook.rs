//! The one place the CLI gets Jacobian determinants from the engine
//! ([`kinegen_core::Derived::det`]): the square 6×6 world Jacobian's, or the square task
//! Jacobian's, or why there is none.

use kinegen_core::algebra::graph::Id;
use kinegen_core::kinematics::det::meaning::meaning;
use kinegen_core::kinematics::det::structural::square_rows;
use kinegen_core::{Chain, Derived};

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
    /// What its zero set is on the arm: the relations of the axes that hold there and
    /// the joints that can then move without moving the tool
    /// ([`kinegen_core::kinematics::det::meaning`]).
    pub meaning: String,
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

/// The determinants of `chain` from the engine's results.
pub fn determinants(chain: &Chain, derived: &Derived) -> Determinants {
    let Some(rows) = square_rows(chain) else {
        return Determinants {
            det: None,
            det_task: None,
            missing: "not available: the Jacobian is not square (see manipulability)".into(),
        };
    };
    match &derived.det {
        Some(Ok(d)) => {
            let det = Determinant {
                node: d.node,
                text: d.text.clone(),
                latex: d.latex.clone(),
                factors: d
                    .factors
                    .iter()
                    .map(|f| Factor {
                        text: f.text.clone(),
                        latex: f.latex.clone(),
                        power: f.power,
                        joints: f.joints.clone(),
                        meaning: meaning(chain, &derived.model.sym, &d.rows, f),
                    })
                    .collect(),
            };
            // The 6×6 world Jacobian, or the square task Jacobian (its rows).
            let full = rows.len() == 6 && rows == (0..6).collect::<Vec<_>>();
            let task_square = chain.task.as_ref().is_some_and(|t| t.len() == chain.dof());
            // What a missing full det J says when only the task rows are square.
            let missing = if full {
                String::new()
            } else {
                "not available: the 6×N Jacobian is not square (see manipulability)".into()
            };
            Determinants {
                det: full.then(|| det.clone()),
                det_task: task_square.then_some(det),
                missing,
            }
        }
        Some(Err(why)) => Determinants {
            det: None,
            det_task: None,
            missing: format!("not available: {why}"),
        },
        None => Determinants {
            det: None,
            det_task: None,
            missing: "not available: the Jacobian is not square (see manipulability)".into(),
        },
    }
}
