"""Closed-form inverse kinematics of UR arms: every solution, exactly, for one pose or a batch.

For a flange pose ``T = T_0_6`` the UR's geometry gives up to eight solutions:

1. **θ1** (two): the origin of DH frame 5, ``c = p − d6 z``, must lie on a vertical plane at
   distance ``d4`` from the base axis: ``θ1 = atan2(c_y, c_x) ± acos(d4 / ‖c_xy‖) + π/2``.
2. **θ5** (two per θ1): ``cos θ5 = z_x sin θ1 − z_y cos θ1`` (the flange's z axis against the
   shoulder axis).
3. **θ6**: ``cos θ6 · sin θ5 = x_x sin θ1 − x_y cos θ1`` and
   ``sin θ6 · sin θ5 = −(y_x sin θ1 − y_y cos θ1)``.
4. **θ2, θ3, θ4** (two): what remains is a planar arm in the plane of joints 2–4: the origin of
   frame 3 at ``(a2 c2 + a3 c23, a2 s2 + a3 s23)`` (law of cosines for θ3), and
   ``θ4 = θ234 − θ2 − θ3`` with ``θ234`` read off ``T_1_4``.

Singular poses are solved exactly, with rounding clamped rather than turned into NaN:

* **shoulder** (``‖c_xy‖ = d4``): the two θ1 branches merge into one;
* **wrist** (``sin θ5 = 0``): only ``θ234 ± θ6`` is determined (``θ234 = θ2 + θ3 + θ4``), and
  a one-parameter family of configurations reaches the pose; for each θ1 urkin returns the two
  members whose elbow is nearest a right angle (see :func:`_wrist_theta6`), in place of the
  two θ5 branches, which coincide;
* **elbow** (``θ3 = 0`` or ``π``): a double root.

Duplicates that singular poses produce are returned once.  Angles are wrapped to (−π, π].
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from urkin.kinematics import _joints, fk
from urkin.numerical_ik import IKResult
from urkin.robots import Robot
from urkin.transforms import check_transform, rotation_angle

__all__ = ["ACOS_TOLERANCE", "SNAP", "ik_analytic", "ik_closest", "wrap_angles"]

#: Arguments of acos within this of ±1 are clamped (rounding at a singular pose); further out,
#: the pose is out of reach for that branch.
ACOS_TOLERANCE = 1e-9
#: Arguments of acos within this of ±1 are a double root: taken as exactly ±1.
SNAP = 1e-12


def wrap_angles(q: ArrayLike) -> np.ndarray:
    """Angles wrapped to (−π, π].

    Examples
    --------
    >>> wrap_angles([np.pi, -np.pi, 3 * np.pi / 2, 0.5])
    array([ 3.14159265,  3.14159265, -1.57079633,  0.5       ])
    """
    angles = np.asarray(q, dtype=float)
    return angles - 2.0 * np.pi * np.ceil((angles - np.pi) / (2.0 * np.pi))


def _wrap_near(angles: np.ndarray) -> np.ndarray:
    """:func:`wrap_angles` for angles already within (−3π, 3π]: two comparisons, no division."""
    return angles - 2.0 * np.pi * ((angles > np.pi).astype(float) - (angles <= -np.pi))


def _acos(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """acos with rounding clamped; also whether the argument was within reach.

    Arguments within :data:`SNAP` of ±1 are taken as exactly ±1: a double root (the shoulder,
    wrist or elbow singularity), where rounding of order 1e-16 would otherwise move the angle
    by its square root, ~1e-8 rad, for a pose change of ~1e-16 m.
    """
    ok = np.abs(x) <= 1.0 + ACOS_TOLERANCE
    snapped = np.where(np.abs(x) >= 1.0 - SNAP, np.sign(x), np.clip(x, -1.0, 1.0))
    return np.arccos(snapped), ok


def _solve_flange(T: np.ndarray, robot: Robot) -> tuple[np.ndarray, np.ndarray]:
    """All eight branches for flange poses T (N, 4, 4): solutions (N, 8, 6) and a mask of the
    real, distinct ones (out-of-reach branches and repeats at singular poses are False)."""
    d1, a2, a3, d4, d5, d6 = robot.lengths
    n = len(T)
    x, y, z, p = T[:, :3, 0], T[:, :3, 1], T[:, :3, 2], T[:, :3, 3]
    c = p - d6 * z  # origin of DH frame 5 (the wrist point)
    radius = np.hypot(c[:, 0], c[:, 1])
    shoulder, ok1 = _acos(np.where(radius > 0, d4 / np.where(radius > 0, radius, 1.0), np.inf))
    theta1 = (
        np.arctan2(c[:, 1], c[:, 0])[:, None]
        + np.array([1.0, -1.0]) * shoulder[:, None]
        + np.pi / 2
    )  # (n, 2)
    # sin and cos of θ1 = heading ± φ + π/2 from the geometry, without trig calls
    ch, sh = (
        c[:, 0] / np.where(radius > 0, radius, 1.0),
        c[:, 1] / np.where(radius > 0, radius, 1.0),
    )
    cphi, sphi = np.cos(shoulder), np.sin(shoulder)
    side = np.array([1.0, -1.0])
    s1 = ch[:, None] * cphi[:, None] - sh[:, None] * sphi[:, None] * side  # cos(heading ± φ)
    c1 = -(sh[:, None] * cphi[:, None] + ch[:, None] * sphi[:, None] * side)  # −sin(heading ± φ)
    theta5, _ = _acos(z[:, 0, None] * s1 - z[:, 1, None] * c1)  # θ5 of the "+" branch, (n, 2)
    # θ6 and θ234 of the "+" branch (sin θ5 > 0); the "−" branch adds π to both
    theta6 = np.arctan2(
        -(y[:, 0, None] * s1 - y[:, 1, None] * c1), x[:, 0, None] * s1 - x[:, 1, None] * c1
    )
    # sin θ5 · (sin θ234, cos θ234) = −(z_z, z_x c1 + z_y s1): normalise rather than call trig
    zz, zr = -z[:, 2, None] * np.ones_like(s1), -(z[:, 0, None] * c1 + z[:, 1, None] * s1)
    theta234 = np.arctan2(zz, zr)
    length = np.hypot(zz, zr)
    s234 = zz / np.where(length > 0, length, 1.0)
    c234 = zr / np.where(length > 0, length, 1.0)
    branch = np.array([1.0, -1.0])
    theta6 = theta6[:, :, None] + np.array([0.0, np.pi])  # (n, 2, 2)
    theta234 = theta234[:, :, None] + np.array([0.0, np.pi])
    s234, c234 = s234[:, :, None] * branch, c234[:, :, None] * branch
    theta5 = theta5[:, :, None] * branch
    # the wrist point in frame 1's plane (x along the arm, y up from the shoulder)
    X5 = (c[:, 0, None] * c1 + c[:, 1, None] * s1)[:, :, None]
    Y5 = (c[:, 2] - d1)[:, None, None]
    wrist = (theta5[:, :, :1] == 0.0) | (theta5[:, :, :1] == np.pi)  # (n, 2, 1), after snapping
    if np.any(wrist):
        rule234, rule6 = _wrist_representatives(T, X5, Y5, theta5, robot)
        theta234 = np.where(wrist, rule234, theta234)
        theta6 = np.where(wrist, rule6, theta6)
        s234 = np.where(wrist, np.sin(rule234), s234)
        c234 = np.where(wrist, np.cos(rule234), c234)
    # the planar 2R arm reaches the origin of frame 3: the wrist point minus d5 along z4
    px, py = X5 - d5 * s234, Y5 + d5 * c234
    elbow, ok3 = _acos((px * px + py * py - a2 * a2 - a3 * a3) / (2.0 * a2 * a3))  # (n, 2, 2)
    # θ3 = ±elbow and θ2 = atan2(py, px) ∓ atan2(a3 sin(elbow), a2 + a3 cos(elbow))
    gamma = np.arctan2(a3 * np.sin(elbow), a2 + a3 * np.cos(elbow))
    sign = np.array([1.0, -1.0])
    theta3 = elbow[..., None] * sign  # (n, 2, 2, 2)
    theta2 = np.arctan2(py, px)[..., None] - gamma[..., None] * sign
    q = np.empty((n, 2, 2, 2, 6))  # each angle wrapped to (−π, π] on its smallest array
    q[..., 0] = _wrap_near(theta1)[:, :, None, None]
    theta2 = _wrap_near(theta2)
    q[..., 1] = theta2
    q[..., 2] = theta3  # acos: already in [−π, π], and −π only at a removed double root
    q[..., 3] = _wrap_near(_wrap_near(theta234)[..., None] - theta2 - theta3)
    q[..., 4] = _wrap_near(theta5)[..., None]
    q[..., 5] = _wrap_near(theta6)[..., None]
    # real and distinct: double roots at singular poses give each solution once
    keep = np.broadcast_to((ok1[:, None, None] & ok3)[..., None], (n, 2, 2, 2)).copy()
    keep[:, 1] &= (shoulder != 0.0)[:, None, None]  # the θ1 branches merge
    keep[..., 1] &= (elbow != 0.0) & (elbow != np.pi)  # θ3 = 0 or π: a double root
    same_rep = np.abs(wrap_angles(theta234[:, :, 1] - theta234[:, :, 0])) < 1e-12
    keep[:, :, 1] &= ~(wrist[:, :, 0] & same_rep)[:, :, None]
    return q.reshape(n, 8, 6), keep.reshape(n, 8)


def _wrist_representatives(T, X5, Y5, theta5, robot) -> tuple[np.ndarray, np.ndarray]:
    """θ234 and θ6 of the two representatives of a wrist-singular family (sin θ5 = 0).

    With sin θ5 = 0 only ``φ = θ234 ± θ6`` is fixed (``+`` when θ5 = 0, ``−`` when θ5 = π):
    choosing θ234 moves joint 5's centre on a circle of radius d5 round the wrist point and
    changes the planar arm's reach ρ.  The representatives take the two θ234 (one on each side
    of the circle) whose ρ is nearest ``√(a2² + a3²)``: the elbow nearest a right angle.
    """
    _, a2, a3, _, d5, _ = robot.lengths
    A = np.hypot(X5, Y5)
    beta = np.arctan2(Y5, X5)
    sigma = (A * A + d5 * d5 - (a2 * a2 + a3 * a3)) / (2.0 * d5 * np.where(A > 0, A, 1.0))
    half = np.arcsin(np.clip(sigma, -1.0, 1.0))
    theta234 = np.concatenate([beta + half, beta + np.pi - half], axis=-1)  # (n, 2, 2)
    phi = np.arctan2(T[:, 2, 0], T[:, 2, 1])[:, None, None]  # θ234 + θ6, or θ6 − θ234
    flipped = np.abs(theta5) == np.pi
    return theta234, np.where(flipped, phi + theta234, phi - theta234)


#: Large batches are solved in blocks of this many poses, which keeps temporaries in cache.
_BLOCK = 2048


def _solve(poses: np.ndarray, robot: Robot) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_solve_flange` block by block, without floating-point warnings (out-of-reach
    poses are expected)."""
    n = len(poses)
    with np.errstate(invalid="ignore", divide="ignore"):
        if n <= _BLOCK:
            return _solve_flange(poses, robot)
        q, keep = np.empty((n, 8, 6)), np.empty((n, 8), dtype=bool)
        for start in range(0, n, _BLOCK):
            q[start : start + _BLOCK], keep[start : start + _BLOCK] = _solve_flange(
                poses[start : start + _BLOCK], robot
            )
    return q, keep


