//! A serial arm's zero-configuration geometry, the form the closed-form solvers read:
//! joint `i` turns about (or slides along) the unit axis `h[i]` through the point `p[i]`,
//! all in the base frame at `q = 0`, and the tool's pose at `q = 0` is `(r_tool, p_tool)`.
//!
//! With `R_i = rot(h[i], q[i])` (product of exponentials, IK-Geo's convention),
//!
//! ```text
//! R(q) = R_1 ⋯ R_N · r_tool
//! p(q) = p[0] + R_1 (p[1] − p[0]) + R_1 R_2 (p[2] − p[1]) + ⋯ + R_1 ⋯ R_N (p_tool − p[N−1])
//! ```
//!
//! (a prismatic joint `i` adds `q[i] h[i]` after `R_1 ⋯ R_{i−1}`). Any point on an axis
//! serves; the solvers move points onto axis intersections ([`closest_points`]).

use super::lanes::{Lanes, Vectors};
use crate::math::{abs, all_finite, sin_cos, sqrt};
use nalgebra::{Matrix3, Vector3};

/// A 3-vector.
pub type V3 = Vector3<f64>;
/// A 3×3 matrix.
pub type M3 = Matrix3<f64>;

/// Zero-configuration geometry of an `N`-joint arm (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Geometry<const N: usize> {
    /// Unit joint axes, base frame, `q = 0`.
    pub h: [V3; N],
    /// A point on each axis.
    pub p: [V3; N],
    /// `true` for a prismatic joint.
    pub prismatic: [bool; N],
    /// Tool orientation at `q = 0`.
    pub r_tool: M3,
    /// Tool position at `q = 0`.
    pub p_tool: V3,
}

/// A target pose: rotation and position of the tool in the base frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// Rotation.
    pub r: M3,
    /// Position.
    pub p: V3,
}

impl Pose {
    /// From a row-major homogeneous transform.
    #[inline]
    pub fn from_matrix(t: &[[f64; 4]; 4]) -> Pose {
        Pose {
            r: M3::from_fn(|i, j| t[i][j]),
            p: V3::new(t[0][3], t[1][3], t[2][3]),
        }
    }

    /// The inverse transform `(Rᵀ, −Rᵀ p)`.
    #[inline]
    pub fn inverse(&self) -> Pose {
        let rt = self.r.transpose();
        Pose {
            r: rt,
            p: -(rt * self.p),
        }
    }

    /// Whether every entry is finite.
    #[inline]
    pub fn is_finite(&self) -> bool {
        // One comparison for all twelve entries (instead of a branch each).
        all_finite(self.r.iter().chain(self.p.iter()))
    }
}

/// `m v`, as the operator computes it. With the `small-ik` feature one out-of-line copy
/// of its nine products and six sums (on a Cortex-M each a soft-float call) serves every
/// caller; else it is the operator, inlined.
#[cfg_attr(feature = "small-ik", inline(never))]
#[cfg_attr(not(feature = "small-ik"), inline(always))]
pub(crate) fn mv(m: &M3, v: &V3) -> V3 {
    m * v
}

/// `a bᵀ`, as the operators compute it (out of line with `small-ik`, as [`mv`]).
#[cfg_attr(feature = "small-ik", inline(never))]
#[cfg_attr(not(feature = "small-ik"), inline(always))]
pub(crate) fn mul_transposed(a: &M3, b: &M3) -> M3 {
    a * b.transpose()
}

/// The rotation about the unit axis `k` whose angle has sine `s` and cosine `c`
/// (Rodrigues: `c I + s [k]× + (1 − c) k kᵀ`).
#[inline]
pub fn rot_sc(k: &V3, s: f64, c: f64) -> M3 {
    let t = 1.0 - c;
    let (x, y, z) = (k.x, k.y, k.z);
    M3::new(
        c + t * x * x,
        t * x * y - s * z,
        t * x * z + s * y,
        t * x * y + s * z,
        c + t * y * y,
        t * y * z - s * x,
        t * x * z - s * y,
        t * y * z + s * x,
        c + t * z * z,
    )
}

