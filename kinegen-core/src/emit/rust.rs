//! Rust emission: the robot type, its inherent `impl` and the `Kinematics` trait
//! implementations, printed from [`Functions`].

use std::fmt::Write;

use proc_macro2::{Ident, TokenStream};

use crate::chain::Chain;
use crate::emit::docs::struct_doc;
use crate::emit::functions::{Const, DetOf, Functions, Item, Method, MethodBody};
use crate::emit::ik::{CheckImpl, SingularCheck};
use crate::model::robot::Scalar;

/// What the generated item looks like from outside: `#[attrs] vis struct ident`.
#[derive(Clone, Debug)]
pub struct ItemHeader {
    /// Outer attributes written on the struct (doc comments, `#[derive]`s beyond ours).
    pub attrs: TokenStream,
    /// Visibility (`pub`, `pub(crate)` or empty).
    pub vis: TokenStream,
    /// The type's name.
    pub ident: Ident,
}

impl ItemHeader {
    /// `pub struct <Name>` with the name made a Rust type name from a display name
    /// (`"UR5"` → `Ur5`, `"planar RR"` → `PlanarRr`).
    pub fn public(display_name: &str) -> Self {
        ItemHeader {
            attrs: TokenStream::new(),
            vis: quote::quote!(pub),
            ident: Ident::new(&type_name(display_name), proc_macro2::Span::call_site()),
        }
    }
}

/// A Rust type name (UpperCamelCase) from a display name.
pub fn type_name(display: &str) -> String {
    let mut out = String::new();
    for word in display.split(|c: char| !c.is_ascii_alphanumeric()) {
        let mut chars = word.chars();
        if let Some(first) = chars.next() {
            out.push(first.to_ascii_uppercase());
            out.extend(chars.map(|c| c.to_ascii_lowercase()));
        }
    }
    if out.is_empty() || out.starts_with(|c: char| c.is_ascii_digit()) {
        out.insert_str(0, "Robot");
    }
    out
}

/// The item for `chain` as source text: struct (with `Default`), inherent `impl`, trait
/// `impl`s ([`lex`] makes it tokens). Printed into one string, sized first: a long
/// chain's item is tens of megabytes, and a second copy (the inherent `impl`'s body, each
/// method's `let`s joined) or a string doubled as it grows was the engine's peak of
/// memory.
pub fn print(chain: &Chain, header: &ItemHeader, functions: &Functions) -> String {
    let ident = header.ident.to_string();
    let qty = format!("&[{}; {}]", functions.float, chain.dof());
    let mut items = String::with_capacity(printed_size(functions));
    items.push_str(&the_struct(chain, header, functions));
    let _ = writeln!(
        items,
        "#[allow(clippy::all, clippy::pedantic, unused_parens, non_snake_case)]\nimpl {ident} {{"
    );
    for item in &functions.items {
        match item {
            Item::Method(m) => method(&mut items, m, &qty),
            Item::Const(c) => konst(&mut items, c),
        }
    }
    items.push_str("}\n");
    if chain.scalar == Scalar::F64 {
        items.push_str(&traits(chain, &ident, functions));
    }
    if let Some(check) = &functions.check {
        items.push_str(&check_impl(chain, &ident, check));
        // The trait is f64-typed (a `Kinematics<N>` supertrait): f32 robots have the
        // inherent methods only.
        if chain.scalar == Scalar::F64 {
            items.push_str(&ik_impl(chain, &ident, check));
        }
    }
    items
}

/// About how long [`print`](fn@print)'s text is: the methods' docs and statements, and
/// room for the rest.
fn printed_size(functions: &Functions) -> usize {
    let lines = |lets: &[String]| lets.iter().map(|l| l.len() + 1).sum::<usize>();
    let text = |m: &Method| {
        m.doc.len()
            + match &m.body {
                MethodBody::Code { body, result } => lines(&body.lets) + result.len(),
                MethodBody::Custom { lets, result, .. } => lines(lets) + result.len(),
                MethodBody::Expr(e) => e.len(),
            }
    };
    let methods: usize = functions
        .items
        .iter()
        .map(|item| match item {
            Item::Method(m) => text(m) + 256,
            Item::Const(c) => c.doc.len() + c.value.len() + 64,
        })
        .sum();
    methods + 64 * 1024
}

