"""Lesson 04 — Jacobians and singularities."""

from __future__ import annotations

from collections.abc import Callable
from functools import partial

import numpy as np

import urkin
from urkin.course import concepts, wire
from urkin.course.compare import (
    Mismatch,
    as_array,
    close,
    compare,
    float32_helper,
    identify_mistake,
    tolerance,
    unless_right,
)
from urkin.course.exercise import Check, Exercise, Lesson
from urkin.course.inputs import (
    negated_a,
    random_arm,
    random_pose,
    random_q,
    random_screw_axes,
)
from urkin.kinematics import (
    SINGULARITIES,
    dh_transform,
    position_jacobian,
    singularity_factors,
)
from urkin.poe import (
    body_screws,
    fk_space,
    geometric_from_space,
    jacobian_body,
    jacobian_space,
    space_from_geometric,
    space_screws,
)
from urkin.transforms import adjoint, inv_transform, se3_exp, wrap_angles

_fk, _fk_frames, _jacobian = urkin.fk, urkin.fk_frames, urkin.jacobian

# ------------------------------------------------------------------------------------ helpers


# ------------------------------------------------------------------- 4.1 geometric_jacobian


def _columns(frames, p, axis=lambda F: F[:3, 2], shift=0, lever=lambda o, p: p - o):
    """A Jacobian built column by column from a list of frames, with the recipe's pieces
    swappable (which frame, which axis, which lever arm)."""
    J = np.zeros((6, 6))
    for i in range(6):
        F = frames[i + shift]
        z = axis(F)
        J[:3, i] = np.cross(z, lever(F[:3, 3], p))
        J[3:, i] = z
    return J


def _own_frames(robot, q, convention="standard") -> list[np.ndarray]:
    frames = [np.eye(4)]
    for i in range(6):
        link = dh_transform(q[i], robot.d[i], robot.a[i], robot.alpha[i], convention)
        frames.append(frames[-1] @ link)
    return frames


def _own_columns(arm, q, convention) -> np.ndarray:
    frames = _own_frames(arm, q, convention)
    return _columns(frames, frames[-1][:3, 3])


def _jacobian_hypotheses(arm, q):
    J = _jacobian(arm, q)
    frames = list(_fk_frames(arm, q))
    p = frames[-1][:3, 3]
    R = frames[-1][:3, :3]
    hypotheses = {
        "rows in twist order (ω; v): the geometric Jacobian stacks v first, then ω": lambda: (
            np.vstack([J[3:], J[:3]])
        ),
        "joint i turns about z of frame i − 1 (the base z for joint 1), not of frame i": lambda: (
            _columns(frames, p, shift=1)
        ),
        "the angular rows from frame i: joint i turns about z_(i−1), the base z for joint 1": (
            lambda: np.vstack([J[:3], _columns(frames, p, shift=1)[3:]])
        ),
        "the linear rows from frame i: joint i turns about z_(i−1) through p_(i−1)": (
            lambda: np.vstack([_columns(frames, p, shift=1)[:3], J[3:]])
        ),
        "the lever arm points the wrong way: v_i = z_(i−1) × (p − p_(i−1)), from the joint to "
        "the flange": lambda: _columns(frames, p, lever=lambda o, p: o - p),
        "the lever arm from the base origin (z × p): it runs from the joint's origin p_(i−1) "
        "to the flange, p − p_(i−1)": lambda: _columns(frames, p, lever=lambda o, p: p),
        "the lever arm from frame i's origin: it runs from p_(i−1), on joint i's axis, to the "
        "flange": lambda: np.vstack(
            [
                np.column_stack(
                    [np.cross(frames[i][:3, 2], p - frames[i + 1][:3, 3]) for i in range(6)]
                ),
                J[3:],
            ]
        ),
        "the joint axis taken from the wrong column of the frame: z is the third column, "
        "frame[:3, 2]": lambda: _columns(frames, p, axis=lambda F: F[:3, 0]),
        "the joint axis taken from the third row of the rotation: z is the third column, "
        "frame[:3, 2]": lambda: _columns(frames, p, axis=lambda F: F[2, :3]),
        "the velocity of the wrist centre (frame 5's origin), not of the flange: p is frame "
        "6's origin": lambda: _columns(frames, frames[5][:3, 3]),
        "the space Jacobian (ω; v_s), which measures velocity at the base origin": lambda: (
            space_from_geometric(J, _fk(arm, q))
        ),
        "v measured at the base origin (v + p × ω, the space Jacobian's v_s), not at the "
        "flange": lambda: np.vstack([space_from_geometric(J, _fk(arm, q))[3:], J[3:]]),
        "the body Jacobian (ω_b; v_b), in flange coordinates: the geometric one is in base "
        "coordinates, [v; ω]": lambda: np.vstack([R.T @ J[3:], R.T @ J[:3]]),
        "[v; ω] in flange coordinates (Rᵀ v; Rᵀ ω): the geometric Jacobian is in base "
        "coordinates": lambda: np.vstack([R.T @ J[:3], R.T @ J[3:]]),
        "the Jacobian transposed": lambda: J.T,
        "the angular rows left at zero: rows 3–5 of column i hold the joint's axis "
        "z_(i−1)": lambda: np.vstack([J[:3], np.zeros((3, 6))]),
        "q treated as degrees": lambda: _jacobian(arm, np.radians(q)),
        "a2 and a3 with the wrong sign in your DH frames (UR publishes them negative)": lambda: (
            _jacobian(negated_a(arm), q)
        ),
        "frames built with modified (Craig) DH link transforms from the standard-DH table": (
            lambda: _own_columns(arm, q, "modified")
        ),
    }
    return unless_right(hypotheses, J)


def _differences(arm, q, h=1e-6):
    """∂p/∂q and the angular velocity columns of the flange, by central differences of urkin's
    forward kinematics: (3, 6) and (3, 6)."""
    steps = h * np.eye(6)
    plus, minus = _fk(arm, q + steps), _fk(arm, q - steps)
    dp = (plus[:, :3, 3] - minus[:, :3, 3]).T / (2 * h)
    W = (plus[:, :3, :3] - minus[:, :3, :3]) / (2 * h) @ _fk(arm, q)[:3, :3].T  # [ω_i]
    omega = 0.5 * np.stack(
        [W[:, 2, 1] - W[:, 1, 2], W[:, 0, 2] - W[:, 2, 0], W[:, 1, 0] - W[:, 0, 1]]
    )
    return dp, omega


_JACOBIAN_SHAPES = {
    (3, 6): "only the three linear rows: the geometric Jacobian is 6 × 6, [v; ω]",
    (6, 3): "only three columns, or the linear rows transposed: J is 6 × 6, one column per joint",
}


def _jacobian_call(sub, arm, q) -> np.ndarray:
    inputs = {"robot": arm.name, "q": q}
    value = sub.geometric_jacobian(arm, q)
    return as_array(value, (6, 6), "geometric_jacobian(robot, q)", inputs, _JACOBIAN_SHAPES)


def _compare_rows(got, rows, expected, *, what, arm, q):
    """Compare some rows of the student's J; a mistake is named from the whole matrix (a few
    rows cannot tell, say, the twist order from the space Jacobian)."""
    try:
        compare(got[rows], expected, what=what, inputs={"robot": arm.name, "q": q}, atol=1e-7)
    except Mismatch as exc:
        exc.mistake = identify_mistake(got, _jacobian_hypotheses(arm, q))
        raise


def _linear_rows_are_derivatives(sub, rng):
    for _ in range(5):
        arm, q = random_arm(rng), random_q(rng)
        got = _jacobian_call(sub, arm, q)
        _compare_rows(
            got,
            slice(0, 3),
            _differences(arm, q)[0],
            what="the first three rows must be ∂p/∂q, the rate at which the flange moves as each "
            "joint turns (checked with central differences of the flange position, h = 1e-6)",
            arm=arm,
            q=q,
        )


def _angular_rows_are_rates_of_turn(sub, rng):
    for _ in range(5):
        arm, q = random_arm(rng), random_q(rng)
        got = _jacobian_call(sub, arm, q)
        _compare_rows(
            got,
            slice(3, 6),
            _differences(arm, q)[1],
            what="the last three rows must be the flange's angular velocity per joint rate: "
            "[ω_i] = (∂R/∂q_i) Rᵀ (checked with central differences of the flange orientation, "
            "h = 1e-6)",
            arm=arm,
            q=q,
        )


def _jacobian_matches(sub, rng):
    for _ in range(10):
        arm, q = random_arm(rng), random_q(rng)
        compare(
            _jacobian_call(sub, arm, q),
            _jacobian(arm, q),
            what="column i = [z_(i−1) × (p − p_(i−1)); z_(i−1)], from the DH frames",
            inputs={"robot": arm.name, "q": q},
            hypotheses=_jacobian_hypotheses(arm, q),
        )


# ---------------------------------------------------------------------- 4.2 numeric_jacobian


def _dyadic(rng, n: int, span: float, bits: int = 8) -> np.ndarray:
    """Random multiples of 2^-bits in [−span, span]: with few binary digits, q ± h (h a power
    of 2) is exact even in float32, so a float32 implementation is judged on its arithmetic,
    not on the rounding of its steps."""
    largest = int(span * 2**bits)
    return rng.integers(-largest, largest + 1, n) / 2**bits


def _values(f, x) -> np.ndarray:
    return np.asarray(f(np.asarray(x, dtype=float)), dtype=float).ravel()


def _differentiate(f, q, h, offsets=(1.0, -1.0), base=None) -> np.ndarray:
    """Finite differences of f at q, column j = (f(q + a h e_j) − f(q + b h e_j)) / (2h) for
    ``offsets = (a, b)``; ``base(j)`` replaces e_j (for the mis-stepped hypotheses)."""
    q = np.asarray(q, dtype=float)
    columns = []
    for j in range(q.size):
        e = np.eye(q.size)[j] if base is None else base(j)
        a, b = offsets
        columns.append((_values(f, q + a * h * e) - _values(f, q + b * h * e)) / (2 * h))
    return np.column_stack(columns)


def _central(f, q, h) -> np.ndarray:
    return _differentiate(f, q, h)


_TRANSPOSED = (
    "transposed: row i is output i, column j is input q_j (shape (m, n)) — np.column_stack, "
    "or np.array(columns).T"
)


