//! The determinant as users read it: each factor of [`structural::determinant`] written
//! with sines and cosines of angle sums, given a node of its own, and the product checked
//! equal to the determinant's normal form before it is used.

use num_traits::{One, Signed};

use crate::algebra::graph::Id;
use crate::algebra::poly::{Poly, VarKind};
use crate::algebra::trig::{self, TrigTerm};
use crate::chain::Chain;
use crate::kinematics::det::structural::{self, DetError, Factored};
use crate::kinematics::model::Model;
use crate::model::value::{fmt_rat, Rat};

/// Largest determinant (terms summed over its factors) emitted in closed form.
const MAX_FACTOR_TERMS: usize = 64;

/// The closed-form Jacobian determinant and the singular factors it implies.
#[derive(Clone, Debug)]
pub struct DetModel {
    /// Rows of the square Jacobian (indices into `[vx vy vz ωx ωy ωz]`).
    pub rows: Vec<usize>,
    /// `constant · Π factors`.
    pub factored: Factored,
    /// Constant `√k` factors taken out of `factored` (ring variables; the determinant
    /// is `constant · Π surds · Π factors`).
    pub surds: Vec<crate::algebra::poly::Var>,
    /// Distinct nonconstant factors with multiplicity, their node, text and LaTeX.
    pub factors: Vec<DetFactor>,
    /// The whole determinant.
    pub node: Id,
    /// Plain text: `a2*a3*sin(q3)*sin(q5)*(…)`.
    pub text: String,
    /// LaTeX.
    pub latex: String,
}

/// One factor of a determinant.
#[derive(Clone, Debug)]
pub struct DetFactor {
    /// Normal form.
    pub poly: Poly,
    /// Multiplicity.
    pub power: u32,
    /// Code.
    pub node: Id,
    /// Text (`sin(q3)`, `a2*cos(q2) + a3*cos(q2+q3)`).
    pub text: String,
    /// LaTeX.
    pub latex: String,
    /// Joints (1-based) it depends on.
    pub joints: Vec<usize>,
}

/// The determinant of the square (task) Jacobian of `chain`, if there is one and it is
/// within budget (terms, and the deadline the model was built with); `Err` with the
/// reason otherwise. Its nodes are added to the model's graph.
pub fn determinant(chain: &Chain, model: &mut Model) -> Result<DetModel, String> {
    let rows = structural::square_rows(chain).ok_or("the Jacobian is not square")?;
    let deadline = model.sym.graph.deadline;
    let late = || {
        format!(
            "{} ran out before the closed-form determinant was done",
            deadline.describe()
        )
    };
    let mut factored =
        structural::determinant(chain, &mut model.sym, &rows).map_err(|e| match e {
            DetError::Deadline => late(),
            e => format!("closed-form determinant over budget ({e:?})"),
        })?;
    let surds = take_surds(&mut factored, &model.sym.graph.ring);
    let size: usize = factored.factors.iter().map(|f| f.len()).sum();
    if size > MAX_FACTOR_TERMS {
        return Err(format!(
            "the closed form has {size} terms in its factors, more than a numeric LU costs"
        ));
    }
    let mut factors: Vec<DetFactor> = structural::powers(&factored.clone())
        .into_iter()
        .map(|(poly, power)| factor(model, &mut factored, poly, power))
        .collect();
    // Parameters first, then single sines and cosines, then the larger factors.
    factors.sort_by_key(|f| (!f.joints.is_empty(), f.poly.len(), f.joints.clone()));
    let g = &mut model.sym.graph;
    let mut node = g.num(factored.constant.clone());
    for &v in &surds {
        let l = g.leaf(v);
        node = g.mul(node, l);
    }
    for f in &factors {
        for _ in 0..f.power {
            node = g.mul(node, f.node);
        }
    }
    // Past the deadline the product's nodes may have no normal form to check.
    if g.past_deadline() {
        return Err(late());
    }
    // Check: the emitted product equals the determinant's normal form.
    if let (Some(nf), Ok(expanded)) = (g.nf(node), factored.expand(&g.ring, g.max_terms)) {
        let expanded = surds
            .iter()
            .fold(expanded, |p, &v| g.ring.mul(&p, &Poly::var(v)));
        if *nf != expanded {
            return Err("internal check failed: simplified determinant differs".into());
        }
    }
    let surd_text: Vec<u32> = surds
        .iter()
        .filter_map(|&v| match g.ring.kind(v) {
            VarKind::Sqrt(k) => Some(*k),
            _ => None,
        })
        .collect();
    let (text, latex) = det_text(&factored.constant, &surd_text, &factors);
    Ok(DetModel {
        rows,
        factored,
        surds,
        factors,
        node,
        text,
        latex,
    })
}

