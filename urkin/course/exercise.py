"""Lessons, their exercises and checks, and how an exercise is run against a submission.

A lesson module (``urkin/course/lessons/lessonNN.py``) declares one :class:`Lesson`: its
exercises, each a function the student writes (``dh_transform``) with an id (``"2.1"``), the
:class:`Check` objects that grade it and their points, and what counts as urkin's own answer to
it (:attr:`Exercise.answer`).  A check is a function ``(submission, rng)``: it draws inputs from
``rng``, calls the student's functions through the :class:`~urkin.course.submission.Submission`
(any function the submission defines, not only the exercise's), and raises
:class:`~urkin.course.compare.Mismatch` when an answer is wrong.

The same checks serve the notebook's check cell (:func:`urkin.course.check`, fixed visible
seed, in the student's kernel) and the autograder (a fresh seed per run, the submission in an
isolated process, the checks outside it).
"""

from __future__ import annotations

import warnings
import zlib
from collections.abc import Callable, Mapping
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from urkin.course.compare import Mismatch
from urkin.course.submission import StudentRaised, Submission, SubmissionGone

__all__ = [
    "VISIBLE_SEED",
    "Check",
    "CheckResult",
    "Exercise",
    "ExerciseResult",
    "Lesson",
    "link_dependencies",
    "run_exercise",
]

#: Seed of the inputs a notebook's check cell uses; grading uses other, fresh seeds.
VISIBLE_SEED = 0


@dataclass(frozen=True)
class Check:
    """One graded property of an exercise: ``run(submission, rng)`` returns normally when the
    property holds and raises :class:`~urkin.course.compare.Mismatch` otherwise.

    A check that only reads the student's code (``reads_code``: "no matrix inverse", "a closed
    form") earns its points only when another check of the exercise earned some: a stub
    has no matrix products either.  A ``gated`` check, one of a special case a trivial body
    passes (the Jacobian at q = 0 is the screw axes it is given; a manipulability of 0 at a
    singularity; ``True`` for a free path), earns its points only when another check of the
    answers earned some: returning the argument, 0 or True earns nothing.
    """

    description: str
    points: float
    run: Callable[[Submission, np.random.Generator], None]
    reads_code: bool = False
    gated: bool = False


@dataclass(frozen=True)
class Exercise:
    """A function to write, with the checks that grade it.

    Parameters
    ----------
    id : str
        ``"<lesson>.<k>"``, for example ``"2.1"``; exercises are numbered in the order they
        appear in the lesson.
    function : str
        Name of the function the student defines in the exercise's cell.
    title : str
        What the function does, in a few words.
    checks : tuple of Check
    answer : tuple
        What counts as urkin's own answer to the exercise: library functions, classes or
        modules (objects, or dotted public names for constants).  While the exercise is graded
        they, and every library function that uses them, are hidden from the submission
        (:mod:`urkin.course.answers`): calling them earns nothing.
    uses : tuple of str
        Other functions of the submission the checks call (for example the student's
        ``lm_step`` inside ``ik_lm``); the grader defines them too.
    builds_on : tuple of str
        Ids of earlier exercises whose functions this one usually calls; when both lose
        points, the feedback says to fix the earlier one first.
    """

    id: str
    function: str
    title: str
    checks: tuple[Check, ...]
    answer: tuple[Any, ...] = ()
    uses: tuple[str, ...] = ()
    builds_on: tuple[str, ...] = ()

    @property
    def points(self) -> float:
        """Total points of the exercise."""
        return float(sum(c.points for c in self.checks))

    @property
    def lesson(self) -> str:
        """Two-digit lesson number, ``"02"`` for exercise ``"2.1"``."""
        return f"{int(self.id.split('.')[0]):02d}"


@dataclass(frozen=True)
class Lesson:
    """A lesson: its number, title, one line for the README's table, and its exercises.

    The notebook is ``solutions/NN_<slug>.py`` (and its executed ``.ipynb``); the module that
    declares the lesson is ``urkin/course/lessons/lessonNN.py``.
    """

    number: str
    title: str
    summary: str
    exercises: tuple[Exercise, ...] = ()

    def __post_init__(self) -> None:
        if not (len(self.number) == 2 and self.number.isdigit()):
            raise ValueError(f"a lesson number has two digits, like '02'; got {self.number!r}")
        for k, ex in enumerate(self.exercises, start=1):
            expected = f"{int(self.number)}.{k}"
            if ex.id != expected:
                raise ValueError(
                    f"lesson {self.number}: exercise {k} must have id {expected!r}; got {ex.id!r}"
                )
        functions = [ex.function for ex in self.exercises]
        if len(set(functions)) != len(functions):
            raise ValueError(f"lesson {self.number}: two exercises name the same function")

    @property
    def points(self) -> float:
        return float(sum(ex.points for ex in self.exercises))

    def exercise(self, exercise_id: str) -> Exercise:
        for ex in self.exercises:
            if ex.id == exercise_id:
                return ex
        raise KeyError(f"lesson {self.number} has no exercise {exercise_id!r}")


@dataclass
class CheckResult:
    """Outcome of one check."""

    description: str
    points: float
    earned: float
    message: str = ""
    mistake: str | None = None


