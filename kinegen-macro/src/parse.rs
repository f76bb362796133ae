//! Tokens → [`RawRobot`], remembering where every entry was written.
//!
//! ```text
//! #[attrs] vis struct Name;                 // or: vis struct Name = "robots/x.toml";
//!                                           // or: vis struct Name = urdf("x.urdf", base = "b", tip = "t");
//! key: value, ...                           // name, convention, params, joints, task,
//!                                           // base, tool, scalar, budget, ik_free (URDF:
//!                                           // name, params (a table, or `auto`), task, scalar, budget, snap,
//!                                           // ik_free)
//! ```
//! Values are token expressions (`pi/2`, `-a2`, `0.5*L1`), turned into text for
//! `kinegen_core::model::value::parse_value`; only the *shape* (which keys, lists, rows) is
//! checked here. The DH rules are `kinegen_core::model::validate::validate`'s.

use kinegen_core::model::input;
use kinegen_core::model::raw::{DhError, Path, RawJoint, RawRobot, RawValue};
use kinegen_core::model::value::{parse_decimal, rat_to_f64};
use kinegen_core::Budget;
use proc_macro2::{Delimiter, Group, TokenStream, TokenTree};
use quote::ToTokens;
use syn::ext::IdentExt;
use syn::parse::{Parse, ParseStream, Parser};
use syn::{Attribute, Ident, Lit, LitStr, Token, Visibility};

use crate::report::Spans;

/// The macro input, read but not validated.
pub struct Input {
    /// Outer attributes for the generated struct (doc comments, derives).
    pub attrs: Vec<Attribute>,
    /// Visibility of the generated struct.
    pub vis: Visibility,
    /// Name of the generated struct.
    pub ident: Ident,
    /// The file of the file form (`struct Ur5 = "robots/ur5.toml";`).
    pub file: Option<LitStr>,
    /// The URDF form (`struct Ur5 = urdf("ur5.urdf", base = "base_link", tip = "tool0");`).
    pub urdf: Option<UrdfCall>,
    /// `snap: 1e-4` (URDF), with its tokens; `Err` with the message if it is not a
    /// number.
    pub snap: Option<(TokenStream, Result<f64, String>)>,
    /// `ik_free: 7`, with its tokens; `Err` with the message if it is not a joint number.
    pub ik_free: Option<(TokenStream, Result<usize, String>)>,
    /// `params: auto` (URDF): every length of the chain named.
    pub symbolic: bool,
    /// The entries written in the macro.
    pub robot: RawRobot,
    /// `budget: { .. }`, if written.
    pub budget: Option<Budget>,
    /// Top-level keys written in the macro (in the file form, they override the file's).
    pub keys: Vec<String>,
    /// Where each entry is.
    pub spans: Spans,
    /// Entries of the wrong shape, reported together with the validation errors.
    pub shape_errors: Vec<DhError>,
}

/// `urdf("file.urdf", base = "link", tip = "link")`.
pub struct UrdfCall {
    /// The file, relative to the crate's manifest.
    pub file: LitStr,
    /// `base = "…"`.
    pub base: Option<LitStr>,
    /// `tip = "…"`.
    pub tip: Option<LitStr>,
}

impl Parse for UrdfCall {
    fn parse(stream: ParseStream) -> syn::Result<Self> {
        let file: LitStr = stream.parse()?;
        let mut call = UrdfCall {
            file,
            base: None,
            tip: None,
        };
        while !stream.is_empty() {
            stream.parse::<Token![,]>()?;
            if stream.is_empty() {
                break;
            }
            let key: Ident = stream.parse()?;
            stream.parse::<Token![=]>()?;
            let value: LitStr = stream.parse()?;
            let slot = match key.to_string().as_str() {
                "base" => &mut call.base,
                "tip" => &mut call.tip,
                other => {
                    return Err(syn::Error::new(
                        key.span(),
                        format!("unknown argument `{other}`: `urdf(\"file.urdf\", base = \"link\", tip = \"link\")`"),
                    ))
                }
            };
            if slot.replace(value).is_some() {
                return Err(syn::Error::new(
                    key.span(),
                    input::given_twice(&key.to_string()),
                ));
            }
        }
        Ok(call)
    }
}

