"""The machinery shared by every exercise: checks, results, reports and mistake detection.

An :class:`Exercise` is a function the student writes (``dh_transform``), an id (``"2.1"``) and
a list of :class:`Check` objects, each worth some points.  A check draws its own inputs from a
seeded random generator, calls the student's function and raises :class:`Mismatch` when the
answer is wrong, naming the likely mistake when a known wrong hypothesis reproduces it.

The same code serves the notebook's ``check("2.1", dh_transform)`` cell, which uses a fixed
visible seed, and the autograder, which uses a fresh seed for every grading run.
"""

from __future__ import annotations

import sys
import traceback
import warnings
import zlib
from collections.abc import Callable, Mapping
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

__all__ = [
    "VISIBLE_SEED",
    "Check",
    "CheckResult",
    "Exercise",
    "ExerciseResult",
    "ForbiddenCallError",
    "Mismatch",
    "as_array",
    "check",
    "compare",
    "exercise",
    "exercises_for_lesson",
    "format_array",
    "identify_mistake",
    "link_dependencies",
    "register",
    "require_rotation",
    "require_transform",
    "run_exercise",
    "run_exercises",
]

#: Seed of the inputs a notebook's check cell uses; grading uses other, fresh seeds.
VISIBLE_SEED = 0

_REGISTRY: dict[str, Exercise] = {}


class Mismatch(Exception):
    """Raised by a check when the student's answer is wrong.

    Parameters
    ----------
    what : str
        One sentence saying what is wrong.
    inputs : mapping, optional
        The inputs the function was called with.
    expected, got : optional
        The right answer and the student's answer.
    mistake : str, optional
        The name of the likely mistake, when one was identified.
    """

    def __init__(
        self,
        what: str,
        *,
        inputs: Mapping[str, Any] | None = None,
        expected: Any = None,
        got: Any = None,
        mistake: str | None = None,
    ) -> None:
        super().__init__(what)
        self.what = what
        self.inputs = dict(inputs or {})
        self.expected = expected
        self.got = got
        self.mistake = mistake

    def describe(self) -> str:
        lines = [self.what]
        flat = {k: v for k, v in self.inputs.items() if np.ndim(v) < 2}
        if flat:
            shown = ", ".join(f"{k}={format_array(v, inline=True)}" for k, v in flat.items())
            lines.append(f"input:    {shown}")
        for k, v in self.inputs.items():
            if k not in flat:
                lines.append(f"input {k} =")
                lines.append(" " * 10 + format_array(v).replace("\n", "\n" + " " * 10))
        if self.expected is not None:
            lines.append("expected: " + format_array(self.expected).replace("\n", "\n" + " " * 10))
        if self.got is not None:
            lines.append("got:      " + format_array(self.got).replace("\n", "\n" + " " * 10))
        if self.mistake:
            lines.append(f"likely mistake: {self.mistake}")
        return "\n".join(lines)


class ForbiddenCallError(RuntimeError):
    """Raised when a submission calls the urkin function its exercise asks it to write."""


@dataclass(frozen=True)
class Check:
    """One graded property of an exercise.

    ``run(student_function, rng)`` returns normally when the property holds and raises
    :class:`Mismatch` otherwise.
    """

    description: str
    points: float
    run: Callable[[Callable[..., Any], np.random.Generator], None]


