"""Build the student notebooks in ``course/`` from the lesson sources in ``solutions/``.

A lesson is two files: ``solutions/NN_topic.py`` (jupytext's percent format: the text authors
edit; ``solutions/NN_topic.ipynb`` is its executed pair, which nbval runs) and its module
``urkin/course/lessons/lessonNN.py`` (its exercises, points and checks).  Exercise code sits
between ``### BEGIN SOLUTION`` and ``### END SOLUTION`` inside the function the student
writes; the student version keeps the signature and docstring and raises
``NotImplementedError("Exercise N.k: …")`` instead.  Student notebooks carry no outputs, a
normalised ``python3`` kernelspec and no other metadata than the lesson number.

:func:`check` holds the lesson's notebook to its module: each exercise has its heading
``### Exercise N.k — `function` (P points)`` with the declared points, a paragraph saying what
is *Checked*, one solution block, and the check cell ``check("N.k", function)`` right after it;
``course/`` matches ``solutions/``; no solution line leaks; the README's lesson table is the
list of lessons.

Commands (also ``urkin course …``)::

    python -m urkin.course.build execute   # paired .py → .ipynb, executed in place (jupytext)
    python -m urkin.course.build build     # solutions/ → course/, and the README's lesson table
    python -m urkin.course.build check     # fails on drift, a leak, a missing or wrong heading
    python -m urkin.course.build render    # course/ executed once into docs/lessons/ (the site)
"""

from __future__ import annotations

import argparse
import copy
import json
import re
import sys
from pathlib import Path

__all__ = [
    "KERNELSPEC",
    "build",
    "build_student_notebook",
    "check",
    "execute",
    "find_lessons",
    "normalise_solution",
    "render",
    "strip_solutions",
]

BEGIN, END = "### BEGIN SOLUTION", "### END SOLUTION"
KERNELSPEC = {"display_name": "Python 3 (ipykernel)", "language": "python", "name": "python3"}
_DEF = re.compile(r"^\s*def\s+([A-Za-z_]\w*)\s*\(")


def find_lessons(root: Path) -> list[Path]:
    """The solution notebooks ``solutions/NN_*.ipynb`` under a course root, in order."""
    return sorted((root / "solutions").glob("[0-9][0-9]_*.ipynb"))


def _source(cell: dict) -> str:
    source = cell.get("source", "")
    return "".join(source) if isinstance(source, list) else source


def _lesson_number(path: Path) -> str:
    return path.name[:2]


def _declared(lesson: str):
    from urkin.course.lessons import lessons

    declared = lessons().get(lesson)
    if declared is None:
        raise ValueError(
            f"solutions/{lesson}_*: no lesson module urkin/course/lessons/lesson{lesson}.py"
        )
    return declared


def _exercise_for(function: str, lesson: str, where: str) -> str:
    for ex in _declared(lesson).exercises:
        if ex.function == function:
            return ex.id
    raise ValueError(
        f"{where}: a solution block sits in `{function}`, which no exercise of "
        f"lesson {lesson} names (see urkin/course/lessons/lesson{lesson}.py)"
    )


def strip_solutions(source: str, lesson: str, where: str) -> tuple[str, list[str], list[str]]:
    """Replace solution blocks; return the new source, the exercise ids and the removed lines."""
    out, removed, ids = [], [], []
    function, inside = None, False
    for line in source.split("\n"):
        match = _DEF.match(line)
        if match and not inside:
            function = match.group(1)
        stripped = line.strip()
        if stripped == BEGIN:
            if inside or function is None:
                raise ValueError(f"{where}: {BEGIN} outside a function, or nested")
            inside = True
            indent = line[: len(line) - len(line.lstrip())]
            exercise_id = _exercise_for(function, lesson, where)
            ids.append(exercise_id)
            out.append(
                f'{indent}raise NotImplementedError("Exercise {exercise_id}: write {function}")'
            )
            continue
        if stripped == END:
            if not inside:
                raise ValueError(f"{where}: {END} without {BEGIN}")
            inside = False
            continue
        if inside:
            removed.append(line)
        else:
            out.append(line)
    if inside:
        raise ValueError(f"{where}: {BEGIN} without {END}")
    return "\n".join(out), ids, removed


