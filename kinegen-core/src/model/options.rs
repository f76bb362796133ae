//! What bounds the engine: the [`Budget`] a user sets, the one [`Deadline`] it becomes
//! when the engine starts, and the other [`Options`].

use std::time::{Duration, Instant};

/// Bounds on the symbolic engine; over them it emits correct, less simplified code.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Budget {
    /// e-graph node limit per simplification run.
    pub nodes: usize,
    /// e-graph iteration limit per run.
    pub iterations: usize,
    /// Wall-clock safety net for the whole engine, milliseconds: one deadline, set when
    /// the engine starts ([`Deadline`]); each long phase checks it and, past it, emits
    /// correct but less simplified code and a note naming the phase.
    pub time_ms: u64,
}

impl Budget {
    /// Largest normal form (terms) the exact core keeps for one expression.
    pub fn max_terms(&self) -> usize {
        self.nodes.max(1)
    }
}

/// The moment the engine must stop simplifying: [`Budget::time_ms`] after it started.
///
/// Past it every phase takes the path that is always correct: new normal forms are
/// dropped (structural sharing only), no further middle frame is tried, the e-graph
/// polish stops, and the determinant is the numeric LU one. Before it, nothing depends
/// on the clock, so the output is the same on every run that does not reach it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Deadline {
    /// `None`: never.
    at: Option<Instant>,
    /// The budget it came from (for notes).
    ms: u64,
}

impl Deadline {
    /// `ms` milliseconds from now (0: already passed).
    pub fn after_ms(ms: u64) -> Self {
        Deadline {
            at: Instant::now().checked_add(Duration::from_millis(ms)),
            ms,
        }
    }

    /// The deadline of a budget, starting now.
    pub fn start(budget: &Budget) -> Self {
        Deadline::after_ms(budget.time_ms)
    }

    /// A deadline that never passes (the default of the low-level builders).
    pub fn never() -> Self {
        Deadline { at: None, ms: 0 }
    }

    /// Whether it has passed.
    pub fn passed(&self) -> bool {
        self.at.is_some_and(|t| Instant::now() >= t)
    }

    /// Time left (zero once passed; `Duration::MAX` for [`Deadline::never`]).
    pub fn remaining(&self) -> Duration {
        match self.at {
            Some(t) => t.saturating_duration_since(Instant::now()),
            None => Duration::MAX,
        }
    }

    /// What a note says about it: ``the `time_ms` budget (500 ms)``.
    pub fn describe(&self) -> String {
        format!("the `time_ms` budget ({} ms)", self.ms)
    }
}

impl Default for Deadline {
    fn default() -> Self {
        Deadline::never()
    }
}

impl Default for Budget {
    fn default() -> Self {
        Budget {
            nodes: 5_000,
            iterations: 20,
            time_ms: 10_000,
        }
    }
}

/// Engine options beyond the robot model.
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// Bounds on simplification.
    pub budget: Budget,
    /// Extra rewrite rules `(lhs, rhs)` for the e-graph polish, in egg's pattern
    /// syntax (`("(* ?a (+ ?b ?c))", "(+ (* ?a ?b) (* ?a ?c))")`). For experiments:
    /// every rewritten expression is checked against the unsimplified one, so a wrong
    /// rule is caught and reported, never emitted (see [`crate::simplify::polish`]).
    pub extra_rewrites: Vec<(String, String)>,
    /// The joint (0-based) a 7-joint arm's closed-form IK leaves free (`ik_free`, written
    /// 1-based); `None`: the engine's default (see
    /// [`crate::kinematics::ik::family::FREE_JOINT_ORDER`]).
    pub ik_free: Option<usize>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deadlines() {
        let never = Deadline::never();
        assert!(!never.passed());
        assert_eq!(never.remaining(), Duration::MAX);
        let now = Deadline::after_ms(0);
        assert!(now.passed());
        assert_eq!(now.remaining(), Duration::ZERO);
        let later = Deadline::start(&Budget::default());
        assert!(later.remaining() <= Duration::from_secs(10));
        assert_eq!(later.describe(), "the `time_ms` budget (10000 ms)");
    }
}
