"""Benchmark: numerical IK, urkin next to its peers, on the same seeded targets.

    python bench/ik.py                    # 1000 UR5 targets, q uniform in [−π, π]⁶
    python bench/ik.py --targets 200      # fewer, for a quick look

Peers are imported when installed (``pip install -e ".[peers]"``) and skipped with a message
otherwise:

* Robotics Toolbox for Python's C++ ``ik_LM`` on a DH model built from UR's official numbers
  (the toolbox's bundled UR5 carries the d1 = 0.089459 typo), called on the arm's cached ETS
  (``arm.ik_LM`` rebuilds it on every call) with ``tol=1e-20``: its ``tol`` bounds ½‖e‖², so
  the ``5e-13`` used before stopped at ‖e‖ ≈ 1e-6 and verified only about a third of its
  solves at 1e-9, which flattered urkin;
* Modern Robotics' ``IKinSpace`` (pure Python, Newton–Raphson on the twist error), on a subset
  of the targets because it is slow;
* urkin: ``urkin.ik`` one target at a time, and all targets in one batched call.

Each solver and start is timed in ``--rounds`` interleaved rounds (3 by default; Modern
Robotics in one) and its best round is reported, so that a slow spell of the machine does not
fall on one row only.  Every solution is verified the same way: pose error below 1e-9
(position in metres and rotation angle in radians) measured with urkin's forward kinematics,
after wrapping the joint angles.  The table gives the time per solve, the time per *verified*
solve and its ratio to the toolbox's, all measured in the same run, on whatever machine runs
this; tests never assert on them.
"""

from __future__ import annotations

import argparse
import platform
import time

import numpy as np

import urkin
from urkin.poe import space_screws
from urkin.transforms import rotation_angle

ROBOT = urkin.robot("ur5")


def verified(q: np.ndarray, targets: np.ndarray) -> np.ndarray:
    """Which solutions reach their targets within 1e-9 m and 1e-9 rad (urkin's FK)."""
    wrapped = (np.asarray(q, dtype=float) + np.pi) % (2 * np.pi) - np.pi
    ok = np.all(np.isfinite(wrapped), axis=1)
    T = urkin.fk(ROBOT, np.where(ok[:, None], wrapped, 0.0))
    position = np.linalg.norm(T[:, :3, 3] - targets[:, :3, 3], axis=1)
    angle = rotation_angle(T[:, :3, :3], targets[:, :3, :3])
    return ok & (position < 1e-9) & (angle < 1e-9)


def timed(solve, targets, starts):
    t0 = time.perf_counter()
    q = solve(targets, starts)
    return (time.perf_counter() - t0) / len(targets), q


def urkin_single(targets, starts):
    return np.array([urkin.ik(ROBOT, T, q0=q0).q for T, q0 in zip(targets, starts)])


def urkin_batched(targets, starts):
    return urkin.ik(ROBOT, targets, q0=starts).q


def toolbox_solver():
    try:
        import roboticstoolbox as rtb
    except ImportError:
        return None, "roboticstoolbox-python is not installed: its row is skipped"
    links = [
        rtb.RevoluteDH(d=d, a=a, alpha=alpha) for d, a, alpha in zip(ROBOT.d, ROBOT.a, ROBOT.alpha)
    ]
    ets = rtb.DHRobot(links, name="UR5 (official DH)").ets()

    def solve(targets, starts):
        return np.array([ets.ik_LM(T, q0=q0, tol=1e-20)[0] for T, q0 in zip(targets, starts)])

    return solve, ""


