"""pytransform3d's SO(3) and SE(3) test suites, ported to :mod:`urkin.transforms`.

pytransform3d (Alexander Fabisch, DFKI; BSD-3-Clause licence) tests its rotations and rigid
transformations in ``pytransform3d/rotations/test/`` and ``pytransform3d/transformations/test/``
(read at release 3.14.4).  Every property below that has an urkin counterpart is restated here
in urkin's conventions; no code was copied, and pytransform3d need not be installed (the
expected values are closed forms, textbook matrices, or series computed here).

Ported (one test function per property; the source test is named in each docstring)
    * ``test_matrix.py``: input validation of rotation matrices (dtype, shape, orthonormality,
      determinant, the tolerance and its threshold, issue #54), renormalization (``norm_matrix``,
      ``matrix_requires_renormalization``), matrix ↔ axis-angle round trips including angles
      near 0 and near π (issues #43, #189, #198), the comparison with Modern Robotics' log at
      θ = π, cos θ > 1 by round-off, continuity across π, and the unchecked path.
    * ``test_axis_angle.py``: normalization of rotation vectors (angles outside [0, π], any
      number of extra turns), shape validation.
    * ``test_angle.py``: angle normalization (``norm_angle`` → :func:`wrap_angles`, with its
      precision tests), rotations about the basis axes, active versus passive.
    * ``test_euler.py``: Euler-angle normalization, conventions and round trips, both gimbal
      locks and their neighbourhood, for urkin's one convention, roll–pitch–yaw.
    * ``test_rot_log.py``: cross-product matrices.
    * ``test_rotations_random.py``: random rotations.
    * ``test_polar_decom.py``: the nearest rotation of a scaled or perturbed matrix.
    * ``test_batch_rotations.py``: the same conversions on stacks of any leading shape.
    * ``test_transform.py``: input validation of transforms, the log of an almost-identity
      pose, the unchecked paths, the adjoint.
    * ``test_transform_operations.py``: inversion, concatenation.
    * ``test_screws.py``: exponential coordinates ↔ transform (fixed cases, random poses,
      normalization of ‖ω‖ > π, the 180° ambiguity of screws), ↔ the se(3) matrix, revolute
      screw axes, shape validation.
    * ``test_transformations_random.py``: random poses.

Added where a port exposed something: se3_exp and se3_log against a matrix-exponential series
at small angles (1e-7 … 1e-2 rad), and argument validation of the tolerance and of the random
samplers.

Skipped, because urkin does not offer them
    Quaternions, dual quaternions, position–quaternion (``pq``), SLERP, modified Rodrigues
    parameters, rotors; the Euler conventions other than roll–pitch–yaw (23 of 24) and the
    axis-index arguments that choose them (``euler_near_gimbal_lock``,
    ``assert_euler_equal``); screw parameters with a pitch and their checks
    (``check_screw_parameters``, ``check_screw_axis``, ``check_screw_matrix``,
    ``check_transform_log``, ``screw_axis_from_exponential_coordinates``); left Jacobians of
    SO(3) and SE(3); vector helpers (``norm_vector``, ``perpendicular_to_vector(s)``,
    ``angle_between_vectors``, ``vector_projection``, ``plane_basis_from_normal``,
    ``matrix_from_two_vectors``, ``axis_angle_from_two_directions``); points and directions
    in homogeneous coordinates; ``scale_transform``; random rotations around a mean with a
    covariance; ``out=`` arguments; ``strict_check=False`` warnings; and everything outside
    SO(3)/SE(3): plotting, the transform manager, trajectories, uncertainty, cameras, URDF,
    meshes.

Conventions that differ (asserted here as urkin's, not pytransform3d's)
    * Rotation vectors are compact (``θ k``, 3 numbers), never ``(k, θ)``; at θ = π, ``ω`` and
      ``−ω`` are the same rotation and urkin's sign follows the round-off of the matrix's
      antisymmetric part, so values at π are compared up to sign (as pytransform3d's own
      ``assert_compact_axis_angle_equal`` does).
    * ``inv_transform`` always validates (no ``check=False``): a matrix that is not rigid is
      refused with a ValueError naming ``T`` instead of being inverted.
    * ``unskew`` and ``twist_vector`` read the antisymmetric part of the rotation block and do
      not refuse a non-skew matrix; ``make_transform`` does not validate ``R``.
    * A ``(3, 3)`` array given to :func:`so3_exp` is a stack of three rotation vectors.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from urkin import poe
from urkin.transforms import (
    adjoint,
    check_rotation,
    check_transform,
    inv_transform,
    make_transform,
    orthonormalize,
    random_rotations,
    random_transforms,
    rot_x,
    rot_y,
    rot_z,
    rotation_angle,
    rotation_to_rpy,
    rpy_to_rotation,
    se3_exp,
    se3_log,
    skew,
    so3_exp,
    so3_log,
    twist_matrix,
    twist_vector,
    unskew,
    wrap_angles,
)

PI = np.pi
EYE3 = np.eye(3)
AXIS_ROTATIONS = (rot_x, rot_y, rot_z)


# ------------------------------------------------------------------------- references


def unit(v):
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def random_unit_vectors(rng, n):
    v = rng.normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=1, keepdims=True)


def expm_series(M, terms=30):
    """``exp(M)`` by scaling, a Taylor series and squaring: a reference independent of urkin's
    closed forms (for matrices whose norm is a few units at most)."""
    norm = np.abs(M).sum(axis=-1).max()
    squarings = max(0, math.ceil(math.log2(norm))) + 2 if norm > 0 else 0
    A = M / 2.0**squarings
    term = np.eye(len(M))
    total = term.copy()
    for k in range(1, terms):
        term = term @ A / k
        total = total + term
    for _ in range(squarings):
        total = total @ total
    return total


def textbook_rpy(roll, pitch, yaw):
    """Roll, pitch, yaw as Craig's X–Y–Z fixed angles, written out entry by entry."""
    cr, sr, cp, sp, cy, sy = (f(a) for a in (roll, pitch, yaw) for f in (np.cos, np.sin))
    return np.array(
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    )


def assert_same_rotation_vector(w1, w2, atol=1e-12):
    """Equal rotation vectors, where at angle π ``ω`` and ``−ω`` are the same rotation."""
    w1, w2 = np.asarray(w1), np.asarray(w2)
    if abs(np.linalg.norm(w1) - PI) < 1e-6:
        if np.dot(w1, w2) < 0:
            w2 = -w2
    np.testing.assert_allclose(w1, w2, rtol=0, atol=atol)


def normalized_rotation_vector(axis, angle):
    """``angle · axis`` with the angle brought into [0, π] (the axis flips for negative ones)."""
    wrapped = float(wrap_angles(angle))
    return abs(wrapped) * (np.sign(wrapped) or 1.0) * np.asarray(axis)


# ------------------------------------------------------------ test_matrix.py: validation


def test_check_rotation_returns_float_arrays():
    """test_check_matrix: a list or an int array comes back as a float64 ndarray; a float
    rotation comes back unchanged."""
    for given_R in ([[1, 0, 0], [0, 1, 0], [0, 0, 1]], np.eye(3, dtype=int)):
        R = check_rotation(given_R)
        assert type(R) is np.ndarray and R.dtype == np.float64
        np.testing.assert_array_equal(R, EYE3)
    R = rot_z(0.3)
    np.testing.assert_array_equal(check_rotation(R), R)


