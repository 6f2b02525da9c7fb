"""Rotations and rigid-body transforms: SO(3) and SE(3) as numpy arrays.

Conventions
    * Rotations are 3×3 arrays, homogeneous transforms 4×4 arrays; every function also accepts
      a stack ``(..., 3, 3)`` or ``(..., 4, 4)`` and works on all of them at once.
    * Rotation vectors (exponential coordinates) ``ω = θ k``: unit axis ``k`` times angle ``θ``
      in radians.
    * Roll–pitch–yaw ``(r, p, y)`` are fixed-axis X–Y–Z angles: ``R = Rz(y) @ Ry(p) @ Rx(r)``.
    * Twists and screw axes are 6-vectors ``(ω, v)``, angular part first, as in Lynch and Park's
      *Modern Robotics*; adjoint matrices act on them in that order.
    * Names carry frames: ``T_a_b`` is the pose of frame ``b`` in frame ``a``, so
      ``T_a_c = T_a_b @ T_b_c``.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from urkin._inputs import flag, generator, real, sample_shape, shape_text

__all__ = [
    "adjoint",
    "check_rotation",
    "check_transform",
    "inv_transform",
    "make_transform",
    "orthonormalize",
    "pose_error",
    "random_rotations",
    "random_transforms",
    "rot_x",
    "rot_y",
    "rot_z",
    "rotation_angle",
    "rotation_parts",
    "rotation_to_rpy",
    "rpy_to_rotation",
    "se3_exp",
    "se3_log",
    "skew",
    "so3_exp",
    "so3_log",
    "twist_matrix",
    "twist_vector",
    "unskew",
    "wrap_angles",
]

#: Default tolerance of :func:`check_rotation` on ``‖RᵀR − I‖`` and ``|det R − 1|``.
ROTATION_TOLERANCE = 1e-6

#: Largest entry of a rotation vector :func:`so3_exp` and :func:`se3_exp` take: beyond about
#: 1e154, ``‖ω‖²`` and ``[ω]²`` overflow (and such an angle has no meaning left in float64).
LONGEST_ROTATION_VECTOR = 1e150


def _core(x: ArrayLike, core: tuple[int, ...], name: str) -> np.ndarray:
    """``x`` as a float array of shape ``(..., *core)``, or an error naming it."""
    array = real(x, name)
    if array.ndim < len(core) or array.shape[array.ndim - len(core) :] != core:
        raise ValueError(f"{name} must have shape {shape_text(core)}; got {array.shape}")
    return array


def _vector3(x: ArrayLike, name: str) -> np.ndarray:
    return _core(x, (3,), name)


def _unchecked(x: ArrayLike, core: tuple[int, ...], name: str) -> np.ndarray:
    """``x`` as an array of shape ``(..., *core)`` without the value checks (``check=False``):
    a list is still accepted and a wrong shape still named, which costs next to nothing."""
    array = np.asarray(x)
    if array.ndim < len(core) or array.shape[array.ndim - len(core) :] != core:
        raise ValueError(f"{name} must have shape {shape_text(core)}; got {array.shape}")
    return array


def _checking(check: bool) -> bool:
    """The ``check=`` flag as a bool (False at no cost), or a TypeError naming it."""
    return check is not False and flag(check, "check")


def _tolerance(tol: float) -> float:
    """``tol`` as a float that is finite and ≥ 0, or an error naming it."""
    if type(tol) is float and 0.0 <= tol < math.inf:
        return tol  # the common case, at no cost
    value = real(tol, "tol")
    if value.ndim != 0 or value < 0.0:
        raise ValueError(f"tol must be one number ≥ 0; got {tol!r}")
    return float(value)


def _is_transform_one(rows: list[list[float]], tol: float) -> bool:
    """Whether ``rows`` (a 4×4 pose as lists of floats) is rigid within ``tol``, finite."""
    x, y, z, w = rows[3]
    return (
        abs(x) <= tol
        and abs(y) <= tol
        and abs(z) <= tol
        and abs(w - 1.0) <= tol
        and math.isfinite(rows[0][3] + rows[1][3] + rows[2][3])
        and _is_rotation_one(rows, tol)
    )


def _is_rotation_one(rows: list[list[float]], tol: float) -> bool:
    """Whether the upper-left 3×3 block of ``rows`` (lists of floats) is a rotation within
    ``tol``; False for NaN or infinite entries too (every entry reaches the determinant)."""
    (a, b, c, *_), (d, e, f, *_), (g, h, i, *_) = rows[0], rows[1], rows[2]
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    return (
        abs(det - 1.0) <= tol
        and abs(a * a + d * d + g * g - 1.0) <= tol
        and abs(b * b + e * e + h * h - 1.0) <= tol
        and abs(c * c + f * f + i * i - 1.0) <= tol
        and abs(a * b + d * e + g * h) <= tol
        and abs(a * c + d * f + g * i) <= tol
        and abs(b * c + e * f + h * i) <= tol
    )


def check_rotation(R: ArrayLike, tol: float = ROTATION_TOLERANCE, name: str = "R") -> np.ndarray:
    """Validate one rotation matrix or a stack of them and return it as a float array.

    Parameters
    ----------
    R : array_like, shape (3, 3) or (..., 3, 3)
        Candidate rotation matrices.
    tol : float
        Largest accepted ``max |RᵀR − I|`` and ``|det R − 1|``.
    name : str
        Name used in error messages.

    Returns
    -------
    ndarray
        ``R`` as a float array: ``R`` itself (not a copy) when it already is one, as
        :func:`numpy.asarray` gives it.

    Raises
    ------
    ValueError
        If the shape is wrong, an entry is not finite, the columns are not orthonormal or the
        matrix is a reflection (``det R = −1``), or ``tol`` is negative or not finite.

    Examples
    --------
    >>> check_rotation(rot_z(0.3)).shape
    (3, 3)
    >>> check_rotation(np.diag([1.0, 1.0, -1.0]))
    Traceback (most recent call last):
    ...
    ValueError: R is a reflection, not a rotation: det(R) = -1
    """
    tol = _tolerance(tol)
    if type(R) is np.ndarray and R.shape == (3, 3) and R.dtype == np.float64:
        if _is_rotation_one(R.tolist(), tol):
            return R  # the scalar fast path; anything else gets the full check's message
    array = _core(R, (3, 3), name)
    _rotation_deviation(array, tol, name)
    return array


#: From this many matrices on, :func:`_rotation_deviation` first copies them into contiguous rows.
_CONTIGUOUS = 64


def _rotation_deviation(array: np.ndarray, tol: float, name: str) -> np.ndarray:
    """Each matrix's largest deviation from a rotation, ``max(|RᵀR − I|, |det R − 1|)``
    (shape ``array.shape[:-2]``), after the errors of :func:`check_rotation` for a reflection
    or a deviation beyond ``tol``.  Column by column: cheaper than a batched matmul and LU for
    stacks of small matrices."""
    if array.ndim > 2 and array.size >= 9 * _CONTIGUOUS:
        # a large stack: its entries as contiguous rows, since strided views cost each of the
        # forty operations below about twice as much
        entries = np.ascontiguousarray(np.moveaxis(array, (-2, -1), (0, 1)))
    else:
        entries = np.moveaxis(array, (-2, -1), (0, 1))
    # the three columns, each as its three components
    x, y, z = ([entries[i, j, ...] for i in range(3)] for j in range(3))

    def dot(u, v):
        return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]

    gram = np.abs(dot(x, x) - 1.0)
    for d in (dot(y, y) - 1.0, dot(z, z) - 1.0, dot(x, y), dot(x, z), dot(y, z)):
        gram = np.maximum(gram, np.abs(d))
    det = (
        x[0] * (y[1] * z[2] - y[2] * z[1])
        - x[1] * (y[0] * z[2] - y[2] * z[0])
        + x[2] * (y[0] * z[1] - y[1] * z[0])
    )
    if np.any(det < 0):
        raise ValueError(f"{name} is a reflection, not a rotation: det({name}) = -1")
    gram_error = float(gram.max(initial=0.0))
    det_error = float(np.abs(det - 1.0).max(initial=0.0))
    if gram_error > tol or det_error > tol:
        symbol = name if str(name).isidentifier() else "R"  # "the rotation part of T" reads as R
        if gram_error > tol:
            what = f"its columns are not orthonormal (max |{symbol}ᵀ{symbol} − I| = "
            error = gram_error
        else:
            what, error = f"its determinant is not 1 (|det {symbol} − 1| = ", det_error
        raise ValueError(f"{name} is not a rotation matrix: {what}{_above(error, tol)})")
    return np.maximum(gram, np.abs(det - 1.0))


def _above(value: float, tol: float) -> str:
    """``value``, and the tolerance ``tol`` it exceeds, with the digits that tell them apart."""
    for digits in range(3, 18):
        shown = f"{value:.{digits}g}"
        if shown != f"{tol:.{digits}g}":
            break
    return f"{shown}, tolerance {tol:g}"


def check_transform(T: ArrayLike, tol: float = ROTATION_TOLERANCE, name: str = "T") -> np.ndarray:
    """Validate one homogeneous transform or a stack of them and return it as a float array.

    Parameters
    ----------
    T : array_like, shape (4, 4) or (..., 4, 4)
        Candidate rigid-body transforms.
    tol : float
        Tolerance of the rotation test and of the bottom row ``[0, 0, 0, 1]``.
    name : str
        Name used in error messages.

    Returns
    -------
    ndarray
        ``T`` as a float array: ``T`` itself (not a copy) when it already is one, as
        :func:`numpy.asarray` gives it.

    Raises
    ------
    ValueError
        If the shape is wrong, an entry is not finite, the bottom row is not ``[0, 0, 0, 1]``
        or the upper-left block is not a rotation, or ``tol`` is negative or not finite.

    Examples
    --------
    >>> check_transform(np.eye(4)).shape
    (4, 4)
    >>> check_transform(np.zeros((4, 4)))
    Traceback (most recent call last):
    ...
    ValueError: T must end in the row [0, 0, 0, 1]; got [0. 0. 0. 0.]
    """
    return _checked_transform(T, tol, name)[0]


#: Up to this many poses, a stack is checked pose by pose on Python floats (fewer operations
#: than the array test's forty).
_FEW_POSES = 16

_BOTTOM = np.array([0.0, 0.0, 0.0, 1.0])
_BOTTOM.setflags(write=False)


def _checked_transform(T: ArrayLike, tol: float, name: str) -> tuple[np.ndarray, np.ndarray | None]:
    """:func:`check_transform`, and each pose's deviation from a rotation
    (:func:`_rotation_deviation`) where the full check measured it; None where the scalar fast
    path accepted the poses."""
    tol = _tolerance(tol)
    if type(T) is np.ndarray and T.dtype == np.float64 and T.shape[-2:] == (4, 4):
        # the scalar fast path, for one pose or a few; anything else gets the full check
        if T.ndim == 2 and _is_transform_one(T.tolist(), tol):
            return T, None
        if T.ndim == 3 and len(T) <= _FEW_POSES:
            if all(_is_transform_one(t, tol) for t in T.tolist()):
                return T, None
    array = _core(T, (4, 4), name)
    bottom = array[..., 3, :]
    if np.abs(bottom - _BOTTOM).max(initial=0.0) > tol:  # one pass; the row-wise one to name it
        bad = np.abs(bottom - _BOTTOM).max(axis=-1) > tol
        first = bottom[bad][0] if bottom.ndim > 1 else bottom
        raise ValueError(f"{name} must end in the row [0, 0, 0, 1]; got {first}")
    rotation = array[..., :3, :3]
    return array, _rotation_deviation(rotation, tol, f"the rotation part of {name}")


#: Singular values below this fraction of the largest count as zero in :func:`orthonormalize`.
_RANK_TOLERANCE = 1e-12


def orthonormalize(R: ArrayLike) -> np.ndarray:
    """The rotation nearest to ``R`` (Frobenius norm): ``U Vᵀ`` of the SVD ``R = U Σ Vᵀ``.

    For a matrix copied with a few decimals, or accumulated through many products, that is a
    rotation again to round-off.

    Parameters
    ----------
    R : array_like, shape (..., 3, 3)
        Matrices close to rotations.  A reflection (det < 0) is refused, and so is a matrix of
        rank 0 or 1, which many rotations are equally near; of rank 2, the nearest rotation is
        unique.

    Returns
    -------
    ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> R = np.round(rot_z(0.3), 4)  # four decimals: 1e-5 from orthonormal
    >>> bool(np.abs(orthonormalize(R) - rot_z(0.3)).max() < 1e-4)
    True
    >>> check_rotation(orthonormalize(R), tol=1e-14).shape
    (3, 3)
    """
    M = _core(R, (3, 3), "R")
    U, S, Vt = np.linalg.svd(M)
    tiny = _RANK_TOLERANCE * S[..., 0]
    if np.any(S[..., 1] + S[..., 2] <= tiny):  # zero or rank 1: every rotation about an axis ties
        raise ValueError(
            "R has no nearest rotation: it is zero or of rank 1 (its second and third singular "
            "values are 0), so many rotations are equally near"
        )
    sign = np.linalg.det(U) * np.linalg.det(Vt)  # of det R, unless its third singular value is 0
    if np.any((sign < 0) & (S[..., 2] > tiny)):
        raise ValueError("R is closer to a reflection than to a rotation (det R < 0)")
    # rank 2 (det R = 0): the nearest rotation turns the null direction whichever way makes
    # det = +1 (the SVD's sign for it is arbitrary)
    U = U.copy()
    U[..., :, 2] *= sign[..., None]
    return U @ Vt


def _exp_coefficients(omega: np.ndarray, name: str, *, translation: bool = False) -> tuple:
    """``sin θ / θ`` and ``(1 − cos θ) / θ²`` of ``θ = ‖ω‖`` (shapes ``(..., 1, 1)``), and
    ``(θ − sin θ) / θ³`` too for ``translation``, accurate at every angle; or an error naming
    ``name`` if an entry of ``ω`` is larger in magnitude than :data:`LONGEST_ROTATION_VECTOR`.

    ``(1 − cos θ) / θ²`` is computed as ``½ (sin(θ/2) / (θ/2))²``: ``1 − cos θ`` itself keeps
    only ``ε/θ²`` of relative precision, which ``se3_exp`` multiplies by ``[ω] v`` (size ``θ``)
    into errors of ``ε/θ``, 1e-10 m at ``θ = 1e-6``.
    """
    if not np.abs(omega).max(initial=0.0) <= LONGEST_ROTATION_VECTOR:  # before ‖ω‖² overflows
        raise ValueError(
            f"{name} is too long to exponentiate: its rotation vector has an entry beyond "
            f"±{LONGEST_ROTATION_VECTOR:g} rad"
        )
    theta = np.linalg.norm(omega, axis=-1)[..., None, None]
    small = theta < 1e-6
    safe = np.where(small, 1.0, theta)
    half = 0.5 * safe
    # the Taylor series near 0, where the closed forms divide 0 by 0
    a = np.where(small, 1.0 - theta**2 / 6.0, np.sin(safe) / safe)
    b = np.where(small, 0.5 - theta**2 / 24.0, 0.5 * (np.sin(half) / half) ** 2)
    if not translation:
        return a, b
    # (θ − sin θ) / θ³ as (1 − sin θ / θ) / θ², as accurate (ε/θ² either way) without θ³,
    # which overflowed beyond θ = 1e102 into c = 0 and a wrong translation
    c = np.where(small, 1.0 / 6.0 - theta**2 / 120.0, (1.0 - a) / safe**2)
    return a, b, c


def _axis_rotation(angle: ArrayLike, axis: int) -> np.ndarray:
    theta = real(angle, "angle")
    c, s = np.cos(theta), np.sin(theta)
    R = np.zeros((*theta.shape, 3, 3))
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    R[..., axis, axis] = 1.0
    R[..., i, i] = c
    R[..., j, j] = c
    R[..., i, j] = -s
    R[..., j, i] = s
    return R


def rot_x(angle: ArrayLike) -> np.ndarray:
    """Rotation by ``angle`` radians about the x axis; shape (3, 3), or (..., 3, 3) for an array.

    Examples
    --------
    >>> rot_x(np.pi / 2).round(3)
    array([[ 1.,  0.,  0.],
           [ 0.,  0., -1.],
           [ 0.,  1.,  0.]])
    """
    return _axis_rotation(angle, 0)


def rot_y(angle: ArrayLike) -> np.ndarray:
    """Rotation by ``angle`` radians about the y axis; shape (3, 3), or (..., 3, 3) for an array.

    Examples
    --------
    >>> rot_y(np.pi / 2) @ [1.0, 0.0, 0.0]
    array([ 6.123234e-17,  0.000000e+00, -1.000000e+00])
    """
    return _axis_rotation(angle, 1)


def rot_z(angle: ArrayLike) -> np.ndarray:
    """Rotation by ``angle`` radians about the z axis; shape (3, 3), or (..., 3, 3) for an array.

    Examples
    --------
    >>> rot_z([0.0, np.pi]).shape
    (2, 3, 3)
    """
    return _axis_rotation(angle, 2)


def make_transform(R: ArrayLike | None = None, p: ArrayLike | None = None) -> np.ndarray:
    """Homogeneous transform from a rotation ``R`` and a translation ``p``.

    Parameters
    ----------
    R : array_like, shape (..., 3, 3), optional
        Rotation (identity if omitted).  It is not validated; see :func:`check_rotation`.
    p : array_like, shape (..., 3), optional
        Translation in metres (zero if omitted).

    Returns
    -------
    ndarray, shape (..., 4, 4)

    Examples
    --------
    >>> make_transform(p=[0.1, 0.2, 0.3])[:3, 3]
    array([0.1, 0.2, 0.3])
    """
    R_array = np.eye(3) if R is None else _core(R, (3, 3), "R")
    p_array = np.zeros(3) if p is None else _vector3(p, "p")
    try:
        batch = np.broadcast_shapes(R_array.shape[:-2], p_array.shape[:-1])
    except ValueError:
        raise ValueError(
            f"R and p must be stacks of the same length; got shapes {R_array.shape} and "
            f"{p_array.shape}"
        ) from None
    T = np.zeros((*batch, 4, 4))
    T[..., :3, :3] = R_array
    T[..., :3, 3] = p_array
    T[..., 3, 3] = 1.0
    return T


def inv_transform(T: ArrayLike) -> np.ndarray:
    """Inverse of rigid-body transforms without a general matrix inverse.

    ``inv([[R, p], [0, 1]]) = [[Rᵀ, −Rᵀ p], [0, 1]]``.

    Parameters
    ----------
    T : array_like, shape (..., 4, 4)
        Rigid-body transforms (validated with :func:`check_transform`: a matrix that is not a
        rotation and translation has no inverse of this form).

    Returns
    -------
    ndarray, shape (..., 4, 4)

    Examples
    --------
    >>> T = make_transform(rot_z(0.4), [0.3, -0.1, 0.2])
    >>> np.allclose(inv_transform(T) @ T, np.eye(4))
    True
    """
    array = check_transform(T)
    R_t = np.swapaxes(array[..., :3, :3], -1, -2)
    out = np.zeros_like(array)
    out[..., :3, :3] = R_t
    out[..., :3, 3] = -(R_t @ array[..., :3, 3, None])[..., 0]
    out[..., 3, 3] = 1.0
    return out


def skew(w: ArrayLike) -> np.ndarray:
    """Skew-symmetric matrix ``[w]`` with ``[w] @ v = w × v``.

    Examples
    --------
    >>> skew([1.0, 2.0, 3.0])
    array([[ 0., -3.,  2.],
           [ 3.,  0., -1.],
           [-2.,  1.,  0.]])
    """
    v = _vector3(w, "w")
    W = np.zeros((*v.shape[:-1], 3, 3))
    W[..., 0, 1], W[..., 0, 2] = -v[..., 2], v[..., 1]
    W[..., 1, 0], W[..., 1, 2] = v[..., 2], -v[..., 0]
    W[..., 2, 0], W[..., 2, 1] = -v[..., 1], v[..., 0]
    return W


def unskew(W: ArrayLike) -> np.ndarray:
    """Vector ``w`` of a skew-symmetric matrix ``[w]`` (its antisymmetric part is used).

    Examples
    --------
    >>> unskew(skew([1.0, 2.0, 3.0]))
    array([1., 2., 3.])
    """
    M = _core(W, (3, 3), "W")
    return 0.5 * np.stack(
        [M[..., 2, 1] - M[..., 1, 2], M[..., 0, 2] - M[..., 2, 0], M[..., 1, 0] - M[..., 0, 1]],
        axis=-1,
    )


def so3_exp(omega: ArrayLike) -> np.ndarray:
    """Rotation matrix of a rotation vector ``ω = θ k`` (Rodrigues' formula).

    ``exp([ω]) = I + sin θ [k] + (1 − cos θ) [k]²``; accurate down to ``θ = 0``.

    Parameters
    ----------
    omega : array_like, shape (..., 3)
        Rotation vectors in radians.

    Returns
    -------
    ndarray, shape (..., 3, 3)

    Raises
    ------
    ValueError
        If the shape is wrong, or an entry is not finite or larger in magnitude than
        :data:`LONGEST_ROTATION_VECTOR`.

    Examples
    --------
    >>> np.allclose(so3_exp([0.0, 0.0, 0.7]), rot_z(0.7))
    True
    """
    w = _vector3(omega, "omega")
    a, b = _exp_coefficients(w, "omega")
    W = skew(w)
    return np.eye(3) + a * W + b * (W @ W)


def so3_log(R: ArrayLike, *, check: bool = True) -> np.ndarray:
    """Rotation vector ``ω = θ k`` of a rotation matrix, with ``θ`` in [0, π].

    Accurate over the whole range, including angles near 0 and exactly π (where the axis is
    read from the symmetric part of ``R``).

    Parameters
    ----------
    R : array_like, shape (..., 3, 3)
        Rotation matrices.
    check : bool
        Validate ``R`` with :func:`check_rotation` (default).  ``check=False`` is for inner
        loops that pass float rotations they computed themselves.

    Returns
    -------
    ndarray, shape (..., 3)

    Examples
    --------
    >>> so3_log(rot_x(0.5))
    array([0.5, 0. , 0. ])
    >>> np.round(so3_log(rot_y(np.pi)), 12)
    array([0.        , 3.14159265, 0.        ])
    """
    return rotation_parts(R, check=check)[2]


def rotation_parts(
    R: ArrayLike, *, check: bool = True
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(sin θ · k, θ, θ · k)`` of rotation matrices: :func:`so3_log` with its by-products.

    ``sin θ · k`` is the axial vector of the antisymmetric part of ``R`` (the course reports'
    cross-product orientation error); ``θ = atan2(‖sin θ k‖, (trace − 1)/2)`` is accurate at
    every angle; near π, where the antisymmetric part has lost the axis, the axis is read from
    the symmetric part ``(R + Rᵀ)/2 − cos θ·I = (1 − cos θ) k kᵀ``.

    Examples
    --------
    >>> sin_axis, angle, omega = rotation_parts(rot_z(0.5))
    >>> float(angle), omega.round(12) + 0.0
    (0.5, array([0. , 0. , 0.5]))
    """
    R = check_rotation(R) if _checking(check) else _unchecked(R, (3, 3), "R")
    s = 0.5 * np.stack(
        [R[..., 2, 1] - R[..., 1, 2], R[..., 0, 2] - R[..., 2, 0], R[..., 1, 0] - R[..., 0, 1]],
        axis=-1,
    )
    sin_theta = np.sqrt(np.sum(s * s, axis=-1))
    cos_theta = 0.5 * (R[..., 0, 0] + R[..., 1, 1] + R[..., 2, 2] - 1.0)
    theta = np.arctan2(sin_theta, cos_theta)
    small = sin_theta < 1e-8
    scale = np.where(small, 1.0 + theta**2 / 6.0, theta / np.where(small, 1.0, sin_theta))
    omega = scale[..., None] * s
    near_pi = cos_theta < -0.9
    if np.any(near_pi):
        B = 0.5 * (R + np.swapaxes(R, -1, -2)) - cos_theta[..., None, None] * np.eye(3)
        column = np.argmax(np.diagonal(B, axis1=-2, axis2=-1), axis=-1)
        k = np.take_along_axis(B, column[..., None, None], axis=-1)[..., 0]
        # rows far from π may have B = 0 (R = I): their k is never used, so divide safely
        norm = np.linalg.norm(k, axis=-1, keepdims=True)
        k = k / np.where(norm > 0.0, norm, 1.0)
        sign = np.where(np.sum(k * s, axis=-1) < 0.0, -1.0, 1.0)
        omega = np.where(near_pi[..., None], (sign * theta)[..., None] * k, omega)
    return s, theta, omega


def rotation_angle(R1: ArrayLike, R2: ArrayLike | None = None) -> np.ndarray | float:
    """Angle in radians of the rotation taking ``R1`` to ``R2`` (of ``R1`` itself if no ``R2``).

    Uses ``2·asin(‖R1 − R2‖_F / (2√2))``, which stays accurate for tiny angles where
    ``arccos((trace − 1)/2)`` loses all precision below about 1e-8 rad.

    Examples
    --------
    >>> float(rotation_angle(rot_z(1e-12), np.eye(3)))
    1e-12
    """
    A = check_rotation(R1, name="R1")
    B = np.eye(3) if R2 is None else check_rotation(R2, name="R2")
    try:
        return _angle_between(A, B)
    except ValueError:
        raise ValueError(
            f"R1 and R2 must be rotations of matching stacks; got shapes {A.shape} and {B.shape}"
        ) from None


def _angle_between(A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """The angle of ``Aᵀ B`` for checked rotations (stacks broadcast): ``2·asin(‖A − B‖_F /
    (2√2))`` up to π/2, exact to round-off for tiny angles; beyond, where the arcsine's slope
    grows without bound (6e-8 rad of error at π), ``atan2(sin θ, cos θ)`` of the relative
    rotation, its sine from the antisymmetric part and its cosine from the trace."""
    half_sine = np.sqrt(np.sum((A - B) ** 2, axis=(-2, -1))) / (2.0 * np.sqrt(2.0))  # sin(θ/2)
    angle = 2.0 * np.arcsin(np.minimum(half_sine, 1.0))
    wide = half_sine > _SIN_QUARTER_TURN
    if np.any(wide):
        C = np.swapaxes(A, -1, -2) @ B
        if np.ndim(angle) == 0:
            return _wide_angle(C)
        wide_angle = _wide_angle(np.broadcast_to(C, (*angle.shape, 3, 3))[wide])
        angle[wide] = wide_angle
    return angle


#: sin(π/4): above it, :func:`_angle_between` measures the angle with atan2.
_SIN_QUARTER_TURN = math.sin(math.pi / 4)


def _wide_angle(C: np.ndarray) -> np.ndarray:
    """The angle of rotations ``C`` (..., 3, 3) as ``atan2(sin θ, cos θ)``."""
    x = C[..., 2, 1] - C[..., 1, 2]
    y = C[..., 0, 2] - C[..., 2, 0]
    z = C[..., 1, 0] - C[..., 0, 1]
    sine = 0.5 * np.sqrt(x * x + y * y + z * z)
    cosine = 0.5 * (C[..., 0, 0] + C[..., 1, 1] + C[..., 2, 2] - 1.0)
    return np.arctan2(sine, cosine)


def pose_error(
    T1: ArrayLike, T2: ArrayLike, *, check: bool = True
) -> tuple[np.ndarray, np.ndarray]:
    """Position error (metres) and rotation angle (radians) between poses ``T1`` and ``T2``.

    The angle is :func:`rotation_angle`'s ``2·asin(‖R1 − R2‖_F / (2√2))``, accurate at every
    size.  Stacks broadcast.  ``check=False`` skips the validation of two float arrays of
    poses the caller made itself (an inner loop's).

    Returns
    -------
    (ndarray, ndarray)
        Shapes ``(...)``: ``‖p1 − p2‖`` and the angle of ``R1ᵀ R2``.

    Examples
    --------
    >>> T = make_transform(rot_z(1e-12), [0.3, 0.0, 0.0])
    >>> position, angle = pose_error(T, np.eye(4))
    >>> float(position), float(angle)
    (0.3, 1e-12)
    """
    checking = _checking(check)
    A = T1 if not checking and _poses(T1) else check_transform(T1, name="T1")
    B = T2 if not checking and _poses(T2) else check_transform(T2, name="T2")
    if A.shape == B.shape == (4, 4):  # the scalar fast path
        (a, b, c, x), (d, e, f, y), (g, h, i, z), _ = A.tolist()
        (a2, b2, c2, x2), (d2, e2, f2, y2), (g2, h2, i2, z2), _ = B.tolist()
        x, y, z = x - x2, y - y2, z - z2
        a, b, c, d, e, f, g, h, i = (
            a - a2,
            b - b2,
            c - c2,
            d - d2,
            e - e2,
            f - f2,
            g - g2,
            h - h2,
            i - i2,
        )
        frob = math.sqrt(a * a + b * b + c * c + d * d + e * e + f * f + g * g + h * h + i * i)
        half_sine = frob / (2.0 * math.sqrt(2.0))
        if half_sine > _SIN_QUARTER_TURN:  # beyond π/2: atan2, as _angle_between does
            angle = float(_wide_angle(A[:3, :3].T @ B[:3, :3]))
        else:
            angle = 2.0 * math.asin(half_sine)
        return np.float64(math.sqrt(x * x + y * y + z * z)), np.float64(angle)
    try:
        dp = A[..., :3, 3] - B[..., :3, 3]
        angle = _angle_between(A[..., :3, :3], B[..., :3, :3])
    except ValueError:
        raise ValueError(
            f"T1 and T2 must be poses of matching stacks; got shapes {A.shape} and {B.shape}"
        ) from None
    return np.sqrt(np.sum(dp * dp, axis=-1)), angle


def _poses(T: object) -> bool:
    """Whether ``T`` is what ``check=False`` takes: a float array of shape (..., 4, 4) (else it
    is checked anyway, for an error that names it rather than numpy's)."""
    return type(T) is np.ndarray and T.dtype == np.float64 and T.shape[-2:] == (4, 4)


def wrap_angles(q: ArrayLike, *, check: bool = True, out: np.ndarray | None = None) -> np.ndarray:
    """Angles wrapped into (−π, π], the one interval urkin uses everywhere.

    NaN stays NaN (the rows of a stack of closed-form solutions that are not solutions); an
    infinite angle is refused.

    Parameters
    ----------
    q : array_like
        Angles in radians, any shape.
    check : bool
        Validate ``q`` (numbers, not complex).  ``check=False`` is for inner loops that pass a
        float array of angles they built themselves, within a few turns: it skips the exact
        reduction of angles beyond 512 turns (whose subtraction of whole turns of the rounded
        2π loses about ``|q| · 2⁻⁵³``: 8e-9 rad at 1.2e8 rad, and every digit beyond 1e16).
    out : ndarray, optional
        Where to write the result (``out=q`` wraps a float array in place).

    Examples
    --------
    >>> wrap_angles([np.pi, -np.pi, 3 * np.pi / 2, 0.5])
    array([ 3.14159265,  3.14159265, -1.57079633,  0.5       ])
    """
    checking = _checking(check) or not isinstance(q, (np.ndarray, np.floating, float))
    if checking:
        angles = real(q, "q", finite=False)
        if np.isinf(angles).any():
            raise ValueError("q contains infinity: an infinite angle has no wrapped value")
    else:
        angles = q
    if out is not None and (
        not isinstance(out, np.ndarray) or out.shape != np.shape(angles) or out.dtype != float
    ):
        raise ValueError(
            f"out must be a float array of q's shape {np.shape(angles)}; got "
            f"{getattr(out, 'dtype', type(out).__name__)} of shape {np.shape(out)}"
        )
    # ceil((x − π)/2π) counts the turns to remove; −π lands on π exactly (the division by 2π
    # is kept rather than a multiplication by 1/2π, which is not exact at x = −π)
    exact = None
    if checking:  # before the subtraction, which may write over the angles (out=q)
        far = np.abs(angles) > _FEW_TURNS  # NaN is not: it stays NaN
        if far.any():  # numpy's sine and cosine reduce by the true π, to the last bit
            exact = np.arctan2(np.sin(angles), np.cos(angles))
            exact = np.where(exact == -np.pi, np.pi, exact)
    turns = np.ceil((angles - np.pi) / (2.0 * np.pi))
    turns *= 2.0 * np.pi
    wrapped = np.subtract(angles, turns, out=out)
    # just above −π, (x − π) rounds to −2π and the turn added overshoots π by an ulp
    high = wrapped > np.pi
    if high.any():
        if isinstance(wrapped, np.ndarray):
            np.subtract(wrapped, 2.0 * np.pi, out=wrapped, where=high)
        else:  # one angle, as a numpy scalar
            wrapped = wrapped - 2.0 * np.pi
    if exact is not None:
        if isinstance(wrapped, np.ndarray):
            np.copyto(wrapped, exact, where=far)
        else:  # one angle, as a numpy scalar
            wrapped = exact[()]
    return wrapped


#: Beyond 512 turns, :func:`wrap_angles` reduces angles through their sine and cosine, by the
#: true π (within, whole turns of the rounded 2π are removed, which loses at most about 5e-13
#: rad there and keeps the interval's ends where that arithmetic puts them).
_FEW_TURNS = 1024 * np.pi


def random_rotations(
    shape: int | tuple[int, ...] = (), seed: int | np.random.Generator = 0
) -> np.ndarray:
    """Rotations drawn uniformly (Haar measure) from seeded random unit quaternions.

    Parameters
    ----------
    shape : int or tuple of int
        Leading shape; ``()`` (default) for one rotation.
    seed : int or numpy.random.Generator

    Returns
    -------
    ndarray, shape (*shape, 3, 3)

    Raises
    ------
    TypeError
        If ``shape`` is not an int or a tuple of ints, or ``seed`` not an int or a Generator.
    ValueError
        If ``shape`` or ``seed`` is negative.

    Examples
    --------
    >>> R = random_rotations(1000, seed=1)
    >>> R.shape, float(np.abs(np.linalg.det(R) - 1).max()) < 1e-12
    ((1000, 3, 3), True)
    """
    size = sample_shape(shape)
    rng = generator(seed)
    quaternion = rng.normal(size=(*size, 4))
    quaternion /= np.linalg.norm(quaternion, axis=-1, keepdims=True)
    w, x, y, z = np.moveaxis(quaternion, -1, 0)
    R = np.empty((*w.shape, 3, 3))
    R[..., 0, :] = np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1)
    R[..., 1, :] = np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1)
    R[..., 2, :] = np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1)
    return R


