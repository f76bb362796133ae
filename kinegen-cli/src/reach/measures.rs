//! What each IK solution of a map is measured by: its manipulability and the values of
//! the determinant's singular factors that depend on the joints (`sin(q5)`, the elbow's
//! `a2·c2 + a3·c23 + d5·s234`), all from one register program over the engine's nodes.

use crate::eval::LANES_FROM;
use kinegen_core::kinematics::program::{Program, LANES};
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
    lane_registers: Vec<[f64; LANES]>,
    lane_out: Vec<[f64; LANES]>,
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

    /// Registers for [`Measures::eval_each`].
    pub fn scratch(&self) -> Scratch {
        Scratch {
            registers: self.program.registers(),
            out: vec![0.0; self.program.outputs()],
            lane_registers: self.program.lane_registers(),
            lane_out: vec![[0.0; LANES]; self.program.outputs()],
        }
    }

    /// The manipulability at `q` and the factors' values.
    fn eval<'s>(&self, q: &[f64], s: &'s mut Scratch) -> (f64, &'s [f64]) {
        // A measure needs no last bit: the faster sine and cosine of generated code.
        self.program
            .eval_with(q, &mut s.registers, &mut s.out, kinegen::math::sin_cos_n);
        self.read(&mut s.out)
    }

    /// The manipulability and the factors' values at each of the joint vectors `qs`
    /// holds (`n` values each, one after the other), `f` called with each one's in order:
    /// [`LANES`] at a time through the program's lanes (`eval_lanes`, AVX2 sines where
    /// the CPU has it), with the bits one run per vector gives.
    pub fn eval_each(&self, qs: &[f64], n: usize, s: &mut Scratch, mut f: impl FnMut(f64, &[f64])) {
        let count = qs.len() / n.max(1);
        if count < LANES_FROM {
            for q in qs.chunks_exact(n) {
                let (m, values) = self.eval(q, s);
                f(m, values);
            }
            return;
        }
        let Scratch {
            out,
            lane_registers,
            lane_out,
            ..
        } = s;
        let q = |i: usize| &qs[i * n..(i + 1) * n];
        crate::eval::eval_groups(
            &self.program,
            count,
            q,
            lane_registers,
            lane_out,
            |_, len, v| {
                for l in 0..len {
                    for (o, lanes) in out.iter_mut().zip(v) {
                        *o = lanes[l];
                    }
                    let (m, values) = self.read(out);
                    f(m, values);
                }
            },
        );
    }

    /// The manipulability and the factors' values from the program's outputs.
    fn read<'s>(&self, out: &'s mut [f64]) -> (f64, &'s [f64]) {
        match self.manipulability {
            Manipulability::Det => (out[0].abs(), &out[1..]),
            Manipulability::Rows(rows, n) => {
                let j = DMatrix::from_row_slice(rows, n, &out[..rows * n]);
                let w = (&j * j.transpose()).determinant().max(0.0).sqrt();
                (w, &out[rows * n..])
            }
        }
    }
}
