"""The autograder, end to end: the student notebooks, wrong and correct variants, a hostile class,
the reports and the commands an instructor types."""

from __future__ import annotations

import csv
import hashlib
import importlib
import json
import os
import shlex
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from tests.hostile import HOSTILE, Context
from tests.notebooks import ROOT, notebook, solution_path, student_notebook, write
from urkin.course.grading import Grader, grade_many, grade_notebook, isolation, write_reports
from urkin.course.lessons import lessons

SEED = 424242
TIME_LIMIT = 5.0


def _row(result):
    """What must not depend on who else is in the class."""
    return [(e.exercise, e.earned, e.status, tuple(e.mistakes)) for e in result.exercises]


def _variants(kind: str, numbers=None):
    cases = []
    for number in lessons():
        if numbers and number not in numbers:
            continue
        module = importlib.import_module(f"tests.variants.lesson{number}")
        for index, v in enumerate(getattr(module, kind, [])):
            cases.append((number, index, v))
    return cases


@pytest.mark.parametrize("number", list(lessons()))
def test_the_student_notebooks_score_zero(number):
    (path,) = sorted((ROOT / "course").glob(f"{number}_*.ipynb"))
    result = grade_notebook(path, seed=SEED, time_limit=TIME_LIMIT)
    assert result.status == "graded", result.reason
    assert result.earned == 0
    assert {e.status for e in result.exercises} == {"not attempted"}, [
        e.report() for e in result.exercises
    ]


# through the isolated grader, a few variants of every exercise (all of them run in-process in
# tests/test_variants.py): the ones that exercise the grader's reading of a notebook most
PER_EXERCISE = {"WRONG": 3, "CORRECT": 2}


@pytest.fixture(scope="module")
def graded_variants(tmp_path_factory):
    """Some WRONG and CORRECT variants of every exercise, as notebooks, graded in one run."""
    folder = tmp_path_factory.mktemp("variants")
    cases = {}
    for kind, most in PER_EXERCISE.items():
        taken: dict[str, int] = {}
        for number, index, v in _variants(kind):
            if taken.get(v.exercise, 0) >= most:
                continue
            taken[v.exercise] = taken.get(v.exercise, 0) + 1
            function = lessons()[number].exercise(v.exercise).function
            name = f"{kind.lower()}_{v.exercise}_{index:03d}_{number}.ipynb"
            write(student_notebook(number, {function: v.source, **dict(v.also)}), folder / name)
            cases[name] = (kind, v)
    # the time limit only guards against hangs: a busy machine must not turn slow into wrong
    with Grader(SEED, time_limit=120.0, jobs=1) as grader, ThreadPoolExecutor(2) as pool:
        graded = pool.map(
            lambda n: grader.grade(folder / n, exercises=[cases[n][1].exercise]), cases
        )
        results = dict(zip(cases, graded))
    return cases, results


def test_wrong_variants_lose_their_points_through_the_grader(graded_variants):
    cases, results = graded_variants
    failures = []
    for name, (kind, v) in cases.items():
        if kind != "WRONG":
            continue
        (outcome,) = results[name].exercises
        lost = outcome.earned < outcome.points if v.points is None else outcome.earned == v.points
        named = v.mistake is None or any(v.mistake in m for m in outcome.mistakes)
        if not (lost and named):
            failures.append(f"{name} ({v.name}):\n{outcome.report()}")
    assert not failures, "\n\n".join(failures)


def test_correct_variants_earn_full_marks_through_the_grader(graded_variants):
    cases, results = graded_variants
    failures = []
    for name, (kind, v) in cases.items():
        if kind != "CORRECT":
            continue
        (outcome,) = results[name].exercises
        if outcome.status != "passed":
            failures.append(f"{name} ({v.name}):\n{outcome.report()}\n{results[name].notes}")
    assert not failures, "\n\n".join(failures)


def test_mistakes_are_named_for_most_wrong_variants(graded_variants):
    cases, results = graded_variants
    expected = [n for n, (kind, v) in cases.items() if kind == "WRONG" and v.mistake]
    named = [n for n in expected if results[n].exercises[0].mistakes]
    assert len(named) >= 0.9 * len(expected)


# ------------------------------------------------------------------------------ hostile class