def build_student_notebook(solution: dict, lesson: str, name: str = "notebook") -> dict:
    """The student version of a solution notebook (a new dict; the input is not changed)."""
    student = {
        "cells": [],
        "metadata": {
            "kernelspec": dict(KERNELSPEC),
            "language_info": {"name": "python"},
            "urkin": {"lesson": lesson},
        },
        "nbformat": 4,
        "nbformat_minor": 5,
    }
    for index, cell in enumerate(solution["cells"]):
        kind = cell["cell_type"]
        new = {"cell_type": kind, "id": cell.get("id", f"cell-{index}"), "metadata": {}}
        source = _source(cell)
        if kind == "code":
            source, _, _ = strip_solutions(source, lesson, f"{name}, cell {index + 1}")
            new["execution_count"] = None
            new["outputs"] = []
        new["source"] = source
        tags = cell.get("metadata", {}).get("tags")
        if tags:
            new["metadata"]["tags"] = list(tags)
        student["cells"].append(new)
    return student


def normalise_solution(notebook: dict, lesson: str) -> dict:
    """Solution notebook with stable cell ids, the python3 kernelspec and minimal metadata."""
    out = copy.deepcopy(notebook)
    out["metadata"] = {
        "kernelspec": dict(KERNELSPEC),
        "language_info": {"name": "python"},
        "urkin": {"lesson": lesson},
    }
    if "jupytext" in notebook.get("metadata", {}):  # keep the pairing, not jupytext's versions
        out["metadata"]["jupytext"] = {"formats": "ipynb,py:percent"}
    for index, cell in enumerate(out["cells"]):
        cell["id"] = f"c{index:03d}"
        tags = cell.get("metadata", {}).get("tags")
        cell["metadata"] = {"tags": list(tags)} if tags else {}
        cell["source"] = _source(cell)
    out["nbformat"], out["nbformat_minor"] = 4, 5
    return out


_EMBEDDED = re.compile(r"base64,[A-Za-z0-9+/=]+")


def _drop_embedded_pictures(notebook: dict) -> None:
    """Replace the pictures embedded in HTML outputs (an animation's frames) by ``DATA``.

    The stored solution notebooks exist for nbval, which compares HTML outputs only after
    the same substitution (``tests/nbval_sanitize.cfg``); the frames would make lesson 08's
    notebook 6 MB in every commit.  Image outputs (figures, keyframe strips) stay; re-running
    a cell brings its animation back.
    """
    for cell in notebook["cells"]:
        for output in cell.get("outputs", []):
            html = output.get("data", {}).get("text/html")
            if html is not None:
                text = "".join(html) if isinstance(html, list) else html
                output["data"]["text/html"] = _EMBEDDED.sub("base64,DATA", text)


def _dumps(notebook: dict) -> str:
    return json.dumps(notebook, indent=1, sort_keys=True, ensure_ascii=False) + "\n"


TABLE_START = "<!-- lessons: written by `urkin course build` from urkin/course/lessons -->"
TABLE_END = "<!-- /lessons -->"


def lesson_table() -> str:
    """The README's table of lessons, from the lesson modules."""
    from urkin.course.lessons import lessons

    rows = ["| lesson | topic |", "|---|---|"]
    rows += [f"| {n} | {lesson.summary} |" for n, lesson in lessons().items()]
    return "\n".join(rows)


def _readme_with_table(text: str) -> str | None:
    start, end = text.find(TABLE_START), text.find(TABLE_END)
    if start < 0 or end < start:
        return None
    return text[: start + len(TABLE_START)] + "\n" + lesson_table() + "\n" + text[end:]


def build(root: Path) -> list[Path]:
    """Write ``course/NN_topic.ipynb`` for every solution notebook, and the README's lesson
    table; return the notebooks written."""
    written = []
    (root / "course").mkdir(exist_ok=True)
    for path in find_lessons(root):
        notebook = json.loads(path.read_text(encoding="utf-8"))
        student = build_student_notebook(notebook, _lesson_number(path), path.name)
        target = root / "course" / path.name
        target.write_text(_dumps(student), encoding="utf-8")
        written.append(target)
    readme = root / "README.md"
    if readme.exists():
        updated = _readme_with_table(readme.read_text(encoding="utf-8"))
        if updated is not None:
            readme.write_text(updated, encoding="utf-8")
    return written


