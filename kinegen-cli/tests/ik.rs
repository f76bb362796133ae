//! `kinegen ik` as a user calls it: poses made by the independent numeric reference's
//! forward kinematics, solved by the binary, every solution checked against that
//! reference again (not against the engine that produced it).

use std::f64::consts::{PI, TAU};
use std::path::PathBuf;

use kinegen::ik::XorShift64;
use kinegen_core::front::toml_file;
use kinegen_core::model::robot::JointKind;
use kinegen_core::numeric::NumericRobot;
use serde_json::Value;

mod common;
use common::{fails, floats, robot_file, solutions_and_flags, stdout};

fn tmp(name: &str, value: &Value) -> PathBuf {
    let path = std::env::temp_dir().join(format!("kinegen-ik-{}-{name}.json", std::process::id()));
    std::fs::write(&path, value.to_string()).unwrap();
    path
}

fn pose_json(t: &nalgebra::Matrix4<f64>) -> Value {
    Value::from(
        (0..4)
            .map(|r| (0..4).map(|c| t[(r, c)]).collect::<Vec<_>>())
            .collect::<Vec<_>>(),
    )
}

/// `max |T_a − T_b|` over the top three rows (rotation and metres alike: the robots'
/// lengths are O(1 m)).
fn distance(a: &nalgebra::Matrix4<f64>, b: &nalgebra::Matrix4<f64>) -> f64 {
    (a - b).fixed_view::<3, 4>(0, 0).amax()
}

/// 40 seeded configurations of each 6-joint robot with a closed form: every listed exact
/// solution reaches the pose (checked by the numeric reference), the configuration that
/// made the pose is among them (modulo 2π), and `near` returns it.
#[test]
fn every_solution_reaches_the_pose_and_the_source_is_among_them() {
    for (name, locked) in [
        ("ur5", None),
        ("ur10e", None),
        ("puma560", None),
        ("stanford", None),
        ("kuka_kr6_r900", None),
        ("abb_irb120", None),
        ("kuka_iiwa14", Some(6)),
        ("panda", Some(6)),
    ] {
        let (robot, _) = toml_file::load_file(&robot_file(name)).unwrap();
        let reference = NumericRobot::new(&robot).unwrap();
        let n = robot.dof();
        let mut rng = XorShift64::new(0x1234_5678 ^ n as u64);
        let mut qs = Vec::new();
        let mut poses = Vec::new();
        for _ in 0..40 {
            let q: Vec<f64> = robot
                .joints
                .iter()
                .map(|j| match (j.kind, j.limits) {
                    (JointKind::Prismatic, Some([lo, hi])) => lo + (hi - lo) * rng.next_f64(),
                    (JointKind::Prismatic, None) => 0.1 + 0.5 * rng.next_f64(),
                    (JointKind::Revolute, limits) => {
                        // Inside the limits: `near` prefers solutions within them.
                        let [lo, hi] = limits.unwrap_or([-PI, PI]);
                        let (lo, hi) = (lo.max(-PI), hi.min(PI));
                        lo + (hi - lo) * rng.next_f64()
                    }
                })
                .collect();
            poses.push(pose_json(&reference.fk(&q).unwrap()));
            qs.push(Value::from(q));
        }
        let poses_file = tmp(&format!("{name}-poses"), &Value::from(poses.clone()));
        let near_file = tmp(&format!("{name}-near"), &Value::from(qs.clone()));
        let mut args = vec!["ik", name, "--json", "--poses"];
        let poses_arg = poses_file.to_string_lossy().into_owned();
        let near_arg = near_file.to_string_lossy().into_owned();
        args.push(&poses_arg);
        args.extend(["--near", &near_arg]);
        let out: Value = serde_json::from_str(&stdout(&args)).unwrap();
        let _ = std::fs::remove_file(&poses_file);
        let _ = std::fs::remove_file(&near_file);
        let results = out.as_array().unwrap();
        assert_eq!(results.len(), 40, "{name}");
        for (i, r) in results.iter().enumerate() {
            let q0 = floats(&qs[i]);
            let t0 = reference.fk(&q0).unwrap();
            let (solutions, exact) = solutions_and_flags(r);
            assert!(!solutions.is_empty(), "{name} pose {i}: no solution");
            let mut found = false;
            for (q, &ex) in solutions.iter().zip(&exact) {
                let mut q = q.clone();
                if let Some(k) = locked {
                    assert!(
                        (q[k] - q0[k]).abs() < 1e-12,
                        "{name}: the locked joint moved"
                    );
                    q[k] = q0[k];
                }
                let d = distance(&reference.fk(&q).unwrap(), &t0);
                if ex {
                    assert!(
                        d < 1e-9,
                        "{name} pose {i}: exact solution {q:?} misses by {d:e}"
                    );
                }
                let same = q.iter().zip(&q0).zip(&robot.joints).all(|((a, b), j)| {
                    let e = a - b;
                    let e = match j.kind {
                        JointKind::Revolute => {
                            e - std::f64::consts::TAU * (e / std::f64::consts::TAU).round()
                        }
                        JointKind::Prismatic => e,
                    };
                    e.abs() < 1e-6
                });
                found |= same;
            }
            assert!(found, "{name} pose {i}: {q0:?} is not among {solutions:?}");
            let near = floats(&r["near"]);
            let d: f64 = near
                .iter()
                .zip(&q0)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(d < 1e-6, "{name} pose {i}: near {near:?} is not {q0:?}");
            assert!(!r["family"].as_str().unwrap().is_empty());
        }
    }
}

