"""urkin.trajectory: paths sampled by arc length, orientation along them, time scaling.

References are independent of the code under test: segment lengths from the vertices, circle
geometry (distance to the centre and the plane), finite differences of s(t), dense sampling of
the profiles against their limits, and seed 000's own corners (../shared/seeds, not copied).
"""

import math

import numpy as np
import pytest

from urkin import trajectory as tj
from urkin.transforms import random_rotations, rot_x, rot_z, rotation_angle

STEPS = (1e-3, 7e-4, 2.5e-3, 0.01)


def _gaps(points, closed):
    ahead = np.roll(points, -1, axis=0) if closed else points[1:]
    return np.linalg.norm(ahead - points[: len(ahead)], axis=1)


def _random_polyline(rng, closed):
    k = int(rng.integers(2 if not closed else 3, 7))
    return rng.uniform(-0.5, 0.5, (k, 3)), closed


@pytest.mark.parametrize("seed", range(30))
def test_polyline_samples_every_spacing_within_step_equal_per_segment_corners_once(seed):
    rng = np.random.default_rng(seed)
    vertices, closed = _random_polyline(rng, closed=bool(seed % 2))
    step = STEPS[seed % len(STEPS)]
    path = tj.polyline(vertices, closed=closed)
    points = path.points(step)
    gaps = _gaps(points, closed)
    assert gaps.max() <= step
    # corners: each vertex appears exactly once among the samples; nothing else repeats
    for v in vertices:
        assert np.sum(np.all(np.abs(points - v) < 1e-12, axis=1)) == 1
    assert len(np.unique(points.round(12), axis=0)) == len(points)
    if not closed:
        np.testing.assert_array_equal(points[-1], vertices[-1])
    np.testing.assert_array_equal(points[0], vertices[0])
    # equal along each segment, and as few pieces as the step allows (margin 1e-9)
    ends = np.r_[vertices[1:], vertices[:1]] if closed else vertices[1:]
    lengths = np.linalg.norm(ends - vertices[: len(ends)], axis=1)
    assert path.length == pytest.approx(lengths.sum(), abs=1e-14)
    start = 0
    for length in lengths:
        pieces = int(np.floor(length / (step * (1 - 1e-9)))) + 1
        segment_gaps = gaps[start : start + pieces]
        np.testing.assert_allclose(segment_gaps, length / pieces, rtol=1e-9)
        assert length / (pieces - 1) > step if pieces > 1 else True
        start += pieces
    assert start == len(gaps)


def test_a_side_that_is_a_whole_number_of_steps_gets_one_piece_more():
    points = tj.line((0.0, 0.0, 0.3), (0.15, 0.0, 0.3)).points(1e-3)
    assert len(points) == 152  # 151 pieces: 150 would put 1 mm ± round-off between samples
    assert _gaps(points, False).max() <= 1e-3


def test_at_follows_the_arc_length_and_batches():
    vertices = np.array([[0.0, 0, 0], [0.3, 0, 0], [0.3, 0.4, 0]])
    path = tj.polyline(vertices)
    np.testing.assert_allclose(
        path.at([[0.0, 0.3], [0.5, 0.7]]),
        [[[0, 0, 0], [0.3, 0, 0]], [[0.3, 0.2, 0], [0.3, 0.4, 0]]],
        atol=1e-15,
    )
    with pytest.raises(ValueError, match="s must lie in"):
        path.at(0.8)


def test_seed_000_square_corners_in_the_seed_order_and_its_circle():
    center, side = np.array([0.25, 0.1, 0.3]), 0.15
    square = tj.square(center, side, plane="yz")
    h = side / 2
    seed_corners = center + np.array([[0, -h, -h], [0, h, -h], [0, h, h], [0, -h, h], [0, -h, -h]])
    np.testing.assert_allclose(square.vertices, seed_corners, atol=1e-15)
    assert square.length == pytest.approx(0.6, abs=1e-15)
    circle = tj.circle(center, 0.1, plane="yz")
    points = circle.points(1e-3)
    assert len(points) == 629  # 2π·0.1 m / 1 mm = 628.3: 629 equal chords
    np.testing.assert_allclose(points[0], center + np.array([0, 0.1, 0]), atol=1e-15)
    assert points[1][2] > center[2]  # from +y towards +z, as the seed's cos/sin


