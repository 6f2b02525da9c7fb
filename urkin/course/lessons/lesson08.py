"""Lesson 08 — the arm moves: paths at 1 mm, time scaling, tracking.

Every expected answer here is computed by the check's own formulas (never by urkin.trajectory,
urkin.tracking or urkin.tracking_report, which are the exercises' hidden answers), and every
named mistake by a hypothesis that computes its typical wrong answer.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from typing import Any

import numpy as np

from urkin import tracking, trajectory
from urkin.analytic_ik import ik_analytic
from urkin.course import concepts, wire
from urkin.course.compare import Mismatch, as_array, close, tolerance
from urkin.course.exercise import Check, Exercise, Lesson
from urkin.course.inputs import random_arm, random_regular_q
from urkin.course.submission import StudentRaised
from urkin.kinematics import fk

# bound here, in the lesson module, which the grading guard never touches
_fk, _ik_analytic = fk, ik_analytic
_TURN = 2.0 * math.pi


def _unit(rng) -> np.ndarray:
    v = rng.normal(size=3)
    return v / np.linalg.norm(v)


# ----------------------------------------------------------------------- 8.1 sample_polyline

_ROUND_OFF = 1e-9  # relative: where L/step is this close to a whole number m, m or m + 1 pieces

_FIXED_COUNT = (
    "the same number of samples on every segment, whatever its length (seed 000 takes 20 per "
    "side with linspace): the spacing grows with the segment; cut a segment of length L into "
    "ceil(L / step) pieces"
)
_REPEATED = (
    "corners repeated: np.linspace(a, b, n + 1) on each segment includes both ends, so every "
    "inner corner appears twice (a zero spacing); take each segment without its end point and "
    "add the path's last point once"
)
_ROUND = (
    "round(L / step) pieces instead of ceil: where L / step rounds down, the spacing exceeds step"
)
_FLOOR = "int(L / step) pieces (rounded down): the spacing exceeds step; use ceil(L / step)"
_NO_END = "the end point is missing: an open polyline ends with its last corner"
_CLOSED_REPEATS = (
    "the closed path repeats its start: its last sample is one piece before corners[0], which "
    "is already the first sample"
)
_CLOSED_IGNORED = (
    "closed=True ignored: a closed polyline also has the segment from its last corner back "
    "to corners[0]"
)
_ZERO_SEGMENT = (
    "a zero-length segment (a repeated corner) adds a sample: it must add nothing, so the "
    "corner appears once (ceil(0 / step) = 0 pieces, not at least one)"
)


def _segments(corners: np.ndarray, closed: bool) -> tuple[np.ndarray, np.ndarray]:
    ends = np.concatenate([corners[1:], corners[:1]]) if closed else corners[1:]
    return corners[: len(ends)], ends


def _piece_options(length: float, step: float) -> tuple[int, ...]:
    """The accepted numbers of pieces of one segment: ceil(L/step), and where L/step is within a
    relative 1e-9 of a whole number m, m or m + 1."""
    if length == 0.0:
        return (0,)
    ratio = length / step
    m = round(ratio)
    if m >= 1 and abs(ratio - m) <= _ROUND_OFF * ratio:
        return (m, m + 1)
    return (math.ceil(ratio),)


def _polyline_samples(corners, pieces, closed, *, ends=False, last=True) -> np.ndarray:
    """Segment i cut into pieces[i] equal pieces (with ``ends``: linspace with both ends);
    an open polyline's last corner added (unless ``last`` is False)."""
    starts, stops = _segments(corners, closed)
    parts = []
    for a, b, n in zip(starts, stops, pieces):
        if n <= 0:
            continue
        fractions = np.linspace(0.0, 1.0, n + 1) if ends else np.arange(n) / n
        parts.append(a + fractions[:, None] * (b - a))
    samples = np.concatenate(parts) if parts else np.empty((0, 3))
    if not closed and last and not ends:
        samples = np.concatenate([samples, corners[-1:]])
    return samples


def _lengths(corners, closed) -> np.ndarray:
    starts, stops = _segments(corners, closed)
    return np.sqrt(((stops - starts) ** 2).sum(axis=1))


def _polyline_answers(corners, step, closed) -> list[np.ndarray]:
    """Every accepted answer (one per choice of pieces where a length is a whole number of
    steps)."""
    options = [_piece_options(L, step) for L in _lengths(corners, closed)]
    return [_polyline_samples(corners, pieces, closed) for pieces in itertools.product(*options)]


def _polyline_hypotheses(corners, step, closed, count: int) -> dict[str, Callable[[], Any]]:
    lengths = _lengths(corners, closed)
    ceil = [math.ceil(L / step) for L in lengths]
    segments = len(lengths)

    def fixed(ends: bool):
        def compute():
            per = count if ends else count - (0 if closed else 1)
            if per % segments or per // segments < 1:
                raise ValueError("not a whole number per segment")
            n = per // segments - (1 if ends else 0)
            return _polyline_samples(corners, [n] * segments, closed, ends=ends)

        return compute

    hypotheses = {
        _FIXED_COUNT: fixed(True),
        _FIXED_COUNT + " ": fixed(False),
        _ZERO_SEGMENT: lambda: _polyline_samples(corners, [max(n, 1) for n in ceil], closed),
        _REPEATED: lambda: _polyline_samples(corners, ceil, closed, ends=True),
        _ROUND: lambda: _polyline_samples(corners, [round(L / step) for L in lengths], closed),
        _FLOOR: lambda: _polyline_samples(corners, [int(L / step) for L in lengths], closed),
    }
    if closed:
        hypotheses[_CLOSED_REPEATS] = lambda: np.concatenate(
            [_polyline_samples(corners, ceil, True), corners[:1]]
        )
        hypotheses[_CLOSED_IGNORED] = lambda: _polyline_samples(corners, ceil[:-1], False)
    else:
        hypotheses[_NO_END] = lambda: _polyline_samples(corners, ceil, False, last=False)
    return hypotheses


def _sampled_mistake(got, hypotheses, answers) -> str | None:
    for name, compute in hypotheses.items():
        try:
            value = np.asarray(compute(), dtype=float)
        except (ValueError, ZeroDivisionError):
            continue
        if any(value.shape == a.shape and close(value, a, 1e-9) for a in answers):
            continue
        if value.shape == got.shape and close(got, value, 1e-9):
            return name.strip()
    return None


