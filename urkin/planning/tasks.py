"""Pick and place on a tabletop: the task runner and the replay that checks any task.

A task is a list of **steps**: ``("move", Q)`` — joint-space waypoints ``Q`` (m, 6) joined by
straight edges —, ``("grip", name)`` and ``("release", name)``.  :func:`replay` checks a list
of steps from scratch: every configuration and edge at ``resolution`` (no sphere centre and
no corner of a carried block moves more than that between samples), the arm and gripper by
their spheres, a carried block exactly (boxes, :func:`~urkin.planning.box_separation`) against
the other boxes and by its sphere cover against the arm; a grip needs the tool at the centre
of the block's top face pointing down, with nothing on the block; a release needs the block
upright on a support.

:func:`pick_and_place` builds such a task for a list of :class:`~urkin.planning.Move` goals.
Each move is: **to pre-grasp** (RRT-Connect), **approach** (straight down, 1 mm samples),
**grasp**, **lift** (straight up), **transfer** (RRT-Connect with the block attached),
**descend**, **release**, **retreat**.  The grasp is the closed-form configuration nearest
the arm's current one (over the yaws of the block's symmetry) whose approach and lift are
free; the place, any of the three nearest the lifted configuration whose descent and
retreat are free (the planner goes to whichever it reaches).
"""

from __future__ import annotations

import functools
import math
import time
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from urkin.analytic_ik import ik_analytic
from urkin.kinematics import _joints, _one_configuration, fk
from urkin.planning.blocks import (
    Block,
    _grasp_at,
    _yaw_near,
    box_separation,
    grasp_yaws,
)
from urkin.planning.checks import (
    RESOLUTION,
    _intervals,
    _offence,
    clearance,
    explain,
    is_free,
)
from urkin.planning.rrt import Plan, _check_options, rrt_connect
from urkin.planning.scene import Scene
from urkin.planning.spheres import SphereModel
from urkin.planning.tabletop import TOUCH, Move, World, _inside, _support_of, validate_goal
from urkin.planning.timing import time_parametrize
from urkin.tracking import track
from urkin.trajectory import line, minimum_time, pose_path
from urkin.transforms import inv_transform, rot_z, wrap_angles

__all__ = ["Phase", "Task", "pick_and_place", "replay"]

#: Height of the pre-grasp and pre-place poses above the grasp and the place (m).
HOVER = 0.08
#: Tool speed (m/s) and acceleration (m/s²) of the straight vertical moves.
TOOL_SPEED, TOOL_ACCELERATION = 0.1, 0.5
#: Time the suction takes to grip or release (s).
GRIP_TIME = 0.3
#: How close (m and rad) the tool must be to a block's grasp, and a released block to resting.
GRIP_TOLERANCE = 1e-3

PHASES = ("to pre-grasp", "approach", "grasp", "lift", "transfer", "descend", "release", "retreat")


@dataclass(frozen=True)
class Phase:
    """One phase of a pick and place.

    Attributes
    ----------
    name : str
        One of ``"to pre-grasp"``, ``"approach"``, ``"grasp"``, ``"lift"``, ``"transfer"``,
        ``"descend"``, ``"release"``, ``"retreat"``.
    block : str
        The block being moved.
    success : bool
    reason : str
        Why not, when it failed.
    q : ndarray, shape (m, 6)
        Its waypoints (straight edges between them); one row for grasp and release.
    seconds : float
        Computing time.
    duration : float
        Motion time (s).
    clearance : float
        The smallest distance of the arm and gripper spheres to collision over the checked
        samples (m); ``nan`` for grasp and release.
    """

    name: str
    block: str
    success: bool
    reason: str
    q: np.ndarray
    seconds: float
    duration: float
    clearance: float


