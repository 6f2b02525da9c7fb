"""Lesson 05 — Newton–Raphson inverse kinematics."""

from __future__ import annotations

import re

import numpy as np

import urkin
from urkin import trajectory
from urkin.course import concepts, wire
from urkin.course.compare import (
    Mismatch,
    angles_tolerance,
    as_array,
    close,
    compare,
    tolerance,
)
from urkin.course.exercise import Check, Exercise, Lesson
from urkin.course.inputs import random_arm, random_pose, random_regular_q
from urkin.course.submission import StudentRaised
from urkin.numerical_ik import orientation_error
from urkin.transforms import make_transform, rotation_angle, so3_exp, wrap_angles

_fk, _ik, _jacobian = urkin.fk, urkin.ik, urkin.jacobian
_orientation_error = orientation_error


def _unit(rng) -> np.ndarray:
    axis = rng.normal(size=3)
    return axis / np.linalg.norm(axis)


# ---------------------------------------------------------------------------- 5.2 pose_error


def _expected_error(T, T_target):
    e_p = T_target[:3, 3] - T[:3, 3]
    return np.r_[e_p, _orientation_error(T[:3, :3], T_target[:3, :3])]


_CROSS = (
    "the seeds' cross-product error ½ Σ rᵢ × tᵢ = sin φ·k, not the rotation vector φ·k: it "
    "shrinks for large errors and vanishes at 180°"
)
_HALF_TURN_AXIS = (
    "no half-turn branch: near φ = π, s = sin φ·k has (almost) vanished and lost the axis; read "
    "k from the symmetric part ½(R_e + R_eᵀ) − cos φ I = (1 − cos φ) k kᵀ"
)
_HALF_TURN_SIGN = (
    "the sign of k near a half turn: the column of the symmetric part gives ±k; pick the sign "
    "that agrees with s"
)
_ZERO_ANGLE = (
    "0/0 at φ = 0: φ / sin φ is undefined there (and arccos of the trace gives φ = 0 for tiny "
    "angles); use e_o = s when φ is tiny"
)
_TOOL_FRAME = (
    "the orientation error is in the tool frame, log(Rᵀ R_target); it belongs in the base "
    "frame, log(R_target Rᵀ), like the Jacobian's ω"
)


_REVERSED = (
    "the orientation part points the wrong way: log(R R_targetᵀ) is the rotation back from the "
    "target, log(R_target Rᵀ) the one towards it"
)


def _pose_error_hypotheses(T, T_target):
    right = _expected_error(T, T_target)
    e_p, e_o = right[:3], right[3:]
    cross = _orientation_error(T[:3, :3], T_target[:3, :3], "cross")
    angle = np.linalg.norm(e_o)
    return {
        _CROSS: lambda: np.r_[e_p, cross],
        "the error points the wrong way: current − target, not target − current": lambda: -right,
        _REVERSED: lambda: np.r_[e_p, -e_o],
        "the position part points the wrong way: p − p_target, not p_target − p": lambda: np.r_[
            -e_p, e_o
        ],
        _TOOL_FRAME: lambda: np.r_[e_p, T[:3, :3].T @ e_o],
        "(orientation; position) order: the geometric Jacobian puts position first": lambda: np.r_[
            e_o, e_p
        ],
        "the vee of R_e − R_eᵀ is 2 sin φ·k: the factor ½ in s is missing": lambda: np.r_[
            e_p, 2.0 * e_o
        ],
        "φ·s = φ sin φ·k: s must be divided by sin φ, e_o = (φ / sin φ) s": lambda: np.r_[
            e_p, np.sin(angle) * e_o
        ],
        "the rotation vector in degrees; radians belong with metres": lambda: np.r_[
            e_p, np.degrees(e_o)
        ],
    }


def _pose_inputs(T, T_target):
    return {"T": T, "T_target": T_target}


def _call_pose_error(sub, T, T_target, nan_mistake=None):
    inputs = _pose_inputs(T, T_target)
    try:
        return as_array(
            sub.pose_error(T.copy(), T_target.copy()), (6,), "pose_error(T, T_target)", inputs
        )
    except Mismatch as exc:
        if nan_mistake and "NaN" in exc.what:
            exc.mistake = nan_mistake
        raise


def _right_at(sub, rng, angle: float, form: str = "log") -> bool:
    """Whether the student's orientation error is right (``form="cross"``: is sin φ·k) for a
    turn of ``angle`` about a random axis: a probe that tells similar mistakes apart."""
    T = random_pose(rng)
    T_target = T @ make_transform(so3_exp(_unit(rng) * angle))
    try:
        got = np.asarray(sub.pose_error(T.copy(), T_target.copy()), dtype=float)
    except (StudentRaised, TypeError, ValueError):
        return False
    expected = _orientation_error(T[:3, :3], T_target[:3, :3], form)
    return got.shape == (6,) and close(got[3:], expected, 1e-6)


def _pose_error_mistake(sub, rng, got, T, T_target, sign_free=False, atol=1e-6):
    """The named mistake that reproduces ``got`` (with ``sign_free``, up to the sign of e_o)."""
    for name, hypothesis in _pose_error_hypotheses(T, T_target).items():
        if sign_free and name == _REVERSED:
            continue  # at a half turn, −e_o is as right as e_o
        value = np.asarray(hypothesis(), dtype=float)
        candidates = [value, np.r_[value[:3], -value[3:]]] if sign_free else [value]
        if any(close(got, c, atol) for c in candidates):
            near_half_turn = rotation_angle(T[:3, :3], T_target[:3, :3]) > 2.6
            if name == _REVERSED and near_half_turn and _right_at(sub, rng, 1.0):
                return _HALF_TURN_SIGN  # reversed only where the symmetric part gives the axis
            return name
    return None


def _compare_pose_error(sub, rng, got, T, T_target, what, atol_mistake=1e-6):
    try:
        compare(got, _expected_error(T, T_target), what=what, inputs=_pose_inputs(T, T_target))
    except Mismatch as exc:
        exc.mistake = _pose_error_mistake(sub, rng, got, T, T_target, atol=atol_mistake)
        raise


def _pose_error_matches(sub, rng):
    for _ in range(15):
        T, T_target = random_pose(rng), random_pose(rng)
        got = _call_pose_error(sub, T, T_target)
        _compare_pose_error(
            sub,
            rng,
            got,
            T,
            T_target,
            "e = [p_target − p; log(R_target Rᵀ)] (rotation vector, base frame)",
        )


def _signed_permutation(rng) -> np.ndarray:
    """A rotation whose entries are 0 and ±1: R Rᵀ = I holds exactly in floating point."""
    R = np.eye(3)[rng.permutation(3)] * rng.choice([-1.0, 1.0], 3)
    if np.linalg.det(R) < 0:
        R[:, 0] = -R[:, 0]
    return R


