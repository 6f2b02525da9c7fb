"""The shared option checks of urkin._inputs: positive() on its fast path (plain int and
float) and on its general path must give the same verdicts."""

from __future__ import annotations

import math

import numpy as np
import pytest

from urkin._inputs import positive


@pytest.mark.parametrize(
    "value, kwargs",
    [
        (0.5, {}),
        (3, {}),
        (0, {"zero_ok": True}),
        (0.0, {"zero_ok": True}),
        (7, {"integer": True}),
        (10**400, {"integer": True}),  # too large for a float, still a valid count
        (np.float64(0.25), {}),
        (np.int64(4), {"integer": True}),
    ],
)
def test_accepted_values_come_back_unchanged(value, kwargs):
    assert positive(value, "x", **kwargs) is value


@pytest.mark.parametrize(
    "value, kwargs, error",
    [
        (True, {}, TypeError),
        (False, {"zero_ok": True}, TypeError),
        ("1", {}, TypeError),
        (None, {}, TypeError),
        (np.ones(1), {}, TypeError),
        (math.nan, {}, ValueError),
        (math.inf, {}, ValueError),
        (-math.inf, {"zero_ok": True}, ValueError),
        (0, {}, ValueError),
        (0.0, {}, ValueError),
        (-1, {"zero_ok": True}, ValueError),
        (-1e-300, {"zero_ok": True}, ValueError),
        (2.0, {"integer": True}, ValueError),
        (np.float64(math.nan), {}, ValueError),
    ],
)
def test_refused_values_name_the_option(value, kwargs, error):
    with pytest.raises(error, match=r"^tol must be"):
        positive(value, "tol", **kwargs)
