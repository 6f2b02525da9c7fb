"""Configurations on and near the UR arms' singular families, for the IK tests.

The families are the zeros of the three factors of ``det J``
(:func:`urkin.kinematics.singularity_factors`): the shoulder (the wrist point in the plane of
the base axis parallel to the shoulder axis), the elbow (θ3 = 0 or π) and the wrist (θ5 = 0
or π).  Nothing here imports urkin: ``arm`` is any object with the DH lengths ``a2``, ``a3``
and ``d5``.
"""

import numpy as np


def on_family(arm, family, rng, q=None):
    """A random configuration (or ``q`` moved) exactly on every singular family of ``family``."""
    q = rng.uniform(-np.pi, np.pi, 6) if q is None else q.copy()
    if "elbow" in family:
        q[2] = rng.choice([0.0, np.pi])
    if "wrist" in family:
        q[4] = rng.choice([0.0, np.pi])
    if "shoulder" in family:
        for _ in range(1000):
            reach = arm.a2 * np.cos(q[1]) + arm.a3 * np.cos(q[1] + q[2])
            if abs(reach) <= arm.d5:
                break
            q[1] = rng.uniform(-np.pi, np.pi)
        q[3] = np.arcsin(-reach / arm.d5) - q[1] - q[2]
    return q


#: The singular families and their intersections.
FAMILIES = [
    ("shoulder",),
    ("wrist",),
    ("elbow",),
    ("shoulder", "wrist"),
    ("shoulder", "elbow"),
    ("elbow", "wrist"),
    ("shoulder", "elbow", "wrist"),
]


#: Distances (rad, or m for the shoulder) from each singular family.
NEAR = (1e-3, 1e-5, 1e-7, 1e-9, 1e-10, 1e-11, 1e-12)


def near_family(arm, family, distance, rng):
    """A configuration ``distance`` off each singularity of ``family``: θ3 off 0 or π (elbow),
    θ5 off 0 or π (wrist), the shoulder factor ``a2 c2 + a3 c23 + d5 s234`` off 0 (shoulder)."""
    q = on_family(arm, family, rng)
    if "elbow" in family:
        q[2] += rng.choice([-distance, distance])
    if "wrist" in family:
        q[4] += rng.choice([-distance, distance])
    if "shoulder" in family:  # the planar reach a2 c2 + a3 c23 + d5 s234 = ±distance
        reach = arm.a2 * np.cos(q[1]) + arm.a3 * np.cos(q[1] + q[2])
        offset = rng.choice([-distance, distance])  # on_family keeps |reach| ≤ d5
        q[3] = np.arcsin(np.clip((offset - reach) / arm.d5, -1.0, 1.0)) - q[1] - q[2]
    return q
