//! Numbers in lanes: the `L` branches of one level of a closed-form solve side by side,
//! each operation once for all of them. Every operation is a loop over a fixed-size
//! array, which the compiler turns into vector instructions where the target has vector
//! registers for `f64` (two lanes per SSE2 register on x86_64), and into plain scalar
//! code elsewhere (a Cortex-M). Lane `i` of every result is the scalar operation on lane
//! `i` of the operands, bit for bit.
//!
//! The operations (and the solvers built from them, `ik::regular`) are inlined always
//! where that gives vector code (x86_64, aarch64), and left to the compiler elsewhere: on
//! a Cortex-M4F, whose `f64` arithmetic is library calls, inlining every lane operation
//! cost 12 KB more flash for no speed.
//!
//! ```
//! use kinegen::ik::lanes::Lanes;
//! let a = Lanes([1.0, 2.0]);
//! let b = Lanes([0.5, -1.0]);
//! assert_eq!((a * b + a).0, [1.5, 0.0]);
//! assert_eq!(a.twice::<4>().0, [1.0, 1.0, 2.0, 2.0]);
//! ```

use core::ops::{Add, Div, Mul, Neg, Sub};
use nalgebra::{Matrix3, Vector3};

/// `L` numbers, one per branch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lanes<const L: usize>(pub [f64; L]);

impl<const L: usize> Lanes<L> {
    /// `x` in every lane.
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn splat(x: f64) -> Self {
        Lanes([x; L])
    }

    /// `f` of every lane.
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn map(self, f: impl Fn(f64) -> f64) -> Self {
        let mut r = self.0;
        for x in &mut r {
            *x = f(*x);
        }
        Lanes(r)
    }

    /// `√x` of every lane.
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn sqrt(self) -> Self {
        self.map(crate::math::sqrt)
    }

    /// Each lane twice, for the next level of branches (every branch splits in two):
    /// lanes `2i` and `2i + 1` of the result are lane `i`. `M` must be `2 L`.
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn twice<const M: usize>(self) -> Lanes<M> {
        debug_assert!(M == 2 * L);
        let mut r = [0.0; M];
        for (j, x) in r.iter_mut().enumerate() {
            *x = self.0[j / 2];
        }
        Lanes(r)
    }

    /// The two branches of every lane, interleaved: lane `2i` of the result is lane `i`
    /// of `first`, lane `2i + 1` lane `i` of `second`. `M` must be `2 L`.
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn interleave<const M: usize>(first: Self, second: Self) -> Lanes<M> {
        debug_assert!(M == 2 * L);
        let mut r = [0.0; M];
        for i in 0..L {
            r[2 * i] = first.0[i];
            r[2 * i + 1] = second.0[i];
        }
        Lanes(r)
    }
}

macro_rules! lane_op {
    ($trait:ident, $f:ident, $op:tt) => {
        impl<const L: usize> $trait for Lanes<L> {
            type Output = Lanes<L>;
            #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
            fn $f(self, other: Lanes<L>) -> Lanes<L> {
                let mut r = self.0;
                for i in 0..L {
                    r[i] $op other.0[i];
                }
                Lanes(r)
            }
        }
        impl<const L: usize> $trait<f64> for Lanes<L> {
            type Output = Lanes<L>;
            #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
            fn $f(self, other: f64) -> Lanes<L> {
                let mut r = self.0;
                for x in &mut r {
                    *x $op other;
                }
                Lanes(r)
            }
        }
    };
}

lane_op!(Add, add, +=);
lane_op!(Sub, sub, -=);
lane_op!(Mul, mul, *=);
lane_op!(Div, div, /=);

impl<const L: usize> Neg for Lanes<L> {
    type Output = Lanes<L>;
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    fn neg(self) -> Lanes<L> {
        self.map(|x| -x)
    }
}