def _judge_polyline(sub, corners, step, closed, what, *, default_step=False, as_list=False):
    inputs = {"corners": corners, "step": step, "closed": str(closed)}
    argument = corners.tolist() if as_list else corners.copy()
    if default_step:
        value = sub.sample_polyline(argument, closed=closed)
        inputs["step"] = "not given (the default, 1e-3)"
    else:
        value = sub.sample_polyline(argument, step=step, closed=closed)
    try:
        shape = np.shape(value)
    except (TypeError, ValueError):
        shape = ()
    answers = _polyline_answers(corners, step, closed)
    rows = shape[0] if len(shape) == 2 else len(answers[0])
    call = "sample_polyline(corners, step, closed)"
    got = as_array(value, (rows, 3), call, inputs)
    for answer in answers:
        if answer.shape == got.shape and close(got, answer, 1e-12):
            return
    expected = min(answers, key=lambda a: abs(len(a) - len(got)))
    hypotheses = _polyline_hypotheses(corners, step, closed, len(got))
    mistake = _sampled_mistake(got, hypotheses, answers)
    counts = sorted({len(a) for a in answers})
    if len(got) not in counts:
        spelled = " or ".join(str(c) for c in counts)
        detail = f"{spelled} samples expected, got {len(got)}"
    else:
        ring = np.concatenate([got, got[:1]]) if closed else got
        gaps = np.linalg.norm(np.diff(ring, axis=0), axis=1)
        if gaps.max(initial=0.0) > step + 1e-12:
            detail = f"a spacing of {gaps.max() * 1e3:.4f} mm exceeds the step {step * 1e3:.4f} mm"
        elif gaps.min(initial=1.0) == 0.0:
            detail = "two consecutive samples are the same point"
        else:
            detail = "the samples are not where the expected ones are"
    raise Mismatch(
        f"{what}: {detail}",
        inputs=inputs,
        expected=expected,
        got=got,
        mistake=mistake,
    )


def _random_polyline(rng, closed: bool, fractions=(0.0, 1.0), rounds_down=True, fewest=None):
    """Random corners (K, 3), K from ``fewest`` (2 open, 3 closed) to 6, and a step (m):
    segment lengths between 0.3 and 40 steps, each length/step with its fractional part in
    ``fractions`` (away from whole numbers), and with ``rounds_down`` some segment whose
    L/step rounds down (round() ≠ ceil())."""
    while True:
        step = 10 ** rng.uniform(-3.7, -2.3)
        K = int(rng.integers(fewest or (3 if closed else 2), 7))
        corners = [rng.uniform(-0.5, 0.5, 3)]
        for _ in range(K - 1):
            corners.append(corners[-1] + _unit(rng) * step * rng.uniform(0.3, 40.0))
        corners = np.array(corners)
        ratios = _lengths(corners, closed) / step
        parts = ratios - np.floor(ratios)
        lo, hi = fractions
        if not np.all((parts > max(lo, 1e-6)) & (parts < min(hi, 1 - 1e-6))):
            continue
        if rounds_down and not np.any(parts < 0.45):
            continue
        return corners, step


def _sample_open(sub, rng):
    for trial in range(4):
        corners, step = _random_polyline(rng, False)
        _judge_polyline(
            sub,
            corners,
            step,
            False,
            "an open polyline: each segment cut into ceil(L / step) equal pieces, every corner "
            "once, ending with the last corner",
            as_list=trial == 1,
        )


def _sample_closed(sub, rng):
    for _ in range(4):
        corners, step = _random_polyline(rng, True)
        _judge_polyline(
            sub,
            corners,
            step,
            True,
            "a closed polyline: also the segment back to corners[0], which is not repeated at "
            "the end",
        )


def _sample_edges(sub, rng):
    # a repeated corner (zero-length segment), open, among three other segments (so that a
    # repeated corner and every corner repeated differ); every L/step rounds up (round = ceil)
    corners, step = _random_polyline(rng, False, (0.55, 0.95), rounds_down=False, fewest=4)
    k = int(rng.integers(len(corners)))
    corners = np.insert(corners, k, corners[k], axis=0)
    _judge_polyline(
        sub, corners, step, False, "a repeated corner (a zero-length segment) adds nothing"
    )
    # a closed polyline whose last corner is its first again
    corners, step = _random_polyline(rng, False, (0.55, 0.95), rounds_down=False)
    corners = np.concatenate([corners, corners[:1]])
    while not np.all(_lengths(corners[:-1], True) / step % 1 > 0.55):  # closing segment too
        corners, step = _random_polyline(rng, False, (0.55, 0.95), rounds_down=False)
        corners = np.concatenate([corners, corners[:1]])
    _judge_polyline(
        sub,
        corners,
        step,
        True,
        "a closed polyline whose last corner repeats corners[0]: the zero-length closing "
        "segment adds nothing",
    )
    # seed 000's square: 0.15 m sides, 1 mm (the default step), in the yz plane
    centre = np.array([0.25, 0.1, 0.3]) + rng.uniform(-0.05, 0.05, 3)
    half = 0.075
    square = centre + half * np.array([[0, -1, -1], [0, 1, -1], [0, 1, 1], [0, -1, 1]])
    _judge_polyline(
        sub,
        square,
        1e-3,
        True,
        "seed 000's square, sides of 0.15 m at the default 1 mm: 150 or 151 pieces per side",
        default_step=True,
    )
    # sides that are a whole number of random steps
    m = int(rng.integers(20, 80))
    side = float(rng.uniform(0.05, 0.2))
    u, v = _unit(rng), _unit(rng)
    v -= (v @ u) * u
    v /= np.linalg.norm(v)
    square = centre + side * np.array([0 * u, u, u + v, v])
    _judge_polyline(
        sub,
        square,
        side / m,
        True,
        f"a square whose sides are {m} steps long: {m} or {m + 1} pieces per side",
    )


# ----------------------------------------------------------------------- 8.3 quintic_scaling

_CUBIC = "the cubic s = 3τ² − 2τ³ (lesson's other profile): the quintic is 10τ³ − 15τ⁴ + 6τ⁵"
_PER_TAU = (
    "derivatives with respect to τ, not t: ds/dt = (ds/dτ)(1/T) and d²s/dt² = (d²s/dτ²)(1/T²)"
)
_ONE_T = "s̈ divided by T only once: the chain rule gives d²s/dt² = (d²s/dτ²) / T²"
_NOT_CLIPPED = (
    "not clipped: before t = 0 the motion has not started (0, 0, 0) and after T it has ended "
    "(1, 0, 0); the polynomial goes on outside [0, T]"
)
_NO_TAU = "τ = t / T forgotten: the polynomial evaluated at t itself"


