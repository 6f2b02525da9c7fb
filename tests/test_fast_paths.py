"""The scalar fast paths give what the stacked code gives, and refuse what it refuses.

A single pose or configuration takes a path written on Python floats (DESIGN §2); these tests
hold each one to the stacked path of the same function, on random input, near the singular
families, and on input that must be refused with the same message.
"""

from __future__ import annotations

import numpy as np
import pytest

import urkin
from urkin import numerical_ik
from urkin.numerical_ik import _rotation_parts_one
from urkin.robots import random_configurations
from urkin.transforms import (
    check_rotation,
    check_transform,
    pose_error,
    random_transforms,
    rotation_parts,
    so3_exp,
    wrap_angles,
)

ARMS = [urkin.robot(name) for name in urkin.ROBOTS]


def _configurations(rng: np.random.Generator, n: int) -> np.ndarray:
    """Random configurations, a third of them pushed to within 1e-3 … 1e-12 of a wrist,
    elbow or shoulder-adjacent singularity."""
    q = rng.uniform(-np.pi, np.pi, (n, 6))
    near = 10.0 ** rng.uniform(-12, -3, n) * rng.choice([-1.0, 1.0], n)
    third = n // 3
    q[:third, 4] = rng.choice([0.0, np.pi], third) + near[:third]  # wrist
    q[third : 2 * third, 2] = rng.choice([0.0, np.pi], third) + near[third : 2 * third]  # elbow
    return q


@pytest.mark.parametrize("arm", ARMS, ids=lambda arm: arm.name)
def test_one_pose_of_ik_analytic_is_the_stack_of_one(arm):
    rng = np.random.default_rng(11)
    poses = urkin.fk(arm, _configurations(rng, 300))
    stacked, mask = urkin.ik_analytic(arm, poses, return_mask=True)
    for T, rows, keep in zip(poses, stacked, mask):
        single = urkin.ik_analytic(arm, T)
        assert len(single) == keep.sum()
        if len(single):
            gap = np.abs(wrap_angles(single[:, None, :] - rows[keep][None, :, :])).max(axis=-1)
            # every single-pose solution is a stacked one and vice versa (modulo 2π); near a
            # double root the two roundings of √(small) may differ by ~1e-8 rad, both exact
            assert gap.min(axis=1).max() < 1e-6 and gap.min(axis=0).max() < 1e-6
            reached = urkin.fk(arm, single)
            position, angle = pose_error(reached, np.broadcast_to(T, reached.shape))
            assert position.max() < 1e-12 and angle.max() < 1e-12


@pytest.mark.parametrize("arm", ARMS[:2], ids=lambda arm: arm.name)
def test_one_configuration_of_fk_and_jacobian_is_the_stack_of_one(arm):
    q = _configurations(np.random.default_rng(12), 200)
    np.testing.assert_allclose(
        np.array([urkin.fk(arm, x) for x in q]), urkin.fk(arm, q), rtol=0, atol=1e-15
    )
    np.testing.assert_allclose(
        np.array([urkin.jacobian(arm, x) for x in q]), urkin.jacobian(arm, q), rtol=0, atol=1e-15
    )


@pytest.mark.parametrize(
    "bad, message",
    [
        (np.array([0.1, 0.2, np.nan, 0.0, 0.0, 0.0]), "q contains NaN or infinity"),
        (np.array([0.1, 0.2, np.inf, 0.0, 0.0, 0.0]), "q contains NaN or infinity"),
        (np.array([0.1, 0.2, 30.0, 0.0, 0.0, 0.0]), "q has an angle of 30 rad"),
    ],
)
def test_the_fast_path_refuses_what_the_stack_refuses(bad, message):
    for function in (urkin.fk, urkin.jacobian, urkin.position_jacobian, urkin.fk_frames):
        for q in (bad, bad[None]):
            with pytest.raises(ValueError, match=message):
                function(urkin.robot("ur5"), q)


def test_check_transform_and_check_rotation_refuse_one_pose_as_they_refuse_a_stack():
    T = random_transforms(seed=3)
    shear = T.copy()
    shear[0, 1] += 1e-3
    reflection = T.copy()
    reflection[:3, 2] *= -1.0
    bottom = T.copy()
    bottom[3, 0] = 0.1
    nan = T.copy()
    nan[1, 3] = np.nan
    cases = [shear, reflection, bottom, nan]
    for case in cases:
        with pytest.raises(ValueError) as one:
            check_transform(case)
        with pytest.raises(ValueError) as stack:
            check_transform(case[None])
        # the same complaint; only the place of a bad entry is written with the stack's index
        assert str(one.value).split("(")[0] == str(stack.value).split("(")[0]
    for case in cases[:2]:
        with pytest.raises(ValueError):
            check_rotation(case[:3, :3])
    assert check_transform(T) is T and check_rotation(T[:3, :3].copy()).shape == (3, 3)


