"""Lesson 01 — rigid-body transforms."""

from __future__ import annotations

import ast
import itertools
import re

import numpy as np

from urkin.course import concepts
from urkin.course.compare import (
    Mismatch,
    as_array,
    close,
    compare,
    identify_mistake,
    require_rotation,
    require_transform,
)
from urkin.course.display import below
from urkin.course.exercise import Check, Exercise, Lesson
from urkin.course.inputs import random_pose, random_rotation
from urkin.course.submission import StudentRaised
from urkin.transforms import (
    inv_transform,
    make_transform,
    pose_error,
    rot_x,
    rot_y,
    rot_z,
    rotation_angle,
    rotation_to_rpy,
    rpy_to_rotation,
    skew,
    so3_exp,
    so3_log,
    wrap_angles,
)


def _in_dtype(value, like):
    """``value`` in the floating dtype of the student's answer ``like`` (so that :func:`close`
    judges a float32 answer at float32's precision)."""
    dtype = like.dtype if np.issubdtype(like.dtype, np.floating) else np.float64
    return np.asarray(value, dtype=np.float64).astype(dtype)


def _named(exc: Mismatch, got, hypotheses) -> Mismatch:
    """``exc`` with the likely mistake named, when one of ``hypotheses`` reproduces ``got``."""
    if exc.mistake is None:
        exc.mistake = identify_mistake(got, hypotheses)
    return exc


def _matrix(value, shape, what, inputs, wrong_shapes):
    """The student's answer as an array of ``shape``; a known wrong shape names its mistake."""
    try:
        return as_array(value, shape, what, inputs)
    except Mismatch as exc:
        try:
            got_shape = np.shape(value)
        except Exception:  # a ragged answer: no shape to read a mistake from
            raise exc from None
        exc.mistake = exc.mistake or wrong_shapes.get(got_shape)
        raise


# ------------------------------------------------------------------------------ 1.1 rot_z


