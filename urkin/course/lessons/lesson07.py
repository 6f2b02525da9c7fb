"""Lesson 07 — closed-form (geometric) inverse kinematics."""

from __future__ import annotations

import ast
import re
from collections.abc import Callable, Mapping
from fractions import Fraction
from functools import partial
from typing import Any

import numpy as np

from urkin.analytic_ik import ik_analytic
from urkin.course import concepts
from urkin.course.compare import (
    Float32Helper,
    Mismatch,
    as_array,
    close,
    float32_helper,
    format_array,
    judged_like,
    tolerance,
)
from urkin.course.exercise import Check, Exercise, Lesson
from urkin.course.inputs import random_arm, random_rotation
from urkin.course.lab import LAB_BASE_IN_WORLD, LAB_LINKS, LAB_OFFSET, fk_lab, ik_lab, lab_robot
from urkin.course.submission import StudentRaised
from urkin.kinematics import fk
from urkin.transforms import make_transform, rot_x, rot_z, rotation_angle, wrap_angles

# bound here, in the lesson module, which the grading guard never touches
_fk_lab, _ik_lab, _ik_analytic, _fk = fk_lab, ik_lab, ik_analytic, fk
_LAB = lab_robot()

_L1, _L2, _L3, _L4, _L5, _L6, _L7, _L8, _L9, _L10 = LAB_LINKS
_OFFSET = _L2 - _L4 + _L6  # 0.110 m: the wrist's sideways offset from the arm's plane
_BASE = np.array(LAB_BASE_IN_WORLD)
_TURN, _DEGREE_TURN = 2 * np.pi, 360.0

# ------------------------------------------------------------------------ shared: mistakes

_ARCTAN = (
    "the lab sheet's arctan(y/x): it loses the quadrant when x < 0 (behind the base); use "
    "atan2(y, x)"
)
_UNSIGNED = (
    "the lab sheet's r = √(x² + y²): it loses the sign of the reach when wrist 1 is behind the "
    "base axis; use the signed r = x3 cos θ1 + y3 sin θ1"
)
_ARCTAN_HR = (
    "the lab sheet's arctan(h/r) in θ2: once r is signed it can be negative, and arctan loses "
    "the quadrant; use atan2 (or planar_2r on (r, −h))"
)
_DEGREES = "returned degrees: the course works in radians"
_MILLIMETRES = (
    "millimetres: the sheet's 110, 83, 141 … are millimetres; in metres they are 0.110 "
    "(L2 − L4 + L6), 0.083 (L7), 0.141 (L8 + L10) — use OFFSET and L1 … L10"
)
_ATAN2_SWAPPED = "atan2(x, y): numpy's arctan2 takes y first, arctan2(y, x)"

# numbers of the lab sheet in millimetres (and 1000, a conversion), which metres never need
_MILLIMETRE_NUMBERS = {110, 83, 59, 82, 141, 152, 120, 244, 93, 213, 53.5, 150, 1000}


def _millimetre_literals(sub: Any, function: str) -> bool:
    """Whether the student's function (or a function it uses) writes a length in millimetres."""
    try:
        sources = sub.code(function)
    except Exception:  # reading the code is only for naming a mistake
        return False
    for source in sources.values():
        try:
            tree = ast.parse(source)
        except SyntaxError:
            continue
        for node in ast.walk(tree):
            if (
                isinstance(node, ast.Constant)
                and isinstance(node.value, (int, float))
                and not isinstance(node.value, bool)
                and node.value in _MILLIMETRE_NUMBERS
            ):
                return True
    return False


def _unwired(value: Any, shape: tuple[int, ...]) -> Any:
    """Undo what the plain-data copy does to numpy scalars and 0-d arrays (it gives them shape
    (1,)): a float32 θ1, or a tuple of float32 angles, as the student returned it."""
    if isinstance(value, np.ndarray) and value.shape == (1,) and shape == ():
        return value.reshape(())
    if (
        isinstance(value, (list, tuple))
        and len(shape) == 1
        and len(value) == shape[0]
        and any(isinstance(v, np.ndarray) for v in value)
        and all(
            (isinstance(v, np.ndarray) and v.shape == (1,)) or isinstance(v, (int, float))
            for v in value
        )
    ):
        parts = [np.reshape(v, ()) for v in value]
        narrow = [v.dtype for v in parts if v.dtype.kind == "f" and v.dtype.itemsize < 8]
        return np.array(parts, dtype=min(narrow, key=lambda d: d.itemsize) if narrow else None)
    return value


def _answer(
    sub: Any,
    function: str,
    value: Any,
    shape: tuple[int, ...],
    what: str,
    inputs: Mapping[str, Any],
    nan_mistake: str | None = None,
) -> np.ndarray:
    """:func:`as_array`, naming the likely mistake when the answer is NaN."""
    try:
        return as_array(_unwired(value, shape), shape, what, inputs)
    except Mismatch as exc:
        if exc.mistake is None and "NaN" in exc.what:
            if nan_mistake is not None:
                exc.mistake = nan_mistake
            elif _millimetre_literals(sub, function):
                exc.mistake = _MILLIMETRES
        raise


def _domain_error(exc: StudentRaised) -> bool:
    """Whether the student's function raised the math module's NaN: ``math.acos(1.0000001)``."""
    return exc.kind == "ValueError" and "math domain error" in exc.message


def _no_value(exc: StudentRaised, what: str, mistake: str | None) -> Mismatch:
    """A ``math domain error`` as the Mismatch its NaN would have been."""
    where = f" ({exc.where})" if exc.where else ""
    return Mismatch(
        f"{what} raised ValueError: math domain error{where} — a square root, acos or asin of "
        "a number out of its range",
        inputs=exc.inputs,
        mistake=mistake,
    )


def _gap(got: Any, expected: Any, period: float = _TURN) -> np.ndarray:
    """|got − expected| up to whole turns of ``period``."""
    difference = np.asarray(got, dtype=float) - np.asarray(expected, dtype=float)
    return np.abs(difference - period * np.round(difference / period))


def _same_angles(
    got: np.ndarray, expected: Any, atol: float, period: float = _TURN, like: Any = None
) -> bool:
    """Whether the angles ``got`` equal ``expected`` up to whole turns, to
    :func:`tolerance` (the precision of ``like``, ``got`` itself by default)."""
    expected = np.asarray(expected, dtype=float)
    if np.shape(got) != expected.shape or not np.all(np.isfinite(expected)):
        return False
    scale = float(np.abs(expected).max(initial=0.0))
    like = got if like is None else like
    return bool(np.all(_gap(got, expected, period) <= tolerance(atol, like, scale)))


Hypotheses = Mapping[str, tuple[Callable[[], Any], float]]


def _radians(compute: Callable[[], Any]) -> tuple[Callable[[], Any], float]:
    return compute, _TURN


def _degrees(compute: Callable[[], Any]) -> tuple[Callable[[], Any], float]:
    return (lambda: np.degrees(compute())), _DEGREE_TURN


def _identify(
    got: np.ndarray, hypotheses: Hypotheses, right: Any = None, atol: float = 1e-6
) -> str | None:
    """The first wrong hypothesis whose angles equal ``got`` up to whole turns; a hypothesis
    that gives the ``right`` angles for these inputs tells nothing and is skipped."""
    for name, (compute, period) in hypotheses.items():
        try:
            with np.errstate(all="ignore"):
                candidate = np.asarray(compute(), dtype=float)
        except Exception:  # a hypothesis that cannot be evaluated simply does not match
            continue
        if right is not None and _same_angles(candidate, right, atol, period):
            continue
        if _same_angles(got, candidate, atol, period):
            return name
    return None


def _identify_nan(got: np.ndarray, hypotheses: Hypotheses) -> str | None:
    """The first wrong hypothesis with no value exactly where ``got`` is NaN, and the same
    angles elsewhere (at least two of them: one may be a constant, such as θ5)."""
    missing = ~np.isfinite(got)
    if np.count_nonzero(~missing) < 2:
        return None
    for name, (compute, period) in hypotheses.items():
        try:
            with np.errstate(all="ignore"):
                candidate = np.asarray(compute(), dtype=float)
        except Exception:  # a hypothesis that cannot be evaluated simply does not match
            continue
        if candidate.shape != got.shape:
            continue
        if np.array_equal(~np.isfinite(candidate), missing) and _same_angles(
            got[~missing], candidate[~missing], 1e-6, period
        ):
            return name
    return None


