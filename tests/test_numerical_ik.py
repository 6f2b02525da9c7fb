"""Numerical IK: verified success, reproducibility, failures that say why, and the blind spot."""

import itertools
import zlib

import numpy as np
import pytest

import urkin
from tests.reference import OFFICIAL_DH, dh_fk
from tests.singular_poses import FAMILIES, NEAR, near_family
from urkin.numerical_ik import IK_METHODS, orientation_error
from urkin.transforms import make_transform, rot_x, rot_z, rpy_to_rotation

HOME = np.array([0.0, -np.pi / 2, 0.0, -np.pi / 2, 0.0, 0.0])


def pose_error(lengths, q, T_target):
    """Position (m) and rotation angle (rad) between the reference FK of q and a target."""
    T = dh_fk(lengths, q)
    frob = np.linalg.norm(T[:3, :3] - T_target[:3, :3])
    return np.linalg.norm(T[:3, 3] - T_target[:3, 3]), 2 * np.arcsin(min(frob / np.sqrt(8), 1))


@pytest.mark.parametrize("name", ["UR5", "UR3"])
def test_default_method_from_zeros_succeeds_on_random_reachable_poses(name):
    arm = urkin.robot(name)
    Q = np.random.default_rng(2026).uniform(-np.pi, np.pi, (1000, 6))
    targets = np.array([dh_fk(OFFICIAL_DH[name], q) for q in Q])
    result = urkin.ik(arm, targets, q0=np.zeros(6))
    verified = np.array(
        [max(pose_error(OFFICIAL_DH[name], q, T)) < 1e-9 for q, T in zip(result.q, targets)]
    )
    assert verified.mean() >= 0.999
    # success is claimed only where the pose error really is within tolerance
    assert not np.any(result.success & ~verified)


def test_a_seed_reproduces_the_result_exactly():
    ur5 = urkin.robot("ur5")
    targets = urkin.fk(ur5, np.random.default_rng(5).uniform(-np.pi, np.pi, (50, 6)))
    first, again = urkin.ik(ur5, targets, seed=7), urkin.ik(ur5, targets, seed=7)
    np.testing.assert_array_equal(first.q, again.q)
    np.testing.assert_array_equal(first.iterations, again.iterations)
    single, single_again = urkin.ik(ur5, targets[3], seed=7), urkin.ik(ur5, targets[3], seed=7)
    np.testing.assert_array_equal(single.q, single_again.q)


@pytest.mark.parametrize("method", IK_METHODS)
def test_every_method_converges_and_never_overclaims(method):
    ur10 = urkin.robot("ur10")
    Q = np.random.default_rng(11).uniform(-np.pi, np.pi, (200, 6))
    targets = urkin.fk(ur10, Q)
    result = urkin.ik(ur10, targets, method=method)
    assert result.success.mean() >= (0.95 if method == "dls" else 0.995)
    for q, T, ok in zip(result.q, targets, result.success):
        assert ok == (max(pose_error(OFFICIAL_DH["UR10"], q, T)) <= 1e-10 * 1.0000001)


def test_single_and_batched_solves_agree_on_what_they_claim():
    ur5 = urkin.robot("ur5")
    targets = urkin.fk(ur5, np.random.default_rng(3).uniform(-np.pi, np.pi, (20, 6)))
    batch = urkin.ik(ur5, targets)
    for i, T in enumerate(targets):
        one = urkin.ik(ur5, T)
        assert one.success and batch[i].success
        assert isinstance(one.q, np.ndarray) and one.q.shape == (6,)
        assert max(pose_error(OFFICIAL_DH["UR5"], one.q, T)) < 1e-9


def test_position_only_targets():
    ur3 = urkin.robot("ur3")
    points = urkin.fk(ur3, np.random.default_rng(4).uniform(-np.pi, np.pi, (100, 6)))[:, :3, 3]
    result = urkin.ik(ur3, points, method="nr")
    assert result.success.all()
    reached = np.array([dh_fk(OFFICIAL_DH["UR3"], q)[:3, 3] for q in result.q])
    np.testing.assert_allclose(reached, points, atol=1e-9)
    np.testing.assert_array_equal(result.orientation_error, 0.0)


