"""Benchmark: motion planning on UR5 problems, urkin's RRT-Connect next to OMPL's.

    python bench/planning.py                  # 6 problems per family, 2 seeds each
    python bench/planning.py --quick          # 3 problems per family, 1 seed, for a look
    python bench/planning.py --problems 10 --runs 3 --time-limit 10
    python bench/planning.py --set mbm --problems 100 --runs 1   # MotionBenchMaker, all 700

Two sets of problems.  ``--set mbm``: the MotionBenchMaker UR5 problems as VAMP ships them
(``bench/mbm_problems.py``; seven families of 100, the UR5 on a 0.91 m pedestal with a
force-torque sensor and a Robotiq gripper, joints limited to ±π); problems whose start or
goal is in collision under urkin's sphere model are left out and listed with the pair that
collides.  The default, ``--set seeded``, comes from ``bench/planning_problems.py``: five
MotionBenchMaker-like families (``empty``, ``table``, ``shelf``, ``box``, ``cage``) of UR5
scenes standing on a floor, each problem a start and a goal configuration, both free, whose
straight edge is not (except in ``empty``, where no draw's is: that family times a call's
fixed cost).  Both planners get the same problems, the same seeds (1, 2, …) and the same time limit:

* urkin: ``planning.rrt_connect(model, scene, start, goal, seed=s, time_limit=…,
  max_iterations=10**7)``, which shortcuts its path and re-checks it at a quarter of its
  1 cm resolution before returning (the iteration bound lifted so that, as for OMPL, the time
  limit alone ends a run);
* OMPL (``pip install ompl``; skipped with a note when missing): ``RRTConnect`` with default
  settings on a ``RealVectorStateSpace(6)`` bounded by the robot's joint limits, then
  ``SimpleSetup.simplifySolution()``; its state validity checker is a Python callback calling
  ``planning.is_free(model, scene, q)`` on one state, and its motion validator's longest valid
  segment is set so that no sphere centre moves more than urkin's 1 cm between checked states
  (the line printed under the tables says how).  ``ompl.util.RNG.setSeed(s)`` before each run.

Each run is timed with ``time.perf_counter`` around the planning call, simplification
included (for OMPL: ``solve`` and ``simplifySolution``; its setup is done before).  A run
counts as solved only if its path starts at the start, ends at the goal, stays within the
joint limits and has every edge free under ``planning.edges_free`` at 1 mm, whichever
planner produced it.  Times of unsolved runs (up to the time limit) count in the medians.
Path lengths are Euclidean joint-space lengths (rad) of the simplified, solved paths.
A last table times urkin's collision checks alone.  Numbers are from whatever machine runs
this; nothing here is asserted by tests.
"""

from __future__ import annotations

import argparse
import contextlib
import platform
import subprocess
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import Any

import mbm_problems as mbm
import numpy as np
import planning_problems as pp

from urkin import planning

Problem = pp.Problem | mbm.Problem

#: The sphere model planned with: the bare UR5 of planning_problems, or (``--set mbm``) the
#: MotionBenchMaker UR5 on its pedestal with its sensor and gripper (``main`` sets it).
MODEL = pp.MODEL
#: urkin's edge resolution (its default) and the finer one every returned path is verified at.
RESOLUTION, VERIFY = 0.01, 0.001


@dataclass(frozen=True)
class Run:
    problem: Problem
    planner: str
    seed: int
    seconds: float
    returned: bool  # the planner said it found a path
    solved: bool  # ... and the path passed the verification
    length: float
    reason: str


def limits() -> tuple[np.ndarray, np.ndarray]:
    """Joint limits as ``rrt_connect`` samples them (``urkin.planning.rrt._limits``)."""
    table = np.array(MODEL.robot.joint_limits)
    return table[:, 0], table[:, 1]


