"""What a check uses to judge an answer: conversion, tolerances, comparisons, named mistakes.

A check raises :class:`Mismatch` when an answer is wrong.  The message says what was expected,
shows the inputs, the expected and received values and — when a known wrong hypothesis
reproduces the answer — names the likely mistake.

Tolerances follow the answer's precision: a float64 answer is compared to the tolerance the
exercise states (1e-9 unless it says otherwise), a float32 answer to float32's precision, so a
correct single-precision implementation passes.  So is a float64 answer built on one of the
student's earlier functions that answers in float32 (:func:`float32_helper`): it cannot be
more precise than that function.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any
from weakref import WeakKeyDictionary

import numpy as np

__all__ = [
    "FLOAT32_ULPS",
    "Float32Helper",
    "Mismatch",
    "angles_tolerance",
    "as_array",
    "close",
    "compare",
    "float32_helper",
    "format_array",
    "identify_mistake",
    "judged_like",
    "require_rotation",
    "require_transform",
    "require_varying",
    "tolerance",
    "unless_right",
]


def format_array(value: Any, inline: bool = False) -> str:
    """Short, deterministic text for numbers and arrays (4 decimals, no ``-0``).

    Examples
    --------
    >>> format_array([1.0, -0.0, 1 / 3], inline=True)
    '[1.    , 0.    , 0.3333]'
    >>> format_array(121)
    '121'
    """
    if isinstance(value, str):
        return value
    if isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_)):
        return str(int(value))  # a count or a seed: as it is
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


def _describe_inputs(inputs: Mapping[str, Any]) -> list[str]:
    lines = []
    flat = {k: v for k, v in inputs.items() if isinstance(v, str) or np.ndim(v) < 2}
    if flat:
        shown = ", ".join(f"{k}={format_array(v, inline=True)}" for k, v in flat.items())
        lines.append(f"input:    {shown}")
    for k, v in inputs.items():
        if k not in flat:
            lines.append(f"input {k} =")
            lines.append(" " * 10 + format_array(v).replace("\n", "\n" + " " * 10))
    return lines


class Mismatch(Exception):
    """Raised by a check when the student's answer is wrong.

    Parameters
    ----------
    what : str
        One sentence saying what is wrong.
    inputs : mapping, optional
        The inputs the function was called with (shown, so that the case can be reproduced).
    expected, got : optional
        The right answer and the student's answer.
    mistake : str, optional
        The name of the likely mistake, when one was identified.
    difference : str, optional
        How far apart ``expected`` and ``got`` are, when that is not visible in 4 decimals.
    """

    def __init__(
        self,
        what: str,
        *,
        inputs: Mapping[str, Any] | None = None,
        expected: Any = None,
        got: Any = None,
        mistake: str | None = None,
        difference: str | None = None,
    ) -> None:
        super().__init__(what)
        self.what = what
        self.inputs = dict(inputs or {})
        self.expected = expected
        self.got = got
        self.mistake = mistake
        self.difference = difference

    def describe(self) -> str:
        """The report's text: what is wrong, the inputs, expected, got, the likely mistake."""
        lines = [self.what, *_describe_inputs(self.inputs)]
        if self.expected is not None:
            lines.append("expected: " + format_array(self.expected).replace("\n", "\n" + " " * 10))
        if self.got is not None:
            lines.append("got:      " + format_array(self.got).replace("\n", "\n" + " " * 10))
        if self.difference:
            lines.append(self.difference)
        if self.mistake:
            lines.append(f"likely mistake: {self.mistake}")
        return "\n".join(lines)


# The float32 tolerance, in units of float32's ε (1.19e-7) times max(1, scale): four times the
# largest error of honest float32 answers on the checks' inputs.  Measured with every lesson's
# reference functions, their results and the earlier functions they call cast to float32
# (chains such as forward kinematics over float32 DH links included): at most 2 ε · max(1,
# scale), on seeds 0, 1 and 20261123.
FLOAT32_ULPS = 8.0