def random_transforms(
    shape: int | tuple[int, ...] = (),
    seed: int | np.random.Generator = 0,
    radius: float = 1.0,
) -> np.ndarray:
    """Seeded random poses: uniform rotations and positions uniform in a cube of half-side
    ``radius`` (metres).

    Raises
    ------
    ValueError
        If ``radius`` is negative or not finite (or ``shape`` is negative).

    Examples
    --------
    >>> T = random_transforms((2, 3), seed=4)
    >>> T.shape, check_transform(T, tol=1e-12).shape
    ((2, 3, 4, 4), (2, 3, 4, 4))
    """
    half_side = real(radius, "radius")
    if half_side.ndim != 0 or half_side < 0.0:
        raise ValueError(f"radius must be one number ≥ 0; got {radius!r}")
    rng = generator(seed)
    R = random_rotations(shape, rng)
    T = np.zeros((*R.shape[:-2], 4, 4))
    T[..., :3, :3] = R
    T[..., :3, 3] = rng.uniform(-half_side, half_side, (*R.shape[:-2], 3))
    T[..., 3, 3] = 1.0
    return T


def rpy_to_rotation(rpy: ArrayLike) -> np.ndarray:
    """Rotation from roll–pitch–yaw angles: ``R = Rz(yaw) @ Ry(pitch) @ Rx(roll)``.

    Parameters
    ----------
    rpy : array_like, shape (..., 3)
        ``(roll, pitch, yaw)`` in radians.

    Returns
    -------
    ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> np.allclose(rpy_to_rotation([0.0, 0.0, 0.3]), rot_z(0.3))
    True
    """
    angles = _vector3(rpy, "rpy")
    return rot_z(angles[..., 2]) @ rot_y(angles[..., 1]) @ rot_x(angles[..., 0])


