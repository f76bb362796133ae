//! `kinegen eval`: numeric values of the generated formulas at a configuration.
//!
//! Values come from [`Model::eval`], which evaluates the very nodes the generated Rust
//! is printed from, so they are what the generated functions return (up to the order
//! of floating-point operations).

use std::fmt::Write;

use kinegen_core::algebra::graph::Id;
use kinegen_core::kinematics::model::Model;
use kinegen_core::Chain;
use serde_json::{json, Value};

use crate::det_hook::Determinants;
use crate::error::CliError;

/// Parse `--q 0.1,0.2,…`: exactly one finite number per joint.
pub fn parse_q(text: &str, dof: usize) -> Result<Vec<f64>, CliError> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let mut q = Vec::with_capacity(parts.len());
    for (i, p) in parts.iter().enumerate() {
        match p.parse::<f64>() {
            Ok(x) if x.is_finite() => q.push(x),
            Ok(_) => {
                return Err(CliError::Usage(format!(
                    "--q: joint value {} `{p}` is not a finite number",
                    i + 1
                )))
            }
            Err(_) => {
                return Err(CliError::Usage(format!(
                    "--q: joint value {} `{p}` is not a number",
                    i + 1
                )))
            }
        }
    }
    if q.len() != dof {
        return Err(CliError::Usage(format!(
            "--q: the robot has {dof} joints but {} joint values were given",
            q.len()
        )));
    }
    Ok(q)
}

/// Everything `eval` reports.
#[derive(Clone, Debug)]
pub struct Values {
    /// Tool pose, 4×4.
    pub fk: Vec<Vec<f64>>,
    /// World-frame Jacobian, 6×N.
    pub jacobian: Vec<Vec<f64>>,
    /// Tool-frame Jacobian, 6×N.
    pub jacobian_ee: Vec<Vec<f64>>,
    /// Task Jacobian rows, if the robot has a task.
    pub task_jacobian: Option<Vec<Vec<f64>>>,
    /// det J, where the engine has it.
    pub det: Option<f64>,
    /// det of the task Jacobian, where the engine has it.
    pub det_task: Option<f64>,
    /// Yoshikawa's `√det(J Jᵀ)` of the full 6×N Jacobian (0 for N < 6: it cannot move
    /// in all six directions) — the Robotics Toolbox's `manipulability(q)`.
    pub manipulability: f64,
    /// `√det(Jt Jtᵀ)` of the task Jacobian, if the robot has task rows.
    pub manipulability_task: Option<f64>,
    /// Of the linear rows `[vx vy vz]` (`axes="trans"`).
    pub manipulability_trans: f64,
    /// Of the angular rows `[ωx ωy ωz]` (`axes="rot"`).
    pub manipulability_rot: f64,
}

/// Yoshikawa's manipulability of the given rows (see [`kinegen_core::numeric::manipulability`]).
fn manipulability(rows: &[Vec<f64>], dof: usize) -> f64 {
    let m = nalgebra::DMatrix::from_fn(rows.len(), dof, |r, c| rows[r][c]);
    kinegen_core::numeric::manipulability(&m)
}

fn rows(model: &Model, chain: &Chain, q: &[f64], rows: &[Vec<Id>]) -> Vec<Vec<f64>> {
    rows.iter().map(|r| model.eval(chain, q, r)).collect()
}

/// Evaluate every output at `q` (length already checked).
pub fn values(chain: &Chain, model: &Model, dets: &Determinants, q: &[f64]) -> Values {
    let mut fk: Vec<Vec<f64>> = model
        .fk_rows
        .iter()
        .map(|r| model.eval(chain, q, r))
        .collect();
    fk.push(vec![0.0, 0.0, 0.0, 1.0]);
    let jacobian = rows(model, chain, q, &model.jacobian);
    let jacobian_ee = rows(model, chain, q, &model.jacobian_ee);
    let task_jacobian = chain
        .task
        .as_ref()
        .map(|_| rows(model, chain, q, &model.task));
    let one = |d: &Option<crate::det_hook::Determinant>| {
        d.as_ref().map(|d| model.eval(chain, q, &[d.node])[0])
    };
    let n = chain.dof();
    Values {
        fk,
        det: one(&dets.det),
        det_task: one(&dets.det_task),
        manipulability: manipulability(&jacobian, n),
        manipulability_task: task_jacobian.as_ref().map(|t| manipulability(t, n)),
        manipulability_trans: manipulability(&jacobian[..3], n),
        manipulability_rot: manipulability(&jacobian[3..], n),
        jacobian,
        jacobian_ee,
        task_jacobian,
    }
}

