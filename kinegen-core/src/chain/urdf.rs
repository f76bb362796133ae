//! A URDF chain as a [`Chain`]: the joints on the path from a base link to a tip link,
//! each `origin` as elementary transforms, each movable joint as a [`Motion`].
//!
//! - A joint is `Trans(xyz) · Rz(yaw) · Ry(pitch) · Rx(roll)` (zero entries left out),
//!   then its motion about (revolute, continuous) or along (prismatic) its axis in the
//!   joint frame, read there for the Jacobian ([`AxisAt::Motion`]). Fixed joints fold
//!   into the constant transforms around them: before the first movable joint they are
//!   the chain's base, after the last its tool.
//! - Axes along ±x, ±y, ±z are exact (`-z` is a motion about z with `sign = -1`). Any
//!   other axis `u` is `Rz(φ) Ry(θ)` (which takes z onto u), the motion about z, then
//!   `Ry(−θ) Rz(−φ)`: φ and θ are exact when they are multiples of π/12 — decided
//!   exactly from the file's decimals (`1 1 0`, `0 1 1` are exact) or within the snap
//!   tolerance — and otherwise the nearest doubles, said so in [`Chain::snaps`].
//! - **Snapping.** URDF writes π/2 as `1.5707963267948966`, `1.570796327` or `1.5708`
//!   and zero as `1e-17`. Angles within [`Selection::snap`] (radians) of a multiple of
//!   π/12, and lengths within it (metres) of 0, become that exact value, so the
//!   structure the closed forms depend on (cos α = 0) survives. The default
//!   [`DEFAULT_SNAP`] = 1e-4 snaps `1.5708` (3.7e-6 from π/2) and `3.1416`; `snap = 0`
//!   keeps every decimal exactly as written. Every snap is listed with the error it can
//!   cause ([`Snap`]).
//! - Named lengths ([`Selection::params`], `d1 = "shoulder_pan_joint.origin.z"`) stay
//!   symbolic and become fields of the generated type, with the file's value as default.
//! - `q` is ordered along the chain, base to tip, movable joints only. Limits come from
//!   `<limit>` (none for continuous joints). Floating and planar joints, and mimic
//!   joints, on the chain are errors; joints off the chain are ignored.

use std::collections::BTreeMap;
use std::f64::consts::PI;

use num_traits::{Signed, Zero};

use crate::chain::named_lengths;
use crate::chain::{unit, Axis, AxisAt, Chain, Elem, Link, Motion, Snap};
use crate::front::located::LoadError;
use crate::front::urdf::{Joint, JointType, Number, Urdf};
use crate::model::raw::Path;
use crate::model::robot::{JointKind, Param, Scalar};
use crate::model::validate::param_name_problem;
use crate::model::value::{parse_decimal, rat_to_f64, Rat, Value};

/// The default snap tolerance: radians for angles, metres for lengths.
pub const DEFAULT_SNAP: f64 = 1e-4;

/// Which chain of the tree, and how to read its numbers.
#[derive(Clone, Debug, PartialEq)]
pub struct Selection {
    /// The base link (default: the root).
    pub base: Option<String>,
    /// The tip link (default: the only leaf after a moving joint, or the one before a
    /// parallel gripper's prismatic fingers, see
    /// [`Urdf::path`](crate::front::urdf::Urdf::path)).
    pub tip: Option<String>,
    /// Snap tolerance (radians / metres); 0 keeps every decimal exactly.
    pub snap: f64,
    /// Named lengths `(name, "joint.origin.x|y|z")`: symbolic, fields of the type.
    pub params: Vec<(String, String)>,
    /// Name every other non-zero length too (`d1`, `a2`…: [`named_lengths`]), so every
    /// formula is in symbols.
    pub symbolic: bool,
}

impl Default for Selection {
    fn default() -> Self {
        Selection {
            base: None,
            tip: None,
            snap: DEFAULT_SNAP,
            params: Vec::new(),
            symbolic: false,
        }
    }
}

/// A snap before its bounds are known: which joint (index on the path) and where.
struct Pending {
    snap: Snap,
    joint: usize,
    kind: SnapKind,
}

#[derive(Clone, Copy, PartialEq)]
enum SnapKind {
    Length,
    /// A constant rotation in joint `joint`'s origin.
    Rotation,
    /// The joint's axis.
    Axis,
}

const XYZ: [&str; 3] = ["x", "y", "z"];
const RPY: [&str; 3] = ["roll", "pitch", "yaw"];

