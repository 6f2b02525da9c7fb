"""Starting a submission's process in isolation, and ending it with everything it started.

On Linux every submission process runs in the sandbox of :mod:`urkin.course.grading.jail`
(its own user, mount, PID and network namespaces, a read-only view of the system and of urkin
where only a small tmpfs is writable), under a memory limit that counts every process it
starts (a cgroup, when the grader may create one; otherwise a per-process address-space limit
and a cap on the number of processes), and dies with all its processes when the grader ends
it.  Where namespaces are not available (macOS, kernels that forbid unprivileged user
namespaces) the process still runs in a private temporary directory with resource limits,
scores are still computed outside it, and :func:`support` says loudly that file isolation is
off — the grader prints that and writes it into every report.
"""

from __future__ import annotations

import functools
import hashlib
import json
import os
import re
import secrets
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

__all__ = ["Limits", "Process", "Support", "cache_folder", "start", "support"]

JAIL = Path(__file__).with_name("jail.py")
_SYSTEM = ("/usr", "/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32", "/etc")


@dataclass(frozen=True)
class Limits:
    """What one submission process (with everything it starts) may use."""

    memory_bytes: int = 1024 * 2**20
    tasks: int = 64  # processes and threads
    file_bytes: int = 64 * 2**20  # largest file, and the size of its writable /tmp
    open_files: int = 256


@dataclass(frozen=True)
class Support:
    """What isolation this machine gives submission processes."""

    namespaces: bool
    memory: str  # "cgroup v2", "cgroup v1" or "per process"
    reason: str = ""  # why namespaces are off

    @property
    def summary(self) -> str:
        if self.namespaces:
            files = "isolated (own user, mount, PID and network namespaces; read-only system)"
        else:
            files = f"NOT ISOLATED: {self.reason}"
        memory = (
            "counted for all its processes by a " + self.memory
            if self.memory.startswith("cgroup")
            else "limited per process (RLIMIT_AS) with a cap on the number of processes"
        )
        return f"submission files {files}; memory {memory}"


def cache_folder() -> Path | None:
    """``$URKIN_CACHE``, else ``$XDG_CACHE_HOME/urkin`` or ``~/.cache/urkin``, if it is ours and
    only ours to write (the grader keeps its views of urkin and its sandbox probe there)."""
    base = os.environ.get("URKIN_CACHE") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"), "urkin"
    )
    path = Path(base)
    try:
        path.mkdir(parents=True, exist_ok=True, mode=0o755)
        info = path.stat()
        if path.is_symlink() or info.st_uid != os.getuid() or info.st_mode & 0o022:
            return None
        return path
    except OSError:
        return None


# ----------------------------------------------------------------------------- cgroups


def _mounts() -> list[tuple[str, str, str]]:
    found = []
    try:
        with open("/proc/self/mountinfo") as handle:
            for line in handle:
                left, _, right = line.partition(" - ")
                fields, more = left.split(), right.split()
                if len(fields) >= 5 and len(more) >= 3:
                    found.append((fields[4], more[0], more[2]))  # mount point, fstype, options
    except OSError:
        pass
    return found


def _own_cgroups() -> dict[str, str]:
    own = {}
    try:
        with open("/proc/self/cgroup") as handle:
            for line in handle:
                _, controllers, path = line.rstrip("\n").split(":", 2)
                for controller in controllers.split(",") if controllers else [""]:
                    own[controller] = path
    except OSError:
        pass
    return own


@functools.cache
def _cgroup_parents() -> tuple[str, tuple[str, ...]]:
    """("cgroup v1" or "cgroup v2", directories under which sandboxes get their groups)."""
    own = _own_cgroups()
    mounts = _mounts()
    v1 = {}
    for point, fstype, options in mounts:
        if fstype == "cgroup":
            for controller in ("memory", "pids"):
                if controller in options.split(",") and controller in own:
                    v1[controller] = os.path.join(point, own[controller].lstrip("/"))
    if len(v1) == 2 and all(os.access(p, os.W_OK) for p in v1.values()):
        return "cgroup v1", (v1["memory"], v1["pids"])
    for point, fstype, _ in mounts:
        if fstype == "cgroup2" and "" in own:
            here = os.path.join(point, own[""].lstrip("/"))
            try:
                with open(os.path.join(here, "cgroup.subtree_control")) as handle:
                    enabled = handle.read().split()
            except OSError:
                continue
            if {"memory", "pids"} <= set(enabled) and os.access(here, os.W_OK):
                return "cgroup v2", (here,)
    return "per process", ()