def rotation_to_rpy(R: ArrayLike) -> np.ndarray:
    """Roll–pitch–yaw angles of a rotation, the inverse of :func:`rpy_to_rotation`.

    Pitch is in [−π/2, π/2]; roll and yaw in (−π, π].  At the gimbal lock (pitch = ±π/2)
    only ``roll ∓ yaw`` is defined: the yaw is then reported as 0.

    Parameters
    ----------
    R : array_like, shape (..., 3, 3)

    Returns
    -------
    ndarray, shape (..., 3)
        ``(roll, pitch, yaw)`` in radians.

    Examples
    --------
    >>> rotation_to_rpy(rpy_to_rotation([0.1, -0.2, 0.3]))
    array([ 0.1, -0.2,  0.3])
    """
    M = check_rotation(R)
    cos_pitch = np.hypot(M[..., 0, 0], M[..., 1, 0])
    pitch = np.arctan2(-M[..., 2, 0], cos_pitch)
    # yaw from the first column; exactly at the lock it is free, and reported as 0
    yaw = np.where(cos_pitch < 1e-14, 0.0, np.arctan2(M[..., 1, 0], M[..., 0, 0]))
    # roll from what is left once yaw and pitch are taken out: Ry(pitch)ᵀ Rz(yaw)ᵀ R = Rx(roll).
    # It is read from entries of size one, so near the lock, where yaw is barely determined,
    # roll still matches it and the angles rebuild R to round-off.
    cy, sy, cp, sp = np.cos(yaw), np.sin(yaw), np.cos(pitch), np.sin(pitch)
    cos_roll = -sy * M[..., 0, 1] + cy * M[..., 1, 1]
    sin_roll = sp * (cy * M[..., 0, 1] + sy * M[..., 1, 1]) + cp * M[..., 2, 1]
    roll = np.arctan2(sin_roll, cos_roll)
    rpy = np.stack([roll, pitch, yaw], axis=-1)
    rpy[..., ::2][rpy[..., ::2] == -np.pi] = np.pi  # roll and yaw in (−π, π]
    return rpy


