//! Real invocations of the `kinegen` binary.

use kinegen_core::{front::toml_file, generate, numeric, ItemHeader};
use predicates::prelude::*;
use serde_json::Value;

mod common;
use common::{fails, kinegen, robot_file, stdout};

#[test]
fn show_planar_rr() {
    insta::assert_snapshot!("show_planar_rr", stdout(&["show", "planar_rr"]));
}

#[test]
fn show_ur5() {
    insta::assert_snapshot!("show_ur5", stdout(&["show", "ur5"]));
}

/// The readable `eval` table, manipulability section included (12 decimals: the same on
/// every platform's libm).
#[test]
fn eval_table_planar_rr() {
    insta::assert_snapshot!(
        "eval_planar_rr",
        stdout(&["eval", "planar_rr", "--q", "0.3,0.5"])
    );
}

#[test]
fn show_latex_planar_rr() {
    insta::assert_snapshot!(
        "show_latex_planar_rr",
        stdout(&["show", "planar_rr", "--latex"])
    );
}

#[test]
fn show_what_selects_sections_and_files_work_like_names() {
    let fk = stdout(&["show", "ur5", "--what", "fk"]);
    assert!(
        fk.contains("== Forward kinematics") && !fk.contains("== Geometric Jacobian"),
        "{fk}"
    );
    assert!(fk.contains("c23 = cos(q2 + q3) = "), "{fk}");
    let path = robot_file("ur5");
    assert_eq!(
        stdout(&["show", path.to_str().unwrap(), "--what", "fk"]),
        fk
    );
    let j = stdout(&["show", "planar_rr", "--what", "jacobian", "--latex"]);
    assert!(j.contains(r"J_{1,1} &= t_{2} - s_{1}\,L_{1}"), "{j}");
    assert!(!j.contains("Forward kinematics"), "{j}");
    for what in ["det", "singularities"] {
        let s = stdout(&["show", "puma560", "--what", what]);
        assert!(s.starts_with("PUMA"), "{s}");
    }
}

#[test]
fn shipped_robots_work_from_any_directory() {
    let out = kinegen()
        .current_dir("/")
        .args(["show", "ur5", "--what", "fk"])
        .assert()
        .success();
    assert!(String::from_utf8_lossy(&out.get_output().stdout).starts_with("UR5 — 6 joints"));
}

/// `kinegen rust` prints what the macro expands to: `kinematics!` calls
/// `kinegen_core::generate(&robot.chain(), &header, &options)` with the header of
/// `pub struct <Name>` (kinegen-macro/src/expand.rs), which for the file form is
/// `ItemHeader::public(&robot.name)`. The file form adds one `const _: &str =
/// include_str!(…)` line for cargo's rebuild tracking, which is not part of the robot.
#[test]
fn rust_is_the_macro_expansion() {
    for name in ["planar_rr", "ur5"] {
        let (robot, options) = toml_file::load_file(&robot_file(name)).unwrap();
        let expected =
            generate(&robot.chain(), &ItemHeader::public(&robot.name), &options).pretty();
        assert_eq!(stdout(&["rust", name]), expected, "{name}");
    }
    let planar = stdout(&["rust", "planar_rr"]);
    assert!(planar.contains("pub struct PlanarRr {"), "{planar}");
    assert!(
        planar.contains("impl ::kinegen::Kinematics<2> for PlanarRr"),
        "{planar}"
    );
}

fn matrix(v: &Value) -> Vec<Vec<f64>> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|r| {
            r.as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        })
        .collect()
}

fn assert_close(
    what: &str,
    got: &[Vec<f64>],
    want: impl Fn(usize, usize) -> f64,
    rows: usize,
    cols: usize,
) {
    assert_eq!(got.len(), rows, "{what}");
    for (r, row) in got.iter().enumerate() {
        assert_eq!(row.len(), cols, "{what}");
        for (c, &x) in row.iter().enumerate() {
            let w = want(r, c);
            assert!(
                (x - w).abs() < 1e-12,
                "{what}[{r}][{c}]: {x} vs reference {w}"
            );
        }
    }
}

/// Yoshikawa's `√det(M Mᵀ)` of the rows `rows` of the reference Jacobian `j`.
fn reference_manipulability(j: &nalgebra::DMatrix<f64>, rows: &[usize]) -> f64 {
    let m = nalgebra::DMatrix::from_fn(rows.len(), j.ncols(), |r, c| j[(rows[r], c)]);
    numeric::manipulability(&m)
}