def tolerance(atol: float, like: Any = None, scale: float = 1.0) -> float:
    """The tolerance to compare an answer with: ``atol``, or its dtype's precision if coarser.

    Parameters
    ----------
    atol : float
        The tolerance the exercise states for float64 answers.
    like : array_like, optional
        The student's answer (or what it was computed from); a float32 (or coarser) one gets
        ``FLOAT32_ULPS`` ε of float32, times ``max(1, scale)``.
    scale : float
        Size of the numbers compared.

    Examples
    --------
    >>> tolerance(1e-9, np.zeros(3))
    1e-09
    >>> round(tolerance(1e-9, np.zeros(3, dtype=np.float32)), 9)
    9.54e-07
    """
    dtype = getattr(like, "dtype", None)
    if dtype is None or not np.issubdtype(dtype, np.floating) or dtype.itemsize >= 8:
        return atol
    # float32 (and anything coarser, which float32's precision judges)
    return max(atol, FLOAT32_ULPS * float(np.finfo(np.float32).eps) * max(1.0, abs(scale)))


def angles_tolerance(atol: float, like: Any, rates: Any, q: Any) -> float:
    """:func:`tolerance` for what is computed from joint angles ``q``, such as the pose an IK
    answer reaches: a float32 answer's rounding of each ``q_i`` (float32's ε ·
    ``max(1, |q_i|)``) moves it by up to ``‖rates[:, i]‖`` times that, so ``scale`` is the sum
    of these.

    Parameters
    ----------
    atol : float
        The tolerance for float64 answers.
    like : array_like
        The student's answer (its dtype decides).
    rates : array_like, shape (k, n)
        How fast each joint moves what is compared (a Jacobian, rows [v; ω] at the flange).
    q : array_like, shape (n,)
        The joint angles.
    """
    rates = np.asarray(rates, dtype=float)
    q = np.abs(np.asarray(q, dtype=float))
    scale = float(np.sum(np.linalg.norm(rates, axis=0) * np.maximum(1.0, q)))
    return tolerance(atol, like, scale)


def _is_float32(value: Any) -> bool:
    dtype = getattr(value, "dtype", None)
    return dtype is not None and np.issubdtype(dtype, np.floating) and dtype.itemsize < 8


@dataclass(frozen=True)
class Float32Helper:
    """An earlier function of the student's that answers in float32, which an answer uses.

    ``name`` is the function, ``exercise`` its exercise id and ``sample`` one of its answers:
    passed as ``like`` to :func:`tolerance` (or as ``helper`` to :func:`compare`), it judges an
    answer built on the function at float32's precision, whatever dtype the answer has.
    """

    name: str
    exercise: str
    sample: np.ndarray

    @property
    def note(self) -> str:
        """What the feedback says about it."""
        return (
            f"your {self.name} ({self.exercise}) returns float32, so an answer built on it is "
            "judged at float32's precision"
        )


def judged_like(got: Any, helper: Float32Helper | None) -> Any:
    """What an answer ``got`` is as precise as, for :func:`tolerance`'s ``like``: itself, or
    the float32 ``helper`` it is built on when it is not float32 itself."""
    return helper.sample if helper is not None and not _is_float32(got) else got


#: The float32 helpers found for each submission's functions (:func:`float32_helper`): the
#: checks of one exercise ask again and again, and each probe is a call of the student's code.
_FOUND: WeakKeyDictionary = WeakKeyDictionary()


def float32_helper(
    sub: Any, function: str, probes: Mapping[str, tuple[str, tuple[Any, ...]]]
) -> Float32Helper | None:
    """The first of the student's earlier functions that ``function`` uses (directly or not)
    and that answers in float32, or None.

    Parameters
    ----------
    sub : Submission
        The student's functions.
    function : str
        The exercise's function, whose answer is judged.
    probes : mapping
        name → (exercise id, arguments): an earlier function and the arguments to call it with
        to see its dtype.
    """
    found = _FOUND.setdefault(sub, {})
    if function not in found:
        found[function] = _probe_float32(sub, function, probes)
    return found[function]


