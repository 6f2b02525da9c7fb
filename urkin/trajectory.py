"""Task-space paths sampled by arc length, orientation along them, and time scaling.

Paths
    :func:`line`, :func:`polyline`, :func:`square` and :func:`circle` build a :class:`Path`:
    its :attr:`~Path.length` is exact, :meth:`Path.at` gives the point at any arc length, and
    :meth:`Path.points` samples it so that every spacing is at most ``step`` and equal along
    each segment, every corner appears exactly once, and an open path's end point is included
    (a closed path's end is its start, sampled once).
Orientation
    :func:`pose_path` turns points into poses ``(M, 4, 4)`` with a constant orientation or one
    interpolated along the arc length (slerp: a constant angular rate about one axis).
Time scaling
    :func:`time_scaling` gives ``s(t)``, ``ṡ(t)`` and ``s̈(t)`` of a rest-to-rest motion (cubic,
    quintic or trapezoidal velocity) and :func:`minimum_time` the shortest duration under
    per-joint velocity and acceleration limits when every joint follows the same ``s(t)``;
    :func:`joint_trajectory` samples such a joint-space move as a :class:`Trajectory`, and
    :func:`via_trajectory` a piecewise-cubic one through via points at given times.
Tracking
    :func:`track` (from :mod:`urkin.tracking`) follows poses with warm-started IK.

Units are metres, radians and seconds; every function is batched over samples (no Python loop
over them).

Examples
--------
>>> import numpy as np
>>> square_path = square(center=(0.25, 0.1, 0.3), side=0.15, plane="yz")
>>> round(square_path.length, 12)
0.6
>>> pts = square_path.points(step=1e-3)
>>> pts.shape
(604, 3)
>>> gaps = np.linalg.norm(np.diff(pts, axis=0, append=pts[:1]), axis=1)
>>> bool(gaps.max() <= 1e-3), round(float(gaps.min() * 1e3), 4)
(True, 0.9934)
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from urkin._inputs import flag, positive, real, unit
from urkin.tracking import Tracking, track
from urkin.transforms import check_rotation, so3_exp, so3_log

__all__ = [
    "Path",
    "TimeScaling",
    "Tracking",
    "Trajectory",
    "circle",
    "joint_trajectory",
    "line",
    "minimum_time",
    "polyline",
    "pose_path",
    "square",
    "time_scaling",
    "track",
    "via_trajectory",
]

#: The coordinate planes a square or circle may lie in, as (first in-plane axis, second); the
#: normal is their cross product (``"yz"``: normal +x, as seed 000's paths).
PLANES = {"xy": (0, 1), "yz": (1, 2), "zx": (2, 0)}


def _point(x: ArrayLike, name: str) -> np.ndarray:
    array = np.array(real(x, name))  # a copy: a path keeps its own points
    if array.shape != (3,):
        raise ValueError(
            f"{name} must be a point (x, y, z) in metres, shape (3,); got {array.shape}"
        )
    return array


def _positive(x: float, name: str) -> float:
    value = real(x, name)
    if value.ndim != 0 or not value > 0:
        raise ValueError(f"{name} must be one number > 0; got {x!r}")
    return float(value)


def _plane_axes(plane: str | None, normal: ArrayLike | None) -> tuple[np.ndarray, np.ndarray]:
    """Two orthonormal in-plane axes (u, v) with u × v along the plane's normal."""
    if (plane is None) == (normal is None):
        raise ValueError("give the plane either by name (plane='xy', 'yz' or 'zx') or as normal")
    if plane is not None:
        if not isinstance(plane, str) or plane not in PLANES:
            raise ValueError(f"plane must be one of {', '.join(PLANES)}; got {plane!r}")
        eye = np.eye(3)
        return eye[PLANES[plane][0]], eye[PLANES[plane][1]]
    n = unit(_point(normal, "normal"), "normal")
    # u: the base axis least aligned with n, made perpendicular to it (deterministic)
    axis = np.eye(3)[int(np.argmin(np.abs(n)))]
    u = axis - (axis @ n) * n
    u /= np.linalg.norm(u)
    return u, np.cross(n, u)


def _step(step: float) -> float:
    return _positive(step, "step")


