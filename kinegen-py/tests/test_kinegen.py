"""The Python module against independent numeric references.

FK against a product of DH transforms written here in NumPy; Jacobians and Hessians
against finite differences; det J against numpy.linalg.det; IK by the IKFast-style
self-test (poses from random configurations, every exact solution put back through fk,
the generating configuration found among them). Fixed seeds throughout.
"""

import math
import pathlib

import numpy as np
import pytest

import kinegen
from tables import dh_table

ROOT = pathlib.Path(__file__).resolve().parents[2]
ROBOTS = ROOT / "robots"
TAU = 2 * math.pi


def dh_standard(a, alpha, d, theta):
    """The standard DH transform Rz(theta) Tz(d) Tx(a) Rx(alpha)."""
    ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
    return np.array(
        [
            [ct, -st * ca, st * sa, a * ct],
            [st, ct * ca, -ct * sa, a * st],
            [0.0, sa, ca, d],
            [0.0, 0.0, 0.0, 1.0],
        ]
    )


# The tables of robots/ur5.toml and robots/puma560.toml, rows (a, alpha, d), revolute.
UR5_DH = dh_table(ROBOTS / "ur5.toml")
PUMA_DH = dh_table(ROBOTS / "puma560.toml")


def dh_fk(table, q):
    t = np.eye(4)
    for (a, alpha, d), qi in zip(table, q):
        t = t @ dh_standard(a, alpha, d, qi)
    return t


def sample(robot, m, rng):
    """m configurations within the robot's limits (and within [-pi, pi] for revolute
    joints, [-0.5, 0.5] m where a prismatic joint has no limits)."""
    lim = robot.limits
    lo = np.maximum(lim[:, 0], -math.pi)
    hi = np.minimum(lim[:, 1], math.pi)
    return rng.uniform(lo, hi, size=(m, robot.dof))


def fk_fd_jacobian(robot, q, h):
    """The world Jacobian from central differences of fk: position rows from dp/dq,
    rotation rows from the axial vector of dR/dq R^T."""
    n = robot.dof
    j = np.zeros((6, n))
    r = robot.fk(q)[:3, :3]
    for k in range(n):
        e = np.zeros(n)
        e[k] = h
        tp, tm = robot.fk(q + e), robot.fk(q - e)
        j[:3, k] = (tp[:3, 3] - tm[:3, 3]) / (2 * h)
        w = (tp[:3, :3] - tm[:3, :3]) / (2 * h) @ r.T
        j[3:, k] = [w[2, 1], w[0, 2], w[1, 0]]
    return j


def same_angles(a, b, revolute):
    """Difference of two joint vectors, whole turns removed on revolute joints."""
    d = np.asarray(a) - np.asarray(b)
    d[revolute] = (d[revolute] + math.pi) % TAU - math.pi
    return np.max(np.abs(d))


@pytest.fixture(scope="module")
def ur5():
    return kinegen.robots.ur5()


@pytest.fixture(scope="module")
def puma():
    return kinegen.robots.puma560()


# ---------------------------------------------------------------------------------------
# Loading


def test_every_shipped_robot_loads_and_the_stub_lists_it(shipped):
    names = kinegen.robots.names()
    assert sorted(names) == sorted(p.stem for p in ROBOTS.glob("*.toml") if p.name != "Cargo.toml")
    stub = (pathlib.Path(kinegen.__file__).parent / "robots.pyi").read_text()
    for name in names:
        assert f"def {name}() -> Robot" in stub, name
        r = shipped[name]
        assert r.dof == len(r.joint_names) == r.limits.shape[0]
        assert r.limits.shape == (r.dof, 2)
        t = r.fk(np.zeros(r.dof))
        assert t.shape == (4, 4)
        np.testing.assert_array_equal(t[3], [0, 0, 0, 1])
        np.testing.assert_allclose(t[:3, :3] @ t[:3, :3].T, np.eye(3), atol=1e-12)


