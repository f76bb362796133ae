//! Drives the course's planar RRR arm (a = 3.5, 3.5, 2; task `[x, y, θ]`) along a straight
//! line with the Cartesian proportional controller `q ← q + K_p J⁻¹ (x_d ⊖ x(q))`, one step
//! per control period, and reports how far the tool strays from the line.
//!
//! Run: `cargo run --example planar_rrr_line`

use kinegen::control::{cartesian_p_step_task, task_coordinates};
use kinegen::{Kinematics, TaskKinematics};
use nalgebra::{SVector, Vector2};

/// The planar RRR arm in closed form (rows `[vx, vy, vz, ωx, ωy, ωz]`).
struct PlanarRrr {
    a: [f64; 3],
}

impl PlanarRrr {
    fn angles(q: &[f64; 3]) -> [f64; 3] {
        [q[0], q[0] + q[1], q[0] + q[1] + q[2]]
    }
}

impl Kinematics<3> for PlanarRrr {
    const NAME: &'static str = "planar RRR";

    fn fk(&self, q: &[f64; 3]) -> [[f64; 4]; 4] {
        self.frames(q)[2]
    }

    fn frames(&self, q: &[f64; 3]) -> [[[f64; 4]; 4]; 3] {
        let th = Self::angles(q);
        let (mut x, mut y) = (0.0, 0.0);
        let mut out = [[[0.0; 4]; 4]; 3];
        for i in 0..3 {
            let (s, c) = th[i].sin_cos();
            x += self.a[i] * c;
            y += self.a[i] * s;
            out[i] = [
                [c, -s, 0.0, x],
                [s, c, 0.0, y],
                [0.0, 0.0, 1.0, 0.0],
                [0.0, 0.0, 0.0, 1.0],
            ];
        }
        out
    }

    #[allow(clippy::needless_range_loop)] // textbook index notation: column c, link k
    fn jacobian(&self, q: &[f64; 3]) -> [[f64; 3]; 6] {
        let th = Self::angles(q);
        let mut j = [[0.0; 3]; 6];
        for c in 0..3 {
            // Column c: sum over links k ≥ c of a_k (−sin θ_k, cos θ_k).
            for k in c..3 {
                let (s, co) = th[k].sin_cos();
                j[0][c] -= self.a[k] * s;
                j[1][c] += self.a[k] * co;
            }
            j[5][c] = 1.0;
        }
        j
    }

    fn jacobian_ee(&self, q: &[f64; 3]) -> [[f64; 3]; 6] {
        let j = self.jacobian(q);
        let (s, c) = Self::angles(q)[2].sin_cos();
        let mut out = j;
        for col in 0..3 {
            out[0][col] = c * j[0][col] + s * j[1][col];
            out[1][col] = -s * j[0][col] + c * j[1][col];
        }
        out
    }

    fn limits(&self) -> [[f64; 2]; 3] {
        [[f64::NEG_INFINITY, f64::INFINITY]; 3]
    }
}

impl TaskKinematics<3, 3> for PlanarRrr {
    const TASK_ROWS: [usize; 3] = [0, 1, 5];

    fn task_jacobian(&self, q: &[f64; 3]) -> [[f64; 3]; 3] {
        let j = self.jacobian(q);
        [j[0], j[1], j[5]]
    }
}

/// Distance from `p` to the segment `a`–`b`.
fn distance_to_segment(p: Vector2<f64>, a: Vector2<f64>, b: Vector2<f64>) -> f64 {
    let d = b - a;
    let t = ((p - a).dot(&d) / d.norm_squared()).clamp(0.0, 1.0);
    (p - (a + d * t)).norm()
}

fn main() {
    let robot = PlanarRrr { a: [3.5, 3.5, 2.0] };
    let rate_hz = 500.0;
    let duration = 2.0;
    let kp = 0.5;
    // Start configuration and the line it follows: from the tool's start to a point 4 m
    // away, keeping the tool angle.
    let mut q = [0.3, 1.2, -0.9];
    let x0 = task_coordinates(&robot, &q);
    let start = Vector2::new(x0[0], x0[1]);
    let end = Vector2::new(x0[0] + 3.0, x0[1] - 2.5);
    let steps = (duration * rate_hz) as usize;
    let (mut max_err, mut sum_sq, mut max_lag) = (0.0f64, 0.0, 0.0f64);
    for k in 1..=steps {
        // Desired point moves along the line with a smooth (cubic) time law.
        let s = k as f64 / steps as f64;
        let s = s * s * (3.0 - 2.0 * s);
        let p_d = start + (end - start) * s;
        let x_d = SVector::<f64, 3>::new(p_d[0], p_d[1], x0[2]);
        q = match cartesian_p_step_task(&robot, &q, &x_d, kp) {
            Ok(q) => q,
            Err(e) => {
                eprintln!("step {k}: {e}");
                std::process::exit(1);
            }
        };
        let x = task_coordinates(&robot, &q);
        let p = Vector2::new(x[0], x[1]);
        let e = distance_to_segment(p, start, end);
        max_err = max_err.max(e);
        sum_sq += e * e;
        max_lag = max_lag.max((p - p_d).norm());
    }
    // Let the controller settle on the end point.
    let x_end = SVector::<f64, 3>::new(end[0], end[1], x0[2]);
    for _ in 0..50 {
        q = cartesian_p_step_task(&robot, &q, &x_end, kp).expect("non-singular at the end point");
    }
    let final_error = (task_coordinates(&robot, &q) - x_end).norm();
    println!(
        "planar RRR (a = 3.5, 3.5, 2), straight line ({:.3}, {:.3}) -> ({:.3}, {:.3}) m",
        start[0], start[1], end[0], end[1]
    );
    println!("{steps} control steps at {rate_hz} Hz, Kp = {kp}");
    println!(
        "path error (distance to the line): max {max_err:.3e} m, RMS {:.3e} m",
        (sum_sq / steps as f64).sqrt()
    );
    println!("tracking lag behind the moving set-point: max {max_lag:.3e} m");
    println!("final error after settling: {final_error:.3e}");
}