def _largest_gap(
    got: np.ndarray, expected: Any, atol: float, helper: Float32Helper | None = None
) -> str | None:
    gap = float(_gap(got, expected).max())
    if gap >= 1e-3:  # visible in the 4-decimal display
        return None
    scale = float(np.abs(np.asarray(expected, dtype=float)).max(initial=0.0))
    note = "" if helper is None else f" ({helper.note})"
    return (
        f"largest difference {gap:.1e} rad (up to whole turns); the tolerance is "
        f"{tolerance(atol, judged_like(got, helper), scale):.0e}{note}"
    )


# the earlier functions ik_lab is built on, and arguments that show their dtype
_EARLIER = {
    "planar_2r": ("7.2", (0.25, 0.1, 0.2, 0.15)),
    "lab_theta1": ("7.1", (0.3, 0.2)),
}


def _compare_angles(
    got: np.ndarray,
    expected: Any,
    *,
    what: str,
    inputs: Mapping[str, Any],
    hypotheses: Hypotheses,
    atol: float,
    helper: Float32Helper | None = None,
) -> None:
    """Raise :class:`Mismatch` (naming a likely mistake) unless the angles ``got`` equal
    ``expected`` up to whole turns (at float32's precision when ``got`` is built on a float32
    ``helper``)."""
    if _same_angles(got, expected, atol, like=judged_like(got, helper)):
        return
    raise Mismatch(
        what,
        inputs=inputs,
        expected=expected,
        got=got,
        mistake=_identify(got, hypotheses, right=expected),
        difference=_largest_gap(got, expected, atol, helper),
    )


# ---------------------------------------------------------------------------- 7.1 lab_theta1

_UR_THETA1 = "UR's joint 1 (the lab's θ1 + π): lab_theta1 returns the lab's θ1; ik_lab adds π later"
_OFF_BY_PI = "off by π"  # behind the base: the sheet's arctan, or UR's joint 1 (see _theta1_pi)


def _theta1(xc, yc):
    return np.arctan2(yc, xc) - np.arcsin(_OFFSET / np.hypot(xc, yc))


def _theta1_hypotheses(xc: float, yc: float) -> dict:
    rho = np.hypot(xc, yc)
    return {
        _OFF_BY_PI: _radians(lambda: _theta1(xc, yc) + np.pi),
        "θc + θB: that is the other tangent (the other shoulder branch); the lab's arm uses "
        "θ1 = θc − θB": _radians(lambda: np.arctan2(yc, xc) + np.arcsin(_OFFSET / rho)),
        "arccos(0.110/ρ) where the figure has arcsin: θB is the angle opposite the 0.110 m "
        "side": _radians(lambda: np.arctan2(yc, xc) - np.arccos(_OFFSET / rho)),
        _ATAN2_SWAPPED: _radians(lambda: np.arctan2(xc, yc) - np.arcsin(_OFFSET / rho)),
        "ρ² in place of ρ = √(x² + y²)": _radians(
            lambda: np.arctan2(yc, xc) - np.arcsin(_OFFSET / rho**2)
        ),
        "θB missing: the offset wrist costs θB = asin(0.110/ρ), θ1 = θc − θB": _radians(
            lambda: np.arctan2(yc, xc)
        ),
        "arctan(0.110/ρ) where the figure has arcsin (0.110 m is opposite θB, ρ the "
        "hypotenuse)": _radians(lambda: np.arctan2(yc, xc) - np.arctan(_OFFSET / rho)),
        "θB − θc: θ1 = θc − θB": _radians(lambda: -_theta1(xc, yc)),
        _DEGREES: _degrees(lambda: _theta1(xc, yc)),
        _DEGREES + " (and the sheet's arctan)": _degrees(
            lambda: np.arctan(yc / xc) - np.arcsin(_OFFSET / rho)
        ),
    }


def _wrist_centre(rng: np.random.Generator, side: str) -> tuple[float, float]:
    """A wrist centre in reach (ρ > 0.110 m), in front of the base axis (x > 0) or behind."""
    while True:
        rho, angle = rng.uniform(0.115, 0.6), rng.uniform(-np.pi, np.pi)
        x, y = rho * np.cos(angle), rho * np.sin(angle)
        if (x > 0.03) if side == "front" else (x < -0.03):
            return float(x), float(y)


def _theta1_answer(sub, xc: float, yc: float) -> np.ndarray:
    inputs = {"x_c": xc, "y_c": yc}
    return _answer(sub, "lab_theta1", sub.lab_theta1(xc, yc), (), "lab_theta1(x_c, y_c)", inputs)


def _theta1_pi(sub, xc: float, yc: float) -> str | None:
    """Which mistake an answer off by π behind the base is: the sheet's arctan (right in
    front of the base) or UR's joint 1 (off by π in front too)."""
    try:
        mirrored = _theta1_answer(sub, -xc, -yc)  # the same ρ, in front of the base
    except (Mismatch, StudentRaised):
        return None
    if _same_angles(mirrored, _theta1(-xc, -yc), 1e-6):
        return _ARCTAN
    return _UR_THETA1 if _same_angles(mirrored, _theta1(-xc, -yc) + np.pi, 1e-6) else None


def _theta1_nan(sub, xc: float, yc: float) -> str | None:
    """The mistake behind a NaN answer: a hypothesis that has no value here either and
    matches the student's answer for a wrist centre further out in the same direction."""
    scale = 0.55 / np.hypot(xc, yc)
    try:
        further = _theta1_answer(sub, xc * scale, yc * scale)
    except Mismatch as exc:  # NaN even 0.55 m out, where 0.110/ρ is far from 1
        return _MILLIMETRES if "NaN" in exc.what else None
    except StudentRaised as exc:
        return _MILLIMETRES if _domain_error(exc) else None
    mistake = _identify(
        further,
        _theta1_hypotheses(xc * scale, yc * scale),
        right=_theta1(xc * scale, yc * scale),
    )
    if mistake is not None:
        with np.errstate(all="ignore"):
            here = _theta1_hypotheses(xc, yc)[mistake][0]()
        if not np.all(np.isfinite(here)):
            return mistake
    return None


def _theta1_matches(side: str, sub, rng):
    what = (
        "θ1 = atan2(y_c, x_c) − asin(0.110 / √(x_c² + y_c²)), in the lab's convention"
        if side == "front"
        else "behind the base (x_c < 0) θ1 must still point the arm at the wrist centre"
    )
    for _ in range(8):
        xc, yc = _wrist_centre(rng, side)
        inputs = {"x_c": xc, "y_c": yc}
        try:
            got = _theta1_answer(sub, xc, yc)
        except Mismatch as exc:
            if exc.mistake is None and "NaN" in exc.what:
                exc.mistake = _theta1_nan(sub, xc, yc)
            raise
        except StudentRaised as exc:
            if not _domain_error(exc):
                raise
            mistake = _MILLIMETRES if _millimetre_literals(sub, "lab_theta1") else None
            raise _no_value(exc, "lab_theta1", mistake or _theta1_nan(sub, xc, yc)) from None
        expected = _theta1(xc, yc)
        if _same_angles(got, expected, 1e-9):
            continue
        mistake = _identify(got, _theta1_hypotheses(xc, yc), right=expected)
        if mistake == _OFF_BY_PI:
            mistake = _UR_THETA1 if side == "front" else _theta1_pi(sub, xc, yc)
        raise Mismatch(
            what,
            inputs=inputs,
            expected=expected,
            got=got,
            mistake=mistake,
            difference=_largest_gap(got, expected, 1e-9),
        )


# ---------------------------------------------------------------------------- 7.2 planar_2r

_OTHER_ELBOW_2R = "the other elbow (θb = −acos(…)): the exercise asks for θb = +acos(…) ≥ 0"
_NOT_CLIPPED = (
    "cos θb not clipped to [−1, 1]: on the ring's edge rounding puts it a hair past ±1, where "
    "arccos has no value"
)


def _elbow(x, y, l1, l2):
    return np.arccos(np.clip((x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2), -1.0, 1.0))


def _first(direction, b, l1, l2):
    return direction - np.arctan2(l2 * np.sin(b), l1 + l2 * np.cos(b))


def _planar(x, y, l1, l2):
    b = _elbow(x, y, l1, l2)
    return np.array([_first(np.arctan2(y, x), b, l1, l2), b])


