//! The URDF reader under mutation (issue 32): 10 000 mutants of the shipped URDF files —
//! elements deleted or duplicated, parents and children swapped, links renamed, joint
//! types changed, numbers made huge, tiny, negative or not numbers, odd whitespace and
//! unicode, truncations, deep link trees — through the CLI's loader (`Urdf::parse`, then
//! `kinegen_cli::robots::urdf_chain`, as `kinegen … robot.urdf` does). None may panic;
//! every refusal names the file and a line; about one in 5 of the mutants that still
//! describe a chain is generated and its model compared with a numeric reference computed from
//! the parsed joints (`fuzz/src/urdf_check.rs`, the fuzz target's own oracle).
//!
//! Mutants come from a fixed-seed generator: every run checks the same ones.

#[allow(dead_code)]
#[path = "../../fuzz/src/urdf_check.rs"]
mod urdf_check;

use std::panic::{catch_unwind, AssertUnwindSafe};

use kinegen::ik::XorShift64;
use kinegen_cli::error::CliError;
use kinegen_cli::robots::{urdf_chain, UrdfArgs};
use kinegen_core::front::urdf::Urdf;
use urdf_check::{load_and_check, UrdfOutcome};

/// The runtime's seeded generator, with the two draws the mutator needs.
struct Rng(XorShift64);

impl Rng {
    fn below(&mut self, n: usize) -> usize {
        (self.0.next_u64() % n.max(1) as u64) as usize
    }

    fn pick<'a, T>(&mut self, xs: &'a [T]) -> &'a T {
        &xs[self.below(xs.len())]
    }
}

const NUMBERS: &[&str] = &[
    "1e300",
    "-1e300",
    "1e-300",
    "-0",
    "0",
    "NaN",
    "inf",
    "-inf",
    "1.5708",
    "-3.14159",
    "1e9",
    "12345678901234567890",
    "0x10",
    "1,5",
    "",
    "--1",
    "1e",
    ".",
    "+.5",
    "1 2",
    "٣",
];

const ODD: &[&str] = &[
    "\t",
    "\u{a0}",
    "\u{200b}",
    "é",
    "\u{feff}",
    "\r\n",
    "日本",
    "\u{1F916}",
    " ",
    "\n\n",
    "&amp;",
    "<!-- x -->",
    "<![CDATA[x]]>",
];

const TYPES: &[&str] = &[
    "floating",
    "planar",
    "fixed",
    "continuous",
    "revolute",
    "prismatic",
    "spherical",
    "",
];

/// One mutation of `src` (by lines; every operator keeps the text valid UTF-8).
fn mutate(src: &str, rng: &mut Rng) -> String {
    let mut lines: Vec<String> = src.lines().map(str::to_string).collect();
    let tagged: Vec<usize> = (0..lines.len())
        .filter(|&i| lines[i].contains('<'))
        .collect();
    if tagged.is_empty() {
        return src.to_string();
    }
    let at = *rng.pick(&tagged);
    match rng.below(10) {
        // Delete an element's line, or a whole <joint> … </joint> block.
        0 => {
            let end = block_end(&lines, at);
            lines.drain(at..=end);
        }
        // Duplicate one.
        1 => {
            let end = block_end(&lines, at);
            let copy: Vec<String> = lines[at..=end].to_vec();
            let to = rng.below(lines.len());
            lines.splice(to..to, copy);
        }
        // Swap a joint's parent and child.
        2 => {
            let text = lines.join("\n");
            let (p, c) = (text.find("<parent link=\""), text.find("<child link=\""));
            if let (Some(p), Some(c)) = (p, c) {
                let value = |at: usize, key: &str| {
                    let s = &text[at + key.len()..];
                    s[..s.find('"').unwrap_or(0)].to_string()
                };
                let (pv, cv) = (value(p, "<parent link=\""), value(c, "<child link=\""));
                let swapped = text
                    .replacen(
                        &format!("<parent link=\"{pv}\""),
                        "<parent link=\"\u{0}P\"",
                        1,
                    )
                    .replacen(
                        &format!("<child link=\"{cv}\""),
                        &format!("<child link=\"{pv}\""),
                        1,
                    )
                    .replacen(
                        "<parent link=\"\u{0}P\"",
                        &format!("<parent link=\"{cv}\""),
                        1,
                    );
                return swapped;
            }
        }
        // A number made huge, tiny, negative or not a number.
        3 | 4 => {
            let line = &lines[at];
            let starts: Vec<usize> = line
                .char_indices()
                .filter(|&(i, ch)| {
                    (ch.is_ascii_digit() || ch == '-')
                        && line[..i]
                            .chars()
                            .last()
                            .is_some_and(|p| p == '"' || p == ' ')
                })
                .map(|(i, _)| i)
                .collect();
            if let Some(&s) = starts.get(rng.below(starts.len().max(1))) {
                let e = line[s..].find([' ', '"']).map_or(line.len(), |k| s + k);
                lines[at] = format!("{}{}{}", &line[..s], rng.pick(NUMBERS), &line[e..]);
            }
        }
        // Odd whitespace or unicode at a character boundary.
        5 => {
            let line = &lines[at];
            let cut: Vec<usize> = line.char_indices().map(|(i, _)| i).collect();
            let k = *rng.pick(&cut);
            lines[at] = format!("{}{}{}", &line[..k], rng.pick(ODD), &line[k..]);
        }
        // Truncated at a character boundary.
        6 => {
            let text = lines.join("\n");
            let cut: Vec<usize> = text.char_indices().map(|(i, _)| i).collect();
            return match cut.get(rng.below(cut.len())) {
                Some(&k) => text[..k].to_string(),
                None => text,
            };
        }
        // A deep tree: 20–400 links hanging off an existing one.
        7 => {
            let links: Vec<String> = lines
                .iter()
                .filter_map(|l| l.split("<link name=\"").nth(1))
                .filter_map(|s| s.split('"').next())
                .map(str::to_string)
                .collect();
            let Some(mut parent) = links.get(rng.below(links.len())).cloned() else {
                return lines.join("\n");
            };
            let depth = 20 + rng.below(380);
            let mut tree = String::new();
            for k in 0..depth {
                tree.push_str(&format!(
                    "<link name=\"deep{k}\"/><joint name=\"deep_j{k}\" type=\"revolute\">\
                     <parent link=\"{parent}\"/><child link=\"deep{k}\"/>\
                     <origin xyz=\"0 0 0.01\" rpy=\"0 0.1 0\"/><axis xyz=\"0 0 1\"/></joint>\n"
                ));
                parent = format!("deep{k}");
            }
            if let Some(end) = lines.iter().rposition(|l| l.contains("</robot>")) {
                lines.insert(end, tree);
            }
        }
        // A link reference renamed to one that does not exist.
        8 => {
            lines[at] = lines[at].replacen("link=\"", "link=\"missing_", 1);
        }
        // A joint's type changed.
        _ => {
            if let Some(k) = lines[at].find("type=\"") {
                let rest = &lines[at][k + 6..];
                let e = rest.find('"').unwrap_or(0);
                lines[at] = format!(
                    "{}type=\"{}{}",
                    &lines[at][..k],
                    rng.pick(TYPES),
                    &rest[e..]
                );
            }
        }
    }
    lines.join("\n")
}