def _quintic(t, T, *, cubic=False, per_tau=False, one_t=False, clip=True, scale=True):
    tau = t / T if scale else np.asarray(t, dtype=float)
    inside = np.ones(np.shape(t), dtype=bool)
    if clip:
        inside = (tau >= 0.0) & (tau <= 1.0)
        tau = np.clip(tau, 0.0, 1.0)
    if cubic:
        s = tau * tau * (3.0 - 2.0 * tau)
        sd, sdd = 6.0 * tau * (1.0 - tau), 6.0 - 12.0 * tau
    else:
        s = 10.0 * tau**3 - 15.0 * tau**4 + 6.0 * tau**5
        sd = 30.0 * tau**2 - 60.0 * tau**3 + 30.0 * tau**4
        sdd = 60.0 * tau - 180.0 * tau**2 + 120.0 * tau**3
    if not per_tau:
        sd, sdd = sd / T, sdd / (T if one_t else T * T)
    return s, np.where(inside, sd, 0.0), np.where(inside, sdd, 0.0)


def _quintic_hypotheses(t, T) -> dict[str, Callable[[], Any]]:
    return {
        _CUBIC: lambda: _quintic(t, T, cubic=True),
        _PER_TAU: lambda: _quintic(t, T, per_tau=True),
        _ONE_T: lambda: _quintic(t, T, one_t=True),
        _NOT_CLIPPED: lambda: _quintic(t, T, clip=False),
        _NO_TAU: lambda: _quintic(t, T, scale=False),
    }


_NAMES = ("s", "ṡ", "s̈")
_PEAKS = (1.0, 15.0 / 8.0, 10.0 / math.sqrt(3.0))  # peak s, ṡ·T, |s̈|·T²


def _judge_quintic(sub, t, T, what):
    inputs = {"t": t, "T": T}
    shape = np.shape(t)
    value = sub.quintic_scaling(t.copy() if isinstance(t, np.ndarray) else t, T)
    if not (isinstance(value, (tuple, list)) and len(value) == 3):
        raise Mismatch(
            "quintic_scaling(t, T) must return three arrays: (s, s_dot, s_ddot)", inputs=inputs
        )
    got = [
        as_array(v, shape, f"{name}, value {i + 1} of quintic_scaling(t, T),", inputs)
        for i, (v, name) in enumerate(zip(value, _NAMES))
    ]
    right = _quintic(np.asarray(t, dtype=float), T)
    for i, (g, r) in enumerate(zip(got, right)):
        scale = _PEAKS[i] / T**i
        if close(g, r, 1e-12 * scale):
            continue
        mistake = None
        for name, compute in _quintic_hypotheses(np.asarray(t, dtype=float), T).items():
            wrong = compute()
            if all(
                close(w, c, 1e-9 * p / T**j)
                for j, (w, c, p) in enumerate(zip(wrong, right, _PEAKS))
            ):
                continue
            if all(
                close(gg, w, 1e-9 * p / T**j)
                for j, (gg, w, p) in enumerate(zip(got, wrong, _PEAKS))
            ):
                mistake = name
                break
        gap = float(np.abs(g - r).max())
        raise Mismatch(
            f"{what}: {_NAMES[i]} is wrong (largest error {gap:.2e}; the tolerance is "
            f"{tolerance(1e-12 * scale, g, scale):.0e}, 1e-12 of its peak)",
            inputs=inputs,
            expected=r,
            got=g,
            mistake=mistake,
        )


def _quintic_inside(sub, rng):
    for shape in ((9,), (3, 4), (9,), (5,)):
        T = float(10 ** rng.uniform(-0.7, 1.3))
        t = rng.uniform(0.0, T, shape)
        t.flat[0], t.flat[-1] = 0.0, T
        _judge_quintic(sub, t, T, "s(t), ṡ(t), s̈(t) of the quintic for times in [0, T]")


def _quintic_outside(sub, rng):
    for _ in range(3):
        T = float(10 ** rng.uniform(-0.7, 1.3))
        t = np.concatenate(
            [rng.uniform(-2 * T, 0.0, 3), rng.uniform(0.0, T, 2), rng.uniform(T, 3 * T, 3)]
        )
        rng.shuffle(t)
        _judge_quintic(
            sub, t, T, "before t = 0 the motion rests at (0, 0, 0), after T at (1, 0, 0)"
        )
    T = float(10 ** rng.uniform(-0.7, 1.3))
    for t in (float(rng.uniform(-T, 0.0)), float(rng.uniform(T, 2 * T))):
        _judge_quintic(sub, t, T, "one time t (a float): three arrays of shape ()")


# ---------------------------------------------------------------------- 8.4 minimum_duration

_PER_JOINT = (
    "one T per joint: every joint follows the same s(t), so one duration, the largest, serves "
    "them all"
)
_SUM_JOINTS = "the joints' durations added: the slowest joint sets T (the largest), not the sum"
_SUM_LIMITS = (
    "the velocity-limited and acceleration-limited durations added: T is the larger of the two"
)
_CUBIC_PEAKS = (
    "the cubic's peaks (ṡ = 3/(2T), s̈ = 6/T²): the quintic's are ṡ = 15/(8T) and |s̈| = 10/(√3 T²)"
)
_VELOCITY_ONLY = "only the velocity limit: T must also satisfy |d| 10/(√3 T²) ≤ a"
_ACCELERATION_ONLY = "only the acceleration limit: T must also satisfy |d| 15/(8T) ≤ v"
_SIGNED = "signed distances: a joint moving by a negative distance needs time too; use |d|"
_NO_REFUSAL = "no ValueError for a limit ≤ 0 (a zero limit gives an infinite or NaN duration)"


_QUINTIC_PEAKS = (15.0 / 8.0, 10.0 / math.sqrt(3.0))  # peak ṡ·T and |s̈|·T² of the quintic


def _duration(d, v, a, *, velocity=True, acceleration=True, peaks=_QUINTIC_PEAKS):
    """The shortest quintic duration, joint by joint (the check's own loop)."""
    times = []
    for dj, vj, aj in zip(d, v, a):
        dj = abs(float(dj))
        tv = peaks[0] * dj / float(vj) if velocity else 0.0
        ta = math.sqrt(peaks[1] * dj / float(aj)) if acceleration else 0.0
        times.append(max(tv, ta))
    return times


