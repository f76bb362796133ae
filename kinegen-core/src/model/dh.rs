//! A Denavit–Hartenberg table, checked: what [`crate::model::validate`] makes of a
//! [`crate::model::raw::RawRobot`], and what [`crate::chain::dh`] turns into the
//! engine's [`crate::chain::Chain`].

use crate::model::robot::{JointKind, Param, Scalar, TaskRow};
use crate::model::value::Value;

/// DH convention.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Convention {
    /// Standard (distal) DH: `A_i = Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i)`.
    Standard,
    /// Modified (proximal, Craig) DH: `A_i = Rx(α_{i-1}) Tx(a_{i-1}) Rz(θ_i) Tz(d_i)`;
    /// row i holds `a_{i-1}` and `α_{i-1}`.
    Modified,
}

/// A checked joint. Offsets are folded into `theta` (revolute) or `d` (prismatic):
/// the joint variable `q_i` is added to that entry — or, for a flipped joint,
/// subtracted from it (θ = −q_i + theta, as the Robotics Toolbox's `flip`).
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// Revolute or prismatic.
    pub kind: JointKind,
    /// Link length `a` (modified: `a_{i-1}`).
    pub a: Value,
    /// Link twist `α` (modified: `α_{i-1}`).
    pub alpha: Value,
    /// Link offset `d`; for a prismatic joint, the constant added to `q_i`.
    pub d: Value,
    /// Joint angle `θ`; for a revolute joint, the constant added to `q_i`.
    pub theta: Value,
    /// Joint limits `[min, max]` (radians or metres), if given: always on the user's `q_i`.
    pub limits: Option<[f64; 2]>,
    /// The joint runs against its axis: θ (or d) = −q_i + the entry.
    pub flip: bool,
}

/// A fixed transform `Trans(xyz) · Rz(yaw) · Ry(pitch) · Rx(roll)`, as in URDF.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// Translation.
    pub xyz: [Value; 3],
    /// `[roll, pitch, yaw]`.
    pub rpy: [Value; 3],
}

/// A checked robot model.
#[derive(Clone, Debug, PartialEq)]
pub struct Robot {
    /// Display name (`"UR5"`).
    pub name: String,
    /// DH convention.
    pub convention: Convention,
    /// Named parameters, in declaration order.
    pub params: Vec<Param>,
    /// Joints, base to tool.
    pub joints: Vec<Joint>,
    /// Base transform (world → frame 0).
    pub base: Option<Frame>,
    /// Tool transform (frame N → tool point).
    pub tool: Option<Frame>,
    /// Rows of the reduced Jacobian.
    pub task: Option<Vec<TaskRow>>,
    /// Scalar type of generated code.
    pub scalar: Scalar,
}

impl Robot {
    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.joints.len()
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
}
