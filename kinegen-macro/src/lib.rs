//! The `kinematics!` proc-macro: parse the DH table, report errors at their spans,
//! and hand the robot to `kinegen_core::generate`. Everything else lives in the core.

mod expand;
mod parse;
mod report;

use proc_macro::TokenStream;

/// Generate closed-form kinematics from a DH table (see the `kinegen` crate docs).
#[proc_macro]
pub fn kinematics(input: TokenStream) -> TokenStream {
    let input = syn::parse_macro_input!(input as parse::Input);
    expand::expand(input)
        .unwrap_or_else(syn::Error::into_compile_error)
        .into()
}
