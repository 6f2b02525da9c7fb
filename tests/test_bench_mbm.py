"""``bench/mbm_problems.py`` reads the MotionBenchMaker UR5 problems as published: the robot's
mounting and its gripper spheres are checked against VAMP's URDF chain (parsed here by
``tests/robot_models``, not by urkin), scenes against their YAML."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

import urkin
from tests import robot_models as rm
from urkin import planning

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "bench"))
mbm = pytest.importorskip("mbm_problems")
URDF = mbm.DATA / "ur5_spherized.urdf"


def _joint(name: str):
    return next(j for j in rm.ET.parse(URDF).getroot().findall("joint") if j.get("name") == name)


def test_mount_places_tool0_where_the_urdf_does(rng):
    arm = mbm.robot()
    T_world_base_link = rm.origin(_joint("offset_joint"))
    for q in rng.uniform(-np.pi, np.pi, (20, 6)):
        expected = T_world_base_link @ rm.urdf_fk(URDF, q, tip="tool0")
        np.testing.assert_allclose(urkin.fk(arm, q), expected, atol=1e-8)
    assert arm.joint_limits == ((-3.14159265, 3.14159265),) * 6


def test_gripper_spheres_ride_where_the_urdf_puts_them(rng):
    model = mbm.model()
    centres, radii, links = mbm.tool_spheres()
    assert len(centres) == 17 and set(links) >= {"fts_robotside", "robotiq_85_base_link"}
    tool = np.flatnonzero(model.frames == planning.TOOL_FRAME)
    np.testing.assert_array_equal(model.radii[tool], radii)
    urdf_links = {link.get("name"): link for link in rm.ET.parse(URDF).getroot().findall("link")}
    expected = []
    for link in dict.fromkeys(links):
        for collision in urdf_links[link].findall("collision"):
            if collision.find("geometry/sphere") is not None:
                expected.append((link, rm.origin(collision)[:, 3]))
    T_world_base_link = rm.origin(_joint("offset_joint"))
    for q in rng.uniform(-np.pi, np.pi, (5, 6)):
        placed = model.place(q)[tool]
        want = [(T_world_base_link @ rm.urdf_fk(URDF, q, tip=link) @ c)[:3] for link, c in expected]
        np.testing.assert_allclose(placed, want, atol=1e-8)


def test_scenes_and_requests_read_as_written():
    files = mbm._files()
    data = files[("bookshelf_tall", 67, "scene")]
    scene = mbm.scene(data)
    objects = data["world"]["collision_objects"]
    assert len(scene) == sum(len(o["primitives"]) for o in objects)
    can = next(c for c in scene.cylinders if c.name == "Can1")
    np.testing.assert_allclose(can.centre, [-1.075783474403198, 0.369645358582922, 1.38])
    assert (can.radius, can.length) == (0.03, 0.14)
    # its orientation (0, 0, 0.99989, 0.01465) turns about z: the axis stays z
    np.testing.assert_allclose(can.axis, [0, 0, 1], atol=1e-12)
    start, goal = mbm.request(files[("bookshelf_tall", 67, "request")])
    np.testing.assert_array_equal(start, [1.57, -1.5707, 0, -1.5707, -1.57, 3.14])
    np.testing.assert_allclose(goal[:2], [-0.9286197650820029, -2.127327282445364])


def test_every_problem_loads_with_a_reason_when_left_out():
    problems = mbm.problems()
    assert len(problems) == 700
    assert {p.family for p in problems} == set(mbm.FAMILIES)
    left_out = [p for p in problems if p.reason]
    assert all("in collision" in p.reason for p in left_out)
    assert len(left_out) < len(problems) / 2
