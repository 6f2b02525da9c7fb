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
        (lambda: tj.circle((0, 0, 0), 0.1, normal=(0, 0, 0)), "normal must be a non-zero"),
        (lambda: tj.circle((0, 0), 0.1, plane="xy"), r"center must be a point"),
        (lambda: tj.line((0, 0, 0), (1, 0, 0)).points(0.0), "step must be one number > 0"),
        (lambda: tj.line((0, 0, 0), (1, 0, 0)).points(float("nan")), "step"),
    ],
)
def test_bad_paths_are_refused_with_the_argument_named(call, message):
    with pytest.raises((ValueError, TypeError), match=message):
        call()


def test_plane_normal_keeps_its_direction_at_any_scale():
    """A normal whose norm overflows (or underflows) still gives the plane it points across."""
    reference = tj.circle((0.4, 0, 0.3), 0.05, normal=(0, 0, 1)).points()
    for normal in ((0, 0, 1e300), (0, 0, 5e-324), (0, 1e-200, 1e300)):
        points = tj.circle((0.4, 0, 0.3), 0.05, normal=normal).points()
        assert np.allclose(points, reference, rtol=0, atol=1e-15)


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
    for samples, error in ((np.nan, ValueError), (np.inf, ValueError), ("x", TypeError)):
        with pytest.raises(error, match="samples must be an integer from 2"):
            tj.joint_trajectory(q0, q1, profile, samples=samples)
    with pytest.raises(TypeError, match="TimeScaling"):
        tj.joint_trajectory(q0, q1, 2.0)


# ------------------------------------------------------------------------- via-point trajectories
# References: each segment's cubic solved from its four boundary conditions as a linear system
# (not the Hermite form the code uses), the heuristic velocities by a loop over vias and joints,
# finite differences, and the cubic time scaling's closed form 3τ² − 2τ³.


def _random_vias(seed, k=5, n=6):
    rng = np.random.default_rng(seed)
    q_via = rng.uniform(-np.pi, np.pi, (k, n))
    q_via[2, 1] = q_via[1, 1]  # a joint that stands still over a segment (slope 0)
    t_via = np.r_[0.0, np.cumsum(rng.integers(1, 9, k - 1))] / 8 + 0.25  # exact in binary
    return rng, q_via, t_via


def _heuristic(q_via, t_via):
    k, n = q_via.shape
    v = np.zeros((k, n))
    for i in range(1, k - 1):
        for joint in range(n):
            before = (q_via[i, joint] - q_via[i - 1, joint]) / (t_via[i] - t_via[i - 1])
            after = (q_via[i + 1, joint] - q_via[i, joint]) / (t_via[i + 1] - t_via[i])
            if (before > 0 and after > 0) or (before < 0 and after < 0):
                v[i, joint] = (before + after) / 2
    return v


def _reference(q_via, t_via, v_via, t):
    """q, qd, qdd at times t from each segment's cubic a0 + a1 s + a2 s² + a3 s³, its
    coefficients solved from q and q̇ at both ends."""
    segment = np.clip(np.searchsorted(t_via, t, side="right") - 1, 0, len(t_via) - 2)
    out = np.zeros((3, len(t), q_via.shape[1]))
    for j in range(len(t_via) - 1):
        T = t_via[j + 1] - t_via[j]
        system = np.array([[1, 0, 0, 0], [0, 1, 0, 0], [1, T, T**2, T**3], [0, 1, 2 * T, 3 * T**2]])
        a = np.linalg.solve(system, np.stack([q_via[j], v_via[j], q_via[j + 1], v_via[j + 1]]))
        s = (t[segment == j] - t_via[j])[:, None]
        out[0, segment == j] = a[0] + a[1] * s + a[2] * s**2 + a[3] * s**3
        out[1, segment == j] = a[1] + 2 * a[2] * s + 3 * a[3] * s**2
        out[2, segment == j] = 2 * a[2] + 6 * a[3] * s
    return out


