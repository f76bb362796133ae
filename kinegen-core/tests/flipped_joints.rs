//! DH joints that run against their axis (`flip = true`, the Robotics Toolbox's `flip`):
//! the engine's FK, Jacobian, determinant and singular factors equal the numeric
//! reference, which implements flip on its own (θ = −q + offset in the DH matrix, the
//! column's axis negated, the rate negated in velocity propagation).
//!
//! The case is RTB's Kinova Jaco (`robots/kinova_jaco.toml`): joint 1 flipped, offsets
//! of ±π/2, −π and 100° (which does not fold into the joint's sine and cosine), twists
//! of 60°.

use kinegen_core::front::toml_file::{load_file, load_str};
use kinegen_core::kinematics::model::Model;
use kinegen_core::numeric::{self, NumericRobot};
use kinegen_core::{derive, Chain, Robot};
use nalgebra::Matrix4;

mod common;

fn jaco() -> (Robot, Chain) {
    let (robot, _) = load_file(&common::robots_dir().join("kinova_jaco.toml")).unwrap();
    let chain = robot.chain();
    (robot, chain)
}

/// `|a − b| ≤ tol·(1 + |b|)`.
fn close(a: f64, b: f64, tol: f64, what: &str) {
    assert!(
        (a - b).abs() <= tol * (1.0 + b.abs()),
        "{what}: engine {a} vs reference {b}"
    );
}

fn check_fk_and_jacobian(chain: &Chain, model: &Model, num: &NumericRobot, q: &[f64]) {
    let t: Matrix4<f64> = num.fk(q).unwrap();
    for (r, row) in model.fk_rows.iter().enumerate() {
        for (c, v) in model.eval(chain, q, row).into_iter().enumerate() {
            close(v, t[(r, c)], 1e-12, &format!("fk[{r}][{c}] at {q:?}"));
        }
    }
    let j = num.jacobian(q).unwrap();
    let j_fd = num.jacobian_fd(q, 1e-6).unwrap();
    let j_prop = num.jacobian_propagation(q).unwrap();
    assert!(
        (&j - &j_fd).amax() < 1e-8,
        "axes vs finite differences at {q:?}"
    );
    assert!(
        (&j - &j_prop).amax() < 1e-12,
        "axes vs propagation at {q:?}"
    );
    for (r, row) in model.jacobian.iter().enumerate() {
        for (c, v) in model.eval(chain, q, row).into_iter().enumerate() {
            close(v, j[(r, c)], 1e-12, &format!("J[{r}][{c}] at {q:?}"));
        }
    }
}

#[test]
fn jaco_fk_jacobian_det_and_factors_match_the_reference() {
    let (robot, chain) = jaco();
    assert_eq!(chain.links[0].motion.sign, -1);
    assert!(chain.links[1..].iter().all(|l| l.motion.sign == 1));
    let derived = derive(&chain, &Default::default());
    let model = &derived.model;
    let det = derived
        .det
        .as_ref()
        .expect("6×6")
        .as_ref()
        .expect("closed form");
    let num = NumericRobot::new(&robot).unwrap();
    let c = num_traits::ToPrimitive::to_f64(&det.factored.constant).unwrap();
    for q in numeric::configurations(14, 200, 6) {
        check_fk_and_jacobian(&chain, model, &num, &q);
        let d_ref = numeric::det6(&num.jacobian(&q).unwrap()).unwrap();
        let d = model.eval(&chain, &q, &[det.node])[0];
        close(d, d_ref, 1e-12, &format!("det at {q:?}"));
        // The factors multiply back to the determinant.
        let ids: Vec<_> = det.factors.iter().map(|f| f.node).collect();
        let product: f64 = model
            .eval(&chain, &q, &ids)
            .iter()
            .zip(&det.factors)
            .map(|(v, f)| v.powi(f.power as i32))
            .product();
        close(c * product, d_ref, 1e-12, &format!("Π factors at {q:?}"));
    }
    // A flipped joint 1 turns the arm about the base: det J does not depend on q1.
    assert!(
        det.factors.iter().all(|f| !f.joints.contains(&1)),
        "{}",
        det.text
    );
}

/// Flipping a joint is the same as negating its variable: the flipped robot at q equals
/// the unflipped one at q with q_i negated — FK exactly in value, Jacobian column i
/// negated, det negated (one column), the same singular factors.
#[test]
fn flip_is_negating_the_joint_variable() {
    let src = |flip: bool| {
        format!(
            "convention = \"modified\"\n\
             [[joints]]\ntype = \"revolute\"\na = 0\nalpha = 0\nd = 0.3\n\
             [[joints]]\ntype = \"revolute\"\na = 0\nalpha = \"-pi/2\"\nd = 0\nflip = {flip}\noffset = 0.25\n\
             [[joints]]\ntype = \"prismatic\"\na = 0.1\nalpha = \"pi/2\"\ntheta = 0\nflip = {flip}\n\
             [[joints]]\ntype = \"revolute\"\na = 0.2\nalpha = 0\nd = 0.1\n\
             [[joints]]\ntype = \"revolute\"\na = 0\nalpha = \"pi/2\"\nd = 0\n\
             [[joints]]\ntype = \"revolute\"\na = 0\nalpha = \"-pi/2\"\nd = 0\n\
             [tool]\nxyz = [0, 0, 0.1]\n"
        )
    };
    let (flipped, _) = load_str(&src(true), "flipped.toml").unwrap();
    let (plain, _) = load_str(&src(false), "plain.toml").unwrap();
    let (cf, cp) = (flipped.chain(), plain.chain());
    let (df, dp) = (
        derive(&cf, &Default::default()),
        derive(&cp, &Default::default()),
    );
    let det_f = df.det.as_ref().unwrap().as_ref().unwrap();
    let det_p = dp.det.as_ref().unwrap().as_ref().unwrap();
    let num_f = NumericRobot::new(&flipped).unwrap();
    for mut q in numeric::configurations(41, 200, 6) {
        q[2] = 0.2 + q[2].abs() / 10.0;
        check_fk_and_jacobian(&cf, &df.model, &num_f, &q);
        let mut qn = q.clone();
        qn[1] = -q[1];
        qn[2] = -q[2];
        let tf = df.model.eval(&cf, &q, &df.model.fk_rows.concat());
        let tp = dp.model.eval(&cp, &qn, &dp.model.fk_rows.concat());
        for (a, b) in tf.iter().zip(&tp) {
            close(
                *a,
                *b,
                1e-12,
                "fk(flipped, q) = fk(plain, q with q2, q3 negated)",
            );
        }
        let d_f = df.model.eval(&cf, &q, &[det_f.node])[0];
        let d_p = dp.model.eval(&cp, &qn, &[det_p.node])[0];
        // Two columns negated: the determinant keeps its sign.
        close(d_f, d_p, 1e-12, "det");
    }
    assert_eq!(
        det_f.factors.len(),
        det_p.factors.len(),
        "{} vs {}",
        det_f.text,
        det_p.text
    );
}