impl Urdf {
    /// The chain `sel.base → sel.tip` (see the module docs).
    ///
    /// Errors name the file's line; those about an option carry its path (`base`,
    /// `tip`, `snap`, `params.d1`) so a front end can point at the option instead.
    pub fn chain(&self, sel: &Selection) -> Result<Chain, LoadError> {
        if !(sel.snap.is_finite() && sel.snap >= 0.0) {
            return Err(self.error(
                self.line,
                Path::root().key("snap"),
                format!("`snap` must be a tolerance ≥ 0, not {}", sel.snap),
            ));
        }
        let (base, tip, joints) = self.path(sel.base.as_deref(), sel.tip.as_deref())?;
        let auto = match sel.symbolic {
            true => named_lengths::name_lengths(&joints, &sel.params, sel.snap),
            false => Vec::new(),
        };
        let mut wanted = sel.params.clone();
        wanted.extend(auto.iter().map(|n| (n.name.clone(), n.entry.clone())));
        let (names, params) = self.named_lengths(&wanted, &joints)?;
        let named_rows = self.named_summary(&names, &joints);
        let mut b = Builder {
            tol: sel.snap,
            names,
            pending: Vec::new(),
        };
        let mut fixed: Vec<Elem> = Vec::new();
        let mut base_elems = Vec::new();
        let mut links = Vec::new();
        for (k, j) in joints.iter().enumerate() {
            let origin = b.origin(k, j);
            let kind = match j.kind {
                JointType::Fixed => {
                    fixed.extend(origin);
                    continue;
                }
                JointType::Revolute | JointType::Continuous => JointKind::Revolute,
                JointType::Prismatic => JointKind::Prismatic,
                JointType::Floating | JointType::Planar => {
                    return Err(self.error(
                        j.line,
                        Path::root().key(&j.name),
                        format!(
                            "joint `{}` on the chain `{base}` → `{tip}` is {}: kinegen takes revolute, \
                             continuous, prismatic and fixed joints",
                            j.name,
                            j.kind.name()
                        ),
                    ))
                }
            };
            if let Some(m) = &j.mimic {
                return Err(self.error(
                    j.line,
                    Path::root().key(&j.name),
                    format!(
                        "joint `{}` on the chain mimics `{m}`: coupled joints are not supported; \
                         end the chain before it (choose another tip)",
                        j.name
                    ),
                ));
            }
            if links.is_empty() {
                base_elems = Elem::merge_translations(std::mem::take(&mut fixed));
            }
            let mut before = std::mem::take(&mut fixed);
            before.extend(origin);
            let (pre, axis, sign, post) = b.axis(k, j);
            before.extend(pre);
            let before = Elem::merge_translations(before);
            links.push(Link {
                name: j.name.clone(),
                before,
                motion: Motion {
                    kind,
                    axis,
                    sign,
                    offset: Value::zero(),
                },
                after: post,
                axis_at: AxisAt::Motion,
                limits: j.limits,
            });
        }
        if links.is_empty() {
            return Err(self.error(
                self.line,
                Path::root().key("tip"),
                format!("no movable joint between `{base}` and `{tip}`"),
            ));
        }
        let snaps = bounds(b.pending, &joints);
        Ok(Chain {
            name: self.name.clone(),
            params,
            base: base_elems,
            links,
            tool: Elem::merge_translations(fixed),
            task: None,
            scalar: Scalar::F64,
            description: format!("URDF `{}`, `{base}` → `{tip}`", self.label),
            summary: summary(&joints, sel.snap, &named_rows),
            snaps,
        })
    }

    /// The named lengths (`(joint on the path, coordinate) → name`, base to tip) as a
    /// table: name, the file's value, and where it is written.
    fn named_summary(
        &self,
        names: &BTreeMap<(usize, usize), String>,
        joints: &[&Joint],
    ) -> Vec<String> {
        let mut rows = Vec::new();
        for (&(k, i), name) in names {
            let j = joints[k];
            rows.push(format!(
                "| {name} | {} | `{}.origin.{}`, {}:{} |",
                j.xyz[i].text, j.name, XYZ[i], self.label, j.origin_line
            ));
        }
        if rows.is_empty() {
            return rows;
        }
        let mut s = vec![
            String::new(),
            "Named lengths (fields of the generated type; defaults as the file writes them):"
                .into(),
            String::new(),
            "| name | value | written at |".into(),
            "|---|---|---|".into(),
        ];
        s.extend(rows);
        s
    }

