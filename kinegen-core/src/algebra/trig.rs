//! Reading polynomials back as trigonometry: `a2 c2 c3 − a2 s2 s3` → `a2·cos(q2+q3)`,
//! `a2 c2 c3 + a2 s2 s3` → `a2·cos(q2-q3)`.
//!
//! A normal form in `s_i`, `c_i` is exact but long; people write sines and cosines of
//! angle sums and differences. This module rewrites a polynomial greedily as a sum of
//! terms `coefficient · (other variables) · Π sin/cos(q_i ± … ± q_j)` over runs of
//! consecutive joints, taking at each step the grouping that absorbs the most terms
//! (plain sums first, so a difference is taken only where it absorbs more), and checks
//! the result expands back to the same normal form (else it keeps the plain form).
//! Differences come from joints that turn the other way (a URDF axis along −y after
//! one along +y).

use std::collections::BTreeMap;

use num_traits::{One, Signed};

use crate::algebra::angles::{AngleDef, AngleSource};
use crate::algebra::poly::{Mono, Poly, Ring, Var};
use crate::model::value::{fmt_rat, Rat};

/// `sin` or `cos` of a signed sum of consecutive joint angles (`q2 - q3 + q4`).
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct SumTrig {
    /// true for sin.
    pub sin: bool,
    /// Angles (indices into the angle list) of consecutive joints, each `true` where it
    /// is subtracted; the first is never subtracted.
    pub angles: Vec<(usize, bool)>,
}

/// One term: `coef · rest · Π trig`.
#[derive(Clone, Debug, PartialEq)]
pub struct TrigTerm {
    /// Rational coefficient.
    pub coef: Rat,
    /// Non-trigonometric variables (parameters, prismatic joints, √k).
    pub rest: Mono,
    /// Trigonometric factors; a variable squared appears twice.
    pub trig: Vec<SumTrig>,
}

/// Angles that can be summed: joint angles in order (`None` breaks a run).
struct Angles {
    /// For each ring var that is a sine/cosine: (angle index, is_sin).
    of_var: BTreeMap<Var, (usize, bool)>,
    /// Joint number (1-based) of each angle, if it is a joint angle without offset.
    joint_of: Vec<Option<usize>>,
}

impl Angles {
    fn new(angles: &[AngleDef]) -> Self {
        let mut of_var = BTreeMap::new();
        let mut joint_of = Vec::new();
        for (k, a) in angles.iter().enumerate() {
            of_var.insert(a.vars.0, (k, true));
            of_var.insert(a.vars.1, (k, false));
            joint_of.push(match &a.source {
                AngleSource::Joint { joint, .. } => Some(joint + 1),
                AngleSource::Constant(_) => None,
            });
        }
        Angles { of_var, joint_of }
    }
}

/// `(sin, cos)` of `x ± y` from those of `x` and `y` (`minus` for `x − y`).
pub fn add_angle(
    ring: &Ring,
    (s, c): (&Poly, &Poly),
    (sy, cy): (&Poly, &Poly),
    minus: bool,
) -> (Poly, Poly) {
    // sin(−y) = −sin y, cos(−y) = cos y.
    let sy = if minus { sy.neg() } else { sy.clone() };
    let ns = ring.mul(s, cy).add(&ring.mul(c, &sy));
    let nc = ring.mul(c, cy).sub(&ring.mul(s, &sy));
    (ns, nc)
}

/// The normal form of `sin`/`cos` of a sum of the chain's angles.
pub fn sum_nf(ring: &Ring, angles: &[AngleDef], t: &SumTrig) -> Poly {
    let (mut s, mut c) = (Poly::zero(), Poly::one());
    for &(a, minus) in &t.angles {
        let (sa, ca) = (Poly::var(angles[a].vars.0), Poly::var(angles[a].vars.1));
        (s, c) = add_angle(ring, (&s, &c), (&sa, &ca), minus);
    }
    if t.sin {
        s
    } else {
        c
    }
}

