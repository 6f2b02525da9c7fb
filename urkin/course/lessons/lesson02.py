"""Lesson 02 — Denavit–Hartenberg forward kinematics."""

from __future__ import annotations

import ast

import numpy as np

import urkin
from urkin.course import concepts
from urkin.course.compare import (
    Mismatch,
    as_array,
    close,
    compare,
    float32_helper,
    judged_like,
    require_transform,
    require_varying,
    tolerance,
)
from urkin.course.exercise import Check, Exercise, Lesson
from urkin.course.inputs import negated_a, random_arm, random_q
from urkin.course.seeds import SEED002_ARM, seed002_position
from urkin.course.symbolic_answer import Symbolic
from urkin.course.wire import Function, Opaque
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

# the earlier functions an answer may be built on, and arguments that show their dtype
_EARLIER = {
    "forward_kinematics": ("2.2", (urkin.robot("ur5"), np.array([0.3, -1.2, 1.1, -0.6, 0.8, 0.2]))),
    "dh_transform": ("2.1", (0.7, 0.1, 0.3, np.pi / 2)),
}


def _helper(sub, function):
    """The float32 earlier function ``function`` is built on (its answer is judged at float32's
    precision then), or None."""
    return float32_helper(sub, function, _EARLIER)


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
        "the joint angles shifted by one joint (q[i − 1] with link i, as np.roll(q, 1)): link "
        "i turns by q[i], numbered from 0 like the rows of the table": lambda: _fk(
            robot, np.roll(q, 1)
        ),
        "the joint angles shifted by one joint (q[i + 1] with link i): link i turns by q[i], "
        "numbered from 0 like the rows of the table": lambda: _fk(robot, np.roll(q, -1)),
    }


def _fk_is_transform(sub, rng):
    helper = _helper(sub, "forward_kinematics")
    answers = []
    for _ in range(5):
        robot, q = random_arm(rng), random_q(rng)
        inputs = {"robot": robot.name, "q": q}
        T = as_array(
            sub.forward_kinematics(robot, q), (4, 4), "forward_kinematics(robot, q)", inputs
        )
        require_transform(T, "forward_kinematics", inputs, helper)
        answers.append(T)
    require_varying(answers, "forward_kinematics", inputs)


def _fk_matches(sub, rng):
    helper = _helper(sub, "forward_kinematics")
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
            helper=helper,
        )


def _fk_accepts_lists(sub, rng):
    robot = random_arm(rng)
    q = random_q(rng)
    inputs = {"robot": robot.name, "q": f"the list {[round(float(x), 4) for x in q]}"}
    helper = _helper(sub, "forward_kinematics")
    like = None if helper is None else helper.sample
    expected = _fk(robot, q)
    got = as_array(
        sub.forward_kinematics(robot, q.tolist()),
        (4, 4),
        "forward_kinematics(robot, q) with q a list",
        inputs,
    )
    if close(got, expected, 1e-9, like):
        return
    # blamed on the list only where an array passes
    with_array = as_array(
        sub.forward_kinematics(robot, q.copy()),
        (4, 4),
        "forward_kinematics(robot, q)",
        {"robot": robot.name, "q": q},
    )
    if not close(with_array, expected, 1e-9, like):  # not a list's fault: say so, no point
        raise Mismatch(
            "the pose is wrong for an array of angles too (the checks above say why): this "
            "point is for the right pose from a list of six numbers as well",
            inputs=inputs,
            expected=expected,
            got=got,
        )
    compare(
        got,
        expected,
        what="q may be a list of six numbers, not only an array",
        inputs=inputs,
        helper=helper,
    )


def _fk_zero_pose(sub, rng):
    helper = _helper(sub, "forward_kinematics")
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
            helper=helper,
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


# ---------------------------------------------------------------------------- 2.4 symbolic_fk

_QUARTER_TURNS = (np.pi / 2, 0.0, -np.pi / 2, np.pi)


