"""Forward kinematics and Jacobians of UR arms, for one configuration or a batch.

Every function takes joint angles ``q`` of shape ``(6,)`` (one configuration) or ``(N, 6)``
(a batch) in radians, and returns arrays with the matching leading shape.  The heavy lifting
is done by code generated from the SymPy derivation in :mod:`urkin.symbolic`
(``urkin/_generated``): scalar ``math`` code for one pose, whole-column numpy code for a batch.

Poses are those of the robot's tool frame (the flange, DH frame 6, unless a tool was set with
:meth:`urkin.Robot.with_tool`) in the robot's world frame (DH frame 0, UR's ``base``, unless
a base was set with :meth:`urkin.Robot.with_base`).
"""

from __future__ import annotations

import functools
import itertools
import math

import numpy as np
from numpy.typing import ArrayLike

from urkin._generated import ur_kinematics as _gen
from urkin._inputs import choice, flag, positive, real, unstack
from urkin.robots import Robot, check_robot
from urkin.transforms import check_transform, inv_transform

__all__ = [
    "MAX_JOINT_ANGLE",
    "SINGULARITIES",
    "SINGULARITY_TOLERANCE",
    "check_joints",
    "condition_number",
    "dh_chain",
    "dh_transform",
    "fk",
    "fk_frames",
    "flange_pose",
    "jacobian",
    "manipulability",
    "position_jacobian",
    "singular_families",
    "singularities",
    "singularity_factors",
]

#: Joint angles beyond ±8π (±1440°) are rejected as a likely degrees-for-radians mistake.
MAX_JOINT_ANGLE = 8 * math.pi


#: Batches are evaluated in blocks of this many poses, which keeps the workspace in cache (not a
#: power of two: rows 16 kB apart would compete for the same cache sets).
_BLOCK = 2000
#: Up to this many poses, a stack is evaluated pose by pose with the one-pose code: the column
#: code's fixed cost (~100 numpy calls) is then larger than the rows' (bench/kinematics.py).
_FEW = 24


def _many(function, array: np.ndarray, robot: Robot, shape: tuple[int, ...]) -> np.ndarray:
    """Evaluate a generated ``*_many`` function block by block into one output array, with one
    contiguous workspace for all blocks."""
    n = array.shape[0]
    out = np.empty((n, *shape), dtype=array.dtype)
    work = np.empty((function.work_rows, min(n, _BLOCK)), dtype=array.dtype)
    lengths = robot.lengths
    for start in range(0, n, _BLOCK):
        stop = start + _BLOCK
        function(array[start:stop], *lengths, out=out[start:stop], work=work)
    return out


def _range_error(largest: float, name: str) -> ValueError:
    return ValueError(
        f"{name} has an angle of {largest:.4g} rad: joint angles are in radians "
        "(did you pass degrees? numpy.radians converts them)"
    )


def _one_configuration(q: ArrayLike, name: str) -> np.ndarray:
    """One checked configuration (6,), a fresh array, or an error naming ``name``."""
    array, lead, _ = _joints(q, name)
    if lead != ():
        raise ValueError(f"{name} must be one configuration, shape (6,); got shape {np.shape(q)}")
    return array[0].copy()


def _joints(
    q: ArrayLike, name: str = "q", *, complex_ok: bool = False
) -> tuple[np.ndarray, tuple[int, ...], list[float] | None]:
    """Checked joint angles: ``(array, lead, values)``.

    ``array`` has shape (N, 6) with the leading axes ``lead`` flattened (the batching rule);
    for one real configuration ``lead`` is ``()`` and ``values`` its six floats (the scalar
    fast path), else ``values`` is None.  Complex angles (complex-step derivatives) are taken
    only with ``complex_ok``.
    """
    values = _six(q)
    if values is not None:  # the common case, checked without building another array
        if q.ndim == 1:
            return q.reshape(1, 6), (), values
        return q, (1,), None  # a stack of one keeps its leading axis
    if type(q) is np.ndarray and q.dtype is _FLOAT and q.ndim > 1 and q.shape[-1] == 6 and q.size:
        # a float stack: two reductions check it (NaN fails both comparisons)
        if -MAX_JOINT_ANGLE <= q.min() and q.max() <= MAX_JOINT_ANGLE:
            return q.reshape(-1, 6), q.shape[:-1], None
    array = real(q, name, complex_ok=complex_ok)  # NaN and infinity are refused here
    if array.ndim == 0 or array.shape[-1] != 6:
        raise ValueError(
            f"{name} must be 6 joint angles in radians, shape (6,) or (..., 6); got {array.shape}"
        )
    lead = array.shape[:-1]
    array = array.reshape(-1, 6)
    largest = float(np.abs(array.real).max(initial=0.0))
    if largest > MAX_JOINT_ANGLE:
        raise _range_error(largest, name)
    if lead == () and array.dtype.kind == "f":
        return array, lead, array[0].tolist()
    return array, lead, None


