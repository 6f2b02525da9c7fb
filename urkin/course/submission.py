"""What a check sees of a submission: every function it defines, called with plain data.

A check receives a :class:`Submission` and calls the student's functions through it, by name —
``sub.call("forward_kinematics", robot, q)`` or simply ``sub.forward_kinematics(robot, q)`` —
so it can test the exercise's function against the student's other functions (a Jacobian
against finite differences of the student's own forward kinematics, an IK solver through the
student's own step function).  Arguments and answers cross as plain data (:mod:`urkin.course.wire`):
a check never holds an object the submission made.

* :class:`LocalSubmission` calls functions of a namespace in this process: the notebook's
  check cell.
* :class:`urkin.course.grading.remote.RemoteSubmission` calls them in an isolated child
  process: the autograder.

A student's exception reaches the check as :class:`StudentRaised` (its type, message, the line
of the student's code and the inputs); a submission that stops answering (time limit, crash)
raises :class:`SubmissionGone`.
"""

from __future__ import annotations

import ast
import difflib
import inspect
import sysconfig
import textwrap
import traceback
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from urkin.course import wire
from urkin.course.parsing import parse
from urkin.course.watch import LibraryWatch

__all__ = [
    "Call",
    "LocalSubmission",
    "StudentRaised",
    "Submission",
    "SubmissionGone",
    "named_inputs",
]


_LIBRARY_PREFIXES = tuple(
    str(p)
    for p in (
        Path(wire.__file__).resolve().parents[1],  # urkin
        Path(sysconfig.get_paths()["stdlib"]).resolve(),
        Path(sysconfig.get_paths()["purelib"]).resolve(),
        Path(sysconfig.get_paths()["platlib"]).resolve(),
    )
)


class StudentRaised(Exception):
    """A student's function raised: ``kind`` is the exception's type name."""

    def __init__(
        self, kind: str, message: str, where: str = "", inputs: Mapping[str, Any] | None = None
    ) -> None:
        super().__init__(f"{kind}: {message}")
        self.kind, self.message, self.where = kind, message, where
        self.inputs = dict(inputs or {})

    def describe(self, what: str | None = None) -> str:
        from urkin.course.compare import Mismatch  # for its display of inputs

        first = self.message.strip().splitlines()[0][:300] if self.message.strip() else ""
        if what is None:
            if self.kind == "SystemExit":
                what = "called sys.exit(); grading needs the function to return"
            elif self.kind == "MemoryError":
                what = "ran out of memory: is an array far larger than it should be?"
            elif self.kind == "RecursionError":
                what = "infinite recursion"
            else:
                what = f"raised {self.kind}{': ' + first if first else ''}"
        where = f" ({self.where})" if self.where else ""
        return Mismatch(what + where, inputs=self.inputs).describe()


class SubmissionGone(Exception):
    """The submission stopped answering: ``status`` is ``timeout`` or ``crashed``."""

    def __init__(self, status: str, message: str) -> None:
        super().__init__(message)
        self.status, self.message = status, message


@dataclass
class Call:
    """One call of a watched function (see :meth:`Submission.spy`)."""

    args: tuple
    kwargs: dict = field(default_factory=dict)
    result: Any = None
    raised: str | None = None


def named_inputs(parameters: list[str], args: tuple, kwargs: Mapping[str, Any]) -> dict:
    """Arguments by parameter name, for feedback (``arg1``… when a name is unknown)."""
    named = {}
    for i, value in enumerate(args):
        named[parameters[i] if i < len(parameters) else f"arg{i + 1}"] = value
    named.update(kwargs)
    return {k: (f"robot {v.name}" if type(v).__name__ == "Robot" else v) for k, v in named.items()}


class Submission:
    """The student's functions, as a check sees them (see the module docstring)."""

    def missing(self, name: str) -> str:
        """Why ``name`` cannot be graded ("" when it can)."""
        raise NotImplementedError

    def has(self, name: str) -> bool:
        """Whether the submission defines a function ``name``."""
        return not self.missing(name)

    def call(self, name: str, *args: Any, **kwargs: Any) -> Any:
        """Call the student's ``name`` with copies of the arguments; returns plain data."""
        return self.spy(name, (), *args, **kwargs)[0]

    def spy(
        self, name: str, watched: tuple[str, ...], *args: Any, **kwargs: Any
    ) -> tuple[Any, dict[str, list[Call]]]:
        """Call ``name`` and record every call it makes to the submission's ``watched``
        functions (for example the student's ``lm_step`` inside ``ik_lm``).  A watched name
        ``"module.function"`` (with a dot) is a library function: one argument-less call is
        recorded if the call reached its code by any route
        (:class:`~urkin.course.watch.LibraryWatch`)."""
        raise NotImplementedError

    def code(self, name: str) -> dict[str, str]:
        """Source of the function ``name`` and of every function of the submission it uses,
        directly or not: name → source text (a name bound by assignment, such as an alias
        ``f = forward_kinematics``, maps to that statement, so the function it names follows)."""
        raise NotImplementedError

    def __getattr__(self, name: str) -> Callable[..., Any]:
        if name.startswith("_"):
            raise AttributeError(name)
        return lambda *args, **kwargs: self.call(name, *args, **kwargs)


