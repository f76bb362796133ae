//! Straight Cartesian lines between two poses, and tracking them with an IK solver.
//!
//! The position moves along the segment `p(s) = p₀ + s·(p₁ − p₀)` and the orientation
//! along the shortest great arc between the two unit quaternions (slerp), both driven
//! by one scalar profile `s(t)` from 0 to 1. Position and orientation therefore start,
//! stop and pass every fraction of the way together.
//!
//! [`CartesianLine::track_ik`] follows the samples with the runtime's numerical IK, each
//! solve seeded with the previous solution, and refuses joint jumps (branch changes);
//! [`CartesianLine::track_closed_form`] takes the nearest exact closed-form solution of
//! each sample instead (robots with a closed-form IK family).
//!
//! Euler angles are not interpolated: their components are coupled, so interpolating
//! them one by one neither follows a shortest rotation nor keeps a constant axis.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use super::error::{self, TrajectoryError};
use super::profile::{Profile, SampleTimes};
use super::trapezoid::Trapezoid;
use crate::ik::{self, IkError, IkOptions, IkSolution, IkTarget, InverseKinematics};
use crate::math;
use crate::Kinematics;

/// How far `s(0)` and `s(T)` may be from 0 and 1 for a profile to count as normalised.
const NORMALIZED_TOL: f64 = 1e-9;

/// A straight line from one pose to another, timed by a scalar profile `s(t)`.
///
/// ```
/// use kinegen::trajectory::{CartesianLine, Quintic};
/// use nalgebra::{Isometry3, Vector3};
/// let a = Isometry3::new(Vector3::new(0.3, -0.2, 0.4), Vector3::new(0.0, 0.0, 0.0));
/// let b = Isometry3::new(Vector3::new(0.5, 0.1, 0.2), Vector3::new(0.0, 0.0, 1.0));
/// let s = Quintic::new([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], 2.0)?;
/// let line = CartesianLine::new(a, b, s)?;
/// let poses = line.sample(500.0)?; // one target every 2 ms
/// assert_eq!(poses.count(), 1001);
/// # Ok::<(), kinegen::trajectory::TrajectoryError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(
        into = "super::stored::LineEnds<P>",
        try_from = "super::stored::LineEnds<P>",
        bound(
            serialize = "P: Profile + Clone + serde::Serialize",
            deserialize = "P: Profile + serde::Deserialize<'de>"
        )
    )
)]
pub struct CartesianLine<P> {
    start: Isometry3<f64>,
    end: Isometry3<f64>,
    profile: P,
    /// `p₁ − p₀`.
    delta: Vector3<f64>,
    /// Rotation from start to end as axis·angle in the world frame (`θ ∈ [0, π]`):
    /// the angular velocity per unit of `ṡ`.
    omega_per_s: Vector3<f64>,
}

impl<P: Profile> CartesianLine<P> {
    /// The line from `start` to `end` timed by `profile`, which must go from `s = 0` to
    /// `s = 1` (e.g. a [`Trapezoid`] or [`Quintic`](super::Quintic) from 0.0 to 1.0).
    pub fn new(
        start: Isometry3<f64>,
        end: Isometry3<f64>,
        profile: P,
    ) -> Result<Self, TrajectoryError> {
        check_pose(&start)?;
        check_pose(&end)?;
        let (s0, s1) = (profile.position(0.0), profile.position(profile.duration()));
        let duration = profile.duration();
        if !(duration.is_finite() && duration >= 0.0) {
            return Err(TrajectoryError::InvalidDuration { value: duration });
        }
        if !(math::abs(s0) <= NORMALIZED_TOL && math::abs(s1 - 1.0) <= NORMALIZED_TOL) {
            return Err(TrajectoryError::NotNormalized { start: s0, end: s1 });
        }
        Ok(Self::assemble(start, end, profile))
    }

    fn assemble(start: Isometry3<f64>, end: Isometry3<f64>, profile: P) -> Self {
        let delta = end.translation.vector - start.translation.vector;
        // Relative rotation in the start frame, mapped to the world frame: ω = R₀·(k θ).
        let rel = start.rotation.inverse() * end.rotation;
        let omega_per_s = start.rotation * rel.scaled_axis();
        Self {
            start,
            end,
            profile,
            delta,
            omega_per_s,
        }
    }

    /// The timing profile `s(t)`.
    pub fn profile(&self) -> &P {
        &self.profile
    }

