"""Lesson 07 — closed-form (geometric) inverse kinematics."""

from __future__ import annotations

from functools import partial

import numpy as np

import urkin
from urkin.analytic_ik import wrap_angles
from urkin.exercises.framework import Check, Exercise, Mismatch, as_array, compare, register
from urkin.lab_ik import LAB_BASE_IN_WORLD, LAB_LINKS, LAB_OFFSET

_fk_lab, _ik_lab = urkin.fk_lab, urkin.ik_lab  # bound before any grading guard is installed

_OFFSET = LAB_LINKS[1] - LAB_LINKS[3] + LAB_LINKS[5]  # L2 − L4 + L6 = 0.110 m
_ARCTAN = (
    "the lab sheet's arctan(y/x): it loses the quadrant when x < 0 (behind the base), use "
    "atan2(y, x)"
)
_UNSIGNED = (
    "the lab sheet's r = √(x² + y²): it loses the sign of the reach when the wrist is behind the "
    "base axis, use r = x cos θ1 + y sin θ1"
)
_ARCTAN_HR = (
    "arctan(h/r) in θ2: once r is signed it can be negative, and arctan loses the quadrant; "
    "use atan2(h, r)"
)

# ---------------------------------------------------------------------------- 7.1 lab_theta1


def _theta1(xc, yc):
    return np.arctan2(yc, xc) - np.arcsin(_OFFSET / np.hypot(xc, yc))


def _theta1_hypotheses(xc, yc):
    return {
        _ARCTAN: lambda: np.arctan(yc / xc) - np.arcsin(_OFFSET / np.hypot(xc, yc)),
        "+ arcsin: that is the other shoulder branch; the lab's arm has the offset on the "
        "other side": lambda: np.arctan2(yc, xc) + np.arcsin(_OFFSET / np.hypot(xc, yc)),
        "returned degrees": lambda: np.degrees(_theta1(xc, yc)),
    }


def _table_point(rng, behind: bool):
    """A wrist point (base frame) in reach, behind the base axis (x < 0) or in front."""
    while True:
        radius, angle = rng.uniform(0.15, 0.45), rng.uniform(-np.pi, np.pi)
        x, y = radius * np.cos(angle), radius * np.sin(angle)
        if (x < -0.05) if behind else (x > 0.05):
            return x, y


def _theta1_matches(behind: bool, student, rng):
    what = (
        "behind the base (x < 0) θ1 must still point the arm at the wrist point"
        if behind
        else "θ1 = atan2(y, x) − asin(0.110 / √(x² + y²))"
    )
    for _ in range(6):
        xc, yc = _table_point(rng, behind=behind)
        got = as_array(student(xc, yc), (), "lab_theta1(x_c, y_c)")
        compare(
            wrap_angles(got),
            wrap_angles(_theta1(xc, yc)),
            what=what,
            inputs={"x_c": xc, "y_c": yc},
            hypotheses=_theta1_hypotheses(xc, yc),
        )


register(
    Exercise(
        id="7.1",
        function="lab_theta1",
        title="the lab's base angle θ1 (lab convention)",
        checks=(
            Check(
                "right for wrist points in front of the base", 1, partial(_theta1_matches, False)
            ),
            Check(
                "right behind the base, where arctan(y/x) fails", 2, partial(_theta1_matches, True)
            ),
        ),
        forbidden=("urkin.lab_ik.ik_lab",),
    )
)


# ---------------------------------------------------------------------------- 7.2 planar_2r


def _planar_target(rng, behind: bool, l1: float, l2: float):
    while True:
        reach = rng.uniform(abs(l1 - l2) + 0.02, l1 + l2 - 0.02)
        angle = rng.uniform(-np.pi, np.pi)
        x, y = reach * np.cos(angle), reach * np.sin(angle)
        if (x < 0) == behind:
            return x, y


