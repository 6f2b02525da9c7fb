import math

import numpy as np
import pytest

import urkin
from tests.reference import OFFICIAL_DH
from urkin.robots import ALPHA_UR, T_BASE_LINK_BASE, Robot


def test_the_seven_arms_in_ur_order():
    assert urkin.ROBOTS == ("UR3", "UR5", "UR10", "UR3e", "UR5e", "UR10e", "UR16e")


@pytest.mark.parametrize("name", sorted(OFFICIAL_DH))
def test_dh_lengths_are_urs_published_values(name):
    assert urkin.robot(name).lengths == OFFICIAL_DH[name]


def test_ur5_d1_is_the_official_value_not_the_toolbox_typo():
    ur5 = urkin.robot("UR5")
    assert ur5.d1 == 0.089159
    assert "0.089459" in ur5.notes


def test_lookup_ignores_case_and_spaces():
    assert urkin.robot(" ur10E ") is urkin.robot("UR10e")


def test_unknown_name_lists_the_known_ones():
    with pytest.raises(KeyError, match="UR3, UR5, UR10, UR3e, UR5e, UR10e, UR16e"):
        urkin.robot("UR20")


def test_joint_limits_are_plus_minus_two_pi(arm):
    assert arm.joint_limits == ((-2 * math.pi, 2 * math.pi),) * 6


def test_dh_table_has_the_ur_structure(arm):
    table = arm.dh_table()
    np.testing.assert_array_equal(table[:, 2], ALPHA_UR)
    np.testing.assert_array_equal(table[[1, 2], 0], 0.0)
    np.testing.assert_array_equal(table[[0, 3, 4, 5], 1], 0.0)


def test_base_and_tool_default_to_identity_and_are_read_only(arm):
    assert arm.has_identity_frames
    np.testing.assert_array_equal(arm.base, np.eye(4))
    with pytest.raises(ValueError):
        arm.tool[0, 3] = 1.0


def test_with_tool_and_base_return_new_arms():
    ur5 = urkin.robot("ur5")
    T = np.eye(4)
    T[2, 3] = 0.1
    tooled = ur5.with_tool(T)
    assert not tooled.has_identity_frames and ur5.has_identity_frames
    assert tooled.tool[2, 3] == 0.1


def test_bad_base_transform_is_rejected():
    with pytest.raises(ValueError, match="not a rotation"):
        urkin.robot("ur5").with_base(np.diag([2.0, 1.0, 1.0, 1.0]))


def test_millimetres_are_rejected():
    with pytest.raises(ValueError, match="millimetres"):
        Robot("UR5-mm", 89.2, -425.0, -392.0, 109.3, 94.75, 82.5)


def test_urdf_base_link_is_rz_pi_of_base():
    expected = np.array([[-1, 0, 0, 0], [0, -1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]], float)
    np.testing.assert_array_equal(T_BASE_LINK_BASE, expected)


@pytest.mark.parametrize("name", ["ur3", "ur5e", "ur10"])
@pytest.mark.parametrize("shape", [(), 7, (3, 4)])
def test_random_configurations_are_generator_uniform_draws(name, shape):
    """Drawn as lower + span·random(): the very numbers of ``Generator.uniform(lower, upper)``
    (which costs 6 µs more for one configuration), seed by seed."""
    from urkin.robots import random_configurations

    arm = urkin.robot(name)
    lower = np.maximum([lo for lo, _ in arm.joint_limits], -math.pi)
    upper = np.minimum([hi for _, hi in arm.joint_limits], math.pi)
    size = (shape,) if isinstance(shape, int) else shape
    expected = np.random.default_rng(3).uniform(lower, upper, (*size, 6))
    drawn = random_configurations(arm, shape, seed=3)
    assert np.array_equal(drawn, expected)


@pytest.mark.parametrize("which", ["with_base", "with_tool"])
def test_a_base_or_tool_typed_with_a_few_decimals_is_made_rigid(which):
    # 7 decimals: 1e-7 from orthonormal, which the checks accept; kept as given, every pose
    # fk gives would be as skewed and IK could reach none of them
    R = np.round(urkin.transforms.rot_z(0.3) @ urkin.transforms.rot_x(0.2), 7)
    M = urkin.transforms.make_transform(R, [0.5, 0.0, 0.1])
    arm = getattr(urkin.robot("ur5"), which)(M)
    kept = arm.base if which == "with_base" else arm.tool
    assert np.abs(kept[:3, :3] - R).max() < 1e-6
    assert np.abs(kept[:3, :3].T @ kept[:3, :3] - np.eye(3)).max() < 1e-14
    T = urkin.fk(arm, [0.1, -1.2, 1.1, -0.5, 0.7, 0.3])
    assert np.abs(T[:3, :3].T @ T[:3, :3] - np.eye(3)).max() < 1e-14
    assert urkin.ik(arm, T).success


def test_an_exact_base_is_kept_to_the_bit():
    M = urkin.transforms.make_transform(urkin.transforms.rot_z(0.3), [0.5, 0.0, 0.1])
    assert np.array_equal(urkin.robot("ur5").with_base(M).base, M)
    assert urkin.robot("ur5").with_tool(np.eye(4)).has_identity_frames
