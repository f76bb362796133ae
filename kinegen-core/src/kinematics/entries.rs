//! A chain's entries as graph nodes: lengths (rational constants plus parameters), joint
//! angles and constant angles.
//!
//! Angles whose value is a multiple of π/12 (π/6, π/4 among them) fold to exact
//! constants in ℚ[√2, √3]
//! (a twist of π/2 has cosine exactly 0, and whole terms vanish); a joint offset that is
//! a multiple of π/2 folds into the joint's own sine and cosine; any other constant
//! angle, or one that names a parameter, becomes a sine/cosine pair of its own.

use num_traits::{One, Signed, Zero};

use crate::algebra::angles::{AngleDef, AngleSource};
use crate::algebra::graph::{Graph, Id};
use crate::algebra::poly::Var;
use crate::model::value::{Rat, Value};

/// The graph being built and the variables its leaves stand for.
pub struct Entries {
    /// The straight-line code so far.
    pub graph: Graph,
    /// Sine/cosine pairs, in order of first use.
    pub angles: Vec<AngleDef>,
    /// Ring variables of prismatic joints: `(joint, var)`.
    pub joint_vars: Vec<(usize, Var)>,
    /// Ring variables of named parameters: `(name, var)`.
    pub param_vars: Vec<(String, Var)>,
    /// Constant angles that did not fold, so far (names `s_k1`, `c_k1`, …).
    consts: usize,
}

impl Entries {
    /// No entries yet, on `graph`.
    pub fn new(graph: Graph) -> Self {
        Entries {
            graph,
            angles: Vec::new(),
            joint_vars: Vec::new(),
            param_vars: Vec::new(),
            consts: 0,
        }
    }

    /// The variable of prismatic joint `i` (0-based), `q{i+1}`.
    pub fn joint_var(&mut self, i: usize) -> Id {
        let v = self.graph.ring.joint(i, &format!("q{}", i + 1));
        self.joint_vars.push((i, v));
        self.graph.leaf(v)
    }

    fn param(&mut self, name: &str) -> Id {
        let v = self.graph.ring.param(name);
        if !self.param_vars.iter().any(|(n, _)| n == name) {
            self.param_vars.push((name.to_string(), v));
        }
        self.graph.leaf(v)
    }

    /// A length entry: rational constant plus parameters.
    pub fn length(&mut self, v: &Value) -> Id {
        let mut acc = self.graph.num(v.konst.clone());
        for (name, c) in &v.params {
            let p = self.param(name);
            let k = self.graph.num(c.clone());
            let term = self.graph.mul(k, p);
            acc = self.graph.add(acc, term);
        }
        acc
    }

    fn new_angle(&mut self, source: AngleSource, suffix: String) -> (Id, Id) {
        let n = self.angles.len();
        let vars = self.graph.ring.angle(n, &suffix);
        self.angles.push(AngleDef {
            source,
            vars,
            suffix,
        });
        (self.graph.leaf(vars.0), self.graph.leaf(vars.1))
    }

    /// θ = sign·q_i + value: a multiple of π/2 folds into the sine and cosine of q_i
    /// exactly; any other value is added at run time.
    pub fn joint_angle(&mut self, i: usize, sign: i8, value: &Value) -> (Id, Id) {
        let quarter = value.konst.is_zero() && value.params.is_empty() && {
            let k = &value.pi * Rat::from_integer(2.into());
            k.is_integer()
        };
        let offset = if quarter {
            Value::zero()
        } else {
            value.clone()
        };
        // Unfolded, the pair is sin/cos(sign·q + offset) itself.
        let (s, c) = self.new_angle(
            AngleSource::Joint {
                joint: i,
                sign: if quarter { 1 } else { sign },
                offset,
            },
            format!("{}", i + 1),
        );
        if !quarter {
            return (s, c);
        }
        let g = &mut self.graph;
        // sin(−q) = −sin q, cos(−q) = cos q.
        let (s, c) = if sign < 0 { (g.neg(s), c) } else { (s, c) };
        // sin/cos(θ + kπ/2)
        let k = (&value.pi * Rat::from_integer(2.into())).to_integer();
        let k = ((k % 4) + 4) % 4;
        let k: u32 = num_traits::ToPrimitive::to_u32(&k).unwrap_or(0);
        match k {
            0 => (s, c),
            1 => (c, g.neg(s)),
            2 => (g.neg(s), g.neg(c)),
            _ => (g.neg(c), s),
        }
    }

    /// A constant angle: exact for multiples of π/12 (so of π/6 and π/4), else its own pair.
    pub fn const_angle(&mut self, value: &Value) -> (Id, Id) {
        if value.konst.is_zero() && value.params.is_empty() {
            if let Some((s, c)) = self.exact_sin_cos(&value.pi) {
                return (s, c);
            }
        }
        self.consts += 1;
        let suffix = format!("_k{}", self.consts);
        self.new_angle(AngleSource::Constant(value.clone()), suffix)
    }

