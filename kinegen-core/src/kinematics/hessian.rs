//! The kinematic Hessian `H[j] = ∂J/∂q_j` of the world-frame geometric Jacobian, formed
//! from the Jacobian's own columns with cross products (Haviland & Corke, "Manipulator
//! Differential Kinematics", arXiv 2207.01794; the Robotics Toolbox's `(n, 6, n)` layout).
//!
//! Column `i` of `J` is `[v_i; ω_i]` (`ω_i = 0` for a prismatic joint). A rate of joint
//! `j` turns (about `ω_j`) or shifts everything after it rigidly, so for `j ≤ i` joint
//! `i`'s axis and the tool point turn together and
//!
//! ```text
//! ∂J_i/∂q_j = [ω_j × v_i; ω_j × ω_i]        (j ≤ i)
//! ```
//!
//! while for `j > i` joint `j` moves the tool point but not joint `i`'s axis:
//!
//! ```text
//! ∂J_i/∂q_j = [ω_i × v_j; 0]                (j > i)
//! ```
//!
//! The linear rows are symmetric, `H[j][r][i] = H[i][r][j]` for `r < 3` (they are second
//! derivatives of the tool position, which commute); the angular rows are not
//! (`∂ω_i/∂q_j = ω_j × ω_i` for `j < i`, `0` for `j > i`). One node serves both halves
//! of the linear part. Flipped joints (`Motion.sign = −1`) need nothing: their column
//! already carries `−axis`, which is the axis their positive rate turns about.

use crate::algebra::graph::Graph;
use crate::kinematics::jacobian::{from_columns, Column, Rows};
use crate::kinematics::transform::cross;

/// `H[j]` for every joint `j`: the 6×N matrix `∂J/∂q_j`, rows `[vx vy vz ωx ωy ωz]`, in
/// the frame the columns `cols` are expressed in (the world frame for the Jacobian's).
pub fn hessian(g: &mut Graph, cols: &[Column]) -> Vec<Rows> {
    let n = cols.len();
    let zero = g.int(0);
    let none = Column {
        lin: [zero; 3],
        ang: [zero; 3],
    };
    let mut h = vec![vec![none; n]; n];
    for i in 0..n {
        for j in 0..=i {
            let lin = cross(g, cols[j].ang, cols[i].lin);
            let ang = cross(g, cols[j].ang, cols[i].ang);
            h[j][i] = Column { lin, ang };
            // ∂J_j/∂q_i for i > j: the same linear part, no angular part.
            if j < i {
                h[i][j] = Column {
                    lin,
                    ang: [zero; 3],
                };
            }
        }
    }
    h.iter().map(|hj| from_columns(hj)).collect()
}
