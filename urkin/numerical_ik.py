"""Numerical inverse kinematics: one iteration core, step rules plugged into it, any number of
targets.

``urkin.ik(robot, target, q0=None, method="lm")`` finds joint angles ``q`` with
``fk(robot, q) ≈ target``.  The core owns everything the step rules share, with the same rules
for one target (:func:`_iterate_one`, bookkeeping in Python floats on the generated one-pose
kinematics) and for a stack (:func:`_iterate`, every unsolved target a row; a stack of up to
sixteen targets is solved target by target, and a stack's last few unsolved targets are handed to
the single path, each continuing its attempt):

* an error that is re-measured after every step (a step rule may reject a trial step);
* separate tolerances on the position (metres) and the orientation (radians);
* step limiting (no joint moves more than ``max_step`` radians in one step);
* angle wrapping into (−π, π] and the robot's joint limits;
* where an attempt stalls close to a nearly singular solution (micrometres short, the error
  left along the Jacobian's weakest direction falling only at second order), a step along
  that direction fitted to the error (:func:`_singular_steps`), unless ``max_restarts=0``;
* restarts from seeded random configurations when an attempt stalls, or reaches a point where
  the error is orthogonal to every direction the joints can move the tool (a local minimum);
* verification: success is reported only when the pose error of the returned ``q``, measured
  with :func:`urkin.fk` against the target as given, is within both tolerances.

Step rules (``method``, or a :class:`StepRule` object):

``"nr"`` (:class:`NewtonRaphson`)
    ``Δq = J⁺ e``.
``"dls"`` (:class:`DampedLeastSquares`)
    ``Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e`` with a fixed damping ``λ`` (0.01): robust near singularities,
    but only linearly convergent there, which the failure reason says.
``"lm"`` (:class:`LevenbergMarquardt`, default)
    ``Δq = (JᵀJ + μ I)⁻¹ Jᵀ e`` with ``μ`` adapted every iteration from how well the step's
    predicted error reduction matched the actual one (Nielsen's rule): smaller after a good
    step (and at most ``10 |e|²``, so that the last steps converge quadratically), larger —
    and the step rejected — after one that does not lower the error.
``"poe"`` (:class:`MatrixLog`)
    Modern Robotics' ``IKinSpace``: the matrix-log twist error ``V_s = log(T_target T⁻¹)`` and
    ``Δq = J_s⁺ V_s`` with the space Jacobian.

The orientation error of ``nr``, ``dls`` and ``lm`` is the rotation vector
``log(R_target R_currentᵀ)`` (``orientation="log"``, default).  The course reports'
``orientation="cross"``, ``½ Σ r_i × t_i`` over the columns of the current and target
rotations, equals ``sin(φ)·k`` and vanishes at a 180° error: from an orientation exactly half
a turn away it sees no error at all (its blind spot), so it is taught but not the default.

A target is a 4×4 pose, or a position (3-vector, metres) when only the tool position matters.
Targets that cannot be reached are rejected before iterating, with the distance beyond reach.
A target rotation is accepted up to :data:`urkin.transforms.ROTATION_TOLERANCE` from orthonormal;
the iteration aims at the nearest rotation, and when the given one is further from it than
``tol_orientation`` the failure says so rather than blaming convergence.
"""

from __future__ import annotations

import copy
import functools
import math
import sys
from operator import add as _add
from struct import Struct

import numpy as np
from numpy.typing import ArrayLike

from urkin._generated import ur_kinematics as _gen
from urkin._inputs import choice, positive, real
from urkin.ik_result import (
    RIGID_TOLERANCE,
    IKResult,
    nearest_rigid,
    skew_reason,
    stacked,
    unreachable,
    verified,
)
from urkin.kinematics import _joints, fk, flange_pose, jacobian
from urkin.robots import Robot, check_robot, random_configurations
from urkin.transforms import (
    ROTATION_TOLERANCE,
    _is_transform_one,
    check_rotation,
    check_transform,
    rotation_parts,
    se3_log,
    skew,
    wrap_angles,
)

__all__ = [
    "IK_METHODS",
    "DampedLeastSquares",
    "IKResult",
    "LevenbergMarquardt",
    "MatrixLog",
    "NewtonRaphson",
    "StepRule",
    "ik",
    "orientation_error",
]


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
    choice(form, "form", ("log", "cross"))
    Rc = check_rotation(R_current, name="R_current")
    Rt = check_rotation(R_target, name="R_target")
    try:
        relative = Rt @ np.swapaxes(Rc, -1, -2)
    except ValueError:
        raise ValueError(
            "R_current and R_target must be rotations of matching stacks; got shapes "
            f"{Rc.shape} and {Rt.shape}"
        ) from None
    sin_axis, _, omega = rotation_parts(relative, check=False)
    return omega if form == "log" else sin_axis


# ----------------------------------------------------------------------------- the problem


@functools.lru_cache(maxsize=64)
def _limits(joint_limits: tuple[tuple[float, float], ...]) -> tuple[np.ndarray, np.ndarray, bool]:
    """Lower and upper joint limits as arrays, and whether they allow every angle of (−π, π]."""
    lower = np.array([lo for lo, _ in joint_limits])
    upper = np.array([hi for _, hi in joint_limits])
    lower.flags.writeable = upper.flags.writeable = False
    return lower, upper, bool(np.all(lower <= -np.pi) and np.all(upper >= np.pi))


def _into_limits(wrapped: np.ndarray, lower: np.ndarray, upper: np.ndarray) -> np.ndarray:
    """Angles wrapped into (−π, π] (..., 6) moved into the joint limits: kept where they are
    inside, else the whole turn of them inside the limits (a joint allowed 2 … 6 rad turns to
    4 rad, not −2.28), else clipped to the limits (an angle in a gap of a joint that turns less
    than a full turn)."""
    inside = (wrapped >= lower) & (wrapped <= upper)
    if inside.all():
        return wrapped
    turned = wrapped + (2.0 * np.pi) * np.ceil((lower - wrapped) / (2.0 * np.pi))
    return np.where(
        inside, wrapped, np.where(turned <= upper, turned, np.clip(wrapped, lower, upper))
    )


def _into_limit(x: float, lo: float, hi: float) -> float:
    """:func:`_into_limits` of one float angle, with the same operations."""
    if lo <= x <= hi:
        return x
    turned = x + (2.0 * math.pi) * math.ceil((lo - x) / (2.0 * math.pi))
    return turned if turned <= hi else min(max(x, lo), hi)


