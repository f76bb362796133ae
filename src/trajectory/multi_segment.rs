//! Paths through via points `p₀, p₁, …, p_{K−1}`, as one profile over the whole motion.
//!
//! Two ways to pass a via point:
//! - [`StopAtVias`]: a trapezoid per segment, so the motion comes to rest at every point
//!   (velocity and acceleration-free joins are trivially continuous: `q̇ = 0`).
//! - [`ThroughVias`]: a cubic per segment with a shared velocity at each via point, so
//!   the motion flows through without stopping. Position and velocity are continuous at
//!   the joins; acceleration is not (that would need a cubic spline, a global solve).
//!
//! Limits: [`StopAtVias`] is built from trapezoids within `v_max` and `a_max`.
//! [`ThroughVias::new`] takes the times as given and does not look at limits;
//! [`ThroughVias::new_within`] refuses times whose cubics exceed `v_max` or `a_max`
//! ([`TrajectoryError::LimitExceeded`]), and [`ThroughVias::with_limits`] chooses the
//! times itself: the fastest schedule, among uniform scalings of per-segment rest-to-rest
//! times, whose peaks stay within both limits.
//!
//! The via velocities of [`ThroughVias::new`] follow the common heuristic (Craig,
//! *Introduction to Robotics*, §7.3): with the segment slopes `mᵢ = (pᵢ − pᵢ₋₁)/(tᵢ − tᵢ₋₁)`,
//! the velocity at via point `i` is `(mᵢ + mᵢ₊₁)/2` if both slopes have the same sign,
//! and 0 if the path turns back there (or either segment is flat); the first and last
//! points are at rest.
//!
//! Everything lives in fixed-size arrays: `K` is the number of points, so there are
//! `K − 1` segments (the arrays hold one unused slot, because `K − 1` cannot be written
//! as an array length in stable Rust).

use super::error::{self, TrajectoryError};
use super::polynomial::Cubic;
use super::profile::{clamp_time, Profile};
use super::trapezoid::{Stretch, Trapezoid};
use crate::math;

/// Checks `K ≥ 2`, finite points, and `times` starting at 0 and increasing strictly.
fn check_path<const K: usize>(
    points: &[f64; K],
    times: Option<&[f64; K]>,
) -> Result<(), TrajectoryError> {
    if K < 2 {
        return Err(TrajectoryError::TooFewPoints { count: K });
    }
    for p in points {
        error::finite(*p, "via point")?;
    }
    if let Some(times) = times {
        for (i, t) in times.iter().enumerate() {
            error::finite(*t, "via-point time")?;
            let ok = if i == 0 { *t == 0.0 } else { *t > times[i - 1] };
            if !ok {
                return Err(TrajectoryError::TimesNotIncreasing { index: i });
            }
        }
    }
    Ok(())
}

/// Index of the segment that holds `t` (already clamped to `[0, T]`): the last `i` with
/// `times[i] ≤ t`, at most `K − 2` so `t = T` falls at the end of the last segment.
fn segment_index<const K: usize>(times: &[f64; K], t: f64) -> usize {
    times[1..].partition_point(|&ti| ti <= t).min(K - 2)
}

/// Via points visited one after the other, at rest at each (a trapezoid per segment).
///
/// ```
/// use kinegen::trajectory::{Profile, StopAtVias};
/// let path = StopAtVias::new([0.0, 1.0, 0.5], 1.0, 2.0)?;
/// let t1 = path.arrival_times()[1];
/// assert_eq!(path.position(t1), 1.0);
/// assert_eq!(path.velocity(t1), 0.0);
/// # Ok::<(), kinegen::trajectory::TrajectoryError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(
        into = "super::stored::StopAtViasParts<K>",
        try_from = "super::stored::StopAtViasParts<K>"
    )
)]
pub struct StopAtVias<const K: usize> {
    /// `segments[i]` goes from point `i` to `i + 1`; the last slot is unused.
    segments: [Trapezoid; K],
    /// Arrival time at each point (`times[0] = 0`).
    times: [f64; K],
}

