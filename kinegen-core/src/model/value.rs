//! Exact values of DH table entries.
//!
//! An entry is a number (`0.425`, `-1e-3`), a named link parameter (`a2`), an angle
//! expression (`pi/2`, `-2*pi/3`) or a linear combination of those (`d1 + 0.1`, `pi/2 - t0`).
//! It is kept as the exact linear form `k + p·π + Σ cᵢ·paramᵢ` with rational `k`, `p`, `cᵢ`:
//! decimal literals convert exactly, so a twist of `pi/2` gives exactly `cos α = 0` and
//! the zero it implies is a structural zero, not a rounding residue.

use std::collections::BTreeMap;
use std::fmt;

use num_bigint::BigInt;
use num_traits::{One, Signed, ToPrimitive, Zero};

/// Exact rational numbers of the engine.
pub type Rat = num_rational::BigRational;

/// An exact linear form `konst + pi·π + Σ params[name]·name`.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub struct Value {
    /// Rational constant part.
    pub konst: Rat,
    /// Rational multiple of π.
    pub pi: Rat,
    /// Named link parameters with their rational coefficients (no zero coefficients).
    pub params: BTreeMap<String, Rat>,
}

impl Value {
    /// The exact zero.
    pub fn zero() -> Self {
        Self::default()
    }

    /// An exact rational constant.
    pub fn rational(r: Rat) -> Self {
        Value {
            konst: r,
            ..Self::default()
        }
    }

    /// `r·π`.
    pub fn pi_times(r: Rat) -> Self {
        Value {
            pi: r,
            ..Self::default()
        }
    }

    /// A named parameter with coefficient 1.
    pub fn param(name: &str) -> Self {
        let mut params = BTreeMap::new();
        params.insert(name.to_string(), Rat::one());
        Value {
            params,
            ..Self::default()
        }
    }

    /// Exactly the value of a finite `f64` as written in shortest decimal form
    /// (`0.089159` → 89159/10⁶), which is what a user typed in a TOML file.
    pub fn from_f64(x: f64) -> Result<Self, ValueError> {
        if !x.is_finite() {
            return Err(ValueError::new(format!("`{x}` is not a finite number")));
        }
        Ok(Self::rational(parse_decimal(&format!("{x}"))?))
    }

    /// Whether the value is exactly zero.
    pub fn is_zero(&self) -> bool {
        self.konst.is_zero() && self.pi.is_zero() && self.params.is_empty()
    }

    /// Whether the value contains no named parameter.
    pub fn is_constant(&self) -> bool {
        self.params.is_empty()
    }

    /// The exact rational, if the value has neither π nor parameters.
    pub fn as_rational(&self) -> Option<&Rat> {
        (self.pi.is_zero() && self.params.is_empty()).then_some(&self.konst)
    }

    /// Numeric value, with parameter values from `param`.
    pub fn eval(&self, param: &dyn Fn(&str) -> f64) -> f64 {
        let mut v = rat_to_f64(&self.konst) + rat_to_f64(&self.pi) * core::f64::consts::PI;
        for (name, c) in &self.params {
            v += rat_to_f64(c) * param(name);
        }
        v
    }

    /// `self + other`.
    pub fn add(&self, other: &Value) -> Value {
        let mut out = self.clone();
        out.konst += &other.konst;
        out.pi += &other.pi;
        for (name, c) in &other.params {
            let e = out.params.entry(name.clone()).or_insert_with(Rat::zero);
            *e += c;
            if e.is_zero() {
                out.params.remove(name);
            }
        }
        out
    }

    /// `r · self`.
    pub fn scale(&self, r: &Rat) -> Value {
        if r.is_zero() {
            return Value::zero();
        }
        Value {
            konst: &self.konst * r,
            pi: &self.pi * r,
            params: self
                .params
                .iter()
                .map(|(n, c)| (n.clone(), c * r))
                .collect(),
        }
    }

    /// The parameter names this value depends on.
    pub fn param_names(&self) -> impl Iterator<Item = &str> {
        self.params.keys().map(String::as_str)
    }
}

