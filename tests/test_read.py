"""Reading submitted notebooks: odd files, IPython syntax, which definition is graded, and which
statements run."""

from __future__ import annotations

import json
import os

import pytest

from tests.notebooks import notebook, write
from urkin.course.grading.read import read_notebook, read_untrusted


def _plan_text(nb, roots, graded=None):
    return [
        (site.cell, site.kind, sorted(site.binds or {site.mutates}))
        for site in nb.plan(set(roots), graded or {})
    ]


@pytest.mark.parametrize(
    ("make", "words"),
    [
        (lambda p: os.mkfifo(p), "not a regular file"),
        (lambda p: p.mkdir(), "directory"),
        (lambda p: p.symlink_to(write({"cells": []}, p.parent / "real")), "symbolic link"),
        (lambda p: p.write_bytes(b"\xff\xfe not utf-8"), "not a valid notebook"),
        (lambda p: p.write_text('{"cells": [ this is not json'), "not a valid notebook"),
        (lambda p: p.write_text("[" * 100_000 + "]" * 100_000), "not a valid notebook"),
        (lambda p: p.write_text('{"cells": 3}'), "not a valid notebook"),
        (lambda p: p.write_text("{}"), "not a valid notebook"),
    ],
    ids=["fifo", "directory", "symlink", "binary", "bad-json", "deep-json", "cells", "no-cells"],
)
def test_a_file_that_is_no_notebook_is_read_without_raising(tmp_path, make, words):
    path = tmp_path / "alice_02.ipynb"
    make(path)
    nb = read_notebook(path)
    assert nb.error and words in nb.error
    assert nb.lesson == "02"


def test_a_huge_file_is_refused_before_it_is_read(tmp_path):
    path = tmp_path / "big_02.ipynb"
    with open(path, "wb") as handle:
        handle.truncate(30 * 2**20)
    with pytest.raises(ValueError, match="larger than"):
        read_untrusted(path)


def test_malformed_cells_are_skipped_with_a_note(tmp_path):
    data = notebook("def f(x):\n    return x\n")
    data["cells"] += [{"cell_type": "code", "source": 3}, "not a cell", {"cell_type": "code"}]
    nb = read_notebook(write(data, tmp_path / "a_02.ipynb"))
    assert nb.error is None and "f" in {n for s in nb.sites for n in s.binds}
    assert any("malformed" in note for note in nb.notes)


def test_ipython_syntax_is_tolerated(tmp_path):
    cells = (
        "%matplotlib inline\nimport numpy as np\nnp.linalg.solve?\n!pip install nothing",
        "def f(x):\n    %timeit x\n    return np.sin(x)\n",
        "%%time\ndef g(x):\n    return 2 * x\n",
        "%%bash\necho not python\n",
        "files = !ls\n??np.cos\n",
    )
    nb = read_notebook(write(notebook(*cells), tmp_path / "a_02.ipynb"))
    bound = {n for s in nb.sites for n in s.binds}
    assert {"np", "f", "g", "files"} <= bound
    assert any("%%bash" in note for note in nb.notes)
    assert not any("syntax error" in note for note in nb.notes)


def test_a_syntax_error_loses_only_its_cell(tmp_path):
    nb = read_notebook(
        write(
            notebook("def f(x)\n    return x", "def g(x):\n    return x"), tmp_path / "a_02.ipynb"
        )
    )
    assert {n for s in nb.sites for n in s.binds} == {"g"}
    assert any("code cell 1 has a syntax error on line 1" in n for n in nb.notes)


def test_the_lesson_comes_from_metadata_then_the_file_name(tmp_path):
    path = write(notebook("x = 1", lesson="05"), tmp_path / "bob_hw.ipynb")
    assert read_notebook(path).lesson == "05"
    path = write(notebook("x = 1", lesson="05"), tmp_path / "bob_hw10.ipynb")
    assert read_notebook(path).lesson == "05"  # a number in a name the student chose
    assert "metadata says lesson 05 and its file name lesson 10" in read_notebook(path).notes[0]
    path = write(notebook("x = 1", lesson="05"), tmp_path / "02_dh_forward_kinematics.ipynb")
    assert read_notebook(path).lesson is None  # another lesson's course name: --lesson decides
    assert read_notebook(path, lesson="2").lesson == "02"
    path = write(notebook("x = 1", lesson=None), tmp_path / "bob_02.ipynb")
    assert read_notebook(path).lesson == "02"
    assert read_notebook(path, lesson="3").lesson == "03"
    assert (
        read_notebook(write(notebook("x = 1", lesson=None), tmp_path / "hw.ipynb")).lesson is None
    )