def test_unreachable_positions_fail_fast_with_the_distance():
    ur5 = urkin.robot("ur5")
    d1, a2, a3, d4, d5, d6 = OFFICIAL_DH["UR5"]
    target = np.array([1.5, 0.5, 0.3])
    reach = abs(a2) + abs(a3) + np.hypot(d4, d5) + d6
    beyond = np.linalg.norm(target - [0, 0, d1]) - reach
    result = urkin.ik(ur5, target, q0=HOME)
    assert not result.success and result.iterations == 0
    assert f"{beyond:.4f} m beyond" in result.reason
    np.testing.assert_array_equal(result.q, HOME)  # the guess, flagged as a failure


def test_unreachable_poses_fail_fast():
    ur5 = urkin.robot("ur5")
    far = make_transform(rot_x(np.pi), [1.2, 0.4, 0.3])
    inside = make_transform(np.eye(3), [0.02, 0.01, 0.4])  # wrist point within d4 of the axis
    result = urkin.ik(ur5, np.array([far, inside]))
    assert not result.success.any()
    assert "beyond the UR5's reach" in result.reason[0]
    assert "closer than the UR5's shoulder offset" in result.reason[1]
    assert np.isfinite(result.q).all()


@pytest.mark.parametrize("method", IK_METHODS)
def test_singular_and_hard_targets_fail_cleanly_or_succeed_honestly(method):
    ur5 = urkin.robot("ur5")
    hard = [
        urkin.fk(ur5, HOME),  # shoulder, elbow and wrist singular at once
        urkin.fk(ur5, [0.3, -np.pi / 2, 0.0, 0.4, 1.0, 0.2]),  # arm stretched out
        urkin.fk(ur5, [0.3, -1.0, 1.2, 0.4, 0.0, 0.2]),  # wrist singular
    ]
    not_quite = urkin.fk(ur5, HOME)
    not_quite[:3, :3] = np.eye(3)  # passes the reach test but no configuration reaches it
    targets = np.array([*hard, not_quite])
    result = urkin.ik(ur5, targets, method=method, max_restarts=3)
    assert np.isfinite(result.q).all() and np.isfinite(result.residual).all()
    for q, T, ok, reason in zip(result.q, targets, result.success, result.reason):
        assert ok == (max(pose_error(OFFICIAL_DH["UR5"], q, T)) <= 1e-10 * 1.0000001)
        assert reason == "converged" if ok else reason.startswith("did not converge")
    assert not result.success[-1]


@pytest.mark.parametrize("family", FAMILIES, ids=["+".join(f) for f in FAMILIES])
def test_targets_near_singular_families_are_solved(family):
    """At 1e-3 … 1e-12 off each singular family.  Near the shoulder's, every solution of the
    pose is nearly singular: the error left along the Jacobian's weakest direction falls only
    through second-order terms, and damped steps stalled 5e-7 m short, attempt after attempt,
    until the core stepped along that direction."""
    ur5 = urkin.robot("ur5")
    for distance in NEAR:
        rng = np.random.default_rng(zlib.crc32(f"{family}{distance}".encode()))
        Q = np.array([near_family(ur5, family, distance, rng) for _ in range(20)])
        targets = np.array([dh_fk(OFFICIAL_DH["UR5"], q) for q in Q])
        batch = urkin.ik(ur5, targets)
        singles = [urkin.ik(ur5, T) for T in targets[:4]]
        for result, T in [*zip(batch, targets), *zip(singles, targets)]:
            assert result.success, f"{distance:g} off: {result.reason}"
            assert max(pose_error(OFFICIAL_DH["UR5"], result.q, T)) <= 1e-10 * 1.0000001


def test_a_stall_near_a_singular_solution_ends_in_a_step_not_a_restart():
    """The wrist point 6e-5 m off the shoulder singularity: from 0.05 rad away the damped steps
    stall 5e-7 m short.  With restarts allowed the core steps along the weakest direction and
    arrives without one; with max_restarts=0 the rule runs alone and the failure says how far
    it got."""
    ur5 = urkin.robot("ur5")
    q = np.array([1.3051131120389492, 0.32859834696325496, 2.1434857807772936,
                  -0.9244280494519286, 3.082802010297441, -2.044079749274399])  # fmt: skip
    assert abs(urkin.kinematics.singularity_factors(ur5, q)[0]) < 1e-4
    T = dh_fk(OFFICIAL_DH["UR5"], q)
    alone = urkin.ik(ur5, T, q + 0.05, max_restarts=0)
    assert not alone.success and 1e-7 < alone.residual < 1e-6
    assert alone.reason.startswith("did not converge: after 0 restarts")
    helped = urkin.ik(ur5, T, q + 0.05, max_restarts=1)
    assert helped.success and helped.restarts == 0
    assert max(pose_error(OFFICIAL_DH["UR5"], helped.q, T)) <= 1e-10 * 1.0000001


