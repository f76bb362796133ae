//! What a singular factor means on the arm, found on the arm itself rather than guessed
//! from which joints the factor involves.
//!
//! A factor's zero set is a set of configurations; what happens there is geometry. From
//! two generic configurations (deterministic, within the limits) one joint of the factor
//! is moved until the factor changes sign and bisected onto its zero. There the joint
//! axes, the points where axes meet and the tool point are compared with the generic
//! configuration: the relations that hold on the zero set and not off it are the
//! singularity's meaning — axes that come into line or become parallel, parallel axes
//! that fall into one plane, a point where axes meet (or the tool point) that reaches an
//! axis or the plane of two axes. Only relations found from both starts are kept (one
//! start's coincidences are not the factor's). Then the Jacobian's null motion names the
//! joints that can move together without moving the tool.
//!
//! Everything here is numbers on the model's nodes (register programs), after the
//! derivation: nothing it finds changes a formula.

use super::closed_form::DetFactor;
use crate::chain::Chain;
use crate::kinematics::frames::SymbolicChain;
use crate::kinematics::program::Program;
use crate::model::robot::JointKind;
use crate::words::and_list;
use core::f64::consts::PI;
use nalgebra::{DMatrix, Vector3};

type V3 = Vector3<f64>;

/// Samples along a joint when looking for a sign change of the factor.
const SAMPLES: usize = 720;

/// A relation holds on the zero set when it does to this (radians, or times the arm's
/// size), and is new when the generic configuration misses it by more than [`GENERIC`].
const HOLDS: f64 = 1e-7;
const GENERIC: f64 = 1e-4;

/// A joint takes part in the null motion when its rate is at least this fraction of the
/// largest.
const TAKES_PART: f64 = 0.05;

/// The meaning of `factor = 0` for `chain` (whose model is `sym`; `rows`: the rows of
/// the square Jacobian, indices into `[vx vy vz ωx ωy ωz]`): the geometric relations
/// that hold where it vanishes, and the joints whose motion then leaves the tool still.
pub fn meaning(chain: &Chain, sym: &SymbolicChain, rows: &[usize], factor: &DetFactor) -> String {
    if factor.joints.is_empty() {
        return "a constant of the robot's lengths, not zero for this robot (else det J would \
                vanish at every q); zero only for a robot with that length 0"
            .into();
    }
    let arm = Arm::new(chain, sym, factor);
    let found: Vec<(Vec<String>, Vec<usize>)> = (0..2)
        .filter_map(|seed| {
            let q0 = generic(chain, seed);
            let q = arm.zero_of_factor(&q0, &factor.joints)?;
            let at = arm.at(&q);
            let off = arm.at(&q0);
            Some((relations(&at, &off), arm.null_motion(&q, rows)))
        })
        .collect();
    let Some((first, _)) = found.first() else {
        let joints: Vec<String> = factor.joints.iter().map(|j| format!("q{j}")).collect();
        return format!(
            "no zero found moving one of {} from two generic configurations",
            joints.join(", ")
        );
    };
    let events: Vec<&String> = first
        .iter()
        .filter(|e| found.iter().all(|(r, _)| r.contains(e)))
        .collect();
    // The joints of the null motion at either zero (one can leave a joint out where its
    // share happens to be small).
    let mut joints: Vec<usize> = found.iter().flat_map(|(_, j)| j.iter().copied()).collect();
    joints.sort_unstable();
    joints.dedup();
    // A task Jacobian's rows are some of the tool's coordinates.
    let tool = if rows.len() < 6 {
        "the tool in the task's coordinates"
    } else {
        "the tool"
    };
    let still = match joints.as_slice() {
        [] => String::new(),
        [j] => format!("joint {j} can then move without moving {tool}"),
        _ => format!(
            "joints {} can then move together without moving {tool}",
            joint_list(&joints)
        ),
    };
    let events: Vec<&str> = events.iter().map(|e| e.as_str()).collect();
    match (events.is_empty(), still.is_empty()) {
        (true, true) => "no relation of the axes and no null motion found there".into(),
        (false, true) => events.join("; "),
        (true, false) => still,
        (false, false) => format!("{}: {still}", events.join("; ")),
    }
}

/// `1, 2 and 3`.
fn joint_list(joints: &[usize]) -> String {
    let names: Vec<String> = joints.iter().map(|j| j.to_string()).collect();
    and_list(&names)
}