#[test]
fn eval_json_matches_the_numeric_reference() {
    let cases: [(&str, &[f64]); 5] = [
        ("planar_rr", &[0.3, -1.1]),
        ("planar_rrr", &[0.3, -1.1, 0.7]),
        ("ur5", &[0.1, -0.7, 1.3, 0.4, -2.2, 0.9]),
        ("puma560", &[0.2, 0.3, -0.4, 1.0, 0.6, -1.5]),
        ("scara", &[0.5, -0.4, 0.1, 0.7]),
    ];
    for (name, q) in cases {
        let qs: Vec<String> = q.iter().map(|x| x.to_string()).collect();
        let text = stdout(&["eval", name, "--q", &qs.join(","), "--json"]);
        let v: Value = serde_json::from_str(&text).unwrap();
        let (robot, _) = toml_file::load_file(&robot_file(name)).unwrap();
        let n = robot.dof();
        let reference = numeric::NumericRobot::new(&robot).unwrap();
        let t = reference.fk(q).unwrap();
        assert_close(name, &matrix(&v["fk"]), |r, c| t[(r, c)], 4, 4);
        let j = reference.jacobian(q).unwrap();
        assert_close(name, &matrix(&v["jacobian"]), |r, c| j[(r, c)], 6, n);
        let je = reference.jacobian_ee(q).unwrap();
        assert_close(name, &matrix(&v["jacobian_ee"]), |r, c| je[(r, c)], 6, n);
        let jt = robot.task.as_ref().map(|_| {
            let jt = reference.task_jacobian(q).unwrap();
            let got = matrix(&v["task_jacobian"]);
            assert_close(name, &got, |r, c| jt[(r, c)], jt.nrows(), n);
            jt
        });
        if jt.is_none() {
            assert!(v["task_jacobian"].is_null(), "{name}");
        }
        check_manipulability(
            name,
            &v,
            &nalgebra::DMatrix::from_fn(6, n, |r, c| j[(r, c)]),
            jt.as_ref(),
        );
        // Null until the engine has the determinant (kinegen-cli/src/det_hook.rs);
        // once it does, it must agree with the reference.
        for (key, reference_det) in [
            ("det", (n == 6).then(|| numeric::det6(&j).unwrap())),
            ("det_task", jt.as_ref().and_then(|m| numeric::det(m).ok())),
        ] {
            if let (Some(got), Some(want)) = (v[key].as_f64(), reference_det) {
                assert!((got - want).abs() < 1e-12, "{name} {key}: {got} vs {want}");
            } else {
                assert!(v[key].is_null(), "{name} {key}: {}", v[key]);
            }
        }
    }
}

/// The four manipulability fields against the reference Jacobian's rows (the Robotics
/// Toolbox's `axes`: all, trans, rot; and the task rows). Fewer joints than rows means 0,
/// exactly: a planar arm's full Jacobian cannot move in six directions.
fn check_manipulability(
    name: &str,
    v: &Value,
    j: &nalgebra::DMatrix<f64>,
    jt: Option<&nalgebra::DMatrix<f64>>,
) {
    let n = j.ncols();
    for (key, rows) in [
        ("manipulability", &[0, 1, 2, 3, 4, 5][..]),
        ("manipulability_trans", &[0, 1, 2][..]),
        ("manipulability_rot", &[3, 4, 5][..]),
    ] {
        let got = v[key].as_f64().unwrap();
        let want = reference_manipulability(j, rows);
        if rows.len() > n {
            assert_eq!(got, 0.0, "{name} {key}");
        }
        assert!(
            (got - want).abs() < 1e-12,
            "{name} {key}: {got} vs reference {want}"
        );
    }
    match jt {
        Some(jt) => {
            let got = v["manipulability_task"].as_f64().unwrap();
            let want = numeric::manipulability(jt);
            assert!(want > 1e-3, "{name}: a regular pose expected");
            assert!(
                (got - want).abs() < 1e-12,
                "{name} task: {got} vs reference {want}"
            );
        }
        None => assert!(v["manipulability_task"].is_null(), "{name}"),
    }
}

