"""RRT-Connect (Kuffner & LaValle, 2000) in joint space, and shortcutting of its paths.

Two trees grow towards each other: one from the start, one from every goal configuration
(planning to a pose is planning to all of its closed-form IK solutions).  Each iteration
draws a configuration within the joint limits, *extends* one tree by at most ``step`` radians
towards it, then *connects* the other tree to the new node: the whole straight run to it, cut
into pieces no longer than ``step``, is checked in one batched edge check and the free prefix
is added (the pieces' ends first, in one batch).  The trees then swap roles, unless one has
more than twice the other's nodes: then the smaller extends, as in VAMP.  The random
targets are drawn a block at a time and their new nodes, with the middles of their edges,
checked in one batch (most blocked extensions end there, cheaply); which tree extends
towards each is decided as the block is drawn, and a tree that grew meanwhile is searched
again among its new nodes.  The trees
live in preallocated arrays; the nearest node is found over the whole tree with one array
operation.  Every edge of the trees is checked with
:func:`urkin.planning.edges_free` at ``resolution`` (no sphere centre moves further between
samples); a shortcut is taken only where it is proven free between its samples too
(:func:`~urkin.planning.certify_edges`).  The final path's other edges are certified, and
those that cannot be are checked once more at a quarter of the resolution; where an edge of
the trees fails there, or passes but cannot be proven free between its samples, it is
replaced: an edge in doubt by a detour through a waypoint near its middle whose two
edges are proven free (nearby candidates tried in one batch), and otherwise the way between
its ends is planned again at half the resolution (an edge in doubt stays if both fail).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from urkin._inputs import positive, real
from urkin.analytic_ik import _whole_turns_into_limits, ik_analytic, ik_closest
from urkin.kinematics import _joints, _one_configuration
from urkin.planning.checks import (
    FINEST,
    RESOLUTION,
    _check,
    _collides,
    _edges_free,
    _offence,
    _proven,
    _travels,
)
from urkin.planning.scene import Scene, _dot
from urkin.planning.spheres import SphereModel
from urkin.transforms import check_transform

__all__ = ["Plan", "rrt_connect", "shortcut"]


@dataclass(frozen=True)
class Plan:
    """The result of :func:`rrt_connect`.

    Attributes
    ----------
    path : ndarray, shape (M, 6)
        Waypoints from the start to the goal reached (joint space; straight edges between
        them are free); empty when no path was found.
    success : bool
    reason : str
        Empty on success; otherwise a sentence saying why not.
    iterations : int
        Iterations of the planner (draws of a random configuration).
    nodes : int
        Nodes in both trees.
    goal : int
        Index of the goal configuration reached (−1 if none).
    goals : ndarray, shape (G, 6)
        The goal configurations planned to (for a pose target: its IK solutions).
    seconds : float
        Wall-clock time of the call.
    """

    path: np.ndarray
    success: bool
    reason: str
    iterations: int
    nodes: int
    goal: int
    goals: np.ndarray
    seconds: float


def _limits(model: SphereModel) -> tuple[np.ndarray, np.ndarray]:
    limits = np.array(model.robot.joint_limits)
    return limits[:, 0], limits[:, 1]


def _goal_configurations(
    model: SphereModel, goals: ArrayLike, q_start: np.ndarray
) -> tuple[np.ndarray, bool]:
    """The goal configurations (K, 6), and whether they are a pose's solutions."""
    array = real(goals, "goals")
    if array.size == 0:
        raise ValueError(f"goals: no goal given (an empty array of shape {array.shape})")
    if array.shape[-2:] == (4, 4):
        if array.ndim != 2:
            raise ValueError(f"goals: give one pose (4, 4); got shape {array.shape}")
        solutions = ik_analytic(model.robot, check_transform(array, name="goals (a pose)"))
        if len(solutions) == 0:
            why = ik_closest(model.robot, array, np.zeros(6)).reason
            raise ValueError(f"goals: the pose has no inverse kinematics solution: {why}")
        return _turned_into_limits(model, np.asarray(solutions, dtype=float), q_start), True
    Q, lead, _ = _joints(goals, "goals")
    if len(lead) > 1:
        raise ValueError(
            "goals must be one configuration (6,), a list of them (G, 6) or one pose (4, 4); "
            f"got shape {array.shape}"
        )
    return Q.reshape(-1, 6).copy(), False


