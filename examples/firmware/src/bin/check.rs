//! Host side: reads the firmware's output (stdin, or the file given as argument), computes
//! the same quantities on the host and compares.
//!
//! - f64: the firmware's values (software floating point on the M4F) against the host's
//!   `kinegen_robots::Ur5`: must agree to 1e-12 (they are expected to be bit-identical:
//!   same generated code, same `libm`, IEEE arithmetic on both sides).
//! - f32: the firmware's values (the M4F's FPU) against the host's f32 twin (1e-12: also
//!   expected bit-identical; the f32 `ik`, solved in f64 and rounded, to 1e-6 rad) and
//!   against the host's f64 at the same joint values, within the bounds measured on all
//!   robots in `robots/tests/f32_error.rs`: 4 ε·reach for positions and linear Jacobian
//!   rows, 4 ε for rotation entries and angular rows, 8 ε·0.12 m³ for the determinant
//!   (0.12 m³ is the largest |det J| of the UR5 seen there), ε = f32::EPSILON.
//!
//! - The Jaco's general 6R `ik` (f64): the firmware's solutions against the host's (count,
//!   flags and order equal, joint values to 1e-9 rad), the generating configuration among
//!   the exact ones; and the stack the firmware measured for it and for the UR5's `ik`,
//!   printed (a figure must be below the painted 512 KB).
//!
//! - With the feature `defmt`: the firmware's `defmt` record (its UR5 `ik` solutions
//!   logged through kinegen's `defmt::Format`), decoded with the firmware's ELF (its path
//!   in `FIRMWARE_ELF`): one message per `ik` record, with the same count, flags and
//!   joint values (bit for bit).
//!
//! Exit status 0 when everything agrees, 1 otherwise (with the differences printed).

use std::collections::HashMap;
use std::io::Read;
use std::process::ExitCode;

use kinegen_firmware::{to_f32, Ur5F32, CONFIGS, HEADER, JACO_CONFIGS, TRAILER};
use kinegen_robots::{KinovaJaco, Ur5};

/// UR5's reach (m): |a2| + |a3| + d4 + d6 bounds the tool point's distance from the base.
const REACH: f64 = 0.425 + 0.39225 + 0.10915 + 0.0823 + 0.089159 + 0.09465;
/// Largest |det J| of the UR5 over 20 000 random configurations (robots/tests/f32_error.rs).
const DET_SCALE: f64 = 0.12;

/// One record: (scalar, case, quantity) → values.
type Records = HashMap<(String, usize, String), Vec<f64>>;

fn parse(text: &str) -> Result<Records, String> {
    let mut lines = text.lines().map(str::trim_end).filter(|l| !l.is_empty());
    match lines.next() {
        Some(h) if h == HEADER => {}
        other => return Err(format!("expected `{HEADER}` first, got {other:?}")),
    }
    let mut records = Records::new();
    let mut ended = false;
    for line in lines {
        if line == TRAILER {
            ended = true;
            continue;
        }
        let fields: Vec<&str> = line.split(' ').collect();
        match fields.as_slice() {
            ["cpacr", v] => {
                let bits = u32::from_str_radix(v.trim_start_matches("0x"), 16)
                    .map_err(|e| format!("bad cpacr `{v}`: {e}"))?;
                if bits & (0xF << 20) != 0xF << 20 {
                    return Err(format!("FPU not enabled: CPACR = {bits:#010x}"));
                }
                println!("firmware: CPACR = {bits:#010x} (CP10/CP11 full access: FPU on)");
            }
            ["error", ..] => return Err(format!("firmware reported: {line}")),
            // Read by `defmt_messages` (feature `defmt`).
            ["defmt", _] => {}
            ["stack", function, bytes] => {
                let bytes: f64 = bytes.parse().map_err(|e| format!("`{line}`: {e}"))?;
                let key = ("stack".to_string(), 0, function.to_string());
                if records.insert(key, vec![bytes]).is_some() {
                    return Err(format!("record given twice: `{line}`"));
                }
            }
            [scalar, case, name, values @ ..] => {
                let case: usize = case.parse().map_err(|e| format!("`{line}`: {e}"))?;
                // f32 values are printed as the shortest text that reads back to the
                // same f32: read them as f32, then widen exactly.
                let read = |v: &str| match *scalar {
                    "f64" => v.parse::<f64>().map_err(|e| e.to_string()),
                    "f32" => v.parse::<f32>().map(f64::from).map_err(|e| e.to_string()),
                    other => Err(format!("unknown scalar `{other}`")),
                };
                let values = values
                    .iter()
                    .map(|v| read(v).map_err(|e| format!("`{v}` in `{line}`: {e}")))
                    .collect::<Result<Vec<_>, _>>()?;
                let key = (scalar.to_string(), case, name.to_string());
                if records.insert(key, values).is_some() {
                    return Err(format!("record given twice: `{line}`"));
                }
            }
            _ => return Err(format!("cannot read line `{line}`")),
        }
    }
    if !ended {
        return Err(format!("no `{TRAILER}` line: the firmware stopped early"));
    }
    Ok(records)
}

