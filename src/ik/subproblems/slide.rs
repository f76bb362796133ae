//! **The slide to a distance** — `q` with `‖u + q h‖ = d`: where the line through `u`
//! along the unit `h` meets the sphere of radius `d` about the origin. A prismatic joint
//! between two revolute ones that meet (the Stanford arm's joint 3) comes down to it: the
//! revolute joints keep the distance from their meeting point.

use super::{Fit, EPS, ROOT_MERGE};
use crate::ik::geometry::V3;

/// **The slide to a distance** — `q` with `‖u + q h‖ = d` (unit `h`): `q² + 2 b q + c = 0`
/// with `b = h·u`, `c = ‖u‖² − d²`. Two roots `−b ± √(b² − c)`, a double root when the
/// discriminant is within [`ROOT_MERGE`] rounding errors of zero (the line touches the
/// sphere), or least squares `−b` (the nearest point of the line to the sphere) when it
/// misses. Returns the roots, how many are used, and the fit.
pub fn slide(u: &V3, h: &V3, d: f64) -> ([f64; 2], usize, Fit) {
    let b = h.dot(u);
    let (uu, dd) = (u.norm_squared(), d * d);
    let disc = b * b - (uu - dd);
    let merge = ROOT_MERGE * EPS * (b * b + uu + dd);
    if disc.abs() <= merge {
        ([-b, -b], 1, Fit::Double)
    } else if disc < 0.0 {
        ([-b, -b], 1, Fit::LeastSquares)
    } else {
        let s = crate::math::sqrt(disc);
        ([-b + s, -b - s], 2, Fit::Exact)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_roots_reach_the_distance_and_a_tangent_line_is_double() {
        let (u, h) = (V3::new(0.3, -0.2, 0.5), V3::new(1.0, 2.0, -2.0) / 3.0);
        let (roots, n, fit) = slide(&u, &h, 1.3);
        assert_eq!((n, fit), (2, Fit::Exact));
        for q in roots {
            assert!(((u + h * q).norm() - 1.3).abs() < 1e-15);
        }
        // The line's nearest point to the origin is at distance ‖u − (h·u) h‖.
        let near = (u - h * h.dot(&u)).norm();
        assert_eq!(slide(&u, &h, near).2, Fit::Double);
        assert_eq!(slide(&u, &h, 0.5 * near).2, Fit::LeastSquares);
    }
}
