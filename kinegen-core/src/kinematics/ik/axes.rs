//! Exact geometry of the joint axes at `q = 0`: which are parallel, which meet, which
//! three meet in one point — decided on normal forms, so "parallel" means parallel for
//! every value of the parameters, not within a tolerance.
//!
//! An axis is a line `p + t h` with `h` and `p` polynomials (in the parameters, `√2`,
//! `√3`, constant angles, and the sine and cosine of a joint left variable). Every test is
//! a polynomial identity: no division, so nothing is decided by a float.

use crate::algebra::graph::Id;
use crate::algebra::poly::{Poly, Ring};
use crate::kinematics::frames::SymbolicChain;

/// A vector of normal forms.
pub type PVec = [Poly; 3];

/// The joint axes of a chain at `q = 0`, as normal forms.
#[derive(Clone, Debug)]
pub struct Axes {
    /// Directions `h_i` (the joint's positive sense; negated for a flipped joint).
    pub h: Vec<PVec>,
    /// A point `p_i` on each axis.
    pub p: Vec<PVec>,
    /// The tool point.
    pub tool: PVec,
    ring: Ring,
}

impl Axes {
    /// The axes of `sym` (built with [`SymbolicChain::at_zero`]); `None` if a normal form
    /// is over the term budget (nothing can then be decided exactly).
    pub fn of(sym: &SymbolicChain) -> Option<Axes> {
        let g = &sym.graph;
        let nf = |v: &[Id; 3]| -> Option<PVec> {
            Some([
                g.nf(v[0])?.clone(),
                g.nf(v[1])?.clone(),
                g.nf(v[2])?.clone(),
            ])
        };
        let mut h = Vec::new();
        let mut p = Vec::new();
        for (z, o) in &sym.axes {
            h.push(nf(z)?);
            p.push(nf(o)?);
        }
        Some(Axes {
            h,
            p,
            tool: nf(&sym.tool.p)?,
            ring: g.ring.clone(),
        })
    }

    /// Number of axes.
    pub fn len(&self) -> usize {
        self.h.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.h.is_empty()
    }

    fn cross(&self, a: &PVec, b: &PVec) -> PVec {
        let r = &self.ring;
        let c = |i: usize, j: usize| r.mul(&a[i], &b[j]).sub(&r.mul(&a[j], &b[i]));
        [c(1, 2), c(2, 0), c(0, 1)]
    }

    fn dot(&self, a: &PVec, b: &PVec) -> Poly {
        let r = &self.ring;
        r.mul(&a[0], &b[0])
            .add(&r.mul(&a[1], &b[1]))
            .add(&r.mul(&a[2], &b[2]))
    }

    fn scale(&self, a: &PVec, k: &Poly) -> PVec {
        let r = &self.ring;
        [r.mul(&a[0], k), r.mul(&a[1], k), r.mul(&a[2], k)]
    }

    /// Axes `i` and `j` are parallel (or antiparallel).
    pub fn parallel(&self, i: usize, j: usize) -> bool {
        is_zero(&self.cross(&self.h[i], &self.h[j]))
    }

    /// Axis `i` is along the constant direction `d` (up to sign).
    pub fn along(&self, i: usize, d: &PVec) -> bool {
        is_zero(&self.cross(&self.h[i], d))
    }

    /// Axes `i` and `j` are perpendicular (`h_i · h_j = 0` identically).
    pub fn perpendicular(&self, i: usize, j: usize) -> bool {
        self.dot(&self.h[i], &self.h[j]).is_zero()
    }

    /// `h_i · h_j` when it is a constant (`±1` for parallel unit axes).
    pub fn dot_constant(&self, i: usize, j: usize) -> Option<f64> {
        self.dot(&self.h[i], &self.h[j])
            .as_constant()
            .map(|r| crate::model::value::rat_to_f64(&r))
    }

    /// The directions of axes `i`, `j`, `k` are linearly independent (`h_i · (h_j × h_k)
    /// ≠ 0` identically).
    pub fn independent(&self, i: usize, j: usize, k: usize) -> bool {
        !self
            .dot(&self.h[i], &self.cross(&self.h[j], &self.h[k]))
            .is_zero()
    }

    /// The tool point lies on axis `i` (turning joint `i` leaves it where it is).
    pub fn tool_on(&self, i: usize) -> bool {
        is_zero(&self.cross(&sub(&self.tool, &self.p[i]), &self.h[i]))
    }

    /// Axes `i` and `j` lie in one plane (they meet or are parallel).
    pub fn coplanar(&self, i: usize, j: usize) -> bool {
        let d = sub(&self.p[j], &self.p[i]);
        self.dot(&d, &self.cross(&self.h[i], &self.h[j])).is_zero()
    }

    /// Axes `i` and `j` meet in exactly one point.
    pub fn intersect(&self, i: usize, j: usize) -> bool {
        !self.parallel(i, j) && self.coplanar(i, j)
    }

    /// Axes `i`, `j` meet and axis `k` passes through their meeting point (so `i`, `j`,
    /// `k` have a common point, whatever the joints between them do when they all turn
    /// about it).
    pub fn concurrent(&self, i: usize, j: usize, k: usize) -> bool {
        if !self.intersect(i, j) {
            return false;
        }
        // c = p_i + (N / D) h_i,  D = |h_i × h_j|²,  N = ((p_j − p_i) × h_j)·(h_i × h_j);
        // c on axis k  ⇔  ((p_i − p_k) D + N h_i) × h_k = 0  (D ≠ 0: not parallel).
        let n_ij = self.cross(&self.h[i], &self.h[j]);
        let d = self.dot(&n_ij, &n_ij);
        let n = self.dot(&self.cross(&sub(&self.p[j], &self.p[i]), &self.h[j]), &n_ij);
        let v = add(
            &self.scale(&sub(&self.p[i], &self.p[k]), &d),
            &self.scale(&self.h[i], &n),
        );
        is_zero(&self.cross(&v, &self.h[k]))
    }
}

/// World z, `[0, 0, 1]`.
pub fn unit_z() -> PVec {
    [Poly::zero(), Poly::zero(), Poly::one()]
}

fn is_zero(v: &PVec) -> bool {
    v.iter().all(Poly::is_zero)
}

fn sub(a: &PVec, b: &PVec) -> PVec {
    [a[0].sub(&b[0]), a[1].sub(&b[1]), a[2].sub(&b[2])]
}

fn add(a: &PVec, b: &PVec) -> PVec {
    [a[0].add(&b[0]), a[1].add(&b[1]), a[2].add(&b[2])]
}
