"""Lesson 02 — DH forward kinematics."""

from __future__ import annotations

import numpy as np

import urkin
from urkin.exercises.framework import (
    Check,
    Exercise,
    as_array,
    compare,
    register,
    require_transform,
)
from urkin.exercises.inputs import negated_a, random_arm, random_q
from urkin.kinematics import dh_chain, dh_transform
from urkin.seeds import seed002_position

_fk = urkin.fk  # the reference, bound before any grading guard is installed

# What an exercise may not call: urkin's own answer to it, under any of its names.
_FK_FUNCTIONS = (
    "urkin.kinematics.fk",
    "urkin.kinematics.fk_frames",
    "urkin.kinematics.dh_chain",
    "urkin._generated.ur_kinematics.t06_one",
    "urkin._generated.ur_kinematics.t06_many",
    "urkin._generated.ur_kinematics.frames_one",
    "urkin._generated.ur_kinematics.frames_many",
)


# --------------------------------------------------------------------------- 2.1 dh_transform


def _link(rng):
    return (
        rng.uniform(-np.pi, np.pi),
        rng.uniform(-0.3, 0.3),
        rng.uniform(-0.7, 0.7),
        float(rng.choice([np.pi / 2, 0.0, -np.pi / 2, rng.uniform(-np.pi, np.pi)])),
    )


def _dh_is_transform(student, rng):
    for _ in range(10):
        theta, d, a, alpha = _link(rng)
        T = as_array(student(theta, d, a, alpha), (4, 4), "dh_transform(theta, d, a, alpha)")
        require_transform(T, "dh_transform", {"theta": theta, "d": d, "a": a, "alpha": alpha})


def _transpose_rotation(T):
    out = T.copy()
    out[:3, :3] = T[:3, :3].T
    return out


def _dh_matches(student, rng):
    for _ in range(20):
        theta, d, a, alpha = _link(rng)
        got = as_array(student(theta, d, a, alpha), (4, 4), "dh_transform(theta, d, a, alpha)")
        expected = dh_transform(theta, d, a, alpha)
        compare(
            got,
            expected,
            what="standard DH: T = Rz(θ) Tz(d) Tx(a) Rx(α)",
            inputs={"theta": theta, "d": d, "a": a, "alpha": alpha},
            hypotheses=_dh_hypotheses(theta, d, a, alpha),
        )


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


register(
    Exercise(
        id="2.1",
        function="dh_transform",
        title="one standard-DH link transform",
        checks=(
            Check("returns a homogeneous transform", 1, _dh_is_transform),
            Check("matches Rz(θ) Tz(d) Tx(a) Rx(α) on random links", 3, _dh_matches),
        ),
        forbidden=("urkin.kinematics.dh_transform", "urkin.kinematics.dh_chain"),
    )
)


# ---------------------------------------------------------------------- 2.2 forward_kinematics


def _reversed_chain(robot, q):
    links = dh_transform(q, robot.d, robot.a, robot.alpha)
    T = np.eye(4)
    for link in links[::-1]:
        T = T @ link
    return T


def _fk_is_transform(student, rng):
    for _ in range(5):
        robot, q = random_arm(rng), random_q(rng)
        T = as_array(student(robot, q.copy()), (4, 4), "forward_kinematics(robot, q)")
        require_transform(T, "forward_kinematics", {"robot": robot.name, "q": q})


def _fk_matches(student, rng):
    for _ in range(20):
        robot, q = random_arm(rng), random_q(rng)
        got = as_array(student(robot, q.copy()), (4, 4), "forward_kinematics(robot, q)")
        compare(
            got,
            _fk(robot, q),
            what="T_0_6 = T_0_1 T_1_2 … T_5_6 with the robot's standard-DH table",
            inputs={"robot": robot.name, "q": q},
            hypotheses=_fk_hypotheses(robot, q),
        )


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


def _fk_zero_pose(student, rng):
    for name in urkin.ROBOTS:
        robot = urkin.robot(name)
        got = as_array(student(robot, np.zeros(6)), (4, 4), "forward_kinematics(robot, 0)")
        compare(
            got[:3, 3],
            _fk(robot, np.zeros(6))[:3, 3],
            what="at q = 0 the arm lies along −x: p = (a2 + a3, −d4 − d6, d1 − d5)",
            inputs={"robot": name, "q": np.zeros(6)},
            hypotheses={
                label: (lambda h=h: h()[:3, 3])
                for label, h in _fk_hypotheses(robot, np.zeros(6)).items()
            },
        )


register(
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
            Check("matches the DH chain for random arms and configurations", 3, _fk_matches),
        ),
        forbidden=_FK_FUNCTIONS,
        builds_on=("2.1",),
    )
)


# --------------------------------------------------------------------------- 2.3 ur5_position

_UR5 = urkin.robot("ur5")


def _seed002_position(q):
    """Seed 002's published p for UR angles and the UR5's lengths: the d6·c234 terms lack s5.

    Its formula holds in either sign convention: negating a2 and a3 absorbs the half turns
    between the report's angles and UR's.
    """
    return np.array(seed002_position(q, _UR5.lengths))


def _position_matches(student, rng):
    for _ in range(20):
        q = random_q(rng)
        got = as_array(student(q.copy()), (3,), "ur5_position(q)")
        compare(
            got,
            _fk(_UR5, q)[:3, 3],
            what="p is the last column of T_0_6 for the UR5",
            inputs={"q": q},
            hypotheses=_position_hypotheses(q),
        )


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


def _position_where_seed002_is_blind(student, rng):
    # q2 + q3 + q4 = 90° makes cos(q2+q3+q4) = 0: the seed's own test pose, where its error hides
    for _ in range(5):
        q = random_q(rng)
        q[3] = np.pi / 2 - q[1] - q[2]
        got = as_array(student(q.copy()), (3,), "ur5_position(q)")
        compare(
            got, _fk(_UR5, q)[:3, 3], what="p at a pose with q2 + q3 + q4 = 90°", inputs={"q": q}
        )


register(
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
            Check("matches the UR5 flange position for random q", 3, _position_matches),
        ),
        forbidden=(
            *_FK_FUNCTIONS,
            "urkin.kinematics.dh_transform",
            "urkin.symbolic.ur_t06",
            "urkin.symbolic.ur_frames",
        ),
    )
)
