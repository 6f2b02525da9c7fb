"""Lesson 06: other correct ways to write the exercises, and known mistakes."""

from tests.variants import Variant

# ------------------------------------------------------------------------------- 6.1 dls_step

_DLS_CHOLESKY = """
def dls_step(J, e, lam):
    J, e = np.asarray(J, dtype=float), np.asarray(e, dtype=float)
    A = J @ J.T + lam**2 * np.eye(len(e))
    L = np.linalg.cholesky(A)  # A = L Lᵀ: two triangular solves apply A⁻¹
    y = np.linalg.solve(L, e)
    return J.T @ np.linalg.solve(L.T, y)
"""

_DLS_LM_FORM = """
def dls_step(J, e, lam):
    J = np.array(J, dtype=float)
    n = J.shape[1]
    return np.linalg.solve(J.T @ J + lam * lam * np.identity(n), J.T @ np.asarray(e, float))
"""

_DLS_AUGMENTED = '''
def dls_step(J, e, lam):
    """min ‖J Δq − e‖² + λ²‖Δq‖²: least squares on [J; λI] Δq = [e; 0]."""
    J, e = np.asarray(J, dtype=float), np.asarray(e, dtype=float)
    m, n = J.shape
    A = np.vstack([J, lam * np.eye(n)])
    b = np.concatenate([e, np.zeros(n)])
    return np.linalg.lstsq(A, b, rcond=None)[0]
'''

_DLS_FLOAT32 = """
def dls_step(J, e, lam):
    J = np.asarray(J, dtype=np.float32)
    e = np.asarray(e, dtype=np.float32)
    damping = np.float32(lam) ** 2 * np.eye(J.shape[0], dtype=np.float32)
    return J.T @ np.linalg.solve(J @ J.T + damping, e)
"""

_DLS_LOOPS = """
def _damped_matrix(J, lam):
    m = len(J)
    A = [[sum(J[i][k] * J[j][k] for k in range(len(J[0]))) for j in range(m)] for i in range(m)]
    for i in range(m):
        A[i][i] += lam**2
    return np.array(A)


def dls_step(J, e, lam):
    J = np.asarray(J, dtype=float)
    x = np.linalg.solve(_damped_matrix(J, lam), np.asarray(e, dtype=float))
    return J.T @ x
"""

_DLS = """
def dls_step(J, e, lam):
    J = np.asarray(J, dtype=float)
    e = np.asarray(e, dtype=float)
    return {body}
"""


def _dls(body):
    return _DLS.format(body=body)


_DLS_SVD_HELPER = """
def damped_svd_step(jac, err, lam):
    # Σ σ/(σ² + lam²) (uᵀ err) v over the SVD of jac: the lesson's helper of section 1
    U_, s_, Vt_ = np.linalg.svd(jac, full_matrices=False)
    keep = s_ > 1e-12 * s_[0]
    gain = np.where(keep, s_ / np.where(keep, s_**2 + lam**2, 1.0), 0.0)
    return Vt_.T @ (gain * (U_.T @ err))


def dls_step(J, e, lam):
    return damped_svd_step(np.asarray(J, dtype=float), np.asarray(e, dtype=float), lam)
"""

_SEED000_UNDEFINED_I = """
def dls_step(J, e, lam):
    J_dls = J.T * (J * J.T + lam**2 * I)**-1
    return J_dls @ e
"""

_SEED000_EYE = """
def dls_step(J, e, lam):
    I = np.eye(len(e))
    J_dls = J.T * (J * J.T + lam**2 * I)**-1
    return J_dls @ e
"""

# -------------------------------------------------------------------------------- 6.2 lm_step

_LM = """
def lm_step(J, e, mu):
    J = np.asarray(J, dtype=float)
    e = np.asarray(e, dtype=float)
    return {body}
"""


def _lm(body):
    return _LM.format(body=body)


_LM_AUGMENTED = """
def lm_step(J, e, mu):
    J, e = np.asarray(J, dtype=float), np.asarray(e, dtype=float)
    n = J.shape[1]
    stacked = np.concatenate([J, np.sqrt(mu) * np.eye(n)])
    rhs = np.concatenate([e, np.zeros(n)])
    step, *_ = np.linalg.lstsq(stacked, rhs, rcond=None)
    return step
"""

_LM_CHOLESKY = """
def lm_step(J, e, mu):
    J = np.asarray(J, dtype=float)
    A = J.T @ J
    A[np.diag_indices_from(A)] += mu
    L = np.linalg.cholesky(A)
    return np.linalg.solve(L.T, np.linalg.solve(L, J.T @ np.asarray(e, dtype=float)))
"""

_LM_FLOAT32 = """
def lm_step(J, e, mu):
    J = np.asarray(J, dtype=np.float32)
    A = J.T @ J + np.float32(mu) * np.eye(J.shape[1], dtype=np.float32)
    return np.linalg.solve(A, J.T @ np.asarray(e, dtype=np.float32))
"""

