"""Lesson 06 — damped least squares and Levenberg–Marquardt."""

from __future__ import annotations

import ast
import itertools
import re

import numpy as np

import urkin
from urkin.course import concepts
from urkin.course.compare import (
    Mismatch,
    angles_tolerance,
    as_array,
    close,
    compare,
    format_array,
    tolerance,
    unless_right,
)
from urkin.course.exercise import Check, Exercise, Lesson
from urkin.course.inputs import random_arm, random_q, random_regular_q, random_screw_axes
from urkin.course.submission import StudentRaised
from urkin.numerical_ik import orientation_error
from urkin.poe import (
    body_screws,
    fk_body,
    fk_space,
    jacobian_body,
    jacobian_space,
    space_screws,
)
from urkin.transforms import (
    adjoint,
    inv_transform,
    make_transform,
    rotation_angle,
    se3_log,
    so3_exp,
    wrap_angles,
)

_fk, _ik, _jacobian = urkin.fk, urkin.ik, urkin.jacobian
_orientation_error = orientation_error

_HOME = np.array([0.0, -np.pi / 2, 0.0, -np.pi / 2, 0.0, 0.0])


def _random_qs(rng, count: int) -> np.ndarray:
    """``count`` configurations, uniform in [−π, π)⁶."""
    return rng.uniform(-np.pi, np.pi, (count, 6))


def _random_jacobian(rng, rows: int, cols: int = 6, singular: bool = False) -> np.ndarray:
    J = rng.normal(size=(rows, cols))
    if singular:  # make two rows dependent: the arm has lost a direction
        J[1] = 0.5 * J[0]
    return J


def _seed000_elementwise(J, e, lam):
    """Seed 000's crashing line made to run: element-wise * and **-1 where @ and inv belong."""
    return (J.T * (J * J.T + lam**2 * np.eye(J.shape[0])) ** -1) @ e


def _seed001_minus(J, e, mu):
    """Seed 001's printed update, (JᵀJ + μI)⁻¹ − JᵀV, with its minus where a product belongs."""
    return np.linalg.inv(J.T @ J + mu * np.eye(J.shape[1])) - J.T @ e


_SEED000 = (
    "seed 000's first DLS line: in numpy * and **-1 are element-wise; the damped inverse "
    "needs matrix products (@) and a solve"
)
_SEED001 = "seed 001's update (JᵀJ + μI)⁻¹ − JᵀV: the minus should be a product, (JᵀJ + μI)⁻¹ JᵀV"


def _identity_size(name: str) -> str:
    size = "m × m (J.shape[0])" if name == "dls_step" else "n × n (J.shape[1])"
    return (
        f"an identity of the wrong size: in {name} it is {size}, so that Jacobians of any "
        "shape work (np.eye(6) fails for a 3 × 6 one)"
    )


def _raised_mistake(exc: StudentRaised, J, name: str) -> str | None:
    """The likely mistake behind an exception of the student's step function."""
    if exc.kind == "NameError" and "'I'" in exc.message:
        return _SEED000 + " (and I is undefined there)"
    shapes = [
        tuple(int(n) for n in re.findall(r"\d+", found))
        for found in re.findall(r"\(([\d, ]+)\)", exc.message)
    ]
    m, n = J.shape
    if exc.kind == "ValueError" and len(shapes) >= 2:
        if {shapes[0], shapes[1]} == {(m, n), (n, m)}:
            return _SEED000
        if any(len(s) == 2 and s[0] == s[1] for s in shapes[:2]):
            return _identity_size(name)
    return None


def _step_inputs(J, e, damping, name: str) -> dict:
    return {"J": J, "e": e, "lam" if name == "dls_step" else "mu": damping}


def _call_step(sub, J, e, damping, name: str, watched: tuple[str, ...] = ()):
    """The student's step as an (n,) array, or a Mismatch that names the seeds' mistakes, and
    which of the ``watched`` library functions it reached
    (:meth:`~urkin.course.submission.Submission.spy`)."""
    inputs = _step_inputs(J, e, damping, name)
    what = f"{name}(J, e, {'lam' if name == 'dls_step' else 'mu'})"
    try:
        value, calls = sub.spy(name, watched, J.copy(), e.copy(), damping)
    except StudentRaised as exc:
        mistake = _raised_mistake(exc, J, name)
        if mistake is None:
            raise
        where = f" ({exc.where})" if exc.where else ""
        raise Mismatch(
            f"{what} raised {exc.kind}: {exc.message.strip()[:200]}{where}",
            inputs=inputs,
            mistake=mistake,
        ) from None
    m, n = J.shape
    mu = damping if name == "lm_step" else damping**2
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        array = None
    if array is not None and array.shape == (n, n):
        if close(array, _seed001_minus(J, e, mu), 1e-6):
            raise Mismatch(
                f"{name} must return the step Δq, shape ({n},); got a matrix",
                inputs=inputs,
                got=array,
                mistake=_SEED001,
            )
    if array is not None and array.shape == (n, m):
        if close(array, J.T @ np.linalg.solve(J @ J.T + mu * np.eye(m), np.eye(m)), 1e-6):
            raise Mismatch(
                f"{name} must return the step Δq, shape ({n},); got the damped inverse matrix",
                inputs=inputs,
                got=array,
                mistake="returns the matrix Jᵀ(JJᵀ + λ²I)⁻¹ instead of the step: apply it to e",
            )
    return as_array(value, (n,), what, inputs), sorted(w for w, made in calls.items() if made)


def _step_atol(got, A, expected, atol: float) -> float:
    """``atol``, or for a float32 (float16) answer its precision for a system of A's condition."""
    dtype = getattr(got, "dtype", np.dtype(float))
    if not np.issubdtype(dtype, np.floating) or dtype.itemsize >= 8:
        return atol
    scale = max(1.0, float(np.abs(expected).max(initial=0.0)))
    return max(atol, 8 * float(np.finfo(dtype).eps) * float(np.linalg.cond(A)) * scale)


# ------------------------------------------------------------------------------ 6.1 dls_step


def _dls_matrix(J, lam):
    return J @ J.T + lam**2 * np.eye(J.shape[0])


def _dls_expected(J, e, lam):
    return J.T @ np.linalg.solve(_dls_matrix(J, lam), e)


def _dls_hypotheses(J, e, lam):
    hypotheses = {
        _SEED000: lambda: _seed000_elementwise(J, e, lam),
        "λ where λ² belongs: Jᵀ(JJᵀ + λ²I)⁻¹e": lambda: (
            J.T @ np.linalg.solve(J @ J.T + lam * np.eye(J.shape[0]), e)
        ),
        "no damping: that is the plain pseudo-inverse step": lambda: np.linalg.pinv(J) @ e,
    }
    if J.shape[0] == J.shape[1]:
        hypotheses["J where Jᵀ belongs: Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e"] = lambda: (
            J @ np.linalg.solve(_dls_matrix(J, lam), e)
        )
    return hypotheses


_SHAPES = ((6, 6), (6, 6), (6, 6), (3, 6), (3, 6))


def _dls_matches(sub, rng):
    odd = (int(rng.integers(2, 6)), int(rng.integers(4, 8)))  # "any shape m × n"
    for rows, cols in (*_SHAPES, odd):
        J = _random_jacobian(rng, rows, cols)
        e, lam = rng.normal(size=rows), rng.uniform(0.05, 0.5)
        got, _ = _call_step(sub, J, e, lam, "dls_step")
        expected = _dls_expected(J, e, lam)
        compare(
            got,
            expected,
            atol=_step_atol(got, _dls_matrix(J, lam), expected, 1e-9),
            what="Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e",
            inputs=_step_inputs(J, e, lam, "dls_step"),
            hypotheses=_dls_hypotheses(J, e, lam),
        )