def _turned_into_limits(model: SphereModel, Q: np.ndarray, q_start: np.ndarray) -> np.ndarray:
    """A pose's solutions (K, 6), in (−π, π], with each joint outside its limits turned by
    whole turns to the equivalent angle nearest the start that is inside them, where one is
    (a joint limited to 4.5 … 6 rad reaches the solution −1.0 as 5.28)."""
    lower, upper = _limits(model)
    near = _whole_turns_into_limits(Q, q_start, lower, upper)
    outside = (Q < lower) | (Q > upper)
    return np.where(outside & (near >= lower) & (near <= upper), near, Q)


def rrt_connect(
    model: SphereModel,
    scene: Scene,
    start: ArrayLike,
    goals: ArrayLike,
    *,
    seed: int = 0,
    max_iterations: int = 100_000,
    time_limit: float | None = None,
    step: float = 0.5,
    resolution: float = RESOLUTION,
    simplify: bool = True,
) -> Plan:
    """A collision-free joint-space path from ``start`` to any of ``goals``.

    Parameters
    ----------
    model : SphereModel
    scene : Scene
    start : array_like, shape (6,)
    goals : array_like, shape (6,), (G, 6) or (4, 4)
        Goal configurations, or a tool pose (all its closed-form IK solutions become goals).
    seed : int
        Seed of the random draws: a seed reproduces a plan exactly.
    max_iterations : int
        Draws of a random configuration before giving up (VAMP's default too: the hardest
        of MotionBenchMaker's UR5 cage problems take over 15,000).
    time_limit : float, optional
        Seconds before giving up (checked once per iteration).
    step : float
        Longest edge of the trees, radians (the largest joint change), at least 1e-3.
    resolution : float
        Edge-check resolution, metres (see :func:`urkin.planning.edges_free`).
    simplify : bool
        Shortcut the path (:func:`shortcut`) before returning it.

    Returns
    -------
    Plan

    Raises
    ------
    ValueError
        When the start is outside the joint limits or in collision, or every goal is (the
        message says which and why), or a pose has no IK solution.

    Examples
    --------
    >>> import urkin
    >>> from urkin import planning
    >>> model = planning.sphere_model(urkin.robot("ur5"))
    >>> wall = planning.Scene(boxes=[planning.Box([-0.45, 0, 0.3], [0.05, 0.6, 0.6])])
    >>> start, goal = [-1.2, -1.2, 1.2, -1.6, -1.57, 0], [1.2, -1.2, 1.2, -1.6, -1.57, 0]
    >>> planning.edges_free(model, wall, start, goal)  # the straight edge hits the wall
    False
    >>> plan = planning.rrt_connect(model, wall, start, goal, seed=0)
    >>> plan.success, bool(planning.edges_free(model, wall, plan.path[:-1], plan.path[1:]).all())
    (True, True)
    """
    t0 = time.perf_counter()
    _check(model, scene)
    _check_options(seed, max_iterations, time_limit, step)
    if not isinstance(simplify, (bool, np.bool_)):
        raise TypeError(f"simplify must be True or False; got {simplify!r:.40}")
    lower, upper = _limits(model)
    q_start = _one_configuration(start, "start")
    _within(q_start, lower, upper, "start")
    if _collides(model, scene, q_start[None])[0]:
        raise ValueError(f"start is in collision: {_offence(model, scene, q_start)}")
    G, pose = _goal_configurations(model, goals, q_start)
    inside = np.all((G >= lower) & (G <= upper), axis=1)
    if not inside.any():
        _within(G[0], lower, upper, "the pose's solution 0" if pose else "goals[0]")
    free = inside & ~_collides(model, scene, G)
    if not free.any():
        raise ValueError(_no_goal(model, scene, G, inside, pose))
    rng = np.random.default_rng(seed)
    capacity = min(2 * max_iterations, 4096) + len(G) + 2  # doubled when full
    trees = [
        _Tree(capacity, q_start[None], np.array([-1])),
        _Tree(capacity, G[free], np.flatnonzero(free)),
    ]
    goal_indices = np.flatnonzero(free)
    # the straight edge first: often enough in an open scene
    starts = np.repeat(q_start[None], len(goal_indices), 0)
    travel = _travels(model, starts, G[goal_indices], resolution)
    direct = _edges_free(model, scene, starts, G[goal_indices], travel, resolution, known=2)
    iterations = 0
    path = None
    if direct.any():
        k = int(goal_indices[np.flatnonzero(direct)[0]])
        path, reached = np.array([q_start, G[k]]), k
    draws = _Draws(model, scene, rng, lower, upper, step, resolution)
    while path is None and iterations < max_iterations:
        if time_limit is not None and time.perf_counter() - t0 > time_limit:
            break
        a, near, q_new, free_end, speeds = draws.next(trees, max_iterations - iterations)
        b = trees[1] if a is trees[0] else trees[0]
        iterations += 1
        if not free_end or not _edge(model, scene, a.nodes[near], q_new, resolution, speeds):
            continue
        new = a.add(q_new, near)
        link = _connect(model, scene, b, q_new, step, resolution)
        if link is not None:
            path, reached = _join(a, b, new, link)
    nodes = trees[0].count + trees[1].count
    if path is None:
        limit = (
            f"within {time_limit:g} s"
            if time_limit is not None and iterations < max_iterations
            else f"in {iterations} iteration{'' if iterations == 1 else 's'}"
        )
        return Plan(
            np.empty((0, 6)),
            False,
            f"no collision-free path found {limit} (seed {seed}): the trees grew to {nodes} "
            "nodes without meeting; the goals may be enclosed, or need more iterations",
            iterations,
            nodes,
            -1,
            G,
            time.perf_counter() - t0,
        )
    known = None  # the edges already proven free: the shortcuts taken
    if simplify and len(path) > 2:
        path, known = _shortcut(model, scene, path, seed, _ROUNDS, _BATCH, resolution)
    fine, proven = _rechecked(model, scene, path, resolution, known)
    # edges free at the samples but not proven free between them (certify_edges) are in
    # doubt: they may graze an obstacle between samples
    doubt = fine & ~proven
    for k in np.flatnonzero(doubt)[::-1]:  # the last first: earlier indices stay
        # an edge in doubt: around it through a waypoint near its middle, both halves proven
        waypoint = _detour(model, scene, path[k], path[k + 1], rng, lower, upper)
        if waypoint is not None:
            path = np.concatenate([path[: k + 1], waypoint[None], path[k + 1 :]])
            fine = np.concatenate([fine[:k], [True, True], fine[k + 1 :]])
            doubt = np.concatenate([doubt[:k], [False, False], doubt[k + 1 :]])
    if (doubt.any() or not fine.all()) and resolution > _FINEST:
        # an edge of the trees that failed the re-check, or is in doubt and has no detour:
        # planned again between its ends at half the resolution; an edge in doubt stays if
        # that fails
        left = None if time_limit is None else max(0.0, time_limit - (time.perf_counter() - t0))
        for k in np.flatnonzero(~fine | doubt)[::-1]:  # the last first: earlier indices stay
            sub = rrt_connect(
                model,
                scene,
                path[k],
                path[k + 1],
                seed=seed,
                max_iterations=max_iterations,
                time_limit=left,
                step=step,
                resolution=resolution / 2,
                simplify=simplify,
            )
            if sub.success:
                path = np.concatenate([path[:k], sub.path, path[k + 2 :]])
                fine = np.concatenate([fine[:k], np.ones(len(sub.path) - 1, bool), fine[k + 1 :]])
    if not fine.all():
        k = int(np.flatnonzero(~fine)[0])
        return Plan(
            path,
            False,
            f"edge {k} of the path collides when re-checked at {resolution / _RECHECK * 1000:g} "
            "mm: plan again with a finer resolution",
            iterations,
            nodes,
            reached,
            G,
            time.perf_counter() - t0,
        )
    return Plan(path, True, "", iterations, nodes, reached, G, time.perf_counter() - t0)


