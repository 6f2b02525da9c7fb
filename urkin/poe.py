"""Product of exponentials: screw axes, forward kinematics and Jacobians (Modern Robotics).

Conventions are those of Lynch and Park, *Modern Robotics*:

* a screw axis is a 6-vector ``(ω, v)``; for a revolute joint with unit axis ``ω`` through the
  point ``q``, ``v = −ω × q``;
* the screw axes of an n-joint arm are the columns of ``S`` (space frame) or ``B`` (body frame),
  arrays of shape (6, n), Modern Robotics' ``Slist`` and ``Blist``;
* ``M`` is the pose of the end-effector frame at the zero configuration;
* ``T(q) = e^[S1]q1 ⋯ e^[Sn]qn M = M e^[B1]q1 ⋯ e^[Bn]qn``;
* the space Jacobian ``J_s`` and body Jacobian ``J_b`` map joint rates to the twists
  ``(ω, v)`` of the end effector in the space and body frames.

urkin's geometric Jacobian (:func:`urkin.jacobian`) stacks ``[v; ω]`` with ``v`` the velocity of
the end-effector origin; :func:`space_from_geometric` and :func:`geometric_from_space` convert.
Every function takes one configuration ``(n,)`` or a batch ``(N, n)``.
"""

from __future__ import annotations

import functools

import numpy as np
from numpy.typing import ArrayLike

from urkin._inputs import choice, real
from urkin.kinematics import dh_transform, fk, fk_frames
from urkin.robots import Robot
from urkin.transforms import (
    ROTATION_TOLERANCE,
    _core,
    adjoint,
    check_transform,
    inv_transform,
    se3_exp,
    skew,
)

__all__ = [
    "body_screws",
    "fk_body",
    "fk_space",
    "geometric_from_space",
    "jacobian_body",
    "jacobian_space",
    "screw_axis",
    "space_from_geometric",
    "space_screws",
]


def screw_axis(omega: ArrayLike, point: ArrayLike) -> np.ndarray:
    """Screw axis ``(ω, −ω × q)`` of a revolute joint turning about unit axis ``ω`` through ``q``.

    Parameters
    ----------
    omega : array_like, shape (..., 3)
        Unit direction of the joint axis.
    point : array_like, shape (..., 3)
        Any point on the axis, metres.

    Returns
    -------
    ndarray, shape (..., 6)

    Examples
    --------
    >>> screw_axis([0, 0, 1], [0.5, 0, 0])  # a vertical axis through x = 0.5 m
    array([ 0. ,  0. ,  1. ,  0. , -0.5,  0. ])
    """
    w = _core(omega, (3,), "omega")
    q = _core(point, (3,), "point")
    length = np.linalg.norm(w, axis=-1)
    if np.any(np.abs(length - 1.0) > ROTATION_TOLERANCE):
        worst = float(np.max(np.abs(length - 1.0)))
        raise ValueError(
            "omega must be a unit direction (a revolute joint's axis; divide it by its norm): "
            f"|‖omega‖ − 1| = {worst:.3g} > {ROTATION_TOLERANCE:g}"
        )
    try:
        w, q = np.broadcast_arrays(w, q)
    except ValueError:
        raise ValueError(
            f"omega and point must be stacks of matching shape; got {w.shape} and {q.shape}"
        ) from None
    return np.concatenate([w, -np.cross(w, q)], axis=-1) + 0.0


def _frames_at_zero(table: np.ndarray, convention: str) -> np.ndarray:
    links = dh_transform(0.0, table[:, 0], table[:, 1], table[:, 2], convention)
    frames = [np.eye(4)]
    for link in links:
        frames.append(frames[-1] @ link)
    return np.array(frames)


