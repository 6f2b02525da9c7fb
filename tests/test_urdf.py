"""urkin.fk against the ROS-Industrial URDF models (tests/data/urdf; parsed in robot_models)."""

import numpy as np
import pytest

import urkin

from .robot_models import chain, origin, urdf_fk, urdf_path


@pytest.mark.parametrize("name", ["UR3", "UR5", "UR10"])
def test_base_link_to_tool0_is_rz_pi_times_fk(name, rng):
    path = urdf_path(name)
    assert len([j for j in chain(path, "base_link", "tool0") if j.get("type") == "revolute"]) == 6
    arm = urkin.robot(name)
    Q = rng.uniform(-np.pi, np.pi, size=(100, 6))
    expected = np.array([urdf_fk(path, q) for q in Q])
    np.testing.assert_allclose(urkin.T_BASE_LINK_BASE @ urkin.fk(arm, Q), expected, atol=1e-12)


def test_urdf_names_base_link_to_base_as_rz_pi():
    path = urdf_path("ur5")
    (joint,) = chain(path, "base_link", "base")
    np.testing.assert_allclose(origin(joint), urkin.T_BASE_LINK_BASE, atol=1e-15)