def _random_rows(rng, n):
    """A new arm: n rows (d, a, α) of metres and radians, most twists multiples of π/2."""
    return [
        (
            round(float(rng.uniform(-0.3, 0.3)), 4),
            round(float(rng.uniform(-0.5, 0.5)), 4),
            float(rng.choice([*_QUARTER_TURNS, round(float(rng.uniform(-3.0, 3.0)), 3)])),
        )
        for _ in range(n)
    ]


def _symbolic_answer(sub, rows, inputs) -> Symbolic:
    """The student's T_0_n as a symbolic 4×4 matrix in q1 … qn, or a Mismatch saying why not."""
    what = "symbolic_fk(rows)"
    got = sub.symbolic_fk([tuple(row) for row in rows])
    if isinstance(got, np.ndarray) or isinstance(got, (int, float)):
        raise Mismatch(
            f"{what} returned numbers ({np.shape(got)}), not a SymPy matrix in q1 … q{len(rows)}",
            inputs=inputs,
            mistake="the joint angles were replaced by numbers: keep them as SymPy symbols",
        )
    if not isinstance(got, Symbolic):
        shown = got if isinstance(got, Opaque) else type(got).__name__
        raise Mismatch(f"{what} returned {shown}, not a SymPy Matrix", inputs=inputs)
    if got.shape != (4, 4):
        raise Mismatch(
            f"{what} returned a SymPy {got!r}, not a 4×4 matrix",
            inputs=inputs,
            mistake=None if got.shape == () else "T_0_n is the whole 4×4 homogeneous transform",
        )
    names = [f"q{i}" for i in range(1, len(rows) + 1)]
    extra = sorted(got.symbols - set(names))
    if extra:
        zero_based = {f"q{i}" for i in range(len(rows))}
        raise Mismatch(
            f"{what} contains the symbol(s) {', '.join(extra)}; the joint angles are "
            f"{', '.join(names)} and nothing else is symbolic",
            inputs=inputs,
            mistake=(
                "joints are numbered from 1: q1 … qn, not q0 … q(n−1)"
                if set(extra) <= zero_based
                else "lengths or twists left as symbols: put the table's numbers in"
                if not any(e.startswith("q") for e in extra)
                else None
            ),
        )
    return got


def _evaluated(answer: Symbolic, q: np.ndarray) -> np.ndarray:
    """T(q) for each row of q, shape (K, 4, 4)."""
    values = {f"q{i + 1}": q[:, i] for i in range(q.shape[1])}
    return np.moveaxis(answer.evaluate(values), -1, 0)


def _symbolic_fk_hypotheses(rows, q):
    table = np.asarray(rows, dtype=float)
    flipped = table * np.array([1.0, 1.0, -1.0])
    return {
        "modified (Craig) DH link matrices with a standard-DH table": lambda: dh_chain(
            table, q, convention="modified"
        ),
        "the links multiplied in reverse order (T_(n−1)_n … T_0_1)": lambda: np.array(
            [_reverse_product(table, qk) for qk in q]
        ),
        "the twists α with the wrong sign (Rx(−α))": lambda: dh_chain(flipped, q),
        "d and a swapped in each row": lambda: dh_chain(table[:, [1, 0, 2]], q),
    }


def _reverse_product(table, q):
    T = np.eye(4)
    for link in dh_transform(q, table[:, 0], table[:, 1], table[:, 2])[::-1]:
        T = T @ link
    return T


def _symbolic_fk_tables(rng):
    yield [tuple(row) for row in urkin.robot("ur3").dh_table().tolist()]
    for n in (2, 3, int(rng.integers(4, 7))):
        rows = _random_rows(rng, n)
        if n == 3:  # one twist that is no multiple of π/2, whatever the draw
            d, a, _ = rows[-1]
            rows[-1] = (d, a, round(float(rng.uniform(0.2, 1.3)) * rng.choice([-1.0, 1.0]), 3))
        yield rows


