"""Blocks on a table: upright cuboids, their top-down grasps, their sphere covers, and exact
box–box tests.

A :class:`Block` is a cuboid standing upright (its own z axis vertical) with a name, its full
edge lengths and its pose in the world (table) frame.  Its **grasp** (:func:`top_down_grasp`)
puts the tool origin — a suction cup's tip — at the centre of the top face with the tool's
z axis pointing straight down; the tool's yaw is the block's yaw plus a multiple of the
block's symmetry (90° for a square footprint, 180° otherwise), the multiple chosen nearest a
given yaw (the wrist's current one), so the last joint turns as little as possible.

A carried block is attached to the tool frame as the spheres of :func:`block_spheres` (for
the arm's self-collision checks) and tested against the other boxes exactly
(:func:`box_separation`, the separating-axis test).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from urkin._inputs import positive, real, shape_text
from urkin.transforms import check_rotation, check_transform, make_transform, rot_z, wrap_angles

__all__ = [
    "Block",
    "block_spheres",
    "box_separation",
    "grasp_yaws",
    "symmetry",
    "tool_yaw",
    "top_down_grasp",
]

#: Largest tilt (rad) of a block's z axis from the vertical that still counts as upright.
UPRIGHT_TOLERANCE = 1e-6


@dataclass(frozen=True)
class Block:
    """An upright cuboid: a ``name``, full edge lengths ``size`` (x, y, z; metres) and its
    ``pose`` ``T_world_block`` (the pose of its centre; its z axis vertical).

    Examples
    --------
    >>> from urkin import planning
    >>> a = planning.Block.standing("A", [0.05, 0.05, 0.04], x=0.2, y=0.1)
    >>> a.bottom, a.top, a.yaw
    (0.0, 0.04, 0.0)
    """

    name: str
    size: np.ndarray
    pose: np.ndarray

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise ValueError(f"block name must be a non-empty string; got {self.name!r}")
        size = real(self.size, "size").astype(float)
        if size.shape != (3,) or np.any(size <= 0) or np.any(size > 5.0):
            raise ValueError(
                f"block {self.name!r}: size must be three positive edge lengths in metres; "
                f"got {np.asarray(self.size).tolist()}"
            )
        pose = check_transform(self.pose, name="pose")
        if pose.shape != (4, 4):
            raise ValueError(f"block {self.name!r}: pose must be one (4, 4) transform")
        tilt = math.hypot(pose[0, 2], pose[1, 2])
        if not (tilt <= UPRIGHT_TOLERANCE and pose[2, 2] > 0):
            raise ValueError(
                f"block {self.name!r} must stand upright (its z axis vertical); it is tilted "
                f"by {math.degrees(math.atan2(tilt, pose[2, 2])):.3g}°"
            )
        size.setflags(write=False)
        pose = pose.copy()
        pose.setflags(write=False)
        object.__setattr__(self, "size", size)
        object.__setattr__(self, "pose", pose)

    @classmethod
    def standing(
        cls,
        name: str,
        size: ArrayLike,
        x: float,
        y: float,
        bottom: float = 0.0,
        yaw: float = 0.0,
    ) -> Block:
        """A block whose bottom face's centre is at ``(x, y, bottom)``, turned by ``yaw``."""
        size = real(size, "size")
        x, y, bottom, yaw = (
            float(real(v, n)) for v, n in ((x, "x"), (y, "y"), (bottom, "bottom"), (yaw, "yaw"))
        )
        centre = [x, y, bottom + float(size.reshape(-1)[-1]) / 2]
        return cls(name, size, make_transform(rot_z(yaw), centre))

    @property
    def centre(self) -> np.ndarray:
        """The centre, world frame (m)."""
        return self.pose[:3, 3]

    @property
    def bottom(self) -> float:
        """Height of the bottom face (m)."""
        return float(self.pose[2, 3] - self.size[2] / 2)

    @property
    def top(self) -> float:
        """Height of the top face (m)."""
        return float(self.pose[2, 3] + self.size[2] / 2)

    @property
    def yaw(self) -> float:
        """The angle of the block's x axis about the vertical, in (−π, π]."""
        return float(math.atan2(self.pose[1, 0], self.pose[0, 0]))

    def moved(self, pose: ArrayLike) -> Block:
        """The same block at another pose."""
        return Block(self.name, self.size, pose)

    def footprint(self) -> np.ndarray:
        """The corners of the bottom face, (4, 2) x–y in the world frame, counter-clockwise."""
        hx, hy = self.size[0] / 2, self.size[1] / 2
        local = np.array([[hx, hy], [-hx, hy], [-hx, -hy], [hx, -hy]])
        return local @ self.pose[:2, :2].T + self.pose[:2, 3]


