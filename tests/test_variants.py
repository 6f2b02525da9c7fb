"""Every lesson's checks against realistic correct and wrong versions of its functions.

The solution notebook's own functions must earn full marks; each ``CORRECT`` variant of
``tests/variants/lessonNN.py`` too; each ``WRONG`` variant must lose the points it should and
have its mistake named.  Checks run here in-process, as in a notebook's check cell; the
autograder's tests run the same variants through the isolated grader.
"""

from __future__ import annotations

import importlib

import pytest

from tests.namespaces import solution_namespace, variant
from urkin.course.answers import answer_for
from urkin.course.cell import check_result
from urkin.course.exercise import run_exercise
from urkin.course.lessons import exercise, lessons
from urkin.course.submission import LocalSubmission

SEEDS = (0, 1, 20261123)


def _namespace(number: str) -> dict:
    return solution_namespace(number)


def _variants(kind: str):
    cases = []
    for number in lessons():
        try:
            module = importlib.import_module(f"tests.variants.lesson{number}")
        except ModuleNotFoundError:
            continue
        for v in getattr(module, kind, []):
            cases.append(pytest.param(number, v, id=f"{v.exercise}-{v.name}"))
    return cases


EXERCISES = [
    pytest.param(number, ex.id, id=ex.id)
    for number, each in lessons().items()
    for ex in each.exercises
]


@pytest.mark.parametrize(("number", "exercise_id"), EXERCISES)
@pytest.mark.parametrize("seed", SEEDS)
def test_the_solution_earns_full_marks(number, exercise_id, seed):
    result = check_result(exercise_id, None, _namespace(number), seed)
    assert result.status == "passed", result.report()


@pytest.mark.parametrize(("number", "v"), _variants("CORRECT"))
@pytest.mark.parametrize("seed", SEEDS)
def test_a_correct_variant_earns_full_marks(number, v, seed):
    result = check_result(v.exercise, None, variant(number, v.exercise, v.source, v.also), seed)
    assert result.status == "passed", result.report()


@pytest.mark.parametrize(("number", "v"), _variants("WRONG"))
@pytest.mark.parametrize("seed", SEEDS)
def test_a_wrong_variant_loses_points_and_is_named(number, v, seed):
    result = check_result(v.exercise, None, variant(number, v.exercise, v.source, v.also), seed)
    if v.points is None:
        assert result.earned < result.points, result.report()
    else:
        assert result.earned == v.points, result.report()
    if v.mistake is not None:
        assert any(v.mistake in m for m in result.mistakes), result.report()


class _Calls(LocalSubmission):
    """A local submission that records which of the student's functions the checks call."""

    def __init__(self, namespace, hide):
        super().__init__(namespace, hide=hide)
        self.names: set[str] = set()

    def spy(self, name, watched, *args, **kwargs):
        self.names |= {name, *(w for w in watched if "." not in w)}  # dotted: library code
        return super().spy(name, watched, *args, **kwargs)

    def code(self, name):
        self.names.add(name)
        return super().code(name)


@pytest.mark.parametrize(("number", "exercise_id"), EXERCISES)
def test_checks_call_only_the_functions_the_exercise_declares(number, exercise_id):
    """The grader defines the exercise's function and its ``uses`` only: a check that calls
    another student function must declare it."""
    ex = exercise(exercise_id)
    submission = _Calls(_namespace(number), answer_for(ex).hidden_in)
    run_exercise(ex, submission, 0)
    assert submission.names <= {ex.function, *ex.uses}, submission.names
