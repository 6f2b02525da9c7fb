"""Lesson 03 — product of exponentials: correct and wrong versions of the exercise functions."""

from tests.variants import Variant

CORRECT = [
    # ------------------------------------------------------------------------------ 3.1
    Variant(
        "3.1",
        "q × ω with hstack",
        """
def screw_axis(w, q):
    w = np.array(w, dtype=float)
    return np.hstack((w, np.cross(q, w)))
""",
    ),
    Variant(
        "3.1",
        "cross product by hand, a list",
        """
def screw_axis(w, q):
    wx, wy, wz = w
    qx, qy, qz = q
    cross = [wy * qz - wz * qy, wz * qx - wx * qz, wx * qy - wy * qx]
    return [wx, wy, wz, -cross[0], -cross[1], -cross[2]]
""",
    ),
    Variant(
        "3.1",
        "skew matrix helper",
        """
def hat(w):
    return np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


def screw_axis(w, q):
    omega = np.asarray(w, dtype=float)
    v = -hat(omega) @ np.asarray(q, dtype=float)
    return np.concatenate([omega, v])
""",
    ),
    Variant(
        "3.1",
        "float32",
        """
def screw_axis(w, q):
    w = np.asarray(w, dtype=np.float32)
    q = np.asarray(q, dtype=np.float32)
    return np.concatenate([w, -np.cross(w, q)]).astype(np.float32)
""",
    ),
    Variant(
        "3.1",
        "normalises w, foot of the perpendicular, urkin's skew",
        """
from urkin.transforms import skew as cross_matrix


def screw_axis(w, q):
    w = np.asarray(w, dtype=float)
    w = w / np.linalg.norm(w)
    q = np.asarray(q, dtype=float)
    foot = q - np.dot(q, w) * w  # the point of the axis nearest the origin
    S = np.zeros(6)
    S[:3] = w
    S[3:] = -cross_matrix(w) @ foot
    return S
""",
    ),
    # ------------------------------------------------------------------------------ 3.2
    Variant(
        "3.2",
        "own skew, explicit R and G",
        """
def twist_exp(S, theta):
    S = np.asarray(S, dtype=float)
    w, v = S[:3], S[3:]
    W = np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])
    R = np.eye(3) + np.sin(theta) * W + (1 - np.cos(theta)) * W @ W
    G = np.eye(3) * theta + (1 - np.cos(theta)) * W + (theta - np.sin(theta)) * W @ W
    return np.vstack([np.hstack([R, (G @ v)[:, None]]), [0.0, 0.0, 0.0, 1.0]])
""",
    ),
    Variant(
        "3.2",
        "the series, summed to 60 terms",
        """
def twist_exp(S, theta):
    S = np.asarray(S, dtype=float)
    A = np.zeros((4, 4))
    A[:3, :3] = skew(S[:3]) * theta
    A[:3, 3] = S[3:] * theta
    total, term = np.eye(4), np.eye(4)
    for k in range(1, 60):
        term = term @ A / k
        total = total + term
    return total
""",
    ),
    Variant(
        "3.2",
        "scaling and squaring",
        """
def twist_exp(S, theta):
    S = np.asarray(S, dtype=float)
    A = np.zeros((4, 4))
    A[:3, :3] = skew(S[:3]) * theta
    A[:3, 3] = S[3:] * theta
    halvings = 6
    A = A / 2**halvings
    total, term = np.eye(4), np.eye(4)
    for k in range(1, 16):
        term = term @ A / k
        total = total + term
    for _ in range(halvings):
        total = total @ total
    return total
""",
    ),
    Variant(
        "3.2",
        "geometric: Trans(q) Rot Trans(−q) with q = ω × v",
        """
def twist_exp(S, theta):
    w, v = np.asarray(S[:3], dtype=float), np.asarray(S[3:], dtype=float)
    R = so3_exp(w * theta)
    point = np.cross(w, v)  # the point of the axis nearest the origin
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = (np.eye(3) - R) @ point
    return T
""",
    ),
    Variant(
        "3.2",
        "outer-product Rodrigues, float32",
        """
def twist_exp(S, theta):
    S = np.asarray(S, dtype=np.float32)
    w, v = S[:3], S[3:]
    c, s = np.cos(theta), np.sin(theta)
    W = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]], dtype=np.float32)
    R = c * np.eye(3) + s * W + (1 - c) * np.outer(w, w)
    G = theta * np.eye(3) + (1 - c) * W + (theta - s) * W @ W
    T = np.eye(4, dtype=np.float32)
    T[:3, :3] = R
    T[:3, 3] = G @ v
    return T
""",
    ),
    Variant(
        "3.2",
        "se3 formula with the angle from the norm of ω θ",
        """
def twist_exp(S, theta):
    S = np.asarray(S, dtype=float)
    omega_theta = S[:3] * theta
    angle = np.linalg.norm(omega_theta)
    if angle < 1e-12:
        T = np.eye(4)
        T[:3, 3] = S[3:] * theta
        return T
    W = skew(omega_theta / angle)
    R = np.eye(3) + np.sin(angle) * W + (1 - np.cos(angle)) * W @ W
    G = angle * np.eye(3) + (1 - np.cos(angle)) * W + (angle - np.sin(angle)) * W @ W
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = G @ (S[3:] * theta / angle)
    return T
""",
    ),
    # ------------------------------------------------------------------------------ 3.3
    Variant(
        "3.3",
        "functools.reduce",
        """
import functools


def fk_space(M, S, q):
    factors = [twist_exp(S[:, i], q[i]) for i in range(len(q))]
    return functools.reduce(np.matmul, factors + [np.asarray(M)])
""",
    ),
    Variant(
        "3.3",
        "multi_dot",
        """
def fk_space(M, S, q):
    S = np.asarray(S, dtype=float)
    return np.linalg.multi_dot([twist_exp(s, angle) for s, angle in zip(S.T, q)] + [M])
""",
    ),
    Variant(
        "3.3",
        "from M leftwards, last joint first",
        """
def fk_space(M, S, q):
    T = np.array(M, dtype=float)
    for i in reversed(range(S.shape[1])):
        T = twist_exp(S[:, i], q[i]) @ T
    return T
""",
    ),
    Variant(
        "3.3",
        "through the body axes Ad(M⁻¹) S",
        """
from urkin.transforms import adjoint, inv_transform


def fk_space(M, S, q):
    B = adjoint(inv_transform(M)) @ S
    T = np.array(M, dtype=float)
    for i in range(B.shape[1]):
        T = T @ twist_exp(B[:, i], q[i])
    return T
""",
    ),
    Variant(
        "3.3",
        "float32",
        """
def fk_space(M, S, q):
    T = np.eye(4, dtype=np.float32)
    for i in range(S.shape[1]):
        T = T @ twist_exp(S[:, i], q[i]).astype(np.float32)
    return T @ np.asarray(M, dtype=np.float32)
""",
    ),
    Variant(
        "3.3",
        "on a float32 twist_exp",
        """
def twist_exp(S, theta):
    S = np.asarray(S, dtype=np.float32)
    W = skew(S[:3]).astype(np.float32)
    s, c = np.float32(np.sin(theta)), np.float32(np.cos(theta))
    T = np.eye(4, dtype=np.float32)
    T[:3, :3] = np.eye(3) + s * W + (1 - c) * W @ W
    t = np.float32(theta)
    T[:3, 3] = (t * np.eye(3) + (1 - c) * W + (t - s) * W @ W) @ S[3:]
    return T


def fk_space(M, S, q):
    T = np.eye(4)
    for i in range(len(q)):
        T = T @ twist_exp(S[:, i], q[i])
    return T @ M
""",
    ),
    # ------------------------------------------------------------------------------ 3.4
    Variant(
        "3.4",
        "functools.reduce",
        """
from functools import reduce


def fk_body(M, B, q):
    return reduce(lambda T, i: T @ twist_exp(B[:, i], q[i]), range(len(q)), np.asarray(M))
""",
    ),
    Variant(
        "3.4",
        "multi_dot, q as a list",
        """
def fk_body(M, B, q):
    B = np.asarray(B, dtype=float)
    angles = list(q)
    return np.linalg.multi_dot([M] + [twist_exp(B[:, i], angles[i]) for i in range(len(angles))])
""",
    ),
    Variant(
        "3.4",
        "through the space axes Ad(M) B",
        """
from urkin.transforms import adjoint


def fk_body(M, B, q):
    S = adjoint(M) @ B
    T = np.eye(4)
    for i in range(S.shape[1]):
        T = T @ twist_exp(S[:, i], q[i])
    return T @ M
""",
    ),
    Variant(
        "3.4",
        "float32",
        """
def fk_body(M, B, q):
    T = np.asarray(M, dtype=np.float32)
    for axis, angle in zip(np.asarray(B).T, q):
        T = T @ twist_exp(axis, angle).astype(np.float32)
    return T
""",
    ),
    # ------------------------------------------------------------------------------ 3.5
    Variant(
        "3.5",
        "urkin's so3_log for the rotation, G by solving",
        """
from urkin.transforms import so3_log


def twist_log(T):
    T = np.asarray(T, dtype=float)
    omega_theta = so3_log(T[:3, :3])
    theta = np.linalg.norm(omega_theta)
    if theta < 1e-12:
        return np.r_[0.0, 0.0, 0.0, T[:3, 3]]
    w = omega_theta / theta
    W = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
    G = np.eye(3) * theta + (1 - np.cos(theta)) * W + (theta - np.sin(theta)) * W @ W
    return np.r_[omega_theta, np.linalg.solve(G, T[:3, 3]) * theta]
""",
    ),
    Variant(
        "3.5",
        "atan2 angle, the axis from a column of R + I near π, a list result",
        """
def twist_log(T):
    R = np.array([[float(x) for x in row[:3]] for row in T[:3]])
    p = np.array([float(T[0][3]), float(T[1][3]), float(T[2][3])])
    c = (np.trace(R) - 1) / 2
    s = 0.5 * np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    theta = np.arctan2(np.linalg.norm(s), c)
    if theta == 0.0:
        return [0.0, 0.0, 0.0, *p]
    if np.pi - theta < 1e-5:
        k = int(np.argmax(np.diag(R)))
        w = (R[:, k] + np.eye(3)[k]) / np.sqrt(2 * (1 + R[k, k]))
        if w @ s < 0:
            w = -w
    else:
        w = s / np.sin(theta)
    W = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
    G_inv = np.eye(3) / theta - W / 2 + (1 / theta - 1 / np.tan(theta / 2) / 2) * W @ W
    return [*(w * theta), *(G_inv @ p * theta)]
""",
    ),
    # ------------------------------------------------------------------------------ 3.6
    Variant(
        "3.6",
        "least squares on [ω]q = −v with q·ω = 0",
        """
def screw_to_joint(S):
    S = np.asarray(S, dtype=float)
    w, v = S[:3], S[3:]
    if not np.isclose(np.linalg.norm(w), 1.0, rtol=0.0, atol=1e-9):
        raise ValueError("S: its angular part ω must be a unit vector")
    W = np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])
    A = np.vstack([W, w])  # ω × q = −v, and q ⟂ ω
    b = np.r_[-v, 0.0]
    q, *_ = np.linalg.lstsq(A, b, rcond=None)
    return q
""",
    ),
    Variant(
        "3.6",
        "any point of the line, then projected, float32",
        """
def screw_to_joint(S):
    w = np.asarray(S[:3], dtype=np.float32)
    v = np.asarray(S[3:], dtype=np.float32)
    if abs(float(w @ w) - 1.0) > 1e-5:
        raise ValueError(f"screw axis S has |ω|² = {float(w @ w):.3f}, not 1")
    point = -np.linalg.pinv(urkin.transforms.skew(w)) @ v + 0.3 * w  # on the line
    return (point - (point @ w) * w).astype(np.float32)
""",
    ),
    # ------------------------------------------------------------------------------ 3.7
    Variant(
        "3.7",
        "the matrix form M⁻¹ [S] M, column by column",
        """
def body_from_space(S, M):
    S = np.asarray(S, dtype=float)
    M = np.asarray(M, dtype=float)
    M_inv = inv_transform(M)
    B = np.empty_like(S)
    for i in range(S.shape[1]):
        conjugated = M_inv @ twist_matrix(S[:, i]) @ M  # = [Ad(M⁻¹) S_i]
        W = conjugated[:3, :3]
        B[:, i] = [W[2, 1], W[0, 2], W[1, 0], *conjugated[:3, 3]]
    return B
""",
    ),
    Variant(
        "3.7",
        "np.block with np.linalg.inv(M), a list of columns",
        """
def body_from_space(S, M):
    T = np.linalg.inv(M)
    R, p = T[:3, :3], T[:3, 3]
    P = np.array([[0, -p[2], p[1]], [p[2], 0, -p[0]], [-p[1], p[0], 0]])
    Ad = np.block([[R, np.zeros((3, 3))], [P @ R, R]])
    columns = [Ad @ np.asarray(S)[:, i] for i in range(np.shape(S)[1])]
    return np.column_stack(columns)
""",
    ),
    Variant(
        "3.7",
        "solving Ad(M) B = S",
        """
def body_from_space(S, M):
    R, p = M[:3, :3], M[:3, 3]
    Ad_M = np.zeros((6, 6))
    Ad_M[:3, :3] = Ad_M[3:, 3:] = R
    Ad_M[3:, :3] = skew(p) @ R
    return np.linalg.solve(Ad_M, S)
""",
    ),
    Variant(
        "3.7",
        "cross products: (Rᵀω, Rᵀ(v + ω × p)), float32",
        """
def body_from_space(S, M):
    S = np.asarray(S, dtype=float)
    R, p = M[:3, :3], M[:3, 3]
    w, v = S[:3], S[3:]
    w_body = R.T @ w
    v_body = R.T @ (v + np.cross(w.T, p).T)
    return np.vstack([w_body, v_body]).astype(np.float32)
""",
    ),
    # ------------------------------------------------------------------------------ 3.8
    Variant(
        "3.8",
        "prefix chains with dh_chain, p × z",
        """
def screws_from_dh(rows):
    rows = np.asarray(rows, dtype=float)
    n = len(rows)
    chain = urkin.kinematics.dh_chain
    frames = [np.eye(4)] + [chain(rows[:k], np.zeros(k)) for k in range(1, n + 1)]
    S = np.column_stack([np.r_[F[:3, 2], np.cross(F[:3, 3], F[:3, 2])] for F in frames[:-1]])
    return S, frames[-1]
""",
    ),
    Variant(
        "3.8",
        "own link matrices and the student's screw_axis, a list",
        """
def screws_from_dh(rows):
    T = np.eye(4)
    columns = []
    for d, a, alpha in rows:
        columns.append(screw_axis(T[:3, 2], T[:3, 3]))
        ca, sa = np.cos(alpha), np.sin(alpha)
        link = np.array([[1, 0, 0, a], [0, ca, -sa, 0], [0, sa, ca, d], [0, 0, 0, 1]])
        T = T @ link
    return [np.array(columns).T, T]
""",
    ),
    Variant(
        "3.8",
        "rotations and origins kept apart, float32",
        """
def screws_from_dh(rows):
    R, p = np.eye(3), np.zeros(3)
    S = []
    for d, a, alpha in np.asarray(rows, dtype=float):
        z = R[:, 2].copy()
        S.append(np.concatenate([z, np.cross(p, z)]))
        p = p + d * R[:, 2] + a * R[:, 0]
        R = R @ urkin.transforms.rot_x(alpha)
    M = np.eye(4)
    M[:3, :3], M[:3, 3] = R, p
    return np.array(S, dtype=np.float32).T, M.astype(np.float32)
""",
    ),
]

