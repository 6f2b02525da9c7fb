"""Argument checks and the batching rule, shared by every public function of the library.

Checks
    Numbers arrive as anything array-like.  :func:`real` turns them into a float array or says
    clearly what is wrong, naming the argument: not numbers, complex (refused unless a function
    documents complex-step support), NaN or infinite.

Batching rule (DESIGN §2)
    A function takes one item or a stack of them in the leading axes and returns the same
    leading axes.  A function checks an argument's trailing *core* shape, flattens its leading
    axes into one and computes on ``(N, *core)`` arrays; :func:`unstack` gives the result those
    leading axes back (none for a single item).  Single items take each function's scalar fast
    path instead.
"""

from __future__ import annotations

import math
import operator
import sys
from numbers import Integral, Real
from typing import Any

import numpy as np

__all__ = [
    "choice",
    "flag",
    "generator",
    "positive",
    "real",
    "sample_shape",
    "shape_text",
    "unit",
    "unstack",
]


def positive(
    value: Any, name: str, *, integer: bool = False, zero_ok: bool = False, what: str = ""
) -> float | int:
    """``value`` if it is a finite number above 0 (or at least 0 with ``zero_ok``; an integer
    with ``integer``); otherwise an error naming ``name`` and saying what it must be
    (``what``, by default "a number > 0" or the like): a TypeError for what is not a number (a
    string, None, a bool, an array), a ValueError for NaN, infinity, a fraction or the sign.

    Examples
    --------
    >>> positive(0.5, "step")
    0.5
    >>> positive(float("nan"), "tol")
    Traceback (most recent call last):
    ...
    ValueError: tol must be a number > 0; got nan
    """
    kind = type(value)
    if (kind is int or (kind is float and not integer)) and (
        0 < value <= _LARGEST or (zero_ok and value == 0) or (integer and value > 0)
    ):  # the common case, without the abstract-class checks below (a count may be any int)
        return value
    kinds = Integral if integer else Real
    if not what:
        what = f"{'an integer' if integer else 'a number'} {'≥' if zero_ok else '>'} 0"
    if isinstance(value, bool) or not isinstance(value, Real):
        raise TypeError(f"{name} must be {what}; got {type(value).__name__} {value!r:.40}")
    try:
        finite = (integer and isinstance(value, Integral)) or (
            math.isfinite(value) and abs(value) <= _LARGEST
        )
    except OverflowError:  # an integer beyond any float, where a number is asked for
        finite = False
    if not (isinstance(value, kinds) and finite) or value < 0 or (value == 0 and not zero_ok):
        shown = f"{value!r:.40}" if finite or not isinstance(value, Integral) else "a huge integer"
        raise ValueError(f"{name} must be {what}; got {shown}")
    return value


#: The largest number :func:`positive` accepts (a larger integer is no float).
_LARGEST = sys.float_info.max


def choice(value: Any, name: str, options: tuple[str, ...]) -> str:
    """``value`` if it is one of the strings ``options``; otherwise an error naming ``name``
    and listing them: a TypeError for what is not a string (an array of names, None), a
    ValueError for another string.

    Examples
    --------
    >>> choice("log", "form", ("log", "cross"))
    'log'
    >>> choice("sin", "form", ("log", "cross"))
    Traceback (most recent call last):
    ...
    ValueError: form must be one of 'log', 'cross'; got 'sin'
    """
    if type(value) is str and value in options:
        return value
    listed = ", ".join(map(repr, options))
    if not isinstance(value, str):
        raise TypeError(f"{name} must be one of {listed}; got {type(value).__name__} {value!r:.40}")
    raise ValueError(f"{name} must be one of {listed}; got {value!r}")


def flag(value: Any, name: str) -> bool:
    """``value`` as a bool if it is True or False (numpy's too); otherwise a TypeError naming
    ``name`` (None, a number, a string or an array is not a yes or no).

    Examples
    --------
    >>> flag(True, "closed")
    True
    >>> flag("yes", "closed")
    Traceback (most recent call last):
    ...
    TypeError: closed must be True or False; got str 'yes'
    """
    if value is True or value is False or isinstance(value, np.bool_):
        return bool(value)
    raise TypeError(f"{name} must be True or False; got {type(value).__name__} {value!r:.40}")


def generator(seed: Any) -> np.random.Generator:
    """``numpy.random.default_rng(seed)`` for an int ≥ 0 or a Generator (passed through), or
    an error naming ``seed`` (a bool is not a seed: ``True`` would quietly be 1)."""
    if isinstance(seed, np.random.Generator):
        return seed
    if isinstance(seed, (bool, np.bool_)) or not isinstance(seed, (int, np.integer)):
        raise TypeError(
            f"seed must be an int ≥ 0 or a numpy.random.Generator; got {type(seed).__name__}"
        )
    if seed < 0:
        raise ValueError(f"seed must be an int ≥ 0 or a numpy.random.Generator; got {seed}")
    return np.random.default_rng(seed)


def sample_shape(shape: Any) -> tuple[int, ...]:
    """``shape`` (an int or a tuple of ints ≥ 0, numpy integers too, no bools) as a tuple, or
    an error naming it."""
    if type(shape) is tuple and not shape:  # one item: the common case, at no cost
        return ()
    items = (shape,) if isinstance(shape, (int, np.integer)) else shape
    try:
        if isinstance(items, (str, bytes)) or any(isinstance(n, (bool, np.bool_)) for n in items):
            raise TypeError
        size = tuple(operator.index(n) for n in items)
    except TypeError:
        raise TypeError(f"shape must be an int or a tuple of ints; got {shape!r}") from None
    if any(n < 0 for n in size):
        raise ValueError(f"shape must not be negative; got {shape!r}")
    return size


