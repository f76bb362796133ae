//! A [`Chain`]'s frames as straight-line code: every link frame, the tool, and each
//! joint's axis with a point on it, all as nodes of one graph.
//!
//! The chain is unrolled link by link, each elementary transform right-multiplied onto
//! the frame so far ([`crate::kinematics::transform`]); the graph folds zeros and ones
//! and shares equal values. Optionally the tail of the chain is built in a middle frame
//! ([`Pivot`]) and rotated out once at the end.

use crate::algebra::angles::{AngleDef, AngleSource};
use crate::algebra::graph::{Graph, Id};
use crate::algebra::poly::Var;
use crate::algebra::poly::VarKind;
use crate::chain::{AxisAt, Chain, Elem, Link, Motion};
use crate::kinematics::entries::Entries;
use crate::kinematics::transform::{compose, point, rotate, translate, turn, Transform};
use crate::model::options::Deadline;
use crate::model::robot::JointKind;

/// The symbolic frames of a chain and the graph they live in.
#[derive(Clone, Debug)]
pub struct SymbolicChain {
    /// The straight-line code and its ring.
    pub graph: Graph,
    /// Sine/cosine pairs, in order of first use.
    pub angles: Vec<AngleDef>,
    /// Ring variables of prismatic joints: `(joint, var)`.
    pub joint_vars: Vec<(usize, Var)>,
    /// Ring variables of named parameters: `(name, var)`.
    pub param_vars: Vec<(String, Var)>,
    /// Ring variables of joint rates `q̇_j`: `(joint, var)`, made by the outputs that
    /// read them ([`SymbolicChain::rates`]).
    pub rate_vars: Vec<(usize, Var)>,
    /// `base · A1 ⋯ Ai` for i = 1..=N.
    pub frames: Vec<Transform>,
    /// The base frame (frame 0).
    pub base: Transform,
    /// `base · A1 ⋯ AN · tool`.
    pub tool: Transform,
    /// For each joint: its axis (unit vector it turns about or slides along) and a
    /// point on it, in world coordinates.
    pub axes: Vec<([Id; 3], [Id; 3])>,
    /// The same axes and points in tool coordinates, from the chain unrolled backwards
    /// from the tool (`tool⁻¹ · A_N⁻¹ ⋯ A_i⁻¹`): joint i's entries depend on joints
    /// i..N only, which keeps the tool-frame Jacobian's exact forms small (rotating the
    /// world columns by `Rᵀ` multiplies two full-chain polynomials only for most of the
    /// product to cancel).
    pub tool_axes: Vec<([Id; 3], [Id; 3])>,
    /// Each link's steps as unrolled, and the tool's: what [`SymbolicChain::in_frame`]
    /// replays from a link frame.
    links: Vec<LinkSteps>,
    tool_steps: Vec<Step>,
    base_steps: Vec<Step>,
}

/// The chain seen from one link frame: every joint's axis and a point on it, every link
/// frame's origin and the tool point, in that frame's coordinates.
#[derive(Clone, Debug)]
pub struct FrameView {
    /// Per joint: its axis and a point on it.
    pub axes: Vec<([Id; 3], [Id; 3])>,
    /// Per link frame (`frames[j]`): its origin.
    pub origins: Vec<[Id; 3]>,
    /// The tool point.
    pub tool: [Id; 3],
}

/// The chain from a middle frame `k`: `T_k⁻¹ · T_i` for the frames after it.
///
/// Expressing the tail of the chain in frame `k` removes joints 1..k from every
/// product (for a UR arm in frame 1, the elbow plane is 2-D); the world values are
/// recovered with one rotation by `R_k` at the end. Which `k` is cheapest depends
/// on the arm, so the model tries several and counts operations.
#[derive(Clone, Debug)]
pub struct Pivot {
    /// `k`: joints `k+1..=N` (0-based `k..N`) have local axes.
    pub k: usize,
    /// `base · A1 ⋯ Ak` in world coordinates.
    pub frame: Transform,
    /// Axes and points of joints `k..N` (0-based) in frame `k`.
    pub axes: Vec<([Id; 3], [Id; 3])>,
    /// The tool in frame `k`.
    pub tool: Transform,
}

/// Which joints are variables.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Joints {
    /// All of them.
    Variable,
    /// None but `keep`: the others are at `q = 0`.
    Zero { keep: Option<usize> },
}

