"""Textbook implementations of the exercises, written without urkin, and known-wrong variants.

The tests check that the exercise checks give these full marks, and that each wrong variant
loses points with the mistake it embodies named in the feedback.
"""

import numpy as np


def deg_to_rad(angles_deg):
    return np.asarray(angles_deg, dtype=float) * (np.pi / 180.0)


def base_link_pose(T_base_tool):
    Rz_pi = np.diag([-1.0, -1.0, 1.0, 1.0])
    return Rz_pi @ T_base_tool


def rot_z(theta):
    c, s = np.cos(theta), np.sin(theta)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def transform_inverse(T):
    R, p = T[:3, :3], T[:3, 3]
    out = np.eye(4)
    out[:3, :3] = R.T
    out[:3, 3] = -R.T @ p
    return out


def rotation_to_rpy(R):
    pitch = np.arctan2(-R[2, 0], np.hypot(R[0, 0], R[1, 0]))
    if np.hypot(R[0, 0], R[1, 0]) < 1e-9:
        return np.array([np.arctan2(-R[1, 2], R[1, 1]), pitch, 0.0])
    return np.array([np.arctan2(R[2, 1], R[2, 2]), pitch, np.arctan2(R[1, 0], R[0, 0])])


def axis_angle_to_rotation(axis, angle):
    k = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


def dh_transform(theta, d, a, alpha):
    ct, st, ca, sa = np.cos(theta), np.sin(theta), np.cos(alpha), np.sin(alpha)
    return np.array(
        [
            [ct, -st * ca, st * sa, a * ct],
            [st, ct * ca, -ct * sa, a * st],
            [0, sa, ca, d],
            [0, 0, 0, 1],
        ]
    )


def forward_kinematics(robot, q):
    T = np.eye(4)
    for theta, d, a, alpha in zip(q, robot.d, robot.a, robot.alpha):
        T = T @ dh_transform(theta, d, a, alpha)
    return T


def ur5_position(q):
    d1, a2, a3, d4, d5, d6 = 0.089159, -0.425, -0.39225, 0.10915, 0.09465, 0.0823
    q1, q2, q3, q4, q5, _ = q
    c1, s1, c5, s5 = np.cos(q1), np.sin(q1), np.cos(q5), np.sin(q5)
    c234, s234 = np.cos(q2 + q3 + q4), np.sin(q2 + q3 + q4)
    reach = a2 * np.cos(q2) + a3 * np.cos(q2 + q3)
    return np.array(
        [
            d4 * s1 + d5 * c1 * s234 + d6 * (s1 * c5 - c1 * c234 * s5) + c1 * reach,
            -d4 * c1 + d5 * s1 * s234 - d6 * (c1 * c5 + s1 * c234 * s5) + s1 * reach,
            d1 + a2 * np.sin(q2) + a3 * np.sin(q2 + q3) - d5 * c234 - d6 * s234 * s5,
        ]
    )


def _skew(w):
    return np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


def screw_axis(w, q):
    w, q = np.asarray(w, float), np.asarray(q, float)
    return np.concatenate([w, -np.cross(w, q)])


def twist_exp(S, theta):
    w, v = np.asarray(S[:3], float), np.asarray(S[3:], float)
    W = _skew(w)
    T = np.eye(4)
    T[:3, :3] = np.eye(3) + np.sin(theta) * W + (1 - np.cos(theta)) * W @ W
    T[:3, 3] = (np.eye(3) * theta + (1 - np.cos(theta)) * W + (theta - np.sin(theta)) * W @ W) @ v
    return T


def fk_space(M, S, q):
    T = np.eye(4)
    for i in range(len(q)):
        T = T @ twist_exp(S[:, i], q[i])
    return T @ M


def fk_body(M, B, q):
    T = np.array(M, dtype=float)
    for i in range(len(q)):
        T = T @ twist_exp(B[:, i], q[i])
    return T


