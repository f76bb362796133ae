//! Robots generated from URDF files against a numeric URDF evaluator written here from
//! the specification (it reads the XML itself and shares no code with kinegen's URDF
//! reader or chain builder): 200 configurations per robot, fixed seed.
//!
//! - With `snap: 0` the generated code reads every decimal as written, so FK and the
//!   Jacobian equal the evaluator's to 1e-9 (the Jacobian also against central finite
//!   differences of the evaluator's FK).
//! - With the default snap the code uses exact angles; it stays within the error bound
//!   the generated type reports for its snaps.
//! - The UR5 and Panda from their URDFs equal the DH robots (`Ur5`, `Panda`) to 1e-12.

use kinegen::Kinematics;
use kinegen_robots::{Panda, PandaUrdf, Ur5, Ur5Urdf};
use nalgebra::{Matrix3, Matrix4, Rotation3, Unit, Vector3};

/// A joint of the evaluator: origin, axis (unit), kind.
struct RefJoint {
    origin: Matrix4<f64>,
    axis: Vector3<f64>,
    kind: String,
}

fn floats(s: Option<&str>, default: [f64; 3]) -> [f64; 3] {
    match s {
        None => default,
        Some(s) => {
            let v: Vec<f64> = s.split_whitespace().map(|x| x.parse().unwrap()).collect();
            [v[0], v[1], v[2]]
        }
    }
}

/// The joints from `base` to `tip` of the URDF at `robots/<file>`, as the URDF spec reads
/// them: origin `Trans(xyz)·Rz(yaw)·Ry(pitch)·Rx(roll)`, axis normalised, default `1 0 0`.
fn reference_chain(file: &str, base: &str, tip: &str) -> Vec<RefJoint> {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(file);
    let src = std::fs::read_to_string(path).unwrap();
    let doc = roxmltree::Document::parse(&src).unwrap();
    let joints: Vec<roxmltree::Node> = doc
        .root_element()
        .children()
        .filter(|n| n.has_tag_name("joint"))
        .collect();
    let link_of = |j: &roxmltree::Node, role: &str| {
        j.children()
            .find(|c| c.has_tag_name(role))
            .and_then(|c| c.attribute("link"))
            .unwrap()
            .to_string()
    };
    let mut chain = Vec::new();
    let mut cur = tip.to_string();
    while cur != base {
        let j = joints.iter().find(|j| link_of(j, "child") == cur).unwrap();
        let origin = j.children().find(|c| c.has_tag_name("origin"));
        let xyz = floats(origin.and_then(|o| o.attribute("xyz")), [0.0; 3]);
        let rpy = floats(origin.and_then(|o| o.attribute("rpy")), [0.0; 3]);
        let axis = floats(
            j.children()
                .find(|c| c.has_tag_name("axis"))
                .and_then(|a| a.attribute("xyz")),
            [1.0, 0.0, 0.0],
        );
        let rot = Rotation3::from_axis_angle(&Vector3::z_axis(), rpy[2])
            * Rotation3::from_axis_angle(&Vector3::y_axis(), rpy[1])
            * Rotation3::from_axis_angle(&Vector3::x_axis(), rpy[0]);
        let mut m = Matrix4::identity();
        m.fixed_view_mut::<3, 3>(0, 0).copy_from(rot.matrix());
        m.fixed_view_mut::<3, 1>(0, 3)
            .copy_from(&Vector3::new(xyz[0], xyz[1], xyz[2]));
        chain.push(RefJoint {
            origin: m,
            axis: Vector3::new(axis[0], axis[1], axis[2]).normalize(),
            kind: j.attribute("type").unwrap().to_string(),
        });
        cur = link_of(j, "parent");
    }
    chain.reverse();
    chain
}

