"""The ROS-Industrial UR models as independent references: URDF chains and collision meshes.

``tests/data/urdf`` holds the URDFs and ``tests/data/meshes`` the collision STLs, both copied
from the BSD ``example-robot-data`` wheel (see their READMEs).  Everything here is parsed with
the standard library and numpy, never with urkin, so tests can hold urkin to it.

The URDF's angles are xacro's ``pi/2`` and ``pi`` printed to 12 significant digits
(1.57079632679, 3.14159265359); they are snapped back to the exact multiples of π/2 they stand
for, so comparisons can be made at 1e-12.
"""

from __future__ import annotations

import math
import struct
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

DATA = Path(__file__).parent / "data"
URDF_DIR = DATA / "urdf"
MESH_DIR = DATA / "meshes"

#: The arm's links in the URDF, in the order of the DH frames they move with (frame 0 … 6).
LINKS = (
    "base_link",
    "shoulder_link",
    "upper_arm_link",
    "forearm_link",
    "wrist_1_link",
    "wrist_2_link",
    "wrist_3_link",
)
#: The collision mesh of each link (file name in tests/data/meshes/<arm>/).
MESHES = ("base", "shoulder", "upperarm", "forearm", "wrist1", "wrist2", "wrist3")


def snap(angle: float) -> float:
    quarter = round(angle / (math.pi / 2))
    return quarter * math.pi / 2 if abs(angle - quarter * math.pi / 2) < 1e-10 else angle


def rot(axis, angle):
    x, y, z = np.asarray(axis, float) / np.linalg.norm(axis)
    c, s = math.cos(angle), math.sin(angle)
    K = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    return np.eye(3) + s * K + (1 - c) * K @ K


def origin(element) -> np.ndarray:
    """The transform of a joint's (or a collision element's) ``<origin>``."""
    found = element.find("origin")
    T = np.eye(4)
    if found is None:
        return T
    xyz = [float(v) for v in found.get("xyz", "0 0 0").split()]
    r, p, y = (snap(float(v)) for v in found.get("rpy", "0 0 0").split())
    T[:3, :3] = rot([0, 0, 1], y) @ rot([0, 1, 0], p) @ rot([1, 0, 0], r)
    T[:3, 3] = xyz
    return T


def urdf_path(name: str) -> Path:
    return URDF_DIR / f"{name.lower()}_robot.urdf"


def chain(path: Path, root: str, tip: str):
    """The joints from ``root`` to ``tip``, in order."""
    joints = {j.find("child").get("link"): j for j in ET.parse(path).getroot().findall("joint")}
    out, link = [], tip
    while link != root:
        joint = joints[link]
        out.append(joint)
        link = joint.find("parent").get("link")
    return out[::-1]


def urdf_fk(path: Path, q, tip: str = "tool0") -> np.ndarray:
    """``T_base_link_tip`` of the URDF at joint angles ``q`` (the revolute joints in order)."""
    T = np.eye(4)
    angles = iter(q)
    for joint in chain(path, "base_link", tip):
        T = T @ origin(joint)
        if joint.get("type") == "revolute":
            axis = [float(v) for v in joint.find("axis").get("xyz").split()]
            motion = np.eye(4)
            motion[:3, :3] = rot(axis, next(angles))
            T = T @ motion
    return T


def read_stl(path: Path) -> np.ndarray:
    """The triangles of a binary or ASCII STL file, shape (M, 3, 3) (metres as stored)."""
    data = path.read_bytes()
    if len(data) >= 84:
        (count,) = struct.unpack_from("<I", data, 80)
        if len(data) == 84 + 50 * count:
            records = np.frombuffer(data, dtype=np.uint8, offset=84).reshape(count, 50)
            floats = records[:, 12:48].copy().view("<f4").reshape(count, 3, 3)
            return floats.astype(float)
    words = data.decode("ascii").split()
    vertices = [
        [float(words[i + 1]), float(words[i + 2]), float(words[i + 3])]
        for i, word in enumerate(words)
        if word == "vertex"
    ]
    return np.array(vertices, dtype=float).reshape(-1, 3, 3)


def posed_meshes(name: str, q) -> list[np.ndarray]:
    """Each link's collision triangles (M, 3, 3) in ``base_link``, the arm at joint angles
    ``q`` (6,), placed by the URDF chain and the collision element's ``<origin>``."""
    path = urdf_path(name)
    links = {link.get("name"): link for link in ET.parse(path).getroot().findall("link")}
    posed = []
    for k, (link, mesh) in enumerate(zip(LINKS, MESHES)):
        T = (urdf_fk(path, q[:k], tip=link) if k else np.eye(4)) @ origin(
            links[link].find("collision")
        )
        triangles = read_stl(MESH_DIR / name.lower() / f"{mesh}.stl")
        posed.append(triangles @ T[:3, :3].T + T[:3, 3])
    return posed


def sample_surface(triangles: np.ndarray, n: int, rng: np.random.Generator) -> np.ndarray:
    """``n`` points uniformly distributed (by area) on a triangle mesh (M, 3, 3)."""
    return sample_surface_picks(triangles, n, rng)[0]


def sample_surface_picks(
    triangles: np.ndarray, n: int, rng: np.random.Generator
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`sample_surface`'s points (n, 3) and the triangle each lies on (n,)."""
    a, b, c = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    pick = rng.choice(len(triangles), size=n, p=area / area.sum())
    u, v = rng.random((2, n))
    flip = u + v > 1
    u[flip], v[flip] = 1 - u[flip], 1 - v[flip]
    return a[pick] + u[:, None] * (b - a)[pick] + v[:, None] * (c - a)[pick], pick