impl Joints {
    fn variable(self, i: usize) -> bool {
        match self {
            Joints::Variable => true,
            Joints::Zero { keep } => keep == Some(i),
        }
    }
}

/// An elementary transform with its arguments as nodes.
#[derive(Clone, Copy, Debug)]
enum Step {
    Turn { axis: usize, s: Id, c: Id },
    Move { axis: usize, d: Id },
}

impl Step {
    /// The inverse transform: the same axis, the opposite angle or length.
    fn inverse(self, g: &mut Graph) -> Step {
        match self {
            Step::Turn { axis, s, c } => Step::Turn {
                axis,
                s: g.neg(s),
                c,
            },
            Step::Move { axis, d } => Step::Move { axis, d: g.neg(d) },
        }
    }
}

/// One link's steps as [`unroll`] applied them, kept to replay the chain from another
/// frame ([`SymbolicChain::tool_axes`], [`SymbolicChain::in_frame`]).
#[derive(Clone, Debug)]
struct LinkSteps {
    before: Vec<Step>,
    motion: Step,
    after: Vec<Step>,
    /// The joint's axis (0, 1, 2 for x, y, z), whether it is read at the link frame
    /// (else just before the motion), and whether the joint runs against it.
    axis: usize,
    at_link_frame: bool,
    flip: bool,
}

/// `t` through one link's steps: the new frame, and the joint's axis and a point on it.
fn replay(g: &mut Graph, t: Transform, l: &LinkSteps) -> (Transform, ([Id; 3], [Id; 3])) {
    let mut t = apply_all(g, t, &l.before);
    let mut axis = (t.cols[l.axis], t.p);
    t = apply(g, t, l.motion);
    t = apply_all(g, t, &l.after);
    if l.at_link_frame {
        axis = (t.cols[l.axis], t.p);
    }
    if l.flip {
        // The joint runs against its axis: its velocity is along −axis.
        axis.0 = axis.0.map(|x| g.neg(x));
    }
    (t, axis)
}

/// `u` right-multiplied by the inverses of `steps`, last first: one step back along the
/// chain per step.
fn back(g: &mut Graph, u: Transform, steps: &[Step]) -> Transform {
    steps.iter().rev().fold(u, |u, s| {
        let inv = s.inverse(g);
        apply(g, u, inv)
    })
}

/// Links `links` walked backwards from the frame at their end (`u`, in the coordinates
/// wanted): each joint's axis and a point on it, and the frame before each link.
///
/// At a joint's motion `u` maps the joint's frame into the wanted coordinates; the
/// motion turns about (or slides along) its own axis, so the axis reads the same on
/// either side of it, and for a revolute joint so does the point.
#[allow(clippy::type_complexity)]
fn walk_back(
    g: &mut Graph,
    mut u: Transform,
    links: &[LinkSteps],
) -> (Vec<([Id; 3], [Id; 3])>, Vec<Transform>) {
    let mut axes = Vec::with_capacity(links.len());
    let mut before = Vec::with_capacity(links.len());
    for l in links.iter().rev() {
        u = back(g, u, &l.after);
        let mut z = u.cols[l.axis];
        if l.flip {
            z = z.map(|x| g.neg(x));
        }
        axes.push((z, u.p));
        u = back(g, u, std::slice::from_ref(&l.motion));
        u = back(g, u, &l.before);
        before.push(u);
    }
    axes.reverse();
    before.reverse();
    (axes, before)
}

impl SymbolicChain {
    /// Build the frames left to right from the base.
    pub fn new(chain: &Chain, max_terms: usize) -> SymbolicChain {
        SymbolicChain::build(chain, max_terms, None, Deadline::never()).0
    }

    /// Build the frames; with `pivot = Some(k)` (`1 ≤ k < N`) the frames after `k` are
    /// built in frame `k` and composed with `T_k` (see [`Pivot`]). The graph drops new
    /// normal forms once `deadline` has passed (the frames are still complete and
    /// correct, only less simplified), and keeps it for the phases that build on it.
    pub fn build(
        chain: &Chain,
        max_terms: usize,
        pivot: Option<usize>,
        deadline: Deadline,
    ) -> (SymbolicChain, Option<Pivot>) {
        SymbolicChain::build_with(chain, max_terms, pivot, deadline, Joints::Variable)
    }

