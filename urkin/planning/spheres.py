"""Sphere models of the arms: spheres attached to DH frames, placed by ``fk_frames``.

A :class:`SphereModel` is a list of spheres, each fixed in one frame of the arm — DH frame 0
(the base) to 6 (the flange), or 7, the tool frame (the flange moved by the robot's ``tool``
transform: a gripper, a held block) — with the pairs of spheres that self-collision checks
test.  :func:`sphere_model` gives the fitted models of the UR3, UR5 and UR10; a model can also
be built by hand from ``(frame, x, y, z, radius)`` rows (:meth:`SphereModel.from_rows`) and
given extra spheres on the tool (:meth:`SphereModel.with_tool_spheres`).

Provenance of the fitted models
    Fitted to the ROS-Industrial ``ur_description`` collision meshes (BSD; copied from the
    ``example-robot-data`` 6.0.0 wheel into ``tests/data/meshes``) by ``python -m
    tests.fit_spheres``: each link's mesh in its DH frame, split into pieces no longer than
    12 mm, grouped by halving, each group enclosed by a sphere through the group's vertices
    (plus 0.5 mm).  A group is cut in two, across a principal axis, while that makes its
    sphere reach markedly less far beyond the link's surface (its *excess*: the mean, over
    points of the sphere, of how far outside the mesh they lie), until it is within 6 mm: a
    tube becomes a row of slices hardly wider than the tube, a housing a few pieces.  A sphere
    that still reaches more than 10 mm past the surface over a twentieth of its own (the 95th
    percentile of those distances) is then cut by that measure while cuts pay (a slice across
    a tube's flange, which refused a MotionBenchMaker goal whose mesh is 8 mm clear).  A ball
    holding a triangle's corners holds the whole triangle, so the spheres cover every point
    of the mesh surface; ``tests/test_planning_spheres.py`` checks it on fresh surface
    samples, the meshes placed by the URDF and the spheres by :func:`urkin.fk_frames`, at
    random configurations.  Beyond flat faces and ends the spheres still reach 1–3 cm past
    the surface (a ball cannot follow a flat face); around the tubes of the UR5's upper arm
    and forearm, 4–13 mm (k-means groups, which split a tube's ring before its length, left
    16 mm and more there, and one ball on each wrist 2 cm).

Self-collision pairs
    Three pairs of links of the fitted models are tested on their meshes, not their spheres: the
    base and the upper arm (their relative pose depends on joints 1 and 2 only), the forearm and
    wrist 2 (joints 4 and 5), and the forearm and wrist 3 turned about joint 6's axis by any
    angle (a solid of revolution around its nearly round mesh: joints 4 and 5 again; the UR5's
    wrist 3 carries a bump 5.6 mm high, which the solid leaves out and a small sphere of its own
    holds, tested against the forearm spheres it can meet by the rule of hand-built models
    below).  ``python -m tests.pair_tables`` tabulates the exact distance of each pair over its
    two joints, one node per degree (:class:`MeshPair`; between nodes a lower bound from the
    nearest four).  Their spheres, which reach 1–3 cm beyond the surface at the housings' flat
    faces, overlap where the links are clear: of random configurations, the spheres leave 60 %
    of the UR5's free of self-collision, the tables 70 % (UR10: 79 and 82 %; UR3: 59 and 66 %);
    of VAMP's 700 MotionBenchMaker UR5 problems (VAMP's gripper spheres on the flange), the
    spheres put the start or goal of 48 in collision, the tables and spheres together 4 (three
    by a tabled pair whose meshes are 0.1–2.4 mm apart, one by a sphere 1 mm into a table;
    none of the 689 that VAMP's own spheres leave free).  The other pairs of the fitted models are
    witnessed by the meshes: in 2,000 seeded random configurations, wherever two links that are
    not the same or adjacent came within 5 mm of each other, the two spheres holding the nearby
    points form a pair to test; pairs that overlapped in every one of 20,000 random
    configurations are dropped (a fixed overlap of two housings would make every configuration a
    collision).  The tests check on fresh configurations that no contact of the meshes goes
    unseen, and the table against surface samples.  Of a hand-built model (:func:`self_pairs`,
    no meshes to consult): two spheres are tested against each other unless their links are the
    same or adjacent (frames ``i`` and ``i ± 1``; the tool frame is part of link 6), or, over
    20,000 random configurations within the joint limits (seed 0), they never came within 2 cm
    of each other (they cannot meet in practice) or always overlapped; it runs once per model (a
    fifth of a second for 50 spheres).  Tool spheres added to a fitted model get their pairs by
    this rule.
"""

from __future__ import annotations

import base64
import functools
import io
import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from urkin._generated import ur_kinematics as _gen
from urkin._inputs import real
from urkin.kinematics import fk_frames
from urkin.planning._sphere_tables import FITTED, PAIRS
from urkin.planning.scene import _nonzero
from urkin.robots import Robot, check_robot, random_configurations
from urkin.robots import robot as _robot_by_name

__all__ = [
    "FRAME_NAMES",
    "TOOL_FRAME",
    "MeshPair",
    "SphereModel",
    "self_pairs",
    "sphere_model",
]