impl Parse for Input {
    fn parse(stream: ParseStream) -> syn::Result<Self> {
        let attrs = stream.call(Attribute::parse_outer)?;
        let vis: Visibility = stream.parse()?;
        stream.parse::<Token![struct]>()?;
        let ident: Ident = stream.parse()?;
        let (mut file, mut urdf) = (None, None);
        if stream.peek(Token![=]) {
            stream.parse::<Token![=]>()?;
            if stream.peek(Ident) {
                let form: Ident = stream.parse()?;
                if form != "urdf" {
                    return Err(syn::Error::new(
                        form.span(),
                        "expected a TOML file `\"robot.toml\"` or `urdf(\"robot.urdf\", base = \"…\", tip = \"…\")`",
                    ));
                }
                let args;
                syn::parenthesized!(args in stream);
                urdf = Some(args.parse::<UrdfCall>()?);
            } else {
                file = Some(stream.parse::<LitStr>()?);
            }
        }
        stream.parse::<Token![;]>()?;

        let mut r = Reader {
            urdf: urdf.is_some(),
            ..Reader::default()
        };
        // Whole-robot errors (missing `convention`) point at the struct's name.
        r.spans.insert(Path::root(), ident.to_token_stream());
        let mut input = Input {
            attrs,
            vis,
            ident,
            file,
            urdf,
            snap: None,
            ik_free: None,
            symbolic: false,
            robot: RawRobot::default(),
            budget: None,
            keys: Vec::new(),
            spans: Spans::default(),
            shape_errors: Vec::new(),
        };
        for entry in entries(stream)? {
            let key = entry.key.to_string();
            if input.keys.contains(&key) {
                r.syntax
                    .push(syn::Error::new(entry.key.span(), input::given_twice(&key)));
                continue;
            }
            input.keys.push(key.clone());
            if key == "snap" && r.urdf {
                let text = expr_text(&entry.value);
                let value = parse_decimal(text.trim_start_matches('+'))
                    .map(|v| rat_to_f64(&v))
                    .map_err(|_| {
                        format!(
                            "`snap` is a tolerance in radians / metres, e.g. `1e-4`, not `{text}`"
                        )
                    });
                r.spans.insert(Path::root().key("snap"), entry.tokens());
                input.snap = Some((entry.tokens(), value));
                continue;
            }
            if key == "params" && r.urdf && expr_text(&entry.value).trim() == "auto" {
                r.spans.insert(Path::root().key("params"), entry.tokens());
                input.symbolic = true;
                continue;
            }
            if key == "ik_free" {
                let text = expr_text(&entry.value);
                let value = input::ik_free_value(text.trim().parse::<i128>().ok());
                r.spans.insert(Path::root().key("ik_free"), entry.tokens());
                input.ik_free = Some((entry.tokens(), value));
                continue;
            }
            r.top(&entry, &mut input.robot, &mut input.budget);
        }
        if let Some(e) = crate::report::combine(r.syntax) {
            return Err(e);
        }
        input.spans = r.spans;
        input.shape_errors = r.errors;
        Ok(input)
    }
}

/// `key: value` as written; `value` is every token up to the next comma at this level.
struct Entry {
    key: Ident,
    value: Vec<TokenTree>,
}

impl Entry {
    /// Key through value, for underlining the whole entry.
    fn tokens(&self) -> TokenStream {
        let mut t = self.key.to_token_stream();
        t.extend(self.value.iter().cloned());
        t
    }

    fn value_tokens(&self) -> TokenStream {
        self.value.iter().cloned().collect()
    }
}