    fn error(&self, line: usize, path: Path, message: String) -> LoadError {
        LoadError::at(&self.label, line, path, message)
    }

    /// `(joint index, coordinate) → name` of the named lengths, and the parameters.
    #[allow(clippy::type_complexity)]
    fn named_lengths(
        &self,
        wanted: &[(String, String)],
        joints: &[&Joint],
    ) -> Result<(BTreeMap<(usize, usize), String>, Vec<Param>), LoadError> {
        let mut names = BTreeMap::new();
        let mut params = Vec::new();
        let mut errors = Vec::new();
        for (name, entry) in wanted {
            let path = Path::root().key("params").key(name);
            let mut fail = |msg: String| errors.push(self.error(self.line, path.clone(), msg));
            if let Some(problem) = param_name_problem(name) {
                fail(problem);
                continue;
            }
            if params.iter().any(|p: &Param| &p.name == name) {
                fail(format!("duplicate parameter `{name}`"));
                continue;
            }
            let parts: Vec<&str> = entry.rsplitn(3, '.').collect();
            let (joint, coord) = match parts.as_slice() {
                [c, "origin", j] => (*j, XYZ.iter().position(|x| x == c)),
                _ => (entry.as_str(), None),
            };
            let Some(coord) = coord else {
                fail(format!(
                    "`{entry}` is not a length of the file: write `JOINT.origin.x`, `.y` or `.z`"
                ));
                continue;
            };
            let Some(k) = joints.iter().position(|j| j.name == joint) else {
                fail(format!(
                    "no joint `{joint}` on the chain (parameter `{name}` = `{entry}`)"
                ));
                continue;
            };
            if let Some(other) = names.insert((k, coord), name.clone()) {
                fail(format!("`{entry}` is named twice: `{other}` and `{name}`"));
                continue;
            }
            params.push(Param {
                name: name.clone(),
                value: Value::rational(joints[k].xyz[coord].value.clone()),
            });
        }
        match errors.into_iter().reduce(|mut a, b| {
            a.errors.extend(b.errors);
            a
        }) {
            Some(e) => Err(e),
            None => Ok((names, params)),
        }
    }
}

/// Snapping state while the chain is built.
struct Builder {
    tol: f64,
    names: BTreeMap<(usize, usize), String>,
    pending: Vec<Pending>,
}

impl Builder {
    fn record(
        &mut self,
        joint: usize,
        kind: SnapKind,
        entry: String,
        written: String,
        used: String,
        delta: f64,
    ) {
        self.pending.push(Pending {
            snap: Snap {
                entry,
                written,
                used,
                delta,
                position_bound: 0.0,
                orientation_bound: 0.0,
            },
            joint,
            kind,
        });
    }

    /// `Trans(xyz) · Rz(yaw) · Ry(pitch) · Rx(roll)` of joint `k`, zero entries left out.
    fn origin(&mut self, k: usize, j: &Joint) -> Vec<Elem> {
        let mut out = Vec::new();
        for (i, n) in j.xyz.iter().enumerate() {
            let v = match self.names.get(&(k, i)) {
                Some(name) => Value::param(name),
                None => self.length(k, &format!("{}.origin.{}", j.name, XYZ[i]), n),
            };
            if !v.is_zero() {
                out.push(Elem::Trans([Axis::X, Axis::Y, Axis::Z][i], v));
            }
        }
        for (i, axis) in [(2, Axis::Z), (1, Axis::Y), (0, Axis::X)] {
            let entry = format!("{}.origin.{}", j.name, RPY[i]);
            let v = self.angle(k, &entry, &j.rpy[i]);
            if !v.is_zero() {
                out.push(Elem::Rot(axis, v));
            }
        }
        out
    }

    fn length(&mut self, k: usize, entry: &str, n: &Number) -> Value {
        let x = n.to_f64();
        if !n.value.is_zero() && x.abs() <= self.tol {
            self.record(
                k,
                SnapKind::Length,
                entry.into(),
                n.text.clone(),
                "0".into(),
                x.abs(),
            );
            return Value::zero();
        }
        Value::rational(n.value.clone())
    }