/// A configuration in no special position: each joint at its own irrational-looking
/// fraction of its range (shrunk by a tenth from each end), `seed` shifting them.
fn generic(chain: &Chain, seed: usize) -> Vec<f64> {
    chain
        .links
        .iter()
        .zip(chain.kinds())
        .enumerate()
        .map(|(i, (link, kind))| {
            let [lo, hi] = link.limits.unwrap_or(match kind {
                JointKind::Revolute => [-PI, PI],
                JointKind::Prismatic => [0.1, 0.5],
            });
            let (lo, hi) = if lo.is_finite() && hi.is_finite() && hi > lo {
                (lo, hi)
            } else {
                (-PI, PI)
            };
            let f = 0.5 + 0.4 * (2.1 * i as f64 + 1.7 * seed as f64 + 0.4).sin();
            lo + (hi - lo) * (0.1 + 0.8 * f)
        })
        .collect()
}

/// The arm's axes, points and tool at a configuration.
struct Frames {
    h: Vec<V3>,
    p: Vec<V3>,
    tool: V3,
    /// The arm's size, for distances.
    size: f64,
}

/// The register programs the search and the relations evaluate.
struct Arm {
    factor: Program,
    frames: Program,
    prismatic: Vec<bool>,
}

impl Arm {
    fn new(chain: &Chain, sym: &SymbolicChain, factor: &DetFactor) -> Arm {
        let mut ids = Vec::new();
        for (h, p) in &sym.axes {
            ids.extend(h);
            ids.extend(p);
        }
        ids.extend(sym.tool.p);
        Arm {
            factor: Program::new(sym, chain, &[factor.node]),
            frames: Program::new(sym, chain, &ids),
            prismatic: chain.kinds().map(|k| k == JointKind::Prismatic).collect(),
        }
    }

    fn factor(&self, q: &[f64]) -> f64 {
        let mut r = self.factor.registers();
        let mut out = [0.0];
        self.factor.eval(q, &mut r, &mut out);
        out[0]
    }

    fn at(&self, q: &[f64]) -> Frames {
        let mut r = self.frames.registers();
        let mut v = vec![0.0; self.frames.outputs()];
        self.frames.eval(q, &mut r, &mut v);
        let n = self.prismatic.len();
        let v3 = |k: usize| V3::new(v[k], v[k + 1], v[k + 2]);
        let p: Vec<V3> = (0..n).map(|i| v3(6 * i + 3)).collect();
        let tool = v3(6 * n);
        let size = 1.0
            + p.iter()
                .chain([&tool])
                .map(|x| x.amax())
                .fold(0.0, f64::max);
        Frames {
            h: (0..n).map(|i| v3(6 * i).normalize()).collect(),
            p,
            tool,
            size,
        }
    }

    /// A configuration where the factor vanishes: `q0` with one of `joints` (1-based)
    /// moved to the first sign change of the factor along it, bisected.
    fn zero_of_factor(&self, q0: &[f64], joints: &[usize]) -> Option<Vec<f64>> {
        for &j in joints {
            let k = j - 1;
            // Along a sliding joint, twice the arm's size either way (its limits need
            // not hold the zero: the meaning is the geometry's).
            let (lo, hi) = if self.prismatic[k] {
                let size = self.at(q0).size;
                (-2.0 * size, 2.0 * size)
            } else {
                (-PI, PI)
            };
            let mut q = q0.to_vec();
            let mut at = |x: f64| {
                q[k] = x;
                self.factor(&q)
            };
            let step = (hi - lo) / SAMPLES as f64;
            let (mut a, mut fa) = (lo, at(lo));
            for s in 1..=SAMPLES {
                let b = lo + step * s as f64;
                let fb = at(b);
                if !(fa.is_finite() && fb.is_finite()) {
                    (a, fa) = (b, fb);
                    continue;
                }
                if fa == 0.0 || fa.signum() != fb.signum() {
                    let (mut a, mut b, mut fa) = (a, b, fa);
                    for _ in 0..80 {
                        if fa == 0.0 {
                            break;
                        }
                        let m = 0.5 * (a + b);
                        let fm = at(m);
                        if fm.signum() == fa.signum() {
                            (a, fa) = (m, fm);
                        } else {
                            b = m;
                        }
                    }
                    let mut q = q0.to_vec();
                    q[k] = if fa == 0.0 { a } else { 0.5 * (a + b) };
                    return Some(q);
                }
                (a, fa) = (b, fb);
            }
        }
        None
    }

