"""urkin.trajectory.track: warm-started, nearest-solution tracking that never moves on failure
and never winds a joint past its limits.  Every reached sample is re-measured with urkin.fk
here; branches are read off urkin.ik_analytic's row order (its documented branch bits)."""

import re

import numpy as np
import pytest

import urkin
from urkin import trajectory as tj
from urkin.tracking import _chase
from urkin.tracking_report import tracking_report
from urkin.transforms import pose_error, rot_z, wrap_angles

UR3, UR5 = urkin.robot("ur3"), urkin.robot("ur5")


def _branches(robot, q, poses):
    """The ik_analytic row (branch) each configuration is, by matching wrapped angles."""
    rows, mask = urkin.ik_analytic(robot, poses, return_mask=True)
    gap = np.abs(wrap_angles(rows - wrap_angles(q)[:, None, :])).max(axis=2)
    gap[~mask] = np.inf
    assert np.all(gap.min(axis=1) < 1e-6)
    return np.argmin(gap, axis=1)


def _elbow_up_start(robot, pose):
    solutions = urkin.ik_analytic(robot, pose)
    elbows = urkin.fk_frames(robot, solutions)[:, 3, 2, 3]  # height of the elbow (frame 3)
    return solutions[int(np.argmax(elbows))]


@pytest.mark.parametrize(
    ("robot", "path"),
    [
        (UR3, tj.circle((0.25, 0.1, 0.3), 0.1, plane="yz")),  # seed 000's circle
        (UR3, tj.square((0.25, 0.1, 0.3), 0.15, plane="yz")),  # seed 000's square
        (UR5, tj.square((0.4, 0.1, 0.2), 0.2, plane="xy")),
        (UR5, tj.circle((-0.3, 0.35, 0.45), 0.12, normal=(1, 1, 1))),
    ],
)
def test_paths_are_tracked_exactly_on_one_branch_within_limits(robot, path):
    poses = tj.pose_path(path, rot_z(0.4) if robot is UR5 else None)
    q0 = _elbow_up_start(robot, poses[0])
    result = tj.track(robot, poses, q0)
    assert result.ok.all(), result.failures
    position, angle = pose_error(urkin.fk(robot, result.q), poses)
    assert position.max() < 1e-9 and angle.max() < 1e-9
    assert len(set(_branches(robot, result.q, poses))) == 1  # no branch flip
    assert np.abs(result.q).max() <= 2 * np.pi
    assert np.abs(np.diff(result.q, axis=0)).max() < 0.05  # 1 mm steps: small joint steps
    np.testing.assert_allclose(result.q[0], q0, atol=1e-9)


@pytest.mark.parametrize("method", ["lm", "dls", "nr"])
def test_numerical_methods_track_warm_started(method):
    path = tj.circle((0.25, 0.1, 0.3), 0.1, plane="yz")
    poses = tj.pose_path(path)[::7]
    q0 = _elbow_up_start(UR3, poses[0])
    result = tj.track(UR3, poses, q0, method=method)
    assert result.ok.all(), result.failures
    assert result.method == method
    position, angle = pose_error(urkin.fk(UR3, result.q), poses)
    assert position.max() < 1e-9 and angle.max() < 1e-9


@pytest.mark.parametrize("robot", [UR3, UR5, urkin.robot("ur5e")])
def test_a_path_through_the_wrist_singularity_keeps_its_branch(robot):
    """θ5 passes through 0 (one sample exactly on it), then the tool turns about its axis with
    θ5 = 0 (a run of singular samples): ik_analytic's representatives there would swing
    joints 4 and 6 by radians and back; the track continues smoothly, through every sample."""
    through = np.tile([0.4, -1.3, 1.2, -0.6, 0.0, 0.2], (61, 1))
    through[:, 4] = np.linspace(0.3, -0.3, 61)
    through[30, 4] = 0.0
    turning = np.tile([0.4, -1.3, 1.2, -0.6, 0.0, 0.2], (41, 1))
    turning[:, 5] = np.linspace(0.2, 1.0, 41)
    for Q in (through, turning, turning[::-1]):
        poses = urkin.fk(robot, Q)
        result = tj.track(robot, poses, Q[0])
        assert result.ok.all(), result.failures
        np.testing.assert_allclose(result.q, Q, atol=1e-9)
        assert len(result.report.jumps) == 0
        started_off = tj.track(robot, poses, Q[0] + 0.05)  # q0 a little off the path
        assert started_off.ok.all()
        assert np.abs(np.diff(started_off.q, axis=0)).max() < 0.05