/// Rewrite `p` as a sum of trigonometric terms; `None` if the check fails.
pub fn rewrite(ring: &Ring, angles: &[AngleDef], p: &Poly) -> Option<Vec<TrigTerm>> {
    let ang = Angles::new(angles);
    let mut rest = p.clone();
    let mut out = Vec::new();
    let mut guard = 0;
    while !rest.is_empty() {
        guard += 1;
        if guard > 10_000 {
            return None;
        }
        // The term with the most trigonometric variables first.
        let (mono, coef) = rest
            .terms()
            .max_by_key(|(m, _)| m.iter().filter(|(v, _)| ang.of_var.contains_key(v)).count())
            .map(|(m, c)| (m.clone(), c.clone()))?;
        let (trig_vars, other): (Mono, Mono) =
            mono.iter().partition(|(v, _)| ang.of_var.contains_key(v));
        // Singles: every variable on its own (always exact, absorbs one term).
        let singles: Vec<(usize, bool, u32)> = trig_vars
            .iter()
            .map(|&(v, e)| {
                let (a, s) = ang.of_var[&v];
                (a, s, e)
            })
            .collect();
        let mut best: Option<(isize, TrigTerm, Poly)> = None;
        for grouping in groupings(&singles, &ang) {
            let mut nf = Poly::constant(Rat::one());
            for t in &grouping {
                nf = ring.mul(&nf, &sum_nf(ring, angles, t));
            }
            // Coefficient so that the chosen monomial matches.
            let k = nf
                .terms()
                .find(|(m, _)| **m == trig_vars)
                .map(|(_, c)| c.clone());
            let Some(k) = k else { continue };
            let c = &coef / &k;
            let term_nf = ring.mul(&nf, &Poly::from_terms([(other.clone(), c.clone())]));
            // Terms of `rest` the subtraction removes, less those it adds: looked up
            // term by term, not by subtracting (`rest` may have thousands of terms and a
            // run of six joints has 243 groupings).
            let gain: isize = term_nf
                .terms()
                .map(|(m, c)| match rest.coefficient(m) {
                    Some(r) if r == c => 1,
                    Some(_) => 0,
                    None => -1,
                })
                .sum();
            if gain > 0 && best.as_ref().is_none_or(|(g, _, _)| gain > *g) {
                best = Some((
                    gain,
                    TrigTerm {
                        coef: c,
                        rest: other.clone(),
                        trig: grouping,
                    },
                    term_nf,
                ));
            }
        }
        let (_, term, term_nf) = best?;
        out.push(term);
        rest = rest.sub(&term_nf);
    }
    // Read in joint order: a2*cos(q2) + a3*cos(q2+q3) + d5*sin(q2+q3+q4).
    out.sort_by(|a, b| {
        let key = |t: &TrigTerm| {
            let mut angles: Vec<usize> = t
                .trig
                .iter()
                .flat_map(|f| f.angles.iter().map(|&(a, _)| a))
                .collect();
            angles.sort_unstable();
            (angles.len(), angles, t.rest.clone())
        };
        key(a).cmp(&key(b))
    });
    // Check: the terms expand back to p.
    let mut sum = Poly::zero();
    for t in &out {
        let mut nf = Poly::from_terms([(t.rest.clone(), t.coef.clone())]);
        for f in &t.trig {
            nf = ring.mul(&nf, &sum_nf(ring, angles, f));
        }
        sum = sum.add(&nf);
    }
    (sum == *p).then_some(out)
}

/// Most groupings tried for one term (a term with six joints' variables has 243).
const MAX_GROUPINGS: usize = 1024;

/// Longest run whose sign patterns are tried (2^(k−1) of them).
const MAX_SIGNED_RUN: usize = 6;

/// Ways to group a term's trigonometric variables into signed sums over consecutive
/// joints: every plain grouping first, then those with differences.
fn groupings(singles: &[(usize, bool, u32)], ang: &Angles) -> Vec<Vec<SumTrig>> {
    // Variables with exponent 1 on joint angles can join runs; the rest stay single.
    let mut fixed = Vec::new();
    let mut runnable: Vec<(usize, bool)> = Vec::new();
    for &(a, s, e) in singles {
        if e == 1 && ang.joint_of[a].is_some() {
            runnable.push((a, s));
        } else {
            for _ in 0..e {
                fixed.push(SumTrig {
                    sin: s,
                    angles: vec![(a, false)],
                });
            }
        }
    }
    runnable.sort_by_key(|&(a, _)| ang.joint_of[a]);
    let n = runnable.len();
    if n == 0 {
        return vec![fixed];
    }
    // Ways to cut the sorted list into runs of consecutive joints: it must be cut
    // between joints that are not consecutive, and may be between those that are (the
    // first ten such places: a bounded number of cuts whatever the term).
    let consecutive =
        |i: usize| ang.joint_of[runnable[i].0] == ang.joint_of[runnable[i - 1].0].map(|j| j + 1);
    let free: Vec<usize> = (1..n).filter(|&i| consecutive(i)).collect();
    let mut cuts: Vec<Vec<&[(usize, bool)]>> = Vec::new();
    for mask in 0u32..(1 << free.len().min(10)) {
        let mut runs = Vec::new();
        let mut begin = 0;
        for i in 1..n {
            let cut = match free.iter().position(|&f| f == i) {
                Some(j) => j < 10 && mask & (1 << j) != 0,
                None => true,
            };
            if cut {
                runs.push(&runnable[begin..i]);
                begin = i;
            }
        }
        runs.push(&runnable[begin..]);
        cuts.push(runs);
    }
    // Each run of k ≤ MAX_SIGNED_RUN angles has 2^(k−1) sign patterns (bit j: angle
    // j+1 subtracted), a longer run its plain sum only; pattern 0 everywhere is the
    // plain sum.
    let mut results = Vec::new();
    for with_differences in [false, true] {
        for runs in &cuts {
            let sizes: Vec<u64> = runs
                .iter()
                .map(|r| match r.len() <= MAX_SIGNED_RUN {
                    true => 1 << (r.len() - 1),
                    false => 1,
                })
                .collect();
            let total: u64 = sizes.iter().fold(1, |t, &s| t.saturating_mul(s));
            let patterns = if with_differences { 1..total } else { 0..1 };
            for mut code in patterns {
                let mut groups: Vec<SumTrig> = fixed.clone();
                for (run, size) in runs.iter().zip(&sizes) {
                    groups.push(close(run, code % size));
                    code /= size;
                }
                results.push(groups);
                if results.len() >= MAX_GROUPINGS {
                    return results;
                }
            }
        }
    }
    results
}

