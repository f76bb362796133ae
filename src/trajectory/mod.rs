//! Trajectory generation: timing laws for joints and for the path parameter of
//! Cartesian lines, sampled at a control rate without allocation.
//!
//! - [`Profile`]: a scalar motion law with position, velocity, acceleration and jerk,
//!   and [`Profile::sample`] to iterate `(t, q, q̇, q̈)` at a rate.
//! - [`Trapezoid`]: trapezoidal velocity profile from `(v_max, a_max)`, `(v_max, T)` or
//!   `(a_max, T)`; triangular when the distance is too short to reach `v_max`.
//! - [`Cubic`], [`Quintic`]: polynomials with boundary positions, velocities (and
//!   accelerations).
//! - [`Synchronized`]: `N` joints that start and finish together.
//! - [`StopAtVias`], [`ThroughVias`]: paths through via points, stopping at each or
//!   passing with continuous velocity.
//! - [`CartesianLine`]: straight line between two poses (slerp for the orientation),
//!   sampled as pose targets and tracked with an IK solver through [`track`].
//!
//! Joint space needs no singularity checks and every joint moves straight in joint
//! space; Cartesian space moves the tool straight, which is a curve in joint space and
//! can pass near singularities, where the joint velocities from IK grow large.

mod cartesian;
mod error;
mod multi_segment;
mod polynomial;
mod profile;
#[cfg(feature = "serde")]
mod stored;
mod sync;
mod trapezoid;

pub use cartesian::{
    slerp, track, CartesianLine, CartesianSamples, IkTrack, IkTrackError, OutOfReach, Track,
};
pub use error::TrajectoryError;
pub use multi_segment::{heuristic_via_velocities, StopAtVias, ThroughVias};
pub use polynomial::{Cubic, Quintic};
pub use profile::{Profile, SampleTimes, Samples};
pub use sync::{SyncSamples, Synchronized};
pub use trapezoid::{Stretch, Trapezoid};
