"""Drawing UR arms with matplotlib: 3D stick figures, frame triads, a pose panel and the
course's figures.

Imports matplotlib, so ``import urkin`` does not load this module; use
``import urkin.plot``.  Lengths are in metres; the panel shows angles in degrees, the only
place urkin uses them.

Two kinds of functions live here:

* building blocks (:func:`axes3d`, :func:`draw_frame`, :func:`draw_robot`, :func:`draw_arms`,
  :func:`draw_ellipsoid`, …) draw on an axes you pass and return what they drew, so figures
  can be composed;
* figure functions (``*_figure``, :func:`robot_panels`, the ``lab_*`` views) draw one whole
  figure of the course from data a lesson computed, and return the
  :class:`~matplotlib.figure.Figure`.  The lessons compute the kinematics; these functions
  only draw it.

Every 3D view that shows an arm says which frame it is drawn in (a note under it, see
:func:`frame_note`), keeps x, y and z at one scale, and is oriented so that its
axis labels read normally: the z label always reads upwards, and the views chosen here keep
x increasing to the right.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import ListedColormap, LogNorm
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Arc, Circle, Patch, Wedge
from matplotlib.ticker import MaxNLocator
from numpy.typing import ArrayLike

from urkin.kinematics import check_joints, fk_frames
from urkin.robots import Robot, check_robot
from urkin.tracking_report import TrackingReport
from urkin.transforms import check_transform, make_transform, rotation_to_rpy

__all__ = [
    "AXIS_COLOURS",
    "BLOCK_COLOURS",
    "OBSTACLE_COLOUR",
    "Animation",
    "animate",
    "animate_plan",
    "animate_task",
    "arms_figure",
    "axes3d",
    "convergence_figure",
    "cspace_figure",
    "draw_angle_arc",
    "draw_arms",
    "draw_ellipsoid",
    "draw_ellipsoid_arms",
    "draw_frame",
    "draw_reference_axes",
    "draw_robot",
    "draw_scene",
    "draw_spheres",
    "draw_world",
    "edge_clearance_figure",
    "ellipsoid_panels",
    "entry_error_maps",
    "error_maps_figure",
    "frame_note",
    "goal_map_figure",
    "grasp_yaws_figure",
    "jacobian_columns_figure",
    "joint_paths_figure",
    "lab_elbows_figure",
    "lab_scene",
    "lab_side_view",
    "lab_top_view",
    "manipulability_figure",
    "pose_text",
    "robot_panels",
    "rotation_steps_figure",
    "show_robot",
    "signed_distance_figure",
    "singular_families_figure",
    "solver_runs_figure",
    "sphere_models_figure",
    "square_traces_figure",
    "step_size_figure",
    "time_scaling_figure",
    "tracking_report_figure",
    "world_figure",
]

#: Colours of the x, y and z axes of a frame triad (red, green, blue).
AXIS_COLOURS = ("tab:red", "tab:green", "tab:blue")

#: The frame urkin's poses are given in when a robot has no base transform.
BASE_FRAME = "base frame {0}"


# ---------------------------------------------------------------------------------------------
# building blocks
# ---------------------------------------------------------------------------------------------


def _reach(robot: Robot) -> float:
    """A length that covers the arm in any configuration, metres."""
    return abs(robot.a2) + abs(robot.a3) + robot.d4 + robot.d6


def _robot_frame(robot: Robot) -> str:
    """Name of the frame :func:`fk_frames` gives this robot's poses in."""
    base = robot.base
    if base is None or np.array_equal(base, np.eye(4)):
        return BASE_FRAME
    return "world frame (robot.base places the base frame {0} in it)"


def frame_note(ax, frame: str, *, units: str = "metres"):
    """Say, just below a 3D axes, on the left, which frame it is drawn in.

    Below the axes, the note cannot run into the axis labels, whatever the view; a figure
    with constrained layout makes room for it.  Called again on the same axes, it replaces
    the note rather than adding a second one.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.Axes3D
    frame : str
        The frame's name, e.g. ``"base frame {0}"`` or ``"table frame"``.
    units : str
        Units of the axes.

    Returns
    -------
    matplotlib.text.Text

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> ax = axes3d()
    >>> frame_note(ax, "table frame").get_text()
    'drawn in the table frame, lengths in metres'
    >>> plt.close(ax.figure)
    """
    text = f"drawn in the {frame}, lengths in {units}"
    note = getattr(ax, "_urkin_frame_note", None)
    if note is not None:
        note.set_text(text)
        return note
    note = ax.text2D(
        0.0,
        -0.005,
        text,
        transform=ax.transAxes,
        ha="left",
        va="top",
        fontsize=9,
        color="0.25",
    )
    ax._urkin_frame_note = note
    return note


def axes3d(
    ax=None,
    *,
    center: ArrayLike = (0.0, 0.0, 0.3),
    half_width: float = 0.5,
    title: str | None = None,
    figsize: tuple[float, float] = (7.0, 7.0),
    frame: str | None = None,
    view: tuple[float, float] | None = None,
):
    """A 3D axes with equal scales on x, y and z, labelled in metres.

    At most six ticks per axis, so that tick labels do not run into each other, and the z
    label always reads upwards (matplotlib would turn it to read downwards in some views).

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
    frame : str, optional
        The frame the view is drawn in, written in a corner by :func:`frame_note`.
        :func:`draw_robot` writes the base frame if this is not given.
    view : tuple of float, optional
        ``(elevation, azimuth)`` in degrees, as for ``view_init``.

    Returns
    -------
    mpl_toolkits.mplot3d.Axes3D

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> ax = axes3d(center=(0.0, 0.0, 0.0), half_width=1.0, title="a cube")
    >>> ax.get_xlim(), ax.get_zlabel(), ax.get_title()
    ((np.float64(-1.0), np.float64(1.0)), 'z (m)', 'a cube')
    >>> plt.close(ax.figure)
    """
    if ax is None:
        fig = plt.figure(figsize=figsize, layout="constrained")
        ax = fig.add_subplot(projection="3d")
    c = np.asarray(center, dtype=float)
    for axis, setter in zip(range(3), (ax.set_xlim, ax.set_ylim, ax.set_zlim)):
        setter(c[axis] - half_width, c[axis] + half_width)
    ax.set_box_aspect((1.0, 1.0, 1.0))
    ax.set_facecolor("none")  # a neighbour's labels may reach into this axes: do not hide them
    ax.plot([c[0] - half_width, c[0] + half_width], [0, 0], [0, 0], color="0.8", linewidth=0.8)
    ax.plot([0, 0], [c[1] - half_width, c[1] + half_width], [0, 0], color="0.8", linewidth=0.8)
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(nbins=5, steps=[1, 2, 2.5, 5, 10]))
    ax.tick_params(labelsize=9)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.zaxis.set_rotate_label(False)
    ax.set_zlabel("z (m)", rotation=90)
    if title:
        ax.set_title(title)
    if view is not None:
        ax.view_init(*view)
    if frame:
        frame_note(ax, frame)
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

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> ax = axes3d()
    >>> len(draw_frame(ax, np.eye(4), 0.1, label="base", tips=True))  # 3 lines, 4 texts
    7
    >>> plt.close(ax.figure)
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
        artists.append(ax.text(*origin, f" {label}", fontsize=9))
    return artists


