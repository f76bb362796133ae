//! `kinegen reach`: the map against brute force (the runtime's numerical IK from many
//! starts on the compiled robots), the same map however it is computed, the file read
//! back, base placement, and the bad requests.

use std::path::PathBuf;

use kinegen::ik::{solve_nearest, IkOptions, IkTarget, MultiStart};
use kinegen::Kinematics;
use kinegen_cli::ik::Solver;
use kinegen_cli::reach::npz::{self, Array};
use kinegen_cli::reach::{map, Grid, Map, Orientations, Settings};
use kinegen_cli::{robots, UrdfArgs};
use kinegen_core::derive;
use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion};

mod common;
use common::{fails, stdout};

fn tmp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("kinegen-reach-{}-{name}", std::process::id()))
}

fn map_of(robot: &str, grid: Grid, orientations: Orientations, skip: bool, threads: usize) -> Map {
    map_with(robot, grid, orientations, skip, threads, true)
}

fn map_with(
    robot: &str,
    grid: Grid,
    orientations: Orientations,
    skip: bool,
    threads: usize,
    roll_symmetry: bool,
) -> Map {
    let (chain, options) = robots::load(robot, &UrdfArgs::default()).unwrap();
    let derived = derive(&chain, &options);
    let settings = Settings {
        grid,
        orientations,
        free_samples: 4,
        skip,
        threads: Some(threads),
        progress: false,
        roll_symmetry,
    };
    map::compute(&chain, &derived, &settings).unwrap()
}

/// Every pose of the map (voxel index, pose index, world pose) of a coarse grid.
fn poses_of(m: &Map) -> Vec<(usize, usize, Isometry3<f64>)> {
    let g = &m.settings.grid;
    let spread = m.settings.orientations.offset_radius(g.resolution);
    let mut out = Vec::new();
    for i in 0..g.len() {
        let c = g.centre(i);
        for (j, rel) in m.poses.iter().enumerate() {
            let r = Matrix3::from_fn(|a, b| rel.rotation[a][b]);
            let t = Translation3::new(
                c[0] + spread * rel.offset[0],
                c[1] + spread * rel.offset[1],
                c[2] + spread * rel.offset[2],
            );
            let rot = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(r));
            out.push((i, j, Isometry3::from_parts(t, rot)));
        }
    }
    out
}

/// The map against brute force: every pose the numerical IK reaches from 8 starts
/// (within the limits) is reachable in the map, so each voxel's reachability index is
/// at least the brute-force count, and above it only by the numerical solver's own
/// misses, which are counted and must stay a small share. The generated code the
/// numerical IK calls is unoptimised in tests: one pose in `stride` of each voxel.
fn against_brute_force<R: Kinematics<6>>(name: &str, robot: &R, resolution: f64, stride: usize) {
    let m = map_of(
        name,
        Grid::reuleaux(resolution).unwrap(),
        Orientations::Reuleaux,
        true,
        2,
    );
    let options = IkOptions {
        max_iterations: 60,
        ..IkOptions::default()
    };
    let multi = MultiStart {
        starts: 8,
        rng_seed: 7,
        stop_at_first: true,
    };
    let (chain, engine_options) = robots::load(name, &UrdfArgs::default()).unwrap();
    let derived = derive(&chain, &engine_options);
    let solver = Solver::new(&chain, &derived).unwrap();
    let (mut both, mut numeric_misses, mut map_misses) = (0, 0, 0);
    let mut ri_numeric = vec![0u32; m.voxels.len()];
    let mut ri_map = vec![0u32; m.voxels.len()];
    for (i, j, pose) in poses_of(&m) {
        if m.voxels[i].skipped || (i + j) % stride != 0 {
            continue;
        }
        let in_map = m.voxels[i].mask & (1 << j) != 0;
        let numeric =
            solve_nearest(robot, &IkTarget::Pose(pose), &[0.1; 6], &options, &multi).is_ok();
        match (in_map, numeric) {
            (true, true) => both += 1,
            (true, false) => {
                numeric_misses += 1;
                // A genuine miss of the numerical solver: the closed form's solution
                // reaches the pose in the compiled robot's own `fk`.
                assert!(
                    reached_in_compiled_fk(&solver, robot, &pose),
                    "{name}: {pose}"
                );
            }
            (false, true) => map_misses += 1,
            (false, false) => {}
        }
        ri_numeric[i] += u32::from(numeric);
        ri_map[i] += u32::from(in_map);
    }
    eprintln!(
        "{name} at {resolution} m, one pose in {stride}: {both} poses reached by both, {numeric_misses} by the map only (numerical misses), {map_misses} by the numerical IK only"
    );
    assert_eq!(map_misses, 0, "{name}: poses the map misses");
    assert!(both > 300, "{name}: a meaningful sample ({both})");
    assert!(
        numeric_misses * 5 < both,
        "{name}: the numerical reference misses {numeric_misses} of {}",
        both + numeric_misses
    );
    for (i, v) in m.voxels.iter().enumerate() {
        assert!(ri_map[i] >= ri_numeric[i]);
        assert_eq!(v.reachable, v.mask.count_ones());
    }
}

