//! The twelve ways to write the general 6R's loop as Raghavan and Roth's two sides
//! ([`Formulation`]): which joint's point and direction are carried round the loop, and
//! where the loop is split; the links of each side as they act on a point and a
//! direction ([`Link`]).

use crate::ik::geometry::{rot_sc, Geometry, Pose, M3, V3};

/// One link of the closed loop `e^{ξ1 q1} ⋯ e^{ξ6 q6} M T⁻¹ = I`, as it acts on a point
/// or a direction: a joint's turn (about `axis`, which is `−h` for an inverse turn, so the
/// angle is always the joint's own value) or the fixed transform `M T⁻¹` (or its inverse).
#[derive(Clone, Copy, Debug)]
pub(super) enum Link {
    Turn { joint: usize, axis: V3, point: V3 },
    Fixed { r: M3, t: V3 },
}

impl Link {
    /// The link applied to a point `p` and a direction `l`, a turn by the angle of sine
    /// `s` and cosine `c`.
    #[inline]
    pub(super) fn apply(&self, p: &V3, l: &V3, s: f64, c: f64) -> (V3, V3) {
        match self {
            Link::Turn { axis, point, .. } => {
                let r = rot_sc(axis, s, c);
                (r * (p - point) + point, r * l)
            }
            Link::Fixed { r, t } => (r * p + t, r * l),
        }
    }

    fn inverse(&self) -> Link {
        match *self {
            Link::Turn { joint, axis, point } => Link::Turn {
                joint,
                axis: -axis,
                point,
            },
            Link::Fixed { r, t } => Link::Fixed {
                r: r.transpose(),
                t: -(r.tr_mul(&t)),
            },
        }
    }
}

/// One way to write the loop as Raghavan and Roth's two sides (see the module):
/// the joint whose axis gives `(p, l)` (eliminated first), and whether the three-joint side
/// comes after the split (else before). Twelve in all; a special geometry (two parallel
/// axes, a 60° wrist) makes some of them degenerate — six dependent equations, or a
/// singular pencil — and the solver takes the first that is not.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Formulation {
    /// The joint (0-based) whose point and direction are carried round the loop.
    pub eliminated: usize,
    /// The three-joint side is the one after the split (`true`) or before it.
    pub three_after: bool,
}

/// The order the formulations are tried in: Raghavan and Roth's own (joint 6 eliminated,
/// joints 3, 4, 5 against 1, 2) and its mirror first.
pub const FORMULATIONS: [Formulation; 12] = {
    let mut all = [Formulation {
        eliminated: 5,
        three_after: true,
    }; 12];
    let order = [5, 0, 2, 3, 1, 4];
    let mut i = 0;
    while i < 6 {
        all[2 * i] = Formulation {
            eliminated: order[i],
            three_after: true,
        };
        all[2 * i + 1] = Formulation {
            eliminated: order[i],
            three_after: false,
        };
        i += 1;
    }
    all
};

impl Formulation {
    /// The joint whose half-angle tangent is the eigenvalue: the third after the
    /// eliminated one round the loop, wherever the loop is split (split after two joints,
    /// it is the first of the three-joint side's; after three, the last).
    pub const fn eigen_joint(&self) -> usize {
        (self.eliminated + 3) % 6
    }
}

/// The two sides of one formulation for one pose.
pub(super) struct Sides {
    /// The eliminated joint's point and direction.
    pub(super) start: (V3, V3),
    /// The three-joint side, innermost first: two links sampled (with the fixed one,
    /// if it lies there), the last one the joint whose angle becomes the eigenvalue.
    pub(super) three: [Link; 4],
    pub(super) three_len: usize,
    /// The two-joint side, innermost first.
    pub(super) two: [Link; 3],
    pub(super) two_len: usize,
}

impl Formulation {
    /// The loop read from just after the eliminated joint `f`: the links `e1 ⋯ e6` (five
    /// turns and `M T⁻¹`) with `e1 ⋯ e6 (p_f, h_f) = (p_f, h_f)`; split after the second
    /// joint (`three_after`: `e3 ⋯ e6 (p, h) = e2⁻¹ e1⁻¹ (p, h)`) or after the third
    /// (`e4 ⋯ e6 (p, h) = e3⁻¹ e2⁻¹ e1⁻¹ (p, h)`), the fixed link kept off the outer end of
    /// the three-joint side.
    pub(super) fn sides(&self, g: &Geometry<6>, pose: &Pose) -> Sides {
        let f = self.eliminated;
        let rt = pose.r.transpose();
        let fixed = Link::Fixed {
            r: g.r_tool * rt,
            t: g.p_tool - g.r_tool * (rt * pose.p),
        };
        let turn = |j: usize| Link::Turn {
            joint: j,
            axis: g.h[j],
            point: g.p[j],
        };
        // The loop after f: joints f+1 … 5, M T⁻¹, joints 0 … f−1.
        let mut links = [fixed; 6];
        let mut n = 0;
        for j in f + 1..6 {
            links[n] = turn(j);
            n += 1;
        }
        links[n] = fixed;
        n += 1;
        for j in 0..f {
            links[n] = turn(j);
            n += 1;
        }
        // Where the split falls: after the `k`-th joint (2 or 3).
        let k = if self.three_after { 2 } else { 3 };
        let mut joints = 0;
        let mut cut = 0;
        for (i, l) in links.iter().enumerate() {
            if let Link::Turn { .. } = l {
                joints += 1;
                if joints == k {
                    cut = i + 1;
                }
            }
        }
        // The fixed link right at the split goes to the two-joint side.
        let fixed_at_cut = matches!(links[cut], Link::Fixed { .. });
        let mut sides = Sides {
            start: (g.p[f], g.h[f]),
            three: [fixed; 4],
            three_len: 0,
            two: [fixed; 3],
            two_len: 0,
        };
        // Before the split, inverted: e1⁻¹ innermost.
        let before: &[Link] = &links[..cut];
        let after: &[Link] = &links[cut..];
        if self.three_after {
            // Three after: e3 ⋯ e6, innermost e6; the fixed link at the split moves over
            // as its inverse, applied last on the two-joint side.
            let (after, moved) = if fixed_at_cut {
                (&after[1..], Some(links[cut].inverse()))
            } else {
                (after, None)
            };
            for l in after.iter().rev() {
                sides.three[sides.three_len] = *l;
                sides.three_len += 1;
            }
            for l in before.iter() {
                sides.two[sides.two_len] = l.inverse();
                sides.two_len += 1;
            }
            if let Some(m) = moved {
                sides.two[sides.two_len] = m;
                sides.two_len += 1;
            }
        } else {
            // Three before, inverted: e1⁻¹ innermost, e3⁻¹ outermost; a fixed link just
            // before the split (after the third joint) cannot be there, it would be
            // outermost: it moves to the other side, innermost-last.
            let last_is_fixed = matches!(before[cut - 1], Link::Fixed { .. });
            let (before, moved) = if last_is_fixed {
                (&before[..cut - 1], Some(before[cut - 1]))
            } else {
                (before, None)
            };
            for l in before.iter() {
                sides.three[sides.three_len] = l.inverse();
                sides.three_len += 1;
            }
            for l in after.iter().rev() {
                sides.two[sides.two_len] = *l;
                sides.two_len += 1;
            }
            if let Some(m) = moved {
                sides.two[sides.two_len] = m;
                sides.two_len += 1;
            }
        }
        sides
    }
}

/// The joint of a turn.
pub(super) fn joint(l: &Link) -> usize {
    match l {
        Link::Turn { joint, .. } => *joint,
        Link::Fixed { .. } => usize::MAX,
    }
}