def space_screws(
    robot: Robot | ArrayLike, convention: str = "standard"
) -> tuple[np.ndarray, np.ndarray]:
    """Space-frame screw axes ``S`` and home pose ``M`` of an arm, derived from its DH table.

    Parameters
    ----------
    robot : Robot or array_like, shape (n, 3)
        A UR arm (its base and tool transforms are honoured), or any revolute arm's DH table
        with rows ``(d_i, a_i, α_i)`` (``(d_i, a_{i-1}, α_{i-1})`` in the modified convention).
    convention : {"standard", "modified"}
        Convention of a table (ignored for a Robot, whose tables are standard).

    Returns
    -------
    S : ndarray, shape (6, n)
        One screw axis ``(ω, v)`` per column, in the base (space) frame.
    M : ndarray, shape (4, 4)
        End-effector pose at ``q = 0``.

    Notes
    -----
    In standard DH, joint ``i`` turns about the z axis of frame ``i − 1``; in modified DH,
    about the z axis of frame ``i``.  The screw axis is that axis through that frame's origin.

    Examples
    --------
    >>> import urkin
    >>> S, M = space_screws(urkin.robot("ur5"))
    >>> S[:, 0]  # joint 1: the base z axis through the origin
    array([0., 0., 1., 0., 0., 0.])
    """
    choice(convention, "convention", ("standard", "modified"))
    if isinstance(robot, Robot):
        if convention != "standard":
            raise ValueError(
                "convention='modified' is for a DH table: a Robot's table is standard DH"
            )
        frames = fk_frames(robot, np.zeros(6))
        axes, M = frames[:-1], fk(robot, np.zeros(6))
    else:
        try:
            table = real(robot, "robot")
        except (TypeError, ValueError) as error:
            raise type(error)(
                f"robot must be a urkin Robot or a DH table of rows (d, a, alpha); {error}"
            ) from None
        if table.ndim != 2 or table.shape[1] != 3 or not len(table):
            raise ValueError(
                f"a DH table has rows (d, a, alpha), at least one: shape (n, 3); got {table.shape}"
            )
        frames = _frames_at_zero(table, convention)
        axes = frames[:-1] if convention == "standard" else frames[1:]
        M = frames[-1]
    S = screw_axis(axes[:, :3, 2], axes[:, :3, 3]).T
    return S, M


def body_screws(
    robot: Robot | ArrayLike, convention: str = "standard"
) -> tuple[np.ndarray, np.ndarray]:
    """Body-frame screw axes ``B = Ad(M⁻¹) S`` and home pose ``M`` (see :func:`space_screws`).

    Examples
    --------
    >>> import urkin
    >>> B, M = body_screws(urkin.robot("ur3"))
    >>> B[:, 5]  # the last joint turns about the flange's own z axis
    array([0., 0., 1., 0., 0., 0.])
    """
    S, M = space_screws(robot, convention)
    return adjoint(inv_transform(M)) @ S + 0.0, M


@functools.lru_cache(maxsize=64)
def _checked_home(data: bytes) -> np.ndarray:
    home = check_transform(np.frombuffer(data).reshape(4, 4), name="M").copy()
    home.setflags(write=False)
    return home


