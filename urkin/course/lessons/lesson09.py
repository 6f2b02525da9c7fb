"""Lesson 09 — collisions and motion planning: spheres, distances, edges, RRT-Connect.

Every expected answer here is computed by the check's own formulas (never by urkin.planning,
whose scene, checks and planner are the exercises' hidden answers): the sphere–box distance
from the box's clipped closest point, the sample count from its definition, a path's
collisions from the check's own samples of a joint-space obstacle, the RRT step from its
definition.  Every named mistake is a hypothesis that computes its typical wrong answer.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from urkin.course import wire
from urkin.course.compare import Mismatch, as_array, compare, unless_right
from urkin.course.exercise import Check, Exercise, Lesson
from urkin.course.submission import StudentRaised
from urkin.planning import checks, rrt, scene
from urkin.transforms import so3_exp

# ------------------------------------------------------------------- 9.1 sphere_box_distance

_NO_ROTATION = (
    "the box's rotation ignored: the centre must first be taken into the box's frame, "
    "Rᵀ(c − c_box), and only there compared with the half sizes"
)
_TRANSPOSED = (
    "the rotation applied the wrong way round, R(c − c_box): the columns of R are the box's "
    "axes in the base frame, so the coordinates along them are Rᵀ(c − c_box)"
)
_FULL_AS_HALF = (
    "box_size used as half sizes: box_size holds full edge lengths, so the faces are at "
    "±box_size/2 from the box's centre"
)
_CLIPPED_INSIDE = (
    "inside the box the distance was clipped to 0: a centre inside is at minus its depth "
    "below the nearest face, so that a deeper ball has a more negative distance"
)
_INSIDE_POSITIVE = (
    "inside the box the depth came out positive: a centre inside the box has a negative "
    "distance, minus its depth below the nearest face"
)
_NO_RADIUS = (
    "the radius not subtracted: that is the distance of the centre; the ball's surface is "
    "r closer to the box"
)
_RADIUS_ADDED = "the radius added instead of subtracted: the ball's surface is r closer"
_LARGEST_GAP = (
    "beside an edge or a corner, the largest per-axis gap instead of the length of the gap "
    "vector: the closest point of the box is the clipped point, ‖max(|p| − h, 0)‖ away"
)
_SUM_GAPS = (
    "beside an edge or a corner, the per-axis gaps added: the distance is the length of the "
    "gap vector, √(Σ gᵢ²), not Σ gᵢ"
)


def _box_distance(
    c,
    r,
    box_centre,
    size,
    R,
    *,
    rotation="inverse",
    half=True,
    inside="depth",
    outside="length",
    radius="minus",
) -> float:
    """The check's signed distance (clipped closest point), or a named mistake's."""
    offset = np.asarray(c, dtype=float) - np.asarray(box_centre, dtype=float)
    R = np.asarray(R, dtype=float)
    local = {"inverse": R.T @ offset, "none": offset, "forward": R @ offset}[rotation]
    h = np.asarray(size, dtype=float) / (2.0 if half else 1.0)
    gap = np.abs(local - np.clip(local, -h, h))
    if np.any(gap > 0):
        d = {
            "length": math.sqrt(float(gap @ gap)),
            "largest": float(gap.max()),
            "sum": float(gap.sum()),
        }[outside]
    else:
        depth = float(np.min(h - np.abs(local)))
        d = {"depth": -depth, "clipped": 0.0, "positive": depth}[inside]
    return d + {"minus": -r, "none": 0.0, "plus": r}[radius]


def _box_hypotheses(c, r, bc, size, R) -> dict[str, Callable[[], Any]]:
    def wrong(**how):
        return lambda: _box_distance(c, r, bc, size, R, **how)

    return {
        _NO_ROTATION: wrong(rotation="none"),
        _TRANSPOSED: wrong(rotation="forward"),
        _FULL_AS_HALF: wrong(half=False),
        _CLIPPED_INSIDE: wrong(inside="clipped"),
        _INSIDE_POSITIVE: wrong(inside="positive"),
        _NO_RADIUS: wrong(radius="none"),
        _RADIUS_ADDED: wrong(radius="plus"),
        _LARGEST_GAP: wrong(outside="largest"),
        _SUM_GAPS: wrong(outside="sum"),
    }


def _judge_box(sub, c, r, bc, size, R, what, *, as_lists=False):
    inputs = {"centre": c, "radius": r, "box_centre": bc, "box_size": size, "box_R": R}
    args = [np.array(x, dtype=float) if isinstance(x, np.ndarray) else x for x in (c, bc, size, R)]
    if as_lists:
        args = [np.asarray(x).tolist() for x in args]
    value = sub.sphere_box_distance(args[0], r, args[1], args[2], args[3])
    call = "sphere_box_distance(centre, radius, box_centre, box_size, box_R)"
    got = as_array(value, (), call, inputs)
    right = _box_distance(c, r, bc, size, R)
    compare(
        got,
        right,
        what=what,
        inputs=inputs,
        hypotheses=unless_right(_box_hypotheses(c, r, bc, size, R), right),
    )


def _rotation(rng) -> np.ndarray:
    """A rotation about a random axis by 0.4 to π rad, either way (one that matters)."""
    axis = rng.normal(size=3)
    return so3_exp(axis / np.linalg.norm(axis) * rng.choice([-1.0, 1.0]) * rng.uniform(0.4, np.pi))


def _box(rng, scale=(0.05, 0.8)):
    return rng.uniform(-1.0, 1.0, 3), rng.uniform(*scale, 3), _rotation(rng)


def _outside_point(rng, h, axes: int, gap_range=(0.02, 0.3)) -> np.ndarray:
    """A point of the box frame beyond ``axes`` faces (1: a face, 2: an edge, 3: a corner),
    within 80 % of the half sizes along the others."""
    local = rng.uniform(-0.8, 0.8, 3) * h
    chosen = rng.choice(3, axes, replace=False)
    sides = rng.choice([-1.0, 1.0], axes)
    local[chosen] = sides * (h[chosen] + rng.uniform(*gap_range, axes))
    return local


def _box_outside(sub, rng):
    for axes, overlap in ((1, False), (2, False), (3, False), (1, True), (2, True), (3, True)):
        bc, size, R = _box(rng)
        local = _outside_point(rng, size / 2, axes)
        gap = np.linalg.norm(np.abs(local) - np.minimum(np.abs(local), size / 2))
        r = float(rng.uniform(1.2, 2.0) * gap if overlap else rng.uniform(0.1, 0.8) * gap)
        c = bc + R @ local
        where = {1: "a face", 2: "an edge", 3: "a corner"}[axes]
        _judge_box(
            sub,
            c,
            r,
            bc,
            size,
            R,
            f"a ball beside {where} of a rotated box"
            + (", overlapping it (a negative distance)" if overlap else "")
            + ": ‖gap to the clipped closest point‖ − r",
        )


def _box_inside(sub, rng):
    for _ in range(3):
        bc, size, R = _box(rng)
        local = rng.uniform(-0.9, 0.9, 3) * size / 2
        r = float(rng.uniform(0.01, 0.2))
        _judge_box(
            sub,
            bc + R @ local,
            r,
            bc,
            size,
            R,
            "the centre inside a rotated box: minus its depth below the nearest face, minus r",
        )


def _box_shapes(sub, rng):
    # a board 1 cm thick, the ball above it; given as lists
    bc, _, R = _box(rng)
    size = np.array([rng.uniform(0.3, 0.6), rng.uniform(0.2, 0.5), 0.01])
    local = np.array([rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), rng.uniform(0.03, 0.1)])
    r = float(rng.uniform(0.01, 0.02))
    _judge_box(
        sub,
        bc + R @ local,
        r,
        bc,
        size,
        R,
        "a board 1 cm thick, the inputs given as lists",
        as_lists=True,
    )
    # a table 1.5 m long with the identity rotation, the ball beside its long edge, overlapping
    size = np.array([1.5, 0.8, 0.05])
    bc = np.array([0.2, 0.0, -0.03])
    local = np.array([rng.uniform(-0.6, 0.6), 0.4 + rng.uniform(0.01, 0.04), 0.03])
    gap = math.hypot(local[1] - 0.4, local[2] - 0.025)
    _judge_box(
        sub,
        bc + local,
        float(rng.uniform(1.2, 2.0) * gap),
        bc,
        size,
        np.eye(3),
        "a table 1.5 m long, the identity rotation, a ball over its long edge",
    )
    # a point (radius 0) inside a small cube
    bc, _, R = _box(rng)
    size = np.full(3, rng.uniform(0.04, 0.1))
    local = rng.uniform(-0.4, 0.4, 3) * size
    _judge_box(sub, bc + R @ local, 0.0, bc, size, R, "a point (radius 0) inside a small cube")


# -------------------------------------------------------------------- 9.2 samples_needed

_MAX_NORM = (
    "only the largest joint term max_j ρ_j|Δq_j|: all the joints turn at once and each moves "
    "the centre, so their displacements add up: Σ_j ρ_j|Δq_j|"
)
_EUCLIDEAN = (
    "the Euclidean norm √(Σ_j (ρ_j Δq_j)²): the joints' displacements need not be "
    "perpendicular to one another; the bound that always holds is their sum Σ_j ρ_j|Δq_j|"
)
_MAX_RHO = (
    "one lever arm, the largest ρ, for every joint: each joint moves the centre by its own "
    "ρ_j|Δq_j|"
)
_NO_RHO = (
    "the joint changes without their lever arms: radians are not metres; a centre ρ_j from "
    "joint j's axis moves ρ_j|Δq_j| when the joint turns by Δq_j"
)
_ONE_SHORT = (
    "one sample short: the number of pieces returned instead of the number of samples (n "
    "pieces have n + 1 ends, both ends of the edge included), or the pieces rounded down (int, "
    "floor or round) where they must be ⌈D / resolution⌉"
)
_SIGNED = "signed joint changes: a joint that turns backwards moves the spheres too; use |Δq_j|"
_WRAPPED = (
    "Δq wrapped into (−π, π]: the edge is the straight line from qa to qb in joint space, and "
    "along it a joint turns by all of qb_j − qa_j, more than half a turn too"
)

_ROUND_OFF = 1e-9  # relative: where D / resolution is this close to a whole number m, m or m+1

_FLOAT_COUNT = (
    "returns a float; the count must be an int (e.g. int(np.ceil(...))): np.ceil and "
    "max(1.0, …) give floats, which range() and np.linspace's num refuse"
)


def _is_int(value) -> bool:
    """Whether ``value`` is an int: Python's or a NumPy integer (which the plain-data copy
    gives as a 0-d integer array), not a float that happens to be whole, nor a bool."""
    if isinstance(value, (bool, np.bool_)):
        return False
    if isinstance(value, (int, np.integer)):
        return True
    return (
        isinstance(value, np.ndarray)
        and value.shape == ()
        and np.issubdtype(value.dtype, np.integer)
    )


def _type_name(value) -> str:
    """The type of a returned count, as the student wrote it."""
    if isinstance(value, np.ndarray):
        return f"a NumPy {value.dtype}"
    if isinstance(value, np.generic):
        return f"a numpy.{type(value).__name__}"
    return f"a {type(value).__name__}"


def _bound(qa, qb, rho, rule="sum") -> float:
    dq = np.asarray(qb, dtype=float) - np.asarray(qa, dtype=float)
    rho = np.asarray(rho, dtype=float)
    terms = np.abs(dq) * rho
    return {
        "sum": float(terms.sum()),
        "max": float(terms.max()),
        "euclidean": float(np.sqrt(np.sum(terms**2))),
        "max_rho": float(rho.max() * np.abs(dq).sum()),
        "no_rho": float(np.abs(dq).sum()),
        "signed": float(dq @ rho),
        "wrapped": float((np.abs((dq + np.pi) % (2 * np.pi) - np.pi) * rho).sum()),
    }[rule]


def _samples(qa, qb, rho, resolution, *, rule="sum", rounding="ceil", ends=1) -> int:
    ratio = _bound(qa, qb, rho, rule) / resolution
    pieces = {"ceil": math.ceil, "floor": math.floor, "round": round}[rounding](ratio)
    return max(1, pieces) + ends if rounding == "ceil" else pieces + ends


def _accepted(qa, qb, rho, resolution) -> set[int]:
    ratio = _bound(qa, qb, rho) / resolution
    m = round(ratio)
    if m >= 1 and abs(ratio - m) <= _ROUND_OFF * ratio:
        return {m + 1, m + 2}
    return {max(1, math.ceil(ratio)) + 1}


_SAMPLE_MISTAKES = {
    _MAX_NORM: {"rule": "max"},
    _EUCLIDEAN: {"rule": "euclidean"},
    _MAX_RHO: {"rule": "max_rho"},
    _NO_RHO: {"rule": "no_rho"},
    _SIGNED: {"rule": "signed"},
    _WRAPPED: {"rule": "wrapped"},
    _ONE_SHORT: {"ends": 0},
    _ONE_SHORT + " ": {"rounding": "floor"},
    _ONE_SHORT + "  ": {"rounding": "round"},
}


def _judge_samples(sub, qa, qb, rho, resolution, what, *, as_lists=False):
    inputs = {"qa": qa, "qb": qb, "rho": rho, "resolution": resolution}
    args = [x.tolist() if as_lists else x.copy() for x in (qa, qb, rho)]
    value = sub.samples_needed(*args, resolution)
    if isinstance(value, np.ndarray) and value.shape == (1,):  # a NumPy scalar, as copied
        value = value.reshape(())
    call = "samples_needed(qa, qb, rho, resolution)"
    got = float(as_array(value, (), call, inputs))
    right = _accepted(qa, qb, rho, resolution)
    if got != round(got):
        raise Mismatch(f"{call} must return a whole number of samples", inputs=inputs, got=got)
    if int(got) in right:
        if not _is_int(value):
            raise Mismatch(
                f"{call} must return an int: it is a count, which path_is_free passes on to "
                f"np.linspace and range; got {_type_name(value)} {got:g}",
                inputs=inputs,
                expected=min(right),
                got=got,
                mistake=_FLOAT_COUNT,
            )
        return
    mistake = None
    for name, how in _SAMPLE_MISTAKES.items():
        try:
            wrong = _samples(qa, qb, rho, resolution, **how)
        except (ValueError, OverflowError):
            continue
        if wrong not in right and wrong == int(got):
            mistake = name.strip()
            break
    D = _bound(qa, qb, rho)
    raise Mismatch(
        f"{what}: D = Σ_j ρ_j|Δq_j| = {D:.6g} m, so {max(1, math.ceil(D / resolution))} "
        f"pieces of at most {resolution:g} m and {min(right)} samples",
        inputs=inputs,
        expected=min(right),
        got=got,
        mistake=mistake,
    )


def _edge_problem(rng, *, distinct=True):
    """Random edge ends (rad), lever arms ρ (m) and a resolution (m) away from whole-number
    ratios, on which (with ``distinct``) every named mistake gives another count."""
    while True:
        qa = rng.uniform(-np.pi, np.pi, 6)
        dq = rng.uniform(-1.2, 1.2, 6) * (rng.random(6) < 0.85)
        qb = qa + dq
        rho = rng.uniform(0.05, 0.9, 6)
        resolution = float(10 ** rng.uniform(-2.7, -1.7))
        ratio = _bound(qa, qb, rho) / resolution
        if (
            ratio < 3
            or abs(ratio - round(ratio)) < 0.05
            or abs(ratio - math.floor(ratio) - 0.5) < 0.05
        ):
            continue
        if distinct:
            right = _accepted(qa, qb, rho, resolution)
            counts = [  # wrapping changes nothing below half a turn (_samples_edges tests it)
                _samples(qa, qb, rho, resolution, **how)
                for name, how in _SAMPLE_MISTAKES.items()
                if name != _WRAPPED
            ]
            if any(c in right for c in counts):
                continue
        return qa, qb, rho, resolution


def _samples_random(sub, rng):
    for _ in range(5):
        qa, qb, rho, resolution = _edge_problem(rng)
        _judge_samples(
            sub,
            qa,
            qb,
            rho,
            resolution,
            "⌈Σ_j ρ_j|Δq_j| / resolution⌉ pieces, and one sample more than pieces (both ends)",
        )


def _samples_edges(sub, rng):
    # a short edge: the bound below one resolution, still its two ends
    qa, qb, rho, resolution = _edge_problem(rng, distinct=False)
    scale = rng.uniform(0.2, 0.8) * resolution / _bound(qa, qb, rho)
    qb = qa + scale * (qb - qa)
    _judge_samples(sub, qa, qb, rho, resolution, "a short edge (the bound below the resolution)")
    # one joint turning backwards, given as lists
    qa, _, rho, resolution = _edge_problem(rng, distinct=False)
    j = int(rng.integers(6))
    qb = qa.copy()
    while True:
        qb[j] = qa[j] - rng.uniform(0.3, 1.5)
        ratio = _bound(qa, qb, rho) / resolution
        if abs(ratio - round(ratio)) > 0.05 and abs(ratio - math.floor(ratio) - 0.5) > 0.05:
            break
    _judge_samples(
        sub,
        qa,
        qb,
        rho,
        resolution,
        f"only joint {j + 1} turns, backwards; the inputs given as lists",
        as_lists=True,
    )
    # joints turning both ways
    while True:
        qa, qb, rho, resolution = _edge_problem(rng)
        dq = qb - qa
        if (dq > 0.2).sum() >= 2 and (dq < -0.2).sum() >= 2:
            break
    _judge_samples(sub, qa, qb, rho, resolution, "joints turning both ways")
    # a joint turning more than half a turn: the straight edge turns it all the way
    qa, qb, rho, resolution = _edge_problem(rng, distinct=False)
    j = int(rng.integers(6))
    while True:
        qb[j] = qa[j] + rng.choice([-1.0, 1.0]) * rng.uniform(3.6, 5.5)
        ratio = _bound(qa, qb, rho) / resolution
        if abs(ratio - round(ratio)) > 0.05 and abs(ratio - math.floor(ratio) - 0.5) > 0.05:
            break
    _judge_samples(
        sub, qa, qb, rho, resolution, f"joint {j + 1} turns by more than half a turn (|Δq| > π)"
    )
    # an edge of length zero: its one configuration, as both ends
    _judge_samples(sub, qa, qa.copy(), rho, resolution, "an edge of length zero (qa = qb)")


# ----------------------------------------------------------------------- 9.3 path_is_free

_WAYPOINTS_ONLY = (
    "only the waypoints checked: the arm passes through every configuration of the straight "
    "edges between them too (MIT's manipulation autograder makes the same mistake); check "
    "each edge at samples_needed(qa, qb, rho, resolution) samples"
)
_FIXED_COUNT = (
    "a fixed number of samples per edge (ten): a long edge can cross a thin obstacle "
    "between two of them; take samples_needed(qa, qb, rho, resolution) for each edge"
)
_NO_GOAL = (
    "the last waypoint never checked: each edge's samples stop short of its end, and nothing "
    "checks the goal itself"
)
_NO_START = (
    "the first waypoint never checked: each edge's samples start after its beginning, and "
    "nothing checks the start itself"
)
_TOO_MANY = (
    "far more samples than the resolution needs: samples_needed(qa, qb, rho, resolution) per "
    "edge is enough (no centre moves more than the resolution between two of them), and every "
    "extra sample costs a collision check"
)


def _inside(Q, lower, upper) -> np.ndarray:
    P = np.asarray(Q, dtype=float)[..., None, :]
    return np.all((P >= lower) & (P <= upper), axis=-1).any(axis=-1)


def _edge_t(qa, qb, rho, resolution, rule) -> np.ndarray:
    """The fractions along an edge at which a rule checks it."""
    if rule == "fixed":
        return np.linspace(0.0, 1.0, 10)
    n = max(1, math.ceil(_bound(qa, qb, rho) / resolution))
    return np.arange(n + 1) / n


def _path_free(path, rho, resolution, lower, upper, rule="resolution") -> bool:
    """The check's own answer (rule "resolution") or a named mistake's."""
    path = np.asarray(path, dtype=float)
    if rule == "waypoints":
        return not _inside(path, lower, upper).any()
    for k in range(len(path) - 1):
        qa, qb = path[k], path[k + 1]
        t = _edge_t(qa, qb, rho, resolution, "fixed" if rule == "fixed" else "resolution")
        if rule == "no_goal":
            t = t[:-1]
        elif rule == "no_start":
            t = t[1:]
        if _inside(qa + t[:, None] * (qb - qa), lower, upper).any():
            return False
    return True


_PATH_MISTAKES = {
    _WAYPOINTS_ONLY: "waypoints",
    _FIXED_COUNT: "fixed",
    _NO_GOAL: "no_goal",
    _NO_START: "no_start",
}


def _random_path(rng, M):
    """M waypoints (rad) with steps of about a radian per joint, lever arms ρ (m) and a
    resolution (m)."""
    path = [rng.uniform(-2.0, 2.0, 6)]
    for _ in range(M - 1):
        path.append(path[-1] + rng.uniform(-1.2, 1.2, 6))
    rho = rng.uniform(0.15, 0.7, 6)
    return np.array(path), rho, float(rng.uniform(0.006, 0.02))


def _wall(rng, path, rho, resolution, edge, *, thin):
    """A joint-space box that the edge ``edge`` crosses, touching no waypoint and no other
    edge; None if none was found.  Thin: 1.5 × resolution / ρ_j thick along the joint j that
    turns most, so the samples of the resolution rule cannot miss it, and crossed between two
    of ten evenly spaced samples; thick: crossed over 16 to 30 % of the edge."""
    qa, qb = path[edge], path[edge + 1]
    dq = qb - qa
    j = int(np.argmax(np.abs(dq)))
    others = np.delete(np.arange(len(path) - 1), edge)
    for _ in range(50):
        t = rng.uniform(0.2, 0.8)
        if thin:
            width = 1.5 * resolution / rho[j]
            half_t = width / (2 * abs(dq[j]))
            if np.min(np.abs(np.linspace(0.0, 1.0, 10) - t)) < half_t + 0.01:
                continue
        else:
            half_t = rng.uniform(0.08, 0.15)
            width = 2 * half_t * abs(dq[j])
        half = np.abs(dq) * half_t + 0.02  # the edge stays inside while it crosses
        half[j] = width / 2
        centre = qa + t * dq
        lower, upper = centre - half, centre + half
        if not _touched(path, others, lower - 0.01, upper + 0.01, waypoints=True):
            return lower, upper
    return None


def _touched(path, edges, lower, upper, *, waypoints=False) -> bool:
    """Whether the box holds a waypoint (with ``waypoints``) or a point of the edges (sampled
    far more finely than any check samples them)."""
    if waypoints and _inside(path, lower[None], upper[None]).any():
        return True
    s = np.linspace(0.0, 1.0, 2001)[:, None]
    return any(
        _inside(path[k] + s * (path[k + 1] - path[k]), lower[None], upper[None]).any()
        for k in edges
    )


def _near_miss(rng, path, edge):
    """A box beside the edge ``edge`` (offset along the joint that turns least) that no edge
    enters; None if none was found."""
    qa, qb = path[edge], path[edge + 1]
    j = int(np.argmin(np.abs(qb - qa)))
    for _ in range(20):
        centre = qa + rng.uniform(0.3, 0.7) * (qb - qa)
        centre[j] += rng.choice([-1.0, 1.0]) * 0.15
        lower, upper = centre - 0.08, centre + 0.08
        if not _touched(path, range(len(path) - 1), lower - 0.01, upper + 0.01, waypoints=True):
            return lower, upper
    return None


def _obstructed(rng, M, kind):
    """A random path of M waypoints and a box: ``"free"`` (a near miss), ``"thick"`` or
    ``"thin"`` (a wall across one edge), with a sentence saying which."""
    while True:
        path, rho, resolution = _random_path(rng, M)
        edge = int(rng.integers(M - 1))
        if kind == "free":
            box = _near_miss(rng, path, edge)
            why = "every waypoint and every edge misses the box"
        else:
            box = _wall(rng, path, rho, resolution, edge, thin=kind == "thin")
            why = (
                f"the waypoints are free, but edge {edge + 1} (from waypoint {edge + 1} to "
                f"{edge + 2}) crosses a {'thin ' if kind == 'thin' else ''}box"
            )
        if box is not None:
            return path, rho, resolution, box[0][None], box[1][None], why


def _path_inputs(path, rho, resolution, lower, upper) -> dict:
    return {
        "is_free": f"the check's stand-in: free outside {len(lower)} box(es) of joint space, "
        f"lower corners {np.round(lower, 4).tolist()}, upper corners "
        f"{np.round(upper, 4).tolist()}",
        "path": path,
        "rho": rho,
        "resolution": resolution,
    }


def _call_path(sub, path, rho, resolution, lower, upper, is_free=None) -> bool:
    inputs = _path_inputs(path, rho, resolution, lower, upper)
    if is_free is None:
        is_free = wire.Function("joint_boxes", lower=lower, upper=upper)
    value = sub.path_is_free(is_free, path.copy(), rho.copy(), resolution)
    call = "path_is_free(is_free, path, rho, resolution)"
    if isinstance(value, (str, bytes)) or value is None or np.ndim(value) != 0:
        raise Mismatch(f"{call} must return one bool (True or False)", inputs=inputs)
    got = float(as_array(value, (), call, inputs))
    if got not in (0.0, 1.0):
        raise Mismatch(f"{call} must return a bool (True or False)", inputs=inputs, got=got)
    return bool(got)


def _judge_paths(sub, cases, what):
    """Each case ``(path, rho, resolution, lower, upper, why)``: the answer of each, then the
    mistake whose answers match all of them."""
    answers = [_call_path(sub, p, r, s, lo, hi) for p, r, s, lo, hi, _ in cases]
    rights = [_path_free(p, r, s, lo, hi) for p, r, s, lo, hi, _ in cases]
    if answers == rights:
        return
    k = next(i for i, (a, b) in enumerate(zip(answers, rights)) if a != b)
    path, rho, resolution, lower, upper, why = cases[k]
    mistake = None
    for name, rule in _PATH_MISTAKES.items():
        predicted = [_path_free(p, r, s, lo, hi, rule) for p, r, s, lo, hi, _ in cases]
        if predicted != rights and predicted == answers:
            mistake = name
            break
    raise Mismatch(
        f"{what}. Path {k + 1} of {len(cases)}: {why}, so path_is_free must return {rights[k]}",
        inputs=_path_inputs(path, rho, resolution, lower, upper),
        expected=float(rights[k]),
        got=float(answers[k]),
        mistake=mistake,
    )


def _paths_edges(sub, rng):
    cases = [
        _obstructed(rng, int(rng.integers(3, 6)), kind)
        for kind in ("thick", "free", "thin", "thick", "free", "thin")
    ]
    _judge_paths(sub, cases, "every waypoint and every edge checked, at the resolution")


def _paths_waypoints(sub, rng):
    cases = []
    for which in ("goal", "start", "middle"):
        path, rho, resolution = _random_path(rng, 4)
        k = {"goal": 3, "start": 0, "middle": int(rng.integers(1, 3))}[which]
        lower, upper = path[k] - 1e-6, path[k] + 1e-6  # touches that waypoint only
        why = f"waypoint {k + 1} (the {which}) is in collision"
        cases.append((path, rho, resolution, lower[None], upper[None], why))
    _judge_paths(sub, cases, "a waypoint in collision: the start, the goal or one between")


def _paths_budget(sub, rng):
    for _ in range(2):
        path, rho, resolution, lower, upper, _ = _obstructed(rng, 4, "free")
        needed = sum(
            len(_edge_t(path[k], path[k + 1], rho, resolution, "resolution"))
            for k in range(len(path) - 1)
        )
        budget = 2 * needed + len(path)
        inputs = _path_inputs(path, rho, resolution, lower, upper)
        # answered by the checks (wire.ANSWERED_BY_CHECKS): they count the configurations
        is_free = wire.Function("joint_boxes", lower=lower, upper=upper, budget=budget)
        too_many = Mismatch(
            f"path_is_free asked is_free about more than {budget} configurations; "
            f"the edges need {needed} at this resolution",
            inputs=inputs,
            mistake=_TOO_MANY,
        )
        try:
            free = _call_path(sub, path, rho, resolution, lower, upper, is_free)
        except StudentRaised:
            if is_free._built.refused:
                raise too_many from None
            raise
        if is_free._built.refused:  # refused, and the refusal caught
            raise too_many
        if not free:
            raise Mismatch(
                "every waypoint and every edge of this path misses the box: path_is_free "
                "must return True",
                inputs=inputs,
                expected=1.0,
                got=0.0,
            )
        _judge_coverage(path, rho, resolution, is_free._built.seen(), inputs)


_TOO_COARSE = (
    "edges sampled more coarsely than the resolution: consecutive samples along an edge must be "
    "at most 1 / (samples_needed − 1) of it apart, samples_needed(qa, qb, rho, resolution) "
    "samples from qa to qb (np.linspace(0, 1, samples_needed(…)) of the way), else a centre "
    "moves more than the resolution between two of them and a thin obstacle slips through"
)


def _judge_coverage(path, rho, resolution, asked, inputs):
    """That the configurations ``asked`` (K, 6) include, along every edge of a free path,
    samples no further apart than the resolution rule's, from one end to the other (what
    "checked at the resolution" means, whatever order or batches they were asked in)."""
    for k in range(len(path) - 1):
        qa, qb = path[k], path[k + 1]
        dq = qb - qa
        pieces = len(_edge_t(qa, qb, rho, resolution, "resolution")) - 1
        length2 = float(dq @ dq)
        if length2 == 0.0:
            continue
        t = (asked - qa) @ dq / length2
        off = np.linalg.norm(asked - qa - t[:, None] * dq, axis=1)
        on = t[(off <= 1e-9 * (1.0 + math.sqrt(length2))) & (t > -1e-9) & (t < 1 + 1e-9)]
        # the ends as if asked (whether the waypoints were is another check's question)
        widest = float(np.diff(np.sort(np.r_[0.0, on, 1.0])).max())
        if widest > (1.0 + 1e-6) / pieces:
            raise Mismatch(
                f"edge {k + 1} was sampled {widest:.3g} of its length apart at the widest; at "
                f"this resolution its {pieces + 1} samples are 1/{pieces} = {1 / pieces:.3g} "
                "of it apart",
                inputs=inputs,
                mistake=_TOO_COARSE,
            )


# ----------------------------------------------------------------------------- 9.4 steer

_OVERSHOOT = (
    "a full step even when q_rand is closer than one step: the new node lands beyond q_rand "
    "(and the step divides by zero when q_rand = q_near); return q_rand itself when "
    "max_j |Δq_j| ≤ step"
)
_NO_LIMIT = "no step limit: q_rand returned however far it is; RRT grows by steps of at most step"
_AWAY = "the step goes away from q_rand: the direction is q_rand − q_near"
_FROM_TARGET = (
    "the step taken from q_rand back towards q_near: the new node is one step from q_near, "
    "towards q_rand"
)
_EUCLIDEAN_STEP = (
    "the step measured with the Euclidean norm ‖Δq‖: a step here is the largest joint change "
    "max_j |Δq_j| (as urkin.planning.rrt_connect measures it); scale Δq by step / max_j |Δq_j|"
)
_PER_JOINT = (
    "each joint clipped to ±step on its own: that changes the direction (the joints no longer "
    "move in proportion); scale the whole Δq by step / max_j |Δq_j|"
)
_UNNORMALISED = "Δq multiplied by step without dividing by its size: q_near + step·Δq"


def _steer(q_near, q_rand, step, how="right") -> np.ndarray:
    a, b = np.asarray(q_near, dtype=float), np.asarray(q_rand, dtype=float)
    d = b - a
    largest = float(np.max(np.abs(d)))
    if how == "no_limit":
        return b.copy()
    if how == "clip":
        return a + np.clip(d, -step, step)
    if how == "unnormalised":
        return a + step * d
    norm = float(np.linalg.norm(d)) if how == "euclidean" else largest
    if how != "overshoot" and norm <= step:
        return b.copy()
    unit = d / norm
    return {
        "right": a + step * unit,
        "overshoot": a + step * unit,
        "euclidean": a + step * unit,
        "away": a - step * unit,
        "from_target": b - step * unit,
    }[how]


_STEER_MISTAKES = {
    _OVERSHOOT: "overshoot",
    _NO_LIMIT: "no_limit",
    _AWAY: "away",
    _FROM_TARGET: "from_target",
    _EUCLIDEAN_STEP: "euclidean",
    _PER_JOINT: "clip",
    _UNNORMALISED: "unnormalised",
}


def _judge_steer(sub, q_near, q_rand, step, what, *, as_lists=False):
    inputs = {"q_near": q_near, "q_rand": q_rand, "step": step}
    args = [x.tolist() if as_lists else x.copy() for x in (q_near, q_rand)]
    value = sub.steer(args[0], args[1], step)
    call = "steer(q_near, q_rand, step)"
    right = _steer(q_near, q_rand, step)
    try:
        got = as_array(value, (6,), call, inputs)
    except Mismatch as exc:
        if "NaN" in exc.what and np.array_equal(q_near, q_rand):
            exc.mistake = exc.mistake or _OVERSHOOT
        raise
    hypotheses = {
        name: (lambda how=how: _steer(q_near, q_rand, step, how))
        for name, how in _STEER_MISTAKES.items()
    }
    compare(got, right, what=what, inputs=inputs, hypotheses=unless_right(hypotheses, right))


def _steer_far(sub, rng):
    for _ in range(5):
        step = float(rng.uniform(0.05, 1.0))
        q_near = rng.uniform(-np.pi, np.pi, 6)
        direction = rng.normal(size=6)
        direction /= np.abs(direction).max()
        q_rand = q_near + rng.uniform(1.5, 10.0) * step * direction
        _judge_steer(
            sub,
            q_near,
            q_rand,
            step,
            "a far q_rand: one step towards it, the largest joint change exactly step",
        )


def _steer_near(sub, rng):
    step = float(rng.uniform(0.2, 1.0))
    q_near = rng.uniform(-np.pi, np.pi, 6)
    direction = rng.normal(size=6)
    q_rand = q_near + rng.uniform(0.3, 0.9) * step * direction / np.abs(direction).max()
    _judge_steer(sub, q_near, q_rand, step, "q_rand within one step: q_rand itself")
    # within one step in every joint, yet more than a step away in the Euclidean norm
    q_rand = q_near + 0.9 * step * rng.choice([-1.0, 1.0], 6)
    _judge_steer(
        sub,
        q_near,
        q_rand,
        step,
        "every joint within one step (‖Δq‖ > step): q_rand itself; the inputs given as lists",
        as_lists=True,
    )
    _judge_steer(sub, q_near, q_near.copy(), step, "q_rand = q_near: q_near itself")


LESSON = Lesson(
    number="09",
    title="Collisions and motion planning: spheres, edges, RRT-Connect",
    summary="collision checking with spheres fitted to the arm (seed 001's joint spheres "
    "measured), signed distances and scenes, checking the edges between waypoints, "
    "RRT-Connect to every IK solution of a pose, shortcutting, the planned motion animated",
    exercises=(
        Exercise(
            id="9.1",
            function="sphere_box_distance",
            title="the signed distance from a ball to a rotated box",
            checks=(
                Check(
                    "a ball beside a face, an edge or a corner of a rotated box, clear of it or "
                    "overlapping it",
                    2,
                    _box_outside,
                ),
                Check(
                    "the centre inside the box: minus its depth below the nearest face",
                    1,
                    _box_inside,
                ),
                Check(
                    "a thin board, a long table with the identity rotation, a point; lists",
                    1,
                    _box_shapes,
                ),
            ),
            answer=(scene,),
        ),
        Exercise(
            id="9.2",
            function="samples_needed",
            title="how many configurations an edge needs so that no sphere moves more than "
            "the resolution between two",
            checks=(
                Check(
                    "random edges: ⌈Σ ρ_j|Δq_j| / resolution⌉ pieces, one sample more",
                    2,
                    _samples_random,
                ),
                Check(
                    "a short edge, a joint turning backwards, joints turning both ways, a joint "
                    "turning more than half a turn, an edge of length zero",
                    1,
                    _samples_edges,
                ),
            ),
            answer=(checks,),
        ),
        Exercise(
            id="9.3",
            function="path_is_free",
            title="a path is free when its waypoints and its edges are",
            checks=(
                Check(
                    "edges that cross a box between free waypoints, thick or thin; free paths",
                    2,
                    _paths_edges,
                ),
                Check(
                    "a waypoint in collision: the start, the goal, one between",
                    1,
                    _paths_waypoints,
                    gated=True,  # "never free" passes too
                ),
                Check(
                    "every edge sampled at the resolution, and no more than twice the samples "
                    "it needs",
                    1,
                    _paths_budget,
                    gated=True,  # "always free" asks for no sample
                ),
            ),
            answer=(checks,),
            builds_on=("9.2",),
        ),
        Exercise(
            id="9.4",
            function="steer",
            title="RRT's step: at most step radians in the largest joint change, towards q_rand",
            checks=(
                Check("far targets: one step of exactly step towards q_rand", 2, _steer_far),
                Check(
                    "near targets are reached, not overshot; q_rand = q_near",
                    1,
                    _steer_near,
                ),
            ),
            answer=(rrt,),
        ),
    ),
)
