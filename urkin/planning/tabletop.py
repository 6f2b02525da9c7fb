"""A tabletop world: an arm mounted by a table, fixed obstacles, blocks to move, and the
validation of a goal for a block.

Every object is an upright cuboid (:class:`~urkin.planning.blocks.Block`) in the world frame,
the frame the robot's ``base`` transform places the arm in.  The arm is checked with its
sphere model (arm and gripper) against all of them; a carried block is checked against them
exactly (:func:`~urkin.planning.blocks.box_separation`; resting contact is allowed, overlap
deeper than :data:`TOUCH` is not) and against the arm with its sphere cover.

:func:`validate_goal` tells whether a block can be put at a goal, and if not, every reason
that applies, each with its numbers, in a fixed order: the block itself (unknown, or under
another block), the table, reach with the tool pointing down, support, overlaps, the arm at
the place pose, and (optionally) a collision-free path.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import ArrayLike

from urkin.analytic_ik import ik_analytic, ik_closest
from urkin.kinematics import _one_configuration, fk
from urkin.planning.blocks import (
    Block,
    _grasp_at,
    _yaw_near,
    block_spheres,
    box_separation,
    grasp_yaws,
)
from urkin.planning.checks import explain, is_free
from urkin.planning.scene import Box, Scene
from urkin.planning.spheres import SphereModel
from urkin.robots import Robot, check_robot
from urkin.transforms import wrap_angles

__all__ = ["GoalCheck", "Move", "World", "validate_goal"]

#: Overlap of a carried or placed block with another box that still counts as resting contact.
TOUCH = 1e-4
#: A goal's bottom may be this far from a support's top; it is then put exactly on it.
SUPPORT_GAP = 0.005


@dataclass(frozen=True, eq=False)
class World:
    """An arm by a table with fixed obstacles and movable blocks, all in the world frame.

    Parameters
    ----------
    robot : Robot
        The arm, its ``base`` placing it in the world frame, its ``tool`` the gripper's tip
        (the tool's z axis the gripper's direction).
    model : SphereModel
        Spheres of the arm and the gripper (e.g. ``sphere_model(robot).with_tool_spheres``).
    table : Block
        The table; its top face is where blocks stand.
    blocks : sequence of Block
        The movable blocks (unique names).
    obstacles : sequence of Block
        Fixed upright boxes (posts, walls, shelves).
    max_protrusion : float
        How far a carried block's sphere cover may reach beyond its faces (m).
    """

    robot: Robot
    model: SphereModel
    table: Block
    blocks: tuple[Block, ...] = ()
    obstacles: tuple[Block, ...] = ()
    max_protrusion: float = 0.008
    _scenes: dict = field(default_factory=dict, init=False, repr=False)

    def __post_init__(self) -> None:
        check_robot(self.robot)
        if not isinstance(self.model, SphereModel):
            raise TypeError(f"model must be a planning.SphereModel; got {type(self.model)}")
        if self.model.robot.lengths != self.robot.lengths:
            raise ValueError("model must be a sphere model of robot (its DH lengths differ)")
        for name in ("blocks", "obstacles"):
            given = getattr(self, name)
            if isinstance(given, Block):  # one block: as a sequence of one (Scene does the same)
                given = (given,)
            if isinstance(given, (str, bytes)) or not isinstance(given, Iterable):
                raise TypeError(
                    f"{name} must be a sequence of planning.Block; got {type(given).__name__}"
                )
            items = tuple(given)
            for item in items:
                if not isinstance(item, Block):
                    raise TypeError(f"{name} must hold planning.Block objects; got {type(item)}")
            object.__setattr__(self, name, items)
        if not isinstance(self.table, Block):
            raise TypeError(f"table must be a planning.Block; got {type(self.table).__name__}")
        names = [self.table.name, *(b.name for b in self.obstacles), *(b.name for b in self.blocks)]
        twice = sorted({n for n in names if names.count(n) > 1})
        if twice:
            raise ValueError(f"names must be unique; repeated: {', '.join(twice)}")

    def __repr__(self) -> str:
        return (
            f"World({self.robot.name}, table {self.table.size[0]:g} × {self.table.size[1]:g} m, "
            f"blocks {', '.join(b.name for b in self.blocks) or 'none'}, "
            f"{len(self.obstacles)} obstacles)"
        )

    @property
    def names(self) -> tuple[str, ...]:
        """The block names."""
        return tuple(b.name for b in self.blocks)

    def block(self, name: str) -> Block:
        """The block called ``name``."""
        for b in self.blocks:
            if b.name == name:
                return b
        raise KeyError(f"no block named {name!r} (blocks: {', '.join(self.names) or 'none'})")

    def with_block(self, block: Block) -> World:
        """This world with ``block`` (by its name) at its new pose."""
        self.block(block.name)
        return replace(
            self, blocks=tuple(block if b.name == block.name else b for b in self.blocks)
        )

    def boxes(self, without: Sequence[str] = ()) -> tuple[Block, ...]:
        """The table, the obstacles and the blocks, except those named in ``without``."""
        return tuple(
            b for b in (self.table, *self.obstacles, *self.blocks) if b.name not in without
        )

    def scene(self, without: Sequence[str] = ()) -> Scene:
        """The boxes as a :class:`~urkin.planning.Scene` (cached per ``without``)."""
        key = tuple(sorted(without))  # a World's blocks never change: with_block makes another
        if key not in self._scenes:
            self._scenes[key] = Scene(
                boxes=[
                    Box(b.centre, b.size, b.pose[:3, :3], name=b.name) for b in self.boxes(without)
                ]
            )
        return self._scenes[key]

    def carrying(self, size: ArrayLike) -> SphereModel:
        """The arm's model holding a block of ``size`` by the centre of its top face (its cover
        of :func:`~urkin.planning.block_spheres` fixed in the tool frame)."""
        return _carrying(
            self.model, tuple(float(s) for s in np.asarray(size)), float(self.max_protrusion)
        )

    def below(self, name: str) -> str | None:
        """What block ``name`` stands on: ``"table"``'s name, a block's, or None."""
        return _support_of(self, self.block(name), exclude=(name,))

    def above(self, name: str) -> tuple[str, ...]:
        """The blocks standing on block ``name``."""
        return tuple(
            b.name
            for b in self.blocks
            if b.name != name and _support_of(self, b, (b.name,)) == name
        )


@functools.lru_cache(maxsize=32)
def _carrying(model: SphereModel, size: tuple[float, ...], protrusion: float) -> SphereModel:
    centres, radii = block_spheres(size, protrusion)
    centres = centres + np.array([0.0, 0.0, size[2] / 2])  # the tool's z points down
    return model.with_tool_spheres(centres, radii, name="carried block")


def _inside(point: np.ndarray, box: Block, margin: float = 0.0) -> np.ndarray:
    """How far (x, y) of ``point`` lies outside ``box``'s top face along its own axes (≤ 0:
    inside), as (2,) metres."""
    local = box.pose[:2, :2].T @ (point[:2] - box.pose[:2, 3])
    return np.abs(local) - box.size[:2] / 2 - margin


def _support_of(world: World, block: Block, exclude: Sequence[str]) -> str | None:
    for other in world.boxes(exclude):
        if abs(block.bottom - other.top) <= 1e-6 and np.all(_inside(block.centre, other) <= 1e-9):
            return other.name
    return None


@dataclass(frozen=True)
class Move:
    """A goal: put block ``block`` with the centre of its bottom face at ``(x, y)`` (world
    frame, m), turned by ``yaw`` (rad), at height ``z`` (m; default: on whatever is highest
    under ``(x, y)``)."""

    block: str
    x: float
    y: float
    z: float | None = None
    yaw: float = 0.0


@dataclass(frozen=True)
class GoalCheck:
    """The verdict of :func:`validate_goal`.

    Attributes
    ----------
    ok : bool
    reasons : tuple of str
        Every reason the goal is refused, in a fixed order; empty when ``ok``.
    placed : Block or None
        The block at its goal pose (put exactly on its support), when the goal is
        well-formed enough to have one.
    support : str or None
        What it would stand on.
    """

    ok: bool
    reasons: tuple[str, ...]
    placed: Block | None = None
    support: str | None = None

    def __str__(self) -> str:
        return "ok" if self.ok else "; ".join(self.reasons)


def _number(value: object, name: str, reasons: list[str]) -> float | None:
    if isinstance(value, (bool, np.bool_)):  # True is not 1 m
        reasons.append(f"{name} must be a number in metres; got {value!r}")
        return None
    try:
        x = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        reasons.append(f"{name} must be a number in metres; got {value!r:.40}")
        return None
    if not math.isfinite(x):
        reasons.append(f"{name} must be a finite number; got {x}")
        return None
    if abs(x) > 100:
        reasons.append(f"{name} = {x:g} is not a table coordinate in metres")
        return None
    return x


def _place_configurations(world: World, placed: Block, yaw_near: float) -> np.ndarray:
    """Every closed-form solution (k, 6) that holds ``placed`` by its top, over the yaws of
    its symmetry."""
    yaws = grasp_yaws(placed, yaw_near)
    T = np.stack([_grasp_at(placed, yaw) for yaw in yaws])
    solutions = ik_analytic(world.robot, T).reshape(-1, 6)
    return solutions[~np.isnan(solutions[:, 0])]


def validate_goal(
    world: World,
    goal: Move | Sequence,
    *,
    q_start: ArrayLike | None = None,
    plan: bool = False,
    seed: int = 0,
    max_iterations: int = 3000,
) -> GoalCheck:
    """Can ``goal`` be done in ``world``?  Every reason it cannot, each with its numbers.

    The checks, in this order (a check whose inputs are missing is skipped):

    1. the block exists and nothing stands on it;
    2. the goal's numbers are numbers, and the block's centre lies over the table
       (``"outside the table (x = 0.61 > 0.50 m)"``), not hanging over its edge;
    3. the arm reaches the grasp with the tool pointing down (the closed form's reason, with
       the distance);
    4. support: the block's bottom is within :data:`SUPPORT_GAP` of the top of the table or
       of a block under its centre (then it is put exactly there);
    5. the block overlaps no other box (by how much, exact for upright boxes);
    6. at the place pose, some closed-form configuration is free of collisions with the
       block held (otherwise the first offending pair of the nearest one);
    7. with ``plan=True`` and everything above fine: :func:`~urkin.planning.pick_and_place`
       finds a collision-free task from ``q_start`` (its reason otherwise).

    Parameters
    ----------
    world : World
    goal : Move or (block, x, y[, z[, yaw]])
        What a user typed; anything that is not a valid goal gets reasons, never an exception.
    q_start : array_like, shape (6,), optional
        The arm's configuration (for the yaw to stay near, and for ``plan``).
    plan, seed, max_iterations
        Plan the whole pick and place (check 7) from ``q_start`` (required with ``plan``).

    Returns
    -------
    GoalCheck

    Examples
    --------
    A UR3 with a 10 cm suction rod, a table, a block:

    >>> import urkin
    >>> from urkin import planning
    >>> from urkin.transforms import make_transform
    >>> ur3 = urkin.robot("ur3").with_tool(make_transform(p=[0, 0, 0.1]))
    >>> model = planning.sphere_model(ur3).with_tool_spheres([[0, 0, -0.05]], 0.02)
    >>> table = planning.Block.standing("table", [1.2, 1.2, 0.03], 0, 0, bottom=-0.03)
    >>> cube = planning.Block.standing("A", [0.05] * 3, 0.3, 0.1)
    >>> world = planning.World(ur3, model, table, [cube])
    >>> print(validate_goal(world, ("A", 0.7, 0.0)))  # doctest: +ELLIPSIS
    outside the table (x = 0.70 > 0.60 m); unreachable with the tool down: the target is ...
    >>> validate_goal(world, ("A", 0.25, -0.15)).ok
    True
    """
    if not isinstance(world, World):
        raise TypeError(f"world must be a planning.World; got {type(world).__name__}")
    if plan and q_start is None:
        raise ValueError("plan=True plans from q_start: give the arm's configuration")
    reasons: list[str] = []
    if isinstance(goal, Move):
        fields = [goal.block, goal.x, goal.y, goal.z, goal.yaw]
    elif isinstance(goal, (tuple, list)) and 3 <= len(goal) <= 5:
        fields = [*goal, *[None, 0.0][len(goal) - 3 :]]
    else:
        return GoalCheck(False, (f"a goal is (block, x, y[, z[, yaw]]); got {goal!r:.60}",))
    name = fields[0]
    if not isinstance(name, str) or name not in world.names:
        known = ", ".join(world.names)
        return GoalCheck(False, (f"no block named {name!r:.20} (blocks: {known})",))
    block = world.block(name)
    on_top = world.above(name)
    if on_top:
        reasons.append(f"block {name} is under block {on_top[0]}: move {on_top[0]} first")
    x = _number(fields[1], "x", reasons)
    y = _number(fields[2], "y", reasons)
    z = None if fields[3] is None else _number(fields[3], "z", reasons)
    yaw = _number(fields[4], "yaw", reasons)
    if x is None or y is None or yaw is None or (fields[3] is not None and z is None):
        return GoalCheck(False, tuple(reasons))
    table = world.table
    point = np.array([x, y, 0.0])
    out = _inside(point, table)
    local = table.pose[:2, :2].T @ (point[:2] - table.pose[:2, 3])
    if np.any(out > 0):
        axis = int(np.argmax(out))
        label = "xy"[axis] if np.allclose(table.pose[:2, :2], np.eye(2)) else "xy"[axis] + "'"
        value = (x, y)[axis] if label in "xy" else local[axis]
        edge = (table.pose[axis, 3] if label in "xy" else 0.0) + math.copysign(
            table.size[axis] / 2, local[axis]
        )
        sign = ">" if local[axis] > 0 else "<"
        reasons.append(f"outside the table ({label} = {value:.2f} {sign} {edge:.2f} m)")
    # where it would stand
    supports = [(table.top, table.name)] if np.all(out <= 0) else []
    supports += [
        (b.top, b.name)
        for b in world.blocks
        if b.name != name and np.all(_inside(point, b) <= 1e-9)
    ]
    if z is None:
        z = max((top for top, _ in supports), default=table.top)
    placed = Block.standing(name, block.size, x, y, z, yaw)
    # reach with the tool pointing down
    q_now = None if q_start is None else _one_configuration(q_start, "q_start")
    yaw_now = 0.0 if q_now is None else _yaw_near(fk(world.robot, q_now))
    configurations = _place_configurations(world, placed, yaw_now)
    if len(configurations) == 0:
        T = _grasp_at(placed, float(grasp_yaws(placed, yaw_now)[0]))
        why = ik_closest(world.robot, T, np.zeros(6)).reason.removeprefix("unreachable: ")
        reasons.append(f"unreachable with the tool down: {why}")
    # support
    support = None
    if supports:
        gaps = [abs(z - top) for top, _ in supports]
        k = int(np.argmin(gaps))
        if gaps[k] <= SUPPORT_GAP:
            support = supports[k][1]
            placed = Block.standing(name, block.size, x, y, supports[k][0], yaw)
        else:
            reasons.append(
                f"no support: the block's bottom must be within {SUPPORT_GAP * 1e3:.0f} mm of a "
                f"top below it; the nearest ({supports[k][1]}) is {gaps[k] * 1e3:.0f} mm off"
            )
    elif np.all(out <= 0):
        reasons.append("no support: nothing under the block's centre")
    # overlaps
    others = world.boxes((name,))
    if others:
        gap = box_separation(
            placed.centre,
            placed.pose[:3, :3],
            placed.size / 2,
            np.array([b.centre for b in others]),
            np.array([b.pose[:3, :3] for b in others]),
            np.array([b.size / 2 for b in others]),
        )
        for b, g in zip(others, gap):
            if g < -TOUCH:
                kind = "block" if b.name in world.names else "obstacle" if b is not table else ""
                what = f"{kind} {b.name}".strip()
                reasons.append(f"overlaps {what} by {-g * 1e3:.0f} mm")
    # the arm at the place pose, holding the block
    if len(configurations) and not reasons:
        # the arm and gripper against the boxes, the carried block's cover against the arm
        # (the block itself against the boxes was the overlap test)
        carried = world.carrying(block.size)
        scene = world.scene(without=(name,))
        arm = is_free(world.model, scene, configurations)
        own = is_free(carried, Scene(), configurations)
        if not np.any(arm & own):
            near = (
                configurations[0]
                if q_now is None
                else configurations[
                    np.argmin(np.linalg.norm(wrap_angles(configurations - q_now), axis=1))
                ]
            )
            why = (
                explain(world.model, scene, near)
                if not is_free(world.model, scene, near)
                else explain(carried, Scene(), near)
            )
            why = why.removeprefix("in collision: ")
            reasons.append(f"arm in collision at the place pose: {why}")
    if reasons:
        return GoalCheck(False, tuple(reasons), placed, support)
    if plan:
        from urkin.planning.tasks import pick_and_place

        result = pick_and_place(
            world,
            [Move(name, x, y, placed.bottom, yaw)],
            q_now,
            seed=seed,
            max_iterations=max_iterations,
        )
        if not result.success:
            return GoalCheck(False, (result.reason,), placed, support)
    return GoalCheck(True, (), placed, support)
