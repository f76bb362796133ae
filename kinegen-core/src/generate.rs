//! The engine's entry point, as the pipeline it runs: a [`Chain`] in, a
//! pretty-printable Rust item out.
//!
//! ```text
//! Chain ─ simplify::order ─▶ Model ─ det ─▶ DetModel ─ second order ─▶ SecondOrder, DetGradient
//!       ─ emit::functions ─▶ Functions ─ emit::rust ─▶ tokens
//! ```

use proc_macro2::TokenStream;

use crate::chain::Chain;
use crate::emit::functions::{functions, Stats};
use crate::emit::rust::{item, ItemHeader};
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
    // What the type holds: each method's straight-line code and doc, the constants.
    let functions = functions(
        chain,
        &derived.model,
        &derived.det,
        &derived.second,
        &derived.det_gradient,
        &derived.ik,
    );
    // Printed, and parsed into tokens.
    let tokens = item(chain, header, &functions);
    let mut notes = derived.model.notes;
    notes.extend(functions.notes);
    Generated {
        tokens,
        notes,
        stats: functions.stats,
    }
}

/// The symbolic stages of [`generate`]: what the CLI shows and evaluates.
pub fn derive(chain: &Chain, options: &Options) -> Derived {
    let deadline = Deadline::start(&options.budget);
    // FK, frames and Jacobians in each candidate evaluation order (middle frame), each
    // simplified — e-graph polish, fewest negations, every rewrite checked — and the
    // cheapest kept.
    let mut model = cheapest(chain, options, deadline);
    // The determinant of the square Jacobian, factored, in closed form.
    let det = square_rows(chain).map(|_| closed_form::determinant(chain, &mut model));
    // Second order on the simplified Jacobian's nodes: Hessian, J̇, J̇q̇, J̇_ee, with
    // signs moved for the fewest negations (checked); the determinant's gradient.
    let mut second = second_order(chain, &mut model);
    simplify_second_order(&mut model, &mut second);
    let det_gradient = match &det {
        Some(Ok(d)) => Some(det_gradient(&mut model, d, chain.dof())),
        _ => None,
    };
    // The IK family, decided exactly from the axes at q = 0, and its geometry.
    let ik = ik::model(chain, options.budget.max_terms());
    Derived {
        model,
        det,
        second,
        det_gradient,
        ik,
    }
}
