"""Lesson 03 — the product of exponentials."""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

import numpy as np

import urkin
from urkin.course import concepts
from urkin.course.compare import (
    Mismatch,
    as_array,
    close,
    compare,
    identify_mistake,
    require_transform,
    tolerance,
    unless_right,
)
from urkin.course.exercise import Check, Exercise, Lesson
from urkin.course.inputs import random_arm, random_pose, random_q, random_screw_axes
from urkin.course.submission import StudentRaised
from urkin.kinematics import dh_chain, dh_transform
from urkin.poe import body_screws, jacobian_space, screw_axis, space_screws
from urkin.transforms import adjoint, inv_transform, rotation_angle, se3_exp, se3_log, skew

_fk = urkin.fk

# ------------------------------------------------------------------------------------ helpers


def _unit(rng) -> np.ndarray:
    """A unit axis: along a coordinate axis now and then (as UR's joints are), else random."""
    if rng.random() < 0.25:
        w = np.zeros(3)
        w[int(rng.integers(3))] = rng.choice([-1.0, 1.0])
        return w
    w = rng.normal(size=3)
    return w / np.linalg.norm(w)


def _perpendicular(w, rng) -> np.ndarray:
    """A random unit vector perpendicular to the unit vector ``w``."""
    while True:
        d = np.cross(w, rng.normal(size=3))
        if np.linalg.norm(d) > 0.1:
            return d / np.linalg.norm(d)


def _transform(R, p) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, p
    return T


# ---------------------------------------------------------------------------- 3.1 screw_axis

_SCREW_SHAPES = {
    (2, 3): "ω and v returned as two rows (2 × 3): S is one vector of six numbers, "
    "np.concatenate([ω, v])",
    (3,): "only three numbers returned: S = (ω, v) has six, ω first",
    (6, 1): "a column of shape (6, 1): S is a flat vector of shape (6,)",
    (1, 6): "a row of shape (1, 6): S is a flat vector of shape (6,)",
}


def _screw_hypotheses(w, q):
    v = -np.cross(w, q)
    hypotheses = {
        "v = ω × q has the wrong sign: a revolute joint's v is −ω × q (= q × ω)": lambda: np.r_[
            w, -v
        ],
        "(v, ω) order: Modern Robotics writes screw axes (ω, v), angular part first": lambda: np.r_[
            v, w
        ],
        "(v, ω) order, and v = ω × q has the wrong sign: S = (ω, −ω × q)": lambda: np.r_[-v, w],
        "v = q: the point itself is not the linear part; v = −ω × q": lambda: np.r_[w, q],
        "v = −q: the point itself is not the linear part; v = −ω × q": lambda: np.r_[w, -q],
        "w and q swapped: the joint turns about w through the point q": lambda: np.r_[
            q, -np.cross(q, w)
        ],
    }
    return unless_right(hypotheses, np.r_[w, v])


def _screw_call(sub, w, q) -> np.ndarray:
    inputs = {"w": w, "q": q}
    return as_array(sub.screw_axis(w, q), (6,), "screw_axis(w, q)", inputs, _SCREW_SHAPES)


def _screw_matches(sub, rng):
    for _ in range(10):
        w, q = _unit(rng), rng.uniform(-0.5, 0.5, 3)
        compare(
            _screw_call(sub, w, q),
            screw_axis(w, q),
            what="S = (ω, v) with v = −ω × q",
            inputs={"w": w, "q": q},
            hypotheses=_screw_hypotheses(w, q),
        )


def _screw_describes_the_line(sub, rng):
    for _ in range(8):
        w, q = _unit(rng), rng.uniform(-0.5, 0.5, 3)
        t = float(rng.uniform(0.2, 1.0) * rng.choice([-1.0, 1.0]))
        first = _screw_call(sub, w, q)
        along = q + t * w
        moved = _screw_call(sub, w, along)
        if not close(moved, first, 1e-9):
            raise Mismatch(
                "any point of the axis describes the same joint: moving q along ω (to q + t·w) "
                "must not change S",
                inputs={"w": w, "q": q, "t": t},
                expected=first,
                got=moved,
                mistake=identify_mistake(moved, _screw_hypotheses(w, along)),
            )
        d = rng.uniform(0.1, 0.4) * _perpendicular(w, rng)
        elsewhere = q + d
        other = _screw_call(sub, w, elsewhere)
        if np.abs(other.astype(float) - first).max() < 0.25 * np.linalg.norm(d):
            raise Mismatch(
                "a parallel axis elsewhere (through q + d, d ⟂ w) is another joint: its S must "
                "differ (v changes by −ω × d)",
                inputs={"w": w, "q": q, "d": d},
                expected=screw_axis(w, elsewhere),
                got=other,
                mistake=identify_mistake(other, _screw_hypotheses(w, elsewhere)),
            )


# ----------------------------------------------------------------------------- 3.2 twist_exp


def _twist_inputs(rng) -> tuple[np.ndarray, float]:
    """A revolute screw axis and an angle of 0.3 to π rad either way (small angles hide
    mistakes of order θ²)."""
    S = screw_axis(_unit(rng), rng.uniform(-0.5, 0.5, 3))
    return S, float(rng.uniform(0.3, np.pi) * rng.choice([-1.0, 1.0]))


def _closed_form(w, v, theta, G=None, R=None) -> np.ndarray:
    """e^[S]θ from the closed form, with the rotation or the translation's matrix replaced."""
    W = skew(np.asarray(w, dtype=float))
    s, c = np.sin(theta), np.cos(theta)
    rotation = np.eye(3) + s * W + (1 - c) * W @ W if R is None else R(W, s, c)
    matrix = theta * np.eye(3) + (1 - c) * W + (theta - s) * W @ W if G is None else G(W, s, c)
    return _transform(rotation, matrix @ np.asarray(v, dtype=float))


def _series(A: np.ndarray, terms: int) -> np.ndarray:
    total, term = np.eye(4), np.eye(4)
    for k in range(1, terms):
        term = term @ A / k
        total = total + term
    return total


def _truncated_series(S, theta, got) -> np.ndarray:
    """The partial sum of e^[S]θ's series (2 to 40 terms) nearest to ``got``."""
    A = np.zeros((4, 4))
    A[:3, :3], A[:3, 3] = skew(S[:3]) * theta, S[3:] * theta
    sums = [_series(A, n) for n in range(2, 41)]
    return min(sums, key=lambda T: float(np.abs(T - got).max()))


