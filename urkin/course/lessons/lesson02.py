"""Lesson 02 — Denavit–Hartenberg forward kinematics."""

from __future__ import annotations

import ast

import numpy as np

import urkin
from urkin.course import concepts
from urkin.course.compare import (
    Mismatch,
    as_array,
    compare,
    require_transform,
    require_varying,
)
from urkin.course.exercise import Check, Exercise, Lesson
from urkin.course.inputs import negated_a, random_arm, random_q
from urkin.course.seeds import seed002_position
from urkin.kinematics import dh_chain, dh_transform

_fk = urkin.fk

# --------------------------------------------------------------------------- 2.1 dh_transform


def _link(rng):
    return (
        rng.uniform(-np.pi, np.pi),
        rng.uniform(-0.3, 0.3),
        rng.uniform(-0.7, 0.7),
        float(rng.choice([np.pi / 2, 0.0, -np.pi / 2, rng.uniform(-np.pi, np.pi)])),
    )


def _link_inputs(theta, d, a, alpha):
    return {"theta": theta, "d": d, "a": a, "alpha": alpha}


def _dh_is_transform(sub, rng):
    answers = []
    for _ in range(10):
        link = _link(rng)
        inputs = _link_inputs(*link)
        T = as_array(sub.dh_transform(*link), (4, 4), "dh_transform(theta, d, a, alpha)", inputs)
        require_transform(T, "dh_transform", inputs)
        answers.append(T)
    require_varying(answers, "dh_transform", inputs)


def _transpose_rotation(T):
    out = T.copy()
    out[:3, :3] = T[:3, :3].T
    return out


def _dh_hypotheses(theta, d, a, alpha):
    return {
        "modified (Craig) DH, Rx(α) Tx(a) Rz(θ) Tz(d), instead of standard DH": lambda: (
            dh_transform(theta, d, a, alpha, convention="modified")
        ),
        "θ and α treated as degrees": lambda: dh_transform(
            np.radians(theta), d, a, np.radians(alpha)
        ),
        "the rotation block is transposed": lambda: _transpose_rotation(
            dh_transform(theta, d, a, alpha)
        ),
    }


def _dh_matches(sub, rng):
    for _ in range(20):
        link = _link(rng)
        inputs = _link_inputs(*link)
        got = as_array(sub.dh_transform(*link), (4, 4), "dh_transform(theta, d, a, alpha)", inputs)
        compare(
            got,
            dh_transform(*link),
            what="standard DH: T = Rz(θ) Tz(d) Tx(a) Rx(α)",
            inputs=inputs,
            hypotheses=_dh_hypotheses(*link),
        )


# ---------------------------------------------------------------------- 2.2 forward_kinematics


def _reversed_chain(robot, q):
    T = np.eye(4)
    for link in dh_transform(q, robot.d, robot.a, robot.alpha)[::-1]:
        T = T @ link
    return T


def _fk_hypotheses(robot, q):
    return {
        "a2 and a3 with the wrong sign (UR publishes them negative)": lambda: _fk(
            negated_a(robot), q
        ),
        "modified DH link transforms with the standard-DH table": lambda: dh_chain(
            robot.dh_table(), q, convention="modified"
        ),
        "q treated as degrees": lambda: _fk(robot, np.radians(q)),
        "the links multiplied in reverse order (T_5_6 … T_0_1)": lambda: _reversed_chain(robot, q),
    }


def _fk_is_transform(sub, rng):
    answers = []
    for _ in range(5):
        robot, q = random_arm(rng), random_q(rng)
        inputs = {"robot": robot.name, "q": q}
        T = as_array(
            sub.forward_kinematics(robot, q), (4, 4), "forward_kinematics(robot, q)", inputs
        )
        require_transform(T, "forward_kinematics", inputs)
        answers.append(T)
    require_varying(answers, "forward_kinematics", inputs)


def _fk_matches(sub, rng):
    for _ in range(20):
        robot, q = random_arm(rng), random_q(rng)
        inputs = {"robot": robot.name, "q": q}
        got = as_array(
            sub.forward_kinematics(robot, q), (4, 4), "forward_kinematics(robot, q)", inputs
        )
        compare(
            got,
            _fk(robot, q),
            what="T_0_6 = T_0_1 T_1_2 … T_5_6 with the robot's standard-DH table",
            inputs=inputs,
            hypotheses=_fk_hypotheses(robot, q),
        )


def _fk_accepts_lists(sub, rng):
    robot = random_arm(rng)
    q = random_q(rng)
    inputs = {"robot": robot.name, "q": f"the list {[round(float(x), 4) for x in q]}"}
    got = as_array(
        sub.forward_kinematics(robot, q.tolist()),
        (4, 4),
        "forward_kinematics(robot, q) with q a list",
        inputs,
    )
    compare(
        got, _fk(robot, q), what="q may be a list of six numbers, not only an array", inputs=inputs
    )


def _fk_zero_pose(sub, rng):
    for name in urkin.ROBOTS:
        robot = urkin.robot(name)
        inputs = {"robot": name, "q": np.zeros(6)}
        got = as_array(
            sub.forward_kinematics(robot, np.zeros(6)),
            (4, 4),
            "forward_kinematics(robot, 0)",
            inputs,
        )
        compare(
            got[:3, 3],
            _fk(robot, np.zeros(6))[:3, 3],
            what="at q = 0 the arm lies along −x: p = (a2 + a3, −d4 − d6, d1 − d5)",
            inputs=inputs,
            hypotheses={
                label: (lambda h=h: h()[:3, 3])
                for label, h in _fk_hypotheses(robot, np.zeros(6)).items()
            },
        )


