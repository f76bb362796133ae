//! Inverse velocity kinematics, pseudo-inverses, DLS, static forces, manipulability and
//! the analytical Jacobian on hand-written robots (see `common`).

mod common;

use common::*;
use kinegen::adapters::{jacobian_matrix, rotation_of, task_jacobian_matrix};
use kinegen::analytic::{
    analytical_jacobian, analytical_jacobian_at, euler_angles, euler_rate_matrix, EulerConvention,
};
use kinegen::forces::{joint_torques, joint_torques_at};
use kinegen::linalg::{Lu, Svd};
use kinegen::manipulability::{
    condition_number, manipulability, manipulability_rot, manipulability_task,
    manipulability_trans, measures, smallest_singular_value,
};
use kinegen::velocity::*;
use kinegen::{Kinematics, SolveError};
use nalgebra::{DMatrix, Matrix3, SMatrix, SVector, Vector3};
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;
#[path = "../kinegen-core/tests/common/fixed_seed.rs"]
mod fixed_seed;
use fixed_seed::fixed_seed;
use std::f64::consts::{FRAC_PI_2, PI};

fn angle() -> impl Strategy<Value = f64> {
    -PI..PI
}
fn q6() -> impl Strategy<Value = [f64; 6]> {
    [angle(), angle(), angle(), angle(), angle(), angle()]
}
fn q7() -> impl Strategy<Value = [f64; 7]> {
    [
        angle(),
        angle(),
        angle(),
        angle(),
        angle(),
        angle(),
        angle(),
    ]
}
fn v6() -> impl Strategy<Value = SVector<f64, 6>> {
    [
        -1.0..1.0f64,
        -1.0..1.0,
        -1.0..1.0,
        -1.0..1.0,
        -1.0..1.0,
        -1.0..1.0,
    ]
    .prop_map(SVector::from)
}

/// Independent reference: nalgebra's own (allocating, bidiagonal) SVD.
fn reference_singular_values<const M: usize, const N: usize>(j: &SMatrix<f64, M, N>) -> Vec<f64> {
    let d = DMatrix::from_fn(M, N, |r, c| j[(r, c)]);
    let mut s: Vec<f64> = d
        .svd(false, false)
        .singular_values
        .iter()
        .copied()
        .collect();
    s.sort_by(|a, b| b.partial_cmp(a).unwrap());
    s
}

fn penrose<const M: usize, const N: usize>(
    j: &SMatrix<f64, M, N>,
    p: &SMatrix<f64, N, M>,
    tol: f64,
) {
    let jp = j * p;
    let pj = p * j;
    assert!((jp * j - j).norm() <= tol * (1.0 + j.norm()), "J J+ J != J");
    assert!(
        (pj * p - p).norm() <= tol * (1.0 + p.norm()),
        "J+ J J+ != J+"
    );
    assert!(
        (jp - jp.transpose()).norm() <= tol * (1.0 + jp.norm()),
        "J J+ not symmetric"
    );
    assert!(
        (pj - pj.transpose()).norm() <= tol * (1.0 + pj.norm()),
        "J+ J not symmetric"
    );
}

#[test]
fn test_robots_match_finite_differences() {
    let q = [0.3, -1.1, 0.7, 0.4, -0.9, 1.3];
    let r = ur5();
    let fd = fd_position_jacobian(&r, &q);
    let j = r.jacobian(&q);
    for row in 0..3 {
        for c in 0..6 {
            assert!((fd[row][c] - j[row][c]).abs() < 1e-8);
        }
    }
    // The UR5 determinant factors as a2 a3 s3 s5 (a2 c2 + a3 c23 + d5 s234), up to sign.
    let det = r.jacobian_det(&q).unwrap();
    let closed = UR5_A2 * UR5_A3 * q[2].sin() * q[4].sin() * ur5_shoulder_factor(&q);
    assert!(
        (det.abs() - closed.abs()).abs() < 1e-12,
        "{det} vs {closed}"
    );
}

/// The stack-only SVD of the 6×7 arm's Jacobian against nalgebra's.
fn check_singular_values(q: [f64; 7]) -> Result<(), TestCaseError> {
    let j = jacobian_matrix(&redundant7(), &q);
    let svd = Svd::new(&j).unwrap();
    let reference = reference_singular_values(&j);
    for k in 0..6 {
        prop_assert!((svd.singular_values[k] - reference[k]).abs() < 1e-12 * (1.0 + reference[0]));
    }
    prop_assert!(svd.singular_values[6].abs() < 1e-12);
    // U Σ Vᵀ = J
    let rebuilt =
        svd.u * SMatrix::<f64, 7, 7>::from_diagonal(&svd.singular_values) * svd.v.transpose();
    prop_assert!((rebuilt - j).norm() < 1e-12);
    Ok(())
}