def _twist_hypotheses(S, theta, got=None):
    w, v = S[:3], S[3:]
    right = se3_exp(S * theta)
    I3 = np.eye(3)
    hypotheses = {
        "the translation is v·θ: a rotation about an axis off the origin also moves the "
        "origin — use (Iθ + (1 − cos θ)[ω] + (θ − sin θ)[ω]²) v": lambda: _transform(
            right[:3, :3], v * theta
        ),
        "the rotation block is transposed (that is the turn by −θ)": lambda: _transform(
            right[:3, :3].T, right[:3, 3]
        ),
        "θ with the wrong sign: that is the turn by −θ": lambda: se3_exp(-S * theta),
        "θ treated as degrees": lambda: se3_exp(S * np.radians(theta)),
        "θ left out: that is the turn by 1 rad, e^[S]": lambda: se3_exp(S),
        "θ left out of the rotation: R = e^[ω]θ, Rodrigues with sin θ and cos θ": lambda: (
            _transform(se3_exp(S)[:3, :3], right[:3, 3])
        ),
        "S read as (v, ω): a screw axis is (ω, v), angular part first": lambda: _closed_form(
            v, w, theta
        ),
        "Iθ written as I in the translation's matrix: (Iθ + (1 − cos θ)[ω] + (θ − sin θ)[ω]²)"
        " v": lambda: _closed_form(
            w, v, theta, G=lambda W, s, c: I3 + (1 - c) * W + (theta - s) * W @ W
        ),
        "the [ω] term of the translation has the wrong sign: +(1 − cos θ)[ω]": lambda: _closed_form(
            w, v, theta, G=lambda W, s, c: theta * I3 - (1 - c) * W + (theta - s) * W @ W
        ),
        "the [ω]² term of the translation has the wrong sign: +(θ − sin θ)[ω]²": lambda: (
            _closed_form(
                w, v, theta, G=lambda W, s, c: theta * I3 + (1 - c) * W - (theta - s) * W @ W
            )
        ),
        "the translation is R v: use (Iθ + (1 − cos θ)[ω] + (θ − sin θ)[ω]²) v": lambda: _transform(
            right[:3, :3], right[:3, :3] @ v
        ),
        "the translation is (I − R) v: the geometric form (I − R) q needs a point q of the "
        "axis (ω × v), not v": lambda: _transform(right[:3, :3], (I3 - right[:3, :3]) @ v),
        "the translation is (I − R)(v × ω): the point of the axis nearest the origin is "
        "ω × v": lambda: _transform(right[:3, :3], (I3 - right[:3, :3]) @ np.cross(v, w)),
        "Rodrigues' last term needs [ω]², not [ω]: R = I + sin θ [ω] + (1 − cos θ)[ω]²": lambda: (
            _closed_form(w, v, theta, R=lambda W, s, c: I3 + s * W + (1 - c) * W)
        ),
        "sin and cos swapped in Rodrigues' formula: R = I + sin θ [ω] + (1 − cos θ)[ω]²": lambda: (
            _closed_form(w, v, theta, R=lambda W, s, c: I3 + c * W + (1 - s) * W @ W)
        ),
    }
    if got is not None:
        hypotheses[
            "the series I + [S]θ + ([S]θ)²/2! + … is cut off too early: sum terms until "
            "they are negligible, or use the closed form"
        ] = lambda: _truncated_series(S, theta, got)
    return unless_right(hypotheses, right)


_TWIST_SHAPES = {
    (3, 4): "only the top three rows (3 × 4): a homogeneous transform has the last row "
    "[0, 0, 0, 1]",
    (6,): "a 6-vector: e^[S]θ is a 4 × 4 homogeneous transform",
}


def _twist_call(sub, S, theta) -> np.ndarray:
    inputs = {"S": S, "theta": theta}
    value = sub.twist_exp(S, theta)
    if isinstance(value, (tuple, list)) and [np.shape(v) for v in value] == [(3, 3), (3,)]:
        raise Mismatch(
            "twist_exp(S, theta) must return one 4 × 4 homogeneous transform; got a pair (R, p)",
            inputs=inputs,
            mistake="R and p returned separately: return the 4 × 4 matrix [[R, p], [0, 0, 0, 1]]",
        )
    got = as_array(value, (4, 4), "twist_exp(S, theta)", inputs, _TWIST_SHAPES)
    if not close(got[3], [0, 0, 0, 1], 1e-12):
        raise Mismatch(
            "twist_exp(S, theta): the last row of a homogeneous transform is [0, 0, 0, 1]",
            inputs=inputs,
            got=got,
            mistake="the last row of the transform is not [0, 0, 0, 1]",
        )
    return got


def _twist_is_a_turn(sub, rng):
    for _ in range(6):
        S, theta = _twist_inputs(rng)
        inputs = {"S": S, "theta": theta}
        got = _twist_call(sub, S, theta)
        try:
            require_transform(got, "twist_exp(S, theta)", inputs)
        except Mismatch as exc:
            exc.mistake = identify_mistake(got, _twist_hypotheses(S, theta, got))
            raise
        R, w = got[:3, :3].astype(float), S[:3]
        if not (close(R @ w, w, like=got) and close(np.trace(R), 1 + 2 * np.cos(theta), like=got)):
            raise Mismatch(
                "the rotation block must turn by θ about ω: R ω = ω and trace R = 1 + 2 cos θ",
                inputs=inputs,
                expected=se3_exp(S * theta),
                got=got,
                mistake=identify_mistake(got, _twist_hypotheses(S, theta, got)),
            )


def _twist_matches(sub, rng):
    for _ in range(10):
        S, theta = _twist_inputs(rng)
        got = _twist_call(sub, S, theta)
        compare(
            got,
            se3_exp(S * theta),
            what="e^[S]θ = [[e^[ω]θ, (Iθ + (1 − cos θ)[ω] + (θ − sin θ)[ω]²) v], [0, 1]]",
            inputs={"S": S, "theta": theta},
            hypotheses=_twist_hypotheses(S, theta, got),
        )


def _twist_turns_about_its_axis(sub, rng):
    for _ in range(8):
        S, theta = _twist_inputs(rng)
        w, v = S[:3], S[3:]
        got = _twist_call(sub, S, theta)
        on_axis = np.cross(w, v) + rng.uniform(-0.5, 0.5) * w  # ω × v lies on the axis
        radius = rng.uniform(0.2, 0.5)
        off_axis = on_axis + radius * _perpendicular(w, rng)
        inputs = {"S": S, "theta": theta, "point on the axis": on_axis}
        moved = got[:3, :3] @ on_axis + got[:3, 3]
        if not close(moved, on_axis, like=got):
            raise Mismatch(
                "a turn about the screw axis leaves the points of the axis where they are",
                inputs=inputs,
                expected=on_axis,
                got=moved,
                mistake=identify_mistake(got, _twist_hypotheses(S, theta, got)),
            )
        image = got[:3, :3] @ off_axis + got[:3, 3]
        start, end = off_axis - on_axis, image - on_axis
        facts = np.array(
            [
                np.linalg.norm(end - np.dot(end, w) * w),  # distance from the axis
                np.dot(end, w),  # height along it
                np.linalg.norm(image - off_axis),  # how far the point travelled
                np.dot(np.cross(start, end), w) / radius**2,  # sin of the signed turn
            ]
        )
        expected = [radius, 0.0, 2 * radius * abs(np.sin(theta / 2)), np.sin(theta)]
        if not close(facts, expected, like=got):
            raise Mismatch(
                "a point off the axis must turn about it by θ (right-handed about ω): keep its "
                "distance r from the axis and its height along it, travel the chord "
                "2 r |sin(θ/2)| (shown: distance, height, chord, sin of the turn)",
                inputs={"S": S, "theta": theta, "point": off_axis, "r": radius},
                expected=expected,
                got=facts,
                mistake=identify_mistake(got, _twist_hypotheses(S, theta, got)),
            )


# ----------------------------------------------------------------- 3.3 fk_space and 3.4 fk_body


def _chain(factors) -> np.ndarray:
    T = np.eye(4)
    for factor in factors:
        T = T @ factor
    return T


def _elementwise(first, factors) -> np.ndarray:
    T = np.array(first, dtype=float)
    for factor in factors:
        T = T * factor
    return T


def _reference_factors(axes, q) -> list[np.ndarray]:
    return [se3_exp(axes[:, i] * q[i]) for i in range(axes.shape[1])]


def _student_factors(sub, axes, q, scaled=False, rows=False) -> list[np.ndarray]:
    """The student's own twist_exp for every joint (raises when it cannot give them)."""
    factors = []
    for i in range(len(q)):
        axis = axes[i] if rows else axes[:, i]
        args = (axis * q[i], 1.0) if scaled else (axis, float(q[i]))
        inputs = {"S_i": args[0], "theta": args[1]}
        factors.append(as_array(sub.twist_exp(*args), (4, 4), "twist_exp(S_i, q_i)", inputs))
    return factors


