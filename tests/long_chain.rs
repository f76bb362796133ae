//! A 100-joint chain of oblique joints (every axis `0.6 0.8 0`, every origin turned by
//! rpy `0.3 0.2 0.1` and shifted by `0.1 0.05 0.2`: no two axes parallel or meeting, so
//! no normal form stays small) compiles in the test suite's debug build and computes its
//! forward kinematics. Its `fk` body binds over 4 000 intermediates; when each was a
//! `let` in one run, their nested scopes overflowed rustc's stack while LLVM wrote the
//! debug information (a SIGSEGV), from about 100 joints on. The bodies are now cut into
//! blocks (`emit::code`'s `MAX_LET_RUN`).

kinegen::kinematics! {
    /// The oblique chain, from `tests/data/oblique100.urdf`.
    // Its normal forms overflow the term budget on purpose: the notes are warnings.
    #[allow(deprecated)]
    pub struct Oblique100 = urdf("tests/data/oblique100.urdf");
}

use kinegen::nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

/// The product of the chain's joint transforms, as the URDF specification defines them:
/// `origin` (translation, then roll, pitch, yaw about fixed axes), then the turn about
/// `axis`.
fn reference_fk(q: &[f64; 100]) -> [[f64; 4]; 4] {
    let origin = Isometry3::from_parts(
        Translation3::new(0.1, 0.05, 0.2),
        UnitQuaternion::from_euler_angles(0.3, 0.2, 0.1),
    );
    let axis = Vector3::new(0.6, 0.8, 0.0);
    let t = q.iter().fold(Isometry3::identity(), |t, &qi| {
        t * origin * Isometry3::rotation(axis * qi)
    });
    let m = t.to_homogeneous();
    core::array::from_fn(|i| core::array::from_fn(|j| m[(i, j)]))
}

#[test]
fn the_generated_fk_is_the_product_of_the_joints() {
    let robot = Oblique100;
    for k in 0..3 {
        let q: [f64; 100] = core::array::from_fn(|i| 0.7 * (i as f64 * 0.37 + k as f64).sin());
        let (ours, theirs) = (robot.fk(&q), reference_fk(&q));
        // The chain reaches ~20 m: rounding in 100 products of 4 × 4 matrices.
        for i in 0..3 {
            for j in 0..4 {
                assert!(
                    (ours[i][j] - theirs[i][j]).abs() <= 1e-9 * 20.0,
                    "q{k}: T[{i}][{j}] {} against {}",
                    ours[i][j],
                    theirs[i][j]
                );
            }
        }
    }
}
