"""Random inputs for checks: angles, rotations, poses, joint configurations, arms."""

from __future__ import annotations

import numpy as np

import urkin
from urkin.poe import screw_axis
from urkin.robots import Robot
from urkin.transforms import make_transform, so3_exp


def random_rotation(rng: np.random.Generator) -> np.ndarray:
    """A rotation about a random axis by an angle in (−π, π)."""
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    return so3_exp(axis * rng.uniform(-np.pi, np.pi))


def random_pose(rng: np.random.Generator) -> np.ndarray:
    """A rigid transform with a random rotation and a translation within ±1 m."""
    return make_transform(random_rotation(rng), rng.uniform(-1.0, 1.0, 3))


def random_q(rng: np.random.Generator) -> np.ndarray:
    """Six joint angles uniform in [−π, π)."""
    return rng.uniform(-np.pi, np.pi, 6)


def random_regular_q(
    rng: np.random.Generator, centre: np.ndarray | None = None, spread: float = np.pi
) -> np.ndarray:
    """Joint angles within ``spread`` of ``centre`` (uniform over [−π, π) without one) whose
    elbow and wrist are at least ~11° from their singularities (|sin q3|, |sin q5| ≥ 0.2)."""
    while True:
        q = random_q(rng) if centre is None else centre + rng.uniform(-spread, spread, 6)
        if abs(np.sin(q[2])) >= 0.2 and abs(np.sin(q[4])) >= 0.2:
            return q


def random_screw_axes(rng: np.random.Generator, n: int, reach: float = 0.5) -> np.ndarray:
    """Screw axes (6, n) of ``n`` revolute joints: random unit axes through random points
    within ±``reach`` metres (an arm of any number of joints, for product-of-exponentials
    checks)."""
    w = rng.normal(size=(n, 3))
    w /= np.linalg.norm(w, axis=1, keepdims=True)
    return screw_axis(w, rng.uniform(-reach, reach, (n, 3))).T


def random_arm(rng: np.random.Generator) -> Robot:
    """One of the seven UR arms."""
    return urkin.robot(urkin.ROBOTS[int(rng.integers(len(urkin.ROBOTS)))])


def negated_a(robot: Robot) -> Robot:
    """The arm with a2 and a3 of the opposite sign (a common transcription mistake)."""
    return Robot(f"{robot.name} (+a)", robot.d1, -robot.a2, -robot.a3, robot.d4, robot.d5, robot.d6)
