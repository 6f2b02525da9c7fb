"""The library at its edges: near every singular family at distances 1e-3 … 1e-12, gimbal lock,
complex and NaN input, non-rigid matrices, grids of poses, and bad input that must name the
argument.  Every result is checked against an independent reference (the DH product of
tests/reference.py, finite differences, a rotation rebuilt from its angles), never against
values printed by the code under test."""

import zlib

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import urkin
from tests.reference import OFFICIAL_DH, dh_fk
from urkin import poe
from urkin.analytic_ik import ik_analytic, ik_closest
from urkin.kinematics import (
    condition_number,
    dh_chain,
    dh_transform,
    flange_pose,
    manipulability,
    singularities,
)
from urkin.robots import random_configurations
from urkin.transforms import (
    adjoint,
    inv_transform,
    pose_error,
    random_rotations,
    random_transforms,
    rotation_angle,
    rotation_parts,
    rotation_to_rpy,
    rpy_to_rotation,
    se3_log,
    so3_log,
    wrap_angles,
)

DISTANCES = [10.0**-k for k in range(3, 13)]


def reference_pose_error(arm, q, T):
    R = dh_fk(OFFICIAL_DH[arm.name], q)
    frob = np.linalg.norm(R[:3, :3] - T[:3, :3])
    return max(np.linalg.norm(R[:3, 3] - T[:3, 3]), 2 * np.arcsin(min(frob / np.sqrt(8), 1)))


def configurations(arm, family, distance, rng, count=20):
    """Configurations ``distance`` (rad) from a singular family: wrist (q5 near 0 or π), elbow
    (q3 near 0 or π), shoulder (q4 moved off the configuration whose wrist point lies on the
    d4 cylinder)."""
    out = []
    while len(out) < count:
        q = rng.uniform(-np.pi, np.pi, 6)
        sign = rng.choice([-1.0, 1.0])
        if family == "wrist":
            q[4] = rng.choice([0.0, np.pi]) + sign * distance
        elif family == "elbow":
            q[2] = rng.choice([0.0, np.pi]) + sign * distance
        else:
            reach = arm.a2 * np.cos(q[1]) + arm.a3 * np.cos(q[1] + q[2])
            if abs(reach) > 0.9 * arm.d5:
                continue
            q[3] = np.arcsin(-reach / arm.d5) - q[1] - q[2] + sign * distance
        out.append(q)
    return np.array(out)


@pytest.mark.parametrize("family", ["wrist", "elbow", "shoulder"])
@pytest.mark.parametrize("name", urkin.ROBOTS)
def test_closed_form_is_exact_near_every_singular_family(name, family):
    arm = urkin.robot(name)
    rng = np.random.default_rng(zlib.crc32(f"{name}{family}".encode()))
    for distance in DISTANCES:
        Q = configurations(arm, family, distance, rng)
        T = urkin.fk(arm, Q)
        stacked = ik_analytic(arm, T)
        for q, target, rows in zip(Q, T, stacked):
            found = ik_analytic(arm, target)
            assert len(found) >= 1
            assert len(found) == np.sum(~np.isnan(rows[:, 0]))
            # every solution is exact, by the independent DH product (near two families at once,
            # e.g. the elbow folded and the wrist within 1e-4 rad, rounding amplified by 1/sin θ5
            # reaches a few 1e-12)
            assert max(reference_pose_error(arm, s, target) for s in found) < 1e-11
            # and the configuration that made the pose is among them, up to the conditioning:
            # near the wrist family |sin θ5| divides the rounding; near a double root (shoulder,
            # elbow) the rounding's square root moves the angles, amplified by the wrist
            closest = np.abs(wrap_angles(found - q)).max(axis=1).min()
            assert closest < (1e-6 + 1e-12 / distance if family == "wrist" else 1e-3)
            # the closest solution within the limits is found and exact
            result = ik_closest(arm, target, q)
            assert result.success and reference_pose_error(arm, result.q, target) < 1e-11


def test_closed_form_keeps_both_shoulder_branches_until_they_are_equal():
    ur5 = urkin.robot("ur5")
    rng = np.random.default_rng(4)
    for distance in (1e-3, 1e-5, 1e-6):
        for q in configurations(ur5, "shoulder", distance, rng):
            found = ik_analytic(ur5, urkin.fk(ur5, q))
            # the shoulder branch is bit 2 of the row: both present
            assert len(found) >= 4 and np.ptp(found[:, 0]) > 0.0