def test_the_stub_declares_every_public_member():
    stub = (pathlib.Path(kinegen.__file__).parent / "_kinegen.pyi").read_text()
    members = [m for m in dir(kinegen.Robot) if not m.startswith("__")]
    assert "fk" in members and "ik_near" in members
    for m in members:
        assert f"    def {m}(" in stub, m
    assert "def robot_names(" in stub and "class LoadError(Exception)" in stub


def test_properties(ur5, puma):
    assert ur5.name == "UR5" and puma.name == "PUMA 560"
    assert ur5.dof == 6
    assert ur5.joint_names == ["q1", "q2", "q3", "q4", "q5", "q6"]
    np.testing.assert_allclose(puma.limits[1], np.array([-45, 225]) * math.pi / 180)
    assert ur5.has_det and not kinegen.robots.planar_rr().has_det
    assert "UR5" in repr(ur5)
    assert ur5.ik_family is not None


def test_from_toml_and_from_urdf_match_the_shipped_robots(ur5, shipped):
    q = sample(ur5, 5, np.random.default_rng(1))
    np.testing.assert_array_equal(
        kinegen.Robot.from_toml(ROBOTS / "ur5.toml").fk(q), ur5.fk(q)
    )
    via_urdf = kinegen.Robot.from_urdf(
        str(ROBOTS / "urdf" / "ur5.urdf"), base="base_link", tip="tool0"
    )
    np.testing.assert_allclose(via_urdf.fk(q), shipped["ur5_urdf"].fk(q), atol=1e-12)
    # The URDF's base is the DH base turned by pi about z.
    rz = np.diag([-1.0, -1.0, 1.0, 1.0])
    np.testing.assert_allclose(rz @ via_urdf.fk(q), ur5.fk(q), atol=1e-12)


def test_from_dh_dicts_and_tuples(ur5):
    rows = [
        {"a": 0, "alpha": "pi/2", "d": "d1"},
        {"a": "a2", "alpha": 0, "d": 0},
        {"a": "a3", "alpha": 0, "d": 0},
        {"a": 0, "alpha": "pi/2", "d": "d4"},
        {"a": 0, "alpha": "-pi/2", "d": "d5"},
        {"a": 0, "alpha": 0, "d": "d6", "limits": ["-pi", "pi"]},
    ]
    params = dict(d1=0.089159, a2=-0.425, a3=-0.39225, d4=0.10915, d5=0.09465, d6=0.0823)
    r = kinegen.Robot.from_dh(rows, params=params, name="my UR5")
    assert r.name == "my UR5"
    np.testing.assert_allclose(r.limits[5], [-math.pi, math.pi])
    det_line = [line for line in r.det.splitlines() if line.startswith("det J =")]
    assert det_line == [line for line in ur5.det.splitlines() if line.startswith("det J =")]
    q = sample(ur5, 5, np.random.default_rng(2))
    np.testing.assert_allclose(r.fk(q), ur5.fk(q), atol=1e-15)
    numeric = kinegen.Robot.from_dh(UR5_DH)
    np.testing.assert_allclose(numeric.fk(q), ur5.fk(q), atol=1e-14)
    offset = kinegen.Robot.from_dh([(1.0, 0.0, 0.0, "pi/2")])
    np.testing.assert_allclose(offset.fk([0.0])[:2, 3], [0.0, 1.0], atol=1e-15)
    modified = kinegen.Robot.from_dh([(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)], convention="modified")
    np.testing.assert_allclose(modified.fk([math.pi / 2, 0.0])[:2, 3], [0.0, 1.0], atol=1e-15)


# ---------------------------------------------------------------------------------------
# First order