    /// The joints (1-based) of the Jacobian's null motion at `q`: the right singular
    /// vector of its smallest singular value, rows `rows`.
    fn null_motion(&self, q: &[f64], rows: &[usize]) -> Vec<usize> {
        let f = self.at(q);
        let n = f.h.len();
        let mut j = DMatrix::zeros(rows.len(), n);
        for i in 0..n {
            let (v, w) = if self.prismatic[i] {
                (f.h[i], V3::zeros())
            } else {
                (f.h[i].cross(&(f.tool - f.p[i])), f.h[i])
            };
            let col = [v.x, v.y, v.z, w.x, w.y, w.z];
            for (r, &row) in rows.iter().enumerate() {
                j[(r, i)] = col[row];
            }
        }
        if j.iter().any(|x| !x.is_finite()) {
            return Vec::new();
        }
        // The null vector of JᵀJ (N × N): its eigenvector of the smallest eigenvalue
        // (iterations bounded: no input makes this spin).
        let Some(e) = nalgebra::SymmetricEigen::try_new(j.transpose() * &j, f64::EPSILON, 1000)
        else {
            return Vec::new();
        };
        let Some((k, _)) = e
            .eigenvalues
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.total_cmp(b.1))
        else {
            return Vec::new();
        };
        let v = e.eigenvectors.column(k);
        let top = v.amax();
        (0..n)
            .filter(|&i| v[i].abs() >= TAKES_PART * top)
            .map(|i| i + 1)
            .collect()
    }
}

/// Whether lines `(p, h)` and `(q, g)` (unit directions) are parallel.
fn parallel(h: &V3, g: &V3) -> f64 {
    h.cross(g).norm()
}

/// The distance of point `x` from the line `(p, h)`.
fn off_line(x: &V3, p: &V3, h: &V3) -> f64 {
    (x - p).cross(h).norm()
}

/// The distance of point `x` from the plane through `p` with unit normal `n`.
fn off_plane(x: &V3, p: &V3, n: &V3) -> f64 {
    (x - p).dot(n).abs()
}

/// The points the relations look at: where consecutive axes meet (at both `a` and `b`:
/// the arm's own point, not a coincidence; a wrist's three axes give one point), and the
/// tool point where it is none of those — each a name and the axes defining it (none
/// for the tool point).
fn points(a: &Frames, b: &Frames) -> Vec<(String, Vec<usize>)> {
    let n = a.h.len();
    let same = |f: &Frames, x: &V3, y: &V3| (x - y).norm() <= HOLDS * f.size;
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for i in 0..n.saturating_sub(1) {
        let (Some(x), Some(y)) = (meeting(a, i, i + 1), meeting(b, i, i + 1)) else {
            continue;
        };
        match groups.last_mut() {
            Some(g)
                if g.last() == Some(&i)
                    && same(a, &point(a, g), &x)
                    && same(b, &point(b, g), &y) =>
            {
                g.push(i + 1)
            }
            _ => groups.push(vec![i, i + 1]),
        }
    }
    let mut out: Vec<(String, Vec<usize>)> = groups
        .into_iter()
        .map(|g| {
            (
                format!("the point where axes {} meet", joint_list(&plus_one(&g))),
                g,
            )
        })
        .collect();
    let tool_elsewhere = out
        .iter()
        .all(|(_, g)| !(same(a, &point(a, g), &a.tool) && same(b, &point(b, g), &b.tool)));
    if tool_elsewhere {
        out.push(("the tool point".into(), Vec::new()));
    }
    out
}

/// Where axes `i` and `j` meet at `f` (the point on axis `i` closest to axis `j`), if
/// they do.
fn meeting(f: &Frames, i: usize, j: usize) -> Option<V3> {
    let c = f.h[i].cross(&f.h[j]);
    let nc = c.norm();
    let d = f.p[j] - f.p[i];
    if nc <= GENERIC || d.dot(&c).abs() / nc > HOLDS * f.size {
        return None;
    }
    let s = d.cross(&f.h[j]).dot(&c) / (nc * nc);
    Some(f.p[i] + f.h[i] * s)
}

/// The point `of` (from [`points`]: where its first two axes meet, or the tool point)
/// on the frames `f`.
fn point(f: &Frames, of: &[usize]) -> V3 {
    match of {
        [i, j, ..] => meeting(f, *i, *j).unwrap_or(f.p[*i]),
        _ => f.tool,
    }
}

