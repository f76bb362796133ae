//! Run time of the generated kinematics against what users would pick instead, in one run
//! (issue 7; results and how to read them in BENCHMARKS.md):
//!
//! - `generated`: the code `kinematics!` generates (`kinegen_robots::{Ur5, Puma560, Panda}`);
//! - `nalgebra_loop`: a lean numeric reference on fixed-size nalgebra types — one DH matrix
//!   per joint (one `sin_cos` each, twist cosines/sines precomputed), multiplied in a loop,
//!   Jacobian columns `[z × (p − o); z]`, determinant by nalgebra's LU;
//! - `core_numeric`: `kinegen_core::numeric::NumericRobot`, the engine's test oracle (heap
//!   `Vec`/`DMatrix`, DH matrices from elementary transforms: written for clarity, not speed);
//! - `k`: the `k` crate's `SerialChain` of the same DH table (`end_transform`, `k::jacobian`);
//! - `baseline`: one `sin_cos` per joint alone (six for UR5 and PUMA 560), the floor the
//!   issue measures against: the platform's `f64::sin_cos`, `libm::sincos`,
//!   `libm::sin` + `libm::cos`, and `kinegen::math::sin_cos`, which generated code calls.
//!
//! Every variant is checked against the generated code at start (assertions, so the
//! comparison is apples to apples); inputs cycle through 1024 random configurations so the
//! branch predictor neither sees one constant input nor learns the sequence (it learns a
//! cycle of 64, which flatters branchy trig such as libm's quadrant `match`). `cargo bench --bench kinematics` ends
//! by printing the median table and the ratios of this run.

mod common;

use common::{configurations, cycle, load, median, paired, DhLoop};
use criterion::{criterion_group, Criterion};
use k::nalgebra as kna;
use kinegen::Kinematics;
use kinegen_core::model::{dh::Convention, robot::JointKind};
use kinegen_core::numeric::{rot_x, rot_z, trans, NumericRobot};
use kinegen_robots::{Panda, Puma560, Ur5};
use nalgebra::Matrix4;
use std::time::{Duration, SystemTime};

/// `k`'s nalgebra (0.30) isometry from a rigid homogeneous matrix of ours (0.33).
fn to_k(m: &Matrix4<f64>) -> kna::Isometry3<f64> {
    let r = kna::Matrix3::from_fn(|i, j| m[(i, j)]);
    let rot = kna::UnitQuaternion::from_rotation_matrix(&kna::Rotation3::from_matrix_unchecked(r));
    kna::Isometry3::from_parts(kna::Translation3::new(m[(0, 3)], m[(1, 3)], m[(2, 3)]), rot)
}

/// The same chain in `k`: node i rotates about its own z axis by `q_i`; its origin is what
/// the DH table puts between joint i−1's rotation and joint i's. Standard DH
/// `A_i = Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i)`: origin_i = `Tx(a_{i−1}) Rx(α_{i−1}) · Tz(d_i) Rz(θ⁰_i)`
/// (`Tz` and `Rz` commute), and a fixed end node `Tx(a_N) Rx(α_N) · tool`. Modified
/// `A_i = Rx(α) Tx(a) Rz(θ_i) Tz(d_i)`: origin_i = `Rx(α_i) Tx(a_i) Tz(d_i) Rz(θ⁰_i)`, end node
/// `tool`. The base goes into the first origin.
fn k_chain(r: &NumericRobot) -> k::SerialChain<f64> {
    let standard = r.convention == Convention::Standard;
    let mut pending = r.base; // what comes before the next joint's rotation
    let mut nodes: Vec<k::Node<f64>> = Vec::new();
    for (i, j) in r.joints.iter().enumerate() {
        assert_eq!(j.kind, JointKind::Revolute);
        let own = if standard {
            trans(0.0, 0.0, j.d) * rot_z(j.theta)
        } else {
            rot_x(j.alpha) * trans(j.a, 0.0, 0.0) * trans(0.0, 0.0, j.d) * rot_z(j.theta)
        };
        let node: k::Node<f64> = k::NodeBuilder::new()
            .name(&format!("joint{}", i + 1))
            .joint_type(k::JointType::Rotational {
                axis: kna::Vector3::z_axis(),
            })
            .origin(to_k(&(pending * own)))
            .finalize()
            .into();
        if let Some(parent) = nodes.last() {
            node.set_parent(parent);
        }
        nodes.push(node);
        pending = if standard {
            trans(j.a, 0.0, 0.0) * rot_x(j.alpha)
        } else {
            Matrix4::identity()
        };
    }
    let tool: k::Node<f64> = k::NodeBuilder::new()
        .name("tool")
        .joint_type(k::JointType::Fixed)
        .origin(to_k(&(pending * r.tool)))
        .finalize()
        .into();
    tool.set_parent(nodes.last().unwrap());
    k::SerialChain::new_unchecked(k::Chain::from_root(nodes[0].clone()))
}