/// A pose out of reach: the answers are finite, flagged as not exact, with the residual
/// the reference measures; `near` says there is no exact solution.
#[test]
fn unreachable_pose_gives_flagged_nearest_solutions() {
    let (robot, _) = toml_file::load_file(&robot_file("puma560")).unwrap();
    let reference = NumericRobot::new(&robot).unwrap();
    let pose = "1,0,0,2,0,1,0,0,0,0,1,0,0,0,0,1";
    let out: Value = serde_json::from_str(&stdout(&[
        "ik",
        "puma560",
        "--pose",
        pose,
        "--json",
        "--near",
        "0,0,0,0,0,0",
    ]))
    .unwrap();
    let solutions = out["solutions"].as_array().unwrap();
    assert!(!solutions.is_empty());
    let target = nalgebra::Matrix4::new(
        1.0, 0.0, 0.0, 2.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
    );
    for (k, q) in solutions.iter().enumerate() {
        let q = floats(q);
        assert!(q.iter().all(|x| x.is_finite()));
        assert_eq!(out["exact"][k], Value::Bool(false));
        let measured = distance(&reference.fk(&q).unwrap(), &target);
        let reported = out["residual"][k].as_f64().unwrap();
        assert!(measured > 0.5, "an unreachable pose reached: {measured}");
        assert!(
            (measured - reported).abs() < 1e-9,
            "{measured} vs {reported}"
        );
    }
    assert_eq!(out["near"], Value::Null);
}

/// The planar arms solve their task rows [x, y, θ] or [x, y].
#[test]
fn planar_arm_solves_its_task_rows() {
    let out: Value = serde_json::from_str(&stdout(&[
        "ik",
        "planar_rr",
        "--pose",
        "1,0,0,0.5,0,1,0,0.3,0,0,1,0,0,0,0,1",
        "--json",
    ]))
    .unwrap();
    let (robot, _) = toml_file::load_file(&robot_file("planar_rr")).unwrap();
    let reference = NumericRobot::new(&robot).unwrap();
    let solutions = out["solutions"].as_array().unwrap();
    assert_eq!(solutions.len(), 2);
    for q in solutions {
        let t = reference.fk(&floats(q)).unwrap();
        assert!((t[(0, 3)] - 0.5).abs() < 1e-12 && (t[(1, 3)] - 0.3).abs() < 1e-12);
    }
}