#[test]
fn eval_planar_rr_by_hand() {
    // x = L1 c1 + L2 c12 with L1 = L2 = 1; √det(Jt Jtᵀ) = |det Jt| = L1 L2 |s2| for the
    // task rows [x, y]; the full 6×2 J, and its 3×2 linear and angular blocks, give 0.
    let v: Value =
        serde_json::from_str(&stdout(&["eval", "planar_rr", "--q", "0.3,0.5", "--json"])).unwrap();
    let x = v["fk"][0][3].as_f64().unwrap();
    assert!((x - (0.3f64.cos() + 0.8f64.cos())).abs() < 1e-15);
    let w = |key: &str| v[key].as_f64().unwrap();
    assert!((w("manipulability_task") - 0.5f64.sin()).abs() < 1e-14);
    assert_eq!(w("manipulability"), 0.0);
    assert_eq!(w("manipulability_trans"), 0.0);
    assert_eq!(w("manipulability_rot"), 0.0);
    let keys: Vec<&String> = v.as_object().unwrap().keys().collect();
    assert_eq!(
        keys,
        [
            "fk",
            "jacobian",
            "jacobian_ee",
            "det",
            "task_jacobian",
            "det_task",
            "manipulability",
            "manipulability_task",
            "manipulability_trans",
            "manipulability_rot",
            "hessian",
            "jacobian_dot",
            "jdot_qdot",
            "det_gradient",
            "manipulability_gradient",
            "manipulability_task_gradient"
        ]
    );
    // Without --qd the rate-dependent values are null; det J = L1 L2 s2 has the gradient
    // (0, L1 L2 c2).
    assert!(v["jacobian_dot"].is_null() && v["jdot_qdot"].is_null());
    let g = v["det_gradient"].as_array().unwrap();
    assert_eq!(g[0].as_f64(), Some(0.0));
    assert!((g[1].as_f64().unwrap() - 0.5f64.cos()).abs() < 1e-15);
    // Planar RRR, task [x, y, rz]: |det Jt| = a1 a2 |s2| = 3.5² |sin 0.5|.
    let v: Value = serde_json::from_str(&stdout(&[
        "eval",
        "planar_rrr",
        "--q",
        "0.3,0.5,-0.2",
        "--json",
    ]))
    .unwrap();
    let want = 3.5 * 3.5 * 0.5f64.sin();
    assert!((v["manipulability_task"].as_f64().unwrap() - want).abs() < 1e-12);
    assert_eq!(v["manipulability"].as_f64().unwrap(), 0.0);
    // UR5: square, so √det(J Jᵀ) = |det J|; no task rows.
    let v: Value = serde_json::from_str(&stdout(&[
        "eval",
        "ur5",
        "--q",
        "0.1,-0.7,1.3,0.4,-2.2,0.9",
        "--json",
    ]))
    .unwrap();
    let (w, det) = (
        v["manipulability"].as_f64().unwrap(),
        v["det"].as_f64().unwrap(),
    );
    assert!((w - det.abs()).abs() < 1e-12, "{w} vs |{det}|");
    assert!(v["manipulability_task"].is_null());
}