@pytest.mark.parametrize("given", [False, True], ids=["heuristic", "given"])
@pytest.mark.parametrize("seed", range(5))
def test_via_trajectory_passes_every_via_exactly_with_its_velocity(seed, given):
    rng, q_via, t_via = _random_vias(seed)
    v_via = rng.uniform(-2, 2, q_via.shape) if given else _heuristic(q_via, t_via)
    step = 1 / 64  # a power of two: the sample times hit the vias exactly
    traj = tj.via_trajectory(q_via, t_via, v_via if given else None, dt=step)
    at = np.round((t_via - t_via[0]) / step).astype(int)
    np.testing.assert_array_equal(traj.t[at], t_via)
    np.testing.assert_array_equal(traj.q[at], q_via)
    np.testing.assert_array_equal(traj.qd[at], v_via)
    assert traj.t[-1] == t_via[-1] and len(traj.t) == at[-1] + 1
    # and between the vias, the cubics solved from their boundary conditions
    q, qd, qdd = _reference(q_via, t_via, v_via, traj.t)
    np.testing.assert_allclose(traj.q, q, atol=1e-12)
    np.testing.assert_allclose(traj.qd, qd, atol=1e-11)
    np.testing.assert_allclose(traj.qdd, qdd, atol=1e-10)


def test_via_heuristic_velocities_average_same_sign_slopes_else_stop():
    q_via = np.array([[0.0, 0.0], [1.0, 1.0], [3.0, 0.5], [3.0, 2.0], [2.0, 2.5]])
    t_via = np.array([0.0, 1.0, 2.0, 3.0, 5.0])
    traj = tj.via_trajectory(q_via, t_via, samples=11)  # every 0.5 s: vias at 0, 2, 4, 6, 10
    # joint 1: slopes 1, 2, 0, −0.5 → 1.5, 0 (a slope of zero), 0 (turns); joint 2: 1, −0.5,
    # 1.5, 0.25 → 0 (turns back), 0 (turns), 0.875
    expected = [[0.0, 0.0], [1.5, 0.0], [0.0, 0.0], [0.0, 0.875], [0.0, 0.0]]
    np.testing.assert_array_equal(traj.qd[[0, 2, 4, 6, 10]], expected)
    np.testing.assert_array_equal(_heuristic(q_via, t_via), expected)


@pytest.mark.parametrize("seed", range(3))
def test_via_trajectory_is_continuous_in_q_and_qd_and_its_rates_are_the_slopes(seed):
    _, q_via, t_via = _random_vias(10 + seed)
    h = 2.0**-12
    traj = tj.via_trajectory(q_via, t_via, dt=h)
    inner = np.round((t_via[1:-1] - t_via[0]) / h).astype(int)  # samples exactly at the vias
    np.testing.assert_array_equal(traj.t[inner], t_via[1:-1])
    qdd_max = np.abs(traj.qdd).max()
    # one-sided limits: one sample before and after each interior via, h → 0
    for i in inner:
        before, at, after = traj.q[i - 1], traj.q[i], traj.q[i + 1]
        assert np.all(np.abs(after - at - h * traj.qd[i]) <= qdd_max * h**2)
        assert np.all(np.abs(at - before - h * traj.qd[i]) <= qdd_max * h**2)
        assert np.all(np.abs(traj.qd[i + 1] - traj.qd[i - 1]) <= 2 * qdd_max * h * 1.001)
    # the left limits, from each segment's own cubic at its end (the reference)
    _, v_left, a_left = _reference(
        q_via[:-1], t_via[:-1], _heuristic(q_via, t_via)[:-1], t_via[1:-1]
    )
    np.testing.assert_allclose(v_left, traj.qd[inner], atol=1e-12)
    assert np.abs(a_left - traj.qdd[inner]).max() > 1e-3  # accelerations jump at the vias
    # away from the vias, the velocities and accelerations are the slopes of q and qd
    smooth = np.ones(len(traj.t), dtype=bool)
    for i in inner:
        smooth[i - 1 : i + 2] = False
    smooth[[0, -1]] = False
    dq = np.gradient(traj.q, h, axis=0)
    dqd = np.gradient(traj.qd, h, axis=0)
    np.testing.assert_allclose(dq[smooth], traj.qd[smooth], atol=1e-6 * max(1.0, qdd_max))
    np.testing.assert_allclose(dqd[smooth], traj.qdd[smooth], atol=1e-9 * max(1.0, qdd_max))


