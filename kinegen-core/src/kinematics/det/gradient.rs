//! The gradient of the closed-form determinant, by exact differentiation of its factors.
//!
//! `det J = C · Π_k f_k^(p_k)` (`C` rational times constant `√k`s) with every factor a polynomial in `s_i`, `c_i`, prismatic
//! `q_i` and parameters ([`super::closed_form`]). Along `q_j`: `∂s_i/∂q_j = σ c_i`,
//! `∂c_i/∂q_j = −σ s_i` for the angle `σ q_j + offset` of joint `j` (`σ = ±1`, a flipped
//! joint has −1), `∂q_j/∂q_j = 1` for a prismatic joint, and everything else is constant
//! ([`crate::algebra::poly::Ring::derivative`]). The product rule over the factors,
//!
//! ```text
//! ∂det/∂q_j = C · Σ_k p_k · f_k^(p_k − 1) · ∂f_k/∂q_j · Π_(l≠k) f_l^(p_l),
//! ```
//!
//! keeps the result factored: a controller reads `∂f_k/∂q_j` (the singular factors'
//! gradients) to push away from one singularity, or `∂det/∂q_j` for all of them, and
//! nothing divides by a factor that may be zero. Each gradient entry is checked against
//! the derivative of the determinant's expanded normal form before it is used.

use crate::algebra::angles::AngleSource;
use crate::algebra::graph::Id;
use crate::algebra::poly::{Poly, Var, VarKind};
use crate::algebra::trig;
use crate::kinematics::det::closed_form::{trig_node, DetModel};
use crate::kinematics::model::Model;

/// `∂det/∂q` and `∂f_k/∂q` as nodes, with the factors' derivatives as text.
#[derive(Clone, Debug)]
pub struct DetGradient {
    /// `∂det/∂q_j`, j = 1..N.
    pub gradient: Vec<Id>,
    /// `factors[k][j] = ∂f_k/∂q_j` for the singular factors in the order of
    /// [`DetModel::factors`].
    pub factors: Vec<Vec<Id>>,
    /// `(text, latex)` of each `∂f_k/∂q_j` (`"0"` where it does not depend on `q_j`).
    pub texts: Vec<Vec<(String, String)>>,
}

/// The derivative of every ring variable along joint `j` of `model` (`None`: constant).
fn along_joint(model: &Model, j: usize) -> impl Fn(Var) -> Option<Poly> + '_ {
    let sym = &model.sym;
    move |v| {
        let driven = |a: usize| match &sym.angles[a].source {
            AngleSource::Joint { joint, sign, .. } if *joint == j => Some(i64::from(*sign)),
            _ => None,
        };
        let signed = |sign: i64, w: Var| {
            let p = Poly::var(w);
            if sign < 0 {
                p.neg()
            } else {
                p
            }
        };
        match sym.graph.ring.kind(v) {
            VarKind::Sin(a) => driven(*a).map(|s| signed(s, sym.angles[*a].vars.1)),
            VarKind::Cos(a) => driven(*a).map(|s| signed(-s, sym.angles[*a].vars.0)),
            VarKind::Joint(k) if *k == j => Some(Poly::one()),
            _ => None,
        }
    }
}

/// The gradient of `det` (built into `model`'s graph), or `Err` when a check fails.
pub fn det_gradient(model: &mut Model, det: &DetModel, dof: usize) -> Result<DetGradient, String> {
    let mut factors = Vec::new();
    let mut texts = Vec::new();
    for f in &det.factors {
        let mut nodes = Vec::new();
        let mut text = Vec::new();
        for j in 0..dof {
            let d = model
                .sym
                .graph
                .ring
                .derivative(&f.poly, &along_joint(model, j));
            let (node, t) = poly_node(model, &d);
            nodes.push(node);
            text.push(t);
        }
        factors.push(nodes);
        texts.push(text);
    }
    // The cofactor of each factor: C · p_k · f_k^(p_k − 1) · Π_(l≠k) f_l^(p_l).
    let g = &mut model.sym.graph;
    let k = det.factors.len();
    let power = |g: &mut crate::algebra::graph::Graph, node: Id, p: u32| {
        let mut x = g.int(1);
        for _ in 0..p {
            x = g.mul(x, node);
        }
        x
    };
    let full: Vec<Id> = det
        .factors
        .iter()
        .map(|f| power(g, f.node, f.power))
        .collect();
    // C · Π √k: the constant part.
    let mut constant = g.num(det.factored.constant.clone());
    for &v in &det.surds {
        let l = g.leaf(v);
        constant = g.mul(constant, l);
    }
    let mut prefix = vec![constant];
    for &x in &full {
        let last = *prefix.last().expect("nonempty");
        prefix.push(g.mul(last, x));
    }
    let mut suffix = vec![g.int(1); k + 1];
    for i in (0..k).rev() {
        suffix[i] = g.mul(full[i], suffix[i + 1]);
    }
    let cofactor: Vec<Id> = (0..k)
        .map(|i| {
            let f = &det.factors[i];
            let lower = power(g, f.node, f.power - 1);
            let p = g.int(i64::from(f.power));
            let a = g.mul(prefix[i], suffix[i + 1]);
            let b = g.mul(p, lower);
            g.mul(a, b)
        })
        .collect();
    let gradient: Vec<Id> = (0..dof)
        .map(|j| {
            let terms: Vec<Id> = (0..k).map(|i| g.mul(cofactor[i], factors[i][j])).collect();
            g.sum(&terms)
        })
        .collect();
    check(model, det, &gradient)?;
    Ok(DetGradient {
        gradient,
        factors,
        texts,
    })
}

/// A polynomial as code and as text: sines and cosines of angle sums where the rewrite
/// holds, the plain normal form otherwise.
fn poly_node(model: &mut Model, p: &Poly) -> (Id, (String, String)) {
    if p.is_zero() {
        return (model.sym.graph.int(0), ("0".into(), "0".into()));
    }
    let sym = &model.sym;
    match trig::rewrite(&sym.graph.ring, &sym.angles, p) {
        Some(terms) => {
            let text = trig::text(&sym.graph.ring, &sym.angles, &terms);
            let latex = trig::latex(&sym.graph.ring, &sym.angles, &terms);
            (trig_node(model, &terms), (text, latex))
        }
        None => {
            let s = sym.graph.ring.display(p).to_string();
            (model.sym.graph.from_poly(p), (s.clone(), s))
        }
    }
}

/// Each gradient entry equals the derivative of the determinant's own normal form (the
/// emitted `jacobian_det` node's, or else the expanded factored form's; skipped past the
/// term budget, where the factors' gradients were formed one by one).
fn check(model: &Model, det: &DetModel, gradient: &[Id]) -> Result<(), String> {
    let g = &model.sym.graph;
    let expanded = match g.nf(det.node) {
        Some(nf) => nf.clone(),
        None => match det.factored.expand(&g.ring, g.max_terms) {
            Ok(p) => det
                .surds
                .iter()
                .fold(p, |p, &v| g.ring.mul(&p, &Poly::var(v))),
            Err(_) => return Ok(()),
        },
    };
    for (j, &id) in gradient.iter().enumerate() {
        let want = g.ring.derivative(&expanded, &along_joint(model, j));
        if g.nf(id).is_some_and(|nf| *nf != want) {
            return Err(format!(
                "internal check failed: ∂det/∂q{} differs from the derivative of det J",
                j + 1
            ));
        }
    }
    Ok(())
}
