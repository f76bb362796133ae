//! The exact core: sparse multivariate polynomials over the rationals, reduced after
//! every product by the identities of their variables.
//!
//! Variables are `s_i`, `c_i` (sine and cosine of an angle), prismatic joint values
//! `q_i`, named link parameters, and the algebraic constants `√2`, `√3` (which come
//! from twists of π/4, π/3, π/6). The reductions `s_i² → 1 − c_i²` and `√k² → k`
//! make every polynomial's form unique (its normal form): two expressions are equal
//! exactly when their normal forms are, and zero exactly when the form is empty.

use std::collections::BTreeMap;
use std::fmt;
use std::hash::{Hash, Hasher};

use num_traits::{One, Signed, Zero};

use crate::algebra::fast_hash::{hash_magnitude, mix, FxHasher};
use crate::algebra::rational;
use crate::model::value::{fmt_rat, rat_to_f64, Rat};

/// A variable of the ring: an index into [`Ring`]'s table.
pub type Var = u32;

/// What a variable stands for.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum VarKind {
    /// Sine of angle number `angle` (paired with a [`VarKind::Cos`]).
    Sin(usize),
    /// Cosine of angle number `angle`.
    Cos(usize),
    /// Value of a prismatic joint (its index).
    Joint(usize),
    /// Rate `q̇_j` of joint `j` (its index): an input of the velocity-dependent outputs
    /// (`jdot_qdot`, `jacobian_dot`), constant as far as `∂/∂q` is concerned.
    Rate(usize),
    /// A named link parameter.
    Param(String),
    /// `√k` for a small integer k (2 or 3).
    Sqrt(u32),
}

/// A monomial: variables with positive exponents, sorted by variable.
pub type Mono = Vec<(Var, u32)>;

/// A polynomial in normal form: monomial → nonzero rational coefficient.
#[derive(Clone, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
pub struct Poly {
    terms: BTreeMap<Mono, Rat>,
}

/// By [`Poly::fingerprint`], a function of the terms, so consistent with equality.
impl Hash for Poly {
    fn hash<H: Hasher>(&self, state: &mut H) {
        state.write_u64(self.fingerprint());
    }
}

impl Poly {
    /// 0.
    pub fn zero() -> Self {
        Poly::default()
    }

    /// A rational constant.
    pub fn constant(r: Rat) -> Self {
        let mut p = Poly::zero();
        if !r.is_zero() {
            p.terms.insert(Vec::new(), r);
        }
        p
    }

    /// 1.
    pub fn one() -> Self {
        Self::constant(Rat::one())
    }

    /// A single variable.
    pub fn var(v: Var) -> Self {
        let mut p = Poly::zero();
        p.terms.insert(vec![(v, 1)], Rat::one());
        p
    }

    /// Whether this is exactly 0.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// The constant, if the polynomial has no variables.
    pub fn as_constant(&self) -> Option<Rat> {
        match self.terms.len() {
            0 => Some(Rat::zero()),
            1 => self.terms.get(&Vec::new()).cloned(),
            _ => None,
        }
    }

    /// Number of terms.
    pub fn len(&self) -> usize {
        self.terms.len()
    }

    /// Whether there are no terms (the zero polynomial).
    pub fn is_empty(&self) -> bool {
        self.terms.is_empty()
    }

    /// A 64-bit hash of the normal form that is odd under negation,
    /// `(−p).fingerprint() == p.fingerprint().wrapping_neg()`, so value numbering can
    /// look an opposite value up without building it: the sum over the terms of a hash
    /// of (monomial, |coefficient|), each signed like its coefficient.
    pub fn fingerprint(&self) -> u64 {
        let mut sum = 0u64;
        for (m, c) in &self.terms {
            let mut h = FxHasher::default();
            for &(v, e) in m {
                h.write_u64((u64::from(v) << 32) | u64::from(e));
            }
            h.write_u64(u64::MAX);
            hash_magnitude(c, &mut h);
            let t = mix(h.finish());
            sum = if c.is_negative() {
                sum.wrapping_sub(t)
            } else {
                sum.wrapping_add(t)
            };
        }
        sum
    }