@pytest.mark.parametrize("shape", [(4, 4), (3,), (3, 4), (4, 3), (0,), (), (2, 3)])
def test_check_rotation_refuses_a_wrong_shape_naming_it(shape):
    """test_check_matrix: a 4×4 matrix (or any other shape) is not a rotation."""
    with pytest.raises(ValueError, match=r"R must have shape \(3, 3\)"):
        check_rotation(np.ones(shape))


@pytest.mark.parametrize(
    "matrix",
    [
        [[1, 0, 0], [0, 1, 0], [0, 0.1, 1]],  # a shear: RᵀR ≠ I
        np.diag([1.0, 1.0, 2.0]),  # test_deactivate_rotation_matrix_precision_error
        np.zeros((3, 3)),
        [[1, 0, 0], [1, 0, 0], [0, 0, 1]],  # rank 2
    ],
)
def test_check_rotation_refuses_a_matrix_that_is_not_orthonormal(matrix):
    """test_check_matrix: columns that are not orthonormal are refused, saying so."""
    with pytest.raises(ValueError, match="R is not a rotation matrix: its columns are not"):
        check_rotation(matrix)


@pytest.mark.parametrize("matrix", [-EYE3, np.diag([1.0, 1.0, -1.0]), np.diag([1.0, 1.0, -2.0])])
def test_check_rotation_refuses_a_reflection(matrix):
    """test_check_matrix: det R = −1 (an orthonormal reflection) is refused."""
    with pytest.raises(ValueError, match=r"R is a reflection, not a rotation: det\(R\) = -1"):
        check_rotation(matrix)


def test_check_rotation_accepts_round_off():
    """test_check_matrix and test_check_matrix_threshold (issue #54): round-off of 1e-16 and
    a rotation printed with eight decimals are rotations, returned as given."""
    R = np.array([[1, 0, 1e-16], [0, 1, 0], [0, 0, 1]])
    np.testing.assert_array_equal(check_rotation(R), R)
    printed = np.array(
        [
            [-9.15361835e-01, 4.01808328e-01, 2.57475872e-02],
            [5.15480570e-02, 1.80374088e-01, -9.82246499e-01],
            [-3.99318925e-01, -8.97783496e-01, -1.85819250e-01],
        ]
    )
    np.testing.assert_array_equal(check_rotation(printed), printed)


def test_check_rotation_threshold_is_its_tolerance(rng):
    """test_assert_rotation_matrix_behaves_like_check_matrix: one diagonal entry moved by
    ``e`` moves ``RᵀR`` by about ``2e``; below the tolerance it passes, above it is refused."""
    for R in random_rotations(5, seed=rng):
        for error in (0.0, 1e-8, 1e-7, 1e-5, 1e-4, 1.0):
            moved = R.copy()
            moved[2, 2] += error
            gram_error = np.abs(moved.T @ moved - EYE3).max()
            if gram_error <= 0.5e-6:
                np.testing.assert_array_equal(check_rotation(moved), moved)
            else:
                with pytest.raises(ValueError, match="R is not a rotation matrix"):
                    check_rotation(moved)


@pytest.mark.parametrize(
    ("tol", "error", "message"),
    [
        (-1e-6, ValueError, "tol must be one number ≥ 0"),
        (np.nan, ValueError, "tol contains NaN"),
        (np.inf, ValueError, "tol contains NaN or infinity"),
        ("1e-6", TypeError, "tol must be numbers"),
        ([1e-6, 1e-6], ValueError, "tol must be one number"),
    ],
)
def test_the_tolerance_is_validated(tol, error, message):
    """strict_check's counterpart: a tolerance that is not a finite number ≥ 0 is refused
    (a NaN tolerance used to accept any matrix)."""
    with pytest.raises(error, match=message):
        check_rotation(2 * EYE3, tol=tol)
    with pytest.raises(error, match=message):
        check_transform(np.eye(4), tol=tol)


def test_a_looser_tolerance_accepts_more():
    R = EYE3.copy()
    R[1, 0] = 1e-3
    with pytest.raises(ValueError, match="tolerance 1e-06"):
        check_rotation(R)
    np.testing.assert_array_equal(check_rotation(R, tol=1e-2), R)


# -------------------------------------------------- test_matrix.py / test_polar_decom.py


def test_orthonormalize_keeps_rotations_and_repairs_round_off():
    """test_norm_rotation_matrix: the identity stays, an ε off it comes back to it, a
    stretched axis is taken out."""
    np.testing.assert_array_equal(orthonormalize(EYE3), EYE3)
    R = EYE3.copy()
    R[1, 0] += np.finfo(float).eps
    repaired = orthonormalize(R)
    np.testing.assert_allclose(repaired, EYE3, rtol=0, atol=1e-14)
    assert abs(np.linalg.det(repaired) - 1.0) <= 1e-15
    R = EYE3.copy()
    R[1, 1] += 0.3
    np.testing.assert_allclose(orthonormalize(R), EYE3, rtol=0, atol=1e-14)


def test_products_of_rotations_drift_and_orthonormalize_repairs_them(rng):
    """test_matrix_requires_renormalization: a product of rotations is a rotation to round-off;
    a perturbation of 1e-3 is refused and its nearest rotation passes a 1e-15 check."""
    total = EYE3
    for rpy in rng.uniform(-PI, PI, (10, 3)):
        R = rpy_to_rotation(rpy)
        check_rotation(R, tol=1e-14)
        total = R @ total
    check_rotation(total, tol=1e-14)
    check_rotation(orthonormalize(total), tol=1e-14)
    np.testing.assert_allclose(orthonormalize(total), total, rtol=0, atol=1e-14)
    bad = EYE3.copy()
    bad[1, 0] += 1e-3
    with pytest.raises(ValueError, match="not a rotation"):
        check_rotation(bad)
    check_rotation(orthonormalize(bad), tol=1e-14)


def test_orthonormalize_is_the_polar_decomposition(rng):
    """test_polar_decomposition: a scaled rotation gives the rotation back; a basis vector
    turned by a few degrees is repaired by spreading the error over all three columns."""
    for R in random_rotations(5, seed=rng):
        np.testing.assert_allclose(orthonormalize(23.5 * R), R, rtol=0, atol=1e-14)
    R = rpy_to_rotation(np.radians([45.0, 45.0, -45.0]))
    moved = R.copy()
    moved[:, 0] = rot_z(np.radians(1.0)) @ moved[:, 0]
    errors = np.linalg.norm(moved - R, axis=0)
    np.testing.assert_allclose(errors, [2 * np.sin(np.radians(0.5)) * np.hypot(*R[:2, 0]), 0, 0])
    repaired = np.linalg.norm(orthonormalize(moved) - R, axis=0)
    assert np.all(repaired > 0) and np.all(repaired < errors[0])
    assert np.std(repaired) < np.std(errors)
    for R in random_rotations(20, seed=rng):
        moved = R.copy()
        column = rng.integers(3)
        turn = AXIS_ROTATIONS[rng.integers(3)](np.radians(rng.uniform(-3, 3)))
        moved[:, column] = turn @ moved[:, column]
        errors = np.linalg.norm(moved - R, axis=0)
        repaired = np.linalg.norm(orthonormalize(moved) - R, axis=0)
        assert np.all(repaired > 0) and np.all(repaired < errors.sum())
        assert np.std(repaired) < np.std(errors)
        check_rotation(orthonormalize(moved), tol=1e-14)