def check_joints(q: ArrayLike, name: str = "q") -> np.ndarray:
    """Validate joint angles and return them as a float array of shape (6,) or (..., 6): a
    view of ``q`` itself (not a copy) when it already is a float array, as
    :func:`numpy.asarray` gives it.

    Raises
    ------
    TypeError
        If ``q`` is not numeric, or complex.
    ValueError
        If the shape is wrong, a value is NaN or infinite, or an angle exceeds
        :data:`MAX_JOINT_ANGLE` (which almost always means degrees were passed).

    Examples
    --------
    >>> check_joints([0, -1.57, 0, -1.57, 0, 0]).shape
    (6,)
    >>> check_joints([0, 90, 0, 0, 0, 0])
    Traceback (most recent call last):
    ...
    ValueError: q has an angle of 90 rad: joint angles are in radians (did you pass degrees? numpy.radians converts them)
    """  # noqa: E501
    array, lead, _ = _joints(q, name)
    return array.reshape(*lead, 6)


_FLOAT = np.dtype(float)


def _six(q: ArrayLike) -> list[float] | None:
    """The scalar fast path's test: the six floats of ``q`` when it is one configuration, of
    shape (6,) or a stack of one (1, 6), as a float array, finite and within
    ±:data:`MAX_JOINT_ANGLE`; else None (and the general path checks ``q`` and explains what is
    wrong).

    One Euclidean norm decides (:func:`math.hypot`: NaN and inf fail it, and it does not
    overflow): it is at most ``MAX_JOINT_ANGLE`` only when every angle is in range, and the
    rare configuration with every angle in range but a larger norm takes the general path,
    which checks each angle."""
    if type(q) is np.ndarray and q.dtype is _FLOAT:
        shape = q.shape
        if shape == _SIX or shape == _ONE_ROW:
            values = q.tolist()
            if len(values) == 1:  # a stack of one
                (values,) = values
            if _hypot(*values) <= MAX_JOINT_ANGLE:
                return values
    return None


_SIX, _ONE_ROW = (6,), (1, 6)


_hypot = math.hypot
_chain = itertools.chain.from_iterable


def _one_pose_first(one, stacked: tuple[int, ...]):
    """Decorator: the public function runs the generated one-pose function ``one`` itself when
    ``robot`` is a plain :class:`Robot` and ``q`` one configuration, of shape (6,) or a stack
    of one (``stacked``: the shape of a stack of one's result), as a float array, finite and
    within ±:data:`MAX_JOINT_ANGLE` (:func:`_six`'s test, written out: the fast path of
    :func:`fk`, :func:`jacobian` and :func:`position_jacobian` makes no call but ``one``'s),
    and likewise a few configurations (k, 6), k ≤ :data:`_FEW` (:func:`_few`'s test), row by
    row; anything else goes to the decorated function, which checks it."""

    item = stacked[1:]

    def decorate(general):
        @functools.wraps(general)
        def public(robot: Robot, q: ArrayLike) -> np.ndarray:
            if type(robot) is Robot and robot._plain and type(q) is np.ndarray:
                if q.dtype is _FLOAT:
                    shape = q.shape
                    if shape == _SIX:
                        values = q.tolist()
                        if _hypot(*values) <= MAX_JOINT_ANGLE:
                            return one(values, robot.lengths)
                    elif shape == _ONE_ROW:
                        (values,) = q.tolist()
                        if _hypot(*values) <= MAX_JOINT_ANGLE:
                            return one(values, robot.lengths, _empty(stacked))
                    else:
                        rows = _few(q)
                        if rows is not None:
                            return _row_by_row(one, rows, robot.lengths, item)
            return general(robot, q)

        return public

    return decorate