/// The JSON object: `{"fk", "jacobian", "jacobian_ee", "det", "task_jacobian",
/// "det_task", "manipulability", "manipulability_task", "manipulability_trans",
/// "manipulability_rot"}` (`null` where a value does not exist).
pub fn to_json(v: &Values) -> Value {
    json!({
        "fk": v.fk,
        "jacobian": v.jacobian,
        "jacobian_ee": v.jacobian_ee,
        "det": v.det,
        "task_jacobian": v.task_jacobian,
        "det_task": v.det_task,
        "manipulability": v.manipulability,
        "manipulability_task": v.manipulability_task,
        "manipulability_trans": v.manipulability_trans,
        "manipulability_rot": v.manipulability_rot,
    })
}

fn matrix(s: &mut String, title: &str, labels: &[&str], m: &[Vec<f64>]) {
    let _ = writeln!(s, "{title}");
    for (i, row) in m.iter().enumerate() {
        let label = labels.get(i).copied().unwrap_or("");
        let cells: Vec<String> = row.iter().map(|x| format!("{x:>12.6}")).collect();
        let _ = writeln!(s, "  {label:>3} {}", cells.join(" "));
    }
}

/// A readable table of the values.
pub fn to_table(chain: &Chain, q: &[f64], v: &Values, missing: &str) -> String {
    let mut s = format!("{} at q = {:?}\n\n", chain.name, q);
    matrix(&mut s, "fk (tool pose T)", &[], &v.fk);
    let rows6 = ["vx", "vy", "vz", "ωx", "ωy", "ωz"];
    matrix(&mut s, "\njacobian (world frame)", &rows6, &v.jacobian);
    matrix(&mut s, "\njacobian_ee (tool frame)", &rows6, &v.jacobian_ee);
    if let (Some(t), Some(task)) = (&v.task_jacobian, &chain.task) {
        let labels: Vec<&str> = task.iter().map(|r| r.name()).collect();
        matrix(&mut s, "\ntask_jacobian", &labels, t);
    }
    s.push('\n');
    let det = |d: Option<f64>| d.map_or(missing.to_string(), |x| format!("{x:.12}"));
    let _ = writeln!(s, "det J                  {}", det(v.det));
    let _ = writeln!(s, "det J_task             {}", det(v.det_task));
    let _ = writeln!(s, "\nmanipulability √det(J Jᵀ), Yoshikawa:");
    let _ = writeln!(s, "  all rows (J)         {:.12}", v.manipulability);
    if let Some(w) = v.manipulability_task {
        let _ = writeln!(s, "  task rows (J_task)   {w:.12}");
    }
    let _ = writeln!(s, "  trans [vx vy vz]     {:.12}", v.manipulability_trans);
    let _ = writeln!(s, "  rot [ωx ωy ωz]       {:.12}", v.manipulability_rot);
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn q_is_checked_value_by_value() {
        assert_eq!(parse_q("0.1, -2,3e-1", 3).unwrap(), vec![0.1, -2.0, 0.3]);
        let e = |t: &str, n| parse_q(t, n).unwrap_err().to_string();
        assert_eq!(e("0.1,x", 2), "--q: joint value 2 `x` is not a number");
        assert_eq!(e("0.1,,0.2", 3), "--q: joint value 2 `` is not a number");
        assert_eq!(
            e("nan,0", 2),
            "--q: joint value 1 `nan` is not a finite number"
        );
        assert_eq!(
            e("0.1,0.2", 6),
            "--q: the robot has 6 joints but 2 joint values were given"
        );
    }
}
