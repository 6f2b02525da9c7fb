"""What a joint path does to the arm while it follows a path of poses: a tracking report.

:func:`tracking_report` measures a joint path ``q`` (M, 6) against the poses ``(M, 4, 4)`` it
was meant to reach, with numbers for every way a path follower can go wrong: samples spaced
further apart than claimed, or repeated; poses missed; what the arm does *between* samples;
joints that jump, wind up past their limits, or change branch; singularities approached;
links below the mounting plane; speeds and accelerations over the limits at a given duration;
and the samples that failed.  Everything is batched over the samples.  The report keeps the
per-sample numbers too, and :meth:`TrackingReport.plot` draws them in four panels.

Branches are the signs of the three singular factors of :func:`urkin.kinematics.
singularity_factors` — shoulder ``a2 c2 + a3 c23 + d5 s234``, elbow ``sin q3``, wrist
``sin q5``: a branch can only change where its factor passes through zero, at a singularity,
which is where closed-form solutions meet.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from urkin._inputs import real
from urkin.kinematics import fk, fk_frames, singularity_factors
from urkin.robots import Robot, check_robot
from urkin.transforms import check_transform, pose_error, wrap_angles

if TYPE_CHECKING:  # matplotlib is imported only when a report is drawn
    from matplotlib.figure import Figure

__all__ = ["TrackingReport", "tracking_report"]

_FAMILIES = ("shoulder", "elbow", "wrist")
_SAME = 1e-12  # m, and per rotation entry: closer consecutive targets are the same sample
_TIE = 1e-9  # minima closer than this are equal; the report names the first


@dataclass(frozen=True)
class TrackingReport:
    """Numbers that say how well a joint path follows a path of poses (see the module).

    The summaries come with the per-sample arrays they summarise (empty in a report built by
    hand without them); :meth:`plot` draws those.

    Attributes
    ----------
    samples : int
        Number of samples M.
    spacing : tuple of float
        (min, median, max) distance between consecutive target positions (m); a repeated
        sample shows as a minimum of 0.
    repeated : ndarray of int
        Indices k where target k + 1 is target k again (same position and orientation to
        1e-12, so that round-off in how the samples were computed does not hide a repeat).
    position_error, orientation_error : tuple of float
        (max, rms) of the distance (m) and rotation angle (rad) from ``fk(q[k])`` to pose k.
    midpoint_deviation : float
        Largest distance (m) from the flange at the joint midpoint ``(q[k] + q[k+1]) / 2`` to
        the straight segment between targets k and k + 1: what the arm does between samples.
    joint_step : ndarray, shape (6,)
        Largest ``|q[k+1] − q[k]|`` of each joint (rad).
    jumps : ndarray of int
        Indices k where some joint changes by more than ``jump`` between samples k and k + 1.
    branches : ndarray, shape (M, 3)
        Sign (+1 or −1; 0 exactly at a singularity) of the shoulder, elbow and wrist factors.
    branch_flips : dict of str to ndarray of int
        For each family, the indices k where its sign differs between samples k and k + 1.
    winding : dict of str to ndarray
        ``"turns"`` net turns of each joint from the first sample to the last, and ``"min"``
        and ``"max"`` of each joint (rad); ``"beyond_limits"`` the joints that leave the
        robot's limits (1-based).
    singularity_margin : dict of str to tuple
        For each family, (smallest absolute factor, sample): metres for the shoulder, the
        absolute sine for the elbow and wrist.
    below_base : tuple
        (lowest height of any DH frame origin 1-6 above the mounting plane z = 0 (m), sample,
        frame); negative means below the plane.
    limits : dict or None
        With a ``duration``: ``"peak_velocity"`` and ``"peak_acceleration"`` (6,) of each joint
        (rad/s, rad/s²) when the samples are passed at equal time steps; with the limits also
        ``"velocity_ratio"`` and ``"acceleration_ratio"`` (peak / limit), the ``"bottleneck"``
        joint (1-based) and the sample where its ratio peaks.
    failures : dict of int to str
        The samples that failed and why (as given).
    position_errors, orientation_errors : ndarray, shape (M,)
        The distance (m) and rotation angle (rad) from ``fk(q[k])`` to pose k, per sample.
    spacings : ndarray, shape (M − 1,)
        The distance between target positions k and k + 1 (m).
    q : ndarray, shape (M, 6)
        The joint path (rad) as given (not wrapped: a joint that winds up shows it).
    factors : ndarray, shape (M, 3)
        The shoulder (m), elbow and wrist factors of
        :func:`urkin.kinematics.singularity_factors` at each sample.
    joint_limits : ndarray, shape (6, 2)
        The robot's joint limits (rad), lower and upper.
    """

    samples: int
    spacing: tuple[float, float, float]
    repeated: np.ndarray
    position_error: tuple[float, float]
    orientation_error: tuple[float, float]
    midpoint_deviation: float
    joint_step: np.ndarray
    jumps: np.ndarray
    branches: np.ndarray
    branch_flips: dict[str, np.ndarray]
    winding: dict[str, np.ndarray]
    singularity_margin: dict[str, tuple[float, int]]
    below_base: tuple[float, int, int]
    limits: dict[str, np.ndarray | int] | None = None
    failures: dict[int, str] = field(default_factory=dict)
    position_errors: np.ndarray = field(default_factory=lambda: np.zeros(0))
    orientation_errors: np.ndarray = field(default_factory=lambda: np.zeros(0))
    spacings: np.ndarray = field(default_factory=lambda: np.zeros(0))
    q: np.ndarray = field(default_factory=lambda: np.zeros((0, 6)))
    factors: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))
    joint_limits: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))

    def rows(self) -> list[tuple[str, str]]:
        """The report as (quantity, value) text rows."""
        lo, mid, hi = self.spacing
        flips = ", ".join(f"{k} {len(v)}" for k, v in self.branch_flips.items())
        margin = ", ".join(
            f"{k} {v[0]:.3g} (sample {v[1]})" for k, v in self.singularity_margin.items()
        )
        height, where, frame = self.below_base
        rows = [
            ("samples", f"{self.samples}"),
            (
                "target spacing min / median / max",
                f"{lo * 1e3:.3f} / {mid * 1e3:.3f} / {hi * 1e3:.3f} mm",
            ),
            ("repeated samples", f"{len(self.repeated)}"),
            ("position error max / rms", _pair(self.position_error, "m")),
            ("orientation error max / rms", _pair(self.orientation_error, "rad")),
            ("deviation between samples", f"{self.midpoint_deviation * 1e3:.3f} mm"),
            ("largest joint step", " ".join(f"{s:.4f}" for s in self.joint_step) + " rad"),
            ("jumps", f"{len(self.jumps)}"),
            ("branch flips", flips),
            (
                "net turns per joint",
                " ".join(f"{round(t, 2) + 0.0:+.2f}" for t in self.winding["turns"]),
            ),
            ("joints beyond their limits", _joints(self.winding["beyond_limits"])),
            ("closest to a singularity", margin),
            ("lowest joint origin", f"{height * 1e3:.1f} mm (frame {frame}, sample {where})"),
            ("failed samples", f"{len(self.failures)}"),
        ]
        if self.limits is not None:
            rows.append(
                (
                    "peak joint speed",
                    " ".join(f"{v:.3f}" for v in self.limits["peak_velocity"]) + " rad/s",
                )
            )
            rows.append(
                (
                    "peak joint acceleration",
                    " ".join(f"{v:.3f}" for v in self.limits["peak_acceleration"]) + " rad/s²",
                )
            )
            if "bottleneck" in self.limits:
                rows.append(
                    (
                        "bottleneck",
                        f"joint {self.limits['bottleneck']} at sample "
                        f"{self.limits['bottleneck_sample']}, "
                        f"{self.limits['worst_ratio']:.2f} × its limit",
                    )
                )
        return rows

    def __str__(self) -> str:
        rows = self.rows()
        width = max(len(name) for name, _ in rows)
        return "\n".join(f"{name:<{width}}  {value}" for name, value in rows)

    def plot(
        self, *, title: str | None = None, figsize: tuple[float, float] = (11.0, 7.5)
    ) -> Figure:
        """The report's per-sample numbers in four panels.

        The panels show the spacing of the targets (mm) with the 1 mm line and the repeated
        samples; the position (m) and orientation (rad) error at each sample, on a log axis;
        the joint angles (degrees) with the joint limits and the branch flips; and the
        distance from each singular family (shoulder factor in m, ``|sin q3|``,
        ``|sin q5|``), on a log axis, with the failed samples.  Drawn by
        :func:`urkin.plot.tracking_report_figure` (this imports matplotlib; ``import urkin``
        does not).

        Parameters
        ----------
        title : str, optional
            Title of the whole figure.
        figsize : tuple of float
            Figure size (inches).

        Returns
        -------
        matplotlib.figure.Figure

        Raises
        ------
        ValueError
            If the report has no per-sample arrays (built by hand without them).

        Examples
        --------
        >>> import matplotlib
        >>> matplotlib.use("Agg")
        >>> import matplotlib.pyplot as plt
        >>> import urkin
        >>> from urkin import trajectory
        >>> ur3 = urkin.robot("ur3")
        >>> poses = trajectory.pose_path(trajectory.circle((0.25, 0.1, 0.3), 0.1, plane="yz"))
        >>> report = trajectory.track(ur3, poses, urkin.ik_analytic(ur3, poses[0])[2]).report
        >>> fig = report.plot(title="seed 000's circle")
        >>> [ax.get_title() for ax in fig.axes]  # doctest: +NORMALIZE_WHITESPACE
        ['Target spacing', 'Pose error at each sample', 'Joint angles',
         'Distance from the singularities']
        >>> plt.close(fig)
        """
        from urkin.plot import tracking_report_figure

        return tracking_report_figure(self, title=title, figsize=figsize)


def _size(value: float) -> str:
    """A measured error, as a bound once it is round-off (its digits differ between CPUs)."""
    return "below 1e-12" if value < 1e-12 else f"{value:.2e}"


def _pair(values: tuple[float, float], unit: str) -> str:
    return f"{_size(values[0])} / {_size(values[1])} {unit}"


def _joints(joints: np.ndarray) -> str:
    return ", ".join(str(int(j)) for j in joints) if len(joints) else "none"


def _segment_distance(points: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance from each point to the segment from a to b (rows)."""
    ab = b - a
    length2 = np.einsum("ij,ij->i", ab, ab)
    t = np.einsum("ij,ij->i", points - a, ab) / np.where(length2 > 0, length2, 1.0)
    closest = a + np.clip(t, 0.0, 1.0)[:, None] * ab
    return np.linalg.norm(points - closest, axis=1)


