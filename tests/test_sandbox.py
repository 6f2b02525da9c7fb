"""The process that runs a submission: what it can see, write, reach, use and leave behind."""

from __future__ import annotations

import os
import time

import numpy as np
import pytest

from tests.notebooks import notebook, write
from urkin.course.answers import PACKAGE, answer_for
from urkin.course.grading import isolation
from urkin.course.grading.read import read_notebook
from urkin.course.grading.remote import RemoteSubmission
from urkin.course.lessons import exercise
from urkin.course.submission import StudentRaised, SubmissionGone

ISOLATED = isolation.support().namespaces
needs_namespaces = pytest.mark.skipif(not ISOLATED, reason=isolation.support().reason)


@pytest.fixture(scope="module")
def view(tmp_path_factory):
    folder = tmp_path_factory.mktemp("view")
    os.chmod(folder, 0o755)
    return answer_for(exercise("2.2")).write_view(folder)


def sandboxed(tmp_path, view, source, limits=None, time_limit=20.0):
    """The notebook cell ``source`` defined in a sandboxed child, ready for calls."""
    nb = read_notebook(
        write(
            notebook("import os, sys, time\nimport numpy as np", source),
            tmp_path / "probe_02.ipynb",
        )
    )
    names = {n for s in nb.sites for n in s.binds if s.cell == 2}
    plan = nb.plan(names, {})
    child = RemoteSubmission(
        nb, {}, plan, view, PACKAGE, limits or isolation.Limits(), time_limit, 30.0
    )
    child.start()
    return child


@needs_namespaces
def test_the_submission_sees_no_course_files_and_writes_only_tmp(tmp_path, view):
    repository = str(PACKAGE.parent)
    child = sandboxed(
        tmp_path,
        view,
        f"""
def look():
    out = {{}}
    out["repository"] = sorted(os.listdir({repository!r}))
    out["pid"] = os.getpid()
    out["uid"] = os.getuid()
    for target in ("/evil", {str(PACKAGE / "evil.py")!r}, "/tmp/ok"):
        try:
            open(target, "w").write("x")
            out[target] = "written"
        except OSError as exc:
            out[target] = exc.strerror
    out["grader temp"] = os.path.exists({str(view)!r})
    out["kinematics source"] = "def fk(" in open({str(PACKAGE / "kinematics.py")!r}).read()
    return out
""",
    )
    try:
        seen = child.call("look")
    finally:
        child.close()
    assert set(seen["repository"]) <= {"urkin", ".venv"}
    assert seen["pid"] == 1 and seen["uid"] != 0
    assert seen["/evil"] == "Read-only file system"
    assert seen[str(PACKAGE / "evil.py")] == "Read-only file system"
    assert seen["/tmp/ok"] == "written"
    assert seen["grader temp"] is False
    assert seen["kinematics source"] is False
    assert not (PACKAGE / "evil.py").exists()


@needs_namespaces
def test_no_network(tmp_path, view):
    child = sandboxed(
        tmp_path,
        view,
        """
import socket
def connect():
    try:
        socket.create_connection(("127.0.0.1", 22), timeout=2)
        return "connected"
    except OSError as exc:
        return type(exc).__name__
""",
    )
    try:
        assert child.call("connect") in ("ConnectionRefusedError", "OSError")
    finally:
        child.close()


def _alive(marker: str) -> list[int]:
    found = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as handle:
                if marker.encode() in handle.read():
                    found.append(int(pid))
        except OSError:
            pass
    return found


def test_processes_it_starts_die_with_it(tmp_path, view):
    marker = f"urkin-orphan-{os.getpid()}-{time.time_ns()}"
    child = sandboxed(
        tmp_path,
        view,
        f"""
import subprocess
def spawn():
    for _ in range(3):
        subprocess.Popen([sys.executable, "-c", "import time; time.sleep(600)", {marker!r}],
                         start_new_session=True)
    return os.getpid()
""",
    )
    try:
        child.call("spawn")
        deadline = time.monotonic() + 10  # a busy machine may not have run exec() yet
        while len(_alive(marker)) < 3 and time.monotonic() < deadline:
            time.sleep(0.05)
        assert len(_alive(marker)) == 3
    finally:
        child.close()
    deadline = time.monotonic() + 10
    while _alive(marker) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert _alive(marker) == []