def _difference_hypotheses(f, q, h, resolution=1e-6) -> dict[str, Callable[[], np.ndarray]]:
    """Finite-difference slips; two whose answers cannot be told apart at this ``resolution``
    (zeros and J·h, for a small h) are left out."""
    n = np.size(q)
    size = float(np.abs(_central(f, q, h)).max())
    hypotheses = {
        "forward differences (f(q + h) − f(q)) / h: only first-order accurate; use central "
        "differences (f(q + h) − f(q − h)) / 2h": lambda: 2 * _differentiate(f, q, h, (1, 0)),
        "backward differences (f(q) − f(q − h)) / h: only first-order accurate; use central "
        "differences (f(q + h) − f(q − h)) / 2h": lambda: 2 * _differentiate(f, q, h, (0, -1)),
        "divided by h instead of 2h": lambda: 2 * _central(f, q, h),
        "the step h argument is ignored (a fixed step is used): use the h you are given": (
            lambda: _central(f, q, 1e-6)
        ),
        "steps of ±h/2 (f(q + h/2) − f(q − h/2)) / h: the lesson's central difference steps "
        "by ±h": lambda: 2 * _differentiate(f, q, h, (0.5, -0.5)),
        "every entry of q nudged at once (q + h): nudge one entry at a time, q + h e_j": lambda: (
            _differentiate(f, q, h, base=lambda j: np.ones(n))
        ),
        "the steps pile up from column to column: start every column from a fresh copy of q": (
            lambda: _differentiate(f, q, h, base=lambda j: (np.arange(n) <= j).astype(float))
        ),
        "(f(q + h) − f(q)) / 2h: the nudged copies share q's memory (q_plus = q does not copy): "
        "use q.copy() or q + h e_j": lambda: _differentiate(f, q, h, (1, 0)),
        _TRANSPOSED: lambda: _central(f, q, h).T,
    }
    if h * size > 10 * resolution:  # else zeros and J·h look alike
        hypotheses[
            "all zeros: q_plus and q_minus are the same array (q itself), so f(q_plus) − "
            "f(q_minus) = 0; use q.copy() or q + h e_j"
        ] = lambda: np.zeros((np.size(_values(f, q)), n))
        hypotheses["divided by 2 instead of 2h"] = lambda: h * _central(f, q, h)
    return unless_right(hypotheses, _central(f, q, h))


def _numeric_shapes(m: int, n: int) -> dict[tuple[int, ...], str]:
    shapes = {
        (m * n,): "a flat vector: return the (m, n) matrix, one row per output, one column per "
        "input",
    }
    if m != n:
        shapes[(n, m)] = _TRANSPOSED
    return shapes


def _fd_atol(got, atol: float, h: float, f_scale: float, q_scale: float, J_scale: float):
    """``atol`` for float64 answers; for a float32 answer, float32's round-off of f and of
    q ± h amplified by 1/h, which is what a correct float32 implementation produces."""
    dtype = got.dtype
    if dtype.itemsize >= 8:
        return atol
    eps = float(np.finfo(dtype).eps)
    return max(atol, 64 * eps * (J_scale + (f_scale + q_scale * J_scale) / h))


def _judge_difference(sub, f, q, h, expected, *, what, inputs, atol, as_list=False):
    """Call numeric_jacobian(f, q, h) and compare with ``expected`` (float32 answers to their
    round-off amplified by 1/h)."""
    m, n = np.size(_values(f, q)), np.size(q)
    value = sub.numeric_jacobian(f, q.tolist() if as_list else q, h)
    got = as_array(value, (m, n), "numeric_jacobian(f, q, h)", inputs, _numeric_shapes(m, n))
    scales = (
        float(np.abs(_values(f, q)).max()),
        float(np.abs(q).max()),
        float(np.abs(expected).max()),
    )
    atol = _fd_atol(got, atol, h, *scales)
    compare(
        got,
        expected,
        what=what,
        inputs=inputs,
        hypotheses=_difference_hypotheses(f, q, h, max(1e-6, atol)),
        atol=atol,
    )
    return got


_SHAPES = ((2, 5), (4, 2), (1, 3), (5, 3), (3, 6), (6, 4))


def _exact_on_linear(sub, rng):
    order = rng.permutation(len(_SHAPES))
    for case in range(4):
        m, n = _SHAPES[order[case]]
        A, b = rng.normal(size=(m, n)), rng.normal(size=m)
        q, h = _dyadic(rng, n, 1.0), 2.0 ** -int(rng.integers(2, 8))
        f = wire.Function("linear", A=A, b=b)
        as_list = case == 0
        _judge_difference(
            sub,
            f,
            q,
            h,
            A,
            what=f"for f(q) = A q + b ({m} outputs, {n} inputs) the Jacobian is A, shape ({m}, {n})"
            + (", with q given as a list" if as_list else ""),
            inputs={"A": A, "b": b, "q": q.tolist() if as_list else q, "h": h},
            atol=1e-9,
            as_list=as_list,
        )


def _smooth_derivative(x):
    return np.array(
        [
            [np.cos(x[0]) * x[1] ** 2, 2 * np.sin(x[0]) * x[1], 0.0],
            [x[1], x[0], 0.5 * np.exp(0.5 * x[2])],
            [0.0, -x[2] * np.sin(x[1] * x[2]), -x[1] * np.sin(x[1] * x[2])],
        ]
    )


_SMOOTH = "f(x) = (sin x₀ · x₁², exp(x₂/2) + x₀ x₁, cos(x₁ x₂))"


def _central_at_h(sub, rng):
    smooth = wire.Function("smooth3")
    for h in (2.0**-2, 2.0**-3, 2.0**-4):
        q = _dyadic(rng, 3, 1.0)
        _judge_difference(
            sub,
            smooth,
            q,
            h,
            _central(smooth, q, h),
            what=f"central differences with the step h = {h:g} you are given: column j is "
            "(f(q + h e_j) − f(q − h e_j)) / 2h",
            inputs={"f": _SMOOTH, "q": q, "h": h},
            atol=1e-9,
        )
    arm = random_arm(rng)
    q, h = _dyadic(rng, 6, np.pi, bits=6), 2.0**-4
    flange = wire.Function("flange_position", robot=arm)
    _judge_difference(
        sub,
        flange,
        q,
        h,
        _central(flange, q, h),
        what=f"central differences with the step h = {h:g} of the {arm.name}'s flange position "
        "(3 outputs, 6 inputs)",
        inputs={"f": f"the {arm.name}'s flange position p(q)", "q": q, "h": h},
        atol=1e-9,
    )
    for _ in range(2):
        q, h = _dyadic(rng, 3, 1.0), 2.0**-10
        _judge_difference(
            sub,
            smooth,
            q,
            h,
            _smooth_derivative(q),
            what="with h ≈ 1e-3 central differences are within ~1e-6 of the derivative "
            "(second order)",
            inputs={"f": _SMOOTH, "q": q, "h": h},
            atol=2e-5,
        )


def _float32_steps(f, q, h) -> np.ndarray:
    """Central differences with q and h in float32 (f in float64): what a correct float32
    implementation that differentiates a float64 function returns."""
    x, step = np.asarray(q, dtype=np.float32), np.float32(h)
    columns = []
    for j in range(x.size):
        e = np.zeros_like(x)
        e[j] = step
        columns.append((_values(f, x + e) - _values(f, x - e)) / (2 * h))
    return np.column_stack(columns)


def _default_step_hypotheses(f, q) -> dict[str, Callable[[], np.ndarray]]:
    hypotheses = dict(_difference_hypotheses(f, q, 1e-6))
    for h in (1e-2, 1e-3, 1e-4, 1e-8):
        hypotheses[f"the default step is not the lesson's h = 1e-6 (this looks like h = {h:g})"] = (
            lambda h=h: _central(f, q, h)
        )
    return unless_right(hypotheses, _central(f, q, 1e-6))


def _on_the_arm(sub, rng):
    arm, q = random_arm(rng), random_q(rng)
    flange = wire.Function("flange_position", robot=arm)
    inputs = {"f": f"the {arm.name}'s flange position p(q)", "q": q}
    what = "∂p/∂q of the flange position (a 3 × 6 matrix), with the default step h = 1e-6"
    got = as_array(
        sub.numeric_jacobian(flange, q),
        (3, 6),
        "numeric_jacobian(f, q)",
        inputs,
        _numeric_shapes(3, 6),
    )
    exact = _jacobian(arm, q)[:3]
    if got.dtype.itemsize >= 8:
        steps32 = _float32_steps(flange, q, 1e-6)
        if close(got, steps32, 1e-6 * float(np.abs(exact).max())):
            return  # q ± h rounded to float32: as good as float32 steps can be
        compare(
            got,
            exact,
            what=what + " (central differences there are accurate to ~1e-10, forward ones to "
            "~1e-7; the tolerance is 1e-8)",
            inputs=inputs,
            atol=1e-8,
            hypotheses=_default_step_hypotheses(flange, q),
        )
        return
    # a float32 answer: at h = 1e-6 its round-off (~ε₃₂/h) swamps the derivative, so it is
    # judged there to that precision, and again at h = 2⁻⁸, where float32 is accurate
    atol = _fd_atol(got, 1e-7, 1e-6, 1.0, float(np.abs(q).max()), float(np.abs(exact).max()))
    compare(
        got,
        exact,
        what=what,
        inputs=inputs,
        atol=atol,
        hypotheses=_difference_hypotheses(flange, q, 1e-6),
    )
    q = _dyadic(rng, 6, np.pi, bits=6)
    _judge_difference(
        sub,
        flange,
        q,
        2.0**-8,
        _central(flange, q, 2.0**-8),
        what=what.replace(
            "the default step h = 1e-6",
            "h = 2⁻⁸ (a float32 answer is also judged where float32 is accurate)",
        ),
        inputs={**inputs, "q": q, "h": 2.0**-8},
        atol=1e-9,
    )


# ------------------------------------------------------ 4.3 jacobian_space, 4.4 jacobian_body


def _twist_form_inputs(form: str, rng):
    """Screw axes and angles: a UR arm's (space or body) half the time, else 2 to 7 joints."""
    if rng.random() < 0.5:
        arm = random_arm(rng)
        axes = (space_screws if form == "space" else body_screws)(arm)[0]
        return axes, random_q(rng)
    n = int(rng.integers(2, 8))
    return random_screw_axes(rng, n, 0.6), rng.uniform(-np.pi, np.pi, n)


def _exp(axis, angle) -> np.ndarray:
    return se3_exp(np.asarray(axis) * angle)


def _carried(axes, q, left=False) -> np.ndarray:
    """Column i is ``Ad(e^[A1]q1 ⋯ e^[A(i−1)]q(i−1)) A_i``: the space recipe, the product of
    exponentials multiplied on the right (or, wrongly, on the left).  The body recipe is
    the same read from the last joint with the angles negated (see the hypotheses)."""
    J, T = np.zeros(np.shape(axes)), np.eye(4)
    for i in range(np.shape(axes)[1]):
        J[:, i] = adjoint(T) @ axes[:, i]
        T = _exp(axes[:, i], q[i]) @ T if left else T @ _exp(axes[:, i], q[i])
    return J


_VW_ORDER = "rows in the order (v, ω): a twist is (ω, v), angular part first"


def _twist_jacobian_hypotheses(form: str, axes, q) -> dict:
    right = (jacobian_space if form == "space" else jacobian_body)(axes, q)
    hypotheses = {
        _VW_ORDER: lambda: np.r_[right[3:], right[:3]],
        "each column is the home axis itself: the joints before it move it (the adjoint of "
        "their product)"
        if form == "space"
        else "each column is the home body axis itself: "
        "the joints after it move it, seen from the end effector": lambda: np.array(axes),
        "angles in degrees": lambda: (jacobian_space if form == "space" else jacobian_body)(
            axes, np.radians(q)
        ),
    }
    if form == "space":
        hypotheses[
            "the product of exponentials multiplied on the left (e^[S_i]q_i T), not the "
            "right: the joints are carried in order 1, 2, …"
        ] = lambda: _carried(axes, q, left=True)
        hypotheses["the body Jacobian: space columns are Ad(e^[S1]q1 ⋯ e^[S(i−1)]q(i−1)) S_i"] = (
            lambda: jacobian_body(axes, q)
        )
    else:
        hypotheses[
            "exponentials of +B_k q_k: the body columns need e^(−[B_k] q_k), the "
            "motion of the joints after i undone"
        ] = lambda: _carried(axes[:, ::-1], q[::-1])[:, ::-1]
        hypotheses[
            "the product taken from joint 1 forwards: the body columns carry the joints "
            "after i, from joint n backwards"
        ] = lambda: _carried(axes, -q)
        hypotheses["the space Jacobian: body columns are Ad(e^−[Bn]qn ⋯ e^−[B(i+1)]q(i+1)) B_i"] = (
            lambda: jacobian_space(axes, q)
        )
    return unless_right(hypotheses, right)