def _symbolic_is_matrix(sub, rng):
    rows = [tuple(row) for row in urkin.robot("ur3").dh_table().tolist()]
    answer = _symbolic_answer(sub, rows, {"rows": "the UR3's table"})
    if not answer.symbols:
        raise Mismatch(
            "symbolic_fk(rows) for the UR3 does not depend on any joint angle",
            inputs={"rows": "the UR3's table"},
            mistake="the joint angles were replaced by numbers: keep them as SymPy symbols",
        )


def _symbolic_matches(sub, rng):
    for rows in _symbolic_fk_tables(rng):
        inputs = {"rows": np.asarray(rows)}
        answer = _symbolic_answer(sub, rows, inputs)
        q = rng.uniform(-np.pi, np.pi, (12, len(rows)))
        got = _evaluated(answer, q)
        inputs["q (12 random configurations, one per row)"] = q
        if np.iscomplexobj(got):
            raise Mismatch("symbolic_fk(rows) is complex at real joint angles", inputs=inputs)
        compare(
            got,
            dh_chain(np.asarray(rows), q),
            what="T_0_n(q) = T_0_1(q1) T_1_2(q2) … with Rz(q_i) Tz(d_i) Tx(a_i) Rx(α_i)",
            inputs=inputs,
            hypotheses=_symbolic_fk_hypotheses(rows, q),
        )


def _symbolic_exact_twists(sub, rng):
    rows = [(0.2, 0.0, np.pi / 2), (0.0, -0.4, 0.0), (0.1, 0.0, -np.pi / 2)]
    inputs = {"rows": np.asarray(rows)}
    answer = _symbolic_answer(sub, rows, inputs)
    residues = [x for x in answer.floats if 0.0 < abs(x) < 1e-12]
    if residues:
        raise Mismatch(
            f"the matrix for twists ±π/2 contains the number {residues[0]:.3g}, a "
            "floating-point cos(π/2): every term multiplied by it should not exist",
            inputs=inputs,
            mistake="twists typed as floats: turn a float multiple of π/2 into an exact one "
            "(sp.pi/2) before taking its cosine",
        )


# ------------------------------------------------------------------------- 2.5 upright_flange

_UPRIGHT = np.array([0.0, -np.pi / 2, 0.0, -np.pi / 2, 0.0, 0.0])


def _lengths(robot):
    return {
        "d1": robot.d1,
        "a2": robot.a2,
        "a3": robot.a3,
        "d4": robot.d4,
        "d5": robot.d5,
        "d6": robot.d6,
    }


def _upright_hypotheses(robot):
    d1, a2, a3, d4, d5, d6 = robot.lengths
    return {
        "a2 and a3 added with their signs: UR's are negative, and the arm points up": lambda: (
            np.array([0.0, -(d4 + d6), d1 + a2 + a3 + d5])
        ),
        "d5 subtracted: at this pose z4 points up, so d5 lifts the flange": lambda: np.array(
            [0.0, -(d4 + d6), d1 - a2 - a3 - d5]
        ),
        "the sideways offsets d4 and d6 along +y: at q1 = 0 they point along −y0": lambda: np.array(
            [0.0, d4 + d6, d1 - a2 - a3 + d5]
        ),
        "d6 along z: the flange faces sideways (along −y0) at this pose": lambda: np.array(
            [0.0, -d4, d1 - a2 - a3 + d5 + d6]
        ),
        "the position at q = 0 (the arm lying along −x), not standing up": lambda: np.array(
            [a2 + a3, -(d4 + d6), d1 - d5]
        ),
    }


def _upright_arms(rng):
    yield from (urkin.robot(name) for name in urkin.ROBOTS)
    for k in range(5):
        lengths = rng.uniform(
            [0.05, -0.7, -0.6, 0.05, 0.05, 0.04], [0.3, -0.1, -0.1, 0.2, 0.15, 0.12]
        )
        yield urkin.Robot(f"a new arm ({k + 1})", *np.round(lengths, 4))


def _upright_matches(sub, rng):
    for robot in _upright_arms(rng):
        inputs = {"robot": robot.name, **_lengths(robot)}
        got = as_array(sub.upright_flange(robot), (3,), "upright_flange(robot)", inputs)
        compare(
            got,
            _fk(robot, _UPRIGHT)[:3, 3],
            what="the flange of the arm standing straight up, q = (0, −π/2, 0, −π/2, 0, 0)",
            inputs=inputs,
            hypotheses=_upright_hypotheses(robot),
        )