def test_the_cross_product_error_is_blind_at_180_degrees():
    R = rpy_to_rotation([0.3, -0.4, 1.1])
    k = np.array([2.0, -1.0, 2.0]) / 3.0
    for angle in (0.1, 1.0, 2.5):
        turned = make_transform(np.eye(3))[:3, :3]
        W = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
        turned = (np.eye(3) + np.sin(angle) * W + (1 - np.cos(angle)) * W @ W) @ R
        np.testing.assert_allclose(orientation_error(R, turned), angle * k, atol=1e-12)
        np.testing.assert_allclose(
            orientation_error(R, turned, "cross"), np.sin(angle) * k, atol=1e-12
        )
    half_turn = rot_z(np.pi) @ R
    np.testing.assert_allclose(orientation_error(R, half_turn, "cross"), 0.0, atol=1e-15)
    assert np.linalg.norm(orientation_error(R, half_turn)) == pytest.approx(np.pi)


def test_the_blind_spot_stalls_newton_raphson_where_the_log_error_does_not():
    ur5 = urkin.robot("ur5")
    start = np.array([0.4, -1.3, 1.1, -0.9, 1.2, 0.3])
    target = urkin.fk(ur5, start + np.array([0, 0, 0, 0, 0, np.pi]))  # same point, half a turn
    blind = urkin.ik(ur5, target, q0=start, method="nr", orientation="cross", max_restarts=0)
    seeing = urkin.ik(ur5, target, q0=start, method="nr", orientation="log", max_restarts=0)
    assert not blind.success and blind.orientation_error == pytest.approx(np.pi)
    assert "3.14e+00 rad" in blind.reason
    assert seeing.success


def test_tool_and_base_are_honoured():
    T_world_base = make_transform(rpy_to_rotation([0.0, 0.1, 0.5]), [0.4, -0.2, 0.05])
    T_flange_tool = make_transform(rot_x(0.2), [0.0, 0.03, 0.15])
    arm = urkin.robot("ur5e").with_base(T_world_base).with_tool(T_flange_tool)
    Q = np.random.default_rng(8).uniform(-np.pi, np.pi, (30, 6))
    targets = urkin.fk(arm, Q)
    poses = urkin.ik(arm, targets)
    assert poses.success.all()
    np.testing.assert_allclose(urkin.fk(arm, poses.q), targets, atol=1e-9)
    points = urkin.ik(arm, targets[:, :3, 3])
    assert points.success.all()
    np.testing.assert_allclose(urkin.fk(arm, points.q)[:, :3, 3], targets[:, :3, 3], atol=1e-9)


@pytest.mark.parametrize(
    ("kwargs", "error", "message"),
    [
        ({"target": np.zeros((2, 2))}, ValueError, "target must be a pose"),
        ({"target": np.diag([1.0, 1.0, -1.0, 1.0])}, ValueError, "reflection"),
        ({"target": [np.nan, 0, 0]}, ValueError, "NaN"),
        ({"target": np.eye(4), "method": "newton"}, ValueError, "method must be one of"),
        ({"target": np.eye(4), "orientation": "quat"}, ValueError, "orientation"),
        (
            {"target": np.tile(np.eye(4), (3, 1, 1)), "q0": np.zeros((2, 6))},
            ValueError,
            "2 configurations for 3 targets",
        ),
        ({"target": [0.3, 0.1, 0.2], "method": "poe"}, ValueError, "full poses"),
        ({"target": np.eye(4), "q0": np.full(6, 90.0)}, ValueError, "degrees"),
        (
            {"target": np.eye(4), "method": urkin.numerical_ik.LevenbergMarquardt},
            TypeError,
            r"not the class: pass LevenbergMarquardt\(\)",
        ),
    ],
)
def test_bad_input_names_the_problem(kwargs, error, message):
    with pytest.raises(error, match=message):
        urkin.ik(urkin.robot("ur5"), **kwargs)


@pytest.mark.parametrize("guess_shape", [(6,), (1, 6), (1, 1, 6)])
@pytest.mark.parametrize("target_lead", [(), (1,), (3,)])
def test_one_guess_of_any_stack_shape_serves_every_target(guess_shape, target_lead):
    """q0 holding one configuration, as (6,) or a stack of one, is the guess of every target;
    the result keeps the targets' leading axes."""
    ur5 = urkin.robot("ur5")
    Q = np.random.default_rng(4).uniform(-2.5, 2.5, (*target_lead, 6))
    guess = np.full(guess_shape, 0.1)
    result = urkin.ik(ur5, urkin.fk(ur5, Q), q0=guess)
    assert result.q.shape == (*target_lead, 6)
    assert np.all(result.success)
    np.testing.assert_allclose(urkin.fk(ur5, result.q), urkin.fk(ur5, Q), atol=1e-9)


