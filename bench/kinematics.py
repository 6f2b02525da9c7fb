"""Benchmark: import time, single-pose and batched FK and Jacobian cost, DH and PoE.

    python bench/kinematics.py            # or: make bench

Prints markdown tables.  Side by side with urkin: a plain numpy product of DH matrices (the
way the course reports compute FK, one 4×4 product per link) and, when installed,
Robotics Toolbox for Python (``pip install -e ".[peers]"``).  Times are the best of
several repeats, on whatever machine runs this; nothing here is asserted by tests.
"""

from __future__ import annotations

import platform
import statistics
import subprocess
import sys
import timeit

import numpy as np

import urkin
from urkin import poe
from urkin.kinematics import dh_transform

SIZES = (1_000, 10_000, 100_000)
ROBOT = urkin.robot("ur5")
S, M = poe.space_screws(ROBOT)
B, _ = poe.body_screws(ROBOT)


def best_time(statement, number: int, repeat: int = 5) -> float:
    """Best time per call in seconds."""
    return min(timeit.repeat(statement, number=number, repeat=repeat)) / number


def import_time(repeat: int = 7) -> tuple[float, bool]:
    code = (
        "import sys, time; t = time.perf_counter(); import urkin; "
        "print(time.perf_counter() - t, 'sympy' in sys.modules)"
    )
    times, sympy_loaded = [], False
    for _ in range(repeat):
        out = subprocess.run(
            [sys.executable, "-c", code], capture_output=True, text=True, check=True
        ).stdout.split()
        times.append(float(out[0]))
        sympy_loaded |= out[1] == "True"
    return statistics.median(times), sympy_loaded


def plain_dh_fk(q: np.ndarray) -> np.ndarray:
    """A straightforward FK: build the six DH matrices and multiply them (batched)."""
    links = dh_transform(q, ROBOT.d, ROBOT.a, ROBOT.alpha)  # (..., 6, 4, 4)
    T = links[..., 0, :, :]
    for i in range(1, 6):
        T = T @ links[..., i, :, :]
    return T


def toolbox():
    try:
        import roboticstoolbox as rtb
    except ImportError:
        return None
    return rtb.models.DH.UR5()


def main() -> None:
    rng = np.random.default_rng(0)
    q = rng.uniform(-np.pi, np.pi, 6)
    print(
        f"# urkin kinematics benchmark ({platform.processor() or platform.machine()}, "
        f"Python {platform.python_version()}, numpy {np.__version__})\n"
    )

    seconds, sympy_loaded = import_time()
    print("| measure | value |\n|---|---|")
    print(f"| `import urkin` (median of 7 fresh interpreters) | {seconds * 1e3:.0f} ms |")
    print(f"| SymPy imported by `import urkin` | {'yes' if sympy_loaded else 'no'} |\n")

    rows = [
        ("urkin.fk", lambda: urkin.fk(ROBOT, q)),
        ("urkin.jacobian", lambda: urkin.jacobian(ROBOT, q)),
        ("urkin.position_jacobian", lambda: urkin.position_jacobian(ROBOT, q)),
        ("urkin.fk_frames", lambda: urkin.fk_frames(ROBOT, q)),
        ("urkin.poe.fk_space (PoE)", lambda: poe.fk_space(M, S, q)),
        ("urkin.poe.fk_body (PoE)", lambda: poe.fk_body(M, B, q)),
        ("urkin.poe.jacobian_space (PoE)", lambda: poe.jacobian_space(S, q)),
        ("urkin.poe.jacobian_body (PoE)", lambda: poe.jacobian_body(B, q)),
        ("plain DH product (6 × 4×4 matmul)", lambda: plain_dh_fk(q)),
    ]
    ur5_rtb = toolbox()
    if ur5_rtb is not None:
        rows += [
            ("roboticstoolbox UR5.fkine", lambda: ur5_rtb.fkine(q)),
            ("roboticstoolbox UR5.jacob0", lambda: ur5_rtb.jacob0(q)),
        ]
    print("## One configuration\n\n| function | µs per call |\n|---|---|")
    for name, call in rows:
        number = 20_000 if name.startswith("urkin.") and "poe" not in name else 2_000
        print(f"| {name} | {best_time(call, number) * 1e6:.2f} |")
    if ur5_rtb is None:
        print("\n(roboticstoolbox-python is not installed: its rows are skipped)")

    print("\n## Batches\n")
    header = " | ".join(f"N = {n:,}" for n in SIZES)
    print(f"| function, ns per pose | {header} |\n|---|{'---|' * len(SIZES)}")
    batch_rows = [
        ("urkin.fk", lambda Q: urkin.fk(ROBOT, Q)),
        ("urkin.jacobian", lambda Q: urkin.jacobian(ROBOT, Q)),
        ("urkin.position_jacobian", lambda Q: urkin.position_jacobian(ROBOT, Q)),
        ("urkin.fk_frames", lambda Q: urkin.fk_frames(ROBOT, Q)),
        ("urkin.poe.fk_space (PoE)", lambda Q: poe.fk_space(M, S, Q)),
        ("urkin.poe.fk_body (PoE)", lambda Q: poe.fk_body(M, B, Q)),
        ("urkin.poe.jacobian_space (PoE)", lambda Q: poe.jacobian_space(S, Q)),
        ("urkin.poe.jacobian_body (PoE)", lambda Q: poe.jacobian_body(B, Q)),
        ("plain DH product", plain_dh_fk),
    ]
    if ur5_rtb is not None:
        batch_rows.append(("roboticstoolbox fkine (trajectory)", lambda Q: ur5_rtb.fkine(Q)))
    for name, call in batch_rows:
        cells = []
        for n in SIZES:
            Q = rng.uniform(-np.pi, np.pi, (n, 6))
            number = max(1, 100_000 // n)
            cells.append(
                f"{best_time(lambda Q=Q, call=call: call(Q), number, repeat=3) / n * 1e9:.0f}"
            )
        print(f"| {name} | {' | '.join(cells)} |")


if __name__ == "__main__":
    main()
