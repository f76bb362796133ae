//! The kinematic chain: a robot as a sequence of elementary transforms, and its
//! symbolic frames built as straight-line code.
//!
//! DH is one way to build a chain (`Rz θ, Tz d, Tx a, Rx α` per joint, or the modified
//! order); base and tool add `T(xyz) Rz Ry Rx`. Angles whose value is a multiple of
//! π/6 or π/4 fold to exact constants in ℚ[√2, √3]; any other constant angle, or one
//! that depends on a parameter, becomes a sine/cosine pair of its own.

use num_traits::{One, Signed, Zero};

use crate::dh::{Convention, Frame, JointKind, Robot};
use crate::generate::Deadline;
use crate::graph::{Graph, Id};
use crate::poly::Var;
use crate::value::{Rat, Value};

/// Where an angle's sine and cosine come from at run time.
#[derive(Clone, Debug, PartialEq)]
pub enum AngleSource {
    /// `sin_cos(q[joint] + offset)`; `offset` is zero unless the table has a
    /// non-foldable offset.
    Joint {
        /// Joint index (0-based).
        joint: usize,
        /// Constant added to `q[joint]`.
        offset: Value,
    },
    /// A constant angle that does not fold (e.g. a twist of 0.3 rad or one that
    /// names a parameter).
    Constant(Value),
}

/// One sine/cosine pair of the chain.
#[derive(Clone, Debug, PartialEq)]
pub struct AngleDef {
    /// Where its value comes from.
    pub source: AngleSource,
    /// Ring variables `(s, c)`.
    pub vars: (Var, Var),
    /// Name suffix (`1` for joint 1: `s1`, `c1`).
    pub suffix: String,
}

/// A symbolic rigid transform: rotation as three columns, and the origin.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Transform {
    /// `cols[j][i]` is `R[i][j]`.
    pub cols: [[Id; 3]; 3],
    /// Origin.
    pub p: [Id; 3],
}

impl Transform {
    /// The identity.
    pub fn identity(g: &mut Graph) -> Self {
        let (o, l) = (g.int(0), g.int(1));
        Transform {
            cols: [[l, o, o], [o, l, o], [o, o, l]],
            p: [o, o, o],
        }
    }

    /// `R[i][j]`.
    pub fn r(&self, i: usize, j: usize) -> Id {
        self.cols[j][i]
    }

    /// The z axis (third column).
    pub fn z(&self) -> [Id; 3] {
        self.cols[2]
    }
}

/// `R · v` for the rotation of `w` (zeros and ones fold away).
pub fn rotate(g: &mut Graph, w: &Transform, v: [Id; 3]) -> [Id; 3] {
    let mut out = [0; 3];
    for (i, o) in out.iter_mut().enumerate() {
        let terms: Vec<Id> = (0..3).map(|m| g.mul(w.cols[m][i], v[m])).collect();
        *o = g.sum(&terms);
    }
    out
}

/// An elementary transform.
#[derive(Clone, Copy, Debug)]
enum Elem {
    Rot { axis: usize, s: Id, c: Id },
    Trans { axis: usize, d: Id },
}

/// The symbolic chain of a robot.
#[derive(Clone, Debug)]
pub struct Chain {
    /// The straight-line code and its ring.
    pub graph: Graph,
    /// Sine/cosine pairs, in order of first use.
    pub angles: Vec<AngleDef>,
    /// Ring variables of prismatic joints: `(joint, var)`.
    pub joint_vars: Vec<(usize, Var)>,
    /// Ring variables of named parameters: `(name, var)`.
    pub param_vars: Vec<(String, Var)>,
    /// `base · A1 ⋯ Ai` for i = 1..=N.
    pub frames: Vec<Transform>,
    /// The base frame (frame 0).
    pub base: Transform,
    /// `base · A1 ⋯ AN · tool`.
    pub tool: Transform,
    /// For each joint: its axis (unit z of the frame it rotates or slides about) and a
    /// point on it, in world coordinates.
    pub axes: Vec<([Id; 3], [Id; 3])>,
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

impl Chain {
    /// Build the symbolic chain of a checked robot, left to right from the base.
    pub fn new(robot: &Robot, max_terms: usize) -> Chain {
        Chain::with_pivot(robot, max_terms, None).0
    }

    /// Build the chain; with `pivot = Some(k)` (`1 ≤ k < N`) the frames after `k` are
    /// built in frame `k` and composed with `T_k` (see [`Pivot`]).
    pub fn with_pivot(
        robot: &Robot,
        max_terms: usize,
        pivot: Option<usize>,
    ) -> (Chain, Option<Pivot>) {
        Chain::with_pivot_until(robot, max_terms, pivot, Deadline::never())
    }