def _pose_error_edge_angles(sub, rng):
    # no turn at all (R_target Rᵀ = I exactly, as for a pose in a grid-aligned orientation),
    # and a turn far too small for arccos of the trace
    for angle in (0.0, 10 ** rng.uniform(-12, -9)):
        T = random_pose(rng)
        if angle == 0.0:
            T[:3, :3] = _signed_permutation(rng)
        T_target = make_transform(so3_exp(_unit(rng) * angle), rng.uniform(-0.1, 0.1, 3)) @ T
        got = _call_pose_error(sub, T, T_target, nan_mistake=_ZERO_ANGLE)
        turn = "no turn" if angle == 0 else f"a turn of {angle:.1e} rad"
        _compare_pose_error(
            sub, rng, got, T, T_target, f"{turn}: e_o = φ·k, zero or tiny", atol_mistake=1e-13
        )  # tiny values: the hypotheses differ by less
    # exactly half a turn: e_o = ±π k, either sign
    for _ in range(2):
        T, u = random_pose(rng), _unit(rng)
        T_target = T @ make_transform(so3_exp(np.pi * u), rng.uniform(-0.1, 0.1, 3))
        got = _call_pose_error(sub, T, T_target, nan_mistake=_HALF_TURN_AXIS)
        k = T[:3, :3] @ u  # the turn's axis, in the base frame
        e_p = T_target[:3, 3] - T[:3, 3]
        candidates = (np.r_[e_p, np.pi * k], np.r_[e_p, -np.pi * k])
        # 1e-7: arccos of the trace may lose its last digits at exactly π; no mistake hides there
        if any(close(got, c, 1e-7) for c in candidates):
            continue
        if np.linalg.norm(got[3:]) < 1e-6:
            mistake = _CROSS if _right_at(sub, rng, 2 * np.pi / 3, "cross") else _HALF_TURN_AXIS
        else:
            mistake = _pose_error_mistake(sub, rng, got, T, T_target, sign_free=True)
            if mistake is None and close(got[:3], e_p, 1e-6):
                mistake = _HALF_TURN_AXIS
        raise Mismatch(
            "a target turned by 180° must give an orientation error of length π along the "
            "turn's axis (either sign); the cross-product form gives 0 there, and Newton's "
            "method would stop believing it has arrived",
            inputs=_pose_inputs(T, T_target),
            expected=candidates[0],
            got=got,
            mistake=mistake,
        )
    # nearly half a turn: here the sign of k is no longer free
    for _ in range(5):
        T, u = random_pose(rng), _unit(rng)
        angle = np.pi - 10 ** rng.uniform(-6, -0.5)
        T_target = T @ make_transform(so3_exp(angle * u), rng.uniform(-0.1, 0.1, 3))
        got = _call_pose_error(sub, T, T_target, nan_mistake=_HALF_TURN_AXIS)
        _compare_pose_error(
            sub,
            rng,
            got,
            T,
            T_target,
            f"a turn of π − {np.pi - angle:.1e} rad: e_o = φ·k, with the sign of k from s",
        )


# ----------------------------------------------------------------------------- 5.3 ik_newton


def _plain_newton(arm, T_target, q0, limit, norm, position_only) -> bool:
    """Whether Newton–Raphson with the pseudo-inverse, steps scaled down to ``limit`` (their
    largest joint change, or with ``norm`` their length) and wrapped angles reaches the target
    within 1e-10 in 100 iterations."""
    q = np.array(q0, dtype=float)
    for _ in range(100):
        T = _fk(arm, q)
        e = T_target[:3, 3] - T[:3, 3]
        if not position_only:
            e = np.r_[e, _orientation_error(T[:3, :3], T_target[:3, :3])]
        if np.abs(e).max() < 1e-10:
            return True
        J = _jacobian(arm, q)
        step = np.linalg.pinv(J[:3] if position_only else J) @ e
        size = np.linalg.norm(step) if norm else np.abs(step).max()
        q = wrap_angles(q + step * min(1.0, limit / max(size, 1e-300)))
    return False


#: Step limits a correct solver might use: (limit, whether it bounds the step's length).
_LIMITS = ((1.0, False), (0.5, False), (0.3, False), (1.0, True), (0.5, True))


def _newton_problem(rng, spread: float, position_only: bool = False):
    """A random arm, a target pose it reaches at a configuration away from the elbow and wrist
    singularities, and a start ``spread`` rad away per joint from which plain Newton–Raphson
    converges with any of several step limits (largest joint change 1, 0.5 or 0.3 rad, or
    step length 1 or 0.5 rad): the start is in the solution's basin, whatever the limit."""
    arm = random_arm(rng)
    while True:
        q_true = random_regular_q(rng)
        q0 = q_true + rng.uniform(-spread, spread, 6)
        T_target = _fk(arm, q_true)
        if all(
            _plain_newton(arm, T_target, q0, limit, norm, position_only) for limit, norm in _LIMITS
        ):
            return arm, T_target, q0


def _ik_inputs(arm, T_target, q0, position_only=False):
    if position_only:
        return {"robot": arm.name, "p_target": T_target[:3, 3], "q0": q0}
    return {"robot": arm.name, "q0": q0, "T_target": T_target}


_MILLIMETRES = (
    "millimetres on one side of e = p_target − p only (seed 002 worked in mm): keep metres "
    "throughout"
)
_MILLIMETRES_BOTH = (
    "millimetres on both sides of e = p_target − p (seed 002 worked in mm): e in mm with J_v "
    "in metres gives a step 1000 times too long; keep metres throughout"
)
_UNCHANGED = (
    "returns q0 unchanged: the loop never takes a step (a loop condition the wrong way round, "
    "like seed 001's `while ‖V‖ < ε`, or a return inside the loop)"
)
_TOO_EARLY = (
    "stops too early: a tolerance looser than the exercise's 1e-12 (or tol ignored), or too few "
    "iterations"
)


def _check_reached(arm, q, q0, T_target, what, inputs, position_only=False):
    """Raise Mismatch unless fk(arm, q) reaches the target within 1e-8 (float32: its precision)."""
    if np.max(np.abs(wrap_angles(q - np.asarray(q0, dtype=float)))) < 1e-12:
        raise Mismatch(
            f"{what} returned its initial guess unchanged", inputs=inputs, got=q, mistake=_UNCHANGED
        )
    T = _fk(arm, wrap_angles(q))  # fk takes angles within a few turns: wrap the answer first
    position = float(np.linalg.norm(T[:3, 3] - T_target[:3, 3]))
    angle = 0.0 if position_only else float(rotation_angle(T[:3, :3], T_target[:3, :3]))
    # a float32 answer: the miss its rounding alone can cause
    tol = angles_tolerance(1e-8, q, _jacobian(arm, wrap_angles(q.astype(float))), q)
    if position <= tol and angle <= tol:
        return
    mistake = None
    if max(position, angle) < 1e-5:
        mistake = _TOO_EARLY
    elif position_only and close(T[:3, 3] * 1000, T_target[:3, 3], 1e-6):
        mistake = _MILLIMETRES
    elif not position_only and position <= tol and angle > 3.0:
        mistake = _CROSS
    target = "the target point" if position_only else "the target"
    miss = f"{position:.2e} m" if position_only else f"{position:.2e} m and {angle:.2e} rad"
    raise Mismatch(
        f"{what}: fk(robot, q) must reach {target} within {tol:.0e} (m and rad); it misses "
        f"by {miss}",
        inputs=inputs,
        got=q,
        mistake=mistake,
    )