def _probe_float32(sub: Any, function: str, probes: Mapping) -> Float32Helper | None:
    """:func:`float32_helper`, by calling the earlier functions."""
    from urkin.course.submission import StudentRaised

    try:
        used = set(sub.code(function))
    except Exception:  # the code cannot be read: probe every earlier function defined
        used = set(probes)
    for name, (exercise_id, args) in probes.items():
        if name == function or name not in used or not sub.has(name):
            continue
        try:
            value = sub.call(name, *args)
        except (StudentRaised, TypeError, ValueError):  # a function that cannot be probed
            continue
        values = value if isinstance(value, (tuple, list)) else [value]
        for part in values:
            if _is_float32(part):
                return Float32Helper(name, exercise_id, np.asarray(part))
    return None


def _shape_of(value: Any) -> tuple[int, ...] | None:
    try:
        return np.shape(np.asarray(value, dtype=float))
    except (TypeError, ValueError):
        return None


def as_array(
    value: Any,
    shape: tuple[int, ...],
    what: str,
    inputs: Mapping[str, Any] | None = None,
    wrong_shapes: Mapping[tuple[int, ...], str] | None = None,
) -> np.ndarray:
    """The student's return value as a real array of ``shape``, or a :class:`Mismatch` saying why
    not (naming the mistake when the answer has one of the ``wrong_shapes``).  Float32 and
    float16 answers keep their dtype (see :func:`tolerance`)."""
    try:
        return _as_array(value, shape, what, inputs)
    except Mismatch as exc:
        if exc.mistake is None and wrong_shapes:
            exc.mistake = wrong_shapes.get(_shape_of(value))
        raise


def _as_array(
    value: Any, shape: tuple[int, ...], what: str, inputs: Mapping[str, Any] | None
) -> np.ndarray:
    if value is None:
        raise Mismatch(f"{what} returned None: is a `return` statement missing?", inputs=inputs)
    try:
        array = np.asarray(value)
        if array.dtype == object:
            array = array.astype(float)
    except (TypeError, ValueError):
        raise Mismatch(
            f"{what} must return numbers (an array of shape {shape}); got {type(value).__name__}",
            inputs=inputs,
        ) from None
    if np.issubdtype(array.dtype, np.complexfloating):
        if np.all(np.isfinite(array)) and np.abs(array.imag).max(initial=0.0) <= 1e-12:
            array = array.real
        else:
            raise Mismatch(f"{what} returned complex numbers", inputs=inputs, got=array.real)
    if not (np.issubdtype(array.dtype, np.floating) and array.dtype.itemsize <= 8):
        if not (np.issubdtype(array.dtype, np.number) or array.dtype == bool):
            raise Mismatch(
                f"{what} must return numbers; got an array of {array.dtype}", inputs=inputs
            )
        array = array.astype(float)
    if array.shape != shape:
        raise Mismatch(
            f"{what} must return an array of shape {shape}; got shape {array.shape}",
            inputs=inputs,
        )
    if not np.all(np.isfinite(array)):
        raise Mismatch(f"{what} returned NaN or infinity", inputs=inputs, got=array)
    return array


def close(got: Any, expected: Any, atol: float = 1e-9, like: Any = None) -> bool:
    """Whether ``got`` matches ``expected`` to :func:`tolerance`: the precision of ``like``, the
    student's answer ``got`` was computed from (``got`` itself by default)."""
    expected = np.asarray(expected, dtype=float)
    scale = float(np.abs(expected).max(initial=0.0))
    if np.shape(got) != expected.shape:
        return False
    like = got if like is None else like
    return bool(np.allclose(got, expected, rtol=0, atol=tolerance(atol, like, scale)))


def require_rotation(
    R: np.ndarray, what: str, inputs: Mapping[str, Any], helper: Float32Helper | None = None
) -> None:
    """Raise :class:`Mismatch` unless ``R`` is a rotation matrix (orthonormal, det = +1); to
    float32's precision when ``R`` is float32 or built on a float32 ``helper``."""
    like = judged_like(R, helper)
    if not close(R.T @ R, np.eye(3), 1e-9, like):
        raise Mismatch(
            f"{what} is not orthonormal: RᵀR ≠ I",
            inputs=inputs,
            got=R,
            difference=None if helper is None else helper.note,
        )
    if np.linalg.det(R.astype(float)) < 0:
        raise Mismatch(f"{what} has det = −1: a reflection, not a rotation", inputs=inputs, got=R)


