#!/usr/bin/env python3
"""EAIK (Ostermeier et al., C++ with Python bindings, `pip install eaik`) on the poses
kinegen's IK benches solve, for a side-by-side figure outside CI (CI stays free of Python).

    cargo run --release --example ik_geometry_json -- ur5 > ur5.json
    python3 benches/eaik/eaik_bench.py ur5.json

EAIK gets kinegen's own geometry (`ik_geometry()`: axes H, offsets P between the points,
tool rotation), so both solve the same arm. The script checks EAIK's forward kinematics
against kinegen's poses (1e-9), counts solutions, exact ones (EAIK's fk within 1e-9 of the
pose) and how often the generating configuration is among them, then times
`IK_batched(poses, 1)` — the C++ solver over the whole batch in one call, one thread, so
Python's per-call cost is not counted — as the median of `--repeats` batches.
"""
import argparse
import json
import statistics
import time

import numpy as np
from eaik.pybindings import EAIK


def robot(geometry):
    h = np.array(geometry["h"])
    p = np.array(geometry["p"])
    # IK-Geo's convention: P0 = p1, Pi = p(i+1) - p(i), P6 = p_tool - p6.
    offsets = [p[0]] + [p[i] - p[i - 1] for i in range(1, 6)] + [np.array(geometry["p_tool"]) - p[5]]
    return EAIK.Robot(h.T, np.array(offsets).T, np.array(geometry["r_tool"]), [], True)


def same(a, b):
    d = np.asarray(a) - np.asarray(b)
    return bool(np.all(np.abs(d - 2 * np.pi * np.round(d / (2 * np.pi))) < 1e-6))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("geometry", help="output of `cargo run --example ik_geometry_json`")
    ap.add_argument("--repeats", type=int, default=30)
    args = ap.parse_args()
    with open(args.geometry) as f:
        geometry = json.load(f)
    bot = robot(geometry)
    cases = geometry["cases"]
    poses = [np.array(c["pose"]) for c in cases]
    worst = max(float(np.max(np.abs(bot.fwdkin(np.array(c["q"])) - pose))) for c, pose in zip(cases, poses))
    if worst > 1e-9:
        raise SystemExit(f"EAIK's fk differs from kinegen's by {worst:e}: not the same arm")
    sols = bot.calculate_IK_batched(poses, 1)
    total = exact = found = 0
    for c, pose, s in zip(cases, poses, sols):
        qs = [np.asarray(q) for q in s.Q]
        total += len(qs)
        good = [q for q in qs if float(np.max(np.abs(bot.fwdkin(q) - pose))) < 1e-9]
        exact += len(good)
        found += any(same(q, c["q"]) for q in good)
    print(f"EAIK {len(poses)} poses: fk agrees with kinegen's to {worst:.1e}; {total} solutions, "
          f"{exact} exact by fk (1e-9), generating q among them for {found}/{len(poses)}")
    times = []
    for _ in range(args.repeats):
        t = time.perf_counter()
        bot.calculate_IK_batched(poses, 1)
        times.append(time.perf_counter() - t)
    per_pose = statistics.median(times) / len(poses) * 1e6
    print(f"EAIK IK_batched, 1 thread: median {per_pose:.2f} µs per pose over {args.repeats} batches")


if __name__ == "__main__":
    main()
