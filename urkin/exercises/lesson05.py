"""Lesson 05 — Newton–Raphson inverse kinematics."""

from __future__ import annotations

import numpy as np

import urkin
from urkin.exercises.framework import Check, Exercise, Mismatch, as_array, compare, register
from urkin.exercises.inputs import random_arm, random_pose, random_q, random_regular_q
from urkin.numerical_ik import orientation_error
from urkin.transforms import make_transform, rot_z

_fk, _ik = urkin.fk, urkin.ik  # references, bound before any grading guard is installed
_orientation_error = orientation_error

_IK_FUNCTIONS = (
    "urkin.numerical_ik.ik",
    "urkin.numerical_ik._iterate_one",
    "urkin.numerical_ik._iterate_batch",
)


# ---------------------------------------------------------------------------- 5.1 pose_error


def _expected_error(T, T_target):
    e_p = T_target[:3, 3] - T[:3, 3]
    return np.r_[e_p, _orientation_error(T[:3, :3], T_target[:3, :3])]


_CROSS = (
    "the seeds' cross-product error ½ Σ rᵢ × tᵢ = sin φ·k, not the rotation vector φ·k: it "
    "shrinks for large errors and vanishes at 180°"
)


def _pose_error_hypotheses(T, T_target):
    right = _expected_error(T, T_target)
    cross = _orientation_error(T[:3, :3], T_target[:3, :3], "cross")
    in_tool = T[:3, :3].T @ right[3:]
    return {
        _CROSS: lambda: np.r_[right[:3], cross],
        "the error points the wrong way: target − current, not current − target": lambda: -right,
        "the orientation error is in the tool frame, log(Rᵀ R_target); it belongs in the base "
        "frame, log(R_target Rᵀ), like the Jacobian's ω": lambda: np.r_[right[:3], in_tool],
        "(orientation; position) order: the geometric Jacobian puts position first": lambda: np.r_[
            right[3:], right[:3]
        ],
    }


def _pose_error_matches(student, rng):
    for _ in range(15):
        T, T_target = random_pose(rng), random_pose(rng)
        got = as_array(student(T.copy(), T_target.copy()), (6,), "pose_error(T, T_target)")
        compare(
            got,
            _expected_error(T, T_target),
            what="e = [p_target − p; log(R_target Rᵀ)] (rotation vector, base frame)",
            inputs={"T": T, "T_target": T_target},
            hypotheses=_pose_error_hypotheses(T, T_target),
        )


def _pose_error_sees_half_turns(student, rng):
    for _ in range(5):
        T = random_pose(rng)
        T_target = T @ make_transform(rot_z(np.pi))  # the same point, turned by 180°
        got = as_array(student(T.copy(), T_target.copy()), (6,), "pose_error(T, T_target)")
        if not np.isclose(np.linalg.norm(got[3:]), np.pi, atol=1e-9):
            raise Mismatch(
                "a target turned by 180° must give an orientation error of length π; the "
                "cross-product form gives 0 there, so Newton's method would stop believing it "
                "has arrived",
                inputs={"T": T, "T_target": T_target},
                expected=f"|e_o| = {np.pi:.4f}",
                got=f"|e_o| = {np.linalg.norm(got[3:]):.4f}",
                mistake=_CROSS if np.linalg.norm(got[3:]) < 1e-6 else None,
            )


register(
    Exercise(
        id="5.1",
        function="pose_error",
        title="the 6-vector error between two poses",
        checks=(
            Check("matches [p_t − p; log(R_t Rᵀ)] on random pose pairs", 2, _pose_error_matches),
            Check("sees a 180° orientation error", 1, _pose_error_sees_half_turns),
        ),
        forbidden=("urkin.numerical_ik.orientation_error", "urkin.transforms.so3_log"),
    )
)


# ----------------------------------------------------------------------------- 5.2 ik_newton