def _newton_converges(sub, rng, spread: float, count: int):
    for _ in range(count):
        arm, T_target, q0 = _newton_problem(rng, spread)
        inputs = _ik_inputs(arm, T_target, q0)
        q = as_array(
            sub.ik_newton(arm, T_target.copy(), q0.copy()),
            (6,),
            "ik_newton(robot, T_target, q0)",
            inputs,
        )
        _check_reached(arm, q, q0, T_target, "ik_newton", inputs)


def _newton_close(sub, rng):
    _newton_converges(sub, rng, 0.1, 5)


def _newton_far(sub, rng):
    _newton_converges(sub, rng, 0.5, 5)


def _parallel(d, s, atol) -> bool:
    """Whether the joint change d is c·s with c > 0 (to atol in every joint)."""
    ss = float(s @ s)
    if ss == 0.0:
        return False
    c = float(d @ s) / ss
    return c > 0 and float(np.abs(d - c * s).max()) <= atol


def _one_step(sub, name, arm, target, q0, max_step, inputs):
    """The joint change of one iteration with max_iterations=1 (2 if 1 takes no step)."""
    for count in (1, 2):
        call = (
            f"{name}(robot, {'p_target' if name == 'ik_position' else 'T_target'}, q0, "
            f"max_iterations={count}, max_step={max_step})"
        )
        q = as_array(
            sub.call(name, arm, target.copy(), q0.copy(), max_iterations=count, max_step=max_step),
            (6,),
            call,
            inputs,
        )
        d = wrap_angles(q - q0)
        if np.abs(d).max() > 1e-12:
            return q, d, call
    raise Mismatch(
        f"{call} returned q0 unchanged: one iteration must take one step",
        inputs=inputs,
        got=q,
        mistake=_UNCHANGED,
    )


_ITERATIONS = "max_iterations is ignored: with max_iterations=1 it must stop after one step"
_NO_LIMIT = (
    "the step is not scaled down to max_step (no step limit, or the max_step argument ignored)"
)


def _limited(step, max_step):
    return step * min(1.0, max_step / np.abs(step).max())


def _ignores_iterations(sub, name, arm, target, q0, max_step, q_one):
    """A callable: whether max_iterations=2 gives the answer of max_iterations=1 (``q_one``)."""

    def ignored() -> bool:
        try:
            q_two = sub.call(
                name, arm, target.copy(), q0.copy(), max_iterations=2, max_step=max_step
            )
            return np.shape(q_two) == (6,) and close(np.asarray(q_two, dtype=float), q_one, 1e-12)
        except (StudentRaised, TypeError, ValueError):
            return False

    return ignored


def _judge_step(q, d, steps, max_step, call, inputs, hypotheses, ignores_iterations):
    """Raise Mismatch unless d is one of ``steps`` scaled down to at most max_step
    (``ignores_iterations()``: whether max_iterations=2 gives the same answer as 1)."""
    atol = tolerance(1e-9, like=q, scale=np.pi)
    largest = float(np.abs(d).max())
    if any(_parallel(d, s, atol) for s in steps):
        if largest <= max_step * (1 + 1e-9) + atol:
            return
        raise Mismatch(
            f"{call}: no joint may move more than max_step = {max_step} rad in one step; one "
            f"moved {largest:.4f} rad",
            inputs=inputs,
            expected=_limited(steps[0], max_step),
            got=d,
            mistake=_NO_LIMIT,
        )
    s = steps[0]
    mistake = None
    if any(close(d, wrap_angles(step), 1e-9) for step in steps):  # the whole step, then wrapped
        mistake = _NO_LIMIT
    elif ignores_iterations():
        mistake = _ITERATIONS
    elif _parallel(d, np.clip(s, -max_step, max_step), atol):
        mistake = (
            "each joint clipped to ±max_step separately: that changes the step's direction; "
            "scale the whole step down instead"
        )
    else:
        for label, step in hypotheses:
            if _parallel(d, step, atol):
                mistake = label
                break
    raise Mismatch(
        f"{call}: one iteration moves q along the Newton step Δq, scaled down so that no joint "
        "moves more than max_step",
        inputs=inputs,
        expected=_limited(s, max_step),
        got=d,
        mistake=mistake,
    )


def _student_step_error(sub, T, T_target):
    """The student's own pose_error at T, if it gives one (ik_newton is meant to use it)."""
    try:
        e = np.asarray(sub.pose_error(T.copy(), T_target.copy()), dtype=float)
    except (StudentRaised, TypeError, ValueError):
        return None
    return e if e.shape == (6,) and np.all(np.isfinite(e)) else None


def _newton_step(sub, rng):
    max_step = 0.05
    for _ in range(3):
        while True:
            arm, T_target, q0 = _newton_problem(rng, 0.5)
            T0, J = _fk(arm, q0), _jacobian(arm, q0)
            e = _expected_error(T0, T_target)
            s = np.linalg.pinv(J) @ e
            if np.abs(s).max() > 4 * max_step:
                break
        inputs = _ik_inputs(arm, T_target, q0)
        steps = [s]
        own = _student_step_error(sub, T0, T_target)
        if own is not None:
            steps.append(np.linalg.pinv(J) @ own)
        cross = np.r_[e[:3], _orientation_error(T0[:3, :3], T_target[:3, :3], "cross")]
        hypotheses = {
            "the step goes the wrong way: q + Δq with Δq = J⁺ e and e = target − current": -s,
            "Jᵀ e is the Jacobian-transpose (gradient) step, not Newton's J⁺ e": J.T @ e,
            _CROSS: np.linalg.pinv(J) @ cross,
            _TOOL_FRAME: np.linalg.pinv(J) @ np.r_[e[:3], T0[:3, :3].T @ e[3:]],
        }.items()
        q, d, call = _one_step(sub, "ik_newton", arm, T_target, q0, max_step, inputs)
        ignored = _ignores_iterations(sub, "ik_newton", arm, T_target, q0, max_step, q)
        _judge_step(q, d, steps, max_step, call, inputs, hypotheses, ignored)


_NOT_WRAPPED = "the angles are not wrapped into [−π, π): add (q + π) % 2π − π after each step"
_WRAPPED_0_2PI = "the angles are wrapped into [0, 2π) instead of [−π, π)"


