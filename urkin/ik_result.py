"""What an inverse-kinematics solver returns, and how it fails: one result type for all of them.

Every solver that picks one configuration per target — the numerical :func:`urkin.ik` and the
closed-form :func:`urkin.ik_closest` — returns an :class:`IKResult` whose ``success`` was
re-measured with :func:`urkin.fk` against the target as given (:func:`verified`), and whose
``reason`` says why not when it failed: out of reach (with the distance, :func:`unreachable`),
outside the joint limits, a target rotation that is not orthonormal to the tolerance, or no
convergence (with the error that remained).  Malformed input is never a failed result: it
raises, naming the argument.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from urkin.kinematics import fk, flange_pose
from urkin.robots import Robot
from urkin.transforms import (
    _FEW_POSES,
    _is_rotation_one,
    _rotation_deviation,
    orthonormalize,
    pose_error,
    rotation_angle,
)

__all__ = [
    "RIGID_TOLERANCE",
    "IKResult",
    "nearest_rigid",
    "no_solution_reason",
    "skew_reason",
    "stacked",
    "unreachable",
    "verified",
]

#: A target whose rotation is further than this from orthonormal (any entry of ``RᵀR − I``,
#: or ``det R − 1``) is solved for its nearest rotation: no configuration reaches a matrix
#: that is not a rotation.
RIGID_TOLERANCE = 1e-14


@dataclass
class IKResult:
    """What an IK solver found, for one target or (arrays) for a stack of targets.

    Attributes
    ----------
    q : ndarray, shape (6,) or (..., 6)
        The solution when ``success``; otherwise the configuration with the smallest error
        found (the initial guess when the target was rejected before iterating).  Never NaN.
    success : bool or ndarray of bool
        True only if the pose error of ``q``, re-measured with :func:`urkin.fk`, is within both
        tolerances.
    residual : float or ndarray
        ``max(position_error, orientation_error)`` of ``q`` (metres and radians).
    position_error : float or ndarray
        Distance between the tool and the target position, metres.
    orientation_error : float or ndarray
        Angle of the rotation between the tool and the target orientation, radians (0 for a
        position-only target).
    iterations : int or ndarray
        Iterations over all attempts (0 for the closed form).
    restarts : int or ndarray
        Restarts from random configurations (0 for the closed form).
    reason : str or list of str
        ``"converged"``, or why not.
    """

    q: np.ndarray
    success: bool | np.ndarray
    residual: float | np.ndarray
    position_error: float | np.ndarray
    orientation_error: float | np.ndarray
    iterations: int | np.ndarray
    restarts: int | np.ndarray
    reason: str | list = field(default="")

    def __len__(self) -> int:
        if np.ndim(self.success) == 0:
            raise TypeError("a single IKResult has no length; batched results do")
        return len(self.success)

    def __getitem__(self, index: int) -> IKResult:
        if np.ndim(self.success) != 1:
            raise TypeError(
                "a single IKResult cannot be indexed; index a batch of targets (one leading axis)"
            )
        if not isinstance(index, (int, np.integer)) or isinstance(index, bool):
            raise TypeError(
                f"an IKResult is indexed by one integer (a target of the batch); got "
                f"{type(index).__name__} {index!r:.40} (slice the arrays: result.q[0:2], "
                "result.success[0:2])"
            )
        return IKResult(
            self.q[index].copy(),
            bool(self.success[index]),
            float(self.residual[index]),
            float(self.position_error[index]),
            float(self.orientation_error[index]),
            int(self.iterations[index]),
            int(self.restarts[index]),
            self.reason[index],
        )

    def __repr__(self) -> str:
        if np.ndim(self.success) == 0:
            q = np.array2string(np.asarray(self.q), precision=4, separator=", ")
            return (
                f"IKResult(success={self.success}, q={q}, residual={self.residual:.2e}, "
                f"iterations={self.iterations}, restarts={self.restarts}, reason={self.reason!r})"
            )
        if np.size(self.success) == 0:
            return "IKResult(batch of 0)"
        return (
            f"IKResult(batch of {np.size(self.success)}: {int(np.sum(self.success))} succeeded, "
            f"median iterations {np.median(self.iterations):g})"
        )


def _wrist_points(robot: Robot, T_world_tool: np.ndarray) -> np.ndarray:
    T_base_flange = flange_pose(robot, T_world_tool, check=False)
    return T_base_flange[..., :3, 3] - robot.d6 * T_base_flange[..., :3, 2]


def _metres(x: float) -> str:
    """A distance for a message: to 0.1 mm, or in scientific notation when absurdly large."""
    return f"{x:.4f}" if x < 1e6 else f"{x:.3g}"


def unreachable(robot: Robot, targets: np.ndarray, pose: bool) -> tuple[np.ndarray, list[str]]:
    """Targets (N, 4, 4) or positions (N, 3) that no configuration reaches, and why.

    Necessary conditions: a pose fixes its wrist point ``w = p − d6 z`` (the origin of DH frame
    5), which lies within ``|a2| + |a3| + √(d4² + d5²)`` of the shoulder point ``(0, 0, d1)`` and
    at least ``d4`` from the base axis; a position lies within that reach plus ``d6`` (plus the
    tool's offset).  A target within ``1e-9`` m of the border passes.

    Examples
    --------
    >>> import urkin
    >>> bad, why = unreachable(urkin.robot("ur3"), np.array([[1.0, 0.0, 0.2]]), pose=False)
    >>> bool(bad[0]), why[0]
    (True, "unreachable: the target is 0.3213 m beyond the UR3's reach (it is 1.0012 m from the shoulder; at most 0.6799 m is reachable)")
    """  # noqa: E501
    arm = abs(robot.a2) + abs(robot.a3) + math.hypot(robot.d4, robot.d5)
    if pose and len(targets) == 1 and robot._plain:  # the scalar fast path
        (_, _, zx, px), (_, _, zy, py), (_, _, zz, pz), _ = targets[0].tolist()
        wx, wy, wz = px - robot.d6 * zx, py - robot.d6 * zy, pz - robot.d6 * zz - robot.d1
        if math.sqrt(wx * wx + wy * wy + wz * wz) <= arm + 1e-9 and (
            math.hypot(wx, wy) >= robot.d4 - 1e-9
        ):
            return np.zeros(1, dtype=bool), [""]
    if pose:
        points = _wrist_points(robot, targets)
        reach, what = arm, "its wrist point"
    else:
        T_base_world = np.linalg.inv(robot.base)
        points = targets @ T_base_world[:3, :3].T + T_base_world[:3, 3]
        reach = arm + robot.d6 + float(np.linalg.norm(robot.tool[:3, 3]))
        what = "it"
    offset = points - [0.0, 0.0, robot.d1]
    distance = np.hypot(np.hypot(offset[..., 0], offset[..., 1]), offset[..., 2])  # no overflow
    bad = distance > reach + 1e-9
    reasons = [
        f"unreachable: the target is {_metres(d - reach)} m beyond the {robot.name}'s reach "
        f"({what} is {_metres(d)} m from the shoulder; at most {reach:.4f} m is reachable)"
        if flag
        else ""
        for flag, d in zip(bad, distance)
    ]
    if pose:
        radial = np.hypot(points[:, 0], points[:, 1])
        inner = (radial < robot.d4 - 1e-9) & ~bad
        for i in np.flatnonzero(inner):
            reasons[i] = (
                f"unreachable: the wrist point is {radial[i]:.4f} m from the base axis, "
                f"{robot.d4 - radial[i]:.4g} m closer than the {robot.name}'s shoulder offset "
                f"d4 = {robot.d4:.4f} m allows"
            )
        bad = bad | inner
    return bad, reasons


def no_solution_reason(robot: Robot, T_world_tool: np.ndarray, elbow_miss: float) -> str:
    """Why the closed form found no solution for one pose, with the distance.

    ``elbow_miss`` is how far (metres) the planar arm of joints 2–3 falls short on its nearest
    branch, for poses that pass the necessary conditions of :func:`unreachable`.
    """
    bad, reasons = unreachable(robot, T_world_tool[None], pose=True)
    if bad[0]:
        return reasons[0]
    return (
        f"unreachable: on every branch the elbow misses the wrist by at least {elbow_miss:.4g} m "
        "(the upper arm and forearm cannot stretch or fold that far)"
    )


def verified(
    robot: Robot,
    q: np.ndarray,
    goal: np.ndarray,
    found: Sequence[bool],
    reasons: list[str],
    tol_position: float,
    tol_orientation: float,
    lead: tuple[int, ...],
    iterations: Sequence[int] | None = None,
    restarts: Sequence[int] | None = None,
    failure: Callable[[int, float, float], str] | None = None,
) -> IKResult:
    """The :class:`IKResult` of configurations ``q`` (N, 6) for targets ``goal`` — poses
    (N, 4, 4) or positions (N, 3) — re-measured with :func:`urkin.fk`.

    ``found`` says which rows the solver believes solved; ``reasons`` holds the reason of each
    row it rejected before solving (else ""); any other row that fails gets
    ``failure(row, position error, rotation error)``, or a plain statement of the miss.
    ``lead`` gives the result its leading axes (``()`` for one target).
    """
    n = len(q)
    if goal.shape == (1, 4, 4):  # one pose (or a stack of one): its errors in floats
        position, rotation = pose_error(fk(robot, q[0]), goal[0], check=False)
        success = bool(found[0]) and position <= tol_position and rotation <= tol_orientation
        if success:
            why = "converged"
        elif reasons[0]:
            why = reasons[0]
        elif failure:
            why = failure(0, float(position), float(rotation))
        else:
            why = f"the solution misses the target by {position:.2e} m and {rotation:.2e} rad"
        one = IKResult(
            q[0].copy(),
            success,
            float(max(position, rotation)),
            float(position),
            float(rotation),
            0 if iterations is None else int(iterations[0]),
            0 if restarts is None else int(restarts[0]),
            why,
        )
        return one if lead == () else _with_leading_axes(_stack_of_one(one), lead)
    T = fk(robot, q)
    if goal.shape[-2:] == (4, 4):
        position_error, rotation_error = pose_error(T, goal, check=False)
    else:
        with np.errstate(over="ignore"):  # a target 1e300 m away: inf, and the reason says so
            position_error = np.linalg.norm(T[:, :3, 3] - goal, axis=-1)
        rotation_error = np.zeros(n)
    success = (
        np.asarray(found) & (position_error <= tol_position) & (rotation_error <= tol_orientation)
    )
    why = list(reasons)
    for i in np.flatnonzero(~success):
        if not why[i]:
            position, rotation = float(position_error[i]), float(rotation_error[i])
            why[i] = (
                failure(int(i), position, rotation)
                if failure
                else f"the solution misses the target by {position:.2e} m and {rotation:.2e} rad"
            )
    for i in np.flatnonzero(success):
        why[i] = "converged"
    iterations = np.zeros(n, dtype=int) if iterations is None else np.asarray(iterations)
    restarts = np.zeros(n, dtype=int) if restarts is None else np.asarray(restarts)
    residual = np.maximum(position_error, rotation_error)
    result = IKResult(
        q, success, residual, position_error, rotation_error, iterations, restarts, why
    )
    return result[0] if lead == () else _with_leading_axes(result, lead)


def stacked(results: list[IKResult], lead: tuple[int, ...]) -> IKResult:
    """One result for a stack of targets from the results of its targets solved one by one,
    with the stack's leading axes ``lead``."""
    columns = [
        np.array([getattr(r, name) for r in results])
        for name in (
            "success",
            "residual",
            "position_error",
            "orientation_error",
            "iterations",
            "restarts",
        )
    ]
    flat = IKResult(np.stack([r.q for r in results]), *columns, [r.reason for r in results])
    return _with_leading_axes(flat, lead)


def _stack_of_one(one: IKResult) -> IKResult:
    """A single result as a batch of one (arrays of one entry, ``q`` of shape (1, 6))."""
    return IKResult(
        one.q[None],
        np.array([one.success]),
        np.array([one.residual]),
        np.array([one.position_error]),
        np.array([one.orientation_error]),
        np.array([one.iterations]),
        np.array([one.restarts]),
        [one.reason],
    )


def _with_leading_axes(result: IKResult, lead: tuple[int, ...]) -> IKResult:
    """A flat result (one leading axis) reshaped to the leading axes ``lead``."""
    if len(lead) <= 1:
        return result
    shaped = np.empty(len(result.reason), dtype=object)
    shaped[:] = result.reason
    fields = (result.success, result.residual, result.position_error, result.orientation_error)
    return IKResult(
        result.q.reshape(*lead, 6),
        *(a.reshape(lead) for a in fields),
        result.iterations.reshape(lead),
        result.restarts.reshape(lead),
        shaped.reshape(lead).tolist(),
    )


def nearest_rigid(
    goal: np.ndarray, tol: float = RIGID_TOLERANCE, deviation: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Checked target poses (N, 4, 4) with each rotation further than ``tol`` from orthonormal
    replaced by its nearest rotation (:func:`~urkin.transforms.orthonormalize`), and the angle
    (rad) each was moved by (0 for the others): the targets IK solves, and how far they are
    from what was asked (a pose copied with a few decimals is off by about its last digit).
    ``deviation`` (N,): each pose's deviation from a rotation, if the check measured it."""
    if deviation is None and len(goal) == 1 and _is_rotation_one(goal[0].tolist(), tol):
        return goal, np.zeros(1)  # one rigid pose: the common case of a single solve
    if deviation is None and len(goal) <= _FEW_POSES:  # a few poses: their floats, one by one
        off = np.array([not _is_rotation_one(rows, tol) for rows in goal.tolist()], dtype=bool)
    else:
        if deviation is None:  # checked poses: no error raised here
            deviation = _rotation_deviation(goal[:, :3, :3], math.inf, "target")
        off = deviation.reshape(-1) > tol
    skew = np.zeros(len(goal))
    if not off.any():
        return goal, skew
    R = goal[:, :3, :3]
    rigid = goal.copy()
    rigid[off, :3, :3] = orthonormalize(R[off])
    skew[off] = rotation_angle(R[off], rigid[off, :3, :3])
    return rigid, skew


def skew_reason(angle: float, tol_name: str, tol: float) -> str:
    """Why a target ``angle`` rad from its nearest rotation fails a tolerance ``tol``."""
    return (
        f"the target's rotation is {angle:.2e} rad from the nearest rotation matrix, more than "
        f"{tol_name} = {tol:g}: no configuration can match it (urkin.transforms.orthonormalize "
        "gives the nearest rotation)"
    )
