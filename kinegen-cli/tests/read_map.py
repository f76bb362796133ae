"""`kinegen reach`'s files as Reuleaux's users and NumPy users open them.

    python kinegen-cli/tests/read_map.py path/to/kinegen

Writes a UR5 map at 0.3 m as `.h5` and `.npz` into a temporary directory, then checks
with h5py that the HDF5 file has Reuleaux's layout (`/Spheres/sphere_dataset` N×4
float64 with a float32 `Resolution` attribute, `/Poses/poses_dataset` M×10 float32),
with numpy that the `.npz` holds the same tables, and that each voxel's reachability
index matches its rows of the pose table. Exits non-zero on any failure.
"""

import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np


def main(kinegen):
    with tempfile.TemporaryDirectory() as d:
        h5 = os.path.join(d, "ur5.h5")
        npz = os.path.join(d, "ur5.npz")
        for out in (h5, npz):
            subprocess.run(
                [kinegen, "reach", "ur5", "--resolution", "0.3", "-o", out],
                check=True,
                stdout=subprocess.DEVNULL,
            )
        with h5py.File(h5, "r") as f:
            spheres = f["/Spheres/sphere_dataset"]
            poses = f["/Poses/poses_dataset"]
            assert spheres.dtype == np.float64 and spheres.shape[1] == 4, spheres
            assert poses.dtype == np.float32 and poses.shape[1] == 10, poses
            resolution = spheres.attrs["Resolution"]
            assert resolution.dtype == np.float32 and abs(resolution - 0.3) < 1e-7
            s, p = spheres[()], poses[()]
            names = [n.decode() for n in f["/kinegen/factor_names"][()]]
        z = np.load(npz)
        assert np.array_equal(z["spheres"], s)
        assert np.array_equal(z["poses"], p)
        assert list(z["factor_names"]) == names, (list(z["factor_names"]), names)
        # Each voxel's rows in the pose table: its reachability index of 50 poses.
        centres, counts = np.unique(p[:, :3], axis=0, return_counts=True)
        assert len(centres) == len(s)
        by_centre = {tuple(c): n for c, n in zip(centres, counts)}
        for row in s:
            n = by_centre[tuple(row[:3].astype(np.float32))]
            assert abs(row[3] - 100.0 * n / 50) < 1e-9, (row, n)
        # Unit quaternions, poses one voxel radius from their centre.
        assert np.allclose(np.linalg.norm(p[:, 6:], axis=1), 1.0, atol=1e-6)
        assert np.allclose(np.linalg.norm(p[:, 3:6] - p[:, :3], axis=1), 0.3, atol=1e-6)
        print(f"read_map.py: {len(s)} spheres, {len(p)} poses, h5py and numpy agree")


if __name__ == "__main__":
    main(sys.argv[1])
