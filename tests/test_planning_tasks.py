"""Pick and place: blocks, grasps, sphere covers, box tests, goal validation, the task runner
and its replay — against references computed here (interval arithmetic for upright boxes,
points sampled on boxes and spheres, forward kinematics), never against the code's prints."""

from __future__ import annotations

import math

import numpy as np
import pytest

import urkin
from urkin import planning
from urkin.course.tabletop import (
    HANOI_PEGS,
    LAB_HOME,
    StackPrompt,
    hanoi_moves,
    hanoi_tasks,
    hanoi_world,
    lab_world,
    parse_goal,
)
from urkin.planning.tabletop import SUPPORT_GAP, TOUCH
from urkin.transforms import make_transform, random_rotations, rot_x, rot_z, wrap_angles

# ---------------------------------------------------------------------------- blocks


def test_a_block_must_stand_upright_and_have_a_size_in_metres():
    with pytest.raises(ValueError, match=r"upright.*tilted by 5\.73"):
        planning.Block("A", [0.05] * 3, make_transform(rot_x(0.1)))
    with pytest.raises(ValueError, match="size must be three positive"):
        planning.Block.standing("A", [0.05, 0, 0.05], 0, 0)
    with pytest.raises(ValueError, match="name"):
        planning.Block.standing("", [0.05] * 3, 0, 0)
    b = planning.Block.standing("A", [0.06, 0.04, 0.03], 0.2, -0.1, bottom=0.05, yaw=2.0)
    assert b.bottom == pytest.approx(0.05) and b.top == pytest.approx(0.08)
    assert b.yaw == pytest.approx(2.0)


@pytest.mark.parametrize("square", [True, False])
def test_top_down_grasp_points_down_at_the_top_centre_with_the_nearest_symmetric_yaw(square):
    rng = np.random.default_rng(3)
    for _ in range(200):
        w = rng.uniform(0.02, 0.08)
        size = [w, w, 0.04] if square else [w, w * 1.5, 0.04]
        yaw = rng.uniform(-np.pi, np.pi)
        block = planning.Block.standing("A", size, *rng.uniform(-0.3, 0.3, 2), yaw=yaw)
        near = rng.uniform(-np.pi, np.pi)
        T = planning.top_down_grasp(block, near)
        assert np.allclose(T[:3, 3], [*block.centre[:2], block.top], atol=1e-12)
        assert np.allclose(T[:3, 2], [0, 0, -1], atol=1e-12)
        got = math.atan2(T[1, 0], T[0, 0])
        step = np.pi / 2 if square else np.pi
        k = wrap_angles(got - yaw) / step
        assert abs(k - round(k)) < 1e-9  # the block's yaw turned by its symmetry
        assert abs(wrap_angles(got - near)) <= step / 2 + 1e-9  # the nearest such yaw


def _box_points(size, n=9, surface_only=True):
    g = np.linspace(-0.5, 0.5, n)
    P = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3)
    if surface_only:
        P = P[np.any(np.abs(P) == 0.5, axis=1)]
    return P * size


def _box_distance(P, size):
    """Signed distance of points to an axis-aligned box at the origin."""
    q = np.abs(P) - np.asarray(size) / 2
    outside = np.linalg.norm(np.maximum(q, 0), axis=-1)
    return outside + np.minimum(q.max(axis=-1), 0)


@pytest.mark.parametrize("size", [[0.05, 0.05, 0.05], [0.06, 0.04, 0.03], [0.2, 0.02, 0.1]])
@pytest.mark.parametrize("protrusion", [0.004, 0.008])
def test_block_spheres_cover_the_surface_and_protrude_at_most_as_stated(size, protrusion):
    centres, radii = planning.block_spheres(size, protrusion)
    P = _box_points(np.array(size), n=25)
    d = np.linalg.norm(P[:, None] - centres[None], axis=-1) - radii
    assert d.min(axis=1).max() <= 1e-12  # every surface point is in a sphere
    # the farthest any sphere reaches outside: sample each sphere's surface densely
    u = np.random.default_rng(0).normal(size=(4000, 3))
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    reach = max(_box_distance(c + r * u, size).max() for c, r in zip(centres, radii))
    assert reach <= protrusion + 1e-12
    assert reach > protrusion / 3  # and the bound is not vacuous