def _dls_at_singularities(sub, rng):
    for rows in (6, 3):
        J, e, lam = _random_jacobian(rng, rows, singular=True), rng.normal(size=rows), 0.01
        got, _ = _call_step(sub, J, e, lam, "dls_step")
        expected = _dls_expected(J, e, lam)
        compare(
            got,
            expected,
            atol=_step_atol(got, _dls_matrix(J, lam), expected, 1e-6),
            what="with a singular J the damped step stays finite: ‖Δq‖ ≤ ‖e‖ / (2λ)",
            inputs=_step_inputs(J, e, lam, "dls_step"),
            hypotheses=_dls_hypotheses(J, e, lam),
        )


_INVERSES = {"inv", "pinv", "matrix_power"}
#: numpy's inverses, watched while the student's step runs.
_INVERSE_CODE = tuple(f"numpy.linalg.{name}" for name in sorted(_INVERSES))
_INVERSE = "an explicit inverse (np.linalg.inv or pinv) where np.linalg.solve belongs"
_SVD = "an SVD where np.linalg.solve belongs: the exercise asks for the step without one"


def _inverses_in(source: str, svd_too: bool) -> list[str]:
    """What in ``source`` forms a matrix inverse (or, with ``svd_too``, uses an SVD)."""
    found = []
    try:
        tree = ast.parse(source)
    except SyntaxError:
        return found
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            func = node.func
            name = func.attr if isinstance(func, ast.Attribute) else None
            name = func.id if isinstance(func, ast.Name) else name
            if name in _INVERSES:
                found.append(f"{name}()")
            elif svd_too and name in ("svd", "damped_svd_step"):
                found.append(f"{name}()")
        elif isinstance(node, ast.Attribute) and node.attr == "I":
            found.append(".I")
    return found


def _solves(name: str, svd_too: bool):
    def run(sub, rng):
        # the code counts only for a working step (a stub or a constant has no inverse either)
        J, e, damping = _random_jacobian(rng, 6), rng.normal(size=6), rng.uniform(0.05, 0.5)
        watched = _INVERSE_CODE + (("numpy.linalg.svd",) if svd_too else ())
        got, seen = _call_step(sub, J, e, damping, name, watched)
        if name == "dls_step":
            A, expected = _dls_matrix(J, damping), _dls_expected(J, e, damping)
        else:
            A, expected = _lm_matrix(J, damping), _lm_expected(J, e, damping)
        compare(
            got,
            expected,
            atol=_step_atol(got, A, expected, 1e-9),
            what=f"the step must be right before its code is judged: {name} must match the formula",
            inputs=_step_inputs(J, e, damping, name),
        )
        found_in = [
            (function, sorted(set(_inverses_in(source, svd_too))))
            for function, source in sub.code(name).items()
        ]
        # and while it ran: an inverse named by a string built at run time is not in the code
        reached = [f"{w.rpartition('.')[2]}()" for w in seen]
        found_in.append((f"{name} (seen while it ran)", reached))
        for function, found in found_in:
            if not found:
                continue
            inverse = any(f not in ("svd()", "damped_svd_step()") for f in found)
            raise Mismatch(
                f"{function} uses {', '.join(found)}: apply the damped matrix's inverse to a "
                "vector with np.linalg.solve(A, b), without forming an inverse"
                + (" or an SVD" if svd_too else "")
                + " — faster, and more accurate",
                mistake=_INVERSE if inverse else _SVD,
            )

    return run


# ------------------------------------------------------------------------------- 6.2 lm_step


def _lm_matrix(J, mu):
    return J.T @ J + mu * np.eye(J.shape[1])


def _lm_expected(J, e, mu):
    return np.linalg.solve(_lm_matrix(J, mu), J.T @ e)


def _lm_hypotheses(J, e, mu):
    n = J.shape[1]
    hypotheses = {
        "μ² where μ belongs: Levenberg–Marquardt adds μI to JᵀJ": lambda: np.linalg.solve(
            J.T @ J + mu**2 * np.eye(n), J.T @ e
        ),
        "μ added to every entry of JᵀJ instead of its diagonal (μI)": lambda: np.linalg.solve(
            J.T @ J + mu, J.T @ e
        ),
        "the Jᵀ on the right is missing: solve (JᵀJ + μI) Δq = Jᵀe": lambda: np.linalg.solve(
            _lm_matrix(J, mu), e[:n]
        ),
        "no damping: that is the plain pseudo-inverse step": lambda: np.linalg.pinv(J) @ e,
    }
    if J.shape[0] == n:
        hypotheses["J e where Jᵀ e belongs: solve (JᵀJ + μI) Δq = Jᵀe"] = lambda: np.linalg.solve(
            _lm_matrix(J, mu), J @ e
        )
    return hypotheses


def _lm_matches(sub, rng):
    odd = (int(rng.integers(2, 6)), int(rng.integers(4, 8)))
    for rows, cols in ((6, 6), (6, 6), (6, 6), (3, 6), odd):
        J = _random_jacobian(rng, rows, cols)
        e, mu = rng.normal(size=rows), 10 ** rng.uniform(-4, 0)
        got, _ = _call_step(sub, J, e, mu, "lm_step")
        expected = _lm_expected(J, e, mu)
        compare(
            got,
            expected,
            atol=_step_atol(got, _lm_matrix(J, mu), expected, 1e-9),
            what="Δq = (JᵀJ + μ I)⁻¹ Jᵀ e",
            inputs=_step_inputs(J, e, mu, "lm_step"),
            hypotheses=_lm_hypotheses(J, e, mu),
        )


def _lm_is_dls(sub, rng):
    # (JᵀJ + μI)⁻¹Jᵀ = Jᵀ(JJᵀ + μI)⁻¹: Levenberg–Marquardt's step is the DLS step with λ² = μ
    for rows in (6, 3):
        J, e, mu = _random_jacobian(rng, rows, singular=True), rng.normal(size=rows), 1e-3
        got, _ = _call_step(sub, J, e, mu, "lm_step")
        expected = _dls_expected(J, e, np.sqrt(mu))
        compare(
            got,
            expected,
            atol=_step_atol(got, _lm_matrix(J, mu), expected, 1e-6),
            what="with λ² = μ the LM step equals the DLS step, singular J included",
            inputs=_step_inputs(J, e, mu, "lm_step"),
            hypotheses=_lm_hypotheses(J, e, mu),
        )


# --------------------------------------------------------------------------------- 6.3 ik_lm


def _pose_error(arm, q, T_target):
    T = _fk(arm, q)
    return np.r_[T_target[:3, 3] - T[:3, 3], _orientation_error(T[:3, :3], T_target[:3, :3])]


def _plain_lm(arm, T_target, q0, down, up, mu, limit, iterations=200) -> tuple[bool, int]:
    """One Levenberg–Marquardt attempt without restarts (μ ÷ down after a step that lowers
    ‖e‖, × up after one that does not; steps limited to ``limit`` rad): whether it converges,
    and how many steps it kept before its first rejection — ``iterations`` unless that
    rejected step raised every size of e (see _norms) by more than 1 %."""
    q = np.array(q0, dtype=float)
    e = _pose_error(arm, q, T_target)
    kept, first_bad, rejected = 0, iterations, False
    for _ in range(iterations):
        if np.abs(e).max() < 1e-12:
            return True, first_bad
        J = _jacobian(arm, q)
        step = np.linalg.solve(J.T @ J + mu * np.eye(6), J.T @ e)
        step *= min(1.0, limit / max(np.abs(step).max(), 1e-300))
        trial = _pose_error(arm, wrap_angles(q + step), T_target)
        if trial @ trial < e @ e:
            q, e, mu = wrap_angles(q + step), trial, max(mu / down, 1e-12)
            kept += 1
        else:
            if not rejected and np.all(_norms(trial) > 1.01 * _norms(e)):
                first_bad = kept
            rejected = True
            mu *= up
            if mu > 1e8:
                return False, first_bad
    return False, first_bad