/// FK and the geometric Jacobian (world frame, `[v; ω]`) of the evaluator.
fn reference(chain: &[RefJoint], q: &[f64]) -> (Matrix4<f64>, Vec<[f64; 6]>) {
    let mut t = Matrix4::identity();
    let mut axes = Vec::new();
    let mut k = 0;
    for j in chain {
        t *= j.origin;
        if j.kind == "fixed" {
            continue;
        }
        let r: Matrix3<f64> = t.fixed_view::<3, 3>(0, 0).into_owned();
        let o: Vector3<f64> = t.fixed_view::<3, 1>(0, 3).into_owned();
        axes.push((j.kind.clone(), r * j.axis, o));
        let mut m = Matrix4::identity();
        if j.kind == "prismatic" {
            m.fixed_view_mut::<3, 1>(0, 3).copy_from(&(j.axis * q[k]));
        } else {
            let rot = Rotation3::from_axis_angle(&Unit::new_normalize(j.axis), q[k]);
            m.fixed_view_mut::<3, 3>(0, 0).copy_from(rot.matrix());
        }
        t *= m;
        k += 1;
    }
    let p: Vector3<f64> = t.fixed_view::<3, 1>(0, 3).into_owned();
    let cols = axes
        .into_iter()
        .map(|(kind, z, o)| {
            let (v, w) = if kind == "prismatic" {
                (z, Vector3::zeros())
            } else {
                (z.cross(&(p - o)), z)
            };
            [v.x, v.y, v.z, w.x, w.y, w.z]
        })
        .collect();
    (t, cols)
}

fn configurations<const N: usize>() -> Vec<[f64; N]> {
    kinegen_core::numeric::configurations(2718, 200, N)
        .into_iter()
        .map(|q| core::array::from_fn(|i| q[i]))
        .collect()
}

/// Generated code vs the evaluator at 200 configurations: FK and J within `tol` (plus
/// `bound_pos`/`bound_rot` for a snapped robot), J also against finite differences.
fn check<const N: usize, K: Kinematics<N>>(
    robot: &K,
    chain: &[RefJoint],
    tol: f64,
    (bound_pos, bound_rot): (f64, f64),
    prismatic: &[usize],
) {
    for mut q in configurations::<N>() {
        for &i in prismatic {
            q[i] = q[i].abs() / 20.0;
        }
        let (t_ref, j_ref) = reference(chain, &q);
        let t = robot.fk(&q);
        for r in 0..3 {
            for c in 0..4 {
                let slack = if c == 3 { bound_pos } else { bound_rot };
                let d = (t[r][c] - t_ref[(r, c)]).abs();
                assert!(
                    d <= tol + slack,
                    "{}: fk[{r}][{c}] off by {d:e} at {q:?}",
                    K::NAME
                );
            }
        }
        let j = robot.jacobian(&q);
        let h = 1e-6;
        for (c, col) in j_ref.iter().enumerate() {
            let (mut qp, mut qm) = (q, q);
            qp[c] += h;
            qm[c] -= h;
            let (tp, tm) = (reference(chain, &qp).0, reference(chain, &qm).0);
            for r in 0..6 {
                let d = (j[r][c] - col[r]).abs();
                let slack = 2.0 * (bound_pos + bound_rot);
                assert!(
                    d <= tol + slack,
                    "{}: J[{r}][{c}] off by {d:e} at {q:?}",
                    K::NAME
                );
                if r < 3 && bound_pos == 0.0 {
                    let fd = (tp[(r, 3)] - tm[(r, 3)]) / (2.0 * h);
                    let d = (j[r][c] - fd).abs();
                    assert!(
                        d <= 1e-9,
                        "{}: J[{r}][{c}] vs finite differences {d:e}",
                        K::NAME
                    );
                }
            }
        }
    }
}

