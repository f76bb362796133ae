//! The origins of the frames along the chain at a configuration: the points a stick
//! figure joins. Computed from the chain's elementary transforms (the same chain the
//! formulas come from); the last point is the tool point of `fk`.

use kinegen_core::chain::{Axis, Elem};
use kinegen_core::model::robot::JointKind;
use kinegen_core::numeric::{rot_x, rot_y, rot_z, trans};
use kinegen_core::Chain;
use nalgebra::Matrix4;

fn rotation(axis: Axis, angle: f64) -> Matrix4<f64> {
    match axis {
        Axis::X => rot_x(angle),
        Axis::Y => rot_y(angle),
        Axis::Z => rot_z(angle),
    }
}

fn translation(axis: Axis, d: f64) -> Matrix4<f64> {
    let mut v = [0.0; 3];
    v[axis.index()] = d;
    trans(v[0], v[1], v[2])
}

fn elem(chain: &Chain, e: &Elem) -> Matrix4<f64> {
    match e {
        Elem::Rot(a, v) => rotation(*a, chain.eval(v)),
        Elem::Trans(a, v) => translation(*a, chain.eval(v)),
    }
}

/// World positions of the base, of every link frame after its joint, and of the tool
/// point, at `q` (one value per joint).
pub fn origins(chain: &Chain, q: &[f64]) -> Vec<[f64; 3]> {
    let mut t = Matrix4::identity();
    let origin = |t: &Matrix4<f64>| [t[(0, 3)], t[(1, 3)], t[(2, 3)]];
    let mut out = vec![origin(&t)];
    for e in &chain.base {
        t *= elem(chain, e);
    }
    out.push(origin(&t));
    for (link, &qi) in chain.links.iter().zip(q) {
        for e in &link.before {
            t *= elem(chain, e);
        }
        let m = &link.motion;
        let x = f64::from(m.sign) * qi + chain.eval(&m.offset);
        t *= match m.kind {
            JointKind::Revolute => rotation(m.axis, x),
            JointKind::Prismatic => translation(m.axis, x),
        };
        for e in &link.after {
            t *= elem(chain, e);
        }
        out.push(origin(&t));
    }
    for e in &chain.tool {
        t *= elem(chain, e);
    }
    out.push(origin(&t));
    // Frames at the same place (a DH offset of zero) draw nothing: keep one.
    out.dedup_by(|a, b| (0..3).all(|k| (a[k] - b[k]).abs() < 1e-12));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The last origin is where the engine's own `fk` puts the tool.
    #[test]
    fn the_last_point_is_the_tool_point_of_fk() {
        for name in ["ur5", "puma560", "panda", "stanford"] {
            let (chain, options) =
                crate::robots::load(name, &crate::robots::UrdfArgs::default()).unwrap();
            let derived = kinegen_core::derive(&chain, &options);
            let q: Vec<f64> = (0..chain.dof()).map(|i| 0.3 + 0.2 * i as f64).collect();
            let ids: Vec<_> = derived.model.fk_rows.iter().flatten().copied().collect();
            let fk = derived.model.eval(&chain, &q, &ids);
            let p = *origins(&chain, &q).last().unwrap();
            for k in 0..3 {
                assert!(
                    (p[k] - fk[4 * k + 3]).abs() < 1e-12,
                    "{name}: {p:?} vs {fk:?}"
                );
            }
        }
    }
}