def _lm_problem(rng, start: np.ndarray | None):
    """A random arm and a target, away from elbow and wrist singularities, that urkin's LM
    reaches without restarts from ``start`` (without one: from a start 0.5 rad away)."""
    arm = random_arm(rng)
    while True:
        centre = random_q(rng) if start is None else start
        q_true = random_regular_q(rng, centre, 0.7)
        q0 = q_true + rng.uniform(-0.5, 0.5, 6) if start is None else start.copy()
        T_target = _fk(arm, q_true)
        if _ik(arm, T_target, q0=q0, method="lm", max_restarts=0).success:
            return arm, T_target, q0


def _trap_problem(rng, restarts_reach: float = 0.0):
    """A random arm and a target near home (solution away from the elbow and wrist
    singularities) that Levenberg–Marquardt from home cannot reach without a restart — urkin's
    (Nielsen's μ rule) and two plain ones (μ ÷3/×2 as the lesson's, ÷10/×10) all stall — and
    that urkin's reaches with restarts; with ``restarts_reach``, a single attempt of urkin's
    from a random configuration must also reach it at least that often (in 48 tries), so that
    any restart scheme with a dozen restarts or more gets there too."""
    arm = random_arm(rng)
    while True:
        Q = np.array([random_regular_q(rng, _HOME, 0.7) for _ in range(48)])
        T = _fk(arm, Q)
        attempts = _ik(arm, T, q0=_HOME, method="lm", max_restarts=0)
        for i in np.flatnonzero(~attempts.success):
            if (
                not _plain_lm(arm, T[i], _HOME, 3.0, 2.0, 1e-3, 0.5)[0]
                and not _plain_lm(arm, T[i], _HOME, 10.0, 10.0, 1e-2, 1.0)[0]
                and _ik(arm, T[i], q0=_HOME, method="lm").success
                and (
                    not restarts_reach
                    or _ik(
                        arm,
                        np.repeat(T[i][None], 48, axis=0),
                        q0=_random_qs(rng, 48),
                        method="lm",
                        max_restarts=0,
                    ).success.mean()
                    >= restarts_reach
                )
            ):
                return arm, T[i]


#: Plain Levenberg–Marquardt rules (μ ÷ down, × up, first μ, step limit) that the check of
#: adaptive damping sets an overshooting first step for, one each.
_RULES = (
    (3.0, 2.0, 1e-3, 0.5),
    (10.0, 10.0, 1e-2, 1.0),
    (3.0, 2.0, 1e-4, 1.0),
    (3.0, 2.0, 1e-3, 1.0),
)


def _overshoot_problem(rng, rule):
    """A random arm and a target near home (its solution away from the elbow and wrist
    singularities) where plain Levenberg–Marquardt from home with ``rule`` rejects its first
    step within eight, and that step raises the error clearly: a solver with this rule that
    keeps every step follows the same path up to there and shows it."""
    arm = random_arm(rng)
    while True:
        T_target = _fk(arm, random_regular_q(rng, _HOME, 0.7))
        if _plain_lm(arm, T_target, _HOME, *rule, iterations=10)[1] <= 7:
            return arm, T_target, _HOME.copy()


def _lm_inputs(arm, T_target, q0) -> dict:
    return {"robot": arm.name, "q0": q0, "T_target": T_target}


def _step_call(call) -> tuple | None:
    """(J, e, μ, largest |Δq_i| returned, Δq returned) of one recorded call of lm_step, or None
    when its arguments cannot be read (the step is NaN, or None, when its result cannot be)."""
    args = list(call.args) + [call.kwargs[k] for k in ("J", "e", "mu") if k in call.kwargs]
    if len(args) < 3:
        return None
    try:
        J, e, mu = np.asarray(args[0], float), np.asarray(args[1], float), float(args[2])
    except (TypeError, ValueError):
        return None
    if J.ndim != 2 or e.shape != (J.shape[0],) or not np.isfinite(mu):
        return None
    try:
        step = np.asarray(call.result, dtype=float)
        size = float(np.abs(step).max())
    except (TypeError, ValueError):
        step, size = None, float("nan")
    if step is not None and step.shape != (J.shape[1],):
        step = None
    return J, e, mu, size, step


def _attempts(trace) -> list[list[tuple]]:
    """The recorded (J, e, μ) split into attempts: Levenberg–Marquardt never lets ‖e‖ grow, so
    a larger error starts a new attempt (a restart)."""
    attempts: list[list[tuple]] = []
    previous = np.inf
    for row in trace:
        size = float(np.linalg.norm(row[1]))
        if size > previous * (1 + 1e-9) + 1e-15 or not attempts:
            attempts.append([])
        attempts[-1].append(row)
        previous = size
    return attempts


def _spy_lm(sub, arm, T_target, q0, q0_argument=None):
    value, calls = sub.spy(
        "ik_lm",
        ("lm_step",),
        arm,
        T_target.copy(),
        q0.copy() if q0_argument is None else q0_argument,
    )
    trace = [row for row in map(_step_call, calls.get("lm_step", [])) if row is not None]
    return value, trace


_FIXED = (
    "a fixed μ: that is damped least squares, not Levenberg–Marquardt (seed 001's "
    "'Levenberg–Marquardt' never changes μ); adapt it after every step"
)
_NO_RESTART = (
    "no restarts: from this start Levenberg–Marquardt stalls in a trap (Jᵀe ≈ 0, μ keeps "
    "growing); restart from a random configuration when μ passes 1e8"
)
_NOT_INCREASED = "μ is not increased after a rejected step"
_NOT_DECREASED = "μ is not decreased after a good (accepted) step"
_ACCEPTS_ALL = "steps that raise the error are accepted: reject them and increase μ"
_SAME_RESTART = (
    "restarts from the same configuration, which leads into the same trap: restart from a "
    "random one, uniform in [−π, π)⁶"
)
_UNCHANGED = (
    "returns q0 unchanged: the loop never takes a step (a loop condition the wrong way round, "
    "like seed 001's `while ‖V‖ < ε`, or a return inside the loop)"
)
_TOO_EARLY = (
    "stops too early: a tolerance looser than 1e-12, a test on the wrong quantity, or too few "
    "iterations"
)


def _miss_mistake(trace, position: float, angle: float, arm, q0) -> str | None:
    """The likely reason why ik_lm missed, from its calls of lm_step."""
    mus = {row[2] for row in trace}
    miss = max(position, angle)
    attempts = _attempts(trace)
    _, fault, grew, shrank = _review_damping(trace)
    if len(mus) == 1 and miss < 1e-3:
        return _FIXED
    if fault is not None:
        return fault
    if _accepted_increase(trace, arm, q0):
        return _ACCEPTS_ALL
    if miss < 1e-5:
        return _NOT_DECREASED if grew and not shrank else _TOO_EARLY
    if len(attempts) == 1 and trace:
        return _NO_RESTART
    if len(attempts) > 2 and all(np.array_equal(a[0][1], attempts[0][0][1]) for a in attempts):
        return _SAME_RESTART
    return None


def _unchanged(value, q0) -> bool:
    """Whether ik_lm's answer is its initial guess."""
    try:
        q = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return False
    return q.shape == (6,) and bool(np.max(np.abs(q - q0)) < 1e-12)


