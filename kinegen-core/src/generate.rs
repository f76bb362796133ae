//! The engine's entry point, as the pipeline it runs: a [`Chain`] in, a
//! pretty-printable Rust item out.
//!
//! ```text
//! Chain ─ simplify::order ─▶ Model ─ det ─▶ DetModel ─ second order ─▶ SecondOrder, DetGradient
//!       ─ emit::functions ─▶ Functions ─ emit::rust ─▶ tokens
//! ```

use std::time::Instant;

use proc_macro2::TokenStream;

use crate::chain::Chain;
use crate::emit::functions::{functions, Functions, Stats};
use crate::emit::rust::{lex, print, ItemHeader};
use crate::kinematics::det::closed_form::{self, DetModel};
use crate::kinematics::det::gradient::{det_gradient, DetGradient};
use crate::kinematics::det::structural::square_rows;
use crate::kinematics::ik::{self, IkModel};
use crate::kinematics::model::Model;
use crate::kinematics::second_order::{second_order, SecondOrder};
use crate::model::options::{Deadline, Options};
use crate::simplify::order::cheapest;
use crate::simplify::pass::simplify_second_order;

/// The engine's output.
#[derive(Clone, Debug)]
pub struct Generated {
    /// The item: struct, inherent impl, trait impls.
    pub tokens: TokenStream,
    /// Compile-time notes: fallbacks taken, budgets hit (empty when the engine did
    /// everything it can). Not part of `tokens`: the `kinematics!` macro reports each
    /// as a compiler warning.
    pub notes: Vec<String>,
    /// Operation counts of the main outputs.
    pub stats: Stats,
    /// Wall time of each stage.
    pub times: StageTimes,
}

/// Wall time of each engine stage, in milliseconds: where the time a user waits for in
/// `cargo build` goes (`kinegen stats` prints it).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StageTimes {
    /// FK, frames and Jacobians: every candidate evaluation order simplified, the
    /// cheapest kept.
    pub order_ms: f64,
    /// The factored determinant and its singular factors.
    pub det_ms: f64,
    /// Hessian, `J̇`, `J̇ q̇`, `J̇_ee` with their simplification, and the determinant's
    /// gradient.
    pub second_order_ms: f64,
    /// The closed-form IK: family decided from the exact axes, geometry planned.
    pub ik_ms: f64,
    /// Every method's straight-line code and doc (`emit::functions`; 0 from [`derive()`]).
    pub emit_ms: f64,
    /// Of `emit_ms`, the closed-form IK's items.
    pub ik_emit_ms: f64,
    /// Printing the item and lexing it into tokens (0 from [`derive()`]).
    pub print_ms: f64,
}

/// Milliseconds since `t`, and restarts it.
fn lap(t: &mut Instant) -> f64 {
    let now = Instant::now();
    let ms = (now - *t).as_secs_f64() * 1e3;
    *t = now;
    ms
}

impl Generated {
    /// The generated code, pretty-printed.
    pub fn pretty(&self) -> String {
        match syn::parse2::<syn::File>(self.tokens.clone()) {
            Ok(file) => prettyplease::unparse(&file),
            Err(_) => self.tokens.to_string(),
        }
    }
}

/// The symbolic results for a chain, before anything is printed.
#[derive(Clone, Debug)]
pub struct Derived {
    /// FK, frames and Jacobians, simplified, in the cheapest evaluation order.
    pub model: Model,
    /// The closed-form determinant of the square Jacobian (`Err`: why not; `None`: the
    /// Jacobian is not square).
    pub det: Option<Result<DetModel, String>>,
    /// The Hessian, `J̇`, `J̇ q̇` and `J̇_ee`, built on the model's Jacobian.
    pub second: SecondOrder,
    /// The gradient of the closed-form determinant and of its factors (`None`: no closed
    /// form; `Err`: why not).
    pub det_gradient: Option<Result<DetGradient, String>>,
    /// Closed-form IK (`Err`: why no family fits). An f32 robot's is solved in f64 at run
    /// time (see `emit::ik`).
    pub ik: Result<IkModel, String>,
    /// Wall time of the symbolic stages (`emit_ms`, `print_ms` are 0).
    pub times: StageTimes,
}