    /// The frames at `q = 0`: every joint fixed at its zero (its offset), except joint
    /// `keep` (0-based), which stays a variable. Axes, points and the tool are then
    /// constants — polynomials in the parameters (and in `keep`'s sine and cosine) — whose
    /// exact normal forms decide which joint axes are parallel or meet.
    pub fn at_zero(chain: &Chain, max_terms: usize, keep: Option<usize>) -> SymbolicChain {
        let joints = Joints::Zero { keep };
        SymbolicChain::build_with(chain, max_terms, None, Deadline::never(), joints).0
    }

    fn build_with(
        chain: &Chain,
        max_terms: usize,
        pivot: Option<usize>,
        deadline: Deadline,
        joints: Joints,
    ) -> (SymbolicChain, Option<Pivot>) {
        let mut graph = Graph::new(Default::default(), max_terms);
        graph.deadline = deadline;
        let mut b = Entries::new(graph);
        let mut t = Transform::identity(&mut b.graph);
        let base_steps = fixed(&mut b, &chain.base);
        t = apply_all(&mut b.graph, t, &base_steps);
        let base = t;
        let pivot_at = pivot.filter(|&k| k >= 1 && k < chain.dof());
        let mut frames = Vec::new();
        let mut axes = Vec::new();
        // In pivot mode, `t` is local to frame k after the pivot and `world` maps it out.
        let mut world: Option<Transform> = None;
        let mut local_axes = Vec::new();
        let mut link_steps = Vec::new();
        for (i, link) in chain.links.iter().enumerate() {
            if pivot_at == Some(i) {
                world = Some(t);
                t = Transform::identity(&mut b.graph);
            }
            let (axis, steps);
            (t, axis, steps) = unroll(&mut b, t, i, link, joints.variable(i));
            link_steps.push(steps);
            match &world {
                Some(w) => {
                    local_axes.push(axis);
                    let z = rotate(&mut b.graph, w, axis.0);
                    let o = point(&mut b.graph, w, axis.1);
                    axes.push((z, o));
                    frames.push(compose(&mut b.graph, w, &t));
                }
                None => {
                    axes.push(axis);
                    frames.push(t);
                }
            }
        }
        let steps = fixed(&mut b, &chain.tool);
        t = apply_all(&mut b.graph, t, &steps);
        // The tool frame's view: the chain unrolled backwards from the tool.
        let g = &mut b.graph;
        let from_tool = Transform::identity(g);
        let from_tool = back(g, from_tool, &steps);
        let (tool_axes, _) = walk_back(g, from_tool, &link_steps);
        let (tool, pivot) = match (world, pivot_at) {
            (Some(w), Some(k)) => (
                compose(&mut b.graph, &w, &t),
                Some(Pivot {
                    k,
                    frame: w,
                    axes: local_axes,
                    tool: t,
                }),
            ),
            _ => (t, None),
        };
        let sym = SymbolicChain {
            graph: b.graph,
            angles: b.angles,
            joint_vars: b.joint_vars,
            param_vars: b.param_vars,
            rate_vars: Vec::new(),
            frames,
            base,
            tool,
            axes,
            tool_axes,
            links: link_steps,
            tool_steps: steps,
            base_steps,
        };
        (sym, pivot)
    }
}

impl SymbolicChain {
    /// The chain seen from the world frame: its axes, link origins and tool point as
    /// built (what [`SymbolicChain::in_frame`] gives for a link frame).
    pub fn world_view(&self) -> FrameView {
        FrameView {
            axes: self.axes.clone(),
            origins: self.frames.iter().map(|t| t.p).collect(),
            tool: self.tool.p,
        }
    }

    /// The chain seen from link frame `k` (`frames[k]`, 0-based): the links after it
    /// replayed forwards from the identity, those up to it walked backwards. Every entry
    /// then depends only on the joints between the frame and the point or axis — small
    /// exact forms, where rotating world values by `R_kᵀ` would multiply two
    /// whole-chain polynomials for most of the product to cancel.
    pub fn in_frame(&mut self, k: usize) -> FrameView {
        let g = &mut self.graph;
        let n = self.links.len();
        let id = Transform::identity(g);
        let (mut axes, before) = walk_back(g, id, &self.links[..=k]);
        // `before[j]` is frame j − 1 (the base for j = 0); frame k is the identity.
        let mut origins: Vec<[Id; 3]> = before[1..].iter().map(|t| t.p).collect();
        origins.push(id.p);
        let mut t = id;
        for l in &self.links[k + 1..n] {
            let axis;
            (t, axis) = replay(g, t, l);
            axes.push(axis);
            origins.push(t.p);
        }
        let tool = apply_all(g, t, &self.tool_steps).p;
        FrameView {
            axes,
            origins,
            tool,
        }
    }