def _check_lm_reached(arm, T_target, q0, value, trace, start, inputs):
    q = as_array(value, (6,), "ik_lm(robot, T_target, q0)", inputs)
    if _unchanged(q, q0):
        raise Mismatch(
            f"from {start}, ik_lm returned its initial guess unchanged",
            inputs=inputs,
            got=q,
            mistake=_UNCHANGED,
        )
    T = _fk(arm, wrap_angles(q))  # fk takes angles within a few turns: wrap the answer first
    position = float(np.linalg.norm(T[:3, 3] - T_target[:3, 3]))
    angle = float(rotation_angle(T[:3, :3], T_target[:3, :3]))
    # a float32 answer: the miss its rounding alone can cause
    tol = angles_tolerance(1e-8, q, _jacobian(arm, wrap_angles(q.astype(float))), q)
    if position <= tol and angle <= tol:
        return
    raise Mismatch(
        f"from {start}, fk(robot, q) must reach the target within {tol:.0e} m and {tol:.0e} "
        f"rad; it misses by {position:.2e} m and {angle:.2e} rad",
        inputs=inputs,
        got=q,
        mistake=_miss_mistake(trace, position, angle, arm, q0),
    )


def _lm_from(sub, rng, start_q: np.ndarray | None, start: str, count: int, as_list=False):
    for case in range(count):
        arm, T_target, q0 = _lm_problem(rng, start_q)
        inputs = _lm_inputs(arm, T_target, q0)
        argument = q0.tolist() if as_list and case == 0 else None
        try:
            value, trace = _spy_lm(sub, arm, T_target, q0, argument)
        except StudentRaised as exc:
            if argument is None:
                raise
            sub.ik_lm(arm, T_target.copy(), q0.copy())  # raises when lists are not the trouble
            where = f" ({exc.where})" if exc.where else ""
            raise Mismatch(
                f"ik_lm(robot, T_target, q0) with q0 the list {[round(x, 4) for x in argument]} "
                f"raised {exc.kind}: {exc.message.strip()[:200]}{where}",
                inputs=inputs,
                mistake="q0 as a list: convert it with np.asarray(q0, dtype=float) before using "
                "array operations on it",
            ) from None
        _check_lm_reached(arm, T_target, q0, value, trace, start, inputs)


def _lm_nearby(sub, rng):
    _lm_from(sub, rng, None, "a start 0.5 rad away", 5)


def _lm_from_singular_home(sub, rng):
    _lm_from(
        sub,
        rng,
        _HOME,
        "the home pose, where shoulder, elbow and wrist are all singular",
        4,
        as_list=True,
    )


def _rejected(before, after) -> bool:
    """Whether lm_step was called again at the same point (same J and e) after returning a
    step long enough to have moved it: the step was rejected.

    A step of round-off size, taken in a trap, may be accepted without visibly changing e:
    a pair counts only when e is unchanged bit for bit after a step above 1e-13 rad (which
    moves q), or unchanged to 1e-12 after a step above 1e-8 rad (a rejection that undid
    the step, q − Δq, leaves round-off behind)."""
    (Ja, ea, _, size, _), (Jb, eb, *_) = before, after
    if Ja.shape != Jb.shape or not size > 1e-13:
        return False
    if np.array_equal(ea, eb) and np.array_equal(Ja, Jb):
        return True
    scale = max(1.0, float(np.abs(ea).max()))
    return bool(
        size > 1e-8 and np.abs(ea - eb).max() <= 1e-12 * scale and np.abs(Ja - Jb).max() <= 1e-12
    )


def _norms(e) -> np.ndarray:
    """The sizes of a pose error a solver might compare: 1-, 2- and ∞-norms, and the position
    and orientation parts taken together (sum and larger of their lengths)."""
    p, o = np.linalg.norm(e[:3]), np.linalg.norm(e[3:])
    return np.array([np.abs(e).sum(), np.linalg.norm(e), np.abs(e).max(), p + o, max(p, o)])


def _kept(arm, q, step, J_next) -> float | None:
    """The c in [0, 1] with jacobian(q + c·step) = J_next — the step was kept, scaled down or
    not (c = 0: q stayed) — or None when there is none (a restart, or another change of q)."""
    tol = 1e-9 * max(1.0, float(np.abs(J_next).max()))

    def gap(c):
        return float(np.abs(_jacobian(arm, wrap_angles(q + c * step)) - J_next).max())

    if gap(0.0) <= tol:
        return 0.0
    grid = np.linspace(0.0, 1.0, 21)
    best = int(np.argmin([gap(c) for c in grid]))
    lo, hi = grid[max(best - 1, 0)], grid[min(best + 1, len(grid) - 1)]
    ratio = (np.sqrt(5.0) - 1.0) / 2.0
    a, b = hi - ratio * (hi - lo), lo + ratio * (hi - lo)
    gap_a, gap_b = gap(a), gap(b)
    for _ in range(60):  # golden-section search for the smallest gap
        if gap_a < gap_b:
            hi, b, gap_b = b, a, gap_a
            a = hi - ratio * (hi - lo)
            gap_a = gap(a)
        else:
            lo, a, gap_a = a, b, gap_b
            b = lo + ratio * (hi - lo)
            gap_b = gap(b)
    c = 0.5 * (lo + hi)
    return c if gap(c) <= tol else None


def _accepted_increase(trace, arm, q0) -> str | None:
    """A step that raised the error but was kept, found by following the solve from q0 while
    each call's J shows where q went (the step returned, scaled down or not; a restart or
    anything else ends the search): every size of e grew by 1 % or more."""
    q = np.array(q0, dtype=float)
    if not trace or trace[0][0].shape != (6, 6):
        return None
    if not np.abs(_jacobian(arm, q) - trace[0][0]).max() <= 1e-9:
        return None
    for k, (before, after) in enumerate(itertools.pairwise(trace[:40])):
        step = before[4]
        if step is None or before[0].shape != (6, 6) or after[0].shape != (6, 6):
            return None
        if not (np.all(np.isfinite(step)) and np.all(np.isfinite(after[0]))):
            return None
        c = _kept(arm, q, step, after[0])
        if c is None:
            return None
        if c * np.abs(step).max() <= 1e-9:
            continue  # rejected: q stays
        q = q + c * step
        if np.linalg.norm(before[1]) > 1e-9 and np.all(_norms(after[1]) > 1.01 * _norms(before[1])):
            return (
                f"after its step number {k + 1}, ik_lm called lm_step from the point the step "
                f"led to, with a larger error (‖e‖ {np.linalg.norm(before[1]):.3g} → "
                f"{np.linalg.norm(after[1]):.3g}): Levenberg–Marquardt keeps only steps that "
                "lower the error; reject the others (stay at q) and increase μ"
            )
    return None


def _review_damping(trace) -> tuple[str | None, str | None, int, int]:
    """How μ moved between the recorded calls of lm_step: the first fault found (what, and the
    mistake's name; None, None when there is none), the rejections after which μ grew and the
    good steps after which it shrank.

    A rejected step shows as two calls at the same point (same J and e): μ must not fall, nor
    stay (up to a cap above 1e3) while the same call repeats.  An accepted step
    that cut ‖e‖ below 0.4 times its value has a gain ratio ρ ≥ 0.84, after which every
    adaptive rule (÷3 or ÷10, Marquardt's thresholds, Nielsen's max(1/3, 1 − (2ρ − 1)³))
    lowers μ, or keeps it at a floor."""
    grew = shrank = 0
    for attempt in _attempts(trace):
        repeats = 0  # consecutive calls with the same J, e and μ
        for before, after in itertools.pairwise(attempt):
            mu, mu_next = before[2], after[2]
            size, size_next = np.linalg.norm(before[1]), np.linalg.norm(after[1])
            same = _rejected(before, after)
            repeats = repeats + 1 if same and mu_next == mu else 0
            if same:  # the step was rejected: retried from here
                # one repeated call may be a second use of the same step; a third is a loop
                if mu_next < mu or (repeats >= 2 and mu < 1e3):
                    what = (
                        f"after a rejected step (lm_step called again at the same point) μ went "
                        f"from {mu:.3g} to {mu_next:.3g}: it must grow, to try a shorter, more "
                        "cautious step"
                    )
                    return what, _NOT_INCREASED, grew, shrank
                grew += mu_next > mu
            elif size_next <= 0.4 * size:
                if mu_next > mu:
                    what = (
                        f"after an accepted step that cut ‖e‖ from {size:.3g} to "
                        f"{size_next:.3g}, μ went from {mu:.3g} to {mu_next:.3g}: a good step "
                        "means the linear model can be trusted more, so μ must shrink"
                    )
                    return what, _NOT_DECREASED, grew, shrank
                shrank += mu_next < mu
    return None, None, grew, shrank