    /// Start pose.
    pub fn start(&self) -> &Isometry3<f64> {
        &self.start
    }

    /// End pose.
    pub fn end(&self) -> &Isometry3<f64> {
        &self.end
    }

    /// Duration `T` (the profile's).
    pub fn duration(&self) -> f64 {
        self.profile.duration()
    }

    /// Length of the straight line, `|p₁ − p₀|`.
    pub fn length(&self) -> f64 {
        self.delta.norm()
    }

    /// Rotation angle from start to end orientation along the shortest arc, in `[0, π]`.
    pub fn angle(&self) -> f64 {
        self.omega_per_s.norm()
    }

    /// Pose at path parameter `s ∈ [0, 1]` (clamped): position on the segment,
    /// orientation by quaternion slerp. Exactly `start` at 0 and `end` at 1.
    pub fn pose_at(&self, s: f64) -> Isometry3<f64> {
        let s = super::profile::clamp_time(s, 1.0);
        if s == 0.0 {
            return self.start;
        }
        if s == 1.0 {
            return self.end;
        }
        let p = self.start.translation.vector + self.delta * s;
        Isometry3::from_parts(
            Translation3::from(p),
            slerp(&self.start.rotation, &self.end.rotation, s),
        )
    }

    /// Target pose at time `t`.
    pub fn pose(&self, t: f64) -> Isometry3<f64> {
        self.pose_at(self.profile.position(t))
    }

    /// Target twist `[vx, vy, vz, ωx, ωy, ωz]` at `t` in the world frame (the row order
    /// of [`Kinematics::jacobian`](crate::Kinematics::jacobian)), ready for `q̇ = J⁻¹ ẋ`.
    pub fn twist(&self, t: f64) -> [f64; 6] {
        scaled(&self.delta, &self.omega_per_s, self.profile.velocity(t))
    }

    /// Target acceleration `[ax, ay, az, αx, αy, αz]` at `t` in the world frame.
    pub fn twist_rate(&self, t: f64) -> [f64; 6] {
        scaled(&self.delta, &self.omega_per_s, self.profile.acceleration(t))
    }