@dataclass(frozen=True)
class Path:
    """A path in space, parametrised by arc length.

    Build one with :func:`line`, :func:`polyline`, :func:`square` or :func:`circle`.

    Attributes
    ----------
    vertices : ndarray, shape (K, 3)
        The corners of a polyline (the first again at the end of a closed one); for a circle,
        its start point.
    closed : bool
        Whether the path ends where it starts.
    center, radius, axes :
        For a circle: its centre (m), radius (m) and in-plane axes ``(u, v)`` (the path is
        ``center + radius (cos φ u + sin φ v)`` for φ from ``start`` to ``start + 2π``);
        ``None`` for a polyline.
    start : float
        A circle's starting angle φ (rad).
    """

    vertices: np.ndarray
    closed: bool
    center: np.ndarray | None = None
    radius: float | None = None
    axes: tuple[np.ndarray, np.ndarray] | None = None
    start: float = 0.0

    @property
    def is_circle(self) -> bool:
        """Whether this is a circle (else a polyline)."""
        return self.radius is not None

    @property
    def segment_lengths(self) -> np.ndarray:
        """Length of each straight segment (m); a circle is one segment of length 2πr."""
        if self.is_circle:
            return np.array([2 * math.pi * self.radius])
        d = np.diff(self.vertices, axis=0)
        return np.hypot(np.hypot(d[:, 0], d[:, 1]), d[:, 2])  # no overflow of the squares

    @property
    def length(self) -> float:
        """Total arc length (m), exact."""
        return float(self.segment_lengths.sum())

    def at(self, s: ArrayLike) -> np.ndarray:
        """The point(s) at arc length ``s`` from the start (m), ``0 ≤ s ≤ length``.

        Returns shape ``s.shape + (3,)``.
        """
        s = real(s, "s")
        if np.any(s < -1e-12 * max(1.0, self.length)) or np.any(s > self.length * (1 + 1e-12)):
            raise ValueError(f"s must lie in [0, {self.length:.6g}] m, the path's length")
        s = np.clip(s, 0.0, self.length)
        if self.is_circle:
            phi = self.start + s / self.radius
            u, v = self.axes
            return self.center + self.radius * (
                np.cos(phi)[..., None] * u + np.sin(phi)[..., None] * v
            )
        ends = np.cumsum(self.segment_lengths)
        k = np.minimum(np.searchsorted(ends, s, side="right"), len(ends) - 1)
        begin = ends[k] - self.segment_lengths[k]
        fraction = (s - begin) / self.segment_lengths[k]
        a, b = self.vertices[k], self.vertices[k + 1]
        return a + fraction[..., None] * (b - a)

    def points(self, step: float = 1e-3) -> np.ndarray:
        """Samples ``(M, 3)``: every spacing ≤ ``step`` (m) and equal along each segment.

        A segment of length ``L`` is cut into the fewest equal pieces no longer than ``step``,
        with a margin of 1e-9 so that round-off can never make a spacing exceed ``step``: a
        segment whose length is a whole number of steps gets one piece more (a 0.15 m side at
        1 mm: 151 pieces of 0.993 mm).  Every corner appears once; an open path ends with its
        end point, a closed one with the sample before its start (the spacing from the last
        sample back to the first is ≤ ``step`` too).  A circle's samples are equally spaced in
        angle; their spacing is the chord, shorter than the arc (see :meth:`chord_error`).
        """
        lengths, pieces = self.segment_lengths, self._pieces(step)
        if self.is_circle:
            phi = self.start + np.arange(pieces[0]) * (2 * math.pi / pieces[0])
            u, v = self.axes
            return self.center + self.radius * (np.cos(phi)[:, None] * u + np.sin(phi)[:, None] * v)
        segment = np.repeat(np.arange(len(lengths)), pieces)
        first = np.repeat(np.cumsum(pieces) - pieces, pieces)
        fraction = (np.arange(pieces.sum()) - first) / np.repeat(pieces, pieces)
        a, b = self.vertices[segment], self.vertices[segment + 1]
        samples = a + fraction[:, None] * (b - a)
        return samples if self.closed else np.concatenate([samples, self.vertices[-1:]])

    def _pieces(self, step: float) -> np.ndarray:
        """How many equal pieces each segment is cut into for ``step``."""
        step = _step(step)
        with np.errstate(over="ignore"):
            pieces = np.floor(self.segment_lengths / (step * (1 - 1e-9))) + 1
        if not pieces.sum() <= MAX_SAMPLES:  # inf too
            raise ValueError(
                f"sampling a path of {self.length:.4g} m every step = {step:g} m takes more than "
                f"{MAX_SAMPLES:,} points: lengths are in metres (did you pass millimetres?), or "
                "use a larger step"
            )
        return pieces.astype(int)

    def chord_error(self, step: float = 1e-3) -> float:
        """Largest distance (m) between the path and the straight lines joining its samples:
        0 for a polyline, ``r (1 − cos(Δφ/2))`` for a circle sampled every ``Δφ``."""
        if not self.is_circle:
            return 0.0
        return float(self.radius * (1 - math.cos(math.pi / self._pieces(step)[0])))