def _upright_is_predicted(sub, rng):
    code = sub.code("upright_flange")
    chained = sorted({"dh_transform", "forward_kinematics", "ur5_position"} & set(code))
    products = sorted({p for source in code.values() for p in _products_in(source)})
    if chained or products:
        used = ", ".join([*(f"your {c}" for c in chained), *products])
        raise Mismatch(
            f"upright_flange uses {used}: the exercise asks you to predict the position from "
            "the lengths (sums of d's and a's), then verify it with forward kinematics",
            mistake="computed with forward kinematics instead of predicted from the lengths",
        )


# ---------------------------------------------------------------------------- 2.6 to_modified


def _tool(a, alpha):
    """Tx(a) Rx(α): what is left of the last standard row once a and α have moved down."""
    return dh_transform(0.0, 0.0, a, alpha)


def _down(column):
    """A column moved down one row, with 0 at the top: entry i holds entry i − 1."""
    return np.r_[0.0, column[:-1]]


def _up(column):
    """A column moved up one row, with 0 at the bottom: entry i holds entry i + 1."""
    return np.r_[column[1:], 0.0]


def _modified_right(rows):
    """The modified table (d_i, a_(i−1), α_(i−1)) with a_0 = α_0 = 0, and Tx(a_n) Rx(α_n)."""
    d, a, alpha = rows.T
    return np.column_stack([d, _down(a), _down(alpha)]), _tool(a[-1], alpha[-1])


def _table_hypotheses(rows):
    d, a, alpha = rows.T
    return {
        "rows copied unchanged: in the modified table row i holds a and α of row i − 1 "
        "(a_0 = α_0 = 0)": rows,
        "a and α shifted the wrong way (row i holds a_(i+1), α_(i+1)): they move down one "
        "row, to the next joint's transform": np.column_stack([d, _up(a), _up(alpha)]),
        "α shifted but not a: Tx(a_i) and Rx(α_i) move down together": np.column_stack(
            [d, a, _down(alpha)]
        ),
        "a shifted but not α: Tx(a_i) and Rx(α_i) move down together": np.column_stack(
            [d, _down(a), alpha]
        ),
        "d shifted too: d_i runs along z_(i−1), joint i's own axis, and stays in row i": (
            np.column_stack([_down(d), _down(a), _down(alpha)])
        ),
    }


def _tool_hypotheses(rows):
    _, a, alpha = rows.T
    return {
        "the tool transform forgotten (the identity): a_n and α_n of the last row are left "
        "over, T_tool = Tx(a_n) Rx(α_n)": np.eye(4),
        "T_tool = Rx(α_n) only: a_n of the last row is left over too": _tool(0.0, alpha[-1]),
        "T_tool = Tx(a_n) only: α_n of the last row is left over too": _tool(a[-1], 0.0),
        "T_tool inverted: it follows the modified chain, T_0_n = (modified chain) Tx(a_n) "
        "Rx(α_n)": np.linalg.inv(_tool(a[-1], alpha[-1])),
        "T_tool from the first row (a_1, α_1): what is left over is the last row's": _tool(
            a[0], alpha[0]
        ),
    }


def _same_table(got, expected) -> bool:
    """Equal to 1e-12, twists compared modulo 2π."""
    gap = np.asarray(got, dtype=float) - expected
    gap[:, 2] = (gap[:, 2] + np.pi) % (2 * np.pi) - np.pi
    return bool(np.abs(gap).max() <= tolerance(1e-12, got, 1.0))


