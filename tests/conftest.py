import numpy as np
import pytest

import urkin


@pytest.fixture
def rng():
    return np.random.default_rng(20261121)


@pytest.fixture(params=urkin.ROBOTS)
def arm(request):
    return urkin.robot(request.param)
