"""Other projects' test suites, ported to urkin: every property ur-analytic-ik asserts of its
closed-form IK (on all seven arms, with its own sampling ranges), its real-robot UR5e data, and
Modern Robotics' documented examples for the functions urkin shares with it.

The peers themselves are not installed in CI: their properties are restated here, and the
expected numbers are the ones their documentation prints (inputs and outputs of the book's
examples), never values printed by urkin."""

import re
from pathlib import Path

import numpy as np
import pytest

import urkin
from tests.reference import OFFICIAL_DH, dh_fk
from urkin import poe
from urkin.analytic_ik import ik_analytic, ik_closest
from urkin.transforms import adjoint, inv_transform, se3_exp, se3_log, so3_exp, so3_log

RUNS = 300  # ur-analytic-ik uses 1000 per property and arm; 300 × 7 arms keeps the suite fast
ARMS = urkin.ROBOTS


def official_fk(arm, q):
    return dh_fk(OFFICIAL_DH[arm.name], q)


# ------------------------------------------------------------- ur-analytic-ik's properties


@pytest.fixture(params=ARMS)
def arm(request):
    return urkin.robot(request.param)


def test_consistency_and_correctness(arm):
    """Every solution reaches the pose it was asked for (so all solutions agree)."""
    rng = np.random.default_rng(0)
    q = rng.uniform(-2 * np.pi, 2 * np.pi, (RUNS, 6))
    T = urkin.fk(arm, urkin.transforms.wrap_angles(q))
    for pose in T:
        for solution in ik_analytic(arm, pose):
            np.testing.assert_allclose(official_fk(arm, solution), pose, atol=1e-8)


def test_correctness_at_the_edge_case_configuration(arm):
    pose = urkin.fk(arm, np.deg2rad([0, -45, -90, -90, 90, 0]))
    found = ik_analytic(arm, pose)
    assert len(found) >= 1
    for solution in found:
        np.testing.assert_allclose(official_fk(arm, solution), pose, atol=1e-8)


def test_inclusion(arm):
    """The configuration a pose came from is one of its solutions."""
    rng = np.random.default_rng(1)
    for q in rng.uniform(-np.pi / 2, np.pi / 2, (RUNS, 6)):
        found = ik_analytic(arm, urkin.fk(arm, q))
        assert np.any([np.allclose(q, s) for s in found])


@pytest.mark.parametrize("far", [5.0, 20.0])
def test_strictness(arm, far):
    """Unreachable poses have no solutions."""
    pose = np.array([[1.0, 0, 0, far], [0, 0, -1, far], [0, 1, 0, far], [0, 0, 0, 1]])
    assert len(ik_analytic(arm, pose)) == 0
    assert not ik_closest(arm, pose, np.zeros(6)).success


def test_range(arm):
    rng = np.random.default_rng(2)
    q = rng.uniform(-2 * np.pi, 2 * np.pi, (RUNS, 6))
    found = ik_analytic(arm, urkin.fk(arm, urkin.transforms.wrap_angles(q)))
    assert found.shape == (RUNS, 8, 6)  # a stack: eight slots per pose, NaN rows where none
    solutions = found[~np.isnan(found).any(axis=-1)]
    assert len(solutions) >= RUNS
    assert np.all((solutions > -np.pi) & (solutions <= np.pi))


def test_axis_aligned_top_down_pose(arm):
    """Some solvers fail on axis-aligned poses (cambel/ur_ikfast#4)."""
    pose = np.eye(4)
    pose[:3, :3] = np.column_stack([[-1.0, 0, 0], [0, 1.0, 0], [0, 0, -1.0]])
    pose[:3, 3] = [-0.2, -0.2, 0.2]
    found = ik_analytic(arm, pose)
    assert len(found) == 8 if arm.name in ("UR3", "UR3e", "UR5", "UR5e") else len(found) >= 4
    for solution in found:
        np.testing.assert_allclose(official_fk(arm, solution), pose, atol=1e-8)