@dataclass(frozen=True)
class Exercise:
    """A function to write, with the checks that grade it.

    Parameters
    ----------
    id : str
        ``"<lesson>.<k>"``, for example ``"2.1"``.
    function : str
        Name of the function the student defines.
    title : str
        What the function does, in a few words.
    checks : tuple of Check
    forbidden : tuple of str
        Dotted names of urkin functions that do the exercise's work; a submission that calls
        them earns nothing for the exercise.
    builds_on : tuple of str
        Ids of earlier exercises whose functions this one usually calls; when both lose
        points, the feedback says to fix the earlier one first.
    """

    id: str
    function: str
    title: str
    checks: tuple[Check, ...]
    forbidden: tuple[str, ...] = ()
    builds_on: tuple[str, ...] = ()

    @property
    def points(self) -> float:
        """Total points of the exercise."""
        return float(sum(c.points for c in self.checks))

    @property
    def lesson(self) -> str:
        """Two-digit lesson number, ``"02"`` for exercise ``"2.1"``."""
        return f"{int(self.id.split('.')[0]):02d}"


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
    """Outcome of grading one exercise; serialisable with :meth:`to_dict`."""

    exercise: str
    function: str
    title: str
    points: float
    earned: float
    status: str  # passed, partial, failed, not attempted, missing, error, timeout, crashed…
    message: str = ""
    checks: list[CheckResult] = field(default_factory=list)

    @property
    def mistakes(self) -> list[str]:
        """Names of the mistakes the checks identified."""
        return sorted({c.mistake for c in self.checks if c.mistake})

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> ExerciseResult:
        values = dict(data)
        values["checks"] = [CheckResult(**c) for c in values.get("checks", [])]
        return cls(**values)

    def report(self) -> str:
        """The text a student reads: the verdict first, then each check."""
        head = f"Exercise {self.exercise} · {self.function} — {_points(self.earned)}/"
        head += f"{_points(self.points)} points"
        lines = [f"{head}: {self.status}"]
        if self.message:
            lines.append("  " + self.message.replace("\n", "\n  "))
        for c in self.checks:
            mark = "✓" if c.earned == c.points else "✗"
            lines.append(f"  {mark} {c.description} ({_points(c.earned)}/{_points(c.points)})")
            if c.message:
                lines.append("      " + c.message.replace("\n", "\n      "))
        return "\n".join(lines)


def _points(x: float) -> str:
    return f"{x:g}"


def register(exercise: Exercise) -> Exercise:
    """Add an exercise to the registry (ids are unique)."""
    if exercise.id in _REGISTRY:
        raise ValueError(f"exercise {exercise.id} is registered twice")
    _REGISTRY[exercise.id] = exercise
    return exercise


def exercise(exercise_id: str) -> Exercise:
    """Look up an exercise by id, for example ``exercise("2.1")``."""
    _load_lessons()
    try:
        return _REGISTRY[str(exercise_id)]
    except KeyError:
        known = ", ".join(sorted(_REGISTRY, key=_id_key))
        raise KeyError(f"no exercise {exercise_id!r}; known exercises: {known}") from None


def exercises_for_lesson(lesson: str | int) -> list[Exercise]:
    """Exercises of a lesson (``"02"`` or ``2``), in order."""
    _load_lessons()
    number = f"{int(lesson):02d}"
    return sorted(
        (e for e in _REGISTRY.values() if e.lesson == number), key=lambda e: _id_key(e.id)
    )


def _id_key(exercise_id: str) -> tuple[int, ...]:
    return tuple(int(part) for part in exercise_id.split("."))


def _load_lessons() -> None:
    import urkin.exercises  # noqa: F401  (importing the package registers every lesson)


# ----------------------------------------------------------------------------- helpers


def format_array(value: Any, inline: bool = False) -> str:
    """Short, deterministic text for numbers and arrays (4 decimals, no ``-0``)."""
    if isinstance(value, str):
        return value
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return repr(value)[:200]
    if array.ndim == 0:
        return f"{float(array) + 0.0:.4f}"
    text = np.array2string(
        np.round(array, 4) + 0.0,
        precision=4,
        suppress_small=True,
        separator=", ",
        max_line_width=90,
        threshold=40,
    )
    return " ".join(text.split()) if inline else text


def as_array(value: Any, shape: tuple[int, ...], what: str) -> np.ndarray:
    """Convert a student's return value to a float array of the given shape, or say why not."""
    if value is None:
        raise Mismatch(f"{what} returned None: is a `return` statement missing?")
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise Mismatch(
            f"{what} must return numbers (an array of shape {shape}); got {type(value).__name__}"
        ) from None
    if array.shape != shape:
        raise Mismatch(f"{what} must return an array of shape {shape}; got shape {array.shape}")
    if not np.all(np.isfinite(array)):
        raise Mismatch(f"{what} returned NaN or infinity", got=array)
    return array


