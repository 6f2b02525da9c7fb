"""Benchmark: closed-form IK, every solution, urkin batched next to ur-analytic-ik.

    python bench/ik_analytic.py

ur-analytic-ik (``pip install ur-analytic-ik``, in the ``peers`` extra) is a C++ implementation
called once per pose; urkin solves a whole batch of poses in one call.  Both are timed on the
same seeded UR5 poses (q uniform in [−π, π]⁶), then both are run on poses that are *exactly*
singular — generated from configurations on the shoulder, wrist and elbow families and their
intersections — and the table counts the poses each one solves: at least one returned
solution reaches the pose within 1e-9 m and 1e-9 rad.
"""

from __future__ import annotations

import platform
import time

import numpy as np

import urkin
from urkin.transforms import rotation_angle

ROBOT = urkin.robot("ur5")


def reaches(solutions: np.ndarray, T: np.ndarray) -> bool:
    if len(solutions) == 0:
        return False
    reached = urkin.fk(ROBOT, np.asarray(solutions, dtype=float))
    position = np.linalg.norm(reached[:, :3, 3] - T[:3, 3], axis=1)
    angle = rotation_angle(reached[:, :3, :3], T[:3, :3])
    return bool(np.any((position < 1e-9) & (angle < 1e-9)))


def on_family(family: tuple[str, ...], rng: np.random.Generator) -> np.ndarray:
    q = rng.uniform(-np.pi, np.pi, 6)
    if "elbow" in family:
        q[2] = rng.choice([0.0, np.pi])
    if "wrist" in family:
        q[4] = rng.choice([0.0, np.pi])
    if "shoulder" in family:
        while abs(ROBOT.a2 * np.cos(q[1]) + ROBOT.a3 * np.cos(q[1] + q[2])) > ROBOT.d5:
            q[1] = rng.uniform(-np.pi, np.pi)
        reach = ROBOT.a2 * np.cos(q[1]) + ROBOT.a3 * np.cos(q[1] + q[2])
        q[3] = np.arcsin(-reach / ROBOT.d5) - q[1] - q[2]
    return q


def peer():
    try:
        import ur_analytic_ik
    except ImportError:
        return None
    return lambda T: ur_analytic_ik.ur5.inverse_kinematics(np.ascontiguousarray(T))


def main() -> None:
    rng = np.random.default_rng(7)
    n = 10_000
    T = urkin.fk(ROBOT, rng.uniform(-np.pi, np.pi, (n, 6)))
    print(
        f"# closed-form IK, all solutions, UR5 ({platform.machine()}, "
        f"Python {platform.python_version()}, numpy {np.__version__})\n"
    )
    rows = []
    single = min(_time(lambda: [urkin.ik_analytic(ROBOT, t) for t in T[:2000]]) for _ in range(5))
    rows.append(("urkin.ik_analytic, one pose per call", 2000, single / 2000))
    for size in (10, 100, n):
        batch = T[:size]
        best = min(_time(lambda batch=batch: urkin.ik_analytic(ROBOT, batch)) for _ in range(7))
        rows.append((f"urkin.ik_analytic, batch of {size:,}", size, best / size))
    other = peer()
    if other is not None:
        best = min(_time(lambda: [other(t) for t in T[:2000]]) for _ in range(5))
        rows.append(("ur-analytic-ik, one call per pose (C++)", 2000, best / 2000))
    print("| solver | poses | µs per pose | × ur-analytic-ik per call |\n|---|---|---|---|")
    for name, count, seconds in rows:
        ratio = "–" if other is None else f"{seconds / rows[-1][2]:.3f}"
        print(f"| {name} | {count:,} | {seconds * 1e6:.2f} | {ratio} |")
    if other is None:
        print("\n(ur-analytic-ik is not installed: its rows are skipped)")

    print("\n| exactly singular poses | poses | solved by urkin | solved by ur-analytic-ik |")
    print("|---|---|---|---|")
    families = [
        ("shoulder",),
        ("wrist",),
        ("elbow",),
        ("shoulder", "wrist"),
        ("shoulder", "elbow"),
        ("elbow", "wrist"),
        ("shoulder", "elbow", "wrist"),
    ]
    for family in families:
        poses = urkin.fk(ROBOT, np.array([on_family(family, rng) for _ in range(1000)]))
        ours = sum(reaches(urkin.ik_analytic(ROBOT, t), t) for t in poses)
        theirs = "–" if other is None else str(sum(reaches(other(t), t) for t in poses))
        print(f"| {' + '.join(family)} | {len(poses)} | {ours} | {theirs} |")


def _time(call) -> float:
    t0 = time.perf_counter()
    call()
    return time.perf_counter() - t0


if __name__ == "__main__":
    main()