fn k_fk(chain: &k::SerialChain<f64>, q: &[f64]) -> kna::Isometry3<f64> {
    chain.set_joint_positions_unchecked(q);
    chain.end_transform()
}

fn k_jacobian(chain: &k::SerialChain<f64>, q: &[f64]) -> kna::DMatrix<f64> {
    chain.set_joint_positions_unchecked(q);
    k::jacobian(chain)
}

fn k_fk_and_jacobian(
    chain: &k::SerialChain<f64>,
    q: &[f64],
) -> (kna::Isometry3<f64>, kna::DMatrix<f64>) {
    chain.set_joint_positions_unchecked(q);
    let j = k::jacobian(chain);
    // `k::jacobian` left every node's world transform cached; the tool node's is the pose.
    let t = chain.iter().last().unwrap().world_transform().unwrap();
    (t, j)
}

/// Everything within `tol` of the generated code, or a panic naming the entry.
fn check<const N: usize, K: Kinematics<N>>(
    name: &str,
    robot: &K,
    lean: &DhLoop<N>,
    core: &NumericRobot,
    chain: &k::SerialChain<f64>,
    qs: &[[f64; N]],
) {
    let tol = 1e-12;
    let near = |a: f64, b: f64, what: &str| {
        assert!(
            (a - b).abs() <= tol,
            "{name} {what}: generated {a} vs {b} (|Δ| = {:e})",
            (a - b).abs()
        )
    };
    for q in qs.iter().take(8) {
        let t = robot.fk(q);
        let j = robot.jacobian(q);
        let (t2, j2) = robot.fk_and_jacobian(q);
        let (tl, jl) = lean.fk_and_jacobian(q);
        let tc = core.fk(q).unwrap();
        let jc = core.jacobian(q).unwrap();
        let tk = k_fk(chain, q).to_homogeneous();
        let jk = k_jacobian(chain, q);
        let (tk2, jk2) = k_fk_and_jacobian(chain, q);
        assert_eq!(jk2, jk, "{name}: k fused Jacobian");
        for r in 0..4 {
            for c in 0..4 {
                near(t[r][c], t2[r][c], &format!("fk[{r}][{c}] (fused)"));
                near(
                    t[r][c],
                    tl[(r, c)],
                    &format!("fk[{r}][{c}] (nalgebra loop)"),
                );
                near(t[r][c], tc[(r, c)], &format!("fk[{r}][{c}] (core numeric)"));
                near(t[r][c], tk[(r, c)], &format!("fk[{r}][{c}] (k)"));
                near(
                    t[r][c],
                    tk2.to_homogeneous()[(r, c)],
                    &format!("fk[{r}][{c}] (k fused)"),
                );
            }
        }
        for r in 0..6 {
            for c in 0..N {
                near(j[r][c], j2[r][c], &format!("J[{r}][{c}] (fused)"));
                near(j[r][c], jl[(r, c)], &format!("J[{r}][{c}] (nalgebra loop)"));
                near(j[r][c], jc[(r, c)], &format!("J[{r}][{c}] (core numeric)"));
                near(j[r][c], jk[(r, c)], &format!("J[{r}][{c}] (k)"));
            }
        }
    }
}