_empty = np.empty


def _few(q: ArrayLike) -> list[list[float]] | None:
    """The rows of ``q`` when it is a small stack (k ≤ :data:`_FEW`, k, 6) of float angles, all
    finite and in range; else None (the general path checks ``q``).

    :func:`_six`'s test on the whole stack at once: one Euclidean norm of every angle (NaN and
    inf fail it) at most ``MAX_JOINT_ANGLE``; a stack of angles in range but of a larger norm
    takes the general path."""
    if type(q) is np.ndarray and q.ndim == 2 and q.shape[1] == 6 and q.dtype is _FLOAT:
        if len(q) <= _FEW:
            rows = q.tolist()
            if _hypot(*_chain(rows)) <= MAX_JOINT_ANGLE:
                return rows
    return None


def _evaluate(robot: Robot, q: ArrayLike, one, many, shape: tuple[int, ...]) -> np.ndarray:
    """A generated function at ``q``: the scalar code for one real configuration, the column
    code for a stack (and for complex angles), with the leading axes kept."""
    values = _six(q)
    if values is not None:  # a stack of one pose costs what one pose does
        return one(values, robot.lengths, None if q.ndim == 1 else np.empty((1, *shape)))
    rows = _few(q)
    if rows is None:
        array, lead, values = _joints(q, complex_ok=True)
        if values is not None:
            return one(values, robot.lengths)
        if len(array) > _FEW or array.dtype.kind != "f":
            return unstack(_many(many, array, robot, shape), lead)
        rows = array.tolist()
    else:
        lead = (len(rows),)
    out = _row_by_row(one, rows, robot.lengths, shape)
    return out if len(lead) == 1 else unstack(out, lead)


def _row_by_row(one, rows: list[list[float]], lengths, shape: tuple[int, ...]) -> np.ndarray:
    """A few poses (``rows``, checked): the one-pose code ``one`` row by row, straight into the
    output (k, *shape), which beats the column code's fixed cost."""
    out = np.empty((len(rows), *shape))
    size = 8 * math.prod(shape)
    for row, at in zip(rows, range(0, len(rows) * size, size)):
        one(row, lengths, out, at)
    return out


@_one_pose_first(_gen.t06_one, (1, 4, 4))
def fk(robot: Robot, q: ArrayLike) -> np.ndarray:
    """Forward kinematics: the tool pose ``T_base_tool`` for joint angles ``q``.

    Parameters
    ----------
    robot : Robot
        The arm, for example ``urkin.robot("ur5")``.
    q : array_like, shape (6,) or (N, 6)
        Joint angles in radians.

    Returns
    -------
    ndarray, shape (4, 4) or (N, 4, 4)
        Homogeneous transforms of the tool frame (the flange unless a tool was set) in the
        base frame (DH frame 0 unless a base was set).

    Examples
    --------
    >>> import urkin
    >>> ur5 = urkin.robot("ur5")
    >>> home = [0, -np.pi / 2, 0, -np.pi / 2, 0, 0]
    >>> fk(ur5, home).round(5) + 0.0  # + 0.0 turns -0.0 into 0.0
    array([[-1.     ,  0.     ,  0.     ,  0.     ],
           [ 0.     ,  0.     , -1.     , -0.19145],
           [ 0.     , -1.     ,  0.     ,  1.00106],
           [ 0.     ,  0.     ,  0.     ,  1.     ]])
    >>> fk(ur5, np.zeros((10, 6))).shape
    (10, 4, 4)
    """
    robot = check_robot(robot)
    T = _evaluate(robot, q, _gen.t06_one, _gen.t06_many, (4, 4))
    if robot._plain:
        return T
    return robot.base @ T @ robot.tool


