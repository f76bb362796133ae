//! Numeric reference kinematics: the ground truth generated code is tested against.
//!
//! Everything here is plain floating point on nalgebra, written for clarity, not speed:
//! forward kinematics by multiplying DH matrices, the geometric Jacobian from joint axes
//! (`z × (p − o)` columns), and two independent ways to get the same Jacobian — central
//! finite differences of FK ([`jacobian_fd`]) and recursive velocity propagation link to
//! link ([`jacobian_propagation`]). Three methods that share no code past the DH matrix
//! agreeing to rounding is what makes this a reference.
//!
//! Conventions (as in [`crate::model::dh`]): the joint variable `q_i` is added to `theta`
//! (revolute) or `d` (prismatic); Jacobian rows are `[vx vy vz ωx ωy ωz]`, the linear part
//! being the velocity of the tool point, all expressed in the world (base) frame unless the
//! name says `_ee`.
//!
//! ```
//! use kinegen_core::numeric::NumericRobot;
//! # use kinegen_core::model::{raw::{RawJoint, RawRobot, RawValue}, validate::validate};
//! # let row = || RawJoint { kind: Some("revolute".into()), fields: vec![
//! #     ("a".into(), RawValue::Number(1.0)), ("alpha".into(), RawValue::Number(0.0)),
//! #     ("d".into(), RawValue::Number(0.0))] };
//! # let raw = RawRobot { convention: Some("standard".into()), joints: vec![row(), row()],
//! #     ..Default::default() };
//! # let robot = validate(&raw).unwrap();
//! // `robot`: a planar RR arm with L1 = L2 = 1.
//! let model = NumericRobot::new(&robot).unwrap();
//! let q = [0.3, 0.5];
//! let t = model.fk(&q).unwrap();
//! assert!((t[(0, 3)] - (0.3f64.cos() + 0.8f64.cos())).abs() < 1e-15);
//! let j = model.jacobian(&q).unwrap();
//! let j_fd = model.jacobian_fd(&q, 1e-6).unwrap();
//! assert!((j - j_fd).amax() < 1e-8);
//! ```

use std::fmt;

use nalgebra::{DMatrix, Dyn, Matrix3, Matrix4, Matrix6, OMatrix, Vector3, U6};

use crate::model::dh::{Convention, Frame, Robot};
use crate::model::robot::{JointKind, TaskRow};

/// A 6×N Jacobian, rows `[vx vy vz ωx ωy ωz]`.
pub type Jacobian = OMatrix<f64, U6, Dyn>;

/// Why a numeric evaluation was refused.
#[derive(Clone, Debug, PartialEq)]
pub enum NumericError {
    /// `q` has the wrong length.
    JointCount {
        /// The robot's number of joints.
        expected: usize,
        /// The length of `q` given.
        found: usize,
    },
    /// A table entry, parameter or joint value is NaN or infinite.
    NonFinite(String),
    /// A determinant was asked of a non-square matrix.
    NotSquare {
        /// Rows.
        rows: usize,
        /// Columns.
        cols: usize,
    },
    /// The finite-difference step is not a positive finite number.
    BadStep(f64),
}

impl fmt::Display for NumericError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NumericError::JointCount { expected, found } => write!(
                f,
                "the robot has {expected} joints but {found} joint values were given"
            ),
            NumericError::NonFinite(what) => write!(f, "{what} is not a finite number"),
            NumericError::NotSquare { rows, cols } => {
                write!(
                    f,
                    "a determinant needs a square matrix, this one is {rows}×{cols}"
                )
            }
            NumericError::BadStep(h) => {
                write!(
                    f,
                    "finite-difference step {h} is not a positive finite number"
                )
            }
        }
    }
}

impl std::error::Error for NumericError {}

/// Rotation about x by `t` (homogeneous).
pub fn rot_x(t: f64) -> Matrix4<f64> {
    let (s, c) = t.sin_cos();
    Matrix4::new(
        1.0, 0.0, 0.0, 0.0, //
        0.0, c, -s, 0.0, //
        0.0, s, c, 0.0, //
        0.0, 0.0, 0.0, 1.0,
    )
}

