"""Parameter tables of the Universal Robots arms, with their provenance.

Every arm of the UR family has the same kinematic structure: six revolute joints whose
standard Denavit–Hartenberg twists are ``α = (π/2, 0, 0, π/2, −π/2, 0)``, with only six
non-zero lengths ``d1, a2, a3, d4, d5, d6``.  The numbers below are Universal Robots'
published standard-DH values.

Source
    Universal Robots, "DH Parameters for calculations of kinematics and dynamics",
    https://www.universal-robots.com/articles/ur/application-installation/dh-parameters-for-calculations-of-kinematics-and-dynamics/

Notes
    * Peter Corke's Robotics Toolbox lists the UR5 with ``d1 = 0.089459``: a typo.  UR's value
      (and the ROS-Industrial URDF) is ``d1 = 0.089159``.
    * UR's ``a`` is Wikipedia's ``r``: the common normal length.  ``a2`` and ``a3`` are negative
      because the DH ``x`` axes point from the elbow back towards the shoulder.

Frames
    Poses in urkin are expressed in DH frame 0, which UR calls ``base``.  ROS/URDF models
    name a frame ``base_link`` rotated by π about ``z``: ``T_base_link_base = Rz(π)``
    (:data:`T_BASE_LINK_BASE`).  URDF's ``tool0`` frame *is* DH frame 6 (the flange).
"""

from __future__ import annotations

import functools
import math
import numbers
from dataclasses import dataclass, field, replace

import numpy as np

from urkin._inputs import generator, sample_shape

__all__ = [
    "ALPHA_UR",
    "ROBOTS",
    "T_BASE_LINK_BASE",
    "Robot",
    "UnknownRobotError",
    "check_robot",
    "random_configurations",
    "robot",
]

#: Standard-DH link twists α_i shared by every UR arm (radians).
ALPHA_UR: tuple[float, ...] = (math.pi / 2, 0.0, 0.0, math.pi / 2, -math.pi / 2, 0.0)

_UR_DH_SOURCE = (
    "Universal Robots, 'DH Parameters for calculations of kinematics and dynamics' "
    "(universal-robots.com)"
)

#: Pose of UR's ``base`` frame (DH frame 0) in the URDF ``base_link`` frame: Rz(π).
T_BASE_LINK_BASE: np.ndarray = np.array(
    [[-1.0, 0.0, 0.0, 0.0], [0.0, -1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]]
)
T_BASE_LINK_BASE.setflags(write=False)


def _frozen(matrix: np.ndarray | None, name: str) -> np.ndarray:
    """A read-only copy of the base or tool transform ``matrix`` (None: the identity)."""
    if matrix is None:
        array = np.eye(4)
    else:
        # imported here so that robots stays importable on its own in docs builds
        from urkin.transforms import _is_rotation_one, check_transform, orthonormalize

        array = np.array(check_transform(matrix, name=name), dtype=float)
        if array.shape != (4, 4):
            raise ValueError(f"{name} must be one 4×4 transform; got shape {array.shape}")
        if not _is_rotation_one(array.tolist(), _RIGID):  # e.g. typed with a few decimals
            array[:3, :3] = orthonormalize(array[:3, :3])  # else every pose fk gives is skewed
    array.setflags(write=False)
    return array


#: A base or tool rotation further than this from orthonormal (but within the checks'
#: tolerance) is replaced by its nearest rotation.
_RIGID = 1e-14


class UnknownRobotError(KeyError, ValueError):
    """An arm name :func:`robot` does not know (a KeyError, as a failed lookup, and a
    ValueError, as a bad argument); the message lists the known names."""

    def __str__(self) -> str:
        return str(self.args[0]) if self.args else ""


