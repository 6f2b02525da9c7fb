"""Grade one submission in a tree of processes: ``python -m urkin.grading.worker``.

::

    worker (trusted: reads the notebook, collects results, writes RESULT.json)
      └── setup process: limits memory, mutes output, installs guards, executes the
          submission's definitions once, then for each exercise
            └── exercise process (forked): runs the checks with a wall-clock and a memory
                limit and sends back one result

The setup process executes the submission's imports, functions and classes, and only the
top-level assignments those need (:func:`urkin.grading.notebook.needed_statements`).  A hang, a
crash, ``sys.exit()``, ``os._exit()`` or a huge allocation inside an exercise ends only that
exercise's process.  If executing the definitions themselves hangs or ends the setup
process, the worker starts again with imports, functions and classes only.

POSIX only (it forks).
"""

from __future__ import annotations

import argparse
import difflib
import json
import os
import select
import signal
import sys
import time
from pathlib import Path

from urkin.exercises import Exercise, ExerciseResult, exercises_for_lesson, run_exercise
from urkin.exercises.framework import link_dependencies
from urkin.grading import sandbox
from urkin.grading.notebook import Submission, needed_statements, read_submission

__all__ = ["grade_in_subprocesses", "main"]


def _blank(ex: Exercise, status: str, message: str) -> ExerciseResult:
    return ExerciseResult(ex.id, ex.function, ex.title, ex.points, 0.0, status, message)


def _send(fd: int, message: dict) -> None:
    data = (json.dumps(message) + "\n").encode()
    while data:
        data = data[os.write(fd, data) :]


class _Reader:
    """Newline-delimited JSON messages from a pipe, with deadlines."""

    def __init__(self, fd: int) -> None:
        self.fd, self.buffer, self.closed = fd, b"", False

    def next(self, deadline: float) -> dict | None:
        while b"\n" not in self.buffer:
            remaining = deadline - time.monotonic()
            if self.closed or remaining <= 0:
                return None
            ready, _, _ = select.select([self.fd], [], [], remaining)
            if not ready:
                return None
            chunk = os.read(self.fd, 65536)
            if not chunk:
                self.closed = True
                return None
            self.buffer += chunk
        line, self.buffer = self.buffer.split(b"\n", 1)
        try:
            return json.loads(line)
        except json.JSONDecodeError:
            return None


def _exit_description(status: int) -> str:
    if os.WIFSIGNALED(status):
        number = os.WTERMSIG(status)
        try:
            name = signal.Signals(number).name
        except ValueError:
            name = f"signal {number}"
        hint = " (out of memory?)" if number in (signal.SIGKILL, signal.SIGSEGV) else ""
        return f"was killed by {name}{hint}"
    code = os.WEXITSTATUS(status) if os.WIFEXITED(status) else status
    return f"ended with exit code {code} (did the function call os._exit()?)"


def _missing(ex: Exercise, namespace: dict, notes: list[str]) -> ExerciseResult:
    functions = [k for k, v in namespace.items() if callable(v) and not k.startswith("_")]
    close = difflib.get_close_matches(ex.function, functions, n=1)
    message = f"no function named `{ex.function}` was found in the notebook"
    if close:
        message += f"; did you mean `{close[0]}`? The name must be exactly `{ex.function}`"
    if notes:
        message += " (" + "; ".join(notes) + ")"
    return _blank(ex, "missing", message)


def _run_one_exercise(ex, function, seed, time_limit, memory_bytes) -> ExerciseResult:
    """Fork, grade ``ex`` in the child, wait at most ``time_limit`` seconds (in setup process)."""
    read_end, write_end = os.pipe()
    pid = os.fork()
    if pid == 0:  # exercise process
        os.close(read_end)
        try:
            sandbox.limit_memory(memory_bytes)
            sandbox.set_active(ex.forbidden)
            result = run_exercise(ex, function, seed)
            calls = sandbox.forbidden_calls()
            if calls and result.status != "forbidden":
                result = _blank(
                    ex,
                    "forbidden",
                    f"calls {calls[0]}, which is urkin's own "
                    "answer to this exercise: write it yourself",
                )
            _send(write_end, result.to_dict())
        finally:
            os._exit(0)
    os.close(write_end)
    reader = _Reader(read_end)
    message = reader.next(time.monotonic() + time_limit)
    if message is None and not reader.closed:
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
        os.close(read_end)
        return _blank(
            ex,
            "timeout",
            f"stopped after {time_limit:g} s without an answer: an infinite loop, or far too slow?",
        )
    _, status = os.waitpid(pid, 0)
    os.close(read_end)
    if message is None:
        return _blank(
            ex,
            "crashed",
            f"the grading process {_exit_description(status)} before the checks finished",
        )
    return ExerciseResult.from_dict(message)


