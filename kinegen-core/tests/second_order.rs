//! The engine's second-order outputs — Hessian, `J̇`, `J̇ q̇`, `J̇_ee`, the determinant's
//! gradient, the singular factors' gradients, the manipulability gradients — evaluated
//! node by node against the numeric reference and against finite differences, on every
//! robot of `robots/` and on random tables (both conventions, prismatic joints, base and
//! tool, flipped joints), 200 configurations each, fixed seeds.
//!
//! Tolerances, per entry, with `s = max(1, |reference|)`:
//! - closed form against closed form (the numeric reference's cross products of joint
//!   axes, its velocity/acceleration propagation, `Σ_j H[j] q̇_j`): `1e-10·s` — both are
//!   a few dozen roundings of metre-sized numbers (≈1e-15 each);
//! - closed form against central differences with step `h = 1e-5` (of the engine's own
//!   Jacobian, factors and determinant, and of the reference's): `1e-6·s` — truncation
//!   `h²/6·|f'''|` ≈ 2e-11 and rounding `ε·|f|/h` ≈ 2e-11 on metre-sized arms, with
//!   margin for the larger third derivatives of the random tables' long links.
//!
//! Flipped joints (`Motion.sign = −1`) are tested twice: written in the DH table
//! (`flip = true`, which the numeric reference follows natively), and on chains edited
//! directly, where joint `i` flipped is the unflipped robot at
//! `q_i → −q_i` with column `i` negated, so the reference is the numeric robot at `S q`
//! (`S = diag(±1)`): `J(q) = J₀(Sq) S`, `H[j](q) = s_j H₀[j](Sq) S`, `J̇q̇ = J̇₀q̇₀` at
//! `(Sq, Sq̇)`, `∂det/∂q_j = det(S) s_j ∂det₀/∂q_j`.

mod common;
#[path = "common/random_robot.rs"]
mod random_robot;

use common::robot_files;
use kinegen_core::front::toml_file::load_file;
use kinegen_core::kinematics::jacobian::Rows;
use kinegen_core::model::robot::JointKind;
use kinegen_core::numeric::{self, Jacobian, NumericRobot};
use kinegen_core::{derive, Chain, Derived, Options, Robot};
use nalgebra::DMatrix;
use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use std::sync::atomic::{AtomicUsize, Ordering};

/// Manipulability gradients checked, and skipped near a singularity.
static MANIPULABILITY: [AtomicUsize; 2] = [AtomicUsize::new(0), AtomicUsize::new(0)];

const CONFIGURATIONS: usize = 200;
const CLOSED: f64 = 1e-10;
const FD: f64 = 1e-6;
const H: f64 = 1e-5;

/// SplitMix64: reproducible configurations without a dependency.
struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

fn close(got: f64, want: f64, tol: f64, what: &dyn Fn() -> String) {
    assert!(
        (got - want).abs() <= tol * want.abs().max(1.0),
        "{}: {got} vs {want} (|Δ| = {:e})",
        what(),
        (got - want).abs()
    );
}

/// A robot under test: its chain (possibly with flipped joints), what the engine derived
/// from it, and the numeric reference of the unflipped DH table.
struct Case {
    name: String,
    chain: Chain,
    derived: Derived,
    reference: NumericRobot,
    /// `s_i = ±1`: joint `i` flipped.
    signs: Vec<f64>,
}

impl Case {
    fn new(name: &str, robot: &Robot, flips: &[usize]) -> Case {
        let mut chain = robot.chain();
        for &i in flips {
            chain.links[i].motion.sign = -1;
        }
        let signs = (0..chain.dof())
            .map(|i| if flips.contains(&i) { -1.0 } else { 1.0 })
            .collect();
        let derived = derive(&chain, &Options::default());
        Case {
            name: name.to_string(),
            derived,
            reference: NumericRobot::new(robot).unwrap(),
            chain,
            signs,
        }
    }

    fn n(&self) -> usize {
        self.chain.dof()
    }

    fn eval(&self, q: &[f64], qd: &[f64], ids: &[u32]) -> Vec<f64> {
        self.derived
            .model
            .eval_with_rates(&self.chain, q, Some(qd), ids)
    }

    fn matrix(&self, q: &[f64], qd: &[f64], rows: &Rows) -> Jacobian {
        let n = self.n();
        let flat: Vec<u32> = rows.iter().flatten().copied().collect();
        let v = self.eval(q, qd, &flat);
        Jacobian::from_fn(n, |r, c| v[r * n + c])
    }

    /// `S x`.
    fn flip(&self, x: &[f64]) -> Vec<f64> {
        x.iter().zip(&self.signs).map(|(a, s)| a * s).collect()
    }