@pytest.mark.parametrize("method", ["lm", "nr", "dls", "poe"])
def test_numerical_tracks_continue_across_pi_without_a_turn(method):
    """ik wraps its solutions into (−π, π]; a track continues each joint by the equivalent
    nearest the previous sample (joint 1 here goes from 3.0 to 3.3 rad)."""
    Q = np.tile([3.0, -1.2, 1.4, -0.6, 1.1, 0.2], (31, 1))
    Q[:, 0] = np.linspace(3.0, 3.3, 31)
    result = tj.track(UR5, urkin.fk(UR5, Q), Q[0], method=method)
    assert result.ok.all(), result.failures
    np.testing.assert_allclose(result.q, Q, atol=1e-8)
    assert len(result.report.jumps) == 0
    # past +2π the joint would wind beyond its limit: the track stops there and says so
    Q = np.tile([6.0, -1.2, 1.4, -0.6, 1.1, 0.2], (31, 1))
    Q[:, 0] = np.linspace(6.0, 6.6, 31)
    result = tj.track(UR5, urkin.fk(UR5, Q), Q[0], method=method)
    assert result.ok[: int(np.argmax(Q[:, 0] > 2 * np.pi))].all()
    assert not result.ok[Q[:, 0] > 2 * np.pi + 0.02].any()
    assert np.abs(result.q).max() <= 2 * np.pi
    assert all("joint 1 would turn past its limit" in why for why in result.failures.values())


def test_a_sample_out_of_reach_leaves_the_arm_where_it_was_and_says_why():
    points = tj.line((0.3, 0.1, 0.3), (0.9, 0.1, 0.3)).points(0.01)  # UR3 reaches ~0.5 m
    there = np.r_[points, points[::-1]]  # out and back
    poses = tj.pose_path(there)
    q0 = _elbow_up_start(UR3, poses[0])
    result = tj.track(UR3, poses, q0)
    failed = np.flatnonzero(~result.ok)
    assert len(failed) > 0 and result.ok[0] and result.ok[-1]
    assert set(result.failures) == set(failed.tolist())
    assert all("unreachable" in result.failures[k] for k in failed)
    for k in failed:  # never moved on a failed sample
        np.testing.assert_array_equal(result.q[k], result.q[k - 1])
    position, angle = pose_error(urkin.fk(UR3, result.q[result.ok]), poses[result.ok])
    assert position.max() < 1e-9 and angle.max() < 1e-9


def test_a_path_that_would_wind_a_joint_past_its_limit_stops_there():
    # the tool turns about its own axis by three full turns while standing still
    T0 = urkin.fk(UR5, np.array([0.3, -1.2, 1.4, -0.6, 1.1, 0.5]))
    turns = np.linspace(0, 6 * np.pi, 361)
    poses = T0 @ np.stack([np.eye(4)] * len(turns))
    poses[:, :3, :3] = T0[:3, :3] @ rot_z(turns)
    q0 = np.array([0.3, -1.2, 1.4, -0.6, 1.1, 0.5])
    result = tj.track(UR5, poses, q0)
    assert np.abs(result.q).max() <= 2 * np.pi + 1e-12
    failed = np.flatnonzero(~result.ok)
    assert len(failed) > 0 and np.all(np.diff(failed) == 1) and failed[-1] == len(poses) - 1
    assert "joint 6 would turn past its limit" in result.failures[int(failed[0])]
    reached = result.ok
    position, angle = pose_error(urkin.fk(UR5, result.q[reached]), poses[reached])
    assert position.max() < 1e-9 and angle.max() < 1e-9
    # joint 6 went as far as it could: to within one sample's turn (6π/360) of +2π
    assert 2 * np.pi - 6 * np.pi / 360 < result.q[reached][-1, 5] <= 2 * np.pi


