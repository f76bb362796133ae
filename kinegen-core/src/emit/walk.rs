//! The one walk over a formula that every printer shares: the engine's Rust-syntax
//! formula (`c1 * L1 + L2 * c12`) parsed with `syn`, printed again with the least
//! parentheses its precedence needs. What a sum, a product or a name looks like is a
//! `Style`: plain text ([`crate::emit::text`]), LaTeX ([`crate::emit::latex`]) and
//! MathML ([`crate::emit::mathml`]) are three styles of this walk, so they cannot
//! disagree on structure.
//!
//! Powers are read in two spellings: `x.powi(2)`, and `x^2` as the determinant's text
//! writes them (`^` binds looser than `*` in Rust, so it is rewritten to `.powi` before
//! parsing, to mean what a reader means).

use std::fmt;

use syn::{BinOp, Expr, Lit, UnOp};

use crate::emit::angle_names::AngleName;

/// A formula the renderer does not understand (not produced by the engine).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FormulaError {
    /// The formula as given.
    pub formula: String,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for FormulaError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot render `{}`: {}", self.formula, self.message)
    }
}

impl std::error::Error for FormulaError {}

/// Precedence levels, loosest first.
pub(crate) const SUM: u8 = 1;
pub(crate) const PRODUCT: u8 = 2;
pub(crate) const UNARY: u8 = 3;
pub(crate) const ATOM: u8 = 4;

/// A printed subexpression: its text, its precedence, and whether it starts with a
/// number (a product then needs a visible operator before it: `a · 0.5`).
#[derive(Clone, Debug)]
pub(crate) struct Node {
    pub text: String,
    pub prec: u8,
    pub leads_with_number: bool,
}

impl Node {
    pub(crate) fn new(text: String, prec: u8) -> Node {
        Node {
            text,
            prec,
            leads_with_number: false,
        }
    }
}

/// How one output notation prints each construct; the walk decides where parentheses
/// go (it calls [`Style::paren`]) and passes operands already printed.
pub(crate) trait Style {
    /// A literal as written (`0.425`, `1e-5`, `1.0`).
    fn number(&self, digits: &str) -> String;
    /// A variable (`c23`, `L1`, `self.L1` as `L1`).
    fn name(&self, name: &str) -> String;
    /// `(s)`.
    fn paren(&self, s: &str) -> String;
    /// `-x` (x already parenthesised where needed).
    fn neg(&self, x: &str) -> String;
    /// `x + y` or `x - y`.
    fn sum(&self, x: &str, minus: bool, y: &str) -> String;
    /// `x y`; `y_number`: `y` starts with a number.
    fn product(&self, x: &str, y: &str, y_number: bool) -> String;
    /// `x / y` with the operands as printed (unparenthesised).
    fn quotient(&self, x: &Node, y: &Node) -> Node;
    /// `f(args)`.
    fn call(&self, f: &str, args: &[String]) -> String;
    /// `base^exp` (base parenthesised where needed).
    fn power(&self, base: &str, exp: &str) -> String;
}

/// `formula` printed in `style`.
pub(crate) fn render(formula: &str, style: &impl Style) -> Result<String, FormulaError> {
    let err = |message: String| FormulaError {
        formula: formula.to_string(),
        message,
    };
    let expr = syn::parse_str::<Expr>(&caret_powers(formula)).map_err(|e| err(e.to_string()))?;
    Walk { style }.expr(&expr).map(|n| n.text).map_err(err)
}

/// `x^2` → `x.powi(2)`: the determinant's text writes powers with `^`, which Rust parses
/// looser than `*` (`a*b^2` would be `(a*b)^2`).
fn caret_powers(formula: &str) -> String {
    let mut out = String::with_capacity(formula.len());
    let mut chars = formula.chars().peekable();
    while let Some(c) = chars.next() {
        if c == '^' {
            let mut digits = String::new();
            while let Some(d) = chars.peek().filter(|d| d.is_ascii_digit()) {
                digits.push(*d);
                chars.next();
            }
            if digits.is_empty() {
                out.push('^');
            } else {
                out.push_str(&format!(".powi({digits})"));
            }
        } else {
            out.push(c);
        }
    }
    out
}

struct Walk<'s, S> {
    style: &'s S,
}

