"""Inputs at the edges of what the library takes: joint limits beyond ±π, poses absurdly far,
current configurations several turns out, paths that stay put, complex steps through a tool,
undamped and overdamped steps, sample counts and limits many orders of magnitude off, chains
without joints, custom arms with d5 = 0.  Each either gets the right answer, checked against
an independent one (forward kinematics, a complex-step derivative), or a clear error naming
its argument."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import urkin
from urkin import poe
from urkin import trajectory as tj
from urkin import transforms as tf
from urkin.robots import random_configurations
from urkin.tracking import track

UR5 = urkin.robot("ur5")
Q = np.array([0.3, -1.2, 1.4, -0.6, 1.1, 4.0])


def _arm(limits_6: tuple[float, float]) -> urkin.Robot:
    return urkin.Robot("UR5", *UR5.lengths, joint_limits=((-np.pi, np.pi),) * 5 + (limits_6,))


@pytest.mark.parametrize("limits", [(2.0, 6.0), (3.5, 6.0), (-6.0, -3.5)])
def test_numerical_ik_reaches_angles_beyond_pi_that_the_limits_allow(limits):
    arm = _arm(limits)
    q = Q.copy()
    q[5] = 4.0 if limits[1] > 0 else -4.0
    T = urkin.fk(arm, q)
    for q0 in (q + 0.05, None):
        result = urkin.ik(arm, T, q0=q0)
        assert result.success, result.reason
        assert limits[0] <= result.q[5] <= limits[1]
        assert np.abs(urkin.fk(arm, result.q) - T).max() < 1e-9
    stack = urkin.ik(arm, np.stack([T] * 20))
    assert stack.success.all()
    assert np.all((stack.q[:, 5] >= limits[0]) & (stack.q[:, 5] <= limits[1]))


def test_random_configurations_of_limits_outside_pi_lie_within_them():
    q = random_configurations(_arm((3.5, 6.0)), 1000, seed=3)
    assert np.all((q[:, 5] >= 3.5) & (q[:, 5] <= 6.0))
    assert np.all(np.abs(q[:, :5]) <= np.pi)


@pytest.mark.parametrize(
    ("shape", "seed", "error"),
    [
        (-1, 0, ValueError),
        ((2, -1), 0, ValueError),
        (2, -1, ValueError),
        ("2", 0, TypeError),
        (2.5, 0, TypeError),
        (True, 0, TypeError),  # True is not 1
        ((2, True), 0, TypeError),
        (2, True, TypeError),
        (2, "x", TypeError),
    ],
)
def test_random_configurations_refuse_bad_shapes_and_seeds(shape, seed, error):
    """Negative sizes and seeds are ValueErrors, wrong types (bools too) TypeErrors; each
    names the argument.  random_rotations and random_transforms check alike."""
    from urkin.transforms import random_rotations, random_transforms

    for draw in (
        lambda: random_configurations(UR5, shape, seed),
        lambda: random_rotations(shape, seed),
        lambda: random_transforms(shape, seed=seed),
    ):
        with pytest.raises(error, match=r"shape|seed"):
            draw()


def test_random_configurations_take_numpy_integers():
    assert random_configurations(UR5, np.int64(2), seed=np.int64(1)).shape == (2, 6)


@pytest.mark.parametrize("distance", [1e155, 1e200, 1e300])
def test_closed_form_ik_of_a_pose_absurdly_far_has_no_solution_and_says_how_far(distance):
    T = tf.make_transform(p=[distance, 0.0, 0.0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no overflow warning either
        assert urkin.ik_analytic(UR5, T).shape == (0, 6)
        assert np.isnan(urkin.ik_analytic(UR5, np.stack([T, T]))).all()
        result = urkin.ik_closest(UR5, T, np.zeros(6))
    assert not result.success
    assert f"{distance:.3g} m from the shoulder" in result.reason


def test_ik_closest_follows_a_current_configuration_several_turns_out():
    q = np.array([0.3, -1.2, 1.4, -0.6, 1.1, 0.2])
    turn = np.array([1.0, 0, 0, 0, 0, 0])
    current = q + (4 * np.pi - 0.4) * turn  # 12.9 rad: back inside ±2π after a turn
    T = urkin.fk(UR5, q)
    result = urkin.ik_closest(UR5, T, current)
    assert result.success  # a solution within ±2π (the current angle is outside them)
    assert np.all(np.abs(result.q) <= 2 * np.pi)
    assert np.abs(urkin.fk(UR5, result.q) - T).max() < 1e-9
    near = urkin.ik_closest(UR5, T, q - 2 * np.pi * turn)  # inside the limits, a turn out
    np.testing.assert_allclose(near.q, q - 2 * np.pi * turn, atol=1e-9)
    with pytest.raises(ValueError, match="q_current has an angle of 1e"):
        urkin.ik_closest(UR5, urkin.fk(UR5, q), np.full(6, 1e300))


def test_a_path_that_stays_put_still_turns_from_R_start_to_R_end():
    poses = tj.pose_path(np.zeros((5, 3)), np.eye(3), tf.rot_z(1.0))
    np.testing.assert_allclose(poses[-1, :3, :3], tf.rot_z(1.0), atol=1e-15)
    np.testing.assert_allclose(poses[2, :3, :3], tf.rot_z(0.5), atol=1e-15)
    with pytest.raises(ValueError, match="single sample"):
        tj.pose_path(np.zeros((1, 3)), np.eye(3), tf.rot_z(1.0))


def test_complex_step_jacobian_through_a_tool_and_a_base_matches_fk():
    arm = UR5.with_tool(tf.make_transform(tf.rot_x(0.3), [0.01, 0.02, 0.15])).with_base(
        tf.make_transform(tf.rot_z(0.7), [0.1, 0.0, 0.2])
    )
    q = np.array([0.4, -1.1, 0.9, -0.3, 0.8, 0.5])
    h = 1e-30
    columns = []
    for k in range(6):
        step = q.astype(complex)
        step[k] += 1j * h
        columns.append(urkin.fk(arm, step)[:3, 3].imag / h)
    np.testing.assert_allclose(urkin.jacobian(arm, q)[:3], np.array(columns).T, atol=1e-14)
    J = urkin.jacobian(arm, q + 1e-30j)
    assert J.dtype == complex
    np.testing.assert_allclose(J.real, urkin.jacobian(arm, q), atol=1e-15)
    assert urkin.position_jacobian(arm, q + 1e-30j).dtype == complex


def test_undamped_dls_takes_least_squares_steps_and_huge_damping_is_refused():
    T = urkin.fk(UR5, [0.3, -1.2, 1.4, -0.6, 1.1, 0.2])
    assert urkin.ik(UR5, T, method="dls", damping=0).success  # from q = 0, a singular pose
    assert urkin.ik(UR5, np.stack([T] * 30), method="dls", damping=0).success.all()
    with pytest.raises(ValueError, match="damping must be at most"):
        urkin.ik(UR5, T, method="dls", damping=1e200)


@pytest.mark.parametrize(
    ("distance", "velocity", "acceleration"),
    [([1e200], 1e-200, 1.0), ([1e-200], 1e200, 1e200), ([1.0], 1e-320, 1e-320)],
)
def test_minimum_time_refuses_limits_many_orders_off_their_distances(
    distance, velocity, acceleration
):
    with pytest.raises(ValueError, match="max_velocity and max_acceleration"):
        tj.minimum_time("cubic", distance, velocity, acceleration)


def test_sample_counts_are_capped_with_a_message():
    scaling = tj.time_scaling("cubic", 1.0)
    with pytest.raises(ValueError, match="samples must be an integer from 2 to"):
        tj.joint_trajectory([0.0], [1.0], scaling, samples=10**13)
    with pytest.raises(ValueError, match="dt = 1e-12 s"):
        tj.via_trajectory([[0.0], [1.0]], [0.0, 1.0], dt=1e-12)
    with pytest.raises(ValueError, match="dt = 1e-300 s"):
        tj.via_trajectory([[0.0], [1.0]], [0.0, 1e300], dt=1e-300)
    with pytest.raises(ValueError, match=r"q_via up to 1e\+308"):
        tj.via_trajectory([[0.0], [1e308], [-1e308]], [0.0, 1.0, 2.0])


def test_chains_without_screw_axes_and_overflowing_screws_are_refused_by_name():
    for call in (
        lambda: poe.fk_space(np.eye(4), np.zeros((6, 0)), np.zeros(0)),
        lambda: poe.fk_body(np.eye(4), np.zeros((6, 0)), np.zeros(0)),
        lambda: poe.jacobian_space(np.zeros((6, 0)), np.zeros(0)),
        lambda: poe.jacobian_body(np.zeros((6, 0)), np.zeros(0)),
    ):
        with pytest.raises(ValueError, match="at least one screw axis"):
            call()
    with pytest.raises(ValueError, match="S times q is too large"):
        poe.fk_space(np.eye(4), np.full((6, 1), 1e200), [1.0])


@pytest.mark.parametrize("tol", [0, -1.0, np.nan, [1e-9, 1e-9]])
def test_track_refuses_a_tolerance_that_is_not_one_positive_number(tol):
    T = urkin.fk(UR5, np.tile([0.3, -1.2, 1.4, -0.6, 1.1, 0.2], (2, 1)))
    with pytest.raises((TypeError, ValueError), match="tol must be"):
        track(UR5, T, np.zeros(6), tol=tol)


@pytest.mark.parametrize(
    "limits",
    [None, "abc", ((0, 1),) * 5, ((0, 1),) * 5 + ((0,),), ((np.nan, 1.0),) * 6, ((1, 0),) * 6],
)
def test_robot_joint_limits_must_be_six_ordered_pairs(limits):
    with pytest.raises(ValueError, match="joint_limits must be six"):
        urkin.Robot("arm", *UR5.lengths, joint_limits=limits)


@pytest.mark.parametrize("q5", [0.0, 1e-9, 0.3])
def test_closed_form_ik_of_an_arm_with_d5_zero_is_exact(q5):
    lengths = list(UR5.lengths)
    lengths[4] = 0.0
    arm = urkin.Robot("d5 = 0", *lengths)
    T = urkin.fk(arm, [0.3, -1.2, 1.4, -0.6, q5, 0.2])
    solutions = urkin.ik_analytic(arm, T)
    assert len(solutions)
    assert np.abs(urkin.fk(arm, solutions) - T).max() < 1e-12


def test_small_misuses_get_messages():
    with pytest.raises(ValueError, match="kind must be"):
        tj.time_scaling(["cubic"], 1.0)
    with pytest.raises(ValueError, match="plane must be one of"):
        tj.square([0, 0, 0], 0.1, plane=["xy"])
    with pytest.raises(ValueError, match="start must be one angle"):
        tj.circle([0, 0, 0], 0.1, plane="yz", start=[1, 2])
    with pytest.raises(ValueError, match="out must be a float array"):
        tf.wrap_angles(np.zeros(3), out=np.zeros(2))
    with pytest.raises(ValueError, match="out must be a float array"):
        tf.wrap_angles(np.zeros(3), out=np.zeros(3, dtype=int))
    batch = urkin.ik(UR5, urkin.fk(UR5, np.zeros((20, 6))))
    with pytest.raises(TypeError, match="indexed by one integer"):
        batch[0:2]
    assert batch[np.int64(3)].success
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert repr(urkin.ik(UR5, np.zeros((0, 4, 4)))) == "IKResult(batch of 0)"
