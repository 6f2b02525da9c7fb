"""Closed-form IK: correctness, inclusion, completeness, strictness and range, singular poses
included, for all seven arms; choosing the nearest solution."""

import warnings
import zlib

import numpy as np
import pytest

import urkin
from tests.reference import OFFICIAL_DH, dh_fk
from tests.singular_poses import FAMILIES, NEAR, near_family, on_family
from urkin.analytic_ik import ik_analytic, ik_closest
from urkin.kinematics import singularity_factors
from urkin.transforms import pose_error, wrap_angles

N_RANDOM = 10_000


def distance_mod_2pi(solutions, q):
    """Smallest max-joint difference, modulo 2π, between q and any of the solutions."""
    if len(solutions) == 0:
        return np.inf
    return np.abs(wrap_angles(solutions - q)).max(axis=-1).min()


@pytest.fixture(scope="module", params=urkin.ROBOTS)
def solved(request):
    """IK(FK(q)) for 10 000 random q per arm, batched."""
    arm = urkin.robot(request.param)
    Q = np.random.default_rng(31).uniform(-np.pi, np.pi, (N_RANDOM, 6))
    T = urkin.fk(arm, Q)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no NaN or overflow warnings
        solutions, mask = ik_analytic(arm, T, return_mask=True)
    return arm, Q, T, solutions, mask


