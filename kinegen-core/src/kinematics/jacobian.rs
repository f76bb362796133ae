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

/// One column of a Jacobian: what a unit rate of the joint adds to the tool point's
/// linear velocity (`lin`) and to the tool frame's angular velocity (`ang`, zero for a
/// prismatic joint).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Column {
    /// `[vx vy vz]`.
    pub lin: [Id; 3],
    /// `[ωx ωy ωz]`.
    pub ang: [Id; 3],
}

/// The columns of a 6×N matrix.
pub fn columns(rows: &Rows) -> Vec<Column> {
    let n = rows.first().map_or(0, Vec::len);
    (0..n)
        .map(|i| Column {
            lin: [rows[0][i], rows[1][i], rows[2][i]],
            ang: [rows[3][i], rows[4][i], rows[5][i]],
        })
        .collect()
}

/// A 6×N matrix from its columns.
pub fn from_columns(cols: &[Column]) -> Rows {
    (0..6)
        .map(|r| {
            cols.iter()
                .map(|c| if r < 3 { c.lin[r] } else { c.ang[r - 3] })
                .collect()
        })
        .collect()
}

/// The Jacobian columns of the joints after a middle frame `k`, in frame `k`'s
/// coordinates, as [`geometric`] formed them before rotating them out: what an output
/// that is covariant under rotations (`J̇ q̇`) can be computed from in that frame.
#[derive(Clone, Debug)]
pub struct LocalColumns {
    /// `k`: the columns are those of joints `k..N` (0-based).
    pub k: usize,
    /// Frame `k` in world coordinates (`R_k`, `p_k`).
    pub frame: Transform,
    /// Columns of joints `k..N` in frame `k`.
    pub columns: Vec<Column>,
    /// The tool point in frame `k`.
    pub tool: [Id; 3],
}

impl LocalColumns {
    /// Every column of the Jacobian in frame `k`: those of joints `k..N` as built, those
    /// of the joints before `k` from their axes seen from frame `k` directly
    /// ([`SymbolicChain::in_frame`]: the links before it walked backwards), `[z × (p − o);
    /// z]` with `p` the tool point in frame `k` — so that none of them is a rotated world
    /// column, and none of their exact forms a product of two whole-chain polynomials.
    pub fn all(&self, chain: &Chain, sym: &mut SymbolicChain) -> Vec<Column> {
        if self.k == 0 {
            return self.columns.clone();
        }
        // Frame k is link frame k − 1 (0-based): `base · A1 ⋯ Ak`.
        let view = sym.in_frame(self.k - 1);
        let mut cols = columns_about(chain, &mut sym.graph, &view.axes[..self.k], self.tool);
        cols.extend_from_slice(&self.columns);
        cols
    }
}

/// Every column of the Jacobian in link frame `frames[k]` (0-based), from the chain
/// seen from there ([`SymbolicChain::in_frame`]): `[z × (p − o); z]`.
pub fn in_frame_columns(chain: &Chain, sym: &mut SymbolicChain, k: usize) -> Vec<Column> {
    let view = sym.in_frame(k);
    columns_about(chain, &mut sym.graph, &view.axes, view.tool)
}

/// The columns `[z × (p − o); z]` (prismatic `[z; 0]`) of the joints whose axes and
/// points are `axes` (the first joints of `chain`, as many as given), about the point
/// `p`, all in one frame's coordinates.
pub fn columns_about(
    chain: &Chain,
    g: &mut Graph,
    axes: &[([Id; 3], [Id; 3])],
    p: [Id; 3],
) -> Vec<Column> {
    let zero = g.int(0);
    chain
        .kinds()
        .zip(axes)
        .map(|(kind, &(z, o))| column(g, kind, z, zero, |g| moment(g, z, o, p)))
        .collect()
}

/// `z × (p − o)`: the velocity of the point `p` for a unit rate about the axis through
/// `o` along `z` (a revolute column's linear part).
fn moment(g: &mut Graph, z: [Id; 3], o: [Id; 3], p: [Id; 3]) -> [Id; 3] {
    let r = [g.sub(p[0], o[0]), g.sub(p[1], o[1]), g.sub(p[2], o[2])];
    cross(g, z, r)
}

/// A joint's column from its axis `z`: `[lin; z]` for a revolute joint (`lin` made only
/// then), `[z; 0]` for a prismatic one.
fn column(
    g: &mut Graph,
    kind: JointKind,
    z: [Id; 3],
    zero: Id,
    lin: impl FnOnce(&mut Graph) -> [Id; 3],
) -> Column {
    match kind {
        JointKind::Revolute => Column {
            lin: lin(g),
            ang: z,
        },
        JointKind::Prismatic => Column {
            lin: z,
            ang: [zero; 3],
        },
    }
}

/// The geometric Jacobian of the tool point in the world frame, and (with a middle
/// frame) the columns it was rotated from.
///
/// With a [`Pivot`] the columns of joints after frame `k` are formed in frame `k`
/// (fewer joints in every product) and rotated into the world frame at the end.
pub fn geometric(
    chain: &Chain,
    sym: &mut SymbolicChain,
    pivot: Option<&Pivot>,
) -> (Rows, Option<LocalColumns>) {
    let n = chain.dof();
    let zero = sym.graph.int(0);
    let mut rows = vec![vec![zero; n]; 6];
    let mut local_columns = pivot.map(|pv| LocalColumns {
        k: pv.k,
        frame: pv.frame,
        columns: Vec::new(),
        tool: pv.tool.p,
    });
    for (i, kind) in chain.kinds().enumerate() {
        let local = pivot.filter(|pv| i >= pv.k);
        let (z, o, p) = match local {
            Some(pv) => (pv.axes[i - pv.k].0, pv.axes[i - pv.k].1, pv.tool.p),
            None => (sym.axes[i].0, sym.axes[i].1, sym.tool.p),
        };
        let g = &mut sym.graph;
        let Column { mut lin, mut ang } = column(g, kind, z, zero, |g| moment(g, z, o, p));
        if let Some(pv) = local {
            if let Some(lc) = local_columns.as_mut() {
                lc.columns.push(Column { lin, ang });
            }
            lin = rotate(g, &pv.frame, lin);
            ang = rotate(g, &pv.frame, ang);
        }
        for k in 0..3 {
            rows[k][i] = lin[k];
            rows[k + 3][i] = ang[k];
        }
    }
    (rows, local_columns)
}

/// The geometric Jacobian in the tool frame (`diag(Rᵀ, Rᵀ) · J`), from the joint axes in
/// tool coordinates (`sym.tool_axes`): the tool point is the origin there, so a
/// revolute column is `[o × z; z]` and a prismatic one `[z; 0]`.
pub fn tool_frame(chain: &Chain, sym: &mut SymbolicChain) -> Rows {
    let g = &mut sym.graph;
    let zero = g.int(0);
    let cols: Vec<Column> = chain
        .kinds()
        .zip(&sym.tool_axes)
        .map(|(kind, &(z, o))| column(g, kind, z, zero, |g| cross(g, o, z)))
        .collect();
    from_columns(&cols)
}