def _frames(robot, q):
    frames = [np.eye(4)]
    for theta, d, a, alpha in zip(q, robot.d, robot.a, robot.alpha):
        frames.append(frames[-1] @ dh_transform(theta, d, a, alpha))
    return frames


def geometric_jacobian(robot, q):
    frames = _frames(robot, q)
    p = frames[-1][:3, 3]
    J = np.zeros((6, 6))
    for i in range(6):
        z, o = frames[i][:3, 2], frames[i][:3, 3]
        J[:3, i] = np.cross(z, p - o)
        J[3:, i] = z
    return J


def numeric_jacobian(f, q, h=1e-6):
    q = np.asarray(q, dtype=float)
    columns = []
    for j in range(q.size):
        step = np.zeros_like(q)
        step[j] = h
        columns.append((np.asarray(f(q + step)) - np.asarray(f(q - step))) / (2 * h))
    return np.column_stack(columns)


def singularities(robot, q, tol=1e-9):
    q2, q3, q4, q5 = q[1], q[2], q[3], q[4]
    shoulder = robot.a2 * np.cos(q2) + robot.a3 * np.cos(q2 + q3) + robot.d5 * np.sin(q2 + q3 + q4)
    found = set()
    if abs(shoulder) < tol:
        found.add("shoulder")
    if abs(np.sin(q3)) < tol:
        found.add("elbow")
    if abs(np.sin(q5)) < tol:
        found.add("wrist")
    return found


def _rotation_vector(R):
    """log of a rotation matrix, written out (accurate near 0 and π)."""
    s = 0.5 * np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    theta = np.arctan2(np.linalg.norm(s), 0.5 * (np.trace(R) - 1.0))
    if theta < 1e-9:
        return s
    if np.pi - theta > 1e-3:
        return theta / np.sin(theta) * s
    B = 0.5 * (R + R.T) - np.cos(theta) * np.eye(3)
    k = B[:, np.argmax(np.diag(B))]
    k = k / np.linalg.norm(k)
    return theta * (k if k @ s >= 0 else -k)


def pose_error(T, T_target):
    e_p = T_target[:3, 3] - T[:3, 3]
    return np.concatenate([e_p, _rotation_vector(T_target[:3, :3] @ T[:3, :3].T)])


def _fk_reference(robot, q):
    return _frames(robot, q)[-1]


def _jacobian_reference(robot, q):
    return geometric_jacobian(robot, q)


def ik_newton(robot, T_target, q0, tol=1e-12, max_iterations=100):
    q = np.array(q0, dtype=float)
    for _ in range(max_iterations):
        e = pose_error(_fk_reference(robot, q), T_target)
        if np.linalg.norm(e) < tol:
            break
        step = np.linalg.pinv(_jacobian_reference(robot, q)) @ e
        q = q + step / max(1.0, np.abs(step).max())
    return q


def ik_position(robot, p_target, q0, tol=1e-12, max_iterations=100):
    q = np.array(q0, dtype=float)
    for _ in range(max_iterations):
        e = np.asarray(p_target) - _fk_reference(robot, q)[:3, 3]
        if np.linalg.norm(e) < tol:
            break
        step = np.linalg.pinv(_jacobian_reference(robot, q)[:3]) @ e
        q = q + step / max(1.0, np.abs(step).max())
    return q


def dls_step(J, e, lam):
    return J.T @ np.linalg.solve(J @ J.T + lam**2 * np.eye(J.shape[0]), e)


def lm_step(J, e, mu):
    return np.linalg.solve(J.T @ J + mu * np.eye(J.shape[1]), J.T @ e)


