"""Lesson 00 — how the course works: units and frames."""

from __future__ import annotations

import numpy as np

from urkin.course import concepts
from urkin.course.compare import (
    Mismatch,
    as_array,
    close,
    compare,
    identify_mistake,
    require_transform,
)
from urkin.course.exercise import Check, Exercise, Lesson
from urkin.course.inputs import random_arm, random_pose, random_q
from urkin.course.submission import StudentRaised
from urkin.kinematics import fk
from urkin.robots import T_BASE_LINK_BASE
from urkin.transforms import make_transform, rot_x, rot_y, rot_z

# ---------------------------------------------------------------------------- 0.1 deg_to_rad

_EXACT = np.pi / 180.0


def _as_float(value):
    return np.asarray(value, dtype=float)


def _wrapped(rad):
    """Angles wrapped into (−π, π], as if the conversion also normalised them."""
    return np.arctan2(np.sin(rad), np.cos(rad))


def _factor(got, deg):
    """The constant c with got = c · deg, when there is one (None otherwise)."""
    got, deg = _as_float(got), _as_float(deg)
    if got.shape != deg.shape or not np.any(deg != 0.0):
        return None
    c = float(np.sum(got * deg) / np.sum(deg * deg))
    if c == 0.0 or not close(got, c * deg, 1e-12 * max(1.0, abs(c) * 720)):
        return None
    return c


def _deg_to_rad_mistake(got, deg):
    """The likely mistake behind a wrong conversion of ``deg`` into ``got``."""
    deg = _as_float(deg)
    rad = deg * _EXACT
    named = {
        "the angles came back unchanged, still in degrees": lambda: deg,
        "converted the wrong way, radians to degrees (× 180/π)": lambda: deg * (180.0 / np.pi),
        "the rounded factor 0.0175 instead of π/180 (seed 002 does this)": lambda: deg * 0.0175,
        "the rounded factor 0.01744 instead of π/180 (seed 002 does this too)": lambda: (
            deg * 0.01744
        ),
        "divided by 180 without multiplying by π": lambda: deg / 180.0,
        "the angles were cut to whole degrees first (an integer dtype or int())": lambda: (
            np.trunc(deg) * _EXACT
        ),
        "the angles were rounded to whole degrees first": lambda: np.round(deg) * _EXACT,
        "the result was wrapped into one turn: a conversion keeps 720° as 4π, not 0": lambda: (
            _wrapped(rad)
        ),
        "the result was wrapped into [0, 2π): a conversion keeps −90° as −π/2": lambda: np.mod(
            rad, 2 * np.pi
        ),
    }
    for name, compute in named.items():
        candidate = compute()
        if np.shape(got) == candidate.shape and close(got, candidate, 1e-9):
            if "wrapped" in name and close(candidate, rad, 1e-9):
                continue  # the angles were inside one turn already: wrapping changed nothing
            return name
    got_array = _as_float(got)
    for decimals in range(0, 9):
        if got_array.shape == rad.shape and np.array_equal(got_array, np.round(rad, decimals)):
            return f"the result was rounded (to {decimals} decimals): keep full precision"
    c = _factor(got, deg)
    if c is not None and abs(c / _EXACT - 1.0) < 0.02:
        return f"a rounded factor ({c:.10g}) instead of exactly π/180 = 0.017453292519943…"
    if c is not None:
        return f"the factor {c:.6g} instead of π/180 = 0.0174533"
    return None


def _raised_mistake(exc: StudentRaised, value) -> str | None:
    """A likely mistake behind an exception for a number, a list or an array of angles."""
    text = exc.message
    if exc.kind == "AttributeError" and "'list'" in text:
        return "array methods used on a list: convert the input with np.asarray first"
    if exc.kind not in ("TypeError", "UFuncTypeError") and "Casting" not in exc.kind:
        return None
    if isinstance(value, list) and ("sequence" in text or "'list'" in text):
        return (
            "a list multiplied or divided like an array (a list times a number repeats it or "
            "fails): convert the input with np.asarray first"
        )
    if any(
        words in text
        for words in (
            "must be real number",
            "0-dimensional arrays",
            "length-1 arrays",
            "size-1 arrays",
        )
    ):
        return "math.radians or float() takes one number only: use numpy for lists and arrays"
    if "not iterable" in text and np.ndim(value) == 0:
        return "the function loops over its input, so a single number fails"
    if "cast" in text.lower():
        return "in-place *= on an array of integers: make a float array first"
    return None