@pytest.mark.parametrize(
    "size, protrusion",
    [([50.0, 50.0, 40.0], 0.008), ([1e300] * 3, 0.008), ([0.05] * 3, 1e-7), ([1.0] * 3, 1e-300)],
)
def test_block_spheres_refuse_sizes_that_need_too_many_spheres(size, protrusion):
    """A block in millimetres, or a protrusion far below the sphere model's, would need
    millions of spheres (or overflow the count): refused at once, saying why."""
    with pytest.raises(ValueError, match="sizes are in metres"):
        planning.block_spheres(size, protrusion)


def _upright_depth(ca, ya, ha, cb, yb, hb):
    """The separation of two upright boxes by 1D interval overlaps on the five axes that
    can separate them (both boxes' horizontal axes, and the vertical)."""

    def radius(n, yaw, h):
        ex = np.array([math.cos(yaw), math.sin(yaw), 0.0])
        ey = np.array([-math.sin(yaw), math.cos(yaw), 0.0])
        return abs(n @ ex) * h[0] + abs(n @ ey) * h[1] + abs(n[2]) * h[2]

    axes = [
        np.array([math.cos(y), math.sin(y), 0.0]) for y in (ya, ya + np.pi / 2, yb, yb + np.pi / 2)
    ]
    axes.append(np.array([0.0, 0.0, 1.0]))
    return max(abs(n @ (cb - ca)) - radius(n, ya, ha) - radius(n, yb, hb) for n in axes)


def test_box_separation_is_the_exact_depth_for_upright_boxes():
    rng = np.random.default_rng(7)
    for _ in range(500):
        ha, hb = rng.uniform(0.01, 0.1, 3), rng.uniform(0.01, 0.1, 3)
        ca, cb = rng.uniform(-0.1, 0.1, 3), rng.uniform(-0.1, 0.1, 3)
        ya, yb = rng.uniform(-np.pi, np.pi, 2)
        got = planning.box_separation(ca, rot_z(ya), ha, cb, rot_z(yb), hb)
        assert got == pytest.approx(_upright_depth(ca, ya, ha, cb, yb, hb), abs=1e-12)


def test_box_separation_agrees_with_points_sampled_in_tilted_boxes():
    rng = np.random.default_rng(8)
    R = random_rotations(400, seed=9)
    S = random_rotations(400, seed=10)
    grid = _box_points(np.ones(3), n=7, surface_only=False)
    decided = 0
    for k in range(400):
        ha, hb = rng.uniform(0.02, 0.1, 3), rng.uniform(0.02, 0.1, 3)
        ca, cb = np.zeros(3), rng.uniform(-0.2, 0.2, 3)
        sep = float(planning.box_separation(ca, R[k], ha, cb, S[k], hb))
        swapped = float(planning.box_separation(cb, S[k], hb, ca, R[k], ha))
        assert sep == pytest.approx(swapped, abs=1e-12)
        # points of A inside B prove an overlap; a positive separation must never see one
        P = ca + (grid * 2 * ha) @ R[k].T
        local = (P - cb) @ S[k]
        inside = np.all(np.abs(local) < hb, axis=1).any()
        if inside:
            assert sep < 0
            decided += 1
        if sep > 0:
            assert not inside
    assert decided > 50
    # a common rigid motion changes nothing
    T = make_transform(random_rotations(1, seed=11)[0], [0.3, -0.2, 0.1])
    a = planning.box_separation(ca, R[0], ha, cb, S[0], hb)
    b = planning.box_separation(
        T[:3, :3] @ ca + T[:3, 3],
        T[:3, :3] @ R[0],
        ha,
        T[:3, :3] @ cb + T[:3, 3],
        T[:3, :3] @ S[0],
        hb,
    )
    assert a == pytest.approx(b, abs=1e-12)


# ---------------------------------------------------------------------------- the world


@pytest.fixture(scope="module")
def world():
    return lab_world()