    /// Whether `self == −other`, without building `−other`.
    pub fn is_negation_of(&self, other: &Poly) -> bool {
        self.terms.len() == other.terms.len()
            && self
                .terms
                .iter()
                .zip(&other.terms)
                .all(|((ma, ca), (mb, cb))| {
                    ma == mb
                        && ca.numer().sign() == -cb.numer().sign()
                        && ca.numer().magnitude() == cb.numer().magnitude()
                        && ca.denom() == cb.denom()
                })
    }

    /// Terms in canonical order.
    pub fn terms(&self) -> impl Iterator<Item = (&Mono, &Rat)> {
        self.terms.iter()
    }

    /// The coefficient of one monomial (`None` where it has none).
    pub fn coefficient(&self, m: &Mono) -> Option<&Rat> {
        self.terms.get(m)
    }

    /// Build from terms (merging equal monomials; monomials must already be reduced).
    pub fn from_terms(terms: impl IntoIterator<Item = (Mono, Rat)>) -> Self {
        let mut p = Poly::zero();
        for (m, c) in terms {
            p.add_term(m, c);
        }
        p
    }

    fn add_term(&mut self, m: Mono, c: Rat) {
        if c.is_zero() {
            return;
        }
        match self.terms.entry(m) {
            std::collections::btree_map::Entry::Vacant(e) => {
                e.insert(c);
            }
            std::collections::btree_map::Entry::Occupied(mut e) => {
                let sum = rational::add(e.get(), &c);
                *e.get_mut() = sum;
                if e.get().is_zero() {
                    e.remove();
                }
            }
        }
    }

    /// `self + other`.
    pub fn add(&self, other: &Poly) -> Poly {
        let mut out = self.clone();
        for (m, c) in &other.terms {
            out.add_term(m.clone(), c.clone());
        }
        out
    }

    /// `self − other`.
    pub fn sub(&self, other: &Poly) -> Poly {
        let mut out = self.clone();
        for (m, c) in &other.terms {
            out.add_term(m.clone(), -c);
        }
        out
    }

    /// `−self`.
    pub fn neg(&self) -> Poly {
        Poly {
            terms: self.terms.iter().map(|(m, c)| (m.clone(), -c)).collect(),
        }
    }

    /// `r · self`.
    pub fn scale(&self, r: &Rat) -> Poly {
        if r.is_zero() {
            return Poly::zero();
        }
        Poly {
            terms: self.terms.iter().map(|(m, c)| (m.clone(), c * r)).collect(),
        }
    }

    /// The variables that occur, sorted.
    pub fn vars(&self) -> Vec<Var> {
        let mut v: Vec<Var> = self
            .terms
            .keys()
            .flat_map(|m| m.iter().map(|&(x, _)| x))
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    }

    /// Numeric value with `x(v)` the value of variable `v`.
    pub fn eval(&self, x: &dyn Fn(Var) -> f64) -> f64 {
        self.terms
            .iter()
            .map(|(m, c)| {
                m.iter()
                    .fold(rat_to_f64(c), |acc, &(v, e)| acc * x(v).powi(e as i32))
            })
            .sum()
    }

    /// Total degree.
    pub fn degree(&self) -> u32 {
        self.terms
            .keys()
            .map(|m| m.iter().map(|&(_, e)| e).sum())
            .max()
            .unwrap_or(0)
    }

    /// The largest monomial dividing every term (the monomial content), with the gcd of
    /// numerators over the lcm of denominators as coefficient, sign of the first term.
    pub fn content(&self) -> (Mono, Rat) {
        let mut iter = self.terms.iter();
        let Some((m0, c0)) = iter.next() else {
            return (Vec::new(), Rat::one());
        };
        let mut mono = m0.clone();
        let mut num = c0.numer().abs();
        let mut den = c0.denom().clone();
        for (m, c) in iter {
            mono.retain_mut(|(v, e)| match m.iter().find(|(w, _)| w == v) {
                Some(&(_, f)) => {
                    *e = (*e).min(f);
                    true
                }
                None => false,
            });
            num = num::integer::gcd(num, c.numer().abs());
            den = num::integer::lcm(den, c.denom().clone());
        }
        let mut r = Rat::new(num, den);
        if c0.is_negative() {
            r = -r;
        }
        (mono, r)
    }

    /// Divide by a monomial and a constant that divide every term exactly.
    pub fn div_content(&self, mono: &Mono, r: &Rat) -> Poly {
        Poly {
            terms: self
                .terms
                .iter()
                .map(|(m, c)| (mono_div(m, mono), c / r))
                .collect(),
        }
    }
}