#: The finest resolution an edge that fails the final re-check is planned again at (m), and
#: how much finer than the planning resolution the final re-check is.
_FINEST, _RECHECK = 1e-3, 4


#: Detours around an edge in doubt: how far (rad, per joint, normal) candidate waypoints lie
#: from the edge's middle, smallest first, and how many of each size, all tried in one batch.
_DETOUR_SIZES, _DETOURS = (0.01, 0.03, 0.1, 0.3), 16


def _detour(model, scene, a, b, rng, lower, upper) -> np.ndarray | None:
    """A free waypoint near the middle of the edge ``a`` → ``b`` whose edges to ``a`` and to
    ``b`` are both proven free (:func:`~urkin.planning.certify_edges`): one from the smallest
    spread that has any; None when no candidate is."""
    scale = np.repeat(_DETOUR_SIZES, _DETOURS)[:, None]
    M = (a + b) / 2 + rng.normal(size=(len(scale), 6)) * scale
    M = M[np.all((M >= lower) & (M <= upper), axis=1)]
    M = M[~_collides(model, scene, M)]
    if not len(M):
        return None
    A = np.concatenate([np.repeat(a[None], len(M), axis=0), M])
    B = np.concatenate([M, np.repeat(b[None], len(M), axis=0)])
    proven = _proven(model, scene, A, B, _travels(model, A, B, FINEST), FINEST)
    both = proven[: len(M)] & proven[len(M) :]
    return M[int(np.argmax(both))] if both.any() else None


