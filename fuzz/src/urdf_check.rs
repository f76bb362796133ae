//! The oracle of the URDF fuzz target, also compiled into `kinegen-cli`'s mutation test
//! (`kinegen-cli/tests/urdf_mutants.rs` includes this file by path).
//!
//! Whatever the URDF reader refuses, it refuses with messages that name the file and a
//! line of it. Whatever it accepts and builds a chain of (default base and tip, default
//! snap), the engine's model of that chain — what the generated code computes — equals
//! an independent numeric reference computed here from the parsed joints (origins, axes,
//! joint types), within what snapping may move: [`DEFAULT_SNAP`] per snapped angle and
//! length. Any difference panics.

use kinegen_core::chain::urdf::{Selection, DEFAULT_SNAP};
use kinegen_core::front::located::LoadError;
use kinegen_core::front::urdf::{Joint, JointType, Urdf};
use kinegen_core::numeric::rpy_transform;
use kinegen_core::{derive, generate, Chain, ItemHeader, Options};
use nalgebra::{Matrix4, Rotation3, Unit, Vector3};

/// Chains with more joints are only built, not generated (time per input).
pub const MAX_JOINTS: usize = 8;

/// What happened to an input.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UrdfOutcome {
    /// The XML or the URDF was refused, with located messages.
    Rejected,
    /// Parsed, but no chain could be built (default base and tip), with located messages.
    NoChain,
    /// A chain was built (not generated: too long, not asked for, or numbers too large
    /// to compare).
    Built,
    /// Built, generated, and its model equals the numeric reference.
    Checked,
}

/// Every message names `label` and a line of it (`label:N: …`, N ≥ 1).
pub fn check_error(e: &LoadError, label: &str) {
    assert!(!e.errors.is_empty(), "an error without a message");
    for err in &e.errors {
        assert!(err.line >= 1, "no line: {err}");
        let text = err.to_string();
        assert!(
            text.starts_with(&format!("{label}:{}:", err.line)),
            "{text}"
        );
    }
}

/// Parse `src` and build its default chain with the engine's own loader; if it loads and
/// `generate_it`, generate it and compare its model with the numeric reference at joint
/// values from `q_seed`.
pub fn urdf(src: &str, q_seed: &[f64], generate_it: bool) -> UrdfOutcome {
    let engine = |u: &Urdf| u.chain(&Selection::default());
    load_and_check(src, "fuzz.urdf", engine, || generate_it, q_seed, true)
}

/// Parse `src` (named `label`), build its chain with `build`, and where `check()` says so
/// (it is asked once per built chain) compare its model with the reference
/// ([`chain_outcome`]; `with_code`: generate too).
pub fn load_and_check(
    src: &str,
    label: &str,
    build: impl Fn(&Urdf) -> Result<Chain, LoadError>,
    mut check: impl FnMut() -> bool,
    q_seed: &[f64],
    with_code: bool,
) -> UrdfOutcome {
    let urdf = match Urdf::parse(src, label) {
        Ok(u) => u,
        Err(e) => {
            check_error(&e, label);
            return UrdfOutcome::Rejected;
        }
    };
    match build(&urdf) {
        Err(e) => {
            check_error(&e, label);
            UrdfOutcome::NoChain
        }
        Ok(chain) if check() => chain_outcome(&urdf, &chain, q_seed, with_code),
        Ok(_) => UrdfOutcome::Built,
    }
}

/// The model of `chain` (the default chain of `urdf`) — with `with_code`, also the
/// generated code, checked free of internal errors — compared with the reference.
pub fn chain_outcome(urdf: &Urdf, chain: &Chain, q_seed: &[f64], with_code: bool) -> UrdfOutcome {
    let (_, _, joints) = urdf.path(None, None).expect("the chain was built from it");
    let n = chain.dof();
    assert_eq!(
        n,
        joints.iter().filter(|j| j.kind != JointType::Fixed).count(),
        "one chain joint per moving URDF joint"
    );
    if n > MAX_JOINTS {
        return UrdfOutcome::Built;
    }
    // The sum of the origins' offsets: the arm's size.
    let scale: f64 = joints
        .iter()
        .flat_map(|j| j.xyz.iter().map(|x| x.to_f64().abs()))
        .sum();
    // (NaN fails too.)
    if scale.is_nan() || scale >= 1e4 {
        return UrdfOutcome::Built; // rounding would swamp any tolerance
    }
    let mut options = Options::default();
    options.budget.nodes = options.budget.nodes.min(1_000);
    if with_code {
        let code = generate(chain, &ItemHeader::public("Fuzzed"), &options).pretty();
        assert!(
            !code.contains("compile_error"),
            "internal error in the generated code:\n{}",
            &code[..code.len().min(2000)]
        );
    }
    let q: Vec<f64> = (0..n)
        .map(|i| q_seed.get(i).copied().unwrap_or(0.3 * i as f64 + 0.1))
        .collect();
    let model = derive(chain, &options).model;
    let got = model.eval(chain, &q, &model.fk_rows.concat());
    let want = reference_fk(&joints, &q);
    // Each snapped angle (three per origin, the axis) turns what follows by at most the
    // snap, each snapped length moves it by at most the snap.
    let m = joints.len() as f64;
    let snapped = DEFAULT_SNAP * 4.0 * m * (1.0 + scale + m);
    for r in 0..3 {
        for c in 0..4 {
            let (x, y) = (got[r * 4 + c], want[(r, c)]);
            let tol = 1e-9 * (1.0 + scale + 4.0 * m) + snapped;
            assert!(
                (x - y).abs() <= tol,
                "fk[{r}][{c}] at q = {q:?}: engine {x} vs reference {y} (tolerance {tol:e})"
            );
        }
    }
    UrdfOutcome::Checked
}

/// The tool pose by the URDF specification: per joint on the path, its origin
/// (`xyz`, then `rpy` as fixed-axis roll, pitch, yaw), then its motion about or along its
/// unit axis; the moving joints take `q` in order.
pub fn reference_fk(joints: &[&Joint], q: &[f64]) -> Matrix4<f64> {
    let mut t = Matrix4::identity();
    let mut k = 0;
    for j in joints {
        let f = |x: &[kinegen_core::front::urdf::Number; 3]| {
            [x[0].to_f64(), x[1].to_f64(), x[2].to_f64()]
        };
        t *= rpy_transform(f(&j.xyz), f(&j.rpy));
        // Scaled before normalising: `1e300 0 1` squared overflows.
        let axis = Vector3::from(f(&j.axis));
        let axis = axis / axis.amax();
        let motion = match j.kind {
            JointType::Fixed => continue,
            JointType::Revolute | JointType::Continuous => {
                Rotation3::from_axis_angle(&Unit::new_normalize(axis), q[k]).to_homogeneous()
            }
            JointType::Prismatic => Matrix4::new_translation(&(axis.normalize() * q[k])),
            JointType::Floating | JointType::Planar => unreachable!("no chain has them"),
        };
        t *= motion;
        k += 1;
    }
    t
}