def draw_reference_axes(
    ax,
    length: float = 1.0,
    *,
    names: str = "XYZ",
    color: str = "0.6",
    label: str | None = "fixed axes",
):
    """Grey dashed X, Y and Z axes of a fixed reference frame, with capital letters.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.Axes3D
    length : float
        Length of each axis, metres.
    names : str
        The three letters written at the tips.
    color : str
    label : str, optional
        Legend entry (given to the first axis only).

    Returns
    -------
    list
        The matplotlib artists.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> ax = axes3d(center=(0.0, 0.0, 0.0), half_width=1.0)
    >>> len(draw_reference_axes(ax))  # three lines and three letters
    6
    >>> plt.close(ax.figure)
    """
    artists = []
    for axis, name in enumerate(names):
        tip = np.zeros(3)
        tip[axis] = length
        artists += ax.plot(
            *np.column_stack([np.zeros(3), tip]),
            color=color,
            linestyle="--",
            linewidth=1.0,
            label=label if axis == 0 else None,
        )
        artists.append(ax.text(*(1.08 * tip), name, color="0.45", fontsize=9))
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

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> ax = axes3d()
    >>> surface = draw_ellipsoid(ax, (0.0, 0.0, 0.3), np.diag([0.2, 0.1, 0.05]))
    >>> plt.close(ax.figure)
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
    frame_length: float | None = None,
    color: str = "0.35",
    label: str | None = None,
    alpha: float = 1.0,
    linewidth: float = 4.0,
    frame: str | bool = True,
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
    frame_length : float, optional
        Length of the triad arrows, metres; an eighth of the arm's reach by default, so the
        arrows stay visible on any arm.
    color, label, alpha, linewidth
        Style of the links; ``label`` goes into the legend.
    frame : str or bool
        Which frame the axes are in, for :func:`frame_note`: ``True`` names the robot's
        base frame {0} (or its world frame, if it has a base transform) unless the axes
        already carry a note; a string names another frame; ``False`` writes nothing.

    Returns
    -------
    list
        The matplotlib artists.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import urkin
    >>> ax = axes3d()
    >>> artists = draw_robot(ax, urkin.robot("UR3"), np.zeros(6), frames=False)
    >>> len(artists), ax._urkin_frame_note.get_text()
    (1, 'drawn in the base frame {0}, lengths in metres')
    >>> plt.close(ax.figure)
    """
    poses = fk_frames(check_robot(robot), check_joints(q))
    if poses.ndim != 3:
        raise ValueError("draw_robot draws one configuration: q must have shape (6,)")
    points = poses[:, :3, 3]
    artists = ax.plot(
        *points.T, "-o", color=color, linewidth=linewidth, markersize=5, alpha=alpha, label=label
    )
    if frames:
        length = 0.125 * _reach(robot) if frame_length is None else frame_length
        for pose in poses:
            artists += draw_frame(ax, pose, length, linewidth=1.8)
    if isinstance(frame, str):
        frame_note(ax, frame)
    elif frame and getattr(ax, "_urkin_frame_note", None) is None:
        frame_note(ax, _robot_frame(robot))
    return artists


def draw_arms(
    ax,
    robot: Robot,
    arms: Sequence[tuple[ArrayLike, str, str | None]],
    *,
    linewidth: float = 3.0,
    frames: bool = False,
    frame: str | bool = True,
):
    """Draw several configurations of one arm, each in its own colour.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.Axes3D
    robot : Robot
    arms : sequence of tuple
        Each ``(q, colour, label)``: joint angles (radians, shape (6,)), line colour and legend
        entry (or None).
    linewidth : float
    frames : bool
        Draw the DH frame triads too.
    frame : str or bool
        The frame note, as for :func:`draw_robot`.

    Returns
    -------
    list
        The matplotlib artists.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import urkin
    >>> ax = axes3d()
    >>> arms = [(np.zeros(6), "tab:blue", "q = 0"), (np.full(6, 0.3), "tab:red", None)]
    >>> len(draw_arms(ax, urkin.robot("UR3"), arms))
    2
    >>> plt.close(ax.figure)
    """
    artists = []
    for q, colour, label in arms:
        artists += draw_robot(
            ax, robot, q, frames=frames, color=colour, label=label, linewidth=linewidth, frame=frame
        )
    return artists


def pose_text(T: ArrayLike) -> str:
    """The info panel: position in metres and roll–pitch–yaw in degrees.

    Examples
    --------
    >>> print(pose_text(np.eye(4)))
    position (m)     x  0.000   y  0.000   z  0.000
    roll/pitch/yaw   r    0.0°  p    0.0°  y    0.0°
    >>> flip = np.diag([-1.0, -1.0, 1.0, 1.0])  # a half turn about z, yaw ±180°
    >>> flip[0, 1], flip[1, 0] = 1e-17, -1e-17  # round-off on either side of ±π
    >>> pose_text(flip) == pose_text(np.diag([-1.0, -1.0, 1.0, 1.0]))
    True
    """
    pose = check_transform(T)
    if pose.shape != (4, 4):
        raise ValueError(f"pose_text shows one pose: T must have shape (4, 4); got {pose.shape}")
    x, y, z = np.round(pose[:3, 3], 3) + 0.0  # + 0.0: no "-0.000"
    angles = np.round(np.degrees(rotation_to_rpy(pose[:3, :3])), 1) + 0.0
    # a half turn prints as 180.0 whichever side of ±π round-off put it (atan2 gives either)
    roll, pitch, yaw = np.where(angles == -180.0, 180.0, angles)
    return (
        f"position (m)     x {x:6.3f}   y {y:6.3f}   z {z:6.3f}\n"
        f"roll/pitch/yaw   r {roll:6.1f}°  p {pitch:6.1f}°  y {yaw:6.1f}°"
    )


def show_robot(
    robot: Robot,
    q: ArrayLike,
    *,
    title: str | None = None,
    ax=None,
    figsize: tuple[float, float] = (7.0, 7.0),
    center: ArrayLike | None = None,
    half_width: float | None = None,
    **style,
):
    """A complete view: the arm, its frames, and the flange pose in a panel.

    Parameters
    ----------
    robot : Robot
    q : array_like, shape (6,)
    title : str, optional
        Axes title (the robot's name and q in degrees by default).
    ax : mpl_toolkits.mplot3d.Axes3D, optional
    figsize : tuple of float
        Size of a new figure, inches.
    center, half_width : optional
        The cube shown (metres); by default one that holds the arm in any configuration.
    **style
        Passed to :func:`draw_robot`.

    Returns
    -------
    mpl_toolkits.mplot3d.Axes3D

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import urkin
    >>> ax = show_robot(urkin.robot("UR3"), np.zeros(6))
    >>> ax.get_title()
    'UR3 at q = [0, 0, 0, 0, 0, 0]°'
    >>> plt.close(ax.figure)
    """
    robot = check_robot(robot)
    q = check_joints(q)
    if q.shape != (6,):
        raise ValueError(
            f"show_robot draws one configuration: q must have shape (6,); got {q.shape}"
        )
    reach = _reach(robot)
    if title is None:
        degrees = ", ".join(f"{v:.0f}" for v in np.degrees(q) + 0.0)
        title = f"{robot.name} at q = [{degrees}]°"
    if center is None:
        base = fk_frames(robot, np.zeros(6))[0, :3, 3]
        center = base + np.array([0.0, 0.0, robot.d1 + 0.3 * reach])
    ax = axes3d(
        ax,
        center=center,
        half_width=0.75 * reach if half_width is None else half_width,
        title=title,
        figsize=figsize,
    )
    draw_robot(ax, robot, q, **style)
    T = fk_frames(robot, q)[-1]
    ax.text2D(
        0.0,
        0.97,
        pose_text(T),
        verticalalignment="top",
        transform=ax.transAxes,
        family="monospace",
        fontsize=9,
        bbox={"facecolor": "white", "alpha": 0.8},
    )
    return ax


def draw_angle_arc(
    ax,
    centre: ArrayLike,
    radius: float,
    start: float,
    end: float,
    label: str,
    colour: str,
    label_radius: float = 1.25,
    label_angle: float | None = None,
):
    """On a 2D axes, an arc from angle ``start`` to ``end`` (radians) with a label.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    centre : array_like, shape (2,)
    radius : float
    start, end : float
        Angles in radians, counter-clockwise from the x axis (either order).
    label : str
    colour : str
    label_radius : float
        The label sits at this many radii from the centre …
    label_angle : float, optional
        … at this angle (radians; the middle of the arc by default).

    Returns
    -------
    tuple
        The arc patch and the label.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig, ax = plt.subplots()
    >>> arc, text = draw_angle_arc(ax, (0, 0), 1.0, 0.0, np.pi / 2, "θ", "tab:blue")
    >>> text.get_text(), round(arc.theta2)
    ('θ', 90)
    >>> plt.close(fig)
    """
    low, high = min(start, end), max(start, end)
    c = np.asarray(centre, dtype=float)
    arc = ax.add_patch(
        Arc(
            c,
            2 * radius,
            2 * radius,
            theta1=np.degrees(low),
            theta2=np.degrees(high),
            color=colour,
            linewidth=1.5,
        )
    )
    middle = 0.5 * (low + high) if label_angle is None else label_angle
    text = ax.text(
        c[0] + label_radius * radius * np.cos(middle),
        c[1] + label_radius * radius * np.sin(middle),
        label,
        color=colour,
        ha="center",
        va="center",
        fontsize=11,
    )
    return arc, text


def _figure(figsize: tuple[float, float]) -> Figure:
    """A figure for 3D panels: constrained layout, with room between the panels' titles and
    the figure's title (a 3D axes puts its title inside its own box)."""
    fig = plt.figure(figsize=figsize, layout="constrained")
    fig.get_layout_engine().set(h_pad=0.15)
    return fig


def _floor(ax, x: tuple[float, float], y: tuple[float, float], color: str, alpha: float):
    floor_x, floor_y = np.meshgrid(x, y)
    return ax.plot_surface(floor_x, floor_y, 0.0 * floor_x, color=color, alpha=alpha)


def _legend_patch(ax, color: str, label: str, alpha: float = 0.4):
    """A thick line standing for a surface in the legend (3D surfaces have no legend entry)."""
    return ax.plot([], [], color=color, alpha=alpha, linewidth=8, label=label)


# ---------------------------------------------------------------------------------------------
# lesson 00 and 01
# ---------------------------------------------------------------------------------------------


def robot_panels(
    robot: Robot,
    configurations: Sequence[tuple[ArrayLike, str]],
    *,
    title: str | None = None,
    size: float = 6.5,
    **style,
) -> Figure:
    """One :func:`show_robot` view per configuration, side by side.

    All panels show the same cube, fitted to the configurations, so the arms are drawn as
    large as they can be and at one scale.

    Parameters
    ----------
    robot : Robot
    configurations : sequence of tuple
        Each ``(q, caption)``.
        Joint angles in radians and the title of that panel.
    title : str, optional
        Title of the whole figure.
    size : float
        Width and height of each panel, inches.
    **style
        Passed to :func:`draw_robot`.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import urkin
    >>> fig = robot_panels(urkin.robot("UR3"), [(np.zeros(6), "zero"), (np.ones(6), "one")])
    >>> [ax.get_title() for ax in fig.axes]
    ['zero', 'one']
    >>> plt.close(fig)
    """
    count = len(configurations)
    points = np.concatenate([fk_frames(robot, q)[:, :3, 3] for q, _ in configurations])
    margin = 0.15 * _reach(robot)  # room for the frame arrows
    low, high = points.min(axis=0) - margin, points.max(axis=0) + margin
    half_width = 0.5 * (high - low).max()
    fig = _figure(figsize=(size * count, size + 0.4))
    for index, (q, caption) in enumerate(configurations):
        ax = fig.add_subplot(1, count, index + 1, projection="3d")
        show_robot(
            robot,
            q,
            ax=ax,
            title=caption,
            center=0.5 * (low + high),
            half_width=half_width,
            **style,
        )
    if title:
        fig.suptitle(title, fontsize=13)
    return fig


def rotation_steps_figure(
    rows: Sequence[Sequence[tuple[str, ArrayLike]]],
    *,
    title: str | None = None,
    length: float = 0.8,
    size: float = 4.4,
    view: tuple[float, float] = (22.0, -55.0),
) -> Figure:
    """Rotations applied one after another: each panel a moving frame over the fixed axes.

    Parameters
    ----------
    rows : sequence of sequences of (caption, R)
        One row of panels per sequence; ``R`` (3 × 3) is the moving frame's orientation.
    title : str, optional
        Title of the whole figure.
    length : float
        Length of the moving frame's arrows (the fixed axes are 1 long).
    size : float
        Width and height of each panel, inches.
    view : tuple of float
        ``(elevation, azimuth)`` in degrees.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig = rotation_steps_figure([[("start", np.eye(3)), ("again", np.eye(3))]])
    >>> len(fig.axes)
    2
    >>> plt.close(fig)
    """
    row_count, column_count = len(rows), max(len(row) for row in rows)
    fig = _figure(figsize=(size * column_count, size * row_count + 0.6))
    for row, sequence in enumerate(rows):
        for column, (caption, R) in enumerate(sequence):
            ax = fig.add_subplot(
                row_count, column_count, row * column_count + column + 1, projection="3d"
            )
            axes3d(ax, center=(0.0, 0.0, 0.0), half_width=1.0, title=caption, view=view)
            draw_reference_axes(ax)
            draw_frame(ax, make_transform(R), length=length, linewidth=3.0, tips=True)
            for set_ticks in (ax.set_xticks, ax.set_yticks, ax.set_zticks):
                set_ticks([-1.0, 0.0, 1.0])
            if row == 0 and column == 0:
                ax.legend(loc="upper left", fontsize=8)
    if title:
        fig.suptitle(title)
    return fig


# ---------------------------------------------------------------------------------------------
# lesson 04: Jacobians and singularities
# ---------------------------------------------------------------------------------------------


def jacobian_columns_figure(
    frames: ArrayLike,
    velocities: ArrayLike,
    *,
    scale: float = 0.3,
    title: str | None = None,
    view: tuple[float, float] = (25.0, -25.0),
    figsize: tuple[float, float] = (12.0, 8.0),
) -> Figure:
    """Column by column: each joint's axis, its lever arm to the flange, and the flange
    velocity that joint alone gives.

    Parameters
    ----------
    frames : array_like, shape (7, 4, 4)
        Base and DH frames 1 … 6 (``urkin.fk_frames``); joint ``i`` turns about the z axis of
        frame ``i − 1``, and the last frame's origin is the flange.
    velocities : array_like, shape (6, 3)
        ``v_i``, the flange velocity per unit rate of joint ``i`` (m/s per rad/s).
    scale : float
        Metres of arrow per m/s.
    title : str, optional
    view : tuple of float
        ``(elevation, azimuth)`` in degrees.
    figsize : tuple of float

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import urkin
    >>> frames = urkin.fk_frames(urkin.robot("UR5"), np.full(6, 0.4))
    >>> v = np.cross(frames[:6, :3, 2], frames[6, :3, 3] - frames[:6, :3, 3])
    >>> fig = jacobian_columns_figure(frames, v)
    >>> len(fig.axes[0].get_legend().get_texts())
    9
    >>> plt.close(fig)
    """
    poses = np.asarray(frames, dtype=float)
    v = np.asarray(velocities, dtype=float)
    origins = poses[:, :3, 3]
    flange = origins[-1]
    span = np.ptp(origins, axis=0).max()
    axis_half = 0.12 * span
    colours = plt.get_cmap("tab10")(np.arange(len(v)))
    ax = axes3d(
        center=0.5 * (origins.min(axis=0) + origins.max(axis=0)),
        half_width=0.5 * span + 0.08,
        title=title,
        figsize=figsize,
        frame=BASE_FRAME,
        view=view,
    )
    ax.plot(
        *origins.T,
        "-o",
        color="0.6",
        linewidth=3,
        markersize=5,
        label="arm (links between DH origins)",
    )
    for i, (pose, v_i, colour) in enumerate(zip(poses, v, colours)):
        z, origin = pose[:3, 2], pose[:3, 3]
        axis_line = np.array([origin - axis_half * z, origin + axis_half * z])
        ax.plot(
            *axis_line.T,
            color=colour,
            linewidth=2.5,
            label=f"joint {i + 1}: axis z{i} through p{i}",
        )
        ax.plot(*np.array([origin, flange]).T, "--", color=colour, linewidth=1.2)
        ax.quiver(*flange, *(scale * v_i), color=colour, linewidth=2.0, arrow_length_ratio=0.15)
    ax.plot([], [], "--", color="0.3", label="lever arm p − p_(i−1), in the joint's colour")
    ax.plot(
        [],
        [],
        color="0.3",
        marker=r"$\rightarrow$",
        linestyle="none",
        markersize=12,
        label=f"v_i: flange velocity, {scale:g} m per m/s",
    )
    ax.scatter(*flange, color="k", s=30, depthshade=False)
    ax.text(*(flange + np.array([0.0, 0.0, 0.03])), "p (flange)", fontsize=10)
    ax.legend(loc="center left", bbox_to_anchor=(1.02, 0.5), fontsize=9)
    return ax.figure


def entry_error_maps(
    panels: Sequence[tuple[ArrayLike, str]],
    *,
    row_labels: Sequence[str],
    column_labels: Sequence[str],
    xlabel: str,
    ylabel: str,
    colorbar_label: str,
    title: str | None = None,
    factor: float = 1.0,
    vmax: float | None = None,
    decimals: int = 1,
    figsize: tuple[float, float] = (13.0, 4.4),
) -> Figure:
    """Matrices of errors side by side, every entry coloured and written out.

    Parameters
    ----------
    panels : sequence of (errors, title)
        ``errors`` has shape (rows, columns).
    row_labels, column_labels : sequence of str
        Tick labels.
    xlabel, ylabel, colorbar_label : str
    title : str, optional
        Title of the whole figure.
    factor : float
        Multiplies every entry before it is drawn (1000 for mm from m).
    vmax : float, optional
        Top of the colour scale (the largest entry by default).
    decimals : int
        Decimals of the written values.
    figsize : tuple of float

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig = entry_error_maps([(np.eye(2), "identity")], row_labels=["a", "b"],
    ...                        column_labels=["c", "d"], xlabel="col", ylabel="row",
    ...                        colorbar_label="error")
    >>> len(fig.axes[0].texts)
    4
    >>> plt.close(fig)
    """
    values = [factor * np.asarray(errors, dtype=float) for errors, _ in panels]
    top = max(float(v.max()) for v in values) if vmax is None else vmax
    fig, axes = plt.subplots(1, len(panels), figsize=figsize, layout="constrained", squeeze=False)
    image = None
    for ax, entries, (_, caption) in zip(axes[0], values, panels):
        image = ax.imshow(entries, cmap="Reds", vmin=0.0, vmax=top)
        for (row, col), value in np.ndenumerate(entries):
            ax.text(
                col,
                row,
                f"{value:.{decimals}f}",
                ha="center",
                va="center",
                fontsize=10,
                color="white" if value > 0.6 * top else "black",
            )
        ax.set_xticks(range(entries.shape[1]), column_labels)
        ax.set_yticks(range(entries.shape[0]), row_labels)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.set_title(caption)
    fig.colorbar(image, ax=axes[0], shrink=0.9, label=colorbar_label)
    if title:
        fig.suptitle(title)
    return fig


def step_size_figure(
    steps: ArrayLike,
    errors: Mapping[str, ArrayLike],
    *,
    floor: float,
    title: str | None = None,
    xlabel: str = "step size h (rad)",
    ylabel: str = "largest error (m/rad)",
    slopes: bool = True,
    figsize: tuple[float, float] = (8.5, 5.5),
) -> Figure:
    """Error of finite-difference derivatives against the step size, on log–log axes.

    Parameters
    ----------
    steps : array_like, shape (N,)
        Step sizes ``h``.
    errors : mapping of label to array_like, shape (N,)
        The error of each method at each step size; exact zeros are drawn at ``floor``.
    floor : float
        Where an error of exactly zero is drawn, so that it shows on a log axis.
    title, xlabel, ylabel : str
    slopes : bool
        Draw the reference slopes ``h``, ``h²`` and ``ε/h``.
    figsize : tuple of float

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> h = np.logspace(-12, -1, 12)
    >>> fig = step_size_figure(h, {"forward differences": h + 1e-16 / h}, floor=1e-18)
    >>> fig.axes[0].get_xscale(), fig.axes[0].get_yscale()
    ('log', 'log')
    >>> plt.close(fig)
    """
    h = np.asarray(steps, dtype=float)
    eps = np.finfo(float).eps
    fig, ax = plt.subplots(figsize=figsize, layout="constrained")
    markers = ("o-", "s-", "^-", "v-", "d-")
    for (name, error), style in zip(errors.items(), markers):
        ax.loglog(
            h,
            np.maximum(np.asarray(error, dtype=float), floor),
            style,
            markersize=4,
            linewidth=1.2,
            label=name,
        )
    if slopes:
        ax.loglog(h, h, ":", color="0.5", linewidth=1, label="slopes: h, h², ε/h")
        ax.loglog(h, h**2, ":", color="0.5", linewidth=1)
        ax.loglog(h, eps / h, ":", color="0.5", linewidth=1)
    ax.axhline(eps, color="0.7", linewidth=0.8, linestyle="--", label="machine precision ε")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if title:
        ax.set_title(title)
    ax.set_ylim(floor / 3, 10.0)
    ax.legend(loc="upper center", fontsize=9)
    return fig


def _view_along(ax, direction: ArrayLike, elev: float) -> None:
    """Look at a 3D axes from the horizontal direction of ``direction``, ``elev`` degrees up.

    The view is turned round if it would show the x axis running from right to left.
    """
    d = np.asarray(direction, dtype=float)
    azim = np.degrees(np.arctan2(d[1], d[0]))
    if not -180.0 < azim < 0.0:  # x increases to the right only for azimuths in (−180°, 0°)
        azim -= 180.0
    ax.view_init(elev=elev, azim=azim)


def _shoulder_family(ax, robot: Robot, poses: np.ndarray, q: np.ndarray) -> None:
    origins = poses[:, :3, 3]
    radial = np.array([np.cos(q[0]), np.sin(q[0]), 0.0])  # horizontal, in the arm's plane
    sideways = poses[1, :3, 2]  # the shoulder axis: horizontal, across the arm's plane
    top = origins[:, 2].max() + 0.1
    ax.plot([0, 0], [0, 0], [0, top], color="tab:blue", linewidth=1.5, label="base axis")
    across, up = np.meshgrid([-0.3, 0.3], [0.0, top])
    ax.plot_surface(across * sideways[0], across * sideways[1], up, color="tab:blue", alpha=0.15)
    _legend_patch(
        ax, "tab:blue", "plane through the base axis, parallel to the shoulder axis", alpha=0.3
    )
    ax.scatter(
        *origins[5],
        color="tab:red",
        s=60,
        depthshade=False,
        label="wrist centre (frame 5 origin), in that plane",
    )
    foot = np.array([0.0, 0.0, origins[5, 2]])
    distance = np.linalg.norm(origins[5, :2])
    ax.plot(
        *np.array([foot, origins[5]]).T,
        ":",
        color="tab:red",
        linewidth=2,
        label=f"its distance from the base axis: {distance:.3f} m (= d4)",
    )
    _view_along(ax, 0.6 * radial + 0.8 * sideways, elev=18)


def _elbow_family(ax, robot: Robot, poses: np.ndarray, q: np.ndarray) -> None:
    origins = poses[:, :3, 3]
    ahead = origins[3] - origins[1]
    line = np.array([origins[1] - 0.15 * ahead, origins[3] + 0.15 * ahead])
    ax.plot(
        *line.T,
        "--",
        color="tab:red",
        linewidth=1.5,
        label="frames 1, 2, 3 (shoulder, elbow, wrist 1) in one line",
    )
    ax.scatter(*origins[1:4].T, color="tab:red", s=40, depthshade=False)
    _view_along(ax, poses[1, :3, 2], elev=10)  # along the shoulder axis: the arm's plane


def _wrist_family(ax, robot: Robot, poses: np.ndarray, q: np.ndarray) -> None:
    origins, axes_z = poses[:, :3, 3], poses[:, :3, 2]
    for k, name, colour in (
        (3, "joint 4 axis (z3, through frame 3)", "tab:red"),
        (5, "joint 6 axis (z5, through frame 5)", "tab:purple"),
    ):
        axis_line = np.array([origins[k] - 0.3 * axes_z[k], origins[k] + 0.3 * axes_z[k]])
        ax.plot(*axis_line.T, color=colour, linewidth=2.0, label=name)
    _view_along(ax, np.cross(axes_z[3], axes_z[4]) + 0.5 * axes_z[3], elev=15)


_FAMILIES = {"shoulder": _shoulder_family, "elbow": _elbow_family, "wrist": _wrist_family}


def singular_families_figure(
    robot: Robot,
    configurations: Mapping[str, ArrayLike],
    *,
    conditions: Mapping[str, str] | None = None,
    title: str | None = None,
    size: float = 6.2,
    half_width: float = 0.42,
) -> Figure:
    """One panel per singular family of a UR arm, with the geometry that makes it singular.

    * ``"shoulder"``: the base axis, the plane through it parallel to the shoulder axis, and
      the wrist centre (frame 5's origin) in that plane;
    * ``"elbow"``: frames 1, 2 and 3 in one line;
    * ``"wrist"``: the axes of joints 4 and 6, parallel.

    Each panel is looked at from the side that shows its geometry, turned so that x runs from
    left to right.

    Parameters
    ----------
    robot : Robot
    configurations : mapping
        Family name to joint angles ``q``.
        Keys among ``"shoulder"``, ``"elbow"`` and ``"wrist"``; joint angles in radians.
    conditions : mapping of family name to str, optional
        The condition written in each panel's title.
    title : str, optional
        Title of the whole figure.
    size : float
        Width of each panel, inches.
    half_width : float
        Half the side of each panel's cube, metres.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import urkin
    >>> fig = singular_families_figure(urkin.robot("UR5"), {"elbow": np.zeros(6)})
    >>> fig.axes[0].get_title()
    'elbow'
    >>> plt.close(fig)
    """
    unknown = set(configurations) - set(_FAMILIES)
    if unknown:
        raise ValueError(f"unknown singular families {sorted(unknown)}; known: {list(_FAMILIES)}")
    conditions = conditions or {}
    count = len(configurations)
    fig = _figure(figsize=(size * count, size + 1.6))
    for index, (family, q) in enumerate(configurations.items()):
        q = np.asarray(q, dtype=float)
        poses = fk_frames(robot, q)
        origins = poses[:, :3, 3]
        caption = f"{family}: {conditions[family]}" if family in conditions else family
        ax = axes3d(
            fig.add_subplot(1, count, index + 1, projection="3d"),
            center=0.5 * (origins.min(axis=0) + origins.max(axis=0)),
            half_width=half_width,
            title=caption,
        )
        draw_robot(ax, robot, q, frames=False, color="0.45", linewidth=3, label=robot.name)
        _FAMILIES[family](ax, robot, poses, q)
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.05), fontsize=9)
    if title:
        fig.suptitle(title, fontsize=13)
    return fig