/// `det`: the nalgebra loop's determinant, for 6-joint robots (a closure, statically
/// dispatched like everything else here).
fn bench_robot<const N: usize, K: Kinematics<N>, D: Fn(&[f64; N]) -> f64>(
    c: &mut Criterion,
    group: &str,
    robot: &K,
    file: &str,
    det: Option<D>,
) {
    let core = load(file);
    let lean = DhLoop::<N>::new(&core);
    let chain = k_chain(&core);
    let qs = configurations(&robot.limits(), 0x6b69_6e65_6765_6e00 ^ N as u64);
    check(group, robot, &lean, &core, &chain, &qs);
    if let (Some(det), Some(_)) = (&det, robot.jacobian_det(&qs[0])) {
        for q in qs.iter().take(8) {
            let (d, dl) = (robot.jacobian_det(q).unwrap(), det(q));
            assert!(
                (d - dl).abs() <= 1e-12 * (1.0 + dl.abs()),
                "{group} det: generated {d} vs nalgebra LU {dl}"
            );
        }
    }

    let mut g = c.benchmark_group(group);
    // Operation by operation, the contenders back to back: on a shared machine the load
    // drifts, and neighbours in time see the same load.
    g.bench_function("generated/fk", |b| cycle(b, &qs, |q| robot.fk(&q)));
    g.bench_function("nalgebra_loop/fk", |b| cycle(b, &qs, |q| lean.fk(&q)));
    g.bench_function("core_numeric/fk", |b| {
        cycle(b, &qs, |q| core.fk(&q).unwrap())
    });
    g.bench_function("k/fk", |b| cycle(b, &qs, |q| k_fk(&chain, &q)));

    // The trig floor: N sin_cos calls (six for UR5 and PUMA 560), timed right before the
    // generated Jacobian so both see the same machine load.
    g.bench_function("baseline/sin_cos_f64", |b| {
        cycle(b, &qs, |q| q.map(f64::sin_cos))
    });
    g.bench_function("baseline/sin_cos_libm_sincos", |b| {
        cycle(b, &qs, |q| q.map(libm::sincos))
    });
    g.bench_function("baseline/sin_cos_libm_sin_and_cos", |b| {
        cycle(b, &qs, |q| q.map(|x| (libm::sin(x), libm::cos(x))))
    });
    g.bench_function("baseline/sin_cos_kinegen_math", |b| {
        cycle(b, &qs, |q| q.map(kinegen::math::sin_cos))
    });
    // The same N angles in one batched call (lanes side by side in SIMD registers).
    g.bench_function("baseline/sin_cos_kinegen_math_n", |b| {
        cycle(b, &qs, kinegen::math::sin_cos_n)
    });
    g.bench_function("generated/jacobian", |b| {
        cycle(b, &qs, |q| robot.jacobian(&q))
    });
    g.bench_function("nalgebra_loop/jacobian", |b| {
        cycle(b, &qs, |q| lean.jacobian(&q))
    });
    g.bench_function("core_numeric/jacobian", |b| {
        cycle(b, &qs, |q| core.jacobian(&q).unwrap())
    });
    g.bench_function("k/jacobian", |b| cycle(b, &qs, |q| k_jacobian(&chain, &q)));

    if robot.jacobian_det(&qs[0]).is_some() {
        g.bench_function("generated/jacobian_det", |b| {
            cycle(b, &qs, |q| robot.jacobian_det(&q))
        });
    }
    if let Some(det) = &det {
        g.bench_function("nalgebra_loop/jacobian_det", |b| cycle(b, &qs, |q| det(&q)));
    }

    g.bench_function("generated/fk_and_jacobian", |b| {
        cycle(b, &qs, |q| robot.fk_and_jacobian(&q))
    });
    g.bench_function("nalgebra_loop/fk_and_jacobian", |b| {
        cycle(b, &qs, |q| lean.fk_and_jacobian(&q))
    });
    g.bench_function("k/fk_and_jacobian", |b| {
        cycle(b, &qs, |q| k_fk_and_jacobian(&chain, &q))
    });
    g.finish();
}

fn ur5(c: &mut Criterion) {
    let lean = DhLoop::<6>::new(&load("ur5.toml"));
    let det = |q: &[f64; 6]| lean.jacobian_det(q);
    bench_robot(c, "ur5", &Ur5::default(), "ur5.toml", Some(det));
}

fn puma560(c: &mut Criterion) {
    let lean = DhLoop::<6>::new(&load("puma560.toml"));
    let det = |q: &[f64; 6]| lean.jacobian_det(q);
    bench_robot(c, "puma560", &Puma560::default(), "puma560.toml", Some(det));
}

fn panda(c: &mut Criterion) {
    let no_det: Option<fn(&[f64; 7]) -> f64> = None;
    bench_robot(c, "panda", &Panda::default(), "panda.toml", no_det);
}

fn config() -> Criterion {
    // Modest, so the whole run takes a few minutes on a shared 2-core machine.
    Criterion::default()
        .sample_size(40)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
}

criterion_group! {
    name = benches;
    config = config();
    targets = ur5, puma560, panda
}

const ROBOTS: [&str; 3] = ["ur5", "puma560", "panda"];