def test_world_refuses_repeated_names_and_other_objects(world):
    a = world.blocks[0]
    with pytest.raises(ValueError, match="repeated: A"):
        planning.World(world.robot, world.model, world.table, [a, a])
    with pytest.raises(TypeError, match="Block"):
        planning.World(world.robot, world.model, world.table, [planning.Box([0, 0, 0], [1] * 3)])
    with pytest.raises(TypeError, match="World"):
        planning.validate_goal("world", ("A", 0, 0))
    with pytest.raises(KeyError, match="no block named 'Z'"):
        world.block("Z")


# ------------------------------------------------------------------- goal validation


def _reasons(world, goal, **kw):
    check = planning.validate_goal(world, goal, **kw)
    assert check.ok == (not check.reasons)
    return check.reasons


def test_each_invalid_goal_class_gets_its_reason_with_numbers(world):
    lo, hi = world.table.footprint().min(axis=0), world.table.footprint().max(axis=0)
    assert _reasons(world, ("B", 0.61, 0.1))[0] == f"outside the table (x = 0.61 > {hi[0]:.2f} m)"
    assert _reasons(world, ("B", 0.1, -0.4))[0] == f"outside the table (y = -0.40 < {lo[1]:.2f} m)"
    far = _reasons(world, ("B", 0.45, -0.25))
    assert far and far[0].startswith("unreachable with the tool down: the target is")
    assert " m beyond the UR3's reach" in far[0]
    gap = _reasons(world, ("B", 0.25, -0.05, 0.02))  # 2 cm above the table
    assert gap == (
        "no support: the block's bottom must be within 5 mm of a top below it; the "
        "nearest (table) is 20 mm off",
    )
    assert _reasons(world, ("B", 0.10, -0.05, 0.02)) == (  # and into A
        "no support: the block's bottom must be within 5 mm of a top below it; the nearest "
        "(table) is 20 mm off",
        "overlaps block A by 30 mm",
    )
    a = world.block("A")
    beside = a.centre[:2] + 0.03 * np.array([np.cos(a.yaw), np.sin(a.yaw)])
    over = _reasons(world, ("B", *beside, None, a.yaw))
    assert over == ("overlaps block A by 20 mm",)  # exact: 5 cm blocks 3 cm apart, same yaw
    assert _reasons(world, ("B", 0.22, 0.15)) == ("overlaps obstacle post by 45 mm",)
    assert _reasons(world, ("Z", 0.1, 0.1)) == ("no block named 'Z' (blocks: A, B)",)
    assert _reasons(world, ("A", "x", 0.1)) == ("x must be a number in metres; got 'x'",)
    assert _reasons(world, ("A", float("nan"), 0.1)) == ("x must be a finite number; got nan",)
    assert _reasons(world, ("A", 0.1)) == ("a goal is (block, x, y[, z[, yaw]]); got ('A', 0.1)",)


def test_a_block_under_another_cannot_move_and_the_reasons_keep_their_order(world):
    a = world.block("A")
    stacked = world.with_block(
        world.block("B").moved(make_transform(rot_z(0.3), [*a.centre[:2], a.top + 0.025]))
    )
    assert stacked.below("B") == "A" and stacked.above("A") == ("B",)
    reasons = _reasons(stacked, ("A", 0.61, 0.1))
    assert reasons[0] == "block A is under block B: move B first"
    assert reasons[1].startswith("outside the table")
    assert reasons[2].startswith("unreachable with the tool down")


def test_stacking_snaps_onto_a_support_within_the_gap_and_contact_is_not_overlap(world):
    a = world.block("A")
    check = planning.validate_goal(world, ("B", *a.centre[:2], a.top + 0.004))
    assert check.ok and check.support == "A"
    assert check.placed.bottom == pytest.approx(a.top, abs=1e-15)
    assert SUPPORT_GAP == 0.005 and TOUCH <= 1e-4


def test_arm_in_collision_at_the_place_pose_names_the_pair():
    # a low roof over the goal: the block fits under it, the gripper does not
    roof = planning.Block.standing("roof", [0.2, 0.2, 0.02], 0.25, -0.05, bottom=0.07)
    world = lab_world(obstacles=(roof,))
    reasons = _reasons(world, ("B", 0.25, -0.05))
    assert len(reasons) == 1 and reasons[0].startswith("arm in collision at the place pose: ")
    assert "roof" in reasons[0] and " by " in reasons[0] and "mm" in reasons[0]


