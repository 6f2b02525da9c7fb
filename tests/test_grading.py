"""The autograder against a class of correct, partly wrong, broken and hanging submissions.

The submissions are lesson-02 notebooks made here from the reference solutions in
``tests/solutions_reference.py``, each with one deliberate problem.  Graded in one run, every
one must get its row, the right points per exercise and feedback that names the problem.
"""

from __future__ import annotations

import csv
import inspect
import json
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from tests import solutions_reference as ref
from urkin.exercises import VISIBLE_SEED, exercise, run_exercise
from urkin.grading import grade_many, grade_notebook, write_reports

SEED = 424242
TIME_LIMIT = 3.0

HEADER = "import numpy as np\nimport urkin\nfrom urkin.exercises import check"
DH = inspect.getsource(ref.dh_transform)
FK = inspect.getsource(ref.forward_kinematics)
POSITION = inspect.getsource(ref.ur5_position)
FULL = {"2.1": 4.0, "2.2": 5.0, "2.3": 4.0}


def notebook(*cells: str, lesson: str | None = "02") -> str:
    data = {
        "cells": [
            {"cell_type": "code", "execution_count": None, "id": f"c{i}", "metadata": {},
             "outputs": [], "source": textwrap.dedent(source)}
            for i, source in enumerate(cells)
        ],
        "metadata": {"urkin": {"lesson": lesson}} if lesson else {},
        "nbformat": 4,
        "nbformat_minor": 5,
    }  # fmt: skip
    return json.dumps(data)


def _hard_coded_dh_transform() -> str:
    """A dh_transform that memorised the answers of the notebook's visible check."""
    answers = {}

    def recording(theta, d, a, alpha):
        T = ref.dh_transform(theta, d, a, alpha)
        answers[repr((theta, d, a, alpha))] = T.tolist()
        return T

    run_exercise("2.1", recording, seed=VISIBLE_SEED)
    return (
        f"ANSWERS = {answers!r}\n\n"
        "def dh_transform(theta, d, a, alpha):\n"
        "    return np.array(ANSWERS.get(repr((theta, d, a, alpha)), np.zeros((4, 4))))\n"
    )


def _replace(source: str, old: str, new: str) -> str:
    assert old in source
    return source.replace(old, new)