# ---------------------------------------------------------------------------------- 6.3 ik_lm

_IK_LM = """
def ik_lm(robot, T_target, q0):
    T_target = np.asarray(T_target, dtype=float)

    def pose_error(q):
        T = urkin.fk(robot, q)
        return np.r_[T_target[:3, 3] - T[:3, 3], orientation_error(T[:3, :3], T_target[:3, :3])]

    rng = np.random.default_rng(0)
    q = np.asarray(q0, dtype=float).copy()
    best_q, best_cost = q.copy(), np.inf
    for _ in range({attempts}):
        error = pose_error(q)
        cost = error @ error
        mu = 1e-3
        for _ in range(200):
            if cost < best_cost:
                best_q, best_cost = q.copy(), cost
            if np.abs(error).max() < {tol}:
                return q
            step = {step}
            largest = np.abs(step).max()
            if largest > 0.5:
                step = step * (0.5 / largest)
            trial_error = pose_error(q + step)
            trial_cost = trial_error @ trial_error
            if {accept}:
                q, error, cost = q + step, trial_error, trial_cost
                mu = {down}
            else:
                mu = {up}
                if mu > 1e8:
                    break
        q = {restart}
    return best_q
"""


def _ik_lm(
    attempts="21",
    tol="1e-12",
    step="lm_step(urkin.jacobian(robot, q), error, mu)",
    accept="trial_cost < cost",
    down="max(mu / 3.0, 1e-12)",
    up="2.0 * mu",
    restart="rng.uniform(-np.pi, np.pi, 6)",
):
    return _IK_LM.format(
        attempts=attempts, tol=tol, step=step, accept=accept, down=down, up=up, restart=restart
    )


_IK_LM_TEN = """
def _wrap(q):
    return (q + np.pi) % (2 * np.pi) - np.pi


def _error(robot, q, T_target):
    T = urkin.fk(robot, q)
    return np.concatenate([T_target[:3, 3] - T[:3, 3],
                           orientation_error(T[:3, :3], T_target[:3, :3])])


def ik_lm(robot, T_target, q0):
    rng = np.random.default_rng(1)
    T_target = np.array(T_target, dtype=float)
    q = _wrap(np.array(q0, dtype=float))
    for attempt in range(11):
        mu = 1e-2
        e = _error(robot, q, T_target)
        iterations = 0
        while np.linalg.norm(e) > 1e-12 and mu < 1e6 and iterations < 300:
            J = urkin.jacobian(robot, q)
            dq = lm_step(J, e, mu=mu)
            dq = dq / max(1.0, np.abs(dq).max())
            q_new = _wrap(q + dq)
            e_new = _error(robot, q_new, T_target)
            if np.linalg.norm(e_new) < np.linalg.norm(e):
                q, e = q_new, e_new
                mu = max(mu / 10, 1e-10)
            else:
                mu = mu * 10
            iterations += 1
        if np.linalg.norm(e) <= 1e-12:
            return q
        q = rng.uniform(-np.pi, np.pi, size=6)
    return q
"""

_IK_LM_NIELSEN = """
def ik_lm(robot, T_target, q0):
    T_target = np.asarray(T_target, dtype=float)

    def residual(q):
        T = urkin.fk(robot, q)
        return np.r_[T_target[:3, 3] - T[:3, 3], orientation_error(T[:3, :3], T_target[:3, :3])]

    start = np.array(q0, dtype=float)
    best, best_norm = start, np.inf
    for attempt in range(25):
        q = start if attempt == 0 else np.random.uniform(-np.pi, np.pi, 6)
        e = residual(q)
        J = urkin.jacobian(robot, q)
        mu, nu = 1e-3 * np.max(np.diag(J.T @ J)), 2.0
        for _ in range(150):
            if np.linalg.norm(e) < best_norm:
                best, best_norm = q, np.linalg.norm(e)
            if max(np.linalg.norm(e[:3]), np.linalg.norm(e[3:])) < 1e-12:
                return q
            J = urkin.jacobian(robot, q)
            h = lm_step(J, e, mu)
            h = h * min(1.0, 1.0 / np.abs(h).max())
            e_new = residual(q + h)
            predicted = e @ e - (e - J @ h) @ (e - J @ h)
            rho = (e @ e - e_new @ e_new) / predicted if predicted > 0 else -1.0
            if rho > 0:  # Nielsen's rule: the better the linear model did, the smaller μ
                q, e = q + h, e_new
                mu *= max(1 / 3, 1 - (2 * rho - 1) ** 3)
                nu = 2.0
            else:
                mu *= nu
                nu *= 2
            if mu > 1e10:
                break
    return best
"""