/// Penrose identities of every pseudo-inverse, redundant (6×7) and tall (6×3).
fn check_pseudo_inverses(q: [f64; 7]) -> Result<(), TestCaseError> {
    // Redundant 6×7: right pseudo-inverse and SVD agree.
    let j = jacobian_matrix(&redundant7(), &q);
    let sv = reference_singular_values(&j);
    prop_assume!(sv[5] > 1e-3);
    let p_svd = pinv_svd(&j, 1e-12).unwrap();
    let p_right = pinv_right(&j, 1e-14).unwrap();
    penrose(&j, &p_svd, 1e-9);
    penrose(&j, &p_right, 1e-7);
    prop_assert!((p_svd - p_right).norm() < 1e-6 * (sv[0] / sv[5]).powi(2));
    prop_assert!(
        pinv_left(&j, DEFAULT_TOLERANCE).is_err(),
        "JᵀJ of a 6×7 is singular"
    );
    // Tall 6×3: planar RRR full Jacobian, left pseudo-inverse.
    let q3 = [q[0], q[1], q[2]];
    let j3 = jacobian_matrix(&planar_rrr(), &q3);
    if q[1].sin().abs() > 1e-2 {
        let p_left = pinv_left(&j3, 1e-14).unwrap();
        penrose(&j3, &p_left, 1e-8);
        prop_assert!(
            (p_left - pinv_svd(&j3, 1e-12).unwrap()).norm() < 1e-8 * (1.0 + p_left.norm())
        );
    }
    Ok(())
}

/// How far `√det(J Jᵀ)` of an `m`-row `J` (LU determinant of the Gram matrix) may be
/// from `w = σ₁⋯σₘ`: the determinant errs by `δ ≲ 4m²ε·σ₁²ᵐ` (each of the m² entries of
/// `J Jᵀ`, rounded relative `mε`, times a cofactor ≤ σ₁²⁽ᵐ⁻¹⁾), and
/// `|√a − √b| ≤ min(√|a − b|, |a − b|/√a)` — about `√ε·σ₁ᵐ` where `w ≈ 0`.
fn sqrt_det_tolerance(m: usize, sigma_1: f64, w: f64) -> f64 {
    let delta = 4.0 * (m * m) as f64 * f64::EPSILON * sigma_1.max(1.0).powi(2 * m as i32);
    if w > 0.0 {
        delta.sqrt().min(delta / w)
    } else {
        delta.sqrt()
    }
}

/// Every manipulability against the reference singular values (nalgebra's SVD): the
/// product of the `m` largest, or 0 for a tall block, within `m·16ε·σ₁ᵐ` — each of the
/// two SVDs moves a singular value by a few `ε·σ₁`.
fn check_manipulability(q: [f64; 7]) -> Result<(), TestCaseError> {
    fn reference_w<const M: usize, const N: usize>(j: &SMatrix<f64, M, N>) -> (f64, f64) {
        let sv = reference_singular_values(j);
        let tol = M as f64 * 16.0 * f64::EPSILON * sv[0].max(1.0).powi(M as i32);
        let w = if M > N {
            0.0
        } else {
            sv.iter().take(M).product()
        };
        (w, tol)
    }
    let j = jacobian_matrix(&redundant7(), &q);
    let (w_ref, tol) = reference_w(&j);
    let w = manipulability(&j).unwrap();
    prop_assert!((w - w_ref).abs() <= tol, "{w} vs {w_ref}");
    // ... which is √det(J Jᵀ), to the determinant's rounding.
    let det = (j * j.transpose()).determinant();
    let tol = sqrt_det_tolerance(6, reference_singular_values(&j)[0], w);
    prop_assert!((w - det.max(0.0).sqrt()).abs() <= tol, "{w} vs sqrt({det})");
    // The Robotics Toolbox's axes: linear rows, angular rows.
    let (trans, rot) = (
        j.fixed_rows::<3>(0).into_owned(),
        j.fixed_rows::<3>(3).into_owned(),
    );
    let ((wt, tol_t), (wr, tol_r)) = (reference_w(&trans), reference_w(&rot));
    prop_assert!((manipulability_trans(&j).unwrap() - wt).abs() <= tol_t);
    prop_assert!((manipulability_rot(&j).unwrap() - wr).abs() <= tol_r);
    let reference = reference_singular_values(&j);
    let m = measures(&j).unwrap();
    prop_assert_eq!(m.yoshikawa, w);
    prop_assert!((m.sigma_min - reference[5]).abs() < 1e-12);
    prop_assert!((smallest_singular_value(&j).unwrap() - reference[5]).abs() < 1e-12);
    if reference[5] > 1e-6 {
        prop_assert!(
            (condition_number(&j).unwrap() - reference[0] / reference[5]).abs()
                < 1e-6 * reference[0] / reference[5]
        );
    }
    // Square: √det(JJᵀ) = |det J|.
    let q6 = [q[0], q[1], q[2], q[3], q[4], q[5]];
    let j6 = jacobian_matrix(&ur5(), &q6);
    prop_assert!((manipulability(&j6).unwrap() - j6.determinant().abs()).abs() < 1e-12);
    // Planar RR: the full 6×2 Jacobian cannot move in six directions (0, exactly); its
    // task rows [x, y] give L1 L2 |sin q2|; its linear rows, 3×2, are tall: 0 too.
    let rr = [q[0], q[1]];
    let jrr = jacobian_matrix(&planar_rr(), &rr);
    prop_assert_eq!(manipulability(&jrr).unwrap(), 0.0);
    prop_assert_eq!(manipulability_trans(&jrr).unwrap(), 0.0);
    let task = manipulability_task(&planar_rr(), &rr).unwrap();
    prop_assert!((task - 0.8 * q[1].sin().abs()).abs() < 1e-12);
    prop_assert_eq!(
        task,
        manipulability(&task_jacobian_matrix(&planar_rr(), &rr)).unwrap()
    );
    Ok(())
}

