//! Every robot in `robots/*.toml` loads, its `# home:` poses match the numeric
//! reference, and its three numeric Jacobians (axes, finite differences, velocity
//! propagation) agree at random configurations within the joint limits.

mod common;
use common::robot_files;

use kinegen_core::front::toml_file::load_file;
use kinegen_core::numeric::NumericRobot;
use proptest::prelude::*;
use proptest::test_runner::TestRunner;
#[path = "common/fixed_seed.rs"]
mod fixed_seed;
use fixed_seed::fixed_seed;

/// A `# home: q = [...], position = [...]` line (see robots/README.md).
#[derive(Debug)]
struct Home {
    q: Vec<f64>,
    position: [f64; 3],
}

fn list_after(line: &str, key: &str) -> Result<Vec<f64>, String> {
    let start = line.find(key).ok_or(format!("no `{key}` in `{line}`"))? + key.len();
    let rest = line[start..].trim_start();
    let rest = rest
        .strip_prefix('[')
        .ok_or(format!("`{key}` not followed by `[`"))?;
    let end = rest.find(']').ok_or("unclosed `[`")?;
    rest[..end]
        .split(',')
        .map(|x| x.trim().parse::<f64>().map_err(|e| format!("`{x}`: {e}")))
        .collect()
}

fn homes(src: &str) -> Result<Vec<Home>, String> {
    src.lines()
        .filter_map(|l| l.strip_prefix("# home:"))
        .map(|l| {
            let q = list_after(l, "q =")?;
            let p = list_after(l, "position =")?;
            let position: [f64; 3] = p.try_into().map_err(|_| "position needs 3 numbers")?;
            Ok(Home { q, position })
        })
        .collect()
}

#[test]
fn all_expected_robots_are_present() {
    let names: Vec<String> = robot_files()
        .iter()
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    for want in [
        "planar_rr",
        "planar_rrr",
        "ur3",
        "ur5",
        "ur10",
        "ur5e",
        "ur10e",
        "puma560",
        "stanford",
        "panda",
        "kuka_iiwa14",
        "kuka_kr6_r900",
        "abb_irb120",
        "abb_irb140",
        "scara",
        "cylindrical_rpp",
        "kinova_jaco",
    ] {
        assert!(
            names.iter().any(|n| n == want),
            "robots/{want}.toml missing"
        );
    }
}

#[test]
fn every_file_loads_and_cites_a_source() {
    for path in robot_files() {
        let src = std::fs::read_to_string(&path).unwrap();
        assert!(
            src.starts_with('#'),
            "{}: must open with comments",
            path.display()
        );
        assert!(
            src.to_lowercase().contains("source"),
            "{}: no source cited",
            path.display()
        );
        if let Err(e) = load_file(&path) {
            panic!("{}: {e}", path.display());
        }
    }
}

#[test]
fn home_poses_match_the_reference() {
    let mut checked = 0;
    for path in robot_files() {
        let src = std::fs::read_to_string(&path).unwrap();
        let (robot, _) = load_file(&path).unwrap();
        let model = NumericRobot::new(&robot).unwrap();
        let homes = homes(&src).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        for home in homes {
            let t = model
                .fk(&home.q)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            let got = [t[(0, 3)], t[(1, 3)], t[(2, 3)]];
            for k in 0..3 {
                assert!(
                    (got[k] - home.position[k]).abs() < 1e-9,
                    "{}: fk({:?}) = {got:?}, file says {:?}",
                    path.display(),
                    home.q,
                    home.position
                );
            }
            checked += 1;
        }
    }
    assert!(checked >= 16, "only {checked} home poses checked");
}

#[test]
fn jacobians_agree_within_the_joint_limits() {
    for path in robot_files() {
        let (robot, _) = load_file(&path).unwrap();
        let model = NumericRobot::new(&robot).unwrap();
        // Sample inside the limits; ±π (or ±0.5 m for a prismatic joint) where none.
        let ranges: Vec<(f64, f64)> = robot
            .joints
            .iter()
            .map(|j| match (j.limits, j.kind) {
                (Some([lo, hi]), _) => (lo, hi),
                (None, kinegen_core::model::robot::JointKind::Revolute) => {
                    (-std::f64::consts::PI, std::f64::consts::PI)
                }
                (None, kinegen_core::model::robot::JointKind::Prismatic) => (-0.5, 0.5),
            })
            .collect();
        let strategy = proptest::collection::vec(0.0..1.0f64, ranges.len());
        let mut runner = TestRunner::new(fixed_seed(64));
        let result = runner.run(&strategy, |u| {
            let q: Vec<f64> = u
                .iter()
                .zip(&ranges)
                .map(|(t, (lo, hi))| lo + t * (hi - lo))
                .collect();
            let j = model.jacobian(&q).unwrap();
            let fd = model.jacobian_fd(&q, 1e-5).unwrap();
            let prop = model.jacobian_propagation(&q).unwrap();
            prop_assert!(
                (&j - &fd).amax() < 1e-7,
                "FD differs by {:e} at {q:?}",
                (&j - &fd).amax()
            );
            prop_assert!(
                (&j - &prop).amax() < 1e-12,
                "propagation differs by {:e} at {q:?}",
                (&j - &prop).amax()
            );
            Ok(())
        });
        if let Err(e) = result {
            panic!("{}: {e}", path.display());
        }
    }
}
