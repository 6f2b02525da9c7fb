"""Lesson 01 — rigid-body transforms."""

from __future__ import annotations

import numpy as np

from urkin.exercises.framework import (
    Check,
    Exercise,
    Mismatch,
    as_array,
    compare,
    identify_mistake,
    register,
    require_rotation,
    require_transform,
)
from urkin.exercises.inputs import random_pose, random_rotation
from urkin.transforms import (
    inv_transform,
    rot_x,
    rot_y,
    rot_z,
    rotation_to_rpy,
    rpy_to_rotation,
    skew,
    so3_exp,
)

# ------------------------------------------------------------------------------ 1.1 rot_z


def _rot_z_is_rotation(student, rng):
    for _ in range(10):
        theta = rng.uniform(-np.pi, np.pi)
        R = as_array(student(theta), (3, 3), "rot_z(theta)")
        require_rotation(R, "rot_z(theta)", {"theta": theta})


def _rot_z_matches(student, rng):
    for _ in range(10):
        theta = rng.uniform(-np.pi, np.pi)
        got = as_array(student(theta), (3, 3), "rot_z(theta)")
        compare(
            got,
            rot_z(theta),
            what="Rz(θ) = [[cos θ, −sin θ, 0], [sin θ, cos θ, 0], [0, 0, 1]]",
            inputs={"theta": theta},
            hypotheses=_rot_z_hypotheses(theta),
        )


def _rot_z_hypotheses(theta):
    return {
        "transposed: the sin θ entries have swapped signs (that is Rz(−θ))": lambda: rot_z(-theta),
        "θ treated as degrees": lambda: rot_z(np.radians(theta)),
        "rotation about x instead of z": lambda: rot_x(theta),
        "rotation about y instead of z": lambda: rot_y(theta),
    }


register(
    Exercise(
        id="1.1",
        function="rot_z",
        title="rotation about the z axis",
        checks=(
            Check("returns a 3×3 rotation matrix (orthonormal, det = +1)", 1, _rot_z_is_rotation),
            Check("matches Rz(θ) on random angles", 2, _rot_z_matches),
        ),
        forbidden=("urkin.transforms.rot_z", "urkin.transforms.so3_exp"),
    )
)


# -------------------------------------------------------------------- 1.2 transform_inverse


def _inverse_composes_to_identity(student, rng):
    for _ in range(10):
        T = random_pose(rng)
        got = as_array(student(T.copy()), (4, 4), "transform_inverse(T)")
        R, p = T[:3, :3], T[:3, 3]
        if np.allclose(T @ got, np.eye(4), atol=1e-9) and np.allclose(
            got @ T, np.eye(4), atol=1e-9
        ):
            continue
        compare(
            got,
            inv_transform(T),
            what="T @ transform_inverse(T) must be the identity",
            inputs={"T": T},
            hypotheses=_inverse_hypotheses(R, p),
        )


def _inverse_hypotheses(R, p):
    def inverse(rotation, translation):
        T = np.eye(4)
        T[:3, :3], T[:3, 3] = rotation, translation
        return T

    return {
        "the translation was not rotated: use −Rᵀp, not −p": lambda: inverse(R.T, -p),
        "R was not transposed: the inverse rotation is Rᵀ": lambda: inverse(R, -R @ p),
    }


def _inverse_is_transform(student, rng):
    T = random_pose(rng)
    got = as_array(student(T.copy()), (4, 4), "transform_inverse(T)")
    require_transform(got, "transform_inverse(T)", {"T": T})


register(
    Exercise(
        id="1.2",
        function="transform_inverse",
        title="inverse of a rigid-body transform",
        checks=(
            Check("T @ transform_inverse(T) = I on random poses", 2, _inverse_composes_to_identity),
            Check("returns a homogeneous transform", 1, _inverse_is_transform),
        ),
        forbidden=("urkin.transforms.inv_transform",),
    )
)


# ---------------------------------------------------------------------- 1.3 rotation_to_rpy


def _rpy_hypotheses(R):
    return {
        "returned degrees: seed 000's helper does, but angles are radians here": lambda: np.degrees(
            rotation_to_rpy(R)
        ),
        "returned (yaw, pitch, roll): the order is reversed": lambda: rotation_to_rpy(R)[::-1],
    }


def _rpy_rebuilds_rotation(student, rng):
    for _ in range(20):
        R = random_rotation(rng)
        rpy = as_array(student(R.copy()), (3,), "rotation_to_rpy(R)")
        rebuilt = rpy_to_rotation(rpy)
        if not np.allclose(rebuilt, R, atol=1e-9):
            raise Mismatch(
                "Rz(yaw) @ Ry(pitch) @ Rx(roll) does not give R back",
                inputs={"R": R},
                expected=rotation_to_rpy(R),
                got=rpy,
                mistake=identify_mistake(rpy, _rpy_hypotheses(R)),
            )