    /// Target poses `(t, pose)` at `rate_hz` (e.g. 500 Hz for a UR e-series), ending
    /// exactly at `T` with the end pose. Allocation-free.
    pub fn sample(&self, rate_hz: f64) -> Result<CartesianSamples<'_, P>, TrajectoryError> {
        Ok(CartesianSamples {
            line: self,
            times: SampleTimes::new(self.duration(), rate_hz)?,
        })
    }

    /// Follows the sampled line with an inverse-kinematics solver, seeding each solve
    /// with the previous solution so the nearest branch (elbow up/down, wrist flip) is
    /// kept. See [`track`].
    pub fn track<const N: usize, E, F>(
        &self,
        rate_hz: f64,
        q_start: [f64; N],
        solve: F,
    ) -> Result<Track<CartesianSamples<'_, P>, F, N>, TrajectoryError>
    where
        F: FnMut(&Isometry3<f64>, &[f64; N]) -> Result<[f64; N], E>,
    {
        Ok(track(self.sample(rate_hz)?, q_start, solve))
    }

    /// Follows the sampled line with the runtime's numerical IK ([`ik::solve`]): each
    /// sample is solved from the previous sample's solution (`q_start` for the first),
    /// so with samples a control period apart the solver starts next to the solution on
    /// the robot's current branch and converges to it (its steps are at most
    /// [`IkOptions::max_step`] per joint).
    ///
    /// Because a seed that close can still land on another branch near a singularity,
    /// every solution is also checked against the previous one: a change of more than
    /// `max_joint_step` in any joint (e.g. `v_joint_max / rate_hz`) stops the track with
    /// [`IkTrackError::Jump`] rather than commanding the jump. Pass `f64::INFINITY` to
    /// turn the check off.
    ///
    /// ```
    /// use kinegen::adapters::fk_isometry;
    /// use kinegen::ik::IkOptions;
    /// use kinegen::trajectory::CartesianLine;
    /// use kinegen_robots::Ur5;
    /// use nalgebra::{Isometry3, Translation3};
    /// let ur5 = Ur5::default();
    /// let q0 = [0.3, -1.2, 1.4, -0.3, 1.1, 0.2];
    /// let a = fk_isometry(&ur5, &q0);
    /// let b = Translation3::new(0.1, 0.0, -0.05) * a;
    /// let line = CartesianLine::with_limits(a, b, 0.25, 1.0, 1.0, 2.0)?;
    /// let mut last = q0;
    /// for step in line.track_ik(&ur5, 500.0, q0, &IkOptions::default(), 0.05)? {
    ///     let (_t, sol) = step.expect("the UR5 follows this line");
    ///     last = sol.q;
    /// }
    /// assert!((fk_isometry(&ur5, &last).translation.vector - b.translation.vector).norm() < 1e-9);
    /// # Ok::<(), kinegen::trajectory::TrajectoryError>(())
    /// ```
    pub fn track_ik<'a, R: Kinematics<N>, const N: usize>(
        &'a self,
        robot: &'a R,
        rate_hz: f64,
        q_start: [f64; N],
        options: &IkOptions,
        max_joint_step: f64,
    ) -> Result<IkTrack<'a, P, R, N>, TrajectoryError> {
        if max_joint_step.is_nan() || max_joint_step <= 0.0 {
            return Err(TrajectoryError::InvalidLimit {
                what: "max_joint_step",
                value: max_joint_step,
            });
        }
        for q in &q_start {
            error::finite(*q, "start configuration")?;
        }
        Ok(IkTrack {
            samples: self.sample(rate_hz)?,
            robot,
            options: *options,
            max_joint_step,
            seed: q_start,
            failed: false,
        })
    }

    /// Follows the sampled line with the robot's **closed-form** IK: each sample takes
    /// the exact solution nearest to the previous one (`ik_near`), `q_start` for the
    /// first. No iteration and no seed that can slip to another branch: the nearest
    /// branch is chosen among all of them, and at a singular pose the joints it leaves
    /// free keep their previous values, so the joint path stays continuous through a
    /// wrist singularity where a Jacobian-based tracker's steps blow up. A sample out of
    /// reach yields [`OutOfReach`] and ends the track.
    ///
    /// ```
    /// use kinegen::adapters::fk_isometry;
    /// use kinegen::trajectory::CartesianLine;
    /// use kinegen_robots::Ur5;
    /// use nalgebra::Translation3;
    /// let ur5 = Ur5::default();
    /// let q0 = [0.3, -1.2, 1.4, -0.3, 1.1, 0.2];
    /// let a = fk_isometry(&ur5, &q0);
    /// let b = Translation3::new(0.1, 0.0, -0.05) * a;
    /// let line = CartesianLine::with_limits(a, b, 0.25, 1.0, 1.0, 2.0)?;
    /// let mut last = q0;
    /// for step in line.track_closed_form(&ur5, 500.0, q0)? {
    ///     let (_t, q) = step.expect("the UR5 reaches every sample");
    ///     last = q;
    /// }
    /// assert!((fk_isometry(&ur5, &last).translation.vector - b.translation.vector).norm() < 1e-9);
    /// # Ok::<(), kinegen::trajectory::TrajectoryError>(())
    /// ```
    #[allow(clippy::type_complexity)]
    pub fn track_closed_form<'a, R: InverseKinematics<N>, const N: usize>(
        &'a self,
        robot: &'a R,
        rate_hz: f64,
        q_start: [f64; N],
    ) -> Result<
        Track<
            CartesianSamples<'a, P>,
            impl FnMut(&Isometry3<f64>, &[f64; N]) -> Result<[f64; N], OutOfReach> + 'a,
            N,
        >,
        TrajectoryError,
    > {
        for q in &q_start {
            error::finite(*q, "start configuration")?;
        }
        let solve = move |target: &Isometry3<f64>, seed: &[f64; N]| {
            robot
                .ik_near(&crate::adapters::pose_matrix(target), seed)
                .ok_or(OutOfReach)
        };
        self.track(rate_hz, q_start, solve)
    }
}

/// A sample of [`CartesianLine::track_closed_form`] the robot cannot reach.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OutOfReach;

impl core::fmt::Display for OutOfReach {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str("the pose is out of the robot's reach")
    }
}

/// Why [`CartesianLine::track_ik`] stopped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum IkTrackError<const N: usize> {
    /// The IK solver found no solution for the sample at time `t`.
    Ik {
        /// Time of the sample.
        t: f64,
        /// The solver's reason.
        error: IkError<N>,
    },
    /// The solution for the sample at `t` differs from the previous one by `step` in
    /// joint `joint` (0-based), more than the allowed `max_joint_step`: a branch change
    /// or a singularity on the line, where following it needs unbounded joint speed.
    Jump {
        /// Time of the sample.
        t: f64,
        /// Which joint (0-based).
        joint: usize,
        /// Its change from the previous sample.
        step: f64,
    },
}