proptest! {
    #![proptest_config(fixed_seed(200))]

    #[test]
    fn singular_values_match_reference(q in q7()) {
        check_singular_values(q)?;
    }

    #[test]
    fn pseudo_inverses_satisfy_penrose_identities(q in q7()) {
        check_pseudo_inverses(q)?;
    }

    #[test]
    fn manipulability_matches_the_reference(q in q7()) {
        check_manipulability(q)?;
    }

    #[test]
    fn inverse_velocity_reproduces_twist(q in q6(), xdot in v6()) {
        let j = jacobian_matrix(&ur5(), &q);
        let sv = reference_singular_values(&j);
        prop_assume!(sv[5] > 1e-3);
        let qd = inverse_velocity(&j, &xdot, DEFAULT_TOLERANCE).unwrap();
        prop_assert!((j * qd - xdot).norm() <= 1e-9 * (1.0 + xdot.norm()) * sv[0] / sv[5]);
        // LU determinant agrees with nalgebra's.
        let det = Lu::new(&j, DEFAULT_TOLERANCE).unwrap().determinant();
        prop_assert!((det - j.determinant()).abs() <= 1e-12 * (1.0 + det.abs()));
    }

    #[test]
    fn dls_is_bounded_at_exact_ur5_singularities(q in q6(), xdot in v6(), which in 0usize..3) {
        let mut q = q;
        match which {
            0 => q[2] = 0.0,          // elbow: q3 = 0
            1 => q[4] = 0.0,          // wrist: q5 = 0
            _ => q = match ur5_shoulder_singular(q) { Some(q) => q, None => return Ok(()) },
        }
        let j = jacobian_matrix(&ur5(), &q);
        let sv = reference_singular_values(&j);
        prop_assert!(sv[5] < 1e-9 * sv[0], "configuration is not singular: {sv:?}");
        let singular = matches!(inverse_velocity(&j, &xdot, DEFAULT_TOLERANCE), Err(SolveError::Singular { .. }));
        prop_assert!(singular, "plain inverse must refuse");
        // Not asserted: that `pinv_right` refuses here. It decides by the LU pivots of
        // J Jᵀ, and at an exact singularity the last one can stay above a small tolerance
        // (2.5e-12 of the largest entry at q = [-2.5419, 0.9698, 1.5163, 1.4979, 0, 0],
        // found by a 5000-case search; its docs say so).
        let damping = Damping::default();
        let qd = dls_velocity(&j, &xdot, &damping).unwrap();
        prop_assert!(qd.iter().all(|x| x.is_finite()));
        let lambda = damping.lambda_squared(Svd::new(&j).unwrap().sigma_min()).sqrt();
        let gain = (1.0 / damping.epsilon).max(1.0 / (2.0 * lambda));
        prop_assert!(qd.norm() <= gain * xdot.norm() * (1.0 + 1e-9), "{} > {}", qd.norm(), gain * xdot.norm());
        // The SVD pseudo-inverse handles the rank deficiency too.
        let p = pinv_svd(&j, 1e-9).unwrap();
        penrose(&j, &p, 1e-8);
    }

    #[test]
    fn near_singular_never_gives_nan(q in q6(), xdot in v6(), eps_exp in -16.0..-2.0f64) {
        let mut q = q;
        q[2] = 10f64.powf(eps_exp);
        let j = jacobian_matrix(&ur5(), &q);
        match inverse_velocity(&j, &xdot, DEFAULT_TOLERANCE) {
            Ok(qd) => prop_assert!(qd.iter().all(|x| x.is_finite())),
            Err(e) => {
                let expected = matches!(e, SolveError::Singular { .. } | SolveError::Overflow);
                prop_assert!(expected, "unexpected error {:?}", e);
            }
        }
        prop_assert!(dls_velocity(&j, &xdot, &Damping::default()).unwrap().iter().all(|x| x.is_finite()));
    }

    #[test]
    fn dls_equals_pseudo_inverse_away_from_singularities(q in q6(), xdot in v6()) {
        let j = jacobian_matrix(&ur5(), &q);
        let damping = Damping::default();
        prop_assume!(Svd::new(&j).unwrap().sigma_min() > damping.epsilon);
        let a = dls_velocity(&j, &xdot, &damping).unwrap();
        let b = inverse_velocity(&j, &xdot, DEFAULT_TOLERANCE).unwrap();
        prop_assert!((a - b).norm() < 1e-9 * (1.0 + b.norm()));
    }

    #[test]
    fn jacobian_transpose_is_a_descent_direction(q in q7(), xdot in v6(), alpha in 1e-3..1.0f64) {
        let j = jacobian_matrix(&redundant7(), &q);
        let qd = transpose_velocity(&j, &xdot, alpha).unwrap();
        prop_assert!((j * qd).dot(&xdot) >= 0.0);
        prop_assert!(((j * qd).dot(&xdot) - alpha * (j.transpose() * xdot).norm_squared()).abs() < 1e-12);
    }

    #[test]
    fn static_forces_satisfy_virtual_work(q in q7(), wrench in v6(), qd in [-1.0..1.0f64, -1.0..1.0, -1.0..1.0, -1.0..1.0, -1.0..1.0, -1.0..1.0, -1.0..1.0]) {
        // τ · q̇ = F · ẋ with ẋ = J q̇, for the 6×7 arm and the 6-joint UR5.
        let r = redundant7();
        let qd = SVector::<f64, 7>::from(qd);
        let tau = joint_torques_at(&r, &q, &wrench);
        let xdot = jacobian_matrix(&r, &q) * qd;
        prop_assert!((tau.dot(&qd) - wrench.dot(&xdot)).abs() < 1e-12 * (1.0 + tau.norm() * qd.norm()));
        let q6 = [q[0], q[1], q[2], q[3], q[4], q[5]];
        let qd6 = qd.fixed_rows::<6>(0).into_owned();
        let tau6 = joint_torques_at(&ur5(), &q6, &wrench);
        prop_assert!((tau6.dot(&qd6) - wrench.dot(&(jacobian_matrix(&ur5(), &q6) * qd6))).abs() < 1e-12);
        // Task Jacobian (planar RRR, [Fx, Fy, nz]).
        let q3 = [q[0], q[1], q[2]];
        let jt = task_jacobian_matrix(&planar_rrr(), &q3);
        let f3 = wrench.fixed_rows::<3>(0).into_owned();
        let qd3 = qd.fixed_rows::<3>(0).into_owned();
        prop_assert!((joint_torques(&jt, &f3).dot(&qd3) - f3.dot(&(jt * qd3))).abs() < 1e-10);
    }

    #[test]
    fn analytical_jacobian_matches_euler_angle_rates(q in q6(), conv in prop_oneof![Just(EulerConvention::Zyx), Just(EulerConvention::Zyz)]) {
        let r = ur5();
        let phi = euler_angles(&rotation_of(&r.fk(&q)), conv);
        let det = match conv { EulerConvention::Zyx => phi[1].cos(), EulerConvention::Zyz => phi[1].sin() };
        prop_assume!(det.abs() > 0.05);
        // The Euler angles reproduce the rotation.
        prop_assert!((euler_to_matrix(&phi, conv) - rotation_of(&r.fk(&q))).norm() < 1e-12);
        let ja = analytical_jacobian_at(&r, &q, conv, 1e-6).unwrap();
        // Column c of J_A's lower block = ∂φ/∂q_c (central differences, unwrapped).
        let h = 1e-6;
        for c in 0..6 {
            let (mut qp, mut qm) = (q, q);
            qp[c] += h;
            qm[c] -= h;
            let fp = euler_angles(&rotation_of(&r.fk(&qp)), conv);
            let fm = euler_angles(&rotation_of(&r.fk(&qm)), conv);
            for k in 0..3 {
                let mut d = fp[k] - fm[k];
                if d > PI { d -= 2.0 * PI; }
                if d < -PI { d += 2.0 * PI; }
                prop_assert!((d / (2.0 * h) - ja[(3 + k, c)]).abs() < 1e-5 * (1.0 + ja[(3 + k, c)].abs()),
                    "col {c} row {k}: fd {} vs {}", d / (2.0 * h), ja[(3 + k, c)]);
            }
            for k in 0..3 {
                prop_assert_eq!(ja[(k, c)], r.jacobian(&q)[k][c]);
            }
        }
        // T(φ) T(φ)⁻¹ = I through the public pieces.
        let t = euler_rate_matrix(&phi, conv);
        let geo = SMatrix::<f64, 6, 3>::from_fn(|r, c| if r >= 3 { t[(r - 3, c)] } else { 0.0 });
        let back = analytical_jacobian(&geo, &phi, conv, 1e-9).unwrap();
        prop_assert!((back.fixed_rows::<3>(3) - Matrix3::identity()).norm() < 1e-9 / det.abs());
    }
}

