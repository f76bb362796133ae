//! Step 4's eigenvalues: every eigenvalue of a real square matrix, and nothing else, by
//! Francis's implicit double-shift QR on its Hessenberg form (Golub and Van Loan,
//! *Matrix Computations*, algorithms 7.4.2 and 7.5.2; Wilkinson and Reinsch's `hqr`).
//!
//! In place, on the one matrix: a Householder reduction to upper Hessenberg form, then
//! QR sweeps on the active block only, each deflating where a subdiagonal entry falls
//! below rounding of its neighbours, with Wilkinson's exceptional shifts after 10 and 20
//! sweeps without deflation. No Schur vectors are formed: the eigenvalues are all the
//! general 6R needs (the null vectors come from `M(x)` itself), and leaving `Q` out
//! halves the work and keeps the stack at one matrix — a general-purpose Schur
//! decomposition on the 24 × 24 companion matrix held a dozen copies of it (63 KB of
//! stack on the Cortex-M4F). The number of sweeps is bounded: an input they do not
//! converge on gives `None`, never a hang.

use crate::math::{abs, sqrt};

/// The eigenvalues `(re, im)` of `a` (destroyed), complex pairs adjacent with `im` of
/// opposite signs; `None` if `sweeps` double-shift sweeps did not deflate them all (or an
/// entry is not finite).
pub(super) fn eigenvalues<const N: usize>(
    a: &mut [[f64; N]; N],
    sweeps: usize,
) -> Option<[(f64, f64); N]> {
    if a.iter().flatten().any(|x| !x.is_finite()) {
        return None;
    }
    hessenberg(a);
    francis(a, sweeps)
}

/// `a` to upper Hessenberg form by Householder reflections `P a P` (similar: the same
/// eigenvalues), column by column; the entries below the subdiagonal set to zero.
// A column's entries across rows: indices read plainer than zipped row iterators.
#[allow(clippy::needless_range_loop)]
fn hessenberg<const N: usize>(a: &mut [[f64; N]; N]) {
    for k in 0..N.saturating_sub(2) {
        // The reflection taking a[k+1.., k] onto a multiple of e1, scaled against
        // overflow.
        let scale: f64 = (k + 1..N).map(|i| abs(a[i][k])).sum();
        if scale == 0.0 {
            continue;
        }
        let mut v = [0.0; N];
        let mut norm2 = 0.0;
        for i in k + 1..N {
            v[i] = a[i][k] / scale;
            norm2 += v[i] * v[i];
        }
        let alpha = if v[k + 1] >= 0.0 {
            -sqrt(norm2)
        } else {
            sqrt(norm2)
        };
        // v = x − α e1; P = I − 2 v vᵀ / vᵀv, and vᵀv = 2 (‖x‖² − α x1).
        let vtv = 2.0 * (norm2 - alpha * v[k + 1]);
        v[k + 1] -= alpha;
        if vtv == 0.0 {
            continue;
        }
        let beta = 2.0 / vtv;
        // From the left: rows k+1.., columns k..; `s = β vᵀ a` gathered row by row, so
        // that both loops run along rows.
        let mut s = [0.0; N];
        for (vi, row) in v[k + 1..].iter().zip(&a[k + 1..]) {
            for (sj, x) in s[k..].iter_mut().zip(&row[k..]) {
                *sj += vi * x;
            }
        }
        for (vi, row) in v[k + 1..].iter().zip(&mut a[k + 1..]) {
            let f = beta * vi;
            for (x, sj) in row[k..].iter_mut().zip(&s[k..]) {
                *x -= f * sj;
            }
        }
        // From the right: every row, columns k+1...
        let v = &v[k + 1..];
        for row in a.iter_mut() {
            let row = &mut row[k + 1..];
            let s: f64 = row.iter().zip(v).map(|(x, vj)| x * vj).sum::<f64>() * beta;
            for (x, vj) in row.iter_mut().zip(v) {
                *x -= s * vj;
            }
        }
        a[k + 1][k] = alpha * scale;
        for row in a.iter_mut().skip(k + 2) {
            row[k] = 0.0;
        }
    }
}

