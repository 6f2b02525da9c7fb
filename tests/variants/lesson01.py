"""Lesson 01: other correct ways to write its exercises, and known mistakes."""

from tests.variants import Variant

# A correct rotation_to_rpy, for variants that change one part of it.
_RPY_HEAD = (
    "def rotation_to_rpy(R):\n"
    "    cos_pitch = np.hypot(R[0, 0], R[1, 0])\n"
    "    pitch = np.arctan2(-R[2, 0], cos_pitch)\n"
)
_RPY_LOCK = (
    "    if cos_pitch < 1e-9:\n"
    "        return np.array([np.arctan2(-R[1, 2], R[1, 1]), pitch, 0.0])\n"
)
_RPY_GENERAL = (
    "    roll = np.arctan2(R[2, 1], R[2, 2])\n"
    "    yaw = np.arctan2(R[1, 0], R[0, 0])\n"
    "    return np.array([roll, pitch, yaw])\n"
)


def _rpy(lock: str = _RPY_LOCK, general: str = _RPY_GENERAL, head: str = _RPY_HEAD) -> str:
    return head + lock + general


# A correct transform_inverse, for variants that add something to it.
_INVERSE = (
    "    R, p = T[:3, :3], T[:3, 3]\n"
    "    out = np.eye(4)\n"
    "    out[:3, :3] = R.T\n"
    "    out[:3, 3] = -R.T @ p\n"
    "    return out\n"
)

# A correct axis_angle_to_rotation body after `k` (a unit axis array) is known.
_RODRIGUES = (
    "    K = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])\n"
    "    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * (K @ K)\n"
)

# The start of a rotation_verdict that checks the shape and the finite entries as it should.
_VERDICT_HEAD = (
    "def rotation_verdict(R, tol=1e-9):\n"
    "    R = np.asarray(R, dtype=float)\n"
    "    if R.shape != (3, 3):\n"
    "        raise ValueError(f'R must have shape (3, 3), got {R.shape}')\n"
    "    if not np.all(np.isfinite(R)):\n"
    "        return 'not orthonormal'\n"
)