/// Cases proptest once found (formerly `runtime_velocity.proptest-regressions`: a
/// 7-joint `q` from one of the properties that take only `q`), through all of them.
#[test]
fn former_regressions() {
    let q = [
        0.0,
        -1.1825638799203635,
        0.21699179193771614,
        -1.881623693007099,
        -0.023052181827045493,
        -1.5051876729384264,
        0.46084552733660644,
    ];
    for (name, result) in [
        ("singular values", check_singular_values(q)),
        ("pseudo-inverses", check_pseudo_inverses(q)),
        ("manipulability", check_manipulability(q)),
    ] {
        assert!(
            !matches!(result, Err(TestCaseError::Fail(_))),
            "{name}: {result:?}"
        );
    }
}

/// Near a singularity, as the module docs of `kinegen::manipulability` say: at exact UR5
/// singularities (elbow q3 = 0, wrist q5 = 0, shoulder factor = 0) the true w is 0; the
/// product of singular values comes out within `6·16ε·σ₁⁶` of it, and `√|det(J Jᵀ)|`
/// (the Robotics Toolbox's formula) only within the `√ε`-sized bound of
/// [`sqrt_det_tolerance`], which it does use: it is much further from 0.
#[test]
fn manipulability_at_exact_singularities_is_accurate_to_epsilon() {
    let (mut worst_svd, mut worst_det) = (0.0f64, 0.0f64);
    for (k, q) in configurations::<6>(17, 300).into_iter().enumerate() {
        let mut q = q;
        match k % 3 {
            0 => q[2] = 0.0,
            1 => q[4] = 0.0,
            _ => match ur5_shoulder_singular(q) {
                Some(s) => q = s,
                None => continue,
            },
        }
        let j = jacobian_matrix(&ur5(), &q);
        let scale = reference_singular_values(&j)[0].powi(6);
        let w = manipulability(&j).unwrap();
        let by_det = (j * j.transpose()).determinant().abs().sqrt();
        assert!(
            w <= 6.0 * 16.0 * f64::EPSILON * scale,
            "q = {q:?}: w = {w:e}"
        );
        assert!(by_det <= sqrt_det_tolerance(6, scale.powf(1.0 / 6.0), 0.0));
        worst_svd = worst_svd.max(w / scale);
        worst_det = worst_det.max(by_det / scale);
    }
    eprintln!("UR5 at exact singularities: w/σ₁⁶ ≤ {worst_svd:.1e} (σ product), {worst_det:.1e} (√|det J Jᵀ|)");
    assert!(worst_det > 1e3 * worst_svd.max(f64::MIN_POSITIVE));
}

