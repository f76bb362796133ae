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

type M4 = [[f64; 4]; 4];

fn mul(a: &M4, b: &M4) -> M4 {
    core::array::from_fn(|i| core::array::from_fn(|j| (0..4).map(|k| a[i][k] * b[k][j]).sum()))
}

/// The rotation by `angle` about the unit `axis`, in a homogeneous matrix (Rodrigues).
fn turn(axis: [f64; 3], angle: f64) -> M4 {
    let (s, c) = angle.sin_cos();
    let [x, y, z] = axis;
    let v = 1.0 - c;
    [
        [c + x * x * v, x * y * v - z * s, x * z * v + y * s, 0.0],
        [y * x * v + z * s, c + y * y * v, y * z * v - x * s, 0.0],
        [z * x * v - y * s, z * y * v + x * s, c + z * z * v, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

/// The product of the chain's joint transforms, as the URDF specification defines them:
/// `origin` (translation, then `Rz(yaw) Ry(pitch) Rx(roll)`), then the turn about `axis`.
fn reference_fk(q: &[f64; 100]) -> M4 {
    let mut origin = mul(&turn([0.0, 0.0, 1.0], 0.1), &turn([0.0, 1.0, 0.0], 0.2));
    origin = mul(&origin, &turn([1.0, 0.0, 0.0], 0.3));
    (origin[0][3], origin[1][3], origin[2][3]) = (0.1, 0.05, 0.2);
    q.iter().fold(turn([1.0, 0.0, 0.0], 0.0), |t, &qi| {
        mul(&mul(&t, &origin), &turn([0.6, 0.8, 0.0], qi))
    })
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
