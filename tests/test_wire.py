"""Input functions described by data (urkin.course.wire.Function): rebuilt across the wire.

The IK stand-ins of exercise 5.6, and the complex-step test functions of exercise 4.11, which
keep a complex argument complex."""

from __future__ import annotations

import numpy as np
import pytest

import urkin
from urkin.course import wire


def _across(value, trusted=True):
    """``value`` as the other side of the grader's pipe sees it."""
    return wire.decode(wire.loads(wire.dumps(wire.encode(value))), trusted=trusted)


def test_a_function_of_one_argument_still_takes_one():
    f = _across(wire.Function("linear", A=[[1.0, 2.0], [0.0, 1.0]], b=[0.5, -1.0]))
    np.testing.assert_array_equal(f([1.0, 1.0]), [3.5, 0.0])


def test_fixed_steps_adds_the_step_of_the_nearest_point_to_the_guess():
    rng = np.random.default_rng(3)
    points, steps = rng.normal(size=(4, 3)), rng.normal(size=(4, 6))
    solve = _across(wire.Function("fixed_steps", points=points, steps=steps))
    assert isinstance(solve, wire.Function) and solve.kind == "fixed_steps"
    guess = rng.normal(size=6)
    for k in range(4):
        # any robot (it is not used), the point as a list, the guess unchanged by the call
        np.testing.assert_array_equal(solve(None, points[k].tolist(), guess), guess + steps[k])
    np.testing.assert_array_equal(solve(None, points[2] + 1e-6, guess.tolist()), guess + steps[2])
    np.testing.assert_array_equal(solve(robot=None, p=points[1], q_guess=guess), guess + steps[1])


def test_position_ik_is_urkins_plain_newton_from_the_guess():
    ur5 = urkin.robot("UR5")
    q_true = np.array([0.3, -1.2, 1.4, -1.1, 1.2, 0.4])
    p = urkin.fk(ur5, q_true)[:3, 3]
    guess = q_true + 0.05
    solve = _across(wire.Function("position_ik"))
    q = solve(_across(ur5), p, guess)
    assert np.linalg.norm(urkin.fk(ur5, q)[:3, 3] - p) < 1e-10
    expected = urkin.ik(ur5, p, q0=guess, method="nr", max_restarts=0).q
    np.testing.assert_array_equal(q, expected)


def test_a_submission_never_gets_a_function_back():
    solve = wire.Function("fixed_steps", points=[[0.0, 0.0, 1.0]], steps=[[0.1] * 6])
    back = _across(solve, trusted=False)
    assert isinstance(back, wire.Opaque) and "fixed_steps" in back.text


def test_an_unknown_kind_is_refused():
    with pytest.raises(ValueError, match="unknown function kind"):
        wire.Function("anything_goes")


# ------------------------------------------------ complex-step test functions (exercise 4.11)

RNG = np.random.default_rng(411)
A, B, C = RNG.normal(size=(3, 2, 4))
b = RNG.normal(size=2)
UR5 = urkin.robot("UR5")


def _polynomial_jacobian(x):
    return A + (C @ x)[:, None] * B + (B @ x)[:, None] * C


def _sin_exp_jacobian(x):
    grow = np.exp(B @ x)
    return (np.cos(A @ x) * grow)[:, None] * A + (np.sin(A @ x) * grow)[:, None] * B


CASES = [
    (wire.Function("polynomial", A=A, B=B, C=C, b=b), 4, _polynomial_jacobian),
    (wire.Function("sin_exp", A=A, B=B), 4, _sin_exp_jacobian),
    (
        wire.Function("complex_flange_position", robot=UR5),
        6,
        lambda q: urkin.kinematics.position_jacobian(UR5, q),
    ),
]