def _planar_hypotheses(x: float, y: float, l1: float, l2: float) -> dict:
    b = _elbow(x, y, l1, l2)
    inner = np.pi - b  # the triangle's angle at the elbow
    return {
        "the lab sheet's arctan(y/x) for the tip's direction: it loses the quadrant when "
        "x < 0; use atan2(y, x)": _radians(lambda: [_first(np.arctan(y / x), b, l1, l2), b]),
        "the triangle's inner angle at the elbow (π − θb): θb is the turn from the first "
        "link to the second, cos θb = (x² + y² − l1² − l2²) / (2 l1 l2)": _radians(
            lambda: [_first(np.arctan2(y, x), inner, l1, l2), inner]
        ),
        "θa = atan2(y, x) + atan2(…): the sign belongs to the other elbow; for θb ≥ 0 "
        "subtract": _radians(
            lambda: [np.arctan2(y, x) + np.arctan2(l2 * np.sin(b), l1 + l2 * np.cos(b)), b]
        ),
        "l1 and l2 swapped in atan2(l2 sin θb, l1 + l2 cos θb)": _radians(
            lambda: [np.arctan2(y, x) - np.arctan2(l1 * np.sin(b), l2 + l1 * np.cos(b)), b]
        ),
        _ATAN2_SWAPPED: _radians(lambda: [_first(np.arctan2(x, y), b, l1, l2), b]),
        "arctan(l2 sin θb / (l1 + l2 cos θb)): it loses the quadrant when l1 + l2 cos θb < 0; "
        "use atan2": _radians(
            lambda: [np.arctan2(y, x) - np.arctan(l2 * np.sin(b) / (l1 + l2 * np.cos(b))), b]
        ),
        "θa = atan2(y, x): the first link is turned away from the tip's direction by "
        "atan2(l2 sin θb, l1 + l2 cos θb)": _radians(lambda: [np.arctan2(y, x), b]),
        "returned [θb, θa]: the order is [θa, θb]": _radians(lambda: _planar(x, y, l1, l2)[::-1]),
        _DEGREES: _degrees(lambda: _planar(x, y, l1, l2)),
    }


def _matching(got: np.ndarray, hypotheses: Hypotheses, names, right: Any = None) -> list[str]:
    """The hypotheses among ``names`` whose angles equal ``got`` up to whole turns (leaving
    out those that give the ``right`` angles here)."""
    found = []
    for name in names:
        compute, period = hypotheses[name]
        try:
            with np.errstate(all="ignore"):
                candidate = np.asarray(compute(), dtype=float)
        except Exception:  # a hypothesis that cannot be evaluated simply does not match
            continue
        if right is not None and _same_angles(candidate, right, 1e-6, period):
            continue
        if _same_angles(got, candidate, 1e-6, period):
            found.append(name)
    return found


# x > 0, and folded so far that l1 + l2 cos θb < 0: tells apart mistakes that give the same
# angles elsewhere (arctan(y/x) and arctan in the angle at the origin behind the base, …)
_PLANAR_PROBE = (0.268328 * np.cos(0.4), 0.268328 * np.sin(0.4), 0.2, 0.4)


def _planar_mistake(sub, got: np.ndarray, x, y, l1, l2) -> str | None:
    hypotheses = _planar_hypotheses(x, y, l1, l2)
    names = _matching(got, hypotheses, hypotheses, right=_planar(x, y, l1, l2))
    if len(names) < 2:
        return names[0] if names else None
    try:  # more than one mistake gives these angles here: ask where they differ
        probe = np.asarray(_unwired(sub.planar_2r(*_PLANAR_PROBE), (2,)), dtype=float)
    except (StudentRaised, TypeError, ValueError):
        return names[0]
    there = _matching(probe, _planar_hypotheses(*_PLANAR_PROBE), names)
    return there[0] if len(there) == 1 else names[0]


def _tip(angles: np.ndarray, l1: float, l2: float) -> np.ndarray:
    a, b = np.asarray(angles, dtype=float)
    tip = np.array([l1 * np.cos(a) + l2 * np.cos(a + b), l1 * np.sin(a) + l2 * np.sin(a + b)])
    dtype = getattr(angles, "dtype", None)
    return tip.astype(dtype) if dtype is not None and dtype.itemsize < 8 else tip  # its precision


def _planar_case(
    rng: np.random.Generator, side: str, folded: bool = False
) -> tuple[float, float, float, float]:
    """A target strictly inside the reachable ring, with x > 0 or x < 0; ``folded``: with a
    long second link folded back so far that l1 + l2 cos θb < 0."""
    while True:
        l1, l2 = rng.uniform(0.15, 0.5), rng.uniform(0.1, 0.45)
        if folded:
            l1, l2 = min(l1, l2), max(l1, l2)
            if (l1 + 0.02) / l2 > 0.9:
                continue
            cos_b = rng.uniform(-0.97, -(l1 + 0.02) / l2)
            reach = np.sqrt(l1 * l1 + l2 * l2 + 2 * l1 * l2 * cos_b)
            if not abs(l1 - l2) + 0.02 <= reach <= l1 + l2 - 0.02:
                continue
        else:
            reach = rng.uniform(abs(l1 - l2) + 0.02, l1 + l2 - 0.02)
        angle = rng.uniform(-np.pi, np.pi)
        x, y = reach * np.cos(angle), reach * np.sin(angle)
        if (x > 0.01) if side == "front" else (x < -0.01):
            return float(x), float(y), float(l1), float(l2)


def _cosines(x: float, y: float, l1: float, l2: float) -> tuple[list, list]:
    """cos θb and the cosine of the angle at the origin as students compute them."""
    d, s = np.hypot(x, y), np.sqrt(x * x + y * y)
    elbow = [
        (x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2),
        (x * x + y * y - (l1 * l1 + l2 * l2)) / (2 * l1 * l2),
        (d**2 - l1**2 - l2**2) / (2 * l1 * l2),
        (x**2 + y**2 - l1**2 - l2**2) / 2 / l1 / l2,
        (s**2 - l1**2 - l2**2) / (2 * l1 * l2),
    ]
    origin = [
        (l1**2 + d**2 - l2**2) / (2 * l1 * d),
        (l1**2 + s**2 - l2**2) / (2 * l1 * s),
        (l2**2 - l1**2 - d**2) / (-2 * l1 * d),
        (x * x + y * y + l1 * l1 - l2 * l2) / (2 * l1 * s),
        (l2 * l2 - l1 * l1 - s * s) / (-2 * l1 * s),
    ]
    return elbow, origin


def _edge_case(rng: np.random.Generator, outer: bool) -> tuple[float, float, float, float]:
    """A target on the ring's outer (stretched) or inner (folded) edge, with x > 0: exactly in
    the ring, but where rounding puts cos θb, computed the usual ways, a hair past ±1 (and the
    cosine of the angle at the origin, which the text does not ask to clip, within [−1, 1])."""
    for _ in range(10_000):
        l1, l2 = rng.uniform(0.15, 0.5), rng.uniform(0.1, 0.45)
        if abs(l1 - l2) < 0.05:
            continue
        reach = l1 + l2 if outer else abs(l1 - l2)
        angle = rng.uniform(-0.45 * np.pi, 0.45 * np.pi)
        x, y = float(reach * np.cos(angle)), float(reach * np.sin(angle))
        elbow, origin = _cosines(x, y, l1, l2)
        if not (np.all(np.abs(elbow) > 1.0) and np.all(np.abs(origin) <= 1.0)):
            continue
        # the target as given (exact binary fractions) lies in the ring, on or just inside
        # its edge: only rounding in the student's arithmetic leaves it
        squared = Fraction(x) ** 2 + Fraction(y) ** 2
        edge = (Fraction(float(l1)) + (1 if outer else -1) * Fraction(float(l2))) ** 2
        if (squared <= edge) if outer else (squared >= edge):
            return x, y, float(l1), float(l2)
    raise RuntimeError("no edge target found")  # pragma: no cover


def _planar_inputs(x, y, l1, l2):
    return {"x": x, "y": y, "l1": l1, "l2": l2}


def _planar_reaches(x, y, l1, l2, sub, where: str, edge: bool = False) -> None:
    inputs = _planar_inputs(x, y, l1, l2)
    try:
        value = sub.planar_2r(x, y, l1, l2)
    except StudentRaised as exc:
        if edge and _domain_error(exc):
            raise _no_value(exc, "planar_2r", _NOT_CLIPPED) from None
        raise
    got = _answer(
        sub,
        "planar_2r",
        value,
        (2,),
        "planar_2r(x, y, l1, l2)",
        inputs,
        nan_mistake=_NOT_CLIPPED if edge else None,
    )
    reached = _tip(got, l1, l2)
    # on the edge the elbow angle is a double root: an acos of 1 − ε moves by √(2ε), so a
    # correct answer reaches the tip to about √ of its precision
    atol = max(1e-6, float(np.sqrt(tolerance(1e-12, got)))) if edge else 1e-9
    if not close(reached, [x, y], atol):
        raise Mismatch(
            "the tip (l1 cos θa + l2 cos(θa + θb), l1 sin θa + l2 sin(θa + θb)) must reach "
            f"(x, y) {where}",
            inputs=inputs,
            expected=[x, y],
            got=reached,
            mistake=_planar_mistake(sub, got, x, y, l1, l2),
            difference=f"your angles [θa, θb] = {format_array(got, inline=True)}",
        )
    if not edge and not np.sin(float(got[1])) > 0:
        raise Mismatch(
            "return the elbow θb = +acos(…), between 0 and π: yours reaches (x, y) with the "
            "other elbow",
            inputs=inputs,
            expected=_planar(x, y, l1, l2),
            got=got,
            mistake=_OTHER_ELBOW_2R,
        )