# name -> (notebook text, expected points per exercise, words the feedback must contain)
CLASS = {
    "correct_02.ipynb": (
        notebook(HEADER, DH, FK, POSITION, 'check("2.1", dh_transform)'),
        FULL,
        [],
    ),
    "invalid_json_02.ipynb": ('{"cells": [ this is not json', {}, ["not a valid notebook"]),
    "syntax_error_02.ipynb": (
        notebook(
            HEADER,
            DH.replace(
                "def dh_transform(theta, d, a, alpha):", "def dh_transform(theta, d, a, alpha)"
            ),
            FK,
            POSITION,
        ),
        {"2.1": 0, "2.2": 0, "2.3": 4},
        ["syntax error on line 1", "no function named `dh_transform`"],
    ),
    "missing_function_02.ipynb": (
        notebook(
            HEADER, DH, FK.replace("def forward_kinematics", "def forward_kinematic"), POSITION
        ),
        {"2.1": 4, "2.2": 0, "2.3": 4},
        ["did you mean `forward_kinematic`"],
    ),
    "infinite_loop_02.ipynb": (
        notebook(HEADER, DH, FK, "def ur5_position(q):\n    while True:\n        pass\n"),
        {"2.1": 4, "2.2": 5, "2.3": 0},
        ["stopped after 3 s"],
    ),
    "sys_exit_02.ipynb": (
        notebook(
            HEADER, DH, FK, "import sys\n\ndef ur5_position(q):\n    sys.exit(1)\n", "sys.exit(0)"
        ),
        {"2.1": 4, "2.2": 5, "2.3": 0},
        ["sys.exit()"],
    ),
    "os_exit_02.ipynb": (
        notebook(HEADER, DH, FK, "import os\n\ndef ur5_position(q):\n    os._exit(0)\n"),
        {"2.1": 4, "2.2": 5, "2.3": 0},
        ["os._exit()"],
    ),
    "huge_allocation_02.ipynb": (
        notebook(
            HEADER, DH, FK, "def ur5_position(q):\n    big = np.ones(2**31)\n    return big[:3]\n"
        ),
        {"2.1": 4, "2.2": 5, "2.3": 0},
        ["memory"],
    ),
    "chatty_02.ipynb": (
        notebook(
            HEADER,
            _replace(DH, "    ct, st", "    print('x' * 2_000_000)\n    ct, st"),
            FK,
            POSITION,
            "print('y' * 50_000_000)",
        ),
        FULL,
        [],
    ),
    "calls_urkin_fk_02.ipynb": (
        notebook(
            HEADER,
            DH,
            "def forward_kinematics(robot, q):\n    return urkin.fk(robot, q)\n",
            POSITION,
        ),
        {"2.1": 4, "2.2": 0, "2.3": 4},
        ["calls urkin.kinematics.fk"],
    ),
    "aliases_urkin_fk_02.ipynb": (
        notebook(
            HEADER,
            DH,
            "from urkin import fk as my_fk\n\n"
            "def forward_kinematics(robot, q):\n    return my_fk(robot, q)\n",
            POSITION,
        ),
        {"2.1": 4, "2.2": 0, "2.3": 4},
        ["calls urkin.kinematics.fk"],
    ),
    "hard_coded_02.ipynb": (
        notebook(HEADER, _hard_coded_dh_transform(), POSITION),
        {"2.1": 0, "2.2": 0, "2.3": 4},
        ["standard DH"],
    ),
    "exits_at_top_level_02.ipynb": (
        notebook(
            HEADER,
            DH,
            FK,
            POSITION,
            "import os\nstatus = os._exit(3)\n\ndef report():\n    return status",
        ),
        FULL,
        ["graded again with its imports, functions and classes only"],
    ),
    "degrees_02.ipynb": (
        notebook(
            HEADER,
            _replace(
                DH,
                "ct, st, ca, sa = np.cos(theta), np.sin(theta), np.cos(alpha), np.sin(alpha)",
                "theta, alpha = np.radians(theta), np.radians(alpha)\n"
                "    ct, st, ca, sa = np.cos(theta), np.sin(theta), "
                "np.cos(alpha), np.sin(alpha)",
            ),
            FK,
            POSITION,
        ),
        {"2.1": 1, "2.2": None, "2.3": 4},
        ["θ and α treated as degrees", "fix that one first"],
    ),
    "modified_dh_02.ipynb": (
        notebook(
            HEADER,
            inspect.getsource(ref._modified_dh).replace("_modified_dh", "dh_transform"),
            FK,
            POSITION,
        ),
        {"2.1": 1, "2.2": None, "2.3": 4},
        ["modified (Craig) DH", "fix that one first"],
    ),
    "transposed_rotation_02.ipynb": (
        notebook(
            HEADER,
            DH.replace("def dh_transform", "def _right"),
            "def dh_transform(theta, d, a, alpha):\n    T = _right(theta, d, a, alpha)\n"
            "    T[:3, :3] = T[:3, :3].T\n    return T\n",
            FK,
            POSITION,
        ),
        {"2.1": 1, "2.2": None, "2.3": 4},
        ["rotation block is transposed", "fix that one first"],
    ),
    "a_sign_02.ipynb": (
        notebook(
            HEADER,
            DH,
            _replace(
                FK,
                "zip(q, robot.d, robot.a, robot.alpha)",
                "zip(q, robot.d, -robot.a, robot.alpha)",
            ),
            POSITION,
        ),
        {"2.1": 4, "2.2": 1, "2.3": 4},
        ["a2 and a3 with the wrong sign"],
    ),
    "seed002_formula_02.ipynb": (
        notebook(
            HEADER,
            DH,
            FK,
            inspect.getsource(ref._seed002_position).replace("_seed002_position", "ur5_position"),
        ),
        {"2.1": 4, "2.2": 5, "2.3": 1},
        ["lack the factor sin q5"],
    ),
    "no_lesson.ipynb": (notebook(HEADER, DH, lesson=None), {}, ["cannot tell which lesson"]),
}


@pytest.fixture(scope="module")
def graded_class(tmp_path_factory):
    folder = tmp_path_factory.mktemp("class")
    for name, (text, _, _) in CLASS.items():
        (folder / name).write_text(text, encoding="utf-8")
    results = grade_many([folder], seed=SEED, time_limit=TIME_LIMIT, jobs=2)
    out = write_reports(results, folder / "grades")
    return {r.name: r for r in results}, out


