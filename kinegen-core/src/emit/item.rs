//! The pieces of a generated `impl` as plain values: methods (with their bodies) and
//! constants. Every emitter module builds them; `emit::rust` prints them.

use crate::emit::code::Body;

/// A method `pub fn name(&self, q: &[F; N]) -> ret`, or with `rates`
/// `pub fn name(&self, q: &[F; N], qd: &[F; N]) -> ret`.
#[derive(Clone, Debug)]
pub struct Method {
    /// Rustdoc (markdown, several lines).
    pub doc: String,
    /// The method's name.
    pub name: &'static str,
    /// Whether it also takes the joint rates `qd` (`Code` and `Expr` bodies; a `Custom`
    /// body states its own arguments).
    pub rates: bool,
    /// Return type.
    pub ret: String,
    /// What it computes: straight-line code, or one expression.
    pub body: MethodBody,
}

/// A method's body.
#[derive(Clone, Debug)]
pub enum MethodBody {
    /// `let`s, then `result` built from the body's output expressions.
    Code {
        /// Statements and outputs.
        body: Body,
        /// The returned expression.
        result: String,
    },
    /// A single expression (the numeric determinant fallback).
    Expr(String),
    /// Other arguments than `q`: `pub fn name(&self, args) -> ret { lets; result }`.
    Custom {
        /// The arguments after `&self` (`pose: &[[f64; 4]; 4]`).
        args: String,
        /// Statements.
        lets: Vec<String>,
        /// The returned expression.
        result: String,
    },
}

/// A constant `pub const name: ty = value;`.
#[derive(Clone, Debug)]
pub struct Const {
    /// Rustdoc (markdown, one line or several).
    pub doc: String,
    /// Name.
    pub name: &'static str,
    /// Type.
    pub ty: String,
    /// Value (Rust expression).
    pub value: String,
}

/// An item of the generated `impl`, in the order printed.
#[derive(Clone, Debug)]
pub enum Item {
    /// A method.
    Method(Method),
    /// A constant.
    Const(Const),
}
