"""Closed-form inverse kinematics of UR arms: every solution, exactly, for one pose or a stack.

For a flange pose ``T = T_0_6`` (axes ``x, y, z``, position ``p``) the UR's geometry gives up to
eight solutions, two choices at each of three steps:

1. **θ1** (shoulder left or right): the origin of DH frame 5, the wrist point
   ``w = p − d6 z``, lies on a vertical plane at distance ``d4`` from the base axis, so with
   ``r = ‖w_xy‖``: ``θ1 = atan2(w_y, w_x) ± atan2(√((r − d4)(r + d4)), d4) + π/2``.
2. **θ5, θ6** (wrist flipped or not): with ``n = (sin θ1, −cos θ1, 0)`` (the axis of joints
   2–4), ``cos θ5 = z·n``, ``sin θ5 cos θ6 = x·n`` and ``sin θ5 sin θ6 = −y·n``, so
   ``θ5 = atan2(±‖(x·n, y·n)‖, z·n)`` and ``θ6 = atan2(∓y·n, ±x·n)``: both from sine *and*
   cosine, exact right up to the wrist singularity (an ``acos`` of ``z·n`` is not: its
   rounding near ±1 moves θ5 by the square root of the error).
3. **θ2, θ3, θ4** (elbow up or down): frame 4's x axis is ``u = cos θ5 (cos θ6 x − sin θ6 y)
   − sin θ5 z = (cos θ1 cos θ234, sin θ1 cos θ234, sin θ234)``, which gives
   ``θ234 = θ2 + θ3 + θ4``; what remains is a planar 2R arm (lengths ``a2``, ``a3``) reaching
   the origin of frame 3, ``d5`` back from the wrist point along frame 4's z axis, solved with
   the law of cosines in the factored form ``sin² θ3 ∝ (L − ρ)(L + ρ)(ρ − l)(ρ + l)`` that keeps
   full precision at full stretch ``L`` and full fold ``l``; then ``θ4 = θ234 − θ2 − θ3``.

Singular poses:

* **shoulder** (``r = d4``): both θ1 branches are kept until they are equal to rounding (a
  wrist point ``1e-12`` m off the cylinder still gives two solutions ~1e-5 rad apart, both
  exact; one a few ulps off gives one solution, which misses by those few ulps);
* **wrist** (``sin θ5 = 0``, below :data:`WRIST_TOLERANCE`): only ``θ234 ± θ6`` is fixed and a
  one-parameter family reaches the pose; for each θ1 the two members whose elbow is nearest a
  right angle are returned in place of the two θ5 branches (see :func:`_representatives`);
* **elbow** (``θ3 = 0`` or ``π``): a double root, by the same rule.

Near them:

* **near the wrist** (``sin θ5`` small but above the tolerance): θ234 and θ6 are told apart
  only by the pose's entries of order ``sin θ5``, so each is known to about ``ε / sin θ5``
  while ``θ234 ± θ6`` is exact.  Where the θ234 computed puts frame 3 a hair beyond the
  elbow's reach, it is moved within that rounding (θ6 the other way) onto the border: an exact
  solution, where the hair would otherwise drop the branch (``ε / sin θ5`` of 1e-7 rad moves
  frame 3 by ``d5`` times that);
* **near the shoulder** with the elbow stretched or folded: the wrist point's offset in the
  arm's plane is a double root, known only to ``√ε``, and an elbow that misses by that much
  is solved again from the offset in that range where it misses least.  Where two double
  roots meet, solutions reach the pose within :data:`REACH_TOLERANCE` (elsewhere, to
  round-off).

A pose within :data:`REACH_TOLERANCE` outside the reachable set (inside the ``d4`` cylinder, or
beyond full stretch or fold of the elbow) is taken as on its border: its solutions miss by at
most that much.  Solutions equal to within :data:`DUPLICATE_TOLERANCE` (modulo 2π) are returned
once.  Angles are wrapped to (−π, π].
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from urkin._inputs import flag, positive, real, unstack
from urkin.ik_result import (
    RIGID_TOLERANCE,
    IKResult,
    nearest_rigid,
    no_solution_reason,
    skew_reason,
    verified,
)
from urkin.kinematics import MAX_JOINT_ANGLE, _range_error, flange_pose
from urkin.robots import Robot, check_robot
from urkin.transforms import ROTATION_TOLERANCE, _checked_transform, _is_rotation_one, wrap_angles

__all__ = [
    "DUPLICATE_TOLERANCE",
    "REACH_TOLERANCE",
    "WRIST_TOLERANCE",
    "ik_analytic",
    "ik_closest",
]

#: A pose this far (metres) outside the reachable set is taken as on its border.
REACH_TOLERANCE = 1e-10
#: Below this, ``|sin θ5|`` is a wrist singularity: θ6 is no longer fixed by the pose.
WRIST_TOLERANCE = 1e-13
#: Solutions closer than this (radians, every joint, modulo 2π) are one solution.
DUPLICATE_TOLERANCE = 1e-12

#: Two branches whose gap is within its own rounding error — the wrist point's distance from
#: the ``d4`` cylinder, or the elbow's from full stretch or fold, within a few ulps of the
#: lengths it is computed from — are one double root.
_ROUNDOFF = 8.0 * np.finfo(float).eps

_PI, _TWO_PI = math.pi, 2.0 * math.pi


def _check_lengths(robot: Robot) -> None:
    if robot.a2 == 0.0 or robot.a3 == 0.0:
        raise ValueError(f"{robot.name}: the closed form needs a2 ≠ 0 and a3 ≠ 0")


# ----------------------------------------------------------------------------- one pose


def _wrap_one(angle: float) -> float:
    """One angle in (−π, π] (the scalar twin of :func:`urkin.transforms.wrap_angles`)."""
    if -_PI < angle <= _PI:
        return angle
    angle = math.fmod(angle, _TWO_PI)
    if angle > _PI:
        return angle - _TWO_PI
    if angle <= -_PI:
        return angle + _TWO_PI
    return angle


def _solve_one(
    rows: list[list[float]],
    lengths: tuple[float, ...],
    misses: list[float] | None = None,
    root: float | None = None,
    short: dict[int, float] | None = None,
    prefer: float | None = None,
) -> list[list[float] | None]:
    """The eight branches of one flange pose given as ``T.tolist()``, plain floats, no numpy:
    entry ``i`` is the solution of branch ``i`` (the row layout of :func:`ik_analytic` for a
    stack), or None where that branch has no solution or repeats an earlier one.

    When given, ``misses`` collects how far the elbow falls short on each branch it drops, and
    ``short`` how far (m) on each branch (by its first row) whose elbow misses its border,
    dropped or not.
    ``root`` replaces ``√((r − d4)(r + d4))`` (:func:`_shoulder_retry`).  ``prefer``: at the
    wrist singularity, the θ234 of the family member returned (both θ5 branches; one row where
    its elbow reaches), in place of the two representatives."""
    d1, a2, a3, d4, d5, d6 = lengths
    (xx, yx, zx, px), (xy, yy, zy, py), (xz, yz, zz, pz) = rows[0], rows[1], rows[2]
    wx, wy, wz = px - d6 * zx, py - d6 * zy, pz - d6 * zz
    r2 = wx * wx + wy * wy
    r = math.sqrt(r2)
    found: list[list[float] | None] = [None] * 8
    if r - d4 < -REACH_TOLERANCE or r2 == 0.0 or r2 == math.inf:  # inf: a wrist at 1e154 m
        return found
    retry = root is None
    if root is None:
        gap = r - d4 if abs(r - d4) > _ROUNDOFF * (abs(px) + abs(py) + d6 + d4) else 0.0
        root = math.sqrt(max(gap * (r + d4), 0.0))
    # the branches whose elbow misses its border, kept where the shoulder retry may fill them
    missed: dict[int, float] | None = short
    if missed is None and retry and root < _SHOULDER_NEAR:
        missed = {}
    big, small = abs(a2) + abs(a3), abs(abs(a2) - abs(a3))
    two_a2a3 = 2.0 * a2 * a3
    # Rows can repeat only where two branches meet: at a wrist representative, or where the
    # θ1 or θ3 branches are closer than DUPLICATE_TOLERANCE; elsewhere θ1, θ6 (by π) or θ3
    # tells them apart, and the pairwise comparison is skipped.
    suspect = False
    shoulders: list[float] = []
    for branch, shoulder in enumerate((1.0, -1.0) if root > 0.0 else (1.0,)):
        s1 = wx * d4 - shoulder * wy * root
        c1 = -(wy * d4 + shoulder * wx * root)
        norm = math.hypot(s1, c1)
        s1, c1 = s1 / norm, c1 / norm
        q1 = _wrap_one(math.atan2(s1, c1))
        shoulders.append(q1)
        A = xx * s1 - xy * c1  # sin θ5 cos θ6
        B = yy * c1 - yx * s1  # sin θ5 sin θ6
        C = zx * s1 - zy * c1  # cos θ5
        S = math.hypot(A, B)
        X, Y = c1 * wx + s1 * wy, wz - d1  # the wrist point in the arm's plane
        for sign5, flip in enumerate((1.0, -1.0)):
            if S > WRIST_TOLERANCE:
                q5 = math.atan2(flip * S, C)
                q6 = math.atan2(flip * B, flip * A)
                s5, c5 = flip * S, C
                c6, s6 = flip * A / S, flip * B / S
                ux = c5 * (c6 * xx - s6 * yx) - s5 * zx
                uy = c5 * (c6 * xy - s6 * yy) - s5 * zy
                s234 = c5 * (c6 * xz - s6 * yz) - s5 * zz
                c234 = c1 * ux + s1 * uy
                q234 = math.atan2(s234, c234)
            else:
                suspect = True
                q5 = math.atan2(S, C)
                q234 = _representative_one(X, Y, flip, a2, a3, d5) if prefer is None else prefer
                s234, c234 = math.sin(q234), math.cos(q234)
                x4 = (c1 * c234, s1 * c234, s234)
                sign = 1.0 if C >= 0.0 else -1.0
                q6 = math.atan2(
                    -sign * (x4[0] * yx + x4[1] * yy + x4[2] * yz),
                    sign * (x4[0] * xx + x4[1] * xy + x4[2] * xz),
                )
            ex, ey = X - d5 * s234, Y + d5 * c234  # the origin of frame 3
            rho = math.hypot(ex, ey)
            slot = 4 * branch + 2 * sign5
            if rho > big or rho < small:  # beyond the elbow's reach, by a hair or for good
                miss = rho - big if rho > big else small - rho
                # frame 3 moves at most d5 · band (_split_shift): most branches stay out
                border, shift = (big if rho > big else small), 0.0
                if S > WRIST_TOLERANCE and d5 * 0.5 * REACH_TOLERANCE >= miss * S:
                    spread = _shoulder_spread(px, py, r, root, d4, d6)
                    band = min(_SPLIT + spread, 0.5 * min(miss, REACH_TOLERANCE)) / S
                    shift = _split_shift(X, Y, q234, band, border, d5)
                elif S <= WRIST_TOLERANCE and prefer is not None:  # the nearest member that reaches
                    shift = _split_shift(X, Y, q234, _PI, border, d5)
                if shift != 0.0:  # within θ234's rounding (or its family): onto the border
                    q234 += shift
                    q6 -= shift if C >= 0.0 else -shift  # θ234 ± θ6 stays
                    s234, c234 = math.sin(q234), math.cos(q234)
                    ex, ey = X - d5 * s234, Y + d5 * c234
                    rho = math.hypot(ex, ey)
                    miss = max(rho - big, small - rho)
                if miss > _ROUNDOFF * big and missed is not None:
                    missed[slot] = miss
                if miss > REACH_TOLERANCE:
                    if misses is not None:
                        misses.append(miss)
                    continue
            c3 = min(1.0, max(-1.0, (ex * ex + ey * ey - a2 * a2 - a3 * a3) / two_a2a3))
            stretch = big - rho if big - rho > _ROUNDOFF * big else 0.0
            fold = rho - small if rho - small > _ROUNDOFF * big else 0.0
            product = stretch * (big + rho) * fold * (rho + small)
            s3 = math.sqrt(product) / abs(two_a2a3)
            heading = math.atan2(ey, ex)
            q5, q6 = _wrap_one(q5), _wrap_one(q6)
            for elbow in (1.0, -1.0) if s3 > 0.0 else (1.0,):
                q3 = math.atan2(elbow * s3, c3)
                q2 = _wrap_one(heading - math.atan2(a3 * elbow * s3, a2 + a3 * c3))
                q4 = _wrap_one(q234 - q2 - q3)
                found[slot + (elbow < 0.0)] = [q1, q2, _wrap_one(q3), q4, q5, q6]
            if s3 > 0.0 and abs(_wrap_one(found[slot][2] - found[slot + 1][2])) < (
                DUPLICATE_TOLERANCE
            ):
                suspect = True
    if len(shoulders) == 2 and abs(_wrap_one(shoulders[0] - shoulders[1])) < DUPLICATE_TOLERANCE:
        suspect = True
    if missed and retry and _shoulder_retry(rows, lengths, root, r, found, missed):
        suspect = True
    return _distinct_one(found) if suspect else found


def _shoulder_rounding(px, py, r, d4, d6):
    """How far rounding leaves ``root² = (r − d4)(r + d4)`` open: the wrist point's distance
    from the ``d4`` cylinder is known to ``_ROUNDOFF (|px| + |py| + d6 + d4)`` (as ``gap``),
    times ``r + d4``.  Floats or arrays."""
    return _ROUNDOFF * (abs(px) + abs(py) + (d6 + d4)) * (r + d4)


def _shoulder_range(px, py, r, root, d4, d6):
    """The two ends of the range of ``root`` that rounding leaves open (floats or arrays)."""
    delta = _shoulder_rounding(px, py, r, d4, d6)
    return np.sqrt(np.maximum(root * root - delta, 0.0)), np.sqrt(root * root + delta)


#: A shoulder whose ``root`` rounding leaves this far open (m) may hide a reachable elbow;
#: it can only where ``root`` is below ``_SHOULDER_NEAR`` (m; the range is about
#: ``1e-16 / root`` wide).
_SHOULDER_OPEN, _SHOULDER_NEAR = 1e-12, 1e-3


def _shoulder_retry(rows, lengths, root, r, found, missed) -> bool:
    """Near the shoulder singularity, fill the branches ``missed`` (their elbow just out of
    reach, dropped or on the reach tolerance: first row → miss) from the root, within
    ``root``'s rounding range, where the elbow misses least (a golden-section search); whether
    any branch was filled with an exact solution.

    There ``root = √((r − d4)(r + d4))``, the wrist point's offset in the arm's plane, is a
    double root: rounding of ``ε`` in ``r`` moves it by ``√ε``, and a solution from any root
    in that range reaches the pose to about ``ε`` (the wrist point's distance from the base
    axis is what changes, by as little as the rounding).  A stretched or folded elbow turns
    the root's ``√ε`` into a miss of about as much: the right root in the range removes it."""
    (_, _, _, px), (_, _, _, py) = rows[0], rows[1]
    low, high = (float(x) for x in _shoulder_range(px, py, r, root, lengths[3], lengths[5]))
    if high - low < _SHOULDER_OPEN:
        return False
    exact = _ROUNDOFF * (abs(lengths[1]) + abs(lengths[2]))
    changed = False
    for slot in missed:
        a, b = (-high if low == 0.0 else low), high
        c, d = b - _GOLDEN * (b - a), a + _GOLDEN * (b - a)
        fc, fd = _branch_miss(rows, lengths, slot, c), _branch_miss(rows, lengths, slot, d)
        for _ in range(_GOLDEN_STEPS):
            if min(fc[0], fd[0]) <= exact:
                break
            if fc[0] < fd[0]:
                b, d, fd = d, c, fc
                c = b - _GOLDEN * (b - a)
                fc = _branch_miss(rows, lengths, slot, c)
            else:
                a, c, fc = c, d, fd
                d = a + _GOLDEN * (b - a)
                fd = _branch_miss(rows, lengths, slot, d)
        best, where, solved = fc if fc[0] <= fd[0] else fd
        if best <= exact and solved[where] is not None:
            found[where], found[where + 1] = solved[where], solved[where + 1]
            changed = True
    return changed


