"""Seeds 000 and 002's tracking programs, replayed: each published number of ERRATA.md comes out.

The references are ERRATA.md's measurements (found there with independent code) and plain
geometry; nothing here compares urkin with itself.
"""

from __future__ import annotations

import numpy as np
import pytest

import urkin
from urkin.course.seed_programs import (
    SEED000_HOME,
    seed000_circle,
    seed000_run,
    seed000_solve,
    seed000_square,
    seed002_run,
)
from urkin.course.seeds import SEED002_ARM

UR3 = urkin.robot("UR3")


def _spacing(poses):
    return np.linalg.norm(np.diff(poses[:, :3, 3], axis=0), axis=1)


def test_seed_000_samples_about_8_and_11_mm_not_1_mm_with_repeats():
    square, circle = seed000_square(), seed000_circle()
    assert _spacing(square).max() == pytest.approx(0.15 / 19)
    assert _spacing(circle).max() == pytest.approx(
        2 * np.pi * 0.1 / 59 * np.sinc(1 / 59), rel=1e-12
    )
    assert (_spacing(square) < 1e-12).sum() == 3  # three inner corners twice
    assert np.allclose(circle[0], circle[-1])  # the start once more at the end
    centre = np.array([0.25, 0.1, 0.3])
    assert np.allclose(np.linalg.norm(circle[:, :3, 3] - centre, axis=1), 0.1)
    assert np.allclose(square[:, :3, :3], np.eye(3)) and np.allclose(circle[:, 0, 3], 0.25)


def test_seed_000_home_then_square_winds_joint_3_to_minus_865_degrees():
    replay = seed000_run(UR3, seed000_square(), SEED000_HOME)
    assert replay.converged.all()
    assert np.degrees(replay.q[:, 2].min()) == pytest.approx(-865, abs=1)
    # converged by its mixed test: every position within 1 mm, as the 1e-3 bound allows
    errors = np.linalg.norm(urkin.fk(UR3, replay.q)[:, :3, 3] - seed000_square()[:, :3, 3], axis=1)
    assert errors.max() < 1e-3


def test_seed_000_home_then_circle_puts_the_elbow_80_mm_below_the_mounting_plane():
    replay = seed000_run(UR3, seed000_circle(), SEED000_HOME)
    elbow = urkin.kinematics.fk_frames(UR3, replay.q)[:, 2, 2, 3]  # frame 2's origin, height
    assert elbow.min() == pytest.approx(-0.080, abs=1e-3)


def test_seed_000_first_step_from_home_and_the_huge_second_one():
    # ERRATA: the first step is 0.43 rad, the second about 13 rad
    target = seed000_square()[0]
    q1, _, _ = seed000_solve(UR3, target, SEED000_HOME, max_iter=1)
    q2, _, _ = seed000_solve(UR3, target, SEED000_HOME, max_iter=2)
    assert np.abs(q1 - SEED000_HOME).max() == pytest.approx(0.43, abs=0.01)
    assert np.abs(q2 - q1).max() == pytest.approx(13.5, abs=0.5)


def test_seed_000_overwrites_the_state_when_a_solve_fails():
    poses = np.broadcast_to(np.eye(4), (30, 4, 4)).copy()
    poses[:, :3, 3] = np.column_stack(
        [np.linspace(0.25, 0.7, 30), np.full(30, 0.1), np.full(30, 0.3)]
    )
    replay = seed000_run(UR3, poses, SEED000_HOME)
    failed = np.flatnonzero(~replay.converged)
    assert failed.size > 0 and failed[0] > 0
    k = failed[0]
    assert not np.array_equal(replay.q[k], replay.q[k - 1])  # moved although it failed


def test_seed_002_published_formula_misses_by_centimetres_the_truth_within_its_test():
    side = np.linspace(0.0, 0.2, 41)[:-1]
    corners = np.array([[0.3, 0.2, 0.2], [0.5, 0.2, 0.2], [0.5, 0.4, 0.2], [0.3, 0.4, 0.2]])
    points = np.vstack(
        [a + np.outer(side / 0.2, b - a) for a, b in zip(corners, np.roll(corners, -1, axis=0))]
    )
    published, truth = seed002_run(points), seed002_run(points, published=False)
    assert published.converged.all() and truth.converged.all()

    def miss(q):
        return np.linalg.norm(urkin.fk(SEED002_ARM, q)[:, :3, 3] - points, axis=1)

    assert miss(published.q).min() > 0.05  # centimetres off, although "converged"
    assert miss(truth.q).max() <= np.sqrt(3) * 1e-3 + 1e-12  # 1 mm per coordinate
    assert miss(published.q).max() <= 2 * SEED002_ARM.d6  # lesson 02's bound
    # the drawn angles are the solved ones scaled by 0.01744 / 0.0175 in the report's angles
    shift = np.array([0.0, np.pi, 0.0, -np.pi, 0.0, 0.0])
    assert np.allclose(published.drawn + shift, (published.q + shift) * 0.01744 / 0.0175)
