//! What the benches share: the robots' numeric models, the configurations they cycle
//! through, the lean nalgebra DH loop every contender is compared with (and its textbook
//! Hessian), criterion's medians of this run, and interleaved ratios.

// Each bench uses a part of this.
#![allow(dead_code)]

use criterion::Bencher;
use kinegen::ik::XorShift64;
use kinegen_core::model::{dh::Convention, robot::JointKind};
use kinegen_core::numeric::NumericRobot;
use nalgebra::{Matrix4, Matrix6, SMatrix, Vector3};
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::{Instant, SystemTime};

/// Number of configurations cycled through (a power of two: the index wraps with a mask).
pub const CONFIGS: usize = 1024;

pub fn load(file: &str) -> NumericRobot {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("robots")
        .join(file);
    let robot = kinegen_core::front::toml_file::load_file(&path)
        .unwrap_or_else(|e| panic!("{file}: {e:?}"))
        .0;
    NumericRobot::new(&robot).unwrap()
}

pub fn configurations<const N: usize>(limits: &[[f64; 2]; N], seed: u64) -> Vec<[f64; N]> {
    let mut rng = XorShift64::new(seed);
    (0..CONFIGS).map(|_| rng.configuration(limits)).collect()
}

/// Time `f` on the configurations in turn.
pub fn cycle<const N: usize, R>(
    b: &mut Bencher,
    qs: &[[f64; N]],
    mut f: impl FnMut([f64; N]) -> R,
) {
    let mut i = 0;
    b.iter(|| {
        let q = black_box(qs[i]);
        i = (i + 1) & (CONFIGS - 1);
        f(q)
    })
}

/// The lean numeric reference: what a user writes with nalgebra from the DH table.
pub struct DhLoop<const N: usize> {
    standard: bool,
    /// Per joint `[a, d, θ offset, cos α, sin α]`.
    links: [[f64; 5]; N],
    base: Matrix4<f64>,
    tool: Matrix4<f64>,
}

impl<const N: usize> DhLoop<N> {
    pub fn new(r: &NumericRobot) -> Self {
        assert_eq!(r.dof(), N);
        assert!(r.joints.iter().all(|j| j.kind == JointKind::Revolute));
        let mut links = [[0.0; 5]; N];
        for (l, j) in links.iter_mut().zip(&r.joints) {
            let (sa, ca) = j.alpha.sin_cos();
            *l = [j.a, j.d, j.theta, ca, sa];
        }
        DhLoop {
            standard: r.convention == Convention::Standard,
            links,
            base: r.base,
            tool: r.tool,
        }
    }

    /// `A_i(q)` in closed form (standard `Rz Tz Tx Rx`, modified `Rx Tx Rz Tz`).
    #[inline]
    fn link(&self, i: usize, q: f64) -> Matrix4<f64> {
        let [a, d, th, ca, sa] = self.links[i];
        let (s, c) = (th + q).sin_cos();
        if self.standard {
            Matrix4::new(
                c,
                -s * ca,
                s * sa,
                a * c, //
                s,
                c * ca,
                -c * sa,
                a * s, //
                0.0,
                sa,
                ca,
                d, //
                0.0,
                0.0,
                0.0,
                1.0,
            )
        } else {
            Matrix4::new(
                c,
                -s,
                0.0,
                a, //
                s * ca,
                c * ca,
                -sa,
                -sa * d, //
                s * sa,
                c * sa,
                ca,
                ca * d, //
                0.0,
                0.0,
                0.0,
                1.0,
            )
        }
    }

    pub fn fk(&self, q: &[f64; N]) -> Matrix4<f64> {
        let mut t = self.base;
        for (i, &qi) in q.iter().enumerate() {
            t *= self.link(i, qi);
        }
        t * self.tool
    }

    /// Tool pose and world-frame Jacobian, columns `[z × (p − o); z]`.
    pub fn fk_and_jacobian(&self, q: &[f64; N]) -> (Matrix4<f64>, SMatrix<f64, 6, N>) {
        // Joint i's axis frame: frame i−1 (standard), frame i (modified).
        let mut axes = [Matrix4::identity(); N];
        let mut t = self.base;
        for (i, &qi) in q.iter().enumerate() {
            if self.standard {
                axes[i] = t;
            }
            t *= self.link(i, qi);
            if !self.standard {
                axes[i] = t;
            }
        }
        let t = t * self.tool;
        let p: Vector3<f64> = t.fixed_view::<3, 1>(0, 3).into_owned();
        let mut j = SMatrix::<f64, 6, N>::zeros();
        for (i, f) in axes.iter().enumerate() {
            let z: Vector3<f64> = f.fixed_view::<3, 1>(0, 2).into_owned();
            let o: Vector3<f64> = f.fixed_view::<3, 1>(0, 3).into_owned();
            j.fixed_view_mut::<3, 1>(0, i).copy_from(&z.cross(&(p - o)));
            j.fixed_view_mut::<3, 1>(3, i).copy_from(&z);
        }
        (t, j)
    }

    pub fn jacobian(&self, q: &[f64; N]) -> SMatrix<f64, 6, N> {
        self.fk_and_jacobian(q).1
    }
}