def _rechecked(model, scene, path: np.ndarray, resolution: float, known=None):
    """Two verdicts on each edge of ``path``: whether it is free at the samples of the final
    re-check, at a quarter of the resolution, and whether it is proven free between them too
    (:func:`~urkin.planning.certify_edges`).  An edge proven free is free at any samples:
    only the others are re-checked; ``known`` (M − 1,) marks edges already proven (the
    shortcuts :func:`_shortcut` took), which are not certified again."""
    A, B = path[:-1], path[1:]
    proven = np.zeros(len(A), dtype=bool) if known is None else known.copy()
    todo = np.flatnonzero(~proven)
    fine = proven.copy()
    if len(todo):
        travel = _travels(model, A[todo], B[todo], resolution)
        proven[todo] = now = _proven(model, scene, A[todo], B[todo], travel, FINEST)
        fine[todo] = now
        if not now.all():
            left = todo[~now]
            fine[left] = _fine(model, scene, A[left], B[left], travel[~now], resolution)
    return fine, proven


def _fine(model, scene, A, B, travel, resolution: float) -> np.ndarray:
    """Whether each edge ``A`` → ``B`` (with its :func:`~urkin.planning.checks._travel`) is
    free at the resolution of the final re-check."""
    return _edges_free(model, scene, A, B, travel, resolution / _RECHECK, known=2)


def _check_options(seed, max_iterations, time_limit, step) -> None:
    positive(seed, "seed", integer=True, zero_ok=True, what=_SEED)
    positive(max_iterations, "max_iterations", integer=True, what="an integer ≥ 1")
    if time_limit is not None:
        positive(time_limit, "time_limit", zero_ok=True, what="seconds (0 or more) or None")
    positive(step, "step", what="a positive angle (rad)")
    if step < _MIN_STEP:
        raise ValueError(
            f"step must be at least {_MIN_STEP:g} rad (a connect adds a node every step: "
            f"smaller steps fill memory before they find anything); got {step!r}"
        )


#: The shortest tree edge rrt_connect takes (rad).
_MIN_STEP = 1e-3


#: What a seed must be (the messages of the option checks).
_SEED = "an integer ≥ 0 (a random seed)"


def _no_goal(
    model: SphereModel, scene: Scene, G: np.ndarray, inside: np.ndarray, pose: bool
) -> str:
    """Why none of the goals ``G`` (K, 6) can be planned to: those not ``inside`` the joint
    limits are outside them, the others in collision; one example of each."""
    what = "solution" if pose else "goal"
    parts = []
    outside = np.flatnonzero(~inside)
    if len(outside):
        k = int(outside[0])
        lower, upper = _limits(model)
        j = int(np.flatnonzero((G[k] < lower) | (G[k] > upper))[0])
        parts.append(
            f"{len(outside)} outside the joint limits ({what} {k}: joint {j + 1} is "
            f"{G[k, j]:.4g} rad, allowed [{lower[j]:.4g}, {upper[j]:.4g}])"
        )
    colliding = np.flatnonzero(inside)
    k = int(colliding[0])
    parts.append(f"{len(colliding)} in collision ({what} {k}: {_offence(model, scene, G[k])})")
    given = f"the pose's {len(G)} solutions" if pose else f"{len(G)} goals given"
    return f"no goal can be reached ({given}): " + "; ".join(parts)