def _twist_jacobian_call(form: str, sub, axes, q, inputs) -> np.ndarray:
    function = sub.jacobian_space if form == "space" else sub.jacobian_body
    n = axes.shape[1]
    shapes = {(n, 6): f"the transpose, ({n}, 6): one column per joint, shape (6, {n})"}
    return as_array(function(axes, q), (6, n), f"jacobian_{form}", inputs, shapes)


def _twist_jacobian_home(form: str, sub, rng):
    letter = "S" if form == "space" else "B"
    for _ in range(4):
        axes, q = _twist_form_inputs(form, rng)
        n = axes.shape[1]
        inputs = {letter: axes, "q": np.zeros(n)}
        compare(
            _twist_jacobian_call(form, sub, axes, np.zeros(n), inputs),
            axes,
            what=f"at q = 0 every column is its home axis: J = {letter}",
            inputs=inputs,
            hypotheses=unless_right({_VW_ORDER: lambda a=axes: np.r_[a[3:], a[:3]]}, axes),
        )
        inputs = {letter: axes, "q": q}
        got = _twist_jacobian_call(form, sub, axes, q, inputs)
        index, what = (0, "the first") if form == "space" else (n - 1, "the last")
        compare(
            got[:, index],
            axes[:, index],
            what=f"{what} column is {letter}_{index + 1} at any q: no joint "
            + ("before" if form == "space" else "after")
            + " it moves its axis",
            inputs=inputs,
        )


def _twist_jacobian_matches(form: str, sub, rng):
    letter = "S" if form == "space" else "B"
    for _ in range(8):
        axes, q = _twist_form_inputs(form, rng)
        inputs = {letter: axes, "q": q}
        compare(
            _twist_jacobian_call(form, sub, axes, q, inputs),
            (jacobian_space if form == "space" else jacobian_body)(axes, q),
            what=(
                "J_s column i = Ad(e^[S1]q1 ⋯ e^[S(i−1)]q(i−1)) S_i"
                if form == "space"
                else "J_b column i = Ad(e^−[Bn]qn ⋯ e^−[B(i+1)]q(i+1)) B_i"
            ),
            inputs=inputs,
            hypotheses=_twist_jacobian_hypotheses(form, axes, q),
        )


def _twist_of(T_dot: np.ndarray) -> np.ndarray:
    """(ω, v) of a 4 × 4 twist matrix."""
    return np.r_[T_dot[2, 1], T_dot[0, 2], T_dot[1, 0], T_dot[:3, 3]]


def _twist_jacobian_differentiates(form: str, sub, rng):
    """Each column is the twist of the pose's derivative: Ṫ T⁻¹ (space) or T⁻¹ Ṫ (body), by
    central differences of the product of exponentials."""
    letter = "S" if form == "space" else "B"
    h = 1e-6
    for _ in range(4):
        axes, q = _twist_form_inputs(form, rng)
        n = axes.shape[1]
        inputs = {letter: axes, "q": q}
        got = _twist_jacobian_call(form, sub, axes, q, inputs)

        def product(angles, axes=axes):
            return fk_space(np.eye(4), axes, angles)  # e^[A1]q1 ⋯ e^[An]qn

        T_inv = inv_transform(product(q))
        expected = np.empty((6, n))
        for i in range(n):
            step = h * np.eye(n)[i]
            T_dot = (product(q + step) - product(q - step)) / (2 * h)
            expected[:, i] = _twist_of(T_dot @ T_inv if form == "space" else T_inv @ T_dot)
        if not close(got, expected, 1e-7):
            raise Mismatch(
                "column i must be the "
                + ("spatial twist Ṫ T⁻¹" if form == "space" else "body twist T⁻¹ Ṫ")
                + " of the product of exponentials when joint i alone turns at 1 rad/s "
                "(central differences, h = 1e-6, compared to 1e-7)",
                inputs=inputs,
                expected=expected,
                got=got,
                mistake=identify_mistake(got, _twist_jacobian_hypotheses(form, axes, q)),
            )


def _twist_jacobian_exercise(exercise_id: str, form: str) -> Exercise:
    letter = "S" if form == "space" else "B"
    return Exercise(
        id=exercise_id,
        function=f"jacobian_{form}",
        title=f"the {form} Jacobian from screw axes",
        checks=(
            Check(
                f"J = {letter} at q = 0, and the "
                + ("first" if form == "space" else "last")
                + " column never moves",
                1,
                partial(_twist_jacobian_home, form),
                gated=True,  # returning the screw axes passes too
            ),
            Check(
                "matches the Jacobian for UR arms and arms of 2 to 7 joints",
                2,
                partial(_twist_jacobian_matches, form),
            ),
            Check(
                "its columns are the twists of the pose's derivative, joint by joint",
                1,
                partial(_twist_jacobian_differentiates, form),
            ),
        ),
        answer=concepts.JACOBIAN,
    )


# ----------------------------------------------------------------------- 4.5 singularities

_FAMILY_JOINT = {"elbow": 2, "wrist": 4}


def _factor(arm, q) -> float:
    """The shoulder factor a2 cos q2 + a3 cos(q2 + q3) + d5 sin(q2 + q3 + q4), metres."""
    return float(singularity_factors(arm, q)[0])


def _shoulder_q4(arm, q, target: float) -> float | None:
    """q4 that makes the shoulder factor equal ``target`` (None if the wrist cannot)."""
    reach = arm.a2 * np.cos(q[1]) + arm.a3 * np.cos(q[1] + q[2])
    s = (target - reach) / arm.d5
    if abs(s) > 0.95:
        return None
    return float(wrap_angles(np.arcsin(s) - q[1] - q[2]))


def _configuration(arm, rng, families=(), near: dict | None = None) -> np.ndarray:
    """A configuration on exactly ``families`` (or, for ``near = {family: value}``, with that
    family's factor equal to the value); the other factors are far from zero."""
    near = near or {}
    while True:
        q = random_q(rng)
        for family, joint in _FAMILY_JOINT.items():
            if family in families:
                q[joint] = rng.choice([0.0, np.pi, -np.pi])
            elif family in near:
                q[joint] = wrap_angles(np.arcsin(near[family]) + rng.choice([0.0, np.pi]))
        if "shoulder" in families or "shoulder" in near:
            target = near.get("shoulder", 0.0)
            # choose q2 so that the reach is within the wrist's d5 of the target
            A, B = arm.a2 + arm.a3 * np.cos(q[2]), -arm.a3 * np.sin(q[2])
            K = float(np.hypot(A, B))
            reach = rng.uniform(-0.8, 0.8) * min(arm.d5, K)
            q[1] = wrap_angles(np.arctan2(B, A) + rng.choice([-1.0, 1.0]) * np.arccos(reach / K))
            q4 = _shoulder_q4(arm, q, target)
            if q4 is None:
                continue
            q[3] = q4
        factors = np.abs(singularity_factors(arm, q))
        wanted = [name in families for name in SINGULARITIES]
        ok = all(
            (f <= 1e-12) if want else (name in near or f >= (0.02 if name == "shoulder" else 0.2))
            for name, f, want in zip(SINGULARITIES, factors, wanted)
        )
        if ok:
            return q


def _regular_configuration(arm, rng) -> np.ndarray:
    q = _configuration(arm, rng)
    if rng.random() < 0.5:  # cos q3 = 0 or cos q5 = 0: where a cosine test goes wrong
        q[2] = rng.choice([np.pi / 2, -np.pi / 2])
    else:
        q[4] = rng.choice([np.pi / 2, -np.pi / 2])
    if abs(_factor(arm, q)) < 0.02:
        return _regular_configuration(arm, rng)
    return q


_NAMES_HINT = "a set of names such as {'wrist'} (empty when q is regular)"


def _names(value, inputs) -> set[str]:
    what = "singularities(robot, q)"
    if value is None:
        raise Mismatch(f"{what} returned None: is a `return` statement missing?", inputs=inputs)
    if isinstance(value, dict) and not value:
        return set()  # {} for the empty set: a common slip that means the same here
    if isinstance(value, dict) and all(isinstance(v, (bool, np.bool_)) for v in value.values()):
        raise Mismatch(
            f"{what} must return {_NAMES_HINT}; got a dict of flags {value!r:.80}",
            inputs=inputs,
            mistake="a dict of True/False flags: return the set of the names that are present",
        )
    if isinstance(value, str):
        raise Mismatch(
            f"{what} must return {_NAMES_HINT}; got the string {value!r:.80}",
            inputs=inputs,
            mistake="a single string: return a set of names, even for one family",
        )
    if not isinstance(value, (set, frozenset, list, tuple, dict)):
        raise Mismatch(
            f"{what} must return {_NAMES_HINT}; got {type(value).__name__} {value!r:.80}",
            inputs=inputs,
            mistake="not a set of names: return {'shoulder', 'elbow', 'wrist'} or a subset",
        )
    items = list(value)
    if items and all(isinstance(v, (bool, np.bool_)) for v in items):
        raise Mismatch(
            f"{what} must return {_NAMES_HINT}; got the flags {items!r:.80}",
            inputs=inputs,
            mistake="True/False flags for (shoulder, elbow, wrist): return the names of the "
            "families that are present",
        )
    names = {str(v).strip().lower() for v in items}
    unknown = names - set(SINGULARITIES)
    if unknown:
        raise Mismatch(
            f"{what} returned unknown names {sorted(unknown)}; use "
            f"{', '.join(repr(s) for s in SINGULARITIES)}",
            inputs=inputs,
            mistake="the family names must be exactly 'shoulder', 'elbow' and 'wrist'",
        )
    return names


def _ask(sub, arm, q, tol=None) -> set[str]:
    inputs = {"robot": arm.name, "q": q} | ({} if tol is None else {"tol": f"{tol:.1e}"})
    value = sub.singularities(arm, q) if tol is None else sub.singularities(arm, q, tol)
    return _names(value, inputs)


def _flags(sub, arm, q, family, tol=None) -> bool | None:
    """Whether the student's function flags ``family`` at q (None if it fails there)."""
    try:
        return family in _ask(sub, arm, q, tol)
    except Exception:  # a probe that fails tells us nothing
        return None


def _zero_along(G, q, joint) -> np.ndarray | None:
    """q with q[joint] moved to a zero of G (a sign change on a grid, then bisection)."""
    grid = np.linspace(-np.pi, np.pi, 181)
    values = []
    for x in grid:
        probe = q.copy()
        probe[joint] = x
        values.append(G(probe))
    for k in range(len(grid) - 1):
        if values[k] == 0 or values[k] * values[k + 1] < 0:
            lo, hi = grid[k], grid[k + 1]
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                probe = q.copy()
                probe[joint] = lo
                g_lo = G(probe)
                probe[joint] = mid
                if g_lo * G(probe) <= 0:
                    hi = mid
                else:
                    lo = mid
            probe = q.copy()
            probe[joint] = 0.5 * (lo + hi)
            return probe
    return None