/// The rotation by `theta` about the unit axis `k`.
#[inline]
pub fn rot(k: &V3, theta: f64) -> M3 {
    // Size first, through `Angle::new`: one copy of the inlined `sin_cos` for both (the
    // same bits).
    #[cfg(feature = "small-ik")]
    {
        Angle::new(theta).rot(k)
    }
    #[cfg(not(feature = "small-ik"))]
    {
        let (s, c) = sin_cos(theta);
        rot_sc(k, s, c)
    }
}

/// An angle with its sine and cosine. The subproblems find the sine and cosine of their
/// roots algebraically (a root of `r cos(θ − φ) = b` has them from `r`, `φ`'s and `b`
/// without a `sin`/`cos` call), so the solvers turn by a root without evaluating it again.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Angle {
    /// The angle (radians, `(−π, π]` when it comes from a subproblem).
    pub theta: f64,
    /// `sin θ`.
    pub sin: f64,
    /// `cos θ`.
    pub cos: f64,
}

impl Angle {
    /// `theta`, with its sine and cosine evaluated.
    #[cfg_attr(feature = "small-ik", inline(never))]
    pub fn new(theta: f64) -> Angle {
        let (sin, cos) = sin_cos(theta);
        Angle { theta, sin, cos }
    }

    /// The angle whose sine and cosine are proportional to `y` and `x` (`x² + y² > 0`).
    #[inline]
    pub fn atan2(y: f64, x: f64) -> Angle {
        let r = sqrt(x * x + y * y);
        Angle {
            theta: crate::math::fast_atan2(y, x),
            sin: y / r,
            cos: x / r,
        }
    }

    /// The rotation by this angle about the unit axis `k`.
    #[inline]
    pub fn rot(&self, k: &V3) -> M3 {
        rot_sc(k, self.sin, self.cos)
    }
}

/// A fixed vector `p` turned about a fixed unit axis `k`: `rot(k, θ) p = a + cos θ u +
/// sin θ w` with `a = (k·p) k`, `u = p − a`, `w = k × p`, split once so that each turn
/// costs six products (instead of a rotation matrix and its product with `p`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orbit {
    a: V3,
    u: V3,
    w: V3,
}

impl Orbit {
    /// `p`'s orbit about `k`.
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn new(k: &V3, p: &V3) -> Orbit {
        let a = k * k.dot(p);
        Orbit {
            a,
            u: p - a,
            w: k.cross(p),
        }
    }

    /// `rot(k, θ) p` for the angle `t`.
    #[inline]
    pub fn at(&self, t: &Angle) -> V3 {
        self.a + self.u * t.cos + self.w * t.sin
    }

    /// `rot(k, −θ) p = rot(k, θ)ᵀ p` for the angle `t`.
    #[inline]
    pub fn back(&self, t: &Angle) -> V3 {
        self.a + self.u * t.cos - self.w * t.sin
    }

    /// `rot(k, θ) p` for the `L` angles with cosines `c` and sines `s` (`−s`: backwards).
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn at_lanes<const L: usize>(&self, c: Lanes<L>, s: Lanes<L>) -> Vectors<L> {
        Vectors::circle(&self.a, &self.u, &self.w, c, s)
    }
}

/// A vector orthogonal to the unit `k` (`k` crossed with the coordinate axis least
/// parallel to it: never short).
#[inline]
pub(crate) fn orthogonal(k: &V3) -> V3 {
    let e = if abs(k.x) < 0.6 {
        V3::x()
    } else if abs(k.y) < 0.6 {
        V3::y()
    } else {
        V3::z()
    };
    k.cross(&e)
}