def fk_frames(robot: Robot, q: ArrayLike) -> np.ndarray:
    """Poses of the base and of DH frames 1 … 6, for drawing the arm or building Jacobians.

    Parameters
    ----------
    robot : Robot
    q : array_like, shape (6,) or (N, 6)
        Joint angles in radians.

    Returns
    -------
    ndarray, shape (7, 4, 4) or (N, 7, 4, 4)
        ``[T_base_0, T_base_1, …, T_base_6]``: frame 0 is the robot's base (the identity
        unless a base was set); the tool transform is not applied.

    Examples
    --------
    >>> import urkin
    >>> frames = fk_frames(urkin.robot("ur3"), np.zeros(6))
    >>> frames[1][:3, 3]  # the shoulder frame sits d1 above the base
    array([0.    , 0.    , 0.1519])
    """
    robot = check_robot(robot)
    frames = _evaluate(robot, q, _gen.frames_one, _gen.frames_many, (7, 4, 4))
    if robot._plain:
        return frames
    return robot.base @ frames


def flange_pose(robot: Robot, T_world_tool: ArrayLike, *, check: bool = True) -> np.ndarray:
    """The flange pose in DH frame 0 that puts the robot's tool at ``T_world_tool``:
    ``base⁻¹ · T_world_tool · tool⁻¹``, for poses (4, 4) or (..., 4, 4); the inverse of what
    :func:`fk` applies.  ``check=False`` skips validating the robot and the poses (callers
    that have checked them).

    Examples
    --------
    >>> import urkin
    >>> from urkin.transforms import make_transform
    >>> arm = urkin.robot("ur5").with_tool(make_transform(p=[0.0, 0.0, 0.1]))
    >>> q = [0.3, -1.2, 1.4, -0.6, 1.1, 0.2]
    >>> bool(np.allclose(flange_pose(arm, fk(arm, q)), fk(urkin.robot("ur5"), q)))
    True
    """
    if check is not False and flag(check, "check"):
        robot = check_robot(robot)
        T_world_tool = check_transform(T_world_tool, name="T_world_tool")
    if robot._plain:
        return np.array(T_world_tool, dtype=float)  # a fresh array, never the caller's
    return inv_transform(robot.base) @ T_world_tool @ inv_transform(robot.tool)


def _with_tool_and_base(robot: Robot, J: np.ndarray, q: ArrayLike) -> np.ndarray:
    """Move a flange Jacobian to the tool origin and express it in the world frame."""
    R06 = _evaluate(robot, q, _gen.t06_one, _gen.t06_many, (4, 4))[..., :3, :3]
    r = R06 @ robot.tool[:3, 3]  # flange → tool origin, in base coordinates
    J = J.copy()
    # v_tool = v_flange + ω × r, written out (complex angles too: a complex-step derivative)
    w = J[..., 3:, :]
    rx, ry, rz = r[..., 0, None], r[..., 1, None], r[..., 2, None]
    J[..., 0, :] -= ry * w[..., 2, :] - rz * w[..., 1, :]
    J[..., 1, :] -= rz * w[..., 0, :] - rx * w[..., 2, :]
    J[..., 2, :] -= rx * w[..., 1, :] - ry * w[..., 0, :]
    R_base = robot.base[:3, :3]
    J[..., :3, :] = R_base @ J[..., :3, :]
    J[..., 3:, :] = R_base @ J[..., 3:, :]
    return J


@_one_pose_first(_gen.jacobian_one, (1, 6, 6))
def jacobian(robot: Robot, q: ArrayLike) -> np.ndarray:
    """Geometric Jacobian ``[v; ω]`` of the tool origin, in the base frame.

    Column ``i`` maps the speed of joint ``i`` (rad/s) to the linear velocity ``v`` (m/s) of
    the tool origin and the angular velocity ``ω`` (rad/s) of the tool, both in base
    coordinates: ``[v; ω] = J(q) q̇``.

    Parameters
    ----------
    robot : Robot
    q : array_like, shape (6,) or (N, 6)
        Joint angles in radians.

    Returns
    -------
    ndarray, shape (6, 6) or (N, 6, 6)

    Examples
    --------
    >>> import urkin
    >>> J = jacobian(urkin.robot("ur5"), np.zeros(6))
    >>> J[3:, 0]  # joint 1 turns about the base z axis
    array([0., 0., 1.])
    """
    robot = check_robot(robot)
    J = _evaluate(robot, q, _gen.jacobian_one, _gen.jacobian_many, (6, 6))
    if robot._plain:
        return J
    return _with_tool_and_base(robot, J, q)