@pytest.mark.parametrize(("f", "n", "jacobian"), CASES, ids=[f.kind for f, _, _ in CASES])
def test_a_complex_step_function_survives_the_wire_and_keeps_complex_arguments(f, n, jacobian):
    back = _across(f)
    assert isinstance(back, wire.Function) and back.kind == f.kind
    x = RNG.uniform(-1.0, 1.0, n)
    np.testing.assert_array_equal(back(x), f(x))
    np.testing.assert_array_equal(back(list(x)), f(x))  # a list is read as numbers
    assert not np.iscomplexobj(back(x))
    h = 1e-20
    J = np.column_stack([np.imag(back(x + 1j * h * e)) / h for e in np.eye(n)])
    np.testing.assert_allclose(J, jacobian(x), rtol=0, atol=1e-12)


def test_a_submission_cannot_rebuild_a_complex_step_function():
    data = wire.loads(wire.dumps(wire.encode(CASES[2][0])))
    assert isinstance(wire.decode(data), wire.Opaque)  # untrusted: described, never built


def test_the_flange_position_for_numeric_jacobian_still_drops_nothing_real():
    """The real-valued kind of exercise 4.2 is unchanged: it reads its argument as floats."""
    q = RNG.uniform(-np.pi, np.pi, 6)
    real = _across(wire.Function("flange_position", robot=UR5))
    complex_kept = _across(wire.Function("complex_flange_position", robot=UR5))
    np.testing.assert_array_equal(real(q), complex_kept(q))
    np.testing.assert_array_equal(real(q.astype(np.float32)), complex_kept(q.astype(np.float32)))


# ------------------------------------------ candidate closed-form positions (exercise 2.7)


def test_the_right_closed_form_is_the_flange_position_of_every_arm():
    rng = np.random.default_rng(27)
    formula = _across(wire.Function("ur_position"))
    for name in urkin.ROBOTS:
        robot = _across(urkin.robot(name))
        for q in rng.uniform(-np.pi, np.pi, (20, 6)):
            p = urkin.fk(robot, q)[:3, 3]
            np.testing.assert_allclose(formula(robot, q), p, rtol=0, atol=1e-12)
            np.testing.assert_array_equal(formula(robot, list(q)), formula(robot, q))


def test_seed002s_formula_as_published_misses_by_its_known_error():
    """ERRATA 002: |e| = d6 |cos(q2+q3+q4)| (1 − sin q5); at 0.35 rad on every (report's) joint
    the formula gives (759.367, 78.336, 415.781) mm."""
    from urkin.course.seeds import SEED002_ARM, SEED002_SHIFT

    arm = _across(SEED002_ARM)
    published = _across(wire.Function("seed002_position", report_angles=True))
    q_report = np.full(6, 0.35)
    np.testing.assert_allclose(
        1000 * published(arm, q_report - SEED002_SHIFT),
        [759.367, 78.336, 415.781],
        rtol=0,
        atol=5e-4,
    )
    q = np.random.default_rng(2).uniform(-np.pi, np.pi, (50, 6))
    errors = [np.linalg.norm(published(arm, qk) - urkin.fk(arm, qk)[:3, 3]) for qk in q]
    bound = arm.d6 * np.abs(np.cos(q[:, 1:4].sum(axis=1))) * (1.0 - np.sin(q[:, 4]))
    np.testing.assert_allclose(errors, bound, rtol=0, atol=1e-12)
    # its terms with UR's lengths and angles make the same mistake on any UR arm
    terms = _across(wire.Function("seed002_position"))
    ur10 = urkin.robot("UR10")
    errors = [np.linalg.norm(terms(ur10, qk) - urkin.fk(ur10, qk)[:3, 3]) for qk in q]
    bound = ur10.d6 * np.abs(np.cos(q[:, 1:4].sum(axis=1))) * (1.0 - np.sin(q[:, 4]))
    np.testing.assert_allclose(errors, bound, rtol=0, atol=1e-12)


