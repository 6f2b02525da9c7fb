"""The reports of a grading run, written once every submission process has ended.

Into the output folder:

* ``gradebook.csv`` — one row per submission (even one that could not be graded): one column
  per exercise, the total, the maximum, the status, the named mistakes, the reason, and the
  file's name in ASCII (``ascii()``: two names that look alike, with a Cyrillic а or a
  zero-width space, never share it);
* ``feedback/<submission>.md`` — what the student reads: the score first, then each exercise's
  report (the failed input, expected and received values, the likely mistake); no test source;
* ``results/<submission>.json`` — one Gradescope ``results.json`` per submission (and, when a
  single submission is graded, ``results.json`` itself, which is Gradescope's file);
* ``summary.json`` — the class at a glance.

Every file is written atomically (a temporary file renamed into place), the folder and its
sub-folders must not be symbolic links, file names are made from the submission's name so
that two submissions never share one, and text that came from a submission is cleaned of
control, format (zero-width, bidirectional) and line-separator characters (a name, of every
line break) and cannot start a spreadsheet formula.
"""

from __future__ import annotations

import csv
import hashlib
import io
import json
import os
import re
import tempfile
import unicodedata
from pathlib import Path

from urkin.course.grading.runner import SubmissionResult
from urkin.course.lessons import lessons

__all__ = ["feedback_text", "gradescope_result", "report_names", "write_reports"]


def _clean(text: str) -> str:
    """Text from a submission with every control, format (zero-width, bidirectional override)
    and line- or paragraph-separator character but the newline replaced by ``?``."""
    text = str(text)
    if not text.isascii() or not text.isprintable():
        text = "".join("?" if c != "\n" and unicodedata.category(c) in _UNSEEN else c for c in text)
    return text.replace("```", "'''")


#: Unicode categories a reader does not see as themselves: controls, format characters (the
#: zero-width space, bidirectional overrides), line and paragraph separators, unassigned.
_UNSEEN = frozenset({"Cc", "Cf", "Zl", "Zp", "Co", "Cn", "Cs"})


def _name(text: str) -> str:
    """A submission's name on one line: :func:`_clean`, and its newlines made ``?`` too."""
    return _clean(text).replace("\n", "?")


def _cell(text: str) -> str:
    """A spreadsheet cell that cannot start a formula."""
    text = _clean(text).replace("\n", " ")
    return "'" + text if text[:1] in ("=", "+", "-", "@", "\t", "\r") else text


def report_names(results: list[SubmissionResult]) -> list[str]:
    """File names (no extension) for the reports: safe characters, unique, stable.

    A submission whose name is already safe (letters, digits, ``.``, ``_``, ``-``, not at
    its ends) keeps it (less ``.ipynb``); one whose name had to be changed, or that repeats
    another's but for case (both then), gets a digest of
    its own name appended: no file name can take the name of another's reports, whatever order
    they come in (``bob 02.ipynb`` becomes ``bob_02-…``, never ``bob_02``, which is
    ``bob_02.ipynb``'s)."""
    names = [""] * len(results)
    taken: set[str] = set()
    bases = [
        re.sub(r"[^A-Za-z0-9._-]+", "_", r.name).strip("._-")[:100].removesuffix(".ipynb")
        or "submission"
        for r in results
    ]
    safe = [base == r.name.removesuffix(".ipynb") for base, r in zip(bases, results)]
    lowered = [base.lower() for base, ok in zip(bases, safe) if ok]
    safe = [ok and lowered.count(base.lower()) == 1 for base, ok in zip(bases, safe)]
    for first in (True, False):  # the names kept as they are, then the others
        for i, result in enumerate(results):
            if safe[i] is not first:
                continue
            base = bases[i]
            name = base if safe[i] else ""
            digest = hashlib.sha256(result.name.encode(errors="replace")).hexdigest()
            width = 8
            while not name or name.lower() in taken:
                name = f"{base}-{digest[:width]}" if width <= len(digest) else f"{base}-{i}"
                width += 8
            taken.add(name.lower())
            names[i] = name
    return names


def _literal(text: str) -> str:
    """Markdown that shows ``text`` as it is: every ASCII punctuation character escaped, so
    that a file name cannot render as a heading, a link, an image or HTML."""
    return re.sub(r"([!-/:-@\[-`{-~])", r"\\\1", text)


def _block(text: str) -> list[str]:
    """``text`` as a fenced code block whose fence is longer than any run of backticks in it
    (text a submission wrote cannot close the block and go on as markdown)."""
    longest = max((len(run) for run in re.findall(r"`+", text)), default=0)
    fence = "`" * max(3, longest + 1)
    return [fence, text, fence]