def _duration_hypotheses(d, v, a) -> dict[str, Callable[[], Any]]:
    positive = np.maximum(np.asarray(d, dtype=float), 0.0)
    return {
        _SUM_JOINTS: lambda: sum(_duration(d, v, a)),
        _SUM_LIMITS: lambda: (
            max(_duration(d, v, a, acceleration=False)) + max(_duration(d, v, a, velocity=False))
        ),
        _CUBIC_PEAKS: lambda: max(_duration(d, v, a, peaks=(1.5, 6.0))),
        _VELOCITY_ONLY: lambda: max(_duration(d, v, a, acceleration=False)),
        _ACCELERATION_ONLY: lambda: max(_duration(d, v, a, velocity=False)),
        _SIGNED: lambda: max(_duration(positive, v, a)),
    }


def _peak_ratio(d, v, a, T) -> tuple[float, int, str]:
    """The largest (peak / limit) of any joint at duration T, its joint (1-based) and limit."""
    best = (0.0, 0, "")
    for j, (dj, vj, aj) in enumerate(zip(d, v, a)):
        dj = abs(float(dj))
        for ratio, name in (
            (15 * dj / (8 * T * vj), "velocity"),
            (10 * dj / (math.sqrt(3) * T * T * aj), "acceleration"),
        ):
            if ratio > best[0]:
                best = (ratio, j + 1, name)
    return best


def _call_duration(sub, d, v, a, inputs):
    call = "minimum_duration(distance, max_velocity, max_acceleration)"
    value = sub.minimum_duration(d.copy(), v.copy(), a.copy())
    try:
        return float(as_array(value, (), call, inputs, {(len(d),): _PER_JOINT}))
    except Mismatch as exc:
        if "NaN" in exc.what and np.any(d < 0):
            exc.mistake = exc.mistake or _SIGNED + " (the square root of a negative is NaN)"
        raise


def _judge_duration(sub, d, v, a, what):
    inputs = {"distance": d, "max_velocity": v, "max_acceleration": a}
    got = _call_duration(sub, d, v, a, inputs)
    expected = max(_duration(d, v, a))
    if abs(got - expected) <= 1e-12 * expected:
        return
    detail = ""
    if got > 0 and np.isfinite(got):
        ratio, joint, limit = _peak_ratio(d, v, a, got)
        if ratio > 1 + 1e-9:
            detail = (
                f"; at T = {got:.6g} s joint {joint} would exceed its {limit} limit "
                f"{ratio:.4g} times over"
            )
        else:
            detail = (
                f"; at T = {got:.6g} s no joint reaches a limit (the closest, joint {joint}'s "
                f"{limit}, is at {ratio:.4g} of it): a shorter T is allowed"
            )
    mistake = None
    for name, compute in _duration_hypotheses(d, v, a).items():
        wrong = float(compute())
        if abs(wrong - expected) > 1e-9 * expected and abs(got - wrong) <= 1e-9 * abs(wrong):
            mistake = name
            break
    raise Mismatch(
        f"{what}{detail}",
        inputs=inputs,
        expected=expected,
        got=got,
        mistake=mistake,
        difference=None
        if abs(got - expected) > 1e-4
        else f"relative difference {abs(got - expected) / expected:.1e}; the tolerance is 1e-12",
    )


def _duration_problem(rng, n: int, bound: str | None, *, still: int = 0, distinct=False):
    """Random distances (either sign) and limits; the slowest joint clearly bound by one limit,
    with ``bound`` ("velocity" or "acceleration") that one and its distance negative;
    ``still`` joints that do not move; with ``distinct``, every named mistake wrong here (but
    the limit that binds alone)."""
    while True:
        d = rng.uniform(-3.0, 3.0, n)
        d[rng.choice(n, still, replace=False)] = 0.0
        v = rng.uniform(0.3, 3.2, n)
        a = rng.uniform(0.5, 15.0, n)
        times = [
            (15 * abs(x) / (8 * y), math.sqrt(10 * abs(x) / (math.sqrt(3) * z)))
            for x, y, z in zip(d, v, a)
        ]
        j = int(np.argmax([max(t) for t in times]))
        which = "velocity" if times[j][0] >= times[j][1] else "acceleration"
        if min(abs(times[j][0] - times[j][1]), abs(d[j])) < 1e-3:
            continue
        if bound is not None and (which != bound or d[j] > 0):
            continue
        right = max(_duration(d, v, a))
        same = {_VELOCITY_ONLY: "velocity", _ACCELERATION_ONLY: "acceleration"}
        if distinct and any(
            abs(float(compute()) - right) < 1e-6 * right
            for name, compute in _duration_hypotheses(d, v, a).items()
            if same.get(name) != bound  # bound by velocity: velocity alone is right
        ):
            continue
        return d, v, a


def _duration_random(sub, rng):
    for n, bound in ((6, "velocity"), (6, "acceleration"), (1, None), (3, None), (7, None)):
        d, v, a = _duration_problem(rng, n, bound)
        _judge_duration(
            sub,
            d,
            v,
            a,
            "T = max over joints of max(15|d|/(8v), √(10|d|/(√3 a))): the shortest quintic "
            "move with every joint within its limits",
        )


def _duration_edges(sub, rng):
    n = int(rng.integers(2, 7))
    d, v, a = np.zeros(n), rng.uniform(0.3, 3.2, n), rng.uniform(0.5, 15.0, n)
    _judge_duration(sub, d, v, a, "no joint moves: T = 0.0")
    for bound in ("velocity", "acceleration"):
        d, v, a = _duration_problem(rng, 6, bound, still=2, distinct=True)
        _judge_duration(sub, d, v, a, "joints that do not move (d = 0) take no time")
    for name in ("max_velocity", "max_acceleration"):
        d, v, a = _duration_problem(rng, 4, None)
        limits = {"max_velocity": v, "max_acceleration": a}
        j = int(np.argmax(np.abs(d)))
        limits[name][j] = 0.0 if name == "max_velocity" else -limits[name][j]
        inputs = {"distance": d, "max_velocity": v, "max_acceleration": a}
        try:
            value = sub.minimum_duration(d.copy(), v.copy(), a.copy())
        except StudentRaised as exc:
            if exc.kind == "ValueError":
                continue
            if exc.kind == "NotImplementedError" and exc.message.strip().startswith("Exercise "):
                raise
            raise Mismatch(
                f"a limit ≤ 0 must raise ValueError; minimum_duration raised {exc.kind}",
                inputs=inputs,
                mistake=_NO_REFUSAL,
            ) from None
        raise Mismatch(
            f"{name}[{j}] = {limits[name][j]:g} is not a limit: minimum_duration must raise "
            "ValueError, and it returned a value",
            inputs=inputs,
            got=value if np.ndim(value) == 0 and not isinstance(value, str) else None,
            mistake=_NO_REFUSAL,
        )


