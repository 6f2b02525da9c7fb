"""The UR3 lab's closed-form IK for a gripper pointing down (seed report 004), fixed.

The lab places a UR3 on a table and asks for joint angles that put a suction gripper at
``(x_w, y_w, z_w)`` in the table ("world") frame, pointing straight down, turned by ``yaw_w``
about the vertical.  Its link table (metres) is

======  ======  ======  ======  ======  ======  ======  ======  ======  ======
L1      L2      L3      L4      L5      L6      L7      L8      L9      L10
0.152   0.120   0.244   0.093   0.213   0.083   0.083   0.082   0.0535  0.059
======  ======  ======  ======  ======  ======  ======  ======  ======  ======

and its robot is the UR DH model with ``d1 = L1``, ``a2 = −L3``, ``a3 = −L5``,
``d4 = L2 − L4 + L6``, ``d5 = L7``, ``d6 = L8``, based at ``(−0.15, 0.15, 0.01)`` m in the world
frame, with the gripper at ``(−L9, 0, L10)`` in the flange frame (:func:`lab_robot`).

The report's formulas, as printed, mix metres and millimetres and fail behind the base: its
``θ1 = arctan(y/x) − …`` loses the quadrant when the wrist point has ``x < 0``, and its
``r = √(x² + y²)`` loses the sign of the reach when the wrist point lies behind the base axis.
With ``atan2`` and the signed ``r = x cos θ1 + y sin θ1`` every reachable target round-trips, and
the result is exactly one branch of :func:`urkin.ik_analytic` (shoulder "+", θ5 = −π/2, elbow
θ3 > 0).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from urkin.kinematics import fk
from urkin.robots import Robot
from urkin.transforms import make_transform, rot_z, wrap_angles

__all__ = ["LAB_LINKS", "fk_lab", "ik_lab", "lab_robot"]

#: The lab's link lengths L1 … L10 in metres.
LAB_LINKS: tuple[float, ...] = (
    0.152,
    0.120,
    0.244,
    0.093,
    0.213,
    0.083,
    0.083,
    0.082,
    0.0535,
    0.059,
)

#: Position of the robot's base (DH frame 0) in the table's world frame, metres.
LAB_BASE_IN_WORLD = (-0.15, 0.15, 0.01)

#: Lab angles = UR controller angles − this (the lab's zero stretches the arm along +x).
LAB_OFFSET = np.array([np.pi, 0.0, 0.0, -np.pi / 2, 0.0, 0.0])


def lab_robot() -> Robot:
    """The lab's UR3: its DH lengths, its place on the table, and its gripper as the tool.

    The tool frame sits at the gripper tip with z pointing down (along the flange's z) and x
    along the gripper's yaw direction, so the tool pose's yaw is the lab's ``yaw_w``.

    Examples
    --------
    >>> lab_robot().lengths
    (0.152, -0.244, -0.213, 0.11, 0.083, 0.082)
    """
    L1, L2, L3, L4, L5, L6, L7, L8, L9, L10 = LAB_LINKS
    return Robot(
        "UR3 (lab)",
        L1,
        -L3,
        -L5,
        round(L2 - L4 + L6, 12),
        L7,
        L8,
        base=make_transform(p=LAB_BASE_IN_WORLD),
        tool=make_transform(rot_z(np.pi), [-L9, 0.0, L10]),
        source="seed report 004: a UR3 lab sheet (link table L1 … L10)",
        notes="world frame = table; tool = suction gripper pointing down",
    )


def fk_lab(q: ArrayLike) -> np.ndarray:
    """The lab's forward kinematics: gripper ``(x_w, y_w, z_w, yaw_w)`` for UR joint angles.

    ``yaw_w`` is the angle of the gripper's x axis about the world's vertical; it is meaningful
    when the gripper points down (θ5 = −π/2 in the lab's branch).

    Examples
    --------
    >>> fk_lab(ik_lab(0.25, 0.05, 0.10, 0.3)).round(12) + 0.0
    array([0.25, 0.05, 0.1 , 0.3 ])
    """
    T = fk(lab_robot(), q)
    yaw = np.arctan2(T[..., 1, 0], T[..., 0, 0])
    return np.concatenate([T[..., :3, 3], yaw[..., None]], axis=-1)


def ik_lab(x_w: ArrayLike, y_w: ArrayLike, z_w: ArrayLike, yaw_w: ArrayLike) -> np.ndarray:
    """The lab's closed-form IK, fixed: UR joint angles for a gripper pointing down.

    Parameters
    ----------
    x_w, y_w, z_w : float or array_like
        Gripper tip in the table frame, metres.
    yaw_w : float or array_like
        Gripper yaw about the vertical, radians.

    Returns
    -------
    ndarray, shape (6,) or (N, 6)
        UR controller angles (wrapped to (−π, π]): the branch with shoulder "+",
        θ5 = −π/2 and elbow θ3 > 0.

    Raises
    ------
    ValueError
        If a target is out of reach; the message says by how much.

    Examples
    --------
    >>> q = ik_lab(-0.05, 0.35, 0.08, 1.0)  # behind the base: the printed formulas fail here
    >>> fk_lab(q).round(12) + 0.0
    array([-0.05,  0.35,  0.08,  1.  ])
    """
    L1, L2, L3, L4, L5, L6, L7, L8, L9, L10 = LAB_LINKS
    offset = L2 - L4 + L6  # 0.110 m: the sideways offset of the wrist from the shoulder plane
    x, y, z, yaw = np.broadcast_arrays(
        *(np.asarray(v, dtype=float) for v in (x_w, y_w, z_w, yaw_w))
    )
    bx, by, bz = LAB_BASE_IN_WORLD
    # the gripper in the base frame, then the wrist centre under the flange
    x, y, z = x - bx, y - by, z - bz
    xc, yc = x - L9 * np.cos(yaw), y - L9 * np.sin(yaw)
    radius = np.hypot(xc, yc)
    too_close = radius < offset
    with np.errstate(invalid="ignore", divide="ignore"):
        theta1 = np.arctan2(yc, xc) - np.arcsin(np.clip(offset / radius, -1.0, 1.0))
        theta6 = np.pi / 2 + theta1 - yaw
        z3 = z + L8 + L10
        x1, y1 = xc - L7 * np.cos(theta1), yc - L7 * np.sin(theta1)
        x3, y3 = x1 + offset * np.sin(theta1), y1 - offset * np.cos(theta1)
        r = x3 * np.cos(theta1) + y3 * np.sin(theta1)  # signed: negative behind the base axis
        h = z3 - L1
        reach = np.hypot(r, h)
        cos3 = (r * r + h * h - L3 * L3 - L5 * L5) / (2 * L3 * L5)
        out = too_close | (np.abs(cos3) > 1.0 + 1e-12)
        theta3 = np.arccos(np.clip(cos3, -1.0, 1.0))
        theta2 = -(
            np.arctan2(h, r)
            + np.arccos(np.clip((L5 * L5 - L3 * L3 - reach * reach) / (-2 * L3 * reach), -1, 1))
        )
    if np.any(out):
        i = int(np.flatnonzero(out.ravel())[0])
        if too_close.ravel()[i]:
            why = (
                f"its wrist point is {radius.ravel()[i]:.4f} m from the base axis, less than "
                f"the {offset:.3f} m offset"
            )
        else:
            excess = (
                reach.ravel()[i] - (L3 + L5)
                if cos3.ravel()[i] > 1
                else abs(L3 - L5) - (reach.ravel()[i])
            )
            why = f"the arm would have to stretch {excess:.4f} m further than it can"
        raise ValueError(f"unreachable gripper target ({np.sum(out)} of {out.size}): {why}")
    theta4 = -theta2 - theta3
    lab = np.stack(
        [theta1, theta2, theta3, theta4, np.full_like(theta1, -np.pi / 2), theta6], axis=-1
    )
    return wrap_angles(lab + LAB_OFFSET)