def test_chase_follows_the_chain_like_a_loop():
    rng = np.random.default_rng(3)
    for length in (1, 2, 3, 7, 64, 1000):
        table = rng.integers(0, 8, (length, 8))
        first = int(rng.integers(8))
        expected = [first]
        for k in range(length):
            expected.append(int(table[k, expected[-1]]))
        np.testing.assert_array_equal(_chase(table, first), expected)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: tj.track(UR3, np.eye(4), np.zeros(6)), r"shape \(M, 4, 4\)"),
        (lambda: tj.track(UR3, np.eye(4)[None], np.zeros(5)), r"q0 must be one configuration"),
        (lambda: tj.track(UR3, np.eye(4)[None], np.full(6, 7.0)), "outside the robot's joint"),
        (lambda: tj.track(UR3, np.eye(4)[None], np.zeros(6), method="rrt"), "method must be"),
        (lambda: tj.track(UR3, 2 * np.eye(4)[None], np.zeros(6)), "poses"),
        (lambda: tj.track("ur3", np.eye(4)[None], np.zeros(6)), "robot"),
    ],
)
def test_bad_input_is_refused_with_the_argument_named(call, message):
    with pytest.raises((ValueError, TypeError), match=message):
        call()


# ------------------------------------------------------------------------- the tracking report


def _seed_square_poses():
    """Seed 000's square as the seed samples it: 20 points per side, corners repeated."""
    c, h = np.array([0.25, 0.1, 0.3]), 0.075
    corners = c + np.array([[0, -h, -h], [0, h, -h], [0, h, h], [0, -h, h], [0, -h, -h]])
    points = np.concatenate([np.linspace(corners[k], corners[k + 1], 20) for k in range(4)])
    return tj.pose_path(points)  # each side's end is the next side's start


def test_the_report_counts_the_seed_sampling_errors():
    poses = _seed_square_poses()
    q0 = _elbow_up_start(UR3, poses[0])
    report = tracking_report(UR3, poses, tj.track(UR3, poses, q0).q)
    assert len(report.repeated) == 3  # three inner corners sampled twice
    assert report.spacing[0] == 0.0
    assert report.spacing[2] == pytest.approx(0.15 / 19, rel=1e-9)  # 7.9 mm, not 1 mm
    assert report.position_error[0] < 1e-9
    # between two samples 7.9 mm apart the arm strays further from the straight segment
    exact_poses = tj.pose_path(tj.square((0.25, 0.1, 0.3), 0.15, plane="yz"))
    exact = tj.track(UR3, exact_poses, q0).report
    assert exact.midpoint_deviation < report.midpoint_deviation
    assert len(exact.repeated) == 0 and exact.spacing[2] <= 1e-3