def test_instruction_lists_give_the_graphs_values(shipped):
    # The methods evaluate flat instruction lists built from the engine's graph, with the
    # generated code's sines and cosines (kinegen::math::sin_cos_n); walking the graph
    # itself (as `kinegen eval` does, with the platform's) must give the same values up
    # to those functions' rounding: a few ulps of the entries' size.
    rng = np.random.default_rng(13)
    for name, r in shipped.items():
        for q in sample(r, 5, rng):
            for which in ["fk", "jacobian", "jacobian_ee"]:
                mine = getattr(r, which)(q)
                ref = r._reference(which, q)
                flat = mine[:3].ravel() if which == "fk" else mine.ravel()
                scale = max(1.0, np.abs(ref).max())
                np.testing.assert_allclose(
                    flat, ref, rtol=0, atol=16 * np.finfo(float).eps * scale,
                    err_msg=f"{name} {which}",
                )


@pytest.mark.parametrize("which", ["ur5", "puma"])
def test_fk_against_a_product_of_dh_transforms(which, ur5, puma):
    robot, table = (ur5, UR5_DH) if which == "ur5" else (puma, PUMA_DH)
    qs = sample(robot, 200, np.random.default_rng(3))
    batch = robot.fk(qs)
    assert batch.shape == (200, 4, 4)
    for q, t in zip(qs, batch):
        np.testing.assert_allclose(t, dh_fk(table, q), atol=1e-14)


def test_jacobians_against_finite_differences_on_every_shipped_robot(shipped):
    # Central differences: truncation ~ h^2 (|fk'''| ~ reach ~ 1 m), rounding ~ eps/h.
    h = 1e-5
    tol = 10 * (h * h + np.finfo(float).eps / h)
    rng = np.random.default_rng(4)
    for name, r in shipped.items():
        for q in sample(r, 3, rng):
            j = r.jacobian(q)
            assert j.shape == (6, r.dof)
            np.testing.assert_allclose(j, fk_fd_jacobian(r, q, h), atol=tol, err_msg=name)
            # The tool-frame Jacobian is the world one seen in the tool's axes.
            rot = r.fk(q)[:3, :3]
            ee = np.vstack([rot.T @ j[:3], rot.T @ j[3:]])
            np.testing.assert_allclose(r.jacobian_ee(q), ee, atol=1e-12, err_msg=name)


def test_det_against_numpy_and_its_factors(shipped):
    rng = np.random.default_rng(5)
    with_det = [n for n, r in shipped.items() if r.has_det]
    assert "ur5" in with_det and "puma560" in with_det
    for name in with_det:
        r = shipped[name]
        qs = sample(r, 50, rng)
        det = r.jacobian_det(qs)
        ref = np.linalg.det(r.jacobian(qs))
        np.testing.assert_allclose(det, ref, rtol=1e-9, atol=1e-12, err_msg=name)
        # det J = c * prod(factor ** power), c the same everywhere.
        names, values = r.singular_factors(qs)
        powers = np.array([p for (_, p, _) in r.det_factors])
        assert names == [t for (t, _, _) in r.det_factors]
        prod = np.prod(values**powers, axis=1)
        keep = np.abs(prod) > 1e-6
        c = det[keep] / prod[keep]
        np.testing.assert_allclose(c, c[0], rtol=1e-9, err_msg=name)
        # Manipulability of a square J is |det J|.
        np.testing.assert_allclose(r.manipulability(qs), np.abs(det), rtol=1e-7, atol=1e-12)


def test_a_vanishing_factor_makes_the_jacobian_singular(ur5):
    q = np.array([0.3, -1.0, 1.2, 0.4, 0.0, 0.7])  # q5 = 0: the wrist is singular
    names, values = ur5.singular_factors(q)
    assert values[names.index("sin(q5)")] == 0.0
    assert abs(ur5.jacobian_det(q)) < 1e-15
    assert np.linalg.matrix_rank(ur5.jacobian(q), tol=1e-9) == 5


