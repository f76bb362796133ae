//! The engine's notes as compiler warnings, on stable Rust.
//!
//! Stable Rust has no API for a proc-macro to emit a warning, so each note becomes a
//! constant marked `#[deprecated(note = "…")]` inside an anonymous `const _`, used right
//! there: rustc then prints `warning: use of deprecated constant …: <note>` (the
//! technique of the `proc-macro-warning` crate). The use carries a span of the macro
//! input — rustc does not report lints at spans that belong to another crate's macro.
//!
//! It is a lint like any other: `#[allow(deprecated)]` on the struct inside the macro
//! (forwarded here) or on an enclosing module or crate silences it, and
//! `#![deny(deprecated)]` makes it an error. The expansion uses nothing but `const`
//! items, so it compiles in `no_std` crates.

use proc_macro2::{Span, TokenStream};
use quote::quote;
use syn::{Attribute, Ident};

/// One warning per note at `span`; none without notes. `attrs` are the struct's
/// attributes: its lint levels (`allow`, `warn`, `deny`, `forbid`) and `cfg`s apply to
/// the warnings too.
pub fn warnings(notes: &[String], robot: &str, span: Span, attrs: &[Attribute]) -> TokenStream {
    let forwarded: Vec<&Attribute> = attrs
        .iter()
        .filter(|a| {
            ["allow", "warn", "deny", "forbid", "cfg"]
                .iter()
                .any(|k| a.path().is_ident(k))
        })
        .collect();
    notes
        .iter()
        .map(|note| {
            let message = format!("kinegen: `{robot}`: {note}");
            // Spanned at the input: the name in the message and the place it points at.
            let name = Ident::new("kinegen_note", span);
            quote! {
                #(#forwarded)*
                const _: () = {
                    #[deprecated(note = #message)]
                    #[allow(non_upper_case_globals)]
                    const #name: () = ();
                    #name
                };
            }
        })
        .collect()
}