/// `key: value, key: value, ...` with an optional trailing comma.
fn entries(stream: ParseStream) -> syn::Result<Vec<Entry>> {
    let mut out = Vec::new();
    while !stream.is_empty() {
        // Keywords are fine as keys (`type`), and misspelt ones get our message.
        let key = Ident::parse_any(stream)?;
        stream.parse::<Token![:]>()?;
        let mut value = Vec::new();
        while !stream.is_empty() && !stream.peek(Token![,]) {
            value.push(stream.parse::<TokenTree>()?);
        }
        if value.is_empty() {
            return Err(syn::Error::new(key.span(), format!("`{key}` has no value")));
        }
        out.push(Entry { key, value });
        if !stream.is_empty() {
            stream.parse::<Token![,]>()?;
        }
    }
    Ok(out)
}

/// The group if `value` is exactly one group with this delimiter.
fn single_group(value: &[TokenTree], delimiter: Delimiter) -> Option<&Group> {
    match value {
        [TokenTree::Group(g)] if g.delimiter() == delimiter => Some(g),
        _ => None,
    }
}

/// Split a token stream at its top-level commas (nested groups keep theirs).
fn split_commas(stream: TokenStream) -> Vec<Vec<TokenTree>> {
    let mut out = vec![Vec::new()];
    for tt in stream {
        match &tt {
            TokenTree::Punct(p) if p.as_char() == ',' => out.push(Vec::new()),
            _ => {
                if let Some(last) = out.last_mut() {
                    last.push(tt);
                }
            }
        }
    }
    if out.last().is_some_and(Vec::is_empty) {
        out.pop();
    }
    out
}

/// An expression's text as a person would write it: `pi/2`, `-a2`, `d1 + 0.1`.
/// (`TokenStream::to_string` would give `pi / 2`, and messages quote this text.)
fn expr_text(tokens: &[TokenTree]) -> String {
    let mut s = String::new();
    // Whether the previous token ends an operand, making `+`/`-` binary.
    let mut after_operand = false;
    for tt in tokens {
        match tt {
            TokenTree::Punct(p) => {
                let c = p.as_char();
                if after_operand && (c == '+' || c == '-') {
                    s.push(' ');
                    s.push(c);
                    s.push(' ');
                } else {
                    s.push(c);
                }
                after_operand = false;
            }
            TokenTree::Ident(_) | TokenTree::Literal(_) => {
                if after_operand {
                    s.push(' ');
                }
                s.push_str(&tt.to_string());
                after_operand = true;
            }
            TokenTree::Group(g) => {
                let inner: Vec<TokenTree> = g.stream().into_iter().collect();
                let (open, close) = match g.delimiter() {
                    Delimiter::Parenthesis => ("(", ")"),
                    Delimiter::Bracket => ("[", "]"),
                    Delimiter::Brace => ("{", "}"),
                    Delimiter::None => ("", ""),
                };
                if after_operand {
                    s.push(' ');
                }
                s.push_str(open);
                s.push_str(&expr_text(&inner));
                s.push_str(close);
                after_operand = true;
            }
        }
    }
    s
}

#[derive(Default)]
struct Reader {
    /// The URDF form: `convention`, `joints`, `base`, `tool` do not apply.
    urdf: bool,
    spans: Spans,
    /// Shape errors with a path (filtered against validation errors later).
    errors: Vec<DhError>,
    /// Errors that are about syntax, not a path (a duplicate top-level key).
    syntax: Vec<syn::Error>,
}

impl Reader {
    fn shape(&mut self, path: Path, tokens: TokenStream, message: impl Into<String>) {
        self.spans.insert(path.clone(), tokens);
        self.errors.push(DhError {
            path,
            message: message.into(),
        });
    }