/// Compares `got` with `want` entry by entry; returns the largest difference and whether
/// every entry is bit-identical.
struct Compare<'a> {
    failures: &'a mut Vec<String>,
    worst: HashMap<&'static str, f64>,
    identical: usize,
    total: usize,
}

impl Compare<'_> {
    fn check(
        &mut self,
        what: &'static str,
        case: usize,
        got: Option<&Vec<f64>>,
        want: &[f64],
        bound: &dyn Fn(usize) -> f64,
    ) {
        let Some(got) = got else {
            self.failures
                .push(format!("case {case}: no `{what}` record"));
            return;
        };
        if got.len() != want.len() {
            self.failures.push(format!(
                "case {case} {what}: {} values, expected {}",
                got.len(),
                want.len()
            ));
            return;
        }
        for (i, (g, w)) in got.iter().zip(want).enumerate() {
            let diff = (g - w).abs();
            self.total += 1;
            if g.to_bits() == w.to_bits() || (*g == 0.0 && *w == 0.0) {
                self.identical += 1;
            }
            let worst = self.worst.entry(what).or_insert(0.0);
            *worst = worst.max(diff);
            if diff.is_nan() || diff > bound(i) {
                self.failures.push(format!(
                    "case {case} {what}[{i}]: firmware {g:e}, host {w:e}, |diff| {diff:.3e} > {:.3e}",
                    bound(i)
                ));
            }
        }
    }

    fn report(&self, title: &str) {
        let mut worst: Vec<_> = self.worst.iter().collect();
        worst.sort_by(|a, b| a.0.cmp(b.0));
        let list: Vec<String> = worst.iter().map(|(k, v)| format!("{k} {v:.2e}")).collect();
        println!(
            "{title}: {}/{} entries bit-identical; largest |diff|: {}",
            self.identical,
            self.total,
            list.join(", ")
        );
    }
}

fn widen<const R: usize, const C: usize>(m: [[f32; C]; R]) -> Vec<f64> {
    m.iter().flatten().map(|&x| f64::from(x)).collect()
}

fn flat<const R: usize, const C: usize>(m: [[f64; C]; R]) -> Vec<f64> {
    m.iter().flatten().copied().collect()
}

