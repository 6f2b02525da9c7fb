"""Numerical inverse kinematics: one iterative core, four step rules, batched over targets.

``urkin.ik(robot, target, q0=None, method="lm")`` finds joint angles ``q`` with
``fk(robot, q) ≈ target``.  The core owns everything the step rules share:

* iterations with an error that is re-measured after every step;
* separate tolerances on the position (metres) and the orientation (radians);
* step limiting (no joint moves more than ``max_step`` radians in one step);
* angle wrapping into [−π, π) and the robot's joint limits;
* restarts from seeded random configurations when an attempt stalls;
* verification: success is reported only when the pose error of the returned ``q``, measured
  with :func:`urkin.fk`, is within both tolerances.

Step rules (``method``):

``"nr"``
    Newton–Raphson with the pseudo-inverse: ``Δq = J⁺ e``.
``"dls"``
    Damped least squares with a fixed damping: ``Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e``, ``λ = 0.01``.
``"lm"`` (default)
    Levenberg–Marquardt: ``Δq = (JᵀJ + μ I)⁻¹ Jᵀ e`` with ``μ`` adapted every iteration from
    how well the step's predicted error reduction matched the actual one (Nielsen's rule):
    smaller after a good step, larger — and the step rejected — after one that does not
    lower the error.
``"poe"``
    Newton–Raphson on the matrix-log twist error of Modern Robotics' ``IKinSpace``:
    ``V_s = log(T_target T⁻¹)``, ``Δq = J_s⁺ V_s`` with the space Jacobian.

The orientation error of ``nr``, ``dls`` and ``lm`` is the rotation vector
``log(R_target R_currentᵀ)`` (``orientation_error="log"``, default).  The course reports'
``orientation_error="cross"``, ``½ Σ r_i × t_i`` over the columns of the current and target
rotations, equals ``sin(φ)·k`` and vanishes at a 180° error: from an orientation exactly half
a turn away it sees no error at all (its blind spot), so it is taught but not the default.

A target is a 4×4 pose, or a position (3-vector, metres) when only the tool position matters.
Targets that cannot be reached are rejected before iterating, with the distance beyond reach.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from urkin._generated import ur_kinematics as _gen
from urkin.kinematics import _joints, fk, jacobian
from urkin.robots import Robot
from urkin.transforms import check_transform, rotation_angle, rotation_parts, skew, twist_parts

__all__ = ["IK_METHODS", "IKResult", "ik", "orientation_error"]

IK_METHODS = ("nr", "dls", "lm", "poe")


@dataclass
class IKResult:
    """What :func:`ik` found, for one target or (arrays) for a batch.

    Attributes
    ----------
    q : ndarray, shape (6,) or (N, 6)
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
        Iterations over all attempts.
    restarts : int or ndarray
        Restarts from random configurations.
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
    reason: str | list[str] = field(default="")

    def __len__(self) -> int:
        if np.ndim(self.success) == 0:
            raise TypeError("a single IKResult has no length; batched results do")
        return len(self.success)

    def __getitem__(self, index: int) -> IKResult:
        if np.ndim(self.success) == 0:
            raise TypeError("a single IKResult cannot be indexed; batched results can")
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
        return (
            f"IKResult(batch of {len(self)}: {int(np.sum(self.success))} succeeded, "
            f"median iterations {np.median(self.iterations):g})"
        )


