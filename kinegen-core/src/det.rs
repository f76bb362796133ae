//! Closed-form Jacobian determinants, by structure rather than brute force.
//!
//! `det J` does not change when J is expressed in another frame (`diag(Rᵀ, Rᵀ)`, det 1)
//! or about another reference point (`[[I, −[r]×], [0, I]]`, det 1). Expressed in a
//! middle frame about a point on the last axes, J has many exact zeros; the determinant
//! is then taken structurally — a row or column with a single nonzero entry splits off
//! that entry as a factor, the rest is memoised Laplace expansion with every product in
//! normal form — and comes out as a product of small factors. Every choice of frame and
//! point gives the same polynomial; the one with the most, smallest factors is kept, and
//! the product of the factors is checked equal to the others' in normal form.

use std::collections::HashMap;

use num_traits::{One, Signed, Zero};

use crate::chain::Chain;
use crate::dh::{JointKind, Robot};
use crate::graph::Id;
use crate::jacobian::cross;
use crate::poly::{Poly, Ring, TooLarge};
use crate::value::Rat;

/// A determinant as `constant · Π factors`, each factor in normal form.
#[derive(Clone, Debug, PartialEq)]
pub struct Factored {
    /// Rational constant (sign included).
    pub constant: Rat,
    /// Nonconstant factors, with multiplicity (sorted: single variables first).
    pub factors: Vec<Poly>,
}

impl Factored {
    fn one() -> Self {
        Factored {
            constant: Rat::one(),
            factors: Vec::new(),
        }
    }

    /// Whether the determinant is identically zero.
    pub fn is_zero(&self) -> bool {
        self.constant.is_zero()
    }

    /// The product, expanded in normal form.
    pub fn expand(&self, ring: &Ring, max_terms: usize) -> Result<Poly, TooLarge> {
        let mut p = Poly::constant(self.constant.clone());
        for f in &self.factors {
            p = ring.mul_bounded(&p, f, max_terms)?;
        }
        Ok(p)
    }

    fn push(&mut self, p: Poly) {
        // Split off the monomial and rational content: a2·s5·(…) → a2, s5, (…).
        let (mono, k) = p.content();
        let rest = p.div_content(&mono, &k);
        self.constant *= k;
        for &(v, e) in &mono {
            for _ in 0..e {
                self.factors.push(Poly::var(v));
            }
        }
        if let Some(c) = rest.as_constant() {
            self.constant *= c;
        } else {
            // Normalise the sign: leading coefficient positive.
            let lead_neg = rest.terms().next().is_some_and(|(_, c)| c.is_negative());
            if lead_neg {
                self.constant = -self.constant.clone();
                self.factors.push(rest.neg());
            } else {
                self.factors.push(rest);
            }
        }
    }

    fn mul(mut self, other: Factored) -> Self {
        self.constant *= other.constant;
        self.factors.extend(other.factors);
        self
    }

    fn size(&self) -> usize {
        self.factors.iter().map(Poly::len).sum()
    }

    fn sort(&mut self) {
        self.factors
            .sort_by(|a, b| a.len().cmp(&b.len()).then(a.cmp(b)));
    }
}

/// Why a closed-form determinant was not produced.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DetError {
    /// The matrix is not square.
    NotSquare,
    /// Expressions grew past the term budget.
    TooLarge,
    /// The engine's deadline ([`crate::generate::Deadline`]) passed first.
    Deadline,
}

/// Largest frame entry (terms) a determinant is built from: products of larger ones
/// are slow and their determinant would not be small.
const MAX_DET_INPUT_TERMS: usize = 100;

/// Largest intermediate polynomial (terms) of a closed-form determinant.
pub const MAX_DET_TERMS: usize = 400;

