//! The geometric Jacobian as straight-line code: columns `[z × (p − o); z]` for
//! revolute joints and `[z; 0]` for prismatic ones, with `z`, `o` the joint's axis
//! and a point on it and `p` the tool point, all in world coordinates.

use crate::chain::{Chain, Transform};
use crate::dh::{JointKind, Robot};
use crate::graph::{Graph, Id};

/// A 6×N matrix of nodes, row-major (`rows[r][joint]`), rows `[vx vy vz ωx ωy ωz]`.
pub type Rows = Vec<Vec<Id>>;

/// `a × b`.
pub fn cross(g: &mut Graph, a: [Id; 3], b: [Id; 3]) -> [Id; 3] {
    let mut out = [0; 3];
    for (i, o) in out.iter_mut().enumerate() {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let x = g.mul(a[j], b[k]);
        let y = g.mul(a[k], b[j]);
        *o = g.sub(x, y);
    }
    out
}

/// The geometric Jacobian of the tool point in the world frame.
pub fn geometric(robot: &Robot, chain: &mut Chain) -> Rows {
    let n = robot.dof();
    let zero = chain.graph.int(0);
    let mut rows = vec![vec![zero; n]; 6];
    let p = chain.tool.p;
    for (i, joint) in robot.joints.iter().enumerate() {
        let (z, o) = chain.axes[i];
        let g = &mut chain.graph;
        let (lin, ang) = match joint.kind {
            JointKind::Revolute => {
                let r = [g.sub(p[0], o[0]), g.sub(p[1], o[1]), g.sub(p[2], o[2])];
                (cross(g, z, r), z)
            }
            JointKind::Prismatic => (z, [zero; 3]),
        };
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
