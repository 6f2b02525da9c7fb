"""Adding a lesson takes exactly two files: its notebook source and its lesson module.

In a temporary copy of the course, a throwaway lesson 99 is added as ``solutions/99_*.py`` and
``urkin/course/lessons/lesson99.py``, nothing else; the course's own commands then execute
it, build its student notebook and the README's lesson table, check the whole course, and
grade it: the solution earns full marks and the student notebook nothing.
"""

from __future__ import annotations

import csv
import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

NOTEBOOK = '''# %% [markdown]
# # Lesson 99 — a throwaway lesson
#
# It exists only to prove that a lesson is two files.

# %%
import numpy as np

from urkin.course import check

# %% [markdown]
# ### Exercise 99.1 — `triple` (2 points)
#
# Write `triple(x)`, three times `x`, for a number or an array.
#
# *Checked* (to 1e-9; a float32 answer to float32's precision): random numbers and arrays.

# %%
def triple(x):
    """Three times x."""
    ### BEGIN SOLUTION
    return 3 * np.asarray(x, dtype=float)
    ### END SOLUTION


# %%
check("99.1", triple)
'''

MODULE = '''"""Lesson 99 — a throwaway lesson (the test of adding a lesson)."""

import numpy as np

from urkin.course.compare import as_array, compare
from urkin.course.exercise import Check, Exercise, Lesson


def _numbers(sub, rng):
    for _ in range(5):
        x = rng.normal(size=int(rng.integers(1, 5)))
        got = as_array(sub.triple(x), x.shape, "triple(x)", {"x": x})
        compare(got, 3 * x, what="3 x", inputs={"x": x},
                hypotheses={"doubled": lambda x=x: 2 * x})


LESSON = Lesson(
    number="99",
    title="a throwaway lesson",
    summary="a throwaway lesson, added by a test",
    exercises=(Exercise("99.1", "triple", "three times x", (Check("triples", 2, _numbers),)),),
)
'''


def _run(copy: Path, *args: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(copy), "URKIN_CACHE": str(copy / ".cache")}
    return subprocess.run(
        [sys.executable, "-m", "urkin", *args],
        cwd=copy,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )


@pytest.fixture(scope="module")
def course_copy(tmp_path_factory):
    copy = tmp_path_factory.mktemp("course")
    ignore = shutil.ignore_patterns("__pycache__", "*.ipynb_checkpoints", "_build", "lessons")
    shutil.copytree(ROOT / "urkin", copy / "urkin", ignore=shutil.ignore_patterns("__pycache__"))
    for folder in ("solutions", "course"):
        shutil.copytree(ROOT / folder, copy / folder, ignore=ignore)
    shutil.copyfile(ROOT / "README.md", copy / "README.md")
    before = {p.relative_to(copy) for p in copy.rglob("*") if p.is_file()}
    (copy / "solutions" / "99_throwaway.py").write_text(NOTEBOOK, encoding="utf-8")
    (copy / "urkin" / "course" / "lessons" / "lesson99.py").write_text(
        textwrap.dedent(MODULE), encoding="utf-8"
    )
    return copy, before


def test_a_new_lesson_needs_exactly_its_two_files(course_copy):
    copy, before = course_copy
    run = _run(copy, "course", "check")
    assert run.returncode == 1
    assert "no solutions/99_*.ipynb" in run.stdout  # the module is discovered at once
    for step in (("course", "execute", "99_throwaway"), ("course", "build")):
        run = _run(copy, *step)
        assert run.returncode == 0, (step, run.stdout[-2000:], run.stderr[-3000:])
    run = _run(copy, "course", "check")
    assert run.returncode == 0, run.stdout
    assert "| 99 | a throwaway lesson, added by a test |" in (copy / "README.md").read_text()
    after = {
        p.relative_to(copy)
        for p in copy.rglob("*")
        if p.is_file() and ".cache" not in p.parts and "__pycache__" not in p.parts
    }
    made = {str(p) for p in after - before}
    assert made == {
        "solutions/99_throwaway.py",
        "urkin/course/lessons/lesson99.py",
        "solutions/99_throwaway.ipynb",  # executed by the course's command
        "course/99_throwaway.ipynb",  # built by it
    }


def test_the_new_lesson_is_graded(course_copy):
    copy, _ = course_copy
    if not (copy / "course" / "99_throwaway.ipynb").exists():
        pytest.skip("the lesson was not built")
    run = _run(
        copy,
        "grade",
        "solutions/99_throwaway.ipynb",
        "course/99_throwaway.ipynb",
        "--out",
        "grades",
        "--quiet",
    )
    assert run.returncode == 0, run.stderr[-3000:]
    with open(copy / "grades" / "gradebook.csv", newline="", encoding="utf-8") as handle:
        rows = {row["submission"]: row for row in csv.DictReader(handle)}
    assert rows["solutions/99_throwaway.ipynb"]["total"] == "2"
    assert rows["course/99_throwaway.ipynb"]["total"] == "0"