def _planar_check(side: str, sub, rng):
    where = "for targets with x > 0" if side == "front" else "for targets with x < 0 too"
    for k in range(6):
        _planar_reaches(*_planar_case(rng, side, folded=k % 3 == 2), sub, where)


def _planar_edges(sub, rng):
    for outer in (True, False, True, False):
        where = "on the ring's outer edge (stretched)" if outer else "on its inner edge (folded)"
        _planar_reaches(*_edge_case(rng, outer), sub, where, edge=True)


# -------------------------------------------------------------------------------- 7.3 ik_lab

_LAB_ANGLES = (
    "lab angles returned: UR controller angles are the lab's plus LAB_TO_UR = [π, 0, 0, −π/2, 0, 0]"
)
_SHEET = (
    "the lab sheet's formulas as printed: its arctan(y/x) loses the quadrant behind the base, "
    "its r = √(x² + y²) the sign of the reach, its arctan(h/r) the quadrant of θ2; use atan2 "
    "and the signed r"
)
_OTHER_ELBOW = "the other elbow (θ3 < 0): the lab's branch has θ3 > 0 (planar_2r's θb ≥ 0)"
_NOT_WRAPPED = (
    "angles not wrapped into (−π, π]: wrap after adding LAB_TO_UR (wrap_angles or "
    "arctan2(sin, cos))"
)
_WRAPPED_POSITIVE = "angles wrapped into [0, 2π); the lesson wraps into (−π, π]"


def _lab_model(
    xw,
    yw,
    zw,
    yaw,
    *,
    heading="atan2",
    tangent=-1.0,
    base=-1.0,
    plate=-1.0,
    signed=True,
    direction="atan2",
    plane=-1.0,
    elbow=1.0,
    height=_L8 + _L10,
    shoulder=_L1,
    back=_L7,
    base_z=None,
    theta4=lambda t2, t3: -t2 - t3,
    theta5=-np.pi / 2,
    theta6=lambda t1, yaw: np.pi / 2 + t1 - yaw,
    offset=LAB_OFFSET,
):
    """The lab's solution (UR angles, unwrapped), with its usual mistakes switchable."""
    x, y = xw + base * _BASE[0], yw + base * _BASE[1]
    z = zw + (base if base_z is None else base_z) * _BASE[2]
    xc, yc = x + plate * _L9 * np.cos(yaw), y + plate * _L9 * np.sin(yaw)
    rho = np.hypot(xc, yc)
    towards = np.arctan(yc / xc) if heading == "arctan" else np.arctan2(yc, xc)
    arc = np.arccos if heading == "arccos" else np.arcsin
    t1 = towards + tangent * arc(_OFFSET / rho)
    x3 = xc - back * np.cos(t1) + _OFFSET * np.sin(t1)
    y3 = yc - back * np.sin(t1) - _OFFSET * np.cos(t1)
    r = x3 * np.cos(t1) + y3 * np.sin(t1) if signed else np.hypot(x3, y3)
    h = z + height - shoulder
    t3 = elbow * np.arccos((r * r + h * h - _L3 * _L3 - _L5 * _L5) / (2 * _L3 * _L5))
    beta = np.arctan2(_L5 * np.sin(t3), _L3 + _L5 * np.cos(t3))
    t2 = (-np.arctan(h / r) if direction == "arctan" else np.arctan2(plane * h, r)) - beta
    lab = np.array([t1, t2, t3, theta4(t2, t3), theta5, theta6(t1, yaw)])
    return lab + offset


def _lab_row(xw, yw, zw, yaw, row):
    pose = make_transform(rot_z(yaw) @ rot_x(np.pi), [xw, yw, zw])
    return _ik_analytic(_LAB, pose[None], return_mask=True)[0][0, row]


def _lab_hypotheses(xw, yw, zw, yaw) -> dict:
    t = (xw, yw, zw, yaw)
    model = partial(_lab_model, *t)
    half = np.array([np.pi, 0.0, 0.0, 0.0, 0.0, 0.0])
    return {
        _ARCTAN: _radians(lambda: model(heading="arctan")),
        _UNSIGNED: _radians(lambda: model(signed=False)),
        _ARCTAN_HR: _radians(lambda: model(direction="arctan")),
        _SHEET: _radians(lambda: model(heading="arctan", signed=False, direction="arctan")),
        _ARCTAN + "; and its r = √(x² + y²)": _radians(
            lambda: model(heading="arctan", signed=False)
        ),
        _ARCTAN + "; and its arctan(h/r)": _radians(
            lambda: model(heading="arctan", direction="arctan")
        ),
        _LAB_ANGLES: _radians(lambda: model(offset=0.0)),
        "LAB_TO_UR subtracted: UR angles are the lab's plus [π, 0, 0, −π/2, 0, 0]": _radians(
            lambda: model(offset=-LAB_OFFSET)
        ),
        "only θ1's π of LAB_TO_UR added: θ4 needs its −π/2 too": _radians(
            lambda: model(offset=half)
        ),
        "only θ4's −π/2 of LAB_TO_UR added: θ1 needs its π too": _radians(
            lambda: model(offset=LAB_OFFSET - half)
        ),
        _DEGREES: _degrees(lambda: model()),
        "yaw_w converted from degrees: it is already in radians": _radians(
            lambda: _lab_model(xw, yw, zw, np.radians(yaw))
        ),
        "+ arcsin in θ1: that is the other tangent; the lab's θ1 = θc − θB": _radians(
            lambda: model(tangent=1.0)
        ),
        "arccos(0.110/ρ) in θ1 where the lab has arcsin": _radians(lambda: model(heading="arccos")),
        "the shoulder '−' branch (row 6 of urkin.ik_analytic): the lab's θ1 comes from "
        "lab_theta1": _radians(lambda: _lab_row(*t, 6)),
        _OTHER_ELBOW: _radians(lambda: model(elbow=-1.0)),
        "θ5 = +π/2: the lab's gripper points down with θ5 = −π/2": _radians(
            lambda: model(theta5=np.pi / 2)
        ),
        "θ6 with the wrong sign: θ6 = π/2 + θ1 − ψ": _radians(
            lambda: model(theta6=lambda t1, yaw: yaw - t1 - np.pi / 2)
        ),
        "θ6 without its π/2: θ6 = π/2 + θ1 − ψ": _radians(
            lambda: model(theta6=lambda t1, yaw: t1 - yaw)
        ),
        "planar_2r(r, h, …) in place of planar_2r(r, −h, …): in the lab's plane θ2 and θ3 turn "
        "downwards": _radians(lambda: model(plane=1.0)),
        "BASE_IN_TABLE added: base-frame coordinates are the table's minus BASE_IN_TABLE": (
            _radians(lambda: model(base=1.0))
        ),
        "BASE_IN_TABLE not subtracted: the target is in the table frame, the formulas in the "
        "base frame": _radians(lambda: model(base=0.0)),
        "x_c = x + L9 cos ψ: the wrist centre is L9 back from the cup, x_c = x − L9 cos ψ": (
            _radians(lambda: model(plate=1.0))
        ),
        "the cup used as the wrist centre: step back L9 along the yaw first": _radians(
            lambda: model(plate=0.0)
        ),
        "h without L10: wrist 1 is L8 + L10 = 0.141 m above the cup": _radians(
            lambda: model(height=_L8)
        ),
        "h without L8: wrist 1 is L8 + L10 = 0.141 m above the cup": _radians(
            lambda: model(height=_L10)
        ),
        "h without − L1: h is the height above the shoulder axis, L1 above the base": (
            _radians(lambda: model(shoulder=0.0))
        ),
        "z not moved into the base frame: z = z_w − 0.01": _radians(lambda: model(base_z=0.0)),
        "r without the step back L7 from the wrist centre to wrist 1": _radians(
            lambda: model(back=0.0)
        ),
        "θ4 = θ2 + θ3: the wrist stays level with θ4 = −θ2 − θ3": _radians(
            lambda: model(theta4=lambda t2, t3: t2 + t3)
        ),
    }


def _target_inputs(target) -> dict:
    return dict(zip(("x_w", "y_w", "z_w", "yaw_w"), target))