def _check_wrapped(q, what, inputs):
    tol = tolerance(1e-12, like=q, scale=np.pi)
    if np.all(q >= -np.pi - tol) and np.all(q <= np.pi + tol):
        return
    mistake = _WRAPPED_0_2PI if np.all(q >= -tol) and np.all(q < 2 * np.pi + tol) else None
    raise Mismatch(
        f"{what} must return joint angles wrapped into [−π, π) (the same arm pose without extra "
        "turns); this start has whole extra turns on some joints",
        inputs=inputs,
        expected=wrap_angles(q),
        got=q,
        mistake=mistake or _NOT_WRAPPED,
    )


def _call_with_list(sub, name, arg_names, args, array_args, inputs, what):
    """Call with some arguments as plain lists.  When that raises but the same call with
    arrays does not, the failure names the missing np.asarray; otherwise it is the student's
    exception as it is (a stub's NotImplementedError included)."""
    try:
        return sub.call(name, *args)
    except StudentRaised as exc:
        sub.call(name, *array_args)  # raises on its own when lists are not the trouble
        where = f" ({exc.where})" if exc.where else ""
        raise Mismatch(
            f"{what} with {arg_names} given as a plain list raised {exc.kind}: "
            f"{exc.message.strip()[:200]}{where}",
            inputs=inputs,
            mistake=f"{arg_names} as a list: convert it with np.asarray(…, dtype=float) before "
            "using array operations on it",
        ) from None


def _extra_turns(rng) -> np.ndarray:
    turns = rng.integers(-2, 3, 6)
    turns[rng.integers(6)] = rng.choice([-1, 1])
    return 2 * np.pi * turns


def _newton_wraps_and_takes_lists(sub, rng):
    for case in range(3):
        arm, T_target, q_start = _newton_problem(rng, 0.3)
        q0 = q_start + _extra_turns(rng)
        inputs = _ik_inputs(arm, T_target, q0)
        what = "ik_newton(robot, T_target, q0)"
        if case == 0:
            value = _call_with_list(
                sub,
                "ik_newton",
                "q0",
                (arm, T_target.copy(), q0.tolist()),
                (arm, T_target.copy(), q0.copy()),
                inputs,
                what,
            )
        else:
            value = sub.ik_newton(arm, T_target.copy(), q0.copy())
        q = as_array(value, (6,), what, inputs)
        _check_reached(arm, q, q0, T_target, "ik_newton", inputs)
        _check_wrapped(q, "ik_newton", inputs)


# --------------------------------------------------------------------------- 5.1 ik_position


def _position_converges(sub, rng):
    for _ in range(8):
        arm, T_target, q0 = _newton_problem(rng, 0.4, position_only=True)
        p_target = T_target[:3, 3]
        inputs = _ik_inputs(arm, T_target, q0, position_only=True)
        q = as_array(
            sub.ik_position(arm, p_target.copy(), q0.copy()),
            (6,),
            "ik_position(robot, p_target, q0)",
            inputs,
        )
        _check_reached(arm, q, q0, T_target, "ik_position", inputs, position_only=True)


def _position_step(sub, rng):
    max_step = 0.05
    for _ in range(3):
        while True:
            arm, T_target, q0 = _newton_problem(rng, 0.5, position_only=True)
            p_target = T_target[:3, 3]
            p = _fk(arm, q0)[:3, 3]
            e = p_target - p
            J = _jacobian(arm, q0)
            s = np.linalg.pinv(J[:3]) @ e
            if np.abs(s).max() > 4 * max_step:
                break
        inputs = _ik_inputs(arm, T_target, q0, position_only=True)
        six_by_six = np.linalg.pinv(J) @ np.r_[e, 0.0, 0.0, 0.0]
        hypotheses = {
            "a 6 × 6 Jacobian with a zero orientation error keeps the orientation: that is a "
            "different, often impossible problem; use the 3 × 6 position Jacobian": six_by_six,
            "the bottom three rows of the geometric Jacobian are ω; the position rows (v) are "
            "the top three": np.linalg.pinv(J[3:]) @ e,
            "the step goes the wrong way: q + Δq with Δq = J_v⁺ e and e = p_target − p": -s,
            "J_vᵀ e is the Jacobian-transpose (gradient) step, not Newton's J_v⁺ e": J[:3].T @ e,
        }.items()
        hypotheses = [
            *hypotheses,
            (_MILLIMETRES, np.linalg.pinv(J[:3]) @ (p_target / 1000 - p)),
            (_MILLIMETRES, np.linalg.pinv(J[:3]) @ (p_target * 1000 - p)),
        ]
        q, d, call = _one_step(sub, "ik_position", arm, p_target, q0, max_step, inputs)
        ignored = _ignores_iterations(sub, "ik_position", arm, p_target, q0, max_step, q)
        _judge_step(q, d, [s], max_step, call, inputs, hypotheses, ignored)
    _position_small_step(sub, rng)


def _position_small_step(sub, rng):
    """A target a fraction of a millimetre away, max_step = 1: no step limit applies, so one
    iteration moves q by J_v⁺e itself (a step 1000 times too long is millimetres in e)."""
    arm, q0 = random_arm(rng), random_regular_q(rng)
    J = _jacobian(arm, q0)[:3]
    p = _fk(arm, q0)[:3, 3]
    e = rng.normal(size=3)
    s = np.linalg.pinv(J) @ e
    e, s = e * (3e-4 / np.abs(s).max()), s * (3e-4 / np.abs(s).max())  # the step: 3e-4 rad
    p_target = p + e
    T_target = np.eye(4)
    T_target[:3, 3] = p_target
    inputs = _ik_inputs(arm, T_target, q0, position_only=True)
    q, d, call = _one_step(sub, "ik_position", arm, p_target, q0, 1.0, inputs)
    atol = tolerance(1e-9, like=q, scale=np.pi)
    if float(np.abs(d - s).max()) <= atol:
        return
    mistake = None
    if _parallel(d, s, atol) and 500 < float(np.abs(d).max() / np.abs(s).max()) < 2000:
        mistake = _MILLIMETRES_BOTH
    raise Mismatch(
        f"{call}: with the target {1000 * np.linalg.norm(e):.2f} mm away no joint comes near "
        "max_step, so one iteration moves q by the Newton step Δq = J_v⁺e itself",
        inputs=inputs,
        expected=s,
        got=d,
        mistake=mistake,
        difference=f"largest joint change {np.abs(d).max():.2e} rad, expected "
        f"{np.abs(s).max():.2e} rad",
    )


def _position_wraps_and_takes_lists(sub, rng):
    for case in range(3):
        arm, T_target, q_start = _newton_problem(rng, 0.3, position_only=True)
        q0 = q_start + _extra_turns(rng)
        p_target = T_target[:3, 3]
        inputs = _ik_inputs(arm, T_target, q0, position_only=True)
        what = "ik_position(robot, p_target, q0)"
        if case == 0:
            value = _call_with_list(
                sub,
                "ik_position",
                "p_target and q0",
                (arm, p_target.tolist(), q0.tolist()),
                (arm, p_target.copy(), q0.copy()),
                inputs,
                what,
            )
        else:
            value = sub.ik_position(arm, p_target.copy(), q0.copy())
        q = as_array(value, (6,), what, inputs)
        _check_reached(arm, q, q0, T_target, "ik_position", inputs, position_only=True)
        _check_wrapped(q, "ik_position", inputs)


