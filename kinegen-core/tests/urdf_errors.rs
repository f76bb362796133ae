//! Bad URDF input: every case a clear error at the file's line, never a panic.

use kinegen_core::chain::urdf::Selection;
use kinegen_core::front::urdf::Urdf;

/// A two-joint arm `base → a → b` with `joint2` written by the caller.
fn arm(joint2: &str) -> String {
    format!(
        "<robot name=\"r\">\n\
         <link name=\"base\"/>\n<link name=\"a\"/>\n<link name=\"b\"/>\n\
         <joint name=\"joint1\" type=\"revolute\">\n\
           <parent link=\"base\"/><child link=\"a\"/><axis xyz=\"0 0 1\"/>\n\
         </joint>\n\
         {joint2}\n\
         </robot>\n"
    )
}

fn parse_err(src: &str) -> String {
    Urdf::parse(src, "r.urdf").unwrap_err().to_string()
}

fn chain_err(src: &str, base: Option<&str>, tip: Option<&str>) -> String {
    let urdf = Urdf::parse(src, "r.urdf").unwrap();
    let sel = Selection {
        base: base.map(Into::into),
        tip: tip.map(Into::into),
        ..Selection::default()
    };
    urdf.chain(&sel).unwrap_err().to_string()
}

const JOINT2: &str = "<joint name=\"joint2\" type=\"prismatic\">\n<parent link=\"a\"/><child link=\"b\"/>\n<axis xyz=\"1 0 0\"/></joint>";

#[test]
fn a_good_arm_builds() {
    let urdf = Urdf::parse(&arm(JOINT2), "r.urdf").unwrap();
    assert_eq!(urdf.chain(&Selection::default()).unwrap().dof(), 2);
}

#[test]
fn missing_file() {
    let e = Urdf::load_file(std::path::Path::new("/nonexistent/arm.urdf")).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("/nonexistent/arm.urdf: cannot read the file"),
        "{e}"
    );
}

#[test]
fn not_xml_and_not_urdf() {
    let e = parse_err("<robot name=\"r\">\n<link name=\"a\">\n</robot>");
    assert!(e.starts_with("r.urdf:3: not an XML file: "), "{e}");
    let e = parse_err("convention = \"standard\"\n");
    assert!(e.starts_with("r.urdf:1: not an XML file: "), "{e}");
    let e = parse_err("<?xml version=\"1.0\"?>\n<sdf version=\"1.6\"><model name=\"m\"/></sdf>");
    assert_eq!(
        e,
        "r.urdf:2: not a URDF file: the root element is <sdf>, not <robot>"
    );
}

#[test]
fn unknown_links_and_a_tip_not_below_the_base() {
    let src = arm(JOINT2);
    assert_eq!(
        chain_err(&src, Some("bse"), None),
        "r.urdf:1: base: no link `bse` (the base): the links are `base`, `a` and `b`"
    );
    assert_eq!(
        chain_err(&src, None, Some("tool0")),
        "r.urdf:1: tip: no link `tool0` (the tip): the links are `base`, `a` and `b`"
    );
    assert_eq!(
        chain_err(&src, Some("b"), Some("a")),
        "r.urdf:3: tip: tip link `a` is not below base link `b`"
    );
}

#[test]
fn several_leaves_need_a_tip() {
    let src = arm(JOINT2).replace(
        "</robot>",
        "<link name=\"c\"/><joint name=\"j3\" type=\"fixed\"><parent link=\"a\"/><child link=\"c\"/></joint>\n</robot>",
    );
    assert_eq!(
        chain_err(&src, None, None),
        "r.urdf:1: tip: the tree has 2 leaves, name the tip link: `b` and `c`"
    );
}