def _flange_targets(robot: Robot, T: ArrayLike) -> tuple[np.ndarray, bool]:
    poses = check_transform(T, name="T")
    single = poses.ndim == 2
    poses = poses.reshape(-1, 4, 4)
    if not robot._plain:
        poses = np.linalg.inv(robot.base) @ poses @ np.linalg.inv(robot.tool)
    return poses, single


def ik_analytic(
    robot: Robot, T: ArrayLike, *, return_mask: bool = False
) -> np.ndarray | tuple[np.ndarray, np.ndarray]:
    """Every closed-form solution of a UR arm's inverse kinematics.

    Parameters
    ----------
    robot : Robot
    T : array_like, shape (4, 4) or (N, 4, 4)
        Tool poses in the robot's base frame (flange poses unless the robot has a tool).
    return_mask : bool
        For a batch, also return the validity mask (always returned for a batch when True;
        ignored for a single pose).

    Returns
    -------
    ndarray
        For one pose: shape (k, 6), ``k ≤ 8`` distinct exact solutions (``k = 0`` when the
        pose is out of reach), wrapped to (−π, π].  For a batch: shape (N, 8, 6) with NaN in
        the rows that are not solutions (out of reach, or repeats of an earlier row at a
        singular pose); with ``return_mask=True`` also the (N, 8) boolean mask of real rows.
        Row ``i`` of every pose is the same branch: bit 2 of ``i`` chooses the θ1 branch, bit
        1 the sign of θ5 and bit 0 the sign of θ3 (elbow up or down).

    Examples
    --------
    >>> import urkin
    >>> ur5 = urkin.robot("ur5")
    >>> T = urkin.fk(ur5, [0.3, -1.2, 1.4, -0.6, 1.1, 0.2])
    >>> solutions = ik_analytic(ur5, T)
    >>> solutions.shape
    (8, 6)
    >>> bool(np.allclose(urkin.fk(ur5, solutions), T, atol=1e-12))
    True
    >>> ik_analytic(ur5, urkin.fk(ur5, np.zeros(6)) @ np.diag([1, 1, 1, 1.0])).shape[0] < 8
    True
    """
    if not isinstance(robot, Robot):
        raise TypeError(f"expected a urkin Robot such as urkin.robot('ur5'); got {robot!r:.40}")
    poses, single = _flange_targets(robot, T)
    q, keep = _solve(poses, robot)
    if single:
        return q[0][keep[0]]
    q[~keep] = np.nan
    return (q, keep) if return_mask else q