def _within(q: np.ndarray, lower: np.ndarray, upper: np.ndarray, name: str) -> None:
    bad = np.flatnonzero((q < lower) | (q > upper))
    if len(bad):
        j = int(bad[0])
        raise ValueError(
            f"{name} is outside the joint limits: joint {j + 1} is {q[j]:.4g} rad, allowed "
            f"[{lower[j]:.4g}, {upper[j]:.4g}]"
        )


def _towards(q_from: np.ndarray, q_to: np.ndarray, step: float) -> np.ndarray:
    """``q_to``, or the configuration ``step`` from ``q_from`` towards it in the joint that
    moves most: (6,), or (K, 6) for rows of starts and targets."""
    delta = q_to - q_from
    largest = np.max(np.abs(delta), axis=-1, keepdims=True)
    far = largest > step
    scale = np.divide(step, largest, out=np.zeros_like(largest), where=far)
    return np.where(far, q_from + delta * scale, q_to)


def _edge(model, scene, qa, qb, resolution, speeds=None) -> bool:
    """Whether the edge between two free configurations is free (``speeds``: its
    :func:`~urkin.planning.checks._travel`, if known)."""
    A, B = qa[None], qb[None]
    travel = _travels(model, A, B, resolution) if speeds is None else speeds[None]
    return bool(_edges_free(model, scene, A, B, travel, resolution, known=2)[0])


class _Draws:
    """The random targets of the coming iterations, drawn a block at a time, with each one's
    new node (``step`` from the nearest node of the tree that will extend towards it) and the
    middle of its edge checked for collision in one batch, and the speed bounds of the free
    ones' edges found in one more: most extensions fail at their new node or along their
    edge, and one check of many configurations costs little more than one of one.

    Which tree extends in each iteration of a block (:func:`_extending`) is decided when the
    block is drawn, from the trees' sizes then: the balance of the trees is kept a block late
    at most.  (Deciding again at each iteration, as the trees grew, changed a third of the
    draws of MotionBenchMaker's cage problems, hemmed-in trees whose sizes keep crossing the
    balance rule's threshold; each was then placed and checked alone, and the problems took
    1.2–1.6 times as long.)  When a draw comes up whose tree grew since it was drawn, all that
    tree's queued draws are searched again among its new nodes only, and those with a
    nearer node have their new nodes placed and checked again, in one batch."""

    def __init__(self, model, scene, rng, lower, upper, step, resolution) -> None:
        self.model, self.scene, self.rng = model, scene, rng
        self.lower, self.upper, self.step = lower, upper, step
        self.resolution = resolution
        self.last: _Tree | None = None  # the tree that extends in the last iteration drawn
        self.size = min(4, _DRAWS)  # the block size doubles up to _DRAWS: easy problems end soon
        self.queue: list[tuple] = []

    def _fill(self, trees: list[_Tree], left: int) -> None:
        size = min(self.size, left)
        self.size = min(2 * self.size, _DRAWS)
        targets = self.rng.uniform(self.lower, self.upper, (size, 6))
        extends, last = [], self.last  # which tree each draw extends, from the trees now
        for _ in range(size):
            last = _extending(trees, last)
            extends.append(last)
        self.last = last
        near = np.empty(size, dtype=np.intp)
        starts = np.empty((size, 6))
        for tree in trees:  # each tree's nearest nodes to its targets, in one batch
            mine = np.array([t is tree for t in extends])
            if mine.any():
                near[mine] = tree.nearest(targets[mine])
                starts[mine] = tree.nodes[near[mine]]
        new, free, speeds = self._placed(starts, targets)
        self.queue = [
            (tree, tree.count, target, int(k), q, bool(f), v)
            for tree, target, k, q, f, v in zip(extends, targets, near, new, free, speeds)
        ][::-1]

    def _placed(self, starts: np.ndarray, targets: np.ndarray) -> tuple:
        """The new nodes ``step`` from ``starts`` towards ``targets`` (K, 6), whether each is
        free (:func:`_ends_blocked`) and the speed bounds of the free ones' edges (None for
        the others), each found in one batch."""
        new = _towards(starts, targets, self.step)
        free = ~_ends_blocked(self.model, self.scene, starts, new)
        speeds: list[np.ndarray | None] = [None] * len(new)
        if free.any():
            found = _travels(self.model, starts[free], new[free], self.resolution)
            for k, row in zip(np.flatnonzero(free), found):
                speeds[k] = row
        return new, free, speeds

    def _refresh(self, tree: _Tree) -> None:
        """Search ``tree``'s queued draws, drawn before it grew, again among its new nodes;
        those with a nearer node get their new node placed and checked again, in one batch
        (a connect adds many nodes at once, nearer to many of them)."""
        mine = [k for k, entry in enumerate(self.queue) if entry[0] is tree]
        entries = [self.queue[k] for k in mine]
        first = min(entry[1] for entry in entries)
        targets = np.array([entry[2] for entry in entries])
        near = np.array([entry[3] for entry in entries])
        d = tree.nodes[None, first : tree.count] - targets[:, None]
        d2 = _dot(d, d)
        best = np.argmin(d2, axis=1)
        gap = tree.nodes[near] - targets
        nearer = d2[np.arange(len(mine)), best] < _dot(gap, gap)
        for k, entry in zip(mine, entries):  # searched up to the tree's size now
            self.queue[k] = (tree, tree.count, *entry[2:])
        if nearer.any():
            near[nearer] = first + best[nearer]
            new, free, speeds = self._placed(tree.nodes[near[nearer]], targets[nearer])
            for n, k in enumerate(np.flatnonzero(nearer)):
                t = mine[k]
                self.queue[t] = (
                    tree,
                    tree.count,
                    targets[k],
                    int(near[k]),
                    new[n],
                    bool(free[n]),
                    speeds[n],
                )

    def next(self, trees: list[_Tree], left: int) -> tuple:
        """The tree that extends, its node nearest the target, the new node, whether it is
        free and the speed bounds of the edge between them (None if not known)."""
        if not self.queue:
            self._fill(trees, left)
        tree, count = self.queue[-1][:2]
        if tree.count > count:  # grown since drawn: are new nodes nearer?
            self._refresh(tree)
        tree, _, _, near, q_new, free, speeds = self.queue.pop()
        return tree, near, q_new, free, speeds