def _twist(V: ArrayLike, name: str) -> np.ndarray:
    return _core(V, (6,), name)


def twist_matrix(V: ArrayLike) -> np.ndarray:
    """The 4×4 matrix ``[V] = [[[ω], v], [0, 0]]`` of a twist ``V = (ω, v)`` (an element of se(3)).

    Examples
    --------
    >>> twist_matrix([0, 0, 1, 0.5, 0, 0]) + 0.0  # + 0.0 turns -0.0 into 0.0
    array([[ 0. , -1. ,  0. ,  0.5],
           [ 1. ,  0. ,  0. ,  0. ],
           [ 0. ,  0. ,  0. ,  0. ],
           [ 0. ,  0. ,  0. ,  0. ]])
    """
    twist = _twist(V, "V")
    M = np.zeros((*twist.shape[:-1], 4, 4))
    M[..., :3, :3] = skew(twist[..., :3])
    M[..., :3, 3] = twist[..., 3:]
    return M


def twist_vector(M: ArrayLike) -> np.ndarray:
    """The twist ``(ω, v)`` of a 4×4 se(3) matrix, the inverse of :func:`twist_matrix`.

    Examples
    --------
    >>> twist_vector(twist_matrix([1.0, 2.0, 3.0, 4.0, 5.0, 6.0]))
    array([1., 2., 3., 4., 5., 6.])
    """
    array = _core(M, (4, 4), "M")
    return np.concatenate([unskew(array[..., :3, :3]), array[..., :3, 3]], axis=-1)