@dataclass(frozen=True)
class Task:
    """The result of :func:`pick_and_place`.

    Attributes
    ----------
    success : bool
    reason : str
    phases : tuple of Phase
    start, world : World
        Before and after (the blocks where they were put).
    goals : tuple of Block
        Each move's block at its validated goal pose.
    t : ndarray, shape (M,)
        Times of the timed joint trajectory (s).
    q : ndarray, shape (M, 6)
        The joint trajectory: every sample lies on a checked edge.
    block_poses : ndarray, shape (M, B, 4, 4)
        Each block's pose at each sample (``start.names`` order): carried ones move.
    """

    success: bool
    reason: str
    phases: tuple[Phase, ...]
    start: World
    world: World
    goals: tuple[Block, ...]
    t: np.ndarray
    q: np.ndarray
    block_poses: np.ndarray

    def steps(self) -> list[tuple[str, object]]:
        """The task as steps for :func:`replay`."""
        out: list[tuple[str, object]] = []
        for p in self.phases:
            if p.name == "grasp":
                out.append(("grip", p.block))
            elif p.name == "release":
                out.append(("release", p.block))
            elif len(p.q) > 1:
                out.append(("move", p.q))
        return out

    def report(self) -> str:
        """A table: one row per phase (success, compute time, motion time, clearance)."""
        rows = [f"{'block':<6}{'phase':<14}{'ok':<5}{'compute':>9}{'motion':>9}{'clearance':>11}"]
        for p in self.phases:
            gap = "" if math.isnan(p.clearance) else f"{p.clearance * 1e3:8.0f} mm"
            rows.append(
                f"{p.block:<6}{p.name:<14}{'yes' if p.success else 'NO':<5}"
                f"{p.seconds * 1e3:7.0f} ms{p.duration:7.1f} s{gap:>11}"
                + ("" if p.success else f"  {p.reason}")
            )
        return "\n".join(rows)


# --- checking segments -------------------------------------------------------------------


@functools.lru_cache(maxsize=32)
def _corners(robot_model: SphereModel, size: tuple[float, ...]) -> SphereModel:
    """Tiny spheres at a carried block's corners, to bound how far they move (edge counts)."""
    h = np.array(size) / 2
    signs = np.array(np.meshgrid([-1, 1], [-1, 1], [-1, 1], indexing="ij")).reshape(3, -1).T
    corners = signs * h + [0.0, 0.0, h[2]]
    rows = np.column_stack([np.full(8, 7), corners, np.full(8, 1e-6)])
    return SphereModel.from_rows(robot_model.robot, rows, pairs=np.zeros((0, 2), dtype=np.intp))


def _edge_samples(models: Sequence[SphereModel], Q: np.ndarray, resolution: float) -> np.ndarray:
    """Samples of the edges between consecutive waypoints of ``Q``: no sphere of ``models``
    moves more than ``resolution`` between them (ends included)."""
    if len(Q) == 1:
        return Q
    A, B = Q[:-1], Q[1:]
    counts = np.max([_intervals(m, A, B, resolution) for m in models], axis=0)
    edge = np.repeat(np.arange(len(A)), counts)
    start = np.cumsum(counts) - counts
    s = (np.arange(counts.sum()) - np.repeat(start, counts)) / np.repeat(counts, counts)
    return np.vstack([A[edge] + s[:, None] * (B[edge] - A[edge]), Q[-1:]])


@dataclass(frozen=True)
class _Verdict:
    free: bool
    clearance: float
    reason: str