def _ends_blocked(model, scene, starts: np.ndarray, ends: np.ndarray) -> np.ndarray:
    """Whether each extension from ``starts`` to ``ends`` ((K, 6) or (6,)) is blocked at its
    new node or at the middle of its edge, in one check: most blocked extensions are found
    here, where one configuration costs a few microseconds, rather than by their edge check.
    (K,) bool, or a bool for one extension."""
    ends = np.atleast_2d(ends)
    hit = _collides(model, scene, np.concatenate([ends, (starts + ends) / 2]))
    blocked = hit[: len(ends)] | hit[len(ends) :]
    return bool(blocked[0]) if np.ndim(starts) == 1 else blocked


def _extending(trees: list[_Tree], last: _Tree | None) -> _Tree:
    """The tree that extends next: the smaller while the other has more than twice its nodes
    (balanced trees, as VAMP grows them: a tree hemmed in by obstacles gets the draws), else
    the one that did not extend last (the start's tree first)."""
    start, goal = trees
    if start.count > 2 * goal.count:
        return goal
    if goal.count > 2 * start.count:
        return start
    return goal if last is start else start


#: The largest block of random targets drawn (and their new nodes checked) at once.
_DRAWS = 64


class _Tree:
    """Nodes, parents and the goal each root stands for, in preallocated arrays (doubled when
    full: a connect adds up to one node per ``step`` of its run)."""

    def __init__(self, capacity: int, roots: np.ndarray, goal_of_root: np.ndarray) -> None:
        self.nodes = np.empty((capacity + len(roots), 6))
        self.parent = np.empty(capacity + len(roots), dtype=np.intp)
        self.count = len(roots)
        self.nodes[: self.count] = roots
        self.parent[: self.count] = -1
        self.goal_of_root = goal_of_root
        self.root_goal = None if goal_of_root[0] < 0 else goal_of_root

    def nearest(self, q: np.ndarray) -> int | np.ndarray:
        """The index of the node nearest ``q`` (6,), or of each row of ``q`` (K, 6): (K,)."""
        d = self.nodes[None, : self.count] - np.atleast_2d(q)[:, None]
        near = np.argmin(_dot(d, d), axis=1)
        return int(near[0]) if np.ndim(q) == 1 else near

    def add(self, q: np.ndarray, parent: int) -> int:
        if self.count == len(self.nodes):
            self.nodes = np.concatenate([self.nodes, np.empty_like(self.nodes)])
            self.parent = np.concatenate([self.parent, np.empty_like(self.parent)])
        self.nodes[self.count] = q
        self.parent[self.count] = parent
        self.count += 1
        return self.count - 1

    def branch(self, index: int) -> tuple[np.ndarray, int]:
        """Nodes from ``index`` back to its root, and the root's index."""
        chain = []
        while index >= 0:
            chain.append(index)
            root, index = index, int(self.parent[index])
        return self.nodes[chain], root