/// The last line of the element starting at line `at`: its `</joint>` for a `<joint`,
/// else the line itself.
fn block_end(lines: &[String], at: usize) -> usize {
    if lines[at].contains("<joint") && !lines[at].contains("/>") {
        (at..lines.len())
            .find(|&i| lines[i].contains("</joint>"))
            .unwrap_or(at)
    } else {
        at
    }
}

/// The shipped URDFs, `(file name, text)`.
fn sources() -> Vec<(String, String)> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../robots/urdf");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "urdf"))
        .collect();
    files.sort();
    files
        .iter()
        .map(|p| {
            let name = p.file_name().unwrap().to_string_lossy().to_string();
            (name, std::fs::read_to_string(p).unwrap())
        })
        .collect()
}

const MUTANTS: usize = 10_000;
/// Mutants whose index is a multiple of this, when they build a chain, are generated
/// and compared (about one in 5 of those that build).
const GENERATE_EVERY: usize = 5;
const Q: [f64; 8] = [0.3, -1.1, 0.7, 2.0, -0.4, 1.3, 0.2, -2.5];
/// The mutants are drawn in order from one generator, then checked on this many threads:
/// which mutant is checked how depends on its index only, so the tally is the same on
/// any machine.
const THREADS: usize = 2;

/// Mutant `k` through the CLI's loader and the oracle.
fn outcome(src: &str, k: usize) -> UrdfOutcome {
    let cli = |urdf: &Urdf| match urdf_chain(urdf, &UrdfArgs::default()) {
        Ok(chain) => Ok(chain),
        Err(CliError::Load(e)) => Err(e),
        Err(CliError::Usage(m)) => panic!("a usage error without options: {m}"),
    };
    load_and_check(
        src,
        "mutant.urdf",
        cli,
        || k % GENERATE_EVERY == 0,
        &Q,
        false,
    )
}

#[test]
fn ten_thousand_urdf_mutants_load_or_say_where() {
    let sources = sources();
    assert!(sources.len() >= 10, "{} URDF files", sources.len());
    let mut rng = Rng(XorShift64::new(32));
    let mutants: Vec<(&str, String)> = (0..MUTANTS)
        .map(|_| {
            let (name, text) = rng.pick(&sources);
            let mut src = text.clone();
            for _ in 0..1 + rng.below(3) {
                src = mutate(&src, &mut rng);
            }
            (name.as_str(), src)
        })
        .collect();
    // Per thread: the tally, and the time spent loading and checking.
    let run = |first: usize| {
        let mut tally = [0usize; 4];
        let mut times = [std::time::Duration::ZERO; 2];
        for (k, (name, src)) in mutants.iter().enumerate().skip(first).step_by(THREADS) {
            let start = std::time::Instant::now();
            let result = catch_unwind(AssertUnwindSafe(|| outcome(src, k)));
            let took = start.elapsed();
            match result {
                Ok(UrdfOutcome::Checked) => times[1] += took,
                _ => times[0] += took,
            }
            match result {
                Ok(o) => tally[o as usize] += 1,
                Err(_) => panic!("mutant {k} of {name} (above):\n{src}"),
            }
        }
        (tally, times)
    };
    let parts: Vec<_> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..THREADS).map(|t| s.spawn(move || run(t))).collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let mut tally = [0usize; 4];
    let mut times = [std::time::Duration::ZERO; 2];
    for (t, d) in &parts {
        for i in 0..4 {
            tally[i] += t[i];
        }
        times[0] += d[0];
        times[1] += d[1];
    }
    let [rejected, no_chain, built_only, checked] = tally;
    eprintln!(
        "{MUTANTS} mutants: {rejected} refused by the reader, {no_chain} without a chain, \
         {built_only} built, {checked} generated and checked; {:?} loading, {:?} checking \
         (CPU time over {THREADS} threads)",
        times[0], times[1]
    );
    // The mutator reaches every path: refusals of both kinds, chains, checked chains.
    assert!(
        rejected > 1_000 && no_chain > 500 && built_only > 1_000,
        "{tally:?}"
    );
    assert!(checked >= 100, "{tally:?}");
}