/// One factor read back as trigonometry, with the sign that makes most terms positive
/// (moved into `factored`'s constant), its node, text and joints.
fn factor(model: &mut Model, factored: &mut Factored, poly: Poly, power: u32) -> DetFactor {
    let sym = &mut model.sym;
    let mut poly = poly;
    let mut terms = trig::rewrite(&sym.graph.ring, &sym.angles, &poly);
    // Sign: most terms positive, the first one positive on a tie.
    if let Some(t) = &mut terms {
        let neg = t.iter().filter(|x| x.coef.is_negative()).count();
        if 2 * neg > t.len() || (2 * neg == t.len() && t[0].coef.is_negative()) {
            for x in t.iter_mut() {
                x.coef = -x.coef.clone();
            }
            poly = poly.neg();
            if power % 2 == 1 {
                factored.constant = -factored.constant.clone();
            }
            for f in factored.factors.iter_mut() {
                if *f == poly.neg() {
                    *f = poly.clone();
                }
            }
        }
    }
    let ring = &sym.graph.ring;
    let (text, latex) = match &terms {
        Some(t) => (
            trig::text(ring, &sym.angles, t),
            trig::latex(ring, &sym.angles, t),
        ),
        None => {
            let s = ring.display(&poly).to_string();
            (s.clone(), s)
        }
    };
    let node = match &terms {
        Some(terms) => trig_node(model, terms),
        None => model.sym.graph.from_poly(&poly),
    };
    let joints = joints_of(model, &poly);
    DetFactor {
        poly,
        power,
        node,
        text,
        latex,
        joints,
    }
}

/// `Σ coef · rest · Π sin/cos(angle sum)` as code.
pub(crate) fn trig_node(model: &mut Model, terms: &[TrigTerm]) -> Id {
    let sym = &mut model.sym;
    let g = &mut sym.graph;
    let mut acc = Vec::new();
    for t in terms {
        let mut x = g.num(t.coef.clone());
        for &(v, e) in &t.rest {
            let l = g.leaf(v);
            for _ in 0..e {
                x = g.mul(x, l);
            }
        }
        for f in &t.trig {
            let nf = trig::sum_nf(&g.ring, &sym.angles, f);
            let y = g.from_poly(&nf);
            x = g.mul(x, y);
        }
        acc.push(x);
    }
    g.sum(&acc)
}

/// The joints (1-based) a polynomial depends on.
fn joints_of(model: &Model, poly: &Poly) -> Vec<usize> {
    let sym = &model.sym;
    let mut joints: Vec<usize> = poly
        .vars()
        .into_iter()
        .filter_map(|v| match sym.graph.ring.kind(v) {
            VarKind::Sin(a) | VarKind::Cos(a) => match &sym.angles[*a].source {
                crate::algebra::angles::AngleSource::Joint { joint, .. } => Some(joint + 1),
                _ => None,
            },
            VarKind::Joint(j) => Some(j + 1),
            _ => None,
        })
        .collect();
    joints.dedup();
    joints
}

/// `√k` factors of the determinant (from twists of π/3, π/4, …) are constants, never
/// zero: not singular factors. Pairs of equal ones become `k` in the constant; the rest
/// (one per `k`) are taken out of `factored` and returned as their ring variables.
fn take_surds(
    factored: &mut Factored,
    ring: &crate::algebra::poly::Ring,
) -> Vec<crate::algebra::poly::Var> {
    let mut surds: Vec<crate::algebra::poly::Var> = Vec::new();
    let mut rest = Vec::new();
    for f in factored.factors.drain(..) {
        let var = f
            .vars()
            .first()
            .copied()
            .filter(|_| f.len() == 1 && f.degree() == 1);
        let sqrt = var.filter(|&v| matches!(ring.kind(v), VarKind::Sqrt(_)));
        match sqrt {
            Some(v) if f == Poly::var(v) => match surds.iter().position(|&w| w == v) {
                Some(i) => {
                    surds.remove(i);
                    if let VarKind::Sqrt(k) = ring.kind(v) {
                        factored.constant *= Rat::from_integer((*k).into());
                    }
                }
                None => surds.push(v),
            },
            _ => rest.push(f),
        }
    }
    factored.factors = rest;
    surds.sort_unstable();
    surds
}

fn det_text(constant: &Rat, surds: &[u32], factors: &[DetFactor]) -> (String, String) {
    let mut text: Vec<String> = Vec::new();
    let mut latex: Vec<String> = Vec::new();
    let neg = constant.is_negative();
    let k = constant.abs();
    if !k.is_one() || (factors.is_empty() && surds.is_empty()) {
        text.push(fmt_rat(&k));
        latex.push(fmt_rat(&k));
    }
    for s in surds {
        text.push(format!("sqrt({s})"));
        latex.push(format!("\\sqrt{{{s}}}"));
    }
    for f in factors {
        let single = f.poly.len() == 1;
        let (t, l) = if single {
            (f.text.clone(), f.latex.clone())
        } else {
            (
                format!("({})", f.text),
                format!("\\left({}\\right)", f.latex),
            )
        };
        let (t, l) = if f.power > 1 {
            (format!("{t}^{}", f.power), format!("{l}^{{{}}}", f.power))
        } else {
            (t, l)
        };
        text.push(t);
        latex.push(l);
    }
    let sign = if neg { "-" } else { "" };
    (
        format!("{sign}{}", text.join("*")),
        format!("{sign}{}", latex.join(" \\, ")),
    )
}