def _nearby_problem(rng, spread: float, position_only: bool = False):
    """A random arm, a target pose it reaches, and a start ``spread`` rad away per joint,
    such that plain Newton–Raphson (urkin's, without restarts) converges from that start."""
    arm = random_arm(rng)
    while True:
        q_true = random_regular_q(rng)
        q0 = q_true + rng.uniform(-spread, spread, 6)
        T_target = _fk(arm, q_true)
        target = T_target[:3, 3] if position_only else T_target
        if _ik(arm, target, q0=q0, method="nr", max_restarts=0).success:
            return arm, T_target, q0


def _verify_pose(arm, q, T_target, what, inputs):
    T = _fk(arm, q)
    position, angle = (
        np.linalg.norm(T[:3, 3] - T_target[:3, 3]),
        np.linalg.norm(_orientation_error(T[:3, :3], T_target[:3, :3])),
    )
    if position > 1e-8 or angle > 1e-8:
        raise Mismatch(
            f"{what}: fk(robot, q) must reach the target (within 1e-8 m and 1e-8 rad); it "
            f"misses by {position:.2e} m and {angle:.2e} rad",
            inputs=inputs,
        )


def _newton_converges(student, rng, spread: float):
    for _ in range(6):
        arm, T_target, q0 = _nearby_problem(rng, spread)
        q = as_array(student(arm, T_target.copy(), q0.copy()), (6,), "ik_newton(robot, T, q0)")
        if np.allclose(q, q0):
            raise Mismatch(
                "ik_newton returned its initial guess unchanged",
                inputs={"robot": arm.name, "q0": q0},
            )
        _verify_pose(arm, q, T_target, "ik_newton", {"robot": arm.name, "q0": q0})


def _newton_close(student, rng):
    _newton_converges(student, rng, 0.1)


def _newton_far(student, rng):
    _newton_converges(student, rng, 0.5)


register(
    Exercise(
        id="5.2",
        function="ik_newton",
        title="full-pose Newton–Raphson IK",
        checks=(
            Check("reaches targets from a start 0.1 rad away", 2, _newton_close),
            Check("reaches targets from a start 0.5 rad away", 2, _newton_far),
        ),
        forbidden=_IK_FUNCTIONS,
        builds_on=("5.1",),
    )
)


# --------------------------------------------------------------------------- 5.3 ik_position


def _position_converges(student, rng):
    for _ in range(8):
        arm, T_target, q0 = _nearby_problem(rng, 0.4, position_only=True)
        p_target = T_target[:3, 3]
        q = as_array(student(arm, p_target.copy(), q0.copy()), (6,), "ik_position(robot, p, q0)")
        reached = _fk(arm, q)[:3, 3]
        miss = np.linalg.norm(reached - p_target)
        if miss > 1e-8:
            raise Mismatch(
                f"fk(robot, q)[:3, 3] must reach p_target within 1e-8 m; it misses by {miss:.2e} m",
                inputs={"robot": arm.name, "p_target": p_target, "q0": q0},
                expected=p_target,
                got=reached,
                mistake="the position was reached in millimetres, not metres (seed 002 worked "
                "in millimetres)"
                if np.allclose(reached * 1000, p_target, atol=1e-3)
                else None,
            )


def _position_ignores_orientation(student, rng):
    # any orientation will do: targets far from the start's orientation must still be reached
    arm = urkin.robot("ur5")
    for _ in range(4):
        q0 = random_q(rng)
        p_target = _fk(arm, q0 + rng.uniform(-0.3, 0.3, 6))[:3, 3]
        q = as_array(student(arm, p_target.copy(), q0.copy()), (6,), "ik_position")
        miss = np.linalg.norm(_fk(arm, q)[:3, 3] - p_target)
        if miss > 1e-8:
            raise Mismatch(
                f"only the position counts: use the 3×6 position Jacobian (missed by {miss:.2e} m)",
                inputs={"robot": arm.name, "p_target": p_target, "q0": q0},
            )


register(
    Exercise(
        id="5.3",
        function="ik_position",
        title="position-only Newton–Raphson IK",
        checks=(
            Check("reaches random target points", 2, _position_converges),
            Check("needs only the position (3 × 6 Jacobian)", 1, _position_ignores_orientation),
        ),
        forbidden=_IK_FUNCTIONS,
    )
)