/// The Markdown tables of BENCHMARKS.md, from this run's medians.
fn summary(since: SystemTime) {
    let fmt = |x: Option<f64>| x.map_or("–".to_string(), |v| format!("{v:.1}"));
    let ratio = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) => format!("{:.2}×", a / b),
        _ => "–".to_string(),
    };
    println!("\n## Medians of this run (ns)\n");
    println!("| robot | operation | generated | nalgebra loop | core numeric | k | k / generated | nalgebra loop / generated | core numeric / generated |");
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|");
    for robot in ROBOTS {
        for op in ["fk", "jacobian", "jacobian_det", "fk_and_jacobian"] {
            let m = |who: &str| median(robot, &format!("{who}/{op}"), since);
            let g = m("generated");
            if g.is_none() {
                continue;
            }
            let (l, cn, k) = (m("nalgebra_loop"), m("core_numeric"), m("k"));
            println!(
                "| {robot} | {op} | {} | {} | {} | {} | {} | {} | {} |",
                fmt(g),
                fmt(l),
                fmt(cn),
                fmt(k),
                ratio(k, g),
                ratio(l, g),
                ratio(cn, g)
            );
        }
    }
    println!("\n## The trig floor: one sin_cos per joint (ns), and generated jacobian / it\n");
    println!("| robot | generated jacobian | f64::sin_cos | libm::sincos | libm::sin + libm::cos | kinegen::math::sin_cos | kinegen::math::sin_cos_n | J / f64::sin_cos | J / libm::sincos | J / libm sin+cos | J / kinegen::math | J / kinegen::math (batched) |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for robot in ROBOTS {
        let g = median(robot, "generated/jacobian", since);
        let b = |id: &str| median(robot, &format!("baseline/sin_cos_{id}"), since);
        let ids = [
            "f64",
            "libm_sincos",
            "libm_sin_and_cos",
            "kinegen_math",
            "kinegen_math_n",
        ];
        if g.is_none() && ids.iter().all(|id| b(id).is_none()) {
            continue;
        }
        print!("| {robot} | {} |", fmt(g));
        for id in ids {
            print!(" {} |", fmt(b(id)));
        }
        for id in ids {
            print!(" {} |", ratio(g, b(id)));
        }
        println!();
    }
    println!("\n## N scalar kinegen::math::sin_cos / one kinegen::math::sin_cos_n (criterion)\n");
    for robot in ROBOTS {
        let b = |id: &str| median(robot, &format!("baseline/sin_cos_{id}"), since);
        let (scalar, batched) = (b("kinegen_math"), b("kinegen_math_n"));
        if scalar.is_some() || batched.is_some() {
            println!(
                "| {robot} | {} ns | {} ns | {} |",
                fmt(scalar),
                fmt(batched),
                ratio(scalar, batched)
            );
        }
    }
}

/// The ratios once more, each from interleaved batches (see [`paired`]).
fn paired_row<const N: usize, K: Kinematics<N>>(name: &str, robot: &K, file: &str) {
    let core = load(file);
    let lean = DhLoop::<N>::new(&core);
    let chain = k_chain(&core);
    let qs = configurations(&robot.limits(), 0x6b69_6e65_6765_6e00 ^ N as u64);
    let j = |q: [f64; N]| robot.jacobian(&q);
    let r = [
        paired(&qs, |q| k_jacobian(&chain, &q), j),
        paired(&qs, |q| lean.jacobian(&q), j),
        paired(&qs, j, |q| q.map(f64::sin_cos)),
        paired(&qs, j, |q| q.map(libm::sincos)),
        paired(&qs, j, |q| q.map(|x| (libm::sin(x), libm::cos(x)))),
        paired(&qs, j, |q| q.map(kinegen::math::sin_cos)),
        paired(&qs, j, kinegen::math::sin_cos_n),
        paired(
            &qs,
            |q| q.map(kinegen::math::sin_cos),
            kinegen::math::sin_cos_n,
        ),
    ];
    println!(
        "| {name} | {:.2}× | {:.2}× | {:.2}× | {:.2}× | {:.2}× | {:.2}× | {:.2}× | {:.2}× |",
        r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7]
    );
}

fn paired_table() {
    println!("\n## Jacobian ratios from interleaved batches (median of 41 rounds)\n");
    println!("| robot | k / generated | nalgebra loop / generated | generated / N f64::sin_cos | generated / N libm::sincos | generated / N libm sin+cos | generated / N kinegen::math::sin_cos | generated / kinegen::math::sin_cos_n of N | N kinegen::math::sin_cos / sin_cos_n of N |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    paired_row("ur5", &Ur5::default(), "ur5.toml");
    paired_row("puma560", &Puma560::default(), "puma560.toml");
    paired_row("panda", &Panda::default(), "panda.toml");
}

fn main() {
    common::bench_main(benches, summary, paired_table);
}
