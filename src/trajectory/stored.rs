//! A trajectory as it is stored (the `serde` feature): the inputs that define it, read
//! back through the same constructors. A profile read from a file therefore satisfies
//! every invariant a planned one does (finite values, a positive duration, phases that
//! join, joints that finish together), and a planned profile reads back bit for bit:
//! the constructors are deterministic and the stored inputs are the ones they were given.
//!
//! ```
//! # #[cfg(feature = "serde")] {
//! use kinegen::trajectory::{Profile, Trapezoid};
//! let p = Trapezoid::new(0.0, 1.0, 0.5, 2.0)?;
//! let text = serde_json::to_string(&p).unwrap();
//! assert_eq!(text, r#"{"start":0.0,"goal":1.0,"accel_time":0.25,"duration":2.25}"#);
//! let back: Trapezoid = serde_json::from_str(&text).unwrap();
//! assert_eq!(back, p);
//! // A profile whose phases cannot join is refused, as the constructors refuse it.
//! let bad = r#"{"start":0.0,"goal":1.0,"accel_time":2.0,"duration":1.0}"#;
//! assert!(serde_json::from_str::<Trapezoid>(bad).is_err());
//! # }
//! # Ok::<(), kinegen::trajectory::TrajectoryError>(())
//! ```

use super::{
    error, CartesianLine, Cubic, Profile, Quintic, StopAtVias, Synchronized, ThroughVias,
    TrajectoryError, Trapezoid,
};
use nalgebra::Isometry3;
use serde::{Deserialize, Serialize};
use serde_big_array::BigArray;

/// A trapezoid: its ends and its timing; the cruise speed and the acceleration follow
/// (`|Δ| = v·(T − t_a)`, `v = a·t_a`).
#[derive(Serialize, Deserialize)]
pub(super) struct TrapezoidTiming {
    start: f64,
    goal: f64,
    accel_time: f64,
    duration: f64,
}

impl From<Trapezoid> for TrapezoidTiming {
    fn from(p: Trapezoid) -> Self {
        TrapezoidTiming {
            start: p.start(),
            goal: p.goal(),
            accel_time: p.accel_time(),
            duration: p.duration(),
        }
    }
}

impl TryFrom<TrapezoidTiming> for Trapezoid {
    type Error = TrajectoryError;
    fn try_from(s: TrapezoidTiming) -> Result<Self, TrajectoryError> {
        let q0 = error::finite(s.start, "start")?;
        let q1 = error::finite(s.goal, "goal")?;
        let t_a = error::finite(s.accel_time, "acceleration time")?;
        let duration = error::finite(s.duration, "duration")?;
        if duration < 0.0 {
            return Err(TrajectoryError::InvalidDuration { value: duration });
        }
        if t_a == 0.0 && q0 == q1 {
            return Ok(Trapezoid::at_rest(q0, duration));
        }
        // The two blends must fit in the duration: t_a ≤ T/2. A triangular profile has
        // t_a = T/2 up to the rounding of T = 2·t_a, hence the few ulps.
        if !(t_a > 0.0 && t_a <= 0.5 * duration * (1.0 + 4.0 * f64::EPSILON)) {
            let what = "acceleration time";
            return Err(TrajectoryError::PartsDoNotFit { part: 0, what });
        }
        Trapezoid::from_timing(q0, q1, t_a, duration)
    }
}

/// A cubic: its boundary positions and velocities and its duration.
#[derive(Serialize, Deserialize)]
pub(super) struct CubicEnds {
    start: [f64; 2],
    end: [f64; 2],
    duration: f64,
}

impl From<Cubic> for CubicEnds {
    fn from(p: Cubic) -> Self {
        let c = p.coefficients();
        let t = p.duration();
        CubicEnds {
            start: [c[0], c[1]],
            end: [p.position(t), p.velocity(t)],
            duration: t,
        }
    }
}

impl TryFrom<CubicEnds> for Cubic {
    type Error = TrajectoryError;
    fn try_from(s: CubicEnds) -> Result<Self, TrajectoryError> {
        Cubic::new(s.start[0], s.end[0], s.start[1], s.end[1], s.duration)
    }
}

/// A quintic: its boundary positions, velocities and accelerations and its duration.
#[derive(Serialize, Deserialize)]
pub(super) struct QuinticEnds {
    start: [f64; 3],
    end: [f64; 3],
    duration: f64,
}

impl From<Quintic> for QuinticEnds {
    fn from(p: Quintic) -> Self {
        let c = p.coefficients();
        let t = p.duration();
        QuinticEnds {
            // `a₂ = acc0/2`: doubling is exact.
            start: [c[0], c[1], 2.0 * c[2]],
            end: [p.position(t), p.velocity(t), p.acceleration(t)],
            duration: t,
        }
    }
}