/// A SCARA from its URDF (`robots/urdf/cobra600.urdf`): without task rows no closed form,
/// and the error names the rows that give one; with `--task x,y,z,rz` every seeded
/// configuration within the limits is recovered, each exact solution reaching the pose by
/// the numeric reference of the same arm's DH table (`robots/scara.toml`).
#[test]
fn scara_urdf_solves_the_task_rows_given_on_the_command_line() {
    let urdf = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../robots/urdf/cobra600.urdf");
    let urdf = urdf.to_string_lossy().into_owned();
    let rigid = "1,0,0,0.4,0,-1,0,0.1,0,0,-1,0.3,0,0,0,1";
    let e = fails(&["ik", &urdf, "--pose", rigid]);
    assert!(e.contains("--task x,y,z,rz"), "{e}");
    let e = fails(&["ik", &urdf, "--task", "x,y,w", "--pose", rigid]);
    assert!(e.contains("--task: unknown task row `w`"), "{e}");
    let e = fails(&["ik", &urdf, "--task", "x,y,x,rz", "--pose", rigid]);
    assert!(e.contains("twice"), "{e}");
    let e = fails(&["ik", "scara", "--task", "x,y,z,rz", "--pose", rigid]);
    assert!(e.contains("task = [...]"), "{e}");

    let (robot, _) = toml_file::load_file(&robot_file("scara")).unwrap();
    let reference = NumericRobot::new(&robot).unwrap();
    // The URDF's limits: ±105°, ±145°, the quill 0…0.21 m, the roll unlimited.
    let limits = [[-1.8326, 1.8326], [-2.5307, 2.5307], [0.0, 0.21], [-PI, PI]];
    let mut rng = XorShift64::new(0x5CA2A);
    let qs: Vec<Vec<f64>> = (0..30)
        .map(|_| {
            limits
                .iter()
                .map(|[lo, hi]| lo + (hi - lo) * rng.next_f64())
                .collect()
        })
        .collect();
    let poses: Vec<Value> = qs
        .iter()
        .map(|q| pose_json(&reference.fk(q).unwrap()))
        .collect();
    let poses_file = tmp("cobra600-poses", &Value::from(poses));
    let poses_arg = poses_file.to_string_lossy().into_owned();
    let args = [
        "ik", &urdf, "--task", "x,y,z,rz", "--json", "--poses", &poses_arg,
    ];
    let out: Value = serde_json::from_str(&stdout(&args)).unwrap();
    let _ = std::fs::remove_file(&poses_file);
    let results = out.as_array().unwrap();
    assert_eq!(results.len(), qs.len());
    for (i, (r, q0)) in results.iter().zip(&qs).enumerate() {
        assert_eq!(r["family"], "planar");
        let t0 = reference.fk(q0).unwrap();
        let (solutions, exact) = solutions_and_flags(r);
        let mut found = false;
        for (q, &ex) in solutions.iter().zip(&exact) {
            let d = distance(&reference.fk(q).unwrap(), &t0);
            // The arm spans 0.6 m: 1e-12 of it, with room for a few roundings.
            if ex {
                assert!(d < 1e-12, "pose {i}: exact solution {q:?} misses by {d:e}");
            }
            found |= q.iter().zip(q0).enumerate().all(|(k, (a, b))| {
                let e = a - b;
                let e = if k == 2 {
                    e
                } else {
                    e - TAU * (e / TAU).round()
                };
                e.abs() < 1e-9
            });
        }
        assert!(found, "pose {i}: {q0:?} is not among {solutions:?}");
    }
}

/// The cylindrical arm's position IK from the CLI: both solutions (the reach on either
/// side of axis 1) reach the point, checked by the engine's numeric reference.
#[test]
fn ik_cylindrical_rpp_position() {
    let out: Value = serde_json::from_str(&stdout(&[
        "ik",
        "cylindrical_rpp",
        "--pose",
        "1,0,0,0.2,0,1,0,0.3,0,0,1,0.7,0,0,0,1",
        "--json",
    ]))
    .unwrap();
    let (robot, _) = toml_file::load_file(&robot_file("cylindrical_rpp")).unwrap();
    let reference = NumericRobot::new(&robot).unwrap();
    let solutions = out["solutions"].as_array().unwrap();
    assert_eq!(solutions.len(), 2, "{out}");
    for q in solutions {
        let t = reference.fk(&floats(q)).unwrap();
        let p = [t[(0, 3)], t[(1, 3)], t[(2, 3)]];
        assert!(
            (p[0] - 0.2).abs() < 1e-12 && (p[1] - 0.3).abs() < 1e-12 && (p[2] - 0.7).abs() < 1e-12,
            "{p:?}"
        );
    }
}

