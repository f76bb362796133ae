//! Time derivatives of the Jacobian along a joint motion with rates `q̇`: `J̇`, the bias
//! acceleration `J̇ q̇`, and the derivative of the tool-frame Jacobian — accumulated over
//! the joints from the Jacobian's columns, never by forming a Hessian.
//!
//! With `w_i = ω_i q̇_i` and `u_i = v_i q̇_i` (column `i` times its rate), the angular
//! velocity of link `i` is `W_i = w_1 + ⋯ + w_i` (`W_0 = 0`) and the tool point's velocity
//! due to the joints after `i` is `R_i = u_(i+1) + ⋯ + u_N`. Summing the Hessian
//! ([`crate::kinematics::hessian`]) against `q̇`:
//!
//! ```text
//! J̇_i   = [W_i × v_i + ω_i × R_i;  W_i × ω_i]
//! J̇ q̇  = [Σ_i (W_(i−1) + W_i) × u_i;  Σ_i W_(i−1) × w_i]
//! ```
//!
//! The second line is velocity/acceleration propagation with `q̈ = 0`: `Σ_i W_i × u_i`
//! turns each joint's contribution with the links before and at it, `Σ_i w_i × R_i =
//! Σ_i W_(i−1) × u_i` carries the tool point along joint `i`'s turn. Both sums are cross
//! products of vectors, so they can be formed in any frame and rotated out once
//! ([`jdot_qdot_in`], from [`crate::kinematics::jacobian::LocalColumns`]).
//!
//! The tool-frame Jacobian `J_ee = diag(Rᵀ, Rᵀ) J` (`R` the tool rotation, `Ṙ = [Ω]× R`,
//! `Ω = W_N`) has
//!
//! ```text
//! J̇_ee = diag(Rᵀ, Rᵀ) (J̇ − diag([Ω]×, [Ω]×) J),  column i: [ω_i × R_i + v_i × Ω_i⁺;  ω_i × Ω_i⁺]
//! ```
//!
//! with `Ω_i⁺ = Ω − W_i = w_(i+1) + ⋯ + w_N` and every vector of the column in the tool
//! frame (formed from `J_ee`'s own columns: no rotation): in the tool frame only the
//! joints after `i` change column `i`. This is the derivative of `jacobian_ee`; `diag(Rᵀ, Rᵀ) J̇` (what the
//! Robotics Toolbox's `hessiane` contracts to) differs from it by
//! `diag(Rᵀ, Rᵀ) diag([Ω]×, [Ω]×) J`.

use crate::algebra::graph::{Graph, Id};
use crate::kinematics::jacobian::Column;
use crate::kinematics::transform::{add, cross, rotate, scale, Transform};

/// `w_i = ω_i q̇_i` and `u_i = v_i q̇_i` for every joint.
fn rates_times_columns(g: &mut Graph, cols: &[Column], qd: &[Id]) -> Vec<Column> {
    cols.iter()
        .zip(qd)
        .map(|(c, &r)| Column {
            lin: scale(g, r, c.lin),
            ang: scale(g, r, c.ang),
        })
        .collect()
}

/// Suffix sums: `out[i] = x_(i+1) + ⋯ + x_N` (zero for the last joint).
fn after(g: &mut Graph, x: &[[Id; 3]]) -> Vec<[Id; 3]> {
    let zero = g.int(0);
    let mut out = vec![[zero; 3]; x.len()];
    let mut acc = [zero; 3];
    for i in (0..x.len()).rev() {
        out[i] = acc;
        acc = add(g, acc, x[i]);
    }
    out
}

/// `J̇` in the frame of `cols`: column `i` is `[W_i × v_i + ω_i × R_i; W_i × ω_i]`.
pub fn jacobian_dot(g: &mut Graph, cols: &[Column], qd: &[Id]) -> Vec<Column> {
    let wu = rates_times_columns(g, cols, qd);
    let u: Vec<[Id; 3]> = wu.iter().map(|c| c.lin).collect();
    let r = after(g, &u);
    let zero = g.int(0);
    let mut w = [zero; 3];
    let mut out = Vec::with_capacity(cols.len());
    for (i, c) in cols.iter().enumerate() {
        w = add(g, w, wu[i].ang);
        let turn = cross(g, w, c.lin);
        let carry = cross(g, c.ang, r[i]);
        out.push(Column {
            lin: add(g, turn, carry),
            ang: cross(g, w, c.ang),
        });
    }
    out
}

/// `J̇ q̇` in the frame of `cols`: `[Σ (W_(i−1) + W_i) × u_i; Σ W_(i−1) × w_i]`.
pub fn jdot_qdot(g: &mut Graph, cols: &[Column], qd: &[Id]) -> Column {
    let wu = rates_times_columns(g, cols, qd);
    let zero = g.int(0);
    let mut before = [zero; 3];
    let (mut lin, mut ang) = (Vec::new(), Vec::new());
    for c in &wu {
        let upto = add(g, before, c.ang);
        let both = add(g, before, upto);
        lin.push(cross(g, both, c.lin));
        ang.push(cross(g, before, c.ang));
        before = upto;
    }
    Column {
        lin: sum3(g, &lin),
        ang: sum3(g, &ang),
    }
}

/// `J̇ q̇` formed from the columns `local` of the Jacobian in a middle frame (see
/// [`crate::kinematics::jacobian::LocalColumns::all`]) and rotated out once by that frame's rotation: the same vector
/// as [`jdot_qdot`] of the world columns, since cross products commute with rotations.
pub fn jdot_qdot_in(g: &mut Graph, local: &[Column], frame: &Transform, qd: &[Id]) -> Column {
    let a = jdot_qdot(g, local, qd);
    Column {
        lin: rotate(g, frame, a.lin),
        ang: rotate(g, frame, a.ang),
    }
}

/// `d/dt` of the tool-frame Jacobian from its own columns `ee` (`diag(Rᵀ, Rᵀ) J`):
/// column `i` is `[ω_i × R_i + v_i × Ω_i⁺; ω_i × Ω_i⁺]` with every vector in the tool
/// frame (the world-frame form rotated by `Rᵀ`, which commutes with cross products).
pub fn jacobian_ee_dot(g: &mut Graph, ee: &[Column], qd: &[Id]) -> Vec<Column> {
    let wu = rates_times_columns(g, ee, qd);
    let u: Vec<[Id; 3]> = wu.iter().map(|c| c.lin).collect();
    let w: Vec<[Id; 3]> = wu.iter().map(|c| c.ang).collect();
    let (r, omega) = (after(g, &u), after(g, &w));
    ee.iter()
        .enumerate()
        .map(|(i, c)| {
            let carry = cross(g, c.ang, r[i]);
            let turn = cross(g, c.lin, omega[i]);
            Column {
                lin: add(g, carry, turn),
                ang: cross(g, c.ang, omega[i]),
            }
        })
        .collect()
}

/// `Σ xᵢ` of 3-vectors.
fn sum3(g: &mut Graph, xs: &[[Id; 3]]) -> [Id; 3] {
    let zero = g.int(0);
    xs.iter().fold([zero; 3], |acc, &x| add(g, acc, x))
}
