"""The plain data that passes between the checks and a submission's functions.

Checks never touch an object a submission made: every argument a check passes and every value
a student's function returns is turned into plain data — numbers, strings, numpy arrays (their
dtype kept, so that a float32 answer is judged at float32's precision), lists, tuples, dicts
and sets of those — and rebuilt on the other side.  In the autograder this is the JSON that
crosses the pipe between the trusted grader and the isolated child running the submission; in
a notebook's check cell the same round trip gives the check the same values it would get when
graded.

Two kinds of argument are rebuilt from a description rather than copied: a UR arm
(:class:`urkin.Robot`, by its DH lengths) and an input function (:class:`Function`, by a kind
and its parameters, for exercises that take a function such as ``numeric_jacobian(f, q)`` or
an IK solver ``track_positions(robot, points, q0, solve)``, a candidate formula
``formula_gap(formula, robot)`` or a collision test ``path_is_free(is_free, path, …)``).
A SymPy expression or matrix with symbols in it arrives as a
:class:`urkin.course.symbolic_answer.Symbolic` (read from its ``srepr`` text without running it);
anything else a student's function returns that is not plain data arrives as :class:`Opaque`.

Some input functions are answered by the side that made them (:data:`ANSWERED_BY_CHECKS`: the
collision test ``is_free`` of exercise 9.3, whose check counts the configurations it is asked
about): within :func:`callbacks`, such a function crosses as a numbered :class:`Callback` and
the other side calls it back over the wire, so that nothing the submission can reach counts
its calls or holds its parameters.
"""

from __future__ import annotations

import base64
import contextlib
import contextvars
import json
import math
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = [
    "ANSWERED_BY_CHECKS",
    "MAX_MESSAGE_BYTES",
    "MAX_SYMBOLIC_TOTAL",
    "Callback",
    "Function",
    "Opaque",
    "TooLarge",
    "WireError",
    "callbacks",
    "copy",
    "decode",
    "dumps",
    "encode",
    "loads",
    "symbolic_budget",
    "ur_flange_position",
]

#: Largest message (one argument list or one answer) either side accepts, in bytes.
MAX_MESSAGE_BYTES = 32 * 2**20
_MAX_DEPTH = 32
_MAX_TEXT = 2000
# Longest SymPy srepr text sent (= urkin.course.symbolic_answer.MAX_TEXT, which the trusted side
# enforces; that module is not part of what a graded submission can import).
MAX_SYMBOLIC_TEXT = 512 * 2**10
#: Most SymPy srepr text read from one message, all its symbolic values together: reading
#: costs up to about 0.2 kB of memory (kept while the check runs) and 2.5 µs per character, so
#: 32 MB of it (a message's limit, in 64 texts of the largest size) would take 6 GB and
#: minutes.  An honest answer holds one matrix (a six-joint chain: under 200 kB) and perhaps a
#: few small ones in recorded calls.
MAX_SYMBOLIC_TOTAL = 256 * 2**10
#: Most JSON containers (lists and objects) and items (commas) in a message from a submission:
#: 30 MB of ``[[],[],…]`` would otherwise be ten million lists in the grader, over a gigabyte.
#: An honest answer of arrays is a few containers per array (their data is one string).
MAX_CONTAINERS, MAX_ITEMS = 100_000, 1_000_000
_DTYPES = {
    "bool",
    "int8",
    "int16",
    "int32",
    "int64",
    "uint8",
    "uint16",
    "uint32",
    "uint64",
    "float16",
    "float32",
    "float64",
    "complex64",
    "complex128",
}


class WireError(ValueError):
    """A value that cannot cross: too large, too deep, or malformed."""


class TooLarge(WireError):
    """A message too large to read: its bytes, or its lists and items."""


@dataclass(frozen=True)
class Opaque:
    """Something a student's function returned that is not plain data (its type and repr)."""

    type_name: str
    text: str

    def __repr__(self) -> str:
        return f"<{self.type_name}: {self.text}>"


def _linear(A, b):
    A, b = np.asarray(A, dtype=float), np.asarray(b, dtype=float)
    return lambda x: A @ np.asarray(x, dtype=float) + b


