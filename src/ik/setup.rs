//! What a family's solvers compute from the geometry and the target before the first
//! joint, shared by the branch-by-branch solvers ([`super::families`]) and the lanes
//! ([`super::regular`]).

use super::geometry::{meet, Geometry, Pose, M3, V3};

/// **h2 ∥ h3 ∥ h4, h5 ∩ h6** (Universal Robots): the links between the joints' points up to
/// where axes 5 and 6 meet, the senses of the parallel axes, and that point at the target.
#[derive(Clone, Copy, Debug)]
pub struct ThreeParallel {
    /// The joint axes.
    pub h: [V3; 6],
    /// `h3 = σ3 h2` (the engine proved them parallel).
    pub s3: f64,
    /// `h4 = σ4 h2`.
    pub s4: f64,
    /// `p12`, `p23`, `p34`, and `p45` to where axes 5 and 6 meet.
    pub links: [V3; 4],
    /// The target's rotation without the tool: `R06 = R0T r_toolᵀ`.
    pub r06: M3,
    /// Where axes 5 and 6 meet at the target, from joint 1's point:
    /// `p16 = p0T − R06 p6T − p1`.
    pub p16: V3,
}

impl ThreeParallel {
    /// The set-up of `g` for the target `pose`.
    #[inline(always)]
    pub fn new(g: &Geometry<6>, pose: &Pose) -> ThreeParallel {
        let c56 = meet(g, 4, 5);
        let r06 = pose.r * g.r_tool.transpose();
        let h = g.h;
        ThreeParallel {
            h,
            s3: h[2].dot(&h[1]).signum(),
            s4: h[3].dot(&h[1]).signum(),
            links: [
                g.p[1] - g.p[0],
                g.p[2] - g.p[1],
                g.p[3] - g.p[2],
                c56 - g.p[3],
            ],
            r06,
            p16: pose.p - r06 * (g.p_tool - c56) - g.p[0],
        }
    }
}