CORRECT = [
    # ------------------------------------------------------------------------ 1.1 rot_z
    Variant(
        "1.1",
        "math.cos and math.sin in nested lists",
        "import math\n\n"
        "def rot_z(theta):\n"
        "    c, s = math.cos(theta), math.sin(theta)\n"
        "    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]], dtype=float)\n",
    ),
    Variant(
        "1.1",
        "columns are the turned axes",
        "def rot_z(theta):\n"
        "    x_axis = np.array([np.cos(theta), np.sin(theta), 0.0])\n"
        "    y_axis = np.array([-np.sin(theta), np.cos(theta), 0.0])\n"
        "    return np.column_stack([x_axis, y_axis, [0.0, 0.0, 1.0]])\n",
    ),
    Variant(
        "1.1",
        "float32",
        "def rot_z(theta):\n"
        "    c, s = np.cos(theta), np.sin(theta)\n"
        "    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]], dtype=np.float32)\n",
    ),
    Variant(
        "1.1",
        "identity filled in",
        "def rot_z(theta):\n"
        "    R = np.eye(3)\n"
        "    R[0, 0] = R[1, 1] = np.cos(theta)\n"
        "    R[1, 0] = np.sin(theta)\n"
        "    R[0, 1] = -R[1, 0]\n"
        "    return R\n",
    ),
    Variant(
        "1.1",
        "a complex exponential",
        "def rot_z(theta):\n"
        "    z = np.exp(1j * theta)\n"
        "    return np.array([[z.real, -z.imag, 0.0], [z.imag, z.real, 0.0], [0.0, 0.0, 1.0]])\n",
    ),
    Variant(
        "1.1",
        "transpose of the inverse",
        "def rot_z(theta):\n"
        "    c, s = np.cos(theta), np.sin(theta)\n"
        "    return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]).T\n",
    ),
    Variant(
        "1.1",
        "a 2×2 helper embedded in 3×3",
        "def _plane(theta):\n"
        "    c, s = np.cos(theta), np.sin(theta)\n"
        "    return np.array([[c, -s], [s, c]])\n\n"
        "def rot_z(theta):\n"
        "    R = np.eye(3)\n"
        "    R[:2, :2] = _plane(theta)\n"
        "    return R\n",
    ),
    Variant(
        "1.1",
        "Rodrigues with urkin's skew of e_z",
        "def rot_z(theta):\n"
        "    K = skew([0.0, 0.0, 1.0])\n"
        "    return np.eye(3) + np.sin(theta) * K + (1 - np.cos(theta)) * K @ K\n",
    ),
    Variant(
        "1.1",
        "an assert on a scalar angle",
        "def rot_z(theta):\n"
        "    assert np.ndim(theta) == 0, 'one angle'\n"
        "    theta = float(theta)\n"
        "    c, s = np.cos(theta), np.sin(theta)\n"
        "    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])\n",
    ),
    # ------------------------------------------------------------ 1.2 transform_inverse
    Variant(
        "1.2",
        "np.block",
        "def transform_inverse(T):\n"
        "    R, p = T[:3, :3], T[:3, 3:]\n"
        "    return np.block([[R.T, -R.T @ p], [np.zeros((1, 3)), np.ones((1, 1))]])\n",
    ),
    Variant(
        "1.2",
        "row vector p @ R",
        "def transform_inverse(T):\n"
        "    R, p = T[:3, :3], T[:3, 3]\n"
        "    out = np.eye(4)\n"
        "    out[:3, :3] = R.T\n"
        "    out[:3, 3] = -(p @ R)\n"
        "    return out\n",
    ),
    Variant(
        "1.2",
        "explicit loops",
        "def transform_inverse(T):\n"
        "    out = np.zeros((4, 4))\n"
        "    for i in range(3):\n"
        "        for j in range(3):\n"
        "            out[i, j] = T[j, i]\n"
        "    for i in range(3):\n"
        "        out[i, 3] = -sum(T[j, i] * T[j, 3] for j in range(3))\n"
        "    out[3, 3] = 1.0\n"
        "    return out\n",
    ),
    Variant(
        "1.2",
        "float32",
        "def transform_inverse(T):\n"
        "    R = np.asarray(T[:3, :3], dtype=np.float32)\n"
        "    p = np.asarray(T[:3, 3], dtype=np.float32)\n"
        "    out = np.eye(4, dtype=np.float32)\n"
        "    out[:3, :3] = R.T\n"
        "    out[:3, 3] = -R.T @ p\n"
        "    return out\n",
    ),
    Variant(
        "1.2",
        "urkin's make_transform",
        "def transform_inverse(T):\n"
        "    R, p = T[:3, :3], T[:3, 3]\n"
        "    return make_transform(R.T, -R.T @ p)\n",
    ),
    Variant(
        "1.2",
        "einsum and hstack",
        "def transform_inverse(T):\n"
        "    Rt = np.einsum('ij->ji', T[:3, :3])\n"
        "    top = np.hstack([Rt, -(Rt @ T[:3, 3]).reshape(3, 1)])\n"
        "    return np.vstack([top, [0.0, 0.0, 0.0, 1.0]])\n",
    ),
    Variant(
        "1.2",
        "ValueError when R is not a rotation",
        "def transform_inverse(T):\n"
        "    R = T[:3, :3]\n"
        "    if not np.allclose(R.T @ R, np.eye(3), atol=1e-6):\n"
        "        raise ValueError('T is not a rigid transform')\n" + _INVERSE,
    ),
    Variant(
        "1.2",
        "NotImplementedError outside the contract",
        "def transform_inverse(T):\n"
        "    if abs(np.linalg.det(T[:3, :3]) - 1.0) > 1e-6:\n"
        "        raise NotImplementedError('only rigid transforms')\n" + _INVERSE,
    ),
    Variant(
        "1.2",
        "urkin's check_transform first",
        "def transform_inverse(T):\n    T = urkin.transforms.check_transform(T)\n" + _INVERSE,
    ),
    Variant(
        "1.2",
        "a helper that inverts the rotation by transposing",
        "def _undo_turn(R):\n"
        "    return R.T\n\n"
        "def transform_inverse(T):\n"
        "    Ri = _undo_turn(T[:3, :3])\n"
        "    out = np.identity(4)\n"
        "    out[:3, :3] = Ri\n"
        "    out[:3, 3] = -Ri.dot(T[:3, 3])\n"
        "    return out\n",
    ),
    # -------------------------------------------------------------- 1.3 rotation_to_rpy
    Variant(
        "1.3",
        "arcsin for the pitch",
        "def rotation_to_rpy(R):\n"
        "    pitch = np.arcsin(np.clip(-R[2, 0], -1.0, 1.0))\n"
        "    if np.hypot(R[0, 0], R[1, 0]) < 1e-9:\n"
        "        return np.array([np.arctan2(-R[1, 2], R[1, 1]), pitch, 0.0])\n"
        "    return np.array([np.arctan2(R[2, 1], R[2, 2]), pitch,"
        " np.arctan2(R[1, 0], R[0, 0])])\n",
    ),
    Variant(
        "1.3",
        "cos pitch as sqrt(1 − r31²)",
        _rpy(
            head="def rotation_to_rpy(R):\n"
            "    cos_pitch = np.sqrt(max(0.0, 1.0 - R[2, 0] ** 2))\n"
            "    pitch = np.arctan2(-R[2, 0], cos_pitch)\n"
        ),
    ),
    Variant(
        "1.3",
        "math.atan2 and a tuple",
        "import math\n\n"
        "def rotation_to_rpy(R):\n"
        "    r = [[float(x) for x in row] for row in R]\n"
        "    cp = math.sqrt(r[0][0] ** 2 + r[1][0] ** 2)\n"
        "    pitch = math.atan2(-r[2][0], cp)\n"
        "    if cp < 1e-9:\n"
        "        return (math.atan2(-r[1][2], r[1][1]), pitch, 0.0)\n"
        "    return (math.atan2(r[2][1], r[2][2]), pitch, math.atan2(r[1][0], r[0][0]))\n",
    ),
    Variant(
        "1.3",
        "cos pitch from the bottom row",
        _rpy(
            head="def rotation_to_rpy(R):\n"
            "    cos_pitch = np.sqrt(R[2, 1] ** 2 + R[2, 2] ** 2)\n"
            "    pitch = np.arctan2(-R[2, 0], cos_pitch)\n"
        ),
    ),
    Variant(
        "1.3",
        "lock test on |r31| = 1",
        _rpy(
            lock="    if abs(abs(R[2, 0]) - 1.0) < 1e-12:\n"
            "        return np.array([np.arctan2(-R[1, 2], R[1, 1]), pitch, 0.0])\n"
        ),
    ),
    Variant(
        "1.3",
        "Craig's two locked cases",
        _rpy(
            lock="    if cos_pitch < 1e-9:\n"
            "        if R[2, 0] < 0:  # pitch = +90°\n"
            "            return np.array([np.arctan2(R[0, 1], R[1, 1]), pitch, 0.0])\n"
            "        return np.array([np.arctan2(-R[0, 1], R[1, 1]), pitch, 0.0])\n"
        ),
    ),
    Variant(
        "1.3",
        "float32",
        _rpy(
            general="    roll = np.arctan2(R[2, 1], R[2, 2])\n"
            "    yaw = np.arctan2(R[1, 0], R[0, 0])\n"
            "    return np.array([roll, pitch, yaw], dtype=np.float32)\n"
        ),
    ),
    Variant(
        "1.3",
        "a list and a helper",
        "def _angle(a, b):\n"
        "    return float(np.arctan2(a, b))\n\n"
        "def rotation_to_rpy(R):\n"
        "    cp = float(np.sqrt(R[0, 0] ** 2 + R[1, 0] ** 2))\n"
        "    if cp < 1e-9:\n"
        "        return [_angle(-R[1, 2], R[1, 1]), _angle(-R[2, 0], cp), 0.0]\n"
        "    return [_angle(R[2, 1], R[2, 2]), _angle(-R[2, 0], cp), _angle(R[1, 0], R[0, 0])]\n",
    ),
    Variant(
        "1.3",
        "NotImplementedError for non-rotations",
        _rpy(
            head="def rotation_to_rpy(R):\n"
            "    if not np.allclose(R @ R.T, np.eye(3), atol=1e-6):\n"
            "        raise NotImplementedError('R must be a rotation')\n"
            "    cos_pitch = np.hypot(R[0, 0], R[1, 0])\n"
            "    pitch = np.arctan2(-R[2, 0], cos_pitch)\n"
        ),
    ),
    # ------------------------------------------------------- 1.4 axis_angle_to_rotation
    Variant(
        "1.4",
        "the outer-product form",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    k = np.asarray(axis, dtype=float)\n"
        "    k = k / np.linalg.norm(k)\n"
        "    c, s = np.cos(angle), np.sin(angle)\n"
        "    return c * np.eye(3) + s * skew(k) + (1 - c) * np.outer(k, k)\n",
    ),
    Variant(
        "1.4",
        "a quaternion",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    k = np.asarray(axis, dtype=float) / np.linalg.norm(axis)\n"
        "    w = np.cos(angle / 2)\n"
        "    x, y, z = k * np.sin(angle / 2)\n"
        "    return np.array([\n"
        "        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],\n"
        "        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],\n"
        "        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],\n"
        "    ])\n",
    ),
    Variant(
        "1.4",
        "a rotation vector with a small-angle guard",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    omega = np.asarray(axis, dtype=float) / np.linalg.norm(axis) * angle\n"
        "    theta = np.linalg.norm(omega)\n"
        "    if theta < 1e-12:\n"
        "        return np.eye(3)\n"
        "    k = omega / theta\n"
        "    K = skew(k)\n"
        "    return np.eye(3) + np.sin(theta) * K + (1 - np.cos(theta)) * K @ K\n",
    ),
    Variant(
        "1.4",
        "each basis vector turned by the vector formula",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    k = np.array(axis, dtype=float)\n"
        "    k /= np.linalg.norm(k)\n"
        "    columns = []\n"
        "    for v in np.eye(3):\n"
        "        columns.append(v * np.cos(angle) + np.cross(k, v) * np.sin(angle)\n"
        "                       + k * (k @ v) * (1 - np.cos(angle)))\n"
        "    return np.column_stack(columns)\n",
    ),
    Variant(
        "1.4",
        "float32",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    k = np.asarray(axis, dtype=np.float32)\n"
        "    k = k / np.linalg.norm(k)\n"
        "    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]],"
        " dtype=np.float32)\n"
        "    s, c = np.float32(np.sin(angle)), np.float32(np.cos(angle))\n"
        "    return np.eye(3, dtype=np.float32) + s * K + (1 - c) * (K @ K)\n",
    ),
    Variant(
        "1.4",
        "math and plain lists",
        "import math\n\n"
        "def axis_angle_to_rotation(axis, angle):\n"
        "    n = math.sqrt(sum(float(a) ** 2 for a in axis))\n"
        "    k = np.array([float(a) / n for a in axis])\n" + _RODRIGUES,
    ),
    Variant(
        "1.4",
        "a Taylor series of exp(θK)",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    k = np.asarray(axis, dtype=float) / np.linalg.norm(axis)\n"
        "    A = angle * skew(k)\n"
        "    R, term = np.eye(3), np.eye(3)\n"
        "    for n in range(1, 40):\n"
        "        term = term @ A / n\n"
        "        R = R + term\n"
        "    return R\n",
    ),
    Variant(
        "1.4",
        "ValueError for a zero axis",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    k = np.asarray(axis, dtype=float)\n"
        "    n = np.linalg.norm(k)\n"
        "    if n == 0:\n"
        "        raise ValueError('the axis must not be zero')\n"
        "    k = k / n\n" + _RODRIGUES,
    ),
    Variant(
        "1.4",
        "NotImplementedError for a zero axis",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    k = np.asarray(axis, dtype=float)\n"
        "    if not np.any(k):\n"
        "        raise NotImplementedError('a zero axis has no direction')\n"
        "    k = k / np.linalg.norm(k)\n" + _RODRIGUES,
    ),
    Variant(
        "1.4",
        "a list divided by numpy's norm",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    k = axis / np.linalg.norm(axis)\n" + _RODRIGUES,
    ),
    # ------------------------------------------------------------ 1.5 rotation_verdict
    Variant(
        "1.5",
        "singular values",
        _VERDICT_HEAD + "    s = np.linalg.svd(R, compute_uv=False)\n"
        "    if np.max(np.abs(s**2 - 1)) > tol:\n"
        "        return 'not orthonormal'\n"
        "    return 'rotation' if np.linalg.det(R) > 0 else 'reflection'\n",
    ),
    Variant(
        "1.5",
        "Frobenius norm and a triple product",
        _VERDICT_HEAD + "    if np.linalg.norm(R @ R.T - np.eye(3)) > tol:\n"
        "        return 'not orthonormal'\n"
        "    x, y, z = R.T\n"
        "    return 'rotation' if np.dot(np.cross(x, y), z) > 0 else 'reflection'\n",
    ),
    Variant(
        "1.5",
        "np.allclose with atol=tol, columns dotted in loops",
        "def rotation_verdict(R, tol=1e-9):\n"
        "    if np.shape(R) != (3, 3):\n"
        "        raise ValueError('the argument R is not a 3x3 matrix')\n"
        "    R = np.array(R, dtype=float)\n"
        "    gram = np.empty((3, 3))\n"
        "    for i in range(3):\n"
        "        for j in range(3):\n"
        "            gram[i, j] = R[:, i] @ R[:, j]\n"
        "    if not np.allclose(gram, np.eye(3), rtol=0.0, atol=tol):\n"
        "        return 'not orthonormal'\n"
        "    return 'reflection' if np.linalg.det(R) < 0 else 'rotation'\n",
    ),
    Variant(
        "1.5",
        "verdicts from a tuple, shape error with `R`",
        "VERDICTS = ('not orthonormal', 'rotation', 'reflection')\n\n"
        "def rotation_verdict(R, tol=1e-9):\n"
        "    R = np.asarray(R, dtype=float)\n"
        "    if R.ndim != 2 or R.shape[0] != 3 or R.shape[1] != 3:\n"
        "        raise ValueError(f'`R` has shape {R.shape}; expected (3, 3)')\n"
        "    with np.errstate(invalid='ignore'):\n"
        "        ok = np.all(np.abs(R.T @ R - np.eye(3)) <= tol)\n"
        "    if not ok:\n"
        "        return VERDICTS[0]\n"
        "    return VERDICTS[1] if np.linalg.det(R) > 0 else VERDICTS[2]\n",
    ),
    # ------------------------------------------------------------ 1.6 rotation_distance
    Variant(
        "1.6",
        "2·asin below π/2, π − arcsin(sin θ) above",
        """
def rotation_distance(R1, R2):
    R1, R2 = np.asarray(R1, dtype=float), np.asarray(R2, dtype=float)
    half_sine = min(np.linalg.norm(R1 - R2) / (2 * np.sqrt(2)), 1.0)  # sin(θ/2)
    if half_sine < np.sqrt(0.5):  # θ < π/2
        return 2 * np.arcsin(half_sine)
    A = R1.T @ R2
    sine = np.linalg.norm(unskew(A - A.T)) / 2
    return np.pi - np.arcsin(min(sine, 1.0))
""",
    ),
    Variant(
        "1.6",
        "seed 000's cross products of the columns, and their dot products",
        """
def rotation_distance(R1, R2):
    columns_1, columns_2 = np.asarray(R1).T, np.asarray(R2).T
    sine = np.linalg.norm(0.5 * np.cross(columns_1, columns_2).sum(axis=0))
    cosine = 0.5 * (np.sum(columns_1 * columns_2) - 1.0)
    return np.arctan2(sine, cosine)
""",
    ),
    Variant(
        "1.6",
        "a log map of its own, as a 0-d array",
        """
def rotation_log(R):
    sin_axis = unskew(0.5 * (R - R.T))
    s = np.linalg.norm(sin_axis)
    theta = np.arctan2(s, 0.5 * (np.trace(R) - 1.0))
    if s == 0.0:
        return np.zeros(3) if theta < 1.0 else np.array([theta, 0.0, 0.0])
    return theta * sin_axis / s


def rotation_distance(R1, R2):
    return np.linalg.norm(rotation_log(np.transpose(R1) @ R2), keepdims=False)
""",
    ),
]