class _Problem:
    """The targets (flange poses or tool positions), their error and the robot's kinematics."""

    def __init__(self, robot, positions, rotations, form, tol_position, tol_orientation, lever=0.0):
        self.robot = robot
        # the distance from the flange to the tool point, when the targets are flange poses of
        # an arm with a tool: its position then misses by at most the flange's position error
        # plus lever × the rotation error, which the convergence test bounds (verified() judges
        # the tool's pose)
        self.lever = lever
        self.p = positions  # (N, 3)
        self.R = rotations  # (N, 3, 3), or None for position-only targets
        self.form = form
        self.tol_position = tol_position
        self.tol_orientation = tol_orientation
        self.lower, self.upper, self.wide_limits = _limits(robot.joint_limits)
        # the first target as floats, for the single-target path: position, rotation row by row
        self.position_one = positions[0].tolist() if len(positions) else None
        self.rotation_one = (
            None if rotations is None or not len(rotations) else rotations[0].ravel().tolist()
        )

    def row(self, i: int) -> _Problem:
        """The problem of target ``i`` alone (for the single-target path)."""
        return _Problem(
            self.robot,
            self.p[i : i + 1],
            None if self.R is None else self.R[i : i + 1],
            self.form,
            self.tol_position,
            self.tol_orientation,
            self.lever,
        )

    def evaluate(self, Q: np.ndarray, rows: np.ndarray):
        """Poses of ``Q`` (k, 6) and their errors against the targets ``rows``: ``(T, e,
        position error, orientation error)``."""
        T = fk(self.robot, Q)
        e_p = self.p[rows] - T[:, :3, 3]
        position_error = np.sqrt(np.sum(e_p * e_p, axis=-1))
        if self.R is None:
            return T, e_p, position_error, np.zeros(len(rows))
        sin_axis, theta, omega = rotation_parts(
            self.R[rows] @ np.swapaxes(T[:, :3, :3], -1, -2), check=False
        )
        e_o = omega if self.form == "log" else sin_axis
        return T, np.concatenate([e_p, e_o], axis=-1), position_error, theta

    def errors(self, Q: np.ndarray, rows: np.ndarray) -> np.ndarray:
        """The errors ``e`` (k, m) of :meth:`evaluate` alone; one configuration of a single
        target's problem by :meth:`evaluate_one` (a fifth of the stacked path's cost)."""
        if len(Q) == 1 and len(self.p) == 1:
            J, e = np.empty((6, 6)), np.empty((1, 3 if self.R is None else 6))
            self.evaluate_one(Q[0].tolist(), J, e[0])
            return e
        return self.evaluate(Q, rows)[1]

    def evaluate_one(self, q: list[float], J: np.ndarray, error: np.ndarray):
        """:meth:`evaluate` for one configuration (six floats) against the only target, with
        its Jacobian: the pose's top three rows as a tuple of 12 floats, ``e`` (m,), the two
        errors as floats, ``J`` (m, 6) and ``|e|²`` as a float; ``J`` and ``e`` are written
        into the arrays given, ``J`` (6, 6) and ``error`` (m,).  The plain kinematics give the
        pose and the Jacobian from one generated function (they share every cosine and sine)."""
        robot = self.robot
        if robot._plain:
            pose = _gen.pose_jacobian_one(q, robot.lengths, J)
        else:
            array = np.array(q)
            pose = tuple(fk(robot, array)[:3].ravel().tolist())
            J[...] = jacobian(robot, array)
        a, b, c, x, d, e, f, y, g, h, i, z = pose
        tx, ty, tz = self.position_one
        x, y, z = tx - x, ty - y, tz - z
        squares = x * x + y * y + z * z
        position_error = math.sqrt(squares)
        if self.R is None:
            _pack3(error, 0, x, y, z)
            return pose, error, position_error, 0.0, J[:3], squares
        t0, t1, t2, t3, t4, t5, t6, t7, t8 = self.rotation_one
        sin_axis, theta, omega = _rotation_parts_one(  # of R_target R_currentᵀ
            t0 * a + t1 * b + t2 * c,
            t0 * d + t1 * e + t2 * f,
            t0 * g + t1 * h + t2 * i,
            t3 * a + t4 * b + t5 * c,
            t3 * d + t4 * e + t5 * f,
            t3 * g + t4 * h + t5 * i,
            t6 * a + t7 * b + t8 * c,
            t6 * d + t7 * e + t8 * f,
            t6 * g + t7 * h + t8 * i,
        )
        u, v, w = omega if self.form == "log" else sin_axis
        squares += u * u + v * v + w * w
        _pack6(error, 0, x, y, z, u, v, w)
        return pose, error, position_error, theta, J, squares

    def jacobians(self, Q: np.ndarray) -> np.ndarray:
        J = jacobian(self.robot, Q)
        return J if self.R is not None else J[..., :3, :]

    def wrap(self, q: np.ndarray) -> np.ndarray:
        wrapped = wrap_angles(q, check=False)
        return wrapped if self.wide_limits else _into_limits(wrapped, self.lower, self.upper)

    def wrap_one(self, q: list[float]) -> list[float]:
        """:meth:`wrap` of one configuration given as six floats, to the same bits."""
        if not (-math.pi < min(q) and max(q) <= math.pi):
            q = [_wrap_float(x) for x in q]
        if self.wide_limits:
            return q
        return [_into_limit(x, lo, hi) for (lo, hi), x in zip(self.robot.joint_limits, q)]


_pack3, _pack6 = Struct("3d").pack_into, Struct("6d").pack_into


def _wrap_float(x: float) -> float:
    """:func:`urkin.transforms.wrap_angles` of one float, with the same operations (so the
    single and the stacked paths wrap to the same bits)."""
    y = x - math.ceil((x - math.pi) / (2.0 * math.pi)) * (2.0 * math.pi)
    return y - 2.0 * math.pi if y > math.pi else y


def _rotation_parts_one(
    r00: float,
    r01: float,
    r02: float,
    r10: float,
    r11: float,
    r12: float,
    r20: float,
    r21: float,
    r22: float,
) -> tuple[tuple[float, ...], float, tuple[float, ...]]:
    """:func:`urkin.transforms.rotation_parts` of one rotation given as its nine entries (row
    by row), with Python floats (the hot path of a single solve)."""
    s0, s1, s2 = 0.5 * (r21 - r12), 0.5 * (r02 - r20), 0.5 * (r10 - r01)
    sin_theta = math.sqrt(s0 * s0 + s1 * s1 + s2 * s2)
    cos_theta = 0.5 * (r00 + r11 + r22 - 1.0)
    theta = math.atan2(sin_theta, cos_theta)
    if cos_theta < -0.9:  # near π: the axis from the symmetric part, as rotation_parts does
        b0, b1, b2 = r00 - cos_theta, r11 - cos_theta, r22 - cos_theta
        if b0 >= b1 and b0 >= b2:
            k = (b0, 0.5 * (r10 + r01), 0.5 * (r20 + r02))
        elif b1 >= b2:
            k = (0.5 * (r01 + r10), b1, 0.5 * (r21 + r12))
        else:
            k = (0.5 * (r02 + r20), 0.5 * (r12 + r21), b2)
        norm = math.sqrt(k[0] * k[0] + k[1] * k[1] + k[2] * k[2])
        scale = theta / norm if k[0] * s0 + k[1] * s1 + k[2] * s2 >= 0.0 else -theta / norm
        return (s0, s1, s2), theta, (scale * k[0], scale * k[1], scale * k[2])
    scale = 1.0 + theta * theta / 6.0 if sin_theta < 1e-8 else theta / sin_theta
    return (s0, s1, s2), theta, (scale * s0, scale * s1, scale * s2)


