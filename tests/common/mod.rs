//! Hand-written test robots implementing `kinegen::Kinematics` numerically (DH matrix
//! products, Jacobian columns `z_{i-1} × (p − o_{i-1})`), until the generated robots of
//! `kinegen-robots` replace them. Standard DH: `A_i = Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i)`.
#![allow(dead_code)]

use core::f64::consts::FRAC_PI_2;
use kinegen::{Kinematics, TaskKinematics};
use nalgebra::{Matrix4, Vector3};

/// A revolute-only serial arm in standard DH.
#[derive(Debug, Clone, Copy)]
pub struct DhRobot<const N: usize> {
    pub a: [f64; N],
    pub d: [f64; N],
    pub alpha: [f64; N],
    pub limits: [[f64; 2]; N],
}

fn dh(theta: f64, d: f64, a: f64, alpha: f64) -> Matrix4<f64> {
    let (st, ct) = theta.sin_cos();
    let (sa, ca) = alpha.sin_cos();
    Matrix4::new(
        ct,
        -st * ca,
        st * sa,
        a * ct,
        st,
        ct * ca,
        -ct * sa,
        a * st,
        0.0,
        sa,
        ca,
        d,
        0.0,
        0.0,
        0.0,
        1.0,
    )
}

fn to_rows(m: &Matrix4<f64>) -> [[f64; 4]; 4] {
    let mut r = [[0.0; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            r[i][j] = m[(i, j)];
        }
    }
    r
}

impl<const N: usize> DhRobot<N> {
    fn chain(&self, q: &[f64; N]) -> [Matrix4<f64>; N] {
        let mut out = [Matrix4::identity(); N];
        let mut t = Matrix4::identity();
        for i in 0..N {
            t *= dh(q[i], self.d[i], self.a[i], self.alpha[i]);
            out[i] = t;
        }
        out
    }
}

impl<const N: usize> Kinematics<N> for DhRobot<N> {
    const NAME: &'static str = "dh-test-robot";

    fn fk(&self, q: &[f64; N]) -> [[f64; 4]; 4] {
        to_rows(&self.chain(q)[N - 1])
    }

    fn frames(&self, q: &[f64; N]) -> [[[f64; 4]; 4]; N] {
        let c = self.chain(q);
        let mut out = [[[0.0; 4]; 4]; N];
        for i in 0..N {
            out[i] = to_rows(&c[i]);
        }
        out
    }

    fn jacobian(&self, q: &[f64; N]) -> [[f64; N]; 6] {
        let c = self.chain(q);
        let p = c[N - 1].fixed_view::<3, 1>(0, 3).into_owned();
        let mut j = [[0.0; N]; 6];
        for i in 0..N {
            let prev = if i == 0 {
                Matrix4::identity()
            } else {
                c[i - 1]
            };
            let z: Vector3<f64> = prev.fixed_view::<3, 1>(0, 2).into_owned();
            let o: Vector3<f64> = prev.fixed_view::<3, 1>(0, 3).into_owned();
            let v = z.cross(&(p - o));
            for r in 0..3 {
                j[r][i] = v[r];
                j[r + 3][i] = z[r];
            }
        }
        j
    }

    fn jacobian_ee(&self, q: &[f64; N]) -> [[f64; N]; 6] {
        let t = self.chain(q)[N - 1];
        let rt = t.fixed_view::<3, 3>(0, 0).transpose();
        let j = self.jacobian(q);
        let mut out = [[0.0; N]; 6];
        for c in 0..N {
            let v = rt * Vector3::new(j[0][c], j[1][c], j[2][c]);
            let w = rt * Vector3::new(j[3][c], j[4][c], j[5][c]);
            for r in 0..3 {
                out[r][c] = v[r];
                out[r + 3][c] = w[r];
            }
        }
        out
    }

    fn limits(&self) -> [[f64; 2]; N] {
        self.limits
    }

    fn jacobian_det(&self, q: &[f64; N]) -> Option<f64> {
        if N != 6 {
            return None;
        }
        let j = self.jacobian(q);
        Some(
            nalgebra::SMatrix::<f64, 6, N>::from_fn(|r, c| j[r][c])
                .fixed_view::<6, 6>(0, 0)
                .determinant(),
        )
    }
}

/// Planar RR arm (L1 = 1, L2 = 0.8) with task `[x, y]`.
pub fn planar_rr() -> DhRobot<2> {
    DhRobot {
        a: [1.0, 0.8],
        d: [0.0; 2],
        alpha: [0.0; 2],
        limits: [[-std::f64::consts::PI, std::f64::consts::PI]; 2],
    }
}

impl TaskKinematics<2, 2> for DhRobot<2> {
    const TASK_ROWS: [usize; 2] = [0, 1];
    fn task_jacobian(&self, q: &[f64; 2]) -> [[f64; 2]; 2] {
        let j = self.jacobian(q);
        [j[0], j[1]]
    }
}