def _planar_check(student, rng, behind: bool):
    for _ in range(6):
        l1, l2 = rng.uniform(0.15, 0.5), rng.uniform(0.1, 0.45)
        x, y = _planar_target(rng, behind, l1, l2)
        got = as_array(student(x, y, l1, l2), (2,), "planar_2r(x, y, l1, l2)")
        a, b = got
        reached = np.array(
            [l1 * np.cos(a) + l2 * np.cos(a + b), l1 * np.sin(a) + l2 * np.sin(a + b)]
        )
        if not np.allclose(reached, [x, y], atol=1e-9):
            elbow = np.arccos(np.clip((x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2), -1, 1))
            arctan = np.arctan(y / x) - np.arctan2(l2 * np.sin(elbow), l1 + l2 * np.cos(elbow))
            raise Mismatch(
                "the arm's tip (l1 cos θa + l2 cos(θa + θb), l1 sin θa + l2 sin(θa + θb)) must "
                "reach (x, y)",
                inputs={"x": x, "y": y, "l1": l1, "l2": l2},
                expected=[x, y],
                got=reached,
                mistake=_ARCTAN if np.allclose([a, b], [arctan, elbow], atol=1e-9) else None,
            )
        if b < -1e-12:
            raise Mismatch(
                "return the elbow branch with θb ≥ 0 (θb = +acos(…))",
                inputs={"x": x, "y": y, "l1": l1, "l2": l2},
                got=got,
            )


def _planar_front(student, rng):
    _planar_check(student, rng, behind=False)


def _planar_behind(student, rng):
    _planar_check(student, rng, behind=True)


register(
    Exercise(
        id="7.2",
        function="planar_2r",
        title="the planar two-link sub-problem",
        checks=(
            Check("reaches targets with x > 0", 1, _planar_front),
            Check("reaches targets with x < 0 too", 2, _planar_behind),
        ),
    )
)


# -------------------------------------------------------------------------------- 7.3 ik_lab


def _lab_variant(xw, yw, zw, yaw, arctan=False, unsigned=False, arctan_hr=False, lab_angles=False):
    """The lab sheet's formulas in metres, with its mistakes switchable; also the signed r."""
    L1, _, L3, _, L5, _, L7, L8, L9, L10 = LAB_LINKS
    bx, by, bz = LAB_BASE_IN_WORLD
    x, y, z = xw - bx, yw - by, zw - bz
    xc, yc = x - L9 * np.cos(yaw), y - L9 * np.sin(yaw)
    heading = np.arctan(yc / xc) if arctan else np.arctan2(yc, xc)
    t1 = heading - np.arcsin(_OFFSET / np.hypot(xc, yc))
    t6 = np.pi / 2 + t1 - yaw
    x3 = xc - L7 * np.cos(t1) + _OFFSET * np.sin(t1)
    y3 = yc - L7 * np.sin(t1) - _OFFSET * np.cos(t1)
    signed_r = x3 * np.cos(t1) + y3 * np.sin(t1)
    r = np.hypot(x3, y3) if unsigned else signed_r
    h = z + L8 + L10 - L1
    t3 = np.arccos((r * r + h * h - L3 * L3 - L5 * L5) / (2 * L3 * L5))
    direction = np.arctan(h / r) if arctan_hr else np.arctan2(h, r)
    t2 = -(direction + np.arccos((L5 * L5 - L3 * L3 - r * r - h * h) / (-2 * L3 * np.hypot(r, h))))
    lab = np.array([t1, t2, t3, -t2 - t3, -np.pi / 2, t6])
    return wrap_angles(lab if lab_angles else lab + LAB_OFFSET), signed_r


