"""Benchmark: import time, single-pose and batched FK and Jacobian cost, DH and PoE.

    python bench/kinematics.py            # or: make bench

Prints markdown tables.  Side by side with urkin, in the same run: a plain numpy product of DH
matrices (the way the course reports compute FK, one 4×4 product per link); Pinocchio on a
model built from the same DH table (single configurations: the 4×4 flange pose and the 6×6
frame Jacobian, the outputs urkin's calls hand back); a plain C loop of urkin's own generated
expressions, compiled when a C compiler is present (``bench/c_reference.py``), for batches;
and Robotics Toolbox for Python.  Peers are skipped with a note when not installed
(``pip install -e ".[peers]"``).  Times are the best of several repeats, on whatever machine
runs this; nothing here is asserted by tests.
"""

from __future__ import annotations

import math
import platform
import statistics
import subprocess
import sys
import timeit

import c_reference
import numpy as np

import urkin
from urkin import poe
from urkin.kinematics import dh_transform

BATCH_SIZES = (1, 10, 100, 1_000, 10_000, 100_000)
ROBOT = urkin.robot("ur5")
S, M = poe.space_screws(ROBOT)


def best_time(statement, number: int, repeat: int = 5) -> float:
    """Best time per call in seconds."""
    return min(timeit.repeat(statement, number=number, repeat=repeat)) / number


