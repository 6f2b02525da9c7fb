"""RRT-Connect and shortcutting: every returned edge re-checked finer, seeded, honest failures."""

import dataclasses

import numpy as np
import pytest

import urkin
from urkin import planning

UR5 = urkin.robot("ur5")
MODEL = planning.sphere_model(UR5)
WALL = planning.Scene(
    boxes=[
        planning.Box([-0.45, 0.0, 0.3], [0.05, 0.6, 0.6], name="wall"),
        planning.Box([0, 0, -0.06], [2, 2, 0.1], name="table"),
    ]
)
START = np.array([-1.2, -1.2, 1.2, -1.6, -1.57, 0])
GOAL = np.array([1.2, -1.2, 1.2, -1.6, -1.57, 0])


@pytest.mark.parametrize("seed", range(4))
def test_plans_around_a_wall_with_every_edge_free(seed):
    assert not planning.edges_free(MODEL, WALL, START, GOAL)
    plan = planning.rrt_connect(MODEL, WALL, START, GOAL, seed=seed)
    assert plan.success and plan.reason == ""
    np.testing.assert_array_equal(plan.path[0], START)
    np.testing.assert_array_equal(plan.path[-1], GOAL)
    assert planning.edges_free(MODEL, WALL, plan.path[:-1], plan.path[1:], resolution=0.002).all()
    again = planning.rrt_connect(MODEL, WALL, START, GOAL, seed=seed)
    np.testing.assert_array_equal(again.path, plan.path)


def test_open_scene_takes_the_straight_edge_and_several_goals():
    plan = planning.rrt_connect(MODEL, planning.Scene(), START, np.array([GOAL, START + 0.1]))
    assert plan.success and len(plan.path) == 2 and plan.iterations == 0


def test_a_pose_goal_plans_to_one_of_its_ik_solutions():
    T = urkin.fk(UR5, GOAL)
    plan = planning.rrt_connect(MODEL, WALL, START, T, seed=0)
    assert plan.success
    np.testing.assert_allclose(urkin.fk(UR5, plan.path[-1]), T, atol=1e-9)