HONEST = {
    "alice_02_dh_forward_kinematics.ipynb": lambda: student_notebook("02"),
    "bob_01_rigid_body_transforms.ipynb": lambda: student_notebook("01"),
    "carol_00_how_the_course_works.ipynb": lambda: student_notebook("00"),
    "dave_02_dh_forward_kinematics.ipynb": lambda: student_notebook(
        "02", {"dh_transform": _variants("WRONG", ["02"])[0][2].source}
    ),
    "erin_02_dh_forward_kinematics.ipynb": lambda: student_notebook("02", solved=False),
}


def _digest(folder: Path) -> dict[str, str]:
    out = {}
    for path in sorted(folder.rglob("*")):
        if path.is_file() and not path.is_symlink() and path.stat().st_size < 2**22:
            out[str(path.relative_to(folder))] = hashlib.sha256(path.read_bytes()).hexdigest()
    return out


def _chain(pid: int) -> list[bytes]:
    """The command lines of ``pid``'s live ancestors, parent first, PID 1 left out."""
    lines = []
    while pid > 1:
        try:
            with open(f"/proc/{pid}/stat", "rb") as handle:
                pid = int(handle.read().rsplit(b")", 1)[1].split()[1])
            if pid > 1:
                with open(f"/proc/{pid}/cmdline", "rb") as handle:
                    lines.append(handle.read())
        except (OSError, ValueError, IndexError):
            break
    return lines


def _children_alive(cache: Path) -> list[int]:
    """Submission processes still alive that came from the grading run whose views are in
    ``cache`` (a jail of that run among their ancestors), or that nothing but other
    submission processes holds (left behind): not those of tests running alongside."""
    found = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as handle:
                if b"course/grading/child.py" not in handle.read():
                    continue
        except OSError:
            continue
        chain = _chain(int(pid))
        ours = any(b"jail.py" in line and str(cache).encode() in line for line in chain)
        if ours or all(b"course/grading/child.py" in line for line in chain):
            found.append(int(pid))
    return found


ISOLATED = isolation.support().namespaces


@pytest.fixture(scope="module")
def hostile_class(tmp_path_factory):
    if not ISOLATED:  # without file isolation a submission can touch files: nothing to prove
        pytest.skip(isolation.support().summary)
    folder = tmp_path_factory.mktemp("class")
    out = tmp_path_factory.mktemp("grades")
    context = Context(folder, out, f"MARKER{os.getpid()}")
    for name, make in HONEST.items():
        write(make(), folder / name)
    honest_before = {n: (folder / n).read_bytes() for n in HONEST}
    for name, (make, _) in HOSTILE.items():
        make(folder / name, context)
    script = (
        "import json, resource, sys\n"
        "from urkin.course.grading import grade_many, write_reports\n"
        "results = grade_many([sys.argv[1]], seed=int(sys.argv[3]), time_limit=float(sys.argv[4]),"
        " setup_limit=10.0, jobs=2)\n"
        "write_reports(results, sys.argv[2])\n"
        # VmHWM is this process's own peak: ru_maxrss also keeps the peak of the process that
        # spawned it (Linux records the old memory's high-water mark at exec), here pytest's
        "peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss\n"
        "try:\n"
        "    for line in open('/proc/self/status'):\n"
        "        if line.startswith('VmHWM:'):\n"
        "            peak = int(line.split()[1])\n"
        "except OSError:\n"
        "    pass\n"
        "print(json.dumps({'rss_kb': peak, 'rows': len(results)}))\n"
    )
    cache = tmp_path_factory.mktemp("cache")  # this run's views: its jails name them
    start = time.monotonic()
    run = subprocess.run(
        [sys.executable, "-c", script, str(folder), str(out), str(SEED), str(TIME_LIMIT)],
        capture_output=True,
        text=True,
        timeout=900,
        env={**os.environ, "URKIN_CACHE": str(cache)},
    )
    elapsed = time.monotonic() - start
    assert run.returncode == 0, run.stderr[-3000:]
    stats = json.loads(run.stdout.strip().splitlines()[-1])
    reports_then = _digest(out)
    time.sleep(6)  # any daemon left behind would strike now
    return {
        "folder": folder,
        "out": out,
        "context": context,
        "stats": stats,
        "elapsed": elapsed,
        "reports_then": reports_then,
        "honest_before": honest_before,
        "cache": cache,
    }


def _gradebook(out: Path) -> dict[str, dict]:
    with open(out / "gradebook.csv", newline="", encoding="utf-8") as handle:
        return {row["submission"]: row for row in csv.DictReader(handle)}