def tracking_report(
    robot: Robot,
    poses: ArrayLike,
    q: ArrayLike,
    *,
    failures: dict[int, str] | None = None,
    jump: float = 0.2,
    duration: float | None = None,
    max_velocity: ArrayLike | None = None,
    max_acceleration: ArrayLike | None = None,
) -> TrackingReport:
    """Measure the joint path ``q`` against the poses it should follow.

    Parameters
    ----------
    robot : Robot
    poses : array_like, shape (M, 4, 4)
        The targets, M ≥ 2.
    q : array_like, shape (M, 6)
        The joint path (rad), one configuration per target.
    failures : dict of int to str, optional
        Samples already known to have failed, with reasons (from :func:`urkin.tracking.track`).
    jump : float
        A joint change between neighbouring samples larger than this (rad) is a jump.
    duration : float, optional
        Time (s) to pass all samples at equal time steps; gives joint speeds and accelerations
        (central differences).
    max_velocity, max_acceleration : array_like, optional
        Joint limits (rad/s, rad/s²; one number or one per joint) to compare the peaks with.

    Returns
    -------
    TrackingReport

    Examples
    --------
    >>> import urkin
    >>> from urkin import trajectory
    >>> ur3 = urkin.robot("ur3")
    >>> poses = trajectory.pose_path(trajectory.square((0.25, 0.1, 0.3), 0.15, plane="yz"))
    >>> followed = trajectory.track(ur3, poses, urkin.ik_analytic(ur3, poses[0])[2])
    >>> report = tracking_report(ur3, poses, followed.q)
    >>> report.spacing[2] <= 1e-3, len(report.repeated), report.position_error[0] < 1e-9
    (True, 0, True)
    >>> {family: len(k) for family, k in report.branch_flips.items()}
    {'shoulder': 0, 'elbow': 0, 'wrist': 0}
    """
    robot = check_robot(robot)
    T = check_transform(poses, name="poses")
    Q = real(q, "q")
    if T.ndim != 3 or len(T) < 2:
        raise ValueError(
            f"poses must be a path of poses, shape (M, 4, 4) with M ≥ 2; got {T.shape}"
        )
    if Q.shape != (len(T), 6):
        raise ValueError(
            f"q must have one configuration per pose, shape ({len(T)}, 6); got {Q.shape}"
        )
    jump = float(real(jump, "jump"))
    positions = T[:, :3, 3]
    gaps = np.linalg.norm(np.diff(positions, axis=0), axis=1)
    same_orientation = np.abs(np.diff(T[:, :3, :3], axis=0)).max(axis=(1, 2)) <= _SAME
    repeated = np.flatnonzero((gaps <= _SAME) & same_orientation)

    turned = wrap_angles(Q)  # the same arm poses; a path that winds up may leave fk's range
    position, angle = pose_error(fk(robot, turned), T)
    mid = fk(robot, wrap_angles((Q[1:] + Q[:-1]) / 2))[:, :3, 3]
    deviation = _segment_distance(mid, positions[:-1], positions[1:])

    steps = np.abs(np.diff(Q, axis=0))
    jumps = np.flatnonzero((steps > jump).any(axis=1))

    factors = singularity_factors(robot, turned)
    branches = np.sign(factors)
    flips = {
        name: np.flatnonzero(branches[1:, i] * branches[:-1, i] < 0)
        for i, name in enumerate(_FAMILIES)
    }
    # the first sample within _TIE of the smallest, so that round-off cannot pick among equals
    size = np.abs(factors)
    low = np.argmax(size <= size.min(axis=0) + _TIE, axis=0)
    margin = {
        name: (float(abs(factors[low[i], i])), int(low[i])) for i, name in enumerate(_FAMILIES)
    }

    limits = np.array(robot.joint_limits)
    outside = (Q < limits[:, 0]) | (Q > limits[:, 1])
    winding = {
        "turns": (Q[-1] - Q[0]) / (2 * math.pi),
        "min": Q.min(axis=0),
        "max": Q.max(axis=0),
        "beyond_limits": np.flatnonzero(outside.any(axis=0)) + 1,
    }

    heights = fk_frames(robot, turned)[:, 1:, 2, 3]  # (M, 6): DH frames 1-6
    lowest = int(np.argmax(heights.ravel() <= heights.min() + _TIE))  # first of equals
    sample, frame = np.unravel_index(lowest, heights.shape)
    below = (float(heights[sample, frame]), int(sample), int(frame) + 1)

    timing = None
    if duration is not None:
        dt = float(real(duration, "duration")) / (len(T) - 1)
        if not dt > 0:
            raise ValueError("duration must be > 0 (s)")
        velocity = np.gradient(Q, dt, axis=0)
        acceleration = np.gradient(velocity, dt, axis=0)
        timing = {
            "peak_velocity": np.abs(velocity).max(axis=0),
            "peak_acceleration": np.abs(acceleration).max(axis=0),
        }
        if max_velocity is not None and max_acceleration is not None:
            v_ratio = np.abs(velocity) / np.broadcast_to(real(max_velocity, "max_velocity"), 6)
            a_ratio = np.abs(acceleration) / np.broadcast_to(
                real(max_acceleration, "max_acceleration"), 6
            )
            ratio = np.maximum(v_ratio, a_ratio)
            top = ratio.max()  # the first of the ratios equal to the largest, to round-off
            first = int(np.argmax(ratio.ravel() >= top - _TIE * max(1.0, top)))
            worst_sample, worst_joint = np.unravel_index(first, ratio.shape)
            timing |= {
                "velocity_ratio": v_ratio.max(axis=0),
                "acceleration_ratio": a_ratio.max(axis=0),
                "bottleneck": int(worst_joint) + 1,
                "bottleneck_sample": int(worst_sample),
                "worst_ratio": float(ratio[worst_sample, worst_joint]),
            }

    return TrackingReport(
        samples=len(T),
        spacing=(float(gaps.min()), float(np.median(gaps)), float(gaps.max())),
        repeated=repeated,
        position_error=(float(position.max()), float(np.sqrt(np.mean(position**2)))),
        orientation_error=(float(angle.max()), float(np.sqrt(np.mean(angle**2)))),
        midpoint_deviation=float(deviation.max()),
        joint_step=steps.max(axis=0),
        jumps=jumps,
        branches=branches,
        branch_flips=flips,
        winding=winding,
        singularity_margin=margin,
        below_base=below,
        limits=timing,
        failures=dict(failures or {}),
        position_errors=position,
        orientation_errors=angle,
        spacings=gaps,
        q=Q.copy(),
        factors=factors,
        joint_limits=limits,
    )
