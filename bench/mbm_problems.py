"""The MotionBenchMaker UR5 problems (VAMP's copy), read into urkin scenes and configurations.

``bench/data/motionbenchmaker_ur5/`` holds the problems as published (see its README): seven
families of 100 MoveIt planning scenes and requests for a UR5 carrying a force-torque sensor
and a Robotiq 2F-85 gripper, mounted 0.9144 m up a pedestal.  This module turns them into
``urkin.planning`` objects:

* the robot: ``urkin.robot("ur5")`` mounted where the URDF's ``offset_joint`` puts
  ``base_link`` (DH frame 0 is ``base_link`` turned by π about z,
  :data:`urkin.robots.T_BASE_LINK_BASE`), joint limits from the URDF (±π on every joint);
  joint angles are the URDF's (UR's URDF joints read the controller's angles);
* its spheres: urkin's, fitted to the arm's collision meshes (:func:`planning.sphere_model`;
  the forearm and wrist 2 are tested on their tabulated meshes), plus VAMP's spheres of the
  sensor and the gripper (fingers open, as in every request), carried into the flange frame
  (``tool0``) through the URDF's fixed joints;
* scenes: every collision object's primitives (boxes and cylinders, with MoveIt's
  ``[height, radius]`` for cylinders about their pose's z axis), named by their ``id``;
* a problem: the start's and the first goal constraint's six arm joints.

A problem is *valid for urkin* when its start and goal are free under urkin's model: 696 of
the 700 (with every pair of links tested on their spheres, none on tabulated meshes, 652).
VAMP ships 689 as valid: those free under its own spheres (:func:`vamp_model`, the spherized
URDF's spheres with every pair on links neither the same nor adjacent, gives exactly that
count); urkin's model accepts all of them (before its fit cut spheres by their reach, it
refused cage/100: a forearm sphere 1 mm into a box that the mesh clears by 8 mm).
``problems()`` returns every problem with ``reason`` saying why an invalid
one is left out, and ``vamp_free``.
"""

from __future__ import annotations

import math
import re
import tarfile
import xml.etree.ElementTree as ET
from dataclasses import dataclass, replace
from functools import lru_cache
from pathlib import Path

import numpy as np
import yaml

import urkin
from urkin import planning
from urkin.robots import T_BASE_LINK_BASE
from urkin.transforms import rpy_to_rotation

DATA = Path(__file__).resolve().parent / "data" / "motionbenchmaker_ur5"
FAMILIES = (
    "bookshelf_small",
    "bookshelf_tall",
    "bookshelf_thin",
    "box",
    "cage",
    "table_pick",
    "table_under_pick",
)
JOINTS = (
    "shoulder_pan_joint",
    "shoulder_lift_joint",
    "elbow_joint",
    "wrist_1_joint",
    "wrist_2_joint",
    "wrist_3_joint",
)
#: Links whose spheres ride on the flange: the force-torque sensor and the gripper.
TOOL_ROOT = "wrist_3_link"


@dataclass(frozen=True)
class Problem:
    """One MotionBenchMaker query: a scene, a start and a goal configuration."""

    family: str
    draw: int  # the problem's number within its family (its file names' number)
    scene: planning.Scene
    start: np.ndarray
    goal: np.ndarray
    reason: str  # empty when start and goal are free under urkin's model
    vamp_free: bool  # start and goal are free under VAMP's own spheres (vamp_model)

    @property
    def name(self) -> str:
        return f"{self.family}/{self.draw}"


def _origin(element: ET.Element | None) -> np.ndarray:
    T = np.eye(4)
    if element is not None:
        T[:3, :3] = rpy_to_rotation([float(v) for v in element.get("rpy", "0 0 0").split()])
        T[:3, 3] = [float(v) for v in element.get("xyz", "0 0 0").split()]
    return T


@lru_cache(maxsize=1)
def _urdf() -> ET.Element:
    return ET.parse(DATA / "ur5_spherized.urdf").getroot()


