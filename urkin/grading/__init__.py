"""The autograder: grade submitted notebooks safely and write the reports.

From the command line::

    urkin grade submissions/ --out grades/
    pytest tests/grading --submission alice_02_dh_fk.ipynb

From Python::

    from urkin.grading import grade_notebook
    result = grade_notebook("alice_02_dh_fk.ipynb")

See :mod:`urkin.grading.worker` for how a submission is isolated and
:mod:`urkin.grading.notebook` for what of it is executed.
"""

from urkin.grading.reports import feedback_text, gradescope_result, write_reports
from urkin.grading.runner import (
    DEFAULT_MEMORY_LIMIT_MB,
    DEFAULT_SETUP_LIMIT,
    DEFAULT_TIME_LIMIT,
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
