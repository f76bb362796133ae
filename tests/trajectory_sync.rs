//! Several joints synchronised to finish together.

use kinegen::trajectory::{Profile, Stretch, Synchronized, TrajectoryError, Trapezoid};
use proptest::prelude::*;
#[path = "../kinegen-core/tests/common/fixed_seed.rs"]
mod fixed_seed;
use fixed_seed::fixed_seed;

const N: usize = 6;

fn joints() -> impl Strategy<Value = ([f64; N], [f64; N], [f64; N], [f64; N], bool)> {
    (
        proptest::array::uniform6(-3.0..3.0_f64),
        proptest::array::uniform6(-3.0..3.0_f64),
        proptest::array::uniform6(0.1..3.0_f64),
        proptest::array::uniform6(0.1..20.0_f64),
        any::<bool>(),
    )
}

proptest! {
    #![proptest_config(fixed_seed(256))]

    #[test]
    fn all_joints_finish_together_within_limits((q0, q1, v_max, a_max, keep_v) in joints()) {
        let stretch = if keep_v { Stretch::KeepVelocity } else { Stretch::KeepAcceleration };
        let s = Synchronized::new(q0, q1, v_max, a_max, stretch).unwrap();
        let slowest = (0..N)
            .map(|i| Trapezoid::new(q0[i], q1[i], v_max[i], a_max[i]).unwrap().duration())
            .fold(0.0, f64::max);
        prop_assert_eq!(s.duration(), slowest);
        for i in 0..N {
            let j = s.joint(i);
            prop_assert_eq!(j.duration(), s.duration());
            prop_assert_eq!(j.position(0.0), q0[i]);
            prop_assert_eq!(j.position(s.duration()), q1[i]);
            prop_assert_eq!(j.velocity(0.0), 0.0);
            prop_assert_eq!(j.velocity(s.duration()), 0.0);
            prop_assert!(j.peak_velocity() <= v_max[i] * (1.0 + 1e-12), "joint {i}: v {} > {}", j.peak_velocity(), v_max[i]);
            prop_assert!(j.peak_acceleration() <= a_max[i] * (1.0 + 1e-12), "joint {i}: a {} > {}", j.peak_acceleration(), a_max[i]);
        }
        // The sampled vector agrees with the joints, and every joint is still moving
        // until the end: none arrives early.
        let t_mid = 0.5 * s.duration();
        let q = s.position(t_mid);
        for i in 0..N {
            prop_assert_eq!(q[i], s.joint(i).position(t_mid));
            if q0[i] != q1[i] {
                prop_assert!(s.joint(i).velocity(s.duration() * 0.999) != 0.0);
            }
        }
        let last = s.sample(500.0).unwrap().last().unwrap();
        prop_assert_eq!(last.0, s.duration());
        prop_assert_eq!(last.1, q1);
    }

    #[test]
    fn too_short_a_common_duration_is_refused((q0, q1, v_max, a_max, _k) in joints(), f in 0.1..0.99_f64) {
        let s = Synchronized::new(q0, q1, v_max, a_max, Stretch::KeepAcceleration).unwrap();
        prop_assume!(s.duration() > 0.0);
        let r = Synchronized::with_duration(q0, q1, v_max, a_max, f * s.duration(), Stretch::KeepAcceleration);
        prop_assert!(matches!(r, Err(TrajectoryError::VelocityTooLow { .. } | TrajectoryError::AccelerationTooLow { .. })), "{:?}", r);
    }
}

#[test]
fn keep_velocity_cruises_at_v_max() {
    // Joint 0 sets T = 2/1 + 1/2 = 2.5 s. Joint 1 (1 rad, same limits) stretched to 2.5 s
    // keeping v_max = 1: t_a = T − Δ/v = 1.5 s > T/2, so v_max is too fast for 1 rad in
    // 2.5 s and it falls back to a triangle with peak 2Δ/T = 0.8.
    let s = Synchronized::new(
        [0.0, 0.0],
        [2.0, 1.0],
        [1.0, 1.0],
        [2.0, 2.0],
        Stretch::KeepVelocity,
    )
    .unwrap();
    assert!((s.duration() - 2.5).abs() < 1e-15);
    assert!(s.joint(1).is_triangular());
    assert!((s.joint(1).peak_velocity() - 0.8).abs() < 1e-15);
    // Joint 1 with 1.8 rad: t_a = 2.5 − 1.8 = 0.7 s, cruising at exactly v_max.
    let s = Synchronized::new(
        [0.0, 0.0],
        [2.0, 1.8],
        [1.0, 1.0],
        [2.0, 2.0],
        Stretch::KeepVelocity,
    )
    .unwrap();
    assert!((s.joint(1).accel_time() - 0.7).abs() < 1e-12);
    assert!((s.joint(1).peak_velocity() - 1.0).abs() < 1e-12);
}

#[test]
fn nothing_moves() {
    let s = Synchronized::new(
        [1.0; 3],
        [1.0; 3],
        [1.0; 3],
        [1.0; 3],
        Stretch::KeepAcceleration,
    )
    .unwrap();
    assert_eq!(s.duration(), 0.0);
    assert_eq!(s.position(5.0), [1.0; 3]);
    assert_eq!(s.sample(500.0).unwrap().count(), 1);
}

#[test]
fn bad_limits_are_errors() {
    let r = Synchronized::new(
        [0.0; 2],
        [1.0; 2],
        [1.0, -1.0],
        [1.0; 2],
        Stretch::KeepAcceleration,
    );
    assert!(matches!(
        r,
        Err(TrajectoryError::InvalidLimit { what: "v_max", .. })
    ));
}