def draw_ellipsoid_arms(
    ax,
    robot: Robot,
    configurations: ArrayLike,
    ellipsoids: ArrayLike,
    *,
    scale: float,
    colors: Sequence | None = None,
    labels: Sequence[str] | None = None,
    alpha: float = 0.35,
    linewidth: float = 2.5,
):
    """Arms along a path, each with an ellipsoid at its flange origin, in the arm's colour.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.Axes3D
    robot : Robot
    configurations : array_like, shape (k, 6)
        Joint angles in radians.
    ellipsoids : array_like, shape (k, 3, 3)
        Semi-axes of each ellipsoid as columns (``U Σ`` for a velocity ellipsoid,
        ``U Σ⁻¹`` for a force ellipsoid).
    scale : float
        Metres of drawing per unit of the semi-axes.
    colors : sequence, optional
        One colour per arm (viridis by default).
    labels : sequence of str, optional
        Legend entries.
    alpha, linewidth

    Returns
    -------
    list
        The matplotlib artists.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import urkin
    >>> ax = axes3d()
    >>> artists = draw_ellipsoid_arms(ax, urkin.robot("UR5"), np.zeros((2, 6)),
    ...                               np.stack([np.eye(3)] * 2), scale=0.1)
    >>> len(artists)
    4
    >>> plt.close(ax.figure)
    """
    qs = np.atleast_2d(np.asarray(configurations, dtype=float))
    shapes = np.asarray(ellipsoids, dtype=float).reshape(len(qs), 3, 3)
    if colors is None:
        colors = plt.get_cmap("viridis")(np.linspace(0.0, 0.85, len(qs)))
    if labels is None:
        labels = [None] * len(qs)
    flanges = fk_frames(robot, qs)[:, -1, :3, 3]
    artists = []
    for q, shape, flange, colour, label in zip(qs, shapes, flanges, colors, labels):
        artists.append(draw_ellipsoid(ax, flange, shape, scale=scale, color=colour, alpha=alpha))
        artists += draw_robot(
            ax, robot, q, frames=False, color=colour, linewidth=linewidth, label=label
        )
    return artists


def manipulability_figure(
    robot: Robot,
    configurations: ArrayLike,
    ellipsoids: ArrayLike,
    labels: Sequence[str],
    *,
    s: ArrayLike,
    manipulability: Mapping[str, ArrayLike],
    semi_axes: ArrayLike,
    condition: ArrayLike,
    scale: float,
    center: ArrayLike,
    half_width: float,
    s_label: str = "path parameter s",
    semi_axes_label: str = "singular values of J_v",
    condition_label: str = "κ = σ_max / σ_min of J",
    title: str | None = None,
    view: tuple[float, float] = (18.0, -62.0),
    figsize: tuple[float, float] = (16.0, 8.5),
) -> Figure:
    """An arm approaching a singularity: velocity ellipsoids in 3D, and the measures of
    distance to the singularity along the path.

    Parameters
    ----------
    robot : Robot
    configurations : array_like, shape (k, 6)
        The configurations drawn, radians.
    ellipsoids : array_like, shape (k, 3, 3)
        Their velocity ellipsoids' semi-axes as columns (``U Σ``), m/s per rad/s.
    labels : sequence of str
        Legend entries of the drawn configurations.
    s : array_like, shape (N,)
        The path parameter.
    manipulability : mapping of label to array_like, shape (N,)
        Manipulability measures along the path.
    semi_axes : array_like, shape (N, 3)
        Singular values of ``J_v`` along the path, largest first.
    condition : array_like, shape (N,)
        Condition number along the path; values above 1e12 (a singular J) are left out.
    scale : float
        Metres of ellipsoid per m/s.
    center, half_width
        The 3D view's cube, metres.
    s_label, semi_axes_label, condition_label, title : str
    view : tuple of float
    figsize : tuple of float

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import urkin
    >>> s = np.linspace(0, 1, 5)
    >>> fig = manipulability_figure(urkin.robot("UR5"), np.zeros((1, 6)), np.eye(3)[None],
    ...                             ["q = 0"], s=s, manipulability={"w": s},
    ...                             semi_axes=np.ones((5, 3)), condition=1 + s, scale=0.1,
    ...                             center=(0, 0, 0.4), half_width=0.5)
    >>> len(fig.axes)
    4
    >>> plt.close(fig)
    """
    s = np.asarray(s, dtype=float)
    kappa = np.asarray(condition, dtype=float)
    sigma = np.asarray(semi_axes, dtype=float)
    fig = _figure(figsize=figsize)
    grid = fig.add_gridspec(3, 2, width_ratios=(1.15, 1.0))
    ax3 = axes3d(
        fig.add_subplot(grid[:, 0], projection="3d"),
        center=center,
        half_width=half_width,
        title=f"velocity ellipsoids of the flange (×{scale:g}, m per m/s) along the path",
        view=view,
    )
    draw_ellipsoid_arms(ax3, robot, configurations, ellipsoids, scale=scale, labels=labels)
    ax3.legend(loc="upper left", fontsize=9)

    top = fig.add_subplot(grid[0, 1])
    for name, values in manipulability.items():
        top.plot(s, values, label=name)
    top.set_ylabel("manipulability w")
    top.set_title("measures along the path")
    top.legend(loc="lower left", fontsize=8)

    middle = fig.add_subplot(grid[1, 1], sharex=top)
    for axis_index, style in enumerate(["-", "--", ":"][: sigma.shape[1]]):
        middle.plot(s, sigma[:, axis_index], style, color="tab:green", label=f"σ{axis_index + 1}")
    middle.set_ylabel("semi-axes of the\nellipsoid (m/s per rad/s)")
    middle.legend(loc="center left", fontsize=8, title=semi_axes_label, title_fontsize=8)

    bottom = fig.add_subplot(grid[2, 1], sharex=top)
    finite = np.isfinite(kappa) & (kappa < 1e12)
    bottom.semilogy(s[finite], kappa[finite], color="tab:red", label=condition_label)
    if not finite[-1]:
        last = np.flatnonzero(finite)[-1]
        bottom.annotate(
            f"κ → ∞ at s = {s[-1]:g}",
            xy=(s[last], kappa[last]),
            xytext=(s[0] + 0.62 * (s[-1] - s[0]), np.sqrt(kappa[finite].min() * kappa[last])),
            arrowprops={"arrowstyle": "->"},
        )
    bottom.set_ylabel("condition number κ")
    bottom.set_xlabel(s_label)
    bottom.legend(loc="upper left", fontsize=8)
    for panel in (top, middle, bottom):
        panel.grid(True, alpha=0.3)
    if title:
        fig.suptitle(title, fontsize=13)
    return fig


def ellipsoid_panels(
    robot: Robot,
    configurations: ArrayLike,
    panels: Sequence[tuple[str, ArrayLike, float]],
    *,
    labels: Sequence[str] | None = None,
    colors: Sequence | None = None,
    center: ArrayLike,
    half_width: float,
    title: str | None = None,
    view: tuple[float, float] = (18.0, -62.0),
    size: float = 7.5,
) -> Figure:
    """The same arms in several 3D panels, each panel with its own ellipsoids.

    Parameters
    ----------
    robot : Robot
    configurations : array_like, shape (k, 6)
        Joint angles in radians.
    panels : sequence of (title, ellipsoids, scale)
        ``ellipsoids`` has shape (k, 3, 3), semi-axes as columns; ``scale`` is metres of
        drawing per unit of the semi-axes.
    labels : sequence of str, optional
        Legend entries of the configurations.
    colors : sequence, optional
        One colour per configuration.
    center, half_width
        Each panel's cube, metres.
    title : str, optional
        Title of the whole figure.
    view : tuple of float
    size : float
        Width and height of each panel, inches.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import urkin
    >>> shapes = np.eye(3)[None]
    >>> fig = ellipsoid_panels(urkin.robot("UR5"), np.zeros((1, 6)),
    ...                        [("velocity", shapes, 0.1), ("force", shapes, 0.05)],
    ...                        center=(0, 0, 0.4), half_width=0.5)
    >>> [ax.get_title() for ax in fig.axes]
    ['velocity', 'force']
    >>> plt.close(fig)
    """
    count = len(panels)
    fig = _figure(figsize=(size * count, size))
    for index, (caption, ellipsoids, scale) in enumerate(panels):
        ax = axes3d(
            fig.add_subplot(1, count, index + 1, projection="3d"),
            center=center,
            half_width=half_width,
            title=caption,
            view=view,
        )
        draw_ellipsoid_arms(
            ax, robot, configurations, ellipsoids, scale=scale, colors=colors, labels=labels
        )
        if labels is not None:
            ax.legend(loc="upper left", fontsize=9)
    if title:
        fig.suptitle(title, fontsize=13)
    return fig


# ---------------------------------------------------------------------------------------------
# lesson 05: Newton–Raphson
# ---------------------------------------------------------------------------------------------


def square_traces_figure(
    square: ArrayLike,
    traces: Sequence[tuple[ArrayLike, str, str, str]],
    misses: Sequence[tuple[ArrayLike, str, str]],
    *,
    prediction: tuple[ArrayLike, str] | None = None,
    prediction_color: str = "tab:red",
    limit: tuple[float, str] | None = None,
    origin_note: str | None = None,
    square_label: str = "target path",
    index_label: str = "target point along the path (index)",
    top_title: str = "top view",
    title: str | None = None,
    figsize: tuple[float, float] = (15.0, 6.0),
) -> Figure:
    """Flange traces over a target path seen from above, and the miss at each target point.

    Parameters
    ----------
    square : array_like, shape (k, 3)
        The target path's corners (or points), metres, drawn as a thick grey line.
    traces : sequence of (points, label, colour, linestyle)
        Flange positions, shape (N, 3), metres.
    misses : sequence of (values, label, colour)
        Distance of the flange from each target, mm, shape (N,).
    prediction : (values, label), optional
        Predicted misses (mm), drawn as open markers in ``prediction_color``.
    prediction_color : str
        Give it a colour no curve of ``misses`` has.
    limit : (value, label), optional
        A horizontal line on the misses panel (mm).
    origin_note : str, optional
        A note pointing at the base origin in the top view.
    square_label, index_label, top_title, title : str
    figsize : tuple of float

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> path = np.array([[0.3, 0.2, 0.2], [0.5, 0.2, 0.2], [0.5, 0.4, 0.2]])
    >>> fig = square_traces_figure(path, [(path, "flange", "tab:blue", "-")],
    ...                            [(np.zeros(3), "miss", "tab:blue")],
    ...                            prediction=(np.zeros(3), "predicted"))
    >>> [ax.get_xlabel() for ax in fig.axes]
    ['x (m)', 'target point along the path (index)']
    >>> plt.close(fig)
    """
    if prediction is not None and any(colour == prediction_color for *_, colour in misses):
        raise ValueError("draw the prediction in a colour that no curve of misses has")
    fig, (top, along) = plt.subplots(
        1, 2, figsize=figsize, layout="constrained", gridspec_kw={"width_ratios": (1.0, 1.3)}
    )
    corners = np.asarray(square, dtype=float)
    top.plot(*corners[:, :2].T, color="black", linewidth=6, alpha=0.2, label=square_label)
    for points, name, colour, style in traces:
        top.plot(*np.asarray(points)[:, :2].T, style, color=colour, linewidth=1.6, label=name)
    top.plot(0.0, 0.0, "k+", markersize=12)
    if origin_note:
        top.annotate(
            origin_note,
            xy=(0.0, 0.0),
            xytext=(0.05, 0.28),
            arrowprops={"arrowstyle": "->"},
            fontsize=9,
        )
    top.set_aspect("equal")
    top.set_xlabel("x (m)")
    top.set_ylabel("y (m)")
    top.set_title(top_title)
    top.legend(loc="lower right", fontsize=8)

    for values, name, colour in misses:
        values = np.asarray(values, dtype=float)
        along.plot(np.arange(len(values)), values, color=colour, linewidth=1.8, label=name)
    if prediction is not None:
        values = np.asarray(prediction[0], dtype=float)
        along.plot(
            np.arange(len(values)),
            values,
            "o",
            color=prediction_color,
            markersize=4,
            fillstyle="none",
            label=prediction[1],
        )
    if limit is not None:
        along.axhline(limit[0], color="0.5", linestyle=":", label=limit[1])
    along.set_xlabel(index_label)
    along.set_ylabel("distance flange − target (mm)")
    along.set_title("how far the real flange is from each target")
    if limit is not None:
        along.set_ylim(-0.03 * limit[0], 1.12 * limit[0])
    along.legend(loc="center right", fontsize=9)
    if title:
        fig.suptitle(title, fontsize=13)
    return fig