def _where(xw, yw, zw, yaw) -> tuple[float, float]:
    """The wrist centre's x in the base frame and the signed reach r of wrist 1."""
    xc = xw - _BASE[0] - _L9 * np.cos(yaw)
    yc = yw - _BASE[1] - _L9 * np.sin(yaw)
    t1 = _theta1(xc, yc)
    return float(xc), float(xc * np.cos(t1) + yc * np.sin(t1) - _L7)


def _lab_target(rng: np.random.Generator, kind: str) -> tuple[float, float, float, float]:
    """A gripper target the lab's branch reaches, away from its singular edges: with the wrist
    centre in front of the base axis, behind it, or in front with wrist 1 behind the base axis
    (r < 0, the arm reaching back over its shoulder)."""
    while True:
        yaw, zw = rng.uniform(-np.pi, np.pi), rng.uniform(0.0, 0.25)
        if kind == "over the shoulder":  # the wrist centre just outside the 0.110 m circle
            rho, angle = rng.uniform(0.113, 0.136), rng.uniform(-0.5 * np.pi, 0.5 * np.pi)
            xw = _BASE[0] + rho * np.cos(angle) + _L9 * np.cos(yaw)
            yw = _BASE[1] + rho * np.sin(angle) + _L9 * np.sin(yaw)
        else:
            xw, yw = rng.uniform(-0.5, 0.2), rng.uniform(-0.2, 0.5)
        target = (float(xw), float(yw), float(zw), float(yaw))
        xc, r = _where(*target)
        try:
            q = _ik_lab(*target)
        except ValueError:
            continue
        rho = np.hypot(xc, target[1] - _BASE[1] - _L9 * np.sin(yaw))
        if rho < _OFFSET + 0.002 or abs(np.sin(q[2])) < 0.2:
            continue  # near the shoulder or elbow singularity
        if kind == "over the shoulder" and xc > 0.03 and r < -0.005:
            return target
        if kind == "behind" and xc < -0.03 and r > 0.005:
            return target
        if kind == "front" and xc > 0.03 and r > 0.005:
            return target


# targets that every formula of the sheet, and every mistake named here, reaches
_EASY_TARGETS = ((0.0, 0.40, 0.05, 1.75), (0.1, 0.3, 0.1, 1.0))


def _lab_nan(sub) -> str | None:
    """The mistake behind a NaN answer, when the answer is NaN for the easiest targets too."""
    for target in _EASY_TARGETS:
        try:
            q = np.asarray(sub.ik_lab(*target), dtype=float)
        except StudentRaised as exc:
            if _domain_error(exc):
                continue
            return None
        except (TypeError, ValueError):
            return None
        if np.all(np.isfinite(q)):
            return None
    return _MILLIMETRES


def _lab_answer(sub, target) -> np.ndarray:
    inputs = _target_inputs(target)
    what = "ik_lab(x_w, y_w, z_w, yaw_w)"
    try:
        return _answer(sub, "ik_lab", sub.ik_lab(*target), (6,), what, inputs)
    except StudentRaised as exc:
        if not _domain_error(exc):
            raise
        mistake = _MILLIMETRES if _millimetre_literals(sub, "ik_lab") else None
        raise _no_value(exc, "ik_lab", mistake or _lab_nan(sub)) from None
    except Mismatch as exc:
        if exc.mistake is None and "NaN" in exc.what and exc.got is not None:
            exc.mistake = _identify_nan(np.asarray(exc.got), _lab_hypotheses(*target))
            exc.mistake = exc.mistake or _lab_nan(sub)
        raise


def _round_trip(sub, target, where: str) -> np.ndarray:
    """The student's angles for ``target``, which fk_lab must take back to the target."""
    q = _lab_answer(sub, target)
    inputs = _target_inputs(target)
    if np.abs(q).max() > 4 * np.pi:
        raise Mismatch(
            "ik_lab returned joint angles far outside ±2π: angles are in radians",
            inputs=inputs,
            expected=_ik_lab(*target),
            got=q,
            mistake=_identify(q, _lab_hypotheses(*target), right=_ik_lab(*target)),
        )
    reached = _fk_lab(q.astype(float))
    expected = np.array([*target[:3], wrap_angles(target[3])])
    error = np.r_[reached[:3] - expected[:3], wrap_angles(reached[3] - expected[3])]
    helper = float32_helper(sub, "ik_lab", _EARLIER)
    atol = tolerance(1e-8, judged_like(q, helper), np.pi)
    if not np.abs(error).max() <= atol:
        gap = float(np.abs(error).max())
        note = "" if helper is None else f" ({helper.note})"
        raise Mismatch(
            f"fk_lab(ik_lab(x_w, y_w, z_w, yaw_w)) must give back the target {where}",
            inputs=inputs,
            expected=expected,
            got=reached,
            mistake=_identify(q, _lab_hypotheses(*target), right=_ik_lab(*target)),
            difference=f"your ik_lab returned q = {format_array(q, inline=True)}; largest "
            f"difference {gap:.1e} (m, and rad for the yaw); the tolerance is {atol:.0e}{note}",
        )
    return q


def _lab_round_trips(kind: str, sub, rng):
    where = {
        "front": "(wrist centre in front of the base)",
        "behind": "(wrist centre behind the base, x_c < 0)",
        "over the shoulder": "(wrist 1 behind the base axis, r < 0)",
    }[kind]
    for _ in range(6):
        _round_trip(sub, _lab_target(rng, kind), where)


def _lab_branch(sub, rng):
    helper = float32_helper(sub, "ik_lab", _EARLIER)
    for kind in ("front", "behind", "front", "behind"):
        target = _lab_target(rng, kind)
        q = _lab_answer(sub, target)
        _compare_angles(
            q,
            _ik_lab(*target),
            what="the lab's branch: θ1 from lab_theta1 (shoulder '+'), θ5 = −π/2 and the elbow "
            "θ3 > 0 (compared up to whole turns)",
            inputs=_target_inputs(target),
            hypotheses=_lab_hypotheses(*target),
            atol=1e-8,
            helper=helper,
        )


def _wrap_target(rng: np.random.Generator, kind: str, theta6: bool):
    """A target whose unwrapped UR angles leave (−π, π]: θ1 (the lab's θ1 > 0), and θ6 too
    when ``theta6``."""
    while True:
        target = _lab_target(rng, kind)
        raw = _lab_model(*target)
        if raw[0] > np.pi and (not theta6 or not -np.pi < raw[5] <= np.pi):
            return target


def _in_range(q: np.ndarray, like: Any = None) -> bool:
    like = q if like is None else like
    return bool(np.all((q > -np.pi) & (q <= np.pi + tolerance(1e-12, like, np.pi))))


def _lab_wrapped(sub, rng):
    for k, kind in enumerate(("front", "behind") * 3):
        target = _wrap_target(rng, kind, theta6=k < 4)
        q = _round_trip(sub, target, "(and every angle in (−π, π])")
        if not _in_range(q, judged_like(q, float32_helper(sub, "ik_lab", _EARLIER))):
            positive = np.all((q >= 0) & (q < _TURN))
            raise Mismatch(
                "return UR angles wrapped into (−π, π], as wrap_angles does",
                inputs=_target_inputs(target),
                expected=_ik_lab(*target),
                got=q,
                mistake=_WRAPPED_POSITIVE if positive else _NOT_WRAPPED,
            )


# ----------------------------------------------------------------------------- 7.4 wrist_angles


def _wrist_reference(T, theta1) -> np.ndarray:
    """Both (θ5, θ6) rows for a flange pose and θ1: θ5 ≥ 0 first."""
    x, y, z = T[:3, 0], T[:3, 1], T[:3, 2]
    z1 = np.array([np.sin(theta1), -np.cos(theta1), 0.0])
    a, b = x @ z1, -(y @ z1)  # cos θ6 sin θ5 and sin θ6 sin θ5
    theta5 = np.arctan2(np.hypot(a, b), z @ z1)
    theta6 = np.arctan2(b, a)
    return np.array([[theta5, theta6], [-theta5, float(wrap_angles(theta6 + np.pi))]])


def _wrist_call(sub, T, theta1) -> np.ndarray:
    inputs = {"T": T, "theta1": theta1}
    shapes = {(4,): "four numbers in one row: return [[θ5, θ6], [−θ5, θ6 + π]], shape (2, 2)"}
    return as_array(sub.wrist_angles(T, theta1), (2, 2), "wrist_angles(T, theta1)", inputs, shapes)