_GOLDEN, _GOLDEN_STEPS = (math.sqrt(5.0) - 1.0) / 2.0, 60


def _branch_miss(rows, lengths, slot: int, x: float):
    """How far the elbow of branch ``slot`` (its first row) misses with the shoulder offset
    ``root = x`` (x < 0: the offset on the other side, the other θ1 branch, ``slot ^ 4``; inf
    where it has no solution at all), that branch's row and the solutions."""
    where = slot if x >= 0.0 else slot ^ 4
    short: dict[int, float] = {}
    solved = _solve_one(rows, lengths, root=abs(x), short=short)
    if where in short:
        return short[where], where, solved
    return (0.0 if solved[where] is not None else math.inf), where, solved


#: Near the wrist singularity θ234 and θ6 are told apart only by the pose's entries of order
#: ``S = sin θ5`` (``A``, ``B``), each rounded by a few ulps and moved by θ1's own error, so
#: each is known to about ``(_SPLIT + θ1's error) / S`` while ``θ234 ± θ6`` stays exact.
_SPLIT = 64.0 * np.finfo(float).eps


def _shoulder_spread(px, py, r, root, d4, d6):
    """How far θ1 may be off from rounding (floats or arrays): with ``root²`` known to ``δ``
    (:func:`_shoulder_rounding`), θ1 moves by about ``δ / (2 r root)``, and up to ``√δ / r``
    on the cylinder."""
    delta = _shoulder_rounding(px, py, r, d4, d6)
    return delta / (r * (root + delta**0.5))


