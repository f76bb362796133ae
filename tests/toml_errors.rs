//! The compile-fail cases of `kinegen-macro/tests/ui` through the TOML front end: the same messages,
//! each with the line of the offending entry.

use kinegen_core::front::toml_file::load_str;

/// The errors of `src` as `file:LINE: path: message` lines.
fn errors(src: &str) -> Vec<String> {
    match load_str(src, "robot.toml") {
        Ok(_) => panic!("expected errors, the file loaded"),
        Err(e) => e.errors.iter().map(ToString::to_string).collect(),
    }
}

/// A one-joint revolute arm with `extra` lines added to its joint and `tail` after it.
fn one_joint(joint: &str, tail: &str) -> String {
    format!("name = \"one\"\nconvention = \"standard\"\n\n[[joints]]\ntype = \"revolute\"\n{joint}\n{tail}")
}

#[test]
fn missing_column() {
    assert_eq!(
        errors(&one_joint("a = 0\nalpha = 0", "")),
        ["robot.toml:4: joints[0]: missing column `d`"]
    );
}

#[test]
fn unknown_column() {
    assert_eq!(
        errors(&one_joint("a = 0\nalhpa = \"pi/2\"\nd = 0", "")),
        [
            "robot.toml:4: joints[0]: missing column `alpha`",
            "robot.toml:7: joints[0].alhpa: unknown column `alhpa`: expected a, alpha, d, theta, offset, limits or flip",
        ]
    );
}

#[test]
fn duplicate_keys_are_toml_syntax_errors() {
    // TOML itself forbids a key twice (columns, parameters, top-level keys): the
    // parser's message, at the second one.
    assert_eq!(
        errors(&one_joint("a = 0\nalpha = 0\nd = 0\na = 1", "")),
        ["robot.toml:9: duplicate key `a` in table `joints`"]
    );
    assert_eq!(
        errors(&one_joint(
            "a = 0\nalpha = 0\nd = 0",
            "[params]\nL1 = 1.0\nL2 = 0.5\nL1 = 2.0\n"
        )),
        ["robot.toml:12: duplicate key `L1` in table `params`"]
    );
}

#[test]
fn unknown_convention() {
    let src =
        "convention = \"denavit\"\n[[joints]]\ntype = \"revolute\"\na = 0\nalpha = 0\nd = 0\n";
    assert_eq!(
        errors(src),
        ["robot.toml:1: convention: unknown convention `denavit`: expected `standard` or `modified`"]
    );
}

#[test]
fn missing_convention() {
    let src = "name = \"x\"\n[[joints]]\ntype = \"revolute\"\na = 0\nalpha = 0\nd = 0\n";
    assert_eq!(
        errors(src),
        ["robot.toml:1: missing `convention`: say `standard` (Rz Tz Tx Rx) or `modified` (Rx Tx Rz Tz)"]
    );
}

#[test]
fn joint_type() {
    let src = one_joint(
        "a = 0\nalpha = 0\nd = 0",
        "[[joints]]\ntype = \"spherical\"\na = 0\nalpha = 0\nd = 0\n",
    );
    assert_eq!(
        errors(&src),
        ["robot.toml:10: joints[1].type: unknown joint type `spherical`: expected `revolute` or `prismatic`"]
    );
    let src = "convention = \"standard\"\n[[joints]]\na = 0\nalpha = 0\nd = 0\n";
    assert_eq!(
        errors(src),
        ["robot.toml:2: joints[0]: missing joint type: `revolute` or `prismatic`"]
    );
}

#[test]
fn parameters() {
    let src = one_joint(
        "a = \"a2\"\nalpha = \"pi/2\"\nd = \"d1\"",
        "[params]\nd1 = 0.089159\n",
    );
    assert_eq!(
        errors(&src),
        ["robot.toml:6: joints[0].a: undefined parameter `a2`"]
    );
    let src = one_joint("a = \"L1\"\nalpha = 0\nd = 0", "[params]\nL1 = \"one\"\n");
    assert_eq!(
        errors(&src),
        ["robot.toml:10: params.L1: parameter `L1` must have a numeric value, not `one`"]
    );
}

