"""Lesson 04 — Jacobians and singularities."""

from __future__ import annotations

import numpy as np

import urkin
from urkin.exercises.framework import (
    Check,
    Exercise,
    Mismatch,
    as_array,
    compare,
    register,
)
from urkin.exercises.inputs import random_arm, random_q
from urkin.kinematics import SINGULARITIES, singularities
from urkin.poe import space_from_geometric

_fk, _fk_frames, _jacobian = urkin.fk, urkin.fk_frames, urkin.jacobian
_singularities = singularities

# ------------------------------------------------------------------- 4.1 geometric_jacobian


def _columns_from(frames: np.ndarray, p: np.ndarray, shift: int, flip: bool) -> np.ndarray:
    J = np.zeros((6, 6))
    for i in range(6):
        z, o = frames[i + shift][:3, 2], frames[i + shift][:3, 3]
        J[:3, i] = np.cross(z, o - p) if flip else np.cross(z, p - o)
        J[3:, i] = z
    return J


def _jacobian_hypotheses(arm, q):
    J = _jacobian(arm, q)
    frames = _fk_frames(arm, q)
    p = frames[-1][:3, 3]
    return {
        "rows in twist order (ω; v): the geometric Jacobian stacks v first, then ω": lambda: (
            np.vstack([J[3:], J[:3]])
        ),
        "joint i turns about z of frame i − 1 (the base z for joint 1), not of frame i": lambda: (
            _columns_from(frames, p, 1, False)
        ),
        "the lever arm points the wrong way: v_i = z_(i−1) × (p − p_(i−1)), from the joint to "
        "the flange": lambda: _columns_from(frames, p, 0, True),
        "the space Jacobian (ω; v_s), which measures velocity at the base origin": lambda: (
            space_from_geometric(J, _fk(arm, q))
        ),
    }


def _jacobian_matches(student, rng):
    for _ in range(10):
        arm, q = random_arm(rng), random_q(rng)
        got = as_array(student(arm, q.copy()), (6, 6), "geometric_jacobian(robot, q)")
        compare(
            got,
            _jacobian(arm, q),
            what="column i = [z_(i−1) × (p − p_(i−1)); z_(i−1)], from the DH frames",
            inputs={"robot": arm.name, "q": q},
            hypotheses=_jacobian_hypotheses(arm, q),
        )


def _linear_rows_are_derivatives(student, rng):
    h = 1e-6
    for _ in range(5):
        arm, q = random_arm(rng), random_q(rng)
        got = as_array(student(arm, q.copy()), (6, 6), "geometric_jacobian(robot, q)")
        steps = h * np.eye(6)
        derivative = (_fk(arm, q + steps)[:, :3, 3] - _fk(arm, q - steps)[:, :3, 3]).T / (2 * h)
        if not np.allclose(got[:3], derivative, atol=1e-7):
            raise Mismatch(
                "the first three rows must be ∂p/∂q, the rate at which the flange moves as each "
                "joint turns (checked with central differences of the flange position)",
                inputs={"robot": arm.name, "q": q},
                expected=derivative,
                got=got[:3],
            )


register(
    Exercise(
        id="4.1",
        function="geometric_jacobian",
        title="the geometric Jacobian, column by column",
        checks=(
            Check(
                "its linear rows are the derivative of the flange position",
                2,
                _linear_rows_are_derivatives,
            ),
            Check("matches [v; ω] for random arms and configurations", 2, _jacobian_matches),
        ),
        forbidden=(
            "urkin.kinematics.jacobian",
            "urkin.kinematics.position_jacobian",
            "urkin.poe.jacobian_space",
            "urkin.poe.jacobian_body",
            "urkin.poe.geometric_from_space",
            "urkin._generated.ur_kinematics.jacobian_one",
            "urkin._generated.ur_kinematics.jacobian_many",
            "urkin._generated.ur_kinematics.position_jacobian_one",
            "urkin._generated.ur_kinematics.position_jacobian_many",
        ),
    )
)


# ---------------------------------------------------------------------- 4.2 numeric_jacobian


