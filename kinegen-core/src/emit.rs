//! Rust emission (work in progress: the struct only).

use quote::quote;

use crate::dh::Robot;
use crate::generate::{Generated, ItemHeader, Options};

pub(crate) fn emit(_robot: &Robot, header: &ItemHeader, _options: &Options) -> Generated {
    let ItemHeader { attrs, vis, ident } = header;
    Generated {
        tokens: quote! { #attrs #vis struct #ident; },
        notes: Vec::new(),
    }
}