# ----------------------------------------------------------------------------- step rules


class StepRule:
    """How one iteration moves the joints; the core (:func:`_iterate`) does the rest.

    A rule sees the rows of the stack it is asked to step (``rows``, indices of targets), their
    current poses ``T`` (k, 4, 4), Jacobians ``J`` (k, m, 6) and errors ``e`` (k, m), and
    returns the joint steps (k, 6).  Rules that keep state per target (a damping) allocate it in
    :meth:`start` and reset it in :meth:`restart`; rules that may reject a trial step say so in
    :meth:`accept`; :meth:`given_up` lets a rule end an attempt early.  On the single-target
    path ``J`` and ``e`` live in arrays that are written again at later iterations: a rule
    copies what it keeps.

    Attributes
    ----------
    name : str
        The ``method`` name.
    max_step : float
        Default largest change of any joint in one step (radians; ``inf``: no limit).
    patience : int
        An attempt restarts when its error has not fallen below 99 % of its best for this many
        iterations.
    uses_pose : bool
        Whether :meth:`step` reads ``T``; the single-target path, which works on Python floats,
        builds the (4, 4) array only for rules that do, and passes None to the others.
    """

    name = ""
    max_step = 1.0
    patience = 6
    uses_pose = False

    def start(self, n: int) -> None:
        """Per-target state for a stack of ``n`` targets (none by default); ``start(1)`` also
        begins an attempt on the single-target path."""

    def restart(self, rows: np.ndarray) -> None:
        """A new attempt begins for these targets (nothing to reset by default)."""

    def for_row(self, row: int) -> StepRule:
        """This rule for target ``row`` alone, its attempt's state kept: how a stack hands a
        target to the single path.  Rules with per-target state override it to keep that
        state; the default gives a copy with the state of a new attempt."""
        one = copy.copy(self)
        one.start(1)
        return one

    def step(self, problem: _Problem, rows, T, J, e) -> np.ndarray:
        raise NotImplementedError

    def accept(self, rows, e, e_trial, J, dq) -> np.ndarray:
        """Which trial steps to keep (all, by default)."""
        return np.ones(np.shape(rows), dtype=bool)

    def accept_one(self, e, e_trial, J, dq, squares: float, squares_trial: float) -> bool:
        """:meth:`accept` on the single-target path, given also ``|e|²`` and ``|e_trial|²``
        as floats (the default asks :meth:`accept`)."""
        return bool(self.accept(0, e, e_trial, J, dq))

    def given_up(self, rows: np.ndarray) -> np.ndarray | bool:
        return False

    def given_up_one(self) -> bool:
        """:meth:`given_up` on the single-target path (after :meth:`start` ``(1)``)."""
        return False

    def stall_reason(self) -> str:
        """What to add to the failure reason when attempts stall (nothing by default)."""
        return ""

    def __repr__(self) -> str:
        return f"{type(self).__name__}()"


def _pinv_step(J: np.ndarray, e: np.ndarray) -> np.ndarray:
    return (np.linalg.pinv(J, rcond=1e-12) @ e[..., None])[..., 0]


try:  # numpy's solver without its wrapper's checks: 1 µs for a 6×6 system instead of 5.5
    from numpy.linalg._umath_linalg import solve1 as _solve1
except ImportError:  # pragma: no cover - a numpy without the private module
    _solve1 = np.linalg.solve


def _solve_positive_definite(A: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, list[float]]:
    """``A⁻¹ b`` for one symmetric positive definite ``A`` (LM's ``JᵀJ + μI``, μ > 0), which
    LU solves without the singular-matrix checks :func:`numpy.linalg.solve` makes first; a
    non-finite result (which positive definiteness rules out) falls back to it.  Also the
    solution as a list of floats."""
    x = _solve1(A, b)
    values = x.tolist()
    total = sum(values)
    if total - total == 0.0:
        return x, values
    x = np.linalg.solve(A, b)
    return x, x.tolist()


class NewtonRaphson(StepRule):
    """``Δq = J⁺ e`` (pseudo-inverse: least squares, minimum norm)."""

    name = "nr"

    def step(self, problem, rows, T, J, e):
        return _pinv_step(J, e)


#: The largest damping ``dls`` takes.
_MAX_DAMPING = 1e6


class DampedLeastSquares(StepRule):
    """``Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e`` with a fixed damping ``λ``.

    A fixed damping bounds the step near singularities but slows convergence there: each
    iteration shrinks the error along a singular direction with singular value σ only by
    ``λ² / (σ² + λ²)``; a failure says so.
    """

    name = "dls"

    def __init__(self, damping: float = 0.01) -> None:
        self.damping = float(positive(damping, "damping", zero_ok=True))
        if self.damping > 0.0 and self.damping * self.damping < sys.float_info.min:
            raise ValueError(
                f"damping must be 0 (undamped) or at least {math.sqrt(sys.float_info.min):.3g}: "
                f"λ² = {self.damping * self.damping:g} underflows; got {damping!r}"
            )
        if self.damping > _MAX_DAMPING:
            raise ValueError(
                f"damping must be at most {_MAX_DAMPING:g} (λ² is added to JJᵀ, whose entries "
                f"are about 1: a larger λ leaves steps of nothing); got {damping!r}"
            )

    def step(self, problem, rows, T, J, e):
        Jt = np.swapaxes(J, -1, -2)
        if self.damping == 0.0:  # undamped: the least-squares step, defined at a singularity too
            return _pinv_step(J, e)
        A = J @ Jt + self.damping**2 * np.eye(J.shape[-2])
        return (Jt @ np.linalg.solve(A, e[..., None]))[..., 0]

    def stall_reason(self):
        return (
            f" (damped least squares with a fixed λ = {self.damping:g} converges only linearly "
            "near a singularity: method='lm' adapts the damping)"
        )

    def __repr__(self):
        return f"DampedLeastSquares(damping={self.damping:g})"


