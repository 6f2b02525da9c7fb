"""The lessons of the course, found automatically: one module ``lessonNN.py`` per lesson.

Each module defines ``LESSON``, a :class:`~urkin.course.exercise.Lesson` with its exercises,
points, checks, mistake detectors and what counts as urkin's own answer to each exercise.  The
course's notebook is ``solutions/NN_<topic>.py``.  Nothing else registers a lesson: the
builder, the notebook check cells, the grader, the tests, the docs' table of contents and the
README's lesson table all read this list.
"""

from __future__ import annotations

import functools
import importlib
import pkgutil

from urkin.course.exercise import Exercise, Lesson

__all__ = ["exercise", "lesson", "lessons"]


@functools.cache
def lessons() -> dict[str, Lesson]:
    """Every lesson, by two-digit number, in order."""
    found = {}
    for info in sorted(pkgutil.iter_modules(__path__), key=lambda i: i.name):
        if not (info.name.startswith("lesson") and info.name[6:].isdigit()):
            continue
        module = importlib.import_module(f"{__name__}.{info.name}")
        declared = getattr(module, "LESSON", None)
        if not isinstance(declared, Lesson):
            raise TypeError(f"{module.__name__} must define LESSON, a urkin.course.Lesson")
        if declared.number != info.name[6:]:
            raise ValueError(f"{module.__name__} declares lesson {declared.number!r}")
        found[declared.number] = declared
    return found


def lesson(number: str | int) -> Lesson:
    """The lesson ``number`` (``"02"`` or ``2``); a clear error names the known ones."""
    key = f"{int(number):02d}"
    known = lessons()
    if key not in known:
        raise KeyError(f"no lesson {key}; the lessons are {', '.join(known)}")
    return known[key]


def exercise(exercise_id: str) -> Exercise:
    """The exercise ``"N.k"``, for example ``exercise("2.1")``."""
    if not isinstance(exercise_id, str):
        # a number loses the exercise's trailing zeros: 4.10 is 4.1
        raise TypeError(
            "give the exercise as a string such as '2.1' (a number drops trailing zeros: "
            f"4.10 is 4.1); got the {type(exercise_id).__name__} {exercise_id!r}"
        )
    text = exercise_id
    try:
        return lesson(text.split(".")[0]).exercise(text)
    except (KeyError, ValueError):
        known = ", ".join(e.id for each in lessons().values() for e in each.exercises)
        raise KeyError(f"no exercise {text!r}; the exercises are {known}") from None