def symmetry(size: ArrayLike) -> float:
    """The yaw (rad) that turns a block's footprint onto itself: π/2 when square, else π."""
    s = real(size, "size")
    return math.pi / 2 if abs(float(s[0]) - float(s[1])) <= 1e-9 else math.pi


def tool_yaw(T_world_tool: ArrayLike) -> np.ndarray | float:
    """The yaw of a tool's x axis about the world's vertical (rad): the angle of its
    horizontal part from the world's x axis.  For a tool pointing down (the grasps of the
    block tasks), the turn about the vertical that takes the world's x axis to the tool's.

    Raises
    ------
    ValueError
        Where the tool's x axis is vertical (within 1e-9 rad), which has no yaw.

    Examples
    --------
    >>> from urkin.transforms import make_transform, rot_x, rot_y, rot_z
    >>> round(tool_yaw(make_transform(rot_z(0.3) @ rot_x(np.pi))), 12)
    0.3
    >>> tool_yaw(make_transform(rot_y(np.pi / 2)))
    Traceback (most recent call last):
    ...
    ValueError: T_world_tool's x axis is vertical: it has no yaw
    """
    T = check_transform(T_world_tool, name="T_world_tool")
    yaw, vertical = _yaw(T)
    if np.any(vertical):
        where = "" if T.ndim == 2 else f" at {tuple(int(i) for i in np.argwhere(vertical)[0])}"
        raise ValueError(f"T_world_tool's x axis is vertical{where}: it has no yaw")
    return float(yaw) if yaw.ndim == 0 else yaw