_NO_ABS = (
    "the absolute value is missing: a factor of −1 is not ≤ tol; a family is present when "
    "|factor| ≤ tol"
)
_OFF_BY_ONE = (
    "joint numbers off by one: q_k is q[k − 1] in Python (0-based) — q2 is q[1], q3 is q[2], "
    "q5 is q[4]"
)


def _shoulder_candidates(arm) -> dict[str, Callable[[np.ndarray], float]]:
    a2, a3, d4, d5 = arm.a2, arm.a3, arm.d4, arm.d5

    def reach(q):
        return a2 * np.cos(q[1]) + a3 * np.cos(q[1] + q[2])

    return {
        "the shoulder factor without its wrist term: it is a2 cos q2 + a3 cos(q2+q3) "
        "+ d5 sin(q2+q3+q4)": reach,
        "the wrist term of the shoulder factor with the wrong sign: + d5 sin(q2+q3+q4)": (
            lambda q: reach(q) - d5 * np.sin(q[1] + q[2] + q[3])
        ),
        "d4 in the shoulder factor where d5 belongs: a2 cos q2 + a3 cos(q2+q3) "
        "+ d5 sin(q2+q3+q4)": lambda q: reach(q) + d4 * np.sin(q[1] + q[2] + q[3]),
        "cos(q2+q3+q4) in the shoulder factor where sin(q2+q3+q4) belongs": (
            lambda q: reach(q) + d5 * np.cos(q[1] + q[2] + q[3])
        ),
        "a2 and a3 taken positive in the shoulder factor (UR's are negative: use robot.a2, "
        "robot.a3)": lambda q: -reach(q) + d5 * np.sin(q[1] + q[2] + q[3]),
        "sin and cos swapped in the shoulder factor: a2 cos q2 + a3 cos(q2+q3) "
        "+ d5 sin(q2+q3+q4)": lambda q: (
            a2 * np.sin(q[1]) + a3 * np.sin(q[1] + q[2]) + d5 * np.cos(q[1] + q[2] + q[3])
        ),
        _OFF_BY_ONE: lambda q: (
            a2 * np.cos(q[2]) + a3 * np.cos(q[2] + q[3]) + d5 * np.sin(q[2] + q[3] + q[4])
        ),
    }


def _family_probes(sub, arm, name, joint, base) -> str | None:
    """Name a mistake in the elbow or wrist test from the student's answers near ``base``."""
    label = f"q{joint + 1}"
    at = {}
    for value in (np.pi / 2, -np.pi / 2, 0.0, np.pi, 1e-12, 2 * np.pi):
        probe = base.copy()
        probe[joint] = value
        at[value] = _flags(sub, arm, probe, name)
    if at[-np.pi / 2] and at[np.pi / 2] is False:
        return _NO_ABS
    if at[np.pi / 2]:
        return f"the {name} tested with cos {label}: it is singular where sin {label} = 0"
    shifted = base.copy()
    shifted[joint + 1] = 0.0  # the next joint at zero, this one regular
    if (
        (joint + 1 != 3 or abs(_factor(arm, shifted)) > 0.02)
        and _flags(sub, arm, base, name) is False
        and _flags(sub, arm, shifted, name)
    ):
        return _OFF_BY_ONE
    if at[0.0] and at[np.pi] is False:
        if at[1e-12]:
            return (
                f"the {name} is singular at {label} = ±π too, not only at 0: test "
                f"|sin {label}| ≤ tol"
            )
        return (
            f"the {name} compared with 0 exactly: sin π is 1.2e-16 in floating point, "
            f"not 0 — test |sin {label}| ≤ tol"
        )
    if at[0.0] and at[np.pi] and at[2 * np.pi] is False:
        return (
            f"the {name} tested on the angle {label} (0 and ±π) instead of sin {label}: "
            f"{label} = ±2π is the same singular configuration"
        )
    return None


def _shoulder_probes(sub, arm, rng) -> str | None:
    """Name a mistake in the shoulder factor: the student flags the zero of a wrong one."""
    for label, G in _shoulder_candidates(arm).items():
        tried = 0
        for _ in range(6):
            base = _configuration(arm, rng)
            for joint in (3, 1):
                probe = _zero_along(G, base, joint)
                if probe is None:
                    continue
                factors = np.abs(singularity_factors(arm, probe))
                if factors[0] < 0.02 or factors[1] < 0.1 or factors[2] < 0.1:
                    continue
                flagged = _flags(sub, arm, probe, "shoulder")
                if flagged:
                    return label
                tried += 1
            if tried >= 2:
                break
    return None


def _shoulder_sign_probe(sub, arm, rng) -> str | None:
    """The absolute value missing: the shoulder flagged wherever its factor is negative."""
    signs = {}
    for _ in range(40):
        q = _configuration(arm, rng)
        sign = float(np.sign(_factor(arm, q)))
        if sign not in signs:
            signs[sign] = _flags(sub, arm, q, "shoulder")
        if len(signs) == 2:
            return _NO_ABS if signs[-1.0] and signs[1.0] is False else None
    return None


def _diagnose(sub, arm, q, expected: set, got: set, rng, tol=None) -> str | None:
    """Name the likely mistake by asking the student's function about related configurations."""
    base = _configuration(arm, rng)
    for name, joint in _FAMILY_JOINT.items():
        if (name in expected) != (name in got):
            found = _family_probes(sub, arm, name, joint, base)
            if found:
                return found
    if ("shoulder" in expected) != ("shoulder" in got):
        found = _shoulder_sign_probe(sub, arm, rng) or _shoulder_probes(sub, arm, rng)
        if found:
            return found
    alone = all(_flags(sub, arm, _configuration(arm, rng, (f,)), f) for f in expected - got)
    if len(expected) > 1 and len(got) == 1 and got < expected and alone:
        return (
            "only one family returned (an if/elif chain or an early return): at an "
            "intersection several families hold at once"
        )
    factors = np.abs(singularity_factors(arm, q))
    for name in sorted(expected ^ got):
        size = float(factors[SINGULARITIES.index(name)])
        if size < 1e-12 or not alone:
            continue
        if tol is None and _flags(sub, arm, q, name, 1e-9) == (name in expected):
            return "the default of tol is not the lesson's 1e-9: singularities(robot, q, tol=1e-9)"
        loose, strict = _flags(sub, arm, q, name, 10 * size), _flags(sub, arm, q, name, size / 10)
        if loose is not None and loose == strict:
            return (
                "the tol argument is ignored (a fixed tolerance, or np.isclose's default): "
                "a family is present when its factor is at most tol"
            )
    return None


def _expected(arm, q, tol=1e-9) -> set[str]:
    factors = np.abs(singularity_factors(arm, q))
    return {name for name, f in zip(SINGULARITIES, factors) if f <= tol}


_DET = (
    "det J = a2 a3 · sin q3 · sin q5 · (a2 cos q2 + a3 cos(q2+q3) + d5 sin(q2+q3+q4)): a "
    "family is present when its factor is at most tol"
)


def _shown(factors) -> str:
    return "(" + ", ".join(f"{f:.2g}" for f in factors) + ")"


def _compare_names(sub, arm, q, expected: set, rng, tol=None, what=_DET):
    got = _ask(sub, arm, q, tol)
    if got == expected:
        return
    inputs = {"robot": arm.name, "q": q} | ({} if tol is None else {"tol": f"{tol:.1e}"})
    factors = singularity_factors(arm, q)
    raise Mismatch(
        what,
        inputs={**inputs, "factors (shoulder m, sin q3, sin q5)": _shown(factors)},
        expected=", ".join(sorted(expected)) or "none",
        got=", ".join(sorted(got)) or "none",
        mistake=_diagnose(sub, arm, q, expected, got, rng, tol),
    )


def _regular(sub, rng):
    for _ in range(8):
        arm = random_arm(rng)
        _compare_names(sub, arm, _regular_configuration(arm, rng), set(), rng)
    for family in SINGULARITIES:  # and not "none" everywhere
        arm = random_arm(rng)
        q = _configuration(arm, rng, (family,))
        got = _ask(sub, arm, q)
        if not got:
            raise Mismatch(
                f"q is singular (the {family} family) but no family was found: " + _DET,
                inputs={
                    "robot": arm.name,
                    "q": q,
                    "factors (shoulder m, sin q3, sin q5)": _shown(singularity_factors(arm, q)),
                },
                expected=family,
                got="none",
                mistake=_diagnose(sub, arm, q, {family}, got, rng),
            )


def _single_families(sub, rng):
    for family in SINGULARITIES:
        for k in range(4):
            arm = random_arm(rng)
            q = _configuration(arm, rng, (family,))
            while family in _FAMILY_JOINT and k == 3:  # at ±2π: one full turn from 0
                q[_FAMILY_JOINT[family]] = rng.choice([2 * np.pi, -2 * np.pi])
                if _expected(arm, q) == {family}:
                    break
                q = _configuration(arm, rng, (family,))
            _compare_names(sub, arm, q, {family}, rng)


def _intersections(sub, rng):
    for families in (
        ("shoulder", "elbow"),
        ("elbow", "wrist"),
        ("shoulder", "wrist"),
        ("shoulder", "elbow", "wrist"),
    ):
        arm = random_arm(rng)
        _compare_names(sub, arm, _configuration(arm, rng, families), set(families), rng)


def _respects_tol(sub, rng):
    for family in SINGULARITIES:
        for exponents in ((np.log10(1.5e-8), -7.0), (-5.0, -3.0)):  # just off it, and further
            arm = random_arm(rng)
            factor = float(10 ** rng.uniform(*exponents)) * rng.choice([-1.0, 1.0])
            q = _configuration(arm, rng, near={family: factor})
            size = abs(singularity_factors(arm, q)[SINGULARITIES.index(family)])
            for tol, expected in ((None, set()), (10 * size, {family}), (size / 10, set())):
                shown = "1.0e-09, the default" if tol is None else f"{tol:.1e}"
                _compare_names(
                    sub,
                    arm,
                    q,
                    expected,
                    rng,
                    tol,
                    what=f"the {family} factor is {size:.1e} here: a family is present when its "
                    f"factor is at most tol (tol = {shown})",
                )


# -------------------------------------------------------------------------- 4.6 manipulability


def _man_call(sub, J) -> float:
    inputs = {"J": J}
    raw = sub.manipulability(J)
    try:
        finite = bool(np.isfinite(np.asarray(raw, dtype=float)).all())
    except (TypeError, ValueError):
        finite = True  # as_array says what is wrong with it
    if not finite:
        raise Mismatch(
            "manipulability(J) returned NaN or infinity",
            inputs=inputs,
            got=raw,
            mistake=(
                "det(J Jᵀ) is a hair below 0 at a singularity (round-off): clip it at 0 before "
                "the square root, or multiply the singular values"
            ),
        )
    return float(as_array(raw, (), "manipulability(J)", inputs))