impl<const N: usize> core::fmt::Display for IkTrackError<N> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Ik { t, error } => write!(f, "at t = {t} s: {error}"),
            Self::Jump { t, joint, step } => write!(
                f,
                "at t = {t} s joint {} would jump by {step} (branch change or singularity)",
                joint + 1
            ),
        }
    }
}

#[cfg(feature = "std")]
impl<const N: usize> std::error::Error for IkTrackError<N> {}

#[cfg(feature = "std")]
impl std::error::Error for OutOfReach {}

/// Iterator returned by [`CartesianLine::track_ik`]: `Ok((t, solution))` per sample, or
/// the first error, after which it stops.
#[derive(Debug, Clone)]
pub struct IkTrack<'a, P, R, const N: usize> {
    samples: CartesianSamples<'a, P>,
    robot: &'a R,
    options: IkOptions,
    max_joint_step: f64,
    seed: [f64; N],
    failed: bool,
}

impl<P: Profile, R: Kinematics<N>, const N: usize> Iterator for IkTrack<'_, P, R, N> {
    type Item = Result<(f64, IkSolution<N>), IkTrackError<N>>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.failed {
            return None;
        }
        let (t, target) = self.samples.next()?;
        let result = ik::solve(
            self.robot,
            &IkTarget::Pose(target),
            &self.seed,
            &self.options,
        )
        .map_err(|error| IkTrackError::Ik { t, error })
        .and_then(|sol| {
            for (joint, (a, b)) in sol.q.iter().zip(self.seed.iter()).enumerate() {
                let step = a - b;
                if step.is_nan() || math::abs(step) > self.max_joint_step {
                    return Err(IkTrackError::Jump { t, joint, step });
                }
            }
            Ok(sol)
        });
        match result {
            Ok(sol) => {
                self.seed = sol.q;
                Some(Ok((t, sol)))
            }
            Err(e) => {
                self.failed = true;
                Some(Err(e))
            }
        }
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        if self.failed {
            (0, Some(0))
        } else {
            (0, self.samples.size_hint().1)
        }
    }
}

impl CartesianLine<Trapezoid> {
    /// A line as fast as the limits allow: a trapezoid on `s` whose limits are the
    /// tighter of `v_max/L`, `ω_max/θ` (and `a_max/L`, `α_max/θ`), with `L` the line's
    /// length and `θ` its rotation angle, so the tool's linear speed stays within
    /// `v_max`, its angular speed within `ω_max`, and so on. Poses that coincide give a
    /// zero-duration line.
    pub fn with_limits(
        start: Isometry3<f64>,
        end: Isometry3<f64>,
        v_max: f64,
        a_max: f64,
        omega_max: f64,
        alpha_max: f64,
    ) -> Result<Self, TrajectoryError> {
        check_pose(&start)?;
        check_pose(&end)?;
        let v_max = error::limit(v_max, "v_max")?;
        let a_max = error::limit(a_max, "a_max")?;
        let omega_max = error::limit(omega_max, "omega_max")?;
        let alpha_max = error::limit(alpha_max, "alpha_max")?;
        let probe = Self::assemble(start, end, Trapezoid::at_rest(1.0, 0.0));
        let (length, angle) = (probe.length(), probe.angle());
        if length == 0.0 && angle == 0.0 {
            return Ok(probe);
        }
        // Limits on ṡ and s̈; a zero length (or angle) puts no limit from that side.
        let tighter = |lin: f64, ang: f64| {
            let a = if length > 0.0 {
                lin / length
            } else {
                f64::INFINITY
            };
            let b = if angle > 0.0 {
                ang / angle
            } else {
                f64::INFINITY
            };
            a.min(b)
        };
        let profile = Trapezoid::new(
            0.0,
            1.0,
            tighter(v_max, omega_max),
            tighter(a_max, alpha_max),
        )?;
        Ok(Self::assemble(start, end, profile))
    }
}

fn scaled(lin: &Vector3<f64>, ang: &Vector3<f64>, k: f64) -> [f64; 6] {
    [
        lin.x * k,
        lin.y * k,
        lin.z * k,
        ang.x * k,
        ang.y * k,
        ang.z * k,
    ]
}