/// The square Jacobian whose determinant is taken: the full 6×N for N = 6, or the task
/// rows when they are as many as the joints.
pub fn square_rows(robot: &Robot) -> Option<Vec<usize>> {
    match &robot.task {
        Some(t) if t.len() == robot.dof() => Some(t.iter().map(|r| r.index()).collect()),
        None if robot.dof() == 6 => Some((0..6).collect()),
        Some(_) if robot.dof() == 6 => Some((0..6).collect()),
        _ => None,
    }
}

/// The closed-form determinant of the Jacobian rows `rows` (indices into
/// `[vx vy vz ωx ωy ωz]`), the linear rows taken at the tool point.
///
/// For the full 6×6 Jacobian every frame and every joint-frame origin as reference point
/// is tried; for a task Jacobian only frames (its linear rows depend on the point), and
/// only frames that rotate about world z when the task has rows other than all six.
///
/// Once the deadline of the chain's graph has passed it gives up with
/// [`DetError::Deadline`] (the caller then emits a numeric determinant).
pub fn determinant(robot: &Robot, chain: &mut Chain, rows: &[usize]) -> Result<Factored, DetError> {
    let n = robot.dof();
    if rows.len() != n {
        return Err(DetError::NotSquare);
    }
    if chain.graph.past_deadline() {
        return Err(DetError::Deadline);
    }
    let full = rows.len() == 6;
    let mut points: Vec<[Id; 3]> = vec![chain.tool.p];
    let mut frames: Vec<[[Id; 3]; 3]> = vec![identity_cols(chain)];
    if full {
        // Points on the last axes (the wrist) and middle frames give the sparsest
        // matrices; the other choices only cost time.
        let n = chain.frames.len();
        points.extend(chain.frames[n.saturating_sub(4)..].iter().map(|t| t.p));
        frames.extend(
            chain.frames[..n.saturating_sub(2).max(1)]
                .iter()
                .map(|t| t.cols),
        );
    } else {
        // A task Jacobian is invariant only under rotations that map its rows to
        // themselves: rotations about world z when the rows are x, y (, z, rz).
        let planar = rows.iter().all(|&r| r != 3 && r != 4);
        if planar {
            for t in &chain.frames {
                let z = chain.graph.int(0);
                let one = chain.graph.int(1);
                if t.cols[2] == [z, z, one] {
                    frames.push(t.cols);
                }
            }
        }
    }
    // A determinant worth a closed form is small; past this many terms in any
    // intermediate the numeric LU is cheaper anyway, so give up early.
    let max_terms = chain.graph.max_terms.min(MAX_DET_TERMS);
    let mut best: Option<(Factored, (usize, usize))> = None;
    let mut reference: Option<Poly> = None;
    // Rank the choices by sparsity (zeros, then terms) and expand only the best few.
    type Scored = ((usize, usize), Vec<Vec<Poly>>);
    let mut candidates: Vec<Scored> = Vec::new();
    for point in &points {
        for cols in &frames {
            if chain.graph.past_deadline() {
                return Err(DetError::Deadline);
            }
            // Entries past the determinant's budget cannot give a small closed form:
            // cap the normal forms while building the matrix so they stop early.
            let saved = chain.graph.max_terms;
            chain.graph.max_terms = saved.min(MAX_DET_TERMS);
            let m = matrix(robot, chain, rows, *point, cols);
            chain.graph.max_terms = saved;
            if let Some(m) = m {
                let nonzero = m.iter().flatten().filter(|p| !p.is_zero()).count();
                let terms = m.iter().flatten().map(Poly::len).sum::<usize>();
                candidates.push(((nonzero, terms), m));
            }
        }
    }
    candidates.sort_by_key(|(score, _)| *score);
    candidates.truncate(3);
    {
        for (_, m) in candidates {
            let mut memo = HashMap::new();
            let all_rows: u32 = (1 << n) - 1;
            let deadline = chain.graph.deadline;
            let r = det_rec(
                &Limits {
                    ring: &chain.graph.ring,
                    max_terms,
                    deadline: &deadline,
                },
                &m,
                all_rows,
                all_rows,
                &mut memo,
            );
            if chain.graph.past_deadline() {
                return Err(DetError::Deadline);
            }
            let Ok(mut f) = r else {
                continue;
            };
            f.sort();
            let expanded = f
                .expand(&chain.graph.ring, max_terms)
                .map_err(|_| DetError::TooLarge)?;
            match &reference {
                None => reference = Some(expanded),
                Some(r) => {
                    // Every frame and point must give the same polynomial.
                    if *r != expanded {
                        return Err(DetError::TooLarge);
                    }
                }
            }
            let score = (usize::MAX - f.factors.len(), f.size());
            if best.as_ref().is_none_or(|(_, s)| score < *s) {
                best = Some((f, score));
            }
        }
    }
    match best {
        Some((f, _)) => Ok(f),
        None if chain.graph.past_deadline() => Err(DetError::Deadline),
        None => Err(DetError::TooLarge),
    }
}