def _adapts(sub, rng):
    """μ grows after every rejected step and shrinks after a very good one (see
    _review_damping), and steps that raise the error are not kept, in six solves: from home
    to a trap (rejections, then a restart), from home to four targets where an early step of
    a common rule overshoots, and from a start 0.5 rad away."""
    problems = [
        (*_trap_problem(rng), _HOME.copy()),
        *(_overshoot_problem(rng, rule) for rule in _RULES),
        _lm_problem(rng, None),
    ]
    traces = []
    for arm, T_target, q0 in problems:
        value, trace = _spy_lm(sub, arm, T_target, q0)
        if not trace:
            unchanged = _unchanged(value, q0)
            raise Mismatch(
                "ik_lm never called your lm_step: build the iteration on it, Δq = lm_step(J, e, "
                "mu) (the check watches those calls to see μ adapt)",
                inputs=_lm_inputs(arm, T_target, q0),
                mistake=_UNCHANGED if unchanged else "ik_lm does not use lm_step",
            )
        traces.append(trace)
    mus = {row[2] for trace in traces for row in trace}
    if len(mus) == 1:
        raise Mismatch(
            f"in {len(traces)} solves ik_lm called lm_step {sum(map(len, traces))} times, always "
            f"with μ = {mus.pop():.3g}: Levenberg–Marquardt adapts μ, larger after a rejected "
            "step, smaller after a good one",
            inputs=_lm_inputs(*problems[0]),
            mistake=_FIXED,
        )
    shrank = 0
    for (arm, T_target, q0), trace in zip(problems, traces):
        what, mistake, _, down = _review_damping(trace)
        if what is None:
            what, mistake = _accepted_increase(trace, arm, q0), _ACCEPTS_ALL
        if what is not None:
            raise Mismatch(what, inputs=_lm_inputs(arm, T_target, q0), mistake=mistake)
        shrank += down
    if not shrank:
        raise Mismatch(
            "μ never shrank after a good step: after an accepted step μ must decrease, so that "
            "Levenberg–Marquardt becomes Gauss–Newton near the solution",
            inputs=_lm_inputs(*problems[-1]),
            mistake=_NOT_DECREASED,
        )


def _restarts(sub, rng):
    for _ in range(2):
        arm, T_target = _trap_problem(rng, restarts_reach=0.5)
        q0 = _HOME.copy()
        inputs = _lm_inputs(arm, T_target, q0)
        value, trace = _spy_lm(sub, arm, T_target, q0)
        _check_lm_reached(
            arm,
            T_target,
            q0,
            value,
            trace,
            "home, to a target LM reaches only after a restart",
            inputs,
        )


# --------------------------------------------------------------------------------- 6.4 ik_poe


def _poe_problem(rng, n: int | None = None, away: float = 0.3):
    """(M, S, T_target, q0): a UR arm's space screws (or, with ``n``, a random arm of n joints:
    screws of random joints through random points), a target reached at random angles and a
    start ``away`` rad from them on every joint — one that the plain iteration itself solves
    within 20 steps, also from a start moved by 1e-6 rad (about 1 % of draws are not solved
    at all; on some others the iterates wander before they converge, and round-off in another
    process's linear algebra can send them elsewhere: a correct answer must not lose points
    on either)."""
    while True:
        if n is None:
            arm = random_arm(rng)
            S, M = space_screws(arm)
            q_true = random_regular_q(rng)
        else:
            S = random_screw_axes(rng, n)
            M = make_transform(p=rng.uniform(-0.5, 0.5, 3))
            q_true = rng.uniform(-np.pi, np.pi, n)
        q0 = q_true + away * rng.choice([-1.0, 1.0], len(q_true))
        T_target = fk_space(M, S, q_true)
        nudged = q0 + 1e-6 * rng.uniform(-1.0, 1.0, len(q0))
        if all(_poe_solves(M, S, T_target, start, 20) for start in (q0, nudged)):
            return M, S, T_target, q0


def _poe_solves(M, S, T_target, q, steps: int) -> bool:
    """Whether the plain iteration from ``q`` reaches the target within ``steps`` steps."""
    for _ in range(steps):
        q = _poe_one_step(M, S, T_target, q)
        if _poe_miss(M, S, T_target, q) < 1e-10:
            return True
    return False


def _reach_tolerance(got, J_s, T_target) -> float:
    """1e-8 (m and rad), or for a float32 answer the miss its own rounding can cause: J_s, the
    space Jacobian at ``got``, gives each joint's rates [ω; v], and the flange at the target
    moves at v + ω × p."""
    w, v = J_s[:3], J_s[3:]
    moves = v + np.cross(w.T, T_target[:3, 3]).T
    return angles_tolerance(1e-8, got, np.vstack([moves, w]), got)


def _poe_miss(M, S, T_target, q) -> float:
    """Position (m) or angle (rad) by which ``q`` misses the target, whichever is larger."""
    T = fk_space(M, S, q)
    return max(
        float(np.linalg.norm(T[:3, 3] - T_target[:3, 3])),
        float(rotation_angle(T[:3, :3], T_target[:3, :3])),
    )


def _poe_call(sub, M, S, T_target, q0, **kwargs) -> np.ndarray:
    inputs = {"M": M, "S": S, "T_target": T_target, "q0": q0, **kwargs}
    value = sub.ik_poe(M, S, T_target, q0, **kwargs)
    if isinstance(value, tuple) and len(value) == 2 and np.ndim(value[1]) == 0:
        value = value[0]  # Modern Robotics' (θ, success) is fine too
    return as_array(value, (S.shape[1],), "ik_poe", inputs)


def _poe_one_step(M, S, T_target, q0, twist="space", jacobian="space", swap=False):
    """One Newton step on the log error twist, with its frame and Jacobian swappable."""
    T = fk_space(M, S, q0)
    if twist == "space":
        V = se3_log(T_target @ inv_transform(T))
    elif twist == "body":
        V = se3_log(inv_transform(T) @ T_target)
    else:  # the inverse motion, log(T T_target⁻¹)
        V = se3_log(T @ inv_transform(T_target))
    if swap:
        V = np.r_[V[3:], V[:3]]
    J = jacobian_space(S, q0) if jacobian == "space" else jacobian_body(_body_from_space(M, S), q0)
    return q0 + np.linalg.pinv(J) @ V


def _body_from_space(M, S) -> np.ndarray:
    return adjoint(inv_transform(M)) @ S


def _poe_step_hypotheses(M, S, T_target, q0) -> dict:
    right = _poe_one_step(M, S, T_target, q0)
    return unless_right(
        {
            "the body twist log(T⁻¹ T_target) with the space Jacobian: pair a space twist with "
            "J_s, or a body twist with J_b": lambda: _poe_one_step(M, S, T_target, q0, "body"),
            "the space twist with the body Jacobian: pair a space twist with J_s": lambda: (
                _poe_one_step(M, S, T_target, q0, "space", "body")
            ),
            "the twist of the inverse motion, log(T T_target⁻¹): the error twist carries T to "
            "the target, log(T_target T⁻¹)": lambda: _poe_one_step(M, S, T_target, q0, "back"),
            "the twist read as (v, ω): se3_log returns (ω, v), the order the space Jacobian's "
            "rows have": lambda: _poe_one_step(M, S, T_target, q0, swap=True),
        },
        right,
    )