def _man_hypotheses(J) -> dict:
    right = float(np.prod(np.linalg.svd(J, compute_uv=False)))
    m, n = J.shape
    hypotheses = {
        "det(J Jᵀ) without the square root: w = √det(J Jᵀ)": lambda: np.linalg.det(J @ J.T),
        "√det(Jᵀ J): for a J with fewer rows than columns Jᵀ J is singular; use J Jᵀ": lambda: (
            np.sqrt(max(np.linalg.det(J.T @ J), 0.0))
        ),
        "the condition number σ_max / σ_min instead of the product of the singular values": (
            lambda: np.linalg.cond(J)
        ),
    }
    if m == n:
        hypotheses["det J without its absolute value: manipulability is never negative"] = lambda: (
            np.linalg.det(J)
        )
    return unless_right(hypotheses, right)


def _man_random(sub, rng):
    for shape in ((6, 6), (3, 6), (2, 5), (6, 7), (6, 6), (3, 6)):
        J = rng.normal(size=shape) * rng.uniform(0.2, 1.0)
        expected = float(np.prod(np.linalg.svd(J, compute_uv=False)))
        got = _man_call(sub, J)
        compare(
            np.asarray(got),
            expected,
            what="w = √det(J Jᵀ), the product of the singular values of J",
            inputs={"J": J},
            hypotheses=_man_hypotheses(J),
            atol=1e-9 * max(1.0, expected),
        )


def _man_square_sign(sub, rng):
    for _ in range(4):
        J = rng.normal(size=(6, 6))
        if np.linalg.det(J) > 0:
            J[:, 0] = -J[:, 0]  # a negative determinant
        compare(
            np.asarray(_man_call(sub, J)),
            abs(np.linalg.det(J)),
            what="for a square J, w = |det J| ≥ 0 (here det J < 0)",
            inputs={"J": J},
            hypotheses=_man_hypotheses(J),
            atol=1e-9 * max(1.0, abs(np.linalg.det(J))),
        )


def _man_singular(sub, rng):
    for family in ("elbow", "wrist") * 4:
        arm, q = random_arm(rng), random_q(rng)
        q[2 if family == "elbow" else 4] = 0.0
        J = _jacobian(arm, q)
        got = _man_call(sub, J)
        if not abs(got) < 1e-6:  # √det(J Jᵀ) of a round-off determinant: up to ~1e-8
            raise Mismatch(
                f"at a singular configuration ({family}: q{3 if family == 'elbow' else 5} = 0) "
                "the manipulability is 0 (below 1e-6 in floating point)",
                inputs={"J": J},
                expected=0.0,
                got=got,
                mistake=identify_mistake(got, _man_hypotheses(J)),
            )


# -------------------------------------------------------------------- 4.7 elbow_lost_direction


def _wrist1_jacobian(arm, q) -> np.ndarray:
    """The 3 × 3 position Jacobian of frame 3's origin (wrist 1) with respect to q1, q2, q3:
    column i is z_(i−1) × (o3 − o_(i−1))."""
    frames = _fk_frames(arm, q)
    o3 = frames[3][:3, 3]
    return np.column_stack([np.cross(frames[i][:3, 2], o3 - frames[i][:3, 3]) for i in range(3)])


def _lost_direction(arm, q) -> np.ndarray:
    """The left singular vector of the smallest singular value of wrist 1's Jacobian."""
    return np.linalg.svd(_wrist1_jacobian(arm, q))[0][:, 2]


def _elbow_singular(rng, q3: float):
    """A random UR arm at a configuration with the elbow angle ``q3`` (0, ±π, ±2π) and wrist 1
    at least ~5 cm off the base axis, so that joints 1-3 still move it in two directions."""
    while True:
        arm, q = random_arm(rng), random_q(rng)
        q[2] = q3
        if np.linalg.svd(_wrist1_jacobian(arm, q), compute_uv=False)[1] > 0.05:
            return arm, q


def _unit(v) -> np.ndarray:
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def _same_line(a, b, atol: float) -> bool:
    """Whether unit vectors ``a`` and ``b`` are equal up to sign."""
    return bool(min(np.abs(a - b).max(), np.abs(a + b).max()) <= atol)


_FRAME_INDEX = (
    "fk_frames(robot, q)[k] is DH frame k (index 0 is the base frame): wrist 1 is frame 3's "
    "origin, [3], and the shoulder frame 1's, [1]"
)


def _lost_hypotheses(arm, q) -> dict[str, np.ndarray]:
    """Unit directions students give instead of the lost one (compared up to sign)."""
    frames = _fk_frames(arm, q)
    o, z = frames[:, :3, 3], frames[:, :3, 2]
    line = o[3] - o[1]
    return {
        "the shoulder axis z1 (joints 2 and 3 turn about it): joint 1 moves wrist 1 along it, "
        "z0 × o3 is parallel to z1": z[1],
        "across the arm in its plane (z1 × the arm's line): joints 2 and 3 both move wrist 1 "
        "that way": np.cross(z[1], line),
        "measured from the base origin (o3 − o0): the arm's line runs through the shoulder, "
        "frame 1's origin, d1 above the base origin": o[3],
        "the flange (frame 6) instead of wrist 1, frame 3's origin": o[6] - o[1],
        _FRAME_INDEX + " (this is o4 − o2)": o[4] - o[2],
        _FRAME_INDEX + " (this is o2 − o0)": o[2] - o[0],
        "the base axis z0: joints 1-3 can move wrist 1 up and down": z[0],
    }


def _lost_mistake(got, arm, q) -> str | None:
    lost = _lost_direction(arm, q)
    for name, candidate in _lost_hypotheses(arm, q).items():
        candidate = _unit(candidate)
        if _same_line(got, candidate, 1e-6) and not _same_line(candidate, lost, 1e-6):
            return name
    return None


def _lost_matches(sub, rng, angles: tuple[float, ...]):
    for q3 in angles:
        arm, q = _elbow_singular(rng, q3)
        inputs = {"robot": arm.name, "q": q}
        got = as_array(
            sub.elbow_lost_direction(arm, q.copy()), (3,), "elbow_lost_direction(robot, q)", inputs
        )
        lost = _lost_direction(arm, q)
        length = float(np.linalg.norm(got.astype(float)))
        if not abs(length - 1.0) <= tolerance(1e-9, got):
            direction = got / length if length > 0 else got
            along = length > 0 and _same_line(direction, lost, 1e-6)
            raise Mismatch(
                f"the lost direction must be a unit vector; this one has length {length:.6g}",
                inputs=inputs,
                got=got,
                mistake=(
                    "not normalised: the direction is right, divide it by its length"
                    if along
                    else _lost_mistake(direction, arm, q)
                ),
            )
        if not _same_line(got, lost, tolerance(1e-9, got)):
            kind = "stretched" if np.cos(q3) > 0 else "folded"
            raise Mismatch(
                f"at this {kind} elbow (q3 = {q3:.4f}) joints 1-3 cannot move wrist 1 along the "
                "expected direction (either sign), the left singular vector of the smallest "
                "singular value of its 3 × 3 position Jacobian; they can move it along yours",
                inputs=inputs,
                expected=lost if got @ lost >= 0 else -lost,
                got=got,
                mistake=_lost_mistake(got, arm, q),
            )


def _lost_stretched(sub, rng):
    _lost_matches(sub, rng, (0.0, 0.0, 0.0, 2 * np.pi, 0.0, -2 * np.pi, 0.0, 0.0))


def _lost_folded(sub, rng):
    _lost_matches(sub, rng, (np.pi, -np.pi, np.pi, -np.pi))


# ------------------------------------------------------------------------ 4.8 holding_torques

_G = 9.81


def _hold_wrench(arm, q, mass, r_com, *, frame="flange", sign=1.0, lever=1.0, g=_G, moment=True):
    """The wrench the flange applies to the part, with one piece swappable for a wrong one."""
    T = _fk(arm, q)
    f = np.array([0.0, 0.0, sign * mass * g])
    r = T[:3, :3] @ r_com if frame == "flange" else np.asarray(r_com, dtype=float)
    return np.r_[f, lever * np.cross(r, f) if moment else np.zeros(3)]


def _hold_hypotheses(arm, q, mass, r_com) -> dict:
    J = _jacobian(arm, q)

    def torques(**wrong):
        return lambda: J.T @ _hold_wrench(arm, q, mass, r_com, **wrong)

    return {
        "the sign of F: these torques let the part fall; the flange pushes the part UP with "
        "m g": torques(sign=-1.0),
        "the wrench has no moment: with the centre of mass off the flange origin, the weight "
        "also twists the flange, r × f": torques(moment=False),
        "r_com used as if it were in the base frame: it is given in the flange frame, rotate "
        "it by the flange's R first": torques(frame="base"),
        "the lever reversed (f × r instead of r × f)": torques(lever=-1.0),
        "the mass used as a force: the weight is m g, g = 9.81 m/s²": torques(g=1.0),
        "J F instead of Jᵀ F: torques come from the TRANSPOSED Jacobian": lambda: (
            J @ _hold_wrench(arm, q, mass, r_com)
        ),
    }


# the student's geometric Jacobian (4.1), which τ = Jᵀ F is usually built on, and where to see
# its dtype
_JACOBIAN_PROBE = {
    "geometric_jacobian": ("4.1", (urkin.robot("ur5"), np.array([0.3, -1.2, 1.1, -0.6, 0.8, 0.2])))
}


def _hold_cases(sub, rng, offset: bool):
    helper = float32_helper(sub, "holding_torques", _JACOBIAN_PROBE)
    for _ in range(5):
        arm, q = random_arm(rng), random_q(rng)
        mass = float(rng.uniform(0.2, 5.0))
        r_com = rng.uniform(-0.15, 0.15, 3) if offset else np.zeros(3)
        inputs = {"robot": arm.name, "q": q, "mass": mass, "r_com": r_com}
        got = as_array(
            sub.holding_torques(arm, q.copy(), mass, r_com.copy()),
            (6,),
            "holding_torques(robot, q, mass, r_com)",
            inputs,
        )
        expected = _jacobian(arm, q).T @ _hold_wrench(arm, q, mass, r_com)
        compare(
            got,
            expected,
            what="τ = Jᵀ F, F = [f; r × f] the wrench the flange holds the part with (N·m)",
            inputs=inputs,
            hypotheses=unless_right(_hold_hypotheses(arm, q, mass, r_com), expected),
            helper=helper,
        )


# ------------------------------------------------------------------------ 4.9 ellipsoid_axes

_ZERO = 1e-12  # a singular value at most _ZERO · σ1 counts as zero: round-off, not reach
_ROUND_OFF = (
    "σ3 is round-off here (below 1e-12 σ1) and was used as it is — compared with 0 exactly, "
    "or np.linalg.cond(J_v) —, which gives a huge finite number: count σ ≤ 1e-12 σ1 as zero "
    "(force semi-axis inf, condition inf)"
)
_SQUARE_ROOTS = (
    "σ as square roots of the eigenvalues of J Jᵀ: those carry round-off of about 1e-16 σ1², "
    "so a zero σ3 comes out near 1e-8 σ1 (or NaN, when the round-off is negative) — take the "
    "singular values of J_v itself (np.linalg.svd)"
)
_VT_ROWS = (
    "rows of Vᵀ: they are directions in joint space, one entry per joint; the ellipsoid's axes "
    "are the columns of U, in task space (3 × 3)"
)
_TOO_LARGE = (
    "a zero threshold far above round-off: σ3 = 1e-5 σ1 is small but real, and only σ ≤ "
    "1e-12 σ1 counts as zero"
)