def orientation_error(R_current: ArrayLike, R_target: ArrayLike, form: str = "log") -> np.ndarray:
    """Rotation error that turns ``R_current`` towards ``R_target``, in the base frame.

    Parameters
    ----------
    R_current, R_target : array_like, shape (..., 3, 3)
    form : {"log", "cross"}
        ``"log"``: the rotation vector ``φ k`` of ``R_target R_currentᵀ`` (exact).
        ``"cross"``: ``½ Σ_i r_i × t_i`` over the columns ``r_i`` of ``R_current`` and ``t_i``
        of ``R_target``, which equals ``sin(φ) k``: a fair approximation for small errors that
        vanishes at ``φ = π``.

    Returns
    -------
    ndarray, shape (..., 3)

    Examples
    --------
    >>> from urkin.transforms import rot_x
    >>> orientation_error(np.eye(3), rot_x(0.5))
    array([0.5, 0. , 0. ])
    >>> orientation_error(np.eye(3), rot_x(np.pi), form="cross") + 0.0  # blind at 180°
    array([0., 0., 0.])
    """
    if form not in ("log", "cross"):
        raise ValueError(f"orientation error form must be 'log' or 'cross'; got {form!r}")
    Rc = np.asarray(R_current, dtype=float)
    Rt = np.asarray(R_target, dtype=float)
    sin_axis, _, omega = rotation_parts(Rt @ np.swapaxes(Rc, -1, -2))
    return omega if form == "log" else sin_axis


def _rotation_parts_one(R: list[list[float]]) -> tuple[list[float], float, list[float]]:
    """:func:`urkin.transforms.rotation_parts` of one rotation, with Python floats (the hot path
    of a single solve)."""
    (r00, r01, r02), (r10, r11, r12), (r20, r21, r22) = R
    s = [0.5 * (r21 - r12), 0.5 * (r02 - r20), 0.5 * (r10 - r01)]
    sin_theta = math.sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2])
    cos_theta = 0.5 * (r00 + r11 + r22 - 1.0)
    theta = math.atan2(sin_theta, cos_theta)
    if cos_theta < -0.9:  # near π: the rare case, handled by the batched code
        _, _, omega = rotation_parts(np.array(R)[None])
        return s, theta, omega[0].tolist()
    scale = 1.0 + theta * theta / 6.0 if sin_theta < 1e-8 else theta / sin_theta
    return s, theta, [scale * s[0], scale * s[1], scale * s[2]]


# ----------------------------------------------------------------------------- reachability


def _unreachable(robot: Robot, targets: np.ndarray, pose: bool) -> tuple[np.ndarray, list[str]]:
    """Targets no configuration reaches (necessary conditions), and why, per target.

    A pose fixes the point ``c = p − d6 z`` of the flange (the origin of DH frame 5); it lies
    within ``|a2| + |a3| + √(d4² + d5²)`` of the shoulder point ``(0, 0, d1)`` and at least
    ``d4`` from the base axis.  A position alone lies within that reach plus ``d6`` (plus the
    tool's offset).
    """
    T_base_world = np.linalg.inv(robot.base)
    arm = abs(robot.a2) + abs(robot.a3) + float(np.hypot(robot.d4, robot.d5))
    if pose:
        T_base_flange = T_base_world @ targets @ np.linalg.inv(robot.tool)
        points = T_base_flange[:, :3, 3] - robot.d6 * T_base_flange[:, :3, 2]
        reach, what = arm, "its wrist point"
    else:
        points = targets @ T_base_world[:3, :3].T + T_base_world[:3, 3]
        reach = arm + robot.d6 + float(np.linalg.norm(robot.tool[:3, 3]))
        what = "it"
    distance = np.linalg.norm(points - [0.0, 0.0, robot.d1], axis=-1)
    bad = distance > reach + 1e-9
    reasons = [
        f"unreachable: the target is {d - reach:.4f} m beyond the {robot.name}'s reach ({what} "
        f"is {d:.4f} m from the shoulder; at most {reach:.4f} m is reachable)"
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
                f"{robot.d4 - radial[i]:.4f} m closer than the {robot.name}'s shoulder offset "
                f"d4 = {robot.d4:.4f} m allows"
            )
        bad = bad | inner
    return bad, reasons


# ----------------------------------------------------------------------------- the core