# ------------------------------------------------------------------------- 8.2 track_nearest

_TRACK_TOL = 1e-9  # rad, and the pose error fk(q_k) − pose_k where ok

_OVERWRITE_ZERO = (
    "a failed sample's row is left unset (zeros, NaN or garbage, seed 000's overwrite): where "
    "solve_all returns no rows the arm stays where it was, q[k] = q[k − 1]"
)
_OVERWRITE_Q0 = (
    "a failed sample's row is q0: the arm stays where it was, the previous configuration "
    "q[k − 1], not where it started"
)
_NO_OK = "ok not recorded: ok[k] is False where solve_all returns no rows"
_FIRST = (
    "the first solution, not the nearest: solve_all lists the solutions in no particular "
    "order; take the one nearest the previous configuration"
)
_PLAIN_DISTANCE = (
    "nearest without wrapping the difference: angles a turn apart are the same joint "
    "position; measure ‖wrap(q_sol − q_prev)‖, with each difference wrapped into [−π, π)"
)
_NOT_CONTINUED = (
    "no shortest-turn continuation: the solutions are wrapped into [−π, π), so returning them "
    "as they are makes a joint jump by 2π where it passes ±π (and drops q0's extra turns); "
    "use q_k = q_(k−1) + wrap(q_sol − q_(k−1))"
)
_FROM_Q0 = (
    "every sample compared with (and continued from) q0 instead of the previous sample: once "
    "a joint has moved more than π from q0, its continuation jumps by a turn"
)
_ONLY_Q = "only q returned: return both, q and ok (a tuple of two arrays)"


def _wrap(x):
    return (np.asarray(x, dtype=float) + math.pi) % _TURN - math.pi


def _nearest_track(
    q0,
    listed,
    *,
    choose="nearest",
    distance="wrapped",
    reference="previous",
    rows="continued",
    failure="held",
    ok_rule="found",
):
    """The check's own tracking of listed solutions, or one of its named mistakes."""
    previous = np.array(q0, dtype=float)
    Q, ok = np.zeros((len(listed), 6)), np.zeros(len(listed), dtype=bool)
    for k, solutions in enumerate(listed):
        if len(solutions) == 0:
            Q[k] = {"held": previous, "zeros": np.zeros(6), "q0": q0}[failure]
            ok[k] = ok_rule == "all"
            continue
        base = previous if reference == "previous" else np.asarray(q0, dtype=float)
        raw = solutions - base
        gaps = np.linalg.norm(_wrap(raw) if distance == "wrapped" else raw, axis=1)
        row = 0 if choose == "first" else int(np.argmin(gaps))
        previous = base + _wrap(solutions[row] - base) if rows == "continued" else solutions[row]
        Q[k], ok[k] = previous, True
    return Q, ok


_TRACK_MISTAKES = {
    _OVERWRITE_ZERO: {"failure": "zeros"},
    _OVERWRITE_Q0: {"failure": "q0"},
    _NO_OK: {"ok_rule": "all"},
    _FIRST: {"choose": "first"},
    _PLAIN_DISTANCE: {"distance": "plain"},
    _NOT_CONTINUED: {"rows": "wrapped"},
    _FROM_Q0: {"reference": "q0"},
}


def _same(a, b, atol=_TRACK_TOL) -> bool:
    (Q, ok), (Q2, ok2) = a, b
    return bool(np.array_equal(ok, ok2) and np.abs(Q - Q2).max(initial=0.0) <= atol)


def _listed(rng, arm, Q_path, unreachable=()):
    """The solutions of the path's poses, wrapped into [−π, π), rows in random order; the
    samples in ``unreachable`` get none."""
    poses = _fk(arm, _wrap(Q_path))
    solutions, real_rows = _ik_analytic(arm, poses, return_mask=True)
    listed = []
    for k in range(len(poses)):
        rows = _wrap(solutions[k][real_rows[k]])
        rows = rows[rng.permutation(len(rows))]
        listed.append(rows[:0] if k in unreachable else rows)
    return poses, listed


def _unambiguous(q0, listed) -> bool:
    """Whether, along the right tracking, each nearest solution is clearly the nearest and no
    joint of it is near half a turn from the previous configuration."""
    previous = np.array(q0, dtype=float)
    for solutions in listed:
        if len(solutions) == 0:
            continue
        differences = _wrap(solutions - previous)
        gaps = np.linalg.norm(differences, axis=1)
        row = int(np.argmin(gaps))
        if len(gaps) > 1 and gaps[row] > 0.5 * np.partition(gaps, 1)[1]:
            return False
        if np.any(np.abs(differences[row]) > math.pi - 1e-3):
            return False
        previous = previous + differences[row]
    return True


def _regular_path(arm, Q) -> bool:
    q2, q3, q4, q5 = Q[:, 1], Q[:, 2], Q[:, 3], Q[:, 4]
    shoulder = arm.a2 * np.cos(q2) + arm.a3 * np.cos(q2 + q3) + arm.d5 * np.sin(q2 + q3 + q4)
    return bool(
        np.abs(np.sin(q3)).min() > 0.2
        and np.abs(np.sin(q5)).min() > 0.2
        and np.abs(shoulder).min() > 0.05
    )


def _wavy(rng, centre, M, amplitude):
    """A joint path from ``centre``: each joint a part of a sine wave (less than a period)."""
    s = np.linspace(0.0, 1.0, M)[:, None]
    phase = rng.uniform(0.0, _TURN, 6)
    frequency = rng.uniform(0.3, 0.8, 6)
    return centre + rng.uniform(-amplitude, amplitude, 6) * (
        np.sin(_TURN * frequency * s + phase) - np.sin(phase)
    )


def _distinct(poses) -> bool:
    """Whether every two poses differ by more than 1e-3 in some entry."""
    gaps = np.abs(poses[:, None] - poses[None, :]).max(axis=(2, 3))
    return bool(gaps[~np.eye(len(poses), dtype=bool)].min(initial=1.0) > 1e-3)


