import numpy as np
import pytest

import urkin


def pytest_addoption(parser):
    group = parser.getgroup("urkin grading")
    group.addoption(
        "--submission",
        action="append",
        default=[],
        metavar="PATH",
        help="grade this notebook (or folder of notebooks) in tests/grading; repeatable. "
        "Without it, tests/grading grades the solution notebooks, which must score full marks.",
    )
    group.addoption("--grading-seed", type=int, default=None, help="seed of the test inputs")
    group.addoption("--time-limit", type=float, default=None, help="seconds per exercise")


@pytest.fixture
def rng():
    return np.random.default_rng(20261121)


@pytest.fixture(params=urkin.ROBOTS)
def arm(request):
    return urkin.robot(request.param)