def _rpy_in_range(student, rng):
    for _ in range(20):
        R = random_rotation(rng)
        roll, pitch, yaw = as_array(student(R.copy()), (3,), "rotation_to_rpy(R)")
        if not (
            -np.pi - 1e-12 <= roll <= np.pi + 1e-12
            and -np.pi - 1e-12 <= yaw <= np.pi + 1e-12
            and -np.pi / 2 - 1e-12 <= pitch <= np.pi / 2 + 1e-12
        ):
            raise Mismatch(
                "roll and yaw belong in [−π, π] and pitch in [−π/2, π/2] (radians)",
                inputs={"R": R},
                got=[roll, pitch, yaw],
                mistake=identify_mistake([roll, pitch, yaw], _rpy_hypotheses(R)),
            )


def _locked_rotation(pitch_sign: float, roll: float, yaw: float) -> np.ndarray:
    """Rz(yaw) Ry(±π/2) Rx(roll) with its zeros exactly zero, as a hand-typed pose would be.

    (``rpy_to_rotation`` at ±π/2 leaves cos(π/2) = 6e-17 in place of those zeros, which lets
    formulas without a gimbal-lock branch get lucky.)
    """
    if pitch_sign > 0:
        s, c = np.sin(roll - yaw), np.cos(roll - yaw)
        return np.array([[0.0, s, c], [0.0, c, -s], [-1.0, 0.0, 0.0]])
    s, c = np.sin(roll + yaw), np.cos(roll + yaw)
    return np.array([[0.0, -s, -c], [0.0, c, -s], [1.0, 0.0, 0.0]])


def _rpy_gimbal_lock(student, rng):
    for pitch_sign in (1.0, -1.0, 1.0, -1.0):
        R = _locked_rotation(pitch_sign, rng.uniform(-np.pi, np.pi), rng.uniform(-np.pi, np.pi))
        rpy = as_array(student(R.copy()), (3,), "rotation_to_rpy(R) at pitch = ±90°")
        if not np.allclose(rpy_to_rotation(rpy), R, atol=1e-9):
            raise Mismatch(
                "at pitch = ±90° only roll ∓ yaw is defined, and the general formulas divide "
                "0 by 0: handle this case separately (any angles that rebuild R will do)",
                inputs={"R": R},
                got=rpy,
            )


register(
    Exercise(
        id="1.3",
        function="rotation_to_rpy",
        title="roll, pitch and yaw of a rotation",
        checks=(
            Check(
                "Rz(yaw) Ry(pitch) Rx(roll) rebuilds R for random rotations",
                2,
                _rpy_rebuilds_rotation,
            ),
            Check("angles in radians, in the standard ranges", 1, _rpy_in_range),
            Check("copes with the gimbal lock (pitch = ±90°)", 1, _rpy_gimbal_lock),
        ),
        forbidden=("urkin.transforms.rotation_to_rpy",),
    )
)


# ---------------------------------------------------------------- 1.4 axis_angle_to_rotation


def _rodrigues_unnormalised(axis, angle):
    K = skew(axis)
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


def _axis_angle_inputs(rng):
    axis = rng.normal(size=3) * rng.uniform(0.2, 3.0)  # deliberately not a unit vector
    return axis, rng.uniform(-np.pi, np.pi)


def _axis_angle_is_rotation(student, rng):
    for _ in range(10):
        axis, angle = _axis_angle_inputs(rng)
        R = as_array(student(axis.copy(), angle), (3, 3), "axis_angle_to_rotation(axis, angle)")
        require_rotation(R, "axis_angle_to_rotation(axis, angle)", {"axis": axis, "angle": angle})


def _axis_angle_matches(student, rng):
    for _ in range(10):
        axis, angle = _axis_angle_inputs(rng)
        unit = axis / np.linalg.norm(axis)
        got = as_array(student(axis.copy(), angle), (3, 3), "axis_angle_to_rotation")
        compare(
            got,
            so3_exp(unit * angle),
            what="R = I + sin θ [k] + (1 − cos θ) [k]² with k the unit axis",
            inputs={"axis": axis, "angle": angle},
            hypotheses=_axis_angle_hypotheses(axis, angle),
        )


def _axis_angle_hypotheses(axis, angle):
    unit = axis / np.linalg.norm(axis)
    return {
        "the axis was not normalised to a unit vector first": lambda: _rodrigues_unnormalised(
            axis, angle
        ),
        "transposed: that is the rotation by −θ": lambda: so3_exp(-unit * angle),
        "θ treated as degrees": lambda: so3_exp(unit * np.radians(angle)),
    }


def _axis_is_fixed(student, rng):
    for _ in range(10):
        axis, angle = _axis_angle_inputs(rng)
        R = as_array(student(axis.copy(), angle), (3, 3), "axis_angle_to_rotation")
        if not np.allclose(R @ axis, axis, atol=1e-9):
            raise Mismatch(
                "a rotation leaves its own axis where it is: R k = k",
                inputs={"axis": axis, "angle": angle},
                expected=axis,
                got=R @ axis,
            )


register(
    Exercise(
        id="1.4",
        function="axis_angle_to_rotation",
        title="Rodrigues' formula",
        checks=(
            Check("returns a rotation matrix", 1, _axis_angle_is_rotation),
            Check("matches Rodrigues' formula for random axes and angles", 2, _axis_angle_matches),
            Check("leaves the rotation axis fixed (R k = k)", 1, _axis_is_fixed),
        ),
        forbidden=("urkin.transforms.so3_exp",),
    )
)
