//! Planar arms — **every axis along world z**: planar 2R and 3R arms, SCARA. They solve the
//! task rows x, y (with three revolute joints also the angle about z, with a prismatic
//! joint also z): the elbow from SP3 in the xy plane, the first joint from SP1, the third
//! from the tool's angle, the prismatic joint from z.

use crate::ik::geometry::{rot, Geometry, Pose, M3, V3};
use crate::ik::solutions::Candidates;
use crate::ik::subproblems::{sp1, sp3, wrap};

/// **Planar** — every axis along world z; solves the task rows x, y (with three revolute
/// joints also the angle about z, with a prismatic joint also z):
///
/// 1. with three revolute joints, `ψ = φ − φ0` (the tool's angle about z, minus its
///    angle at `q = 0`) fixes the last one's contribution: `w = p − rot(z, ψ) (pT − p3)`
/// 2. the second revolute joint — SP3 in the xy plane: `‖p12 + rot(h2, q2) v‖ = ‖w − p1‖`
///    (elbow up, elbow down)
/// 3. the first — SP1; the third from ψ; the prismatic joint from z.
///
/// `revolute` lists the revolute joints (2 or 3, 0-based), `prismatic` the prismatic one.
pub fn planar<const N: usize>(
    g: &Geometry<N>,
    pose: &Pose,
    revolute: &[usize],
    prismatic: Option<usize>,
    free: &[f64; N],
    out: &mut Candidates<N, 2>,
) {
    let flat = |v: V3| V3::new(v.x, v.y, 0.0);
    let z = V3::z();
    let sign = |i: usize| g.h[i].z.signum();
    let (a, b) = (revolute[0], revolute[1]);
    let psi = yaw(g, pose);
    let (w, end) = match revolute.get(2) {
        Some(&c) => (pose.p - rot(&z, psi) * (g.p_tool - g.p[c]), g.p[c]),
        None => (pose.p, g.p_tool),
    };
    let (p_ab, v, d) = (flat(g.p[b] - g.p[a]), flat(end - g.p[b]), flat(w - g.p[a]));
    let tb = sp3(&v, &(-p_ab), &g.h[b], d.norm(), free[b]);
    for qb in tb.as_slice() {
        let u = p_ab + qb.rot(&g.h[b]) * v;
        let qb = qb.theta;
        let (qa, fa) = sp1(&u, &d, &g.h[a], free[a]);
        let mut q = *free;
        q[a] = qa;
        q[b] = qb;
        if let Some(&c) = revolute.get(2) {
            q[c] = wrap(sign(c) * (psi - sign(a) * qa - sign(b) * qb));
        }
        if let Some(j) = prismatic {
            q[j] = sign(j) * (pose.p.z - g.p_tool.z);
        }
        out.push(q, tb.fit.and(fa));
    }
}

/// `ψ = φ − φ0`: the tool's angle about world z at `pose` (its x axis' azimuth, as the
/// task row `rz` measures it), minus its angle at `q = 0`.
#[inline]
pub(super) fn yaw<const N: usize>(g: &Geometry<N>, pose: &Pose) -> f64 {
    let angle = |r: &M3| crate::math::atan2(r[(1, 0)], r[(0, 0)]);
    angle(&pose.r) - angle(&g.r_tool)
}
