"""One test per exercise of each graded submission (see conftest.py)."""

import pytest


def test_exercise(submission_exercise, grade):
    path, exercise_id = submission_exercise
    result = grade(path)
    if result.status != "graded":
        pytest.fail(f"{path.name} was not graded: {result.reason}", pytrace=False)
    outcome = result.exercise(exercise_id)
    if outcome is None:
        pytest.fail(f"exercise {exercise_id} has no result", pytrace=False)
    if outcome.earned < outcome.points:
        notes = "\n".join(result.notes)
        pytest.fail(outcome.report() + (f"\n{notes}" if notes else ""), pytrace=False)