/// The relations that hold at `at` (on the factor's zero set) and not at `off` (the
/// generic configuration it was found from), most telling first.
fn relations(at: &Frames, off: &Frames) -> Vec<String> {
    let n = at.h.len();
    let tol = |f: &Frames| HOLDS * f.size;
    let mut lines = Vec::new();
    let mut parallels = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            let in_line = |f: &Frames| {
                parallel(&f.h[i], &f.h[j]) <= HOLDS && off_line(&f.p[j], &f.p[i], &f.h[i]) <= tol(f)
            };
            let par = |f: &Frames| parallel(&f.h[i], &f.h[j]) <= HOLDS;
            if in_line(at) && !in_line(off) {
                lines.push(format!("axes {} and {} are in line", i + 1, j + 1));
            } else if par(at) && parallel(&off.h[i], &off.h[j]) > GENERIC {
                parallels.push((i, j));
            }
        }
    }
    if !lines.is_empty() {
        // Axes in line: what else lines up follows from it.
        return lines;
    }
    let mut out = Vec::new();
    // Three or more parallel axes that fall into one plane.
    let mut in_plane: Vec<Vec<usize>> = Vec::new();
    for i in 0..n {
        let group: Vec<usize> = (0..n)
            .filter(|&j| parallel(&at.h[i], &at.h[j]) <= HOLDS)
            .collect();
        if group.len() < 3 || group[0] != i {
            continue;
        }
        let coplanar = |f: &Frames| {
            let (a, b) = (group[0], group[1]);
            let across = f.h[a].cross(&(f.p[b] - f.p[a]));
            if across.norm() <= tol(f) {
                return false;
            }
            let normal = across.normalize();
            group[2..]
                .iter()
                .all(|&c| off_plane(&f.p[c], &f.p[a], &normal) <= tol(f))
        };
        let parallel_off = group
            .iter()
            .all(|&j| parallel(&off.h[i], &off.h[j]) <= HOLDS);
        if coplanar(at) && !(parallel_off && coplanar(off)) {
            out.push(format!(
                "axes {} are parallel and in one plane",
                joint_list(&plus_one(&group))
            ));
            in_plane.push(group);
        }
    }
    // Parallel groups at the zero set that a new pair joined.
    if !parallels.is_empty() {
        let mut groups: Vec<Vec<usize>> = Vec::new();
        for i in 0..n {
            match groups
                .iter_mut()
                .find(|g| parallel(&at.h[g[0]], &at.h[i]) <= HOLDS)
            {
                Some(g) => g.push(i),
                None => groups.push(vec![i]),
            }
        }
        for g in groups {
            if !in_plane.contains(&g)
                && parallels
                    .iter()
                    .any(|(i, j)| g.contains(i) && g.contains(j))
            {
                out.push(format!("axes {} are parallel", joint_list(&plus_one(&g))));
            }
        }
    }
    if !out.is_empty() {
        return out;
    }
    // A point reaching an axis.
    let pts = points(at, off);
    for (name, of) in &pts {
        let (x, y) = (point(at, of), point(off, of));
        for k in (0..n).filter(|k| !of.contains(k)) {
            if off_line(&x, &at.p[k], &at.h[k]) <= tol(at)
                && off_line(&y, &off.p[k], &off.h[k]) > GENERIC * off.size
            {
                out.push(format!("{name} is on axis {}", k + 1));
            }
        }
    }
    if !out.is_empty() {
        return out;
    }
    // A point reaching the plane of two axes (parallel or meeting), or the plane
    // through one axis parallel to another.
    'points: for (name, of) in &pts {
        let (x, y) = (point(at, of), point(off, of));
        for i in (0..n).filter(|k| !of.contains(k)) {
            for j in (0..n).filter(|k| *k != i && !of.contains(k)) {
                let plane = |f: &Frames| {
                    let c = f.h[i].cross(&f.h[j]);
                    if c.norm() > GENERIC {
                        Some(c.normalize())
                    } else {
                        let across = f.h[i].cross(&(f.p[j] - f.p[i]));
                        (across.norm() > GENERIC * f.size).then(|| across.normalize())
                    }
                };
                let (Some(na), Some(no)) = (plane(at), plane(off)) else {
                    continue;
                };
                if j < i && at.h[i].cross(&at.h[j]).norm() <= GENERIC {
                    continue; // the plane of two parallel axes: once, i < j
                }
                if off_plane(&x, &at.p[i], &na) <= tol(at)
                    && off_plane(&y, &off.p[i], &no) > GENERIC * off.size
                {
                    let which = if at.h[i].cross(&at.h[j]).norm() <= GENERIC {
                        format!("the plane of axes {} and {}", i + 1, j + 1)
                    } else {
                        format!(
                            "the plane through axis {} parallel to axis {}",
                            i + 1,
                            j + 1
                        )
                    };
                    out.push(format!("{name} lies in {which}"));
                    // One plane per point: the others through it follow.
                    continue 'points;
                }
            }
        }
    }
    out
}

