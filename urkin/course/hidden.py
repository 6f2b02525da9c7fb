"""Stand-ins for urkin's own answer to an exercise while the exercise is graded.

Whatever a submission does with a hidden name — call it, index it, multiply by it, read an
attribute — raises :class:`ForbiddenCallError`, whose message says which name was hidden and
why.  The grader puts these stand-ins in the copy of urkin that a submission sees
(:mod:`urkin.course.answers`); a notebook's check cell puts them in place for the length of
each call to the student's function.
"""

from __future__ import annotations

from typing import Any, NoReturn

__all__ = ["ForbiddenCallError", "Hidden"]


class ForbiddenCallError(RuntimeError):
    """The submission used urkin's own answer to the exercise being graded."""


class Hidden:
    """Raises :class:`ForbiddenCallError` on any use (see the module docstring).

    Examples
    --------
    >>> fk = Hidden("urkin.kinematics.fk", "2.2")
    >>> fk
    <urkin.kinematics.fk: hidden while exercise 2.2 is graded>
    >>> fk(None, [0.0] * 6)
    Traceback (most recent call last):
    ...
    urkin.course.hidden.ForbiddenCallError: urkin.kinematics.fk is urkin's own answer to exercise 2.2 (or computes it): it earns no points there, so it is hidden while 2.2 is graded. Write the exercise with numpy.
    """  # noqa: E501

    __slots__ = ("_exercise", "_name")

    def __init__(self, name: str, exercise: str) -> None:
        object.__setattr__(self, "_name", name)
        object.__setattr__(self, "_exercise", exercise)

    def _refuse(self, *args: Any, **kwargs: Any) -> NoReturn:
        name, exercise = (
            object.__getattribute__(self, "_name"),
            object.__getattribute__(self, "_exercise"),
        )
        raise ForbiddenCallError(
            f"{name} is urkin's own answer to exercise {exercise} (or computes it): it earns "
            f"no points there, so it is hidden while {exercise} is graded. Write the exercise "
            "with numpy."
        )

    def __getattr__(self, attribute: str) -> Any:
        if attribute.startswith("__") and attribute.endswith("__"):
            raise AttributeError(attribute)
        self._refuse()

    def __repr__(self) -> str:
        name, exercise = (
            object.__getattribute__(self, "_name"),
            object.__getattribute__(self, "_exercise"),
        )
        return f"<{name}: hidden while exercise {exercise} is graded>"

    __call__ = __getitem__ = __setitem__ = __iter__ = __len__ = __contains__ = _refuse
    __array__ = __float__ = __int__ = __index__ = __complex__ = _refuse
    __add__ = __radd__ = __sub__ = __rsub__ = __mul__ = __rmul__ = _refuse
    __matmul__ = __rmatmul__ = __truediv__ = __rtruediv__ = __pow__ = __neg__ = _refuse
    __lt__ = __le__ = __gt__ = __ge__ = __setattr__ = _refuse