#[test]
fn show_what_ik_lists_the_derivation() {
    insta::assert_snapshot!("show_ik_ur5", stdout(&["show", "ur5", "--what", "ik"]));
    // Read from the tool, joint 7 free by default; every joint that would do is listed.
    insta::assert_snapshot!("show_ik_panda", stdout(&["show", "panda", "--what", "ik"]));
    // Three joints placing the tool point: the cylindrical arm.
    insta::assert_snapshot!(
        "show_ik_cylindrical_rpp",
        stdout(&["show", "cylindrical_rpp", "--what", "ik"])
    );
    // Five joints: the position first, the approach in the arm's plane, the roll.
    insta::assert_snapshot!(
        "show_ik_widowx250",
        stdout(&["show", "widowx250", "--what", "ik"])
    );
    let text = stdout(&["show", "panda", "--what", "ik", "--free", "6"]);
    assert!(text.contains("(joint 6 locked)"), "{text}");
    // Joint 2 locked leaves no family of subproblems either way: the general 6R.
    let text = stdout(&["show", "panda", "--what", "ik", "--free", "2"]);
    assert!(
        text.contains("general 6R (Raghavan–Roth elimination, eigenvalues) (joint 2 locked)")
            && text.contains("joints 1, 3 with the general 6R"),
        "{text}"
    );
    // The elbow locked: the six others, read from the tool, are a spherical wrist after
    // three skew axes (SP5).
    let text = stdout(&["show", "panda", "--what", "ik", "--free", "4"]);
    assert!(
        text.contains("spherical wrist, general arm (SP5), read from the tool (joint 4 locked)"),
        "{text}"
    );
}

/// `--free`, and `free_joint` / `free_value` in the JSON of a 7-joint arm.
#[test]
fn the_free_joint_is_chosen_and_reported() {
    let q = [0.3, -0.5, 0.4, -1.9, 0.2, 1.5, 0.7];
    let (robot, _) = toml_file::load_file(&robot_file("panda")).unwrap();
    let reference = NumericRobot::new(&robot).unwrap();
    let t = reference.fk(&q).unwrap();
    let pose: Vec<String> = (0..4)
        .flat_map(|i| (0..4).map(move |j| (i, j)))
        .map(|(i, j)| t[(i, j)].to_string())
        .collect();
    let pose = pose.join(",");
    for (free, value) in [("7", q[6]), ("6", q[5])] {
        let out: Value = serde_json::from_str(&stdout(&[
            "ik",
            "panda",
            "--pose",
            &pose,
            "--free",
            free,
            "--locked",
            &value.to_string(),
            "--json",
        ]))
        .unwrap();
        assert_eq!(out["free_joint"], free.parse::<u64>().unwrap(), "{out}");
        assert_eq!(out["free_value"], value, "{out}");
        let found = out["solutions"]
            .as_array()
            .unwrap()
            .iter()
            .any(|s| floats(s).iter().zip(q).all(|(a, b)| (a - b).abs() < 1e-9));
        assert!(found, "--free {free}: {out}");
    }
    // The iiwa by its arm angle: eight exact solutions, `arm_angle` in the JSON.
    let (iiwa, _) = toml_file::load_file(&robot_file("kuka_iiwa14")).unwrap();
    let t = NumericRobot::new(&iiwa).unwrap().fk(&q).unwrap();
    let iiwa_pose: Vec<String> = (0..4)
        .flat_map(|i| (0..4).map(move |j| (i, j)))
        .map(|(i, j)| t[(i, j)].to_string())
        .collect();
    let iiwa_pose = iiwa_pose.join(",");
    let out: Value = serde_json::from_str(&stdout(&[
        "ik",
        "kuka_iiwa14",
        "--pose",
        &iiwa_pose,
        "--arm-angle",
        "0.3",
        "--json",
    ]))
    .unwrap();
    assert_eq!(out["arm_angle"], 0.3, "{out}");
    assert_eq!(out["solutions"].as_array().unwrap().len(), 8, "{out}");
    assert!(
        out["exact"].as_array().unwrap().iter().all(|e| e == true),
        "{out}"
    );
    let e = fails(&["ik", "panda", "--pose", &pose, "--arm-angle", "0.3"]);
    assert!(e.contains("no arm angle"), "{e}");
    let e = fails(&[
        "ik",
        "kuka_iiwa14",
        "--pose",
        &iiwa_pose,
        "--arm-angle",
        "0.3",
        "--locked",
        "0",
    ]);
    assert!(e.contains("give one"), "{e}");
    let e = fails(&["ik", "ur5", "--pose", &pose, "--free", "2"]);
    assert!(e.contains("--free") && e.contains("7-joint"), "{e}");
    let e = fails(&[
        "ik", "panda", "--pose", &pose, "--free", "9", "--locked", "0",
    ]);
    assert!(e.contains("--free") && e.contains("joints 1 to 7"), "{e}");
}