def _smooth3(x):
    x = np.asarray(x)
    return np.array(
        [np.sin(x[0]) * x[1] ** 2, np.exp(0.5 * x[2]) + x[0] * x[1], np.cos(x[1] * x[2])]
    )


def _flange_position(robot):
    from urkin.kinematics import fk

    return lambda q: fk(robot, np.asarray(q, dtype=float))[:3, 3]


def _fixed_steps(points, steps):
    points, steps = np.asarray(points, dtype=float), np.asarray(steps, dtype=float)

    def solve(robot, p, q_guess):
        k = int(np.argmin(np.linalg.norm(points - np.asarray(p, dtype=float), axis=1)))
        return np.asarray(q_guess, dtype=float) + steps[k]

    return solve


def _position_ik():
    def solve(robot, p, q_guess):
        from urkin.numerical_ik import ik

        return ik(robot, np.asarray(p, dtype=float), q0=q_guess, method="nr", max_restarts=0).q

    return solve


def _listed_solutions(poses, solutions, counts):
    poses = np.asarray(poses, dtype=float)
    solutions, counts = np.asarray(solutions, dtype=float), np.asarray(counts, dtype=int)

    def solve_all(robot, T):
        gaps = np.abs(poses - np.asarray(T, dtype=float)).max(axis=(1, 2))
        k = int(np.argmin(gaps))
        return solutions[k, : counts[k]].copy()

    return solve_all


def _complex_kept(x) -> np.ndarray:
    """``x`` as an array: complex numbers kept (complex-step derivatives), anything else float."""
    x = np.asarray(x)
    return x if np.iscomplexobj(x) else x.astype(float)


def _polynomial(A, B, C, b):
    A, B, C, b = (np.asarray(v, dtype=float) for v in (A, B, C, b))

    def f(x):
        x = _complex_kept(x)
        return A @ x + (B @ x) * (C @ x) + b

    return f


def _sin_exp(A, B):
    A, B = np.asarray(A, dtype=float), np.asarray(B, dtype=float)

    def f(x):
        x = _complex_kept(x)
        return np.sin(A @ x) * np.exp(B @ x)

    return f


def _complex_flange_position(robot):
    from urkin.kinematics import fk

    return lambda q: fk(robot, _complex_kept(q))[:3, 3]


def ur_flange_position(lengths, q) -> np.ndarray:
    """The closed-form flange position of a UR-type arm (UR's angles and sign convention),
    which the checks of exercise 2.7 hand out as a candidate formula.  It is part of the
    forward kinematics concept (:data:`urkin.course.concepts.FORWARD_KINEMATICS`): hidden
    from the exercises that ask for it."""
    d1, a2, a3, d4, d5, d6 = (float(x) for x in lengths)
    q1, q2, q3, q4, q5, _ = np.asarray(q, dtype=float)
    c1, s1, c5, s5 = np.cos(q1), np.sin(q1), np.cos(q5), np.sin(q5)
    c234, s234 = np.cos(q2 + q3 + q4), np.sin(q2 + q3 + q4)
    reach = a2 * np.cos(q2) + a3 * np.cos(q2 + q3)
    return np.array(
        [
            c1 * reach + d4 * s1 + d5 * c1 * s234 + d6 * (s1 * c5 - c1 * c234 * s5),
            s1 * reach - d4 * c1 + d5 * s1 * s234 - d6 * (c1 * c5 + s1 * c234 * s5),
            d1 + a2 * np.sin(q2) + a3 * np.sin(q2 + q3) - d5 * c234 - d6 * s234 * s5,
        ]
    )


def _ur_position():
    return lambda robot, q: ur_flange_position(robot.lengths, q)


def _seed002_formula(report_angles=False):
    from urkin.course.seeds import SEED002_LENGTHS, SEED002_SHIFT, seed002_position

    if report_angles:  # as published: its lengths, at its angles q_UR + SEED002_SHIFT
        return lambda robot, q: np.array(
            seed002_position(np.asarray(q, dtype=float) + SEED002_SHIFT, SEED002_LENGTHS)
        )
    return lambda robot, q: np.array(seed002_position(np.asarray(q, dtype=float), robot.lengths))


def _folded_ur_position(joint):
    def formula(robot, q):
        q = np.array(q, dtype=float)
        q[joint] = np.arctan(np.tan(q[joint]))  # q_joint itself for |q_joint| < π/2 only
        return ur_flange_position(robot.lengths, q)

    return formula


