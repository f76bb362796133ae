//! A DH table as a [`Chain`]: each row is four elementary transforms, in the order of
//! its convention, with the joint variable in θ (revolute) or d (prismatic).
//!
//! - standard (distal): `A_i = Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i)`; the joint moves about
//!   `z_{i-1}`, read before the row (the textbook's `z_{i-1} × (p − o_{i-1})`).
//! - modified (proximal, Craig): `A_i = Rx(α_{i-1}) Tx(a_{i-1}) Rz(θ_i) Tz(d_i)`; the
//!   joint moves about `z_i`, read in the link frame.
//!
//! A flipped joint (`flip = true`) runs against z: its motion is `Rz(−q_i + θ_i)` or
//! `Tz(−q_i + d_i)` (`Motion::sign = -1`).
//!
//! Base and tool are `Trans(xyz) · Rz(yaw) · Ry(pitch) · Rx(roll)`, zero entries left out.

use crate::chain::{Axis, AxisAt, Chain, Elem, Link, Motion};
use crate::model::dh::{Convention, Frame, Joint, Robot};
use crate::model::robot::JointKind;

impl Robot {
    /// The chain of this table (see the module docs).
    pub fn chain(&self) -> Chain {
        Chain {
            name: self.name.clone(),
            params: self.params.clone(),
            base: self.base.as_ref().map(frame).unwrap_or_default(),
            links: self
                .joints
                .iter()
                .enumerate()
                .map(|(i, j)| link(self.convention, i, j))
                .collect(),
            tool: self.tool.as_ref().map(frame).unwrap_or_default(),
            task: self.task.clone(),
            scalar: self.scalar,
            description: match self.convention {
                Convention::Standard => "standard DH",
                Convention::Modified => "modified (Craig) DH",
            }
            .into(),
            summary: summary(self),
            snaps: Vec::new(),
        }
    }
}

/// One DH row.
fn link(convention: Convention, i: usize, j: &Joint) -> Link {
    // The joint variable adds to θ or d (a flipped one subtracts); the other of the two
    // is a constant.
    let sign = if j.flip { -1 } else { 1 };
    let (motion, fixed) = match j.kind {
        JointKind::Revolute => (
            Motion {
                kind: j.kind,
                axis: Axis::Z,
                sign,
                offset: j.theta.clone(),
            },
            Elem::Trans(Axis::Z, j.d.clone()),
        ),
        JointKind::Prismatic => (
            Motion {
                kind: j.kind,
                axis: Axis::Z,
                sign,
                offset: j.d.clone(),
            },
            Elem::Rot(Axis::Z, j.theta.clone()),
        ),
    };
    let tx = Elem::Trans(Axis::X, j.a.clone());
    let rx = Elem::Rot(Axis::X, j.alpha.clone());
    // Rz(θ) and Tz(d) commute: the constant one goes on the side that keeps the row's
    // textbook order Rz Tz (revolute: motion then Tz; prismatic: Rz then motion).
    let (z_before, z_after) = match j.kind {
        JointKind::Revolute => (vec![], vec![fixed]),
        JointKind::Prismatic => (vec![fixed], vec![]),
    };
    let (before, after, axis_at) = match convention {
        Convention::Standard => {
            let mut after = z_after;
            after.extend([tx, rx]);
            (z_before, after, AxisAt::Motion)
        }
        Convention::Modified => {
            let mut before = vec![rx, tx];
            before.extend(z_before);
            (before, z_after, AxisAt::LinkFrame)
        }
    };
    Link {
        name: format!("q{}", i + 1),
        before,
        motion,
        after,
        axis_at,
        limits: j.limits,
    }
}

/// `Trans(xyz) · Rz(yaw) · Ry(pitch) · Rx(roll)`, zero entries left out.
pub fn frame(f: &Frame) -> Vec<Elem> {
    let mut out = Vec::new();
    for (axis, v) in [Axis::X, Axis::Y, Axis::Z].into_iter().zip(&f.xyz) {
        if !v.is_zero() {
            out.push(Elem::Trans(axis, v.clone()));
        }
    }
    for (axis, v) in [
        (Axis::Z, &f.rpy[2]),
        (Axis::Y, &f.rpy[1]),
        (Axis::X, &f.rpy[0]),
    ] {
        if !v.is_zero() {
            out.push(Elem::Rot(axis, v.clone()));
        }
    }
    out
}

/// The DH table as markdown, for the generated type's rustdoc (π written as π).
fn summary(robot: &Robot) -> Vec<String> {
    let mut s = vec![
        "| joint | type | a | α | d | θ |".into(),
        "|---|---|---|---|---|---|".into(),
    ];
    for (i, j) in robot.joints.iter().enumerate() {
        let q = if j.flip {
            format!("-q{}", i + 1)
        } else {
            format!("q{}", i + 1)
        };
        let (kind, d, th) = match j.kind {
            JointKind::Revolute => (
                "revolute",
                j.d.to_string(),
                with_var(&q, &j.theta.to_string()),
            ),
            JointKind::Prismatic => (
                "prismatic",
                with_var(&q, &j.d.to_string()),
                j.theta.to_string(),
            ),
        };
        s.push(format!(
            "| {} | {kind} | {} | {} | {} | {} |",
            i + 1,
            greek_pi(&j.a.to_string()),
            greek_pi(&j.alpha.to_string()),
            greek_pi(&d),
            greek_pi(&th)
        ));
    }
    s
}

/// `pi/2` → `π/2`, `3*pi/4` → `3π/4`: the word `pi` of a printed [`crate::model::value::Value`],
/// not a parameter that merely contains it (`pivot`).
fn greek_pi(text: &str) -> String {
    let word = |c: char| c.is_alphanumeric() || c == '_';
    let mut out = String::new();
    let mut rest = text;
    while let Some(at) = rest.find("pi") {
        let (before, after) = (&rest[..at], &rest[at + 2..]);
        let alone = !before.ends_with(word) && !after.starts_with(word);
        out.push_str(before);
        if alone {
            if out.ends_with('*') && out[..out.len() - 1].ends_with(|c: char| c.is_ascii_digit()) {
                out.pop();
            }
            out.push('π');
        } else {
            out.push_str("pi");
        }
        rest = after;
    }
    out.push_str(rest);
    out
}

/// `q2`, `q2 + pi/2`, `q2 - 0.1`.
fn with_var(q: &str, rest: &str) -> String {
    if rest == "0" {
        q.to_string()
    } else if let Some(r) = rest.strip_prefix('-') {
        format!("{q} - {r}")
    } else {
        format!("{q} + {rest}")
    }
}

#[cfg(test)]
mod tests {
    use super::greek_pi;

    #[test]
    fn pi_is_greek_only_as_a_word() {
        assert_eq!(greek_pi("pi/2"), "π/2");
        assert_eq!(greek_pi("-pi/2"), "-π/2");
        assert_eq!(greek_pi("3*pi/4"), "3π/4");
        assert_eq!(greek_pi("q2 + pi"), "q2 + π");
        assert_eq!(greek_pi("a*pi + 0.1"), "a*π + 0.1");
        assert_eq!(greek_pi("pivot + api + pi_2"), "pivot + api + pi_2");
    }
}