def test_two_vias_are_the_cubic_time_scaling():
    q0, q1 = np.array([0.1, -1.2, 2.0]), np.array([1.0, 0.3, -0.5])
    T, start = 2.5, 0.75
    traj = tj.via_trajectory([q0, q1], [start, start + T], samples=101)
    tau = ((traj.t - start) / T)[:, None]
    delta = q1 - q0
    np.testing.assert_allclose(traj.t, np.linspace(start, start + T, 101), atol=0)
    np.testing.assert_allclose(traj.q, q0 + (3 * tau**2 - 2 * tau**3) * delta, atol=1e-14)
    np.testing.assert_allclose(traj.qd, (6 * tau - 6 * tau**2) / T * delta, atol=1e-14)
    np.testing.assert_allclose(traj.qdd, (6 - 12 * tau) / T**2 * delta, atol=1e-13)
    same = tj.joint_trajectory(q0, q1, tj.time_scaling("cubic", T), samples=101)
    np.testing.assert_allclose(traj.q, same.q, atol=1e-14)
    np.testing.assert_allclose(traj.qd, same.qd, atol=1e-14)
    np.testing.assert_allclose(traj.qdd, same.qdd, atol=1e-13)


def test_via_trajectory_sampling_by_count_or_step():
    q_via, t_via = [[0.0], [1.0]], [0.0, 0.3]
    assert len(tj.via_trajectory(q_via, t_via).t) == 100
    by_step = tj.via_trajectory(q_via, t_via, dt=0.1)  # 0.3 / 0.1 = 2.9999999999999996
    np.testing.assert_allclose(by_step.t, [0.0, 0.1, 0.2, 0.3], atol=1e-15)
    assert by_step.t[-1] == 0.3 and by_step.q[-1, 0] == 1.0
    short = tj.via_trajectory(q_via, t_via, dt=0.25)  # does not reach the end: stops before
    np.testing.assert_array_equal(short.t, [0.0, 0.25])


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"q_via": [0.0, 1.0]}, r"q_via must have shape \(K, n\)"),
        ({"q_via": [[0.0, 1.0]], "t_via": [0.0]}, "K ≥ 2"),
        ({"t_via": [0.0, 1.0]}, r"t_via must have one time per via, shape \(3,\)"),
        ({"t_via": [0.0, 1.0, 1.0]}, r"strictly increasing; t_via\[2\]"),
        ({"t_via": [0.0, 2.0, 1.0]}, "strictly increasing"),
        ({"q_via": [[0.0, 1.0], [np.nan, 0.0], [1.0, 1.0]]}, "q_via contains NaN"),
        ({"t_via": [0.0, np.nan, 2.0]}, "t_via contains NaN"),
        ({"qd_via": np.zeros((3, 3))}, r"qd_via must have one velocity per via and joint"),
        ({"qd_via": [[0.0, 0.0], [np.inf, 0.0], [0.0, 0.0]]}, "qd_via contains NaN or inf"),
        ({"samples": 1}, "samples must be an integer from 2"),
        ({"samples": 2.5}, "samples must be an integer from 2"),
        ({"samples": np.nan}, "samples must be an integer from 2 to 10,000,000; got nan"),
        ({"samples": np.inf}, "samples must be an integer from 2 to 10,000,000; got inf"),
        ({"samples": 10, "dt": 0.1}, "samples or dt, not both"),
        ({"dt": 0.0}, "dt must be one number > 0"),
        ({"dt": np.nan}, "dt"),
    ],
)
def test_bad_vias_are_refused_with_the_argument_named(kwargs, message):
    arguments = {"q_via": [[0.0, 1.0], [1.0, 0.0], [2.0, 2.0]], "t_via": [0.0, 1.0, 2.0]}
    arguments |= kwargs
    with pytest.raises(ValueError, match=message):
        tj.via_trajectory(**arguments)