def test_correctness_every_solution_reaches_the_pose(solved):
    arm, _, T, solutions, mask = solved
    reached = urkin.fk(arm, solutions[mask])
    targets = np.repeat(T, mask.sum(axis=1), axis=0)
    assert np.abs(reached - targets).max() < 1e-9
    # and by the independent DH product
    rows = np.flatnonzero(mask.ravel())[:200]
    for row in rows:
        np.testing.assert_allclose(
            dh_fk(OFFICIAL_DH[arm.name], solutions.reshape(-1, 6)[row]), T[row // 8], atol=1e-9
        )


def test_inclusion_the_generating_configuration_is_among_the_solutions(solved):
    _, Q, _, solutions, mask = solved
    gaps = np.abs(wrap_angles(solutions - Q[:, None, :])).max(axis=-1)
    gaps = np.where(mask, gaps, np.inf).min(axis=1)
    assert gaps.max() < 1e-9


def test_range_nan_rows_and_distinctness(solved):
    _, _, _, solutions, mask = solved
    real = solutions[mask]
    assert np.all((real > -np.pi) & (real <= np.pi))
    assert np.isnan(solutions[~mask]).all() and not np.isnan(real).any()
    counts = mask.sum(axis=1)
    assert set(np.unique(counts)) <= {2, 4, 6, 8}
    assert (counts == 8).mean() > 0.6  # generic poses: all eight branches
    for s, m in zip(solutions[:500], mask[:500]):
        pairwise = np.abs(wrap_angles(s[m][:, None] - s[m][None])).max(axis=-1)
        assert (pairwise + np.eye(m.sum()) * 10).min() > 1e-9


def test_consistency_single_and_batched_agree(solved):
    arm, _, T, solutions, mask = solved
    for i in range(0, N_RANDOM, 331):  # across the solver's blocks of poses
        single = ik_analytic(arm, T[i])
        np.testing.assert_allclose(single, solutions[i][mask[i]], atol=0)


@pytest.mark.parametrize("count", [2, 13, 14, 40])
def test_small_stacks_agree_with_single_calls(count):
    """A stack of a few poses (solved pose by pose) or more (in columns) gives each pose the
    rows one call gives it, NaN rows where the mask is False, singular poses included."""
    arm = urkin.robot("ur5")
    rng = np.random.default_rng(count)
    Q = rng.uniform(-np.pi, np.pi, (count, 6))
    Q[0, 4] = 0.0  # on the wrist singularity
    Q[1, 2] = np.pi  # elbow stretched
    T = urkin.fk(arm, Q)
    solutions, mask = ik_analytic(arm, T, return_mask=True)
    assert solutions.shape == (count, 8, 6) and mask.shape == (count, 8)
    assert np.isnan(solutions[~mask]).all() and not np.isnan(solutions[mask]).any()
    np.testing.assert_array_equal(ik_analytic(arm, T), solutions)
    assert mask.any(axis=1).all()
    for row in np.flatnonzero(mask.ravel()):  # each reaches its pose, by the independent product
        np.testing.assert_allclose(
            dh_fk(OFFICIAL_DH[arm.name], solutions.reshape(-1, 6)[row]), T[row // 8], atol=1e-9
        )
    for i in range(count):
        single = ik_analytic(arm, T[i])
        assert len(single) == mask[i].sum()
        np.testing.assert_allclose(single, solutions[i][mask[i]], atol=1e-12)


def test_completeness_numerical_search_finds_nothing_else():
    # many random starts of the numerical solver: every solution it finds is an analytic one
    ur5 = urkin.robot("ur5")
    Q = np.random.default_rng(5).uniform(-np.pi, np.pi, (40, 6))
    T = urkin.fk(ur5, Q)
    starts = np.random.default_rng(6).uniform(-np.pi, np.pi, (40, 6))
    numeric = urkin.ik(
        ur5, np.repeat(T, len(starts), axis=0), q0=np.tile(starts, (40, 1)), max_restarts=0
    )
    found = numeric.q[numeric.success].reshape(-1, 6)
    owners = np.repeat(np.arange(40), len(starts))[numeric.success]
    for i in range(40):
        analytic = ik_analytic(ur5, T[i])
        for q in found[owners == i]:
            # joint-space agreement is looser than pose agreement near singular configurations
            assert distance_mod_2pi(analytic, q) < 1e-5
        distinct = []  # cluster the numerical solutions (they agree to ~1e-8 in joint space)
        for q in found[owners == i]:
            if not distinct or distance_mod_2pi(np.array(distinct), q) > 1e-5:
                distinct.append(q)
        assert len(distinct) <= len(analytic)


def test_strictness_out_of_reach_poses_have_no_solutions():
    ur10e = urkin.robot("ur10e")
    T = urkin.fk(ur10e, np.random.default_rng(2).uniform(-np.pi, np.pi, (500, 6)))
    far = T.copy()
    far[:, 0, 3] += 3.0  # three metres further along x: beyond the arm's reach
    inside = T.copy()
    inside[:, :2, 3] = 0.0  # the flange on the base axis with the tool pointing sideways
    inside[:, :3, :3] = np.eye(3)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        solutions, mask = ik_analytic(ur10e, far, return_mask=True)
        assert not mask.any() and np.isnan(solutions).all()
        assert ik_analytic(ur10e, far[0]).shape == (0, 6)
        _, inside_mask = ik_analytic(ur10e, inside, return_mask=True)
    assert not inside_mask.any()


# ---------------------------------------------------------------------------- singular poses


@pytest.mark.parametrize("family", FAMILIES, ids=["+".join(f) for f in FAMILIES])
def test_exact_at_singular_poses(arm, family):
    rng = np.random.default_rng(zlib.crc32(f"{arm.name}{family}".encode()))
    Q = np.array([on_family(arm, family, rng) for _ in range(300)])
    flags = np.abs(singularity_factors(arm, Q)) < 1e-9
    for name, column in zip(("shoulder", "elbow", "wrist"), flags.T):
        assert column.all() == (name in family)
    T = urkin.fk(arm, Q)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        solutions, mask = ik_analytic(arm, T, return_mask=True)
    assert mask.any(axis=1).all()
    reached = urkin.fk(arm, solutions[mask])
    assert np.abs(reached - np.repeat(T, mask.sum(axis=1), axis=0)).max() < 1e-9
    # a double root (shoulder, elbow): rounding of 1e-16 in the pose moves the angles by its
    # square root, ~1e-8 rad, and the wrist angles by that over |sin θ5|; the poses are exact.
    # Both at once: the shoulder's 1e-8 rad moves the elbow's target by ~1e-9 m, and the folded
    # or stretched elbow turns that into ~1e-4 rad (the poses are still met to 1e-9, above)
    double_roots = len({"shoulder", "elbow"} & set(family))
    tol = (1e-9, 1e-5, 1e-2)[double_roots]
    for q, s, m in zip(Q, solutions, mask):
        s = s[m]
        if "wrist" in family:
            # a one-parameter family reaches the pose: q's family (its θ1 and θ5) is among the
            # solutions, and every solution reaches the pose (checked above)
            assert distance_mod_2pi(s[:, [0, 4]], q[[0, 4]]) < tol
        else:
            assert distance_mod_2pi(s, q) < tol


@pytest.mark.parametrize("family", FAMILIES, ids=["+".join(f) for f in FAMILIES])
def test_exact_near_singular_poses(arm, family):
    """Just off each singular family, at 1e-3 … 1e-12, every pose keeps solutions and each
    reaches it: to round-off, or within REACH_TOLERANCE where the shoulder's double root
    (rounding of ε in the pose moves its offset by √ε) meets the elbow's or the wrist's; and
    ik_closest finds one (no false "unreachable")."""
    from urkin.analytic_ik import REACH_TOLERANCE

    tol = REACH_TOLERANCE if "shoulder" in family and len(family) > 1 else 1e-12
    for distance in NEAR:
        rng = np.random.default_rng(zlib.crc32(f"{arm.name}{family}{distance}".encode()))
        Q = np.array([near_family(arm, family, distance, rng) for _ in range(100)])
        T = urkin.fk(arm, Q)
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            solutions, mask = ik_analytic(arm, T, return_mask=True)
        assert mask.any(axis=1).all(), f"a pose {distance:g} off lost every solution"
        reached = urkin.fk(arm, solutions[mask])
        assert np.abs(reached - np.repeat(T, mask.sum(axis=1), axis=0)).max() < tol
        for i in range(0, 100, 25):  # the one-pose path finds as many
            assert len(ik_analytic(arm, T[i])) == mask[i].sum()
        assert ik_closest(arm, T, Q).success.all()


def test_the_wrist_representatives_have_the_elbow_nearest_a_right_angle():
    # on a wrist-singular pose, θ234 moves joint 5 on a circle of radius d5 round the wrist
    # point; the planar reach ρ(θ234) sets cos θ3 = (ρ² − a2² − a3²) / (2 a2 a3)
    ur5 = urkin.robot("ur5")
    d1, a2, a3, _, d5, d6 = OFFICIAL_DH["UR5"]
    rng = np.random.default_rng(12)
    sweep = np.linspace(-np.pi, np.pi, 20001)
    for _ in range(40):
        q = on_family(ur5, ("wrist",), rng)
        T = urkin.fk(ur5, q)
        wrist_point = T[:3, 3] - d6 * T[:3, 2]
        representatives = [s for s in ik_analytic(ur5, T) if abs(np.sin(s[4])) < 1e-12]
        assert len(representatives) >= 2
        for rep in representatives:
            X = wrist_point[0] * np.cos(rep[0]) + wrist_point[1] * np.sin(rep[0])
            Y = wrist_point[2] - d1
            rho2 = (X - d5 * np.sin(sweep)) ** 2 + (Y + d5 * np.cos(sweep)) ** 2
            cos3 = (rho2 - a2**2 - a3**2) / (2 * a2 * a3)
            best = np.abs(cos3[np.abs(cos3) <= 1]).min()
            assert abs(np.cos(rep[2])) <= best + 1e-6


# ---------------------------------------------------------------------------- ik_closest


def test_closest_solution_follows_the_current_configuration():
    ur5 = urkin.robot("ur5")
    rng = np.random.default_rng(8)
    Q = rng.uniform(-2 * np.pi + 0.1, 2 * np.pi - 0.1, (200, 6))  # beyond ±π, within ±2π
    result = ik_closest(ur5, urkin.fk(ur5, Q), Q + rng.normal(0, 0.01, Q.shape))
    assert result.success.all()
    np.testing.assert_allclose(result.q, Q, atol=1e-9)  # the same branch and the same turn
    lower, upper = -2 * np.pi, 2 * np.pi
    assert np.all((result.q >= lower) & (result.q <= upper))


def test_closest_is_the_nearest_2pi_equivalent_within_the_limits():
    ur5 = urkin.robot("ur5")
    rng = np.random.default_rng(9)
    shifts = np.array(np.meshgrid(*[[-2 * np.pi, 0, 2 * np.pi]] * 6)).reshape(6, -1).T
    for _ in range(30):
        q = rng.uniform(-np.pi, np.pi, 6)
        current = rng.uniform(-2 * np.pi, 2 * np.pi, 6)
        T = urkin.fk(ur5, q)
        result = ik_closest(ur5, T, current)
        # brute force: every solution, every combination of whole turns, inside ±2π
        candidates = (ik_analytic(ur5, T)[:, None, :] + shifts[None]).reshape(-1, 6)
        inside = candidates[np.all(np.abs(candidates) <= 2 * np.pi, axis=1)]
        nearest = np.linalg.norm(inside - current, axis=1).min()
        assert result.success
        assert np.linalg.norm(result.q - current) == pytest.approx(nearest, abs=1e-9)
        assert np.all(np.abs(result.q) <= 2 * np.pi)


@pytest.mark.parametrize("name", ["ur3", "ur5", "ur5e", "ur10e"])
@pytest.mark.parametrize("q5", [0.0, 1e-14, np.pi, -np.pi + 1e-14])
def test_closest_at_the_wrist_singularity_is_the_member_nearest_the_current(name, q5):
    """With sin θ5 = 0 a one-parameter family reaches the pose and ik_analytic returns two
    representatives per shoulder; ik_closest must still return the member nearest the current
    configuration: the current one itself when it is exact, one nearby when it is a hair off
    (not a representative with joints 4 and 6 turned by radians)."""
    arm = urkin.robot(name)
    rng = np.random.default_rng(12)
    Q = rng.uniform(-np.pi, np.pi, (40, 6))
    Q[:, 2] = rng.choice([-1, 1], 40) * rng.uniform(0.3, 2.5, 40)  # an elbow well bent
    Q[:, 4] = q5
    T = urkin.fk(arm, Q)
    for rows in (slice(0, 1), slice(0, 3), slice(None)):  # one pose, a few, a stack
        exact = ik_closest(arm, T[rows], Q[rows])
        assert np.all(exact.success)
        assert np.abs(wrap_angles(exact.q - Q[rows])).max() < 1e-9
        near = ik_closest(arm, T[rows], Q[rows] + 1e-3)
        assert np.all(near.success)
        assert np.linalg.norm(wrap_angles(near.q - Q[rows]), axis=-1).max() < 0.02
        position, angle = pose_error(urkin.fk(arm, near.q), T[rows])
        assert position.max() < 1e-9 and angle.max() < 1e-9


def test_closest_reports_unreachable_poses():
    ur3 = urkin.robot("ur3")
    far = np.eye(4)
    far[:3, 3] = [2.0, 0.0, 0.3]
    result = ik_closest(ur3, far, np.zeros(6))
    assert not result.success and "1.4031 m beyond the UR3" in result.reason
    assert np.isfinite(result.q).all()


def test_a_pose_not_quite_rigid_is_solved_as_its_nearest_rotation():
    """check_transform accepts rotations 1e-6 from orthonormal; no configuration reaches such
    a matrix, so the solutions are those of its nearest rotation, exactly (one pose or a
    stack), and ik_closest says how far the target is from a rotation when that is beyond
    its tolerance."""
    ur5 = urkin.robot("ur5")
    q = np.array([0.3, -1.2, 1.4, -0.6, 1.1, 0.2])
    T = urkin.fk(ur5, q)
    scaled = T.copy()
    scaled[:3, :3] *= 1 + 1e-7  # its nearest rotation is T's
    for solutions in (ik_analytic(ur5, scaled), ik_analytic(ur5, scaled[None])[0]):
        assert len(solutions) == 8
        assert np.abs(urkin.fk(ur5, solutions) - T).max() < 1e-12
    result = ik_closest(ur5, scaled, q)
    assert not result.success and "from the nearest rotation matrix" in result.reason
    assert ik_closest(ur5, np.round(T, 9), q).success  # 9 decimals: within tol = 1e-9


def test_return_mask_gives_a_pair_for_one_pose_too():
    ur5 = urkin.robot("ur5")
    T = urkin.fk(ur5, [0.3, -1.2, 1.4, -0.6, 1.1, 0.2])
    q, mask = ik_analytic(ur5, T, return_mask=True)
    assert q.shape == (8, 6) and mask.shape == (8,) and mask.all()
    far = T.copy()
    far[:3, 3] = [5.0, 0.0, 0.0]
    q, mask = ik_analytic(ur5, far, return_mask=True)
    assert q.shape == (0, 6) and mask.shape == (0,)