def test_failures_are_sentences_and_bad_input_is_refused():
    boxed = planning.Scene(
        boxes=[
            planning.Box([-0.45, 0.0, 0.3], [0.05, 2.0, 2.0], name="wall"),
            planning.Box([0.45, 0.0, 0.3], [0.05, 2.0, 2.0], name="wall 2"),
        ]
    )
    plan = planning.rrt_connect(MODEL, boxed, START, GOAL, seed=0, max_iterations=20)
    assert not plan.success  # twenty iterations are not enough between the two walls
    assert plan.reason.startswith("no collision-free path found in 20 iterations (seed 0)")
    assert len(plan.path) == 0 and plan.goal == -1
    with pytest.raises(
        ValueError, match=r"start is in collision: upper arm sphere \d+ penetrates box 'table'"
    ):
        planning.rrt_connect(MODEL, WALL, [0, 0.5, 0, 0, 0, 0], GOAL)
    with pytest.raises(
        ValueError, match=r"no goal can be reached \(1 goals given\): 1 in collision"
    ):
        planning.rrt_connect(MODEL, WALL, START, [0, 0.5, 0, 0, 0, 0])
    # one goal outside the limits, one in collision: each kind counted, with an example
    with pytest.raises(ValueError) as raised:
        planning.rrt_connect(MODEL, WALL, START, [[7, 0, 0, 0, 0, 0], [0, 0.5, 0, 0, 0, 0]])
    message = str(raised.value)
    assert "1 outside the joint limits (goal 0: joint 1 is 7 rad" in message
    assert "1 in collision (goal 1: upper arm sphere" in message
    with pytest.raises(
        ValueError, match=r"goals must be one configuration .* got shape \(2, 3, 6\)"
    ):
        planning.rrt_connect(MODEL, WALL, START, np.tile(GOAL, (2, 3, 1)))
    with pytest.raises(ValueError, match=r"goals \(a pose\) must end in the row \[0, 0, 0, 1\]"):
        planning.rrt_connect(MODEL, WALL, START, np.ones((4, 4)))
    for options, kind, message in (
        ({"seed": "x"}, TypeError, r"seed must be an integer ≥ 0 \(a random seed\); got str 'x'"),
        ({"seed": -1}, ValueError, "seed must be an integer ≥ 0"),
        ({"max_iterations": 2.5}, ValueError, "max_iterations must be an integer ≥ 1; got 2.5"),
        ({"max_iterations": 0}, ValueError, "max_iterations must be an integer ≥ 1; got 0"),
        ({"time_limit": -1}, ValueError, r"time_limit must be seconds \(0 or more\) or None"),
        ({"time_limit": "1"}, TypeError, "time_limit must be seconds"),
        ({"step": float("nan")}, ValueError, r"step must be a positive angle \(rad\); got nan"),
    ):
        with pytest.raises(kind, match=message):
            planning.rrt_connect(MODEL, WALL, START, GOAL, **options)
    far = urkin.transforms.make_transform(np.eye(3), [5.0, 0.0, 0.0])
    with pytest.raises(
        ValueError,
        match=r"no inverse kinematics solution: unreachable: the target is 4\.04\d* m beyond",
    ):
        planning.rrt_connect(MODEL, WALL, START, far)
    for goals, kind, message in (
        ("abc", TypeError, "goals must be numbers; got str"),
        ([[0, 1, 2, 3, 4, 5], [0, 1]], ValueError, "goals must be a regular array of numbers"),
        (
            np.zeros((0, 6)),
            ValueError,
            r"goals: no goal given \(an empty array of shape \(0, 6\)\)",
        ),
    ):
        with pytest.raises(kind, match=message):
            planning.rrt_connect(MODEL, WALL, START, goals)
    with pytest.raises(TypeError, match=r"boxes must be a sequence of planning\.Box"):
        planning.Scene(boxes=5)
    path = [START, GOAL]
    with pytest.raises(ValueError, match="rounds must be an integer ≥ 0; got -1"):
        planning.shortcut(MODEL, WALL, path, rounds=-1)
    with pytest.raises(ValueError, match="batch must be an integer ≥ 1; got 0"):
        planning.shortcut(MODEL, WALL, path, batch=0)
    with pytest.raises(
        TypeError, match=r"seed must be an integer ≥ 0 \(a random seed\); got NoneType"
    ):
        planning.shortcut(MODEL, WALL, path, seed=None)
    with pytest.raises(ValueError, match="start is outside the joint limits: joint 1 is 7"):
        planning.rrt_connect(MODEL, WALL, [7, 0, 0, 0, 0, 0], GOAL)
    with pytest.raises(ValueError, match="start must be one configuration"):
        planning.rrt_connect(MODEL, WALL, np.zeros((2, 6)), GOAL)


def test_shortcut_keeps_the_ends_and_only_free_edges(rng):
    wiggle = np.linspace(START, GOAL, 9)
    wiggle[1:-1, 1] -= 0.6  # lift the upper arm over the wall on the way
    wiggle[1:-1, 2] -= 0.6
    if not planning.edges_free(MODEL, WALL, wiggle[:-1], wiggle[1:]).all():
        pytest.skip("the hand-made detour is not free")
    short = planning.shortcut(MODEL, WALL, wiggle, seed=3)
    assert len(short) <= len(wiggle)
    np.testing.assert_array_equal(short[[0, -1]], wiggle[[0, -1]])
    assert planning.edges_free(MODEL, WALL, short[:-1], short[1:]).all()
    with pytest.raises(ValueError, match="path must have shape"):
        planning.shortcut(MODEL, WALL, START)


def test_trees_grow_past_their_first_capacity():
    """A connect adds a node per step of its run: two iterations can add dozens of nodes."""
    scene = planning.Scene(
        boxes=[
            planning.Box([1.12, 0, 1.0], [2.0, 0.04, 2.2]),
            planning.Box([0, 0, -0.06], [3, 3, 0.1]),
        ]
    )
    start = [-2.6, -1.3, 1.3, -1.57, -1.57, 0]
    goal = [6.0, -1.3, 1.3, -1.57, -1.57, 0]
    plan = planning.rrt_connect(MODEL, scene, start, goal, seed=22, max_iterations=2)
    assert plan.nodes > 2 * 2 + 3