/// Some exact solution within the limits of the closed form (the map's solver) puts the
/// compiled robot's tool at `pose`, to 1e-9 of the arm's metre scale.
fn reached_in_compiled_fk<R: Kinematics<6>>(
    solver: &Solver,
    robot: &R,
    pose: &Isometry3<f64>,
) -> bool {
    let m = pose.to_homogeneous();
    let target: [[f64; 4]; 4] = std::array::from_fn(|r| std::array::from_fn(|c| m[(r, c)]));
    let r = solver.solve(target, None, None, None).unwrap();
    r.branches
        .iter()
        .filter(|b| b.flags.exact && b.flags.within_limits)
        .any(|b| {
            let q: [f64; 6] = b.q.clone().try_into().unwrap();
            let t = robot.fk(&q);
            (0..3).all(|i| (0..4).all(|j| (t[i][j] - target[i][j]).abs() < 1e-9))
        })
}

#[test]
fn ur5_map_against_brute_force() {
    against_brute_force("ur5", &kinegen_robots::Ur5::default(), 0.3, 4);
}

#[test]
fn puma560_map_against_brute_force() {
    against_brute_force("puma560", &kinegen_robots::Puma560::default(), 0.3, 8);
}

/// Skipping the voxels outside the reach sphere changes nothing but the time; neither
/// does the thread count.
#[test]
fn skipping_and_threads_leave_the_map_unchanged() {
    let grid = || Grid::reuleaux(0.25).unwrap();
    let skipped = map_of("ur5", grid(), Orientations::Reuleaux, true, 1);
    let solved = map_of("ur5", grid(), Orientations::Reuleaux, false, 2);
    assert!(
        skipped.ik_calls < solved.ik_calls / 2,
        "{} {}",
        skipped.ik_calls,
        solved.ik_calls
    );
    let strip = |m: &Map| -> Vec<map::Voxel> {
        m.voxels
            .iter()
            .map(|v| map::Voxel {
                skipped: false,
                ..v.clone()
            })
            .collect()
    };
    let a = strip(&skipped);
    let b = strip(&solved);
    assert!(a
        .iter()
        .zip(&b)
        .all(|(x, y)| format!("{x:?}") == format!("{y:?}")));
    let bytes = |m: &Map| {
        let mut buf = std::io::Cursor::new(Vec::new());
        npz::write(&mut buf, &m.arrays()).unwrap();
        buf.into_inner()
    };
    assert_eq!(bytes(&skipped), bytes(&solved));
}

/// Rolls about the approach axis solved once (the last joint turns the tool about it)
/// give the map that solving every roll gives: the same reachable poses and solution
/// counts, the same measures to rounding.
#[test]
fn shared_rolls_give_the_map_of_every_roll() {
    let o = Orientations::Approach {
        directions: 12,
        rolls: 5,
    };
    for robot in ["ur5", "puma560"] {
        let grid = || Grid::reuleaux(0.3).unwrap();
        let shared = map_with(robot, grid(), o.clone(), true, 2, true);
        let every = map_with(robot, grid(), o.clone(), true, 2, false);
        assert_eq!(shared.rolls_shared, 5, "{robot}");
        assert_eq!(every.rolls_shared, 1);
        assert_eq!(shared.ik_calls * 5, every.ik_calls);
        let mut reachable = 0;
        for (a, b) in shared.voxels.iter().zip(&every.voxels) {
            assert_eq!(
                (a.reachable, a.solutions_min, a.solutions_sum, a.mask),
                (b.reachable, b.solutions_min, b.solutions_sum, b.mask),
                "{robot}"
            );
            reachable += a.reachable;
            let close = |x: f64, y: f64| (x.is_nan() && y.is_nan()) || (x - y).abs() <= 1e-9;
            assert!(close(a.manipulability, b.manipulability), "{robot}");
            for (x, y) in a.factor_min.iter().zip(&b.factor_min) {
                assert!(close(*x, *y), "{robot}");
            }
            for (x, y) in a.factor_best.iter().zip(&b.factor_best) {
                assert!(close(*x, *y), "{robot}");
            }
        }
        assert!(reachable > 1000, "{robot}: {reachable}");
    }
}