impl<S: Style> Walk<'_, S> {
    fn paren(&self, n: Node) -> Node {
        Node::new(self.style.paren(&n.text), ATOM)
    }

    fn expr(&self, e: &Expr) -> Result<Node, String> {
        match e {
            Expr::Paren(p) => self.expr(&p.expr),
            Expr::Group(g) => self.expr(&g.expr),
            Expr::Lit(l) => {
                let digits = match &l.lit {
                    Lit::Float(f) => f.base10_digits().to_string(),
                    Lit::Int(i) => i.base10_digits().to_string(),
                    other => return Err(format!("unexpected literal `{}`", quote::quote!(#other))),
                };
                Ok(Node {
                    text: self.style.number(&digits),
                    prec: ATOM,
                    leads_with_number: true,
                })
            }
            Expr::Path(p) => {
                let name = p
                    .path
                    .segments
                    .last()
                    .map(|s| s.ident.to_string())
                    .ok_or("empty path")?;
                Ok(Node::new(self.style.name(&name), ATOM))
            }
            // `self.L1` (parameters as the generated code reads them) is `L1`.
            Expr::Field(f) => match &f.member {
                syn::Member::Named(id) => Ok(Node::new(self.style.name(&id.to_string()), ATOM)),
                syn::Member::Unnamed(_) => Err("unexpected tuple field".into()),
            },
            Expr::Unary(u) => match u.op {
                UnOp::Neg(_) => {
                    let x = self.expr(&u.expr)?;
                    // `-(a + b)`, `-(-a)`; a product or atom reads without parentheses.
                    let x = if x.prec <= SUM || x.prec == UNARY {
                        self.paren(x)
                    } else {
                        x
                    };
                    Ok(Node::new(self.style.neg(&x.text), UNARY))
                }
                _ => Err(format!("unexpected operator `{}`", quote::quote!(#u))),
            },
            Expr::Binary(b) => self.binary(b),
            Expr::Call(c) => {
                let Expr::Path(p) = &*c.func else {
                    return Err("unexpected call".into());
                };
                let f = p
                    .path
                    .segments
                    .last()
                    .map(|s| s.ident.to_string())
                    .ok_or("empty path")?;
                let args = c
                    .args
                    .iter()
                    .map(|a| self.expr(a).map(|n| n.text))
                    .collect::<Result<Vec<_>, _>>()?;
                Ok(Node::new(self.style.call(&f, &args), ATOM))
            }
            Expr::MethodCall(m) if m.method == "powi" && m.args.len() == 1 => {
                let base = self.expr(&m.receiver)?;
                let exp = self.expr(&m.args[0])?;
                let base = if base.prec < ATOM {
                    self.paren(base)
                } else {
                    base
                };
                Ok(Node {
                    text: self.style.power(&base.text, &exp.text),
                    prec: ATOM,
                    leads_with_number: base.leads_with_number,
                })
            }
            Expr::MethodCall(m) if m.args.is_empty() => {
                // `x.sqrt()`, `x.sin()`.
                let x = self.expr(&m.receiver)?;
                Ok(Node::new(
                    self.style.call(&m.method.to_string(), &[x.text]),
                    ATOM,
                ))
            }
            other => Err(format!(
                "unsupported expression `{}`",
                quote::quote!(#other)
            )),
        }
    }

    fn binary(&self, b: &syn::ExprBinary) -> Result<Node, String> {
        let x = self.expr(&b.left)?;
        let y = self.expr(&b.right)?;
        let lead = x.leads_with_number;
        match b.op {
            BinOp::Add(_) | BinOp::Sub(_) => {
                let minus = matches!(b.op, BinOp::Sub(_));
                // `a + (-b)`: keep the sign visible rather than silently rewriting;
                // `a - (b + c)`.
                let y = if y.prec == UNARY || (minus && y.prec <= SUM) {
                    self.paren(y)
                } else {
                    y
                };
                Ok(Node {
                    text: self.style.sum(&x.text, minus, &y.text),
                    prec: SUM,
                    leads_with_number: lead,
                })
            }
            BinOp::Mul(_) => {
                // A leading minus reads as the whole product's sign: `-a b`.
                let x = if x.prec <= SUM { self.paren(x) } else { x };
                let y = if y.prec <= SUM || y.prec == UNARY {
                    self.paren(y)
                } else {
                    y
                };
                Ok(Node {
                    text: self.style.product(&x.text, &y.text, y.leads_with_number),
                    prec: PRODUCT,
                    leads_with_number: x.leads_with_number,
                })
            }
            BinOp::Div(_) => Ok(self.style.quotient(&x, &y)),
            _ => Err(format!("unsupported operator `{}`", quote::quote!(#b))),
        }
    }
}

/// The accent over a name's letter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Accent {
    None,
    /// `nc23` = −c₂₃.
    Bar,
    /// `qd3` = q̇₃.
    Dot,
}

/// The letter part of a name.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Base {
    /// One italic letter (`c`, `L`).
    Letter(String),
    /// A Greek letter's name (`alpha`).
    Greek(String),
    /// Several letters, upright (`len`).
    Word(String),
    /// No leading letter: the name as it is (`_x`).
    Raw(String),
}

/// A name as textbooks write it: accent, letter, subscript.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct NameParts {
    pub accent: Accent,
    pub base: Base,
    /// `23`, `2-3+4`, `1,2`, `k1` (empty: none).
    pub sub: String,
}

pub(crate) const GREEK: &[(&str, char)] = &[
    ("alpha", 'α'),
    ("beta", 'β'),
    ("gamma", 'γ'),
    ("delta", 'δ'),
    ("epsilon", 'ε'),
    ("zeta", 'ζ'),
    ("eta", 'η'),
    ("theta", 'θ'),
    ("iota", 'ι'),
    ("kappa", 'κ'),
    ("lambda", 'λ'),
    ("mu", 'μ'),
    ("nu", 'ν'),
    ("xi", 'ξ'),
    ("pi", 'π'),
    ("rho", 'ρ'),
    ("sigma", 'σ'),
    ("tau", 'τ'),
    ("upsilon", 'υ'),
    ("phi", 'φ'),
    ("chi", 'χ'),
    ("psi", 'ψ'),
    ("omega", 'ω'),
    ("Gamma", 'Γ'),
    ("Delta", 'Δ'),
    ("Theta", 'Θ'),
    ("Lambda", 'Λ'),
    ("Xi", 'Ξ'),
    ("Pi", 'Π'),
    ("Sigma", 'Σ'),
    ("Phi", 'Φ'),
    ("Psi", 'Ψ'),
    ("Omega", 'Ω'),
];

/// Split a variable name into textbook parts: `c23` → c, 23; `nc23` → c̄, 23; `qd3` →
/// q̇, 3; `c2m3` → c, 2-3; `alpha2` → α, 2; `d_bs` → d, bs; `c1_2_3` → c, 1,2,3.
pub(crate) fn name_parts(name: &str) -> NameParts {
    if let Some(sum) = AngleName::parse(name) {
        return NameParts {
            accent: if sum.negated {
                Accent::Bar
            } else {
                Accent::None
            },
            base: Base::Letter(if sum.sin { "s" } else { "c" }.into()),
            sub: sum.latex_subscript(name),
        };
    }
    // Joint rates `qd3` are q̇₃.
    if let Some(j) = name.strip_prefix("qd") {
        if !j.is_empty() && j.bytes().all(|b| b.is_ascii_digit()) {
            return NameParts {
                accent: Accent::Dot,
                base: Base::Letter("q".into()),
                sub: j.into(),
            };
        }
    }
    // Base: the leading letters; subscript: the rest, without a leading `_`, with
    // further `_` as separators.
    let cut = name
        .find(|c: char| !c.is_ascii_alphabetic())
        .unwrap_or(name.len());
    let (base, rest) = name.split_at(cut);
    if base.is_empty() {
        return NameParts {
            accent: Accent::None,
            base: Base::Raw(name.into()),
            sub: String::new(),
        };
    }
    let sub = rest.strip_prefix('_').unwrap_or(rest).replace('_', ",");
    let base = if GREEK.iter().any(|(g, _)| *g == base) {
        Base::Greek(base.into())
    } else if base.chars().count() > 1 {
        Base::Word(base.into())
    } else {
        Base::Letter(base.into())
    };
    NameParts {
        accent: Accent::None,
        base,
        sub,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn caret_powers_bind_to_their_base() {
        assert_eq!(caret_powers("a*cos(q3)^2"), "a*cos(q3).powi(2)");
        assert_eq!(caret_powers("(a + b)^12*c"), "(a + b).powi(12)*c");
        assert_eq!(caret_powers("a ^ b"), "a ^ b");
    }
}
