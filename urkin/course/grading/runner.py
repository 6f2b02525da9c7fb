"""Grading notebooks: for each exercise, an isolated process runs the submission's functions and
the checks judge them from here.

One :class:`Grader` is one grading run: a fresh seed (unless one is given), the limits, and the
submissions' views of urkin (one per exercise, written once into the run's temporary folder).
:func:`grade_notebook` grades one file, :func:`grade_many` a class, a few at a time.  Every file
gets a result — an unreadable or hostile one with its reason — and nothing a submission does
changes another's: each exercise of each submission runs in a process of its own, started
fresh, and its inputs are drawn from the run's seed and the exercise alone.
"""

from __future__ import annotations

import difflib
import math
import os
import secrets
import shutil
import sys
import tempfile
import threading
import time
from collections.abc import Callable, Iterable
from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import dataclass, field
from pathlib import Path

from urkin.course.answers import PACKAGE, answer_for
from urkin.course.exercise import (
    CheckResult,
    Exercise,
    ExerciseResult,
    Lesson,
    link_dependencies,
    run_exercise,
)
from urkin.course.grading import isolation
from urkin.course.grading.read import Notebook, Site, exercise_cells, read_notebook
from urkin.course.grading.remote import RemoteSubmission
from urkin.course.lessons import lessons
from urkin.course.submission import SubmissionGone

__all__ = [
    "DEFAULT_MEMORY_LIMIT_MB",
    "DEFAULT_SETUP_LIMIT",
    "DEFAULT_TIME_LIMIT",
    "Grader",
    "SubmissionResult",
    "find_submissions",
    "grade_many",
    "grade_notebook",
    "new_seed",
    "progress_bar",
]

#: Wall-clock seconds the calls of one exercise of one submission may take.
DEFAULT_TIME_LIMIT = 60.0
#: Memory (MiB) the process of one exercise may use, with everything it starts.
DEFAULT_MEMORY_LIMIT_MB = 1024
#: Seconds for starting that process and executing the notebook's definitions.
DEFAULT_SETUP_LIMIT = 60.0


@dataclass
class SubmissionResult:
    """The grade of one submitted file."""

    name: str
    path: str
    lesson: str | None
    seed: int
    status: str  # graded, unreadable, unknown lesson, error
    reason: str = ""
    notes: list[str] = field(default_factory=list)
    exercises: list[ExerciseResult] = field(default_factory=list)
    isolation: str = ""

    @property
    def earned(self) -> float:
        return float(sum(e.earned for e in self.exercises))

    @property
    def points(self) -> float:
        if self.lesson is None or self.lesson not in lessons():
            return 0.0
        return lessons()[self.lesson].points

    @property
    def mistakes(self) -> list[str]:
        """The named mistakes, as ``"2.1: <mistake>"``."""
        return [f"{e.exercise}: {m}" for e in self.exercises for m in e.mistakes]

    def exercise(self, exercise_id: str) -> ExerciseResult | None:
        return next((e for e in self.exercises if e.exercise == exercise_id), None)

    def to_dict(self) -> dict:
        return {
            "name": self.name,
            "path": self.path,
            "lesson": self.lesson,
            "seed": self.seed,
            "status": self.status,
            "reason": self.reason,
            "notes": self.notes,
            "earned": self.earned,
            "points": self.points,
            "isolation": self.isolation,
            "exercises": [e.to_dict() for e in self.exercises],
        }


_READING = threading.Lock()


def new_seed() -> int:
    """A fresh, non-zero seed for one grading run (zero is the notebooks' visible seed)."""
    return secrets.randbelow(2**31 - 1) + 1


def _blank(ex: Exercise, status: str, message: str) -> ExerciseResult:
    checks = [CheckResult(c.description, c.points, 0.0) for c in ex.checks]
    return ExerciseResult(ex.id, ex.function, ex.title, ex.points, 0.0, status, message, checks)


def _missing(ex: Exercise, notebook: Notebook) -> ExerciseResult:
    defined = sorted({n for s in notebook.sites if s.kind in ("def", "assign") for n in s.binds})
    close = difflib.get_close_matches(ex.function, defined, n=1)
    message = f"no function named `{ex.function}` was found in the notebook"
    if close:
        message += f"; did you mean `{close[0]}`? The name must be exactly `{ex.function}`"
    broken = [n for n in notebook.notes if "syntax error" in n or "skipped" in n]
    if broken:
        message += " (" + "; ".join(broken[:3]) + ")"
    return _blank(ex, "missing", message)


