//! A chain's entries as graph nodes: lengths (rational constants plus parameters), joint
//! angles and constant angles.
//!
//! Angles whose value is a multiple of π/6 or π/4 fold to exact constants in ℚ[√2, √3]
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

    /// A constant angle: exact for multiples of π/6 and π/4, else its own pair.
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

    /// sin and cos of `t·π` when t is a multiple of 1/4 or 1/6.
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
        let r = |n: i64, d: i64| Rat::new(n.into(), d.into());
        // (rational part, √k part) of sin and cos for t in [0, 1/2].
        type Surd = (Rat, u32);
        let table: [(Rat, Surd, Surd); 5] = [
            (r(0, 1), (r(0, 1), 1), (r(1, 1), 1)),
            (r(1, 6), (r(1, 2), 1), (r(1, 2), 3)),
            (r(1, 4), (r(1, 2), 2), (r(1, 2), 2)),
            (r(1, 3), (r(1, 2), 3), (r(1, 2), 1)),
            (r(1, 2), (r(1, 1), 1), (r(0, 1), 1)),
        ];
        let (_, (sk, sq), (ck, cq)) = table.into_iter().find(|(x, _, _)| *x == t)?;
        let s = self.surd(&(sk * sign_s), sq);
        let c = self.surd(&(ck * sign_c), cq);
        Some((s, c))
    }

    /// `k·√n` (n = 1 means the rational k).
    fn surd(&mut self, k: &Rat, n: u32) -> Id {
        let kk = self.graph.num(k.abs());
        let x = if n == 1 {
            kk
        } else {
            let v = self.graph.ring.sqrt(n);
            let l = self.graph.leaf(v);
            self.graph.mul(kk, l)
        };
        if k.is_negative() {
            self.graph.neg(x)
        } else {
            x
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
    }
}
