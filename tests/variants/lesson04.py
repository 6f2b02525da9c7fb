"""Lesson 04 — Jacobians and singularities: correct and wrong versions of the exercise
functions."""

from tests.variants import Variant


def _jacobian_with(column: str, frames: str = "urkin.fk_frames(robot, np.asarray(q, float))"):
    """A geometric_jacobian whose column i is computed by ``column`` (from z, o, p, i)."""
    return f"""
def geometric_jacobian(robot, q):
    frames = {frames}
    p = frames[6][:3, 3]
    J = np.zeros((6, 6))
    for i in range(6):
        z, o = frames[i][:3, 2], frames[i][:3, 3]
        J[:, i] = {column}
    return J
"""


_SHOULDER = "a2 * np.cos(q2) + a3 * np.cos(q2 + q3) + d5 * np.sin(q2 + q3 + q4)"


def _singularities_with(
    shoulder=_SHOULDER,
    elbow="abs(np.sin(q3)) <= tol",
    wrist="abs(np.sin(q5)) <= tol",
    angles="q[1], q[2], q[3], q[4]",
    tol="tol",
):
    """A singularities function with one piece swapped for a wrong one."""
    return f"""
def singularities(robot, q, tol=1e-9):
    tol = {tol}
    q2, q3, q4, q5 = {angles}
    a2, a3, d4, d5 = robot.a2, robot.a3, robot.d4, robot.d5
    found = set()
    if abs({shoulder}) <= tol:
        found.add("shoulder")
    if {elbow}:
        found.add("elbow")
    if {wrist}:
        found.add("wrist")
    return found
"""


def _numeric_with(column: str, extra: str = ""):
    """A numeric_jacobian whose column j is computed by ``column`` (from f, q, h, e)."""
    return f"""
def numeric_jacobian(f, q, h=1e-6):
    q = np.asarray(q, dtype=float)
    {extra}
    columns = []
    for j in range(q.size):
        e = np.zeros(q.size)
        e[j] = 1.0
        columns.append({column})
    return np.column_stack(columns)
"""


def _complex_step_with(column: str, extra: str = "", default: str = "1e-20"):
    """A complex_step_jacobian whose column j is computed by ``column`` (from position, q, h,
    e: the unit vector e_j)."""
    return f"""
def complex_step_jacobian(position, q, h={default}):
    q = np.asarray(q, dtype=float)
    {extra}
    columns = []
    for j in range(q.size):
        e = np.zeros(q.size)
        e[j] = 1.0
        columns.append({column})
    return np.column_stack(columns)
"""


_JS = """
def jacobian_space(S, q):
    S = np.asarray(S, dtype=float)
    J = np.zeros(S.shape)
    T = np.eye(4)
    for i in range(S.shape[1]):
        J[:, i] = adjoint(T) @ S[:, i]
        T = T @ se3_exp(S[:, i] * q[i])
    return J
"""

_JB = """
def jacobian_body(B, q):
    B = np.asarray(B, dtype=float)
    J = np.zeros(B.shape)
    T = np.eye(4)
    for i in reversed(range(B.shape[1])):
        J[:, i] = adjoint(T) @ B[:, i]
        T = T @ se3_exp(-B[:, i] * q[i])
    return J
"""