def _rot_z_hypotheses(theta):
    c, s = np.cos(theta), np.sin(theta)
    return {
        "transposed: the sin θ entries have swapped signs (that is Rz(−θ))": lambda: rot_z(-theta),
        "θ treated as degrees": lambda: rot_z(np.radians(theta)),
        "θ converted to degrees before cos and sin (they take radians)": lambda: rot_z(
            np.degrees(theta)
        ),
        "rotation about x instead of z": lambda: rot_x(theta),
        "rotation about y instead of z": lambda: rot_y(theta),
        "both sin θ entries have the same sign: [[c, s], [s, c]] is not a rotation": lambda: (
            np.array([[c, s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
        ),
        "both sin θ entries are negative: [[c, −s], [−s, c]] is not a rotation": lambda: np.array(
            [[c, -s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]
        ),
        "sin and cos swapped": lambda: np.array([[s, -c, 0.0], [c, s, 0.0], [0.0, 0.0, 1.0]]),
        "the bottom-right entry must be 1: a turn about z leaves z where it is": lambda: np.array(
            [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 0.0]]
        ),
        "returned the identity: θ is not used": lambda: np.eye(3),
    }


_ROT_Z_SHAPES = {
    (2, 2): "a 2×2 plane rotation: Rz is 3×3, with a 1 for the z axis",
    (4, 4): "a 4×4 homogeneous transform: rot_z returns the 3×3 rotation",
}


def _rot_z_angles(rng):
    """Eight angles in (−π, π) and two beyond ±π (up to ±8 rad): any angle is allowed."""
    return [rng.uniform(-np.pi, np.pi) for _ in range(8)] + [
        rng.choice([-1.0, 1.0]) * rng.uniform(np.pi, 8.0) for _ in range(2)
    ]


def _rot_z_call(sub, theta):
    inputs = {"theta": theta}
    R = _matrix(sub.rot_z(theta), (3, 3), "rot_z(theta)", inputs, _ROT_Z_SHAPES)
    return R, inputs


def _rot_z_is_rotation_by_theta(sub, rng):
    for theta in _rot_z_angles(rng):
        R, inputs = _rot_z_call(sub, theta)
        hypotheses = _rot_z_hypotheses(theta)
        try:
            require_rotation(R, "rot_z(theta)", inputs)
            compare(
                np.trace(R),
                1 + 2 * np.cos(theta),
                what="a rotation by θ has trace 1 + 2 cos θ",
                inputs=inputs,
            )
        except Mismatch as exc:
            raise _named(exc, R, hypotheses) from None


def _rot_z_matches(sub, rng):
    for theta in _rot_z_angles(rng):
        R, inputs = _rot_z_call(sub, theta)
        compare(
            R,
            rot_z(theta),
            what="Rz(θ) = [[cos θ, −sin θ, 0], [sin θ, cos θ, 0], [0, 0, 1]]",
            inputs=inputs,
            hypotheses=_rot_z_hypotheses(theta),
        )


# -------------------------------------------------------------------- 1.2 transform_inverse


def _inverse_hypotheses(T):
    R, p = T[:3, :3], T[:3, 3]

    def pose(rotation, translation, bottom=(0.0, 0.0, 0.0, 1.0)):
        out = make_transform(rotation, translation)
        out[3] = bottom
        return out

    translation_in_bottom_row = np.eye(4)
    translation_in_bottom_row[:3, :3] = R.T
    translation_in_bottom_row[3, :3] = -R.T @ p
    return {
        "the translation was not rotated: use −Rᵀp, not −p": lambda: pose(R.T, -p),
        "R was not transposed: the inverse rotation is Rᵀ": lambda: pose(R, -R @ p),
        "only the translation was negated: the inverse is [[Rᵀ, −Rᵀp], [0, 1]]": lambda: pose(
            R, -p
        ),
        "the translation used R, not Rᵀ: −Rᵀp (if you overwrote T's rotation block first, "
        "R = T[:3, :3] is a view and changed with it)": lambda: pose(R.T, -R @ p),
        "the minus sign is missing: the translation is −Rᵀp": lambda: pose(R.T, R.T @ p),
        "the whole 4×4 matrix was transposed: only the rotation block is": lambda: T.T,
        "the translation went into the bottom row instead of the last column": lambda: (
            translation_in_bottom_row
        ),
        "the bottom row must be [0, 0, 0, 1] (an array of zeros needs its 1)": lambda: pose(
            R.T, -R.T @ p, (0.0, 0.0, 0.0, 0.0)
        ),
        "returned T unchanged": lambda: T,
    }


_INVERSE_SHAPES = {
    (3, 3): "only the rotation block came back: the inverse is the whole 4×4 transform",
    (3, 4): "the bottom row [0, 0, 0, 1] is missing: the inverse is 4×4",
}


def _reciprocal_mistake(value, T):
    """Whether ``value`` is T's entries inverted one by one (1/T or T**-1 of an array)."""
    try:
        got = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return None
    if got.shape != (4, 4):
        return None
    nonzero = T != 0
    with np.errstate(all="ignore"):
        if np.allclose(got[nonzero], 1.0 / T[nonzero], rtol=1e-6, atol=0.0):
            return (
                "the entries were inverted one by one (1/T or T**-1 of an array): the inverse "
                "of a matrix is not taken entry by entry"
            )
    return None


def _inverse_call(sub, T, watched=()):
    """The student's inverse of ``T`` as a (4, 4) array, its inputs, and which of the
    ``watched`` library functions (:meth:`~urkin.course.submission.Submission.spy`) it reached."""
    inputs = {"T": T}
    value, calls = sub.spy("transform_inverse", watched, T.copy())
    try:
        got = _matrix(value, (4, 4), "transform_inverse(T)", inputs, _INVERSE_SHAPES)
    except Mismatch as exc:
        exc.mistake = exc.mistake or _reciprocal_mistake(value, T)
        raise
    return got, inputs, sorted(name for name, made in calls.items() if made)


def _inverse_is_transform(sub, rng):
    for _ in range(5):
        T = random_pose(rng)
        got, inputs, _ = _inverse_call(sub, T)
        try:
            require_transform(got, "transform_inverse(T)", inputs)
            compare(
                got[:3, :3],
                T[:3, :3].T,
                what="the rotation block of the inverse is Rᵀ",
                inputs=inputs,
            )
        except Mismatch as exc:
            raise _named(exc, got, _inverse_hypotheses(T)) from None


def _inverse_composes_to_identity(sub, rng):
    for _ in range(10):
        T = random_pose(rng)
        T[:3, 3] *= rng.uniform(0.5, 3.0)  # translations up to a few metres
        got, inputs, _ = _inverse_call(sub, T)
        compare(
            got,
            inv_transform(T),
            what="T @ transform_inverse(T) must be the identity: the inverse is "
            "[[Rᵀ, −Rᵀp], [0, 1]]",
            inputs=inputs,
            hypotheses=_inverse_hypotheses(T),
        )


_GENERAL_INVERSES = {"inv", "pinv", "solve", "lstsq", "tensorinv", "tensorsolve"}
_GENERAL_INVERSE = "a general matrix inverse (np.linalg.inv or alike), not the transpose formula"
#: numpy's general inverses, watched while the student's function runs.
_GENERAL_INVERSE_CODE = tuple(
    f"numpy.linalg.{name}" for name in (*sorted(_GENERAL_INVERSES), "matrix_power")
)


def _is_negative_constant(node):
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
        node = node.operand
        return isinstance(node, ast.Constant) and isinstance(node.value, (int, float))
    return (
        isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and node.value < 0
    )


def _general_inverses_in(source: str, own: set[str]) -> list[str]:
    """What in ``source`` inverts a matrix in general: np.linalg.inv, pinv, solve, ``**-1``,
    a numpy matrix's ``.I``, matrix_power(…, −1).  Names of the student's own functions
    (``own``) do not count."""
    try:
        tree = ast.parse(source)
    except SyntaxError:
        return []
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            name = node.func.attr if isinstance(node.func, ast.Attribute) else None
            name = node.func.id if isinstance(node.func, ast.Name) else name
            if name in _GENERAL_INVERSES and name not in own:
                found.append(f"{ast.unparse(node.func)}()")
            elif name == "matrix_power" and any(_is_negative_constant(a) for a in node.args[1:]):
                found.append("matrix_power(…, −1)")
        elif isinstance(node, ast.Attribute) and node.attr == "I":
            found.append("a numpy matrix's .I")
        elif (
            isinstance(node, ast.BinOp)
            and isinstance(node.op, ast.Pow)
            and _is_negative_constant(node.right)
            and not isinstance(node.left, ast.Constant)
        ):
            found.append("** −1")
    return found


def _non_rigid_probe(rng):
    """A 4×4 [[A, p], [0, 1]] whose A is far from orthonormal: its general inverse differs
    from the transpose formula [[Aᵀ, −Aᵀp], [0, 1]]."""
    A = random_rotation(rng) @ np.diag(rng.uniform(1.5, 2.5, 3))
    return make_transform(A, rng.uniform(-1.0, 1.0, 3))


def _nearly_rigid_probe(rng):
    """A rigid transform whose rotation is moved 2e-7 from orthonormal (max |RᵀR − I|), as a
    pose typed with seven decimals is."""
    R = random_rotation(rng)
    E = rng.normal(size=(3, 3))
    E = E + E.T
    R = R @ (np.eye(3) + 1e-7 * E / np.abs(E).max())  # RᵀR − I ≈ 2e-7 E / max|E|
    return make_transform(R, rng.uniform(-1.0, 1.0, 3))


def _is_numeric(value) -> bool:
    try:
        np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return False
    return True


def _inverse_is_structured(sub, rng):
    T = random_pose(rng)
    got, inputs, seen = _inverse_call(sub, T, _GENERAL_INVERSE_CODE)
    compare(
        got,
        inv_transform(T),
        what="the transpose formula [[Rᵀ, −Rᵀp], [0, 1]] (this point needs a right inverse first)",
        inputs=inputs,
        hypotheses=_inverse_hypotheses(T),
    )
    code = sub.code("transform_inverse")
    for name, source in code.items():
        found = _general_inverses_in(source, set(code))
        if found:
            raise Mismatch(
                f"{name} inverts a matrix in general ({', '.join(sorted(set(found)))}): the "
                "exercise asks for the transpose formula [[Rᵀ, −Rᵀp], [0, 1]], no general inverse",
                inputs={},
                mistake=_GENERAL_INVERSE,
            )
    # and while it ran: a general inverse named by a string built at run time is not in the code
    used = [f"np.linalg.{name.rpartition('.')[2]}()" for name in seen]
    if used:
        raise Mismatch(
            f"transform_inverse inverts a matrix in general ({', '.join(used)}, seen while it "
            "ran): the exercise asks for the transpose formula [[Rᵀ, −Rᵀp], [0, 1]], no general "
            "inverse",
            inputs={"T": T},
            mistake=_GENERAL_INVERSE,
        )
    # A transform 2e-7 from orthonormal, within the 1e-6 the course's checks accept as rigid (a
    # pose typed with seven decimals): the transpose formula and a general inverse differ there
    # by about that much, so a general inverse shows however it was reached, and refusing it
    # refuses a transform the course calls rigid.
    nearly = _nearly_rigid_probe(rng)
    try:
        value = sub.transform_inverse(nearly.copy())
    except StudentRaised as exc:
        if exc.kind == "ForbiddenCallError":
            raise
        raise Mismatch(
            f"transform_inverse raised {exc.kind} for a transform whose rotation is 2e-7 from "
            "orthonormal, within the 1e-6 the course's checks accept as rigid (a pose typed with "
            "seven decimals is one): invert it with the transpose formula",
            inputs={"T (2e-7 from rigid)": nearly},
        ) from None
    answer = np.asarray(value, dtype=float) if _is_numeric(value) else None
    if answer is not None and answer.shape == (4, 4):
        R, p = nearly[:3, :3], nearly[:3, 3]
        formula = make_transform(R.T, -R.T @ p)
        if not close(answer, formula, 1e-9) and close(answer, np.linalg.inv(nearly), 1e-9):
            raise Mismatch(
                "given a transform whose rotation is 2e-7 from orthonormal, transform_inverse "
                "returned its general inverse (which differs from the transpose formula by about "
                "that much): the exercise asks for the formula, no general inverse",
                inputs={"T (2e-7 from rigid)": nearly},
                expected=formula,
                got=answer,
                mistake=_GENERAL_INVERSE,
            )
    # A matrix that is not a rigid transform, outside the function's contract: any exception,
    # and any answer other than the general inverse, is fine.
    probe = _non_rigid_probe(rng)
    try:
        value = sub.transform_inverse(probe.copy())
    except StudentRaised as exc:
        if exc.kind == "ForbiddenCallError":
            raise
        return
    if not _is_numeric(value):
        return
    answer = np.asarray(value, dtype=float)
    general = np.linalg.inv(probe)
    if answer.shape == (4, 4) and close(answer, general, 1e-6):
        raise Mismatch(
            "given a 4×4 matrix whose block A is not a rotation, transform_inverse returned its "
            "general inverse A⁻¹; the transpose formula returns Aᵀ: the exercise asks for the "
            "formula, no general inverse",
            inputs={"T (not a rigid transform)": probe},
            expected=make_transform(probe[:3, :3].T, -probe[:3, :3].T @ probe[:3, 3]),
            got=answer,
            mistake=_GENERAL_INVERSE,
        )


# ---------------------------------------------------------------------- 1.3 rotation_to_rpy

_RPY_SHAPES = {
    (3, 3): "a 3×3 matrix came back: the answer is the three angles (roll, pitch, yaw)",
    (1, 3): "an array of shape (1, 3): return a flat array of the three angles",
    (3, 1): "an array of shape (3, 1): return a flat array of the three angles",
}


def _second_solution(rpy):
    roll, pitch, yaw = rpy
    return wrap_angles([roll + np.pi, np.pi - pitch, yaw + np.pi])


# one name wherever the checks see it, so that the summary names it once
_RPY_DEGREES = "returned degrees: seed 000's helper does, but angles are radians here"


def _rpy_hypotheses(R):
    rpy = rotation_to_rpy(R)
    return {
        _RPY_DEGREES: lambda: np.degrees(rpy),
        "returned (yaw, pitch, roll): the order is reversed": lambda: rpy[::-1],
        "the matrix was read transposed (R[i, j] for R[j, i])": lambda: rotation_to_rpy(R.T),
        "the angles of R = Rx(roll) Ry(pitch) Rz(yaw): the product is Rz(yaw) Ry(pitch) "
        "Rx(roll)": lambda: -rotation_to_rpy(R.T),
        "pitch has the wrong sign: r31 = −sin(pitch)": lambda: rpy * [1.0, -1.0, 1.0],
        "arctan(a / b) instead of atan2(a, b): it cannot tell the quadrant": lambda: np.array(
            [np.arctan(R[2, 1] / R[2, 2]), rpy[1], np.arctan(R[1, 0] / R[0, 0])]
        ),
        "the second solution (cos pitch < 0): pitch belongs in [−π/2, π/2]": lambda: (
            _second_solution(rpy)
        ),
        "roll and yaw wrapped into [0, 2π) instead of (−π, π]": lambda: [
            np.mod(rpy[0], 2 * np.pi),
            rpy[1],
            np.mod(rpy[2], 2 * np.pi),
        ],
        "angles wrapped into [0, 2π) instead of (−π, π] (pitch in [−π/2, π/2])": lambda: np.mod(
            rpy, 2 * np.pi
        ),
    }


def _rpy_diagnosis(got, expected):
    """Which of the three angles are wrong, when the hypotheses do not say."""
    difference = wrap_angles(np.asarray(got, dtype=float) - expected)
    names = ("roll", "pitch", "yaw")
    wrong = [n for n, d in zip(names, difference) if abs(d) > 1e-6]
    right = [n for n in names if n not in wrong]
    if not wrong or not right:
        return None
    if all(abs(abs(d) - np.pi) < 1e-6 for n, d in zip(names, difference) if n in wrong):
        return (
            f"{' and '.join(wrong)} off by π: arctan(a / b) cannot tell the quadrant, atan2(a, b) "
            "can"
        )
    return (
        f"{' and '.join(wrong)} wrong, {' and '.join(right)} right: check which entries of R "
        f"{'its formula reads' if len(wrong) == 1 else 'their formulas read'}"
    )


def _rpy_mistake(got, R):
    return identify_mistake(got, _rpy_hypotheses(R)) or _rpy_diagnosis(got, rotation_to_rpy(R))


def _rpy_call(sub, R, what="rotation_to_rpy(R)"):
    inputs = {"R": R}
    rpy = _matrix(sub.rotation_to_rpy(R.copy()), (3,), what, inputs, _RPY_SHAPES)
    return rpy, inputs


def _rotations(rng):
    """Rotations with roll and yaw in every quadrant, pitch of both signs, and random ones."""
    rotations = []
    for roll_quadrant in range(4):
        for yaw_quadrant in range(4):
            roll = -np.pi + (roll_quadrant + rng.uniform(0.05, 0.95)) * np.pi / 2
            yaw = -np.pi + (yaw_quadrant + rng.uniform(0.05, 0.95)) * np.pi / 2
            pitch = rng.choice([-1.0, 1.0]) * rng.uniform(0.05, 1.5)
            rotations.append(rpy_to_rotation([roll, pitch, yaw]))
    rotations += [random_rotation(rng) for _ in range(8)]
    order = rng.permutation(len(rotations))
    return [rotations[i] for i in order]


def _rebuilt(rpy):
    return _in_dtype(rpy_to_rotation(np.asarray(rpy, dtype=float)), rpy)


def _rpy_rebuilds_rotation(sub, rng):
    for R in _rotations(rng):
        rpy, inputs = _rpy_call(sub, R)
        if not close(_rebuilt(rpy), R, 1e-9):
            raise Mismatch(
                "Rz(yaw) @ Ry(pitch) @ Rx(roll) does not give R back",
                inputs=inputs,
                expected=rotation_to_rpy(R),
                got=rpy,
                mistake=_rpy_mistake(rpy, R),
            )


def _rpy_in_range(sub, rng):
    for R in _rotations(rng):
        rpy, inputs = _rpy_call(sub, R)
        expected = rotation_to_rpy(R)
        if not close(rpy, expected, 1e-9):
            raise Mismatch(
                "roll and yaw belong in (−π, π] and pitch in [−π/2, π/2], in radians: away "
                "from the gimbal lock, only one set of angles in those ranges rebuilds R",
                inputs=inputs,
                expected=expected,
                got=rpy,
                mistake=_rpy_mistake(rpy, R),
            )


def _locked_rotation(pitch_sign: float, roll: float, yaw: float) -> np.ndarray:
    """Rz(yaw) Ry(±π/2) Rx(roll) with its zeros exactly zero, as a hand-typed pose would be.

    (``rpy_to_rotation`` at ±π/2 leaves cos(π/2) = 6e-17 in place of those zeros, which lets
    formulas without a gimbal-lock branch get lucky.)
    """
    if pitch_sign > 0:
        s, c = np.sin(roll - yaw), np.cos(roll - yaw)
        return np.array([[0.0, s, c], [0.0, c, -s], [-1.0, 0.0, 0.0]])
    s, c = np.sin(roll + yaw), np.cos(roll + yaw)
    return np.array([[0.0, -s, -c], [0.0, c, -s], [1.0, 0.0, 0.0]])


def _locked_hypotheses(R):
    pitch = np.pi / 2 if R[2, 0] < 0 else -np.pi / 2
    turn = np.arctan2(-R[1, 2], R[1, 1])  # r − y at +90°, r + y at −90°
    into_yaw = -turn if pitch > 0 else turn
    plus_90_only = "the locked branch is right only at pitch = +90°: use roll = atan2(−r23, r22)"
    return {
        "no separate gimbal-lock branch: the general formulas meet atan2(0, 0) = 0 there": (
            lambda: [0.0, pitch, 0.0]
        ),
        "at the gimbal lock the turn went into yaw: the convention is yaw = 0, all of it in "
        "roll": lambda: [0.0, pitch, into_yaw],
        f"{plus_90_only} (atan2(r12, r22) fails at −90°)": lambda: [
            np.arctan2(R[0, 1], R[1, 1]),
            pitch,
            0.0,
        ],
        f"{plus_90_only} (atan2(r12, r13) fails at −90°)": lambda: [
            np.arctan2(R[0, 1], R[0, 2]),
            pitch,
            0.0,
        ],
        "the locked roll has the wrong sign of r23: roll = atan2(−r23, r22)": lambda: [
            np.arctan2(R[1, 2], R[1, 1]),
            pitch,
            0.0,
        ],
        _RPY_DEGREES: lambda: np.degrees([turn, pitch, 0.0]),
    }


def _rpy_gimbal_lock(sub, rng):
    for pitch_sign in (1.0, -1.0, 1.0, -1.0):
        R = _locked_rotation(pitch_sign, rng.uniform(-np.pi, np.pi), rng.uniform(-np.pi, np.pi))
        inputs = {"R": R}
        what = "rotation_to_rpy(R) at pitch = ±90°"
        value = sub.rotation_to_rpy(R.copy())
        try:
            rpy = _matrix(value, (3,), what, inputs, _RPY_SHAPES)
        except Mismatch as exc:
            if exc.mistake is None and "NaN" in exc.what:
                exc.mistake = (
                    "no separate gimbal-lock branch: the general formulas divide 0 by 0 there"
                )
            raise
        hypotheses = _locked_hypotheses(R)
        if not close(_rebuilt(rpy), R, 1e-9):
            raise Mismatch(
                "at pitch = ±90° only roll ∓ yaw is defined, and the general formulas meet "
                "atan2(0, 0): handle this case separately (yaw = 0, roll = atan2(−r23, r22))",
                inputs=inputs,
                expected=rotation_to_rpy(R),
                got=rpy,
                mistake=identify_mistake(rpy, hypotheses),
            )
        if not close(rpy[2], 0.0, 1e-9):
            raise Mismatch(
                "at the gimbal lock the convention sets yaw = 0 and puts the whole turn into roll",
                inputs=inputs,
                expected=rotation_to_rpy(R),
                got=rpy,
                mistake=identify_mistake(rpy, hypotheses)
                or "at the gimbal lock the turn went into yaw: the convention is yaw = 0, all of "
                "it in roll",
            )
    # near the lock, not at it: the general formulas are exact there, the lock branch is not
    for pitch_sign in (1.0, -1.0):
        short = 10.0 ** rng.uniform(-6.0, -3.0)
        rpy_true = [rng.uniform(-np.pi, np.pi), pitch_sign * (np.pi / 2 - short), 0.0]
        rpy_true[2] = rng.uniform(-np.pi, np.pi)
        R = rpy_to_rotation(np.array(rpy_true))
        rpy, inputs = _rpy_call(sub, R, f"rotation_to_rpy(R) {short:.0e} rad from the lock")
        if not close(_rebuilt(rpy), R, 1e-9):
            raise Mismatch(
                f"{short:.0e} rad short of pitch = ±90° the angles must still rebuild R (to 1e-9): "
                "the general formulas are accurate there, and only at the lock itself does "
                "atan2 meet (0, 0)",
                inputs=inputs,
                expected=rotation_to_rpy(R),
                got=rpy,
                mistake=_WIDE_LOCK,
            )


_WIDE_LOCK = (
    "the gimbal-lock branch taken too far from the lock (np.isclose's default tolerance, or a "
    "threshold such as cos(pitch) < 1e-3): there it drops the yaw that R still holds; test "
    "cos(pitch) against a tiny number such as 1e-9"
)


# ---------------------------------------------------------------- 1.4 axis_angle_to_rotation


def _rodrigues_unnormalised(axis, angle):
    K = skew(axis)
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


def _outer_unnormalised(axis, angle):
    return (
        np.cos(angle) * np.eye(3)
        + np.sin(angle) * skew(axis)
        + (1 - np.cos(angle)) * np.outer(axis, axis)
    )


def _rodrigues(unit, angle, sin=np.sin, cos=np.cos, square=lambda K: K @ K):
    K = skew(unit)
    return np.eye(3) + sin(angle) * K + (1 - cos(angle)) * square(K)


def _axis_angle_inputs(rng):
    axis = rng.normal(size=3)
    axis *= 10 ** rng.uniform(-1.5, 1.5) / np.linalg.norm(axis)  # deliberately not a unit vector
    return axis, rng.uniform(-np.pi, np.pi)


def _axis_angle_hypotheses(axis, angle):
    unit = axis / np.linalg.norm(axis)
    return {
        "the axis was not normalised to a unit vector first": lambda: _rodrigues_unnormalised(
            axis, angle
        ),
        "the axis was not normalised to a unit vector first (in k kᵀ)": lambda: _outer_unnormalised(
            axis, angle
        ),
        "transposed: that is the rotation by −θ (a sign in [k] or in sin θ)": lambda: so3_exp(
            -unit * angle
        ),
        "θ treated as degrees": lambda: so3_exp(unit * np.radians(angle)),
        "K**2 squares entry by entry: [k]² is the matrix product K @ K": lambda: _rodrigues(
            unit, angle, square=lambda K: K * K
        ),
        "(1 + cos θ) instead of (1 − cos θ)": lambda: (
            np.eye(3) + np.sin(angle) * skew(unit) + (1 + np.cos(angle)) * skew(unit) @ skew(unit)
        ),
        "sin θ and cos θ swapped": lambda: _rodrigues(unit, angle, sin=np.cos, cos=np.sin),
        "half the angle: Rodrigues' formula takes θ itself (θ/2 belongs to quaternions)": (
            lambda: so3_exp(unit * angle / 2)
        ),
        "twice the angle": lambda: so3_exp(unit * angle * 2),
        "[k] written without its signs: the skew matrix is [[0, −k3, k2], [k3, 0, −k1], "
        "[−k2, k1, 0]]": lambda: _rodrigues_unsigned(unit, angle),
    }


def _rodrigues_unsigned(unit, angle):
    k1, k2, k3 = unit
    K = np.array([[0.0, k3, k2], [k3, 0.0, k1], [k2, k1, 0.0]])
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


_AXIS_ANGLE_SHAPES = {(4, 4): "a 4×4 transform came back: the answer is the 3×3 rotation"}


def _axis_angle_call(sub, axis, angle, shown_axis=None):
    inputs = {"axis": axis if shown_axis is None else shown_axis, "angle": angle}
    what = "axis_angle_to_rotation(axis, angle)"
    zero_over_zero = (
        "a division by the angle (or by |axis · angle|): at angle 0 that is 0/0, yet R = I there"
    )
    try:
        value = sub.axis_angle_to_rotation(axis.copy(), angle)
    except StudentRaised as exc:
        if angle != 0.0 or exc.kind not in (
            "ValueError",
            "ZeroDivisionError",
            "FloatingPointError",
        ):
            raise
        first = exc.message.strip().splitlines()[0][:200] if exc.message.strip() else ""
        where = f" ({exc.where})" if exc.where else ""
        raise Mismatch(
            f"{what} raised {exc.kind} at angle 0: {first}{where}",
            inputs=inputs,
            mistake=zero_over_zero,
        ) from None
    try:
        R = _matrix(value, (3, 3), what, inputs, _AXIS_ANGLE_SHAPES)
    except Mismatch as exc:
        if exc.mistake is None and "NaN" in exc.what and angle == 0.0:
            exc.mistake = zero_over_zero
        raise
    return R, inputs


def _axis_angle_is_rotation(sub, rng):
    for _ in range(10):
        axis, angle = _axis_angle_inputs(rng)
        R, inputs = _axis_angle_call(sub, axis, angle)
        try:
            require_rotation(R, "axis_angle_to_rotation(axis, angle)", inputs)
            compare(
                np.trace(R),
                1 + 2 * np.cos(angle),
                what="a rotation by θ has trace 1 + 2 cos θ",
                inputs=inputs,
            )
        except Mismatch as exc:
            raise _named(exc, R, _axis_angle_hypotheses(axis, angle)) from None


def _axis_angle_matches(sub, rng):
    cases = [_axis_angle_inputs(rng) for _ in range(10)]
    cases += [(_axis_angle_inputs(rng)[0], 0.0), (_axis_angle_inputs(rng)[0], np.pi)]
    for axis, angle in cases:
        R, inputs = _axis_angle_call(sub, axis, angle)
        unit = axis / np.linalg.norm(axis)
        compare(
            R,
            so3_exp(unit * angle),
            what="R = I + sin θ [k] + (1 − cos θ) [k]² with k the unit axis",
            inputs=inputs,
            hypotheses=_axis_angle_hypotheses(axis, angle),
        )


def _axis_is_fixed(sub, rng):
    for _ in range(10):
        axis, angle = _axis_angle_inputs(rng)
        R, inputs = _axis_angle_call(sub, axis, angle)
        unit = axis / np.linalg.norm(axis)
        across = np.cross(unit, rng.normal(size=3))
        across /= np.linalg.norm(across)
        hypotheses = _axis_angle_hypotheses(axis, angle)
        turned = _in_dtype(R.astype(float) @ unit, R)
        if not close(turned, unit, 1e-9):
            raise Mismatch(
                "a rotation leaves its own axis where it is: R k = k (k the unit axis)",
                inputs=inputs,
                expected=unit,
                got=turned,
                mistake=identify_mistake(R, hypotheses),
            )
        cosine = _in_dtype(across @ R.astype(float) @ across, R)
        if not close(cosine, np.cos(angle), 1e-9):
            raise Mismatch(
                "a vector v perpendicular to the axis turns by the angle: v · R v = cos θ",
                inputs={**inputs, "v": across},
                expected=np.cos(angle),
                got=cosine,
                mistake=identify_mistake(R, hypotheses),
            )


def _list_mistake(exc: StudentRaised) -> str | None:
    if exc.kind == "AttributeError" and "'list'" in exc.message:
        return "array methods used on a list: convert the axis with np.asarray first"
    if exc.kind == "TypeError" and ("'list'" in exc.message or "sequence" in exc.message):
        return (
            "the axis list was used like an array (a list divided by a number fails): "
            "convert it with np.asarray first"
        )
    return None


def _axis_as_list(sub, rng):
    for _ in range(3):
        axis, angle = _axis_angle_inputs(rng)
        listed = [round(float(x), 4) for x in axis]
        inputs = {"axis": f"the list {listed}", "angle": angle}
        what = "axis_angle_to_rotation(axis, angle) with axis a list"
        try:
            value = sub.axis_angle_to_rotation(list(listed), angle)
        except StudentRaised as exc:
            mistake = _list_mistake(exc)
            if mistake is None:
                raise
            first = exc.message.strip().splitlines()[0][:200]
            where = f" ({exc.where})" if exc.where else ""
            raise Mismatch(
                f"{what} raised {exc.kind}: {first}{where}", inputs=inputs, mistake=mistake
            ) from None
        R = _matrix(value, (3, 3), what, inputs, _AXIS_ANGLE_SHAPES)
        unit = np.array(listed) / np.linalg.norm(listed)
        compare(
            R,
            so3_exp(unit * angle),
            what="the axis may be a list of three numbers, not only an array",
            inputs=inputs,
            hypotheses=_axis_angle_hypotheses(np.array(listed), angle),
        )


# --------------------------------------------------------------------- 1.5 rotation_verdict

_VERDICTS = ("rotation", "reflection", "not orthonormal")
_DEFAULT_TOL = 1e-9


def _deviation(R):
    """max |RᵀR − I| (NaN when an entry is not finite)."""
    with np.errstate(all="ignore"):
        return float(np.abs(R.T @ R - np.eye(3)).max())


def _determinant(R):
    with np.errstate(all="ignore"):
        try:
            return float(np.linalg.det(R))
        except np.linalg.LinAlgError:
            return float("nan")


def _verdict(R, tol=_DEFAULT_TOL):
    """The verdict the contract of exercise 1.5 asks for."""
    if not np.all(np.isfinite(R)) or not _deviation(R) <= tol:
        return "not orthonormal"
    return "rotation" if _determinant(R) > 0 else "reflection"


_FIXED_TOL = (
    "tol was not used: a fixed tolerance decided instead of the tol given (is `tol` a "
    "parameter, and is it the number compared with?)"
)


def _measured(R):
    """max |RᵀR − I| and det R as the feedback shows them: round-off shows as "below 1e-13"
    (the checks' smallest deviation on purpose is 5e-16 × 1000), no "−0.0000"."""
    return (
        f"max |RᵀR − I| is {below(_deviation(R), 1e-13)}, "
        f"det R = {round(_determinant(R), 4) + 0.0:+.4f}"
    )


def _mistake_text(key):
    """A hypothesis' name; every fixed tolerance has the same one (the checks cannot tell
    which tolerance it was)."""
    return _FIXED_TOL if isinstance(key, tuple) else key


_ALLCLOSE_RTOL = (
    "np.allclose(RᵀR, I, atol=tol) keeps numpy's relative tolerance (rtol 1e-5): a matrix "
    "1e-6 from orthonormal passes; give rtol=0 as well, or compare max |RᵀR − I| with tol"
)
_UNIT_COLUMNS = (
    "only unit columns and |det R| = 1 were tested: columns of length 1 can still lean on one "
    "another (RᵀR's off-diagonal entries), and det R hardly changes; test RᵀR = I"
)


def _sign_verdict(det):
    return "rotation" if det > 0 else "reflection"


def _verdict_hypotheses(R, tol, tol_first=False):
    """Wrong verdicts by name; with ``tol_first``, those about the tolerance come first (for
    matrices built to test it, where a determinant-only verdict would match as well)."""
    det, deviation = _determinant(R), _deviation(R)
    exact = bool(np.array_equal(R.T @ R, np.eye(3)))
    about_tol = {
        "RᵀR was compared with I exactly (== or np.array_equal): round-off leaves a true "
        "rotation's RᵀR about 1e-16 away from I; compare within tol": lambda: (
            _sign_verdict(det) if exact else "not orthonormal"
        ),
        "tol was not used: np.allclose's default tolerances (rtol 1e-5, atol 1e-8) decided "
        "instead of the tol given": lambda: (
            _sign_verdict(det) if np.allclose(R.T @ R, np.eye(3)) else "not orthonormal"
        ),
    }
    for fixed in (1e-12, 1e-10, 1e-9, 1e-8, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2):
        about_tol[("fixed", fixed)] = lambda fixed=fixed: _verdict(R, fixed)
    others = {
        "only the determinant was checked: det R = +1 does not make a rotation (a shear has "
        "det 1 too, and a scaled rotation any det); test RᵀR = I first": lambda: _sign_verdict(det),
        "only orthonormality was checked: a reflection (det R = −1) is orthonormal too, but it "
        "is not a rotation; the sign of det R tells them apart": lambda: (
            "rotation" if deviation <= tol else "not orthonormal"
        ),
        "the sign of det R was read backwards: +1 is a rotation, −1 a reflection": lambda: {
            "rotation": "reflection",
            "reflection": "rotation",
            "not orthonormal": "not orthonormal",
        }[_verdict(R, tol)],
    }
    near = {  # the tolerance kept loose in a way of its own: named before the rest
        _ALLCLOSE_RTOL: lambda: (
            _sign_verdict(det)
            if np.allclose(R.T @ R, np.eye(3), rtol=1e-5, atol=tol)
            else "not orthonormal"
        ),
        _UNIT_COLUMNS: lambda: (
            _sign_verdict(det)
            if np.abs(np.linalg.norm(R, axis=0) - 1.0).max() <= tol and abs(abs(det) - 1.0) <= tol
            else "not orthonormal"
        ),
    }
    return {**near, **about_tol, **others} if tol_first else {**others, **near, **about_tol}


def _verdict_mistake(got, R, tol, tol_first=False):
    right = _verdict(R, tol)
    for name, compute in _verdict_hypotheses(R, tol, tol_first).items():
        try:
            candidate = compute()
        except Exception:  # a hypothesis that cannot be evaluated names nothing
            continue
        if candidate == got and candidate != right:
            return _mistake_text(name)
    return None


_LIBRARY_VERDICTS = ("check_rotation", "check_transform")


def _refuse_library_verdict(sub):
    """A Mismatch when the student's code calls urkin's own validators: they give the verdict
    (and cannot be hidden while graded: every UR arm is built with them), so each check reads
    the code for them instead."""
    code = sub.code("rotation_verdict")
    for name, source in code.items():
        try:
            tree = ast.parse(source)
        except SyntaxError:
            continue
        for node in ast.walk(tree):
            used = node.id if isinstance(node, ast.Name) else None
            used = node.attr if isinstance(node, ast.Attribute) else used
            if used in _LIBRARY_VERDICTS and used not in code:
                raise Mismatch(
                    f"{name} uses urkin's {used}, which gives the verdict itself: the exercise "
                    "asks for the two tests, RᵀR = I within tol and the sign of det R, written "
                    "with numpy",
                    mistake=f"urkin's {used} used: it earns no points in exercise 1.5",
                )


#: urkin's validators and the functions inside them, watched while the student's verdict runs:
#: reading the code misses them when they are named by strings built at run time.
_LIBRARY_VERDICT_CODE = tuple(
    f"urkin.transforms.{name}"
    for name in (
        *_LIBRARY_VERDICTS,
        "_rotation_deviation",
        "_checked_transform",
        "_is_rotation_one",
        "_is_transform_one",
    )
)


def _verdict_call(sub, R, tol=None):
    """The student's verdict for ``R`` (with ``tol`` when given), checked to be one of the
    three strings, and reached without urkin's validators."""
    inputs = {"R": R} if tol is None else {"R": R, "tol": f"{tol:.3g}"}
    what = "rotation_verdict(R)" if tol is None else "rotation_verdict(R, tol)"
    arguments = (R.copy(),) if tol is None else (R.copy(), tol)
    got, calls = sub.spy("rotation_verdict", _LIBRARY_VERDICT_CODE, *arguments)
    used = sorted(name.rpartition(".")[2] for name, made in calls.items() if made)
    if used:
        public = next((name for name in used if name in _LIBRARY_VERDICTS), "check_rotation")
        raise Mismatch(
            f"{what} runs urkin's own validator ({', '.join(used)}; seen while it ran), which "
            "gives the verdict itself: the exercise asks for the two tests, RᵀR = I within tol "
            "and the sign of det R, written with numpy",
            inputs=inputs,
            mistake=f"urkin's {public} used: it earns no points in exercise 1.5",
        )
    if isinstance(got, str) and got in _VERDICTS:
        return got, inputs
    if got is None:
        raise Mismatch(f"{what} returned None: is a `return` statement missing?", inputs=inputs)
    shown = repr(got)[:80]
    mistake = None
    if isinstance(got, str):
        normal = " ".join(got.lower().replace("_", " ").replace("-", " ").split())
        if normal in _VERDICTS or normal in ("non orthonormal", "not orthogonal"):
            mistake = (
                "the verdict is spelled differently: return exactly 'rotation', 'reflection' "
                "or 'not orthonormal' (lower case, one space)"
            )
    elif isinstance(got, (bool, np.bool_)):
        mistake = "a True/False answer: the verdict has three values, returned as strings"
    raise Mismatch(
        f"{what} must return one of the strings 'rotation', 'reflection' or "
        f"'not orthonormal'; got {shown}",
        inputs=inputs,
        mistake=mistake,
    )


def _require_verdict(sub, R, why, tol=None, near=False):
    """A Mismatch unless the student's verdict on ``R`` is right; a ``tol`` given is passed on
    (and, as ``near``, a matrix close to orthonormal, makes the tolerance the first suspect when
    the verdict is wrong)."""
    got, inputs = _verdict_call(sub, R, tol)
    right = _verdict(R, _DEFAULT_TOL if tol is None else tol)
    if got != right:
        raise Mismatch(
            f"{why}: {_measured(R)}",
            inputs=inputs,
            expected=right,
            got=got,
            mistake=_verdict_mistake(
                got, R, _DEFAULT_TOL if tol is None else tol, tol_first=near or tol is not None
            ),
        )


def _inexact_rotation(rng):
    """A random rotation whose RᵀR differs from I by round-off (not exactly I)."""
    while True:
        R = random_rotation(rng)
        if not np.array_equal(R.T @ R, np.eye(3)):
            return R


def _reflections(rng):
    mirror = np.diag([1.0, 1.0, -1.0])
    n = rng.normal(size=3)
    n /= np.linalg.norm(n)
    swapped = _inexact_rotation(rng)[:, [1, 0, 2]]
    return [
        mirror,
        _inexact_rotation(rng) @ mirror,
        mirror @ _inexact_rotation(rng),
        -_inexact_rotation(rng),
        swapped,
        np.eye(3) - 2.0 * np.outer(n, n),  # a Householder mirror
    ]


def _verdict_rotations_and_reflections(sub, rng):
    _refuse_library_verdict(sub)
    rotations = [np.eye(3), *(_inexact_rotation(rng) for _ in range(7))]
    for R in rotations:
        _require_verdict(sub, R, "a rotation (orthonormal to round-off, det +1) is 'rotation'")
    for R in _reflections(rng):
        _require_verdict(sub, R, "an orthonormal matrix with det −1 is 'reflection'")


def _shear(rng):
    """A unit upper or lower shear: det exactly 1, not orthonormal."""
    S = np.eye(3)
    i, j = rng.choice(3, size=2, replace=False)
    S[i, j] = rng.choice([-1.0, 1.0]) * rng.uniform(0.05, 1.0)
    return S


def _verdict_not_orthonormal(sub, rng):
    _refuse_library_verdict(sub)
    Q = _inexact_rotation(rng)
    scale = rng.choice([rng.uniform(0.5, 0.99), rng.uniform(1.01, 2.0)])
    singular = _inexact_rotation(rng)
    singular[:, 2] = singular[:, 0]
    unit_axis = rng.normal(size=3)
    unit_axis /= np.linalg.norm(unit_axis)
    K = skew(2.0 * unit_axis)  # an axis of length 2 in Rodrigues' formula
    angle = rng.uniform(0.5, 2.5)
    stretch = rng.uniform(1e-6, 3e-6)
    leaning = _inexact_rotation(rng)
    leaning[:, 1] = np.cos(1e-6) * leaning[:, 1] + np.sin(1e-6) * leaning[:, 0]  # still unit
    cases = [
        (_shear(rng), "a shear with det exactly 1"),
        (_inexact_rotation(rng) @ _shear(rng), "a rotation times a shear (det 1)"),
        (_shear(rng) @ np.diag([1.0, -1.0, 1.0]), "a mirrored shear (det −1)"),
        (scale * Q, f"a rotation scaled by {scale:.3f}"),
        (singular, "a rotation with its third column replaced by the first (det 0)"),
        (
            np.eye(3) + np.sin(angle) * K + (1.0 - np.cos(angle)) * K @ K,
            "Rodrigues' formula with an axis of length 2",
        ),
    ]
    near = [  # inside np.allclose's rtol (1e-5), far beyond tol (1e-9)
        (
            (1.0 + stretch) * _inexact_rotation(rng),
            f"a rotation scaled by 1 + {stretch:.1e} (max |RᵀR − I| about {2 * stretch:.0e})",
        ),
        (leaning, "a rotation whose second column leans 1e-6 rad towards its first (unit columns)"),
    ]
    for R, name in cases:
        _require_verdict(sub, R, f"{name} is 'not orthonormal', whatever its determinant")
    for R, name in near:
        _require_verdict(sub, R, f"{name} is 'not orthonormal' at tol = 1e-9", near=True)


def _near_orthonormal(rng, proper, deviation):
    """An orthonormal matrix (det +1 when ``proper``) stretched so that max |RᵀR − I| is
    between ``deviation / 2`` and ``deviation``: RᵀR − I = V diag(e) Vᵀ, all e of one sign."""
    Q = _inexact_rotation(rng)
    Q = Q if proper else Q @ np.diag([1.0, 1.0, -1.0])
    V = random_rotation(rng)
    sign = rng.choice([-1.0, 1.0]) if deviation < 0.5 else 1.0
    e = sign * deviation * rng.uniform(0.5, 1.0, 3)
    return Q @ V @ np.diag(np.sqrt(1.0 + e)) @ V.T


def _verdict_honours_tol(sub, rng):
    """Tolerances far apart (between 1e-4 and 1e-3, the default 1e-9, between 1e-12 and
    1e-11), so that no fixed tolerance passes; each matrix 1000 times inside or outside its
    tol, so that neither rounding nor the choice of norm can decide.  All six verdicts are
    gathered first: the mistake named is one that explains every one of them."""
    _refuse_library_verdict(sub)
    tols = [10.0 ** rng.uniform(-4.0, -3.0), _DEFAULT_TOL, 10.0 ** rng.uniform(-12.0, -11.0)]
    cases = []
    for tol in tols:
        outside = _near_orthonormal(rng, bool(rng.integers(2)), 1e3 * tol)
        inside = _near_orthonormal(rng, True, 1e-3 * tol)
        assert _deviation(inside) <= 1e-2 * tol and _deviation(outside) >= 1e2 * tol
        cases += [
            (outside, tol, "a matrix 1000 times beyond tol of orthonormal is 'not orthonormal'"),
            (inside, tol, "a rotation 1000 times within tol of orthonormal is 'rotation'"),
        ]
    answers = [(R, tol, why, *_verdict_call(sub, R, tol)) for R, tol, why in cases]
    wrong = [a for a in answers if a[3] != _verdict(a[0], a[1])]
    if not wrong:
        return
    R, tol, why, got, inputs = wrong[0]
    mistake = None
    for name in _verdict_hypotheses(R, tol, tol_first=True):
        explained = True
        for R_k, tol_k, _, got_k, _ in answers:
            try:
                explained = _verdict_hypotheses(R_k, tol_k)[name]() == got_k
            except Exception:  # a hypothesis that cannot be evaluated explains nothing
                explained = False
            if not explained:
                break
        if explained:
            mistake = _mistake_text(name)
            break
    raise Mismatch(
        f"{why}: {_measured(R)}",
        inputs=inputs,
        expected=_verdict(R, tol),
        got=got,
        mistake=mistake,
    )


_NAMES_R = re.compile(r"(?<![A-Za-z0-9_])R(?![A-Za-z0-9_])")


def _verdict_bad_input(sub, rng):
    _refuse_library_verdict(sub)
    for bad in (np.nan, np.inf, -np.inf):
        R = _inexact_rotation(rng)
        R[tuple(rng.integers(3, size=2))] = bad
        got, inputs = _verdict_call(sub, R)
        if got != "not orthonormal":
            raise Mismatch(
                f"a matrix with an entry {bad} is 'not orthonormal'",
                inputs=inputs,
                expected="not orthonormal",
                got=got,
                mistake="a NaN slipped through: every comparison with NaN is False, so "
                "`deviation > tol` does not catch it (and inf − inf is NaN); test "
                "np.isfinite first, or write `not deviation <= tol`",
            )
    shapes = [
        (make_transform(random_rotation(rng), rng.uniform(-1.0, 1.0, 3)), "a 4×4 transform"),
        (random_rotation(rng)[:2, :2], "a 2×2 matrix"),
        (random_rotation(rng)[:, 0], "a vector of 3"),
        (np.column_stack([random_rotation(rng), np.zeros(3)]), "a 3×4 matrix"),
    ]
    for R, name in shapes:
        inputs = {"R": R}
        what = f"rotation_verdict(R) for {name}"
        try:
            got = sub.rotation_verdict(R.copy())
        except StudentRaised as exc:
            first = exc.message.strip().splitlines()[0][:200] if exc.message.strip() else ""
            where = f" ({exc.where})" if exc.where else ""
            if exc.kind == "ValueError" and _NAMES_R.search(exc.message):
                continue
            if exc.kind == "ValueError":
                mistake = (
                    "the ValueError does not name the argument R: check R.shape == (3, 3) "
                    "yourself and say what is wrong with R"
                )
            elif exc.kind == "AssertionError":
                mistake = "an assert raises AssertionError (and is skipped under python -O)"
            else:
                mistake = "no shape check: test R.shape == (3, 3) first and raise ValueError"
            raise Mismatch(
                f"{what} must raise ValueError naming R; it raised {exc.kind}: {first}{where}",
                inputs=inputs,
                mistake=mistake,
            ) from None
        raise Mismatch(
            f"{what} must raise ValueError naming R, not return a verdict",
            inputs=inputs,
            got=got if isinstance(got, str) else repr(got)[:80],
            mistake="no shape check: test R.shape == (3, 3) first and raise ValueError",
        )


# -------------------------------------------------------------------- 1.6 rotation_distance


def _quarter_turns() -> tuple[np.ndarray, ...]:
    """The 24 rotations with entries 0 and ±1 (turns by multiples of 90° about the axes)."""
    found = []
    for order in itertools.permutations(range(3)):
        for signs in itertools.product((1.0, -1.0), repeat=3):
            P = np.zeros((3, 3))
            P[range(3), order] = signs
            if np.linalg.det(P) > 0:
                found.append(P)
    return tuple(found)


# Products with these are exact in floating point: a pair (P, P E) has exactly Pᵀ(P E) = E.
_QUARTER_TURNS = _quarter_turns()
# What arccos gives next to 1: arccos(1 − j·2⁻⁵³), the only angles a trace can say below 1e-7.
_ARCCOS_STEPS = np.arccos(1.0 - np.arange(0, 65) * 2.0**-53)

_TRACE_TINY = (
    "arccos((tr R1ᵀR2 − 1)/2), or another formula through the trace: cos θ = 1 − θ²/2 rounds "
    "to 1 below about 1e-8 rad, so the angle comes out 0 or about 1.5e-8; use 2·asin(‖R1 − "
    "R2‖_F / 2√2) there, or the atan2 of the log map"
)
_BEYOND_ONE = (
    "arccos or arcsin of a number that round-off pushed just beyond ±1 gives NaN: (tr R1ᵀR2 − "
    "1)/2 is 1 + 2.2e-16 for some rotations compared with themselves, and ‖R1 − R2‖_F / 2√2 "
    "can exceed 1 next to a half turn; clip it into [−1, 1] (np.clip) first"
)
_FLAT_NEAR_PI = (
    "2·asin(‖R1 − R2‖_F / 2√2) or arccos((tr − 1)/2) used near π: sin(θ/2) and cos θ are flat "
    "at a half turn, so their round-off of 1e-16 costs about √1e-16 = 1e-8 rad there; sin θ is "
    "not flat: use atan2(½‖vee(A − Aᵀ)‖, ½(tr A − 1)) with A = R1ᵀR2 (at least above π/2)"
)
_DISTANCE_SHAPES = {
    (3,): "three numbers came back (a rotation vector?): the distance is one angle, its length",
    (3, 3): "a 3×3 matrix came back (R1ᵀR2?): the distance is the angle of that rotation",
    (1,): "an array holding one number: return the angle itself, a float",
}


def _unit_vector(rng) -> np.ndarray:
    k = rng.normal(size=3)
    return k / np.linalg.norm(k)


def _turned_pair(rng, R, E):
    """R with R E or E R (both are turned by E's angle from R), in random order."""
    R2 = R @ E if rng.random() < 0.5 else E @ R
    return (R, R2) if rng.random() < 0.5 else (R2, R)


def _distance_value(sub, R1, R2, inputs) -> float:
    """The student's angle as a float (NaN passes through, for :func:`_refuse_nan`)."""
    value = sub.rotation_distance(R1.copy(), R2.copy())
    try:
        raw = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raw = None
    if raw is not None and raw.shape == () and np.isnan(raw):
        return float("nan")
    return float(as_array(value, (), "rotation_distance(R1, R2)", inputs, _DISTANCE_SHAPES))


def _refuse_nan(answers) -> None:
    """A Mismatch for the first NaN among ``answers``: (inputs, got, …) tuples."""
    for inputs, got, *_ in answers:
        if np.isnan(got):
            raise Mismatch(
                "rotation_distance(R1, R2) returned NaN",
                inputs=inputs,
                got="nan",
                mistake=_BEYOND_ONE,
            )


def _distance_hypotheses(R1, R2, theta):
    frobenius = float(np.linalg.norm(R1 - R2))
    return {
        "degrees: angles are radians here (np.degrees is for display only)": lambda: np.degrees(
            theta
        ),
        "‖R1 − R2‖_F is not the angle itself: θ = 2·asin(‖R1 − R2‖_F / 2√2)": lambda: frobenius,
        "the factor 2 is missing: asin(‖R1 − R2‖_F / 2√2) is θ/2": lambda: theta / 2,
        "‖R1 − R2‖_F divided by 2 instead of 2√2 = ‖R − I‖_F at a half turn": lambda: (
            2 * np.arcsin(frobenius / 2)
        ),
        "the angle of R1 R2: the rotation from R1 to R2 is R1ᵀR2": lambda: np.linalg.norm(
            so3_log(R1 @ R2)
        ),
        "atan2's arguments swapped: atan2(sin θ, cos θ), the sine first": lambda: np.arctan2(
            np.cos(theta), np.sin(theta)
        ),
        "sin θ is half the length of vee(A − Aᵀ): the ½ is missing": lambda: np.arctan2(
            2 * np.sin(theta), np.cos(theta)
        ),
        "cos θ is (tr A − 1)/2: the ½ is missing": lambda: np.arctan2(
            np.sin(theta), 2 * np.cos(theta)
        ),
    }


def _distance_random_pairs(sub, rng):
    low, high = 0.05, np.pi - 0.05
    answers = []
    for j in rng.permutation(10):  # one angle in each tenth of [0.05, π − 0.05]
        theta = low + (j + rng.uniform()) * (high - low) / 10
        R1, R2 = _turned_pair(rng, random_rotation(rng), so3_exp(theta * _unit_vector(rng)))
        inputs = {"R1": R1, "R2": R2}
        answers.append((inputs, _distance_value(sub, R1, R2, inputs), R1, R2, theta))
    _refuse_nan(answers)
    for inputs, got, R1, R2, theta in answers:
        compare(
            np.asarray(got),
            theta,
            what="the angle θ of R1ᵀR2, in radians in [0, π], to 1e-12",
            inputs=inputs,
            hypotheses=_distance_hypotheses(R1, R2, theta),
            atol=1e-12,
        )


def _tiny_mistake(got, theta, R1, R2) -> str | None:
    if got == 0.0 or np.any(np.abs(got - _ARCCOS_STEPS[1:]) <= 1e-6 * _ARCCOS_STEPS[1:]):
        return _TRACE_TINY
    for name, compute in _distance_hypotheses(R1, R2, theta).items():
        with np.errstate(all="ignore"):
            value = float(compute())
        if abs(got - value) <= 1e-6 * abs(value):
            return name
    return _TRACE_TINY if got > 1e-8 else None


def _distance_tiny_and_zero(sub, rng):
    answers = []
    for exponent in range(10, 15):  # one angle in each decade from 1e-14 to 1e-9 rad
        theta = 10.0**-exponent * rng.uniform(1.0, 10.0)
        P = _QUARTER_TURNS[int(rng.integers(len(_QUARTER_TURNS)))]
        R1, R2 = _turned_pair(rng, P, so3_exp(theta * _unit_vector(rng)))
        inputs = {"R1": R1, "R2": R2, "θ (rad)": f"{theta:.3e}"}
        answers.append((inputs, _distance_value(sub, R1, R2, inputs), R1, R2, theta))
    same = [np.eye(3), _QUARTER_TURNS[int(rng.integers(len(_QUARTER_TURNS)))]]
    for beyond in (True, True, False, False):  # RᵀR's trace rounds above 3, and below it
        while True:
            R = random_rotation(rng)
            cosine = (np.trace(R.T @ R) - 1.0) / 2.0
            if (cosine > 1.0) if beyond else (cosine < 1.0):
                break
        same.append(R)
    for R in same:
        inputs = {"R1 = R2": R}
        answers.append((inputs, _distance_value(sub, R, R.copy(), inputs), R, R, 0.0))
    _refuse_nan(answers)
    for inputs, got, R1, R2, theta in answers:
        if theta == 0.0 and not abs(got) <= 1e-15:
            raise Mismatch(
                "a rotation compared with itself is 0 rad away (0, or below 1e-15)",
                inputs=inputs,
                expected="0 rad",
                got=f"{got:.3e} rad",
                mistake=_TRACE_TINY
                if np.any(np.abs(abs(got) - _ARCCOS_STEPS[1:]) <= 1e-6 * _ARCCOS_STEPS[1:])
                else None,
            )
        if theta > 0.0 and not abs(got - theta) <= 1e-6 * theta:
            raise Mismatch(
                "a tiny angle (1e-14 to 1e-9 rad) to 1e-6 relative: R1 is a quarter turn "
                "(entries 0, ±1), so R1ᵀR2 holds no round-off and the angle is known to the "
                "last digit",
                inputs=inputs,
                expected=f"{theta:.6e} rad",
                got=f"{got:.6e} rad",
                mistake=_tiny_mistake(got, theta, R1, R2),
            )


def _near_pi_mistake(got, theta) -> str | None:
    """The mistake behind an angle a little off next to π, read from how far it is from π.

    Through cos θ or sin(θ/2), a number within round-off of ∓1, the angle can only come out
    as π − d with d² / 2⁻⁵² a whole number (d = √(2 m ε) for the m-th double next to ∓1).
    """
    deficit, true_deficit = np.pi - got, np.pi - theta
    steps = deficit**2 / 2.0**-52
    if got == np.pi or (steps >= 0.5 and abs(steps - round(steps)) < 1e-3):
        return _FLAT_NEAR_PI  # (got == π is wrong here: θ < π)
    if true_deficit > 0.0 and abs(deficit - 2.0 * true_deficit) <= 1e-3 * true_deficit:
        return "sin θ is half the length of vee(A − Aᵀ): the ½ is missing"
    if true_deficit > 0.0 and abs(deficit - 0.5 * true_deficit) <= 1e-3 * true_deficit:
        return "cos θ is (tr A − 1)/2: the ½ is missing"
    return None


def _distance_near_half_turn(sub, rng):
    cases = []
    for _ in range(2):  # exact half turns about a coordinate axis, from a quarter turn
        P = _QUARTER_TURNS[int(rng.integers(len(_QUARTER_TURNS)))]
        cases.append((_turned_pair(rng, P, np.diag(rng.permutation([1.0, -1.0, -1.0]))), np.pi))
    k = _unit_vector(rng)
    cases.append((_turned_pair(rng, random_rotation(rng), 2 * np.outer(k, k) - np.eye(3)), np.pi))
    for low in (-9.0, -8.0, -7.0, rng.uniform(-9.0, -7.0)):  # π − 1e-9 … π − 1e-6
        theta = np.pi - 10.0 ** rng.uniform(low, low + 1.0)
        E = so3_exp(theta * _unit_vector(rng))
        cases.append((_turned_pair(rng, random_rotation(rng), E), theta))
    answers = []
    for (R1, R2), theta in cases:
        inputs = {"R1": R1, "R2": R2, "π − θ (rad)": f"{np.pi - theta:.3e}"}
        answers.append((inputs, _distance_value(sub, R1, R2, inputs), R1, R2, theta))
    _refuse_nan(answers)
    for inputs, got, R1, R2, theta in answers:
        if abs(got - theta) <= 1e-12:
            continue
        mistake = identify_mistake(got, _distance_hypotheses(R1, R2, theta), right=theta)
        raise Mismatch(
            "next to a half turn (θ within 1e-6 of π, or π exactly) the angle to 1e-12",
            inputs=inputs,
            expected=f"{theta:.15f} rad",
            got=f"{got:.15f} rad",
            difference=f"difference {abs(got - theta):.1e} rad; the tolerance is 1e-12",
            mistake=mistake or _near_pi_mistake(got, theta),
        )


LESSON = Lesson(
    number="01",
    title="Rigid-body transforms",
    summary="rigid-body transforms: rotations, homogeneous transforms, inverse, roll–pitch–yaw, "
    "exp and log",
    exercises=(
        Exercise(
            id="1.1",
            function="rot_z",
            title="rotation about the z axis",
            checks=(
                Check(
                    "returns a 3×3 rotation matrix (orthonormal, det = +1) by the angle θ",
                    1,
                    _rot_z_is_rotation_by_theta,
                ),
                Check("matches Rz(θ) on random angles", 2, _rot_z_matches),
            ),
            answer=concepts.ELEMENTARY_ROTATIONS,
        ),
        Exercise(
            id="1.2",
            function="transform_inverse",
            title="inverse of a rigid-body transform",
            checks=(
                Check(
                    "returns a homogeneous transform whose rotation block is Rᵀ",
                    1,
                    _inverse_is_transform,
                ),
                Check(
                    "T @ transform_inverse(T) = I on random poses", 2, _inverse_composes_to_identity
                ),
                Check(
                    "uses the transpose formula, not a general matrix inverse",
                    1,
                    _inverse_is_structured,
                ),
            ),
            answer=concepts.RIGID_INVERSE,
        ),
        Exercise(
            id="1.3",
            function="rotation_to_rpy",
            title="roll, pitch and yaw of a rotation",
            checks=(
                Check(
                    "Rz(yaw) Ry(pitch) Rx(roll) rebuilds R for random rotations",
                    2,
                    _rpy_rebuilds_rotation,
                ),
                Check(
                    "angles in radians, roll and yaw in (−π, π], pitch in [−π/2, π/2]",
                    1,
                    _rpy_in_range,
                ),
                Check(
                    "copes with the gimbal lock (pitch = ±90°): yaw = 0, R rebuilt; near it too",
                    1,
                    _rpy_gimbal_lock,
                ),
            ),
            answer=concepts.RPY,
        ),
        Exercise(
            id="1.4",
            function="axis_angle_to_rotation",
            title="Rodrigues' formula",
            checks=(
                Check("returns a rotation matrix by the given angle", 1, _axis_angle_is_rotation),
                Check(
                    "matches Rodrigues' formula for axes of any length and angles (0 and π too)",
                    2,
                    _axis_angle_matches,
                ),
                Check(
                    "turns about its axis: R k = k, and vectors across it turn by θ",
                    1,
                    _axis_is_fixed,
                ),
                Check("accepts the axis as a list", 1, _axis_as_list),
            ),
            answer=concepts.SO3_EXP,
        ),
        Exercise(
            id="1.5",
            function="rotation_verdict",
            title="rotation, reflection or not orthonormal",
            checks=(
                Check(
                    "random rotations are 'rotation', orthonormal matrices with det −1 "
                    "'reflection'",
                    2,
                    _verdict_rotations_and_reflections,
                ),
                Check(
                    "shears (det 1), scaled and singular matrices are 'not orthonormal'",
                    1,
                    _verdict_not_orthonormal,
                ),
                Check(
                    "honours tol: 1000 times inside is orthonormal, 1000 times beyond is not",
                    1,
                    _verdict_honours_tol,
                ),
                Check(
                    "NaN or infinite entries are 'not orthonormal'; a wrong shape raises "
                    "ValueError naming R",
                    1,
                    _verdict_bad_input,
                ),
            ),
        ),
        Exercise(
            id="1.6",
            function="rotation_distance",
            title="the angle between two orientations, accurate at every size",
            checks=(
                Check(
                    "the angle of R1ᵀR2 for random pairs from 0.05 to π − 0.05 rad, to 1e-12",
                    2,
                    _distance_random_pairs,
                ),
                Check(
                    "tiny angles, 1e-14 to 1e-9 rad, to 1e-6 relative; a rotation and itself: 0",
                    1,
                    _distance_tiny_and_zero,
                ),
                Check(
                    "next to a half turn (within 1e-6 of π, and π exactly), to 1e-12",
                    1,
                    _distance_near_half_turn,
                ),
            ),
            answer=(*concepts.ROTATION_LOG, rotation_angle, pose_error),
        ),
    ),
)
