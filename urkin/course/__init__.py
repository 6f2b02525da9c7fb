"""The course wing: everything in urkin that exists because of the lessons.

* :mod:`urkin.course.lessons` — one module per lesson: its exercises, points, checks, mistake
  detectors and what counts as urkin's own answer to each exercise;
* :func:`check` — the notebook's check cell, ``check("2.1", dh_transform)``;
* :mod:`urkin.course.lab` and :mod:`urkin.course.seeds` — the source reports' models (the UR3
  lab's top-down IK, seed 002's published formulas), which the lessons test and fix;
* :mod:`urkin.course.build` — builds the student notebooks of ``course/`` from ``solutions/``;
* :mod:`urkin.course.grading` — the autograder, which judges submissions from outside the
  process that runs them.

The library (``urkin``) never imports this wing.
"""

from urkin.course.cell import check
from urkin.course.display import below
from urkin.course.exercise import Check, Exercise, Lesson
from urkin.course.lab import fk_lab, ik_lab
from urkin.course.lessons import exercise, lesson, lessons

__all__ = [
    "Check",
    "Exercise",
    "Lesson",
    "below",
    "check",
    "exercise",
    "fk_lab",
    "ik_lab",
    "lesson",
    "lessons",
]
