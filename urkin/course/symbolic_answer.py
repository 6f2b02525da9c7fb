"""A SymPy expression a submission returned, read without running its text.

A student's symbolic answer (a SymPy expression or matrix whose entries contain symbols) crosses
the wire as its ``srepr`` text.  The trusted side never hands that text to ``sympify`` or
``eval``, and never imports SymPy: it parses the text with Python's own parser (:mod:`ast`),
accepts only the constructors a kinematics expression is made of (symbols, integers, rationals,
floats, sums, products, powers, the elementary functions, π and e, matrices of those), and
evaluates the tree with numpy at many points at once.

Examples
--------
>>> answer = read("Add(Mul(Integer(2), Symbol('x')), cos(Symbol('y')))")
>>> sorted(answer.symbols)
['x', 'y']
>>> answer.evaluate({"x": [1.0, 2.0], "y": [0.0, 0.0]})
array([3., 5.])
>>> read("__import__('os').system('ls')")  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
ValueError: the expression uses __import__('os').system('ls'), which ... may not contain
"""

from __future__ import annotations

import ast
import re
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from urkin.course.parsing import parse

__all__ = ["MAX_TEXT", "Symbolic", "read"]

#: Longest srepr text accepted (characters).  A six-joint chain with generic twist angles,
#: unsimplified, is about 140 kB (expanded, 170 kB); parsing costs about 0.35 kB of memory per
#: character and 4 µs, so the limit also bounds what a hostile answer makes the grader do.
MAX_TEXT = 512 * 2**10

_FUNCTIONS = {
    "sin": np.sin,
    "cos": np.cos,
    "tan": np.tan,
    "asin": np.arcsin,
    "acos": np.arccos,
    "atan": np.arctan,
    "atan2": np.arctan2,
    "exp": np.exp,
    "log": np.log,
    "sqrt": np.sqrt,
    "Abs": np.abs,
    "sign": np.sign,
}
_CONSTANTS = {
    "pi": np.pi,
    "E": np.e,
    "I": 1j,
    "oo": np.inf,
    "zoo": complex(np.inf, np.nan),
    "nan": np.nan,
}
_LONG_NUMBER = re.compile(r"\d{301}")
_MATRICES = {"Matrix", "MutableDenseMatrix", "ImmutableDenseMatrix", "ImmutableMatrix"}


def _name(node: ast.AST) -> str:
    try:
        return ast.unparse(node)[:60]
    except Exception:  # pragma: no cover - ast.unparse handles every parsed node
        return type(node).__name__


def _literal(node: ast.AST, kind: type) -> Any:
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub) and kind is int:
        return -_literal(node.operand, int)
    if (
        isinstance(node, ast.Constant)
        and isinstance(node.value, kind)
        and not isinstance(node.value, bool)
    ):
        return node.value
    raise ValueError(f"expected a {kind.__name__} literal, found {_name(node)}")


def _check(node: ast.AST, symbols: set[str], floats: list[float]) -> None:
    """Refuse every node that is not part of an expression tree SymPy's srepr writes."""
    if isinstance(node, ast.Name):
        if node.id not in _CONSTANTS:
            raise ValueError(f"the expression uses the name {node.id!r}, which is not a number")
        return
    if not isinstance(node, ast.Call) or not isinstance(node.func, ast.Name):
        raise ValueError(
            f"the expression uses {_name(node)}, which a symbolic answer may not contain"
        )
    head, args = node.func.id, node.args
    if head == "Symbol":
        if len(args) != 1 or not all(isinstance(k.value, ast.Constant) for k in node.keywords):
            raise ValueError("a Symbol takes its name and assumptions only")
        symbols.add(_literal(args[0], str))
        return
    if node.keywords and head != "Float":
        raise ValueError(f"{head}(…) with keyword arguments is not an expression urkin reads")
    if head == "Integer":
        if len(args) != 1:
            raise ValueError("an Integer has one value")
        _literal(args[0], int)
        return
    if head == "Rational":
        if len(args) != 2 or _literal(args[1], int) == 0:
            raise ValueError("a Rational has a numerator and a non-zero denominator")
        _literal(args[0], int)
        return
    if head == "Float":
        if len(args) != 1:
            raise ValueError("a Float has one value")
        floats.append(float(_literal(args[0], str)))
        return
    if head in _MATRICES:
        if len(args) != 1 or not isinstance(args[0], ast.List):
            raise ValueError("a matrix is written as a list of rows")
        rows = args[0].elts
        if not rows or not all(isinstance(r, ast.List) for r in rows):
            raise ValueError("a matrix is written as a list of rows")
        if len({len(r.elts) for r in rows}) != 1:
            raise ValueError("the matrix's rows have different lengths")
        for row in rows:
            for entry in row.elts:
                _check(entry, symbols, floats)
        return
    if head in ("Add", "Mul") or (head == "Pow" and len(args) == 2) or head in _FUNCTIONS:
        if not args:
            raise ValueError(f"{head}() without arguments")
        for arg in args:
            _check(arg, symbols, floats)
        return
    raise ValueError(f"the expression uses {head}(…), which urkin cannot evaluate")