def _twist_exp_atol(sub) -> float:
    """1e-9, or float32's tolerance when the student's twist_exp answers in float32 (their
    forward kinematics then cannot be more precise, whatever dtype it returns)."""
    if not sub.has("twist_exp"):
        return 1e-9
    try:
        probe = np.asarray(sub.twist_exp(np.array([0.0, 0.0, 1.0, 0.0, -0.5, 0.0]), 0.7))
    except (StudentRaised, TypeError, ValueError):
        return 1e-9
    if np.issubdtype(probe.dtype, np.floating) and probe.dtype.itemsize < 8:
        return tolerance(1e-9, probe, 2.0)
    return 1e-9


_SIX_JOINTS = (
    "a loop over six joints (range(6), or len({letter}): the six rows of {letter}): "
    "loop over the n columns, range(len(q))"
)


@dataclass(frozen=True)
class _ProductForm:
    """What differs between the space form (3.3) and the body form (3.4) of the product."""

    name: str  # "space" or "body"
    letter: str  # "S" or "B"
    screws: Callable[..., tuple[np.ndarray, np.ndarray]]
    formula: str
    other_order: str  # the mistake of putting M on the other side

    @property
    def space(self) -> bool:
        return self.name == "space"

    @property
    def call(self) -> str:
        return f"fk_{self.name}(M, {self.letter}, q)"

    def product(self, M, factors) -> np.ndarray:
        return _chain(factors) @ M if self.space else M @ _chain(factors)

    def assemblies(self, M, factors) -> dict[str, Callable[[], np.ndarray]]:
        """The usual ways of putting the right factors together wrongly."""
        other = (lambda: M @ _chain(factors)) if self.space else (lambda: _chain(factors) @ M)
        return {
            self.other_order: other,
            "the exponentials multiplied in reverse order (joint n first)": lambda: self.product(
                M, factors[::-1]
            ),
            "M left out: T = e^[S1]q1 ⋯ e^[Sn]qn alone is not the end-effector pose": lambda: (
                _chain(factors)
            ),
            "M on the wrong side and the exponentials in reverse order": lambda: (
                M @ _chain(factors[::-1]) if self.space else _chain(factors[::-1]) @ M
            ),
            "an element-wise product (*) instead of the matrix product (@)": lambda: (
                _elementwise(np.eye(4), factors) @ M if self.space else _elementwise(M, factors)
            ),
            "the first joint left out of the product": lambda: self.product(M, factors[1:]),
            "the last joint left out (a loop that stops one joint early)": lambda: self.product(
                M, factors[:-1]
            ),
        }

    def hypotheses(self, sub, M, axes, q) -> dict[str, Callable[[], np.ndarray]]:
        right = _reference_factors(axes, q)
        # with one joint turned, leaving joints out (or all of them) is not told apart
        several = np.count_nonzero(q) > 1
        found = {
            "your twist_exp (exercise 3.2) gives wrong factors: this product of them is right, "
            "fix twist_exp first": lambda: self.product(M, _student_factors(sub, axes, q)),
            f"twist_exp called with ({self.letter}_i·q_i, 1): it takes a unit-ω screw axis and "
            "the angle separately": lambda: self.product(
                M, _student_factors(sub, axes, q, scaled=True)
            ),
        }
        if several:
            found["T = M whatever q: the exponentials of the joints are missing"] = lambda: M
        if axes.shape[0] == axes.shape[1] and several:
            found[
                f"the rows {self.letter}[i] taken as screw axes: they are the columns "
                f"{self.letter}[:, i]"
            ] = lambda: self.product(M, _student_factors(sub, axes, q, rows=True))
        found["q treated as degrees"] = lambda: self.product(
            M, _reference_factors(axes, np.radians(q))
        )
        found["the joint angles with the wrong sign"] = lambda: self.product(
            M, _reference_factors(axes, -np.asarray(q))
        )
        assemblies = self.assemblies(M, right)
        if not several:
            assemblies = {
                k: h
                for k, h in assemblies.items()
                if "left out of" not in k and not k.startswith("the last joint")
            }
        found.update(assemblies)
        return unless_right(found, self.product(M, right))

    def answer(self, sub, M, axes, q, inputs) -> np.ndarray:
        try:
            value = sub.call(f"fk_{self.name}", M, axes, q)
        except StudentRaised as exc:
            if exc.kind != "IndexError" or axes.shape[1] >= 6:
                raise
            raise Mismatch(
                exc.describe().splitlines()[0] + f" for an arm with {axes.shape[1]} joints",
                inputs=inputs,
                mistake=_SIX_JOINTS.format(letter=self.letter),
            ) from None
        return as_array(value, (4, 4), self.call, inputs)


_SPACE = _ProductForm(
    name="space",
    letter="S",
    screws=space_screws,
    formula="T = e^[S1]q1 ⋯ e^[S6]q6 M",
    other_order="M multiplied first: M e^[S1]q1 ⋯ is the body form, which needs body screw axes",
)
_BODY = _ProductForm(
    name="body",
    letter="B",
    screws=body_screws,
    formula="T = M e^[B1]q1 ⋯ e^[B6]q6",
    other_order="M multiplied last: e^[B1]q1 ⋯ M is the space form, which needs space screw axes",
)


def _other_arm(rng) -> tuple[np.ndarray, np.ndarray]:
    """A random revolute arm with 2, 3, 4, 5 or 7 joints (a DH table) and a configuration."""
    n = int(rng.choice([2, 3, 4, 5, 7]))
    table = np.column_stack(
        [
            rng.uniform(-0.3, 0.3, n),
            rng.uniform(-0.5, 0.5, n),
            rng.choice([0.0, np.pi / 2, -np.pi / 2], n),
        ]
    )
    return table, rng.uniform(-np.pi, np.pi, n)


def _product_home_and_single_joints(form: _ProductForm, sub, rng):
    atol = _twist_exp_atol(sub)
    cases = []
    for _ in range(2):
        cases.append((random_arm(rng), np.zeros(6)))
    for _ in range(4):
        q = np.zeros(6)
        q[int(rng.integers(6))] = rng.uniform(0.3, np.pi) * rng.choice([-1.0, 1.0])
        cases.append((random_arm(rng), q))
    for arm, q in cases:
        axes, M = form.screws(arm)
        inputs = {"robot": arm.name, "q": q}
        got = form.answer(sub, M, axes, q, inputs)
        still = not q.any()
        compare(
            got,
            M if still else _fk(arm, q),
            what=(
                "at q = 0 every exponential is the identity: T = M"
                if still
                else "with one joint turned, T = e^[S_i]q_i M (space form) = M e^[B_i]q_i "
                "(body form)"
            ),
            inputs=inputs,
            hypotheses=form.hypotheses(sub, M, axes, q),
            atol=atol,
        )


def _product_matches(form: _ProductForm, sub, rng):
    atol = _twist_exp_atol(sub)
    for _ in range(10):
        arm, q = random_arm(rng), random_q(rng)
        axes, M = form.screws(arm)
        inputs = {"robot": arm.name, "q": q}
        compare(
            form.answer(sub, M, axes, q, inputs),
            _fk(arm, q),
            what=f"{form.formula} (the {arm.name}'s flange pose)",
            inputs=inputs,
            hypotheses=form.hypotheses(sub, M, axes, q),
            atol=atol,
        )


def _right_on_a_ur_arm(form: _ProductForm, sub, arm, q) -> bool:
    axes, M = form.screws(arm)
    try:
        got = np.asarray(sub.call(f"fk_{form.name}", M, axes, q), dtype=float)
    except Exception:  # a probe that fails tells us nothing
        return False
    return got.shape == (4, 4) and bool(np.allclose(got, _fk(arm, q), rtol=0, atol=1e-5))