impl<const K: usize> StopAtVias<K> {
    /// Each segment as fast as `v_max` and `a_max` allow.
    pub fn new(points: [f64; K], v_max: f64, a_max: f64) -> Result<Self, TrajectoryError> {
        check_path(&points, None)?;
        let mut segments = [Trapezoid::at_rest(points[K - 1], 0.0); K];
        let mut times = [0.0; K];
        for i in 0..K - 1 {
            segments[i] = Trapezoid::new(points[i], points[i + 1], v_max, a_max)?;
            times[i + 1] = times[i] + segments[i].duration();
        }
        Ok(Self { segments, times })
    }

    /// Arrive at point `i` at `times[i]` (`times[0] = 0`, strictly increasing), each
    /// segment a trapezoid within `v_max` and `a_max` slowed down as `stretch` says.
    /// `Err` if a segment's time is shorter than its limits allow.
    pub fn with_times(
        points: [f64; K],
        times: [f64; K],
        v_max: f64,
        a_max: f64,
        stretch: Stretch,
    ) -> Result<Self, TrajectoryError> {
        check_path(&points, Some(&times))?;
        let mut segments = [Trapezoid::at_rest(points[K - 1], 0.0); K];
        for i in 0..K - 1 {
            segments[i] = Trapezoid::stretched(
                points[i],
                points[i + 1],
                v_max,
                a_max,
                times[i + 1] - times[i],
                stretch,
            )?;
        }
        Ok(Self { segments, times })
    }

    /// `N` joints through `K` joint-space points, stopping at each, synchronised per
    /// segment: segment `i` takes the longest of the joints' minimum times, so all joints
    /// arrive at every via point together. Returns one profile per joint.
    pub fn synchronized<const N: usize>(
        points: [[f64; N]; K],
        v_max: [f64; N],
        a_max: [f64; N],
        stretch: Stretch,
    ) -> Result<[Self; N], TrajectoryError> {
        if K < 2 {
            return Err(TrajectoryError::TooFewPoints { count: K });
        }
        let mut times = [0.0; K];
        for i in 0..K - 1 {
            let mut longest = 0.0_f64;
            for j in 0..N {
                let seg = Trapezoid::new(points[i][j], points[i + 1][j], v_max[j], a_max[j])?;
                longest = longest.max(seg.duration());
            }
            if longest == 0.0 {
                // Two equal consecutive points: a zero-length segment has no arrival
                // time of its own, so refuse rather than divide by zero later.
                return Err(TrajectoryError::TimesNotIncreasing { index: i + 1 });
            }
            times[i + 1] = times[i] + longest;
        }
        let mut out = [Self {
            segments: [Trapezoid::at_rest(0.0, 0.0); K],
            times,
        }; N];
        for j in 0..N {
            out[j] = Self::with_times(points.map(|p| p[j]), times, v_max[j], a_max[j], stretch)?;
        }
        Ok(out)
    }

    /// Arrival time at each point (`[0] = 0`, `[K − 1] = T`).
    pub fn arrival_times(&self) -> &[f64; K] {
        &self.times
    }

    /// Segments planned already (the last slot unused) and their arrival times: `Err`
    /// unless they join (each ends where the next starts), the times start at 0 and
    /// each is the previous plus its segment's duration (to rounding: `with_times`
    /// takes the times as given). What a stored path is read back through.
    #[cfg(feature = "serde")]
    pub(super) fn from_parts(
        segments: [Trapezoid; K],
        times: [f64; K],
    ) -> Result<Self, TrajectoryError> {
        if K < 2 {
            return Err(TrajectoryError::TooFewPoints { count: K });
        }
        if times[0] != 0.0 {
            return Err(TrajectoryError::TimesNotIncreasing { index: 0 });
        }
        for i in 0..K - 1 {
            let t = error::finite(times[i + 1], "via-point time")?;
            let arrival = times[i] + segments[i].duration();
            if math::abs(arrival - t) > 4.0 * f64::EPSILON * math::abs(t) {
                let what = "arrival time";
                return Err(TrajectoryError::PartsDoNotFit { part: i, what });
            }
            if i + 2 < K && segments[i].goal() != segments[i + 1].start() {
                return Err(TrajectoryError::PartsDoNotFit {
                    part: i,
                    what: "end",
                });
            }
        }
        // The unused last slot stands at the last point, as the constructors leave it.
        if segments[K - 1] != Trapezoid::at_rest(segments[K - 2].goal(), 0.0) {
            return Err(TrajectoryError::PartsDoNotFit {
                part: K - 2,
                what: "end",
            });
        }
        Ok(Self { segments, times })
    }