@pytest.mark.parametrize("seed", range(10))
def test_circle_lies_on_its_circle_with_equal_chords_and_the_chord_error_is_the_sagitta(seed):
    rng = np.random.default_rng(100 + seed)
    center, radius = rng.uniform(-1, 1, 3), rng.uniform(0.01, 0.4)
    normal = rng.normal(size=3)
    step = STEPS[seed % len(STEPS)]
    path = tj.circle(center, radius, normal=normal, start=rng.uniform(-3, 3))
    points = path.points(step)
    n = normal / np.linalg.norm(normal)
    np.testing.assert_allclose(np.linalg.norm(points - center, axis=1), radius, rtol=1e-12)
    assert np.abs((points - center) @ n).max() < 1e-12
    gaps = _gaps(points, closed=True)
    assert gaps.max() <= step
    np.testing.assert_allclose(gaps, gaps[0], rtol=1e-9)
    # counter-clockwise about the normal
    assert np.cross(points[0] - center, points[1] - center) @ n > 0
    # chord error: the distance from a chord's midpoint to the circle
    mid = (points + np.roll(points, -1, axis=0)) / 2
    sagitta = radius - np.linalg.norm(mid - center, axis=1)
    assert path.chord_error(step) == pytest.approx(sagitta.max(), rel=1e-6)
    assert path.length == pytest.approx(2 * math.pi * radius, rel=1e-15)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: tj.polyline([[0, 0, 0], [0, 0, 0], [1, 0, 0]]), "coincide"),
        (lambda: tj.polyline([[0, 0, 0]]), r"shape \(K, 3\)"),
        (lambda: tj.polyline([[0, 0], [1, 1]]), r"shape \(K, 3\)"),
        (lambda: tj.polyline([[0, 0, 0], [np.nan, 0, 0]]), "NaN"),
        (lambda: tj.square((0, 0, 0), 0.1, plane="xz"), "plane must be one of"),
        (lambda: tj.square((0, 0, 0), 0.1), "either by name"),
        (lambda: tj.square((0, 0, 0), 0.1, plane="xy", normal=(0, 0, 1)), "either by name"),
        (lambda: tj.square((0, 0, 0), -0.1, plane="xy"), "side must be one number > 0"),
        (lambda: tj.circle((0, 0, 0), 0.1, normal=(0, 0, 0)), "zero vector"),
        (lambda: tj.circle((0, 0), 0.1, plane="xy"), r"center must be a point"),
        (lambda: tj.line((0, 0, 0), (1, 0, 0)).points(0.0), "step must be one number > 0"),
        (lambda: tj.line((0, 0, 0), (1, 0, 0)).points(float("nan")), "step"),
    ],
)
def test_bad_paths_are_refused_with_the_argument_named(call, message):
    with pytest.raises((ValueError, TypeError), match=message):
        call()