def _check(
    world: World,
    Q: np.ndarray,
    held: str | None,
    T_tool_block: np.ndarray | None,
    resolution: float,
) -> _Verdict:
    """Every configuration and edge of ``Q`` (m, 6), holding ``held`` at ``T_tool_block``."""
    robot = world.robot
    if held is None:
        S = _edge_samples([world.model], Q, resolution)
        scene = world.scene()
        distance = clearance(world.model, scene, S).distance  # free: strictly positive
        gap = float(distance.min())
        if gap <= 0:
            q = S[int(np.argmax(distance <= 0))]
            return _Verdict(False, gap, explain(world.model, scene, q))
        return _Verdict(True, gap, "")
    block = world.block(held)
    size = tuple(float(s) for s in block.size)
    carried = world.carrying(size)
    S = _edge_samples([carried, _corners(world.model, size)], Q, resolution)
    scene = world.scene(without=(held,))
    arm_distance = clearance(world.model, scene, S).distance
    own_distance = clearance(carried, Scene(), S).distance
    arm, own = arm_distance > 0, own_distance > 0
    others = world.boxes((held,))
    poses = fk(robot, S) @ T_tool_block
    sep = box_separation(
        poses[:, None, :3, 3],
        poses[:, None, :3, :3],
        block.size / 2,
        np.array([b.centre for b in others]),
        np.array([b.pose[:3, :3] for b in others]),
        np.array([b.size / 2 for b in others]),
    )
    boxed = np.all(sep >= -TOUCH, axis=1)
    gap = float(min(arm_distance.min(), own_distance.min()))
    bad = ~(arm & own & boxed)
    if not bad.any():
        return _Verdict(True, gap, "")
    k = int(np.argmax(bad))
    if not arm[k]:
        why = explain(world.model, scene, S[k])
    elif not own[k]:
        why = explain(carried, Scene(), S[k])
    else:
        o = int(np.argmin(sep[k]))
        why = f"the carried block {held} overlaps {others[o].name} by {-sep[k, o] * 1e3:.1f} mm"
    return _Verdict(False, gap, why)


# --- replay --------------------------------------------------------------------------------


def _grip_error(world: World, q: np.ndarray, block: Block) -> str:
    """Why the tool at ``q`` cannot grip ``block`` ("" when it can)."""
    T = fk(world.robot, q)
    miss = float(np.linalg.norm(T[:3, 3] - [*block.centre[:2], block.top]))
    tilt = math.atan2(math.hypot(T[0, 2], T[1, 2]), -T[2, 2])
    if miss > GRIP_TOLERANCE or tilt > GRIP_TOLERANCE:
        return (
            f"the tool is {miss * 1e3:.1f} mm from the centre of {block.name}'s top face "
            f"and {math.degrees(tilt):.2f}° from pointing down"
        )
    on = [
        b.name
        for b in world.blocks
        if b.name != block.name and _support_of(world, b, (b.name,)) == block.name
    ]
    if on:
        return f"block {on[0]} stands on {block.name}"
    return ""