fn identity_cols(chain: &mut Chain) -> [[Id; 3]; 3] {
    let (o, l) = (chain.graph.int(0), chain.graph.int(1));
    [[l, o, o], [o, l, o], [o, o, l]]
}

/// Rows `rows` of J about `point`, expressed in the frame with rotation columns `cols`.
fn matrix(
    robot: &Robot,
    chain: &mut Chain,
    rows: &[usize],
    point: [Id; 3],
    cols: &[[Id; 3]; 3],
) -> Option<Vec<Vec<Poly>>> {
    let n = robot.dof();
    let g = &mut chain.graph;
    // Inputs past the determinant's budget: no closed form from this choice, and
    // multiplying their normal forms out would only cost time.
    let small = |g: &crate::graph::Graph, ids: &[Id]| {
        ids.iter()
            .all(|&id| g.nf(id).is_some_and(|p| p.len() <= MAX_DET_INPUT_TERMS))
    };
    let flat: Vec<Id> = cols.iter().flatten().copied().chain(point).collect();
    if !small(g, &flat) || !chain.axes.iter().all(|(z, o)| small(g, z) && small(g, o)) {
        return None;
    }
    let zero = g.int(0);
    let mut m = vec![vec![Poly::zero(); n]; rows.len()];
    for (i, joint) in robot.joints.iter().enumerate() {
        let (z, o) = chain.axes[i];
        let (lin, ang) = match joint.kind {
            JointKind::Revolute => {
                let r = [
                    g.sub(point[0], o[0]),
                    g.sub(point[1], o[1]),
                    g.sub(point[2], o[2]),
                ];
                (cross(g, z, r), z)
            }
            JointKind::Prismatic => (z, [zero; 3]),
        };
        let mut col = [0; 6];
        for (block, v) in [(0, lin), (3, ang)] {
            for (k, c) in cols.iter().enumerate() {
                // (Rᵀ v)_k = column k of R · v
                let terms: Vec<Id> = (0..3).map(|t| g.mul(c[t], v[t])).collect();
                col[block + k] = g.sum(&terms);
            }
        }
        for (r, &row) in rows.iter().enumerate() {
            m[r][i] = g.nf(col[row])?.clone();
        }
    }
    Some(m)
}

type Memo = HashMap<(u32, u32), Factored>;

/// What bounds a Laplace expansion.
struct Limits<'a> {
    ring: &'a Ring,
    /// Largest intermediate (terms).
    max_terms: usize,
    /// Past it, give up (the caller reports [`DetError::Deadline`]).
    deadline: &'a crate::generate::Deadline,
}

