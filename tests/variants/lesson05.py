"""Lesson 05: other correct ways to write the exercises, and known mistakes."""

from tests.variants import Variant

# ------------------------------------------------------------------------------ 5.2 pose_error

_QUATERNION = """
def pose_error(T, T_target):
    T, T_target = np.asarray(T, dtype=float), np.asarray(T_target, dtype=float)
    R = T_target[:3, :3] @ T[:3, :3].T
    # a unit quaternion (w, x, y, z) of R by Shepperd's method, then 2 atan2(|v|, w) v / |v|
    trace = np.trace(R)
    i = int(np.argmax([trace, R[0, 0], R[1, 1], R[2, 2]]))
    if i == 0:
        w = 0.5 * np.sqrt(1.0 + trace)
        v = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]]) / (4 * w)
    else:
        a, b, c = (i - 1, i % 3, (i + 1) % 3)
        va = 0.5 * np.sqrt(1.0 + R[a, a] - R[b, b] - R[c, c])
        w = (R[c, b] - R[b, c]) / (4 * va)
        v = np.zeros(3)
        v[a] = va
        v[b] = (R[a, b] + R[b, a]) / (4 * va)
        v[c] = (R[a, c] + R[c, a]) / (4 * va)
    if w < 0:
        w, v = -w, -v
    size = np.linalg.norm(v)
    e_o = v * 2.0 if size < 1e-12 else 2.0 * np.arctan2(size, w) * v / size
    return np.concatenate([T_target[:3, 3] - T[:3, 3], e_o])
"""

_ARCCOS_EIGH = """
def _vee(A):
    return np.array([A[2, 1], A[0, 2], A[1, 0]])


def pose_error(T, T_target):
    T, T_target = np.array(T, dtype=float), np.array(T_target, dtype=float)
    R = T_target[:3, :3] @ T[:3, :3].T
    s = 0.5 * _vee(R - R.T)
    phi = np.arccos(np.clip(0.5 * (np.trace(R) - 1.0), -1.0, 1.0))
    if phi < 1e-6:
        e_o = s
    elif phi < 3.0:
        e_o = phi / np.sin(phi) * s
    else:  # the axis is the eigenvector of the symmetric part with the largest eigenvalue
        values, vectors = np.linalg.eigh(0.5 * (R + R.T))
        k = vectors[:, np.argmax(values)]
        if k @ s < 0:
            k = -k
        e_o = phi * k
    return np.hstack((T_target[:3, 3] - T[:3, 3], e_o))
"""

_CROSS_THEN_SCALED = """
def pose_error(T, T_target):
    T, T_target = np.asarray(T, dtype=float), np.asarray(T_target, dtype=float)
    R, Rt = T[:3, :3], T_target[:3, :3]
    s = np.zeros(3)
    for i in range(3):  # ½ Σ rᵢ × tᵢ = sin φ · k, in the base frame
        s += 0.5 * np.cross(R[:, i], Rt[:, i])
    Re = Rt @ R.T
    c = 0.5 * (Re[0, 0] + Re[1, 1] + Re[2, 2] - 1.0)
    phi = np.arctan2(np.linalg.norm(s), c)
    if phi < 1e-9:
        e_o = s
    elif c > -0.5:
        e_o = phi / np.sin(phi) * s
    else:
        B = 0.5 * (Re + Re.T) - c * np.eye(3)
        col = int(np.argmax(np.diag(B)))
        k = B[:, col] / np.linalg.norm(B[:, col])
        e_o = phi * (k if k @ s >= 0 else -k)
    e_p = T_target[:3, 3] - T[:3, 3]
    return np.array([*e_p, *e_o])
"""