@_one_pose_first(_gen.position_jacobian_one, (1, 3, 6))
def position_jacobian(robot: Robot, q: ArrayLike) -> np.ndarray:
    """Position Jacobian ``∂p/∂q`` of the tool origin, in the base frame.

    Derived by differentiating the closed-form position in :mod:`urkin.symbolic`; it equals
    the first three rows of :func:`jacobian`.

    Parameters
    ----------
    robot : Robot
    q : array_like, shape (6,) or (N, 6)
        Joint angles in radians.

    Returns
    -------
    ndarray, shape (3, 6) or (N, 3, 6)

    Examples
    --------
    >>> import urkin
    >>> position_jacobian(urkin.robot("ur5"), np.zeros((4, 6))).shape
    (4, 3, 6)
    """
    robot = check_robot(robot)
    if not robot._plain:
        return jacobian(robot, q)[..., :3, :]
    return _evaluate(robot, q, _gen.position_jacobian_one, _gen.position_jacobian_many, (3, 6))


def dh_transform(
    theta: ArrayLike,
    d: ArrayLike,
    a: ArrayLike,
    alpha: ArrayLike,
    convention: str = "standard",
) -> np.ndarray:
    """Numeric DH link transform ``T_{i-1,i}``, broadcasting over its arguments.

    Parameters
    ----------
    theta, d, a, alpha : array_like
        Joint angle (rad), offset (m), length (m) and twist (rad).  In the modified convention
        ``a`` and ``alpha`` are the previous link's ``a_{i-1}`` and ``α_{i-1}``.
    convention : {"standard", "modified"}
        ``"standard"``: ``Rz(θ) Tz(d) Tx(a) Rx(α)``; ``"modified"`` (Craig):
        ``Rx(α) Tx(a) Rz(θ) Tz(d)``.

    Returns
    -------
    ndarray, shape (..., 4, 4)

    Examples
    --------
    >>> dh_transform(0.0, 0.1, 0.2, np.pi / 2).round(3)
    array([[ 1. , -0. ,  0. ,  0.2],
           [ 0. ,  0. , -1. ,  0. ],
           [ 0. ,  1. ,  0. ,  0.1],
           [ 0. ,  0. ,  0. ,  1. ]])
    """
    choice(convention, "convention", ("standard", "modified"))
    values = [real(x, name) for x, name in ((theta, "theta"), (d, "d"), (a, "a"), (alpha, "alpha"))]
    try:
        th, dd, aa, al = np.broadcast_arrays(*values)
    except ValueError:
        shapes = ", ".join(str(v.shape) for v in values)
        raise ValueError(f"theta, d, a and alpha must broadcast together; got {shapes}") from None
    ct, st, ca, sa = np.cos(th), np.sin(th), np.cos(al), np.sin(al)
    T = np.zeros((*th.shape, 4, 4))
    if convention == "standard":
        T[..., 0, :] = np.stack([ct, -st * ca, st * sa, aa * ct], axis=-1)
        T[..., 1, :] = np.stack([st, ct * ca, -ct * sa, aa * st], axis=-1)
        T[..., 2, 1], T[..., 2, 2], T[..., 2, 3] = sa, ca, dd
    else:
        T[..., 0, 0], T[..., 0, 1], T[..., 0, 3] = ct, -st, aa
        T[..., 1, :] = np.stack([st * ca, ct * ca, -sa, -sa * dd], axis=-1)
        T[..., 2, :] = np.stack([st * sa, ct * sa, ca, ca * dd], axis=-1)
    T[..., 3, 3] = 1.0
    return T


