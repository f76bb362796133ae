//! The kinematic chain: the engine's only input.
//!
//! A [`Chain`] is a robot as a product of elementary transforms — rotations about and
//! translations along the axes of the current frame, with exact constant or symbolic
//! arguments — and, once per [`Link`], the motion of a joint about or along one of those
//! axes. Nothing here knows where the robot came from: a DH table (both conventions,
//! [`dh`]) is one builder of it, a URDF joint list another. Everything after this stage
//! (frames, Jacobians, determinants, code) reads only a `Chain`.
//!
//! ```
//! use kinegen_core::front::toml_file::load_str;
//! let src = "convention = \"standard\"\n[[joints]]\ntype = \"revolute\"\na = 1\nalpha = 0\nd = 0\n";
//! let (robot, _) = load_str(src, "r.toml").unwrap();
//! let chain = robot.chain();
//! assert_eq!(chain.dof(), 1);
//! assert_eq!(chain.to_string(), "link 1: Rz(q1) Tz(0) Tx(1) Rx(0)\n");
//! ```

pub mod dh;
pub mod named_lengths;
pub mod urdf;

use std::fmt;

use crate::model::robot::{JointKind, Param, Scalar, TaskRow};
use crate::model::value::Value;

/// A coordinate axis of the current frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Axis {
    /// x.
    X,
    /// y.
    Y,
    /// z.
    Z,
}

impl Axis {
    /// 0, 1, 2 for x, y, z.
    pub fn index(self) -> usize {
        self as usize
    }

    fn name(self) -> &'static str {
        ["x", "y", "z"][self as usize]
    }
}

/// A constant elementary transform, right-multiplied onto the current frame.
#[derive(Clone, Debug, PartialEq)]
pub enum Elem {
    /// Rotation about an axis by a constant angle (radians, may name parameters).
    Rot(Axis, Value),
    /// Translation along an axis by a constant length (may name parameters).
    Trans(Axis, Value),
}

impl Elem {
    /// The axis it turns about or moves along.
    pub fn axis(&self) -> Axis {
        match self {
            Elem::Rot(a, _) | Elem::Trans(a, _) => *a,
        }
    }

    /// Consecutive translations gathered, one per axis in the order the axes first
    /// appear (translations commute), exactly: `Tx(0.042825) Tx(0.025875) Tx(0.0385)`
    /// — fixed URDF joints in a row — is `Tx(0.1072)`; a sum that is zero is left out.
    /// Rotations stay where they are.
    ///
    /// ```
    /// use kinegen_core::chain::{Axis, Elem};
    /// use kinegen_core::model::value::Value;
    /// let t = |a, x: f64| Elem::Trans(a, Value::from_f64(x).unwrap());
    /// let merged = Elem::merge_translations(vec![t(Axis::X, 0.5), t(Axis::Z, 1.0), t(Axis::X, 0.25)]);
    /// assert_eq!(merged, vec![t(Axis::X, 0.75), t(Axis::Z, 1.0)]);
    /// ```
    pub fn merge_translations(elems: Vec<Elem>) -> Vec<Elem> {
        let mut out: Vec<Elem> = Vec::with_capacity(elems.len());
        // Where the current run of translations starts in `out`.
        let mut run = 0;
        for e in elems {
            match e {
                Elem::Trans(axis, v) => {
                    let same = out[run..]
                        .iter_mut()
                        .find(|x| matches!(x, Elem::Trans(a, _) if *a == axis));
                    match same {
                        Some(Elem::Trans(_, w)) => *w = w.add(&v),
                        _ => out.push(Elem::Trans(axis, v)),
                    }
                }
                rot => {
                    drop_zero_translations(&mut out, run);
                    out.push(rot);
                    run = out.len();
                }
            }
        }
        drop_zero_translations(&mut out, run);
        out
    }
}

/// `u / |u|`, scaled by the largest component first: squaring `1e300` overflows, and
/// the axis `1e300 0 1` came out as `0 0 0` — then "snapped" to z (found by the URDF
/// mutation test). The URDF builder's axes and its named lengths' directions.
pub(crate) fn unit(v: &[f64; 3]) -> [f64; 3] {
    let m = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let w = v.map(|x| x / m);
    let n = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
    w.map(|x| x / n)
}