/// A run's sine or cosine: the monomial's parity of sines decides which; `minus` has
/// bit j set where angle j + 1 of the run is subtracted.
fn close(run: &[(usize, bool)], minus: u64) -> SumTrig {
    let sines = run.iter().filter(|(_, s)| *s).count();
    let subtracted = |j: usize| {
        j > 0
            && u32::try_from(j - 1)
                .ok()
                .and_then(|b| minus.checked_shr(b))
                .is_some_and(|m| m & 1 != 0)
    };
    SumTrig {
        sin: sines % 2 == 1,
        angles: run
            .iter()
            .enumerate()
            .map(|(j, &(a, _))| (a, subtracted(j)))
            .collect(),
    }
}

/// The angles of a signed sum as text, each with `true` where it is subtracted.
fn angle_parts(defs: &[AngleDef], angles: &[(usize, bool)]) -> Vec<(String, bool)> {
    angles
        .iter()
        .map(|&(a, minus)| {
            let text = match &defs[a].source {
                AngleSource::Joint {
                    joint,
                    sign,
                    offset,
                } if *sign > 0 => match offset.is_zero() {
                    true => format!("q{}", joint + 1),
                    false => format!("(q{} + {offset})", joint + 1),
                },
                s @ AngleSource::Joint { .. } => format!("({})", s.text()),
                AngleSource::Constant(v) => format!("{v}"),
            };
            (text, minus)
        })
        .collect()
}

/// Text of a signed angle sum: `q2+q3`, `q2-q3`.
pub fn angle_text(defs: &[AngleDef], angles: &[(usize, bool)]) -> String {
    let mut s = String::new();
    for (k, (text, minus)) in angle_parts(defs, angles).into_iter().enumerate() {
        if k > 0 {
            s.push(if minus { '-' } else { '+' });
        }
        s.push_str(&text);
    }
    s
}

/// A term's trigonometric factors with equal neighbours counted: `cos(q3)·cos(q3)` is
/// `cos(q3)^2` to a reader.
fn powers(trig: &[SumTrig]) -> Vec<(&SumTrig, usize)> {
    let mut out: Vec<(&SumTrig, usize)> = Vec::new();
    for f in trig {
        match out.last_mut() {
            Some((g, n)) if *g == f => *n += 1,
            _ => out.push((f, 1)),
        }
    }
    out
}

/// Plain-text formula of a rewritten polynomial (`a2*cos(q2) + a3*cos(q2+q3)`).
pub fn text(ring: &Ring, angles: &[AngleDef], terms: &[TrigTerm]) -> String {
    let mut s = String::new();
    for (i, t) in terms.iter().enumerate() {
        let neg = t.coef.is_negative();
        let a = t.coef.abs();
        s.push_str(match (i, neg) {
            (0, true) => "-",
            (0, false) => "",
            (_, true) => " - ",
            (_, false) => " + ",
        });
        let mut parts: Vec<String> = Vec::new();
        if !a.is_one() {
            parts.push(fmt_rat(&a));
        }
        for &(v, e) in &t.rest {
            let n = ring.name(v).to_string();
            parts.push(if e == 1 { n } else { format!("{n}^{e}") });
        }
        for (f, power) in powers(&t.trig) {
            let f = format!(
                "{}({})",
                if f.sin { "sin" } else { "cos" },
                angle_text(angles, &f.angles)
            );
            parts.push(if power == 1 {
                f
            } else {
                format!("{f}^{power}")
            });
        }
        if parts.is_empty() {
            parts.push("1".into());
        }
        s.push_str(&parts.join("*"));
    }
    if s.is_empty() {
        s.push('0');
    }
    s
}