def arms_figure(
    robot: Robot,
    panels: Sequence[tuple[str, Sequence[tuple[ArrayLike, str, str | None]]]],
    *,
    center: ArrayLike,
    half_width: float,
    target: ArrayLike | None = None,
    target_label: str = "target",
    pose: ArrayLike | None = None,
    pose_length: float = 0.15,
    floor: str | None = "the plane the robot stands on, z = 0",
    floor_color: str = "0.5",
    view: tuple[float, float] = (20.0, -50.0),
    columns: int | None = None,
    size: float = 6.5,
    legend: str = "all",
    shared_note: bool | None = None,
    title: str | None = None,
) -> Figure:
    """Configurations of one arm compared, in one or more 3D panels.

    Parameters
    ----------
    robot : Robot
    panels : sequence of (title, arms)
        ``arms`` is a sequence of ``(q, colour, label)`` as for :func:`draw_arms`.
    center, half_width
        Each panel's cube, metres.
    target : array_like, shape (3,), optional
        A point every arm should reach, drawn as a black star.
    target_label : str
    pose : array_like, shape (4, 4), optional
        A pose drawn as a frame triad in every panel (e.g. the flange pose all reach).
    pose_length : float
        Length of its arrows, metres.
    floor : str, optional
        Legend entry of the plane z = 0, shaded; None leaves it out.
    floor_color : str
    view : tuple of float
        ``(elevation, azimuth)`` in degrees.
    columns : int, optional
        Panels per row (all in one row by default).
    size : float
        Width and height of each panel, inches.
    legend : {"all", "first"}
        Which panels get a legend.
    shared_note : bool, optional
        State the frame once, under the whole figure, instead of in every panel (the
        default when there are more than two panels, which leaves them little room).
    title : str, optional
        Title of the whole figure.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import urkin
    >>> panels = [("one", [(np.zeros(6), "tab:blue", "q = 0")]),
    ...           ("two", [(np.ones(6), "tab:red", "q = 1")])]
    >>> fig = arms_figure(urkin.robot("UR3"), panels, center=(0, 0, 0.2), half_width=0.5,
    ...                   target=(0.2, 0.1, 0.1))
    >>> [ax.get_title() for ax in fig.axes]
    ['one', 'two']
    >>> plt.close(fig)
    """
    count = len(panels)
    columns = count if columns is None else columns
    rows = -(-count // columns)
    shared_note = count > 2 if shared_note is None else shared_note
    fig = _figure(figsize=(size * columns, size * rows + 0.4))
    c = np.asarray(center, dtype=float)
    for index, (caption, arms) in enumerate(panels):
        ax = axes3d(
            fig.add_subplot(rows, columns, index + 1, projection="3d"),
            center=c,
            half_width=half_width,
            title=caption,
            view=view,
        )
        if floor:
            span = (c[0] - half_width, c[0] + half_width), (c[1] - half_width, c[1] + half_width)
            _floor(ax, *span, color=floor_color, alpha=0.15)
        draw_arms(ax, robot, arms, frame=not shared_note)
        if pose is not None:
            draw_frame(ax, pose, length=pose_length, linewidth=3)
        if target is not None:
            ax.scatter(
                *np.asarray(target, dtype=float),
                color="black",
                marker="*",
                s=90,
                depthshade=False,
                label=target_label,
            )
        if floor:
            _legend_patch(ax, floor_color, floor)
        if legend == "all" or index == 0:
            ax.legend(loc="upper left", fontsize=9)
    if shared_note:
        fig.supxlabel(
            f"every panel drawn in the {_robot_frame(robot)}, lengths in metres",
            fontsize=10,
            color="0.25",
        )
    if title:
        fig.suptitle(title, fontsize=13)
    return fig


def convergence_figure(
    runs: Sequence[Mapping[str, ArrayLike]],
    compared: Sequence[tuple[Mapping[str, ArrayLike], str, str]],
    *,
    floor: float,
    titles: tuple[str, str],
    title: str | None = None,
    colors: Sequence[str] = ("tab:blue", "tab:orange", "tab:green", "tab:purple", "tab:brown"),
    figsize: tuple[float, float] = (14.0, 5.5),
) -> Figure:
    """Error histories of iterative solves, position and orientation, on log axes.

    Parameters
    ----------
    runs : sequence of mappings
        Left panel: one solve per colour; each maps ``"position"`` (m) and ``"angle"`` (rad)
        to the error after each iteration.
    compared : sequence of tuple
        Right panel: ``(history, label, colour)`` per solve compared on one target, each
        history as in ``runs``.
    floor : float
        Where an error of exactly zero is drawn.
    titles : (str, str)
        Titles of the two panels.
    title : str, optional
        Title of the whole figure.
    colors : sequence of str
    figsize : tuple of float

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> run = {"position": np.array([1.0, 1e-3, 0.0]), "angle": np.array([1.0, 1e-4, 0.0])}
    >>> fig = convergence_figure([run], [(run, "fresh", "tab:orange")], floor=1e-17,
    ...                          titles=("left", "right"))
    >>> [ax.get_title() for ax in fig.axes]
    ['left', 'right']
    >>> plt.close(fig)
    """
    ylabel = f"error (m or rad; exact zero drawn at {floor:.0e})"
    fig, (left, right) = plt.subplots(1, 2, figsize=figsize, layout="constrained")
    for i, (history, colour) in enumerate(zip(runs, colors)):
        steps = np.arange(len(history["position"]))
        left.semilogy(steps, np.maximum(history["position"], floor), "o-", color=colour)
        left.semilogy(steps, np.maximum(history["angle"], floor), "s--", color=colour, markersize=4)
        left.plot([], [], color=colour, linewidth=6, label=f"target {i + 1}")
    left.plot([], [], "o-", color="0.3", label="position error (m)")
    left.plot([], [], "s--", color="0.3", markersize=4, label="orientation error (rad)")
    left.axhline(
        np.finfo(float).eps,
        color="0.5",
        linewidth=0.8,
        linestyle=":",
        label="machine precision, 2.2e-16",
    )
    for history, name, colour in compared:
        steps = np.arange(len(history["position"]))
        right.semilogy(
            steps,
            np.maximum(history["position"], floor),
            "o-",
            color=colour,
            markersize=4,
            label=f"{name}: position (m)",
        )
        right.semilogy(
            steps,
            np.maximum(history["angle"], floor),
            "s--",
            color=colour,
            markersize=3,
            label=f"{name}: orientation (rad)",
        )
    for ax, caption in zip((left, right), titles):
        ax.set_xlabel("iteration")
        ax.set_ylabel(ylabel)
        ax.set_title(caption)
        ax.set_ylim(floor / 3, 10)
        ax.legend(loc="upper right", fontsize=8)
    if title:
        fig.suptitle(title, fontsize=13)
    return fig


def solver_runs_figure(
    runs: Mapping[str, tuple[Mapping[str, ArrayLike], str]],
    *,
    floor: float,
    titles: tuple[str, str, str] = (
        "position error",
        "orientation error",
        "size of the step before the limit",
    ),
    seen: str | None = None,
    seen_label: str = "what the solver sees",
    step_limit: float | None = 1.0,
    tick_step: int = 5,
    title: str | None = None,
    figsize: tuple[float, float] = (16.0, 5.0),
) -> Figure:
    """Solves compared iteration by iteration: position error, true angle, step size.

    Parameters
    ----------
    runs : mapping of name to (history, colour)
        Each history maps ``"position"`` (m), ``"angle"`` (rad, the true angle to the
        target) and ``"step"`` (rad, the largest joint change asked for) to one value per
        iteration; ``"seen"`` is the orientation error the solver itself measured.
    floor : float
        Where an error of exactly zero is drawn.
    titles : (str, str, str)
        Titles of the three panels.
    seen : str, optional
        Name of the run whose ``"seen"`` error is drawn too (dotted, with crosses).
    seen_label : str
    step_limit : float, optional
        Drawn as a dashed line on the step panel.
    tick_step : int
        Iterations between ticks.
    title : str, optional
        Title of the whole figure.
    figsize : tuple of float

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> run = {"position": np.array([1.0, 0.0]), "angle": np.array([3.0, 0.0]),
    ...        "step": np.array([2.0]), "seen": np.array([0.0, 0.0])}
    >>> fig = solver_runs_figure({"log": (run, "tab:blue")}, floor=1e-17, seen="log")
    >>> len(fig.axes)
    3
    >>> plt.close(fig)
    """
    fig, (left, middle, right) = plt.subplots(1, 3, figsize=figsize, layout="constrained")
    for name, (run, colour) in runs.items():
        steps = np.arange(len(run["position"]))
        left.semilogy(
            steps,
            np.maximum(run["position"], floor),
            "o-",
            color=colour,
            markersize=4,
            label=f"{name} error",
        )
        middle.semilogy(
            steps,
            np.maximum(run["angle"], floor),
            "o-",
            color=colour,
            markersize=4,
            label=f"{name} error: true angle to the target",
        )
        right.semilogy(
            np.arange(len(run["step"])),
            run["step"],
            "o-",
            color=colour,
            markersize=4,
            label=f"{name} error",
        )
    if seen is not None:
        run, colour = runs[seen]
        middle.semilogy(
            np.arange(len(run["seen"])),
            np.maximum(run["seen"], floor),
            "x:",
            color=colour,
            label=f"{seen} error: {seen_label}",
        )
    if step_limit is not None:
        right.axhline(
            step_limit, color="0.4", linestyle="--", label=f"step limit: {step_limit:g} rad"
        )
    left.set_ylabel("distance to the target (m)")
    middle.set_ylabel(f"angle (rad; exact zero drawn at {floor:.0e})")
    right.set_ylabel("largest joint change asked for (rad)")
    last = max(len(run["position"]) for run, _ in runs.values())
    for ax, caption in zip((left, middle, right), titles):
        ax.set_title(caption)
        ax.set_xlabel("iteration")
        ax.set_xticks(range(0, last, tick_step))
        ax.grid(True, alpha=0.3)
        ax.legend(loc="lower left", fontsize=8)
    middle.legend(loc="center left", bbox_to_anchor=(0.0, 0.32), fontsize=8)
    if title:
        fig.suptitle(title, fontsize=13)
    return fig


# ---------------------------------------------------------------------------------------------
# lesson 07: geometric inverse kinematics (the lab's UR3 on its table)
# ---------------------------------------------------------------------------------------------


def lab_scene(
    robot: Robot,
    q: ArrayLike,
    *,
    frames: Sequence[tuple[ArrayLike, str, float]],
    gripper: ArrayLike,
    target: ArrayLike,
    table: tuple[tuple[float, float], tuple[float, float]],
    center: ArrayLike,
    half_width: float,
    frame: str = "table frame",
    gripper_label: str = "gripper",
    table_label: str = "table top, z = 0",
    title: str | None = None,
    view: tuple[float, float] = (22.0, -70.0),
    figsize: tuple[float, float] = (8.5, 8.5),
) -> Figure:
    """An arm on its table: the arm, its gripper, frames that matter and the target.

    Parameters
    ----------
    robot : Robot
        With its base placed on the table (``robot.base``), so that it is drawn in the
        table's frame.
    q : array_like, shape (6,)
        Joint angles in radians.
    frames : sequence of tuple
        ``(T, label, length)`` per frame drawn as a labelled triad, poses in the table frame.
    gripper : array_like, shape (k, 3)
        The gripper's polyline from the flange to its tip, metres.
    target : array_like, shape (3,)
    table : ((x0, x1), (y0, y1))
        Extent of the table top drawn at z = 0, metres.
    center, half_width
        The view's cube, metres.
    frame : str
        The frame everything is drawn in.
    gripper_label, table_label, title : str
    view : tuple of float
    figsize : tuple of float

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import urkin
    >>> fig = lab_scene(urkin.robot("UR3"), np.zeros(6), frames=[(np.eye(4), "base", 0.08)],
    ...                 gripper=np.zeros((2, 3)), target=(0.1, 0.1, 0.0),
    ...                 table=((-0.3, 0.3), (-0.3, 0.3)), center=(0, 0, 0.2), half_width=0.4)
    >>> fig.axes[0]._urkin_frame_note.get_text()
    'drawn in the table frame, lengths in metres'
    >>> plt.close(fig)
    """
    ax = axes3d(
        center=center, half_width=half_width, title=title, figsize=figsize, frame=frame, view=view
    )
    _floor(ax, *table, color="tan", alpha=0.25)
    draw_robot(ax, robot, q, frames=False, label="the arm (DH frame origins)")
    ax.plot(
        *np.asarray(gripper, dtype=float).T, color="tab:orange", linewidth=4, label=gripper_label
    )
    for T, name, length in frames:
        draw_frame(ax, T, length=length, label=name, linewidth=2.5)
    ax.scatter(
        *np.asarray(target, dtype=float)[:3],
        color="black",
        marker="*",
        s=80,
        depthshade=False,
        label="target",
    )
    _legend_patch(ax, "tan", table_label, alpha=0.5)
    for colour, axis in zip(AXIS_COLOURS, "xyz"):
        ax.plot([], [], color=colour, linewidth=2.5, label=f"{axis} axis of a frame")
    ax.legend(loc="upper left", fontsize=9)
    return ax.figure


def lab_top_view(
    arm: ArrayLike,
    wrist_centre: ArrayLike,
    cup: ArrayLike,
    *,
    theta1: float,
    yaw: float,
    offset: float,
    offset_name: str = "the offset",
    plate_name: str = "its length",
    title: str | None = None,
    figsize: tuple[float, float] = (9.5, 8.5),
) -> Figure:
    """The base angle from above: the arm's line, tangent to the offset circle, and the
    wrist centre beside it.

    Parameters
    ----------
    arm : array_like, shape (k, 2) or (k, 3)
        The arm's DH frame origins in the base frame (only x and y are used), metres.
    wrist_centre : array_like, shape (2,) or (3,)
        ``(x_c, y_c)``, metres.
    cup : array_like, shape (2,) or (3,)
        The gripper tip ``(x, y)``, metres.
    theta1 : float
        The base angle: the arm's direction ``u = (cos θ1, sin θ1)``, radians.
    yaw : float
        The gripper's yaw ψ, radians.
    offset : float
        The wrist's sideways offset from the arm's plane, metres.
    offset_name, plate_name : str
        How the lesson writes the offset and the gripper plate's length.
    title : str, optional
    figsize : tuple of float

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> fig = lab_top_view(np.zeros((2, 2)), (0.2, 0.15), (0.25, 0.15), theta1=0.2, yaw=0.0,
    ...                    offset=0.11)
    >>> fig.axes[0].get_xlabel()
    'x in the base frame (m)'
    >>> plt.close(fig)
    """
    points = np.asarray(arm, dtype=float)[:, :2]
    c = np.asarray(wrist_centre, dtype=float)[:2]
    tip = np.asarray(cup, dtype=float)[:2]
    u = np.array([np.cos(theta1), np.sin(theta1)])
    n = np.array([-u[1], u[0]])
    foot = (c @ u) * u
    rho, theta_c = np.hypot(*c), np.arctan2(c[1], c[0])
    plate = np.linalg.norm(tip - c)
    fig, ax = plt.subplots(figsize=figsize, layout="constrained")
    ax.add_patch(
        Circle(
            (0, 0),
            offset,
            fill=False,
            linestyle="--",
            color="0.4",
            label=f"circle of radius {offset_name} = {offset:.3f} m",
        )
    )
    ax.plot(
        *points.T,
        "-o",
        color="0.6",
        linewidth=4,
        markersize=5,
        alpha=0.45,
        label="the arm seen from above (DH frame origins)",
    )
    ax.plot(
        [0, 1.35 * foot[0]],
        [0, 1.35 * foot[1]],
        "-.",
        color="tab:blue",
        label="arm's direction u = (cos θ1, sin θ1)",
    )
    ax.plot(
        [0, c[0]],
        [0, c[1]],
        ":",
        color="tab:purple",
        linewidth=2,
        label=f"base to wrist centre, ρ = {rho:.3f} m",
    )
    ax.plot(
        [foot[0], c[0]],
        [foot[1], c[1]],
        color="tab:green",
        linewidth=2,
        label=f"offset {offset:.3f} m along n, at a right angle",
    )
    mark = 0.05 * rho  # the right-angle mark at the foot
    corner = foot + mark * (n - u)
    ax.plot(
        [foot[0] - mark * u[0], corner[0], foot[0] + mark * n[0]],
        [foot[1] - mark * u[1], corner[1], foot[1] + mark * n[1]],
        color="tab:green",
        linewidth=1,
    )
    ax.plot(
        [c[0], tip[0]],
        [c[1], tip[1]],
        color="tab:orange",
        linewidth=4,
        label=f"gripper plate, {plate_name} = {plate:.4g} m at yaw ψ",
    )
    ax.plot(*c, "o", color="tab:purple", markersize=9, label="wrist centre (x_c, y_c)")
    ax.plot(*tip, "*", color="black", markersize=14, label="suction cup (x, y)")
    ax.plot(0, 0, "k+", markersize=16, markeredgewidth=2, label="base axis")
    ax.plot([c[0], c[0] + 0.28 * rho], [c[1], c[1]], "--", color="tab:orange", linewidth=1)
    draw_angle_arc(ax, (0, 0), 0.24 * rho, 0.0, theta1, "θ1", "tab:blue", 1.4)
    draw_angle_arc(ax, (0, 0), 0.95 * rho, theta1, theta_c, "θB", "tab:green", 1.1)
    draw_angle_arc(ax, (0, 0), 1.34 * rho, 0.0, theta_c, "θc", "tab:purple", 1.0, label_angle=0.2)
    draw_angle_arc(ax, c, 0.14 * rho, 0.0, yaw, "ψ", "tab:orange", 1.5)
    reach = max(1.4 * rho, np.abs(points).max() + 0.05)
    low = -max(offset + 0.04, 0.15)
    ax.set_xlim(low, reach)
    ax.set_ylim(low, reach)
    ax.set_aspect("equal")
    ax.grid(True, alpha=0.3)
    ax.set_xlabel("x in the base frame (m)")
    ax.set_ylabel("y in the base frame (m)")
    if title:
        ax.set_title(title)
    ax.legend(loc="lower right", fontsize=9)
    return fig


def lab_side_view(
    side: ArrayLike,
    *,
    cup_height: float,
    table_height: float,
    theta2: float,
    theta3: float,
    offset: float,
    wrist_label: str = "wrist 1 → wrist 2 → flange",
    gripper_label: str = "gripper, straight down (its sideways part is out of this plane)",
    title: str | None = None,
    figsize: tuple[float, float] = (11.5, 7.0),
) -> Figure:
    """The arm in its own vertical plane: the two-link problem of reaching wrist 1.

    Parameters
    ----------
    side : array_like, shape (7, 2)
        The base and DH frames 1 … 6 in the arm's plane: (distance along the arm's
        direction u, height above the base frame's origin), metres.
    cup_height : float
        Height of the gripper tip (the wrist centre's height), metres.
    table_height : float
        Height of the table top, metres (negative: below the base frame's origin).
    theta2, theta3 : float
        Shoulder and elbow angles, radians; positive turns a link downwards in this view.
    offset : float
        The wrist's sideways offset out of this plane, metres.
    wrist_label, gripper_label : str
        Legend entries of the wrist links and of the gripper.
    title : str, optional
    figsize : tuple of float

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> side = np.array([[0, 0], [0, 0.15], [0.08, 0.38], [0.15, 0.18], [0.15, 0.18],
    ...                  [0.23, 0.18], [0.23, 0.1]])
    >>> fig = lab_side_view(side, cup_height=0.04, table_height=-0.01, theta2=-1.2,
    ...                     theta3=2.5, offset=0.11)
    >>> fig.axes[0].get_aspect()
    1.0
    >>> plt.close(fig)
    """
    side = np.asarray(side, dtype=float)
    shoulder, elbow, wrist1 = side[1], side[2], side[3]
    shoulder_height = shoulder[1]
    r, h = wrist1[0] - shoulder[0], wrist1[1] - shoulder_height
    far = side[:, 0].max() + 0.07  # where the h arrow stands
    fig, ax = plt.subplots(figsize=figsize, layout="constrained")
    ax.axhline(table_height, color="tan", linewidth=6, alpha=0.6, label="table top")
    ax.plot(
        *side[:4].T,
        "-o",
        color="0.35",
        linewidth=5,
        markersize=7,
        label="base, shoulder, elbow, wrist 1",
    )
    ax.plot(
        *side[4:].T,
        "-o",
        color="0.6",
        linewidth=4,
        markersize=6,
        label=wrist_label,
    )
    ax.plot(
        [side[6, 0], side[6, 0]],
        [side[6, 1], cup_height],
        color="tab:orange",
        linewidth=4,
        label=gripper_label,
    )
    ax.plot(
        side[6, 0],
        cup_height,
        "o",
        color="tab:purple",
        markersize=9,
        label="wrist centre at the cup's height, z_c",
    )
    ax.plot(
        [shoulder[0], wrist1[0]],
        [shoulder[1], wrist1[1]],
        ":",
        color="tab:purple",
        linewidth=2,
        label=f"shoulder to wrist 1: √(r² + h²) = {np.hypot(r, h):.3f} m",
    )
    below = shoulder_height - 0.05
    ax.annotate(
        "",
        xy=(wrist1[0], below),
        xytext=(shoulder[0], below),
        arrowprops={"arrowstyle": "<->", "color": "tab:blue"},
    )
    ax.text(
        shoulder[0] + r / 2,
        below - 0.015,
        "r",
        color="tab:blue",
        ha="center",
        va="top",
        fontsize=12,
    )
    ax.annotate(
        "",
        xy=(far, wrist1[1]),
        xytext=(far, shoulder_height),
        arrowprops={"arrowstyle": "<->", "color": "tab:blue", "shrinkA": 0, "shrinkB": 0},
    )
    ax.text(far + 0.01, shoulder_height + h / 2, "h", color="tab:blue", va="center", fontsize=12)
    ax.plot([shoulder[0], far + 0.01], [shoulder_height] * 2, "--", color="tab:blue", lw=0.8)
    ax.plot([side[5, 0], far + 0.01], [wrist1[1]] * 2, "--", color="tab:blue", linewidth=0.8)
    upper, fore = -theta2, -(theta2 + theta3)  # link directions in this view
    draw_angle_arc(ax, shoulder, 0.05, 0.0, upper, "−θ2", "tab:red", 1.5)
    draw_angle_arc(ax, elbow, 0.045, fore, upper, "θ3", "tab:red", 1.6)
    draw_angle_arc(ax, wrist1, 0.04, fore, 0.0, "−θ4", "tab:red", 1.6)
    for corner, direction in ((elbow, upper), (wrist1, fore)):  # links extended
        ax.plot(
            [corner[0], corner[0] + 0.07 * np.cos(direction)],
            [corner[1], corner[1] + 0.07 * np.sin(direction)],
            "--",
            color="tab:red",
            linewidth=0.8,
        )
    ax.text(
        wrist1[0] + 0.012,
        wrist1[1] + 0.03,
        f"wrist 1 (the sheet's 3end); from\nhere the wrist is offset {offset:.3f} m\n"
        "out of this plane",
        fontsize=9,
        va="bottom",
    )
    ax.set_aspect("equal")
    ax.set_xlim(min(side[:, 0].min(), 0.0) - 0.1, far + 0.06)
    ax.set_ylim(table_height - 0.02, side[:, 1].max() + 0.09)
    ax.grid(True, alpha=0.3)
    ax.set_xlabel("distance from the base axis along the arm's direction u (m)")
    ax.set_ylabel("height above the base frame's origin (m)")
    if title:
        ax.set_title(title)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=9)
    return fig


