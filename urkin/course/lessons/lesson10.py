"""Lesson 10 — pick and place: grasp frames, goal validation, a two-block stack, the Tower of
Hanoi.

Every expected answer here is computed by the check's own formulas — the grasp from its
definition, a goal's broken rules from boxes and the closed-form IK, the Tower of Hanoi by
simulating the pegs — never by the library functions that are the exercises' hidden answers
(``top_down_grasp``, ``validate_goal``, ``pick_and_place``).  A stacking task (10.3) is judged
by :func:`urkin.planning.replay`, which checks every configuration and edge of it from scratch;
its goals are drawn so that urkin's own planner can do them (on the trusted side).  Every
named mistake is a hypothesis that computes its typical wrong answer, or (10.3) the replay's
verdict on the student's task read for its cause.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from urkin.analytic_ik import ik_analytic
from urkin.course.compare import Mismatch, as_array, compare, require_transform, unless_right
from urkin.course.exercise import Check, Exercise, Lesson
from urkin.course.lab import LAB_BASE_IN_WORLD, lab_robot
from urkin.course.tabletop import GRIPPER_SPHERES, LAB_HOME, TABLE, lab_world
from urkin.planning import blocks, tabletop, tasks
from urkin.planning.blocks import Block
from urkin.planning.spheres import sphere_model
from urkin.planning.tabletop import World
from urkin.robots import robot as make_robot
from urkin.transforms import inv_transform, make_transform, rot_z, so3_exp

#: A tool pointing down, its x axis along the world's x: rot_x(π).
_DOWN = np.diag([1.0, -1.0, -1.0])

# ----------------------------------------------------------------------- 10.1 grasp_flange_pose

_UP = (
    "the tool points up: its z axis must point straight down, into the block's top face "
    "(a rotation by π about the tool's x axis, R = Rz(yaw)·diag(1, −1, −1))"
)
_NOT_REDUCED = (
    "the block's yaw used as it is: the tool's yaw is the block's yaw plus the multiple of its "
    "symmetry (90° for a square footprint, 180° otherwise) nearest yaw_now, so that the last "
    "joint turns as little as possible"
)
_HALF_TURN_SQUARE = (
    "a square block reduced by 180° only: a square footprint looks the same every 90°, so "
    "four tool yaws grasp it"
)
_QUARTER_TURN_OBLONG = (
    "an oblong block turned by 90°: only a square footprint is the same after a quarter "
    "turn; an oblong one repeats every 180°"
)
_NEAREST_ZERO = (
    "the multiple nearest 0 instead of nearest yaw_now: the point is to turn the wrist as "
    "little as possible from where it is"
)
_NOT_AROUND = (
    "the nearest yaw measured along the line, not around the circle: 3.0 rad and −3.1 rad "
    "are 0.18 rad apart; compare angles by their wrapped difference (or round "
    "(yaw_now − yaw_block) / symmetry to the nearest whole number)"
)
_YAW_NOW = (
    "the wrist's current yaw kept: the tool's yaw must match the block's faces (the block's "
    "yaw plus a multiple of its symmetry)"
)
_X_FLIPPED = (
    "the tool's x axis turned by π (a rotation by π about y instead of about x): the tool's "
    "x axis is the block's x axis turned by the chosen multiple of the symmetry"
)
_NO_OFFSET = (
    "the gripper's offset forgotten: that is the tool's pose; the flange is T_world_tool · "
    "T_flange_tool⁻¹"
)
_NOT_INVERTED = (
    "T_flange_tool applied without inverting it: T_world_tool = T_world_flange · "
    "T_flange_tool, so T_world_flange = T_world_tool · T_flange_tool⁻¹"
)
_WRONG_SIDE = (
    "T_flange_tool⁻¹ multiplied on the left: it is expressed in the flange's frame, so it "
    "goes on the right, T_world_tool · T_flange_tool⁻¹"
)
_AT_CENTRE = (
    "the grasp at the block's centre: the suction cup holds the centre of the top face, half "
    "the block's height above its centre"
)
_FULL_HEIGHT = (
    "the full height added to the centre: the top face is half the height above the centre "
    "(the pose is the pose of the block's centre)"
)


def _grasp(
    T_block,
    size,
    yaw_now,
    T_ft,
    *,
    axis="down",
    step="symmetry",
    near="circle",
    position="top",
    tool="inverse",
) -> np.ndarray:
    """The check's flange pose for a grasp (or a named mistake's)."""
    T_block = np.asarray(T_block, dtype=float)
    size = np.asarray(size, dtype=float)
    yaw_block = math.atan2(T_block[1, 0], T_block[0, 0])
    square = abs(size[0] - size[1]) <= 1e-9
    symmetry = {
        "symmetry": math.pi / 2 if square else math.pi,
        "half": math.pi,
        "quarter": math.pi / 2,
    }[step]
    if near == "circle":  # every 2π-periodic candidate: the nearest on the line is nearest
        yaw = yaw_block + round((yaw_now - yaw_block) / symmetry) * symmetry
    elif near == "none":
        yaw = yaw_block
    elif near == "zero":
        yaw = yaw_block - round(yaw_block / symmetry) * symmetry
    elif near == "line":
        k = np.arange(round(2 * math.pi / symmetry))
        candidates = np.angle(np.exp(1j * (yaw_block + k * symmetry)))
        yaw = float(candidates[np.argmin(np.abs(candidates - yaw_now))])
    else:  # "now"
        yaw = yaw_now
    R = rot_z(yaw) @ {"down": _DOWN, "up": np.eye(3), "flipped": np.diag([-1.0, 1.0, -1.0])}[axis]
    lift = {"top": size[2] / 2, "centre": 0.0, "full": size[2]}[position]
    T_tool = make_transform(R, T_block[:3, 3] + [0.0, 0.0, lift])
    T_ft = np.asarray(T_ft, dtype=float)
    return {
        "inverse": T_tool @ inv_transform(T_ft),
        "none": T_tool,
        "forward": T_tool @ T_ft,
        "left": inv_transform(T_ft) @ T_tool,
    }[tool]


_GRASP_MISTAKES = {
    _UP: {"axis": "up"},
    _X_FLIPPED: {"axis": "flipped"},
    _NOT_AROUND: {"near": "line"},
    _NOT_REDUCED: {"near": "none"},
    _HALF_TURN_SQUARE: {"step": "half"},
    _QUARTER_TURN_OBLONG: {"step": "quarter"},
    _NEAREST_ZERO: {"near": "zero"},
    _YAW_NOW: {"near": "now"},
    _NO_OFFSET: {"tool": "none"},
    _NOT_INVERTED: {"tool": "forward"},
    _WRONG_SIDE: {"tool": "left"},
    _AT_CENTRE: {"position": "centre"},
    _FULL_HEIGHT: {"position": "full"},
}


def _judge_grasp(sub, T_block, size, yaw_now, T_ft, what, *, as_lists=False):
    inputs = {
        "T_world_block": T_block,
        "block_size": size,
        "yaw_now": yaw_now,
        "T_flange_tool": T_ft,
    }
    args = [x.tolist() if as_lists else x.copy() for x in (T_block, size)]
    value = sub.grasp_flange_pose(args[0], args[1], float(yaw_now), T_ft.copy())
    call = "grasp_flange_pose(T_world_block, block_size, yaw_now, T_flange_tool)"
    got = as_array(value, (4, 4), call, inputs)
    right = _grasp(T_block, size, yaw_now, T_ft)
    hypotheses = {
        name: (lambda how=how: _grasp(T_block, size, yaw_now, T_ft, **how))
        for name, how in _GRASP_MISTAKES.items()
    }
    try:
        compare(got, right, what=what, inputs=inputs, hypotheses=unless_right(hypotheses, right))
    except Mismatch as exc:
        if exc.mistake is None:
            require_transform(got, "the returned pose", inputs)
        raise


def _lab_tool() -> np.ndarray:
    return np.asarray(lab_robot().tool, dtype=float)


def _yaw_away_from_ties(rng, yaw_block: float, symmetry: float, margin: float = 0.12) -> float:
    """A wrist yaw whose nearest grasp yaw is clear: at least ``margin`` from the midpoint
    between two candidates, and not one of them."""
    while True:
        offset = rng.uniform(0.0, symmetry)
        if abs(offset - symmetry / 2) > margin and min(offset, symmetry - offset) > 0.05:
            k = int(rng.integers(-2, 3))
            return float(np.angle(np.exp(1j * (yaw_block + offset + k * symmetry))))


def _block_pose(rng, size, *, bottom=None) -> np.ndarray:
    bottom = float(rng.uniform(0.0, 0.15)) if bottom is None else bottom
    yaw = float(rng.uniform(-math.pi, math.pi))
    centre = [rng.uniform(-0.2, 0.45), rng.uniform(-0.25, 0.5), bottom + size[2] / 2]
    return make_transform(rot_z(yaw), centre)


def _grasp_square(sub, rng):
    for k in range(4):  # the nearest grasp yaw is the block's turned by k quarter turns
        w = rng.uniform(0.03, 0.08)
        size = np.array([w, w, rng.uniform(0.02, 0.1)])
        T_block = _block_pose(rng, size, bottom=0.0)
        yaw_block = math.atan2(T_block[1, 0], T_block[0, 0])
        offset = rng.uniform(0.05, math.pi / 4 - 0.12) * rng.choice([-1.0, 1.0])
        yaw_now = float(np.angle(np.exp(1j * (yaw_block + k * math.pi / 2 + offset))))
        _judge_grasp(
            sub,
            T_block,
            size,
            yaw_now,
            _lab_tool(),
            "a square block on the table, the lab's gripper: the top face's centre, tool z "
            "down, the block's yaw plus the multiple of 90° nearest yaw_now",
        )


def _grasp_oblong(sub, rng):
    for k in range(3):  # two of them with the wrist nearer a quarter turn than a half turn
        w = rng.uniform(0.03, 0.06)
        size = np.array([w, w + rng.uniform(0.015, 0.05), rng.uniform(0.02, 0.1)])
        if rng.random() < 0.5:
            size[:2] = size[1::-1]
        T_block = _block_pose(rng, size)
        yaw_block = math.atan2(T_block[1, 0], T_block[0, 0])
        if k == 0:
            yaw_now = _yaw_away_from_ties(rng, yaw_block, math.pi)
        else:
            offset = rng.uniform(math.pi / 4 + 0.1, math.pi / 2 - 0.12) * rng.choice([-1, 1])
            turn = int(rng.integers(2)) * math.pi
            yaw_now = float(np.angle(np.exp(1j * (yaw_block + turn + offset))))
        _judge_grasp(
            sub,
            T_block,
            size,
            yaw_now,
            _lab_tool(),
            "an oblong block (its footprint repeats every 180°): the block's yaw plus the "
            "multiple of 180° nearest yaw_now",
        )


def _random_tool(rng) -> np.ndarray:
    axis = rng.normal(size=3)
    R = so3_exp(axis / np.linalg.norm(axis) * rng.uniform(0.4, math.pi))
    return make_transform(R, rng.uniform(-0.1, 0.1, 3))


def _grasp_tools(sub, rng):
    # yaw_now near +π, the nearest grasp yaw just past −π: nearest around the circle
    for sign in (1.0, -1.0):
        w = rng.uniform(0.03, 0.07)
        square = sign > 0
        size = np.array([w, w if square else w + rng.uniform(0.02, 0.04), rng.uniform(0.02, 0.08)])
        symmetry = math.pi / 2 if square else math.pi
        a, b = rng.uniform(0.05, 0.3, 2)
        yaw_now = sign * (math.pi - a)
        target = -sign * (math.pi - b)  # a + b from yaw_now, across ±π
        # the block's own yaw neither the nearest around the circle nor along the line
        turns = int(rng.integers(1, 3)) if square else 0
        yaw_block = float(np.angle(np.exp(1j * (target + turns * symmetry))))
        centre = [rng.uniform(-0.2, 0.45), rng.uniform(-0.25, 0.5), rng.uniform(0.0, 0.2)]
        _judge_grasp(
            sub,
            make_transform(rot_z(yaw_block), centre),
            size,
            yaw_now,
            _random_tool(rng),
            "yaw_now near ±π, the nearest grasp yaw across it; a tool turned and offset at "
            "random; the inputs given as lists",
            as_lists=True,
        )
    # a wrist wound beyond ±π, a block on another one
    w = rng.uniform(0.03, 0.07)
    size = np.array([w, w, rng.uniform(0.02, 0.08)])
    T_block = _block_pose(rng, size, bottom=float(rng.uniform(0.03, 0.2)))
    yaw_block = math.atan2(T_block[1, 0], T_block[0, 0])
    yaw_now = _yaw_away_from_ties(rng, yaw_block, math.pi / 2) + rng.choice([-1, 1]) * 2 * math.pi
    _judge_grasp(
        sub,
        T_block,
        size,
        yaw_now,
        _random_tool(rng),
        "yaw_now wound beyond ±π (the same wrist angle, a turn further), a block standing on "
        "another one, a random tool",
    )


# --------------------------------------------------------------------------- the world as data

RULES = ("table", "reach", "support", "overlap")
#: A block's bottom may be this far from a top and still rest on it (m).
SUPPORT_GAP = 0.005
#: Deeper than this (m) is an overlap; less is touching.
TOUCH = 1e-4


def world_data(world: World, gripper: np.ndarray = GRIPPER_SPHERES) -> dict:
    """A :class:`~urkin.planning.World` as plain data: what 10.2 and 10.3 receive."""

    def box(b: Block) -> dict:
        return {"size": np.array(b.size, dtype=float), "pose": np.array(b.pose, dtype=float)}

    return {
        "robot": world.robot,
        "gripper": np.asarray(gripper, dtype=float),
        "table": box(world.table),
        "blocks": {b.name: box(b) for b in world.blocks},
        "obstacles": {b.name: box(b) for b in world.obstacles},
    }


def _describe(world: World) -> str:
    def at(b: Block) -> str:
        x, y = b.centre[:2]
        dims = "×".join(f"{100 * s:.1f}" for s in b.size)
        return f"{b.name} {dims} cm at ({x:.3f}, {y:.3f}), bottom {b.bottom:.3f}, yaw {b.yaw:.2f}"

    base = world.robot.base[:3, 3]
    parts = [
        f"base at ({base[0]:.3f}, {base[1]:.3f}, {base[2]:.3f})",
        "blocks: " + "; ".join(at(b) for b in world.blocks),
    ]
    if world.obstacles:
        parts.append("obstacles: " + "; ".join(at(b) for b in world.obstacles))
    return "; ".join(parts)


# ------------------------------------------------------------------------ 10.2 goal_problems

_OWN_PLACE = (
    "the block collides with itself: its current place was counted as an obstacle; when it is "
    "put at the goal it has left that place"
)
_CONTACT = (
    "touching counted as overlapping: a block resting on another, or standing against its "
    "side, shares a face with it; only an overlap deeper than 0.1 mm counts"
)
_HEIGHTS = (
    "the footprints compared without the heights: a block standing on another has the same "
    "footprint but not the same volume; boxes overlap only where their height ranges do too"
)
_NEAREST = (
    "the support taken from the nearest block rather than the one under the centre: a block "
    "beside the goal holds nothing up; only the top faces that contain (x, y) support it"
)
_ONLY_TABLE = (
    "only the table as a support: a block can stand on another block whose top face contains (x, y)"
)
_EXACT = (
    "exact contact required for support: the bottom may be within 5 mm of the top (and is "
    "then put exactly on it)"
)
_NOT_SNAPPED = (
    "the block not put onto its support before the overlap test: a bottom 3 mm below a top "
    "is within the 5 mm and rests on it, so it overlaps nothing"
)
_REACH_CENTRE = (
    "reach tested at the block's centre (or bottom) instead of its grasp: the tool holds the "
    "centre of the top face, z + height"
)
_ONE_YAW = (
    "reach tested with one tool yaw only: any yaw the footprint allows (0, ±π/2, π for a "
    "square, 0 and π otherwise) will do"
)
_BASE_IGNORED = (
    "the robot's base ignored: the goal is in the table frame and the arm stands at "
    "(−0.15, 0.15, 0.01) m in it (seed 004's first step); ik_analytic(world['robot'], T) "
    "takes T in that frame"
)
_TOOL_IGNORED = (
    "the gripper ignored: the arm must put the gripper's tip, not its flange, on the block "
    "(ik_analytic with world['robot'], whose tool is the gripper)"
)
_TABLE_FULL = (
    "the table's full size used as a half size: its top face reaches size/2 from its centre "
    "along each of its axes"
)
_FOOTPRINT = (
    "the whole footprint required on the table: the rule is about the centre (x, y); a block "
    "may overhang the table's edge"
)
_TURN_IGNORED = (
    "the other boxes' yaw ignored: a turned block covers another footprint; compare the "
    "footprints along both boxes' axes (or use urkin.planning.box_separation)"
)
_ORDER = 'the rules out of order: list them as "table", "reach", "support", "overlap"'


def _over(box: dict, x: float, y: float, scale: float = 1.0, turned: bool = True) -> bool:
    """Whether (x, y) lies over the top face of ``box`` (half sizes times ``scale``)."""
    R = np.asarray(box["pose"])[:2, :2] if turned else np.eye(2)
    local = R.T @ (np.array([x, y]) - np.asarray(box["pose"])[:2, 3])
    return bool(np.all(np.abs(local) <= scale * np.asarray(box["size"])[:2] / 2 + 1e-12))


def _top(box: dict) -> float:
    return float(np.asarray(box["pose"])[2, 3] + np.asarray(box["size"])[2] / 2)


def _separation(a: dict, b: dict, *, heights=True, turned=True) -> float:
    """The separating-axis gap of two upright boxes (m; negative: overlap depth)."""
    pa, pb = np.asarray(a["pose"]), np.asarray(b["pose"])
    ha, hb = np.asarray(a["size"]) / 2, np.asarray(b["size"]) / 2
    Ra = pa[:2, :2] if turned else np.eye(2)
    Rb = pb[:2, :2] if turned else np.eye(2)
    d = pb[:2, 3] - pa[:2, 3]
    gaps = []
    for axis in (*Ra.T, *Rb.T):
        reach = np.abs(axis @ Ra) @ ha[:2] + np.abs(axis @ Rb) @ hb[:2]
        gaps.append(abs(axis @ d) - reach)
    if heights:
        gaps.append(abs(pb[2, 3] - pa[2, 3]) - ha[2] - hb[2])
    return float(max(gaps))


def _yaws(size) -> tuple[float, ...]:
    if abs(float(size[0]) - float(size[1])) <= 1e-9:
        return (0.0, math.pi / 2, math.pi, -math.pi / 2)
    return (0.0, math.pi)


def _reachable(robot, x, y, z_grasp, yaws) -> bool:
    T = np.stack([make_transform(rot_z(yaw) @ _DOWN, [x, y, z_grasp]) for yaw in yaws])
    found = ik_analytic(robot, T).reshape(-1, 6)
    return bool(np.any(~np.isnan(found[:, 0])))


def _problems(
    data: dict,
    name: str,
    x: float,
    y: float,
    z: float,
    *,
    own=False,
    touch=TOUCH,
    heights=True,
    turned=True,
    nearest=False,
    blocks_support=True,
    gap=SUPPORT_GAP,
    snap=True,
    reach_at="top",
    yaws="all",
    robot="world",
    table_scale=1.0,
    footprint=False,
    order=RULES,
) -> list[str]:
    """The rules a goal breaks, by the check's own geometry (or a named mistake's)."""
    table, mine = data["table"], data["blocks"][name]
    size = np.asarray(mine["size"], dtype=float)
    others = {n: b for n, b in data["blocks"].items() if n != name}
    broken = set()
    # 1. the table
    if footprint:
        half = size[:2] / 2
        corners = [(x + sx * half[0], y + sy * half[1]) for sx in (-1, 1) for sy in (-1, 1)]
        on_table = all(_over(table, cx, cy, table_scale) for cx, cy in corners)
    else:
        on_table = _over(table, x, y, table_scale)
    if not on_table:
        broken.add("table")
    # 3. support (before reach: the overlap test needs where it rests)
    tops = [_top(table)] if on_table else []
    if nearest and others:
        closest = min(
            others.values(),
            key=lambda b: math.dist(np.asarray(b["pose"])[:2, 3], (x, y)),
        )
        tops.append(_top(closest))
    elif blocks_support:
        tops += [_top(b) for b in others.values() if _over(b, x, y, turned=turned)]
    bottom = z
    if tops:
        k = int(np.argmin([abs(z - t) for t in tops]))
        if abs(z - tops[k]) <= gap:
            bottom = tops[k] if snap else z
        else:
            broken.add("support")
    # 2. reach
    arm = data["robot"]
    if robot == "no base":
        arm = arm.with_base(np.eye(4))
    elif robot == "no tool":
        arm = arm.with_tool(np.eye(4))
    z_grasp = z + {"top": size[2], "centre": size[2] / 2, "bottom": 0.0}[reach_at]
    if not _reachable(arm, x, y, z_grasp, _yaws(size) if yaws == "all" else (0.0,)):
        broken.add("reach")
    # 4. overlap
    placed = {"size": size, "pose": make_transform(p=[x, y, bottom + size[2] / 2])}
    against = [table, *data["obstacles"].values(), *others.values()]
    if own:
        against.append(mine)
    if any(_separation(placed, b, heights=heights, turned=turned) < -touch for b in against):
        broken.add("overlap")
    return [rule for rule in order if rule in broken]


_GOAL_MISTAKES: dict[str, dict] = {
    _OWN_PLACE: {"own": True},
    _CONTACT: {"touch": -1e-6},
    _HEIGHTS: {"heights": False},
    _NEAREST: {"nearest": True},
    _ONLY_TABLE: {"blocks_support": False},
    _EXACT: {"gap": 1e-9},
    _NOT_SNAPPED: {"snap": False},
    _REACH_CENTRE: {"reach_at": "centre"},
    _REACH_CENTRE + " ": {"reach_at": "bottom"},
    _ONE_YAW: {"yaws": "one"},
    _BASE_IGNORED: {"robot": "no base"},
    _TOOL_IGNORED: {"robot": "no tool"},
    _TABLE_FULL: {"table_scale": 2.0},
    _FOOTPRINT: {"footprint": True},
    _TURN_IGNORED: {"turned": False},
    _ORDER: {"order": tuple(sorted(RULES))},
    _ORDER + " ": {"order": tuple(reversed(RULES))},
}


def _call_goal(sub, data, name, x, y, z, inputs) -> list[str]:
    value = sub.goal_problems(data, name, x, y, z)
    call = "goal_problems(world, block, x, y, z)"
    if value is None:
        raise Mismatch(f"{call} returned None: is a `return` statement missing?", inputs=inputs)
    if isinstance(value, (str, bytes, dict)) or not isinstance(value, (list, tuple)):
        raise Mismatch(
            f"{call} must return a list of rule names, like ['table', 'reach']; got "
            f"{type(value).__name__}",
            inputs=inputs,
        )
    got = list(value)
    unknown = [v for v in got if not isinstance(v, str) or v not in RULES]
    if unknown:
        raise Mismatch(
            f"{call} returned {unknown[0]!r:.40}, which is not one of the rule names "
            f"{', '.join(repr(r) for r in RULES)}",
            inputs=inputs,
            got=str(got),
        )
    return got


def _goal_inputs(world: World, name: str, x: float, y: float, z: float) -> dict:
    return {"block": name, "x": x, "y": y, "z": z, "world": _describe(world)}


def _judge_goals(sub, cases, what):
    """Each case ``(world, name, x, y, z, why)``: the rules of each, then the mistake whose
    answers match all of them."""
    answers, rights = [], []
    for world, name, x, y, z, _ in cases:
        data = world_data(world)
        answers.append(_call_goal(sub, data, name, x, y, z, _goal_inputs(world, name, x, y, z)))
        rights.append(_problems(data, name, x, y, z))
    if answers == rights:
        return
    k = next(i for i, (a, b) in enumerate(zip(answers, rights)) if a != b)
    world, name, x, y, z, why = cases[k]
    mistake = None
    for label, how in _GOAL_MISTAKES.items():
        predicted = [_problems(world_data(c[0]), *c[1:5], **how) for c in cases]
        if predicted != rights and predicted == answers:
            mistake = label.strip()
            break
    if mistake is None and sorted(answers[k]) == sorted(rights[k]):
        mistake = _ORDER
    if mistake is None:  # the one goal, then
        for label, how in _GOAL_MISTAKES.items():
            predicted = _problems(world_data(world), name, x, y, z, **how)
            if predicted != rights[k] and predicted == answers[k]:
                mistake = label.strip()
                break
    raise Mismatch(
        f"{what}. Goal {k + 1} of {len(cases)}: {why}, so goal_problems must return {rights[k]}",
        inputs=_goal_inputs(world, name, x, y, z),
        expected=str(rights[k]),
        got=str(answers[k]),
        mistake=mistake,
    )


def _base_robot(rng):
    """The lab's UR3 and gripper, its base moved by up to 3 cm from the lab's."""
    base = np.array(LAB_BASE_IN_WORLD)
    base[:2] += rng.uniform(-0.03, 0.03, 2)
    return make_robot("ur3").with_base(make_transform(p=base)).with_tool(lab_robot().tool)


def _polar(base, distance, angle):
    return base[:2] + distance * np.array([math.cos(angle), math.sin(angle)])


def _goal_world(rng, moving=(0.05, 0.05, 0.05), others=2, post=True, turned=True) -> World:
    """A world for goals: the lab's table, a random base, the moving block M, ``others``
    blocks and a post, all apart, within reach."""
    arm = _base_robot(rng)
    base = arm.base[:3, 3]
    while True:
        spots = []
        for _ in range(1 + others + int(post)):
            for _ in range(200):
                p = _polar(base, rng.uniform(0.25, 0.42), rng.uniform(-1.3, 1.5))
                if all(math.dist(p, s) > 0.13 for s in spots) and _over(
                    {"size": TABLE.size, "pose": TABLE.pose}, *p, scale=0.85
                ):
                    spots.append(p)
                    break
        if len(spots) == 1 + others + int(post):
            break
    found = [Block.standing("M", moving, *spots[0], yaw=float(rng.uniform(-math.pi, math.pi)))]
    for k in range(others):
        w = rng.uniform(0.04, 0.07)
        size = [
            w,
            w if rng.random() < 0.5 else w + rng.uniform(0.01, 0.03),
            rng.uniform(0.03, 0.08),
        ]
        yaw = float(rng.uniform(0.3, 1.2) * rng.choice([-1, 1])) if turned else 0.0
        found.append(Block.standing("ABC"[k], size, *spots[1 + k], yaw=yaw))
    obstacles = [Block.standing("post", [0.04, 0.04, 0.2], *spots[-1])] if post else []
    model = sphere_model(arm).with_tool_spheres(
        GRIPPER_SPHERES[:, :3], GRIPPER_SPHERES[:, 3], name="gripper"
    )
    return World(arm, model, TABLE, tuple(found), tuple(obstacles))


def _stable(world: World, name: str, x: float, y: float, z: float) -> bool:
    """Whether the table's and the reach's verdicts are the same a few millimetres around the
    goal (a centre near the table's edge, a grasp near the reach's boundary): a goal the check
    may use.  (Support and overlap cases are built with clear margins or exact contact.)"""
    data = world_data(world)
    size = world.block(name).size

    def verdict(dx, dy, dz):
        px, py = x + dx, y + dy
        return (
            _over(data["table"], px, py),
            _reachable(world.robot, px, py, z + dz + size[2], _yaws(size)),
        )

    right = verdict(0.0, 0.0, 0.0)
    return all(
        verdict(*d) == right
        for d in (
            (0.004, 0, 0),
            (-0.004, 0, 0),
            (0, 0.004, 0),
            (0, -0.004, 0),
            (0, 0, 0.006),
            (0, 0, -0.006),
        )
    )


def _free_spot(rng, world, name, *, distance=(0.25, 0.4), clear=0.1, tries=400):
    """(x, y) on the table within reach, at least ``clear`` from every other box."""
    base = world.robot.base[:3, 3]
    for _ in range(tries):
        x, y = _polar(base, rng.uniform(*distance), rng.uniform(-1.3, 1.5))
        if not _over({"size": TABLE.size, "pose": TABLE.pose}, x, y, scale=0.9):
            continue
        if _apart(world, x, y, clear=clear):
            data = world_data(world)
            if _problems(data, name, x, y, 0.0) == [] and _stable(world, name, x, y, 0.0):
                return float(x), float(y)
    raise RuntimeError("no free spot found")


def _inside(world: World, x: float, y: float, margin: float = 0.045) -> bool:
    """Whether (x, y) is at least ``margin`` inside the table's edges (a block there does not
    overhang)."""
    local = np.abs(world.table.pose[:2, :2].T @ (np.array([x, y]) - world.table.pose[:2, 3]))
    return bool(np.all(local <= world.table.size[:2] / 2 - margin))


def _find(rng, draw: Callable, accept: Callable, what: str, tries: int = 500):
    """The first of ``draw(rng)``'s values that ``accept`` takes."""
    for _ in range(tries):
        value = draw(rng)
        if accept(*value):
            return value
    raise RuntimeError(f"the check could not draw {what}")