def verify(problem: Problem, path: np.ndarray) -> str:
    """Empty if ``path`` solves ``problem`` (checked at 1 mm), else what is wrong with it."""
    if len(path) < 2:
        return "no path"
    if not np.allclose(path[0], problem.start, atol=1e-9, rtol=0):
        return "path does not start at the start"
    if not np.allclose(path[-1], problem.goal, atol=1e-9, rtol=0):
        return "path does not end at the goal"
    lower, upper = limits()
    if np.any(path < lower) or np.any(path > upper):
        return "path leaves the joint limits"
    free = planning.edges_free(MODEL, problem.scene, path[:-1], path[1:], resolution=VERIFY)
    if not np.all(free):
        k = int(np.flatnonzero(~free)[0])
        return f"edge {k} of {len(free)} collides when checked at {VERIFY * 1000:g} mm"
    return ""


def length(path: np.ndarray) -> float:
    return float(np.linalg.norm(np.diff(path, axis=0), axis=1).sum())


def finish(
    problem: Problem,
    planner: str,
    seed: int,
    seconds: float,
    path: np.ndarray | None,
    reason: str,
) -> Run:
    returned = path is not None
    if returned:
        reason = verify(problem, path)
    solved = returned and not reason
    return Run(
        problem, planner, seed, seconds, returned, solved, length(path) if solved else 0, reason
    )


def run_urkin(problem: Problem, seed: int, time_limit: float) -> Run:
    t0 = time.perf_counter()
    plan = planning.rrt_connect(
        MODEL,
        problem.scene,
        problem.start,
        problem.goal,
        seed=seed,
        time_limit=time_limit,
        max_iterations=10**7,
    )
    seconds = time.perf_counter() - t0
    return finish(problem, "urkin", seed, seconds, plan.path if plan.success else None, plan.reason)


# --- OMPL -------------------------------------------------------------------------------------


def reach_bounds() -> np.ndarray:
    """R (6,): the most any sphere centre moves per radian of each joint, in any
    configuration: urkin's per-link bound ρ_j (``planning.checks._reach``), the largest over
    the spheres.  (urkin's own edges use a tighter bound from each edge's two ends, which a
    fixed joint-space segment length cannot.)"""
    return planning.checks._reach(MODEL).max(axis=0)


def segment_length() -> float:
    """The longest joint-space segment (Euclidean, rad) over which no sphere centre moves more
    than ``RESOLUTION``: a centre moves at most Σ_j |Δq_j| R_j ≤ ‖Δq‖₂ ‖R‖₂ (Cauchy–Schwarz)."""
    return RESOLUTION / float(np.linalg.norm(reach_bounds()))


def joint_space(ob: ModuleType) -> Any:
    """OMPL's ``RealVectorStateSpace(6)`` bounded by the joint limits urkin samples in."""
    lower, upper = limits()
    space = ob.RealVectorStateSpace(6)
    bounds = ob.RealVectorBounds(6)
    for j in range(6):
        bounds.setLow(j, float(lower[j]))
        bounds.setHigh(j, float(upper[j]))
    space.setBounds(bounds)
    return space


@contextlib.contextmanager
def quiet(util: ModuleType) -> Iterator[None]:
    level = util.getLogLevel()
    util.setLogLevel(util.LOG_NONE)
    try:
        yield
    finally:
        util.setLogLevel(level)