def _wrist_mistake(got, T, theta1) -> str | None:
    """Name the usual slips by comparing with their answers (angles modulo 2π)."""
    right = _wrist_reference(T, theta1)
    x, y, z = T[:3, 0], T[:3, 1], T[:3, 2]
    z1 = np.array([np.sin(theta1), -np.cos(theta1), 0.0])
    slips = {
        "θ6 of the second branch not turned by π: flipping θ5 turns the wrist over, "
        "θ6 → θ6 + π": np.array([right[0], [right[1, 0], right[0, 1]]]),
        "θ5 from the wrong axis: cos θ5 = z · z1 with z1 = (sin θ1, −cos θ1, 0), the axis of "
        "joints 2-4": np.array(
            [
                [np.arccos(np.clip(z @ [np.cos(theta1), np.sin(theta1), 0.0], -1, 1)), right[0, 1]],
                [
                    -np.arccos(np.clip(z @ [np.cos(theta1), np.sin(theta1), 0.0], -1, 1)),
                    right[1, 1],
                ],
            ]
        ),
        "the sign of y · z1: sin θ6 sin θ5 = −y · z1": np.array(
            [
                [right[0, 0], np.arctan2(y @ z1, x @ z1)],
                [right[1, 0], float(wrap_angles(np.arctan2(y @ z1, x @ z1) + np.pi))],
            ]
        ),
    }
    for name, candidate in slips.items():
        if np.abs(wrap_angles(got.astype(float) - candidate)).max() < 1e-6 and not (
            np.abs(wrap_angles(candidate - right)).max() < 1e-6
        ):
            return name
    return None


def _wrist_configurations(rng, q5_size: tuple[float, float] | None = None):
    arm = random_arm(rng)
    q = rng.uniform(-np.pi, np.pi, 6)
    if q5_size is None:
        while abs(np.sin(q[4])) < 0.1:
            q[4] = rng.uniform(-np.pi, np.pi)
    else:
        q[4] = 10 ** rng.uniform(*q5_size) * rng.choice([-1.0, 1.0])
    return arm, q


def _wrist_rows_match(sub, rng, q5_size=None, atol5=1e-9, atol6=1e-9):
    for _ in range(8 if q5_size is None else 4):
        arm, q = _wrist_configurations(rng, q5_size)
        T = _fk(arm, q)
        got = _wrist_call(sub, T, q[0])
        right = _wrist_reference(T, q[0])
        gap = np.abs(wrap_angles(got.astype(float) - right))
        if not (
            gap[:, 0].max() <= tolerance(atol5, got) and gap[:, 1].max() <= tolerance(atol6, got)
        ):
            near = q5_size is not None
            raise Mismatch(
                "the rows must be [θ5, θ6] with θ5 ≥ 0 and then [−θ5, θ6 + π] (angles compared "
                f"modulo 2π, θ5 to {atol5:g}, θ6 to {atol6:g})"
                + (f"; here sin θ5 is only {np.sin(q[4]):.1e}" if near else ""),
                inputs={"T": T, "theta1": q[0], "the configuration": q},
                expected=right,
                got=got,
                mistake=(
                    "θ5 from arccos(z · z1): next to the wrist singularity the cosine is 1 to "
                    "within round-off and arccos loses the angle; use θ5 = atan2(|sin θ5|, "
                    "cos θ5) with |sin θ5| = ‖(x · z1, y · z1)‖"
                    if near and gap[:, 0].max() > tolerance(atol5, got)
                    else _wrist_mistake(got, T, q[0])
                ),
            )


def _wrist_generic(sub, rng):
    _wrist_rows_match(sub, rng)


def _wrist_near_singular(sub, rng):
    _wrist_rows_match(sub, rng, q5_size=(-8.5, -7.5), atol6=1e-6)


def _wrist_is_a_solution(sub, rng):
    """Each row, with θ1 and the θ234 it implies (step 4), gives the flange's orientation: the
    rotation of a UR arm depends on θ1, θ2 + θ3 + θ4, θ5 and θ6 only."""
    for _ in range(4):
        arm, q = _wrist_configurations(rng)
        T = _fk(arm, q)
        got = _wrist_call(sub, T, q[0]).astype(float)
        x_z, y_z, z_z = T[2, :3]
        for theta5, theta6 in got:
            c5, s5, c6, s6 = np.cos(theta5), np.sin(theta5), np.cos(theta6), np.sin(theta6)
            q234 = np.arctan2(c5 * (c6 * x_z - s6 * y_z) - s5 * z_z, s6 * x_z + c6 * y_z)
            R = _fk(arm, np.array([q[0], q234, 0.0, 0.0, theta5, theta6]))[:3, :3]
            if rotation_angle(R, T[:3, :3]) > 1e-8:
                raise Mismatch(
                    "every row (θ5, θ6), with θ1 and θ2 + θ3 + θ4 from step 4, must give the "
                    "flange's orientation",
                    inputs={"T": T, "theta1": q[0]},
                    expected=_wrist_reference(T, q[0]),
                    got=got,
                    mistake=_wrist_mistake(got, T, q[0]),
                )


# --------------------------------------------------------------------------- 7.5 solution_count

_MARGIN = 0.005  # m: every pose is this far from each reach boundary
_WRIST_MARGIN = 0.05  # |sin θ5| at least this on every θ1 branch


def _branch_geometry(robot, T, *, clip=False, d1=True, d5=True, d6=True):
    """ρ − d4 (the wrist point's distance from the base axis, less d4) and, for each of the
    four (θ1, θ5) branches, (wrist 1's distance from the shoulder axis, |sin θ5|); no branches
    when ρ < d4 (with ``clip``: θ1 from an arccos clipped to [−1, 1], as if it existed).  The
    switches leave out d1, d5 or d6 (the usual slips)."""
    T = np.asarray(T, dtype=float)
    z = T[:3, 2]
    wrist = T[:3, 3] - (robot.d6 if d6 else 0.0) * z  # joint 5's centre
    rho = float(np.hypot(wrist[0], wrist[1]))
    rows: list[tuple[float, float]] = []
    if rho < robot.d4 and not clip:
        return rho - robot.d4, rows
    tangent = float(np.arccos(np.clip(robot.d4 / rho, -1.0, 1.0)))
    for side in (1.0, -1.0):
        theta1 = np.arctan2(wrist[1], wrist[0]) + side * tangent + np.pi / 2
        z1 = np.array([np.sin(theta1), -np.cos(theta1), 0.0])  # the axis of joints 2-4
        u = np.array([np.cos(theta1), np.sin(theta1), 0.0])  # the arm's direction
        across = np.cross(z1, z)  # the wrist link (z4) is at right angles to z1 and to z
        sin5 = float(np.linalg.norm(across))
        link = across / sin5 if sin5 > 0.0 else across  # (at the wrist singularity: no margin)
        for flip in (1.0, -1.0):
            wrist1 = wrist - (robot.d5 if d5 else 0.0) * flip * link
            reach = float(np.hypot(u @ wrist1, wrist1[2] - (robot.d1 if d1 else 0.0)))
            rows.append((reach, sin5))
    return rho - robot.d4, rows


def _ring(robot) -> tuple[float, float]:
    return abs(abs(robot.a2) - abs(robot.a3)), abs(robot.a2) + abs(robot.a3)


def _closing(robot, rows) -> list[bool]:
    small, big = _ring(robot)
    return [small <= reach <= big for reach, _ in rows]


def _model_count(robot, T, **switches) -> int:
    """2 solutions (the two elbows) for each (θ1, θ5) branch whose triangle closes."""
    _, rows = _branch_geometry(robot, T, **switches)
    return 2 * sum(_closing(robot, rows))


def _with_margins(robot, T) -> bool:
    """Whether T is at least _MARGIN from every reach boundary and _WRIST_MARGIN from the wrist
    singularity, and urkin's count agrees with the branch-by-branch count."""
    gap, rows = _branch_geometry(robot, T)
    if abs(gap) < _MARGIN:
        return False
    small, big = _ring(robot)
    for reach, sin5 in rows:
        if sin5 < _WRIST_MARGIN or min(abs(reach - small), abs(reach - big)) < _MARGIN:
            return False
    return len(_ik_analytic(robot, T)) == _model_count(robot, T)