def _ellipsoid_expected(J):
    """(U, σ, force semi-axes, condition) of a 3 × n matrix, by the SVD."""
    U, sigma, _ = np.linalg.svd(J)
    zero = sigma <= _ZERO * sigma[0]
    force = np.full(3, np.inf)
    force[~zero] = 1.0 / sigma[~zero]
    condition = np.inf if zero[2] else float(sigma[0] / sigma[2])
    return U, sigma, force, condition


def _distinct(J) -> bool:
    """Whether the semi-axes of J's ellipsoid are distinct (5 % of σ1 apart) and σ3 ≥ 1 % of
    σ1: its principal directions are then defined to far better than 1e-9."""
    sigma = np.linalg.svd(J, compute_uv=False)
    return bool(min(-np.diff(sigma)) >= 0.05 * sigma[0] and sigma[2] >= 0.01 * sigma[0])


def _distinct_pair(J) -> bool:
    """For a J of rank 2: whether σ1 − σ2 ≥ 5 % of σ1 and σ2 ≥ 10 % of σ1."""
    sigma = np.linalg.svd(J, compute_uv=False)
    return bool(sigma[0] - sigma[1] >= 0.05 * sigma[0] and sigma[1] >= 0.1 * sigma[0])


def _with_signs(got, expected) -> np.ndarray:
    """``got`` with each column's sign flipped where that brings it closer to ``expected``."""
    return got * np.where(np.sum(got * expected, axis=0) < 0, -1.0, 1.0)


def _matches(got, candidate, rtol=1e-6) -> bool:
    """Equal shapes, infinities in the same places, finite entries equal to ``rtol`` relative
    (1 absolute below 1)."""
    got, candidate = np.asarray(got, dtype=float), np.asarray(candidate, dtype=float)
    if got.shape != candidate.shape or np.isnan(got).any() or np.isnan(candidate).any():
        return False
    if not np.array_equal(np.isposinf(got), np.isposinf(candidate)):
        return False
    if np.isneginf(got).any() or np.isneginf(candidate).any():
        return False
    finite = np.isfinite(candidate)
    gap = np.abs(got[finite] - candidate[finite])
    return bool(np.all(gap <= rtol * np.maximum(1.0, np.abs(candidate[finite]))))


def _named(got, hypotheses: dict, right, signs=False) -> str | None:
    """The first hypothesis that reproduces ``got`` and not the ``right`` answer."""
    for name, compute in hypotheses.items():
        try:
            with np.errstate(all="ignore"):
                candidate = np.asarray(compute(), dtype=float)
        except Exception:  # a hypothesis that cannot be evaluated names nothing
            continue
        if _matches(candidate, right) or (
            signs
            and candidate.shape == np.shape(right)
            and _matches(_with_signs(candidate, right), right)
        ):
            continue
        shown = _with_signs(got, candidate) if signs and np.shape(got) == candidate.shape else got
        if _matches(shown, candidate):
            return name
    return None


def _small_as_zero(got_force, force, sigma1: float) -> bool:
    """Whether the answer has +inf where a small (≤ 1e-3 σ1) but real σ gives a finite 1/σ."""
    wrong = np.isposinf(got_force) & np.isfinite(force)
    return bool(wrong.any() and np.all(force[wrong] * sigma1 >= 1e3))


def _small_sigma(got_sigma3: float, sigma1: float) -> str | None:
    """Name the mistake that turns a zero σ3 (round-off) into ``got_sigma3``."""
    if not np.isfinite(got_sigma3) or got_sigma3 < 0:
        return None
    if got_sigma3 <= _ZERO * sigma1:
        return _ROUND_OFF
    if got_sigma3 <= 1e-6 * sigma1:
        return _SQUARE_ROOTS
    return None


def _numbers(value, shape, what, inputs, *, finite=True, wrong_shapes=None) -> np.ndarray:
    """``value`` as real float64 numbers of ``shape``; NaN never, inf only if not ``finite``."""
    if value is None:
        raise Mismatch(f"{what} is None", inputs=inputs)
    try:
        array = np.asarray(value)
        if np.iscomplexobj(array):
            if np.abs(array.imag).max(initial=0.0) > 1e-12:
                raise Mismatch(f"{what} has complex entries", inputs=inputs, got=array.real)
            array = array.real
        if np.issubdtype(array.dtype, np.floating) and array.dtype.itemsize < 8:
            raise Mismatch(
                f"{what} is {array.dtype}: the semi-axes are compared to 1e-9 and σ ≤ 1e-12 σ1 "
                "counts as zero, which only float64 can resolve",
                inputs=inputs,
                mistake=f"computed in {array.dtype}: use float64 (np.asarray(J_v, dtype=float))",
            )
        array = array.astype(float)
    except (TypeError, ValueError):
        raise Mismatch(
            f"{what} must be numbers; got {type(value).__name__}", inputs=inputs
        ) from None
    if array.shape != shape:
        raise Mismatch(
            f"{what} must have shape {shape}; got shape {array.shape}",
            inputs=inputs,
            mistake=(wrong_shapes or {}).get(array.shape),
        )
    if np.isnan(array).any():
        raise Mismatch(f"{what} contains NaN", inputs=inputs, got=array, mistake=_NAN)
    if finite and np.isinf(array).any():
        raise Mismatch(f"{what} contains infinity", inputs=inputs, got=array)
    return array


_NAN = (
    "NaN where σ is zero: the square root of a negative round-off eigenvalue of J Jᵀ, 0 · inf "
    "or inf / inf — take the singular values of J_v itself (np.linalg.svd), and give inf where "
    "σ ≤ 1e-12 σ1"
)


def _ellipsoid_call(sub, J, inputs):
    """The student's (U, velocity, force, condition), each as float numbers of its shape."""
    n = J.shape[1]
    what = "ellipsoid_axes(J_v)"
    value = sub.ellipsoid_axes(J.copy())
    if value is None:
        raise Mismatch(f"{what} returned None: is a `return` statement missing?", inputs=inputs)
    if not isinstance(value, (tuple, list)) or len(value) != 4:
        size = f" of length {len(value)}" if isinstance(value, (tuple, list)) else ""
        raise Mismatch(
            f"{what} must return a tuple (U, velocity, force, condition); got "
            f"{type(value).__name__}{size}",
            inputs=inputs,
            mistake="np.linalg.svd's (U, σ, Vᵀ) returned as they are"
            if size == " of length 3"
            else None,
        )
    rows = _VT_ROWS
    values = (
        f"{n} values: the eigenvalues of J_vᵀ J_v ({n} × {n}, joint space); the ellipsoid's "
        "semi-axes are the 3 singular values of J_v"
    )
    U = _numbers(
        value[0], (3, 3), f"U (item 0 of {what})", inputs, wrong_shapes={(n, n): rows, (3, n): rows}
    )
    velocity = _numbers(
        value[1], (3,), f"velocity (item 1 of {what})", inputs, wrong_shapes={(n,): values}
    )
    force = _numbers(value[2], (3,), f"force (item 2 of {what})", inputs, finite=False)
    condition = _numbers(value[3], (), f"condition (item 3 of {what})", inputs, finite=False)
    return U, velocity, force, float(condition)


def _judge_ellipsoid(sub, J, inputs, *, where=""):
    U, sigma, force, condition = _ellipsoid_expected(J)
    got_U, got_v, got_f, got_c = _ellipsoid_call(sub, J, inputs)
    singular = bool(sigma[2] <= _ZERO * sigma[0])
    velocity_hypotheses = {
        "σ² instead of σ: the eigenvalues of J Jᵀ are the squares of the semi-axes; take their "
        "square roots, or the singular values of J_v": lambda: sigma**2,
        "sorted ascending: list the semi-axes largest first, σ1 ≥ σ2 ≥ σ3": lambda: sigma[::-1],
        "the force semi-axes 1/σ in place of the velocity ones σ": lambda: 1.0 / sigma,
    }
    if not close(got_v, sigma, 1e-9):
        mistake = _named(got_v, velocity_hypotheses, sigma)
        if mistake is None and singular:
            mistake = _small_sigma(float(got_v[2]), float(sigma[0]))
        gap = float(np.abs(got_v - sigma).max())
        raise Mismatch(
            f"velocity{where}: the semi-axes σ1 ≥ σ2 ≥ σ3 of the velocity ellipsoid, the singular "
            "values of J_v, largest first (to 1e-9)",
            inputs=inputs,
            expected=sigma,
            got=got_v,
            mistake=mistake,
            difference=f"largest difference {gap:.1e}; the tolerance is 1e-09"
            if gap < 1e-3
            else None,
        )
    _, _, Vt = np.linalg.svd(J)
    direction_hypotheses = {
        "sorted ascending: column i of U pairs with σ_i, largest first": lambda: U[:, ::-1],
        "the directions as rows (U transposed): they are the columns of U": lambda: U.T,
        "the columns scaled by σ (U Σ, the semi-axes as vectors): return unit directions, the "
        "lengths go in velocity": lambda: U * sigma,
    }
    if J.shape[1] == 3:
        direction_hypotheses[_VT_ROWS] = lambda: Vt
        direction_hypotheses[
            "columns of V (directions in joint space): the ellipsoid's axes are the columns of U"
        ] = lambda: Vt.T
    if not close(_with_signs(got_U, U), U, 1e-9):
        raise Mismatch(
            f"U{where}: column i is the unit direction of the semi-axis σ_i, the i-th left "
            "singular vector of J_v (each column up to its sign, to 1e-9)",
            inputs=inputs,
            expected=_with_signs(U, got_U),
            got=got_U,
            mistake=_named(got_U, direction_hypotheses, U, signs=True),
        )
    force_hypotheses = {
        "the force semi-axes equal to σ: they are the inverses, 1/σ — a direction the flange "
        "moves in slowly is one it pushes in strongly": lambda: sigma,
        "the force semi-axes in descending order: keep U's column order, force[i] = 1/σ_i "
        "belongs to the direction U[:, i]": lambda: force[::-1],
        "1/σ²: the inverses of the eigenvalues of J Jᵀ; the semi-axes are 1/σ": lambda: (
            1.0 / sigma**2
        ),
    }
    if not _matches(got_f, force, 1e-9):
        mistake = _named(got_f, force_hypotheses, force)
        if mistake is None and singular and np.isfinite(got_f[2]) and got_f[2] > 0:
            mistake = _small_sigma(1.0 / float(got_f[2]), float(sigma[0]))
        if mistake is None and _small_as_zero(got_f, force, float(sigma[0])):
            mistake = _TOO_LARGE
        raise Mismatch(
            f"force{where}: the force ellipsoid's semi-axes 1/σ_i in U's column order, inf where "
            "σ_i ≤ 1e-12 σ1 (to 1e-9, relative)",
            inputs=inputs,
            expected=force,
            got=got_f,
            mistake=mistake,
        )
    condition_hypotheses = {
        "σ3/σ1, upside down: the condition number σ1/σ3 is at least 1": lambda: sigma[2] / sigma[0],
        "(σ1/σ3)², the condition number of J Jᵀ (np.linalg.cond(J @ J.T)): J's own is σ1/σ3": (
            lambda: (sigma[0] / sigma[2]) ** 2
        ),
    }
    if not _matches(np.array(got_c), np.array(condition), 1e-9):
        mistake = _named(np.array(got_c), condition_hypotheses, np.array(condition))
        if mistake is None and singular and np.isfinite(got_c) and got_c > 0:
            mistake = _small_sigma(float(sigma[0]) / got_c, float(sigma[0]))
        if mistake is None and np.isposinf(got_c) and condition >= 1e3:
            mistake = _TOO_LARGE
        raise Mismatch(
            f"condition{where}: σ1/σ3, inf where σ3 ≤ 1e-12 σ1 (to 1e-9, relative)",
            inputs=inputs,
            expected=condition,
            got=got_c,
            mistake=mistake,
        )