def test_pose_error_of_one_pair_is_the_stack_of_one():
    A, B = random_transforms(500, seed=1), random_transforms(500, seed=2)
    B[:100, :3, :3] = A[:100, :3, :3] @ so3_exp(
        np.random.default_rng(3).normal(size=(100, 3)) * 1e-9
    )
    position, angle = pose_error(A, B)
    for i in range(500):
        p, a = pose_error(A[i], B[i])
        # 2·asin near a half turn amplifies rounding by 1/cos(angle/2): same bound, both ways
        assert abs(p - position[i]) <= 1e-15
        assert abs(a - angle[i]) <= 2e-15 / max(np.cos(angle[i] / 2), 1e-3)


def test_the_float_rotation_log_matches_the_stacked_one_near_a_half_turn():
    rng = np.random.default_rng(5)
    axis = rng.normal(size=(3000, 3))
    axis /= np.linalg.norm(axis, axis=1, keepdims=True)
    angle = np.concatenate(
        [rng.uniform(0.0, np.pi, 1000), np.pi - 10.0 ** rng.uniform(-12, -1, 2000)]
    )
    R = so3_exp(axis * angle[:, None])
    _, theta, omega = rotation_parts(R)
    for i in range(len(R)):
        _, t, w = _rotation_parts_one(*R[i].ravel().tolist())
        assert abs(t - theta[i]) < 1e-15
        np.testing.assert_allclose(w, omega[i], rtol=0, atol=1e-12)


def test_a_single_ik_solve_reaches_every_target_the_batch_reaches():
    arm = urkin.robot("ur5")
    rng = np.random.default_rng(8)
    targets = urkin.fk(arm, rng.uniform(-np.pi, np.pi, (40, 6)))
    batch = urkin.ik(arm, targets)
    for i, T in enumerate(targets):
        one = urkin.ik(arm, T)
        assert one.success and batch.success[i]
        position, angle = pose_error(urkin.fk(arm, one.q), T)
        assert position <= 1e-10 and angle <= 1e-10


@pytest.mark.parametrize("size", [1, 2, 5, 9, 10])
def test_small_stacks_take_the_one_pose_code_with_the_stack_layout(size):
    arm = urkin.robot("ur5")
    q = _configurations(np.random.default_rng(13), 60)
    poses = urkin.fk(arm, q)
    big, big_mask = urkin.ik_analytic(arm, poses, return_mask=True)
    for start in range(0, 60 - size, size):
        part = slice(start, start + size)
        np.testing.assert_allclose(urkin.fk(arm, q[part]), poses[part], rtol=0, atol=1e-15)
        np.testing.assert_allclose(
            urkin.jacobian(arm, q[part]), urkin.jacobian(arm, q)[part], rtol=0, atol=1e-15
        )
        small, small_mask = urkin.ik_analytic(arm, poses[part], return_mask=True)
        np.testing.assert_array_equal(small_mask, big_mask[part])
        gap = np.abs(wrap_angles(small - big[part]))[small_mask]
        assert gap.max() < 1e-6  # row i is branch i in both; double roots may round apart
    grid = urkin.fk(arm, q[:6].reshape(2, 3, 6))
    assert grid.shape == (2, 3, 4, 4) and urkin.ik_analytic(arm, grid).shape == (2, 3, 8, 6)


@pytest.mark.parametrize("lead", [(2,), (3,), (2, 4)])
def test_a_few_ik_targets_are_solved_exactly_as_if_alone(lead):
    """Up to eight targets go one by one through the single path: each result equals the
    single call's (same configuration, iterations and restarts), in the stack's axes."""
    arm = urkin.robot("ur5")
    q = random_configurations(arm, lead, seed=21)
    targets = urkin.fk(arm, q)
    # one target out of reach, to show failures are stacked too
    targets[(0,) * len(lead) + (slice(0, 3), 3)] = [3.0, 0.0, 0.0]
    batch = urkin.ik(arm, targets)
    assert batch.q.shape == (*lead, 6) and np.shape(batch.success) == lead
    flat_targets, flat_q = targets.reshape(-1, 4, 4), batch.q.reshape(-1, 6)
    flat_reason = np.array(batch.reason, dtype=object).reshape(-1)
    for i, T in enumerate(flat_targets):
        one = urkin.ik(arm, T)
        np.testing.assert_array_equal(flat_q[i], one.q)
        assert np.ravel(batch.iterations)[i] == one.iterations
        assert np.ravel(batch.success)[i] == one.success
        assert flat_reason[i] == one.reason
    assert not np.ravel(batch.success)[0] and "unreachable" in flat_reason[0]