def test_drawing_targets_a_block_at_a_time_extends_from_the_nearest_node(monkeypatch):
    """rrt_connect draws its random targets and checks their new nodes a block at a time;
    which tree extends towards each is decided at the draw, and a tree that grows within the
    block is searched again: every extension starts from the node of its tree nearest its
    target when it runs, and the verdict on its new node is that node's own."""
    runs = []
    original = planning.rrt._Draws.next

    def next_(self, trees, left):
        if not self.queue:
            self._fill(trees, left)
        tree, drawn, target = self.queue[-1][:3]  # drawn: the tree's size at the draw
        result = original(self, trees, left)
        runs.append((tree, drawn, target, tree.nodes[: tree.count].copy(), result))
        return result

    monkeypatch.setattr(planning.rrt._Draws, "next", next_)
    monkeypatch.setattr(planning.rrt, "_DRAWS", 8)
    plan = planning.rrt_connect(MODEL, WALL, START, GOAL, seed=3, simplify=False)
    assert plan.success and plan.iterations > 8 * 4  # the trees grew while blocks were pending
    grown = 0
    for tree, drawn, target, nodes, (extends, near, q_new, free, _) in runs:
        assert extends is tree  # the tree decided at the draw
        gaps = np.linalg.norm(nodes - target, axis=1)
        assert gaps[near] == gaps.min()
        np.testing.assert_array_equal(q_new, planning.rrt._towards(nodes[near], target, 0.5))
        assert free == planning.is_free(MODEL, WALL, [q_new, (nodes[near] + q_new) / 2]).all()
        grown += near >= drawn  # a node added since the block was drawn
    assert grown


def test_the_smaller_tree_extends_while_the_other_is_twice_its_size():
    start, goal = (planning.rrt._Tree(8, np.zeros((n, 6)), np.arange(n) - 1) for n in (1, 1))
    trees = [start, goal]
    assert planning.rrt._extending(trees, None) is start  # the start's tree first
    assert planning.rrt._extending(trees, start) is goal  # then they alternate
    for _ in range(2):
        start.add(np.ones(6), 0)
    assert start.count == 3 and goal.count == 1
    assert planning.rrt._extending(trees, goal) is goal  # the smaller, again and again
    assert planning.rrt._extending(trees, start) is goal
    goal.add(np.ones(6), 0)
    assert planning.rrt._extending(trees, goal) is start  # balanced again: alternate


def test_shortcuts_are_taken_only_where_proven_and_not_certified_again(monkeypatch):
    """A shortcut is taken only where certify_edges proves it free, so the final re-check
    certifies only the path's other edges (the marks _shortcut returns are exactly the
    shortcuts it took) and no shortcut can fail the finer re-check."""
    wiggle = np.linspace(START, GOAL, 9)
    wiggle[1:-1, 1] -= 0.6  # lift the upper arm over the wall on the way
    wiggle[1:-1, 2] -= 0.6
    assert planning.edges_free(MODEL, WALL, wiggle[:-1], wiggle[1:]).all()
    short, taken = planning.rrt._shortcut(MODEL, WALL, wiggle, 3, 30, 16, 0.01)
    assert len(short) < len(wiggle) and taken.any() and len(taken) == len(short) - 1
    rows = {q.tobytes() for q in wiggle}
    assert all(q.tobytes() in rows for q in short)
    assert planning.certify_edges(MODEL, WALL, short[:-1][taken], short[1:][taken]).all()
    # the final re-check is not asked to certify the shortcuts again
    real, asked = planning.rrt._proven, []

    def proven(model, scene, A, B, *rest):
        asked.extend(zip(map(bytes, A), map(bytes, B)))
        return real(model, scene, A, B, *rest)

    monkeypatch.setattr(planning.rrt, "_proven", proven)
    fine, certified = planning.rrt._rechecked(MODEL, WALL, short, 0.01, taken)
    assert fine.all() and certified[taken].all()
    skipped = {(bytes(a), bytes(b)) for a, b in zip(short[:-1][taken], short[1:][taken])}
    assert not skipped & set(asked)


