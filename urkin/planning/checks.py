"""Collision checks of a sphere model in a scene: configurations, clearances, straight edges.

Every function takes one configuration or a stack of them (DESIGN §2) and tests all the
configurations at once, as array operations with no Python loop over configurations, spheres or
obstacles.  :func:`is_free` and the edge checks test in two phases: each frame's spheres are
grouped under bounding balls of at most 10 cm, the balls are tested first, and only the spheres
of a ball that touches something are placed and tested (the verdicts are exactly those of
testing every sphere).  The base's spheres are left out of the scene tests: they never move,
so an obstacle that overlaps the base is a property of the scene, not of a configuration.
A stack of at most 40 configurations of a small model in a small scene skips the broad
phase: there, testing every sphere against every obstacle takes fewer array operations than
culling (the same verdicts).

Contact counts as collision: a configuration is free when every sphere is strictly apart from
every obstacle and from every sphere it is paired with.

Edges (:func:`edges_free`) are straight lines in joint space, checked at samples close enough
that **no sphere centre moves more than** ``resolution`` **metres between consecutive samples**.
A sphere centre's speed along an edge is at most ``Σ_j |Δq_j| R_j``, where ``R_j`` bounds its
distance to joint ``j``'s axis on the whole edge: at most ``ρ_j`` (its distance to its own
frame's origin plus the lengths ``√(a_i² + d_i²)`` of the links in between), and at most what
the distances at the edge's two ends allow, given how fast the joints after ``j`` can change it
(:func:`_travel`; about half the samples of ``ρ_j`` alone on random edges); :func:`edge_samples`
gives the count.  One edge checked alone takes ``ρ_j`` alone: twice the samples, checked in the
same few batches, for a tenth of the cost of the tighter bound.  A collision missed between two
free samples is therefore at most ``resolution / 2`` deep.  Most samples need no check of their
own: the middle sample of each block of four intervals is checked with every sphere grown by the
most that sphere can move over half the block, and where the grown arm is free the whole block
is proven free, between its samples too (:func:`_edges_free`); only the samples of the other
blocks are checked one by one.  The verdicts are those of checking every sample.  The samples
are taken coarse to fine (both ends, the middle, the quarters, …) across all the edges at once,
so a collision anywhere on any edge is usually found in the first batches.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from urkin._inputs import positive
from urkin.kinematics import _joints
from urkin.planning.scene import Scene, _dot, _nonzero, _squares
from urkin.planning.spheres import (
    FRAME_NAMES,
    SphereModel,
    _check_model,
    _frames,
    _placing_matrix,
    _tables,
)

__all__ = [
    "Clearance",
    "certify_edges",
    "clearance",
    "edge_samples",
    "edges_free",
    "explain",
    "is_free",
]

#: Default edge resolution: the most any sphere centre moves between samples (metres).
RESOLUTION = 0.01
#: The default ``finest`` of :func:`certify_edges` (metres).
FINEST = 1e-4


def _check(model: SphereModel, scene: Scene) -> None:
    _check_model(model)
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a planning.Scene; got {type(scene).__name__}")


def _collides(model: SphereModel, scene: Scene, Q: np.ndarray) -> np.ndarray:
    """Whether each configuration of ``Q`` (N, 6), checked, is in collision: (N,) bool.

    Two phases.  The groups' bounding balls (:func:`_groups`) are tested first, against the
    scene and against each other; only the spheres of a group whose ball touches an obstacle,
    and only the sphere pairs of two groups whose balls meet, are then placed and tested.  A
    group's ball holds every sphere of the group, so a sphere can touch nothing its group's
    ball does not: the verdicts are those of testing every sphere."""
    return _hits(model, scene, Q, None)[1]


def _hits(
    model: SphereModel, scene: Scene, Q: np.ndarray, grow: np.ndarray | None
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_collides` of ``Q`` (N, 6) grown by ``grow`` (N, S + P), and as they are: two
    (N,) bools, the first True wherever the second is.

    Grown, each sphere's radius grows by its column, and a tabulated mesh pair collides when
    its distance may be within its column (:func:`_edges_free` proves blocks of an edge free
    with it).  The broad phase tests the grown balls, and the spheres or pairs it finds are
    tested grown and, where they touch grown, as they are.  Without ``grow`` both are the
    verdicts as they are."""
    n = len(Q)
    if n <= _DENSE and len(model.pairs) + len(_dense(model).moving) * len(scene) <= _DENSE_WORK:
        return _dense_hits(model, scene, Q, grow)
    if n > _BLOCK_ROWS:  # in blocks whose arrays stay in the processor's cache
        parts = [
            _hits(
                model,
                scene,
                Q[k : k + _BLOCK_ROWS],
                None if grow is None else grow[k : k + _BLOCK_ROWS],
            )
            for k in range(0, n, _BLOCK_ROWS)
        ]
        return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])
    hit = np.zeros(n, dtype=bool)  # as they are
    grown = hit if grow is None else np.zeros(n, dtype=bool)
    if not len(model):
        return grown, hit
    F4 = _frames(model.robot, Q)  # (N, 8, 4, 4)
    points = _Points(model, F4)
    groups = _groups(model)
    g = len(groups.radii)
    sparse = n >= _SPARSE  # the balls placed frame by frame (_place_by_frame)
    if sparse:
        G = _place_by_frame(F4, groups.by_frame, g)  # (N, 3, g), coordinate-major
    else:
        G = _place(F4, groups.place)  # (N, g, 3)
    if grow is not None:  # a ball grows by the most any of its spheres grows
        grow_groups = grow[:, groups.filled].max(axis=2)  # (N, g)
    if len(groups.pairs):
        gp = len(groups.pairs)
        if sparse:  # from the placed balls
            d = np.take(G, groups.pairs[:, 0], axis=2)
            d -= np.take(G, groups.pairs[:, 1], axis=2)
            d *= d
            d2 = d[:, 0] + d[:, 1]
            d2 += d[:, 2]
        else:  # one product: the pairs' x, then y, then z differences (N, 3 gp)
            d = F4.reshape(n, 128) @ groups.apart
            d *= d
            d2 = d[:, :gp] + d[:, gp : 2 * gp]
            d2 += d[:, 2 * gp :]
        if grow is None:
            near = d2 <= groups.reach2
        else:
            reach = groups.reach + grow_groups[:, groups.pairs[:, 0]]
            reach += grow_groups[:, groups.pairs[:, 1]]
            near = d2 <= reach * reach
        if near.any():  # the sphere pairs of the near group pairs, listed by group pair
            rows, k = _nonzero(near)
            counts = groups.pair_count[k]
            offsets = np.repeat(groups.pair_start[k] - np.cumsum(counts) + counts, counts)
            rows = np.repeat(rows, counts)
            offsets += np.arange(len(rows))
            k = groups.pair_order[offsets]
            i, j = model.pairs[k, 0], model.pairs[k, 1]
            d = points(rows, i)
            d -= points(rows, j)
            d2 = _squares(d)
            reach = model.radii[i] + model.radii[j]
            hit[rows[d2 <= reach * reach]] = True
            if grow is not None:
                reach += grow[rows, i] + grow[rows, j]
                grown[rows[d2 <= reach * reach]] = True
    _mesh_hits(model, Q, grow, grown, hit)
    moving = groups.moving
    todo = np.flatnonzero(~hit)  # configurations not yet known to collide as they are
    if len(scene) and len(moving) and len(todo):
        if sparse:  # (3, T m): one flat take from the coordinate-major balls
            at = (todo[:, None] * (3 * g) + moving).reshape(-1)
            balls = np.take(G, at + _AXES * g)
        else:
            balls = G[todo[:, None], moving].reshape(-1, 3).T
        radii = _repeated(groups.radii[moving], len(todo))
        if grow is not None:
            radii = radii + grow_groups[todo[:, None], moving].reshape(-1)
        touch = scene._touches(balls, radii)
        rows, k = _nonzero(touch.reshape(len(todo), len(moving)))
        rows = todo[rows]
        if len(rows):
            members = groups.members[moving[k]]  # (H, m), −1 pads
            valid = members >= 0
            rows = np.repeat(rows, valid.sum(axis=1))
            spheres = members[valid]
            centres = points(rows, spheres)  # (3, H)
            if grow is None:
                hit[rows[scene._touches(centres, model.radii[spheres])]] = True
            else:
                touch = scene._touches(centres, model.radii[spheres] + grow[rows, spheres])
                rows, spheres, centres = rows[touch], spheres[touch], centres[:, touch]
                grown[rows] = True
                hit[rows[scene._touches(centres, model.radii[spheres])]] = True
    return grown, hit


