"""Independent references for the tests: nothing here imports urkin.

* ``OFFICIAL_DH``: Universal Robots' published standard-DH tables, typed from
  https://www.universal-robots.com/articles/ur/application-installation/dh-parameters-for-calculations-of-kinematics-and-dynamics/
* ``dh_fk``: a plain product of standard-DH matrices, written out entry by entry; it also
  accepts complex joint angles, for complex-step differentiation.
* ``complex_step_jacobian``: the geometric Jacobian ``[v; ω]`` from ``dh_fk`` by complex-step
  differentiation (exact to rounding, no step-size trade-off).
* ``finite_difference_jacobian``: the same by central differences.
"""

from __future__ import annotations

import numpy as np

ALPHA = (np.pi / 2, 0.0, 0.0, np.pi / 2, -np.pi / 2, 0.0)

#: name -> (d1, a2, a3, d4, d5, d6) in metres, from UR's DH page
OFFICIAL_DH = {
    "UR3": (0.1519, -0.24365, -0.21325, 0.11235, 0.08535, 0.0819),
    "UR5": (0.089159, -0.425, -0.39225, 0.10915, 0.09465, 0.0823),
    "UR10": (0.1273, -0.612, -0.5723, 0.163941, 0.1157, 0.0922),
    "UR3e": (0.15185, -0.24355, -0.2132, 0.13105, 0.08535, 0.0921),
    "UR5e": (0.1625, -0.425, -0.3922, 0.1333, 0.0997, 0.0996),
    "UR10e": (0.1807, -0.6127, -0.57155, 0.17415, 0.11985, 0.11655),
    "UR16e": (0.1807, -0.4784, -0.36, 0.17415, 0.11985, 0.11655),
}


def dh_table(lengths):
    d1, a2, a3, d4, d5, d6 = lengths
    d = (d1, 0.0, 0.0, d4, d5, d6)
    a = (0.0, a2, a3, 0.0, 0.0, 0.0)
    return list(zip(d, a, ALPHA))


def dh_matrix(theta, d, a, alpha):
    ct, st = np.cos(theta), np.sin(theta)
    ca, sa = np.cos(alpha), np.sin(alpha)
    return np.array(
        [
            [ct, -st * ca, st * sa, a * ct],
            [st, ct * ca, -ct * sa, a * st],
            [0.0, sa, ca, d],
            [0.0, 0.0, 0.0, 1.0],
        ],
        dtype=np.result_type(theta, float),
    )


def dh_fk(lengths, q):
    """T_0_6 as the product of the six DH matrices; q real or complex, shape (6,)."""
    T = np.eye(4, dtype=np.result_type(q, float))
    for theta, (d, a, alpha) in zip(q, dh_table(lengths)):
        T = T @ dh_matrix(theta, d, a, alpha)
    return T


def _vee(W):
    return 0.5 * np.array([W[2, 1] - W[1, 2], W[0, 2] - W[2, 0], W[1, 0] - W[0, 1]])


def complex_step_jacobian(lengths, q, h=1e-30):
    q = np.asarray(q, dtype=float)
    R = dh_fk(lengths, q)[:3, :3]
    J = np.zeros((6, 6))
    for k in range(6):
        dq = q.astype(complex)
        dq[k] += 1j * h
        dT = dh_fk(lengths, dq).imag / h
        J[:3, k] = dT[:3, 3]
        J[3:, k] = _vee(dT[:3, :3] @ R.T)
    return J


def finite_difference_jacobian(lengths, q, h=1e-6):
    q = np.asarray(q, dtype=float)
    R = dh_fk(lengths, q)[:3, :3]
    J = np.zeros((6, 6))
    for k in range(6):
        e = np.zeros(6)
        e[k] = h
        dT = (dh_fk(lengths, q + e) - dh_fk(lengths, q - e)) / (2 * h)
        J[:3, k] = dT[:3, 3]
        J[3:, k] = _vee(dT[:3, :3] @ R.T)
    return J