def _poe_first_step(sub, rng):
    for _ in range(4):
        M, S, T_target, q0 = _poe_problem(rng, away=0.6)
        compare(
            _poe_call(sub, M, S, T_target, q0, max_iterations=1),
            _poe_one_step(M, S, T_target, q0),
            what="one iteration (max_iterations=1) is q0 + J_s⁺ V_s with "
            "[V_s] = log(T_target T(q0)⁻¹) and J_s the space Jacobian at q0",
            inputs={"M": M, "S": S, "T_target": T_target, "q0": q0, "max_iterations": 1},
            hypotheses=_poe_step_hypotheses(M, S, T_target, q0),
        )


def _poe_reaches(sub, rng, any_arm: bool):
    for _ in range(3 if any_arm else 5):
        n = int(rng.integers(2, 8)) if any_arm else None
        M, S, T_target, q0 = _poe_problem(rng, n=n)
        got = _poe_call(sub, M, S, T_target, q0)
        miss = _poe_miss(M, S, T_target, got.astype(float))
        if not miss < _reach_tolerance(got, jacobian_space(S, got.astype(float)), T_target):
            raise Mismatch(
                "the answer must reach the target: e^[S1]q1 ⋯ e^[Sn]qn M = T_target within "
                f"1e-8 m and 1e-8 rad (it misses by {miss:.2g})",
                inputs={"M": M, "S": S, "T_target": T_target, "q0": q0},
                expected=T_target,
                got=fk_space(M, S, got.astype(float)),
            )


def _poe_ur_arms(sub, rng):
    _poe_reaches(sub, rng, any_arm=False)


def _poe_any_arm(sub, rng):
    _poe_reaches(sub, rng, any_arm=True)


# ----------------------------------------------------------------------- 6.5 damping_for_step

_NO_MAX_STEP_CHECK = (
    "max_step not checked: raise ValueError (naming max_step) when it is ≤ 0, NaN or infinite "
    "— no damping can keep a step within a bound of 0 or less"
)
_NO_E_CHECK = "e not checked: raise ValueError when e holds a NaN or an infinity"


def _damping_right(e, max_step) -> float:
    """λ = ‖e‖ / (2 max_step): the peak gain 1/(2λ) of σ/(σ² + λ²) times ‖e‖ is max_step."""
    return float(np.linalg.norm(e)) / (2.0 * max_step)


def _damping_hypotheses(e, max_step) -> dict:
    size = float(np.linalg.norm(e))
    return {
        "forgot the 1/2: the gain σ/(σ² + λ²) peaks at 1/(2λ), so ‖Δq‖ ≤ ‖e‖/(2λ) and "
        "λ = ‖e‖/(2·max_step)": lambda: size / max_step,
        "returned λ²: the damping term in JJᵀ + λ²I is λ², but the function returns λ": lambda: (
            (size / (2.0 * max_step)) ** 2
        ),
        "a square root: λ = √(‖e‖/max_step) — the bound ‖e‖/(2λ) is proportional to 1/λ, "
        "not 1/λ²": lambda: np.sqrt(size / max_step),
        "the largest |e_i| in place of the norm ‖e‖: the bound is on the whole step, "
        "‖Δq‖ ≤ ‖e‖/(2λ)": lambda: float(np.abs(e).max()) / (2.0 * max_step),
        "‖e‖² in place of ‖e‖: the step grows linearly with the error": lambda: (
            size**2 / (2.0 * max_step)
        ),
    }


def _damping_mistake(got, e, max_step) -> str | None:
    """The hypothesis that gives ``got`` (to 1e-9 relative, float32: its precision), unless it
    also gives the right λ for these inputs."""
    right = _damping_right(e, max_step)
    rel = tolerance(1e-9, got)
    for name, compute in _damping_hypotheses(e, max_step).items():
        candidate = float(compute())
        if abs(candidate - right) <= 1e-9 * max(right, 1e-300):
            continue
        if abs(float(got) - candidate) <= rel * max(abs(candidate), 1e-300):
            return name
    return None


def _damping_inputs(e, max_step) -> dict:
    return {"e": np.asarray(e, dtype=float), "max_step": max_step}


def _damping_call(sub, e, max_step) -> np.ndarray:
    inputs = _damping_inputs(e, max_step)
    value = sub.damping_for_step(e, max_step)
    got = as_array(value, (), "damping_for_step(e, max_step)", inputs)
    if got < 0:
        raise Mismatch(
            "the damping must be a number ≥ 0 (only λ² enters the step, so its sign means "
            "nothing: return the non-negative one)",
            inputs=inputs,
            expected=_damping_right(e, max_step),
            got=got,
        )
    return got


def _damping_agrees(got, e, max_step, what: str) -> None:
    right = _damping_right(e, max_step)
    if abs(float(got) - right) <= tolerance(1e-12, got) * right:
        return
    raise Mismatch(
        f"{what}; here ‖e‖ = {np.linalg.norm(e):.6g} and max_step = {max_step:.6g}, so λ = "
        f"{right:.6g}, but your function returned {float(got):.6g}",
        inputs=_damping_inputs(e, max_step),
        expected=right,
        got=got,
        mistake=_damping_mistake(got, e, max_step),
        difference=f"relative difference {abs(float(got) - right) / right:.1e}",
    )


def _damping_matches(sub, rng):
    for n in (1, 2, 3, 6, 6, int(rng.integers(4, 9))):
        e = rng.normal(size=n) * 10 ** rng.uniform(-3, 1)
        max_step = float(10 ** rng.uniform(-2, 1))
        shown = e.tolist() if n == 3 else e  # array_like: a list too
        got = _damping_call(sub, shown, max_step)
        _damping_agrees(
            got,
            e,
            max_step,
            "λ must be the smallest damping that keeps every DLS step within max_step: "
            "‖e‖ / (2·max_step) (to 1e-12, relative)",
        )


def _orthogonal(rng, n: int, first: np.ndarray | None = None) -> np.ndarray:
    """A random n × n orthogonal matrix (with ``first`` as its first column, when given)."""
    start = rng.normal(size=(n, n))
    if first is not None:
        start[:, 0] = first
    Q, R = np.linalg.qr(start)
    Q = Q * np.sign(np.diag(R))
    return Q


def _sharp_jacobian(rng, e, sigma) -> np.ndarray:
    """An m × k Jacobian (m = len(e)) whose singular value ``sigma`` has its output direction
    along e, the others random between 1e-3 and 10: the DLS step for e then has the length
    ‖e‖ σ/(σ² + λ²), which is largest, ‖e‖/(2λ), at σ = λ."""
    m = len(e)
    k = m + int(rng.integers(0, 3))
    U = _orthogonal(rng, m, e / np.linalg.norm(e))
    V = _orthogonal(rng, k)
    sigmas = 10 ** rng.uniform(-3, 1, m)
    sigmas[0] = sigma
    S = np.zeros((m, k))
    S[np.arange(m), np.arange(m)] = sigmas
    return U @ S @ V.T