@dataclass
class ExerciseResult:
    """Outcome of grading one exercise; serialisable with :meth:`to_dict`.

    ``status`` is one of ``passed``, ``partial``, ``failed``, ``not attempted``, ``missing``,
    ``forbidden`` (urkin's own answer used), ``timeout``, ``crashed``, ``error`` (the grader
    could not run it).
    """

    exercise: str
    function: str
    title: str
    points: float
    earned: float
    status: str
    message: str = ""
    checks: list[CheckResult] = field(default_factory=list)

    @property
    def mistakes(self) -> list[str]:
        """Names of the mistakes the checks identified."""
        return sorted({c.mistake for c in self.checks if c.mistake})

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    def report(self) -> str:
        """The text a student reads: the verdict first, then each check."""
        head = (
            f"Exercise {self.exercise} · {self.function} — {self.earned:g}/{self.points:g} points"
        )
        lines = [f"{head}: {self.status}"]
        if self.message:
            lines.append("  " + self.message.replace("\n", "\n  "))
        for c in self.checks:
            mark = "✓" if c.earned == c.points else "✗"
            lines.append(f"  {mark} {c.description} ({c.earned:g}/{c.points:g})")
            if c.message:
                lines.append("      " + c.message.replace("\n", "\n      "))
        return "\n".join(lines)


def _rng(seed: int, exercise_id: str, index: int) -> np.random.Generator:
    return np.random.default_rng([seed, zlib.crc32(exercise_id.encode()), index])


def _stub_of(raised: StudentRaised) -> str | None:
    """The exercise id of a course stub's NotImplementedError ("Exercise 2.1: write …")."""
    text = raised.message.strip()
    if raised.kind == "NotImplementedError" and text.startswith("Exercise "):
        return text.split()[1].rstrip(":")
    return None


def run_exercise(ex: Exercise, submission: Submission, seed: int = VISIBLE_SEED) -> ExerciseResult:
    """Run every check of ``ex`` on a submission; never raises for anything the submission does.

    Parameters
    ----------
    ex : Exercise
    submission : Submission
        The student's functions (in the notebook's kernel, or isolated by the grader).
    seed : int
        Seed of the random inputs: :data:`VISIBLE_SEED` in notebook check cells, a fresh one
        per grading run.

    Returns
    -------
    ExerciseResult
    """
    result = ExerciseResult(ex.id, ex.function, ex.title, ex.points, 0.0, "failed")
    missing = submission.missing(ex.function)
    if missing:
        result.status, result.message = "missing", missing
        result.checks = [CheckResult(c.description, c.points, 0.0) for c in ex.checks]
        return result
    forbidden: str | None = None
    gone: SubmissionGone | None = None
    own_stub, other_failure = 0, False
    for index, chk in enumerate(ex.checks):
        outcome = CheckResult(chk.description, chk.points, 0.0)
        result.checks.append(outcome)
        if gone is not None:
            outcome.message = "not run: " + gone.status
            continue
        try:
            with warnings.catch_warnings(), np.errstate(all="ignore"):
                warnings.simplefilter("ignore")
                chk.run(submission, _rng(seed, ex.id, index))
            outcome.earned = chk.points
        except Mismatch as exc:
            other_failure = True
            outcome.message, outcome.mistake = exc.describe(), exc.mistake
        except StudentRaised as exc:
            stub = _stub_of(exc)
            if exc.kind == "ForbiddenCallError":
                forbidden = exc.message
            elif stub == ex.id:
                own_stub += 1
                outcome.message = "not written yet: the function still raises NotImplementedError"
            elif stub is not None:
                outcome.message = (
                    f"it calls a function of exercise {stub} that is not written yet "
                    f"({exc.message.strip()})"
                )
            elif exc.kind == "NotImplementedError":
                other_failure = True
                outcome.message = exc.describe("raises NotImplementedError for these inputs")
            else:
                other_failure = True
                outcome.message = exc.describe()
        except SubmissionGone as exc:
            gone = exc
            outcome.message = exc.message
        except Exception as exc:  # an answer so odd that judging it failed: no points, no crash
            other_failure = True
            outcome.message = f"the answer could not be judged ({type(exc).__name__}: {exc})"
    # what reads code needs a check of the answers; a gated check, another one
    answered = [c for c, d in zip(result.checks, ex.checks) if c.earned and not d.reads_code]
    for c, d in zip(result.checks, ex.checks):
        if c.earned and (
            (d.reads_code and not answered) or (d.gated and not any(o is not c for o in answered))
        ):
            c.earned = 0.0
            c.message = "earns its points once the function gives right answers"
    result.earned = float(sum(c.earned for c in result.checks))
    if forbidden is not None:
        result.status, result.message, result.earned = "forbidden", forbidden, 0.0
        for c in result.checks:
            c.earned = 0.0
    elif own_stub and not other_failure and not result.earned and not result.mistakes:
        result.status = "not attempted"
        result.message = "not attempted yet: the function still raises NotImplementedError"
        for c in result.checks:
            c.message = ""
    elif gone is not None:
        result.status, result.message = gone.status, gone.message
    elif result.earned == result.points:
        result.status = "passed"
    elif result.earned > 0:
        result.status = "partial"
    if result.mistakes and result.status in ("partial", "failed"):
        result.message = "likely mistake: " + "; ".join(result.mistakes)
    return result


def link_dependencies(results: list[ExerciseResult], exercises: Mapping[str, Exercise]) -> None:
    """Add "fix exercise 2.1 first" to results that lost points while an exercise they build on
    lost points too."""
    by_id = {r.exercise: r for r in results}
    for result in results:
        if result.earned == result.points or result.exercise not in exercises:
            continue
        for earlier_id in exercises[result.exercise].builds_on:
            earlier = by_id.get(earlier_id)
            if earlier is not None and earlier.earned < earlier.points:
                note = (
                    f"{result.function} usually calls your {earlier.function}, which lost "
                    f"points in exercise {earlier_id}: fix that one first"
                )
                result.message = f"{result.message}\n{note}" if result.message else note
