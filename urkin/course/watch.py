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
from types import FrameType, MappingProxyType


class LibraryWatch:
    """Which library functions a call reaches, by any route: a profile hook sees each Python
    frame that runs their code, however the function was named (an alias, ``getattr`` with a
    name built from strings, a module imported again).  ``names`` are ``"module.function"``,
    e.g. ``"numpy.linalg.inv"`` (a numpy function is followed to the Python code it
    dispatches to); those that cannot be found are left out.

    Used as a context manager around the call; ``seen`` then holds the names reached.  A hook
    the call removes, replaces or changes the table of counts as reaching every watched
    function: what it did is no longer known (only code written against this hook, by someone
    who read it, gets around it).

    Examples
    --------
    >>> import numpy as np
    >>> with LibraryWatch(["numpy.linalg.inv", "numpy.linalg.pinv"]) as watch:
    ...     _ = getattr(np.linalg, "in" + "v")(np.eye(2))
    >>> sorted(watch.seen)
    ['numpy.linalg.inv']
    """

    def __init__(self, names: Iterable[str]) -> None:
        codes: dict = {}
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
                codes[code] = name
        # read-only (a hook whose table was emptied would see nothing and still be installed),
        # with its contents kept apart to tell at the end that they were not changed
        self.codes = MappingProxyType(codes)
        self._contents = tuple(codes.items())
        self.seen: set[str] = set()
        self._previous: tuple = (None, None)

    def _hook(self, frame: FrameType, event: str, arg: object) -> None:
        if event == "call":
            name = self.codes.get(frame.f_code)
            if name is not None:
                self.seen.add(name)

    def _intact(self) -> bool:
        """Whether the hook is still the one installed, with the table it was given."""
        return (
            sys.getprofile() is self._installed
            and type(self.codes) is MappingProxyType
            and tuple(self.codes.items()) == self._contents
        )

    def __enter__(self) -> LibraryWatch:
        if self._contents:
            self._previous = sys.getprofile(), threading.getprofile()
            self._installed = self._hook  # one bound method, to recognise it afterwards
            sys.setprofile(self._installed)
            threading.setprofile(self._installed)  # threads the call starts are watched too
        return self

    def __exit__(self, *exc: object) -> None:
        if self._contents:
            if not self._intact():
                self.seen.update(name for _, name in self._contents)
            sys.setprofile(self._previous[0])
            threading.setprofile(self._previous[1])