/// Rotation about y by `t` (homogeneous).
pub fn rot_y(t: f64) -> Matrix4<f64> {
    let (s, c) = t.sin_cos();
    Matrix4::new(
        c, 0.0, s, 0.0, //
        0.0, 1.0, 0.0, 0.0, //
        -s, 0.0, c, 0.0, //
        0.0, 0.0, 0.0, 1.0,
    )
}

/// Rotation about z by `t` (homogeneous).
pub fn rot_z(t: f64) -> Matrix4<f64> {
    let (s, c) = t.sin_cos();
    Matrix4::new(
        c, -s, 0.0, 0.0, //
        s, c, 0.0, 0.0, //
        0.0, 0.0, 1.0, 0.0, //
        0.0, 0.0, 0.0, 1.0,
    )
}

/// Translation by `(x, y, z)` (homogeneous).
pub fn trans(x: f64, y: f64, z: f64) -> Matrix4<f64> {
    let mut m = Matrix4::identity();
    m[(0, 3)] = x;
    m[(1, 3)] = y;
    m[(2, 3)] = z;
    m
}

/// One link's DH transform, built from elementary transforms (not a closed-form matrix,
/// so that a sign slip in a hand-expanded formula cannot hide here).
///
/// Standard: `Rz(θ) Tz(d) Tx(a) Rx(α)`; modified: `Rx(α) Tx(a) Rz(θ) Tz(d)`.
pub fn dh_matrix(convention: Convention, a: f64, alpha: f64, d: f64, theta: f64) -> Matrix4<f64> {
    match convention {
        Convention::Standard => {
            rot_z(theta) * trans(0.0, 0.0, d) * trans(a, 0.0, 0.0) * rot_x(alpha)
        }
        Convention::Modified => {
            rot_x(alpha) * trans(a, 0.0, 0.0) * rot_z(theta) * trans(0.0, 0.0, d)
        }
    }
}

/// `Trans(xyz) · Rz(yaw) · Ry(pitch) · Rx(roll)` with `rpy = [roll, pitch, yaw]`, as in URDF.
pub fn rpy_transform(xyz: [f64; 3], rpy: [f64; 3]) -> Matrix4<f64> {
    trans(xyz[0], xyz[1], xyz[2]) * rot_z(rpy[2]) * rot_y(rpy[1]) * rot_x(rpy[0])
}

/// A base or tool [`Frame`] as a matrix, parameters looked up in `param`.
pub fn frame_transform(frame: &Frame, param: &dyn Fn(&str) -> f64) -> Matrix4<f64> {
    let ev = |i: usize, v: &[crate::model::value::Value; 3]| v[i].eval(param);
    rpy_transform(
        [ev(0, &frame.xyz), ev(1, &frame.xyz), ev(2, &frame.xyz)],
        [ev(0, &frame.rpy), ev(1, &frame.rpy), ev(2, &frame.rpy)],
    )
}

/// The rotation block of a homogeneous transform.
fn rotation(t: &Matrix4<f64>) -> Matrix3<f64> {
    t.fixed_view::<3, 3>(0, 0).into_owned()
}

/// The translation column of a homogeneous transform.
fn position(t: &Matrix4<f64>) -> Vector3<f64> {
    t.fixed_view::<3, 1>(0, 3).into_owned()
}

/// The axis vector of the skew-symmetric part of `m`: `vee((m − mᵀ)/2)`.
fn vee_skew(m: &Matrix3<f64>) -> Vector3<f64> {
    Vector3::new(
        0.5 * (m[(2, 1)] - m[(1, 2)]),
        0.5 * (m[(0, 2)] - m[(2, 0)]),
        0.5 * (m[(1, 0)] - m[(0, 1)]),
    )
}

/// One joint with every entry evaluated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NumericJoint {
    /// Revolute or prismatic.
    pub kind: JointKind,
    /// Link length.
    pub a: f64,
    /// Link twist.
    pub alpha: f64,
    /// Link offset (constant part for a prismatic joint).
    pub d: f64,
    /// Joint angle (constant part for a revolute joint).
    pub theta: f64,
    /// The joint runs against its axis (the Robotics Toolbox's `flip`): θ = −q + theta.
    pub flip: bool,
}

