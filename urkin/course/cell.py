"""The notebook's check cell: ``check("2.1", dh_transform)`` prints what is right and wrong.

The check runs in the student's own kernel, on the fixed visible seed, with the same checks
the grader uses: it sees the whole notebook (every function defined so far), hides urkin's own
answer to the exercise while the student's function runs, and says "fix 2.1 first" when an
exercise that this one builds on loses points too.  It never raises.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from typing import Any

from urkin.course.answers import answer_for
from urkin.course.exercise import (
    VISIBLE_SEED,
    Exercise,
    ExerciseResult,
    link_dependencies,
    run_exercise,
)
from urkin.course.lessons import exercise
from urkin.course.submission import LocalSubmission

__all__ = ["check", "check_result"]


def _run(ex: Exercise, namespace: dict[str, Any], function: Any, seed: int) -> ExerciseResult:
    overrides = {ex.function: function} if function is not None else {}
    submission = LocalSubmission(namespace, overrides, hide=answer_for(ex).hidden_in)
    return run_exercise(ex, submission, seed)


def check_result(
    exercise_id: str,
    function: Callable[..., Any] | None,
    namespace: dict[str, Any],
    seed: int = VISIBLE_SEED,
) -> ExerciseResult:
    """The result :func:`check` prints, for a function and the namespace it lives in."""
    ex = exercise(exercise_id)
    result = _run(ex, namespace, function, seed)
    if result.earned < result.points and ex.builds_on:
        earlier = {e: exercise(e) for e in ex.builds_on}
        results = [
            _run(earlier[e], namespace, None, seed)
            for e in ex.builds_on
            if callable(namespace.get(earlier[e].function))
        ]
        link_dependencies([*results, result], {ex.id: ex, **earlier})
    return result


def check(exercise_id: str, function: Callable[..., Any] | None = None) -> None:
    """Check an exercise and print a short report; never raises.

    Parameters
    ----------
    exercise_id : str
        For example ``"2.1"``.
    function : callable, optional
        The student's function; by default the notebook's function of the exercise's name.
        The checks may also call the notebook's other functions.
    """
    try:
        namespace = sys._getframe(1).f_globals
        text = check_result(exercise_id, function, namespace).report()
    except KeyboardInterrupt:
        raise
    except BaseException as exc:  # the check cell itself must never fail
        text = f"could not check exercise {exercise_id}: {type(exc).__name__}: {exc}"
    print(text, file=sys.stdout)