/// `elems[from..]` without translations by zero.
fn drop_zero_translations(elems: &mut Vec<Elem>, from: usize) {
    let mut i = from;
    while i < elems.len() {
        if matches!(&elems[i], Elem::Trans(_, v) if v.is_zero()) {
            elems.remove(i);
        } else {
            i += 1;
        }
    }
}

/// The motion of a joint: about (revolute) or along (prismatic) an axis of the current
/// frame, by `sign · q + offset` where `q` is the joint variable.
#[derive(Clone, Debug, PartialEq)]
pub struct Motion {
    /// Revolute or prismatic.
    pub kind: JointKind,
    /// The axis of the current frame it turns about or slides along.
    pub axis: Axis,
    /// `+1`, or `-1` for a joint that runs against its axis.
    pub sign: i8,
    /// Constant added to `sign · q` (a DH table's θ or d, its `offset`).
    pub offset: Value,
}

/// Where a link's joint axis (and a point on it) is read for the Jacobian.
///
/// Every frame whose origin lies on the joint's axis gives the same Jacobian column;
/// the choice only decides which expressions the generated code computes. The DH
/// builders keep the textbook's: `z_{i-1}`, `o_{i-1}` for standard DH, `z_i`, `o_i` for
/// modified DH.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AxisAt {
    /// In the frame just before the motion.
    Motion,
    /// In the link's frame (its end). Valid when every element after the motion turns
    /// about or moves along the joint's own axis ([`Chain::check`]).
    LinkFrame,
}

/// One moving link: the constant transforms before its joint, the joint's motion, the
/// constant transforms after it. Its frame (the link frame `base · A1 ⋯ Ai`) is the end.
#[derive(Clone, Debug, PartialEq)]
pub struct Link {
    /// The joint's name (`q3` for a DH row, the joint's name in a URDF).
    pub name: String,
    /// Constant transforms before the motion.
    pub before: Vec<Elem>,
    /// The joint.
    pub motion: Motion,
    /// Constant transforms after the motion.
    pub after: Vec<Elem>,
    /// Where the joint axis is read for the Jacobian.
    pub axis_at: AxisAt,
    /// Joint limits `[min, max]` on `q` (radians or metres), if known.
    pub limits: Option<[f64; 2]>,
}

/// A robot as the engine sees it.
#[derive(Clone, Debug, PartialEq)]
pub struct Chain {
    /// Display name (`"UR5"`).
    pub name: String,
    /// Named parameters, in declaration order: fields of the generated type.
    pub params: Vec<Param>,
    /// World → frame 0.
    pub base: Vec<Elem>,
    /// The moving links, base to tip; link `i` carries joint variable `q[i]`.
    pub links: Vec<Link>,
    /// Frame N → tool point.
    pub tool: Vec<Elem>,
    /// Rows of the reduced (task) Jacobian.
    pub task: Option<Vec<TaskRow>>,
    /// Scalar type of the generated code.
    pub scalar: Scalar,
    /// What the robot was described as (`standard DH`, `modified (Craig) DH`).
    pub description: String,
    /// The description itself, for the generated type's rustdoc (markdown lines: the
    /// DH table, the URDF joints).
    pub summary: Vec<String>,
    /// Values of the description the builder replaced by exact ones (a URDF's
    /// `1.5708` by π/2), each with the error it can cause: printed in the rustdoc and
    /// by `kinegen show --what model`, never silent.
    pub snaps: Vec<Snap>,
}

/// One value of the description replaced by an exact one, and what that can cost.
///
/// The bounds are first order in `delta` and assume the rest of the chain exact; the
/// bounds of several snaps add. A constant rotation off by δ turns everything after it
/// by δ: the tool's orientation moves by at most δ and its position by at most δ times
/// the reach after it (the sum of the lengths of the translations that follow, prismatic
/// travel included). A joint axis off by δ gives a joint rotation off by at most 2δ at
/// any angle. A length off by ε moves the tool by at most ε.
#[derive(Clone, Debug, PartialEq)]
pub struct Snap {
    /// Which entry (`shoulder_lift_joint.origin.rpy[0]`, `wrist_1_joint.axis`).
    pub entry: String,
    /// As written (`1.570796327`).
    pub written: String,
    /// What is used instead (`pi/2`, `0`, `0 0 1`).
    pub used: String,
    /// `|written − used|`: radians for angles and axes (the angle between them), metres
    /// for lengths.
    pub delta: f64,
    /// Bound on the tool position error it can cause, metres (∞ past a prismatic joint
    /// without limits).
    pub position_bound: f64,
    /// Bound on the tool orientation error it can cause, radians.
    pub orientation_bound: f64,
}

