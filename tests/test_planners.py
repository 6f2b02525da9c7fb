"""urkin.course.planners: seed 001's list planner replayed by its stated rule, and RRT-Connect
with its trees kept — every tree edge and every path edge free, the trees' records consistent."""

from __future__ import annotations

import numpy as np
import pytest

from urkin import planning
from urkin.course.planners import rrt_connect_grown, seed001_lists

from .test_planning_rrt import GOAL, MODEL, START, WALL

LOW, HIGH = np.full(6, -np.pi), np.full(6, np.pi)


def _edges_of(tree):
    child = np.flatnonzero(tree.parent >= 0)
    return tree.nodes[tree.parent[child]], tree.nodes[child]


def test_seed_001s_lists_take_a_draw_only_from_their_newest_point():
    grown = seed001_lists(MODEL, WALL, START, GOAL, seed=3, lower=LOW, upper=HIGH)
    rng = np.random.default_rng(3)  # the same draws, replayed by the rule itself
    newest = [START, GOAL]
    for _ in range(grown.iterations):
        x = rng.uniform(LOW, HIGH)
        took = [bool(planning.edges_free(MODEL, WALL, q, x)) for q in newest]
        newest = [x if t else q for t, q in zip(took, newest)]
    assert grown.success and all(took)  # the last draw is shared by both lists
    for tree in (grown.start_tree, grown.goal_tree):
        np.testing.assert_array_equal(tree.parent, np.arange(len(tree.nodes)) - 1)  # a chain
    np.testing.assert_array_equal(grown.path[[0, -1]], [START, GOAL])
    assert planning.edges_free(MODEL, WALL, grown.path[:-1], grown.path[1:]).all()
    assert grown.edges >= 2 * grown.iterations - 1 and grown.samples > grown.edges


def test_rrt_connect_grown_keeps_free_trees_of_short_edges_and_a_free_path():
    grown = rrt_connect_grown(MODEL, WALL, START, GOAL, step=0.4, seed=1, lower=LOW, upper=HIGH)
    assert grown.success and not planning.edges_free(MODEL, WALL, START, GOAL)
    np.testing.assert_array_equal(grown.path[[0, -1]], [START, GOAL])
    assert planning.edges_free(MODEL, WALL, grown.path[:-1], grown.path[1:], 0.005).all()
    for tree, root in ((grown.start_tree, START), (grown.goal_tree, GOAL)):
        np.testing.assert_array_equal(tree.nodes[0], root)
        a, b = _edges_of(tree)
        assert np.abs(b - a).max() <= 0.4 + 1e-12
        assert planning.edges_free(MODEL, WALL, a, b).all()
        assert np.all(np.diff(tree.born) >= 0) and tree.born[-1] <= grown.iterations
        early = tree.until(1)
        assert len(early.nodes) <= len(tree.nodes) and np.all(early.born <= 1)


def test_planning_in_two_joints_holds_the_others_and_failures_are_reported():
    goal = START.copy()
    goal[0] = GOAL[0]
    grown = rrt_connect_grown(
        MODEL,
        WALL,
        START,
        goal,
        joints=(0, 1),
        step=0.3,
        seed=0,
        lower=[-np.pi, -np.pi],
        upper=[np.pi, 0.0],
    )
    assert grown.success and grown.start_tree.nodes.shape[1] == 2
    np.testing.assert_array_equal(grown.path[:, 2:], np.repeat(START[None, 2:], len(grown.path), 0))
    boxed = planning.Scene(boxes=[planning.Box([-0.45, 0.0, 0.3], [0.05, 4.0, 4.0])])
    lists = seed001_lists(MODEL, boxed, START, GOAL, seed=0, max_iterations=5)
    assert not lists.success and lists.iterations == 5 and len(lists.path) == 0
    with pytest.raises(ValueError, match="agree on the joints that are not planned"):
        rrt_connect_grown(MODEL, WALL, START, GOAL, joints=(1,))
    with pytest.raises(ValueError, match="start is in collision"):
        seed001_lists(MODEL, WALL, [0, 0.5, 0, 0, 0, 0], GOAL)
    with pytest.raises(ValueError, match="max_iterations must be at least 1"):
        seed001_lists(MODEL, WALL, START, GOAL, max_iterations=0)