impl fmt::Display for Value {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut terms: Vec<(Rat, String)> = Vec::new();
        if !self.pi.is_zero() {
            terms.push((self.pi.clone(), "pi".into()));
        }
        for (n, c) in &self.params {
            terms.push((c.clone(), n.clone()));
        }
        if !self.konst.is_zero() || terms.is_empty() {
            terms.push((self.konst.clone(), String::new()));
        }
        for (i, (c, name)) in terms.iter().enumerate() {
            let neg = c.is_negative();
            let a = c.abs();
            match (i, neg) {
                (0, true) => write!(f, "-")?,
                (0, false) => {}
                (_, true) => write!(f, " - ")?,
                (_, false) => write!(f, " + ")?,
            }
            if name.is_empty() {
                write!(f, "{}", fmt_rat(&a))?;
            } else if a.is_one() {
                write!(f, "{name}")?;
            } else if a.numer().is_one() {
                write!(f, "{name}/{}", a.denom())?;
            } else if a.is_integer() {
                write!(f, "{}*{name}", a.numer())?;
            } else {
                write!(f, "{}*{name}/{}", a.numer(), a.denom())?;
            }
        }
        Ok(())
    }
}

/// A rational printed as a short decimal when it has one (`0.425`), else as `p/q`.
pub fn fmt_rat(r: &Rat) -> String {
    if r.is_integer() {
        return r.numer().to_string();
    }
    // Terminating decimal iff the denominator is 2^a 5^b.
    let mut d = r.denom().clone();
    let two = BigInt::from(2);
    let five = BigInt::from(5);
    let mut digits = 0u32;
    let (mut n2, mut n5) = (0u32, 0u32);
    while (&d % &two).is_zero() {
        d /= &two;
        n2 += 1;
    }
    while (&d % &five).is_zero() {
        d /= &five;
        n5 += 1;
    }
    if d.is_one() {
        digits = digits.max(n2.max(n5));
        let scaled = r * Rat::from_integer(BigInt::from(10).pow(digits));
        let n = scaled.to_integer();
        let neg = n.is_negative();
        let s = n.abs().to_string();
        let s = format!("{:0>width$}", s, width = digits as usize + 1);
        let (int, frac) = s.split_at(s.len() - digits as usize);
        return format!("{}{}.{}", if neg { "-" } else { "" }, int, frac);
    }
    format!("{}/{}", r.numer(), r.denom())
}

/// `f64` of a rational (nearest or within an ulp; exact for the decimals of DH tables
/// after rounding).
pub fn rat_to_f64(r: &Rat) -> f64 {
    if let (Some(n), Some(d)) = (r.numer().to_i64(), r.denom().to_i64()) {
        if n.unsigned_abs() < (1 << 53) && d < (1 << 53) {
            return n as f64 / d as f64;
        }
    }
    // Large numerators or denominators: go through a correctly rounded decimal string.
    fmt_rat(r).parse::<f64>().unwrap_or_else(|_| {
        r.numer().to_f64().unwrap_or(f64::NAN) / r.denom().to_f64().unwrap_or(f64::NAN)
    })
}

/// Why an entry is not a valid value.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ValueError {
    /// Human-readable reason, without location (the caller adds it).
    pub message: String,
}

impl ValueError {
    fn new(message: impl Into<String>) -> Self {
        ValueError {
            message: message.into(),
        }
    }
}

impl fmt::Display for ValueError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for ValueError {}

/// Parse a decimal literal (`12`, `-0.425`, `1.5e-3`) exactly.
pub fn parse_decimal(s: &str) -> Result<Rat, ValueError> {
    let bad = || ValueError::new(format!("`{s}` is not a number"));
    let t = s.trim();
    let (neg, t) = match t.strip_prefix('-') {
        Some(r) => (true, r),
        None => (false, t.strip_prefix('+').unwrap_or(t)),
    };
    let (mant, exp) = match t.find(['e', 'E']) {
        Some(i) => (&t[..i], t[i + 1..].parse::<i32>().map_err(|_| bad())?),
        None => (t, 0),
    };
    let (int, frac) = match mant.find('.') {
        Some(i) => (&mant[..i], &mant[i + 1..]),
        None => (mant, ""),
    };
    if (int.is_empty() && frac.is_empty())
        || !int.bytes().all(|b| b.is_ascii_digit())
        || !frac.bytes().all(|b| b.is_ascii_digit())
        || exp.abs() > 300
    {
        return Err(bad());
    }
    let digits: BigInt = format!("{int}{frac}").parse().map_err(|_| bad())?;
    let scale = exp - frac.len() as i32;
    let ten = BigInt::from(10);
    let mut r = if scale >= 0 {
        Rat::from_integer(digits * ten.pow(scale as u32))
    } else {
        Rat::new(digits, ten.pow((-scale) as u32))
    };
    if neg {
        r = -r;
    }
    Ok(r)
}