_IK_LM_MARQUARDT = '''
def _log(R):
    s = 0.5 * np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    c = 0.5 * (np.trace(R) - 1)
    phi = np.arctan2(np.linalg.norm(s), c)
    if phi < 1e-12:
        return s
    if c > -0.5:
        return phi / np.sin(phi) * s
    B = 0.5 * (R + R.T) - c * np.eye(3)
    k = B[:, np.argmax(np.diag(B))]
    k = k / np.linalg.norm(k)
    return phi * (k if k @ s >= 0 else -k)


def ik_lm(robot, T_target, q0):
    """Marquardt's thresholds on the gain ratio; restarts near q0, then anywhere."""
    generator = np.random.default_rng(12345)
    q_start = np.asarray(q0, dtype=float)
    for restart in range(30):
        if restart == 0:
            q = q_start.copy()
        elif restart < 3:
            q = q_start + generator.normal(0.0, 1.0, 6)
        else:
            q = generator.uniform(-np.pi, np.pi, 6)
        mu = 1e-3
        T = urkin.fk(robot, q)
        e = np.r_[T_target[:3, 3] - T[:3, 3], _log(T_target[:3, :3] @ T[:3, :3].T)]
        for iteration in range(200):
            if np.all(np.abs(e) < 1e-12):
                return q
            J = urkin.jacobian(robot, q)
            dq = lm_step(J, e, mu)
            scale = np.abs(dq).max()
            if scale > 0.5:
                dq = dq * 0.5 / scale
            T_new = urkin.fk(robot, q + dq)
            e_new = np.r_[T_target[:3, 3] - T_new[:3, 3],
                          _log(T_target[:3, :3] @ T_new[:3, :3].T)]
            predicted = 2 * e @ (J @ dq) - (J @ dq) @ (J @ dq)
            rho = (e @ e - e_new @ e_new) / predicted if predicted > 0 else -1
            if rho > 0:
                q, e = q + dq, e_new
            if rho > 0.75:
                mu = mu / 3
            elif rho < 0.25:
                mu = mu * 2
            if mu > 1e8:
                break
    return q
'''

_IK_LM_UNDO = (
    _ik_lm()
    .replace(
        "            trial_error = pose_error(q + step)\n",
        "            q = q + step\n            trial_error = pose_error(q)\n",
    )
    .replace(
        "q, error, cost = q + step, trial_error, trial_cost",
        "error, cost = trial_error, trial_cost",
    )
    .replace(
        "                mu = 2.0 * mu\n",
        "                q = q - step  # undo\n                mu = 2.0 * mu\n",
    )
)

_IK_LM_FLOAT32 = _ik_lm().replace(
    "                return q\n", "                return q.astype(np.float32)\n"
)

_FIXED_DLS = """
def ik_lm(robot, T_target, q0):
    T_target = np.asarray(T_target, dtype=float)
    rng = np.random.default_rng(0)
    q = np.asarray(q0, dtype=float)
    for attempt in range(21):
        for _ in range(200):
            T = urkin.fk(robot, q)
            e = np.r_[T_target[:3, 3] - T[:3, 3], orientation_error(T[:3, :3], T_target[:3, :3])]
            if np.abs(e).max() < 1e-12:
                return q
            step = lm_step(urkin.jacobian(robot, q), e, {mu})
            q = q + step * min(1.0, 0.5 / np.abs(step).max())
        q = rng.uniform(-np.pi, np.pi, 6)
    return q
"""

_IK_LM_TIES = _ik_lm(
    accept="np.abs(trial_error).max() <= np.abs(error).max()",
    down="max(mu / 2.0, 1e-7)",
    up="4.0 * mu",
)

_IK_LM_PATIENCE = '''
def ik_lm(robot, T_target, q0):
    """Restarts when 20 iterations bring no 1 % progress; steps limited in length."""
    rng = np.random.default_rng(2024)

    def error_at(q):
        T = urkin.fk(robot, q)
        return np.r_[T_target[:3, 3] - T[:3, 3], orientation_error(T[:3, :3], T_target[:3, :3])]

    q = np.array(q0, dtype=float)
    for restart in range(40):
        e, mu, stale, best = error_at(q), 1e-2, 0, np.inf
        while stale < 20:
            if np.linalg.norm(e[:3]) < 1e-12 and np.linalg.norm(e[3:]) < 1e-12:
                return q
            step = lm_step(urkin.jacobian(robot, q), e, mu)
            length = np.linalg.norm(step)
            if length > 0.4:
                step *= 0.4 / length
            e_new = error_at(q + step)
            if e_new @ e_new < e @ e:
                q, e, mu = q + step, e_new, mu / 5
            else:
                mu *= 5
            size = np.linalg.norm(e)
            stale = 0 if size < 0.99 * best else stale + 1
            best = min(best, size)
        q = rng.uniform(-np.pi, np.pi, 6)
    return q
'''