def _pair_problems(path: Path, notebook: dict) -> list[str]:
    pair = path.with_suffix(".py")
    if not pair.exists():
        return []
    try:
        import jupytext
    except ImportError:
        return [f"{pair}: jupytext is not installed, so the pair could not be compared"]
    text_cells = jupytext.read(pair)["cells"]
    ipynb_cells = notebook["cells"]
    if [(c["cell_type"], _source(c)) for c in text_cells] != [
        (c["cell_type"], _source(c)) for c in ipynb_cells
    ]:
        return [f"{path} differs from its pair {pair.name}: run `urkin course execute`"]
    return []


_HEADING = re.compile(
    r"^###\s+Exercise\s+(\d+\.\d+)\s+—\s+`(\w+)`\s+\((\d+(?:\.\d+)?)\s+points?\)", re.M
)


def _exercise_problems(path: Path, notebook: dict, lesson: str) -> list[str]:
    """Each exercise: its heading and points, its *Checked* paragraph, its check cell."""
    problems = []
    cells = notebook["cells"]
    headings = {}
    for index, cell in enumerate(cells):
        if cell["cell_type"] == "markdown":
            for match in _HEADING.finditer(_source(cell)):
                headings[match.group(1)] = (index, match.group(2), float(match.group(3)))
    code = [i for i, c in enumerate(cells) if c["cell_type"] == "code"]
    order = [headings[ex.id][0] for ex in _declared(lesson).exercises if ex.id in headings]
    if order != sorted(order):
        problems.append(f"{path}: the exercises must be numbered in the order they appear")
    for ex in _declared(lesson).exercises:
        where = f"{path}: exercise {ex.id}"
        heading = headings.get(ex.id)
        if heading is None:
            problems.append(
                f"{where} has no heading '### Exercise {ex.id} — `{ex.function}` "
                f"({ex.points:g} points)'"
            )
        else:
            index, function, points = heading
            if function != ex.function or points != ex.points:
                problems.append(
                    f"{where}: its heading says `{function}` ({points:g} points); "
                    f"the lesson module declares `{ex.function}` ({ex.points:g})"
                )
            if "*Checked*" not in _source(cells[index]):
                problems.append(f"{where}: its text does not say what is *Checked*")
        defining = [
            i
            for i in code
            if re.search(rf"^def {ex.function}\(", _source(cells[i]), re.M)
            and BEGIN in _source(cells[i])
        ]
        if not defining:
            continue  # reported with the solution blocks
        following = [i for i in code if i > defining[0]]
        expected = f'check("{ex.id}", {ex.function})'
        if not following or _source(cells[following[0]]).strip() != expected:
            problems.append(f"{where}: the code cell after it must be exactly {expected}")
    return problems


def math_layout(markdown: str) -> list[str]:
    """Places where a lesson's maths would not render as maths on the docs site (MyST).

    Two layouts break: a line inside inline ``$…$`` that begins like a list item (``+ ``,
    ``- ``, ``* ``), which Markdown turns into a bullet with raw TeX around it; and display
    maths ``$$…$$`` spread over several lines inside a list item, which is not read as maths.

    Examples
    --------
    >>> math_layout("a $x\\n+ y$ b")
    ["line 2 starts with '+ ' inside $…$: Markdown reads it as a list item"]
    >>> math_layout("* item\\n  $$x$$")
    []
    """
    problems = []
    inline = display = False
    in_item = False
    for number, line in enumerate(markdown.splitlines(), start=1):
        stripped = line.strip()
        if re.match(r"([-*+]|\d+\.) ", stripped) and not (inline or display):
            in_item = True
        elif not line.startswith(" ") and not (inline or display):
            in_item = False
        if inline and re.match(r"[-+*] ", stripped):
            problems.append(
                f"line {number} starts with '{stripped[:2]}' inside $…$: Markdown reads it as "
                "a list item"
            )
        if not display and stripped.startswith("$$") and stripped.count("$$") == 1 and in_item:
            problems.append(
                f"line {number}: display maths $$…$$ over several lines inside a list item is "
                "not read as maths; keep it on one line"
            )
        for token in re.findall(r"\$\$|\$", line):
            if token == "$$":
                display = not display
            elif not display:
                inline = not inline
    return problems