@functools.lru_cache(maxsize=64)
def _revolute_pieces(data: bytes, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """Constant matrices ``A_s, A_c, A_t`` of the exponentials of unit-ω screw axes, or None.

    ``e^[A]θ = I + sin θ·A_s + (1 − cos θ)·A_c + θ·A_t`` with ``W = [ω]``:
    ``A_s = [[W, −W²v], 0]``, ``A_c = [[W², Wv], 0]``, ``A_t = [[0, v + W²v], 0]``, so a
    batch costs three multiply-adds per joint instead of a general exponential.
    """
    axes = np.frombuffer(data).reshape(6, n)
    omega, v = axes[:3].T, axes[3:].T
    with np.errstate(over="ignore"):  # an axis of 1e200: not a unit one, not a warning
        lengths = np.linalg.norm(omega, axis=1)
    if not np.allclose(lengths, 1.0, rtol=0, atol=1e-12):
        return None
    W = skew(omega)
    W2 = W @ W
    Wv, W2v = (W @ v[..., None])[..., 0], (W2 @ v[..., None])[..., 0]
    A_s, A_c, A_t = np.zeros((3, n, 4, 4))
    A_s[:, :3, :3], A_s[:, :3, 3] = W, -W2v
    A_c[:, :3, :3], A_c[:, :3, 3] = W2, Wv
    A_t[:, :3, 3] = v + W2v
    for piece in (A_s, A_c, A_t):
        piece.setflags(write=False)
    return A_s, A_c, A_t


def _check(M: ArrayLike | None, screws: ArrayLike, q: ArrayLike, name: str):
    axes = real(screws, name)
    if axes.ndim != 2 or axes.shape[0] != 6:
        raise ValueError(
            f"{name} must have shape (6, n), one screw axis per column; got {axes.shape}"
        )
    axes = np.ascontiguousarray(axes)
    angles = real(q, "q")
    n = axes.shape[1]
    if n == 0:
        raise ValueError(f"{name} must hold at least one screw axis (shape (6, n), n ≥ 1)")
    if angles.shape[-1:] != (n,):
        raise ValueError(
            f"q must have shape ({n},) or (..., {n}) for {n} screw axes; got {angles.shape}"
        )
    if M is None:
        return None, axes, angles
    home = real(M, "M")
    if home.shape != (4, 4):
        raise ValueError(f"M must have shape (4, 4); got {home.shape}")
    return _checked_home(np.ascontiguousarray(home).tobytes()), axes, angles


def _home(M: ArrayLike) -> ArrayLike:
    """``M``, unless it is None (which :func:`_check` takes for "no home pose")."""
    if M is None:
        raise TypeError(
            "M must be the home pose, a (4, 4) transform (space_screws gives it); got None"
        )
    return M


def _moved_screw(T: np.ndarray, screw: np.ndarray) -> np.ndarray:
    """``Ad_T @ screw`` for a batch of transforms: ``(R ω, p × R ω + R v)``."""
    R, p = T[..., :3, :3], T[..., :3, 3]
    w, v = R @ screw[:3], R @ screw[3:]
    px, py, pz = p[..., 0], p[..., 1], p[..., 2]
    wx, wy, wz = w[..., 0], w[..., 1], w[..., 2]
    lever = np.stack([py * wz - pz * wy, pz * wx - px * wz, px * wy - py * wx], axis=-1)
    return np.concatenate([w, lever + v], axis=-1)


def _exponentials(axes: np.ndarray, angles: np.ndarray, name: str) -> np.ndarray:
    """``e^[A_i] q_i`` for every joint (``name``: the axes' argument): shape (..., n, 4, 4)."""
    pieces = _revolute_pieces(axes.tobytes(), axes.shape[1])
    if pieces is None:  # prismatic or non-unit axes: the general exponential
        try:
            return se3_exp(angles[..., :, None] * axes.T)
        except ValueError as exc:  # se3_exp names its own argument, a product of ours
            raise ValueError(
                f"{name} times q is too large to exponentiate (each {name}_i q_i must be a "
                f"twist of a few turns at most): {exc}"
            ) from None
    A_s, A_c, A_t = pieces
    theta = angles[..., None, None]
    return np.eye(4) + np.sin(theta) * A_s + (1.0 - np.cos(theta)) * A_c + theta * A_t


def fk_space(M: ArrayLike, S: ArrayLike, q: ArrayLike) -> np.ndarray:
    """Forward kinematics in the space form: ``T = e^[S1]q1 ⋯ e^[Sn]qn M``.

    Parameters
    ----------
    M : array_like, shape (4, 4)
        End-effector pose at ``q = 0``.
    S : array_like, shape (6, n)
        Space-frame screw axes, one per column.
    q : array_like, shape (n,) or (N, n)
        Joint angles in radians.

    Returns
    -------
    ndarray, shape (4, 4) or (N, 4, 4)

    Examples
    --------
    >>> import urkin
    >>> ur5 = urkin.robot("ur5")
    >>> S, M = space_screws(ur5)
    >>> q = [0.1, -1.0, 1.2, -0.3, 0.5, 0.7]
    >>> np.allclose(fk_space(M, S, q), urkin.fk(ur5, q))
    True
    """
    home, axes, angles = _check(_home(M), S, q, "S")
    E = _exponentials(axes, angles, "S")
    T = E[..., 0, :, :]
    for i in range(1, axes.shape[1]):
        T = T @ E[..., i, :, :]
    return T @ home


def fk_body(M: ArrayLike, B: ArrayLike, q: ArrayLike) -> np.ndarray:
    """Forward kinematics in the body form: ``T = M e^[B1]q1 ⋯ e^[Bn]qn``.

    Parameters
    ----------
    M : array_like, shape (4, 4)
        End-effector pose at ``q = 0``.
    B : array_like, shape (6, n)
        Body-frame screw axes, one per column.
    q : array_like, shape (n,) or (N, n)
        Joint angles in radians.

    Returns
    -------
    ndarray, shape (4, 4) or (N, 4, 4)

    Examples
    --------
    >>> import urkin
    >>> B, M = body_screws(urkin.robot("ur3"))
    >>> fk_body(M, B, np.zeros((5, 6))).shape
    (5, 4, 4)
    """
    home, axes, angles = _check(_home(M), B, q, "B")
    E = _exponentials(axes, angles, "B")
    T = np.broadcast_to(home, (*angles.shape[:-1], 4, 4))
    for i in range(axes.shape[1]):
        T = T @ E[..., i, :, :]
    return T


def jacobian_space(S: ArrayLike, q: ArrayLike) -> np.ndarray:
    """Space Jacobian: column ``i`` is ``Ad(e^[S1]q1 ⋯ e^[S(i-1)]q(i-1)) S_i``.

    It maps joint rates to the end effector's twist ``(ω, v_s)`` in the space frame, where
    ``v_s`` is the velocity of the point of the body at the space frame's origin.

    Parameters
    ----------
    S : array_like, shape (6, n)
    q : array_like, shape (n,) or (N, n)

    Returns
    -------
    ndarray, shape (6, n) or (N, 6, n)

    Examples
    --------
    >>> import urkin
    >>> S, M = space_screws(urkin.robot("ur5"))
    >>> np.allclose(jacobian_space(S, np.zeros(6)), S)  # at q = 0 the columns are the axes
    True
    """
    _, axes, angles = _check(None, S, q, "S")
    E = _exponentials(axes, angles, "S")
    n = axes.shape[1]
    J = np.empty((*angles.shape[:-1], 6, n))
    J[..., :, 0] = axes[:, 0]
    T = E[..., 0, :, :]
    for i in range(1, n):
        J[..., :, i] = _moved_screw(T, axes[:, i])
        T = T @ E[..., i, :, :]
    return J


def jacobian_body(B: ArrayLike, q: ArrayLike) -> np.ndarray:
    """Body Jacobian: column ``i`` is ``Ad(e^−[Bn]qn ⋯ e^−[B(i+1)]q(i+1)) B_i``.

    It maps joint rates to the end effector's twist ``(ω_b, v_b)`` in its own frame.

    Parameters
    ----------
    B : array_like, shape (6, n)
    q : array_like, shape (n,) or (N, n)

    Returns
    -------
    ndarray, shape (6, n) or (N, 6, n)

    Examples
    --------
    >>> import urkin
    >>> B, M = body_screws(urkin.robot("ur5"))
    >>> jacobian_body(B, np.zeros((3, 6))).shape
    (3, 6, 6)
    """
    _, axes, angles = _check(None, B, q, "B")
    E_inverse = _exponentials(axes, -angles, "B")
    n = axes.shape[1]
    J = np.empty((*angles.shape[:-1], 6, n))
    J[..., :, n - 1] = axes[:, n - 1]
    T = E_inverse[..., n - 1, :, :]
    for i in range(n - 2, -1, -1):
        J[..., :, i] = _moved_screw(T, axes[:, i])
        T = T @ E_inverse[..., i, :, :]
    return J


def _jacobian_and_origin(J: ArrayLike, name: str, T_base_tool: ArrayLike):
    """A checked Jacobian (..., 6, n) and the tool origins (..., 3) of checked rigid poses."""
    matrix = real(J, name)
    if matrix.ndim < 2 or matrix.shape[-2] != 6:
        raise ValueError(f"{name} must have shape (6, n) or (..., 6, n); got {matrix.shape}")
    T = check_transform(T_base_tool, name="T_base_tool")
    if T.shape[:-2] not in ((), matrix.shape[:-2]):
        raise ValueError(
            f"T_base_tool must be one pose or one per Jacobian {matrix.shape[:-2]}; got {T.shape}"
        )
    return matrix, T[..., :3, 3]


def space_from_geometric(J: ArrayLike, T_base_tool: ArrayLike) -> np.ndarray:
    """Space Jacobian ``(ω; v_s)`` from a geometric Jacobian ``[v; ω]`` of the tool origin.

    ``v_s = v + p × ω`` with ``p`` the tool origin: the velocity of the body point at the base
    origin rather than at the tool.

    Parameters
    ----------
    J : array_like, shape (..., 6, n)
        Geometric Jacobian, rows ``[v; ω]`` (:func:`urkin.jacobian`).
    T_base_tool : array_like, shape (..., 4, 4)
        The tool pose the Jacobian belongs to (:func:`urkin.fk`).

    Returns
    -------
    ndarray, shape (..., 6, n)

    Examples
    --------
    >>> import urkin
    >>> ur5, q = urkin.robot("ur5"), [0.3, -1.1, 0.9, 0.2, -0.6, 1.4]
    >>> S, M = space_screws(ur5)
    >>> J_s = space_from_geometric(urkin.jacobian(ur5, q), urkin.fk(ur5, q))
    >>> np.allclose(J_s, jacobian_space(S, q))
    True
    """
    geometric, p = _jacobian_and_origin(J, "J", T_base_tool)
    Jv, Jw = geometric[..., :3, :], geometric[..., 3:, :]
    return np.concatenate([Jw, Jv + skew(p) @ Jw], axis=-2)


def geometric_from_space(J_space: ArrayLike, T_base_tool: ArrayLike) -> np.ndarray:
    """Geometric Jacobian ``[v; ω]`` of the tool origin from a space Jacobian ``(ω; v_s)``.

    The inverse of :func:`space_from_geometric`: ``v = v_s − p × ω``.

    Examples
    --------
    >>> import urkin
    >>> ur3, q = urkin.robot("ur3"), np.zeros(6)
    >>> S, M = space_screws(ur3)
    >>> np.allclose(geometric_from_space(jacobian_space(S, q), M), urkin.jacobian(ur3, q))
    True
    """
    space, p = _jacobian_and_origin(J_space, "J_space", T_base_tool)
    Jw, Jvs = space[..., :3, :], space[..., 3:, :]
    return np.concatenate([Jvs - skew(p) @ Jw, Jw], axis=-2)