def _split_shift(X: float, Y: float, q234: float, band: float, border: float, d5: float) -> float:
    """The smallest change of θ234 within ``band`` that brings the origin of frame 3 (``d5``
    from the wrist point ``(X, Y)`` in the arm's plane) to the distance ``border`` from the
    shoulder (full stretch or full fold); 0.0 where none does.

    Near the wrist singularity the computed θ234 can put frame 3 just out of the planar arm's
    reach although the pose is reachable: moving θ234 within its rounding (and θ6 the other
    way, which changes the pose by about ``S`` times the move, as little as the rounding did)
    puts it back on the border, an exact solution, where leaving it would drop every branch
    or miss by up to the reach tolerance.  The ``band`` is that rounding (``_SPLIT`` and θ1's
    spread, over ``S``), and no more than makes the pose's error smaller than the miss it
    removes (at most :data:`REACH_TOLERANCE`, a dropped branch's)."""
    A = math.hypot(X, Y)
    if A * d5 == 0.0:
        return 0.0
    # |frame 3|² = A² + d5² − 2 d5 A sin(θ234 − β), β the direction of the wrist point
    sigma = (A * A + d5 * d5 - border * border) / (2.0 * d5 * A)
    if not -1.0 <= sigma <= 1.0:
        return 0.0
    beta, half = math.atan2(Y, X), math.asin(sigma)
    best = 0.0
    for theta in (beta + half, beta + _PI - half):
        shift = _wrap_one(theta - q234)
        if abs(shift) <= band and (best == 0.0 or abs(shift) < abs(best)):
            best = shift
    return best