/// `check --same-ik A B`: the `ik` records of two firmware outputs (the default IK and the
/// size-first one) hold the same solutions: count, flags and order equal, joint values to
/// 1e-9 rad (f64) or 1e-6 (f32, rounded once from f64) — the two paths compute the same
/// subproblems grouped differently, so they agree to rounding, not to the bit.
fn same_ik(a: &str, b: &str) -> Result<usize, String> {
    let read = |path: &str| {
        std::fs::read_to_string(path)
            .map_err(|e| format!("{path}: {e}"))
            .and_then(|t| parse(&t))
    };
    let (a, b) = (read(a)?, read(b)?);
    let mut solutions = 0;
    for (key, x) in a.iter().filter(|(k, _)| k.2 == "ik") {
        let y = b
            .get(key)
            .ok_or_else(|| format!("{key:?}: missing in the second output"))?;
        let tolerance = if key.0 == "f64" { 1e-9 } else { 1e-6 };
        if x.len() != y.len() || (0..x.len()).any(|i| is_count_or_flag(i) && x[i] != y[i]) {
            return Err(format!(
                "{key:?}: solutions or flags differ: {x:?} vs {y:?}"
            ));
        }
        if let Some(i) = (0..x.len()).find(|&i| (x[i] - y[i]).abs() > tolerance) {
            return Err(format!("{key:?}: entry {i}: {} vs {}", x[i], y[i]));
        }
        solutions += x[0] as usize;
    }
    if b.keys().filter(|k| k.2 == "ik").count() != a.keys().filter(|k| k.2 == "ik").count() {
        return Err("the outputs hold different `ik` records".into());
    }
    Ok(solutions)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    if let [_, flag, a, b] = args.as_slice() {
        if flag == "--same-ik" {
            return match same_ik(a, b) {
                Ok(n) => {
                    println!("check: the two IK paths give the same {n} solutions");
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("check: {e}");
                    ExitCode::FAILURE
                }
            };
        }
    }
    let mut text = String::new();
    let read = match std::env::args().nth(1) {
        Some(path) => std::fs::read_to_string(&path)
            .map(|t| text = t)
            .map_err(|e| format!("{path}: {e}")),
        None => std::io::stdin()
            .read_to_string(&mut text)
            .map(|_| ())
            .map_err(|e| format!("stdin: {e}")),
    };
    let records = match read.and_then(|()| parse(&text)) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("check: {e}");
            return ExitCode::FAILURE;
        }
    };
    let get = |s: &str, case: usize, name: &str| records.get(&(s.into(), case, name.into()));

    let eps = f64::from(f32::EPSILON);
    let (r64, r32) = (Ur5::default(), Ur5F32::default());
    let mut failures = Vec::new();
    let mut f64_fw = Compare {
        failures: &mut Vec::new(),
        worst: HashMap::new(),
        identical: 0,
        total: 0,
    };
    let mut f64_failures = Vec::new();
    f64_fw.failures = &mut f64_failures;
    let exact = |_| 1e-12;
    for (case, q) in CONFIGS.iter().enumerate() {
        f64_fw.check("q", case, get("f64", case, "q"), q, &|_| 0.0);
        f64_fw.check("fk", case, get("f64", case, "fk"), &flat(r64.fk(q)), &exact);
        f64_fw.check(
            "jac",
            case,
            get("f64", case, "jac"),
            &flat(r64.jacobian(q)),
            &exact,
        );
        f64_fw.check(
            "det",
            case,
            get("f64", case, "det"),
            &[r64.jacobian_det(q)],
            &exact,
        );
        // Every IK solution of fk(q): the same count, flags and order; joint values to
        // 1e-9 rad (the firmware's atan2/sqrt come from the `libm` crate, the host's from
        // the platform: a few ulps apart, amplified at most by the subproblems' conditioning
        // away from singular poses).
        let want = ik_values(&r64.ik(&r64.fk(q)));
        f64_fw.check("ik", case, get("f64", case, "ik"), &want, &ik_bound);
    }
    // The Jaco's general 6R: the same solutions as the host's; the generating
    // configuration among the exact ones.
    let jaco = KinovaJaco::default();
    for (case, q) in JACO_CONFIGS.iter().enumerate() {
        f64_fw.check("jaco-q", case, get("f64", case, "jaco-q"), q, &|_| 0.0);
        let want = ik_values(&jaco.ik(&jaco.fk(q)));
        f64_fw.check(
            "jaco-ik",
            case,
            get("f64", case, "jaco-ik"),
            &want,
            &ik_bound,
        );
        let found = get("f64", case, "jaco-ik").is_some_and(|got| {
            got[1..].chunks(7).any(|s| {
                s[0] == 1.0
                    && s[1..].iter().zip(q).all(|(a, b)| {
                        let d = (a - b).rem_euclid(std::f64::consts::TAU);
                        d.min(std::f64::consts::TAU - d) <= 1e-9
                    })
            })
        });
        if !found {
            f64_fw.failures.push(format!(
                "Jaco case {case}: the generating configuration is not among the firmware's exact solutions"
            ));
        }
    }
    f64_fw.report("f64 firmware vs f64 host");
    for function in ["jaco_ik_f64", "ur5_ik_f64"] {
        match records.get(&("stack".into(), 0, function.into())) {
            Some(b) if b[0] < 512.0 * 1024.0 - 64.0 => {
                println!("firmware: `{function}` used {} bytes of stack", b[0]);
            }
            Some(b) => f64_failures.push(format!(
                "`{function}`: stack {} bytes, the whole painted area: more than measured",
                b[0]
            )),
            None => f64_failures.push(format!("no stack record for `{function}`")),
        }
    }
    failures.append(&mut f64_failures);

    // f32 against the host's f32 twin: the same single-precision code on another IEEE machine.
    let mut f32_failures = Vec::new();
    let mut f32_fw = Compare {
        failures: &mut f32_failures,
        worst: HashMap::new(),
        identical: 0,
        total: 0,
    };
    let close = |_| 1e-12;
    for (case, q) in CONFIGS.iter().enumerate() {
        let q32 = to_f32(q);
        let qw: Vec<f64> = q32.iter().map(|&x| f64::from(x)).collect();
        f32_fw.check("q", case, get("f32", case, "q"), &qw, &|_| 0.0);
        f32_fw.check(
            "fk",
            case,
            get("f32", case, "fk"),
            &widen(r32.fk(&q32)),
            &close,
        );
        f32_fw.check(
            "jac",
            case,
            get("f32", case, "jac"),
            &widen(r32.jacobian(&q32)),
            &close,
        );
        let d = f64::from(r32.jacobian_det(&q32));
        f32_fw.check("det", case, get("f32", case, "det"), &[d], &close);
        // The f32 IK (solved in f64, rounded): count and flags exact, joint values to 1e-6
        // rad (a few f32 ulps: the f64 solve's libm differences, rounded, could flip one).
        let ik = r32.ik(&r32.fk(&q32));
        let mut want = vec![ik.len() as f64];
        for b in ik.iter() {
            want.push(if b.exact { 1.0 } else { 0.0 });
            want.extend(b.q.map(f64::from));
        }
        f32_fw.check("ik", case, get("f32", case, "ik"), &want, &|i| {
            if is_count_or_flag(i) {
                0.0
            } else {
                1e-6
            }
        });
    }
    f32_fw.report("f32 firmware vs f32 host");
    failures.append(&mut f32_failures);

    // f32 against f64 at the same joint values: the single-precision error.
    let mut err_failures = Vec::new();
    let mut f32_err = Compare {
        failures: &mut err_failures,
        worst: HashMap::new(),
        identical: 0,
        total: 0,
    };
    // fk entries: rotation (columns 0..3) and position (column 3) of rows 0..3.
    let fk_bound = |i: usize| {
        if i % 4 == 3 {
            4.0 * eps * REACH
        } else {
            4.0 * eps
        }
    };
    // jac: rows 0..3 linear (m), rows 3..6 angular.
    let jac_bound = |i: usize| {
        if i < 18 {
            4.0 * eps * REACH
        } else {
            4.0 * eps
        }
    };
    for (case, q) in CONFIGS.iter().enumerate() {
        let q = to_f32(q).map(f64::from);
        f32_err.check(
            "fk",
            case,
            get("f32", case, "fk"),
            &flat(r64.fk(&q)),
            &fk_bound,
        );
        f32_err.check(
            "jac",
            case,
            get("f32", case, "jac"),
            &flat(r64.jacobian(&q)),
            &jac_bound,
        );
        let d = r64.jacobian_det(&q);
        f32_err.check("det", case, get("f32", case, "det"), &[d], &|_| {
            8.0 * eps * DET_SCALE
        });
    }
    f32_err.report("f32 firmware vs f64 host (same q)");
    failures.append(&mut err_failures);

    #[cfg(feature = "defmt")]
    match defmt_messages(&text) {
        Ok(messages) => failures.extend(defmt_check(&messages, &records)),
        Err(e) => failures.push(format!("defmt: {e}")),
    }
    #[cfg(not(feature = "defmt"))]
    if text.lines().any(|l| l.starts_with("defmt ")) {
        failures.push("a `defmt` record, but this check was built without `defmt`".into());
    }

    if failures.is_empty() {
        println!(
            "check: firmware output agrees with the host ({} UR5 and {} Jaco configurations)",
            CONFIGS.len(),
            JACO_CONFIGS.len()
        );
        ExitCode::SUCCESS
    } else {
        for f in &failures {
            eprintln!("check: {f}");
        }
        eprintln!("check: {} disagreement(s)", failures.len());
        ExitCode::FAILURE
    }
}