def test_pose_path_constant_and_slerp_orientation():
    path = tj.line((0.2, 0.0, 0.3), (0.2, 0.2, 0.3))
    R0 = random_rotations(1, seed=3)[0]
    constant = tj.pose_path(path, R0)
    np.testing.assert_array_equal(constant[:, :3, :3], np.broadcast_to(R0, (len(constant), 3, 3)))
    np.testing.assert_allclose(constant[:, :3, 3], path.points(), atol=0)
    np.testing.assert_array_equal(constant[:, 3], np.broadcast_to([0, 0, 0, 1], (len(constant), 4)))
    R1 = R0 @ rot_x(2.0)
    turning = tj.pose_path(path, R0, R1, step=1e-3)
    np.testing.assert_allclose(turning[0, :3, :3], R0, atol=1e-15)
    np.testing.assert_allclose(turning[-1, :3, :3], R1, atol=1e-12)
    # a constant rate about one axis: the angle from the start grows in step with the distance
    travelled = np.linalg.norm(turning[:, :3, 3] - turning[0, :3, 3], axis=1)
    angles = rotation_angle(R0, turning[:, :3, :3])
    np.testing.assert_allclose(angles, 2.0 * travelled / travelled[-1], atol=1e-12)
    default = tj.pose_path(np.array([[0, 0, 0], [0.1, 0, 0]]))
    np.testing.assert_array_equal(default[:, :3, :3], np.broadcast_to(np.eye(3), (2, 3, 3)))


def test_pose_path_refuses_a_half_turn_and_a_non_rotation():
    path = tj.line((0, 0, 0), (0.1, 0, 0))
    with pytest.raises(ValueError, match="turned by π"):
        tj.pose_path(path, np.eye(3), rot_z(np.pi))
    with pytest.raises(ValueError, match="R_start"):
        tj.pose_path(path, 2 * np.eye(3))


# ------------------------------------------------------------------------------- time scaling


def _profiles():
    return [
        tj.time_scaling("cubic", 2.0),
        tj.time_scaling("quintic", 1.3),
        tj.time_scaling("trapezoid", 1.7),
        tj.time_scaling("trapezoid", 2.0, peak_speed=1.0),
        tj.time_scaling("trapezoid", 0.5, peak_speed=3.9),
    ]


@pytest.mark.parametrize("profile", _profiles(), ids=lambda p: f"{p.kind}-{p.T}")
def test_time_scaling_rests_at_both_ends_and_its_derivatives_are_the_slopes(profile):
    T = profile.T
    s, sd, sdd = profile(np.array([-1.0, 0.0, T, T + 1.0]))
    np.testing.assert_allclose(s, [0, 0, 1, 1], atol=1e-15)
    assert sd[0] == sd[-1] == 0 and sdd[0] == sdd[-1] == 0
    t = np.linspace(0.01 * T, 0.99 * T, 997)
    h = 1e-6 * T
    s_p, sd_p, _ = profile(t + h)
    s_m, sd_m, _ = profile(t - h)
    _, sd_0, sdd_0 = profile(t)
    smooth = np.ones_like(t, dtype=bool)
    if profile.kind == "trapezoid":  # s̈ jumps where the phases meet: skip those instants
        ta = profile.peak_speed / profile.peak_acceleration
        smooth = (np.abs(t - ta) > 2 * h) & (np.abs(t - (T - ta)) > 2 * h)
    np.testing.assert_allclose(((s_p - s_m) / (2 * h))[smooth], sd_0[smooth], atol=1e-6 / T)
    np.testing.assert_allclose(((sd_p - sd_m) / (2 * h))[smooth], sdd_0[smooth], atol=1e-5 / T**2)
    dense = np.linspace(0, T, 200001)
    _, sd_d, sdd_d = profile(dense)
    assert sd_d.max() == pytest.approx(profile.peak_speed, rel=1e-8)
    assert np.abs(sdd_d).max() == pytest.approx(profile.peak_acceleration, rel=1e-6)
    assert np.all(np.diff(profile(dense)[0]) >= 0)