def _modified_mistake(rows, table, tool) -> str | None:
    """The named mistakes the answer (table, tool) makes, joined, or None."""
    right_table, right_tool = _modified_right(rows)
    found = []
    if not _same_table(table, right_table):
        found += [
            name
            for name, h in _table_hypotheses(rows).items()
            if not _same_table(h, right_table) and _same_table(table, h)
        ][:1]
    if not close(tool, right_tool, 1e-12):
        found += [
            name
            for name, h in _tool_hypotheses(rows).items()
            if not close(h, right_tool, 1e-12) and close(tool, h, 1e-12)
        ][:1]
    return "; and ".join(found) or None


def _modified_answer(sub, rows, inputs) -> tuple[np.ndarray, np.ndarray]:
    """The student's (modified_rows, T_tool), checked for shape."""
    what = "to_modified(rows)"
    got = sub.to_modified(rows.copy())
    if not (isinstance(got, (tuple, list)) and len(got) == 2):
        raise Mismatch(
            f"{what} must return a pair (modified_rows, T_tool); got {type(got).__name__}"
            + (f" of length {len(got)}" if isinstance(got, (tuple, list)) else ""),
            inputs=inputs,
        )
    n = len(rows)
    table = as_array(got[0], (n, 3), f"{what}[0], the modified table,", inputs)
    tool = as_array(got[1], (4, 4), f"{what}[1], T_tool,", inputs)
    return table, tool


def _modified_tables(rng):
    """(name, rows): the seven UR arms, then random tables of 1 to 7 joints."""
    for name in urkin.ROBOTS:
        yield f"the {name}'s table", urkin.robot(name).dh_table()
    for n in (1, 2, 3, 5, 7, int(rng.integers(1, 8))):
        yield f"a new arm of {n} joint(s)", np.array(_random_rows(rng, n))


def _modified_chain(sub, rng):
    for name, rows in _modified_tables(rng):
        inputs = {"arm": name, "rows": rows}
        table, tool = _modified_answer(sub, rows, inputs)
        q = rng.uniform(-np.pi, np.pi, (8, len(rows)))
        got = dh_chain(table.astype(float), q, convention="modified") @ tool.astype(float)
        expected = dh_chain(rows, q)
        if not close(got, expected, 1e-12, like=table):
            raise Mismatch(
                "the modified chain times T_tool must equal the standard chain at every q: "
                "dh_chain(modified_rows, q, convention='modified') @ T_tool = dh_chain(rows, q) "
                "(to 1e-12); shown at the first of 8 random q",
                inputs={**inputs, "q": q[0]},
                expected=expected[0],
                got=got[0],
                mistake=_modified_mistake(rows, table, tool),
            )


def _modified_table(sub, rng):
    for name, rows in _modified_tables(rng):
        inputs = {"arm": name, "rows": rows}
        table, tool = _modified_answer(sub, rows, inputs)
        right, _ = _modified_right(rows)
        if not _same_table(table, right):
            raise Mismatch(
                "the modified table has rows (d_i, a_(i−1), α_(i−1)): d stays, a and α move "
                "down one row, with a_0 = α_0 = 0",
                inputs=inputs,
                expected=right,
                got=table,
                mistake=_modified_mistake(rows, table, tool),
            )


def _modified_tool(sub, rng):
    for name, rows in _modified_tables(rng):
        inputs = {"arm": name, "rows": rows}
        table, tool = _modified_answer(sub, rows, inputs)
        _, right = _modified_right(rows)
        if not close(tool, right, 1e-12):
            raise Mismatch(
                "T_tool = Tx(a_n) Rx(α_n), with a_n and α_n from the last row of the standard "
                "table (the identity when both are 0, as on UR arms)",
                inputs=inputs,
                expected=right,
                got=tool,
                mistake=_modified_mistake(rows, table, tool),
            )


# ---------------------------------------------------------------------------- 2.7 formula_gap


def _draw(n, seed):
    """The contract's configurations: np.random.default_rng(seed).uniform(-π, π, (n, 6))."""
    return np.random.default_rng(seed).uniform(-np.pi, np.pi, (n, 6))


def _flange(robot, q):
    """Flange positions for the rows of q (urkin.fk refuses angles in degrees; this does not)."""
    return dh_chain(robot.dh_table(), q)[:, :3, 3]