#: Levenberg–Marquardt damping: starts at _TAU × max diag(JᵀJ), follows Nielsen's update
#: (μ × max(1/3, 1 − (2ρ − 1)³) after a step that lowers the error by the fraction ρ of what
#: the linear model predicted, μ × ν with ν doubling after one that does not), and an attempt
#: gives up when μ exceeds _MU_GIVE_UP.  After a good step μ is also kept at most
#: _ERROR_DAMPING × |e|² (the new error's), as in Yamashita and Fukushima's μ = |e|²: near a
#: solution the damping then vanishes with the error and the last steps converge
#: quadratically (Nielsen's rule alone shrinks μ by at most a third per step, and the error
#: fell only about a hundredfold per step there).  Far away |e|² ≳ 1 and the cap is not met.
#: Measured on 2,000 random UR5 targets from q0 = 0 and from random q0 (bench/ik.py's kind):
#: 17.7 and 16.6 iterations per solve instead of 18.6 and 17.7, every target solved, as
#: before; with the factor 1 about the same, with 0.1 and less more iterations than without.
#: The cap stops at _MU_FLOOR: at a singular solution (the wrist's, q5 = 0) JᵀJ + μI must
#: stay solvable when the error vanishes.  _TAU = 0.03 took 4 % fewer iterations than 0.01 on
#: three seeded sets of 2,000 targets (0.003 and 0.3 more).
_TAU, _MU_GIVE_UP, _ERROR_DAMPING, _MU_FLOOR = 3e-2, 1e8, 10.0, 1e-12
_DIAGONAL = np.arange(6)


class LevenbergMarquardt(StepRule):
    """``Δq = (JᵀJ + μ I)⁻¹ Jᵀ e`` with μ adapted by Nielsen's rule (see the module notes).

    Steps are limited to 1.5 rad per joint (the damping already shortens poor steps; measured
    on 2,000 random UR5 targets from q0 = 0, 15.3 iterations per solve instead of 16.4 with
    1 rad, 18.2 with 0.7, and about 15.3 with 2, 3 or no limit, with more restarts)."""

    name = "lm"
    max_step = 1.5

    def start(self, n):
        self.mu_one, self.nu_one = math.nan, 2.0  # NaN: not yet set for this attempt
        if n > 1:  # the same per target of a stack (start(1) begins a single-target attempt)
            self.mu = np.full(n, np.nan)
            self.nu = np.full(n, 2.0)
        if "gram" not in self.__dict__:  # scratch: JᵀJ + μI of one target, and its diagonal
            self.gram = np.empty((6, 6))
            self.gram_diagonal = self.gram.reshape(36)[::7]

    def restart(self, rows):
        self.mu[rows], self.nu[rows] = np.nan, 2.0

    def for_row(self, row):
        one = copy.copy(self)
        one.__dict__.pop("gram", None)  # its own scratch (start makes it)
        one.start(1)
        one.mu_one, one.nu_one = float(self.mu[row]), float(self.nu[row])
        return one

    def step(self, problem, rows, T, J, e):
        if J.ndim == 2:  # one target (rows is its index): the same step, fewer numpy calls
            Jt = J.T
            A = Jt.dot(J, out=self.gram)  # ndarray.dot: half the @ operator's overhead on 6×6
            mu = self.mu_one
            if mu != mu:  # NaN: a new attempt
                mu = self.mu_one = _TAU * max(self.gram_diagonal.tolist())
            self.gram_diagonal += mu
            g = Jt.dot(e)
            if mu > 0:
                dq, values = _solve_positive_definite(A, g)
            else:
                dq = np.linalg.solve(A, g)
                values = dq.tolist()
            self.last_step = (dq, g, mu, values)  # for accept's predicted reduction
            return dq
        Jt = np.swapaxes(J, -1, -2)
        A = Jt @ J
        g = (Jt @ e[..., None])[..., 0]
        mu = self.mu[rows]
        fresh = np.isnan(mu)
        if np.any(fresh):
            mu = np.where(fresh, _TAU * np.diagonal(A, axis1=-2, axis2=-1).max(axis=-1), mu)
            self.mu[rows] = mu
        A[..., _DIAGONAL, _DIAGONAL] += np.asarray(mu)[..., None]
        return np.linalg.solve(A, g[..., None])[..., 0]

    def accept_one(self, e, e_trial, J, dq, squares, squares_trial):
        # the gain ratio of accept, in floats
        step, g, mu, values = self.last_step
        if dq is step:  # not shortened: (JᵀJ + μI) Δq = g gives |JΔq|² = Δq·g − μ|Δq|²
            # 2 Δq·g − |JΔq|² = Δq·(g + μΔq), in floats (half the two dot products' cost)
            a, b, c, d, f, h = values
            g0, g1, g2, g3, g4, g5 = g.tolist()
            predicted = (
                a * (g0 + mu * a)
                + b * (g1 + mu * b)
                + c * (g2 + mu * c)
                + d * (g3 + mu * d)
                + f * (g4 + mu * f)
                + h * (g5 + mu * h)
            )
        else:
            Jdq = J.dot(dq)
            predicted = float(Jdq.dot(e + e - Jdq))
        rho = (squares - squares_trial) / predicted if predicted > 0 else -1.0
        if rho > 0:
            self.mu_one = min(
                self.mu_one * max(1.0 / 3.0, 1.0 - (2.0 * rho - 1.0) ** 3),
                max(_ERROR_DAMPING * squares_trial, _MU_FLOOR),
            )
            self.nu_one = 2.0
        else:
            self.mu_one *= self.nu_one
            self.nu_one *= 2.0
        return rho > 0

    def accept(self, rows, e, e_trial, J, dq):
        # gain ratio: actual reduction of |e|² over the reduction the linear model predicts
        Jdq = (J @ dq[..., None])[..., 0]
        predicted = np.sum(Jdq * (2.0 * e - Jdq), axis=-1)
        squares_trial = np.sum(e_trial * e_trial, axis=-1)
        actual = np.sum(e * e, axis=-1) - squares_trial
        rho = np.where(predicted > 0, actual / np.where(predicted > 0, predicted, 1.0), -1.0)
        better = rho > 0
        shrink = np.maximum(1.0 / 3.0, 1.0 - (2.0 * rho - 1.0) ** 3)
        mu, nu = self.mu[rows], self.nu[rows]
        lowered = np.minimum(mu * shrink, np.maximum(_ERROR_DAMPING * squares_trial, _MU_FLOOR))
        self.mu[rows] = np.where(better, lowered, mu * nu)
        self.nu[rows] = np.where(better, 2.0, 2.0 * nu)
        return better

    def given_up(self, rows):
        return self.mu[rows] >= _MU_GIVE_UP

    def given_up_one(self):
        return self.mu_one >= _MU_GIVE_UP