def _imported_from_urkin(site: Site) -> str | None:
    import ast

    node = site.node
    if isinstance(node, ast.ImportFrom) and (node.module or "").split(".")[0] == "urkin":
        return f"from {node.module} import …"
    if isinstance(node, ast.Import) and any(a.name.split(".")[0] == "urkin" for a in node.names):
        return "import urkin…"
    return None


def _validated(result: ExerciseResult, ex: Exercise) -> ExerciseResult:
    """The result as the lesson declares it could be: known id, finite points within range."""
    ok = (
        result.exercise == ex.id
        and len(result.checks) == len(ex.checks)
        and all(
            math.isfinite(c.earned) and 0 <= c.earned <= d.points and c.points == d.points
            for c, d in zip(result.checks, ex.checks)
        )
    )
    if not ok:
        return _blank(ex, "error", "the grader produced an invalid result and discarded it")
    result.earned = float(sum(c.earned for c in result.checks))
    return result


class Grader:
    """One grading run (see the module docstring); use as a context manager.

    Parameters
    ----------
    seed : int, optional
        Seed of the test inputs (a fresh one when omitted).
    time_limit : float
        Wall-clock seconds per exercise.
    memory_limit_mb : int
        Memory per exercise process (with its children), MiB.
    setup_limit : float
        Seconds for an exercise process to start and execute the notebook's definitions.
    isolate : bool
        Run submissions in the namespace sandbox where the machine allows it.
    jobs : int, optional
        Exercise processes run at once for one submission (default: the number of cores).
    """

    def __init__(
        self,
        seed: int | None = None,
        time_limit: float = DEFAULT_TIME_LIMIT,
        memory_limit_mb: int = DEFAULT_MEMORY_LIMIT_MB,
        setup_limit: float = DEFAULT_SETUP_LIMIT,
        isolate: bool = True,
        jobs: int | None = None,
    ) -> None:
        self.seed = new_seed() if seed is None else int(seed)
        self.jobs = max(1, jobs or os.cpu_count() or 1)
        self.time_limit, self.setup_limit = float(time_limit), float(setup_limit)
        self.limits = isolation.Limits(memory_bytes=int(memory_limit_mb) * 2**20)
        self.isolate = isolate
        self.support = (
            isolation.support()
            if isolate
            else isolation.Support(False, "per process", "isolation was turned off (isolate=False)")
        )
        self._folder = Path(tempfile.mkdtemp(prefix="urkin-grade-"))
        os.chmod(self._folder, 0o755)
        self._views: dict[str, Path] = {}
        self._lock = threading.Lock()

    def __enter__(self) -> Grader:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        shutil.rmtree(self._folder, ignore_errors=True)

    def _view(self, ex: Exercise) -> Path:
        """The submission's view of urkin for ``ex``: from the cache, or written once.  Without
        namespaces a submission could write into its view (it runs as the grader's user, and
        the view is not mounted read-only): it then gets a view of this run only, never the
        cache's, which later runs, isolated ones too, would trust."""
        with self._lock:
            if ex.id not in self._views:
                answer = answer_for(ex)
                cache = isolation.cache_folder() if self.support.namespaces else None
                folder = cache / "views" / answer.key() if cache else None
                if folder is None or not (folder / "urkin" / "__init__.py").exists():
                    fresh = Path(tempfile.mkdtemp(prefix="view-", dir=self._folder))
                    os.chmod(fresh, 0o755)
                    answer.write_view(fresh)
                    if folder is not None:
                        try:
                            folder.parent.mkdir(parents=True, exist_ok=True)
                            os.replace(fresh, folder)  # atomic; another run may win the race
                        except OSError:
                            folder = fresh
                    else:
                        folder = fresh
                self._views[ex.id] = folder
            return self._views[ex.id]

    def grade(
        self,
        path: str | Path,
        lesson: str | None = None,
        name: str | None = None,
        exercises: Iterable[str] | None = None,
    ) -> SubmissionResult:
        """Grade one file (only the ``exercises`` named, if given); never raises for anything
        the file contains or does."""
        path = Path(path)
        with _READING:  # one notebook parsed at a time: the grader's memory stays small
            notebook = read_notebook(path, lesson)
        result = SubmissionResult(
            name or path.name,
            str(path),
            notebook.lesson,
            self.seed,
            "error",
            isolation=self.support.summary,
        )
        if notebook.lesson is None or notebook.lesson not in lessons():
            result.status = "unknown lesson"
            result.reason = notebook.conflict or (
                "cannot tell which lesson this notebook is: keep the course notebook's name "
                "(NN_topic.ipynb) or its metadata, or pass --lesson"
            )
            if notebook.error:
                result.status, result.reason = "unreadable", notebook.error
            return result
        if notebook.error:
            result.status, result.reason = "unreadable", notebook.error
            return result
        declared = lessons()[notebook.lesson]
        chosen = set(exercises) if exercises is not None else None
        result.notes = list(notebook.notes)
        result.exercises = self._exercises(notebook, declared, result.notes, chosen)
        link_dependencies(result.exercises, {ex.id: ex for ex in declared.exercises})
        result.status = "graded"
        return result

    def _exercises(self, notebook: Notebook, lesson: Lesson, notes: list[str], chosen=None):
        cells = {}
        course = sorted((PACKAGE.parent / "course").glob(f"{lesson.number}_*.ipynb"))
        if course:
            cells = exercise_cells(course[0])
        graded = {}
        for ex in lesson.exercises:
            site = notebook.graded_site(ex.function, ex.id, cells.get(ex.function))
            if site is not None:
                graded[ex.function] = site
                stub = notebook.stub_left(ex.function, cells.get(ex.function), site)
                if stub is not None:
                    notes.append(
                        f"{stub.describe()}, the exercise's cell, still holds the stub of "
                        f"`{ex.function}`: the grader graded the one in {site.describe()}"
                    )
                for later in notebook.redefinitions(ex.function, site):
                    notes.append(
                        f"{later.describe()} defines `{ex.function}` again; the grader graded "
                        f"the one in {site.describe()}, the exercise's cell, and ignored this one"
                    )

        def one(ex: Exercise) -> tuple[ExerciseResult, list[str]]:
            site = graded.get(ex.function)
            if site is None:
                return _missing(ex, notebook), []
            imported = _imported_from_urkin(site)
            if imported:
                return _blank(
                    ex,
                    "forbidden",
                    (
                        f"`{ex.function}` is imported from urkin ({imported}), not written in the "
                        "notebook: urkin's own answer earns no points"
                    ),
                ), []
            result, setup_notes = self._one(ex, notebook, graded)
            return _validated(result, ex), setup_notes

        # the exercises are independent processes: run them side by side
        todo = [ex for ex in lesson.exercises if chosen is None or ex.id in chosen]
        with ThreadPoolExecutor(max_workers=self.jobs) as pool:
            outcomes = list(pool.map(one, todo))
        for _, setup_notes in outcomes:
            notes += [n for n in setup_notes if n not in notes]
        return [result for result, _ in outcomes]

    def _one(self, ex: Exercise, notebook: Notebook, graded: dict):
        cut = notebook.check_call(ex.id, graded[ex.function])
        plan_notes: list[str] = []
        plan = notebook.plan({ex.function, *ex.uses}, graded, cut, plan_notes)
        submission = RemoteSubmission(
            notebook,
            graded,
            plan,
            self._view(ex),
            PACKAGE,
            self.limits,
            self.time_limit,
            self.setup_limit,
        )
        try:
            try:
                notes = plan_notes + submission.start()
            except SubmissionGone as gone:
                return _blank(ex, gone.status, gone.message), plan_notes
            except OSError as exc:
                return _blank(ex, "error", f"the grader could not start the process: {exc}"), []
            return run_exercise(ex, submission, self.seed), notes
        finally:
            submission.close()