class _Problem:
    """Targets, their error measure and the tolerances: what every step rule needs."""

    def __init__(self, robot, positions, rotations, form, tol_position, tol_orientation):
        self.robot = robot
        self.p = positions  # (N, 3)
        self.R = rotations  # (N, 3, 3), or None for position-only targets
        self.form = form
        self.tol_position = tol_position
        self.tol_orientation = tol_orientation
        self.lower = np.array([lo for lo, _ in robot.joint_limits])
        self.upper = np.array([hi for _, hi in robot.joint_limits])
        self.fast = robot._plain  # the generated one-pose functions apply
        self.wide_limits = bool(np.all(self.lower <= -np.pi) and np.all(self.upper >= np.pi))

    # --- forward kinematics, for a batch and for one configuration
    def poses(self, Q: np.ndarray) -> np.ndarray:
        return fk(self.robot, Q)

    def jacobians(self, Q: np.ndarray) -> np.ndarray:
        J = jacobian(self.robot, Q)
        return J if self.R is not None else J[..., :3, :]

    def pose_one(self, q: np.ndarray) -> np.ndarray:
        if self.fast:
            return _gen.t06_one(*q.tolist(), *self.robot.lengths)
        return fk(self.robot, q)

    def jacobian_one(self, q: np.ndarray) -> np.ndarray:
        J = (
            _gen.jacobian_one(*q.tolist(), *self.robot.lengths)
            if self.fast
            else jacobian(self.robot, q)
        )
        return J if self.R is not None else J[:3]

    # --- errors: the vector the steps reduce, and the true position and orientation errors
    def errors(self, T: np.ndarray, rows: np.ndarray):
        e_p = self.p[rows] - T[:, :3, 3]
        position_error = np.sqrt(np.sum(e_p * e_p, axis=-1))
        if self.R is None:
            return e_p, position_error, np.zeros(len(rows))
        sin_axis, theta, omega = rotation_parts(self.R[rows] @ np.swapaxes(T[:, :3, :3], -1, -2))
        e_o = omega if self.form == "log" else sin_axis
        return np.concatenate([e_p, e_o], axis=-1), position_error, theta

    def error_one(self, T: np.ndarray, row: int):
        x, y, z = (self.p[row] - T[:3, 3]).tolist()
        position_error = math.sqrt(x * x + y * y + z * z)
        if self.R is None:
            return np.array((x, y, z)), position_error, 0.0
        sin_axis, theta, omega = _rotation_parts_one((self.R[row] @ T[:3, :3].T).tolist())
        return (
            np.array((x, y, z, *(omega if self.form == "log" else sin_axis))),
            position_error,
            theta,
        )

    def space_twist(self, T: np.ndarray, rows) -> np.ndarray:
        """Modern Robotics' error twist ``V_s = log(T_target T⁻¹)``, as ``(ω, v)``."""
        p, R = T[..., :3, 3], T[..., :3, :3]
        dR = self.R[rows] @ np.swapaxes(R, -1, -2)
        dp = self.p[rows] - (dR @ p[..., None])[..., 0]
        return twist_parts(dR, dp)

    def wrap(self, q: np.ndarray) -> np.ndarray:
        wrapped = (q + np.pi) % (2.0 * np.pi) - np.pi
        return wrapped if self.wide_limits else np.clip(wrapped, self.lower, self.upper)

    def random_configuration(self, rng: np.random.Generator, count: int | None = None):
        """Uniform joint angles within the limits (and [−π, π)): shape (6,) or (count, 6)."""
        size = None if count is None else (count, len(self.lower))
        return rng.uniform(np.maximum(self.lower, -np.pi), np.minimum(self.upper, np.pi), size)


def _pinv_step(J: np.ndarray, e: np.ndarray) -> np.ndarray:
    return (np.linalg.pinv(J, rcond=1e-12) @ e[..., None])[..., 0]


def _damped_step(J: np.ndarray, e: np.ndarray, damping: float) -> np.ndarray:
    """``Jᵀ (J Jᵀ + λ² I)⁻¹ e``."""
    Jt = np.swapaxes(J, -1, -2)
    A = J @ Jt + damping**2 * np.eye(J.shape[-2])
    return (Jt @ np.linalg.solve(A, e[..., None]))[..., 0]