def _yaw(T: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`tool_yaw` of checked poses, and where it is undefined (the x axis vertical:
    its yaw is then 0)."""
    x, y = T[..., 0, 0], T[..., 1, 0]
    vertical = np.hypot(x, y) <= 1e-9
    return np.where(vertical, 0.0, np.arctan2(y, x)), vertical


def _yaw_near(T: np.ndarray) -> float:
    """The yaw of one checked tool pose to order grasps by (0 where it has none)."""
    return float(_yaw(T)[0])


def _down(yaw: np.ndarray) -> np.ndarray:
    """Rotations (..., 3, 3) with z pointing down and x at ``yaw`` about the vertical."""
    c, s = np.cos(yaw), np.sin(yaw)
    R = np.zeros((*np.shape(yaw), 3, 3))
    R[..., 0, 0], R[..., 1, 0] = c, s
    R[..., 0, 1], R[..., 1, 1] = s, -c
    R[..., 2, 2] = -1.0
    return R


def grasp_yaws(block: Block, yaw_near: float = 0.0) -> np.ndarray:
    """The tool yaws that grasp ``block`` from above, nearest ``yaw_near`` first (rad, in
    (−π, π]): the block's yaw plus every multiple of its :func:`symmetry`."""
    step = symmetry(block.size)
    k = np.arange(round(2 * math.pi / step))
    yaws = wrap_angles(block.yaw + k * step)
    return yaws[np.argsort(np.abs(wrap_angles(yaws - float(yaw_near))), kind="stable")]


def top_down_grasp(block: Block, yaw_near: float = 0.0) -> np.ndarray:
    """The tool pose that grasps ``block`` from above: ``T_world_tool``, (4, 4).

    The tool origin is at the centre of the block's top face, the tool's z axis points
    straight down, and its x axis is the block's x axis turned by the multiple of the block's
    symmetry (90° for a square footprint, 180° otherwise) that brings it nearest
    ``yaw_near`` (the wrist's current yaw, :func:`tool_yaw`).

    Parameters
    ----------
    block : Block
    yaw_near : float
        The yaw to stay near (rad).

    Examples
    --------
    >>> from urkin import planning
    >>> cube = planning.Block.standing("A", [0.05, 0.05, 0.05], x=0.2, y=0.1, yaw=0.1)
    >>> T = planning.top_down_grasp(cube, yaw_near=1.5)
    >>> T[:3, 3].round(6).tolist(), round(planning.tool_yaw(T), 6)  # 0.1 + π/2
    ([0.2, 0.1, 0.05], 1.670796)
    >>> T[:3, 2].tolist()  # the tool points down
    [0.0, 0.0, -1.0]
    """
    if not isinstance(block, Block):
        raise TypeError(f"block must be a planning.Block; got {type(block).__name__}")
    return _grasp_at(block, float(grasp_yaws(block, float(real(yaw_near, "yaw_near")))[0]))


def _grasp_at(block: Block, yaw: float) -> np.ndarray:
    """The top-down grasp of ``block`` with the tool's x axis at ``yaw``."""
    return make_transform(_down(np.array(yaw)), [*block.centre[:2], block.top])


#: The most spheres :func:`block_spheres` makes for one block (a 1 m cube at the default
#: protrusion takes about 12,000).
MAX_BLOCK_SPHERES = 20_000


def block_spheres(size: ArrayLike, max_protrusion: float = 0.008) -> tuple[np.ndarray, np.ndarray]:
    """Spheres covering a box's surface, centred in its frame: ``(centres (K, 3), radii (K,))``.

    The box is cut into a grid of equal cells, as few as keep every sphere within
    ``max_protrusion`` of the box; each cell on the surface gets the sphere through its eight
    corners (radius half the cell's diagonal), so every point of the surface lies in a sphere
    and no sphere reaches more than ``max_protrusion`` beyond a face.  (A box cannot be
    inside an obstacle without its surface meeting it, so the inner cells are left out.)

    Examples
    --------
    >>> centres, radii = block_spheres([0.05, 0.05, 0.05])
    >>> len(radii), bool((radii - 0.05 / 3 / 2).max() <= 0.008)
    (26, True)
    """
    s = real(size, "size").astype(float)
    if s.shape != (3,) or np.any(s <= 0):
        raise ValueError(f"size must be three positive edge lengths (m); got {s.tolist()}")
    p = float(positive(max_protrusion, "max_protrusion", what="a positive distance (m)"))
    with np.errstate(over="ignore"):  # infinitely many cells: refused below
        n = np.maximum(1.0, np.ceil(s / (p / 0.36)))  # cells along each edge, floats until known
    while True:
        many = n.max() > MAX_BLOCK_SPHERES  # checked first: the products could overflow
        if many or np.prod(n) - np.prod(np.maximum(n - 2.0, 0.0)) > MAX_BLOCK_SPHERES:
            raise ValueError(
                f"a block of size {s.tolist()} m needs more than {MAX_BLOCK_SPHERES:,} spheres "
                f"to stay within max_protrusion = {p:g} m of it: sizes are in metres (did you "
                "pass millimetres?), or allow a larger max_protrusion"
            )
        cell = s / n
        radius = float(np.sqrt(cell @ cell)) / 2
        if radius - cell.min() / 2 <= p:
            break
        n[int(np.argmax(cell))] += 1
    n = n.astype(int)
    grid = np.stack(np.meshgrid(*(np.arange(k) for k in n), indexing="ij"), axis=-1).reshape(-1, 3)
    surface = np.any((grid == 0) | (grid == n - 1), axis=1)
    centres = (grid[surface] + 0.5) * cell - s / 2
    return centres, np.full(len(centres), radius)


def _stack(x: ArrayLike, name: str, core: tuple[int, ...]) -> np.ndarray:
    """``x`` as a float array of ``core`` items (one, or a stack), or an error naming it."""
    array = real(x, name)
    if array.shape[array.ndim - len(core) :] != core or array.ndim < len(core):
        raise ValueError(f"{name} must have shape {shape_text(core)}; got {array.shape}")
    return array


def box_separation(
    centre_a: ArrayLike,
    R_a: ArrayLike,
    half_a: ArrayLike,
    centre_b: ArrayLike,
    R_b: ArrayLike,
    half_b: ArrayLike,
) -> np.ndarray:
    """The separating-axis test of oriented boxes, batched: the largest gap along any of the
    15 axes (faces of either box, cross products of their edges), metres.

    Negative means the boxes overlap; then, for two upright boxes (z axes vertical), its
    magnitude is exactly how far one must move to separate them (the penetration depth).
    Positive is a lower bound of their distance.  Arguments broadcast over leading axes:
    centres (..., 3), rotations (..., 3, 3) (columns: the box's axes), half edge lengths
    (..., 3).

    Examples
    --------
    >>> I = np.eye(3)
    >>> float(box_separation([0, 0, 0], I, [0.1] * 3, [0.15, 0, 0], I, [0.1] * 3)).__round__(6)
    -0.05
    """
    ca, cb = _stack(centre_a, "centre_a", (3,)), _stack(centre_b, "centre_b", (3,))
    Ra, Rb = _stack(R_a, "R_a", (3, 3)), _stack(R_b, "R_b", (3, 3))
    ha, hb = _stack(half_a, "half_a", (3,)), _stack(half_b, "half_b", (3,))
    for R, name in ((Ra, "R_a"), (Rb, "R_b")):
        check_rotation(R, name=name)  # the test takes the columns as the box's unit axes
    for h, name in ((ha, "half_a"), (hb, "half_b")):
        if np.any(h < 0):
            raise ValueError(f"{name} must be half edge lengths ≥ 0 (metres); got {h.min():g}")
    try:
        lead = np.broadcast_shapes(
            ca.shape[:-1], Ra.shape[:-2], ha.shape[:-1], cb.shape[:-1], Rb.shape[:-2], hb.shape[:-1]
        )
    except ValueError:
        shapes = ", ".join(
            f"{name} {v.shape}"
            for name, v in zip(
                ("centre_a", "R_a", "half_a", "centre_b", "R_b", "half_b"), (ca, Ra, ha, cb, Rb, hb)
            )
        )
        raise ValueError(f"the boxes' stacks must broadcast together; got {shapes}") from None
    ca, cb, ha, hb = (np.broadcast_to(v, (*lead, 3)) for v in (ca, cb, ha, hb))
    Ra, Rb = (np.broadcast_to(R, (*lead, 3, 3)) for R in (Ra, Rb))
    t = cb - ca
    # axes: the 3 + 3 face normals, then the 9 edge cross products
    cross = np.cross(Ra[..., :, :, None], Rb[..., :, None, :], axis=-3)  # (..., 3, 3, 3)
    cross = cross.reshape(*cross.shape[:-2], 9)
    norm = np.linalg.norm(cross, axis=-2, keepdims=True)
    usable = norm > 1e-9  # parallel edges give no axis
    cross = np.where(usable, cross / np.where(usable, norm, 1.0), 0.0)
    axes = np.concatenate([Ra, Rb, cross], axis=-1)  # (..., 3, 15)
    reach_a = np.einsum("...k,...ik->...i", ha, np.abs(np.einsum("...ji,...jk->...ik", axes, Ra)))
    reach_b = np.einsum("...k,...ik->...i", hb, np.abs(np.einsum("...ji,...jk->...ik", axes, Rb)))
    gap = np.abs(np.einsum("...j,...ji->...i", t, axes)) - reach_a - reach_b
    valid = np.concatenate(
        [np.ones((*usable.shape[:-2], 6), dtype=bool), usable[..., 0, :]], axis=-1
    )
    return np.max(np.where(valid, gap, -np.inf), axis=-1)