def test_no_path_is_reported_with_the_iterations_and_the_seed(world):
    check = planning.validate_goal(
        world, ("A", 0.0, 0.45), q_start=LAB_HOME, plan=True, seed=0, max_iterations=1
    )
    assert not check.ok and len(check.reasons) == 1
    assert check.reasons[0].startswith(
        "A: transfer failed: no collision-free path found in 1 iteration (seed 0)"
    )
    assert planning.validate_goal(world, ("A", 0.0, 0.45), q_start=LAB_HOME, plan=True).ok


def _independent_verdict(world, name, x, y):
    """Is a goal (on whatever is highest under it) valid?  Re-derived: centre over the table,
    upright-box overlaps by intervals, a closed-form grasp that fk confirms, and some grasp
    configuration whose arm and carried block are free."""
    t = world.table
    local = t.pose[:2, :2].T @ (np.array([x, y]) - t.pose[:2, 3])
    if np.any(np.abs(local) > t.size[:2] / 2):
        return False
    block = world.block(name)
    if any(b.name != name and world.below(b.name) == name for b in world.blocks):
        return False
    tops = [t.top] + [
        b.top
        for b in world.blocks
        if b.name != name
        and np.all(np.abs(b.pose[:2, :2].T @ ([x, y] - b.pose[:2, 3])) <= b.size[:2] / 2)
    ]
    z = max(tops)
    placed = planning.Block.standing(name, block.size, x, y, z)
    for other in world.boxes((name,)):
        if (
            _upright_depth(
                placed.centre, 0.0, placed.size / 2, other.centre, other.yaw, other.size / 2
            )
            < -TOUCH
        ):
            return False
    Ts = [planning.top_down_grasp(placed, y) for y in (0, np.pi / 2, np.pi, -np.pi / 2)]
    sols = [s for T in Ts for s in urkin.ik_analytic(world.robot, T)]
    if not sols:
        return False
    Q = np.array(sols)
    assert np.allclose(urkin.fk(world.robot, Q)[:, 2, 2], -1, atol=1e-9)
    scene = world.scene(without=(name,))
    free = planning.is_free(world.model, scene, Q) & planning.is_free(
        world.carrying(block.size), planning.Scene(), Q
    )
    return bool(free.any())


def test_a_fuzz_of_typed_goals_never_crashes_and_never_accepts_an_invalid_one(world):
    rng = np.random.default_rng(2026)
    junk = [
        "",
        "x",
        "1e999",
        "nan",
        "-inf",
        "0.1 0.2 0.3",
        "A",
        "()",
        "0,1,",
        "1e-320 5",
        "ＡＢ",
        "0x10 2",
        "None",
        "[0.1, 0.2]",
        "0.1;0.2",
        " 0.25   -0.05 ",
    ]
    accepted = 0
    for k in range(1000):
        kind = k % 4
        name = ("A", "B", "C", 3)[rng.integers(4)] if k % 10 == 0 else ("A", "B")[k % 2]
        if kind == 0:  # typed text
            goal = parse_goal(
                junk[rng.integers(len(junk))]
                if rng.random() < 0.3
                else f"{rng.uniform(-0.7, 0.7):.3f} {rng.uniform(-0.5, 0.8):.3f}",
                "A" if name not in ("A", "B") else name,
            )
            if isinstance(goal, str):
                assert goal.startswith("could not read")
                continue
            goal = (goal.block, goal.x, goal.y)
        elif kind == 1:  # anything at all
            anything = [0.1, "0.2", None, np.nan, np.inf, 1e9, -0.05, [1], "A"]
            goal = (name, *(anything[i] for i in rng.integers(len(anything), size=rng.integers(4))))
        else:  # numbers over and around the table
            goal = (name, float(rng.uniform(-0.6, 0.65)), float(rng.uniform(-0.45, 0.75)))
        check = planning.validate_goal(world, goal)
        assert isinstance(check.ok, bool) and all(isinstance(r, str) and r for r in check.reasons)
        if check.ok:
            accepted += 1
            assert _independent_verdict(world, goal[0], float(goal[1]), float(goal[2])), goal
        elif isinstance(goal[0], str) and goal[0] in world.names and len(goal) == 3:
            try:
                x, y = float(goal[1]), float(goal[2])
            except (TypeError, ValueError):
                continue
            if math.isfinite(x) and math.isfinite(y) and abs(x) < 100 and abs(y) < 100:
                assert not _independent_verdict(world, goal[0], x, y), (goal, check.reasons)
    assert accepted > 100