def ik_closest(
    robot: Robot,
    T: ArrayLike,
    q_current: ArrayLike,
    *,
    tol_position: float = 1e-9,
    tol_orientation: float = 1e-9,
) -> IKResult:
    """The closed-form solution nearest the current configuration, within the joint limits.

    Each solution is shifted joint by joint by multiples of 2π to the equivalent closest to
    ``q_current`` that respects the robot's joint limits (±2π on UR arms), and the solution
    whose shifted angles are nearest (Euclidean norm) wins.  This is what a trajectory
    follows: no joint jumps by a turn, and a branch is kept as long as it exists.

    Parameters
    ----------
    robot : Robot
    T : array_like, shape (4, 4) or (N, 4, 4)
        Tool poses.
    q_current : array_like, shape (6,) or (N, 6)
        The configuration(s) to stay close to.
    tol_position, tol_orientation : float
        Tolerances of the verification of the returned solution (metres, radians).

    Returns
    -------
    IKResult
        ``success`` is False (``q = q_current``) when the pose has no solution.

    Examples
    --------
    >>> import urkin
    >>> ur5 = urkin.robot("ur5")
    >>> q = np.array([0.3, -1.2, 1.4, -0.6, 1.1, 6.0])  # joint 6 beyond π: still within ±2π
    >>> result = ik_closest(ur5, urkin.fk(ur5, q), q + 0.01)
    >>> bool(result.success), bool(np.allclose(result.q, q))
    (True, True)
    """
    poses, single = _flange_targets(robot, T)
    current, _ = _joints(q_current, "q_current")
    current = np.broadcast_to(current, (len(poses), 6)) if current.ndim == 1 else current
    if len(current) != len(poses):
        raise ValueError(f"q_current holds {len(current)} configurations for {len(poses)} poses")
    q, valid = _solve(poses, robot)
    lower = np.array([lo for lo, _ in robot.joint_limits])
    upper = np.array([hi for _, hi in robot.joint_limits])
    # the 2π-equivalent of each angle nearest the current one, pushed back inside the limits
    shifted = current[:, None, :] + wrap_angles(q - current[:, None, :])
    shifted = np.where(shifted > upper, shifted - 2 * np.pi, shifted)
    shifted = np.where(shifted < lower, shifted + 2 * np.pi, shifted)
    inside = np.all((shifted >= lower) & (shifted <= upper), axis=-1) & valid
    distance = np.where(inside, np.linalg.norm(shifted - current[:, None, :], axis=-1), np.inf)
    best = np.argmin(distance, axis=1)
    found = np.isfinite(distance[np.arange(len(poses)), best])
    chosen = np.where(found[:, None], shifted[np.arange(len(poses)), best], current)
    reached = fk(robot, chosen)
    goal = check_transform(T, name="T").reshape(-1, 4, 4)
    position_error = np.linalg.norm(reached[:, :3, 3] - goal[:, :3, 3], axis=-1)
    rotation_error = rotation_angle(reached[:, :3, :3], goal[:, :3, :3])
    success = found & (position_error <= tol_position) & (rotation_error <= tol_orientation)
    reasons = [
        "converged"
        if ok
        else "no closed-form solution within the joint limits: the pose is out of reach"
        if not f
        else f"the closed-form solution misses by {pe:.2e} m and {re:.2e} rad"
        for ok, f, pe, re in zip(success, found, position_error, rotation_error)
    ]
    result = IKResult(
        chosen,
        success,
        np.maximum(position_error, rotation_error),
        position_error,
        rotation_error,
        np.zeros(len(poses), dtype=int),
        np.zeros(len(poses), dtype=int),
        reasons,
    )
    return result[0] if single else result