def test_time_scaling_textbook_values():
    # Lynch & Park §9.2: cubic peak ṡ = 3/(2T), s̈ = 6/T²; quintic peak ṡ = 15/(8T), s̈ = 10/(√3 T²)
    assert tj.time_scaling("cubic", 2.0).peak_speed == 0.75
    assert tj.time_scaling("cubic", 2.0).peak_acceleration == 1.5
    assert tj.time_scaling("quintic", 2.0).peak_speed == 15 / 16
    assert tj.time_scaling("quintic", 1.0).peak_acceleration == pytest.approx(5.773502692, rel=1e-9)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: tj.time_scaling("septic", 1.0), "kind must be"),
        (lambda: tj.time_scaling("cubic", 0.0), "T must be one number > 0"),
        (lambda: tj.time_scaling("cubic", 1.0, peak_speed=1.2), "trapezoid's"),
        (lambda: tj.time_scaling("trapezoid", 1.0, peak_speed=1.0), r"peak_speed must lie in"),
        (lambda: tj.time_scaling("trapezoid", 1.0, peak_speed=2.5), r"peak_speed must lie in"),
        (lambda: tj.minimum_time("cubic", [0.0, 0.0], 1.0, 1.0), "not all zero"),
        (lambda: tj.minimum_time("cubic", [1.0, 0.5], [1.0, -1.0], 1.0), "max_velocity"),
        (lambda: tj.minimum_time("cubic", [1.0, 0.5], 1.0, [1.0, 1.0, 1.0]), "max_acceleration"),
    ],
)
def test_bad_time_scalings_are_refused(call, message):
    with pytest.raises(ValueError, match=message):
        call()


@pytest.mark.parametrize("kind", ["cubic", "quintic", "trapezoid"])
@pytest.mark.parametrize("seed", range(8))
def test_minimum_time_keeps_every_joint_within_limits_and_one_joint_at_its_limit(kind, seed):
    rng = np.random.default_rng(seed)
    distance = rng.uniform(-3, 3, 6)
    distance[rng.integers(6)] = 0.0  # a joint that does not move costs nothing
    v_max = rng.uniform(0.5, 3.2, 6)
    a_max = rng.uniform(0.5, 40.0, 6) if seed % 2 else 1e3  # seed odd: cruising possible
    profile = tj.minimum_time(kind, distance, v_max, a_max)
    t = np.linspace(0, profile.T, 400001)
    _, sd, sdd = profile(t)
    speed = np.abs(distance)[None] * sd[:, None]
    accel = np.abs(distance)[None] * np.abs(sdd)[:, None]
    assert np.all(speed <= v_max * (1 + 1e-9))
    assert np.all(accel <= np.broadcast_to(a_max, 6) * (1 + 1e-9))
    # minimal: some joint reaches its velocity or acceleration limit
    used = max((speed / v_max).max(), (accel / a_max).max())
    assert used == pytest.approx(1.0, rel=1e-6)
    if (
        kind == "trapezoid"
    ):  # and the trapezoid is time-optimal: it uses both limits or is a triangle
        V = np.min(v_max[distance != 0] / np.abs(distance[distance != 0]))
        A = np.min(np.broadcast_to(a_max, 6)[distance != 0] / np.abs(distance[distance != 0]))
        optimal = 2 / math.sqrt(A) if V * V >= A else 1 / V + V / A
        assert profile.T == pytest.approx(optimal, rel=1e-12)


def test_joint_trajectory_moves_from_start_to_end_with_consistent_rates():
    q0, q1 = np.array([0.1, -1.2, 2.0]), np.array([1.0, 0.3, -0.5])
    profile = tj.minimum_time("quintic", q1 - q0, 1.0, 2.0)
    traj = tj.joint_trajectory(q0, q1, profile, samples=2001)
    np.testing.assert_allclose(traj.q[0], q0, atol=0)
    np.testing.assert_allclose(traj.q[-1], q1, atol=1e-15)
    dt = traj.t[1] - traj.t[0]
    np.testing.assert_allclose(np.gradient(traj.q, dt, axis=0)[1:-1], traj.qd[1:-1], atol=1e-5)
    np.testing.assert_allclose(np.gradient(traj.qd, dt, axis=0)[1:-1], traj.qdd[1:-1], atol=1e-4)
    with pytest.raises(ValueError, match="samples"):
        tj.joint_trajectory(q0, q1, profile, samples=1)
    with pytest.raises(TypeError, match="TimeScaling"):
        tj.joint_trajectory(q0, q1, 2.0)