class _JointBoxes:
    """``is_free(q)``: True where joint angles lie outside every box ``lower[b] ≤ q ≤ upper[b]``
    of joint space; q of shape (6,) gives a bool, (..., 6) an array of bools.  With ``budget``,
    a call that would bring the configurations asked about (over the object's life: one call
    of a student's function) beyond it raises RuntimeError instead of answering, and sets
    ``refused``; the configurations asked about are kept (:meth:`seen`).  Answered by the
    checks (:data:`ANSWERED_BY_CHECKS`): the count and the record are theirs."""

    def __init__(self, lower, upper, budget=None):
        self.lower = np.asarray(lower, dtype=float).reshape(-1, 6)
        self.upper = np.asarray(upper, dtype=float).reshape(-1, 6)
        self.budget = None if budget is None else int(budget)
        self.asked = 0
        self.refused = False  # whether a call went beyond the budget (caught or not)
        self._seen: list[np.ndarray] = []  # with a budget: every configuration asked about

    def __call__(self, q):
        Q = np.asarray(q, dtype=float)
        if Q.shape[-1:] != (6,):
            raise ValueError(f"is_free takes joint angles of shape (6,) or (N, 6); got {Q.shape}")
        count = Q.size // 6
        if self.budget is not None and self.asked + count > self.budget:
            self.refused = True
            raise RuntimeError(
                f"is_free was asked about more than {self.budget} configurations for this path: "
                "far more than the edges need at this resolution"
            )
        self.asked += count
        if self.budget is not None:
            self._seen.append(Q.reshape(-1, 6).copy())
        P = Q[..., None, :]
        inside = np.all((P >= self.lower) & (P <= self.upper), axis=-1).any(axis=-1)
        free = ~inside
        return bool(free) if free.ndim == 0 else free

    def seen(self) -> np.ndarray:
        """Every configuration asked about (with a budget, which bounds them): (K, 6)."""
        return np.concatenate(self._seen) if self._seen else np.zeros((0, 6))


_FUNCTION_KINDS = {
    "linear": _linear,  # f(x) = A x + b
    "smooth3": lambda: _smooth3,  # a fixed smooth map R³ → R³
    "flange_position": _flange_position,  # q ↦ the robot's flange position
    # position-only IK stand-ins, solve(robot, p, q_guess) ↦ q:
    "fixed_steps": _fixed_steps,  # q_guess + steps[k], k the listed point nearest p
    "position_ik": _position_ik,  # urkin.ik(robot, p, q0=q_guess, method="nr", max_restarts=0).q
    # all closed-form solutions of a pose, solve_all(robot, T) ↦ (K, 6), listed by the check:
    "listed_solutions": _listed_solutions,  # solutions[k, :counts[k]], k the listed pose nearest T
    # complex-step test functions: a complex argument stays complex
    "polynomial": _polynomial,  # f(x) = A x + (B x) ∘ (C x) + b
    "sin_exp": _sin_exp,  # f(x) = sin(A x) ∘ exp(B x)
    "complex_flange_position": _complex_flange_position,  # q ↦ the flange position, q complex
    # candidate closed-form positions formula(robot, q) ↦ p, to be tested (exercise 2.7):
    "ur_position": _ur_position,  # the right closed form for the robot's lengths
    # seed 002's published p (its d6·cos(q2+q3+q4) terms lack sin q5): with report_angles, its
    # own lengths at its angles q + SEED002_SHIFT; otherwise its terms with the robot's lengths
    "seed002_position": _seed002_formula,
    "folded_ur_position": _folded_ur_position,  # right while |q[joint]| < π/2, turned by π beyond
    # a collision test in joint space, is_free(q) ↦ bool (exercise 9.3): free outside every box
    # lower[b] ≤ q ≤ upper[b]; with budget, refuses to answer about more configurations
    "joint_boxes": _JointBoxes,
}


#: Kinds of :class:`Function` that cross as a :class:`Callback` within :func:`callbacks`.
ANSWERED_BY_CHECKS = frozenset({"joint_boxes"})

_TABLE: contextvars.ContextVar[list | None] = contextvars.ContextVar("callbacks", default=None)


