"""The shared option checks of urkin._inputs: positive() on its fast path (plain int and
float) and on its general path must give the same verdicts."""

from __future__ import annotations

import math

import numpy as np
import pytest

from urkin._inputs import positive


@pytest.mark.parametrize(
    "value, kwargs",
    [
        (0.5, {}),
        (3, {}),
        (0, {"zero_ok": True}),
        (0.0, {"zero_ok": True}),
        (7, {"integer": True}),
        (10**400, {"integer": True}),  # too large for a float, still a valid count
        (np.float64(0.25), {}),
        (np.int64(4), {"integer": True}),
    ],
)
def test_accepted_values_come_back_unchanged(value, kwargs):
    assert positive(value, "x", **kwargs) is value


@pytest.mark.parametrize(
    "value, kwargs, error",
    [
        (True, {}, TypeError),
        (False, {"zero_ok": True}, TypeError),
        ("1", {}, TypeError),
        (None, {}, TypeError),
        (np.ones(1), {}, TypeError),
        (math.nan, {}, ValueError),
        (math.inf, {}, ValueError),
        (-math.inf, {"zero_ok": True}, ValueError),
        (0, {}, ValueError),
        (0.0, {}, ValueError),
        (-1, {"zero_ok": True}, ValueError),
        (-1e-300, {"zero_ok": True}, ValueError),
        (2.0, {"integer": True}, ValueError),
        (np.float64(math.nan), {}, ValueError),
    ],
)
def test_refused_values_name_the_option(value, kwargs, error):
    with pytest.raises(error, match=r"^tol must be"):
        positive(value, "tol", **kwargs)


# ------------------------------------------------------------------ numbers that are not numbers


def _ur5():
    import urkin

    return urkin.robot("ur5")


Q = [0.3, -1.2, 1.4, -0.6, 1.1, 0.2]


@pytest.mark.parametrize(
    "q, error, words",
    [
        (np.ma.array(Q, mask=[0, 0, 0, 0, 0, 1]), ValueError, "masked entries (entry 5)"),
        (np.array([True, *Q[1:]], dtype=object), TypeError, "got bool"),
        (np.array(["0.3", *Q[1:]], dtype=object), TypeError, "got str"),
        (np.array([b"0.3", *Q[1:]], dtype=object), TypeError, "got bytes"),
        (np.array([None, *Q[1:]], dtype=object), TypeError, "got None"),
        ([10**400, *Q[1:]], ValueError, "beyond float range"),
        (np.array([np.longdouble("1e400"), *Q[1:]]), ValueError, "beyond float range"),
    ],
)
def test_what_numpy_would_read_as_a_number_is_refused_by_name(q, error, words):
    """A masked value, a bool, a string or None in an object array, an int or long double
    beyond float range: numpy would quietly use the hidden value, 1, 0.3, NaN or inf."""
    import urkin

    with pytest.raises(error, match="q ") as raised:
        urkin.fk(_ur5(), q)
    assert words in str(raised.value)


def test_masked_arrays_without_masked_entries_are_their_values():
    import urkin

    q = np.ma.array(Q, mask=False)
    np.testing.assert_array_equal(urkin.fk(_ur5(), q), urkin.fk(_ur5(), np.array(Q)))


def test_results_are_fresh_arrays_not_the_callers():
    """A path keeps its own corners and centre; a flange pose is a new array even where it
    equals the tool pose."""
    import urkin
    from urkin import trajectory

    T = urkin.fk(_ur5(), np.array(Q))
    F = urkin.kinematics.flange_pose(_ur5(), T)
    F[0, 3] = 99.0
    assert T[0, 3] != 99.0
    corners = np.array([[0.0, 0, 0], [1, 0, 0]])
    path = trajectory.polyline(corners)
    corners[1, 0] = 5.0
    assert path.length == 1.0
    centre = np.zeros(3)
    circle = trajectory.circle(centre, 0.1, plane="xy")
    centre[0] = 7.0
    np.testing.assert_allclose(circle.points(0.01)[0], [0.1, 0.0, 0.0])


def _options():
    import urkin
    from urkin import kinematics, numerical_ik, poe, tracking, trajectory, transforms

    ur5, T = _ur5(), urkin.fk(_ur5(), np.array(Q))
    two = np.array(["lm", "nr"])
    return [
        ("method", lambda: urkin.ik(ur5, T, method=two)),
        ("orientation", lambda: urkin.ik(ur5, T, orientation=two)),
        ("form", lambda: numerical_ik.orientation_error(np.eye(3), np.eye(3), form=two)),
        ("part", lambda: kinematics.manipulability(ur5, np.array(Q), part=two)),
        ("convention", lambda: kinematics.dh_transform(0.0, 0.1, 0.2, 0.3, convention=two)),
        ("convention", lambda: poe.space_screws(ur5, convention="bogus")),
        ("convention", lambda: poe.space_screws(ur5, convention="modified")),
        ("method", lambda: tracking.track(ur5, T[None], np.array(Q), method=two)),
        ("closed", lambda: trajectory.polyline([[0, 0, 0], [1, 0, 0]], closed=float("nan"))),
        ("closed", lambda: trajectory.polyline([[0, 0, 0], [1, 0, 0]], closed=None)),
        ("check", lambda: transforms.so3_log(np.eye(3), check=np.array([True, False]))),
        ("check", lambda: transforms.pose_error(T, T, check="no")),
        ("check", lambda: transforms.wrap_angles([0.1], check=None)),
        ("return_mask", lambda: urkin.ik_analytic(ur5, T[None], return_mask="yes")),
    ]


@pytest.mark.parametrize("index", range(14))
def test_options_given_the_wrong_kind_of_value_are_named(index):
    """A string option given an array, a bogus string or a number; a yes-or-no flag given
    anything but True or False: an error naming the option (not numpy's "truth value of an
    array is ambiguous", nor a value quietly ignored)."""
    name, call = _options()[index]
    with pytest.raises((TypeError, ValueError), match=name):
        call()


def test_huge_paths_turn_by_length_or_are_named():
    """Lengths are summed without squaring overflow (1e200 m steps turn as any other), and a
    path longer than a float can hold is an error naming the points."""
    from urkin import trajectory, transforms

    points = np.array([[0, 0, 0], [1e200, 0, 0], [2e200, 0, 0.0]])
    poses = trajectory.pose_path(points, np.eye(3), transforms.rot_z(0.4))
    np.testing.assert_allclose(poses[1, :3, :3], transforms.rot_z(0.2), atol=1e-15)
    points = np.array([[0, 0, 0], [1.7e308, 0, 0], [-1.7e308, 0, 0.0]])
    with pytest.raises(ValueError, match="points"):
        trajectory.pose_path(points, np.eye(3), transforms.rot_z(0.4))