/// LaTeX of a rewritten polynomial (`a_{2} \cos(q_{2}) + …`).
pub fn latex(ring: &Ring, angles: &[AngleDef], terms: &[TrigTerm]) -> String {
    let sub = |name: &str| -> String {
        let i = name
            .find(|c: char| c.is_ascii_digit())
            .unwrap_or(name.len());
        let (head, tail) = name.split_at(i);
        if tail.is_empty() {
            head.to_string()
        } else {
            format!("{head}_{{{tail}}}")
        }
    };
    let mut s = String::new();
    for (i, t) in terms.iter().enumerate() {
        let neg = t.coef.is_negative();
        let a = t.coef.abs();
        s.push_str(match (i, neg) {
            (0, true) => "-",
            (0, false) => "",
            (_, true) => " - ",
            (_, false) => " + ",
        });
        let mut parts: Vec<String> = Vec::new();
        if !a.is_one() {
            parts.push(fmt_rat(&a));
        }
        for &(v, e) in &t.rest {
            let n = sub(ring.name(v));
            parts.push(if e == 1 { n } else { format!("{n}^{{{e}}}") });
        }
        for (f, power) in powers(&t.trig) {
            let mut arg = String::new();
            for (k, (text, minus)) in angle_parts(angles, &f.angles).into_iter().enumerate() {
                if k > 0 {
                    arg.push_str(if minus { " - " } else { " + " });
                }
                let terms: Vec<String> = text.split('+').map(|x| sub(x.trim())).collect();
                arg.push_str(&terms.join(" + "));
            }
            let power = match power {
                1 => String::new(),
                p => format!("^{{{p}}}"),
            };
            parts.push(format!(
                "\\{}{power}({arg})",
                if f.sin { "sin" } else { "cos" },
            ));
        }
        if parts.is_empty() {
            parts.push("1".into());
        }
        s.push_str(&parts.join(" "));
    }
    if s.is_empty() {
        s.push('0');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::value::Value;

    /// `n` joint angles, with their ring.
    fn joints(n: usize) -> (Ring, Vec<AngleDef>) {
        let mut ring = Ring::new();
        let defs = (0..n)
            .map(|i| AngleDef {
                source: AngleSource::Joint {
                    joint: i,
                    sign: 1,
                    offset: Value::zero(),
                },
                vars: ring.angle(i, &format!("{}", i + 1)),
                suffix: format!("{}", i + 1),
            })
            .collect();
        (ring, defs)
    }

    #[test]
    fn differences_are_read_back() {
        let (ring, defs) = joints(3);
        let (s2, c2) = defs[1].vars;
        let (s3, c3) = defs[2].vars;
        let v = |x| Poly::var(x);
        // 2·(c2 c3 + s2 s3) + 3·(s2 c3 − c2 s3) = 2 cos(q2−q3) + 3 sin(q2−q3)
        let p = ring
            .mul(&v(c2), &v(c3))
            .add(&ring.mul(&v(s2), &v(s3)))
            .scale(&Rat::from_integer(2.into()))
            .add(
                &ring
                    .mul(&v(s2), &v(c3))
                    .sub(&ring.mul(&v(c2), &v(s3)))
                    .scale(&Rat::from_integer(3.into())),
            );
        let terms = rewrite(&ring, &defs, &p).unwrap();
        assert_eq!(text(&ring, &defs, &terms), "2*cos(q2-q3) + 3*sin(q2-q3)");
        // A plain sum stays a sum.
        let sum = ring.mul(&v(c2), &v(c3)).sub(&ring.mul(&v(s2), &v(s3)));
        let terms = rewrite(&ring, &defs, &sum).unwrap();
        assert_eq!(text(&ring, &defs, &terms), "cos(q2+q3)");
    }

    /// A term with forty joints' variables: a bounded number of groupings, at once.
    #[test]
    fn groupings_are_bounded() {
        let (_, defs) = joints(40);
        let singles: Vec<(usize, bool, u32)> = (0..40).map(|i| (i, i % 2 == 0, 1)).collect();
        let g = groupings(&singles, &Angles::new(&defs));
        assert!(!g.is_empty() && g.len() <= MAX_GROUPINGS, "{}", g.len());
    }
}
