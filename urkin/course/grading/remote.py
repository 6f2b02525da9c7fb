"""The trusted side of grading one exercise: a :class:`~urkin.course.submission.Submission`
whose functions run in an isolated child process (:mod:`urkin.course.grading.child`).

The checks run here, in the grader.  They send the child plain data (which function to call,
with which arguments), receive plain data back, and compute every comparison, verdict and
mistake name themselves: nothing the submission does in its process can reach them.  Every
read from the child has a deadline and a size limit, and what the child writes to stderr is
kept only up to a few kilobytes.
"""

from __future__ import annotations

import ast
import os
import selectors
import signal
import time
from pathlib import Path
from typing import Any

from urkin.course import wire
from urkin.course.grading import isolation
from urkin.course.grading.read import Notebook, Site
from urkin.course.submission import (
    Call,
    StudentRaised,
    Submission,
    SubmissionGone,
    functions_used,
    named_inputs,
)

__all__ = ["RemoteSubmission", "exit_description"]

_STDERR_KEPT = 4096


def exit_description(status: int | None) -> str:
    """'was killed by SIGKILL (out of memory?)', 'ended with exit code 3 (os._exit?)'."""
    if status is None:
        return "did not end"
    if status < 0:
        number = -status
        try:
            name = signal.Signals(number).name
        except ValueError:
            name = f"signal {number}"
        hint = " (out of memory?)" if number in (signal.SIGKILL, signal.SIGSEGV) else ""
        return f"was killed by {name}{hint}"
    if status > 128:
        return exit_description(128 - status)
    return f"ended with exit code {status} (did the submission call os._exit()?)"