def test_orthonormalize_refuses_a_reflection_and_a_wrong_shape():
    with pytest.raises(ValueError, match="closer to a reflection"):
        orthonormalize(-EYE3)
    with pytest.raises(ValueError, match=r"R must have shape \(3, 3\)"):
        orthonormalize(np.eye(4))


# ------------------------------------------------- test_matrix.py: matrix ↔ axis-angle


@pytest.mark.parametrize(
    ("R", "expected"),
    [
        (EYE3, [0.0, 0.0, 0.0]),
        (rot_x(-PI) @ rot_y(-PI), [0.0, 0.0, PI]),  # intrinsic x-y-z (−π, −π, 0)
        (rot_x(-PI) @ rot_z(-PI), [0.0, PI, 0.0]),  # intrinsic x-y-z (−π, 0, −π)
        (rot_y(-PI) @ rot_z(-PI), [PI, 0.0, 0.0]),  # intrinsic x-y-z (0, −π, −π)
        (so3_exp(PI * unit([1.0, 1.0, 0.0])), PI * unit([1.0, 1.0, 0.0])),
    ],
)
def test_log_of_known_rotations(R, expected):
    """test_conversions_matrix_(compact_)axis_angle: the identity and half turns."""
    w = so3_log(R)
    assert_same_rotation_vector(w, expected, atol=1e-14)
    np.testing.assert_allclose(so3_exp(w), R, rtol=0, atol=1e-14)


def test_matrix_axis_angle_round_trips(rng):
    """test_conversions_matrix_(compact_)axis_angle: random rotation vectors of angle < π."""
    axes = random_unit_vectors(rng, 50)
    w = axes * rng.uniform(0, PI, (50, 1))
    R = so3_exp(w)
    check_rotation(R, tol=1e-14)
    np.testing.assert_allclose(so3_log(R), w, rtol=0, atol=1e-13)
    np.testing.assert_allclose(so3_exp(so3_log(R)), R, rtol=0, atol=1e-14)
    check_rotation(so3_exp(so3_log(R)), tol=1e-14)


@pytest.mark.parametrize("basis", [0, 1, 2])
def test_log_at_pi_agrees_with_modern_robotics(basis):
    """test_compare_axis_angle_from_matrix_to_lynch_park: at θ = π (trace −1) the axis is
    Modern Robotics' ``(r_1b, r_2b, 1 + r_bb) / √(2 (1 + r_bb))`` for the basis axis b."""
    R = AXIS_ROTATIONS[basis](-PI)  # pytransform3d's passive rotation by π
    assert np.trace(R) == pytest.approx(-1.0, abs=1e-15)
    column = R[:, basis].copy()
    column[basis] += 1.0
    axis = column / np.sqrt(2.0 * (1.0 + R[basis, basis]))
    w = so3_log(R)
    assert np.linalg.norm(w) == pytest.approx(PI, abs=1e-15)
    assert_same_rotation_vector(w, PI * axis, atol=1e-14)


@pytest.mark.parametrize("angle", [PI - 5e-8, 5e-8, PI + 5e-8, -5e-8, PI - 1e-7, 1e-7, -PI])
def test_log_near_zero_and_pi(angle):
    """test_issue43 and test_issue43_numerical_precision: angles 5e-8 and 1e-7 from 0 and from
    π, on either side, about an oblique axis; the log is the same rotation normalized into
    [0, π] (axis flipped for angles past π or below 0), axis and angle to 1e-12."""
    for axis in (unit([-1.0, 1.0, 1.0]), unit([1.0, 1.0, 1.0])):
        R = so3_exp(angle * axis)
        w = so3_log(R)
        expected = normalized_rotation_vector(axis, angle)
        assert np.linalg.norm(w) == pytest.approx(np.linalg.norm(expected), abs=1e-12)
        assert_same_rotation_vector(w, expected, atol=1e-12)
        np.testing.assert_allclose(w / np.linalg.norm(w), unit(expected), rtol=0, atol=1e-12)
        np.testing.assert_allclose(so3_exp(w), R, rtol=0, atol=1e-14)


def test_log_is_continuous_through_pi():
    """test_conversions_matrix_axis_angle_continuous: turns from 3.1 to 3.2 rad about x; past
    π the log is the shorter turn the other way."""
    for angle in np.arange(3.1, 3.2, 0.01):
        R = so3_exp([angle, 0.0, 0.0])
        check_rotation(R, tol=1e-14)
        w = so3_log(R)
        np.testing.assert_allclose(w, [float(wrap_angles(angle)), 0.0, 0.0], rtol=0, atol=1e-14)
        np.testing.assert_allclose(so3_exp(w), R, rtol=0, atol=1e-14)


def test_log_when_round_off_puts_the_cosine_above_one():
    """test_axis_angle_from_matrix_cos_angle_greater_1: the trace of a matrix 1e-8 rad from
    the identity exceeds 3 by round-off; the log is finite, the axial vector of R − Rᵀ."""
    R = np.array(
        [
            [1.0000000000000004, -1.4402617650886727e-08, 2.3816502339526408e-08],
            [1.4402617501592725e-08, 1.0000000000000004, 1.2457848566326355e-08],
            [-2.3816502529500374e-08, -1.2457848247850049e-08, 0.9999999999999999],
        ]
    )
    assert np.trace(R) > 3.0
    w = so3_log(R)
    assert np.all(np.isfinite(w))
    np.testing.assert_allclose(w, unskew(R), rtol=1e-12, atol=0)


def test_log_of_a_half_turn_with_round_off_matches_its_repaired_matrix():
    """test_bug_189: a half turn with round-off of a few ε gives the log of its nearest
    rotation."""
    R = np.array(
        [
            [-1.0000000000000004, 2.8285718503485576e-16, 1.0966597378775709e-16],
            [1.0966597378775709e-16, -2.2204460492503131e-16, 1.0000000000000002],
            [2.8285718503485576e-16, 1.0000000000000002, -2.2204460492503131e-16],
        ]
    )
    w, repaired = so3_log(R), so3_log(orthonormalize(R))
    assert_same_rotation_vector(w, repaired, atol=1e-14)
    assert_same_rotation_vector(w, PI * unit([0.0, 1.0, 1.0]), atol=1e-14)
    np.testing.assert_allclose(so3_exp(w), R, rtol=0, atol=1e-14)


def test_log_of_a_half_turn_about_a_diagonal():
    """test_bug_198: the exact half turn that swaps x and y."""
    R = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])
    w = so3_log(R)
    assert_same_rotation_vector(w, PI * unit([1.0, 1.0, 0.0]), atol=1e-14)
    np.testing.assert_allclose(so3_exp(w), R, rtol=0, atol=1e-14)


def test_the_unchecked_log_takes_what_the_checked_one_takes():
    """test_axis_angle_from_matrix_without_check: ``check=False`` skips the validation only;
    a list is still read and a wrong shape still named (not an IndexError or TypeError)."""
    R = rot_y(0.7).tolist()
    np.testing.assert_array_equal(so3_log(R, check=False), so3_log(R))
    with pytest.raises(ValueError, match=r"R must have shape \(3, 3\)"):
        so3_log(np.eye(4), check=False)
    with pytest.raises(ValueError, match=r"T must have shape \(4, 4\)"):
        se3_log(EYE3.tolist(), check=False)
    with pytest.raises(ValueError, match=r"T must have shape \(4, 4\)"):
        adjoint(EYE3, check=False)