    /// `M S`: column `i` times `s_i`.
    fn flip_columns(&self, m: &Jacobian) -> Jacobian {
        let mut out = m.clone();
        for (i, s) in self.signs.iter().enumerate() {
            out.column_mut(i).scale_mut(*s);
        }
        out
    }

    fn joint_ranges(&self) -> Vec<(f64, f64)> {
        self.chain
            .links
            .iter()
            .map(|l| match (l.limits, l.motion.kind) {
                (Some([lo, hi]), _) => (lo, hi),
                (None, JointKind::Revolute) => (-std::f64::consts::PI, std::f64::consts::PI),
                (None, JointKind::Prismatic) => (-0.5, 0.5),
            })
            .collect()
    }
}

fn assert_matrix(got: &Jacobian, want: &Jacobian, tol: f64, what: &dyn Fn() -> String) {
    for r in 0..got.nrows() {
        for c in 0..got.ncols() {
            close(got[(r, c)], want[(r, c)], tol, &|| {
                format!("{}[{r}][{c}]", what())
            });
        }
    }
}

/// Everything at one configuration.
fn check(case: &Case, q: &[f64], qd: &[f64]) {
    let n = case.n();
    let at = |what: &str| format!("{} {what} at q = {q:?}, qd = {qd:?}", case.name);
    let s = &case.derived.second;
    let model = &case.derived.model;
    let (q0, qd0) = (case.flip(q), case.flip(qd));
    let reference = &case.reference;
    // The Jacobian itself, flipped.
    let j = case.matrix(q, qd, &model.jacobian);
    let j_ref = case.flip_columns(&reference.jacobian(&q0).unwrap());
    assert_matrix(&j, &j_ref, CLOSED, &|| at("J"));
    // H against the reference's cross products and the engine Jacobian's differences.
    let h: Vec<Jacobian> = s.hessian.iter().map(|hj| case.matrix(q, qd, hj)).collect();
    let h_ref = reference.hessian(&q0).unwrap();
    let h_fd = engine_hessian_fd(case, q, qd);
    for k in 0..n {
        let want = case.flip_columns(&h_ref[k]) * case.signs[k];
        assert_matrix(&h[k], &want, CLOSED, &|| at(&format!("H[{k}]")));
        assert_matrix(&h[k], &h_fd[k], FD, &|| at(&format!("H[{k}] vs FD")));
    }
    // J̇ = Σ_j H[j] q̇_j, and the derivative of J along q + t q̇.
    let jd = case.matrix(q, qd, &s.jacobian_dot);
    let sum = (0..n).fold(Jacobian::zeros(n), |acc, k| acc + &h[k] * qd[k]);
    assert_matrix(&jd, &sum, CLOSED, &|| at("J̇ vs Σ H q̇"));
    let jd_ref = case.flip_columns(&reference.jacobian_dot_fd(&q0, &qd0, H).unwrap());
    assert_matrix(&jd, &jd_ref, FD, &|| at("J̇ vs d/dt J"));
    // J̇ q̇ = the product, = the propagation.
    let a = case.eval(q, qd, &s.jdot_qdot);
    let product = &jd * nalgebra::DVector::from_column_slice(qd);
    let propagated = reference.jdot_qdot_propagation(&q0, &qd0).unwrap();
    for r in 0..6 {
        close(a[r], product[r], CLOSED, &|| at(&format!("J̇q̇[{r}] vs J̇·q̇")));
        close(a[r], propagated[r], CLOSED, &|| {
            at(&format!("J̇q̇[{r}] vs propagation"))
        });
    }
    // The tool-frame Jacobian's derivative.
    let jee_dot = case.matrix(q, qd, &s.jacobian_ee_dot);
    let jee_ref = case.flip_columns(&reference.jacobian_ee_dot_fd(&q0, &qd0, H).unwrap());
    assert_matrix(&jee_dot, &jee_ref, FD, &|| at("J̇_ee vs d/dt J_ee"));
    check_det_gradient(case, q, &at);
    check_manipulability_gradient(case, q, &j, &h, &at);
}

/// `(J(q + h e_k) − J(q − h e_k)) / 2h` of the engine's own Jacobian.
fn engine_hessian_fd(case: &Case, q: &[f64], qd: &[f64]) -> Vec<Jacobian> {
    let model = &case.derived.model;
    (0..case.n())
        .map(|k| {
            let mut plus = q.to_vec();
            let mut minus = q.to_vec();
            plus[k] += H;
            minus[k] -= H;
            (case.matrix(&plus, qd, &model.jacobian) - case.matrix(&minus, qd, &model.jacobian))
                / (2.0 * H)
        })
        .collect()
}

