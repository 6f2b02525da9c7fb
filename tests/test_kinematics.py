"""urkin's FK and Jacobians against references that share no code with it."""

import numpy as np
import pytest

import urkin
from tests.reference import (
    OFFICIAL_DH,
    complex_step_jacobian,
    dh_fk,
    finite_difference_jacobian,
)
from urkin.kinematics import check_joints, dh_chain, dh_transform
from urkin.robots import T_BASE_LINK_BASE, Robot
from urkin.transforms import make_transform, rpy_to_rotation


def random_q(rng, n=None):
    return rng.uniform(-np.pi, np.pi, size=(6,) if n is None else (n, 6))


def test_fk_equals_a_plain_product_of_dh_matrices(arm, rng):
    Q = random_q(rng, 200)
    expected = np.array([dh_fk(OFFICIAL_DH[arm.name], q) for q in Q])
    np.testing.assert_allclose(urkin.fk(arm, Q), expected, rtol=0, atol=1e-12)
    for q, T in zip(Q[:20], expected):
        np.testing.assert_allclose(urkin.fk(arm, q), T, rtol=0, atol=1e-12)


def test_batches_larger_than_a_block_match_single_poses(rng):
    ur10 = urkin.robot("ur10")
    Q = random_q(rng, 5000)  # more than one evaluation block
    T = urkin.fk(ur10, Q)
    J = urkin.jacobian(ur10, Q)
    for i in rng.choice(5000, 30, replace=False):
        np.testing.assert_allclose(T[i], urkin.fk(ur10, Q[i]), rtol=0, atol=1e-14)
        np.testing.assert_allclose(J[i], urkin.jacobian(ur10, Q[i]), rtol=0, atol=1e-14)


def test_column_code_cos_sin_match_numpy_over_the_whole_angle_range(rng):
    # the batched code takes cos and sin from tan(angle / 2); angles reach ±8π per joint and
    # ±24π as sums, and the tangent is largest next to odd multiples of π
    from urkin._generated.ur_kinematics import _cos_sin

    odd = np.pi * np.arange(-23, 24, 2)
    near = (odd[:, None] + np.array([-1e-8, -1e-15, 0.0, 1e-15, 1e-8])).ravel()
    angles = np.concatenate([rng.uniform(-24 * np.pi, 24 * np.pi, 100_000), near])
    c, s = np.empty_like(angles), np.empty_like(angles)
    _cos_sin(angles, c, s)
    np.testing.assert_allclose(c, np.cos(angles), rtol=0, atol=1e-15)
    np.testing.assert_allclose(s, np.sin(angles), rtol=0, atol=1e-15)


def test_complex_batches_larger_than_a_block_keep_their_derivative(rng):
    ur5 = urkin.robot("ur5")
    Q = random_q(rng, 4100)
    h = 1e-20
    T = urkin.fk(ur5, Q + 1j * h * np.eye(6)[2])  # d/dq3 by complex step, over three blocks
    for i in (0, 2500, 4099):
        dT = complex_step_jacobian(OFFICIAL_DH["UR5"], Q[i])  # columns [v; ω]
        np.testing.assert_allclose(T[i, :3, 3].imag / h, dT[:3, 2], rtol=0, atol=1e-12)


def test_fk_frames_are_the_partial_products(arm, rng):
    from tests.reference import dh_matrix, dh_table

    q = random_q(rng)
    frames = urkin.fk_frames(arm, q)
    T = np.eye(4)
    np.testing.assert_array_equal(frames[0], T)
    for i, (d, a, alpha) in enumerate(dh_table(OFFICIAL_DH[arm.name])):
        T = T @ dh_matrix(q[i], d, a, alpha)
        np.testing.assert_allclose(frames[i + 1], T, rtol=0, atol=1e-12)
    assert urkin.fk_frames(arm, random_q(rng, 3)).shape == (3, 7, 4, 4)


def test_jacobian_equals_complex_step_derivative(arm, rng):
    for q in random_q(rng, 40):
        expected = complex_step_jacobian(OFFICIAL_DH[arm.name], q)
        np.testing.assert_allclose(urkin.jacobian(arm, q), expected, rtol=0, atol=1e-12)


def test_jacobian_agrees_with_central_differences(arm, rng):
    Q = random_q(rng, 10)
    J = urkin.jacobian(arm, Q)
    for q, Jq in zip(Q, J):
        np.testing.assert_allclose(
            Jq, finite_difference_jacobian(OFFICIAL_DH[arm.name], q), rtol=0, atol=1e-8
        )


def test_position_jacobian_is_the_derivative_of_position(arm, rng):
    Q = random_q(rng, 40)
    Jp = urkin.position_jacobian(arm, Q)
    for q, Jq in zip(Q, Jp):
        np.testing.assert_allclose(
            Jq, complex_step_jacobian(OFFICIAL_DH[arm.name], q)[:3], rtol=0, atol=1e-12
        )
    np.testing.assert_allclose(Jp, urkin.jacobian(arm, Q)[:, :3], rtol=0, atol=1e-13)