# --------------------------------------------------------------------- 5.4 convergence_order


def _order_of(e) -> float:
    """log(e_(k+1)/e_k) / log(e_k/e_(k−1)) over the last three values of ``e``."""
    a, b, c = np.asarray(e, dtype=float)[-3:]
    return float(np.log(c / b) / np.log(b / a))


def _order_sequence(rng, p: float, count: int = 6, floor: float = 1e-280) -> list[float]:
    """Up to ``count`` errors (at least three) above ``floor`` with e_(k+1) = C e_k^p, C
    random: a decreasing sequence of order p."""
    if p == 1.0:
        C = rng.uniform(0.05, 0.7)
        e = [10 ** rng.uniform(-3.0, 0.0)]
    else:
        C = 10 ** rng.uniform(-1.0, 1.0)
        ceiling = C ** (-1.0 / (p - 1.0))  # below it the sequence decreases
        e = [ceiling * 10 ** rng.uniform(-2.0, -0.5)]
    while len(e) < count and C * e[-1] ** p > floor:
        e.append(C * e[-1] ** p)
    return e


def _shown(e) -> str:
    """Errors as text with three significant digits: they span many orders of magnitude."""
    return "[" + ", ".join(f"{x:.3e}" for x in np.asarray(e, dtype=float)) + "]"


_ORDER_SHAPES = {
    (1,): "an array of one number: return the order as a float",
    (2,): "two numbers: return one estimate, from the last three errors",
}


_AMBIGUOUS = ("differences instead", "the rate")  # equal for a geometric sequence


def _order_hypotheses(e) -> dict:
    e = np.asarray(e, dtype=float)
    a, b, c = e[-3:]
    hypotheses = {
        "the first three errors: the order is read from the last three, the ones nearest the "
        "solution, where the asymptotic behaviour has set in": lambda: _order_of(e[:3]),
        "three errors but not the last three (e[-4:-1]): use e[-3:], the newest": lambda: _order_of(
            e[:-1]
        ),
        "the ratio upside down: p = log(e_(k+1)/e_k) / log(e_k/e_(k−1)) — the newest ratio "
        "goes on top": lambda: 1.0 / _order_of(e),
        "differences instead of logarithms, (e_(k+1) − e_k)/(e_k − e_(k−1)): the order "
        "compares the logarithms of successive ratios": lambda: (c - b) / (b - a),
        "the rate e_(k+1)/e_k, not the order: the rate of a linear method is this ratio, the "
        "order is log(e_(k+1)/e_k) / log(e_k/e_(k−1))": lambda: c / b,
        "a ratio of ratios, (e_(k+1)/e_k)/(e_k/e_(k−1)): take their logarithms first": lambda: (
            (c / b) / (b / a)
        ),
        "log e_(k+1) / log e_k: the order divides the logarithms of successive ratios, "
        "log(e_(k+1)/e_k) / log(e_k/e_(k−1))": lambda: np.log(c) / np.log(b),
    }
    if np.isclose((c - b) / (b - a), c / b, rtol=1e-6, atol=0.0):  # a geometric tail
        hypotheses = {k: h for k, h in hypotheses.items() if not k.startswith(_AMBIGUOUS)}
    return hypotheses


def _order_call(sub, e, inputs=None) -> np.ndarray:
    inputs = {"errors": _shown(e)} if inputs is None else inputs
    value = sub.convergence_order(e.copy() if isinstance(e, np.ndarray) else list(e))
    return as_array(value, (), "convergence_order(errors)", inputs, _ORDER_SHAPES)


def _order_compare(sub, e, what, inputs=None) -> None:
    expected = _order_of(e)
    answer = _order_call(sub, e, inputs)
    got = float(answer)
    if abs(got - expected) <= tolerance(1e-9 * max(1.0, abs(expected)), answer, expected):
        return
    mistake = None  # named by relative closeness: wrong answers such as a rate can be tiny
    for name, hypothesis in _order_hypotheses(e).items():
        try:
            with np.errstate(all="ignore"):
                candidate = float(hypothesis())
        except (ValueError, ZeroDivisionError):  # e[:-1] of three errors has only two
            continue
        if abs(candidate - expected) <= 1e-6 * max(1.0, abs(expected)):
            continue  # right for these errors: names nothing
        if abs(got - candidate) <= 1e-6 * abs(candidate):
            mistake = name
            break
    raise Mismatch(
        what,
        inputs=inputs or {"errors": _shown(e)},
        expected=f"{expected:.6g}",
        got=f"{got:.6g}",
        mistake=mistake,
    )


def _order_known(sub, rng):
    orders = [1.5, 2.0, 3.0] * 2
    rng.shuffle(orders)
    for p in [*orders, 1.0, 1.0]:  # linear last: there the rate and the differences agree
        e = np.array(_order_sequence(rng, p, count=int(rng.integers(4, 8))))
        _order_compare(
            sub,
            e,
            f"a sequence with e_(k+1) = C e_k^p exactly, of order p = {p:g}: "
            "log(e_(k+1)/e_k) / log(e_k/e_(k−1)) gives p (to 1e-9, relative)",
            inputs={"errors": _shown(e), "order": f"{p:g}"},
        )


def _order_uses_last_three(sub, rng):
    pairs = [(1.0, 2.0), (1.0, 3.0), (3.0, 1.5)]
    rng.shuffle(pairs)
    for index, (early, late) in enumerate([*pairs, (2.0, 1.0), (1.5, 1.0)]):
        head = _order_sequence(rng, early, count=int(rng.integers(3, 6)), floor=1e-60)
        tail = _order_sequence(rng, late, count=3)
        # scaled to start below the head (still decreasing); e → s e keeps the order p
        scale = 0.5 * head[-1] / tail[0]
        tail = [t * scale for t in tail]
        e = head + tail
        shown = e if index == 0 else np.array(e)  # the first one as a plain list
        _order_compare(
            sub,
            shown,
            f"order {early:g} at first, then {late:g} for the last three errors: the estimate "
            "comes from the last three",
            inputs={"errors": _shown(e), "early order": f"{early:g}", "late order": f"{late:g}"},
        )


_NO_ERROR_CHECK = (
    "no check of the input: fewer than three errors, a value that is not positive and finite, "
    "or e_k = e_(k−1) (a zero denominator) have no order; raise ValueError naming errors"
)