def test_the_final_recheck_gives_the_verdicts_of_both_checks():
    """The final re-check certifies every edge and samples only those it cannot prove free:
    its verdicts are certify_edges' and edges_free's at a quarter of the resolution, edge by
    edge, whether free, blocked or grazing."""
    rng = np.random.default_rng(5)
    path = np.vstack([START, START + rng.normal(0, 0.4, (30, 6)), GOAL])
    fine, proven = planning.rrt._rechecked(MODEL, WALL, path, 0.01)
    A, B = path[:-1], path[1:]
    np.testing.assert_array_equal(proven, planning.certify_edges(MODEL, WALL, A, B))
    np.testing.assert_array_equal(fine, planning.edges_free(MODEL, WALL, A, B, resolution=0.0025))
    assert proven.any() and not fine.all()


def test_an_edge_of_the_trees_that_fails_the_finer_recheck_is_planned_again(monkeypatch):
    """Where an edge of the trees passed at the resolution but fails the re-check at a quarter
    of it, the way between its ends is planned again at half the resolution (here the
    re-check is made to refuse the first edge once)."""
    real, calls = planning.rrt._rechecked, []

    def rechecked(model, scene, path, resolution, known=None):
        calls.append(resolution)
        fine, proven = real(model, scene, path, resolution, known)
        if len(calls) == 1:
            fine[0] = proven[0] = False
        return fine, proven

    monkeypatch.setattr(planning.rrt, "_rechecked", rechecked)
    plan = planning.rrt_connect(MODEL, WALL, START, GOAL, seed=2, simplify=False)
    assert plan.success
    assert calls[:2] == [0.01, 0.005]  # the path at 1 cm, then the edge's new plan at 5 mm
    assert planning.edges_free(MODEL, WALL, plan.path[:-1], plan.path[1:], resolution=0.002).all()
    # when the new plan fails too, the planner says so
    refused = np.zeros(1, bool)
    monkeypatch.setattr(planning.rrt, "_rechecked", lambda *a: (refused.repeat(len(a[2]) - 1),) * 2)
    plan = planning.rrt_connect(MODEL, WALL, START, GOAL, seed=2, simplify=False)
    assert not plan.success and "re-checked at 2.5 mm" in plan.reason


def test_an_edge_free_at_the_samples_but_not_proven_is_replaced(monkeypatch):
    """An edge the final re-check passes but certify_edges cannot prove free (it may graze an
    obstacle between samples) is replaced by a detour through a waypoint near its middle whose
    two edges are proven free; without a detour, it is planned again at half the resolution;
    if that fails too, the edge stays (it is free at every sample)."""
    resolutions = []
    real = planning.rrt._rechecked
    base = planning.rrt_connect(MODEL, WALL, START, GOAL, seed=2, simplify=False)

    def doubt_first(model, scene, path, resolution, known=None):
        resolutions.append(resolution)
        fine, proven = real(model, scene, path, resolution, known)
        if len(resolutions) == 1 and np.array_equal(path[0], base.path[0]):
            proven[0] = False  # the first edge of the first path is in doubt
        return fine, proven

    monkeypatch.setattr(planning.rrt, "_rechecked", doubt_first)
    plan = planning.rrt_connect(MODEL, WALL, START, GOAL, seed=2, simplify=False)
    assert plan.success and resolutions == [0.01]  # no new plan: a detour
    assert len(plan.path) == len(base.path) + 1
    np.testing.assert_array_equal(plan.path[2:], base.path[1:])
    detour = plan.path[1] - (base.path[0] + base.path[1]) / 2
    assert 0 < np.abs(detour).max() < 2.0
    assert planning.certify_edges(MODEL, WALL, plan.path[:-1], plan.path[1:]).all()
    # without a detour: planned again at half the resolution
    resolutions.clear()
    monkeypatch.setattr(planning.rrt, "_detour", lambda *a: None)
    plan = planning.rrt_connect(MODEL, WALL, START, GOAL, seed=2, simplify=False)
    assert plan.success and resolutions[:2] == [0.01, 0.005]
    # never proven: every edge is planned again, fails the same way, and stays
    monkeypatch.setattr(planning.rrt, "_proven", lambda m, s, A, *_: np.zeros(len(A), bool))
    plain = planning.rrt_connect(MODEL, WALL, START, GOAL, seed=2, simplify=False)
    assert plain.success and len(plain.path) >= 2