def _count_hypotheses(robot, T) -> dict[str, Callable[[], int]]:
    _, rows = _branch_geometry(robot, T)
    closing = _closing(robot, rows)
    return {
        "always 8: the pose decides how many of the 2 × 2 × 2 branches exist": lambda: 8,
        "the elbow triangle not checked: each (θ1, θ5) branch must also put wrist 1 within the "
        "planar arm's ring, ||a2| − |a3|| ≤ distance from the shoulder axis ≤ |a2| + |a3|": (
            lambda: 8 if rows else 0
        ),
        "the d4 cylinder not checked: a wrist point closer than d4 to the base axis has no "
        "tangent, so no θ1 and no solution at all (a clipped arccos invents one)": lambda: (
            _model_count(robot, T, clip=True)
        ),
        "the elbow decided once per θ1, as if both θ5 gave the same wrist 1: flipping θ5 turns "
        "the wrist link (z4 = ±z1 × z) over, and wrist 1 moves to the other side of joint 5's "
        "centre, so each θ5 needs its own triangle": lambda: 4 * sum(closing[0::2]) if rows else 0,
        "the two elbows not counted: each branch whose triangle closes gives two solutions, "
        "elbow up and elbow down": lambda: sum(closing),
        "only the θ1 tangents counted: 2 when the wrist point is outside the d4 cylinder": lambda: (
            2 if rows else 0
        ),
        "wrist 1's height measured from the base, not from the shoulder (d1 left out)": lambda: (
            _model_count(robot, T, d1=False)
        ),
        "wrist 1 taken at joint 5's centre: step back d5 along the wrist link": lambda: (
            _model_count(robot, T, d5=False)
        ),
        "the flange position p in place of the wrist point p − d6 z": lambda: _model_count(
            robot, T, d6=False
        ),
    }


def _count_probes() -> tuple[tuple[Any, np.ndarray], ...]:
    """Fixed poses of every kind (8, far, inside and just outside the cylinder, 2, 4, 6) on
    which the student's answers tell the hypotheses apart."""
    rng = np.random.default_rng(75)
    return (
        _middle_pose(rng),
        _far_pose(rng),
        _near_axis_pose(rng, True),
        _near_axis_pose(rng, False),
        *(_middle_pose(rng, (count,)) for count in (2, 4, 6)),
    )


_PROBES: list[tuple[Any, np.ndarray]] = []


def _count_mistake(sub, seen, robot, T, got: float, right: int) -> str | None:
    """The first hypothesis that gives ``got`` here (and not the right count), and the
    student's answers on every pose of the check before it and on the probe poses."""
    if not _PROBES:
        _PROBES.extend(_count_probes())
    answers = list(seen)
    for probe_robot, probe_T in _PROBES:
        try:
            answers.append((probe_robot, probe_T, _count_call(sub, probe_robot, probe_T)))
        except (Mismatch, StudentRaised):
            continue
    for name, compute in _count_hypotheses(robot, T).items():
        value = compute()
        if value == right or value != got:
            continue
        if all(_count_hypotheses(r, t)[name]() == g for r, t, g in answers):
            return name
    return None


def _translated(T, shift) -> np.ndarray:
    moved = np.array(T, dtype=float)
    moved[:3, 3] += shift
    return moved


def _middle_pose(rng, wanted=(8,)):
    """A random configuration's pose with a count in ``wanted``, away from every boundary."""
    arm = random_arm(rng)
    while True:
        T = _fk(arm, rng.uniform(-np.pi, np.pi, 6))
        if _with_margins(arm, T) and _model_count(arm, T) in wanted:
            return arm, T


def _far_pose(rng):
    """A pose whose wrist point is well beyond the arm's stretch from the shoulder."""
    arm = random_arm(rng)
    big = _ring(arm)[1]
    while True:
        direction = rng.normal(size=3)
        direction /= np.linalg.norm(direction)
        reach = big + arm.d4 + arm.d5 + arm.d6 + arm.d1
        p = direction * reach * rng.uniform(1.1, 1.8)
        T = make_transform(random_rotation(rng), p)
        if _with_margins(arm, T) and _model_count(arm, T) == 0:
            return arm, T


def _near_axis_pose(rng, inside: bool):
    """A random configuration's pose moved sideways so that its wrist point is inside the d4
    cylinder (where a clipped θ1 would still close a triangle) or just outside it, with all
    eight solutions."""
    arm = random_arm(rng)
    while True:
        T = _fk(arm, rng.uniform(-np.pi, np.pi, 6))
        wrist = T[:3, 3] - arm.d6 * T[:3, 2]
        rho = np.hypot(wrist[0], wrist[1])
        if rho < 1e-3:
            continue
        radius = arm.d4 * rng.uniform(0.05, 0.9) if inside else arm.d4 + rng.uniform(0.005, 0.03)
        shift = np.r_[wrist[:2] * (radius / rho - 1.0), 0.0]
        T = _translated(T, shift)
        if not _with_margins(arm, T):
            continue
        if inside and _model_count(arm, T, clip=True) > 0:
            return arm, T
        if not inside and _model_count(arm, T) == 8:
            return arm, T


def _count_call(sub, robot, T) -> float:
    inputs = {"robot": robot.name, "T": T}
    got = as_array(sub.solution_count(robot, T), (), "solution_count(robot, T)", inputs)
    if not float(got).is_integer():
        raise Mismatch(
            "solution_count must return a whole number: how many distinct solutions there are",
            inputs=inputs,
            got=got,
        )
    return float(got)


def _count_explained(robot, T) -> str:
    gap, rows = _branch_geometry(robot, T)
    rho = gap + robot.d4
    if not rows:
        return (
            f"the wrist point p − d6 z is {rho:.4f} m from the base axis, inside the cylinder "
            f"of radius d4 = {robot.d4:.4f} m"
        )
    small, big = _ring(robot)
    reaches = ", ".join(f"{reach:.4f}" for reach, _ in rows)
    return (
        f"the wrist point is {rho:.4f} m from the base axis (d4 = {robot.d4:.4f} m); on the "
        f"four (θ1, θ5) branches wrist 1 is {reaches} m from the shoulder axis, and the "
        f"planar arm reaches from {small:.4f} m to {big:.4f} m"
    )


def _count_cases(sub, cases, what: str) -> None:
    seen: list[tuple[Any, np.ndarray, float]] = []
    for robot, T in cases:
        got = _count_call(sub, robot, T)
        right = len(_ik_analytic(robot, T))
        if got != right:
            raise Mismatch(
                f"{what}: {robot.name} has {right} distinct solutions for this pose, not "
                f"{got:g} — {_count_explained(robot, T)}",
                inputs={"robot": robot.name, "T": T},
                expected=right,
                got=got,
                mistake=_count_mistake(sub, seen, robot, T, got, right),
            )
        seen.append((robot, T, got))


def _count_middle_and_far(sub, rng):
    cases = [_middle_pose(rng), _far_pose(rng), _middle_pose(rng), _far_pose(rng)]
    cases += [_middle_pose(rng), _far_pose(rng)]
    _count_cases(sub, cases, "8 in the middle of the workspace, 0 beyond the arm's reach")


def _count_near_axis(sub, rng):
    cases = [_near_axis_pose(rng, inside) for inside in (True, False, True, True, False, True)]
    _count_cases(sub, cases, "near the base axis: 0 inside the d4 cylinder, 8 just outside it")


def _count_partial(sub, rng):
    cases = [_middle_pose(rng, (count,)) for count in (2, 6, 4, 6, 2, 4)]
    _count_cases(sub, cases, "2, 4 or 6: each (θ1, θ5) branch closes its elbow triangle or not")


# ---------------------------------------------------------------------- 7.6 nearest_solution

_LIMIT = 2 * np.pi


def _shifted(solutions: np.ndarray, q: np.ndarray, limits: bool = True) -> np.ndarray:
    """Each angle turned by whole turns to its equivalent nearest ``q`` (within ±2π)."""
    shifted = solutions + _TURN * np.round((q - solutions) / _TURN)
    if limits:
        shifted = np.where(shifted > _LIMIT, shifted - _TURN, shifted)
        shifted = np.where(shifted < -_LIMIT, shifted + _TURN, shifted)
    return shifted


def _nearest(solutions: np.ndarray, q: np.ndarray, limits: bool = True, norm=None):
    shifted = _shifted(solutions, q, limits)
    gaps = (norm or (lambda d: np.linalg.norm(d, axis=1)))(shifted - q)
    return shifted[int(np.argmin(gaps))]


def _nearest_hypotheses(solutions: np.ndarray, q: np.ndarray) -> dict:
    return {
        "the nearest solution returned wrapped into (−π, π]: shift each angle by whole turns to "
        "its equivalent nearest q_current": lambda: solutions[
            int(np.argmin(np.linalg.norm(_shifted(solutions, q) - q, axis=1)))
        ],
        "chosen by plain distance to q_current, ignoring that angles a turn apart are the same "
        "joint position": lambda: solutions[int(np.argmin(np.linalg.norm(solutions - q, axis=1)))],
        "limits ignored: an equivalent beyond ±2π is not a configuration the arm can reach; "
        "take the one a turn back": lambda: _nearest(solutions, q, limits=False),
        "the largest joint difference instead of the Euclidean norm of the difference": lambda: (
            _nearest(solutions, q, norm=lambda d: np.abs(d).max(axis=1))
        ),
        "the sum of the joint differences' sizes (L1) instead of the Euclidean norm of the "
        "difference": lambda: _nearest(solutions, q, norm=lambda d: np.abs(d).sum(axis=1)),
        "the first solution, whatever q_current is": lambda: _shifted(solutions[:1], q)[0],
    }