def ik_lm(robot, T_target, q0, tol=1e-12, max_iterations=200, restarts=10):
    rng = np.random.default_rng(0)
    q = np.array(q0, dtype=float)
    for _ in range(restarts + 1):
        mu = 1e-2
        e = pose_error(_fk_reference(robot, q), T_target)
        for _ in range(max_iterations):
            if np.linalg.norm(e) < tol or mu > 1e8:
                break
            step = lm_step(_jacobian_reference(robot, q), e, mu)
            trial = q + step / max(1.0, np.abs(step).max())
            e_trial = pose_error(_fk_reference(robot, trial), T_target)
            if e_trial @ e_trial < e @ e:
                q, e, mu = trial, e_trial, max(mu / 10, 1e-12)
            else:
                mu *= 10
        if np.linalg.norm(e) < tol:
            return q
        q = rng.uniform(-np.pi, np.pi, 6)  # a local minimum: start again elsewhere
    return q


LAB = (0.152, 0.120, 0.244, 0.093, 0.213, 0.083, 0.083, 0.082, 0.0535, 0.059)


def lab_theta1(x_c, y_c):
    offset = LAB[1] - LAB[3] + LAB[5]
    return np.arctan2(y_c, x_c) - np.arcsin(offset / np.hypot(x_c, y_c))


def planar_2r(x, y, l1, l2):
    b = np.arccos(np.clip((x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2), -1, 1))
    return np.array([np.arctan2(y, x) - np.arctan2(l2 * np.sin(b), l1 + l2 * np.cos(b)), b])


def ik_lab(x_w, y_w, z_w, yaw_w, arctan=False, unsigned=False, arctan_hr=False):
    L1, L2, L3, L4, L5, L6, L7, L8, L9, L10 = LAB
    x, y, z = x_w + 0.15, y_w - 0.15, z_w - 0.01  # world → base frame
    xc, yc = x - L9 * np.cos(yaw_w), y - L9 * np.sin(yaw_w)
    offset = L2 - L4 + L6
    heading = np.arctan(yc / xc) if arctan else np.arctan2(yc, xc)
    t1 = heading - np.arcsin(offset / np.hypot(xc, yc))
    x3 = xc - L7 * np.cos(t1) + offset * np.sin(t1)
    y3 = yc - L7 * np.sin(t1) - offset * np.cos(t1)
    r = np.hypot(x3, y3) if unsigned else x3 * np.cos(t1) + y3 * np.sin(t1)
    h = z + L8 + L10 - L1
    t3 = np.arccos((r * r + h * h - L3 * L3 - L5 * L5) / (2 * L3 * L5))
    direction = np.arctan(h / r) if arctan_hr else np.arctan2(h, r)
    t2 = -(direction + np.arctan2(L5 * np.sin(t3), L3 + L5 * np.cos(t3)))
    lab = np.array([t1, t2, t3, -t2 - t3, -np.pi / 2, np.pi / 2 + t1 - yaw_w])
    return lab + np.array([np.pi, 0.0, 0.0, -np.pi / 2, 0.0, 0.0])


SOLUTIONS = {
    "0.1": deg_to_rad,
    "0.2": base_link_pose,
    "1.1": rot_z,
    "1.2": transform_inverse,
    "1.3": rotation_to_rpy,
    "1.4": axis_angle_to_rotation,
    "2.1": dh_transform,
    "2.2": forward_kinematics,
    "2.3": ur5_position,
    "3.1": screw_axis,
    "3.2": twist_exp,
    "3.3": fk_space,
    "3.4": fk_body,
    "4.1": geometric_jacobian,
    "4.2": numeric_jacobian,
    "4.3": singularities,
    "5.1": pose_error,
    "5.2": ik_newton,
    "5.3": ik_position,
    "6.1": dls_step,
    "6.2": lm_step,
    "6.3": ik_lm,
    "7.1": lab_theta1,
    "7.2": planar_2r,
    "7.3": ik_lab,
}


# ------------------------------------------------------------------ known-wrong variants


def _modified_dh(theta, d, a, alpha):
    ct, st, ca, sa = np.cos(theta), np.sin(theta), np.cos(alpha), np.sin(alpha)
    return np.array(
        [
            [ct, -st, 0, a],
            [st * ca, ct * ca, -sa, -sa * d],
            [st * sa, ct * sa, ca, ca * d],
            [0, 0, 0, 1],
        ]
    )


