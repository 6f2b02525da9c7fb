"""Lesson 03 — product of exponentials."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

import numpy as np

import urkin
from urkin.exercises.framework import (
    Check,
    Exercise,
    Mismatch,
    as_array,
    compare,
    register,
    require_transform,
)
from urkin.exercises.inputs import random_arm, random_q
from urkin.kinematics import dh_chain
from urkin.poe import body_screws, fk_body, fk_space, screw_axis, space_screws
from urkin.transforms import se3_exp

_fk = urkin.fk  # references, bound before any grading guard is installed
_screw_axis, _se3_exp = screw_axis, se3_exp

_FK_FUNCTIONS = (
    "urkin.kinematics.fk",
    "urkin.kinematics.fk_frames",
    "urkin.kinematics.dh_chain",
    "urkin.poe.fk_space",
    "urkin.poe.fk_body",
    "urkin._generated.ur_kinematics.t06_one",
    "urkin._generated.ur_kinematics.t06_many",
    "urkin._generated.ur_kinematics.frames_one",
    "urkin._generated.ur_kinematics.frames_many",
)


def _unit(rng) -> np.ndarray:
    w = rng.normal(size=3)
    return w / np.linalg.norm(w)


# ---------------------------------------------------------------------------- 3.1 screw_axis


def _screw_hypotheses(w, q):
    right = _screw_axis(w, q)
    return {
        "v = ω × q has the wrong sign: a revolute joint's v is −ω × q (= q × ω)": lambda: np.r_[
            w, np.cross(w, q)
        ],
        "(v, ω) order: Modern Robotics writes screw axes (ω, v), angular part first": lambda: np.r_[
            right[3:], right[:3]
        ],
        "v = q: the point itself is not the linear part": lambda: np.r_[w, q],
    }


def _screw_matches(student, rng):
    for _ in range(10):
        w, q = _unit(rng), rng.uniform(-0.5, 0.5, 3)
        got = as_array(student(w.copy(), q.copy()), (6,), "screw_axis(w, q)")
        compare(
            got,
            _screw_axis(w, q),
            what="S = (ω, v) with v = −ω × q",
            inputs={"w": w, "q": q},
            hypotheses=_screw_hypotheses(w, q),
        )


def _screw_ignores_where_on_the_axis(student, rng):
    for _ in range(10):
        w, q, t = _unit(rng), rng.uniform(-0.5, 0.5, 3), rng.uniform(-1.0, 1.0)
        first = as_array(student(w.copy(), q.copy()), (6,), "screw_axis(w, q)")
        moved = as_array(student(w.copy(), q + t * w), (6,), "screw_axis(w, q + t w)")
        if not np.allclose(first, moved, atol=1e-9):
            raise Mismatch(
                "any point on the axis describes the same joint: moving q along ω must not "
                "change S",
                inputs={"w": w, "q": q, "t": t},
                expected=first,
                got=moved,
            )


register(
    Exercise(
        id="3.1",
        function="screw_axis",
        title="the screw axis of a revolute joint",
        checks=(
            Check("matches (ω, −ω × q) for random axes and points", 2, _screw_matches),
            Check("is the same for every point on the axis", 1, _screw_ignores_where_on_the_axis),
        ),
        forbidden=("urkin.poe.screw_axis",),
    )
)


# ----------------------------------------------------------------------------- 3.2 twist_exp


def _twist_inputs(rng):
    return _screw_axis(_unit(rng), rng.uniform(-0.5, 0.5, 3)), rng.uniform(-np.pi, np.pi)


def _twist_hypotheses(S, theta):
    right = _se3_exp(S * theta)
    naive = np.eye(4)
    naive[:3, :3], naive[:3, 3] = right[:3, :3], S[3:] * theta
    transposed = right.copy()
    transposed[:3, :3] = right[:3, :3].T
    return {
        "the translation is not v·θ: a rotation about an axis off the origin also moves the "
        "origin — use (Iθ + (1 − cos θ)[ω] + (θ − sin θ)[ω]²) v": lambda: naive,
        "the rotation block is transposed (that is the turn by −θ)": lambda: transposed,
        "θ treated as degrees": lambda: _se3_exp(S * np.radians(theta)),
    }


def _twist_is_transform(student, rng):
    for _ in range(5):
        S, theta = _twist_inputs(rng)
        got = as_array(student(S.copy(), theta), (4, 4), "twist_exp(S, theta)")
        require_transform(got, "twist_exp(S, theta)", {"S": S, "theta": theta})


def _twist_matches(student, rng):
    for _ in range(10):
        S, theta = _twist_inputs(rng)
        got = as_array(student(S.copy(), theta), (4, 4), "twist_exp(S, theta)")
        compare(
            got,
            _se3_exp(S * theta),
            what="e^[S]θ = [[e^[ω]θ, (Iθ + (1 − cos θ)[ω] + (θ − sin θ)[ω]²) v], [0, 1]]",
            inputs={"S": S, "theta": theta},
            hypotheses=_twist_hypotheses(S, theta),
        )


def _twist_fixes_its_axis(student, rng):
    for _ in range(10):
        S, theta = _twist_inputs(rng)
        point = np.r_[np.cross(S[:3], S[3:]), 1.0]  # ω × v lies on the axis
        got = as_array(student(S.copy(), theta), (4, 4), "twist_exp(S, theta)")
        if not np.allclose(got @ point, point, atol=1e-9):
            raise Mismatch(
                "a rotation about the screw axis leaves the points of the axis where they are",
                inputs={"S": S, "theta": theta, "point on the axis": point[:3]},
                expected=point[:3],
                got=(got @ point)[:3],
            )


register(
    Exercise(
        id="3.2",
        function="twist_exp",
        title="the exponential e^[S]θ of a revolute screw axis",
        checks=(
            Check("returns a homogeneous transform", 1, _twist_is_transform),
            Check("matches e^[S]θ for random screw axes and angles", 2, _twist_matches),
            Check("leaves the points of the axis fixed", 1, _twist_fixes_its_axis),
        ),
        forbidden=("urkin.transforms.se3_exp",),
    )
)


# ----------------------------------------------------------------- 3.3 fk_space and 3.4 fk_body


@dataclass(frozen=True)
class _ProductForm:
    """What differs between the space form (3.3) and the body form (3.4) of the product."""

    name: str  # "space" or "body"
    letter: str  # "S" or "B"
    screws: Callable[..., tuple[np.ndarray, np.ndarray]]
    reference: Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray]
    formula: str
    other_order: str  # the mistake of putting M on the other side

    @property
    def call(self) -> str:
        return f"fk_{self.name}(M, {self.letter}, q)"

    def hypotheses(self, M, axes, q) -> dict:
        space = self.name == "space"
        product_alone = self.reference(np.eye(4), axes, q)
        return {
            self.other_order: lambda: M @ product_alone if space else product_alone @ M,
            "the exponentials multiplied in reverse order (joint 6 first)": lambda: (
                _reversed_product(M, axes, q, space)
            ),
            "q treated as degrees": lambda: self.reference(M, axes, np.radians(q)),
        }


_SPACE = _ProductForm(
    name="space",
    letter="S",
    screws=space_screws,
    reference=fk_space,
    formula="T = e^[S1]q1 ⋯ e^[S6]q6 M",
    other_order="M multiplied first: M e^[S1]q1 ⋯ is the body form, which needs body screw axes",
)
_BODY = _ProductForm(
    name="body",
    letter="B",
    screws=body_screws,
    reference=fk_body,
    formula="T = M e^[B1]q1 ⋯ e^[B6]q6",
    other_order="M multiplied last: e^[B1]q1 ⋯ M is the space form, which needs space screw axes",
)


def _reversed_product(M, axes, q, space: bool):
    E = [_se3_exp(axes[:, i] * q[i]) for i in range(axes.shape[1])][::-1]
    T = np.eye(4)
    for e in E:
        T = T @ e
    return T @ M if space else M @ T


def _other_arm(rng) -> tuple[np.ndarray, np.ndarray]:
    """A random revolute arm with 3 or 7 joints (a DH table) and a configuration for it."""
    n = int(rng.choice([3, 7]))
    table = np.column_stack(
        [
            rng.uniform(-0.3, 0.3, n),
            rng.uniform(-0.5, 0.5, n),
            rng.choice([0.0, np.pi / 2, -np.pi / 2], n),
        ]
    )
    return table, rng.uniform(-np.pi, np.pi, n)


def _product_at_zero(form: _ProductForm, student, rng):
    for _ in range(3):
        axes, M = form.screws(random_arm(rng))
        got = as_array(student(M.copy(), axes.copy(), np.zeros(6)), (4, 4), form.call)
        compare(
            got,
            M,
            what="at q = 0 every exponential is the identity: T = M",
            inputs={"M": M, "q": np.zeros(6)},
        )


def _product_matches(form: _ProductForm, student, rng):
    for _ in range(10):
        arm, q = random_arm(rng), random_q(rng)
        axes, M = form.screws(arm)
        got = as_array(student(M.copy(), axes.copy(), q.copy()), (4, 4), form.call)
        compare(
            got,
            _fk(arm, q),
            what=f"{form.formula} (the {arm.name}'s flange pose)",
            inputs={"robot": arm.name, "q": q},
            hypotheses=form.hypotheses(M, axes, q),
        )


def _product_any_joint_count(form: _ProductForm, student, rng):
    for _ in range(4):
        table, q = _other_arm(rng)
        axes, M = form.screws(table)
        got = as_array(student(M.copy(), axes.copy(), q.copy()), (4, 4), form.call)
        compare(
            got,
            dh_chain(table, q),
            what=(
                f"an arm with {len(q)} joints: {form.letter} has one column per joint, "
                f"(6, {len(q)})"
            ),
            inputs={form.letter: axes, "q": q},
            hypotheses=form.hypotheses(M, axes, q),
        )


for _id, _form in (("3.3", _SPACE), ("3.4", _BODY)):
    register(
        Exercise(
            id=_id,
            function=f"fk_{_form.name}",
            title=f"forward kinematics, {_form.name} form",
            checks=(
                Check("gives M at q = 0", 1, partial(_product_at_zero, _form)),
                Check(
                    "matches the arm's flange pose for random arms and q",
                    2,
                    partial(_product_matches, _form),
                ),
                Check(
                    "works for any number of joints", 1, partial(_product_any_joint_count, _form)
                ),
            ),
            forbidden=_FK_FUNCTIONS,
            builds_on=("3.2",),
        )
    )
