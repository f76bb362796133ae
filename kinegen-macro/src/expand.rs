//! Validate the parsed input (merged with its TOML file in the file form), report every
//! error at its place, and call the engine.

use std::path::PathBuf;

use kinegen_core::front::toml_file::RawFile;
use kinegen_core::model::input;
use kinegen_core::model::raw::{DhError, Path, PathSeg, RawRobot};
use kinegen_core::model::validate::validate;
use kinegen_core::{Budget, Chain, ItemHeader, Options};
use proc_macro2::{Span, TokenStream};
use quote::quote;
use syn::{Attribute, Ident, LitStr, Visibility};

use crate::parse::Input;
use crate::report;

/// The generated item, or every error found.
pub fn expand(input: Input) -> syn::Result<TokenStream> {
    if input.urdf.is_some() {
        return crate::urdf::expand(input);
    }
    let Input {
        attrs,
        vis,
        ident,
        file,
        robot: mut raw,
        budget,
        keys,
        spans,
        shape_errors,
        ik_free,
        symbolic,
        ..
    } = input;
    let mut budget = budget;
    let mut from_file = None;
    let mut rebuild_on_change = TokenStream::new();
    if let Some(lit) = &file {
        let (path, src) = read(lit)?;
        let parsed = RawFile::parse(&src, &lit.value()).map_err(|e| file_error(lit, e))?;
        if let Some((urdf, options)) = &parsed.urdf {
            let from_toml = crate::urdf::FromToml {
                toml: lit,
                toml_path: &path,
                file: &parsed,
                urdf,
                options,
            };
            return crate::urdf::expand_toml(
                from_toml,
                Input {
                    attrs,
                    vis,
                    ident,
                    file: file.clone(),
                    urdf: None,
                    snap: None,
                    ik_free,
                    symbolic,
                    robot: raw,
                    budget,
                    keys,
                    spans,
                    shape_errors,
                },
            );
        }
        raw = merge(parsed.robot.clone(), raw, &keys);
        if !keys.iter().any(|k| k == "budget") {
            budget = parsed.budget;
        }
        rebuild_on_change = track(&path);
        from_file = Some(parsed);
    }
    if raw.name.is_none() {
        raw.name = Some(ident.to_string());
    }
    // Where the engine's notes are reported: the `budget` entry when it is written in
    // the macro (notes are about the budget), else the struct's name.
    let note_span = spans
        .find(&Path::root().key("budget"))
        .filter(|_| keys.iter().any(|k| k == "budget"))
        .and_then(|t| t.clone().into_iter().next())
        .map_or(ident.span(), |t| t.span());

    // An error belongs to the macro when its top-level key was written there (or when
    // there is no file); else to the file, reported at the path literal with its line.
    let in_macro = |e: &DhError| match e.path.0.first() {
        Some(PathSeg::Key(k)) => keys.contains(k),
        _ => from_file.is_none(),
    };
    let mut shape = shape_errors;
    if let Some(f) = &from_file {
        shape.extend(f.shape_errors.iter().cloned());
    }
    let checked = validate(&raw);
    let checks = checked.as_ref().err().cloned().unwrap_or_default();
    let errors = input::combine_errors(shape, checks);
    let errors = errors.iter().map(|e| match (&from_file, &file) {
        (Some(f), Some(lit)) if !in_macro(e) => {
            syn::Error::new(lit.span(), f.locate(e.clone()).to_string())
        }
        _ => report::error(&spans, e),
    });
    if let Some(err) = report::combine(errors) {
        return Err(err);
    }
    let robot = match checked {
        Ok(robot) => robot,
        // Unreachable: `validate` failing gives at least one error above.
        Err(_) => return Err(syn::Error::new(ident.span(), "invalid robot")),
    };

    let chain = robot.chain();
    let free = match (&ik_free, &from_file, &file) {
        (Some(written), _, _) => ik_free_in_macro(written, chain.dof())?,
        (None, Some(f), Some(lit)) => f.ik_free_of(chain.dof()).map_err(|e| file_error(lit, e))?,
        _ => None,
    };
    Ok(emit(
        &chain,
        (attrs, vis, ident),
        (budget, free),
        note_span,
        rebuild_on_change,
    ))
}

/// `ik_free: k` written in the macro, checked against the robot's `dof`: the joint,
/// 0-based, or the error at the entry.
pub fn ik_free_in_macro(
    (tokens, value): &(TokenStream, Result<usize, String>),
    dof: usize,
) -> syn::Result<Option<usize>> {
    value
        .clone()
        .and_then(|k| input::check_ik_free(k, dof))
        .map(Some)
        .map_err(|msg| syn::Error::new_spanned(tokens, msg))
}

/// The item for `chain`, the notes as warnings at `note_span`, and `extra` tokens; the
/// engine bounded by `budget`, a 7-joint arm's IK leaving joint `ik_free` (0-based) free.
pub fn emit(
    chain: &Chain,
    (attrs, vis, ident): (Vec<Attribute>, Visibility, Ident),
    (budget, ik_free): (Option<Budget>, Option<usize>),
    note_span: Span,
    extra: TokenStream,
) -> TokenStream {
    let header = ItemHeader {
        attrs: quote! { #(#attrs)* },
        vis: quote! { #vis },
        ident,
    };
    let options = Options {
        budget: budget.unwrap_or_default(),
        ik_free,
        ..Options::default()
    };
    let generated = kinegen_core::generate(chain, &header, &options);
    let tokens = generated.tokens;
    let warnings = crate::warnings::warnings(
        &generated.notes,
        &header.ident.to_string(),
        note_span,
        &attrs,
    );
    quote! { #tokens #extra #warnings }
}

/// `const _: &str = include_str!(path);`: cargo rebuilds the crate when the file changes.
pub fn track(path: &std::path::Path) -> TokenStream {
    let abs = path.to_string_lossy().into_owned();
    quote! { const _: &str = ::core::include_str!(#abs); }
}

/// The file of the file form, relative to the crate being compiled.
pub fn read(lit: &LitStr) -> syn::Result<(PathBuf, String)> {
    let rel = lit.value();
    let Some(dir) = std::env::var_os("CARGO_MANIFEST_DIR") else {
        return Err(syn::Error::new(
            lit.span(),
            "CARGO_MANIFEST_DIR is not set: the file form needs cargo to locate the file",
        ));
    };
    let path = PathBuf::from(dir).join(&rel);
    match std::fs::read_to_string(&path) {
        Ok(src) => Ok((path, src)),
        Err(e) => Err(syn::Error::new(
            lit.span(),
            format!("cannot read `{rel}` (relative to the crate's Cargo.toml): {e}"),
        )),
    }
}

pub fn file_error(lit: &LitStr, err: kinegen_core::front::toml_file::LoadError) -> syn::Error {
    let errors = err
        .errors
        .iter()
        .map(|e| syn::Error::new(lit.span(), e.to_string()));
    report::combine(errors).unwrap_or_else(|| syn::Error::new(lit.span(), "invalid file"))
}

/// The file's robot with the top-level entries written in the macro put in its place.
fn merge(mut base: RawRobot, over: RawRobot, keys: &[String]) -> RawRobot {
    for key in keys {
        match key.as_str() {
            "name" => base.name = over.name.clone(),
            "convention" => base.convention = over.convention.clone(),
            "params" => base.params = over.params.clone(),
            "joints" => base.joints = over.joints.clone(),
            "task" => base.task = over.task.clone(),
            "base" => base.base = over.base.clone(),
            "tool" => base.tool = over.tool.clone(),
            "scalar" => base.scalar = over.scalar.clone(),
            _ => {}
        }
    }
    base
}