def _fixed_below(root: str) -> dict[str, np.ndarray]:
    """Pose in ``root`` of every link hanging from it by fixed joints."""
    joints = [j for j in _urdf().findall("joint") if j.get("type") == "fixed"]
    poses = {root: np.eye(4)}
    grown = True
    while grown:
        grown = False
        for j in joints:
            parent, child = j.find("parent").get("link"), j.find("child").get("link")
            if parent in poses and child not in poses:
                poses[child] = poses[parent] @ _origin(j.find("origin"))
                grown = True
    return poses


def robot() -> urkin.Robot:
    """The UR5 as the problems mount it, with the URDF's joint limits."""
    mount = next(j for j in _urdf().findall("joint") if j.get("name") == "offset_joint")
    limits = []
    for name in JOINTS:
        joint = next(j for j in _urdf().findall("joint") if j.get("name") == name)
        limit = joint.find("limit")
        limits.append((float(limit.get("lower")), float(limit.get("upper"))))
    arm = urkin.robot("ur5").with_base(_origin(mount.find("origin")) @ T_BASE_LINK_BASE)
    return replace(arm, joint_limits=tuple(limits))


def tool_spheres() -> tuple[np.ndarray, np.ndarray, list[str]]:
    """VAMP's sensor and gripper spheres in the flange frame: centres (K, 3), radii (K,), and
    the link each comes from."""
    below = _fixed_below(TOOL_ROOT)
    T_flange = np.linalg.inv(below["tool0"])
    centres, radii, links = [], [], []
    for link in _urdf().findall("link"):
        name = link.get("name")
        if name not in below or name == TOOL_ROOT:
            continue
        for c, r in _spheres_of(link):
            centres.append((T_flange @ below[name] @ c)[:3])
            radii.append(r)
            links.append(name)
    return np.array(centres), np.array(radii), links


def _spheres_of(link: ET.Element) -> list[tuple[np.ndarray, float]]:
    out = []
    for collision in link.findall("collision"):
        sphere = collision.find("geometry/sphere")
        if sphere is not None:
            out.append((_origin(collision.find("origin"))[:, 3], float(sphere.get("radius"))))
    return out


@lru_cache(maxsize=1)
def vamp_model() -> planning.SphereModel:
    """VAMP's own spheres (the spherized URDF's, arm and gripper) as a urkin model, every pair
    of spheres on links neither the same nor adjacent tested: under it exactly 689 of the 700
    problems have a free start and goal, the number VAMP ships as valid."""
    links = {link.get("name"): link for link in _urdf().findall("link")}
    joints = {j.find("child").get("link"): j for j in _urdf().findall("joint")}
    by_name = {j.get("name"): j.find("child").get("link") for j in _urdf().findall("joint")}
    arm_links = ["base_link"] + [by_name[name] for name in JOINTS]  # DH frames 0 … 6

    def at_zero(name: str) -> np.ndarray:  # the link's pose in base_link, every joint at 0
        T = np.eye(4)
        while name != "base_link":
            joint = joints[name]
            T = _origin(joint.find("origin")) @ T
            name = joint.find("parent").get("link")
        return T

    frames = T_BASE_LINK_BASE @ urkin.fk_frames(urkin.robot("ur5"), np.zeros(6))
    rows = []
    for k, name in enumerate(arm_links):
        T = np.linalg.inv(frames[k]) @ at_zero(name)
        rows += [(k, *(T @ c)[:3], r) for c, r in _spheres_of(links[name])]
    centres, radii, _ = tool_spheres()
    rows += [(7, *c, r) for c, r in zip(centres, radii)]
    model = planning.SphereModel.from_rows(robot(), rows, pairs=np.zeros((0, 2), dtype=int))
    link = np.minimum(model.frames, 6)
    i, j = np.triu_indices(len(model), 1)
    apart = np.abs(link[i] - link[j]) >= 2
    return model.with_pairs(np.column_stack([i[apart], j[apart]]))


