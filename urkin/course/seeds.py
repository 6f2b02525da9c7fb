"""The course reports' published UR5 model (seed 002), transcribed once, mistakes included.

Lessons 02, 04 and 05 put seed 002's hand-derived flange position and Jacobian to the test, so
they need them exactly as printed (converted from millimetres to metres), errors and all:
``p_x`` and ``p_y`` lack a factor ``sin q5`` on their ``d6 cos(q2 + q3 + q4)`` terms, and the
Jacobian is the exact derivative of that wrong position. Nothing else in urkin uses them.

The report works in its own convention: positive ``a2`` and ``a3`` and lengths close to, but
not exactly, UR's UR5 numbers. The same physical pose therefore has the angles
``q_seed = q_UR + SEED002_SHIFT``, and :data:`SEED002_ARM` is the report's arm in UR's
convention, for :func:`urkin.fk` at ``q_UR``.

The functions accept numbers, numpy arrays (one angle vector per trailing column) or SymPy
symbols: pass ``cos=sympy.cos, sin=sympy.sin`` to get expressions.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from urkin.robots import ALPHA_UR, Robot

__all__ = [
    "SEED002_ARM",
    "SEED002_DH",
    "SEED002_LENGTHS",
    "SEED002_SHIFT",
    "seed002_jacobian",
    "seed002_position",
]

SEED002_LENGTHS = (0.0892, 0.425, 0.392, 0.1093, 0.09475, 0.0825)
"""The report's ``d1, a2, a3, d4, d5, d6`` in metres (its 89.2, 425, 392, … mm)."""

SEED002_DH = np.column_stack(
    [
        (SEED002_LENGTHS[0], 0.0, 0.0, *SEED002_LENGTHS[3:]),
        (0.0, SEED002_LENGTHS[1], SEED002_LENGTHS[2], 0.0, 0.0, 0.0),
        ALPHA_UR,
    ]
)
"""The report's standard-DH rows ``(d_i, a_i, α_i)``: UR's twists, positive ``a2`` and ``a3``."""

SEED002_SHIFT = np.array([0.0, np.pi, 0.0, -np.pi, 0.0, 0.0])
"""``q_seed = q_UR + SEED002_SHIFT``: flipping the signs of ``a2`` and ``a3`` turns the x axes
of frames 2 and 3 by half a turn, which enters at joint 2 and leaves at joint 4."""

_d1, _a2, _a3, _d4, _d5, _d6 = SEED002_LENGTHS
SEED002_ARM = Robot(
    "UR5 (seed 002's lengths)",
    _d1,
    -_a2,
    -_a3,
    _d4,
    _d5,
    _d6,
    source="seed report 002, converted to UR's sign convention",
)
"""The report's arm in UR's convention (negative ``a2``, ``a3``): ``urkin.fk`` at ``q_UR``."""


def seed002_position(
    q: Any,
    lengths: Sequence[Any] = SEED002_LENGTHS,
    cos: Callable[[Any], Any] = np.cos,
    sin: Callable[[Any], Any] = np.sin,
) -> list[Any]:
    """Seed 002's published flange position ``[p_x, p_y, p_z]``, term by term as printed.

    Right in ``p_z``, wrong in ``p_x`` and ``p_y`` by up to ``2·d6`` (see the module notes).

    Parameters
    ----------
    q : sequence of 6 angles
        The report's joint angles (radians): numbers, arrays of equal shape, or SymPy symbols.
    lengths : sequence of 6
        ``d1, a2, a3, d4, d5, d6`` in the report's convention (metres, or symbols).
    cos, sin : callable
        The trigonometric functions to use (``sympy.cos``, ``sympy.sin`` for expressions).

    Returns
    -------
    list of 3
        ``[p_x, p_y, p_z]`` in the units of ``lengths``.

    Examples
    --------
    The test the report could not pass: 0.35 rad on every joint (ERRATA.md).

    >>> [round(1000 * float(p), 3) for p in seed002_position([0.35] * 6)]
    [759.367, 78.336, 415.781]
    """
    d1, a2, a3, d4, d5, d6 = lengths
    c1, s1, c2, s2, c3, s3 = cos(q[0]), sin(q[0]), cos(q[1]), sin(q[1]), cos(q[2]), sin(q[2])
    c5, s5 = cos(q[4]), sin(q[4])
    c234, s234 = cos(q[1] + q[2] + q[3]), sin(q[1] + q[2] + q[3])
    arm = a2 * c2 + a3 * c2 * c3 - a3 * s2 * s3  # in-plane reach of upper arm and forearm
    return [
        d5 * c1 * s234 + d4 * s1 - d6 * c1 * c234 + d6 * c5 * s1 + c1 * arm,
        d5 * s1 * s234 - d4 * c1 - d6 * s1 * c234 - d6 * c1 * c5 + s1 * arm,
        d1 - d6 * s234 * s5 + a3 * sin(q[1] + q[2]) + a2 * s2 - d5 * c234,
    ]