def _fk_with(link, robot, q, flip_a=False, reverse=False):
    a = robot.a * (-1 if flip_a else 1)
    links = [link(t, d, aa, al) for t, d, aa, al in zip(q, robot.d, a, robot.alpha)]
    T = np.eye(4)
    for L in links[::-1] if reverse else links:
        T = T @ L
    return T


def _seed002_position(q):
    d1, a2, a3, d4, d5, d6 = 0.089159, -0.425, -0.39225, 0.10915, 0.09465, 0.0823
    q1, q2, q3, q4, q5, _ = q
    c1, s1, c5 = np.cos(q1), np.sin(q1), np.cos(q5)
    c234, s234 = np.cos(q2 + q3 + q4), np.sin(q2 + q3 + q4)
    reach = a2 * np.cos(q2) + a3 * np.cos(q2 + q3)
    return np.array(
        [
            d5 * c1 * s234 + d4 * s1 - d6 * c1 * c234 + d6 * c5 * s1 + c1 * reach,
            d5 * s1 * s234 - d4 * c1 - d6 * s1 * c234 - d6 * c1 * c5 + s1 * reach,
            d1 - d6 * s234 * np.sin(q5) + a2 * np.sin(q2) + a3 * np.sin(q2 + q3) - d5 * c234,
        ]
    )


#: exercise id -> list of (wrong function, words the named mistake must contain)
WRONG = {
    "0.1": [
        (lambda x: np.asarray(x, float) * 0.0175, "0.0175"),
        (lambda x: np.degrees(x), "wrong way"),
        (lambda x: np.asarray(x, float), "unchanged"),
    ],
    "0.2": [(lambda T: T @ np.diag([-1.0, -1.0, 1.0, 1.0]), "wrong side")],
    "1.1": [
        (lambda t: rot_z(t).T, "transposed"),
        (lambda t: rot_z(np.radians(t)), "degrees"),
    ],
    "1.2": [
        (
            lambda T: np.block([[T[:3, :3].T, -T[:3, 3:]], [np.zeros((1, 3)), np.ones((1, 1))]]),
            "not rotated",
        ),
    ],
    "1.3": [
        (lambda R: np.degrees(rotation_to_rpy(R)), "degrees"),
        (lambda R: rotation_to_rpy(R)[::-1], "reversed"),
    ],
    "1.4": [
        (lambda k, t: axis_angle_to_rotation(k, t).T, "transposed"),
    ],
    "2.1": [
        (_modified_dh, "modified"),
        (lambda t, d, a, al: dh_transform(np.radians(t), d, a, np.radians(al)), "degrees"),
        (lambda *args: _transposed(dh_transform(*args)), "transposed"),
    ],
    "2.2": [
        (lambda robot, q: _fk_with(dh_transform, robot, q, flip_a=True), "wrong sign"),
        (lambda robot, q: _fk_with(_modified_dh, robot, q), "modified"),
        (lambda robot, q: _fk_with(dh_transform, robot, np.radians(q)), "degrees"),
        (lambda robot, q: _fk_with(dh_transform, robot, q, reverse=True), "reverse order"),
    ],
    "2.3": [(_seed002_position, "seed 002")],
    "3.1": [
        (lambda w, q: np.concatenate([w, np.cross(w, q)]), "wrong sign"),
        (lambda w, q: np.roll(screw_axis(w, q), 3), "(v, ω) order"),
    ],
    "3.2": [
        (lambda S, t: _with_translation(twist_exp(S, t), np.asarray(S[3:]) * t), "not v·θ"),
        (lambda S, t: _transposed(twist_exp(S, t)), "transposed"),
    ],
    "3.3": [
        (lambda M, S, q: M @ fk_space(np.eye(4), S, q), "M multiplied first"),
        (lambda M, S, q: fk_space(np.eye(4), S[:, ::-1], q[::-1]) @ M, "reverse order"),
    ],
    "3.4": [(lambda M, B, q: fk_body(np.eye(4), B, q) @ M, "M multiplied last")],
    "4.1": [
        (lambda r, q: np.roll(geometric_jacobian(r, q), 3, axis=0), "twist order"),
        (lambda r, q: _jacobian_from_frame(r, q, 1), "frame i − 1"),
        (lambda r, q: _jacobian_from_frame(r, q, 0, flip=True), "wrong way"),
    ],
    "4.2": [
        (lambda f, q, h=1e-6: _forward_difference(f, q, h), "forward differences"),
        (lambda f, q, h=1e-6: 2 * numeric_jacobian(f, q, h), "divided by h"),
    ],
    "4.3": [
        (lambda r, q: _elbow_with_cos(r, q), "cos q3"),
        (lambda r, q: _wrist_only_at_zero(r, q), "±π too"),
    ],
    "5.1": [
        (
            lambda T, Tt: np.concatenate([Tt[:3, 3] - T[:3, 3], _cross_error(T, Tt)]),
            "cross-product",
        ),
        (lambda T, Tt: -pose_error(T, Tt), "wrong way"),
        (lambda T, Tt: np.roll(pose_error(T, Tt), 3), "order"),
    ],
    "6.1": [
        (lambda J, e, lam: (J.T * (J * J.T + lam**2 * I) ** -1) @ e, "seed 000"),  # noqa: F821
        (lambda J, e, lam: (J.T * (J * J.T + lam**2 * np.eye(len(e))) ** -1) @ e, "seed 000"),
        (lambda J, e, lam: J.T @ np.linalg.solve(J @ J.T + lam * np.eye(len(e)), e), "λ²"),
    ],
    "7.1": [
        (
            lambda x, y: ik_lab.__globals__["np"].arctan(y / x) - np.arcsin(0.110 / np.hypot(x, y)),
            "arctan",
        )
    ],
    "7.3": [
        (lambda x, y, z, yaw: ik_lab(x, y, z, yaw, arctan=True), "arctan"),
        (lambda x, y, z, yaw: ik_lab(x, y, z, yaw, unsigned=True), "√(x² + y²)"),
        (lambda x, y, z, yaw: ik_lab(x, y, z, yaw, arctan_hr=True), "arctan(h/r)"),
    ],
    "6.2": [
        (lambda J, e, mu: np.linalg.inv(J.T @ J + mu * np.eye(6)) - J.T @ e, "seed 001"),
        (lambda J, e, mu: np.linalg.solve(J.T @ J + mu**2 * np.eye(6), J.T @ e), "μ²"),
    ],
}