_IK_LM_TWICE = _ik_lm().replace(
    "                q, error, cost = q + step, trial_error, trial_cost\n",
    "                again = lm_step(urkin.jacobian(robot, q), error, mu)  # the same step again\n"
    "                again = again * min(1.0, 0.5 / np.abs(again).max())\n"
    "                q, error, cost = q + again, trial_error, trial_cost\n",
)

_IK_LM_ACCEPT_ALL = _ik_lm(
    accept="True", down="max(mu / 3.0, 1e-12) if better else 2.0 * mu"
).replace(
    "            if True:\n", "            better = trial_cost < cost\n            if True:\n"
)

_IK_LM_NO_UNDO = _IK_LM_TEN.replace(
    """            if np.linalg.norm(e_new) < np.linalg.norm(e):
                q, e = q_new, e_new
                mu = max(mu / 10, 1e-10)
            else:
                mu = mu * 10
""",
    """            better = np.linalg.norm(e_new) < np.linalg.norm(e)
            q, e = q_new, e_new  # the step is kept either way
            mu = max(mu / 10, 1e-10) if better else mu * 10
""",
)

_POE = """
def ik_poe(M, S, T_target, q0, tol_omega=1e-10, tol_v=1e-10, max_iterations=50):
    q = np.array(q0, dtype=float)
    for _ in range(max_iterations):
        T = urkin.poe.fk_space(M, S, q)
        V = se3_log(T_target @ inv_transform(T))
        if np.linalg.norm(V[:3]) <= tol_omega and np.linalg.norm(V[3:]) <= tol_v:
            break
        q = q + np.linalg.pinv(urkin.poe.jacobian_space(S, q)) @ V
    return q
"""

# ---------------------------------------------------------------------------- 6.6 ik_poe_body

_BODY = """
def ik_poe_body(M, B, T_target, q0, tol_omega=1e-10, tol_v=1e-10, max_iterations=50):
    q = np.array(q0, dtype=float)
    for _ in range(max_iterations):
        T = urkin.poe.fk_body(M, B, q)
        V = se3_log(inv_transform(T) @ T_target)
        if np.linalg.norm(V[:3]) <= tol_omega and np.linalg.norm(V[3:]) <= tol_v:
            break
        q = q + np.linalg.pinv(urkin.poe.jacobian_body(B, q)) @ V
    return q
"""

_BODY_STEP = "q = q + np.linalg.pinv(urkin.poe.jacobian_body(B, q)) @ V"

# ----------------------------------------------------------------------- 6.5 damping_for_step

_DAMPING = """
def damping_for_step(e, max_step):
    e = np.asarray(e, dtype=float)
    if not (np.isfinite(max_step) and max_step > 0):
        raise ValueError(f"max_step must be a finite number > 0; got {{max_step}}")
    if not np.all(np.isfinite(e)):
        raise ValueError("e holds a NaN or an infinity")
    return {body}
"""


def _damping(body):
    return _DAMPING.format(body=body)


_DAMPING_MATH = """
import math


def damping_for_step(e, max_step):
    values = [float(x) for x in np.ravel(e)]
    if not (math.isfinite(max_step) and max_step > 0.0):
        raise ValueError("max_step: expected a finite bound > 0")
    if not all(math.isfinite(x) for x in values):
        raise ValueError("the error e must be finite")
    peak_gain_per_lambda = 0.5  # max over σ of σ/(σ² + λ²) is 1/(2λ)
    return peak_gain_per_lambda * math.sqrt(sum(x * x for x in values)) / max_step
"""

_DAMPING_SWEEP = """
def damping_for_step(e, max_step):
    # the step bound ‖e‖ g_max(λ), g_max(λ) = max over σ of σ/(σ² + λ²), solved for λ by
    # bisection on a log scale (it is decreasing in λ)
    e = np.asarray(e, dtype=float)
    if not np.isfinite(max_step) or max_step <= 0:
        raise ValueError("max_step must be positive and finite")
    if not np.isfinite(e).all():
        raise ValueError("non-finite e")
    size = np.sqrt(e @ e)
    if size == 0:
        return 0.0
    peak = lambda lam: lam / (lam * lam + lam * lam)  # at σ = λ (g' = 0 there)
    lo, hi = 1e-300, 1e300
    for _ in range(4000):
        mid = np.sqrt(lo * hi)
        if size * peak(mid) > max_step:
            lo = mid
        else:
            hi = mid
        if hi <= lo * (1 + 1e-15):
            break
    return hi
"""

_DAMPING_FLOAT32 = """
def damping_for_step(e, max_step):
    e = np.asarray(e, dtype=np.float32)
    if not (np.isfinite(max_step) and max_step > 0):
        raise ValueError("max_step must be > 0")
    if not np.all(np.isfinite(e)):
        raise ValueError("e must be finite")
    return np.linalg.norm(e) / np.float32(2 * max_step)
"""