class _Group:
    """The cgroup(s) of one sandbox."""

    def __init__(self, limits: Limits) -> None:
        kind, parents = _cgroup_parents()
        self.kind, self.dirs = kind, []
        name = f"urkin-{os.getpid()}-{secrets.token_hex(4)}"
        try:
            for parent in parents:
                path = os.path.join(parent, name)
                os.mkdir(path)
                self.dirs.append(path)
            if kind == "cgroup v1":
                memory, pids = self.dirs
                _put(memory, "memory.limit_in_bytes", limits.memory_bytes)
                _put(memory, "memory.memsw.limit_in_bytes", limits.memory_bytes, optional=True)
                _put(pids, "pids.max", limits.tasks)
            elif kind == "cgroup v2":
                (group,) = self.dirs
                _put(group, "memory.max", limits.memory_bytes)
                _put(group, "memory.swap.max", 0, optional=True)
                _put(group, "pids.max", limits.tasks)
        except OSError:
            self.close()
            self.kind, self.dirs = "per process", []

    @property
    def procs(self) -> list[str]:
        return [os.path.join(d, "cgroup.procs") for d in self.dirs]

    def kill(self) -> None:
        for _ in range(50):
            pids = set()
            for procs in self.procs:
                try:
                    with open(procs) as handle:
                        pids |= {int(p) for p in handle.read().split()}
                except OSError:
                    pass
            if not pids:
                return
            for pid in pids:
                try:
                    os.kill(pid, signal.SIGKILL)
                except (ProcessLookupError, PermissionError):
                    pass
            time.sleep(0.01)

    def close(self) -> None:
        self.kill()
        for path in reversed(self.dirs):
            for _ in range(100):
                try:
                    os.rmdir(path)
                    break
                except FileNotFoundError:
                    break
                except OSError:
                    time.sleep(0.01)
        self.dirs = []


def _put(directory: str, name: str, value: int, optional: bool = False) -> None:
    try:
        with open(os.path.join(directory, name), "w") as handle:
            handle.write(str(value))
    except OSError:
        if not optional:
            raise


# ----------------------------------------------------------------------------- the sandbox


def _python_paths() -> list[str]:
    """Directories the child's Python needs: its prefixes and site-packages, never the course
    repository itself."""
    paths = {sys.base_prefix, sys.prefix, sys.exec_prefix}
    for entry in sys.path:
        if entry and ("site-packages" in entry or "dist-packages" in entry):
            paths.add(entry)
    for path in list(paths):
        paths.add(os.path.realpath(path))
    paths.add(os.path.dirname(os.path.dirname(os.path.realpath(sys.executable))))
    return sorted(p for p in paths if os.path.isdir(p))


def _rlimits(limits: Limits, namespaces: bool) -> dict[str, int]:
    address_space = limits.memory_bytes + 768 * 2**20  # the interpreter and numpy's mappings
    return {
        "RLIMIT_AS": address_space,
        "RLIMIT_FSIZE": limits.file_bytes,
        "RLIMIT_NOFILE": limits.open_files,
        "RLIMIT_CORE": 0,
        **({"RLIMIT_NPROC": limits.tasks} if namespaces else {}),
    }


def _environment(home: str) -> dict[str, str]:
    return {
        "PATH": "/usr/local/bin:/usr/bin:/bin",
        "HOME": home,
        "TMPDIR": home,
        "LANG": "C.UTF-8",
        "MPLBACKEND": "Agg",
        "MPLCONFIGDIR": os.path.join(home, ".matplotlib"),
        "OPENBLAS_NUM_THREADS": "1",
        "OMP_NUM_THREADS": "1",
        "MKL_NUM_THREADS": "1",
        "PYTHONHASHSEED": "0",
    }