/// ROS-Industrial's files hang a `base` frame from `base_link` by a fixed joint: a leaf
/// that ends no chain of joints is no tip to ask about. Two leaves after moving joints
/// still are; a tree of fixed joints only lists them all.
#[test]
fn a_leaf_after_fixed_joints_only_is_not_a_tip() {
    let base_frame = "<link name=\"frame\"/><joint name=\"j0\" type=\"fixed\"><parent link=\"base\"/><child link=\"frame\"/></joint>\n</robot>";
    let src = arm(JOINT2).replace("</robot>", base_frame);
    let urdf = Urdf::parse(&src, "r.urdf").unwrap();
    let chain = urdf.chain(&Selection::default()).unwrap();
    assert_eq!(chain.dof(), 2);
    assert!(chain.description.contains("`b`"), "{}", chain.description);

    let another = "<link name=\"c\"/><joint name=\"j3\" type=\"fixed\"><parent link=\"a\"/><child link=\"c\"/></joint>\n</robot>";
    let src = src.replace("</robot>", another);
    assert_eq!(
        chain_err(&src, None, None),
        "r.urdf:1: tip: the tree has 3 leaves, 2 of them after a moving joint; name the tip link: `b` and `c`"
    );

    let fixed = "<robot name=\"r\">\n<link name=\"base\"/><link name=\"x\"/><link name=\"y\"/>\n\
        <joint name=\"f1\" type=\"fixed\"><parent link=\"base\"/><child link=\"x\"/></joint>\n\
        <joint name=\"f2\" type=\"fixed\"><parent link=\"base\"/><child link=\"y\"/></joint>\n</robot>\n";
    assert_eq!(
        chain_err(fixed, None, None),
        "r.urdf:1: tip: the tree has 2 leaves, name the tip link: `x` and `y`"
    );
}

#[test]
fn floating_planar_and_mimic_joints_on_the_chain() {
    for kind in ["floating", "planar"] {
        let j = JOINT2.replace("prismatic", kind);
        let e = chain_err(&arm(&j), None, None);
        assert!(
            e.starts_with(&format!(
                "r.urdf:8: joint2: joint `joint2` on the chain `base` → `b` is {kind}"
            )),
            "{e}"
        );
    }
    let j = JOINT2.replace("</joint>", "<mimic joint=\"joint1\"/></joint>");
    let e = chain_err(&arm(&j), None, None);
    assert!(
        e.starts_with("r.urdf:8: joint2: joint `joint2` on the chain mimics `joint1`"),
        "{e}"
    );
    // Off the chain, a floating joint is ignored.
    let src = arm(JOINT2).replace(
        "</robot>",
        "<link name=\"c\"/><joint name=\"j3\" type=\"floating\"><parent link=\"a\"/><child link=\"c\"/></joint>\n</robot>",
    );
    let urdf = Urdf::parse(&src, "r.urdf").unwrap();
    let sel = Selection {
        tip: Some("b".into()),
        ..Selection::default()
    };
    assert_eq!(urdf.chain(&sel).unwrap().dof(), 2);
}

#[test]
fn xacro_left_in() {
    let hint = "this is an unexpanded xacro file: run `xacro FILE.urdf.xacro > FILE.urdf` first";
    let declared = "<robot name=\"r\" xmlns:xacro=\"http://www.ros.org/wiki/xacro\">\n<xacro:property name=\"d1\" value=\"0.1\"/>\n</robot>";
    assert!(parse_err(declared).starts_with(&format!("r.urdf:2: {hint}")));
    let undeclared = "<robot name=\"r\">\n\n<xacro:include filename=\"arm.xacro\"/>\n</robot>";
    assert!(parse_err(undeclared).starts_with(&format!("r.urdf:3: {hint}")));
    let subst = arm(&JOINT2.replace("1 0 0", "${axis}"));
    assert!(parse_err(&subst).starts_with(&format!("r.urdf:10: {hint}")));
}

#[test]
fn bad_numbers_and_a_zero_axis() {
    let e = parse_err(&arm(&JOINT2.replace("1 0 0", "0 0 0")));
    assert_eq!(e, "r.urdf:10: joint2.axis: joint `joint2` has a zero axis");
    let e = parse_err(&arm(&JOINT2.replace("1 0 0", "NaN 0 1")));
    assert_eq!(e, "r.urdf:10: joint2.axis: `NaN` is not a number");
    let e = parse_err(&arm(&JOINT2.replace("1 0 0", "one 0 1")));
    assert_eq!(e, "r.urdf:10: joint2.axis: `one` is not a number");
    let e = parse_err(&arm(&JOINT2.replace("1 0 0", "1 0")));
    assert_eq!(e, "r.urdf:10: joint2.axis: needs 3 numbers, found 2: `1 0`");
    let lim = JOINT2.replace("</joint>", "<limit lower=\"inf\" upper=\"1\"/></joint>");
    let e = parse_err(&arm(&lim));
    assert_eq!(e, "r.urdf:10: joint2.limit: `inf` is not a number");
}