fn euler_to_matrix(phi: &Vector3<f64>, conv: EulerConvention) -> Matrix3<f64> {
    use nalgebra::Rotation3;
    let rz = |a| Rotation3::from_axis_angle(&Vector3::z_axis(), a);
    let ry = |a| Rotation3::from_axis_angle(&Vector3::y_axis(), a);
    let rx = |a| Rotation3::from_axis_angle(&Vector3::x_axis(), a);
    match conv {
        EulerConvention::Zyx => (rz(phi[0]) * ry(phi[1]) * rx(phi[2])).into_inner(),
        EulerConvention::Zyz => (rz(phi[0]) * ry(phi[1]) * rz(phi[2])).into_inner(),
    }
}

#[test]
fn planar_rr_stretched_out_is_singular_and_dls_bounded() {
    let r = planar_rr();
    for q1 in [-2.0, 0.0, 0.4, 3.0] {
        for q2 in [0.0, PI] {
            let j = task_jacobian_matrix(&r, &[q1, q2]);
            let xdot = SVector::<f64, 2>::new(0.3, -0.7);
            assert!(
                matches!(
                    inverse_velocity(&j, &xdot, DEFAULT_TOLERANCE),
                    Err(SolveError::Singular { .. })
                ),
                "q2 = {q2}"
            );
            let qd = dls_velocity(&j, &xdot, &Damping::default()).unwrap();
            assert!(
                qd.iter().all(|x| x.is_finite())
                    && qd.norm() <= xdot.norm() / (2.0 * 0.05) * (1.0 + 1e-9)
            );
            assert!(manipulability(&j).unwrap() < 1e-15);
            assert!(condition_number(&j).unwrap() > 1e14);
        }
    }
    // Planar RRR task Jacobian [x, y, θ] at q2 = 0: det = a1 a2 sin q2 = 0.
    let j = task_jacobian_matrix(&planar_rrr(), &[0.3, 0.0, -0.4]);
    assert!(inverse_velocity(
        &j,
        &SVector::<f64, 3>::new(1.0, 0.0, 0.0),
        DEFAULT_TOLERANCE
    )
    .is_err());
    let j = task_jacobian_matrix(&planar_rrr(), &[0.3, 0.9, -0.4]);
    assert!((j.determinant() - 12.25 * 0.9f64.sin()).abs() < 1e-12);
}