/// Determinant of the submatrix on `rows` × `cols` (bit sets), factored.
fn det_rec(
    lim: &Limits,
    m: &[Vec<Poly>],
    rows: u32,
    cols: u32,
    memo: &mut Memo,
) -> Result<Factored, TooLarge> {
    if rows == 0 {
        return Ok(Factored::one());
    }
    if let Some(f) = memo.get(&(rows, cols)) {
        return Ok(f.clone());
    }
    if lim.deadline.passed() {
        return Err(TooLarge);
    }
    let (ring, max_terms) = (lim.ring, lim.max_terms);
    let ri: Vec<usize> = bits(rows);
    let ci: Vec<usize> = bits(cols);
    // The line (row or column) with the fewest nonzeros.
    let mut best: Option<(usize, bool, usize)> = None; // (count, is_row, index)
    for &r in &ri {
        let k = ci.iter().filter(|&&c| !m[r][c].is_zero()).count();
        if best.is_none_or(|b| k < b.0) {
            best = Some((k, true, r));
        }
    }
    for &c in &ci {
        let k = ri.iter().filter(|&&r| !m[r][c].is_zero()).count();
        if best.is_none_or(|b| k < b.0) {
            best = Some((k, false, c));
        }
    }
    let (count, is_row, line) = best.expect("nonempty");
    let result = if count == 0 {
        Factored {
            constant: Rat::zero(),
            factors: Vec::new(),
        }
    } else {
        // Laplace along the line; a single entry becomes a factor.
        let others: Vec<usize> = if is_row { ci.clone() } else { ri.clone() };
        let pos_line = if is_row { &ri } else { &ci }
            .iter()
            .position(|&x| x == line)
            .unwrap_or(0);
        let mut terms: Vec<Factored> = Vec::new();
        for (k, &o) in others.iter().enumerate() {
            let (r, c) = if is_row { (line, o) } else { (o, line) };
            let e = &m[r][c];
            if e.is_zero() {
                continue;
            }
            let minor = det_rec(lim, m, rows & !(1 << r), cols & !(1 << c), memo)?;
            if minor.is_zero() {
                continue;
            }
            let mut f = Factored::one();
            if (pos_line + k) % 2 == 1 {
                f.constant = -f.constant;
            }
            f.push(e.clone());
            terms.push(f.mul(minor));
        }
        match terms.len() {
            0 => Factored {
                constant: Rat::zero(),
                factors: Vec::new(),
            },
            1 => terms.pop().expect("one term"),
            _ => {
                // A sum: pull out factors common to all terms, expand the rest.
                let common = common_factors(&terms);
                let mut sum = Poly::zero();
                for t in &terms {
                    let mut rest = t.factors.clone();
                    for c in &common {
                        if let Some(i) = rest.iter().position(|x| x == c) {
                            rest.remove(i);
                        }
                    }
                    let mut p = Poly::constant(t.constant.clone());
                    for x in &rest {
                        p = ring.mul_bounded(&p, x, max_terms)?;
                    }
                    sum = sum.add(&p);
                    if sum.len() > max_terms {
                        return Err(TooLarge);
                    }
                }
                let mut f = Factored::one();
                for c in common {
                    f.factors.push(c);
                }
                if sum.is_zero() {
                    Factored {
                        constant: Rat::zero(),
                        factors: Vec::new(),
                    }
                } else {
                    f.push(sum);
                    f
                }
            }
        }
    };
    memo.insert((rows, cols), result.clone());
    Ok(result)
}

fn common_factors(terms: &[Factored]) -> Vec<Poly> {
    let mut common: Vec<Poly> = terms[0].factors.clone();
    for t in &terms[1..] {
        let mut avail = t.factors.clone();
        common.retain(|c| match avail.iter().position(|x| x == c) {
            Some(i) => {
                avail.remove(i);
                true
            }
            None => false,
        });
    }
    common
}

fn bits(x: u32) -> Vec<usize> {
    (0..32).filter(|i| x & (1 << i) != 0).collect()
}

/// Merge equal factors into powers: `[(factor, multiplicity)]`.
pub fn powers(f: &Factored) -> Vec<(Poly, u32)> {
    let mut out: Vec<(Poly, u32)> = Vec::new();
    for p in &f.factors {
        match out.iter_mut().find(|(q, _)| q == p) {
            Some((_, k)) => *k += 1,
            None => out.push((p.clone(), 1)),
        }
    }
    out
}