_FLOAT32_ERROR = """
def pose_error(T, T_target):
    T = np.asarray(T, dtype=np.float32)
    T_target = np.asarray(T_target, dtype=np.float32)
    R = T_target[:3, :3] @ T[:3, :3].T
    s = np.float32(0.5) * np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    cos_phi = np.float32(0.5) * (np.trace(R) - np.float32(1.0))
    phi = np.arctan2(np.linalg.norm(s), cos_phi)
    if phi < 1e-6:
        e_o = s
    elif cos_phi > -0.9:
        e_o = (phi / np.sin(phi)) * s
    else:
        B = np.float32(0.5) * (R + R.T) - cos_phi * np.eye(3, dtype=np.float32)
        k = B[:, np.argmax(np.diag(B))]
        k = k / np.linalg.norm(k)
        e_o = phi * (k if k @ s >= 0 else -k)
    return np.concatenate([T_target[:3, 3] - T[:3, 3], e_o]).astype(np.float32)
"""

_POSE_ERROR_BODY = """
def pose_error(T, T_target):
    T, T_target = np.asarray(T, dtype=float), np.asarray(T_target, dtype=float)
    R = T_target[:3, :3] @ T[:3, :3].T
    s = 0.5 * np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    cos_phi = 0.5 * (np.trace(R) - 1.0)
    phi = np.arctan2(np.linalg.norm(s), cos_phi)
    {orientation}
    return {result}
"""

_SOLUTION_ORIENTATION = """if phi < 1e-9:
        e_o = s
    elif cos_phi > -0.9:
        e_o = (phi / np.sin(phi)) * s
    else:
        B = 0.5 * (R + R.T) - cos_phi * np.eye(3)
        k = B[:, np.argmax(np.diag(B))]
        k = k / np.linalg.norm(k)
        e_o = phi * (k if k @ s >= 0.0 else -k)"""


def _pose_error(orientation=_SOLUTION_ORIENTATION, result=None):
    result = result or "np.concatenate([T_target[:3, 3] - T[:3, 3], e_o])"
    return _POSE_ERROR_BODY.format(orientation=orientation, result=result)


_CROSS_ERROR = """
def pose_error(T, T_target):
    T, T_target = np.asarray(T), np.asarray(T_target)
    e_o = 0.5 * sum(np.cross(T[:3, i], T_target[:3, i]) for i in range(3))
    return np.concatenate([T_target[:3, 3] - T[:3, 3], e_o])
"""

_NAIVE = """if phi < 1e-9:
        e_o = s
    else:
        e_o = (phi / np.sin(phi)) * s"""

_ARCCOS_NO_GUARD = """phi = np.arccos(np.clip(cos_phi, -1.0, 1.0))
    if cos_phi > -0.9:
        e_o = (phi / np.sin(phi)) * s
    else:
        B = 0.5 * (R + R.T) - cos_phi * np.eye(3)
        k = B[:, np.argmax(np.diag(B))]
        e_o = phi * (k if k @ s >= 0.0 else -k) / np.linalg.norm(k)"""

_NO_SIGN = _SOLUTION_ORIENTATION.replace("(k if k @ s >= 0.0 else -k)", "k")

# -------------------------------------------------------------------------------- 5.3 ik_newton

_NEWTON = """
def ik_newton(robot, T_target, q0, tol=1e-12, max_iterations=100, max_step=1.0):
    q = np.array(q0, dtype=float)
    for _ in range(max_iterations):
        e = pose_error(urkin.fk(robot, q), T_target)
        if np.linalg.norm(e[:3]) < tol and np.linalg.norm(e[3:]) < tol:
            break
        step = {step}
        largest = np.abs(step).max()
        if largest > max_step:
            step = step * (max_step / largest)
        q = {update}
    return q
"""

_PINV = "np.linalg.pinv(urkin.jacobian(robot, q)) @ e"
_WRAP = "(q + step + np.pi) % (2.0 * np.pi) - np.pi"


def _newton(step=_PINV, update=_WRAP):
    return _NEWTON.format(step=step, update=update)