def _order_refuses_bad_input(sub, rng):
    e = _order_sequence(rng, 2.0, count=5)
    _order_call(sub, np.array(e))  # a function that refuses every sequence earns nothing here
    cases = [
        ("only two errors", np.array(e[-2:])),
        ("a zero error among the last three", np.r_[e[:-1], 0.0]),
        ("a negative error among the last three", np.r_[e[:-2], -e[-2], e[-1]]),
        ("a negative error early in the sequence", np.r_[-e[0], e[1:]]),
        ("NaN among the errors", np.r_[e[:-1], np.nan]),
        ("an infinite error", np.r_[np.inf, e[1:]]),
        ("e_k = e_(k−1): log(e_k/e_(k−1)) = 0", np.r_[e[:-2], e[-3], e[-1]]),
    ]
    for name, bad in cases:
        inputs = {"errors": _shown(bad), "case": name}
        try:
            value = sub.convergence_order(bad.copy())
        except StudentRaised as exc:
            if exc.kind == "NotImplementedError" and exc.message.strip().startswith("Exercise "):
                raise
            if exc.kind != "ValueError":
                raise Mismatch(
                    f"convergence_order(errors) raised {exc.kind} for {name}: the contract is a "
                    "ValueError that names errors",
                    inputs=inputs,
                    mistake=(
                        "another exception than ValueError (an assert, an IndexError, a "
                        "division by zero): raise ValueError naming errors"
                    ),
                ) from None
            if exc.message.startswith(("not enough values to unpack", "too many values")):
                raise Mismatch(
                    f"convergence_order(errors) for {name}: the ValueError came from unpacking "
                    f"({exc.message.strip()[:80]}), not from a check that names errors",
                    inputs=inputs,
                    mistake=_NO_ERROR_CHECK,
                ) from None
            if not re.search(r"\berrors\b", exc.message):
                raise Mismatch(
                    f"convergence_order(errors) raised ValueError for {name}, but its message "
                    f"does not name the argument errors: {exc.message.strip()[:120]!r}",
                    inputs=inputs,
                    mistake=(
                        "the ValueError's message does not say which argument is wrong (errors)"
                    ),
                ) from None
            continue
        raise Mismatch(
            f"convergence_order(errors) must raise ValueError for {name}, and it returned a value",
            inputs=inputs,
            got=value if np.ndim(value) == 0 else None,
            mistake=_NO_ERROR_CHECK,
        )


# ----------------------------------------------------------------------- 5.5 null_space_step


def _null_step(J, e, q, q_rest, gain, *, pull=None, wrap=True, projector="pinv", task_gain=False):
    """Δq = J⁺ e + k (I − J⁺ J) wrap(q_rest − q), with one piece swappable for a wrong one."""
    J_plus = np.linalg.pinv(J)
    difference = (q_rest - q) if pull is None else pull
    if wrap:
        difference = wrap_angles(difference)
    if projector == "none":
        N = np.eye(J.shape[1])
    elif projector == "transpose":
        N = np.eye(J.shape[1]) - J.T @ J
    else:
        N = np.eye(J.shape[1]) - J_plus @ J
    task = J_plus @ e
    return (gain * task if task_gain else task) + gain * N @ difference


def _null_hypotheses(J, e, q, q_rest, gain) -> dict:
    return {
        "the pull added without the projector (I − J⁺ J): it moves the task too": lambda: (
            _null_step(J, e, q, q_rest, gain, projector="none")
        ),
        "Jᵀ in place of J⁺ in the projector: I − Jᵀ J is no projector unless J's rows are "
        "orthonormal": lambda: _null_step(J, e, q, q_rest, gain, projector="transpose"),
        "the pull towards q instead of q_rest (q − q_rest)": lambda: _null_step(
            J, e, q, q_rest, gain, pull=q - q_rest
        ),
        "q_rest − q not wrapped: a joint a turn from its rest angle is pulled round a full "
        "turn": lambda: _null_step(J, e, q, q_rest, gain, wrap=False),
        "the gain applied to the task term J⁺ e too: only the secondary pull is scaled by k": (
            lambda: _null_step(J, e, q, q_rest, gain, task_gain=True)
        ),
    }


def _null_compare(sub, J, e, q, q_rest, gain, what) -> None:
    inputs = {"J": J, "e": e, "q": q, "q_rest": q_rest, "gain": gain}
    n = J.shape[1]
    got = as_array(
        sub.null_space_step(J.copy(), e.copy(), q.copy(), q_rest.copy(), gain),
        (n,),
        "null_space_step(J, e, q, q_rest, gain)",
        inputs,
    )
    compare(
        got,
        _null_step(J, e, q, q_rest, gain),
        what=what,
        inputs=inputs,
        hypotheses=_null_hypotheses(J, e, q, q_rest, gain),
    )


def _near_rest(rng, n: int) -> tuple[np.ndarray, np.ndarray]:
    """q and q_rest less than half a turn apart in every joint."""
    q_rest = rng.uniform(-np.pi, np.pi, n)
    return q_rest + rng.uniform(-2.5, 2.5, n), q_rest


def _null_position(sub, rng):
    for _ in range(5):
        arm = random_arm(rng)
        q, q_rest = _near_rest(rng, 6)
        J = urkin.position_jacobian(arm, q)
        e, gain = rng.normal(0, 0.05, 3), float(rng.uniform(0.1, 2.0))
        _null_compare(sub, J, e, q, q_rest, gain, "Δq = J⁺ e + k (I − J⁺ J) wrap(q_rest − q)")


def _null_shapes(sub, rng):
    for m, n in ((2, 6), (3, 7), (6, 6), (3, 6)):
        J = rng.normal(size=(m, n))
        if (m, n) == (3, 6):  # rank 2: a task direction no joint moves (as at a singularity)
            J[2] = 0.0
        q, q_rest = _near_rest(rng, n)
        _null_compare(
            sub,
            J,
            rng.normal(size=m),
            q,
            q_rest,
            float(rng.uniform(0.1, 2.0)),
            f"Δq for a {m} × {n} Jacobian"
            + (" of rank 2" if (m, n) == (3, 6) else "")
            + " (J⁺ is the pseudo-inverse, I is n × n)",
        )


def _null_wrapped(sub, rng):
    for _ in range(4):
        arm = random_arm(rng)
        q_rest = rng.uniform(-np.pi, np.pi, 6)
        q = q_rest + rng.choice([-1.0, 1.0], 6) * rng.uniform(3.5, 5.5, 6)  # > half a turn
        q = np.clip(q, -2 * np.pi, 2 * np.pi)
        J = urkin.position_jacobian(arm, q)
        _null_compare(
            sub,
            J,
            rng.normal(0, 0.05, 3),
            q,
            q_rest,
            float(rng.uniform(0.1, 2.0)),
            "with joints more than half a turn from their rest angles, q_rest − q is wrapped "
            "into (−π, π] first",
        )


# ----------------------------------------------------------------------- 5.6 track_positions

_TRACK_TOL = 1e-9  # m: the contract's default tol, and how close a row must be (rad)