# ---------------------------------------------------------------------------- tasks


def _final_ok(task, tol=1e-3):
    last = {goal.name: goal for goal in task.goals}  # a block may move more than once
    for goal in last.values():
        got = task.world.block(goal.name)
        assert np.linalg.norm(got.centre - goal.centre) < tol
        step = np.pi / 2 if abs(goal.size[0] - goal.size[1]) < 1e-12 else np.pi
        k = wrap_angles(got.yaw - goal.yaw) / step
        assert abs(k - round(k)) < 1e-6


@pytest.fixture(scope="module")
def stack(world):
    return planning.pick_and_place(
        world, [("A", 0.25, -0.05), ("B", 0.25, -0.05)], LAB_HOME, seed=0
    )


def test_two_blocks_are_stacked_at_the_goal_and_the_replay_checks_every_edge(world, stack):
    assert stack.success, stack.reason
    names = [p.name for p in stack.phases]
    assert names == list(planning.tasks.PHASES) * 2
    ok, why, final = planning.replay(world, LAB_HOME, stack.steps())
    assert ok, why
    _final_ok(stack)
    assert final.below("B") == "A" and final.below("A") == "table"
    assert np.linalg.norm(final.block("B").centre - [0.25, -0.05, 0.075]) < 1e-3


def test_the_timed_trajectory_follows_the_checked_phases_and_carries_the_blocks(world, stack):
    t, q = stack.t, stack.q
    assert np.all(np.diff(t) > 0) and t[0] == 0
    assert np.allclose(q[0], LAB_HOME) and np.abs(np.diff(q, axis=0)).max() < 0.2
    assert len(stack.block_poses) == len(t)
    # while A is carried, it keeps its pose in the tool frame
    tools = urkin.fk(world.robot, q)
    rel = np.linalg.inv(tools) @ stack.block_poses[:, 0]
    moving = np.linalg.norm(np.diff(stack.block_poses[:, 0, :3, 3], axis=0), axis=1) > 1e-9
    carried = np.flatnonzero(moving) + 1
    assert len(carried) > 10
    assert np.allclose(rel[carried], rel[carried[0]], atol=1e-9)
    assert np.allclose(rel[carried[0], :3, 3], [0, 0, 0.025], atol=1e-9)
    assert np.allclose(stack.block_poses[-1, 0], stack.world.block("A").pose, atol=1e-9)
    report = stack.report()
    assert report.count("\n") == len(stack.phases) and " NO " not in report


def test_the_tower_of_hanoi_keeps_the_rule_and_ends_on_the_last_peg():
    world = hanoi_world(3)
    moves = hanoi_moves(3)
    assert len(moves) == 7
    goals = hanoi_tasks(world, moves)
    task = planning.pick_and_place(world, goals, LAB_HOME, seed=0)
    assert task.success, task.reason
    ok, why, final = planning.replay(world, LAB_HOME, task.steps())
    assert ok, why
    _final_ok(task)
    for name, under in (("D3", "D2"), ("D2", "D1"), ("D1", "table")):
        assert final.below(name) == under
    assert np.allclose(final.block("D1").centre[:2], HANOI_PEGS[2], atol=1e-3)
    # the rule, from the blocks' heights along the way: never a wider block on a narrower
    widths = {b.name: b.size[0] for b in world.blocks}
    state = world
    for goal in task.goals:
        state = state.with_block(goal)
        under = state.below(goal.name)
        if under != "table":
            assert widths[under] > widths[goal.name]


