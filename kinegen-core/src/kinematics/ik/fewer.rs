//! The families of arms with fewer than six joints, or solving task rows: planar arms,
//! the 3-joint position arms, the gantry with a turn about z (task rows), and the 4- and
//! 5-joint arms with a pitching wrist (the whole pose) — each decided exactly from the
//! axes at `q = 0`, each failed condition named.

use crate::chain::Chain;
use crate::kinematics::frames::SymbolicChain;
use crate::kinematics::ik::axes::Axes;
use crate::kinematics::ik::plan::{finish, Family, IkPlan, Match, Position};
use crate::model::robot::{JointKind, TaskRow};

/// Planar arms solving their task rows.
pub(super) fn planar(
    chain: &Chain,
    max_terms: usize,
    kinds: &[JointKind],
) -> Result<IkPlan, String> {
    let task = chain.task.clone().unwrap_or_default();
    let sym = SymbolicChain::at_zero(chain, max_terms, None);
    let axes = Axes::of(&sym).ok_or("the axes' normal forms are over the term budget")?;
    let z = crate::kinematics::ik::axes::unit_z();
    if let Some(i) = (0..chain.dof()).find(|&i| !axes.along(i, &z)) {
        return Err(format!("planar: axis {} is not along world z", i + 1));
    }
    let revolute: Vec<usize> = (0..chain.dof())
        .filter(|&i| kinds[i] == JointKind::Revolute)
        .collect();
    let prismatic: Vec<usize> = (0..chain.dof())
        .filter(|&i| kinds[i] == JointKind::Prismatic)
        .collect();
    let mut want = vec![TaskRow::X, TaskRow::Y];
    if revolute.len() == 3 {
        want.push(TaskRow::Rz);
    }
    if prismatic.len() == 1 {
        want.push(TaskRow::Z);
    }
    let mut have = task.clone();
    have.sort();
    want.sort();
    if !(2..=3).contains(&revolute.len()) || prismatic.len() > 1 || have != want {
        return Err(format!(
            "planar: {} revolute and {} prismatic joints along z with task rows [{}] (planar IK \
             solves x, y with 2 revolute joints, + rz with 3, + z with one prismatic joint)",
            revolute.len(),
            prismatic.len(),
            task.iter().map(|r| r.name()).collect::<Vec<_>>().join(", ")
        ));
    }
    let steps = steps_planar(&revolute, prismatic.first().copied());
    let family = Family::Planar {
        revolute,
        prismatic: prismatic.first().copied(),
    };
    Ok(plain(family, steps))
}

