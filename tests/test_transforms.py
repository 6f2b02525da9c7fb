import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from urkin import transforms as tf

finite = st.floats(-10, 10, allow_nan=False)
vectors = arrays(float, 3, elements=finite)
angles = st.floats(-np.pi, np.pi, allow_nan=False)


def random_rotations(rng, n):
    # uniformly distributed rotations from normalised quaternions (independent of urkin)
    quat = rng.normal(size=(n, 4))
    w, x, y, z = (quat / np.linalg.norm(quat, axis=1, keepdims=True)).T
    return np.stack(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    ).transpose(2, 0, 1)


def test_axis_rotations_match_the_textbook_matrices():
    c, s = np.cos(0.3), np.sin(0.3)
    np.testing.assert_allclose(tf.rot_x(0.3), [[1, 0, 0], [0, c, -s], [0, s, c]], atol=1e-15)
    np.testing.assert_allclose(tf.rot_y(0.3), [[c, 0, s], [0, 1, 0], [-s, 0, c]], atol=1e-15)
    np.testing.assert_allclose(tf.rot_z(0.3), [[c, -s, 0], [s, c, 0], [0, 0, 1]], atol=1e-15)


def test_rotations_are_batched():
    assert tf.rot_z(np.zeros((4, 5))).shape == (4, 5, 3, 3)
    assert tf.so3_exp(np.zeros((7, 3))).shape == (7, 3, 3)


@given(vectors)
def test_exp_is_a_rotation(w):
    tf.check_rotation(tf.so3_exp(w), tol=1e-12)


@given(vectors.filter(lambda w: np.linalg.norm(w) < np.pi - 1e-6))
def test_log_inverts_exp(w):
    np.testing.assert_allclose(tf.so3_log(tf.so3_exp(w)), w, atol=1e-12)


def test_exp_of_a_rotation_about_z_is_rot_z():
    np.testing.assert_allclose(tf.so3_exp([0, 0, 0.7]), tf.rot_z(0.7), atol=1e-15)


def test_log_round_trips_random_rotations(rng):
    R = random_rotations(rng, 2000)
    np.testing.assert_allclose(tf.so3_exp(tf.so3_log(R)), R, atol=1e-12)


@pytest.mark.parametrize("angle", [np.pi, np.pi - 1e-9, np.pi - 1e-5, 3.0, 1e-9, 1e-14, 0.0])
def test_log_is_accurate_near_zero_and_pi(rng, angle):
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    R = tf.so3_exp(angle * axis)
    w = tf.so3_log(R)
    np.testing.assert_allclose(np.linalg.norm(w), angle, atol=1e-12)
    np.testing.assert_allclose(tf.so3_exp(w), R, atol=1e-12)


def test_skew_is_the_cross_product(rng):
    a, b = rng.normal(size=(2, 3))
    np.testing.assert_allclose(tf.skew(a) @ b, np.cross(a, b), atol=1e-15)
    np.testing.assert_allclose(tf.unskew(tf.skew(a)), a)


@given(angles, st.floats(-1.5, 1.5), angles)
@settings(max_examples=200)
def test_rpy_round_trip(roll, pitch, yaw):
    R = tf.rpy_to_rotation([roll, pitch, yaw])
    rpy = tf.rotation_to_rpy(R)
    # the same angles, roll and yaw in (−π, π] (an input of −π comes back as π)
    np.testing.assert_allclose(tf.wrap_angles(rpy - [roll, pitch, yaw]), 0.0, atol=1e-9)
    assert np.all(rpy[::2] > -np.pi) and np.all(rpy[::2] <= np.pi)


def test_roll_and_yaw_of_half_a_turn_are_pi_not_minus_pi():
    assert tf.rotation_to_rpy(tf.rot_z(-np.pi))[2] == np.pi
    assert tf.rotation_to_rpy(tf.rot_x(-np.pi))[0] == np.pi
    stack = tf.rotation_to_rpy(np.stack([tf.rot_z(-np.pi), tf.rot_x(-np.pi)]))
    assert stack[0, 2] == np.pi and stack[1, 0] == np.pi


def test_wrap_angles_keeps_an_angle_just_above_minus_pi():
    x = np.nextafter(-np.pi, 0.0)
    assert tf.wrap_angles(x) == x
    assert tf.wrap_angles(np.array([x, 3 * np.pi]))[0] == x
    assert np.all(tf.wrap_angles(np.array([x, -np.pi, 7.0, 3 * np.pi])) <= np.pi)


def test_pose_error_of_one_pose_is_exact_near_half_a_turn():
    for gap in (1e-6, 1e-8, 1e-10):
        B = tf.make_transform(tf.rot_z(np.pi - gap))
        assert abs(tf.pose_error(np.eye(4), B)[1] - (np.pi - gap)) < 1e-14
        assert tf.pose_error(np.eye(4), B)[1] == tf.pose_error(np.eye(4)[None], B[None])[1][0]