/// The file as NumPy reads it: Reuleaux's sphere table (x, y, z, reachability) and pose
/// table (centre, position, quaternion), one row per reachable voxel and pose, and the
/// measures alongside.
#[test]
fn npz_has_reuleaux_tables_and_measures() {
    let path = tmp("ur5.npz");
    let out = stdout(&[
        "reach",
        "ur5",
        "--resolution",
        "0.3",
        "-o",
        &path.to_string_lossy(),
        "--threads",
        "2",
    ]);
    assert!(out.contains("map written to"), "{out}");
    let arrays = npz::read(std::fs::File::open(&path).unwrap()).unwrap();
    let _ = std::fs::remove_file(&path);
    let get = |name: &str| arrays.iter().find(|(n, _)| n == name).unwrap().1.clone();
    let Array::F64(shape, spheres) = get("spheres") else {
        panic!()
    };
    assert_eq!(shape[1], 4);
    let v = shape[0];
    assert!(v > 50, "{v} reachable voxels");
    let Array::F32(pshape, poses) = get("poses") else {
        panic!()
    };
    assert_eq!(pshape[1], 10);
    // Rows of the pose table per voxel add up to its reachability index.
    let total: f64 = spheres.chunks(4).map(|s| s[3] / 100.0 * 50.0).sum();
    assert_eq!(total.round() as usize, pshape[0]);
    for p in poses.chunks(10) {
        let q = p[6] * p[6] + p[7] * p[7] + p[8] * p[8] + p[9] * p[9];
        assert!((q - 1.0).abs() < 1e-5, "unit quaternion {p:?}");
        let d = ((p[3] - p[0]).powi(2) + (p[4] - p[1]).powi(2) + (p[5] - p[2]).powi(2)).sqrt();
        assert!((d - 0.3).abs() < 1e-5, "on the voxel's sphere: {d}");
    }
    let Array::Str(names) = get("factor_names") else {
        panic!()
    };
    assert_eq!(
        names,
        [
            "sin(q3)",
            "sin(q5)",
            "a2*cos(q2) + a3*cos(q2+q3) + d5*sin(q2+q3+q4)"
        ]
    );
    let Array::F64(fshape, fmin) = get("factor_min") else {
        panic!()
    };
    let Array::F64(_, fbest) = get("factor_best") else {
        panic!()
    };
    assert_eq!(fshape, [v, 3]);
    assert!(fmin
        .iter()
        .zip(&fbest)
        .all(|(a, b)| a.is_finite() && a <= b));
    let Array::F64(_, w) = get("manipulability") else {
        panic!()
    };
    assert!(w.iter().all(|x| *x > 0.0));
    let Array::U32(_, dims) = get("dims") else {
        panic!()
    };
    assert_eq!(dims, [11, 11, 11]);
}

/// The HDF5 file in Reuleaux's layout (read back with the writer crate's own reader):
/// the same sphere and pose tables as the `.npz`, with the resolution attribute.
#[test]
fn hdf5_has_reuleaux_datasets() {
    let (npz_path, h5_path) = (tmp("same.npz"), tmp("same.h5"));
    for p in [&npz_path, &h5_path] {
        stdout(&[
            "reach",
            "puma560",
            "--resolution",
            "0.3",
            "-o",
            &p.to_string_lossy(),
        ]);
    }
    let arrays = npz::read(std::fs::File::open(&npz_path).unwrap()).unwrap();
    let file = hdf5_pure::File::open(&h5_path).unwrap();
    let _ = std::fs::remove_file(&npz_path);
    let _ = std::fs::remove_file(&h5_path);
    let get = |name: &str| arrays.iter().find(|(n, _)| n == name).unwrap().1.clone();
    let spheres = file.dataset("/Spheres/sphere_dataset").unwrap();
    let Array::F64(shape, data) = get("spheres") else {
        panic!()
    };
    assert_eq!(
        spheres.shape().unwrap(),
        shape.iter().map(|&d| d as u64).collect::<Vec<_>>()
    );
    assert_eq!(spheres.read_f64().unwrap(), data);
    match spheres.attrs().unwrap().get("Resolution") {
        Some(hdf5_pure::AttrValue::F32(r)) => assert_eq!(*r, 0.3f32),
        other => panic!("Resolution attribute: {other:?}"),
    }
    let poses = file.dataset("/Poses/poses_dataset").unwrap();
    let Array::F32(pshape, pdata) = get("poses") else {
        panic!()
    };
    assert_eq!(
        poses.shape().unwrap(),
        pshape.iter().map(|&d| d as u64).collect::<Vec<_>>()
    );
    assert_eq!(poses.read_f32().unwrap(), pdata);
    let Array::F64(_, w) = get("manipulability") else {
        panic!()
    };
    assert_eq!(
        file.dataset("/kinegen/manipulability")
            .unwrap()
            .read_f64()
            .unwrap(),
        w
    );
}

