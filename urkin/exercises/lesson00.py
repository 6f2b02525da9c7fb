"""Lesson 00 — how the course works: units and frames."""

from __future__ import annotations

import numpy as np

from urkin.exercises.framework import (
    Check,
    Exercise,
    as_array,
    compare,
    register,
    require_transform,
)
from urkin.exercises.inputs import random_pose
from urkin.robots import T_BASE_LINK_BASE
from urkin.transforms import rot_z


def _deg_to_rad_hypotheses(deg):
    return {
        "the angles came back unchanged, still in degrees": lambda: deg,
        "converted the wrong way, radians to degrees (× 180/π)": lambda: np.degrees(deg),
        "the rounded factor 0.0175 instead of π/180 (seed 002 does this)": lambda: deg * 0.0175,
        "the rounded factor 0.01744 instead of π/180 (seed 002 does this too)": lambda: (
            deg * 0.01744
        ),
        "divided by 180 without multiplying by π": lambda: deg / 180.0,
    }


def _known_angles(student, rng):
    for deg, rad in [(180.0, np.pi), (-90.0, -np.pi / 2), (0.0, 0.0), (45.0, np.pi / 4)]:
        got = as_array(student(deg), (), "deg_to_rad(angle)")
        compare(
            got,
            rad,
            what=f"{deg:g}° is {rad:.6f} rad",
            inputs={"angles_deg": deg},
            hypotheses=_deg_to_rad_hypotheses(np.asarray(deg)),
            atol=1e-12,
        )


def _random_angles(student, rng):
    for _ in range(10):
        deg = rng.uniform(-720.0, 720.0, int(rng.integers(1, 7)))
        got = as_array(student(deg.copy()), deg.shape, "deg_to_rad(angles)")
        compare(
            got,
            np.radians(deg),
            what="wrong conversion",
            inputs={"angles_deg": deg},
            hypotheses=_deg_to_rad_hypotheses(deg),
            atol=1e-12,
        )


def _whole_batch(student, rng):
    deg = rng.uniform(-360.0, 360.0, (50, 6))
    got = as_array(student(deg.copy()), deg.shape, "deg_to_rad on an (N, 6) array")
    compare(
        got,
        np.radians(deg),
        what="a batch of configurations converts element by element",
        inputs={"angles_deg": f"array of shape {deg.shape}"},
        atol=1e-12,
    )


register(
    Exercise(
        id="0.1",
        function="deg_to_rad",
        title="degrees to radians, for one angle or an array",
        checks=(
            Check("converts 180°, −90°, 0° and 45° exactly", 1, _known_angles),
            Check("converts random angles of any length", 2, _random_angles),
            Check("converts an (N, 6) array of configurations at once", 1, _whole_batch),
        ),
    )
)


def _is_transform(student, rng):
    for _ in range(5):
        T = random_pose(rng)
        got = as_array(student(T.copy()), (4, 4), "base_link_pose(T_base_tool)")
        require_transform(got, "base_link_pose(T_base_tool)", {"T_base_tool": T})


def _base_link_matches(student, rng):
    for _ in range(10):
        T = random_pose(rng)
        got = as_array(student(T.copy()), (4, 4), "base_link_pose(T_base_tool)")
        compare(
            got,
            T_BASE_LINK_BASE @ T,
            what="T_base_link_tool = T_base_link_base @ T_base_tool",
            inputs={"T_base_tool": T},
            hypotheses=_base_link_hypotheses(T),
        )


def _base_link_hypotheses(T):
    return {
        "multiplied on the wrong side: T_base_tool @ Rz(π) turns the tool, not the base": (
            lambda: T @ T_BASE_LINK_BASE
        ),
        "rotated by π/2 instead of π": lambda: _rz(np.pi / 2) @ T,
        "returned T_base_tool unchanged": lambda: T,
    }


def _rz(angle):
    T = np.eye(4)
    T[:3, :3] = rot_z(angle)
    return T


register(
    Exercise(
        id="0.2",
        function="base_link_pose",
        title="a tool pose in the URDF base_link frame",
        checks=(
            Check("returns a 4×4 homogeneous transform", 1, _is_transform),
            Check("equals Rz(π) @ T_base_tool on random poses", 2, _base_link_matches),
        ),
    )
)