def _distances(formula, robot, q):
    """|formula(robot, q_k) − flange position| for every row q_k of q, metres."""
    p = np.array([formula(robot, q_k) for q_k in q], dtype=float)
    return np.linalg.norm(p - _flange(robot, q), axis=1)


def _worst(distances, q):
    k = int(np.argmax(distances))
    return float(distances[k]), q[k]


def _other_draws(n, seed):
    """Configurations a student may have tested instead of the stated draw, by mistake."""
    return {
        "angles drawn in degrees, uniform(−180, 180), and used as radians": (
            np.random.default_rng(seed).uniform(-180.0, 180.0, (n, 6))
        ),
        "the drawn angles converted with np.radians: they are radians already, and what is "
        "left is a few degrees around q = 0": np.radians(_draw(n, seed)),
        "a different random draw (the legacy np.random.seed and np.random.uniform): use "
        "np.random.default_rng(seed).uniform(-np.pi, np.pi, (n, 6))": (
            np.random.RandomState(seed).uniform(-np.pi, np.pi, (n, 6))
        ),
        "a different random draw (shape (6, n), transposed): use "
        "np.random.default_rng(seed).uniform(-np.pi, np.pi, (n, 6))": (
            np.random.default_rng(seed).uniform(-np.pi, np.pi, (6, n)).T
        ),
    }


def _smallest(distances, q):
    """The largest distance, and every configuration within 1e-12 of the smallest (round-off
    decides which of them an argmin picks)."""
    return float(distances.max()), q[distances <= distances.min() + 1e-12]


_ONLY_ZERO = "only q = 0 tested: the configurations are the n random ones of the stated draw"


def _gap_hypotheses(formula, robot, n, seed):
    """name ↦ a function giving (gap, q_worst) as the mistake computes them: q_worst is one
    configuration, or rows of which the mistake picks one, or None (any)."""
    q = _draw(n, seed)

    def coordinate_max():
        p = np.array([formula(robot, q_k) for q_k in q], dtype=float)
        per = np.abs(p - _flange(robot, q))
        k = int(np.argmax(per.max(axis=1)))
        return float(per[k].max()), q[k]

    hypotheses = {
        _ONLY_ZERO: lambda: _worst(_distances(formula, robot, np.zeros((1, 6))), np.zeros((1, 6))),
        "the mean distance instead of the largest": lambda: (
            float(_distances(formula, robot, q).mean()),
            None,
        ),
        "the configuration of the smallest distance (argmin) instead of the largest": lambda: (
            _smallest(_distances(formula, robot, q), q)
        ),
        "the largest single coordinate |Δx|, |Δy| or |Δz| instead of the Euclidean distance": (
            coordinate_max
        ),
    }
    for name, other in _other_draws(n, seed).items():
        hypotheses[name] = lambda other=other: _worst(_distances(formula, robot, other), other)
    return hypotheses


def _gap_answer(sub, formula, robot, n, seed, inputs):
    """The student's (gap, q_worst), checked for shape."""
    what = "formula_gap(formula, robot, n, seed)"
    got = sub.formula_gap(formula, robot) if n is None else sub.formula_gap(formula, robot, n, seed)
    if not (isinstance(got, (tuple, list)) and len(got) == 2):
        raise Mismatch(
            f"{what} must return a pair (gap, q_worst); got {type(got).__name__}"
            + (f" of length {len(got)}" if isinstance(got, (tuple, list)) else ""),
            inputs=inputs,
        )
    gap = as_array(got[0], (), f"{what}[0], the gap,", inputs)
    q_worst = as_array(got[1], (6,), f"{what}[1], q_worst,", inputs)
    return gap, q_worst


def _rows_like(q, q_worst):
    """Indices of the rows of q equal to q_worst (to 1e-12, or the answer's precision)."""
    return np.flatnonzero(np.abs(q - q_worst).max(axis=1) <= tolerance(1e-12, q_worst, np.pi))