def test_every_file_of_the_hostile_class_gets_one_row(hostile_class):
    book = _gradebook(hostile_class["out"])
    assert hostile_class["stats"]["rows"] == len(book)
    assert len(book) >= len(HONEST) + len(HOSTILE)
    for name in [*HONEST, *HOSTILE]:
        shown = name if not name.startswith(("=", "+", "-", "@")) else "'" + name
        shown = "".join("?" if (c < " " or "\u202a" <= c <= "\u202e") else c for c in shown)
        assert shown in book, name


def test_attacks_earn_nothing(hostile_class):
    results = json.loads((hostile_class["out"] / "summary.json").read_text())["submissions"]
    by_name = {r["submission"]: r for r in results}
    failures = []
    for name, (_, expected) in HOSTILE.items():
        if not expected:
            continue
        data = json.loads((hostile_class["out"] / by_name[name]["results"]).read_text())
        scores = {t["name"].split()[1]: t["score"] for t in data["tests"]}
        for exercise_id, most in expected.items():
            if scores.get(exercise_id, 0) > most:
                failures.append(f"{name}: {exercise_id} earned {scores[exercise_id]} > {most}")
    assert not failures, failures


def test_honest_students_get_exactly_the_row_they_get_alone(hostile_class):
    summary = json.loads((hostile_class["out"] / "summary.json").read_text())["submissions"]
    in_class = {r["submission"]: r for r in summary}
    for name in HONEST:
        alone = grade_notebook(hostile_class["folder"] / name, seed=SEED, time_limit=TIME_LIMIT)
        data = json.loads((hostile_class["out"] / in_class[name]["results"]).read_text())
        assert [t["score"] for t in data["tests"]] == [e.earned for e in alone.exercises], name
        assert in_class[name]["mistakes"] == alone.mistakes, name


def test_nothing_outside_its_row_changed(hostile_class):
    folder, out, marker = (
        hostile_class["folder"],
        hostile_class["out"],
        hostile_class["context"].marker,
    )
    for name, before in hostile_class["honest_before"].items():
        assert (folder / name).read_bytes() == before, name
    assert _digest(out) == hostile_class["reports_then"]  # nothing rewrote the reports later
    assert not (Path.cwd() / "RESULT.json").exists()
    for path in out.rglob("*"):
        if path.is_file() and marker in path.read_text(errors="replace"):
            assert "fake_report_text" in path.name or path.name in (
                "gradebook.csv",
                "summary.json",
            ), path
    cache = hostile_class["cache"]
    deadline = time.monotonic() + 5
    while _children_alive(cache) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert _children_alive(cache) == []


def test_the_grader_stays_small_and_within_its_time_bound(hostile_class):
    assert hostile_class["stats"]["rss_kb"] < 300 * 1024
    # 40-odd files, each exercise at most TIME_LIMIT plus start-up, two at a time
    assert hostile_class["elapsed"] < 600


def test_a_fake_report_stays_in_its_own_feedback(hostile_class):
    out = hostile_class["out"]
    (own,) = [p for p in (out / "feedback").iterdir() if "fake_report_text" in p.name]
    text = own.read_text()
    assert "\u202e" not in text and text.count("```") % 2 == 0
    alice = [p for p in (out / "feedback").iterdir() if p.name.startswith("alice_02")]
    total = sum(ex.points for ex in lessons()["02"].exercises)
    assert alice and f"{total:g} / {total:g}" in alice[0].read_text()
    book = (out / "gradebook.csv").read_text()
    assert "\n=" not in book and ",=" not in book


# ------------------------------------------------------------------------------ the reports