def test_results_index_and_print():
    ur5 = urkin.robot("ur5")
    targets = urkin.fk(ur5, np.random.default_rng(9).uniform(-np.pi, np.pi, (3, 6)))
    batch = urkin.ik(ur5, targets)
    assert len(batch) == 3 and batch[1].success is True
    assert "3 succeeded" in repr(batch)
    assert "success=True" in repr(batch[0])
    with pytest.raises(TypeError):
        len(batch[0])


def test_a_custom_step_rule_runs_on_the_single_and_the_stacked_path():
    """A rule written against the StepRule API alone (step and accept, no single-path
    methods): its accept is asked on both paths, and its rejections are honoured."""
    from urkin.numerical_ik import StepRule

    class CautiousNewton(StepRule):
        name = "cautious"

        def __init__(self):
            self.asked = 0

        def step(self, problem, rows, T, J, e):
            return (
                np.linalg.lstsq(J, e, rcond=None)[0]
                if J.ndim == 2
                else np.stack([np.linalg.lstsq(j, v, rcond=None)[0] for j, v in zip(J, e)])
            )

        def accept(self, rows, e, e_trial, J, dq):
            self.asked += 1
            better = np.sum(e_trial * e_trial, axis=-1) < np.sum(e * e, axis=-1)
            return better

    ur5 = urkin.robot("ur5")
    targets = urkin.fk(ur5, np.random.default_rng(8).uniform(-np.pi, np.pi, (40, 6)))
    rule = CautiousNewton()
    single = urkin.ik(ur5, targets[0], method=rule)
    assert rule.asked > 0 and single.success
    stacked = urkin.ik(ur5, targets, method=rule)
    assert stacked.success.mean() >= 0.9
    position = np.linalg.norm(urkin.fk(ur5, stacked.q)[:, :3, 3] - targets[:, :3, 3], axis=1)
    assert position[stacked.success].max() <= 1e-10


def test_lm_damping_falls_with_the_error_so_the_end_is_quadratic(monkeypatch):
    """After a good step μ is at most 10·|e|² (Yamashita–Fukushima), never below the floor
    that keeps JᵀJ + μI solvable at a singular solution; from a start 0.05 rad off a regular
    solution the error then falls faster than quadratically's square root each step."""
    from urkin import numerical_ik as nik

    rule = nik.LevenbergMarquardt()
    rule.start(1)
    J = np.eye(6)
    e = np.full(6, 1e-3)
    rule.mu_one = 1.0
    dq = rule.step(None, 0, None, J, e)
    assert rule.accept_one(e, 0.01 * e, J, dq, float(e @ e), float(1e-4 * e @ e))
    assert rule.mu_one == pytest.approx(10 * 1e-4 * float(e @ e))
    rule.mu_one = 1.0
    dq = rule.step(None, 0, None, J, e)
    assert rule.accept_one(e, 0 * e, J, dq, float(e @ e), 0.0)
    assert rule.mu_one == nik._MU_FLOOR

    ur5 = urkin.robot("ur5")
    q = np.array([0.3, -1.2, 1.4, -0.6, 1.1, 0.2])
    residuals = []
    evaluate_one = nik._Problem.evaluate_one

    def spy(self, *args):
        out = evaluate_one(self, *args)
        residuals.append(max(out[2], out[3]))
        return out

    monkeypatch.setattr(nik._Problem, "evaluate_one", spy)
    result = urkin.ik(ur5, urkin.fk(ur5, q), q0=q + 0.05)
    assert result.success
    tail = [r for r in residuals if 1e-12 < r < 1e-2]
    assert len(tail) >= 2
    assert all(b < a**1.5 for a, b in itertools.pairwise(tail)), tail