def test_hanoi_moves_and_the_rule():
    for n in range(1, 6):
        moves = hanoi_moves(n)
        assert len(moves) == 2**n - 1
        pegs = [list(range(n, 0, -1)), [], []]
        for a, b in moves:
            disk = pegs[a].pop()
            assert not pegs[b] or pegs[b][-1] > disk
            pegs[b].append(disk)
        assert pegs[2] == list(range(n, 0, -1))
    with pytest.raises(
        ValueError,
        match=r"move 2 \(0 → 1\): D2 \(5.0 cm\) may not go on the "
        r"smaller D3 \(4.0 cm\)",
    ):
        hanoi_tasks(hanoi_world(3), [(0, 1), (0, 1)])
    with pytest.raises(ValueError, match="peg 1 is empty"):
        hanoi_tasks(hanoi_world(3), [(1, 2)])


# ---------------------------------------------------------------------------- the replay


def test_replay_refuses_bad_tasks_with_the_step_and_the_reason(world, stack):
    steps = stack.steps()
    q_grip = steps[1][1][-1]
    # a straight edge between free waypoints that is not free: waypoints are not enough
    rng = np.random.default_rng(5)
    Q = urkin.robots.random_configurations(world.robot, 400, seed=5)
    Q = Q[planning.is_free(world.model, world.scene(), Q)]
    home = np.broadcast_to(LAB_HOME, Q.shape)
    far = Q[~planning.edges_free(world.model, world.scene(), home, Q)][rng.integers(10)]
    ok, why, _ = planning.replay(world, LAB_HOME, [("move", np.array([LAB_HOME, far]))])
    assert not ok and why.startswith("step 0 (move): in collision: ")
    # gripping away from the block, releasing in the air, ending with a block held
    ok, why, _ = planning.replay(world, LAB_HOME, [("grip", "A")])
    assert not ok and "mm from the centre of A's top face" in why
    lift_end = steps[3][1][-1]
    ok, why, _ = planning.replay(world, LAB_HOME, [*steps[:4], ("release", "A")])
    assert not ok and "released 80.0 mm from the nearest support" in why
    ok, why, _ = planning.replay(world, LAB_HOME, steps[:4])
    assert not ok and why == "the task ends holding A"
    assert np.allclose(steps[3][1][0], q_grip) and lift_end.shape == (6,)
    # a move that does not start where the arm is; a wrong kind; a second grip
    ok, why, _ = planning.replay(world, LAB_HOME, [("move", np.array([q_grip, q_grip]))])
    assert not ok and "from where the arm is" in why
    ok, why, _ = planning.replay(world, LAB_HOME, [("jump", None)])
    assert not ok and "'move', 'grip' or 'release'" in why
    ok, why, _ = planning.replay(world, LAB_HOME, [*steps[:3], ("grip", "B")])
    assert not ok and "already holding A" in why


def test_replay_tests_the_carried_block_exactly(world):
    """Carry A through the post at a height where the gripper passes over the post's top and
    the block, hanging below it, does not: only the block's test can see it."""
    post = world.obstacles[0]
    task = planning.pick_and_place(world, [("A", 0.22, 0.02)], LAB_HOME, seed=0)
    assert task.success, task.reason
    steps = task.steps()
    q_lifted = steps[3][1][-1]
    T = urkin.fk(world.robot, q_lifted)
    height = post.top + 0.03  # block from 0.18 to 0.23 m: its lower 2 cm cross the post
    start = np.array([T[0, 3], T[1, 3], height])
    end = np.array([post.centre[0], post.centre[1] + 0.1, height])
    up = urkin.trajectory.pose_path(urkin.trajectory.line(T[:3, 3], start), T[:3, :3])
    across = urkin.trajectory.pose_path(urkin.trajectory.line(start, end), T[:3, :3])
    q1 = urkin.trajectory.track(world.robot, up, q_lifted)
    q2 = urkin.trajectory.track(world.robot, across, q1.q[-1])
    assert q1.ok.all() and q2.ok.all()
    bad = [*steps[:4], ("move", q1.q), ("move", q2.q)]
    ok, why, _ = planning.replay(world, LAB_HOME, bad)
    assert not ok and why.startswith("step 5 (move): the carried block A overlaps post by")
    # the arm and gripper spheres alone see nothing there
    Q = q2.q
    assert planning.is_free(world.model, world.scene(without=("A",)), Q).all()