/// Three joints placing the tool point (task rows x, y, z): the cases of [`Position`],
/// decided exactly at `q = 0`.
pub(super) fn position(
    chain: &Chain,
    max_terms: usize,
    kinds: &[JointKind],
) -> Result<IkPlan, String> {
    let sym = SymbolicChain::at_zero(chain, max_terms, None);
    let axes = Axes::of(&sym).ok_or("the axes' normal forms are over the term budget")?;
    let r = |i: usize| kinds[i] == JointKind::Revolute;
    let (case, steps) = match (r(0), r(1), r(2)) {
        (true, true, third) if axes.intersect(0, 1) && !axes.parallel(0, 1) => {
            if third {
                (
                    Position::Intersecting,
                    vec![
                        "c12 where axes 1 and 2 meet; d = p − c12".to_string(),
                        "q3 — SP3: ‖(p3 − c12) + rot(h3, q3) (pT − p3)‖ = ‖d‖ (two roots)".into(),
                        "(q1, q2) — SP2: rot(−h1, q1) d = rot(h2, q2) ((p3 − c12) + R3 (pT − p3)) (two pairs; q1 free when p is on axis 1)".into(),
                    ],
                )
            } else {
                (
                    Position::IntersectingPrismatic,
                    vec![
                        "c12 where axes 1 and 2 meet; d = p − c12, u = pT − c12".to_string(),
                        "q3 — ‖u + q3 h3‖ = ‖d‖ (a quadratic, two roots)".into(),
                        "(q1, q2) — SP2: rot(−h1, q1) d = rot(h2, q2) (u + q3 h3) (two pairs; q1 free when p is on axis 1)".into(),
                    ],
                )
            }
        }
        (true, true, true) if axes.parallel(1, 2) && !axes.parallel(0, 1) => (
            Position::Parallel,
            vec![
                "q1 — SP4: h2ᵀ rot(−h1, q1) (p − p1) = h2ᵀ (pT − p1) (two roots)".to_string(),
                "q3 — SP3: ‖p23 + rot(h3, q3) p3T‖ = ‖rot(−h1, q1) (p − p1) − p12‖ (two roots)".into(),
                "q2 — SP1: rot(h2, q2) (p23 + R3 p3T) = rot(−h1, q1) (p − p1) − p12".into(),
            ],
        ),
        (first, false, last) if first != last => {
            // One revolute joint, first or last; the prismatic axes a, b.
            let (rv, [a, b]) = if first { (0, [1, 2]) } else { (2, [0, 1]) };
            if axes.parallel(a, b) {
                return Err(format!(
                    "position: the prismatic axes {} and {} are parallel",
                    a + 1,
                    b + 1
                ));
            }
            if axes.perpendicular(rv, a) && axes.perpendicular(rv, b) {
                return Err(format!(
                    "position: axis {} is orthogonal to both prismatic axes: the component of p along it is fixed",
                    rv + 1
                ));
            }
            let steps = if first {
                vec![
                    "n = h2 × h3 / ‖h2 × h3‖".to_string(),
                    "q1 — SP4: nᵀ rot(−h1, q1) (p − p1) = nᵀ (pT − p1) (two roots)".into(),
                    "(q2, q3) — q2 h2 + q3 h3 = rot(−h1, q1) (p − p1) − (pT − p1) (a 2 × 2 linear system)".into(),
                ]
            } else {
                vec![
                    "n = h1 × h2 / ‖h1 × h2‖".to_string(),
                    "q3 — SP4: nᵀ rot(h3, q3) (pT − p3) = nᵀ (p − p3) (two roots)".into(),
                    "(q1, q2) — q1 h1 + q2 h2 = (p − p3) − rot(h3, q3) (pT − p3) (a 2 × 2 linear system)".into(),
                ]
            };
            (
                Position::OneRevolute {
                    revolute_first: first,
                },
                steps,
            )
        }
        (false, false, false) => {
            if !axes.independent(0, 1, 2) {
                return Err("position: the prismatic axes are not independent".into());
            }
            (
                Position::Cartesian,
                vec!["(q1, q2, q3) — q1 h1 + q2 h2 + q3 h3 = p − pT (Cramer's rule)".to_string()],
            )
        }
        _ => {
            return Err(
                "position: none of R R R with h1 ∩ h2 or h2 ∥ h3, R R P with h1 ∩ h2, R P P, P P R, P P P"
                    .into(),
            )
        }
    };
    Ok(plain(Family::Position(case), steps))
}

/// Four joints, task rows x, y, z, rz, not all along z: [`Family::CartesianYaw`], decided
/// exactly at `q = 0`.
pub(super) fn cartesian_yaw(
    chain: &Chain,
    max_terms: usize,
    kinds: &[JointKind],
) -> Result<IkPlan, String> {
    let revolute: Vec<usize> = (0..4)
        .filter(|&i| kinds[i] == JointKind::Revolute)
        .collect();
    let &[r] = revolute.as_slice() else {
        return Err(format!(
            "Cartesian with yaw: {} revolute joints (it has one, about z, and three prismatic)",
            revolute.len()
        ));
    };
    let sym = SymbolicChain::at_zero(chain, max_terms, None);
    let axes = Axes::of(&sym).ok_or("the axes' normal forms are over the term budget")?;
    let z = crate::kinematics::ik::axes::unit_z();
    let slides: Vec<usize> = (0..4).filter(|&i| i != r).collect();
    // The yaw turns the slides after joint r: their determinant stays what it is at q = 0
    // when none comes before r, or every one after r is vertical.
    let constant =
        slides.iter().all(|&i| i > r) || slides.iter().all(|&i| i < r || axes.along(i, &z));
    let fails = [
        (
            !axes.along(r, &z),
            format!("axis {} is not along world z", r + 1),
        ),
        (
            !axes.independent(slides[0], slides[1], slides[2]),
            "the prismatic axes are not independent".into(),
        ),
        (
            !constant,
            format!(
                "a prismatic axis after joint {} is not vertical: the yaw would turn it against those before",
                r + 1
            ),
        ),
    ];
    if let Some((_, why)) = fails.iter().find(|(fail, _)| *fail) {
        return Err(format!("Cartesian with yaw: {why}"));
    }
    let names: Vec<String> = slides.iter().map(|i| format!("q{}", i + 1)).collect();
    let steps = vec![
        format!(
            "q{} — the yaw: ψ = φ − φ0 (the tool's angle about z, minus its angle at q = 0), q{} = ±ψ",
            r + 1,
            r + 1
        ),
        format!(
            "({}) — p = c + Σ qi ai with q{} known (c the tool point with the slides at 0, ai their axes): Cramer's rule",
            names.join(", "),
            r + 1
        ),
    ];
    Ok(plain(Family::CartesianYaw { revolute: r }, steps))
}