/// `∂/∂q_k` of the engine node `id` by central differences.
fn node_fd(case: &Case, q: &[f64], id: u32, k: usize) -> f64 {
    let mut plus = q.to_vec();
    let mut minus = q.to_vec();
    plus[k] += H;
    minus[k] -= H;
    let zero = vec![0.0; q.len()];
    (case.eval(&plus, &zero, &[id])[0] - case.eval(&minus, &zero, &[id])[0]) / (2.0 * H)
}

fn check_det_gradient(case: &Case, q: &[f64], at: &dyn Fn(&str) -> String) {
    let Some(Ok(det)) = &case.derived.det else {
        return;
    };
    let g = match &case.derived.det_gradient {
        Some(Ok(g)) => g,
        other => panic!("{}: no det gradient: {other:?}", case.name),
    };
    let zero = vec![0.0; q.len()];
    let grad = case.eval(q, &zero, &g.gradient);
    let flip_det: f64 = case.signs.iter().product();
    for (k, &dk) in grad.iter().enumerate() {
        close(dk, node_fd(case, q, det.node, k), FD, &|| {
            at(&format!("∂det/∂q{}", k + 1))
        });
        // Against the numeric determinant's differences (of the unflipped robot).
        let reference = reference_det_fd(case, &case.flip(q), k) * flip_det * case.signs[k];
        close(dk, reference, FD, &|| {
            at(&format!("∂det/∂q{} vs numeric", k + 1))
        });
    }
    for (f, df) in det.factors.iter().zip(&g.factors) {
        let d = case.eval(q, &zero, df);
        for (k, &x) in d.iter().enumerate() {
            close(x, node_fd(case, q, f.node, k), FD, &|| {
                at(&format!("∂({})/∂q{}", f.text, k + 1))
            });
        }
    }
}

/// `∂det/∂q_k` of the reference's (square task or 6×6) Jacobian, by central differences.
fn reference_det_fd(case: &Case, q0: &[f64], k: usize) -> f64 {
    let det = |q: &[f64]| {
        let jt = case.reference.task_jacobian(q).unwrap();
        if jt.nrows() == jt.ncols() {
            numeric::det(&jt).unwrap()
        } else {
            numeric::det6(&case.reference.jacobian(q).unwrap()).unwrap()
        }
    };
    let mut plus = q0.to_vec();
    let mut minus = q0.to_vec();
    plus[k] += H;
    minus[k] -= H;
    (det(&plus) - det(&minus)) / (2.0 * H)
}

fn rows_of(m: &Jacobian, rows: &[usize]) -> DMatrix<f64> {
    DMatrix::from_fn(rows.len(), m.ncols(), |r, c| m[(rows[r], c)])
}

/// `w · tr(J⁺ H_k)` from the engine's J and H against central differences of `w`
/// (the numeric SVD of the engine's Jacobian), full rows and task rows. Relative to the
/// scale `w + |∂w/∂q_k|` (`w` is a product of up to six singular values: millimetres to
/// metres cubed); skipped where the condition number passes 100, since `w` is not
/// differentiable at a singularity (it behaves like `|f|`) and its differences lose
/// digits near one. With more rows than joints the measure is identically 0 (see
/// `robots/tests/second_order.rs` for the generated gradient being 0 there).
fn check_manipulability_gradient(
    case: &Case,
    q: &[f64],
    j: &Jacobian,
    h: &[Jacobian],
    at: &dyn Fn(&str) -> String,
) {
    let mut sets: Vec<(String, Vec<usize>)> = vec![("m".into(), (0..6).collect())];
    if let Some(task) = &case.chain.task {
        sets.push(("m_task".into(), task.iter().map(|r| r.index()).collect()));
    }
    let model = &case.derived.model;
    let zero = vec![0.0; q.len()];
    for (name, rows) in sets {
        if rows.len() > q.len() {
            // More rows than joints: `√det(J Jᵀ)` is identically 0, nothing to compare.
            continue;
        }
        let jt = |q: &[f64]| rows_of(&case.matrix(q, &zero, &model.jacobian), &rows);
        let sv = jt(q).singular_values();
        if sv.max() > 100.0 * sv.min() {
            MANIPULABILITY[1].fetch_add(1, Ordering::Relaxed);
            continue;
        }
        MANIPULABILITY[0].fetch_add(1, Ordering::Relaxed);
        let w = |q: &[f64]| numeric::manipulability(&jt(q));
        let hs: Vec<DMatrix<f64>> = h.iter().map(|hk| rows_of(hk, &rows)).collect();
        let grad = numeric::manipulability_gradient(&rows_of(j, &rows), &hs);
        for (k, &gk) in grad.iter().enumerate() {
            let mut plus = q.to_vec();
            let mut minus = q.to_vec();
            plus[k] += H;
            minus[k] -= H;
            let fd = (w(&plus) - w(&minus)) / (2.0 * H);
            let scale = w(q) + fd.abs();
            assert!(
                (gk - fd).abs() <= FD * scale,
                "{}: {gk} vs {fd} (w = {})",
                at(&format!("∂{name}/∂q{}", k + 1)),
                w(q)
            );
        }
    }
}

