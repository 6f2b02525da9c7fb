"""Run one command in a sandbox of Linux namespaces (standard library only, run by path)::

    python -I -B jail.py CONFIG_JSON COMMAND...

The command runs in its own mount, PID, network, IPC and UTS namespaces and its own user
namespace, as an unprivileged user (``nobody`` when the grader runs as root):

* **files**: a new root made of read-only bind mounts of the system and Python directories
  the grader names (``binds``), the submission's view of urkin mounted over urkin's own
  directory, a fresh ``/proc``, a minimal ``/dev`` and small private tmpfs mounts (``tmpfs``,
  the only writable places).  Everything else — the course's solutions, other submissions,
  the grader's output folder, home directories — does not exist in there;
* **processes**: the command is PID 1 of its namespace; when it ends, or when this jail process
  is killed, the kernel kills every process it started;
* **network**: none (a new network namespace has only a loopback device, down);
* **limits**: resource limits set before the command starts (``rlimits``), which it cannot
  raise, and the cgroups named in ``cgroups`` (joined while still privileged).

Exit status: the command's; 125 with a line on stderr when the sandbox cannot be made.
"""

import ctypes
import json
import os
import platform
import resource
import signal
import stat
import sys

CLONE_NEWNS = 0x00020000
CLONE_NEWUTS = 0x04000000
CLONE_NEWIPC = 0x08000000
CLONE_NEWUSER = 0x10000000
CLONE_NEWPID = 0x20000000
CLONE_NEWNET = 0x40000000
MS_RDONLY, MS_NOSUID, MS_NODEV, MS_NOEXEC = 1, 2, 4, 8
MS_REMOUNT, MS_NOATIME, MS_NODIRATIME, MS_BIND, MS_REC = 32, 1024, 2048, 4096, 16384
MS_PRIVATE, MS_RELATIME, MS_STRICTATIME = 1 << 18, 1 << 21, 1 << 24
MNT_DETACH = 2
PR_SET_PDEATHSIG, PR_SET_DUMPABLE, PR_SET_NO_NEW_PRIVS = 1, 4, 38
SYS_PIVOT_ROOT = {
    "x86_64": 155,
    "aarch64": 41,
    "arm64": 41,
    "riscv64": 41,
    "ppc64le": 203,
    "s390x": 217,
    "armv7l": 218,
    "i686": 217,
}
NOBODY = 65534

_libc = ctypes.CDLL(None, use_errno=True)


class JailError(Exception):
    pass


def _check(result: int, what: str) -> None:
    if result != 0:
        error = ctypes.get_errno()
        raise JailError(f"{what}: {os.strerror(error)}")


def _mount(source, target, fstype, flags, data=None) -> None:
    encode = lambda s: s.encode() if s is not None else None  # noqa: E731
    _check(
        _libc.mount(
            encode(source), encode(target), encode(fstype), ctypes.c_ulong(flags), encode(data)
        ),
        f"mount {source or ''} on {target}",
    )


def _write(path: str, text: str) -> None:
    fd = os.open(path, os.O_WRONLY)
    try:
        os.write(fd, text.encode())
    finally:
        os.close(fd)


def _die_with_parent() -> None:
    parent = os.getppid()
    _libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    if os.getppid() != parent:  # the parent died before the request took effect
        os._exit(125)


def _locked_flags(path: str) -> int:
    """Flags a read-only remount must keep (the kernel refuses to drop them in a namespace)."""
    flags = os.statvfs(path).f_flag
    out = 0
    for st, ms in (
        (os.ST_NOSUID, MS_NOSUID),
        (os.ST_NODEV, MS_NODEV),
        (os.ST_NOEXEC, MS_NOEXEC),
        (os.ST_NOATIME, MS_NOATIME),
        (os.ST_NODIRATIME, MS_NODIRATIME),
        (getattr(os, "ST_RELATIME", 4096), MS_RELATIME),
    ):
        if flags & st:
            out |= ms
    return out


def _submounts(path: str) -> list[str]:
    found = []
    with open("/proc/self/mountinfo") as handle:
        for line in handle:
            point = line.split()[4].encode().decode("unicode_escape")
            if point == path or point.startswith(path.rstrip("/") + "/"):
                found.append(point)
    return sorted(found, key=len)


def _read_only(path: str) -> None:
    for point in _submounts(path):
        try:
            _mount(None, point, None, MS_REMOUNT | MS_BIND | MS_RDONLY | _locked_flags(point))
        except (JailError, OSError):
            if point == path:
                raise


def _make_target(source: str, target: str) -> None:
    if os.path.lexists(target):
        return
    parent = os.path.dirname(target)
    os.makedirs(parent, mode=0o755, exist_ok=True)
    if stat.S_ISDIR(os.stat(source).st_mode):
        os.mkdir(target, 0o755)
    else:
        os.close(os.open(target, os.O_WRONLY | os.O_CREAT, 0o644))


def _bind(source: str, root: str, target: str, writable: bool = False) -> None:
    inside = root + target
    if os.path.islink(source) and os.path.dirname(os.path.normpath(source)) == "/":
        # a top-level symlink (merged /usr: /bin -> usr/bin): recreate it
        if not os.path.lexists(inside):
            os.symlink(os.readlink(source), inside)
        return
    _make_target(source, inside)
    _mount(source, inside, None, MS_BIND | MS_REC)
    if not writable:
        _read_only(inside)


