"""Scenes of obstacles — boxes, cylinders, spheres and capsules — and exact signed distances.

Every obstacle is convex, so the distance from a sphere to it is the distance from the
sphere's centre to the obstacle minus the radius; inside an obstacle the centre's distance is
negative (minus the depth to its surface), and the difference is how deep the sphere goes in.
:meth:`Scene.signed_distances` evaluates it for many points against every obstacle at once,
with no Python loop over points or obstacles of one kind.

Obstacles are given in the robot's base frame (DH frame 0 moved by the robot's ``base``), in
metres; sizes are full lengths (a box's edges, a cylinder's length), as a catalogue states them.
"""

from __future__ import annotations

import functools
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from urkin._inputs import real, unit
from urkin.transforms import check_rotation, orthonormalize

#: Boxes with a bounding ball at most this wide (m) are broad-phased in Scene._touches.
_SMALL = 0.3

#: Dot products along the last axis, ``Σ_i a[..., i] b[..., i]`` (broadcast): numpy's ``vecdot``
#: where there is one (numpy ≥ 2: a third of einsum's cost on the few hundred rows of a
#: collision check), else einsum.
_dot = getattr(np, "vecdot", None) or functools.partial(np.einsum, "...i,...i->...")


def _nonzero(mask: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`numpy.nonzero` of a 2-D bool array: the rows and columns of its True entries, in
    row-major order.  A large array is searched flat (numpy 2.4's 2-D search took 140 µs for
    50,000 entries, a flat one 23); a small one, where the flat search's extra steps cost more,
    by numpy's."""
    if mask.size < _FLAT_SEARCH:
        return np.nonzero(mask)
    flat = np.flatnonzero(mask)
    rows = flat // mask.shape[1]
    flat -= rows * mask.shape[1]
    return rows, flat


#: The largest radius (m) of a ball :meth:`Scene._touches` is asked about, for the bound of
#: its cull's round-off (a model's spheres are at most 2 m, grown by an edge check's margins).
_MAX_BALL = 4.0

#: Entries from which :func:`_nonzero` searches flat (measured: the two cost alike at 800).
_FLAT_SEARCH = 1024


def _offsets(Pt: np.ndarray, centres: np.ndarray) -> np.ndarray:
    """Points ``Pt`` (3, M) less each of ``centres`` (K, 3): (K, 3, M).  Differences first,
    then squares: far from the origin an expansion ``|p|² − 2 p·c + |c|²`` would lose the
    millimetres to round-off (at 5e5 m, 0.6 mm)."""
    return Pt[None, :, :] - centres[:, :, None]


def _squares(Pt: np.ndarray) -> np.ndarray:
    """The squared lengths of coordinate-major vectors ``Pt`` (3, M): (M,)."""
    out = Pt[0] * Pt[0]
    out += Pt[1] * Pt[1]
    out += Pt[2] * Pt[2]
    return out


__all__ = ["Box", "Capsule", "Cylinder", "Scene", "Sphere"]


#: The largest coordinate or size of an obstacle (m).  The tests square distances: far beyond
#: the robot's cell their round-off grows with the square of the coordinates, and from about
#: 1e154 m the squares overflow (an obstacle there would vanish from the checks).
FARTHEST = 1e6


def _far(value: float, name: str) -> ValueError:
    return ValueError(
        f"{name} reaches {value:g} m: obstacles are given in metres, within ±{FARTHEST:g} m of "
        "the robot (a larger scene loses the precision of the distance tests)"
    )


def _vector(x: ArrayLike, name: str, *, bounded: bool = True) -> np.ndarray:
    v = real(x, name)
    if v.shape != (3,):
        raise ValueError(f"{name} must be a 3-vector (metres); got shape {v.shape}")
    if bounded and np.abs(v).max() > FARTHEST:
        raise _far(float(np.abs(v).max()), name)
    return _frozen(v)


def _frozen(v: np.ndarray) -> np.ndarray:
    """A read-only copy of ``v``: an obstacle keeps its own numbers (a scene caches them, and
    an edit of the caller's array after the checks would bypass them)."""
    v = np.array(v, dtype=float)
    v.setflags(write=False)
    return v


def _length(x: float, name: str, *, zero_ok: bool = False) -> float:
    array = real(x, name)
    if array.ndim != 0:
        raise ValueError(f"{name} must be one number (metres); got shape {array.shape}")
    value = float(array)
    if value < 0 or (value == 0 and not zero_ok):
        raise ValueError(f"{name} must be positive (metres); got {value:g}")
    if value > FARTHEST:
        raise _far(value, name)
    return value


def _name(name: object, kind: str) -> None:
    if name is not None and not isinstance(name, str):
        raise TypeError(
            f"{kind} name must be a str or None; got {type(name).__name__} {name!r:.40}"
        )


@dataclass(frozen=True)
class Box:
    """A box: ``centre``, full edge lengths ``size`` along its own axes, and ``rotation`` (its
    axes in the base frame; identity by default)."""

    centre: ArrayLike
    size: ArrayLike
    rotation: ArrayLike | None = None
    name: str | None = None

    def __post_init__(self) -> None:
        _name(self.name, "box")
        object.__setattr__(self, "centre", _vector(self.centre, "box centre"))
        size = _vector(self.size, "box size")
        if np.any(size <= 0):
            raise ValueError(f"box size must be three positive edge lengths (m); got {size}")
        object.__setattr__(self, "size", size)
        R = np.eye(3) if self.rotation is None else check_rotation(self.rotation, name="rotation")
        if R.shape != (3, 3):
            raise ValueError(f"rotation must be one rotation matrix (3, 3); got shape {R.shape}")
        # the checks use Rᵀ as the inverse: a matrix 1e-6 from orthonormal (which
        # check_rotation accepts) would move a point 1e5 m from the centre by 0.1 m, so one
        # further than round-off from orthonormal is replaced by its nearest rotation
        if np.abs(R.T @ R - np.eye(3)).max() > 1e-15:
            R = orthonormalize(R)
        object.__setattr__(self, "rotation", _frozen(R))


@dataclass(frozen=True)
class Cylinder:
    """A solid cylinder with flat caps: ``centre``, unit ``axis`` direction, ``radius`` and full
    ``length`` along the axis."""

    centre: ArrayLike
    axis: ArrayLike
    radius: float
    length: float
    name: str | None = None

    def __post_init__(self) -> None:
        _name(self.name, "cylinder")
        object.__setattr__(self, "centre", _vector(self.centre, "cylinder centre"))
        object.__setattr__(
            self,
            "axis",
            _frozen(unit(_vector(self.axis, "cylinder axis", bounded=False), "cylinder axis")),
        )
        object.__setattr__(self, "radius", _length(self.radius, "cylinder radius"))
        object.__setattr__(self, "length", _length(self.length, "cylinder length"))


@dataclass(frozen=True)
class Sphere:
    """A ball: ``centre`` and ``radius``."""

    centre: ArrayLike
    radius: float
    name: str | None = None

    def __post_init__(self) -> None:
        _name(self.name, "sphere")
        object.__setattr__(self, "centre", _vector(self.centre, "sphere centre"))
        object.__setattr__(self, "radius", _length(self.radius, "sphere radius"))


@dataclass(frozen=True)
class Capsule:
    """The points within ``radius`` of the segment from ``a`` to ``b``."""

    a: ArrayLike
    b: ArrayLike
    radius: float
    name: str | None = None

    def __post_init__(self) -> None:
        _name(self.name, "capsule")
        object.__setattr__(self, "a", _vector(self.a, "capsule a"))
        object.__setattr__(self, "b", _vector(self.b, "capsule b"))
        object.__setattr__(self, "radius", _length(self.radius, "capsule radius"))


_KINDS = (
    ("boxes", Box, "box"),
    ("cylinders", Cylinder, "cylinder"),
    ("spheres", Sphere, "sphere"),
    ("capsules", Capsule, "capsule"),
)


@dataclass(frozen=True, eq=False)
class Scene:
    """Obstacles in the robot's base frame.

    Parameters
    ----------
    boxes, cylinders, spheres, capsules : sequence
        Obstacles of each kind: :class:`Box`, :class:`Cylinder`, :class:`Sphere`,
        :class:`Capsule` objects (or dicts of their arguments).

    Attributes
    ----------
    names : tuple of str
        One name per obstacle, boxes first, then cylinders, spheres and capsules (the order of
        :meth:`signed_distances`' columns): an obstacle's ``name``, or ``"box 2"`` etc.

    Examples
    --------
    >>> from urkin import planning
    >>> scene = planning.Scene(boxes=[planning.Box([0.5, 0, 0.2], [0.1, 0.4, 0.4], name="wall")])
    >>> scene.signed_distances([[0.3, 0, 0.2], [0.5, 0, 0.2]]).round(3)
    array([[ 0.15],
           [-0.05]])
    """

    boxes: Sequence[Box] = ()
    cylinders: Sequence[Cylinder] = ()
    spheres: Sequence[Sphere] = ()
    capsules: Sequence[Capsule] = ()
    names: tuple[str, ...] = field(init=False)

    def __post_init__(self) -> None:
        names: list[str] = []
        for attribute, kind, label in _KINDS:
            given = getattr(self, attribute)
            if given is None:
                given = ()
            if isinstance(given, (kind, dict)):
                given = (given,)
            if isinstance(given, (str, bytes)) or not isinstance(given, Iterable):
                raise TypeError(
                    f"{attribute} must be a sequence of planning.{kind.__name__} (or of dicts "
                    f"of its arguments); got {type(given).__name__}"
                )
            items = []
            for k, item in enumerate(given):
                if isinstance(item, dict):
                    try:
                        item = kind(**item)
                    except TypeError as error:
                        raise TypeError(f"{attribute}[{k}]: {error}") from None
                elif not isinstance(item, kind):
                    raise TypeError(
                        f"{attribute}[{k}] must be a planning.{kind.__name__} (or a dict of its "
                        f"arguments); got {type(item).__name__}"
                    )
                items.append(item)
                names.append(item.name if item.name else f"{label} {k}")
            object.__setattr__(self, attribute, tuple(items))
        object.__setattr__(self, "names", tuple(names))
        boxes = self.boxes
        # boxes: rows of Rᵀ stacked as one (3, 3B) matrix, so one product places every point
        # in every box's frame
        self._set(
            "_box_Rt",
            np.concatenate([b.rotation for b in boxes], axis=1) if boxes else np.zeros((3, 0)),
        )
        self._set(
            "_box_c",
            np.concatenate([b.rotation.T @ b.centre for b in boxes]) if boxes else np.zeros(0),
        )
        self._set("_box_h", np.concatenate([b.size / 2 for b in boxes]) if boxes else np.zeros(0))
        cyl = self.cylinders
        self._set("_cyl_c", np.array([c.centre for c in cyl]).reshape(-1, 3))
        self._set("_cyl_a", np.array([c.axis for c in cyl]).reshape(-1, 3))
        self._set("_cyl_r", np.array([c.radius for c in cyl]))
        self._set("_cyl_h", np.array([c.length / 2 for c in cyl]))
        sph = self.spheres
        self._set("_sph_c", np.array([s.centre for s in sph]).reshape(-1, 3))
        self._set("_sph_r", np.array([s.radius for s in sph]))
        cap = self.capsules
        self._set("_cap_a", np.array([c.a for c in cap]).reshape(-1, 3))
        self._set("_cap_d", np.array([c.b - c.a for c in cap]).reshape(-1, 3))
        self._set("_cap_r", np.array([c.radius for c in cap]))
        # for _touches: boxes and cylinders whose bounding ball is larger than _SMALL are tested
        # with every ball; the small ones and capsules only where their bounding balls meet the
        # ball (see _touches)
        bound = np.linalg.norm(self._box_h.reshape(-1, 3), axis=1)
        big = bound > _SMALL
        self._set("_box_R", np.array([b.rotation for b in boxes]).reshape(-1, 3, 3))
        self._set("_box_o", np.array([b.centre for b in boxes]).reshape(-1, 3))
        self._set("_box_hh", self._box_h.reshape(-1, 3))
        # every box axis-major, for _gaps2: row k·B + b is box b's axis k, so one product gives
        # (3B, M) local coordinates whose three (B, M) blocks add up without a reduction; the
        # big ones alike for _touches
        R = self._box_R
        self._set("_all_R", R.transpose(2, 0, 1).reshape(-1, 3))
        self._set(
            "_all_c", (R.transpose(0, 2, 1) @ self._box_o[..., None])[..., 0].T.reshape(-1, 1)
        )
        self._set("_all_h", self._box_hh.T.reshape(-1, 1))
        rows = np.tile(big, 3)  # the big boxes' rows, axis by axis
        for name in ("R", "c", "h"):
            self._set(f"_big_{name}", getattr(self, f"_all_{name}")[rows])
        cyl_bound = np.hypot(self._cyl_r, self._cyl_h)
        big_cyl = cyl_bound > _SMALL
        object.__setattr__(self, "_big_cyl", np.flatnonzero(big_cyl))
        cap_m = self._cap_a + self._cap_d / 2  # a bounding ball per capsule
        cap_bound = np.linalg.norm(self._cap_d, axis=1) / 2 + self._cap_r
        small_box, small_cyl = np.flatnonzero(~big), np.flatnonzero(~big_cyl)
        centres = np.concatenate([self._box_o[small_box], self._cyl_c[small_cyl], cap_m])
        radii = np.concatenate([bound[small_box], cyl_bound[small_cyl], cap_bound])
        # which obstacle each culled column stands for: its kind (0 box, 1 cylinder, 2 capsule)
        # and its index among the obstacles of that kind
        kinds = np.repeat([0, 1, 2], [len(small_box), len(small_cyl), len(cap_m)])
        object.__setattr__(self, "_small_kind", kinds)
        object.__setattr__(
            self,
            "_small",
            np.concatenate([small_box, small_cyl, np.arange(len(cap_m))]).astype(np.intp),
        )
        # the cull's expansion in coordinates about the culled obstacles' middle, whose
        # round-off, for a ball touching one of them, is bounded by their spread (not by how
        # far from the origin the scene is): the slack its test allows
        origin = centres.mean(axis=0) if len(centres) else np.zeros(3)
        local = centres - origin
        self._set("_small_origin", origin.reshape(3, 1))
        self._set(
            "_small_rows",
            np.vstack(
                [
                    -2.0 * local.T,
                    -2.0 * radii,
                    np.ones(len(radii)),
                    np.sum(local**2, axis=1) - radii**2,
                ]
            )
            .reshape(6, -1)
            .T,
        )
        spread = np.max(np.linalg.norm(local, axis=1) + radii, initial=0.0) + _MAX_BALL
        object.__setattr__(self, "_small_slack", 1e-9 + 64 * 2.3e-16 * spread**2)

    def _set(self, name: str, value: np.ndarray) -> None:
        value = np.ascontiguousarray(value, dtype=float)
        value.setflags(write=False)
        object.__setattr__(self, name, value)

    def __len__(self) -> int:
        return len(self.names)

    def __repr__(self) -> str:
        counts = ", ".join(f"{len(getattr(self, a))} {a}" for a, _, _ in _KINDS if getattr(self, a))
        return f"Scene({counts or 'empty'})"

    def signed_distances(self, points: ArrayLike) -> np.ndarray:
        """Signed distance from each point to each obstacle: positive outside, negative inside
        (minus the distance to the surface).

        Parameters
        ----------
        points : array_like, shape (..., 3)

        Returns
        -------
        ndarray, shape (..., len(scene))
            Columns in the order of :attr:`names`.
        """
        P = real(points, "points")
        if P.shape[-1:] != (3,):
            raise ValueError(f"points must have shape (..., 3); got shape {P.shape}")
        lead = P.shape[:-1]
        flat = P.reshape(-1, 3)
        return self._distances(flat).reshape(*lead, len(self))

    def _touches(self, Pt: np.ndarray, r: np.ndarray) -> np.ndarray:
        """Whether each ball (centres ``Pt`` (3, M), coordinate-major; radii ``r`` (M,)) touches
        an obstacle: (M,) bool, the same verdict as ``signed_distances <= r`` for a ball that is
        not within round-off of touching.

        Squared distances, no square roots but a cylinder's radial one.  Large boxes and
        cylinders (a bounding ball wider than 0.3 m: floors, walls, shelves) and spheres are
        tested with every ball, their coordinates for all balls from one matrix product; small
        boxes, small cylinders and capsules only where their bounding balls meet the ball (one
        more product finds where), which most balls do not.
        """
        M = Pt.shape[1]
        hit = np.zeros(M, dtype=bool)
        if not len(self) or not M:
            return hit
        # obstacle-major: arrays (obstacles, M), so reductions over obstacles run along M
        r2 = r * r
        if len(self._big_h):
            L = self._big_R @ Pt  # (3B, M) coordinates in each box's frame
            L -= self._big_c
            np.abs(L, out=L)
            L -= self._big_h
            np.maximum(L, 0.0, out=L)
            L *= L
            B = len(L) // 3
            S = L[:B] + L[B : 2 * B]
            S += L[2 * B :]
            hit = (S <= r2).any(axis=0)
        if len(self._small):
            # |p − c|² − (r + R)² as one product: [−2c, −2R, 1, |c|² − R²]·[p, r, |p|² − r², 1],
            # p and c about _small_origin
            A = np.empty((6, M))
            np.subtract(Pt, self._small_origin, out=A[:3])
            A[3] = r
            A[4] = _squares(A[:3])
            A[4] -= r2
            A[5] = 1.0
            k, m = _nonzero(self._small_rows @ A <= self._small_slack)
            if len(m):
                kind, index = self._small_kind[k], self._small[k]
                tests = (self._touch_boxes, self._touch_cylinders, self._touch_capsules)
                for code, test in enumerate(tests):  # the kinds of _small_kind, in order
                    pick = kind == code
                    if pick.any():
                        mm = m[pick]
                        hit[mm[test(Pt[:, mm].T, r[mm], index[pick])]] = True
        if len(self._big_cyl):
            k = self._big_cyl
            D = _offsets(Pt, self._cyl_c[k])
            t = np.einsum("ki,kim->km", self._cyl_a[k], D)  # along the axis
            u = np.sqrt(np.maximum(np.einsum("kim,kim->km", D, D) - t * t, 0.0))
            u -= self._cyl_r[k, None]
            np.maximum(u, 0.0, out=u)
            v = np.abs(t) - self._cyl_h[k, None]
            np.maximum(v, 0.0, out=v)
            hit |= (u * u + v * v <= r2).any(axis=0)
        if self.spheres:
            D = _offsets(Pt, self._sph_c)
            reach = r + self._sph_r[:, None]
            hit |= (np.einsum("kim,kim->km", D, D) <= reach * reach).any(axis=0)
        return hit

    def _gaps2(self, P: np.ndarray) -> np.ndarray:
        """The squared distance from each point ``P`` (M, 3) to the nearest obstacle, 0 inside
        one: (M,).  A ball of radius ``r`` touches an obstacle where it is at most ``r²`` (the
        verdict of :meth:`_touches`, but for round-off within reach of contact).

        Every point against every obstacle, no broad phase: for the few points of a single
        check, fewer array operations than :meth:`_touches`' culling."""
        Pt = P.T
        gaps = []
        if self.boxes:
            B = len(self.boxes)
            L = self._all_R @ Pt  # (3B, M) coordinates in each box's frame, axis-major
            L -= self._all_c
            np.abs(L, out=L)
            L -= self._all_h
            np.maximum(L, 0.0, out=L)
            L *= L
            S = L[:B] + L[B : 2 * B]
            S += L[2 * B :]
            gaps.append(S.min(axis=0))
        if self.cylinders:
            D = _offsets(Pt, self._cyl_c)
            t = np.einsum("ki,kim->km", self._cyl_a, D)
            u = np.sqrt(np.maximum(np.einsum("kim,kim->km", D, D) - t * t, 0.0))
            u -= self._cyl_r[:, None]
            np.maximum(u, 0.0, out=u)
            v = np.abs(t) - self._cyl_h[:, None]
            np.maximum(v, 0.0, out=v)
            gaps.append((u * u + v * v).min(axis=0))
        if self.spheres:
            D = _offsets(Pt, self._sph_c)
            e = np.sqrt(np.einsum("kim,kim->km", D, D)) - self._sph_r[:, None]
            np.maximum(e, 0.0, out=e)
            gaps.append((e * e).min(axis=0))
        if self.capsules:
            d = P[:, None, :] - self._cap_a  # (M, K, 3)
            length2 = np.sum(self._cap_d**2, axis=-1)
            s = np.einsum("mki,ki->mk", d, self._cap_d) / np.where(length2 > 0, length2, 1.0)
            d -= np.clip(s, 0.0, 1.0)[..., None] * self._cap_d
            e = np.sqrt(np.einsum("mki,mki->mk", d, d)) - self._cap_r
            np.maximum(e, 0.0, out=e)
            gaps.append((e * e).min(axis=1))
        return functools.reduce(np.minimum, gaps)

    def _touch_boxes(self, P: np.ndarray, r: np.ndarray, k: np.ndarray) -> np.ndarray:
        local = np.einsum("ni,nij->nj", P - self._box_o[k], self._box_R[k])
        q = np.maximum(np.abs(local) - self._box_hh[k], 0.0)
        return _dot(q, q) <= r * r

    def _touch_cylinders(self, P: np.ndarray, r: np.ndarray, k: np.ndarray) -> np.ndarray:
        d = P - self._cyl_c[k]
        t = _dot(d, self._cyl_a[k])
        u = np.sqrt(np.maximum(_dot(d, d) - t * t, 0.0)) - self._cyl_r[k]
        np.maximum(u, 0.0, out=u)
        v = np.maximum(np.abs(t) - self._cyl_h[k], 0.0)
        return u * u + v * v <= r * r

    def _touch_capsules(self, P: np.ndarray, r: np.ndarray, k: np.ndarray) -> np.ndarray:
        d = P - self._cap_a[k]
        seg = self._cap_d[k]
        length2 = np.sum(seg * seg, axis=1)
        s = np.clip(np.sum(d * seg, axis=1) / np.where(length2 > 0, length2, 1.0), 0.0, 1.0)
        e = d - s[:, None] * seg
        reach = r + self._cap_r[k]
        return np.sum(e * e, axis=1) <= reach * reach

    def _distances(self, P: np.ndarray) -> np.ndarray:
        """:meth:`signed_distances` of checked points (M, 3): (M, len(scene))."""
        parts = []
        if self.boxes:
            B = len(self.boxes)
            q = np.abs(P @ self._box_Rt - self._box_c) - self._box_h  # (M, 3B)
            q = q.reshape(len(P), B, 3)
            outside = np.sqrt(np.sum(np.maximum(q, 0.0) ** 2, axis=-1))
            parts.append(outside + np.minimum(q.max(axis=-1), 0.0))
        if self.cylinders:
            d = P[:, None, :] - self._cyl_c  # (M, C, 3)
            t = np.einsum("mci,ci->mc", d, self._cyl_a)
            radial = np.sqrt(np.maximum(np.sum(d * d, axis=-1) - t * t, 0.0))
            u = radial - self._cyl_r
            v = np.abs(t) - self._cyl_h
            outside = np.hypot(np.maximum(u, 0.0), np.maximum(v, 0.0))
            parts.append(outside + np.minimum(np.maximum(u, v), 0.0))
        if self.spheres:
            d = P[:, None, :] - self._sph_c
            parts.append(np.sqrt(np.sum(d * d, axis=-1)) - self._sph_r)
        if self.capsules:
            d = P[:, None, :] - self._cap_a  # (M, K, 3)
            length2 = np.sum(self._cap_d**2, axis=-1)
            s = np.clip(
                np.einsum("mki,ki->mk", d, self._cap_d) / np.where(length2 > 0, length2, 1.0),
                0.0,
                1.0,
            )
            e = d - s[..., None] * self._cap_d
            parts.append(np.sqrt(np.sum(e * e, axis=-1)) - self._cap_r)
        if not parts:
            return np.zeros((len(P), 0))
        return np.concatenate(parts, axis=-1) if len(parts) > 1 else parts[0]