    fn angle(&mut self, k: usize, entry: &str, n: &Number) -> Value {
        if n.value.is_zero() {
            return Value::zero();
        }
        match snap_to_twelfths(n.to_f64(), self.tol) {
            Some((t, _)) => {
                let delta = distance_to_pi_multiple(&n.value, &t);
                let v = Value::pi_times(t);
                self.record(
                    k,
                    SnapKind::Rotation,
                    entry.into(),
                    n.text.clone(),
                    v.to_string(),
                    delta,
                );
                v
            }
            None => Value::rational(n.value.clone()),
        }
    }

    /// The joint's axis: rotations before the motion, the motion's axis and sign, and
    /// the rotations after it.
    fn axis(&mut self, k: usize, j: &Joint) -> (Vec<Elem>, Axis, i8, Vec<Elem>) {
        let [x, y, z] = j.axis.clone().map(|n| n.value);
        let sign = |r: &Rat| if r.is_negative() { -1 } else { 1 };
        match (x.is_zero(), y.is_zero(), z.is_zero()) {
            (false, true, true) => return (vec![], Axis::X, sign(&x), vec![]),
            (true, false, true) => return (vec![], Axis::Y, sign(&y), vec![]),
            (true, true, false) => return (vec![], Axis::Z, sign(&z), vec![]),
            _ => {}
        }
        let written: Vec<&str> = j.axis.iter().map(|n| n.text.as_str()).collect();
        let written = written.join(" ");
        let u = unit(&j.axis.clone().map(|n| n.to_f64()));
        let entry = format!("{}.axis", j.name);
        // Within the tolerance of a coordinate axis: that axis.
        let big = (0..3)
            .max_by(|&a, &b| u[a].abs().total_cmp(&u[b].abs()))
            .unwrap_or(2);
        let off: f64 = (0..3).filter(|&i| i != big).map(|i| u[i] * u[i]).sum();
        let delta = off.sqrt().atan2(u[big].abs());
        if delta <= self.tol {
            let s = if u[big] < 0.0 { -1 } else { 1 };
            let mut used = ["0"; 3];
            used[big] = if s < 0 { "-1" } else { "1" };
            self.record(k, SnapKind::Axis, entry, written, used.join(" "), delta);
            return (vec![], [Axis::X, Axis::Y, Axis::Z][big], s, vec![]);
        }
        self.oblique(k, entry, written, (&x, &y, &z), u)
    }

    /// An axis off the coordinate axes: `Rz(φ) Ry(θ)` takes z onto it.
    fn oblique(
        &mut self,
        k: usize,
        entry: String,
        written: String,
        (x, y, z): (&Rat, &Rat, &Rat),
        u: [f64; 3],
    ) -> (Vec<Elem>, Axis, i8, Vec<Elem>) {
        let rho2 = x * x + y * y;
        let phi_f = u[1].atan2(u[0]);
        let theta_f = (u[0] * u[0] + u[1] * u[1]).sqrt().atan2(u[2]);
        let mut inexact = false;
        let mut rounded = false;
        let mut pick = |exact: Option<Rat>, f: f64| match exact {
            Some(t) => Value::pi_times(t),
            None => match snap_to_twelfths(f, self.tol) {
                Some((t, _)) => {
                    inexact = true;
                    Value::pi_times(t)
                }
                None => {
                    rounded = true;
                    Value::from_f64(f).unwrap_or_default()
                }
            },
        };
        let phi = pick(exact_phi(x, y), phi_f);
        let theta = pick(exact_theta(&rho2, z), theta_f);
        let (p, t) = (phi.eval(&|_| f64::NAN), theta.eval(&|_| f64::NAN));
        let used_u = [t.sin() * p.cos(), t.sin() * p.sin(), t.cos()];
        let dot: f64 = (0..3).map(|i| u[i] * used_u[i]).sum();
        let cross = [
            u[1] * used_u[2] - u[2] * used_u[1],
            u[2] * used_u[0] - u[0] * used_u[2],
            u[0] * used_u[1] - u[1] * used_u[0],
        ];
        let delta = cross.iter().map(|c| c * c).sum::<f64>().sqrt().atan2(dot);
        let used = format!("Rz({phi}) Ry({theta}) · z");
        if rounded {
            let used = format!("{used}, angles rounded to the nearest double");
            self.record(k, SnapKind::Axis, entry, written, used, delta);
        } else if inexact {
            self.record(k, SnapKind::Axis, entry, written, used, delta);
        }
        let neg = |v: &Value| v.scale(&-Rat::from_integer(1.into()));
        let mut pre = Vec::new();
        let mut post = Vec::new();
        if !phi.is_zero() {
            pre.push(Elem::Rot(Axis::Z, phi.clone()));
        }
        if !theta.is_zero() {
            pre.push(Elem::Rot(Axis::Y, theta.clone()));
            post.push(Elem::Rot(Axis::Y, neg(&theta)));
        }
        if !phi.is_zero() {
            post.push(Elem::Rot(Axis::Z, neg(&phi)));
        }
        (pre, Axis::Z, 1, post)
    }
}

