//! The oracle of the fuzz targets, also compiled into kinegen-core's tests
//! (`fuzz_regressions.rs`, `front_end_props.rs` include this file by path), so a crashing
//! input is replayed there with exactly the checks that caught it.
//!
//! Whatever the front end accepts must generate code without an internal error, and the
//! engine's model (what the code computes, evaluated node by node) must equal the numeric
//! reference of `kinegen_core::numeric`: FK, both Jacobians, the closed-form determinant
//! when there is one, the Hessian and `J̇ q̇`. Any difference panics.

use kinegen_core::numeric::{self, NumericRobot};
use kinegen_core::{derive, front::toml_file, generate, Derived, ItemHeader, Options, Robot};

/// Tables with more joints are only loaded, not generated (time per input).
pub const MAX_JOINTS: usize = 8;
/// Cap on the `nodes` budget a fuzzed file may ask for (time per input).
pub const MAX_NODES: usize = 1_000;

/// What happened to an input.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// The front end refused it with an error message.
    Rejected,
    /// Accepted, but too large or with entries too large to compare numerically;
    /// generated without an internal error when small enough.
    Generated,
    /// Accepted, generated, and the model equals the numeric reference.
    Checked,
}

/// Load TOML text; if it loads, generate and check it at joint values from `q_seed`.
pub fn toml(src: &str, q_seed: &[f64]) -> Outcome {
    match toml_file::load_str(src, "fuzz.toml") {
        Err(e) => {
            // Every error names the file and says something.
            assert!(!e.errors.is_empty(), "an error without a message");
            let text = e.to_string();
            assert!(text.starts_with("fuzz.toml"), "{text}");
            Outcome::Rejected
        }
        Ok((robot, mut options)) => {
            options.budget.nodes = options.budget.nodes.min(MAX_NODES);
            robot_outcome(&robot, &options, q_seed)
        }
    }
}