class MatrixLog(StepRule):
    """Modern Robotics' ``IKinSpace``: ``Δq = J_s⁺ V_s``, ``V_s = log(T_target T⁻¹)``.

    Modern Robotics takes full steps; pass ``max_step=math.inf`` to :func:`urkin.ik` for its
    exact iteration (the default keeps the 1 rad limit of the other rules)."""

    name = "poe"
    uses_pose = True

    def step(self, problem, rows, T, J, e):
        p, R = T[..., :3, 3], T[..., :3, :3]
        Jw = J[..., 3:, :]
        J_space = np.concatenate([Jw, J[..., :3, :] + skew(p) @ Jw], axis=-2)
        T_error = np.zeros_like(T)  # T_target T⁻¹: the error twist in the space frame
        T_error[..., :3, :3] = dR = problem.R[rows] @ np.swapaxes(R, -1, -2)
        T_error[..., :3, 3] = problem.p[rows] - (dR @ p[..., None])[..., 0]
        T_error[..., 3, 3] = 1.0
        return _pinv_step(J_space, se3_log(T_error, check=False))


#: The step rules by ``method`` name.
IK_METHODS = ("lm", "nr", "dls", "poe")


def _rule(method: str | StepRule, damping: float) -> StepRule:
    if isinstance(method, StepRule):
        return method
    if isinstance(method, type) and issubclass(method, StepRule):
        raise TypeError(
            f"method must be a StepRule object, not the class: pass {method.__name__}() "
            f"instead of {method.__name__}"
        )
    if not isinstance(method, str):
        raise TypeError(
            f"method must be one of {', '.join(IK_METHODS)} or a StepRule; got "
            f"{type(method).__name__}"
        )
    if method == "lm":
        return LevenbergMarquardt()
    if method == "nr":
        return NewtonRaphson()
    if method == "dls":
        return DampedLeastSquares(damping)
    if method == "poe":
        return MatrixLog()
    raise ValueError(f"method must be one of {', '.join(IK_METHODS)} or a StepRule; got {method!r}")


# ----------------------------------------------------------------------------- the core

#: An attempt restarts when its error has not fallen below _PROGRESS × its best for the rule's
#: patience (a local minimum), or after max_iterations in all.  Progress means 1 %: near a
#: nearly singular solution LM's damped steps gain only a few per cent per iteration, and a
#: 10 % rule restarted them there (178 unsolved in 1e6 random UR5 poses; 70 with 1 %).
_PROGRESS = 0.99


def _limited(step: np.ndarray, max_step: float) -> np.ndarray:
    if max_step == math.inf:
        return step
    largest = np.max(np.abs(step), axis=-1, keepdims=True)
    return step * np.minimum(1.0, max_step / np.maximum(largest, 1e-300))


#: An attempt also ends when its error has not fallen by 1 % at the last step and the error
#: is nearly orthogonal to every direction the joints can move the tool,
#: ``|Jᵀe| < _STATIONARY · |J|_F · |e|``: a stationary point of ``|e|²`` that is not a
#: solution (a local minimum).  Converging to a solution the ratio stays near 0.1 or more;
#: into a local minimum it falls about tenfold per step while the error stays put, and waiting
#: for the patience spent some six more iterations there.  Only above _SINGULAR_BELOW: closer,
#: the error of a nearly singular solution lies along the Jacobian's weakest direction, and a
#: slow approach there looks alike (without restarts it would end; with them, the stall gets
#: its step along that direction after the patience).  And only when a restart is left: the
#: last attempt (the only one with ``max_restarts=0``) waits for its patience, as an attempt
#: that crawls out of a flat stretch needs (with no restarts, 10 of lesson 06's 500 LM solves
#: from home did, that the test would have ended).  Measured on 2,000 random UR5
#: targets from q0 = 0 and from random q0: 16.4 and 15.4 iterations per solve instead of
#: 17.7 and 16.6, every target solved (0.03 saves a little more, in more restarts).
_STATIONARY = 1e-2


def _stationary(J: np.ndarray, e: np.ndarray, squares):
    """Whether the errors ``e`` (m,) or (k, m) are nearly orthogonal to the ranges of their
    Jacobians ``J`` (m, 6) or (k, m, 6) (``squares``: ``|e|²``, a float or (k,))."""
    if J.ndim == 2:  # one target: the same test, fewer numpy calls
        g = e.dot(J)
        flat = J.ravel()
        return float(g.dot(g)) < _STATIONARY**2 * float(flat.dot(flat)) * squares
    g = (e[:, None, :] @ J)[:, 0]
    return np.sum(g * g, axis=-1) < _STATIONARY**2 * np.sum(J * J, axis=(1, 2)) * squares


def _stalled(attempt, since_progress, given_up, patience: int, max_iterations: int):
    """When an attempt ends without success (for one target or, elementwise, many)."""
    return (attempt >= max_iterations) | (since_progress >= patience) | given_up


#: An attempt that stalls (or runs out of iterations) with a residual below _SINGULAR_BELOW
#: (metres and radians) tries a step along the Jacobian's weakest direction
#: (:func:`_singular_steps`) before it restarts, if it is its first or the attempt's best has
#: improved since the last (by _PROGRESS); the step is taken, as one iteration, if its
#: residual is below _SINGULAR_BELOW too (the damped steps after it put back what it changed
#: in the other directions).
_SINGULAR_BELOW = 1e-3


def _singular_steps(problem, rows, Q: np.ndarray, J: np.ndarray, e: np.ndarray) -> np.ndarray:
    """Trial configurations for attempts stalled at ``Q`` (k, 6), with Jacobians ``J`` (k, m, 6)
    and errors ``e`` (k, m) against the targets ``rows``, near a solution where ``J`` is nearly
    singular (the wrist point micrometres from the shoulder axis, say).

    Along the right singular vector ``v`` of the smallest singular value σ, the error's
    component along the left one, ``a(t) = u · e(q + t v)``, is ``a0 + a1 t + a2 t²`` with
    ``|a1| ≈ σ``: the step that removes it is large (``a0 / σ``, or ``√|a0 / a2|`` where σ
    vanishes), and moving that far changes the other components at second order, far more
    than the error left, so a damped step declines it and stalls.  Here the quadratic is
    fitted from the errors at ``q ± s v`` (``s = √|a0|``, and once more at ``s = |t|`` when
    its root ``t`` lies beyond ``2s``), the configuration moves to its root nearest 0 (to its
    vertex when it has none; at most 1 rad), and :data:`_CORRECTIONS` least-squares steps in
    the other directions (σ left out) put back what the move changed there.  The caller keeps
    a trial within _SINGULAR_BELOW of its target, as one iteration."""
    m = J.shape[-2]
    U, S, Vt = np.linalg.svd(J)
    u, v = U[..., m - 1], Vt[..., m - 1, :]  # (k, m), (k, 6)
    a0 = np.einsum("km,km->k", u, e)
    s = np.clip(np.sqrt(np.abs(a0)), 1e-9, 0.1)
    t = _quadratic_root(problem, rows, Q, u, v, a0, s)
    far = np.abs(t) > 2.0 * s  # far beyond the probes: fitted again where it landed
    if far.any():
        t[far] = _quadratic_root(
            problem, rows[far], Q[far], u[far], v[far], a0[far], np.abs(t[far])
        )
    Q = problem.wrap(Q + t[:, None] * v)
    for _ in range(_CORRECTIONS):
        e = problem.errors(Q, rows)
        U, S, Vt = np.linalg.svd(problem.jacobians(Q))
        kept = S[..., : m - 1]
        steps = np.einsum("kmi,km->ki", U[..., : m - 1], e) / np.maximum(kept, 1e-300)
        Q = problem.wrap(Q + np.einsum("ki,kij->kj", steps, Vt[..., : m - 1, :]))
    return Q