mod num {
    pub use num_integer as integer;
}

/// `a / b` for monomials where `b` divides `a`.
pub fn mono_div(a: &Mono, b: &Mono) -> Mono {
    a.iter()
        .filter_map(|&(v, e)| {
            let f = b.iter().find(|(w, _)| *w == v).map_or(0, |&(_, f)| f);
            (e > f).then_some((v, e - f))
        })
        .collect()
}

fn mono_mul(a: &Mono, b: &Mono) -> Mono {
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        match a[i].0.cmp(&b[j].0) {
            std::cmp::Ordering::Less => {
                out.push(a[i]);
                i += 1;
            }
            std::cmp::Ordering::Greater => {
                out.push(b[j]);
                j += 1;
            }
            std::cmp::Ordering::Equal => {
                out.push((a[i].0, a[i].1 + b[j].1));
                i += 1;
                j += 1;
            }
        }
    }
    out.extend_from_slice(&a[i..]);
    out.extend_from_slice(&b[j..]);
    out
}

/// A polynomial grew past the term budget.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TooLarge;

/// The variable table and its reduction rules.
#[derive(Clone, Debug, Default)]
pub struct Ring {
    kinds: Vec<VarKind>,
    names: Vec<String>,
    /// For `Sin` variables: the paired cosine.
    cos_of: Vec<Option<Var>>,
    /// For `Sqrt(k)` variables: k.
    square: Vec<Option<u32>>,
    index: BTreeMap<VarKindKey, Var>,
}

#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum VarKindKey {
    Sin(usize),
    Cos(usize),
    Joint(usize),
    Rate(usize),
    Param(String),
    Sqrt(u32),
}

impl From<&VarKind> for VarKindKey {
    fn from(k: &VarKind) -> Self {
        match k {
            VarKind::Sin(a) => VarKindKey::Sin(*a),
            VarKind::Cos(a) => VarKindKey::Cos(*a),
            VarKind::Joint(j) => VarKindKey::Joint(*j),
            VarKind::Rate(j) => VarKindKey::Rate(*j),
            VarKind::Param(n) => VarKindKey::Param(n.clone()),
            VarKind::Sqrt(k) => VarKindKey::Sqrt(*k),
        }
    }
}

impl Ring {
    /// An empty ring.
    pub fn new() -> Self {
        Self::default()
    }

    /// The variable for `kind`, created with display `name` on first use. A `Sin` and
    /// its `Cos` must both be made through [`Ring::angle`].
    fn var(&mut self, kind: VarKind, name: &str) -> Var {
        let key = VarKindKey::from(&kind);
        if let Some(&v) = self.index.get(&key) {
            return v;
        }
        let v = self.kinds.len() as Var;
        let sq = match kind {
            VarKind::Sqrt(k) => Some(k),
            _ => None,
        };
        self.kinds.push(kind);
        self.names.push(name.to_string());
        self.cos_of.push(None);
        self.square.push(sq);
        self.index.insert(key, v);
        v
    }

    /// The (sin, cos) pair of angle number `angle`, named `s<suffix>`, `c<suffix>`.
    pub fn angle(&mut self, angle: usize, suffix: &str) -> (Var, Var) {
        let s = self.var(VarKind::Sin(angle), &format!("s{suffix}"));
        let c = self.var(VarKind::Cos(angle), &format!("c{suffix}"));
        self.cos_of[s as usize] = Some(c);
        (s, c)
    }

    /// A prismatic joint's value.
    pub fn joint(&mut self, j: usize, name: &str) -> Var {
        self.var(VarKind::Joint(j), name)
    }

    /// The rate `q̇_j` of joint `j`.
    pub fn rate(&mut self, j: usize, name: &str) -> Var {
        self.var(VarKind::Rate(j), name)
    }

    /// A named link parameter.
    pub fn param(&mut self, name: &str) -> Var {
        self.var(VarKind::Param(name.to_string()), name)
    }

    /// `√k` (k = 2 or 3).
    pub fn sqrt(&mut self, k: u32) -> Var {
        self.var(VarKind::Sqrt(k), &format!("sqrt{k}"))
    }

    /// What a variable stands for.
    pub fn kind(&self, v: Var) -> &VarKind {
        &self.kinds[v as usize]
    }

    /// A variable's display name.
    pub fn name(&self, v: Var) -> &str {
        &self.names[v as usize]
    }