#: The most samples :meth:`Path.points` takes (10 km of path at 1 mm).
MAX_SAMPLES = 10_000_000


def polyline(points: ArrayLike, closed: bool = False) -> Path:
    """The path through ``points`` (K, 3) in order, straight between them (m).

    With ``closed=True`` it returns from the last point to the first.  Two consecutive points
    that coincide are an error (a repeated corner is sampled twice by seed 000's square).

    Examples
    --------
    >>> polyline([[0, 0, 0], [0.3, 0, 0], [0.3, 0.4, 0]]).length
    0.7
    """
    closed = flag(closed, "closed")
    vertices = np.array(real(points, "points"))  # a copy: the path keeps its own corners
    if vertices.ndim != 2 or vertices.shape[1] != 3 or len(vertices) < 2:
        raise ValueError(f"points must have shape (K, 3) with K ≥ 2; got {vertices.shape}")
    if closed and np.array_equal(vertices[0], vertices[-1]):
        vertices = vertices[:-1]  # closing is what closed=True does
    if closed:
        vertices = np.concatenate([vertices, vertices[:1]])
    with np.errstate(over="ignore"):
        lengths = Path(vertices=vertices, closed=closed).segment_lengths
    if not np.isfinite(lengths).all():
        k = int(np.argmax(~np.isfinite(lengths)))
        raise ValueError(
            f"points {k} and {(k + 1) % (len(vertices) - closed)} are too far apart: their "
            "distance overflows a float (points are in metres)"
        )
    if np.any(lengths == 0.0):
        k = int(np.argmin(lengths))
        raise ValueError(
            f"points {k} and {(k + 1) % (len(vertices) - closed)} coincide: a "
            "path needs distinct consecutive points"
        )
    return Path(vertices=vertices, closed=closed)


def line(start: ArrayLike, end: ArrayLike) -> Path:
    """The straight path from ``start`` to ``end`` (m).

    Examples
    --------
    >>> line((0, 0, 0), (0.003, 0.004, 0)).points(step=1e-3).shape  # 5 mm: 6 pieces
    (7, 3)
    """
    return polyline(np.stack([_point(start, "start"), _point(end, "end")]))


def square(
    center: ArrayLike,
    side: float,
    plane: str | None = None,
    normal: ArrayLike | None = None,
) -> Path:
    """The closed square of side ``side`` (m) centred at ``center`` in a plane.

    The plane is named (``"xy"``, ``"yz"``, ``"zx"``: in-plane axes ``(u, v)`` in that order)
    or given by its ``normal`` (then ``u`` is the base axis least aligned with it, made
    perpendicular, and ``v = n × u``).  The corners are visited counter-clockwise about the
    normal, from ``center − side/2 (u + v)``: for ``plane="yz"`` the order of seed 000.

    Examples
    --------
    >>> square((0, 0, 0), 2.0, plane="xy").vertices[:, :2]
    array([[-1., -1.],
           [ 1., -1.],
           [ 1.,  1.],
           [-1.,  1.],
           [-1., -1.]])
    """
    c, half = _point(center, "center"), _positive(side, "side") / 2
    u, v = _plane_axes(plane, normal)
    corners = c + half * np.array([-u - v, u - v, u + v, -u + v])
    return polyline(corners, closed=True)


def circle(
    center: ArrayLike,
    radius: float,
    plane: str | None = None,
    normal: ArrayLike | None = None,
    start: float = 0.0,
) -> Path:
    """The full circle of ``radius`` (m) about ``center``, counter-clockwise about the normal.

    The plane is given as for :func:`square`; the circle starts at angle ``start`` (rad) from
    the in-plane axis ``u`` (for ``plane="yz"``, ``start=0``: seed 000's circle, from
    ``center + radius ŷ`` towards ``+z``).

    Examples
    --------
    >>> path = circle((0.25, 0.1, 0.3), 0.1, plane="yz")
    >>> round(path.length, 12) == round(2 * np.pi * 0.1, 12)
    True
    >>> len(path.points(1e-3)), path.chord_error(1e-3) < 1.3e-6
    (629, True)
    """
    c, r = _point(center, "center"), _positive(radius, "radius")
    u, v = _plane_axes(plane, normal)
    start = real(start, "start")
    if start.ndim:
        raise ValueError(f"start must be one angle (rad); got shape {start.shape}")
    start = float(start)
    first = c + r * (math.cos(start) * u + math.sin(start) * v)
    return Path(vertices=first[None], closed=True, center=c, radius=r, axes=(u, v), start=start)