def _product_any_joint_count(form: _ProductForm, sub, rng):
    atol = _twist_exp_atol(sub)
    probe = random_arm(rng), random_q(rng)
    for _ in range(4):
        table, q = _other_arm(rng)
        axes, M = form.screws(table)
        inputs = {"M": M, form.letter: axes, "q": q}
        hypotheses = form.hypotheses(sub, M, axes, q)
        if len(q) > 6:  # right on six-joint arms, and only the first six joints here

            def six(M=M, axes=axes, q=q):
                if not _right_on_a_ur_arm(form, sub, *probe):
                    raise ValueError("not right on six joints either")
                return form.product(M, _reference_factors(axes[:, :6], q[:6]))

            hypotheses = {_SIX_JOINTS.format(letter=form.letter): six, **hypotheses}
        compare(
            form.answer(sub, M, axes, q, inputs),
            dh_chain(table, q),
            what=(
                f"an arm with {len(q)} joints: {form.letter} has one column per joint, "
                f"(6, {len(q)})"
            ),
            inputs=inputs,
            hypotheses=hypotheses,
            atol=atol,
        )


def _product_uses_own_twist_exp(form: _ProductForm, sub, rng):
    if not sub.has("twist_exp"):
        raise Mismatch(
            f"fk_{form.name} must build each factor with your own twist_exp (exercise 3.2), "
            "and this notebook defines no function twist_exp",
            mistake="twist_exp (exercise 3.2) is not defined",
        )
    for _ in range(3):
        arm, q = random_arm(rng), random_q(rng)
        axes, M = form.screws(arm)
        inputs = {"robot": arm.name, "q": q}
        try:
            factors = _student_factors(sub, axes, q)
        except (StudentRaised, Mismatch) as exc:
            if isinstance(exc, StudentRaised) and exc.message.startswith("Exercise 3.2:"):
                raise  # twist_exp is not written yet: the report says so
            reason = exc.describe() if isinstance(exc, StudentRaised) else exc.what
            raise Mismatch(
                f"this check multiplies your own twist_exp's factors, and twist_exp(S_i, q_i) "
                f"does not give a 4 × 4 transform: {reason.splitlines()[0]}",
                inputs={**inputs, **exc.inputs},
            ) from None
        atol = max((tolerance(1e-9, E, 2.0) for E in factors), default=1e-9)
        compare(
            form.answer(sub, M, axes, q, inputs),
            form.product(M, factors),
            what=(
                f"{form.formula}, each factor from your own twist_exp: your fk_{form.name} "
                "does not agree with it"
            ),
            inputs=inputs,
            hypotheses=unless_right(form.assemblies(M, factors), form.product(M, factors)),
            atol=atol,
        )


def _product_exercise(exercise_id: str, form: _ProductForm) -> Exercise:
    return Exercise(
        id=exercise_id,
        function=f"fk_{form.name}",
        title=f"forward kinematics, {form.name} form",
        checks=(
            Check(
                "gives M at q = 0, and the right pose when one joint alone turns",
                1,
                partial(_product_home_and_single_joints, form),
            ),
            Check(
                "matches the arm's flange pose for random arms and q",
                2,
                partial(_product_matches, form),
            ),
            Check("works for any number of joints", 1, partial(_product_any_joint_count, form)),
            Check(
                "multiplies the factors of your own twist_exp",
                1,
                partial(_product_uses_own_twist_exp, form),
            ),
        ),
        answer=concepts.FORWARD_KINEMATICS,
        uses=("twist_exp",),
        builds_on=("3.2",),
    )


# ----------------------------------------------------------------------------- 3.5 twist_log


def _log_inputs(rng, low: float = 0.1, high: float = 3.0) -> tuple[np.ndarray, np.ndarray]:
    """A twist V = (ωθ, vθ) with θ in [low, high] and the pose e^[V]."""
    w = _unit(rng)
    V = np.r_[w, rng.uniform(-0.6, 0.6, 3)] * rng.uniform(low, high)
    return V, se3_exp(V)


_ORDER = "(v, ω) order: a twist is (ω, v), angular part first"


def _G_inverse(w, theta, half=-0.5) -> np.ndarray:
    """G(θ)⁻¹ for a unit axis w (``half``: the coefficient of [ω], −½ when right)."""
    W = skew(w)
    return np.eye(3) / theta + half * W + (1 / theta - 0.5 / np.tan(theta / 2)) * W @ W


def _log_hypotheses(T):
    right = se3_log(T)
    theta = float(np.linalg.norm(right[:3]))
    w, p = right[:3] / theta, T[:3, 3]
    G = (
        theta * np.eye(3)
        + (1 - np.cos(theta)) * skew(w)
        + (theta - np.sin(theta)) * (skew(w) @ skew(w))
    )
    hypotheses = {
        _ORDER: lambda: np.r_[right[3:], right[:3]],
        "the linear part is p: vθ = θ G⁻¹(θ) p — p is where the origin ends up, not the "
        "twist's linear velocity": lambda: np.r_[right[:3], p],
        "the linear part is v, not vθ: multiply G⁻¹(θ) p by θ": lambda: np.r_[
            right[:3], right[3:] / theta
        ],
        "the angular part is the unit axis ω, not ωθ": lambda: np.r_[right[:3] / theta, right[3:]],
        "G⁻¹ with +½[ω]: G⁻¹ = I/θ − [ω]/2 + (1/θ − cot(θ/2)/2)[ω]²": lambda: np.r_[
            right[:3], theta * _G_inverse(w, theta, half=0.5) @ p
        ],
        "G(θ) p instead of G⁻¹(θ) p: p = G(θ) v, so v = G⁻¹(θ) p": lambda: np.r_[right[:3], G @ p],
        "the twist of T⁻¹ (R read transposed, or log(T⁻¹)): the sign of ω is flipped": lambda: (
            se3_log(inv_transform(T))
        ),
    }
    return unless_right(hypotheses, right)


_LOG_SHAPES = {
    (2, 3): "ωθ and vθ returned as two rows (2 × 3): V is one vector of six numbers",
    (4, 4): "a 4 × 4 matrix: return the twist as the 6-vector (ωθ, vθ), not the matrix [V]",
    (6, 1): "a column of shape (6, 1): V is a flat vector of shape (6,)",
}


def _log_call(sub, T, inputs=None) -> np.ndarray:
    inputs = {"T": T} if inputs is None else inputs
    value = sub.twist_log(T)
    if isinstance(value, (tuple, list)) and len(value) == 2 and np.ndim(value[1]) == 0:
        raise Mismatch(
            "twist_log(T) must return one 6-vector V = (ωθ, vθ); got a pair (S, θ)",
            inputs=inputs,
            mistake="the screw axis and θ returned separately: return their product S θ",
        )
    try:
        raw = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raw = None
    if raw is not None and raw.shape == (6,) and not np.all(np.isfinite(raw)):
        raise Mismatch(
            "twist_log(T) returned NaN or infinity",
            inputs=inputs,
            got=raw,
            mistake=(
                "a division by sin θ or θ where it is zero: handle θ = 0 (a pure translation, "
                "V = (0, p)) and θ = π (the axis from the symmetric part of R) separately"
            ),
        )
    got = as_array(value, (6,), "twist_log(T)", inputs, _LOG_SHAPES)
    return got


def _log_matches(sub, rng):
    for _ in range(10):
        V, T = _log_inputs(rng)
        compare(
            _log_call(sub, T),
            V,
            what="V = (ωθ, θ G⁻¹(θ) p) with θ = |ωθ| in [0, π]",
            inputs={"T": T},
            hypotheses=_log_hypotheses(T),
        )