def _ellipsoid_arms(sub, rng):
    cases = 0
    while cases < 6:
        arm, q = random_arm(rng), random_q(rng)
        J = urkin.position_jacobian(arm, q)
        if not _distinct(J):
            continue
        cases += 1
        _judge_ellipsoid(sub, J, {"J_v": J}, where=f" (the {arm.name}'s position Jacobian)")


def _ellipsoid_matrices(sub, rng):
    for n in (3, 6, 7, 7, 6, 3):
        J = rng.normal(size=(3, n)) * rng.uniform(0.2, 2.0)
        while not _distinct(J):
            J = rng.normal(size=(3, n)) * rng.uniform(0.2, 2.0)
        _judge_ellipsoid(sub, J, {"J_v": J}, where=f" (a random 3 × {n} matrix)")


def _ellipsoid_singular(sub, rng):
    for k, q3 in enumerate((0.0, np.pi, 0.0, -np.pi, 2 * np.pi, 0.0)):
        while True:  # σ1 and σ2 distinct, so that all three directions are well defined
            arm, q = _elbow_singular(rng, q3)
            J = _wrist1_jacobian(arm, q)
            if _distinct_pair(J):
                break
        if k % 2:
            J = np.c_[J, np.zeros((3, 3))]  # joints 4-6 do not move wrist 1
        kind = "stretched" if np.cos(q3) > 0 else "folded"
        _judge_ellipsoid(
            sub,
            J,
            {"J_v": J, "robot": arm.name, "q": q},
            where=f" (wrist 1's position Jacobian, 3 × {J.shape[1]}, at a {kind} elbow, q3 = "
            f"{q3:.4f}: σ3 is round-off, the force semi-axis along the arm is inf)",
        )
    J = rng.normal(size=(3, 2)) @ rng.normal(size=(2, 7))  # rank 2 by construction
    while not _distinct_pair(J):
        J = rng.normal(size=(3, 2)) @ rng.normal(size=(2, 7))
    _judge_ellipsoid(sub, J, {"J_v": J}, where=" (a 3 × 7 matrix of rank 2: σ3 is round-off)")
    U = np.linalg.qr(rng.normal(size=(3, 3)))[0]
    V = np.linalg.qr(rng.normal(size=(7, 7)))[0]
    sigma = np.array([1.0, rng.uniform(0.2, 0.8), 1e-5]) * rng.uniform(0.5, 2.0)
    J = U @ np.diag(sigma) @ V[:, :3].T
    _judge_ellipsoid(
        sub, J, {"J_v": J}, where=" (a 3 × 7 matrix with σ3 = 1e-5 σ1: small, but not zero)"
    )


# ------------------------------------------------------------------ 4.10 space_from_geometric


def _space_hypotheses(J, T) -> dict:
    p, R = T[:3, 3], T[:3, :3]
    Jv, Jw = J[:3], J[3:]
    lever = np.cross(p, Jw, axis=0)
    return {
        "rows not reordered ([v_s; ω]): the space Jacobian is in twist order (ω; v_s), angular "
        "rows first": lambda: np.vstack([Jv + lever, Jw]),
        "v − p × ω (or v + ω × p), the lever's sign reversed: the body point at the base origin "
        "moves with v_s = v + ω × (0 − p) = v + p × ω": lambda: np.vstack([Jw, Jv - lever]),
        "p of the base (its origin, 0) instead of the flange origin p = T[:3, 3]: the rows are "
        "only reordered": lambda: np.vstack([Jw, Jv]),
        "p taken from the third column of T (the flange's z axis): the flange origin is the last "
        "column, T[:3, 3]": lambda: np.vstack([Jw, Jv + np.cross(T[:3, 2], Jw, axis=0)]),
        "p in flange coordinates (Rᵀ p): p, v and ω are all in base coordinates": lambda: np.vstack(
            [Jw, Jv + np.cross(R.T @ p, Jw, axis=0)]
        ),
        "the body Jacobian Ad_(T⁻¹) J_s = (Rᵀ ω; Rᵀ v), in flange coordinates: the space "
        "Jacobian is in base coordinates": lambda: np.vstack([R.T @ Jw, R.T @ Jv]),
        "the conversion run backwards (geometric_from_space): J is the geometric Jacobian "
        "[v; ω]; the space one is (ω; v + p × ω)": lambda: np.vstack(
            [Jw - np.cross(p, Jv, axis=0), Jv]
        ),
    }


def _space_call(sub, J, T, inputs) -> np.ndarray:
    n = J.shape[1]
    shapes = {(n, 6): f"the transpose, ({n}, 6): one column per joint, shape (6, {n})"}
    if n != 6:
        shapes[(6, 6)] = f"six joints assumed: J has {n} columns, and so has the answer"
    value = sub.space_from_geometric(J.copy(), T.copy())
    return as_array(value, (6, n), "space_from_geometric(J, T)", inputs, shapes)


def _space_arms(sub, rng):
    for _ in range(6):
        arm, q = random_arm(rng), random_q(rng)
        J, T = _jacobian(arm, q), _fk(arm, q)
        inputs = {"J": J, "T": T, "robot": arm.name, "q": q}
        got = _space_call(sub, J, T, inputs)
        compare(
            got,
            jacobian_space(space_screws(arm)[0], q),
            what=f"the space Jacobian (ω; v_s) of the {arm.name} at q, as "
            "jacobian_space(S, q) gives it: v_s = v + p × ω, p the flange origin (to 1e-10)",
            inputs=inputs,
            hypotheses=_space_hypotheses(J, T),
            atol=1e-10,
        )


def _space_any(sub, rng):
    sizes = [int(rng.integers(1, 6)), *(rng.permutation(7)[:4] + 1)]  # the first below six
    for n in sizes:
        J, T = rng.normal(size=(6, n)), random_pose(rng)
        inputs = {"J": J, "T": T}
        p = T[:3, 3]
        expected = np.vstack([J[3:], J[:3] + np.cross(p, J[3:], axis=0)])
        compare(
            _space_call(sub, J, T, inputs),
            expected,
            what=f"(ω; v + p × ω) for a 6 × {n} J and a random flange pose T, p = T[:3, 3] "
            "(to 1e-10)",
            inputs=inputs,
            hypotheses=_space_hypotheses(J, T),
            atol=1e-10,
        )


# ----------------------------------------------------------------- 4.11 complex_step_jacobian

_CS_DEFAULT = 1e-20  # the contract's default step
_CS_REAL_STEP = (
    "a finite difference with a real step (central or forward differences): it subtracts two "
    "nearly equal values of f and loses digits to cancellation — about 1e-11 at best for central "
    "differences, 1e-8 for forward ones; the complex step Im f(q + i h e_j)/h subtracts nothing"
)
_CS_TRANSPOSED = (
    "transposed: row k is output k, column j is input q_j (shape (m, n)) — np.column_stack, "
    "or np.array(columns).T"
)
_CS_FLOAT32 = (
    "the answer is {dtype}: the point of the complex step is all of float64's digits; keep "
    "complex128 (q + 1j * h * e with q in float64) and return float64"
)


def _complex_step(f, q, h, *, part=np.imag, divide=True, base=None) -> np.ndarray:
    """Column j = part(f(q + i h e_j)) / h; ``base(j)`` replaces e_j (for the hypotheses)."""
    q = np.asarray(q, dtype=float)
    columns = []
    for j in range(q.size):
        e = np.eye(q.size)[j] if base is None else base(j)
        value = np.asarray(f(q + 1j * h * e)).ravel()
        columns.append(part(value) / (h if divide else 1.0))
    return np.column_stack(columns)


def _analytic_case(rng, m: int, n: int, kind: str):
    """A random analytic test function R^n → R^m (a wire.Function), its formula and its
    parameters (shown with a failure), and its exact Jacobian as a function of x."""
    scale = 1.0 / np.sqrt(n)
    A, B = rng.normal(0.0, scale, (m, n)), rng.normal(0.0, 0.5 * scale, (m, n))
    if kind == "polynomial":
        C, b = rng.normal(0.0, scale, (m, n)), rng.normal(size=m)
        f = wire.Function("polynomial", A=A, B=B, C=C, b=b)
        shown = {"f": "f(x) = A x + (B x) ∘ (C x) + b", "A": A, "B": B, "C": C, "b": b}
        return f, shown, lambda x: A + (C @ x)[:, None] * B + (B @ x)[:, None] * C
    f = wire.Function("sin_exp", A=A, B=B)
    shown = {"f": "f(x) = sin(A x) ∘ exp(B x)", "A": A, "B": B}

    def jacobian(x):
        grow = np.exp(B @ x)
        return (np.cos(A @ x) * grow)[:, None] * A + (np.sin(A @ x) * grow)[:, None] * B

    return f, shown, jacobian


def _cs_hypotheses(f, q, h) -> dict[str, Callable[[], np.ndarray]]:
    n = np.size(q)
    hypotheses = {
        "the real part Re f(q + i h e_j)/h (≈ f(q)/h): the derivative is in the imaginary "
        "part, np.imag": lambda: _complex_step(f, q, h, part=np.real),
        "all zeros: the imaginary step was lost — x[j] += 1j * h on a real array keeps only the "
        "real part (numpy's ComplexWarning; make the copy complex, q.astype(complex)), and a "
        "real step of 1e-20 vanishes (q + 1e-20 == q)": lambda: np.zeros(
            (np.size(f(np.asarray(q, dtype=float))), n)
        ),
        "Im f(q + i h e_j) not divided by h": lambda: _complex_step(f, q, h, divide=False),
        "divided by 2h: the complex step divides Im f(q + i h e_j) by h (central differences "
        "divide by 2h)": lambda: _complex_step(f, q, h) / 2,
        "the sign flipped (a step of −i h, or −Im): Im f(q + i h e_j)/h": lambda: (
            -_complex_step(f, q, h)
        ),
        "every entry of q nudged at once (q + i h): nudge one entry at a time, q + i h e_j": (
            lambda: _complex_step(f, q, h, base=lambda j: np.ones(n))
        ),
        "the steps pile up from column to column: start every column from a fresh complex copy "
        "of q": lambda: _complex_step(f, q, h, base=lambda j: (np.arange(n) <= j).astype(float)),
        _CS_TRANSPOSED: lambda: _complex_step(f, q, h).T,
        "central differences with a real step, (f(q + h e_j) − f(q − h e_j)) / 2h: the "
        "complex step is Im f(q + i h e_j)/h": lambda: _central(f, q, h),
        "forward differences with a real step, (f(q + h e_j) − f(q)) / h: the complex step is "
        "Im f(q + i h e_j)/h": lambda: 2 * _differentiate(f, q, h, (1, 0)),
    }
    if h != _CS_DEFAULT:
        hypotheses[
            "the step h argument is ignored (a fixed step is used): use the h you are given"
        ] = lambda: _complex_step(f, q, _CS_DEFAULT)
    for fixed in (1e-2, 1e-3, 1e-4, 1e-5):
        hypotheses[
            f"a fixed step h = {fixed:g} is used: use the h you are given (its default is 1e-20)"
        ] = lambda fixed=fixed: _complex_step(f, q, fixed)
    return hypotheses