def pose_path(
    points: Path | ArrayLike,
    R_start: ArrayLike | None = None,
    R_end: ArrayLike | None = None,
    step: float = 1e-3,
) -> np.ndarray:
    """Poses ``(M, 4, 4)`` at the path's samples: a constant orientation or one interpolated.

    Parameters
    ----------
    points : Path or array_like, shape (M, 3)
        A path (sampled with ``step``) or its samples (m).
    R_start : array_like, shape (3, 3), optional
        The orientation at the start (default: the identity, as seed 000).
    R_end : array_like, shape (3, 3), optional
        The orientation at the end.  Between the two the orientation turns about one fixed axis
        at a rate proportional to arc length (slerp): ``R_start exp(λ log(R_startᵀ R_end))``,
        ``λ`` the fraction of the length travelled (of a closed path's whole length, which ends
        back at its start; of the sample count for a path that stays put).  The shorter way
        round is taken; a turn of exactly π has no unique shorter way and is refused.
    step : float
        Sampling step (m) when ``points`` is a :class:`Path`.

    Examples
    --------
    >>> from urkin.transforms import rot_z
    >>> poses = pose_path(line((0, 0, 0), (0.1, 0, 0)), rot_z(0.0), rot_z(1.0), step=0.06)
    >>> poses.shape, round(float(np.arctan2(poses[1, 1, 0], poses[1, 0, 0])), 12)
    ((3, 4, 4), 0.5)
    """
    if isinstance(points, Path):
        samples = points.points(step)
    else:
        samples = real(points, "points")
        if samples.ndim != 2 or samples.shape[1] != 3 or len(samples) < 1:
            raise ValueError(f"points must have shape (M, 3); got {samples.shape}")
    R0 = np.eye(3) if R_start is None else check_rotation(R_start, name="R_start")
    if R0.shape != (3, 3):
        raise ValueError(f"R_start must be one rotation, shape (3, 3); got {R0.shape}")
    poses = np.zeros((len(samples), 4, 4))
    poses[:, :3, 3] = samples
    poses[:, 3, 3] = 1.0
    if R_end is None:
        poses[:, :3, :3] = R0
        return poses
    R1 = check_rotation(R_end, name="R_end")
    if R1.shape != (3, 3):
        raise ValueError(f"R_end must be one rotation, shape (3, 3); got {R1.shape}")
    turn = so3_log(R0.T @ R1)
    if np.linalg.norm(turn) > math.pi - 1e-9:
        raise ValueError(
            "R_end is turned by π from R_start: the shorter way round is not unique; add an "
            "intermediate orientation"
        )
    with np.errstate(over="ignore", invalid="ignore"):  # hypot does not overflow its squares
        d = np.diff(samples, axis=0)  # a difference or a sum still may: refused below
        travelled = np.r_[0.0, np.cumsum(np.hypot(np.hypot(d[:, 0], d[:, 1]), d[:, 2]))]
    total = points.length if isinstance(points, Path) else travelled[-1]  # closed: back to start
    if not (np.isfinite(travelled[-1]) and np.isfinite(total)):
        raise ValueError("points: the path's length overflows a float (it is beyond 1e308 m)")
    if total > 0:
        fraction = travelled / total
    elif len(samples) > 1:  # a path that stays put: the turn spread over its samples
        fraction = np.linspace(0.0, 1.0, len(samples))
    elif np.linalg.norm(turn) > 0.0:
        raise ValueError(
            "points is a single sample: it cannot hold both R_start and R_end; give at least "
            "two samples"
        )
    else:
        fraction = np.zeros(1)
    poses[:, :3, :3] = R0 @ so3_exp(fraction[:, None] * turn)
    return poses


# ------------------------------------------------------------------------------- time scaling

#: Peak ṡ·T and peak s̈·T² of each rest-to-rest profile (the trapezoid's with its default
#: cruise speed 1.5/T, accelerating for the first and last third of the motion).
_PEAKS = {
    "cubic": (1.5, 6.0),
    "quintic": (1.875, 10.0 / math.sqrt(3.0)),
}


