"""The singularity map of a URDF arm: det J and its factors, and |det J| over (q2, q3).

    python kinegen-py/examples/singularity_map.py [ARM.urdf] [--tip LINK] [--out FILE.png]

Without a file, the UR5 of robots/urdf/ur5.urdf (base_link to tool0). The plot needs matplotlib (optional);
without it the script prints the map's extremes instead.
"""

import argparse
import pathlib

import numpy as np

import kinegen

HERE = pathlib.Path(__file__).resolve().parent
DEFAULT = HERE.parents[1] / "robots" / "urdf" / "ur5.urdf"


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("urdf", nargs="?", default=str(DEFAULT))
    p.add_argument("--base")
    p.add_argument("--tip")
    p.add_argument("--out", default="singularity_map.png")
    p.add_argument("--n", type=int, default=200, help="grid points per axis")
    a = p.parse_args()
    if a.urdf == str(DEFAULT) and a.tip is None:
        a.base, a.tip = "base_link", "tool0"  # the file has several leaves

    # symbolic: the lengths keep names (d1, a2, ...) so the factors read as in a textbook.
    robot = kinegen.Robot.from_urdf(a.urdf, base=a.base, tip=a.tip, symbolic=True)
    print(f"{robot.name}: {robot.dof} joints {robot.joint_names}")
    if not robot.has_det:
        print("no square Jacobian: no det J (see robot.manipulability)")
        return
    print(robot.det)
    print("singular where a factor vanishes:")
    for text, power, joints in robot.det_factors:
        on = ", ".join(f"q{j}" for j in joints) or "no joint"
        print(f"  {text} = 0{'' if power == 1 else f'  (power {power})'}   [{on}]")

    # |det J| over q2, q3, the other joints at a generic configuration.
    q0 = np.array([0.3, -0.7, 1.1, -0.4, 0.9, 0.2][: robot.dof])
    grid = np.linspace(-np.pi, np.pi, a.n)
    q2, q3 = np.meshgrid(grid, grid, indexing="ij")
    qs = np.tile(q0, (q2.size, 1))
    qs[:, 1], qs[:, 2] = q2.ravel(), q3.ravel()
    det = np.abs(robot.jacobian_det(qs)).reshape(q2.shape)
    i = np.unravel_index(np.argmin(det), det.shape)
    print(f"|det J| over q2, q3 in [-pi, pi]: max {det.max():.4g}, min {det.min():.3g} "
          f"at q2 = {grid[i[0]]:.3f}, q3 = {grid[i[1]]:.3f}")

    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is optional and not installed: no plot (pip install matplotlib)")
        return
    fig, ax = plt.subplots(figsize=(6, 5))
    m = ax.pcolormesh(grid, grid, np.log10(det.T + 1e-12), shading="auto", cmap="viridis")
    fig.colorbar(m, label="log10 |det J|")
    ax.set_xlabel("q2 (rad)")
    ax.set_ylabel("q3 (rad)")
    ax.set_title(f"{robot.name}: |det J|, other joints at {np.round(q0, 2).tolist()}")
    fig.tight_layout()
    fig.savefig(a.out, dpi=120)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