def test_a_dwindling_batch_hands_its_last_targets_to_the_single_path(monkeypatch):
    """The last few unsolved targets of a batch are finished on the single path (each once),
    and every result is still verified with fk."""
    arm = urkin.robot("ur5")
    targets = urkin.fk(arm, random_configurations(arm, 60, seed=5))
    handed = []
    single = numerical_ik._iterate_one

    def spy(problem, *args, **kwargs):
        handed.append(kwargs["seed"])
        return single(problem, *args, **kwargs)

    monkeypatch.setattr(numerical_ik, "_iterate_one", spy)
    result = urkin.ik(arm, targets)
    rows = [row for _, row in handed]
    assert 1 <= len(rows) <= numerical_ik._HAND_OFF and len(set(rows)) == len(rows)
    assert result.success.all()
    position, angle = pose_error(urkin.fk(arm, result.q), targets)
    assert position.max() <= 1e-10 and angle.max() <= 1e-10


@pytest.mark.parametrize("arm", ARMS[:2], ids=lambda arm: arm.name)
def test_the_combined_pose_and_jacobian_code_gives_fk_and_the_jacobian(arm):
    """numerical IK's one generated call per trial equals the two separate generated calls."""
    from urkin._generated import ur_kinematics as generated

    for q in _configurations(np.random.default_rng(31), 200):
        J = np.empty((6, 6))
        pose = generated.pose_jacobian_one(q.tolist(), arm.lengths, J)
        np.testing.assert_allclose(
            np.reshape(pose, (3, 4)), urkin.fk(arm, q)[:3], rtol=0, atol=1e-15
        )
        np.testing.assert_allclose(J, urkin.jacobian(arm, q), rtol=0, atol=1e-15)


@pytest.mark.parametrize(
    "function, shape",
    [
        (urkin.fk, (4, 4)),
        (urkin.jacobian, (6, 6)),
        (urkin.position_jacobian, (3, 6)),
        (urkin.fk_frames, (7, 4, 4)),
    ],
    ids=lambda x: getattr(x, "__name__", ""),
)
def test_a_stack_of_one_keeps_its_axis_and_equals_the_single_call(function, shape):
    arm = urkin.robot("ur5")
    q = np.array([0.3, -1.2, 1.4, -0.6, 1.1, 0.2])
    stacked_one = function(arm, q[None])
    assert stacked_one.shape == (1, *shape)
    np.testing.assert_array_equal(stacked_one[0], function(arm, q))


def _stack_of_one_calls():
    """Every public function taking joint angles, as ``(name, call(q))``."""
    from urkin import kinematics, planning

    arm = urkin.robot("ur5")
    model = planning.sphere_model(arm)
    table = planning.Scene(boxes=[planning.Box([0, 0, -0.06], [2, 2, 0.1], name="table")])
    other = np.array([0.5, -1.0, 1.0, -0.4, 1.2, 0.0])
    return [
        ("check_joints", lambda q: kinematics.check_joints(q)),
        ("wrap_angles", lambda q: wrap_angles(q)),
        ("singularity_factors", lambda q: kinematics.singularity_factors(arm, q)),
        ("singular_families", lambda q: kinematics.singular_families(arm, q)),
        ("manipulability", lambda q: kinematics.manipulability(arm, q)),
        ("condition_number", lambda q: kinematics.condition_number(arm, q)),
        ("is_free", lambda q: planning.is_free(model, table, q)),
        ("clearance", lambda q: planning.clearance(model, table, q).distance),
        ("edges_free", lambda q: planning.edges_free(model, table, q, other + 0 * q)),
        ("certify_edges", lambda q: planning.certify_edges(model, table, q, other + 0 * q)),
        ("edge_samples", lambda q: planning.edge_samples(model, q, other + 0 * q)),
        ("place", lambda q: model.place(q)),
    ]


@pytest.mark.parametrize(
    "name, call", _stack_of_one_calls(), ids=lambda x: x if isinstance(x, str) else ""
)
def test_every_function_of_joint_angles_keeps_the_axis_of_a_stack_of_one(name, call):
    """The batching rule (DESIGN §2): a (1, 6) stack gives a result with a leading axis of 1,
    equal to the single configuration's (which the scalar fast path of (6,) computes)."""
    q = np.array([0.3, -1.2, 1.4, -0.6, 1.1, 0.2])
    single, stacked = np.asarray(call(q)), np.asarray(call(q[None]))
    assert stacked.shape == (1, *single.shape), name
    np.testing.assert_allclose(stacked[0], single, rtol=0, atol=1e-15)


@pytest.mark.parametrize(
    "name, call", _stack_of_one_calls(), ids=lambda x: x if isinstance(x, str) else ""
)
@pytest.mark.parametrize("lead", [(0,), (2, 0)], ids=str)
def test_every_function_of_joint_angles_takes_an_empty_stack(name, call, lead):
    """An empty stack gives an empty result with its leading axes, not numpy's error."""
    single = np.asarray(call(np.zeros(6)))
    assert np.asarray(call(np.zeros((*lead, 6)))).shape == (*lead, *single.shape), name