_TWIST_V_THETA = """
def twist_exp(S, theta):
    S = np.asarray(S, dtype=float)
    T = np.eye(4)
    T[:3, :3] = so3_exp(S[:3] * theta)
    T[:3, 3] = S[3:] * theta
    return T
"""

_TWIST_LOG = """
from urkin.transforms import so3_log


def twist_log(T):
    T = np.asarray(T, dtype=float)
    wt = so3_log(T[:3, :3])
    theta = np.linalg.norm(wt)
    if theta < 1e-12:
        return np.r_[np.zeros(3), T[:3, 3]]
    w = wt / theta
    W = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
    G_inv = np.eye(3) / theta - W / 2 + (1 / theta - 0.5 / np.tan(theta / 2)) * W @ W
    return np.r_[wt, G_inv @ T[:3, 3] * theta]
"""


_SCREWS_FROM_DH = """
def screws_from_dh(rows):
    table = np.asarray(rows, dtype=float)
    T = np.eye(4)
    S = np.zeros((6, len(table)))
    for i, (d, a, alpha) in enumerate(table):
        READ
        S[:3, i], S[3:, i] = z, -np.cross(z, p)
        MOVE
    return S, T
"""


def _screws_from_dh(
    read: str = "z, p = T[:3, 2], T[:3, 3]",
    move: str = "T = T @ LINK",
    replace: tuple[tuple[str, str], ...] = (),
) -> str:
    """Exercise 3.8's solution with the line that reads frame i (``read``) or moves on to frame
    i + 1 (``move``; LINK is the link transform at q = 0) replaced, then ``replace``'s pairs."""
    source = _SCREWS_FROM_DH.replace("READ", read).replace("MOVE", move)
    source = source.replace("LINK", "urkin.kinematics.dh_transform(0.0, d, a, alpha)")
    for old, new in replace:
        assert old in source, old
        source = source.replace(old, new)
    return source