@dataclass(frozen=True, eq=False)
class Robot:
    """One UR arm: its standard-DH table, joint limits and the frames around it.

    Parameters
    ----------
    name : str
        Model name, for example ``"UR5e"``.
    d1, a2, a3, d4, d5, d6 : float
        The non-zero standard-DH lengths in metres (``a2`` and ``a3`` negative as UR publishes
        them).
    joint_limits : tuple of (float, float)
        Lower and upper limit of each joint in radians (±2π on every UR joint).
    base : ndarray, shape (4, 4)
        Pose of DH frame 0 in the user's world frame (identity unless set with
        :meth:`with_base`).
    tool : ndarray, shape (4, 4)
        Pose of the tool frame in DH frame 6, the flange (identity unless set with
        :meth:`with_tool`).
    source : str
        Where the numbers come from.
    notes : str
        Anything a user of these numbers should know.

    Examples
    --------
    >>> import urkin
    >>> ur5 = urkin.robot("ur5")
    >>> ur5.name, ur5.d1, ur5.a2
    ('UR5', 0.089159, -0.425)
    >>> ur5.dh_table().shape
    (6, 3)
    """

    name: str
    d1: float
    a2: float
    a3: float
    d4: float
    d5: float
    d6: float
    joint_limits: tuple[tuple[float, float], ...] = field(
        default=((-2 * math.pi, 2 * math.pi),) * 6, repr=False
    )
    base: np.ndarray = field(default=None, repr=False)  # type: ignore[assignment]
    tool: np.ndarray = field(default=None, repr=False)  # type: ignore[assignment]
    source: str = field(default=_UR_DH_SOURCE, repr=False)
    notes: str = field(default="", repr=False)
    _plain: bool = field(init=False, repr=False, default=True)
    #: The six DH lengths ``(d1, a2, a3, d4, d5, d6)`` in metres, as floats.
    lengths: tuple[float, float, float, float, float, float] = field(
        init=False,
        repr=False,
        compare=False,
        default=(),  # type: ignore[assignment]
    )

    def __post_init__(self) -> None:
        for label in ("d1", "a2", "a3", "d4", "d5", "d6"):
            x = getattr(self, label)
            if isinstance(x, (bool, np.bool_)) or not isinstance(x, numbers.Real):
                raise TypeError(f"{self.name}: {label} must be a length in metres; got {x!r}")
            if not math.isfinite(x):
                raise ValueError(f"{self.name}: {label} must be finite; got {x!r}")
            object.__setattr__(self, label, float(x))  # numpy scalars too: one float type
        lengths = (self.d1, self.a2, self.a3, self.d4, self.d5, self.d6)
        if any(abs(x) > 5.0 for x in lengths):
            raise ValueError(
                f"{self.name}: DH lengths are in metres; {lengths} looks like millimetres"
            )
        try:
            limits = tuple((float(lo), float(hi)) for lo, hi in self.joint_limits)
        except (TypeError, ValueError):  # None, a ragged row, a string
            limits = ()
        if len(limits) != 6 or not all(lo < hi for lo, hi in limits):  # NaN fails lo < hi
            raise ValueError(
                f"{self.name}: joint_limits must be six (lower, upper) pairs of numbers in "
                f"radians with lower < upper; got {self.joint_limits!r:.120}"
            )
        object.__setattr__(self, "joint_limits", limits)
        object.__setattr__(self, "base", _frozen(self.base, "T_world_base"))
        object.__setattr__(self, "tool", _frozen(self.tool, "T_flange_tool"))
        plain = np.array_equal(self.base, np.eye(4)) and np.array_equal(self.tool, np.eye(4))
        object.__setattr__(self, "_plain", bool(plain))
        object.__setattr__(self, "lengths", tuple(float(x) for x in lengths))

    @property
    def d(self) -> np.ndarray:
        """DH offsets ``d_i`` along ``z_{i-1}`` for the six joints, metres."""
        return np.array([self.d1, 0.0, 0.0, self.d4, self.d5, self.d6])

    @property
    def a(self) -> np.ndarray:
        """DH lengths ``a_i`` along ``x_i`` for the six joints, metres."""
        return np.array([0.0, self.a2, self.a3, 0.0, 0.0, 0.0])

    @property
    def alpha(self) -> np.ndarray:
        """DH twists ``α_i`` about ``x_i`` for the six joints, radians."""
        return np.array(ALPHA_UR)

    @property
    def has_identity_frames(self) -> bool:
        """True when ``base`` and ``tool`` are both the identity: poses are flange poses in DH
        frame 0."""
        return self._plain

    def dh_table(self) -> np.ndarray:
        """The standard-DH table as rows ``(d_i, a_i, α_i)``, shape (6, 3)."""
        return np.column_stack([self.d, self.a, self.alpha])

    def with_base(self, T_world_base: np.ndarray) -> Robot:
        """A copy of this arm mounted at ``T_world_base`` (pose of DH frame 0 in the world).

        A rotation that is orthonormal only within the checks' tolerance (a matrix typed with
        a few decimals) is replaced by its nearest rotation, so that every pose :func:`fk`
        gives is rigid (and IK can reach them)."""
        return replace(self, base=T_world_base)

    def with_tool(self, T_flange_tool: np.ndarray) -> Robot:
        """A copy of this arm carrying a tool at ``T_flange_tool`` (tool pose in DH frame 6);
        its rotation is made orthonormal as :meth:`with_base`'s is."""
        return replace(self, tool=T_flange_tool)