def _apart(
    world: World,
    x: float,
    y: float,
    skip: Sequence[str] = (),
    clear: float = 0.1,
    inside: bool = True,
) -> bool:
    """Whether (x, y) is well inside the table (with ``inside``) and at least ``clear`` from
    every box but the table and ``skip`` (M's current place included)."""
    return (_inside(world, x, y) or not inside) and all(
        math.dist((x, y), b.centre[:2]) > clear for b in world.boxes(("table", *skip))
    )


def _goals_table(sub, rng):
    world = _goal_world(rng)
    data = world_data(world)
    low, high = world.table.footprint().min(axis=0), world.table.footprint().max(axis=0)
    cases = [(world, "M", *_free_spot(rng, world, "M"), 0.0, "free, on the table, within reach")]

    def at_edge(depth_range):
        def draw(rng):
            side, along = int(rng.integers(4)), rng.uniform(0.15, 0.85)
            depth = rng.uniform(*depth_range)
            if side < 2:
                x = high[0] + depth if side == 0 else low[0] - depth
                y = low[1] + along * (high[1] - low[1])
            else:
                y = high[1] + depth if side == 2 else low[1] - depth
                x = low[0] + along * (high[0] - low[0])
            return float(x), float(y), depth

        return draw

    x, y, depth = _find(
        rng,
        at_edge((0.02, 0.08)),
        lambda x, y, d: _stable(world, "M", x, y, 0.0) and _apart(world, x, y, inside=False),
        "a goal off the table's edge",
    )
    cases.append((world, "M", x, y, 0.0, f"(x, y) is {100 * depth:.1f} cm beyond the table's edge"))
    x, y, depth = _find(
        rng,
        at_edge((-0.02, -0.005)),
        lambda x, y, d: (
            _stable(world, "M", x, y, 0.0)
            and _apart(world, x, y, inside=False)
            and "reach" not in _problems(data, "M", x, y, 0.0)
        ),
        "a goal overhanging the table's edge, within reach",
    )
    cases.append(
        (
            world,
            "M",
            x,
            y,
            0.0,
            f"(x, y) is {-100 * depth:.1f} cm inside the table's edge: the block overhangs it",
        )
    )
    cases.append((world, "M", 2.0, -1.5, 0.0, "(x, y) = (2, −1.5) m, far off the table"))
    _judge_goals(sub, cases, "the table: only the centre (x, y) must be over its top face")