def _track_problem(rng, M, *, sweep, turns, unreachable=(), fail=(), keep=()):
    """A random UR arm, a smooth regular joint path, its poses and listed solutions, and q0,
    such that the mistakes in ``fail`` give wrong answers and those in ``keep`` right ones.

    sweep: one joint (1 or 6) moves by more than π, passing ±π; turns: q0 carries whole turns
    on two or three joints; otherwise the path keeps within ±(π − 0.3)."""
    while True:
        arm = random_arm(rng)
        centre = random_regular_q(rng)
        Q = _wavy(rng, centre, M, 0.3)
        if sweep:
            j = int(rng.choice([0, 5]))
            side = float(rng.choice([-1.0, 1.0]))
            margin = rng.uniform(0.3, 0.8)
            start = side * (math.pi - margin)
            Q[:, j] = start + side * np.linspace(0.0, math.pi + rng.uniform(0.1, margin), M)
        elif np.abs(Q).max() > math.pi - 0.3:
            continue
        if not _regular_path(arm, Q):
            continue
        q0 = Q[0] + rng.normal(0.0, 0.03, 6)
        if turns:
            joints = rng.choice(6, int(rng.integers(2, 4)), replace=False)
            q0[joints] -= _TURN * np.sign(q0[joints])
        poses, listed = _listed(rng, arm, Q, unreachable)
        if not _distinct(poses):
            continue
        if any(len(x) == 0 for k, x in enumerate(listed) if k not in unreachable):
            continue
        if not _unambiguous(q0, listed):
            continue
        right = _nearest_track(q0, listed)
        if any(_same(_nearest_track(q0, listed, **_TRACK_MISTAKES[m]), right) for m in fail):
            continue
        if all(_same(_nearest_track(q0, listed, **_TRACK_MISTAKES[m]), right) for m in keep):
            return arm, poses, listed, q0


def _track_inputs(arm, poses, q0, listed):
    counts = [len(x) for x in listed]
    return {
        "robot": arm.name,
        "q0": q0,
        "poses": f"{len(poses)} poses of a smooth joint path of the {arm.name}",
        "solve_all": "the check's stand-in: the closed-form solutions of each pose, wrapped into "
        "[−π, π), rows in random order; solutions per pose " + " ".join(map(str, counts)),
    }


def _call_track(sub, arm, poses, q0, solve_all, inputs):
    M = len(poses)
    what = "track_nearest(robot, poses, q0, solve_all)"
    value = sub.track_nearest(arm, poses.copy(), q0.copy(), solve_all)
    if not (isinstance(value, (tuple, list)) and len(value) == 2):
        raise Mismatch(
            f"{what} must return two values, q of shape ({M}, 6) and ok of shape ({M},)",
            inputs=inputs,
            mistake=_ONLY_Q if np.shape(value) == (M, 6) else None,
        )
    try:
        Q = as_array(value[0], (M, 6), f"q, the first value {what} returns,", inputs)
    except Mismatch as exc:
        if "NaN" in exc.what:
            exc.mistake = exc.mistake or _OVERWRITE_ZERO
        raise
    ok = as_array(value[1], (M,), f"ok, the second value {what} returns,", inputs)
    if not np.all((ok == 0) | (ok == 1)):
        raise Mismatch(f"ok, the second value {what} returns, must hold booleans", inputs=inputs)
    return Q.astype(float), ok.astype(bool)


def _judge_track(sub, arm, poses, listed, q0, what):
    inputs = _track_inputs(arm, poses, q0, listed)
    counts = np.array([len(x) for x in listed])
    padded = np.full((len(listed), 8, 6), np.nan)
    for k, rows in enumerate(listed):
        padded[k, : len(rows)] = rows
    solve_all = wire.Function("listed_solutions", poses=poses, solutions=padded, counts=counts)
    Q, ok = _call_track(sub, arm, poses, q0, solve_all, inputs)
    Q_right, ok_right = _nearest_track(q0, listed)
    gap = np.abs(Q - Q_right).max(axis=1)
    wrong = (ok != ok_right) | (gap > _TRACK_TOL)
    held = np.array(
        [ok_right[k] or np.array_equal(Q[k], Q[k - 1] if k else q0) for k in range(len(Q))]
    )
    wrong |= ~held
    if not wrong.any():
        return
    k = int(np.flatnonzero(wrong)[0])
    before = Q[k - 1] if k else q0
    if ok[k] != ok_right[k]:
        detail = f"ok[{k}] must be {bool(ok_right[k])}, not {bool(ok[k])}"
    elif not ok_right[k]:
        detail = (
            f"sample {k} has no solution: q[{k}] must be q[{k - 1}] exactly (the arm stays "
            "where it was)"
            if k
            else "sample 0 has no solution: q[0] must be q0 exactly"
        )
    else:
        miss = float(np.abs(_fk(arm, _wrap(Q[k])) - poses[k]).max())
        jump = np.abs(Q[k] - before)
        if miss > _TRACK_TOL:
            detail = f"fk(robot, q[{k}]) misses pose {k} by {miss:.2e} (largest entry)"
        elif jump.max() > math.pi:
            j = int(np.argmax(jump))
            detail = (
                f"joint {j + 1} turns by {jump[j]:.4f} rad from sample {k - 1 if k else 'q0'} "
                f"to {k}: more than π, so not the shortest turn"
            )
        else:
            detail = (
                f"q[{k}] reaches pose {k} but is not the solution nearest the previous "
                "configuration, continued by the shortest turn"
            )
    mistake = None
    for name, wrongly in _TRACK_MISTAKES.items():
        hypothesis = _nearest_track(q0, listed, **wrongly)
        if not _same(hypothesis, (Q_right, ok_right)) and _same((Q, ok), hypothesis, 1e-6):
            mistake = name
            break
    raise Mismatch(
        f"{what}. Sample {k} is the first wrong one: {detail}",
        inputs=inputs,
        expected=Q_right[k],
        got=Q[k],
        mistake=mistake,
    )


def _track_sweep(sub, rng):
    for _ in range(2):
        arm, poses, listed, q0 = _track_problem(
            rng,
            40,
            sweep=True,
            turns=False,
            fail=(_FIRST, _PLAIN_DISTANCE, _NOT_CONTINUED, _FROM_Q0),
        )
        _judge_track(
            sub,
            arm,
            poses,
            listed,
            q0,
            "a smooth path on which joint 1 or 6 turns by more than π, passing ±π: each "
            "sample's solution nearest the previous one (wrapped differences), each joint "
            "continued by its shortest turn",
        )