def ompl_runner() -> tuple[Callable[[Problem, int, float], Run] | None, str]:
    """A function running OMPL's RRTConnect on a problem, and a line on how it is set up (or
    why it is missing)."""
    try:
        from importlib.metadata import version

        from ompl import base as ob
        from ompl import geometric as og
        from ompl import util
    except ImportError:
        return None, "OMPL not installed (pip install ompl): its rows are skipped"
    util.setLogLevel(util.LOG_ERROR)
    space = joint_space(ob)
    segment = segment_length()
    fraction = segment / space.getMaximumExtent()
    space.setLongestValidSegmentFraction(fraction)

    def run(problem: Problem, seed: int, time_limit: float) -> Run:
        scene = problem.scene

        def valid(state: Any) -> bool:
            return planning.is_free(
                MODEL, scene, [state[0], state[1], state[2], state[3], state[4], state[5]]
            )

        with quiet(util):  # reseeding after the first draw is reported as an error; it works
            util.RNG.setSeed(seed)
        setup = og.SimpleSetup(space)
        setup.setStateValidityChecker(valid)
        start, goal = space.allocState(), space.allocState()
        for j in range(6):
            start[j], goal[j] = float(problem.start[j]), float(problem.goal[j])
        setup.setStartAndGoalStates(start, goal)
        setup.setPlanner(og.RRTConnect(setup.getSpaceInformation()))
        setup.setup()
        t0 = time.perf_counter()
        status = setup.solve(time_limit)
        exact = setup.haveExactSolutionPath()
        if exact:
            setup.simplifySolution()
        seconds = time.perf_counter() - t0
        path = None
        if exact:
            found = setup.getSolutionPath()
            path = np.array(
                [[found.getState(k)[j] for j in range(6)] for k in range(found.getStateCount())]
            )
        return finish(problem, "OMPL", seed, seconds, path, f"OMPL: {status}")

    note = (
        f"OMPL {version('ompl')}: RRTConnect with its default range, 0.2 × the space's extent "
        f"{space.getMaximumExtent():.2f} rad = {0.2 * space.getMaximumExtent():.2f} rad (urkin: "
        f"steps of 0.5 rad in the largest joint), then simplifySolution().  Edge checks matched to "
        f"urkin's guarantee: R_j, the most any sphere centre moves per radian of joint j in any "
        f"configuration (urkin's per-link bound), gives ‖R‖₂ = {RESOLUTION / segment:.3f} m/rad, "
        f"so a joint-space segment of {segment * 1000:.2f} mrad moves no centre more than "
        f"{RESOLUTION * 1000:g} mm (Σ|Δq_j| R_j ≤ ‖Δq‖₂ ‖R‖₂): longest valid segment fraction "
        f"{fraction:.4g}.  Validity: a Python callback calling planning.is_free on one state."
    )
    return run, note


# --- tables -----------------------------------------------------------------------------------


def percentile(values: list[float], q: float) -> float:
    return float(np.percentile(values, q)) if values else float("nan")


def summary(runs: list[Run]) -> tuple[str, float, float, float]:
    solved = sum(r.solved for r in runs)
    seconds = [r.seconds for r in runs]
    lengths = [r.length for r in runs if r.solved]
    return (
        f"{solved}/{len(runs)}",
        percentile(seconds, 50),
        percentile(seconds, 90),
        percentile(lengths, 50),
    )


def print_table(runs: list[Run], planners: list[str], families: list[str]) -> None:
    print(
        "| family | problems × seeds | planner | solved (verified) | median ms | p90 ms "
        "| median length (rad) | median time urkin / OMPL |"
    )
    print("|---|---|---|---|---|---|---|---|")
    for family in [*families, "all"]:
        mine = [r for r in runs if family in ("all", r.problem.family)]
        if not mine:
            continue
        medians = {}
        rows = []
        for planner in planners:
            theirs = [r for r in mine if r.planner == planner]
            solved, median, p90, median_length = summary(theirs)
            medians[planner] = median
            rows.append((planner, len(theirs), solved, median, p90, median_length))
        ratio = (
            f"{medians['urkin'] / medians['OMPL']:.3f}"
            if "OMPL" in medians and medians["OMPL"] > 0
            else "–"
        )
        for planner, count, solved, median, p90, median_length in rows:
            label = f"**{family}**" if family == "all" else family
            shown = ratio if planner == "urkin" else ""
            print(
                f"| {label} | {count} | {planner} | {solved} | {median * 1000:,.1f} "
                f"| {p90 * 1000:,.1f} | {median_length:.2f} | {shown} |"
            )


def print_failures(runs: list[Run]) -> None:
    failed = [r for r in runs if not r.solved]
    if not failed:
        print("\nEvery run was solved and verified.")
        return
    print("\nRuns not solved:\n")
    for r in failed:
        what = "returned a path that failed verification: " if r.returned else ""
        print(f"- {r.planner} {r.problem.name} seed {r.seed} ({r.seconds:.2f} s): {what}{r.reason}")


def print_left_out(problems: list[mbm.Problem]) -> None:
    if not problems:
        return
    print(
        f"\n{len(problems)} problems left out: their start or goal is in collision under "
        "urkin's model (the first offending pair, planning.explain):\n"
    )
    for p in problems:
        vamp = "" if p.vamp_free else " (VAMP's own spheres refuse it too)"
        print(f"- {p.name}: {p.reason}{vamp}")


