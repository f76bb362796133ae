#!/usr/bin/env python3
"""He & Liu's analytic Franka Panda IK as PyPI ships it — `frankik` and `panda-python`
(module `panda_py`), both Python bindings over the C++ — on the poses kinegen's
`Panda::ik_with` solves in `benches/ik_closed_form.rs`, in a separate process as EAIK is
compared (CI stays free of Python).

Run (README):

    python3 -m venv /tmp/pandavenv && /tmp/pandavenv/bin/pip install numpy frankik panda-python
    cargo run --release --example panda_ik_json > /tmp/panda.json
    /tmp/pandavenv/bin/python benches/panda_ik/panda_ik_bench.py /tmp/panda.json

and `cargo bench --bench ik_closed_form` just before or after it for kinegen's time on the
same poses (`panda_kinegen_ik_with_q7`).

The JSON holds 1 000 poses `fk(q)` of configurations drawn uniformly within the limits
(seed 2026), in kinegen's frames (base; tool = the Franka Hand TCP of `robots/panda.toml`),
kinegen's geometry at q = 0 and its flange and tool poses at q = 0. The script

1. evaluates kinegen's forward kinematics from that geometry (product of exponentials)
   and checks it against every pose (1e-12), so that every answer below is judged by
   kinegen's fk;
2. reconciles frames, per library: its `fk` must equal kinegen's pose times one fixed
   transform at all 1 000 configurations (1e-9), else it aborts; then the frame its
   `ik_full` reads the pose in is found among (a) its own fk's frame, (b) kinegen's tool
   frame, (c) the flange, on the first 50 poses: the one whose answers reach the pose by
   kinegen's fk; it aborts unless 90 % of those answers do;
3. calls `ik_full(pose, q_actual, q7)` (all solutions for one q7, up to four, NaN rows
   for none) with q7 of the generating configuration and q_actual = Franka's home
   configuration (both libraries' default), and counts the poses with ≥ 1 solution,
   solutions, the generating configuration recovered (all joints within 1e-6 rad modulo
   2π) and wrong answers (kinegen's fk > 1e-9 off the pose); a row with any NaN is no
   solution, as the libraries document it, and rows partly NaN are counted apart; the same counts with q_actual = the generating configuration are
   printed as well, to show what q_actual changes;
4. times each library's `ik_full` over the 1 000 poses (`time.perf_counter_ns` around
   the loop; `--repeats` rounds, libraries interleaved; median per call), and the same
   call with q7 outside joint 7's limits, which He & Liu's code answers with NaN before
   any solving: the binding's and the loop's own cost per call.

`--export-cpp FILE` writes the poses for `he_liu_bench.cpp` (He & Liu's C++ timed without
bindings; how to build it is at its top) and stops; `--cpp-solutions FILE` adds the
counts of the answers that program wrote to the report.
"""
import argparse
import importlib.metadata as metadata
import json
import platform
import statistics
import time

import numpy as np

HOME = np.array([0.0, -np.pi / 4, 0.0, -3 * np.pi / 4, 0.0, np.pi / 2, np.pi / 4])
EXACT = 1e-9
SAME = 1e-6
CALIBRATION = 50


def rodrigues(h, t):
    k = np.array([[0.0, -h[2], h[1]], [h[2], 0.0, -h[0]], [-h[1], h[0], 0.0]])
    return np.eye(3) + np.sin(t) * k + (1.0 - np.cos(t)) * (k @ k)


class KinegenFk:
    """kinegen's forward kinematics in product-of-exponentials form, from its geometry."""

    def __init__(self, data):
        self.h = [np.array(x) for x in data["h"]]
        self.p = [np.array(x) for x in data["p"]]
        self.m = np.eye(4)
        self.m[:3, :3] = np.array(data["r_tool"])
        self.m[:3, 3] = np.array(data["p_tool"])

    def __call__(self, q):
        t = np.eye(4)
        for h, p, qi in zip(self.h, self.p, q):
            e = np.eye(4)
            e[:3, :3] = rodrigues(h, qi)
            e[:3, 3] = p - e[:3, :3] @ p
            t = t @ e
        return t @ self.m


def off(a, b):
    """max |a − b| over the top three rows of two poses."""
    return float(np.max(np.abs(np.asarray(a)[:3] - np.asarray(b)[:3])))


def same(a, b):
    d = np.asarray(a) - np.asarray(b)
    return bool(np.all(np.abs(d - 2 * np.pi * np.round(d / (2 * np.pi))) < SAME))