def dh_chain(table: ArrayLike, q: ArrayLike, convention: str = "standard") -> np.ndarray:
    """Product of DH link transforms for any serial arm: ``T_0_n = T_0_1 T_1_2 … T_{n-1}_n``.

    A plain, general (and slower) counterpart of :func:`fk` for tables that are not a UR arm,
    or for comparing conventions.

    Parameters
    ----------
    table : array_like, shape (n, 3)
        Rows ``(d_i, a_i, α_i)`` (in the modified convention ``(d_i, a_{i-1}, α_{i-1})``).
    q : array_like, shape (n,) or (N, n)
        Joint angles in radians (added to θ offsets of zero).
    convention : {"standard", "modified"}

    Returns
    -------
    ndarray, shape (4, 4) or (N, 4, 4)

    Examples
    --------
    >>> import urkin
    >>> ur3 = urkin.robot("ur3")
    >>> q = np.array([0.1, -1.2, 0.8, 0.3, 1.1, -0.4])
    >>> np.allclose(dh_chain(ur3.dh_table(), q), fk(ur3, q))
    True
    """
    rows = real(table, "table")
    if rows.ndim != 2 or rows.shape[1] != 3 or len(rows) == 0:
        raise ValueError(f"table must be (n, 3) rows (d, a, alpha); got shape {rows.shape}")
    angles = real(q, "q")
    if angles.ndim == 0 or angles.shape[-1] != rows.shape[0]:
        raise ValueError(
            f"q must have shape ({len(rows)},) or (..., {len(rows)}) for a table of "
            f"{len(rows)} rows; got {angles.shape}"
        )
    links = dh_transform(angles, rows[:, 0], rows[:, 1], rows[:, 2], convention)
    T = links[..., 0, :, :]
    for i in range(1, rows.shape[0]):
        T = T @ links[..., i, :, :]
    return T


#: Names of the UR singular families, in the order of :func:`singularity_factors`.
SINGULARITIES: tuple[str, str, str] = ("shoulder", "elbow", "wrist")

#: A family is present when the magnitude of its factor is at most this (metres for the
#: shoulder factor, dimensionless for the others).
SINGULARITY_TOLERANCE = 1e-9


def singularity_factors(robot: Robot, q: ArrayLike) -> np.ndarray:
    """The three factors of ``det J = a2 a3 · s3 · s5 · (a2 c2 + a3 c23 + d5 s234)``.

    For every UR arm the determinant of the geometric Jacobian factors into

    * **shoulder**: ``a2 cos q2 + a3 cos(q2 + q3) + d5 sin(q2 + q3 + q4)`` (metres): the
      distance of the wrist centre from the plane that holds the base axis and is parallel to
      the shoulder axis.  When it is zero, turning joint 1 moves the wrist centre only in a
      direction joints 2 and 3 already provide, and no joint can move it along the shoulder
      axis;
    * **elbow**: ``sin q3``: zero when the upper arm and forearm are aligned;
    * **wrist**: ``sin q5``: zero when the axes of joints 4 and 6 are parallel.

    Lesson 04 derives this with SymPy.

    Parameters
    ----------
    robot : Robot
    q : array_like, shape (6,) or (N, 6)

    Returns
    -------
    ndarray, shape (3,) or (N, 3)
        ``(shoulder, elbow, wrist)`` factors.

    Examples
    --------
    >>> import urkin
    >>> ur5 = urkin.robot("ur5")
    >>> singularity_factors(ur5, [0, -np.pi / 2, 0, -np.pi / 2, 0, 0]).round(6) + 0.0
    array([0., 0., 0.])
    """
    robot = check_robot(robot)
    array = check_joints(q)
    q2, q3, q4, q5 = (array[..., i] for i in (1, 2, 3, 4))
    shoulder = robot.a2 * np.cos(q2) + robot.a3 * np.cos(q2 + q3) + robot.d5 * np.sin(q2 + q3 + q4)
    return np.stack([shoulder, np.sin(q3), np.sin(q5)], axis=-1)