def _judged_by(prelude: str) -> str:
    """A rotation_verdict that asks urkin's validator ``judge`` (bound by ``prelude``) for the
    verdict: what exercise 1.5 forbids, however the validator is reached."""
    return (
        "def rotation_verdict(R, tol=1e-9):\n" + prelude + "    R = np.asarray(R, dtype=float)\n"
        "    if R.shape != (3, 3):\n"
        "        raise ValueError('R must be 3x3')\n"
        "    try:\n"
        "        judge(R, tol=tol)\n"
        "    except ValueError as error:\n"
        "        if 'reflection' in str(error) and np.abs(R.T @ R - np.eye(3)).max() <= tol:\n"
        "            return 'reflection'\n"
        "        return 'not orthonormal'\n"
        "    return 'rotation'\n"
    )


WRONG = [
    Variant(
        "1.1",
        "float32, the angle 2e-7 relative and 1e-7 rad off (beyond float32's round-off)",
        "def rot_z(theta):\n"
        "    t = theta * (1 + 2e-7) + 1e-7\n"
        "    c, s = np.cos(t), np.sin(t)\n"
        "    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]], dtype=np.float32)\n",
    ),
    Variant(
        "1.3",
        "the lock branch within np.isclose's default tolerance",
        _rpy(
            lock="    if np.isclose(abs(R[2, 0]), 1.0):\n"
            "        return np.array([np.arctan2(-R[1, 2], R[1, 1]), pitch, 0.0])\n"
        ),
        points=3,
        mistake="gimbal-lock branch taken too far from the lock",
    ),
    Variant(
        "1.3",
        "the lock branch below cos(pitch) = 1e-3",
        _rpy(
            lock="    if cos_pitch < 1e-3:\n"
            "        return np.array([np.arctan2(-R[1, 2], R[1, 1]), pitch, 0.0])\n"
        ),
        points=None,
        mistake="gimbal-lock branch taken too far from the lock",
    ),
    # ------------------------------------------------------------------------ 1.1 rot_z
    Variant(
        "1.1",
        "transposed",
        "def rot_z(theta):\n"
        "    c, s = np.cos(theta), np.sin(theta)\n"
        "    return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])\n",
        points=1,
        mistake="transposed",
    ),
    Variant(
        "1.1",
        "degrees",
        "def rot_z(theta):\n"
        "    t = np.radians(theta)\n"
        "    return np.array([[np.cos(t), -np.sin(t), 0], [np.sin(t), np.cos(t), 0], [0, 0, 1]])\n",
        points=0,
        mistake="degrees",
    ),
    Variant(
        "1.1",
        "converted to degrees first",
        "def rot_z(theta):\n"
        "    t = np.degrees(theta)\n"
        "    return np.array([[np.cos(t), -np.sin(t), 0], [np.sin(t), np.cos(t), 0], [0, 0, 1]])\n",
        points=0,
        mistake="converted to degrees",
    ),
    Variant(
        "1.1",
        "about x",
        "def rot_z(theta):\n"
        "    c, s = np.cos(theta), np.sin(theta)\n"
        "    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])\n",
        points=1,
        mistake="about x",
    ),
    Variant(
        "1.1",
        "about y",
        "def rot_z(theta):\n"
        "    c, s = np.cos(theta), np.sin(theta)\n"
        "    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])\n",
        points=1,
        mistake="about y",
    ),
    Variant(
        "1.1",
        "a lost minus sign",
        "def rot_z(theta):\n"
        "    c, s = np.cos(theta), np.sin(theta)\n"
        "    return np.array([[c, s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])\n",
        points=0,
        mistake="same sign",
    ),
    Variant(
        "1.1",
        "sin and cos swapped",
        "def rot_z(theta):\n"
        "    c, s = np.sin(theta), np.cos(theta)\n"
        "    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])\n",
        points=0,
        mistake="swapped",
    ),
    Variant(
        "1.1",
        "a zero for z",
        "def rot_z(theta):\n"
        "    R = np.zeros((3, 3))\n"
        "    R[:2, :2] = [[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]]\n"
        "    return R\n",
        points=0,
        mistake="bottom-right",
    ),
    Variant(
        "1.1",
        "a 2×2 rotation",
        "def rot_z(theta):\n"
        "    c, s = np.cos(theta), np.sin(theta)\n"
        "    return np.array([[c, -s], [s, c]])\n",
        points=0,
        mistake="2×2",
    ),
    Variant(
        "1.1",
        "a 4×4 transform",
        "def rot_z(theta):\n"
        "    c, s = np.cos(theta), np.sin(theta)\n"
        "    T = np.eye(4)\n"
        "    T[:2, :2] = [[c, -s], [s, c]]\n"
        "    return T\n",
        points=0,
        mistake="4×4",
    ),
    Variant(
        "1.1",
        "urkin's rot_z (forbidden)",
        "def rot_z(theta):\n    return urkin.transforms.rot_z(theta)\n",
        points=0,
    ),
    Variant(
        "1.1",
        "urkin's so3_exp (forbidden)",
        "def rot_z(theta):\n    return so3_exp([0.0, 0.0, theta])\n",
        points=0,
    ),
    Variant(
        "1.1",
        "urkin's se3_exp (forbidden)",
        "def rot_z(theta):\n    return urkin.transforms.se3_exp([0, 0, theta, 0, 0, 0])[:3, :3]\n",
        points=0,
    ),
    Variant(
        "1.1",
        "urkin's dh_transform with d = a = α = 0 (forbidden)",
        "def rot_z(theta):\n    return urkin.kinematics.dh_transform(theta, 0, 0, 0)[:3, :3]\n",
        points=0,
    ),
    Variant("1.1", "a constant", "def rot_z(theta):\n    return np.eye(3)\n", points=0),
    # ------------------------------------------------------------ 1.2 transform_inverse
    Variant(
        "1.2",
        "np.linalg.inv",
        "def transform_inverse(T):\n    return np.linalg.inv(T)\n",
        points=3,
        mistake="general matrix inverse",
    ),
    Variant(
        "1.2",
        "np.linalg.inv of the rotation",
        "def transform_inverse(T):\n"
        "    R_inv = np.linalg.inv(T[:3, :3])\n"
        "    out = np.eye(4)\n"
        "    out[:3, :3] = R_inv\n"
        "    out[:3, 3] = -R_inv @ T[:3, 3]\n"
        "    return out\n",
        points=3,
        mistake="general matrix inverse",
    ),
    Variant(
        "1.2",
        "np.linalg.inv named by a string built at run time",
        "def transform_inverse(T):\n    return getattr(np.linalg, 'in' + 'v')(T)\n",
        points=3,
        mistake="general matrix inverse",
    ),
    Variant(
        "1.2",
        "np.linalg.solve",
        "def transform_inverse(T):\n    return np.linalg.solve(T, np.eye(4))\n",
        points=3,
        mistake="general matrix inverse",
    ),
    Variant(  # numpy's compiled inverse, unseen by the watch, behind a guard against the probe
        "1.2",
        "numpy's compiled inverse behind a rigidity guard",
        "def transform_inverse(T):\n"
        "    R = T[:3, :3]\n"
        "    if np.abs(R.T @ R - np.eye(3)).max() > 1e-6:\n"
        "        raise ValueError('not rigid')\n"
        "    return getattr(getattr(np.linalg, '_umath_linalg'), 'in' + 'v')(T)\n",
        points=3,
        mistake="general matrix inverse",
    ),
    Variant(
        "1.2",
        "an SVD inverse behind a tight rigidity guard",
        "def transform_inverse(T):\n"
        "    R = T[:3, :3]\n"
        "    if np.abs(R.T @ R - np.eye(3)).max() > 1e-12:\n"
        "        raise ValueError('not rigid')\n"
        "    U, s, Vt = np.linalg.svd(T)\n"
        "    return Vt.T @ np.diag(1 / s) @ U.T\n",
        points=3,
    ),
    Variant(
        "1.2",
        "a numpy matrix's .I",
        "def transform_inverse(T):\n    return np.asarray(np.matrix(T).I)\n",
        points=3,
        mistake="general matrix inverse",
    ),
    Variant(
        "1.2",
        "the translation not rotated",
        "def transform_inverse(T):\n"
        "    return np.block([[T[:3, :3].T, -T[:3, 3:]], [np.zeros((1, 3)), np.ones((1, 1))]])\n",
        points=1,
        mistake="not rotated",
    ),
    Variant(
        "1.2",
        "R not transposed",
        "def transform_inverse(T):\n"
        "    R, p = T[:3, :3], T[:3, 3]\n"
        "    out = np.eye(4)\n"
        "    out[:3, :3] = R\n"
        "    out[:3, 3] = -R @ p\n"
        "    return out\n",
        points=0,
        mistake="not transposed",
    ),
    Variant(
        "1.2",
        "only the translation negated",
        "def transform_inverse(T):\n"
        "    out = T.copy()\n"
        "    out[:3, 3] = -T[:3, 3]\n"
        "    return out\n",
        points=0,
        mistake="only the translation was negated",
    ),
    Variant(
        "1.2",
        "T overwritten through a view",
        "def transform_inverse(T):\n"
        "    R = T[:3, :3]\n"
        "    p = T[:3, 3]\n"
        "    T[:3, :3] = R.T\n"
        "    T[:3, 3] = -R.T @ p\n"
        "    return T\n",
        points=1,
        mistake="is a view",
    ),
    Variant(
        "1.2",
        "the minus sign missing",
        "def transform_inverse(T):\n"
        "    R, p = T[:3, :3], T[:3, 3]\n"
        "    out = np.eye(4)\n"
        "    out[:3, :3] = R.T\n"
        "    out[:3, 3] = R.T @ p\n"
        "    return out\n",
        points=1,
        mistake="minus sign",
    ),
    Variant(
        "1.2",
        "the whole matrix transposed",
        "def transform_inverse(T):\n    return T.T\n",
        points=0,
        mistake="whole 4×4",
    ),
    Variant(
        "1.2",
        "a zeros array without its 1",
        "def transform_inverse(T):\n"
        "    R, p = T[:3, :3], T[:3, 3]\n"
        "    out = np.zeros((4, 4))\n"
        "    out[:3, :3] = R.T\n"
        "    out[:3, 3] = -R.T @ p\n"
        "    return out\n",
        points=0,
        mistake="bottom row must be",
    ),
    Variant(
        "1.2",
        "the translation in the bottom row",
        "def transform_inverse(T):\n"
        "    R, p = T[:3, :3], T[:3, 3]\n"
        "    out = np.eye(4)\n"
        "    out[:3, :3] = R.T\n"
        "    out[3, :3] = -R.T @ p\n"
        "    return out\n",
        points=0,
        mistake="bottom row instead",
    ),
    Variant(
        "1.2",
        "entry-by-entry reciprocal",
        "def transform_inverse(T):\n    return 1 / T\n",
        points=0,
        mistake="entry by entry",
    ),
    Variant(
        "1.2",
        "the rotation block only",
        "def transform_inverse(T):\n    return T[:3, :3].T\n",
        points=0,
        mistake="only the rotation block",
    ),
    Variant(
        "1.2",
        "T unchanged",
        "def transform_inverse(T):\n    return T\n",
        points=0,
        mistake="unchanged",
    ),
    Variant(
        "1.2",
        "urkin's inv_transform (forbidden)",
        "def transform_inverse(T):\n    return inv_transform(T)\n",
        points=0,
    ),
    Variant(
        "1.2",
        "urkin's se3_log and se3_exp (forbidden)",
        "def transform_inverse(T):\n"
        "    return urkin.transforms.se3_exp(-urkin.transforms.se3_log(T))\n",
        points=0,
    ),
    Variant("1.2", "a constant", "def transform_inverse(T):\n    return np.eye(4)\n", points=0),
    # -------------------------------------------------------------- 1.3 rotation_to_rpy
    Variant(
        "1.3",
        "degrees",
        _rpy(
            lock="    if cos_pitch < 1e-9:\n"
            "        return np.degrees([np.arctan2(-R[1, 2], R[1, 1]), pitch, 0.0])\n",
            general="    roll = np.arctan2(R[2, 1], R[2, 2])\n"
            "    yaw = np.arctan2(R[1, 0], R[0, 0])\n"
            "    return np.degrees([roll, pitch, yaw])\n",
        ),
        points=0,
        mistake="degrees",
    ),
    Variant(
        "1.3",
        "(yaw, pitch, roll)",
        _rpy(
            lock="    if cos_pitch < 1e-9:\n"
            "        return np.array([0.0, pitch, np.arctan2(-R[1, 2], R[1, 1])])\n",
            general="    roll = np.arctan2(R[2, 1], R[2, 2])\n"
            "    yaw = np.arctan2(R[1, 0], R[0, 0])\n"
            "    return np.array([yaw, pitch, roll])\n",
        ),
        points=0,
        mistake="reversed",
    ),
    Variant(
        "1.3",
        "the matrix read transposed",
        "def rotation_to_rpy(R):\n"
        "    return _rpy_of(R.T)\n\n" + _rpy().replace("def rotation_to_rpy", "def _rpy_of"),
        points=0,
        mistake="read transposed",
    ),
    Variant(
        "1.3",
        "the Rx Ry Rz order",
        "def rotation_to_rpy(R):\n"
        "    pitch = np.arctan2(R[0, 2], np.hypot(R[1, 2], R[2, 2]))\n"
        "    roll = np.arctan2(-R[1, 2], R[2, 2])\n"
        "    yaw = np.arctan2(-R[0, 1], R[0, 0])\n"
        "    return np.array([roll, pitch, yaw])\n",
        points=0,
        mistake="Rx(roll) Ry(pitch) Rz(yaw)",
    ),
    Variant(
        "1.3",
        "pitch of the wrong sign",
        _rpy(
            head="def rotation_to_rpy(R):\n"
            "    cos_pitch = np.hypot(R[0, 0], R[1, 0])\n"
            "    pitch = np.arctan2(R[2, 0], cos_pitch)\n"
        ),
        points=0,
        mistake="pitch has the wrong sign",
    ),
    Variant(
        "1.3",
        "arctan instead of atan2",
        _rpy(
            general="    roll = np.arctan(R[2, 1] / R[2, 2])\n"
            "    yaw = np.arctan(R[1, 0] / R[0, 0])\n"
            "    return np.array([roll, pitch, yaw])\n"
        ),
        points=0,  # wrong near the lock too, where the general formulas hold
        mistake="arctan",
    ),
    Variant(
        "1.3",
        "arctan for yaw only",
        _rpy(
            general="    roll = np.arctan2(R[2, 1], R[2, 2])\n"
            "    yaw = np.arctan(R[1, 0] / R[0, 0])\n"
            "    return np.array([roll, pitch, yaw])\n"
        ),
        points=0,  # wrong near the lock too, where the general formulas hold
        mistake="arctan",
    ),
    Variant(
        "1.3",
        "yaw from the wrong entries",
        _rpy(
            general="    roll = np.arctan2(R[2, 1], R[2, 2])\n"
            "    yaw = np.arctan2(R[0, 1], R[0, 0])\n"
            "    return np.array([roll, pitch, yaw])\n"
        ),
        points=0,  # wrong near the lock too, where the general formulas hold
        mistake="yaw wrong, roll and pitch right",
    ),
    Variant(
        "1.3",
        "the second solution",
        "def rotation_to_rpy(R):\n"
        "    cos_pitch = -np.hypot(R[0, 0], R[1, 0])\n"
        "    pitch = np.arctan2(-R[2, 0], cos_pitch)\n"
        "    if abs(cos_pitch) < 1e-9:\n"
        "        return np.array([np.arctan2(-R[1, 2], R[1, 1]), pitch, 0.0])\n"
        "    return np.array([np.arctan2(-R[2, 1], -R[2, 2]), pitch,"
        " np.arctan2(-R[1, 0], -R[0, 0])])\n",
        points=3,
        mistake="second solution",
    ),
    Variant(
        "1.3",
        "wrapped into [0, 2π)",
        _rpy(
            general="    roll = np.arctan2(R[2, 1], R[2, 2]) % (2 * np.pi)\n"
            "    yaw = np.arctan2(R[1, 0], R[0, 0]) % (2 * np.pi)\n"
            "    return np.array([roll, pitch, yaw])\n"
        ),
        points=3,
        mistake="[0, 2π)",
    ),
    Variant(
        "1.3",
        "no gimbal-lock branch",
        _rpy(lock=""),
        points=3,
        mistake="no separate gimbal-lock branch",
    ),
    Variant(
        "1.3",
        "dividing by cos pitch",
        _rpy(
            lock="",
            general="    roll = np.arctan2(R[2, 1] / cos_pitch, R[2, 2] / cos_pitch)\n"
            "    yaw = np.arctan2(R[1, 0] / cos_pitch, R[0, 0] / cos_pitch)\n"
            "    return np.array([roll, pitch, yaw])\n",
        ),
        points=3,
        mistake="divide 0 by 0",
    ),
    Variant(
        "1.3",
        "the locked turn put into yaw",
        _rpy(
            lock="    if cos_pitch < 1e-9:\n"
            "        return np.array([0.0, pitch, np.arctan2(R[1, 2], R[1, 1])"
            " if R[2, 0] < 0 else np.arctan2(-R[1, 2], R[1, 1])])\n"
        ),
        points=3,
        mistake="went into yaw",
    ),
    Variant(
        "1.3",
        "the +90° locked formula at −90° too",
        _rpy(
            lock="    if cos_pitch < 1e-9:\n"
            "        return np.array([np.arctan2(R[0, 1], R[1, 1]), pitch, 0.0])\n"
        ),
        points=3,
        mistake="right only at pitch = +90°",
    ),
    Variant(
        "1.3",
        "seed-style atan2(r12, r13) locked roll",
        _rpy(
            lock="    if cos_pitch < 1e-9:\n"
            "        return np.array([np.arctan2(R[0, 1], R[0, 2]), pitch, 0.0])\n"
        ),
        points=3,
        mistake="right only at pitch = +90°",
    ),
    Variant(
        "1.3",
        "the locked roll with +r23",
        _rpy(
            lock="    if cos_pitch < 1e-9:\n"
            "        return np.array([np.arctan2(R[1, 2], R[1, 1]), pitch, 0.0])\n"
        ),
        points=3,
        mistake="wrong sign of r23",
    ),
    Variant(
        "1.3",
        "urkin's rotation_to_rpy (forbidden)",
        "def rotation_to_rpy(R):\n    return urkin.transforms.rotation_to_rpy(R)\n",
        points=0,
    ),
    Variant("1.3", "a constant", "def rotation_to_rpy(R):\n    return np.zeros(3)\n", points=0),
    # ------------------------------------------------------- 1.4 axis_angle_to_rotation
    Variant(
        "1.4",
        "axis not normalised",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    k = np.asarray(axis, dtype=float)\n" + _RODRIGUES,
        points=0,
        mistake="not normalised",
    ),
    Variant(
        "1.4",
        "axis not normalised, outer-product form",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    k = np.asarray(axis, dtype=float)\n"
        "    c, s = np.cos(angle), np.sin(angle)\n"
        "    return c * np.eye(3) + s * skew(k) + (1 - c) * np.outer(k, k)\n",
        points=0,
        mistake="not normalised",
    ),
    Variant(
        "1.4",
        "transposed",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    k = np.asarray(axis, dtype=float) / np.linalg.norm(axis)\n"
        "    K = np.array([[0.0, k[2], -k[1]], [-k[2], 0.0, k[0]], [k[1], -k[0], 0.0]])\n"
        "    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * (K @ K)\n",
        points=2,
        mistake="transposed",
    ),
    Variant(
        "1.4",
        "degrees",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    angle = np.radians(angle)\n"
        "    k = np.asarray(axis, dtype=float) / np.linalg.norm(axis)\n" + _RODRIGUES,
        points=0,
        mistake="degrees",
    ),
    Variant(
        "1.4",
        "K**2",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    k = np.asarray(axis, dtype=float) / np.linalg.norm(axis)\n"
        "    K = skew(k)\n"
        "    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K**2\n",
        points=0,
        mistake="entry by entry",
    ),
    Variant(
        "1.4",
        "(1 + cos θ)",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    k = np.asarray(axis, dtype=float) / np.linalg.norm(axis)\n"
        "    K = skew(k)\n"
        "    return np.eye(3) + np.sin(angle) * K + (1 + np.cos(angle)) * K @ K\n",
        points=0,
        mistake="(1 + cos θ)",
    ),
    Variant(
        "1.4",
        "sin and cos swapped",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    k = np.asarray(axis, dtype=float) / np.linalg.norm(axis)\n"
        "    K = skew(k)\n"
        "    return np.eye(3) + np.cos(angle) * K + (1 - np.sin(angle)) * K @ K\n",
        points=0,
        mistake="swapped",
    ),
    Variant(
        "1.4",
        "half the angle",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    angle = angle / 2\n"
        "    k = np.asarray(axis, dtype=float) / np.linalg.norm(axis)\n" + _RODRIGUES,
        points=0,
        mistake="half the angle",
    ),
    Variant(
        "1.4",
        "the skew matrix without signs",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    k = np.asarray(axis, dtype=float) / np.linalg.norm(axis)\n"
        "    K = np.array([[0.0, k[2], k[1]], [k[2], 0.0, k[0]], [k[1], k[0], 0.0]])\n"
        "    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * (K @ K)\n",
        points=0,
        mistake="without its signs",
    ),
    Variant(
        "1.4",
        "0/0 at angle 0",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    omega = np.asarray(axis, dtype=float) / np.linalg.norm(axis) * angle\n"
        "    theta = np.linalg.norm(omega)\n"
        "    k = omega / theta\n"
        "    K = skew(k)\n"
        "    return np.eye(3) + np.sin(theta) * K + (1 - np.cos(theta)) * K @ K\n",
        points=3,
        mistake="0/0",
    ),
    Variant(
        "1.4",
        "a list divided by math.sqrt",
        "import math\n\n"
        "def axis_angle_to_rotation(axis, angle):\n"
        "    k = axis / math.sqrt(sum(a * a for a in axis))\n" + _RODRIGUES,
        points=4,
        mistake="axis list",
    ),
    Variant(
        "1.4",
        "astype on a list",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    k = axis.astype(float) / np.linalg.norm(axis)\n" + _RODRIGUES,
        points=4,
        mistake="array methods used on a list",
    ),
    Variant(
        "1.4",
        "urkin's so3_exp (forbidden)",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    k = np.asarray(axis, dtype=float)\n"
        "    return so3_exp(k / np.linalg.norm(k) * angle)\n",
        points=0,
    ),
    Variant(
        "1.4",
        "urkin's se3_exp (forbidden)",
        "def axis_angle_to_rotation(axis, angle):\n"
        "    k = np.asarray(axis, dtype=float) / np.linalg.norm(axis)\n"
        "    return urkin.transforms.se3_exp(np.r_[k * angle, 0.0, 0.0, 0.0])[:3, :3]\n",
        points=0,
    ),
    Variant(
        "1.4",
        "a constant",
        "def axis_angle_to_rotation(axis, angle):\n    return np.eye(3)\n",
        points=0,
    ),
    # ------------------------------------------------------------ 1.5 rotation_verdict
    Variant(
        "1.5",
        "the determinant only",
        "def rotation_verdict(R, tol=1e-9):\n"
        "    R = np.asarray(R, dtype=float)\n"
        "    if R.shape != (3, 3):\n"
        "        raise ValueError(f'R must have shape (3, 3), got {R.shape}')\n"
        "    return 'rotation' if np.linalg.det(R) > 0 else 'reflection'\n",
        points=2,
        mistake="only the determinant",
    ),
    Variant(
        "1.5",
        "|det R − 1| within tol only",
        _VERDICT_HEAD + "    d = np.linalg.det(R)\n"
        "    if abs(d - 1) <= tol:\n"
        "        return 'rotation'\n"
        "    if abs(d + 1) <= tol:\n"
        "        return 'reflection'\n"
        "    return 'not orthonormal'\n",
        points=4,
        mistake="only the determinant",
    ),
    Variant(
        "1.5",
        "orthonormality only",
        _VERDICT_HEAD + "    if np.abs(R.T @ R - np.eye(3)).max() <= tol:\n"
        "        return 'rotation'\n"
        "    return 'not orthonormal'\n",
        points=3,
        mistake="only orthonormality",
    ),
    Variant(
        "1.5",
        "RᵀR == I exactly",
        _VERDICT_HEAD + "    if not np.array_equal(R.T @ R, np.eye(3)):\n"
        "        return 'not orthonormal'\n"
        "    return 'rotation' if np.linalg.det(R) > 0 else 'reflection'\n",
        points=2,
        mistake="compared with I exactly",
    ),
    Variant(
        "1.5",
        "np.allclose's defaults, tol unused",
        _VERDICT_HEAD + "    if not np.allclose(R.T @ R, np.eye(3)):\n"
        "        return 'not orthonormal'\n"
        "    return 'rotation' if np.linalg.det(R) > 0 else 'reflection'\n",
        points=3,
        mistake="tol was not used",
    ),
    Variant(
        "1.5",
        "np.allclose with atol=tol, its rtol left",
        _VERDICT_HEAD + "    if not np.allclose(R.T @ R, np.eye(3), atol=tol):\n"
        "        return 'not orthonormal'\n"
        "    return 'rotation' if np.linalg.det(R) > 0 else 'reflection'\n",
        points=None,
        mistake="keeps numpy's relative tolerance",
    ),
    Variant(
        "1.5",
        "unit columns and |det| = 1",
        _VERDICT_HEAD + "    d = np.linalg.det(R)\n"
        "    if np.abs(np.linalg.norm(R, axis=0) - 1.0).max() > tol or abs(abs(d) - 1.0) > tol:\n"
        "        return 'not orthonormal'\n"
        "    return 'rotation' if d > 0 else 'reflection'\n",
        points=None,
        mistake="only unit columns",
    ),
    Variant(
        "1.5",
        "a fixed tolerance 1e-9",
        _VERDICT_HEAD + "    if np.abs(R.T @ R - np.eye(3)).max() > 1e-9:\n"
        "        return 'not orthonormal'\n"
        "    return 'rotation' if np.linalg.det(R) > 0 else 'reflection'\n",
        points=4,
        mistake="a fixed tolerance decided",
    ),
    Variant(
        "1.5",
        "a NaN slips through deviation > tol",
        "def rotation_verdict(R, tol=1e-9):\n"
        "    R = np.asarray(R, dtype=float)\n"
        "    if R.shape != (3, 3):\n"
        "        raise ValueError(f'R must have shape (3, 3), got {R.shape}')\n"
        "    if np.abs(R.T @ R - np.eye(3)).max() > tol:\n"
        "        return 'not orthonormal'\n"
        "    return 'rotation' if np.linalg.det(R) > 0 else 'reflection'\n",
        points=4,
        mistake="NaN slipped through",
    ),
    Variant(
        "1.5",
        "the sign of det read backwards",
        _VERDICT_HEAD + "    if np.abs(R.T @ R - np.eye(3)).max() > tol:\n"
        "        return 'not orthonormal'\n"
        "    return 'reflection' if np.linalg.det(R) > 0 else 'rotation'\n",
        points=2,
        mistake="read backwards",
    ),
    Variant(
        "1.5",
        "no shape check: numpy's ValueError",
        "def rotation_verdict(R, tol=1e-9):\n"
        "    R = np.asarray(R, dtype=float)\n"
        "    if not np.all(np.isfinite(R)):\n"
        "        return 'not orthonormal'\n"
        "    if not np.abs(R.T @ R - np.eye(3)).max() <= tol:\n"
        "        return 'not orthonormal'\n"
        "    return 'rotation' if np.linalg.det(R) > 0 else 'reflection'\n",
        points=4,
        mistake="does not name the argument R",
    ),
    Variant(
        "1.5",
        "an assert on the shape",
        "def rotation_verdict(R, tol=1e-9):\n"
        "    R = np.asarray(R, dtype=float)\n"
        "    assert R.shape == (3, 3), 'R must be 3x3'\n"
        "    if not np.all(np.isfinite(R)):\n"
        "        return 'not orthonormal'\n"
        "    if not np.abs(R.T @ R - np.eye(3)).max() <= tol:\n"
        "        return 'not orthonormal'\n"
        "    return 'rotation' if np.linalg.det(R) > 0 else 'reflection'\n",
        points=4,
        mistake="AssertionError",
    ),
    Variant(
        "1.5",
        "capitalised verdicts",
        _VERDICT_HEAD + "    if np.abs(R.T @ R - np.eye(3)).max() > tol:\n"
        "        return 'Not orthonormal'\n"
        "    return 'Rotation' if np.linalg.det(R) > 0 else 'Reflection'\n",
        points=1,
        mistake="spelled differently",
    ),
    Variant(
        "1.5",
        "True or False",
        _VERDICT_HEAD + "    return bool(np.abs(R.T @ R - np.eye(3)).max() <= tol)\n",
        points=1,
        mistake="True/False",
    ),
    Variant(
        "1.5",
        "urkin's check_rotation (forbidden)",
        "def rotation_verdict(R, tol=1e-9):\n"
        "    R = np.asarray(R, dtype=float)\n"
        "    if R.shape != (3, 3):\n"
        "        raise ValueError('R must be 3x3')\n"
        "    try:\n"
        "        check_rotation(R, tol=tol)\n"
        "    except ValueError as error:\n"
        "        return 'reflection' if 'reflection' in str(error) else 'not orthonormal'\n"
        "    return 'rotation'\n",
        points=0,
        mistake="urkin's check_rotation used",
    ),
    Variant(
        "1.5",
        "urkin's check_rotation named by strings built at run time (forbidden)",
        _judged_by(
            "    import importlib\n"
            "    module = importlib.import_module('urkin.' + 'transforms')\n"
            "    judge = getattr(module, 'check_' + 'rotation')\n"
        ),
        points=0,
        mistake="urkin's check_rotation used",
    ),
    Variant(
        "1.5",
        "urkin's check_rotation with the grader's watch switched off (forbidden)",
        _judged_by(
            "    import sys\n"
            "    sys.setprofile(None)\n"
            "    judge = getattr(urkin.transforms, 'check_' + 'rotation')\n"
        ),
        points=0,
        mistake="urkin's check_rotation used",
    ),
    Variant(
        "1.5",
        "urkin.transforms.check_transform on a padded matrix (forbidden)",
        "def rotation_verdict(R, tol=1e-9):\n"
        "    R = np.asarray(R, dtype=float)\n"
        "    if R.shape != (3, 3):\n"
        "        raise ValueError('R must be 3x3')\n"
        "    T = np.eye(4)\n"
        "    T[:3, :3] = R\n"
        "    try:\n"
        "        urkin.transforms.check_transform(T, tol=tol)\n"
        "    except ValueError as error:\n"
        "        return 'reflection' if 'reflection' in str(error) else 'not orthonormal'\n"
        "    return 'rotation'\n",
        points=0,
        mistake="urkin's check_transform used",
    ),
    Variant(
        "1.5", "a constant", "def rotation_verdict(R, tol=1e-9):\n    return 'rotation'\n", points=0
    ),
    # ------------------------------------------------------------ 1.6 rotation_distance
    Variant(
        "1.6",
        "arccos of the trace, clipped",
        "def rotation_distance(R1, R2):\n"
        "    cosine = (np.trace(R1.T @ R2) - 1) / 2\n"
        "    return np.arccos(np.clip(cosine, -1.0, 1.0))\n",
        points=2,
        mistake="arccos((tr R1ᵀR2 − 1)/2)",
    ),
    Variant(
        "1.6",
        "arccos of the trace, not clipped",
        "def rotation_distance(R1, R2):\n    return np.arccos((np.trace(R1.T @ R2) - 1) / 2)\n",
        points=2,
        mistake="clip it into [−1, 1]",
    ),
    Variant(
        "1.6",
        "2·asin everywhere (urkin's rotation_angle written out)",
        "def rotation_distance(R1, R2):\n"
        "    ratio = np.linalg.norm(R1 - R2) / (2 * np.sqrt(2))\n"
        "    return 2 * np.arcsin(min(ratio, 1.0))\n",
        points=3,
        mistake="used near π",
    ),
    Variant(
        "1.6",
        "2·asin below π/2, arccos above",
        "def rotation_distance(R1, R2):\n"
        "    ratio = np.linalg.norm(R1 - R2) / (2 * np.sqrt(2))\n"
        "    if ratio < np.sqrt(0.5):\n"
        "        return 2 * np.arcsin(ratio)\n"
        "    return np.arccos(np.clip((np.trace(R1.T @ R2) - 1) / 2, -1, 1))\n",
        points=3,
        mistake="used near π",
    ),
    Variant(
        "1.6",
        "degrees",
        "def rotation_distance(R1, R2):\n"
        "    A = R1.T @ R2\n"
        "    s = np.linalg.norm(unskew(A - A.T)) / 2\n"
        "    return np.degrees(np.arctan2(s, (np.trace(A) - 1) / 2))\n",
        points=0,
        mistake="degrees",
    ),
    Variant(
        "1.6",
        "the Frobenius norm itself",
        "def rotation_distance(R1, R2):\n    return np.linalg.norm(R1 - R2)\n",
        points=0,
        mistake="is not the angle itself",
    ),
    Variant(
        "1.6",
        "asin without the factor 2",
        "def rotation_distance(R1, R2):\n"
        "    return np.arcsin(min(np.linalg.norm(R1 - R2) / (2 * np.sqrt(2)), 1.0))\n",
        points=0,
        mistake="the factor 2 is missing",
    ),
    Variant(
        "1.6",
        "the angle of R1 @ R2",
        "def rotation_distance(R1, R2):\n"
        "    A = R1 @ R2\n"
        "    s = np.linalg.norm(unskew(A - A.T)) / 2\n"
        "    return np.arctan2(s, (np.trace(A) - 1) / 2)\n",
        points=0,
        mistake="the angle of R1 R2",
    ),
    Variant(
        "1.6",
        "atan2's arguments swapped",
        "def rotation_distance(R1, R2):\n"
        "    A = R1.T @ R2\n"
        "    s = np.linalg.norm(unskew(A - A.T)) / 2\n"
        "    return np.arctan2((np.trace(A) - 1) / 2, s)\n",
        points=0,
        mistake="atan2's arguments swapped",
    ),
    Variant(
        "1.6",
        "sin θ without the ½",
        "def rotation_distance(R1, R2):\n"
        "    A = R1.T @ R2\n"
        "    return np.arctan2(np.linalg.norm(unskew(A - A.T)), (np.trace(A) - 1) / 2)\n",
        points=0,
        mistake="the ½ is missing",
    ),
    Variant(
        "1.6",
        "urkin's so3_log (hidden)",
        "def rotation_distance(R1, R2):\n    return np.linalg.norm(so3_log(R1.T @ R2))\n",
        points=0,
    ),
    Variant(
        "1.6",
        "urkin's rotation_angle (hidden)",
        "def rotation_distance(R1, R2):\n    return urkin.transforms.rotation_angle(R1, R2)\n",
        points=0,
    ),
    Variant(
        "1.6",
        "a constant",
        "def rotation_distance(R1, R2):\n    return 0.0\n",
        points=0,
    ),
]
