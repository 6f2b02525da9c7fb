"""What counts as urkin's own answer to each exercise, and the views of urkin that hide it."""

from __future__ import annotations

import ast
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import urkin
from urkin.course.answers import PACKAGE, answer_for, library_modules
from urkin.course.hidden import ForbiddenCallError, Hidden
from urkin.course.lessons import exercise, lessons

EXERCISES = [ex for each in lessons().values() for ex in each.exercises]
IDS = [ex.id for ex in EXERCISES]


def test_the_library_never_imports_the_course_wing():
    offenders = []
    for path in sorted(PACKAGE.rglob("*.py")):
        relative = path.relative_to(PACKAGE)
        if relative.parts[0] == "course" or relative.name in ("cli.py", "__main__.py"):
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = []
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                names = [node.module or ""] + [f"{node.module}.{a.name}" for a in node.names]
            if any(n == "urkin.course" or n.startswith("urkin.course.") for n in names):
                offenders.append(str(relative))
    assert offenders == []


def test_import_urkin_does_not_load_the_course_wing():
    code = "import sys, urkin; print(any(m.startswith('urkin.course') for m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


@pytest.mark.parametrize("ex", EXERCISES, ids=IDS)
def test_an_answer_names_library_code_and_never_the_robots(ex):
    hidden = answer_for(ex).names()
    assert bool(hidden) == bool(ex.answer), f"{ex.id} declares {ex.answer} and hides {hidden}"
    for always in ("urkin.robots.Robot", "urkin.robots.robot", "urkin.robots.ROBOTS"):
        assert always not in hidden
    assert all(name.split(".")[0] == "urkin" for name in hidden)
    assert not any(name.startswith("urkin.course.grading") for name in hidden)


@pytest.mark.parametrize(
    ("exercise_id", "routes"),
    [
        (
            "2.2",
            [
                "urkin.kinematics.fk",
                "urkin.kinematics.fk_frames",
                "urkin.poe.fk_space",
                "urkin.symbolic.ur_t06",
                "urkin._generated.ur_kinematics.t06_one",
                "urkin.plot.draw_robot",
                "urkin.numerical_ik.ik",
                "urkin.course.lab.fk_lab",
            ],
        ),
        ("2.3", ["urkin.kinematics.dh_transform", "urkin.symbolic.ur_frames"]),
        ("1.3", ["urkin.transforms.rotation_to_rpy", "urkin.plot.pose_text"]),
        ("3.2", ["urkin.transforms.se3_exp", "urkin.poe.fk_space"]),
        ("4.1", ["urkin.kinematics.jacobian", "urkin._generated.ur_kinematics.jacobian_one"]),
        (
            "5.3",
            ["urkin.numerical_ik.ik", "urkin.analytic_ik.ik_analytic", "urkin.course.lab.ik_lab"],
        ),
        ("5.2", ["urkin.transforms.so3_log", "urkin.numerical_ik.orientation_error"]),
        ("7.3", ["urkin.course.lab.ik_lab", "urkin.analytic_ik.ik_closest"]),
    ],
)
def test_other_routes_to_the_answer_are_hidden_too(exercise_id, routes):
    hidden = set(answer_for(exercise(exercise_id)).names())
    assert set(routes) <= hidden, sorted(set(routes) - hidden)


def test_what_an_exercise_does_not_ask_for_stays_visible():
    hidden = set(answer_for(exercise("2.2")).names())
    assert {
        "urkin.transforms.rot_z",
        "urkin.symbolic.Q",
        "urkin.symbolic.simplify_angles",
        "urkin.symbolic.dh_transform",
    }.isdisjoint(hidden)
    assert "urkin.kinematics.fk" not in answer_for(exercise("4.2")).names()


def test_hiding_in_process_covers_aliases_and_restores_them():
    namespace = {"my_fk": urkin.fk, "other": np.cos}
    original = urkin.kinematics.fk
    with answer_for(exercise("2.2")).hidden_in(namespace):
        assert isinstance(namespace["my_fk"], Hidden) and namespace["other"] is np.cos
        assert isinstance(urkin.fk, Hidden) and isinstance(urkin.numerical_ik.fk, Hidden)
        with pytest.raises(ForbiddenCallError, match=r"exercise 2\.2"):
            namespace["my_fk"](urkin.robot("ur5"), np.zeros(6))
        with pytest.raises(ForbiddenCallError):
            urkin.poe.fk_space(np.eye(4), np.zeros((6, 6)), np.zeros(6))
    assert urkin.fk is original and namespace["my_fk"] is original
    assert urkin.robot("ur5").name == "UR5"


def test_a_hidden_name_refuses_every_use():
    stand_in = Hidden("urkin.robots.T_BASE_LINK_BASE", "0.2")
    for use in (
        lambda: stand_in @ np.eye(4),
        lambda: np.asarray(stand_in) + 1,
        lambda: stand_in[0],
        lambda: stand_in.T,
        lambda: list(stand_in),
        lambda: float(stand_in),
    ):
        with pytest.raises(ForbiddenCallError, match=r"exercise 0\.2"):
            use()


VIEW_PROBE = textwrap.dedent(
    """
    import sys
    sys.path.insert(0, sys.argv[1])
    import urkin, urkin.course
    from urkin.course import check, seeds, lab
    assert urkin.__file__.startswith(sys.argv[1]), urkin.__file__
    assert urkin.robot("ur5").name == "UR5"
    assert check("2.1", None) is None
    for name in sys.argv[2:]:
        module, _, item = name.rpartition(".")
        __import__(module)
        value = getattr(sys.modules[module], item)
        try:
            value()
        except Exception as exc:
            assert type(exc).__name__ == "ForbiddenCallError", (name, exc)
        else:
            raise AssertionError(f"{name} answered")
    print("ok")
    """
)


@pytest.mark.parametrize("ex", EXERCISES, ids=IDS)
def test_the_view_of_urkin_imports_and_hides_the_answer(ex, tmp_path):
    answer = answer_for(ex)
    answer.write_view(tmp_path)
    names = [n for n in answer.names() if not n.startswith("urkin.symbolic")][:40]
    run = subprocess.run(
        [sys.executable, "-I", "-B", "-c", VIEW_PROBE, str(tmp_path), *names],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.stdout.strip() == "ok", run.stderr[-2000:]


def test_every_library_module_is_in_the_views():
    names = set(library_modules())
    for module in (
        "urkin",
        "urkin.kinematics",
        "urkin._generated.ur_kinematics",
        "urkin.course.lab",
        "urkin.course.wire",
        "urkin.course.grading.child",
    ):
        assert module in names
    assert not any(
        n.startswith(("urkin.course.lessons", "urkin.course.grading.runner")) for n in names
    )
    assert Path(PACKAGE / "course" / "lessons").is_dir()
