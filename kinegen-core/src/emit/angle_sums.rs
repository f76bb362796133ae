//! Which intermediates are the sine or cosine of a sum or difference of consecutive
//! joint angles, so the coder names them `c23`, `s2m3` ([`AngleName`]).
//!
//! Recognised on demand from a normal form's variables rather than listed up front:
//! sin/cos of a sum of the angles of joints `i..=j` (each with sign ±1) is multilinear in
//! every one of those joints' (sin, cos) pair and in nothing else, so the variables of a
//! normal form say which run of joints it could be, and only that run's sums are
//! expanded (once, then kept). Listing every run of a 1 000-joint chain up front held
//! about 150 MB of normal forms of which a few were ever looked up.

use std::cell::RefCell;
use std::collections::HashMap;

use crate::algebra::angles::AngleSource;
use crate::algebra::fast_hash::FastMap;
use crate::algebra::poly::{Poly, Ring, Var};
use crate::algebra::trig;
use crate::chain::Chain;
use crate::emit::angle_names::AngleName;
use crate::kinematics::frames::SymbolicChain;
use crate::model::robot::JointKind;

/// Largest expansion of an angle sum given a name (sums of up to 8 angles).
const MAX_NAMED_SUM_TERMS: usize = 128;

/// Longest run of joints whose differences get names (`c2m34`): every sign pattern
/// of a run of k joints is 2^(k−1) names, so longer runs name their plain sum only.
const MAX_NAMED_DIFFERENCE: usize = 4;

/// A run's joints (1-based, subtracted ones marked) with sin and cos of its angle.
type Run = (Vec<(usize, bool)>, Poly, Poly);

/// The angle-sum names of one chain, looked up by normal form.
pub(crate) struct AngleSums<'a> {
    ring: &'a Ring,
    dof: usize,
    /// sin and cos of each revolute joint's angle (without offset), by joint index.
    joint_angle: Vec<Option<(Poly, Poly)>>,
    /// The joint (0-based) whose sin or cos a variable is.
    joint_of: FastMap<Var, usize>,
    /// Names of the sums over joints `first..=last` (0-based), expanded when first asked.
    runs: RefCell<FastMap<(usize, usize), HashMap<Poly, String>>>,
}

impl<'a> AngleSums<'a> {
    /// The sums of `chain`'s joint angles in the symbolic frames `sym`.
    pub(crate) fn new(chain: &Chain, sym: &'a SymbolicChain) -> Self {
        let joint_angle: Vec<Option<(Poly, Poly)>> = chain
            .kinds()
            .enumerate()
            .map(|(i, kind)| {
                if kind != JointKind::Revolute {
                    return None;
                }
                sym.angles.iter().find_map(|a| match &a.source {
                    AngleSource::Joint { joint, offset, .. } if *joint == i && offset.is_zero() => {
                        Some((Poly::var(a.vars.0), Poly::var(a.vars.1)))
                    }
                    _ => None,
                })
            })
            .collect();
        let mut joint_of = FastMap::default();
        for (i, angle) in joint_angle.iter().enumerate() {
            if let Some((s, c)) = angle {
                for v in s.vars().into_iter().chain(c.vars()) {
                    joint_of.insert(v, i);
                }
            }
        }
        AngleSums {
            ring: &sym.graph.ring,
            dof: chain.dof(),
            joint_angle,
            joint_of,
            runs: RefCell::new(FastMap::default()),
        }
    }

    /// `c23` where `p` is cos(q2 + q3), `nc23` where it is −cos(q2 + q3); `None` where
    /// `p` is no named sum.
    pub(crate) fn name(&self, p: &Poly) -> Option<String> {
        if p.len() < 2 || p.len() > MAX_NAMED_SUM_TERMS {
            return None;
        }
        let mut joints = p.vars().into_iter().map(|v| self.joint_of.get(&v).copied());
        let first = joints.next()??;
        let (mut lo, mut hi) = (first, first);
        for j in joints {
            let j = j?;
            (lo, hi) = (lo.min(j), hi.max(j));
        }
        if lo == hi {
            return None;
        }
        let mut runs = self.runs.borrow_mut();
        let names = runs
            .entry((lo, hi))
            .or_insert_with(|| self.run_names(lo, hi));
        names
            .get(p)
            .cloned()
            .or_else(|| names.get(&p.neg()).map(|n| format!("n{n}")))
    }

