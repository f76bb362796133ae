//! What the engine hands on for a robot's closed-form IK: the families ([`Family`],
//! [`Position`]), the plan ([`IkPlan`]: family, locked joint, derivation), and how a
//! family matched on a chain becomes a plan. The matching itself: `family.rs` (six and
//! seven joints), `fewer.rs` (fewer joints, or task rows).

/// A closed-form family.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Family {
    /// h2 ∥ h3 ∥ h4, h5 ∩ h6.
    ThreeParallelTwoIntersecting,
    /// Spherical wrist, h2 ∥ h3.
    SphericalTwoParallel,
    /// Spherical wrist, h1 ∩ h2.
    SphericalTwoIntersecting,
    /// Spherical wrist, h1 ∩ h2, joint 3 prismatic.
    SphericalTwoIntersectingPrismatic,
    /// All axes along world z: revolute joints (2 or 3, 0-based) and at most one
    /// prismatic joint, solving task rows x, y (rz with 3 revolute joints, z with the
    /// prismatic one).
    Planar {
        /// Revolute joints, in order.
        revolute: Vec<usize>,
        /// The prismatic joint, if any.
        prismatic: Option<usize>,
    },
    /// Three joints placing the tool point (task rows x, y, z).
    Position(Position),
    /// Three prismatic joints and one revolute joint about world z, in any order (task
    /// rows x, y, z, rz): the yaw, then the slides from a linear system
    /// (`kinegen::ik::families::cartesian_yaw`).
    CartesianYaw {
        /// The revolute joint (0-based).
        revolute: usize,
    },
    /// Four or five revolute joints, h2 ∥ h3 ∥ h4 after h1 (h1 ∦ h2); with five, the tool
    /// point on axis 5 (h5 ∦ h2): the position, the approach in the arm's plane and the
    /// roll (`kinegen::ik::families::pitch_roll`).
    PitchRoll {
        /// Five joints (a roll at the tool), else four.
        roll: bool,
    },
    /// Spherical wrist, the first three axes in no special position: SP5 (a quartic).
    Spherical,
    /// h2 ∥ h3 ∥ h4, h5 and h6 not meeting: SP6 (a quartic).
    ThreeParallel,
    /// Six revolute joints in no family, either way round: Raghavan and Roth's
    /// elimination to a 12 × 12 quadratic eigenproblem in one joint's half-angle tangent,
    /// solved at run time on the geometry's numbers (`kinegen::ik::families::general_6r`).
    General6r,
}

/// The cases of [`Family::Position`] (`kinegen::ik::families::position_*`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Position {
    /// R R R, h1 ∩ h2: q3 by SP3, (q1, q2) by SP2.
    Intersecting,
    /// R R R, h2 ∥ h3, h1 ∦ h2: q1 by SP4, q3 by SP3, q2 by SP1.
    Parallel,
    /// R R P, h1 ∩ h2: q3 from a quadratic, (q1, q2) by SP2.
    IntersectingPrismatic,
    /// One revolute joint, first (R P P, the cylindrical arm) or last (P P R), the
    /// prismatic axes not parallel and not both orthogonal to the revolute one.
    OneRevolute {
        /// The revolute joint is joint 1 (else joint 3).
        revolute_first: bool,
    },
    /// P P P, the axes independent.
    Cartesian,
}

/// How a robot's IK is generated.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct IkPlan {
    /// The family.
    pub family: Family,
    /// The joint locked (0-based) for a 7-joint arm.
    pub locked: Option<usize>,
    /// The family matches the chain read from the tool to the base: the runtime solves
    /// the inverted pose on the inverted geometry and reverses the joints back.
    pub reversed: bool,
    /// A 7-joint arm: every joint (0-based) whose locking leaves a family, in order.
    pub lockable: Vec<usize>,
    /// An S-R-S arm with an orthogonal shoulder and wrist (the iiwa): the derivation of
    /// its solutions by arm angle (`ik_arm_angle`, `arm_angle_intervals`), else `None`.
    pub arm_angle: Option<Vec<String>>,
    /// One-line name for `IK_FAMILY`.
    pub name: String,
    /// The derivation, one line per step, with the robot's joint numbers.
    pub steps: Vec<String>,
    /// Most solutions a pose can have.
    pub max_solutions: usize,
    /// The wrist is orthogonal (`a ⟂ h5 ⟂ h6` at `q = 0`, with `a` the axis turning
    /// before h5: h4, or h2 ∥ h3 ∥ h4 for the UR family), decided exactly: the second
    /// root of q5 takes the other wrist joints from the first by half turns
    /// (`kinegen::ik::families::WristPair::HalfTurn`).
    pub wrist_half_turn: bool,
}