impl NumericJoint {
    /// `(θ, d)` with the joint variable added to the right one (its negative for a
    /// flipped joint, as RTB's `DHLink.A`: `q = -q + offset`).
    fn theta_d(&self, q: f64) -> (f64, f64) {
        let q = if self.flip { -q } else { q };
        match self.kind {
            JointKind::Revolute => (self.theta + q, self.d),
            JointKind::Prismatic => (self.theta, self.d + q),
        }
    }
}

/// A robot with every table entry, base and tool evaluated to `f64` once.
#[derive(Clone, Debug, PartialEq)]
pub struct NumericRobot {
    /// DH convention.
    pub convention: Convention,
    /// Joints, base to tool.
    pub joints: Vec<NumericJoint>,
    /// World → frame 0.
    pub base: Matrix4<f64>,
    /// Frame N → tool point.
    pub tool: Matrix4<f64>,
    /// Task rows, if declared.
    pub task: Option<Vec<TaskRow>>,
}

impl NumericRobot {
    /// Evaluate with the table's default parameter values.
    pub fn new(robot: &Robot) -> Result<Self, NumericError> {
        Self::with_params(robot, &|n| robot.param_value(n))
    }

    /// Evaluate with parameter values from `param` (e.g. a calibrated robot).
    pub fn with_params(robot: &Robot, param: &dyn Fn(&str) -> f64) -> Result<Self, NumericError> {
        let finite = |x: f64, what: &dyn Fn() -> String| {
            if x.is_finite() {
                Ok(x)
            } else {
                Err(NumericError::NonFinite(what()))
            }
        };
        let mut joints = Vec::with_capacity(robot.dof());
        for (i, j) in robot.joints.iter().enumerate() {
            let at = |col: &'static str| move || format!("joints[{i}].{col}");
            joints.push(NumericJoint {
                kind: j.kind,
                a: finite(j.a.eval(param), &at("a"))?,
                alpha: finite(j.alpha.eval(param), &at("alpha"))?,
                d: finite(j.d.eval(param), &at("d"))?,
                theta: finite(j.theta.eval(param), &at("theta"))?,
                flip: j.flip,
            });
        }
        let frame = |f: &Option<Frame>, name: &str| -> Result<Matrix4<f64>, NumericError> {
            let m = f
                .as_ref()
                .map_or_else(Matrix4::identity, |f| frame_transform(f, param));
            if m.iter().all(|x| x.is_finite()) {
                Ok(m)
            } else {
                Err(NumericError::NonFinite(format!("the {name} frame")))
            }
        };
        Ok(NumericRobot {
            convention: robot.convention,
            joints,
            base: frame(&robot.base, "base")?,
            tool: frame(&robot.tool, "tool")?,
            task: robot.task.clone(),
        })
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.joints.len()
    }

    fn check(&self, q: &[f64]) -> Result<(), NumericError> {
        if q.len() != self.dof() {
            return Err(NumericError::JointCount {
                expected: self.dof(),
                found: q.len(),
            });
        }
        match q.iter().position(|x| !x.is_finite()) {
            Some(i) => Err(NumericError::NonFinite(format!("q[{i}] = {}", q[i]))),
            None => Ok(()),
        }
    }

    /// `A_i(q_i)`, 0-based `i`.
    pub fn link(&self, i: usize, q: f64) -> Matrix4<f64> {
        let j = &self.joints[i];
        let (theta, d) = j.theta_d(q);
        dh_matrix(self.convention, j.a, j.alpha, d, theta)
    }

    /// `base · A1 … Ai` for i = 1..N (no tool).
    pub fn frames(&self, q: &[f64]) -> Result<Vec<Matrix4<f64>>, NumericError> {
        self.check(q)?;
        let mut t = self.base;
        Ok(q.iter()
            .enumerate()
            .map(|(i, &qi)| {
                t *= self.link(i, qi);
                t
            })
            .collect())
    }

    /// `base · A1 … AN · tool`.
    pub fn fk(&self, q: &[f64]) -> Result<Matrix4<f64>, NumericError> {
        let frames = self.frames(q)?;
        Ok(frames.last().copied().unwrap_or(self.base) * self.tool)
    }