_NEWTON_WHILE = '''
def _limit(step, largest_allowed):
    """The step scaled down so that its length is at most largest_allowed."""
    length = np.linalg.norm(step)
    return step if length <= largest_allowed else step * (largest_allowed / length)


def _wrap(q):
    return np.arctan2(np.sin(q), np.cos(q))


def ik_newton(robot, T_target, q0, tol=1e-12, max_iterations=100, max_step=1.0):
    q = np.array(q0, dtype=float)
    T_target = np.asarray(T_target)
    e = pose_error(urkin.fk(robot, q), T_target)
    iteration = 0
    while np.abs(e).max() >= tol and iteration < max_iterations:
        J = urkin.jacobian(robot, q)
        q = _wrap(q + _limit(np.linalg.lstsq(J, e, rcond=None)[0], max_step))
        e = pose_error(urkin.fk(robot, q), T_target)
        iteration += 1
    return q
'''

_NEWTON_FLOAT32 = _newton().replace("    return q\n", "    return q.astype(np.float32)\n")

_NEWTON_MIXED_NORM = _newton(
    step="np.linalg.solve(urkin.jacobian(robot, q), e)",
    update="np.mod(q + step + np.pi, 2 * np.pi) - np.pi",
).replace("np.linalg.norm(e[:3]) < tol and np.linalg.norm(e[3:]) < tol", "np.linalg.norm(e) < tol")

_NEWTON_INVERTED = """
def ik_newton(robot, T_target, q0, tol=1e-12, max_iterations=100, max_step=1.0):
    q = np.array(q0, dtype=float)
    e = pose_error(urkin.fk(robot, q), T_target)
    while np.linalg.norm(e) < tol:  # seed 001's loop condition
        step = np.linalg.pinv(urkin.jacobian(robot, q)) @ e
        q = q + step * min(1.0, max_step / np.abs(step).max())
        e = pose_error(urkin.fk(robot, q), T_target)
    return q
"""

_NEWTON_CROSS = """
def ik_newton(robot, T_target, q0, tol=1e-12, max_iterations=100, max_step=1.0):
    q = np.array(q0, dtype=float)
    for _ in range(max_iterations):
        T = urkin.fk(robot, q)
        e_o = 0.5 * sum(np.cross(T[:3, i], T_target[:3, i]) for i in range(3))
        e = np.r_[T_target[:3, 3] - T[:3, 3], e_o]
        if np.abs(e).max() < tol:
            break
        step = np.linalg.pinv(urkin.jacobian(robot, q)) @ e
        step = step * min(1.0, max_step / np.abs(step).max())
        q = (q + step + np.pi) % (2.0 * np.pi) - np.pi
    return q
"""

_NEWTON_LIST_UNSAFE = """
def ik_newton(robot, T_target, q0, tol=1e-12, max_iterations=100, max_step=1.0):
    q = q0.astype(float)
    for _ in range(max_iterations):
        e = pose_error(urkin.fk(robot, q), T_target)
        if np.linalg.norm(e[:3]) < tol and np.linalg.norm(e[3:]) < tol:
            break
        step = np.linalg.pinv(urkin.jacobian(robot, q)) @ e
        largest = np.abs(step).max()
        if largest > max_step:
            step = step * (max_step / largest)
        q = (q + step + np.pi) % (2.0 * np.pi) - np.pi
    return q
"""

# ------------------------------------------------------------------------------ 5.1 ik_position

_POSITION = """
def ik_position(robot, p_target, q0, tol=1e-12, max_iterations=100, max_step=1.0):
    q = np.array(q0, dtype=float)
    p_target = np.asarray(p_target, dtype=float)
    for _ in range(max_iterations):
        e = p_target - urkin.fk(robot, q)[:3, 3]
        if np.linalg.norm(e) < tol:
            break
        step = {step}
        largest = np.abs(step).max()
        if largest > max_step:
            step = step * (max_step / largest)
        q = {update}
    return q
"""

_POSITION_PINV = "np.linalg.pinv(urkin.kinematics.position_jacobian(robot, q)) @ e"


def _position(step=_POSITION_PINV, update=_WRAP):
    return _POSITION.format(step=step, update=update)