#[test]
fn bad_requests_exit_2_with_a_reason() {
    let rigid = "1,0,0,0.3,0,1,0,0,0,0,1,0.4,0,0,0,1";
    let e = fails(&["ik", "ur5", "--pose", "1,2,3"]);
    assert!(e.contains("16 numbers"), "{e}");
    let e = fails(&["ik", "ur5", "--pose", "1,0,0,0,0,1,0,0,0,0,1,NaN,0,0,0,1"]);
    assert!(e.contains("non-finite"), "{e}");
    let e = fails(&["ik", "ur5", "--pose", "2,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1"]);
    assert!(e.contains("not a rotation"), "{e}");
    let e = fails(&["ik", "ur5", "--pose", "1,0,0,0,0,1,0,0,0,0,1,0,0,0,1,1"]);
    assert!(e.contains("last row"), "{e}");
    let e = fails(&["ik", "stanford", "--pose", rigid, "--free", "3"]);
    assert!(e.contains("7-joint"), "{e}");
    let e = fails(&["ik", "kuka_iiwa14", "--pose", rigid]);
    assert!(e.contains("--locked"), "{e}");
    let e = fails(&["ik", "panda", "--pose", rigid]);
    assert!(e.contains("--locked"), "{e}");
    let e = fails(&["ik", "ur5", "--pose", rigid, "--near", "0,0"]);
    assert!(e.contains("--near"), "{e}");
    let e = fails(&["ik", "ur5"]);
    assert!(e.contains("--pose"), "{e}");
    let bad = std::env::temp_dir().join(format!("kinegen-ik-{}-bad.json", std::process::id()));
    std::fs::write(&bad, "[\n[[1,0,0,0],\n").unwrap();
    let e = fails(&["ik", "ur5", "--poses", &bad.to_string_lossy()]);
    assert!(
        e.contains(":3:") || e.contains(":2:"),
        "the file's line: {e}"
    );
    std::fs::write(&bad, "[[1,0,0,0]]").unwrap();
    let e = fails(&["ik", "ur5", "--poses", &bad.to_string_lossy()]);
    assert!(e.contains("pose 0"), "{e}");
    let _ = std::fs::remove_file(&bad);
}

/// The WidowX 250's forward kinematics as its URDF writes the joints (`robots/urdf/
/// wx250.urdf`: frames parallel at q = 0), written out here apart from the engine.
fn widowx250_fk(q: &[f64]) -> nalgebra::Matrix4<f64> {
    use kinegen_core::numeric::{rot_x, rot_y, rot_z, trans};
    trans(0.0, 0.0, 0.072)
        * rot_z(q[0])
        * trans(0.0, 0.0, 0.03865)
        * rot_y(q[1])
        * trans(0.04975, 0.0, 0.25)
        * rot_y(q[2])
        * trans(0.25, 0.0, 0.0)
        * rot_y(q[3])
        * trans(0.065, 0.0, 0.0)
        * rot_x(q[4])
        * trans(0.093, 0.0, 0.0)
}