def test_manipulability_of_a_redundant_arm():
    panda = kinegen.robots.panda()
    q = sample(panda, 10, np.random.default_rng(6))
    j = panda.jacobian(q)
    ref = np.sqrt(np.linalg.det(j @ np.swapaxes(j, 1, 2)))
    np.testing.assert_allclose(panda.manipulability(q), ref, rtol=1e-9)


# ---------------------------------------------------------------------------------------
# Second order


@pytest.mark.parametrize("name", ["ur5", "puma560", "panda", "scara", "planar_rrr"])
def test_hessian_and_jdot_qdot_against_finite_differences(name, shipped):
    r = shipped[name]
    rng = np.random.default_rng(7)
    h = 1e-5
    for q in sample(r, 3, rng):
        hess = r.hessian(q)
        assert hess.shape == (r.dof, 6, r.dof)
        for k in range(r.dof):
            e = np.zeros(r.dof)
            e[k] = h
            fd = (r.jacobian(q + e) - r.jacobian(q - e)) / (2 * h)
            np.testing.assert_allclose(hess[k], fd, atol=1e-8, err_msg=f"{name} H[{k}]")
        qd = rng.uniform(-1, 1, r.dof)
        ref = np.einsum("kri,k,i->r", hess, qd, qd)
        np.testing.assert_allclose(r.jdot_qdot(q, qd), ref, atol=1e-12)


# ---------------------------------------------------------------------------------------
# Batches equal single calls


def test_batches_equal_single_calls(ur5):
    qs = sample(ur5, 7, np.random.default_rng(8))
    qd = np.random.default_rng(9).uniform(-1, 1, qs.shape)
    for method in ["fk", "frames", "jacobian", "jacobian_ee", "jacobian_det", "manipulability", "hessian"]:
        f = getattr(ur5, method)
        batch = f(qs)
        assert np.shape(batch)[0] == 7, method
        for q, b in zip(qs, batch):
            np.testing.assert_array_equal(f(q), b, err_msg=method)
    names, values = ur5.singular_factors(qs)
    for q, v in zip(qs, values):
        np.testing.assert_array_equal(ur5.singular_factors(q)[1], v)
    jq = ur5.jdot_qdot(qs, qd)
    for q, v, b in zip(qs, qd, jq):
        np.testing.assert_array_equal(ur5.jdot_qdot(q, v), b)
    poses = ur5.fk(qs)
    many = ur5.ik(poses)
    for i, pose in enumerate(poses):
        one = ur5.ik(pose)
        k = one["q"].shape[0]
        np.testing.assert_array_equal(many["q"][i, :k], one["q"])
        assert not many["valid"][i, k:].any()
        for key in ["valid", "exact", "singular", "within_limits"]:
            np.testing.assert_array_equal(many[key][i, :k], one[key])
    near, found = ur5.ik_near(poses, qs)
    assert found.all()
    for i in range(7):
        np.testing.assert_array_equal(near[i], ur5.ik_near(poses[i], qs[i]))
    # Lists are arrays too, and so are arrays in any memory layout (Fortran order, a
    # strided view): the same values as a C-contiguous array's.
    np.testing.assert_array_equal(ur5.fk(qs[0].tolist()), ur5.fk(qs[0]))
    np.testing.assert_array_equal(ur5.fk(np.asfortranarray(qs)), ur5.fk(qs))
    wide = np.repeat(qs, 2, axis=1)
    np.testing.assert_array_equal(ur5.jacobian(wide[:, ::2]), ur5.jacobian(qs))
    np.testing.assert_array_equal(ur5.ik(np.asfortranarray(poses))["q"], many["q"])


# ---------------------------------------------------------------------------------------
# Inverse kinematics: the IKFast-style self-test