CORRECT = [
    # ------------------------------------------------------------------------------ 4.6
    Variant(
        "4.6",
        "product of the singular values",
        "def manipulability(J):\n    return np.prod(np.linalg.svd(J, compute_uv=False))\n",
    ),
    Variant(
        "4.6",
        "|det J| for square, clipped det otherwise",
        """
def manipulability(J):
    J = np.asarray(J, dtype=float)
    if J.shape[0] == J.shape[1]:
        return abs(np.linalg.det(J))
    return np.sqrt(np.clip(np.linalg.det(J @ J.T), 0, None))
""",
    ),
    # ------------------------------------------------------------------------------ 4.3
    Variant(
        "4.3",
        "own adjoint and Rodrigues, a list q, columns appended",
        """
def hat(w):
    return np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


def exp6(S, theta):
    w, v = S[:3], S[3:]
    W = hat(w)
    R = np.eye(3) + np.sin(theta) * W + (1 - np.cos(theta)) * W @ W
    G = np.eye(3) * theta + (1 - np.cos(theta)) * W + (theta - np.sin(theta)) * W @ W
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, G @ v
    return T


def Ad(T):
    R, p = T[:3, :3], T[:3, 3]
    A = np.zeros((6, 6))
    A[:3, :3] = A[3:, 3:] = R
    A[3:, :3] = hat(p) @ R
    return A


def jacobian_space(S, q):
    S = np.array(S, dtype=float)
    columns, T = [], np.eye(4)
    for i, angle in enumerate(list(q)):
        columns.append(Ad(T) @ S[:, i])
        T = T @ exp6(S[:, i], angle)
    return np.column_stack(columns)
""",
    ),
    # ------------------------------------------------------------------------------ 4.4
    Variant(
        "4.4",
        "inverse adjoints of the product from the end (T⁻¹ of the forward product)",
        """
def jacobian_body(B, q):
    B = np.asarray(B, dtype=float)
    n = B.shape[1]
    J = np.zeros((6, n))
    for i in range(n):
        T = np.eye(4)
        for k in range(i + 1, n):
            T = T @ se3_exp(B[:, k] * q[k])
        J[:, i] = adjoint(np.linalg.inv(T)) @ B[:, i]
    return J
""",
    ),
    # ------------------------------------------------------------------------------ 4.1
    Variant(
        "4.1",
        "vectorised over the frames",
        """
def geometric_jacobian(robot, q):
    frames = urkin.fk_frames(robot, q)
    z, o, p = frames[:6, :3, 2], frames[:6, :3, 3], frames[6, :3, 3]
    return np.vstack([np.cross(z, p - o).T, z.T])
""",
    ),
    Variant(
        "4.1",
        "own DH products, skew matrices",
        """
def dh(theta, d, a, alpha):
    ct, st, ca, sa = np.cos(theta), np.sin(theta), np.cos(alpha), np.sin(alpha)
    return np.array([[ct, -st * ca, st * sa, a * ct],
                     [st, ct * ca, -ct * sa, a * st],
                     [0.0, sa, ca, d],
                     [0.0, 0.0, 0.0, 1.0]])


def hat(w):
    return np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


def geometric_jacobian(robot, q):
    T = np.eye(4)
    frames = [T]
    for i in range(6):
        T = T @ dh(q[i], robot.d[i], robot.a[i], robot.alpha[i])
        frames.append(T)
    p = frames[-1][:3, 3]
    columns = []
    for i in range(6):
        z, o = frames[i][:3, 2], frames[i][:3, 3]
        columns.append(np.concatenate([hat(z) @ (p - o), z]))
    return np.array(columns).T
""",
    ),
    Variant(
        "4.1",
        "screw axes of the moved frames, then v = v_s − p × ω",
        """
def geometric_jacobian(robot, q):
    frames = urkin.fk_frames(robot, q)
    p = urkin.fk(robot, q)[:3, 3]
    J = np.zeros((6, 6))
    for i in range(6):
        w, point = frames[i][:3, 2], frames[i][:3, 3]
        v_space = -np.cross(w, point)  # the current screw axis (w, v_s)
        J[:3, i] = v_space - np.cross(p, w)
        J[3:, i] = w
    return J
""",
    ),
    Variant(
        "4.1",
        "float32",
        _jacobian_with(
            "np.concatenate([np.cross(z, p - o), z]).astype(np.float32)",
            "urkin.fk_frames(robot, q).astype(np.float32)",
        ).replace("np.zeros((6, 6))", "np.zeros((6, 6), dtype=np.float32)"),
    ),
    Variant(
        "4.1",
        "column by column, hstack of lists",
        """
def geometric_jacobian(robot, q):
    frames = urkin.fk_frames(robot, q)
    p = frames[-1][:3, 3]
    Jv = [np.cross(frames[i][:3, 2], p - frames[i][:3, 3]) for i in range(6)]
    Jw = [frames[i][:3, 2] for i in range(6)]
    return np.vstack([np.column_stack(Jv), np.column_stack(Jw)])
""",
    ),
    # ------------------------------------------------------------------------------ 4.2
    Variant(
        "4.2",
        "vectorised over h·I",
        """
def numeric_jacobian(f, q, h=1e-6):
    q = np.asarray(q, dtype=float)
    steps = h * np.eye(len(q))
    return np.array([np.asarray(f(q + s)) - np.asarray(f(q - s)) for s in steps]).T / (2 * h)
""",
    ),
    Variant(
        "4.2",
        "nudge a copy and restore it",
        """
def numeric_jacobian(f, q, h=1e-6):
    x = np.array(q, dtype=float)
    m = np.size(f(x))
    J = np.zeros((m, x.size))
    for j in range(x.size):
        x[j] += h
        f_plus = np.asarray(f(x), dtype=float)
        x[j] -= 2 * h
        f_minus = np.asarray(f(x), dtype=float)
        x[j] += h
        J[:, j] = (f_plus - f_minus) / (2 * h)
    return J
""",
    ),
    Variant(
        "4.2",
        "divides by the step actually taken",
        """
def numeric_jacobian(f, q, h=1e-6):
    q = np.asarray(q, dtype=float)
    columns = []
    for j in range(len(q)):
        up, down = q.copy(), q.copy()
        up[j] += h
        down[j] -= h
        columns.append((np.asarray(f(up)) - np.asarray(f(down))) / (up[j] - down[j]))
    return np.stack(columns, axis=1)
""",
    ),
    Variant(
        "4.2",
        "float32 answer",
        """
def numeric_jacobian(f, q, h=1e-6):
    q = np.asarray(q, dtype=np.float32)
    J = []
    for j in range(q.size):
        step = np.zeros_like(q)
        step[j] = h
        J.append((np.asarray(f(q + step), dtype=np.float32)
                  - np.asarray(f(q - step), dtype=np.float32)) / np.float32(2 * h))
    return np.array(J, dtype=np.float32).T
""",
    ),
    Variant(
        "4.2",
        "float32 steps, float64 f",
        """
def numeric_jacobian(f, q, h=1e-6):
    q = np.asarray(q, dtype=np.float32)
    columns = []
    for j in range(q.size):
        step = np.zeros_like(q)
        step[j] = h
        columns.append((np.asarray(f(q + step)) - np.asarray(f(q - step))) / (2 * h))
    return np.column_stack(columns)
""",
    ),
    Variant(
        "4.2",
        "lists and atleast_1d",
        """
def numeric_jacobian(f, q, h=1e-6):
    q = [float(x) for x in q]
    columns = []
    for j in range(len(q)):
        plus = q[:j] + [q[j] + h] + q[j + 1:]
        minus = q[:j] + [q[j] - h] + q[j + 1:]
        columns.append((np.atleast_1d(f(np.array(plus))) - np.atleast_1d(f(np.array(minus))))
                       / (2 * h))
    return np.array(columns).T
""",
    ),
    # ------------------------------------------------------------------------------ 4.3
    Variant(
        "4.5",
        "factors zipped with the names, a sorted list",
        """
def singularities(robot, q, tol=1e-9):
    q = np.asarray(q, dtype=float)
    factors = [
        robot.a2 * np.cos(q[1]) + robot.a3 * np.cos(q[1] + q[2]) + robot.d5 * np.sin(q[1:4].sum()),
        np.sin(q[2]),
        np.sin(q[4]),
    ]
    return sorted(n for n, f in zip(["shoulder", "elbow", "wrist"], factors) if abs(f) <= tol)
""",
    ),
    Variant(
        "4.5",
        "np.isclose with atol = tol, a tuple",
        """
def singularities(robot, q, tol=1e-9):
    q1, q2, q3, q4, q5, q6 = q
    names = []
    shoulder = robot.a2 * np.cos(q2) + robot.a3 * np.cos(q2 + q3) + robot.d5 * np.sin(q2 + q3 + q4)
    if np.isclose(shoulder, 0.0, atol=tol):
        names.append("shoulder")
    if np.isclose(np.sin(q3), 0.0, atol=tol):
        names.append("elbow")
    if np.isclose(np.sin(q5), 0.0, atol=tol):
        names.append("wrist")
    return tuple(names)
""",
    ),
    Variant(
        "4.5",
        "math module, strict <, capitalised names",
        """
import math


def singularities(robot, q, tol=1e-9):
    s = robot.a2 * math.cos(q[1]) + robot.a3 * math.cos(q[1] + q[2]) \\
        + robot.d5 * math.sin(q[1] + q[2] + q[3])
    result = set()
    if abs(s) < tol:
        result.add("Shoulder")
    if abs(math.sin(q[2])) < tol:
        result.add("Elbow")
    if abs(math.sin(q[4])) < tol:
        result.add("Wrist")
    return result
""",
    ),
    Variant(
        "4.5",
        "{} when regular",
        """
def singularities(robot, q, tol=1e-9):
    factors = urkin_factors(robot, q)
    names = [n for n, f in zip(("shoulder", "elbow", "wrist"), factors) if abs(f) <= tol]
    if not names:
        return {}
    return set(names)


def urkin_factors(robot, q):
    q2, q3, q4, q5 = q[1:5]
    return (
        robot.a2 * np.cos(q2) + robot.a3 * np.cos(q2 + q3) + robot.d5 * np.sin(q2 + q3 + q4),
        np.sin(q3),
        np.sin(q5),
    )
""",
    ),
    Variant(
        "4.5",
        "the shoulder from the wrist centre's distance to the plane",
        """
def singularities(robot, q, tol=1e-9):
    frames = urkin.fk_frames(robot, q)
    wrist_centre = frames[5][:3, 3]
    normal = np.cross([0.0, 0.0, 1.0], frames[1][:3, 2])  # ⟂ the base axis and the shoulder axis
    normal = normal / np.linalg.norm(normal)
    found = set()
    if abs(np.dot(wrist_centre, normal)) <= tol:
        found.add("shoulder")
    if abs(np.sin(q[2])) <= tol:
        found.add("elbow")
    if abs(np.sin(q[4])) <= tol:
        found.add("wrist")
    return found
""",
    ),
    # ------------------------------------------------------------------------------ 4.7
    Variant(
        "4.7",
        "the arm's line, made perpendicular to the shoulder axis",
        """
def elbow_lost_direction(robot, q):
    frames = urkin.fk_frames(robot, np.asarray(q, dtype=float))
    z1 = frames[1][:3, 2]
    line = np.cross(z1, np.cross(frames[3][:3, 3] - frames[1][:3, 3], z1))
    return line / np.linalg.norm(line)
""",
    ),
    Variant(
        "4.7",
        "SVD of wrist 1's central-difference Jacobian",
        """
def elbow_lost_direction(robot, q):
    q = np.asarray(q, dtype=float)
    def wrist_1(x):
        return urkin.fk_frames(robot, x)[3][:3, 3]
    h = 1e-6
    steps = np.eye(6)[:3]
    J = np.column_stack([(wrist_1(q + h * e) - wrist_1(q - h * e)) / (2 * h) for e in steps])
    return np.linalg.svd(J)[0][:, 2]
""",
    ),
    # ------------------------------------------------------------------------------ 4.8
    Variant(
        "4.8",
        "the gradient of the potential energy, by the complex step",
        """
def holding_torques(robot, q, mass, r_com):
    q = np.asarray(q, dtype=float)
    point = np.r_[np.asarray(r_com, dtype=float), 1.0]
    def V(x):
        return mass * 9.81 * (urkin.fk(robot, x) @ point)[2]
    return np.array([V(q + 1e-30j * e).imag / 1e-30 for e in np.eye(6)])
""",
    ),
    Variant(
        "4.8",
        "the Jacobian of the centre of mass, shifted by the lever",
        """
def holding_torques(robot, q, mass, r_com):
    q = np.asarray(q, dtype=float)
    T = urkin.fk(robot, q)
    J = urkin.jacobian(robot, q)
    r = T[:3, :3] @ np.asarray(r_com, dtype=float)
    Jc = J[:3] - np.cross(r, J[3:].T).T  # velocity of the centre of mass: v + ω × r
    return Jc.T @ np.array([0.0, 0.0, 9.81 * mass])
""",
    ),
    Variant(
        "4.8",
        "Jᵀ F on the student's float32 geometric_jacobian (full marks in 4.1)",
        """
def holding_torques(robot, q, mass, r_com):
    q = np.asarray(q, dtype=float)
    J = geometric_jacobian(robot, q)
    f = np.array([0.0, 0.0, mass * 9.81])
    lever = urkin.fk(robot, q)[:3, :3] @ np.asarray(r_com, dtype=float)
    return J.T @ np.r_[f, np.cross(lever, f)]
""",
        also=(
            (
                "geometric_jacobian",
                """
def geometric_jacobian(robot, q):
    frames = urkin.fk_frames(robot, np.asarray(q, dtype=float))
    p = frames[6][:3, 3]
    J = np.zeros((6, 6))
    for i in range(6):
        z, origin = frames[i][:3, 2], frames[i][:3, 3]
        J[:3, i] = np.cross(z, p - origin)
        J[3:, i] = z
    return J.astype(np.float32)
""",
            ),
        ),
    ),
    # ------------------------------------------------------------------------------ 4.9
    Variant(
        "4.9",
        "eigh of J Jᵀ, σ as |J_vᵀ u|",
        """
def ellipsoid_axes(J_v):
    J = np.asarray(J_v, dtype=float)
    _, vectors = np.linalg.eigh(J @ J.T)
    U = vectors[:, ::-1]  # eigh sorts ascending: largest first
    sigma = np.linalg.norm(J.T @ U, axis=0)  # |J_vᵀ u_i| = σ_i, exact to round-off of σ1
    zero = sigma <= 1e-12 * sigma[0]
    with np.errstate(divide="ignore"):
        force = np.where(zero, np.inf, 1.0 / sigma)
    condition = np.inf if zero[2] else sigma[0] / sigma[2]
    return U, sigma, force, condition
""",
    ),
    Variant(
        "4.9",
        "right-handed U, lists, np.linalg.cond",
        """
def ellipsoid_axes(J_v):
    U, s, _ = np.linalg.svd(np.array(J_v, dtype=float), full_matrices=False)
    if np.linalg.det(U) < 0:
        U[:, 2] = -U[:, 2]  # right-handed
    force = [float("inf") if x <= 1e-12 * s[0] else 1 / x for x in s]
    condition = np.linalg.cond(J_v) if s[2] > 1e-12 * s[0] else float("inf")
    return [U, list(s), force, condition]
""",
    ),
    Variant(
        "4.9",
        "columns negated, rank counted",
        """
def ellipsoid_axes(J_v):
    U, s, _ = np.linalg.svd(J_v)
    rank = int(np.sum(s > 1e-12 * s[0]))
    force = np.array([1 / s[i] if i < rank else np.inf for i in range(3)])
    return -U, s, force, s[0] / s[2] if rank == 3 else np.inf
""",
    ),
    # ------------------------------------------------------------------------------ 4.10
    Variant(
        "4.10",
        "adjoint of a pure translation",
        """
def space_from_geometric(J, T):
    J = np.asarray(J, dtype=float)
    shift = np.eye(4)
    shift[:3, 3] = np.asarray(T)[:3, 3]
    return urkin.transforms.adjoint(shift) @ np.vstack([J[3:], J[:3]])
""",
    ),
    Variant(
        "4.10",
        "through the body Jacobian and Ad_T",
        """
def space_from_geometric(J, T):
    J, T = np.asarray(J, dtype=float), np.asarray(T, dtype=float)
    R = T[:3, :3]
    J_body = np.vstack([R.T @ J[3:], R.T @ J[:3]])
    return urkin.transforms.adjoint(T) @ J_body
""",
    ),
    Variant(
        "4.10",
        "column by column with a skew matrix",
        """
def space_from_geometric(J, T):
    p = [T[0][3], T[1][3], T[2][3]]
    P = np.array([[0, -p[2], p[1]], [p[2], 0, -p[0]], [-p[1], p[0], 0]])
    columns = []
    for column in np.asarray(J, dtype=float).T:
        v, w = column[:3], column[3:]
        columns.append(np.concatenate([w, v + P @ w]))
    return np.array(columns).T
""",
    ),
    # ------------------------------------------------------------------------------ 4.11
    Variant(
        "4.11",
        "one row per nudged point, transposed at the end",
        """
def complex_step_jacobian(position, q, h=1e-20):
    q = np.asarray(q, dtype=float)
    steps = 1j * h * np.eye(q.size)
    return np.array([np.asarray(position(q + s)).imag for s in steps]).T / h
""",
    ),
    Variant(
        "4.11",
        "a complex copy nudged and restored",
        """
def complex_step_jacobian(position, q, h=1e-20):
    x = np.array(q, dtype=complex)
    J = np.zeros((np.size(position(x.real)), x.size))
    for j in range(x.size):
        x[j] += 1j * h
        J[:, j] = np.imag(position(x)) / h
        x[j] = x[j].real
    return J
""",
    ),
    Variant(
        "4.11",
        "symmetric step (f(q + ih) − f(q − ih)) / 2ih",
        _complex_step_with(
            "((np.asarray(position(q + 1j * h * e)) - np.asarray(position(q - 1j * h * e)))"
            " / (2j * h)).real"
        ),
    ),
    Variant(
        "4.11",
        "lists and complex()",
        """
def complex_step_jacobian(position, q, h=1e-20):
    q = [float(x) for x in q]
    columns = []
    for j in range(len(q)):
        point = [complex(x) for x in q]
        point[j] += complex(0.0, h)
        columns.append([value.imag / h for value in np.asarray(position(np.array(point)))])
    return np.array(columns).T
""",
    ),
]