/// A 5-joint arm (the WidowX 250, from its URDF): a pose of its own `fk` is reached
/// exactly; the same point with an orientation it cannot take (the gripper level, facing
/// away from the arm's plane) gets every branch on the point, none exact.
#[test]
fn ik_widowx250_position_first() {
    let q = [0.4, -0.3, 0.5, 0.2, -0.7];
    let pose = widowx250_fk(&q);
    let flat: Vec<String> = pose.transpose().iter().map(|x| format!("{x:e}")).collect();
    let out: Value = serde_json::from_str(&stdout(&[
        "ik",
        "widowx250",
        "--pose",
        &flat.join(","),
        "--json",
    ]))
    .unwrap();
    let solutions = out["solutions"].as_array().unwrap();
    let exact = out["exact"].as_array().unwrap();
    assert!(
        solutions
            .iter()
            .zip(exact)
            .any(|(s, e)| e.as_bool().unwrap()
                && floats(s).iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-9)),
        "{out}"
    );
    // Level and facing along y, at a point in front of the arm along x.
    let out: Value = serde_json::from_str(&stdout(&[
        "ik",
        "widowx250",
        "--pose",
        "0,-1,0,0.3,1,0,0,0.05,0,0,1,0.25,0,0,0,1",
        "--json",
    ]))
    .unwrap();
    let solutions = out["solutions"].as_array().unwrap();
    assert_eq!(solutions.len(), 4, "{out}");
    for (q, e) in solutions.iter().zip(out["exact"].as_array().unwrap()) {
        assert!(!e.as_bool().unwrap(), "{out}");
        let t = widowx250_fk(&floats(q));
        let miss = (t[(0, 3)] - 0.3)
            .hypot(t[(1, 3)] - 0.05)
            .hypot(t[(2, 3)] - 0.25);
        assert!(miss < 1e-12, "{q}: the point missed by {miss:e}");
    }
}

/// A Cartesian gantry with a yaw axis (`tests/data/gantry_yaw.toml`, P P P R, task x, y,
/// z, rz): the engine's family, and the configuration of a pose made by the numeric
/// reference found by the binary.
#[test]
fn ik_cartesian_gantry_with_yaw() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/data/gantry_yaw.toml");
    let toml = std::fs::read_to_string(&path).unwrap();
    let file = path.to_str().unwrap();
    let show = stdout(&["show", file, "--what", "ik"]);
    assert!(
        show.contains("position and yaw, Cartesian with a turn about z")
            && show.contains("one solution per pose"),
        "{show}"
    );
    let (robot, _) = toml_file::load_str(&toml, "gantry_yaw.toml").unwrap();
    let reference = NumericRobot::new(&robot).unwrap();
    let q = [0.2, 0.3, 0.4, 0.7];
    let pose = reference.fk(&q).unwrap();
    let flat: Vec<String> = pose.transpose().iter().map(|x| format!("{x:e}")).collect();
    let out: Value =
        serde_json::from_str(&stdout(&["ik", file, "--pose", &flat.join(","), "--json"])).unwrap();
    let solutions = out["solutions"].as_array().unwrap();
    assert_eq!(solutions.len(), 1, "{out}");
    assert!(out["exact"][0].as_bool().unwrap(), "{out}");
    let got = floats(&solutions[0]);
    assert!(
        got.iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-12),
        "{got:?}"
    );
}

/// The Jaco fits no family of subproblems: the general 6R, up to 16 solutions, every one
/// reaching the pose the numeric reference made, the source configuration among them.
#[test]
fn ik_kinova_jaco_general_6r() {
    let show = stdout(&["show", "kinova_jaco", "--what", "ik"]);
    assert!(
        show.contains("general 6R (Raghavan–Roth elimination, eigenvalues)")
            && show.contains("at most 16 solutions per pose"),
        "{show}"
    );
    let (robot, _) = toml_file::load_file(&robot_file("kinova_jaco")).unwrap();
    let reference = NumericRobot::new(&robot).unwrap();
    let q = [0.3, -0.7, 0.4, 1.1, -0.5, 0.8];
    let pose = reference.fk(&q).unwrap();
    let flat: Vec<String> = pose.transpose().iter().map(|x| format!("{x:e}")).collect();
    let out: Value = serde_json::from_str(&stdout(&[
        "ik",
        "kinova_jaco",
        "--pose",
        &flat.join(","),
        "--json",
    ]))
    .unwrap();
    let solutions = out["solutions"].as_array().unwrap();
    assert!(solutions.len() >= 2, "{out}");
    let mut found = false;
    for (i, s) in solutions.iter().enumerate() {
        let got = floats(s);
        assert!(out["exact"][i].as_bool().unwrap(), "{out}");
        assert!(
            distance(&reference.fk(&got).unwrap(), &pose) < 1e-10,
            "{got:?}"
        );
        found |= got.iter().zip(&q).all(|(a, b)| {
            let d = a - b;
            (d - std::f64::consts::TAU * (d / std::f64::consts::TAU).round()).abs() < 1e-9
        });
    }
    assert!(found, "{out}");
}