def _draw_mistake(q_worst, n, seed) -> str:
    """Why q_worst is not a configuration of the stated draw, as well as can be told."""
    if not np.any(q_worst):
        return _ONLY_ZERO
    for name, other in _other_draws(n, seed).items():
        if len(_rows_like(other, q_worst)):
            return name
    return (
        "q_worst is not one of the drawn configurations: test at exactly the n configurations "
        "of np.random.default_rng(seed).uniform(-np.pi, np.pi, (n, 6)) (a fixed handful of "
        "poses, or another draw, cannot be reproduced or checked)"
    )


def _gap_cases(rng):
    """(robot, n, seed): the default n = 1000, seed = 0 (n None), then two random ones."""
    yield random_arm(rng), None, 0
    for _ in range(2):
        yield random_arm(rng), int(rng.integers(50, 400)), int(rng.integers(1, 10_000))


def _gap_inputs(formula_text, robot, n, seed):
    if n is None:
        n, seed = "1000 (the default)", "0 (the default)"
    return {"formula": formula_text, "robot": robot.name, "n": n, "seed": seed}


def _gap_like(sub, gap):
    """What a gap is as precise as (:func:`judged_like`), and the float32 forward kinematics it
    may be built on."""
    helper = _helper(sub, "formula_gap")
    return judged_like(gap, helper), helper


def _gap_right_formula(sub, rng):
    formula = Function("ur_position")
    for robot, n, seed in _gap_cases(rng):
        inputs = _gap_inputs("the right closed-form flange position", robot, n, seed)
        gap, q_worst = _gap_answer(sub, formula, robot, n, seed, inputs)
        like, helper = _gap_like(sub, gap)
        if not (0.0 <= gap <= tolerance(1e-12, like)):
            raise Mismatch(
                "a right formula is off by round-off only: the gap must be ≥ 0 and below 1e-12",
                inputs=inputs,
                got=gap,
                difference=f"gap {float(gap):.3g} m"
                + ("" if helper is None else f" ({helper.note})"),
            )
        n_drawn = 1000 if n is None else n
        if not len(_rows_like(_draw(n_drawn, seed), q_worst)):
            raise Mismatch(
                "q_worst must be one of the n configurations drawn by "
                "np.random.default_rng(seed).uniform(-np.pi, np.pi, (n, 6))",
                inputs=inputs,
                got=q_worst,
                mistake=_draw_mistake(q_worst, n_drawn, seed),
            )


def _judge_gap(sub, formula, formula_text, robot, n, seed):
    """The student's (gap, q_worst) must be the largest distance and where it occurs."""
    inputs = _gap_inputs(formula_text, robot, n, seed)
    gap, q_worst = _gap_answer(sub, formula, robot, n, seed, inputs)
    n_drawn, seed_drawn = (1000, 0) if n is None else (n, seed)
    q = _draw(n_drawn, seed_drawn)
    distances = _distances(formula, robot, q)
    right_gap, right_q = _worst(distances, q)
    like, helper = _gap_like(sub, gap)
    atol = tolerance(1e-12, like, right_gap)
    at = _rows_like(q, q_worst)
    gap_ok = abs(float(gap) - right_gap) <= atol
    q_ok = len(at) and distances[at].max() >= right_gap - atol
    if gap_ok and q_ok:
        return
    mistake = None
    for name, compute in _gap_hypotheses(formula, robot, n_drawn, seed_drawn).items():
        try:
            with np.errstate(all="ignore"):
                h_gap, h_q = compute()
        except Exception:  # a hypothesis that cannot be evaluated simply does not match
            continue
        same_gap = abs(float(gap) - h_gap) <= tolerance(1e-12, like, h_gap)
        same_q = h_q is None or len(_rows_like(np.atleast_2d(h_q), q_worst))
        is_right = abs(h_gap - right_gap) <= 1e-12 and (
            h_q is None or np.array_equal(np.atleast_2d(h_q), right_q[None])
        )
        if same_gap and same_q and not is_right:
            mistake = name
            break
    if mistake is None and not len(at):
        mistake = _draw_mistake(q_worst, n_drawn, seed_drawn)
    raise Mismatch(
        "(gap, q_worst): the largest Euclidean distance |formula(robot, q) − flange position| "
        "over the n configurations of np.random.default_rng(seed).uniform(-np.pi, np.pi, "
        "(n, 6)), and the configuration where it occurs (to 1e-12)",
        inputs=inputs,
        expected=np.r_[right_gap, right_q],
        got=np.r_[float(gap), q_worst],
        mistake=mistake,
        difference="shown as (gap, q1, …, q6)"
        + (f"; gap {right_gap:.15g} m expected, {float(gap):.15g} m got" if not gap_ok else "")
        + ("" if helper is None else f" ({helper.note})"),
    )