    /// [`Chain::with_pivot`] with a deadline: the graph drops new normal forms once it
    /// has passed (the chain is still complete and correct, only less simplified), and
    /// keeps it for the phases that build on the chain.
    pub fn with_pivot_until(
        robot: &Robot,
        max_terms: usize,
        pivot: Option<usize>,
        deadline: Deadline,
    ) -> (Chain, Option<Pivot>) {
        let mut graph = Graph::new(Default::default(), max_terms);
        graph.deadline = deadline;
        let mut b = Builder {
            graph,
            angles: Vec::new(),
            joint_vars: Vec::new(),
            param_vars: Vec::new(),
            consts: 0,
        };
        let mut t = Transform::identity(&mut b.graph);
        if let Some(f) = &robot.base {
            for e in b.frame_elems(f) {
                t = b.apply(&t, e);
            }
        }
        let base = t;
        let n = robot.dof();
        let pivot_at = pivot.filter(|&k| k >= 1 && k < n);
        let mut frames = Vec::new();
        let mut axes = Vec::new();
        // In pivot mode, `t` is local to frame k after the pivot and `world` maps it out.
        let mut world: Option<Transform> = None;
        let mut local_axes = Vec::new();
        for (i, j) in robot.joints.iter().enumerate() {
            if pivot_at == Some(i) {
                world = Some(t);
                t = Transform::identity(&mut b.graph);
            }
            let (sq, cq) = match j.kind {
                JointKind::Revolute => b.joint_angle(i, &j.theta),
                JointKind::Prismatic => b.const_angle(&j.theta),
            };
            let d = match j.kind {
                JointKind::Revolute => b.length(&j.d),
                JointKind::Prismatic => {
                    let v = b.graph.ring.joint(i, &format!("q{}", i + 1));
                    b.joint_vars.push((i, v));
                    let q = b.graph.leaf(v);
                    let k = b.length(&j.d);
                    b.graph.add(q, k)
                }
            };
            let a = b.length(&j.a);
            let (sa, ca) = b.const_angle(&j.alpha);
            let rz = Elem::Rot {
                axis: 2,
                s: sq,
                c: cq,
            };
            let tz = Elem::Trans { axis: 2, d };
            let tx = Elem::Trans { axis: 0, d: a };
            let rx = Elem::Rot {
                axis: 0,
                s: sa,
                c: ca,
            };
            let axis = match robot.convention {
                Convention::Standard => {
                    // The joint moves about z of the previous frame.
                    let axis = (t.z(), t.p);
                    for e in [rz, tz, tx, rx] {
                        t = b.apply(&t, e);
                    }
                    axis
                }
                Convention::Modified => {
                    for e in [rx, tx, rz, tz] {
                        t = b.apply(&t, e);
                    }
                    // The joint moves about z of its own frame.
                    (t.z(), t.p)
                }
            };
            match &world {
                Some(w) => {
                    local_axes.push(axis);
                    let z = b.rotate(w, axis.0);
                    let o = b.point(w, axis.1);
                    axes.push((z, o));
                    frames.push(b.compose(w, &t));
                }
                None => {
                    axes.push(axis);
                    frames.push(t);
                }
            }
        }
        if let Some(f) = &robot.tool {
            for e in b.frame_elems(f) {
                t = b.apply(&t, e);
            }
        }
        let (tool, pivot) = match (world, pivot_at) {
            (Some(w), Some(k)) => (
                b.compose(&w, &t),
                Some(Pivot {
                    k,
                    frame: w,
                    axes: local_axes,
                    tool: t,
                }),
            ),
            _ => (t, None),
        };
        (
            Chain {
                graph: b.graph,
                angles: b.angles,
                joint_vars: b.joint_vars,
                param_vars: b.param_vars,
                frames,
                base,
                tool,
                axes,
            },
            pivot,
        )
    }
}

struct Builder {
    graph: Graph,
    angles: Vec<AngleDef>,
    joint_vars: Vec<(usize, Var)>,
    param_vars: Vec<(String, Var)>,
    consts: usize,
}

impl Builder {
    fn param(&mut self, name: &str) -> Id {
        let v = self.graph.ring.param(name);
        if !self.param_vars.iter().any(|(n, _)| n == name) {
            self.param_vars.push((name.to_string(), v));
        }
        self.graph.leaf(v)
    }

    /// A length entry: rational constant plus parameters.
    fn length(&mut self, v: &Value) -> Id {
        let mut acc = self.graph.num(v.konst.clone());
        for (name, c) in &v.params {
            let p = self.param(name);
            let k = self.graph.num(c.clone());
            let term = self.graph.mul(k, p);
            acc = self.graph.add(acc, term);
        }
        acc
    }