_COLD = (
    "a cold start: every point is solved from q0; each must start from the previous reached "
    "answer (a warm start), q0 only for the first"
)
_OVERWRITE = (
    "a failed answer overwrites the arm's configuration (seed 000's bug): where a point is not "
    "reached, Q[k] repeats the previous row and the next point starts from there"
)
_FROM_FAILED = (
    "the next point starts from the failed answer: after a failure the guess is the last "
    "reached answer (q0 if none yet), not what the solver returned"
)
_NO_OK = (
    "ok is not recorded: ok[k] is True only where fk(robot, answer) is within tol of "
    "points[k]; an unreachable point gives False"
)
_NEVER_TESTED = (
    "every answer taken as reached: no test with urkin.fk, so a failed answer is stored, "
    "used as the next guess and marked ok"
)
_SKIP_FIRST = (
    "off by one: q0 taken as the answer for points[0] (point k+1 solved into row k+1 from row "
    "k); q0 is where the arm is before the first point, which must be solved too"
)
_ROW_BEFORE = (
    "off by one: each row stored before its point is solved: Q[k] must be the configuration "
    "after point k (its answer, or the previous row if it failed)"
)
_ONLY_Q = "only Q returned: return both, Q and ok (a tuple of two arrays)"


def _reached(arm, q, p, tol=_TRACK_TOL) -> bool:
    return bool(np.linalg.norm(_fk(arm, wrap_angles(q))[:3, 3] - p) <= tol)


def _track(arm, points, q0, solve, *, guess="reached", rows="held", ok="measured", skip=False):
    """Warm-started tracking with ``solve``, or one of its named mistakes: ``guess`` is
    "reached" (right), "q0" (cold start) or "answer" (the last answer, failed or not); ``rows``
    "held" (right), "answer" (the failed answer stored) or "before" (stored before solving);
    ``ok`` "measured" (right) or "all"; ``skip``: q0 taken as the answer for points[0]."""
    q = np.array(q0, dtype=float)
    last = q.copy()
    Q, reached = [], []
    for k, p in enumerate(points):
        if skip and k == 0:
            Q.append(q.copy())
            reached.append(True)
            continue
        start = {"reached": q, "q0": np.asarray(q0, dtype=float), "answer": last}[guess]
        answer = np.asarray(solve(arm, p, start.copy()), dtype=float)
        hit = _reached(arm, answer, p)
        before = q.copy()
        if hit or rows == "answer":
            q = answer
        last = answer
        Q.append(before if rows == "before" else q.copy())
        reached.append(hit or ok == "all")
    return np.array(Q), np.array(reached)


def _track_hypotheses(arm, points, q0, solve) -> dict:
    def run(**wrong):
        return lambda: _track(arm, points, q0, solve, **wrong)

    return {
        _COLD: run(guess="q0"),
        _NEVER_TESTED: run(guess="answer", rows="answer", ok="all"),
        _OVERWRITE: run(guess="answer", rows="answer"),
        _FROM_FAILED: run(guess="answer"),
        _NO_OK: run(ok="all"),
        _SKIP_FIRST: run(skip=True),
        _ROW_BEFORE: run(rows="before"),
    }


def _same_track(Q, ok, Q_right, ok_right, atol=_TRACK_TOL) -> bool:
    """Same ok, and rows equal modulo whole turns (a wrapped row is the same arm)."""
    return bool(
        np.array_equal(ok, ok_right)
        and Q.shape == Q_right.shape
        and np.abs(wrap_angles(Q - Q_right)).max(initial=0.0) <= atol
    )


def _call_track(sub, arm, points, q0, solve, inputs):
    M = len(points)
    what = "track_positions(robot, points, q0, solve)"
    value = sub.track_positions(arm, points.copy(), q0.copy(), solve)
    if not (isinstance(value, (tuple, list)) and len(value) == 2):
        mistake = _ONLY_Q if np.shape(value) == (M, 6) else None
        raise Mismatch(
            f"{what} must return two values, Q of shape ({M}, 6) and ok of shape ({M},)",
            inputs=inputs,
            mistake=mistake,
        )
    Q = as_array(value[0], (M, 6), f"Q, the first value {what} returns,", inputs)
    ok = as_array(value[1], (M,), f"ok, the second value {what} returns,", inputs)
    if not np.all((ok == 0) | (ok == 1)):
        raise Mismatch(
            f"ok, the second value {what} returns, must hold True or False for each point",
            inputs=inputs,
            got=ok,
        )
    return Q, ok.astype(bool)


def _track_mistake(arm, points, q0, solve, Q, ok, Q_right, ok_right):
    """The named mistake whose rows and ok the student's are (to 1e-6), or None."""
    for name, hypothesis in _track_hypotheses(arm, points, q0, solve).items():
        Q_wrong, ok_wrong = hypothesis()
        if not _same_track(Q_wrong, ok_wrong, Q_right, ok_right) and _same_track(
            Q, ok, Q_wrong, ok_wrong, 1e-6
        ):
            return name
    return None


def _judge_track(sub, arm, points, q0, solve, what, inputs):
    """Raise Mismatch unless the student's (Q, ok) is warm-started tracking with ``solve``."""
    Q, ok = _call_track(sub, arm, points, q0, solve, inputs)
    Q_right, ok_right = _track(arm, points, q0, solve)
    if _same_track(Q, ok, Q_right, ok_right):
        return
    gap = np.abs(wrap_angles(Q - Q_right)).max(axis=1)
    k = int(np.flatnonzero((ok != ok_right) | (gap > _TRACK_TOL))[0])
    wrong = []
    if ok[k] != ok_right[k]:
        wrong.append(f"ok[{k}] must be {bool(ok_right[k])}, not {bool(ok[k])}")
    if gap[k] > _TRACK_TOL:
        wrong.append(f"Q[{k}] must be the row expected below (angles compared modulo 2π)")
    raise Mismatch(
        f"{what}. Row {k} is the first wrong one: " + "; ".join(wrong),
        inputs=inputs,
        expected=Q_right[k],
        got=Q[k],
        mistake=_track_mistake(arm, points, q0, solve, Q, ok, Q_right, ok_right),
    )


def _stepping_path(rng, arm, q0, reachable):
    """Points and the stand-in solve's steps: a reachable point k lies where its step takes the
    last reached answer (so only that guess reaches it); an unreachable one is 4 m away."""
    q = np.array(q0, dtype=float)
    points, steps = [], []
    for hit in reachable:
        step = rng.uniform(-0.15, 0.15, 6) if hit else rng.uniform(-0.6, 0.6, 6)
        step[rng.integers(5)] += rng.choice([-1.0, 1.0]) * 0.1  # never a near-zero step
        if hit:
            q = q + step
            points.append(_fk(arm, q)[:3, 3])
        else:
            points.append(4.0 * _unit(rng))
        steps.append(step)
    return np.array(points), np.array(steps)


def _stepping_inputs(arm, points, q0, steps):
    return {
        "robot": arm.name,
        "q0": q0,
        "points": points,
        "solve": "the check's stand-in: solve(robot, points[k], q_guess) = q_guess + steps[k]",
        "steps": steps,
    }


