"""Seeds 000 and 002's tracking programs, replayed as their code runs them, in metres.

Lesson 08 measures what these programs did with :func:`urkin.tracking_report.tracking_report`,
so they are reproduced here with every habit that matters, and nothing else:

* **Seed 000** (UR3, Python): a circle of 60 samples over ``linspace(0, 2π, 60)`` (so the first
  and last are the same point) and a square of 20 samples per side over ``linspace(0, 1, 20)``
  (so every corner comes twice), both in the Y–Z plane around (0.25, 0.1, 0.3) m with the
  identity orientation; Newton–Raphson with the damped inverse ``Jᵀ(JJᵀ + λ²I)⁻¹`` (λ = 0.01),
  the orientation error ``½ Σ nᵢ × nᵢ*``, a stop when the norm of the *mixed* 6-vector
  (metres and radians together) is below 10⁻³, at most 50 steps; each solve warm-starts from
  the robot's current state, and the state is overwritten with the solver's answer whether it
  converged or not (only the move to the first sample checks).
* **Seed 002** (UR5, MATLAB, millimetres): position-only Newton–Raphson with the pseudo-inverse
  on its published position formula and Jacobian (:mod:`urkin.course.seeds`), a stop when
  every coordinate is within 1 mm (the bare number ``1``), at most 200 steps, the answer passed
  through the two degree factors 0.0175 and 0.01744 before it warm-starts the next point, and
  drawn after one more pass through them.

The solvers loop over the samples in Python on purpose: each solve starts from the previous
answer, exactly as the seeds' programs do. Nothing in :mod:`urkin` uses this module.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

import urkin
from urkin.course.seeds import SEED002_ARM, SEED002_SHIFT, seed002_jacobian, seed002_position
from urkin.robots import Robot
from urkin.transforms import wrap_angles

__all__ = [
    "SEED000_CENTER",
    "SEED000_HOME",
    "Replay",
    "seed000_circle",
    "seed000_run",
    "seed000_solve",
    "seed000_square",
    "seed002_run",
]

SEED000_CENTER = np.array([0.25, 0.1, 0.3])
"""Centre of seed 000's circle and square (m), in the UR3's base frame."""

SEED000_HOME = np.array([0.0, -np.pi / 2, 0.0, -np.pi / 2, 0.0, 0.0])
"""Seed 000's "home" configuration (rad): upright, and singular three times over."""

_SEED002_FACTOR = 0.01744 / 0.0175  # radians → "degrees" by ÷ 0.0175 → "radians" by × 0.01744


@dataclass(frozen=True)
class Replay:
    """What a seed's program left in its joint state at each sample.

    Attributes
    ----------
    q : ndarray, shape (M, 6)
        The joint state after each sample (rad), as the program stores it (not wrapped).
    converged : ndarray of bool, shape (M,)
        Whether the program's own convergence test passed at that sample.
    drawn : ndarray, shape (M, 6)
        The angles the program's animation draws (seed 002 rescales them; seed 000 draws ``q``).
    """

    q: np.ndarray
    converged: np.ndarray
    drawn: np.ndarray


def _poses(points: np.ndarray) -> np.ndarray:
    poses = np.broadcast_to(np.eye(4), (len(points), 4, 4)).copy()
    poses[:, :3, 3] = points
    return poses


def seed000_circle(center: ArrayLike = SEED000_CENTER, radius: float = 0.1) -> np.ndarray:
    """Seed 000's circle as its code samples it: 60 poses, the first repeated as the last.

    Examples
    --------
    >>> poses = seed000_circle()
    >>> poses.shape, bool(np.allclose(poses[0], poses[-1]))
    ((60, 4, 4), True)
    """
    c = np.asarray(center, dtype=float)
    t = np.linspace(0.0, 2.0 * np.pi, 60)
    points = np.column_stack(
        [np.full_like(t, c[0]), c[1] + radius * np.cos(t), c[2] + radius * np.sin(t)]
    )
    return _poses(points)


def seed000_square(center: ArrayLike = SEED000_CENTER, side: float = 0.15) -> np.ndarray:
    """Seed 000's square as its code samples it: 20 poses per side, both ends included.

    Examples
    --------
    >>> poses = seed000_square()
    >>> steps = np.linalg.norm(np.diff(poses[:, :3, 3], axis=0), axis=1)
    >>> poses.shape, int((steps < 1e-12).sum()), round(1000 * float(steps.max()), 2)
    ((80, 4, 4), 3, 7.89)
    """
    c = np.asarray(center, dtype=float)
    h = side / 2
    corners = c + np.array([[0, -h, -h], [0, h, -h], [0, h, h], [0, -h, h], [0, -h, -h]])
    t = np.linspace(0.0, 1.0, 20)[None, :, None]  # each side: both ends included, as printed
    points = (corners[:-1, None] + (corners[1:] - corners[:-1])[:, None] * t).reshape(-1, 3)
    return _poses(points)