def test_reports_gradebook_feedback_and_one_gradescope_file_each(tmp_path):
    folder = tmp_path / "class"
    folder.mkdir()
    write(student_notebook("02"), folder / "a_02.ipynb")
    (folder / "sub").mkdir()
    write(
        student_notebook("02", {"dh_transform": _variants("WRONG", ["02"])[1][2].source}),
        folder / "sub" / "a_02.ipynb",
    )
    results = grade_many([folder], seed=SEED, time_limit=TIME_LIMIT)
    out = write_reports(results, tmp_path / "grades")
    book = _gradebook(out)
    assert set(book) == {"class/a_02.ipynb", "sub/a_02.ipynb"}  # parents tell them apart
    wrong = book["sub/a_02.ipynb"]
    assert wrong["2.1"] == "1" and "modified (Craig) DH" in wrong["mistakes"]
    results_files = sorted(p.name for p in (out / "results").iterdir())
    feedback_files = sorted(p.name for p in (out / "feedback").iterdir())
    assert len(results_files) == len(feedback_files) == 2  # names never collide
    for name in results_files:
        data = json.loads((out / "results" / name).read_text())
        assert {"score", "tests", "output"} <= set(data)
        assert all({"name", "score", "max_score", "output"} <= set(t) for t in data["tests"])
    assert not (out / "results.json").exists()  # one Gradescope file per submission
    assert json.loads((out / "summary.json").read_text())["submissions"]
    assert not list(out.rglob(".tmp-*"))  # written atomically


def test_a_single_submission_also_writes_gradescopes_results_json(tmp_path):
    path = write(student_notebook("00"), tmp_path / "a_00.ipynb")
    out = write_reports([grade_notebook(path, seed=SEED)], tmp_path / "grades")
    data = json.loads((out / "results.json").read_text())
    assert data["score"] == lessons()["00"].points


def test_reports_refuse_to_write_through_a_symbolic_link(tmp_path):
    path = write(student_notebook("00"), tmp_path / "a_00.ipynb")
    result = grade_notebook(path, seed=SEED)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (tmp_path / "grades").symlink_to(elsewhere)
    with pytest.raises(ValueError, match="symbolic link"):
        write_reports([result], tmp_path / "grades")
    assert list(elsewhere.iterdir()) == []


# ------------------------------------------------------------------------------ the commands


def _readme_commands() -> list[str]:
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    block = text[text.index("- Grade a class") :]
    start = block.index("```console") + len("```console")
    block = block[start : block.index("```", start)]
    return [line.split("#")[0].strip() for line in block.strip().splitlines()]


def test_the_readmes_grading_commands_work_as_written(tmp_path):
    commands = _readme_commands()
    assert commands[0].startswith(".venv/bin/urkin grade submissions/")
    submissions = tmp_path / "submissions"
    submissions.mkdir()
    write(student_notebook("02"), submissions / "alice_02_dh_forward_kinematics.ipynb")
    bin_dir = Path(sys.executable).parent
    for command in commands:
        argv = shlex.split(command)
        argv[0] = str(bin_dir / Path(argv[0]).name)
        argv = [
            a if not a.startswith(("submissions/", "grades/")) else str(tmp_path / a) for a in argv
        ]
        run = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True, timeout=600)
        assert run.returncode == 0, (command, run.stdout[-2000:], run.stderr[-2000:])
    assert (tmp_path / "grades" / "gradebook.csv").exists()


def test_the_solutions_score_full_marks_through_the_command(tmp_path):
    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "urkin",
            "grade",
            *map(str, map(solution_path, lessons())),
            "--out",
            str(tmp_path / "grades"),
            "--seed",
            str(SEED),
            "--quiet",
        ],
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert run.returncode == 0, run.stderr[-3000:]
    book = _gradebook(tmp_path / "grades")
    for row in book.values():
        assert row["total"] == row["max"], row
    assert "isolation:" in run.stdout