def lab_elbows_figure(
    side: ArrayLike,
    elbows: Sequence[tuple[ArrayLike, str, str]],
    *,
    lengths: tuple[float, float],
    table_height: float,
    shoulder_label: str = "shoulder axis",
    title: str | None = None,
    figsize: tuple[float, float] = (8.5, 8.0),
) -> Figure:
    """The planar two-link sub-problem: both elbows reaching the same wrist-1 point.

    Parameters
    ----------
    side : array_like, shape (7, 2)
        The lab arm's base and DH frames 1 … 6 in its plane, as for :func:`lab_side_view`;
        the base column and the wrist, which both elbows share, are drawn from it.
    elbows : sequence of (points, label, colour)
        Each elbow's shoulder, elbow and wrist 1 in the plane, shape (3, 2), metres.
    lengths : (float, float)
        Upper arm and forearm lengths, metres: the reachable ring around the shoulder.
    table_height : float
        Height of the table top, metres.
    shoulder_label : str
        Legend entry of the shoulder axis.
    title : str, optional
    figsize : tuple of float

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> side = np.array([[0, 0], [0, 0.15], [0.08, 0.38], [0.15, 0.18], [0.15, 0.18],
    ...                  [0.23, 0.18], [0.23, 0.1]])
    >>> fig = lab_elbows_figure(side, [(side[1:4], "elbow", "0.3")], lengths=(0.24, 0.21),
    ...                         table_height=-0.01)
    >>> len(fig.axes[0].get_legend().get_texts())
    6
    >>> plt.close(fig)
    """
    side = np.asarray(side, dtype=float)
    shoulder, wrist1 = side[1], side[3]
    upper, fore = lengths
    fig, ax = plt.subplots(figsize=figsize, layout="constrained")
    ax.add_patch(
        Wedge(
            shoulder,
            upper + fore,
            0,
            360,
            width=2 * min(upper, fore),
            color="tab:green",
            alpha=0.12,
            label=f"reachable ring for wrist 1: {abs(upper - fore):.3f} m ≤ d ≤ "
            f"{upper + fore:.3f} m",
        )
    )
    for points, name, colour in elbows:
        ax.plot(
            *np.asarray(points, dtype=float).T,
            "-o",
            color=colour,
            linewidth=4,
            markersize=7,
            label=name,
        )
    ax.plot(*side[:2].T, "-", color="0.6", linewidth=4, label="base column and wrist (shared)")
    ax.plot(*side[3:].T, "-", color="0.6", linewidth=3)
    ax.plot(*wrist1, "*", color="black", markersize=14, zorder=5, label="wrist 1: the tip to reach")
    ax.plot(*shoulder, "k+", markersize=14, markeredgewidth=2, label=shoulder_label)
    ax.axhline(table_height, color="tan", linewidth=6, alpha=0.6, label="table top")
    extent = upper + fore + 0.04
    ax.set_aspect("equal")
    ax.set_xlim(shoulder[0] - extent, shoulder[0] + extent)
    ax.set_ylim(shoulder[1] - extent, shoulder[1] + extent)
    ax.grid(True, alpha=0.3)
    ax.set_xlabel("distance from the base axis along the arm's direction u (m)")
    ax.set_ylabel("height above the base frame's origin (m)")
    if title:
        ax.set_title(title)
    ax.legend(loc="upper left", fontsize=9)
    return fig


def error_maps_figure(
    xs: ArrayLike,
    ys: ArrayLike,
    panels: Sequence[tuple[ArrayLike, str]],
    *,
    valid: ArrayLike,
    floor: float,
    contours: Sequence[tuple[ArrayLike, str, str, str]] = (),
    marker: tuple[ArrayLike, str] | None = None,
    invalid_label: str = "out of reach",
    missing_label: str = "reachable, but no answer (NaN)",
    colorbar_label: str = "error (m)",
    xlabel: str = "x (m)",
    ylabel: str = "y (m)",
    title: str | None = None,
    figsize: tuple[float, float] = (15.0, 8.2),
) -> Figure:
    """Maps of an error over a grid of targets, on a log colour scale, side by side.

    Grid cells outside ``valid`` are grey; valid cells whose error is not finite (no answer)
    are red.

    Parameters
    ----------
    xs, ys : array_like, shapes (nx,) and (ny,)
        Coordinates of the evenly spaced grid, metres.
    panels : sequence of (errors, title)
        ``errors`` has shape (ny, nx); exact zeros are drawn at ``floor``.
    valid : array_like of bool, shape (ny, nx)
        The cells that have an answer to compare with.
    floor : float
        Bottom of the colour scale (its top is 1).
    contours : sequence of (field, colour, linestyle, label)
        Fields of shape (ny, nx) whose zero level is drawn as a line.
    marker : (xy, label), optional
        A point marked with a white plus.
    invalid_label, missing_label, colorbar_label, xlabel, ylabel, title : str
    figsize : tuple of float

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> xs, ys = np.linspace(-1, 1, 5), np.linspace(-1, 1, 4)
    >>> gx, gy = np.meshgrid(xs, ys)
    >>> fig = error_maps_figure(xs, ys, [(np.abs(gx) * 1e-3, "left")], valid=gy > -0.9,
    ...                        floor=1e-16, contours=[(gx, "white", "--", "x = 0")])
    >>> fig.axes[0].get_title()
    'left'
    >>> plt.close(fig)
    """
    xs, ys = np.asarray(xs, dtype=float), np.asarray(ys, dtype=float)
    dx, dy = 0.5 * (xs[1] - xs[0]), 0.5 * (ys[1] - ys[0])
    extent = (xs[0] - dx, xs[-1] + dx, ys[0] - dy, ys[-1] + dy)
    grid_x, grid_y = np.meshgrid(xs, ys)
    valid = np.asarray(valid, dtype=bool)
    fig, axes = plt.subplots(
        1, len(panels), figsize=figsize, sharey=True, layout="constrained", squeeze=False
    )
    image = None
    for ax, (errors, caption) in zip(axes[0], panels):
        errors = np.asarray(errors, dtype=float)
        shown = np.where(valid, np.maximum(errors, floor), np.nan)
        image = ax.imshow(
            shown, extent=extent, origin="lower", cmap="viridis", norm=LogNorm(vmin=floor, vmax=1)
        )
        missing = np.where(valid & ~np.isfinite(errors), 1.0, np.nan)
        ax.imshow(missing, extent=extent, origin="lower", cmap=ListedColormap(["tab:red"]))
        ax.imshow(
            np.where(valid, np.nan, 1.0),
            extent=extent,
            origin="lower",
            cmap=ListedColormap(["0.85"]),
        )
        for field, colour, style, _ in contours:
            ax.contour(
                grid_x,
                grid_y,
                np.asarray(field),
                levels=[0.0],
                colors=colour,
                linestyles=style,
                linewidths=1.5,
            )
        if marker is not None:
            ax.plot(*marker[0], "P", color="white", markeredgecolor="black", markersize=13)
        ax.set_title(caption)
        ax.set_xlabel(xlabel)
        ax.set_aspect("equal")
    axes[0, 0].set_ylabel(ylabel)
    handles = [
        Patch(facecolor="0.85", edgecolor="0.4", label=invalid_label),
        Patch(facecolor="tab:red", edgecolor="0.4", label=missing_label),
    ]
    handles += [
        Line2D([], [], color=colour, linestyle=style, label=label)
        for _, colour, style, label in contours
    ]
    if marker is not None:
        handles.append(
            Line2D(
                [],
                [],
                marker="P",
                color="white",
                markeredgecolor="black",
                linestyle="",
                markersize=11,
                label=marker[1],
            )
        )
    fig.legend(handles=handles, loc="outside lower center", ncol=3, fontsize=9, facecolor="0.7")
    fig.colorbar(image, ax=axes[0], shrink=0.8, label=colorbar_label)
    if title:
        fig.suptitle(title, fontsize=13)
    return fig


def joint_paths_figure(
    fraction: ArrayLike,
    panels: Sequence[tuple[ArrayLike, str]],
    *,
    levels: Sequence[tuple[float, str, str]] = (
        (np.pi, ":", "±π: where wrapping cuts"),
        (2 * np.pi, "--", "±2π: UR's joint limits"),
    ),
    highlight: int | None = 5,
    xlabel: str = "position along the path (0 = start, 1 = end)",
    title: str | None = None,
    figsize: tuple[float, float] = (15.0, 5.5),
) -> Figure:
    """Joint angles along a path, one panel per way of computing them.

    Parameters
    ----------
    fraction : array_like, shape (N,)
        Position along the path.
    panels : sequence of tuple
        Each ``(q, title)``.
        ``q`` has shape (N, 6), radians.
    levels : sequence of (angle, linestyle, label)
        Horizontal lines drawn at ± each angle.
    highlight : int, optional
        Index of a joint drawn thicker.
    xlabel, title : str
    figsize : tuple of float

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> s = np.linspace(0, 1, 5)
    >>> fig = joint_paths_figure(s, [(np.outer(s, np.ones(6)), "one")])
    >>> len(fig.axes[0].get_lines())  # six joints, four levels
    10
    >>> plt.close(fig)
    """
    s = np.asarray(fraction, dtype=float)
    fig, axes = plt.subplots(
        1, len(panels), figsize=figsize, sharey=True, layout="constrained", squeeze=False
    )
    for ax, (q, caption) in zip(axes[0], panels):
        q = np.asarray(q, dtype=float)
        for joint in range(q.shape[1]):
            ax.plot(
                s,
                q[:, joint],
                linewidth=2.5 if joint == highlight else 1.5,
                label=f"joint {joint + 1}",
            )
        for level, style, name in levels:
            ax.axhline(level, color="0.5", linestyle=style, linewidth=1, label=name)
            ax.axhline(-level, color="0.5", linestyle=style, linewidth=1)
        ax.set_title(caption)
        ax.set_xlabel(xlabel)
        ax.grid(True, alpha=0.3)
    axes[0, 0].set_ylabel("joint angle (rad)")
    axes[0, 0].legend(loc="lower right", fontsize=8, ncol=2)
    if title:
        fig.suptitle(title, fontsize=13)
    return fig


# ---------------------------------------------------------------------------------------------
# the tracking report
# ---------------------------------------------------------------------------------------------

# imported with the section that draws it (urkin.tracking_report imports this module lazily)

#: Where :func:`tracking_report_figure` draws a value of exactly zero on its log axes.
_REPORT_FLOOR = 1e-17


#: Colour and line style of each singular family in :func:`tracking_report_figure`.
_FAMILY_STYLES = {
    "shoulder": ("tab:pink", "-"),
    "elbow": ("tab:olive", "--"),
    "wrist": ("tab:cyan", "-."),
}


def _runs(indices: ArrayLike) -> list[tuple[int, int]]:
    """Consecutive runs ``(first, last)`` in sorted integer indices."""
    k = np.asarray(indices, dtype=int)
    if k.size == 0:
        return []
    breaks = np.flatnonzero(np.diff(k) > 1)
    return list(zip(k[np.r_[0, breaks + 1]].tolist(), k[np.r_[breaks, len(k) - 1]].tolist()))


def _mark_failures(ax, failed: np.ndarray) -> None:
    """Shade the failed samples (consecutive ones as one band)."""
    for i, (first, last) in enumerate(_runs(failed)):
        ax.axvspan(
            first - 0.5,
            last + 0.5,
            color="tab:red",
            alpha=0.2,
            linewidth=0,
            label=f"failed samples ({len(failed)})" if i == 0 else None,
        )


