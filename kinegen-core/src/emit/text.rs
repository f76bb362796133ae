//! Formulas as compact plain text for a terminal and for code comments: `c1·L1 + L2·c12`.
//! One style of [`crate::emit::walk`]'s printer (LaTeX and MathML are the others).
//!
//! ```
//! use kinegen_core::emit::text::to_text;
//! assert_eq!(to_text("-(s1 * L1 + t2)").unwrap(), "-(s1·L1 + t2)");
//! assert_eq!(to_text("a2 * cos(q3)^2").unwrap(), "a2·cos(q3)^2");
//! ```

use crate::emit::walk::{self, FormulaError, Node, Style, ATOM, PRODUCT, SUM};

/// A Rust-syntax formula as compact plain text for a terminal: `c1·L1 + L2·c12`,
/// integral floats without `.0`, minimal parentheses, powers `x^2`.
pub fn to_text(formula: &str) -> Result<String, FormulaError> {
    walk::render(formula, &Text)
}

/// The plain-text style.
struct Text;

impl Style for Text {
    fn number(&self, digits: &str) -> String {
        digits.strip_suffix(".0").unwrap_or(digits).to_string()
    }

    fn name(&self, name: &str) -> String {
        name.to_string()
    }

    fn paren(&self, s: &str) -> String {
        format!("({s})")
    }

    fn neg(&self, x: &str) -> String {
        format!("-{x}")
    }

    fn sum(&self, x: &str, minus: bool, y: &str) -> String {
        format!("{x} {} {y}", if minus { '-' } else { '+' })
    }

    fn product(&self, x: &str, y: &str, _: bool) -> String {
        format!("{x}·{y}")
    }

    fn quotient(&self, x: &Node, y: &Node) -> Node {
        let x = if x.prec <= SUM {
            self.paren(&x.text)
        } else {
            x.text.clone()
        };
        let y = if y.prec < ATOM {
            self.paren(&y.text)
        } else {
            y.text.clone()
        };
        Node::new(format!("{x}/{y}"), PRODUCT)
    }

    fn call(&self, f: &str, args: &[String]) -> String {
        format!("{f}({})", args.join(", "))
    }

    fn power(&self, base: &str, exp: &str) -> String {
        format!("{base}^{exp}")
    }
}