def interleaved(calls: list[tuple[object, int]], rounds: int = 40) -> list[float]:
    """Best time per call in seconds of each ``(statement, number)``, timed in turn, a slice
    of ``number // 10`` calls each, for ``rounds`` rounds: a slow spell of a shared machine
    then hits every function alike, where timing one after the other would let it fall on
    one function and skew the ratios."""
    best = [math.inf] * len(calls)
    for _ in range(rounds):
        for k, (statement, number) in enumerate(calls):
            chunk = max(1, number // 10)
            best[k] = min(best[k], timeit.timeit(statement, number=chunk) / chunk)
    return best


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


def pinocchio_model():
    """Pinocchio's model of the same arm, built from urkin's DH table (revolute-z joints whose
    placements are the DH offsets ``Tz(d) Tx(a) Rx(α)`` of the previous link, and a flange
    frame), or None when Pinocchio is not installed."""
    try:
        import pinocchio as pin
    except ImportError:
        return None
    model = pin.Model()
    parent, placement = 0, pin.SE3.Identity()
    for i, (d, a, alpha) in enumerate(zip(ROBOT.d, ROBOT.a, ROBOT.alpha)):
        parent = model.addJoint(parent, pin.JointModelRZ(), placement, f"joint{i + 1}")
        model.appendBodyToJoint(parent, pin.Inertia.Zero(), pin.SE3.Identity())
        placement = pin.SE3(pin.utils.rotate("x", alpha), np.array([a, 0.0, d]))
    flange = model.addFrame(pin.Frame("flange", parent, 0, placement, pin.FrameType.OP_FRAME))
    data = model.createData()
    world = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED

    def fk(q):  # the flange pose as a 4×4 array, like urkin.fk
        pin.forwardKinematics(model, data, q)
        return pin.updateFramePlacement(model, data, flange).homogeneous

    def jacobian(q):  # [v; ω] of the flange origin in base axes, like urkin.jacobian
        return pin.computeFrameJacobian(model, data, q, flange, world)

    def fk_only(q):  # joint placements only, no array handed back
        pin.forwardKinematics(model, data, q)

    return fk, jacobian, fk_only


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

    pin = pinocchio_model()
    if pin is not None:
        Q = rng.uniform(-np.pi, np.pi, (1000, 6))
        worst = max(
            max(np.abs(pin[0](x) - urkin.fk(ROBOT, x)).max() for x in Q),
            max(np.abs(pin[1](x) - urkin.jacobian(ROBOT, x)).max() for x in Q),
        )
        print(f"Pinocchio and urkin agree to {worst:.1e} on 1000 random configurations.\n")
    rows = [
        ("urkin.fk", lambda: urkin.fk(ROBOT, q), "fk"),
        ("urkin.jacobian", lambda: urkin.jacobian(ROBOT, q), "jacobian"),
        ("urkin.position_jacobian", lambda: urkin.position_jacobian(ROBOT, q), ""),
        ("urkin.fk_frames", lambda: urkin.fk_frames(ROBOT, q), ""),
        ("urkin.poe.fk_space (PoE)", lambda: poe.fk_space(M, S, q), ""),
        ("urkin.poe.jacobian_space (PoE)", lambda: poe.jacobian_space(S, q), ""),
        ("plain DH product (6 × 4×4 matmul)", lambda: plain_dh_fk(q), ""),
    ]
    if pin is not None:
        rows += [
            ("pinocchio forwardKinematics + flange pose (4×4)", lambda: pin[0](q), "pin fk"),
            ("pinocchio computeFrameJacobian (6×6)", lambda: pin[1](q), "pin jacobian"),
            ("pinocchio forwardKinematics alone (no array out)", lambda: pin[2](q), ""),
        ]
    ur5_rtb = toolbox()
    if ur5_rtb is not None:
        rows += [
            ("roboticstoolbox UR5.fkine", lambda: ur5_rtb.fkine(q), ""),
            ("roboticstoolbox UR5.jacob0", lambda: ur5_rtb.jacob0(q), ""),
        ]
    single = {}
    print(
        "## One configuration\n\nBest of 40 rounds, each timing every function in turn.\n\n"
        "| function | µs per call |\n|---|---|"
    )
    numbers = [
        2_000 if "poe" in name or "plain" in name or "robotics" in name else 20_000
        for name, _, _ in rows
    ]
    times = interleaved([(call, number) for (_, call, _), number in zip(rows, numbers)])
    for (name, _, key), seconds in zip(rows, times):
        single[key] = seconds
        print(f"| {name} | {seconds * 1e6:.2f} |")
    if pin is not None:
        print("\n| ratio (same run) | value |\n|---|---|")
        print(f"| urkin.fk / Pinocchio FK + pose | {single['fk'] / single['pin fk']:.2f} |")
        ratio = single["jacobian"] / single["pin jacobian"]
        print(f"| urkin.jacobian / Pinocchio frame Jacobian | {ratio:.2f} |")
    else:
        print("\n(pinocchio is not installed: its rows are skipped)")
    if ur5_rtb is None:
        print("\n(roboticstoolbox-python is not installed: its rows are skipped)")

    reference = c_reference.load()
    print("\n## Batches\n")
    print(
        "ns per pose.  The C loop runs the same generated expressions compiled with "
        f"`cc {' '.join(c_reference.FLAGS)}`; the last rows divide urkin's time by it.\n"
    )
    header = " | ".join(f"N = {n:,}" for n in BATCH_SIZES)
    print(f"| function | {header} |\n|---|{'---|' * len(BATCH_SIZES)}")
    batch_rows = [
        ("urkin.fk", lambda Q: urkin.fk(ROBOT, Q)),
        ("urkin.jacobian", lambda Q: urkin.jacobian(ROBOT, Q)),
        ("urkin.position_jacobian", lambda Q: urkin.position_jacobian(ROBOT, Q)),
        ("urkin.fk_frames", lambda Q: urkin.fk_frames(ROBOT, Q)),
        ("urkin.poe.fk_space (PoE)", lambda Q: poe.fk_space(M, S, Q)),
        ("urkin.poe.jacobian_space (PoE)", lambda Q: poe.jacobian_space(S, Q)),
        ("plain DH product", plain_dh_fk),
    ]
    if reference is not None:
        batch_rows += [
            ("C loop, fk", lambda Q: reference.fk(ROBOT, Q)),
            ("C loop, jacobian", lambda Q: reference.jacobian(ROBOT, Q)),
        ]
    if pin is not None:
        batch_rows += [
            ("pinocchio fk, a Python loop", lambda Q: [pin[0](x) for x in Q]),
            ("pinocchio jacobian, a Python loop", lambda Q: [pin[1](x) for x in Q]),
        ]
    measured = {}
    for name, call in batch_rows:
        cells = []
        for n in BATCH_SIZES:
            Q = rng.uniform(-np.pi, np.pi, (n, 6))
            number = max(1, 100_000 // n) if "pinocchio" not in name else max(1, 10_000 // n)
            measured[name, n] = best_time(lambda Q=Q, call=call: call(Q), number, repeat=5) / n
            cells.append(f"{measured[name, n] * 1e9:,.0f}")
        print(f"| {name} | {' | '.join(cells)} |")
    if reference is not None:
        for what in ("fk", "jacobian"):
            cells = [
                f"{measured[f'urkin.{what}', n] / measured[f'C loop, {what}', n]:.2f}"
                for n in BATCH_SIZES
            ]
            print(f"| urkin.{what} / C loop | {' | '.join(cells)} |")
        for what in ("fk", "jacobian"):
            cells = [f"{measured[f'urkin.{what}', n] / single[what]:.2f}" for n in BATCH_SIZES]
            print(f"| urkin.{what} per pose / one-pose call | {' | '.join(cells)} |")
    else:
        print("\n(no C compiler: the C loop rows are skipped)")


if __name__ == "__main__":
    main()
