"""Product-of-exponentials kinematics against independent references."""

import numpy as np
import pytest

import urkin
from tests.reference import OFFICIAL_DH, complex_step_jacobian, dh_fk
from urkin import poe
from urkin.robots import T_BASE_LINK_BASE, Robot
from urkin.transforms import (
    adjoint,
    inv_transform,
    make_transform,
    rot_z,
    rpy_to_rotation,
    se3_exp,
    se3_log,
    twist_matrix,
)


def random_q(rng, n=None):
    return rng.uniform(-np.pi, np.pi, size=(6,) if n is None else (n, 6))


def test_space_and_body_fk_equal_the_dh_product(arm, rng):
    S, M = poe.space_screws(arm)
    B, M_body = poe.body_screws(arm)
    np.testing.assert_array_equal(M, M_body)
    Q = random_q(rng, 100)
    expected = np.array([dh_fk(OFFICIAL_DH[arm.name], q) for q in Q])
    np.testing.assert_allclose(poe.fk_space(M, S, Q), expected, rtol=0, atol=1e-12)
    np.testing.assert_allclose(poe.fk_body(M, B, Q), expected, rtol=0, atol=1e-12)
    for q, T in zip(Q[:10], expected):
        np.testing.assert_allclose(poe.fk_space(M, S, q), T, rtol=0, atol=1e-12)
        np.testing.assert_allclose(poe.fk_body(M, B, q), T, rtol=0, atol=1e-12)


def test_screw_axes_are_unit_rotations_with_v_perpendicular(arm):
    S, _ = poe.space_screws(arm)
    np.testing.assert_allclose(np.linalg.norm(S[:3], axis=0), 1.0, atol=1e-15)
    np.testing.assert_allclose(np.sum(S[:3] * S[3:], axis=0), 0.0, atol=1e-15)  # pure rotations


# Modern Robotics (Lynch & Park), the UR5 example: its space frame is Rz(π) of DH frame 0
W1, W2, L1, L2, H1, H2 = 0.109, 0.082, 0.425, 0.392, 0.089, 0.095
BOOK_M = np.array([[-1, 0, 0, L1 + L2], [0, 0, 1, W1 + W2], [0, 1, 0, H1 - H2], [0, 0, 0, 1]])
BOOK_S = np.array(
    [
        [0, 0, 1, 0, 0, 0],
        [0, 1, 0, -H1, 0, 0],
        [0, 1, 0, -H1, 0, L1],
        [0, 1, 0, -H1, 0, L1 + L2],
        [0, 0, -1, -W1, L1 + L2, 0],
        [0, 1, 0, H2 - H1, 0, L1 + L2],
    ],
    dtype=float,
).T
BOOK_T = np.array([[0, -1, 0, 0.095], [1, 0, 0, 0.109], [0, 0, 1, 0.988], [0, 0, 0, 1]], float)


def test_modern_robotics_ur5_example():
    q = np.array([0.0, -np.pi / 2, 0.0, 0.0, np.pi / 2, 0.0])
    np.testing.assert_allclose(poe.fk_space(BOOK_M, BOOK_S, q), BOOK_T, atol=1e-12)
    book_ur5 = Robot("MR UR5", H1, -L1, -L2, W1, H2, W2)
    S, M = poe.space_screws(book_ur5)
    np.testing.assert_allclose(adjoint(T_BASE_LINK_BASE) @ S, BOOK_S, atol=1e-15)
    np.testing.assert_allclose(T_BASE_LINK_BASE @ M, BOOK_M, atol=1e-15)


# Seed 001: a UR3 in V-REP, joint axes a_n through points q_n, and its printed S and M
SEED001_AXES = np.array(
    [[0, 0, 1], [-1, 0, 0], [-1, 0, 0], [-1, 0, 0], [0, 0, 1], [-1, 0, 0]], float
)
SEED001_POINTS = np.array(
    [
        [0, 0, 0.1045],
        [-0.116, 0, 0.109],
        [-0.117, 0, 0.353],
        [-0.118, 0, 0.566],
        [-0.112, 0, 0.65],
        [-0.112, 0, 0.651],
    ]
)
SEED001_S = np.array(
    [
        [0, -1, -1, -1, 0, -1],
        [0, 0, 0, 0, 0, 0],
        [1, 0, 0, 0, 1, 0],
        [0, 0, 0, 0, 0, 0],
        [0, -0.109, -0.352, -0.566, 0.112, -0.651],
        [0, 0, 0, 0, 0, 0],
    ]
)
SEED001_M = np.array([[0, 0, -1, -0.194], [0, 1, 0, 0], [1, 0, 0, 0.651], [0, 0, 0, 1]], float)


