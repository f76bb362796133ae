"""kinegen's Python module against what a Python user has, on the UR5: Pinocchio (`pin`),
the Robotics Toolbox (`roboticstoolbox-python`) and EAIK, all in one run.

    pip install pin roboticstoolbox-python eaik      # besides kinegen and numpy
    python kinegen-py/bench/bench.py [--n 10000] [--repeats 5]

Every contender's values are checked equal to kinegen's first (fk and the world
Jacobian to 1e-12 at 100 configurations; every exact IK solution of kinegen among
EAIK's at 100 poses), then each is timed: single calls from Python (the per-call cost a
user pays in a loop) and, where the library has one, its batch call, per configuration.
Times are the best of `--repeats` runs of a loop (µs per call). A contender that is not
installed is left out and said so.
"""

import argparse
import math
import pathlib
import subprocess
import sys
import tempfile
import time

import numpy as np

import kinegen

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "kinegen-py" / "tests"))
from tables import dh_table  # noqa: E402

# robots/ur5.toml: (a, alpha, d) per joint, standard DH.
UR5_DH = dh_table(ROOT / "robots" / "ur5.toml")


def best(f, loops, repeats):
    """Best time per call (µs) of `loops` calls of f, over `repeats` runs."""
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        for _ in range(loops):
            f()
        times.append((time.perf_counter() - t) / loops)
    return min(times) * 1e6


def best_batch(f, count, repeats):
    """Best time per item (µs) of one batch call covering `count` items."""
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        f()
        times.append((time.perf_counter() - t) / count)
    return min(times) * 1e6