def grade_notebook(
    path: str | Path,
    *,
    seed: int | None = None,
    lesson: str | None = None,
    time_limit: float = DEFAULT_TIME_LIMIT,
    memory_limit_mb: int = DEFAULT_MEMORY_LIMIT_MB,
    setup_limit: float = DEFAULT_SETUP_LIMIT,
    name: str | None = None,
    isolate: bool = True,
) -> SubmissionResult:
    """Grade one notebook (see :class:`Grader`); never raises for a bad submission."""
    with Grader(seed, time_limit, memory_limit_mb, setup_limit, isolate) as grader:
        return grader.grade(path, lesson, name)


def find_submissions(paths: Iterable[str | Path]) -> list[Path]:
    """Everything to grade: files named directly, and every entry named ``*.ipynb`` inside the
    folders named (recursively, without following symbolic links), sorted.  A FIFO, a
    directory or a link named ``*.ipynb`` is listed too: it gets a row saying why it was not
    graded."""
    found: list[Path] = []
    for item in map(Path, paths):
        if item.is_dir() and not item.is_symlink() and item.suffix != ".ipynb":
            for folder, dirs, files in os.walk(item, followlinks=False):
                dirs[:] = sorted(d for d in dirs if d != ".ipynb_checkpoints")
                for entry in sorted([*files, *dirs]):
                    if entry.endswith(".ipynb"):
                        found.append(Path(folder) / entry)
        else:
            found.append(item)
    return sorted(dict.fromkeys(found))