def _quadratic_root(problem, rows, Q, u, v, a0, s) -> np.ndarray:
    """The root nearest 0 of ``a0 + a1 t + a2 t²`` fitted to ``u · e(Q + t v)`` at ``t = ±s``
    (its vertex where it has none; within ±1 rad): :func:`_singular_steps`' move."""
    plus = np.einsum("km,km->k", u, problem.errors(Q + s[:, None] * v, rows))
    minus = np.einsum("km,km->k", u, problem.errors(Q - s[:, None] * v, rows))
    a1 = (plus - minus) / (2.0 * s)
    a2 = (plus + minus - 2.0 * a0) / (2.0 * s * s)
    disc = a1 * a1 - 4.0 * a2 * a0
    root = np.sqrt(np.maximum(disc, 0.0))
    below = -a1 - np.where(a1 >= 0.0, root, -root)  # no cancellation: |below| ≥ |a1|
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(disc >= 0.0, 2.0 * a0 / below, -a1 / (2.0 * a2))
    return np.where(np.isfinite(t), np.clip(t, -1.0, 1.0), 0.0)


#: Least-squares steps after a move along the weakest direction (:func:`_singular_steps`).
_CORRECTIONS = 2


def _iterate_one(
    problem,
    rule,
    q0,
    *,
    max_iterations,
    max_restarts,
    max_step,
    seed,
    singular_steps=True,
    attempt_state=None,
):
    """:func:`_iterate` for one target, with the bookkeeping in Python floats: the same rules
    (called on unstacked arrays) and the same stall and restart policy.  Returns the best
    configuration, whether it met the tolerances, the iterations and restarts used and the
    best residual.

    ``attempt_state`` — ``(iterations in this attempt, iterations since progress, the
    attempt's best residual, that best at its last step along the weakest direction)`` with
    ``rule`` already holding the attempt's state — continues an attempt begun in a stack
    instead of starting one."""
    rng = None  # made at the first restart: most solves need none
    q = best_q = q0.tolist()  # the configuration as six floats; a new list at each change
    best = math.inf
    iterations = restarts = 0
    if attempt_state is None:
        rule.start(1)
        attempt, since_progress, attempt_best, singular_best = 0, 0, math.inf, math.inf
    else:
        attempt, since_progress, attempt_best, singular_best = attempt_state
    tol_position, tol_orientation, lever = (
        problem.tol_position,
        problem.tol_orientation,
        problem.lever,
    )
    patience, limit_steps, uses_pose = rule.patience, max_step != math.inf, rule.uses_pose
    # J and e of the current configuration and of the trial, in two pairs of arrays that
    # swap roles when a trial is accepted (a rule must not keep them across iterations)
    m = 3 if problem.R is None else 6
    current, spare = (np.empty((6, 6)), np.empty(m)), (np.empty((6, 6)), np.empty(m))
    # the calls of every iteration, looked up once
    evaluate_one, wrap_one, progress = problem.evaluate_one, problem.wrap_one, _PROGRESS
    step, accept_one, given_up_one = rule.step, rule.accept_one, rule.given_up_one
    pose, e, pos, rot, J, squares = evaluate_one(q, *current)
    while True:
        residual = pos if pos > rot else rot
        if residual < best:
            best, best_q = residual, q
        if residual < progress * attempt_best:
            since_progress = 0
        else:
            since_progress += 1
        if residual < attempt_best:
            attempt_best = residual
        if pos + lever * rot <= tol_position and rot <= tol_orientation:
            return np.array(best_q), True, iterations, restarts, best
        if (
            attempt >= max_iterations
            or since_progress >= patience
            or given_up_one()
            or (
                since_progress
                and restarts < max_restarts
                and residual >= _SINGULAR_BELOW
                and _stationary(J, e, squares)
            )
        ):
            if (
                singular_steps
                and residual < _SINGULAR_BELOW
                and attempt_best < _PROGRESS * singular_best
            ):
                singular_best = attempt_best
                rows = np.zeros(1, dtype=np.intp)
                trial = _singular_steps(problem, rows, np.array([q]), J[None], e[None])[0]
                evaluated = evaluate_one(trial.tolist(), *spare)
                if max(evaluated[2], evaluated[3]) < _SINGULAR_BELOW:
                    q, (pose, e, pos, rot, J, squares) = trial.tolist(), evaluated
                    current, spare = spare, current
                    since_progress = 0
                    rule.start(1)
                    iterations += 1
                    attempt += 1
                    continue
            if restarts >= max_restarts:
                return np.array(best_q), False, iterations, restarts, best
            restarts += 1
            attempt, since_progress, attempt_best, singular_best = 0, 0, math.inf, math.inf
            rule.start(1)
            rng = np.random.default_rng(seed) if rng is None else rng
            q = random_configurations(problem.robot, (), rng).tolist()
            pose, e, pos, rot, J, squares = evaluate_one(q, *current)
            continue
        T = np.array((*pose, 0.0, 0.0, 0.0, 1.0)).reshape(4, 4) if uses_pose else None
        dq = step(problem, 0, T, J, e)
        steps = dq.tolist()
        if limit_steps:
            largest = max(max(steps), -min(steps))
            if largest > max_step:
                dq = dq * (max_step / largest)
                steps = dq.tolist()
        trial = wrap_one(list(map(_add, q, steps)))
        evaluated = evaluate_one(trial, *spare)
        if accept_one(e, evaluated[1], J, dq, squares, evaluated[5]):
            q, (pose, e, pos, rot, J, squares) = trial, evaluated
            current, spare = spare, current
        iterations += 1
        attempt += 1


#: When this few targets are still unsolved, each goes on alone on the single-target path: a
#: pass of the stacked loop costs about sixteen single iterations whatever the number of rows
#: (bench/ik.py's batch-size table: with 8, a stack of 9 cost 1.2× single solves per target).
_HAND_OFF = 16


