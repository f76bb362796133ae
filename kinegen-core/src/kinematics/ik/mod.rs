//! Closed-form inverse kinematics, planned at expansion time: the joint axes at `q = 0`
//! classified exactly ([`axes`]), the family and its derivation chosen ([`family`]; the
//! arms with fewer joints in `fewer.rs`), the plan it gives ([`mod@plan`]), and the
//! zero-configuration geometry the generated code hands to the runtime solver.

pub mod axes;
pub mod family;
mod fewer;
pub mod plan;

use crate::algebra::graph::Id;
use crate::chain::Chain;
use crate::kinematics::frames::SymbolicChain;
use crate::kinematics::transform::Transform;
use family::{plan, IkPlan};

/// What the generated `ik` needs: the plan and the geometry's nodes.
#[derive(Clone, Debug)]
pub struct IkModel {
    /// Family, locked joint, derivation.
    pub plan: IkPlan,
    /// The frames at `q = 0` (every joint at its zero): the graph of the nodes below.
    pub zero: SymbolicChain,
    /// Per joint: axis (3 nodes) then point (3 nodes); then the tool's rotation
    /// (row-major, 9) and position (3).
    pub ids: Vec<Id>,
    /// For a plan read from the tool to the base: the same, of the chain read backwards
    /// (joint `i` is joint `N − 1 − i`; its axis negated and seen from the tool at `q = 0`,
    /// the world frame as its tool), so the run time does not invert the geometry.
    pub reversed_ids: Option<Vec<Id>>,
}

/// The IK model of `chain`, or why it has none (naming the axes that break each
/// family's condition); `free`: the joint (0-based) a 7-joint arm leaves free, when the
/// user chose it (`ik_free`).
pub fn model(chain: &Chain, max_terms: usize, free: Option<usize>) -> Result<IkModel, String> {
    let plan = plan(chain, max_terms, free)?;
    let mut zero = SymbolicChain::at_zero(chain, max_terms, None);
    let ids = geometry_ids(&zero.axes, &zero.tool);
    let reversed_ids = plan.reversed.then(|| {
        let world = zero.world_from_tool();
        let g = &mut zero.graph;
        let axes: Vec<([Id; 3], [Id; 3])> = zero
            .tool_axes
            .iter()
            .rev()
            .map(|(h, p)| (h.map(|x| g.neg(x)), *p))
            .collect();
        geometry_ids(&axes, &world)
    });
    Ok(IkModel {
        plan,
        zero,
        ids,
        reversed_ids,
    })
}

/// Per joint its axis then its point, then the tool's rotation (row-major) and position:
/// the order of [`IkModel::ids`].
fn geometry_ids(axes: &[([Id; 3], [Id; 3])], tool: &Transform) -> Vec<Id> {
    let mut ids = Vec::new();
    for (h, p) in axes {
        ids.extend(h);
        ids.extend(p);
    }
    for row in tool.rows() {
        ids.extend(&row[..3]);
    }
    ids.extend(tool.p);
    ids
}

/// The zero-configuration geometry as numbers, with the chain's parameter values.
#[derive(Clone, Debug, PartialEq)]
pub struct GeometryValues {
    /// Unit joint axes.
    pub h: Vec<[f64; 3]>,
    /// A point on each axis.
    pub p: Vec<[f64; 3]>,
    /// Which joints are prismatic.
    pub prismatic: Vec<bool>,
    /// Tool rotation at `q = 0`, row-major.
    pub r_tool: [[f64; 3]; 3],
    /// Tool position at `q = 0`.
    pub p_tool: [f64; 3],
}

impl IkModel {
    /// The geometry's numeric values (what the generated `ik_geometry` returns).
    pub fn values(&self, chain: &Chain) -> GeometryValues {
        let n = chain.dof();
        let v = self.zero.eval(chain, &vec![0.0; n], &self.ids);
        let v3 = |k: usize| [v[k], v[k + 1], v[k + 2]];
        GeometryValues {
            h: (0..n).map(|i| v3(6 * i)).collect(),
            p: (0..n).map(|i| v3(6 * i + 3)).collect(),
            prismatic: chain
                .kinds()
                .map(|k| k == crate::model::robot::JointKind::Prismatic)
                .collect(),
            r_tool: [v3(6 * n), v3(6 * n + 3), v3(6 * n + 6)],
            p_tool: v3(6 * n + 9),
        }
    }
}