# --- collision-check costs --------------------------------------------------------------------


def ten_boxes(rng: np.random.Generator) -> planning.Scene:
    """The floor and nine boxes around the arm."""
    boxes = [pp.FLOOR]
    for k in range(9):
        centre = pp.polar(rng.uniform(0.35, 0.8), rng.uniform(-np.pi, np.pi), rng.uniform(0, 0.8))
        boxes.append(
            planning.Box(
                centre,
                rng.uniform(0.05, 0.3, 3),
                rotation=pp.rz(rng.uniform(0, np.pi)),
                name=f"{k}",
            )
        )
    return planning.Scene(boxes=boxes)


def best(call: Callable[[], object], repeat: int = 5) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        call()
        times.append(time.perf_counter() - t0)
    return min(times)


def micro(ompl_available: bool) -> None:
    model = pp.MODEL  # the bare arm at the origin, whatever set was planned
    rng = np.random.default_rng(7)
    scene = ten_boxes(rng)
    lower, upper = limits()
    Q = rng.uniform(-np.pi, np.pi, (10_000, 6))
    batch = best(lambda: planning.is_free(model, scene, Q)) / len(Q)
    free = planning.is_free(model, scene, Q)
    single_q = Q[:1000]
    single = best(lambda: [planning.is_free(model, scene, q) for q in single_q], 3) / len(single_q)
    # edges of 0.75 rad (Euclidean) from free configurations, in random directions
    starts = Q[free][:1000]
    direction = rng.normal(size=starts.shape)
    direction /= np.linalg.norm(direction, axis=1, keepdims=True)
    ends = np.clip(starts + 0.75 * direction, lower, upper)
    edges = best(lambda: planning.edges_free(model, scene, starts, ends)) / len(starts)
    pairs = list(zip(starts[:200], ends[:200]))
    one = best(lambda: [planning.edges_free(model, scene, a, b) for a, b in pairs], 3)
    edges_one = one / len(pairs)
    edge_free = planning.edges_free(model, scene, starts, ends).mean()
    certified = best(lambda: planning.certify_edges(model, scene, starts, ends)) / len(starts)
    proven = planning.certify_edges(model, scene, starts, ends).mean()
    samples = np.mean(planning.edge_samples(model, starts, ends)) + 1
    print(f"\n## Collision checks ({len(scene)}-box scene: the floor and nine boxes)\n")
    print("| check | µs | notes |")
    print("|---|---|---|")
    print(
        f"| is_free, batch of {len(Q):,d} configurations, per configuration | {batch * 1e6:.2f} "
        f"| q uniform in [−π, π]⁶, {100 * free.mean():.1f} % free; budget ≤ 5 (DESIGN §7) |"
    )
    print(f"| is_free, one configuration per call | {single * 1e6:.1f} | budget ≤ 100 (issue 12) |")
    print(
        f"| edges_free, batch of {len(starts):,d} edges of 0.75 rad, per edge | {edges * 1e6:.1f} "
        f"| from free configurations, {100 * edge_free:.1f} % free, "
        f"{samples:.0f} samples each at 1 cm |"
    )
    print(
        f"| edges_free, one edge of 0.75 rad per call | {edges_one * 1e6:.1f} "
        "| budget ≤ 150 (issue 12); VAMP's SIMD kernel: 2–3 |"
    )
    print(
        f"| certify_edges, the same 1,000 edges, per edge | {certified * 1e6:.1f} "
        f"| proven free throughout: {100 * proven:.1f} % |"
    )
    if ompl_available:
        callback = ompl_valid(scene, Q)
        print(f"| OMPL isValid through the Python callback, one state | {callback * 1e6:.1f} | |")


def ompl_valid(scene: planning.Scene, Q: np.ndarray) -> float:
    from ompl import base as ob

    space = joint_space(ob)
    info = ob.SpaceInformation(space)
    info.setStateValidityChecker(
        lambda s: planning.is_free(pp.MODEL, scene, [s[0], s[1], s[2], s[3], s[4], s[5]])
    )
    info.setup()
    states = []
    for q in Q[:1000]:
        state = space.allocState()
        for j in range(6):
            state[j] = float(q[j])
        states.append(state)
    return best(lambda: [info.isValid(s) for s in states], 3) / len(states)