class Process:
    """A running submission process; :meth:`end` kills it and everything it started."""

    def __init__(self, popen: subprocess.Popen, group: _Group, scratch: str) -> None:
        self.popen, self._group, self._scratch = popen, group, scratch

    @property
    def stderr(self):
        return self.popen.stderr

    def end(self) -> int | None:
        """Kill the process tree (if still running), wait until every process of it is gone,
        clean up; return the exit status."""
        tree = _descendants(self.popen.pid)
        for pid in [self.popen.pid, *tree]:
            try:
                os.kill(pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
        try:
            os.killpg(self.popen.pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass
        self._group.kill()
        try:
            status = self.popen.wait(timeout=10)
        except subprocess.TimeoutExpired:
            status = None
        deadline = time.monotonic() + 10
        while any(_running(pid) for pid in tree) and time.monotonic() < deadline:
            time.sleep(0.005)
        if self.popen.stderr is not None:
            self.popen.stderr.close()
        self._group.close()
        shutil.rmtree(self._scratch, ignore_errors=True)
        return status


def _descendants(root: int) -> list[int]:
    """Every process below ``root`` (from /proc; empty where there is no /proc)."""
    parents: dict[int, list[int]] = {}
    try:
        entries = os.listdir("/proc")
    except OSError:
        return []
    for entry in entries:
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat", "rb") as handle:
                fields = handle.read().rsplit(b")", 1)[1].split()
            parents.setdefault(int(fields[1]), []).append(int(entry))
        except (OSError, IndexError, ValueError):
            continue
    found, todo = [], [root]
    while todo:
        for child in parents.get(todo.pop(), []):
            found.append(child)
            todo.append(child)
    return found


def _running(pid: int) -> bool:
    """Whether ``pid`` is alive (a zombie counts as gone)."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as handle:
            return handle.read().rsplit(b")", 1)[1].split()[0] != b"Z"
    except (OSError, IndexError):
        return False


def start(
    view: Path,
    package: Path,
    arguments: list[str],
    limits: Limits,
    pass_fds: tuple[int, ...],
    isolate: bool = True,
) -> Process:
    """Start the child runtime of ``view`` (a directory holding the view's ``urkin``).

    Parameters
    ----------
    view : Path
        Directory containing the submission's copy of the ``urkin`` package.
    package : Path
        urkin's real package directory: in the sandbox the view is mounted over it.
    arguments : list of str
        Arguments for the child runtime after the script.
    limits : Limits
    pass_fds : tuple of int
        Pipe ends the child talks through.
    isolate : bool
        Use the namespace sandbox when :func:`support` says it works.
    """
    group = _Group(limits)
    scratch = tempfile.mkdtemp(prefix="urkin-sandbox-")
    os.chmod(scratch, 0o777)
    jailed = isolate and support().namespaces
    if jailed:
        script = str(package / "course" / "grading" / "child.py")
        binds = [[p, p] for p in (*_SYSTEM, *_python_paths())]
        binds.append([str(view / "urkin"), str(package)])
        config = {
            "root": scratch,
            "binds": binds,
            "tmpfs": {"/tmp": limits.file_bytes, "/dev/shm": 16 * 2**20},
            "cgroups": group.procs,
            "rlimits": _rlimits(limits, True),
            "env": _environment("/tmp"),
            "cwd": "/tmp",
            "pass_fds": list(pass_fds),
        }
        command = _jailed(config, [script, *arguments])
        cwd = "/"
    else:
        script = str(view / "urkin" / "course" / "grading" / "child.py")
        command = [sys.executable, "-I", "-B", script, *arguments, _json(_rlimits(limits, False))]
        cwd = scratch
    popen = subprocess.Popen(
        command,
        cwd=cwd,
        env=_environment("/tmp" if jailed else scratch),
        stdin=subprocess.DEVNULL,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        pass_fds=pass_fds,
        start_new_session=True,
    )
    if not jailed and group.dirs:
        for procs in group.procs:
            try:
                with open(procs, "w") as handle:
                    handle.write(str(popen.pid))
            except OSError:
                pass
    return Process(popen, group, scratch)


def _jailed(config: dict, python_arguments: list[str]) -> list[str]:
    """The command that runs this Python with ``python_arguments`` in the jail of ``config``."""
    python = [sys.executable, "-I", "-B"]
    return [*python, str(JAIL), _json(config), *python, *python_arguments]


def _json(value: dict) -> str:
    return json.dumps(value, separators=(",", ":"))


def _probe_record() -> Path | None:
    """Where the probe's answer is kept: one file per boot, user, Python and jail."""
    cache = cache_folder()
    try:
        with open("/proc/sys/kernel/random/boot_id") as handle:
            boot = handle.read().strip()
    except OSError:
        return None
    if cache is None:
        return None
    digest = hashlib.sha256(f"{boot}:{os.getuid()}:{sys.executable}".encode())
    digest.update(JAIL.read_bytes())
    return cache / f"sandbox-{digest.hexdigest()[:24]}.json"


@functools.cache
def support() -> Support:
    """Whether submissions can run in the namespace sandbox: probed once per boot (the answer
    is kept in the grader's cache folder), and always a fresh process."""
    memory = _cgroup_parents()[0]
    if not sys.platform.startswith("linux"):
        return Support(False, memory, f"{sys.platform} has no Linux namespaces")
    if os.environ.get("URKIN_NO_SANDBOX"):
        return Support(False, memory, "URKIN_NO_SANDBOX is set")
    record = _probe_record()
    try:
        if record is not None and record.exists():
            known = json.loads(record.read_text())
            return Support(bool(known["namespaces"]), memory, str(known["reason"]))
    except (OSError, ValueError, KeyError):
        pass
    found = _probe(memory)
    if record is not None:
        try:
            record.write_text(json.dumps({"namespaces": found.namespaces, "reason": found.reason}))
        except OSError:
            pass
    return found


def _probe(memory: str) -> Support:
    """Run a trivial command in the sandbox and see that it is PID 1 and sees nothing of ours."""
    scratch = tempfile.mkdtemp(prefix="urkin-probe-")
    os.chmod(scratch, 0o777)
    try:
        binds = [[p, p] for p in (*_SYSTEM, *_python_paths())]
        config = {
            "root": scratch,
            "binds": binds,
            "tmpfs": {"/tmp": 2**20},
            "env": {},
            "cwd": "/tmp",
            "rlimits": {},
        }
        secret = os.path.join(scratch, "outside")  # the sandbox must not see it
        Path(secret).touch()
        probe = f"import os; print(os.getpid(), os.path.exists({secret!r}))"
        result = subprocess.run(
            _jailed(config, ["-c", probe]),
            capture_output=True,
            text=True,
            timeout=30,
        )
    except (OSError, subprocess.SubprocessError) as exc:
        return Support(False, memory, f"the sandbox could not start ({exc})")
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    if result.returncode == 0 and re.fullmatch(r"1 False\s*", result.stdout):
        return Support(True, memory)
    why = (result.stderr.strip().splitlines() or ["no reason given"])[-1]
    return Support(False, memory, f"Linux namespaces are not available here ({why[:200]})")