def tracking_report_figure(
    report: TrackingReport,
    *,
    title: str | None = None,
    figsize: tuple[float, float] = (11.0, 7.5),
) -> Figure:
    """The per-sample numbers of a tracking report, in four panels.

    1. **Target spacing** (mm) between targets k and k + 1, drawn between the two samples,
       with the 1 mm line and the repeated samples (spacing 0, same orientation) marked.
    2. **Pose error** at each sample: position (m) and orientation (rad) on one log axis;
       an error of exactly zero is drawn at 1e-17.
    3. **Joint angles** (degrees, not wrapped) with the joint limits (±360° on every UR arm),
       so that winding shows; a branch flip of a singular family is a vertical line between
       the two samples.
    4. **Distance from the singularities** on a log axis: the absolute shoulder factor (m),
       ``|sin q3|`` (elbow) and ``|sin q5|`` (wrist); zero drawn at 1e-17.

    Failed samples are shaded red in panels 2 and 4.

    Parameters
    ----------
    report : urkin.tracking_report.TrackingReport
        From :func:`urkin.tracking_report.tracking_report` (or a tracking's ``report``).
    title : str, optional
        Title of the whole figure.
    figsize : tuple of float

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ValueError
        If the report has no per-sample arrays.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import urkin
    >>> from urkin.tracking_report import tracking_report
    >>> ur5 = urkin.robot("ur5")
    >>> q = np.linspace([0.3, -1.2, 1.4, -0.6, 1.1, 0.5], [0.5, -1.0, 1.0, -0.2, 1.3, 9.0], 40)
    >>> fig = tracking_report_figure(tracking_report(ur5, urkin.fk(ur5, q), q))
    >>> [ax.get_title() for ax in fig.axes]  # doctest: +NORMALIZE_WHITESPACE
    ['Target spacing', 'Pose error at each sample', 'Joint angles',
     'Distance from the singularities']
    >>> plt.close(fig)
    """
    q = np.asarray(report.q, dtype=float)
    samples = len(q)
    if samples == 0 or len(report.position_errors) != samples:
        raise ValueError(
            "report has no per-sample arrays: make it with urkin.tracking_report.tracking_report"
        )
    k = np.arange(samples)
    between = k[:-1] + 0.5
    failed = np.array(sorted(report.failures), dtype=int)
    fig, axes = plt.subplots(2, 2, figsize=figsize, layout="constrained", sharex=True)
    spacing_ax, error_ax, joint_ax, margin_ax = axes.ravel()

    # (1) spacing
    spacing_mm = np.asarray(report.spacings) * 1e3
    spacing_ax.plot(
        between,
        spacing_mm,
        ".-" if samples <= 200 else "-",  # dots only where they can be told apart
        color="tab:blue",
        markersize=3,
        linewidth=1,
        label="spacing",
    )
    spacing_ax.axhline(1.0, color="0.3", linestyle="--", linewidth=1, label="1 mm")
    repeated = np.asarray(report.repeated, dtype=int)
    if len(repeated):
        spacing_ax.plot(
            repeated + 0.5,
            np.zeros(len(repeated)),
            "x",
            color="tab:red",
            markersize=9,
            markeredgewidth=2,
            clip_on=False,
            label=f"repeated sample ({len(repeated)})",
        )
    spacing_ax.set_ylim(0, max(1.2, 1.1 * float(spacing_mm.max())))
    spacing_ax.set_title("Target spacing")
    spacing_ax.set_ylabel("spacing to the next target (mm)")

    # (2) pose error
    error_ax.semilogy(
        k,
        np.maximum(report.position_errors, _REPORT_FLOOR),
        "-",
        color="tab:blue",
        linewidth=1.2,
        label="position (m)",
    )
    error_ax.semilogy(
        k,
        np.maximum(report.orientation_errors, _REPORT_FLOOR),
        "--",
        color="tab:orange",
        linewidth=1.2,
        label="orientation (rad)",
    )
    error_ax.axhline(
        np.finfo(float).eps,
        color="0.5",
        linestyle=":",
        linewidth=1,
        label="machine precision, 2.2e-16",
    )
    _mark_failures(error_ax, failed)
    worst = max(float(np.max(report.position_errors)), float(np.max(report.orientation_errors)))
    error_ax.set_ylim(_REPORT_FLOOR / 3, max(1e-12, 3 * worst))  # round-off reads as round-off
    error_ax.set_title("Pose error at each sample")
    error_ax.set_ylabel(f"error (m or rad; 0 drawn at {_REPORT_FLOOR:.0e})")

    # (3) joint angles
    for joint in range(6):
        joint_ax.plot(k, np.degrees(q[:, joint]), linewidth=1.4, label=f"joint {joint + 1}")
    limits = np.asarray(report.joint_limits, dtype=float)
    levels = np.unique(np.degrees(limits)) if limits.size else np.array([-360.0, 360.0])
    if len(levels) == 2 and levels[0] == -levels[1]:
        limit_label = f"limits ±{levels[1]:.0f}°"
    else:
        limit_label = "limits " + ", ".join(f"{v:+.0f}°" for v in levels)
    for i, level in enumerate(levels):
        joint_ax.axhline(
            level, color="0.3", linestyle=":", linewidth=1.2, label=limit_label if i == 0 else None
        )
    for family, where in report.branch_flips.items():
        colour, style = _FAMILY_STYLES.get(family, ("0.3", "-"))
        for i, flip in enumerate(np.asarray(where, dtype=int)):
            joint_ax.axvline(
                flip + 0.5,
                color=colour,
                linestyle=style,
                linewidth=1.6,
                label=f"{family} flip ({len(where)})" if i == 0 else None,
            )
    joint_ax.set_title("Joint angles")
    joint_ax.set_ylabel("joint angle (°, not wrapped)")
    low = min(float(np.degrees(q).min()), float(levels.min()))
    high = max(float(np.degrees(q).max()), float(levels.max()))
    tick = 90.0
    while (high - low) / tick > 9:  # ticks at multiples of 90°, at most about ten
        tick *= 2
    joint_ax.set_yticks(np.arange(np.ceil(low / tick), np.floor(high / tick) + 1) * tick)
    span = high - low
    joint_ax.set_ylim(low - 0.06 * span, high + 0.32 * span)  # the top: room for the legend
    joint_ax.legend(fontsize=7.5, loc="upper center", ncol=5, framealpha=0.85, columnspacing=1.0)

    # (4) singularity margins
    factors = np.abs(np.asarray(report.factors, dtype=float))
    names = ("shoulder |factor| (m)", "elbow |sin q3|", "wrist |sin q5|")
    for column, (name, family) in enumerate(zip(names, ("shoulder", "elbow", "wrist"))):
        colour, style = _FAMILY_STYLES[family]
        margin_ax.semilogy(
            k,
            np.maximum(factors[:, column], _REPORT_FLOOR),
            color=colour,
            linestyle=style,
            linewidth=1.4,
            label=name,
        )
    smallest = float(np.maximum(factors, _REPORT_FLOOR).min())
    margin_ax.set_ylim(min(smallest / 3, 1e-3), 3.0)  # at least three decades: no minor labels
    _mark_failures(margin_ax, failed)
    margin_ax.set_title("Distance from the singularities")
    margin_ax.set_ylabel(f"|factor| (m or 1; 0 drawn at {_REPORT_FLOOR:.0e})")

    for ax in (spacing_ax, error_ax, margin_ax):
        ax.legend(fontsize=8, loc="best", framealpha=0.85)
    for ax in axes.ravel():
        ax.grid(True, alpha=0.3)
        ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    for ax in axes[1]:
        ax.set_xlabel("sample")
    if title:
        fig.suptitle(title, fontsize=13)
    return fig


def time_scaling_figure(
    scalings: Sequence,
    *,
    samples: int = 401,
    title: str | None = None,
    figsize: tuple[float, float] = (11.0, 3.6),
) -> Figure:
    """Position, speed and acceleration of rest-to-rest time scalings, side by side.

    Parameters
    ----------
    scalings : sequence of urkin.trajectory.TimeScaling
        Each is drawn over ``0 ≤ t ≤ T`` in its own colour, labelled with its kind and ``T``.
    samples : int
        Points per curve.
    title : str, optional
        Figure title.
    figsize : tuple of float
        Inches.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from urkin.trajectory import time_scaling
    >>> fig = time_scaling_figure([time_scaling("cubic", 2.0), time_scaling("quintic", 2.0)])
    >>> [ax.get_ylabel() for ax in fig.axes]
    ['s', 'ṡ (1/s)', 's̈ (1/s²)']
    >>> plt.close(fig)
    """
    fig = plt.figure(figsize=figsize, layout="constrained")
    axes = fig.subplots(1, 3)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for k, scaling in enumerate(scalings):
        t = np.linspace(0.0, scaling.T, samples)
        values = scaling(t)
        label = f"{scaling.kind}, T = {scaling.T:.2f} s"
        for ax, value in zip(axes, values):
            ax.plot(t, value, color=colours[k % len(colours)], linewidth=2, label=label)
    for ax, name, what in zip(
        axes, ("s", "ṡ (1/s)", "s̈ (1/s²)"), ("path parameter", "speed", "acceleration")
    ):
        ax.set_xlabel("t (s)")
        ax.set_ylabel(name)
        ax.set_title(what)
        ax.grid(alpha=0.3)
        ax.axhline(0.0, color="0.5", linewidth=0.8)
    axes[0].legend(loc="upper left", fontsize=8)
    if title:
        fig.suptitle(title)
    return fig


from urkin.animation import Animation, animate  # noqa: E402

# ---------------------------------------------------------------------------------------------
# lesson 09: spheres, scenes, edges and the planners' trees
# ---------------------------------------------------------------------------------------------

#: Colour of obstacles in the figures of :mod:`urkin.planning` scenes.
OBSTACLE_COLOUR = "tab:brown"


def draw_spheres(
    ax,
    centres: ArrayLike,
    radii: ArrayLike,
    *,
    color: str | Sequence[str] = "tab:blue",
    alpha: float = 0.25,
    resolution: int = 12,
) -> list:
    """Draw balls as translucent surfaces.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.Axes3D
    centres : array_like, shape (S, 3)
        Centres, metres (already placed: :meth:`urkin.planning.SphereModel.place`).
    radii : array_like, shape (S,) or float
        Radii, metres.
    color : str or sequence of str
        One colour, or one per ball.
    alpha : float
        Opacity.
    resolution : int
        Grid lines around each ball (half as many from pole to pole).

    Returns
    -------
    list
        The surfaces, one per ball.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> ax = axes3d()
    >>> len(draw_spheres(ax, [[0, 0, 0.2], [0, 0, 0.4]], 0.05, color=["tab:blue", "tab:red"]))
    2
    >>> plt.close(ax.figure)
    """
    c = np.asarray(centres, dtype=float).reshape(-1, 3)
    r = np.broadcast_to(np.asarray(radii, dtype=float), (len(c),))
    colours = [color] * len(c) if isinstance(color, str) else list(color)
    if len(colours) != len(c):
        raise ValueError(f"color must be one colour or one per ball ({len(c)}); got {len(colours)}")
    u, v = np.meshgrid(
        np.linspace(0.0, 2.0 * np.pi, resolution + 1),
        np.linspace(0.0, np.pi, resolution // 2 + 1),
    )
    unit = np.stack([np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v)])
    return [
        ax.plot_surface(
            *(centre[:, None, None] + radius * unit),
            color=colour,
            alpha=alpha,
            linewidth=0,
            shade=True,
        )
        for centre, radius, colour in zip(c, r, colours)
    ]


def _box_faces(centre: np.ndarray, size: np.ndarray, rotation: np.ndarray) -> list[np.ndarray]:
    """The six faces (4 corners each) of a box."""
    signs = np.array(
        [
            [-1, -1, -1],
            [1, -1, -1],
            [1, 1, -1],
            [-1, 1, -1],
            [-1, -1, 1],
            [1, -1, 1],
            [1, 1, 1],
            [-1, 1, 1],
        ],
        dtype=float,
    )
    corners = centre + (signs * (size / 2)) @ rotation.T
    faces = ((0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (1, 2, 6, 5), (0, 3, 7, 4))
    return [corners[list(face)] for face in faces]


def _cylinder_points(centre: np.ndarray, axis: np.ndarray, radius: float, length: float):
    """Grid (3, 2, 17) of a cylinder's side."""
    e1 = np.cross(axis, [1.0, 0.0, 0.0] if abs(axis[0]) < 0.9 else [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(axis, e1)
    theta, t = np.meshgrid(np.linspace(0, 2 * np.pi, 17), np.array([-0.5, 0.5]))
    ring = radius * (
        np.cos(theta)[None] * e1[:, None, None] + np.sin(theta)[None] * e2[:, None, None]
    )
    return centre[:, None, None] + ring + length * t[None] * axis[:, None, None]


def _round_surface(ax, points: np.ndarray, color: str, alpha: float):
    return ax.plot_surface(*points, color=color, alpha=alpha, linewidth=0, shade=True)


def draw_scene(
    ax,
    scene,
    *,
    color: str = OBSTACLE_COLOUR,
    alpha: float = 0.25,
    highlight: Mapping[str, str] | None = None,
    label: str | None = "obstacles",
    clip: bool = True,
) -> list:
    """Draw the obstacles of a :class:`urkin.planning.Scene`: boxes, cylinders, spheres and
    capsules, as translucent solids.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.Axes3D
    scene : urkin.planning.Scene
    color : str
        Colour of the obstacles.
    alpha : float
        Opacity of their faces.
    highlight : mapping, optional
        Obstacle name → colour, for obstacles drawn in another colour.
    label : str, optional
        Legend entry of the obstacles (a patch; 3D solids have none of their own).
    clip : bool
        Cut boxes that are not rotated (a table, a wall) to the axes' current limits: 3D
        artists are not clipped, and a large table would cover the figure.  Set the limits
        first (:func:`axes3d`).

    Returns
    -------
    list
        The matplotlib artists.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from urkin import planning
    >>> scene = planning.Scene(
    ...     boxes=[planning.Box([0.4, 0, 0.1], [0.2, 0.4, 0.2], name="shelf")],
    ...     cylinders=[planning.Cylinder([0, 0.4, 0.2], [0, 0, 1], 0.03, 0.4)],
    ...     spheres=[planning.Sphere([0, -0.4, 0.3], 0.05)],
    ...     capsules=[planning.Capsule([0.2, 0.2, 0.5], [0.3, 0.3, 0.5], 0.02)],
    ... )
    >>> ax = axes3d()
    >>> len(draw_scene(ax, scene, highlight={"shelf": "tab:red"}))  # a capsule is 3 surfaces
    7
    >>> plt.close(ax.figure)
    """
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    colours = dict(highlight or {})
    names = iter(scene.names)
    artists: list = []
    view = np.array([ax.get_xlim(), ax.get_ylim(), ax.get_zlim()])  # (3, 2)
    for box in scene.boxes:
        face = colours.get(next(names), color)
        centre, size = box.centre, box.size
        if clip and np.allclose(box.rotation, np.eye(3)):  # 3D artists are not clipped
            low = np.maximum(centre - size / 2, view[:, 0])
            high = np.minimum(centre + size / 2, view[:, 1])
            if np.any(high <= low):
                continue  # wholly outside the view
            centre, size = (low + high) / 2, high - low
        solid = Poly3DCollection(
            _box_faces(centre, size, box.rotation),
            facecolor=face,
            edgecolor=face,
            linewidths=0.6,
            alpha=alpha,
        )
        artists.append(ax.add_collection3d(solid))
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 17), np.linspace(0, np.pi, 9))
    ball = np.stack([np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v)])
    for cylinder in scene.cylinders:
        face = colours.get(next(names), color)
        points = _cylinder_points(cylinder.centre, cylinder.axis, cylinder.radius, cylinder.length)
        artists.append(_round_surface(ax, points, face, alpha))
    for sphere in scene.spheres:
        face = colours.get(next(names), color)
        points = sphere.centre[:, None, None] + sphere.radius * ball
        artists.append(_round_surface(ax, points, face, alpha))
    for capsule in scene.capsules:  # a cylinder between two balls
        face = colours.get(next(names), color)
        along = capsule.b - capsule.a
        length = float(np.linalg.norm(along))
        if length > 0:
            middle = 0.5 * (capsule.a + capsule.b)
            points = _cylinder_points(middle, along / length, capsule.radius, length)
            artists.append(_round_surface(ax, points, face, alpha))
        for end in (capsule.a, capsule.b):
            points = end[:, None, None] + capsule.radius * ball
            artists.append(_round_surface(ax, points, face, alpha))
    if label:
        artists += _legend_patch(ax, color, label, alpha=max(alpha, 0.4))
    return artists