def source_state() -> str:
    """The commit urkin runs from, and whether its ``urkin/`` differs from it."""
    root = Path(__file__).resolve().parent.parent
    try:
        commit = subprocess.run(
            ["git", "-C", str(root), "rev-parse", "--short", "HEAD"],
            capture_output=True,
            text=True,
            check=True,
        ).stdout.strip()
        changed = subprocess.run(
            ["git", "-C", str(root), "status", "--porcelain", "--", "urkin"],
            capture_output=True,
            text=True,
            check=True,
        ).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "urkin from an unknown commit"
    return f"urkin at {commit}" + (" with uncommitted changes" if changed else "")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument(
        "--set",
        choices=("seeded", "mbm"),
        default="seeded",
        help="seeded: planning_problems' families; mbm: the MotionBenchMaker UR5 problems",
    )
    parser.add_argument("--problems", type=int, default=6, help="problems per family")
    parser.add_argument("--runs", type=int, default=2, help="seeds per problem (1, 2, …)")
    parser.add_argument("--time-limit", type=float, default=5.0, help="seconds per run")
    parser.add_argument("--seed", type=int, default=0, help="base seed of the problems")
    parser.add_argument("--families", nargs="+", help="families to run (default: all of the set)")
    parser.add_argument("--quick", action="store_true", help="3 problems per family, 1 seed")
    parser.add_argument("--no-ompl", action="store_true", help="urkin alone")
    args = parser.parse_args()
    if args.quick:
        args.problems, args.runs = 3, 1
    global MODEL
    every = mbm.FAMILIES if args.set == "mbm" else pp.FAMILIES
    families = args.families or list(every)
    unknown = sorted(set(families) - set(every))
    if unknown:
        parser.error(f"--families: {', '.join(unknown)} not in the {args.set} set: {every}")
    if args.set == "mbm":
        MODEL = mbm.model()
        loaded = mbm.problems(tuple(families), args.problems)
        problems: list[Problem] = [p for p in loaded if not p.reason]
        left_out = [p for p in loaded if p.reason]
        title = (
            f"MotionBenchMaker UR5 problems (VAMP's copy): the first {args.problems} of each "
            f"family, {len(problems)} of {len(loaded)} with start and goal free under urkin's "
            f"model ({sum(p.vamp_free for p in problems)} of the "
            f"{sum(p.vamp_free for p in loaded)} free under VAMP's own spheres)"
        )
    else:
        problems = [p for f in families for p in pp.problems(f, args.problems, args.seed)]
        left_out = []
        title = f"{args.problems} seeded problems per family (problem seed {args.seed})"
    ompl, note = (None, "OMPL left out (--no-ompl)") if args.no_ompl else ompl_runner()
    planners = ["urkin"] + (["OMPL"] if ompl else [])
    if ompl is None:
        print(f"{note}\n")
    print(
        f"# motion planning: {title} × {args.runs} planner seeds, time limit "
        f"{args.time_limit:g} s; {MODEL}; {source_state()}; {platform.machine()}, "
        f"Python {platform.python_version()}, numpy {np.__version__}\n"
    )
    runs: list[Run] = []
    for problem in problems:
        for seed in range(1, args.runs + 1):
            runs.append(run_urkin(problem, seed, args.time_limit))
            if ompl:
                runs.append(ompl(problem, seed, args.time_limit))
    print_table(runs, planners, families)
    print(
        "\nSolved: the path verified at 1 mm.  Times: per run, planning call with "
        "simplification, unsolved runs included.  Budget (DESIGN §7): every problem solved, "
        "median in tens of milliseconds."
        + (
            "  The empty family (floor only) keeps problems whose straight edge is free (no "
            "draw had one that is not): it times a call's fixed cost."
            if args.set == "seeded"
            else "  The MotionBenchMaker robot: urkin's UR5 spheres and VAMP's 17 sensor and "
            "gripper spheres (bench/mbm_problems.py)."
        )
    )
    print(f"\n{note}")
    print_failures(runs)
    print_left_out(left_out)
    micro(ompl is not None)


if __name__ == "__main__":
    main()