def singular_families(robot: Robot, q: ArrayLike, tol: float = SINGULARITY_TOLERANCE) -> np.ndarray:
    """Which singular families hold at ``q``: booleans ``(shoulder, elbow, wrist)``.

    Returns
    -------
    ndarray of bool, shape (3,) or (N, 3)
    """
    positive(tol, "tol", zero_ok=True)
    return np.abs(singularity_factors(robot, q)) <= tol


def singularities(
    robot: Robot, q: ArrayLike, tol: float = SINGULARITY_TOLERANCE
) -> tuple[str, ...] | list[tuple[str, ...]]:
    """Names of the singular families present at ``q`` (see :func:`singularity_factors`).

    Parameters
    ----------
    robot : Robot
    q : array_like, shape (6,) or (N, 6)
    tol : float
        Largest factor magnitude that counts as singular.  At the default 1e-9 a flagged
        configuration's Jacobian has a smallest singular value far below 1e-6.

    Returns
    -------
    tuple of str, or (nested) lists of tuples for a stack
        A subset of ``("shoulder", "elbow", "wrist")``, empty when ``q`` is regular; for ``q``
        (..., 6), lists nested as its leading axes.

    Examples
    --------
    >>> import urkin
    >>> singularities(urkin.robot("ur5"), [0, -np.pi / 2, 0, -np.pi / 2, 0, 0])
    ('shoulder', 'elbow', 'wrist')
    >>> singularities(urkin.robot("ur5"), [0.1, -1.0, 1.2, -0.3, 0.5, 0.7])
    ()
    """
    return _named(singular_families(robot, q, tol))


def _named(flags: np.ndarray) -> tuple[str, ...] | list:
    """The names of the flagged families of ``flags`` (..., 3): a tuple for one, nested lists
    of tuples with the leading shape for a stack."""
    if flags.ndim == 1:
        return tuple(name for name, flag in zip(SINGULARITIES, flags) if flag)
    return [_named(row) for row in flags]


def manipulability(robot: Robot, q: ArrayLike, part: str = "full") -> np.ndarray | float:
    """Yoshikawa's manipulability ``w = sqrt(det(J Jᵀ))``, zero exactly at singularities.

    Parameters
    ----------
    robot : Robot
    q : array_like, shape (6,) or (N, 6)
    part : {"full", "position"}
        The whole 6×6 Jacobian (then ``w = |det J|``, units mixing m and rad) or its linear
        rows only (``w`` in m³/rad³: the volume of the velocity ellipsoid).

    Returns
    -------
    float or ndarray, shape (N,)

    Examples
    --------
    >>> import urkin
    >>> ur5 = urkin.robot("ur5")
    >>> float(manipulability(ur5, [0, -np.pi / 2, 0, -np.pi / 2, 0, 0]))
    0.0
    """
    choice(part, "part", ("full", "position"))
    J = jacobian(robot, check_joints(q))  # real angles only: complex ones are refused here
    if part == "full":
        return np.abs(np.linalg.det(J)) + 0.0
    if part == "position":
        Jv = J[..., :3, :]
        return np.sqrt(np.maximum(np.linalg.det(Jv @ np.swapaxes(Jv, -1, -2)), 0.0))
    raise ValueError(f"part must be 'full' or 'position'; got {part!r}")


def condition_number(robot: Robot, q: ArrayLike) -> np.ndarray | float:
    """Condition number ``σ_max / σ_min`` of the geometric Jacobian.

    It grows without bound towards a singularity (where rounding leaves ``σ_min`` near 1e-17
    rather than exactly 0).

    Examples
    --------
    >>> import urkin
    >>> ur5 = urkin.robot("ur5")
    >>> bool(condition_number(ur5, [0, -np.pi / 2, 0, -np.pi / 2, 0, 0]) > 1e15)
    True
    >>> round(float(condition_number(ur5, [0.1, -1.0, 1.2, -0.3, 0.5, 0.7])), 1)
    12.2
    """
    sigma = np.linalg.svd(jacobian(robot, check_joints(q)), compute_uv=False)
    with np.errstate(divide="ignore"):
        return sigma[..., 0] / sigma[..., -1]