# ------------------------------------------------------------------ test_axis_angle.py


@pytest.mark.parametrize("seed", range(5))
def test_rotation_vectors_are_normalized_by_the_log(seed):
    """test_norm_axis_angle / test_norm_compact_axis_angle / test_check_compact_axis_angle:
    log(exp(ω)) has ‖ω‖ in [0, π], is the same rotation, and ignores extra whole turns."""
    rng = np.random.default_rng(seed)
    axis = random_unit_vectors(rng, 1)[0]
    angle = rng.uniform(-20.0, -10.0 + 2.0 * PI)
    first = so3_log(so3_exp(angle * axis))
    assert 0.0 <= np.linalg.norm(first) <= PI
    assert_same_rotation_vector(first, normalized_rotation_vector(axis, angle), atol=1e-13)
    for turns in range(6):
        turned = so3_log(so3_exp((angle + 2.0 * PI * turns) * axis))
        np.testing.assert_allclose(turned, first, rtol=0, atol=1e-13)
    for basis in np.eye(3):  # half turns about the basis axes stay as they are
        assert_same_rotation_vector(so3_log(so3_exp(PI * basis)), PI * basis, atol=1e-14)


@given(arrays(float, 3, elements=st.floats(-30.0, 30.0, allow_nan=False)))
@settings(max_examples=300, deadline=None)
def test_exp_log_round_trip_at_any_length(w):
    """Any rotation vector: exp gives a rotation, and exp(log(exp(ω))) = exp(ω)."""
    R = so3_exp(w)
    check_rotation(R, tol=1e-14)
    v = so3_log(R)
    assert np.linalg.norm(v) <= PI + 1e-15
    np.testing.assert_allclose(so3_exp(v), R, rtol=0, atol=1e-14)


def test_exp_agrees_with_the_matrix_exponential_series(rng):
    """matrix_from_compact_axis_angle: Rodrigues' formula is ``expm([ω])``."""
    for w in random_unit_vectors(rng, 20) * rng.uniform(0, 3.0, (20, 1)):
        np.testing.assert_allclose(so3_exp(w), expm_series(skew(w)), rtol=0, atol=1e-14)


def test_rotation_vectors_of_a_wrong_shape_are_refused_naming_them():
    """test_check_compact_axis_angle: a 4-vector is not a rotation vector (a (3, 3) array is
    three of them: urkin's batching rule)."""
    with pytest.raises(ValueError, match=r"omega must have shape \(3,\)"):
        so3_exp(np.zeros(4))
    with pytest.raises(ValueError, match="omega must have shape"):
        so3_exp(1.0)
    assert so3_exp(np.zeros((3, 3))).shape == (3, 3, 3)


def test_absurdly_long_rotation_vectors_are_refused_not_turned_into_nan():
    """Found while porting: an angle of 1e200 rad overflowed ``‖ω‖²`` and came back as a NaN
    matrix, and beyond 1e102 rad ``θ³`` overflowed into a wrong translation.  Long vectors
    within float range give a rotation, and a screw motion whose translation along the axis
    survives (the rest, of size 1/θ, vanishes)."""
    for w in ([1e200, 0.0, 0.0], [1e155, 1e155, 0.0], [0.0, -np.finfo(float).max, 0.0]):
        with pytest.raises(ValueError, match="omega is too long to exponentiate"):
            so3_exp(w)
        with pytest.raises(ValueError, match="V is too long to exponentiate"):
            se3_exp([*w, 0.0, 0.0, 0.0])
    for length in (1e20, 1e120, 1e150):
        check_rotation(so3_exp([length, 0.0, 0.0]), tol=1e-14)
        T = se3_exp([0.0, 0.0, length, 1.0, 2.0, 3.0])
        check_transform(T, tol=1e-14)
        np.testing.assert_allclose(T[:3, 3], [0.0, 0.0, 3.0], rtol=0, atol=1e-12)


# ----------------------------------------------------------------------- test_angle.py


def test_wrap_angles_removes_whole_turns(rng):
    """test_norm_angle: any number of turns (here up to five either way) is removed."""
    wrapped = rng.uniform(-PI, PI, 100)
    for turns in np.linspace(-10.0 * PI, 10.0 * PI, 11):
        np.testing.assert_allclose(wrap_angles(wrapped + turns), wrapped, rtol=0, atol=1e-14)


def test_wrap_angles_interval_is_half_open():
    """test_norm_angle: −π and π both give π (urkin's interval is (−π, π])."""
    assert wrap_angles(-PI) == PI and wrap_angles(PI) == PI
    assert wrap_angles(3 * PI) == PI and wrap_angles(-3 * PI) == PI


def test_wrap_angles_precision():
    """test_norm_angle_precision: a fine grid of (−π, π] survives added turns to within the
    round-off of the addition itself, and the smallest angles around 0 are kept exactly."""
    grid = np.linspace(PI, -PI, num=200_000, endpoint=False)[::-1]
    for turns in np.linspace(-10.0 * PI, 10.0 * PI, 11):
        shifted = grid + turns
        bound = 2.0 * np.spacing(np.abs(shifted).max())
        assert np.abs(wrap_angles(shifted) - grid).max() <= bound
    eps, epsneg = np.finfo(float).eps, np.finfo(float).epsneg
    tiny = np.array([eps, -eps, epsneg, -epsneg])
    np.testing.assert_array_equal(wrap_angles(tiny), tiny)


def test_wrap_angles_of_huge_angles_is_exact():
    """Far beyond a few turns, removing whole turns of the rounded 2π loses ``|q| · 2⁻⁵³`` (8e-9
    rad at 1.2e8, everything at 1e17): such angles are reduced by the true π, as a 60-digit
    reference does (and within 512 turns, to the round-off of that subtraction)."""
    import mpmath

    mpmath.mp.dps = 60
    angles = [30.0, -1000.0, 123456789.0, 1e10, -4e15, 1e17, 2.0**60]
    exact = [
        float(mpmath.mpf(x) - mpmath.nint(mpmath.mpf(x) / (2 * mpmath.pi)) * 2 * mpmath.pi)
        for x in angles
    ]
    wrapped = wrap_angles(angles)
    np.testing.assert_allclose(wrapped[2:], exact[2:], rtol=0, atol=4.5e-16)
    np.testing.assert_allclose(wrapped[:2], exact[:2], rtol=0, atol=2e-13)
    assert wrap_angles(1e17) == wrap_angles([1e17])[0]
    in_place = np.array(angles)
    wrap_angles(in_place, out=in_place)  # the angles it reads are the ones it overwrites
    np.testing.assert_array_equal(in_place, wrapped)


@pytest.mark.parametrize(
    ("basis", "minus_quarter"),
    [
        (0, [[1, 0, 0], [0, 0, 1], [0, -1, 0]]),
        (1, [[0, 0, -1], [0, 1, 0], [1, 0, 0]]),
        (2, [[0, 1, 0], [-1, 0, 0], [0, 0, 1]]),
    ],
)
def test_rotations_about_the_basis_axes(basis, minus_quarter):
    """test_passive_matrix_from_angle / test_active_matrix_from_angle: quarter turns are the
    textbook matrices, urkin's rotations are active (the passive ones are their transposes),
    and they agree with the exponential of the axis."""
    rotation = AXIS_ROTATIONS[basis]
    np.testing.assert_allclose(rotation(-PI / 2), minus_quarter, rtol=0, atol=1e-14)
    np.testing.assert_allclose(rotation(PI / 2), np.transpose(minus_quarter), rtol=0, atol=1e-14)
    for angle in np.random.default_rng(21).uniform(-PI, PI, 20):
        np.testing.assert_allclose(rotation(-angle), rotation(angle).T, rtol=0, atol=0)
        np.testing.assert_allclose(rotation(angle), so3_exp(angle * EYE3[basis]), atol=1e-14)