    /// Geometric Jacobian in the world frame, from joint axes.
    ///
    /// Joint i's axis `z` and a point `o` on it, in the world frame: standard DH — frame
    /// i−1 (`base·A1…A_{i−1}`, frame 0 being the base), since `A_i` starts with `Rz(θ_i)
    /// Tz(d_i)`; modified DH — frame i (`base·A1…A_i`), since `A_i = Rx Tx · Rz(θ_i)
    /// Tz(d_i)` moves along frame i's own z axis, through frame i's origin. Revolute
    /// column `[z × (p − o); z]`, prismatic `[z; 0]`, `p` the tool point.
    pub fn jacobian(&self, q: &[f64]) -> Result<Jacobian, NumericError> {
        let frames = self.frames(q)?;
        let p = position(&(frames.last().copied().unwrap_or(self.base) * self.tool));
        let mut j = Jacobian::zeros(self.dof());
        for (i, joint) in self.joints.iter().enumerate() {
            let axis_frame = match self.convention {
                Convention::Standard if i == 0 => self.base,
                Convention::Standard => frames[i - 1],
                Convention::Modified => frames[i],
            };
            let z: Vector3<f64> = axis_frame.fixed_view::<3, 1>(0, 2).into_owned();
            // A flipped joint's positive rate turns (or slides) about −z.
            let z = if joint.flip { -z } else { z };
            let o = position(&axis_frame);
            let (v, w) = match joint.kind {
                JointKind::Revolute => (z.cross(&(p - o)), z),
                JointKind::Prismatic => (z, Vector3::zeros()),
            };
            j.fixed_view_mut::<3, 1>(0, i).copy_from(&v);
            j.fixed_view_mut::<3, 1>(3, i).copy_from(&w);
        }
        Ok(j)
    }

    /// The Jacobian expressed in the tool frame: `diag(Rᵀ, Rᵀ) · J`, `R` the tool rotation.
    pub fn jacobian_ee(&self, q: &[f64]) -> Result<Jacobian, NumericError> {
        let rt = rotation(&self.fk(q)?).transpose();
        let j = self.jacobian(q)?;
        let mut out = Jacobian::zeros(self.dof());
        out.fixed_rows_mut::<3>(0)
            .copy_from(&(rt * j.fixed_rows::<3>(0)));
        out.fixed_rows_mut::<3>(3)
            .copy_from(&(rt * j.fixed_rows::<3>(3)));
        Ok(out)
    }

    /// The Jacobian by central finite differences of [`fk`](Self::fk) with step `h`.
    ///
    /// Linear part: `(p(q + h eᵢ) − p(q − h eᵢ)) / 2h`. Angular part: the world-frame
    /// angular velocity is `vee(Ṙ Rᵀ)`; with `Ṙ ≈ (R₊ − R₋)/2h` the product is skew only
    /// to O(h²), so its skew part is taken. Truncation error is O(h²), rounding O(ε/h):
    /// `h ≈ 1e-5` gives about 1e-10 on metre-sized arms.
    pub fn jacobian_fd(&self, q: &[f64], h: f64) -> Result<Jacobian, NumericError> {
        self.check(q)?;
        if !(h.is_finite() && h > 0.0) {
            return Err(NumericError::BadStep(h));
        }
        let r = rotation(&self.fk(q)?);
        let mut j = Jacobian::zeros(self.dof());
        let mut qp = q.to_vec();
        for i in 0..self.dof() {
            qp[i] = q[i] + h;
            let tp = self.fk(&qp)?;
            qp[i] = q[i] - h;
            let tm = self.fk(&qp)?;
            qp[i] = q[i];
            let v = (position(&tp) - position(&tm)) / (2.0 * h);
            let rdot = (rotation(&tp) - rotation(&tm)) / (2.0 * h);
            let w = vee_skew(&(rdot * r.transpose()));
            j.fixed_view_mut::<3, 1>(0, i).copy_from(&v);
            j.fixed_view_mut::<3, 1>(3, i).copy_from(&w);
        }
        Ok(j)
    }