#: Names of the frames spheres attach to: DH frames 0 … 6, then the tool frame.
FRAME_NAMES = ("base", "shoulder", "upper arm", "forearm", "wrist 1", "wrist 2", "wrist 3", "tool")
#: The index of the tool frame (the flange moved by the robot's ``tool`` transform).
TOOL_FRAME = 7

#: The self-pair rule's sampling (see the module notes).
_PAIR_SAMPLES, _PAIR_MARGIN, _PAIR_SEED = 20_000, 0.02, 0


@dataclass(frozen=True, eq=False)
class MeshPair:
    """Two links whose collision meshes' distance is tabulated over the two joints between
    them (``python -m tests.pair_tables``).

    The links move with DH frames ``a`` and ``a + 2``, so their relative pose depends on joints
    ``a + 1`` and ``a + 2`` only; or with frames ``a`` and ``a + 3``, the second link's mesh
    replaced by a solid of revolution about joint ``a + 3``'s axis that holds it turned by
    any angle, whose pose depends on the same two joints.  ``distance`` (n, n) holds the
    meshes' exact distance (rounded down; 0 where they intersect) at the grid nodes
    ``q = −π + 2π k / n`` of those joints;
    ``reach`` (2,) bounds the distance of the second link's mesh from each joint's axis, so
    between nodes the distance falls at most by ``Σ |Δq| · reach``: :meth:`lower_bound` takes
    the best of the four surrounding nodes.  Neighbouring nodes must not differ by more than
    that allows (checked): the lower bound is then continuous from cell to cell and falls at
    most at the rate ``reach`` along any edge, which the edge checks' grown samples rely on.

    Attributes
    ----------
    frames : tuple of int
        The two links' DH frames, ``(a, a + 2)`` or ``(a, a + 3)``.
    distance : ndarray, shape (n, n)
        Metres; rows: the first joint, columns: the second.
    reach : ndarray, shape (2,)
        Metres.
    spheres : ndarray, shape (k, 4)
        Spheres ``(x, y, z, radius)`` fixed in the second link's frame that hold the part of
        its mesh the table leaves out (the UR5's wrist 3 carries a small bump that its solid
        of revolution would spread around the whole turn); a fitted model tests them
        against the first link's spheres that they can meet (the rule of hand-built models,
        module notes).  Empty by default.
    """

    frames: tuple[int, int]
    distance: np.ndarray
    reach: np.ndarray
    spheres: np.ndarray = field(default_factory=lambda: np.zeros((0, 4)))

    def __post_init__(self) -> None:
        frames = tuple(self.frames) if isinstance(self.frames, (tuple, list)) else ()
        if len(frames) != 2 or not all(isinstance(f, (int, np.integer)) for f in frames):
            raise ValueError(
                f"frames must be two DH frame numbers, (a, a + 2) or (a, a + 3); got "
                f"{self.frames!r}"
            )
        a, b = int(frames[0]), int(frames[1])
        object.__setattr__(self, "frames", (a, b))
        for name in ("distance", "reach", "spheres"):  # float arrays of their own, or an error
            object.__setattr__(self, name, real(getattr(self, name), name, finite=False).copy())
        n = len(self.distance) if self.distance.ndim else 0
        spheres = self.spheres
        if spheres.ndim != 2 or spheres.shape[1] != 4 or not np.isfinite(spheres).all():
            raise ValueError(
                f"spheres must be finite rows (x, y, z, radius), shape (k, 4); got shape "
                f"{spheres.shape}"
            )
        if np.any(spheres[:, 3] <= 0):
            raise ValueError("spheres: every radius must be positive (metres)")
        spheres.setflags(write=False)
        if b - a not in (2, 3) or not 0 <= a <= 6 - (b - a):
            raise ValueError(
                f"frames must be (a, a + 2) or (a, a + 3) within frames 0 … 6; got {self.frames}"
            )
        if self.distance.shape != (n, n) or n < 2 or self.reach.shape != (2,):
            raise ValueError(
                f"distance must be (n, n) and reach (2,); got {self.distance.shape} and "
                f"{self.reach.shape}"
            )
        if not (np.isfinite(self.distance).all() and np.all(self.reach >= 0)):
            raise ValueError("distance must be finite and reach non-negative (metres)")
        for axis, step in enumerate(self._slope()):
            jump = float(np.abs(self.distance - np.roll(self.distance, 1, axis)).max())
            if jump > step * (1 + 1e-9):
                raise ValueError(
                    f"distance changes by {jump * 1000:.3g} mm between neighbouring nodes of "
                    f"joint {self.joints[axis] + 1}, more than its reach allows "
                    f"({step * 1000:.3g} mm per step): reach must bound how fast it can change"
                )
        self.distance.setflags(write=False)
        self.reach.setflags(write=False)
        # a lower bound over each cell between four nodes: at its point farthest from every
        # node (half a step in each joint from the nearest)
        D = self.distance
        corners = np.minimum(
            np.minimum(D, np.roll(D, -1, 0)), np.roll(np.minimum(D, np.roll(D, -1, 0)), -1, 1)
        )
        floor = corners - self._slope().sum() / 2
        # both tables flat, wrapped by two more rows and columns: a cell's lower node (i, k),
        # 0 ≤ i, k ≤ n (n where round-off lands on 2π), is entry (n + 2) i + k, and the four
        # nodes around it are that entry plus ``_nodes``
        for name, table in (("_floor", floor), ("_flat", D)):
            flat = np.pad(table, (0, 2), mode="wrap").reshape(-1)
            flat.setflags(write=False)
            object.__setattr__(self, name, flat)
        object.__setattr__(self, "_nodes", np.array([0, n + 2, 1, n + 3]))

    @property
    def joints(self) -> tuple[int, int]:
        """The two joints' indices into a configuration (0-based)."""
        return self.frames[0], self.frames[0] + 1

    def _slope(self) -> np.ndarray:
        """How much the distance can fall per grid step of each joint (m)."""
        return self.reach * (2 * math.pi / len(self.distance))

    def lower_bound(self, Q: np.ndarray) -> np.ndarray:
        """A lower bound of the meshes' distance at configurations ``Q`` (N, 6): (N,) metres
        (0 or less where they may touch): the best of the four surrounding nodes' distances,
        less how far it can fall from each."""
        everywhere = np.full((len(Q), 1), np.inf)  # no cell ruled out
        return _tables((self,)).bounds(Q, everywhere)[2]

    def collides(self, Q: np.ndarray) -> np.ndarray:
        """Whether the meshes may touch at configurations ``Q`` (N, 6): (N,) bool (the bound
        is computed only in the cells whose lower bound does not already rule it out)."""
        rows, _, bound = _tables((self,)).bounds(Q, None)
        hit = np.zeros(len(Q), dtype=bool)
        hit[rows[bound <= 0.0]] = True
        return hit