def _damping_bound(sub, rng):
    """With the student's λ, no Jacobian gives a DLS step longer than max_step: random ones, and
    the sharpest one, whose singular value along e equals λ (then ‖Δq‖ = ‖e‖/(2λ))."""
    # λ below 1 (where λ² < λ), above 3 (where √(2λ) < λ) and anywhere
    for exponents in ((-3.0, -0.5), (0.5, 2.0), (-3.0, 2.0), (-3.0, 2.0)):
        m = int(rng.integers(2, 9))
        e = rng.normal(size=m) * 10 ** rng.uniform(-3, 0)
        max_step = float(np.linalg.norm(e) / (2.0 * 10 ** rng.uniform(*exponents)))
        inputs = _damping_inputs(e, max_step)
        got = _damping_call(sub, e, max_step)
        lam = float(got)
        if lam == 0.0:
            raise Mismatch(
                "λ = 0 for an error e ≠ 0: without damping a singular value near zero makes the "
                "step as long as you like",
                inputs=inputs,
                expected=_damping_right(e, max_step),
                got=got,
                mistake=_damping_mistake(got, e, max_step),
            )
        jacobians = [("whose singular value along e equals your λ", _sharp_jacobian(rng, e, lam))]
        jacobians += [
            ("random", rng.normal(size=(m, m + 1)) * 10 ** rng.uniform(-2, 1)) for _ in range(3)
        ]
        for kind, J in jacobians:
            step = J.T @ np.linalg.solve(J @ J.T + lam**2 * np.eye(m), e)
            length = float(np.linalg.norm(step))
            if length > max_step * (1.0 + tolerance(1e-9, got)):
                raise Mismatch(
                    f"with your λ = {lam:.6g}, a Jacobian {kind} gives a DLS step of length "
                    f"{length:.6g} rad > max_step = {max_step:.6g}: λ is too small to guarantee "
                    "the bound for every J",
                    inputs={**inputs, "J": J},
                    expected=_damping_right(e, max_step),
                    got=got,
                    mistake=_damping_mistake(got, e, max_step),
                )


def _expect_value_error(sub, e, max_step, names: str | None, mistake: str) -> None:
    inputs = {"e": np.asarray(e, dtype=float), "max_step": max_step}
    demand = f"raise ValueError{f' naming {names}' if names else ''}"
    try:
        value = sub.damping_for_step(e, max_step)
    except StudentRaised as exc:
        if exc.kind == "ValueError" and (names is None or names in exc.message):
            return
        first = exc.message.strip().splitlines()[0][:200] if exc.message.strip() else ""
        if exc.kind == "ValueError":  # raised, but the message does not say which input
            mistake = f"the ValueError's message does not name {names}: say which input is wrong"
        raise Mismatch(
            f"damping_for_step must {demand} here; it raised {exc.kind}: {first}",
            inputs=inputs,
            mistake=mistake,
        ) from None
    raise Mismatch(
        f"damping_for_step must {demand} here; it returned {format_array(value, inline=True)}",
        inputs=inputs,
        mistake=mistake,
    )


def _damping_edges(sub, rng):
    """e = 0 needs no damping; bad max_step or e raise ValueError — once λ itself is right."""
    m = int(rng.integers(2, 7))
    e, max_step = rng.normal(size=m), float(rng.uniform(0.05, 1.0))
    _damping_agrees(
        _damping_call(sub, e, max_step),
        e,
        max_step,
        "the edge cases count once λ is right: λ = ‖e‖ / (2·max_step) (to 1e-12, relative)",
    )
    got = _damping_call(sub, np.zeros(m), max_step)
    if float(got) != 0.0:
        raise Mismatch(
            "for e = 0 the step is 0 whatever λ is, so the smallest damping is λ = 0",
            inputs=_damping_inputs(np.zeros(m), max_step),
            expected=0.0,
            got=got,
        )
    for bad in (0.0, -float(rng.uniform(0.1, 1.0)), np.nan, np.inf):
        _expect_value_error(sub, e, bad, "max_step", _NO_MAX_STEP_CHECK)
    for bad in (np.nan, np.inf, -np.inf):
        broken = e.copy()
        broken[int(rng.integers(m))] = bad
        _expect_value_error(sub, broken, max_step, None, _NO_E_CHECK)


# ----------------------------------------------------------------------------- 6.6 ik_poe_body


def _body_problem(rng, n: int | None = None, away: float = 0.3, beyond_pi: bool = False):
    """(M, B, T_target, q0): a UR arm's body screws (or, with ``n``, a random arm of n joints:
    screws of random joints through random points, seen from a home pose that is turned and
    moved), a target reached at random angles and a start ``away`` rad from them on every
    joint, that the plain body iteration itself solves within 12 steps, although the answer
    gets 50: a start from which Newton wanders for longer is one where round-off decides the
    path (about 8 % of UR draws), and a correct answer whose arithmetic differs must not lose
    points on it.  With ``beyond_pi``, one joint of the start is 2π further on (the same pose,
    an angle outside [−π, π])."""
    while True:
        if n is None:
            B, M = body_screws(random_arm(rng))
            q_true = random_regular_q(rng)
        else:
            B = random_screw_axes(rng, n)
            M = make_transform(so3_exp(rng.uniform(-1.0, 1.0, 3)), rng.uniform(-0.5, 0.5, 3))
            q_true = rng.uniform(-np.pi, np.pi, n)
        q0 = q_true + away * rng.choice([-1.0, 1.0], len(q_true))
        if beyond_pi:
            joint = int(rng.integers(len(q0)))
            q0[joint] += 2 * np.pi if q0[joint] >= 0 else -2 * np.pi
        T_target = fk_body(M, B, q_true)
        if _body_miss(M, B, T_target, _body_iterate(M, B, T_target, q0, 12)) < 1e-10:
            return M, B, T_target, q0


def _body_miss(M, B, T_target, q) -> float:
    """Position (m) or angle (rad) by which ``q`` misses the target, whichever is larger."""
    T = fk_body(M, B, q)
    return max(
        float(np.linalg.norm(T[:3, 3] - T_target[:3, 3])),
        float(rotation_angle(T[:3, :3], T_target[:3, :3])),
    )


def _body_call(sub, M, B, T_target, q0, **kwargs) -> np.ndarray:
    inputs = {"M": M, "B": B, "T_target": T_target, "q0": q0, **kwargs}
    value = sub.ik_poe_body(M, B, T_target, q0, **kwargs)
    if isinstance(value, tuple) and len(value) == 2 and np.ndim(value[1]) == 0:
        value = value[0]  # Modern Robotics' (θ, success) is fine too
    return as_array(value, (B.shape[1],), "ik_poe_body", inputs)


def _body_iterate(
    M,
    B,
    T_target,
    q0,
    steps: int,
    twist="body",
    jacobian="body",
    swap=False,
    fk="body",
    frozen=False,
    wrap=False,
):
    """``steps`` Newton steps on the log error twist, each part swappable for a mistake: the
    twist's frame ("body", "space", or "back" for log(T_target⁻¹ T)), the Jacobian's frame,
    (v, ω) order, T(q) as fk_space with the body screws, the Jacobian frozen at q0, the angles
    wrapped after each step."""
    q = np.array(q0, dtype=float)
    J0 = None
    for _ in range(steps):
        T = fk_body(M, B, q) if fk == "body" else fk_space(M, B, q)
        if twist == "body":
            V = se3_log(inv_transform(T) @ T_target)
        elif twist == "space":
            V = se3_log(T_target @ inv_transform(T))
        else:
            V = se3_log(inv_transform(T_target) @ T)
        if swap:
            V = np.r_[V[3:], V[:3]]
        if jacobian == "body":
            J = jacobian_body(B, q)
        else:
            J = jacobian_space(adjoint(M) @ B, q)
        if frozen:
            J0 = J if J0 is None else J0
            J = J0
        q = q + np.linalg.pinv(J) @ V
        if wrap:
            q = wrap_angles(q)
    return q