def se3_exp(V: ArrayLike) -> np.ndarray:
    """Rigid-body motion ``exp([V])`` of exponential coordinates ``V = (ω, v)`` (a twist × time).

    ``R = exp([ω])`` and ``p = (I + (1 − cos θ)/θ² [ω] + (θ − sin θ)/θ³ [ω]²) v`` with
    ``θ = ‖ω‖``; a pure translation (``ω = 0``) gives ``p = v``.

    Parameters
    ----------
    V : array_like, shape (..., 6)

    Returns
    -------
    ndarray, shape (..., 4, 4)

    Raises
    ------
    ValueError
        If the shape is wrong, an entry is not finite, or an entry of ``ω`` is larger in
        magnitude than :data:`LONGEST_ROTATION_VECTOR`.

    Examples
    --------
    >>> T = se3_exp([0, 0, np.pi / 2, 0, 0, 0])  # a quarter turn about z
    >>> np.allclose(T[:3, :3], rot_z(np.pi / 2)), T[:3, 3]
    (True, array([0., 0., 0.]))
    >>> se3_exp([0, 0, 0, 0.1, 0.2, 0.3])[:3, 3]  # a pure translation
    array([0.1, 0.2, 0.3])
    """
    twist = _twist(V, "V")
    omega, v = twist[..., :3], twist[..., 3:]
    a, b, c = _exp_coefficients(omega, "V", translation=True)
    W = skew(omega)
    W2 = W @ W
    T = np.zeros((*twist.shape[:-1], 4, 4))
    T[..., :3, :3] = np.eye(3) + a * W + b * W2
    T[..., :3, 3] = ((np.eye(3) + b * W + c * W2) @ v[..., None])[..., 0]
    T[..., 3, 3] = 1.0
    return T