@pytest.mark.parametrize("which", ["ur5", "puma"])
def test_ik_self_test_2000_poses(which, ur5, puma):
    robot = ur5 if which == "ur5" else puma
    rng = np.random.default_rng(10)
    qs = sample(robot, 2000, rng)
    poses = robot.fk(qs)
    sol = robot.ik(poses)
    revolute = np.ones(robot.dof, dtype=bool)
    missed = []
    for i in range(len(qs)):
        valid = sol["valid"][i]
        assert valid.any(), i
        for j in np.flatnonzero(valid & sol["exact"][i]):
            t = robot.fk(sol["q"][i, j])
            assert np.max(np.abs(t - poses[i])) < 1e-9, (i, j)
            assert sol["residual"][i, j] < 1e-9
        exact = sol["q"][i][valid & sol["exact"][i]]
        if not any(same_angles(s, qs[i], revolute) < 1e-7 for s in exact):
            missed.append(i)
    # Every generating configuration is found, except near a singularity, where the
    # solutions are a continuum or the branches meet.
    for i in missed:
        _, f = robot.singular_factors(qs[i])
        assert np.min(np.abs(f)) < 1e-3, (i, qs[i])
    assert len(missed) <= 2, missed
    print(f"{which}: {len(missed)} of {len(qs)} generating configurations not recovered")


def test_ik_flags_at_a_singular_pose(ur5):
    q = np.array([0.3, -1.0, 1.2, 0.4, 0.0, 0.7])
    s = ur5.ik(ur5.fk(q))
    # The shoulder's other branches have sin(q5) != 0: only the branches at q5 = 0 or pi
    # are flagged, each with the factor that vanishes.
    _, f = ur5.singular_factors(s["q"])
    vanishing = np.any(np.abs(f) <= 1e-9, axis=1)
    assert vanishing.any() and not vanishing.all()
    np.testing.assert_array_equal(s["singular"], vanishing)
    for flagged, names in zip(s["singular"], s["singular_factors"]):
        assert names == (["sin(q5) = 0"] if flagged else [])


def test_a_batch_whose_later_poses_have_more_solutions(ur5):
    # 4 (out of reach: least squares), 6 (q5 = 0) and 8 solutions, in that order: the
    # batch's rows are spread out twice as it is solved, and equal the single calls.
    far = np.eye(4)
    far[0, 3] = 5.0
    singular = ur5.fk(np.array([0.3, -1.0, 1.2, 0.4, 0.0, 0.7]))
    regular = ur5.fk(np.array([0.3, -1.0, 1.2, 0.4, 0.5, 0.7]))
    poses = np.stack([far, singular, regular, far])
    many = ur5.ik(poses)
    assert many["q"].shape == (4, 8, 6)
    for i, pose in enumerate(poses):
        one = ur5.ik(pose)
        k = one["q"].shape[0]
        assert many["valid"][i].sum() == k
        np.testing.assert_array_equal(many["q"][i, :k], one["q"])
        assert np.isnan(many["q"][i, k:]).all() and np.isnan(many["residual"][i, k:]).all()
        for key in ["exact", "singular", "within_limits", "residual"]:
            np.testing.assert_array_equal(many[key][i, :k], one[key])
    assert [ur5.ik(p)["q"].shape[0] for p in poses] == [4, 6, 8, 4]


def test_ik_out_of_reach_gives_no_exact_solution(ur5):
    pose = np.eye(4)
    pose[0, 3] = 5.0  # 5 m away: the UR5 reaches 0.85 m
    s = ur5.ik(pose)
    assert not s["exact"].any()
    assert ur5.ik_near(pose, np.zeros(6)) is None


def test_ik_near_finds_the_configuration_it_is_given(puma):
    rng = np.random.default_rng(11)
    qs = sample(puma, 50, rng)
    near, found = puma.ik_near(puma.fk(qs), qs + rng.uniform(-1e-3, 1e-3, qs.shape))
    assert found.all()
    np.testing.assert_allclose(near, qs, atol=1e-8)