def test_a_detour_passes_an_obstacle_on_the_edge_with_both_edges_proven():
    """_detour, given an edge that an obstacle cuts at its middle, finds a free waypoint
    nearby whose edges to both ends are proven free, the nearest it tries."""
    a, b = np.array([0.0, -1.2, 1.2, -1.6, -1.57, 0]), np.array([1.0, -1.2, 1.2, -1.6, -1.57, 0])
    middle = MODEL.place((a + b) / 2)[-1]  # the flange's sphere, halfway: a ball there
    scene = planning.Scene(spheres=[planning.Sphere(middle, 0.02)])
    assert planning.is_free(MODEL, scene, np.array([a, b])).all()
    assert not planning.edges_free(MODEL, scene, a, b)
    assert not planning.certify_edges(MODEL, scene, a, b)
    lower, upper = np.array(UR5.joint_limits).T
    waypoint = planning.rrt._detour(MODEL, scene, a, b, np.random.default_rng(0), lower, upper)
    assert waypoint is not None and planning.is_free(MODEL, scene, waypoint)
    assert planning.certify_edges(MODEL, scene, [a, waypoint], [waypoint, b]).all()
    blocked = planning.Scene(spheres=[planning.Sphere(middle, 2.0)])  # nothing gets around
    assert (
        planning.rrt._detour(MODEL, blocked, a, b, np.random.default_rng(0), lower, upper) is None
    )


def test_a_pose_goal_is_reached_where_the_limits_need_a_whole_turn_of_its_solution():
    """Joint 1 limited to 4.5 … 6 rad: the closed-form solution −1.0 rad is reached as 5.28."""
    arm = dataclasses.replace(
        urkin.robot("ur5"), joint_limits=((4.5, 6.0),) + ((-2 * np.pi, 2 * np.pi),) * 5
    )
    model = planning.sphere_model(arm)
    T = urkin.fk(arm, [5.28, -1.2, 1.2, -1.6, -1.57, 0.3])
    plan = planning.rrt_connect(model, planning.Scene(), [5.0, -1.2, 1.2, -1.6, -1.57, 0.0], T)
    assert plan.success
    assert 4.5 <= plan.path[-1][0] <= 6.0
    assert np.abs(urkin.fk(arm, plan.path[-1]) - T).max() < 1e-12


def test_a_step_too_small_to_plan_with_is_refused():
    with pytest.raises(ValueError, match=r"step must be at least 0\.001 rad"):
        planning.rrt_connect(MODEL, planning.Scene(), np.zeros(6), np.full(6, 0.1), step=1e-7)


def test_pick_and_place_checks_its_options_and_start_before_planning():
    from urkin.transforms import make_transform

    ur3 = urkin.robot("ur3").with_tool(make_transform(p=[0, 0, 0.1]))
    model = planning.sphere_model(ur3).with_tool_spheres([[0, 0, -0.05]], 0.02)
    table = planning.Block.standing("table", [1.2, 1.2, 0.03], 0, 0, bottom=-0.03)
    world = planning.World(ur3, model, table, [planning.Block.standing("A", [0.05] * 3, 0.3, 0.1)])
    q_start = [0, -1.8, 1.6, -1.37, -1.5708, 0]
    move = [("A", 0.25, -0.15)]
    for options, error in (
        ({"seed": None}, TypeError),
        ({"seed": -1}, ValueError),
        ({"seed": 1.5}, ValueError),
        ({"max_iterations": 0}, ValueError),
    ):
        with pytest.raises(error, match=next(iter(options))):
            planning.pick_and_place(world, move, q_start, **options)
    with pytest.raises(ValueError, match=r"q_start must be one configuration"):
        planning.pick_and_place(world, move, np.zeros((2, 6)))
    with pytest.raises(ValueError, match=r"q_start must be one configuration"):
        planning.validate_goal(world, move[0], q_start=np.zeros((2, 6)))


def test_booleans_are_not_numbers_and_simplify_is_a_boolean():
    with pytest.raises(TypeError, match="simplify must be True or False"):
        planning.rrt_connect(MODEL, planning.Scene(), np.zeros(6), np.full(6, 0.1), simplify="no")
    with pytest.raises(TypeError, match="booleans"):
        planning.Cylinder([0, 0, 0], [0, 0, 1], True, 1.0)
    with pytest.raises(TypeError, match="booleans"):
        planning.is_free(MODEL, planning.Scene(), np.zeros(6, dtype=bool))