def require_transform(
    T: np.ndarray, what: str, inputs: Mapping[str, Any], helper: Float32Helper | None = None
) -> None:
    """Raise :class:`Mismatch` unless ``T`` is a homogeneous rigid-body transform (see
    :func:`require_rotation` for ``helper``)."""
    like = judged_like(T, helper)
    if not close(T[3], [0, 0, 0, 1], 1e-12, like):
        raise Mismatch(f"{what}: the last row must be [0, 0, 0, 1]", inputs=inputs, got=T)
    require_rotation(T[:3, :3], f"the 3×3 block of {what}", inputs, helper)


def identify_mistake(
    got: Any,
    hypotheses: Mapping[str, Callable[[], Any]],
    atol: float = 1e-6,
    right: Any = None,
) -> str | None:
    """Name of the first wrong hypothesis whose answer equals ``got``, or None.  A hypothesis
    that gives the ``right`` answer for these inputs names nothing."""
    right = None if right is None else np.asarray(right, dtype=float)
    for name, compute in hypotheses.items():
        try:
            with np.errstate(all="ignore"):
                candidate = np.asarray(compute(), dtype=float)
        except Exception:  # a hypothesis that cannot be evaluated simply does not match
            continue
        if (
            right is not None
            and candidate.shape == right.shape
            and np.allclose(candidate, right, rtol=0, atol=1e-6)
        ):
            continue
        if candidate.shape == np.shape(got) and close(got, candidate, atol):
            return name
    return None


def compare(
    got: np.ndarray,
    expected: Any,
    *,
    what: str,
    inputs: Mapping[str, Any],
    hypotheses: Mapping[str, Callable[[], Any]] | None = None,
    atol: float = 1e-9,
    helper: Float32Helper | None = None,
) -> None:
    """Raise :class:`Mismatch` (naming a likely mistake) unless ``got`` matches ``expected``
    within :func:`tolerance` ``(atol, got)`` — at float32's precision when ``got`` is built on
    a float32 ``helper``."""
    expected = np.asarray(expected, dtype=float)
    like = judged_like(got, helper)
    if close(got, expected, atol, like):
        return
    mistake = identify_mistake(got, hypotheses or {}, max(atol, 1e-6), right=expected)
    difference = None
    if np.shape(got) == expected.shape:
        gap = float(np.abs(np.asarray(got, dtype=float) - expected).max())
        scale = float(np.abs(expected).max(initial=0.0))
        if gap < 1e-3:  # the 4-decimal display would hide it
            difference = (
                f"largest difference {gap:.1e}; the tolerance is {tolerance(atol, like, scale):.0e}"
            )
            if helper is not None and like is helper.sample:
                difference += f" ({helper.note})"
    raise Mismatch(
        what, inputs=inputs, expected=expected, got=got, mistake=mistake, difference=difference
    )


def require_varying(answers: list[Any], what: str, inputs: Mapping[str, Any]) -> None:
    """Raise :class:`Mismatch` when every answer is the same although the inputs were not: a
    constant (an identity matrix, a stub) is not an answer, however well-formed."""
    if len(answers) > 1 and all(np.array_equal(answers[0], a) for a in answers[1:]):
        raise Mismatch(
            f"{what} returned the same value for {len(answers)} different inputs",
            inputs=inputs,
            got=answers[0],
        )


def unless_right(hypotheses: Mapping[str, Callable[[], Any]], right: Any) -> dict:
    """The hypotheses, each refusing to name a mistake where it gives the ``right`` answer (to
    1e-6) for these inputs: at q = 0, degrees and radians agree."""

    def guarded(compute: Callable[[], Any]) -> Callable[[], np.ndarray]:
        def hypothesis() -> np.ndarray:
            value = np.asarray(compute(), dtype=float)
            if value.shape == np.shape(right) and np.allclose(value, right, rtol=0, atol=1e-6):
                raise ValueError("this hypothesis gives the right answer here")
            return value

        return hypothesis

    return {name: guarded(compute) for name, compute in hypotheses.items()}