def test_ik_of_a_seven_joint_arm_needs_the_locked_joint():
    iiwa = kinegen.robots.kuka_iiwa14()
    assert "joint 7 locked" in iiwa.ik_family
    q = sample(iiwa, 1, np.random.default_rng(12))[0]
    pose = iiwa.fk(q)
    with pytest.raises(ValueError, match="locks joint 7"):
        iiwa.ik(pose)
    s = iiwa.ik(pose, locked=float(q[6]))
    exact = s["q"][s["exact"]]
    for x in exact:
        np.testing.assert_allclose(iiwa.fk(x), pose, atol=1e-9)
        assert x[6] == q[6]
    assert min(same_angles(x, q, np.ones(7, dtype=bool)) for x in exact) < 1e-7
    np.testing.assert_allclose(iiwa.ik_near(pose, q), q, atol=1e-7)


# ---------------------------------------------------------------------------------------
# Text


def test_text_outputs(ur5):
    assert "det J = a2*a3*sin(q3)*sin(q5)*" in ur5.det
    latex = ur5.latex()
    assert "\\sin" in latex and "align" in latex
    assert "\\det" not in ur5.latex("fk")
    rust = ur5.rust()
    assert "pub struct" in rust and "fn fk" in rust and "fn jacobian_det" in rust
    r = ur5._repr_latex_()
    assert r.startswith("$\\det J = ") and r.endswith("$")


def test_html_shows_det_and_every_factor_as_mathml(shipped):
    # Jupyter's rich display: well-formed markup (parsed as XML here), det J as one
    # displayed <math> and one <math> per singular factor, each factor's text beside it.
    import xml.etree.ElementTree as ET

    for name, r in shipped.items():
        html = r._repr_html_()
        root = ET.fromstring(html)
        maths = [e for e in root.iter() if e.tag == "math"]
        factors = r.det_factors
        if factors:  # det J, or a planar arm's square task Jacobian's det
            assert sum(m.get("display") == "block" for m in maths) == 1, name
            assert len(maths) == 1 + len(factors), name
            for text, _, _ in factors:
                assert f"{text} = 0" in html, (name, text)
            # Every formula is laid out from tokens, not left as plain text.
            assert all(m.find(".//mtext") is None for m in maths[:1]), name
        else:
            assert not maths and "Determinant" in html, name


# ---------------------------------------------------------------------------------------
# Errors


