//! `kinegen eval`: numeric values of the generated formulas at a configuration.
//!
//! Values come from [`Model::eval`], which evaluates the very nodes the generated Rust
//! is printed from, so they are what the generated functions return (up to the order
//! of floating-point operations).

use std::fmt::Write;

use kinegen_core::algebra::graph::Id;
use kinegen_core::kinematics::model::Model;
use kinegen_core::kinematics::program::{Program, LANES};
use kinegen_core::{Chain, Derived};
use nalgebra::DMatrix;
use serde_json::{json, Value};

use crate::det_hook::Determinants;
use crate::error::CliError;

/// Parse `--q 0.1,0.2,…`: exactly one finite number per joint.
pub fn parse_q(text: &str, dof: usize) -> Result<Vec<f64>, CliError> {
    parse_joint_values(text, dof, "--q")
}

/// Parse a joint vector given to `flag` (`--q`, `--qd`): exactly one finite number per
/// joint.
pub fn parse_joint_values(text: &str, dof: usize, flag: &str) -> Result<Vec<f64>, CliError> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let mut q = Vec::with_capacity(parts.len());
    for (i, p) in parts.iter().enumerate() {
        match p.parse::<f64>() {
            Ok(x) if x.is_finite() => q.push(x),
            Ok(_) => {
                return Err(CliError::Usage(format!(
                    "{flag}: joint value {} `{p}` is not a finite number",
                    i + 1
                )))
            }
            Err(_) => {
                return Err(CliError::Usage(format!(
                    "{flag}: joint value {} `{p}` is not a number",
                    i + 1
                )))
            }
        }
    }
    if q.len() != dof {
        return Err(CliError::Usage(format!(
            "{flag}: the robot has {dof} joints but {} joint values were given",
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
    /// The second-order values.
    pub second: SecondOrderValues,
}

/// What `eval` reports of the second-order outputs.
#[derive(Clone, Debug)]
pub struct SecondOrderValues {
    /// `H[j][row][col] = ∂J[row][col]/∂q_j`, N×6×N.
    pub hessian: Vec<Vec<Vec<f64>>>,
    /// `J̇` (6×N), with `--qd`.
    pub jacobian_dot: Option<Vec<Vec<f64>>>,
    /// `J̇ q̇` (6), with `--qd`.
    pub jdot_qdot: Option<Vec<f64>>,
    /// `∂det/∂q` where the engine has the closed-form determinant.
    pub det_gradient: Option<Vec<f64>>,
    /// `∂m/∂q` of [`Values::manipulability`] (the full 6×N Jacobian; 0 for N < 6, where
    /// that is identically 0).
    pub manipulability_gradient: Vec<f64>,
    /// `∂m/∂q` of [`Values::manipulability_task`], with task rows.
    pub manipulability_task_gradient: Option<Vec<f64>>,
}

/// Yoshikawa's manipulability of the given rows (see [`kinegen_core::numeric::manipulability`]).
fn manipulability(rows: &[Vec<f64>], dof: usize) -> f64 {
    let m = nalgebra::DMatrix::from_fn(rows.len(), dof, |r, c| rows[r][c]);
    kinegen_core::numeric::manipulability(&m)
}

fn rows(model: &Model, chain: &Chain, q: &[f64], rows: &[Vec<Id>]) -> Vec<Vec<f64>> {
    rows.iter().map(|r| model.eval(chain, q, r)).collect()
}

/// Evaluate every output at `q` and, where given, the joint rates `qd` (lengths
/// already checked).
pub fn values(
    chain: &Chain,
    derived: &Derived,
    dets: &Determinants,
    q: &[f64],
    qd: Option<&[f64]>,
) -> Values {
    let model = &derived.model;
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
        second: second_order(chain, derived, q, qd, &jacobian),
        jacobian,
        jacobian_ee,
        task_jacobian,
    }
}

/// The second-order values at `q` (and `qd`), `jacobian` the values of J there.
fn second_order(
    chain: &Chain,
    derived: &Derived,
    q: &[f64],
    qd: Option<&[f64]>,
    jacobian: &[Vec<f64>],
) -> SecondOrderValues {
    let (model, s) = (&derived.model, &derived.second);
    let n = chain.dof();
    let (hessian, jacobian_dot, jdot_qdot) = if s.at_run_time.is_some() {
        // Left to run time: what the generated methods compute from J's columns.
        let hessian = hessian_of(jacobian);
        let jacobian_dot: Option<Vec<Vec<f64>>> = qd.map(|qd| {
            (0..6)
                .map(|r| {
                    (0..n)
                        .map(|i| (0..n).map(|k| hessian[k][r][i] * qd[k]).sum())
                        .collect()
                })
                .collect()
        });
        let jdot_qdot = jacobian_dot.as_ref().zip(qd).map(|(jd, qd)| {
            jd.iter()
                .map(|row: &Vec<f64>| row.iter().zip(qd).map(|(a, b)| a * b).sum())
                .collect()
        });
        (hessian, jacobian_dot, jdot_qdot)
    } else {
        let hessian = s.hessian.iter().map(|h| rows(model, chain, q, h)).collect();
        let jacobian_dot = qd.map(|qd| {
            s.jacobian_dot
                .iter()
                .map(|r| model.eval_with_rates(chain, q, Some(qd), r))
                .collect()
        });
        let jdot_qdot = qd.map(|qd| model.eval_with_rates(chain, q, Some(qd), &s.jdot_qdot));
        (hessian, jacobian_dot, jdot_qdot)
    };
    let det_gradient = match &derived.det_gradient {
        Some(Ok(g)) => Some(model.eval(chain, q, &g.gradient)),
        _ => None,
    };
    // Rows `rows` of J and of every H[j], for the manipulability gradient.
    let gradient = |rows: &[usize]| {
        let pick = |m: &[Vec<f64>]| DMatrix::from_fn(rows.len(), n, |r, c| m[rows[r]][c]);
        let hs: Vec<DMatrix<f64>> = hessian.iter().map(|h| pick(h)).collect();
        kinegen_core::numeric::manipulability_gradient(&pick(jacobian), &hs)
    };
    let all: Vec<usize> = (0..6).collect();
    let manipulability_task_gradient = chain.task.as_ref().map(|t| {
        let rows: Vec<usize> = t.iter().map(|r| r.index()).collect();
        gradient(&rows)
    });
    SecondOrderValues {
        manipulability_gradient: gradient(&all),
        manipulability_task_gradient,
        hessian,
        jacobian_dot,
        jdot_qdot,
        det_gradient,
    }
}

/// `H[k] = ∂J/∂q_k` from J's values (rows `[v; ω]`), by the formulas
/// `kinegen::jacobian_rates::hessian` evaluates: `∂J_i/∂q_k = [ω_k × v_i; ω_k × ω_i]` for
/// k ≤ i, `[ω_i × v_k; 0]` for k > i.
fn hessian_of(j: &[Vec<f64>]) -> Vec<Vec<Vec<f64>>> {
    let n = j[0].len();
    let v = |i: usize| [j[0][i], j[1][i], j[2][i]];
    let w = |i: usize| [j[3][i], j[4][i], j[5][i]];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    // Column i of H[k] as (linear, angular).
    let cell = |k: usize, i: usize| {
        if k <= i {
            (cross(w(k), v(i)), cross(w(k), w(i)))
        } else {
            (cross(w(i), v(k)), [0.0; 3])
        }
    };
    (0..n)
        .map(|k| {
            let cols: Vec<_> = (0..n).map(|i| cell(k, i)).collect();
            (0..6)
                .map(|r| {
                    cols.iter()
                        .map(|(lin, ang)| if r < 3 { lin[r] } else { ang[r - 3] })
                        .collect()
                })
                .collect()
        })
        .collect()
}

/// The JSON object: `{"fk", "jacobian", "jacobian_ee", "det", "task_jacobian",
/// "det_task", "manipulability", "manipulability_task", "manipulability_trans",
/// "manipulability_rot", "hessian", "jacobian_dot", "jdot_qdot", "det_gradient",
/// "manipulability_gradient", "manipulability_task_gradient"}` (`null` where a value
/// does not exist; `jacobian_dot` and `jdot_qdot` without `--qd`).
pub fn to_json(v: &Values) -> Value {
    let s = &v.second;
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
        "hessian": s.hessian,
        "jacobian_dot": s.jacobian_dot,
        "jdot_qdot": s.jdot_qdot,
        "det_gradient": s.det_gradient,
        "manipulability_gradient": s.manipulability_gradient,
        "manipulability_task_gradient": s.manipulability_task_gradient,
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
    second_order_table(&mut s, chain, &v.second, missing);
    s
}

fn vector(s: &mut String, title: &str, x: &[f64]) {
    let cells: Vec<String> = x.iter().map(|x| format!("{x:>12.6}")).collect();
    let _ = writeln!(s, "{title:<30} {}", cells.join(" "));
}

/// The second-order part of [`to_table`].
fn second_order_table(s: &mut String, chain: &Chain, v: &SecondOrderValues, missing: &str) {
    let rows6 = ["vx", "vy", "vz", "ωx", "ωy", "ωz"];
    for (j, h) in v.hessian.iter().enumerate() {
        matrix(s, &format!("\nhessian H[{j}] = ∂J/∂q{}", j + 1), &rows6, h);
    }
    match (&v.jacobian_dot, &v.jdot_qdot) {
        (Some(jd), Some(a)) => {
            matrix(s, "\njacobian_dot (world frame)", &rows6, jd);
            s.push('\n');
            vector(s, "jdot_qdot", a);
        }
        _ => {
            let _ = writeln!(
                s,
                "\njacobian_dot, jdot_qdot: give the joint rates with --qd"
            );
        }
    }
    match &v.det_gradient {
        Some(g) => vector(s, "det_gradient", g),
        None => {
            let _ = writeln!(s, "{:<30} {missing}", "det_gradient");
        }
    }
    vector(s, "manipulability_gradient", &v.manipulability_gradient);
    if let (Some(g), Some(_)) = (&v.manipulability_task_gradient, &chain.task) {
        vector(s, "manipulability_task_gradient", g);
    }
}

/// Fewer joint vectors than this are evaluated one by one ([`Program::eval_with`]): one
/// run of the program's [`LANES`] costs more than one or two single runs.
pub const LANES_FROM: usize = 3;

/// [`Program::eval_lanes`] with the sines and cosines four lanes at a time where the CPU
/// has AVX2 ([`kinegen::math::sin_cos_n_avx2`], inlined into the program's AVX2 build),
/// else [`kinegen::math::sin_cos_n`]: the same bits either way. What the CLI's residuals
/// and the Python module's batches evaluate.
pub fn eval_lanes(
    program: &Program,
    q: [&[f64]; LANES],
    registers: &mut [[f64; LANES]],
    out: &mut [[f64; LANES]],
) {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU has AVX2 (asked just now), so does the program's build that
        // `eval_lanes` picks on the same question.
        let sin_cos = |x| unsafe { kinegen::math::sin_cos_n_avx2(x) };
        return program.eval_lanes(q, registers, out, sin_cos);
    }
    program.eval_lanes(q, registers, out, kinegen::math::sin_cos_n)
}

/// [`eval_lanes`] over `count` joint vectors (`q(i)`), [`LANES`] at a time — a short
/// last group repeats its last vector in the lanes left over — calling `f(first, len,
/// out)` for each group in order: vectors `first..first + len` are lanes `0..len` of
/// `out`.
pub fn eval_groups<'q>(
    program: &Program,
    count: usize,
    q: impl Fn(usize) -> &'q [f64],
    registers: &mut [[f64; LANES]],
    out: &mut [[f64; LANES]],
    mut f: impl FnMut(usize, usize, &[[f64; LANES]]),
) {
    for first in (0..count).step_by(LANES) {
        let len = LANES.min(count - first);
        let lanes: [&[f64]; LANES] = core::array::from_fn(|l| q(first + l.min(len - 1)));
        eval_lanes(program, lanes, registers, out);
        f(first, len, out);
    }
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
