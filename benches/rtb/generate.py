#!/usr/bin/env python3
"""Regenerate the Robotics Toolbox for Python's Rust IK for the UR5 and PUMA 560.

Writes, into ``generated/`` beside this script:

- ``ur5.rs`` and ``puma560.rs``: ``DHRobot.analytic_ik().generate("rust")`` for the
  Toolbox's own ``models.DH.UR5()`` and ``models.DH.Puma560()``, each file as the Toolbox
  writes it (its header: where it came from, the MIT licence, the DH table), after two
  lines saying which package versions and which command made it;
- ``fk_samples.rs``: the Toolbox's ``fkine`` at a few seeded configurations of each arm,
  which the bench compares with kinegen's fk to find the frames' mapping (and stops if
  there is none).

It prints how long each derivation took (``analytic_ik()``: the symbolic solution,
SymPy, and the Toolbox's own check on random poses) and how long the code generation
took.

Needs ``pip install "roboticstoolbox-python[ik]"`` (SymPy and python-flint), e.g.::

    python3 -m venv /tmp/rtbvenv
    /tmp/rtbvenv/bin/pip install "roboticstoolbox-python[ik]==1.5.0"
    /tmp/rtbvenv/bin/python benches/rtb/generate.py
"""

from __future__ import annotations

import importlib.metadata as md
import time
from pathlib import Path

import numpy as np
import roboticstoolbox as rtb

OUT = Path(__file__).resolve().parent / "generated"

# (file stem, the Toolbox's model class name, the constant prefix in fk_samples.rs)
ROBOTS = [("ur5", "UR5", "UR5"), ("puma560", "Puma560", "PUMA560")]

# Configurations per robot at which the Toolbox's fkine is recorded.
SAMPLES = 8


def versions() -> str:
    names = ["roboticstoolbox-python", "sympy", "python-flint", "spatialmath-python", "numpy"]
    out = []
    for name in names:
        try:
            out.append(f"{name} {md.version(name)}")
        except md.PackageNotFoundError:
            out.append(f"{name} (not installed)")
    return ", ".join(out)


def rust_array(values) -> str:
    return "[" + ", ".join(repr(float(v)) for v in values) + "]"


def main() -> None:
    OUT.mkdir(exist_ok=True)
    ver = versions()
    print(ver)
    samples = [
        "//! The Robotics Toolbox for Python's `fkine` at a few configurations (seeded,",
        "//! uniform in [-pi, pi)), row-major 4x4, written by `benches/rtb/generate.py`",
        f"//! ({ver}).",
        "//! The bench finds the fixed transform between these and kinegen's fk.",
    ]
    for stem, cls, prefix in ROBOTS:
        robot = getattr(rtb.models.DH, cls)()
        t0 = time.perf_counter()
        solver = robot.analytic_ik()
        t1 = time.perf_counter()
        source = solver.generate("rust")
        t2 = time.perf_counter()
        command = f'roboticstoolbox.models.DH.{cls}().analytic_ik().generate("rust")'
        head = [
            f"//! Written by `benches/rtb/generate.py`: `{command}`,",
            f"//! with {ver}. The Toolbox's own header follows, unchanged.",
            "//!",
        ]
        path = OUT / f"{stem}.rs"
        path.write_text("\n".join(head) + "\n" + source.rstrip("\n") + "\n", encoding="utf-8")
        print(
            f"{cls}: {type(solver).__name__} ({solver.method}); "
            f"analytic_ik() {t1 - t0:.2f} s, generate(\"rust\") {t2 - t1:.2f} s "
            f"-> {path.relative_to(OUT.parent.parent.parent)} ({len(source)} bytes)"
        )

        rng = np.random.default_rng(2026)
        rows = []
        for _ in range(SAMPLES):
            q = rng.uniform(-np.pi, np.pi, robot.n)
            t = robot.fkine(q).A
            rows.append(f"    ({rust_array(q)}, {rust_array(t.ravel())}),")
        samples += [
            "",
            f"/// `(q, fkine(q))` of `models.DH.{cls}()`.",
            f"pub const {prefix}: [([f64; 6], [f64; 16]); {SAMPLES}] = [",
            *rows,
            "];",
        ]
    (OUT / "fk_samples.rs").write_text("\n".join(samples) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
