"""The untrusted side of grading: run a submission's definitions, then answer calls.

Run by the grader inside the sandbox, as a script of the submission's view of urkin
(:mod:`urkin.course.answers`)::

    python -I -B …/urkin/course/grading/child.py READ_FD WRITE_FD [LIMITS_JSON]

It reads one ``setup`` message (the notebook's cells and which of their top-level statements to
execute), executes those statements, replies ``ready`` with what went wrong, then answers
``call`` messages — call this function of the submission with these arguments, watching calls
to those — until its input closes.  Every value crosses as plain data (:mod:`urkin.course.wire`).
An argument the checks answer themselves (a :class:`~urkin.course.wire.Callback`) becomes a
function that sends each call's arguments back (``callback``) and returns the ``answer``.

Nothing here is trusted: the submission runs in this process and may read, replace or forge
anything in it, this file included.  The grader therefore takes only plain data from it and
computes every verdict itself.
"""

from __future__ import annotations

import ast
import builtins
import json
import linecache
import os
import sys
import traceback
from pathlib import Path


def _quiet() -> None:
    """Send what the submission prints to /dev/null; fd 2 stays for this runtime's own fatal
    errors (a traceback, a crash in C code)."""
    import faulthandler

    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    os.close(devnull)
    faulthandler.enable(file=sys.__stderr__)
    sink = open(os.devnull, "w")
    sys.stdout = sys.stderr = sink


def _limit(limits: dict) -> None:
    """Resource limits, when the grader could not set them from outside."""
    import resource

    for name, value in limits.items():
        key = getattr(resource, name, None)
        if key is not None:
            try:
                resource.setrlimit(key, (value, value))
            except (ValueError, OSError):
                pass


class _Channel:
    def __init__(self, read_fd: int, write_fd: int) -> None:
        self.reader = os.fdopen(read_fd, "rb", buffering=1 << 16)
        self.write_fd = write_fd

    def receive(self) -> dict | None:
        line = self.reader.readline()
        return json.loads(line) if line else None

    def send(self, message: dict) -> None:
        from urkin.course import wire

        data = wire.dumps(message)
        while data:
            data = data[os.write(self.write_fd, data) :]


def _where(exc: BaseException) -> str:
    for frame in reversed(traceback.extract_tb(exc.__traceback__)):
        if frame.filename.startswith("<cell "):
            line = f": `{frame.line.strip()[:120]}`" if frame.line else ""
            cell = frame.filename[1:-1]
            return f"in {frame.name}, {cell} line {frame.lineno}{line}"
    return ""


def _raised(exc: BaseException) -> list[str]:
    try:
        text = str(exc)
    except Exception:
        text = "(an exception whose message cannot be printed)"
    return [type(exc).__name__[:80], text[:2000], _where(exc)]


def _setup(message: dict) -> tuple[dict, list[str]]:
    """Execute the selected statements; return the namespace and notes on what failed."""
    namespace: dict = {"__name__": "__main__", "__builtins__": builtins}
    trees = {}
    for number, source in message["cells"].items():
        filename = f"<cell {number}>"
        linecache.cache[filename] = (len(source), None, source.splitlines(True), filename)
        trees[number] = ast.parse(source, filename=filename)
    notes = []
    for number, index in message["run"]:
        node = trees[str(number)].body[index]
        try:
            code = compile(ast.Module(body=[node], type_ignores=[]), f"<cell {number}>", "exec")
            exec(code, namespace)
        except BaseException as exc:  # nothing a submission does may stop the others
            kind, text, _ = _raised(exc)
            first = text.strip().splitlines()[0][:200] if text.strip() else ""
            notes.append(
                f"code cell {number}, line {node.lineno}: {kind}{': ' + first if first else ''}"
            )
    return namespace, notes


#: The errors a function of the checks may raise, as the submission sees them.
_ERRORS = {"ValueError": ValueError, "TypeError": TypeError, "RuntimeError": RuntimeError}