_DAMPING_NO_CHECKS = """
def damping_for_step(e, max_step):
    return np.linalg.norm(e) / (2 * max_step)
"""

_DAMPING_LE_ZERO_ONLY = """
def damping_for_step(e, max_step):
    e = np.asarray(e, dtype=float)
    if max_step <= 0:
        raise ValueError("max_step must be > 0")
    if not np.all(np.isfinite(e)):
        raise ValueError("e must be finite")
    return np.linalg.norm(e) / (2 * max_step)
"""

_DAMPING_UNNAMED = """
def damping_for_step(e, max_step):
    e = np.asarray(e, dtype=float)
    if not (np.isfinite(max_step) and max_step > 0) or not np.all(np.isfinite(e)):
        raise ValueError("bad input")
    return np.linalg.norm(e) / (2 * max_step)
"""

_DAMPING_NO_E_CHECK = """
def damping_for_step(e, max_step):
    if not (np.isfinite(max_step) and max_step > 0):
        raise ValueError("max_step must be a finite number > 0")
    return float(np.linalg.norm(e)) / (2 * max_step)
"""

CORRECT = [
    # ------------------------------------------------------------------------------ 6.4
    Variant(
        "6.4",
        "Modern Robotics' IKinSpace: Ad(T) log(T⁻¹ T_target), (θ, success) returned",
        """
from urkin.transforms import adjoint


def ik_poe(M, S, T_target, q0, tol_omega=1e-10, tol_v=1e-10, max_iterations=50):
    theta = np.array(q0, dtype=float)
    for i in range(max_iterations + 1):
        T_sb = urkin.poe.fk_space(M, S, theta)
        V_s = adjoint(T_sb) @ se3_log(np.linalg.inv(T_sb) @ T_target)
        done = np.linalg.norm(V_s[:3]) <= tol_omega and np.linalg.norm(V_s[3:]) <= tol_v
        if done or i == max_iterations:
            return theta, done
        theta = theta + np.linalg.pinv(urkin.poe.jacobian_space(S, theta)) @ V_s
""",
    ),
    Variant("6.5", "math module, a named 1/2", _DAMPING_MATH),
    Variant("6.5", "bisection on the peak gain", _DAMPING_SWEEP),
    Variant("6.5", "float32", _DAMPING_FLOAT32),
    Variant("6.5", "0.5 * √(e·e) / max_step", _damping("0.5 * np.sqrt(e @ e) / max_step")),
    Variant("6.1", "Cholesky factor and two solves", _DLS_CHOLESKY),
    Variant("6.1", "the (JᵀJ + λ²I) form", _DLS_LM_FORM),
    Variant("6.1", "lstsq on [J; λI]", _DLS_AUGMENTED),
    Variant("6.1", "float32", _DLS_FLOAT32),
    Variant("6.1", "loops and a helper", _DLS_LOOPS),
    Variant(
        "6.1",
        "no asarray, J.shape[0]",
        "def dls_step(J, e, lam):\n"
        "    return J.T @ np.linalg.solve(J @ J.T + lam**2 * np.eye(J.shape[0]), e)\n",
    ),
    Variant(
        "6.2",
        "the Jᵀ(JJᵀ + μI) form",
        _lm("J.T @ np.linalg.solve(J @ J.T + mu * np.eye(J.shape[0]), e)"),
    ),
    Variant("6.2", "lstsq on [J; √μ I]", _LM_AUGMENTED),
    Variant("6.2", "Cholesky", _LM_CHOLESKY),
    Variant("6.2", "float32", _LM_FLOAT32),
    Variant(
        "6.2",
        "calls dls_step with λ = √μ",
        "def lm_step(J, e, mu):\n    return dls_step(J, e, np.sqrt(mu))\n",
    ),
    Variant("6.3", "×10 / ÷10, wrapped angles, norm test, 10 restarts", _IK_LM_TEN),
    Variant("6.3", "Nielsen's rule, unseeded restarts", _IK_LM_NIELSEN),
    Variant("6.3", "Marquardt's thresholds, own log map, restarts near q0 first", _IK_LM_MARQUARDT),
    Variant("6.3", "rejection undoes the step (q − step)", _IK_LM_UNDO),
    Variant("6.3", "float32 answer", _IK_LM_FLOAT32),
    Variant("6.3", "lm_step called again for an accepted step", _IK_LM_TWICE),
    Variant(
        "6.3", "μ capped at 1e6, restarts after 200 iterations", _ik_lm(up="min(2.0 * mu, 1e6)")
    ),
    Variant("6.3", "ties accepted (<=), max-abs error, ×4 and ÷2, floor 1e-7", _IK_LM_TIES),
    Variant("6.3", "restarts after 20 iterations without progress, norm limit", _IK_LM_PATIENCE),
    # ------------------------------------------------------------------------------ 6.6
    Variant(
        "6.6",
        "Modern Robotics' IKinBody: np.linalg.inv, (θ, success) returned",
        """
def ik_poe_body(M, B, T_target, q0, tol_omega=1e-10, tol_v=1e-10, max_iterations=50):
    theta = np.array(q0, dtype=float)
    for i in range(max_iterations + 1):
        V_b = se3_log(np.linalg.inv(urkin.poe.fk_body(M, B, theta)) @ T_target)
        done = np.linalg.norm(V_b[:3]) <= tol_omega and np.linalg.norm(V_b[3:]) <= tol_v
        if done or i == max_iterations:
            return theta, done
        theta = theta + np.linalg.pinv(urkin.poe.jacobian_body(B, theta)) @ V_b
""",
    ),
    Variant(
        "6.6",
        "body twist and Jacobian from the space ones through Ad(T⁻¹)",
        """
from urkin.transforms import adjoint


def ik_poe_body(M, B, T_target, q0, tol_omega=1e-10, tol_v=1e-10, max_iterations=50):
    M, B = np.asarray(M, dtype=float), np.asarray(B, dtype=float)
    S = adjoint(M) @ B
    q = np.array(q0, dtype=float)
    for _ in range(max_iterations):
        T = urkin.poe.fk_space(M, S, q)
        to_body = adjoint(inv_transform(T))
        V = to_body @ se3_log(T_target @ inv_transform(T))
        if np.linalg.norm(V[:3]) <= tol_omega and np.linalg.norm(V[3:]) <= tol_v:
            break
        q = q + np.linalg.pinv(to_body @ urkin.poe.jacobian_space(S, q)) @ V
    return q
""",
    ),
    Variant(
        "6.6",
        "own body Jacobian and product of exponentials, a while loop",
        """
from urkin.transforms import adjoint, se3_exp


def ik_poe_body(M, B, T_target, q0, tol_omega=1e-10, tol_v=1e-10, max_iterations=50):
    B = np.asarray(B, dtype=float)
    n = B.shape[1]
    q = np.array(q0, dtype=float)

    def pose(q):
        T = np.array(M, dtype=float)
        for i in range(n):
            T = T @ se3_exp(B[:, i] * q[i])
        return T

    def body_jacobian(q):
        J = np.zeros((6, n))
        T = np.eye(4)
        for i in reversed(range(n)):
            J[:, i] = adjoint(T) @ B[:, i]
            T = T @ se3_exp(-B[:, i] * q[i])
        return J

    V = se3_log(inv_transform(pose(q)) @ T_target)
    k = 0
    while k < max_iterations and (
        np.linalg.norm(V[:3]) > tol_omega or np.linalg.norm(V[3:]) > tol_v
    ):
        q = q + np.linalg.pinv(body_jacobian(q)) @ V
        V = se3_log(inv_transform(pose(q)) @ T_target)
        k += 1
    return q
""",
    ),
]