def _gap_seed002(sub, rng):
    published = Function("seed002_position", report_angles=True)
    _judge_gap(
        sub, published, "seed 002's published p (its own lengths and angles)", SEED002_ARM, None, 0
    )
    terms = Function("seed002_position")
    text = "seed 002's terms (d6·cos(q2+q3+q4) without sin q5) with the robot's lengths"
    for robot, n, seed in _gap_cases(rng):
        if n is not None:  # the default draw was judged on the published formula
            _judge_gap(sub, terms, text, robot, n, seed)


def _gap_folded(sub, rng):
    for robot, n, seed in _gap_cases(rng):
        joint = int(rng.integers(0, 5))
        formula = Function("folded_ur_position", joint=joint)
        text = (
            f"the right closed form, but with arctan(tan(q{joint + 1})) for q{joint + 1}: right "
            f"at q = 0 and wherever |q{joint + 1}| < π/2, turned by half a turn beyond"
        )
        _judge_gap(sub, formula, text, robot, n, seed)


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
            uses=("dh_transform",),
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
        Exercise(
            id="2.4",
            function="symbolic_fk",
            title="T_0_n of a new arm, derived in SymPy",
            checks=(
                Check(
                    "returns a 4×4 SymPy matrix in the joint angles q1 … qn",
                    1,
                    _symbolic_is_matrix,
                ),
                Check(
                    "equals the DH chain for the UR3 and new arms of 2 to 6 joints",
                    3,
                    _symbolic_matches,
                ),
                Check("twists that are multiples of π/2 are exact", 1, _symbolic_exact_twists),
            ),
            answer=(*concepts.DH_LINK, *concepts.FORWARD_KINEMATICS),
        ),
        Exercise(
            id="2.5",
            function="upright_flange",
            title="predict where the flange is with the arm standing up",
            checks=(
                Check(
                    "the flange position at q = (0, −π/2, 0, −π/2, 0, 0) for the seven UR arms "
                    "and new ones",
                    2,
                    _upright_matches,
                ),
                Check(
                    "predicted from the lengths: no forward kinematics, no matrix products",
                    1,
                    _upright_is_predicted,
                    reads_code=True,
                ),
            ),
            answer=concepts.FORWARD_KINEMATICS,
        ),
        Exercise(
            id="2.6",
            function="to_modified",
            title="a standard-DH table rewritten for the modified convention",
            checks=(
                Check(
                    "modified chain × T_tool = standard chain, for the UR arms and new arms of "
                    "1 to 7 joints at random q",
                    2,
                    _modified_chain,
                ),
                Check("the modified table (d_i, a_(i−1), α_(i−1))", 1, _modified_table),
                Check("the tool transform Tx(a_n) Rx(α_n)", 1, _modified_tool),
            ),
        ),
        Exercise(
            id="2.7",
            function="formula_gap",
            title="put a closed-form position to the test at random configurations",
            checks=(
                Check(
                    "a right formula: gap below 1e-12, q_worst one of the drawn configurations",
                    1,
                    _gap_right_formula,
                ),
                Check(
                    "seed 002's formula: the exact largest distance and where it occurs",
                    2,
                    _gap_seed002,
                ),
                Check(
                    "a formula right at and near q = 0 but wrong elsewhere is caught",
                    1,
                    _gap_folded,
                ),
            ),
            uses=("forward_kinematics", "dh_transform"),
        ),
    ),
)