class _Remote:
    """A function of the checks (:class:`~urkin.course.wire.Callback` ``slot``): each call
    sends its arguments over ``channel`` and returns the checks' answer, or raises their
    error."""

    def __init__(self, slot: int, channel: _Channel) -> None:
        self._slot, self._channel = slot, channel

    def __call__(self, *args, **kwargs):
        from urkin.course import wire

        self._channel.send(
            {
                "callback": {
                    "slot": self._slot,
                    "args": wire.encode(list(args), lenient=True),
                    "kwargs": wire.encode(kwargs, lenient=True),
                }
            }
        )
        message = self._channel.receive()
        answer = message.get("answer") if isinstance(message, dict) else None
        if not isinstance(answer, dict):
            raise RuntimeError("the checks did not answer")
        if "raised" in answer:
            kind, text = answer["raised"]
            raise _ERRORS.get(kind, RuntimeError)(text)
        return wire.decode(answer.get("value"), trusted=True)

    def __repr__(self) -> str:
        return "<a function of the checks>"


def _bound(value, channel: _Channel):
    """``value`` with every :class:`~urkin.course.wire.Callback` in it made a :class:`_Remote`."""
    from urkin.course import wire

    if isinstance(value, wire.Callback):
        return _Remote(value.slot, channel)
    if isinstance(value, list):
        return [_bound(v, channel) for v in value]
    if isinstance(value, tuple):
        return tuple(_bound(v, channel) for v in value)
    if isinstance(value, dict):
        return {k: _bound(v, channel) for k, v in value.items()}
    return value


def _answer(namespace: dict, request: dict, channel: _Channel) -> dict:
    from urkin.course import wire
    from urkin.course.watch import LibraryWatch  # imported by main before the submission ran

    reply: dict = {"id": request.get("id")}
    function = namespace.get(request["name"])
    if not callable(function):
        reply["raised"] = ["NameError", f"{request['name']} is not a function here", ""]
        return reply
    args = _bound(wire.decode(request["args"], trusted=True), channel)
    kwargs = _bound(wire.decode(request["kwargs"], trusted=True), channel)
    spied: dict[str, list] = {}
    saved = {}
    watched = request.get("spy", [])
    library = LibraryWatch([name for name in watched if "." in name])
    for name in watched:
        original = namespace.get(name)
        if not callable(original):
            continue
        saved[name] = original
        spied[name] = []

        def record(*a, _name=name, _original=original, **k):
            entry = {
                "args": wire.encode(list(a), lenient=True),
                "kwargs": wire.encode(k, lenient=True),
            }
            if len(spied[_name]) < 5000:
                spied[_name].append(entry)
            try:
                value = _original(*a, **k)
            except BaseException as exc:
                entry["raised"] = type(exc).__name__
                raise
            entry["result"] = wire.encode(value, lenient=True)
            return value

        namespace[name] = record
    try:
        with library:
            value = function(*args, **kwargs)
        reply["value"] = wire.encode(value, lenient=True)
    except BaseException as exc:
        reply["raised"] = _raised(exc)
    finally:
        namespace.update(saved)
    for name in library.seen:  # a library function reached: one call, its arguments not kept
        spied[name] = [{"args": wire.encode([], lenient=True)}]
    if spied:
        reply["spied"] = spied
    return reply


def main(argv: list[str]) -> int:
    read_fd, write_fd = int(argv[1]), int(argv[2])
    if len(argv) > 3:
        _limit(json.loads(argv[3]))
    sys.path.insert(0, str(Path(__file__).resolve().parents[3]))
    import urkin.course.watch  # noqa: F401 - before the submission can put another in its place

    _quiet()
    channel = _Channel(read_fd, write_fd)
    setup = channel.receive()
    if setup is None:
        return 0
    namespace, notes = _setup(setup["setup"])
    channel.send({"ready": notes})
    while True:
        request = channel.receive()
        if request is None or "call" not in request:
            return 0
        try:
            reply = _answer(namespace, request["call"], channel)
        except BaseException as exc:  # an answer that cannot be encoded, for example
            reply = {"id": request["call"].get("id"), "raised": _raised(exc)}
        channel.send(reply)


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv))
    except Exception:
        os.write(2, traceback.format_exc()[-3000:].encode(errors="replace"))
        sys.exit(1)