def test_only_what_the_functions_need_is_executed(tmp_path):
    cells = (
        "import numpy as np\nimport matplotlib.pyplot as plt\nimport urkin\nimport urkin.symbolic",
        "SCALE = 2.0\nunused = np.ones(10**9)\nDH = np.zeros(3)\nDH[1] = 5.0\nDH.fill(1.0)\n"
        "plt.plot([1])\nprint('hello')",
        "def helper(x):\n    return SCALE * x\n",
        "def f(x):\n    return helper(x) + DH.sum() + np.pi\n",
        "f(3)\nwhile True:\n    pass\n",
    )
    nb = read_notebook(write(notebook(*cells), tmp_path / "a_02.ipynb"))
    plan = _plan_text(nb, {"f"})
    assert (1, "import", ["np"]) in plan
    assert not any("plt" in names or "urkin" in names for _, _, names in plan)
    assert (2, "assign", ["SCALE"]) in plan and (2, "assign", ["DH"]) in plan
    assert (2, "mutation", ["DH"]) in plan  # DH[1] = 5.0 and DH.fill(1.0)
    assert not any("unused" in names for _, _, names in plan)
    assert sum(kind == "other" for _, kind, _ in plan) == 0


def test_a_submodule_import_runs_only_when_used(tmp_path):
    cells = (
        "import urkin\nimport urkin.symbolic\nimport urkin.plot",
        "def f(q):\n    return urkin.symbolic.Q[0]\n",
        "def g(q):\n    return urkin.robot('ur5')\n",
    )
    nb = read_notebook(write(notebook(*cells), tmp_path / "a_02.ipynb"))

    def imports(roots):
        return [s.module or "urkin" for s in nb.plan(roots, {}) if s.kind == "import"]

    assert imports({"f"}) == ["urkin", "urkin.symbolic"]
    assert imports({"g"}) == ["urkin"]


def test_top_level_blocks_that_define_names_run(tmp_path):
    cells = (
        "try:\n    import scipy_missing as sp\nexcept ImportError:\n    sp = None\n",
        "if sp is None:\n    def solve(A, b):\n        return A\nelse:\n    solve = sp.solve\n",
        "with open('x') as fh:\n    pass\nfor k in range(3):\n    LAST = k\n",
        "def f(A, b):\n    return solve(A, b), LAST\n",
    )
    nb = read_notebook(write(notebook(*cells), tmp_path / "a_02.ipynb"))
    kinds = [(cell, kind) for cell, kind, _ in _plan_text(nb, {"f"})]
    assert kinds == [(1, "block"), (2, "block"), (3, "block"), (4, "def")]


def test_the_graded_definition_is_the_exercise_cells_not_the_last(tmp_path):
    cells = (
        "import numpy as np",
        "def dh_transform(theta, d, a, alpha):\n    return 'mine'\n",
        'check("2.1", dh_transform)',
        "from urkin.kinematics import dh_transform  # compare with the reference",
        "def dh_transform(theta, d, a, alpha):\n    return 'later'\n",
    )
    nb = read_notebook(write(notebook(*cells), tmp_path / "a_02.ipynb"))
    site = nb.graded_site("dh_transform", "2.1")
    assert site.cell == 2
    assert [s.cell for s in nb.redefinitions("dh_transform", site)] == [4, 5]
    plan = nb.plan({"dh_transform"}, {"dh_transform": site})
    assert [s.cell for s in plan] == [2]


def test_the_course_cell_id_wins_over_the_check_cell(tmp_path):
    data = notebook("def f(x):\n    return 1\n", "def f(x):\n    return 2\n", 'check("2.1", f)')
    data["cells"][1]["id"] = "exercise-cell"
    nb = read_notebook(write(data, tmp_path / "a_02.ipynb"))
    assert nb.graded_site("f", "2.1", "exercise-cell").cell == 2
    assert nb.graded_site("f", "2.1").cell == 2  # the last one before the check cell
    data["cells"].pop(2)
    nb = read_notebook(write(data, tmp_path / "a_02.ipynb"))
    assert nb.graded_site("f", "2.1").cell == 1  # no check cell: the first definition


def test_reading_is_deterministic_and_json_safe(tmp_path):
    data = notebook("def f(x):\n    return x\n")
    path = write(data, tmp_path / "a_02.ipynb")
    first, second = read_notebook(path), read_notebook(path)
    assert [(s.cell, s.kind) for s in first.sites] == [(s.cell, s.kind) for s in second.sites]
    json.dumps(first.cells)


