//! The geometric Jacobian as straight-line code: columns `[z × (p − o); z]` for
//! revolute joints and `[z; 0]` for prismatic ones, with `z`, `o` the joint's axis
//! and a point on it and `p` the tool point, all in world coordinates.

use crate::algebra::graph::{Graph, Id};
use crate::chain::Chain;
use crate::kinematics::frames::{Pivot, SymbolicChain};
use crate::kinematics::transform::{cross, rotate, Transform};
use crate::model::robot::JointKind;

/// A 6×N matrix of nodes, row-major (`rows[r][joint]`), rows `[vx vy vz ωx ωy ωz]`.
pub type Rows = Vec<Vec<Id>>;

/// The geometric Jacobian of the tool point in the world frame.
///
/// With a [`Pivot`] the columns of joints after frame `k` are formed in frame `k`
/// (fewer joints in every product) and rotated into the world frame at the end.
pub fn geometric(chain: &Chain, sym: &mut SymbolicChain, pivot: Option<&Pivot>) -> Rows {
    let n = chain.dof();
    let zero = sym.graph.int(0);
    let mut rows = vec![vec![zero; n]; 6];
    for (i, kind) in chain.kinds().enumerate() {
        let local = pivot.filter(|pv| i >= pv.k);
        let (z, o, p) = match local {
            Some(pv) => (pv.axes[i - pv.k].0, pv.axes[i - pv.k].1, pv.tool.p),
            None => (sym.axes[i].0, sym.axes[i].1, sym.tool.p),
        };
        let g = &mut sym.graph;
        let (mut lin, mut ang) = match kind {
            JointKind::Revolute => {
                let r = [g.sub(p[0], o[0]), g.sub(p[1], o[1]), g.sub(p[2], o[2])];
                (cross(g, z, r), z)
            }
            JointKind::Prismatic => (z, [zero; 3]),
        };
        if let Some(pv) = local {
            lin = rotate(g, &pv.frame, lin);
            ang = rotate(g, &pv.frame, ang);
        }
        for k in 0..3 {
            rows[k][i] = lin[k];
            rows[k + 3][i] = ang[k];
        }
    }
    rows
}

/// `diag(Rᵀ, Rᵀ) · J`: the same Jacobian expressed in the frame `t` (the tool frame).
pub fn rotate_into(g: &mut Graph, t: &Transform, j: &Rows) -> Rows {
    let n = j[0].len();
    let mut out = vec![vec![0; n]; 6];
    for col in 0..n {
        for block in [0, 3] {
            for (r, row) in out.iter_mut().skip(block).take(3).enumerate() {
                // (Rᵀ v)_r = column r of R · v
                let terms: Vec<Id> = (0..3)
                    .map(|k| g.mul(t.cols[r][k], j[block + k][col]))
                    .collect();
                row[col] = g.sum(&terms);
            }
        }
    }
    out
}