    fn new_angle(&mut self, source: AngleSource, suffix: String) -> (Id, Id) {
        let n = self.angles.len();
        let vars = self.graph.ring.angle(n, &suffix);
        self.angles.push(AngleDef {
            source,
            vars,
            suffix,
        });
        (self.graph.leaf(vars.0), self.graph.leaf(vars.1))
    }

    /// θ = q_i + value: fold multiples of π/2 exactly, else a runtime offset.
    fn joint_angle(&mut self, i: usize, value: &Value) -> (Id, Id) {
        let quarter = value.konst.is_zero() && value.params.is_empty() && {
            let k = &value.pi * Rat::from_integer(2.into());
            k.is_integer()
        };
        let offset = if quarter {
            Value::zero()
        } else {
            value.clone()
        };
        let (s, c) = self.new_angle(
            AngleSource::Joint { joint: i, offset },
            format!("{}", i + 1),
        );
        if !quarter {
            return (s, c);
        }
        // sin/cos(q + kπ/2)
        let k = (&value.pi * Rat::from_integer(2.into())).to_integer();
        let k = ((k % 4) + 4) % 4;
        let k: u32 = num_traits::ToPrimitive::to_u32(&k).unwrap_or(0);
        let g = &mut self.graph;
        match k {
            0 => (s, c),
            1 => (c, g.neg(s)),
            2 => (g.neg(s), g.neg(c)),
            _ => (g.neg(c), s),
        }
    }

    /// A constant angle: exact for multiples of π/6 and π/4, else its own pair.
    fn const_angle(&mut self, value: &Value) -> (Id, Id) {
        if value.konst.is_zero() && value.params.is_empty() {
            if let Some((s, c)) = self.exact_sin_cos(&value.pi) {
                return (s, c);
            }
        }
        self.consts += 1;
        let suffix = format!("_k{}", self.consts);
        self.new_angle(AngleSource::Constant(value.clone()), suffix)
    }

    /// sin and cos of `t·π` when t is a multiple of 1/4 or 1/6.
    fn exact_sin_cos(&mut self, t: &Rat) -> Option<(Id, Id)> {
        let two = Rat::from_integer(2.into());
        // t mod 2 in [0, 2)
        let mut t = t - (t / &two).floor() * &two;
        let mut sign_s = Rat::one();
        let mut sign_c = Rat::one();
        if t >= Rat::one() {
            t -= Rat::one();
            sign_s = -sign_s;
            sign_c = -sign_c;
        }
        let half = Rat::new(1.into(), 2.into());
        if t > half {
            t = Rat::one() - t;
            sign_c = -sign_c;
        }
        let r = |n: i64, d: i64| Rat::new(n.into(), d.into());
        // (rational part, √k part) of sin and cos for t in [0, 1/2].
        type Surd = (Rat, u32);
        let table: [(Rat, Surd, Surd); 5] = [
            (r(0, 1), (r(0, 1), 1), (r(1, 1), 1)),
            (r(1, 6), (r(1, 2), 1), (r(1, 2), 3)),
            (r(1, 4), (r(1, 2), 2), (r(1, 2), 2)),
            (r(1, 3), (r(1, 2), 3), (r(1, 2), 1)),
            (r(1, 2), (r(1, 1), 1), (r(0, 1), 1)),
        ];
        let (_, (sk, sq), (ck, cq)) = table.into_iter().find(|(x, _, _)| *x == t)?;
        let s = self.surd(&(sk * sign_s), sq);
        let c = self.surd(&(ck * sign_c), cq);
        Some((s, c))
    }

    /// `k·√n` (n = 1 means the rational k).
    fn surd(&mut self, k: &Rat, n: u32) -> Id {
        let kk = self.graph.num(k.abs());
        let x = if n == 1 {
            kk
        } else {
            let v = self.graph.ring.sqrt(n);
            let l = self.graph.leaf(v);
            self.graph.mul(kk, l)
        };
        if k.is_negative() {
            self.graph.neg(x)
        } else {
            x
        }
    }

    fn frame_elems(&mut self, f: &Frame) -> Vec<Elem> {
        let mut out = Vec::new();
        for (axis, v) in f.xyz.iter().enumerate() {
            if !v.is_zero() {
                let d = self.length(v);
                out.push(Elem::Trans { axis, d });
            }
        }
        // R = Rz(yaw) Ry(pitch) Rx(roll)
        for (axis, v) in [(2, &f.rpy[2]), (1, &f.rpy[1]), (0, &f.rpy[0])] {
            if !v.is_zero() {
                let (s, c) = self.const_angle(v);
                out.push(Elem::Rot { axis, s, c });
            }
        }
        out
    }