/// Planar RRR arm of the course (a = 3.5, 3.5, 2) with task `[x, y, θ]`.
pub fn planar_rrr() -> DhRobot<3> {
    DhRobot {
        a: [3.5, 3.5, 2.0],
        d: [0.0; 3],
        alpha: [0.0; 3],
        limits: [[f64::NEG_INFINITY, f64::INFINITY]; 3],
    }
}

impl TaskKinematics<3, 3> for DhRobot<3> {
    const TASK_ROWS: [usize; 3] = [0, 1, 5];
    fn task_jacobian(&self, q: &[f64; 3]) -> [[f64; 3]; 3] {
        let j = self.jacobian(q);
        [j[0], j[1], j[5]]
    }
}

pub const UR5_A2: f64 = -0.425;
pub const UR5_A3: f64 = -0.39225;
pub const UR5_D5: f64 = 0.09465;

/// UR5, standard DH (Universal Robots' published parameters), joint limits ±2π.
pub fn ur5() -> DhRobot<6> {
    let tau = 2.0 * std::f64::consts::PI;
    DhRobot {
        a: [0.0, UR5_A2, UR5_A3, 0.0, 0.0, 0.0],
        d: [0.089159, 0.0, 0.0, 0.10915, UR5_D5, 0.0823],
        alpha: [FRAC_PI_2, 0.0, 0.0, FRAC_PI_2, -FRAC_PI_2, 0.0],
        limits: [[-tau, tau]; 6],
    }
}

/// The UR5 shoulder-singularity factor `a2 c2 + a3 c23 + d5 s234`.
pub fn ur5_shoulder_factor(q: &[f64; 6]) -> f64 {
    UR5_A2 * q[1].cos() + UR5_A3 * (q[1] + q[2]).cos() + UR5_D5 * (q[1] + q[2] + q[3]).sin()
}

/// A UR5 configuration on the shoulder singularity: keeps q1, q3, q4 and solves
/// `a2 c2 + a3 c23 + d5 s234 = 0` for q2 by bisection on a sign change.
pub fn ur5_shoulder_singular(mut q: [f64; 6]) -> Option<[f64; 6]> {
    let f = |q2: f64, q: &[f64; 6]| {
        let mut qq = *q;
        qq[1] = q2;
        ur5_shoulder_factor(&qq)
    };
    let n = 64;
    let (lo, hi) = (-std::f64::consts::PI, std::f64::consts::PI);
    for k in 0..n {
        let (mut a, mut b) = (
            lo + (hi - lo) * k as f64 / n as f64,
            lo + (hi - lo) * (k + 1) as f64 / n as f64,
        );
        if f(a, &q).signum() != f(b, &q).signum() {
            for _ in 0..200 {
                let m = 0.5 * (a + b);
                if f(m, &q).signum() == f(a, &q).signum() {
                    a = m;
                } else {
                    b = m;
                }
            }
            q[1] = 0.5 * (a + b);
            return Some(q);
        }
    }
    None
}

/// A 7-joint redundant arm (UR5-like with an extra wrist roll) for pseudo-inverse tests.
pub fn redundant7() -> DhRobot<7> {
    DhRobot {
        a: [0.0, -0.425, -0.39225, 0.0, 0.0, 0.0, 0.05],
        d: [0.089159, 0.0, 0.0, 0.10915, 0.09465, 0.0823, 0.05],
        alpha: [FRAC_PI_2, 0.0, 0.0, FRAC_PI_2, -FRAC_PI_2, FRAC_PI_2, 0.0],
        limits: [[-6.0, 6.0]; 7],
    }
}

/// Central finite differences of the tool position and `J` columns agree (sanity of the
/// hand-written robots themselves).
pub fn fd_position_jacobian<R: Kinematics<N>, const N: usize>(
    robot: &R,
    q: &[f64; N],
) -> [[f64; N]; 3] {
    let h = 1e-6;
    let mut out = [[0.0; N]; 3];
    for c in 0..N {
        let (mut qp, mut qm) = (*q, *q);
        qp[c] += h;
        qm[c] -= h;
        let (tp, tm) = (robot.fk(&qp), robot.fk(&qm));
        for r in 0..3 {
            out[r][c] = (tp[r][3] - tm[r][3]) / (2.0 * h);
        }
    }
    out
}

/// `count` deterministic configurations of `N` joint values in [-π, π]
/// ([`kinegen_core::numeric::configurations`]).
pub fn configurations<const N: usize>(seed: u64, count: usize) -> Vec<[f64; N]> {
    kinegen_core::numeric::configurations(seed, count, N)
        .into_iter()
        .map(|q| core::array::from_fn(|i| q[i]))
        .collect()
}