def _lab_target(rng, kind: str):
    """A gripper target on the table that the lab's arm reaches: with the wrist point in front
    of the base axis, behind it, or so close that the arm reaches back over the shoulder (r < 0)."""
    bx = LAB_BASE_IN_WORLD[0]
    while True:
        if kind == "over the shoulder":  # wrist point just outside the 0.110 m offset circle
            radius, angle = rng.uniform(0.112, 0.14), rng.uniform(-np.pi, np.pi)
            yaw = rng.uniform(-np.pi, np.pi)
            xw = bx + radius * np.cos(angle) + LAB_LINKS[8] * np.cos(yaw)
            yw = LAB_BASE_IN_WORLD[1] + radius * np.sin(angle) + LAB_LINKS[8] * np.sin(yaw)
            zw = rng.uniform(0.0, 0.2)
        else:
            xw, yw = rng.uniform(-0.45, 0.15), rng.uniform(-0.15, 0.45)
            zw, yaw = rng.uniform(0.0, 0.2), rng.uniform(-np.pi, np.pi)
        xc = xw - bx - LAB_LINKS[8] * np.cos(yaw)  # the wrist point's x in the base frame
        try:
            _ik_lab(xw, yw, zw, yaw)
        except ValueError:
            continue
        with np.errstate(all="ignore"):
            _, signed_r = _lab_variant(xw, yw, zw, yaw)
        if kind == "over the shoulder" and signed_r < -1e-3:
            return xw, yw, zw, yaw
        if kind == "behind" and xc < -0.05 and signed_r > 0:
            return xw, yw, zw, yaw
        if kind == "front" and xc > 0.05 and signed_r > 0:
            return xw, yw, zw, yaw


def _lab_check(student, rng, kind: str):
    for _ in range(6):
        target = _lab_target(rng, kind)
        q = as_array(student(*target), (6,), "ik_lab(x_w, y_w, z_w, yaw_w)")
        reached = _fk_lab(q)
        expected = np.array([*target[:3], wrap_angles(target[3])])
        error = np.r_[reached[:3] - expected[:3], wrap_angles(reached[3] - expected[3])]
        if np.abs(error).max() > 1e-8:
            mistake = None
            for name, options in (
                (_ARCTAN, {"arctan": True}),
                (_UNSIGNED, {"unsigned": True}),
                (_ARCTAN_HR, {"arctan_hr": True}),
                (
                    "lab angles returned: UR controller angles are the lab's plus "
                    "[π, 0, 0, −π/2, 0, 0]",
                    {"lab_angles": True},
                ),
            ):
                with np.errstate(all="ignore"):
                    variant, _ = _lab_variant(*target, **options)
                if np.allclose(wrap_angles(variant - q), 0.0, atol=1e-7):
                    mistake = name
                    break
            raise Mismatch(
                f"fk_lab(ik_lab(x, y, z, yaw)) must give back (x, y, z, yaw) ({kind})",
                inputs=dict(zip(("x_w", "y_w", "z_w", "yaw_w"), target)),
                expected=expected,
                got=reached,
                mistake=mistake,
            )


def _lab_front(student, rng):
    _lab_check(student, rng, "front")


def _lab_behind(student, rng):
    _lab_check(student, rng, "behind")


def _lab_over_the_shoulder(student, rng):
    _lab_check(student, rng, "over the shoulder")


def _lab_branch(student, rng):
    for _ in range(4):
        target = _lab_target(rng, "behind" if rng.integers(2) else "front")
        q = as_array(student(*target), (6,), "ik_lab(x_w, y_w, z_w, yaw_w)")
        if not (np.isclose(wrap_angles(q[4]), -np.pi / 2) and q[2] > 0):
            raise Mismatch(
                "the lab's branch has θ5 = −π/2 (gripper plate level) and the elbow θ3 > 0",
                inputs=dict(zip(("x_w", "y_w", "z_w", "yaw_w"), target)),
                got=q,
            )


register(
    Exercise(
        id="7.3",
        function="ik_lab",
        title="the lab's top-down gripper IK, fixed",
        checks=(
            Check("round-trips targets in front of the base", 1, _lab_front),
            Check("round-trips targets behind the base", 1, _lab_behind),
            Check(
                "round-trips targets so close that the arm reaches back (r < 0)",
                1,
                _lab_over_the_shoulder,
            ),
            Check("returns the lab's branch (θ5 = −π/2, θ3 > 0)", 1, _lab_branch),
        ),
        forbidden=(
            "urkin.lab_ik.ik_lab",
            "urkin.analytic_ik.ik_analytic",
            "urkin.analytic_ik.ik_closest",
            "urkin.numerical_ik.ik",
        ),
        builds_on=("7.1", "7.2"),
    )
)