@pytest.mark.parametrize(
    ("option", "message"),
    [
        (["--lesson", "99"], "no lesson '99': the course's lessons are 00, 01"),
        (["--lesson", "nine"], "no lesson 'nine'"),
        (["--time-limit", "-5"], "argument --time-limit: must be above 0; got -5"),
        (["--time-limit", "nan"], "argument --time-limit: must be above 0; got nan"),
        (["--memory-limit", "0"], "argument --memory-limit: must be above 0; got 0"),
        (["--jobs", "two"], "argument --jobs: not a number: 'two'"),
        (["--setup-limit", "inf"], "argument --setup-limit: must be above 0; got inf"),
    ],
)
def test_grade_options_are_checked_before_any_grading(tmp_path, capsys, option, message):
    """A limit of no time or an unknown lesson would otherwise grade a whole class into
    rows of errors."""
    from urkin.cli import main

    with pytest.raises(SystemExit) as stop:
        main(["grade", str(tmp_path), "--out", str(tmp_path / "out"), *option])
    assert stop.value.code == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_names_that_look_alike_or_break_lines_stay_apart_and_on_one_line(tmp_path):
    """A zero-width space, a Cyrillic а, a formula or a quote in front, a line break: each
    row's ``file`` column (ASCII escapes) is its own, no invisible character reaches a
    report, and a name cannot write lines of its own into the feedback."""
    from urkin.course.grading.runner import SubmissionResult

    names = [
        "alice_02.ipynb",
        "alice\u200b_02.ipynb",
        "\u0430lice_02.ipynb",
        "=1+1_02.ipynb",
        "'=1+1_02.ipynb",
        "x\n\nLesson 02: 29 / 29 points\u2028_02.ipynb",
    ]
    results = [SubmissionResult(n, n, "02", SEED, "error", "a test") for n in names]
    out = write_reports(results, tmp_path / "grades")
    with open(out / "gradebook.csv", encoding="utf-8", newline="") as handle:
        rows = list(csv.DictReader(handle))
    assert len({row["file"] for row in rows}) == len(names)
    assert all(row["file"].isascii() and row["file"][0] in "'\"" for row in rows)
    for path in [out / "gradebook.csv", *(out / "feedback").iterdir()]:
        text = path.read_text(encoding="utf-8")
        assert not {"\u200b", "\u2028"} & set(text)
    fake = next(p for p in (out / "feedback").iterdir() if p.name.startswith("x"))
    assert fake.read_text(encoding="utf-8").splitlines()[:6] == [
        r"# x\?\?Lesson 02\: 29 \/ 29 points\?\_02\.ipynb",
        "",
        "Not graded:",
        "```",
        "a test",
        "```",
    ]


def test_no_name_takes_another_submissions_reports(tmp_path):
    """``bob 02.ipynb`` (a space) must not take ``bob_02.ipynb``'s feedback file, in whatever
    order they come: a name that had to be changed, or repeats another's but for case, gets a
    digest of its own name; a safe name keeps its own."""
    from urkin.course.grading.reports import report_names
    from urkin.course.grading.runner import SubmissionResult

    names = ["bob 02.ipynb", "bob_02.ipynb", "..ipynb", "a/x.ipynb", "x.ipynb"]
    for order in (names, names[::-1]):
        results = [SubmissionResult(n, n, "02", SEED, "error", "a test") for n in order]
        got = dict(zip(order, report_names(results)))
        assert got["bob_02.ipynb"] == "bob_02" and got["x.ipynb"] == "x"
        assert got["bob 02.ipynb"].startswith("bob_02-")
        assert len(set(got.values())) == len(names)
    alone = SubmissionResult("bob 02.ipynb", "", "02", SEED, "error")
    assert report_names([alone]) == [got["bob 02.ipynb"]]  # stable: a digest of the name
    # names that differ only in case (one file on a case-insensitive disk): both digested
    pair = [SubmissionResult(n, n, "02", SEED, "error") for n in ("Bob_02.ipynb", "bob_02.ipynb")]
    for order in (pair, pair[::-1]):
        first, second = report_names(order)
        assert first.lower() != second.lower() and "-" in first and "-" in second


def test_text_from_a_submission_stays_literal_in_its_feedback(tmp_path):
    """A note or an error message may hold markdown, HTML or a run of backticks; the feedback
    shows it in a code block it cannot close, and the title escaped: no fake score in bold, no
    remote image, no raw HTML rendered."""
    from urkin.course.grading.reports import feedback_text
    from urkin.course.grading.runner import SubmissionResult

    attack = "**Lesson 02: 29 / 29 points** ![](http://evil.example/p.png) <script>x</script>"
    result = SubmissionResult(
        "![](http://evil.example/p.png) <b>bob</b>_02.ipynb",
        "",
        "02",
        SEED,
        "graded",
        notes=[f"an error: {attack}", "`````\n# Lesson 02: 29 / 29 points\n`````"],
    )
    text = feedback_text(result)
    title = text.splitlines()[0]
    assert title.startswith("# ") and "![](" not in title and "<b>" not in title
    body = text.split("About the notebook:\n", 1)[1]
    fence = body.splitlines()[0]
    assert set(fence) == {"`"} and len(fence) >= 3
    inside, after = body[len(fence) + 1 :].split("\n" + fence + "\n", 1)
    assert attack in inside and "# Lesson 02: 29 / 29 points" in inside
    assert not any(line.startswith(fence) for line in inside.splitlines())  # cannot close it
    assert "29 / 29" not in after and "<script>" not in after