    /// sin and cos of `t·π` when t is a multiple of 1/4 or 1/6 (so also of 1/12): exact
    /// values in ℚ[√2, √3], e.g. sin(π/12) = (√6 − √2)/4.
    fn exact_sin_cos(&mut self, t: &Rat) -> Option<(Id, Id)> {
        let two = Rat::from_integer(2.into());
        // t mod 2 in [0, 2)
        let mut t = t - (t / &two).floor() * &two;
        let mut sign_s = Rat::one();
        let mut sign_c = Rat::one();
        if t >= Rat::one() {
            t -= Rat::one();
            sign_s = -sign_s;
            sign_c = -sign_c;
        }
        let half = Rat::new(1.into(), 2.into());
        if t > half {
            t = Rat::one() - t;
            sign_c = -sign_c;
        }
        let twelfths = &t * Rat::from_integer(12.into());
        if !twelfths.is_integer() {
            return None;
        }
        let k = num_traits::ToPrimitive::to_usize(&twelfths.to_integer())?;
        let r = |n: i64| Rat::new(n.into(), 4.into());
        // sin(kπ/12) for k = 0..=6 as quarters of √1, √2, √3, √6; cos(kπ/12) = sin((6−k)π/12).
        let sines: [[Rat; 4]; 7] = [
            [r(0), r(0), r(0), r(0)],
            [r(0), r(-1), r(0), r(1)],
            [r(2), r(0), r(0), r(0)],
            [r(0), r(2), r(0), r(0)],
            [r(0), r(0), r(2), r(0)],
            [r(0), r(1), r(0), r(1)],
            [r(4), r(0), r(0), r(0)],
        ];
        let s = self.surds(&sines[k], &sign_s);
        let c = self.surds(&sines[6 - k], &sign_c);
        Some((s, c))
    }

    /// `sign · (k1 + k2·√2 + k3·√3 + k6·√2·√3)` for `k = [k1, k2, k3, k6]`.
    fn surds(&mut self, k: &[Rat; 4], sign: &Rat) -> Id {
        let mut terms = Vec::new();
        for (coef, roots) in k.iter().zip([&[][..], &[2], &[3], &[2, 3]]) {
            if coef.is_zero() {
                continue;
            }
            let c = coef * sign;
            let mut x = self.graph.num(c.abs());
            for &n in roots {
                let v = self.graph.ring.sqrt(n);
                let l = self.graph.leaf(v);
                x = self.graph.mul(x, l);
            }
            terms.push(if c.is_negative() {
                self.graph.neg(x)
            } else {
                x
            });
        }
        match terms.as_slice() {
            [] => self.graph.int(0),
            [a] => *a,
            // sin(π/12) = (√6 − √2)/4: the difference, not a sum with a negation.
            [a, b] => self.graph.add(*a, *b),
            _ => self.graph.sum(&terms),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_twists() {
        let mut b = Entries::new(Graph::default());
        for (t, s, c) in [
            (Rat::new(1.into(), 2.into()), 1.0, 0.0),
            (Rat::new((-1).into(), 2.into()), -1.0, 0.0),
            (Rat::new(1.into(), 3.into()), 3f64.sqrt() / 2.0, 0.5),
            (
                Rat::new(3.into(), 4.into()),
                0.5f64.sqrt(),
                -(0.5f64.sqrt()),
            ),
            (Rat::new(7.into(), 6.into()), -0.5, -(3f64.sqrt() / 2.0)),
            (Rat::one(), 0.0, -1.0),
        ] {
            let (si, ci) = b.exact_sin_cos(&t).unwrap();
            let ring = b.graph.ring.clone();
            let val = |v: Var| match ring.kind(v) {
                crate::algebra::poly::VarKind::Sqrt(k) => (*k as f64).sqrt(),
                _ => f64::NAN,
            };
            assert!((b.graph.eval(si, &val) - s).abs() < 1e-15, "sin {t}");
            assert!((b.graph.eval(ci, &val) - c).abs() < 1e-15, "cos {t}");
        }
        assert!(b.exact_sin_cos(&Rat::new(1.into(), 5.into())).is_none());
        assert!(b.exact_sin_cos(&Rat::new(1.into(), 24.into())).is_none());
    }

    /// Every multiple of π/12 over two turns, against `f64::sin_cos`, and its normal form
    /// squares to one exactly (s² + c² = 1 in ℚ[√2, √3]).
    #[test]
    fn twelfths_of_pi_are_exact() {
        let mut b = Entries::new(Graph::default());
        for k in -24..=24 {
            let t = Rat::new(k.into(), 12.into());
            let (si, ci) = b.exact_sin_cos(&t).unwrap();
            let ring = b.graph.ring.clone();
            let val = |v: Var| match ring.kind(v) {
                crate::algebra::poly::VarKind::Sqrt(k) => (*k as f64).sqrt(),
                _ => f64::NAN,
            };
            let (s, c) = (f64::from(k) * std::f64::consts::PI / 12.0).sin_cos();
            assert!((b.graph.eval(si, &val) - s).abs() < 1e-15, "sin {k}π/12");
            assert!((b.graph.eval(ci, &val) - c).abs() < 1e-15, "cos {k}π/12");
            let (ss, cc) = (b.graph.mul(si, si), b.graph.mul(ci, ci));
            let one = b.graph.add(ss, cc);
            assert_eq!(b.graph.as_num(one), Some(&Rat::one()), "s² + c² at {k}π/12");
        }
    }
}