_TABLE: dict[str, Robot] = {
    r.name.lower(): r
    for r in (
        Robot("UR3", 0.1519, -0.24365, -0.21325, 0.11235, 0.08535, 0.0819),
        Robot(
            "UR5",
            0.089159,
            -0.425,
            -0.39225,
            0.10915,
            0.09465,
            0.0823,
            notes="Robotics Toolbox's UR5 has d1 = 0.089459, a typo for UR's 0.089159.",
        ),
        Robot("UR10", 0.1273, -0.612, -0.5723, 0.163941, 0.1157, 0.0922),
        Robot("UR3e", 0.15185, -0.24355, -0.2132, 0.13105, 0.08535, 0.0921),
        Robot("UR5e", 0.1625, -0.425, -0.3922, 0.1333, 0.0997, 0.0996),
        Robot("UR10e", 0.1807, -0.6127, -0.57155, 0.17415, 0.11985, 0.11655),
        Robot("UR16e", 0.1807, -0.4784, -0.36, 0.17415, 0.11985, 0.11655),
    )
}

#: Names of the arms :func:`robot` knows, in UR's order.
ROBOTS: tuple[str, ...] = tuple(r.name for r in _TABLE.values())


def check_robot(value: object, name: str = "robot") -> Robot:
    """``value`` if it is a :class:`Robot`; otherwise a TypeError that says what to pass.

    Examples
    --------
    >>> check_robot("ur5")
    Traceback (most recent call last):
    ...
    TypeError: robot must be a urkin Robot such as urkin.robot('ur5'); got the str 'ur5'
    """
    if isinstance(value, Robot):
        return value
    shown = f"the {type(value).__name__} {value!r:.40}"
    raise TypeError(f"{name} must be a urkin Robot such as urkin.robot('ur5'); got {shown}")


def robot(name: str) -> Robot:
    """Look up a UR arm by name, ignoring case.

    Parameters
    ----------
    name : str
        One of :data:`ROBOTS`, for example ``"ur5"`` or ``"UR10e"``.

    Returns
    -------
    Robot
        The arm with UR's official standard-DH parameters.

    Raises
    ------
    UnknownRobotError
        If the name is unknown (a KeyError and a ValueError); the message lists the known
        names.
    TypeError
        If ``name`` is not a string.

    Examples
    --------
    >>> robot("Ur3e").d6
    0.0921
    """
    if not isinstance(name, str):
        raise TypeError(
            f"name must be an arm's name such as 'ur5' (one of {', '.join(ROBOTS)}); got the "
            f"{type(name).__name__} {name!r:.40}"
        )
    try:
        return _TABLE[name.strip().lower()]
    except KeyError:
        raise UnknownRobotError(
            f"unknown robot {name!r}; urkin knows {', '.join(ROBOTS)} (case does not matter)"
        ) from None


def random_configurations(
    robot: Robot, shape: int | tuple[int, ...] = (), seed: int | np.random.Generator = 0
) -> np.ndarray:
    """Seeded joint configurations drawn uniformly within ``robot``'s limits and (−π, π] (for
    a joint whose limits lie outside (−π, π], within its limits).

    Parameters
    ----------
    robot : Robot
    shape : int or tuple of int
        Leading shape; ``()`` (default) for one configuration.
    seed : int or numpy.random.Generator

    Returns
    -------
    ndarray, shape (*shape, 6)

    Examples
    --------
    >>> q = random_configurations(robot("ur5"), (2, 3), seed=1)
    >>> q.shape, bool((abs(q) <= math.pi).all())
    ((2, 3, 6), True)
    """
    arm = check_robot(robot)
    size = sample_shape(shape)
    lower, span = _draw_limits(arm.joint_limits)
    # Generator.uniform(lower, upper) draws lower + (upper − lower)·u, u from random(): the same
    # numbers, without the 6 µs its array bounds cost a single configuration
    return lower + span * generator(seed).random((*size, 6))


@functools.lru_cache(maxsize=32)
def _draw_limits(joint_limits: tuple[tuple[float, float], ...]) -> tuple[np.ndarray, np.ndarray]:
    """The lower bounds :func:`random_configurations` draws from and the spans above them: the
    limits within (−π, π], or, for a joint whose limits lie outside that interval, the limits
    (at most a turn of them)."""
    lo = np.array([lo for lo, _ in joint_limits])
    hi = np.array([hi for _, hi in joint_limits])
    lower, upper = np.maximum(lo, -math.pi), np.minimum(hi, math.pi)
    outside = lower >= upper
    lower = np.where(outside, lo, lower)
    upper = np.where(outside, np.minimum(hi, lo + 2 * math.pi), upper)
    span = upper - lower
    lower.flags.writeable = span.flags.writeable = False
    return lower, span