def _cube_with_obstacles(
    points: np.ndarray, scene, margin: float = 0.15
) -> tuple[np.ndarray, float]:
    """Centre and half-width of a cube holding ``points`` (N, 3) and the parts of the scene's
    boxes within ``margin`` of their bounding box (a huge table adds only its nearby part)."""
    low, high = points.min(axis=0), points.max(axis=0)
    shown = [points]
    for box in getattr(scene, "boxes", ()):
        corners = np.concatenate(_box_faces(box.centre, box.size, box.rotation))
        a = np.maximum(corners.min(axis=0), low - margin)
        b = np.minimum(corners.max(axis=0), high + margin)
        if np.all(b > a):
            shown.append(np.array([a, b]))
    everything = np.concatenate(shown)
    lo, hi = everything.min(axis=0), everything.max(axis=0)
    return 0.5 * (lo + hi), 0.52 * float((hi - lo).max())


def sphere_models_figure(
    robot: Robot,
    panels: Sequence[tuple[ArrayLike, ArrayLike, ArrayLike, str, ArrayLike | None]],
    *,
    scene=None,
    title: str | None = None,
    size: float = 5.5,
    center: ArrayLike | None = None,
    half_width: float | None = None,
    view: tuple[float, float] = (20.0, -60.0),
) -> Figure:
    """Sphere models of an arm, one panel per configuration, in a scene.

    Each panel draws the stick figure (as :func:`draw_robot`), the spheres (blue; red where
    the panel's ``hit`` flag is set) and the scene's obstacles, all panels in one cube.

    Parameters
    ----------
    robot : Robot
    panels : sequence of tuple
        Each ``(q, centres, radii, caption, hit)``: joint angles (rad, shape (6,)), the
        spheres' placed centres (S, 3) and radii (S,) in metres, the panel's title, and
        ``hit`` — None, or one bool per sphere (drawn red where True).
    scene : urkin.planning.Scene, optional
        Obstacles, drawn in every panel.
    title : str, optional
        Title of the whole figure.
    size : float
        Width and height of each panel, inches.
    center, half_width : optional
        The cube shown (metres); by default one that holds every sphere and the obstacles
        near them (boxes that are not rotated are cut to the cube).
    view : tuple of float
        ``(elevation, azimuth)`` in degrees.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import urkin
    >>> from urkin import planning
    >>> ur3 = urkin.robot("UR3")
    >>> model = planning.sphere_model(ur3)
    >>> q = np.array([0.0, -1.2, 1.0, -1.4, -1.57, 0.0])
    >>> fig = sphere_models_figure(ur3, [(q, model.place(q), model.radii, "fitted", None)])
    >>> fig.axes[0].get_title()
    'fitted'
    >>> plt.close(fig)
    """
    count = len(panels)
    if count == 0:
        raise ValueError("panels must hold at least one (q, centres, radii, caption, hit)")
    placed = [np.asarray(c, dtype=float).reshape(-1, 3) for _, c, _, _, _ in panels]
    if center is None or half_width is None:
        reach = np.concatenate(placed)
        radii = np.concatenate(
            [
                np.broadcast_to(np.asarray(r, dtype=float), (len(c),))
                for (_, _, r, _, _), c in zip(panels, placed)
            ]
        )
        base = fk_frames(robot, np.zeros(6))[0, :3, 3]
        points = np.concatenate(
            [reach - radii[:, None], reach + radii[:, None], base[None]], axis=0
        )
        cube_c, cube_half = _cube_with_obstacles(points, scene)
        c = cube_c if center is None else np.asarray(center, dtype=float)
        half = cube_half if half_width is None else half_width
    else:
        c, half = np.asarray(center, dtype=float), half_width
    fig = _figure(figsize=(size * count, size + 0.5))
    for index, ((q, _, radii, caption, hit), centres) in enumerate(zip(panels, placed)):
        ax = fig.add_subplot(1, count, index + 1, projection="3d")
        axes3d(ax, center=c, half_width=half, title=caption, view=view)
        if scene is not None:
            draw_scene(ax, scene, label="obstacles" if index == 0 else None)
        flags = np.zeros(len(centres), dtype=bool) if hit is None else np.asarray(hit, dtype=bool)
        colours = np.where(flags, "tab:red", "tab:blue").tolist()
        draw_spheres(ax, centres, radii, color=colours, alpha=0.22)
        draw_robot(ax, robot, q, frames=False, color="0.15", linewidth=3.0)
        if index == 0:
            _legend_patch(ax, "tab:blue", "spheres", alpha=0.4)
            if flags.any() or any(p[4] is not None and np.any(p[4]) for p in panels):
                _legend_patch(ax, "tab:red", "spheres touching an obstacle", alpha=0.4)
            ax.legend(loc="upper left", fontsize=8, framealpha=0.85)
    if title:
        fig.suptitle(title, fontsize=13)
    return fig


