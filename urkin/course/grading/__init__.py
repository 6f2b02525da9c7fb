"""The autograder: grade submitted notebooks from outside the code that runs them.

From the command line::

    urkin grade submissions/ --out grades/
    pytest tests/grading --submission alice_02_dh_fk.ipynb

From Python::

    from urkin.course.grading import grade_notebook
    result = grade_notebook("alice_02_dh_fk.ipynb")

How it works: :mod:`~urkin.course.grading.read` reads the notebook (never executing it) and
picks, for each exercise, the statements its functions need;
:mod:`~urkin.course.grading.isolation` starts a sandboxed process that runs them
(:mod:`~urkin.course.grading.child`) with urkin's own answer hidden
(:mod:`urkin.course.answers`); :mod:`~urkin.course.grading.remote` lets the checks call the
functions there with plain data; the verdicts are computed here, and
:mod:`~urkin.course.grading.reports` writes the gradebook, feedback and Gradescope results.
"""

from urkin.course.grading.reports import feedback_text, gradescope_result, write_reports
from urkin.course.grading.runner import (
    DEFAULT_MEMORY_LIMIT_MB,
    DEFAULT_SETUP_LIMIT,
    DEFAULT_TIME_LIMIT,
    Grader,
    SubmissionResult,
    find_submissions,
    grade_many,
    grade_notebook,
    new_seed,
    progress_bar,
)

__all__ = [
    "DEFAULT_MEMORY_LIMIT_MB",
    "DEFAULT_SETUP_LIMIT",
    "DEFAULT_TIME_LIMIT",
    "Grader",
    "SubmissionResult",
    "feedback_text",
    "find_submissions",
    "grade_many",
    "grade_notebook",
    "gradescope_result",
    "new_seed",
    "progress_bar",
    "write_reports",
]