def _iterate(
    problem,
    rule,
    Q0,
    candidates,
    *,
    max_iterations,
    max_restarts,
    max_step,
    seed,
    singular_steps=True,
):
    """The iteration loop over every unsolved target at once: returns the best configuration
    of each target, whether it met the tolerances, and the iterations and restarts used.

    Once at most :data:`_HAND_OFF` targets are left, each is handed to :func:`_iterate_one`:
    it goes on with its current attempt (configuration, damping, stall counters), the restarts
    it has left and its own restart stream (``(seed, row)``)."""
    n = len(Q0)
    rule.start(n)
    rng = np.random.default_rng(seed)
    q, best_q = Q0.copy(), Q0.copy()
    best = np.full(n, np.inf)
    success = np.zeros(n, dtype=bool)
    iterations = np.zeros(n, dtype=int)
    attempt = np.zeros(n, dtype=int)
    restarts = np.zeros(n, dtype=int)
    attempt_best = np.full(n, np.inf)
    since_progress = np.zeros(n, dtype=int)
    singular_best = np.full(n, np.inf)  # attempt_best at the attempt's last singular step
    rows = np.flatnonzero(candidates)
    if len(rows) > _HAND_OFF:
        T, e, pos, rot = problem.evaluate(q[rows], rows)
    while len(rows) > _HAND_OFF:
        residual = np.maximum(pos, rot)
        improved = residual < best[rows]
        best[rows[improved]] = residual[improved]
        best_q[rows[improved]] = q[rows[improved]]
        progress = residual < _PROGRESS * attempt_best[rows]
        since_progress[rows] = np.where(progress, 0, since_progress[rows] + 1)
        attempt_best[rows] = np.minimum(attempt_best[rows], residual)
        done = (pos + problem.lever * rot <= problem.tol_position) & (
            rot <= problem.tol_orientation
        )
        success[rows[done]] = True
        stalled = ~done & _stalled(
            attempt[rows], since_progress[rows], rule.given_up(rows), rule.patience, max_iterations
        )
        look = ~done & ~stalled & (since_progress[rows] > 0) & (restarts[rows] < max_restarts)
        look &= residual >= _SINGULAR_BELOW
        look = np.flatnonzero(look)
        if len(look):  # a local minimum (_STATIONARY)
            squares = np.sum(e[look] * e[look], axis=-1)
            stalled[look] = _stationary(problem.jacobians(q[rows[look]]), e[look], squares)
        near = stalled & (residual < _SINGULAR_BELOW) & singular_steps
        near &= attempt_best[rows] < _PROGRESS * singular_best[rows]
        if near.any():  # first a step along the weakest direction (near a singular solution)
            tried = rows[near]
            singular_best[tried] = attempt_best[tried]
            trial = _singular_steps(problem, tried, q[tried], problem.jacobians(q[tried]), e[near])
            T_trial, e_trial, pos_trial, rot_trial = problem.evaluate(trial, tried)
            better = np.maximum(pos_trial, rot_trial) < _SINGULAR_BELOW
            kept = np.flatnonzero(near)[better]
            q[rows[kept]] = trial[better]
            T[kept], e[kept], pos[kept], rot[kept] = (
                T_trial[better],
                e_trial[better],
                pos_trial[better],
                rot_trial[better],
            )
            since_progress[rows[kept]] = 0
            iterations[rows[kept]] += 1
            attempt[rows[kept]] += 1
            rule.restart(rows[kept])
            stalled[kept] = False
        if stalled.any():  # restart from a random configuration, or give up
            again = stalled & (restarts[rows] < max_restarts)
            if again.any():
                fresh = rows[again]
                restarts[fresh] += 1
                attempt[fresh], since_progress[fresh], attempt_best[fresh] = 0, 0, np.inf
                singular_best[fresh] = np.inf
                rule.restart(fresh)
                q[fresh] = random_configurations(problem.robot, len(fresh), rng)
                T[again], e[again], pos[again], rot[again] = problem.evaluate(q[fresh], fresh)
            go = ~done & ~(stalled & ~again)
        else:
            go = ~done
        if not go.all():
            rows, T, e, pos, rot = rows[go], T[go], e[go], pos[go], rot[go]
            if not len(rows):
                break
        J = problem.jacobians(q[rows])
        dq = _limited(rule.step(problem, rows, T, J, e), max_step)
        trial = problem.wrap(q[rows] + dq)
        T_trial, e_trial, pos_trial, rot_trial = problem.evaluate(trial, rows)
        keep = rule.accept(rows, e, e_trial, J, dq)
        if keep.all():
            q[rows], T, e, pos, rot = trial, T_trial, e_trial, pos_trial, rot_trial
        else:
            q[rows[keep]] = trial[keep]
            T[keep], e[keep], pos[keep], rot[keep] = (
                T_trial[keep],
                e_trial[keep],
                pos_trial[keep],
                rot_trial[keep],
            )
        iterations[rows] += 1
        attempt[rows] += 1
    for r in rows.tolist():
        q_r, success[r], used, restarted, residual = _iterate_one(
            problem.row(r),
            rule.for_row(r),
            q[r],
            max_iterations=max_iterations,
            max_restarts=max_restarts - int(restarts[r]),
            singular_steps=singular_steps,
            max_step=max_step,
            seed=(seed, r),
            attempt_state=(
                int(attempt[r]),
                int(since_progress[r]),
                float(attempt_best[r]),
                float(singular_best[r]),
            ),
        )
        iterations[r] += used
        restarts[r] += restarted
        if success[r] or residual < best[r]:
            best_q[r] = q_r
    return best_q, success, iterations, restarts


# ----------------------------------------------------------------------------- the solver


def _targets(target: ArrayLike) -> tuple[np.ndarray, bool, tuple[int, ...]]:
    """Checked targets as (N, 4, 4) poses or (N, 3) positions, whether they are poses, and
    their leading axes."""
    if type(target) is np.ndarray and target.dtype == np.float64 and target.size == 16:
        # one pose: check_transform's scalar test checks finiteness and rigidity at once
        if target.shape == (4, 4):
            return check_transform(target, name="target")[None], True, ()
        if target.shape[-2:] == (4, 4):  # a stack of one: taken as it is if rigid
            if _is_transform_one(target.reshape(4, 4).tolist(), ROTATION_TOLERANCE):
                return target.reshape(1, 4, 4), True, target.shape[:-2]
    goal = real(target, "target")
    if goal.shape[-2:] == (4, 4):
        goal = check_transform(goal, name="target")
        return goal.reshape(-1, 4, 4), True, goal.shape[:-2]
    if goal.ndim >= 1 and goal.shape[-1] == 3:
        return goal.reshape(-1, 3), False, goal.shape[:-1]
    raise ValueError(
        "target must be a pose (4, 4) or (..., 4, 4), or a position (3,) or (..., 3); "
        f"got shape {goal.shape}"
    )


