//! The [`Profile`] trait every scalar motion law implements, and sampling at a control
//! rate without allocation.

use super::error::TrajectoryError;

/// A scalar motion law `q(t)` over `[0, T]`: one joint, or the path parameter `s(t)` of a
/// Cartesian line.
///
/// Outside `[0, T]` every method evaluates at the nearest end (`t` is clamped): before
/// the start the profile holds its initial state, after the end its final state. For
/// rest-to-rest profiles that is standing still at the start or goal.
pub trait Profile {
    /// Duration `T` in seconds.
    fn duration(&self) -> f64;

    /// Position `q(t)`.
    fn position(&self, t: f64) -> f64;

    /// Velocity `q̇(t)`.
    fn velocity(&self, t: f64) -> f64;

    /// Acceleration `q̈(t)`. Where it jumps (trapezoid phase switches) the value of the
    /// phase that starts at `t` is returned, and at `T` that of the last phase.
    fn acceleration(&self, t: f64) -> f64;

    /// Jerk `q⃛(t)`. Where the acceleration jumps, the jerk is a Dirac impulse that no
    /// number can represent; the finite part (here 0) is returned.
    fn jerk(&self, t: f64) -> f64;

    /// Samples `(t, q, q̇, q̈)` at `rate_hz`: `t = 0, 1/rate, 2/rate, …` and a last
    /// sample exactly at `T` if the grid does not land on it. Allocation-free.
    ///
    /// ```
    /// use kinegen::trajectory::{Profile, Trapezoid};
    /// let p = Trapezoid::new(0.0, 1.0, 2.0, 4.0)?;
    /// let last = p.sample(500.0)?.last().unwrap();
    /// assert_eq!(last, (p.duration(), 1.0, 0.0, -4.0));
    /// # Ok::<(), kinegen::trajectory::TrajectoryError>(())
    /// ```
    fn sample(&self, rate_hz: f64) -> Result<Samples<'_, Self>, TrajectoryError>
    where
        Self: Sized,
    {
        Ok(Samples {
            profile: self,
            times: SampleTimes::new(self.duration(), rate_hz)?,
        })
    }
}

/// Clamp `t` into `[0, duration]`; NaN goes to 0 so no method ever returns NaN for a NaN time.
#[inline]
pub(crate) fn clamp_time(t: f64, duration: f64) -> f64 {
    if t > 0.0 {
        if t < duration {
            t
        } else {
            duration
        }
    } else {
        0.0
    }
}

/// The sample times `0, 1/rate, 2/rate, …` up to `T`, ending exactly at `T`.
///
/// Each time is computed as `k / rate` (not by repeated addition), so it does not drift.
#[derive(Debug, Clone)]
pub struct SampleTimes {
    rate_hz: f64,
    duration: f64,
    next: u64,
    /// Index of the last grid time strictly before `T` (grid times up to it are yielded,
    /// then `T` itself).
    last_grid: u64,
    done: bool,
}

impl SampleTimes {
    /// The sample times of a motion of `duration` seconds at `rate_hz`.
    pub fn new(duration: f64, rate_hz: f64) -> Result<Self, TrajectoryError> {
        if !(rate_hz.is_finite() && rate_hz > 0.0) {
            return Err(TrajectoryError::InvalidRate { rate_hz });
        }
        if !(duration.is_finite() && duration >= 0.0) {
            return Err(TrajectoryError::InvalidDuration { value: duration });
        }
        let steps = duration * rate_hz;
        if !steps.is_finite() || steps >= u64::MAX as f64 {
            return Err(TrajectoryError::Overflow);
        }
        // Grid points closer to T than a millionth of a period are replaced by T itself,
        // so rounding in `T·rate` does not add a near-duplicate last sample.
        let mut last_grid = steps as u64; // truncation = floor for steps ≥ 0
        while last_grid > 0 && last_grid as f64 / rate_hz > duration - 1e-6 / rate_hz {
            last_grid -= 1;
        }
        Ok(Self {
            rate_hz,
            duration,
            next: 0,
            last_grid,
            done: false,
        })
    }

    fn remaining(&self) -> u64 {
        if self.done {
            0
        } else if self.duration == 0.0 {
            1
        } else {
            self.last_grid + 2 - self.next
        }
    }
}

impl Iterator for SampleTimes {
    type Item = f64;

    fn next(&mut self) -> Option<f64> {
        if self.done {
            return None;
        }
        if self.duration == 0.0 {
            self.done = true;
            return Some(0.0);
        }
        if self.next <= self.last_grid {
            let t = self.next as f64 / self.rate_hz;
            self.next += 1;
            Some(t)
        } else {
            self.done = true;
            Some(self.duration)
        }
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = self.remaining();
        match usize::try_from(n) {
            Ok(n) => (n, Some(n)),
            Err(_) => (usize::MAX, None),
        }
    }
}

/// Samples `(t, q, q̇, q̈)` of a [`Profile`]; see [`Profile::sample`].
#[derive(Debug, Clone)]
pub struct Samples<'a, P> {
    profile: &'a P,
    times: SampleTimes,
}

impl<P: Profile> Iterator for Samples<'_, P> {
    type Item = (f64, f64, f64, f64);

    fn next(&mut self) -> Option<Self::Item> {
        let t = self.times.next()?;
        let p = self.profile;
        Some((t, p.position(t), p.velocity(t), p.acceleration(t)))
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        self.times.size_hint()
    }
}
