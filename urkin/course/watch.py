"""Which library functions a submission's call reaches, by any route.

Part of the grading runtime (:mod:`urkin.course.grading.child` uses it inside the sandbox, and
:class:`~urkin.course.submission.Submission` in the student's own kernel): copied into every
view of urkin as it is.  Like everything the submission's process runs, it can be subverted by
code written against it; what it closes is the easy route around the checks that read the
code, a function named by a string built at run time.
"""

from __future__ import annotations

import importlib
import sys
import threading
from collections.abc import Iterable
from types import FrameType


class LibraryWatch:
    """Which library functions a call reaches, by any route: a profile hook sees each Python
    frame that runs their code, however the function was named (an alias, ``getattr`` with a
    name built from strings, a module imported again).  ``names`` are ``"module.function"``,
    e.g. ``"numpy.linalg.inv"`` (a numpy function is followed to the Python code it
    dispatches to); those that cannot be found are left out.

    Used as a context manager around the call; ``seen`` then holds the names reached.  A hook
    the call removes or replaces counts as reaching every watched function: what it did is no
    longer known (only code written against this hook, by someone who read it, gets around it).

    Examples
    --------
    >>> import numpy as np
    >>> with LibraryWatch(["numpy.linalg.inv", "numpy.linalg.pinv"]) as watch:
    ...     _ = getattr(np.linalg, "in" + "v")(np.eye(2))
    >>> sorted(watch.seen)
    ['numpy.linalg.inv']
    """

    def __init__(self, names: Iterable[str]) -> None:
        self.codes: dict = {}
        for name in names:
            module, _, attribute = name.rpartition(".")
            try:
                value = getattr(importlib.import_module(module), attribute)
            except Exception:  # not importable here: nothing to watch
                continue
            for _ in range(10):  # decorators and numpy's dispatchers keep the function here
                if not hasattr(value, "__wrapped__"):
                    break
                value = value.__wrapped__
            code = getattr(value, "__code__", None)
            if code is not None:
                self.codes[code] = name
        self.seen: set[str] = set()
        self._previous: tuple = (None, None)

    def _hook(self, frame: FrameType, event: str, arg: object) -> None:
        if event == "call":
            name = self.codes.get(frame.f_code)
            if name is not None:
                self.seen.add(name)

    def __enter__(self) -> LibraryWatch:
        if self.codes:
            self._previous = sys.getprofile(), threading.getprofile()
            self._installed = self._hook  # one bound method, to recognise it afterwards
            sys.setprofile(self._installed)
            threading.setprofile(self._installed)  # threads the call starts are watched too
        return self

    def __exit__(self, *exc: object) -> None:
        if self.codes:
            if sys.getprofile() is not self._installed:
                self.seen.update(self.codes.values())
            sys.setprofile(self._previous[0])
            threading.setprofile(self._previous[1])