def _track_warm(sub, rng):
    for _ in range(3):
        arm, q0 = random_arm(rng), random_regular_q(rng)
        points, steps = _stepping_path(rng, arm, q0, [True] * int(rng.integers(5, 9)))
        solve = wire.Function("fixed_steps", points=points, steps=steps)
        _judge_track(
            sub,
            arm,
            points,
            q0,
            solve,
            "each point is solved from the previous answer (q0 for the first): the stand-in "
            "solve returns its guess plus steps[k] (so Q[k] − steps[k] is the guess point k "
            "started from), and points[k] lies where steps[k] takes the previous answer",
            _stepping_inputs(arm, points, q0, steps),
        )


# In this order: the first two tell every named mistake apart; in the third, a cold start and
# a guess from the failed answer give the same rows.
_FAILURE_PATTERNS = (
    (False, True, True, False, True),  # the first point fails: the arm stays at q0
    (True, True, False, False, True, True),  # two failures in a row
    (True, False, True, True, False),  # the last point fails
)


def _track_failures(sub, rng):
    for pattern in _FAILURE_PATTERNS:
        arm, q0 = random_arm(rng), random_regular_q(rng)
        points, steps = _stepping_path(rng, arm, q0, pattern)
        solve = wire.Function("fixed_steps", points=points, steps=steps)
        failed = ", ".join(str(k) for k, hit in enumerate(pattern) if not hit)
        _judge_track(
            sub,
            arm,
            points,
            q0,
            solve,
            f"points {failed} are out of reach (4 m away): there ok is False and the arm stays "
            "where it was, and the next point starts from the last reached answer",
            _stepping_inputs(arm, points, q0, steps),
        )


def _track_square(sub, rng):
    ur5 = urkin.robot("UR5")
    solve = wire.Function("position_ik")
    for _ in range(2):
        while True:
            q0 = random_regular_q(rng)
            centre = _fk(ur5, q0)[:3, 3] + rng.uniform(-0.01, 0.01, 3)
            points = trajectory.square(centre, 0.03, normal=_unit(rng)).points(step=1e-3)
            if _track(ur5, points, q0, solve)[1].all():  # urkin.ik reaches every point
                break
        inputs = {
            "robot": ur5.name,
            "q0": q0,
            "points": f"a square of side 0.03 m about {np.round(centre, 4).tolist()}, "
            f"{len(points)} samples at most 1 mm apart",
            "solve": 'urkin.ik(robot, p, q0=q_guess, method="nr", max_restarts=0).q',
        }
        Q, ok = _call_track(sub, ur5, points, q0, solve, inputs)
        misses = np.linalg.norm(_fk(ur5, wrap_angles(Q))[:, :3, 3] - points, axis=1)
        wrong = np.flatnonzero(~ok | (misses > _TRACK_TOL))
        if wrong.size == 0:
            continue
        k = int(wrong[0])
        Q_right, ok_right = _track(ur5, points, q0, solve)
        mistake = _track_mistake(ur5, points, q0, solve, Q, ok, Q_right, ok_right)
        raise Mismatch(
            f"every point of the square is reachable from the previous one: ok must be True "
            f"throughout and urkin.fk(robot, Q[k]) within {_TRACK_TOL:.0e} m of points[k]; "
            f"row {k}: ok {bool(ok[k])}, flange {misses[k]:.2e} m from its point",
            inputs=inputs,
            expected=points[k],
            got=_fk(ur5, wrap_angles(Q[k]))[:3, 3],
            mistake=mistake,
        )


LESSON = Lesson(
    number="05",
    title="Newton–Raphson inverse kinematics",
    summary="Newton–Raphson IK: position-only and full pose, convergence, basins of attraction, "
    "the 180° blind spot",
    exercises=(
        Exercise(
            id="5.1",
            function="ik_position",
            title="position-only Newton–Raphson IK",
            checks=(
                Check("reaches random target points", 2, _position_converges),
                Check(
                    "one iteration is the step J_v⁺e with the 3 × 6 position Jacobian, scaled "
                    "down to max_step",
                    1,
                    _position_step,
                ),
                Check(
                    "returns angles wrapped into [−π, π); accepts p_target and q0 as lists",
                    1,
                    _position_wraps_and_takes_lists,
                ),
            ),
            answer=concepts.INVERSE_KINEMATICS,
        ),
        Exercise(
            id="5.2",
            function="pose_error",
            title="the 6-vector error between two poses",
            checks=(
                Check(
                    "matches [p_t − p; log(R_t Rᵀ)] on random pose pairs", 2, _pose_error_matches
                ),
                Check(
                    "sees a 180° turn (length π, along its axis), near half turns and no turn",
                    1,
                    _pose_error_edge_angles,
                ),
            ),
            answer=concepts.ROTATION_LOG,
        ),
        Exercise(
            id="5.3",
            function="ik_newton",
            title="full-pose Newton–Raphson IK",
            checks=(
                Check("reaches targets from a start 0.1 rad away", 2, _newton_close),
                Check("reaches targets from a start 0.5 rad away", 2, _newton_far),
                Check("one iteration is the step J⁺e, scaled down to max_step", 1, _newton_step),
                Check(
                    "returns angles wrapped into [−π, π); accepts q0 as a list",
                    1,
                    _newton_wraps_and_takes_lists,
                ),
            ),
            answer=concepts.INVERSE_KINEMATICS,
            uses=("pose_error",),
            builds_on=("5.2",),
        ),
        Exercise(
            id="5.4",
            function="convergence_order",
            title="the order of convergence from the last three errors",
            checks=(
                Check("gives the order p of sequences with e_(k+1) = C e_k^p", 1, _order_known),
                Check(
                    "reads the order from the last three errors (also of a plain list)",
                    1,
                    _order_uses_last_three,
                ),
                Check(
                    "raises ValueError naming errors for too few, non-positive or non-finite "
                    "errors and for e_k = e_(k−1)",
                    1,
                    _order_refuses_bad_input,
                ),
            ),
        ),
        Exercise(
            id="5.5",
            function="null_space_step",
            title="a task step with a secondary objective in its null space",
            checks=(
                Check("the step on position Jacobians of UR arms", 2, _null_position),
                Check("other shapes (2 × 6, 3 × 7, 6 × 6) and a rank-deficient J", 1, _null_shapes),
                Check("wraps q_rest − q into (−π, π]", 1, _null_wrapped),
            ),
        ),
        Exercise(
            id="5.6",
            function="track_positions",
            title="a path of positions, warm-started, holding on failure",
            checks=(
                Check(
                    "solves each point from the previous answer (q0 for the first)",
                    2,
                    _track_warm,
                ),
                Check(
                    "an unreachable point: ok False, the arm stays where it was, the next point "
                    "starts from the last reached answer",
                    1,
                    _track_failures,
                ),
                Check(
                    "follows a 3 cm square at 1 mm on a UR5 with urkin's position IK, every row "
                    "checked with urkin.fk",
                    1,
                    _track_square,
                ),
            ),
        ),
    ),
)
