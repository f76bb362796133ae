//! Real robots' kinematics, generated at compile time by `kinegen::kinematics!` from the
//! DH tables in this crate's TOML files (each cites its source), and from URDF files
//! (`urdf/`, `Ur5Urdf`, `PandaUrdf`).
//!
//! ```
//! use kinegen_robots::Ur5;
//! let ur5 = Ur5::default();
//! let q = [0.1, -1.2, 1.4, -0.3, 1.1, 0.2];
//! let t = ur5.fk(&q);
//! let j = ur5.jacobian(&q);
//! assert!(ur5.jacobian_det(&q).abs() > 1e-6);
//! # let _ = (t, j);
//! ```
#![no_std]
// Parameter names follow the DH tables (`L1`, `a2`).
#![allow(non_snake_case)]

kinegen::kinematics! {
    /// Textbook planar RR arm (L1 = L2 = 1), task `[x, y]`.
    pub struct PlanarRr = "planar_rr.toml";
}
kinegen::kinematics! {
    /// Planar RRR arm of the course notes (a = 3.5, 3.5, 2), task `[x, y, rz]`.
    pub struct PlanarRrr = "planar_rrr.toml";
}
kinegen::kinematics! {
    /// Universal Robots UR3.
    pub struct Ur3 = "ur3.toml";
}
kinegen::kinematics! {
    /// Universal Robots UR5.
    pub struct Ur5 = "ur5.toml";
}
kinegen::kinematics! {
    /// Universal Robots UR10.
    pub struct Ur10 = "ur10.toml";
}
kinegen::kinematics! {
    /// Universal Robots UR5e.
    pub struct Ur5e = "ur5e.toml";
}
kinegen::kinematics! {
    /// Universal Robots UR10e.
    pub struct Ur10e = "ur10e.toml";
}
kinegen::kinematics! {
    /// Unimation PUMA 560 (standard DH, Corke's model).
    pub struct Puma560 = "puma560.toml";
}
kinegen::kinematics! {
    /// Stanford arm (prismatic joint 3).
    pub struct Stanford = "stanford.toml";
}
kinegen::kinematics! {
    /// Franka Emika Panda (modified DH, flange and hand).
    ///
    /// Closed-form IK with joint 7 left free (`ik_with(pose, q7)`): axes 1, 2, 3 meet at
    /// the shoulder and axes 5 and 6 meet, so the six others, read from the tool to the
    /// base, are the spherical-wrist family with two intersecting axes (`IK_STEPS`).
    pub struct Panda = "panda.toml";
}
kinegen::kinematics! {
    /// KUKA LBR iiwa 14 R820 (7 joints). Closed-form IK with joint 7 left free by default
    /// (it only turns the tool); `ik_free: 3` in a `kinematics!` of this file leaves joint 3
    /// free instead, the S-R-S arm's usual redundancy parameter.
    pub struct KukaIiwa14 = "kuka_iiwa14.toml";
}
kinegen::kinematics! {
    /// KUKA KR 6 R900.
    pub struct KukaKr6R900 = "kuka_kr6_r900.toml";
}
kinegen::kinematics! {
    /// ABB IRB 120.
    pub struct AbbIrb120 = "abb_irb120.toml";
}
kinegen::kinematics! {
    /// ABB IRB 140.
    pub struct AbbIrb140 = "abb_irb140.toml";
}
kinegen::kinematics! {
    /// SCARA (Adept Cobra s600), task `[x, y, z, rz]`.
    pub struct Scara = "scara.toml";
}
kinegen::kinematics! {
    /// Kinova Jaco (6 joints, 60° wrist; joint 1 flipped, as in RTB's model).
    ///
    /// Its 60° wrist is not spherical and no three axes are parallel, read either way: no
    /// family of subproblems fits, and its `ik` is the general 6R (Raghavan–Roth's
    /// elimination, solved as an eigenproblem at run time; `IK_STEPS`).
    pub struct KinovaJaco = "kinova_jaco.toml";
}
kinegen::kinematics! {
    /// Universal Robots UR5 from its URDF (`urdf/ur5.urdf`, `base_link` → `tool0`), with
    /// UR's DH names for the lengths.
    pub struct Ur5Urdf = "ur5_urdf.toml";
}
kinegen::kinematics! {
    /// Franka Emika Panda from its URDF, `panda_link0` → `panda_hand_tcp` (the fingers,
    /// one mimicking the other, are off the chain). Closed-form IK with joint 7 left free,
    /// as for [`Panda`].
    pub struct PandaUrdf = "panda_urdf.toml";
}
kinegen::kinematics! {
    /// Cylindrical RPP arm, task `[x, y, z]`: closed-form position IK (the cylindrical
    /// case: q1 by SP4, the slides from a 2 × 2 linear system; `IK_STEPS`).
    pub struct CylindricalRpp = "cylindrical_rpp.toml";
}

