"""urkin.fk against the ROS-Industrial URDF models (tests/data/urdf, see its README).

The URDF is parsed with the standard library.  Its angles are xacro's ``pi/2`` and ``pi``
printed to 12 significant digits (1.57079632679, 3.14159265359); they are snapped back to the
exact multiples of π/2 they stand for, so the comparison can be made at 1e-12.
"""

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import urkin

URDF_DIR = Path(__file__).parent / "data" / "urdf"


def snap(angle: float) -> float:
    quarter = round(angle / (math.pi / 2))
    return quarter * math.pi / 2 if abs(angle - quarter * math.pi / 2) < 1e-10 else angle


def rot(axis, angle):
    x, y, z = np.asarray(axis, float) / np.linalg.norm(axis)
    c, s = math.cos(angle), math.sin(angle)
    K = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    return np.eye(3) + s * K + (1 - c) * K @ K


def origin(joint) -> np.ndarray:
    element = joint.find("origin")
    xyz = [float(v) for v in element.get("xyz", "0 0 0").split()]
    r, p, y = (snap(float(v)) for v in element.get("rpy", "0 0 0").split())
    T = np.eye(4)
    T[:3, :3] = rot([0, 0, 1], y) @ rot([0, 1, 0], p) @ rot([1, 0, 0], r)
    T[:3, 3] = xyz
    return T


def chain(path: Path, root: str, tip: str):
    """The joints from ``root`` to ``tip``, in order."""
    joints = {j.find("child").get("link"): j for j in ET.parse(path).getroot().findall("joint")}
    out, link = [], tip
    while link != root:
        joint = joints[link]
        out.append(joint)
        link = joint.find("parent").get("link")
    return out[::-1]


def urdf_fk(path: Path, q) -> np.ndarray:
    T = np.eye(4)
    angles = iter(q)
    for joint in chain(path, "base_link", "tool0"):
        T = T @ origin(joint)
        if joint.get("type") == "revolute":
            axis = [float(v) for v in joint.find("axis").get("xyz").split()]
            motion = np.eye(4)
            motion[:3, :3] = rot(axis, next(angles))
            T = T @ motion
    return T


@pytest.mark.parametrize("name", ["UR3", "UR5", "UR10"])
def test_base_link_to_tool0_is_rz_pi_times_fk(name, rng):
    path = URDF_DIR / f"{name.lower()}_robot.urdf"
    assert len([j for j in chain(path, "base_link", "tool0") if j.get("type") == "revolute"]) == 6
    arm = urkin.robot(name)
    Q = rng.uniform(-np.pi, np.pi, size=(100, 6))
    expected = np.array([urdf_fk(path, q) for q in Q])
    np.testing.assert_allclose(urkin.T_BASE_LINK_BASE @ urkin.fk(arm, Q), expected, atol=1e-12)


def test_urdf_names_base_link_to_base_as_rz_pi():
    path = URDF_DIR / "ur5_robot.urdf"
    (joint,) = chain(path, "base_link", "base")
    np.testing.assert_allclose(origin(joint), urkin.T_BASE_LINK_BASE, atol=1e-15)
