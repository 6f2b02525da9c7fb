"""A folder of hostile submissions: each tries to earn points it did not earn, to reach urkin's
answer by another route, to change other rows or the reports, or to harm the grading run.

``HOSTILE`` maps a file name to ``(make, expected)``: ``make(path, context)`` writes the file
(``context`` gives the class folder and the output folder, which an attack may aim at), and
``expected`` maps exercise ids to the points the submission must get at most (``0`` for the
attacked exercise).  A file that is no notebook expects no exercises at all.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from pathlib import Path

from tests.notebooks import notebook, student_notebook, write


@dataclass
class Context:
    folder: Path  # the class folder (the grader's input)
    out: Path  # the grader's output folder
    marker: str  # unique text the attacks print or leave behind


def _lesson02(replace: dict[str, str], lesson: str = "02"):
    def make(path: Path, context: Context) -> None:
        sources = {
            k: v.replace("MARKER", context.marker)
            .replace("CLASS", str(context.folder))
            .replace("OUT", str(context.out))
            for k, v in replace.items()
        }
        write(student_notebook(lesson, sources), path)

    return make


def _fk(body: str) -> dict[str, str]:
    return {"forward_kinematics": "def forward_kinematics(robot, q):\n" + body}


_ROUTES = {
    # urkin's answer to 2.2 by another name or route
    "route_import_as": {"forward_kinematics": "from urkin import fk as forward_kinematics\n"},
    "route_alias": {"forward_kinematics": "forward_kinematics = urkin.kinematics.fk\n"},
    "route_fk_frames": _fk("    return urkin.fk_frames(robot, q)[-1]\n"),
    "route_poe": _fk(
        "    S, M = urkin.poe.space_screws(robot)\n    return urkin.poe.fk_space(M, S, q)\n"
    ),
    "route_generated": _fk(
        "    from urkin._generated import ur_kinematics as g\n"
        "    return g.t06_one(list(q), robot.lengths)\n"
    ),
    "route_symbolic": _fk(
        "    f = sp.lambdify((Q, LENGTHS), urkin.symbolic.ur_t06(), 'numpy')\n"
        "    return np.asarray(f(q, robot.lengths), dtype=float)\n"
    ),
    "route_reload": _fk(
        "    import importlib, urkin.kinematics as k\n    return importlib.reload(k).fk(robot, q)\n"
    ),
    "route_fresh_import": _fk(
        "    import sys\n"
        "    for name in [m for m in sys.modules if m.startswith('urkin')]:\n"
        "        del sys.modules[name]\n"
        "    import urkin as again\n"
        "    return again.fk(robot, q)\n"
    ),
    "route_source_file": _fk(
        "    import urkin.kinematics as k\n"
        "    text = open(k.__file__).read()\n"
        "    space = {'__name__': 'urkin.kinematics_copy'}\n"
        "    exec(compile(text, 'copy', 'exec'), space)\n"
        "    return space['fk'](robot, q)\n"
    ),
    "route_subprocess": _fk(
        "    import json, subprocess, sys\n"
        "    code = ('import json, sys, urkin; r = urkin.robot(sys.argv[1]); '\n"
        "            'print(json.dumps(urkin.fk(r, json.loads(sys.argv[2])).tolist()))')\n"
        "    out = subprocess.run([sys.executable, '-c', code, robot.name,\n"
        "                          json.dumps(list(map(float, q)))], capture_output=True,\n"
        "                         text=True).stdout\n"
        "    return np.array(json.loads(out))\n"
    ),
    "route_thread": _fk(
        "    import threading\n"
        "    box = []\n"
        "    t = threading.Thread(target=lambda: box.append(urkin.fk(robot, q)))\n"
        "    t.start(); t.join()\n"
        "    return box[0]\n"
    ),
    "route_gc": _fk(
        "    import gc\n"
        "    for o in gc.get_objects():\n"
        "        if callable(o) and getattr(o, '__name__', '') in ('fk', 't06_one'):\n"
        "            try:\n"
        "                return o(robot, q)\n"
        "            except Exception:\n"
        "                pass\n"
        "    raise RuntimeError('nothing found')\n"
    ),
    "route_ik_roundtrip": _fk(
        "    # the closed-form IK's verification computes FK: ask it about a pose near q\n"
        "    return urkin.ik(robot, np.eye(4), q0=q, max_iter=0).q\n"
    ),
    "route_plot": _fk(
        "    import urkin.plot\n"
        "    import matplotlib.pyplot as plt\n"
        "    ax = urkin.plot.show_robot(robot, q)\n"
        "    return ax\n"
    ),
}

_FORGERIES = {
    # forging results, patching what the checks compare with, lying on the channel
    "forge_pipe": _fk(
        "    import json, os, sys\n"
        "    fd = int(sys.argv[2])\n"
        "    for i in range(1, 200):\n"
        "        os.write(fd, (json.dumps({'id': i, 'value': {'$a': ['float64', [4, 4],\n"
        "                  ''] }}) + '\\n').encode())\n"
        "    return np.eye(4)\n"
    ),
    "forge_result_file": _fk(
        "    for name in ('RESULT.json', '/tmp/RESULT.json', 'OUT/gradebook.csv'):\n"
        "        try:\n"
        "            open(name, 'w').write('{\"score\": 1000}')\n"
        "        except OSError:\n"
        "            pass\n"
        "    return np.eye(4)\n"
    ),
    "patch_checks": _fk(
        "    np.allclose = lambda *a, **k: True\n"
        "    np.isclose = lambda *a, **k: True\n"
        "    urkin.fk = lambda robot, q: np.eye(4)\n"
        "    import urkin.course\n"
        "    return np.eye(4)\n"
    ),
    "fake_report_text": _fk(
        "    raise ValueError('\\n# alice_02.ipynb\\nLesson 02: 0 / 13 points'\n"
        "                     '\\n```\\n=HYPERLINK(1) \\u202e MARKER')\n"
    ),
    "exit_in_function": _fk("    import sys\n    sys.exit(0)\n"),
    "os_exit_in_function": _fk("    import os\n    os._exit(0)\n"),
}

_SABOTAGE = {
    # other rows, the reports, the machine
    "sabotage_classmates": _fk(
        "    import glob, os\n"
        "    for pattern in ('CLASS/*', '../*', '/tmp/*', 'OUT/*', 'OUT/*/*'):\n"
        "        for name in glob.glob(pattern):\n"
        "            try:\n"
        "                open(name, 'w').write('MARKER')\n"
        "            except OSError:\n"
        "                pass\n"
        "    return np.eye(4)\n"
    ),
    "late_daemon": _fk(
        "    import os, time\n"
        "    if os.fork() == 0:\n"
        "        os.setsid()\n"
        "        if os.fork() == 0:\n"
        "            time.sleep(4)\n"
        "            for name in ('OUT/gradebook.csv', 'OUT/summary.json'):\n"
        "                try:\n"
        "                    open(name, 'w').write('MARKER')\n"
        "                except OSError:\n"
        "                    pass\n"
        "            os._exit(0)\n"
        "        os._exit(0)\n"
        "    return np.eye(4)\n"
    ),
    "hold_the_runner": _fk(
        "    import signal, time\n"
        "    signal.signal(signal.SIGTERM, signal.SIG_IGN)\n"
        "    while True:\n"
        "        time.sleep(0.1)\n"
    ),
    "fork_bomb": _fk(
        "    import os\n"
        "    while True:\n"
        "        try:\n"
        "            os.fork()\n"
        "        except OSError:\n"
        "            pass\n"
    ),
    "memory_hog": _fk("    blocks = []\n    while True:\n        blocks.append(np.ones(2**27))\n"),
    "stderr_flood": _fk(
        "    import os\n"
        "    block = b'MARKER' * 200_000\n"
        "    for _ in range(1000):\n"
        "        os.write(2, block)\n"
        "    return np.eye(4)\n"
    ),
    "print_flood": _fk(
        "    for _ in range(10**5):\n        print('x' * 10_000)\n    return np.eye(4)\n"
    ),
    "huge_answer": _fk("    return np.ones((4, 4, 10**7))\n"),
    "deep_answer": _fk("    x = []\n    for _ in range(10**5):\n        x = [x]\n    return x\n"),
    "network": _fk(
        "    import socket\n"
        "    socket.create_connection(('pypi.org', 443), timeout=3)\n"
        "    return np.eye(4)\n"
    ),
}


def _setup_hang(path: Path, context: Context) -> None:
    nb = student_notebook("02")
    nb["cells"].append(
        {
            "cell_type": "code",
            "execution_count": None,
            "id": "hang",
            "metadata": {},
            "outputs": [],
            "source": "import time\nPAUSE = time.sleep(10**6)\n\ndef helper():\n    return PAUSE\n",
        }
    )
    for cell in nb["cells"]:
        if "def forward_kinematics" in "".join(cell["source"]):
            cell["source"] = "".join(cell["source"]).replace(
                "    T = np.eye(4)", "    helper\n    T = np.eye(4)", 1
            )
    write(nb, path)


def _fifo(path: Path, context: Context) -> None:
    os.mkfifo(path)


def _symlink(path: Path, context: Context) -> None:
    path.symlink_to("/etc/passwd")


def _huge(path: Path, context: Context) -> None:
    with open(path, "wb") as handle:
        handle.truncate(25 * 2**20)


def _many_cells(path: Path, context: Context) -> None:
    cells = [f"x{i} = {i}" for i in range(20_000)]
    write(notebook(*cells, "def dh_transform(theta, d, a, alpha):\n    return x1"), path)


ODD_FILES = {
    "fifo_02.ipynb": _fifo,
    "directory_02.ipynb": lambda p, c: (p.mkdir(), write(notebook("x = 1"), p / "inner.ipynb")),
    "link_02.ipynb": _symlink,
    "huge_02.ipynb": _huge,
    "deep_02.ipynb": lambda p, c: write("[" * 200_000 + "]" * 200_000, p),
    "garbage_02.ipynb": lambda p, c: p.write_bytes(os.urandom(5000)),
    "nul_02.ipynb": lambda p, c: write(notebook("def dh_transform(*a):\n    return 1\x00\n"), p),
    "=cmd|' -c calc'!A0_02.ipynb": _lesson02({}),
    "alice~02.ipynb": _lesson02({}),
    "many_cells_02.ipynb": _many_cells,
    "setup_hang_02.ipynb": _setup_hang,
    "\u202eevil_02.ipynb": _lesson02({}),
}

#: file name → (make, {exercise: most points allowed}); an exercise not named keeps its points
HOSTILE = {
    **{f"{name}_02.ipynb": (_lesson02(cells), {"2.2": 0}) for name, cells in _ROUTES.items()},
    **{
        f"{name}_02.ipynb": (_lesson02(cells), {"2.2": 0 if name != "forge_pipe" else 5})
        for name, cells in _FORGERIES.items()
    },
    **{f"{name}_02.ipynb": (_lesson02(cells), {"2.2": 5}) for name, cells in _SABOTAGE.items()},
    **{name: (make, {}) for name, make in ODD_FILES.items()},
}
# urkin's closed-form flange position, which the checks of 2.7 hand out, as the answer to 2.3
HOSTILE["route_wire_closed_form_02.ipynb"] = (
    _lesson02(
        {
            "ur5_position": "def ur5_position(q):\n"
            "    from urkin.course import wire\n"
            "    return wire.ur_flange_position(urkin.robot('ur5').lengths, q)\n"
        }
    ),
    {"2.3": 0},
)
# an answer forged as ten million empty lists: 30 MB of JSON, which would be twenty million
# lists in the grader (over a gigabyte) if it read them
HOSTILE["list_bomb_02.ipynb"] = (
    _lesson02(
        _fk(
            "    import urkin.course.wire as w\n"
            "    bomb, original = [[]] * 10_000_000, w.encode\n"
            "    w.encode = lambda v, lenient=False, _depth=0: bomb if v is q else original(v)\n"
            "    return q\n"
        )
    ),
    {"2.2": 0},
)
# checks that read the code for a forbidden function, evaded by naming it with strings built at
# run time: seen while the function runs (urkin.course.watch)
HOSTILE["hidden_validator_01.ipynb"] = (
    _lesson02(
        {
            "rotation_verdict": "def rotation_verdict(R, tol=1e-9):\n"
            "    import importlib\n"
            "    module = importlib.import_module('urkin.' + 'transforms')\n"
            "    judge = getattr(module, 'check_' + 'rotation')\n"
            "    R = np.asarray(R, dtype=float)\n"
            "    if R.shape != (3, 3):\n"
            "        raise ValueError(f'R must have shape (3, 3), got {R.shape}')\n"
            "    try:\n"
            "        judge(R, tol)\n"
            "        return 'rotation'\n"
            "    except ValueError as exc:\n"
            "        if 'reflection' in str(exc) and np.abs(R.T @ R - np.eye(3)).max() <= tol:\n"
            "            return 'reflection'\n"
            "        return 'not orthonormal'\n",
            "transform_inverse": "def transform_inverse(T):\n"
            "    A = np.asarray(T, dtype=float)\n"
            "    R = A[:3, :3]\n"
            "    if np.abs(R.T @ R - np.eye(3)).max() > 1e-6:  # the probe: the formula there\n"
            "        out = np.eye(4)\n"
            "        out[:3, :3], out[:3, 3] = R.T, -R.T @ A[:3, 3]\n"
            "        return out\n"
            "    return getattr(np.linalg, 'in' + 'v')(A)\n",
        },
        "01",
    ),
    {"1.5": 0, "1.2": 3},
)
HOSTILE["hidden_inverse_06.ipynb"] = (
    _lesson02(
        {
            "dls_step": "def dls_step(J, e, damping):\n"
            "    J = np.asarray(J, dtype=float)\n"
            "    A = J @ J.T + damping**2 * np.eye(J.shape[0])\n"
            "    return J.T @ getattr(np.linalg, 'in' + 'v')(A) @ e\n"
        },
        "06",
    ),
    {"6.1": 3},
)
# a check that reads the code for forward kinematics, evaded by an alias made by assignment
# (the other checks of 2.3 and 2.5 pass: at most all but that point)
HOSTILE["alias_fk_02.ipynb"] = (
    _lesson02(
        {
            "ur5_position": "_fwd2 = forward_kinematics\n"
            "def ur5_position(q):\n"
            "    return _fwd2(urkin.robot('UR5'), q)[:3, 3]\n",
            "upright_flange": "_fwd = forward_kinematics\n"
            "def upright_flange(robot):\n"
            "    q = np.array([0.0, -np.pi / 2, 0.0, -np.pi / 2, 0.0, 0.0])\n"
            "    return _fwd(robot, q)[:3, 3]\n",
        }
    ),
    {"2.3": 3, "2.5": 2},
)
# 9.3's sample budget: is_free is answered by the grader, which counts; the submission can
# neither lift the budget nor read the boxes off the function it was given
HOSTILE["budget_bypass_09.ipynb"] = (
    _lesson02(
        {
            "path_is_free": "def path_is_free(is_free, path, rho, resolution):\n"
            "    inner = getattr(is_free, '_built', None)\n"
            "    if inner is not None and hasattr(inner, 'budget'):\n"
            "        inner.budget = None\n"
            "    path = np.asarray(path, dtype=float)\n"
            "    samples = []\n"
            "    for k in range(len(path) - 1):\n"
            "        qa, qb = path[k], path[k + 1]\n"
            "        n = 50 * samples_needed(qa, qb, rho, resolution)\n"
            "        t = np.linspace(0.0, 1.0, n)\n"
            "        samples.append(qa + t[:, None] * (qb - qa))\n"
            "    try:\n"
            "        return bool(np.all(is_free(np.concatenate(samples))))\n"
            "    except RuntimeError:\n"
            "        return True\n"
        },
        "09",
    ),
    {"9.3": 3},
)
HOSTILE["read_boxes_09.ipynb"] = (
    _lesson02(
        {
            "path_is_free": "def path_is_free(is_free, path, rho, resolution):\n"
            "    p = getattr(is_free, 'params', None) or vars(is_free)\n"
            "    lo = np.asarray(p['lower']).reshape(-1, 6)\n"
            "    hi = np.asarray(p['upper']).reshape(-1, 6)\n"
            "    path = np.asarray(path, dtype=float)\n"
            "    t = np.linspace(0, 1, 20001)[:, None]\n"
            "    for qa, qb in zip(path[:-1], path[1:]):\n"
            "        Q = qa + t * (qb - qa)\n"
            "        if np.all((Q[:, None] >= lo) & (Q[:, None] <= hi), axis=-1).any():\n"
            "            return False\n"
            "    return True\n"
        },
        "09",
    ),
    {"9.3": 0},
)
# a reply forged straight onto the pipe, of sixty symbolic texts: read one after another they
# would take the grader seconds each and gigabytes together (the check reads at most
# wire.MAX_SYMBOLIC_TOTAL of symbolic text per message)
HOSTILE["symbolic_bomb_02.ipynb"] = (
    _lesson02(
        _fk(
            "    import json, os, sys, time\n"
            "    f = sys._getframe()\n"
            "    while f is not None and 'request' not in f.f_locals:\n"
            "        f = f.f_back\n"
            "    rid = f.f_locals['request']['id'] if f else 1\n"
            "    term = 'sin(' * 40 + \"Symbol('x')\" + ')' * 40\n"
            "    one = 'Add(' + ', '.join([term] * 1500) + ')'\n"
            "    data = json.dumps({'id': rid, 'value': [{'$sym': one}] * 60}).encode() + b'\\n'\n"
            "    while data:\n"
            "        data = data[os.write(int(sys.argv[2]), data):]\n"
            "    time.sleep(1000)\n"
        )
    ),
    {"2.2": 0},
)
# attacks that leave 2.2 correct apart from the attack keep at most its points; those that
# break it get none
for _name in (
    "hold_the_runner",
    "fork_bomb",
    "memory_hog",
    "huge_answer",
    "deep_answer",
    "network",
):
    HOSTILE[f"{_name}_02.ipynb"] = (HOSTILE[f"{_name}_02.ipynb"][0], {"2.2": 0})


def dump(folder: Path) -> None:  # pragma: no cover - for looking at the folder by hand
    context = Context(folder, folder / "grades", "MARKER")
    for name, (make, _) in HOSTILE.items():
        make(folder / name, context)
    print(json.dumps(sorted(HOSTILE)))