def require_rotation(R: np.ndarray, what: str, inputs: Mapping[str, Any]) -> None:
    """Raise :class:`Mismatch` unless ``R`` is a rotation matrix (orthonormal, det = +1)."""
    if not np.allclose(R.T @ R, np.eye(3), atol=1e-9):
        raise Mismatch(f"{what} is not orthonormal: RᵀR ≠ I", inputs=inputs, got=R)
    if np.linalg.det(R) < 0:
        raise Mismatch(f"{what} has det = −1: a reflection, not a rotation", inputs=inputs, got=R)


def require_transform(T: np.ndarray, what: str, inputs: Mapping[str, Any]) -> None:
    """Raise :class:`Mismatch` unless ``T`` is a homogeneous rigid-body transform."""
    if not np.allclose(T[3], [0, 0, 0, 1]):
        raise Mismatch(f"{what}: the last row must be [0, 0, 0, 1]", inputs=inputs, got=T)
    require_rotation(T[:3, :3], f"the 3×3 block of {what}", inputs)


def identify_mistake(
    got: np.ndarray,
    hypotheses: Mapping[str, Callable[[], Any]],
    atol: float = 1e-6,
) -> str | None:
    """Name of the first wrong hypothesis whose answer equals ``got``, or None."""
    for name, compute in hypotheses.items():
        try:
            candidate = np.asarray(compute(), dtype=float)
        except Exception:  # a hypothesis that cannot be evaluated simply does not match
            continue
        if candidate.shape == np.shape(got) and np.allclose(candidate, got, rtol=0, atol=atol):
            return name
    return None


def compare(
    got: np.ndarray,
    expected: np.ndarray,
    *,
    what: str,
    inputs: Mapping[str, Any],
    hypotheses: Mapping[str, Callable[[], Any]] | None = None,
    atol: float = 1e-9,
) -> None:
    """Raise :class:`Mismatch` (naming a likely mistake) unless ``got ≈ expected``."""
    if np.allclose(got, expected, rtol=0, atol=atol):
        return
    mistake = identify_mistake(got, hypotheses or {}, atol=max(atol, 1e-6))
    raise Mismatch(what, inputs=inputs, expected=expected, got=got, mistake=mistake)


# ----------------------------------------------------------------------------- running


def _seed_for(seed: int, exercise_id: str, index: int) -> np.random.Generator:
    return np.random.default_rng([seed, zlib.crc32(exercise_id.encode()), index])


def _where_in_student_code(exc: BaseException, function: Callable[..., Any]) -> str:
    """'line 4 of dh_transform' for the innermost frame of the student's code, if any."""
    code = getattr(function, "__code__", None)
    filename = code.co_filename if code else None
    frames = traceback.extract_tb(exc.__traceback__)
    for frame in reversed(frames):
        if frame.filename == filename:
            line = f": `{frame.line.strip()}`" if frame.line else ""
            return f" (in {frame.name}, line {frame.lineno}{line})"
    return ""


def _explain(exc: BaseException, function: Callable[..., Any]) -> tuple[str, str]:
    """(status, message) for an exception escaping a check."""
    where = _where_in_student_code(exc, function)
    if isinstance(exc, NotImplementedError):
        return "not attempted", "not attempted yet: the function still raises NotImplementedError"
    if isinstance(exc, ForbiddenCallError):
        return "forbidden", str(exc)
    if isinstance(exc, SystemExit):
        return "error", f"the function called sys.exit(){where}; grading needs it to return"
    if isinstance(exc, MemoryError):
        return "error", f"ran out of memory{where}: is an array far larger than it should be?"
    if isinstance(exc, RecursionError):
        return "error", f"infinite recursion{where}"
    text = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
    return "error", f"raised {type(exc).__name__}{': ' + text if text else ''}{where}"