def _convert(sub, value, what, inputs):
    """The student's answer for ``value``; an exception with a known cause is a Mismatch."""
    try:
        return sub.deg_to_rad(value)
    except StudentRaised as exc:
        mistake = _raised_mistake(exc, value)
        if mistake is None:
            raise
        first = exc.message.strip().splitlines()[0][:200] if exc.message.strip() else ""
        where = f" ({exc.where})" if exc.where else ""
        raise Mismatch(
            f"{what} raised {exc.kind}: {first}{where}", inputs=inputs, mistake=mistake
        ) from None


def _answer(sub, value, shape, what, inputs):
    """The student's answer for ``value`` as an array of ``shape``, or a Mismatch saying why
    not (naming the mistake when the shape gives it away)."""
    raw = _convert(sub, value, what, inputs)
    try:
        got_shape = np.shape(raw)
    except Exception:  # a ragged answer: as_array says why it is not an array
        got_shape = None
    if shape == () and got_shape == (1,) and isinstance(raw, np.ndarray):
        # The wire gives a 0-d array or a float32 scalar the shape (1,) (np.ascontiguousarray):
        # a right 0-d answer cannot be told from np.atleast_1d's, so both pass.
        raw = raw.reshape(())
    try:
        return as_array(raw, shape, what, inputs)
    except Mismatch as exc:
        if got_shape is not None and len(shape) > 1 and got_shape == (int(np.prod(shape)),):
            exc.mistake = "the array was flattened: return the same shape as the input"
        raise


def _require_conversion(got, deg, what, inputs):
    try:
        compare(got, _as_float(deg) * _EXACT, what=what, inputs=inputs, atol=1e-12)
    except Mismatch as exc:
        exc.mistake = _deg_to_rad_mistake(got, deg)
        raise


def _known_angles(sub, rng):
    whole = [float(15 * k) for k in rng.choice(np.arange(-48, 49), size=2, replace=False)]
    for deg in [180.0, -90.0, 0.0, 45.0, *whole]:
        inputs = {"angles_deg": deg}
        got = _answer(sub, deg, (), "deg_to_rad(angle)", inputs)
        _require_conversion(got, deg, f"{deg:g}° is {deg * _EXACT:.12f} rad", inputs)


def _random_angles(sub, rng):
    for _ in range(10):
        deg = rng.uniform(-720.0, 720.0, int(rng.integers(1, 7)))
        inputs = {"angles_deg": deg}
        got = _answer(sub, deg, deg.shape, "deg_to_rad(angles)", inputs)
        _require_conversion(got, deg, "angles × π/180, element by element", inputs)


def _any_shape(sub, rng):
    for deg in (rng.uniform(-360.0, 360.0, (50, 6)), rng.uniform(-360.0, 360.0, (2, 3, 4))):
        inputs = {"angles_deg": deg}
        what = f"deg_to_rad on an array of shape {deg.shape}"
        got = _answer(sub, deg, deg.shape, what, inputs)
        _require_conversion(got, deg, "an array of any shape converts element by element", inputs)


def _a_list(sub, rng):
    deg = [round(float(x), 3) for x in rng.uniform(-360.0, 360.0, 6)]
    inputs = {"angles_deg": f"the list {deg}"}
    what = "deg_to_rad(angles) with angles a list"
    got = _answer(sub, list(deg), (6,), what, inputs)
    _require_conversion(got, deg, "a list of six angles converts like an array", inputs)


# ------------------------------------------------------------------------ 0.2 base_link_pose


def _pose(R=None, p=None):
    return make_transform(R, p)