@pytest.mark.parametrize("joint", range(5))
def test_a_folded_joint_is_right_near_zero_and_wrong_beyond_a_quarter_turn(joint):
    ur5 = urkin.robot("UR5")
    formula = _across(wire.Function("folded_ur_position", joint=joint))
    q = np.random.default_rng(joint).uniform(-np.pi, np.pi, (200, 6))
    errors = np.array([np.linalg.norm(formula(ur5, qk) - urkin.fk(ur5, qk)[:3, 3]) for qk in q])
    inside = np.abs(q[:, joint]) < np.pi / 2
    assert (
        errors[inside].max() < 1e-12
        and np.linalg.norm(formula(ur5, np.zeros(6)) - urkin.fk(ur5, np.zeros(6))[:3, 3]) < 1e-12
    )
    assert errors[~inside].min() > 1e-3  # a half turn of a joint always moves the flange


# ------------------------------------ all closed-form solutions of listed poses (exercise 8.2)


def test_listed_solutions_returns_the_rows_of_the_nearest_listed_pose():
    rng = np.random.default_rng(84)
    ur5 = urkin.robot("UR5")
    poses = urkin.fk(ur5, rng.uniform(-np.pi, np.pi, (3, 6)))
    solutions = rng.uniform(-np.pi, np.pi, (3, 8, 6))
    counts = np.array([8, 0, 5])
    solve_all = _across(
        wire.Function("listed_solutions", poses=poses, solutions=solutions, counts=counts)
    )
    assert isinstance(solve_all, wire.Function) and solve_all.kind == "listed_solutions"
    robot = _across(ur5)
    for k in range(3):
        rows = solve_all(robot, poses[k])
        assert rows.shape == (counts[k], 6)
        np.testing.assert_array_equal(rows, solutions[k, : counts[k]])
    # a pose given as a list, slightly off, still finds its row; the answer is a copy
    rows = solve_all(None, (poses[2] + 1e-9).tolist())
    np.testing.assert_array_equal(rows, solutions[2, :5])
    rows[:] = 0.0
    np.testing.assert_array_equal(solve_all(None, poses[2]), solutions[2, :5])
    assert solve_all(robot=None, T=poses[1]).shape == (0, 6)


def test_joint_boxes_is_free_outside_its_boxes_and_keeps_a_budget():
    lower = np.array([[0.0] * 6, [2.0] * 6])
    upper = np.array([[1.0] * 6, [3.0] * 6])
    is_free = _across(wire.Function("joint_boxes", lower=lower, upper=upper, budget=4))
    assert is_free(np.full(6, 0.5)) is False and is_free(np.full(6, 1.5)) is True
    np.testing.assert_array_equal(is_free(np.array([[2.5] * 6, [-1.0] * 6])), [False, True])
    with pytest.raises(RuntimeError, match="asked about more than 4 configurations"):
        is_free(np.zeros((1, 6)))  # the fifth
    fresh = _across(wire.Function("joint_boxes", lower=lower, upper=upper, budget=4))
    assert fresh(np.zeros((4, 6))).shape == (4,)  # each copy counts from zero
    with pytest.raises(ValueError, match="joint angles of shape"):
        fresh(np.zeros(5))


def test_one_message_reads_a_bounded_amount_of_symbolic_text():
    # sixty texts of 100 kB: read one after another, seconds and over a gigabyte; past the
    # budget they arrive unread
    one = "Add(" + ", ".join(["sin(" * 40 + "Symbol('x')" + ")" * 40] * 470) + ")"
    assert 100_000 < len(one) < wire.MAX_SYMBOLIC_TOTAL
    values = wire.decode([{"$sym": one}] * 60)
    read = [v for v in values if not isinstance(v, wire.Opaque)]
    assert 1 <= len(read) <= wire.MAX_SYMBOLIC_TOTAL // len(one)
    assert "not read" in values[-1].text
    with wire.symbolic_budget():  # one budget for every decode of a message
        first = wire.decode([{"$sym": one}] * 5)
        rest = wire.decode([{"$sym": one}] * 60)
    assert sum(not isinstance(v, wire.Opaque) for v in first + rest) == len(read)
    with wire.symbolic_budget(0):  # arguments of the checks' own functions: none read
        assert isinstance(wire.decode({"$sym": "Symbol('x')"}), wire.Opaque)