    /// The world frame seen from the tool, `(base · A1 ⋯ AN · tool)⁻¹`: every step walked
    /// back from the tool, so its entries are exact forms as small as the steps make them
    /// (inverting the built `tool` would multiply whole-chain polynomials). With
    /// [`SymbolicChain::tool_axes`] it is the chain read from the tool to the base.
    pub fn world_from_tool(&mut self) -> Transform {
        let g = &mut self.graph;
        let mut u = Transform::identity(g);
        u = back(g, u, &self.tool_steps);
        for l in self.links.iter().rev() {
            u = back(g, u, &l.after);
            u = back(g, u, core::slice::from_ref(&l.motion));
            u = back(g, u, &l.before);
        }
        back(g, u, &self.base_steps)
    }

    /// The joint rates `q̇_1 … q̇_N` as leaves (`qd1`, …), made on first use.
    pub fn rates(&mut self, n: usize) -> Vec<Id> {
        (0..n)
            .map(|j| {
                let v = self.graph.ring.rate(j, &format!("qd{}", j + 1));
                if !self.rate_vars.iter().any(|&(_, w)| w == v) {
                    self.rate_vars.push((j, v));
                }
                self.graph.leaf(v)
            })
            .collect()
    }

    /// Values of the ring's variables at joint values `q` with the chain's parameters:
    /// what the generated code computes before its first operation. Used to evaluate
    /// the symbolic outputs directly (tests, the CLI's `eval`). Joint rates are NaN (see
    /// [`SymbolicChain::variables_with_rates`]).
    pub fn variables(&self, chain: &Chain, q: &[f64]) -> Vec<f64> {
        self.variables_with_rates(chain, q, None)
    }

    /// [`SymbolicChain::variables`] with joint rates `qd` for the outputs that read them
    /// (`None`: NaN, so a rate-dependent value cannot pass for a number).
    pub fn variables_with_rates(&self, chain: &Chain, q: &[f64], qd: Option<&[f64]>) -> Vec<f64> {
        let ring = &self.graph.ring;
        let mut vals = vec![f64::NAN; ring.len()];
        for (v, slot) in vals.iter_mut().enumerate() {
            *slot = match ring.kind(v as u32) {
                VarKind::Joint(j) => q[*j],
                VarKind::Rate(j) => qd.map_or(f64::NAN, |qd| qd[*j]),
                VarKind::Param(n) => chain.param_value(n),
                VarKind::Sqrt(k) => (*k as f64).sqrt(),
                VarKind::Sin(_) | VarKind::Cos(_) => continue,
            };
        }
        for a in &self.angles {
            let x = match &a.source {
                AngleSource::Joint {
                    joint,
                    sign,
                    offset,
                } => f64::from(*sign) * q[*joint] + chain.eval(offset),
                AngleSource::Constant(v) => chain.eval(v),
            };
            vals[a.vars.0 as usize] = x.sin();
            vals[a.vars.1 as usize] = x.cos();
        }
        vals
    }

    /// Evaluate nodes at `q`.
    pub fn eval(&self, chain: &Chain, q: &[f64], ids: &[Id]) -> Vec<f64> {
        self.eval_with_rates(chain, q, None, ids)
    }

    /// Evaluate nodes at `q` and joint rates `qd` (`None`: rates are NaN), sharing the
    /// values of common intermediates between them.
    pub fn eval_with_rates(
        &self,
        chain: &Chain,
        q: &[f64],
        qd: Option<&[f64]>,
        ids: &[Id],
    ) -> Vec<f64> {
        let vals = self.variables_with_rates(chain, q, qd);
        self.graph.eval_all(ids, &|v| vals[v as usize])
    }
}