def test_a_lesson_the_metadata_and_the_file_name_disagree_on_is_not_graded(tmp_path):
    # a finished lesson-02 notebook handed in as lesson 01 (Gradescope's run_autograder sees
    # one file) must not earn lesson 02's points there; --lesson settles it
    from urkin.course.grading.read import read_notebook

    path = write(notebook("x = 1", lesson="09"), tmp_path / "02_dh_forward_kinematics.ipynb")
    read = read_notebook(path)
    assert read.lesson is None
    assert "metadata says lesson 09 and its file name lesson 02: not graded" in read.conflict
    assert read_notebook(path, "02").lesson == "02" and not read_notebook(path, "02").conflict
    agreed = read_notebook(write(notebook("x = 1", lesson="02"), tmp_path / "bob_02.ipynb"))
    assert agreed.lesson == "02" and not agreed.conflict
    chosen = read_notebook(write(notebook("x = 1", lesson="09"), tmp_path / "alice_02_dh.ipynb"))
    assert chosen.lesson == "09" and any("graded as lesson 09" in n for n in chosen.notes)
    with Grader(seed=0) as grader:
        result = grader.grade(path)
    assert result.status == "unknown lesson" and result.earned == 0
    assert "metadata says lesson 09" in result.reason


def test_without_namespaces_no_submission_sees_the_view_cache(tmp_path, monkeypatch):
    """Unisolated (no user namespaces, or URKIN_NO_SANDBOX), a submission runs as the grader's
    user and could rewrite its view of urkin: it gets one made for this run, never the
    cache's, which later runs (isolated ones too) trust."""
    monkeypatch.setenv("URKIN_NO_SANDBOX", "1")
    monkeypatch.setenv("URKIN_CACHE", str(tmp_path / "cache"))
    isolation.support.cache_clear()
    try:
        path = write(student_notebook("00"), tmp_path / "a_00.ipynb")
        assert grade_notebook(path, seed=SEED, time_limit=TIME_LIMIT).status == "graded"
        assert not (tmp_path / "cache" / "views").exists()
    finally:
        isolation.support.cache_clear()


@pytest.mark.parametrize(
    ("number", "exercise", "function", "body"),
    [
        ("00", "0.2", "base_link_pose", "return args[0]"),
        ("04", "4.3", "jacobian_space", "return args[0]"),
        ("04", "4.4", "jacobian_body", "return args[0]"),
        ("04", "4.6", "manipulability", "return 0"),
        ("06", "6.5", "damping_for_step", "return 1e300"),
        ("09", "9.3", "path_is_free", "return True"),
        ("09", "9.3", "path_is_free", "return 0"),
    ],
)
def test_a_trivial_body_earns_nothing(tmp_path, number, exercise, function, body):
    """Returning the argument, 0, True or a huge number passes a special case of some checks
    (the Jacobian at q = 0 is the screw axes it is given): such checks are gated, and earn
    their point only with the function's real answers."""
    source = f"def {function}(*args, **kwargs):\n    {body}\n"
    path = write(student_notebook(number, {function: source}), tmp_path / f"t_{number}.ipynb")
    with Grader(SEED, TIME_LIMIT) as grader:
        result = grader.grade(path, exercises=[exercise])
    assert result.exercise(exercise).earned == 0


def test_a_stub_kept_above_the_function_written_in_a_new_cell_is_not_what_is_graded(tmp_path):
    # a student keeps the exercise cell's stub and writes rot_z in a new cell below it: the
    # check cell sees the new one, and so does the grader (with a note)
    data = student_notebook("01", solved=False)
    at = next(i for i, c in enumerate(data["cells"]) if "def rot_z(" in "".join(c["source"]))
    mine = dict(data["cells"][at], id="mine")
    mine["source"] = (
        "def rot_z(theta):\n"
        "    c, s = np.cos(theta), np.sin(theta)\n"
        "    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])\n"
    )
    data["cells"].insert(at + 1, mine)
    path = write(data, tmp_path / "alice_01.ipynb")
    with Grader(SEED, TIME_LIMIT) as grader:
        result = grader.grade(path, exercises=["1.1"])
    (outcome,) = result.exercises
    assert outcome.earned == outcome.points, outcome.report()
    assert any("still holds the stub of `rot_z`" in n for n in result.notes), result.notes