def test_closed_form_keeps_the_leading_axes_of_a_grid():
    ur3 = urkin.robot("ur3")
    Q = np.random.default_rng(1).uniform(-np.pi, np.pi, (2, 3, 6))
    T = urkin.fk(ur3, Q)
    assert T.shape == (2, 3, 4, 4)
    solutions, mask = ik_analytic(ur3, T, return_mask=True)
    assert solutions.shape == (2, 3, 8, 6) and mask.shape == (2, 3, 8)
    result = ik_closest(ur3, T, Q)
    assert result.q.shape == (2, 3, 6) and result.success.shape == (2, 3)
    np.testing.assert_allclose(result.q, Q, atol=1e-9)
    numeric = urkin.ik(ur3, T, q0=Q + 0.01)
    assert numeric.q.shape == (2, 3, 6) and numeric.success.all()


def test_rpy_round_trip_near_the_gimbal_lock_with_noise():
    rng = np.random.default_rng(5)
    for offset in (1e-6, 1e-9, 2e-9, 1e-12, 0.0):
        for sign in (1.0, -1.0):
            angles = np.array([rng.uniform(-3, 3), sign * (np.pi / 2 - offset), rng.uniform(-3, 3)])
            R = rpy_to_rotation(angles)
            R = R + rng.normal(0, 1e-10, (3, 3))  # within check_rotation's tolerance
            rebuilt = rpy_to_rotation(rotation_to_rpy(R))
            assert np.abs(rebuilt - R).max() < 1e-9


def test_complex_step_through_fk_and_jacobian():
    ur5 = urkin.robot("ur5")
    q = np.array([0.3, -1.2, 1.4, -0.6, 1.1, 0.2])
    h = 1e-30
    J = urkin.jacobian(ur5, q)
    for i in range(6):
        dq = np.zeros(6, dtype=complex)
        dq[i] = 1j * h
        dp = urkin.fk(ur5, q + dq)[:3, 3].imag / h
        np.testing.assert_allclose(dp, J[:3, i], atol=1e-14)
    assert np.iscomplexobj(urkin.jacobian(ur5, q + 1j * h))


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: urkin.ik(urkin.robot("ur5"), np.eye(4) * (1 + 1e-9j)), "target is complex"),
        (lambda: ik_analytic(urkin.robot("ur5"), np.eye(4) * (1 + 1e-3j)), "T is complex"),
        (lambda: rotation_angle(np.eye(3) * (1 + 1j)), "R1 is complex"),
        (lambda: poe.fk_space(np.eye(4), np.zeros((6, 1)), [1j]), "q is complex"),
        (lambda: manipulability(urkin.robot("ur5"), np.zeros(6) + 1e-20j), "q is complex"),
        (lambda: condition_number(urkin.robot("ur5"), np.zeros(6) + 1e-20j), "q is complex"),
        (lambda: urkin.robot("ur5").with_base(np.eye(4) * (1 + 1e-9j)), "T_world_base is comp"),
        (lambda: urkin.robot("ur5").with_tool(np.eye(4) * (1 + 1e-9j)), "T_flange_tool is comp"),
    ],
)
def test_complex_input_is_refused_unless_documented(call, message):
    with pytest.raises(TypeError, match=message):
        call()