kinegen::kinematics! {
    /// A spherical-wrist arm whose first three axes are skew (an illustrative table):
    /// closed-form IK through SP5, a quartic (`IK_STEPS`).
    pub struct SkewShoulder = "skew_shoulder.toml";
}
kinegen::kinematics! {
    /// A UR5e with a 5 cm offset between axes 5 and 6 (an illustrative table): closed-form
    /// IK through SP6, a quartic (`IK_STEPS`).
    pub struct Ur5eWristOffset = "ur5e_wrist_offset.toml";
}
kinegen::kinematics! {
    /// FANUC CRX-10iA/L from its URDF (`urdf/crx10ial.urdf`): axes 2 ∥ 3 and 4 ∥ 6 with
    /// joint 5 150 mm off axis 4 — no family of subproblems fits, read either way; its
    /// `ik` is the general 6R (`IK_STEPS`).
    pub struct FanucCrx10iaL = "fanuc_crx10ial.toml";
}
kinegen::kinematics! {
    /// Kinova Gen3, 7 joints, from its URDF (`urdf/kinova_gen3.urdf`): axes offset by
    /// 11.75 mm (shoulder), 12.75 mm (elbow) and 0.35 mm (wrist), so no joint's locking
    /// leaves a family of subproblems; `ik_with` locks joint 7 and solves the general 6R.
    pub struct KinovaGen3 = "kinova_gen3.toml";
}
kinegen::kinematics! {
    /// Interbotix WidowX 250, 5 joints, from its URDF (`urdf/wx250.urdf`): closed-form IK
    /// for the poses it reaches — the tool point, the approach in the arm's plane and the
    /// roll (`IK_STEPS`); a pose off that set gets its position and the nearest approach,
    /// flagged inexact.
    pub struct WidowX250 = "widowx250.toml";
}