/// Parse an entry such as `pi/2`, `-a2`, `0.5*L1`, `d1 + 0.1`, `-(pi/3)`.
///
/// Grammar: sums and differences of products and quotients of numbers, `pi`
/// (also `π`, `PI`), parameter names and parenthesised expressions, with unary signs.
/// The result must be linear: a product may have at most one non-constant factor,
/// and a divisor must be a nonzero rational constant.
pub fn parse_value(s: &str) -> Result<Value, ValueError> {
    let tokens = tokenize(s)?;
    if tokens.is_empty() {
        return Err(ValueError::new("empty expression"));
    }
    let mut p = Parser {
        toks: &tokens,
        pos: 0,
        src: s,
    };
    let v = p.sum()?;
    if p.pos != tokens.len() {
        return Err(ValueError::new(format!(
            "unexpected `{}` in `{}`",
            tokens[p.pos],
            s.trim()
        )));
    }
    Ok(v)
}

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Num(Rat, String),
    Ident(String),
    Op(char),
}

impl fmt::Display for Tok {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Tok::Num(_, s) | Tok::Ident(s) => f.write_str(s),
            Tok::Op(c) => write!(f, "{c}"),
        }
    }
}

fn tokenize(s: &str) -> Result<Vec<Tok>, ValueError> {
    let mut out = Vec::new();
    let chars: Vec<char> = s.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c.is_whitespace() {
            i += 1;
        } else if c.is_ascii_digit()
            || (c == '.' && chars.get(i + 1).is_some_and(|d| d.is_ascii_digit()))
        {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                i += 1;
            }
            if i < chars.len() && (chars[i] == 'e' || chars[i] == 'E') {
                let mut j = i + 1;
                if j < chars.len() && (chars[j] == '+' || chars[j] == '-') {
                    j += 1;
                }
                if j < chars.len() && chars[j].is_ascii_digit() {
                    i = j;
                    while i < chars.len() && chars[i].is_ascii_digit() {
                        i += 1;
                    }
                }
            }
            // Rust literal suffixes typed in the macro (`1.0f64`, `2_000`).
            let text: String = chars[start..i].iter().collect();
            let mut rest_end = i;
            while rest_end < chars.len()
                && (chars[rest_end].is_alphanumeric() || chars[rest_end] == '_')
            {
                rest_end += 1;
            }
            let suffix: String = chars[i..rest_end].iter().collect();
            if !suffix.is_empty()
                && suffix != "f64"
                && suffix != "f32"
                && !suffix.chars().all(|c| c == '_' || c.is_ascii_digit())
            {
                return Err(ValueError::new(format!("`{text}{suffix}` is not a number")));
            }
            i = rest_end;
            let clean: String = format!("{text}{suffix}")
                .trim_end_matches("f64")
                .trim_end_matches("f32")
                .replace('_', "");
            out.push(Tok::Num(parse_decimal(&clean)?, text));
        } else if c.is_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            out.push(Tok::Ident(chars[start..i].iter().collect()));
        } else if "+-*/()".contains(c) {
            out.push(Tok::Op(c));
            i += 1;
        } else {
            return Err(ValueError::new(format!(
                "unexpected character `{c}` in `{}`",
                s.trim()
            )));
        }
    }
    Ok(out)
}

struct Parser<'a> {
    toks: &'a [Tok],
    pos: usize,
    src: &'a str,
}

