//! The trait every generated f64 type with a closed-form IK implements, so generic code
//! (a Cartesian tracker, a planner) can call the closed form of any robot.

use crate::ik::solutions::IkBranch;
use crate::Kinematics;

/// A robot whose inverse kinematics the `kinematics!` macro derived in closed form.
///
/// The generated inherent methods (`ik`, or `ik_with` for a 7-joint arm, `ik_near`,
/// `ik_seeded`) do the work; this trait exposes them without the solution count `K` in
/// the type, which differs per family.
///
/// ```
/// kinegen::kinematics! {
///     /// A planar RR arm.
///     pub struct Arm;
///     convention: standard,
///     params: { L1: 1.0, L2: 0.8 },
///     joints: [
///         revolute { a: L1, alpha: 0, d: 0 },
///         revolute { a: L2, alpha: 0, d: 0 },
///     ],
///     task: [x, y],
/// }
/// use kinegen::{InverseKinematics, Kinematics};
///
/// let arm = Arm::default();
/// let q = [0.4, -1.1];
/// let pose = arm.fk(&q);
/// assert_eq!(Arm::IK_FAMILY, "planar");
/// let mut count = 0;
/// arm.ik_each(&pose, &[0.0; 2], &mut |b| {
///     assert!(b.exact);
///     count += 1;
/// });
/// assert_eq!(count, 2); // elbow up, elbow down
/// let near = arm.ik_near(&pose, &[0.3, -1.0]).unwrap();
/// assert!((near[0] - q[0]).abs() < 1e-12 && (near[1] - q[1]).abs() < 1e-12);
/// ```
pub trait InverseKinematics<const N: usize>: Kinematics<N> {
    /// The closed-form family (`"three parallel, two intersecting"`, …).
    const IK_FAMILY: &'static str;

    /// The exact solution of `pose` nearest to `q_current` (`None`: out of reach).
    fn ik_near(&self, pose: &[[f64; 4]; 4], q_current: &[f64; N]) -> Option<[f64; N]>;

    /// Calls `f` with every solution of `pose`. `free` gives the joints a singular pose
    /// leaves undetermined, and for a 7-joint arm the locked joint's value.
    fn ik_each(&self, pose: &[[f64; 4]; 4], free: &[f64; N], f: &mut dyn FnMut(&IkBranch<N>));
}