def _cross_error(T, Tt):
    return 0.5 * sum(np.cross(T[:3, i], Tt[:3, i]) for i in range(3))


def _with_translation(T, p):
    T = T.copy()
    T[:3, 3] = p
    return T


def _jacobian_from_frame(robot, q, shift, flip=False):
    frames = _frames(robot, q)
    p = frames[-1][:3, 3]
    J = np.zeros((6, 6))
    for i in range(6):
        z, o = frames[i + shift][:3, 2], frames[i + shift][:3, 3]
        J[:3, i] = np.cross(z, o - p) if flip else np.cross(z, p - o)
        J[3:, i] = z
    return J


def _forward_difference(f, q, h):
    q = np.asarray(q, dtype=float)
    f0 = np.asarray(f(q))
    return np.column_stack([(np.asarray(f(q + h * e)) - f0) / h for e in np.eye(q.size)])


def _wrist_only_at_zero(robot, q):
    found = singularities(robot, q) - {"wrist"}
    if abs(q[4]) < 1e-9:
        found.add("wrist")
    return found


def _elbow_with_cos(robot, q):
    found = singularities(robot, q) - {"elbow"}
    if abs(np.cos(q[2])) < 1e-9:
        found.add("elbow")
    return found


def _transposed(T):
    out = T.copy()
    out[:3, :3] = T[:3, :3].T
    return out