#[test]
fn not_a_tree() {
    // Two roots.
    let src = arm(JOINT2).replace("</robot>", "<link name=\"stray\"/>\n</robot>");
    assert_eq!(
        parse_err(&src),
        "r.urdf:1: the links form 2 trees, a URDF is one: roots `base` and `stray`"
    );
    // Two parents.
    let j = JOINT2.replace("<parent link=\"a\"/>", "<parent link=\"base\"/>");
    let src = arm(&j).replace(
        "</robot>",
        "<joint name=\"j3\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>\n</robot>",
    );
    let e = parse_err(&src);
    assert!(
        e.starts_with("r.urdf:11: j3: link `b` has two parents: joints `joint2` (line 8) and `j3`"),
        "{e}"
    );
    // A cycle (with one root elsewhere).
    let src = arm(JOINT2).replace(
        "</robot>",
        "<joint name=\"back\" type=\"fixed\"><parent link=\"b\"/><child link=\"base\"/></joint>\n</robot>",
    );
    let e = parse_err(&src);
    assert!(
        e.contains("is on a cycle: the links do not form a tree"),
        "{e}"
    );
    // An unknown link.
    let e = parse_err(&arm(
        &JOINT2.replace("<child link=\"b\"/>", "<child link=\"c\"/>")
    ));
    assert!(e.contains("joint2: child link `c` is not declared"), "{e}");
}

#[test]
fn bad_options() {
    let urdf = Urdf::parse(&arm(JOINT2), "r.urdf").unwrap();
    let sel = Selection {
        snap: -1.0,
        ..Selection::default()
    };
    assert_eq!(
        urdf.chain(&sel).unwrap_err().to_string(),
        "r.urdf:1: snap: `snap` must be a tolerance ≥ 0, not -1"
    );
    let sel = Selection {
        params: vec![
            ("s1".into(), "joint1.origin.z".into()),
            ("d".into(), "joint9.origin.z".into()),
            ("e".into(), "joint1.axis.z".into()),
        ],
        ..Selection::default()
    };
    let e = urdf.chain(&sel).unwrap_err().to_string();
    assert!(
        e.contains("params.s1: `s1` is a name the generated code uses"),
        "{e}"
    );
    assert!(
        e.contains("params.d: no joint `joint9` on the chain"),
        "{e}"
    );
    assert!(
        e.contains("params.e: `joint1.axis.z` is not a length of the file"),
        "{e}"
    );
}

/// A parallel gripper (the Panda's hand): a TCP frame and two fingers on prismatic joints
/// after the arm's last joint. The arm ends at the TCP without `tip`; one finger, or
/// fingers on revolute joints (a tool past a sensor's frame), are asked about.
#[test]
fn a_parallel_grippers_fingers_are_not_the_tip() {
    let hand = |kind: &str, fingers: usize| {
        let mut s = String::from(
            "<link name=\"tcp\"/><joint name=\"t\" type=\"fixed\"><parent link=\"b\"/><child link=\"tcp\"/></joint>\n",
        );
        for f in 1..=fingers {
            s += &format!(
                "<link name=\"f{f}\"/><joint name=\"jf{f}\" type=\"{kind}\"><parent link=\"b\"/><child link=\"f{f}\"/><axis xyz=\"0 1 0\"/><limit lower=\"0\" upper=\"0.04\" effort=\"1\" velocity=\"1\"/></joint>\n"
            );
        }
        arm(JOINT2).replace("</robot>", &(s + "</robot>"))
    };
    let urdf = Urdf::parse(&hand("prismatic", 2), "r.urdf").unwrap();
    let chain = urdf.chain(&Selection::default()).unwrap();
    assert_eq!(chain.dof(), 2);
    assert!(
        chain.description.ends_with("`base` → `tcp`"),
        "{}",
        chain.description
    );
    assert_eq!(
        chain_err(&hand("prismatic", 1), None, None),
        "r.urdf:1: tip: the tree has 2 leaves, name the tip link: `tcp` and `f1`"
    );
    assert_eq!(
        chain_err(&hand("revolute", 2), None, None),
        "r.urdf:1: tip: the tree has 3 leaves, name the tip link: `tcp`, `f1` and `f2`"
    );
}