@pytest.mark.parametrize("rotation", AXIS_ROTATIONS)
def test_basis_rotations_of_a_stack(rotation, rng):
    """test_active_matrices_from_angles_0dims/1dim/3dims: any leading shape."""
    assert rotation(0.4).shape == (3, 3)
    angles = rng.normal(size=(2, 3, 4))
    stacked = rotation(angles)
    assert stacked.shape == (2, 3, 4, 3, 3)
    for index in np.ndindex(angles.shape):
        np.testing.assert_array_equal(stacked[index], rotation(angles[index]))


def test_basis_rotations_refuse_what_is_not_an_angle():
    with pytest.raises(TypeError, match="angle must be numbers"):
        rot_x("0.5")
    with pytest.raises(ValueError, match="angle contains NaN"):
        rot_y(np.nan)


# ----------------------------------------------------------------------- test_euler.py


def test_rpy_is_the_fixed_axis_xyz_convention(rng):
    """test_general_matrix_euler_conversions (extrinsic x-y-z, pytransform3d's
    ``active_matrix_from_extrinsic_roll_pitch_yaw``): R = Rz(yaw) Ry(pitch) Rx(roll), entry by
    entry."""
    for roll, pitch, yaw in rng.uniform(-4.0, 4.0, (50, 3)):
        R = rpy_to_rotation([roll, pitch, yaw])
        np.testing.assert_allclose(R, textbook_rpy(roll, pitch, yaw), rtol=0, atol=1e-14)
        np.testing.assert_allclose(R, rot_z(yaw) @ rot_y(pitch) @ rot_x(roll), atol=1e-14)
    np.testing.assert_allclose(rpy_to_rotation([PI / 2, 0, 0]) @ [0, 1, 0], [0, 0, 1], atol=1e-14)
    np.testing.assert_allclose(rpy_to_rotation([0, PI / 2, 0]) @ [0, 0, 1], [1, 0, 0], atol=1e-14)
    np.testing.assert_allclose(rpy_to_rotation([0, 0, PI / 2]) @ [1, 0, 0], [0, 1, 0], atol=1e-14)


def test_rpy_round_trip_inside_the_ranges(rng):
    """test_general_matrix_euler_conversions / test_from_quaternion (normal case): angles in
    roll, yaw ∈ (−π, π], pitch ∈ (−π/2, π/2) come back."""
    rpy = np.column_stack(
        [rng.uniform(-PI, PI, 200), rng.uniform(-1.5, 1.5, 200), rng.uniform(-PI, PI, 200)]
    )
    np.testing.assert_allclose(rotation_to_rpy(rpy_to_rotation(rpy)), rpy, rtol=0, atol=1e-13)


def test_rpy_normalization(rng):
    """test_norm_euler: angles beyond the ranges give the in-range angles of the same matrix."""
    angles = (PI + rng.random((200, 3)) * 2.0 * PI) * np.sign(rng.standard_normal((200, 3)))
    R = rpy_to_rotation(angles)
    rpy = rotation_to_rpy(R)
    assert not np.allclose(rpy, angles)
    roll, pitch, yaw = rpy.T
    assert np.all((roll > -PI) & (roll <= PI) & (yaw > -PI) & (yaw <= PI))
    assert np.all((pitch >= -PI / 2) & (pitch <= PI / 2))
    np.testing.assert_allclose(rpy_to_rotation(rpy), R, rtol=0, atol=1e-14)


@pytest.mark.parametrize(
    "pitch", [PI / 2, -PI / 2, PI / 2 - 1e-7, PI / 2 + 1e-7, -PI / 2 + 1e-7, -PI / 2 - 1e-7]
)
def test_rpy_at_and_near_the_gimbal_lock(pitch, rng):
    """test_euler_near_gimbal_lock and the singular cases of test_from_quaternion: at
    pitch = ±π/2 only roll ∓ yaw is defined (urkin reports yaw 0); at and near it the angles
    still rebuild the matrix to round-off."""
    for roll, yaw in rng.uniform(-PI, PI, (100, 2)):
        R = rpy_to_rotation([roll, pitch, yaw])
        rpy = rotation_to_rpy(R)
        np.testing.assert_allclose(rpy_to_rotation(rpy), R, rtol=0, atol=1e-14)
        if abs(pitch) == PI / 2:
            assert rpy[2] == 0.0
            assert rpy[1] == pytest.approx(pitch, abs=1e-15)


@pytest.mark.parametrize("pitch", [0.0, PI, -PI])
def test_rpy_with_pitch_zero_and_a_half_turn(pitch, rng):
    """test_from_quaternion's "first and second singularity" (pitch 0 and π, singular for
    proper Euler angles, not for roll–pitch–yaw): the angles rebuild the matrix."""
    for roll, yaw in rng.uniform(-PI, PI, (100, 2)):
        R = rpy_to_rotation([roll, pitch, yaw])
        rpy = rotation_to_rpy(R)
        assert abs(rpy[1]) <= PI / 2
        np.testing.assert_allclose(rpy_to_rotation(rpy), R, rtol=0, atol=1e-14)


def test_rpy_of_stacks(rng):
    """test_active_matrices_from_extrinsic_euler_angles_0dims/1dim/3dims: any leading shape."""
    rpy = rng.standard_normal((2, 3, 4, 3))
    R = rpy_to_rotation(rpy)
    assert R.shape == (2, 3, 4, 3, 3)
    back = rotation_to_rpy(R)
    for index in np.ndindex(rpy.shape[:-1]):
        np.testing.assert_allclose(R[index], rpy_to_rotation(rpy[index]), rtol=0, atol=1e-14)
        np.testing.assert_allclose(back[index], rotation_to_rpy(R[index]), rtol=0, atol=1e-14)


def test_rpy_validates_its_arguments():
    """test_from_quaternion's argument checks, in urkin's terms: a 4-vector is not roll,
    pitch, yaw, and a matrix that is not a rotation has no angles."""
    with pytest.raises(ValueError, match=r"rpy must have shape \(3,\)"):
        rpy_to_rotation([0.1, 0.2, 0.3, 0.4])
    with pytest.raises(ValueError, match="R is not a rotation matrix"):
        rotation_to_rpy(np.ones((3, 3)))
    with pytest.raises(ValueError, match="R is a reflection"):
        rotation_to_rpy(-EYE3)
    with pytest.raises(ValueError, match=r"R must have shape \(3, 3\)"):
        rotation_to_rpy(np.eye(4))


# --------------------------------------------------- test_rot_log.py, batch cross products


def test_skew_is_the_cross_product_matrix(rng):
    """test_cross_product_matrix / test_check_skew_symmetric_matrix: ``[v] w = v × w`` and
    ``[v]ᵀ = −[v]``; unskew inverts it."""
    for v, w in rng.normal(size=(5, 2, 3)):
        V = skew(v)
        np.testing.assert_array_equal(V.T, -V)
        np.testing.assert_allclose(V @ w, np.cross(v, w), rtol=0, atol=1e-14)
        np.testing.assert_array_equal(unskew(V), v)


