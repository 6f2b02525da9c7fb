"""Timing planned paths: the motion stays on the checked straight edges, within the limits."""

import itertools

import numpy as np
import pytest

import urkin
from urkin import planning

PATH = np.array(
    [
        [0.0, -1.5, 1.0, 0.0, 0.5, 0.0],
        [0.8, -1.2, 0.4, 0.3, 0.5, -1.0],
        [0.8, -1.2, 0.4, 0.3, 0.5, -1.0],  # repeated: merged
        [1.5, -0.6, 0.9, -0.2, 1.4, -0.2],
        [1.52, -0.6, 0.9, -0.2, 1.4, -0.2],  # short: the acceleration limit decides
    ]
)


@pytest.mark.parametrize("a", [1.5, 50.0])  # limited by acceleration, then by speed
def test_samples_lie_on_the_edges_and_respect_the_limits(a):
    v = np.array([1.0, 1.0, 1.2, 2.0, 2.0, 2.0])
    traj = planning.time_parametrize(PATH, v, a, dt=0.002)
    vias = PATH[[0, 1, 3, 4]]
    # every sample is on the segment between two consecutive vias
    best = np.full(len(traj.q), np.inf)
    for p, q in itertools.pairwise(vias):
        d = q - p
        s = np.clip((traj.q - p) @ d / (d @ d), 0, 1)
        best = np.minimum(best, np.linalg.norm(traj.q - p - s[:, None] * d, axis=1))
    assert best.max() < 1e-12
    assert np.all(np.abs(traj.qd) <= v * (1 + 1e-12))
    assert np.all(np.abs(traj.qdd) <= a * (1 + 1e-12))
    # the durations are the shortest: some joint reaches a limit on every edge
    change = np.abs(np.diff(vias, axis=0))
    T = np.max(np.maximum(1.5 * change / v, np.sqrt(6 * change / a)), axis=1)
    np.testing.assert_allclose(traj.t[-1], T.sum(), rtol=1e-12)
    np.testing.assert_allclose(traj.q[-1], PATH[-1], atol=1e-15)
    np.testing.assert_allclose(traj.qd[[0, -1]], 0, atol=1e-15)
    assert np.all(np.diff(traj.t) > 0)
    peak = max(np.max(np.abs(traj.qd) / v), np.max(np.abs(traj.qdd) / a))
    assert peak > 0.99  # sampled at 2 ms: a limit is reached


def test_rest_to_rest_matches_a_cubic_time_scaling():
    q0, q1 = PATH[0], PATH[1]
    traj = planning.time_parametrize([q0, q1], dt=0.001)
    s, sd, _ = urkin.trajectory.time_scaling("cubic", traj.t[-1])(traj.t)
    np.testing.assert_allclose(traj.q, q0 + s[:, None] * (q1 - q0), atol=1e-12)
    np.testing.assert_allclose(traj.qd, sd[:, None] * (q1 - q0), atol=1e-12)


def test_plans_and_bad_input():
    model = planning.sphere_model(urkin.robot("ur5"))
    plan = planning.rrt_connect(model, planning.Scene(), PATH[0], PATH[3], seed=0)
    assert plan.success
    traj = planning.time_parametrize(plan)
    np.testing.assert_allclose(traj.q[-1], plan.path[-1], atol=1e-15)
    failed = planning.Plan(np.zeros((0, 6)), False, "no path", 10, 2, -1, PATH[:1], 0.1)
    with pytest.raises(ValueError, match=r"path: the plan did not succeed \(no path\)"):
        planning.time_parametrize(failed)
    with pytest.raises(ValueError, match="max_velocity must be positive"):
        planning.time_parametrize(PATH, [1, 1, 1, 1, 1, 0])
    with pytest.raises(ValueError, match="max_acceleration must be positive"):
        planning.time_parametrize(PATH, 1.0, -1)
    with pytest.raises(ValueError, match="path must have shape"):
        planning.time_parametrize(PATH[0])
    with pytest.raises(ValueError, match="NaN"):
        planning.time_parametrize(np.where(PATH == PATH[1, 1], np.nan, PATH))
    with pytest.raises(ValueError, match="dt must be"):
        planning.time_parametrize(PATH, dt=0)
    still = planning.time_parametrize(PATH[[1, 2]])
    assert len(still.t) == 1 and np.all(still.qd == 0)
