"""The course builder: student notebooks generated from solutions, checked for drift and leaks."""

import json
import shutil
from pathlib import Path

import pytest

from urkin.course import build as course

ROOT = Path(__file__).resolve().parents[1]


def code_cell(source, outputs=()):
    return {
        "cell_type": "code",
        "execution_count": 3,
        "id": "x",
        "metadata": {"scrolled": True},
        "outputs": list(outputs),
        "source": source,
    }


SOLUTION_CELL = '''def dh_transform(theta, d, a, alpha):
    """Standard DH link transform."""
    ### BEGIN SOLUTION
    ct, st = np.cos(theta), np.sin(theta)
    return build_the_matrix_from(ct, st, d, a, alpha)
    ### END SOLUTION
'''


def solution_notebook():
    return {
        "cells": [
            {"cell_type": "markdown", "id": "m", "metadata": {}, "source": "# Lesson"},
            code_cell(SOLUTION_CELL, [{"output_type": "stream", "name": "stdout", "text": "x"}]),
            code_cell('check("2.1", dh_transform)'),
        ],
        "metadata": {
            "kernelspec": {"name": "conda-env-robots", "display_name": "robots"},
            "widgets": {"state": {}},
        },
        "nbformat": 4,
        "nbformat_minor": 4,
    }


def test_the_repository_course_is_up_to_date_and_leak_free():
    assert course.check(ROOT) == []


def test_student_version_keeps_the_signature_and_raises():
    student = course.build_student_notebook(solution_notebook(), "02")
    source = student["cells"][1]["source"]
    assert source.startswith("def dh_transform(theta, d, a, alpha):\n")
    assert '"""Standard DH link transform."""' in source
    assert '    raise NotImplementedError("Exercise 2.1: write dh_transform")' in source
    assert "np.cos" not in source and "SOLUTION" not in source
    assert all(c.get("outputs", []) == [] for c in student["cells"])
    assert student["cells"][1]["execution_count"] is None
    assert student["cells"][1]["metadata"] == {}
    assert student["metadata"] == {
        "kernelspec": course.KERNELSPEC,
        "language_info": {"name": "python"},
        "urkin": {"lesson": "02"},
    }


def test_a_solution_block_outside_a_known_exercise_is_an_error():
    notebook = solution_notebook()
    notebook["cells"][1]["source"] = SOLUTION_CELL.replace("dh_transform", "my_helper")
    with pytest.raises(ValueError, match="no exercise of lesson 02 names"):
        course.build_student_notebook(notebook, "02")


def test_unbalanced_markers_are_an_error():
    notebook = solution_notebook()
    notebook["cells"][1]["source"] = SOLUTION_CELL.replace("    ### END SOLUTION\n", "")
    with pytest.raises(ValueError, match="without"):
        course.build_student_notebook(notebook, "02")


@pytest.fixture
def course_copy(tmp_path):
    for folder in ("solutions", "course"):
        shutil.copytree(ROOT / folder, tmp_path / folder)
    return tmp_path


def first_lesson(root):
    return course.find_lessons(root)[0]


def test_check_finds_drift(course_copy):
    path = first_lesson(course_copy)
    notebook = json.loads(path.read_text())
    notebook["cells"][0]["source"] += "\nA new sentence."
    path.write_text(json.dumps(notebook))
    assert any("out of date" in p for p in course.check(course_copy))


def test_check_finds_a_leaked_solution_line(course_copy):
    path = first_lesson(course_copy)
    student_path = course_copy / "course" / path.name
    solution = json.loads(path.read_text())
    lines = [line for cell in solution["cells"] for line in course._source(cell).split("\n")]
    leaked = lines[next(i for i, line in enumerate(lines) if line.strip() == course.BEGIN) + 1]
    student = json.loads(student_path.read_text())
    student["cells"].append(
        {
            "cell_type": "code",
            "execution_count": None,
            "id": "leak",
            "metadata": {},
            "outputs": [],
            "source": leaked,
        }
    )
    student_path.write_text(course._dumps(student))
    problems = course.check(course_copy)
    assert any("leaked" in p for p in problems), problems


def test_check_finds_a_missing_check_cell_and_a_stray_notebook(course_copy):
    path = first_lesson(course_copy)
    notebook = json.loads(path.read_text())
    notebook["cells"] = [c for c in notebook["cells"] if 'check("0.1"' not in course._source(c)]
    path.write_text(json.dumps(notebook))
    (course_copy / "course" / "99_stray.ipynb").write_text("{}")
    problems = course.check(course_copy)
    assert any('must be exactly check("0.1", deg_to_rad)' in p for p in problems), problems
    assert any("99_stray.ipynb has no source" in p for p in problems), problems


def test_build_then_check_is_clean(course_copy):
    for student in (course_copy / "course").glob("*.ipynb"):
        student.unlink()
    course.build(course_copy)
    assert course.check(course_copy) == []


def test_execute_names_an_unknown_lesson(course_copy, capsys):
    assert course.main(["execute", "99_nothing", "--root", str(course_copy)]) == 2
    error = capsys.readouterr().err
    assert "no lesson named 99_nothing" in error and "00_" in error


def test_stored_solution_notebooks_keep_no_embedded_pictures_in_html():
    # nbval compares HTML after replacing base64 payloads (tests/nbval_sanitize.cfg); the
    # frames of an animation would only make the stored notebooks megabytes larger
    for path in sorted((ROOT / "solutions").glob("[0-9][0-9]_*.ipynb")):
        for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]:
            for output in cell.get("outputs", []):
                html = "".join(output.get("data", {}).get("text/html", ""))
                assert "base64," not in html.replace("base64,DATA", ""), path.name


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["build", "99"], "build works on every lesson at once and takes no lesson names; got 99"),
        (["check", "02_dh"], "check works on every lesson at once and takes no lesson names"),
        (["render", "a", "b"], "render takes one folder; got a b"),
    ],
)
def test_course_commands_refuse_arguments_they_would_ignore(capsys, argv, message):
    from urkin.course import build

    with pytest.raises(SystemExit) as stop:
        build.main([*argv, "--root", str(ROOT)])
    assert stop.value.code == 2
    assert message in capsys.readouterr().err


def test_check_wants_the_exercise_as_a_string(capsys):
    """check(4.10, f) would check exercise 4.1: a number is refused, saying why."""
    from urkin.course import check

    check(4.10, lambda *args: None)
    out = capsys.readouterr().out
    assert "give the exercise as a string such as '2.1'" in out and "4.10 is 4.1" in out