/// Base placement: a task made by the UR5 standing at a known point is reachable from
/// there; every position returned reaches every pose; a task wider than the arm has none.
#[test]
fn inverse_finds_the_base_that_made_the_task() {
    let ur5 = kinegen_robots::Ur5::default();
    let base = [0.4, -0.2, 0.0];
    let qs = [
        [0.3, -1.2, 1.4, -0.5, 1.2, 0.3],
        [-0.8, -0.9, 1.1, 0.4, -1.0, 2.0],
        [1.9, -2.1, 0.7, 1.0, 0.8, -0.6],
    ];
    let task: Vec<_> = qs
        .iter()
        .map(|q| {
            let mut t = ur5.fk(q);
            for k in 0..3 {
                t[k][3] += base[k];
            }
            t
        })
        .collect();
    let (chain, options) = robots::load("ur5", &UrdfArgs::default()).unwrap();
    let derived = derive(&chain, &options);
    let found =
        kinegen_cli::reach::inverse::placements(&chain, &derived, &task, 0.0, 0.1, 1, Some(2))
            .unwrap();
    assert!(
        found
            .iter()
            .any(|p| (p.position[0] - base[0]).abs() < 1e-9
                && (p.position[1] - base[1]).abs() < 1e-9),
        "the base that made the task is on the grid and reaches it"
    );
    for w in found.windows(2) {
        assert!(w[0].worst_manipulability >= w[1].worst_manipulability);
    }
    let far: Vec<_> = [0.0, 5.0]
        .iter()
        .map(|x| {
            let mut t = task[0];
            t[0][3] += x;
            t
        })
        .collect();
    assert!(
        kinegen_cli::reach::inverse::placements(&chain, &derived, &far, 0.0, 0.2, 1, Some(2))
            .unwrap()
            .is_empty()
    );
}

#[test]
fn bad_requests_exit_2_and_leave_no_file() {
    for res in ["0", "-0.1", "nan"] {
        let e = fails(&["reach", "ur5", "--resolution", res]);
        assert!(e.contains("--resolution"), "{e}");
    }
    let e = fails(&["reach", "ur5", "--orientations", "7"]);
    assert!(e.contains("--orientations"), "{e}");
    let e = fails(&["reach", "ur5", "--box", "0,0,0,1,1"]);
    assert!(e.contains("6 numbers"), "{e}");
    let missing = tmp("no-such-dir").join("map.npz");
    let e = fails(&["reach", "ur5", "-o", &missing.to_string_lossy()]);
    assert!(e.contains("no directory"), "{e}");
    let csv = tmp("map.csv");
    let e = fails(&["reach", "ur5", "-o", &csv.to_string_lossy()]);
    assert!(e.contains(".npz") && e.contains(".h5"), "{e}");
    assert!(!csv.exists());
    // An 8-joint chain has no closed form.
    let toml = tmp("eight.toml");
    let mut src = String::from("name = \"eight\"\nconvention = \"standard\"\n");
    for i in 0..8 {
        src.push_str(&format!(
            "[[joints]]\ntype = \"revolute\"\na = 0.{}\nalpha = 0.{}\nd = 0.1\n",
            i + 1,
            i + 2
        ));
    }
    std::fs::write(&toml, src).unwrap();
    let out = tmp("eight.npz");
    let e = fails(&[
        "reach",
        &toml.to_string_lossy(),
        "-o",
        &out.to_string_lossy(),
    ]);
    let _ = std::fs::remove_file(&toml);
    assert!(e.contains("no closed-form inverse kinematics"), "{e}");
    assert!(!out.exists());
}