def _twist_step(problem: _Problem, T: np.ndarray, J: np.ndarray, rows) -> np.ndarray:
    """IKinSpace: ``J_s⁺ V_s``, with the space Jacobian from the geometric one."""
    p = T[..., :3, 3]
    Jw = J[..., 3:, :]
    J_space = np.concatenate([Jw, J[..., :3, :] + skew(p) @ Jw], axis=-2)
    return _pinv_step(J_space, problem.space_twist(T, rows))


def _limited(step: np.ndarray, max_step: float) -> np.ndarray:
    largest = np.max(np.abs(step), axis=-1, keepdims=True)
    return step * np.minimum(1.0, max_step / np.maximum(largest, 1e-300))


#: Levenberg–Marquardt damping: starts at _TAU × max diag(JᵀJ), follows Nielsen's update
#: (μ × max(1/3, 1 − (2ρ − 1)³) after a step that lowers the error by the fraction ρ of what
#: the linear model predicted, μ × ν with ν doubling after one that does not), and an attempt
#: gives up when μ exceeds _MU_GIVE_UP.
_TAU, _MU_GIVE_UP = 1e-2, 1e8
#: An attempt restarts when its error has not fallen below _PROGRESS × its best for _PATIENCE
#: iterations (a local minimum), or after max_iterations in all.
_PROGRESS, _PATIENCE = 0.9, 6


@dataclass
class _Settings:
    method: str
    damping: float
    max_iterations: int
    max_restarts: int
    max_step: float


def _iterate_batch(
    problem: _Problem,
    Q0: np.ndarray,
    candidates: np.ndarray,
    settings: _Settings,
    rng: np.random.Generator,
):
    """The iteration loop over all active targets at once (vectorised over targets)."""
    n = len(Q0)
    q, best_q = Q0.copy(), Q0.copy()
    best = np.full(n, np.inf)
    success = np.zeros(n, dtype=bool)
    iterations = np.zeros(n, dtype=int)
    attempt = np.zeros(n, dtype=int)
    restarts = np.zeros(n, dtype=int)
    mu = np.full(n, np.nan)  # NaN: not yet set for this attempt
    nu = np.full(n, 2.0)
    attempt_best = np.full(n, np.inf)
    since_progress = np.zeros(n, dtype=int)
    active = candidates.copy()
    while np.any(active):
        rows = np.flatnonzero(active)
        T = problem.poses(q[rows])
        e, position_error, rotation_error = problem.errors(T, rows)
        residual = np.maximum(position_error, rotation_error)
        improved = residual < best[rows]
        best[rows[improved]] = residual[improved]
        best_q[rows[improved]] = q[rows[improved]]
        progress = residual < _PROGRESS * attempt_best[rows]
        since_progress[rows] = np.where(progress, 0, since_progress[rows] + 1)
        attempt_best[rows] = np.minimum(attempt_best[rows], residual)
        done = (position_error <= problem.tol_position) & (
            rotation_error <= problem.tol_orientation
        )
        success[rows[done]] = True
        stalled = ~done & (
            (attempt[rows] >= settings.max_iterations)
            | (since_progress[rows] >= _PATIENCE)
            | (mu[rows] >= _MU_GIVE_UP)
        )
        # stalled attempts restart from a random configuration, or give up
        stuck = rows[stalled]
        active[stuck[restarts[stuck] >= settings.max_restarts]] = False
        again = stuck[restarts[stuck] < settings.max_restarts]
        if len(again):
            restarts[again] += 1
            attempt[again], since_progress[again] = 0, 0
            mu[again], nu[again], attempt_best[again] = np.nan, 2.0, np.inf
            q[again] = problem.random_configuration(rng, len(again))
        active[rows[done]] = False
        go = ~done & ~stalled
        if not np.any(go):
            continue
        rows, T, e = rows[go], T[go], e[go]
        J = problem.jacobians(q[rows])
        if settings.method == "lm":  # take the step only if it lowers the error
            Jt = np.swapaxes(J, -1, -2)
            A = Jt @ J
            g = (Jt @ e[..., None])[..., 0]
            m = mu[rows]
            m = np.where(np.isnan(m), _TAU * np.diagonal(A, axis1=-2, axis2=-1).max(axis=-1), m)
            h = np.linalg.solve(A + m[:, None, None] * np.eye(A.shape[-1]), g[..., None])[..., 0]
            h = _limited(h, settings.max_step)
            trial = problem.wrap(q[rows] + h)
            e_trial, _, _ = problem.errors(problem.poses(trial), rows)
            model = e - (J @ h[..., None])[..., 0]
            predicted = np.sum(e * e, axis=-1) - np.sum(model * model, axis=-1)
            actual = np.sum(e * e, axis=-1) - np.sum(e_trial * e_trial, axis=-1)
            rho = np.where(predicted > 0, actual / np.where(predicted > 0, predicted, 1.0), -1.0)
            better = rho > 0
            q[rows[better]] = trial[better]
            shrink = np.maximum(1.0 / 3.0, 1.0 - (2.0 * rho - 1.0) ** 3)
            mu[rows] = np.where(better, m * shrink, m * nu[rows])
            nu[rows] = np.where(better, 2.0, 2.0 * nu[rows])
        else:
            if settings.method == "nr":
                step = _pinv_step(J, e)
            elif settings.method == "dls":
                step = _damped_step(J, e, settings.damping)
            else:
                step = _twist_step(problem, T, J, rows)
            q[rows] = problem.wrap(q[rows] + _limited(step, settings.max_step))
        iterations[rows] += 1
        attempt[rows] += 1
    return best_q, success, iterations, restarts


