"""How an exercise is run and reported, whatever the student's function does."""

from __future__ import annotations

import numpy as np
import pytest

from urkin.course import check
from urkin.course.cell import check_result
from urkin.course.compare import Mismatch, as_array, compare, tolerance
from urkin.course.exercise import Check, Exercise, run_exercise
from urkin.course.submission import LocalSubmission, StudentRaised, SubmissionGone


def _doubles(sub, rng):
    for _ in range(3):
        x = rng.normal(size=3)
        got = as_array(sub.double(x), (3,), "double(x)", {"x": x})
        compare(got, 2 * x, what="2 x", inputs={"x": x},
                hypotheses={"tripled instead": lambda x=x: 3 * x})  # fmt: skip


def _doubles_big_numbers(sub, rng):
    x = rng.normal(size=3) * 1e6
    compare(as_array(sub.double(x), (3,), "double(x)", {"x": x}), 2 * x, what="2 x",
            inputs={"x": x})  # fmt: skip


EXERCISE = Exercise(
    "9.1", "double", "twice x",
    (Check("doubles small numbers", 2, _doubles), Check("doubles big numbers", 1,
                                                        _doubles_big_numbers)),
)  # fmt: skip


def _run(source: str, seed: int = 0):
    namespace = {"np": np}
    exec(source, namespace)
    return run_exercise(EXERCISE, LocalSubmission(namespace), seed)


def test_a_right_answer_passes():
    result = _run("def double(x):\n    return 2 * np.asarray(x)\n")
    assert (result.status, result.earned) == ("passed", 3.0)


def test_a_float32_answer_passes_at_float32_precision():
    result = _run("def double(x):\n    return (2 * np.asarray(x)).astype(np.float32)\n")
    assert result.status == "passed", result.report()
    assert tolerance(1e-9, np.float32(1), 2e6) > 1e-9


def test_a_near_miss_shows_the_difference_and_the_tolerance():
    result = _run("def double(x):\n    return 2 * np.asarray(x) + 1e-7\n")
    assert result.status == "failed"
    assert "largest difference 1.0e-07; the tolerance is 1e-09" in result.report()


def test_a_named_mistake():
    result = _run("def double(x):\n    return 3 * np.asarray(x)\n")
    assert result.mistakes == ["tripled instead"]
    assert "likely mistake: tripled instead" in result.report()


@pytest.mark.parametrize(
    ("source", "words"),
    [
        ("def double(x):\n    pass\n", "returned None: is a `return` statement missing?"),
        ("def double(x):\n    return 'two'\n", "must return numbers"),
        ("def double(x):\n    return np.zeros(4)\n", "shape (3,); got shape (4,)"),
        ("def double(x):\n    return x * np.nan\n", "returned NaN or infinity"),
        ("def double(x):\n    return 1 / 0\n", "raised ZeroDivisionError: division by zero"),
        ("def double(x):\n    raise SystemExit(3)\n", "called sys.exit()"),
        ("def double(x):\n    return double(x)\n", "infinite recursion"),
    ],
)
def test_a_broken_answer_gets_a_message_with_its_input(source, words):
    result = _run(source)
    assert result.earned == 0 and result.status == "failed"
    assert words in result.report()
    assert "input:" in result.report()  # the case can be reproduced


def test_the_error_message_points_at_the_students_line():
    result = _run("def double(x):\n    y = undefined_name\n    return y\n")
    assert "(in double, line 2)" in result.report()


def test_a_stub_is_not_attempted():
    result = _run('def double(x):\n    raise NotImplementedError("Exercise 9.1: write double")\n')
    assert (result.status, result.earned) == ("not attempted", 0.0)


def test_not_implemented_outside_the_contract_costs_only_those_checks():
    source = (
        "def double(x):\n"
        "    x = np.asarray(x)\n"
        "    if np.abs(x).max() > 1e3:\n"
        "        raise NotImplementedError('only small numbers')\n"
        "    return 2 * x\n"
    )
    result = _run(source)
    assert (result.status, result.earned) == ("partial", 2.0)
    assert "raises NotImplementedError for these inputs" in result.report()


def test_a_stub_of_another_exercise_is_named():
    source = (
        "def helper(x):\n"
        '    raise NotImplementedError("Exercise 9.0: write helper")\n'
        "def double(x):\n"
        "    return helper(x)\n"
    )
    result = _run(source)
    assert result.status == "failed"
    assert "calls a function of exercise 9.0 that is not written yet" in result.report()


class _Gone(LocalSubmission):
    def spy(self, name, watched, *args, **kwargs):
        raise SubmissionGone("timeout", "stopped after 2 s without an answer")


def test_a_timeout_ends_the_exercise_and_says_so():
    result = run_exercise(EXERCISE, _Gone({"double": lambda x: x}), 0)
    assert result.status == "timeout" and result.earned == 0
    assert all(c.message for c in result.checks)


def test_a_missing_function_suggests_the_close_name():
    result = _run("def doubel(x):\n    return 2 * x\n")
    assert result.status == "missing"
    assert "did you mean `doubel`" in result.message


def test_an_odd_answer_never_crashes_the_check():
    source = (
        "class Weird:\n"
        "    def __array__(self, *a, **k):\n"
        "        raise RuntimeError('no')\n"
        "def double(x):\n"
        "    return Weird()\n"
    )
    result = _run(source)
    assert result.earned == 0


def test_a_student_error_carries_its_inputs():
    exc = StudentRaised("ValueError", "bad", "in f, line 1", {"q": np.zeros(2)})
    assert "input:    q=[0., 0.]" in exc.describe()
    assert isinstance(Mismatch("x"), Exception)


def test_the_check_cell_prints_and_never_raises(capsys):
    def dh_transform(theta, d, a, alpha):
        return np.eye(4)

    check("2.1", dh_transform)
    assert "Exercise 2.1 · dh_transform" in capsys.readouterr().out
    check("9.9", dh_transform)
    assert "no exercise '9.9'" in capsys.readouterr().out


def test_the_check_cell_says_fix_the_exercise_it_builds_on_first():
    namespace = {"np": np}
    exec(
        "def dh_transform(theta, d, a, alpha):\n"
        "    return np.eye(4)\n"
        "def forward_kinematics(robot, q):\n"
        "    T = np.eye(4)\n"
        "    for t, d, a, al in zip(q, robot.d, robot.a, robot.alpha):\n"
        "        T = T @ dh_transform(t, d, a, al)\n"
        "    return T\n",
        namespace,
    )
    result = check_result("2.2", None, namespace)
    assert "fix that one first" in result.message


def test_visible_checks_are_deterministic_and_grading_seeds_differ():
    source = "def double(x):\n    return 3 * np.asarray(x)\n"
    assert _run(source, 0).report() == _run(source, 0).report()
    assert _run(source, 0).report() != _run(source, 1).report()