/// The eigenvalues of the upper Hessenberg `a` by implicit double-shift QR sweeps on its
/// active block `l..=nn`, deflating one real eigenvalue or a 2 × 2 block at its bottom.
fn francis<const N: usize>(a: &mut [[f64; N]; N], sweeps: usize) -> Option<[(f64, f64); N]> {
    let mut out = [(0.0, 0.0); N];
    // The size of the matrix, for a subdiagonal entry between two zero diagonal ones.
    let norm: f64 = (0..N)
        .flat_map(|i| (i.saturating_sub(1)..N).map(move |j| (i, j)))
        .map(|(i, j)| abs(a[i][j]))
        .sum();
    let mut left = sweeps;
    // The exceptional shifts' total, taken off the diagonal and added back to the values.
    let mut shift = 0.0;
    let mut nn = N;
    while nn > 0 {
        let n = nn - 1; // the active block's last row
        let mut its = 0;
        loop {
            // The lowest negligible subdiagonal entry splits off the block l..=n.
            let mut l = n;
            while l > 0 {
                let mut s = abs(a[l - 1][l - 1]) + abs(a[l][l]);
                if s == 0.0 {
                    s = norm;
                }
                if abs(a[l][l - 1]) <= f64::EPSILON * s {
                    a[l][l - 1] = 0.0;
                    break;
                }
                l -= 1;
            }
            let mut x = a[n][n];
            if l == n {
                // A 1 × 1 block: a real eigenvalue.
                out[n] = (x + shift, 0.0);
                nn -= 1;
                break;
            }
            let mut y = a[n - 1][n - 1];
            let mut w = a[n][n - 1] * a[n - 1][n];
            if l + 1 == n {
                // A 2 × 2 block: two real eigenvalues or a complex pair.
                let p = 0.5 * (y - x);
                let q = p * p + w;
                let z = sqrt(abs(q));
                x += shift;
                out[n - 1] = if q >= 0.0 {
                    // The root of larger size first, the other from their product
                    // (no cancellation).
                    let z = p + if p >= 0.0 { z } else { -z };
                    let big = x + z;
                    out[n] = (if z != 0.0 { x - w / z } else { big }, 0.0);
                    (big, 0.0)
                } else {
                    out[n] = (x + p, z);
                    (x + p, -z)
                };
                nn -= 2;
                break;
            }
            if left == 0 {
                return None;
            }
            left -= 1;
            if its == 10 || its == 20 {
                // Exceptional shift: a sweep with shifts from the bottom entries' sizes
                // breaks a cycle the Francis shifts can fall into.
                shift += x;
                for (i, row) in a.iter_mut().enumerate().take(n + 1) {
                    row[i] -= x;
                }
                let s = abs(a[n][n - 1]) + abs(a[n - 1][n - 2]);
                x = 0.75 * s;
                y = x;
                w = -0.4375 * s * s;
            }
            its += 1;
            sweep(a, l, n, x, y, w);
        }
    }
    Some(out)
}