def lessons_mentioned(text: str) -> set[str]:
    """The two-digit lesson numbers a text refers to ("lesson 03", "lessons 05–07").

    Examples
    --------
    >>> sorted(lessons_mentioned("see lesson\\n03 and lessons 05–07; lesson 2 is not a number"))
    ['03', '05', '06', '07']
    """
    found = set()
    for first, last in re.findall(r"[Ll]essons?\s+(\d{2})\b(?:\s*[–-]\s*(\d{2})\b)?", text):
        end = int(last or first)
        found |= {f"{n:02d}" for n in range(int(first), max(end, int(first)) + 1)}
    return found


def _mention_problems(path: Path, notebook: dict, numbers: set[str]) -> list[str]:
    """A lesson may only send its reader to lessons that exist (no promises of future ones)."""
    problems = []
    for index, cell in enumerate(notebook.get("cells", [])):
        text = re.sub(r"\n#? ?", " ", _source(cell))  # a mention broken over comment lines
        for number in sorted(lessons_mentioned(text) - numbers):
            problems.append(
                f"{path}, cell {index + 1}: mentions lesson {number}, which does not exist"
            )
    return problems


def section_numbers(markdown: str) -> list[str]:
    """Problems with a lesson's numbered sections (``## 1. …``): they must run 1, 2, 3 … with
    no number missing or repeated, since the text refers to them by number.

    Examples
    --------
    >>> section_numbers("## 1. A\\n## 2. B\\n## 4. D")
    ['section 3 is missing: the numbered sections run 1, 2, 4']
    >>> section_numbers("## 1. A\\n## Summary")
    []
    """
    found = [int(n) for n in re.findall(r"^## (\d+)\. ", markdown, re.M)]
    if found == list(range(1, len(found) + 1)):
        return []
    missing = sorted(set(range(1, max(found) + 1)) - set(found))
    numbers = ", ".join(map(str, found))
    if missing:
        return [f"section {missing[0]} is missing: the numbered sections run {numbers}"]
    return [f"the numbered sections run {numbers}: not 1, 2, 3 … in order"]


def _section_problems(path: Path, notebook: dict) -> list[str]:
    markdown = "\n".join(
        _source(cell) for cell in notebook.get("cells", []) if cell.get("cell_type") == "markdown"
    )
    return [f"{path}: {problem}" for problem in section_numbers(markdown)]


def _math_layout_problems(path: Path, notebook: dict) -> list[str]:
    return [
        f"{path}, cell {index + 1}: {problem}"
        for index, cell in enumerate(notebook.get("cells", []))
        if cell.get("cell_type") == "markdown"
        for problem in math_layout(_source(cell))
    ]


