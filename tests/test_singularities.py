"""The UR singular families, manipulability and the singularity classifier."""

import itertools

import numpy as np
import pytest

import urkin
from tests.reference import OFFICIAL_DH, complex_step_jacobian
from urkin.kinematics import (
    condition_number,
    manipulability,
    singular_families,
    singularities,
    singularity_factors,
)

FAMILIES = ("shoulder", "elbow", "wrist")


def test_determinant_factors_as_the_errata_state(arm, rng):
    # det J = a2 a3 s3 s5 (a2 c2 + a3 c23 + d5 s234), against a complex-step Jacobian
    for q in rng.uniform(-np.pi, np.pi, (30, 6)):
        det = np.linalg.det(complex_step_jacobian(OFFICIAL_DH[arm.name], q))
        shoulder, elbow, wrist = singularity_factors(arm, q)
        assert det == pytest.approx(arm.a2 * arm.a3 * elbow * wrist * shoulder, abs=1e-14)


def singular_configuration(arm, families, rng):
    """A random configuration on the given singular families (and, generically, no others)."""
    while True:
        q = rng.uniform(-np.pi, np.pi, 6)
        if "elbow" in families:
            q[2] = rng.choice([0.0, np.pi])
        if "wrist" in families:
            q[4] = rng.choice([0.0, np.pi])
        if "shoulder" in families:
            reach = arm.a2 * np.cos(q[1]) + arm.a3 * np.cos(q[1] + q[2])
            if abs(reach) > arm.d5:
                continue
            q234 = np.arcsin(-reach / arm.d5)
            if rng.random() < 0.5:
                q234 = np.pi - q234
            q[3] = q234 - q[1] - q[2]
        others = [f for f in FAMILIES if f not in families]
        factors = dict(zip(FAMILIES, np.abs(singularity_factors(arm, q))))
        if all(factors[f] > 1e-3 for f in others):
            return q


CASES = [c for k in (1, 2, 3) for c in itertools.combinations(FAMILIES, k)]


@pytest.mark.parametrize("families", CASES, ids=["+".join(c) for c in CASES])
def test_classifier_names_each_family_and_intersection(arm, families, rng):
    for _ in range(25):
        q = singular_configuration(arm, families, rng)
        assert singularities(arm, q) == families
        sigma_min = np.linalg.svd(urkin.jacobian(arm, q), compute_uv=False)[-1]
        assert sigma_min < 1e-12
        assert manipulability(arm, q) < 1e-12


def test_regular_configurations_are_not_flagged(arm, rng):
    Q = rng.uniform(-np.pi, np.pi, (2000, 6))
    flags = singular_families(arm, Q)
    sigma_min = np.linalg.svd(urkin.jacobian(arm, Q), compute_uv=False)[:, -1]
    assert not flags[sigma_min > 1e-6].any()


def test_never_flags_a_configuration_with_sigma_min_above_1e_6(arm, rng):
    # walk away from singular configurations by steps from 1e-14 to 1e-2 rad
    Q = []
    for families in CASES:
        for _ in range(20):
            q = singular_configuration(arm, families, rng)
            for scale in np.logspace(-14, -2, 13):
                Q.append(q + scale * rng.normal(size=6))
    Q = np.array(Q)
    flags = singular_families(arm, Q).any(axis=1)
    sigma_min = np.linalg.svd(urkin.jacobian(arm, Q), compute_uv=False)[:, -1]
    assert not (flags & (sigma_min > 1e-6)).any()
    assert flags.sum() > 0.2 * len(Q)  # and it does flag the ones close enough


def test_batched_classifier_and_measures():
    ur5 = urkin.robot("ur5")
    Q = np.array([[0, -np.pi / 2, 0, -np.pi / 2, 0, 0], [0.1, -1.0, 1.2, -0.3, 0.5, 0.7]])
    assert singularities(ur5, Q) == [("shoulder", "elbow", "wrist"), ()]
    J = urkin.jacobian(ur5, Q)
    np.testing.assert_allclose(manipulability(ur5, Q), np.abs(np.linalg.det(J)))
    w_position = manipulability(ur5, Q, part="position")
    Jv = J[:, :3]
    np.testing.assert_allclose(
        w_position, np.sqrt(np.abs(np.linalg.det(Jv @ Jv.transpose(0, 2, 1))))
    )
    cond = condition_number(ur5, Q)
    assert cond[0] > 1e15 and 1 < cond[1] < 100
    with pytest.raises(ValueError, match="part"):
        manipulability(ur5, Q, part="angular")