def test_every_submission_gets_a_row(graded_class):
    results, out = graded_class
    assert set(results) == set(CLASS)
    with open(out / "gradebook.csv", newline="", encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    assert sorted(r["submission"] for r in rows) == sorted(CLASS)
    assert {"2.1", "2.2", "2.3", "total", "max", "status", "reason"} <= set(rows[0])
    for row in rows:
        assert row["status"] == "graded" or row["reason"], row


@pytest.mark.parametrize("name", sorted(CLASS))
def test_points_per_exercise(graded_class, name):
    result = graded_class[0][name]
    _, expected, _ = CLASS[name]
    if not expected:
        assert result.status != "graded"
        assert result.earned == 0
        return
    assert result.status == "graded", result.reason
    for exercise_id, points in expected.items():
        got = result.exercise(exercise_id)
        if points is None:  # built on a wrong dh_transform: must lose points, any number
            assert got.earned < exercise(exercise_id).points
        else:
            assert got.earned == points, got.report()


@pytest.mark.parametrize("name", sorted(CLASS))
def test_feedback_names_the_problem(graded_class, name):
    _, out = graded_class
    feedback = (out / "feedback" / f"{name}.md").read_text(encoding="utf-8")
    for words in CLASS[name][2]:
        assert words in feedback, feedback
    assert "def test_" not in feedback and "assert " not in feedback


def test_feedback_puts_the_score_first(graded_class):
    _, out = graded_class
    lines = (out / "feedback" / "a_sign_02.ipynb.md").read_text(encoding="utf-8").splitlines()
    assert lines[2].startswith("Lesson 02: 9 / 13 points")


def test_results_json_is_gradescope_shaped(graded_class):
    _, out = graded_class
    document = json.loads((out / "results.json").read_text(encoding="utf-8"))
    assert len(document["submissions"]) == len(CLASS)
    one = json.loads((out / "results" / "correct_02.ipynb.json").read_text(encoding="utf-8"))
    assert one["score"] == 13
    assert [t["max_score"] for t in one["tests"]] == [4, 5, 4]
    assert all({"name", "score", "max_score", "output"} <= set(t) for t in one["tests"])


def test_a_single_submission_writes_exactly_gradescopes_file(tmp_path):
    path = tmp_path / "02_dh_fk.ipynb"
    path.write_text(CLASS["correct_02.ipynb"][0], encoding="utf-8")
    write_reports([grade_notebook(path, seed=1)], tmp_path / "out")
    document = json.loads((tmp_path / "out" / "results.json").read_text(encoding="utf-8"))
    assert document["score"] == 13 and len(document["tests"]) == 3


def test_each_run_draws_fresh_inputs_but_a_seed_reproduces_a_run(tmp_path):
    path = tmp_path / "a_sign_02.ipynb"
    path.write_text(CLASS["a_sign_02.ipynb"][0], encoding="utf-8")
    first = grade_notebook(path, seed=11).exercise("2.2").report()
    again = grade_notebook(path, seed=11).exercise("2.2").report()
    other = grade_notebook(path).exercise("2.2").report()
    assert first == again
    assert first != other


def test_the_guard_does_not_disturb_the_reference(tmp_path):
    # a submission that imports everything urkin has must still be graded normally
    path = tmp_path / "02_everything.ipynb"
    path.write_text(
        notebook(
            HEADER + "\nfrom urkin import *\nfrom urkin.kinematics import *", DH, FK, POSITION
        ),
        encoding="utf-8",
    )
    assert grade_notebook(path, seed=3).earned == 13


def test_a_slow_setup_falls_back_to_definitions_only(tmp_path):
    path = tmp_path / "slow_02.ipynb"
    slow = "def spin():\n    while True:\n        pass\n\n\nstuck = spin()\nlog = [stuck]\n\n\n"
    slow += "def show():\n    print(log)"
    path.write_text(notebook(HEADER, DH, FK, POSITION, slow), encoding="utf-8")
    result = grade_notebook(path, seed=3, setup_limit=2)
    assert result.earned == 13
    assert any("took longer than 2 s" in note for note in result.notes)


ROOT = Path(__file__).resolve().parents[1]
STUDENT_NOTEBOOKS = sorted((ROOT / "course").glob("[0-9][0-9]_*.ipynb"))


@pytest.mark.parametrize("path", STUDENT_NOTEBOOKS, ids=lambda p: p.name)
def test_unsolved_student_notebooks_score_zero_without_crashing(path):
    result = grade_notebook(path, seed=5)
    assert result.status == "graded", result.reason
    assert result.exercises and result.earned == 0
    assert {e.status for e in result.exercises} == {"not attempted"}


def test_the_urkin_grade_command(tmp_path):
    out = tmp_path / "grades"
    command = [sys.executable, "-m", "urkin", "grade", str(STUDENT_NOTEBOOKS[0]),
               str(ROOT / "solutions" / STUDENT_NOTEBOOKS[0].name), "--out", str(out),
               "--seed", "3"]  # fmt: skip
    done = subprocess.run(command, capture_output=True, text=True, check=True)
    assert "graded 2 of 2 submissions (seed 3)" in done.stdout
    assert "2/2" in done.stderr  # the progress bar
    rows = list(csv.DictReader(open(out / "gradebook.csv", encoding="utf-8")))
    assert sorted(float(r["total"]) for r in rows) == [0.0, float(rows[0]["max"])]
    assert len(list((out / "feedback").glob("*.md"))) == 2


def test_only_the_assignments_the_definitions_need_are_executed(tmp_path):
    from urkin.grading.notebook import needed_statements, read_submission

    path = tmp_path / "02_pruned.ipynb"
    path.write_text(
        notebook(
            HEADER,
            "SCALE = 2.0\nOFFSET = SCALE + 1\nfig = make_a_slow_figure()",
            "def dh_transform(theta, d, a, alpha):\n"
            "    fig = 1.0\n"
            "    return OFFSET * fig * np.eye(4)",
        ),
        encoding="utf-8",
    )
    statements = read_submission(path).statements
    kept = needed_statements(statements, {"dh_transform"})
    bound = set().union(*(s.binds for s in kept))
    assert {"SCALE", "OFFSET", "dh_transform", "np", "urkin"} <= bound
    assert "fig" not in bound


@pytest.mark.parametrize(
    ("lesson", "cells", "exercise_id", "words"),
    [
        (
            "03",
            [inspect.getsource(ref.screw_axis).replace(
                "return np.concatenate([w, -np.cross(w, q)])",
                "return np.concatenate([-np.cross(w, q), w])")],
            "3.1",
            "(v, ω) order",
        ),
        (
            "04",
            [inspect.getsource(ref.dh_transform), inspect.getsource(ref._frames),
             inspect.getsource(ref.geometric_jacobian).replace(
                 "return J", "return J[[3, 4, 5, 0, 1, 2]]")],
            "4.1",
            "twist order (ω; v)",
        ),
        (
            "06",
            ["def dls_step(J, e, lam):\n"
             "    J_dls = J.T * (J * J.T + lam**2 * I)**-1\n"
             "    return J_dls @ e\n"],
            "6.1",
            "seed 000's first DLS line",
        ),
        (
            "06",
            ["def lm_step(J, e, mu):\n"
             "    return np.linalg.inv(J.T @ J + mu * np.eye(6)) - J.T @ e\n"],
            "6.2",
            "seed 001's update",
        ),
        (
            "07",
            ["def lab_theta1(x_c, y_c):\n"
             "    return np.arctan(y_c / x_c) - np.arcsin(0.110 / np.hypot(x_c, y_c))\n"],
            "7.1",
            "the lab sheet's arctan(y/x)",
        ),
    ],
)  # fmt: skip
def test_a_wrong_convention_loses_points_with_a_named_mistake(tmp_path, lesson, cells,
                                                              exercise_id, words):  # fmt: skip
    path = tmp_path / f"{lesson}_wrong_convention.ipynb"
    path.write_text(notebook(HEADER, *cells, lesson=lesson), encoding="utf-8")
    result = grade_notebook(path, seed=8)
    outcome = result.exercise(exercise_id)
    assert result.status == "graded" and 0 <= outcome.earned < outcome.points
    assert words in outcome.report(), outcome.report()