def same_angles(a, b):
    d = np.asarray(a) - np.asarray(b)
    return float(np.max(np.abs(d - 2 * np.pi * np.round(d / (2 * np.pi)))))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=10000, help="batch size")
    ap.add_argument("--loops", type=int, default=2000, help="single calls per timing")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument(
        "--batch-repeats", type=int, default=20,
        help="runs of each batch call (one call is short: more runs find the quiet one)",
    )
    a = ap.parse_args()

    rng = np.random.default_rng(0)
    ur5 = kinegen.robots.ur5()
    qs = rng.uniform(-math.pi, math.pi, (a.n, 6))
    poses = ur5.fk(qs)
    check = qs[:100]
    rows = []  # (what, contender, µs)

    # kinegen itself.
    q, pose = qs[0], poses[0]
    rows += [
        ("fk", "kinegen, single call", best(lambda: ur5.fk(q), a.loops, a.repeats)),
        ("fk", "kinegen, batch", best_batch(lambda: ur5.fk(qs), a.n, a.batch_repeats)),
        ("jacobian", "kinegen, single call", best(lambda: ur5.jacobian(q), a.loops, a.repeats)),
        ("jacobian", "kinegen, batch", best_batch(lambda: ur5.jacobian(qs), a.n, a.batch_repeats)),
        ("ik", "kinegen, single call", best(lambda: ur5.ik(pose), a.loops, a.repeats)),
        (
            "ik",
            "kinegen, single call, residuals=False",
            best(lambda: ur5.ik(pose, residuals=False), a.loops, a.repeats),
        ),
        ("ik", "kinegen, batch", best_batch(lambda: ur5.ik(poses), a.n, a.batch_repeats)),
        (
            "ik",
            "kinegen, batch, residuals=False",
            best_batch(lambda: ur5.ik(poses, residuals=False), a.n, a.batch_repeats),
        ),
    ]

    # The generated Rust code, compiled (robots/examples/ur5_batch.rs), on the same
    # configurations and poses, its values checked equal to the module's first.
    subprocess.run(
        ["cargo", "build", "--quiet", "--release", "-p", "kinegen-robots", "--example", "ur5_batch"],
        cwd=ROOT,
        check=True,
    )
    target = pathlib.Path(
        subprocess.run(
            ["cargo", "metadata", "--format-version", "1", "--no-deps"],
            cwd=ROOT,
            check=True,
            capture_output=True,
            text=True,
        ).stdout.split('"target_directory":"')[1].split('"')[0]
    )
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        qs.astype("<f8").tofile(tmp / "q.bin")
        poses.astype("<f8").tofile(tmp / "poses.bin")
        out = subprocess.run(
            [str(target / "release" / "examples" / "ur5_batch"), str(tmp / "q.bin"),
             str(tmp / "poses.bin"), str(tmp / "out.bin"), str(a.batch_repeats)],
            check=True,
            capture_output=True,
            text=True,
        ).stdout.split()
        values = np.fromfile(tmp / "out.bin", dtype="<f8")
    fk_rust = values[: 16 * a.n].reshape(a.n, 4, 4)
    jac_rust = values[16 * a.n:].reshape(a.n, 6, 6)
    assert np.max(np.abs(fk_rust - ur5.fk(qs))) < 1e-12
    assert np.max(np.abs(jac_rust - ur5.jacobian(qs))) < 1e-12
    ks = ur5.ik(poses)
    exact = int(np.sum(ks["valid"] & ks["exact"]))
    assert exact == int(out[3]), (exact, out[3])
    print(f"generated Rust: fk and jacobian equal the module's to 1e-12 at {a.n} configurations; "
          f"ik finds the same {exact} exact solutions of {a.n} poses")
    rows += [
        ("fk", "generated Rust, compiled", float(out[0])),
        ("jacobian", "generated Rust, compiled", float(out[1])),
        ("ik", "generated Rust, compiled", float(out[2])),
    ]

    # Pinocchio, on the UR5's URDF (base_link to tool0), against kinegen reading the same
    # file literally (snap=0: the file's 1.570796327 is not taken as pi/2, as pin reads it).
    try:
        import pinocchio as pin
    except ImportError:
        print("pin (Pinocchio) not installed: left out")
    else:
        path = str(ROOT / "robots" / "urdf" / "ur5.urdf")
        urdf = kinegen.Robot.from_urdf(path, base="base_link", tip="tool0", snap=0.0)
        model = pin.buildModelFromUrdf(path)
        data = model.createData()
        fid = model.getFrameId("tool0")
        assert model.nq == 6, model.nq

        def pin_fk(q):
            pin.framesForwardKinematics(model, data, q)
            return data.oMf[fid].homogeneous

        def pin_jac(q):
            return pin.computeFrameJacobian(model, data, q, fid, pin.LOCAL_WORLD_ALIGNED)

        for x in check:
            assert np.max(np.abs(pin_fk(x) - urdf.fk(x))) < 1e-12
            assert np.max(np.abs(pin_jac(x) - urdf.jacobian(x))) < 1e-12
        print("pin: fk and the world Jacobian equal kinegen's (the same URDF) to 1e-12 at 100 configurations")
        rows += [
            ("fk", "pin framesForwardKinematics", best(lambda: pin_fk(q), a.loops, a.repeats)),
            ("jacobian", "pin computeFrameJacobian", best(lambda: pin_jac(q), a.loops, a.repeats)),
        ]

    # The Robotics Toolbox, with the same DH table (its own UR5 model has d1 = 0.089459).
    try:
        import roboticstoolbox as rtb
    except ImportError:
        print("roboticstoolbox-python not installed: left out")
    else:
        bot = rtb.DHRobot([rtb.RevoluteDH(a=x, alpha=al, d=d) for (x, al, d) in UR5_DH])
        ets = bot.ets()
        for x in check:
            assert np.max(np.abs(bot.fkine(x).A - ur5.fk(x))) < 1e-12
            assert np.max(np.abs(bot.jacob0(x) - ur5.jacobian(x))) < 1e-12
            assert np.max(np.abs(ets.eval(x) - ur5.fk(x))) < 1e-12
            assert np.max(np.abs(ets.jacob0(x) - ur5.jacobian(x))) < 1e-12
        print("roboticstoolbox: fkine, jacob0 (DHRobot and ETS) equal kinegen's to 1e-12 at 100 configurations")
        rows += [
            ("fk", "rtb DHRobot.fkine", best(lambda: bot.fkine(q).A, a.loops // 10, a.repeats)),
            ("fk", "rtb ETS.eval", best(lambda: ets.eval(q), a.loops, a.repeats)),
            ("jacobian", "rtb DHRobot.jacob0", best(lambda: bot.jacob0(q), a.loops // 10, a.repeats)),
            ("jacobian", "rtb ETS.jacob0", best(lambda: ets.jacob0(q), a.loops, a.repeats)),
        ]

    # EAIK, with the same DH table.
    try:
        from eaik.IK_DH import DhRobot
    except ImportError:
        print("eaik not installed: left out")
    else:
        a_, al_, d_ = (np.array(c) for c in zip(*UR5_DH))
        eaik = DhRobot(al_, a_, d_)
        for x in check:
            assert np.max(np.abs(eaik.fwdKin(x) - ur5.fk(x))) < 1e-12
        ks = ur5.ik(poses[:100])
        matched = 0
        for i in range(100):
            theirs = [np.asarray(s) for s in eaik.IK(poses[i]).Q]
            ours = ks["q"][i][ks["valid"][i] & ks["exact"][i]]
            assert all(min(same_angles(o, t) for t in theirs) < 1e-6 for o in ours), i
            matched += len(ours)
        print(f"eaik: fk equals kinegen's to 1e-12; all {matched} exact kinegen IK solutions of 100 poses are among EAIK's")
        batch = [p for p in poses]
        rows += [
            ("ik", "eaik IK, single call", best(lambda: eaik.IK(pose), a.loops, a.repeats)),
            ("ik", "eaik IK_batched, 1 thread", best_batch(lambda: eaik.IK_batched(batch, 1), a.n, a.batch_repeats)),
        ]

    print(f"\nUR5, µs per configuration or pose (best of {a.repeats} runs of single calls, "
          f"{a.batch_repeats} of batches of {a.n}):")
    for what in ["fk", "jacobian", "ik"]:
        mine = {c: t for (w, c, t) in rows if w == what}
        single = mine["kinegen, single call"]
        batch = mine["kinegen, batch"]
        rust = mine["generated Rust, compiled"]
        for contender, t in mine.items():
            if contender.startswith("generated"):
                ratio = f"   (kinegen's batch is {batch / t:.1f}× this)"
            elif contender.startswith("kinegen"):
                ratio = ""
            else:
                ratio = f"   ({t / single:.2f}× kinegen's single call"
                # EAIK measures no residuals: against kinegen's call without them too.
                plain = mine.get("kinegen, single call, residuals=False")
                ratio += f", {t / plain:.2f}× without residuals)" if plain else ")"
            print(f"  {what:<9} {contender:<38} {t:9.3f}{ratio}")


if __name__ == "__main__":
    main()