def seed000_solve(
    robot: Robot, T: np.ndarray, q: ArrayLike, max_iter: int = 50, tol: float = 1e-3
) -> tuple[np.ndarray, bool, int]:
    """Seed 000's solver: damped Newton–Raphson on a mixed metre/radian error.

    Returns
    -------
    (ndarray, bool, int)
        The angles after the last step, whether ``‖[e_p; e_ω]‖ < tol`` was reached, and the
        number of steps taken.
    """
    q = np.array(q, dtype=float)
    R_target = T[:3, :3]
    for step in range(max_iter):
        periodic = wrap_angles(q)  # the seed never wraps; its trigonometry does not mind
        T_now = urkin.fk(robot, periodic)
        e_p = T[:3, 3] - T_now[:3, 3]
        e_w = 0.5 * np.cross(T_now[:3, :3].T, R_target.T).sum(axis=0)
        e = np.concatenate([e_p, e_w])
        if np.linalg.norm(e) < tol:
            return q, True, step
        J = urkin.jacobian(robot, periodic)
        q = q + J.T @ np.linalg.solve(J @ J.T + 0.01**2 * np.eye(6), e)
    return q, False, max_iter


def seed000_run(robot: Robot, poses: ArrayLike, q: ArrayLike) -> Replay:
    """Seed 000's ``run_trajectory``: warm starts from the current state, which it overwrites.

    The first sample moves the arm only if its solve converges; every later sample stores
    the solver's answer whether it converged or not.

    Examples
    --------
    >>> replay = seed000_run(urkin.robot("UR3"), seed000_square()[:3], SEED000_HOME)
    >>> replay.q.shape, bool(replay.converged.all())
    ((3, 6), True)
    """
    poses = np.asarray(poses, dtype=float)
    state = np.array(q, dtype=float)
    qs, converged = [], []
    for k, T in enumerate(poses):
        q_sol, ok, _ = seed000_solve(robot, T, state)
        if ok or k > 0:  # the first move checks; the others overwrite the state regardless
            state = q_sol
        qs.append(state)
        converged.append(ok)
    qs = np.array(qs)
    return Replay(qs, np.array(converged), qs)


def seed002_run(
    points: ArrayLike, q_guess: ArrayLike | None = None, published: bool = True
) -> Replay:
    """Seed 002's tracking loop, in UR angles and metres, on its published model or the truth.

    Parameters
    ----------
    points : array_like, shape (M, 3)
        Target positions (m) in the base frame of :data:`urkin.course.seeds.SEED002_ARM`.
    q_guess : array_like, shape (6,), optional
        The first guess in UR angles; by default the report's "20°" on every joint, converted
        with its factor 0.0175.
    published : bool
        Iterate on the report's formula and Jacobian (True) or on the true kinematics of
        ``SEED002_ARM`` (False), everything else the same.

    Returns
    -------
    Replay
        ``q`` the solved UR angles, ``converged`` its 1 mm test, ``drawn`` the angles its
        animation draws (once more through the degree factors).
    """
    points = np.asarray(points, dtype=float)
    guess = np.full(6, 20.0) * 0.0175 - SEED002_SHIFT if q_guess is None else np.array(q_guess)
    qs, converged = [], []
    for point in points:
        q = np.array(guess, dtype=float)
        ok, before = False, q
        for _ in range(200):  # MATLAB's loop returns the angles its last error was measured at
            if published:
                p = np.array(seed002_position(q + SEED002_SHIFT))
                J = np.array(seed002_jacobian(q + SEED002_SHIFT), dtype=float)
            else:
                p = urkin.fk(SEED002_ARM, q)[:3, 3]
                J = urkin.kinematics.position_jacobian(SEED002_ARM, q)
            error = point - p
            if np.abs(error).max() <= 1e-3:
                ok = True
                break
            before, q = q, q + np.linalg.pinv(J) @ error
        qs.append(q if ok else before)
        converged.append(ok)
        guess = (q + SEED002_SHIFT) * _SEED002_FACTOR - SEED002_SHIFT
    qs = np.array(qs)
    drawn = (qs + SEED002_SHIFT) * _SEED002_FACTOR - SEED002_SHIFT
    return Replay(qs, np.array(converged), drawn)