def test_load_errors_name_the_file_and_line(tmp_path):
    bad = tmp_path / "r.toml"
    bad.write_text(
        'name = "R"\nconvention = "standard"\n[[joints]]\ntype = "revolute"\na = 1\nalhpa = 0\nd = 0\n'
    )
    with pytest.raises(kinegen.LoadError) as e:
        kinegen.Robot.from_toml(bad)
    assert f"{bad}:6: joints[0].alhpa: unknown column" in str(e.value)
    with pytest.raises(kinegen.LoadError, match="cannot read"):
        kinegen.Robot.from_toml(tmp_path / "missing.toml")
    with pytest.raises(kinegen.LoadError, match="missing.urdf"):
        kinegen.Robot.from_urdf(tmp_path / "missing.urdf")
    with pytest.raises(kinegen.LoadError, match="--tip"):
        kinegen.Robot.from_urdf(ROBOTS / "urdf" / "ur5.urdf", tip="no_such_link")
    broken = tmp_path / "broken.urdf"
    broken.write_text("<robot name='x'>\n<link name='a'>\n</robot>\n")
    with pytest.raises(kinegen.LoadError, match="broken.urdf:"):
        kinegen.Robot.from_urdf(broken)
    with pytest.raises(kinegen.LoadError, match="missing column `alpha`"):
        kinegen.Robot.from_dh([{"a": 1, "d": 0}])
    assert issubclass(kinegen.LoadError, Exception)


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda r: r.fk(np.zeros(5)), "expected shape"),
        (lambda r: r.fk(np.zeros((2, 3, 6))), "expected shape"),
        (lambda r: r.jacobian(np.zeros((4, 7))), "expected shape"),
        (lambda r: r.fk([0, 0, np.nan, 0, 0, 0]), "entry 2 is not a finite number"),
        (lambda r: r.jacobian_det(np.full((3, 6), np.inf)), "not a finite number \\(row 0\\)"),
        (lambda r: r.hessian([0, 0, 0, 0, 0, "x"]), "could not convert"),
        (lambda r: r.jdot_qdot(np.zeros(6), np.zeros((2, 6))), "shape of q"),
        (lambda r: r.ik(np.zeros((3, 3))), "expected shape"),
        (lambda r: r.ik(np.full((4, 4), np.nan)), "not a finite number"),
        (lambda r: r.ik(2 * np.eye(4)), "last row"),
        (lambda r: r.ik(np.diag([2.0, 1.0, 1.0, 1.0])), "not a rotation"),
        (lambda r: r.ik(np.stack([np.eye(4), 2 * np.eye(4)])), "pose 1: the last row"),
        (lambda r: r.ik_near(np.eye(4), np.zeros((2, 6))), "one configuration per pose"),
        (lambda r: r.latex("nope"), "expected fk, jacobian"),
        (lambda r: kinegen.Robot.shipped("ur7"), "unknown robot `ur7`"),
        (lambda r: kinegen.Robot.shipped("robots/ur5.toml"), "is a path"),
        (lambda r: kinegen.Robot.from_dh([(1.0, 0.0)]), "got 2 values"),
        (lambda r: kinegen.Robot.from_dh([object()]), "expected a dict"),
        (lambda r: kinegen.Robot.from_dh([(float("nan"), 0, 0)]), "not a finite number"),
        (lambda r: kinegen.Robot.from_urdf("x.urdf", snap=-1.0), "snap"),
        (lambda r: kinegen.robots.planar_rr().jacobian_det([0.1, 0.2]), "not available"),
    ],
)
def test_value_errors(call, message, ur5):
    with pytest.raises(ValueError, match=message):
        call(ur5)


def test_no_closed_form_ik_is_a_value_error():
    r = kinegen.Robot.from_dh([(1.0, 0.3, 0.2)] * 4)
    assert r.ik_family is None
    with pytest.raises(ValueError, match="no closed-form inverse kinematics"):
        r.ik(np.eye(4))


def test_scara_urdf_solves_the_task_rows_it_is_given():
    urdf = ROBOTS / "urdf" / "cobra600.urdf"
    with pytest.raises(ValueError, match="task rows \\[x, y, z, rz\\] make it solvable"):
        kinegen.Robot.from_urdf(urdf).ik(np.eye(4))
    with pytest.raises(ValueError, match="unknown task row `w`"):
        kinegen.Robot.from_urdf(urdf, task=["x", "y", "w"])
    r = kinegen.Robot.from_urdf(urdf, task=["x", "y", "z", "rz"])
    assert r.ik_family == "planar"
    q0 = np.array([0.4, -1.1, 0.12, 2.0])
    sol = r.ik(r.fk(q0))
    exact = sol["q"][sol["valid"] & sol["exact"]]
    assert len(exact) == 2
    np.testing.assert_allclose(r.fk(exact), np.broadcast_to(r.fk(q0), (2, 4, 4)), atol=1e-12)
    assert np.abs(exact - q0).max(axis=1).min() < 1e-12


# ---------------------------------------------------------------------------------------
# The example script


def test_singularity_map_example_runs(tmp_path):
    import subprocess
    import sys

    script = ROOT / "kinegen-py" / "examples" / "singularity_map.py"
    out = subprocess.run(
        [sys.executable, str(script), "--n", "40", "--out", str(tmp_path / "map.png")],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    assert "det J = a2*a3*sin(q3)*sin(q5)*" in out
    assert "sin(q5) = 0" in out
    assert ("wrote" in out and (tmp_path / "map.png").is_file()) or "matplotlib is optional" in out