/// The points `a + s·u` and `b + t·v` closest to each other on two lines, or `None` when
/// the lines are parallel (to `tol` in `|u × v|²`).
pub fn closest_points(a: &V3, u: &V3, b: &V3, v: &V3, tol: f64) -> Option<(V3, V3)> {
    let n = u.cross(v);
    let nn = n.norm_squared();
    if nn <= tol {
        return None;
    }
    let d = b - a;
    let s = d.cross(v).dot(&n) / nn;
    let t = d.cross(u).dot(&n) / nn;
    Some((a + u * s, b + v * t))
}

impl<const N: usize> Geometry<N> {
    /// The tool pose at joint values `q` (for tests and checks; the generated `fk` is the
    /// fast one).
    pub fn fk(&self, q: &[f64; N]) -> Pose {
        self.frames(q).0
    }

    /// The tool pose at `q`, with each joint's axis and point in the world frame (the
    /// columns of the geometric Jacobian come from them).
    pub fn frames(&self, q: &[f64; N]) -> (Pose, [V3; N], [V3; N]) {
        let (mut axes, mut points) = ([V3::zeros(); N], [V3::zeros(); N]);
        let mut r = M3::identity();
        let mut p = self.p[0];
        for (i, &qi) in q.iter().enumerate() {
            let next = if i + 1 < N {
                self.p[i + 1]
            } else {
                self.p_tool
            };
            (axes[i], points[i]) = (r * self.h[i], p);
            if self.prismatic[i] {
                p += axes[i] * qi;
            } else {
                r *= rot(&self.h[i], qi);
            }
            p += r * (next - self.p[i]);
        }
        let pose = Pose {
            r: r * self.r_tool,
            p,
        };
        (pose, axes, points)
    }

    /// The same arm read from the tool to the base: joint `i` of the result is joint
    /// `N − 1 − i` of `self`. With `T(q) = e^{ξ1 q1} ⋯ e^{ξN qN} M` (`M` the tool at
    /// `q = 0`), `T(q)⁻¹ = M⁻¹ e^{−ξN qN} ⋯ e^{−ξ1 q1} = e^{ξ'1 qN} ⋯ e^{ξ'N q1} M⁻¹`
    /// where `ξ'` is `−ξ` seen from the tool at `q = 0`: axis `−R_Mᵀ h`, point
    /// `R_Mᵀ (p − p_M)`. So the reversed geometry's forward kinematics at the joints
    /// reversed is the inverse of `self`'s pose: `g.reversed().fk(q_rev) =
    /// g.fk(q).inverse()`.
    pub fn reversed(&self) -> Geometry<N> {
        let rt = self.r_tool.transpose();
        Geometry {
            h: core::array::from_fn(|i| -(rt * self.h[N - 1 - i])),
            p: core::array::from_fn(|i| rt * (self.p[N - 1 - i] - self.p_tool)),
            prismatic: core::array::from_fn(|i| self.prismatic[N - 1 - i]),
            r_tool: rt,
            p_tool: -(rt * self.p_tool),
        }
    }

    /// The `N − 1`-joint geometry with joint `k` locked at `q_k` (its motion folded into
    /// the axes and points after it and into the tool). `M` must be `N − 1`.
    pub fn lock<const M: usize>(&self, k: usize, q_k: f64) -> Geometry<M> {
        debug_assert!(M + 1 == N && k < N);
        let (r, shift) = if self.prismatic[k] {
            (M3::identity(), self.h[k] * q_k)
        } else {
            (rot(&self.h[k], q_k), V3::zeros())
        };
        let pk = self.p[k];
        let moved = |x: &V3| pk + r * (x - pk) + shift;
        let mut g = Geometry {
            h: [V3::zeros(); M],
            p: [V3::zeros(); M],
            prismatic: [false; M],
            r_tool: r * self.r_tool,
            p_tool: moved(&self.p_tool),
        };
        for (j, i) in (0..N).filter(|&i| i != k).enumerate() {
            let after = i > k;
            g.h[j] = if after { r * self.h[i] } else { self.h[i] };
            g.p[j] = if after { moved(&self.p[i]) } else { self.p[i] };
            g.prismatic[j] = self.prismatic[i];
        }
        g
    }