    /// The Jacobian by recursive velocity propagation (Craig §5.6), one column per unit
    /// joint rate, all columns pushed together.
    ///
    /// Each frame carries the angular velocity `ω` of its link and the linear velocity `v`
    /// of its origin, both in its own coordinates. Across a transform `(R, p)` from frame
    /// k to k+1: `ω' = Rᵀ ω`, `v' = Rᵀ (v + ω × p)`. At a joint, a revolute rate adds to
    /// `ω` along the local z, a prismatic rate adds to `v`. The joint sits at frame i−1
    /// (standard DH, before `A_i`) or between `Rx Tx` and `Rz Tz` (modified DH). The base
    /// is fixed; at the tool point the result is rotated into the world frame.
    pub fn jacobian_propagation(&self, q: &[f64]) -> Result<Jacobian, NumericError> {
        self.check(q)?;
        let n = self.dof();
        // Columns: velocity of the current frame due to a unit rate of each joint.
        let mut w = DMatrix::<f64>::zeros(3, n);
        let mut v = DMatrix::<f64>::zeros(3, n);
        let cross = |t: &Matrix4<f64>, w: &mut DMatrix<f64>, v: &mut DMatrix<f64>| {
            let rt = rotation(t).transpose();
            let p = position(t);
            for c in 0..n {
                let wc = Vector3::new(w[(0, c)], w[(1, c)], w[(2, c)]);
                let vc = Vector3::new(v[(0, c)], v[(1, c)], v[(2, c)]);
                let w2 = rt * wc;
                let v2 = rt * (vc + wc.cross(&p));
                for r in 0..3 {
                    w[(r, c)] = w2[r];
                    v[(r, c)] = v2[r];
                }
            }
        };
        let actuate =
            |i: usize, joint: &NumericJoint, w: &mut DMatrix<f64>, v: &mut DMatrix<f64>| {
                let rate = if joint.flip { -1.0 } else { 1.0 };
                match joint.kind {
                    JointKind::Revolute => w[(2, i)] += rate,
                    JointKind::Prismatic => v[(2, i)] += rate,
                }
            };
        for (i, joint) in self.joints.iter().enumerate() {
            let (theta, d) = joint.theta_d(q[i]);
            match self.convention {
                Convention::Standard => {
                    actuate(i, joint, &mut w, &mut v);
                    cross(&self.link(i, q[i]), &mut w, &mut v);
                }
                Convention::Modified => {
                    cross(
                        &(rot_x(joint.alpha) * trans(joint.a, 0.0, 0.0)),
                        &mut w,
                        &mut v,
                    );
                    actuate(i, joint, &mut w, &mut v);
                    cross(&(rot_z(theta) * trans(0.0, 0.0, d)), &mut w, &mut v);
                }
            }
        }
        cross(&self.tool, &mut w, &mut v);
        let r = rotation(&self.fk(q)?);
        let mut j = Jacobian::zeros(n);
        for c in 0..n {
            let wc = r * Vector3::new(w[(0, c)], w[(1, c)], w[(2, c)]);
            let vc = r * Vector3::new(v[(0, c)], v[(1, c)], v[(2, c)]);
            j.fixed_view_mut::<3, 1>(0, c).copy_from(&vc);
            j.fixed_view_mut::<3, 1>(3, c).copy_from(&wc);
        }
        Ok(j)
    }

    /// Joint axes `z_i` and points `o_i` on them (world frame), and the tool point `p`:
    /// what [`jacobian`](Self::jacobian) builds its columns from (a flipped joint's axis
    /// is `−z`, which its positive rate turns about).
    fn axes(&self, q: &[f64]) -> Result<(Vec<Axis>, Vector3<f64>), NumericError> {
        let frames = self.frames(q)?;
        let p = position(&(frames.last().copied().unwrap_or(self.base) * self.tool));
        let axes = (0..self.dof())
            .map(|i| {
                let f = match self.convention {
                    Convention::Standard if i == 0 => self.base,
                    Convention::Standard => frames[i - 1],
                    Convention::Modified => frames[i],
                };
                let z: Vector3<f64> = f.fixed_view::<3, 1>(0, 2).into_owned();
                let z = if self.joints[i].flip { -z } else { z };
                (z, position(&f))
            })
            .collect();
        Ok((axes, p))
    }

