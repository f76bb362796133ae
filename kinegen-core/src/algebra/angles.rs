//! The ring's trigonometric variables and where each comes from at run time: a joint
//! angle (`sin_cos(±q[i] + offset)`) or a constant angle that does not fold to an exact
//! value.

use crate::algebra::poly::Var;
use crate::model::value::Value;

/// Where an angle's sine and cosine come from at run time.
#[derive(Clone, Debug, PartialEq)]
pub enum AngleSource {
    /// `sin_cos(sign·q[joint] + offset)`; `offset` is zero (and `sign` 1) unless the
    /// joint has an offset that does not fold (one that is not a multiple of π/2).
    Joint {
        /// Joint index (0-based).
        joint: usize,
        /// `1`, or `-1` for a joint that runs against its axis.
        sign: i8,
        /// Constant added to `sign·q[joint]`.
        offset: Value,
    },
    /// A constant angle that does not fold (e.g. a twist of 0.3 rad or one that
    /// names a parameter).
    Constant(Value),
}

/// One sine/cosine pair of the chain.
#[derive(Clone, Debug, PartialEq)]
pub struct AngleDef {
    /// Where its value comes from.
    pub source: AngleSource,
    /// Ring variables `(s, c)`.
    pub vars: (Var, Var),
    /// Name suffix (`1` for joint 1: `s1`, `c1`).
    pub suffix: String,
}

impl AngleSource {
    /// The angle as text in the joint variables: `q2`, `q2 + 0.1`, `q2 - 0.1`,
    /// `0.3 - q1`, `pi/5`.
    pub fn text(&self) -> String {
        match self {
            AngleSource::Joint {
                joint,
                sign,
                offset,
            } => {
                let q = format!("q{}", joint + 1);
                match (offset.is_zero(), *sign < 0) {
                    (true, false) => q,
                    (true, true) => format!("-{q}"),
                    (false, false) => match offset.to_string() {
                        o if o.starts_with('-') => format!("{q} - {}", &o[1..]),
                        o => format!("{q} + {o}"),
                    },
                    (false, true) => format!("{offset} - {q}"),
                }
            }
            AngleSource::Constant(v) => v.to_string(),
        }
    }
}