def _forward(f, q, h):
    f0 = np.asarray(f(q), dtype=float)
    return np.column_stack([(np.asarray(f(q + h * e), float) - f0) / h for e in np.eye(len(q))])


def _central(f, q, h):
    return np.column_stack(
        [
            (np.asarray(f(q + h * e), float) - np.asarray(f(q - h * e), float)) / (2 * h)
            for e in np.eye(len(q))
        ]
    )


def _difference_hypotheses(f, q, h):
    return {
        "forward differences (f(q + h) − f(q)) / h: only first-order accurate; use central "
        "differences (f(q + h) − f(q − h)) / 2h": lambda: _forward(f, q, h),
        "divided by h instead of 2h": lambda: 2 * _central(f, q, h),
        "transposed: row i is output i, column j is input q_j (shape (m, n))": lambda: (
            _central(f, q, h).T
        ),
    }


def _exact_on_linear(student, rng):
    for _ in range(5):
        m, n = int(rng.integers(2, 6)), int(rng.integers(2, 7))
        A, b, q = rng.normal(size=(m, n)), rng.normal(size=m), rng.normal(size=n)

        def f(x, A=A, b=b):
            return A @ x + b

        got = as_array(student(f, q.copy(), 1e-4), (m, n), "numeric_jacobian(f, q, h)")
        compare(
            got,
            A,
            what="for f(q) = A q + b the Jacobian is A",
            atol=1e-8,
            inputs={"A": A, "q": q, "h": 1e-4},
            hypotheses=_difference_hypotheses(f, q, 1e-4),
        )


def _smooth(x):
    return np.array(
        [np.sin(x[0]) * x[1] ** 2, np.exp(0.5 * x[2]) + x[0] * x[1], np.cos(x[1] * x[2])]
    )


def _smooth_derivative(x):
    return np.array(
        [
            [np.cos(x[0]) * x[1] ** 2, 2 * np.sin(x[0]) * x[1], 0.0],
            [x[1], x[0], 0.5 * np.exp(0.5 * x[2])],
            [0.0, -x[2] * np.sin(x[1] * x[2]), -x[1] * np.sin(x[1] * x[2])],
        ]
    )


def _second_order(student, rng):
    h = 1e-3  # large enough that a first-order scheme shows its error
    for _ in range(5):
        q = rng.uniform(-1.0, 1.0, 3)
        got = as_array(student(_smooth, q.copy(), h), (3, 3), "numeric_jacobian(f, q, 1e-3)")
        compare(
            got,
            _smooth_derivative(q),
            atol=2e-5,
            what="with h = 1e-3 central differences are within ~1e-6 of the derivative",
            inputs={"q": q, "h": h},
            hypotheses=_difference_hypotheses(_smooth, q, h),
        )


def _on_the_arm(student, rng):
    arm, q = random_arm(rng), random_q(rng)

    def flange_position(x):
        return _fk(arm, x)[:3, 3]

    got = as_array(
        student(flange_position, q.copy(), 1e-6),
        (3, 6),
        "numeric_jacobian(flange_position, q, 1e-6)",
    )
    compare(
        got,
        _jacobian(arm, q)[:3],
        atol=1e-7,
        what="∂p/∂q of the flange position (a 3×6 matrix)",
        inputs={"robot": arm.name, "q": q, "h": 1e-6},
        hypotheses=_difference_hypotheses(flange_position, q, 1e-6),
    )


register(
    Exercise(
        id="4.2",
        function="numeric_jacobian",
        title="the Jacobian of any function by central differences",
        checks=(
            Check("is exact for linear functions", 1, _exact_on_linear),
            Check("is second-order accurate (central differences)", 2, _second_order),
            Check("gives the UR flange's position Jacobian (3 × 6)", 1, _on_the_arm),
        ),
    )
)


# ----------------------------------------------------------------------- 4.3 singularities


def _names(value, what: str) -> set[str]:
    if isinstance(value, str) or not hasattr(value, "__iter__"):
        raise Mismatch(
            f"{what} must return a set (or list) of names such as {{'wrist'}}; got {value!r:.80}"
        )
    names = {str(v).lower() for v in value}
    unknown = names - set(SINGULARITIES)
    if unknown:
        raise Mismatch(
            f"{what} returned unknown names {sorted(unknown)}; use "
            f"{', '.join(repr(s) for s in SINGULARITIES)}"
        )
    return names