def _representative_one(X: float, Y: float, which: float, a2, a3, d5) -> float:
    """:func:`_representatives` for one pose and one of its two members (``which`` = ±1)."""
    A = math.hypot(X, Y)
    # d5 = 0 (a custom arm): the circle is a point, every θ234 reaches as far
    sigma = (A * A + d5 * d5 - (a2 * a2 + a3 * a3)) / (2.0 * d5 * A) if A * d5 != 0.0 else 0.0
    half = math.asin(min(1.0, max(-1.0, sigma)))
    beta = math.atan2(Y, X)
    return beta + half if which > 0 else beta + _PI - half


def _distinct_one(found: list[list[float] | None]) -> list[list[float] | None]:
    """``found`` with every branch that repeats an earlier one (within DUPLICATE_TOLERANCE,
    modulo 2π) set to None."""
    kept: list[list[float]] = []
    distinct: list[list[float] | None] = []
    for q in found:
        if q is not None and any(
            max(abs(_wrap_one(a - b)) for a, b in zip(q, other)) < DUPLICATE_TOLERANCE
            for other in kept
        ):
            q = None
        if q is not None:
            kept.append(q)
        distinct.append(q)
    return distinct


# ----------------------------------------------------------------------------- a stack


def _representatives(X, Y, a2, a3, d5) -> np.ndarray:
    """θ234 of the two representatives of a wrist-singular family (sin θ5 = 0).

    With sin θ5 = 0 only ``θ234 ± θ6`` is fixed by the pose: choosing θ234 moves the origin of
    frame 3 on a circle of radius d5 round the wrist point ``(X, Y)`` (in the arm's plane) and
    changes the planar arm's reach ρ.  The representatives take the two θ234, one on each side
    of the circle, whose ρ is nearest ``√(a2² + a3²)``: the elbow nearest a right angle.
    Shape ``(..., 2)`` for ``X``, ``Y`` of shape ``(...)``.
    """
    A = np.hypot(X, Y)
    across = 2.0 * d5 * A  # 0 where A = 0, or for an arm with d5 = 0 (then any θ234 does)
    sigma = (A * A + d5 * d5 - (a2 * a2 + a3 * a3)) / np.where(across != 0, across, np.inf)
    half = np.arcsin(np.clip(sigma, -1.0, 1.0))
    beta = np.arctan2(Y, X)
    return np.stack([beta + half, beta + np.pi - half], axis=-1)


def _split_shifts(X, Y, q234, band, border, d5) -> np.ndarray:
    """:func:`_split_shift` of arrays of the same shape."""
    A = np.hypot(X, Y)
    across = 2.0 * d5 * A
    sigma = (A * A + d5 * d5 - border * border) / np.where(across != 0.0, across, np.inf)
    ok = (across != 0.0) & (np.abs(sigma) <= 1.0)
    beta, half = np.arctan2(Y, X), np.arcsin(np.clip(sigma, -1.0, 1.0))
    shifts = wrap_angles(np.stack([beta + half, beta + np.pi - half]) - q234, check=False)
    shift = np.where(np.abs(shifts[0]) <= np.abs(shifts[1]), shifts[0], shifts[1])
    return np.where(ok & (np.abs(shift) <= band), shift, 0.0)