    /// The kinematic Hessian `H[j] = ∂J/∂q_j` (world frame), the textbook way: with `z`
    /// the joint axes, `o` points on them and `p` the tool point, for a revolute joint `j`
    /// and `j ≤ i` column `i` of `H[j]` is `[z_j × (z_i × (p − o_i)); z_j × z_i]` (prismatic
    /// `i`: `[z_j × z_i; 0]`), for `j > i` it is `[z_i × v_j; 0]` with `v_j` column `j`'s
    /// linear part; a prismatic joint `j` moves axes without turning them, so it changes
    /// only the columns of the revolute joints before it (`[z_i × z_j; 0]`).
    pub fn hessian(&self, q: &[f64]) -> Result<Vec<Jacobian>, NumericError> {
        let (axes, p) = self.axes(q)?;
        let n = self.dof();
        let revolute = |i: usize| self.joints[i].kind == JointKind::Revolute;
        // Linear part of column i.
        let v = |i: usize| {
            let (z, o) = axes[i];
            if revolute(i) {
                z.cross(&(p - o))
            } else {
                z
            }
        };
        let mut h = vec![Jacobian::zeros(n); n];
        for (j, hj) in h.iter_mut().enumerate() {
            for i in 0..n {
                let (zi, zj) = (axes[i].0, axes[j].0);
                let (lin, ang) = if j <= i {
                    if !revolute(j) {
                        (Vector3::zeros(), Vector3::zeros())
                    } else if revolute(i) {
                        (zj.cross(&v(i)), zj.cross(&zi))
                    } else {
                        (zj.cross(&zi), Vector3::zeros())
                    }
                } else if revolute(i) {
                    (zi.cross(&v(j)), Vector3::zeros())
                } else {
                    (Vector3::zeros(), Vector3::zeros())
                };
                hj.fixed_view_mut::<3, 1>(0, i).copy_from(&lin);
                hj.fixed_view_mut::<3, 1>(3, i).copy_from(&ang);
            }
        }
        Ok(h)
    }

    /// The Hessian by central differences of [`jacobian`](Self::jacobian):
    /// `H[j] ≈ (J(q + h e_j) − J(q − h e_j)) / 2h`.
    pub fn hessian_fd(&self, q: &[f64], h: f64) -> Result<Vec<Jacobian>, NumericError> {
        self.check(q)?;
        if !(h.is_finite() && h > 0.0) {
            return Err(NumericError::BadStep(h));
        }
        let mut qp = q.to_vec();
        (0..self.dof())
            .map(|j| {
                qp[j] = q[j] + h;
                let plus = self.jacobian(&qp)?;
                qp[j] = q[j] - h;
                let minus = self.jacobian(&qp)?;
                qp[j] = q[j];
                Ok((plus - minus) / (2.0 * h))
            })
            .collect()
    }

    /// `J̇` along the joint rates `qd` by central differences in time of
    /// [`jacobian`](Self::jacobian) along `q + t·q̇`: `(J(q + h q̇) − J(q − h q̇)) / 2h`.
    pub fn jacobian_dot_fd(&self, q: &[f64], qd: &[f64], h: f64) -> Result<Jacobian, NumericError> {
        self.along(q, qd, h, &|q| self.jacobian(q))
    }

    /// `d/dt` of [`jacobian_ee`](Self::jacobian_ee) along `qd`, by central differences in
    /// time.
    pub fn jacobian_ee_dot_fd(
        &self,
        q: &[f64],
        qd: &[f64],
        h: f64,
    ) -> Result<Jacobian, NumericError> {
        self.along(q, qd, h, &|q| self.jacobian_ee(q))
    }

    fn along(
        &self,
        q: &[f64],
        qd: &[f64],
        h: f64,
        f: &dyn Fn(&[f64]) -> Result<Jacobian, NumericError>,
    ) -> Result<Jacobian, NumericError> {
        self.check(q)?;
        self.check(qd)?;
        if !(h.is_finite() && h > 0.0) {
            return Err(NumericError::BadStep(h));
        }
        let at = |t: f64| -> Vec<f64> { q.iter().zip(qd).map(|(x, v)| x + t * v).collect() };
        Ok((f(&at(h))? - f(&at(-h))?) / (2.0 * h))
    }