def _connect(model, scene, tree: _Tree, q_target: np.ndarray, step: float, resolution: float):
    """Grow ``tree`` straight towards ``q_target`` as far as it is free: the pieces' ends in
    one check, then the pieces up to the first blocked end in one batched edge check; the
    index of the node at ``q_target`` if it was reached."""
    near = tree.nearest(q_target)
    q_near = tree.nodes[near]
    pieces = max(1, math.ceil(float(np.max(np.abs(q_target - q_near))) / step))
    t = np.arange(pieces + 1)[:, None] / pieces
    points = q_near + t * (q_target - q_near)
    blocked = np.flatnonzero(_collides(model, scene, points[1:]))
    usable = pieces if len(blocked) == 0 else int(blocked[0])
    if usable:
        A, B = points[:usable], points[1 : usable + 1]
        travel = _travels(model, A, B, resolution)
        free = _edges_free(model, scene, A, B, travel, resolution, prefix=True, known=2)
        blocked = np.flatnonzero(~free)
        usable = usable if len(blocked) == 0 else int(blocked[0])
    parent = near
    for k in range(1, usable + 1):
        parent = tree.add(points[k], parent)
    return parent if usable == pieces else None


def _join(a: _Tree, b: _Tree, new: int, link: int):
    """The path start → goal through the node ``new`` of the tree that extended and the node
    ``link`` of the tree that connected to it (both at the same configuration)."""
    branch_a, root_a = a.branch(new)
    branch_b, root_b = b.branch(link)
    if a.root_goal is None:  # a grew from the start
        path = np.concatenate([branch_a[::-1], branch_b[1:]])
        goal = int(b.goal_of_root[root_b])
    else:
        path = np.concatenate([branch_b[::-1], branch_a[1:]])
        goal = int(a.goal_of_root[root_a])
    return path, goal


def shortcut(
    model: SphereModel,
    scene: Scene,
    path: ArrayLike,
    *,
    seed: int = 0,
    rounds: int = 30,
    batch: int = 16,
    resolution: float = RESOLUTION,
) -> np.ndarray:
    """A shorter path through fewer waypoints: straight edges that skip waypoints replace the
    waypoints they skip when they are proven free.

    Waypoints where the path goes straight on are dropped first (no check needed: the path
    is the same).
    Each round draws ``batch`` candidate pairs of waypoints (``i < j − 1``) and checks all their
    edges in one batched call at a few samples each (``32 · resolution``: a cheap filter); the
    ones found free there that skip the most without overlapping are then proven free
    throughout, between samples too (as :func:`~urkin.planning.certify_edges` proves them),
    in one more, and those proven are applied.  It stops after ``rounds`` rounds or three
    rounds without a change.

    Returns
    -------
    ndarray, shape (M', 6)
        Starts and ends where ``path`` does.
    """
    _check(model, scene)
    positive(resolution, "resolution", what="a positive distance (m)")
    P, lead, _ = _joints(path, "path")
    if len(lead) != 1 or len(P) < 2:
        raise ValueError(f"path must have shape (M, 6) with M ≥ 2; got {np.shape(path)}")
    positive(seed, "seed", integer=True, zero_ok=True, what=_SEED)
    positive(rounds, "rounds", integer=True, zero_ok=True)
    positive(batch, "batch", integer=True, what="an integer ≥ 1")
    return _shortcut(model, scene, P, seed, rounds, batch, resolution)[0]