def replay(
    world: World,
    q_start: ArrayLike,
    steps: Sequence[tuple[str, object]],
    *,
    resolution: float = RESOLUTION,
) -> tuple[bool, str, World]:
    """Check a task step by step from ``world`` and ``q_start``: ``(ok, reason, final world)``.

    Parameters
    ----------
    world : World
    q_start : array_like, shape (6,)
    steps : sequence
        ``("move", Q)`` with ``Q`` (m, 6) waypoints (the first row where the arm is),
        ``("grip", name)``, ``("release", name)``.
    resolution : float
        Most any sphere centre or carried block corner moves between checked samples (m).

    Returns
    -------
    ok : bool
    reason : str
        The first problem, naming the step ("step 4 (move): forearm sphere 2 penetrates …").
    world : World
        The blocks where the steps left them.
    """
    q = _one_configuration(q_start, "q_start")
    if isinstance(steps, (str, bytes)) or not isinstance(steps, Sequence):
        return False, f"steps must be a list of steps; got {type(steps).__name__}", world
    held: str | None = None
    grip = None
    for k, step in enumerate(steps):
        if not (isinstance(step, tuple) and len(step) == 2):
            return False, f"step {k}: a step is (kind, value); got {step!r:.60}", world
        kind, value = step
        where = f"step {k} ({kind})"
        if kind == "move":
            try:
                Q, _, _ = _joints(value, f"step {k}'s waypoints")
            except (TypeError, ValueError) as error:
                return False, f"{where}: {error}", world
            if Q.ndim != 2 or len(Q) < 1:
                return False, f"{where}: waypoints must have shape (m, 6)", world
            if np.max(np.abs(Q[0] - q)) > 1e-9:
                return (
                    False,
                    (f"{where}: starts {np.max(np.abs(Q[0] - q)):.3g} rad from where the arm is"),
                    world,
                )
            limits = np.array(world.robot.joint_limits)
            if np.any(Q < limits[:, 0]) or np.any(Q > limits[:, 1]):
                return False, f"{where}: outside the joint limits", world
            verdict = _check(world, Q, held, grip, resolution)
            if not verdict.free:
                return False, f"{where}: {verdict.reason}", world
            q = Q[-1].copy()
        elif kind == "grip":
            if held is not None:
                return False, f"{where}: already holding {held}", world
            if value not in world.names:
                return False, f"{where}: no block named {value!r:.20}", world
            why = _grip_error(world, q, world.block(value))
            if why:
                return False, f"{where}: {why}", world
            held = value
            grip = inv_transform(fk(world.robot, q)) @ world.block(value).pose
        elif kind == "release":
            if held is None or value != held:
                return False, f"{where}: not holding {value!r:.20}", world
            pose = fk(world.robot, q) @ grip
            tilt = math.atan2(math.hypot(pose[0, 2], pose[1, 2]), pose[2, 2])
            if tilt > GRIP_TOLERANCE:
                return False, f"{where}: {held} would be put down tilted by {tilt:.3g} rad", world
            upright = pose.copy()
            yaw = math.atan2(pose[1, 0], pose[0, 0])
            upright[:3, :3] = rot_z(yaw)
            block = world.block(held).moved(upright)
            tops = [
                (abs(block.bottom - b.top), b)
                for b in world.boxes((held,))
                if np.all(_inside(block.centre, b) <= 0)
            ]
            gap, below = min(tops, key=lambda x: x[0], default=(math.inf, None))
            if gap > GRIP_TOLERANCE:
                return (
                    False,
                    (
                        f"{where}: {held} would be released {gap * 1e3:.1f} mm from the "
                        "nearest support under its centre"
                        if below is not None
                        else f"{where}: nothing under {held}'s centre"
                    ),
                    world,
                )
            world = world.with_block(
                block.moved(
                    np.vstack([upright[:2], [0, 0, 1, below.top + block.size[2] / 2], upright[3:]])
                )
            )
            held, grip = None, None
        else:
            return False, f"{where}: a step is 'move', 'grip' or 'release'", world
    if held is not None:
        return False, f"the task ends holding {held}", world
    return True, "", world


# --- the runner ----------------------------------------------------------------------------


def _near(q_ref: np.ndarray, solutions: np.ndarray, lower, upper) -> np.ndarray:
    """Each solution shifted by whole turns to the equivalent nearest ``q_ref`` within limits,
    nearest first; the shoulder and elbow (joints 2 and 3) keep their principal values, since
    a whole turn of either would fold the arm through itself or the table."""
    shifted = q_ref + wrap_angles(solutions - q_ref, check=False)
    shifted = np.where(shifted > upper, shifted - 2 * np.pi, shifted)
    shifted = np.where(shifted < lower, shifted + 2 * np.pi, shifted)
    shifted[:, 1:3] = wrap_angles(solutions[:, 1:3], check=False)
    return shifted[np.argsort(np.linalg.norm(shifted - q_ref, axis=1), kind="stable")]


def _vertical(world: World, q_bottom: np.ndarray) -> np.ndarray | None:
    """Joint waypoints (1 mm of tool travel apart) straight up by :data:`HOVER` from
    ``q_bottom``, on its closed-form branch, or None when the branch cannot follow."""
    T = fk(world.robot, q_bottom)
    p = T[:3, 3]
    poses = pose_path(line(p, p + np.array([0.0, 0.0, HOVER])), T[:3, :3])
    result = track(world.robot, poses, q_bottom)
    return result.q if bool(np.all(result.ok)) else None