def shape_text(core: tuple[int, ...]) -> str:
    """``(4, 4) or (..., 4, 4)``: the shapes a stack of ``core`` items may have."""
    inner = ", ".join(map(str, core))
    return f"({inner}{',' if len(core) == 1 else ''}) or (..., {inner})"


def real(x: Any, name: str, *, complex_ok: bool = False, finite: bool = True) -> np.ndarray:
    """``x`` as a float array (complex too when ``complex_ok``), finite (unless ``finite`` is
    False), or an error naming it.

    Raises
    ------
    TypeError
        If ``x`` is not numbers, or is complex where complex input is not supported.
    ValueError
        If an entry is NaN or infinite.

    Examples
    --------
    >>> real([1, 2], "q")
    array([1., 2.])
    >>> real([1.0, float("nan")], "q")
    Traceback (most recent call last):
    ...
    ValueError: q contains NaN or infinity (entry 1)
    """
    if isinstance(x, np.ma.MaskedArray) and np.ma.getmaskarray(x).any():
        where = np.argwhere(np.ma.getmaskarray(x))[0]
        raise ValueError(
            f"{name} has masked entries ({_entry(where, x.ndim)}): a masked value is no number "
            "(np.ma.filled gives one for each)"
        )
    try:
        array = np.asarray(x)
    except ValueError as exc:
        if "inhomogeneous" in str(exc):  # nested sequences of different lengths
            raise ValueError(
                f"{name} must be a regular array of numbers: its rows have different lengths"
            ) from None
        raise TypeError(f"{name} must be numbers; got {type(x).__name__}") from exc
    except TypeError as exc:
        raise TypeError(f"{name} must be numbers; got {type(x).__name__}") from exc
    kind = array.dtype.kind
    if kind == "O":
        for item in array.flat:  # numpy would read None as NaN, True as 1 and "0.3" as 0.3
            if item is None or isinstance(item, (bool, np.bool_, str, bytes)):
                what = "None" if item is None else type(item).__name__
                raise TypeError(f"{name} must be numbers; got {what}" + " in it" * array.ndim)
        try:
            array = array.astype(complex if complex_ok else float)
        except OverflowError:
            raise ValueError(f"{name} has a number beyond float range (±1.8e308)") from None
        except (TypeError, ValueError):
            raise TypeError(
                f"{name} must be numbers; got {type(x).__name__} holding "
                f"{type(array.flat[0]).__name__ if array.size else 'nothing'}"
            ) from None
        kind = array.dtype.kind
        if kind == "c" and not np.any(array.imag):
            array, kind = array.real, "f"
    if kind in "fc" and array.dtype.itemsize > (8 if kind == "f" else 16):
        with np.errstate(over="ignore"):  # long double beyond float64: say so, not "infinity"
            narrow = array.astype(complex if kind == "c" else float)
        lost = np.isfinite(array) & ~np.isfinite(narrow)
        if lost.any():
            where = np.argwhere(lost)[0] if array.ndim else ()
            raise ValueError(
                f"{name} has a number beyond float range (±1.8e308) ({_entry(where, array.ndim)})"
            )
        array = narrow
    if kind == "c":
        if not complex_ok:
            raise TypeError(
                f"{name} is complex: this function works with real numbers (fk and jacobian "
                "accept complex joint angles, for complex-step derivatives)"
            )
        array = array.astype(complex, copy=False)
    elif kind in "iuf":
        array = array.astype(float, copy=False)
    elif kind == "b":  # True is not 1 m, nor 1 rad
        raise TypeError(f"{name} must be numbers; got booleans")
    else:
        what = type(x).__name__ if array.ndim == 0 else f"an array of {array.dtype}"
        raise TypeError(f"{name} must be numbers; got {what}")
    if finite and not np.isfinite(array).all():
        if array.ndim == 0:
            raise ValueError(f"{name} contains NaN or infinity ({array.item()})")
        where = np.argwhere(~np.isfinite(array))[0]
        raise ValueError(f"{name} contains NaN or infinity ({_entry(where, array.ndim)})")
    return array


def _entry(where, ndim: int) -> str:
    """``entry 3`` or ``entry (1, 2)``: where an array's first offending entry is."""
    if ndim == 0:
        return "the value"
    return f"entry {tuple(int(i) for i in where)}" if ndim > 1 else f"entry {int(where[0])}"


def unit(vector: np.ndarray, name: str) -> np.ndarray:
    """The direction of a checked, finite 3-vector as a unit vector, or a ValueError naming
    ``name`` for the zero vector.  Scaled by its largest entry first, so that neither a huge
    vector (whose norm overflows to infinity) nor a tiny one (whose norm underflows to 0) loses
    its direction.

    Examples
    --------
    >>> unit(np.array([0.0, 3e300, 4e300]), "axis")
    array([0. , 0.6, 0.8])
    >>> unit(np.zeros(3), "axis")
    Traceback (most recent call last):
    ...
    ValueError: axis must be a non-zero direction; got [0.0, 0.0, 0.0]
    """
    largest = float(np.abs(vector).max())
    if largest == 0.0:
        raise ValueError(f"{name} must be a non-zero direction; got {vector.tolist()}")
    scaled = vector / largest
    return scaled / np.sqrt(scaled @ scaled)


def unstack(result: np.ndarray, lead: tuple[int, ...]) -> np.ndarray:
    """A result computed on ``(N, *core)`` items, ``(N, *out)``, given back the leading axes
    ``lead`` of its argument: ``(*lead, *out)``."""
    return result.reshape(*lead, *result.shape[1:])