    /// Number of variables.
    pub fn len(&self) -> usize {
        self.kinds.len()
    }

    /// Whether the ring has no variables yet.
    pub fn is_empty(&self) -> bool {
        self.kinds.is_empty()
    }

    /// Reduce a monomial (exponents of `s`, `√k` at most 1 after this).
    fn reduce_mono(&self, m: Mono, c: Rat, out: &mut Poly) {
        // Find the first variable with a rule and exponent ≥ 2.
        for (i, &(v, e)) in m.iter().enumerate() {
            if e < 2 {
                continue;
            }
            if let Some(k) = self.square[v as usize] {
                let mut m2 = m.clone();
                let half = e / 2;
                if e % 2 == 0 {
                    m2.remove(i);
                } else {
                    m2[i].1 = 1;
                }
                let factor = Rat::from_integer(num_bigint::BigInt::from(k).pow(half));
                return self.reduce_mono(m2, rational::mul(&c, &factor), out);
            }
            if let Some(cv) = self.cos_of[v as usize] {
                // s^e = s^(e-2) (1 − c²)
                let mut base = m.clone();
                if e == 2 {
                    base.remove(i);
                } else {
                    base[i].1 = e - 2;
                }
                let with_c2 = mono_mul(&base, &vec![(cv, 2)]);
                self.reduce_mono(base, c.clone(), out);
                self.reduce_mono(with_c2, -c, out);
                return;
            }
        }
        out.add_term(m, c);
    }

    /// `a · b`, reduced; `Err` when the result would exceed `max_terms`.
    pub fn mul_bounded(&self, a: &Poly, b: &Poly, max_terms: usize) -> Result<Poly, TooLarge> {
        if a.terms.len().saturating_mul(b.terms.len()) > max_terms.saturating_mul(8) {
            return Err(TooLarge);
        }
        let mut out = Poly::zero();
        for (ma, ca) in &a.terms {
            for (mb, cb) in &b.terms {
                self.reduce_mono(mono_mul(ma, mb), rational::mul(ca, cb), &mut out);
            }
            if out.terms.len() > max_terms {
                return Err(TooLarge);
            }
        }
        Ok(out)
    }

    /// `a · b`, reduced.
    pub fn mul(&self, a: &Poly, b: &Poly) -> Poly {
        self.mul_bounded(a, b, usize::MAX / 16)
            .expect("unbounded product cannot exceed its bound")
    }

    /// The derivative `dp/dx` of `p` along a variable `x` of which every ring variable
    /// `v` is a function with derivative `dv(v)` (`None`: constant), in normal form.
    ///
    /// The product rule term by term: `d(c·Π vᵉ) = Σ_v c·e·vᵉ⁻¹·dv·Π_(w≠v) wᶠ`, each
    /// product reduced. For `x = q_j`: `ds = sign·c` and `dc = −sign·s` for the angle
    /// `sign·q_j + offset`, `dq_j = 1` for a prismatic joint, everything else constant —
    /// which keeps `d(s² + c²) = 2sc − 2cs = 0`, so the derivative of a normal form is the
    /// derivative of the function it stands for.
    pub fn derivative(&self, p: &Poly, dv: &dyn Fn(Var) -> Option<Poly>) -> Poly {
        let mut out = Poly::zero();
        for (m, c) in &p.terms {
            for (i, &(v, e)) in m.iter().enumerate() {
                let Some(d) = dv(v) else { continue };
                let mut rest = m.clone();
                if e == 1 {
                    rest.remove(i);
                } else {
                    rest[i].1 = e - 1;
                }
                let k = c * Rat::from_integer(e.into());
                let term = self.mul(&Poly::from_terms([(rest, k)]), &d);
                out = out.add(&term);
            }
        }
        out
    }

    /// Display a polynomial in the ring's variable names (for tests and messages).
    pub fn display<'a>(&'a self, p: &'a Poly) -> impl fmt::Display + 'a {
        PolyDisplay { ring: self, p }
    }
}

struct PolyDisplay<'a> {
    ring: &'a Ring,
    p: &'a Poly,
}

