"""A lesson's solution functions in this process, for testing its checks.

    .venv/bin/python -m tests.namespaces 02            # every exercise of lesson 02, seeds 0, 1, 7
    .venv/bin/python -m tests.namespaces 02 2.2 seed=5 # one exercise, one seed

:func:`solution_namespace` executes the definitions of ``solutions/NN_*.py`` that the
exercises need, selected as the grader selects them (no demonstrations, no plots);
:func:`variant` puts another version of an exercise's cell in its place.  The script prints each
exercise's report for the solution's own functions.
"""

import contextlib
import functools
import io
import os
import sys
from pathlib import Path

os.environ.setdefault("MPLBACKEND", "Agg")
ROOT = Path(__file__).resolve().parents[1]


@functools.cache
def _solution_cells(lesson: str) -> tuple[tuple[str, str, str], ...]:
    """(cell type, id, source) of ``solutions/NN_*.py`` — the text authors edit."""
    import jupytext

    (pair,) = sorted((ROOT / "solutions").glob(f"{int(lesson):02d}_*.py"))
    cells = jupytext.read(pair)["cells"]
    return tuple((c["cell_type"], f"c{i:03d}", c["source"]) for i, c in enumerate(cells))


def namespace_for(
    lesson: str, replace: dict[str, str] | None = None, exercise_id: str | None = None
) -> dict:
    """The lesson's definitions executed here as the grader selects them — every exercise
    function and what it needs (only those of ``exercise_id`` if given, as the grader runs
    one exercise), demonstrations and plots skipped — with the exercise cells of the
    functions in ``replace`` holding other code (a student's variant)."""
    import ast
    import json
    import linecache
    import tempfile

    from urkin.course.build import BEGIN, END
    from urkin.course.grading.read import read_notebook
    from urkin.course.lessons import lesson as declared

    exercises = declared(lesson).exercises
    replace = dict(replace or {})
    cells = []
    for kind, cell_id, source in _solution_cells(lesson):
        if kind == "code" and BEGIN in source:
            function = next(
                (ex.function for ex in exercises if f"def {ex.function}(" in source), None
            )
            if function in replace:
                source = replace.pop(function)
            source = "\n".join(x for x in source.split("\n") if x.strip() not in (BEGIN, END))
        cells.append(
            {
                "cell_type": kind,
                "id": cell_id,
                "metadata": {},
                "source": source,
                **({"outputs": [], "execution_count": None} if kind == "code" else {}),
            }
        )
    assert not replace, f"no exercise cell for {sorted(replace)}"
    data = {
        "cells": cells,
        "metadata": {"urkin": {"lesson": lesson}},
        "nbformat": 4,
        "nbformat_minor": 5,
    }
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / f"{lesson}_variant.ipynb"
        path.write_text(json.dumps(data), encoding="utf-8")
        notebook = read_notebook(path)
    graded = {ex.function: notebook.graded_site(ex.function, ex.id) for ex in exercises}
    graded = {k: v for k, v in graded.items() if v is not None}
    chosen = [ex for ex in exercises if exercise_id in (None, ex.id)]
    roots = {ex.function for ex in chosen} | {u for ex in chosen for u in ex.uses}
    namespace = {"__name__": "__main__"}
    for site in notebook.plan(roots, graded):
        source = notebook.cells[site.cell]
        filename = f"<lesson {lesson} cell {site.cell} {hash(source)}>"
        linecache.cache[filename] = (len(source), None, source.splitlines(True), filename)
        code = compile(ast.Module(body=[site.node], type_ignores=[]), filename, "exec")
        with contextlib.redirect_stdout(io.StringIO()):
            try:
                exec(code, namespace)
            except Exception:  # as in the grader, a failing definition is only a note
                pass
    return namespace


@functools.cache
def solution_namespace(lesson: str) -> dict:
    """The solution's own definitions (see :func:`namespace_for`)."""
    return namespace_for(lesson)


@functools.lru_cache(maxsize=64)
def variant(lesson: str, exercise_id: str, source: str, also: tuple = ()) -> dict:
    """The namespace with ``source`` in the exercise cell of ``exercise_id`` (and, from
    ``also``, other code in other exercises' cells: pairs of function and source)."""
    from urkin.course.lessons import exercise

    replace = {exercise(exercise_id).function: source, **dict(also)}
    return namespace_for(lesson, replace, exercise_id)


if __name__ == "__main__":
    from urkin.course.cell import check_result
    from urkin.course.lessons import lesson

    number = sys.argv[1]
    ids = [a for a in sys.argv[2:] if "=" not in a]
    seeds = [int(a.split("=")[1]) for a in sys.argv[2:] if a.startswith("seed=")] or [0, 1, 7]
    ns = solution_namespace(number)
    for ex in lesson(number).exercises:
        if ids and ex.id not in ids:
            continue
        for seed in seeds:
            print(check_result(ex.id, None, ns, seed).report())
