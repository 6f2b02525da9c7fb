"""Reports of a grading run: ``gradebook.csv``, one feedback file per submission, ``results.json``.

``results.json`` follows Gradescope's autograder format (``score``, ``tests`` with ``name``,
``score``, ``max_score``, ``output``).  When one submission is graded it is exactly that file;
for a class, ``results/<name>.json`` holds one per submission and ``results.json`` lists them.
"""

from __future__ import annotations

import csv
import json
import re
from pathlib import Path

from urkin.exercises import exercises_for_lesson
from urkin.grading.runner import SubmissionResult

__all__ = ["feedback_text", "gradescope_result", "write_reports"]


def _safe(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9._-]+", "_", name)


def feedback_text(result: SubmissionResult) -> str:
    """What the student reads: the verdict first, then each exercise; never test source."""
    lines = [f"# {result.name}"]
    if result.status != "graded":
        lines += ["", f"Not graded: {result.reason}", "", f"Score: 0 / {result.points:g}"]
        return "\n".join(lines) + "\n"
    lines += ["", f"Lesson {result.lesson}: {result.earned:g} / {result.points:g} points"]
    problems = [e for e in result.exercises if e.earned < e.points]
    if problems:
        lines.append("To look at: " + ", ".join(f"{e.exercise} ({e.status})" for e in problems))
    if result.notes:
        lines += ["", "About the notebook:"] + [f"- {note}" for note in result.notes]
    for e in result.exercises:
        lines += ["", "```", e.report(), "```"]
    lines += ["", f"(inputs drawn with seed {result.seed})"]
    return "\n".join(lines) + "\n"


def gradescope_result(result: SubmissionResult) -> dict:
    """Gradescope's ``results.json`` document for one submission."""
    tests = [
        {
            "name": f"Exercise {e.exercise} · {e.function}",
            "score": e.earned,
            "max_score": e.points,
            "status": "passed" if e.earned == e.points else "failed",
            "output": e.report(),
        }
        for e in result.exercises
    ]
    output = result.reason if result.status != "graded" else "\n".join(result.notes)
    return {"score": result.earned, "output": output, "visibility": "visible", "tests": tests}


def write_reports(results: list[SubmissionResult], out_dir: str | Path) -> Path:
    """Write ``gradebook.csv``, ``feedback/<name>.md`` and the JSON results; return the folder."""
    out = Path(out_dir)
    (out / "feedback").mkdir(parents=True, exist_ok=True)
    lessons = sorted({r.lesson for r in results if r.lesson and exercises_for_lesson(r.lesson)})
    columns = [e.id for lesson in lessons for e in exercises_for_lesson(lesson)]
    with open(out / "gradebook.csv", "w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(["submission", "lesson", *columns, "total", "max", "status", "reason"])
        for r in results:
            earned = {e.exercise: f"{e.earned:g}" for e in r.exercises}
            reason = r.reason or "; ".join(
                f"{e.exercise}: {e.status}" for e in r.exercises if e.earned < e.points
            )
            row = [r.name, r.lesson or "", *(earned.get(c, "") for c in columns)]
            writer.writerow([*row, f"{r.earned:g}", f"{r.points:g}", r.status, reason])
    for r in results:
        (out / "feedback" / f"{_safe(r.name)}.md").write_text(feedback_text(r), encoding="utf-8")
    if len(results) == 1:
        document = gradescope_result(results[0])
    else:
        (out / "results").mkdir(exist_ok=True)
        for r in results:
            (out / "results" / f"{_safe(r.name)}.json").write_text(
                json.dumps(gradescope_result(r), indent=1), encoding="utf-8"
            )
        document = {
            "submissions": [{"submission": r.name, **gradescope_result(r)} for r in results]
        }
    (out / "results.json").write_text(json.dumps(document, indent=1), encoding="utf-8")
    return out