@dataclass(frozen=True)
class TimeScaling:
    """A rest-to-rest time scaling ``s(t)`` from 0 to 1 over ``0 ≤ t ≤ T``.

    Call it with times ``t`` (s, any shape) to get ``(s, ṡ, s̈)``, each of ``t``'s shape;
    before 0 it rests at ``s = 0`` and after ``T`` at ``s = 1``.  At ``t = 0`` and ``t = T``
    it gives the motion's one-sided values (a cubic starts with ``s̈ = 6/T²``).

    Attributes
    ----------
    kind : str
        ``"cubic"``, ``"quintic"`` or ``"trapezoid"``.
    T : float
        Duration (s).
    peak_speed : float
        The largest ``ṡ`` (1/s).
    peak_acceleration : float
        The largest ``|s̈|`` (1/s²).
    """

    kind: str
    T: float
    peak_speed: float
    peak_acceleration: float

    def __call__(self, t: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        t = real(t, "t")
        tau = np.clip(t / self.T, 0.0, 1.0)
        moving = (t >= 0) & (t <= self.T)  # at 0 and T: the motion's own one-sided values
        T = self.T
        if self.kind == "cubic":
            s = tau * tau * (3 - 2 * tau)
            sd = 6 * tau * (1 - tau) / T
            sdd = (6 - 12 * tau) / T / T  # T**2 could overflow
        elif self.kind == "quintic":
            s = tau**3 * (10 - 15 * tau + 6 * tau * tau)
            sd = 30 * tau**2 * (1 - tau) ** 2 / T
            sdd = 60 * tau * (1 - tau) * (1 - 2 * tau) / T / T
        else:  # in τ, with the speed in units of 1/T and the acceleration in units of 1/T²
            V = self.peak_speed * T  # in (1, 2]
            # the fraction of T spent speeding up (and slowing down); for a profile that is
            # nearly all cruise, from the two peaks, since V − 1 then cancels (to 0 where the
            # acceleration is 1e16 times the speed)
            if V - 1.0 > _CRUISE:
                ramp, A = (V - 1.0) / V, V * V / (V - 1.0)
            else:
                ramp = (
                    self.peak_speed / self.peak_acceleration / T
                    if self.peak_acceleration > 0.0
                    else (V - 1.0) / V
                )
                A = V / ramp if ramp > 0.0 else math.inf  # inf: no sample is on a ramp
            rising, falling = tau < ramp, tau > 1.0 - ramp
            back = 1.0 - tau
            with np.errstate(over="ignore", invalid="ignore"):  # A = inf times a τ of none
                s = np.where(
                    rising,
                    0.5 * A * tau * tau,
                    np.where(falling, 1 - 0.5 * A * back * back, V * (tau - ramp / 2)),
                )
                sd = np.where(rising, A * tau, np.where(falling, A * back, V)) / T
                sdd = np.where(rising, A, np.where(falling, -A, 0.0)) / T / T
        return s, np.where(moving, sd, 0.0), np.where(moving, sdd, 0.0)


#: A trapezoid whose cruise speed is within this of ``1/T`` (in units of ``1/T``) is nearly all
#: cruise: its ramps are taken from its peaks.
_CRUISE = 1e-4


def time_scaling(kind: str, T: float, peak_speed: float | None = None) -> TimeScaling:
    """The rest-to-rest time scaling of ``kind`` lasting ``T`` seconds.

    Parameters
    ----------
    kind : {"cubic", "quintic", "trapezoid"}
        Cubic: ``s = 3τ² − 2τ³`` (``τ = t/T``), zero speed at both ends. Quintic:
        ``s = 10τ³ − 15τ⁴ + 6τ⁵``, zero speed and acceleration at both ends.  Trapezoid:
        constant acceleration, cruise, constant deceleration.
    T : float
        Duration (s), > 0.
    peak_speed : float, optional
        The trapezoid's cruise speed ``ṡ`` (1/s), between ``1/T`` (exclusive: all cruise)
        and ``2/T`` (a triangle: no cruise).  Default ``1.5/T``.

    Examples
    --------
    >>> ts = time_scaling("quintic", 2.0)
    >>> s, sd, sdd = ts(np.array([0.0, 1.0, 2.0]))
    >>> s.tolist(), sd.tolist(), ts.peak_speed
    ([0.0, 0.5, 1.0], [0.0, 0.9375, 0.0], 0.9375)
    """
    T = _positive(T, "T")
    _kind(kind)
    if kind in _PEAKS:
        if peak_speed is not None:
            raise ValueError(f"peak_speed is the trapezoid's; a {kind} time scaling has none")
        speed, acceleration = _PEAKS[kind]
        return _peaks(kind, T, speed / T, acceleration / T / T)  # T**2 could overflow
    v = 1.5 / T if peak_speed is None else _positive(peak_speed, "peak_speed")
    if not 1.0 < v * T <= 2.0:
        raise ValueError(
            f"peak_speed must lie in (1/T, 2/T] = ({1 / T:.6g}, {2 / T:.6g}] 1/s for T = {T:g} s; "
            f"got {v:.6g}"
        )
    return _peaks("trapezoid", T, v, v / (v * T - 1.0) * v)


def _kind(kind: str) -> None:
    """Check a time scaling's kind is one of the three names."""
    if not isinstance(kind, str) or kind not in ("cubic", "quintic", "trapezoid"):
        raise ValueError(f"kind must be 'cubic', 'quintic' or 'trapezoid'; got {kind!r:.60}")


def _peaks(kind: str, T: float, speed: float, acceleration: float) -> TimeScaling:
    """The time scaling, or a ValueError when ``T`` is so short that its peaks overflow."""
    if not (math.isfinite(speed) and math.isfinite(acceleration)):
        raise ValueError(
            f"T = {T:g} s is too short: the {kind} time scaling's peak speed and acceleration "
            "overflow"
        )
    return TimeScaling(kind, T, speed, acceleration)


def minimum_time(
    kind: str,
    distance: ArrayLike,
    max_velocity: ArrayLike,
    max_acceleration: ArrayLike,
) -> TimeScaling:
    """The fastest time scaling of ``kind`` that keeps every joint within its limits.

    Every joint follows the same ``s(t)``: joint ``i`` moves ``distance[i] · s(t)``, so its
    speed is ``|distance[i]| ṡ`` and its acceleration ``|distance[i]| s̈``.  The slowest joint
    (the bottleneck) sets the duration: for the cubic and quintic ``T`` is the smallest with
    both peaks within limits; for the trapezoid, the shortest bang-coast-bang profile (a
    triangle when the cruise speed is never reached).

    Parameters
    ----------
    kind : {"cubic", "quintic", "trapezoid"}
    distance : array_like, shape (n,)
        How far each joint moves (rad or m); not all zero.
    max_velocity, max_acceleration : array_like, shape (n,) or scalar
        Limits (> 0) per joint, in the units of ``distance`` per s and per s².

    Examples
    --------
    >>> ts = minimum_time("trapezoid", [1.0, 0.5], max_velocity=1.0, max_acceleration=2.0)
    >>> ts.T, ts.peak_speed, ts.peak_acceleration
    (1.5, 1.0, 2.0)
    """
    _kind(kind)
    d = np.abs(real(distance, "distance"))
    if d.ndim != 1 or not np.any(d > 0):
        raise ValueError("distance must be a vector (n,) of joint motions, not all zero")
    limits = []
    for value, name in ((max_velocity, "max_velocity"), (max_acceleration, "max_acceleration")):
        limit = real(value, name)
        if limit.ndim == 0:
            limit = np.broadcast_to(limit, d.shape)
        if limit.shape != d.shape or not np.all(limit > 0):
            raise ValueError(f"{name} must be > 0, one number or one per joint {d.shape}")
        limits.append(limit)
    moving = d > 0
    with np.errstate(over="ignore", under="ignore"):
        V = float(np.min(limits[0][moving] / d[moving]))  # largest ṡ every joint allows (1/s)
        A = float(np.min(limits[1][moving] / d[moving]))  # largest s̈ (1/s²)
    if not (0.0 < V < math.inf and 0.0 < A < math.inf):
        raise ValueError(
            "max_velocity and max_acceleration against distance give no finite, non-zero "
            f"duration (speed ratio {V:g} 1/s, acceleration ratio {A:g} 1/s²): the limits "
            "and the distances are many orders of magnitude apart"
        )
    if kind in _PEAKS:
        speed, acceleration = _PEAKS[kind]
        T = max(speed / V, math.sqrt(acceleration / A))
        if not T < math.inf:
            raise ValueError(
                f"max_velocity and max_acceleration are too small for these distances: the "
                f"move would take longer than {sys.float_info.max:.3g} s"
            )
        return time_scaling(kind, T)
    if V * V >= A:  # the cruise speed is never reached: a triangle
        T = 2.0 / math.sqrt(A)
        return TimeScaling("trapezoid", T, 2.0 / T, A)
    return TimeScaling("trapezoid", 1.0 / V + V / A, V, A)


@dataclass(frozen=True)
class Trajectory:
    """Joint positions, velocities and accelerations sampled in time.

    Attributes
    ----------
    t : ndarray, shape (M,)
        Times (s).
    q, qd, qdd : ndarray, shape (M, n)
        Joint positions (rad), velocities (rad/s) and accelerations (rad/s²).
    """

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray


def joint_trajectory(
    q_start: ArrayLike,
    q_end: ArrayLike,
    scaling: TimeScaling,
    samples: int = 100,
) -> Trajectory:
    """A straight joint-space move from ``q_start`` to ``q_end`` timed by ``scaling``.

    ``q(t) = q_start + s(t) (q_end − q_start)``, sampled at ``samples`` equally spaced times
    from 0 to ``scaling.T``.  (Joint angles are used as given: wrap them first if the move
    should take the shorter way round.)

    Examples
    --------
    >>> traj = joint_trajectory([0.0, 0.0], [1.0, -2.0], time_scaling("cubic", 2.0), samples=3)
    >>> traj.q.tolist(), traj.qd[1].tolist()
    ([[0.0, 0.0], [0.5, -1.0], [1.0, -2.0]], [0.75, -1.5])
    """
    q0, q1 = real(q_start, "q_start"), real(q_end, "q_end")
    if q0.ndim != 1 or q0.shape != q1.shape:
        raise ValueError(
            f"q_start and q_end must be vectors of one shape; got {q0.shape}, {q1.shape}"
        )
    if not isinstance(scaling, TimeScaling):
        raise TypeError("scaling must be a TimeScaling (from time_scaling or minimum_time)")
    _sample_count(samples)
    t = np.linspace(0.0, scaling.T, int(samples))
    s, sd, sdd = scaling(t)
    delta = q1 - q0
    return Trajectory(t, q0 + s[:, None] * delta, sd[:, None] * delta, sdd[:, None] * delta)


def _via_velocities(q: np.ndarray, t: np.ndarray) -> np.ndarray:
    """The heuristic via velocities: zero at the ends; at an interior via the mean of the two
    adjacent segment slopes where they have the same sign, else zero (per joint)."""
    slopes = np.diff(q, axis=0) / np.diff(t)[:, None]  # (K − 1, n)
    before, after = slopes[:-1], slopes[1:]
    same_sign = np.sign(before) * np.sign(after) > 0
    inner = np.where(same_sign, (before + after) / 2, 0.0)
    zero = np.zeros((1, q.shape[1]))
    return np.concatenate([zero, inner, zero])


def _sample_times(t_first: float, t_last: float, samples: int | None, dt: float | None):
    if samples is not None and dt is not None:
        raise ValueError("give samples or dt, not both")
    if dt is None:
        count = 100 if samples is None else samples
        _sample_count(count)
        return np.linspace(t_first, t_last, int(count))
    step = _positive(dt, "dt")
    duration = t_last - t_first
    # every dt from the first via, not past the last (a duration that is a whole number of
    # steps keeps its end despite round-off in duration / step)
    steps = duration / step + 1e-9
    if not steps < MAX_SAMPLES:  # inf too
        raise ValueError(
            f"dt = {step:g} s over {duration:g} s makes more than {MAX_SAMPLES:,} samples: use a "
            "larger dt"
        )
    count = math.floor(steps) + 1
    return np.minimum(t_first + step * np.arange(count), t_last)


def _sample_count(samples: int) -> None:
    """Check a number of samples: an integer from 2 to :data:`MAX_SAMPLES`."""
    what = f"an integer from 2 to {MAX_SAMPLES:,}"
    positive(samples, "samples", integer=True, what=what)
    if not 2 <= samples <= MAX_SAMPLES:
        raise ValueError(f"samples must be {what}; got {samples!r}")


def via_trajectory(
    q_via: ArrayLike,
    t_via: ArrayLike,
    qd_via: ArrayLike | None = None,
    *,
    samples: int | None = None,
    dt: float | None = None,
) -> Trajectory:
    """A piecewise-cubic joint trajectory through via points (Lynch & Park, §9.2).

    Between consecutive vias ``j`` and ``j + 1`` each joint follows the cubic that starts at
    ``q_via[j]`` with velocity ``qd_via[j]`` and ends at ``q_via[j + 1]`` with velocity
    ``qd_via[j + 1]`` after ``T_j = t_via[j + 1] − t_via[j]`` seconds.  With
    ``τ = (t − t_via[j]) / T_j`` it is written in the Hermite form::

        q = (1 − 3τ² + 2τ³) q_j + (3τ² − 2τ³) q_{j+1}
            + T_j (τ − 2τ² + τ³) q̇_j + T_j (τ³ − τ²) q̇_{j+1},

    whose weights are exactly 1 and 0 at ``τ = 0`` and ``τ = 1``: the trajectory passes
    through every via, with the via's velocity, exactly.  Positions and velocities are
    therefore continuous at the vias; **accelerations are not**: each segment has its own
    (linear in time) acceleration and it generally jumps at an interior via.  A sample at an
    interior via's time carries the acceleration of the segment that starts there (the last
    via's, of the last segment).

    Parameters
    ----------
    q_via : array_like, shape (K, n)
        The vias (rad, or m for a linear joint), K ≥ 2.
    t_via : array_like, shape (K,)
        When each via is reached (s), strictly increasing.
    qd_via : array_like, shape (K, n), optional
        The velocity at each via (rad/s).  Default: the classic heuristic — zero at the first
        and last via; at an interior via, per joint, the mean of the slopes
        ``(q_{j+1} − q_j) / T_j`` of the two segments that meet there when they have the same
        sign, else zero (the joint turns back, or stops, there).
    samples : int, optional
        Number of evenly spaced times from ``t_via[0]`` to ``t_via[-1]`` (both included).
        Default 100 when ``dt`` is not given either.
    dt : float, optional
        Instead of ``samples``: a time every ``dt`` seconds from ``t_via[0]``, up to
        ``t_via[-1]`` (included when the duration is a whole number of steps).

    Returns
    -------
    Trajectory
        ``t`` (M,), ``q``, ``qd``, ``qdd`` (M, n).

    Raises
    ------
    ValueError
        Naming the argument: wrong shapes, fewer than two vias, times not strictly
        increasing, NaN or infinite entries, both or bad ``samples`` / ``dt``.

    See Also
    --------
    joint_trajectory : one rest-to-rest move (two vias with zero velocities: the same cubic).

    Examples
    --------
    >>> traj = via_trajectory([[0.0], [1.0], [3.0], [2.0]], [0.0, 1.0, 2.0, 4.0], samples=9)
    >>> traj.t.tolist()
    [0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0]
    >>> traj.q[[0, 2, 4, 8], 0].tolist()  # the vias, at t = 0, 1, 2 and 4 s
    [0.0, 1.0, 3.0, 2.0]
    >>> traj.qd[[2, 4], 0].tolist()  # slopes 1 and 2 average to 1.5; 2 and -0.5 turn: 0
    [1.5, 0.0]
    """
    q = real(q_via, "q_via")
    t = real(t_via, "t_via")
    if q.ndim != 2 or len(q) < 2:
        raise ValueError(f"q_via must have shape (K, n) with K ≥ 2 vias; got {q.shape}")
    if t.shape != (len(q),):
        raise ValueError(f"t_via must have one time per via, shape ({len(q)},); got {t.shape}")
    gaps = np.diff(t)
    if np.any(gaps <= 0):
        k = int(np.argmax(gaps <= 0))
        raise ValueError(
            f"t_via must be strictly increasing; t_via[{k + 1}] = {t[k + 1]:g} s does not come "
            f"after t_via[{k}] = {t[k]:g} s"
        )
    if qd_via is not None:
        v = real(qd_via, "qd_via")
        if v.shape != q.shape:
            raise ValueError(
                f"qd_via must have one velocity per via and joint, shape {q.shape}; got {v.shape}"
            )
    times = _sample_times(float(t[0]), float(t[-1]), samples, dt)
    with np.errstate(all="ignore"):  # gaps too short for the vias are refused below
        if qd_via is None:
            v = _via_velocities(q, t)
        j = np.clip(np.searchsorted(t, times, side="right") - 1, 0, len(t) - 2)  # segment
        T = gaps[j][:, None]
        tau = ((times - t[j]) / gaps[j])[:, None]
        q0, q1, v0, v1 = q[j], q[j + 1], v[j], v[j + 1]
        tau2, tau3 = tau * tau, tau * tau * tau
        position = (
            (1 - 3 * tau2 + 2 * tau3) * q0
            + (3 * tau2 - 2 * tau3) * q1
            + T * (tau - 2 * tau2 + tau3) * v0
            + T * (tau3 - tau2) * v1
        )
        velocity = (
            (6 * tau2 - 6 * tau) * (q0 - q1) / T
            + (1 - 4 * tau + 3 * tau2) * v0
            + (3 * tau2 - 2 * tau) * v1
        )
        acceleration = (12 * tau - 6) * (q0 - q1) / T / T + (  # T * T could overflow
            (6 * tau - 4) * v0 + (6 * tau - 2) * v1
        ) / T
    if not all(np.isfinite(x).all() for x in (position, velocity, acceleration)):
        raise ValueError(
            f"t_via's shortest gap, {gaps.min():g} s, is too short for these vias (q_via up to "
            f"{np.abs(q).max():.3g}): the positions, velocities or accelerations overflow"
        )
    return Trajectory(times, position, velocity, acceleration)