/// One implicit double-shift QR sweep on rows and columns `l..=n` of the Hessenberg `a`,
/// with the shifts the eigenvalues of `[[y, ·], [·, x]]` (`w` the product of the
/// off-diagonal pair), started at the lowest row `m` where two consecutive subdiagonal
/// entries are small enough for the bulge to start there.
#[allow(clippy::needless_range_loop)]
fn sweep<const N: usize>(a: &mut [[f64; N]; N], l: usize, n: usize, x: f64, y: f64, w: f64) {
    // The first column of (H − s1)(H − s2), scaled: (p, q, r).
    let (mut p, mut q, mut r);
    let mut m = n - 2;
    loop {
        let z = a[m][m];
        let (rr, ss) = (x - z, y - z);
        p = (rr * ss - w) / a[m + 1][m] + a[m][m + 1];
        q = a[m + 1][m + 1] - z - rr - ss;
        r = a[m + 2][m + 1];
        let s = abs(p) + abs(q) + abs(r);
        (p, q, r) = (p / s, q / s, r / s);
        if m == l {
            break;
        }
        let u = abs(a[m][m - 1]) * (abs(q) + abs(r));
        let v = abs(p) * (abs(a[m - 1][m - 1]) + abs(z) + abs(a[m + 1][m + 1]));
        if u <= f64::EPSILON * v {
            break;
        }
        m -= 1;
    }
    for i in m + 2..=n {
        a[i][i - 2] = 0.0;
        if i != m + 2 {
            a[i][i - 3] = 0.0;
        }
    }
    // Chase the bulge down: a 3 × 3 reflection per column (2 × 2 at the last).
    for k in m..n {
        let last = k + 1 == n;
        let mut scale = 1.0;
        if k != m {
            p = a[k][k - 1];
            q = a[k + 1][k - 1];
            r = if last { 0.0 } else { a[k + 2][k - 1] };
            scale = abs(p) + abs(q) + abs(r);
            if scale == 0.0 {
                continue;
            }
            (p, q, r) = (p / scale, q / scale, r / scale);
        }
        let norm = sqrt(p * p + q * q + r * r);
        let s = if p >= 0.0 { norm } else { -norm };
        if s == 0.0 {
            continue;
        }
        if k == m {
            if l != m {
                a[k][k - 1] = -a[k][k - 1];
            }
        } else {
            a[k][k - 1] = -s * scale;
        }
        p += s;
        let (x, y, z) = (p / s, q / s, r / s);
        let (q, r) = (q / p, r / p);
        // From the left: rows k..k+2, columns k..=n (the last step: two rows).
        let (top, below) = a.split_at_mut(k + 1);
        let r0 = &mut top[k][k..=n];
        if last {
            let r1 = &mut below[0][k..=n];
            for (a0, a1) in r0.iter_mut().zip(r1.iter_mut()) {
                let t = *a0 + q * *a1;
                *a1 -= t * y;
                *a0 -= t * x;
            }
        } else {
            let (r1, r2) = below.split_at_mut(1);
            let (r1, r2) = (&mut r1[0][k..=n], &mut r2[0][k..=n]);
            for ((a0, a1), a2) in r0.iter_mut().zip(r1.iter_mut()).zip(r2.iter_mut()) {
                let t = *a0 + q * *a1 + r * *a2;
                *a2 -= t * z;
                *a1 -= t * y;
                *a0 -= t * x;
            }
        }
        // From the right: rows l..=min(n, k+3), columns k..k+2.
        let rows = &mut a[l..=n.min(k + 3)];
        if last {
            for row in rows {
                let c = &mut row[k..k + 2];
                let t = x * c[0] + y * c[1];
                c[1] -= t * q;
                c[0] -= t;
            }
        } else {
            for row in rows {
                let c = &mut row[k..k + 3];
                let t = x * c[0] + y * c[1] + z * c[2];
                c[2] -= t * r;
                c[1] -= t * q;
                c[0] -= t;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ik::XorShift64;
    use nalgebra::SMatrix;

    /// Sorted by real part, then imaginary.
    fn sorted<const N: usize>(mut v: [(f64, f64); N]) -> [(f64, f64); N] {
        v.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
        v
    }

    /// Against nalgebra's Schur form on random matrices (entries in ±1, some with a
    /// complex pair forced by a rotation block, some with large and small scales).
    #[test]
    fn matches_a_schur_decomposition() {
        let mut rng = XorShift64::new(24);
        for case in 0..200 {
            let mut a = [[0.0; 24]; 24];
            for row in a.iter_mut() {
                for x in row.iter_mut() {
                    *x = 2.0 * rng.next_f64() - 1.0;
                    if case % 3 == 2 {
                        *x *= 10f64.powi((rng.next_u64() % 7) as i32 - 3);
                    }
                }
            }
            let m = SMatrix::<f64, 24, 24>::from_fn(|i, j| a[i][j]);
            let want = m.schur().complex_eigenvalues().map(|z| (z.re, z.im));
            let want: [(f64, f64); 24] = core::array::from_fn(|i| want[i]);
            let got = eigenvalues(&mut a, 720).expect("converges");
            let size = want.iter().map(|z| z.0.hypot(z.1)).fold(0.0, f64::max);
            for (g, w) in sorted(got).iter().zip(sorted(want)) {
                let d = (g.0 - w.0).hypot(g.1 - w.1);
                assert!(d <= 1e-9 * size, "case {case}: {g:?} against {w:?}");
            }
        }
    }

    /// Known spectra: a diagonal matrix, a rotation block's ±i, a companion matrix of
    /// (x − 1)(x − 2)(x − 3)(x² + 1), a zero matrix, a Jordan block (a quadruple root,
    /// split by rounding to ~ε^(1/4)).
    #[test]
    fn known_spectra() {
        let mut d = [[0.0; 4]; 4];
        for (i, row) in d.iter_mut().enumerate() {
            row[i] = [3.0, -1.0, 0.5, 7.0][i];
        }
        let got = sorted(eigenvalues(&mut d, 100).unwrap());
        assert_eq!(got, [(-1.0, 0.0), (0.5, 0.0), (3.0, 0.0), (7.0, 0.0)]);

        let mut r = [[0.0, -1.0], [1.0, 0.0]];
        let got = sorted(eigenvalues(&mut r, 100).unwrap());
        assert_eq!(got, [(0.0, -1.0), (0.0, 1.0)]);

        // x⁵ − 6x⁴ + 12x³ − 12x² + 11x − 6 = (x − 1)(x − 2)(x − 3)(x² + 1).
        let c = [6.0, -12.0, 12.0, -11.0, 6.0];
        let mut comp = [[0.0; 5]; 5];
        comp[0] = c;
        for i in 1..5 {
            comp[i][i - 1] = 1.0;
        }
        let got = sorted(eigenvalues(&mut comp, 100).unwrap());
        let want = [(0.0, -1.0), (0.0, 1.0), (1.0, 0.0), (2.0, 0.0), (3.0, 0.0)];
        for (g, w) in got.iter().zip(want) {
            assert!(
                (g.0 - w.0).abs() <= 1e-12 && (g.1 - w.1).abs() <= 1e-12,
                "{got:?}"
            );
        }

        let mut z = [[0.0; 6]; 6];
        assert_eq!(eigenvalues(&mut z, 100).unwrap(), [(0.0, 0.0); 6]);

        let mut j = [[0.0; 4]; 4];
        for i in 0..4 {
            j[i][i] = 2.0;
            if i < 3 {
                j[i][i + 1] = 1.0;
            }
        }
        j[3][0] = 1e-16;
        for (re, im) in eigenvalues(&mut j, 100).unwrap() {
            assert!((re - 2.0).hypot(im) <= 1e-3, "{re} {im}");
        }
    }

    /// Not finite, or no sweeps allowed where one is needed: `None`, at once.
    #[test]
    fn bounded() {
        let mut a = [[1.0, f64::NAN], [0.0, 1.0]];
        assert!(eigenvalues(&mut a, 100).is_none());
        let mut rng = XorShift64::new(7);
        let mut b = [[0.0; 8]; 8];
        for x in b.iter_mut().flatten() {
            *x = rng.next_f64() - 0.5;
        }
        assert!(eigenvalues(&mut b, 0).is_none());
        assert!(eigenvalues(&mut b.clone(), 1000).is_some());
    }
}