@pytest.mark.parametrize(
    ("call", "error", "message"),
    [
        (lambda: ik_closest("ur5", np.eye(4), np.zeros(6)), TypeError, "robot must be a urkin"),
        (lambda: ik_analytic("ur5", np.eye(4)), TypeError, "robot must be a urkin"),
        (lambda: urkin.ik("ur5", np.eye(4)), TypeError, "robot must be a urkin"),
        (lambda: urkin.fk("ur5", np.zeros(6)), TypeError, "robot must be a urkin"),
        (lambda: dh_transform(np.nan, 0, 0, 0), ValueError, "theta contains NaN"),
        (lambda: dh_chain(np.zeros((6, 3)), [0, 0, np.nan, 0, 0, 0]), ValueError, "q contains"),
        (lambda: dh_chain(np.zeros((6, 2)), np.zeros(6)), ValueError, "table must be"),
        (lambda: poe.screw_axis([0, 0, np.nan], [0, 0, 0]), ValueError, "NaN"),
        (lambda: poe.screw_axis([0, 0, 2], [0, 0, 0]), ValueError, "omega must be a unit dir"),
        (lambda: poe.screw_axis([0, 0, 0], [0, 0, 0]), ValueError, "omega must be a unit dir"),
        (lambda: inv_transform(np.ones((4, 4))), ValueError, "T must end in the row"),
        (lambda: inv_transform(np.diag([2.0, 1, 1, 1])), ValueError, "not a rotation"),
        (lambda: adjoint(np.eye(3)), ValueError, r"T must have shape \(4, 4\)"),
        (lambda: rotation_angle(np.ones((3, 3))), ValueError, "R1 is not a rotation"),
        (
            lambda: poe.space_from_geometric(np.zeros((6, 6)), np.ones((4, 4))),
            ValueError,
            "T_base_tool",
        ),
        (lambda: urkin.ik(urkin.robot("ur5"), np.eye(4), tol_position=-1), ValueError, "tol_"),
        (lambda: urkin.ik(urkin.robot("ur5"), np.eye(4), max_restarts=1.5), ValueError, "max_"),
        (lambda: ik_closest(urkin.robot("ur5"), np.eye(4), np.zeros(5)), ValueError, "q_current"),
        (lambda: pose_error(np.eye(4), np.eye(3)), ValueError, "T2 must have shape"),
        (lambda: wrap_angles("a"), TypeError, "q must be numbers"),
        (lambda: wrap_angles([0.0, np.inf]), ValueError, "q contains infinity"),
        (lambda: rotation_angle(None), TypeError, "R1 must be numbers; got None"),
        (lambda: urkin.fk(urkin.robot("ur5"), [0, None, 0, 0, 0, 0]), TypeError, "q must be num"),
        (lambda: flange_pose("ur5", np.eye(4)), TypeError, "robot must be a urkin"),
        (lambda: flange_pose(urkin.robot("ur5"), np.ones((4, 4))), ValueError, "T_world_tool"),
        (lambda: flange_pose(urkin.robot("ur5"), "T"), TypeError, "T_world_tool must be num"),
        (lambda: poe.space_screws("ur5"), TypeError, "robot must be a urkin Robot or a DH"),
        (lambda: poe.body_screws([[0, 0, "x"]]), TypeError, "robot must be a urkin Robot or a"),
        (lambda: poe.fk_space(None, np.zeros((6, 1)), [0.0]), TypeError, "M must be the home"),
        (lambda: poe.fk_body(None, np.zeros((6, 1)), [0.0]), TypeError, "M must be the home"),
        (lambda: urkin.robot("ur5").with_base("T"), TypeError, "T_world_base must be numbers"),
        (lambda: urkin.robot("ur5").with_tool(np.eye(3)), ValueError, "T_flange_tool"),
        (lambda: urkin.robot("ur5").with_tool(np.stack([np.eye(4)] * 2)), ValueError, "one 4×4"),
        (lambda: urkin.robot(None), TypeError, "name must be an arm's name"),
        (lambda: urkin.robot("ur6"), ValueError, "unknown robot 'ur6'; urkin knows UR3"),
        (lambda: urkin.robot("ur6"), KeyError, "unknown robot 'ur6'; urkin knows UR3"),
    ],
)
def test_bad_input_names_the_argument(call, error, message):
    with pytest.raises(error, match=message):
        call()


def test_a_target_copied_with_nine_decimals_fails_saying_why():
    ur5 = urkin.robot("ur5")
    T = np.round(urkin.fk(ur5, [0.3, -1.2, 1.4, -0.6, 1.1, 0.2]), 9)
    result = urkin.ik(ur5, T)
    assert not result.success
    assert "from the nearest rotation matrix" in result.reason
    # with the tolerance of the copy, it is solved
    assert urkin.ik(ur5, T, tol_position=1e-8, tol_orientation=1e-8).success


@settings(max_examples=40, deadline=None)
@given(st.sampled_from(urkin.ROBOTS), st.integers(0, 2**31))
def test_properties_of_the_closed_form_on_every_arm(name, seed):
    arm = urkin.robot(name)
    q = np.random.default_rng(seed).uniform(-np.pi, np.pi, 6)
    T = urkin.fk(arm, q)
    found = ik_analytic(arm, T)
    assert 1 <= len(found) <= 8
    assert np.all((found > -np.pi) & (found <= np.pi))
    assert max(reference_pose_error(arm, s, T) for s in found) < 1e-12
    assert np.abs(wrap_angles(found - q)).max(axis=1).min() < 1e-8


def test_random_rotations_and_poses_are_seeded_and_rigid():
    a, b = random_rotations(100, seed=3), random_rotations(100, seed=3)
    np.testing.assert_array_equal(a, b)
    np.testing.assert_allclose(
        a @ np.swapaxes(a, 1, 2), np.broadcast_to(np.eye(3), a.shape), atol=1e-14
    )
    assert random_transforms(seed=2).shape == (4, 4)