    /// The `N − 1`-joint problem with joint `k` locked at `q_k`: its geometry and the pose
    /// its joints must reach. The first joint's motion moves the pose instead of the
    /// geometry — `T = e^{ξ1 q1} T'(q2 … qN)`, so the others reach `e^{−ξ1 q1} T` on the
    /// geometry as it is, one pose turned where [`Geometry::lock`] turns every axis, point
    /// and the tool after the joint; any other joint is locked by [`Geometry::lock`] and
    /// the pose kept. `M` must be `N − 1`.
    ///
    /// ```
    /// use kinegen::ik::geometry::{Geometry, V3, M3};
    /// let g = Geometry::<3> {
    ///     h: [V3::z(), V3::y(), V3::y()],
    ///     p: [V3::zeros(), V3::new(0.0, 0.0, 0.3), V3::new(0.4, 0.0, 0.3)],
    ///     prismatic: [false; 3],
    ///     r_tool: M3::identity(),
    ///     p_tool: V3::new(0.7, 0.0, 0.3),
    /// };
    /// let q = [0.4, -0.3, 0.9];
    /// let (rest, target) = g.lock_at_pose::<2>(0, q[0], &g.fk(&q));
    /// let reached = rest.fk(&[q[1], q[2]]);
    /// assert!((reached.p - target.p).norm() < 1e-15 && (reached.r - target.r).norm() < 1e-15);
    /// ```
    // Inlined where the PC's build has the room: the reversed chain's constant axes fold
    // into the turn of the pose (Panda `ik_with`: 5 744 → 5 463 instructions).
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn lock_at_pose<const M: usize>(
        &self,
        k: usize,
        q_k: f64,
        pose: &Pose,
    ) -> (Geometry<M>, Pose) {
        debug_assert!(M + 1 == N && k < N);
        if k != 0 {
            return (self.lock(k, q_k), *pose);
        }
        let (h, p0) = (self.h[0], self.p[0]);
        let target = if self.prismatic[0] {
            Pose {
                r: pose.r,
                p: pose.p - h * q_k,
            }
        } else {
            let undo = rot(&h, -q_k);
            Pose {
                r: undo * pose.r,
                p: p0 + undo * (pose.p - p0),
            }
        };
        let rest = Geometry {
            h: core::array::from_fn(|j| self.h[j + 1]),
            p: core::array::from_fn(|j| self.p[j + 1]),
            prismatic: core::array::from_fn(|j| self.prismatic[j + 1]),
            r_tool: self.r_tool,
            p_tool: self.p_tool,
        };
        (rest, target)
    }
}

/// Lines closer to parallel than this (`|u × v|²`) have no intersection point to move to.
const PARALLEL: f64 = 1e-20;

/// Where the axes of joints `i` and `j` (0-based) meet, at `q = 0` (the midpoint of the
/// closest points: the engine proved they meet, this only absorbs rounding).
// Indexed where it is called (the joints are constants there), so the solve itself has
// no bounds check: on a microcontroller a panic path pulls in the formatting machinery.
#[inline(always)]
pub(crate) fn meet<const N: usize>(g: &Geometry<N>, i: usize, j: usize) -> V3 {
    meet_lines((&g.p[i], &g.h[i]), (&g.p[j], &g.h[j]))
}

/// [`meet`] for the lines through `p` along `h`.
#[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
fn meet_lines((pi, hi): (&V3, &V3), (pj, hj): (&V3, &V3)) -> V3 {
    // The generated geometries often place a point where the axes meet already (exactly
    // on the other axis): then that point, without the closest-points solve.
    for (h, a, b) in [(hi, pi, pj), (hj, pj, pi)] {
        if h.cross(&(b - a)) == V3::zeros() {
            return *b;
        }
    }
    match closest_points(pi, hi, pj, hj, PARALLEL) {
        Some((a, b)) => (a + b) * 0.5,
        None => *pi,
    }
}

