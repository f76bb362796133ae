"""The DH tables of robots/*.toml as numbers, for references built outside kinegen (the
tests' product of DH transforms, the benchmark's contenders): read from the files
themselves, so that no table is written out twice."""

import math
import tomllib


def dh_table(path):
    """Rows (a, alpha, d) of a standard-DH robot file whose joints are all revolute
    without offsets: each entry a number or a product/quotient of `pi` and the file's
    parameters (``"pi/2"``, ``"-d1"``)."""
    with open(path, "rb") as f:
        robot = tomllib.load(f)
    if robot.get("convention") != "standard":
        raise ValueError(f"{path}: not a standard DH table")
    names = {"pi": math.pi, **robot.get("params", {})}

    def value(x):
        if isinstance(x, (int, float)):
            return float(x)
        # The files' expressions are arithmetic of names and numbers only.
        return float(eval(x, {"__builtins__": {}}, names))

    if "tool" in robot or "base" in robot:
        raise ValueError(f"{path}: a base or tool frame besides the table")
    rows = []
    for joint in robot["joints"]:
        plain = joint.get("type", "revolute") == "revolute"
        if not plain or "theta" in joint or "offset" in joint:
            raise ValueError(f"{path}: a joint that is not a plain revolute one")
        rows.append(tuple(value(joint.get(k, 0)) for k in ("a", "alpha", "d")))
    return rows
