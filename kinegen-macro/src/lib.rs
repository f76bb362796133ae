//! The `kinematics!` proc-macro (placeholder until the parser lands).
use proc_macro::TokenStream;

/// Generate closed-form kinematics from a DH table.
#[proc_macro]
pub fn kinematics(_input: TokenStream) -> TokenStream {
    TokenStream::new()
}