impl fmt::Display for PolyDisplay<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.p.is_zero() {
            return f.write_str("0");
        }
        for (i, (m, c)) in self.p.terms.iter().enumerate() {
            let neg = c.is_negative();
            let a = c.abs();
            match (i, neg) {
                (0, true) => f.write_str("-")?,
                (0, false) => {}
                (_, true) => f.write_str(" - ")?,
                (_, false) => f.write_str(" + ")?,
            }
            let mut parts: Vec<String> = Vec::new();
            if !a.is_one() || m.is_empty() {
                parts.push(fmt_rat(&a));
            }
            for &(v, e) in m {
                let n = self.ring.name(v);
                parts.push(if e == 1 {
                    n.to_string()
                } else {
                    format!("{n}^{e}")
                });
            }
            f.write_str(&parts.join("*"))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pythagoras_is_zero_in_normal_form() {
        let mut r = Ring::new();
        let (s, c) = r.angle(0, "1");
        let s2 = r.mul(&Poly::var(s), &Poly::var(s));
        let c2 = r.mul(&Poly::var(c), &Poly::var(c));
        assert!(s2.add(&c2).sub(&Poly::one()).is_zero());
    }

    #[test]
    fn angle_sum_identity() {
        // sin(a+b)² + cos(a+b)² = 1 with sin/cos of the sum written out.
        let mut r = Ring::new();
        let (s1, c1) = r.angle(0, "1");
        let (s2, c2) = r.angle(1, "2");
        let v = |x| Poly::var(x);
        let s12 = r.mul(&v(s1), &v(c2)).add(&r.mul(&v(c1), &v(s2)));
        let c12 = r.mul(&v(c1), &v(c2)).sub(&r.mul(&v(s1), &v(s2)));
        let sum = r.mul(&s12, &s12).add(&r.mul(&c12, &c12));
        assert_eq!(sum, Poly::one());
    }

    #[test]
    fn square_roots_reduce() {
        let mut r = Ring::new();
        let q3 = r.sqrt(3);
        let p = r.mul(&Poly::var(q3), &Poly::var(q3));
        assert_eq!(p, Poly::constant(Rat::from_integer(3.into())));
    }

    #[test]
    fn content_and_display() {
        let mut r = Ring::new();
        let (s, c) = r.angle(0, "2");
        let a = r.param("a");
        let p = Poly::from_terms([
            (vec![(s, 1), (a, 1)], Rat::new(2.into(), 1.into())),
            (vec![(c, 1), (a, 2)], Rat::new(4.into(), 1.into())),
        ]);
        let (m, k) = p.content();
        assert_eq!(m, vec![(a, 1)]);
        assert_eq!(k, Rat::new(2.into(), 1.into()));
        assert_eq!(r.display(&p.div_content(&m, &k)).to_string(), "s2 + 2*c2*a");
    }

    #[test]
    fn derivative_is_exact_on_the_circle() {
        let mut r = Ring::new();
        let (s, c) = r.angle(0, "1");
        let a = r.param("a");
        // d/dq of s·c·a = (c² − s²)·a = (2c² − 1)·a, and of s² + c² (= 1) is 0.
        let d = |v: Var| {
            if v == s {
                Some(Poly::var(c))
            } else if v == c {
                Some(Poly::var(s).neg())
            } else {
                None
            }
        };
        let p = r.mul(&r.mul(&Poly::var(s), &Poly::var(c)), &Poly::var(a));
        let dp = r.derivative(&p, &d);
        assert_eq!(r.display(&dp).to_string(), "2*c1^2*a - a");
        let one = r
            .mul(&Poly::var(s), &Poly::var(s))
            .add(&r.mul(&Poly::var(c), &Poly::var(c)));
        assert!(r.derivative(&one, &d).is_zero());
        // A variable with a polynomial derivative, raised to a power: d(c³) = −3c²s.
        let c3 = r.mul(&r.mul(&Poly::var(c), &Poly::var(c)), &Poly::var(c));
        assert_eq!(r.display(&r.derivative(&c3, &d)).to_string(), "-3*s1*c1^2");
    }

    #[test]
    fn bounded_product_reports_overflow() {
        let mut r = Ring::new();
        let vars: Vec<Poly> = (0..6)
            .map(|i| Poly::var(r.param(&format!("p{i}"))))
            .collect();
        let sum = vars.iter().fold(Poly::zero(), |acc, v| acc.add(v));
        let sq = r.mul(&sum, &sum);
        assert_eq!(sq.len(), 21);
        assert!(r.mul_bounded(&sq, &sq, 50).is_err());
    }
}