#: Each of the four nodes around a point (MeshPair._nodes), as steps along the two joints.
_STEPS = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]])


@dataclass(frozen=True)
class _Tables:
    """Several :class:`MeshPair` tables as one, so that checks bound every pair at once:
    ``columns`` (2P,), the two joints of each pair; ``steps`` (P, 1), grid steps per radian;
    ``stride`` and ``offset`` (P,), each pair's row length and first entry in ``floor`` and
    ``flat`` (the pairs' flat tables, one after the other); ``nodes`` (P, 4), the four nodes
    around a cell; ``slope`` (P, 1, 2); ``reach`` (P, 2), how fast each pair's lower bound can
    fall per radian of its two joints."""

    columns: np.ndarray
    steps: np.ndarray
    stride: np.ndarray
    offset: np.ndarray
    floor: np.ndarray
    flat: np.ndarray
    nodes: np.ndarray
    slope: np.ndarray
    reach: np.ndarray

    def bounds(
        self, Q: np.ndarray, margin: np.ndarray | None
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The configurations and pairs (rows, pairs, in row order) whose cell's lower bound
        does not rule out coming within ``margin`` (N, P) (None: touching), and
        :meth:`MeshPair.lower_bound` at each."""
        n, P = len(Q), len(self.steps)
        x = Q[:, self.columns].reshape(n, P, 2)
        x += math.pi
        np.mod(x, 2 * math.pi, out=x)
        x *= self.steps  # grid units, 0 … n
        i = x.astype(np.intp)  # the cell's lower node (x ≥ 0: truncation is the floor)
        cell = i[..., 0] * self.stride
        cell += i[..., 1]
        cell += self.offset  # (N, P)
        near = self.floor[cell] <= (0.0 if margin is None else margin)
        if not near.any():  # most configurations: every pair's cell rules out contact
            return _NONE, _NONE, np.zeros(0)
        rows, pairs = _nonzero(near)
        cell, after = cell[rows, pairs], np.modf(x[rows, pairs])[0]  # x − i
        fall = (np.abs(_STEPS - after[:, None, :]) * self.slope[pairs]).sum(axis=2)  # (H, 4)
        return rows, pairs, (self.flat[cell[:, None] + self.nodes[pairs]] - fall).max(axis=1)


_NONE = np.zeros(0, dtype=np.intp)
_NONE.setflags(write=False)


@functools.lru_cache(maxsize=64)
def _tables(meshes: tuple[MeshPair, ...]) -> _Tables:
    """The :class:`_Tables` of ``meshes``."""
    sizes = np.array([len(m._flat) for m in meshes])
    offset = np.cumsum(sizes) - sizes
    return _Tables(
        np.array([j for m in meshes for j in m.joints]),
        np.array([[len(m.distance) / (2 * math.pi)] for m in meshes]),
        np.array([len(m.distance) + 2 for m in meshes]),
        offset,
        np.concatenate([m._floor for m in meshes]),
        np.concatenate([m._flat for m in meshes]),
        np.array([m._nodes for m in meshes]),
        np.array([m._slope()[None] for m in meshes]),
        np.array([m.reach for m in meshes]),
    )


@dataclass(frozen=True, eq=False)
class SphereModel:
    """Spheres fixed in the frames of an arm, and the sphere pairs self-collision tests.

    Attributes
    ----------
    robot : Robot
        The arm whose frames place the spheres.
    frames : ndarray, shape (S,)
        The frame of each sphere: 0 … 6 (DH frames, as :func:`urkin.fk_frames` numbers them)
        or 7 (:data:`TOOL_FRAME`).
    centres : ndarray, shape (S, 3)
        Each centre in its frame, metres.
    radii : ndarray, shape (S,)
        Radii, metres.
    pairs : ndarray, shape (P, 2)
        Sphere indices ``(i, j)``, ``i < j``, tested for self-collision.
    names : tuple of str
        A label per sphere, e.g. ``"forearm sphere 2"`` (numbered within its frame or group).
    source : str
        Where the spheres come from.
    meshes : tuple of MeshPair
        Pairs of links whose self-collision is tested on their tabulated meshes instead of
        their spheres (the fitted models' forearm and wrist 2; empty for hand-built models).
    """

    robot: Robot
    frames: np.ndarray
    centres: np.ndarray
    radii: np.ndarray
    pairs: np.ndarray
    names: tuple[str, ...]
    source: str = ""
    meshes: tuple[MeshPair, ...] = ()
    _moving: np.ndarray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        # read-only copies, checked: the constructor is public (from_rows is the friendly way)
        object.__setattr__(self, "robot", check_robot(self.robot))
        frames = real(self.frames, "frames")
        if frames.ndim != 1 or not len(frames):
            raise ValueError(f"frames must have shape (S,), S ≥ 1; got shape {frames.shape}")
        centres, radii = real(self.centres, "centres"), real(self.radii, "radii")
        if centres.shape != (len(frames), 3) or radii.shape != (len(frames),):
            raise ValueError(
                f"centres and radii must have shapes ({len(frames)}, 3) and ({len(frames)},), "
                f"one row per frame; got {centres.shape} and {radii.shape}"
            )
        _check_spheres(frames, centres, radii, lambda k: f"sphere {k}")
        names = self.names
        if (
            isinstance(names, (str, bytes))
            or not isinstance(names, Sequence)
            or not all(isinstance(name, str) for name in names)
        ):
            raise TypeError(f"names must be a list of strings, one per sphere; got {names!r:.60}")
        if len(names) != len(frames):
            raise ValueError(f"names holds {len(names)} labels for {len(frames)} spheres")
        if not isinstance(self.source, str):
            raise TypeError(f"source must be a str; got {type(self.source).__name__}")
        if not isinstance(self.meshes, tuple) or not all(
            isinstance(m, MeshPair) for m in self.meshes
        ):
            raise TypeError("meshes must be a tuple of planning.MeshPair (from sphere_model)")
        for name, value in (
            ("frames", frames.astype(np.intp)),
            ("centres", centres),
            ("radii", radii),
            ("pairs", _checked_pairs(self.pairs, len(frames))),
        ):
            value = np.array(value)  # a copy: the caller's array stays the caller's
            value.setflags(write=False)
            object.__setattr__(self, name, value)
        object.__setattr__(self, "names", tuple(names))
        moving = np.flatnonzero(self.frames > 0)  # the base's spheres never move
        moving.setflags(write=False)
        object.__setattr__(self, "_moving", moving)

    def __len__(self) -> int:
        return len(self.radii)

    def __repr__(self) -> str:
        return (
            f"SphereModel({self.robot.name}: {len(self)} spheres, {len(self.pairs)} "
            "self-collision pairs)"
        )

    @classmethod
    def from_rows(
        cls,
        robot: Robot,
        rows: ArrayLike,
        pairs: ArrayLike | str = "derive",
        *,
        names: Sequence[str] | None = None,
        source: str = "built by hand",
    ) -> SphereModel:
        """A model from rows ``(frame, x, y, z, radius)``.

        Parameters
        ----------
        robot : Robot
        rows : array_like, shape (S, 5)
            Per sphere: the frame it is fixed in (0 … 6, or 7 for the tool frame; an integer),
            its centre in that frame and its radius (metres, > 0).
        pairs : (P, 2) array_like of sphere indices, or "derive"
            The self-collision pairs, or ``"derive"`` for :func:`self_pairs`'s rule.
        names : sequence of str, optional
            A label per sphere (default: ``"<frame name> sphere <k>"``).
        source : str
            Provenance, shown in reports.

        Examples
        --------
        >>> import urkin
        >>> from urkin import planning
        >>> ur5 = urkin.robot("ur5")
        >>> stick = planning.SphereModel.from_rows(ur5, [[3, 0.2, 0, 0, 0.05], [6, 0, 0, 0, 0.04]])
        >>> stick.names
        ('forearm sphere 0', 'wrist 3 sphere 0')
        """
        robot = check_robot(robot)
        table = real(rows, "rows")
        if table.ndim != 2 or table.shape[1] != 5 or len(table) == 0:
            raise ValueError(
                "rows must have shape (S, 5), one (frame, x, y, z, radius) per sphere; got "
                f"shape {table.shape}"
            )
        frames, radii = table[:, 0], table[:, 4].copy()
        _check_spheres(frames, table[:, 1:4], radii, lambda k: f"rows[{k}]")
        frames = frames.astype(np.intp)
        model = cls(
            robot,
            frames,
            table[:, 1:4],
            radii,
            np.zeros((0, 2), dtype=np.intp),
            _default_names(frames) if names is None else names,
            source,
        )
        return model.with_pairs(pairs)

    def with_pairs(self, pairs: ArrayLike | str = "derive") -> SphereModel:
        """This model with other self-collision pairs (``"derive"``: :func:`self_pairs`); they
        are all its self-collision tests (a fitted model's tabulated :attr:`meshes` are
        dropped)."""
        if isinstance(pairs, str):
            if pairs != "derive":
                raise ValueError(f"pairs must be an (P, 2) array or 'derive'; got {pairs!r}")
            chosen = self_pairs(self)
        else:
            chosen = np.unique(np.sort(_checked_pairs(pairs, len(self)), axis=1), axis=0)
        return SphereModel(
            self.robot, self.frames, self.centres, self.radii, chosen, self.names, self.source
        )

    def with_tool_spheres(
        self, centres: ArrayLike, radii: ArrayLike, name: str = "tool"
    ) -> SphereModel:
        """This model with extra spheres fixed in the tool frame (a gripper, a held object).

        The new spheres' self-collision pairs follow :func:`self_pairs`'s rule (the old pairs
        are kept).

        Parameters
        ----------
        centres : array_like, shape (K, 3)
            Centres in the tool frame (the flange when the robot has no tool), metres.
        radii : array_like, shape (K,) or float
            Radii, metres.
        name : str
            Label of the group: the spheres are named ``"<name> sphere <k>"``.

        Returns
        -------
        SphereModel
        """
        c = real(centres, "centres")
        c = c[None] if c.ndim == 1 else c
        if c.ndim != 2 or c.shape[1] != 3 or len(c) == 0:
            raise ValueError(f"centres must have shape (K, 3); got shape {np.shape(centres)}")
        if np.abs(c).max(initial=0.0) > _MAX_OFFSET:
            raise ValueError(
                f"centres must lie within {_MAX_OFFSET:g} m of the tool frame (metres); got "
                f"{np.abs(c).max():g}"
            )
        r = real(radii, "radii")
        if r.ndim > 1 or (r.ndim == 1 and len(r) not in (1, len(c))):
            raise ValueError(
                f"radii must be one radius or one per centre ({len(c)}); got shape {r.shape}"
            )
        r = np.broadcast_to(r, (len(c),)).astype(float)
        _name_of_group(name)
        bad = np.flatnonzero(~((r > 0) & (r <= _MAX_RADIUS)))
        if len(bad):
            raise ValueError(
                f"radii[{bad[0]}] must be positive and at most {_MAX_RADIUS:g} m (metres); got "
                f"{r[bad[0]]:g}"
            )
        rows = np.column_stack([np.full(len(c), TOOL_FRAME), c, r])
        extra = SphereModel.from_rows(self.robot, rows, pairs=np.zeros((0, 2), dtype=np.intp))
        names = self.names + tuple(f"{name} sphere {k}" for k in range(len(c)))
        merged = SphereModel(
            self.robot,
            np.concatenate([self.frames, extra.frames]),
            np.concatenate([self.centres, extra.centres]),
            np.concatenate([self.radii, extra.radii]),
            self.pairs,
            names,
            self.source + f"; {len(c)} {name} spheres",
        )
        new = self_pairs(merged, only=np.arange(len(self), len(merged)))
        return SphereModel(
            merged.robot,
            merged.frames,
            merged.centres,
            merged.radii,
            np.concatenate([self.pairs, new]).astype(np.intp),
            merged.names,
            merged.source,
            self.meshes,
        )

    def place(self, q: ArrayLike) -> np.ndarray:
        """World (base-frame) centres of every sphere at joint angles ``q``.

        Complex ``q`` gives complex centres (:func:`urkin.fk`'s complex-step support: the
        imaginary parts of ``place(q + 1e-20j · dq) / 1e-20`` are the centres' velocities);
        the collision checks take real configurations only.

        Returns
        -------
        ndarray, shape (S, 3) for q (6,), or (..., S, 3) for q (..., 6)
        """
        frames = frames_with_tool(self.robot, q)
        R = frames[..., self.frames, :3, :3]
        p = frames[..., :3, 3][..., self.frames, :]
        return np.einsum("...sij,sj->...si", R, self.centres) + p


def frames_with_tool(robot: Robot, q: ArrayLike) -> np.ndarray:
    """:func:`urkin.fk_frames` with the tool frame appended: (..., 8, 4, 4)."""
    frames = fk_frames(robot, q)
    tool = frames[..., 6:7, :, :] @ robot.tool
    return np.concatenate([frames, tool], axis=-3)


def _frames(robot: Robot, Q: np.ndarray) -> np.ndarray:
    """:func:`frames_with_tool` of checked configurations ``Q`` (N, 6), for collision checks.

    Stacks of the sizes collision checks mostly see (``_CHAIN``) are computed as the partial
    products of their DH link transforms, base to tool: six batched 4×4 products and a dozen
    array operations, where the generated code makes about a hundred.  Fewer configurations are
    written by the generated one-pose code straight into the stack, then moved by the base
    and given the tool in two products (a plain arm's tool frame is a copy of its flange's)."""
    n = len(Q)
    if _CHAIN[0] <= n <= _CHAIN[1]:
        return _chain(robot, Q)
    if n < _CHAIN[0]:  # the generated one-pose code, straight into the stack
        out = np.empty((n, 8, 4, 4))
        lengths = robot.lengths
        for i, row in enumerate(Q.tolist()):
            _gen.frames_one(row, lengths, out, i * _FRAMES_BYTES)
        if robot._plain:
            out[:, 7] = out[:, 6]  # a plain arm's tool frame is its flange
        else:
            np.matmul(robot.base, out[:, :7], out=out[:, :7])  # numpy buffers the overlap
            np.matmul(out[:, 6], robot.tool, out=out[:, 7])
        return out
    return frames_with_tool(robot, Q)


#: Bytes of one configuration's eight frames.
_FRAMES_BYTES = 8 * 16 * 8


#: Stack sizes for which :func:`_frames` multiplies link transforms (measured: the generated
#: code is faster for up to five configurations, and again from about 300 on an AVX2 machine
#: and 500 on an AVX-512 one, where the products' temporaries outgrow the cache).
_CHAIN = (6, 256)


def _chain(robot: Robot, Q: np.ndarray) -> np.ndarray:
    """Frames 0 … 6 and the tool frame of checked configurations ``Q`` (N, 6): (N, 8, 4, 4)."""
    n = len(Q)
    cos, sin, constant = _link_terms(robot)
    A = np.cos(Q)[..., None] * cos  # T_{i-1,i} = Rz(θ) Tz(d) Tx(a) Rx(α), i = 1 … 6
    A += np.sin(Q)[..., None] * sin
    A += constant
    A = A.reshape(n, 6, 4, 4)
    out = np.empty((n, 8, 4, 4))
    out[:, 0] = robot.base
    np.matmul(robot.base, A[:, 0], out=out[:, 1])
    for i in range(1, 6):  # the six joints
        np.matmul(out[:, i], A[:, i], out=out[:, i + 1])
    np.matmul(out[:, 6], robot.tool, out=out[:, 7])
    return out


def _placing_matrix(frames: np.ndarray, centres: np.ndarray) -> np.ndarray:
    """(128, 3k): row ``16 f + 4 i + j`` of column ``3 m + i`` is the homogeneous centre's
    ``j``-th coordinate for a centre ``m`` fixed in frame ``f``, so that the flattened frames
    times it are the centres' coordinates ``i``."""
    k = len(frames)
    M = np.zeros((8, 4, 4, k, 3))  # frame, row i, column j, centre, coordinate
    homogeneous = np.column_stack([centres, np.ones(k)])
    for i in range(3):
        M[frames, i, :, np.arange(k), i] = homogeneous
    return M.reshape(128, 3 * k)


@functools.lru_cache(maxsize=64)
def _link_terms(robot: Robot) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A DH link transform is linear in cos θ and sin θ: ``cos θ · C + sin θ · S + K``; the
    (6, 16) matrices C, S and K of the six links (cos α and sin α of UR twists are 0 or ±1,
    exact as in the generated code)."""
    ca, sa = np.round(np.cos(robot.alpha)), np.round(np.sin(robot.alpha))
    one, zero = np.ones(6), np.zeros(6)
    cos = np.stack([one, zero, zero, robot.a, zero, ca, -sa, zero], axis=1)
    sin = np.stack([zero, -ca, sa, zero, one, zero, zero, robot.a], axis=1)
    constant = np.stack([zero, sa, ca, robot.d, zero, zero, zero, one], axis=1)
    pad = np.zeros((6, 8))
    terms = (np.hstack([cos, pad]), np.hstack([sin, pad]), np.hstack([pad, constant]))
    for term in terms:
        term.setflags(write=False)
    return terms


def _default_names(frames: Iterable[int]) -> tuple[str, ...]:
    counts: dict[int, int] = {}
    names = []
    for frame in frames:
        k = counts.get(int(frame), 0)
        counts[int(frame)] = k + 1
        names.append(f"{FRAME_NAMES[int(frame)]} sphere {k}")
    return tuple(names)


def _check_model(model: SphereModel) -> None:
    """A TypeError unless ``model`` is a :class:`SphereModel`."""
    if not isinstance(model, SphereModel):
        raise TypeError(
            "model must be a planning.SphereModel, e.g. planning.sphere_model(urkin.robot('ur5')); "
            f"got {type(model).__name__}"
        )


#: How far from its frame's origin a sphere's centre may be (m): no arm link reaches further;
#: and the largest radius (m).
_MAX_OFFSET, _MAX_RADIUS = 5.0, 2.0


def _check_spheres(frames: np.ndarray, centres: np.ndarray, radii: np.ndarray, label) -> None:
    """A ValueError, for the first sphere ``k`` at fault named ``label(k)``, unless every frame
    is an integer 0 … 7, every centre within :data:`_MAX_OFFSET` of its frame and every radius
    in (0, :data:`_MAX_RADIUS`] (metres)."""
    odd = np.flatnonzero((frames != np.round(frames)) | (frames < 0) | (frames > TOOL_FRAME))
    if len(odd):
        raise ValueError(
            f"{label(odd[0])}: the frame must be an integer 0 … 7 (DH frames 0 … 6, 7 the tool "
            f"frame); got {frames[odd[0]]:g}"
        )
    far = np.flatnonzero(np.abs(centres).max(axis=1) > _MAX_OFFSET)
    if len(far):
        raise ValueError(
            f"{label(far[0])}: the centre must lie within {_MAX_OFFSET:g} m of its frame (the "
            f"coordinates are in metres); got {centres[far[0]].tolist()}"
        )
    bad = np.flatnonzero(~((radii > 0) & (radii <= _MAX_RADIUS)))
    if len(bad):
        raise ValueError(
            f"{label(bad[0])}: the radius must be positive and at most {_MAX_RADIUS:g} m "
            f"(metres); got {radii[bad[0]]:g}"
        )


def _checked_pairs(pairs: ArrayLike, count: int) -> np.ndarray:
    """``pairs`` as (P, 2) sphere indices among ``count`` spheres, or a ValueError naming it."""
    try:
        chosen = np.asarray(pairs)
    except ValueError:  # ragged
        chosen = np.zeros((1, 3))  # refused below
    if chosen.size == 0 and chosen.ndim <= 2:
        return np.zeros((0, 2), dtype=np.intp)
    if chosen.ndim != 2 or chosen.shape[1] != 2 or chosen.dtype.kind not in "iu":
        raise ValueError(f"pairs must be integer sphere indices of shape (P, 2); got {pairs!r:.60}")
    if np.any(chosen < 0) or np.any(chosen >= count) or np.any(chosen[:, 0] == chosen[:, 1]):
        raise ValueError(f"pairs must name two different spheres among 0 … {count - 1}")
    return chosen.astype(np.intp)


def _name_of_group(name: object) -> None:
    if not isinstance(name, str):
        raise TypeError(f"name must be a str (the group's label); got {type(name).__name__}")


def self_pairs(model: SphereModel, only: ArrayLike | None = None) -> np.ndarray:
    """The self-collision pairs of ``model`` by the stated rule (module notes).

    Parameters
    ----------
    model : SphereModel
    only : array_like of int, optional
        Derive only the pairs that involve these spheres (the others are not returned).

    Returns
    -------
    ndarray, shape (P, 2)
        Sphere indices ``(i, j)``, ``i < j``.
    """
    _check_model(model)
    link = np.minimum(model.frames, 6)  # the tool frame moves with link 6
    i, j = np.triu_indices(len(model), k=1)
    keep = np.abs(link[i] - link[j]) >= 2
    if only is not None:
        picked = np.asarray(only)
        if picked.ndim > 1 or (picked.size and picked.dtype.kind not in "iu"):
            raise ValueError(f"only must be sphere indices, a list of integers; got {only!r:.60}")
        picked = picked.astype(np.intp)
        if np.any((picked < 0) | (picked >= len(model))):
            raise ValueError(
                f"only must hold sphere indices from 0 to {len(model) - 1}; got {only!r:.60}"
            )
        chosen = np.zeros(len(model), dtype=bool)
        chosen[picked] = True
        keep &= chosen[i] | chosen[j]
    i, j = i[keep], j[keep]
    if len(i) == 0:
        return np.zeros((0, 2), dtype=np.intp)
    near, apart = _contacts(model, i, j)
    rule = near & apart  # within the margin sometimes, and not always overlapping
    return np.column_stack([i[rule], j[rule]]).astype(np.intp)


def _contacts(model: SphereModel, i: np.ndarray, j: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Over the rule's random configurations: whether each pair ever came within the margin,
    and whether it was ever apart.  Found in the arm's base frame (where it stands does not
    change the distances), and kept for the same pairs of the same spheres on the same arm
    and tool (a world rebuilt, a block carried again)."""
    robot = model.robot
    used, index = np.unique(np.concatenate([i, j]), return_inverse=True)
    arm = _Arm(
        (robot.dh_table().tobytes(), robot.tool.tobytes(), robot.joint_limits),
        robot.with_base(np.eye(4)),
    )
    near, apart = _pair_contacts(
        arm,
        model.frames[used].astype(np.intp).tobytes(),
        model.centres[used].tobytes(),
        model.radii[used].tobytes(),
        index.astype(np.intp).tobytes(),
    )
    return near.copy(), apart.copy()


@dataclass(frozen=True)
class _Arm:
    """An arm standing at the origin, equal to another with the same DH table, tool and
    joint limits (``key``): :func:`_pair_contacts`' cache key."""

    key: tuple
    robot: Robot = field(compare=False)


@functools.lru_cache(maxsize=64)
def _pair_contacts(
    arm: _Arm, frames: bytes, centres: bytes, radii: bytes, ends: bytes
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_contacts` of the spheres ``frames``, ``centres`` and ``radii`` (as bytes) and the
    pairs ``ends`` (their indices among them, all firsts then all seconds).  Only these
    spheres are placed, one matrix product per block of configurations, and a pair found both
    near and apart is settled: the later blocks test only the others."""
    frame = np.frombuffer(frames, dtype=np.intp)
    centre = np.frombuffer(centres).reshape(-1, 3)
    radius = np.frombuffer(radii)
    first, second = np.frombuffer(ends, dtype=np.intp).reshape(2, -1)
    robot = arm.robot
    rng = np.random.default_rng(_PAIR_SEED)
    near = np.zeros(len(first), dtype=bool)
    apart = np.zeros(len(first), dtype=bool)
    reach = radius[first] + radius[second]
    within2, touch2 = (reach + _PAIR_MARGIN) ** 2, reach**2
    place = _placing_matrix(frame, centre)
    open_ = np.arange(len(first))
    for _ in range(_PAIR_SAMPLES // 2000):
        if not len(open_):
            break  # every pair settled
        Q = random_configurations(robot, 2000, rng)
        W = (_chain(robot, Q).reshape(len(Q), 128) @ place).reshape(len(Q), -1, 3)
        d = W[:, first[open_]] - W[:, second[open_]]
        d2 = np.einsum("nki,nki->nk", d, d)
        near[open_] |= np.any(d2 <= within2[open_], axis=0)
        apart[open_] |= np.any(d2 > touch2[open_], axis=0)
        open_ = open_[~(near[open_] & apart[open_])]
    near.setflags(write=False)
    apart.setflags(write=False)
    return near, apart


@functools.lru_cache(maxsize=16)
def _fitted(name: str) -> SphereModel:
    arm = _robot_by_name(name)
    pairs = _mesh_pairs(name.lower())
    rows = list(FITTED[name.lower()])
    frames = np.array([row[0] for row in rows])
    extra = []  # what a table leaves out: its spheres against the first link's spheres
    for pair in pairs:
        for sphere in pair.spheres:
            extra.extend((i, len(rows)) for i in np.flatnonzero(frames == pair.frames[0]))
            rows.append((pair.frames[1], *sphere))
    model = SphereModel.from_rows(
        arm,
        rows,
        pairs=PAIRS[name.lower()],
        source=(
            f"fitted to the ROS-Industrial {arm.name} collision meshes (urkin.planning.spheres)"
        ),
    )
    on = np.sort(model.frames[model.pairs], axis=1)
    tabled = np.zeros(len(model.pairs), dtype=bool)  # tested on the meshes now
    for pair in pairs:
        tabled |= np.all(on == pair.frames, axis=1)
    extra = np.array(extra, dtype=np.intp).reshape(-1, 2)
    if len(extra):  # those that can meet, by the rule of hand-built models (module notes)
        near, apart = _contacts(model, extra[:, 0], extra[:, 1])
        extra = extra[near & apart]
    links = ", ".join(
        f"the {FRAME_NAMES[a]} and {FRAME_NAMES[b]}" for a, b in (p.frames for p in pairs)
    )
    return SphereModel(
        arm,
        model.frames,
        model.centres,
        model.radii,
        np.concatenate([model.pairs[~tabled], extra]),
        model.names,
        model.source + f"; {links} tested on their tabulated meshes",
        pairs,
    )


@functools.cache
def _mesh_pairs(name: str) -> tuple[MeshPair, ...]:
    from urkin.planning._pair_tables import NPZ

    with np.load(io.BytesIO(base64.b64decode(NPZ))) as data:
        unit = float(data["unit"])
        pairs = []
        for a, b in data["links"]:
            key = f"{name}_{a}{b}"
            distance = data[f"{key}_distance"].astype(float) * unit
            reach = data[f"{key}_reach"].astype(float)
            spheres = data[f"{key}_spheres"].astype(float)
            pairs.append(MeshPair((int(a), int(b)), distance, reach, spheres))
    return tuple(pairs)


def sphere_model(robot: Robot) -> SphereModel:
    """The fitted sphere model of a UR3, UR5 or UR10, tested to cover its collision meshes.

    Parameters
    ----------
    robot : Robot
        ``urkin.robot("ur3")``, ``("ur5")`` or ``("ur10")``, with any base and tool (the
        spheres follow the DH frames, so they move with the base).

    Returns
    -------
    SphereModel
        With the self-collision pairs of the stated rule (module notes).

    Raises
    ------
    ValueError
        For an arm without published collision meshes here (the e-series), or whose DH
        lengths differ from the model's: build one with :meth:`SphereModel.from_rows`.

    Examples
    --------
    >>> import urkin
    >>> from urkin import planning
    >>> model = planning.sphere_model(urkin.robot("ur5"))
    >>> model.place([0, -1.57, 0, -1.57, 0, 0]).shape == (len(model), 3)
    True
    """
    robot = check_robot(robot)
    key = robot.name.lower()
    if key not in FITTED:
        raise ValueError(
            f"no fitted sphere model for the {robot.name}: the collision meshes it would be "
            f"fitted to exist for {', '.join(k.upper() for k in FITTED)}; build one with "
            "planning.SphereModel.from_rows(robot, rows)"
        )
    model = _fitted(key)
    if robot.lengths != model.robot.lengths:
        raise ValueError(
            f"robot has DH lengths {robot.lengths}, not the {model.robot.name}'s "
            f"{model.robot.lengths} that its sphere model was fitted to"
        )
    if robot is model.robot:
        return model
    return SphereModel(
        robot,
        model.frames,
        model.centres,
        model.radii,
        model.pairs,
        model.names,
        model.source,
        model.meshes,
    )