/// `L` 3-vectors, coordinate by coordinate (lane `i` of `x`, `y`, `z` is vector `i`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vectors<const L: usize> {
    /// First coordinates.
    pub x: Lanes<L>,
    /// Second coordinates.
    pub y: Lanes<L>,
    /// Third coordinates.
    pub z: Lanes<L>,
}

impl<const L: usize> Vectors<L> {
    /// `v` in every lane.
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn splat(v: &Vector3<f64>) -> Self {
        Vectors {
            x: Lanes::splat(v.x),
            y: Lanes::splat(v.y),
            z: Lanes::splat(v.z),
        }
    }

    /// `a + c u + s w` lane by lane: a point of the circle through `a + u` about an axis
    /// `k` (with `u ⟂ k`, `w = k × u`) at the angle whose cosine is `c` and sine `s`.
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn circle(
        a: &Vector3<f64>,
        u: &Vector3<f64>,
        w: &Vector3<f64>,
        c: Lanes<L>,
        s: Lanes<L>,
    ) -> Self {
        Vectors {
            x: c * u.x + s * w.x + a.x,
            y: c * u.y + s * w.y + a.y,
            z: c * u.z + s * w.z + a.z,
        }
    }

    /// `self · v` for a fixed `v`.
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn dot_fixed(&self, v: &Vector3<f64>) -> Lanes<L> {
        self.x * v.x + self.y * v.y + self.z * v.z
    }

    /// `self · other`, lane by lane.
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn dot(&self, other: &Vectors<L>) -> Lanes<L> {
        self.x * other.x + self.y * other.y + self.z * other.z
    }

    /// `self × other`, lane by lane.
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn cross(&self, other: &Vectors<L>) -> Vectors<L> {
        Vectors {
            x: self.y * other.z - self.z * other.y,
            y: self.z * other.x - self.x * other.z,
            z: self.x * other.y - self.y * other.x,
        }
    }

    /// `self − k (k · self)` for a fixed unit `k`: the part off the axis `k`.
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn off_axis(&self, k: &Vector3<f64>) -> Vectors<L> {
        let along = self.dot_fixed(k);
        Vectors {
            x: self.x - along * k.x,
            y: self.y - along * k.y,
            z: self.z - along * k.z,
        }
    }

    /// `m v` for a fixed matrix `m`.
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn mul_by(&self, m: &Matrix3<f64>) -> Vectors<L> {
        let row = |i: usize| self.x * m[(i, 0)] + self.y * m[(i, 1)] + self.z * m[(i, 2)];
        Vectors {
            x: row(0),
            y: row(1),
            z: row(2),
        }
    }

    /// `mᵀ v` for a fixed matrix `m`.
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn tr_mul_by(&self, m: &Matrix3<f64>) -> Vectors<L> {
        let col = |j: usize| self.x * m[(0, j)] + self.y * m[(1, j)] + self.z * m[(2, j)];
        Vectors {
            x: col(0),
            y: col(1),
            z: col(2),
        }
    }

    /// Each vector twice (see [`Lanes::twice`]).
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    pub fn twice<const M: usize>(&self) -> Vectors<M> {
        Vectors {
            x: self.x.twice(),
            y: self.y.twice(),
            z: self.z.twice(),
        }
    }
}

impl<const L: usize> Add for Vectors<L> {
    type Output = Vectors<L>;
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    fn add(self, o: Vectors<L>) -> Vectors<L> {
        Vectors {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }
}

impl<const L: usize> Sub for Vectors<L> {
    type Output = Vectors<L>;
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    fn sub(self, o: Vectors<L>) -> Vectors<L> {
        Vectors {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }
}

impl<const L: usize> Mul<Lanes<L>> for Vectors<L> {
    type Output = Vectors<L>;
    #[cfg_attr(any(target_arch = "x86_64", target_arch = "aarch64"), inline(always))]
    fn mul(self, s: Lanes<L>) -> Vectors<L> {
        Vectors {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }
}