/// The part of `v` orthogonal to the unit `k` (out of line with `small-ik`, as [`mv`]).
#[cfg_attr(feature = "small-ik", inline(never))]
#[cfg_attr(not(feature = "small-ik"), inline)]
pub(crate) fn flat(k: &V3, v: &V3) -> V3 {
    v - k * k.dot(v)
}

/// `|x|` with a floor, for relative tolerances.
#[inline]
pub(crate) fn scale(x: f64) -> f64 {
    abs(x).max(1e-300)
}

/// `√max(x, 0)`.
#[inline]
pub(crate) fn sqrt0(x: f64) -> f64 {
    sqrt(x.max(0.0))
}

/// Geometries of real arms for the unit tests of the solvers.
#[cfg(test)]
pub(crate) mod examples {
    use super::*;

    /// UR5 (standard DH, CB3 numbers) at q = 0 in product-of-exponentials form.
    pub(crate) fn ur5() -> Geometry<6> {
        let (d1, a2, a3, d4, d5, d6) = (0.089159, -0.425, -0.39225, 0.10915, 0.09465, 0.0823);
        let z = V3::z();
        let y = V3::new(0.0, -1.0, 0.0);
        Geometry {
            h: [z, y, y, y, -z, y],
            p: [
                V3::zeros(),
                V3::new(0.0, 0.0, d1),
                V3::new(a2, 0.0, d1),
                V3::new(a2 + a3, -d4, d1),
                V3::new(a2 + a3, -d4, d1),
                V3::new(a2 + a3, -d4, d1 - d5),
            ],
            prismatic: [false; 6],
            r_tool: M3::new(1.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0),
            p_tool: V3::new(a2 + a3, -d4 - d6, d1 - d5),
        }
    }

    /// A PUMA-like arm at q = 0 (shoulder offset, elbow offset): spherical, orthogonal wrist.
    pub(crate) fn puma() -> Geometry<6> {
        let (a2, a3, d3, d4) = (0.4318, 0.0203, 0.15005, 0.4318);
        let (z, y) = (V3::z(), V3::y());
        Geometry {
            h: [z, y, y, z, y, z],
            p: [
                V3::zeros(),
                V3::zeros(),
                V3::new(a2, d3, 0.0),
                V3::new(a2 + a3, d3, d4),
                V3::new(a2 + a3, d3, d4),
                V3::new(a2 + a3, d3, d4),
            ],
            prismatic: [false; 6],
            r_tool: M3::identity(),
            p_tool: V3::new(a2 + a3, d3, d4),
        }
    }

    /// The KUKA iiwa 14 (DH numbers) with joint 3 locked at 0.5 rad: the shoulder's axes
    /// meet, an elbow, a spherical orthogonal wrist.
    pub(crate) fn iiwa_locked() -> Geometry<6> {
        let (d1, d3, d5, d7) = (0.36, 0.42, 0.4, 0.126);
        let (z, y) = (V3::z(), V3::y());
        let turned = rot(&z, 0.5);
        let w = V3::new(0.0, 0.0, d1 + d3 + d5);
        Geometry {
            h: [z, y, -(turned * y), z, turned * y, z],
            p: [
                V3::zeros(),
                V3::new(0.0, 0.0, d1),
                V3::new(0.0, 0.0, d1 + d3),
                w,
                w,
                w,
            ],
            prismatic: [false; 6],
            r_tool: turned,
            p_tool: w + z * d7,
        }
    }

