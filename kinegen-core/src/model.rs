//! Everything the generated code outputs, as nodes of one shared graph.

use crate::chain::{Chain, Transform};
use crate::dh::Robot;
use crate::generate::Options;
use crate::graph::Id;
use crate::jacobian::{self, Rows};

/// The symbolic outputs of a robot.
#[derive(Clone, Debug)]
pub struct Model {
    /// The chain (graph, angles, frames).
    pub chain: Chain,
    /// Top three rows of the tool pose.
    pub fk_rows: [[Id; 4]; 3],
    /// Top three rows of every joint frame.
    pub frame_rows: Vec<[[Id; 4]; 3]>,
    /// World-frame geometric Jacobian.
    pub jacobian: Rows,
    /// Tool-frame geometric Jacobian.
    pub jacobian_ee: Rows,
    /// Task Jacobian rows (empty without task rows).
    pub task: Rows,
    /// Notes for the user (budgets hit, fallbacks).
    pub notes: Vec<String>,
}

/// Rows `[R | p]` of a transform.
pub fn rows(t: &Transform) -> [[Id; 4]; 3] {
    let mut r = [[0; 4]; 3];
    for (i, row) in r.iter_mut().enumerate() {
        for (j, e) in row.iter_mut().take(3).enumerate() {
            *e = t.r(i, j);
        }
        row[3] = t.p[i];
    }
    r
}

impl Model {
    /// Build the chain and all outputs.
    pub fn build(robot: &Robot, options: &Options) -> Model {
        let mut chain = Chain::new(robot, options.budget.max_terms());
        let fk_rows = rows(&chain.tool);
        let frame_rows = chain.frames.iter().map(rows).collect();
        let jacobian = jacobian::geometric(robot, &mut chain);
        let tool = chain.tool;
        let jacobian_ee = jacobian::rotate_into(&mut chain.graph, &tool, &jacobian);
        let task = robot
            .task
            .as_ref()
            .map(|t| t.iter().map(|r| jacobian[r.index()].clone()).collect())
            .unwrap_or_default();
        let mut notes = Vec::new();
        if chain.graph.nf_overflows > 0 {
            notes.push(format!(
                "{} expressions exceeded the normal-form budget of {} terms: they are shared structurally only",
                chain.graph.nf_overflows, chain.graph.max_terms
            ));
        }
        Model {
            chain,
            fk_rows,
            frame_rows,
            jacobian,
            jacobian_ee,
            task,
            notes,
        }
    }
}

impl Model {
    /// Values of the ring's variables at joint values `q` with the table's parameters:
    /// what the generated code computes before its first operation. Used to evaluate
    /// the symbolic outputs directly (tests, the CLI's `eval`).
    pub fn variables(&self, robot: &Robot, q: &[f64]) -> Vec<f64> {
        use crate::chain::AngleSource;
        use crate::poly::VarKind;
        let ring = &self.chain.graph.ring;
        let mut vals = vec![f64::NAN; ring.len()];
        for (v, slot) in vals.iter_mut().enumerate() {
            *slot = match ring.kind(v as u32) {
                VarKind::Joint(j) => q[*j],
                VarKind::Param(n) => robot.param_value(n),
                VarKind::Sqrt(k) => (*k as f64).sqrt(),
                VarKind::Sin(_) | VarKind::Cos(_) => continue,
            };
        }
        for a in &self.chain.angles {
            let x = match &a.source {
                AngleSource::Joint { joint, offset } => q[*joint] + robot.eval(offset),
                AngleSource::Constant(v) => robot.eval(v),
            };
            vals[a.vars.0 as usize] = x.sin();
            vals[a.vars.1 as usize] = x.cos();
        }
        vals
    }

    /// Evaluate nodes at `q`.
    pub fn eval(&self, robot: &Robot, q: &[f64], ids: &[Id]) -> Vec<f64> {
        let vals = self.variables(robot, q);
        ids.iter()
            .map(|&id| self.chain.graph.eval(id, &|v| vals[v as usize]))
            .collect()
    }
}