def _log_of_translations(sub, rng):
    poses = [np.eye(4)] + [_transform(np.eye(3), rng.uniform(-0.8, 0.8, 3)) for _ in range(4)]
    for T in poses:
        compare(
            _log_call(sub, T),
            np.r_[np.zeros(3), T[:3, 3]],
            what="a pure translation (R = I, θ = 0) has the twist V = (0, p)",
            inputs={"T": T},
            hypotheses={_ORDER: lambda T=T: np.r_[T[:3, 3], np.zeros(3)]},
        )


def _log_at_the_edges(sub, rng):
    cases = []
    for _ in range(2):  # exact half turns, R = 2 ω ωᵀ − I: symmetric, so sin θ · ω reads 0
        w = _unit(rng)
        cases.append((np.pi, _transform(2 * np.outer(w, w) - np.eye(3), rng.uniform(-0.6, 0.6, 3))))
    for theta in (np.pi, np.pi - 1e-8, np.pi - 1e-4, 1e-3, 1e-6, 1e-9):
        w = _unit(rng)
        V = np.r_[w, rng.uniform(-0.6, 0.6, 3)] * theta
        cases.append((theta, se3_exp(V)))
    for theta, T in cases:
        inputs = {"T": T, "θ (rad)": theta}
        got = _log_call(sub, T, inputs)
        angle = float(np.linalg.norm(got[:3]))
        if angle <= np.pi + 1e-9 and close(se3_exp(got), T, 1e-8, like=got):
            continue
        near_pi = theta > 3.0
        rotation_wrong = not close(se3_exp(got)[:3, :3], T[:3, :3], 1e-8, like=got)
        swapped = np.r_[got[3:], got[:3]]
        if np.linalg.norm(swapped[:3]) <= np.pi + 1e-9 and close(
            se3_exp(swapped), T, 1e-8, like=got
        ):  # the parts in the other order reproduce T: whatever θ is, that is the mistake
            mistake = _ORDER
        elif near_pi and rotation_wrong:
            mistake = (
                "the axis divided by sin θ next to a half turn: it is lost there; use the "
                "symmetric part of R"
            )
        else:
            mistake = identify_mistake(got, _log_hypotheses(T)) if theta < 3.0 else None
        raise Mismatch(
            "e^[V] must reproduce T, with θ = |ωθ| ≤ π, also "
            + (
                "at and next to a half turn (there sin θ ≈ 0: take the axis from the "
                "symmetric part of R, R + Rᵀ − 2 cos θ I = 2(1 − cos θ) ω ωᵀ)"
                if near_pi
                else "for small turns (compute θ with atan2, not arccos, and keep "
                "1/θ − cot(θ/2)/2 accurate)"
            )
            + " — checked to 1e-8",
            inputs=inputs,
            expected=T,
            got=se3_exp(got),
            mistake=mistake,
            difference=_pose_gap(se3_exp(got), T),
        )


def _pose_gap(A, B) -> str | None:
    """How far pose ``A`` is from ``B``, in words (4 decimals can show two poses alike)."""
    try:
        A = np.asarray(A, dtype=float)
        turn = float(rotation_angle(A[:3, :3], B[:3, :3]))
        shift = float(np.linalg.norm(A[:3, 3] - B[:3, 3]))
    except (TypeError, ValueError):  # not a pose: the values shown say enough
        return None
    return f"e^[V] is {turn:.1e} rad from T's rotation and {shift:.1e} m from its position"


# ------------------------------------------------------------------------- 3.6 screw_to_joint

_NOT_NEAREST = (
    "a point of the axis, but not the one nearest the origin: remove its part along ω, "
    "q − (q·ω) ω — ω × v is that nearest point"
)
_POINT_SHAPES = {
    (6,): "a 6-vector: the answer is one point, shape (3,)",
    (3, 1): "a column of shape (3, 1): the point is a flat vector of shape (3,)",
    (1, 3): "a row of shape (1, 3): the point is a flat vector of shape (3,)",
}


def _joint_hypotheses(S):
    w, v = S[:3], S[3:]
    hypotheses = {
        "v × ω (or S read as (v, ω)): the cross product in the wrong order gives the mirror "
        "point −q; from v = −ω × q, ω × v = q − (ω·q) ω": lambda: np.cross(v, w),
        "v itself: v is the velocity of the body point at the origin, not a point of the axis; "
        "the nearest point is ω × v": lambda: v,
        "−v (which is also ω × (ω × v)): v is a velocity, not a point of the axis; the nearest "
        "point is ω × v": lambda: -v,
        "ω itself: the direction of the axis, not a point on it; the nearest point is ω × v": (
            lambda: w
        ),
    }
    return unless_right(hypotheses, np.cross(w, v))


def _joint_call(sub, S, inputs=None) -> np.ndarray:
    inputs = {"S": S} if inputs is None else inputs
    return as_array(sub.screw_to_joint(S.copy()), (3,), "screw_to_joint(S)", inputs, _POINT_SHAPES)


def _joint_mistake(got, S) -> str | None:
    """The named mistake behind a wrong point: a point of the axis that is not the nearest one,
    or a hypothesis."""
    w, v = S[:3], S[3:]
    on_axis = close(-np.cross(w, got.astype(float)), v, 1e-6)
    if on_axis and abs(float(np.dot(got, w))) > 1e-6:
        return _NOT_NEAREST
    return identify_mistake(got, _joint_hypotheses(S))


def _joint_compare(sub, S, what, inputs=None) -> None:
    got = _joint_call(sub, S, inputs)
    expected = np.cross(S[:3], S[3:])
    if not close(got, expected, 1e-9):
        scale = float(np.abs(expected).max(initial=0.0))
        gap = float(np.abs(got.astype(float) - expected).max())
        raise Mismatch(
            what,
            inputs=inputs or {"S": S},
            expected=expected,
            got=got,
            mistake=_joint_mistake(got, S),
            difference=(
                f"largest difference {gap:.1e}; the tolerance is {tolerance(1e-9, got, scale):.0e}"
                if gap < 1e-3
                else None
            ),
        )


def _joint_random_axes(sub, rng):
    for _ in range(10):
        w, q = _unit(rng), rng.uniform(-0.8, 0.8, 3)
        q = q + rng.uniform(-1.0, 1.0) * w  # any point of the line, not the nearest one
        S = screw_axis(w, q)
        _joint_compare(
            sub,
            S,
            "the point of the axis nearest the origin, q = ω × v (the one point of the axis "
            "with q·ω = 0)",
            inputs={"S": S, "a point of the axis": q},
        )


def _joint_ur_axes(sub, rng):
    for _ in range(3):
        arm = random_arm(rng)
        S_home, _ = space_screws(arm)
        q = random_q(rng)
        current = jacobian_space(S_home, q)  # joint axes at q, same (ω, v) form
        for axes, where in ((S_home, "at q = 0"), (current, "at a random q")):
            for i in range(6):
                S = axes[:, i].copy()
                _joint_compare(
                    sub,
                    S,
                    f"joint {i + 1} of the {arm.name} {where}: the point of its axis nearest "
                    "the base origin, ω × v",
                    inputs={"robot": arm.name, "joint": str(i + 1), "S": S},
                )


_NO_UNIT_CHECK = (
    "no check of the input: a screw axis whose ω is not a unit vector (a prismatic joint, "
    "ω = 0, or an unnormalised ω) has no point ω × v; raise ValueError naming S"
)