def submission_names(paths: list[Path]) -> list[str]:
    """Unique names for reports: the file name, with parent folders where names collide."""
    names = [p.name for p in paths]
    depth = 1
    while len(set(names)) < len(names) and depth < 8:
        depth += 1
        names = ["/".join(p.parts[-depth:]) for p in paths]
    seen: dict[str, int] = {}
    unique = []
    for name in names:
        seen[name] = seen.get(name, 0) + 1
        unique.append(name if seen[name] == 1 else f"{name} ({seen[name]})")
    return unique


def grade_many(
    paths: Iterable[str | Path],
    *,
    seed: int | None = None,
    lesson: str | None = None,
    time_limit: float = DEFAULT_TIME_LIMIT,
    memory_limit_mb: int = DEFAULT_MEMORY_LIMIT_MB,
    setup_limit: float = DEFAULT_SETUP_LIMIT,
    jobs: int | None = None,
    progress: Callable[[int, int, SubmissionResult], None] | None = None,
    isolate: bool = True,
) -> list[SubmissionResult]:
    """Grade every notebook in ``paths`` (files or folders), ``jobs`` at a time.

    All submissions of one run share one seed, so they answer the same questions, and each
    gets exactly the result it would get graded alone.
    """
    notebooks = find_submissions(paths)
    names = submission_names(notebooks)
    results: list[SubmissionResult | None] = [None] * len(notebooks)
    jobs = max(1, jobs or os.cpu_count() or 1)
    inner = 1 if len(notebooks) > 1 else jobs  # exercises side by side only for one notebook
    with Grader(seed, time_limit, memory_limit_mb, setup_limit, isolate, inner) as grader:

        def grade(index: int) -> int:
            try:
                results[index] = grader.grade(notebooks[index], lesson, names[index])
            except Exception as exc:  # a bug of the grader must not lose a row
                results[index] = SubmissionResult(
                    names[index],
                    str(notebooks[index]),
                    None,
                    grader.seed,
                    "error",
                    f"the grader failed on this file: {type(exc).__name__}: {exc}",
                )
            return index

        with ThreadPoolExecutor(max_workers=jobs) as pool:
            futures = [pool.submit(grade, index) for index in range(len(notebooks))]
            for done, future in enumerate(as_completed(futures), start=1):
                index = future.result()
                if progress is not None:
                    progress(done, len(notebooks), results[index])
    return [r for r in results if r is not None]


def progress_bar(stream=sys.stderr) -> Callable[[int, int, SubmissionResult], None]:
    """A progress callback that draws ``[#####.....] 12/40 name`` on one line."""
    start = time.monotonic()

    def draw(done: int, total: int, result: SubmissionResult) -> None:
        width = 30
        filled = int(width * done / max(total, 1))
        elapsed = time.monotonic() - start
        shown = "".join(c if c.isprintable() else "?" for c in result.name)[:40]
        line = f"\r[{'#' * filled}{'.' * (width - filled)}] {done}/{total}  {elapsed:5.1f} s  "
        stream.write(line + f"{shown:<40}" + ("\n" if done == total else ""))
        stream.flush()

    return draw