def _goals_reach(sub, rng):
    world = _goal_world(rng, moving=(0.05, 0.05, float(rng.uniform(0.16, 0.2))), others=1)
    base = world.robot.base[:3, 3]
    data = world_data(world)
    size = world.block("M").size
    cases = []
    for distance, angles, expected, why in (
        ((0.22, 0.35), (2.0, 2.6), [], "behind the robot's base, within reach"),
        ((0.62, 0.75), (-1.0, 1.0), ["reach"], "the table's far side, beyond the arm's reach"),
        ((0.0, 0.05), (-math.pi, math.pi), ["reach"], "next to the base's axis"),
    ):

        def draw(rng, distance=distance, angles=angles):
            sign = rng.choice([-1.0, 1.0]) if angles[0] > 0 else 1.0
            return tuple(
                float(v) for v in _polar(base, rng.uniform(*distance), sign * rng.uniform(*angles))
            )

        x, y = _find(
            rng,
            draw,
            lambda x, y, expected=expected: (
                _problems(data, "M", x, y, 0.0) == expected
                and _stable(world, "M", x, y, 0.0)
                and _apart(world, x, y)
            ),
            f"a goal {why}",
        )
        cases.append((world, "M", x, y, 0.0, why))

    # the tall block's top out of reach, its centre within: along a ray from the base
    def along_ray(rng):
        angle = rng.uniform(-1.0, 1.2)
        r = np.arange(0.3, 0.62, 0.002)
        points = [_polar(base, d, angle) for d in r]
        top = np.array([_reachable(world.robot, *p, size[2], _yaws(size)) for p in points])
        mid = np.array([_reachable(world.robot, *p, size[2] / 2, _yaws(size)) for p in points])
        band = np.flatnonzero(~top & mid)
        if len(band) < 8 or np.any(np.diff(band) != 1):
            return 0.0, 0.0, False
        x, y = points[band[len(band) // 2]]
        return float(x), float(y), True

    x, y, _ = _find(
        rng,
        along_ray,
        lambda x, y, found: (
            found and _problems(data, "M", x, y, 0.0) == ["reach"] and _apart(world, x, y)
        ),
        "a goal where a tall block's top is out of reach and its centre is not",
        tries=60,
    )
    cases.append(
        (
            world,
            "M",
            x,
            y,
            0.0,
            f"a block {100 * size[2]:.0f} cm tall: the grasp on its top is out of reach, a "
            "grasp at its centre would not be",
        )
    )
    _judge_goals(sub, cases, "reach: the tool at the centre of the block's top face, pointing down")


def _goals_support(sub, rng):
    world = _goal_world(rng, others=2)
    a = world.block("A")
    data = world_data(world)
    cases = []

    def over_a(rng):
        p = a.centre[:2] + a.pose[:2, :2] @ (rng.uniform(-0.3, 0.3, 2) * a.size[:2])
        return float(p[0]), float(p[1])

    x, y = _find(rng, over_a, lambda x, y: _stable(world, "M", x, y, a.top), "a goal on block A")
    for dz, why in (
        (0.0, "on block A, exactly on its top"),
        (rng.uniform(0.002, 0.004), "on block A, 2 to 4 mm above its top (it rests on it)"),
        (-rng.uniform(0.002, 0.004), "on block A, 2 to 4 mm below its top (it rests on it)"),
    ):
        cases.append((world, "M", x, y, a.top + float(dz), why))
    x, y = _free_spot(rng, world, "M")
    cases.append((world, "M", x, y, float(rng.uniform(0.03, 0.06)), "3 to 6 cm above the table"))

    def beside_a(rng):
        angle = rng.uniform(-math.pi, math.pi)
        p = a.centre[:2] + rng.uniform(0.06, 0.09) * np.array([math.cos(angle), math.sin(angle)])
        return float(p[0]), float(p[1])

    x, y = _find(
        rng,
        beside_a,
        lambda x, y: (
            not _over(data["blocks"]["A"], x, y)
            and _stable(world, "M", x, y, a.top)
            and _apart(world, x, y, skip=("A",))
        ),
        "a goal beside block A",
    )
    cases.append((world, "M", x, y, a.top, "beside block A, at the height of its top"))
    _judge_goals(
        sub,
        cases,
        "support: a top under (x, y) within 5 mm of the block's bottom (the table's, or "
        "another block's)",
    )


def _goals_overlap(sub, rng):
    world = _goal_world(rng, others=2)
    a = world.block("A")  # made square and straight: M can stand against its side exactly
    a = Block.standing("A", [0.06, 0.06, a.size[2]], *a.centre[:2])
    b = world.block("B")  # turned by 30° to 57°, where its yaw matters most
    turn = float(rng.uniform(0.55, 1.0) * rng.choice([-1.0, 1.0]))
    b = Block.standing("B", b.size, *b.centre[:2], yaw=turn)
    world = world.with_block(a).with_block(b)
    post, m = world.obstacles[0], world.block("M")
    data = world_data(world)
    cases = []

    def against_a(rng):
        p = a.centre[:2].copy()
        axis = int(rng.integers(2))
        p[axis] += rng.choice([-1.0, 1.0]) * (a.size[axis] / 2 + m.size[axis] / 2)
        p[1 - axis] += rng.uniform(-0.01, 0.01)
        return float(p[0]), float(p[1])

    x, y = _find(
        rng,
        against_a,
        lambda x, y: _stable(world, "M", x, y, 0.0) and _apart(world, x, y, skip=("A",)),
        "a goal against block A's side",
    )
    cases.append((world, "M", x, y, 0.0, "against block A's side, touching it"))
    if _stable(world, "M", *a.centre[:2], a.top):
        cases.append((world, "M", *(float(v) for v in a.centre[:2]), a.top, "stacked on block A"))

    def into_post(rng):
        p = post.centre[:2] + rng.uniform(0.02, 0.035) * rng.choice([-1.0, 1.0], 2)
        return float(p[0]), float(p[1])

    x, y = _find(
        rng,
        into_post,
        lambda x, y: _stable(world, "M", x, y, 0.0) and _apart(world, x, y, skip=("post",)),
        "a goal against the post",
    )
    cases.append((world, "M", x, y, 0.0, "against the post, 10 to 25 mm into it"))

    def beside_b(rng):
        angle = rng.uniform(-math.pi, math.pi)
        p = b.centre[:2] + rng.uniform(0.03, 0.09) * np.array([math.cos(angle), math.sin(angle)])
        return float(p[0]), float(p[1])

    def turn_matters(x, y):
        placed = {"size": m.size, "pose": make_transform(p=[x, y, m.size[2] / 2])}
        real = _separation(placed, data["blocks"]["B"])
        straight = _separation(placed, data["blocks"]["B"], turned=False)
        return (
            (real < -0.003) != (straight < -0.003)
            and min(abs(real), abs(straight)) > 0.003
            and not _over(data["blocks"]["B"], x, y)
            and _stable(world, "M", x, y, 0.0)
            and _apart(world, x, y, skip=("B",))
        )

    x, y = _find(rng, beside_b, turn_matters, "a goal where block B's yaw matters", tries=3000)
    cases.append((world, "M", x, y, 0.0, f"beside block B, which is turned by {b.yaw:.2f} rad"))

    def near_itself(rng):
        p = m.centre[:2] + rng.uniform(0.015, 0.03) * rng.choice([-1.0, 1.0], 2)
        return float(p[0]), float(p[1])

    x, y = _find(
        rng, near_itself, lambda x, y: _stable(world, "M", x, y, 0.0), "a goal next to M's place"
    )
    cases.append((world, "M", x, y, 0.0, "1.5 to 3 cm from where M stands now"))
    x, y = _free_spot(rng, world, "M")
    depth = float(rng.uniform(0.02, 0.04))
    if _stable(world, "M", x, y, -depth):
        cases.append((world, "M", x, y, -depth, "2 to 4 cm into the table's top"))
    _judge_goals(sub, cases, "overlap: deeper than 0.1 mm into the table, an obstacle or a block")


# ---------------------------------------------------------------------------- 10.3 stack_two

_EDGE = (
    "a move of only its two ends, whose straight edge takes the arm, or the block it holds, "
    "through an obstacle: plan the motion (planning.rrt_connect; while holding a block, with "
    "world.carrying(size) against the scene without the block) and send all its waypoints"
)
_NOT_ATTACHED = (
    "the carried block not attached while planning: plan the transfer with "
    "world.carrying(size) (the arm holding the block) against the scene without the block"
)
_TOO_LOW = (
    "the block lowered into what it should stand on: the tool stops at the goal's top face, "
    "the height of the support plus the block's own height"
)
_IN_AIR = (
    "released in the air: the block must rest on its support (within 1 mm) when the gripper "
    "lets go; descend all the way first"
)
_OFF_CENTRE = (
    "gripped away from the centre of the top face: the suction cup must be at the centre of "
    "the block's top face, pointing straight down (within 1 mm), when it grips"
)
_STILL_HOLDING = "the task ends while holding a block: release it, then retreat"
_JUMP = (
    "a move that does not start where the arm is: each ('move', Q) starts with the arm's "
    "current configuration (Q[0]), or the arm would jump"
)
_BESIDE = (
    "B put beside A, not on it: B's goal is (x, y) on A's top face, its bottom at the height "
    "of A's top"
)
_NOT_AT_GOAL = "A not put at the goal: its bottom's centre must end at (x, y) on the table"
_LIMITS = "joint angles beyond ±2π, the UR3's limits: keep every waypoint within them"


def _steps_from(value, inputs) -> list[tuple[str, Any]]:
    call = "stack_two(world, x, y, q_start)"
    if not isinstance(value, (list, tuple)) or not value:
        raise Mismatch(
            f"{call} must return a list of steps like ('move', Q), ('grip', 'A'), "
            f"('release', 'A'); got {type(value).__name__}",
            inputs=inputs,
        )
    steps = []
    for k, step in enumerate(value):
        if not (isinstance(step, (list, tuple)) and len(step) == 2 and isinstance(step[0], str)):
            raise Mismatch(
                f"step {k} of {call} is not a pair (kind, value): {str(step)[:80]}", inputs=inputs
            )
        kind, item = step
        if kind == "move":
            try:
                item = np.asarray(item, dtype=float)
            except (TypeError, ValueError):
                raise Mismatch(
                    f"step {k} ('move'): its waypoints must be numbers, shape (m, 6)",
                    inputs=inputs,
                ) from None
        steps.append((kind, item))
    return steps


def _stack_mistake(steps, reason: str) -> str | None:
    match = re.match(r"step (\d+) \((\w+)\)", reason)
    index = int(match.group(1)) if match else -1
    step = steps[index] if 0 <= index < len(steps) else None
    if "the task ends holding" in reason:
        return _STILL_HOLDING
    if "starts" in reason and "from where the arm is" in reason:
        return _JUMP
    if "outside the joint limits" in reason:
        return _LIMITS
    if "would be released" in reason or "nothing under" in reason:
        return _IN_AIR
    if "from the centre of" in reason and "top face" in reason:
        return _OFF_CENTRE
    if step is None or step[0] != "move":
        return None
    held = None
    for kind, item in steps[:index]:
        held = item if kind == "grip" else None if kind == "release" else held
    if len(step[1]) == 2:
        return _EDGE
    if held is not None and "carried block" in reason:
        following = steps[index + 1][0] if index + 1 < len(steps) else None
        return _TOO_LOW if following == "release" else _NOT_ATTACHED
    return None


def _goal_for(rng, world: World, draw: Callable, plans: int = 3) -> tuple[float, float] | None:
    """A goal (x, y) from ``draw(rng)`` for A on the table and B on A that ``validate_goal``
    accepts and urkin's planner can do (None when ``plans`` goals in a row could not be
    planned)."""
    for _ in range(300):
        x, y = (float(v) for v in draw(rng))
        a = tabletop.validate_goal(world, ("A", x, y), q_start=LAB_HOME)
        if not a.ok:
            continue
        b = tabletop.validate_goal(world.with_block(a.placed), ("B", x, y, a.placed.top))
        if not b.ok:
            continue
        try:
            task = tasks.pick_and_place(
                world,
                [("A", x, y), ("B", x, y, a.placed.top)],
                LAB_HOME,
                seed=int(rng.integers(99)),
            )
        except ValueError:  # a planner's goal in collision: a goal not to use
            task = None
        if task is not None and task.success:
            return x, y
        plans -= 1
        if plans == 0:
            return None
    return None


def _or_away(point):
    """The point, or one far off the table (which every goal check refuses)."""
    return (9.0, 9.0) if point is None else point


def _box_goal(xs, ys):
    return lambda rng: (rng.uniform(*xs), rng.uniform(*ys))


def _lab_stack(rng):
    while True:
        world = lab_world()
        goal = _goal_for(rng, world, _box_goal((0.15, 0.35), (-0.22, 0.02)))
        if goal is not None:
            return world, goal


def _wall_stack(rng):
    while True:
        found = [
            Block.standing(
                name,
                [0.05, 0.05, 0.05],
                rng.uniform(*xs),
                rng.uniform(0.30, 0.40),
                yaw=float(rng.uniform(-0.5, 0.5)),
            )
            for name, xs in (("A", (0.05, 0.15)), ("B", (0.22, 0.30)))
        ]
        wall = Block.standing("wall", [0.30, 0.02, 0.10], 0.20, 0.20)
        world = lab_world(blocks=found, obstacles=[wall])
        goal = _goal_for(rng, world, _box_goal((0.12, 0.32), (-0.15, 0.08)))
        if goal is not None:
            return world, goal


def _other_stack(rng):
    base = np.array(LAB_BASE_IN_WORLD)

    def spot(rng, taken, distance=(0.25, 0.40), angles=(-1.0, 1.2)):
        for _ in range(500):
            p = _polar(base, rng.uniform(*distance), rng.uniform(*angles))
            if all(math.dist(p, s) > 0.12 for s in taken):
                return p
        return None

    while True:
        spots = []
        for _ in range(3):
            found = spot(rng, spots)
            if found is None:
                break
            spots.append(found)
        if len(spots) < 3:
            continue
        blocks = []
        for name, where in zip("AB", spots):
            w = rng.uniform(0.04, 0.06)
            size = [w, w if name == "A" else w + rng.uniform(0.01, 0.02), rng.uniform(0.03, 0.06)]
            yaw = float(rng.uniform(-math.pi, math.pi))
            blocks.append(Block.standing(name, size, *where, yaw=yaw))
        post = Block.standing("post", [0.04, 0.04, rng.uniform(0.1, 0.25)], *spots[2])
        world = lab_world(blocks=blocks, obstacles=[post])
        goal = _goal_for(rng, world, lambda rng, taken=spots: _or_away(spot(rng, taken)))
        if goal is not None:
            return world, goal


def _judge_stack(sub, rng, make: Callable, what: str):
    world, (x, y) = make(rng)
    inputs = {"x": x, "y": y, "q_start": LAB_HOME, "world": _describe(world)}
    value = sub.stack_two(world_data(world), x, y, LAB_HOME.copy())
    steps = _steps_from(value, inputs)
    ok, reason, final = tasks.replay(world, LAB_HOME, steps)
    if not ok:
        raise Mismatch(
            f"{what}: urkin.planning.replay refuses the task: {reason}",
            inputs=inputs,
            mistake=_stack_mistake(steps, reason),
        )
    a, b = final.block("A"), final.block("B")
    top = world.table.top
    miss = math.hypot(a.centre[0] - x, a.centre[1] - y)
    if miss > 1e-3 or abs(a.bottom - top) > 1e-3:
        raise Mismatch(
            f"{what}: the task is safe, but A ends at ({a.centre[0]:.3f}, {a.centre[1]:.3f}), "
            f"bottom {a.bottom:.3f} m: {1000 * miss:.1f} mm from the goal",
            inputs=inputs,
            mistake=_NOT_AT_GOAL,
        )
    off = math.hypot(*(b.centre[:2] - a.centre[:2]))
    if off > 1e-3 or abs(b.bottom - a.top) > 1e-3:
        beside = abs(b.bottom - top) <= 1e-3 and math.dist(b.centre[:2], (x, y)) < 0.2
        raise Mismatch(
            f"{what}: the task is safe, but B ends at ({b.centre[0]:.3f}, {b.centre[1]:.3f}), "
            f"bottom {b.bottom:.3f} m, not on A (its top at {a.top:.3f} m, its centre at "
            f"({a.centre[0]:.3f}, {a.centre[1]:.3f}))",
            inputs=inputs,
            mistake=_BESIDE if beside else None,
        )


def _stack_lab(sub, rng):
    _judge_stack(sub, rng, _lab_stack, "the lab's table (blocks A and B, the post), a fresh goal")


def _stack_wall(sub, rng):
    _judge_stack(
        sub,
        rng,
        _wall_stack,
        "A and B behind a wall 10 cm high, the goal in front of it",
    )


def _stack_other(sub, rng):
    _judge_stack(
        sub,
        rng,
        _other_stack,
        "other blocks (B oblong, both turned), the post elsewhere, a fresh goal",
    )


# -------------------------------------------------------------------------------- 10.4 hanoi

_SWAP_FIRST = (
    "target and spare swapped in the first recursive call: the n − 1 smaller blocks first go "
    "to the spare peg, out of the way (hanoi(n − 1, source, spare, target))"
)
_SWAP_SECOND = (
    "the second recursive call moves the smaller blocks to the wrong peg: from the spare peg "
    "onto the target (hanoi(n − 1, spare, target, source))"
)
_BASE_ONE_EMPTY = (
    "an off-by-one in n: with one block there is one move; the base case is n == 0 (no "
    "moves), or n == 1 with its move"
)
_BASE_ZERO_MOVE = "an off-by-one in n: n == 0 blocks need no move; hanoi(0, …) must return []"
_REVERSED = "each move written (to, from): a move is (from peg, to peg)"


def _hanoi(n, source, target, spare, how="right") -> list[tuple[Any, Any]]:
    if how == "one_empty" and n == 1:
        return []
    if n == 0:
        return [(source, target)] if how == "zero_move" else []
    first = (
        _hanoi(n - 1, source, target, spare, how)
        if how == "swap_first"
        else _hanoi(n - 1, source, spare, target, how)
    )
    second = (
        _hanoi(n - 1, spare, source, target, how)
        if how == "swap_second"
        else _hanoi(n - 1, spare, target, source, how)
    )
    move = (target, source) if how == "reversed" else (source, target)
    return [*first, move, *second]


_HANOI_MISTAKES = {
    _SWAP_FIRST: "swap_first",
    _SWAP_SECOND: "swap_second",
    _BASE_ONE_EMPTY: "one_empty",
    _BASE_ZERO_MOVE: "zero_move",
    _REVERSED: "reversed",
}


def _simulate(n: int, pegs: Sequence, moves: list) -> str:
    """Why the moves are not a solution ("" when they are)."""
    source, target, _ = pegs
    stacks = {p: [] for p in pegs}
    stacks[source] = list(range(n, 0, -1))  # sizes, largest at the bottom
    for k, (a, b) in enumerate(moves, start=1):
        if a not in stacks or b not in stacks:
            return f"move {k} is ({a!r}, {b!r}): the pegs are {list(pegs)!r}"
        if not stacks[a]:
            return f"move {k} ({a!r} → {b!r}) takes from an empty peg"
        if stacks[b] and stacks[b][-1] < stacks[a][-1]:
            return (
                f"move {k} ({a!r} → {b!r}) puts block {stacks[a][-1]} on the smaller block "
                f"{stacks[b][-1]}"
            )
        stacks[b].append(stacks[a].pop())
    if len(stacks[target]) != n:
        where = {p: len(s) for p, s in stacks.items()}
        return f"after the moves the pegs hold {where} blocks; all {n} must be on {target!r}"
    if len(moves) != 2**n - 1:
        return f"{len(moves)} moves: the fewest is 2**n − 1 = {2**n - 1}"
    return ""


def _judge_hanoi(sub, n, pegs, what):
    inputs = {"n": n, "source": pegs[0], "target": pegs[1], "spare": pegs[2]}
    value = sub.hanoi(n, *pegs)
    call = "hanoi(n, source, target, spare)"
    if not isinstance(value, (list, tuple)):
        raise Mismatch(
            f"{call} must return a list of moves (from, to); got {type(value).__name__}",
            inputs=inputs,
        )
    moves = []
    for move in value:
        if not (isinstance(move, (list, tuple)) and len(move) == 2):
            raise Mismatch(
                f"{call}: each move must be a pair (from peg, to peg); got {str(move)[:60]}",
                inputs=inputs,
            )
        moves.append(tuple(move))
    why = _simulate(n, pegs, moves)
    if not why:
        return
    mistake = None
    for name, how in _HANOI_MISTAKES.items():
        wrong = _hanoi(n, *pegs, how=how)
        if [tuple(m) for m in wrong] == moves:
            mistake = name
            break
    shown = ", ".join(f"({a!r}, {b!r})" for a, b in moves[:8]) + (" …" if len(moves) > 8 else "")
    raise Mismatch(
        f"{what}: {why}. The first moves: {shown or 'none'}",
        inputs=inputs,
        mistake=mistake,
    )


def _hanoi_small(sub, rng):
    for n in (1, 2, 3):
        pegs = tuple(int(p) for p in rng.permutation(3))
        _judge_hanoi(sub, n, pegs, f"{n} block{'s' if n > 1 else ''}, pegs {pegs}")


def _hanoi_large(sub, rng):
    for n in (4, int(rng.integers(5, 9))):
        names = ["left", "middle", "right"]
        pegs = tuple(names[i] for i in rng.permutation(3))
        _judge_hanoi(sub, n, pegs, f"{n} blocks, pegs named {pegs}")


LESSON = Lesson(
    number="10",
    title="Pick and place: grasps, goals, stacking, the Tower of Hanoi",
    summary="the capstone on seed 004's table: top-down grasp frames reduced by a block's "
    "symmetry, the lab's IK as one closed-form branch, straight vertical approaches, a "
    "carried block attached, goals validated with reasons and re-prompted (seed 001's future "
    "work), pick and place planned and replayed, two blocks stacked, the Tower of Hanoi",
    exercises=(
        Exercise(
            id="10.1",
            function="grasp_flange_pose",
            title="the flange pose that grasps a block from above, the wrist turned the least",
            checks=(
                Check(
                    "square blocks, the lab's gripper: the top face's centre, tool z down, "
                    "the yaw reduced by 90° nearest the wrist's",
                    2,
                    _grasp_square,
                ),
                Check("oblong blocks: the yaw reduced by 180°", 1, _grasp_oblong),
                Check(
                    "turned and offset tools, yaws across ±π and wound beyond it; lists",
                    1,
                    _grasp_tools,
                ),
            ),
            answer=(blocks.top_down_grasp, blocks.grasp_yaws, blocks.symmetry),
        ),
        Exercise(
            id="10.2",
            function="goal_problems",
            title="which rules a goal for a block breaks: table, reach, support, overlap",
            checks=(
                Check("the table: the centre over its top face", 1, _goals_table),
                Check(
                    "reach: far, next to the base, behind it, a tall block's top",
                    1,
                    _goals_reach,
                ),
                Check(
                    "support: on a block within 5 mm, floating, beside a block", 1, _goals_support
                ),
                Check(
                    "overlap: touching is not overlapping; obstacles, turned blocks, the table",
                    1,
                    _goals_overlap,
                ),
            ),
            answer=(tabletop.validate_goal,),
        ),
        Exercise(
            id="10.3",
            function="stack_two",
            title="a task that stacks A at a goal and B on A, safe in every configuration and edge",
            checks=(
                Check("the lab's table, a fresh goal", 2, _stack_lab),
                Check("behind a wall: the carried block must clear it", 1, _stack_wall),
                Check("other blocks and post, a fresh goal", 1, _stack_other),
            ),
            answer=(tasks.pick_and_place,),
        ),
        Exercise(
            id="10.4",
            function="hanoi",
            title="the Tower of Hanoi's moves: 2ⁿ − 1, never a larger block on a smaller one",
            checks=(
                Check("one to three blocks, pegs numbered", 1, _hanoi_small),
                Check("four to eight blocks, pegs named", 1, _hanoi_large),
            ),
        ),
    ),
)
