"""Notebooks for the grader's tests: the course's student notebooks, filled in.

``student_notebook("02")`` is ``course/02_*.ipynb`` with every exercise cell replaced by the
solution's cell — what a student who solved everything hands in; ``replace={"dh_transform":
source}`` puts other code in one exercise's cell; ``solved=False`` leaves the stubs.
"""

from __future__ import annotations

import json
import textwrap
from pathlib import Path

from urkin.course.build import BEGIN, END
from urkin.course.lessons import lesson

ROOT = Path(__file__).resolve().parents[1]


def _source(cell: dict) -> str:
    source = cell.get("source", "")
    return "".join(source) if isinstance(source, list) else source


def solution_path(number: str) -> Path:
    (path,) = sorted((ROOT / "solutions").glob(f"{number}_*.ipynb"))
    return path


def _solved(source: str) -> str:
    return "\n".join(line for line in source.split("\n") if line.strip() not in (BEGIN, END))


def student_notebook(
    number: str, replace: dict[str, str] | None = None, solved: bool = True
) -> dict:
    """The course notebook of lesson ``number`` as a student would hand it in."""
    replace = dict(replace or {})
    (course,) = sorted((ROOT / "course").glob(f"{number}_*.ipynb"))
    student = json.loads(course.read_text(encoding="utf-8"))
    solution = json.loads(solution_path(number).read_text(encoding="utf-8"))
    by_id = {c["id"]: _source(c) for c in solution["cells"]}
    functions = {ex.function for ex in lesson(number).exercises}
    for cell in student["cells"]:
        text = _source(cell)
        if cell["cell_type"] != "code" or 'raise NotImplementedError("Exercise' not in text:
            continue
        name = next((f for f in functions if f"def {f}(" in text), None)
        if name in replace:
            cell["source"] = textwrap.dedent(replace.pop(name)).strip() + "\n"
        elif solved:
            cell["source"] = _solved(by_id[cell["id"]])
    assert not replace, f"no exercise cell for {sorted(replace)}"
    return student


def notebook(*cells: str, lesson: str | None = "02") -> dict:
    """A notebook made of these code cells."""
    return {
        "cells": [
            {
                "cell_type": "code",
                "execution_count": None,
                "id": f"c{i}",
                "metadata": {},
                "outputs": [],
                "source": textwrap.dedent(source),
            }
            for i, source in enumerate(cells)
        ],
        "metadata": {"urkin": {"lesson": lesson}} if lesson else {},
        "nbformat": 4,
        "nbformat_minor": 5,
    }


def write(data: dict | str, path: Path) -> Path:
    path.write_text(data if isinstance(data, str) else json.dumps(data), encoding="utf-8")
    return path