@lru_cache(maxsize=1)
def model() -> planning.SphereModel:
    """urkin's arm spheres with VAMP's sensor and gripper spheres on the flange."""
    centres, radii, _ = tool_spheres()
    return planning.sphere_model(robot()).with_tool_spheres(centres, radii, name="gripper")


def _pose(entry: dict) -> np.ndarray:
    T = np.eye(4)
    x, y, z, w = (float(v) for v in entry["orientation"])
    n = math.sqrt(x * x + y * y + z * z + w * w)
    x, y, z, w = x / n, y / n, z / n, w / n
    T[:3, :3] = [
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ]
    T[:3, 3] = [float(v) for v in entry["position"]]
    return T


def scene(data: dict) -> planning.Scene:
    """A MoveIt planning scene's collision objects as a :class:`planning.Scene`."""
    boxes, cylinders, spheres = [], [], []
    for obj in data["world"]["collision_objects"]:
        frame = _pose(obj["pose"]) if "pose" in obj else np.eye(4)
        for k, (shape, placed) in enumerate(zip(obj["primitives"], obj["primitive_poses"])):
            T = frame @ _pose(placed)
            name = obj["id"] if len(obj["primitives"]) == 1 else f"{obj['id']} {k}"
            size = [float(v) for v in shape["dimensions"]]
            if shape["type"] == "box":
                boxes.append(planning.Box(T[:3, 3], size, rotation=T[:3, :3], name=name))
            elif shape["type"] == "cylinder":
                cylinders.append(planning.Cylinder(T[:3, 3], T[:3, 2], size[1], size[0], name=name))
            elif shape["type"] == "sphere":
                spheres.append(planning.Sphere(T[:3, 3], size[0], name=name))
            else:
                raise ValueError(f"object {obj['id']}: unknown primitive {shape['type']!r}")
    return planning.Scene(boxes=boxes, cylinders=cylinders, spheres=spheres)


def request(data: dict) -> tuple[np.ndarray, np.ndarray]:
    """A motion-plan request's start and (first) goal arm configurations."""
    state = data["start_state"]["joint_state"]
    start = np.array([state["position"][state["name"].index(j)] for j in JOINTS])
    constraints = data["goal_constraints"][0]["joint_constraints"]
    goal = {c["joint_name"]: c["position"] for c in constraints}
    return start, np.array([goal[j] for j in JOINTS], dtype=float)


@lru_cache(maxsize=1)
def _files() -> dict[tuple[str, int, str], dict]:
    """(family, number, "scene" | "request") → the parsed YAML."""
    loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
    out = {}
    with tarfile.open(DATA / "problems.tar.bz2", "r:bz2") as archive:
        for member in archive.getmembers():
            if not member.isfile():
                continue
            _, folder, filename = member.name.split("/")
            kind = "scene" if filename.startswith("scene") else "request"
            number = int(re.findall(r"\d+", filename)[0])
            text = archive.extractfile(member).read()
            out[(folder.removesuffix("_ur5"), number, kind)] = yaml.load(text, Loader=loader)
    return out


def problems(families: tuple[str, ...] = FAMILIES, count: int | None = None) -> list[Problem]:
    """The problems of ``families`` in order (the first ``count`` of each, or all)."""
    files = _files()
    arm = model()
    lower, upper = np.array(arm.robot.joint_limits).T
    out = []
    for family in families:
        numbers = sorted(n for f, n, kind in files if f == family and kind == "scene")
        for number in numbers[:count]:
            world = scene(files[(family, number, "scene")])
            start, goal = request(files[(family, number, "request")])
            reason = ""
            for label, q in (("start", start), ("goal", goal)):
                if np.any(q < lower) or np.any(q > upper):
                    reason = reason or f"{label} outside the joint limits"
                elif not planning.is_free(arm, world, q):
                    reason = reason or f"{label} {planning.explain(arm, world, q)}"
            vamp_free = bool(planning.is_free(vamp_model(), world, np.stack([start, goal])).all())
            out.append(Problem(family, number, world, start, goal, reason, vamp_free))
    return out