def _evaluate(node: ast.AST, values: Mapping[str, np.ndarray]) -> Any:
    if isinstance(node, ast.Name):
        return _CONSTANTS[node.id]
    assert isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
    head, args = node.func.id, node.args
    if head == "Symbol":
        return values[args[0].value]  # type: ignore[attr-defined]
    if head == "Integer":
        return _integer(_literal(args[0], int))
    if head == "Rational":
        return _integer(_literal(args[0], int)) / _integer(_literal(args[1], int))
    if head == "Float":
        return float(_literal(args[0], str))
    parts = [_evaluate(a, values) for a in args]
    if head == "Add":
        return sum(parts[1:], parts[0])
    if head == "Mul":
        out = parts[0]
        for part in parts[1:]:
            out = out * part
        return out
    if head == "Pow":
        base, exponent = parts
        if np.isrealobj(base) and np.isrealobj(exponent):
            base = np.asarray(base, dtype=float)
            if np.any(base < 0) and np.any(np.mod(exponent, 1.0) != 0.0):
                base = base.astype(complex)  # (−8)**(1/3) as SymPy means it: a complex root
        return np.power(base, exponent)
    return _FUNCTIONS[head](*parts)


def _integer(value: int) -> float:
    try:
        return float(value)
    except OverflowError:
        return float("inf") if value > 0 else float("-inf")


@dataclass(frozen=True, eq=False)
class Symbolic:
    """A symbolic answer: its shape (``()`` for an expression, ``(rows, cols)`` for a matrix),
    the names of its symbols, the values of its floating-point constants (``Float`` nodes: a
    6e-17 among them is a cos(π/2) computed in floating point), and a numeric evaluation.
    """

    shape: tuple[int, ...]
    symbols: frozenset[str]
    floats: tuple[float, ...]
    entries: tuple[ast.AST, ...]

    def evaluate(self, values: Mapping[str, Any]) -> np.ndarray:
        """The answer with every symbol replaced by a number or an array of numbers.

        Parameters
        ----------
        values : mapping of str to array_like
            A value for each of :attr:`symbols` (arrays broadcast together).

        Returns
        -------
        numpy.ndarray
            Shape ``self.shape + broadcast shape of the values``; complex only when an entry
            is.

        Raises
        ------
        KeyError
            When a symbol has no value.
        """
        missing = sorted(self.symbols - set(values))
        if missing:
            raise KeyError(f"no value for the symbol(s) {', '.join(missing)}")
        arrays = {k: np.asarray(v) for k, v in values.items()}
        batch = np.broadcast_shapes(*(a.shape for a in arrays.values())) if arrays else ()
        with np.errstate(all="ignore"):
            parts = [np.broadcast_to(_evaluate(e, arrays), batch) for e in self.entries]
        out = np.stack(parts) if parts else np.zeros((0, *batch))
        if np.iscomplexobj(out) and not np.any(out.imag):
            out = out.real
        return out.reshape(self.shape + batch)

    def __repr__(self) -> str:
        names = ", ".join(sorted(self.symbols)[:8])
        what = "expression" if self.shape == () else f"{self.shape[0]}×{self.shape[1]} matrix"
        return f"<SymPy {what} in {names or 'no symbols'}>"


def read(text: str) -> Symbolic:
    """Parse the ``srepr`` text of a SymPy expression or matrix, refusing anything else.

    Parameters
    ----------
    text : str
        What ``sympy.srepr`` wrote.

    Returns
    -------
    Symbolic

    Raises
    ------
    ValueError
        When the text is too long, is not Python syntax, or contains anything but the
        constructors of an expression (a name, an attribute, a call of another function …).
    """
    if not isinstance(text, str) or len(text) > MAX_TEXT:
        raise ValueError("the symbolic answer is too long or not text")
    if _LONG_NUMBER.search(text):
        raise ValueError("the symbolic answer holds a number with more than 300 digits")
    try:
        tree = parse(text, mode="eval").body
    except (SyntaxError, RecursionError, MemoryError, ValueError):
        raise ValueError("the symbolic answer is not an expression urkin can read") from None
    symbols: set[str] = set()
    floats: list[float] = []
    try:
        _check(tree, symbols, floats)
    except RecursionError:
        raise ValueError("the symbolic answer is nested too deeply") from None
    if isinstance(tree, ast.Call) and isinstance(tree.func, ast.Name) and tree.func.id in _MATRICES:
        rows = tree.args[0].elts  # type: ignore[attr-defined]
        entries = tuple(e for row in rows for e in row.elts)
        shape = (len(rows), len(rows[0].elts))
        return Symbolic(shape, frozenset(symbols), tuple(floats), entries)
    return Symbolic((), frozenset(symbols), tuple(floats), (tree,))