def signed_distance_figure(
    x: ArrayLike,
    y: ArrayLike,
    distance: ArrayLike,
    *,
    outline: ArrayLike | None = None,
    circles: Sequence[tuple[ArrayLike, float, str]] = (),
    xlabel: str = "x (m)",
    ylabel: str = "y (m)",
    title: str | None = None,
    figsize: tuple[float, float] = (7.5, 6.0),
) -> Figure:
    """A signed distance field on a plane: colours by distance (blue inside, red outside), the
    zero level (the obstacle's surface) in black, and circles for balls in the plane.

    Parameters
    ----------
    x, y : array_like, shape (nx,) and (ny,)
        The grid's coordinates in the plane, metres.
    distance : array_like, shape (ny, nx)
        Signed distance at each grid point, metres (negative inside).
    outline : array_like, shape (K, 2), optional
        A polygon drawn over the field (the obstacle's section), closed automatically.
    circles : sequence of tuple
        Each ``(centre (2,), radius, label)``: a ball's section, with its label beside it.
    xlabel, ylabel, title : str
    figsize : tuple of float

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> x = y = np.linspace(-1, 1, 41)
    >>> d = np.hypot(*np.meshgrid(x, y)) - 0.5
    >>> fig = signed_distance_figure(x, y, d, circles=[((0.7, 0.0), 0.1, "ball")])
    >>> fig.axes[0].get_xlabel(), fig.axes[1].get_ylabel()
    ('x (m)', 'signed distance (mm)')
    >>> plt.close(fig)
    """
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    d_mm = 1000.0 * np.asarray(distance, dtype=float)
    if d_mm.shape != (len(y), len(x)):
        raise ValueError(f"distance must have shape (len(y), len(x)) = {(len(y), len(x))}")
    fig, ax = plt.subplots(figsize=figsize, layout="constrained")
    bound = 50.0 * math.ceil(float(np.abs(d_mm).max()) / 50.0)  # a multiple of 5 cm
    levels = np.linspace(-bound, bound, 2 * int(bound // 25) + 1)  # every 25 mm
    filled = ax.contourf(x, y, d_mm, levels=levels, cmap="RdBu_r")
    ax.contour(x, y, d_mm, levels=levels[::2], colors="0.3", linewidths=0.4)
    ax.contour(x, y, d_mm, levels=[0.0], colors="black", linewidths=2.0)
    handles = [Line2D([], [], color="black", linewidth=2.0, label="distance 0: the surface")]
    if outline is not None:
        polygon = np.asarray(outline, dtype=float)
        closed = np.vstack([polygon, polygon[:1]])
        ax.plot(*closed.T, ":", color="0.1", linewidth=1.2)
    for centre, radius, text in circles:
        cx, cy = (float(v) for v in centre)
        ax.add_patch(Circle((cx, cy), radius, fill=False, color="tab:green", linewidth=2.0))
        ax.plot(cx, cy, "+", color="tab:green", markersize=8)
        ax.annotate(
            text,
            (cx, cy + radius),
            xytext=(0, 6),
            textcoords="offset points",
            ha="center",
            va="bottom",
            fontsize=9,
            bbox={"facecolor": "white", "alpha": 0.85, "edgecolor": "none", "pad": 1.5},
        )
    if circles:
        handles.append(
            Line2D([], [], color="tab:green", linewidth=2.0, label="a ball and its distance")
        )
    ax.set_aspect("equal")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.legend(handles=handles, loc="lower left", fontsize=8, framealpha=0.9)
    bar = fig.colorbar(filled, ax=ax, label="signed distance (mm)", shrink=0.9)
    tick = 100.0 if bound > 200 else 50.0
    bar.set_ticks(tick * np.arange(-math.floor(bound / tick), math.floor(bound / tick) + 1))
    if title:
        ax.set_title(title)
    return fig


def edge_clearance_figure(
    t: ArrayLike,
    clearance: ArrayLike,
    *,
    samples: ArrayLike | None = None,
    waypoints: ArrayLike = (0.0, 1.0),
    title: str | None = None,
    figsize: tuple[float, float] = (9.0, 4.0),
) -> Figure:
    """The clearance along a straight joint-space edge: where it dips below zero the arm is in
    collision, however free the waypoints are.

    Parameters
    ----------
    t : array_like, shape (N,)
        Position along the edge, 0 (start) to 1 (end).
    clearance : array_like, shape (N,)
        Signed clearance at each ``t``, metres (:func:`urkin.planning.clearance`).
    samples : array_like, optional
        The ``t`` an edge check samples, marked along the bottom.
    waypoints : array_like
        The ``t`` of the waypoints (drawn as large dots on the curve).
    title : str, optional
    figsize : tuple of float

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> t = np.linspace(0, 1, 101)
    >>> fig = edge_clearance_figure(t, 0.05 - 0.2 * np.sin(np.pi * t), samples=[0, 0.5, 1])
    >>> fig.axes[0].get_ylabel()
    'clearance (mm)'
    >>> plt.close(fig)
    """
    s = np.asarray(t, dtype=float)
    c = 1000.0 * np.asarray(clearance, dtype=float)
    fig, ax = plt.subplots(figsize=figsize, layout="constrained")
    ax.plot(s, c, color="tab:blue", linewidth=2, label="clearance along the edge")
    ax.fill_between(s, c, 0.0, where=c < 0, color="tab:red", alpha=0.3, label="in collision")
    ax.axhline(0.0, color="0.2", linewidth=1)
    ends = np.asarray(waypoints, dtype=float)
    ax.plot(
        ends,
        np.interp(ends, s, c),
        "o",
        color="tab:green",
        markersize=10,
        label="the waypoints (checked, free)",
        zorder=3,
    )
    low = min(float(c.min()), 0.0)
    high = max(float(c.max()), 0.0)
    span = max(high - low, 1.0)
    if samples is not None:
        marks = np.asarray(samples, dtype=float)
        ax.plot(
            marks,
            np.full(len(marks), low - 0.08 * span),
            "|",
            color="0.3",
            markersize=9,
            label=f"samples of the edge check ({len(marks)})",
            clip_on=False,
        )
    ax.set_ylim(low - 0.15 * span, high + 0.1 * span)
    ax.set_xlim(-0.02, 1.02)
    ax.set_xlabel("position along the edge (0 = start, 1 = end)")
    ax.set_ylabel("clearance (mm)")
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize=8, framealpha=0.9)
    if title:
        ax.set_title(title)
    return fig


def cspace_figure(
    x: ArrayLike,
    y: ArrayLike,
    free: ArrayLike,
    panels: Sequence[tuple[Sequence[tuple[ArrayLike, ArrayLike, str, str]], ArrayLike | None, str]],
    *,
    start: ArrayLike | None = None,
    goal: ArrayLike | None = None,
    xlabel: str = "joint 1 (rad)",
    ylabel: str = "joint 2 (rad)",
    title: str | None = None,
    size: float = 5.0,
) -> Figure:
    """Searches drawn in a two-joint configuration space: the configurations in collision
    shaded, each search's trees (or lists) as their edges, and the path found.

    Parameters
    ----------
    x, y : array_like, shape (nx,) and (ny,)
        The grid of the two joints (rad).
    free : array_like of bool, shape (ny, nx)
        Whether each grid configuration is free.
    panels : sequence of tuple
        Each ``(trees, path, caption)``: ``trees`` a sequence of ``(nodes (N, 2), parent (N,),
        colour, label)`` (parent −1 for a root), ``path`` an (M, 2) array or None.
    start, goal : array_like, shape (2,), optional
        Marked in every panel.
    xlabel, ylabel, title : str
    size : float
        Width of each panel, inches.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> x = y = np.linspace(-3, 3, 31)
    >>> free = np.hypot(*np.meshgrid(x, y)) > 1
    >>> tree = (np.array([[-2.0, 0.0], [-1.5, 1.5]]), np.array([-1, 0]), "tab:blue", "start tree")
    >>> fig = cspace_figure(x, y, free, [([tree], None, "a tree")], start=(-2, 0), goal=(2, 0))
    >>> fig.axes[0].get_title()
    'a tree'
    >>> plt.close(fig)
    """
    from matplotlib.collections import LineCollection

    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    mask = np.asarray(free, dtype=bool)
    if mask.shape != (len(y), len(x)):
        raise ValueError(f"free must have shape (len(y), len(x)) = {(len(y), len(x))}")
    count = len(panels)
    fig, axes = plt.subplots(
        1,
        count,
        figsize=(size * count, size * 1.15),
        layout="constrained",
        squeeze=False,
        sharey=True,
    )
    shade = ListedColormap(["0.72", "white"])
    for ax, (trees, path, caption) in zip(axes[0], panels):
        ax.pcolormesh(
            x, y, mask.astype(float), cmap=shade, vmin=0, vmax=1, shading="nearest", rasterized=True
        )
        handles = [Patch(facecolor="0.72", label="in collision")]
        for nodes, parent, colour, label in trees:
            nodes = np.asarray(nodes, dtype=float).reshape(-1, 2)
            parent = np.asarray(parent, dtype=int)
            child = np.flatnonzero(parent >= 0)
            segments = np.stack([nodes[parent[child]], nodes[child]], axis=1)
            ax.add_collection(LineCollection(segments, colors=colour, linewidths=1.2))
            ax.plot(*nodes.T, ".", color=colour, markersize=4)
            handles.append(
                Line2D([], [], color=colour, marker=".", label=f"{label} ({len(nodes)})")
            )
        if path is not None and len(path):
            p = np.asarray(path, dtype=float).reshape(-1, 2)
            ax.plot(*p.T, "-", color="tab:red", linewidth=2.5, zorder=4)
            handles.append(Line2D([], [], color="tab:red", linewidth=2.5, label="path found"))
        for point, marker, label in ((start, "o", "start"), (goal, "*", "goal")):
            if point is not None:
                ax.plot(
                    *np.asarray(point, dtype=float),
                    marker,
                    color="black",
                    markersize=11,
                    markerfacecolor="gold",
                    zorder=5,
                )
                handles.append(
                    Line2D(
                        [],
                        [],
                        linestyle="",
                        marker=marker,
                        color="black",
                        markerfacecolor="gold",
                        markersize=9,
                        label=label,
                    )
                )
        ax.set_xlim(x[0], x[-1])
        ax.set_ylim(y[0], y[-1])
        ax.set_title(caption)
        ax.set_xlabel(xlabel)
        ax.legend(
            handles=handles,
            loc="upper center",
            bbox_to_anchor=(0.5, -0.13),
            ncol=2,
            fontsize=8,
            frameon=False,
        )
    axes[0, 0].set_ylabel(ylabel)
    if title:
        fig.suptitle(title, fontsize=13)
    return fig


def animate_plan(
    robot: Robot,
    qs: ArrayLike,
    scene,
    *,
    title: str | None = None,
    max_frames: int = 40,
    view: tuple[float, float] = (25.0, -30.0),
    center: ArrayLike | None = None,
    half_width: float | None = None,
    **options,
) -> Animation:
    """:func:`animate` with a scene's obstacles drawn in every frame (the arm in front of them).

    Parameters
    ----------
    robot : Robot
    qs : array_like, shape (M, 6)
        The motion, radians (a planned path sampled finely enough to look continuous, e.g.
        :func:`urkin.planning.time_parametrize`'s samples).
    scene : urkin.planning.Scene
    title : str, optional
    max_frames : int
    view : tuple of float
        ``(elevation, azimuth)`` in degrees; azimuths in (−180°, 0°) keep x increasing to the
        right.
    center, half_width : optional
        The view cube, metres; by default the cube that holds the arm in every sample and the
        parts of the obstacles within 15 cm of it (boxes that are not rotated are cut to it).
    **options
        Passed to :func:`animate`.

    Returns
    -------
    Animation

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import urkin
    >>> from urkin import planning
    >>> wall = planning.Scene(boxes=[planning.Box([-0.4, 0, 0.2], [0.05, 0.5, 0.4])])
    >>> qs = np.linspace([0.5, -1.2, 1.2, -1.5, -1.57, 0], [-0.5, -1.2, 1.2, -1.5, -1.57, 0], 3)
    >>> animate_plan(urkin.robot("UR3"), qs, wall, max_frames=3)
    <Animation: UR3, 3 frames of 3 samples>
    """
    from urkin.planning import Scene

    robot = check_robot(robot)
    q = check_joints(qs, "qs").reshape(-1, 6)
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a planning.Scene; got {type(scene).__name__}")
    if center is None or half_width is None:
        joints = fk_frames(robot, q)[..., :3, 3].reshape(-1, 3)
        cube_c, cube_half = _cube_with_obstacles(joints, scene)
        center = cube_c if center is None else center
        half_width = cube_half if half_width is None else half_width

    def scenery(ax) -> None:
        ax.view_init(*view)
        ax.computed_zorder = False  # obstacles first, the arm always in front of them
        draw_scene(ax, scene, alpha=0.2, label=None)

    return animate(
        robot,
        q,
        title=title,
        max_frames=max_frames,
        center=center,
        half_width=half_width,
        scenery=scenery,
        **options,
    )


# ---------------------------------------------------------------------------------------------
# lesson 10: blocks on the table, goals, and tasks
# ---------------------------------------------------------------------------------------------

#: Colours of the blocks of a tabletop world, in the order of ``world.blocks``.
BLOCK_COLOURS = ("tab:blue", "tab:green", "tab:purple", "tab:orange", "tab:cyan")


def _block_artist(ax, block, color: str, alpha: float = 0.85):
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    solid = Poly3DCollection(
        _box_faces(block.centre, block.size, block.pose[:3, :3]),
        facecolor=color,
        edgecolor="0.2",
        linewidths=0.6,
        alpha=alpha,
    )
    return ax.add_collection3d(solid)


def draw_world(ax, world, *, goals: Sequence = (), labels: bool = True) -> dict:
    """Draw a :class:`urkin.planning.World`: the table, the obstacles, the blocks (each in its
    colour of :data:`BLOCK_COLOURS`, named on its top) and goal footprints (dashed).

    Returns
    -------
    dict
        Block name → its artist (a ``Poly3DCollection`` whose vertices an animation moves).
    """
    names = {b.name for b in world.blocks}
    draw_scene(ax, world.scene(without=tuple(names)), alpha=0.18, label=None)
    artists = {}
    for k, block in enumerate(world.blocks):
        colour = BLOCK_COLOURS[k % len(BLOCK_COLOURS)]
        artists[block.name] = _block_artist(ax, block, colour)
        if labels:
            ax.text(
                *(block.centre + np.array([0, 0, block.size[2] / 2 + 0.01])),
                block.name,
                ha="center",
                fontsize=10,
                fontweight="bold",
            )
    for goal in goals:
        corners = np.vstack([goal.footprint(), goal.footprint()[:1]])
        ax.plot(
            corners[:, 0],
            corners[:, 1],
            np.full(5, goal.bottom + 1e-3),
            "--",
            color="tab:red",
            linewidth=1.5,
        )
    _legend_patch(ax, OBSTACLE_COLOUR, "table and obstacles", alpha=0.4)
    return artists


def world_figure(
    world,
    q: ArrayLike | None = None,
    *,
    goals: Sequence = (),
    title: str | None = None,
    figsize: tuple[float, float] = (12.0, 6.0),
) -> Figure:
    """A tabletop world in 3D (with the arm at ``q``) and from above (with the robot's base,
    the blocks named, and goal footprints dashed in red).

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import urkin
    >>> from urkin import planning
    >>> from urkin.transforms import make_transform
    >>> ur3 = urkin.robot("ur3").with_tool(make_transform(p=[0, 0, 0.1]))  # a suction rod
    >>> model = planning.sphere_model(ur3).with_tool_spheres([[0, 0, -0.05]], 0.02)
    >>> table = planning.Block.standing("table", [1.2, 1.2, 0.03], 0, 0, bottom=-0.03)
    >>> cube = planning.Block.standing("A", [0.05] * 3, 0.3, 0.1)
    >>> world = planning.World(ur3, model, table, [cube])
    >>> len(world_figure(world, [0, -1.8, 1.6, -1.37, -1.5708, 0]).axes)
    2
    """
    fig = _figure(figsize)
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    robot = world.robot
    points = [b.centre for b in world.boxes() if b is not world.table]
    if q is not None:
        points += list(fk_frames(robot, q)[..., :3, 3].reshape(-1, 3))
    points.append(robot.base[:3, 3])
    c, half = _cube_with_obstacles(np.array(points), world.scene(), margin=0.1)
    axes3d(ax, center=c, half_width=half, title="3D view")
    ax.computed_zorder = False
    draw_world(ax, world, goals=goals)
    if q is not None:
        draw_robot(ax, robot, q, frames=False, linewidth=5.0)
    top = fig.add_subplot(1, 2, 2)
    t = world.table
    outline = np.vstack([t.footprint(), t.footprint()[:1]])
    top.fill(outline[:, 0], outline[:, 1], color=OBSTACLE_COLOUR, alpha=0.12, label="table")
    for obstacle in world.obstacles:
        corners = obstacle.footprint()
        top.fill(corners[:, 0], corners[:, 1], color=OBSTACLE_COLOUR, alpha=0.6)
        top.annotate(obstacle.name, obstacle.centre[:2], ha="center", va="center", fontsize=9)
    for block in sorted(world.blocks, key=lambda b: b.bottom):
        colour = BLOCK_COLOURS[world.names.index(block.name) % len(BLOCK_COLOURS)]
        corners = block.footprint()
        top.fill(corners[:, 0], corners[:, 1], color=colour, alpha=0.85, edgecolor="0.2")
        top.annotate(
            block.name,
            block.centre[:2],
            ha="center",
            va="center",
            color="white",
            fontsize=9,
            fontweight="bold",
        )
    for goal in goals:
        corners = np.vstack([goal.footprint(), goal.footprint()[:1]])
        top.plot(corners[:, 0], corners[:, 1], "--", color="tab:red", linewidth=1.5)
    base = robot.base[:3, 3]
    top.plot(*base[:2], "k^", markersize=10, label="robot base")
    if q is not None:
        tip = (fk_frames(robot, q)[-1] @ robot.tool)[:3, 3]
        top.plot(*tip[:2], "o", color="tab:orange", label="gripper tip")
    if goals:
        top.plot([], [], "--", color="tab:red", label="goal")
    top.set_aspect("equal")
    top.set_xlabel("x (m)")
    top.set_ylabel("y (m)")
    top.set_title("from above (table frame)")
    top.legend(loc="upper left", fontsize=8, framealpha=0.85)
    top.grid(alpha=0.3)
    if title:
        fig.suptitle(title)
    return fig


def goal_map_figure(
    world,
    block: str,
    *,
    step: float = 0.02,
    q: ArrayLike | None = None,
    figsize: tuple[float, float] = (8.0, 7.0),
) -> Figure:
    """Which goals ``(x, y)`` for ``block`` :func:`urkin.planning.validate_goal` accepts, on a
    grid over the table: each cell coloured by the first reason it gives.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import urkin
    >>> from urkin import planning
    >>> from urkin.transforms import make_transform
    >>> ur3 = urkin.robot("ur3").with_tool(make_transform(p=[0, 0, 0.1]))  # a suction rod
    >>> model = planning.sphere_model(ur3).with_tool_spheres([[0, 0, -0.05]], 0.02)
    >>> table = planning.Block.standing("table", [1.2, 1.2, 0.03], 0, 0, bottom=-0.03)
    >>> cube = planning.Block.standing("A", [0.05] * 3, 0.3, 0.1)
    >>> world = planning.World(ur3, model, table, [cube])
    >>> fig = goal_map_figure(world, "A", step=0.2)
    >>> fig.axes[0].get_title()
    'Goals for block A'
    """
    from urkin.planning import validate_goal

    kinds = (
        "ok",
        "outside the table",
        "unreachable",
        "no support",
        "overlaps",
        "arm in collision",
        "other",
    )
    colours = ("tab:green", "0.85", "tab:gray", "tab:olive", "tab:red", "tab:purple", "k")
    t = world.table
    low = t.footprint().min(axis=0)
    high = t.footprint().max(axis=0)
    xs = np.arange(low[0] + step / 2, high[0], step)
    ys = np.arange(low[1] + step / 2, high[1], step)
    grid = np.zeros((len(ys), len(xs)), dtype=int)
    for i, y in enumerate(ys):
        for j, x in enumerate(xs):
            check = validate_goal(world, (block, float(x), float(y)), q_start=q)
            first = "ok" if check.ok else check.reasons[0]
            grid[i, j] = next(
                (k for k, name in enumerate(kinds) if first.startswith(name)), len(kinds) - 1
            )
    fig = _figure(figsize)
    ax = fig.add_subplot(1, 1, 1)
    ax.imshow(
        grid,
        origin="lower",
        extent=(xs[0] - step / 2, xs[-1] + step / 2, ys[0] - step / 2, ys[-1] + step / 2),
        cmap=ListedColormap(colours),
        vmin=-0.5,
        vmax=len(kinds) - 0.5,
        interpolation="nearest",
        alpha=0.8,
    )
    for k, b in enumerate(world.blocks):
        corners = np.vstack([b.footprint(), b.footprint()[:1]])
        ax.plot(
            corners[:, 0], corners[:, 1], color=BLOCK_COLOURS[k % len(BLOCK_COLOURS)], linewidth=2
        )
        ax.annotate(b.name, b.centre[:2], ha="center", va="center", fontweight="bold")
    for obstacle in world.obstacles:
        corners = np.vstack([obstacle.footprint(), obstacle.footprint()[:1]])
        ax.plot(corners[:, 0], corners[:, 1], color=OBSTACLE_COLOUR, linewidth=2)
    ax.plot(*world.robot.base[:2, 3], "k^", markersize=10)
    shown = sorted(set(grid.ravel().tolist()))
    ax.legend(
        handles=[Patch(color=colours[k], label=kinds[k]) for k in shown],
        loc="upper left",
        fontsize=8,
        framealpha=0.9,
        title="first reason",
    )
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_aspect("equal")
    ax.set_title(f"Goals for block {block}")
    return fig


def animate_task(
    task,
    *,
    title: str | None = None,
    max_frames: int = 60,
    view: tuple[float, float] = (28.0, -50.0),
    **options,
) -> Animation:
    """Animate a :class:`urkin.planning.Task`: the arm, the table and obstacles, and the
    blocks moving with the gripper while carried.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from urkin import planning
    >>> import urkin
    >>> from urkin.transforms import make_transform
    >>> ur3 = urkin.robot("ur3").with_tool(make_transform(p=[0, 0, 0.1]))  # a suction rod
    >>> model = planning.sphere_model(ur3).with_tool_spheres([[0, 0, -0.05]], 0.02)
    >>> table = planning.Block.standing("table", [1.2, 1.2, 0.03], 0, 0, bottom=-0.03)
    >>> cube = planning.Block.standing("A", [0.05] * 3, 0.3, 0.1)
    >>> world = planning.World(ur3, model, table, [cube])
    >>> q_start = [0, -1.8, 1.6, -1.37, -1.5708, 0]
    >>> task = planning.pick_and_place(world, [("A", 0.25, -0.15)], q_start)
    >>> animate_task(task, max_frames=4)  # doctest: +ELLIPSIS
    <Animation: UR3, 4 frames of ... samples>
    """
    world = task.start
    robot = world.robot
    joints = fk_frames(robot, task.q)[..., :3, 3].reshape(-1, 3)
    centres = task.block_poses[..., :3, 3].reshape(-1, 3)
    c, half = _cube_with_obstacles(np.vstack([joints, centres]), world.scene(), margin=0.05)
    artists: dict = {}

    def scenery(ax) -> None:
        ax.view_init(*view)
        ax.computed_zorder = False
        artists.update(draw_world(ax, world, goals=task.goals, labels=False))

    def update(k: int) -> None:
        for i, block in enumerate(world.blocks):
            pose = task.block_poses[k, i]
            artists[block.name].set_verts(_box_faces(pose[:3, 3], block.size, pose[:3, :3]))

    return animate(
        robot,
        task.q,
        title=title,
        max_frames=max_frames,
        center=c,
        half_width=half,
        scenery=scenery,
        update=update,
        info=False,
        **options,
    )


def grasp_yaws_figure(
    blocks: Sequence,
    yaw_now: float,
    *,
    title: str | None = None,
    size: float = 4.2,
) -> Figure:
    """Blocks from above with the tool yaws that grasp them: one panel per block.

    Each panel draws the block's footprint, an arrow for every tool x axis that grasps it
    from above (the block's yaw plus each multiple of its symmetry,
    :func:`urkin.planning.blocks.grasp_yaws`), the one nearest ``yaw_now`` in orange with the
    turn from the wrist's current yaw (dashed) marked by an arc.

    Parameters
    ----------
    blocks : sequence of urkin.planning.Block
    yaw_now : float
        The tool's current yaw about the vertical (rad).
    title : str, optional
    size : float
        Width and height of each panel, inches.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from urkin import planning
    >>> cube = planning.Block.standing("A", [0.05, 0.05, 0.05], 0.0, 0.0, yaw=0.3)
    >>> fig = grasp_yaws_figure([cube], yaw_now=2.0)
    >>> fig.axes[0].get_title()
    'A: 4 grasp yaws, 90° apart'
    >>> plt.close(fig)
    """
    from urkin.planning.blocks import grasp_yaws, symmetry

    blocks = list(blocks)
    if not blocks:
        raise ValueError("blocks must hold at least one planning.Block")
    fig, axes = plt.subplots(
        1, len(blocks), figsize=(size * len(blocks), size + 0.8), layout="constrained"
    )
    axes = np.atleast_1d(axes)
    for k, (ax, block) in enumerate(zip(axes, blocks)):
        centre = block.centre[:2]
        reach = 0.75 * float(np.hypot(*block.size[:2]))
        corners = np.vstack([block.footprint(), block.footprint()[:1]])
        ax.fill(
            corners[:, 0],
            corners[:, 1],
            color=BLOCK_COLOURS[k % len(BLOCK_COLOURS)],
            alpha=0.35,
            edgecolor="0.2",
        )
        yaws = grasp_yaws(block, yaw_now)
        for j, yaw in enumerate(yaws):
            chosen = j == 0
            tip = centre + reach * np.array([math.cos(yaw), math.sin(yaw)])
            ax.annotate(
                "",
                xy=tip,
                xytext=centre,
                arrowprops={
                    "arrowstyle": "-|>",
                    "color": "tab:orange" if chosen else "0.45",
                    "linewidth": 2.5 if chosen else 1.2,
                },
            )
        now = centre + 1.1 * reach * np.array([math.cos(yaw_now), math.sin(yaw_now)])
        ax.plot(*np.column_stack([centre, now]), "--", color="k", linewidth=1.2)
        turn = math.remainder(float(yaws[0]) - yaw_now, 2 * math.pi)
        start, end = sorted((math.degrees(yaw_now), math.degrees(yaw_now + turn)))
        ax.add_patch(
            Arc(centre, 1.3 * reach, 1.3 * reach, theta1=start, theta2=end, color="tab:orange")
        )
        step = math.degrees(symmetry(block.size))
        ax.set_title(f"{block.name}: {len(yaws)} grasp yaws, {step:.0f}° apart")
        ax.text(
            0.02,
            0.02,
            f"wrist turns {abs(math.degrees(turn)):.0f}°",
            transform=ax.transAxes,
            fontsize=9,
        )
        ax.set_xlim(centre[0] - 1.25 * reach, centre[0] + 1.25 * reach)
        ax.set_ylim(centre[1] - 1.25 * reach, centre[1] + 1.25 * reach)
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.grid(alpha=0.3)
    handles = [
        Line2D([], [], color="tab:orange", linewidth=2.5, label="the grasp nearest the wrist"),
        Line2D([], [], color="0.45", linewidth=1.2, label="other grasp yaws (tool x axis)"),
        Line2D([], [], color="k", linestyle="--", linewidth=1.2, label="the wrist's yaw now"),
    ]
    fig.legend(handles=handles, loc="outside lower center", ncol=3, fontsize=9)
    if title:
        fig.suptitle(title)
    return fig