def _cs_matches(got, candidate) -> bool:
    """Equal to 1e-9 of the candidate's size (exactly, for a zero candidate)."""
    candidate = np.asarray(candidate, dtype=float)
    if candidate.shape != np.shape(got) or not np.all(np.isfinite(candidate)):
        return False
    size = float(np.abs(candidate).max(initial=0.0))
    return bool(np.allclose(got, candidate, rtol=0, atol=1e-9 * size))


def _cs_mistake(got, f, q, h, right) -> str | None:
    """The named mistake that reproduces ``got`` (relative to each candidate's size, so that
    answers of 1e20 or 1e-20 are told apart), else a real-step difference when ``got`` is close
    to ``right`` but not within round-off."""
    for name, compute in _cs_hypotheses(f, q, h).items():
        try:
            with np.errstate(all="ignore"):
                candidate = np.asarray(compute(), dtype=float)
        except Exception:  # a hypothesis that cannot be evaluated names nothing
            continue
        if not _cs_matches(right, candidate) and _cs_matches(got, candidate):
            return name
    if np.shape(got) == np.shape(right):
        gap = float(np.abs(got - right).max())
        if gap <= 1e-4 * max(1.0, float(np.abs(right).max())):
            return _CS_REAL_STEP
    return None


def _cs_call(sub, f, q, h, inputs, as_list=False) -> np.ndarray:
    """The student's Jacobian as float64 numbers of shape (m, n) (h left to its default when
    None)."""
    m, n = np.size(f(np.asarray(q, dtype=float))), np.size(q)
    args = (f, q.tolist() if as_list else q) + (() if h is None else (h,))
    what = "complex_step_jacobian(position, q" + ("" if h is None else ", h") + ")"
    value = sub.complex_step_jacobian(*args)
    try:
        raw = np.asarray(value)
    except (TypeError, ValueError):
        raw = None
    if raw is not None and np.issubdtype(raw.dtype, np.inexact):
        if np.iscomplexobj(raw) and np.abs(raw.imag).max(initial=0.0) > 1e-12:
            raise Mismatch(
                f"{what} must return real numbers; got complex ones",
                inputs=inputs,
                got=raw.imag,
                mistake="complex numbers returned: the derivative is the imaginary part alone, "
                "np.imag(f(q + 1j * h * e_j)) / h",
            )
        if raw.dtype.itemsize < (16 if np.iscomplexobj(raw) else 8):
            raise Mismatch(
                f"{what} is {raw.dtype}; it is compared to 1e-12, which only float64 resolves",
                inputs=inputs,
                mistake=_CS_FLOAT32.format(dtype=raw.dtype),
            )
    shapes = {(m * n,): "a flat vector: return the (m, n) matrix, one row per output"}
    if m != n:
        shapes[(n, m)] = _CS_TRANSPOSED
    return as_array(value, (m, n), what, inputs, shapes).astype(float)


def _cs_judge(sub, f, q, h, expected, *, what, inputs, atol, as_list=False) -> None:
    got = _cs_call(sub, f, q, h, inputs, as_list)
    if close(got, expected, atol):
        return
    step = _CS_DEFAULT if h is None else h
    gap = float(np.abs(got - expected).max())
    raise Mismatch(
        what,
        inputs=inputs,
        expected=expected,
        got=got,
        mistake=_cs_mistake(got, f, q, step, _complex_step(f, q, step)),
        difference=f"largest difference {gap:.1e}; the tolerance is {atol:.0e}"
        if gap < 1e-3
        else None,
    )


def _cs_analytic(sub, rng):
    order = rng.permutation(len(_SHAPES))
    for case in range(4):
        m, n = _SHAPES[order[case]]
        kind = ("polynomial", "sin_exp")[(case + int(order[0])) % 2]
        f, shown, jacobian = _analytic_case(rng, m, n, kind)
        q = rng.uniform(-1.0, 1.0, n)
        as_list = case == 0
        _cs_judge(
            sub,
            f,
            q,
            None,
            jacobian(q),
            what=f"the Jacobian of {shown['f']} ({m} outputs, {n} inputs), shape ({m}, {n}), "
            "with the default step (to 1e-8)" + (", q given as a list" if as_list else ""),
            inputs={**shown, "q": q.tolist() if as_list else q},
            atol=1e-8,
            as_list=as_list,
        )


def _cs_flange(sub, rng):
    for _ in range(3):
        arm, q = random_arm(rng), random_q(rng)
        f = wire.Function("complex_flange_position", robot=arm)
        _cs_judge(
            sub,
            f,
            q,
            None,
            position_jacobian(arm, q),
            what=f"∂p/∂q of the {arm.name}'s flange position, 3 × 6, with the default step, "
            "against urkin's exact derivative to 1e-12 (central differences reach 1e-11 at best)",
            inputs={
                "position": f"the {arm.name}'s flange position, urkin.fk(robot, q)[:3, 3]",
                "q": q,
            },
            atol=1e-12,
        )


def _cs_given_h(sub, rng):
    cases = []
    for h in (0.4, 2.0**-3):
        m, n = _SHAPES[int(rng.integers(len(_SHAPES)))]
        f, shown, _ = _analytic_case(rng, m, n, "sin_exp")
        cases.append((f, shown, rng.uniform(-1.0, 1.0, n), h))
    arm = random_arm(rng)
    flange = wire.Function("complex_flange_position", robot=arm)
    shown = {"position": f"the {arm.name}'s flange position, urkin.fk(robot, q)[:3, 3]"}
    cases.append((flange, shown, random_q(rng), 0.25))
    for f, shown, q, h in cases:
        _cs_judge(
            sub,
            f,
            q,
            h,
            _complex_step(f, q, h),
            what=f"the complex step with the h = {h:g} you are given: column j is "
            "Im f(q + i h e_j) / h, which differs from the derivative by O(h²) (to 1e-12)",
            inputs={**shown, "q": q, "h": h},
            atol=1e-12,
        )


LESSON = Lesson(
    number="04",
    title="Jacobians and singularities",
    summary="Jacobians: geometric, numeric, space and body; the UR's shoulder, elbow and wrist "
    "singularities; manipulability",
    exercises=(
        Exercise(
            id="4.1",
            function="geometric_jacobian",
            title="the geometric Jacobian, column by column",
            checks=(
                Check(
                    "its linear rows are the derivative of the flange position",
                    1,
                    _linear_rows_are_derivatives,
                ),
                Check(
                    "its angular rows are the flange's rate of turn",
                    1,
                    _angular_rows_are_rates_of_turn,
                ),
                Check("matches [v; ω] for random arms and configurations", 2, _jacobian_matches),
            ),
            answer=concepts.JACOBIAN,
        ),
        Exercise(
            id="4.2",
            function="numeric_jacobian",
            title="the Jacobian of any function by central differences",
            checks=(
                Check(
                    "is exact for linear functions of any shape, q an array or a list",
                    1,
                    _exact_on_linear,
                ),
                Check(
                    "takes central differences with the step h it is given (second order)",
                    2,
                    _central_at_h,
                ),
                Check(
                    "gives the UR flange's position Jacobian (3 × 6) with the default step",
                    1,
                    _on_the_arm,
                ),
            ),
        ),
        _twist_jacobian_exercise("4.3", "space"),
        _twist_jacobian_exercise("4.4", "body"),
        Exercise(
            id="4.5",
            function="singularities",
            title="which singular families hold at q",
            checks=(
                Check(
                    "finds none at regular configurations (cos q3 = 0 or cos q5 = 0 included), "
                    "and some at singular ones",
                    1,
                    _regular,
                ),
                Check("names the shoulder, elbow and wrist families", 2, _single_families),
                Check("names every family at their intersections", 1, _intersections),
                Check(
                    "respects tol: factors 1e-8 … 1e-3 from zero count only when tol allows",
                    1,
                    _respects_tol,
                ),
            ),
            answer=concepts.SINGULARITIES,
        ),
        Exercise(
            id="4.6",
            function="manipulability",
            title="Yoshikawa's manipulability of any Jacobian",
            checks=(
                Check("√det(J Jᵀ) for matrices of several shapes", 2, _man_random),
                Check("|det J| for a square J, whatever its sign", 1, _man_square_sign),
                Check(
                    "0, not NaN, at the elbow and wrist singularities", 1, _man_singular, gated=True
                ),
            ),
            answer=concepts.SINGULARITIES,
        ),
        Exercise(
            id="4.7",
            function="elbow_lost_direction",
            title="the direction wrist 1 cannot move in at an elbow singularity",
            checks=(
                Check(
                    "a unit vector along the lost direction at stretched elbows (q3 = 0, ±2π)",
                    3,
                    _lost_stretched,
                ),
                Check("also at folded elbows (q3 = ±π)", 1, _lost_folded),
            ),
        ),
        Exercise(
            id="4.8",
            function="holding_torques",
            title="the joint torques that hold a part against gravity",
            checks=(
                Check(
                    "a part with its centre of mass at the flange origin",
                    2,
                    partial(_hold_cases, offset=False),
                ),
                Check(
                    "a part with its centre of mass offset, given in the flange frame",
                    2,
                    partial(_hold_cases, offset=True),
                ),
            ),
            uses=("geometric_jacobian",),
        ),
        Exercise(
            id="4.9",
            function="ellipsoid_axes",
            title="the axes of the velocity and force ellipsoids, and the condition number",
            checks=(
                Check(
                    "directions, semi-axes and condition of UR arms' position Jacobians",
                    2,
                    _ellipsoid_arms,
                ),
                Check(
                    "the same for random 3 × 3, 3 × 6 and 3 × 7 matrices", 1, _ellipsoid_matrices
                ),
                Check(
                    "inf, not a huge number or NaN, where σ3 is round-off (elbow singularities, "
                    "rank 2), and finite where it is merely small",
                    1,
                    _ellipsoid_singular,
                ),
            ),
        ),
        Exercise(
            id="4.10",
            function="space_from_geometric",
            title="the space Jacobian from the geometric one",
            checks=(
                Check(
                    "matches jacobian_space for random UR arms and configurations", 2, _space_arms
                ),
                Check("any number of columns (1 to 7) and any flange pose", 1, _space_any),
            ),
            answer=(*concepts.JACOBIAN, space_from_geometric, geometric_from_space),
        ),
        Exercise(
            id="4.11",
            function="complex_step_jacobian",
            title="the Jacobian of any analytic function by the complex step",
            checks=(
                Check(
                    "the (m, n) Jacobian of analytic functions of several shapes, q an array or "
                    "a list",
                    1,
                    _cs_analytic,
                ),
                Check(
                    "the UR flange's position Jacobian to 1e-12, beyond finite differences",
                    1,
                    _cs_flange,
                ),
                Check(
                    "uses the step h it is given: Im f(q + i h e_j) / h at large h",
                    1,
                    _cs_given_h,
                ),
            ),
            answer=concepts.JACOBIAN,
        ),
    ),
)