def _options(world, block_at, yaw_near, q_ref, down, up, resolution, count):
    """Up to ``count`` (bottom configuration, up waypoints, clearance) whose down and up moves
    are free, nearest ``q_ref`` first; and the reason of the last one that was not.

    ``down`` and ``up`` are ``(world, held block or None)`` to check the moves in; a held
    block is gripped where it is in that world, at the bottom configuration."""
    lower, upper = np.array(world.robot.joint_limits).T
    T = np.stack([_grasp_at(block_at, y) for y in grasp_yaws(block_at, yaw_near)])
    found = ik_analytic(world.robot, T).reshape(-1, 6)
    candidates = _near(q_ref, found[~np.isnan(found[:, 0])], lower, upper)
    good, why = [], "no closed-form configuration"
    for q in candidates:
        Q = _vertical(world, q)
        if Q is None:
            why = "the straight vertical move leaves the closed-form branch"
            continue
        verdicts = []
        for (where, held), moves in ((down, Q[::-1]), (up, Q)):
            grip = None if held is None else _hold(where, q, where.block(held))
            verdicts.append(_check(where, moves, held, grip, resolution))
            if not verdicts[-1].free:
                why = verdicts[-1].reason
                break
        else:
            good.append((q, Q, min(v.clearance for v in verdicts)))
            if len(good) == count:
                break
    return good, why


def _duration_line(n: int) -> float:
    return minimum_time("trapezoid", [HOVER], TOOL_SPEED, TOOL_ACCELERATION).T if n > 1 else 0.0