def _joint_refuses_non_unit(sub, rng):
    S = screw_axis(_unit(rng), rng.uniform(-0.5, 0.5, 3))
    _joint_call(sub, S)  # a function that refuses every S earns nothing here
    S[:3] *= 1.0 + 1e-12  # unit to round-off (as a computed ω is): still a joint axis
    _joint_call(sub, S, {"S": S, "case": "ω of length 1 + 1e-12: a unit vector to round-off"})
    w = _unit(rng)
    prismatic = np.r_[np.zeros(3), _unit(rng)]
    cases = [
        ("a prismatic joint, ω = 0", prismatic),
        ("ω of length 2", np.r_[2.0 * w, -np.cross(2.0 * w, rng.uniform(-0.5, 0.5, 3))]),
        ("ω of length 0.5", np.r_[0.5 * w, -np.cross(0.5 * w, rng.uniform(-0.5, 0.5, 3))]),
        ("ω of length 1.01", np.r_[1.01 * w, rng.uniform(-0.3, 0.3, 3)]),
        (
            "ω of length 1.0001 (1e-4 beyond unit, a hundred times the 1e-6 allowed)",
            np.r_[1.0001 * w, rng.uniform(-0.3, 0.3, 3)],
        ),
    ]
    for name, S in cases:
        inputs = {"S": S, "case": name}
        try:
            value = sub.screw_to_joint(S.copy())
        except StudentRaised as exc:
            if exc.kind == "NotImplementedError" and exc.message.strip().startswith("Exercise "):
                raise
            if exc.kind != "ValueError":
                raise Mismatch(
                    f"screw_to_joint(S) raised {exc.kind} for {name}: the contract is a "
                    "ValueError that names S",
                    inputs=inputs,
                    mistake=(
                        "another exception than ValueError (an assert, a division by zero): "
                        "raise ValueError naming S"
                    ),
                ) from None
            if not re.search(r"\bS\b", exc.message):
                raise Mismatch(
                    f"screw_to_joint(S) raised ValueError for {name}, but its message does not "
                    f"name the argument S: {exc.message.strip()[:120]!r}",
                    inputs=inputs,
                    mistake="the ValueError's message does not say which argument is wrong (S)",
                ) from None
            continue
        raise Mismatch(
            f"screw_to_joint(S) must raise ValueError for {name} (|ω| ≠ 1), and it returned a "
            "value",
            inputs=inputs,
            got=value if np.shape(value) == (3,) else None,
            mistake=_NO_UNIT_CHECK,
        )


# ------------------------------------------------------------------------ 3.7 body_from_space

_SIX_COLUMNS = (
    "six columns hard-coded (range(6), or a (6, 6) array of zeros): S has one column per joint, "
    "n of them; loop over S.shape[1] columns, or multiply Ad(M⁻¹) @ S at once"
)


def _adjoint_of(R, p, layout="right") -> np.ndarray:
    """[[R, 0], [[p]R, R]], or another arrangement of its blocks (``layout``)."""
    P = skew(p)
    Ad = np.zeros((6, 6))
    Ad[:3, :3] = Ad[3:, 3:] = R
    if layout == "right":
        Ad[3:, :3] = P @ R
    elif layout == "top right":
        Ad[:3, 3:] = P @ R
    elif layout == "R[p]":
        Ad[3:, :3] = R @ P
    return Ad


def _body_hypotheses(S, M):
    R, p = M[:3, :3], M[:3, 3]
    right_Ad = _adjoint_of(R.T, -R.T @ p)
    swap = [3, 4, 5, 0, 1, 2]
    n = S.shape[1]
    hypotheses = {
        "Ad(M) S instead of Ad(M⁻¹) S: the adjoint of M maps body twists to space ones; "
        "B = Ad(M⁻¹) S goes the other way": lambda: _adjoint_of(R, p) @ S,
        "[p]R in the top-right block: for twists ordered (ω, v) the adjoint is [[R, 0], "
        "[[p]R, R]] (the top-right layout is for (v, ω) twists)": lambda: (
            _adjoint_of(R.T, -R.T @ p, "top right") @ S
        ),
        "B returned in (v, ω) order: screw axes are (ω, v), angular part first": lambda: (
            right_Ad @ S
        )[swap],
        "S read as (v, ω): its rows are (ω, v), angular part first": lambda: right_Ad @ S[swap],
        "R not transposed: M⁻¹ = (Rᵀ, −Rᵀp), so Ad(M⁻¹) has Rᵀ where Ad(M) has R": lambda: (
            _adjoint_of(R, -R.T @ p) @ S
        ),
        "the translation of M⁻¹ taken as −p: it is −Rᵀp": lambda: _adjoint_of(R.T, -p) @ S,
        "a sign lost: the translation of M⁻¹ is −Rᵀp, and [p] is the skew matrix with "
        "[p]v = p × v": lambda: _adjoint_of(R.T, R.T @ p) @ S,
        "R[p] in the bottom-left block: it is [p]R, the skew matrix first": lambda: (
            _adjoint_of(R.T, -R.T @ p, "R[p]") @ S
        ),
        "Ad(M⁻¹)ᵀ S: the adjoint transposed (or applied to the rows of S)": lambda: right_Ad.T @ S,
        "the 6 × 6 adjoint itself came back: B = Ad(M⁻¹) S, one column per joint": lambda: right_Ad,
        "B transposed: one screw axis per column, B[:, i] = Ad(M⁻¹) S[:, i]": lambda: (
            (right_Ad @ S).T
        ),
        "S returned unchanged: those are the axes seen from the base; B = Ad(M⁻¹) S sees them "
        "from the end effector at q = 0": lambda: S,
    }
    if n > 6:
        hypotheses[_SIX_COLUMNS] = lambda: np.c_[right_Ad @ S[:, :6], np.zeros((6, n - 6))]
    return unless_right(hypotheses, right_Ad @ S)


def _body_call(sub, S, M, inputs) -> np.ndarray:
    n = S.shape[1]
    try:
        value = sub.body_from_space(S.copy(), M.copy())
    except StudentRaised as exc:
        if exc.kind != "IndexError" or n >= 6:
            raise
        raise Mismatch(
            exc.describe().splitlines()[0] + f" for {n} screw axes",
            inputs=inputs,
            mistake=_SIX_COLUMNS,
        ) from None
    shapes = (
        {}
        if n == 6
        else {(6, 6): _SIX_COLUMNS, (n, 6): "B transposed: one screw axis per column, shape (6, n)"}
    )
    return as_array(value, (6, n), "body_from_space(S, M)", inputs, shapes)


def _body_compare(sub, S, M, what, inputs) -> np.ndarray:
    got = _body_call(sub, S, M, inputs)
    R, p = M[:3, :3], M[:3, 3]
    compare(
        got,
        _adjoint_of(R.T, -R.T @ p) @ S,
        what=what,
        inputs=inputs,
        hypotheses=_body_hypotheses(S, M),
        atol=1e-12,
    )
    return got


def _arm_name(arm) -> str:
    """The arm's name, and whether it is mounted elsewhere or carries a tool."""
    extras = [
        text
        for text, T in (("on a random mounting", arm.base), ("with a random tool", arm.tool))
        if not np.array_equal(T, np.eye(4))
    ]
    return " ".join([arm.name, *extras[:1], *(f"and {e}" for e in extras[1:])])


def _mounted_arm(rng):
    """A random UR arm, on a random mounting and with a random tool now and then."""
    arm = random_arm(rng)
    if rng.random() < 0.5:
        arm = arm.with_base(random_pose(rng))
    if rng.random() < 0.5:
        arm = arm.with_tool(random_pose(rng))
    return arm