def check(root: Path) -> list[str]:
    """Every problem with the course sources and student notebooks (empty when all is well)."""
    from urkin.course.lessons import lessons as declared_lessons

    problems: list[str] = []
    lessons = find_lessons(root)
    if not lessons:
        return [f"no solution notebooks in {root / 'solutions'}"]
    numbers = {_lesson_number(p) for p in lessons}
    for number in declared_lessons():
        if number not in numbers:
            problems.append(f"lesson module lesson{number}.py has no solutions/{number}_*.ipynb")
    expected_students = set()
    for path in lessons:
        lesson = _lesson_number(path)
        try:
            _declared(lesson)
        except ValueError as exc:
            problems.append(str(exc))
            continue
        notebook = json.loads(path.read_text(encoding="utf-8"))
        problems += _pair_problems(path, notebook)
        problems += _exercise_problems(path, notebook, lesson)
        problems += _math_layout_problems(path, notebook)
        problems += _mention_problems(path, notebook, numbers)
        problems += _section_problems(path, notebook)
        if notebook.get("metadata", {}).get("kernelspec") != KERNELSPEC:
            problems.append(f"{path}: kernelspec is not normalised to python3")
        solution_ids, removed_lines = [], []
        for index, cell in enumerate(notebook["cells"]):
            if cell["cell_type"] != "code":
                continue
            for output in cell.get("outputs", []):
                if output.get("output_type") == "error":
                    problems.append(f"{path}, cell {index + 1}: stored output is an error")
            try:
                _, ids, removed = strip_solutions(
                    _source(cell), lesson, f"{path}, cell {index + 1}"
                )
            except ValueError as exc:
                problems.append(str(exc))
                continue
            solution_ids += ids
            removed_lines += removed
        for ex in _declared(lesson).exercises:
            count = solution_ids.count(ex.id)
            if count != 1:
                problems.append(
                    f"{path}: exercise {ex.id} ({ex.function}) has {count} "
                    "solution blocks; it needs exactly one"
                )
        target = root / "course" / path.name
        expected_students.add(target.name)
        if not target.exists():
            problems.append(f"{target} is missing: run `urkin course build`")
            continue
        try:
            expected = _dumps(build_student_notebook(notebook, lesson, path.name))
        except ValueError:
            continue  # already reported above
        actual = target.read_text(encoding="utf-8")
        if actual != expected:
            problems.append(f"{target} is out of date with {path}: run `urkin course build`")
        problems += _leaks(target, actual, notebook, removed_lines)
    for stray in sorted((root / "course").glob("*.ipynb")):
        if stray.name not in expected_students:
            problems.append(f"{stray} has no source in solutions/")
    readme = root / "README.md"
    if readme.exists():
        text = readme.read_text(encoding="utf-8")
        updated = _readme_with_table(text)
        if updated is None:
            problems.append(f"{readme}: the lesson table's markers are missing ({TABLE_START})")
        elif updated != text:
            problems.append(f"{readme}: the lesson table is out of date: run `urkin course build`")
    return problems


def _leaks(target: Path, text: str, solution: dict, removed_lines: list[str]) -> list[str]:
    problems = []
    if BEGIN in text or END in text:
        problems.append(f"{target}: a solution marker is left in the student notebook")
    student = json.loads(text)
    student_lines = {
        line.strip() for cell in student["cells"] for line in _source(cell).split("\n")
    }
    outside = set()
    for cell in solution["cells"]:
        source = _source(cell)
        if cell["cell_type"] == "code":
            try:
                source, _, _ = strip_solutions(source, _lesson_number(target), str(target))
            except ValueError:
                pass
        outside |= {line.strip() for line in source.split("\n")}
    for line in removed_lines:
        key = line.strip()
        if len(key) >= 12 and key not in outside and key in student_lines:
            problems.append(f"{target}: solution line leaked into the student notebook: {key!r}")
    return problems


def execute(root: Path, names: list[str] | None = None, timeout: int = 120) -> list[Path]:
    """Sync each paired ``solutions/NN_*.py`` into its ``.ipynb`` and execute it in place."""
    import jupytext
    import nbformat
    from nbclient import NotebookClient

    pairs = sorted((root / "solutions").glob("[0-9][0-9]_*.py"))
    wanted = {Path(name).stem for name in names or []}
    unknown = sorted(wanted - {pair.stem for pair in pairs})
    if unknown:
        known = ", ".join(pair.stem for pair in pairs)
        raise ValueError(f"no lesson named {', '.join(unknown)} in solutions/ (lessons: {known})")
    done = []
    for pair in pairs:
        if wanted and pair.stem not in wanted:
            continue
        notebook = jupytext.read(pair)
        notebook.metadata["kernelspec"] = dict(KERNELSPEC)
        client = NotebookClient(
            notebook,
            timeout=timeout,
            kernel_name="python3",
            resources={"metadata": {"path": str(root / "solutions")}},
        )
        client.execute()
        target = pair.with_suffix(".ipynb")
        data = normalise_solution(json.loads(nbformat.writes(notebook)), _lesson_number(pair))
        _drop_embedded_pictures(data)
        target.write_text(_dumps(data), encoding="utf-8")
        done.append(target)
    return done