    /// The bias acceleration `J̇ q̇` by recursive velocity and acceleration propagation
    /// from the base (Craig §6.7, outward iterations with `q̈ = 0`): each frame carries its
    /// link's angular velocity `ω` and acceleration `α` and its origin's velocity `v` and
    /// acceleration `a`, in its own coordinates. Across a transform `(R, p)` (fixed in the
    /// link): `ω' = Rᵀ ω`, `α' = Rᵀ α`, `v' = Rᵀ (v + ω × p)`,
    /// `a' = Rᵀ (a + α × p + ω × (ω × p))`. At a revolute joint turning about the local z
    /// at rate `q̇`: `α += ω × q̇ẑ`, then `ω += q̇ẑ`; at a prismatic one sliding along it:
    /// `a += 2 ω × q̇ẑ` (Coriolis), then `v += q̇ẑ`. Rows `[a; α]` of the tool point and
    /// frame, rotated into the world frame.
    pub fn jdot_qdot_propagation(&self, q: &[f64], qd: &[f64]) -> Result<[f64; 6], NumericError> {
        self.check(q)?;
        self.check(qd)?;
        let mut m = Motion::default();
        for (i, joint) in self.joints.iter().enumerate() {
            let (theta, d) = joint.theta_d(q[i]);
            // A flipped joint moves about −z at rate q̇: about z at −q̇.
            let rate = if joint.flip { -qd[i] } else { qd[i] };
            match self.convention {
                Convention::Standard => {
                    m.actuate(joint.kind, rate);
                    m.carry(&self.link(i, q[i]));
                }
                Convention::Modified => {
                    m.carry(&(rot_x(joint.alpha) * trans(joint.a, 0.0, 0.0)));
                    m.actuate(joint.kind, rate);
                    m.carry(&(rot_z(theta) * trans(0.0, 0.0, d)));
                }
            }
        }
        m.carry(&self.tool);
        let r = rotation(&self.fk(q)?);
        let (a, alpha) = (r * m.a, r * m.alpha);
        Ok([a[0], a[1], a[2], alpha[0], alpha[1], alpha[2]])
    }

    /// The rows of [`jacobian`](Self::jacobian) named by the robot's task (all six if none).
    pub fn task_jacobian(&self, q: &[f64]) -> Result<DMatrix<f64>, NumericError> {
        let j = self.jacobian(q)?;
        let rows: Vec<usize> = match &self.task {
            Some(t) => t.iter().map(|r| r.index()).collect(),
            None => (0..6).collect(),
        };
        Ok(DMatrix::from_fn(rows.len(), self.dof(), |r, c| {
            j[(rows[r], c)]
        }))
    }
}

/// A joint axis (unit vector) and a point on it.
type Axis = (Vector3<f64>, Vector3<f64>);

/// Velocities and accelerations of a frame moving with the chain, in its own coordinates.
#[derive(Clone, Copy, Debug, Default)]
struct Motion {
    /// Angular velocity of the link.
    w: Vector3<f64>,
    /// Angular acceleration of the link.
    alpha: Vector3<f64>,
    /// Velocity of the origin.
    v: Vector3<f64>,
    /// Acceleration of the origin.
    a: Vector3<f64>,
}

impl Motion {
    /// Into the frame `t` (fixed in the current link) away from the current origin.
    fn carry(&mut self, t: &Matrix4<f64>) {
        let (rt, p) = (rotation(t).transpose(), position(t));
        let wp = self.w.cross(&p);
        self.a = rt * (self.a + self.alpha.cross(&p) + self.w.cross(&wp));
        self.v = rt * (self.v + wp);
        self.w = rt * self.w;
        self.alpha = rt * self.alpha;
    }

    /// A joint moving about (revolute) or along (prismatic) the local z at rate `rate`.
    fn actuate(&mut self, kind: JointKind, rate: f64) {
        let z = Vector3::new(0.0, 0.0, rate);
        match kind {
            JointKind::Revolute => {
                self.alpha += self.w.cross(&z);
                self.w += z;
            }
            JointKind::Prismatic => {
                self.a += 2.0 * self.w.cross(&z);
                self.v += z;
            }
        }
    }
}

/// Determinant of a 6×6 Jacobian (a 6-joint robot).
pub fn det6(j: &Jacobian) -> Result<f64, NumericError> {
    if j.ncols() != 6 {
        return Err(NumericError::NotSquare {
            rows: 6,
            cols: j.ncols(),
        });
    }
    Ok(Matrix6::from_fn(|r, c| j[(r, c)]).determinant())
}