def _solve_stack(
    T: np.ndarray, lengths: tuple[float, ...], out: np.ndarray, prefer: np.ndarray | None = None
) -> np.ndarray:
    """All eight branches for flange poses ``T`` (N, 4, 4): writes the solutions into ``out``
    (N, 8, 6), row ``i`` the branch of bits (θ1 branch, θ5 sign, θ3 sign), NaN where there is
    none, and returns the (N, 8) mask of the real, distinct ones.  ``prefer`` (N,): at the
    wrist singularity, each pose's θ234 of the family member returned (:func:`_solve_one`).

    The same steps as :func:`_solve_one`, on whole columns: every intermediate has the
    branches in front and the poses last, ``(2, …, N)``, so each numpy operation runs over
    contiguous memory.  The second wrist branch is not solved again: flipping the sign of
    sin θ5 turns θ5 into −θ5, θ6 into θ6 + π and θ234 into θ234 + π, exactly.
    """
    d1, a2, a3, d4, d5, d6 = lengths
    n = len(T)
    xx, yx, zx, px, xy, yy, zy, py, xz, yz, zz, pz = np.ascontiguousarray(
        T.reshape(n, 16)[:, :12].T
    )
    wx, wy, wz = px - d6 * zx, py - d6 * zy, pz - d6 * zz
    with np.errstate(over="ignore"):  # a wrist 1e154 m away: out of reach, not a warning
        r2 = wx * wx + wy * wy
    r = np.sqrt(r2)
    gap = r - d4
    reach1 = (gap >= -REACH_TOLERANCE) & (r2 > 0.0) & (r2 < np.inf)
    gap[np.abs(gap) <= _ROUNDOFF * (np.abs(px) + np.abs(py) + (d6 + d4))] = 0.0
    root = np.sqrt(np.maximum(gap * (r + d4), 0.0))
    side = np.array([[1.0], [-1.0]])
    s1 = wx * d4 - side * (wy * root)  # (2, N): the two θ1 branches
    c1 = -(wy * d4 + side * (wx * root))
    norm = np.hypot(s1, c1)
    norm[norm == 0.0] = 1.0
    s1 /= norm
    c1 /= norm
    q1 = np.arctan2(s1, c1)
    A = xx * s1 - xy * c1  # sin θ5 cos θ6
    B = yy * c1 - yx * s1  # sin θ5 sin θ6
    C = zx * s1 - zy * c1  # cos θ5
    S = np.hypot(A, B)
    X, Y = c1 * wx + s1 * wy, wz - d1  # the wrist point in the arm's plane
    wrist = S <= WRIST_TOLERANCE
    safe = np.where(wrist, 1.0, S)
    c6, s6 = A / safe, B / safe
    s234 = C * (c6 * xz - s6 * yz) - S * zz
    c234 = c1 * (C * (c6 * xx - s6 * yx) - S * zx) + s1 * (C * (c6 * xy - s6 * yy) - S * zy)
    q234 = np.arctan2(s234, c234)
    q5 = np.arctan2(S, C)
    q6 = np.arctan2(B, A)
    # (2 θ1 branches, 2 θ5 signs, N)
    q234 = np.stack([q234, q234 + np.pi], axis=1)
    s234 = np.stack([s234, -s234], axis=1)
    c234 = np.stack([c234, -c234], axis=1)
    q5 = np.stack([q5, -q5], axis=1)
    q6 = np.stack([q6, q6 + np.pi], axis=1)
    X = X[:, None, :]
    if wrist.any():
        branch, pose = np.nonzero(wrist)
        if prefer is None:
            rep = _representatives(X[branch, 0, pose], Y[pose], a2, a3, d5)  # (k, 2)
        else:
            rep = np.repeat(prefer[pose, None], 2, axis=1)
        cr, sr = np.cos(rep), np.sin(rep)
        cos1, sin1 = c1[branch, pose][:, None], s1[branch, pose][:, None]
        dot_x = (cos1 * xx[pose, None] + sin1 * xy[pose, None]) * cr + xz[pose, None] * sr
        dot_y = (cos1 * yx[pose, None] + sin1 * yy[pose, None]) * cr + yz[pose, None] * sr
        sign = np.where(C[branch, pose] >= 0.0, 1.0, -1.0)[:, None]
        q234[branch, :, pose], s234[branch, :, pose], c234[branch, :, pose] = rep, sr, cr
        q6[branch, :, pose] = np.arctan2(-sign * dot_y, sign * dot_x)
        q5[branch, :, pose] = np.arctan2(S[branch, pose], C[branch, pose])[:, None]
    ex = X - d5 * s234  # the origin of frame 3 in the arm's plane
    ey = Y + d5 * c234
    rho = np.hypot(ex, ey)
    big, small = abs(a2) + abs(a3), abs(abs(a2) - abs(a3))
    miss = np.maximum(rho - big, small - rho)
    # near the wrist singularity: onto the border within θ234's rounding (_split_shift), where
    # frame 3, moving d5 · band at most, can get there
    reach5 = (d5 * 0.5 * REACH_TOLERANCE) / np.where(wrist, np.inf, S)[:, None, :]
    if prefer is not None:  # at the wrist singularity: the nearest member that reaches
        reach5 = np.where(wrist[:, None, :], np.inf, reach5)
    beyond = (miss > 0.0) & (miss <= reach5)
    if beyond.any():
        b, f, k = np.nonzero(beyond)
        border = np.where(rho[b, f, k] > big, big, small)
        spread = _shoulder_spread(px[k], py[k], r[k], root[k], d4, d6)
        limit = 0.5 * np.minimum(miss[b, f, k], REACH_TOLERANCE)
        band = np.minimum(_SPLIT + spread, limit) / S[b, k]
        if prefer is not None:
            band = np.where(wrist[b, k], np.pi, band)
        shift = _split_shifts(X[b, 0, k], Y[k], q234[b, f, k], band, border, d5)
        moved = shift != 0.0
        b, f, k, shift = b[moved], f[moved], k[moved], shift[moved]
        q234[b, f, k] += shift
        q6[b, f, k] -= np.where(C[b, k] >= 0.0, shift, -shift)  # θ234 ± θ6 stays
        s234[b, f, k], c234[b, f, k] = np.sin(q234[b, f, k]), np.cos(q234[b, f, k])
        ex[b, f, k] = X[b, 0, k] - d5 * s234[b, f, k]
        ey[b, f, k] = Y[k] + d5 * c234[b, f, k]
        rho[b, f, k] = np.hypot(ex[b, f, k], ey[b, f, k])
        miss[b, f, k] = np.maximum(rho[b, f, k] - big, small - rho[b, f, k])
    reach3 = (rho - big <= REACH_TOLERANCE) & (small - rho <= REACH_TOLERANCE)
    two_a2a3 = 2.0 * a2 * a3
    c3 = np.clip((ex * ex + ey * ey - (a2 * a2 + a3 * a3)) / two_a2a3, -1.0, 1.0)
    stretch = np.where(big - rho > _ROUNDOFF * big, big - rho, 0.0)
    fold = np.where(rho - small > _ROUNDOFF * big, rho - small, 0.0)
    s3 = np.sqrt(stretch * (big + rho) * fold * (rho + small)) / abs(two_a2a3)
    heading = np.arctan2(ey, ex)
    q3 = np.arctan2(s3, c3)  # elbow +; elbow − is −q3
    lean = np.arctan2(a3 * s3, a2 + a3 * c3)
    # θ1 (an arctangent) and ±θ3, ±θ5 (arctangents in [0, π]) are within [−π, π]: only −π
    # moves (to π, as wrap_angles does); θ2, θ4 and θ6 may be off by turns (wrapped below)
    minus3 = -q3
    for angles in (q1, minus3, q5):
        np.copyto(angles, np.pi, where=angles == -np.pi)
    # branch-major, the joints before the poses: the (48, n) transpose into ``out`` is then
    # its (n, 8, 6) layout, a plain 2-D copy
    grid = np.empty((2, 2, 2, 6, n))  # θ1 branch, θ5 sign, θ3 sign, joint, pose
    grid[..., 0, :] = q1[:, None, None, :]
    grid[:, :, 0, 1], grid[:, :, 1, 1] = heading - lean, heading + lean
    grid[:, :, 0, 2], grid[:, :, 1, 2] = q3, minus3
    grid[..., 3, :] = q234[:, :, None, :] - grid[..., 1, :] - grid[..., 2, :]
    grid[..., 4, :] = q5[:, :, None, :]
    grid[..., 5, :] = q6[:, :, None, :]
    odd = grid[..., 1::2, :]
    wrap_angles(odd, check=False, out=odd)
    keep = np.empty((2, 2, 2, n), dtype=bool)
    keep[...] = (reach1 & reach3)[:, :, None, :]
    keep[1] &= root > 0.0  # the θ1 branches merge
    keep[:, :, 1] &= s3 > 0.0  # θ3 = 0 or π: a double root
    np.copyto(grid, np.nan, where=~keep[:, :, :, None, :])  # no solution: a row of NaN
    q = out
    np.copyto(q.reshape(n, 48), grid.reshape(48, n).T)
    keep = np.ascontiguousarray(keep.reshape(8, n).T)
    # Rows can repeat only where two branches meet (see _solve_one): compare all pairs there.
    suspect = wrist.any(axis=0)
    shoulder_gap = np.abs(wrap_angles(q1[0] - q1[1], check=False))
    elbow_gap = np.abs(wrap_angles(2.0 * q3, check=False))
    suspect |= (root > 0.0) & (shoulder_gap < DUPLICATE_TOLERANCE)
    suspect |= ((s3 > 0.0) & (elbow_gap < DUPLICATE_TOLERANCE)).any(axis=(0, 1))
    if suspect.any():
        rows = q[suspect]
        kept = keep[suspect]
        pairs = rows[:, :, None, :] - rows[:, None, :, :]
        gap = np.abs(wrap_angles(pairs, check=False)).max(axis=-1)
        same = (gap < DUPLICATE_TOLERANCE) & kept[:, None, :] & np.tri(8, 8, -1, dtype=bool)
        kept &= ~same.any(axis=-1)
        keep[suspect] = kept
        q[suspect] = np.where(kept[..., None], rows, np.nan)
    # near the shoulder singularity, a branch whose elbow just misses: solved again pose by pose
    # (_shoulder_retry searches the shoulder's rounding range; rare)
    missed = (miss > _ROUNDOFF * big).any(axis=(0, 1)) & reach1[0] & (root < _SHOULDER_NEAR)
    if missed.any():
        low, high = _shoulder_range(px, py, r, root, d4, d6)
        retry = missed & (high - low >= _SHOULDER_OPEN)
        for i in np.flatnonzero(retry):
            rows = [
                found if found is not None else [np.nan] * 6
                for found in _solve_one(
                    T[i].tolist(), lengths, prefer=None if prefer is None else float(prefer[i])
                )
            ]
            q[i] = rows
            keep[i] = ~np.isnan(q[i, :, 0])
    return keep


