//! A user's crate on nalgebra 0.35 (the newest kinegen accepts): kinegen resolves to the
//! same nalgebra, so the runtime's nalgebra types are this crate's. This compiles only
//! if they are one crate (`same_crate` below), and the run checks that the runtime
//! built on 0.35 still solves: every configuration of 300 is among the closed-form
//! solutions of its pose, for the UR5 (a subproblem family) and the Jaco (the general
//! 6R, whose pencil and null spaces are nalgebra matrices).
//!
//! Run by `.ci/run` (`cargo run` here); exit status 0 when every check holds.

use kinegen::{InverseKinematics, Kinematics};
use nalgebra::{Isometry3, SMatrix, Vector3};

kinegen::kinematics! {
    /// The UR5 (`robots/ur5.toml`).
    pub struct Ur5 = "../../robots/ur5.toml";
}

kinegen::kinematics! {
    /// The Kinova Jaco, 60° wrist (`robots/kinova_jaco.toml`).
    pub struct Jaco = "../../robots/kinova_jaco.toml";
}

/// Does not compile when kinegen's nalgebra is another crate than this one's.
fn same_crate(pose: kinegen::nalgebra::Isometry3<f64>) -> Isometry3<f64> {
    pose
}

/// `count` seeded configurations within ±3 rad; each is found again (to 1e-6 rad, whole
/// turns aside) among the exact solutions of its pose, passed through nalgebra.
fn recovers<R: Kinematics<6> + InverseKinematics<6>>(robot: &R, seed: u64, count: usize) -> usize {
    let mut rng = kinegen::ik::XorShift64::new(seed);
    let mut found = 0;
    for _ in 0..count {
        let q: [f64; 6] = core::array::from_fn(|_| -3.0 + 6.0 * rng.next_f64());
        let pose: Isometry3<f64> = same_crate(kinegen::adapters::fk_isometry(robot, &q));
        let target = kinegen::adapters::pose_matrix(&pose);
        let mut hit = false;
        robot.ik_each(&target, &q, &mut |branch| {
            let off = |i: usize| {
                let d = (branch.q[i] - q[i]).rem_euclid(core::f64::consts::TAU);
                d.min(core::f64::consts::TAU - d)
            };
            hit |= branch.exact && (0..6).all(|i| off(i) < 1e-6);
        });
        found += usize::from(hit);
    }
    found
}

fn main() {
    let ur5 = Ur5::default();
    let q = [0.3, -1.1, 1.4, -0.2, 0.9, 0.5];
    // Matrices of this crate's nalgebra straight from kinegen's adapters.
    let j: SMatrix<f64, 6, 6> = kinegen::adapters::jacobian_matrix(&ur5, &q);
    assert!(
        (j.determinant() - ur5.jacobian_det(&q)).abs() < 1e-12,
        "det J"
    );
    let start = kinegen::adapters::fk_isometry(&ur5, &q);
    let end = Isometry3::new(Vector3::new(0.3, 0.2, 0.4), Vector3::new(0.0, 3.0, 0.0));
    let profile = kinegen::trajectory::Quintic::rest_to_rest(0.0, 1.0, 0.5, 1.0).expect("profile");
    let line = kinegen::trajectory::CartesianLine::new(start, end, profile).expect("line");
    let at_end: Isometry3<f64> = line.pose(line.duration());
    assert!(
        (at_end.translation.vector - end.translation.vector).norm() < 1e-12,
        "line end"
    );

    let (ur5_found, jaco_found) = (recovers(&ur5, 35, 300), recovers(&Jaco::default(), 36, 300));
    println!("nalgebra 0.35: UR5 {ur5_found}/300, Jaco {jaco_found}/300 configurations recovered");
    assert_eq!(ur5_found, 300, "UR5");
    // The Jaco's general 6R: the workspace's self-test holds it to every regular pose;
    // random configurations within ±3 rad are regular with probability one.
    assert_eq!(jaco_found, 300, "Jaco");
}