def _tmpfs(root: str, target: str, size: int, mode: str = "1777") -> None:
    inside = root + target
    os.makedirs(inside, mode=0o755, exist_ok=True)
    _mount("tmpfs", inside, "tmpfs", MS_NOSUID | MS_NODEV, f"size={size},mode={mode}")


def _pivot(root: str) -> None:
    old = root + "/.old-root"
    os.mkdir(old, 0o700)
    number = SYS_PIVOT_ROOT.get(platform.machine())
    if number is not None and _libc.syscall(number, root.encode(), old.encode()) == 0:
        os.chdir("/")
        _check(_libc.umount2(b"/.old-root", MNT_DETACH), "umount the old root")
        os.rmdir("/.old-root")
    else:  # no pivot_root number for this machine: chroot, then the old root is out of reach
        os.chroot(root)
        os.chdir("/")


def _build_root(config: dict) -> None:
    root = config["root"]
    _mount(None, "/", None, MS_REC | MS_PRIVATE)
    _mount("tmpfs", root, "tmpfs", MS_NOSUID | MS_NODEV, "size=4m,mode=0755")
    os.makedirs(root + "/dev", mode=0o755)
    _mount("tmpfs", root + "/dev", "tmpfs", MS_NOSUID, "size=64k,mode=0755")
    for device in ("null", "zero", "full", "random", "urandom"):
        _bind("/dev/" + device, root, "/dev/" + device, writable=True)
    for name, target in (
        ("fd", "/proc/self/fd"),
        ("stdin", "/proc/self/fd/0"),
        ("stdout", "/proc/self/fd/1"),
        ("stderr", "/proc/self/fd/2"),
    ):
        os.symlink(target, f"{root}/dev/{name}")
    for target, size in config["tmpfs"].items():  # first: binds may lie below them
        _tmpfs(root, target, int(size))
    for source, target in config["binds"]:
        if os.path.lexists(source):
            _bind(source, root, target)
    os.makedirs(root + "/proc", mode=0o555)
    _mount("proc", root + "/proc", "proc", MS_NOSUID | MS_NODEV | MS_NOEXEC)
    _pivot(root)
    _mount(None, "/", None, MS_REMOUNT | MS_BIND | MS_RDONLY | MS_NOSUID | MS_NODEV)


def _map_user(uid: int, gid: int) -> None:
    _write("/proc/self/setgroups", "deny")
    _write("/proc/self/uid_map", f"{uid} {uid} 1")
    _write("/proc/self/gid_map", f"{gid} {gid} 1")


def _limit(rlimits: dict) -> None:
    for name, value in rlimits.items():
        key = getattr(resource, name)
        resource.setrlimit(key, (int(value), int(value)))


def _run(config: dict, command: list[str]) -> int:
    _die_with_parent()
    privileged = os.geteuid() == 0
    for procs in config.get("cgroups", []):
        _write(procs, str(os.getpid()))
    namespaces = CLONE_NEWNS | CLONE_NEWPID | CLONE_NEWNET | CLONE_NEWIPC | CLONE_NEWUTS
    if privileged:
        _check(_libc.unshare(namespaces), "unshare")
    else:
        uid, gid = os.getuid(), os.getgid()
        _check(_libc.unshare(CLONE_NEWUSER | namespaces), "unshare")
        _map_user(uid, gid)
    read_fd, write_fd = os.pipe()  # the child reports a failed set-up here
    pid = os.fork()
    if pid:
        os.close(write_fd)
        for fd in config.get("pass_fds", []):
            os.close(fd)
        failure = os.read(read_fd, 4096)
        _, status = os.waitpid(pid, 0)
        if failure:
            sys.stderr.write(failure.decode(errors="replace"))
            return 125
        if os.WIFSIGNALED(status):
            return 128 + os.WTERMSIG(status)
        return os.WEXITSTATUS(status)
    try:  # PID 1 of the new namespace
        os.close(read_fd)
        _die_with_parent()
        _build_root(config)
        if privileged:
            os.setgroups([])
            os.setresgid(NOBODY, NOBODY, NOBODY)
            os.setresuid(NOBODY, NOBODY, NOBODY)
            # a change of user makes /proc/self root's; take it back to write the maps
            _check(_libc.prctl(PR_SET_DUMPABLE, 1, 0, 0, 0), "dumpable")
            _check(_libc.unshare(CLONE_NEWUSER), "unshare the user namespace")
            _map_user(NOBODY, NOBODY)
        _limit(config.get("rlimits", {}))
        _check(_libc.prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0), "no_new_privs")
        os.chdir(config.get("cwd", "/tmp"))
        os.set_inheritable(write_fd, False)
        os.set_blocking(write_fd, True)
        os.execve(command[0], command, config.get("env", {}))
    except BaseException as exc:  # report, then leave without running anything
        os.write(write_fd, f"urkin-jail: {exc}\n".encode())
        os._exit(125)
    return 125  # not reached


def main(argv: list[str]) -> int:
    if len(argv) < 3:
        sys.stderr.write("usage: jail.py CONFIG_JSON COMMAND...\n")
        return 125
    try:
        return _run(json.loads(argv[1]), argv[2:])
    except (JailError, OSError) as exc:
        sys.stderr.write(f"urkin-jail: {exc}\n")
        return 125


if __name__ == "__main__":
    sys.exit(main(sys.argv))