def modern_robotics_solver():
    try:
        import modern_robotics as mr
    except ImportError:
        return None, "modern-robotics is not installed: its row is skipped"
    S, M = space_screws(ROBOT)

    def solve(targets, starts):
        return np.array(
            [mr.IKinSpace(S, M, T, q0, 1e-12, 1e-12)[0] for T, q0 in zip(targets, starts)]
        )

    return solve, ""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--targets", type=int, default=1000)
    parser.add_argument(
        "--mr-targets", type=int, default=200, help="targets for Modern Robotics' slow IKinSpace"
    )
    parser.add_argument(
        "--rounds", type=int, default=3, help="rounds of timing; each row's best is reported"
    )
    args = parser.parse_args()
    rng = np.random.default_rng(2024)
    Q = rng.uniform(-np.pi, np.pi, (args.targets, 6))
    targets = urkin.fk(ROBOT, Q)
    starts = {
        "q0 = 0": np.zeros((args.targets, 6)),
        "random q0": rng.uniform(-np.pi, np.pi, (args.targets, 6)),
    }
    print(
        f"# numerical IK on {args.targets} UR5 targets (q uniform in [−π, π]⁶), "
        f"{platform.machine()}, Python {platform.python_version()}, numpy {np.__version__}\n"
    )
    rows = [
        ("urkin.ik, one target at a time (lm)", urkin_single, args.targets),
        ("urkin.ik, batched (lm)", urkin_batched, args.targets),
    ]
    notes = []
    for name, (solver, note) in [
        ("roboticstoolbox ik_LM (C++, tol=1e-20)", toolbox_solver()),
        ("modern_robotics IKinSpace", modern_robotics_solver()),
    ]:
        if solver is None:
            notes.append(note)
        else:
            count = args.mr_targets if "modern" in name else args.targets
            rows.append((name, solver, min(count, args.targets)))
    # every solver on every start, round after round (so that a slow spell of the machine
    # falls on all of them), each timed as its best round
    runs = [
        (name, solve, count, start, Q0)
        for name, solve, count in rows
        for start, Q0 in starts.items()
    ]
    best, rates = [np.inf] * len(runs), [0.0] * len(runs)
    for round_ in range(args.rounds):
        for k, (name, solve, count, _, Q0) in enumerate(runs):
            if round_ and "modern" in name:
                continue  # slow, and far from the others: one round
            seconds, q = timed(solve, targets[:count], Q0[:count])
            best[k] = min(best[k], seconds)
            if not round_:
                rates[k] = verified(q, targets[:count]).mean()
    measured = [
        (name, start, count, seconds, rate)
        for (name, _, count, start, _), seconds, rate in zip(runs, best, rates)
    ]
    reference = {
        start: seconds / max(rate, 1e-9)
        for name, start, _, seconds, rate in measured
        if name.startswith("roboticstoolbox")
    }
    print(
        "| solver | start | targets | µs per solve | verified success (< 1e-9) "
        "| µs per verified solve | × roboticstoolbox |"
    )
    print("|---|---|---|---|---|---|---|")
    for name, start, count, seconds, rate in measured:
        per_verified = seconds / max(rate, 1e-9)
        ratio = f"{per_verified / reference[start]:.2f}" if start in reference else "–"
        print(
            f"| {name} | {start} | {count} | {seconds * 1e6:,.0f} | {100 * rate:.2f} % "
            f"| {per_verified * 1e6:,.0f} | {ratio} |"
        )
    for note in notes:
        print(f"\n({note})")
    batch_sizes(targets, starts["q0 = 0"], args.rounds)


#: Batch sizes of the second table: every one solves the same targets, in chunks of this size.
BATCH_SIZES = (1, 2, 4, 8, 9, 16, 32, 64, 128, 256, 1000)


def batch_sizes(targets: np.ndarray, starts: np.ndarray, rounds: int) -> None:
    """Per-target time of ``urkin.ik`` on the same targets in batches of each size, next to
    one target per call: a batch of any size should never cost more per target.  Every size
    is timed in ``rounds`` interleaved rounds, its best round reported."""
    n = len(targets)
    sizes = [size for size in BATCH_SIZES if size <= n]
    best, rates = dict.fromkeys(sizes, np.inf), {}
    for _ in range(rounds):
        for size in sizes:
            t0 = time.perf_counter()
            q = np.concatenate(
                [
                    urkin.ik(ROBOT, targets[i : i + size], q0=starts[i : i + size]).q
                    for i in range(0, n, size)
                ]
            )
            best[size] = min(best[size], (time.perf_counter() - t0) / n)
            rates[size] = verified(q, targets).mean()
    rows = [(size, best[size], rates[size]) for size in sizes]
    single = rows[0][1]
    print(f"\n## Batch sizes ({n} targets, q0 = 0, each size solving all of them)\n")
    print("| targets per call | µs per target | verified success | per target / one per call |")
    print("|---|---|---|---|")
    for size, seconds, rate in rows:
        print(f"| {size:,d} | {seconds * 1e6:,.0f} | {100 * rate:.2f} % | {seconds / single:.2f} |")


if __name__ == "__main__":
    main()