#[test]
fn non_finite_input_is_an_error_not_nan() {
    let mut j = jacobian_matrix(&ur5(), &[0.1, -1.0, 1.2, 0.3, 0.7, 0.0]);
    let ok = SVector::<f64, 6>::repeat(0.1);
    let mut bad = ok;
    bad[2] = f64::NAN;
    assert_eq!(
        inverse_velocity(&j, &bad, DEFAULT_TOLERANCE),
        Err(SolveError::NonFinite)
    );
    assert_eq!(
        dls_velocity(&j, &bad, &Damping::default()),
        Err(SolveError::NonFinite)
    );
    assert_eq!(pinv_velocity(&j, &bad, 1e-12), Err(SolveError::NonFinite));
    assert_eq!(
        transpose_velocity(&j, &bad, 0.1),
        Err(SolveError::NonFinite)
    );
    j[(1, 1)] = f64::INFINITY;
    assert_eq!(
        inverse_velocity(&j, &ok, DEFAULT_TOLERANCE),
        Err(SolveError::NonFinite)
    );
    assert_eq!(
        dls_velocity(&j, &ok, &Damping::default()),
        Err(SolveError::NonFinite)
    );
    assert_eq!(pinv_svd(&j, 1e-12).unwrap_err(), SolveError::NonFinite);
    assert_eq!(manipulability(&j), Err(SolveError::NonFinite));
    // Zero matrix: singular, not a division by zero.
    let z = SMatrix::<f64, 6, 6>::zeros();
    assert!(matches!(
        inverse_velocity(&z, &ok, DEFAULT_TOLERANCE),
        Err(SolveError::Singular { .. })
    ));
    assert_eq!(
        dls_velocity(&z, &ok, &Damping::default()).unwrap(),
        SVector::<f64, 6>::zeros()
    );
    assert_eq!(condition_number(&z).unwrap(), f64::INFINITY);
    // The error messages read as sentences.
    let msg = inverse_velocity(&z, &ok, DEFAULT_TOLERANCE)
        .unwrap_err()
        .to_string();
    assert!(msg.starts_with("singular Jacobian"), "{msg}");
}

#[test]
fn euler_representation_singularity_is_an_error() {
    let j = jacobian_matrix(&ur5(), &[0.1, -1.0, 1.2, 0.3, 0.7, 0.0]);
    let e = analytical_jacobian(
        &j,
        &Vector3::new(0.2, FRAC_PI_2, 0.1),
        EulerConvention::Zyx,
        1e-9,
    )
    .unwrap_err();
    assert_eq!(e.convention, EulerConvention::Zyx);
    assert!(e.det < 1e-9);
    assert!(
        analytical_jacobian(&j, &Vector3::new(0.2, 0.0, 0.1), EulerConvention::Zyz, 1e-9).is_err()
    );
    assert!(
        analytical_jacobian(&j, &Vector3::new(0.2, PI, 0.1), EulerConvention::Zyz, 1e-9).is_err()
    );
    assert!(
        analytical_jacobian(&j, &Vector3::new(0.2, 0.0, 0.1), EulerConvention::Zyx, 1e-9).is_ok()
    );
    assert!(e.to_string().contains("ZYX"));
    // det T(φ) = −cos φ₂ (ZYX) and −sin φ₂ (ZYZ).
    let phi = Vector3::new(0.4, 0.3, -1.2);
    assert!(
        (euler_rate_matrix(&phi, EulerConvention::Zyx).determinant() + 0.3f64.cos()).abs() < 1e-15
    );
    assert!(
        (euler_rate_matrix(&phi, EulerConvention::Zyz).determinant() + 0.3f64.sin()).abs() < 1e-15
    );
}