    fn top(&mut self, e: &Entry, robot: &mut RawRobot, budget: &mut Option<Budget>) {
        let key = e.key.to_string();
        let p = Path::root().key(&key);
        self.spans.insert(p.clone(), e.tokens());
        if self.urdf && ["convention", "joints", "base", "tool"].contains(&key.as_str()) {
            let msg = format!(
                "`{key}` belongs to a DH table; the URDF form takes name, params, task, scalar, budget, snap and ik_free \
                 (base and tip go in `urdf(..)`)"
            );
            self.shape(p, e.key.to_token_stream(), msg);
            return;
        }
        match key.as_str() {
            "name" => match e.value.as_slice() {
                [TokenTree::Literal(l)] => match Lit::new(l.clone()) {
                    Lit::Str(s) => robot.name = Some(s.value()),
                    _ => self.shape(
                        p,
                        e.tokens(),
                        "`name` must be a string, e.g. `name: \"UR5\"`",
                    ),
                },
                _ => self.shape(
                    p,
                    e.tokens(),
                    "`name` must be a string, e.g. `name: \"UR5\"`",
                ),
            },
            "convention" => robot.convention = Some(word(&e.value)),
            "scalar" => robot.scalar = Some(word(&e.value)),
            "params" => robot.params = self.table(e, &p).unwrap_or_default(),
            "joints" => robot.joints = self.joints(e, &p),
            "task" => match self.value(&e.value, &p) {
                RawValue::List(items) => robot.task = Some(items),
                _ => self.shape(
                    p,
                    e.tokens(),
                    "`task` must be a list of rows such as `[x, y, rz]`",
                ),
            },
            "base" => robot.base = self.table(e, &p),
            "tool" => robot.tool = self.table(e, &p),
            "budget" => *budget = self.budget(e, &p),
            _ => self.shape(
                p,
                e.key.to_token_stream(),
                input::unknown_top_level_key(&key),
            ),
        }
    }

    /// An entry's value: a `[..]` list (of values) or an expression.
    fn value(&mut self, tokens: &[TokenTree], path: &Path) -> RawValue {
        if let Some(g) = single_group(tokens, Delimiter::Bracket) {
            let items = split_commas(g.stream())
                .iter()
                .enumerate()
                .map(|(i, item)| {
                    let ip = path.index(i);
                    self.spans
                        .insert(ip.clone(), item.iter().cloned().collect());
                    self.value(item, &ip)
                })
                .collect();
            return RawValue::List(items);
        }
        // A string literal holds the expression as in TOML files: `"pi/2"` = `pi/2`.
        if let [TokenTree::Literal(l)] = tokens {
            if let Lit::Str(s) = Lit::new(l.clone()) {
                return RawValue::Text(s.value());
            }
        }
        RawValue::Text(expr_text(tokens))
    }

    /// `{ key: value, ... }` (params, base, tool).
    fn table(&mut self, e: &Entry, path: &Path) -> Option<Vec<(String, RawValue)>> {
        let Some(g) = single_group(&e.value, Delimiter::Brace) else {
            let example = match path.to_string().as_str() {
                "params" => "`params: { L1: 1.0, L2: 0.5 }`",
                _ => "`{ xyz: [x, y, z], rpy: [roll, pitch, yaw] }`",
            };
            self.shape(
                path.clone(),
                e.value_tokens(),
                format!("`{path}` must be a braced table, e.g. {example}"),
            );
            return None;
        };
        match entries.parse2(g.stream()) {
            Ok(inner) => Some(
                inner
                    .iter()
                    .map(|ie| {
                        let kp = path.key(&ie.key.to_string());
                        self.spans.insert(kp.clone(), ie.tokens());
                        (ie.key.to_string(), self.value(&ie.value, &kp))
                    })
                    .collect(),
            ),
            Err(err) => {
                self.syntax.push(err);
                None
            }
        }
    }

