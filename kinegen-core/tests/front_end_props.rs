//! The fuzz targets' properties in the normal test run, on proptest's budget (issue 8):
//! arbitrary text and mutated robot files never panic the TOML front end, and whatever
//! loads generates code without an internal error that computes what the numeric
//! reference computes (the oracle is `fuzz/src/check.rs`, shared with `cargo fuzz`).

#[allow(dead_code)]
#[path = "../../fuzz/src/check.rs"]
mod check;

use check::Outcome;
use proptest::prelude::*;
#[path = "common/fixed_seed.rs"]
mod fixed_seed;
use fixed_seed::fixed_seed;

const Q: [f64; 8] = [0.3, -1.1, 0.7, 2.0, -0.4, 1.3, 0.2, -2.5];

/// Small tables of `robots/` to mutate (the large ones cost too much per case in a debug
/// build; `cargo fuzz` starts from all of them).
fn seeds() -> Vec<String> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../robots");
    [
        "planar_rr",
        "planar_rrr",
        "scara",
        "cylindrical_rpp",
        "stanford",
        "ur5",
    ]
    .iter()
    .map(|n| std::fs::read_to_string(dir.join(format!("{n}.toml"))).unwrap())
    .collect()
}

/// Replacements a mutation can put in place of a line's value: valid and invalid
/// numbers, expressions, names, types.
const VALUES: &[&str] = &[
    "0",
    "1",
    "-1",
    "0.5",
    "1e308",
    "-1e308",
    "1e-320",
    "nan",
    "inf",
    "-inf",
    "\"pi/2\"",
    "\"-pi/3\"",
    "\"0.7\"",
    "\"2*pi\"",
    "\"a2\"",
    "\"L1\"",
    "\"q1\"",
    "\"pi/0\"",
    "\"1/0\"",
    "\"sqrt(2)\"",
    "\"(((\"",
    "\"\"",
    "\"revolute\"",
    "\"prismatic\"",
    "\"spherical\"",
    "\"standard\"",
    "\"modified\"",
    "[1, 2]",
    "[\"-pi\", \"pi\"]",
    "[2, 1]",
    "[]",
    "{}",
    "true",
    "1979-05-27",
    "\"x\"",
    "[\"x\", \"x\"]",
    "[\"x\", \"y\", \"rz\"]",
    "99999999999999999999",
];

#[derive(Clone, Debug)]
enum Mutation {
    DeleteLine(usize),
    DuplicateLine(usize),
    SwapLines(usize, usize),
    ReplaceValue(usize, usize),
    InsertLine(usize, usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let line = any::<usize>();
    prop_oneof![
        line.prop_map(Mutation::DeleteLine),
        line.prop_map(Mutation::DuplicateLine),
        (line, any::<usize>()).prop_map(|(a, b)| Mutation::SwapLines(a, b)),
        (line, 0..VALUES.len()).prop_map(|(l, v)| Mutation::ReplaceValue(l, v)),
        (line, 0..VALUES.len()).prop_map(|(l, v)| Mutation::InsertLine(l, v)),
    ]
}

fn apply(src: &str, mutations: &[Mutation]) -> String {
    let mut lines: Vec<String> = src.lines().map(str::to_string).collect();
    for m in mutations {
        if lines.is_empty() {
            break;
        }
        let n = lines.len();
        match *m {
            Mutation::DeleteLine(i) => {
                lines.remove(i % n);
            }
            Mutation::DuplicateLine(i) => {
                let l = lines[i % n].clone();
                lines.insert(i % n, l);
            }
            Mutation::SwapLines(a, b) => lines.swap(a % n, b % n),
            Mutation::ReplaceValue(i, v) => {
                let l = &mut lines[i % n];
                if let Some(eq) = l.find('=') {
                    *l = format!("{} {}", &l[..=eq], VALUES[v]);
                }
            }
            Mutation::InsertLine(i, v) => {
                let keys = [
                    "a", "d", "alpha", "theta", "offset", "limits", "task", "nodes", "L1",
                ];
                lines.insert(i % n, format!("{} = {}", keys[v % keys.len()], VALUES[v]));
            }
        }
    }
    lines.join("\n")
}

proptest! {
    #![proptest_config(fixed_seed(256))]
    #[test]
    fn arbitrary_text_never_panics(src in "\\PC{0,200}") {
        check::toml(&src, &Q);
    }

    #[test]
    fn toml_like_text_never_panics(src in "([a-z_\\[\\]]{1,8} = [-0-9a-z\"/*.\\[\\], ]{0,12}\n){0,12}") {
        check::toml(&src, &Q);
    }
}

/// Mutated robot files: each loads or fails with a located message; each that loads is
/// generated and compared. Every case costs a generation in a debug build: few cases, and
/// both outcomes must occur (or the property tests nothing).
#[test]
fn mutated_robot_files_load_or_fail_cleanly_and_generate_correct_code() {
    use proptest::test_runner::TestRunner;
    use std::cell::Cell;
    let seeds = seeds();
    let (checked, rejected) = (Cell::new(0), Cell::new(0));
    // The fixed seed: the same 48 files every run, so the counts below are stable.
    let mut runner = TestRunner::new(fixed_seed(48));
    runner
        .run(
            &(0..seeds.len(), prop::collection::vec(mutation(), 1..4)),
            |(seed, mutations)| {
                let src = apply(&seeds[seed], &mutations);
                match check::toml(&src, &Q) {
                    Outcome::Checked => checked.set(checked.get() + 1),
                    Outcome::Rejected => rejected.set(rejected.get() + 1),
                    Outcome::Generated => {}
                }
                Ok(())
            },
        )
        .unwrap();
    eprintln!(
        "mutated files: {} checked, {} rejected",
        checked.get(),
        rejected.get()
    );
    assert!(
        checked.get() >= 5 && rejected.get() >= 5,
        "{} checked, {} rejected",
        checked.get(),
        rejected.get()
    );
}

/// The unmutated seeds load and check (so the property above starts from valid files).
#[test]
fn the_seed_files_are_checked() {
    for src in seeds() {
        assert_eq!(check::toml(&src, &Q), Outcome::Checked);
    }
}