def _body_ur_arms(sub, rng):
    for _ in range(4):
        arm = _mounted_arm(rng)
        S, M = space_screws(arm)
        B, _ = body_screws(arm)
        inputs = {"robot": _arm_name(arm), "S": S, "M": M}
        got = _body_call(sub, S, M, inputs)
        compare(
            got,
            B,
            what=f"the body screw axes of the {_arm_name(arm)}, B = Ad(M⁻¹) S, to 1e-12",
            inputs=inputs,
            hypotheses=_body_hypotheses(S, M),
            atol=1e-12,
        )


def _body_any_axes(sub, rng):
    for n in rng.permutation(np.arange(1, 8)):  # every n from 1 to 7, in random order
        S = random_screw_axes(rng, int(n))
        M = random_pose(rng)
        _body_compare(
            sub,
            S,
            M,
            f"B = Ad(M⁻¹) S for {n} random screw axes (one per column) and a random M, to 1e-12",
            {"S": S, "M": M},
        )


def _body_fk_agrees(sub, rng):
    arms = [_mounted_arm(rng) for _ in range(3)]
    cases = [(_arm_name(arm), *space_screws(arm)) for arm in arms]
    cases.append(("6 random joints", random_screw_axes(rng, 6), random_pose(rng)))
    for name, S, M in cases:
        inputs = {"robot": name, "S": S, "M": M}
        B = _body_call(sub, S, M, inputs)
        q = rng.uniform(-np.pi, np.pi, (5, S.shape[1]))
        T_space = urkin.poe.fk_space(M, S, q)
        T_body = urkin.poe.fk_body(M, B.astype(float), q)
        worst = int(np.argmax(np.abs(T_body - T_space).max(axis=(1, 2))))
        if not close(T_body[worst], T_space[worst], 1e-9, like=B):
            raise Mismatch(
                "with your B, the body form M e^[B1]q1 ⋯ e^[Bn]qn (urkin.poe.fk_body) must give "
                "the pose of the space form e^[S1]q1 ⋯ e^[Sn]qn M (urkin.poe.fk_space), to 1e-9",
                inputs={**inputs, "q": q[worst]},
                expected=T_space[worst],
                got=T_body[worst],
                mistake=identify_mistake(B, _body_hypotheses(S, M)),
            )


# ------------------------------------------------------------------------ 3.8 screws_from_dh

_SIX_JOINTS_DH = (
    "six joints hard-coded (range(6), or a (6, 6) array of zeros): the table has one row per "
    "joint, n of them; loop over len(rows)"
)
_SWAP = [3, 4, 5, 0, 1, 2]


def _random_table(rng, n: int) -> np.ndarray:
    """A new arm's standard-DH table (n, 3): rows (d, a, α), most twists multiples of π/2."""
    alpha = rng.choice([0.0, np.pi / 2, -np.pi / 2], n)
    free = rng.random(n) < 0.3
    alpha[free] = rng.uniform(-np.pi, np.pi, int(free.sum()))
    return np.column_stack([rng.uniform(-0.3, 0.3, n), rng.uniform(-0.5, 0.5, n), alpha])


def _home_frames(rows) -> np.ndarray:
    """DH frames 0 … n of a standard table at q = 0 (frame 0 the base): shape (n + 1, 4, 4)."""
    links = dh_transform(0.0, rows[:, 0], rows[:, 1], rows[:, 2])
    frames = [np.eye(4)]
    for link in links:
        frames.append(frames[-1] @ link)
    return np.array(frames)


def _frame_screws(frames, axis=0, point=0, sign=-1.0, take=lambda F: F[:3, 2]) -> np.ndarray:
    """Screw axes (6, n) read off the frames: joint i + 1's ω from frame i + ``axis``, its point
    from frame i + ``point``, v = ``sign`` · ω × p (the recipe's pieces swappable)."""
    n = len(frames) - 1
    S = np.zeros((6, n))
    for i in range(n):
        w, p = take(frames[i + axis]), frames[i + point][:3, 3]
        S[:3, i], S[3:, i] = w, sign * np.cross(w, p)
    return S


def _dh_screw_hypotheses(rows):
    frames = _home_frames(rows)
    right = _frame_screws(frames)
    swapped = _home_frames(rows[:, [1, 0, 2]])
    n = len(rows)
    hypotheses = {
        "frames off by one: joint i turns about z_(i−1) of frame i − 1 (the base z for joint "
        "1), through its origin p_(i−1) — not about z_i (that is the modified-DH recipe)": lambda: (
            _frame_screws(frames, axis=1, point=1)
        ),
        "v = +ω × p has the wrong sign: a revolute joint's v is −ω × p = p × ω": lambda: (
            _frame_screws(frames, sign=1.0)
        ),
        "S in (v, ω) order: screw axes are (ω, v), angular part first": lambda: right[_SWAP],
        "the point from frame i (p_i) with the axis of frame i − 1: z_(i−1) passes through "
        "p_(i−1); p_i lies a_i off it along x_i": lambda: _frame_screws(frames, point=1),
        "the axis from frame i (z_i) with the point of frame i − 1: joint i turns about "
        "z_(i−1)": lambda: _frame_screws(frames, axis=1),
        "v = p: the frame's origin is a point of the axis, not its v; v = −z × p": lambda: (
            np.vstack([right[:3], frames[:-1, :3, 3].T])
        ),
        "the joint axis taken from the first column of the frame (x): z is the third column, "
        "F[:3, 2]": lambda: _frame_screws(frames, take=lambda F: F[:3, 0]),
        "the joint axis taken from the third row of the rotation: z is the third column, "
        "F[:3, 2]": lambda: _frame_screws(frames, take=lambda F: F[2, :3]),
        "the rows read as (a, d, α): the course's DH rows are (d, a, α), d first": lambda: (
            _frame_screws(swapped)
        ),
        "S transposed: one screw axis per column, shape (6, n)": lambda: right.T,
    }
    if n > 6:
        hypotheses[_SIX_JOINTS_DH] = lambda: np.c_[right[:, :6], np.zeros((6, n - 6))]
    return unless_right(hypotheses, right)


def _dh_home_hypotheses(rows):
    frames = _home_frames(rows)
    return unless_right(
        {
            "M forgotten (the identity, the base frame): M is the end effector's pose at q = 0, "
            "T_0n(0), the last DH frame": lambda: np.eye(4),
            "M = T_0,n−1(0), the last joint's frame: the end effector is frame n, one link "
            "further": lambda: frames[-2],
            "M inverted: it is the pose of frame n in the base frame, T_0n(0)": lambda: (
                inv_transform(frames[-1])
            ),
            "M from the rows read as (a, d, α): the course's DH rows are (d, a, α), d first": (
                lambda: _home_frames(rows[:, [1, 0, 2]])[-1]
            ),
        },
        frames[-1],
    )


def _shape_of_value(value) -> tuple[int, ...] | None:
    """The shape of a returned value as numbers, or None when it is not numbers."""
    try:
        return np.shape(np.asarray(value, dtype=float))
    except (TypeError, ValueError):
        return None