#: The symbolic text :func:`decode` may still read in the message being read (a one-item
#: list, so that nested calls share it); None outside :func:`symbolic_budget`: each call of
#: :func:`decode` then has :data:`MAX_SYMBOLIC_TOTAL` of its own.
_SYMBOLIC: contextvars.ContextVar[list | None] = contextvars.ContextVar("symbolic", default=None)


@contextlib.contextmanager
def symbolic_budget(characters: int = MAX_SYMBOLIC_TOTAL) -> Iterator[None]:
    """Within it, every :func:`decode` together reads at most ``characters`` of SymPy text
    (the values of one message: its answer and its recorded calls); symbolic values beyond
    that arrive as :class:`Opaque`, unread."""
    token = _SYMBOLIC.set([characters])
    try:
        yield
    finally:
        _SYMBOLIC.reset(token)


@contextlib.contextmanager
def callbacks() -> Iterator[list]:
    """Within it, :func:`encode` sends each function of a kind in :data:`ANSWERED_BY_CHECKS`
    as ``{"$cb": k}``, ``k`` its place in the list yielded (the functions to answer calls of),
    and :func:`decode` turns ``{"$cb": k}`` back into that same function (a check cell's round
    trip in one process).  Outside it, :func:`decode` gives a :class:`Callback` (the
    submission's side, which calls the checks back)."""
    table: list = []
    token = _TABLE.set(table)
    try:
        yield table
    finally:
        _TABLE.reset(token)


@dataclass(frozen=True)
class Callback:
    """Function ``slot`` of a call's :func:`callbacks` table, as the submission's side receives
    it: the process running the submission binds it to its channel to the checks."""

    slot: int


@dataclass(frozen=True, eq=False)
class Function:
    """An input function described by data, so that it can be rebuilt wherever it is called.

    Examples
    --------
    >>> f = Function("linear", A=[[1.0, 2.0]], b=[0.5])
    >>> f([1.0, 1.0])
    array([3.5])

    A function of several arguments, such as an IK solver ``solve(robot, p, q_guess)``:

    >>> solve = Function("fixed_steps", points=[[0.0, 0.0, 1.0]], steps=[[0.1] * 6])
    >>> solve(None, [0.0, 0.0, 1.0], [0.0] * 6)
    array([0.1, 0.1, 0.1, 0.1, 0.1, 0.1])
    """

    kind: str
    params: dict[str, Any]

    def __init__(self, kind: str, **params: Any) -> None:
        if kind not in _FUNCTION_KINDS:
            raise ValueError(f"unknown function kind {kind!r}; known: {sorted(_FUNCTION_KINDS)}")
        object.__setattr__(self, "kind", kind)
        object.__setattr__(self, "params", params)
        object.__setattr__(self, "_built", _FUNCTION_KINDS[kind](**params))

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        return self._built(*args, **kwargs)  # type: ignore[attr-defined]

    def __repr__(self) -> str:
        return f"Function({self.kind!r})"


def _array(value: np.ndarray) -> dict:
    array = np.require(value, requirements="C")  # keeps 0-d arrays 0-d
    if array.dtype.name not in _DTYPES:
        raise WireError(f"arrays of {array.dtype} cannot be sent")
    if array.nbytes > MAX_MESSAGE_BYTES:
        raise WireError(f"an array of {array.nbytes} bytes is too large")
    data = base64.b64encode(array.tobytes()).decode("ascii")
    return {"$a": [array.dtype.name, list(array.shape), data]}


def _robot(robot: Any) -> dict:
    return {
        "$robot": {
            "name": robot.name,
            "lengths": [float(x) for x in robot.lengths],
            "joint_limits": [[float(lo), float(hi)] for lo, hi in robot.joint_limits],
            "base": _array(np.asarray(robot.base, dtype=float)),
            "tool": _array(np.asarray(robot.tool, dtype=float)),
        }
    }


def _float(x: float) -> Any:
    if math.isfinite(x):
        return x
    return {"$f": "nan" if math.isnan(x) else ("inf" if x > 0 else "-inf")}


