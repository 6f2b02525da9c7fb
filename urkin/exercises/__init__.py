"""Exercises of the course and their checks.

In a notebook::

    from urkin.exercises import check
    check("2.1", dh_transform)      # prints a report; never raises

The autograder (:mod:`urkin.grading`) runs the same checks with fresh random inputs.
Importing this package registers every lesson's exercises.
"""

from urkin.exercises import (  # noqa: F401  (importing registers the exercises)
    lesson00,
    lesson01,
    lesson02,
    lesson03,
    lesson04,
    lesson05,
    lesson06,
    lesson07,
)
from urkin.exercises.framework import (
    VISIBLE_SEED,
    Check,
    CheckResult,
    Exercise,
    ExerciseResult,
    ForbiddenCallError,
    Mismatch,
    check,
    exercise,
    exercises_for_lesson,
    run_exercise,
)

__all__ = [
    "VISIBLE_SEED",
    "Check",
    "CheckResult",
    "Exercise",
    "ExerciseResult",
    "ForbiddenCallError",
    "Mismatch",
    "check",
    "exercise",
    "exercises_for_lesson",
    "run_exercise",
]