impl Family {
    /// The runtime solver in `kinegen::ik::families`.
    pub fn solver(&self) -> &'static str {
        match self {
            Family::ThreeParallelTwoIntersecting => "three_parallel_two_intersecting",
            Family::SphericalTwoParallel => "spherical_two_parallel",
            Family::SphericalTwoIntersecting => "spherical_two_intersecting",
            Family::SphericalTwoIntersectingPrismatic => "spherical_two_intersecting_prismatic",
            Family::Planar { .. } => "planar",
            Family::Position(Position::Intersecting) => "position_intersecting",
            Family::Position(Position::Parallel) => "position_parallel",
            Family::Position(Position::IntersectingPrismatic) => "position_intersecting_prismatic",
            Family::Position(Position::OneRevolute { .. }) => "position_one_revolute",
            Family::Position(Position::Cartesian) => "position_cartesian",
            Family::PitchRoll { .. } => "pitch_roll",
            Family::CartesianYaw { .. } => "cartesian_yaw",
            Family::Spherical => "spherical",
            Family::ThreeParallel => "three_parallel",
            Family::General6r => "general_6r",
        }
    }

    /// How the family's first step is solved: 0 quadratics, 1 a quartic (SP5 or SP6),
    /// 2 the general 6R's eigenproblem. A family of a higher tier is chosen only where
    /// none of a lower one fits, either way round or with any joint locked.
    pub fn tier(&self) -> u8 {
        match self {
            Family::General6r => 2,
            Family::Spherical | Family::ThreeParallel => 1,
            _ => 0,
        }
    }

    fn title(&self) -> &'static str {
        match self {
            Family::ThreeParallelTwoIntersecting => "three parallel, two intersecting",
            Family::SphericalTwoParallel => "spherical wrist, two parallel",
            Family::SphericalTwoIntersecting => "spherical wrist, two intersecting",
            Family::SphericalTwoIntersectingPrismatic => {
                "spherical wrist, two intersecting, prismatic joint 3"
            }
            Family::Planar { .. } => "planar",
            Family::Position(Position::Intersecting) => "position, h1 ∩ h2",
            Family::Position(Position::Parallel) => "position, h2 ∥ h3",
            Family::Position(Position::IntersectingPrismatic) => {
                "position, h1 ∩ h2, prismatic joint 3"
            }
            Family::Position(Position::OneRevolute {
                revolute_first: true,
            }) => "position, cylindrical (R P P)",
            Family::Position(Position::OneRevolute {
                revolute_first: false,
            }) => "position, P P R",
            Family::Position(Position::Cartesian) => "position, Cartesian (P P P)",
            Family::CartesianYaw { .. } => "position and yaw, Cartesian with a turn about z",
            Family::PitchRoll { roll: false } => "position and pitch, h2 ∥ h3 ∥ h4 (4 joints)",
            Family::PitchRoll { roll: true } => {
                "position, pitch and roll, h2 ∥ h3 ∥ h4, tool on axis 5 (5 joints)"
            }
            Family::Spherical => "spherical wrist, general arm (SP5)",
            Family::ThreeParallel => "three parallel (SP6)",
            Family::General6r => "general 6R (Raghavan–Roth elimination, eigenvalues)",
        }
    }

    /// Most solutions a pose can have.
    fn max_solutions(&self) -> usize {
        match self {
            Family::Planar { .. } => 2,
            Family::Position(Position::OneRevolute { .. }) => 2,
            Family::Position(Position::Cartesian) | Family::CartesianYaw { .. } => 1,
            Family::Position(_) | Family::PitchRoll { .. } => 4,
            Family::General6r => 16,
            _ => 8,
        }
    }
}

/// A 6-joint family matched on some labels: the family, its steps, whether the wrist is
/// orthogonal, whether the labels were read from the tool.
pub(super) struct Match {
    pub(super) family: Family,
    pub(super) steps: Vec<String>,
    pub(super) half_turn: bool,
    pub(super) reversed: bool,
}

/// `why`: the line saying which joint a 7-joint arm leaves free and why.
pub(super) fn finish(
    m: Match,
    locked: Option<usize>,
    lockable: Vec<usize>,
    why: Option<String>,
) -> IkPlan {
    let direction = if m.reversed {
        ", read from the tool"
    } else {
        ""
    };
    let name = match locked {
        Some(k) => format!("{}{direction} (joint {} locked)", m.family.title(), k + 1),
        None => format!("{}{direction}", m.family.title()),
    };
    let max_solutions = m.family.max_solutions();
    let mut steps: Vec<String> = why.into_iter().collect();
    steps.extend(m.steps);
    IkPlan {
        family: m.family,
        locked,
        reversed: m.reversed,
        lockable,
        arm_angle: None,
        name,
        steps,
        max_solutions,
        wrist_half_turn: m.half_turn,
    }
}