/// Generate the Rust item for a chain, within `options.budget` (its `time_ms` counts
/// from here, for the whole engine).
///
/// ```
/// use kinegen_core::{front::toml_file::load_str, generate, ItemHeader};
/// let src = "name = \"RR\"\nconvention = \"standard\"\n[params]\nL1 = 1.0\nL2 = 0.8\n\
///            [[joints]]\ntype = \"revolute\"\na = \"L1\"\nalpha = 0\nd = 0\n\
///            [[joints]]\ntype = \"revolute\"\na = \"L2\"\nalpha = 0\nd = 0\n";
/// let (robot, options) = load_str(src, "rr.toml").unwrap();
/// let code = generate(&robot.chain(), &ItemHeader::public("RR"), &options).pretty();
/// assert!(code.contains("pub fn jacobian(&self, q: &[f64; 2]) -> [[f64; 2]; 6]"));
/// ```
pub fn generate(chain: &Chain, header: &ItemHeader, options: &Options) -> Generated {
    let derived = derive(chain, options);
    let emitted = emit(chain, &derived);
    // The symbolic graph is let go before the item is printed and lexed: for a long
    // chain, graph, text and tokens alive together were the engine's peak of memory.
    drop(derived);
    print_and_lex(chain, header, emitted)
}

/// [`generate`] from the chain's [`derive()`]d results, for a caller that also reads them
/// (the CLI's `stats` and `report`): the chain is derived once.
///
/// ```
/// use kinegen_core::{derive, front::toml_file::load_str, generate, generate_from, ItemHeader};
/// let src = "name = \"RR\"\nconvention = \"standard\"\n[params]\nL1 = 1.0\nL2 = 0.8\n\
///            [[joints]]\ntype = \"revolute\"\na = \"L1\"\nalpha = 0\nd = 0\n\
///            [[joints]]\ntype = \"revolute\"\na = \"L2\"\nalpha = 0\nd = 0\n";
/// let (robot, options) = load_str(src, "rr.toml").unwrap();
/// let chain = robot.chain();
/// let derived = derive(&chain, &options);
/// let header = ItemHeader::public("RR");
/// let code = generate_from(&chain, &header, &derived).pretty();
/// assert_eq!(code, generate(&chain, &header, &options).pretty());
/// ```
pub fn generate_from(chain: &Chain, header: &ItemHeader, derived: &Derived) -> Generated {
    print_and_lex(chain, header, emit(chain, derived))
}

/// What the type holds, from the derived results: each method's straight-line code and
/// doc, the constants; with the stage times so far and the derivation's notes.
struct Emitted {
    functions: Functions,
    times: StageTimes,
    notes: Vec<String>,
}

fn emit(chain: &Chain, derived: &Derived) -> Emitted {
    let mut times = derived.times;
    let mut t = Instant::now();
    let functions = functions(
        chain,
        &derived.model,
        &derived.det,
        &derived.second,
        &derived.det_gradient,
        &derived.ik,
    );
    times.emit_ms = lap(&mut t);
    times.ik_emit_ms = functions.ik_emit_ms;
    Emitted {
        functions,
        times,
        notes: derived.model.notes.clone(),
    }
}

/// The item printed, the methods' code let go, then the text lexed into tokens.
fn print_and_lex(chain: &Chain, header: &ItemHeader, emitted: Emitted) -> Generated {
    let Emitted {
        functions,
        mut times,
        mut notes,
    } = emitted;
    let mut t = Instant::now();
    let text = print(chain, header, &functions);
    let Functions {
        stats,
        notes: emit_notes,
        ..
    } = functions;
    let tokens = lex(&text);
    times.print_ms = lap(&mut t);
    notes.extend(emit_notes);
    Generated {
        tokens,
        notes,
        stats,
        times,
    }
}

/// The symbolic stages of [`generate`]: what the CLI shows and evaluates.
pub fn derive(chain: &Chain, options: &Options) -> Derived {
    let deadline = Deadline::start(&options.budget);
    let mut times = StageTimes::default();
    let mut t = Instant::now();
    // FK, frames and Jacobians in each candidate evaluation order (middle frame), each
    // simplified — e-graph polish, fewest negations, every rewrite checked — and the
    // cheapest kept.
    let mut model = cheapest(chain, options, deadline);
    times.order_ms = lap(&mut t);
    // The determinant of the square Jacobian, factored, in closed form.
    let det = square_rows(chain).map(|_| closed_form::determinant(chain, &mut model));
    times.det_ms = lap(&mut t);
    // Second order on the simplified Jacobian's nodes: Hessian, J̇, J̇q̇, J̇_ee, with
    // signs moved for the fewest negations (checked); the determinant's gradient.
    let mut second = second_order(chain, &mut model);
    simplify_second_order(&mut model, &mut second);
    let det_gradient = match &det {
        Some(Ok(d)) => Some(det_gradient(&mut model, d, chain.dof())),
        _ => None,
    };
    times.second_order_ms = lap(&mut t);
    // The IK family, decided exactly from the axes at q = 0, and its geometry.
    let ik = ik::model(chain, options.budget.max_terms(), options.ik_free);
    times.ik_ms = lap(&mut t);
    Derived {
        model,
        det,
        second,
        det_gradient,
        ik,
        times,
    }
}