kinegen::kinematics! {
    /// UR5 from its URDF, every decimal as written.
    #[allow(deprecated)] // read literally, the file's decimals overflow the budget: the point of snapping
    struct Ur5Literal = urdf("urdf/ur5.urdf", base = "base_link", tip = "tool0");
    snap: 0,
}
kinegen::kinematics! {
    #[allow(deprecated)] // read literally, the file's decimals overflow the budget: the point of snapping
    struct PandaLiteral = urdf("urdf/panda.urdf", base = "panda_link0", tip = "panda_hand_tcp");
    snap: 0,
}
kinegen::kinematics! {
    /// Axes `0 0 -1` and `-1 0 0`; gazebo, transmission and ros2_control blocks.
    #[allow(deprecated)] // read literally, the file's decimals overflow the budget: the point of snapping
    struct KukaLiteral = urdf("urdf/kuka_kr6_r900.urdf", tip = "tool0");
    snap: 0,
}
kinegen::kinematics! {
    struct Kuka = urdf("urdf/kuka_kr6_r900.urdf", tip = "tool0");
}
kinegen::kinematics! {
    /// Continuous joints, rpy written as 3.1416, -1.5708 and 1e-17.
    #[allow(deprecated)] // read literally, the file's decimals overflow the budget: the point of snapping
    struct KinovaLiteral = urdf("urdf/kinova_j2s6s.urdf");
    snap: 0,
}
kinegen::kinematics! {
    struct Kinova = urdf("urdf/kinova_j2s6s.urdf");
}
kinegen::kinematics! {
    /// A prismatic quill along `0 0 -1`.
    #[allow(deprecated)] // read literally, the file's decimals overflow the budget: the point of snapping
    struct Cobra = urdf("urdf/cobra600.urdf");
    snap: 0,
}

kinegen::kinematics! {
    /// ROS-Industrial's file: joint 3 about `0 -1 0` after joint 2 about `0 1 0`, so the
    /// formulas are in q2 − q3 (`s2m3`, `c2m3`).
    struct LrMate200ib = urdf("urdf/fanucLRMate200ib.urdf", tip = "tool0");
}
kinegen::kinematics! {
    struct MotomanMh5 = urdf("urdf/yaskawaMotomanMH5.urdf");
}
kinegen::kinematics! {
    /// Every length named (`d1`, `a1`…), fields with the file's values.
    struct MotomanMh5Named = urdf("urdf/yaskawaMotomanMH5.urdf");
    params: auto,
}

/// The bounds the generated type states for its snaps, read back from the chain.
fn snap_bounds(file: &str, base: Option<&str>, tip: Option<&str>) -> (f64, f64) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(file);
    let urdf = kinegen_core::front::urdf::Urdf::load_file(&path).unwrap();
    let sel = kinegen_core::chain::urdf::Selection {
        base: base.map(Into::into),
        tip: tip.map(Into::into),
        ..Default::default()
    };
    urdf.chain(&sel).unwrap().snap_bounds()
}

#[test]
fn literal_urdf_robots_equal_the_evaluator() {
    let ur5 = reference_chain("urdf/ur5.urdf", "base_link", "tool0");
    check(&Ur5Literal, &ur5, 1e-9, (0.0, 0.0), &[]);
    let panda = reference_chain("urdf/panda.urdf", "panda_link0", "panda_hand_tcp");
    check(&PandaLiteral, &panda, 1e-9, (0.0, 0.0), &[]);
    let kuka = reference_chain("urdf/kuka_kr6_r900.urdf", "base_link", "tool0");
    check(&KukaLiteral, &kuka, 1e-9, (0.0, 0.0), &[]);
    let kinova = reference_chain("urdf/kinova_j2s6s.urdf", "root", "end_effector");
    check(&KinovaLiteral, &kinova, 1e-9, (0.0, 0.0), &[]);
    let cobra = reference_chain("urdf/cobra600.urdf", "base", "tool");
    check(&Cobra, &cobra, 1e-9, (0.0, 0.0), &[2]);
}