def test_modern_robotics_ur5_example():
    # Lynch & Park, Modern Robotics, the UR5 example: W1 = 0.109, W2 = 0.082, L1 = 0.425,
    # L2 = 0.392, H1 = 0.089, H2 = 0.095; at θ2 = −π/2, θ5 = π/2 the book gives T in its
    # space frame, which is Rz(π) applied to DH frame 0.
    W1, W2, L1, L2, H1, H2 = 0.109, 0.082, 0.425, 0.392, 0.089, 0.095
    book_ur5 = Robot("MR UR5", H1, -L1, -L2, W1, H2, W2)
    q = np.array([0.0, -np.pi / 2, 0.0, 0.0, np.pi / 2, 0.0])
    expected = np.array(
        [[0, -1, 0, 0.095], [1, 0, 0, 0.109], [0, 0, 1, 0.988], [0, 0, 0, 1]], dtype=float
    )
    np.testing.assert_allclose(T_BASE_LINK_BASE @ urkin.fk(book_ur5, q), expected, atol=1e-12)


def test_tool_and_base_transforms(rng):
    T_world_base = make_transform(rpy_to_rotation([0.1, -0.2, 0.3]), [0.5, -0.2, 0.1])
    T_flange_tool = make_transform(rpy_to_rotation([0.0, 0.4, -0.1]), [0.01, 0.02, 0.15])
    ur5 = urkin.robot("ur5")
    mounted = ur5.with_base(T_world_base).with_tool(T_flange_tool)
    Q = random_q(rng, 20)
    np.testing.assert_allclose(
        urkin.fk(mounted, Q), T_world_base @ urkin.fk(ur5, Q) @ T_flange_tool, atol=1e-14
    )
    np.testing.assert_allclose(
        urkin.fk_frames(mounted, Q)[:, 0], np.broadcast_to(T_world_base, (20, 4, 4))
    )
    # the Jacobian of the tool point in the world frame, by complex step of the whole chain
    lengths = OFFICIAL_DH["UR5"]
    for q in Q[:10]:
        R = (T_world_base @ dh_fk(lengths, q) @ T_flange_tool)[:3, :3]
        J = np.zeros((6, 6))
        for k in range(6):
            dq = q.astype(complex)
            dq[k] += 1e-30j
            dT = (T_world_base @ dh_fk(lengths, dq) @ T_flange_tool).imag / 1e-30
            W = dT[:3, :3] @ R.T
            J[:3, k] = dT[:3, 3]
            J[3:, k] = [W[2, 1], W[0, 2], W[1, 0]]
        np.testing.assert_allclose(urkin.jacobian(mounted, q), J, atol=1e-12)
        np.testing.assert_allclose(urkin.position_jacobian(mounted, q), J[:3], atol=1e-12)


def test_dh_transform_and_chain_conventions(rng):
    theta, d, a, alpha = rng.uniform(-2, 2, 4)
    c, s = np.cos, np.sin
    Rz = np.array(
        [[c(theta), -s(theta), 0, 0], [s(theta), c(theta), 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
    )
    Rx = np.array(
        [[1, 0, 0, 0], [0, c(alpha), -s(alpha), 0], [0, s(alpha), c(alpha), 0], [0, 0, 0, 1]]
    )
    Tz, Tx = np.eye(4), np.eye(4)
    Tz[2, 3], Tx[0, 3] = d, a
    np.testing.assert_allclose(dh_transform(theta, d, a, alpha), Rz @ Tz @ Tx @ Rx, atol=1e-15)
    np.testing.assert_allclose(
        dh_transform(theta, d, a, alpha, convention="modified"), Rx @ Tx @ Rz @ Tz, atol=1e-15
    )
    with pytest.raises(ValueError, match="convention"):
        dh_transform(theta, d, a, alpha, convention="craig")
    ur3 = urkin.robot("ur3")
    Q = random_q(rng, 5)
    np.testing.assert_allclose(dh_chain(ur3.dh_table(), Q), urkin.fk(ur3, Q), atol=1e-14)


@pytest.mark.parametrize(
    ("q", "error", "message"),
    [
        (np.zeros(5), ValueError, r"shape \(6,\) or \(\.\.\., 6\); got \(5,\)"),
        (np.zeros((3, 7)), ValueError, r"got \(3, 7\)"),
        ([0, 0, np.nan, 0, 0, 0], ValueError, "NaN"),
        (
            np.array([[0.0] * 6, [np.inf] + [0.0] * 5]),
            ValueError,
            r"q contains NaN or infinity \(entry \(1, 0\)\)",
        ),
        ([0, -90, 0, -90, 0, 0], ValueError, "degrees"),
        ("home", TypeError, "q must be numbers; got str"),
        ([None] * 6, TypeError, "got None"),
    ],
)
def test_bad_joint_angles_get_a_clear_error(q, error, message):
    with pytest.raises(error, match=message):
        urkin.fk(urkin.robot("ur5"), q)


def test_robot_argument_is_checked():
    with pytest.raises(TypeError, match=r"urkin.robot\('ur5'\)"):
        urkin.fk("ur5", np.zeros(6))


def test_check_joints_accepts_lists_and_batches():
    assert check_joints([0.0] * 6).dtype == float
    assert check_joints(np.zeros((0, 6))).shape == (0, 6)
    assert urkin.fk(urkin.robot("ur5"), np.zeros((0, 6))).shape == (0, 4, 4)