def encode(value: Any, lenient: bool = False, _depth: int = 0) -> Any:
    """JSON-ready form of ``value``.

    Parameters
    ----------
    value : object
    lenient : bool
        How a submission's answer is sent: array-likes that are not arrays (numpy matrices,
        SymPy matrices of numbers, objects with ``__array__``) become arrays, and anything else
        becomes an :class:`Opaque` description instead of an error.
    """
    if _depth > _MAX_DEPTH:
        raise WireError("the value is nested too deeply")
    if value is None or isinstance(value, (bool, str)):
        return value if not isinstance(value, str) else value[:_MAX_TEXT]
    if isinstance(value, int):
        return value if abs(value) < 2**63 else _float(float(value))
    if isinstance(value, float):
        return _float(value)
    if isinstance(value, complex):
        return {"$c": [_float(value.real), _float(value.imag)]}
    if isinstance(value, (np.ndarray, np.generic)):
        if isinstance(value, np.ndarray) and value.dtype == object:
            if not lenient:
                raise WireError("object arrays cannot be sent")
            try:
                return _array(value.astype(float))
            except (TypeError, ValueError):
                return _opaque(value)
        return _array(np.asarray(value))
    if isinstance(value, (list, tuple, set, frozenset)):
        items = [encode(v, lenient, _depth + 1) for v in value]
        if isinstance(value, list):
            return items
        return {"$t" if isinstance(value, tuple) else "$s": items}
    if isinstance(value, dict):
        return {
            "$d": [
                [encode(k, lenient, _depth + 1), encode(v, lenient, _depth + 1)]
                for k, v in value.items()
            ]
        }
    if isinstance(value, Function):
        table = _TABLE.get()
        if table is not None and value.kind in ANSWERED_BY_CHECKS:
            table.append(value)
            return {"$cb": len(table) - 1}
        return {"$fn": [value.kind, encode(value.params, lenient, _depth + 1)]}
    if type(value).__name__ == "Robot" and hasattr(value, "lengths"):
        return _robot(value)
    if not lenient:
        raise WireError(f"a {type(value).__name__} cannot be sent")
    if hasattr(value, "__array__") or type(value).__module__.startswith("sympy"):
        try:
            return _array(np.asarray(value, dtype=float))
        except (TypeError, ValueError):
            pass
    if type(value).__module__.startswith("sympy"):
        return _sympy(value)
    return _opaque(value)


def _sympy(value: Any) -> dict:
    """A SymPy expression or matrix with symbols in it, as its ``srepr`` text (read on the
    other side by :func:`urkin.course.symbolic_answer.read`, never evaluated as code)."""
    from sympy import srepr

    try:
        text = srepr(value)
    except Exception:
        return _opaque(value)
    if len(text) > MAX_SYMBOLIC_TEXT:
        return _opaque(value)
    return {"$sym": text}


def _opaque(value: Any) -> dict:
    try:
        text = repr(value)[:200]
    except Exception:
        text = "?"
    return {"$o": [type(value).__name__[:80], text]}


def _decode_array(spec: Any) -> np.ndarray:
    if not (isinstance(spec, list) and len(spec) == 3):
        raise WireError("malformed array")
    dtype, shape, data = spec
    if dtype not in _DTYPES or not isinstance(shape, list) or not isinstance(data, str):
        raise WireError("malformed array")
    if len(shape) > 32 or not all(isinstance(n, int) and 0 <= n < 2**40 for n in shape):
        raise WireError("malformed array shape")
    raw = base64.b64decode(data.encode("ascii"), validate=True)
    itemsize = np.dtype(dtype).itemsize
    if len(raw) != math.prod(shape) * itemsize:
        raise WireError("array data does not match its shape")
    return np.frombuffer(raw, dtype=dtype).reshape(shape).copy()


def _decode_robot(spec: Any) -> Any:
    from urkin.robots import Robot

    return Robot(
        str(spec["name"]),
        *(float(x) for x in spec["lengths"]),
        joint_limits=tuple((float(lo), float(hi)) for lo, hi in spec["joint_limits"]),
        base=_decode_array(spec["base"]["$a"]),
        tool=_decode_array(spec["tool"]["$a"]),
    )