_POSITION_RIGHT_INVERSE = _position(
    step="(lambda Jv: Jv.T @ np.linalg.solve(Jv @ Jv.T, e))(urkin.jacobian(robot, q)[:3])",
    update="np.arctan2(np.sin(q + step), np.cos(q + step))",
)

_POSITION_LSTSQ = """
def ik_position(robot, p_target, q0, tol=1e-12, max_iterations=100, max_step=1.0):
    q = np.asarray(q0, dtype=float).copy()
    for iteration in range(max_iterations):
        p = urkin.fk(robot, q)[:3, 3]
        e = np.asarray(p_target, dtype=float) - p
        if np.abs(e).max() < tol:
            return q
        J = urkin.jacobian(robot, q)[:3, :]
        dq, *_ = np.linalg.lstsq(J, e, rcond=None)  # the shortest step that solves J dq = e
        if np.linalg.norm(dq) > max_step:
            dq *= max_step / np.linalg.norm(dq)
        q = np.mod(q + dq + np.pi, 2 * np.pi) - np.pi
    return q
"""

_POSITION_FLOAT32 = _position().replace("    return q\n", "    return np.float32(q)\n")

_POSITION_SIX = """
def ik_position(robot, p_target, q0, tol=1e-12, max_iterations=100, max_step=1.0):
    q = np.array(q0, dtype=float)
    for _ in range(max_iterations):
        e = np.r_[np.asarray(p_target) - urkin.fk(robot, q)[:3, 3], 0.0, 0.0, 0.0]
        if np.linalg.norm(e) < tol:
            break
        step = np.linalg.pinv(urkin.jacobian(robot, q)) @ e
        step = step * min(1.0, max_step / np.abs(step).max())
        q = (q + step + np.pi) % (2.0 * np.pi) - np.pi
    return q
"""

_POSITION_MM = (
    _position()
    .replace(
        "e = p_target - urkin.fk(robot, q)[:3, 3]",
        "e = p_target - 1000 * urkin.fk(robot, q)[:3, 3]",
    )
    .replace(
        "np.linalg.pinv(urkin.kinematics.position_jacobian(robot, q)) @ e",
        "np.linalg.pinv(1000 * urkin.kinematics.position_jacobian(robot, q)) @ e",
    )
)