def _base_link_hypotheses(T):
    R, p = T[:3, :3], T[:3, 3]
    half_turn = T_BASE_LINK_BASE[:3, :3]
    return {
        "multiplied on the wrong side: T_base_tool @ Rz(π) turns the tool, not the base": (
            lambda: T @ T_BASE_LINK_BASE
        ),
        "rotated by π/2 instead of π": lambda: _pose(rot_z(np.pi / 2)) @ T,
        "rotated by −π/2 instead of π": lambda: _pose(rot_z(-np.pi / 2)) @ T,
        "returned T_base_tool unchanged": lambda: T,
        "the angle 180 given in degrees: Rz(180) turns by 180 rad; a half turn is π rad": (
            lambda: _pose(rot_z(180.0)) @ T
        ),
        "a half turn about x instead of z (base_link shares base's z axis)": lambda: (
            _pose(rot_x(np.pi)) @ T
        ),
        "a half turn about y instead of z (base_link shares base's z axis)": lambda: (
            _pose(rot_y(np.pi)) @ T
        ),
        "only the position was turned: the orientation turns with the frame too": lambda: _pose(
            R, half_turn @ p
        ),
        "only the orientation was turned: the position turns with the frame too": lambda: _pose(
            half_turn @ R, p
        ),
        "the inverse of T_base_tool was used: the names must cancel, Rz(π) @ T_base_tool": (
            lambda: T_BASE_LINK_BASE @ np.linalg.inv(T)
        ),
    }


def _base_link_call(sub, T):
    inputs = {"T_base_tool": T}
    got = as_array(sub.base_link_pose(T.copy()), (4, 4), "base_link_pose(T_base_tool)", inputs)
    return got, inputs


def _is_transform_at_same_height(sub, rng):
    for _ in range(5):
        T = random_pose(rng)
        got, inputs = _base_link_call(sub, T)
        try:
            require_transform(got, "base_link_pose(T_base_tool)", inputs)
            compare(
                got[2, 3],
                T[2, 3],
                what="base and base_link share the z axis, so the tool keeps its height z",
                inputs=inputs,
            )
        except Mismatch as exc:
            if exc.mistake is None:
                exc.mistake = _base_link_mistake(got, T)
            raise


def _base_link_mistake(got, T):
    for name, compute in _base_link_hypotheses(T).items():
        if close(got, compute(), 1e-9):
            return name
    return None


def _base_link_matches(sub, rng):
    for _ in range(10):
        T = random_pose(rng)
        got, inputs = _base_link_call(sub, T)
        compare(
            got,
            T_BASE_LINK_BASE @ T,
            what="T_base_link_tool = T_base_link_base @ T_base_tool, with T_base_link_base = Rz(π)",
            inputs=inputs,
            hypotheses=_base_link_hypotheses(T),
        )


# ------------------------------------------------------------------------- 0.3 turn_joint1


def _turn_angles(rng):
    """Eight angles: four within (−π, π), two beyond +π and two beyond −π (up to ±10 rad), none
    within 0.2 rad of a whole turn (where turning changes nothing a check could see)."""
    angles = [
        *rng.uniform(-np.pi, np.pi, 4),
        *rng.uniform(np.pi, 10.0, 2),
        *rng.uniform(-10.0, -np.pi, 2),
    ]
    return [a if abs(_wrapped(a)) > 0.2 else a + 0.5 for a in angles]


def _turn_hypotheses(T, angle):
    R, p = T[:3, :3], T[:3, 3]
    turn = rot_z(angle)
    return {
        "multiplied on the wrong side: T @ Rz(angle) turns the flange about its own z axis; "
        "joint 1 turns the whole arm about the base's z axis, Rz(angle) @ T": lambda: (
            T @ _pose(turn)
        ),
        "turned by −angle: Rz(−angle), or Rz transposed; a positive angle turns "
        "counter-clockwise seen from above": lambda: _pose(rot_z(-angle)) @ T,
        "only the orientation was turned: joint 1 carries the flange's position round the base "
        "z axis too": lambda: _pose(turn @ R, p),
        "only the position was turned: the flange's axes turn with the arm too": lambda: _pose(
            R, turn @ p
        ),
        "the angle was taken as degrees: it is already in radians": lambda: (
            _pose(rot_z(np.radians(angle))) @ T
        ),
        "the angle was converted to degrees before cos and sin (they take radians)": lambda: (
            _pose(rot_z(np.degrees(angle))) @ T
        ),
        "returned T_base_flange unchanged": lambda: T,
        "turned about the base's x axis instead of z": lambda: _pose(rot_x(angle)) @ T,
        "turned about the base's y axis instead of z": lambda: _pose(rot_y(angle)) @ T,
        "the inverse of T was turned: the flange pose itself turns, Rz(angle) @ T": lambda: (
            _pose(turn) @ np.linalg.inv(T)
        ),
    }


