//! Products and sums of the engine's rationals, through machine integers when the
//! operands fit.
//!
//! Nearly every coefficient of a normal form is small (±1, ½, DH decimals such as
//! `0.425 = 17/40` and their products), yet `num-rational` cancels every product and
//! sum with big-integer gcds and divisions; unoptimised, as a proc-macro runs, that
//! was a quarter of a 6-joint expansion (issue 17, callgrind). Here operands whose
//! numerator and denominator fit in `i64` are combined in `i128` and cancelled with a
//! machine gcd; anything larger takes `num-rational`'s path. Both give the reduced
//! form with a positive denominator, which is unique: the result is the same value in
//! the same representation either way.

use num_bigint::BigInt;
use num_traits::{ToPrimitive, Zero};

use crate::model::value::Rat;

/// `a · b`.
pub fn mul(a: &Rat, b: &Rat) -> Rat {
    if let (Some((p1, q1)), Some((p2, q2))) = (small(a), small(b)) {
        if p1 == 0 || p2 == 0 {
            return Rat::zero();
        }
        // Cross-cancel first: the product of reduced fractions is then reduced.
        let (g1, g2) = (gcd(p1.unsigned_abs(), q2), gcd(p2.unsigned_abs(), q1));
        let n = (p1 / g1 as i128) * (p2 / g2 as i128);
        let d = (q1 / g2) * (q2 / g1);
        if let Some(r) = reduced(n, d) {
            return r;
        }
    }
    a * b
}

/// `a + b`.
pub fn add(a: &Rat, b: &Rat) -> Rat {
    if let (Some((p1, q1)), Some((p2, q2))) = (small(a), small(b)) {
        // |p·q| < 2¹²⁶ each, so the sum fits in i128.
        let n = p1 * q2 as i128 + p2 * q1 as i128;
        let d = q1 * q2;
        if n == 0 {
            return Rat::zero();
        }
        let g = gcd(n.unsigned_abs(), d);
        if let Some(r) = reduced(n / g as i128, d / g) {
            return r;
        }
    }
    a + b
}

/// Numerator and (positive) denominator, if both fit in `i64`.
fn small(r: &Rat) -> Option<(i128, u128)> {
    let n = r.numer().to_i64()?;
    let d = r.denom().to_i64()?;
    Some((n.into(), u128::try_from(d).ok()?))
}

/// The rational `n/d` from an already reduced pair with `d > 0`, if both fit in `i64`.
fn reduced(n: i128, d: u128) -> Option<Rat> {
    let n = i64::try_from(n).ok()?;
    let d = i64::try_from(d).ok()?;
    Some(Rat::new_raw(BigInt::from(n), BigInt::from(d)))
}

/// Euclid's gcd; `gcd(0, d) = d`.
fn gcd(mut a: u128, mut b: u128) -> u128 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(n: i64, d: i64) -> Rat {
        Rat::new(n.into(), d.into())
    }

    /// Same value *and* representation as num-rational's, small or large.
    #[test]
    fn agrees_with_num_rational_bit_for_bit() {
        let big = Rat::new(BigInt::from(3) << 70, 7.into());
        let xs = [
            r(0, 1),
            r(1, 1),
            r(-1, 1),
            r(17, 40),
            r(-3, 8),
            r(i64::MAX, 3),
            r(i64::MIN + 1, 5),
            r(5, i64::MAX),
            big.clone(),
            -big,
        ];
        for a in &xs {
            for b in &xs {
                let (m, s) = (mul(a, b), add(a, b));
                assert_eq!(m, a * b, "{a} · {b}");
                assert_eq!((m.numer(), m.denom()), ((a * b).numer(), (a * b).denom()));
                assert_eq!(s, a + b, "{a} + {b}");
                assert_eq!((s.numer(), s.denom()), ((a + b).numer(), (a + b).denom()));
            }
        }
    }
}