def test_an_infinite_loop_stops_at_the_time_limit(tmp_path, view):
    child = sandboxed(
        tmp_path, view, "def spin(x):\n    while True:\n        pass\n", time_limit=2.0
    )
    start = time.monotonic()
    try:
        with pytest.raises(SubmissionGone, match="stopped after 2 s") as gone:
            child.call("spin", 1.0)
    finally:
        child.close()
    assert gone.value.status == "timeout"
    assert time.monotonic() - start < 6


@needs_namespaces
def test_memory_is_counted_over_all_its_processes(tmp_path, view):
    if not isolation.support().memory.startswith("cgroup"):
        pytest.skip("no cgroup for the memory of a process tree here")
    child = sandboxed(
        tmp_path,
        view,
        """
def grow():
    children = []
    for _ in range(4):
        pid = os.fork()
        if pid == 0:
            block = np.ones(300 * 2**20 // 8)  # 300 MB each, under the per-process limit
            time.sleep(30)
            os._exit(0)
        children.append(pid)
    # until two are gone (a busy machine allocates slowly), or 15 s: they would sleep 30
    statuses = {}
    deadline = time.monotonic() + 15
    while len(statuses) < 2 and time.monotonic() < deadline:
        for pid in children:
            if pid not in statuses:
                done = os.waitpid(pid, os.WNOHANG)
                if done != (0, 0):
                    statuses[pid] = done
        time.sleep(0.05)
    return [statuses.get(pid, (0, 0)) for pid in children]
""",
        limits=isolation.Limits(memory_bytes=512 * 2**20),
    )
    try:
        outcome = child.call("grow")
        # the kernel ended the children that went over 512 MB together
        assert sum(status != (0, 0) for status in outcome) >= 2
    except SubmissionGone as gone:
        assert gone.status == "crashed"
    finally:
        child.close()


def test_a_flood_on_stderr_keeps_the_grader_small(tmp_path, view):
    child = sandboxed(
        tmp_path,
        view,
        """
def shout(n):
    block = b"x" * 2**20
    for _ in range(n):
        os.write(2, block)
    return n
""",
    )
    try:
        assert child.call("shout", 200) == 200
        assert len(child.stderr) <= 4096
    finally:
        child.close()


def test_a_huge_answer_is_refused(tmp_path, view):
    child = sandboxed(tmp_path, view, "def big():\n    return np.ones(10**8)\n")
    try:
        with pytest.raises((StudentRaised, SubmissionGone), match=r"too large|larger"):
            child.call("big")
    finally:
        child.close()


def test_a_forged_reply_is_only_ever_the_functions_own_answer(tmp_path, view):
    child = sandboxed(
        tmp_path,
        view,
        """
import json
def forge(x):
    fd = int(sys.argv[2])
    os.write(fd, (json.dumps({"id": 999, "value": 1e9}) + "\\n").encode())
    os.write(fd, b"not json at all\\n")
    return x + 1.0
""",
    )
    try:
        assert child.call("forge", np.float64(1.0)) == 2.0
    finally:
        child.close()


def test_without_namespaces_grading_still_works_and_says_so(tmp_path, view, monkeypatch):
    monkeypatch.setenv("URKIN_NO_SANDBOX", "1")
    isolation.support.cache_clear()
    try:
        assert "NOT ISOLATED" in isolation.support().summary
        child = sandboxed(tmp_path, view, "def double(x):\n    return 2 * x\n")
        try:
            assert child.call("double", 2.5) == 5.0
        finally:
            child.close()
    finally:
        isolation.support.cache_clear()
