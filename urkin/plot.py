"""Drawing UR arms with matplotlib: 3D stick figures, frame triads and a pose panel.

Imports matplotlib, so ``import urkin`` does not load this module; use
``import urkin.plot``.  Every function draws on an axes you pass (or a new one) and returns
what it drew, so lessons can compose figures.  Lengths are in metres; the panel shows angles
in degrees, the only place urkin uses them.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from numpy.typing import ArrayLike

from urkin.kinematics import fk_frames
from urkin.robots import Robot
from urkin.transforms import check_transform, rotation_to_rpy

__all__ = ["axes3d", "draw_ellipsoid", "draw_frame", "draw_robot", "pose_text", "show_robot"]

#: Colours of the x, y and z axes of a frame triad (red, green, blue).
AXIS_COLOURS = ("tab:red", "tab:green", "tab:blue")


def axes3d(
    ax=None,
    *,
    center: ArrayLike = (0.0, 0.0, 0.3),
    half_width: float = 0.5,
    title: str | None = None,
    figsize: tuple[float, float] = (6.0, 6.0),
):
    """A 3D axes with equal scales on x, y and z, labelled in metres.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.Axes3D, optional
        Axes to set up; a new figure is made if omitted.
    center : array_like, shape (3,)
        Centre of the cube shown, metres.
    half_width : float
        Half the side of the cube shown, metres.
    title : str, optional
    figsize : tuple of float
        Size of a new figure, inches.

    Returns
    -------
    mpl_toolkits.mplot3d.Axes3D
    """
    if ax is None:
        fig = plt.figure(figsize=figsize)
        ax = fig.add_subplot(projection="3d")
    c = np.asarray(center, dtype=float)
    for axis, setter in zip(range(3), (ax.set_xlim, ax.set_ylim, ax.set_zlim)):
        setter(c[axis] - half_width, c[axis] + half_width)
    ax.set_box_aspect((1.0, 1.0, 1.0))
    ax.plot([c[0] - half_width, c[0] + half_width], [0, 0], [0, 0], color="0.8", linewidth=0.8)
    ax.plot([0, 0], [c[1] - half_width, c[1] + half_width], [0, 0], color="0.8", linewidth=0.8)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    if title:
        ax.set_title(title)
    return ax


def draw_frame(
    ax,
    T: ArrayLike,
    length: float = 0.05,
    label: str | None = None,
    linewidth: float = 2.0,
    tips: bool = False,
):
    """Draw a frame triad: its x, y and z axes in red, green and blue.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.Axes3D
    T : array_like, shape (4, 4)
        Pose of the frame.
    length : float
        Length of each axis arrow, metres.
    label : str, optional
        Text written at the frame's origin.
    linewidth : float
    tips : bool
        Write "x", "y" and "z" at the arrow tips.

    Returns
    -------
    list
        The matplotlib artists.
    """
    pose = check_transform(T)
    origin = pose[:3, 3]
    artists = []
    for axis, colour in enumerate(AXIS_COLOURS):
        tip = origin + length * pose[:3, axis]
        artists += ax.plot(*np.column_stack([origin, tip]), color=colour, linewidth=linewidth)
        if tips:
            artists.append(ax.text(*tip, "xyz"[axis], color=colour, fontsize=9))
    if label:
        artists.append(ax.text(*origin, f" {label}", fontsize=8))
    return artists


def draw_ellipsoid(
    ax,
    center: ArrayLike,
    axes: ArrayLike,
    scale: float = 1.0,
    color="tab:blue",
    alpha: float = 0.3,
    resolution: int = 24,
):
    """Draw the ellipsoid ``{center + scale · A u : |u| ≤ 1}`` as a surface.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.Axes3D
    center : array_like, shape (3,)
        Its centre, metres.
    axes : array_like, shape (3, 3)
        ``A``: its semi-axes as columns (for a velocity ellipsoid, ``U Σ`` from the singular
        value decomposition ``J_v = U Σ Vᵀ``).
    scale : float
        Metres of drawing per unit of the semi-axes (m per m/s, m per N…).
    color, alpha
        Surface colour and opacity.
    resolution : int
        Grid lines around and from pole to pole.

    Returns
    -------
    The matplotlib surface.
    """
    A = scale * np.asarray(axes, dtype=float)
    u, v = np.meshgrid(
        np.linspace(0, 2 * np.pi, resolution), np.linspace(0, np.pi, resolution // 2 + 1)
    )
    sphere = np.stack([np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v)])
    x, y, z = (A @ sphere.reshape(3, -1) + np.asarray(center, dtype=float)[:, None]).reshape(
        3, *u.shape
    )
    return ax.plot_surface(x, y, z, color=color, alpha=alpha, linewidth=0)


def draw_robot(
    ax,
    robot: Robot,
    q: ArrayLike,
    *,
    frames: bool = True,
    frame_length: float = 0.04,
    color: str = "0.35",
    label: str | None = None,
    alpha: float = 1.0,
    linewidth: float = 4.0,
):
    """Draw the arm as a stick figure through the origins of its DH frames.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.Axes3D
    robot : Robot
    q : array_like, shape (6,)
        Joint angles in radians.
    frames : bool
        Draw the triad of every DH frame (base, 1 … 6).
    frame_length : float
        Length of the triad arrows, metres.
    color, label, alpha, linewidth
        Style of the links; ``label`` goes into the legend.

    Returns
    -------
    list
        The matplotlib artists.
    """
    poses = fk_frames(robot, q)
    if poses.ndim != 3:
        raise ValueError("draw_robot draws one configuration: q must have shape (6,)")
    points = poses[:, :3, 3]
    artists = ax.plot(
        *points.T, "-o", color=color, linewidth=linewidth, markersize=5, alpha=alpha, label=label
    )
    if frames:
        for pose in poses:
            artists += draw_frame(ax, pose, frame_length, linewidth=1.5)
    return artists


def pose_text(T: ArrayLike) -> str:
    """The info panel: position in metres and roll–pitch–yaw in degrees.

    Examples
    --------
    >>> print(pose_text(np.eye(4)))
    position (m)     x  0.000   y  0.000   z  0.000
    roll/pitch/yaw   r    0.0°  p    0.0°  y    0.0°
    """
    pose = check_transform(T)
    x, y, z = np.round(pose[:3, 3], 3) + 0.0  # + 0.0: no "-0.000"
    roll, pitch, yaw = np.round(np.degrees(rotation_to_rpy(pose[:3, :3])), 1) + 0.0
    return (
        f"position (m)     x {x:6.3f}   y {y:6.3f}   z {z:6.3f}\n"
        f"roll/pitch/yaw   r {roll:6.1f}°  p {pitch:6.1f}°  y {yaw:6.1f}°"
    )


def show_robot(robot: Robot, q: ArrayLike, *, title: str | None = None, ax=None, **style):
    """A complete figure: the arm, its frames, and the flange pose in a panel.

    Parameters
    ----------
    robot : Robot
    q : array_like, shape (6,)
    title : str, optional
        Figure title (the robot's name and q in degrees by default).
    ax : mpl_toolkits.mplot3d.Axes3D, optional
    **style
        Passed to :func:`draw_robot`.

    Returns
    -------
    mpl_toolkits.mplot3d.Axes3D
    """
    q = np.asarray(q, dtype=float)
    reach = abs(robot.a2) + abs(robot.a3) + robot.d4 + robot.d6
    if title is None:
        degrees = ", ".join(f"{v:.0f}" for v in np.degrees(q) + 0.0)
        title = f"{robot.name} at q = [{degrees}]°"
    ax = axes3d(ax, center=(0.0, 0.0, robot.d1 + 0.3 * reach), half_width=0.75 * reach, title=title)
    draw_robot(ax, robot, q, **style)
    T = fk_frames(robot, q)[-1]
    ax.text2D(
        0.0,
        0.97,
        pose_text(T),
        verticalalignment="top",
        transform=ax.transAxes,
        family="monospace",
        fontsize=8,
        bbox={"facecolor": "white", "alpha": 0.8},
    )
    return ax