// ---------------------------------------------------------------------------------------
// Exact singular configurations of the *generated* robots (kinegen-robots): the closed
// forms must make the inverse refuse, the damped/SVD inverses stay bounded, and IK stay
// finite, whatever the seed.

use kinegen::adapters::fk_isometry;
use kinegen::ik::{solve, IkError, IkMethod, IkOptions, IkTarget, XorShift64};
use kinegen::TaskKinematics;
use kinegen_robots::{PlanarRr, PlanarRrr, Ur5};

/// The three UR5 singular families of `det J = a2 a3 s3 s5 (a2 c2 + a3 c23 + d5 s234)`,
/// built from random configurations: elbow `q3 = 0` (and `π`), wrist `q5 = 0`, shoulder.
fn ur5_singular_configurations(count: usize) -> Vec<(&'static str, [f64; 6])> {
    let mut rng = XorShift64::new(31);
    let mut out = Vec::new();
    while out.len() < 3 * count {
        let q = rng.configuration(&[[-PI, PI]; 6]);
        let k = out.len() % 3;
        match k {
            0 => {
                let mut e = q;
                e[2] = if out.len() % 2 == 0 { 0.0 } else { PI };
                out.push(("elbow q3 = 0/π", e));
            }
            1 => {
                let mut w = q;
                w[4] = 0.0;
                out.push(("wrist q5 = 0", w));
            }
            _ => {
                if let Some(s) = ur5_shoulder_singular(q) {
                    out.push(("shoulder", s));
                }
            }
        }
    }
    out
}

/// Every IK method from every seed: a solution or a clean error, never NaN/∞.
fn ik_stays_finite<R: Kinematics<N>, const N: usize>(
    robot: &R,
    target: &IkTarget,
    seeds: &[[f64; N]],
) -> usize {
    let mut solved = 0;
    for method in [
        IkMethod::NewtonRaphson,
        IkMethod::DampedLeastSquares(Damping::default()),
        IkMethod::LevenbergMarquardt { initial_mu: 1e-2 },
        IkMethod::JacobianTranspose,
    ] {
        let opts = IkOptions {
            method,
            ..IkOptions::default()
        };
        for seed in seeds {
            match solve(robot, target, seed, &opts) {
                Ok(sol) => {
                    assert!(
                        sol.q.iter().all(|x| x.is_finite()),
                        "{method:?}: {:?}",
                        sol.q
                    );
                    assert!(sol.residual.is_finite());
                    solved += 1;
                }
                Err(IkError::NotConverged { residual, q, .. }) => {
                    assert!(
                        residual.is_finite() && q.iter().all(|x| x.is_finite()),
                        "{method:?}"
                    )
                }
                Err(IkError::Singular { sigma_min, q }) => {
                    assert!(sigma_min.is_finite() && q.iter().all(|x| x.is_finite()))
                }
                Err(IkError::OutOfReach { distance, reach }) => {
                    assert!(distance.is_finite() && reach.is_finite())
                }
                Err(e @ IkError::InvalidInput(_)) => panic!("{method:?}: {e}"),
            }
        }
    }
    solved
}