def seed002_jacobian(
    q: Any,
    lengths: Sequence[Any] = SEED002_LENGTHS,
    cos: Callable[[Any], Any] = np.cos,
    sin: Callable[[Any], Any] = np.sin,
) -> list[list[Any]]:
    """Seed 002's hand-derived 3 × 6 position Jacobian, entry by entry as the report lists it.

    The exact derivative of :func:`seed002_position`, so it inherits that formula's mistake:
    ten of its entries differ from the true position Jacobian.

    Parameters
    ----------
    q, lengths, cos, sin
        As for :func:`seed002_position`.

    Returns
    -------
    list of 3 rows of 6 entries
        ``∂p_i/∂q_j`` in the units of ``lengths`` per radian.

    Examples
    --------
    >>> J = np.array(seed002_jacobian([0.35] * 6))
    >>> J.shape, float(J[2, 0]), float(J[0, 5])
    ((3, 6), 0.0, 0.0)
    """
    _, a2, a3, d4, d5, d6 = lengths  # d1 drops out of every derivative
    c1, s1, c2, s2, c3, s3 = cos(q[0]), sin(q[0]), cos(q[1]), sin(q[1]), cos(q[2]), sin(q[2])
    c5, s5 = cos(q[4]), sin(q[4])
    c23 = cos(q[1] + q[2])
    c234, s234 = cos(q[1] + q[2] + q[3]), sin(q[1] + q[2] + q[3])
    zero = 0 * c1  # a zero of the right shape (and type) for arrays and symbols alike
    # columns 2 to 4 of the x and y rows share the wrist terms (d5, d6), as in the report
    wrist_x, wrist_y = d5 * c1 * c234 + d6 * c1 * s234, d5 * s1 * c234 + d6 * s1 * s234
    row_x = [
        -d5 * s1 * s234
        + d4 * c1
        + d6 * s1 * c234
        - a2 * s1 * c2
        + d6 * c5 * c1
        - a3 * s1 * c2 * c3
        + a3 * s1 * s2 * s3,
        wrist_x - a2 * c1 * s2 - a3 * c1 * s2 * c3 - a3 * c1 * c2 * s3,
        wrist_x - a3 * c1 * c2 * s3 - a3 * c1 * s2 * c3,
        wrist_x,
        -d6 * s5 * s1,
        zero,
    ]
    row_y = [
        d5 * c1 * s234
        + d4 * s1
        - d6 * c1 * c234
        + d6 * s1 * c5
        + a2 * c2 * c1
        + a3 * c2 * c3 * c1
        - a3 * c1 * s2 * s3,
        wrist_y - a2 * s2 * s1 - a3 * s2 * c3 * s1 - a3 * s1 * c2 * s3,
        wrist_y - a3 * c2 * s3 * s1 - a3 * s1 * s2 * c3,
        wrist_y,
        d6 * c1 * s5,
        zero,
    ]
    row_z = [
        zero,
        -d6 * c234 * s5 + a3 * c23 + a2 * c2 + d5 * s234,
        -d6 * c234 * s5 + a3 * c23 + d5 * s234,
        -d6 * c234 * s5 + d5 * s234,
        -d6 * s234 * c5,
        zero,
    ]
    return [row_x, row_y, row_z]