def describe(x):
    """A fixed transform as a translation and a rotation about z (if it is one)."""
    angle = np.degrees(np.arctan2(x[1, 0], x[0, 0]))
    about_z = np.allclose(x[:3, :3], rodrigues([0.0, 0.0, 1.0], np.radians(angle)), atol=1e-12)
    t = ", ".join(f"{v:+.6g}" for v in x[:3, 3])
    return f"translation [{t}] m, " + (f"Rz({angle:+.4g}°)" if about_z else f"rotation {x[:3, :3].tolist()}")


class Library:
    def __init__(self, name, dist, fk, ik_full, args):
        self.name = name
        self.version = metadata.version(dist)
        self.fk = fk
        self.ik_full = ik_full
        # args(pose, q_actual, q7): the positional arguments of `ik_full`.
        self.args = args


def libraries():
    import frankik
    import panda_py

    return [
        Library("frankik", "frankik", frankik.fk, frankik.ik_full,
                lambda pose, qa, q7: (pose, qa, q7, False)),
        Library("panda_py", "panda-python", panda_py.fk, panda_py.ik_full,
                lambda pose, qa, q7: (pose, qa, q7)),
    ]


def reconcile(lib, fk, cases, poses, tool):
    """The library's fk frame and the frame its ik_full reads; aborts if either fails."""
    x_fk = np.linalg.inv(poses[0]) @ np.asarray(lib.fk(np.array(cases[0]["q"])))
    worst = max(off(p @ x_fk, lib.fk(np.array(c["q"]))) for c, p in zip(cases, poses))
    if worst > EXACT:
        raise SystemExit(f"{lib.name}: its fk is no fixed transform of kinegen's pose "
                         f"(off by {worst:.2e} after the best one): frames not reconciled")
    candidates = [
        ("its own fk's frame", x_fk),
        ("kinegen's tool frame (Franka Hand TCP)", np.eye(4)),
        ("the flange", np.linalg.inv(tool)),
    ]
    tried = []
    for label, x in candidates:
        good = total = 0
        for c, p in zip(cases[:CALIBRATION], poses[:CALIBRATION]):
            for q in np.asarray(lib.ik_full(*lib.args(np.ascontiguousarray(p @ x), HOME, c["q"][6]))):
                if not np.isnan(q).all():
                    total += 1
                    good += (not np.isnan(q).any()) and off(fk(q), p) <= EXACT
        tried.append((good, total, label, x))
    good, total, label, x = max(tried, key=lambda t: t[0])
    if total == 0 or good < 0.9 * total:
        summary = "; ".join(f"{lab}: {g}/{t}" for g, t, lab, _ in tried)
        raise SystemExit(f"{lib.name}: no frame makes ik_full's answers reach the poses ({summary})")
    print(f"{lib.name} {lib.version}: fk = kinegen's pose · [{describe(x_fk)}] at all "
          f"{len(cases)} configurations (worst {worst:.1e}); ik_full reads the pose in "
          f"{label} = kinegen's pose · [{describe(x)}] ({good}/{total} answers exact on the "
          f"first {CALIBRATION} poses; the other frames: "
          + ", ".join(f"{g}/{t}" for g, t, lab, _ in tried if lab != label) + ")")
    return x


def tally(lib, cases, inputs, q_actual):
    """Each pose's `ik_full` rows (4 × 7, NaN rows for none)."""
    out = []
    for c, pin in zip(cases, inputs):
        qa = HOME if q_actual is None else np.array(c["q"])
        out.append(np.asarray(lib.ik_full(*lib.args(pin, qa, c["q"][6]))))
    return out


def counts(fk, cases, poses, answers):
    """Counts over all poses. A row with a NaN is no solution (the libraries' "NaN if no
    solution"); rows partly NaN are counted apart."""
    found_any = solutions = found = wrong = wrong_poses = other_q4 = partial = 0
    worst_wrong = 0.0
    for c, p, rows in zip(cases, poses, answers):
        nan = np.isnan(rows)
        partial += int(np.sum(nan.any(axis=1) & ~nan.all(axis=1)))
        rows = [q for q, m in zip(rows, nan) if not m.any()]
        misses = [off(fk(q), p) for q in rows]
        bad = sum(e > EXACT for e in misses)
        worst_wrong = max([worst_wrong] + [e for e in misses if e > EXACT])
        g = any(same(q, c["q"]) for q in rows)
        found_any += bool(rows)
        solutions += len(rows)
        found += g
        wrong += bad
        wrong_poses += bad > 0
        # Not recovered, and no answer has the generating q4: He & Liu solve one root of
        # the elbow (q4) where the Panda's offset elbow can have two within the limits.
        other_q4 += (not g) and not any(abs(q[3] - c["q"][3]) < SAME for q in rows)
    return dict(found_any=found_any, solutions=solutions, found=found, wrong=wrong,
                wrong_poses=wrong_poses, worst_wrong=worst_wrong, other_q4=other_q4,
                partial=partial)


