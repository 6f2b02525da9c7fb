"""Grade many notebooks: one worker process per submission, in its own temporary directory."""

from __future__ import annotations

import json
import os
import secrets
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Iterable
from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import dataclass, field
from pathlib import Path

from urkin.exercises import ExerciseResult, exercises_for_lesson
from urkin.grading.notebook import lesson_of

__all__ = [
    "DEFAULT_MEMORY_LIMIT_MB",
    "DEFAULT_SETUP_LIMIT",
    "DEFAULT_TIME_LIMIT",
    "SubmissionResult",
    "find_submissions",
    "grade_many",
    "grade_notebook",
    "new_seed",
    "progress_bar",
]

#: Wall-clock seconds one exercise of one submission may take.
DEFAULT_TIME_LIMIT = 20.0
#: Memory (MiB) one exercise of one submission may allocate.
DEFAULT_MEMORY_LIMIT_MB = 1024
#: Seconds the notebook's top-level definitions may take before the grader falls back to
#: executing only its imports, functions and classes.
DEFAULT_SETUP_LIMIT = 60.0


@dataclass
class SubmissionResult:
    """The grade of one submitted notebook."""

    name: str
    path: str
    lesson: str | None
    seed: int
    status: str  # graded, unreadable, unknown lesson, error
    reason: str = ""
    notes: list[str] = field(default_factory=list)
    exercises: list[ExerciseResult] = field(default_factory=list)

    @property
    def earned(self) -> float:
        return float(sum(e.earned for e in self.exercises))

    @property
    def points(self) -> float:
        if self.lesson is None:
            return 0.0
        return float(sum(e.points for e in exercises_for_lesson(self.lesson)))

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
            "exercises": [e.to_dict() for e in self.exercises],
        }


def new_seed() -> int:
    """A fresh, non-zero seed for one grading run (zero is the notebooks' visible seed)."""
    return secrets.randbelow(2**31 - 1) + 1


def _worker_environment() -> dict:
    env = dict(os.environ)
    env.update(
        MPLBACKEND="Agg",
        OPENBLAS_NUM_THREADS="1",
        OMP_NUM_THREADS="1",
        MKL_NUM_THREADS="1",
        PYTHONDONTWRITEBYTECODE="1",
        PYTHONHASHSEED="0",
    )
    return env


def grade_notebook(
    path: str | Path,
    *,
    seed: int | None = None,
    lesson: str | None = None,
    time_limit: float = DEFAULT_TIME_LIMIT,
    memory_limit_mb: int = DEFAULT_MEMORY_LIMIT_MB,
    setup_limit: float = DEFAULT_SETUP_LIMIT,
    name: str | None = None,
) -> SubmissionResult:
    """Grade one notebook in a fresh worker process; never raises for a bad submission.

    Parameters
    ----------
    path : str or Path
        The submitted ``.ipynb``.
    seed : int, optional
        Seed of the test inputs (a fresh one when omitted).
    lesson : str, optional
        Lesson number; by default from the notebook's metadata, then its file name.
    time_limit : float
        Wall-clock seconds per exercise.
    memory_limit_mb : int
        Memory per exercise, MiB.
    setup_limit : float
        Seconds for the notebook's top-level definitions.
    name : str, optional
        Name of the submission in reports (the file name by default).

    Returns
    -------
    SubmissionResult
    """
    path = Path(path)
    seed = new_seed() if seed is None else int(seed)
    result = SubmissionResult(name or path.name, str(path), lesson_of(path, lesson), seed, "error")
    if result.lesson is None or not exercises_for_lesson(result.lesson):
        result.status = "unknown lesson"
        result.reason = (
            "cannot tell which lesson this notebook is: keep the course notebook's name "
            "(NN_topic.ipynb) or its metadata, or pass --lesson"
        )
        return result
    exercises = exercises_for_lesson(result.lesson)
    overall = setup_limit * 2 + len(exercises) * (time_limit + 12) + 30
    with tempfile.TemporaryDirectory(prefix="urkin-grade-") as scratch:
        copy = Path(scratch) / "submission.ipynb"
        shutil.copyfile(path, copy)
        out = Path(scratch) / "result.json"
        command = [
            sys.executable, "-m", "urkin.grading.worker", str(copy),
            "--lesson", result.lesson, "--seed", str(seed), "--time-limit", str(time_limit),
            "--memory-limit-mb", str(memory_limit_mb), "--setup-limit", str(setup_limit),
            "--out", str(out),
        ]  # fmt: skip
        process = subprocess.Popen(
            command,
            cwd=scratch,
            env=_worker_environment(),
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            start_new_session=True,
        )
        try:
            _, stderr = process.communicate(timeout=overall)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.communicate()
            result.reason = f"grading took longer than {overall:g} s and was stopped"
            return result
        finally:
            try:  # a submission's stray children die with its worker
                os.killpg(process.pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
        if not out.exists():
            tail = stderr.decode(errors="replace").strip().splitlines()[-3:]
            result.reason = "the grader's worker failed: " + " | ".join(tail)
            return result
        data = json.loads(out.read_text(encoding="utf-8"))
    result.status, result.reason = data["status"], data["reason"]
    result.notes = data["notes"]
    result.exercises = [ExerciseResult.from_dict(e) for e in data["exercises"]]
    return result


def find_submissions(paths: Iterable[str | Path]) -> list[Path]:
    """Notebook files named directly, or found (recursively) in directories, sorted."""
    found: list[Path] = []
    for item in map(Path, paths):
        if item.is_dir():
            found += [
                p for p in sorted(item.rglob("*.ipynb")) if ".ipynb_checkpoints" not in p.parts
            ]
        else:
            found.append(item)
    return found


def _submission_names(paths: list[Path]) -> list[str]:
    """Unique report names: the file name, with parent folders added where names collide."""
    names = [p.name for p in paths]
    depth = 1
    while len(set(names)) < len(names) and depth < 6:
        depth += 1
        names = ["__".join(p.parts[-depth:]) for p in paths]
    return names


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
) -> list[SubmissionResult]:
    """Grade every notebook in ``paths`` (files or folders), a few at a time.

    All submissions of one run share one fresh seed, so they answer the same questions.
    """
    notebooks = find_submissions(paths)
    seed = new_seed() if seed is None else int(seed)
    names = _submission_names(notebooks)
    jobs = max(1, jobs or os.cpu_count() or 1)
    results: list[SubmissionResult | None] = [None] * len(notebooks)

    def grade(index: int) -> int:
        results[index] = grade_notebook(
            notebooks[index], seed=seed, lesson=lesson, time_limit=time_limit,
            memory_limit_mb=memory_limit_mb, setup_limit=setup_limit, name=names[index],
        )  # fmt: skip
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
        line = f"\r[{'#' * filled}{'.' * (width - filled)}] {done}/{total}  {elapsed:5.1f} s  "
        line += f"{result.name[:40]:<40}"
        stream.write(line + ("\n" if done == total else ""))
        stream.flush()

    return draw