def _on_family(arm, families, rng):
    """A configuration on exactly these singular families."""
    while True:
        q = random_q(rng)
        if "elbow" in families:
            q[2] = rng.choice([0.0, np.pi])
        if "wrist" in families:
            q[4] = rng.choice([0.0, np.pi])
        if "shoulder" in families:
            reach = arm.a2 * np.cos(q[1]) + arm.a3 * np.cos(q[1] + q[2])
            if abs(reach) > 0.9 * arm.d5:
                continue
            q[3] = np.arcsin(-reach / arm.d5) - q[1] - q[2]
        if set(_singularities(arm, q)) == set(families) and all(
            abs(np.sin(q[i])) > 0.05 for i, f in ((2, "elbow"), (4, "wrist")) if f not in families
        ):
            return q


def _diagnose(student, arm, q, expected: set[str], got: set[str]) -> str | None:
    """Name the likely mistake by asking the student's function about related configurations."""

    def flags(probe: np.ndarray, name: str) -> bool | None:
        try:
            return name in _names(student(arm, probe), "singularities(robot, q)")
        except Exception:  # a probe that fails tells us nothing
            return None

    for joint, name in ((2, "elbow"), (4, "wrist")):
        if (name in expected) == (name in got):
            continue
        label = f"q{joint + 1}"
        at = {}
        for value in (0.0, np.pi / 2, np.pi):
            probe = q.copy()
            probe[joint] = value
            at[value] = flags(probe, name)
        if at[np.pi / 2]:
            return f"the {name} tested with cos {label}: it is singular where sin {label} = 0"
        if at[0.0] and at[np.pi] is False:
            return f"the {name} is singular at {label} = ±π too, not only at 0: test sin {label}"
    if ("shoulder" in expected) != ("shoulder" in got):
        return "the shoulder factor is a2 cos q2 + a3 cos(q2+q3) + d5 sin(q2+q3+q4), in metres"
    return None


def _compare_names(student, arm, q, expected: set[str]):
    got = _names(student(arm, q.copy()), "singularities(robot, q)")
    if got == expected:
        return
    raise Mismatch(
        "det J = a2 a3 · sin q3 · sin q5 · (a2 cos q2 + a3 cos(q2+q3) + d5 sin(q2+q3+q4)): a "
        "family is present when its factor is zero",
        inputs={"robot": arm.name, "q": q},
        expected=sorted(expected) or "none",
        got=sorted(got) or "none",
        mistake=_diagnose(student, arm, q, expected, got),
    )


def _regular(student, rng):
    for _ in range(10):
        arm, q = random_arm(rng), random_q(rng)
        if _singularities(arm, q):
            continue
        q[2] = np.pi / 2  # cos q3 = 0: a classic wrong guess for the elbow
        _compare_names(student, arm, q, set(_singularities(arm, q)))


def _single_families(student, rng):
    for family in SINGULARITIES:
        for _ in range(4):
            arm = random_arm(rng)
            _compare_names(student, arm, _on_family(arm, (family,), rng), {family})


def _intersections(student, rng):
    for families in (
        ("shoulder", "elbow"),
        ("elbow", "wrist"),
        ("shoulder", "wrist"),
        ("shoulder", "elbow", "wrist"),
    ):
        arm = random_arm(rng)
        _compare_names(student, arm, _on_family(arm, families, rng), set(families))


register(
    Exercise(
        id="4.3",
        function="singularities",
        title="which singular families hold at q",
        checks=(
            Check("finds none at regular configurations", 1, _regular),
            Check("names the shoulder, elbow and wrist families", 2, _single_families),
            Check("names every family at their intersections", 1, _intersections),
        ),
        forbidden=(
            "urkin.kinematics.singularities",
            "urkin.kinematics.singular_families",
            "urkin.kinematics.singularity_factors",
            "urkin.kinematics.manipulability",
            "urkin.kinematics.condition_number",
        ),
    )
)