fn check_pose(pose: &Isometry3<f64>) -> Result<(), TrajectoryError> {
    let finite = pose.translation.vector.iter().all(|x| x.is_finite())
        && pose.rotation.coords.iter().all(|x| x.is_finite());
    if finite {
        Ok(())
    } else {
        Err(TrajectoryError::NotFinite { what: "pose" })
    }
}

/// Spherical linear interpolation along the shortest arc ([`UnitQuaternion::slerp`]),
/// without its panic: nalgebra's `try_slerp` gives up only when the two rotations are
/// equal to within rounding, where normalised linear interpolation is exact enough.
pub fn slerp(q0: &UnitQuaternion<f64>, q1: &UnitQuaternion<f64>, s: f64) -> UnitQuaternion<f64> {
    q0.try_slerp(q1, s, f64::EPSILON).unwrap_or_else(|| {
        let q1 = if q0.coords.dot(&q1.coords) < 0.0 {
            -q1.into_inner()
        } else {
            q1.into_inner()
        };
        UnitQuaternion::new_normalize(q0.into_inner() * (1.0 - s) + q1 * s)
    })
}

/// Target poses of a [`CartesianLine`]; see [`CartesianLine::sample`].
#[derive(Debug, Clone)]
pub struct CartesianSamples<'a, P> {
    line: &'a CartesianLine<P>,
    times: SampleTimes,
}

impl<P: Profile> Iterator for CartesianSamples<'_, P> {
    type Item = (f64, Isometry3<f64>);

    fn next(&mut self) -> Option<Self::Item> {
        let t = self.times.next()?;
        Some((t, self.line.pose(t)))
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        self.times.size_hint()
    }
}

/// Runs `solve(target, seed)` on every `(t, target)` of `targets`, each time seeded with
/// the previous solution (`q_start` for the first). Yields `Ok((t, q))` per sample; on
/// the first `Err` it yields that error and then stops, because later seeds would be
/// stale.
///
/// `solve` is where an inverse-kinematics solver plugs in (e.g. damped least squares
/// from the runtime's `ik` module); seeding with the previous sample keeps the solution
/// on the branch the robot is on.
///
/// ```
/// use kinegen::trajectory::{track, CartesianLine, Trapezoid};
/// use nalgebra::{Isometry3, Vector3};
/// let a = Isometry3::translation(0.0, 0.0, 0.0);
/// let b = Isometry3::translation(1.0, 0.0, 0.0);
/// let line = CartesianLine::new(a, b, Trapezoid::new(0.0, 1.0, 1.0, 1.0)?)?;
/// // A "robot" whose joint is the x coordinate; the solver checks it got the last q.
/// let mut last = [0.0];
/// for step in line.track(100.0, [0.0], |target, seed: &[f64; 1]| {
///     assert_eq!(*seed, last);
///     last = [target.translation.x];
///     Ok::<_, ()>(last)
/// })? {
///     let (_t, q) = step.unwrap();
///     assert!((0.0..=1.0).contains(&q[0]));
/// }
/// # Ok::<(), kinegen::trajectory::TrajectoryError>(())
/// ```
pub fn track<I, F, E, const N: usize>(targets: I, q_start: [f64; N], solve: F) -> Track<I, F, N>
where
    I: Iterator<Item = (f64, Isometry3<f64>)>,
    F: FnMut(&Isometry3<f64>, &[f64; N]) -> Result<[f64; N], E>,
{
    Track {
        targets,
        seed: q_start,
        solve,
        failed: false,
    }
}

/// Iterator returned by [`track`].
#[derive(Debug, Clone)]
pub struct Track<I, F, const N: usize> {
    targets: I,
    seed: [f64; N],
    solve: F,
    failed: bool,
}

impl<I, F, E, const N: usize> Iterator for Track<I, F, N>
where
    I: Iterator<Item = (f64, Isometry3<f64>)>,
    F: FnMut(&Isometry3<f64>, &[f64; N]) -> Result<[f64; N], E>,
{
    type Item = Result<(f64, [f64; N]), E>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.failed {
            return None;
        }
        let (t, target) = self.targets.next()?;
        match (self.solve)(&target, &self.seed) {
            Ok(q) => {
                self.seed = q;
                Some(Ok((t, q)))
            }
            Err(e) => {
                self.failed = true;
                Some(Err(e))
            }
        }
    }
}