/// `(t, |x − tπ|)` for the multiple `t` of 1/12 with `tπ` within `tol` of `x`.
fn snap_to_twelfths(x: f64, tol: f64) -> Option<(Rat, f64)> {
    if tol <= 0.0 {
        return None;
    }
    let k = (x / (PI / 12.0)).round();
    let delta = (x - k * PI / 12.0).abs();
    (delta <= tol && k.abs() < 1e6).then(|| (Rat::new((k as i64).into(), 12.into()), delta))
}

/// `|x − t·π|` from the exact decimal `x` (not its double: `3.141592653589793` is
/// 1.2e-16 from π although it is the double nearest π).
fn distance_to_pi_multiple(x: &Rat, t: &Rat) -> f64 {
    let pi = parse_decimal("3.14159265358979323846264338327950288419716939937510582097494")
        .unwrap_or_default();
    rat_to_f64(&(x - t * pi).abs())
}

fn r(n: i64, d: i64) -> Rat {
    Rat::new(n.into(), d.into())
}

/// `atan2(y, x) / π` when it is a multiple of 1/12, decided exactly: tan φ = y/x is
/// rational, and the multiples of π/12 with a rational tangent are those of π/4.
fn exact_phi(x: &Rat, y: &Rat) -> Option<Rat> {
    let half = |s: &Rat| if s.is_negative() { r(-1, 2) } else { r(1, 2) };
    if y.is_zero() {
        return Some(if x.is_negative() { r(1, 1) } else { r(0, 1) });
    }
    if x.is_zero() {
        return Some(half(y));
    }
    if x.abs() != y.abs() {
        return None;
    }
    let t = if x.is_negative() { r(3, 4) } else { r(1, 4) };
    Some(if y.is_negative() { -t } else { t })
}

/// `atan2(√ρ², z) / π` when it is a multiple of 1/12, decided exactly: tan² θ = ρ²/z² is
/// rational, which among multiples of π/12 leaves 0, 1/3, 1 and 3.
fn exact_theta(rho2: &Rat, z: &Rat) -> Option<Rat> {
    if z.is_zero() {
        return Some(r(1, 2));
    }
    let t2 = rho2 / (z * z);
    let first = [
        (r(0, 1), r(0, 1)),
        (r(1, 3), r(1, 6)),
        (r(1, 1), r(1, 4)),
        (r(3, 1), r(1, 3)),
    ]
    .into_iter()
    .find(|(t, _)| *t == t2)
    .map(|(_, a)| a)?;
    Some(if z.is_negative() {
        r(1, 1) - first
    } else {
        first
    })
}