#[test]
fn snapped_urdf_robots_stay_within_their_stated_bounds() {
    let ur5 = reference_chain("urdf/ur5.urdf", "base_link", "tool0");
    let b = snap_bounds("urdf/ur5.urdf", Some("base_link"), Some("tool0"));
    check(&Ur5Urdf::default(), &ur5, 1e-9, b, &[]);
    let kuka = reference_chain("urdf/kuka_kr6_r900.urdf", "base_link", "tool0");
    check(
        &Kuka,
        &kuka,
        1e-9,
        snap_bounds("urdf/kuka_kr6_r900.urdf", None, Some("tool0")),
        &[],
    );
    let kinova = reference_chain("urdf/kinova_j2s6s.urdf", "root", "end_effector");
    let b = snap_bounds("urdf/kinova_j2s6s.urdf", None, None);
    assert!(b.0 > 1e-6, "3.1416 and 1.5708 are snapped: {b:?}");
    check(&Kinova, &kinova, 1e-9, b, &[]);
    // ROS-Industrial's files, joints about −y after +y (formulas in q2 − q3).
    let lr_mate = reference_chain("urdf/fanucLRMate200ib.urdf", "base_link", "tool0");
    let b = snap_bounds("urdf/fanucLRMate200ib.urdf", None, Some("tool0"));
    check(&LrMate200ib, &lr_mate, 1e-9, b, &[]);
    let mh5 = reference_chain("urdf/yaskawaMotomanMH5.urdf", "base_link", "link_t");
    let b = snap_bounds("urdf/yaskawaMotomanMH5.urdf", None, None);
    check(&MotomanMh5, &mh5, 1e-9, b, &[]);
    let named = MotomanMh5Named::default();
    assert_eq!((named.a2, named.d4, named.d4_2), (0.31, 0.0715, 0.2335));
    check(&named, &mh5, 1e-9, b, &[]);
}

/// The UR5 and Panda from their URDFs are the DH robots: the UR5's base_link is the DH
/// frame 0 turned by π about z.
#[test]
fn urdf_robots_equal_their_dh_tables() {
    let (u, d) = (Ur5Urdf::default(), Ur5::default());
    let turn = |v: [f64; 3]| [-v[0], -v[1], v[2]];
    for q in configurations::<6>() {
        let (tu, td) = (u.fk(&q), d.fk(&q));
        for c in 0..4 {
            let col_d = turn([td[0][c], td[1][c], td[2][c]]);
            for r in 0..3 {
                assert!((tu[r][c] - col_d[r]).abs() < 1e-12, "UR5 fk at {q:?}");
            }
        }
        let (ju, jd) = (u.jacobian(&q), d.jacobian(&q));
        for c in 0..6 {
            for block in [0, 3] {
                let v = turn([jd[block][c], jd[block + 1][c], jd[block + 2][c]]);
                for r in 0..3 {
                    assert!((ju[block + r][c] - v[r]).abs() < 1e-12, "UR5 J at {q:?}");
                }
            }
        }
        let (du, dd) = (u.jacobian_det(&q), d.jacobian_det(&q));
        assert!((du - dd).abs() < 1e-12, "UR5 det at {q:?}: {du} vs {dd}");
    }
    let (u, d) = (PandaUrdf::default(), Panda::default());
    for q in configurations::<7>() {
        let (tu, td) = (u.fk(&q), d.fk(&q));
        let (ju, jd) = (u.jacobian(&q), d.jacobian(&q));
        for r in 0..3 {
            for c in 0..4 {
                assert!((tu[r][c] - td[r][c]).abs() < 1e-12, "Panda fk at {q:?}");
            }
        }
        for r in 0..6 {
            for c in 0..7 {
                assert!((ju[r][c] - jd[r][c]).abs() < 1e-12, "Panda J at {q:?}");
            }
        }
    }
    assert_eq!(Ur5Urdf::SINGULARITIES.len(), Ur5::SINGULARITIES.len());
}