def _iterate_one(problem: _Problem, q0: np.ndarray, settings: _Settings, rng: np.random.Generator):
    """The same loop for a single target, with scalar bookkeeping (one solve's fast path)."""
    q, best_q, best = q0.copy(), q0.copy(), math.inf
    iterations = attempt = restarts = since_progress = 0
    attempt_best = math.inf
    mu, nu = math.nan, 2.0
    rows = np.zeros(1, dtype=int)
    T = problem.pose_one(q)
    e, position_error, rotation_error = problem.error_one(T, 0)
    while True:
        residual = max(position_error, rotation_error)
        if residual < best:
            best, best_q = residual, q.copy()
        since_progress = 0 if residual < _PROGRESS * attempt_best else since_progress + 1
        attempt_best = min(attempt_best, residual)
        if position_error <= problem.tol_position and rotation_error <= problem.tol_orientation:
            return best_q, True, iterations, restarts
        if attempt >= settings.max_iterations or since_progress >= _PATIENCE or mu >= _MU_GIVE_UP:
            if restarts >= settings.max_restarts:
                return best_q, False, iterations, restarts
            restarts += 1
            attempt, mu, nu, since_progress, attempt_best = 0, math.nan, 2.0, 0, math.inf
            q = problem.random_configuration(rng)
            T = problem.pose_one(q)
            e, position_error, rotation_error = problem.error_one(T, 0)
            continue
        J = problem.jacobian_one(q)
        if settings.method == "lm":
            Jt = J.T
            A = Jt @ J
            g = Jt @ e
            if math.isnan(mu):
                mu = _TAU * float(A.diagonal().max())
            A.flat[:: A.shape[0] + 1] += mu
            step = np.linalg.solve(A, g)
            largest = max(map(abs, step.tolist()))
            if largest > settings.max_step:
                step *= settings.max_step / largest
            trial = problem.wrap(q + step)
            T_trial = problem.pose_one(trial)
            e_trial, p_trial, r_trial = problem.error_one(T_trial, 0)
            # gain ratio: actual reduction of |e|² over the reduction the linear model predicts
            Js = J @ step
            predicted = float(2.0 * (e @ Js) - Js @ Js)
            rho = float(e @ e - e_trial @ e_trial) / predicted if predicted > 0 else -1.0
            if rho > 0:
                q, T, e, position_error, rotation_error = trial, T_trial, e_trial, p_trial, r_trial
                mu *= max(1.0 / 3.0, 1.0 - (2.0 * rho - 1.0) ** 3)
                nu = 2.0
            else:
                mu *= nu
                nu *= 2.0
        else:
            if settings.method == "nr":
                step = _pinv_step(J, e)
            elif settings.method == "dls":
                step = _damped_step(J, e, settings.damping)
            else:
                step = _twist_step(problem, T[None], J[None], rows)[0]
            q = problem.wrap(q + _limited(step, settings.max_step))
            T = problem.pose_one(q)
            e, position_error, rotation_error = problem.error_one(T, 0)
        iterations += 1
        attempt += 1


