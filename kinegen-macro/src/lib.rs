//! The `kinematics!` proc-macro: parse the DH table, report errors at their spans,
//! and hand the robot to `kinegen_core::generate`. Everything else lives in the core.

mod expand;
mod parse;
mod report;
mod urdf;
mod warnings;

use proc_macro::TokenStream;

/// Generate closed-form kinematics from a DH table (see the `kinegen` crate docs).
///
/// # Budget and notes
///
/// `budget: { nodes: 5000, iterations: 20, time_ms: 10000 }` (the defaults; any subset)
/// bounds the engine: `nodes` is the largest exact normal form (terms) it keeps and the
/// e-graph size per simplification, `iterations` the e-graph iterations per expression,
/// and `time_ms` a wall-clock deadline for the whole expansion. Over a budget the engine
/// still emits correct code, only less simplified — expressions shared structurally
/// instead of by value, polish skipped, a numeric LU `jacobian_det` instead of the
/// closed form — and says so in a note. Before the deadline nothing depends on the
/// clock: the same table gives the same code on every build that does not reach it.
///
/// Each note is reported as a compiler warning at the `budget` entry (or at the
/// struct's name when there is none), through the `deprecated` lint — stable Rust has
/// no other way for a macro to warn:
///
/// ```text
/// warning: use of deprecated constant `_::kinegen_note`: kinegen: `Noted`: 2 expressions
///          exceeded the normal-form budget of 2 terms: they are shared structurally only
///          (outputs without a normal form: `fk[0][3]`, …)
///   --> src/lib.rs:12:5
///    |
/// 12 |     budget: { nodes: 2 },
///    |     ^^^^^^
/// ```
///
/// A table within its budget gets no warning. To silence them, put
/// `#[allow(deprecated)]` on the struct inside the macro (the struct's lint attributes
/// apply to its notes), or on an enclosing module or the crate; `#![deny(deprecated)]`
/// (or `deny(warnings)`) turns them into errors. Either way the generated type is the
/// same. The expansion is plain `const` items: `no_std` crates get the warnings too.
///
/// ```ignore
/// kinegen::kinematics! {
///     /// Over budget on purpose, and quiet about it.
///     #[allow(deprecated)]
///     pub struct Quiet;
///     convention: standard,
///     joints: [revolute { a: 1, alpha: 0, d: 0 }, revolute { a: 1, alpha: 0, d: 0 }],
///     budget: { nodes: 2 },
/// }
/// ```
#[proc_macro]
pub fn kinematics(input: TokenStream) -> TokenStream {
    let input = syn::parse_macro_input!(input as parse::Input);
    expand::expand(input)
        .unwrap_or_else(syn::Error::into_compile_error)
        .into()
}