def test_cells_read_before_are_remembered_but_their_statements_are_parsed_afresh(tmp_path):
    """The grader remembers what it read from each cell text (the submissions of a lesson
    share most cells): a notebook read twice gives the same sites, each with a node of its own
    (no submission shares an AST with another); texts too long to remember are read each
    time, and the memo keeps at most its size."""
    from urkin.course.grading import read

    source = "import numpy as np\n\ndef f(x):\n    return np.sin(x) + g(x)\n\nT = f(1.0)\n"
    write(notebook(source, "%timeit f(2.0)"), tmp_path / "a_02.ipynb")
    first, again = (read_notebook(tmp_path / "a_02.ipynb") for _ in range(2))
    assert [(s.kind, s.binds, s.uses, s.cell, s.index) for s in first.sites] == [
        (s.kind, s.binds, s.uses, s.cell, s.index) for s in again.sites
    ]
    assert first.sites[1].uses == {"np", "g"} and first.sites[2].kind == "assign"
    assert all(a.node is not b.node for a, b in zip(first.sites, again.sites))
    again.sites[1].uses.add("changed")  # a site's sets are its own
    assert read_notebook(tmp_path / "a_02.ipynb").sites[1].uses == {"np", "g"}
    long = "x = 1\n" * (read._MEMO_CHARACTERS // 6 + 1)
    write(notebook(long), tmp_path / "b_02.ipynb")
    assert len(read_notebook(tmp_path / "b_02.ipynb").sites) == long.count("\n")
    assert read._STATEMENTS.get(long) is None and read._SOURCES.get(long) is None
    for k in range(read._MEMO_SIZE + 5):
        write(notebook(f"y{k} = {k}"), tmp_path / "c_02.ipynb")
        read_notebook(tmp_path / "c_02.ipynb")
    assert len(read._STATEMENTS.table) <= read._MEMO_SIZE >= len(read._SOURCES.table)


def test_a_table_filled_inside_a_top_level_loop_is_executed(tmp_path):
    cells = (
        "FACTORS = {}\nfor unit, f in [('deg', 0.0174), ('rad', 1.0)]:\n    FACTORS[unit] = f\n",
        "for q in range(3):\n    print(q)\n",  # a demonstration: skipped
        "def deg_to_rad(a):\n    return a * FACTORS['deg']\n",
    )
    nb = read_notebook(write(notebook(*cells), tmp_path / "a_00.ipynb"))
    assert [(s.cell, s.kind) for s in nb.plan({"deg_to_rad"}, {})] == [
        (1, "assign"),
        (1, "block"),
        (3, "def"),
    ]


def test_names_keep_the_binding_their_check_cell_saw(tmp_path):
    # a later demo rebinds a global, and a helper of the same name is written again for a later
    # exercise: the first exercise is graded with what its check cell saw (Restart & Run All)
    cells = (
        "import numpy as np\nT_BL = np.diag([-1.0, -1.0, 1.0, 1.0])\n",
        "def _frames(robot, q):\n    return 'robot'\n",
        "def base_link_pose(T):\n    return T_BL @ T, _frames(None, None)\n",
        'check("0.2", base_link_pose)',
        "T_BL = np.eye(4)  # a demonstration\n",
        "def _frames(S, q):\n    return 'screws'\n",
        "def later(S, q):\n    return _frames(S, q)\n",
        'check("0.3", later)',
    )
    nb = read_notebook(write(notebook(*cells), tmp_path / "a_00.ipynb"))
    graded = {"base_link_pose": nb.graded_site("base_link_pose", "0.2")}
    cut = nb.check_call("0.2", graded["base_link_pose"])
    assert cut == (4, 1)
    notes: list[str] = []
    plan = nb.plan({"base_link_pose"}, graded, cut, notes)
    assert [s.cell for s in plan] == [1, 1, 2, 3]
    assert any("code cell 5, line 1 binds `T_BL` again" in n for n in notes)
    assert any("code cell 6, line 1 binds `_frames` again" in n for n in notes)
    graded["later"] = nb.graded_site("later", "0.3")
    plan = nb.plan({"later"}, graded, nb.check_call("0.3", graded["later"]))
    assert [s.cell for s in plan] == [2, 6, 7]  # the later exercise: the later helper wins
    assert [s.cell for s in nb.plan({"base_link_pose"}, graded)] == [1, 1, 2, 3, 5, 6]  # no cut


def test_a_global_set_by_a_skipped_top_level_call_is_explained(tmp_path):
    cells = (
        "_SIGN = None\ndef _init():\n    global _SIGN\n    _SIGN = -1.0\n",
        "_init()\n",
        "def screw_axis(w, q):\n    return _SIGN * w\n",
    )
    nb = read_notebook(write(notebook(*cells), tmp_path / "a_03.ipynb"))
    notes: list[str] = []
    nb.plan({"screw_axis"}, {}, None, notes)
    assert any(
        "code cell 2, line 1 calls `_init()`, which sets the global `_SIGN`" in n for n in notes
    )


def test_a_stub_left_in_the_exercise_cell_gives_way_to_the_function_written_below(tmp_path):
    stub = (
        'def rot_z(theta):\n    """Rotation about z."""\n'
        '    raise NotImplementedError("Exercise 1.1: write rot_z")\n'
    )
    data = notebook(stub, "def rot_z(theta):\n    return 'mine'\n", 'check("1.1", rot_z)')
    data["cells"][0]["id"] = "exercise-cell"
    nb = read_notebook(write(data, tmp_path / "a_01.ipynb"))
    site = nb.graded_site("rot_z", "1.1", "exercise-cell")
    assert site.cell == 2
    assert nb.stub_left("rot_z", "exercise-cell", site).cell == 1
    data["cells"].pop(1)  # only the stub: it is what is graded (not attempted)
    nb = read_notebook(write(data, tmp_path / "a_01.ipynb"))
    site = nb.graded_site("rot_z", "1.1", "exercise-cell")
    assert site.cell == 1 and nb.stub_left("rot_z", "exercise-cell", site) is None