def functions_used(sources: Mapping[str, str], start: str) -> list[str]:
    """Names in ``sources`` that the function ``start`` uses, directly or not (``start`` first)."""
    order, todo = [], [start]
    while todo:
        name = todo.pop()
        if name in order or name not in sources:
            continue
        order.append(name)
        try:
            tree = parse(textwrap.dedent(sources[name]))
        except SyntaxError:
            continue
        todo += sorted({n.id for n in ast.walk(tree) if isinstance(n, ast.Name)} - set(order))
    return order


def _where(exc: BaseException, is_student: Callable[[str], bool]) -> str:
    """'in dh_transform, line 4: `…`' for the innermost frame of the student's code."""
    for frame in reversed(traceback.extract_tb(exc.__traceback__)):
        if is_student(frame.filename):
            line = f": `{frame.line.strip()[:120]}`" if frame.line else ""
            return f"in {frame.name}, line {frame.lineno}{line}"
    return ""


class LocalSubmission(Submission):
    """The functions of a namespace in this process (a notebook's globals).

    Parameters
    ----------
    namespace : dict
        The notebook's globals; watched functions are swapped in it for the length of a call.
    overrides : mapping, optional
        Functions to use instead of the namespace's (the one a check cell passes).
    hide : callable, optional
        A context manager factory that hides urkin's own answer for the length of a call
        (:meth:`urkin.course.answers.Answer.hidden_in`).
    """

    def __init__(
        self,
        namespace: dict[str, Any],
        overrides: Mapping[str, Any] | None = None,
        hide: Callable[[dict[str, Any]], Any] | None = None,
    ) -> None:
        self.namespace = namespace
        self.overrides = dict(overrides or {})
        self.hide = hide

    def _function(self, name: str) -> Any:
        return self.overrides.get(name, self.namespace.get(name))

    def missing(self, name: str) -> str:
        value = self._function(name)
        if callable(value):
            return ""
        if value is not None:
            return (
                f"{name} must be a function; got {type(value).__name__}. Run the cell that "
                "defines it, then this one."
            )
        functions = [k for k, v in self.namespace.items() if callable(v) and not k.startswith("_")]
        close = difflib.get_close_matches(name, functions, n=1)
        hint = f"; did you mean `{close[0]}`? The name must be exactly `{name}`" if close else ""
        return f"no function named `{name}` is defined: run the cell that defines it{hint}"

    @contextmanager
    def _hidden(self) -> Iterator[None]:
        if self.hide is None:
            yield
            return
        with self.hide(self.namespace), self.hide(self.overrides):
            yield

    def _parameters(self, function: Any) -> list[str]:
        try:
            return list(inspect.signature(function).parameters)
        except (TypeError, ValueError):
            return []

    def _is_student(self, filename: str) -> bool:
        """Whether code of ``filename`` is the student's: not urkin's, not an installed
        package's, not the standard library's."""
        return not filename.startswith(_LIBRARY_PREFIXES)

    def spy(
        self, name: str, watched: tuple[str, ...], *args: Any, **kwargs: Any
    ) -> tuple[Any, dict[str, list[Call]]]:
        if self.missing(name):
            raise StudentRaised("NameError", self.missing(name))
        with (
            wire.callbacks()
        ):  # the checks' own functions (wire.ANSWERED_BY_CHECKS) pass as they are
            args, kwargs = wire.copy(args), wire.copy(kwargs)
        inputs = named_inputs(self._parameters(self._function(name)), args, kwargs)
        calls: dict[str, list[Call]] = {w: [] for w in watched}
        saved = {w: self.namespace[w] for w in watched if callable(self.namespace.get(w))}

        def recorder(watched_name: str, original: Any) -> Callable[..., Any]:
            def record(*a: Any, **k: Any) -> Any:
                call = Call(
                    wire.copy(a, lenient=True, trusted=False),
                    wire.copy(k, lenient=True, trusted=False),
                )
                calls[watched_name].append(call)
                try:
                    value = original(*a, **k)
                except BaseException as exc:
                    call.raised = type(exc).__name__
                    raise
                call.result = wire.copy(value, lenient=True, trusted=False)
                return value

            return record

        for w, original in saved.items():
            self.namespace[w] = recorder(w, original)
        library = LibraryWatch([w for w in watched if "." in w])
        try:
            with self._hidden(), library:
                value = self._function(name)(*args, **kwargs)
        except KeyboardInterrupt:
            raise
        except BaseException as exc:
            raise StudentRaised(
                type(exc).__name__, str(exc), _where(exc, self._is_student), inputs
            ) from None
        finally:
            self.namespace.update(saved)
            for w in library.seen:  # a library function reached: one call, arguments not kept
                calls[w].append(Call(()))
        try:
            return wire.copy(value, lenient=True, trusted=False), calls
        except wire.WireError as exc:
            raise StudentRaised(
                "ValueError", f"the answer cannot be read: {exc}", "", inputs
            ) from None

    def code(self, name: str) -> dict[str, str]:
        sources = {}
        for key, value in {**self.namespace, **self.overrides}.items():
            if inspect.isfunction(value) and self._is_student(value.__code__.co_filename):
                try:
                    text = textwrap.dedent(inspect.getsource(value))
                except (OSError, TypeError):
                    continue
                if value.__name__ != key:  # an alias: it uses the function it names
                    sources[key] = f"{key} = {value.__name__}\n"
                    sources.setdefault(value.__name__, text)
                else:
                    sources[key] = text
        return {n: sources[n] for n in functions_used(sources, name)}