def test_in_range_angles_whose_squares_add_up_past_the_bound_take_the_general_path():
    """The one-pose test is one Euclidean norm; six angles each within ±8π can exceed it, and
    must still be computed (by the checked path), not refused."""
    arm = urkin.robot("ur5")
    q = np.full(6, 7.5 * np.pi)
    assert float(np.sum(q * q)) > (8 * np.pi) ** 2
    np.testing.assert_allclose(urkin.fk(arm, q), urkin.fk(arm, q[None])[0], rtol=0, atol=0)
    np.testing.assert_allclose(urkin.fk(arm, q), urkin.fk(arm, wrap_angles(q)), rtol=0, atol=1e-13)


def test_the_float_wrap_of_the_single_ik_path_is_wrap_angles_to_the_bit():
    rng = np.random.default_rng(8)
    x = np.concatenate(
        [
            rng.uniform(-30.0, 30.0, 2000),
            [np.pi, -np.pi, 3 * np.pi, -3 * np.pi, 0.0, -0.0, np.nextafter(np.pi, 4.0)],
        ]
    )
    floats = np.array([numerical_ik._wrap_float(value) for value in x.tolist()])
    np.testing.assert_array_equal(floats, wrap_angles(x, check=False))  # the stacked path's


@pytest.mark.parametrize("max_step", [0.05, 1.0, np.inf])
def test_a_single_solve_returns_wrapped_angles_whatever_the_step_limit(max_step):
    """The single path wraps every trial into (−π, π] (in Python floats), however long the
    steps; a shortened step uses the general predicted reduction of LM's gain ratio, a full
    one the shortcut (JᵀJ + μI)Δq = g."""
    arm = urkin.robot("ur5")
    targets = urkin.fk(arm, random_configurations(arm, 12, seed=9))
    for T in targets:
        result = urkin.ik(arm, T, q0=np.full(6, 3.0), max_step=max_step, max_iterations=400)
        assert result.success, result.reason
        assert np.all(result.q > -np.pi) and np.all(result.q <= np.pi)
        position, angle = pose_error(urkin.fk(arm, result.q), T)
        assert position <= 1e-10 and angle <= 1e-10


@pytest.mark.parametrize("bad", [np.nan, np.inf, 30.0])
def test_a_few_configurations_refuse_what_one_refuses(bad):
    """The row-by-row path of a few configurations (k ≤ 24) tests them all at once; one bad
    angle anywhere sends the stack to the checked path, which names it."""
    q = np.zeros((3, 6))
    q[1, 2] = bad
    for function in (urkin.fk, urkin.jacobian, urkin.position_jacobian, urkin.fk_frames):
        with pytest.raises(ValueError, match=r"q contains NaN or infinity|q has an angle of 30"):
            function(urkin.robot("ur5"), q)


@pytest.mark.parametrize("size", [2, 3, 7, 24])
@pytest.mark.parametrize("scale", [np.pi, 2 * np.pi])
def test_a_few_configurations_are_the_single_results_to_the_bit(size, scale):
    """Row by row (all angles' norm within the bound) or through the checked path (a stack of
    angles up to ±2π whose norm is past it), a small stack equals its rows' single results."""
    arm = urkin.robot("ur10e")
    q = np.random.default_rng(size).uniform(-scale, scale, (size, 6))
    for function in (urkin.fk, urkin.jacobian, urkin.position_jacobian):
        np.testing.assert_array_equal(function(arm, q), np.array([function(arm, x) for x in q]))


@pytest.mark.parametrize("lead", [(1,), (1, 1)])
def test_a_stack_of_one_ik_target_is_the_single_solve(lead):
    """A target of shape (1, 4, 4) or (1, 1, 4, 4) is solved and verified as the single target
    is (the same q, errors, iterations and reason), and reported with its leading axes."""
    arm = urkin.robot("ur5")
    T = urkin.fk(arm, np.array([0.3, -1.2, 1.4, -0.6, 1.1, 0.2]))
    one = urkin.ik(arm, T)
    stack = urkin.ik(arm, T.reshape(*lead, 4, 4))
    assert stack.q.shape == (*lead, 6) and stack.success.shape == lead
    np.testing.assert_array_equal(stack.q.reshape(6), one.q)
    assert stack.iterations.reshape(()) == one.iterations
    assert stack.residual.reshape(()) == one.residual
    assert np.ravel(stack.reason).tolist() == [one.reason]
    with pytest.raises(ValueError, match=r"entry \(0, 0, 0\)"):
        urkin.ik(arm, np.full((1, 4, 4), np.nan))