def test_skew_of_stacks(rng):
    """test_cross_product_matrices (batch): a (2, 2, 3) stack of vectors."""
    v = rng.standard_normal((2, 2, 3))
    V = skew(v)
    assert V.shape == (2, 2, 3, 3)
    for index in np.ndindex(v.shape[:-1]):
        np.testing.assert_array_equal(V[index], skew(v[index]))
    np.testing.assert_array_equal(unskew(V), v)


def test_skew_shapes_are_checked_naming_the_argument():
    """test_check_skew_symmetric_matrix's shape cases; urkin's unskew reads the antisymmetric
    part and does not refuse a matrix that is not skew-symmetric (a documented difference)."""
    for bad in ([], np.zeros(2), np.zeros(4)):
        with pytest.raises(ValueError, match=r"w must have shape \(3,\)"):
            skew(bad)
    for bad in (np.zeros((3, 4)), np.zeros((4, 3)), np.zeros(3)):
        with pytest.raises(ValueError, match=r"W must have shape \(3, 3\)"):
            unskew(bad)
    np.testing.assert_array_equal(unskew(skew([1.0, 2.0, 3.0]) + np.eye(3)), [1.0, 2.0, 3.0])


# ------------------------------------------------------------- test_batch_rotations.py


def test_exp_and_log_of_stacks(rng):
    """test_axis_angles_from_matrices(_0dims, _norot): stacks of rotation vectors, one of
    them zero, and stacks of identities."""
    w = random_unit_vectors(rng, 6).reshape(2, 3, 3) * rng.uniform(0, PI, (2, 3, 1))
    w[0, 0] = 0.0
    R = so3_exp(w)
    assert R.shape == (2, 3, 3, 3)
    np.testing.assert_allclose(so3_log(R), w, rtol=0, atol=1e-13)
    for index in np.ndindex(w.shape[:-1]):
        np.testing.assert_allclose(R[index], so3_exp(w[index]), rtol=0, atol=1e-14)
    np.testing.assert_array_equal(so3_log(np.broadcast_to(EYE3, (2, 2, 3, 3))), np.zeros((2, 2, 3)))


def test_log_of_a_stack_mixing_identity_half_turns_and_the_rest(rng):
    """A stack whose rows need different branches (θ = 0, θ = π, general) gives each row the
    answer it gets alone."""
    R = np.stack([EYE3, rot_x(PI), so3_exp(PI * unit([1, 2, 3])), rot_z(1e-9), rot_y(2.0)])
    stacked = so3_log(R)
    for row, Ri in zip(stacked, R):
        np.testing.assert_allclose(row, so3_log(Ri), rtol=0, atol=1e-14)


# ------------------------------------------------ test_rotations_random.py and friends


def test_random_rotations_are_seeded_rotations():
    """test_random_matrices (without mean and covariance, which urkin has no use for)."""
    a, b = random_rotations((4, 5), seed=33), random_rotations((4, 5), seed=33)
    np.testing.assert_array_equal(a, b)
    assert a.shape == (4, 5, 3, 3)
    assert not np.allclose(a, random_rotations((4, 5), seed=34))
    check_rotation(a, tol=1e-14)
    assert random_rotations(seed=1).shape == (3, 3)
    assert random_rotations(np.int64(2)).shape == (2, 3, 3)
    assert random_rotations(0).shape == (0, 3, 3)


def test_random_rotations_are_uniform():
    """Haar measure: the mean matrix is 0 and the angle θ has distribution (θ − sin θ)/π."""
    R = random_rotations(20_000, seed=5)
    assert np.abs(R.mean(axis=0)).max() < 0.02
    angles = rotation_angle(R)
    for x in (0.5, 1.0, 1.5, 2.0, 2.5, 3.0):
        assert abs(np.mean(angles <= x) - (x - np.sin(x)) / PI) < 0.015


def test_random_poses_are_seeded_and_rigid():
    """test_transformations_random: random poses are valid transforms, within their cube."""
    T = random_transforms(100, seed=7, radius=0.5)
    np.testing.assert_array_equal(T, random_transforms(100, seed=7, radius=0.5))
    check_transform(T, tol=1e-14)
    assert np.abs(T[:, :3, 3]).max() <= 0.5
    np.testing.assert_array_equal(random_transforms(3, seed=1, radius=0.0)[:, :3, 3], 0.0)


@pytest.mark.parametrize(
    ("call", "error", "message"),
    [
        (lambda: random_rotations(2.5), TypeError, "shape must be an int or a tuple of ints"),
        (lambda: random_rotations((2, "3")), TypeError, "shape must be an int"),
        (lambda: random_rotations(-1), ValueError, "shape must not be negative"),
        (lambda: random_rotations(2, seed="a"), TypeError, "seed must be an int"),
        (lambda: random_rotations(2, seed=-1), ValueError, "seed must be an int ≥ 0"),
        (lambda: random_transforms(2, radius=-1.0), ValueError, "radius must be one number ≥ 0"),
        (lambda: random_transforms(2, radius=np.nan), ValueError, "radius contains NaN"),
        (lambda: random_transforms(2, radius="1"), TypeError, "radius must be numbers"),
    ],
)
def test_random_samplers_name_a_bad_argument(call, error, message):
    with pytest.raises(error, match=message):
        call()


# ------------------------------------------------------------------ test_transform.py


def test_check_transform_returns_float_arrays(rng):
    """test_check_transform: an int identity comes back as float64; a random pose unchanged."""
    T = check_transform(np.eye(4, dtype=int))
    assert type(T) is np.ndarray and T.dtype == np.float64
    np.testing.assert_array_equal(T, np.eye(4))
    T = random_transforms(seed=rng)
    np.testing.assert_array_equal(check_transform(T), T)
    np.testing.assert_array_equal(check_transform(T.tolist()), T)


@pytest.mark.parametrize(
    ("T", "message"),
    [
        (np.eye(3), r"T must have shape \(4, 4\)"),
        (np.ones(4), r"T must have shape \(4, 4\)"),
        (make_transform([[1, 1, 1], [0, 0, 0], [2, 2, 2]]), "the rotation part of T is not a"),
        (make_transform(np.diag([1.0, 1.0, -1.0])), "the rotation part of T is a reflection"),
        (np.eye(4) + 0.1 * np.eye(4, k=-3), r"end in the row \[0, 0, 0, 1\]; got \[0.1 0. "),
        (np.diag([2.0, 1.0, 1.0, 1.0]) + 3.0 * np.eye(4, k=-3), r"end in the row \[0, 0, 0, 1"),
        (np.eye(4) + 1e-6, "not a rotation"),
        (np.zeros((4, 4)), r"end in the row \[0, 0, 0, 1"),
    ],
)
def test_check_transform_refuses_what_is_not_rigid(T, message):
    """test_check_transform, test_deactivate_transform_precision_error,
    test_transform_requires_renormalization, test_translate/rotate_transform_with_check."""
    with pytest.raises(ValueError, match=message):
        check_transform(T)


def test_check_transform_message_reads_well():
    """The rotation part's message names it and writes its Gram error with a short symbol."""
    with pytest.raises(ValueError, match=r"\(max \|RᵀR − I\| = 5, tolerance 1e-06\)"):
        check_transform(make_transform([[1, 1, 1], [0, 0, 0], [2, 2, 2]]))