def test_rpy_is_fixed_axis_xyz():
    # yaw about z last: a pure yaw turns x into y
    np.testing.assert_allclose(
        tf.rpy_to_rotation([0, 0, np.pi / 2]) @ [1, 0, 0], [0, 1, 0], atol=1e-15
    )
    R = tf.rpy_to_rotation([0.1, 0.2, 0.3])
    expected = tf.rot_z(0.3) @ tf.rot_y(0.2) @ tf.rot_x(0.1)
    np.testing.assert_allclose(R, expected, atol=1e-15)


@pytest.mark.parametrize("pitch", [np.pi / 2, -np.pi / 2])
def test_rpy_at_gimbal_lock_reproduces_the_rotation(pitch):
    R = tf.rpy_to_rotation([0.4, pitch, -0.3])
    rpy = tf.rotation_to_rpy(R)
    assert rpy[2] == 0.0
    np.testing.assert_allclose(tf.rpy_to_rotation(rpy), R, atol=1e-12)


def test_inverse_transform(rng):
    R = random_rotations(rng, 50)
    T = tf.make_transform(R, rng.normal(size=(50, 3)))
    np.testing.assert_allclose(
        tf.inv_transform(T) @ T, np.broadcast_to(np.eye(4), T.shape), atol=1e-14
    )
    np.testing.assert_allclose(tf.inv_transform(T), np.linalg.inv(T), atol=1e-13)


def test_rotation_angle_is_accurate_for_tiny_angles():
    assert tf.rotation_angle(tf.rot_x(1e-10), np.eye(3)) == pytest.approx(1e-10, rel=1e-6)
    assert tf.rotation_angle(tf.rot_x(2.5)) == pytest.approx(2.5, rel=1e-12)
    assert tf.rotation_angle(tf.rot_x(np.pi)) == pytest.approx(np.pi, rel=1e-12)


@pytest.mark.parametrize("distance", [0.0, 1e-12, 1e-9, 1e-6, 1e-3, 0.5, np.pi / 2])
def test_rotation_angle_is_accurate_up_to_a_half_turn(rng, distance):
    """Near π the arcsine of ‖R1 − R2‖ / 2√2 loses half the digits (6e-8 rad at π about a
    generic axis): the angle stays exact to round-off at every distance from π, for one
    rotation, a stack, a pair of stacks and pose_error, about random axes."""
    axis = rng.normal(size=(200, 3))
    axis /= np.linalg.norm(axis, axis=1, keepdims=True)
    angle = np.pi - distance
    R = tf.so3_exp(axis * angle)
    np.testing.assert_allclose(tf.rotation_angle(R), angle, rtol=0, atol=2e-15)
    assert abs(tf.rotation_angle(R[0]) - angle) < 2e-15
    base = random_rotations(rng, 200)
    np.testing.assert_allclose(tf.rotation_angle(base, base @ R), angle, rtol=0, atol=4e-15)
    T1, T2 = tf.make_transform(base, np.zeros(3)), tf.make_transform(base @ R, np.zeros(3))
    np.testing.assert_allclose(tf.pose_error(T1, T2)[1], angle, rtol=0, atol=4e-15)


@pytest.mark.parametrize(
    ("matrix", "message"),
    [
        (np.eye(4)[:3], "shape"),
        (np.diag([1.0, 1.0, -1.0]), "reflection"),
        (2 * np.eye(3), "not a rotation"),
        (np.full((3, 3), np.nan), "NaN"),
        (np.eye(3).T @ np.array([[1, 1e-3, 0], [0, 1, 0], [0, 0, 1]]), "orthonormal"),
    ],
)
def test_check_rotation_names_the_problem(matrix, message):
    with pytest.raises(ValueError, match=message):
        tf.check_rotation(matrix)


def test_check_transform_names_the_problem():
    T = np.eye(4)
    T[3, 0] = 0.5
    with pytest.raises(ValueError, match=r"\[0, 0, 0, 1\]"):
        tf.check_transform(T)
    with pytest.raises(ValueError, match="rotation part"):
        tf.check_transform(np.diag([1.0, 1.0, -1.0, 1.0]))
    with pytest.raises(TypeError, match="numbers"):
        tf.check_transform("eye")


def test_orthonormalize_refuses_matrices_without_one_nearest_rotation(rng):
    """Zero and rank-1 matrices are equally near a whole family of rotations: refused, not
    turned into the identity.  Of rank 2 (det 0) the nearest rotation is unique whatever sign
    the SVD gives the null direction: no sampled rotation is nearer."""
    for M in (np.zeros((3, 3)), np.ones((3, 3)), np.outer([1.0, 2, 3], [0.0, 1, 0])):
        with pytest.raises(ValueError, match="R has no nearest rotation"):
            tf.orthonormalize(M)
    with pytest.raises(ValueError, match="closer to a reflection"):
        tf.orthonormalize(np.diag([1.0, 1.0, -1.0]))
    samples = tf.so3_exp(rng.normal(size=(100_000, 3)))
    for _ in range(5):
        U, S, Vt = np.linalg.svd(rng.normal(size=(3, 3)))
        M = U @ np.diag([S[0], S[1], 0.0]) @ Vt
        R = tf.orthonormalize(M)
        assert tf.check_rotation(R, tol=1e-12) is not None
        nearest = np.sum((samples - M) ** 2, axis=(1, 2)).min()
        assert np.sum((R - M) ** 2) <= nearest + 1e-12
