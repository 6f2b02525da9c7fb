"""Collision checks of a sphere model in a scene: configurations, clearances, straight edges.

Every function takes one configuration or a stack of them (DESIGN §2) and places all the
spheres of all the configurations at once; the tests against the scene and between the arm's
own spheres are array operations over every (configuration, sphere, obstacle) triple.  The
base's spheres are left out of the scene tests: they never move, so an obstacle that
overlaps the base is a property of the scene, not of a configuration.

Contact counts as collision: a configuration is free when every sphere is strictly apart from
every obstacle and from every sphere it is paired with.

Edges (:func:`edges_free`) are straight lines in joint space, checked at samples close enough
that **no sphere centre moves more than** ``resolution`` **metres between consecutive
samples**.  A sphere centre's speed along an edge is at most ``Σ_j |Δq_j| ρ_j``, where ``ρ_j``
bounds its distance to joint ``j``'s axis (its distance to its own frame's origin plus the
lengths ``√(a_i² + d_i²)`` of the links in between); :func:`edge_samples` gives the count.  A
collision missed between two free samples is therefore at most ``resolution / 2`` deep.  The
samples are taken coarse to fine (both ends, the middle, the quarters, …) across all the edges
at once, so a collision anywhere on any edge is usually found in the first batches.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from urkin.kinematics import _joints
from urkin.planning.scene import Scene
from urkin.planning.spheres import SphereModel

__all__ = ["Clearance", "clearance", "edge_samples", "edges_free", "explain", "is_free"]

#: Default edge resolution: the most any sphere centre moves between samples (metres).
RESOLUTION = 0.01


def _check(model: SphereModel, scene: Scene) -> None:
    if not isinstance(model, SphereModel):
        raise TypeError(
            "model must be a planning.SphereModel, e.g. planning.sphere_model(urkin.robot('ur5')); "
            f"got {type(model).__name__}"
        )
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a planning.Scene; got {type(scene).__name__}")


def _collides(model: SphereModel, scene: Scene, Q: np.ndarray) -> np.ndarray:
    """Whether each configuration of ``Q`` (N, 6), checked, is in collision: (N,) bool."""
    W = model.place(Q)  # (N, S, 3)
    hit = np.zeros(len(Q), dtype=bool)
    if len(model.pairs):
        i, j = model.pairs[:, 0], model.pairs[:, 1]
        d = W[:, i] - W[:, j]
        reach = model.radii[i] + model.radii[j]
        hit |= np.any(np.einsum("npi,npi->np", d, d) <= reach * reach, axis=1)
    if len(scene) and len(model._moving):
        moving = model._moving
        P = W[:, moving].reshape(-1, 3)
        touches = scene._touches(P, np.tile(model.radii[moving], len(Q)))
        hit |= np.any(touches.reshape(len(Q), len(moving)), axis=1)
    return hit


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
        (metres; negative: minus the depth of the deepest penetration).  ``inf`` when there
        is nothing to test.
    sphere : ndarray of int
        The arm's sphere of that pair.
    obstacle : ndarray of int
        The obstacle's index in ``scene.names``, or −1 when the pair is two of the arm's spheres.
    other : ndarray of int
        The other sphere of a self pair, or −1.
    """

    distance: np.ndarray
    sphere: np.ndarray
    obstacle: np.ndarray
    other: np.ndarray


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
    (True, 'shoulder sphere 0', 'table')
    """
    _check(model, scene)
    Q, lead, _ = _joints(q, "q")
    Q = Q.reshape(-1, 6)
    n = len(Q)
    W = model.place(Q)
    best = np.full(n, np.inf)
    sphere = np.full(n, -1)
    obstacle = np.full(n, -1)
    other = np.full(n, -1)
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
    return Clearance(*(a.reshape(lead) for a in (best, sphere, obstacle, other)))


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
    c = clearance(model, scene, Q)
    if not math.isfinite(float(c.distance)):
        return "free: nothing to collide with (no obstacles and no self-collision pairs)"
    a = model.names[int(c.sphere)]
    if int(c.obstacle) >= 0:
        kind = _kind(scene, int(c.obstacle))
        b = f"{kind} '{scene.names[int(c.obstacle)]}'"
    else:
        b = f"{model.names[int(c.other)]} (self-collision)"
    depth = float(c.distance) * 1000
    if depth <= 0:
        return f"in collision: {a} penetrates {b} by {-depth:.0f} mm"
    return f"free: the closest pair is {a} and {b}, {depth:.0f} mm apart"


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
    A, B, lead = _edge_ends(qa, qb)
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
    if not resolution > 0:
        raise ValueError(f"resolution must be a positive distance (m); got {resolution}")
    rho = model.__dict__.get("_rho")
    if rho is None:
        rho = _reach(model)
        object.__setattr__(model, "_rho", rho)
    travel = (np.abs(B - A) @ rho.T).max(axis=1) if len(model) else np.zeros(len(A))
    return np.maximum(1, np.ceil(travel / resolution)).astype(np.intp)


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
    free = _edges_free(model, scene, A, B, _intervals(model, A, B, resolution))
    return bool(free[0]) if lead == () else free.reshape(lead)


#: Samples per batch in edge checks: the first batch holds the coarsest samples of every edge.
_BATCH = 32


def _edges_free(model, scene, A, B, counts, prefix: bool = False) -> np.ndarray:
    """Edges (K, 6) → (K,) free, each cut into ``counts`` intervals; coarse samples first,
    across all the edges, in batches, skipping the edges already found in collision.

    With ``prefix``, only the free prefix of the edges matters (a chain of pieces: nothing
    after the first blocked piece is used): every edge after a blocked one is reported
    blocked without being checked further."""
    samples = counts + 1
    edge = np.repeat(np.arange(len(A)), samples)
    index = np.arange(len(edge)) - np.repeat(np.cumsum(samples) - samples, samples)
    t = index / np.repeat(counts, samples)
    rank = np.concatenate([_rank(int(n)) for n in counts])  # coarse-to-fine rank per sample
    order = np.lexsort((edge, rank))
    edge, t = edge[order], t[order]
    free = np.ones(len(A), dtype=bool)
    start, size = 0, _BATCH
    while start < len(edge):
        e, s = edge[start : start + size], t[start : start + size]
        start += size
        size *= 2
        live = free[e]
        if not live.any():
            continue
        e, s = e[live], s[live]
        Q = A[e] + s[:, None] * (B[e] - A[e])
        hit = _collides(model, scene, Q)
        free[e[hit]] = False
        if prefix and hit.any():
            free[e[hit].min() :] = False
        if not free.any():
            break
    return free


@functools.lru_cache(maxsize=512)
def _rank(n: int) -> np.ndarray:
    """Position of each sample index 0 … n in the coarse-to-fine order (cached: edges of one
    call mostly share a few sample counts)."""
    rank = np.empty(n + 1, dtype=np.intp)
    rank[_order(n)] = np.arange(n + 1)
    rank.setflags(write=False)
    return rank


def _order(n: int) -> np.ndarray:
    """Sample indices 0 … n, coarse first (ends, middle, quarters, …)."""
    seen = np.zeros(n + 1, dtype=bool)
    out = []
    for index in (0, n):
        if not seen[index]:
            seen[index] = True
            out.append(index)
    step = n
    while step > 1:
        step = -(-step // 2)
        grid = np.unique(np.minimum(np.arange(0, n + step, step), n))
        new = grid[~seen[grid]]
        seen[new] = True
        out.extend(new.tolist())
    rest = np.flatnonzero(~seen)
    return np.concatenate([np.array(out, dtype=np.intp), rest])