/// An f64 `ik` record's values: the count, then per solution its exact flag and angles.
fn ik_values<const K: usize>(ik: &kinegen::ik::IkSolutions<6, K>) -> Vec<f64> {
    let mut v = vec![ik.len() as f64];
    for b in ik.iter() {
        v.push(if b.exact { 1.0 } else { 0.0 });
        v.extend(b.q);
    }
    v
}

/// The f64 `ik` records' bound: count and flags exact, joint values to 1e-9 rad.
fn ik_bound(i: usize) -> f64 {
    if is_count_or_flag(i) {
        0.0
    } else {
        1e-9
    }
}

/// In an `ik` record — the count, then per solution its exact flag and six angles — the
/// entries that must match exactly: the count and the flags.
fn is_count_or_flag(i: usize) -> bool {
    i == 0 || (i - 1).is_multiple_of(7)
}

/// The firmware's `defmt` record decoded: one message per frame, with the ELF named by
/// `FIRMWARE_ELF` (its `.defmt` section holds the interned format strings).
#[cfg(feature = "defmt")]
fn defmt_messages(text: &str) -> Result<Vec<String>, String> {
    let hex = text
        .lines()
        .find_map(|l| l.trim_end().strip_prefix("defmt "))
        .ok_or("no `defmt` record in the firmware's output")?;
    if hex.len() % 2 != 0 {
        return Err("the `defmt` record has an odd number of hex digits".into());
    }
    let bytes = (0..hex.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(&hex[i..i + 2], 16))
        .collect::<Result<Vec<u8>, _>>()
        .map_err(|e| format!("the `defmt` record: {e}"))?;
    let path = std::env::var("FIRMWARE_ELF")
        .map_err(|_| "FIRMWARE_ELF must name the firmware's ELF".to_string())?;
    let elf = std::fs::read(&path).map_err(|e| format!("{path}: {e}"))?;
    let table = defmt_decoder::Table::parse(&elf)
        .map_err(|e| format!("{path}: {e}"))?
        .ok_or_else(|| format!("{path}: no `.defmt` section"))?;
    let mut decoder = table.new_stream_decoder();
    decoder.received(&bytes);
    let mut messages = Vec::new();
    loop {
        match decoder.decode() {
            Ok(frame) => messages.push(frame.display_message().to_string()),
            Err(defmt_decoder::DecodeError::UnexpectedEof) => break,
            Err(defmt_decoder::DecodeError::Malformed) => {
                return Err(format!(
                    "a malformed frame after {} messages",
                    messages.len()
                ))
            }
        }
    }
    println!("firmware: {} defmt messages decoded", messages.len());
    Ok(messages)
}