/// The item's text as tokens. Lexed only: inside the macro this is the compiler's own
/// lexer, while parsing the whole item with `syn` (at the opt-level 0 users build
/// proc-macros with) cost a fifth of the Panda's expansion. rustc parses the tokens
/// anyway; the engine's tests parse every robot's item with `syn`
/// (kinegen-core/tests/determinism.rs).
pub fn lex(text: &str) -> TokenStream {
    match text.parse::<TokenStream>() {
        Ok(tokens) => tokens,
        Err(e) => {
            // An engine bug, never the user's input: report it instead of emitting
            // code that does not lex.
            let msg = format!("kinegen internal error: generated code does not lex: {e}");
            quote::quote!(::core::compile_error!(#msg);)
        }
    }
}

/// The struct, its parameters as fields, and `Default` with the table's values.
fn the_struct(chain: &Chain, header: &ItemHeader, functions: &Functions) -> String {
    let f = functions.float;
    let ident = header.ident.to_string();
    let vis = header.vis.to_string();
    let attrs = header.attrs.to_string();
    // After the user's own doc comment, a paragraph of its own (not one run-on summary).
    let gap = if has_doc(&header.attrs) { "///\n" } else { "" };
    let summary = format!("{gap}{}", struct_doc(chain));
    if functions.fields.is_empty() {
        return format!(
            "{attrs}\n{summary}\n#[derive(Clone, Copy, Debug, Default, PartialEq)]\n{vis} struct {ident};\n"
        );
    }
    let mut fields = String::new();
    let mut defaults = String::new();
    for (name, doc, value) in &functions.fields {
        let _ = writeln!(fields, "/// {doc}\npub {name}: {f},");
        let _ = writeln!(defaults, "{name}: {value},");
    }
    format!(
        "{attrs}\n{summary}\n#[derive(Clone, Copy, Debug, PartialEq)]\n{vis} struct {ident} {{\n{fields}}}\n\
         impl ::core::default::Default for {ident} {{\n/// The DH table's values.\nfn default() -> Self {{ Self {{ {defaults} }} }}\n}}\n"
    )
}

/// Whether `attrs` hold a doc comment (`#[doc = …]`).
fn has_doc(attrs: &TokenStream) -> bool {
    use syn::parse::Parser;
    syn::Attribute::parse_outer
        .parse2(attrs.clone())
        .is_ok_and(|a| a.iter().any(|a| a.path().is_ident("doc")))
}

/// `impl Kinematics<N>`, `impl SecondOrderKinematics<N>` and, with task rows,
/// `impl TaskKinematics<N, M>` (f64 only).
fn traits(chain: &Chain, ident: &str, functions: &Functions) -> String {
    let n = chain.dof();
    let mut tr = format!(
        "impl ::kinegen::Kinematics<{n}> for {ident} {{\n\
         const NAME: &'static str = {:?};\n\
         #[inline] fn fk(&self, q: &[f64; {n}]) -> [[f64; 4]; 4] {{ {ident}::fk(self, q) }}\n\
         #[inline] fn frames(&self, q: &[f64; {n}]) -> [[[f64; 4]; 4]; {n}] {{ {ident}::frames(self, q) }}\n\
         #[inline] fn jacobian(&self, q: &[f64; {n}]) -> [[f64; {n}]; 6] {{ {ident}::jacobian(self, q) }}\n\
         #[inline] fn jacobian_ee(&self, q: &[f64; {n}]) -> [[f64; {n}]; 6] {{ {ident}::jacobian_ee(self, q) }}\n\
         #[inline] fn fk_and_jacobian(&self, q: &[f64; {n}]) -> ([[f64; 4]; 4], [[f64; {n}]; 6]) {{ {ident}::fk_and_jacobian(self, q) }}\n\
         #[inline] fn limits(&self) -> [[f64; 2]; {n}] {{ Self::LIMITS }}\n",
        chain.name
    );
    if functions.det == Some(DetOf::Full) {
        let _ = writeln!(
            tr,
            "#[inline] fn jacobian_det(&self, q: &[f64; {n}]) -> Option<f64> {{ Some({ident}::jacobian_det(self, q)) }}"
        );
    }
    tr.push_str("}\n");
    let det_gradient = if functions.det == Some(DetOf::Full) && functions.det_gradient {
        format!("Some({ident}::det_gradient(self, q))")
    } else {
        "{ let _ = q; None }".into()
    };
    let _ = writeln!(
        tr,
        "impl ::kinegen::SecondOrderKinematics<{n}> for {ident} {{\n\
         #[inline] fn hessian(&self, q: &[f64; {n}]) -> [[[f64; {n}]; 6]; {n}] {{ {ident}::hessian(self, q) }}\n\
         #[inline] fn jacobian_dot(&self, q: &[f64; {n}], qd: &[f64; {n}]) -> [[f64; {n}]; 6] {{ {ident}::jacobian_dot(self, q, qd) }}\n\
         #[inline] fn jdot_qdot(&self, q: &[f64; {n}], qd: &[f64; {n}]) -> [f64; 6] {{ {ident}::jdot_qdot(self, q, qd) }}\n\
         #[inline] fn jacobian_ee_dot(&self, q: &[f64; {n}], qd: &[f64; {n}]) -> [[f64; {n}]; 6] {{ {ident}::jacobian_ee_dot(self, q, qd) }}\n\
         #[inline] fn manipulability_gradient(&self, q: &[f64; {n}]) -> [f64; {n}] {{ {ident}::manipulability_gradient(self, q) }}\n\
         #[inline] fn det_gradient(&self, q: &[f64; {n}]) -> Option<[f64; {n}]> {{ {det_gradient} }}\n}}"
    );
    if let Some(task) = &chain.task {
        let m = task.len();
        let rows: Vec<String> = task.iter().map(|r| r.index().to_string()).collect();
        let det = if functions.det.is_some() && m == n {
            format!("#[inline] fn task_jacobian_det(&self, q: &[f64; {n}]) -> Option<f64> {{ Some({ident}::jacobian_det(self, q)) }}\n")
        } else {
            String::new()
        };
        let _ = writeln!(
            tr,
            "impl ::kinegen::TaskKinematics<{n}, {m}> for {ident} {{\n\
             const TASK_ROWS: [usize; {m}] = [{}];\n\
             #[inline] fn task_jacobian(&self, q: &[f64; {n}]) -> [[f64; {n}]; {m}] {{ {ident}::task_jacobian(self, q) }}\n{det}}}",
            rows.join(", "),
        );
    }
    tr
}

/// `impl Check<N>`: what the IK's `finish` step evaluates for least-squares and singular
/// branches.
fn check_impl(chain: &Chain, ident: &str, check: &CheckImpl) -> String {
    let n = chain.dof();
    // An f32 robot's solve is checked in f64: on the geometry's product of exponentials.
    // So is an f64 robot's with kinegen's `small-ik` (`checked_pose`: the runtime's one
    // product of exponentials instead of a second copy of `fk` inlined into `ik`).
    let fk = match check.scalar {
        Scalar::F64 => {
            "::kinegen::ik::solutions::checked_pose(|| self.fk(q), || self.ik_geometry().fk(q))"
        }
        Scalar::F32 => "::kinegen::ik::solutions::pose_matrix(&self.ik_geometry().fk(q))",
    };
    let residual = match &check.task_rows {
        None => format!("::kinegen::ik::solutions::residual(&{fk}, pose)"),
        Some(rows) => {
            format!("::kinegen::ik::solutions::task_residual(&{fk}, pose, &{rows:?})")
        }
    };
    let singular = match &check.singular {
        SingularCheck::Factors => {
            "::kinegen::ik::solutions::vanishing(&self.singular_factors(q))".to_string()
        }
        SingularCheck::Widened(body) => format!(
            "{}\n::kinegen::ik::solutions::vanishing(&[{}])",
            body.lets.join("\n"),
            body.outputs.join(", ")
        ),
        SingularCheck::None => "{ let _ = q; 0 }".to_string(),
    };
    // Straight-line code like the inherent methods', with their lints allowed.
    let attrs = match check.singular {
        SingularCheck::Widened(_) => {
            "#[allow(clippy::all, clippy::pedantic, unused_parens, non_snake_case)] "
        }
        _ => "",
    };
    format!(
        "impl ::kinegen::ik::solutions::Check<{n}> for {ident} {{\n\
         #[inline] fn residual(&self, q: &[f64; {n}], pose: &::kinegen::ik::geometry::Pose) -> f64 {{ {residual} }}\n\
         {attrs}#[inline] fn singular(&self, q: &[f64; {n}]) -> u32 {{ {singular} }}\n}}\n"
    )
}

/// `impl InverseKinematics<N>`: the closed form behind a trait generic code can call.
fn ik_impl(chain: &Chain, ident: &str, check: &CheckImpl) -> String {
    let n = chain.dof();
    let seeded = match check.locked {
        None => "self.ik_seeded(pose, free)".to_string(),
        Some(k) => format!("self.ik_seeded(pose, free[{k}], free)"),
    };
    format!(
        "impl ::kinegen::InverseKinematics<{n}> for {ident} {{\n\
         const IK_FAMILY: &'static str = Self::IK_FAMILY;\n\
         #[inline] fn ik_near(&self, pose: &[[f64; 4]; 4], q_current: &[f64; {n}]) -> ::core::option::Option<[f64; {n}]> {{ {ident}::ik_near(self, pose, q_current) }}\n\
         #[inline] fn ik_each(&self, pose: &[[f64; 4]; 4], free: &[f64; {n}], f: &mut dyn FnMut(&::kinegen::ik::IkBranch<{n}>)) {{ for b in {seeded}.iter() {{ f(b); }} }}\n}}\n"
    )
}

fn doc_lines(out: &mut String, doc: &str) {
    for line in doc.lines() {
        let _ = writeln!(out, "///{}{line}", if line.is_empty() { "" } else { " " });
    }
}

fn method(out: &mut String, m: &Method, qty: &str) {
    let Method {
        doc,
        name,
        rates,
        ret,
        body,
    } = m;
    let (args, unused) = if *rates {
        (format!("q: {qty}, qd: {qty}"), "(q, qd)")
    } else {
        (format!("q: {qty}"), "q")
    };
    // Each statement written out in turn (not joined into a string of its own first).
    let statements = |out: &mut String, lets: &[String]| {
        for l in lets {
            out.push_str(l);
            out.push('\n');
        }
    };
    match body {
        MethodBody::Code { body, result } => {
            doc_lines(out, doc);
            let _ = writeln!(
                out,
                "#[inline]\n#[must_use]\npub fn {name}(&self, {args}) -> {ret} {{\nlet _ = {unused};"
            );
            statements(out, &body.lets);
            let _ = writeln!(out, "{result}\n}}");
        }
        MethodBody::Custom { args, lets, result } => {
            doc_lines(out, doc);
            let _ = writeln!(out, "#[must_use]\npub fn {name}(&self, {args}) -> {ret} {{");
            statements(out, lets);
            let _ = writeln!(out, "{result}\n}}");
        }
        MethodBody::Expr(e) => {
            doc_lines(out, doc);
            let _ = writeln!(
                out,
                "#[inline]\n#[must_use]\npub fn {name}(&self, {args}) -> {ret} {{ {e} }}"
            );
        }
    }
}

fn konst(out: &mut String, c: &Const) {
    doc_lines(out, &c.doc);
    let _ = writeln!(out, "pub const {}: {} = {};", c.name, c.ty, c.value);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_constant_s_doc_of_several_lines_stays_a_doc() {
        let mut out = String::new();
        let c = Const {
            doc: "Formulas.\n\nThe first 2 of 3.".into(),
            name: "FORMULAS",
            ty: "&'static [u8]".into(),
            value: "&[1, 2]".into(),
        };
        konst(&mut out, &c);
        assert_eq!(
            out,
            "/// Formulas.\n///\n/// The first 2 of 3.\npub const FORMULAS: &'static [u8] = &[1, 2];\n"
        );
        assert!(out.parse::<TokenStream>().is_ok());
    }
}