    /// `[ revolute { a: .., alpha: .., d: .. }, prismatic { .. }, ... ]`.
    fn joints(&mut self, e: &Entry, path: &Path) -> Vec<RawJoint> {
        let Some(g) = single_group(&e.value, Delimiter::Bracket) else {
            self.shape(
                path.clone(),
                e.value_tokens(),
                "`joints` must be a list of rows, e.g. `[revolute { a: 0, alpha: pi/2, d: d1 }, ...]`",
            );
            return Vec::new();
        };
        let mut out = Vec::new();
        for (i, row) in split_commas(g.stream()).iter().enumerate() {
            let rp = path.index(i);
            let row_tokens: TokenStream = row.iter().cloned().collect();
            self.spans.insert(rp.clone(), row_tokens.clone());
            let (kind, body) = match row.as_slice() {
                [TokenTree::Ident(kind), TokenTree::Group(b)]
                    if b.delimiter() == Delimiter::Brace =>
                {
                    let tp = rp.key("type");
                    self.spans.insert(tp, kind.to_token_stream());
                    (Some(kind.to_string()), b)
                }
                // No type: the validator says "missing joint type" at the row.
                [TokenTree::Group(b)] if b.delimiter() == Delimiter::Brace => (None, b),
                _ => {
                    self.shape(
                        rp,
                        row_tokens,
                        "a joint row is written `revolute { a: .., alpha: .., d: .. }` or `prismatic { a: .., alpha: .., theta: .. }`",
                    );
                    continue;
                }
            };
            let fields = match entries.parse2(body.stream()) {
                Ok(fields) => fields,
                Err(err) => {
                    self.syntax.push(err);
                    continue;
                }
            };
            let mut joint = RawJoint {
                kind,
                fields: Vec::new(),
            };
            for f in &fields {
                let key = f.key.to_string();
                let fp = rp.key(&key);
                self.spans.insert(fp.clone(), f.tokens());
                let v = self.value(&f.value, &fp);
                joint.fields.push((key, v));
            }
            out.push(joint);
        }
        out
    }

    /// `{ nodes: 5000, iterations: 20, time_ms: 500 }`.
    fn budget(&mut self, e: &Entry, path: &Path) -> Option<Budget> {
        let Some(g) = single_group(&e.value, Delimiter::Brace) else {
            self.shape(
                path.clone(),
                e.value_tokens(),
                "`budget` must be a braced table, e.g. `{ nodes: 5000, iterations: 20, time_ms: 500 }`",
            );
            return None;
        };
        let inner = match entries.parse2(g.stream()) {
            Ok(inner) => inner,
            Err(err) => {
                self.syntax.push(err);
                return None;
            }
        };
        let mut budget = Budget::default();
        for ie in &inner {
            let key = ie.key.to_string();
            let n = match ie.value.as_slice() {
                [TokenTree::Literal(l)] => match Lit::new(l.clone()) {
                    Lit::Int(i) => i.base10_parse::<i128>().ok(),
                    _ => None,
                },
                _ => None,
            };
            if let Err(message) = input::set_budget(&mut budget, &key, n) {
                self.shape(path.key(&key), ie.tokens(), message);
            }
        }
        Some(budget)
    }
}

/// A one-word entry (`standard`, `f32`), also accepted as a string literal.
fn word(tokens: &[TokenTree]) -> String {
    if let [TokenTree::Literal(l)] = tokens {
        if let Lit::Str(s) = Lit::new(l.clone()) {
            return s.value();
        }
    }
    expr_text(tokens)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(src: &str) -> String {
        let tokens: Vec<TokenTree> = src.parse::<TokenStream>().unwrap().into_iter().collect();
        expr_text(&tokens)
    }

    #[test]
    fn expressions_print_as_written() {
        assert_eq!(text("pi / 2"), "pi/2");
        assert_eq!(text("-a2"), "-a2");
        assert_eq!(text("0.5*L1"), "0.5*L1");
        assert_eq!(text("d1+0.1"), "d1 + 0.1");
        assert_eq!(text("pi/2 - t0"), "pi/2 - t0");
        assert_eq!(text("2*-pi"), "2*-pi");
        assert_eq!(text("-(pi/3)"), "-(pi/3)");
        assert_eq!(text("pi pi"), "pi pi");
        assert_eq!(text("1e-3"), "1e-3");
    }

    #[test]
    fn commas_split_at_top_level_only() {
        let s: TokenStream = "a, f(b, c), [d, e],".parse().unwrap();
        assert_eq!(split_commas(s).len(), 3);
    }
}