def _track_turns(sub, rng):
    for _ in range(3):
        arm, poses, listed, q0 = _track_problem(
            rng,
            12,
            sweep=False,
            turns=True,
            fail=(_FIRST, _PLAIN_DISTANCE, _NOT_CONTINUED),
            keep=(_FROM_Q0,),
        )
        _judge_track(
            sub,
            arm,
            poses,
            listed,
            q0,
            "q0 carries extra whole turns on some joints: the first sample is compared with q0 "
            "through wrapped differences, and the joints keep their winding",
        )


_FAILURE_PATTERNS = ((0, 3, 4), (2, 5, 6), (1, 7))  # unreachable samples of 8


def _track_failures(sub, rng):
    for unreachable in _FAILURE_PATTERNS:
        arm, poses, listed, q0 = _track_problem(
            rng,
            8,
            sweep=False,
            turns=False,
            unreachable=unreachable,
            keep=(_PLAIN_DISTANCE, _NOT_CONTINUED, _FROM_Q0),
        )
        _judge_track(
            sub,
            arm,
            poses,
            listed,
            q0,
            f"samples {', '.join(map(str, unreachable))} are unreachable (solve_all returns "
            "no rows): there ok is False and q[k] is q[k − 1] exactly (q0 for the first), and "
            "the next sample is compared with it",
        )


# ----------------------------------------------------------------------- 8.5 read_trajectory

_FAMILIES = ("shoulder", "elbow", "wrist")

_SIGN_OF_ANGLE = (
    "the sign of q3 (q5) instead of sin q3 (sin q5): an angle past ±π has the other sine; "
    "the elbow branch is the sign of sin q3, the wrist's of sin q5"
)
_INDEX_AFTER = (
    "off by one: the flip between samples k and k + 1 is listed as k (the sample before it), "
    "not k + 1"
)
_NO_D5 = (
    "the shoulder factor without d5 sin(q2 + q3 + q4): it is a2 cos q2 + a3 cos(q2 + q3) + "
    "d5 sin(q2 + q3 + q4)"
)
_NET_TURNS = (
    "winding by net turns (q[−1] − q[0]): a joint is wound where its angle leaves [−2π, 2π] "
    "anywhere, even if it comes back"
)
_ZERO_BASED = "0-based joints: the joints are numbered 1 to 6"
_HALF_RANGE = (
    "leaving [−π, π] counted as winding: UR joints turn to ±2π; wound means leaving [−2π, 2π]"
)
_LAST_ONLY = (
    "only the last sample's angle tested: a joint that leaves [−2π, 2π] and comes back is wound too"
)


def _factors(arm, Q, *, sign_of_angle=False, no_d5=False) -> np.ndarray:
    q2, q3, q4, q5 = Q[:, 1], Q[:, 2], Q[:, 3], Q[:, 4]
    shoulder = arm.a2 * np.cos(q2) + arm.a3 * np.cos(q2 + q3)
    if not no_d5:
        shoulder = shoulder + arm.d5 * np.sin(q2 + q3 + q4)
    if sign_of_angle:
        return np.column_stack([shoulder, q3, q5])
    return np.column_stack([shoulder, np.sin(q3), np.sin(q5)])


def _flips(arm, Q, *, shift=0, **wrong) -> dict[str, list[int]]:
    signs = np.sign(_factors(arm, Q, **wrong))
    flips = {}
    for i, name in enumerate(_FAMILIES):
        flips[name] = [k + shift for k in range(len(Q) - 1) if signs[k, i] * signs[k + 1, i] < 0]
    return flips


def _wound(Q, *, rule="range") -> list[int]:
    joints = []
    for j in range(6):
        column = Q[:, j]
        if rule == "range":
            out = column.min() < -_TURN or column.max() > _TURN
        elif rule == "half":
            out = column.min() < -math.pi or column.max() > math.pi
        elif rule == "net":
            out = abs(column[-1] - column[0]) >= _TURN
        else:  # the last sample only
            out = abs(column[-1]) > _TURN
        if out:
            joints.append(j + 1)
    return joints


def _read_call(sub, arm, Q, inputs) -> dict:
    what = "read_trajectory(robot, q)"
    value = sub.read_trajectory(arm, Q.copy())
    if not (isinstance(value, dict) and {"flips", "wound"} <= set(value)):
        raise Mismatch(f"{what} must return a dict with keys 'flips' and 'wound'", inputs=inputs)
    flips = value["flips"]
    if not (isinstance(flips, dict) and set(_FAMILIES) <= set(flips)):
        raise Mismatch(
            f"{what}['flips'] must be a dict with keys 'shoulder', 'elbow' and 'wrist'",
            inputs=inputs,
        )
    read = {name: _indices(flips[name], f"{what}['flips']['{name}']", inputs) for name in _FAMILIES}
    return {"flips": read, "wound": _indices(value["wound"], f"{what}['wound']", inputs)}


def _indices(value, what, inputs) -> list[int]:
    try:
        array = np.asarray(value)
        ok = array.ndim == 1 and (array.size == 0 or np.issubdtype(array.dtype, np.number))
        numbers = array.astype(float) if ok else None
    except (TypeError, ValueError):
        numbers = None
    if numbers is None or np.any(numbers != np.round(numbers)):
        raise Mismatch(f"{what} must be a list of whole numbers", inputs=inputs, got=None)
    return [int(x) for x in numbers]


def _flip_hypotheses(arm, Q) -> dict[str, Callable[[], Any]]:
    return {
        _SIGN_OF_ANGLE: lambda: _flips(arm, Q, sign_of_angle=True),
        _INDEX_AFTER: lambda: _flips(arm, Q, shift=1),
        _NO_D5: lambda: _flips(arm, Q, no_d5=True),
    }


def _wound_hypotheses(Q) -> dict[str, Callable[[], Any]]:
    return {
        _NET_TURNS: lambda: _wound(Q, rule="net"),
        _ZERO_BASED: lambda: [j - 1 for j in _wound(Q)],
        _HALF_RANGE: lambda: _wound(Q, rule="half"),
        _LAST_ONLY: lambda: _wound(Q, rule="last"),
    }


def _read_inputs(arm, Q) -> dict:
    return {"robot": arm.name, "q": Q}