def test_pick_and_place_refuses_a_start_in_collision_and_reports_invalid_goals(world):
    inside = np.array(LAB_HOME)
    inside[1] = 0.5  # the upper arm down through the table
    with pytest.raises(ValueError, match=r"q_start is in collision: .*table"):
        planning.pick_and_place(world, [("A", 0.25, -0.05)], inside)
    task = planning.pick_and_place(world, [("A", 0.61, 0.0)], LAB_HOME)
    assert not task.success and "invalid goal: outside the table (x = 0.61" in task.reason
    assert np.allclose(task.q, [LAB_HOME])


def test_the_stack_prompt_asks_again_until_the_goal_is_valid():
    prompt = StackPrompt()
    for text in ("", "over there", "0.61 0.1", "0.22 0.15", "nan 0"):
        answer = prompt.submit(text)
        assert answer.startswith(("Not understood", "Not there")) and not prompt.done
    assert "x = 0.61 > 0.50 m" in prompt.submit("0.61 0.1")
    answer = prompt.submit("0.25 -0.05")
    assert answer.startswith("Done: A at (0.250, -0.050) on the table, B on A") and prompt.done


def test_replay_answers_anything_with_a_reason(world):
    for steps in (
        None,
        "move",
        3,
        [None],
        [("move",)],
        [("move", "abc")],
        [("move", [1, 2])],
        [("move", np.zeros((2, 7)))],
        [("grip", ["A"])],
        [("release", None)],
    ):
        ok, why, after = planning.replay(world, LAB_HOME, steps)
        assert not ok and why and after is world


def test_the_demo_command_asks_again_until_the_goal_is_valid(monkeypatch, capsys):
    from urkin.cli import main

    typed = iter(["somewhere", "0.61 0.1", "0.25 -0.05"])
    monkeypatch.setattr("builtins.input", lambda prompt="": next(typed))
    assert main(["demo", "--task", "stack"]) == 0
    out = capsys.readouterr().out
    assert "Not understood" in out and "outside the table (x = 0.61 > 0.50 m)" in out
    assert "Done: A at (0.250, -0.050) on the table, B on A" in out

    def eof(prompt=""):
        raise EOFError

    monkeypatch.setattr("builtins.input", eof)
    assert main(["demo", "--task", "stack"]) == 1
    assert main(["demo", "--task", "hanoi", "--blocks", "7"]) == 2
    assert "n must be 1 … 4 blocks" in capsys.readouterr().err


def test_goals_all_in_collision_give_a_failed_plan_not_an_exception(world):
    inside = np.array(LAB_HOME)
    inside[1] = 0.5  # the upper arm down through the table
    plan = planning.tasks._plan(world.model, world.scene(), LAB_HOME, inside, seed=0)
    assert not plan.success and "collision" in plan.reason and "table" in plan.reason


def test_replay_checks_the_arm_while_it_carries_a_block(world, stack):
    steps = stack.steps()
    lifted = steps[3][1][-1]
    scene = world.scene(without=("A",))
    Q = urkin.robots.random_configurations(world.robot, 400, seed=6)
    Q = Q[planning.is_free(world.model, scene, Q)]
    start = np.broadcast_to(lifted, Q.shape)
    carried = world.carrying(world.block("A").size)
    # edges on which the arm meets the scene, though neither it nor the block meets itself
    hits = ~planning.edges_free(world.model, scene, start, Q) & planning.edges_free(
        carried, planning.Scene(), start, Q
    )
    for far in Q[hits][:5]:
        ok, why, _ = planning.replay(world, LAB_HOME, [*steps[:4], ("move", [lifted, far])])
        assert not ok and why.startswith("step 4 (move): ")
    last = why.removeprefix("step 4 (move): in collision: ")
    assert any(last.startswith(f"{n} penetrates box") for n in world.model.names), why


def test_tool_yaw_refuses_a_vertical_x_axis_and_names_the_pose():
    from urkin.transforms import rot_y

    assert planning.tool_yaw(make_transform(rot_z(0.3) @ rot_x(0.5))) == pytest.approx(0.3)
    with pytest.raises(ValueError, match="x axis is vertical: it has no yaw"):
        planning.tool_yaw(make_transform(rot_y(np.pi / 2)))
    stack = np.stack([np.eye(4), make_transform(rot_y(-np.pi / 2))])
    with pytest.raises(ValueError, match=r"vertical at \(1,\)"):
        planning.tool_yaw(stack)