def test_closest_over_the_full_two_turn_range(arm):
    """A configuration moved by a whole turn on one joint is found again, not its wrap."""
    rng = np.random.default_rng(3)
    for _ in range(100):
        q = rng.uniform(-np.pi, np.pi, 6)
        extended = q.copy()
        joint = rng.integers(6)
        extended[joint] += 2 * np.pi if extended[joint] < 0 else -2 * np.pi
        result = ik_closest(arm, urkin.fk(arm, q), extended)
        assert result.success
        np.testing.assert_allclose(result.q, extended, atol=1e-2)


def test_with_a_tool_offset(arm):
    """IK of a tool 0.2 m along the flange's z axis gives back the zero configuration.

    ur-analytic-ik asserts the zero configuration itself.  It is wrist-singular (q5 = 0): a
    one-parameter family (q2 + q3 + q4 + q6 fixed) reaches the pose, and urkin returns the
    family's documented representatives (elbow nearest a right angle), so what is asserted is
    that the zero configuration's family is among them, and that every member reaches the pose.
    """
    tool = np.eye(4)
    tool[2, 3] = 0.2
    with_tool = arm.with_tool(tool)
    found = ik_analytic(with_tool, urkin.fk(with_tool, np.zeros(6)))
    wrapped = urkin.transforms.wrap_angles
    family = (
        np.isclose(found[:, 0], 0.0, atol=1e-9)
        & np.isclose(found[:, 4], 0.0, atol=1e-9)
        & np.isclose(wrapped(found[:, 1] + found[:, 2] + found[:, 3] + found[:, 5]), 0, atol=1e-9)
    )
    assert family.any()
    rng = np.random.default_rng(4)
    for q in rng.uniform(-np.pi, np.pi, (50, 6)):
        pose = urkin.fk(with_tool, q)
        for solution in ik_analytic(with_tool, pose):
            np.testing.assert_allclose(official_fk(arm, solution) @ tool, pose, atol=1e-8)


def read_real_ur5e_pairs():
    text = (Path(__file__).parent / "data" / "peers" / "ur5e_real_poses.txt").read_text()
    pairs = []
    for line in text.splitlines():
        if ";" not in line:
            continue
        joints, pose = line.split(";")
        number = r"-?\d+\.?\d*(?:e-?\d+)?"
        q = np.array([float(x) for x in re.findall(number, joints)])
        T = np.array([float(x) for x in re.findall(number, pose)]).reshape(4, 4)
        pairs.append((q, T))
    return pairs


@pytest.mark.parametrize(("q", "T"), read_real_ur5e_pairs())
def test_solutions_match_the_real_ur5e(q, T):
    """A real UR5e's reported flange poses: the nearest closed-form solution is the joint
    reading within 1e-2 rad, and the nominal model places the flange within 3 mm of the
    calibrated arm (ur-analytic-ik's tolerances)."""
    ur5e = urkin.robot("ur5e")
    result = ik_closest(ur5e, T, q)
    assert result.success
    np.testing.assert_allclose(result.q, q, atol=1e-2)
    assert np.linalg.norm(urkin.fk(ur5e, q)[:3, 3] - T[:3, 3]) < 3e-3
    # the numerical solver started at the joint reading lands on the same branch
    numerical = urkin.ik(ur5e, T, q0=q)
    assert numerical.success
    np.testing.assert_allclose(numerical.q, result.q, atol=1e-6)


# ------------------------------------------------- Modern Robotics' documented examples

MR_T = np.array([[1.0, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 3], [0, 0, 0, 1]])
MR_M = np.array([[-1.0, 0, 0, 0], [0, 1, 0, 6], [0, 0, -1, 2], [0, 0, 0, 1]])
MR_FK = np.array([[0.0, 1, 0, -5], [1, 0, 0, 4], [0, 0, -1, 1.68584073], [0, 0, 0, 1]])


