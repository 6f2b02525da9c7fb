"""Time a planned path: rest-to-rest cubics along its straight joint-space edges.

A planner's path is checked edge by edge along *straight* lines in joint space, so the timed
motion must stay on those lines.  A cubic with zero velocity at both ends moves every joint by
the same fraction ``s(τ) = 3τ² − 2τ³`` of its change, which keeps the arm on the straight
edge; blending through a via with a non-zero velocity (:func:`urkin.trajectory.via_trajectory`'s
default heuristic) would cut the corner, off the edges that were checked.  So the arm stops at
every waypoint (shortcutting leaves few of them), and each edge gets the shortest duration
within both limits: a rest-to-rest cubic over ``Δq`` in ``T`` seconds peaks at ``1.5 Δq / T``
in speed and ``6 Δq / T²`` in acceleration.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from urkin._inputs import positive, real
from urkin.planning.rrt import Plan
from urkin.trajectory import Trajectory, via_trajectory

__all__ = ["time_parametrize"]

#: URScript's ``movej`` defaults: joint speed 1.05 rad/s, joint acceleration 1.4 rad/s².
MAX_VELOCITY, MAX_ACCELERATION = 1.05, 1.4


def _limit(value: ArrayLike, name: str, n: int) -> np.ndarray:
    limit = np.broadcast_to(real(value, name), (n,)) if np.ndim(value) == 0 else real(value, name)
    if limit.shape != (n,) or not np.all(limit > 0):
        raise ValueError(f"{name} must be positive, one number or one per joint ({n}); got {value}")
    return np.asarray(limit, dtype=float)


def time_parametrize(
    path: Plan | ArrayLike,
    max_velocity: float | ArrayLike = MAX_VELOCITY,
    max_acceleration: float | ArrayLike = MAX_ACCELERATION,
    *,
    dt: float = 0.01,
) -> Trajectory:
    """The fastest rest-to-rest timing of a path's straight edges within joint limits.

    Parameters
    ----------
    path : Plan or array_like, shape (M, n)
        A successful :class:`Plan`, or waypoints (rad), M ≥ 1; repeated waypoints are merged.
    max_velocity, max_acceleration : float or array_like, shape (n,)
        Joint speed (rad/s) and acceleration (rad/s²) limits; defaults: URScript ``movej``'s
        1.05 rad/s and 1.4 rad/s².
    dt : float
        Sampling period (s); the last waypoint is always the last sample.

    Returns
    -------
    Trajectory
        ``t``, ``q``, ``qd``, ``qdd``; every sample lies on a path edge, and each edge's
        slowest joint reaches its speed or acceleration limit, none exceeds either.

    Raises
    ------
    ValueError
        For a plan that did not succeed (with its reason), a path that is not (M, n) or holds
        NaN, or limits that are not positive.

    Examples
    --------
    >>> from urkin import planning
    >>> traj = planning.time_parametrize([[0.0, 0, 0, 0, 0, 0], [1.05, 0, 0, 0, 0, 0]], dt=0.5)
    >>> round(float(traj.t[-1]), 3)  # √(6 Δq / a): the acceleration limit decides
    2.121
    """
    if isinstance(path, Plan):
        if not path.success:
            raise ValueError(f"path: the plan did not succeed ({path.reason})")
        path = path.path
    Q = real(path, "path")
    if Q.ndim != 2 or len(Q) < 1:
        raise ValueError(f"path must have shape (M, n) with M ≥ 1 waypoints; got {Q.shape}")
    n = Q.shape[1]
    v = _limit(max_velocity, "max_velocity", n)
    a = _limit(max_acceleration, "max_acceleration", n)
    positive(dt, "dt", what="a positive number of seconds")
    keep = np.concatenate([[True], np.any(np.diff(Q, axis=0) != 0, axis=1)])
    Q = Q[keep]
    if len(Q) == 1:
        zero = np.zeros((1, n))
        return Trajectory(np.zeros(1), Q.copy(), zero, zero.copy())
    change = np.abs(np.diff(Q, axis=0))
    T = np.max(np.maximum(1.5 * change / v, np.sqrt(6.0 * change / a)), axis=1)
    t_via = np.concatenate([[0.0], np.cumsum(T)])
    times = via_trajectory(Q, t_via, np.zeros_like(Q), dt=dt)
    if times.t[-1] < t_via[-1] - 1e-12:  # end exactly at the last waypoint, at rest
        last = via_trajectory(Q[-2:], t_via[-2:], np.zeros((2, n)), samples=2)
        times = Trajectory(
            *(
                np.concatenate([x, y[-1:]])
                for x, y in zip(
                    (times.t, times.q, times.qd, times.qdd), (last.t, last.q, last.qd, last.qdd)
                )
            )
        )
    return times