    /// The named sums and differences over joints `first..=last`: every sign pattern
    /// (the first joint added) up to [`MAX_NAMED_DIFFERENCE`] joints, the plain sum up to
    /// [`MAX_NAMED_SUM_TERMS`] terms. A plain sum keeps its name where a difference has
    /// the same normal form.
    fn run_names(&self, first: usize, last: usize) -> HashMap<Poly, String> {
        let length = last - first + 1;
        let Some((s, c)) = self.joint_angle[first].clone() else {
            return HashMap::new();
        };
        let signs: &[bool] = match length <= MAX_NAMED_DIFFERENCE {
            true => &[false, true],
            false => &[false],
        };
        let mut runs: Vec<Run> = vec![(vec![(first + 1, false)], s, c)];
        for k in first + 1..=last {
            let Some((s2, c2)) = &self.joint_angle[k] else {
                return HashMap::new();
            };
            let mut longer = Vec::new();
            for (joints, s, c) in &runs {
                // sin/cos of a sum of k angles has 2^(k−1) terms: past a few joints the
                // expansion costs more than a name is worth (and grows without bound).
                if s.len() >= MAX_NAMED_SUM_TERMS {
                    continue;
                }
                for &minus in signs {
                    let (ns, nc) = trig::add_angle(self.ring, (s, c), (s2, c2), minus);
                    let mut joints = joints.clone();
                    joints.push((k + 1, minus));
                    longer.push((joints, ns, nc));
                }
            }
            runs = longer;
        }
        let mut names = HashMap::new();
        // Plain sums first, so they keep their names.
        let (plain, differences): (Vec<_>, Vec<_>) = runs
            .into_iter()
            .partition(|(joints, ..)| joints.iter().all(|&(_, minus)| !minus));
        for (joints, s, c) in plain.into_iter().chain(differences) {
            let label = AngleName::label(&joints, self.dof);
            names.entry(s).or_insert(format!("s{label}"));
            names.entry(c).or_insert(format!("c{label}"));
        }
        names
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A planar chain of ten revolute joints (labels take `_`: `c2_3`).
    fn planar_10() -> (Chain, SymbolicChain) {
        let mut src = String::from("name = \"R10\"\nconvention = \"standard\"\n");
        for _ in 0..10 {
            src += "[[joints]]\ntype = \"revolute\"\na = 1.0\nalpha = 0\nd = 0\n";
        }
        let (robot, _) = crate::front::toml_file::load_str(&src, "r10.toml").unwrap();
        let chain = robot.chain();
        let sym = SymbolicChain::new(&chain, 1000);
        (chain, sym)
    }

    /// sin and cos of Σ ± q_j over `joints` (1-based, `true` subtracted).
    fn sum(sym: &SymbolicChain, joints: &[(usize, bool)]) -> (Poly, Poly) {
        let ring = &sym.graph.ring;
        let var = |name: String| {
            (0..ring.len() as Var)
                .find(|&v| ring.name(v) == name)
                .unwrap()
        };
        let (mut s, mut c) = (Poly::zero(), Poly::one());
        for &(j, minus) in joints {
            let angle = (
                Poly::var(var(format!("s{j}"))),
                Poly::var(var(format!("c{j}"))),
            );
            (s, c) = trig::add_angle(ring, (&s, &c), (&angle.0, &angle.1), minus);
        }
        (s, c)
    }

    #[test]
    fn names_sums_and_short_differences_of_consecutive_joints() {
        let (chain, sym) = planar_10();
        let sums = AngleSums::new(&chain, &sym);
        let (s, c) = sum(&sym, &[(2, false), (3, false)]);
        assert_eq!(sums.name(&c).as_deref(), Some("c2_3"));
        assert_eq!(sums.name(&c.neg()).as_deref(), Some("nc2_3"));
        assert_eq!(sums.name(&s).as_deref(), Some("s2_3"));
        let four = [(1, false), (2, true), (3, false), (4, true)];
        assert_eq!(
            sums.name(&sum(&sym, &four).0).as_deref(),
            Some("s1_m2_3_m4")
        );
        let eight: Vec<_> = (3..=10).map(|j| (j, false)).collect();
        assert_eq!(
            sums.name(&sum(&sym, &eight).1).as_deref(),
            Some("c3_4_5_6_7_8_9_10")
        );
    }

    #[test]
    fn leaves_unnamed_what_no_name_covers() {
        let (chain, sym) = planar_10();
        let sums = AngleSums::new(&chain, &sym);
        // Differences of five joints, sums of nine, joints that skip one, one joint.
        let five = [(1, false), (2, true), (3, false), (4, false), (5, false)];
        let nine: Vec<_> = (1..=9).map(|j| (j, false)).collect();
        for joints in [&five[..], &nine, &[(2, false), (4, false)], &[(5, false)]] {
            let (s, c) = sum(&sym, joints);
            assert_eq!((sums.name(&s), sums.name(&c)), (None, None), "{joints:?}");
        }
        // A product of two joints' cosines is no sum.
        let (_, c2) = sum(&sym, &[(2, false)]);
        let (_, c3) = sum(&sym, &[(3, false)]);
        assert_eq!(sums.name(&sym.graph.ring.mul(&c2, &c3)), None);
    }
}