WRONG = [
    # ------------------------------------------------------------------------------ 3.1
    Variant(
        "3.1",
        "v = ω × q",
        "def screw_axis(w, q):\n    return np.concatenate([w, np.cross(w, q)])\n",
        points=1,
        mistake="wrong sign",
    ),
    Variant(
        "3.1",
        "(v, ω) order",
        "def screw_axis(w, q):\n    return np.concatenate([-np.cross(w, q), w])\n",
        points=1,
        mistake="(v, ω) order",
    ),
    Variant(
        "3.1",
        "(v, ω) order and the sign",
        "def screw_axis(w, q):\n    return np.concatenate([np.cross(w, q), w])\n",
        points=1,
        mistake="(v, ω) order, and",
    ),
    Variant(
        "3.1",
        "v = q",
        "def screw_axis(w, q):\n    return np.concatenate([w, q])\n",
        points=0,
        mistake="v = q",
    ),
    Variant(
        "3.1",
        "arguments swapped",
        "def screw_axis(w, q):\n    return np.concatenate([q, -np.cross(q, w)])\n",
        points=0,
        mistake="swapped",
    ),
    Variant(
        "3.1",
        "two rows",
        "def screw_axis(w, q):\n    return np.array([w, -np.cross(w, q)])\n",
        points=0,
        mistake="two rows",
    ),
    Variant(
        "3.1",
        "v only",
        "def screw_axis(w, q):\n    return -np.cross(w, q)\n",
        points=0,
        mistake="only three numbers",
    ),
    Variant(
        "3.1",
        "a column",
        "def screw_axis(w, q):\n    return np.concatenate([w, -np.cross(w, q)]).reshape(6, 1)\n",
        points=0,
        mistake="column",
    ),
    Variant("3.1", "zeros", "def screw_axis(w, q):\n    return np.zeros(6)\n", points=0),
    Variant(
        "3.1",
        "a slip in the hand-written cross product",
        """
def screw_axis(w, q):
    cross = [w[1] * q[2] - w[2] * q[1], w[2] * q[0] - w[0] * q[2], w[0] * q[1] + w[1] * q[0]]
    return np.array([*w, *(-np.array(cross))])
""",
        points=0,
    ),
    # ------------------------------------------------------------------------------ 3.2
    Variant("3.2", "translation v·θ", _TWIST_V_THETA, points=1, mistake="v·θ"),
    Variant(
        "3.2",
        "transposed rotation",
        """
def twist_exp(S, theta):
    W = skew(S[:3])
    T = np.eye(4)
    T[:3, :3] = (np.eye(3) + np.sin(theta) * W + (1 - np.cos(theta)) * W @ W).T
    c, s = np.cos(theta), np.sin(theta)
    T[:3, 3] = (theta * np.eye(3) + (1 - c) * W + (theta - s) * W @ W) @ S[3:]
    return T
""",
        points=1,
        mistake="transposed",
    ),
    Variant(
        "3.2",
        "the turn by −θ",
        """
def twist_exp(S, theta):
    W = skew(S[:3])
    theta = -theta
    T = np.eye(4)
    T[:3, :3] = np.eye(3) + np.sin(theta) * W + (1 - np.cos(theta)) * W @ W
    c, s = np.cos(theta), np.sin(theta)
    T[:3, 3] = (theta * np.eye(3) + (1 - c) * W + (theta - s) * W @ W) @ S[3:]
    return T
""",
        points=1,
        mistake="wrong sign",
    ),
    Variant(
        "3.2",
        "degrees",
        """
def twist_exp(S, theta):
    theta = np.radians(theta)
    W = skew(S[:3])
    T = np.eye(4)
    T[:3, :3] = np.eye(3) + np.sin(theta) * W + (1 - np.cos(theta)) * W @ W
    c, s = np.cos(theta), np.sin(theta)
    T[:3, 3] = (theta * np.eye(3) + (1 - c) * W + (theta - s) * W @ W) @ S[3:]
    return T
""",
        points=0,
        mistake="degrees",
    ),
    Variant(
        "3.2",
        "S read as (v, ω)",
        """
def twist_exp(S, theta):
    v, w = np.asarray(S[:3]), np.asarray(S[3:])
    W = skew(w)
    T = np.eye(4)
    T[:3, :3] = np.eye(3) + np.sin(theta) * W + (1 - np.cos(theta)) * W @ W
    T[:3, 3] = (theta * np.eye(3) + (1 - np.cos(theta)) * W + (theta - np.sin(theta)) * W @ W) @ v
    return T
""",
        points=0,
        mistake="(v, ω)",
    ),
    Variant(
        "3.2",
        "I instead of Iθ",
        """
def twist_exp(S, theta):
    W = skew(S[:3])
    T = np.eye(4)
    T[:3, :3] = np.eye(3) + np.sin(theta) * W + (1 - np.cos(theta)) * W @ W
    T[:3, 3] = (np.eye(3) + (1 - np.cos(theta)) * W + (theta - np.sin(theta)) * W @ W) @ S[3:]
    return T
""",
        points=1,
        mistake="Iθ written as I",
    ),
    Variant(
        "3.2",
        "sign of the [ω] term",
        """
def twist_exp(S, theta):
    W = skew(S[:3])
    T = np.eye(4)
    T[:3, :3] = np.eye(3) + np.sin(theta) * W + (1 - np.cos(theta)) * W @ W
    c, s = np.cos(theta), np.sin(theta)
    T[:3, 3] = (theta * np.eye(3) + (c - 1) * W + (theta - s) * W @ W) @ S[3:]
    return T
""",
        points=1,
        mistake="[ω] term",
    ),
    Variant(
        "3.2",
        "translation (I − R) v",
        """
def twist_exp(S, theta):
    R = so3_exp(np.asarray(S[:3]) * theta)
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = (np.eye(3) - R) @ S[3:]
    return T
""",
        points=1,
        mistake="(I − R) v",
    ),
    Variant(
        "3.2",
        "Rodrigues with [ω] for [ω]²",
        """
def twist_exp(S, theta):
    W = skew(S[:3])
    T = np.eye(4)
    T[:3, :3] = np.eye(3) + np.sin(theta) * W + (1 - np.cos(theta)) * W
    c, s = np.cos(theta), np.sin(theta)
    T[:3, 3] = (theta * np.eye(3) + (1 - c) * W + (theta - s) * W @ W) @ S[3:]
    return T
""",
        points=0,
        mistake="[ω]², not [ω]",
    ),
    Variant(
        "3.2",
        "series cut off after 8 terms",
        """
def twist_exp(S, theta):
    A = np.zeros((4, 4))
    A[:3, :3] = skew(S[:3]) * theta
    A[:3, 3] = np.asarray(S[3:]) * theta
    total, term = np.eye(4), np.eye(4)
    for k in range(1, 8):
        term = term @ A / k
        total = total + term
    return total
""",
        mistake="cut off",
    ),
    Variant(
        "3.2",
        "no last row",
        """
def twist_exp(S, theta):
    W = skew(S[:3])
    R = np.eye(3) + np.sin(theta) * W + (1 - np.cos(theta)) * W @ W
    G = theta * np.eye(3) + (1 - np.cos(theta)) * W + (theta - np.sin(theta)) * W @ W
    return np.hstack([R, (G @ S[3:])[:, None]])
""",
        points=0,
        mistake="top three rows",
    ),
    Variant(
        "3.2",
        "last row of zeros",
        """
def twist_exp(S, theta):
    W = skew(S[:3])
    T = np.zeros((4, 4))
    T[:3, :3] = np.eye(3) + np.sin(theta) * W + (1 - np.cos(theta)) * W @ W
    c, s = np.cos(theta), np.sin(theta)
    T[:3, 3] = (theta * np.eye(3) + (1 - c) * W + (theta - s) * W @ W) @ S[3:]
    return T
""",
        points=0,
        mistake="last row",
    ),
    Variant(
        "3.2",
        "R and p separately",
        """
def twist_exp(S, theta):
    W = skew(S[:3])
    R = np.eye(3) + np.sin(theta) * W + (1 - np.cos(theta)) * W @ W
    G = theta * np.eye(3) + (1 - np.cos(theta)) * W + (theta - np.sin(theta)) * W @ W
    return R, G @ S[3:]
""",
        points=0,
        mistake="separately",
    ),
    Variant(
        "3.2",
        "so3_exp(ω) without θ",
        """
def twist_exp(S, theta):
    W = skew(S[:3])
    c, s = np.cos(theta), np.sin(theta)
    T = np.eye(4)
    T[:3, :3] = so3_exp(np.asarray(S[:3], dtype=float))
    T[:3, 3] = (theta * np.eye(3) + (1 - c) * W + (theta - s) * W @ W) @ S[3:]
    return T
""",
        points=0,
        mistake="θ left out of the rotation",
    ),
    Variant("3.2", "identity", "def twist_exp(S, theta):\n    return np.eye(4)\n", points=0),
    Variant(
        "3.2",
        "urkin's se3_exp",
        "def twist_exp(S, theta):\n    return urkin.transforms.se3_exp(np.asarray(S) * theta)\n",
        points=0,
    ),
    # ------------------------------------------------------------------------------ 3.3
    Variant(
        "3.3",
        "M first",
        """
def fk_space(M, S, q):
    T = np.array(M, dtype=float)
    for i in range(len(q)):
        T = T @ twist_exp(S[:, i], q[i])
    return T
""",
        points=0,
        mistake="M multiplied first",
    ),
    Variant(
        "3.3",
        "reverse order",
        """
def fk_space(M, S, q):
    T = np.eye(4)
    for i in range(len(q)):
        T = twist_exp(S[:, i], q[i]) @ T
    return T @ M
""",
        points=1,
        mistake="reverse order",
    ),
    Variant(
        "3.3",
        "M first, from the last joint",
        """
def fk_space(M, S, q):
    T = np.array(M, dtype=float)
    for i in reversed(range(len(q))):
        T = T @ twist_exp(S[:, i], q[i])
    return T
""",
        points=0,
        mistake="wrong side and the exponentials in reverse",
    ),
    Variant(
        "3.3",
        "degrees",
        """
def fk_space(M, S, q):
    T = np.eye(4)
    for i in range(len(q)):
        T = T @ twist_exp(S[:, i], np.radians(q[i]))
    return T @ M
""",
        points=0,
        mistake="degrees",
    ),
    Variant(
        "3.3",
        "M left out",
        """
def fk_space(M, S, q):
    T = np.eye(4)
    for i in range(len(q)):
        T = T @ twist_exp(S[:, i], q[i])
    return T
""",
        points=0,
        mistake="M left out",
    ),
    Variant(
        "3.3",
        "element-wise product",
        """
def fk_space(M, S, q):
    T = np.eye(4)
    for i in range(len(q)):
        T = T * twist_exp(S[:, i], q[i])
    return T @ M
""",
        mistake="element-wise",
    ),
    Variant(
        "3.3",
        "loop stops one joint early",
        """
def fk_space(M, S, q):
    T = np.eye(4)
    for i in range(len(q) - 1):
        T = T @ twist_exp(S[:, i], q[i])
    return T @ M
""",
        mistake="last joint left out",
    ),
    Variant(
        "3.3",
        "range(6)",
        """
def fk_space(M, S, q):
    T = np.eye(4)
    for i in range(6):
        T = T @ twist_exp(S[:, i], q[i])
    return T @ M
""",
        points=4,
        mistake="loop over six joints",
    ),
    Variant(
        "3.3",
        "range(len(S))",
        """
def fk_space(M, S, q):
    T = np.eye(4)
    for i in range(len(S)):
        T = T @ twist_exp(S[:, i], q[i])
    return T @ M
""",
        points=4,
        mistake="loop over six joints",
    ),
    Variant(
        "3.3",
        "rows of S",
        """
def fk_space(M, S, q):
    T = np.eye(4)
    for i in range(len(q)):
        T = T @ twist_exp(S[i], q[i])
    return T @ M
""",
        points=0,
        mistake="rows",
    ),
    Variant(
        "3.3",
        "S_i q_i with θ = 1",
        """
def fk_space(M, S, q):
    T = np.eye(4)
    for i in range(len(q)):
        T = T @ twist_exp(S[:, i] * q[i], 1.0)
    return T @ M
""",
        points=0,
        mistake="S_i·q_i",
    ),
    Variant(
        "3.3",
        "built on a twist_exp with translation v·θ",
        """
def fk_space(M, S, q):
    T = np.eye(4)
    for i in range(len(q)):
        T = T @ twist_exp(S[:, i], q[i])
    return T @ M
""",
        points=1,
        mistake="your twist_exp",
        also=(("twist_exp", _TWIST_V_THETA),),
    ),
    Variant(
        "3.3",
        "urkin's fk_space",
        "def fk_space(M, S, q):\n    return urkin.poe.fk_space(M, S, q)\n",
        points=0,
    ),
    Variant("3.3", "returns M", "def fk_space(M, S, q):\n    return M\n", points=0),
    # ------------------------------------------------------------------------------ 3.4
    Variant(
        "3.4",
        "M last",
        """
def fk_body(M, B, q):
    T = np.eye(4)
    for i in range(len(q)):
        T = T @ twist_exp(B[:, i], q[i])
    return T @ M
""",
        points=0,
        mistake="M multiplied last",
    ),
    Variant(
        "3.4",
        "reverse order",
        """
def fk_body(M, B, q):
    T = np.eye(4)
    for i in range(len(q)):
        T = twist_exp(B[:, i], q[i]) @ T
    return M @ T
""",
        points=1,
        mistake="reverse order",
    ),
    Variant(
        "3.4",
        "degrees",
        """
def fk_body(M, B, q):
    T = np.array(M, dtype=float)
    for i in range(len(q)):
        T = T @ twist_exp(B[:, i], q[i] * np.pi / 180)
    return T
""",
        points=0,
        mistake="degrees",
    ),
    Variant(
        "3.4",
        "M left out",
        """
def fk_body(M, B, q):
    T = np.eye(4)
    for i in range(len(q)):
        T = T @ twist_exp(B[:, i], q[i])
    return T
""",
        points=0,
        mistake="M left out",
    ),
    Variant(
        "3.4",
        "first joint skipped",
        """
def fk_body(M, B, q):
    T = np.array(M, dtype=float)
    for i in range(1, len(q)):
        T = T @ twist_exp(B[:, i], q[i])
    return T
""",
        mistake="first joint left out",
    ),
    Variant(
        "3.4",
        "built on a twist_exp with translation v·θ",
        """
def fk_body(M, B, q):
    T = np.array(M, dtype=float)
    for i in range(len(q)):
        T = T @ twist_exp(B[:, i], q[i])
    return T
""",
        points=1,
        mistake="your twist_exp",
        also=(("twist_exp", _TWIST_V_THETA),),
    ),
    Variant(
        "3.4",
        "urkin's fk_body",
        "def fk_body(M, B, q):\n    return urkin.poe.fk_body(M, B, q)\n",
        points=0,
    ),
    # ------------------------------------------------------------------------------ 3.5
    Variant(
        "3.5",
        "(v, ω) order",
        _TWIST_LOG.replace(
            "np.r_[wt, G_inv @ T[:3, 3] * theta]", "np.r_[G_inv @ T[:3, 3] * theta, wt]"
        ).replace("np.r_[np.zeros(3), T[:3, 3]]", "np.r_[T[:3, 3], np.zeros(3)]"),
        points=0,
        mistake="(v, ω) order",
    ),
    Variant(
        "3.5",
        "the linear part is p",
        """
from urkin.transforms import so3_log


def twist_log(T):
    T = np.asarray(T, dtype=float)
    return np.r_[so3_log(T[:3, :3]), T[:3, 3]]
""",
        points=1,
        mistake="the linear part is p",
    ),
    Variant(
        "3.5",
        "+½[ω] in G⁻¹",
        _TWIST_LOG.replace("- W / 2", "+ W / 2"),
        points=1,
        mistake="+½[ω]",
    ),
    Variant(
        "3.5",
        "no θ = 0 branch",
        """
def twist_log(T):
    T = np.asarray(T, dtype=float)
    R, p = T[:3, :3], T[:3, 3]
    theta = np.arccos(np.clip((np.trace(R) - 1) / 2, -1, 1))
    w = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]]) / (2 * np.sin(theta))
    W = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
    G_inv = np.eye(3) / theta - W / 2 + (1 / theta - 0.5 / np.tan(theta / 2)) * W @ W
    return np.r_[w * theta, G_inv @ p * theta]
""",
        points=2,
        mistake="handle θ = 0",
    ),
    Variant(
        "3.5",
        "the axis divided by sin θ at a half turn",
        """
def twist_log(T):
    T = np.asarray(T, dtype=float)
    R, p = T[:3, :3], T[:3, 3]
    s = 0.5 * np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    theta = np.arctan2(np.linalg.norm(s), (np.trace(R) - 1) / 2)
    if theta < 1e-12:
        return np.r_[np.zeros(3), p]
    w = s / np.sin(theta)
    W = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
    G_inv = np.eye(3) / theta - W / 2 + (1 / theta - 0.5 / np.tan(theta / 2)) * W @ W
    return np.r_[w * theta, G_inv @ p * theta]
""",
        points=3,
        mistake="symmetric part",
    ),
    Variant(
        "3.5",
        "urkin's se3_log",
        "def twist_log(T):\n    return urkin.transforms.se3_log(T)\n",
        points=0,
    ),
    # ------------------------------------------------------------------------------ 3.6
    Variant(
        "3.6",
        "a tolerance of 1e-2 on |ω|",
        """
def screw_to_joint(S):
    S = np.asarray(S, dtype=float)
    if abs(np.linalg.norm(S[:3]) - 1.0) > 1e-2:
        raise ValueError("S needs a unit ω")
    return np.cross(S[:3], S[3:])
""",
        points=None,
        mistake="no check of the input",
    ),
    Variant(
        "3.6",
        "v × ω: the mirror point",
        """
def screw_to_joint(S):
    S = np.asarray(S, dtype=float)
    if abs(np.linalg.norm(S[:3]) - 1.0) > 1e-6:
        raise ValueError("S needs a unit ω")
    return np.cross(S[3:], S[:3])
""",
        points=1,
        mistake="v × ω",
    ),
    Variant(
        "3.6",
        "v taken as the point",
        """
def screw_to_joint(S):
    S = np.asarray(S, dtype=float)
    if abs(np.linalg.norm(S[:3]) - 1.0) > 1e-6:
        raise ValueError("S needs a unit ω")
    return S[3:].copy()
""",
        points=1,
        mistake="v itself",
    ),
    Variant(
        "3.6",
        "a point of the axis one metre along ω",
        """
def screw_to_joint(S):
    S = np.asarray(S, dtype=float)
    if abs(np.linalg.norm(S[:3]) - 1.0) > 1e-6:
        raise ValueError("S needs a unit ω")
    w, v = S[:3], S[3:]
    return np.cross(w, v) + w
""",
        points=1,
        mistake="not the one nearest the origin",
    ),
    Variant(
        "3.6",
        "no check of ω",
        "def screw_to_joint(S):\n    return np.cross(S[:3], S[3:])\n",
        points=2,
        mistake="no check of the input",
    ),
    Variant(
        "3.6",
        "an assert instead of ValueError",
        """
def screw_to_joint(S):
    S = np.asarray(S, dtype=float)
    assert abs(np.linalg.norm(S[:3]) - 1.0) < 1e-6, "S needs a unit ω"
    return np.cross(S[:3], S[3:])
""",
        points=2,
        mistake="another exception than ValueError",
    ),
    Variant(
        "3.6",
        "a ValueError that does not name S",
        """
def screw_to_joint(S):
    S = np.asarray(S, dtype=float)
    if abs(np.linalg.norm(S[:3]) - 1.0) > 1e-6:
        raise ValueError("the axis must be a unit vector")
    return np.cross(S[:3], S[3:])
""",
        points=2,
        mistake="does not say which argument",
    ),
    Variant(
        "3.6",
        "refuses every screw axis",
        "def screw_to_joint(S):\n    raise ValueError('S is not accepted')\n",
        points=0,
    ),
    # ------------------------------------------------------------------------------ 3.7
    Variant(
        "3.7",
        "Ad(M) instead of Ad(M⁻¹)",
        """
def body_from_space(S, M):
    R, p = M[:3, :3], M[:3, 3]
    Ad = np.zeros((6, 6))
    Ad[:3, :3] = Ad[3:, 3:] = R
    Ad[3:, :3] = skew(p) @ R
    return Ad @ S
""",
        points=0,
        mistake="Ad(M) S instead of Ad(M⁻¹) S",
    ),
    Variant(
        "3.7",
        "[p]R in the top-right block",
        """
def body_from_space(S, M):
    T = inv_transform(M)
    R, p = T[:3, :3], T[:3, 3]
    Ad = np.zeros((6, 6))
    Ad[:3, :3] = Ad[3:, 3:] = R
    Ad[:3, 3:] = skew(p) @ R
    return Ad @ S
""",
        points=0,
        mistake="in the top-right block",
    ),
    Variant(
        "3.7",
        "B returned as (v, ω)",
        """
def body_from_space(S, M):
    T = inv_transform(M)
    R, p = T[:3, :3], T[:3, 3]
    w, v = R @ S[:3], skew(p) @ R @ S[:3] + R @ S[3:]
    return np.vstack([v, w])
""",
        points=0,
        mistake="(v, ω) order",
    ),
    Variant(
        "3.7",
        "np.linalg.inv(M) for p, but M's own R",
        """
def body_from_space(S, M):
    R = M[:3, :3]
    p = np.linalg.inv(M)[:3, 3]
    Ad = np.zeros((6, 6))
    Ad[:3, :3] = Ad[3:, 3:] = R
    Ad[3:, :3] = skew(p) @ R
    return Ad @ S
""",
        points=0,
        mistake="R not transposed",
    ),
    Variant(
        "3.7",
        "the translation of M⁻¹ taken as −p",
        """
def body_from_space(S, M):
    R, p = M[:3, :3].T, -M[:3, 3]
    Ad = np.zeros((6, 6))
    Ad[:3, :3] = Ad[3:, 3:] = R
    Ad[3:, :3] = skew(p) @ R
    return Ad @ S
""",
        points=0,
        mistake="taken as −p",
    ),
    Variant(
        "3.7",
        "R[p] instead of [p]R",
        """
def body_from_space(S, M):
    T = inv_transform(M)
    R, p = T[:3, :3], T[:3, 3]
    Ad = np.zeros((6, 6))
    Ad[:3, :3] = Ad[3:, 3:] = R
    Ad[3:, :3] = R @ skew(p)
    return Ad @ S
""",
        points=0,
        mistake="R[p] in the bottom-left block",
    ),
    Variant(
        "3.7",
        "six columns hard-coded",
        """
def body_from_space(S, M):
    T = inv_transform(M)
    R, p = T[:3, :3], T[:3, 3]
    Ad = np.zeros((6, 6))
    Ad[:3, :3] = Ad[3:, 3:] = R
    Ad[3:, :3] = skew(p) @ R
    B = np.zeros((6, 6))
    for i in range(6):
        B[:, i] = Ad @ S[:, i]
    return B
""",
        points=2,
        mistake="six columns hard-coded",
    ),
    Variant(
        "3.7",
        "six columns hard-coded, into an array shaped like S",
        """
def body_from_space(S, M):
    T = inv_transform(M)
    R, p = T[:3, :3], T[:3, 3]
    Ad = np.zeros((6, 6))
    Ad[:3, :3] = Ad[3:, 3:] = R
    Ad[3:, :3] = skew(p) @ R
    B = np.zeros_like(S)
    for i in range(min(6, S.shape[1])):
        B[:, i] = Ad @ S[:, i]
    return B
""",
        points=2,
        mistake="six columns hard-coded",
    ),
    Variant(
        "3.7",
        "the adjoint itself returned",
        """
def body_from_space(S, M):
    T = inv_transform(M)
    R, p = T[:3, :3], T[:3, 3]
    Ad = np.zeros((6, 6))
    Ad[:3, :3] = Ad[3:, 3:] = R
    Ad[3:, :3] = skew(p) @ R
    return Ad
""",
        points=0,
        mistake="the 6 × 6 adjoint itself",
    ),
    Variant(
        "3.7",
        "S returned unchanged",
        "def body_from_space(S, M):\n    return np.array(S, dtype=float)\n",
        points=0,
        mistake="S returned unchanged",
    ),
    Variant(
        "3.7",
        "urkin's adjoint (hidden)",
        "def body_from_space(S, M):\n    return adjoint(inv_transform(M)) @ S\n",
        points=0,
    ),
    # ------------------------------------------------------------------------------ 3.8
    Variant(
        "3.8",
        "frames off by one (z_i, p_i)",
        _screws_from_dh(read="T = T @ LINK\n        z, p = T[:3, 2], T[:3, 3]", move="pass"),
        points=0,
        mistake="frames off by one",
    ),
    Variant(
        "3.8",
        "v = +z × p",
        _screws_from_dh(replace=(("-np.cross(z, p)", "np.cross(z, p)"),)),
        points=0,
        mistake="v = +ω × p has the wrong sign",
    ),
    Variant(
        "3.8",
        "S in (v, ω) order",
        _screws_from_dh(replace=(("S[:3, i], S[3:, i]", "S[3:, i], S[:3, i]"),)),
        points=0,
        mistake="(v, ω) order",
    ),
    Variant(
        "3.8",
        "the origin of frame i",
        _screws_from_dh(
            read="z = T[:3, 2]\n        T = T @ LINK\n        p = T[:3, 3]", move="pass"
        ),
        points=0,
        mistake="the point from frame i",
    ),
    Variant(
        "3.8",
        "M forgotten",
        _screws_from_dh(replace=(("return S, T", "return S, np.eye(4)"),)),
        points=0,
        mistake="M forgotten",
    ),
    Variant(
        "3.8",
        "M one frame early",
        _screws_from_dh(move="last, T = T, T @ LINK", replace=(("return S, T", "return S, last"),)),
        points=0,
        mistake="the last joint's frame",
    ),
    Variant(
        "3.8",
        "rows read as (a, d, α)",
        _screws_from_dh(replace=(("(d, a, alpha) in", "(a, d, alpha) in"),)),
        points=0,
        mistake="read as (a, d, α)",
    ),
    Variant(
        "3.8",
        "only S returned",
        _screws_from_dh(replace=(("return S, T", "return S"),)),
        points=0,
        mistake="only S returned",
    ),
    Variant(
        "3.8",
        "six joints hard-coded",
        _screws_from_dh(
            replace=(
                ("np.zeros((6, len(table)))", "np.zeros((6, 6))"),
                ("enumerate(table)", "zip(range(6), table)"),
            )
        ),
        points=1,
        mistake="six joints hard-coded",
    ),
    Variant(
        "3.8",
        "urkin's space_screws (hidden)",
        "def screws_from_dh(rows):\n    return urkin.poe.space_screws(rows)\n",
        points=0,
    ),
]