class RemoteSubmission(Submission):
    """The functions of a submitted notebook, defined and called in an isolated process.

    Parameters
    ----------
    notebook : Notebook
        The submission as read (untrusted content, never executed here).
    graded : dict
        Exercise function → the statement graded as its definition.
    plan : list of Site
        The statements the child executes, in order.
    view : Path
        The directory holding the submission's view of urkin for this exercise.
    package : Path
        urkin's real package directory (the view is mounted over it in the sandbox).
    limits : isolation.Limits
    time_limit : float
        Wall-clock seconds for all calls of one exercise.
    setup_limit : float
        Wall-clock seconds for starting the process and executing the definitions.
    """

    def __init__(
        self,
        notebook: Notebook,
        graded: dict[str, Site],
        plan: list[Site],
        view: Path,
        package: Path,
        limits: isolation.Limits,
        time_limit: float,
        setup_limit: float,
    ) -> None:
        self.notebook, self.graded, self.plan = notebook, graded, plan
        self.view, self.package, self.limits = view, package, limits
        self.time_limit, self.setup_limit = time_limit, setup_limit
        self.process: isolation.Process | None = None
        self.deadline = 0.0
        self.stderr = b""
        self.gone: SubmissionGone | None = None
        self._buffer = b""
        self._calls = 0
        self._defined = {name for site in plan for name in site.binds}

    # ------------------------------------------------------------------ process and channel

    def start(self) -> list[str]:
        """Start the child and execute the definitions; return notes on what failed."""
        child_reads, to_child = os.pipe()
        from_child, child_writes = os.pipe()
        try:
            self.process = isolation.start(
                self.view,
                self.package,
                [str(child_reads), str(child_writes)],
                self.limits,
                pass_fds=(child_reads, child_writes),
            )
        finally:
            os.close(child_reads)
            os.close(child_writes)
        self._to, self._from = to_child, from_child
        os.set_blocking(self._from, False)
        cells = {str(n): self.notebook.cells[n] for n in sorted({s.cell for s in self.plan})}
        run = [[site.cell, site.index] for site in self.plan]
        self.deadline = time.monotonic() + self.setup_limit
        self._send({"setup": {"cells": cells, "run": run}}, "its definitions")
        reply = self._receive(
            f"running the notebook's definitions took longer than {self.setup_limit:g} s"
        )
        notes = reply.get("ready") if isinstance(reply, dict) else None
        if not isinstance(notes, list):
            raise self._end("crashed", "the process running the submission answered nonsense")
        return [str(n)[:300] for n in notes[:20]]

    def close(self) -> None:
        if self.process is not None:
            for fd in (self._to, self._from):
                try:
                    os.close(fd)
                except OSError:
                    pass
            self.process.end()
            self.process = None

    def _end(self, status: str, message: str, by_itself: bool = True) -> SubmissionGone:
        """End the submission's process; ``by_itself``: a crash the process had (its exit is
        described), not one the grader declares (an answer it refuses to read)."""
        code = None
        by_itself = by_itself and status == "crashed"
        if self.process is not None:
            if by_itself:  # it ended by itself: give it a moment to report how
                try:
                    code = self.process.popen.wait(timeout=2)
                except Exception:
                    code = None
            self._drain_stderr()
            ended = self.process.end()
            code = ended if code is None and by_itself else code
        if by_itself and code is not None:
            message += f": the process {exit_description(code)}"
        tail = self.stderr.decode(errors="replace").strip().splitlines()[-3:]
        fatal = [line for line in tail if "Error" in line or "Fatal" in line]
        if fatal:  # the submission's own words: quoted as such, never as the grader's
            quoted = " | ".join(repr(line[:160]) for line in fatal)
            message += f" (its last error output, as it wrote it: {quoted})"
        self.process = None
        self.gone = SubmissionGone(status, message)
        return self.gone

    def _drain_stderr(self) -> None:
        if self.process is None or self.process.stderr is None:
            return
        stream = self.process.stderr
        try:
            os.set_blocking(stream.fileno(), False)
            while True:
                chunk = os.read(stream.fileno(), 65536)
                if not chunk:
                    break
                if len(self.stderr) < _STDERR_KEPT:
                    self.stderr += chunk[: _STDERR_KEPT - len(self.stderr)]
        except (BlockingIOError, OSError, ValueError):
            pass

    def _send(self, message: dict, what: str) -> None:
        data = wire.dumps(message)
        os.set_blocking(self._to, False)
        while data:
            if time.monotonic() > self.deadline:
                raise self._end("timeout", f"stopped: sending {what} took too long")
            try:
                data = data[os.write(self._to, data) :]
            except BlockingIOError:
                sel = selectors.DefaultSelector()
                sel.register(self._to, selectors.EVENT_WRITE)
                sel.select(min(0.1, max(0.0, self.deadline - time.monotonic())))
                sel.close()
            except (BrokenPipeError, OSError):
                raise self._end("crashed", "the process running the submission ended") from None

    def _receive(self, timeout_message: str) -> Any:
        selector = selectors.DefaultSelector()
        selector.register(self._from, selectors.EVENT_READ)
        stderr = self.process.stderr if self.process is not None else None
        if stderr is not None:
            os.set_blocking(stderr.fileno(), False)
            selector.register(stderr.fileno(), selectors.EVENT_READ)
        try:
            while b"\n" not in self._buffer:
                remaining = self.deadline - time.monotonic()
                if remaining <= 0:
                    raise self._end("timeout", timeout_message)
                for key, _ in selector.select(min(remaining, 1.0)):
                    try:
                        chunk = os.read(key.fd, 1 << 20)
                    except BlockingIOError:
                        continue
                    if key.fd == self._from:
                        if not chunk:
                            raise self._end("crashed", "the process running the submission ended")
                        self._buffer += chunk
                        if len(self._buffer) > wire.MAX_MESSAGE_BYTES and b"\n" not in self._buffer:
                            raise self._end(
                                "crashed", "the answer was larger than 32 MB", by_itself=False
                            )
                    elif chunk and len(self.stderr) < _STDERR_KEPT:
                        self.stderr += chunk[: _STDERR_KEPT - len(self.stderr)]
                    elif not chunk:
                        selector.unregister(key.fd)
        finally:
            selector.close()
        line, self._buffer = self._buffer.split(b"\n", 1)
        try:
            return wire.loads(line)
        except wire.TooLarge as exc:  # refused unread: it would cost the grader too much
            why = f"the grader could not read the answer: {exc}"
            raise self._end("crashed", why, by_itself=False) from None
        except wire.WireError:  # garbage the process wrote itself: not a reply
            return None

    # ------------------------------------------------------------------------- Submission

    def missing(self, name: str) -> str:
        if name in self.graded or name in self._defined:
            return ""
        return f"no function named `{name}` is defined in the notebook"

    def _parameters(self, name: str) -> list[str]:
        site = self.graded.get(name) or next(
            (s for s in reversed(self.plan) if name in s.binds), None
        )
        node = site.node if site is not None else None
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            return [a.arg for a in (*node.args.posonlyargs, *node.args.args)]
        return []

    def spy(
        self, name: str, watched: tuple[str, ...], *args: Any, **kwargs: Any
    ) -> tuple[Any, dict[str, list[Call]]]:
        if self.gone is not None:
            raise self.gone
        if self.process is None:
            raise SubmissionGone("crashed", "the submission's process is not running")
        inputs = named_inputs(self._parameters(name), args, kwargs)
        if self._calls == 0:
            self.deadline = time.monotonic() + self.time_limit
        self._calls += 1
        with wire.callbacks() as answered_here:
            request = {
                "call": {
                    "id": self._calls,
                    "name": name,
                    "args": wire.encode(list(args)),
                    "kwargs": wire.encode(dict(kwargs)),
                    "spy": list(watched),
                }
            }
        self._send(request, "the arguments")
        limit = self.time_limit
        while True:
            reply = self._receive(
                f"stopped after {limit:g} s without an answer: an infinite loop, or far too slow?"
            )
            if isinstance(reply, dict) and "callback" in reply:
                self._send({"answer": _called_back(answered_here, reply["callback"])}, "an answer")
            elif isinstance(reply, dict) and reply.get("id") == self._calls:
                break
        return self._read_reply(reply, inputs, watched)

    def _read_reply(
        self, reply: dict, inputs: dict, watched: tuple[str, ...]
    ) -> tuple[Any, dict[str, list[Call]]]:
        raised = reply.get("raised")
        if raised is not None:
            if not (isinstance(raised, list) and len(raised) == 3):
                raised = ["Exception", "an error the grader could not read", ""]
            kind, message, where = (str(x) for x in raised)
            raise StudentRaised(kind[:80], message[:2000], where[:300], inputs)
        try:
            with wire.symbolic_budget():  # the whole reply: its answer and its recorded calls
                return self._read_values(reply, watched)
        except (wire.WireError, TypeError, ValueError) as exc:
            raise StudentRaised(
                "ValueError", f"the answer cannot be read: {exc}", "", inputs
            ) from None

    @staticmethod
    def _read_values(reply: dict, watched: tuple[str, ...]) -> tuple[Any, dict[str, list[Call]]]:
        """The answer and the recorded calls of a reply, decoded."""
        value = wire.decode(reply.get("value"))
        calls = {w: [] for w in watched}
        spied = reply.get("spied") or {}
        for w in watched:
            for entry in spied.get(w, [])[:5000] if isinstance(spied, dict) else []:
                if not isinstance(entry, dict):
                    continue
                call_args = wire.decode(entry.get("args", []))
                calls[w].append(
                    Call(
                        tuple(call_args) if isinstance(call_args, list) else (),
                        wire.decode(entry.get("kwargs", {"$d": []})) or {},
                        wire.decode(entry.get("result")),
                        str(entry["raised"])[:80] if entry.get("raised") else None,
                    )
                )
        return value, calls

    def code(self, name: str) -> dict[str, str]:
        sources = {}
        for site in self.notebook.sites:
            if site.kind == "def":
                for bound in site.binds:
                    graded = self.graded.get(bound)
                    if graded is None or graded is site:
                        text = ast.get_source_segment(self.notebook.cells[site.cell], site.node)
                        sources[bound] = text or ""
        for site in self.notebook.sites:  # names bound by assignment (an alias, a partial)
            if site.kind == "assign":
                text = ast.get_source_segment(self.notebook.cells[site.cell], site.node) or ""
                for bound in site.binds:
                    sources.setdefault(bound, text)
        return {n: sources[n] for n in functions_used(sources, name)}


def _called_back(functions: list, request: Any) -> dict:
    """The answer to a submission's call of one of the checks' ``functions`` (a
    :class:`~urkin.course.wire.Callback` it was given): computed here, on arguments read as
    untrusted data, as ``{"value": …}`` or ``{"raised": [kind, message]}``."""
    try:
        slot = request.get("slot") if isinstance(request, dict) else None
        if type(slot) is not int or not 0 <= slot < len(functions):
            raise ValueError("a call of a function the checks did not pass")
        with wire.symbolic_budget(0):  # the checks' own functions take no symbolic arguments
            args = wire.decode(request.get("args", []))
            kwargs = wire.decode(request.get("kwargs", {"$d": []}))
        if not isinstance(args, list) or not isinstance(kwargs, dict):
            raise TypeError("malformed arguments")
        if not all(isinstance(k, str) for k in kwargs):
            raise TypeError("keyword names must be strings")
        return {"value": wire.encode(functions[slot](*args, **kwargs))}
    except Exception as exc:  # the submission's arguments: any error is its own
        return {"raised": [type(exc).__name__, str(exc)[:500]]}