fn run(case: &Case, seed: u64, configurations: usize) {
    let mut rng = Rng(seed);
    let ranges = case.joint_ranges();
    for _ in 0..configurations {
        let q: Vec<f64> = ranges.iter().map(|&(lo, hi)| rng.range(lo, hi)).collect();
        let qd: Vec<f64> = ranges.iter().map(|_| rng.range(-2.0, 2.0)).collect();
        check(case, &q, &qd);
    }
}

#[test]
fn every_robot_against_the_reference() {
    let mut det_gradients = 0;
    for (k, path) in robot_files().iter().enumerate() {
        let (robot, _) = load_file(path).unwrap();
        let case = Case::new(&robot.name, &robot, &[]);
        det_gradients += usize::from(matches!(case.derived.det_gradient, Some(Ok(_))));
        run(&case, 0x5EC0_0D00 + k as u64, CONFIGURATIONS);
    }
    // Every robot with a square Jacobian (all but the two 7-joint arms) has one.
    assert_eq!(det_gradients, robot_files().len() - 2);
    let [done, skipped] = MANIPULABILITY.each_ref().map(|c| c.load(Ordering::Relaxed));
    assert!(
        skipped * 5 < done,
        "{skipped} of {} skipped",
        done + skipped
    );
    eprintln!("manipulability gradients: {done} checked, {skipped} skipped near a singularity");
}

#[test]
fn flipped_joints_are_the_robot_at_minus_q() {
    for (file, flips) in [
        ("ur5.toml", vec![1, 4]),
        ("stanford.toml", vec![0, 2, 5]),
        ("panda.toml", vec![0, 3, 6]),
        ("scara.toml", vec![1, 2]),
        ("planar_rr.toml", vec![1]),
    ] {
        let path = common::robots_dir().join(file);
        let (robot, _) = load_file(&path).unwrap();
        let case = Case::new(&format!("{file} flipped {flips:?}"), &robot, &flips);
        run(&case, 0xF11B, CONFIGURATIONS);
    }
}

#[test]
fn flip_in_the_dh_table_matches_the_numeric_reference() {
    for (file, flips) in [("ur5.toml", vec![0, 3]), ("stanford.toml", vec![1, 2])] {
        let path = common::robots_dir().join(file);
        let (mut robot, _) = load_file(&path).unwrap();
        for &i in &flips {
            robot.joints[i].flip = true;
        }
        let case = Case::new(&format!("{file} flip = true at {flips:?}"), &robot, &[]);
        assert!(flips.iter().all(|&i| case.chain.links[i].motion.sign == -1));
        run(&case, 0xF11C, CONFIGURATIONS);
    }
}

#[test]
fn random_tables_against_the_reference() {
    let config = Config {
        failure_persistence: None,
        rng_algorithm: RngAlgorithm::ChaCha,
        ..Config::default()
    };
    let mut runner = TestRunner::new_with_rng(
        config,
        TestRng::from_seed(RngAlgorithm::ChaCha, &[0x2A; 32]),
    );
    let strategy = random_robot::robot_strategy();
    for k in 0..24u64 {
        let robot = strategy.new_tree(&mut runner).unwrap().current();
        // Every third table flips every other joint.
        let flips: Vec<usize> = match k % 3 {
            0 => (0..robot.dof()).step_by(2).collect(),
            _ => Vec::new(),
        };
        let case = Case::new(&format!("random table {k}"), &robot, &flips);
        run(&case, 0xD0D0 + k, CONFIGURATIONS);
    }
}

/// The symmetry the Hessian has: its linear rows are one node for `H[j][r][i]` and
/// `H[i][r][j]`; its angular rows vanish exactly for `j > i`.
#[test]
fn hessian_symmetry_is_structural() {
    for path in robot_files() {
        let (robot, options) = load_file(&path).unwrap();
        let derived = derive(&robot.chain(), &options);
        let h = &derived.second.hessian;
        let n = h.len();
        let g = &derived.model.sym.graph;
        let zero = |id: u32| g.as_num(id).is_some_and(|x| x.to_string() == "0");
        for (j, i) in (0..n).flat_map(|j| (0..n).map(move |i| (j, i))) {
            for (r, row) in h[j].iter().enumerate() {
                let what = || format!("{}: H[{j}][{r}][{i}]", robot.name);
                if r < 3 {
                    assert_eq!(row[i], h[i][r][j], "{}", what());
                } else if j > i {
                    assert!(zero(row[i]), "{}", what());
                }
            }
        }
    }
}