    /// Segment `i` (from point `i` to `i + 1`), with its own local time from 0.
    pub fn segment(&self, i: usize) -> Option<&Trapezoid> {
        self.segments[..K - 1].get(i)
    }

    fn locate(&self, t: f64) -> (&Trapezoid, f64) {
        let t = clamp_time(t, self.duration());
        let i = segment_index(&self.times, t);
        let seg = &self.segments[i];
        // At the very end use the segment's own end time: `T − tᵢ` can round below it.
        let local = if t >= self.duration() {
            seg.duration()
        } else {
            t - self.times[i]
        };
        (seg, local)
    }
}

impl<const K: usize> Profile for StopAtVias<K> {
    fn duration(&self) -> f64 {
        self.times[K - 1]
    }
    fn position(&self, t: f64) -> f64 {
        let (s, u) = self.locate(t);
        s.position(u)
    }
    fn velocity(&self, t: f64) -> f64 {
        let (s, u) = self.locate(t);
        s.velocity(u)
    }
    fn acceleration(&self, t: f64) -> f64 {
        let (s, u) = self.locate(t);
        s.acceleration(u)
    }
    fn jerk(&self, t: f64) -> f64 {
        let (s, u) = self.locate(t);
        s.jerk(u)
    }
}

/// Via points passed with continuous velocity: a cubic per segment.
///
/// ```
/// use kinegen::trajectory::{Profile, ThroughVias};
/// let path = ThroughVias::new([0.0, 1.0, 3.0], [0.0, 1.0, 2.0])?;
/// // Slopes 1 and 2 have the same sign: pass the middle point at their mean, 1.5.
/// assert_eq!(path.via_velocities(), &[0.0, 1.5, 0.0]);
/// assert_eq!(path.velocity(1.0), 1.5);
/// # Ok::<(), kinegen::trajectory::TrajectoryError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(
        into = "super::stored::ThroughViasPoints<K>",
        try_from = "super::stored::ThroughViasPoints<K>"
    )
)]
pub struct ThroughVias<const K: usize> {
    /// `segments[i]` goes from point `i` to `i + 1`; the last slot is unused.
    segments: [Cubic; K],
    times: [f64; K],
    velocities: [f64; K],
}

impl<const K: usize> ThroughVias<K> {
    /// Through `points` at `times` (`times[0] = 0`, strictly increasing), with the via
    /// velocities from [`heuristic_via_velocities`].
    pub fn new(points: [f64; K], times: [f64; K]) -> Result<Self, TrajectoryError> {
        check_path(&points, Some(&times))?;
        Self::with_velocities(points, times, heuristic_via_velocities(&points, &times))
    }

    /// Like [`ThroughVias::new`], but `Err(LimitExceeded)` if any segment's cubic peaks
    /// above `v_max` in `|q̇|` or `a_max` in `|q̈|`: the times are too short for the limits.
    ///
    /// ```
    /// use kinegen::trajectory::{ThroughVias, TrajectoryError};
    /// // 2 rad in the first second needs a peak speed of 3 rad/s (1.5 Δ/T).
    /// let fast = ThroughVias::new_within([0.0, 2.0], [0.0, 1.0], 2.0, 100.0);
    /// assert!(matches!(fast, Err(TrajectoryError::LimitExceeded { what: "velocity", .. })));
    /// assert!(ThroughVias::new_within([0.0, 2.0], [0.0, 1.5], 2.0, 100.0).is_ok());
    /// ```
    pub fn new_within(
        points: [f64; K],
        times: [f64; K],
        v_max: f64,
        a_max: f64,
    ) -> Result<Self, TrajectoryError> {
        let v_max = error::limit(v_max, "v_max")?;
        let a_max = error::limit(a_max, "a_max")?;
        let path = Self::new(points, times)?;
        path.check_limits(v_max, a_max)?;
        Ok(path)
    }