WRONG = [
    # ------------------------------------------------------------------------------ 6.6
    Variant(
        "6.6",
        "space twist with the body Jacobian",
        _BODY.replace(
            "se3_log(inv_transform(T) @ T_target)", "se3_log(T_target @ inv_transform(T))"
        ),
        points=0,
        mistake="space twist log(T_target T⁻¹) with the body Jacobian",
    ),
    Variant(
        "6.6",
        "body twist with the space Jacobian",
        _BODY.replace(
            "urkin.poe.jacobian_body(B, q)",
            "urkin.poe.jacobian_space(urkin.transforms.adjoint(M) @ B, q)",
        ),
        points=0,
        mistake="body twist with the space Jacobian",
    ),
    Variant(
        "6.6",
        "the inverse motion's twist",
        _BODY.replace(
            "se3_log(inv_transform(T) @ T_target)", "se3_log(inv_transform(T_target) @ T)"
        ),
        points=0,
        mistake="inverse motion",
    ),
    Variant(
        "6.6",
        "(v, ω) order",
        _BODY.replace(
            "        if np.linalg.norm(V[:3])",
            "        V = np.r_[V[3:], V[:3]]\n        if np.linalg.norm(V[:3])",
        ),
        points=0,
        mistake="(v, ω)",
    ),
    Variant(
        "6.6",
        "fk_space with the body screws",
        _BODY.replace("urkin.poe.fk_body(M, B, q)", "urkin.poe.fk_space(M, B, q)"),
        points=0,
        mistake="fk_space with body screws",
    ),
    Variant(
        "6.6",
        "the Jacobian computed once, at q0",
        _BODY.replace(
            "    q = np.array(q0, dtype=float)\n",
            "    q = np.array(q0, dtype=float)\n"
            "    J_plus = np.linalg.pinv(urkin.poe.jacobian_body(B, q))\n",
        ).replace(_BODY_STEP, "q = q + J_plus @ V"),
        points=None,
        mistake="Jacobian not recomputed",
    ),
    Variant(
        "6.6",
        "angles wrapped after each step",
        _BODY.replace(_BODY_STEP, _BODY_STEP + "\n        q = (q + np.pi) % (2 * np.pi) - np.pi"),
        points=2,
        mistake="wrapped",
    ),
    Variant(
        "6.6",
        "exercise 6.4's ik_poe with S = Ad(M) B",
        """
def ik_poe_body(M, B, T_target, q0, tol_omega=1e-10, tol_v=1e-10, max_iterations=50):
    S = urkin.transforms.adjoint(M) @ B
    return ik_poe(M, S, T_target, q0, tol_omega, tol_v, max_iterations)
""",
        points=2,
        mistake="the space pairing",
    ),
    Variant(
        "6.6",
        "urkin.ik",
        """
def ik_poe_body(M, B, T_target, q0, tol_omega=1e-10, tol_v=1e-10, max_iterations=50):
    return urkin.ik(urkin.robot("UR5"), T_target, q0=q0, method="poe").q
""",
        points=0,
    ),
    # ------------------------------------------------------------------------------ 6.4
    Variant(
        "6.4",
        "body twist with the space Jacobian",
        _POE.replace(
            "se3_log(T_target @ inv_transform(T))", "se3_log(inv_transform(T) @ T_target)"
        ),
        points=None,
        mistake="body twist",
    ),
    Variant(
        "6.4",
        "the inverse motion's twist",
        _POE.replace(
            "se3_log(T_target @ inv_transform(T))", "se3_log(T @ inv_transform(T_target))"
        ),
        points=None,
        mistake="inverse motion",
    ),
    Variant(
        "6.4",
        "(v, ω) order",
        _POE.replace(
            "        if np.linalg.norm(V[:3])",
            "        V = np.r_[V[3:], V[:3]]\n        if np.linalg.norm(V[:3])",
        ),
        points=None,
        mistake="(v, ω)",
    ),
    Variant(
        "6.4",
        "urkin.ik",
        """
def ik_poe(M, S, T_target, q0, tol_omega=1e-10, tol_v=1e-10, max_iterations=50):
    return urkin.ik(urkin.robot("UR5"), T_target, q0=q0, method="poe").q
""",
        points=0,
    ),
    Variant(
        "6.5", "the 1/2 forgotten", _damping("np.linalg.norm(e) / max_step"), 0, "forgot the 1/2"
    ),
    Variant(
        "6.5",
        "λ² returned",
        _damping("(np.linalg.norm(e) / (2 * max_step)) ** 2"),
        0,
        "returned λ²",
    ),
    Variant(
        "6.5",
        "a square root",
        _damping("np.sqrt(np.linalg.norm(e) / max_step)"),
        0,
        "a square root",
    ),
    Variant(
        "6.5",
        "the largest |e_i|",
        _damping("np.abs(e).max() / (2 * max_step)"),
        0,
        "the largest |e_i|",
    ),
    Variant("6.5", "‖e‖²", _damping("(e @ e) / (2 * max_step)"), 0, "‖e‖² in place of ‖e‖"),
    Variant("6.5", "no input checks", _DAMPING_NO_CHECKS, 2, "max_step not checked"),
    Variant("6.5", "max_step ≤ 0 only (NaN passes)", _DAMPING_LE_ZERO_ONLY, 2, "max_step not"),
    Variant("6.5", "ValueError without a name", _DAMPING_UNNAMED, 2, "does not name max_step"),
    Variant("6.5", "e not checked", _DAMPING_NO_E_CHECK, 2, "e not checked"),
    Variant("6.1", "seed 000's line, I undefined", _SEED000_UNDEFINED_I, 0, "seed 000"),
    Variant("6.1", "seed 000's line, I = eye", _SEED000_EYE, 0, "seed 000"),
    Variant(
        "6.1", "λ for λ²", _dls("J.T @ np.linalg.solve(J @ J.T + lam * np.eye(len(e)), e)"), 0, "λ²"
    ),
    Variant(
        "6.1",
        "np.linalg.inv",
        _dls("J.T @ np.linalg.inv(J @ J.T + lam**2 * np.eye(len(e))) @ e"),
        3,
        "inverse",
    ),
    Variant(
        "6.1",
        "np.linalg.inv named by a string built at run time",
        _dls("J.T @ getattr(np.linalg, 'in' + 'v')(J @ J.T + lam**2 * np.eye(len(e))) @ e"),
        3,
        "inverse",
    ),
    Variant(
        "6.1",
        "pinv of the damped matrix",
        _dls("J.T @ np.linalg.pinv(J @ J.T + lam**2 * np.eye(len(e))) @ e"),
        3,
        "inverse",
    ),
    Variant(
        "6.1",
        "np.eye(6)",
        _dls("J.T @ np.linalg.solve(J @ J.T + lam**2 * np.eye(6), e)"),
        1,
        "identity of the wrong size",
    ),
    Variant("6.1", "undamped pseudo-inverse", _dls("np.linalg.pinv(J) @ e"), 0, "no damping"),
    Variant("6.1", "the lesson's SVD helper", _DLS_SVD_HELPER, 3, "SVD"),
    Variant(
        "6.1",
        "the matrix, not the step",
        _dls("J.T @ np.linalg.solve(J @ J.T + lam**2 * np.eye(len(e)), np.eye(len(e)))"),
        0,
        "instead of the step",
    ),
    Variant(
        "6.1",
        "J where Jᵀ belongs",
        _dls("J @ np.linalg.solve(J @ J.T + lam**2 * np.eye(len(e)), e)"),
        0,
        "J where Jᵀ",
    ),
    Variant(
        "6.2",
        "seed 001's minus",
        "def lm_step(J, e, mu):\n    return np.linalg.inv(J.T @ J + mu * np.eye(6)) - J.T @ e\n",
        0,
        "seed 001",
    ),
    Variant(
        "6.2", "μ²", _lm("np.linalg.solve(J.T @ J + mu**2 * np.eye(J.shape[1]), J.T @ e)"), 0, "μ²"
    ),
    Variant(
        "6.2", "μ on every entry", _lm("np.linalg.solve(J.T @ J + mu, J.T @ e)"), 0, "every entry"
    ),
    Variant(
        "6.2",
        "Jᵀ missing on the right",
        _lm("np.linalg.solve(J.T @ J + mu * np.eye(J.shape[1]), e)"),
        0,
        "Jᵀ on the right is missing",
    ),
    Variant(
        "6.2",
        "np.linalg.inv",
        _lm("np.linalg.inv(J.T @ J + mu * np.eye(J.shape[1])) @ J.T @ e"),
        3,
        "inverse",
    ),
    Variant(
        "6.2",
        "np.eye(J.shape[0])",
        _lm("np.linalg.solve(J.T @ J + mu * np.eye(J.shape[0]), J.T @ e)"),
        1,
        "identity of the wrong size",
    ),
    Variant("6.3", "fixed damping (DLS), restarts", _FIXED_DLS.format(mu="1e-3"), None, "fixed μ"),
    Variant(
        "6.3",
        "fixed damping, no restarts",
        _FIXED_DLS.format(mu="1e-4").replace("range(21)", "range(1)"),
        None,
        "fixed μ",
    ),
    Variant("6.3", "no restarts", _ik_lm(attempts="1"), None, "no restarts"),
    Variant(
        "6.3",
        "restarts from q0 again",
        _ik_lm(restart="np.asarray(q0, dtype=float).copy()"),
        None,
        "restarts from the same",
    ),
    Variant("6.3", "μ only grows", _ik_lm(down="mu"), None, "μ"),
    Variant(
        "6.3",
        "μ ÷ and × swapped",
        _ik_lm(down="2.0 * mu", up="max(mu / 3.0, 1e-12)"),
        0,
        "μ is not",
    ),
    Variant(
        "6.3",
        "μ unchanged on rejection",
        _ik_lm(up="mu + 0.0 if mu < 1e7 else 2e8"),
        None,
        "not increased",
    ),
    Variant("6.3", "every step accepted", _IK_LM_ACCEPT_ALL, None, "accepted"),
    Variant("6.3", "×10 / ÷10, a worse step kept", _IK_LM_NO_UNDO, None, "accepted"),
    Variant("6.3", "stops at 1e-6", _ik_lm(tol="1e-6"), None, "stops too early"),
    Variant(
        "6.3",
        "seed 001's loop condition",
        _ik_lm().replace(
            "            if np.abs(error).max() < 1e-12:\n                return q\n",
            "            if np.linalg.norm(error) > 1e-6:  # seed 001: while ‖V‖ < ε\n"
            "                return q\n",
        ),
        0,
        "unchanged",
    ),
    Variant(
        "6.3",
        "inline damping, lm_step unused",
        _ik_lm(
            step="(lambda J: np.linalg.solve(J.T @ J + mu * np.eye(6), J.T @ error))"
            "(urkin.jacobian(robot, q))"
        ),
        5,
        "does not use lm_step",
    ),
    Variant(
        "6.3",
        "q0 as a list breaks .copy() arithmetic",
        _ik_lm().replace("q = np.asarray(q0, dtype=float).copy()", "q = q0.copy() + 0.0"),
        4,
        "list",
    ),
]