    /// Six axes in general position (no two parallel, none meeting).
    pub(crate) fn general_6r() -> Geometry<6> {
        let unit = |x: f64, y: f64, z: f64| V3::new(x, y, z).normalize();
        Geometry {
            h: [
                unit(0.0, 0.0, 1.0),
                unit(0.1, 1.0, 0.2),
                unit(0.3, 0.9, -0.1),
                unit(1.0, 0.2, 0.1),
                unit(0.2, 1.0, -0.3),
                unit(0.9, 0.1, 0.4),
            ],
            p: [
                V3::zeros(),
                V3::new(0.05, 0.0, 0.3),
                V3::new(0.4, 0.1, 0.35),
                V3::new(0.5, 0.05, 0.6),
                V3::new(0.7, 0.12, 0.55),
                V3::new(0.8, 0.0, 0.6),
            ],
            prismatic: [false; 6],
            r_tool: M3::identity(),
            p_tool: V3::new(0.9, 0.0, 0.65),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rot_sc_is_rodrigues() {
        let k = V3::new(1.0, 2.0, 2.0) / 3.0;
        let r = rot(&k, 0.7);
        assert!((r * k - k).norm() < 1e-15);
        assert!((r.determinant() - 1.0).abs() < 1e-14);
        let x = V3::new(0.3, -0.2, 0.5);
        let expected =
            x * 0.7f64.cos() + k.cross(&x) * 0.7f64.sin() + k * k.dot(&x) * (1.0 - 0.7f64.cos());
        assert!((r * x - expected).norm() < 1e-15);
    }

    #[test]
    fn a_pose_with_any_entry_not_finite_is_not_finite() {
        let pose = Pose::from_matrix(&[
            [1.0, -0.0, 1e308, 2.0],
            [-1e308, 1.0, 0.0, -3.0],
            [0.0, 5e-324, 1.0, 0.5],
            [0.0, 0.0, 0.0, 1.0],
        ]);
        assert!(pose.is_finite());
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            for k in 0..12 {
                let mut p = pose;
                if k < 9 {
                    p.r[(k / 3, k % 3)] = bad;
                } else {
                    p.p[k - 9] = bad;
                }
                assert!(!p.is_finite(), "{bad} at {k}");
            }
        }
    }

    #[test]
    fn axes_meet_at_a_point_on_both() {
        let mut g = Geometry::<2> {
            h: [V3::z(), V3::x()],
            p: [V3::new(1.0, 2.0, 5.0), V3::new(4.0, 2.0, 3.0)],
            prismatic: [false; 2],
            r_tool: M3::identity(),
            p_tool: V3::zeros(),
        };
        // Axis 0 is the line x = 1, y = 2; axis 1 the line y = 2, z = 3: they meet at
        // (1, 2, 3), which neither point is (the closest-points solve finds it).
        let want = V3::new(1.0, 2.0, 3.0);
        assert!((meet(&g, 0, 1) - want).norm() < 1e-15);
        // A point already at the meeting point is taken as it is, either way round.
        g.p[1] = want;
        assert_eq!(meet(&g, 0, 1), want);
        assert_eq!(meet(&g, 1, 0), want);
    }

    #[test]
    fn an_orbit_turns_like_the_rotation() {
        let k = V3::new(0.3, -0.2, 0.9).normalize();
        let p = V3::new(0.4, 0.1, -0.7);
        let orbit = Orbit::new(&k, &p);
        for theta in [0.0, 0.7, -2.9, 3.1] {
            let t = Angle::new(theta);
            assert!((orbit.at(&t) - rot(&k, theta) * p).norm() < 1e-15);
            assert!((orbit.back(&t) - rot(&k, -theta) * p).norm() < 1e-15);
        }
    }

    #[test]
    fn closest_points_of_skew_and_parallel_lines() {
        let (p, q) = closest_points(
            &V3::zeros(),
            &V3::x(),
            &V3::new(0.0, 1.0, 2.0),
            &V3::z(),
            1e-20,
        )
        .unwrap();
        assert!((p - V3::zeros()).norm() < 1e-15 && (q - V3::new(0.0, 1.0, 0.0)).norm() < 1e-15);
        assert!(closest_points(&V3::zeros(), &V3::x(), &V3::y(), &V3::x(), 1e-20).is_none());
    }
}