    /// Through `points` as fast as `v_max` and `a_max` allow, within one family of
    /// schedules: segment `i` first gets the rest-to-rest cubic time
    /// `max(1.5|Δᵢ|/v_max, √(6|Δᵢ|/a_max))`, the heuristic via velocities are computed,
    /// and then the whole schedule is scaled by one factor `k`.
    ///
    /// Scaling every time by `k` scales the heuristic via velocities, hence every
    /// segment's velocity, by `1/k` and its acceleration by `1/k²` (the cubics keep their
    /// shape in normalised time). So `k = max(peak_v/v_max, √(peak_a/a_max))` computed
    /// once makes the tighter limit exactly binding and the other one satisfied. Not
    /// time-optimal in general (that needs per-segment times), but never over a limit.
    ///
    /// `Err(TimesNotIncreasing)` if two consecutive points are equal (a zero-length
    /// segment has no rest-to-rest time); limits must be finite and positive.
    ///
    /// ```
    /// use kinegen::trajectory::{Profile, ThroughVias};
    /// let path = ThroughVias::with_limits([0.0, 1.0, 3.0, 2.0], 1.0, 2.0)?;
    /// let peak_v = (0..=1000)
    ///     .map(|k| path.velocity(path.duration() * k as f64 / 1000.0).abs())
    ///     .fold(0.0, f64::max);
    /// assert!(peak_v <= 1.0 + 1e-9);
    /// # Ok::<(), kinegen::trajectory::TrajectoryError>(())
    /// ```
    pub fn with_limits(points: [f64; K], v_max: f64, a_max: f64) -> Result<Self, TrajectoryError> {
        let v_max = error::limit(v_max, "v_max")?;
        let a_max = error::limit(a_max, "a_max")?;
        check_path(&points, None)?;
        let mut times = [0.0; K];
        for i in 0..K - 1 {
            let d = math::abs(points[i + 1] - points[i]);
            if d == 0.0 {
                return Err(TrajectoryError::TimesNotIncreasing { index: i + 1 });
            }
            let t = (1.5 * d / v_max).max(math::sqrt(6.0 * d / a_max));
            times[i + 1] = error::finite(times[i] + t, "segment time")?;
        }
        let trial = Self::new(points, times)?;
        let (peak_v, peak_a) = trial.peaks();
        let k = (peak_v.0 / v_max).max(math::sqrt(peak_a.0 / a_max));
        if !(k.is_finite() && k > 0.0) {
            return Err(TrajectoryError::Overflow);
        }
        // Rounding in the cubics' coefficients can leave a peak some ulps above the
        // limit after exact scaling: slow down by a relative 1e-12 (then 1e-11, …).
        let mut nudge = 1e-12;
        loop {
            let mut scaled = times;
            for t in scaled.iter_mut() {
                *t = error::finite(*t * k * (1.0 + nudge), "segment time")?;
            }
            let path = Self::new(points, scaled)?;
            match path.check_limits(v_max, a_max) {
                Ok(()) => return Ok(path),
                Err(e) if nudge >= 1e-9 => return Err(e),
                Err(_) => nudge *= 10.0,
            }
        }
    }

    /// `Err(LimitExceeded)` naming the first segment whose peak `|q̇|` exceeds `v_max` or
    /// peak `|q̈|` exceeds `a_max`.
    pub fn check_limits(&self, v_max: f64, a_max: f64) -> Result<(), TrajectoryError> {
        for i in 0..K - 1 {
            let (v, a) = cubic_peaks(&self.segments[i]);
            if v > v_max {
                return Err(TrajectoryError::LimitExceeded {
                    what: "velocity",
                    segment: i,
                    peak: v,
                    limit: v_max,
                });
            }
            if a > a_max {
                return Err(TrajectoryError::LimitExceeded {
                    what: "acceleration",
                    segment: i,
                    peak: a,
                    limit: a_max,
                });
            }
        }
        Ok(())
    }

    /// Largest `|q̇|` and `|q̈|` over the whole path, each with its segment:
    /// `((peak_v, segment), (peak_a, segment))`, exact (from the cubics' coefficients).
    pub fn peaks(&self) -> ((f64, usize), (f64, usize)) {
        let (mut v, mut a) = ((0.0, 0), (0.0, 0));
        for i in 0..K - 1 {
            let (pv, pa) = cubic_peaks(&self.segments[i]);
            if pv > v.0 {
                v = (pv, i);
            }
            if pa > a.0 {
                a = (pa, i);
            }
        }
        (v, a)
    }