#[test]
fn bad_values() {
    let case = |a: &str| errors(&one_joint(&format!("a = {a}\nalpha = 0\nd = 0"), ""));
    assert_eq!(
        case("\"1e999\""),
        ["robot.toml:6: joints[0].a: `1e999` is not a number"]
    );
    assert_eq!(
        case("inf"),
        ["robot.toml:6: joints[0].a: `inf` is not a finite number"]
    );
    assert_eq!(
        case("nan"),
        ["robot.toml:6: joints[0].a: `NaN` is not a finite number"]
    );
    assert_eq!(
        case("\"pi/\""),
        ["robot.toml:6: joints[0].a: `pi/` ends unexpectedly"]
    );
    assert_eq!(
        case("\"pi/2\""),
        ["robot.toml:6: joints[0].a: `pi/2` contains `pi` but this entry is a length"]
    );
    let src = one_joint(
        "a = \"L1*L2\"\nalpha = 0\nd = 0",
        "[params]\nL1 = 1.0\nL2 = 0.5\n",
    );
    assert_eq!(
        errors(&src),
        ["robot.toml:6: joints[0].a: `L1*L2` is not linear: a product may have only one factor that is `pi` or a parameter"]
    );
}

#[test]
fn no_joints() {
    assert_eq!(
        errors("convention = \"standard\"\njoints = []\n"),
        ["robot.toml:2: joints: the DH table has no joints"]
    );
}

#[test]
fn task_rows() {
    let case = |t: &str| {
        errors(&format!(
            "task = {t}\n{}",
            one_joint("a = 1\nalpha = 0\nd = 0", "")
        ))
    };
    assert_eq!(
        case("[\"x\", \"w\"]"),
        ["robot.toml:1: task[1]: unknown task row `w`: expected x, y, z, rx, ry or rz"]
    );
    assert_eq!(
        case("[\"x\", \"y\", \"x\"]"),
        ["robot.toml:1: task[2]: task row `x` given twice"]
    );
    assert_eq!(
        case("[]"),
        ["robot.toml:1: task: task rows are empty: list some of x, y, z, rx, ry, rz"]
    );
}

#[test]
fn limits() {
    let case = |l: &str| {
        errors(&one_joint(
            &format!("a = 1\nalpha = 0\nd = 0\nlimits = {l}"),
            "",
        ))
    };
    assert_eq!(
        case("[\"pi\", \"-pi\"]"),
        ["robot.toml:9: joints[0].limits: limits have min 3.141592653589793 > max -3.141592653589793"]
    );
    assert_eq!(
        case("[-1, 0, 1]"),
        ["robot.toml:9: joints[0].limits: limits must be `[min, max]`, found 3 values"]
    );
}

#[test]
fn frames() {
    let base = one_joint(
        "a = 1\nalpha = 0\nd = 0",
        "[base]\nxyz = [0, 0.1]\nrpy = [0, 0, 0]\n",
    );
    assert_eq!(
        errors(&base),
        ["robot.toml:10: base.xyz: `xyz` needs 3 values, found 2"]
    );
    let tool = one_joint(
        "a = 1\nalpha = 0\nd = 0",
        "[tool]\nxyz = [0, 0, 0.1]\nrot = [0, 0, 0]\n",
    );
    assert_eq!(
        errors(&tool),
        ["robot.toml:11: tool.rot: unknown entry `rot`: a frame has `xyz` and `rpy`"]
    );
}

#[test]
fn top_level_keys_scalar_and_budget() {
    let src = format!(
        "colour = \"red\"\nscalar = \"f16\"\n{}",
        one_joint(
            "a = 1\nalpha = 0\nd = 0",
            "[budget]\nnodes = 0\ndepth = 3\n"
        )
    );
    assert_eq!(
        errors(&src),
        [
            "robot.toml:1: colour: unknown key `colour`: expected name, convention, params, joints, task, base, tool, scalar, budget or ik_free",
            "robot.toml:2: scalar: unknown scalar type `f16`: expected `f64` or `f32`",
            "robot.toml:12: budget.nodes: `nodes` must be a positive integer (at most 4294967295)",
            "robot.toml:13: budget.depth: unknown budget entry `depth`: expected nodes, iterations or time_ms",
        ]
    );
}

#[test]
fn malformed_toml() {
    let src = "name = \"one link\"\nconvention = \"standard\"\n\n[[joints]\ntype = \"revolute\"\n";
    assert_eq!(
        errors(src),
        ["robot.toml:4: invalid table header: expected `.`, `]]`"]
    );
}

#[test]
fn several_errors_in_file_order() {
    let src = "convention = \"standard\"\ntask = [\"x\", \"y\", \"q\"]\n[params]\nL1 = 1.0\n[[joints]]\ntype = \"revolute\"\na = \"L1\"\nalpha = \"pi/2\"\nd = \"L3\"\n[[joints]]\ntype = \"prismatic\"\na = 0\nalpha = 0\nd = 0\n";
    assert_eq!(
        errors(src),
        [
            "robot.toml:2: task[2]: unknown task row `q`: expected x, y, z, rx, ry or rz",
            "robot.toml:9: joints[0].d: undefined parameter `L3`",
            "robot.toml:10: joints[1]: missing column `theta`",
        ]
    );
}