def _planted_flips(rng):
    """A random arm and a wavy joint path (M = 60) with every family flipping, where the sign
    of q3 or q5 differs from that of its sine somewhere, and no factor near zero."""
    while True:
        arm = random_arm(rng)
        M = 60
        s = np.linspace(0.0, 1.0, M)[:, None]
        Q = rng.uniform(-math.pi, math.pi, 6)
        for m in (rng.uniform(0.6, 1.4, 6), rng.uniform(1.6, 2.4, 6)):  # cycles over the path
            phase = rng.uniform(0.0, _TURN, 6)
            Q = Q + rng.uniform(0.0, 1.2 / m) * np.sin(_TURN * m * s + phase)
        factors = _factors(arm, Q)
        if np.abs(factors).min() < 1e-4 or np.abs(Q[:, [2, 4]]).min() < 1e-4:
            continue
        right = _flips(arm, Q)
        if not all(right.values()):
            continue
        if any(fn() == right for fn in _flip_hypotheses(arm, Q).values()):
            continue
        return arm, Q


def _read_flips(sub, rng):
    for _ in range(3):
        arm, Q = _planted_flips(rng)
        inputs = _read_inputs(arm, Q)
        got = _read_call(sub, arm, Q, inputs)["flips"]
        right = _flips(arm, Q)
        if got == right:
            continue
        name = next(n for n in _FAMILIES if got[n] != right[n])
        mistake = next(
            (m for m, fn in _flip_hypotheses(arm, Q).items() if fn() == got and fn() != right),
            None,
        )
        raise Mismatch(
            f"the {name} branch (sign of its factor) changes between samples k and k + 1 for "
            f"k in {right[name]}; got {got[name]}",
            inputs=inputs,
            mistake=mistake,
        )


def _planted_winding(rng):
    """A joint path (M = 50) in which one joint leaves [−2π, 2π] and comes back, one leaves and
    stays out, one turns by more than a turn without leaving, one passes ±π only."""
    arm = random_arm(rng)
    M = 50
    s = np.linspace(0.0, 1.0, M)
    Q = rng.uniform(-1.0, 1.0, 6) + 0.3 * np.sin(_TURN * s[:, None] + rng.uniform(0, _TURN, 6))
    back, out, net, half = rng.permutation(6)[:4]
    sign = rng.choice([-1.0, 1.0], 4)
    Q[:, back] = sign[0] * (1.5 * math.pi + 0.8 * math.pi * np.sin(math.pi * s))  # out, back
    Q[:, out] = sign[1] * np.linspace(1.4 * math.pi, 2.3 * math.pi, M)  # out at the end
    Q[:, net] = sign[2] * np.linspace(-1.1 * math.pi, 1.2 * math.pi, M)  # 2.3π, inside
    Q[:, half] = sign[3] * (0.5 * math.pi + 0.9 * math.pi * np.sin(math.pi * s))  # past π
    return arm, Q


def _read_wound(sub, rng):
    for _ in range(3):
        arm, Q = _planted_winding(rng)
        inputs = _read_inputs(arm, Q)
        got = _read_call(sub, arm, Q, inputs)["wound"]
        right = _wound(Q)
        if got == right:
            continue
        mistake = next(
            (m for m, fn in _wound_hypotheses(Q).items() if fn() == got and fn() != right), None
        )
        raise Mismatch(
            f"the joints (1-based, sorted) whose angle leaves [−2π, 2π] somewhere are {right}; "
            f"got {got}",
            inputs=inputs,
            mistake=mistake,
        )


LESSON = Lesson(
    number="08",
    title="The arm moves: paths at 1 mm, time scaling, tracking",
    summary="task-space paths sampled by arc length, time scaling and minimum durations, "
    "warm-started nearest-solution tracking and its report; seeds 000 and 002's motion "
    "replayed",
    exercises=(
        Exercise(
            id="8.1",
            function="sample_polyline",
            title="a polyline sampled at most step apart, equal along each segment",
            checks=(
                Check(
                    "open polylines: ceil(L / step) equal pieces per segment, every corner once, "
                    "ending with the last corner",
                    2,
                    _sample_open,
                ),
                Check(
                    "closed polylines: back towards corners[0] without repeating it",
                    1,
                    _sample_closed,
                ),
                Check(
                    "repeated corners add nothing; sides of a whole number of steps (seed "
                    "000's square at the default 1 mm)",
                    1,
                    _sample_edges,
                ),
            ),
            answer=(trajectory,),
        ),
        Exercise(
            id="8.2",
            function="track_nearest",
            title="nearest-solution tracking, continued by the shortest turn, holding on failure",
            checks=(
                Check(
                    "a path on which a joint turns by more than π, passing ±π: the nearest "
                    "solution each time, continued by the shortest turn",
                    2,
                    _track_sweep,
                ),
                Check(
                    "q0 with extra whole turns: wrapped differences, the winding kept",
                    1,
                    _track_turns,
                ),
                Check(
                    "unreachable samples: ok False, q[k] = q[k − 1] exactly, the next sample "
                    "compared with it",
                    2,
                    _track_failures,
                ),
            ),
            answer=(tracking, *concepts.INVERSE_KINEMATICS),
        ),
        Exercise(
            id="8.3",
            function="quintic_scaling",
            title="the quintic time scaling s(t) and its derivatives",
            checks=(
                Check("s, ṡ, s̈ for times in [0, T], any shape of t", 2, _quintic_inside),
                Check(
                    "rests at (0, 0, 0) before 0 and at (1, 0, 0) after T; one float t",
                    1,
                    _quintic_outside,
                ),
            ),
            answer=(trajectory,),
        ),
        Exercise(
            id="8.4",
            function="minimum_duration",
            title="the shortest quintic move within joint velocity and acceleration limits",
            checks=(
                Check(
                    "random distances of either sign and limits: the shortest T, at which a "
                    "peak touches its limit",
                    2,
                    _duration_random,
                ),
                Check(
                    "no motion gives 0.0; joints that do not move take no time; a limit ≤ 0 "
                    "raises ValueError",
                    1,
                    _duration_edges,
                ),
            ),
            answer=(trajectory,),
        ),
        Exercise(
            id="8.5",
            function="read_trajectory",
            title="predict, then verify: branch flips and wound joints of a joint trajectory",
            checks=(
                Check(
                    "shoulder, elbow and wrist flips between samples k and k + 1",
                    2,
                    _read_flips,
                ),
                Check("wound joints: 1-based, leaving [−2π, 2π] anywhere", 1, _read_wound),
            ),
            answer=("urkin.tracking_report", *concepts.SINGULARITIES),
        ),
    ),
)