CORRECT = [
    Variant("5.2", "quaternion, then 2 atan2(|v|, w)", _QUATERNION),
    Variant("5.2", "arccos with guards, eigenvector near π", _ARCCOS_EIGH),
    Variant("5.2", "s as ½ Σ rᵢ × tᵢ, scaled by φ / sin φ", _CROSS_THEN_SCALED),
    Variant("5.2", "float32 answer", _FLOAT32_ERROR),
    Variant(
        "5.3", "np.linalg.solve(J, e)", _newton(step="np.linalg.solve(urkin.jacobian(robot, q), e)")
    ),
    Variant("5.3", "lstsq, norm-limited step, arctan2 wrap, while loop", _NEWTON_WHILE),
    Variant("5.3", "one mixed norm, np.mod wrap", _NEWTON_MIXED_NORM),
    Variant("5.3", "float32 answer", _NEWTON_FLOAT32),
    Variant("5.1", "position_jacobian and pinv", _position()),
    Variant("5.1", "Jᵀ(JJᵀ)⁻¹ by solve, arctan2 wrap", _POSITION_RIGHT_INVERSE),
    Variant("5.1", "lstsq, norm-limited, max-abs test", _POSITION_LSTSQ),
    Variant("5.1", "float32 answer", _POSITION_FLOAT32),
    Variant(
        "5.4",
        "np.polyfit on the log pairs of the last three",
        """
def convergence_order(errors):
    e = np.asarray(errors, dtype=float)
    if e.shape[0] < 3:
        raise ValueError("errors: at least three values are needed")
    if np.any(~np.isfinite(e)) or np.any(e <= 0):
        raise ValueError("every value of errors must be positive and finite")
    if e[-2] == e[-3]:
        raise ValueError("errors: log(e_k / e_k-1) is zero, the order is undefined")
    logs = np.log(e[-3:])
    slope, _ = np.polyfit(logs[:-1], logs[1:], 1)  # log e_k+1 = p log e_k + log C
    return float(slope)
""",
    ),
    Variant(
        "5.4",
        "math.log10 on plain floats, a loop of checks",
        """
import math


def convergence_order(errors):
    values = [float(x) for x in errors]
    if len(values) < 3:
        raise ValueError(f"need three errors, got {len(values)}")
    for x in values:
        if not (math.isfinite(x) and x > 0):
            raise ValueError(f"errors must be positive and finite, found {x}")
    e0, e1, e2 = values[-3:]
    if e1 == e0:
        raise ValueError("the last errors repeat: no order")
    return math.log10(e2 / e1) / math.log10(e1 / e0)
""",
    ),
    # ------------------------------------------------------------------------------ 5.5
    Variant(
        "5.5",
        "least squares for J⁺ e and an SVD basis of the null space",
        """
def null_space_step(J, e, q, q_rest, gain):
    J = np.asarray(J, dtype=float)
    task = np.linalg.lstsq(J, e, rcond=None)[0]
    U, sigma, Vt = np.linalg.svd(J)
    rank = int(np.sum(sigma > 1e-12 * sigma.max()))
    null = Vt[rank:].T  # orthonormal basis of the null space
    pull = (np.asarray(q_rest) - np.asarray(q) + np.pi) % (2 * np.pi) - np.pi
    return task + gain * null @ (null.T @ pull)
""",
    ),
    # ------------------------------------------------------------------------------ 5.6
    Variant(
        "5.6",
        "lists, the index of the last reached row, allclose as the test",
        """
def track_positions(robot, points, q0, solve, tol=1e-9):
    rows, reached = [], []
    last = None
    for p in np.asarray(points, dtype=float):
        start = np.asarray(q0, dtype=float) if last is None else rows[last]
        answer = np.asarray(solve(robot, p, start.tolist()), dtype=float)
        good = bool(np.allclose(urkin.fk(robot, answer)[:3, 3], p, rtol=0, atol=tol / 2))
        reached.append(good)
        rows.append(answer if good else start)
        if good:
            last = len(rows) - 1
    return np.array(rows), np.array(reached)
""",
    ),
    Variant(
        "5.6",
        "answers wrapped into [−π, π) before they are kept",
        """
def track_positions(robot, points, q0, solve, tol=1e-9):
    q = urkin.transforms.wrap_angles(np.asarray(q0, dtype=float))
    Q, ok = [], []
    for p in points:
        p = np.asarray(p, dtype=float)
        answer = urkin.transforms.wrap_angles(np.asarray(solve(robot, p, q), dtype=float))
        hit = np.linalg.norm(urkin.fk(robot, answer)[:3, 3] - p) < tol
        if hit:
            q = answer
        Q.append(q)
        ok.append(hit)
    return np.vstack(Q), np.array(ok, dtype=bool)
""",
    ),
]

_NEWTON_TOOL_FRAME = _newton(
    step="np.linalg.pinv(urkin.jacobian(robot, q))"
    " @ np.r_[e[:3], urkin.fk(robot, q)[:3, :3].T @ e[3:]]"
)


def _order(last="e[-3:]", result="np.log(c / b) / np.log(b / a)", checked="e"):
    """A convergence_order with its input checks, its three errors and its formula
    replaceable (a, b, c: the three errors, oldest first)."""
    return f"""
def convergence_order(errors):
    e = np.asarray(errors, dtype=float)
    if e.size < 3:
        raise ValueError("errors must hold at least three values")
    if not np.all(np.isfinite({checked}) & ({checked} > 0)):
        raise ValueError("errors must be positive and finite")
    if e[-2] == e[-3]:
        raise ValueError("errors: e_k = e_k-1, the order is undefined")
    a, b, c = {last}
    return float({result})
"""