def test_seed001_screw_axes_follow_from_its_axes_and_points():
    S = poe.screw_axis(SEED001_AXES, SEED001_POINTS).T
    # as printed, except column 3, which the report rounded by 1 mm
    np.testing.assert_allclose(np.delete(S, 2, axis=1), np.delete(SEED001_S, 2, axis=1), atol=1e-12)
    np.testing.assert_allclose(S[:, 2], SEED001_S[:, 2], atol=1.0001e-3)


def test_seed001_model_is_the_ur3_within_its_rounding(rng):
    # the V-REP model: UR3 DH angles θ + (0, −π/2, 0, −π/2, 0, 0), a base turned −90° about z
    # with its reference 42.9 mm away along z, and a flange turned −90° about its z
    offset = np.array([0, -np.pi / 2, 0, -np.pi / 2, 0, 0])
    T_vrep_base = make_transform(rot_z(-np.pi / 2), [0, 0, -0.0429])
    T_flange_tool = make_transform(rot_z(-np.pi / 2))
    ur3 = urkin.robot("ur3")
    Q = random_q(rng, 500)
    seed = poe.fk_space(SEED001_M, SEED001_S, Q)
    ours = T_vrep_base @ urkin.fk(ur3, Q + offset) @ T_flange_tool
    np.testing.assert_allclose(seed[:, :3, :3], ours[:, :3, :3], atol=1e-12)
    assert np.abs(seed[:, :3, 3] - ours[:, :3, 3]).max() < 2e-3


def test_space_body_and_geometric_jacobians_agree_through_the_adjoint(arm, rng):
    S, _ = poe.space_screws(arm)
    B, _ = poe.body_screws(arm)
    Q = random_q(rng, 50)
    T = urkin.fk(arm, Q)
    J_s, J_b, J = poe.jacobian_space(S, Q), poe.jacobian_body(B, Q), urkin.jacobian(arm, Q)
    np.testing.assert_allclose(J_s, adjoint(T) @ J_b, rtol=0, atol=1e-12)
    np.testing.assert_allclose(poe.space_from_geometric(J, T), J_s, rtol=0, atol=1e-12)
    np.testing.assert_allclose(poe.geometric_from_space(J_s, T), J, rtol=0, atol=1e-12)
    for q, Jq in zip(Q[:20], J_s):
        expected = poe.space_from_geometric(
            complex_step_jacobian(OFFICIAL_DH[arm.name], q), dh_fk(OFFICIAL_DH[arm.name], q)
        )
        np.testing.assert_allclose(Jq, expected, rtol=0, atol=1e-12)
    np.testing.assert_allclose(poe.jacobian_space(S, Q[0]), J_s[0], rtol=0, atol=1e-14)


def test_body_jacobian_is_the_body_twist_by_complex_step(rng):
    # [V_b] = T⁻¹ dT/dq_i, differentiated with complex steps through the plain DH product
    lengths = OFFICIAL_DH["UR10e"]
    B, _ = poe.body_screws(urkin.robot("ur10e"))
    for q in random_q(rng, 10):
        T_inv = inv_transform(dh_fk(lengths, q))
        columns = []
        for k in range(6):
            dq = q.astype(complex)
            dq[k] += 1e-30j
            W = T_inv @ (dh_fk(lengths, dq).imag / 1e-30)
            columns.append([W[2, 1], W[0, 2], W[1, 0], *W[:3, 3]])
        np.testing.assert_allclose(poe.jacobian_body(B, q), np.array(columns).T, atol=1e-12)