def test_a_stationary_point_is_told_from_a_solution_on_the_way():
    """|Jᵀe| < 0.01·|J|_F·|e| marks an error the joints cannot reduce (a local minimum), one
    target or a stack alike; an error in the Jacobian's range is not one."""
    from urkin.numerical_ik import _stationary

    rng = np.random.default_rng(5)
    J = rng.normal(size=(6, 6))
    J[:, 5] = J[:, 4]  # rank 5: one direction of the task space out of reach
    u = np.linalg.svd(J)[0][:, -1]  # orthogonal to the range of J
    reachable = J @ rng.normal(size=6)
    for e, expected in [(u, True), (reachable, False), (u + 0.1 * reachable, False)]:
        assert _stationary(J, e, float(e @ e)) is expected
    E = np.array([u, reachable])
    stacked = _stationary(np.array([J, J]), E, np.sum(E * E, axis=1))
    assert stacked.tolist() == [True, False]


def test_local_minima_restart_without_waiting_out_the_patience(monkeypatch):
    """With restarts left, an attempt caught in a local minimum (the error above 1 mm, not
    falling, orthogonal to the Jacobian's range) restarts at once: on 300 random targets the
    stacked and the single paths both solve every one, with fewer iterations than the
    patience rule alone takes (the test raised to never)."""
    from urkin import numerical_ik as nik

    ur5 = urkin.robot("ur5")
    targets = urkin.fk(ur5, np.random.default_rng(11).uniform(-np.pi, np.pi, (300, 6)))
    with_test = urkin.ik(ur5, targets)
    single = [urkin.ik(ur5, T) for T in targets[:60]]
    monkeypatch.setattr(nik, "_STATIONARY", 0.0)  # the test off: |Jᵀe|² < 0 never holds
    without = urkin.ik(ur5, targets)
    assert with_test.success.all() and without.success.all()
    assert all(r.success for r in single)
    assert with_test.iterations.sum() < without.iterations.sum()


def test_one_rows_errors_match_the_stacked_evaluation():
    """The singular steps of a single solve measure errors with the one-pose code: the same
    errors as the stacked evaluation, to round-off."""
    from urkin import numerical_ik as nik

    ur5 = urkin.robot("ur5")
    T = urkin.fk(ur5, np.array([0.3, -1.2, 1.4, -0.6, 1.1, 0.2]))
    problem = nik._Problem(ur5, T[None, :3, 3], T[None, :3, :3], "log", 1e-10, 1e-10)
    Q = np.array([[0.2, -1.0, 1.3, -0.4, 1.0, 0.5]])
    rows = np.zeros(1, dtype=np.intp)
    np.testing.assert_allclose(
        problem.errors(Q, rows), problem.evaluate(Q, rows)[1], rtol=0, atol=1e-14
    )


@pytest.mark.parametrize("offset", [[0, 0, 0.15], [0.1, -0.05, 0.2]])
def test_a_tool_converges_on_the_tools_own_error_near_singular_poses(offset):
    # the solver iterates on the flange; the tool point misses by up to the flange's miss plus
    # |offset| × the rotation error, so the convergence test must bound that sum (else the
    # flange converges, the tool misses 1e-10 by a hair and no restart is tried)
    arm = urkin.robot("UR5").with_tool(make_transform(rot_x(0.3), offset))
    rng = np.random.default_rng(17)
    Q = rng.uniform(-3, 3, (120, 6))
    Q[:, 2] = rng.choice([1e-6, -1e-6, 1e-3], len(Q))  # near the elbow singularity
    Q[:60, 4] = 1e-6  # and the wrist's
    T = urkin.fk(arm, Q)
    single = [urkin.ik(arm, t) for t in T]
    assert all(r.success for r in single), [r.reason for r in single if not r.success][:2]
    assert max(r.position_error for r in single) <= 1e-10
    assert urkin.ik(arm, T).success.all()


@pytest.mark.parametrize("damping", [1e-160, 5e-324, 1e-154])
def test_dls_refuses_a_damping_whose_square_underflows(damping):
    T = urkin.fk(urkin.robot("ur5"), [0.1, -1.2, 1.1, -0.5, 0.7, 0.3])
    with pytest.raises(ValueError, match=r"damping must be 0 .* underflows"):
        urkin.ik(urkin.robot("ur5"), T, method="dls", damping=damping)
    assert urkin.ik(urkin.robot("ur5"), T, method="dls", damping=1.5e-154).success


@pytest.mark.parametrize("keyword", ["tol_position", "tol_orientation", "damping"])
def test_an_integer_too_large_for_a_float_is_refused_by_name(keyword):
    T = urkin.fk(urkin.robot("ur5"), [0.1, -1.2, 1.1, -0.5, 0.7, 0.3])
    with pytest.raises(ValueError, match=rf"{keyword} must be .*a huge integer"):
        urkin.ik(urkin.robot("ur5"), T, method="dls", **{keyword: 10**400})
