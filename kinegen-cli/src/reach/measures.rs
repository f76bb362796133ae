//! What each IK solution of a map is measured by: its manipulability and the values of
//! the determinant's singular factors that depend on the joints (`sin(q5)`, the elbow's
//! `a2·c2 + a3·c23 + d5·s234`), all from one register program over the engine's nodes.

use kinegen_core::kinematics::program::Program;
use kinegen_core::{Chain, Derived};
use nalgebra::DMatrix;

/// The program and how to read its outputs.
#[derive(Clone, Debug)]
pub struct Measures {
    program: Program,
    /// Outputs before the factors: 1 (`det J`) or the Jacobian's `rows × n` entries.
    manipulability: Manipulability,
    /// The singular factors measured (text), in the determinant's order.
    pub names: Vec<String>,
}

#[derive(Clone, Copy, Debug)]
enum Manipulability {
    /// The closed-form determinant of the square Jacobian: `|det J|`.
    Det,
    /// `√det(J Jᵀ)` of these rows of the Jacobian (`rows × n`), in numbers.
    Rows(usize, usize),
}

/// Registers of [`Measures`], one set per thread.
#[derive(Clone, Debug)]
pub struct Scratch {
    registers: Vec<f64>,
    out: Vec<f64>,
}

impl Measures {
    /// The measures of `chain`: `|det J|` from the closed-form determinant where the
    /// engine has one (6×6 or square task Jacobian), else `√det(J Jᵀ)` of the Jacobian's
    /// (task) rows; the factors that depend on a joint (constant ones never vanish).
    pub fn of(chain: &Chain, derived: &Derived) -> Measures {
        let model = &derived.model;
        let mut ids = Vec::new();
        let mut names = Vec::new();
        let manipulability = match &derived.det {
            Some(Ok(det)) => {
                ids.push(det.node);
                for f in det.factors.iter().filter(|f| !f.joints.is_empty()) {
                    ids.push(f.node);
                    names.push(f.text.clone());
                }
                Manipulability::Det
            }
            _ => {
                let rows = if model.task.is_empty() {
                    &model.jacobian
                } else {
                    &model.task
                };
                ids.extend(rows.iter().flatten());
                Manipulability::Rows(rows.len(), chain.dof())
            }
        };
        Measures {
            program: Program::new(&model.sym, chain, &ids),
            manipulability,
            names,
        }
    }

    /// Whether a measure depends on joint `j`.
    pub fn reads_joint(&self, j: usize) -> bool {
        self.program.reads_joint(j)
    }

    /// Registers for [`Measures::eval`].
    pub fn scratch(&self) -> Scratch {
        Scratch {
            registers: self.program.registers(),
            out: vec![0.0; self.program.outputs()],
        }
    }

    /// The manipulability at `q` and the factors' values.
    pub fn eval<'s>(&self, q: &[f64], s: &'s mut Scratch) -> (f64, &'s [f64]) {
        // A measure needs no last bit: the faster sine and cosine of generated code.
        self.program
            .eval_with(q, &mut s.registers, &mut s.out, kinegen::math::sin_cos_n);
        match self.manipulability {
            Manipulability::Det => (s.out[0].abs(), &s.out[1..]),
            Manipulability::Rows(rows, n) => {
                let j = DMatrix::from_row_slice(rows, n, &s.out[..rows * n]);
                let w = (&j * j.transpose()).determinant().max(0.0).sqrt();
                (w, &s.out[rows * n..])
            }
        }
    }
}