def decode(data: Any, trusted: bool = False, _depth: int = 0) -> Any:
    """Rebuild a value from :func:`encode`'s form.

    Parameters
    ----------
    data : object
        Parsed JSON.
    trusted : bool
        Whether ``data`` came from the checks (robots and functions are rebuilt) or from a
        submission (they arrive as :class:`Opaque`).
    """
    if _depth > _MAX_DEPTH:
        raise WireError("the value is nested too deeply")
    if data is None or isinstance(data, (bool, int, float, str)):
        return data
    if _depth == 0 and _SYMBOLIC.get() is None:  # a budget of its own
        with symbolic_budget():
            return decode(data, trusted, _depth)
    if isinstance(data, list):
        return [decode(v, trusted, _depth + 1) for v in data]
    if not isinstance(data, dict) or len(data) != 1:
        raise WireError("malformed value")
    ((tag, body),) = data.items()
    if tag == "$a":
        return _decode_array(body)
    if tag == "$f" and body in ("nan", "inf", "-inf"):
        return float(body)
    if tag == "$c" and isinstance(body, list) and len(body) == 2:
        return complex(decode(body[0], trusted, _depth + 1), decode(body[1], trusted, _depth + 1))
    if tag in ("$t", "$s") and isinstance(body, list):
        items = [decode(v, trusted, _depth + 1) for v in body]
        if tag == "$t":
            return tuple(items)
        try:
            return set(items)
        except TypeError:
            return Opaque("set", repr(items)[:200])
    if tag == "$d" and isinstance(body, list):
        out = {}
        for pair in body:
            if not (isinstance(pair, list) and len(pair) == 2):
                raise WireError("malformed dict")
            key = decode(pair[0], trusted, _depth + 1)
            try:
                out[key] = decode(pair[1], trusted, _depth + 1)
            except TypeError:
                raise WireError("a dict key that is not hashable") from None
        return out
    if tag == "$sym" and isinstance(body, str):
        from urkin.course import symbolic_answer  # the trusted side only

        left = _SYMBOLIC.get()
        if left[0] < len(body):
            return Opaque(
                "SymPy expression",
                f"not read: over {MAX_SYMBOLIC_TOTAL // 1024} kB of symbolic text in one answer",
            )
        left[0] -= len(body)
        try:
            return symbolic_answer.read(body)
        except ValueError as exc:
            return Opaque("SymPy expression", f"unreadable: {exc}"[:200])
    if tag == "$o" and isinstance(body, list) and len(body) == 2:
        return Opaque(str(body[0])[:80], str(body[1])[:200])
    if tag == "$robot":
        return _decode_robot(body) if trusted else Opaque("Robot", "a robot")
    if tag == "$fn" and isinstance(body, list) and len(body) == 2:
        if not trusted:
            return Opaque("Function", str(body[0])[:80])
        return Function(str(body[0]), **decode(body[1], trusted, _depth + 1))
    if tag == "$cb" and type(body) is int and body >= 0:
        if not trusted:
            return Opaque("Function", "a function of the checks")
        table = _TABLE.get()
        if table is None:
            return Callback(body)
        if body < len(table):
            return table[body]
    raise WireError(f"unknown tag {tag!r}")


def dumps(message: Any) -> bytes:
    """One message as a line of JSON (``message`` already encoded)."""
    return json.dumps(message, separators=(",", ":"), allow_nan=False).encode() + b"\n"


def loads(line: bytes) -> Any:
    """Parse one line of JSON, refusing anything too large or malformed: more than
    :data:`MAX_MESSAGE_BYTES` bytes, or more than :data:`MAX_CONTAINERS` brackets or
    :data:`MAX_ITEMS` commas (counted in the bytes, strings too: an upper bound, before any
    object is built)."""
    if len(line) > MAX_MESSAGE_BYTES:
        raise TooLarge("the message is too large")
    if line.count(b"[") + line.count(b"{") > MAX_CONTAINERS or line.count(b",") > MAX_ITEMS:
        raise TooLarge(
            f"the message holds more than {MAX_CONTAINERS:,} lists or {MAX_ITEMS:,} items: "
            "send arrays, not nested lists"
        )
    try:
        return json.loads(line)
    except (ValueError, RecursionError) as exc:
        raise WireError(f"malformed message: {exc}") from None


def copy(value: Any, lenient: bool = False, trusted: bool = True) -> Any:
    """``decode(encode(value))``: the value as the other side of the wire would see it."""
    return decode(encode(value, lenient), trusted)
