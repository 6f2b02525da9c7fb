"""Printing numbers in lessons so that the printed text does not depend on the CPU.

A residual of ``3.4e-16`` on one machine is ``5.6e-16`` on another (other BLAS kernels, other
SIMD loops), and a notebook test that compares printed outputs fails there.  Lessons print
bounds instead: ``below(residual)`` is ``"below 1e-12"`` on every machine.
"""

from __future__ import annotations

__all__ = ["below"]


def below(value: float, limit: float = 1e-12) -> str:
    """``"below 1e-12"`` when ``value < limit``; otherwise the value itself, to two digits (a
    value above the bound is an error the lesson means to show, not round-off).

    Parameters
    ----------
    value : float
        A non-negative error or difference.
    limit : float
        The bound to print.

    Examples
    --------
    >>> below(3.4e-16)
    'below 1e-12'
    >>> below(2e-10, 1e-9)
    'below 1e-09'
    >>> below(0.0237, 1e-10)
    '2.4e-02'
    """
    if value < limit:
        return f"below {limit:.0e}"
    return f"{value:.1e}"