@pytest.mark.parametrize("kind", ["cubic", "quintic", "trapezoid"])
def test_time_scaling_at_extreme_durations_is_exact_or_refused(kind):
    """A duration whose square overflows still scales (its peaks are tiny); one so short that
    the peaks overflow is refused, saying so, rather than returning infinities."""
    long = tj.time_scaling(kind, 1e300)
    assert 0 < long.peak_speed < 1e-299 and 0 <= long.peak_acceleration < 1e-299
    s, _, _ = long(np.array([0.0, 5e299, 1e300]))
    assert np.allclose(s, [0.0, 0.5, 1.0], rtol=0, atol=1e-15)
    with pytest.raises(ValueError, match="too short"):
        tj.time_scaling(kind, 1e-160)


@pytest.mark.parametrize(
    "path, step",
    [
        (lambda: tj.line((0, 0, 0), (1e300, 1e300, 0)), 1e-3),  # its squares overflow
        (lambda: tj.circle((0, 0, 0), 1e300, plane="xy"), 1e-3),  # a count beyond int64
        (lambda: tj.square((0, 0, 0), 1e6, plane="xy"), 1e-3),  # 4e9 points: 30 GB
        (lambda: tj.line((0, 0, 0), (1, 0, 0)), 1e-300),
    ],
)
def test_sampling_that_would_take_too_many_points_is_refused(path, step):
    """Before: a negative-dimension error, an empty (0, 3) circle, or a 30 GB allocation."""
    p = path()
    assert math.isfinite(p.length)
    with pytest.raises(ValueError, match="takes more than 10,000,000 points"):
        p.points(step)


def test_via_trajectory_with_gaps_too_short_for_its_vias_is_refused():
    """Vias half a radian apart 1e-160 s apart need accelerations beyond any float: refused,
    not returned as infinities; 1e160 s apart, the accelerations underflow to about zero."""
    q = np.array([[0.0] * 6, [0.5] * 6, [0.0] * 6])
    with pytest.raises(ValueError, match="too short for these vias"):
        tj.via_trajectory(q, [0.0, 1e-160, 2e-160])
    slow = tj.via_trajectory(q, [0.0, 1e160, 2e160])
    assert np.isfinite(slow.qdd).all() and np.abs(slow.qdd).max() < 1e-300
    same = tj.via_trajectory(q, [0.0, 1.0, 2.0])  # the same path, in τ
    np.testing.assert_allclose(slow.q, same.q, rtol=0, atol=1e-15)


@pytest.mark.parametrize("acceleration", [1e15, 1e16, 1e300])
def test_a_trapezoid_that_is_nearly_all_cruise_still_evaluates_within_its_peaks(acceleration):
    # V·T rounds to 1 here: the ramp must come from the two peaks, not from V·T − 1
    ts = tj.minimum_time("trapezoid", [1.0], 1.0, acceleration)
    t = np.linspace(-0.1, ts.T + 0.1, 20_001)
    s, sd, sdd = ts(t)
    assert s[0] == 0.0 and s[-1] == 1.0
    assert np.all(np.diff(s) >= 0) and np.abs(np.diff(s)).max() < 1e-4
    assert sd.max() <= ts.peak_speed * (1 + 1e-12)
    assert np.abs(sdd).max() <= ts.peak_acceleration * (1 + 1e-12)
    motion = tj.joint_trajectory([0.0], [1.0], ts)
    assert np.all(np.isfinite(motion.q))