def test_mr_matrix_exp3_and_log3():
    expected = [
        [-0.69492056, 0.71352099, 0.08929286],
        [-0.19200697, -0.30378504, 0.93319235],
        [0.69297817, 0.6313497, 0.34810748],
    ]
    np.testing.assert_allclose(so3_exp([1.0, 2.0, 3.0]), expected, atol=1e-8)
    R = np.array([[0.0, 0, 1], [1, 0, 0], [0, 1, 0]])
    np.testing.assert_allclose(so3_log(R), [1.20919958] * 3, atol=1e-8)


def test_mr_trans_inv_and_adjoint():
    np.testing.assert_allclose(
        inv_transform(MR_T), [[1, 0, 0, 0], [0, 0, 1, -3], [0, -1, 0, 0], [0, 0, 0, 1]]
    )
    expected = [
        [1, 0, 0, 0, 0, 0],
        [0, 0, -1, 0, 0, 0],
        [0, 1, 0, 0, 0, 0],
        [0, 0, 3, 1, 0, 0],
        [3, 0, 0, 0, 0, -1],
        [0, 0, 0, 0, 1, 0],
    ]
    np.testing.assert_allclose(adjoint(MR_T), expected)


def test_mr_matrix_exp6_and_log6():
    V = np.array([1.57079632, 0, 0, 0, 2.35619449, 2.35619449])
    np.testing.assert_allclose(se3_exp(V), MR_T, atol=1e-7)  # inputs printed to 8 digits
    np.testing.assert_allclose(se3_log(MR_T), [1.57079633, 0, 0, 0, 2.35619449, 2.35619449])


def test_mr_screw_axis_of_a_revolute_joint():
    # ScrewToAxis(q=(3, 0, 0), s=(0, 0, 1), h=0): urkin's joints are revolute (pitch 0)
    np.testing.assert_allclose(poe.screw_axis([0, 0, 1], [3, 0, 0]), [0, 0, 1, 0, -3, 0])


def test_mr_fk_in_space_and_body_forms():
    S = np.array([[0, 0, 1, 4, 0, 0], [0, 0, 0, 0, 1, 0], [0, 0, -1, -6, 0, -0.1]]).T
    B = np.array([[0, 0, -1, 2, 0, 0], [0, 0, 0, 0, 1, 0], [0, 0, 1, 0, 0, 0.1]]).T
    q = [np.pi / 2, 3, np.pi]
    np.testing.assert_allclose(poe.fk_space(MR_M, S, q), MR_FK, atol=1e-8)
    np.testing.assert_allclose(poe.fk_body(MR_M, B, q), MR_FK, atol=1e-8)


def test_mr_jacobians_in_space_and_body_forms():
    screws = np.array(
        [[0, 0, 1, 0, 0.2, 0.2], [1, 0, 0, 2, 0, 3], [0, 1, 0, 0, 2, 1], [1, 0, 0, 0.2, 0.3, 0.4]]
    ).T
    q = [0.2, 1.1, 0.1, 1.2]
    body = [
        [-0.04528405, 0.99500417, 0, 1],
        [0.74359313, 0.09304865, 0.36235775, 0],
        [-0.66709716, 0.03617541, -0.93203909, 0],
        [2.32586047, 1.66809, 0.56410831, 0.2],
        [-1.44321167, 2.94561275, 1.43306521, 0.3],
        [-2.06639565, 1.82881722, -1.58868628, 0.4],
    ]
    space = [
        [0, 0.98006658, -0.09011564, 0.95749426],
        [0, 0.19866933, 0.4445544, 0.28487557],
        [1, 0, 0.89120736, -0.04528405],
        [0, 1.95218638, -2.21635216, -0.51161537],
        [0.2, 0.43654132, -2.43712573, 2.77535713],
        [0.2, 2.96026613, 3.23573065, 2.22512443],
    ]
    np.testing.assert_allclose(poe.jacobian_body(screws, q), body, atol=1e-7)
    np.testing.assert_allclose(poe.jacobian_space(screws, q), space, atol=1e-7)