WRONG = [
    # ------------------------------------------------------------------------------ 4.6
    Variant(
        "4.6",
        "no clip before the square root",
        "def manipulability(J):\n    return np.sqrt(np.linalg.det(J @ J.T))\n",
        points=3,
        mistake="clip it at 0",
    ),
    Variant(
        "4.6",
        "JᵀJ",
        "def manipulability(J):\n    return np.sqrt(max(np.linalg.det(J.T @ J), 0.0))\n",
        points=None,
        mistake="Jᵀ J",
    ),
    Variant(
        "4.6",
        "no square root",
        "def manipulability(J):\n    return max(np.linalg.det(J @ J.T), 0.0)\n",
        points=0,
        mistake="without the square root",
    ),
    Variant(
        "4.6",
        "det J",
        "def manipulability(J):\n    return np.linalg.det(J)\n",
        points=0,
        mistake="absolute value",
    ),
    # ------------------------------------------------------------------------------ 4.3
    Variant(
        "4.3",
        "(v, ω) rows",
        _JS.replace("    return J", "    return np.r_[J[3:], J[:3]]"),
        points=0,
        mistake="(v, ω)",
    ),
    Variant(
        "4.3",
        "the home axes",
        "def jacobian_space(S, q):\n    return np.array(S, dtype=float)\n",
        points=0,
        mistake="home axis",
    ),
    Variant(
        "4.3",
        "product on the left",
        _JS.replace("T = T @ se3_exp(S[:, i] * q[i])", "T = se3_exp(S[:, i] * q[i]) @ T"),
        points=0,
        mistake="on the left",
    ),
    Variant(
        "4.3",
        "urkin's jacobian_space",
        "def jacobian_space(S, q):\n    return urkin.poe.jacobian_space(S, q)\n",
        points=0,
    ),
    # ------------------------------------------------------------------------------ 4.4
    Variant(
        "4.4",
        "exponentials of +B q",
        _JB.replace("se3_exp(-B[:, i] * q[i])", "se3_exp(B[:, i] * q[i])"),
        points=0,
        mistake="+B_k q_k",
    ),
    Variant(
        "4.4",
        "forwards from joint 1",
        _JB.replace("reversed(range(B.shape[1]))", "range(B.shape[1])"),
        points=None,
        mistake="forwards",
    ),
    Variant(
        "4.4",
        "(v, ω) rows",
        _JB.replace("    return J", "    return np.r_[J[3:], J[:3]]"),
        points=0,
        mistake="(v, ω)",
    ),
    # ------------------------------------------------------------------------------ 4.1
    Variant(
        "4.1",
        "twist order",
        _jacobian_with("np.concatenate([z, np.cross(z, p - o)])"),
        points=0,
        mistake="twist order",
    ),
    Variant(
        "4.1",
        "axis of frame i",
        """
def geometric_jacobian(robot, q):
    frames = urkin.fk_frames(robot, q)
    p = frames[6][:3, 3]
    J = np.zeros((6, 6))
    for i in range(6):
        z, o = frames[i + 1][:3, 2], frames[i + 1][:3, 3]
        J[:3, i] = np.cross(z, p - o)
        J[3:, i] = z
    return J
""",
        points=0,
        mistake="frame i − 1",
    ),
    Variant(
        "4.1",
        "lever arm reversed",
        _jacobian_with("np.concatenate([np.cross(p - o, z), z])"),
        points=1,
        mistake="wrong way",
    ),
    Variant(
        "4.1",
        "lever arm from the base origin",
        _jacobian_with("np.concatenate([np.cross(z, p), z])"),
        points=1,
        mistake="base origin",
    ),
    Variant(
        "4.1",
        "lever arm from frame i's origin",
        """
def geometric_jacobian(robot, q):
    frames = urkin.fk_frames(robot, q)
    p = frames[6][:3, 3]
    J = np.zeros((6, 6))
    for i in range(6):
        z = frames[i][:3, 2]
        J[:3, i] = np.cross(z, p - frames[i + 1][:3, 3])
        J[3:, i] = z
    return J
""",
        points=None,
        mistake="frame i's origin",
    ),
    Variant(
        "4.1",
        "x axis of the frame",
        """
def geometric_jacobian(robot, q):
    frames = urkin.fk_frames(robot, q)
    p = frames[6][:3, 3]
    J = np.zeros((6, 6))
    for i in range(6):
        x, o = frames[i][:3, 0], frames[i][:3, 3]
        J[:, i] = np.concatenate([np.cross(x, p - o), x])
    return J
""",
        points=0,
        mistake="wrong column",
    ),
    Variant(
        "4.1",
        "z from the third row",
        """
def geometric_jacobian(robot, q):
    frames = urkin.fk_frames(robot, q)
    p = frames[6][:3, 3]
    J = np.zeros((6, 6))
    for i in range(6):
        z, o = frames[i][2, :3], frames[i][:3, 3]
        J[:, i] = np.concatenate([np.cross(z, p - o), z])
    return J
""",
        points=0,
        mistake="third row",
    ),
    Variant(
        "4.1",
        "the wrist centre's velocity",
        _jacobian_with("np.concatenate([np.cross(z, frames[5][:3, 3] - o), z])"),
        points=1,
        mistake="wrist centre",
    ),
    Variant(
        "4.1",
        "the space Jacobian",
        _jacobian_with("np.concatenate([z, -np.cross(z, o)])"),
        points=0,
        mistake="space Jacobian",
    ),
    Variant(
        "4.1",
        "angular rows left empty",
        _jacobian_with("np.concatenate([np.cross(z, p - o), np.zeros(3)])"),
        points=1,
        mistake="angular rows left at zero",
    ),
    Variant(
        "4.1",
        "transposed",
        _jacobian_with("np.concatenate([np.cross(z, p - o), z])").replace(
            "    return J\n", "    return J.T\n"
        ),
        points=0,
        mistake="transposed",
    ),
    Variant(
        "4.1",
        "own DH frames with positive a2, a3",
        """
def geometric_jacobian(robot, q):
    T = np.eye(4)
    frames = [T]
    for i in range(6):
        T = T @ urkin.kinematics.dh_transform(q[i], robot.d[i], abs(robot.a[i]), robot.alpha[i])
        frames.append(T)
    p = T[:3, 3]
    J = np.zeros((6, 6))
    for i in range(6):
        z, o = frames[i][:3, 2], frames[i][:3, 3]
        J[:, i] = np.concatenate([np.cross(z, p - o), z])
    return J
""",
        points=1,
        mistake="wrong sign",
    ),
    Variant(
        "4.1",
        "only the linear rows",
        """
def geometric_jacobian(robot, q):
    frames = urkin.fk_frames(robot, q)
    p = frames[6][:3, 3]
    return np.column_stack([np.cross(frames[i][:3, 2], p - frames[i][:3, 3]) for i in range(6)])
""",
        points=0,
        mistake="only the three linear rows",
    ),
    Variant(
        "4.1",
        "urkin.jacobian",
        "def geometric_jacobian(robot, q):\n    return urkin.jacobian(robot, q)\n",
        points=0,
    ),
    # ------------------------------------------------------------------------------ 4.2
    Variant(
        "4.2",
        "forward differences",
        _numeric_with("(np.asarray(f(q + h * e)) - f0) / h", "f0 = np.asarray(f(q))"),
        points=1,
        mistake="forward differences",
    ),
    Variant(
        "4.2",
        "backward differences",
        _numeric_with("(f0 - np.asarray(f(q - h * e))) / h", "f0 = np.asarray(f(q))"),
        points=1,
        mistake="backward differences",
    ),
    Variant(
        "4.2",
        "divided by h",
        _numeric_with("(np.asarray(f(q + h * e)) - np.asarray(f(q - h * e))) / h"),
        points=0,
        mistake="divided by h",
    ),
    Variant(
        "4.2",
        "divided by 2",
        _numeric_with("(np.asarray(f(q + h * e)) - np.asarray(f(q - h * e))) / 2"),
        points=0,
        mistake="divided by 2 instead",
    ),
    Variant(
        "4.2",
        "h ignored",
        _numeric_with("(np.asarray(f(q + 1e-6 * e)) - np.asarray(f(q - 1e-6 * e))) / 2e-6"),
        points=2,
        mistake="h argument is ignored",
    ),
    Variant(
        "4.2",
        "steps of ±h/2",
        _numeric_with("(np.asarray(f(q + h / 2 * e)) - np.asarray(f(q - h / 2 * e))) / h"),
        points=2,
        mistake="±h/2",
    ),
    Variant(
        "4.2",
        "all entries nudged at once",
        _numeric_with("(np.asarray(f(q + h)) - np.asarray(f(q - h))) / (2 * h)"),
        points=0,
        mistake="nudged at once",
    ),
    Variant(
        "4.2",
        "steps pile up",
        """
def numeric_jacobian(f, q, h=1e-6):
    up = np.array(q, dtype=float)
    down = np.array(q, dtype=float)
    columns = []
    for j in range(len(up)):
        up[j] += h
        down[j] -= h
        columns.append((np.asarray(f(up)) - np.asarray(f(down))) / (2 * h))
    return np.column_stack(columns)
""",
        points=0,
        mistake="pile up",
    ),
    Variant(
        "4.2",
        "q_plus and q_minus alias q",
        """
def numeric_jacobian(f, q, h=1e-6):
    q = np.asarray(q, dtype=float)
    J = np.zeros((np.size(f(q)), q.size))
    for j in range(q.size):
        q_plus = q
        q_plus[j] += h
        q_minus = q
        q_minus[j] -= h
        J[:, j] = (np.asarray(f(q_plus)) - np.asarray(f(q_minus))) / (2 * h)
    return J
""",
        points=0,
        mistake="same array",
    ),
    Variant(
        "4.2",
        "q_plus aliases q, f(q_plus) taken first",
        """
def numeric_jacobian(f, q, h=1e-6):
    q = np.asarray(q, dtype=float)
    J = np.zeros((np.size(f(q)), q.size))
    for j in range(q.size):
        q_plus = q
        q_plus[j] += h
        f_plus = np.asarray(f(q_plus))
        q_minus = q
        q_minus[j] -= h
        J[:, j] = (f_plus - np.asarray(f(q_minus))) / (2 * h)
    return J
""",
        points=0,
        mistake="share q's memory",
    ),
    Variant(
        "4.2",
        "one row per input",
        """
def numeric_jacobian(f, q, h=1e-6):
    q = np.asarray(q, dtype=float)
    rows = []
    for j in range(q.size):
        e = np.zeros(q.size)
        e[j] = h
        rows.append((np.asarray(f(q + e)) - np.asarray(f(q - e))) / (2 * h))
    return np.array(rows)
""",
        points=0,
        mistake="transposed",
    ),
    Variant(
        "4.2",
        "zeros",
        "def numeric_jacobian(f, q, h=1e-6):\n    return np.zeros((np.size(f(q)), len(q)))\n",
        points=0,
    ),
    Variant(
        "4.2",
        "default step 1e-2",
        _numeric_with("(np.asarray(f(q + h * e)) - np.asarray(f(q - h * e))) / (2 * h)").replace(
            "h=1e-6", "h=1e-2"
        ),
        points=3,
        mistake="default step",
    ),
    # ------------------------------------------------------------------------------ 4.3
    Variant(
        "4.5",
        "elbow with cos q3",
        _singularities_with(elbow="abs(np.cos(q3)) <= tol"),
        points=0,
        mistake="cos q3",
    ),
    Variant(
        "4.5",
        "wrist with cos q5",
        _singularities_with(wrist="abs(np.cos(q5)) <= tol"),
        points=0,
        mistake="cos q5",
    ),
    Variant(
        "4.5",
        "wrist only at q5 = 0",
        _singularities_with(wrist="abs(q5) <= tol"),
        points=None,
        mistake="±π too",
    ),
    Variant(
        "4.5",
        "elbow compared with 0 exactly",
        _singularities_with(elbow="np.sin(q3) == 0"),
        points=None,
        mistake="compared with 0 exactly",
    ),
    Variant(
        "4.5",
        "elbow tested on the angle",
        _singularities_with(
            elbow="min(abs(q3), abs(abs(q3) - np.pi)) <= tol",
        ),
        points=3,
        mistake="±2π",
    ),
    Variant(
        "4.5",
        "no abs on sin q3",
        _singularities_with(elbow="np.sin(q3) <= tol"),
        points=None,
        mistake="absolute value is missing",
    ),
    Variant(
        "4.5",
        "no abs on the shoulder factor",
        _singularities_with().replace("if abs(a2 * np.cos", "if (a2 * np.cos"),
        points=None,
        mistake="absolute value is missing",
    ),
    Variant(
        "4.5",
        "default tol 1e-6",
        _singularities_with().replace("tol=1e-9", "tol=1e-6"),
        points=None,
        mistake="default of tol",
    ),
    Variant(
        "4.5",
        "tol ignored",
        _singularities_with(tol="1e-9"),
        points=4,
        mistake="tol argument is ignored",
    ),
    Variant(
        "4.5",
        "np.isclose's default tolerance",
        """
def singularities(robot, q, tol=1e-9):
    q2, q3, q4, q5 = q[1], q[2], q[3], q[4]
    shoulder = robot.a2 * np.cos(q2) + robot.a3 * np.cos(q2 + q3) + robot.d5 * np.sin(q2 + q3 + q4)
    flags = np.isclose([shoulder, np.sin(q3), np.sin(q5)], 0.0)
    return {name for name, flag in zip(["shoulder", "elbow", "wrist"], flags) if flag}
""",
        points=None,
        mistake="tol argument is ignored",
    ),
    Variant(
        "4.5",
        "shoulder without the wrist term",
        _singularities_with(shoulder="a2 * np.cos(q2) + a3 * np.cos(q2 + q3)"),
        points=None,
        mistake="without its wrist term",
    ),
    Variant(
        "4.5",
        "shoulder with − d5",
        _singularities_with(
            shoulder="a2 * np.cos(q2) + a3 * np.cos(q2 + q3) - d5 * np.sin(q2 + q3 + q4)"
        ),
        points=None,
        mistake="wrong sign",
    ),
    Variant(
        "4.5",
        "shoulder with d4",
        _singularities_with(
            shoulder="a2 * np.cos(q2) + a3 * np.cos(q2 + q3) + d4 * np.sin(q2 + q3 + q4)"
        ),
        points=None,
        mistake="d4",
    ),
    Variant(
        "4.5",
        "joint numbers off by one",
        _singularities_with(angles="q[2], q[3], q[4], q[5]"),
        points=0,
        mistake="off by one",
    ),
    Variant(
        "4.5",
        "if / elif",
        """
def singularities(robot, q, tol=1e-9):
    shoulder = robot.a2 * np.cos(q[1]) + robot.a3 * np.cos(q[1] + q[2]) \\
        + robot.d5 * np.sin(q[1] + q[2] + q[3])
    if abs(shoulder) <= tol:
        return {"shoulder"}
    elif abs(np.sin(q[2])) <= tol:
        return {"elbow"}
    elif abs(np.sin(q[4])) <= tol:
        return {"wrist"}
    return set()
""",
        points=4,
        mistake="only one family",
    ),
    Variant(
        "4.5",
        "flags instead of names",
        """
def singularities(robot, q, tol=1e-9):
    shoulder = robot.a2 * np.cos(q[1]) + robot.a3 * np.cos(q[1] + q[2]) \\
        + robot.d5 * np.sin(q[1] + q[2] + q[3])
    return [bool(abs(shoulder) <= tol), bool(abs(np.sin(q[2])) <= tol),
            bool(abs(np.sin(q[4])) <= tol)]
""",
        points=0,
        mistake="True/False flags",
    ),
    Variant(
        "4.5",
        "names with a suffix",
        _singularities_with().replace('"shoulder"', '"shoulder singularity"'),
        points=None,
        mistake="exactly 'shoulder'",
    ),
    Variant(
        "4.5", "always none", "def singularities(robot, q, tol=1e-9):\n    return set()\n", points=0
    ),
    Variant(
        "4.5",
        "urkin's singularities",
        "def singularities(robot, q, tol=1e-9):\n"
        "    return set(urkin.kinematics.singularities(robot, q, tol))\n",
        points=0,
    ),
    # ------------------------------------------------------------------------------ 4.7
    Variant(
        "4.7",
        "not normalised",
        """
def elbow_lost_direction(robot, q):
    frames = urkin.fk_frames(robot, np.asarray(q, dtype=float))
    return frames[3][:3, 3] - frames[1][:3, 3]
""",
        points=0,
        mistake="not normalised",
    ),
    Variant(
        "4.7",
        "the shoulder axis",
        """
def elbow_lost_direction(robot, q):
    return urkin.fk_frames(robot, np.asarray(q, dtype=float))[1][:3, 2]
""",
        points=0,
        mistake="the shoulder axis z1",
    ),
    Variant(
        "4.7",
        "measured from the base origin",
        """
def elbow_lost_direction(robot, q):
    o3 = urkin.fk_frames(robot, np.asarray(q, dtype=float))[3][:3, 3]
    return o3 / np.linalg.norm(o3)
""",
        points=0,
        mistake="measured from the base origin",
    ),
    Variant(
        "4.7",
        "frames off by one",
        """
def elbow_lost_direction(robot, q):
    frames = urkin.fk_frames(robot, np.asarray(q, dtype=float))
    line = frames[4][:3, 3] - frames[2][:3, 3]
    return line / np.linalg.norm(line)
""",
        points=None,
        mistake="(this is o4 − o2)",
    ),
    # ------------------------------------------------------------------------------ 4.8
    Variant(
        "4.8",
        "the weight, not the holding force",
        """
def holding_torques(robot, q, mass, r_com):
    q = np.asarray(q, dtype=float)
    T = urkin.fk(robot, q)
    f = np.array([0.0, 0.0, -9.81 * mass])
    r = T[:3, :3] @ r_com
    return urkin.jacobian(robot, q).T @ np.r_[f, np.cross(r, f)]
""",
        points=0,
        mistake="let the part fall",
    ),
    Variant(
        "4.8",
        "no moment",
        """
def holding_torques(robot, q, mass, r_com):
    q = np.asarray(q, dtype=float)
    T = urkin.fk(robot, q)
    f = np.array([0.0, 0.0, 9.81 * mass])
    return urkin.jacobian(robot, q).T @ np.r_[f, 0.0, 0.0, 0.0]
""",
        points=2,
        mistake="has no moment",
    ),
    Variant(
        "4.8",
        "offset in the base frame",
        """
def holding_torques(robot, q, mass, r_com):
    q = np.asarray(q, dtype=float)
    T = urkin.fk(robot, q)
    f = np.array([0.0, 0.0, 9.81 * mass])
    return urkin.jacobian(robot, q).T @ np.r_[f, np.cross(r_com, f)]
""",
        points=2,
        mistake="as if it were in the base frame",
    ),
    Variant(
        "4.8",
        "J F",
        """
def holding_torques(robot, q, mass, r_com):
    q = np.asarray(q, dtype=float)
    T = urkin.fk(robot, q)
    f = np.array([0.0, 0.0, 9.81 * mass])
    r = T[:3, :3] @ r_com
    return urkin.jacobian(robot, q) @ np.r_[f, np.cross(r, f)]
""",
        points=0,
        mistake="TRANSPOSED",
    ),
    # ------------------------------------------------------------------------------ 4.9
    Variant(
        "4.9",
        "eigenvalues of J Jᵀ",
        """
def ellipsoid_axes(J_v):
    J = np.asarray(J_v, dtype=float)
    values, vectors = np.linalg.eigh(J @ J.T)
    values, U = values[::-1], vectors[:, ::-1]
    return U, values, 1.0 / values, values[0] / values[2]
""",
        points=0,
        mistake="σ² instead of σ",
    ),
    Variant(
        "4.9",
        "rows of Vᵀ",
        """
def ellipsoid_axes(J_v):
    _, s, Vt = np.linalg.svd(J_v)
    zero = s <= 1e-12 * s[0]
    with np.errstate(divide="ignore"):
        force = np.where(zero, np.inf, 1.0 / s)
    return Vt, s, force, np.inf if zero[2] else s[0] / s[2]
""",
        points=0,
        mistake="rows of Vᵀ",
    ),
    Variant(
        "4.9",
        "force not inverted",
        """
def ellipsoid_axes(J_v):
    U, s, _ = np.linalg.svd(J_v)
    return U, s, s.copy(), np.inf if s[2] <= 1e-12 * s[0] else s[0] / s[2]
""",
        points=0,
        mistake="force semi-axes equal to σ",
    ),
    Variant(
        "4.9",
        "condition upside down",
        """
def ellipsoid_axes(J_v):
    U, s, _ = np.linalg.svd(J_v)
    zero = s <= 1e-12 * s[0]
    with np.errstate(divide="ignore"):
        force = np.where(zero, np.inf, 1.0 / s)
    return U, s, force, s[2] / s[0]
""",
        points=0,
        mistake="upside down",
    ),
    Variant(
        "4.9",
        "condition of J Jᵀ",
        """
def ellipsoid_axes(J_v):
    U, s, _ = np.linalg.svd(J_v)
    zero = s <= 1e-12 * s[0]
    with np.errstate(divide="ignore"):
        force = np.where(zero, np.inf, 1.0 / s)
    return U, s, force, np.linalg.cond(J_v @ J_v.T)
""",
        points=0,
        mistake="the condition number of J Jᵀ",
    ),
    Variant(
        "4.9",
        "sorted ascending",
        """
def ellipsoid_axes(J_v):
    J = np.asarray(J_v, dtype=float)
    values, U = np.linalg.eigh(J @ J.T)
    sigma = np.linalg.norm(J.T @ U, axis=0)
    zero = sigma <= 1e-12 * sigma[-1]
    with np.errstate(divide="ignore"):
        force = np.where(zero, np.inf, 1.0 / sigma)
    return U, sigma, force, np.inf if zero[0] else sigma[-1] / sigma[0]
""",
        points=0,
        mistake="sorted ascending",
    ),
    Variant(
        "4.9",
        "round-off used as it is",
        """
def ellipsoid_axes(J_v):
    U, s, _ = np.linalg.svd(J_v)
    with np.errstate(divide="ignore"):
        force = np.where(s == 0, np.inf, 1.0 / s)
        return U, s, force, s[0] / s[2]
""",
        points=3,
        mistake="used as it is",
    ),
    Variant(
        "4.9",
        "square roots of the eigenvalues",
        """
def ellipsoid_axes(J_v):
    J = np.asarray(J_v, dtype=float)
    values, vectors = np.linalg.eigh(J @ J.T)
    sigma, U = np.sqrt(values[::-1]), vectors[:, ::-1]
    zero = sigma <= 1e-12 * sigma[0]
    with np.errstate(divide="ignore"):
        force = np.where(zero, np.inf, 1.0 / sigma)
    return U, sigma, force, np.inf if zero[2] else sigma[0] / sigma[2]
""",
        points=3,
        mistake="square root",
    ),
    Variant(
        "4.9",
        "a zero threshold too large",
        """
def ellipsoid_axes(J_v):
    U, s, _ = np.linalg.svd(J_v)
    zero = s <= 1e-4 * s[0]
    with np.errstate(divide="ignore"):
        force = np.where(zero, np.inf, 1.0 / s)
    return U, s, force, np.inf if zero[2] else s[0] / s[2]
""",
        points=3,
        mistake="threshold far above round-off",
    ),
    Variant(
        "4.9",
        "float32",
        """
def ellipsoid_axes(J_v):
    U, s, _ = np.linalg.svd(np.asarray(J_v, dtype=np.float32))
    zero = s <= 1e-12 * s[0]
    force = np.where(zero, np.inf, 1.0 / s)
    return U, s, force, np.inf if zero[2] else s[0] / s[2]
""",
        points=0,
        mistake="computed in float32",
    ),
    # ------------------------------------------------------------------------------ 4.10
    Variant(
        "4.10",
        "rows not reordered",
        """
def space_from_geometric(J, T):
    J, p = np.asarray(J, dtype=float), np.asarray(T)[:3, 3]
    return np.vstack([J[:3] + np.cross(p, J[3:], axis=0), J[3:]])
""",
        points=0,
        mistake="rows not reordered",
    ),
    Variant(
        "4.10",
        "v − p × ω",
        """
def space_from_geometric(J, T):
    J, p = np.asarray(J, dtype=float), np.asarray(T)[:3, 3]
    return np.vstack([J[3:], J[:3] + np.cross(J[3:], p, axis=0)])
""",
        points=0,
        mistake="the lever's sign",
    ),
    Variant(
        "4.10",
        "p of the base",
        """
def space_from_geometric(J, T):
    J = np.asarray(J, dtype=float)
    p = np.zeros(3)  # the base origin
    return np.vstack([J[3:], J[:3] + np.cross(p, J[3:], axis=0)])
""",
        points=0,
        mistake="p of the base",
    ),
    Variant(
        "4.10",
        "the body Jacobian",
        """
def space_from_geometric(J, T):
    J, R = np.asarray(J, dtype=float), np.asarray(T)[:3, :3]
    return np.vstack([R.T @ J[3:], R.T @ J[:3]])
""",
        points=0,
        mistake="the body Jacobian",
    ),
    Variant(
        "4.10",
        "six columns assumed",
        """
def space_from_geometric(J, T):
    p = np.asarray(T)[:3, 3]
    J_s = np.zeros((6, 6))
    for i in range(np.shape(J)[1]):
        v, w = np.asarray(J)[:3, i], np.asarray(J)[3:, i]
        J_s[:, i] = np.r_[w, v + np.cross(p, w)]
    return J_s
""",
        points=2,
        mistake="six joints assumed",
    ),
    # ------------------------------------------------------------------------------ 4.11
    Variant(
        "4.11",
        "central differences, h = 1e-6",
        _complex_step_with(
            "(np.asarray(position(q + 1e-6 * e)) - np.asarray(position(q - 1e-6 * e))) / 2e-6"
        ),
        points=1,
        mistake="real step",
    ),
    Variant(
        "4.11",
        "forward differences, h = 1e-6",
        _complex_step_with(
            "(np.asarray(position(q + 1e-6 * e)) - f0) / 1e-6",
            "f0 = np.asarray(position(q))",
        ),
        points=0,
        mistake="real step",
    ),
    Variant(
        "4.11",
        "the real part",
        _complex_step_with("np.real(position(q + 1j * h * e)) / h"),
        points=0,
        mistake="the real part",
    ),
    Variant(
        "4.11",
        "not divided by h",
        _complex_step_with("np.imag(position(q + 1j * h * e))"),
        points=0,
        mistake="not divided by h",
    ),
    Variant(
        "4.11",
        "divided by 2h",
        _complex_step_with("np.imag(position(q + 1j * h * e)) / (2 * h)"),
        points=0,
        mistake="divided by 2h",
    ),
    Variant(
        "4.11",
        "one row per input",
        """
def complex_step_jacobian(position, q, h=1e-20):
    q = np.asarray(q, dtype=float)
    return np.array([np.imag(position(q + 1j * h * e)) / h for e in np.eye(q.size)])
""",
        points=0,
        mistake="transposed",
    ),
    Variant(
        "4.11",
        "1j * h written into a float copy",
        """
def complex_step_jacobian(position, q, h=1e-20):
    q = np.asarray(q, dtype=float)
    J = np.zeros((np.size(position(q)), q.size))
    for j in range(q.size):
        x = q.copy()
        x[j] += 1j * h  # numpy keeps the real part only
        J[:, j] = np.imag(position(x)) / h
    return J
""",
        points=0,
        mistake="imaginary step was lost",
    ),
    Variant(
        "4.11",
        "complex values returned",
        _complex_step_with("np.asarray(position(q + 1j * h * e)) / h"),
        points=0,
        mistake="complex numbers returned",
    ),
    Variant(
        "4.11",
        "h ignored",
        _complex_step_with("np.imag(position(q + 1e-20j * e)) / 1e-20"),
        points=2,
        mistake="h argument is ignored",
    ),
    Variant(
        "4.11",
        "steps pile up",
        """
def complex_step_jacobian(position, q, h=1e-20):
    x = np.array(q, dtype=complex)
    columns = []
    for j in range(x.size):
        x[j] += 1j * h
        columns.append(np.imag(position(x)) / h)
    return np.column_stack(columns)
""",
        points=0,
        mistake="pile up",
    ),
    Variant(
        "4.11",
        "float32 answer",
        _complex_step_with("(np.imag(position(q + 1j * h * e)) / h).astype(np.float32)"),
        points=0,
        mistake="float32",
    ),
]