/// Each UR5 `ik` record's solutions as the defmt message `ur5 <scalar> <case> [IkBranch {
/// q: [..], exact: .., .. }, ..]` prints them: count, flags and joint values equal.
#[cfg(feature = "defmt")]
fn defmt_check(messages: &[String], records: &Records) -> Vec<String> {
    let mut failures = Vec::new();
    let mut compared = 0;
    for scalar in ["f64", "f32"] {
        for case in 0..CONFIGS.len() {
            let head = format!("ur5 {scalar} {case} ");
            let Some(body) = messages.iter().find_map(|m| m.strip_prefix(&head)) else {
                failures.push(format!("defmt: no message `{head}…`"));
                continue;
            };
            let Some(want) = records.get(&(scalar.into(), case, "ik".into())) else {
                failures.push(format!("defmt: no `{scalar} {case} ik` record"));
                continue;
            };
            match defmt_solutions(body, scalar) {
                Ok(got) if got == *want => compared += 1,
                Ok(got) => {
                    failures.push(format!("defmt `{head}`: {got:?}, the ik record {want:?}"))
                }
                Err(e) => failures.push(format!("defmt `{head}`: {e} in `{body}`")),
            }
        }
    }
    if failures.is_empty() {
        println!("firmware: the defmt log of {compared} `ik` calls matches their records");
        if let Some(first) = messages.first() {
            let cut: String = first.chars().take(150).collect();
            println!("firmware: the first reads `{cut}…`");
        }
    }
    failures
}

/// `[IkBranch { q: [a, b, …], exact: true, … }, …]` as the `ik` record's numbers: the
/// count, then per branch the exact flag and the joint values (read as `scalar`).
#[cfg(feature = "defmt")]
fn defmt_solutions(body: &str, scalar: &str) -> Result<Vec<f64>, String> {
    let branches: Vec<&str> = body.split("IkBranch {").skip(1).collect();
    let mut out = vec![branches.len() as f64];
    for b in branches {
        let q = b
            .split_once("q: [")
            .and_then(|(_, r)| r.split_once(']'))
            .ok_or("no `q: [..]`")?
            .0;
        let exact = b
            .split_once("exact: ")
            .map(|(_, r)| r.starts_with("true"))
            .ok_or("no `exact`")?;
        out.push(if exact { 1.0 } else { 0.0 });
        for v in q.split(", ") {
            let v = match scalar {
                "f32" => v.parse::<f32>().map(f64::from).map_err(|e| e.to_string()),
                _ => v.parse::<f64>().map_err(|e| e.to_string()),
            };
            out.push(v.map_err(|e| format!("a joint value: {e}"))?);
        }
    }
    Ok(out)
}
