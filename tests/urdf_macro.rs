//! The macro's URDF form compiles, tracks its file, and takes the options.

kinegen::kinematics! {
    /// A one-joint arm from `kinegen-macro/tests/ui/data/arm.urdf`, its shoulder height named.
    pub struct Arm = urdf("kinegen-macro/tests/ui/data/arm.urdf", base = "base", tip = "tool");
    params: { h: "shoulder.origin.z" },
    scalar: f32,
}

#[test]
fn the_urdf_form_generates_a_robot() {
    let arm = Arm::default();
    assert_eq!(arm.h, 0.1);
    assert_eq!(Arm::DOF, 1);
    // 1.5708 is snapped to π/2: the tool sits 0.2 m along the turned x axis, so at
    // q = 0 it is below the shoulder by exactly 0.2 (x of the tool = 0).
    let t = arm.fk(&[0.0]);
    assert!(
        t[0][3].abs() < 1e-6 && (t[2][3] - (0.1 - 0.2)).abs() < 1e-6,
        "{t:?}"
    );
}