impl TryFrom<QuinticEnds> for Quintic {
    type Error = TrajectoryError;
    fn try_from(s: QuinticEnds) -> Result<Self, TrajectoryError> {
        Quintic::new(s.start, s.end, s.duration)
    }
}

/// Synchronised joints: every joint's trapezoid, which must share one duration.
#[derive(Serialize, Deserialize)]
#[serde(bound = "")]
pub(super) struct SynchronizedJoints<const N: usize> {
    #[serde(with = "BigArray")]
    joints: [Trapezoid; N],
}

impl<const N: usize> From<Synchronized<N>> for SynchronizedJoints<N> {
    fn from(s: Synchronized<N>) -> Self {
        SynchronizedJoints {
            joints: *s.joints(),
        }
    }
}

impl<const N: usize> TryFrom<SynchronizedJoints<N>> for Synchronized<N> {
    type Error = TrajectoryError;
    fn try_from(s: SynchronizedJoints<N>) -> Result<Self, TrajectoryError> {
        Synchronized::from_joints(s.joints)
    }
}

/// A Cartesian line: its two poses and the profile of its path parameter.
#[derive(Serialize, Deserialize)]
pub(super) struct LineEnds<P> {
    start: Isometry3<f64>,
    end: Isometry3<f64>,
    profile: P,
}

impl<P: Profile + Clone> From<CartesianLine<P>> for LineEnds<P> {
    fn from(line: CartesianLine<P>) -> Self {
        LineEnds {
            start: *line.start(),
            end: *line.end(),
            profile: line.profile().clone(),
        }
    }
}

impl<P: Profile> TryFrom<LineEnds<P>> for CartesianLine<P> {
    type Error = TrajectoryError;
    fn try_from(s: LineEnds<P>) -> Result<Self, TrajectoryError> {
        CartesianLine::new(s.start, s.end, s.profile)
    }
}

/// A path that stops at its via points: its trapezoids (the last slot unused) and the
/// arrival times, which must fit them.
#[derive(Serialize, Deserialize)]
#[serde(bound = "")]
pub(super) struct StopAtViasParts<const K: usize> {
    #[serde(with = "BigArray")]
    segments: [Trapezoid; K],
    #[serde(with = "BigArray")]
    times: [f64; K],
}

impl<const K: usize> From<StopAtVias<K>> for StopAtViasParts<K> {
    fn from(path: StopAtVias<K>) -> Self {
        // The last slot: standing at the last point (K ≥ 2 for every planned path).
        let goal = path
            .segment(K.saturating_sub(2))
            .map_or(0.0, Trapezoid::goal);
        let last = Trapezoid::at_rest(goal, 0.0);
        StopAtViasParts {
            segments: core::array::from_fn(|i| *path.segment(i).unwrap_or(&last)),
            times: *path.arrival_times(),
        }
    }
}

impl<const K: usize> TryFrom<StopAtViasParts<K>> for StopAtVias<K> {
    type Error = TrajectoryError;
    fn try_from(s: StopAtViasParts<K>) -> Result<Self, TrajectoryError> {
        StopAtVias::from_parts(s.segments, s.times)
    }
}

/// A path through its via points: the points, their times and velocities.
#[derive(Serialize, Deserialize)]
#[serde(bound = "")]
pub(super) struct ThroughViasPoints<const K: usize> {
    #[serde(with = "BigArray")]
    points: [f64; K],
    #[serde(with = "BigArray")]
    times: [f64; K],
    #[serde(with = "BigArray")]
    velocities: [f64; K],
}

impl<const K: usize> From<ThroughVias<K>> for ThroughViasPoints<K> {
    fn from(path: ThroughVias<K>) -> Self {
        // Point i is where segment i starts; the last, where the last segment ends
        // (cubics return their boundary values exactly).
        let points = core::array::from_fn(|i| match path.segment(i) {
            Some(c) => c.position(0.0),
            // (`checked_sub`: a path with no segment has no point 0 to end either.)
            None => i
                .checked_sub(1)
                .and_then(|p| path.segment(p))
                .map_or(0.0, |c| c.position(c.duration())),
        });
        ThroughViasPoints {
            points,
            times: *path.arrival_times(),
            velocities: *path.via_velocities(),
        }
    }
}

impl<const K: usize> TryFrom<ThroughViasPoints<K>> for ThroughVias<K> {
    type Error = TrajectoryError;
    fn try_from(s: ThroughViasPoints<K>) -> Result<Self, TrajectoryError> {
        ThroughVias::with_velocities(s.points, s.times, s.velocities)
    }
}