# --------------------------------------------------------------------------- 2.3 ur5_position

_UR5 = urkin.robot("ur5")


def _seed002_position(q):
    """Seed 002's published p for UR angles and the UR5's lengths: the d6·c234 terms lack s5.

    Its formula holds in either sign convention: negating a2 and a3 absorbs the half turns
    between the report's angles and UR's.
    """
    return np.array(seed002_position(q, _UR5.lengths))


def _position_hypotheses(q):
    return {
        "seed 002's formula: its d6·cos(q2+q3+q4) terms lack the factor sin q5": lambda: (
            _seed002_position(q)
        ),
        "a2 and a3 with the wrong sign (UR publishes them negative)": lambda: _fk(
            negated_a(_UR5), q
        )[:3, 3],
        "q treated as degrees": lambda: _fk(_UR5, np.radians(q))[:3, 3],
    }


def _position_matches(sub, rng):
    for _ in range(20):
        q = random_q(rng)
        inputs = {"q": q}
        got = as_array(sub.ur5_position(q), (3,), "ur5_position(q)", inputs)
        compare(
            got,
            _fk(_UR5, q)[:3, 3],
            what="p is the last column of T_0_6 for the UR5",
            inputs=inputs,
            hypotheses=_position_hypotheses(q),
        )


def _position_where_seed002_is_blind(sub, rng):
    # q2 + q3 + q4 = 90° makes cos(q2+q3+q4) = 0: the seed's own test pose, where its error hides
    for _ in range(5):
        q = random_q(rng)
        q[3] = np.pi / 2 - q[1] - q[2]
        got = as_array(sub.ur5_position(q), (3,), "ur5_position(q)", {"q": q})
        compare(
            got, _fk(_UR5, q)[:3, 3], what="p at a pose with q2 + q3 + q4 = 90°", inputs={"q": q}
        )


_MATRIX_PRODUCTS = {"dot", "matmul", "multi_dot", "einsum"}


def _products_in(source: str) -> list[str]:
    """What in ``source`` multiplies matrices: ``@``, ``np.dot``, ``np.matmul``, …"""
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, (ast.BinOp, ast.AugAssign)) and isinstance(node.op, ast.MatMult):
            found.append("the @ operator")
        elif isinstance(node, ast.Call):
            name = node.func.attr if isinstance(node.func, ast.Attribute) else None
            name = node.func.id if isinstance(node.func, ast.Name) else name
            if name in _MATRIX_PRODUCTS:
                found.append(f"{name}()")
    return found


def _position_is_closed_form(sub, rng):
    code = sub.code("ur5_position")
    chained = sorted({"dh_transform", "forward_kinematics"} & set(code))
    if chained:
        raise Mismatch(
            f"ur5_position calls your {' and '.join(chained)}: the exercise asks for the closed "
            "form p(q), read off the SymPy derivation, not a product of link transforms",
            mistake="a product of DH matrices instead of the closed-form formula",
        )
    for name, source in code.items():
        products = _products_in(source)
        if products:
            raise Mismatch(
                f"{name} multiplies matrices ({', '.join(sorted(set(products)))}): the closed "
                "form needs only sines, cosines, sums and products of numbers",
                mistake="a product of DH matrices instead of the closed-form formula",
            )


LESSON = Lesson(
    number="02",
    title="Denavit–Hartenberg forward kinematics",
    summary="Denavit–Hartenberg forward kinematics: standard vs modified DH, the SymPy "
    "derivation, seven arms, a published formula's hidden error",
    exercises=(
        Exercise(
            id="2.1",
            function="dh_transform",
            title="one standard-DH link transform",
            checks=(
                Check("returns a homogeneous transform", 1, _dh_is_transform),
                Check("matches Rz(θ) Tz(d) Tx(a) Rx(α) on random links", 3, _dh_matches),
            ),
            answer=concepts.DH_LINK,
        ),
        Exercise(
            id="2.2",
            function="forward_kinematics",
            title="the UR forward kinematics T_0_6(q)",
            checks=(
                Check("returns a homogeneous transform", 1, _fk_is_transform),
                Check(
                    "puts the flange where UR's tables say at q = 0, for all seven arms",
                    1,
                    _fk_zero_pose,
                ),
                Check("matches the DH chain for random arms and configurations", 2, _fk_matches),
                Check("accepts q as a list", 1, _fk_accepts_lists),
            ),
            answer=concepts.FORWARD_KINEMATICS,
            builds_on=("2.1",),
        ),
        Exercise(
            id="2.3",
            function="ur5_position",
            title="the closed-form UR5 flange position",
            checks=(
                Check(
                    "right where cos(q2+q3+q4) = 0 (seed 002's test pose)",
                    1,
                    _position_where_seed002_is_blind,
                ),
                Check("matches the UR5 flange position for random q", 2, _position_matches),
                Check(
                    "is a closed form: no matrix products",
                    1,
                    _position_is_closed_form,
                    reads_code=True,
                ),
            ),
            answer=(*concepts.FORWARD_KINEMATICS, dh_transform),
        ),
    ),
)