/// Every robot table of this crate as `(name, file, TOML source)`, sorted by name: what
/// `kinegen show ur5` reads, and what this crate's types are generated from.
pub const TABLES: &[(&str, &str, &str)] = &[
    (
        "abb_irb120",
        "robots/abb_irb120.toml",
        include_str!("../abb_irb120.toml"),
    ),
    (
        "abb_irb140",
        "robots/abb_irb140.toml",
        include_str!("../abb_irb140.toml"),
    ),
    (
        "cylindrical_rpp",
        "robots/cylindrical_rpp.toml",
        include_str!("../cylindrical_rpp.toml"),
    ),
    (
        "fanuc_crx10ial",
        "robots/fanuc_crx10ial.toml",
        include_str!("../fanuc_crx10ial.toml"),
    ),
    (
        "kinova_gen3",
        "robots/kinova_gen3.toml",
        include_str!("../kinova_gen3.toml"),
    ),
    (
        "kinova_jaco",
        "robots/kinova_jaco.toml",
        include_str!("../kinova_jaco.toml"),
    ),
    (
        "kuka_iiwa14",
        "robots/kuka_iiwa14.toml",
        include_str!("../kuka_iiwa14.toml"),
    ),
    (
        "kuka_kr6_r900",
        "robots/kuka_kr6_r900.toml",
        include_str!("../kuka_kr6_r900.toml"),
    ),
    ("panda", "robots/panda.toml", include_str!("../panda.toml")),
    (
        "panda_urdf",
        "robots/panda_urdf.toml",
        include_str!("../panda_urdf.toml"),
    ),
    (
        "planar_rr",
        "robots/planar_rr.toml",
        include_str!("../planar_rr.toml"),
    ),
    (
        "planar_rrr",
        "robots/planar_rrr.toml",
        include_str!("../planar_rrr.toml"),
    ),
    (
        "puma560",
        "robots/puma560.toml",
        include_str!("../puma560.toml"),
    ),
    ("scara", "robots/scara.toml", include_str!("../scara.toml")),
    (
        "skew_shoulder",
        "robots/skew_shoulder.toml",
        include_str!("../skew_shoulder.toml"),
    ),
    (
        "stanford",
        "robots/stanford.toml",
        include_str!("../stanford.toml"),
    ),
    ("ur10", "robots/ur10.toml", include_str!("../ur10.toml")),
    ("ur10e", "robots/ur10e.toml", include_str!("../ur10e.toml")),
    ("ur3", "robots/ur3.toml", include_str!("../ur3.toml")),
    ("ur5", "robots/ur5.toml", include_str!("../ur5.toml")),
    (
        "ur5_urdf",
        "robots/ur5_urdf.toml",
        include_str!("../ur5_urdf.toml"),
    ),
    ("ur5e", "robots/ur5e.toml", include_str!("../ur5e.toml")),
    (
        "ur5e_wrist_offset",
        "robots/ur5e_wrist_offset.toml",
        include_str!("../ur5e_wrist_offset.toml"),
    ),
    (
        "widowx250",
        "robots/widowx250.toml",
        include_str!("../widowx250.toml"),
    ),
];

/// Every URDF of `robots/urdf/` as `(path relative to robots/, file, XML source)`,
/// sorted: the files the tables above may name (`urdf = "urdf/ur5.urdf"`).
pub const URDFS: &[(&str, &str, &str)] = &[
    (
        "urdf/cobra600.urdf",
        "robots/urdf/cobra600.urdf",
        include_str!("../urdf/cobra600.urdf"),
    ),
    (
        "urdf/crx10ial.urdf",
        "robots/urdf/crx10ial.urdf",
        include_str!("../urdf/crx10ial.urdf"),
    ),
    (
        "urdf/fanucLRMate200ib.urdf",
        "robots/urdf/fanucLRMate200ib.urdf",
        include_str!("../urdf/fanucLRMate200ib.urdf"),
    ),
    (
        "urdf/kinova_gen3.urdf",
        "robots/urdf/kinova_gen3.urdf",
        include_str!("../urdf/kinova_gen3.urdf"),
    ),
    (
        "urdf/kinova_j2s6s.urdf",
        "robots/urdf/kinova_j2s6s.urdf",
        include_str!("../urdf/kinova_j2s6s.urdf"),
    ),
    (
        "urdf/kuka_kr6_r900.urdf",
        "robots/urdf/kuka_kr6_r900.urdf",
        include_str!("../urdf/kuka_kr6_r900.urdf"),
    ),
    (
        "urdf/kuka_lbr_iiwa_14_r820.urdf",
        "robots/urdf/kuka_lbr_iiwa_14_r820.urdf",
        include_str!("../urdf/kuka_lbr_iiwa_14_r820.urdf"),
    ),
    (
        "urdf/panda.urdf",
        "robots/urdf/panda.urdf",
        include_str!("../urdf/panda.urdf"),
    ),
    (
        "urdf/ur16e.urdf",
        "robots/urdf/ur16e.urdf",
        include_str!("../urdf/ur16e.urdf"),
    ),
    (
        "urdf/ur5.urdf",
        "robots/urdf/ur5.urdf",
        include_str!("../urdf/ur5.urdf"),
    ),
    (
        "urdf/wx250.urdf",
        "robots/urdf/wx250.urdf",
        include_str!("../urdf/wx250.urdf"),
    ),
    (
        "urdf/yaskawaMotomanMH5.urdf",
        "robots/urdf/yaskawaMotomanMH5.urdf",
        include_str!("../urdf/yaskawaMotomanMH5.urdf"),
    ),
];