def ik(
    robot: Robot,
    target: ArrayLike,
    q0: ArrayLike | None = None,
    *,
    method: str = "lm",
    orientation: str = "log",
    tol_position: float = 1e-10,
    tol_orientation: float = 1e-10,
    max_iterations: int = 100,
    max_restarts: int = 20,
    max_step: float = 1.0,
    damping: float = 0.01,
    seed: int = 0,
) -> IKResult:
    """Joint angles that put the tool at a target pose (or position), by iteration.

    Parameters
    ----------
    robot : Robot
    target : array_like, shape (4, 4), (N, 4, 4), (3,) or (N, 3)
        Target poses of the tool (in the robot's base frame), or target positions (metres)
        when only the position matters.
    q0 : array_like, shape (6,) or (N, 6), optional
        Initial guesses (zeros by default); one guess serves every target of a batch.
    method : {"lm", "nr", "dls", "poe"}
        The step rule (see the module documentation).
    orientation : {"log", "cross"}
        The orientation error used in the steps of ``lm``, ``nr`` and ``dls``: the rotation
        vector (exact) or the cross-product approximation of the course reports (blind at
        180°).  Success is always judged by the true angle.
    tol_position, tol_orientation : float
        Tolerances on the final position error (m) and orientation error (rad).
    max_iterations : int
        Iterations per attempt before a restart.  An attempt also restarts earlier when its
        error stops falling (no 10 % improvement in 6 iterations: a local minimum).
    max_restarts : int
        Restarts from random configurations (drawn from ``seed``) before giving up.
    max_step : float
        Largest change of any joint in one step, radians.
    damping : float
        λ of ``dls``.
    seed : int
        Seed of the restarts: a seed reproduces a result exactly.

    Returns
    -------
    IKResult
        For a batch, every field is an array over the targets (index it for one target).

    Raises
    ------
    ValueError
        For malformed input: a wrong shape, NaN, a non-rotation matrix, an unknown method.
        Unreachable targets are not an error: they give ``success=False`` and the reason.

    Examples
    --------
    >>> import urkin
    >>> ur5 = urkin.robot("ur5")
    >>> T = urkin.fk(ur5, [0.3, -1.2, 1.4, -0.6, 1.1, 0.2])
    >>> result = urkin.ik(ur5, T)
    >>> bool(result.success), bool(result.residual < 1e-10)
    (True, True)
    >>> bool(np.allclose(urkin.fk(ur5, result.q), T, atol=1e-9))
    True
    >>> urkin.ik(ur5, [2.0, 0.0, 0.5]).reason
    "unreachable: the target is 0.9977 m beyond the UR5's reach (it is 2.0418 m from the shoulder; at most 1.0440 m is reachable)"
    """  # noqa: E501
    if not isinstance(robot, Robot):
        raise TypeError(f"expected a urkin Robot such as urkin.robot('ur5'); got {robot!r:.40}")
    if method not in IK_METHODS:
        raise ValueError(f"method must be one of {', '.join(IK_METHODS)}; got {method!r}")
    if orientation not in ("log", "cross"):
        raise ValueError(f"orientation must be 'log' or 'cross'; got {orientation!r}")
    goal = np.asarray(target, dtype=float)
    single = goal.shape in ((4, 4), (3,))
    pose = goal.shape[-2:] == (4, 4)
    if not (pose or goal.shape[-1:] == (3,)) or goal.ndim > (3 if pose else 2):
        raise ValueError(
            "target must be a pose (4, 4) or (N, 4, 4), or a position (3,) or (N, 3); "
            f"got shape {goal.shape}"
        )
    if pose:
        goal = check_transform(goal, name="target").reshape(-1, 4, 4)
    else:
        if not np.all(np.isfinite(goal)):
            raise ValueError("target contains NaN or infinity")
        goal = goal.reshape(-1, 3)
    n = len(goal)
    guess = np.zeros(6) if q0 is None else _joints(q0, "q0")[0]
    Q0 = np.broadcast_to(guess, (n, 6)).astype(float) if guess.ndim == 1 else guess.copy()
    if len(Q0) != n:
        raise ValueError(f"q0 holds {len(Q0)} configurations for {n} targets")
    if method == "poe" and not pose:
        raise ValueError("method 'poe' needs full poses (4×4), not positions")

    settings = _Settings(method, damping, max_iterations, max_restarts, max_step)
    if pose:  # iterate on the flange's target with the plain (fast) flange kinematics
        plain = (
            robot
            if robot._plain
            else Robot(robot.name, *robot.lengths, joint_limits=robot.joint_limits)
        )
        flange_goal = (
            goal if robot._plain else np.linalg.inv(robot.base) @ goal @ np.linalg.inv(robot.tool)
        )
        problem = _Problem(
            plain,
            flange_goal[:, :3, 3],
            flange_goal[:, :3, :3],
            orientation,
            tol_position,
            tol_orientation,
        )
    else:  # a position of the tool point, in the world frame: the robot's own kinematics
        problem = _Problem(robot, goal, None, orientation, tol_position, tol_orientation)
    bad, reasons = _unreachable(robot, goal, pose)
    rng = np.random.default_rng(seed)
    if n == 1:
        q, ok, count, again = (
            (Q0[0], False, 0, 0) if bad[0] else _iterate_one(problem, Q0[0], settings, rng)
        )
        q, success = q[None], np.array([ok])
        iterations, restarts = np.array([count]), np.array([again])
    else:
        q, success, iterations, restarts = _iterate_batch(problem, Q0, ~bad, settings, rng)
    # verify with the robot's own forward kinematics, tool and base included
    T = fk(robot, q[0])[None] if n == 1 else fk(robot, q)
    if pose:
        position_error = np.linalg.norm(T[:, :3, 3] - goal[:, :3, 3], axis=-1)
        rotation_error = rotation_angle(T[:, :3, :3], goal[:, :3, :3])
    else:
        position_error = np.linalg.norm(T[:, :3, 3] - goal, axis=-1)
        rotation_error = np.zeros(n)
    success = success & (position_error <= tol_position) & (rotation_error <= tol_orientation)
    for i in range(n):
        if success[i]:
            reasons[i] = "converged"
        elif not reasons[i]:
            reasons[i] = (
                f"did not converge: after {restarts[i]} restarts the closest configuration found "
                f"is {position_error[i]:.2e} m and {rotation_error[i]:.2e} rad from the target"
                + (
                    " (the cross-product error is blind to orientations half a turn away)"
                    if orientation == "cross" and rotation_error[i] > 3.0
                    else ""
                )
            )
    residual = np.maximum(position_error, rotation_error)
    result = IKResult(
        q, success, residual, position_error, rotation_error, iterations, restarts, reasons
    )
    return result[0] if single else result