def run_exercise(
    exercise_or_id: Exercise | str,
    function: Callable[..., Any],
    seed: int = VISIBLE_SEED,
) -> ExerciseResult:
    """Run every check of an exercise on a student's function; never raises.

    Parameters
    ----------
    exercise_or_id : Exercise or str
    function : callable
        The student's implementation.
    seed : int
        Seed of the random inputs.  Notebook check cells use :data:`VISIBLE_SEED`; the grader
        draws a fresh one per grading run.

    Returns
    -------
    ExerciseResult
    """
    ex = exercise_or_id if isinstance(exercise_or_id, Exercise) else exercise(exercise_or_id)
    result = ExerciseResult(ex.id, ex.function, ex.title, ex.points, 0.0, "failed")
    if not callable(function):
        result.status = "missing"
        result.message = (
            f"{ex.function} must be a function; got {type(function).__name__}. "
            f"Run the cell that defines it, then this one."
        )
        return result
    fatal: tuple[str, str] | None = None
    for index, chk in enumerate(ex.checks):
        outcome = CheckResult(chk.description, chk.points, 0.0)
        if fatal is None:
            try:
                with warnings.catch_warnings(), np.errstate(all="ignore"):
                    warnings.simplefilter("ignore")
                    chk.run(function, _seed_for(seed, ex.id, index))
                outcome.earned = chk.points
            except Mismatch as exc:
                outcome.message = exc.describe()
                outcome.mistake = exc.mistake
            except (Exception, SystemExit) as exc:
                status, message = _explain(exc, function)
                if status in ("not attempted", "forbidden"):
                    fatal = (status, message)
                else:
                    outcome.message = message
        result.checks.append(outcome)
    result.earned = float(sum(c.earned for c in result.checks))
    if fatal is not None:
        result.status, result.message = fatal
        result.earned = 0.0
        for c in result.checks:
            c.earned = 0.0
    elif result.earned == result.points:
        result.status = "passed"
    elif result.earned > 0:
        result.status = "partial"
    if result.mistakes and fatal is None:
        result.message = "likely mistake: " + "; ".join(result.mistakes)
    return result


def link_dependencies(results: list[ExerciseResult]) -> None:
    """Add "fix exercise 2.1 first" to results that lost points while an exercise they build on
    lost points too."""
    by_id = {r.exercise: r for r in results}
    for result in results:
        if result.earned == result.points:
            continue
        for earlier_id in exercise(result.exercise).builds_on:
            earlier = by_id.get(earlier_id)
            if earlier is not None and earlier.earned < earlier.points:
                note = (
                    f"{result.function} usually calls your {earlier.function}, which lost "
                    f"points in exercise {earlier_id}: fix that one first"
                )
                result.message = f"{result.message}\n{note}" if result.message else note


def run_exercises(
    functions: Mapping[str, Callable[..., Any]], seed: int = VISIBLE_SEED
) -> list[ExerciseResult]:
    """Run several exercises (id → function) and link their dependencies."""
    results = [run_exercise(exercise_id, f, seed) for exercise_id, f in functions.items()]
    link_dependencies(results)
    return results


def check(exercise_id: str, function: Callable[..., Any], seed: int = VISIBLE_SEED) -> None:
    """Check a student's function and print a short report; never raises.

    This is what a notebook's check cell calls: ``check("2.1", dh_transform)``.

    Parameters
    ----------
    exercise_id : str
        For example ``"2.1"``.
    function : callable
        The student's function.
    seed : int
        Seed of the test inputs (the visible seed by default).
    """
    try:
        result = run_exercise(exercise_id, function, seed)
        text = result.report()
    except KeyboardInterrupt:
        raise
    except BaseException as exc:  # the check cell itself must never fail
        text = f"could not check exercise {exercise_id}: {type(exc).__name__}: {exc}"
    print(text, file=sys.stdout)