def test_screws_from_a_modified_dh_table_give_the_same_arm(rng):
    # the UR3 rewritten for the modified convention: a and α shift down one row
    ur3 = urkin.robot("ur3")
    d, a, alpha = ur3.d, np.r_[0.0, ur3.a[:-1]], np.r_[0.0, ur3.alpha[:-1]]
    modified = np.column_stack([d, a, alpha])
    S, M = poe.space_screws(modified, convention="modified")
    S_std, _ = poe.space_screws(ur3)
    np.testing.assert_allclose(S, S_std, atol=1e-15)
    Q = random_q(rng, 20)
    # the modified chain ends in frame 6 turned by the last link's α = 0 and a = 0: the same
    np.testing.assert_allclose(poe.fk_space(M, S, Q), urkin.fk(ur3, Q), atol=1e-12)


def test_a_base_and_tool_are_honoured(rng):
    T_world_base = make_transform(rpy_to_rotation([0.2, -0.1, 0.4]), [0.3, 0.1, -0.2])
    T_flange_tool = make_transform(rpy_to_rotation([0.1, 0.2, 0.3]), [0.0, 0.02, 0.12])
    arm = urkin.robot("ur5").with_base(T_world_base).with_tool(T_flange_tool)
    S, M = poe.space_screws(arm)
    B, _ = poe.body_screws(arm)
    Q = random_q(rng, 10)
    np.testing.assert_allclose(poe.fk_space(M, S, Q), urkin.fk(arm, Q), atol=1e-12)
    np.testing.assert_allclose(poe.fk_body(M, B, Q), urkin.fk(arm, Q), atol=1e-12)
    np.testing.assert_allclose(
        poe.geometric_from_space(poe.jacobian_space(S, Q), urkin.fk(arm, Q)),
        urkin.jacobian(arm, Q),
        atol=1e-12,
    )


def test_se3_exp_and_log(rng):
    V = np.concatenate([rng.normal(size=(200, 3)), rng.normal(size=(200, 3))], axis=1)
    V[:, :3] *= (rng.uniform(0, np.pi - 1e-6, 200) / np.linalg.norm(V[:, :3], axis=1))[:, None]
    np.testing.assert_allclose(se3_log(se3_exp(V)), V, atol=1e-10)
    # exp of a twist matrix by a long Taylor series, an independent reference
    for v in V[:5] * 0.3:
        A, term, series = twist_matrix(v), np.eye(4), np.eye(4)
        for k in range(1, 40):
            term = term @ A / k
            series = series + term
        np.testing.assert_allclose(se3_exp(v), series, atol=1e-13)
    np.testing.assert_allclose(se3_exp(np.zeros(6)), np.eye(4))
    np.testing.assert_allclose(se3_log(np.eye(4)), np.zeros(6))


@pytest.mark.parametrize("angle", [np.pi, np.pi - 1e-9, 1e-9, 1e-5])
def test_se3_log_near_zero_and_pi(angle):
    V = np.array([0.0, 0.6, 0.8, 0.3, -0.2, 0.5])
    V[:3] *= angle
    T = se3_exp(V)
    np.testing.assert_allclose(se3_exp(se3_log(T)), T, atol=1e-12)


def test_adjoint_maps_twists_between_frames(rng):
    T = make_transform(rpy_to_rotation(rng.uniform(-1, 1, 3)), rng.uniform(-1, 1, 3))
    V = rng.normal(size=6)
    np.testing.assert_allclose(
        twist_matrix(adjoint(T) @ V), T @ twist_matrix(V) @ inv_transform(T), atol=1e-14
    )
    np.testing.assert_allclose(adjoint(inv_transform(T)), np.linalg.inv(adjoint(T)), atol=1e-12)


def test_bad_inputs_name_the_problem():
    S, M = poe.space_screws(urkin.robot("ur5"))
    with pytest.raises(ValueError, match=r"shape \(6, n\)"):
        poe.fk_space(M, S[:5], np.zeros(6))
    with pytest.raises(ValueError, match=r"\(6,\) or \(\.\.\., 6\)"):
        poe.fk_space(M, S, np.zeros(5))
    with pytest.raises(ValueError, match="rotation"):
        poe.fk_space(np.diag([1.0, 1.0, -1.0, 1.0]), S, np.zeros(6))
    with pytest.raises(ValueError, match="NaN"):
        poe.jacobian_space(S, [np.nan] * 6)