def _track(
    guess="q",
    keep="if ok[k]:\n            q = answer",
    ok_value="np.linalg.norm(urkin.fk(robot, answer)[:3, 3] - p) <= tol",
    before="",
    post="Q[k] = q",
    returned="Q, ok",
):
    """A track_positions with its guess, its update of q, its ok, where the row is stored and
    what it returns replaceable (``last``: the last answer, reached or not)."""
    return f"""
def track_positions(robot, points, q0, solve, tol=1e-9):
    points = np.asarray(points, dtype=float)
    q = np.array(q0, dtype=float)
    last = q.copy()
    Q = np.empty((len(points), 6))
    ok = np.zeros(len(points), dtype=bool)
    for k, p in enumerate(points):
        {before}
        answer = np.asarray(solve(robot, p, {guess}.copy()), dtype=float)
        ok[k] = {ok_value}
        {keep}
        {post}
    return {returned}
"""


WRONG = [
    Variant("5.2", "seed 000's cross-product error", _CROSS_ERROR, 0, "cross-product"),
    Variant(
        "5.2",
        "current − target",
        _pose_error(result="-np.concatenate([T_target[:3, 3] - T[:3, 3], e_o])"),
        0,
        "wrong way",
    ),
    Variant(
        "5.2",
        "tool frame",
        _pose_error(result="np.concatenate([T_target[:3, 3] - T[:3, 3], T[:3, :3].T @ e_o])"),
        0,
        "tool frame",
    ),
    Variant(
        "5.2",
        "(orientation; position)",
        _pose_error(result="np.concatenate([e_o, T_target[:3, 3] - T[:3, 3]])"),
        0,
        "order",
    ),
    Variant(
        "5.2",
        "degrees",
        _pose_error(result="np.concatenate([T_target[:3, 3] - T[:3, 3], np.degrees(e_o)])"),
        0,
        "degrees",
    ),
    Variant("5.2", "no half-turn branch", _pose_error(_NAIVE), 2, "half-turn"),
    Variant("5.2", "arccos, 0/0 at no turn", _pose_error(_ARCCOS_NO_GUARD), 2, "0/0"),
    Variant("5.2", "no sign for k near π", _pose_error(_NO_SIGN), None, "sign of k"),
    Variant(
        "5.2",
        "factor ½ missing",
        _pose_error(result="np.concatenate([T_target[:3, 3] - T[:3, 3], 2 * e_o])"),
        0,
        "½",
    ),
    Variant("5.3", "no wrapping", _newton(update="q + step"), 5, "not wrapped"),
    Variant(
        "5.3", "wrapped into [0, 2π)", _newton(update="(q + step) % (2 * np.pi)"), 5, "[0, 2π)"
    ),
    Variant(
        "5.3",
        "no step limit",
        _newton().replace("if largest > max_step:", "if False:"),
        None,
        "max_step",
    ),
    Variant(
        "5.3",
        "max_step ignored",
        _newton()
        .replace("max_step / largest", "1.0 / largest")
        .replace("largest > max_step", "largest > 1.0"),
        5,
        "max_step",
    ),
    Variant(
        "5.3",
        "clipped step",
        _newton().replace(
            "step = step * (max_step / largest)", "step = np.clip(step, -max_step, max_step)"
        ),
        None,
        "clipped",
    ),
    Variant(
        "5.3",
        "q − Δq",
        _newton(update="(q - step + np.pi) % (2.0 * np.pi) - np.pi"),
        0,
        "wrong way",
    ),
    Variant(
        "5.3",
        "Jacobian transpose",
        _newton(step="urkin.jacobian(robot, q).T @ e"),
        None,
        "transpose",
    ),
    Variant(
        "5.3",
        "max_iterations ignored",
        _newton().replace("range(max_iterations)", "range(100)"),
        5,
        "max_iterations",
    ),
    Variant("5.3", "loop condition inverted, returns q0", _NEWTON_INVERTED, 0, "unchanged"),
    Variant("5.3", "cross-product error inline", _NEWTON_CROSS, None, "cross-product"),
    Variant(
        "5.3",
        "orientation error turned into the tool frame",
        _NEWTON_TOOL_FRAME,
        None,
        "tool frame",
    ),
    Variant(
        "5.3",
        "returns q0",
        "def ik_newton(robot, T_target, q0, tol=1e-12, max_iterations=100, max_step=1.0):\n"
        "    return np.array(q0, dtype=float)\n",
        0,
        "unchanged",
    ),
    Variant("5.3", "q0.astype: fails for a list", _NEWTON_LIST_UNSAFE, 5, "list"),
    Variant("5.1", "6 × 6 Jacobian, zero orientation error", _POSITION_SIX, None, "3 × 6"),
    Variant(
        "5.1",
        "ω rows instead of v rows",
        _position(step="np.linalg.pinv(urkin.jacobian(robot, q)[3:]) @ e"),
        None,
        "bottom three rows",
    ),
    Variant("5.1", "no wrapping", _position(update="q + step"), 3, "not wrapped"),
    Variant(
        "5.1",
        "returns q0",
        "def ik_position(robot, p_target, q0, tol=1e-12, max_iterations=100, max_step=1.0):\n"
        "    return np.array(q0, dtype=float)\n",
        0,
        "unchanged",
    ),
    Variant(
        "5.1",
        "no step limit",
        _position().replace("if largest > max_step:", "if False:"),
        None,
        "max_step",
    ),
    Variant(
        "5.1",
        "q − Δq",
        _position(update="(q - step + np.pi) % (2.0 * np.pi) - np.pi"),
        0,
        "wrong way",
    ),
    Variant("5.1", "millimetres", _POSITION_MM, None, "millimetres"),
    Variant(
        "5.1",
        "target in millimetres",
        _position().replace(
            "p_target = np.asarray(p_target, dtype=float)",
            "p_target = 1000 * np.asarray(p_target, dtype=float)",
        ),
        None,
        "millimetres",
    ),
    Variant(
        "5.1",
        "millimetres on both sides of e",
        _position().replace(
            "e = p_target - urkin.fk(robot, q)[:3, 3]",
            "e = 1000 * p_target - 1000 * urkin.fk(robot, q)[:3, 3]",
        ),
        None,
        "millimetres on both sides",
    ),
    Variant("5.4", "the first three errors", _order(last="e[:3]"), 2, "first three"),
    Variant(
        "5.4",
        "the ratio upside down",
        _order(result="np.log(b / a) / np.log(c / b)"),
        1,
        "upside down",
    ),
    Variant(
        "5.4",
        "differences instead of logarithms",
        _order(result="(c - b) / (b - a)"),
        1,
        "differences instead of logarithms",
    ),
    Variant("5.4", "the rate e_k+1 / e_k", _order(result="c / b"), 1, "the rate"),
    Variant(
        "5.4",
        "log e_k+1 / log e_k",
        _order(result="np.log(c) / np.log(b)"),
        1,
        "log e_(k+1) / log e_k",
    ),
    Variant(
        "5.4",
        "no check of the input",
        """
def convergence_order(errors):
    a, b, c = np.asarray(errors, dtype=float)[-3:]
    return float(np.log(c / b) / np.log(b / a))
""",
        2,
        "no check of the input",
    ),
    Variant(
        "5.4",
        "checks only the last three",
        _order(checked="e[-3:]"),
        2,
        "no check of the input",
    ),
    Variant(
        "5.4",
        "an assert instead of ValueError",
        """
def convergence_order(errors):
    e = np.asarray(errors, dtype=float)
    assert len(e) >= 3 and np.all(np.isfinite(e) & (e > 0)) and e[-2] != e[-3], "bad errors"
    a, b, c = e[-3:]
    return float(np.log(c / b) / np.log(b / a))
""",
        2,
        "another exception than ValueError",
    ),
    # ------------------------------------------------------------------------------ 5.5
    Variant(
        "5.5",
        "no projector",
        """
def null_space_step(J, e, q, q_rest, gain):
    pull = (np.asarray(q_rest) - np.asarray(q) + np.pi) % (2 * np.pi) - np.pi
    return np.linalg.pinv(J) @ e + gain * pull
""",
        points=0,
        mistake="without the projector",
    ),
    Variant(
        "5.5",
        "not wrapped",
        """
def null_space_step(J, e, q, q_rest, gain):
    J_plus = np.linalg.pinv(J)
    N = np.eye(np.shape(J)[1]) - J_plus @ J
    return J_plus @ e + gain * N @ (np.asarray(q_rest) - np.asarray(q))
""",
        points=3,
        mistake="not wrapped",
    ),
    Variant(
        "5.5",
        "transpose for pseudo-inverse",
        """
def null_space_step(J, e, q, q_rest, gain):
    J = np.asarray(J, dtype=float)
    pull = (np.asarray(q_rest) - np.asarray(q) + np.pi) % (2 * np.pi) - np.pi
    return np.linalg.pinv(J) @ e + gain * (np.eye(J.shape[1]) - J.T @ J) @ pull
""",
        points=0,
        mistake="Jᵀ in place of J⁺",
    ),
    Variant(
        "5.5",
        "six joints hard-coded",
        """
def null_space_step(J, e, q, q_rest, gain):
    J_plus = np.linalg.pinv(J)
    pull = (np.asarray(q_rest) - np.asarray(q) + np.pi) % (2 * np.pi) - np.pi
    return J_plus @ e + gain * (np.eye(6) - J_plus @ J) @ pull
""",
        points=3,
        mistake=None,
    ),
    # ------------------------------------------------------------------------------ 5.6
    Variant(
        "5.6", "cold start from q0", _track(guess="np.array(q0, dtype=float)"), 1, "cold start"
    ),
    Variant(
        "5.6",
        "failed answer overwrites q (seed 000)",
        _track(keep="q = answer"),
        3,
        "overwrites the arm's configuration",
    ),
    Variant(
        "5.6",
        "next guess from the failed answer",
        _track(guess="last", keep="if ok[k]:\n            q = answer\n        last = answer"),
        3,
        "starts from the failed answer",
    ),
    Variant(
        "5.6",
        "ok not recorded",
        """
def track_positions(robot, points, q0, solve, tol=1e-9):
    q = np.array(q0, dtype=float)
    Q, ok = [], np.ones(len(points), dtype=bool)
    for p in np.asarray(points, dtype=float):
        answer = np.asarray(solve(robot, p, q), dtype=float)
        if np.linalg.norm(urkin.fk(robot, answer)[:3, 3] - p) <= tol:
            q = answer
        Q.append(q.copy())
    return np.array(Q), ok
""",
        3,
        "ok is not recorded",
    ),
    Variant(
        "5.6",
        "no fk test: every answer kept and ok",
        _track(ok_value="True", keep="q = answer"),
        3,
        "every answer taken as reached",
    ),
    Variant(
        "5.6",
        "off by one: q0 taken for points[0]",
        """
def track_positions(robot, points, q0, solve, tol=1e-9):
    points = np.asarray(points, dtype=float)
    Q = [np.array(q0, dtype=float)]
    ok = [True]
    for p in points[1:]:  # point k+1 solved from row k
        answer = np.asarray(solve(robot, p, Q[-1].copy()), dtype=float)
        hit = np.linalg.norm(urkin.fk(robot, answer)[:3, 3] - p) <= tol
        Q.append(answer if hit else Q[-1])
        ok.append(hit)
    return np.array(Q), np.array(ok)
""",
        0,
        "q0 taken as the answer for points[0]",
    ),
    Variant(
        "5.6",
        "off by one: row stored before solving",
        _track(before="Q[k] = q", post=""),
        0,
        "stored before its point is solved",
    ),
    Variant(
        "5.6",
        "only Q returned",
        _track(returned="Q"),
        0,
        "only Q returned",
    ),
]
