"""Numbers from the seed reports' errata (../shared/seeds/ERRATA.md) that the lessons teach."""

import numpy as np

import urkin
from urkin.kinematics import dh_chain
from urkin.robots import ALPHA_UR

# seed 002's UR5: its own lengths (mm → m), positive a2 and a3, angles = UR angles + SHIFT
D1, A2, A3, D4, D5, D6 = 0.0892, 0.425, 0.392, 0.1093, 0.09475, 0.0825
SEED002_TABLE = np.column_stack(
    [(D1, 0, 0, D4, D5, D6), (0, A2, A3, 0, 0, 0), ALPHA_UR]
)  # rows (d, a, alpha)
SHIFT = np.array([0.0, np.pi, 0.0, -np.pi, 0.0, 0.0])


def seed002_published_position(q):
    q1, q2, q3, q4, q5, _ = q
    c1, s1, c5, s5 = np.cos(q1), np.sin(q1), np.cos(q5), np.sin(q5)
    c2, s2, c3, s3 = np.cos(q2), np.sin(q2), np.cos(q3), np.sin(q3)
    c234, s234 = np.cos(q2 + q3 + q4), np.sin(q2 + q3 + q4)
    return np.array([
        D5 * c1 * s234 + D4 * s1 - D6 * c1 * c234 + A2 * c1 * c2 + D6 * c5 * s1
        + A3 * c1 * c2 * c3 - A3 * c1 * s2 * s3,
        D5 * s1 * s234 - D4 * c1 - D6 * s1 * c234 - D6 * c1 * c5 + A2 * c2 * s1
        + A3 * c2 * c3 * s1 - A3 * s1 * s2 * s3,
        D1 - D6 * s234 * s5 + A3 * np.sin(q2 + q3) + A2 * s2 - D5 * c234,
    ])  # fmt: skip


def test_seed002_at_035_rad_on_every_joint():
    q = np.full(6, 0.35)
    np.testing.assert_allclose(
        dh_chain(SEED002_TABLE, q)[:3, 3] * 1000, [784.706, 87.586, 415.781], atol=5e-4
    )
    np.testing.assert_allclose(
        seed002_published_position(q) * 1000, [759.367, 78.336, 415.781], atol=5e-4
    )


def test_seed002_angles_are_ur_angles_shifted():
    arm = urkin.Robot("seed 002 UR5", D1, -A2, -A3, D4, D5, D6)
    Q = np.random.default_rng(2).uniform(-np.pi, np.pi, (50, 6))
    np.testing.assert_allclose(dh_chain(SEED002_TABLE, Q + SHIFT), urkin.fk(arm, Q), atol=1e-12)


def test_seed002_formula_error_reaches_two_d6_and_hides_where_c234_is_zero():
    rng = np.random.default_rng(3)
    Q = rng.uniform(-np.pi, np.pi, (4000, 6))
    errors = np.array([
        np.linalg.norm(seed002_published_position(q) - dh_chain(SEED002_TABLE, q)[:3, 3])
        for q in Q
    ])  # fmt: skip
    c234 = np.cos(Q[:, 1] + Q[:, 2] + Q[:, 3])
    np.testing.assert_allclose(errors, D6 * np.abs(c234) * (1 - np.sin(Q[:, 4])), atol=1e-12)
    assert 0.95 * 2 * D6 < errors.max() <= 2 * D6
    np.testing.assert_allclose(seed002_published_position(np.zeros(6))[:2] -
                               dh_chain(SEED002_TABLE, np.zeros(6))[:3, 3][:2],
                               [-D6, 0.0], atol=1e-12)  # 82.5 mm at q = 0  # fmt: skip