/// One link onto frame `t`: the new frame, the joint's axis and a point on it, and the
/// steps applied.
///
/// The link's entries become nodes first, outward from the joint (its motion, the
/// transforms after it, then those before it, nearest first: θ, d, a, α for a DH row in
/// either convention); the order only decides how the generated code orders operands.
fn unroll(
    b: &mut Entries,
    t: Transform,
    i: usize,
    link: &Link,
    variable: bool,
) -> (Transform, ([Id; 3], [Id; 3]), LinkSteps) {
    let motion = if variable {
        motion(b, i, &link.motion)
    } else {
        // At q = 0 the joint is its offset.
        let axis = link.motion.axis;
        match link.motion.kind {
            JointKind::Revolute => step(b, &Elem::Rot(axis, link.motion.offset.clone())),
            JointKind::Prismatic => step(b, &Elem::Trans(axis, link.motion.offset.clone())),
        }
    };
    let after = fixed(b, &link.after);
    let mut before: Vec<Step> = link.before.iter().rev().map(|e| step(b, e)).collect();
    before.reverse();
    let steps = LinkSteps {
        before,
        motion,
        after,
        axis: link.motion.axis.index(),
        at_link_frame: link.axis_at == AxisAt::LinkFrame,
        flip: link.motion.sign < 0,
    };
    let (t, axis) = replay(&mut b.graph, t, &steps);
    (t, axis, steps)
}

/// The joint's motion as a step: `sin_cos(±q + offset)`, or `±q + offset` along the axis.
fn motion(b: &mut Entries, i: usize, m: &Motion) -> Step {
    let axis = m.axis.index();
    match m.kind {
        JointKind::Revolute => {
            let (s, c) = b.joint_angle(i, m.sign, &m.offset);
            Step::Turn { axis, s, c }
        }
        JointKind::Prismatic => {
            let q = b.joint_var(i);
            let q = if m.sign < 0 { b.graph.neg(q) } else { q };
            let k = b.length(&m.offset);
            let d = b.graph.add(q, k);
            Step::Move { axis, d }
        }
    }
}

fn step(b: &mut Entries, e: &Elem) -> Step {
    match e {
        Elem::Rot(axis, v) => {
            let (s, c) = b.const_angle(v);
            Step::Turn {
                axis: axis.index(),
                s,
                c,
            }
        }
        Elem::Trans(axis, v) => Step::Move {
            axis: axis.index(),
            d: b.length(v),
        },
    }
}

/// Constant transforms as steps, their entries made nodes in order.
fn fixed(b: &mut Entries, elems: &[Elem]) -> Vec<Step> {
    elems.iter().map(|e| step(b, e)).collect()
}

fn apply(g: &mut Graph, t: Transform, s: Step) -> Transform {
    match s {
        Step::Turn { axis, s, c } => turn(g, &t, axis, s, c),
        Step::Move { axis, d } => translate(g, &t, axis, d),
    }
}

fn apply_all(g: &mut Graph, t: Transform, steps: &[Step]) -> Transform {
    steps.iter().fold(t, |t, &s| apply(g, t, s))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::raw::{RawJoint, RawRobot, RawValue};
    use crate::model::validate::validate;
    use crate::model::value::Rat;
    use num_traits::Zero;

    fn planar_rr() -> Chain {
        let row = |a: &str| RawJoint {
            kind: Some("revolute".into()),
            fields: vec![
                ("a".into(), RawValue::Text(a.into())),
                ("alpha".into(), RawValue::Number(0.0)),
                ("d".into(), RawValue::Number(0.0)),
            ],
        };
        let robot = validate(&RawRobot {
            name: Some("RR".into()),
            convention: Some("standard".into()),
            params: vec![
                ("L1".into(), RawValue::Number(1.0)),
                ("L2".into(), RawValue::Number(1.0)),
            ],
            joints: vec![row("L1"), row("L2")],
            ..Default::default()
        })
        .unwrap();
        robot.chain()
    }

    #[test]
    fn planar_rr_position_is_textbook() {
        let sym = SymbolicChain::new(&planar_rr(), 1000);
        let g = &sym.graph;
        let px = g.nf(sym.tool.p[0]).unwrap();
        assert_eq!(
            g.ring.display(px).to_string(),
            "-s1*s2*L2 + c1*L1 + c1*c2*L2"
        );
        assert_eq!(g.as_num(sym.tool.p[2]), Some(&Rat::zero()));
    }
}