def summary(t, n):
    return (f"≥ 1 solution for {t['found_any']}/{n} poses, {t['solutions']} solutions, "
            f"generating q recovered {t['found']}/{n} ({t['other_q4']} of the misses: no answer "
            f"with the generating q4), wrong {t['wrong']} on {t['wrong_poses']} poses (up to "
            f"{t['worst_wrong']:.1e} off); {t['partial']} rows partly NaN (not counted as solutions)")


def timed(f, args):
    t = time.perf_counter_ns()
    for a in args:
        f(*a)
    return time.perf_counter_ns() - t


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cases", help="output of `cargo run --release --example panda_ik_json`")
    ap.add_argument("--repeats", type=int, default=30)
    ap.add_argument("--export-cpp", metavar="FILE",
                    help="write the poses for he_liu_bench.cpp (q7, then the pose column-major, "
                         "one line per pose) and stop")
    ap.add_argument("--cpp-solutions", metavar="FILE",
                    help="also count the answers he_liu_bench.cpp wrote (4 rows of 7 per pose)")
    args = ap.parse_args()
    with open(args.cases) as f:
        data = json.load(f)
    cases = data["cases"]
    n = len(cases)
    poses = [np.array(c["pose"]) for c in cases]
    if args.export_cpp:
        # He & Liu's C++ reads the hand TCP's pose (d7e = 0.2104 m = flange 0.107 + hand
        # 0.1034, and the hand's −π/4), kinegen's tool frame: checked by the answers' fk.
        with open(args.export_cpp, "w") as f:
            for c, p in zip(cases, poses):
                f.write(" ".join(repr(float(x)) for x in [c["q"][6], *p.T.flatten()]) + "\n")
        return
    fk = KinegenFk(data)
    worst = max(off(fk(c["q"]), p) for c, p in zip(cases, poses))
    if worst > 1e-12:
        raise SystemExit(f"kinegen's fk from its geometry differs from its poses by {worst:.2e}")
    tool = np.linalg.inv(np.array(data["flange_at_zero"])) @ np.array(data["tool_at_zero"])
    print(f"Python {platform.python_version()}, numpy {np.__version__}")
    print(f"{n} poses (seed {data['seed']}); kinegen's fk from its geometry matches them to {worst:.1e}; "
          f"flange → tool: {describe(tool)}")

    libs = libraries()
    inputs = {}
    for lib in libs:
        x = reconcile(lib, fk, cases, poses, tool)
        inputs[lib.name] = [np.ascontiguousarray(p @ x) for p in poses]

    for lib in libs:
        for label, qa in (("q_actual = home", None), ("q_actual = generating q", "generating")):
            t = counts(fk, cases, poses, tally(lib, cases, inputs[lib.name], qa))
            print(f"{lib.name} ik_full, {label}: " + summary(t, n))

    if args.cpp_solutions:
        rows = np.loadtxt(args.cpp_solutions).reshape(n, 4, 7)
        t = counts(fk, cases, poses, rows)
        print("He & Liu C++ (he_liu_bench.cpp, q_actual = home): " + summary(t, n))

    # An out-of-limits q7 (He & Liu return NaN before solving): the call's own cost.
    q7_out = 10.0
    calls = {}
    for lib in libs:
        assert np.isnan(np.asarray(lib.ik_full(*lib.args(inputs[lib.name][0], HOME, q7_out)))).all()
        calls[lib.name] = (
            [lib.args(pin, HOME, c["q"][6]) for c, pin in zip(cases, inputs[lib.name])],
            [lib.args(pin, HOME, q7_out) for pin in inputs[lib.name]],
        )
        timed(lib.ik_full, calls[lib.name][0])  # warm-up
        timed(lib.ik_full, calls[lib.name][1])
    times = {(lib.name, k): [] for lib in libs for k in ("ik", "trivial")}
    for _ in range(args.repeats):
        for lib in libs:
            solve, trivial = calls[lib.name]
            times[(lib.name, "ik")].append(timed(lib.ik_full, solve))
            times[(lib.name, "trivial")].append(timed(lib.ik_full, trivial))
    for lib in libs:
        ik = statistics.median(times[(lib.name, "ik")]) / n / 1e3
        lo, hi = (min(times[(lib.name, "ik")]) / n / 1e3, max(times[(lib.name, "ik")]) / n / 1e3)
        tr = statistics.median(times[(lib.name, "trivial")]) / n / 1e3
        print(f"{lib.name} ik_full: median {ik:.3f} µs per call (min {lo:.3f}, max {hi:.3f}) over "
              f"{args.repeats} rounds of {n} calls; the same call with q7 out of limits "
              f"(binding and loop only) {tr:.3f} µs; difference {ik - tr:.3f} µs")


if __name__ == "__main__":
    main()
