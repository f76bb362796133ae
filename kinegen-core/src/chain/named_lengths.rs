//! Names for every length of a URDF chain ([`Selection::symbolic`]), so its formulas read
//! like a data sheet: `det J = a3·s5·(…)`, not `0.00000625·s5·(…)`.
//!
//! Each non-zero coordinate of a joint's `<origin xyz>` (after snapping) is named from
//! the movable joint it leads to and its direction there:
//!
//! - `d{m}`: along joint m's own axis, in joint m's origin; joints are numbered like `q`,
//!   from 1.
//! - `d{m−1}`: along joint m−1's axis (where no rotation stands between: the length
//!   slides along that axis), `d{m−1}_2` if joint m−1's origin took `d{m−1}`.
//! - `a{m−1}`, then `b{m−1}`: across both (the first and the second such coordinate, in
//!   x, y, z order): the link from axis m−1 to axis m.
//!
//! That is Craig's (modified DH) numbering — `a_{i−1}` from axis i−1 to axis i, `d_i`
//! along axis i — so where the file's frames follow the joints, the names are the data
//! sheet's: the UR5's `d1`, `a2 = −0.425`, `a3`, `d4`, `d5`, `d6`.
//! - `{joint}_{x|y|z}` (the joint's name made an identifier): a fixed joint's
//!   coordinates, and any coordinate at an angle to the axis (neither along nor across).
//!
//! The axis is compared in the frame the coordinates are written in (the parent link's):
//! the joint's axis turned by its `<origin rpy>`, exactly where the rotations are
//! multiples of π/2, else numerically to 1e-9. A name the user gave (`params`) is kept and
//! that coordinate is not named again; a generated name already taken gets `_2`, `_3`….
//! Values are the file's decimals exactly, so the numbers the generated code starts from
//! are those of the numeric form.
//!
//! [`Selection::symbolic`]: crate::chain::urdf::Selection::symbolic

use std::collections::BTreeSet;

use num_traits::Zero;

use crate::chain::unit;
use crate::front::urdf::{Joint, JointType};
use crate::model::validate::param_name_problem;

/// One generated name: `(name, "joint.origin.x")`, and the line of the joint's origin.
#[derive(Clone, Debug, PartialEq)]
pub struct NamedLength {
    /// The parameter's name (`d1`).
    pub name: String,
    /// The coordinate it names (`joint_s.origin.z`).
    pub entry: String,
    /// Line of the `<origin>` it is read from.
    pub line: usize,
}

/// The names of every non-zero length of `joints` (the chain's path) not named in
/// `taken` (the user's `(name, entry)` pairs); `snap` is the tolerance under which a
/// length is zero.
pub fn name_lengths(joints: &[&Joint], taken: &[(String, String)], snap: f64) -> Vec<NamedLength> {
    let mut names: BTreeSet<String> = taken.iter().map(|(n, _)| n.clone()).collect();
    let entries: BTreeSet<&str> = taken.iter().map(|(_, e)| e.as_str()).collect();
    let mut out = Vec::new();
    let mut movable = 0;
    // The last movable joint's axis in the frame the next origin is written in, while
    // no rotation stands between.
    let mut previous: Option<[f64; 3]> = None;
    for j in joints {
        let is_fixed = j.kind == JointType::Fixed;
        if !is_fixed {
            movable += 1;
        }
        let axis = (!is_fixed).then(|| axis_in_parent(j));
        let along =
            |a: Option<[f64; 3]>, i: usize| a.is_some_and(|a| (a[i].abs() - 1.0).abs() < 1e-9);
        let mut across = 0;
        for (i, coord) in ["x", "y", "z"].into_iter().enumerate() {
            let n = &j.xyz[i];
            let entry = format!("{}.origin.{coord}", j.name);
            if n.value.is_zero() || n.to_f64().abs() <= snap || entries.contains(entry.as_str()) {
                continue;
            }
            let stem = match axis.map(|a| a[i].abs()) {
                Some(_) if along(axis, i) => format!("d{movable}"),
                Some(_) if along(previous, i) => format!("d{}", movable - 1),
                Some(c) if c < 1e-9 => {
                    across += 1;
                    format!("{}{}", if across == 1 { "a" } else { "b" }, movable - 1)
                }
                _ => format!("{}_{coord}", identifier(&j.name)),
            };
            let name = unique(&stem, &mut names);
            out.push(NamedLength {
                name,
                entry,
                line: j.origin_line,
            });
        }
        let turned = j.rpy.iter().any(|n| !n.value.is_zero());
        previous = match (turned, is_fixed) {
            (true, _) => None,
            (false, true) => previous,
            // The joint's axis as written is in its own frame, where the next origin is.
            (false, false) => Some(axis_as_written(j)),
        };
    }
    out
}

/// The joint's axis as written, normalised (in the joint's own frame).
fn axis_as_written(j: &Joint) -> [f64; 3] {
    unit(&j.axis.clone().map(|n| n.to_f64()))
}

/// The joint's axis (unit) in its parent's frame: turned by `Rz(yaw) Ry(pitch) Rx(roll)`.
fn axis_in_parent(j: &Joint) -> [f64; 3] {
    let mut v = axis_as_written(j);
    let [roll, pitch, yaw] = [j.rpy[0].to_f64(), j.rpy[1].to_f64(), j.rpy[2].to_f64()];
    // Rx, then Ry, then Rz (applied to the vector in that order).
    let turn = |v: [f64; 3], axis: usize, t: f64| {
        let (s, c) = t.sin_cos();
        let (p, q) = ((axis + 1) % 3, (axis + 2) % 3);
        let mut w = v;
        w[p] = c * v[p] - s * v[q];
        w[q] = s * v[p] + c * v[q];
        w
    };
    v = turn(v, 0, roll);
    v = turn(v, 1, pitch);
    turn(v, 2, yaw)
}

/// A joint's name as an identifier: other characters become `_`, a leading digit gets
/// `j` in front, lower case.
fn identifier(name: &str) -> String {
    let mut s: String = name
        .chars()
        .map(|c| match c.is_ascii_alphanumeric() {
            true => c.to_ascii_lowercase(),
            false => '_',
        })
        .collect();
    if !s.starts_with(|c: char| c.is_ascii_alphabetic()) {
        s.insert(0, 'j');
    }
    s
}

/// `stem`, or `stem_2`, `stem_3`… — the first that is free and a valid parameter name.
fn unique(stem: &str, names: &mut BTreeSet<String>) -> String {
    let mut k = 1;
    loop {
        let name = match k {
            1 => stem.to_string(),
            _ => format!("{stem}_{k}"),
        };
        if param_name_problem(&name).is_none() && names.insert(name.clone()) {
            return name;
        }
        k += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identifiers_and_unique_names() {
        assert_eq!(identifier("link_6-tool0"), "link_6_tool0");
        assert_eq!(identifier("6dof"), "j6dof");
        let mut taken: BTreeSet<String> = ["d1".to_string()].into();
        assert_eq!(unique("d1", &mut taken), "d1_2");
        assert_eq!(unique("d1", &mut taken), "d1_3");
        // `q2` names a joint variable: never a length.
        assert_eq!(unique("q2", &mut taken), "q2_2");
    }
}