def _turn_case(rng, angle):
    """A random arm at a random configuration, its flange pose, and the pose after joint 1
    turns by ``angle`` (urkin's forward kinematics)."""
    robot, q = random_arm(rng), random_q(rng)
    turned = q.copy()
    turned[0] += angle
    T = fk(robot, q)
    inputs = {"T_base_flange": T, "angle": angle}
    return T, fk(robot, turned), inputs


def _turn_call(sub, T, angle, inputs):
    got = sub.turn_joint1(T.copy(), angle)
    return as_array(got, (4, 4), "turn_joint1(T_base_flange, angle)", inputs)


def _turn_moves_the_position(sub, rng):
    for angle in _turn_angles(rng):
        T, _, inputs = _turn_case(rng, angle)
        got = _turn_call(sub, T, angle, inputs)
        try:
            compare(
                got[:3, 3],
                rot_z(angle) @ T[:3, 3],
                what="joint 1 carries the flange round the base z axis: same height, same "
                "distance from the axis, turned by the angle, p' = Rz(angle) p",
                inputs=inputs,
            )
        except Mismatch as exc:
            exc.expected, exc.got = _pose(rot_z(angle)) @ T, got
            exc.mistake = identify_mistake(got, _turn_hypotheses(T, angle), right=exc.expected)
            raise


def _turn_matches_fk(sub, rng):
    for angle in _turn_angles(rng):
        T, expected, inputs = _turn_case(rng, angle)
        got = _turn_call(sub, T, angle, inputs)
        compare(
            got,
            expected,
            what="the flange pose after joint 1 turns: fk at q with q[0] + angle, which is "
            "Rz(angle) @ T_base_flange",
            inputs=inputs,
            hypotheses=_turn_hypotheses(T, angle),
        )


LESSON = Lesson(
    number="00",
    title="How the course works",
    summary="how the course works: notebooks, exercises and check cells, units, frames, a "
    "first look at the UR3",
    exercises=(
        Exercise(
            id="0.1",
            function="deg_to_rad",
            title="degrees to radians, for one angle or an array",
            checks=(
                Check(
                    "converts 180°, −90°, 0°, 45° and other whole angles exactly", 1, _known_angles
                ),
                Check("converts arrays of random angles of any length", 2, _random_angles),
                Check(
                    "converts an (N, 6) array of configurations, and any other shape, at once",
                    1,
                    _any_shape,
                ),
                Check("accepts a list of angles", 1, _a_list),
            ),
        ),
        Exercise(
            id="0.2",
            function="base_link_pose",
            title="a tool pose in the URDF base_link frame",
            checks=(
                Check(
                    "returns a homogeneous transform with the tool at the same height",
                    1,
                    _is_transform_at_same_height,
                    gated=True,  # the pose it is given passes too
                ),
                Check("equals Rz(π) @ T_base_tool on random poses", 2, _base_link_matches),
            ),
            answer=concepts.BASE_LINK_FRAME,
        ),
        Exercise(
            id="0.3",
            function="turn_joint1",
            title="the flange pose after joint 1 turns, without forward kinematics",
            checks=(
                Check(
                    "the flange position turns about the base z axis by the angle",
                    1,
                    _turn_moves_the_position,
                ),
                Check(
                    "equals fk at q with q[0] + angle, for random arms, configurations and angles",
                    2,
                    _turn_matches_fk,
                ),
            ),
        ),
    ),
)