/// `--qd` adds `jacobian_dot` and `jdot_qdot`; every second-order value equals the
/// numeric reference (cross products of the joint axes, velocity/acceleration
/// propagation, central differences), within 1e-12 for closed forms and 1e-7 for
/// differences (h = 1e-5 on metre-sized arms).
#[test]
fn eval_second_order_matches_the_numeric_reference() {
    let cases: [(&str, &[f64], &[f64]); 3] = [
        (
            "ur5",
            &[0.1, -0.7, 1.3, 0.4, -2.2, 0.9],
            &[0.5, -0.3, 0.8, 0.2, -1.0, 0.4],
        ),
        (
            "panda",
            &[0.1, -0.4, 0.2, -2.0, 0.3, 1.6, 0.7],
            &[0.3, 0.2, -0.4, 0.5, 0.1, -0.2, 0.6],
        ),
        ("scara", &[0.5, -0.4, 0.1, 0.7], &[0.2, -0.6, 0.05, 1.0]),
    ];
    let list = |x: &[f64]| {
        x.iter()
            .map(|v| v.to_string())
            .collect::<Vec<_>>()
            .join(",")
    };
    for (name, q, qd) in cases {
        let text = stdout(&["eval", name, "--q", &list(q), "--qd", &list(qd), "--json"]);
        let v: Value = serde_json::from_str(&text).unwrap();
        let (robot, _) = toml_file::load_file(&robot_file(name)).unwrap();
        let n = robot.dof();
        let reference = numeric::NumericRobot::new(&robot).unwrap();
        let h = reference.hessian(q).unwrap();
        let hs = v["hessian"].as_array().unwrap();
        assert_eq!(hs.len(), n, "{name}");
        for (k, hk) in hs.iter().enumerate() {
            assert_close(name, &matrix(hk), |r, c| h[k][(r, c)], 6, n);
        }
        let jd = reference.jacobian_dot_fd(q, qd, 1e-5).unwrap();
        let got = matrix(&v["jacobian_dot"]);
        for r in 0..6 {
            for c in 0..n {
                assert!((got[r][c] - jd[(r, c)]).abs() < 1e-7, "{name} J̇[{r}][{c}]");
            }
        }
        let a = reference.jdot_qdot_propagation(q, qd).unwrap();
        let got: Vec<f64> = v["jdot_qdot"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert_close(name, &[got], |_, c| a[c], 1, 6);
        let j = reference.jacobian(q).unwrap();
        let jm = nalgebra::DMatrix::from_fn(6, n, |r, c| j[(r, c)]);
        let hm: Vec<_> = h
            .iter()
            .map(|hk| nalgebra::DMatrix::from_fn(6, n, |r, c| hk[(r, c)]))
            .collect();
        let want = numeric::manipulability_gradient(&jm, &hm);
        let got: Vec<f64> = v["manipulability_gradient"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert_close(name, &[got], |_, c| want[c], 1, n);
        assert_eq!(v["det_gradient"].is_null(), n == 7, "{name}");
        assert_eq!(
            v["manipulability_task_gradient"].is_null(),
            robot.task.is_none(),
            "{name}"
        );
    }
}

#[test]
fn eval_table_shows_the_second_order_values() {
    let t = stdout(&["eval", "planar_rr", "--q", "0.3,0.5", "--qd", "1,-1"]);
    assert!(t.contains("hessian H[1] = ∂J/∂q2"), "{t}");
    assert!(t.contains("jacobian_dot (world frame)"), "{t}");
    assert!(t.contains("jdot_qdot "), "{t}");
    assert!(t.contains("manipulability_task_gradient "), "{t}");
    let t = stdout(&["eval", "planar_rr", "--q", "0.3,0.5"]);
    assert!(
        t.contains("jacobian_dot, jdot_qdot: give the joint rates with --qd"),
        "{t}"
    );
}

#[test]
fn eval_table_is_readable() {
    let t = stdout(&["eval", "planar_rr", "--q", "0.3,0.5"]);
    assert!(t.starts_with("planar RR at q = [0.3, 0.5]"), "{t}");
    assert!(t.contains("   vx    -1.012876    -0.717356"), "{t}");
    assert!(t.contains("  all rows (J)         0.000000000000"), "{t}");
    assert!(t.contains("  task rows (J_task)   0.479425538604"), "{t}");
}

#[test]
fn stats_counts_are_the_generated_code_s() {
    let v: Value = serde_json::from_str(&stdout(&["stats", "ur5", "--json"])).unwrap();
    let (robot, options) = toml_file::load_file(&robot_file("ur5")).unwrap();
    let g = generate(&robot.chain(), &ItemHeader::public(&robot.name), &options);
    for (key, ops) in [("fk", g.stats.fk), ("jacobian", g.stats.jacobian)] {
        let o = &v[key];
        let get = |k: &str| o[k].as_u64().unwrap() as usize;
        assert_eq!(
            [
                get("add"),
                get("mul"),
                get("div"),
                get("neg"),
                get("trig"),
                get("total")
            ],
            [ops.add, ops.mul, ops.div, ops.neg, ops.trig, ops.total()],
            "{key}"
        );
        assert_eq!(
            get("total"),
            get("add") + get("mul") + get("div") + get("neg")
        );
    }
    // One sin_cos per joint at most.
    assert!(v["fk"]["trig"].as_u64().unwrap() <= 6);
    assert!(v["det"].is_null() || v["det"]["total"].is_u64());
    assert!(v["time_ms"].as_f64().unwrap() > 0.0);
    // The stages are disjoint laps inside the timed `generate`: each is positive (UR5 has
    // every stage, IK included) and together they do not exceed the whole.
    let stages = &v["stages_ms"];
    let stage = |k: &str| {
        stages[k]
            .as_f64()
            .unwrap_or_else(|| panic!("{k}: {stages}"))
    };
    let parts = ["order", "det", "second_order", "ik", "emit", "print"];
    for k in parts.iter().chain(&["ik_emit"]) {
        assert!(stage(k) > 0.0, "{k}: {stages}");
    }
    let sum: f64 = parts.iter().map(|k| stage(k)).sum();
    assert!(sum <= v["time_ms"].as_f64().unwrap(), "{stages} vs {v}");
    assert!(stage("ik_emit") <= stage("emit"), "{stages}");
    let table = stdout(&["stats", "ur5"]);
    assert!(
        table.contains(&format!("fk            {:>2}", g.stats.fk.add)),
        "{table}"
    );
    assert!(table.contains("engine time: "), "{table}");
    // The second-order functions, counted as generated.
    for (key, ops) in [
        ("hessian", g.stats.hessian),
        ("jacobian_dot", g.stats.jacobian_dot),
        ("jdot_qdot", g.stats.jdot_qdot),
        ("jacobian_ee_dot", g.stats.jacobian_ee_dot),
        ("det_gradient", g.stats.det_gradient.unwrap()),
    ] {
        assert_eq!(v[key]["total"].as_u64(), Some(ops.total() as u64), "{key}");
        assert!(
            table.contains(&format!("{key:<16}{:>6}", ops.add)),
            "{table}"
        );
    }
}

#[test]
fn missing_file() {
    let e = fails(&["show", "no/such/robot.toml"]);
    assert!(
        e.contains("no/such/robot.toml: cannot read the file"),
        "{e}"
    );
}

#[test]
fn malformed_toml_names_the_line() {
    let dir = std::env::temp_dir().join(format!("kinegen-cli-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "name = \"x\"\nconvention = \n").unwrap();
    let e = fails(&["eval", bad.to_str().unwrap(), "--q", "0"]);
    assert!(e.contains("bad.toml:2: "), "{e}");
    let invalid = dir.join("invalid.toml");
    std::fs::write(
        &invalid,
        "name = \"x\"\nconvention = \"standard\"\n[[joints]]\ntype = \"revolute\"\na = 1\nalpha = 0\nd = \"L9\"\n",
    )
    .unwrap();
    let e = fails(&["show", invalid.to_str().unwrap()]);
    assert!(e.contains("invalid.toml:7: joints[0].d: "), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn wrong_number_of_joint_values() {
    let e = fails(&["eval", "ur5", "--q", "0.1,0.2"]);
    assert_eq!(
        e,
        "kinegen: error: --q: the robot has 6 joints but 2 joint values were given\n"
    );
}

#[test]
fn non_numeric_joint_value() {
    let e = fails(&["eval", "planar_rr", "--q", "0.1,abc"]);
    assert_eq!(
        e,
        "kinegen: error: --q: joint value 2 `abc` is not a number\n"
    );
    let e = fails(&["eval", "planar_rr", "--q", "inf,0"]);
    assert_eq!(
        e,
        "kinegen: error: --q: joint value 1 `inf` is not a finite number\n"
    );
}

#[test]
fn bad_joint_rates() {
    let e = fails(&["eval", "ur5", "--q", "0,0,0,0,0,0", "--qd", "0.1,0.2"]);
    assert_eq!(
        e,
        "kinegen: error: --qd: the robot has 6 joints but 2 joint values were given\n"
    );
    let e = fails(&["eval", "planar_rr", "--q", "0,0", "--qd", "nan,1"]);
    assert_eq!(
        e,
        "kinegen: error: --qd: joint value 1 `nan` is not a finite number\n"
    );
}

#[test]
fn negative_joint_values_are_values_not_flags() {
    stdout(&["eval", "planar_rr", "--q", "-0.1,-0.2"]);
}

#[test]
fn unknown_robot() {
    let e = fails(&["stats", "ur99"]);
    assert!(
        e.starts_with("kinegen: error: unknown robot `ur99`: not a file, and not one of "),
        "{e}"
    );
    assert!(e.contains("planar_rr") && e.contains("puma560"), "{e}");
}

#[test]
fn bad_usage_is_clap_s_exit_2() {
    kinegen()
        .args(["show", "ur5", "--what", "torque"])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("invalid value 'torque'"));
    kinegen()
        .args(["eval", "ur5"])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("--q"));
}
