"""Following a path of poses with inverse kinematics: warm-started, nearest, never winding.

:func:`track` turns poses ``(M, 4, 4)`` into joint angles ``(M, 6)`` the way a controller
should: each sample starts from the previous one; by default it takes the closed-form solution
nearest the previous sample (so the arm keeps its branch while the branch exists, and no joint
jumps by a turn); a sample that cannot be solved leaves the arm where it was (it is marked, with
the reason, never silently overwritten); and no joint is wound past its limits.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from urkin._inputs import choice, positive, real
from urkin.analytic_ik import _members, _wrist_singular, ik_analytic, ik_closest
from urkin.kinematics import fk
from urkin.numerical_ik import ik
from urkin.robots import Robot, check_robot
from urkin.tracking_report import TrackingReport, tracking_report
from urkin.transforms import check_transform, pose_error, wrap_angles

__all__ = ["METHODS", "Tracking", "track"]

#: How :func:`track` solves each sample: the closed form (nearest solution) or a numerical
#: step rule of :func:`urkin.ik`, warm-started from the previous sample without restarts.
METHODS = ("analytic", "lm", "nr", "dls", "poe")

_TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class Tracking:
    """The joint angles that follow a path of poses, and which samples were reached.

    Attributes
    ----------
    q : ndarray, shape (M, 6)
        Joint angles (rad) at each sample.  Where a sample failed, the arm stays where it was
        (the previous reached sample's angles, or ``q0`` before the first).
    ok : ndarray of bool, shape (M,)
        Whether ``fk(q[k])`` reaches pose ``k`` within the tolerance (re-measured).
    failures : dict of int to str
        Why each failed sample failed (index → reason).
    method : str
        How the samples were solved.
    report : TrackingReport or None
        The :func:`urkin.tracking_report.tracking_report` of ``q`` against the poses (None for a
        single pose); call that function for speeds against limits at a given duration.
    """

    q: np.ndarray
    ok: np.ndarray
    failures: dict[int, str] = field(default_factory=dict)
    method: str = "analytic"
    report: TrackingReport | None = None


def _limits(robot: Robot) -> tuple[np.ndarray, np.ndarray]:
    limits = np.array(robot.joint_limits)
    return limits[:, 0], limits[:, 1]


def _chase(next_row: np.ndarray, first: int) -> np.ndarray:
    """Rows chosen along a chain where row ``r`` at step ``k`` leads to ``next_row[k, r]`` at
    step ``k + 1``: the prefix compositions of the maps, by doubling (log₂ K passes, no loop
    over the samples)."""
    composed = next_row.copy()
    shift = 1
    while shift < len(composed):
        composed[shift:] = np.take_along_axis(composed[shift:], composed[:-shift], axis=1)
        shift *= 2
    return np.r_[first, composed[:, first]]


def _analytic(
    robot: Robot, poses: np.ndarray, q0: np.ndarray
) -> tuple[np.ndarray, np.ndarray, dict[int, str]]:
    solutions, real_rows = ik_analytic(robot, poses, return_mask=True)  # (M, 8, 6), (M, 8)
    _through_the_wrist(robot, poses, q0, solutions, real_rows)
    reached = np.flatnonzero(real_rows.any(axis=1))
    q = np.empty((len(reached), 6))
    failures: dict[int, str] = {}
    if len(reached):
        found = solutions[reached]
        # the first reached sample: the solution nearest q0 (turns of 2π do not count)
        start = np.linalg.norm(wrap_angles(found[0] - q0, check=False), axis=1)
        first = int(np.nanargmin(start))
        # each later one: the row nearest the row chosen before it (rows that are not
        # solutions are infinitely far)
        gap = np.linalg.norm(
            wrap_angles(found[1:, None, :, :] - found[:-1, :, None, :], check=False), axis=-1
        )
        gap[np.isnan(gap)] = np.inf
        rows = _chase(np.argmin(gap, axis=2), first)
        chosen = found[np.arange(len(reached)), rows]  # (K, 6), wrapped to (−π, π]
        # unwrap: continue each joint from q0 by the shortest turn between samples, then take
        # the exact solution's equivalent nearest that continuation
        steps = wrap_angles(np.diff(np.vstack([q0, chosen]), axis=0), check=False)
        continued = q0 + np.cumsum(steps, axis=0)
        q = chosen + _TWO_PI * np.round((continued - chosen) / _TWO_PI)
        lower, upper = _limits(robot)
        beyond = np.flatnonzero(((q < lower - 1e-12) | (q > upper + 1e-12)).any(axis=1))
        if len(beyond):  # winding: stop where a joint would pass its limit
            stop = int(beyond[0])
            joint = int(np.flatnonzero((q[stop] < lower - 1e-12) | (q[stop] > upper + 1e-12))[0])
            for k in reached[stop:]:
                failures[int(k)] = _winding(joint, lower, upper, int(reached[stop]))
            reached, q = reached[:stop], q[:stop]
    missing = np.setdiff1d(np.arange(len(poses)), np.r_[reached, list(failures)])
    if len(missing):
        result = ik_closest(robot, poses[missing], q0)
        reasons = result.reason if isinstance(result.reason, list) else [result.reason]
        for k, why in zip(missing, reasons):
            failures[int(k)] = why or "no closed-form solution"
    full = np.empty((len(poses), 6))
    ok = np.zeros(len(poses), dtype=bool)
    full[reached], ok[reached] = q, True
    return full, ok, failures


def _through_the_wrist(
    robot: Robot, poses: np.ndarray, q0: np.ndarray, solutions: np.ndarray, real_rows: np.ndarray
) -> None:
    """At wrist-singular samples (``sin θ5 = 0``: a one-parameter family of solutions, of which
    :func:`ik_analytic` returns two representatives per shoulder), replace each sample's rows by
    the members that keep ``θ2 + θ3 + θ4`` of the rows of the last sample before them that is
    not singular (of ``q0`` before the first): row ``r`` becomes the member nearest that
    sample's row ``r``, so a path through the singularity keeps its branch, joint 4 included,
    where the representatives would swing joints 4 and 6 by a large angle and back.  In place,
    on ``solutions`` (M, 8, 6) and ``real_rows`` (M, 8)."""
    singular = _wrist_singular(solutions, real_rows)
    if not singular.any():
        return
    m = len(poses)
    anchor = np.maximum.accumulate(np.where(singular, -1, np.arange(m)))  # −1: q0
    at = np.flatnonzero(singular)
    before = np.where(
        (anchor[at] >= 0)[:, None, None], solutions[np.maximum(anchor[at], 0)], q0
    )  # (K, 8, 6): the rows each singular sample continues
    usable = np.where((anchor[at] >= 0)[:, None], real_rows[np.maximum(anchor[at], 0)], True)
    k, r = np.nonzero(usable)
    found, valid = _members(
        robot, poses[at[k]], before[k, r, 1] + before[k, r, 2] + before[k, r, 3]
    )  # (H, 8, 6) members for each usable (sample, row)
    gap = np.linalg.norm(wrap_angles(found - before[k, r, None], check=False), axis=-1)
    gap[~valid] = np.inf
    nearest = np.argmin(gap, axis=1)
    hit = np.isfinite(gap[np.arange(len(k)), nearest])
    rows = np.full((len(at), 8, 6), np.nan)
    rows[k[hit], r[hit]] = found[np.flatnonzero(hit), nearest[hit]]
    kept = ~np.isnan(rows[..., 0])
    solutions[at] = np.where(kept.any(axis=1)[:, None, None], rows, solutions[at])
    real_rows[at] = np.where(kept.any(axis=1)[:, None], kept, real_rows[at])


def _numerical(
    robot: Robot, poses: np.ndarray, q0: np.ndarray, method: str, tol: float
) -> tuple[np.ndarray, np.ndarray, dict[int, str]]:
    # each solve starts where the previous one ended: the samples depend on one another, so
    # this is one solve per sample (no restarts: a restart would jump to another branch)
    q = np.empty((len(poses), 6))
    ok = np.zeros(len(poses), dtype=bool)
    failures: dict[int, str] = {}
    lower, upper = _limits(robot)
    current = q0
    for k, T in enumerate(poses):
        result = ik(
            robot,
            T,
            current,
            method=method,
            tol_position=tol,
            tol_orientation=tol,
            max_restarts=0,
        )
        if not result.success:
            failures[k] = str(result.reason)
            continue
        # ik wraps into (−π, π]: continue each joint by the equivalent nearest the last sample
        solved = np.asarray(result.q, dtype=float)
        solved = solved + _TWO_PI * np.round((current - solved) / _TWO_PI)
        beyond = np.flatnonzero((solved < lower - 1e-12) | (solved > upper + 1e-12))
        if len(beyond):
            failures[k] = _winding(beyond[0], lower, upper, k)
            continue
        current = solved
        q[k], ok[k] = current, True
    return q, ok, failures


def _winding(joint: int, lower: np.ndarray, upper: np.ndarray, k: int) -> str:
    """Why a sample from ``k`` on is not followed: ``joint`` would turn past its limit."""
    return (
        f"joint {joint + 1} would turn past its limit "
        f"({math.degrees(lower[joint]):.0f}°…{math.degrees(upper[joint]):.0f}°) to "
        f"follow the path from sample {k} on: staying put"
    )


def track(
    robot: Robot,
    poses: ArrayLike,
    q0: ArrayLike,
    *,
    method: str = "analytic",
    tol: float = 1e-9,
) -> Tracking:
    """Joint angles that follow ``poses`` one sample after another, starting from ``q0``.

    Parameters
    ----------
    robot : Robot
    poses : array_like, shape (M, 4, 4)
        The path's poses (tool poses in the robot's base frame), e.g. from
        :func:`urkin.trajectory.pose_path`.
    q0 : array_like, shape (6,)
        Where the arm is before the first sample (rad), within the joint limits.
    method : {"analytic", "lm", "nr", "dls", "poe"}
        ``"analytic"`` (default): the closed-form solution nearest the previous sample, each
        joint continued by its shortest turn (so a joint can pass ±π, but not its limits).
        The others: :func:`urkin.ik` with that step rule, warm-started from the previous
        sample, without random restarts — to compare.
    tol : float
        Largest position (m) and orientation (rad) error that counts as reached.

    Returns
    -------
    Tracking
        ``q`` (M, 6), ``ok`` (M,), the reason of every failed sample and the tracking
        report.  A failed sample leaves the arm where it was.  With the closed form, a
        sample from which a joint would have to pass its limit fails, and so do all after it
        (going on would need a turn back).

    Examples
    --------
    >>> import urkin
    >>> from urkin import trajectory
    >>> ur3 = urkin.robot("ur3")
    >>> poses = trajectory.pose_path(trajectory.circle((0.25, 0.1, 0.3), 0.1, plane="yz"))
    >>> q_start = urkin.ik_analytic(ur3, poses[0])[0]
    >>> result = track(ur3, poses, q_start)
    >>> result.q.shape, bool(result.ok.all())
    ((629, 6), True)
    >>> position, angle = urkin.transforms.pose_error(urkin.fk(ur3, result.q), poses)
    >>> bool(position.max() < 1e-9 and angle.max() < 1e-9)
    True
    """
    robot = check_robot(robot)
    T = check_transform(poses, name="poses")
    if T.ndim != 3 or len(T) == 0:
        raise ValueError(
            f"poses must be a path of poses, shape (M, 4, 4) with M ≥ 1; got {T.shape}"
        )
    start = real(q0, "q0")
    if start.shape != (6,):
        raise ValueError(f"q0 must be one configuration, shape (6,); got {start.shape}")
    lower, upper = _limits(robot)
    if np.any(start < lower) or np.any(start > upper):
        raise ValueError("q0 is outside the robot's joint limits")
    choice(method, "method", METHODS)
    tol = float(positive(tol, "tol"))
    if method == "analytic":
        q, ok, failures = _analytic(robot, T, start)
    else:
        q, ok, failures = _numerical(robot, T, start, method, tol)
    # re-measure every reached sample, whatever solved it
    if ok.any():
        position, angle = pose_error(fk(robot, q[ok]), T[ok])
        missed = np.flatnonzero(ok)[(position > tol) | (angle > tol)]
        for k in missed:
            failures[int(k)] = "the solution misses the pose by more than tol"
        ok[missed] = False
    # a failed sample leaves the arm where it was
    last = np.maximum.accumulate(np.where(ok, np.arange(len(T)), -1))
    held = np.where((last >= 0)[:, None], q[np.maximum(last, 0)], start)
    failures = dict(sorted(failures.items()))
    report = tracking_report(robot, T, held, failures=failures) if len(T) > 1 else None
    return Tracking(held, ok, failures, method, report)
