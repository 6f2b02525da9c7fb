"""The feedback of a few checks, beyond the points: float32 answers built on float32 helpers,
the float32 tolerance, and mistakes named once and in the right place."""

from __future__ import annotations

import numpy as np
import pytest

from tests.namespaces import variant
from tests.variants import lesson02, lesson03, lesson07
from urkin.course.cell import check_result
from urkin.course.compare import FLOAT32_ULPS, tolerance

EPS32 = float(np.finfo(np.float32).eps)


def _result(number, v, seed=0):
    return check_result(v.exercise, None, variant(number, v.exercise, v.source, v.also), seed)


def _named(module, name, exercise=None):
    return next(
        v
        for v in module.CORRECT + module.WRONG
        if v.name == name and exercise in (None, v.exercise)
    )


def test_float32_tolerance_is_a_few_times_the_float32_round_off():
    # honest float32 answers err by at most 2 ε·max(1, scale) on the checks' inputs
    assert FLOAT32_ULPS == 8
    assert tolerance(1e-9, np.zeros(3, dtype=np.float32)) == pytest.approx(8 * EPS32)
    assert tolerance(1e-9, np.zeros(3, dtype=np.float32), 3.0) == pytest.approx(24 * EPS32)
    assert tolerance(1e-9, np.zeros(3)) == 1e-9  # float64: as stated
    assert tolerance(3e-6, np.zeros(3, dtype=np.float32)) == 3e-6  # only ever looser


@pytest.mark.parametrize(
    "name",
    [
        "float32, the flange 3 µm off",
        "float64 product of a float32 dh_transform, the flange 3 µm off",
    ],
)
def test_a_3_micrometre_error_fails_in_float32(name):
    result = _result("02", _named(lesson02, name))
    assert result.earned < result.points, result.report()


def test_a_float32_helper_is_named_when_an_answer_built_on_it_misses():
    result = _result(
        "02", _named(lesson02, "float64 product of a float32 dh_transform, the flange 3 µm off")
    )
    assert "your dh_transform (2.1) returns float32" in result.report(), result.report()


def test_the_lab_ik_round_trip_shows_the_difference_and_the_float32_helper():
    v = _named(lesson07, "built on a float32 planar_2r, every angle 2e-5 rad off")
    result = _result("07", v)
    round_trip = result.checks[0].message
    assert round_trip.startswith("fk_lab(ik_lab(x_w, y_w, z_w, yaw_w)) must give back"), round_trip
    assert "largest difference" in round_trip and "the tolerance is" in round_trip, round_trip
    assert "your planar_2r (7.2) returns float32" in round_trip, round_trip


def test_a_list_failure_is_reported_only_where_an_array_passes():
    # a wrong pose for arrays too is not blamed on lists, and earns no point there either
    result = _result("02", _named(lesson02, "links multiplied in reverse order"))
    assert "q may be a list" not in result.report(), result.report()
    assert "wrong for an array of angles too" in result.report(), result.report()
    assert result.checks[-1].earned == 0, result.report()
    broken = _result("02", _named(lesson02, "a list breaks it: q + 0.0 on an array only"))
    assert broken.checks[-1].earned == 0, broken.report()


def test_the_twist_order_is_named_at_the_half_turn_too():
    result = _result("03", _named(lesson03, "(v, ω) order", "3.5"))
    assert result.mistakes, result.report()
    assert all("(v, ω) order" in m for m in result.mistakes), result.report()
    assert "half turn: it is lost" not in result.report(), result.report()


def test_the_degrees_mistake_is_named_once():
    from tests.variants import lesson01

    result = _result("01", _named(lesson01, "degrees", "1.3"))
    degrees = [m for m in result.mistakes if "degrees" in m]
    assert len(degrees) == 1, result.report()
    assert result.message.count("returned degrees") == 1, result.report()