def _pose_solutions(rng) -> tuple[Any, np.ndarray]:
    """A random UR arm and the closed-form solutions (at least two) of a random pose."""
    while True:
        arm = random_arm(rng)
        solutions = ik_analytic(arm, fk(arm, rng.uniform(-np.pi, np.pi, 6)))
        if len(solutions) >= 2:
            return arm, solutions


def _nearest_compare(sub, solutions: np.ndarray, q: np.ndarray, what: str, arm) -> None:
    inputs = {"robot": arm.name, "solutions": solutions, "q_current": q}
    got = as_array(
        sub.nearest_solution(solutions.copy(), q.copy()),
        (6,),
        "nearest_solution(solutions, q_current)",
        inputs,
    )
    expected = _nearest(solutions, q)
    if close(got, expected, 1e-12):
        return
    hypotheses = {
        name: compute
        for name, compute in _nearest_hypotheses(solutions, q).items()
        if not close(np.asarray(compute(), dtype=float), expected, 1e-9)
    }
    mistake = next((n for n, compute in hypotheses.items() if close(got, compute(), 1e-9)), None)
    raise Mismatch(what, inputs=inputs, expected=expected, got=got, mistake=mistake)


def _nearest_random(sub, rng):
    for _ in range(6):
        arm, solutions = _pose_solutions(rng)
        target = solutions[int(rng.integers(len(solutions)))]
        # near the target turned by whole turns, each joint still well inside ±2π
        turns = rng.integers(-1, 2, 6)
        turns[np.abs(target + _TURN * turns) > _LIMIT - 0.4] = 0
        q = target + _TURN * turns + rng.normal(0, 0.1, 6)
        _nearest_compare(
            sub, solutions, q, "the solution nearest q_current, shifted by whole turns", arm
        )
    # a q_current whose nearest solution by the Euclidean norm is not the one by another norm
    for _ in range(200):
        arm, solutions = _pose_solutions(rng)
        q = rng.uniform(-np.pi, np.pi, 6)
        euclidean = _nearest(solutions, q)
        others = (
            _nearest(solutions, q, norm=lambda d: np.abs(d).sum(axis=1)),
            _nearest(solutions, q, norm=lambda d: np.abs(d).max(axis=1)),
        )
        if not any(close(other, euclidean, 1e-6) for other in others):
            _nearest_compare(
                sub,
                solutions,
                q,
                "nearest by the Euclidean norm of the difference (here neither the largest "
                "joint difference nor the sum of their sizes picks the same solution)",
                arm,
            )
            break


def _nearest_limits(sub, rng):
    for _ in range(6):
        arm, solutions = _pose_solutions(rng)
        q = rng.uniform(-np.pi, np.pi, 6)
        joints = rng.choice(6, size=2, replace=False)
        q[joints] = rng.choice([-1.0, 1.0], 2) * rng.uniform(_LIMIT - 0.5, _LIMIT - 0.05, 2)
        _nearest_compare(
            sub,
            solutions,
            q,
            "near ±2π the nearest equivalent would pass the limit: the one a turn back is taken",
            arm,
        )


def _nearest_empty(sub, rng):
    arm, solutions = _pose_solutions(rng)
    near = solutions[int(rng.integers(len(solutions)))] + rng.normal(0, 0.01, 6)
    _nearest_compare(sub, solutions, near, "the solution q_current is next to", arm)
    empty, q = np.empty((0, 6)), rng.uniform(-np.pi, np.pi, 6)
    inputs = {"solutions": empty, "q_current": q}
    try:
        value = sub.nearest_solution(empty, q)
    except StudentRaised as exc:
        if exc.kind == "NotImplementedError" and exc.message.strip().startswith("Exercise "):
            raise
        if exc.kind == "ValueError" and re.search(r"\bsolutions\b", exc.message):
            return
        raise Mismatch(
            f"nearest_solution raised {exc.kind} for an empty (0, 6) array: the contract is a "
            "ValueError whose message names solutions",
            inputs=inputs,
            mistake=(
                "the error is not a ValueError naming solutions (np.argmin of an empty array "
                "raises a ValueError that does not)"
            ),
        ) from None
    raise Mismatch(
        "nearest_solution must raise ValueError for an empty (0, 6) array (a pose out of "
        "reach), and it returned a value",
        inputs=inputs,
        got=value if np.shape(value) == (6,) else None,
        mistake="no solutions and still an answer: check len(solutions) first",
    )


LESSON = Lesson(
    number="07",
    title="Closed-form (geometric) inverse kinematics",
    summary="closed-form IK: the UR3 lab's top-down gripper solution, fixed; all eight UR "
    "solutions; singular poses",
    exercises=(
        Exercise(
            id="7.1",
            function="lab_theta1",
            title="the lab's base angle θ1 (lab convention)",
            checks=(
                Check(
                    "right for wrist centres in front of the base",
                    1,
                    partial(_theta1_matches, "front"),
                ),
                Check(
                    "right behind the base, where arctan(y/x) fails",
                    2,
                    partial(_theta1_matches, "behind"),
                ),
            ),
            answer=concepts.LAB_IK,
        ),
        Exercise(
            id="7.2",
            function="planar_2r",
            title="the planar two-link sub-problem",
            checks=(
                Check(
                    "reaches targets with x > 0, elbow θb = +acos(…)",
                    1,
                    partial(_planar_check, "front"),
                ),
                Check("reaches targets with x < 0 too", 2, partial(_planar_check, "behind")),
                Check(
                    "reaches targets on the edges of the ring (cos θb clipped to [−1, 1])",
                    1,
                    _planar_edges,
                ),
            ),
        ),
        Exercise(
            id="7.3",
            function="ik_lab",
            title="the lab's top-down gripper IK, fixed",
            checks=(
                Check(
                    "round-trips targets in front of the base",
                    1,
                    partial(_lab_round_trips, "front"),
                ),
                Check(
                    "round-trips targets behind the base", 1, partial(_lab_round_trips, "behind")
                ),
                Check(
                    "round-trips targets so close that wrist 1 is behind the base axis (r < 0)",
                    1,
                    partial(_lab_round_trips, "over the shoulder"),
                ),
                Check(
                    "returns the lab's branch (θ1 from lab_theta1, θ5 = −π/2, θ3 > 0)",
                    1,
                    _lab_branch,
                ),
                Check("returns UR angles wrapped into (−π, π]", 1, _lab_wrapped),
            ),
            answer=concepts.LAB_IK,
            uses=("planar_2r", "lab_theta1"),
            builds_on=("7.1", "7.2"),
        ),
        Exercise(
            id="7.4",
            function="wrist_angles",
            title="θ5 and θ6 of the general closed form",
            checks=(
                Check("both (θ5, θ6) pairs for random poses", 2, _wrist_generic),
                Check(
                    "each pair gives the flange's orientation with that θ1", 1, _wrist_is_a_solution
                ),
                Check(
                    "accurate next to the wrist singularity (|θ5| from 3e-9 to 3e-8)",
                    1,
                    _wrist_near_singular,
                ),
            ),
            answer=concepts.INVERSE_KINEMATICS,
        ),
        Exercise(
            id="7.5",
            function="solution_count",
            title="predict, then verify: how many closed-form solutions a pose has",
            checks=(
                Check(
                    "8 in the middle of the workspace, 0 beyond the arm's reach",
                    1,
                    _count_middle_and_far,
                ),
                Check(
                    "near the base axis: 0 inside the d4 cylinder, 8 just outside it",
                    1,
                    _count_near_axis,
                ),
                Check(
                    "2, 4 or 6 where only some (θ1, θ5) branches close their elbow triangle",
                    1,
                    _count_partial,
                ),
            ),
            answer=concepts.INVERSE_KINEMATICS,
        ),
        Exercise(
            id="7.6",
            function="nearest_solution",
            title="the solution a robot should move to",
            checks=(
                Check(
                    "the solution nearest q_current, each angle shifted by whole turns",
                    2,
                    _nearest_random,
                ),
                Check("within ±2π when q_current is near a limit", 1, _nearest_limits),
                Check("ValueError naming solutions when there are none", 1, _nearest_empty),
            ),
            answer=concepts.INVERSE_KINEMATICS,
        ),
    ),
)
