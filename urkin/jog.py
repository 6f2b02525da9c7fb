"""Jogging a UR arm: a widget-free controller, a Jupyter panel and a desktop window over it.

Seed 000's UR3 jog panel moves the flange 2 cm along a base axis per button (orientation held),
goes home, and runs a circle and a square; it overwrites the joint state even when its solver
fails.  Here the logic is a plain object that tests drive, and the state only ever changes to a
configuration that was verified to reach its target:

:class:`JogController`
    ``press("X+")`` … ``press("Z-")``, :meth:`~JogController.home` and
    :meth:`~JogController.run` (``"circle"``, ``"square"``).  Each returns a :class:`JogStep`
    (new ``q``, ``ok``, a ``status`` line, the configurations passed through).  A press is solved
    with the closed form (:func:`urkin.ik_closest`, the solution nearest the current
    configuration); it is refused, and the arm stays put, when the target is out of reach, when
    a joint would have to wind past its limit or jump (a flip through a singularity), or when a
    joint would go below the mounting plane.  Paths are followed with
    :func:`urkin.tracking.track` and stop at the last sample reached.
:func:`jog_panel`
    The ipywidgets panel (buttons X±, Y±, Z±, Home, Circle, Square, a step slider, a status
    line and a figure); outside a live kernel it shows a recorded animation of the session.
:func:`demo_figure`
    The same buttons as a matplotlib window (``urkin demo``).

Only numpy is imported with this module; matplotlib and ipywidgets are imported by the functions
that draw.  Lengths are metres, angles radians.

Examples
--------
>>> import urkin
>>> jog = JogController(urkin.robot("UR3"))
>>> print(jog.press("X+").status)
X+: moved to x 0.270 y 0.100 z 0.300 m
>>> print(jog.press("z-").status)
Z-: moved to x 0.270 y 0.100 z 0.280 m
>>> jog.trail.shape  # the start, then one configuration per press
(3, 6)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from urkin._inputs import real
from urkin.analytic_ik import ik_analytic, ik_closest
from urkin.kinematics import fk, fk_frames, singularity_factors
from urkin.robots import Robot, check_robot
from urkin.trajectory import (
    PLANES,
    circle,
    joint_trajectory,
    pose_path,
    square,
    time_scaling,
    track,
)
from urkin.transforms import make_transform, wrap_angles

__all__ = [
    "ACTIONS",
    "KEYS",
    "JogController",
    "JogFigure",
    "JogPanel",
    "JogStep",
    "demo_figure",
    "draw_session",
    "home_configuration",
    "jog_panel",
    "parse_script",
]

#: The jog keys: a step of ``controller.step`` along a base axis, orientation held.
KEYS = ("X+", "X-", "Y+", "Y-", "Z+", "Z-")
#: Everything :meth:`JogController.do` accepts (case-insensitive): the keys, then the moves.
ACTIONS = (*KEYS, "home", "circle", "square")

#: Largest joint step (rad) between two samples of a joint-space move (home, approaching a path):
#: enough samples for a smooth animation.
JOINT_MOVE_STEP = 0.02
#: Sampling step (m) of the circle and the square.
PATH_STEP = 1e-3

_AXES = {"X": 0, "Y": 1, "Z": 2}


def _where(T: np.ndarray) -> str:
    """``x 0.270 y 0.100 z 0.300 m``: a position to the millimetre, independent of round-off.

    Rounding first to 1e-9 m makes values that differ only by round-off (0.2699999999999 and
    0.2700000000001) print alike; ``+ 0.0`` turns −0.0 into 0.0.
    """
    x, y, z = np.round(np.round(T[:3, 3], 9), 3) + 0.0
    return f"x {x:.3f} y {y:.3f} z {z:.3f} m"


def _plain(robot: Robot) -> Robot:
    """The same arm without base or tool transform: its frames are in DH frame 0."""
    return robot if robot.has_identity_frames else replace(robot, base=None, tool=None)


def _heights(robot: Robot, q: np.ndarray) -> np.ndarray:
    """Heights (m) of the origins of DH frames 1-6 above the mounting plane, (..., 6)."""
    return fk_frames(_plain(robot), q)[..., 1:, 2, 3]


def _below_plane(robot: Robot, qs: np.ndarray) -> tuple[int, int, float] | None:
    """The first configuration of ``qs`` (K, 6) with a joint below the mounting plane, as
    (row, DH frame 1-6, height in m), or None."""
    if len(qs) == 0:
        return None
    heights = _heights(robot, qs)
    bad = np.flatnonzero((heights < 0.0).any(axis=1))
    if len(bad) == 0:
        return None
    row = int(bad[0])
    frame = int(np.argmin(heights[row]))
    return row, frame + 1, float(heights[row, frame])


def _elbow_up(robot: Robot, q: np.ndarray) -> np.ndarray:
    """Whether the elbow (origin of DH frame 2) is more than 1 nm above the straight line from
    the shoulder (frame 1) to the wrist (frame 3), for configurations (N, 6)."""
    points = fk_frames(_plain(robot), q)[..., 1:4, :3, 3]
    s, e, w = points[..., 0, :], points[..., 1, :], points[..., 2, :]
    d = w - s
    t = np.einsum("...i,...i->...", e - s, d) / np.einsum("...i,...i->...", d, d)
    offset = e - (s + t[..., None] * d)
    return offset[..., 2] > 1e-9


def home_configuration(
    robot: Robot, position: ArrayLike = (0.25, 0.1, 0.3), R: ArrayLike | None = None
) -> np.ndarray:
    """An elbow-up configuration that puts the tool at ``position`` with orientation ``R``.

    The candidates are the closed-form solutions (:func:`urkin.ik_analytic`) whose elbow (the
    origin of DH frame 2) lies above the straight line from the shoulder (frame 1) to the wrist
    (frame 3), and whose DH frame origins 1-6 all lie above the mounting plane ``z = 0`` (the
    ``below_base`` of :func:`urkin.tracking_report.tracking_report`).  Among them, the one on the
    branch of UR's usual ready pose ``[0, −90°, 90°, −90°, −90°, 0]`` is preferred: shoulder
    factor ``a2 c2 + a3 c23 + d5 s234 < 0`` and ``sin q5 < 0`` (the branch signs of
    :func:`urkin.kinematics.singularity_factors`), then any other, in the closed form's branch
    order.  The choice depends on signs, not on comparing nearly equal numbers, so it does not
    change with round-off (except exactly at a singularity).

    For seed 000's UR3 at (0.25, 0.1, 0.3) m with identity orientation this is the solution
    with the shoulder facing the target, elbow bent up by ``q3 ≈ 85°`` (``|sin q3| ≈ 0.997``,
    far from the elbow singularity) and the wrist at ``q5 = −90°``: the circle and the square of
    the demo are followed from it without a branch change, every joint at least 0.118 m above
    the mounting plane (seed 000 started from the triply singular ``[0, −π/2, 0, −π/2, 0, 0]``
    and ended with the elbow 80 mm below it).

    Parameters
    ----------
    robot : Robot
    position : array_like, shape (3,)
        Where the tool should be (m), in the robot's base (or world) frame.
    R : array_like, shape (3, 3), optional
        The tool's orientation (default: the identity, as seed 000).

    Returns
    -------
    ndarray, shape (6,)
        Joint angles (rad), wrapped to (−π, π].

    Raises
    ------
    ValueError
        When no closed-form solution is elbow up with every joint above the mounting plane.

    Examples
    --------
    >>> import urkin
    >>> ur3 = urkin.robot("UR3")
    >>> q = home_configuration(ur3)
    >>> bool(np.abs(urkin.fk(ur3, q)[:3, 3] - [0.25, 0.1, 0.3]).max() < 1e-12)
    True
    >>> np.sign(urkin.kinematics.singularity_factors(ur3, q))  # shoulder, elbow, wrist
    array([-1.,  1., -1.])
    """
    robot = check_robot(robot)
    p = real(position, "position")
    if p.shape != (3,):
        raise ValueError(f"position must be a point (x, y, z) in metres, shape (3,); got {p.shape}")
    T = make_transform(R=np.eye(3) if R is None else R, p=p)
    solutions = ik_analytic(robot, T)
    if len(solutions) == 0:
        raise ValueError(
            f"no configuration of the {robot.name} reaches position {tuple(p.tolist())} m with "
            "this orientation; choose another position (center) or pass q0"
        )
    good = _elbow_up(robot, solutions) & (_heights(robot, solutions) > 0.0).all(axis=1)
    if not good.any():
        raise ValueError(
            f"none of the {len(solutions)} configurations of the {robot.name} that reach "
            f"position {tuple(p.tolist())} m is elbow up with every joint above the mounting "
            "plane; choose another position (center) or pass q0"
        )
    factors = singularity_factors(robot, solutions)
    # preference: UR's usual branch (shoulder factor < 0, sin q5 < 0) first, then row order
    rank = 2 * (factors[:, 0] >= 0) + (factors[:, 2] >= 0)
    rank = np.where(good, rank, 4)
    return solutions[int(np.argmin(rank))].copy()


@dataclass(frozen=True, eq=False)
class JogStep:
    """What one press, home or run did.

    Attributes
    ----------
    q : ndarray, shape (6,)
        The configuration after the step (rad): the new one, or the old one if it was refused.
    ok : bool
        Whether the step did all it was asked (a path that stopped part way is not ok).
    status : str
        One line saying what happened: where the tool is now, or why the arm did not move.
    qs : ndarray, shape (K, 6)
        The configurations passed through, in order, ending with ``q``: one row for a press,
        a joint-space move and a path's samples for a run, none when nothing moved.
    action : str
        What was asked (``"X+"``, ``"home"``, ``"circle"`` …).
    """

    q: np.ndarray
    ok: bool
    status: str
    qs: np.ndarray
    action: str = ""


def _number(value: Any, name: str) -> float:
    """One finite number > 0, or an error naming ``name``."""
    array = real(value, name)
    if array.ndim != 0 or not array > 0:
        raise ValueError(f"{name} must be one number > 0; got {value!r}")
    return float(array)


class JogController:
    """The state of a jogged arm and the moves that change it, without any widgets.

    Parameters
    ----------
    robot : Robot
    q0 : array_like, shape (6,), optional
        Start (and home) configuration (rad), within the robot's joint limits.  Default
        :func:`home_configuration` at ``center``: elbow up, the tool at the centre of the
        circle and the square with the identity orientation.
    step : float
        Length of a press (m), > 0; seed 000's 2 cm by default.
    center : array_like, shape (3,)
        Centre of the circle and of the square (m).
    radius : float
        Radius of the circle (m).
    side : float
        Side of the square (m).
    plane : {"xy", "yz", "zx"}
        Plane of the circle and the square (see :func:`urkin.trajectory.circle`).
    max_jump : float
        Largest change of any joint (rad) allowed for one press, and between two samples of a
        path: a larger one is a flip through a singularity (or a joint winding round), and is
        refused.  0.5 rad is far more than a 2 cm press needs away from singularities; raise it
        for long steps.

    Attributes
    ----------
    robot : Robot
    q0 : ndarray, shape (6,)
        The home configuration.
    history : list of JogStep
        Every step so far, refused ones too.

    Examples
    --------
    >>> import urkin
    >>> jog = JogController(urkin.robot("UR3"), step=0.05)
    >>> print(jog.press("Y-").status)
    Y-: moved to x 0.250 y 0.050 z 0.300 m
    >>> jog.step = 1.0
    >>> result = jog.press("X+")  # 1 m further: out of reach, the arm stays put
    >>> result.ok, result.qs.shape
    (False, (0, 6))
    >>> print(result.status)
    X+: IK failed: unreachable: the target is 0.6548 m beyond the UR3's reach (its wrist point is 1.2527 m from the shoulder; at most 0.5980 m is reachable); staying put
    >>> print(jog.run("circle").status)
    circle: a joint move of 54 steps to the start, then 630 samples round the circle; at x 0.250 y 0.200 z 0.300 m
    >>> print(jog.home().status)
    home: moved to x 0.250 y 0.100 z 0.300 m
    """  # noqa: E501

    def __init__(
        self,
        robot: Robot,
        q0: ArrayLike | None = None,
        step: float = 0.02,
        center: ArrayLike = (0.25, 0.1, 0.3),
        radius: float = 0.1,
        side: float = 0.15,
        plane: str = "yz",
        *,
        max_jump: float = 0.5,
    ) -> None:
        self.robot = check_robot(robot)
        c = real(center, "center")
        if c.shape != (3,):
            raise ValueError(
                f"center must be a point (x, y, z) in metres, shape (3,); got {c.shape}"
            )
        self.center = c.copy()
        self.radius = _number(radius, "radius")
        self.side = _number(side, "side")
        if not isinstance(plane, str) or plane not in PLANES:
            raise ValueError(f"plane must be one of {', '.join(PLANES)}; got {plane!r}")
        self.plane = plane
        self.max_jump = _number(max_jump, "max_jump")
        self.step = step
        limits = np.array(self.robot.joint_limits)
        self._lower, self._upper = limits[:, 0], limits[:, 1]
        if q0 is None:
            start = home_configuration(self.robot, self.center)
        else:
            start = real(q0, "q0").copy()
            if start.shape != (6,):
                raise ValueError(f"q0 must be one configuration, shape (6,); got {start.shape}")
            outside = np.flatnonzero((start < self._lower) | (start > self._upper))
            if len(outside):
                j = int(outside[0])
                raise ValueError(
                    f"q0 is outside the {self.robot.name}'s joint limits: joint {j + 1} is "
                    f"{start[j]:.4f} rad, the limits are "
                    f"[{self._lower[j]:.4f}, {self._upper[j]:.4f}] rad"
                )
        start.setflags(write=False)
        self.q0: np.ndarray = start
        self._q = start
        self.history: list[JogStep] = []

    # ------------------------------------------------------------------------------ state

    @property
    def step(self) -> float:
        """Length of a press (m), > 0."""
        return self._step

    @step.setter
    def step(self, value: float) -> None:
        self._step = _number(value, "step")

    @property
    def q(self) -> np.ndarray:
        """The current configuration (rad), shape (6,) (a copy)."""
        return self._q.copy()

    @property
    def flange(self) -> np.ndarray:
        """The current tool pose (the flange unless the robot has a tool), shape (4, 4)."""
        return fk(self.robot, self._q)

    @property
    def trail(self) -> np.ndarray:
        """Every configuration passed through, in order, from the start: shape (N, 6)."""
        return np.concatenate([self.q0[None], *(s.qs for s in self.history)])

    @property
    def moves(self) -> int:
        """How many steps moved the arm."""
        return sum(len(s.qs) > 0 for s in self.history)

    def _record(self, action: str, ok: bool, status: str, qs: np.ndarray | None = None) -> JogStep:
        qs = np.empty((0, 6)) if qs is None else np.array(qs, dtype=float)
        if len(qs):
            self._q = qs[-1].copy()
            self._q.setflags(write=False)
        qs.setflags(write=False)
        result = JogStep(self.q, bool(ok), status, qs, action)
        self.history.append(result)
        return result

    # ------------------------------------------------------------------------------ moves

    def do(self, action: str) -> JogStep:
        """Do one of :data:`ACTIONS` by name (case-insensitive): a key, home, circle or square.

        Examples
        --------
        >>> import urkin
        >>> jog = JogController(urkin.robot("UR3"))
        >>> jog.do("Home").status
        'home: already there'
        """
        name = _action(action)
        if name in KEYS:
            return self.press(name)
        if name == "home":
            return self.home()
        return self.run(name)

    def press(self, key: str) -> JogStep:
        """Move the tool ``step`` along a base axis, orientation held; or refuse and stay put.

        The target is the current tool pose translated by ``±step`` along the x, y or z axis of
        the robot's base frame (its world frame if it has a base transform).  It is solved with
        :func:`urkin.ik_closest`: the closed-form solution nearest the current configuration,
        within the joint limits, verified to 1e-9 m and rad.  The arm moves only if that
        succeeds and the solution keeps every joint within ``max_jump`` of where it is (a larger
        change is a flip through a singularity, or a joint that would have to wind past its
        limit to follow) and every DH frame origin above the mounting plane.

        Parameters
        ----------
        key : {"X+", "X-", "Y+", "Y-", "Z+", "Z-"}
            Case-insensitive.

        Returns
        -------
        JogStep
            ``qs`` holds the new configuration, or nothing when the press was refused; the
            status says where the tool is, or why it did not move.

        Examples
        --------
        >>> import urkin
        >>> jog = JogController(urkin.robot("UR3"))
        >>> step = jog.press("y+")
        >>> step.ok, step.status, step.qs.shape
        (True, 'Y+: moved to x 0.250 y 0.120 z 0.300 m', (1, 6))
        """
        if not isinstance(key, str) or key.upper() not in KEYS:
            raise ValueError(f"key must be one of {', '.join(KEYS)}; got {key!r}")
        key = key.upper()
        T = self.flange
        T[_AXES[key[0]], 3] += self.step if key[1] == "+" else -self.step
        result = ik_closest(self.robot, T, self._q)
        if not result.success:
            return self._record(key, False, f"{key}: IK failed: {result.reason}; staying put")
        q = np.asarray(result.q, dtype=float)
        delta = q - self._q
        if np.abs(delta).max() > self.max_jump:
            why = self._why_jump(T, delta)
            return self._record(key, False, f"{key}: refused: {why}; staying put")
        below = _below_plane(self.robot, q[None])
        if below is not None:
            _, frame, height = below
            return self._record(
                key,
                False,
                f"{key}: refused: DH frame {frame} would go {-height * 1e3:.2g} mm below the "
                "mounting plane; staying put",
            )
        return self._record(key, True, f"{key}: moved to {_where(fk(self.robot, q))}", q[None])

    def _why_jump(self, T: np.ndarray, delta: np.ndarray) -> str:
        """Why the nearest solution within the limits, ``delta`` away, is too far for a press:
        the nearest solution regardless of limits would wind a joint past its limit, or every
        solution jumps (a flip through a singularity)."""
        solutions = ik_analytic(self.robot, T)
        continued = self._q + wrap_angles(solutions - self._q)
        nearest = continued[np.argmin(np.linalg.norm(continued - self._q, axis=1))]
        outside = np.flatnonzero((nearest < self._lower) | (nearest > self._upper))
        if len(outside) and np.abs(nearest - self._q).max() <= self.max_jump:
            j = int(outside[0])
            return (
                f"joint {j + 1} would have to turn past its limit "
                f"({math.degrees(self._lower[j]):.0f}°…{math.degrees(self._upper[j]):.0f}°); "
                f"the nearest solution within the limits is {np.abs(delta).max():.2f} rad away"
            )
        j = int(np.argmax(np.abs(delta)))
        return (
            f"joint {j + 1} would jump by {abs(delta[j]):.2f} rad (more than max_jump = "
            f"{self.max_jump:g} rad): the arm's current branch ends here (at a singularity or "
            "the edge of its reach) and only another branch reaches the target"
        )

    def _joint_move(self, q_end: np.ndarray) -> np.ndarray:
        """A quintic joint-space move from the current configuration to ``q_end``: the
        configurations after the current one, (K, 6), the last exactly ``q_end``; at most
        :data:`JOINT_MOVE_STEP` per joint between samples."""
        distance = float(np.abs(q_end - self._q).max())
        if distance == 0.0:
            return np.empty((0, 6))
        peak = 1.875  # the quintic's largest ṡ·T: its largest step is 1.875 / (samples − 1)
        samples = max(2, math.ceil(peak * distance / JOINT_MOVE_STEP) + 1)
        moves = joint_trajectory(self._q, q_end, time_scaling("quintic", 1.0), samples).q[1:]
        moves[-1] = q_end
        return moves

    def home(self) -> JogStep:
        """Go back to ``q0`` with a joint-space move (quintic time scaling, every joint at most
        :data:`JOINT_MOVE_STEP` per sample), ending exactly at ``q0``.

        A joint-space move cannot fail part way (every configuration between two within the
        limits is within them); it is refused only if it would take a joint below the mounting
        plane.

        Examples
        --------
        >>> import urkin
        >>> jog = JogController(urkin.robot("UR3"))
        >>> _ = jog.press("Z+")
        >>> step = jog.home()
        >>> step.status, bool((step.q == jog.q0).all())
        ('home: moved to x 0.250 y 0.100 z 0.300 m', True)
        """
        moves = self._joint_move(self.q0)
        if len(moves) == 0:
            return self._record("home", True, "home: already there")
        below = _below_plane(self.robot, moves)
        if below is not None:
            row, frame, height = below
            return self._record(
                "home",
                False,
                f"home: refused: the joint move would take DH frame {frame} "
                f"{-height * 1e3:.2g} mm below the mounting plane (sample {row + 1} of "
                f"{len(moves)}); staying put",
            )
        return self._record(
            "home", True, f"home: moved to {_where(fk(self.robot, self.q0))}", moves
        )

    def path_poses(self, shape: str) -> np.ndarray:
        """The poses of the circle or the square, identity orientation, sampled every
        :data:`PATH_STEP`, with the start again at the end (the loop closed): (M, 4, 4).

        Examples
        --------
        >>> import urkin
        >>> JogController(urkin.robot("UR3")).path_poses("square").shape
        (605, 4, 4)
        """
        name = shape.strip().lower() if isinstance(shape, str) else shape
        if name == "circle":
            path = circle(self.center, self.radius, plane=self.plane)
        elif name == "square":
            path = square(self.center, self.side, plane=self.plane)
        else:
            raise ValueError(f"shape must be 'circle' or 'square'; got {shape!r}")
        poses = pose_path(path, step=PATH_STEP)
        return np.concatenate([poses, poses[:1]])

    def run(self, shape: str) -> JogStep:
        """Go to the start of the circle or the square, then follow it once round.

        The approach is a joint-space move (as :meth:`home`) to the configuration that
        :func:`urkin.tracking.track` chooses for the path's first sample: the closed-form
        solution nearest the current configuration.  A joint-space move was chosen over a
        straight line in task space because it cannot fail part way, needs no orientation
        interpolation (the current orientation may be turned by π from the path's), and is what
        a controller's ``movej`` does.  The path (:meth:`path_poses`, 1 mm samples) is then
        followed with :func:`urkin.tracking.track`, each sample the closed-form solution nearest
        the previous one, verified to 1e-9.

        If a sample fails (out of reach, a joint past its limit), or a joint would change by
        more than ``max_jump`` between samples (a flip through a singularity), or a joint would
        go below the mounting plane, the arm stops at the last sample reached and the status
        says which sample failed and why.  If the start itself cannot be reached, the arm does
        not move.

        Parameters
        ----------
        shape : {"circle", "square"}

        Examples
        --------
        >>> import urkin
        >>> jog = JogController(urkin.robot("UR3"))
        >>> step = jog.run("square")
        >>> step.ok, step.qs.shape
        (True, (635, 6))
        >>> print(step.status)
        square: a joint move of 30 steps to the start, then 605 samples round the square; at x 0.250 y 0.025 z 0.225 m
        """  # noqa: E501
        poses = self.path_poses(shape)
        name = shape.strip().lower()
        tracked = track(self.robot, poses, self._q)
        reached = int(np.argmin(tracked.ok)) if not tracked.ok.all() else len(poses)
        why = tracked.failures.get(reached, "").removesuffix(": staying put")
        if reached == 0:
            return self._record(
                name,
                False,
                f"{name}: the start ({_where(poses[0])}) cannot be reached: {why}; staying put",
            )
        approach = self._joint_move(tracked.q[0])
        below = _below_plane(self.robot, approach)
        if below is not None:
            row, frame, height = below
            return self._record(
                name,
                False,
                f"{name}: refused: the joint move to the start would take DH frame {frame} "
                f"{-height * 1e3:.2g} mm below the mounting plane (sample {row + 1} of "
                f"{len(approach)}); staying put",
            )
        samples = tracked.q[:reached]
        steps = np.abs(np.diff(samples, axis=0))
        jumps = np.flatnonzero((steps > self.max_jump).any(axis=1))
        if len(jumps):
            k = int(jumps[0])
            joint = int(np.argmax(steps[k]))
            reached = k + 1
            why = (
                f"joint {joint + 1} would jump by {steps[k, joint]:.2f} rad from the sample before "
                f"(more than max_jump = {self.max_jump:g} rad): the path leaves the arm's branch"
            )
            samples = samples[:reached]
        below = _below_plane(self.robot, samples)
        if below is not None:
            row, frame, height = below
            reached = row
            why = f"DH frame {frame} would go {-height * 1e3:.2g} mm below the mounting plane"
            samples = samples[:reached]
            if reached == 0:
                return self._record(
                    name, False, f"{name}: refused at the start: {why}; staying put"
                )
        qs = np.concatenate([approach, samples])
        where = _where(fk(self.robot, qs[-1]))
        moved = f"a joint move of {len(approach)} steps to the start, then"
        if reached == len(poses):
            return self._record(
                name, True, f"{name}: {moved} {reached} samples round the {name}; at {where}", qs
            )
        return self._record(
            name,
            False,
            f"{name}: sample {reached} failed (samples 0 … {len(poses) - 1}): {why}; stopped "
            f"at sample {reached - 1}, {where}",
            qs,
        )


def _action(action: str) -> str:
    """The canonical spelling of one of :data:`ACTIONS`, or an error listing them."""
    if isinstance(action, str):
        word = action.strip()
        if word.upper() in KEYS:
            return word.upper()
        if word.lower() in ACTIONS:
            return word.lower()
    raise ValueError(f"action must be one of {', '.join(ACTIONS)}; got {action!r}")


def parse_script(script: str) -> list[str]:
    """The actions of a comma-separated script such as ``"X+, x+, Z-, home, circle"``.

    Examples
    --------
    >>> parse_script("X+, x+,Z-, Home, circle")
    ['X+', 'X+', 'Z-', 'home', 'circle']
    """
    if not isinstance(script, str):
        raise TypeError(f"script must be a string of comma-separated actions; got {script!r}")
    words = [word.strip() for word in script.split(",")]
    if not any(words):
        raise ValueError("script is empty: give comma-separated actions, e.g. 'X+,Z-,circle'")
    return [_action(word) for word in words if word]


# ----------------------------------------------------------------------------- drawing


def draw_session(controller: JogController, ax=None, *, upto: int | None = None):
    """The arm (:func:`urkin.plot.show_robot`) and the trace of the tool through the session.

    Parameters
    ----------
    controller : JogController
    ax : mpl_toolkits.mplot3d.Axes3D, optional
        Axes to draw on (cleared first); a new figure is made if omitted.
    upto : int, optional
        Draw the arm at row ``upto`` of ``controller.trail`` and the trace up to it (default:
        the last row, the current state).

    Returns
    -------
    mpl_toolkits.mplot3d.Axes3D

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> import urkin
    >>> jog = JogController(urkin.robot("UR3"))
    >>> _ = jog.press("X+")
    >>> ax = draw_session(jog)
    >>> ax.get_legend_handles_labels()[1]
    ['tool trace']
    >>> plt.close(ax.figure)
    """
    from urkin.plot import show_robot

    trail = controller.trail
    last = len(trail) - 1 if upto is None else int(upto)
    if not 0 <= last < len(trail):
        raise ValueError(f"upto must be a row of the trail, 0 … {len(trail) - 1}; got {upto!r}")
    if ax is not None:
        view = (ax.elev, ax.azim)
        ax.cla()
        ax._urkin_frame_note = None  # cla removed the note: let draw_robot write it again
        ax.view_init(*view)
    ax = show_robot(controller.robot, trail[last], ax=ax)
    trace = fk(controller.robot, trail[: last + 1])[:, :3, 3]
    ax.plot(*trace.T, color="tab:orange", linewidth=1.5, label="tool trace")
    ax.legend(loc="upper right", fontsize=8)
    return ax


def _frames(count: int, at_most: int) -> np.ndarray:
    """At most ``at_most`` indices spread evenly over ``range(count)``, the last included."""
    if count <= at_most:
        return np.arange(count)
    return np.unique(np.round(np.linspace(0, count - 1, at_most)).astype(int))


class JogPanel:
    """The ipywidgets jog panel over a :class:`JogController` (made by :func:`jog_panel`).

    In a live Jupyter kernel the panel shows its widget; elsewhere (the docs, a notebook
    viewer) its ``text/html`` is a recorded animation of the session so far.

    Attributes
    ----------
    widget : ipywidgets.VBox
        The panel.
    controller : JogController
    buttons : dict of str to ipywidgets.Button
        By name: ``"X+"`` … ``"Z-"``, ``"Home"``, ``"Circle"``, ``"Square"``.
    slider : ipywidgets.IntSlider
        The step in millimetres, bound to ``controller.step``.
    status : ipywidgets.Label
        The last step's status.
    output : ipywidgets.Output
        The figure, redrawn after every step.
    animation_frames : int
        Frames of the recorded animation.
    """

    def __init__(self, controller: JogController, *, animation_frames: int = 60) -> None:
        import ipywidgets as widgets

        if not isinstance(controller, JogController):
            raise TypeError(f"controller must be a JogController; got {type(controller).__name__}")
        if (
            isinstance(animation_frames, bool)
            or not isinstance(animation_frames, (int, np.integer))
            or animation_frames < 1
        ):
            raise ValueError(f"animation_frames must be an integer ≥ 1; got {animation_frames!r}")
        self.controller = controller
        self.animation_frames = int(animation_frames)
        names = [*KEYS, "Home", "Circle", "Square"]
        self.buttons = {
            name: widgets.Button(
                description=name,
                tooltip=_TOOLTIPS[name.upper() if name in KEYS else name.lower()],
                layout=widgets.Layout(width="72px"),
            )
            for name in names
        }
        for name, button in self.buttons.items():
            button.on_click(lambda _button, name=name: self._handle(name))
        self.slider = widgets.IntSlider(
            value=min(50, max(1, round(controller.step * 1000))),
            min=1,
            max=50,
            description="step (mm)",
            continuous_update=False,
        )
        self.slider.observe(self._set_step, names="value")
        self.status = widgets.Label(
            value=f"{controller.robot.name} ready at {_where(controller.flange)}"
        )
        self.output = widgets.Output()
        rows = [
            widgets.HBox([self.buttons[k] for k in ("X-", "X+", "Y-", "Y+", "Z-", "Z+")]),
            widgets.HBox([self.buttons[k] for k in ("Home", "Circle", "Square")] + [self.slider]),
            self.status,
            self.output,
        ]
        self.widget = widgets.VBox(rows)
        self.redraw()

    def _set_step(self, change: dict) -> None:
        self.controller.step = change["new"] / 1000.0

    def _handle(self, name: str) -> None:
        step = self.controller.do(name)
        self.status.value = step.status
        self.redraw()

    def click(self, name: str) -> None:
        """Click a button by name (case-insensitive), as a user would: the same handler runs.

        Examples
        --------
        >>> import matplotlib
        >>> matplotlib.use("Agg")
        >>> import urkin
        >>> panel = jog_panel(JogController(urkin.robot("UR3")))
        >>> panel.click("X+")
        >>> panel.status.value
        'X+: moved to x 0.270 y 0.100 z 0.300 m'
        """
        for key, button in self.buttons.items():
            if isinstance(name, str) and key.lower() == name.strip().lower():
                button.click()
                return
        raise ValueError(f"name must be one of {', '.join(self.buttons)}; got {name!r}")

    def redraw(self) -> None:
        """Draw the current state and the tool trace into the output area.

        The picture is set as the output widget's state (``Output.outputs``) rather than
        displayed inside it: no message has to be routed by a front end, so nothing leaks
        into the notebook cell when no front end runs the widget (a test runner, the docs).
        """
        import base64
        import io

        import matplotlib.pyplot as plt

        ax = draw_session(self.controller)
        try:
            buffer = io.BytesIO()
            ax.figure.savefig(buffer, format="png", dpi=80)
        finally:
            plt.close(ax.figure)
        picture = {
            "output_type": "display_data",
            "data": {
                "image/png": base64.b64encode(buffer.getvalue()).decode("ascii"),
                "text/plain": f"<{self.controller.robot.name} after {self.controller.moves} moves>",
            },
            "metadata": {},
        }
        self.output.outputs = (picture,)

    def text(self) -> str:
        """The plain-text view of the panel."""
        moves = self.controller.moves
        return (
            f"Jog panel: {self.controller.robot.name}, {moves} move{'s' if moves != 1 else ''} "
            "so far; run the notebook to use the buttons"
        )

    def _repr_mimebundle_(self, **kwargs: Any) -> dict[str, Any]:
        from urkin.animation import animate

        bundle = dict(self.widget._repr_mimebundle_(**kwargs))
        robot = self.controller.robot
        bundle["text/html"] = animate(
            robot,
            self.controller.trail,
            title=f"{robot.name} jog session",
            max_frames=self.animation_frames,
        ).html
        bundle["text/plain"] = self.text()
        return bundle

    def __repr__(self) -> str:
        return self.text()


_TOOLTIPS = {
    **{k: f"move the tool {'+' if k[1] == '+' else '−'}step along {k[0].lower()}" for k in KEYS},
    "home": "back to the home configuration (joint-space move)",
    "circle": "go to the circle's start, then follow the circle once",
    "square": "go to the square's start, then follow the square once",
}


def jog_panel(controller: JogController, *, animation_frames: int = 60) -> JogPanel:
    """The jog panel: buttons X±, Y±, Z±, Home, Circle, Square, a step slider (1-50 mm), a
    status line and the arm, redrawn after every step.

    Imports ipywidgets (and matplotlib) when called.  Displayed in a notebook, the panel is the
    live widget; its ``text/html`` alternative is an animation of the session so far
    (:func:`urkin.animation.animate` of ``controller.trail``, at most ``animation_frames``
    frames), for pages without a kernel.  :meth:`JogPanel.click` presses a button from code.

    Parameters
    ----------
    controller : JogController
    animation_frames : int
        Largest number of frames of the recorded animation.

    Returns
    -------
    JogPanel

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import urkin
    >>> panel = jog_panel(JogController(urkin.robot("UR3")))
    >>> panel.click("Z-")
    >>> panel.controller.flange[:3, 3].round(3) + 0.0
    array([0.25, 0.1 , 0.28])
    >>> panel  # in Jupyter: the buttons; in the docs: an animation of the session
    Jog panel: UR3, 1 move so far; run the notebook to use the buttons
    """
    return JogPanel(controller, animation_frames=animation_frames)


# ----------------------------------------------------------------------------- a window


def _interactive_backend() -> bool:
    """Whether matplotlib's current backend opens windows (and runs timers)."""
    import matplotlib

    backend = matplotlib.get_backend().lower()
    try:
        from matplotlib.backends import BackendFilter, backend_registry

        interactive = backend_registry.list_builtin(BackendFilter.INTERACTIVE)
    except ImportError:  # matplotlib < 3.9
        from matplotlib import rcsetup

        interactive = [name.lower() for name in rcsetup.interactive_bk]
    return backend in interactive


class JogFigure:
    """A matplotlib figure with the jog buttons (made by :func:`demo_figure`).

    Attributes
    ----------
    figure : matplotlib.figure.Figure
    controller : JogController
    ax : mpl_toolkits.mplot3d.Axes3D
        The arm's view.
    buttons : dict of str to matplotlib.widgets.Button
        By name, as :class:`JogPanel`'s.
    status : matplotlib.text.Text
        The last step's status.
    """

    def __init__(
        self, controller: JogController, *, frames_per_move: int = 40, interval: int = 40
    ) -> None:
        import matplotlib.pyplot as plt
        from matplotlib.widgets import Button

        if not isinstance(controller, JogController):
            raise TypeError(f"controller must be a JogController; got {type(controller).__name__}")
        self.controller = controller
        self.frames_per_move = int(frames_per_move)
        self.figure = plt.figure(figsize=(8.0, 8.8))
        if self.figure.canvas.manager is not None:
            self.figure.canvas.manager.set_window_title(f"urkin demo: {controller.robot.name} jog")
        self.ax = self.figure.add_axes((0.02, 0.21, 0.96, 0.73), projection="3d")
        names = [*KEYS, "Home", "Circle", "Square"]
        self.buttons: dict[str, Button] = {}
        for i, name in enumerate(names):
            row, col = (0, i) if i < len(KEYS) else (1, i - len(KEYS))
            width = 0.145 if row == 0 else 0.2
            left = 0.03 + col * (width + 0.012)
            holder = self.figure.add_axes((left, 0.125 - row * 0.055, width, 0.045))
            button = Button(holder, name)
            button.on_clicked(lambda _event, name=name: self.click(name))
            self.buttons[name] = button
        self.status = self.figure.text(
            0.03,
            0.058,
            f"{controller.robot.name} ready at {_where(controller.flange)}",
            family="monospace",
            fontsize=8,
            va="top",
            wrap=True,
        )
        self._queue: list[int] = []
        self._animated = _interactive_backend()
        self._timer = self.figure.canvas.new_timer(interval=int(interval))
        self._timer.add_callback(self._tick)
        draw_session(controller, self.ax)

    def click(self, name: str) -> JogStep:
        """Do what the button ``name`` does (case-insensitive) and show it; returns the step."""
        step = self.controller.do(name)
        self.status.set_text(step.status)
        if self._animated and len(step.qs) > 1:
            first = len(self.controller.trail) - len(step.qs)
            self._queue.extend(first + _frames(len(step.qs), self.frames_per_move))
            self._timer.start()
        else:
            self._queue.clear()
            draw_session(self.controller, self.ax)
            self.figure.canvas.draw_idle()
        return step

    def _tick(self) -> None:
        if not self._queue:
            self._timer.stop()
            return
        draw_session(self.controller, self.ax, upto=self._queue.pop(0))
        self.figure.canvas.draw_idle()


def demo_figure(controller: JogController) -> JogFigure:
    """The jog panel as a matplotlib window: the arm in 3D, buttons X±, Y±, Z±, Home, Circle,
    Square (:class:`matplotlib.widgets.Button`) and a status line.

    With an interactive backend the moves are played as animations; otherwise each click
    redraws the end state.  Show it with ``matplotlib.pyplot.show()``.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> import urkin
    >>> window = demo_figure(JogController(urkin.robot("UR3")))
    >>> print(window.click("Z+").status)
    Z+: moved to x 0.250 y 0.100 z 0.320 m
    >>> print(window.status.get_text())
    Z+: moved to x 0.250 y 0.100 z 0.320 m
    >>> plt.close(window.figure)
    """
    return JogFigure(controller)