impl<const N: usize> DhLoop<N> {
    /// The kinematic Hessian the textbook way (Haviland & Corke): from the Jacobian's
    /// columns `[v_i; z_i]`, `H[j]` column `i` is `[z_j × v_i; z_j × z_i]` for `j ≤ i` and
    /// `[z_i × v_j; 0]` for `j > i` (all joints revolute).
    pub fn hessian(&self, q: &[f64; N]) -> [SMatrix<f64, 6, N>; N] {
        let (_, j) = self.fk_and_jacobian(q);
        let col = |i: usize| -> (Vector3<f64>, Vector3<f64>) {
            (
                j.fixed_view::<3, 1>(0, i).into_owned(),
                j.fixed_view::<3, 1>(3, i).into_owned(),
            )
        };
        let mut h = [SMatrix::<f64, 6, N>::zeros(); N];
        for i in 0..N {
            let (vi, zi) = col(i);
            for k in 0..=i {
                let zk = col(k).1;
                let lin = zk.cross(&vi);
                h[k].fixed_view_mut::<3, 1>(0, i).copy_from(&lin);
                h[k].fixed_view_mut::<3, 1>(3, i).copy_from(&zk.cross(&zi));
                if k < i {
                    h[i].fixed_view_mut::<3, 1>(0, k).copy_from(&lin);
                }
            }
        }
        h
    }

    /// `J̇ q̇ = Σ_j q̇_j H[j] q̇` from [`DhLoop::hessian`].
    pub fn jdot_qdot(&self, q: &[f64; N], qd: &[f64; N]) -> nalgebra::Vector6<f64> {
        let h = self.hessian(q);
        let v = nalgebra::SVector::<f64, N>::from(*qd);
        h.iter().zip(qd).map(|(hj, &r)| hj * v * r).sum()
    }
}

impl DhLoop<6> {
    pub fn jacobian_det(&self, q: &[f64; 6]) -> f64 {
        let j: Matrix6<f64> = self.jacobian(q);
        j.determinant()
    }
}

/// Where criterion writes its results (its own rule: `CRITERION_HOME`, else the cargo
/// target directory's `criterion/`).
pub fn criterion_home() -> PathBuf {
    if let Some(h) = std::env::var_os("CRITERION_HOME") {
        return h.into();
    }
    let target = std::env::var_os("CARGO_TARGET_DIR").map_or_else(
        || Path::new(env!("CARGO_MANIFEST_DIR")).join("target"),
        PathBuf::from,
    );
    target.join("criterion")
}

/// The median (ns) of `group/id` if this run measured it (file newer than `since`).
pub fn median(group: &str, id: &str, since: SystemTime) -> Option<f64> {
    let path = criterion_home()
        .join(group)
        .join(id.replace('/', "_"))
        .join("new/estimates.json");
    if std::fs::metadata(&path).ok()?.modified().ok()? < since {
        return None;
    }
    let text = std::fs::read_to_string(&path).ok()?;
    let rest = &text[text.find("\"median\"")?..];
    let rest = &rest[rest.find("\"point_estimate\":")? + "\"point_estimate\":".len()..];
    let end = rest.find([',', '}'])?;
    rest[..end].trim().parse().ok()
}

/// Mean time per call (ns) of `f` over `iters` calls on the configurations in turn.
pub fn batch<const N: usize, R>(
    qs: &[[f64; N]],
    f: &mut impl FnMut([f64; N]) -> R,
    iters: usize,
) -> f64 {
    let t = Instant::now();
    for k in 0..iters {
        black_box(f(black_box(qs[k & (CONFIGS - 1)])));
    }
    t.elapsed().as_nanos() as f64 / iters as f64
}

/// `a / b` robust to a drifting machine load: short batches of `a` and `b` alternate
/// (order swapped every round) and the median of the per-round ratios is returned.
pub fn paired<const N: usize, R, S>(
    qs: &[[f64; N]],
    mut a: impl FnMut([f64; N]) -> R,
    mut b: impl FnMut([f64; N]) -> S,
) -> f64 {
    // Batches of about 2 ms of the slower one.
    let probe = batch(qs, &mut a, 200).max(batch(qs, &mut b, 200));
    let iters = ((2e6 / probe) as usize).clamp(200, 200_000);
    let mut ratios: Vec<f64> = (0..41)
        .map(|round| {
            if round % 2 == 0 {
                let ta = batch(qs, &mut a, iters);
                ta / batch(qs, &mut b, iters)
            } else {
                let tb = batch(qs, &mut b, iters);
                batch(qs, &mut a, iters) / tb
            }
        })
        .collect();
    ratios.sort_by(f64::total_cmp);
    ratios[ratios.len() / 2]
}

/// A bench's `main`: with `KINEGEN_BENCH_PAIRED` set only the interleaved ratios
/// (`paired_table`); else the criterion `benches`, and after a real `--bench` run the
/// tables of this run's medians (`summary`) and, when no filter picked some benchmarks
/// only, the interleaved ratios. (`cargo test --benches` runs each benchmark once without
/// `--bench`: no tables then.)
pub fn bench_main(benches: fn(), summary: fn(SystemTime), paired_table: fn()) {
    let start = SystemTime::now();
    if std::env::var_os("KINEGEN_BENCH_PAIRED").is_some() {
        paired_table();
        return;
    }
    benches();
    criterion::Criterion::default()
        .configure_from_args()
        .final_summary();
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.iter().any(|a| a == "--bench") {
        summary(start);
        if args.iter().all(|a| a.starts_with("--")) {
            paired_table();
        }
    }
}
