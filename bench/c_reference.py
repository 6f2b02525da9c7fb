"""Optional reference for the batched benchmarks: a plain C loop of urkin's own expressions.

The generated one-pose functions in ``urkin/_generated/ur_kinematics.py`` are straight-line
arithmetic on ``cos``/``sin`` of joint-angle sums; their bodies are valid C.  This module turns
``t06_one`` and ``jacobian_one`` into C functions that loop over a stack of configurations,
compiles them with the system's C compiler (``cc -O2``, no fast-math), and loads them with
``ctypes``.  Nothing here is part of urkin, and nothing is built when no compiler is present:
:func:`load` then returns None and the benchmark prints a note instead of the row.
"""

from __future__ import annotations

import ctypes
import inspect
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np

from urkin._generated import ur_kinematics as generated

FLAGS = ("-O2", "-shared", "-fPIC")


def _split(arguments: str) -> list[str]:
    """Top-level comma-separated expressions."""
    parts, depth, current = [], 0, []
    for char in arguments:
        if char == "," and depth == 0:
            parts.append("".join(current).strip())
            current = []
            continue
        depth += char == "("
        depth -= char == ")"
        current.append(char)
    tail = "".join(current).strip()
    return parts + ([tail] if tail else [])


def _c_function(name: str, function) -> str:
    """A C loop over N configurations of a generated ``*_one`` function's expressions."""
    lines = inspect.getsource(function).splitlines()
    body, entries = [], []
    body_start = next(i for i, line in enumerate(lines) if line.rstrip().endswith('"""')) + 1
    for line in lines[body_start:]:
        text = line.strip()
        skip = ("out = ", "if out is", "elif out is", "_pack_")
        if text.startswith(skip) or text == "return out":
            continue  # the entries are read from the tuple branch, zeros included
        if text.endswith((" = q", " = lengths")):
            continue  # the C loop reads the angles and lengths itself
        match = re.match(r"return \((.*)\)$", text)
        if match:
            entries = _split(match.group(1))
            continue
        target, expression = text.split(" = ", 1)
        body.append(f"        double {target} = {expression};")
    stores = "\n".join(f"        o[{i}] = {e};" for i, e in enumerate(entries))
    return f"""
void {name}(const double *q, long n, const double *L, double *out) {{
    const double d1 = L[0], a2 = L[1], a3 = L[2], d4 = L[3], d5 = L[4], d6 = L[5];
    for (long k = 0; k < n; k++) {{
        const double q1 = q[6 * k], q2 = q[6 * k + 1], q3 = q[6 * k + 2];
        const double q4 = q[6 * k + 3], q5 = q[6 * k + 4], q6 = q[6 * k + 5];
        double *o = out + {len(entries)} * k;
        (void)q1; (void)q2; (void)q3; (void)q4; (void)q5; (void)q6; (void)d1;
{chr(10).join(body)}
{stores}
    }}
}}
"""


def source() -> str:
    return "#include <math.h>\n" + "".join(
        _c_function(name, getattr(generated, f"{name}_one")) for name in ("t06", "jacobian")
    )


class Reference:
    """The compiled loops: ``fk(robot, Q)`` (N, 4, 4) and ``jacobian(robot, Q)`` (N, 6, 6)."""

    def __init__(self, library: ctypes.CDLL) -> None:
        self._library = library
        for name in ("t06", "jacobian"):
            getattr(library, name).restype = None

    def _call(self, name: str, robot, Q: np.ndarray, shape: tuple[int, ...]) -> np.ndarray:
        Q = np.ascontiguousarray(Q, dtype=float)
        lengths = np.array(robot.lengths)
        out = np.empty((len(Q), *shape))
        pointer = ctypes.POINTER(ctypes.c_double)
        getattr(self._library, name)(
            Q.ctypes.data_as(pointer),
            ctypes.c_long(len(Q)),
            lengths.ctypes.data_as(pointer),
            out.ctypes.data_as(pointer),
        )
        return out

    def fk(self, robot, Q: np.ndarray) -> np.ndarray:
        return self._call("t06", robot, Q, (4, 4))

    def jacobian(self, robot, Q: np.ndarray) -> np.ndarray:
        return self._call("jacobian", robot, Q, (6, 6))


def load() -> Reference | None:
    """Compile and load the reference, or None when there is no C compiler."""
    compiler = shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
    if compiler is None:
        return None
    build = Path(tempfile.mkdtemp(prefix="urkin-c-reference-"))
    (build / "reference.c").write_text(source(), encoding="utf-8")
    library = build / "reference.so"
    result = subprocess.run(
        [compiler, *FLAGS, "-o", str(library), str(build / "reference.c"), "-lm"],
        capture_output=True,
        text=True,
    )
    if result.returncode != 0:
        return None
    return Reference(ctypes.CDLL(str(library)))