/// Determinant of any square matrix (e.g. a task Jacobian with as many rows as joints).
pub fn det(m: &DMatrix<f64>) -> Result<f64, NumericError> {
    if !m.is_square() {
        return Err(NumericError::NotSquare {
            rows: m.nrows(),
            cols: m.ncols(),
        });
    }
    Ok(m.clone().determinant())
}

/// Yoshikawa's manipulability `√det(J Jᵀ)` of an m×n Jacobian (any rows, e.g. a task
/// Jacobian), computed as the product of the m largest singular values, which equals it
/// without the cancellation of forming `J Jᵀ`. Zero when m > n (J Jᵀ is singular).
pub fn manipulability(j: &DMatrix<f64>) -> f64 {
    let (m, n) = j.shape();
    if m > n {
        return 0.0;
    }
    let sv = j.clone().svd(false, false).singular_values;
    sv.iter().take(m).product()
}

/// The gradient of [`manipulability`] from the Jacobian `j` (M×N) and its Hessian `h`
/// (`h[k] = ∂J/∂q_k`, same rows): `∂w/∂q_k = w · tr(J⁺ H_k)`, with nalgebra's SVD for `w`
/// and the pseudo-inverse `J⁺`. Zero where `w` is (below `1e-300`: not differentiable;
/// identically for a tall `j`).
pub fn manipulability_gradient(j: &DMatrix<f64>, h: &[DMatrix<f64>]) -> Vec<f64> {
    let w = manipulability(j);
    if w < 1e-300 {
        return vec![0.0; h.len()];
    }
    let pinv = j
        .clone()
        .pseudo_inverse(0.0)
        .unwrap_or_else(|_| DMatrix::zeros(j.ncols(), j.nrows()));
    h.iter().map(|hk| w * (&pinv * hk).trace()).collect()
}

/// [`manipulability`] of a 6×N Jacobian.
pub fn manipulability6(j: &Jacobian) -> f64 {
    manipulability(&DMatrix::from_fn(6, j.ncols(), |r, c| j[(r, c)]))
}

/// `count` deterministic configurations of `dof` joint values, uniform in [−π, π]
/// (SplitMix64 from `seed`): the random inputs of the tests, the same on every run.
pub fn configurations(seed: u64, count: usize, dof: usize) -> Vec<Vec<f64>> {
    let mut state = seed;
    let mut unit = move || {
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..count)
        .map(|_| {
            (0..dof)
                .map(|_| std::f64::consts::PI * (2.0 * unit() - 1.0))
                .collect()
        })
        .collect()
}

/// [`NumericRobot::fk`] with default parameters.
pub fn fk(robot: &Robot, q: &[f64]) -> Result<Matrix4<f64>, NumericError> {
    NumericRobot::new(robot)?.fk(q)
}

/// [`NumericRobot::frames`] with default parameters.
pub fn frames(robot: &Robot, q: &[f64]) -> Result<Vec<Matrix4<f64>>, NumericError> {
    NumericRobot::new(robot)?.frames(q)
}

/// [`NumericRobot::jacobian`] with default parameters.
pub fn jacobian(robot: &Robot, q: &[f64]) -> Result<Jacobian, NumericError> {
    NumericRobot::new(robot)?.jacobian(q)
}

/// [`NumericRobot::jacobian_ee`] with default parameters.
pub fn jacobian_ee(robot: &Robot, q: &[f64]) -> Result<Jacobian, NumericError> {
    NumericRobot::new(robot)?.jacobian_ee(q)
}

/// [`NumericRobot::jacobian_fd`] with default parameters.
pub fn jacobian_fd(robot: &Robot, q: &[f64], h: f64) -> Result<Jacobian, NumericError> {
    NumericRobot::new(robot)?.jacobian_fd(q, h)
}

/// [`NumericRobot::jacobian_propagation`] with default parameters.
pub fn jacobian_propagation(robot: &Robot, q: &[f64]) -> Result<Jacobian, NumericError> {
    NumericRobot::new(robot)?.jacobian_propagation(q)
}

/// [`NumericRobot::task_jacobian`] with default parameters.
pub fn task_jacobian(robot: &Robot, q: &[f64]) -> Result<DMatrix<f64>, NumericError> {
    NumericRobot::new(robot)?.task_jacobian(q)
}

#[cfg(test)]
mod tests;
