//! Validation errors → compile errors at the span of the offending entry.

use std::collections::HashMap;

use kinegen_core::model::raw::{DhError, Path};
use proc_macro2::TokenStream;

/// The tokens of every entry, by path. Tokens rather than a `Span`: joining spans is
/// nightly-only, but `syn::Error::new_spanned` underlines from the first to the last
/// token on stable.
#[derive(Default)]
pub struct Spans(HashMap<Path, TokenStream>);

impl Spans {
    /// Record where the entry at `path` was written (a later entry at the same path, a
    /// duplicate, replaces the earlier one: duplicates are reported at the second).
    pub fn insert(&mut self, path: Path, tokens: TokenStream) {
        self.0.insert(path, tokens);
    }

    /// The tokens of the entry at `path`, or of the closest enclosing entry.
    pub fn find(&self, path: &Path) -> Option<&TokenStream> {
        let mut p = Some(path.clone());
        while let Some(cur) = p {
            if let Some(t) = self.0.get(&cur) {
                return Some(t);
            }
            p = cur.parent();
        }
        None
    }
}

/// A compile error for `err` at its entry (the root is always recorded: the struct name).
pub fn error(spans: &Spans, err: &DhError) -> syn::Error {
    match spans.find(&err.path) {
        Some(tokens) => syn::Error::new_spanned(tokens, &err.message),
        None => syn::Error::new(proc_macro2::Span::call_site(), err.to_string()),
    }
}

/// Fold errors into one `syn::Error` that reports them all.
pub fn combine(errors: impl IntoIterator<Item = syn::Error>) -> Option<syn::Error> {
    errors.into_iter().reduce(|mut all, e| {
        all.combine(e);
        all
    })
}
