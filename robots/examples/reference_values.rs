//! The generated code's values at fixed configurations, as JSON on stdout: what other
//! evaluations of the same closed forms are compared with (the Python module's tests
//! read it, `kinegen-py/tests/test_generated_rust.py`).
//!
//! `cargo run -p kinegen-robots --example reference_values > values.json`
//!
//! For every robot of this crate (keyed by its TOML file's name, as
//! `kinegen.robots.<name>()` loads it): its `FORMULAS` (`formulas`, each as
//! `[function, name, text, latex]`), and in `samples` configurations `q` inside the limits (a fixed
//! sequence, the same on every machine), joint rates `qd`, and at each the generated
//! `fk`, `frames`, `jacobian`, `jacobian_ee`, `jacobian_det` (`det`, six joints),
//! `task_jacobian_det` (`task_det`, a square task Jacobian), `hessian`,
//! `jdot_qdot`, and every solution of `ik_each` at `fk(q)` (the generating value of a
//! 7-joint arm's free joint given).

use std::fmt::Write;

use kinegen::{InverseKinematics, Kinematics, SecondOrderKinematics, TaskKinematics};
use kinegen_robots::*;

/// Configurations per robot.
const SAMPLES: usize = 8;

/// A fixed sequence in [0, 1) (a 64-bit LCG, Knuth's MMIX constants).
struct Sequence(u64);

impl Sequence {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A JSON list of numbers (Rust's `{:?}` of an f64 is its shortest round-trip form).
fn list(values: impl IntoIterator<Item = f64>) -> String {
    let items: Vec<String> = values.into_iter().map(|v| format!("{v:?}")).collect();
    format!("[{}]", items.join(","))
}

/// A JSON string.
fn string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// `FORMULAS` as JSON.
fn formulas(all: &[kinegen::Formula]) -> String {
    let items: Vec<String> = all
        .iter()
        .map(|f| {
            let fields = [f.function, f.name, f.text, f.latex].map(string);
            format!("[{}]", fields.join(","))
        })
        .collect();
    format!("[{}]", items.join(","))
}

/// `q` inside the limits (within ±π where a joint has none), away from their ends.
fn configuration<const N: usize>(limits: &[[f64; 2]; N], s: &mut Sequence) -> [f64; N] {
    core::array::from_fn(|i| {
        let [lo, hi] = limits[i];
        let (lo, hi) = (lo.max(-3.0), hi.min(3.0));
        lo + (hi - lo) * (0.05 + 0.9 * s.next())
    })
}

/// The values of one robot: its task Jacobian's determinant and free joint, where it
/// has them.
fn values<const N: usize, R>(
    robot: &R,
    task_det: impl Fn(&R, &[f64; N]) -> Option<f64>,
    free_joint: Option<usize>,
) -> String
where
    R: Kinematics<N> + SecondOrderKinematics<N> + InverseKinematics<N>,
{
    let mut s = Sequence(0x5eed_0000 + N as u64);
    let limits = robot.limits();
    let mut out = String::from("[");
    for k in 0..SAMPLES {
        let q = configuration(&limits, &mut s);
        let qd: [f64; N] = core::array::from_fn(|_| 2.0 * s.next() - 1.0);
        let t = robot.fk(&q);
        let mut free = [0.0; N];
        if let Some(j) = free_joint {
            free[j] = q[j];
        }
        let mut ik = Vec::new();
        robot.ik_each(&t, &free, &mut |b| {
            ik.push(format!(
                "{{\"q\":{},\"exact\":{},\"singular\":{}}}",
                list(b.q),
                b.exact,
                b.at_singularity || b.singular != 0
            ))
        });
        if k > 0 {
            out.push(',');
        }
        let _ = write!(
            out,
            "{{\"q\":{},\"qd\":{},\"fk\":{},\"frames\":{},\"jacobian\":{},\"jacobian_ee\":{},\"det\":{},\"task_det\":{},\"hessian\":{},\"jdot_qdot\":{},\"locked\":{},\"ik\":[{}]}}",
            list(q),
            list(qd),
            list(t.iter().flatten().copied()),
            list(robot.frames(&q).iter().flatten().flatten().copied()),
            list(robot.jacobian(&q).iter().flatten().copied()),
            list(robot.jacobian_ee(&q).iter().flatten().copied()),
            robot
                .jacobian_det(&q)
                .map_or("null".into(), |d| format!("{d:?}")),
            task_det(robot, &q).map_or("null".into(), |d| format!("{d:?}")),
            list(robot.hessian(&q).iter().flatten().flatten().copied()),
            list(robot.jdot_qdot(&q, &qd)),
            free_joint.map_or("null".into(), |j| format!("{:?}", q[j])),
            ik.join(",")
        );
    }
    out.push(']');
    out
}

fn main() {
    let mut robots: Vec<(&str, String, String)> = Vec::new();
    macro_rules! six {
        ($($name:literal => $ty:ident),* $(,)?) => {$(
            robots.push(($name, values(&$ty::default(), |_, _| None, None), formulas($ty::FORMULAS)));
        )*};
    }
    macro_rules! task {
        ($($name:literal => $ty:ident),* $(,)?) => {$(
            robots.push((
                $name,
                values(&$ty::default(), |r, q| TaskKinematics::task_jacobian_det(r, q), None),
                formulas($ty::FORMULAS),
            ));
        )*};
    }
    macro_rules! seven {
        ($($name:literal => $ty:ident),* $(,)?) => {$(
            robots.push((
                $name,
                values(&$ty::default(), |_, _| None, Some($ty::IK_FREE - 1)),
                formulas($ty::FORMULAS),
            ));
        )*};
    }
    task!("planar_rr" => PlanarRr, "planar_rrr" => PlanarRrr, "scara" => Scara,
          "cylindrical_rpp" => CylindricalRpp);
    six!("ur3" => Ur3, "ur5" => Ur5, "ur10" => Ur10, "ur5e" => Ur5e, "ur10e" => Ur10e,
         "puma560" => Puma560, "stanford" => Stanford, "kuka_kr6_r900" => KukaKr6R900,
         "abb_irb120" => AbbIrb120, "abb_irb140" => AbbIrb140, "kinova_jaco" => KinovaJaco,
         "ur5_urdf" => Ur5Urdf, "skew_shoulder" => SkewShoulder,
         "ur5e_wrist_offset" => Ur5eWristOffset, "fanuc_crx10ial" => FanucCrx10iaL,
         "widowx250" => WidowX250);
    seven!("panda" => Panda, "kuka_iiwa14" => KukaIiwa14, "panda_urdf" => PandaUrdf,
           "kinova_gen3" => KinovaGen3);
    let body: Vec<String> = robots
        .iter()
        .map(|(name, samples, formulas)| {
            format!("\"{name}\":{{\"formulas\":{formulas},\"samples\":{samples}}}")
        })
        .collect();
    println!("{{{}}}", body.join(",\n"));
}
