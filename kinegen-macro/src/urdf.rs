//! The URDF forms: `struct Ur5 = urdf("ur5.urdf", base = "base_link", tip = "tool0");`
//! and a TOML file that names a URDF. Errors in the options point at the option; errors
//! in the URDF file at the file's literal, with the file's line.

use std::path::{Path as FsPath, PathBuf};

use kinegen_core::front::toml_file::RawFile;
use kinegen_core::front::urdf::Urdf;
use kinegen_core::front::urdf_robot::{chain, Problem, UrdfOptions};
use kinegen_core::model::raw::{DhError, Path};
use proc_macro2::TokenStream;
use quote::ToTokens;
use syn::LitStr;

use crate::expand::{emit, file_error, ik_free_in_macro, read, track};
use crate::parse::Input;
use crate::report;

/// `urdf("file.urdf", base = .., tip = ..)` followed by options.
pub fn expand(input: Input) -> syn::Result<TokenStream> {
    let Some(call) = &input.urdf else {
        return Err(syn::Error::new(input.ident.span(), "not the URDF form"));
    };
    let mut spans = input.spans;
    for (key, lit) in [("base", &call.base), ("tip", &call.tip)] {
        if let Some(l) = lit {
            spans.insert(Path::root().key(key), l.to_token_stream());
        }
    }
    // `snap`, `params.x`, `task[i]` fall back to the URDF call when they were not written.
    spans.insert(Path::root(), call.file.to_token_stream());
    let mut errors: Vec<syn::Error> = input
        .shape_errors
        .iter()
        .map(|e| report::error(&spans, e))
        .collect();
    let mut options = UrdfOptions {
        name: input.robot.name.clone(),
        base: call.base.as_ref().map(LitStr::value),
        tip: call.tip.as_ref().map(LitStr::value),
        snap: None,
        params: input.robot.params.clone(),
        symbolic: input.symbolic,
        task: input.robot.task.clone(),
        scalar: input.robot.scalar.clone(),
    };
    match &input.snap {
        Some((_, Ok(x))) => options.snap = Some(*x),
        Some((tokens, Err(msg))) => errors.push(syn::Error::new_spanned(tokens, msg)),
        None => {}
    }
    let (path, src) = read(&call.file)?;
    let urdf = Urdf::parse(&src, &call.file.value()).map_err(|e| file_error(&call.file, e))?;
    let built = chain(&urdf, &options).map_err(|problems| {
        problems
            .into_iter()
            .map(|p| match p {
                Problem::Option(e) => report::error(&spans, &e),
                Problem::File(e) => syn::Error::new(call.file.span(), e.to_string()),
            })
            .collect::<Vec<_>>()
    });
    let chain = match built {
        Ok(c) if errors.is_empty() => c,
        Ok(_) => return Err(report::combine(errors).unwrap_or_else(unreachable_error)),
        Err(more) => {
            errors.extend(more);
            return Err(report::combine(errors).unwrap_or_else(unreachable_error));
        }
    };
    let note_span = spans
        .find(&Path::root().key("budget"))
        .filter(|_| input.keys.iter().any(|k| k == "budget"))
        .and_then(|t| t.clone().into_iter().next())
        .map_or(input.ident.span(), |t| t.span());
    let free = match &input.ik_free {
        Some(written) => ik_free_in_macro(written, chain.dof())?,
        None => None,
    };
    Ok(emit(
        &chain,
        (input.attrs, input.vis, input.ident),
        (input.budget, free),
        note_span,
        track(&path),
    ))
}

fn unreachable_error() -> syn::Error {
    syn::Error::new(proc_macro2::Span::call_site(), "invalid URDF robot")
}

/// A TOML file of the file form that names a URDF.
pub struct FromToml<'a> {
    /// The TOML file's literal.
    pub toml: &'a LitStr,
    /// Its path.
    pub toml_path: &'a FsPath,
    /// Its entries.
    pub file: &'a RawFile,
    /// `urdf = "…"`, relative to the TOML file.
    pub urdf: &'a str,
    /// The options it gives.
    pub options: &'a UrdfOptions,
}

/// `struct X = "robot.toml";` where the file says `urdf = "…"`: the file's options,
/// with `name`, `params`, `task`, `scalar` and `budget` written in the macro in their place.
pub fn expand_toml(from: FromToml, input: Input) -> syn::Result<TokenStream> {
    let lit = from.toml;
    let at_file = |msg: String| syn::Error::new(lit.span(), msg);
    if let Some(e) = report::combine(
        input
            .shape_errors
            .iter()
            .map(|e| report::error(&input.spans, e)),
    ) {
        return Err(e);
    }
    if !from.file.shape_errors.is_empty() {
        return Err(file_error(
            lit,
            from.file.locate_all(from.file.shape_errors.clone()),
        ));
    }
    let mut options = from.options.clone();
    for key in &input.keys {
        match key.as_str() {
            "name" => options.name = input.robot.name.clone(),
            "params" => {
                options.params = input.robot.params.clone();
                options.symbolic = input.symbolic;
            }
            "task" => options.task = input.robot.task.clone(),
            "scalar" => options.scalar = input.robot.scalar.clone(),
            "budget" | "ik_free" => {}
            other => {
                let e = DhError {
                    path: Path::root().key(other),
                    message: format!("`{other}` cannot override a URDF robot's file: use name, params, task, scalar, budget or ik_free"),
                };
                return Err(report::error(&input.spans, &e));
            }
        }
    }
    let dir = from
        .toml_path
        .parent()
        .map(FsPath::to_path_buf)
        .unwrap_or_default();
    let urdf_path: PathBuf = dir.join(from.urdf);
    let src = std::fs::read_to_string(&urdf_path).map_err(|e| {
        let line = from.file.line_of(&Path::root().key("urdf"));
        at_file(format!(
            "{}:{line}: urdf: cannot read `{}`: {e}",
            lit.value(),
            urdf_path.display()
        ))
    })?;
    let label = urdf_path.display().to_string();
    let urdf = Urdf::parse(&src, &label).map_err(|e| file_error(lit, e))?;
    let chain = chain(&urdf, &options).map_err(|problems| {
        let errors = problems.into_iter().map(|p| match p {
            // An option written in the macro points there, one from the file at its line.
            Problem::Option(e)
                if input.keys.iter().any(|k| {
                    e.path.0.first() == Some(&kinegen_core::model::raw::PathSeg::Key(k.clone()))
                }) =>
            {
                report::error(&input.spans, &e)
            }
            Problem::Option(e) => at_file(from.file.locate(e).to_string()),
            Problem::File(e) => at_file(e.to_string()),
        });
        report::combine(errors).unwrap_or_else(unreachable_error)
    })?;
    let budget = if input.keys.iter().any(|k| k == "budget") {
        input.budget
    } else {
        from.file.budget
    };
    let free = match &input.ik_free {
        Some(written) => ik_free_in_macro(written, chain.dof())?,
        None => from
            .file
            .ik_free_of(chain.dof())
            .map_err(|e| file_error(lit, e))?,
    };
    let mut extra = track(from.toml_path);
    extra.extend(track(&urdf_path));
    Ok(emit(
        &chain,
        (input.attrs, input.vis, input.ident.clone()),
        (budget, free),
        input.ident.span(),
        extra,
    ))
}
