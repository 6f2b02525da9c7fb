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
from numbers import Integral, Real
from typing import Any

import numpy as np

__all__ = ["positive", "real", "shape_text", "unit", "unstack"]


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
        0 < value < math.inf or (zero_ok and value == 0)
    ):  # the common case, without the abstract-class checks below
        return value
    kinds = Integral if integer else Real
    if not what:
        what = f"{'an integer' if integer else 'a number'} {'≥' if zero_ok else '>'} 0"
    if isinstance(value, bool) or not isinstance(value, Real):
        raise TypeError(f"{name} must be {what}; got {type(value).__name__} {value!r:.40}")
    if (
        not (isinstance(value, kinds) and math.isfinite(value))
        or value < 0
        or (value == 0 and not zero_ok)
    ):
        raise ValueError(f"{name} must be {what}; got {value!r}")
    return value


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
    try:
        array = np.asarray(x)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be numbers; got {type(x).__name__}") from exc
    kind = array.dtype.kind
    if kind == "O" and any(item is None for item in array.flat):
        raise TypeError(f"{name} must be numbers; got None" + (" in it" if array.ndim else ""))
    if kind == "O":
        try:
            array = array.astype(complex if complex_ok else float)
        except (TypeError, ValueError):
            raise TypeError(
                f"{name} must be numbers; got {type(x).__name__} holding "
                f"{type(array.flat[0]).__name__ if array.size else 'nothing'}"
            ) from None
        kind = array.dtype.kind
        if kind == "c" and not np.any(array.imag):
            array, kind = array.real, "f"
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
        place = f"entry {tuple(int(i) for i in where)}" if array.ndim > 1 else f"entry {where[0]}"
        raise ValueError(f"{name} contains NaN or infinity ({place})")
    return array


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
