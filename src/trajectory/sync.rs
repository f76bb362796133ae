//! Several joints synchronised to start and finish together.
//!
//! Each joint's fastest trapezoid under its own limits gives a minimum time `Tᵢ`; the
//! slowest joint sets `T = max Tᵢ`, and every joint is re-planned to take exactly `T`
//! (slower than it could, so within its limits). All joints then start and stop together,
//! which keeps a joint-space motion close to a straight line in joint space.

use super::error::TrajectoryError;
use super::profile::{Profile, SampleTimes};
use super::trapezoid::{Stretch, Trapezoid};

/// `N` trapezoids that share one duration.
///
/// ```
/// use kinegen::trajectory::{Profile, Stretch, Synchronized};
/// let s = Synchronized::new(
///     [0.0, 0.0],
///     [2.0, 0.5],
///     [1.0, 1.0],
///     [2.0, 2.0],
///     Stretch::KeepAcceleration,
/// )?;
/// // Joint 0 needs 2/1 + 0.5 = 2.5 s; joint 1 is slowed down to the same.
/// assert!((s.duration() - 2.5).abs() < 1e-12);
/// assert_eq!(s.joint(1).duration(), s.duration());
/// # Ok::<(), kinegen::trajectory::TrajectoryError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(
        into = "super::stored::SynchronizedJoints<N>",
        try_from = "super::stored::SynchronizedJoints<N>"
    )
)]
pub struct Synchronized<const N: usize> {
    joints: [Trapezoid; N],
    duration: f64,
}

impl<const N: usize> Synchronized<N> {
    /// Plans joint `i` from `q0[i]` to `q1[i]` within `v_max[i]`, `a_max[i]`, all
    /// finishing at the slowest joint's minimum time. `stretch` chooses how the faster
    /// joints are slowed down.
    pub fn new(
        q0: [f64; N],
        q1: [f64; N],
        v_max: [f64; N],
        a_max: [f64; N],
        stretch: Stretch,
    ) -> Result<Self, TrajectoryError> {
        let mut duration = 0.0_f64;
        for i in 0..N {
            duration = duration.max(Trapezoid::new(q0[i], q1[i], v_max[i], a_max[i])?.duration());
        }
        Self::with_duration(q0, q1, v_max, a_max, duration, stretch)
    }

    /// Like [`Synchronized::new`] but all joints take `duration` (which must be at least
    /// the slowest joint's minimum time, else `Err`). A zero duration is allowed only
    /// when no joint moves.
    pub fn with_duration(
        q0: [f64; N],
        q1: [f64; N],
        v_max: [f64; N],
        a_max: [f64; N],
        duration: f64,
        stretch: Stretch,
    ) -> Result<Self, TrajectoryError> {
        let mut joints = [Trapezoid::at_rest(0.0, 0.0); N];
        for i in 0..N {
            joints[i] = if duration == 0.0 {
                // Only reachable when every displacement is zero; `new` checks the inputs.
                Trapezoid::new(q0[i], q1[i], v_max[i], a_max[i])?
            } else {
                Trapezoid::stretched(q0[i], q1[i], v_max[i], a_max[i], duration, stretch)?
            };
        }
        if joints.iter().any(|j| j.duration() != duration) {
            // Zero duration requested but some joint has to move.
            return Err(TrajectoryError::InvalidDuration { value: duration });
        }
        Self::from_joints(joints)
    }

    /// Joints planned already, which must all take the same time (`Err` otherwise).
    pub(super) fn from_joints(joints: [Trapezoid; N]) -> Result<Self, TrajectoryError> {
        let duration = joints.first().map_or(0.0, Trapezoid::duration);
        if let Some(part) = joints.iter().position(|j| j.duration() != duration) {
            let what = "duration";
            return Err(TrajectoryError::PartsDoNotFit { part, what });
        }
        Ok(Self { joints, duration })
    }

    /// The common duration `T`.
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// Joint `i`'s profile. Panics if `i ≥ N`, like indexing an array.
    pub fn joint(&self, i: usize) -> &Trapezoid {
        &self.joints[i]
    }

    /// All joints' profiles.
    pub fn joints(&self) -> &[Trapezoid; N] {
        &self.joints
    }

    /// Joint positions at `t`.
    pub fn position(&self, t: f64) -> [f64; N] {
        self.joints.map(|j| j.position(t))
    }

    /// Joint velocities at `t`.
    pub fn velocity(&self, t: f64) -> [f64; N] {
        self.joints.map(|j| j.velocity(t))
    }

    /// Joint accelerations at `t`.
    pub fn acceleration(&self, t: f64) -> [f64; N] {
        self.joints.map(|j| j.acceleration(t))
    }

    /// Samples `(t, q, q̇, q̈)` at `rate_hz`, ending exactly at `T`; allocation-free.
    pub fn sample(&self, rate_hz: f64) -> Result<SyncSamples<'_, N>, TrajectoryError> {
        Ok(SyncSamples {
            sync: self,
            times: SampleTimes::new(self.duration, rate_hz)?,
        })
    }
}

/// Samples of a [`Synchronized`] motion; see [`Synchronized::sample`].
#[derive(Debug, Clone)]
pub struct SyncSamples<'a, const N: usize> {
    sync: &'a Synchronized<N>,
    times: SampleTimes,
}

impl<const N: usize> Iterator for SyncSamples<'_, N> {
    type Item = (f64, [f64; N], [f64; N], [f64; N]);

    fn next(&mut self) -> Option<Self::Item> {
        let t = self.times.next()?;
        let s = self.sync;
        Some((t, s.position(t), s.velocity(t), s.acceleration(t)))
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        self.times.size_hint()
    }
}