impl Parser<'_> {
    fn peek_op(&self) -> Option<char> {
        match self.toks.get(self.pos) {
            Some(Tok::Op(c)) => Some(*c),
            _ => None,
        }
    }

    fn sum(&mut self) -> Result<Value, ValueError> {
        let mut v = self.product()?;
        while let Some(op @ ('+' | '-')) = self.peek_op() {
            self.pos += 1;
            let rhs = self.product()?;
            v = if op == '+' {
                v.add(&rhs)
            } else {
                v.add(&rhs.scale(&-Rat::one()))
            };
        }
        Ok(v)
    }

    fn product(&mut self) -> Result<Value, ValueError> {
        let mut v = self.unary()?;
        while let Some(op @ ('*' | '/')) = self.peek_op() {
            self.pos += 1;
            let rhs = self.unary()?;
            v = if op == '*' {
                match (v.as_rational(), rhs.as_rational()) {
                    (Some(r), _) => rhs.scale(r),
                    (_, Some(r)) => v.scale(r),
                    _ => {
                        return Err(ValueError::new(format!(
                            "`{}` is not linear: a product may have only one factor that is `pi` or a parameter",
                            self.src.trim()
                        )))
                    }
                }
            } else {
                match rhs.as_rational() {
                    Some(r) if !r.is_zero() => v.scale(&r.recip()),
                    Some(_) => {
                        return Err(ValueError::new(format!(
                            "division by zero in `{}`",
                            self.src.trim()
                        )))
                    }
                    None => {
                        return Err(ValueError::new(format!(
                            "`{}` divides by `pi` or a parameter; only numbers may divide",
                            self.src.trim()
                        )))
                    }
                }
            };
        }
        Ok(v)
    }

    fn unary(&mut self) -> Result<Value, ValueError> {
        match self.peek_op() {
            Some('-') => {
                self.pos += 1;
                Ok(self.unary()?.scale(&-Rat::one()))
            }
            Some('+') => {
                self.pos += 1;
                self.unary()
            }
            _ => self.atom(),
        }
    }

    fn atom(&mut self) -> Result<Value, ValueError> {
        let tok = self.toks.get(self.pos).cloned();
        self.pos += 1;
        match tok {
            Some(Tok::Num(r, _)) => Ok(Value::rational(r)),
            Some(Tok::Ident(name)) => match name.as_str() {
                "pi" | "PI" | "π" => Ok(Value::pi_times(Rat::one())),
                _ => Ok(Value::param(&name)),
            },
            Some(Tok::Op('(')) => {
                let v = self.sum()?;
                if self.peek_op() != Some(')') {
                    return Err(ValueError::new(format!(
                        "missing `)` in `{}`",
                        self.src.trim()
                    )));
                }
                self.pos += 1;
                Ok(v)
            }
            Some(t) => Err(ValueError::new(format!(
                "unexpected `{t}` in `{}`",
                self.src.trim()
            ))),
            None => Err(ValueError::new(format!(
                "`{}` ends unexpectedly",
                self.src.trim()
            ))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(n: i64, d: i64) -> Rat {
        Rat::new(n.into(), d.into())
    }

    #[test]
    fn decimals_are_exact() {
        assert_eq!(parse_decimal("0.089159").unwrap(), r(89159, 1_000_000));
        assert_eq!(parse_decimal("-0.425").unwrap(), r(-17, 40));
        assert_eq!(parse_decimal("1.5e-3").unwrap(), r(3, 2000));
        assert_eq!(parse_decimal("12").unwrap(), r(12, 1));
        assert!(parse_decimal("1.2.3").is_err());
        assert!(parse_decimal("abc").is_err());
    }

    #[test]
    fn f64_round_trips_through_shortest_decimal() {
        assert_eq!(
            Value::from_f64(0.089159).unwrap().konst,
            r(89159, 1_000_000)
        );
        assert!(Value::from_f64(f64::NAN).is_err());
        assert!(Value::from_f64(f64::INFINITY).is_err());
    }

    #[test]
    fn angle_expressions() {
        assert_eq!(parse_value("pi/2").unwrap(), Value::pi_times(r(1, 2)));
        assert_eq!(parse_value("-pi / 2").unwrap(), Value::pi_times(r(-1, 2)));
        assert_eq!(parse_value("2*pi/3").unwrap(), Value::pi_times(r(2, 3)));
        assert_eq!(parse_value("-(pi/3)").unwrap(), Value::pi_times(r(-1, 3)));
        assert_eq!(parse_value("pi").unwrap(), Value::pi_times(r(1, 1)));
    }

    #[test]
    fn parameters_and_sums() {
        let v = parse_value("2*L1 - 0.5 + pi/4").unwrap();
        assert_eq!(v.konst, r(-1, 2));
        assert_eq!(v.pi, r(1, 4));
        assert_eq!(v.params["L1"], r(2, 1));
        assert_eq!(v.to_string(), "pi/4 + 2*L1 - 0.5");
        assert!(parse_value("a - a").unwrap().is_zero());
    }

    #[test]
    fn rejects_nonlinear_and_garbage() {
        assert!(parse_value("L1*L2").is_err());
        assert!(parse_value("1/L1").is_err());
        assert!(parse_value("1/0").is_err());
        assert!(parse_value("pi/").is_err());
        assert!(parse_value("(pi").is_err());
        assert!(parse_value("").is_err());
        assert!(parse_value("3 $ 4").is_err());
        assert!(parse_value("pi pi").is_err());
    }

    #[test]
    fn formats_rationals_as_decimals() {
        assert_eq!(fmt_rat(&r(-17, 40)), "-0.425");
        assert_eq!(fmt_rat(&r(1, 3)), "1/3");
        assert_eq!(fmt_rat(&r(7, 1)), "7");
        assert_eq!(fmt_rat(&r(1, 20)), "0.05");
    }

    #[test]
    fn rust_literal_suffixes() {
        assert_eq!(parse_value("1.0f64").unwrap(), Value::rational(r(1, 1)));
        assert!(parse_value("1.0abc").is_err());
    }
}