#[test]
fn generated_ur5_at_exact_singularities() {
    let ur5 = Ur5::default();
    let damping = Damping::default();
    let xdot = SVector::<f64, 6>::new(0.3, -0.2, 0.1, 0.5, -0.4, 0.2);
    let mut seed_rng = XorShift64::new(8);
    let (mut ik_runs, mut ik_solved) = (0, 0);
    for (family, q) in ur5_singular_configurations(12) {
        // The generated closed-form determinant vanishes there (to rounding for the
        // shoulder, whose q2 is a bisection root).
        let det = ur5.jacobian_det(&q);
        assert!(det.abs() < 1e-12, "{family}: det {det:e} at {q:?}");
        let j = jacobian_matrix(&ur5, &q);
        let sv = reference_singular_values(&j);
        assert!(sv[5] < 1e-9 * sv[0], "{family}: not singular {sv:?}");
        // The plain inverse refuses ...
        assert!(
            matches!(
                inverse_velocity(&j, &xdot, DEFAULT_TOLERANCE),
                Err(SolveError::Singular { .. })
            ),
            "{family}"
        );
        assert!(matches!(
            joint_velocities(&ur5, &q, &xdot, DEFAULT_TOLERANCE),
            Err(SolveError::Singular { .. })
        ));
        assert!(jacobian_inverse(&j, DEFAULT_TOLERANCE).is_err());
        // ... DLS is finite and bounded by ‖ẋ‖/(2λ) (λ = λ_max at σ = 0) ...
        let qd = joint_velocities_dls(&ur5, &q, &xdot, &damping).unwrap();
        let lambda = damping.lambda_squared(sv[5]).sqrt();
        assert!(qd.iter().all(|x| x.is_finite()));
        assert!(
            qd.norm() <= xdot.norm() / (2.0 * lambda).min(damping.epsilon) * (1.0 + 1e-9),
            "{family}: ‖q̇‖ = {}",
            qd.norm()
        );
        // ... and the SVD pseudo-inverse satisfies the Penrose identities, with rank 5.
        let p = pinv_svd(&j, 1e-9).unwrap();
        penrose(&j, &p, 1e-8);
        assert_eq!(Svd::new(&j).unwrap().rank(1e-9), 5, "{family}");
        let v = pinv_velocity(&j, &xdot, 1e-9).unwrap();
        assert!(v.iter().all(|x| x.is_finite()) && v.norm() <= 1e9 * xdot.norm());
        // IK to the singular pose, seeded at the singularity itself and at random.
        let target = IkTarget::Pose(fk_isometry(&ur5, &q));
        let seeds = [q, seed_rng.configuration(&ur5.limits())];
        ik_solved += ik_stays_finite(&ur5, &target, &seeds);
        ik_runs += 4 * seeds.len();
    }
    println!(
        "UR5 at exact singularities: IK solved {ik_solved}/{ik_runs} (methods × seeds), no NaN"
    );
}

#[test]
fn generated_planar_arms_at_exact_singularities() {
    let (rr, rrr) = (PlanarRr::default(), PlanarRrr::default());
    let damping = Damping::default();
    for q1 in [-2.5, -0.3, 0.0, 1.1, 3.0] {
        for q2 in [0.0, PI, -PI] {
            // RR (L1 = L2 = 1): det = L1 L2 sin q2 = 0, stretched out or folded back.
            let q = [q1, q2];
            let j = task_jacobian_matrix(&rr, &q);
            assert!(rr.task_jacobian_det(&q).unwrap().abs() < 1e-15);
            let xdot = SVector::<f64, 2>::new(0.4, -0.9);
            assert!(matches!(
                inverse_velocity(&j, &xdot, DEFAULT_TOLERANCE),
                Err(SolveError::Singular { .. })
            ));
            let qd = dls_velocity(&j, &xdot, &damping).unwrap();
            assert!(qd.iter().all(|x| x.is_finite()));
            assert!(qd.norm() <= xdot.norm() / (2.0 * damping.lambda_max) * (1.0 + 1e-9));
            penrose(&j, &pinv_svd(&j, 1e-9).unwrap(), 1e-9);
            assert!(pinv_left(&j, 1e-12).is_err() && pinv_right(&j, 1e-12).is_err());
            // RRR (a = 3.5, 3.5, 2), task [x, y, θ]: det = a1 a2 sin q2 = 0 for any q3.
            let q3 = [q1, q2, 0.7 - q1];
            let j3 = task_jacobian_matrix(&rrr, &q3);
            assert!(rrr.task_jacobian_det(&q3).unwrap().abs() < 1e-12);
            let x3 = SVector::<f64, 3>::new(1.0, 0.5, -0.2);
            assert!(matches!(
                inverse_velocity(&j3, &x3, DEFAULT_TOLERANCE),
                Err(SolveError::Singular { .. })
            ));
            let qd3 = dls_velocity(&j3, &x3, &damping).unwrap();
            assert!(qd3.iter().all(|x| x.is_finite()));
            assert!(qd3.norm() <= x3.norm() / (2.0 * damping.lambda_max) * (1.0 + 1e-9));
            penrose(&j3, &pinv_svd(&j3, 1e-9).unwrap(), 1e-9);
            // IK: to the singular point itself, and straight out along the stretched arm
            // (a direction the arm cannot move in there), from the singular seed.
            let p = fk_isometry(&rr, &q).translation.vector;
            ik_stays_finite(&rr, &IkTarget::Position(p), &[q, [0.3, 0.4]]);
            let out = IkTarget::Position(p * 1.0001);
            ik_stays_finite(&rr, &out, &[q]);
            let pose = fk_isometry(&rrr, &q3);
            ik_stays_finite(&rrr, &IkTarget::Pose(pose), &[q3, [0.2, -0.5, 0.1]]);
        }
    }
    // Beyond full stretch: refused as out of reach, before any iteration.
    let far = IkTarget::Position(Vector3::new(2.5, 0.0, 0.0));
    assert!(matches!(
        solve(&rr, &far, &[0.0, 0.0], &IkOptions::default()),
        Err(IkError::OutOfReach { .. })
    ));
}