def test_random_configurations_are_seeded_and_within_the_limits():
    ur5 = urkin.robot("ur5")
    a, b = random_configurations(ur5, (4, 5), seed=9), random_configurations(ur5, (4, 5), seed=9)
    np.testing.assert_array_equal(a, b)
    assert a.shape == (4, 5, 6) and np.all(np.abs(a) <= np.pi)
    narrow = urkin.Robot("narrow", *ur5.lengths, joint_limits=((-0.1, 0.2),) * 6)
    q = random_configurations(narrow, 1000, seed=1)
    assert q.min() >= -0.1 and q.max() <= 0.2 and q.max() - q.min() > 0.29
    with pytest.raises(TypeError, match="robot must be a urkin"):
        random_configurations("ur5")


CHECKED = [
    (so3_log, lambda rng: random_rotations(7, rng), "R is not a rotation"),
    (rotation_parts, lambda rng: random_rotations(7, rng), "R is not a rotation"),
    (se3_log, lambda rng: random_transforms(7, rng), "T is not a rigid|not a rotation"),
    (adjoint, lambda rng: random_transforms(7, rng), "T is not a rigid|not a rotation"),
]


@pytest.mark.parametrize(("function", "draw", "message"), CHECKED)
def test_check_false_skips_only_the_validation(function, draw, message, rng):
    """One function per concept: ``check=False`` gives the same answer on valid input (it only
    skips the validation an inner loop has already done); the default refuses bad input."""
    X = draw(rng)
    checked, unchecked = function(X), function(X, check=False)
    for a, b in zip(
        checked if isinstance(checked, tuple) else (checked,),
        unchecked if isinstance(unchecked, tuple) else (unchecked,),
    ):
        np.testing.assert_array_equal(a, b)
    bad = X.copy()
    bad[..., 0, 0] += 1e-3
    with pytest.raises(ValueError, match=message):
        function(bad)


def test_wrap_angles_in_place_without_the_check():
    q = np.array([3 * np.pi, -np.pi, 0.25])
    out = wrap_angles(q, check=False, out=q)
    assert out is q
    np.testing.assert_array_equal(q, [np.pi, np.pi, 0.25])


def test_empty_stacks_give_empty_results():
    """A stack of no poses is a stack: empty results with its leading axes, not an
    IndexError."""
    ur5 = urkin.robot("ur5")
    assert urkin.ik(ur5, np.zeros((0, 4, 4))).q.shape == (0, 6)
    assert urkin.ik(ur5, np.zeros((0, 3))).success.shape == (0,)
    assert ik_analytic(ur5, np.zeros((0, 4, 4))).shape == (0, 8, 6)
    assert ik_analytic(ur5, np.zeros((2, 0, 4, 4))).shape == (2, 0, 8, 6)
    assert ik_closest(ur5, np.zeros((0, 4, 4)), np.zeros(6)).q.shape == (0, 6)


def test_singularities_of_a_grid_keep_its_leading_axes():
    ur5 = urkin.robot("ur5")
    home = [0, -np.pi / 2, 0, -np.pi / 2, 0, 0]
    regular = [0.1, -1.0, 1.2, -0.3, 0.5, 0.7]
    found = singularities(ur5, np.array([[home, regular, home], [regular, regular, home]]))
    assert found[0][0] == ("shoulder", "elbow", "wrist") and found[1][1] == ()
    assert [len(row) for row in found] == [3, 3]


_UR5 = urkin.robot("ur5")
_POSE = urkin.fk(_UR5, [0.3, -1.2, 1.4, -0.6, 1.1, 0.2])


@pytest.mark.parametrize(
    ("call", "error", "message"),
    [
        (lambda: urkin.ik(_UR5, _POSE, damping=float("nan")), ValueError, "damping must be"),
        (lambda: urkin.ik(_UR5, _POSE, method="dls", damping="x"), TypeError, "damping must be"),
        (lambda: urkin.ik(_UR5, _POSE, seed="x"), TypeError, "seed must be an integer ≥ 0"),
        (lambda: urkin.ik(_UR5, _POSE, seed=1.5), ValueError, "seed must be an integer ≥ 0"),
        (lambda: ik_closest(_UR5, _POSE, np.zeros(6), tol=float("nan")), ValueError, "tol must"),
        (lambda: singularities(_UR5, np.zeros(6), tol="x"), TypeError, "tol must be a number"),
        (lambda: singularities(_UR5, np.zeros(6), tol=-1.0), ValueError, "tol must be a number"),
    ],
)
def test_bad_options_name_the_option(call, error, message):
    """A keyword option that is not a number, or NaN, or of the wrong sign, is refused by
    name, also where the option would not have been used (a seed before any restart, the
    damping of another method)."""
    with pytest.raises(error, match=message):
        call()