def _dh_call(sub, rows, inputs) -> tuple[np.ndarray, np.ndarray]:
    """The student's (S, M), each checked for shape."""
    n, what = len(rows), "screws_from_dh(rows)"
    try:
        value = sub.screws_from_dh(rows.copy())
    except StudentRaised as exc:
        if exc.kind != "IndexError" or n >= 6:
            raise
        raise Mismatch(
            exc.describe().splitlines()[0] + f" for a table of {n} rows",
            inputs=inputs,
            mistake=_SIX_JOINTS_DH,
        ) from None
    if value is None:
        raise Mismatch(f"{what} returned None: is a `return` statement missing?", inputs=inputs)
    if not (isinstance(value, (tuple, list)) and len(value) == 2):
        shape = _shape_of_value(value)
        raise Mismatch(
            f"{what} must return a pair (S, M); got {type(value).__name__}"
            + (f" of shape {shape}" if shape else ""),
            inputs=inputs,
            mistake=(
                "only S returned: return the pair (S, M), with M = T_0n(0) the end effector's "
                "pose at q = 0"
                if shape in ((6, n), (n, 6))
                else None
            ),
        )
    first, second = value
    if _shape_of_value(first) == (4, 4) and _shape_of_value(second) in ((6, n), (n, 6)):
        raise Mismatch(
            f"{what} must return (S, M), S first; got a (4, 4) matrix first",
            inputs=inputs,
            mistake="(M, S) returned: the order is (S, M), the screw axes first",
        )
    shapes = {(n, 6): "S transposed: one screw axis per column, shape (6, n)"} if n != 6 else {}
    if n != 6:
        shapes[(6, 6)] = _SIX_JOINTS_DH
    S = as_array(first, (6, n), f"S (item 0 of {what})", inputs, shapes)
    M = as_array(second, (4, 4), f"M (item 1 of {what})", inputs)
    return S, M


def _dh_compare(sub, rows, name, expected=None) -> None:
    inputs = {"arm": name, "rows": rows}
    S, M = _dh_call(sub, rows, inputs)
    S_right, M_right = space_screws(rows) if expected is None else expected
    compare(
        S,
        S_right,
        what=f"the space screw axes of {name}: S_i = (z_(i−1), −z_(i−1) × p_(i−1)) of DH "
        "frame i − 1 at q = 0, one per column (to 1e-12)",
        inputs=inputs,
        hypotheses=_dh_screw_hypotheses(rows),
        atol=1e-12,
    )
    compare(
        M,
        M_right,
        what=f"the home pose M of {name}: the last DH frame at q = 0, T_0n(0) (to 1e-12)",
        inputs=inputs,
        hypotheses=_dh_home_hypotheses(rows),
        atol=1e-12,
    )


def _dh_ur_arms(sub, rng):
    for _ in range(4):
        arm = random_arm(rng)
        _dh_compare(sub, arm.dh_table(), f"the {arm.name}'s table", space_screws(arm))


def _dh_any_table(sub, rng):
    for n in rng.permutation(np.arange(1, 8)):  # every n from 1 to 7, in random order
        _dh_compare(sub, _random_table(rng, int(n)), f"a new arm of {n} joint(s)")


def _dh_fk_agrees(sub, rng):
    cases = [(f"the {arm.name}'s table", arm.dh_table()) for arm in (random_arm(rng),)]
    for n in (int(rng.integers(1, 6)), 7, int(rng.integers(2, 8))):
        cases.append((f"a new arm of {n} joint(s)", _random_table(rng, n)))
    for name, rows in cases:
        inputs = {"arm": name, "rows": rows}
        S_got, M_got = _dh_call(sub, rows, inputs)
        like = S_got if S_got.dtype.itemsize <= M_got.dtype.itemsize else M_got
        S, M = S_got.astype(float), M_got.astype(float)
        q = rng.uniform(-np.pi, np.pi, (5, len(rows)))
        try:
            T_poe = np.array([_chain(_reference_factors(S, q_k)) @ M for q_k in q])
        except ValueError:  # entries too large for an exponential: certainly not the chain
            T_poe = np.full((5, 4, 4), np.inf)
        T_dh = dh_chain(rows, q)
        worst = int(np.argmax(np.abs(T_poe - T_dh).max(axis=(1, 2))))
        if close(T_poe[worst], T_dh[worst], 1e-9, like=like):
            continue
        S_right, M_right = space_screws(rows)
        mistake = None
        if not close(S, S_right, 1e-9):
            mistake = identify_mistake(S, _dh_screw_hypotheses(rows))
        elif not close(M, M_right, 1e-9):
            mistake = identify_mistake(M, _dh_home_hypotheses(rows))
        raise Mismatch(
            "with your S and M, the space form e^[S1]q1 ⋯ e^[Sn]qn M (urkin.poe.fk_space) must "
            "give the table's DH chain dh_chain(rows, q) at every q (to 1e-9)",
            inputs={**inputs, "q": q[worst]},
            expected=T_dh[worst],
            got=T_poe[worst],
            mistake=mistake,
        )


LESSON = Lesson(
    number="03",
    title="The product of exponentials",
    summary=(
        "product of exponentials: screw axes by hand and from DH tables, space and body forms, "
        "the matrix log"
    ),
    exercises=(
        Exercise(
            id="3.1",
            function="screw_axis",
            title="the screw axis of a revolute joint",
            checks=(
                Check("matches (ω, −ω × q) for random axes and points", 2, _screw_matches),
                Check(
                    "describes the axis, not the point: the same S for every point on it, "
                    "another S for a parallel axis",
                    1,
                    _screw_describes_the_line,
                ),
            ),
            answer=concepts.SCREW_AXIS,
        ),
        Exercise(
            id="3.2",
            function="twist_exp",
            title="the exponential e^[S]θ of a revolute screw axis",
            checks=(
                Check("returns a homogeneous transform turning by θ about ω", 1, _twist_is_a_turn),
                Check("matches e^[S]θ for random screw axes and angles", 2, _twist_matches),
                Check(
                    "turns space about the screw axis: its points stay, others circle it",
                    1,
                    _twist_turns_about_its_axis,
                ),
            ),
            answer=concepts.TWIST_EXP,
        ),
        _product_exercise("3.3", _SPACE),
        _product_exercise("3.4", _BODY),
        Exercise(
            id="3.5",
            function="twist_log",
            title="the matrix logarithm of a rigid motion",
            checks=(
                Check("matches the logarithm for random poses", 2, _log_matches),
                Check(
                    "gives (0, p) for pure translations and the identity", 1, _log_of_translations
                ),
                Check(
                    "round-trips at and next to half turns, and for small turns",
                    1,
                    _log_at_the_edges,
                ),
            ),
            answer=concepts.TWIST_LOG,
        ),
        Exercise(
            id="3.6",
            function="screw_to_joint",
            title="the point of a joint's axis nearest the origin, from its screw axis",
            checks=(
                Check(
                    "returns ω × v, the point of the axis nearest the origin, for random axes",
                    1,
                    _joint_random_axes,
                ),
                Check(
                    "finds the nearest points of the joint axes of random UR arms, at q = 0 and "
                    "at a random q",
                    1,
                    _joint_ur_axes,
                ),
                Check(
                    "raises ValueError naming S when ω is not a unit vector",
                    1,
                    _joint_refuses_non_unit,
                ),
            ),
        ),
        Exercise(
            id="3.7",
            function="body_from_space",
            title="body screw axes from space screw axes, B = Ad(M⁻¹) S",
            checks=(
                Check(
                    "the body screw axes of random UR arms, mounted and tooled at random",
                    1,
                    _body_ur_arms,
                ),
                Check(
                    "B = Ad(M⁻¹) S for 1 to 7 random screw axes and a random M",
                    2,
                    _body_any_axes,
                ),
                Check(
                    "with your B, the body-form FK gives the space-form pose at random q",
                    1,
                    _body_fk_agrees,
                ),
            ),
            answer=(adjoint, body_screws),
        ),
        Exercise(
            id="3.8",
            function="screws_from_dh",
            title="the space screw axes and home pose of any arm, from its DH table",
            checks=(
                Check(
                    "the screw axes S and the home pose M of random UR arms' DH tables",
                    1,
                    _dh_ur_arms,
                ),
                Check("S and M of new arms of 1 to 7 joints", 2, _dh_any_table),
                Check(
                    "with your S and M, the space-form FK gives the DH chain at random q",
                    1,
                    _dh_fk_agrees,
                ),
            ),
            answer=(*concepts.SCREW_AXIS, space_screws),
        ),
    ),
)