ALMOST_IDENTITY = np.array(
    [
        [0.9999999999999999, -1.5883146449068575e-16, 4.8699079321578667e-17, -7.54265065748827e-5],
        [5.110044286978025e-17, 0.9999999999999999, 1.1798895336935056e-17, 9.340523179823812e-5],
        [3.0048299647976294e-18, 5.4741890703482423e-17, 1.0, -7.803584869947588e-5],
        [0.0, 0.0, 0.0, 1.0],
    ]
)


def test_log_of_an_almost_identity_pose():
    """test_exponential_coordinates_from_almost_identity_transform and
    test_transform_log_from_almost_identity_transform: rotation round-off of 1e-16 and a
    translation of 1e-4 m give ω ≈ 0 and v = p."""
    V = se3_log(ALMOST_IDENTITY)
    assert np.abs(V[:3]).max() < 1e-15
    np.testing.assert_allclose(V[3:], ALMOST_IDENTITY[:3, 3], rtol=1e-12, atol=0)
    np.testing.assert_allclose(twist_matrix(V), np.zeros((4, 4)), rtol=0, atol=1e-4)
    np.testing.assert_allclose(se3_exp(V), ALMOST_IDENTITY, rtol=0, atol=1e-14)


def test_unchecked_log_and_adjoint_apply_the_formula():
    """test_exponential_coordinates_from_transform_without_check and
    test_adjoint_from_transform_without_check: with ``check=False`` a matrix of ones is not
    refused; the formulas read its blocks (R = ones has no antisymmetric part, p = (1, 1, 1))."""
    ones = np.ones((4, 4))
    np.testing.assert_array_equal(se3_log(ones, check=False), [0, 0, 0, 1, 1, 1])
    Ad = adjoint(ones, check=False)
    np.testing.assert_array_equal(Ad[:3, :3], np.ones((3, 3)))
    np.testing.assert_array_equal(Ad[3:, 3:], np.ones((3, 3)))
    np.testing.assert_allclose(Ad[3:, :3], np.zeros((3, 3)), rtol=0, atol=0)  # [p] @ ones = 0
    np.testing.assert_array_equal(Ad[:3, 3:], np.zeros((3, 3)))
    with pytest.raises(ValueError, match="T must end in the row"):
        se3_log(ones)


def test_adjoint_maps_twists_between_frames(rng):
    """test_adjoint_of_transformation: ``[Ad_T V] = T [V] T⁻¹`` for screw axes times rates,
    and the adjoint of a product is the product of adjoints."""
    for _ in range(10):
        T = random_transforms(seed=rng)
        S = np.r_[random_unit_vectors(rng, 1)[0], rng.normal(size=3)]
        V = S * 3.0 * rng.random()
        np.testing.assert_allclose(
            twist_matrix(adjoint(T) @ V), T @ twist_matrix(V) @ inv_transform(T), atol=1e-14
        )
        T2 = random_transforms(seed=rng)
        np.testing.assert_allclose(adjoint(T @ T2), adjoint(T) @ adjoint(T2), atol=1e-14)
        np.testing.assert_allclose(adjoint(inv_transform(T)), np.linalg.inv(adjoint(T)), atol=1e-13)
        np.testing.assert_allclose(
            se3_exp(adjoint(T) @ V), T @ se3_exp(V) @ inv_transform(T), rtol=0, atol=1e-13
        )


def test_adjoint_has_rotation_blocks_and_is_batched(rng):
    T = random_transforms((2, 3), seed=rng)
    Ad = adjoint(T)
    assert Ad.shape == (2, 3, 6, 6)
    np.testing.assert_array_equal(Ad[..., :3, :3], T[..., :3, :3])
    np.testing.assert_array_equal(Ad[..., 3:, 3:], T[..., :3, :3])
    np.testing.assert_array_equal(Ad[..., :3, 3:], 0.0)
    np.testing.assert_allclose(Ad[..., 3:, :3], skew(T[..., :3, 3]) @ T[..., :3, :3], atol=1e-14)


# ------------------------------------------------------ test_transform_operations.py


def test_inverse_transform(rng):
    """test_invert_transform: the inverse is the matrix inverse, also for stacks."""
    for _ in range(5):
        R = so3_exp(random_unit_vectors(rng, 1)[0] * rng.uniform(0, PI))
        T = make_transform(R, rng.normal(size=3))
        np.testing.assert_allclose(np.linalg.inv(inv_transform(T)), T, rtol=0, atol=1e-14)
        np.testing.assert_allclose(inv_transform(inv_transform(T)), T, rtol=0, atol=1e-14)
    T = random_transforms((3, 4), seed=rng)
    identities = np.broadcast_to(np.eye(4), T.shape)
    np.testing.assert_allclose(inv_transform(T) @ T, identities, rtol=0, atol=1e-14)


def test_inverse_refuses_what_is_not_rigid(rng):
    """test_invert_transform_without_check: urkin's inverse always validates (there is no
    rigid-body inverse of a general matrix), and says what is wrong."""
    A = rng.standard_normal((4, 4))
    with pytest.raises(ValueError, match=r"T must end in the row \[0, 0, 0, 1\]"):
        inv_transform(A + A.T)
    with pytest.raises(ValueError, match="the rotation part of T is not a rotation"):
        inv_transform(make_transform(2.0 * EYE3))
    with pytest.raises(ValueError, match=r"T must have shape \(4, 4\)"):
        inv_transform(EYE3)


def test_concatenation(rng):
    """test_concat: ``T_a_c = T_a_b @ T_b_c`` is rigid, a point goes there and back, and
    ``T_c_a = T_c_b @ T_b_a``."""
    for _ in range(5):
        T_a_b, T_b_c = random_transforms(2, seed=rng)
        T_a_c = T_a_b @ T_b_c
        check_transform(T_a_c, tol=1e-14)
        p_c = np.array([0.3, -0.2, 0.9, 1.0])
        p_a = T_a_c @ p_c
        np.testing.assert_allclose(inv_transform(T_a_c) @ p_a, p_c, rtol=0, atol=1e-14)
        T_c_a = inv_transform(T_b_c) @ inv_transform(T_a_b)
        np.testing.assert_allclose(T_c_a @ p_a, p_c, rtol=0, atol=1e-14)
        np.testing.assert_allclose(T_c_a, inv_transform(T_a_c), rtol=0, atol=1e-14)


def test_make_transform_shapes_are_checked_naming_the_argument():
    with pytest.raises(ValueError, match=r"R must have shape \(3, 3\)"):
        make_transform(np.eye(4))
    with pytest.raises(ValueError, match=r"p must have shape \(3,\)"):
        make_transform(p=[1.0, 2.0])
    with pytest.raises(ValueError, match="R and p must be stacks of the same length"):
        make_transform(np.broadcast_to(EYE3, (2, 3, 3)), np.zeros((3, 3)))


# ----------------------------------------------------------------------- test_screws.py


@pytest.mark.parametrize(
    ("T", "V"),
    [
        (np.eye(4), [0, 0, 0, 0, 0, 0]),
        (make_transform(p=[1.0, 5.0, 0.0]), [0, 0, 0, 1, 5, 0]),
        (make_transform(rot_z(PI / 2)), [0, 0, PI / 2, 0, 0, 0]),
    ],
)
def test_exponential_coordinates_of_known_poses(T, V):
    """test_conversions_between_exponential_coordinates_and_transform: fixed cases."""
    np.testing.assert_allclose(se3_log(T), V, rtol=0, atol=1e-14)
    np.testing.assert_allclose(se3_exp(V), T, rtol=0, atol=1e-14)