def ik(
    robot: Robot,
    target: ArrayLike,
    q0: ArrayLike | None = None,
    *,
    method: str | StepRule = "lm",
    orientation: str = "log",
    tol_position: float = 1e-10,
    tol_orientation: float = 1e-10,
    max_iterations: int = 100,
    max_restarts: int = 30,
    max_step: float | None = None,
    damping: float = 0.01,
    seed: int = 0,
) -> IKResult:
    """Joint angles that put the tool at a target pose (or position), by iteration.

    Parameters
    ----------
    robot : Robot
    target : array_like, shape (4, 4), (..., 4, 4), (3,) or (..., 3)
        Target poses of the tool (in the robot's base frame), or target positions (metres)
        when only the position matters.
    q0 : array_like, shape (6,) or (..., 6), optional
        Initial guesses (zeros by default); one guess serves every target of a stack.
    method : {"lm", "nr", "dls", "poe"} or StepRule
        The step rule (see the module documentation).
    orientation : {"log", "cross"}
        The orientation error used in the steps of ``lm``, ``nr`` and ``dls``: the rotation
        vector (exact) or the cross-product approximation of the course reports (blind at
        180°).  Success is always judged by the true angle.
    tol_position, tol_orientation : float
        Tolerances on the final position error (m) and orientation error (rad).
    max_iterations : int
        Iterations per attempt before a restart.  An attempt also restarts earlier when its
        error stops falling (a local minimum; see :class:`StepRule`).
    max_restarts : int
        Restarts from random configurations (drawn from ``seed``) before giving up.  A pose
        whose only two solutions lie close together (the arm nearly stretched) is found from
        about one random start in four: with 30, all but 1 of 1,000,000 random reachable UR5
        poses are solved (bench/ik_success.py), with 20 all but 32.  With 0, one attempt of
        the step rule alone: no restart, and no step along the Jacobian's weakest direction
        (see the module notes).
    max_step : float, optional
        Largest change of any joint in one step, radians (default: the rule's: 1.5 rad for
        ``lm``, 1 rad for the others).
    damping : float
        λ of ``dls``.
    seed : int
        Seed of the restarts: a seed reproduces a result exactly.

    Returns
    -------
    IKResult
        With the leading axes of the targets (index a 1-D batch for one target).

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
    robot = check_robot(robot)
    positive(damping, "damping", zero_ok=True)
    rule = _rule(method, damping)
    choice(orientation, "orientation", ("log", "cross"))
    positive(tol_position, "tol_position")
    positive(tol_orientation, "tol_orientation")
    positive(max_iterations, "max_iterations", integer=True, zero_ok=True)
    positive(max_restarts, "max_restarts", integer=True, zero_ok=True)
    positive(seed, "seed", integer=True, zero_ok=True, what="an integer ≥ 0 (a random seed)")
    if max_step is not None and max_step != math.inf:
        positive(max_step, "max_step")
    goal, pose, lead = _targets(target)
    n = len(goal)
    if isinstance(rule, MatrixLog) and not pose:
        raise ValueError("method 'poe' needs full poses (4×4), not positions")
    if q0 is None:
        Q0 = np.zeros((n, 6))
    else:
        guess, guess_lead, _ = _joints(q0, "q0")
        if len(guess) == 1:  # one guess (of shape (6,), (1, 6), …) for every target
            Q0 = guess if n == 1 else np.repeat(guess, n, axis=0)
        elif guess_lead == lead:
            Q0 = guess.copy()
        else:
            raise ValueError(
                f"q0 holds {len(guess)} configurations for {n} targets: give one guess, or "
                f"one per target (shape {(*lead, 6)}); got shape {(*guess_lead, 6)}"
            )
    settings = {
        "max_iterations": max_iterations,
        "max_restarts": max_restarts,
        "max_step": rule.max_step if max_step is None else max_step,
        "seed": seed,
        # with no restarts, one attempt of the step rule alone, as the lessons trace it
        "singular_steps": max_restarts > 0,
    }
    tolerances = (orientation, tol_position, tol_orientation)
    if 1 < n <= _HAND_OFF:  # a few targets: each solved as if alone, on the single path
        results = [
            _solve(robot, goal[i : i + 1], pose, (), Q0[i : i + 1], rule, tolerances, settings)
            for i in range(n)
        ]
        return stacked(results, lead)
    return _solve(robot, goal, pose, lead, Q0, rule, tolerances, settings)


def _solve(robot, goal, pose, lead, Q0, rule, tolerances, settings) -> IKResult:
    """:func:`ik` of checked targets ``goal`` (N, 4, 4) or positions (N, 3) from ``Q0`` (N, 6):
    one target on the single path, more on the stacked one; ``tolerances``: the orientation
    error's form and the two tolerances; ``settings``: the core's keyword arguments."""
    orientation, tol_position, tol_orientation = tolerances
    n = len(goal)
    bad, reasons = unreachable(robot, goal, pose)
    if pose:  # iterate on the flange's target, the nearest rotation, with the plain kinematics
        plain = (
            robot
            if robot._plain
            else Robot(robot.name, *robot.lengths, joint_limits=robot.joint_limits)
        )
        rigid, skew_angle = nearest_rigid(goal, min(RIGID_TOLERANCE, 0.1 * tol_orientation))
        flange = flange_pose(robot, rigid, check=False)
        problem = _Problem(
            plain,
            flange[:, :3, 3],
            flange[:, :3, :3],
            orientation,
            tol_position,
            tol_orientation,
            math.hypot(*robot.tool[:3, 3].tolist()),
        )
    else:  # a position of the tool point, in the world frame: the robot's own kinematics
        problem = _Problem(robot, goal, None, orientation, tol_position, tol_orientation)
        skew_angle = np.zeros(n)
    if n == 1:
        single = (
            _iterate_one(problem, rule, Q0[0], **settings) if not bad[0] else (Q0[0], False, 0, 0)
        )
        q, found, iterations, restarts = single[0][None], single[1:2], single[2:3], single[3:4]
        skewed = [0] if not bad[0] and skew_angle[0] > tol_orientation else []
    else:
        q, found, iterations, restarts = _iterate(problem, rule, Q0, ~bad, **settings)
        skewed = np.flatnonzero(~bad & (skew_angle > tol_orientation))
    for i in skewed:
        reasons[i] = skew_reason(skew_angle[i], "tol_orientation", tol_orientation)

    def failure(i: int, position: float, rotation: float) -> str:
        blind = orientation == "cross" and rotation > 3.0
        return (
            f"did not converge: after {restarts[i]} restarts the closest configuration found is "
            f"{position:.2e} m and {rotation:.2e} rad from the target{rule.stall_reason()}"
            + (" (the cross-product error is blind to orientations half a turn away)" * blind)
        )

    return verified(
        robot,
        q,
        goal,
        found,
        reasons,
        tol_position,
        tol_orientation,
        lead,
        iterations,
        restarts,
        failure,
    )