    /// `R · v` for the rotation of `w`.
    fn rotate(&mut self, w: &Transform, v: [Id; 3]) -> [Id; 3] {
        rotate(&mut self.graph, w, v)
    }

    /// `R · v + p` for `w = [R | p]`.
    fn point(&mut self, w: &Transform, v: [Id; 3]) -> [Id; 3] {
        let r = self.rotate(w, v);
        let g = &mut self.graph;
        [
            g.add(w.p[0], r[0]),
            g.add(w.p[1], r[1]),
            g.add(w.p[2], r[2]),
        ]
    }

    /// `w · t`.
    fn compose(&mut self, w: &Transform, t: &Transform) -> Transform {
        Transform {
            cols: [
                self.rotate(w, t.cols[0]),
                self.rotate(w, t.cols[1]),
                self.rotate(w, t.cols[2]),
            ],
            p: self.point(w, t.p),
        }
    }

    /// `t · e`, column by column.
    fn apply(&mut self, t: &Transform, e: Elem) -> Transform {
        let g = &mut self.graph;
        let mut out = *t;
        match e {
            Elem::Trans { axis, d } => {
                for i in 0..3 {
                    let m = g.mul(d, t.cols[axis][i]);
                    out.p[i] = g.add(t.p[i], m);
                }
            }
            Elem::Rot { axis, s, c } => {
                // Right-multiplying by a rotation about `axis` mixes the other two
                // columns (u, v) cyclically: u' = c·u + s·v, v' = −s·u + c·v.
                let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
                for i in 0..3 {
                    let (cu, cv) = (t.cols[u][i], t.cols[v][i]);
                    let a = g.mul(c, cu);
                    let b = g.mul(s, cv);
                    out.cols[u][i] = g.add(a, b);
                    let a = g.mul(s, cu);
                    let b = g.mul(c, cv);
                    out.cols[v][i] = g.sub(b, a);
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dh::{validate, RawJoint, RawRobot, RawValue};

    fn planar_rr() -> Robot {
        let row = |a: &str| RawJoint {
            kind: Some("revolute".into()),
            fields: vec![
                ("a".into(), RawValue::Text(a.into())),
                ("alpha".into(), RawValue::Number(0.0)),
                ("d".into(), RawValue::Number(0.0)),
            ],
        };
        validate(&RawRobot {
            name: Some("RR".into()),
            convention: Some("standard".into()),
            params: vec![
                ("L1".into(), RawValue::Number(1.0)),
                ("L2".into(), RawValue::Number(1.0)),
            ],
            joints: vec![row("L1"), row("L2")],
            ..Default::default()
        })
        .unwrap()
    }

    #[test]
    fn planar_rr_position_is_textbook() {
        let chain = Chain::new(&planar_rr(), 1000);
        let g = &chain.graph;
        let px = g.nf(chain.tool.p[0]).unwrap();
        assert_eq!(
            g.ring.display(px).to_string(),
            "-s1*s2*L2 + c1*L1 + c1*c2*L2"
        );
        assert_eq!(g.as_num(chain.tool.p[2]), Some(&Rat::zero()));
    }

    #[test]
    fn exact_twists() {
        let mut b = Builder {
            graph: Graph::default(),
            angles: vec![],
            joint_vars: vec![],
            param_vars: vec![],
            consts: 0,
        };
        for (t, s, c) in [
            (Rat::new(1.into(), 2.into()), 1.0, 0.0),
            (Rat::new((-1).into(), 2.into()), -1.0, 0.0),
            (Rat::new(1.into(), 3.into()), 3f64.sqrt() / 2.0, 0.5),
            (
                Rat::new(3.into(), 4.into()),
                0.5f64.sqrt(),
                -(0.5f64.sqrt()),
            ),
            (Rat::new(7.into(), 6.into()), -0.5, -(3f64.sqrt() / 2.0)),
            (Rat::one(), 0.0, -1.0),
        ] {
            let (si, ci) = b.exact_sin_cos(&t).unwrap();
            let ring = b.graph.ring.clone();
            let val = |v: Var| match ring.kind(v) {
                crate::poly::VarKind::Sqrt(k) => (*k as f64).sqrt(),
                _ => f64::NAN,
            };
            assert!((b.graph.eval(si, &val) - s).abs() < 1e-15, "sin {t}");
            assert!((b.graph.eval(ci, &val) - c).abs() < 1e-15, "cos {t}");
        }
        assert!(b.exact_sin_cos(&Rat::new(1.into(), 5.into())).is_none());
    }
}