#: Stacks are solved in blocks of this many poses, which keeps temporaries in cache.
_BLOCK = 1000
#: Up to this many poses, a stack is solved pose by pose (bench/ik_analytic.py).
_FEW = 13


def _solve_few(
    poses: list[list[list[float]]], lengths: tuple[float, ...], prefer: list[float] | None = None
) -> np.ndarray:
    """:func:`_solve_one` of each pose given as ``T.tolist()`` (with its ``prefer``, if given):
    (N, 8, 6), NaN rows where a branch has no solution or repeats one."""
    nan, flat = [math.nan] * 6, []
    for i, pose in enumerate(poses):
        for row in _solve_one(pose, lengths, prefer=None if prefer is None else prefer[i]):
            flat += nan if row is None else row
    return np.array(flat).reshape(len(poses), 8, 6)  # one flat list: a third of a nested one's cost


def _solve(
    T: np.ndarray, lengths: tuple[float, ...], prefer: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_solve_stack` block by block, without floating-point warnings (out-of-reach
    poses are expected): (N, 8, 6) branches, rows of NaN where the (N, 8) mask is False.
    ``prefer`` (N,): the θ234 to take at the wrist singularity (:func:`_solve_one`)."""
    n = len(T)
    if n == 0:
        return np.empty((0, 8, 6)), np.empty((0, 8), dtype=bool)
    if n <= _FEW:  # a few poses: the one-pose code, pose by pose, beats the stack's fixed cost
        q = _solve_few(T.tolist(), lengths, None if prefer is None else prefer.tolist())
        return q, ~np.isnan(q[..., 0])
    q, keep = np.empty((n, 8, 6)), np.empty((n, 8), dtype=bool)
    with np.errstate(invalid="ignore", divide="ignore"):
        for start in range(0, n, _BLOCK):
            block = slice(start, start + _BLOCK)
            keep[block] = _solve_stack(
                T[block], lengths, q[block], None if prefer is None else prefer[block]
            )
    return q, keep


def _flange_poses(
    robot: Robot, poses: np.ndarray, deviation: np.ndarray | None
) -> tuple[np.ndarray, tuple[int, ...], np.ndarray]:
    """Checked tool poses (..., 4, 4) (with their ``deviation`` from rigid, if measured) as the
    flange poses in DH frame 0 of their nearest rigid poses (:func:`nearest_rigid`), (N, 4, 4);
    their leading axes; and how far each rotation was moved to make it rigid (rad)."""
    lead = poses.shape[:-2]
    poses, skew = nearest_rigid(poses.reshape(-1, 4, 4), deviation=deviation)
    if not robot._plain:
        poses = flange_pose(robot, poses, check=False)
    return poses, lead, skew


def _wrist_singular(q: np.ndarray, valid: np.ndarray) -> np.ndarray:
    """Which poses of a stack of solutions ``q`` (N, 8, 6) (rows ``valid`` (N, 8)) are at the
    wrist singularity, where the solver returned representatives of a family: (N,) bool."""
    return (valid & (np.abs(np.sin(q[..., 4])) <= WRIST_TOLERANCE)).any(axis=1)


def _members(robot: Robot, T: np.ndarray, prefer: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`ik_analytic` of checked tool poses ``T`` (K, 4, 4) with, at the wrist singularity,
    the family member whose ``θ2 + θ3 + θ4`` is ``prefer`` (K,) (or, where its elbow does not
    reach, the nearest that does) in place of the two representatives: (K, 8, 6) rows, NaN
    where the (K, 8) mask is False.  What a path through the singularity continues with."""
    poses, _, _ = _flange_poses(robot, T, None)
    return _solve(poses, robot.lengths, prefer)


def _why_not(robot: Robot, goal: np.ndarray, poses: np.ndarray, valid: np.ndarray, i: int) -> str:
    if valid[i].any():
        return "unreachable within the joint limits: every closed-form solution is outside them"
    misses: list[float] = []
    _solve_one(poses[i].tolist(), robot.lengths, misses)
    return no_solution_reason(robot, goal.reshape(-1, 4, 4)[i], min(misses, default=0.0))


def ik_analytic(
    robot: Robot, T: ArrayLike, *, return_mask: bool = False
) -> np.ndarray | tuple[np.ndarray, np.ndarray]:
    """Every closed-form solution of a UR arm's inverse kinematics.

    Parameters
    ----------
    robot : Robot
    T : array_like, shape (4, 4) or (..., 4, 4)
        Tool poses in the robot's base frame (flange poses unless the robot has a tool).  A
        rotation further than 1e-14 from orthonormal (``check_transform`` accepts 1e-6) is
        solved as its nearest rotation (:func:`urkin.transforms.orthonormalize`): no
        configuration reaches a matrix that is not a rotation, and the solutions reach the
        nearest one exactly.
    return_mask : bool
        Also return the boolean mask of the real rows: (..., 8) for a stack of poses, and
        (k,), all True, for one pose (so that ``q, mask = ik_analytic(..., return_mask=True)``
        unpacks alike for both).

    Returns
    -------
    ndarray
        For one pose: shape (k, 6), ``k ≤ 8`` distinct exact solutions (``k = 0`` when the
        pose is out of reach), wrapped to (−π, π].  For a stack of shape (..., 4, 4): shape
        (..., 8, 6) with NaN in the rows that are not solutions (out of reach, or repeats of
        an earlier row at a singular pose), and with ``return_mask=True`` also the (..., 8)
        mask of real rows.  Row ``i`` of every pose is the same branch: bit 2 of ``i`` chooses
        the θ1 branch, bit 1 the sign of θ5 and bit 0 the sign of θ3 (elbow up or down).

    Examples
    --------
    >>> import urkin
    >>> ur5 = urkin.robot("ur5")
    >>> T = urkin.fk(ur5, [0.3, -1.2, 1.4, -0.6, 1.1, 0.2])
    >>> solutions = ik_analytic(ur5, T)
    >>> solutions.shape
    (8, 6)
    >>> bool(np.abs(urkin.fk(ur5, solutions) - T).max() < 1e-12)
    True
    >>> ik_analytic(ur5, np.stack([[T, T, T], [T, T, T]])).shape  # a (2, 3) grid of poses
    (2, 3, 8, 6)
    """
    robot = check_robot(robot)
    _check_lengths(robot)
    return_mask = return_mask is not False and flag(return_mask, "return_mask")
    goal, deviation = _checked_transform(T, ROTATION_TOLERANCE, "T")
    if goal.ndim == 2 and robot._plain:  # the scalar fast path: one flange pose, rigid
        rows = goal.tolist()
        if _is_rotation_one(rows, RIGID_TOLERANCE):
            found = [row for row in _solve_one(rows, robot.lengths) if row is not None]
            return _one_pose(found, return_mask)
    if goal.ndim == 3 and len(goal) <= _FEW and robot._plain:  # a few flange poses, rigid
        rows = goal.tolist()
        if all(_is_rotation_one(pose, RIGID_TOLERANCE) for pose in rows):
            q = _solve_few(rows, robot.lengths)
            return (q, ~np.isnan(q[..., 0])) if return_mask else q
    poses, lead, _ = _flange_poses(robot, goal, deviation)
    if lead == ():
        found = [row for row in _solve_one(poses[0].tolist(), robot.lengths) if row is not None]
        return _one_pose(found, return_mask)
    q, keep = _solve(poses, robot.lengths)  # rows of NaN where keep is False
    q, keep = unstack(q, lead), unstack(keep, lead)
    return (q, keep) if return_mask else q


def _one_pose(found: list, return_mask: bool) -> np.ndarray | tuple[np.ndarray, np.ndarray]:
    """One pose's solutions ``found`` (rows of six floats) as (k, 6), with a (k,) mask of
    True if asked."""
    q = np.array(found) if found else np.empty((0, 6))
    return (q, np.ones(len(q), dtype=bool)) if return_mask else q


def _whole_turns_into_limits(
    q: np.ndarray, near: np.ndarray, lower: np.ndarray, upper: np.ndarray
) -> np.ndarray:
    """The whole-turn equivalent of each angle of ``q`` nearest ``near`` (broadcast), pushed
    back inside ``[lower, upper]`` by as many whole turns as it takes (``near`` may be several
    turns out).  Angles whose joint has no equivalent inside stay outside: test the result."""
    turned = near + wrap_angles(q - near, check=False)
    turn = 2 * np.pi
    turned -= turn * np.maximum(np.ceil((turned - upper) / turn), 0.0)
    turned += turn * np.maximum(np.ceil((lower - turned) / turn), 0.0)
    return turned


def ik_closest(robot: Robot, T: ArrayLike, q_current: ArrayLike, *, tol: float = 1e-9) -> IKResult:
    """The closed-form solution nearest the current configuration, within the joint limits.

    Each solution is shifted joint by joint by multiples of 2π to the equivalent closest to
    ``q_current`` that respects the robot's joint limits (±2π on UR arms), and the solution
    whose shifted angles are nearest (Euclidean norm) wins.  This is what a trajectory
    follows: no joint jumps by a turn, and a branch is kept as long as it exists.

    Parameters
    ----------
    robot : Robot
    T : array_like, shape (4, 4) or (..., 4, 4)
        Tool poses.
    q_current : array_like, shape (6,) or (..., 6)
        The configuration(s) to stay close to: one for every pose, or one per pose.
    tol : float
        Tolerance of the verification of the returned solution (metres and radians).

    Returns
    -------
    IKResult
        With the leading axes of ``T``.  ``success`` is False (``q = q_current``, and the
        reason says why, with the distance) when the pose has no solution within the limits.

    Examples
    --------
    >>> import urkin
    >>> ur5 = urkin.robot("ur5")
    >>> q = np.array([0.3, -1.2, 1.4, -0.6, 1.1, 6.0])  # joint 6 beyond π: still within ±2π
    >>> result = ik_closest(ur5, urkin.fk(ur5, q), q + 0.01)
    >>> bool(result.success), bool(np.allclose(result.q, q))
    (True, True)
    """
    robot = check_robot(robot)
    _check_lengths(robot)
    positive(tol, "tol")
    goal, deviation = _checked_transform(T, ROTATION_TOLERANCE, "T")
    poses, lead, skew = _flange_poses(robot, goal, deviation)
    current = real(q_current, "q_current")
    if current.shape[-1:] != (6,) or current.shape[:-1] not in ((), lead):
        raise ValueError(
            "q_current must have shape (6,)"
            + (f" or {(*lead, 6)}" if lead else "")
            + f" for T of shape {goal.shape}; got {current.shape}"
        )
    largest = float(np.abs(current).max(initial=0.0))
    if largest > MAX_JOINT_ANGLE:
        raise _range_error(largest, "q_current")
    current = np.broadcast_to(current, (*lead, 6)).reshape(-1, 6)
    q, valid = _solve(poses, robot.lengths)
    # at the wrist singularity a family reaches the pose: its member that keeps the current
    # θ2 + θ3 + θ4 (and so, on a path through it, the current θ6) joins the candidates
    singular = _wrist_singular(q, valid)
    if singular.any():
        rows = np.flatnonzero(singular)
        extra_q, extra_valid = _solve(
            poses[rows], robot.lengths, current[rows, 1] + current[rows, 2] + current[rows, 3]
        )
        q = np.concatenate([q, np.full_like(q, np.nan)], axis=1)
        valid = np.concatenate([valid, np.zeros_like(valid)], axis=1)
        q[rows, 8:], valid[rows, 8:] = extra_q, extra_valid
    lower = np.array([lo for lo, _ in robot.joint_limits])
    upper = np.array([hi for _, hi in robot.joint_limits])
    shifted = _whole_turns_into_limits(q, current[:, None, :], lower, upper)
    inside = np.all((shifted >= lower) & (shifted <= upper), axis=-1) & valid
    distance = np.where(inside, np.linalg.norm(shifted - current[:, None, :], axis=-1), np.inf)
    best = np.argmin(distance, axis=1)
    rows = np.arange(len(poses))
    found = np.isfinite(distance[rows, best])
    chosen = np.where(found[:, None], shifted[rows, best], current)
    reasons = ["" if ok else _why_not(robot, goal, poses, valid, i) for i, ok in enumerate(found)]
    for i in np.flatnonzero(found & (skew > tol)):
        reasons[i] = skew_reason(skew[i], "tol", tol)
    return verified(robot, chosen, goal.reshape(-1, 4, 4), found, reasons, tol, tol, lead)