def pick_and_place(
    world: World,
    moves: Sequence[Move | tuple],
    q_start: ArrayLike,
    *,
    seed: int = 0,
    max_iterations: int = 3000,
    resolution: float = RESOLUTION,
    dt: float = 0.05,
) -> Task:
    """Pick and place blocks: every move validated, planned, checked, timed.

    Parameters
    ----------
    world : World
    moves : sequence of Move or (block, x, y[, z[, yaw]])
        Done in order, each from where the previous one left the arm and the blocks.
    q_start : array_like, shape (6,)
        The arm's configuration at the start, free of collisions.
    seed : int
        Seed of the planner (move ``k`` plans with ``seed + k``).
    max_iterations : int
        Of each RRT-Connect call.
    resolution : float
        Edge-check resolution (m).
    dt : float
        Sampling period of the timed trajectory (s).

    Returns
    -------
    Task
        Stops at the first phase that fails (``success`` False, the reason says which and
        why); the phases done until then are kept.

    Examples
    --------
    >>> import urkin
    >>> from urkin import planning
    >>> from urkin.transforms import make_transform
    >>> ur3 = urkin.robot("ur3").with_tool(make_transform(p=[0, 0, 0.1]))  # a suction rod
    >>> model = planning.sphere_model(ur3).with_tool_spheres([[0, 0, -0.05]], 0.02)
    >>> table = planning.Block.standing("table", [1.2, 1.2, 0.03], 0, 0, bottom=-0.03)
    >>> cube = planning.Block.standing("A", [0.05] * 3, 0.3, 0.1)
    >>> world = planning.World(ur3, model, table, [cube])
    >>> q_start = [0, -1.8, 1.6, -1.37, -1.5708, 0]
    >>> task = pick_and_place(world, [("A", 0.25, -0.15)], q_start, seed=0)
    >>> task.success, [p.name for p in task.phases][:4]
    (True, ['to pre-grasp', 'approach', 'grasp', 'lift'])
    >>> bool(np.linalg.norm(task.world.block("A").centre - task.goals[0].centre) < 1e-3)
    True
    """
    if not isinstance(world, World):
        raise TypeError(f"world must be a planning.World; got {type(world).__name__}")
    _check_options(seed, max_iterations, None, 0.5)  # rrt_connect's, before any move is planned
    if isinstance(moves, (str, bytes, Move)) or not isinstance(moves, Sequence):
        raise TypeError(
            "moves must be a sequence (list or tuple) of moves, each a planning.Move or "
            f"(block, x, y[, z[, yaw]]); got the {type(moves).__name__} {moves!r:.40}"
        )
    q = _one_configuration(q_start, "q_start")
    start = world
    phases: list[Phase] = []
    goals: list[Block] = []
    if not is_free(world.model, world.scene(), q):
        raise ValueError(f"q_start is in collision: {_offence(world.model, world.scene(), q)}")

    def fail(name: str, block: str, why: str, began: float) -> Task:
        phases.append(
            Phase(name, block, False, why, q[None], time.perf_counter() - began, 0.0, math.nan)
        )
        return _finish(
            False, f"{block}: {name} failed: {why}", phases, start, world, goals, q_start, dt
        )

    for k, move in enumerate(moves):
        began = time.perf_counter()
        verdict = validate_goal(world, move, q_start=q)
        label = move.block if isinstance(move, Move) else str(move[0])[:20]
        if not verdict.ok:
            return fail("to pre-grasp", label, "invalid goal: " + "; ".join(verdict.reasons), began)
        name, placed = label, verdict.placed
        block = world.block(name)
        yaw_now = _yaw_near(fk(world.robot, q))
        # the grasp: nearest closed-form configuration with a free approach and lift
        picks, why = _options(
            world, block, yaw_now, q, (world, None), (world, name), resolution, count=1
        )
        if not picks:
            return fail("approach", name, f"no free straight approach to {name}: {why}", began)
        q_grasp, up_pick, gap_pick = picks[0]
        grip = _hold(world, q_grasp, block)
        seconds = time.perf_counter() - began
        # to pre-grasp
        began = time.perf_counter()
        plan = _plan(
            world.model,
            world.scene(),
            q,
            up_pick[-1],
            seed=seed + k,
            max_iterations=max_iterations,
            resolution=resolution,
        )
        if not plan.success:
            return fail("to pre-grasp", name, plan.reason, began)
        phases.append(
            _planned(
                "to pre-grasp",
                name,
                plan.path,
                time.perf_counter() - began,
                _check(world, plan.path, None, None, resolution),
            )
        )
        line_time = _duration_line(len(up_pick))
        phases.append(
            Phase("approach", name, True, "", up_pick[::-1], seconds, line_time, gap_pick)
        )
        phases.append(Phase("grasp", name, True, "", q_grasp[None], 0.0, GRIP_TIME, math.nan))
        phases.append(Phase("lift", name, True, "", up_pick, 0.0, line_time, gap_pick))
        q = up_pick[-1].copy()
        # the place: up to three configurations with a free descent and retreat
        began = time.perf_counter()
        after = world.with_block(placed)
        places, why = _options(
            world,
            placed,
            _yaw_near(fk(world.robot, q)),
            q,
            (world, name),
            (after, None),
            resolution,
            count=3,
        )
        if not places:
            return fail("descend", name, f"no free straight descent onto the goal: {why}", began)
        seconds = time.perf_counter() - began
        began = time.perf_counter()
        carried = world.carrying(tuple(float(s) for s in block.size))
        plan = _plan(
            carried,
            world.scene(without=(name,)),
            q,
            np.array([up[-1] for _, up, _ in places]),
            seed=seed + k,
            max_iterations=max_iterations,
            resolution=resolution,
        )
        if not plan.success:
            return fail("transfer", name, plan.reason, began)
        verdict_t = _check(world, plan.path, name, grip, resolution)
        if not verdict_t.free:  # the spheres passed, the exact block test did not
            return fail("transfer", name, verdict_t.reason, began)
        phases.append(_planned("transfer", name, plan.path, time.perf_counter() - began, verdict_t))
        q_place, up_place, gap_place = places[plan.goal]
        final = fk(world.robot, q_place) @ grip
        yaw = math.atan2(final[1, 0], final[0, 0])
        placed = Block.standing(name, block.size, *placed.centre[:2], placed.bottom, yaw)
        goals.append(placed)
        phases.append(
            Phase("descend", name, True, "", up_place[::-1], seconds, line_time, gap_place)
        )
        phases.append(Phase("release", name, True, "", q_place[None], 0.0, GRIP_TIME, math.nan))
        phases.append(Phase("retreat", name, True, "", up_place, 0.0, line_time, gap_place))
        world = world.with_block(placed)
        q = up_place[-1].copy()
    return _finish(True, "", phases, start, world, goals, q_start, dt)