    /// Through `points` at `times` with the given velocity at every point (including
    /// the first and last).
    pub fn with_velocities(
        points: [f64; K],
        times: [f64; K],
        velocities: [f64; K],
    ) -> Result<Self, TrajectoryError> {
        check_path(&points, Some(&times))?;
        for v in &velocities {
            error::finite(*v, "via velocity")?;
        }
        // Placeholder for the unused last slot; every real slot is overwritten below.
        let mut segments = [Cubic::new(0.0, 0.0, 0.0, 0.0, 1.0)?; K];
        for i in 0..K - 1 {
            segments[i] = Cubic::new(
                points[i],
                points[i + 1],
                velocities[i],
                velocities[i + 1],
                times[i + 1] - times[i],
            )?;
        }
        Ok(Self {
            segments,
            times,
            velocities,
        })
    }

    /// `N` joints through `K` joint-space points at common `times`: one profile per
    /// joint, each with its own heuristic via velocities.
    pub fn joints<const N: usize>(
        points: [[f64; N]; K],
        times: [f64; K],
    ) -> Result<[Self; N], TrajectoryError> {
        check_path(&[0.0; K], Some(&times))?;
        let first = Self::new(points.map(|p| p[0]), times);
        let mut out = [first?; N];
        for j in 1..N {
            out[j] = Self::new(points.map(|p| p[j]), times)?;
        }
        Ok(out)
    }

    /// Velocity at each point.
    pub fn via_velocities(&self) -> &[f64; K] {
        &self.velocities
    }

    /// Time at each point.
    pub fn arrival_times(&self) -> &[f64; K] {
        &self.times
    }

    /// Segment `i` (from point `i` to `i + 1`), with its own local time from 0.
    pub fn segment(&self, i: usize) -> Option<&Cubic> {
        self.segments[..K - 1].get(i)
    }

    fn locate(&self, t: f64) -> (&Cubic, f64) {
        let t = clamp_time(t, self.duration());
        let i = segment_index(&self.times, t);
        let seg = &self.segments[i];
        // At the very end use the segment's own end time: `T − tᵢ` can round below it.
        let local = if t >= self.duration() {
            seg.duration()
        } else {
            t - self.times[i]
        };
        (seg, local)
    }
}

/// Peak `|q̇|` and `|q̈|` of a cubic on `[0, T]`: `q̈` is linear, so its peak is at an end;
/// `q̇` is quadratic, so its peak is at an end or at the vertex `t* = −c₂/(3c₃)`.
fn cubic_peaks(c: &Cubic) -> (f64, f64) {
    let [_, c1, c2, c3, _, _] = c.coefficients();
    let t = c.duration();
    let v = |t: f64| c1 + 2.0 * c2 * t + 3.0 * c3 * t * t;
    let mut peak_v = math::abs(v(0.0)).max(math::abs(v(t)));
    if c3 != 0.0 {
        let vertex = -c2 / (3.0 * c3);
        if vertex > 0.0 && vertex < t {
            peak_v = peak_v.max(math::abs(v(vertex)));
        }
    }
    let peak_a = math::abs(2.0 * c2).max(math::abs(2.0 * c2 + 6.0 * c3 * t));
    (peak_v, peak_a)
}

/// The via velocities [`ThroughVias::new`] uses: 0 at both ends; at an inner point the
/// mean of the adjacent segments' slopes if they have the same sign, else 0 (so the path
/// does not overshoot a point where it turns back).
pub fn heuristic_via_velocities<const K: usize>(points: &[f64; K], times: &[f64; K]) -> [f64; K] {
    let mut v = [0.0; K];
    for i in 1..K.saturating_sub(1) {
        let before = (points[i] - points[i - 1]) / (times[i] - times[i - 1]);
        let after = (points[i + 1] - points[i]) / (times[i + 1] - times[i]);
        if before * after > 0.0 {
            v[i] = 0.5 * (before + after);
        }
    }
    v
}

impl<const K: usize> Profile for ThroughVias<K> {
    fn duration(&self) -> f64 {
        self.times[K - 1]
    }
    fn position(&self, t: f64) -> f64 {
        let (s, u) = self.locate(t);
        s.position(u)
    }
    fn velocity(&self, t: f64) -> f64 {
        let (s, u) = self.locate(t);
        s.velocity(u)
    }
    fn acceleration(&self, t: f64) -> f64 {
        let (s, u) = self.locate(t);
        s.acceleration(u)
    }
    fn jerk(&self, t: f64) -> f64 {
        let (s, u) = self.locate(t);
        s.jerk(u)
    }
}