fn plus_one(v: &[usize]) -> Vec<usize> {
    v.iter().map(|i| i + 1).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::derive;
    use crate::front::toml_file::load_description_file;

    /// Each factor of a shipped robot's determinant with its meaning.
    fn meanings(file: &str) -> Vec<(String, String)> {
        let path = format!("{}/../robots/{file}.toml", env!("CARGO_MANIFEST_DIR"));
        let (robot, options) = load_description_file(path.as_ref()).unwrap();
        let chain = robot.chain();
        let derived = derive(&chain, &options);
        let det = derived.det.as_ref().unwrap().as_ref().unwrap();
        det.factors
            .iter()
            .map(|f| {
                (
                    f.text.clone(),
                    meaning(&chain, &derived.model.sym, &det.rows, f),
                )
            })
            .collect()
    }

    /// The meaning of the factor whose text is `text`.
    fn of<'a>(m: &'a [(String, String)], text: &str) -> &'a str {
        &m.iter()
            .find(|(t, _)| t == text)
            .unwrap_or_else(|| panic!("{text}: {m:?}"))
            .1
    }

    /// The textbook's three singularities of a 6R arm, found as geometry: the wrist's
    /// axes in line, the wrist centre in the plane of the parallel arm axes (elbow), the
    /// wrist centre on axis 1 or in the plane through it (shoulder).
    #[test]
    fn the_three_singularities_of_industrial_arms() {
        let puma = meanings("puma560");
        assert!(of(&puma, "sin(q5)").starts_with("axes 4 and 6 are in line: joints 4 and 6"));
        assert!(of(&puma, "a3*sin(q3) + d4*cos(q3)")
            .starts_with("the point where axes 4, 5 and 6 meet lies in the plane of axes 2 and 3"));
        assert!(of(&puma, "a2*cos(q2) + a3*cos(q2+q3) - d4*sin(q2+q3)").starts_with(
            "the point where axes 4, 5 and 6 meet lies in the plane through axis 1 parallel to axis 2"
        ));
        let kr6 = meanings("kuka_kr6_r900");
        assert!(of(&kr6, "a1 + a2*sin(q2) + a3*sin(q2+q3) + d4*cos(q2+q3)")
            .starts_with("the point where axes 4, 5 and 6 meet is on axis 1:"));
        let ur5 = meanings("ur5");
        assert!(of(&ur5, "sin(q3)").starts_with("axes 2, 3 and 4 are parallel and in one plane"));
        assert!(of(&ur5, "sin(q5)").starts_with("axes 2, 3, 4 and 6 are parallel"));
        assert!(of(&ur5, "a2").starts_with("a constant of the robot's lengths"));
    }

    /// Arms whose joint 2 or 3 is not an elbow: the SCARA's joint 2 stretches its arm in
    /// a plane, the Stanford arm's sliding joint 3 brings the wrist onto the shoulder.
    #[test]
    fn other_arms_read_as_what_they_are() {
        let scara = meanings("scara");
        assert!(
            of(&scara, "sin(q2)").starts_with("axes 1, 2, 3 and 4 are parallel and in one plane")
        );
        let stanford = meanings("stanford");
        assert!(
            of(&stanford, "q3").starts_with("the point where axes 4, 5 and 6 meet is on axis 2")
        );
        assert!(of(&stanford, "sin(q5)").starts_with("axes 4 and 6 are in line"));
        // No simpler relation of the axes for a skewed shoulder: the null motion only.
        let skew = meanings("skew_shoulder");
        let shoulder = skew.iter().find(|(t, _)| t.len() > 40).unwrap();
        assert!(shoulder.1.starts_with("joints "), "{}", shoulder.1);
    }
}