/// Four or five revolute joints, the whole pose: [`Family::PitchRoll`], decided exactly at
/// `q = 0`.
pub(super) fn pitch_roll(
    chain: &Chain,
    max_terms: usize,
    kinds: &[JointKind],
) -> Result<IkPlan, String> {
    let n = chain.dof();
    let sym = SymbolicChain::at_zero(chain, max_terms, None);
    let axes = Axes::of(&sym).ok_or("the axes' normal forms are over the term budget")?;
    let roll = n == 5;
    let fails = [
        (
            kinds.iter().any(|k| *k != JointKind::Revolute),
            "a joint is prismatic".to_string(),
        ),
        (
            !(axes.parallel(1, 2) && axes.parallel(2, 3)),
            "axes 2, 3, 4 are not parallel".into(),
        ),
        (axes.parallel(0, 1), "axis 1 is parallel to axis 2".into()),
        (
            roll && axes.parallel(4, 1),
            "axis 5 is parallel to axes 2–4 (the roll would add to the pitch)".into(),
        ),
        (
            roll && !axes.tool_on(4),
            "the tool point is off axis 5 (the roll would move it)".into(),
        ),
    ];
    if let Some((_, why)) = fails.iter().find(|(fail, _)| *fail) {
        return Err(format!("pitch and roll ({n} joints): {why}"));
    }
    let v = if roll { "h5" } else { "v = h2 × h1" };
    let mut steps = vec![
        format!(
            "q1 — SP4: h2ᵀ rot(−h1, q1) (p − p1) = h2ᵀ (pT − p1) (two roots: the arm's plane; \
             joints 2–{n} keep the tool point's component along h2); with the tool point on axis 1, \
             (q1, θ) — SP2 from the approach: rot(−h1, q1) R {v} = rot(h2, θ) {v}"
        ),
        if roll {
            "θ = q2 ± q3 ± q4 — SP1: rot(h2, θ) h5 = rot(−h1, q1) R h5, R = R0T RTᵀ (the approach; \
             least squares where it leaves the arm's plane: the position comes first)"
                .to_string()
        } else {
            "θ = q2 ± q3 ± q4 — the turn about h2 nearest to rot(−h1, q1) R, R = R0T RTᵀ, over both \
             directions of the plane ⟂ h2 (the whole rotation: checked on fk; least squares where \
             it is not a turn about h2: the position comes first)"
                .to_string()
        },
    ];
    if roll {
        steps.push(
            "q5 — SP1: rot(h5, q5) x = rot(h2, −θ) rot(−h1, q1) R x, x = h5 × h2 (the roll)".into(),
        );
    }
    steps.extend([
        "q3 — SP3: ‖p23 + rot(h3, q3) p34‖ = ‖w‖, w = rot(−h1, q1) (p − p1) − p12 − rot(h2, θ) (pT − p4) (two roots)".to_string(),
        "q2 — SP1: rot(h2, q2) (p23 + R3 p34) = w; q4 = ±(θ − q2 ∓ q3)".into(),
    ]);
    Ok(plain(Family::PitchRoll { roll }, steps))
}

fn steps_planar(revolute: &[usize], prismatic: Option<usize>) -> Vec<String> {
    let r: Vec<usize> = revolute.iter().map(|i| i + 1).collect();
    let mut s = Vec::new();
    if r.len() == 3 {
        s.push(format!(
            "φ = the tool's angle about z; the point on axis {c} is p{c} = p − rot(z, φ − φ0) (pT − p{c})",
            c = r[2]
        ));
    }
    let (w, end) = match r.get(2) {
        Some(c) => (format!("p{c}"), format!("p{}{c}", r[1])),
        None => ("p".to_string(), format!("p{}T", r[1])),
    };
    s.push(format!(
        "q{b} — SP3 in the xy plane: ‖p{a}{b} + rot(h{b}, q{b}) {end}‖ = ‖{w} − p{a}‖ (elbow up / down)",
        a = r[0],
        b = r[1]
    ));
    s.push(format!("q{} — SP1", r[0]));
    if r.len() == 3 {
        s.push(format!(
            "q{} from φ = ±q{} ± q{} ± q{} + φ0",
            r[2], r[0], r[1], r[2]
        ));
    }
    if let Some(p) = prismatic {
        s.push(format!("q{} from z (it moves along z)", p + 1));
    }
    s
}

/// The plan of a family matched on the chain as it is (no joint locked, read from the
/// base, no wrist).
fn plain(family: Family, steps: Vec<String>) -> IkPlan {
    let m = Match {
        family,
        steps,
        half_turn: false,
        reversed: false,
    };
    finish(m, None, Vec::new(), None)
}