def _body_step_hypotheses(M, B, T_target, q0, steps: int) -> dict:
    right = _body_iterate(M, B, T_target, q0, steps)

    def wrong(**mistake):
        return lambda: _body_iterate(M, B, T_target, q0, steps, **mistake)

    hypotheses = {
        "the space twist log(T_target T⁻¹) with the body Jacobian: pair the body twist "
        "log(T⁻¹ T_target) with J_b": wrong(twist="space"),
        "the body twist with the space Jacobian J_s: the body twist pairs with J_b": wrong(
            jacobian="space"
        ),
        "the space pairing J_s⁺ V_s of exercise 6.4: with fewer than six joints its "
        "least-squares step differs; the exercise asks for J_b⁺ V_b": wrong(
            twist="space", jacobian="space"
        ),
        "the twist of the inverse motion, log(T_target⁻¹ T): the error twist carries T to the "
        "target, log(T⁻¹ T_target)": wrong(twist="back"),
        "the twist read as (v, ω): se3_log returns (ω, v), the order the body Jacobian's rows "
        "have": wrong(swap=True),
        "T(q) = e^[B1]q1 ⋯ e^[Bn]qn M, fk_space with body screws: with body screws "
        "T(q) = M e^[B1]q1 ⋯ e^[Bn]qn (fk_body)": wrong(fk="space"),
        "the angles wrapped into one turn: the exercise asks for plain steps, no wrapping": (
            wrong(wrap=True)
        ),
    }
    if steps > 1:
        hypotheses[
            "the Jacobian not recomputed: J_b(q0) used at every iteration; J_b "
            "depends on q, so recompute it at each new q"
        ] = wrong(frozen=True)
    return unless_right(hypotheses, right)


def _body_steps(sub, rng, steps: int):
    problems = [
        _body_problem(rng, away=0.6, beyond_pi=True),
        _body_problem(rng, away=0.6),
        _body_problem(rng, n=int(rng.integers(2, 6)), away=0.6, beyond_pi=True),
        _body_problem(rng, n=7, away=0.6),
    ]
    what = {
        1: "one iteration (max_iterations=1) is q0 + J_b⁺ V_b with [V_b] = log(T(q0)⁻¹ "
        "T_target), T(q0) = M e^[B1]q1 ⋯ e^[Bn]qn and J_b the body Jacobian at q0",
        2: "two iterations (max_iterations=2): the second step is q1 + J_b(q1)⁺ V_b(q1), with "
        "the twist and the body Jacobian recomputed at q1, the result of the first",
    }[steps]
    for M, B, T_target, q0 in problems:
        compare(
            _body_call(sub, M, B, T_target, q0, max_iterations=steps),
            _body_iterate(M, B, T_target, q0, steps),
            what=what,
            inputs={"M": M, "B": B, "T_target": T_target, "q0": q0, "max_iterations": steps},
            hypotheses=_body_step_hypotheses(M, B, T_target, q0, steps),
        )


def _body_first_step(sub, rng):
    _body_steps(sub, rng, 1)


def _body_second_step(sub, rng):
    _body_steps(sub, rng, 2)


def _body_reaches(sub, rng, any_arm: bool):
    for _ in range(3 if any_arm else 5):
        n = int(rng.integers(2, 8)) if any_arm else None
        M, B, T_target, q0 = _body_problem(rng, n=n)
        got = _body_call(sub, M, B, T_target, q0)
        miss = _body_miss(M, B, T_target, got.astype(float))
        J_s = adjoint(fk_body(M, B, got.astype(float))) @ jacobian_body(B, got.astype(float))
        if not miss < _reach_tolerance(got, J_s, T_target):
            raise Mismatch(
                "the answer must reach the target: M e^[B1]q1 ⋯ e^[Bn]qn = T_target within "
                f"1e-8 m and 1e-8 rad (it misses by {miss:.2g})",
                inputs={"M": M, "B": B, "T_target": T_target, "q0": q0},
                expected=T_target,
                got=fk_body(M, B, got.astype(float)),
            )


def _body_ur_arms(sub, rng):
    _body_reaches(sub, rng, any_arm=False)


def _body_any_arm(sub, rng):
    _body_reaches(sub, rng, any_arm=True)


LESSON = Lesson(
    number="06",
    title="Damped least squares, Levenberg–Marquardt and the PoE solver",
    summary="damping: damped least squares, Levenberg–Marquardt, the PoE matrix-log solver, all "
    "methods compared",
    exercises=(
        Exercise(
            id="6.1",
            function="dls_step",
            title="the damped least-squares step",
            checks=(
                Check("matches Jᵀ(JJᵀ + λ²I)⁻¹e for Jacobians of any shape", 2, _dls_matches),
                Check("stays finite and right when J is singular", 1, _dls_at_singularities),
                Check(
                    "solves with np.linalg.solve: no inverse, no SVD (reads your code)",
                    1,
                    _solves("dls_step", svd_too=True),
                ),
            ),
            answer=concepts.INVERSE_KINEMATICS,
        ),
        Exercise(
            id="6.2",
            function="lm_step",
            title="the Levenberg–Marquardt step",
            checks=(
                Check("matches (JᵀJ + μI)⁻¹Jᵀe", 2, _lm_matches),
                Check("equals the DLS step with λ² = μ, even at a singularity", 1, _lm_is_dls),
                Check(
                    "solves with np.linalg.solve: no inverse (reads your code)",
                    1,
                    _solves("lm_step", svd_too=False),
                ),
            ),
            answer=concepts.INVERSE_KINEMATICS,
        ),
        Exercise(
            id="6.3",
            function="ik_lm",
            title="Levenberg–Marquardt IK with adaptive damping",
            checks=(
                Check("reaches targets from a start 0.5 rad away", 2, _lm_nearby),
                Check(
                    "starts from the triply singular home pose (given as a list)",
                    2,
                    _lm_from_singular_home,
                ),
                Check(
                    "adapts μ: larger after a rejected step, smaller after a good one",
                    1,
                    _adapts,
                ),
                Check("restarts when a trap stops it", 1, _restarts),
            ),
            answer=concepts.INVERSE_KINEMATICS,
            uses=("lm_step",),
            builds_on=("6.2",),
        ),
        Exercise(
            id="6.4",
            function="ik_poe",
            title="matrix-log IK: the space twist with the space Jacobian",
            checks=(
                Check(
                    "one iteration is q0 + J_s⁺ V_s, V_s = log(T_target T⁻¹)",
                    2,
                    _poe_first_step,
                ),
                Check("reaches targets on UR arms from 0.3 rad away", 1, _poe_ur_arms),
                Check("works for arms of 2 to 7 joints", 1, _poe_any_arm),
            ),
            answer=concepts.INVERSE_KINEMATICS,
        ),
        Exercise(
            id="6.5",
            function="damping_for_step",
            title="predict, then verify: the damping that bounds every DLS step",
            checks=(
                Check("matches λ = ‖e‖ / (2 max_step), the smallest such λ", 1, _damping_matches),
                Check(
                    "keeps the DLS step within max_step, even for a J with a singular value "
                    "equal to λ",
                    1,
                    _damping_bound,
                    gated=True,  # a huge λ passes too
                ),
                Check("e = 0 gives λ = 0; bad max_step or e raise ValueError", 1, _damping_edges),
            ),
        ),
        Exercise(
            id="6.6",
            function="ik_poe_body",
            title="matrix-log IK: the body twist with the body Jacobian",
            checks=(
                Check(
                    "one iteration is q0 + J_b⁺ V_b, V_b = log(T⁻¹ T_target)",
                    1,
                    _body_first_step,
                ),
                Check(
                    "the second iteration recomputes V_b and J_b at the new q",
                    1,
                    _body_second_step,
                ),
                Check("reaches targets on UR arms from 0.3 rad away", 1, _body_ur_arms),
                Check("works for arms of 2 to 7 joints", 1, _body_any_arm),
            ),
            answer=concepts.INVERSE_KINEMATICS,
        ),
    ),
)
