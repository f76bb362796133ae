"""The Python module against the Rust code `kinematics!` generates, robot by robot.

`robots/examples/reference_values.rs` evaluates the generated code of every robot of
`robots/` at fixed configurations and writes the values as JSON; `kinegen-py/ci.sh`
runs it and names the file in KINEGEN_RUST_VALUES. Every method of `kinegen.Robot`
must give the same values to 1e-12 (relative to the value's size, at least 1),
`formulas` the generated `FORMULAS`, and `ik` the same solutions with the same `exact` flags (and `singular` wherever the
generated code flags one).

Without KINEGEN_RUST_VALUES (pytest by hand) the tests are skipped; ci.sh fails on a
skipped test.
"""

import json
import os
import pathlib

import numpy as np
import pytest

import kinegen

TOLERANCE = 1e-12


@pytest.fixture(scope="module")
def values():
    path = os.environ.get("KINEGEN_RUST_VALUES")
    if not path:
        pytest.skip("KINEGEN_RUST_VALUES is not set (kinegen-py/ci.sh sets it)")
    return json.loads(pathlib.Path(path).read_text())


def close(python, rust, what):
    python, rust = np.asarray(python, dtype=float).ravel(), np.asarray(rust, dtype=float)
    assert python.shape == rust.shape, f"{what}: shape {python.shape} vs {rust.shape}"
    err = np.abs(python - rust) / np.maximum(1.0, np.abs(rust))
    assert err.max(initial=0.0) <= TOLERANCE, (
        f"{what}: differs from the generated Rust by {err.max():.2e} "
        f"(entry {int(err.argmax())}: {python[err.argmax()]!r} vs {rust[err.argmax()]!r})"
    )


def test_every_shipped_robot_has_generated_values(values):
    assert sorted(values) == sorted(kinegen.robots.names())


def test_every_method_gives_the_generated_codes_values(values, shipped):
    for name, v in values.items():
        robot = shipped[name]
        for k, s in enumerate(v["samples"]):
            q, at = np.array(s["q"]), f"{name} sample {k}"
            close(robot.fk(q), s["fk"], f"{at} fk")
            close(robot.frames(q), s["frames"], f"{at} frames")
            close(robot.jacobian(q), s["jacobian"], f"{at} jacobian")
            close(robot.jacobian_ee(q), s["jacobian_ee"], f"{at} jacobian_ee")
            close(robot.hessian(q), s["hessian"], f"{at} hessian")
            close(robot.jdot_qdot(q, np.array(s["qd"])), s["jdot_qdot"], f"{at} jdot_qdot")
            assert robot.has_det == (s["det"] is not None), f"{at}: has_det"
            if s["det"] is not None:
                close(robot.jacobian_det(q), [s["det"]], f"{at} jacobian_det")
            if s["task_det"] is not None:
                close(robot.task_jacobian_det(q), [s["task_det"]], f"{at} task_jacobian_det")
            else:
                with pytest.raises(ValueError, match="no square task"):
                    robot.task_jacobian_det(q)


def test_ik_gives_the_generated_codes_solutions(values, shipped):
    compared = 0
    for name, v in values.items():
        robot = shipped[name]
        for k, s in enumerate(v["samples"]):
            at = f"{name} sample {k}"
            pose = np.array(s["fk"]).reshape(4, 4)
            r = robot.ik(pose, locked=s["locked"])
            qs, exact = r["q"], r["exact"]
            rust = s["ik"]
            assert len(qs) == len(rust), f"{at}: {len(qs)} solutions, the Rust {len(rust)}"
            unmatched = list(range(len(qs)))
            for b in rust:
                # The same joint values: both wrap revolute joints by the same rule.
                err = np.abs(qs[unmatched] - np.array(b["q"])).max(axis=1)
                i = int(err.argmin())
                assert err[i] <= TOLERANCE * 10, f"{at}: Rust solution {b['q']} missing ({err[i]:.1e})"
                j = unmatched.pop(i)
                assert exact[j] == b["exact"], f"{at}: exact flag of {b['q']}"
                if b["singular"]:
                    assert r["singular"][j], f"{at}: {b['q']} singular in Rust only"
                compared += 1
    assert compared > 500, compared


def test_formulas_are_the_generated_codes(values, shipped):
    for name, v in values.items():
        mine = [[f["function"], f["name"], f["text"], f["latex"]] for f in shipped[name].formulas]
        assert mine == v["formulas"], name
        assert any(f[0] == "fk" for f in mine), name