def _plan(model, scene, start, goals, **options) -> Plan:
    """RRT-Connect; goals that are all in collision for the planner's spheres give a failed
    plan with rrt_connect's reason, not an exception."""
    try:
        return rrt_connect(model, scene, start, goals, **options)
    except ValueError as error:
        return Plan(np.empty((0, 6)), False, str(error), 0, 0, -1, np.atleast_2d(goals), 0.0)


def _hold(world: World, q: np.ndarray, block: Block) -> np.ndarray:
    return inv_transform(fk(world.robot, q)) @ block.pose


def _planned(name: str, block: str, path: np.ndarray, seconds: float, verdict: _Verdict) -> Phase:
    duration = float(time_parametrize(path).t[-1]) if len(path) > 1 else 0.0
    return Phase(
        name, block, verdict.free, verdict.reason, path, seconds, duration, verdict.clearance
    )


def _finish(success, reason, phases, start, world, goals, q_start, dt) -> Task:
    """The timed trajectory and the blocks' poses along it."""
    ts, qs, held_at = [np.zeros(1)], [np.asarray(q_start, dtype=float).reshape(1, 6)], [None]
    clock = 0.0
    for p in phases:
        if not p.success:
            break
        if p.name in ("grasp", "release"):
            times = np.arange(1, max(1, round(p.duration / dt)) + 1) * dt
            Q = np.repeat(p.q, len(times), axis=0)
        elif p.name in ("to pre-grasp", "transfer"):
            timed = time_parametrize(p.q, dt=dt)
            times, Q = timed.t[1:], timed.q[1:]
        else:  # a straight line: trapezoidal in arc length over the 1 mm waypoints
            scaling = minimum_time("trapezoid", [HOVER], TOOL_SPEED, TOOL_ACCELERATION)
            times = np.append(np.arange(dt, scaling.T, dt), scaling.T)
            s = scaling(times)[0] * (len(p.q) - 1)
            j = np.minimum(np.floor(s).astype(int), len(p.q) - 2)
            Q = p.q[j] + (s - j)[:, None] * (p.q[j + 1] - p.q[j])
        ts.append(clock + times)
        qs.append(Q)
        carrying = p.block if p.name in ("lift", "transfer", "descend") else None
        held_at += [carrying] * len(times)
        clock += float(times[-1]) if len(times) else 0.0
    t, q = np.concatenate(ts), np.vstack(qs)
    tools = fk(start.robot, q)
    return Task(
        success,
        reason,
        tuple(phases),
        start,
        world,
        tuple(goals),
        t,
        q,
        _block_poses(start, world, phases, tools, held_at),
    )


def _block_poses(start: World, world: World, phases, tools, held_at) -> np.ndarray:
    names = start.names
    M = len(tools)
    poses = np.empty((M, len(names), 4, 4))
    current = {b.name: b.pose for b in start.blocks}
    held = np.array([names.index(h) if h is not None else -1 for h in held_at])
    # runs of samples with the same held block
    edges = np.flatnonzero(np.diff(held) != 0) + 1
    for a, b in zip(np.concatenate([[0], edges]), np.concatenate([edges, [M]])):
        for i, n in enumerate(names):
            poses[a:b, i] = current[n]
        h = held[a]
        if h >= 0:
            grip = inv_transform(tools[a - 1]) @ current[names[h]] if a else np.eye(4)
            poses[a:b, h] = tools[a:b] @ grip
            current[names[h]] = poses[b - 1, h]
    return poses
