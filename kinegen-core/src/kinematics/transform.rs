//! Symbolic rigid transforms and vectors as graph nodes: products, rotations, cross
//! products (zeros and ones fold away in the graph).

use crate::algebra::graph::{Graph, Id};

/// A symbolic rigid transform: rotation as three columns, and the origin.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Transform {
    /// `cols[j][i]` is `R[i][j]`.
    pub cols: [[Id; 3]; 3],
    /// Origin.
    pub p: [Id; 3],
}

impl Transform {
    /// The identity.
    pub fn identity(g: &mut Graph) -> Self {
        let (o, l) = (g.int(0), g.int(1));
        Transform {
            cols: [[l, o, o], [o, l, o], [o, o, l]],
            p: [o, o, o],
        }
    }

    /// `R[i][j]`.
    pub fn r(&self, i: usize, j: usize) -> Id {
        self.cols[j][i]
    }

    /// The z axis (third column).
    pub fn z(&self) -> [Id; 3] {
        self.cols[2]
    }

    /// Rows `[R | p]`, row-major: the top three rows of the homogeneous matrix.
    pub fn rows(&self) -> [[Id; 4]; 3] {
        let mut r = [[0; 4]; 3];
        for (i, row) in r.iter_mut().enumerate() {
            for (j, e) in row.iter_mut().take(3).enumerate() {
                *e = self.r(i, j);
            }
            row[3] = self.p[i];
        }
        r
    }
}

/// `R · v` for the rotation of `w`.
pub fn rotate(g: &mut Graph, w: &Transform, v: [Id; 3]) -> [Id; 3] {
    let mut out = [0; 3];
    for (i, o) in out.iter_mut().enumerate() {
        let terms: Vec<Id> = (0..3).map(|m| g.mul(w.cols[m][i], v[m])).collect();
        *o = g.sum(&terms);
    }
    out
}

/// `R · v + p` for `w = [R | p]`.
pub fn point(g: &mut Graph, w: &Transform, v: [Id; 3]) -> [Id; 3] {
    let r = rotate(g, w, v);
    [
        g.add(w.p[0], r[0]),
        g.add(w.p[1], r[1]),
        g.add(w.p[2], r[2]),
    ]
}

/// `w · t`.
pub fn compose(g: &mut Graph, w: &Transform, t: &Transform) -> Transform {
    Transform {
        cols: [
            rotate(g, w, t.cols[0]),
            rotate(g, w, t.cols[1]),
            rotate(g, w, t.cols[2]),
        ],
        p: point(g, w, t.p),
    }
}

/// `t · Trans(axis, d)`: the origin moves by `d` along column `axis`.
pub fn translate(g: &mut Graph, t: &Transform, axis: usize, d: Id) -> Transform {
    let mut out = *t;
    for i in 0..3 {
        let m = g.mul(d, t.cols[axis][i]);
        out.p[i] = g.add(t.p[i], m);
    }
    out
}

/// `t · Rot(axis)` for a rotation with sine `s` and cosine `c`.
pub fn turn(g: &mut Graph, t: &Transform, axis: usize, s: Id, c: Id) -> Transform {
    // Right-multiplying by a rotation about `axis` mixes the other two columns (u, v)
    // cyclically: u' = c·u + s·v, v' = −s·u + c·v.
    let mut out = *t;
    let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
    for i in 0..3 {
        let (cu, cv) = (t.cols[u][i], t.cols[v][i]);
        let a = g.mul(c, cu);
        let b = g.mul(s, cv);
        out.cols[u][i] = g.add(a, b);
        let a = g.mul(s, cu);
        let b = g.mul(c, cv);
        out.cols[v][i] = g.sub(b, a);
    }
    out
}

/// `a + b`.
pub fn add(g: &mut Graph, a: [Id; 3], b: [Id; 3]) -> [Id; 3] {
    [g.add(a[0], b[0]), g.add(a[1], b[1]), g.add(a[2], b[2])]
}

/// `k · v` for a scalar node `k`.
pub fn scale(g: &mut Graph, k: Id, v: [Id; 3]) -> [Id; 3] {
    [g.mul(k, v[0]), g.mul(k, v[1]), g.mul(k, v[2])]
}

/// `a × b`.
pub fn cross(g: &mut Graph, a: [Id; 3], b: [Id; 3]) -> [Id; 3] {
    let mut out = [0; 3];
    for (i, o) in out.iter_mut().enumerate() {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let x = g.mul(a[j], b[k]);
        let y = g.mul(a[k], b[j]);
        *o = g.sub(x, y);
    }
    out
}
