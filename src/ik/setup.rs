//! What the family solvers compute from the geometry and the target before the first
//! joint, shared by the branch-by-branch solvers ([`super::families`]) and the lanes
//! ([`super::regular`]).

use super::geometry::{meet, mul_transposed, mv, Geometry, Pose, M3, V3};

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
        let (r06, c56_target) = target_point(g, pose, &c56);
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
            p16: c56_target - g.p[0],
        }
    }
}

/// The target's rotation without the tool, `R06 = R0T r_toolᵀ`, and where the point `c` of
/// the last link (given at `q = 0`) is at the target: `p0T − R06 (p_tool − c)`.
#[inline(always)]
pub fn target_point(g: &Geometry<6>, pose: &Pose, c: &V3) -> (M3, V3) {
    let r06 = mul_transposed(&pose.r, &g.r_tool);
    (r06, pose.p - mv(&r06, &(g.p_tool - c)))
}

/// A spherical wrist's `R06`, its centre `w0` (where joints 4, 5, 6 meet) at `q = 0`, and
/// the centre at the target.
#[inline(always)]
pub fn wrist_centre(g: &Geometry<6>, pose: &Pose) -> (M3, V3, V3) {
    let w0 = meet(g, 3, 4);
    let (r06, w) = target_point(g, pose, &w0);
    (r06, w0, w)
}

/// A spherical wrist's arm (PUMA family, SP5 family): the target's rotation without the
/// tool, the links from joint 1's point to the wrist centre at `q = 0`, and the wrist
/// centre at the target seen from joint 1's point.
#[derive(Clone, Copy, Debug)]
pub struct WristArm {
    /// `R06 = R0T r_toolᵀ`.
    pub r06: M3,
    /// `p12`, `p23`, and `p34` to the wrist centre.
    pub links: [V3; 3],
    /// `p16 = w − p1`, `w` the wrist centre at the target.
    pub p16: V3,
}

impl WristArm {
    /// The set-up of `g` for the target `pose`.
    #[inline(always)]
    pub fn new(g: &Geometry<6>, pose: &Pose) -> WristArm {
        let (r06, w0, w) = wrist_centre(g, pose);
        WristArm {
            r06,
            links: [g.p[1] - g.p[0], g.p[2] - g.p[1], w0 - g.p[2]],
            p16: w - g.p[0],
        }
    }
}
