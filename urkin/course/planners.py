"""Two sampling planners that keep what they grow, for lesson 09's figures: seed 001's two
lists, replayed, and RRT-Connect with its trees.

:func:`urkin.planning.rrt_connect` returns a path, not the trees it grew; the lesson draws the
search itself, so these planners record every node, its parent and the iteration that added it
(:class:`Growth`).  Both plan in a chosen subset of the joints — the others stay at the start's
values — so that a problem in two joints can be drawn in the plane; every edge is checked with
:func:`urkin.planning.edges_free` (no sphere centre moves more than ``resolution`` between its
samples).

**Seed 001** (UR3 in V-REP) keeps two linked lists, one growing from the start and one from the
goal.  Each iteration draws one configuration within the joint bounds; a list takes it when the
straight edge from *the list's newest point* to it is free; the search ends when a configuration
is shared by both lists (both took the same draw), and the path is the start's list followed by
the goal's list reversed.  :func:`seed001_lists` replays that rule; nothing else in the report
constrains it (it gives no step size for the draws, so there is none).

**RRT-Connect** (Kuffner & LaValle, 2000), as :func:`urkin.planning.rrt_connect` runs it: two
trees; each iteration draws a configuration, *extends* one tree from its node nearest the draw by
at most ``step`` radians in the largest joint change, then *connects* the other tree to the new
node — repeated steps of at most ``step`` from its nearest node, as far as the edges are free —
and the trees swap roles.  :func:`rrt_connect_grown` keeps the trees; it checks its edges one
at a time (urkin's planner batches them and preallocates its trees), which is plenty for the
lesson's small problems.

Nothing in :mod:`urkin` uses this module.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from urkin import planning
from urkin.planning.rrt import _towards  # the library's step, the same rule

__all__ = ["Growth", "Tree", "rrt_connect_grown", "seed001_lists"]


@dataclass(frozen=True)
class Tree:
    """Nodes grown from one root (a list is a tree whose parent is always the previous node).

    Attributes
    ----------
    nodes : ndarray, shape (N, k)
        The nodes in the planned joints (rad), the root first.
    parent : ndarray of int, shape (N,)
        Each node's parent (−1 for the root).
    born : ndarray of int, shape (N,)
        The iteration that added each node (0 for the root).
    """

    nodes: np.ndarray
    parent: np.ndarray
    born: np.ndarray

    def until(self, iteration: int) -> Tree:
        """The tree as it stood after ``iteration`` iterations."""
        keep = self.born <= iteration
        return Tree(self.nodes[keep], self.parent[keep], self.born[keep])


@dataclass(frozen=True)
class Growth:
    """What a recording planner grew.

    Attributes
    ----------
    start_tree, goal_tree : Tree
        Grown from the start and from the goal.
    path : ndarray, shape (M, 6)
        Full configurations from start to goal (empty when none was found).
    success : bool
    iterations : int
        Random draws made.
    joints : tuple of int
        The planned joints (0-based); the others keep the start's values.
    edges : int
        Edges checked.
    samples : int
        Configurations on those edges at the resolution (both ends included): the collision
        checks they cost when free (a check stops at the first collision it finds).
    """

    start_tree: Tree
    goal_tree: Tree
    path: np.ndarray
    success: bool
    iterations: int
    joints: tuple[int, ...]
    edges: int = 0
    samples: int = 0


class _Edges:
    """Edge checks of full configurations, counted."""

    def __init__(self, model, scene, base, joints, resolution) -> None:
        self.model, self.scene, self.base, self.joints = model, scene, base, joints
        self.resolution = resolution
        self.edges = self.samples = 0

    def free(self, xa: np.ndarray, xb: np.ndarray) -> bool:
        qa, qb = _full(self.base, self.joints, xa), _full(self.base, self.joints, xb)
        self.edges += 1
        self.samples += int(planning.edge_samples(self.model, qa, qb, self.resolution)) + 1
        return bool(planning.edges_free(self.model, self.scene, qa, qb, self.resolution))


class _Grower:
    """A tree in preallocated arrays (nodes in the planned joints)."""

    def __init__(self, root: np.ndarray, capacity: int) -> None:
        self.nodes = np.empty((capacity, len(root)))
        self.parent = np.empty(capacity, dtype=np.intp)
        self.born = np.empty(capacity, dtype=np.intp)
        self.nodes[0], self.parent[0], self.born[0] = root, -1, 0
        self.count = 1

    def add(self, q: np.ndarray, parent: int, iteration: int) -> int:
        k = self.count
        self.nodes[k], self.parent[k], self.born[k] = q, parent, iteration
        self.count += 1
        return k

    def nearest(self, q: np.ndarray) -> int:
        d = self.nodes[: self.count] - q
        return int(np.argmin(np.einsum("ij,ij->i", d, d)))

    def branch(self, k: int) -> np.ndarray:
        """Nodes from ``k`` back to the root."""
        chain = []
        while k >= 0:
            chain.append(k)
            k = int(self.parent[k])
        return self.nodes[chain]

    def tree(self) -> Tree:
        n = self.count
        return Tree(self.nodes[:n].copy(), self.parent[:n].copy(), self.born[:n].copy())


def _setup(model, scene, start, goal, joints, lower, upper, max_iterations):
    start = np.array(start, dtype=float).reshape(6)
    goal = np.array(goal, dtype=float).reshape(6)
    joints = tuple(int(j) for j in joints)
    if not joints or len(set(joints)) != len(joints) or not all(0 <= j < 6 for j in joints):
        raise ValueError(f"joints must be distinct joint indices 0 … 5; got {joints}")
    if not max_iterations >= 1:
        raise ValueError(f"max_iterations must be at least 1; got {max_iterations}")
    fixed = [j for j in range(6) if j not in joints]
    if not np.allclose(start[fixed], goal[fixed], rtol=0, atol=1e-12):
        raise ValueError("start and goal must agree on the joints that are not planned")
    limits = np.array(model.robot.joint_limits, dtype=float)[list(joints)]
    lo = limits[:, 0] if lower is None else np.asarray(lower, dtype=float)
    hi = limits[:, 1] if upper is None else np.asarray(upper, dtype=float)
    for name, q in (("start", start), ("goal", goal)):
        if not planning.is_free(model, scene, q):
            why = planning.explain(model, scene, q).removeprefix("in collision: ")
            raise ValueError(f"{name} is in collision: {why}")
    return start, goal, joints, lo, hi


def _full(base: np.ndarray, joints: tuple[int, ...], x: np.ndarray) -> np.ndarray:
    q = base.copy()
    q[list(joints)] = x
    return q


def seed001_lists(
    model: planning.SphereModel,
    scene: planning.Scene,
    start: ArrayLike,
    goal: ArrayLike,
    *,
    joints: tuple[int, ...] = (0, 1, 2, 3, 4, 5),
    lower: ArrayLike | None = None,
    upper: ArrayLike | None = None,
    seed: int = 0,
    max_iterations: int = 500,
    resolution: float = 0.01,
) -> Growth:
    """Seed 001's planner: two lists, each extended only from its newest point (module notes).

    Parameters
    ----------
    model, scene
        The arm's spheres and the obstacles.
    start, goal : array_like, shape (6,)
        Free configurations that agree on the joints not in ``joints``.
    joints : tuple of int
        The joints planned (0-based).
    lower, upper : array_like, optional
        Bounds of the draws in those joints (rad); the joint limits by default.
    seed : int
        Seed of the draws.
    max_iterations : int
        Draws before giving up (the report's counter).
    resolution : float
        Edge-check resolution (m), as for :func:`urkin.planning.edges_free`.

    Returns
    -------
    Growth

    Examples
    --------
    >>> import urkin
    >>> from urkin import planning
    >>> model = planning.sphere_model(urkin.robot("ur5"))
    >>> q = np.array([-1.2, -1.2, 1.2, -1.6, -1.57, 0.0])
    >>> grown = seed001_lists(model, planning.Scene(), q, q + [2.4, 0, 0, 0, 0, 0], joints=(0,))
    >>> grown.success, grown.iterations  # the first draw is free from both newest points
    (True, 1)
    """
    start, goal, joints, lo, hi = _setup(
        model, scene, start, goal, joints, lower, upper, max_iterations
    )
    rng = np.random.default_rng(seed)
    lists = [_Grower(start[list(joints)], max_iterations + 1)]
    lists.append(_Grower(goal[list(joints)], max_iterations + 1))
    edges = _Edges(model, scene, start, joints, resolution)
    path = np.empty((0, 6))
    for iteration in range(1, max_iterations + 1):
        x = rng.uniform(lo, hi)
        took = []
        for grower in lists:
            newest = grower.count - 1
            if edges.free(grower.nodes[newest], x):
                took.append(grower.add(x, newest, iteration))
        if len(took) == 2:  # the draw is shared by both lists
            chain = np.concatenate([lists[0].branch(took[0])[::-1], lists[1].branch(took[1])[1:]])
            path = np.array([_full(start, joints, x) for x in chain])
            break
    return Growth(
        lists[0].tree(),
        lists[1].tree(),
        path,
        len(path) > 0,
        iteration,
        joints,
        edges.edges,
        edges.samples,
    )


def rrt_connect_grown(
    model: planning.SphereModel,
    scene: planning.Scene,
    start: ArrayLike,
    goal: ArrayLike,
    *,
    joints: tuple[int, ...] = (0, 1, 2, 3, 4, 5),
    lower: ArrayLike | None = None,
    upper: ArrayLike | None = None,
    step: float = 0.3,
    seed: int = 0,
    max_iterations: int = 500,
    resolution: float = 0.01,
) -> Growth:
    """RRT-Connect that keeps its two trees (module notes).

    Parameters are those of :func:`seed001_lists`, and ``step``: the longest edge of the trees,
    radians (the largest joint change).

    Returns
    -------
    Growth

    Examples
    --------
    >>> import urkin
    >>> from urkin import planning
    >>> model = planning.sphere_model(urkin.robot("ur5"))
    >>> q = np.array([-1.2, -1.2, 1.2, -1.6, -1.57, 0.0])
    >>> grown = rrt_connect_grown(model, planning.Scene(), q, q + [2.4, 0, 0, 0, 0, 0],
    ...                           joints=(0,), step=0.5)
    >>> grown.success, len(grown.path), grown.start_tree.nodes.shape[1]
    (True, 6, 1)
    """
    start, goal, joints, lo, hi = _setup(
        model, scene, start, goal, joints, lower, upper, max_iterations
    )
    if not step > 0:
        raise ValueError(f"step must be positive; got {step}")
    rng = np.random.default_rng(seed)
    capacity = 2 + max_iterations * (2 + int(np.ceil(np.max(hi - lo) / step)))
    start_tree = _Grower(start[list(joints)], capacity)
    goal_tree = _Grower(goal[list(joints)], capacity)
    trees = [start_tree, goal_tree]  # [the tree that extends, the tree that connects]

    free = _Edges(model, scene, start, joints, resolution)

    for iteration in range(1, max_iterations + 1):
        a, b = trees
        x = rng.uniform(lo, hi)
        near = a.nearest(x)
        x_new = _towards(a.nodes[near], x, step)
        if free.free(a.nodes[near], x_new):
            new = a.add(x_new, near, iteration)
            k = b.nearest(x_new)  # connect b to the new node, step by step
            while True:
                x_next = _towards(b.nodes[k], x_new, step)
                if not free.free(b.nodes[k], x_next):
                    break
                k = b.add(x_next, k, iteration)
                if np.array_equal(x_next, x_new):
                    ends = {id(a): new, id(b): k}
                    to_start = start_tree.branch(ends[id(start_tree)])  # meeting node → start
                    to_goal = goal_tree.branch(ends[id(goal_tree)])  # meeting node → goal
                    path = np.concatenate([to_start[::-1], to_goal[1:]])
                    full = np.array([_full(start, joints, x) for x in path])
                    return Growth(
                        start_tree.tree(),
                        goal_tree.tree(),
                        full,
                        True,
                        iteration,
                        joints,
                        free.edges,
                        free.samples,
                    )
        trees.reverse()
    return Growth(
        start_tree.tree(),
        goal_tree.tree(),
        np.empty((0, 6)),
        False,
        max_iterations,
        joints,
        free.edges,
        free.samples,
    )