def feedback_text(result: SubmissionResult) -> str:
    """What the student reads: the verdict first, then each exercise; never test source.
    Everything that may hold text from the submission (its name, error messages, notes) is
    shown literally: escaped, or in a code block it cannot leave."""
    lines = [f"# {_literal(_name(result.name))}"]
    if result.status != "graded":
        lines += ["", "Not graded:", *_block(_clean(result.reason))]
        lines += ["", f"Score: 0 / {result.points:g}"]
        return "\n".join(lines) + "\n"
    lines += ["", f"Lesson {result.lesson}: {result.earned:g} / {result.points:g} points"]
    problems = [e for e in result.exercises if e.earned < e.points]
    if problems:
        lines.append("To look at: " + ", ".join(f"{e.exercise} ({e.status})" for e in problems))
    if result.mistakes:
        lines += ["", "Likely mistakes:"] + [f"- {_clean(m)}" for m in result.mistakes]
    if result.notes:
        notes = "\n".join(f"- {_clean(note)}" for note in result.notes)
        lines += ["", "About the notebook:", *_block(notes)]
    for e in result.exercises:
        lines += ["", *_block(_clean(e.report()))]
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
            "output": _clean(e.report()),
        }
        for e in result.exercises
    ]
    if result.status == "graded":
        output = "\n".join(_clean(n) for n in result.notes)
    else:
        output = f"Not graded: {_clean(result.reason)}"
    return {
        "score": result.earned,
        "output": output,
        "visibility": "visible",
        "stdout_visibility": "hidden",
        "tests": tests,
    }


def _safe_folder(path: Path) -> Path:
    if path.is_symlink():
        raise ValueError(f"{path} is a symbolic link: the grader does not write through links")
    path.mkdir(parents=True, exist_ok=True)
    if path.is_symlink() or not path.is_dir():
        raise ValueError(f"{path} is not a plain folder")
    return path


def _write(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` atomically (a temporary file in the same folder, renamed)."""
    fd, temporary = tempfile.mkstemp(dir=path.parent, prefix=".tmp-", suffix=path.suffix)
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="") as handle:
            handle.write(text)
        os.chmod(temporary, 0o644)
        os.replace(temporary, path)
    except BaseException:
        if os.path.exists(temporary):
            os.unlink(temporary)
        raise


def _gradebook(results: list[SubmissionResult]) -> str:
    known = lessons()
    present = sorted({r.lesson for r in results if r.lesson in known})
    columns = [ex.id for number in present for ex in known[number].exercises]
    buffer = io.StringIO()
    writer = csv.writer(buffer)
    writer.writerow(
        ["submission", "lesson", *columns, "total", "max", "status", "mistakes", "reason", "file"]
    )
    for r in results:
        earned = {e.exercise: f"{e.earned:g}" for e in r.exercises}
        reason = r.reason or "; ".join(
            f"{e.exercise}: {e.status}" for e in r.exercises if e.earned < e.points
        )
        writer.writerow(
            [
                _cell(r.name),
                r.lesson or "",
                *(earned.get(c, "") for c in columns),
                f"{r.earned:g}",
                f"{r.points:g}",
                r.status,
                _cell("; ".join(r.mistakes)),
                _cell(reason),
                ascii(r.name),  # starts with a quote: never a formula
            ]
        )
    return buffer.getvalue()


def write_reports(results: list[SubmissionResult], out_dir: str | Path) -> Path:
    """Write the reports of ``results`` into ``out_dir`` (see the module docstring)."""
    out = _safe_folder(Path(out_dir))
    feedback, gradescope = _safe_folder(out / "feedback"), _safe_folder(out / "results")
    names = report_names(results)
    for result, name in zip(results, names):
        _write(feedback / f"{name}.md", feedback_text(result))
        _write(gradescope / f"{name}.json", json.dumps(gradescope_result(result), indent=1))
    if len(results) == 1:
        _write(out / "results.json", json.dumps(gradescope_result(results[0]), indent=1))
    summary = [
        {
            "submission": _clean(r.name),
            "lesson": r.lesson,
            "score": r.earned,
            "max_score": r.points,
            "status": r.status,
            "mistakes": [_clean(m) for m in r.mistakes],
            "feedback": f"feedback/{name}.md",
            "results": f"results/{name}.json",
        }
        for r, name in zip(results, names)
    ]
    seeds = sorted({r.seed for r in results})
    isolation = sorted({r.isolation for r in results if r.isolation})
    _write(
        out / "summary.json",
        json.dumps({"seeds": seeds, "isolation": isolation, "submissions": summary}, indent=1),
    )
    _write(out / "gradebook.csv", _gradebook(results))
    return out