def test_exponential_coordinates_round_trip_random_poses(rng):
    """test_conversions_between_exponential_coordinates_and_transform: random poses."""
    T = random_transforms(500, seed=rng, radius=3.0)
    V = se3_log(T)
    assert np.all(np.linalg.norm(V[:, :3], axis=1) <= PI)
    np.testing.assert_allclose(se3_exp(V), T, rtol=0, atol=1e-14)


def test_exp_is_the_matrix_exponential_of_the_twist_matrix(rng):
    """test_conversions_between_transform_and_transform_log: ``exp([V])`` as a series."""
    for V in rng.normal(size=(20, 6)):
        np.testing.assert_allclose(se3_exp(V), expm_series(twist_matrix(V)), rtol=0, atol=1e-13)


@pytest.mark.parametrize("angle", [1e-7, 1e-6, 1.0001e-6, 2e-6, 1e-5, 1e-4, 3e-4, 1e-3, 1e-2])
def test_exp_and_log_are_accurate_at_small_angles(angle, rng):
    """Found while porting: ``se3_exp`` lost ε/θ (1.7e-10 m at θ = 1e-6) to ``1 − cos θ``,
    and ``se3_log`` ε/θ² (1.3e-8 at θ = 1e-4); both now match the series to round-off."""
    for axis, v in zip(random_unit_vectors(rng, 20), rng.normal(size=(20, 3))):
        V = np.r_[angle * axis, v]
        reference = expm_series(twist_matrix(V))
        np.testing.assert_allclose(se3_exp(V), reference, rtol=0, atol=1e-14)
        np.testing.assert_allclose(se3_log(reference), V, rtol=0, atol=1e-14)


@pytest.mark.parametrize("gap", [0.0, 1e-12, 1e-9, 1e-7, 1e-5])
def test_exponential_coordinates_at_and_near_pi(gap, rng):
    """The log at θ = π (and just below): ‖ω‖ = θ, and exp gives the pose back."""
    for axis, v in zip(random_unit_vectors(rng, 50), rng.normal(size=(50, 3))):
        T = se3_exp(np.r_[(PI - gap) * axis, v])
        V = se3_log(T)
        assert np.linalg.norm(V[:3]) == pytest.approx(PI - gap, abs=1e-12)
        np.testing.assert_allclose(se3_exp(V), T, rtol=0, atol=1e-14)


def test_exponential_coordinates_are_normalized(rng):
    """test_norm_exponential_coordinates: a pure translation stays; coordinates with ‖ω‖ > π
    come back with ‖ω‖ ≤ π and the same pose."""
    translation = np.array([0.0, 0.0, 0.0, 100.0, 25.0, -23.0])
    np.testing.assert_allclose(se3_log(se3_exp(translation)), translation, rtol=0, atol=0)
    for _ in range(10):
        V = rng.standard_normal(6)
        i = rng.integers(0, 3)
        V[i] = np.sign(V[i]) * (PI + rng.random())
        W = se3_log(se3_exp(V))
        assert not np.all(W == V)
        assert np.linalg.norm(W[:3]) <= PI
        np.testing.assert_allclose(W[:3], so3_log(so3_exp(V[:3])), rtol=0, atol=1e-14)
        np.testing.assert_allclose(se3_exp(W), se3_exp(V), rtol=0, atol=1e-14)


def test_half_turn_screws_with_opposite_axis_and_pitch_are_the_same_motion(rng):
    """test_norm_exponential_coordinates (180° ambiguity): the screw (q, s, h) and (q, −s, −h)
    turned by π give the same pose, and the same log up to the sign of ω."""
    for _ in range(10):
        q = rng.standard_normal(3)
        s = random_unit_vectors(rng, 1)[0]
        h = rng.standard_normal()
        S1 = np.r_[s, np.cross(q, s) + h * s] * PI
        S2 = np.r_[-s, np.cross(q, -s) + (-h) * (-s)] * PI
        np.testing.assert_allclose(se3_exp(S1), se3_exp(S2), rtol=0, atol=1e-14)
        W1, W2 = se3_log(se3_exp(S1)), se3_log(se3_exp(S2))
        assert_same_rotation_vector(W1[:3], W2[:3], atol=1e-12)
        np.testing.assert_allclose(se3_exp(W1), se3_exp(S1), rtol=0, atol=1e-14)


def test_twist_matrix_and_vector(rng):
    """test_conversions_between_screw_matrix_and_screw_axis,
    ..._exponential_coordinates_and_transform_log, ..._screw_matrix_and_transform_log:
    exact round trips, linear in θ, with an se(3) bottom row of zeros."""
    for V in rng.standard_normal((10, 6)):
        M = twist_matrix(V)
        np.testing.assert_array_equal(M[3], 0.0)
        np.testing.assert_array_equal(M[:3, :3], skew(V[:3]))
        np.testing.assert_array_equal(twist_vector(M), V)
        theta = rng.random()
        np.testing.assert_allclose(twist_matrix(V * theta), M * theta, rtol=1e-15, atol=0)
    stack = rng.standard_normal((2, 3, 6))
    np.testing.assert_array_equal(twist_vector(twist_matrix(stack)), stack)


def test_twist_shapes_are_checked_naming_the_argument():
    """test_check_exponential_coordinates, test_check_screw_matrix (shapes),
    test_transform_from_exponential_coordinates_without_check: a 7-vector is refused with a
    ValueError naming V (pytransform3d's unchecked path fails in a numpy broadcast)."""
    for bad in ([0.0], np.zeros(7)):
        with pytest.raises(ValueError, match=r"V must have shape \(6,\)"):
            se3_exp(bad)
        with pytest.raises(ValueError, match=r"V must have shape \(6,\)"):
            twist_matrix(bad)
    for bad in (np.zeros((3, 4)), np.zeros((4, 3))):
        with pytest.raises(ValueError, match=r"M must have shape \(4, 4\)"):
            twist_vector(bad)
        with pytest.raises(ValueError, match=r"T must have shape \(4, 4\)"):
            se3_log(bad)
    assert se3_log(np.eye(4)[None]).shape == (1, 6)


def test_revolute_screw_axes(rng):
    """test_conversions_between_screw_axis_and_parameters, for pitch 0 (urkin's joints are
    revolute): S = (s, q × s), whatever point q of the axis is given."""
    for _ in range(10):
        s = random_unit_vectors(rng, 1)[0]
        q = rng.standard_normal(3)
        S = poe.screw_axis(s, q)
        np.testing.assert_allclose(S, np.r_[s, np.cross(q, s)], rtol=0, atol=1e-14)
        np.testing.assert_allclose(poe.screw_axis(s, q + 4.3 * s), S, rtol=0, atol=1e-14)
        # turning by θ about it moves q nowhere
        T = se3_exp(S * rng.uniform(-PI, PI))
        np.testing.assert_allclose(T[:3, :3] @ q + T[:3, 3], q, rtol=0, atol=1e-14)
    with pytest.raises(ValueError, match=r"omega must have shape \(3,\)"):
        poe.screw_axis([0.0, 1.0], [0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match=r"point must have shape \(3,\)"):
        poe.screw_axis([0.0, 0.0, 1.0], [0.0])
