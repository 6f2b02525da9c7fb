"""The UR3 lab's top-down gripper IK (seed 004), fixed: every reachable table target round-trips,
and the answer is one branch of the general closed form."""

import numpy as np
import pytest

import urkin
from tests.test_analytic_ik import distance_mod_2pi
from urkin.analytic_ik import ik_analytic
from urkin.course.lab import LAB_LINKS, fk_lab, ik_lab, lab_robot
from urkin.transforms import wrap_angles


def lab_grid():
    xs, ys = np.meshgrid(np.linspace(-0.3, 0.5, 33), np.linspace(-0.25, 0.55, 33))
    return xs.ravel(), ys.ravel()


@pytest.mark.parametrize("z", [0.0, 0.06, 0.2])
@pytest.mark.parametrize("yaw", [-2.5, 0.0, 1.2])
def test_lab_ik_round_trips_every_reachable_table_target(z, yaw):
    xs, ys = lab_grid()
    reached = 0
    for x, y in zip(xs, ys):
        try:
            q = ik_lab(x, y, z, yaw)
        except ValueError as exc:
            assert "unreachable" in str(exc)
            continue
        reached += 1
        np.testing.assert_allclose(fk_lab(q), [x, y, z, yaw], atol=1e-9)
    assert reached > 300


def test_lab_ik_is_one_branch_of_the_analytic_solution():
    robot = lab_robot()
    xs, ys = lab_grid()
    behind = 0
    for x, y in zip(xs[::3], ys[::3]):
        try:
            q = ik_lab(x, y, 0.05, 0.7)
        except ValueError:
            continue
        T = urkin.fk(robot, q)
        solutions = ik_analytic(robot, T)
        assert distance_mod_2pi(solutions, q) < 1e-9
        assert q[4] == pytest.approx(-np.pi / 2) and q[2] > 0
        base = np.array([x, y]) - [-0.15, 0.15]
        behind += base[0] < 0  # the wrist behind the base axis: where the printed formula fails
    assert behind > 10


def test_the_printed_lab_formula_fails_behind_the_base():
    offset = LAB_LINKS[1] - LAB_LINKS[3] + LAB_LINKS[5]  # L2 − L4 + L6 = 0.110 m
    x_c, y_c = -0.20, 0.05  # a wrist point behind the base axis (x < 0 in the base frame)
    printed = np.arctan(y_c / x_c) - np.arcsin(offset / np.hypot(x_c, y_c))
    fixed = np.arctan2(y_c, x_c) - np.arcsin(offset / np.hypot(x_c, y_c))
    assert abs(wrap_angles(printed - fixed)) == pytest.approx(np.pi)


def test_lab_ik_refuses_unreachable_targets_with_the_distance():
    with pytest.raises(ValueError, match=r"stretch .* m further"):
        ik_lab(1.2, 0.0, 0.05, 0.0)
    with pytest.raises(ValueError, match="from the base axis"):
        ik_lab(-0.15, 0.15, 0.05, 0.0)
