import numpy as np
import pytest

from tests.solutions_reference import SOLUTIONS, WRONG
from urkin.exercises import check, exercise, exercises_for_lesson, run_exercise

LESSONS = ("00", "01", "02", "03", "04", "05", "06", "07")
ALL_IDS = [e.id for lesson in LESSONS for e in exercises_for_lesson(lesson)]
SEEDS = [0, 1, 20261121]


def test_every_exercise_has_a_reference_solution_here():
    assert sorted(ALL_IDS) == sorted(SOLUTIONS)


@pytest.mark.parametrize("exercise_id", ALL_IDS)
@pytest.mark.parametrize("seed", SEEDS)
def test_a_correct_solution_earns_full_marks(exercise_id, seed):
    result = run_exercise(exercise_id, SOLUTIONS[exercise_id], seed=seed)
    assert result.status == "passed", result.report()
    assert result.earned == exercise(exercise_id).points


@pytest.mark.parametrize(
    ("exercise_id", "wrong", "words"),
    [(eid, f, words) for eid, variants in WRONG.items() for f, words in variants],
)
def test_a_known_mistake_loses_points_and_is_named(exercise_id, wrong, words):
    result = run_exercise(exercise_id, wrong, seed=7)
    assert result.earned < result.points, result.report()
    assert any(words in m for m in result.mistakes), result.report()
    assert words in result.report()


@pytest.mark.parametrize("exercise_id", ALL_IDS)
def test_an_unattempted_exercise_scores_zero_and_says_so(exercise_id):
    def stub(*args):
        raise NotImplementedError(f"Exercise {exercise_id}")

    result = run_exercise(exercise_id, stub)
    assert (result.status, result.earned) == ("not attempted", 0.0)


@pytest.mark.parametrize(
    ("function", "status", "words"),
    [
        (lambda *a: None, "failed", "None"),
        (lambda *a: "four by four", "failed", "numbers"),
        (lambda *a: 1 / 0, "failed", "ZeroDivisionError"),
        (lambda *a: np.zeros((2, 2)), "failed", "shape"),
        ("not a function", "missing", "must be a function"),
    ],
)
def test_broken_answers_get_a_message_not_an_exception(function, status, words):
    result = run_exercise("2.1", function)
    assert result.status == status
    assert result.earned == 0
    assert words in result.report()


def test_sys_exit_inside_a_function_is_reported():
    def leaves(*args):
        raise SystemExit(3)

    result = run_exercise("1.1", leaves)
    assert "sys.exit" in result.report()


def test_the_error_message_points_at_the_students_line():
    def rot_z(theta):
        c = np.cos(theta)
        return np.array([[c, -undefined_name, 0]])  # noqa: F821

    assert "line" in run_exercise("1.1", rot_z).report()


def test_check_prints_a_report_and_never_raises(capsys):
    check("2.1", SOLUTIONS["2.1"])
    assert "passed" in capsys.readouterr().out
    check("9.9", SOLUTIONS["2.1"])
    assert "no exercise" in capsys.readouterr().out


def test_visible_checks_are_deterministic():
    first = run_exercise("2.2", WRONG["2.2"][0][0]).report()
    assert first == run_exercise("2.2", WRONG["2.2"][0][0]).report()


def test_grading_seeds_draw_other_inputs_than_the_visible_check():
    a = run_exercise("2.2", WRONG["2.2"][0][0], seed=0).report()
    b = run_exercise("2.2", WRONG["2.2"][0][0], seed=1).report()
    assert a != b


def test_rpy_without_a_gimbal_lock_branch_loses_the_gimbal_lock_point():
    def general_formulas_only(R):
        pitch = np.arctan2(-R[2, 0], np.hypot(R[0, 0], R[1, 0]))
        return np.array([np.arctan2(R[2, 1], R[2, 2]), pitch, np.arctan2(R[1, 0], R[0, 0])])

    for seed in SEEDS:
        result = run_exercise("1.3", general_formulas_only, seed=seed)
        assert result.earned == result.points - 1, result.report()
        assert "gimbal lock" in result.report()