/// Generate a checked robot and compare its model with the numeric reference.
pub fn robot_outcome(robot: &Robot, options: &Options, q_seed: &[f64]) -> Outcome {
    if robot.dof() > MAX_JOINTS {
        return Outcome::Generated;
    }
    let g = generate(&robot.chain(), &ItemHeader::public(&robot.name), options);
    let code = g.pretty();
    assert!(
        !code.contains("compile_error"),
        "internal error in the generated code:\n{}",
        &code[..code.len().min(2000)]
    );
    let shadowed = shadowed_locals(&code);
    assert!(
        shadowed.is_empty(),
        "generated locals bound twice in one function (fn, name): {shadowed:?}"
    );
    let Ok(num) = NumericRobot::new(robot) else {
        return Outcome::Generated; // a non-finite entry: nothing to compare
    };
    let scale = length_scale(&num);
    // (length_scale is infinite, never NaN, when an entry is not finite.)
    if scale >= 1e4 {
        return Outcome::Generated; // rounding would swamp any tolerance
    }
    let chain = robot.chain();
    let Derived {
        model, det, second, ..
    } = derive(&chain, options);
    let det = det.and_then(Result::ok);
    let n = robot.dof();
    let q: Vec<f64> = (0..n)
        .map(|i| {
            let x = q_seed.get(i).copied().unwrap_or(0.3 * i as f64 + 0.1);
            if x.is_finite() {
                x.clamp(-4.0, 4.0)
            } else {
                0.5
            }
        })
        .collect();
    // Prismatic joint values add up to 4 each to the lengths.
    let tol = |want: f64| 1e-9 * (1.0 + want.abs() + scale + 4.0 * n as f64);
    let t = num.fk(&q).unwrap();
    let fk: Vec<_> = model.fk_rows.iter().flatten().copied().collect();
    let got = model.eval(&chain, &q, &fk);
    for r in 0..3 {
        for c in 0..4 {
            let want = t[(r, c)];
            assert!(
                (got[r * 4 + c] - want).abs() <= tol(want),
                "fk[{r}][{c}] at q = {q:?}: engine {} vs numeric {want}",
                got[r * 4 + c]
            );
        }
    }
    let j = num.jacobian(&q).unwrap();
    let jee = num.jacobian_ee(&q).unwrap();
    for (rows, reference, name) in [
        (&model.jacobian, &j, "J"),
        (&model.jacobian_ee, &jee, "Jee"),
    ] {
        let ids: Vec<_> = rows.iter().flatten().copied().collect();
        let got = model.eval(&chain, &q, &ids);
        for r in 0..6 {
            for c in 0..n {
                let want = reference[(r, c)];
                assert!(
                    (got[r * n + c] - want).abs() <= tol(want),
                    "{name}[{r}][{c}] at q = {q:?}: engine {} vs numeric {want}",
                    got[r * n + c]
                );
            }
        }
    }
    if robot.task.is_some() {
        let reference = num.task_jacobian(&q).unwrap();
        let ids: Vec<_> = model.task.iter().flatten().copied().collect();
        let got = model.eval(&chain, &q, &ids);
        assert_eq!(got.len(), reference.nrows() * n, "task Jacobian shape");
        for r in 0..reference.nrows() {
            for c in 0..n {
                let want = reference[(r, c)];
                assert!(
                    (got[r * n + c] - want).abs() <= tol(want),
                    "Jt[{r}][{c}] at q = {q:?}: engine {} vs numeric {want}",
                    got[r * n + c]
                );
            }
        }
    }
    // Second order: the Hessian against the reference's cross products, J̇q̇ against its
    // acceleration propagation (rates of order one, so q̇² adds no scale).
    let h = num.hessian(&q).unwrap();
    for (k, hk) in second.hessian.iter().enumerate() {
        let ids: Vec<_> = hk.iter().flatten().copied().collect();
        let got = model.eval(&chain, &q, &ids);
        for r in 0..6 {
            for c in 0..n {
                let want = h[k][(r, c)];
                assert!(
                    (got[r * n + c] - want).abs() <= tol(want),
                    "H[{k}][{r}][{c}] at q = {q:?}: engine {} vs numeric {want}",
                    got[r * n + c]
                );
            }
        }
    }
    let qd: Vec<f64> = (0..n).map(|i| 0.7 - 0.3 * i as f64).collect();
    let want = num.jdot_qdot_propagation(&q, &qd).unwrap();
    let got = model.eval_with_rates(&chain, &q, Some(&qd), &second.jdot_qdot);
    for r in 0..6 {
        assert!(
            (got[r] - want[r]).abs() <= tol(want[r]),
            "J̇q̇[{r}] at q = {q:?}, qd = {qd:?}: engine {} vs numeric {}",
            got[r],
            want[r]
        );
    }
    if let Some(d) = &det {
        // The rows the determinant is of (the task rows, or all six for a 6-joint arm).
        let m = nalgebra::DMatrix::from_fn(d.rows.len(), n, |r, c| j[(d.rows[r], c)]);
        let want = numeric::det(&m).unwrap();
        let hadamard: f64 = m.column_iter().map(|c| c.norm()).product();
        let got = model.eval(&chain, &q, &[d.node])[0];
        assert!(
            (got - want).abs() <= 1e-9 * want.abs() + 1e-11 * hadamard,
            "det J at q = {q:?}: engine {got} ({}) vs numeric {want}",
            d.text
        );
    }
    Outcome::Checked
}

/// A length scale of the arm: the sum of its link lengths and offsets and of the base
/// and tool translations (infinite if anything is not finite).
fn length_scale(num: &NumericRobot) -> f64 {
    let links: f64 = num.joints.iter().map(|j| j.a.abs() + j.d.abs()).sum();
    let frames: f64 = (0..3)
        .map(|r| num.base[(r, 3)].abs() + num.tool[(r, 3)].abs())
        .sum();
    let s = links + frames;
    if s.is_finite() {
        s
    } else {
        f64::INFINITY
    }
}

/// Locals bound twice by `let` in one generated function, as `(function, name)`.
///
/// The generated code binds each parameter (`let a2 = self.a2;`) and each intermediate
/// (`s2`, `c23`, `t7`) once; a parameter named like an intermediate would be shadowed
/// and the formula silently wrong, which evaluating the engine's model cannot see.
pub fn shadowed_locals(code: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut function = String::new();
    let mut seen: Vec<String> = Vec::new();
    for line in code.lines().map(str::trim) {
        if let Some(rest) = line
            .strip_prefix("pub fn ")
            .or_else(|| line.strip_prefix("fn "))
        {
            function = rest.split('(').next().unwrap_or("").to_string();
            seen.clear();
        } else if let Some(rest) = line.strip_prefix("let ") {
            let pattern = rest.split(" =").next().unwrap_or("");
            for name in pattern.split(['(', ')', ',']) {
                let name = name.trim().trim_start_matches("mut ").trim();
                if name.is_empty() || name == "_" {
                    continue;
                }
                if seen.iter().any(|n| n == name) {
                    out.push((function.clone(), name.to_string()));
                } else {
                    seen.push(name.to_string());
                }
            }
        }
    }
    out
}
