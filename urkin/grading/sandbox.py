"""What keeps a submission from harming the grader: guards, limits and muted output.

* :func:`install_guards` replaces urkin functions that an exercise asks students to write with
  guards.  While an exercise is graded, a guard called from the submission's code raises
  :class:`~urkin.exercises.ForbiddenCallError` and records the call; called by the checks
  themselves (no submission frame on the stack) it behaves as the original.
* :func:`limit_memory` caps the address space of the current process (POSIX).
* :func:`mute_output` sends everything the submission prints to /dev/null, keeping a count.
"""

from __future__ import annotations

import io
import os
import sys
from collections.abc import Iterable

from urkin.exercises import ForbiddenCallError

__all__ = [
    "Guard",
    "forbidden_calls",
    "install_guards",
    "limit_memory",
    "mute_output",
    "set_active",
]

SUBMISSION_PREFIX = "<submission cell "

_active: set[str] = set()
_calls: list[str] = []


def _called_from_submission() -> bool:
    frame = sys._getframe(2)
    while frame is not None:
        if frame.f_code.co_filename.startswith(SUBMISSION_PREFIX):
            return True
        frame = frame.f_back
    return False


class Guard:
    """Stand-in for an urkin function; see the module docstring."""

    def __init__(self, name: str, original) -> None:
        self._name = name
        self._original = original
        self.__name__ = getattr(original, "__name__", name.rsplit(".", 1)[-1])
        self.__doc__ = getattr(original, "__doc__", None)

    def __call__(self, *args, **kwargs):
        if self._name in _active and _called_from_submission():
            _calls.append(self._name)
            raise ForbiddenCallError(
                f"calls {self._name}, which is urkin's own answer to this exercise: "
                "write it yourself (it earns no points while it calls urkin's)"
            )
        return self._original(*args, **kwargs)

    def __repr__(self) -> str:
        return f"<urkin function {self._name}>"


def _resolve(dotted: str):
    module_name, _, attribute = dotted.rpartition(".")
    __import__(module_name)
    return sys.modules[module_name], attribute


def install_guards(names: Iterable[str]) -> None:
    """Replace each named function, and every alias of it inside urkin, by a :class:`Guard`.

    Must run before the submission's code, so that ``from urkin import fk`` binds the guard.
    The checks keep working because they hold references taken at import time and because a
    guard only refuses calls that come from the submission.
    """
    originals = {}
    for dotted in sorted(set(names)):
        module, attribute = _resolve(dotted)
        original = getattr(module, attribute)
        if isinstance(original, Guard):
            continue
        originals[id(original)] = (dotted, original)
    for module_name, module in list(sys.modules.items()):
        if module is None or not (module_name == "urkin" or module_name.startswith("urkin.")):
            continue
        if module_name.startswith(("urkin.exercises", "urkin.grading")):
            continue
        for attribute, value in list(vars(module).items()):
            if id(value) in originals and originals[id(value)][1] is value:
                dotted, original = originals[id(value)]
                setattr(module, attribute, Guard(dotted, original))


def set_active(names: Iterable[str]) -> None:
    """Make these guards refuse calls from the submission (and the others let them through)."""
    _active.clear()
    _active.update(names)


def forbidden_calls() -> list[str]:
    """Guarded functions the submission called since :func:`set_active`, in order."""
    return list(_calls)


def limit_memory(extra_bytes: int) -> None:
    """Let the current process grow by at most ``extra_bytes`` of address space (POSIX only)."""
    try:
        import resource
    except ImportError:  # pragma: no cover  (Windows)
        return
    try:
        with open("/proc/self/statm") as statm:
            current = int(statm.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError):
        current = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    _, hard = resource.getrlimit(resource.RLIMIT_AS)
    limit = current + extra_bytes
    if hard != resource.RLIM_INFINITY:
        limit = min(limit, hard)
    try:
        resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    except (ValueError, OSError):  # pragma: no cover  (platforms without RLIMIT_AS)
        pass


class _CountingSink(io.TextIOBase):
    """A text stream that throws its text away and counts the characters."""

    def __init__(self) -> None:
        self.characters = 0

    def write(self, text: str) -> int:
        self.characters += len(text)
        return len(text)

    def writable(self) -> bool:
        return True


def mute_output() -> _CountingSink:
    """Send stdout and stderr (Python's and the file descriptors) to a sink; return it."""
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    os.dup2(devnull, 2)
    os.close(devnull)
    sink = _CountingSink()
    sys.stdout = sys.stderr = sink
    return sink
