"""Realistic variants of the lessons' exercise functions, for testing the checks and the grader.

``tests/variants/lessonNN.py`` holds two lists for lesson NN:

* ``CORRECT``: other correct ways a student might write an exercise (another formula, float32,
  loops, lists, SymPy's lambdify, an assert on bad input, ``NotImplementedError`` outside the
  contract …).  Each must earn full marks.
* ``WRONG``: known mistakes.  Each must earn exactly ``points`` (or less than full marks when
  ``points`` is None) and the feedback must name ``mistake`` (when given).

A variant's ``source`` replaces the exercise's cell in the solution notebook (it may also define
helpers); ``also`` puts other code in other exercises' cells (a wrong ``twist_exp`` in its own
cell, under an ``fk_space`` that uses it); everything else stays as the solution has it.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Variant:
    exercise: str  # "2.1"
    name: str  # what is different, in a few words (also the test id)
    source: str  # the function's new definition, and any helpers it needs
    points: float | None = None  # WRONG only: exact points it must earn (None: fewer than full)
    mistake: str | None = None  # WRONG only: words the named mistake must contain
    also: tuple[tuple[str, str], ...] = ()  # (function, source) of other exercise cells