def se3_log(T: ArrayLike, *, check: bool = True) -> np.ndarray:
    """Exponential coordinates ``V = (ω, v)`` of a rigid-body transform, ``‖ω‖ ≤ π``.

    The inverse of :func:`se3_exp`: ``ω = log(R)`` and ``v = G⁻¹ p`` with
    ``G⁻¹ = I − [ω]/2 + (1 − θ sin θ / (2 (1 − cos θ))) / θ² · [ω]²``, the coefficient
    computed as ``(1 − (θ/2) cot(θ/2)) / θ²``, accurate at every angle.

    Parameters
    ----------
    T : array_like, shape (..., 4, 4)
    check : bool
        Validate ``T`` with :func:`check_transform` (default).  ``check=False`` is for inner
        loops that pass float transforms they computed themselves.

    Returns
    -------
    ndarray, shape (..., 6)

    Examples
    --------
    >>> V = np.array([0.1, -0.2, 0.3, 0.4, 0.5, -0.6])
    >>> np.allclose(se3_log(se3_exp(V)), V)
    True
    """
    T = check_transform(T) if _checking(check) else _unchecked(T, (4, 4), "T")
    p = T[..., :3, 3]
    _, theta, omega = rotation_parts(T[..., :3, :3], check=False)
    theta = theta[..., None, None]
    W = skew(omega)
    small = theta < 1e-4
    safe = np.where(small, 1.0, theta)
    half = 0.5 * safe
    # θ sin θ / (2 (1 − cos θ)) = (θ/2) cot(θ/2): the left form loses ε/θ⁴ to 1 − cos θ
    # (1e-8 in v at θ = 1e-4); the right one keeps full precision
    k = np.where(small, 1.0 / 12.0 + theta**2 / 720.0, (1.0 - half / np.tan(half)) / safe**2)
    G_inverse = np.eye(3) - 0.5 * W + k * (W @ W)
    v = (G_inverse @ p[..., None])[..., 0]
    return np.concatenate([omega, v], axis=-1)