#: Larger stacks are checked in blocks of this many configurations.  A block's arrays (every
#: sphere of every configuration placed: 0.6 MB for 51 spheres) stay in the processor's cache
#: and are reused by the memory allocator; one pass over 10,000 configurations allocates
#: arrays of several megabytes, which the allocator maps afresh from the system each time,
#: and takes 1.3 times as long.  Not a power of two: with rows 4 kB apart, the transposes of
#: a block compete for the same cache sets (bench/planning.py's batch of 10,000: 4.50 µs per
#: configuration with 512, 4.14 with 500).
_BLOCK_ROWS = 500

#: Stacks up to this many configurations are checked by :func:`_dense_hits`, when the model
#: and scene are small: self-collision pairs plus moving spheres times obstacles at most
#: ``_DENSE_WORK`` (a bare UR5 with 149 pairs and 47 moving spheres among 10 boxes: 619; with
#: VAMP's gripper among MotionBenchMaker's 15 obstacles, 1,576, where culling pays even for
#: one).
_DENSE, _DENSE_WORK = 40, 700


def _dense_hits(
    model: SphereModel, scene: Scene, Q: np.ndarray, grow: np.ndarray | None
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_hits` of a few configurations (N ≤ ``_DENSE``), with no broad phase: every
    sphere placed by one matrix product, every moving sphere against every obstacle
    (:meth:`Scene._gaps2`), every self-collision pair from the placed centres.  The same
    tests, in a third of the array operations where there are few configurations to cull."""
    n = len(Q)
    hit = np.zeros(n, dtype=bool)
    grown = hit if grow is None else np.zeros(n, dtype=bool)
    if not len(model) or not n:
        return grown, hit
    dense = _dense(model)
    X = _frames(model.robot, Q).reshape(n, 128) @ _placing(model)  # (N, 3 S) centres
    npair = len(model.pairs)
    if npair:
        d = X[:, dense.first]
        d -= X[:, dense.second]  # the pairs' x, then y, then z differences
        d *= d
        d2 = d[:, :npair] + d[:, npair : 2 * npair]
        d2 += d[:, 2 * npair :]
        _mark(hit, d2 <= dense.reach2)
        if grow is not None:
            reach = dense.reach + grow[:, model.pairs[:, 0]]
            reach += grow[:, model.pairs[:, 1]]
            _mark(grown, d2 <= reach * reach)
    _mesh_hits(model, Q, grow, grown, hit)
    m = len(dense.moving)
    if len(scene) and m:
        gaps2 = scene._gaps2(X[:, dense.placed].reshape(n * m, 3)).reshape(n, m)
        _mark(hit, gaps2 <= dense.radii2)
        if grow is not None:
            reach = dense.radii + grow[:, dense.moving]
            _mark(grown, gaps2 <= reach * reach)
    return grown, hit


def _mark(rows: np.ndarray, touching: np.ndarray) -> None:
    """Set ``rows`` (N,) where a row of ``touching`` (N, K) has a True (a whole-array test
    first: mostly there is none, and it costs a fraction of the row-wise one)."""
    if touching.any():
        rows |= touching.any(axis=1)


@dataclass(frozen=True)
class _Dense:
    """The arrays of :func:`_dense_hits`: ``moving``, the spheres not on the base, with their
    ``radii`` and ``radii2``; ``placed``, the columns of their centres among all the placed
    ones (x, y, z of each); ``first`` and ``second``, the columns of the self-collision pairs'
    two centres (the pairs' x, then their y, then their z); ``reach``, ``reach2``: the pairs'
    sums of radii and their squares."""

    moving: np.ndarray
    radii: np.ndarray
    radii2: np.ndarray
    placed: np.ndarray
    first: np.ndarray
    second: np.ndarray
    reach: np.ndarray
    reach2: np.ndarray


def _dense(model: SphereModel) -> _Dense:
    """The model's :class:`_Dense` (built once per model and kept on it)."""
    found = model.__dict__.get("_dense")
    if found is None:
        moving = np.flatnonzero(model.frames > 0)
        i, j = model.pairs[:, 0], model.pairs[:, 1]
        axes = np.arange(3)
        reach = model.radii[i] + model.radii[j]
        radii = model.radii[moving]
        found = _Dense(
            moving,
            radii,
            radii**2,
            (3 * moving[:, None] + axes).reshape(-1),
            (3 * i[None, :] + axes[:, None]).reshape(-1),
            (3 * j[None, :] + axes[:, None]).reshape(-1),
            reach,
            reach**2,
        )
        object.__setattr__(model, "_dense", found)
    return found


def _mesh_hits(model, Q, grow, grown, hit) -> None:
    """Mark in ``hit`` the configurations ``Q`` where a tabulated mesh pair may touch, and in
    ``grown`` where it may come within its column of ``grow`` (:func:`_hits`); every pair at
    once."""
    if not model.meshes:
        return
    margin = None if grow is None else grow[:, len(model) :]
    rows, pairs, bound = _tables(model.meshes).bounds(Q, margin)
    if not len(rows):
        return
    hit[rows[bound <= 0.0]] = True
    if grow is not None:
        grown[rows[bound <= margin[rows, pairs]]] = True


def _place(F: np.ndarray, M: np.ndarray) -> np.ndarray:
    """Centres fixed in frames, placed by the frames ``F`` (N, 8, 4, 4), with their placing
    matrix ``M`` (128, 3k) (:func:`_placing_matrix`): (N, k, 3), one matrix product."""
    return (F.reshape(len(F), 128) @ M).reshape(len(F), -1, 3)


def _repeated(radii: np.ndarray, n: int) -> np.ndarray:
    """``radii`` (k,) once for each of ``n`` configurations: (n k,)."""
    return np.repeat(radii[None], n, axis=0).reshape(-1)


def _placing(model: SphereModel) -> np.ndarray:
    """The placing matrix of the model's spheres (built once per model and kept on it)."""
    found = model.__dict__.get("_placing")
    if found is None:
        found = _placing_matrix(model.frames, model.centres)
        object.__setattr__(model, "_placing", found)
    return found


_SPARSE = 32


def _place_all(model: SphereModel, F4: np.ndarray) -> np.ndarray:
    """Every sphere centre of the model placed by the frames ``F4`` (N, 8, 4, 4): (N, 3, S),
    coordinate-major.  Frame by frame (:func:`_place_by_frame`) from ``_SPARSE``
    configurations on; for fewer, the placing matrix's one product (:func:`_place`) costs
    less than a product per frame."""
    n = len(F4)
    if n < _SPARSE:
        return _place(F4, _placing(model)).transpose(0, 2, 1)
    return _place_by_frame(F4, _by_frame(model), len(model))


def _place_by_frame(F4: np.ndarray, parts, k: int) -> np.ndarray:
    """Centres fixed in frames (``parts``: :func:`_frame_parts`, ``k`` of them) placed by the
    frames ``F4`` (N, 8, 4, 4): (N, 3, k), coordinate-major.  One product of each frame's 3 × 4
    rows with its centres: twelve multiplications per centre, where the placing matrix's
    product makes 128 per coordinate, mostly by zeros."""
    n = len(F4)
    out = np.empty((n, 3, k))
    for frame, where, C in parts:
        out[:, :, where] = (F4[:, frame, :3].reshape(3 * n, 4) @ C).reshape(n, 3, -1)
    return out


def _frame_parts(frames: np.ndarray, centres: np.ndarray):
    """Per frame holding centres: the frame, where its centres are among them (a slice where
    they are consecutive) and their homogeneous coordinates (4, k)."""
    parts = []
    for frame in np.unique(frames):
        where = np.flatnonzero(frames == frame)
        C = np.vstack([centres[where].T, np.ones(len(where))])
        if np.all(np.diff(where) == 1):
            where = slice(int(where[0]), int(where[-1]) + 1)
        parts.append((int(frame), where, C))
    return tuple(parts)


def _by_frame(model: SphereModel) -> tuple[tuple[int, slice | np.ndarray, np.ndarray], ...]:
    """The model's spheres by frame (:func:`_frame_parts`; built once per model and kept on
    it)."""
    found = model.__dict__.get("_by_frame")
    if found is None:
        found = _frame_parts(model.frames, model.centres)
        object.__setattr__(model, "_by_frame", found)
    return found


class _Points:
    """World centres of spheres in configurations, asked for as ``(rows (H,), spheres (H,))``
    and handed back coordinate-major, (3, H): gathered one by one while they are few, and once
    they are many (an eighth of every sphere in every configuration), every sphere placed in
    one matrix product and looked up by one flat :func:`numpy.take` (a fancy index with a
    slice between its arrays costs about six times as much)."""

    def __init__(self, model: SphereModel, F4: np.ndarray) -> None:
        self.model, self.F4, self.placed = model, F4, None

    def __call__(self, rows: np.ndarray, spheres: np.ndarray) -> np.ndarray:
        model = self.model
        k = len(model)
        if self.placed is None and 8 * len(rows) >= len(self.F4) * k:
            self.placed = _place_all(model, self.F4).reshape(-1)  # (N, 3, S), flat
        if self.placed is not None:
            return np.take(self.placed, rows * (3 * k) + spheres + _AXES * k)
        A = self.F4[rows, model.frames[spheres]]  # (H, 4, 4)
        return (_dot(A[:, :3, :3], model.centres[spheres][:, None]) + A[:, :3, 3]).T


#: The offsets of the x, y and z rows of a coordinate-major array, in units of its row length.
_AXES = np.arange(3)[:, None]


#: The largest radius of a group's bounding ball (m): a link's spheres are split until each
#: group's ball is no larger.
_GROUP_RADIUS = 0.1


@dataclass(frozen=True)
class _Groups:
    """Spheres of one frame grouped under bounding balls, for the broad phase of
    :func:`_collides`.

    ``frames``, ``centres``, ``radii``: each group's ball, fixed in its frame; ``members``
    (g, m): the spheres of each group, padded with −1 (``filled``: padded with the group's
    first sphere); ``moving``: the groups not on the base;
    ``pairs`` (gp, 2): group pairs holding at least one self-collision pair of spheres;
    ``pair_order`` (P,): the sphere pairs listed group pair by group pair, ``pair_start`` and
    ``pair_count`` (gp,): where each group pair's list starts and its length; ``place``: the
    balls' placing
    matrix (:func:`_placing_matrix`); ``apart`` (128, 3 gp): the placing matrix of the
    differences of the group pairs' centres, coordinate by coordinate; ``reach``: the sums
    of their radii, ``reach2`` their squares; ``by_frame``: the balls by frame
    (:func:`_frame_parts`)."""

    frames: np.ndarray
    centres: np.ndarray
    radii: np.ndarray
    members: np.ndarray
    filled: np.ndarray
    moving: np.ndarray
    pairs: np.ndarray
    pair_order: np.ndarray
    pair_start: np.ndarray
    pair_count: np.ndarray
    place: np.ndarray
    apart: np.ndarray
    reach: np.ndarray
    reach2: np.ndarray
    by_frame: tuple


def _groups(model: SphereModel) -> _Groups:
    """The model's groups (built once per model and kept on it)."""
    found = model.__dict__.get("_groups")
    if found is None:
        found = _build_groups(model)
        object.__setattr__(model, "_groups", found)
    return found


def _build_groups(model: SphereModel) -> _Groups:
    parts: list[np.ndarray] = []
    for frame in np.unique(model.frames):
        pending = [np.flatnonzero(model.frames == frame)]
        while pending:
            members = pending.pop()
            _, radius = _bound(model.centres[members], model.radii[members])
            if radius <= _GROUP_RADIUS or len(members) == 1:
                parts.append(members)
                continue
            # split across the widest spread of the centres, at its median
            spread = model.centres[members] - model.centres[members].mean(axis=0)
            axis = np.linalg.svd(spread, full_matrices=False)[2][0]
            side = spread @ axis <= np.median(spread @ axis)
            if side.all() or not side.any():
                side = np.arange(len(members)) < len(members) // 2
            pending += [members[side], members[~side]]
    width = max(len(m) for m in parts)
    members = np.full((len(parts), width), -1, dtype=np.intp)
    bounds = [_bound(model.centres[m], model.radii[m]) for m in parts]
    of_sphere = np.empty(len(model), dtype=np.intp)
    for g, m in enumerate(parts):
        members[g, : len(m)] = m
        of_sphere[m] = g
    frames = np.array([model.frames[m[0]] for m in parts], dtype=np.intp)
    by_pair = np.sort(of_sphere[model.pairs], axis=1) if len(model.pairs) else np.zeros((0, 2))
    pairs, pair_group = np.unique(by_pair.astype(np.intp), axis=0, return_inverse=True)
    centres = np.array([c for c, _ in bounds])
    radii = np.array([r for _, r in bounds])
    place = _placing_matrix(frames, centres)
    pairs = pairs.reshape(-1, 2)
    pair_group = pair_group.reshape(-1)
    count = np.bincount(pair_group, minlength=len(pairs))
    by_ball = place.reshape(128, -1, 3)
    apart = (by_ball[:, pairs[:, 0]] - by_ball[:, pairs[:, 1]]).transpose(0, 2, 1)
    return _Groups(
        frames,
        centres,
        radii,
        members,
        np.where(members >= 0, members, members[:, :1]),
        np.flatnonzero(frames > 0),
        pairs,
        np.argsort(pair_group, kind="stable"),
        np.cumsum(count) - count,
        count,
        place,
        np.ascontiguousarray(apart.reshape(128, -1)),
        radii[pairs[:, 0]] + radii[pairs[:, 1]],
        (radii[pairs[:, 0]] + radii[pairs[:, 1]]) ** 2,
        _frame_parts(frames, centres),
    )


def _bound(centres: np.ndarray, radii: np.ndarray) -> tuple[np.ndarray, float]:
    """A ball holding every ball (centres (k, 3), radii (k,)): centred between the extremes."""
    centre = np.min(centres - radii[:, None], axis=0) + np.max(centres + radii[:, None], axis=0)
    centre = centre / 2
    return centre, float(np.max(np.linalg.norm(centres - centre, axis=1) + radii))


def is_free(model: SphereModel, scene: Scene, q: ArrayLike) -> np.ndarray | bool:
    """Whether configurations are free of collisions, with the scene and with the arm itself.

    Parameters
    ----------
    model : SphereModel
    scene : Scene
    q : array_like, shape (6,) or (..., 6)
        Joint angles (rad).

    Returns
    -------
    bool, or ndarray of bool with the leading shape of ``q``

    Examples
    --------
    >>> import urkin
    >>> from urkin import planning
    >>> model = planning.sphere_model(urkin.robot("ur5"))
    >>> table = planning.Scene(boxes=[planning.Box([0, 0, -0.06], [2, 2, 0.1], name="table")])
    >>> planning.is_free(model, table, [0, -1.57, 0, -1.57, 0, 0])
    True
    >>> planning.is_free(model, table, [[0, -1.57, 0, -1.57, 0, 0], [0, 0.5, 0, 0, 0, 0]])
    array([ True, False])
    """
    _check(model, scene)
    Q, lead, _ = _joints(q, "q")
    free = ~_collides(model, scene, Q.reshape(-1, 6))
    return bool(free[0]) if lead == () else free.reshape(lead)


@dataclass(frozen=True)
class Clearance:
    """Signed clearances of configurations and the closest pair of each.

    Attributes
    ----------
    distance : ndarray
        The smallest signed distance between a sphere and an obstacle or a paired sphere
        (metres; negative: minus the depth of the deepest penetration), or the lower bound of
        a tabulated mesh pair's distance (:class:`~urkin.planning.spheres.MeshPair`; 0 or less
        where the meshes may touch).  ``inf`` when there is nothing to test.
    sphere : ndarray of int
        The arm's sphere of that pair (for a mesh pair: the nearest sphere of the first link,
        ``other`` that of the second).
    obstacle : ndarray of int
        The obstacle's index in ``scene.names``, or −1 when the pair is two of the arm's spheres.
    other : ndarray of int
        The other sphere of a self pair, or −1.
    meshes : ndarray of bool
        Whether the pair is a tabulated mesh pair (``distance`` its lower bound), rather than
        two spheres.
    """

    distance: np.ndarray
    sphere: np.ndarray
    obstacle: np.ndarray
    other: np.ndarray
    meshes: np.ndarray


def clearance(model: SphereModel, scene: Scene, q: ArrayLike) -> Clearance:
    """Signed distance of each configuration to collision, and the pair that sets it.

    Returns
    -------
    Clearance
        Arrays with the leading shape of ``q`` (0-d for one configuration).

    Examples
    --------
    >>> import urkin
    >>> from urkin import planning
    >>> model = planning.sphere_model(urkin.robot("ur5"))
    >>> table = planning.Scene(boxes=[planning.Box([0, 0, -0.06], [2, 2, 0.1], name="table")])
    >>> c = planning.clearance(model, table, [0, -1.57, 0, -1.57, 0, 0])
    >>> bool(c.distance > 0), model.names[c.sphere], table.names[c.obstacle]
    (True, 'shoulder sphere 1', 'table')
    """
    _check(model, scene)
    Q, lead, _ = _joints(q, "q")
    Q = Q.reshape(-1, 6)
    n = len(Q)
    best = np.full(n, np.inf)
    sphere = np.full(n, -1)
    obstacle = np.full(n, -1)
    other = np.full(n, -1)
    meshes = np.zeros(n, dtype=bool)
    if not n:  # an empty stack
        return Clearance(*(a.reshape(lead) for a in (best, sphere, obstacle, other, meshes)))
    W = model.place(Q)
    rows = np.arange(n)
    if len(scene) and len(model._moving):
        moving = model._moving
        gaps = scene._distances(W[:, moving].reshape(-1, 3)).reshape(n, len(moving), len(scene))
        gaps = gaps - model.radii[moving, None]
        flat = gaps.reshape(n, -1).argmin(axis=1)
        s, o = np.divmod(flat, len(scene))
        best = gaps[rows, s, o]
        sphere, obstacle = moving[s], o
    if len(model.pairs):
        i, j = model.pairs[:, 0], model.pairs[:, 1]
        gaps = np.linalg.norm(W[:, i] - W[:, j], axis=-1) - (model.radii[i] + model.radii[j])
        k = gaps.argmin(axis=1)
        closer = gaps[rows, k] < best
        best = np.where(closer, gaps[rows, k], best)
        sphere = np.where(closer, i[k], sphere)
        other = np.where(closer, j[k], -1)
        obstacle = np.where(closer, -1, obstacle)
    for pair in model.meshes:  # the nearest spheres of the two links name the pair
        gap = pair.lower_bound(Q)
        closer = gap < best
        if closer.any():
            i, j = (np.flatnonzero(model.frames == f) for f in pair.frames)
            d = np.linalg.norm(W[:, i, None] - W[:, None, j], axis=-1).reshape(n, -1)
            k = d.argmin(axis=1)
            best = np.where(closer, gap, best)
            sphere = np.where(closer, i[k // len(j)], sphere)
            other = np.where(closer, j[k % len(j)], other)
            obstacle = np.where(closer, -1, obstacle)
            meshes |= closer
    return Clearance(*(a.reshape(lead) for a in (best, sphere, obstacle, other, meshes)))


def explain(model: SphereModel, scene: Scene, q: ArrayLike) -> str:
    """A sentence about one configuration: the pair in deepest collision and how deep, or that
    it is free and the closest pair.

    Examples
    --------
    >>> import urkin
    >>> from urkin import planning
    >>> model = planning.sphere_model(urkin.robot("ur5"))
    >>> table = planning.Scene(boxes=[planning.Box([0, 0, -0.06], [2, 2, 0.1], name="table")])
    >>> planning.explain(model, table, [0, 0.5, 0, 0, 0, 0])  # doctest: +ELLIPSIS
    "in collision: upper arm sphere ... penetrates box 'table' by ... mm"
    """
    _check(model, scene)
    Q, lead, _ = _joints(q, "q")
    if lead != ():
        raise ValueError(f"explain takes one configuration, shape (6,); got shape {np.shape(q)}")
    c = clearance(model, scene, Q[0])
    if not math.isfinite(float(c.distance)):
        return "free: nothing to collide with (no obstacles and no self-collision pairs)"
    a = model.names[int(c.sphere)]
    if int(c.obstacle) >= 0:
        kind = _kind(scene, int(c.obstacle))
        b = f"{kind} '{scene.names[int(c.obstacle)]}'"
    else:
        b = f"{model.names[int(c.other)]} (self-collision)"
        if c.meshes:  # a tabulated mesh pair's bound, named by the two links
            pair = {model.frames[int(c.sphere)], model.frames[int(c.other)]}
            a, b = (FRAME_NAMES[f] for f in sorted(pair))
            if float(c.distance) <= 0:
                return f"in collision: the {a} and {b} meshes may touch (self-collision)"
            gap = float(c.distance) * 1000
            return f"free: the closest pair is the {a} and {b} meshes, at least {gap:.0f} mm apart"
    depth = float(c.distance) * 1000
    if depth <= 0:
        return f"in collision: {a} penetrates {b} by {-depth:.0f} mm"
    return f"free: the closest pair is {a} and {b}, {depth:.0f} mm apart"


def _offence(model: SphereModel, scene: Scene, q: np.ndarray) -> str:
    """:func:`explain` of a configuration in collision without its "in collision: ": the
    offending pair and the depth, for error messages that already say it collides."""
    return explain(model, scene, q).removeprefix("in collision: ")


def _kind(scene: Scene, index: int) -> str:
    for attribute, label in (("boxes", "box"), ("cylinders", "cylinder"), ("spheres", "sphere")):
        count = len(getattr(scene, attribute))
        if index < count:
            return label
        index -= count
    return "capsule"


def _reach(model: SphereModel) -> np.ndarray:
    """ρ (S, 6): a bound on each sphere centre's distance to each joint's axis (0 for the
    joints that do not move it); see the module notes."""
    robot = model.robot
    links = np.hypot(robot.a, robot.d)  # |o_i − o_{i−1}|, i = 1 … 6
    centres = model.centres.copy()
    tool = model.frames == 7
    centres[tool] = centres[tool] @ robot.tool[:3, :3].T + robot.tool[:3, 3]  # in frame 6
    own = np.linalg.norm(centres, axis=1)
    link = np.minimum(model.frames, 6)
    total = np.concatenate([[0.0], np.cumsum(links)])  # total[k] = Σ_{i ≤ k} |o_i − o_{i−1}|
    joint = np.arange(1, 7)  # joint j turns frames j … 6 about z_{j−1}, through o_{j−1}
    between = total[link][:, None] - total[joint - 1][None, :]
    rho = np.where(link[:, None] >= joint, own[:, None] + between, 0.0)
    return rho


def edge_samples(
    model: SphereModel, qa: ArrayLike, qb: ArrayLike, resolution: float = RESOLUTION
) -> np.ndarray | int:
    """The number of intervals each edge is cut into so that no sphere centre moves more than
    ``resolution`` metres between samples (see the module notes)."""
    _check_model(model)
    A, B, lead = _edge_ends(qa, qb)
    if not len(A):  # an empty stack
        positive(resolution, "resolution", what="a positive distance (m)")
        return np.zeros(lead, dtype=np.intp)
    counts = _intervals(model, A, B, resolution)
    return int(counts[0]) if lead == () else counts.reshape(lead)


def _edge_ends(qa: ArrayLike, qb: ArrayLike) -> tuple[np.ndarray, np.ndarray, tuple[int, ...]]:
    """Checked edge ends as (K, 6) arrays, and their leading shape."""
    A, lead, _ = _joints(qa, "qa")
    B, lead_b, _ = _joints(qb, "qb")
    if lead != lead_b:
        raise ValueError(
            f"qa and qb must have the same shape; got {np.shape(qa)} and {np.shape(qb)}"
        )
    return A.reshape(-1, 6), B.reshape(-1, 6), lead


def _intervals(model, A, B, resolution) -> np.ndarray:
    travel = _travels(model, A, B, resolution).max(axis=1, initial=0.0)
    return _counts(travel, resolution)


#: The most samples one call checks along its edges (about ten seconds of checks).
MAX_SAMPLES = 10_000_000


def _counts(travel: np.ndarray, resolution: float) -> np.ndarray:
    """The intervals each edge is cut into: (K,) from the edges' travels (K,) (m), or a
    ValueError naming ``resolution`` when all of them would take more than
    :data:`MAX_SAMPLES` samples."""
    with np.errstate(over="ignore"):
        counts = np.maximum(1.0, np.ceil(travel / resolution))
    if not counts.sum() <= MAX_SAMPLES:  # inf too
        raise ValueError(
            f"checking these edges every resolution = {resolution:g} m takes more than "
            f"{MAX_SAMPLES:,} samples: use a coarser resolution (the default is {RESOLUTION:g} m)"
        )
    return counts.astype(np.intp)


def _travels(model, A, B, resolution, rough: bool = False) -> np.ndarray:
    """:func:`_travel` of the edges ``A`` → ``B`` (K, S + P), after checking ``resolution``;
    with ``rough``, the simpler bound ``Σ_j |Δq_j| ρ_j`` (one product instead of some thirty
    array operations, and about twice the samples, which costs a single edge nothing: its
    samples are checked a batch at a time)."""
    positive(resolution, "resolution", what="a positive distance (m)")
    if not len(model):
        return np.zeros((len(A), len(model.meshes)))
    rho = model.__dict__.get("_rho")
    if rho is None:
        rho = _reach(model)
        object.__setattr__(model, "_rho", rho)
    if rough:
        dq = np.abs(B - A)
        out = np.empty((len(A), len(model) + len(model.meshes)))
        np.matmul(dq, rho.T, out=out[:, : len(model)])
        _mesh_speeds(model, dq, out)
        return out
    return _travel(model, rho, A, B)


def _mesh_speeds(model: SphereModel, dq: np.ndarray, out: np.ndarray) -> None:
    """The tabulated mesh pairs' columns of :func:`_travel` from the joint changes ``dq``
    (K, 6), written into the last columns of ``out``."""
    if model.meshes:
        tables = _tables(model.meshes)
        joints = tables.columns.reshape(-1, 2)
        out[:, len(model) :] = np.einsum("kpj,pj->kp", dq[:, joints], tables.reach)


def _travel(model: SphereModel, rho: np.ndarray, A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """Bounds on the speeds along each edge ``A`` → ``B`` (K, 6), in metres per edge: of each
    sphere centre (the most it can move along the edge; module notes), then of each
    tabulated mesh pair (the most its lower bound can fall along the edge): (K, S + P); the
    largest of a row bounds every centre's move.

    The distance ``r_j`` of a centre from joint ``j``'s axis depends only on the joints after
    ``j``, so along the edge it changes at most at the rate ``T_j = Σ_{m>j} |Δq_m| R_m`` where
    ``R_m`` bounds ``r_m``; from its values at the two ends, ``r_j ≤ (r_j(0) + r_j(1) + T_j) / 2``
    everywhere on the edge (and ``≤ ρ_j``).  Taken from the last joint back, each ``R_j``
    bounds the next ``T``; the speed is at most ``Σ_j |Δq_j| R_j``.

    A mesh pair's column is ``Σ |Δq_j| reach_j`` over its two joints: the most its table's
    lower bound (:meth:`~urkin.planning.spheres.MeshPair.lower_bound`, which the checks
    test) can fall along the edge, so that a check grown by it proves what checking every
    sample would find (the meshes' true distance may fall less: a tighter bound on it would
    prove pieces whose samples the table still calls in contact)."""
    K = len(A)
    F4 = _frames(model.robot, np.concatenate([A, B]))  # (2K, 8, 4, 4)
    # r_j: the centres' x and y in frame j − 1, whose z axis is joint j's axis
    across = F4[:, :6, :3, :2].transpose(0, 2, 1, 3).reshape(2 * K, 3, 12)
    xy = _place(F4, _placing(model)) @ across  # (2K, S, 12)
    xy -= (F4[:, :6, None, :3, 3] @ F4[:, :6, :3, :2]).reshape(2 * K, 1, 12)
    xy *= xy
    r = np.sqrt(xy[..., 0::2] + xy[..., 1::2]).transpose(2, 0, 1)  # (6, 2K, S)
    mid = r[:, :K] + r[:, K:]
    mid *= 0.5  # (6, K, S)
    dq = np.abs(B - A)
    half = dq.T[..., None] * 0.5  # (6, K, 1)
    S = len(model)
    out = np.zeros((K, S + len(model.meshes)))
    H = out[:, :S]  # T / 2 (halving is exact: the same bounds, in fewer operations)
    R = np.empty((K, S))  # R_j
    for j in range(5, -1, -1):  # T = Σ_{m>j} |Δq_m| R_m
        np.add(mid[j], H, out=R)
        np.minimum(R, rho[:, j], out=R)
        R *= half[j]
        H += R
    H *= 2.0
    _mesh_speeds(model, dq, out)
    return out


def edges_free(
    model: SphereModel,
    scene: Scene,
    qa: ArrayLike,
    qb: ArrayLike,
    resolution: float = RESOLUTION,
) -> np.ndarray | bool:
    """Whether straight joint-space edges from ``qa`` to ``qb`` are free, ends included.

    Parameters
    ----------
    model : SphereModel
    scene : Scene
    qa, qb : array_like, shape (6,) or (..., 6)
        The ends of each edge.
    resolution : float
        The most any sphere centre moves between consecutive samples (metres): a collision
        missed between two samples is at most half as deep.

    Returns
    -------
    bool, or ndarray of bool with the leading shape of ``qa``

    Examples
    --------
    >>> import urkin
    >>> from urkin import planning
    >>> model = planning.sphere_model(urkin.robot("ur5"))
    >>> table = planning.Scene(boxes=[planning.Box([0, 0, -0.06], [2, 2, 0.1], name="table")])
    >>> up = [0, -1.57, 0, -1.57, 0, 0]
    >>> planning.edges_free(model, table, up, [1, -1.57, 0, -1.57, 0, 0])  # turn about the base
    True
    >>> planning.edges_free(model, table, up, [0, 1.57, 0, -1.57, 0, 0])  # swing down through it
    False
    """
    _check(model, scene)
    A, B, lead = _edge_ends(qa, qb)
    if not len(A):  # an empty stack
        positive(resolution, "resolution", what="a positive distance (m)")
        return np.ones(lead, dtype=bool)
    # one edge: the rough speed bound (more samples, which one edge's batches absorb, for a
    # tenth of the bound's cost); a stack: the tighter bound, since every sample costs there
    speeds = _travels(model, A, B, resolution, rough=len(A) == 1)
    free = _edges_free(model, scene, A, B, speeds, resolution)
    return bool(free[0]) if lead == () else free.reshape(lead)


def certify_edges(
    model: SphereModel,
    scene: Scene,
    qa: ArrayLike,
    qb: ArrayLike,
    finest: float = FINEST,
) -> np.ndarray | bool:
    """Whether straight joint-space edges are proven free: no sphere touches an obstacle or a
    paired sphere, and no tabulated mesh pair may touch, **anywhere** on the edge (not only
    at samples).

    Each edge is cut into pieces over which no sphere moves more than ``4 · finest · 2^7``;
    the middle of each piece is checked with every sphere grown by the most it can move over
    half the piece, which, where it is free, proves the whole piece free (a pair's gap shrinks
    by at most what both spheres move).  Pieces not proven are cut in three and checked again,
    all the edges' pieces of a round in one batch, until every piece is proven, a middle
    collides as it is (the edge is not free), or a piece is down to ``finest``: an edge that stays
    within ``finest`` of contact is not proven (False), though it may be free (so are the
    edges still open when a round would check more than :data:`MAX_SAMPLES` pieces).

    Parameters
    ----------
    model : SphereModel
    scene : Scene
    qa, qb : array_like, shape (6,) or (..., 6)
        The ends of each edge.
    finest : float
        The smallest move (metres) of any sphere over a piece that is still cut into parts.

    Returns
    -------
    bool, or ndarray of bool with the leading shape of ``qa``

    Examples
    --------
    >>> import urkin
    >>> from urkin import planning
    >>> model = planning.sphere_model(urkin.robot("ur5"))
    >>> table = planning.Scene(boxes=[planning.Box([0, 0, -0.06], [2, 2, 0.1], name="table")])
    >>> up = [0, -1.57, 0, -1.57, 0, 0]
    >>> planning.certify_edges(model, table, up, [1, -1.57, 0, -1.57, 0, 0])
    True
    >>> planning.certify_edges(model, table, up, [0, 1.57, 0, -1.57, 0, 0])
    False
    """
    _check(model, scene)
    A, B, lead = _edge_ends(qa, qb)
    positive(finest, "finest", what="a positive distance (m)")
    if not len(A):  # an empty stack
        return np.ones(lead, dtype=bool)
    proven = _proven(model, scene, A, B, _travels(model, A, B, finest), finest)
    return bool(proven[0]) if lead == () else proven.reshape(lead)


def _proven(model, scene, A, B, speeds, finest) -> np.ndarray:
    """:func:`certify_edges` of checked edges (K, 6) with their speed bounds (K, S + P)."""
    travel = speeds.max(axis=1, initial=0.0)
    proven = np.ones(len(A), dtype=bool)
    # first pieces: a coarse start, a few rounds of cutting from the finest
    with np.errstate(over="ignore"):
        counts = np.maximum(1.0, np.ceil(travel / (4 * finest * 2**_CERTIFY_START)))
    if not counts.sum() <= MAX_SAMPLES:  # inf too
        raise ValueError(
            f"certifying these edges to finest = {finest:g} m starts from more than "
            f"{MAX_SAMPLES:,} pieces: use a larger finest (the default is {FINEST:g} m)"
        )
    counts = counts.astype(np.intp)
    edge = np.repeat(np.arange(len(A)), counts)
    lo = (np.arange(len(edge)) - np.repeat(np.cumsum(counts) - counts, counts)) / counts[edge]
    width = 1.0 / counts[edge]
    while len(edge):
        half = width / 2
        Q = A[edge] + (lo + half)[:, None] * (B[edge] - A[edge])
        grown, hit = _hits(model, scene, Q, speeds[edge] * (half * (1 + 1e-9))[:, None])
        proven[edge[hit]] = False  # a collision: not free
        open_ = grown & proven[edge]
        small = open_ & (travel[edge] * width <= finest)
        proven[edge[small]] = False  # still not proven at the finest: within reach of contact
        open_ &= proven[edge]
        if _CERTIFY_CUT * np.count_nonzero(open_) > MAX_SAMPLES:  # too many pieces within reach
            proven[edge[open_]] = False
            break
        edge, lo, width = edge[open_], lo[open_], width[open_] / _CERTIFY_CUT
        edge, lo, width = (np.repeat(a, _CERTIFY_CUT) for a in (edge, lo, width))
        lo += np.tile(_CUTS, len(edge) // _CERTIFY_CUT) * width  # the parts
    return proven


#: :func:`certify_edges`' first pieces (sphere moves up to ``4 · finest · 2^_CERTIFY_START``)
#: and the parts a piece not proven is cut into.  Measured on the paths of MotionBenchMaker's
#: UR5 problems (shortcuts and final re-checks): thirds from ``2^7`` take 0.90 of the time of
#: halves from ``2^6`` (fewer rounds, each a batch whose cost is mostly fixed); ``2^6`` and
#: ``2^8`` with thirds, and quarters, cost more.
_CERTIFY_START, _CERTIFY_CUT = 7, 3
_CUTS = np.arange(_CERTIFY_CUT)


#: Samples in the first batch of an edge check (at least one per edge), the smallest batch
#: after it and how much each batch is larger than the one before.  The first batch is as
#: large as a check without a broad phase goes (``_DENSE``): a single edge's first pass
#: then mostly fits in one call, whose cost hardly depends on its size (measured on 0.75 rad
#: edges: 1.7 calls per edge with 16, 1.05 with 40, and 13 % less time).
_FIRST, _BATCH, _GROWTH = _DENSE, 64, 4
#: Intervals of an edge one sample proves free (even): checked with every sphere grown by the
#: most a centre can move over half as many intervals, the block's middle sample stands for
#: the whole block.
_BLOCK = 4


def _edges_free(
    model,
    scene,
    A,
    B,
    speeds,
    resolution,
    prefix: bool = False,
    known: int = 0,
    prove: bool = True,
) -> np.ndarray:
    """Edges (K, 6) → (K,) free: every sample free, with each edge cut into
    ``n = ceil(travel / resolution)`` intervals (``speeds`` (K, S + P): :func:`_travel`;
    ``travel``, the largest of a row).

    Two passes, each coarse samples first across all the edges, in batches, skipping the edges
    already found in collision.  The first pass checks the middle sample of every block of
    ``_BLOCK`` intervals with each sphere grown by the most it can move over half a block
    (``_BLOCK / 2 · speed / n``; a mesh pair's distance likewise): where that grown model is
    free, no sphere can reach an obstacle or another sphere anywhere on the block (a pair's
    gap shrinks by at most what both spheres move), so the block's samples are all free.
    Where it is not, the middle is checked as it is too, in the same call (a collision there
    blocks the edge at once).  The first pass also checks the samples after the last whole
    block and the ends.  The second pass checks the other samples of the blocks the first
    could not prove free.  The verdicts are those of
    checking every sample, with far fewer checks where the arm keeps clear of everything.

    ``known`` ends are not checked again: 1, the starts are known free (a tree's node, a
    waypoint); 2, both ends are.  With ``prefix``, only the free prefix of the edges matters
    (a chain of pieces: nothing after the first blocked piece is used): every edge after a
    blocked one is reported blocked without being checked further.  Without ``prove``, one
    pass checks every sample (a rough look at a coarse resolution, where grown spheres would
    prove little)."""
    if len(A) == 1:
        return np.array([_edge_free(model, scene, A[0], B[0], speeds[0], resolution, known, prove)])
    counts = _counts(speeds.max(axis=1, initial=0.0), resolution)
    samples = counts + 1
    first = np.cumsum(samples) - samples  # each edge's first sample in the flat arrays
    edge = np.repeat(np.arange(len(A)), samples)
    index = np.arange(len(edge)) - first[edge]
    n = counts[edge]
    middle, known_free, plain = _roles(index, n, known, prove)
    free = np.ones(len(A), dtype=bool)
    # the first pass: the blocks' middles, grown, and the other samples it must check
    pick = np.flatnonzero(middle | plain)
    half = np.where(middle[pick], (_BLOCK / 2) * (1 + 1e-9), 0.0) / n[pick]
    grown = speeds[edge[pick]] * half[:, None]  # (picked, S + P)
    hit, touched = _check_samples(model, scene, A, B, edge, index, n, pick, grown, free, prefix)
    if not free.any():
        return free
    proven = known_free.copy()
    proven[pick[~hit]] = True  # free as it is
    done = pick[middle[pick] & ~touched]  # free grown: its whole block too
    for offset in range(1, _BLOCK // 2 + 1):
        proven[done - offset] = True
        proven[done + offset] = True
    # the second pass: every sample not proven free, on the edges still free
    rest = np.flatnonzero(~proven & free[edge])
    if len(rest):
        _check_samples(model, scene, A, B, edge, index, n, rest, None, free, prefix)
    return free


def _edge_free(model, scene, a, b, speed, resolution, known, prove) -> bool:
    """:func:`_edges_free` of one edge ``a`` → ``b`` (6,), ``speed`` (S + P,): the same samples,
    grown alike, with the bookkeeping of its sample count done once (:func:`_plan`)."""
    n = int(_counts(speed.max(initial=0.0), resolution))
    plan = _plan(n, known, prove)
    step = b - a
    touched = np.zeros(len(plan.first), dtype=bool)
    for part in plan.batches:
        Q = a + plan.t[part, None] * step
        grow = speed * plan.half[part, None] if prove else None
        touched[part], hit = _hits(model, scene, Q, grow)
        if hit.any():
            return False
    if not prove:
        return True
    proven = plan.known.copy()
    proven[plan.first] = True  # free as they are
    done = plan.first[plan.middle & ~touched]  # free grown: their whole blocks too
    for offset in range(1, _BLOCK // 2 + 1):
        proven[done - offset] = True
        proven[done + offset] = True
    rest = plan.order[~proven[plan.order]]
    for part in _batches(len(rest)):
        if _hits(model, scene, a + (rest[part] / n)[:, None] * step, None)[1].any():
            return False
    return True


@dataclass(frozen=True)
class _Plan:
    """How :func:`_edge_free` checks an edge of ``n`` intervals: ``first``, the samples of the
    first pass, coarse first (``t``: where they are on the edge; ``half``: how far each grows,
    in intervals times ``1 / n``, 0 for the plain ones; ``middle``: which are blocks'
    middles), in ``batches`` (slices); ``known``, the samples known free; ``order``, every
    sample, coarse first."""

    first: np.ndarray
    t: np.ndarray
    half: np.ndarray
    middle: np.ndarray
    batches: tuple[slice, ...]
    known: np.ndarray
    order: np.ndarray


@functools.lru_cache(maxsize=512)
def _plan(n: int, known: int, prove: bool) -> _Plan:
    """The :class:`_Plan` of an edge of ``n`` intervals (the samples :func:`_edges_free` picks
    for one edge)."""
    index = np.arange(n + 1)
    middle, known_free, plain = _roles(index, np.full(n + 1, n), known, prove)
    order = np.lexsort((index, _depth(index, np.full(n + 1, n))))
    first = order[(middle | plain)[order]]
    half = np.where(middle[first], (_BLOCK / 2) * (1 + 1e-9), 0.0) / n
    for array in (first, middle, known_free, order):
        array.setflags(write=False)
    return _Plan(first, first / n, half, middle[first], _batches(len(first)), known_free, order)


def _roles(index: np.ndarray, n: np.ndarray, known: int, prove: bool):
    """Of the samples ``index`` of edges cut into ``n`` intervals (both (M,)): which are the
    middles of whole blocks (none without ``prove``), which ends are ``known`` free, and which
    the first pass checks as they are (the samples after the last whole block, and the ends
    not known free)."""
    whole = (n // _BLOCK) * _BLOCK if prove else np.zeros_like(n)
    middle = (index % _BLOCK == _BLOCK // 2) & (index < whole)
    known_free = (index == 0) if known else np.zeros(len(index), dtype=bool)
    if known == 2:
        known_free |= index == n
    plain = ((index > whole) | (index == 0) | (index == n)) & ~known_free
    return middle, known_free, plain


def _batches(count: int) -> tuple[slice, ...]:
    """``count`` samples in batches, coarse ones first: ``_FIRST``, then each ``_GROWTH``
    times larger (at least ``_BATCH``)."""
    batches, start, size = [], 0, _FIRST
    while start < count:
        batches.append(slice(start, start + size))
        start += size
        size = max(_BATCH, _GROWTH * size)
    return tuple(batches)


def _check_samples(model, scene, A, B, edge, index, n, pick, grown, free, prefix):
    """Check the samples ``pick`` (of the flat ``edge``, ``index``, ``n`` arrays), coarse
    first, in batches, as they are and (with ``grown`` (picked, S + P)) grown; samples that
    collide mark their edges blocked in ``free``.  Returns which of ``pick`` collide, and
    which collide grown (both False for those skipped because their edge was already
    blocked)."""
    order = np.lexsort((index[pick], edge[pick], _depth(index[pick], n[pick])))
    pick = pick[order]
    grow = None if grown is None else grown[order]
    hit = np.zeros(len(pick), dtype=bool)
    touched = np.zeros(len(pick), dtype=bool)
    start, size = 0, max(int(free.sum()), _FIRST)
    while start < len(pick):
        batch = np.arange(start, min(start + size, len(pick)))
        start += size
        size = max(_BATCH, _GROWTH * size)
        batch = batch[free[edge[pick[batch]]]]
        if not len(batch):
            continue
        s = pick[batch]
        e = edge[s]
        t = index[s] / n[s]
        Q = A[e] + t[:, None] * (B[e] - A[e])
        touched[batch], blocked = _hits(model, scene, Q, None if grow is None else grow[batch])
        hit[batch] = blocked
        if blocked.any():
            free[e[blocked]] = False
            if prefix:
                free[e[blocked].min() :] = False
            if not free.any():
                break
    out = np.zeros((2, len(pick)), dtype=bool)
    out[0, order], out[1, order] = hit, touched
    return out


def _depth(index: np.ndarray, n: np.ndarray) -> np.ndarray:
    """How fine a sample ``index`` of an edge cut into ``n`` intervals is: 0 for the ends, 1
    for the middle, 2 for the quarters, … (of ``index / n`` rounded down to ``2^-B``, with
    ``2^(B−1) > n``: distinct samples stay distinct)."""
    bits = np.frexp(n)[1] + 1
    scaled = (index << bits) // n
    lowest = scaled & -scaled  # the coarsest power of two dividing it (0 at the start)
    return np.where(index == 0, 0, bits - np.frexp(lowest)[1] + 1)