def test_the_report_sees_misses_jumps_winding_flips_and_the_plane():
    rng = np.random.default_rng(5)
    turns = np.linspace(0, 1, 50)[:, None] * np.array([0, 0, 0, 0, 0, 8 * np.pi])
    q = np.array([0.3, -1.2, 1.4, -0.6, 1.1, 0.5]) + turns  # joint 6 winds four turns
    q[30:, 2] = -q[30:, 2]  # the elbow flips between samples 29 and 30 (a jump too)
    poses = urkin.fk(UR5, wrap_angles(q))
    shifted = q.copy()
    shifted[10] += rng.normal(0, 1e-3, 6)  # one sample misses its pose
    report = tracking_report(UR5, poses, shifted, jump=0.5)
    assert report.position_error[0] > 1e-5
    assert 29 in report.jumps
    assert report.branch_flips["elbow"].tolist() == [29]
    assert report.winding["turns"][5] == pytest.approx(4.0, abs=1e-9)
    assert report.winding["beyond_limits"].tolist() == [6]
    # a configuration with a joint origin below the mounting plane
    low = np.array([0.0, 0.6, -1.5, 0.0, 1.0, 0.0])
    heights = urkin.fk_frames(UR5, low)[1:, 2, 3]
    pair = np.stack([low, low])
    below = tracking_report(UR5, urkin.fk(UR5, pair), pair)
    assert below.below_base[0] == pytest.approx(heights.min(), abs=1e-15)
    assert below.below_base[0] < 0 and below.below_base[2] == int(np.argmin(heights)) + 1


def test_the_report_measures_speeds_against_limits():
    t = np.linspace(0, 2.0, 201)
    q = np.zeros((201, 6)) + np.array([0.3, -1.2, 1.4, -0.6, 1.1, 0.5])
    q[:, 1] += 0.5 * t  # joint 2 turns at 0.5 rad/s
    q[:, 3] += 0.25 * t**2  # joint 4 accelerates at 0.5 rad/s²
    limits = [1, 1, 1, 0.25, 1, 1]
    report = tracking_report(
        UR5, urkin.fk(UR5, q), q, duration=2.0, max_velocity=1.0, max_acceleration=limits
    )
    assert report.limits["peak_velocity"][1] == pytest.approx(0.5, rel=1e-9)
    assert report.limits["peak_acceleration"][3] == pytest.approx(0.5, rel=1e-6)
    assert report.limits["bottleneck"] == 4
    assert report.limits["worst_ratio"] == pytest.approx(2.0, rel=1e-6)
    assert "bottleneck" in str(report)


def test_track_carries_its_report_and_failures():
    poses = tj.pose_path(tj.line((0.3, 0.1, 0.3), (0.9, 0.1, 0.3)).points(0.01))
    result = tj.track(UR3, poses, _elbow_up_start(UR3, poses[0]))
    assert result.failures and result.report.failures == result.failures
    assert "failed samples" in str(result.report)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: tracking_report(UR3, np.eye(4)[None], np.zeros((1, 6))), "M ≥ 2"),
        (lambda: tracking_report(UR3, np.stack([np.eye(4)] * 2), np.zeros((3, 6))), "one conf"),
        (
            lambda: tracking_report(UR3, np.stack([np.eye(4)] * 2), np.zeros((2, 6)), duration=0),
            "duration",
        ),
    ],
)
def test_bad_report_input_is_refused(call, message):
    with pytest.raises(ValueError, match=message):
        call()


# ------------------------------------------------------------------ the report's per-sample numbers


def _angle_between(A, B):
    """Rotation angle of A^T B from its sine (the skew part) and cosine (the trace)."""
    R = np.swapaxes(A, -1, -2) @ B
    skew = R - np.swapaxes(R, -1, -2)
    sine = np.linalg.norm(np.stack([skew[:, 2, 1], skew[:, 0, 2], skew[:, 1, 0]], axis=1), axis=1)
    cosine = (np.trace(R, axis1=1, axis2=2) - 1) / 2
    return np.arctan2(sine / 2, cosine)