def _setup_process(submission, exercises, seed, time_limit, memory_bytes, definitions_only, fd):
    """Body of the setup process: execute the definitions, then grade each exercise."""
    sandbox.mute_output()
    sandbox.limit_memory(2 * memory_bytes)
    sandbox.install_guards(name for ex in exercises for name in ex.forbidden)
    sandbox.set_active(())
    namespace: dict = {"__name__": "__main__"}
    notes = list(submission.notes)
    statements = needed_statements(submission.statements, {ex.function for ex in exercises})
    for statement in statements:
        if definitions_only and statement.kind != "definition":
            continue
        try:
            exec(statement.compile(), namespace)
        except BaseException as exc:  # nothing a submission does may escape
            if len(notes) < 12:
                text = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
                notes.append(
                    f"code cell {statement.cell}, line {statement.node.lineno}: "
                    f"{type(exc).__name__}{': ' + text if text else ''}"
                )
    _send(fd, {"setup": {"notes": notes}})
    for ex in exercises:
        function = namespace.get(ex.function)
        if function is None:
            cell_notes = [n for n in submission.notes if "syntax error" in n]
            result = _missing(ex, namespace, cell_notes)
        else:
            result = _run_one_exercise(ex, function, seed, time_limit, memory_bytes)
        _send(fd, {"exercise": result.to_dict()})


def _attempt(submission, exercises, seed, time_limit, memory_bytes, setup_limit, definitions_only):
    """One setup process; returns (setup_notes or None if setup failed, results so far)."""
    read_end, write_end = os.pipe()
    pid = os.fork()
    if pid == 0:
        os.close(read_end)
        try:
            _setup_process(
                submission, exercises, seed, time_limit, memory_bytes, definitions_only, write_end
            )
        finally:
            os._exit(0)
    os.close(write_end)
    reader = _Reader(read_end)
    first = reader.next(time.monotonic() + setup_limit)
    if first is None or "setup" not in first:
        if not reader.closed:
            os.kill(pid, signal.SIGKILL)
            why = f"took longer than {setup_limit:g} s"
        else:
            why = "ended the grading process"
        os.waitpid(pid, 0)
        os.close(read_end)
        return None, why, []
    notes = first["setup"]["notes"]
    results: list[ExerciseResult] = []
    for _ in exercises:
        message = reader.next(time.monotonic() + time_limit + 10)
        if message is None or "exercise" not in message:
            break
        results.append(ExerciseResult.from_dict(message["exercise"]))
    if len(results) < len(exercises):
        try:
            os.kill(pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        for ex in exercises[len(results) :]:
            results.append(_blank(ex, "crashed", "the grading process ended unexpectedly"))
    os.waitpid(pid, 0)
    os.close(read_end)
    return notes, None, results


def grade_in_subprocesses(
    submission: Submission,
    seed: int,
    time_limit: float,
    memory_limit_mb: int,
    setup_limit: float,
) -> dict:
    """Grade a read submission; returns the JSON-ready result (see :func:`main`)."""
    exercises = exercises_for_lesson(submission.lesson)
    memory_bytes = int(memory_limit_mb) * 2**20
    notes, why, results = _attempt(
        submission, exercises, seed, time_limit, memory_bytes, setup_limit, definitions_only=False
    )
    if notes is None:
        fallback_notes, why_again, results = _attempt(
            submission,
            exercises,
            seed,
            time_limit,
            memory_bytes,
            setup_limit,
            definitions_only=True,
        )
        note = (
            f"running the notebook's top-level assignments {why}; graded again with its "
            "imports, functions and classes only"
        )
        if fallback_notes is None:
            return {
                "status": "error",
                "reason": f"{note}, which {why_again} too",
                "notes": [],
                "exercises": [],
            }
        notes = [note, *fallback_notes]
    link_dependencies(results)
    return {
        "status": "graded",
        "reason": "",
        "notes": notes,
        "exercises": [r.to_dict() for r in results],
    }


def main(argv: list[str] | None = None) -> int:
    """``python -m urkin.grading.worker NOTEBOOK --lesson 02 --seed 1 --out RESULT.json``."""
    parser = argparse.ArgumentParser(prog="python -m urkin.grading.worker")
    parser.add_argument("notebook", type=Path)
    parser.add_argument("--lesson", required=True)
    parser.add_argument("--seed", type=int, required=True)
    parser.add_argument("--time-limit", type=float, default=20.0)
    parser.add_argument("--memory-limit-mb", type=int, default=1024)
    parser.add_argument("--setup-limit", type=float, default=60.0)
    parser.add_argument("--out", type=Path, required=True)
    args = parser.parse_args(argv)
    submission = read_submission(args.notebook, lesson=args.lesson)
    if submission.error:
        result = {"status": "unreadable", "reason": submission.error, "notes": [], "exercises": []}
    else:
        result = grade_in_subprocesses(
            submission, args.seed, args.time_limit, args.memory_limit_mb, args.setup_limit
        )
    args.out.write_text(json.dumps(result, indent=1), encoding="utf-8")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