/// The bounds of each snap: a rotation before the rest of the chain moves the tool by
/// at most δ times the reach after it (sum of translation lengths, prismatic travel
/// included; ∞ past a prismatic joint without limits).
fn bounds(pending: Vec<Pending>, joints: &[&Joint]) -> Vec<Snap> {
    let travel = |j: &Joint| match (j.kind, j.limits) {
        (JointType::Prismatic, Some([lo, hi])) => lo.abs().max(hi.abs()),
        (JointType::Prismatic, None) => f64::INFINITY,
        _ => 0.0,
    };
    let length = |j: &Joint| {
        let v = j.xyz.clone().map(|n| n.to_f64());
        (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
    };
    // reach_after[k]: from the end of joint k's motion to the tool.
    let mut reach_after = vec![0.0; joints.len() + 1];
    for k in (0..joints.len()).rev() {
        let next = joints.get(k + 1).map_or(0.0, |j| length(j) + travel(j));
        reach_after[k] = reach_after[k + 1] + next;
    }
    pending
        .into_iter()
        .map(|p| {
            let mut s = p.snap;
            let j = joints[p.joint];
            let (pos, rot) = match p.kind {
                SnapKind::Length => (s.delta, 0.0),
                SnapKind::Rotation => (s.delta * (travel(j) + reach_after[p.joint]), s.delta),
                SnapKind::Axis => (
                    2.0 * s.delta * reach_after[p.joint] + s.delta * travel(j),
                    if j.kind == JointType::Prismatic {
                        0.0
                    } else {
                        2.0 * s.delta
                    },
                ),
            };
            s.position_bound = if pos.is_nan() { f64::INFINITY } else { pos };
            s.orientation_bound = rot;
            s
        })
        .collect()
}

/// The chain's joints as written, for the rustdoc.
fn summary(joints: &[&Joint], snap: f64, named: &[String]) -> Vec<String> {
    let mut s = vec![
        format!(
            "Joints base to tip (`q` follows the movable ones); numbers within {snap:e} of an exact value \
             are snapped to it (listed below)."
        ),
        String::new(),
        "| q | joint | type | parent → child | origin xyz | origin rpy | axis |".into(),
        "|---|---|---|---|---|---|---|".into(),
    ];
    let mut q = 0;
    for j in joints {
        let text = |v: &[Number; 3]| {
            v.iter()
                .map(|n| n.text.as_str())
                .collect::<Vec<_>>()
                .join(" ")
        };
        let (qi, axis) = if j.kind == JointType::Fixed {
            (String::new(), String::new())
        } else {
            q += 1;
            (format!("q{q}"), text(&j.axis))
        };
        s.push(format!(
            "| {qi} | {} | {} | {} → {} | {} | {} | {axis} |",
            j.name,
            j.kind.name(),
            j.parent,
            j.child,
            text(&j.xyz),
            text(&j.rpy)
        ));
    }
    s.extend(named.iter().cloned());
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::value::fmt_rat;

    #[test]
    #[allow(clippy::approx_constant)] // 1.5708 is what URDF files write for π/2
    fn exact_directions() {
        let (one, zero) = (r(1, 1), r(0, 1));
        assert_eq!(exact_phi(&one, &one), Some(r(1, 4)));
        assert_eq!(exact_phi(&-one.clone(), &one), Some(r(3, 4)));
        assert_eq!(exact_phi(&zero, &-one.clone()), Some(r(-1, 2)));
        assert_eq!(exact_phi(&one, &r(2, 1)), None);
        assert_eq!(exact_theta(&r(3, 1), &one), Some(r(1, 3)));
        assert_eq!(exact_theta(&r(1, 3), &-one.clone()), Some(r(5, 6)));
        assert_eq!(exact_theta(&r(2, 1), &one), None);
        assert_eq!(fmt_rat(&snap_to_twelfths(1.5708, 1e-4).unwrap().0), "0.5");
        assert!(snap_to_twelfths(1.5708, 0.0).is_none());
        assert!(snap_to_twelfths(1.6, 1e-4).is_none());
    }

    /// Fixed joints in a row (a Kinova j2n6s300's wrist) read as one translation.
    #[test]
    fn fixed_joints_in_a_row_are_one_translation() {
        let src = r#"<robot name="r">
  <link name="a"/><link name="b"/><link name="c"/><link name="d"/><link name="e"/><link name="f"/>
  <joint name="j1" type="revolute"><parent link="a"/><child link="b"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="f1" type="fixed"><parent link="b"/><child link="c"/><origin xyz="0.042825 0 0"/></joint>
  <joint name="f2" type="fixed"><parent link="c"/><child link="d"/><origin xyz="0.025875 0 0.5"/></joint>
  <joint name="f3" type="fixed"><parent link="d"/><child link="e"/><origin xyz="0.0385 0 -0.5"/></joint>
  <joint name="j2" type="revolute"><parent link="e"/><child link="f"/>
    <origin xyz="0 0 0" rpy="0 1.5707963267948966 0"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"#;
        let chain = crate::front::urdf::Urdf::parse(src, "r.urdf")
            .unwrap()
            .chain(&Selection::default())
            .unwrap();
        let text = chain.to_string();
        assert!(
            text.contains("link 2: Tx(0.1072) Ry(pi/2) Rz(q2)"),
            "{text}"
        );
    }

    /// A huge component must not overflow the norm: `1e300 0 1` is x, not z.
    #[test]
    fn huge_axes_keep_their_direction() {
        assert_eq!(unit(&[1e300, 0.0, 1.0]), [1.0, 0.0, 1e-300]);
        assert_eq!(unit(&[0.0, -3e200, 4e200]), [0.0, -0.6, 0.8]);
        assert_eq!(unit(&[0.0, 0.0, 2.0]), [0.0, 0.0, 1.0]);
    }
}