impl fmt::Display for Snap {
    /// `` `entry`: `1.5708` → `pi/2` (δ = 3.7e-6): tool ≤ 2.1e-6 m, ≤ 3.7e-6 rad ``.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "`{}`: `{}` → `{}` (δ = {:.1e}): tool ≤ {} m, ≤ {:.1e} rad",
            self.entry,
            self.written,
            self.used,
            self.delta,
            bound(self.position_bound),
            self.orientation_bound
        )
    }
}

/// `1.2e-6`, or `∞`.
pub fn bound(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.1e}")
    } else {
        "∞".into()
    }
}

impl Chain {
    /// The bounds of all snaps together `(position m, orientation rad)`, first order.
    pub fn snap_bounds(&self) -> (f64, f64) {
        self.snaps.iter().fold((0.0, 0.0), |(p, o), s| {
            (p + s.position_bound, o + s.orientation_bound)
        })
    }
}

/// A chain that breaks an invariant the engine relies on (a builder's bug, never the
/// user's input).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ChainError(pub String);

impl fmt::Display for ChainError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ChainError {}

impl Chain {
    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.links.len()
    }

    /// Joint kinds, base to tip.
    pub fn kinds(&self) -> impl Iterator<Item = JointKind> + '_ {
        self.links.iter().map(|l| l.motion.kind)
    }

    /// Default value of a parameter (NaN for an unknown name; validation rules that out).
    pub fn param_value(&self, name: &str) -> f64 {
        self.params
            .iter()
            .find(|p| p.name == name)
            .map_or(f64::NAN, |p| p.value.eval(&|_| f64::NAN))
    }

    /// Numeric value of an entry with the default parameter values.
    pub fn eval(&self, v: &Value) -> f64 {
        v.eval(&|n| self.param_value(n))
    }

    /// Check the invariants: joint signs are ±1, and a link that reads its axis in the
    /// link frame has only elements along that axis after its motion.
    pub fn check(&self) -> Result<(), ChainError> {
        for (i, l) in self.links.iter().enumerate() {
            if l.motion.sign != 1 && l.motion.sign != -1 {
                return Err(ChainError(format!(
                    "link {}: joint sign {} is not ±1",
                    i + 1,
                    l.motion.sign
                )));
            }
            let off_axis = l.after.iter().any(|e| e.axis() != l.motion.axis);
            if l.axis_at == AxisAt::LinkFrame && off_axis {
                return Err(ChainError(format!(
                    "link {}: the axis is read in the link frame, but a transform after the \
                     joint leaves the joint's axis",
                    i + 1
                )));
            }
        }
        Ok(())
    }
}

impl fmt::Display for Elem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Elem::Rot(a, v) => write!(f, "R{}({v})", a.name()),
            Elem::Trans(a, v) => write!(f, "T{}({v})", a.name()),
        }
    }
}

impl fmt::Display for Chain {
    /// One line per part: `base: …`, `link i: … Rz(q_i) …`, `tool: …`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let elems = |v: &[Elem]| v.iter().map(|e| e.to_string()).collect::<Vec<_>>();
        if !self.base.is_empty() {
            writeln!(f, "base: {}", elems(&self.base).join(" "))?;
        }
        for (i, l) in self.links.iter().enumerate() {
            let m = &l.motion;
            let q = format!("q{}", i + 1);
            let var = if m.sign < 0 { format!("-{q}") } else { q };
            let arg = if m.offset.is_zero() {
                var
            } else {
                format!("{var} + {}", m.offset)
            };
            let kind = match m.kind {
                JointKind::Revolute => "R",
                JointKind::Prismatic => "T",
            };
            let mut parts = elems(&l.before);
            parts.push(format!("{kind}{}({arg})", m.axis.name()));
            parts.extend(elems(&l.after));
            writeln!(f, "link {}: {}", i + 1, parts.join(" "))?;
        }
        if !self.tool.is_empty() {
            writeln!(f, "tool: {}", elems(&self.tool).join(" "))?;
        }
        Ok(())
    }
}
