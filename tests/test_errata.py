"""Numbers from the seed reports' errata (../shared/seeds/ERRATA.md) that the lessons teach."""

import numpy as np

import urkin
from urkin.course.seeds import (
    SEED002_ARM,
    SEED002_DH,
    SEED002_LENGTHS,
    SEED002_SHIFT,
    seed002_jacobian,
    seed002_position,
)
from urkin.kinematics import dh_chain, position_jacobian

D6 = SEED002_LENGTHS[5]


def seed002_published_position(q):
    return np.array(seed002_position(q))


def test_seed002_at_035_rad_on_every_joint():
    q = np.full(6, 0.35)
    np.testing.assert_allclose(
        dh_chain(SEED002_DH, q)[:3, 3] * 1000, [784.706, 87.586, 415.781], atol=5e-4
    )
    np.testing.assert_allclose(
        seed002_published_position(q) * 1000, [759.367, 78.336, 415.781], atol=5e-4
    )


def test_seed002_angles_are_ur_angles_shifted():
    Q = np.random.default_rng(2).uniform(-np.pi, np.pi, (50, 6))
    np.testing.assert_allclose(
        dh_chain(SEED002_DH, Q + SEED002_SHIFT), urkin.fk(SEED002_ARM, Q), atol=1e-12
    )


def test_seed002_jacobian_is_the_exact_derivative_of_its_position_with_ten_wrong_entries():
    rng, h = np.random.default_rng(4), 1e-6
    for q in rng.uniform(-np.pi, np.pi, (20, 6)):
        published = np.array(seed002_jacobian(q), dtype=float)
        p = seed002_published_position
        central = np.column_stack([(p(q + h * e) - p(q - h * e)) / (2 * h) for e in np.eye(6)])
        np.testing.assert_allclose(published, central, atol=1e-8)
        true = position_jacobian(SEED002_ARM, q - SEED002_SHIFT)
        assert np.count_nonzero(np.abs(published - true) > 1e-9) == 10


def test_seed002_functions_give_sympy_expressions():
    import sympy as sp

    q = sp.symbols("q1:7")
    p_x = seed002_position(q, cos=sp.cos, sin=sp.sin)[0]
    J = sp.Matrix(seed002_jacobian(q, cos=sp.cos, sin=sp.sin))
    assert sp.simplify(J[0, 4] - sp.diff(p_x, q[4])) == 0


def test_seed002_formula_error_reaches_two_d6_and_hides_where_c234_is_zero():
    rng = np.random.default_rng(3)
    Q = rng.uniform(-np.pi, np.pi, (4000, 6))
    errors = np.array(
        [np.linalg.norm(seed002_published_position(q) - dh_chain(SEED002_DH, q)[:3, 3]) for q in Q]
    )
    c234 = np.cos(Q[:, 1] + Q[:, 2] + Q[:, 3])
    np.testing.assert_allclose(errors, D6 * np.abs(c234) * (1 - np.sin(Q[:, 4])), atol=1e-12)
    assert 0.95 * 2 * D6 < errors.max() <= 2 * D6
    np.testing.assert_allclose(
        seed002_published_position(np.zeros(6))[:2] - dh_chain(SEED002_DH, np.zeros(6))[:3, 3][:2],
        [-D6, 0.0],
        atol=1e-12,
    )  # 82.5 mm at q = 0