#: :func:`shortcut`'s rounds and batch, as :func:`rrt_connect` runs it.
_ROUNDS, _BATCH = 30, 16
#: How much coarser than the resolution :func:`shortcut` samples its candidates before it
#: tries to prove some free.  Measured on the paths of MotionBenchMaker's UR5 problems: 32
#: takes 0.72 of the time of 4 for the same shortened lengths (one chosen candidate in ten
#: then fails its proof, against one in 180); the proof, not the filter, keeps paths free.
_ROUGH = 32


def _shortcut(model, scene, P, seed, rounds, batch, resolution) -> tuple[np.ndarray, np.ndarray]:
    """:func:`shortcut` of a checked path (M, 6), and which edges of the result it proved
    free (the shortcuts it took): (M' − 1,) bool."""
    P = _straightened(P)
    rng = np.random.default_rng(seed)
    refused: set[bytes] = set()  # edges not proven free, by their end configurations
    proven: set[bytes] = set()  # the shortcuts taken
    idle = 0
    for _ in range(rounds):
        if len(P) <= 2 or idle >= 3:
            break
        i = rng.integers(0, len(P) - 2, batch)
        j = np.minimum(i + 2 + rng.integers(0, len(P), batch) % (len(P) - i - 1), len(P) - 1)
        ok = j - i >= 2
        # each candidate once, and none already refused (same choice, less checking)
        keys = [P[a].tobytes() + P[b].tobytes() for a, b in zip(i[ok], j[ok])]
        seen, kept = set(refused), []
        for n, key in enumerate(keys):
            if key not in seen:
                seen.add(key)
                kept.append(n)
        i, j, keys = i[ok][kept], j[ok][kept], [keys[n] for n in kept]
        if len(i) == 0:
            idle += 1
            if len(refused) >= (len(P) - 1) * (len(P) - 2) // 2 and _all_refused(P, refused):
                break  # every shortcut of this path is known refused: no round can change it
            continue
        # every candidate at a few samples; proven free only the longest that do not overlap
        # among those found free
        speeds = _travels(model, P[i], P[j], resolution)
        rough = _edges_free(
            model, scene, P[i], P[j], speeds, _ROUGH * resolution, known=2, prove=False
        )
        chosen = np.flatnonzero(rough)[_apart(i[rough], j[rough])]
        sure = np.zeros(0, dtype=bool)
        if len(chosen):
            sure = _proven(model, scene, P[i[chosen]], P[j[chosen]], speeds[chosen], FINEST)
        refused.update(keys[k] for k in np.flatnonzero(~rough))
        refused.update(keys[k] for k in chosen[~sure])
        taken = chosen[sure]
        if not len(taken):
            idle += 1
            continue
        proven.update(keys[k] for k in taken)
        keep = np.ones(len(P), dtype=bool)
        for a, b in zip(i[taken], j[taken]):
            keep[a + 1 : b] = False
        P = P[keep]
        idle = 0
    taken = np.array([P[a].tobytes() + P[a + 1].tobytes() in proven for a in range(len(P) - 1)])
    return P, taken.astype(bool)


def _straightened(P: np.ndarray) -> np.ndarray:
    """``P`` without the waypoints where it goes straight on (a connect's pieces) or stays:
    the same path, with fewer waypoints to draw shortcuts between."""
    d = np.diff(P, axis=0)
    length = np.linalg.norm(d, axis=1)
    step = d / np.where(length > 0, length, 1.0)[:, None]
    on = (
        (length[:-1] == 0)
        | (length[1:] == 0)
        | (np.einsum("ki,ki->k", step[:-1], step[1:]) >= 1 - 1e-12)
    )
    return P[np.concatenate([[True], ~on, [True]])]


def _apart(i: np.ndarray, j: np.ndarray) -> list[int]:
    """The shortcuts ``i → j`` that skip the most waypoints without overlapping, the longest
    first: their indices."""
    taken: list[int] = []
    for k in np.argsort(i - j, kind="stable"):  # longest skips first
        if all(j[k] <= i[t] or j[t] <= i[k] for t in taken):
            taken.append(int(k))
    return taken


def _all_refused(P: np.ndarray, refused: set[bytes]) -> bool:
    """Whether every edge between two non-neighbouring waypoints of ``P`` is in ``refused``."""
    return all(
        P[a].tobytes() + P[b].tobytes() in refused
        for a in range(len(P) - 2)
        for b in range(a + 2, len(P))
    )
