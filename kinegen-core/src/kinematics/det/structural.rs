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

use crate::algebra::graph::{Graph, Id};
use crate::algebra::poly::{Poly, Ring, TooLarge};
use crate::chain::Chain;
use crate::kinematics::frames::{FrameView, SymbolicChain};
use crate::kinematics::jacobian::columns_about;
use crate::model::options::Deadline;
use crate::model::value::Rat;

/// A determinant as `constant · Π factors`, each factor in normal form.
#[derive(Clone, Debug, PartialEq)]
pub struct Factored {
    /// Rational constant (sign included).
    pub constant: Rat,
    /// Nonconstant factors, with multiplicity (sorted: single variables first).
    pub factors: Vec<Poly>,
}

impl Factored {
    fn zero() -> Self {
        Factored {
            constant: Rat::zero(),
            factors: Vec::new(),
        }
    }

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
    /// The engine's deadline ([`Deadline`]) passed first.
    Deadline,
}

/// Largest frame entry (terms) a determinant is built from: products of larger ones
/// are slow and their determinant would not be small.
const MAX_DET_INPUT_TERMS: usize = 100;

/// Largest intermediate polynomial (terms) of a closed-form determinant.
pub const MAX_DET_TERMS: usize = 400;

/// The square Jacobian whose determinant is taken: the full 6×N for N = 6, or the task
/// rows when they are as many as the joints.
pub fn square_rows(chain: &Chain) -> Option<Vec<usize>> {
    match &chain.task {
        Some(t) if t.len() == chain.dof() => Some(t.iter().map(|r| r.index()).collect()),
        None if chain.dof() == 6 => Some((0..6).collect()),
        Some(_) if chain.dof() == 6 => Some((0..6).collect()),
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
/// Once the deadline of the graph has passed it gives up with [`DetError::Deadline`]
/// (the caller then emits a numeric determinant).
pub fn determinant(
    chain: &Chain,
    sym: &mut SymbolicChain,
    rows: &[usize],
) -> Result<Factored, DetError> {
    if rows.len() != chain.dof() {
        return Err(DetError::NotSquare);
    }
    if sym.graph.past_deadline() {
        return Err(DetError::Deadline);
    }
    // Only the matrices' normal forms are kept: build them in a scratch copy, so that
    // their nodes do not stand in for (and reshape) the outputs built after.
    let candidates = sparsest(chain, &mut sym.clone(), rows)?;
    let mut best: Option<(Factored, (usize, usize))> = None;
    let mut reference: Option<Poly> = None;
    // A determinant worth a closed form is small; past this many terms in any
    // intermediate the numeric LU is cheaper anyway, so give up early.
    let max_terms = sym.graph.max_terms.min(MAX_DET_TERMS);
    for m in candidates {
        let mut memo = HashMap::new();
        let all: u32 = (1 << chain.dof()) - 1;
        let deadline = sym.graph.deadline;
        let lim = Limits {
            ring: &sym.graph.ring,
            max_terms,
            deadline: &deadline,
        };
        let r = det_rec(&lim, &m, all, all, &mut memo);
        if sym.graph.past_deadline() {
            return Err(DetError::Deadline);
        }
        let Ok(mut f) = r else {
            continue;
        };
        f.sort();
        let expanded = f
            .expand(&sym.graph.ring, max_terms)
            .map_err(|_| DetError::TooLarge)?;
        // Every frame and point must give the same polynomial.
        match &reference {
            None => reference = Some(expanded),
            Some(r) if *r != expanded => return Err(DetError::TooLarge),
            Some(_) => {}
        }
        let score = (usize::MAX - f.factors.len(), f.size());
        if best.as_ref().is_none_or(|(_, s)| score < *s) {
            best = Some((f, score));
        }
    }
    match best {
        Some((f, _)) => Ok(f),
        None if sym.graph.past_deadline() => Err(DetError::Deadline),
        None => Err(DetError::TooLarge),
    }
}

/// The frame a determinant's Jacobian is expressed in.
#[derive(Clone, Copy, Debug)]
enum Frame {
    World,
    /// Link frame `frames[k]`.
    Link(usize),
}

/// The reference point a determinant's Jacobian is taken about.
#[derive(Clone, Copy, Debug)]
enum Point {
    Tool,
    /// The origin of link frame `frames[j]`.
    Origin(usize),
}

/// The matrices of the few sparsest frame/point choices (zeros, then terms), in order.
fn sparsest(
    chain: &Chain,
    sym: &mut SymbolicChain,
    rows: &[usize],
) -> Result<Vec<Vec<Vec<Poly>>>, DetError> {
    let (points, frames) = choices(sym, rows);
    // Entries past the determinant's budget cannot give a small closed form: cap the
    // normal forms while building the matrices so they stop early.
    let saved = sym.graph.max_terms;
    sym.graph.max_terms = saved.min(MAX_DET_TERMS);
    // Each frame's view of the chain is built there directly (see
    // `SymbolicChain::in_frame`), not rotated from the world's.
    let views: Vec<FrameView> = frames
        .iter()
        .map(|&f| match f {
            Frame::World => sym.world_view(),
            Frame::Link(k) => sym.in_frame(k),
        })
        .collect();
    type Scored = ((usize, usize), Vec<Vec<Poly>>);
    let mut candidates: Vec<Scored> = Vec::new();
    for &point in &points {
        for view in &views {
            if sym.graph.past_deadline() {
                sym.graph.max_terms = saved;
                return Err(DetError::Deadline);
            }
            let p = match point {
                Point::Tool => view.tool,
                Point::Origin(j) => view.origins[j],
            };
            if let Some(m) = matrix(chain, &mut sym.graph, rows, view, p) {
                let nonzero = m.iter().flatten().filter(|p| !p.is_zero()).count();
                let terms = m.iter().flatten().map(Poly::len).sum::<usize>();
                candidates.push(((nonzero, terms), m));
            }
        }
    }
    sym.graph.max_terms = saved;
    candidates.sort_by_key(|(score, _)| *score);
    candidates.truncate(3);
    Ok(candidates.into_iter().map(|(_, m)| m).collect())
}

/// Reference points and frames the determinant may be taken in.
fn choices(sym: &mut SymbolicChain, rows: &[usize]) -> (Vec<Point>, Vec<Frame>) {
    let mut points = vec![Point::Tool];
    let mut frames = vec![Frame::World];
    let n = sym.frames.len();
    if rows.len() == 6 {
        // Points on the last axes (the wrist) and middle frames give the sparsest
        // matrices; the other choices only cost time. The world frame is one of them:
        // frame 1 is it turned about joint 1's axis by q1, which takes q1 out of every
        // entry; leaving the world out changes no determinant of robots/ and saves the
        // costliest fifth of the matrices.
        points.extend((n.saturating_sub(4)..n).map(Point::Origin));
        frames.clear();
        frames.extend((0..n.saturating_sub(2).max(1)).map(Frame::Link));
    } else {
        // A task Jacobian is invariant only under rotations that map its rows to
        // themselves: rotations about world z when the rows are x, y (, z, rz).
        let planar = rows.iter().all(|&r| r != 3 && r != 4);
        if planar {
            let z = sym.graph.int(0);
            let one = sym.graph.int(1);
            for (k, t) in sym.frames.iter().enumerate() {
                if t.cols[2] == [z, z, one] {
                    frames.push(Frame::Link(k));
                }
            }
        }
    }
    (points, frames)
}

/// Rows `rows` of J about `point`, all in the coordinates of `view`.
fn matrix(
    chain: &Chain,
    g: &mut Graph,
    rows: &[usize],
    view: &FrameView,
    point: [Id; 3],
) -> Option<Vec<Vec<Poly>>> {
    let n = chain.dof();
    // Inputs past the determinant's budget: no closed form from this choice, and
    // multiplying their normal forms out would only cost time.
    let small = |g: &Graph, ids: &[Id]| {
        ids.iter()
            .all(|&id| g.nf(id).is_some_and(|p| p.len() <= MAX_DET_INPUT_TERMS))
    };
    if !small(g, &point) || !view.axes.iter().all(|(z, o)| small(g, z) && small(g, o)) {
        return None;
    }
    let mut m = vec![vec![Poly::zero(); n]; rows.len()];
    for (i, c) in columns_about(chain, g, &view.axes, point)
        .iter()
        .enumerate()
    {
        let col = [c.lin[0], c.lin[1], c.lin[2], c.ang[0], c.ang[1], c.ang[2]];
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
    deadline: &'a Deadline,
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
    let ri: Vec<usize> = bits(rows);
    let ci: Vec<usize> = bits(cols);
    let (count, is_row, line) = sparsest_line(m, &ri, &ci);
    let result = if count == 0 {
        Factored::zero()
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
            0 => Factored::zero(),
            1 => terms.pop().expect("one term"),
            _ => sum(lim, &terms)?,
        }
    };
    memo.insert((rows, cols), result.clone());
    Ok(result)
}

/// The line (row or column) of the submatrix with the fewest nonzeros:
/// `(count, is_row, index)`.
fn sparsest_line(m: &[Vec<Poly>], ri: &[usize], ci: &[usize]) -> (usize, bool, usize) {
    let mut best: Option<(usize, bool, usize)> = None;
    for &r in ri {
        let k = ci.iter().filter(|&&c| !m[r][c].is_zero()).count();
        if best.is_none_or(|b| k < b.0) {
            best = Some((k, true, r));
        }
    }
    for &c in ci {
        let k = ri.iter().filter(|&&r| !m[r][c].is_zero()).count();
        if best.is_none_or(|b| k < b.0) {
            best = Some((k, false, c));
        }
    }
    best.expect("a nonempty submatrix")
}

/// A sum of Laplace terms: the factors common to all of them pulled out, the rest
/// expanded in normal form.
fn sum(lim: &Limits, terms: &[Factored]) -> Result<Factored, TooLarge> {
    let common = common_factors(terms);
    let mut sum = Poly::zero();
    for t in terms {
        let mut rest = t.factors.clone();
        for c in &common {
            if let Some(i) = rest.iter().position(|x| x == c) {
                rest.remove(i);
            }
        }
        let mut p = Poly::constant(t.constant.clone());
        for x in &rest {
            p = lim.ring.mul_bounded(&p, x, lim.max_terms)?;
        }
        sum = sum.add(&p);
        if sum.len() > lim.max_terms {
            return Err(TooLarge);
        }
    }
    if sum.is_zero() {
        return Ok(Factored::zero());
    }
    let mut f = Factored::one();
    f.factors.extend(common);
    f.push(sum);
    Ok(f)
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
