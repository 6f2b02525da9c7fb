"""Grade notebooks with plain pytest: one test per exercise of each submission.

    pytest tests/grading --submission submissions/alice_02_dh_forward_kinematics.ipynb
    pytest tests/grading --submission submissions/     # a folder of them
    pytest tests/grading                                # the solution notebooks

A test passes when its exercise earns full points; its failure message is the feedback the
student would read.  The points of every submission are printed at the end.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from urkin.course.grading import DEFAULT_TIME_LIMIT, Grader, find_submissions, new_seed
from urkin.course.grading.read import read_notebook
from urkin.course.lessons import lessons

ROOT = Path(__file__).resolve().parents[2]
_graded: dict[Path, object] = {}


def _submissions(config) -> list[Path]:
    given = config.getoption("submission")
    if given:
        return find_submissions(given)
    return sorted((ROOT / "solutions").glob("[0-9][0-9]_*.ipynb"))


def pytest_generate_tests(metafunc):
    if "submission_exercise" not in metafunc.fixturenames:
        return
    cases, ids = [], []
    for path in _submissions(metafunc.config):
        number = read_notebook(path).lesson
        exercises = lessons()[number].exercises if number in lessons() else []
        for ex in exercises or [None]:
            cases.append((path, ex.id if ex else None))
            ids.append(f"{path.name}::{ex.id if ex else 'lesson?'}")
    metafunc.parametrize("submission_exercise", cases, ids=ids)


@pytest.fixture(scope="session")
def grader(request):
    seed = request.config.getoption("grading_seed")
    limit = request.config.getoption("time_limit") or DEFAULT_TIME_LIMIT
    with Grader(new_seed() if seed is None else seed, time_limit=limit) as grader:
        yield grader


@pytest.fixture
def grade(grader):
    def grade_once(path: Path):
        if path not in _graded:
            _graded[path] = grader.grade(path)
        return _graded[path]

    return grade_once


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    if not _graded:
        return
    terminalreporter.section("urkin grades")
    for path, result in _graded.items():
        parts = ", ".join(f"{e.exercise}: {e.earned:g}/{e.points:g}" for e in result.exercises)
        terminalreporter.write_line(
            f"{path.name}: {result.earned:g} / {result.points:g} points ({result.status})"
            + (f"  [{parts}]" if parts else f"  {result.reason}")
            + f"  seed {result.seed}"
        )
    terminalreporter.write_line(f"isolation: {next(iter(_graded.values())).isolation}")