def adjoint(T: ArrayLike, *, check: bool = True) -> np.ndarray:
    """Adjoint ``Ad_T = [[R, 0], [[p] R, R]]``, mapping twists ``(ω, v)`` through ``T``.

    If ``V_b`` is a twist in frame b and ``T = T_a_b``, then ``V_a = Ad_T @ V_b``.

    Parameters
    ----------
    T : array_like, shape (..., 4, 4)
    check : bool
        Validate ``T`` with :func:`check_transform` (default); ``check=False`` for inner loops.

    Returns
    -------
    ndarray, shape (..., 6, 6)

    Examples
    --------
    >>> T = make_transform(rot_z(0.3), [0.1, 0.2, 0.3])
    >>> V = np.array([0.0, 0.0, 1.0, 0.0, 0.0, 0.0])
    >>> np.allclose(twist_matrix(adjoint(T) @ V), T @ twist_matrix(V) @ inv_transform(T))
    True
    """
    T = check_transform(T) if _checking(check) else _unchecked(T, (4, 4), "T")
    R, p = T[..., :3, :3], T[..., :3, 3]
    P = np.zeros((*T.shape[:-2], 3, 3))
    P[..., 0, 1], P[..., 0, 2] = -p[..., 2], p[..., 1]
    P[..., 1, 0], P[..., 1, 2] = p[..., 2], -p[..., 0]
    P[..., 2, 0], P[..., 2, 1] = -p[..., 1], p[..., 0]
    Ad = np.zeros((*T.shape[:-2], 6, 6))
    Ad[..., :3, :3] = R
    Ad[..., 3:, 3:] = R
    Ad[..., 3:, :3] = P @ R
    return Ad