def _execute(notebook, root: Path, timeout: int, what: str) -> None:
    from nbclient import NotebookClient
    from nbclient.exceptions import CellExecutionError

    client = NotebookClient(
        notebook,
        timeout=timeout,
        kernel_name="python3",
        resources={"metadata": {"path": str(root / "course")}},
    )
    try:
        client.execute()
    except CellExecutionError as error:
        raise RuntimeError(f"{what} failed to run top to bottom:\n{error}") from None


def _render_key(student: Path) -> str:
    """What a rendered lesson depends on: its notebook and urkin's source."""
    import hashlib

    digest = hashlib.sha256(student.read_bytes())
    for source in sorted(Path(__file__).resolve().parents[1].rglob("*.py")):
        digest.update(source.read_bytes())
    return digest.hexdigest()


def render(root: Path, into: Path, timeout: int = 300, jobs: int = 2) -> list[Path]:
    """Execute every student notebook of ``course/`` once, into ``into`` (for the docs site).

    A lesson that raises fails the call.  A rendered notebook is reused while neither it nor
    urkin's source has changed, so building the docs twice executes nothing the second time.
    ``jobs`` lessons run at once, each in its own kernel (two: the 2-core machine the budgets
    are set on; a lesson's kernel keeps one core busy for the most part).
    """
    from concurrent.futures import ThreadPoolExecutor

    into.mkdir(parents=True, exist_ok=True)
    written, todo = [], []
    for student in sorted((root / "course").glob("[0-9][0-9]_*.ipynb")):
        target = into / student.name
        key = _render_key(student)
        written.append(target)
        if target.exists():
            rendered = json.loads(target.read_text(encoding="utf-8"))
            if rendered.get("metadata", {}).get("urkin", {}).get("rendered_from") == key:
                continue
        todo.append((student, target, key))
    if todo:
        # a thread per lesson drives its kernel (a process of its own): the work is there
        with ThreadPoolExecutor(max(1, min(jobs, len(todo)))) as pool:
            runs = [pool.submit(_render_one, *job, root, timeout) for job in todo]
            for run in runs:
                run.result()  # a lesson that raised raises here
    for stale in sorted(into.glob("*.ipynb")):
        if stale not in written:
            stale.unlink()
    return written


def _render_one(student: Path, target: Path, key: str, root: Path, timeout: int) -> None:
    """Execute one student notebook into ``target``, marked with its render key."""
    import nbformat

    notebook = nbformat.read(student, as_version=4)
    _execute(notebook, root, timeout, f"course/{student.name}")
    notebook.metadata.setdefault("urkin", {})["rendered_from"] = key
    nbformat.write(notebook, target)


def main(argv: list[str] | None = None) -> int:
    """Command line of ``urkin course``."""
    parser = argparse.ArgumentParser(
        prog="urkin course",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("action", choices=["build", "check", "execute", "render"])
    parser.add_argument(
        "lessons", nargs="*", help="execute only these (e.g. 02_dh_fk); render: the folder"
    )
    parser.add_argument("--root", type=Path, default=Path("."), help="course root (default .)")
    args = parser.parse_args(argv)
    root = args.root.resolve()
    if args.action in ("build", "check") and args.lessons:
        parser.error(
            f"{args.action} works on every lesson at once and takes no lesson names; "
            f"got {' '.join(args.lessons)}"
        )
    if args.action == "render" and len(args.lessons) > 1:
        parser.error(f"render takes one folder; got {' '.join(args.lessons)}")
    if args.action == "build":
        for path in build(root):
            print(f"wrote {path.relative_to(root)}")
        return 0
    if args.action == "render":
        into = Path(args.lessons[0]) if args.lessons else root / "docs" / "lessons"
        try:
            rendered = render(root, into)
        except RuntimeError as error:
            print(f"urkin course render: {error}", file=sys.stderr)
            return 1
        print(f"{len(rendered)} lessons rendered in {into}")
        return 0
    if args.action == "execute":
        try:
            executed = execute(root, args.lessons)
        except ValueError as error:
            print(f"urkin course execute: {error}", file=sys.stderr)
            return 2
        for path in executed:
            print(f"executed {path.relative_to(root)}")
        return 0
    problems = check(root)
    for problem in problems:
        print(problem)
    if not problems:
        print(f"course OK: {len(find_lessons(root))} lessons, student notebooks up to date")
    return 1 if problems else 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