def test_the_report_keeps_per_sample_numbers_that_agree_with_fk():
    poses = _seed_square_poses()
    q = tj.track(UR3, poses, _elbow_up_start(UR3, poses[0])).q
    q[5] += np.array([1e-4, -2e-4, 0, 3e-4, 0, 1e-4])  # one sample off its pose
    q[7, 5] += 2 * np.pi  # a turn of joint 6 is the same arm pose
    report = tracking_report(UR3, poses, q)
    reached = urkin.fk(UR3, q)
    position = np.linalg.norm(reached[:, :3, 3] - poses[:, :3, 3], axis=1)
    np.testing.assert_allclose(report.position_errors, position, rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(
        report.orientation_errors, _angle_between(reached[:, :3, :3], poses[:, :3, :3]), atol=1e-14
    )
    assert report.position_errors[5] > 1e-5 and np.delete(report.position_errors, 5).max() < 1e-12
    spacings = [np.linalg.norm(poses[k + 1, :3, 3] - poses[k, :3, 3]) for k in range(len(q) - 1)]
    np.testing.assert_allclose(report.spacings, spacings, rtol=1e-15, atol=0)
    np.testing.assert_array_equal(report.q, q)  # as given, not wrapped
    assert report.q is not q
    q2, q3, q4, q5 = q[:, 1], q[:, 2], q[:, 3], q[:, 4]
    shoulder = UR3.a2 * np.cos(q2) + UR3.a3 * np.cos(q2 + q3) + UR3.d5 * np.sin(q2 + q3 + q4)
    np.testing.assert_allclose(
        report.factors, np.stack([shoulder, np.sin(q3), np.sin(q5)], axis=1), atol=1e-14
    )
    np.testing.assert_array_equal(report.joint_limits, np.array(UR3.joint_limits))
    # the summaries are summaries of these arrays
    assert report.position_error[0] == report.position_errors.max()
    assert report.orientation_error[0] == report.orientation_errors.max()
    assert report.spacing == (
        report.spacings.min(),
        np.median(report.spacings),
        report.spacings.max(),
    )
    np.testing.assert_array_equal(report.branches, np.sign(report.factors))


def _texts(ax):
    return [ax.get_title(), ax.get_xlabel(), ax.get_ylabel()]


def _labelled(ax, start):
    """The artists of ax whose legend label starts with start."""
    artists = ax.get_lines() + ax.patches
    return [a for a in artists if str(a.get_label()).startswith(start)]


TITLES = [
    "Target spacing",
    "Pose error at each sample",
    "Joint angles",
    "Distance from the singularities",
]


def test_the_report_figure_has_four_labelled_panels_and_the_seed_square_repeats_corners():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    poses = _seed_square_poses()
    report = tj.track(UR3, poses, _elbow_up_start(UR3, poses[0])).report
    fig = report.plot(title="seed 000's square")
    try:
        assert len(fig.axes) == 4
        assert [ax.get_title() for ax in fig.axes] == TITLES
        assert fig.get_suptitle() == "seed 000's square"
        units = ["(mm)", "rad", "°", "(m"]
        for ax, unit in zip(fig.axes, units):
            assert unit in ax.get_ylabel(), ax.get_ylabel()
            assert ax.get_legend() is not None
        assert [ax.get_xlabel() for ax in fig.axes[2:]] == ["sample", "sample"]
        assert fig.axes[1].get_yscale() == fig.axes[3].get_yscale() == "log"
        # panel 1: the seed repeats the three inner corners, at the end of sides 1-3
        spacing_ax = fig.axes[0]
        (marks,) = _labelled(spacing_ax, "repeated sample (3)")
        np.testing.assert_array_equal(marks.get_xdata(), np.array([19, 39, 59]) + 0.5)
        np.testing.assert_array_equal(marks.get_ydata(), 0.0)
        (one_mm,) = _labelled(spacing_ax, "1 mm")
        np.testing.assert_array_equal(one_mm.get_ydata(), [1.0, 1.0])
        (spacing,) = _labelled(spacing_ax, "spacing")
        np.testing.assert_allclose(spacing.get_ydata(), report.spacings * 1e3, rtol=1e-15)
        assert spacing.get_ydata()[19] == 0.0 and spacing.get_ydata()[0] > 7.8  # 7.9 mm steps
        # panel 3: the joint angles in degrees, the ±360° limits
        joints = _labelled(fig.axes[2], "joint ")
        assert len(joints) == 6
        np.testing.assert_allclose(joints[2].get_ydata(), np.degrees(report.q[:, 2]))
        dotted = [line for line in fig.axes[2].get_lines() if line.get_linestyle() == ":"]
        assert sorted(line.get_ydata()[0] for line in dotted) == [-360.0, 360.0]
        assert _labelled(fig.axes[2], "limits ±360°")
        fig.canvas.draw()  # lays out without error; constrained layout
        assert fig.get_layout_engine() is not None
    finally:
        plt.close(fig)


def test_the_report_figure_marks_flips_failures_and_exact_zeros():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    turns = np.linspace(0, 1, 50)[:, None] * np.array([0, 0, 0, 0, 0, 8 * np.pi])
    q = np.array([0.3, -1.2, 1.4, -0.6, 0.0, 0.5]) + turns  # q5 = 0: the wrist is singular
    q[30:, 2] = -q[30:, 2]  # the elbow flips between samples 29 and 30
    poses = urkin.fk(UR5, wrap_angles(q))
    failures = {10: "x", 40: "y", 41: "y", 42: "y"}
    report = tracking_report(UR5, poses, q, failures=failures)
    fig = report.plot()
    try:
        error_ax, joint_ax, margin_ax = fig.axes[1:]
        (flip,) = _labelled(joint_ax, "elbow flip (1)")
        np.testing.assert_array_equal(flip.get_xdata(), [29.5, 29.5])
        assert max(line.get_ydata().max() for line in _labelled(joint_ax, "joint 6")) > 1440
        # failures: two bands (sample 10; samples 40-42), in the error and the margin panels
        for ax in (error_ax, margin_ax):
            bands = [p for p in ax.patches if p.get_facecolor()[0] > 0.8]
            assert len(bands) == 2
            assert _labelled(ax, "failed samples (4)")
            spans = sorted(
                (round(p.get_x() + 0.0, 6), round(p.get_x() + p.get_width(), 6)) for p in bands
            )
            assert spans == [(9.5, 10.5), (39.5, 42.5)]
        # |sin q5| is exactly 0 and drawn at the floor; the label says where
        (wrist,) = _labelled(margin_ax, "wrist |sin q5|")
        assert np.all(wrist.get_ydata() == 1e-17)
        assert "0 drawn at 1e-17" in margin_ax.get_ylabel()
        assert margin_ax.get_ylim()[0] < 1e-17
    finally:
        plt.close(fig)


def test_a_report_without_per_sample_arrays_cannot_be_drawn_and_import_stays_light():
    import dataclasses
    import subprocess
    import sys

    poses = _seed_square_poses()
    report = tracking_report(UR3, poses, tj.track(UR3, poses, _elbow_up_start(UR3, poses[0])).q)
    bare = dataclasses.replace(report, q=np.zeros((0, 6)), position_errors=np.zeros(0))
    with pytest.raises(ValueError, match="per-sample arrays"):
        bare.plot()
    code = (
        "import sys, urkin; from urkin import trajectory as tj; "
        "r = tj.track(urkin.robot('ur3'), tj.pose_path(tj.line((0.3, 0.1, 0.3), "
        "(0.3, 0.1, 0.31))), [0.0, -1.2, 1.4, -0.6, 1.1, 0.5]); "
        "print('matplotlib' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_the_printed_table_states_round_off_as_a_bound():
    # poses of the configurations themselves: the errors are round-off, whose digits vary by CPU
    q = np.array([0.3, -1.2, 1.4, -0.6, 1.1, 0.5]) + np.linspace(0, 0.5, 50)[:, None]
    text = str(tracking_report(UR5, urkin.fk(UR5, q), q))
    assert "position error max / rms           below 1e-12 / below 1e-12 m" in text
    assert re.search(r"\de-1[3-9]", text) is None
    # a real error keeps its digits
    poses = urkin.fk(UR5, q)
    poses[:, 0, 3] += 2.5e-4
    assert "2.50e-04 / 2.50e-04 m" in str(tracking_report(UR5, poses, q))
