"""Benchmark: lesson 10's tasks planned end to end — the two-block stack and the Tower of Hanoi.

    python bench/tasks.py                 # seeds 0-4, Hanoi with 3 blocks
    python bench/tasks.py --seeds 10 --hanoi 4

Each task is planned by ``planning.pick_and_place`` on lesson 10's world (the UR3 on the
lab's table, seed report 004) with seeds 0, 1, …, then checked from scratch by
``planning.replay`` (every configuration and edge at 1 cm, the carried block attached and
tested exactly) and its final block poses compared with the goals.  The first table gives,
per phase kind, the median computing time per task over the seeds (the sum over that
phase's occurrences in a task; "approach" is the choice of the grasp — closed-form
solutions over the block's symmetric yaws, the vertical moves tracked and checked —,
"descend" the choice of the place, "to pre-grasp" and "transfer" the RRT-Connect calls; the
first seed also builds the carried blocks' sphere models, about 0.4 s), and the task totals:
computing time, motion time (the timed trajectory's length), replay verdict and the largest
final block error.

The second table re-plans every RRT-Connect query the tasks made (to pre-grasp: the arm and
gripper against the world; transfer: with the carried block's spheres, the block left out of
the scene) with OMPL's RRTConnect + ``simplifySolution()`` (``pip install ompl``; skipped
with a note when missing), its validity a Python callback calling ``planning.is_free`` with
the same model and scene, its motion resolution matched to urkin's 1 cm bound the way
``bench/planning.py`` does, the same seeds, and gives the median times and their ratio.  An
OMPL path counts only if ``planning.edges_free`` passes it at 2.5 mm.  Numbers are from the
machine that runs this; nothing here is asserted by tests.
"""

from __future__ import annotations

import argparse
import platform
import statistics
import time

import numpy as np

from urkin import planning
from urkin.course.tabletop import LAB_HOME, hanoi_moves, hanoi_tasks, hanoi_world, lab_world

STACK_GOAL = (0.25, -0.05)
RESOLUTION, VERIFY = 0.01, 0.0025


def tasks(hanoi: int) -> dict[str, tuple[planning.World, list]]:
    world = lab_world()
    stack = [("A", *STACK_GOAL), ("B", *STACK_GOAL)]
    h = hanoi_world(hanoi)
    return {
        "two-block stack": (world, stack),
        f"Hanoi, {hanoi} blocks": (h, hanoi_tasks(h, hanoi_moves(hanoi))),
    }


def queries(
    task: planning.Task,
) -> list[tuple[str, planning.SphereModel, planning.Scene, np.ndarray]]:
    """The RRT-Connect queries a task made: (kind, model, scene, path found by urkin)."""
    out = []
    world = task.start
    for p in task.phases:
        if p.name == "to pre-grasp":
            out.append((p.name, world.model, world.scene(), p.q))
        elif p.name == "transfer":
            size = world.block(p.block).size
            out.append((p.name, world.carrying(size), world.scene(without=(p.block,)), p.q))
        elif p.name == "release":
            goal = next(g for g in task.goals if g.name == p.block)
            world = world.with_block(goal)
    return out


def ompl_planner():
    try:
        from ompl import base as ob
        from ompl import geometric as og
        from ompl import util
    except ImportError:
        return None, "OMPL not installed (pip install ompl): its columns are empty"
    util.setLogLevel(util.LOG_NONE)

    def plan(model, scene, start, goal, seed, time_limit=10.0):
        lower, upper = np.array(model.robot.joint_limits).T
        space = ob.RealVectorStateSpace(6)
        bounds = ob.RealVectorBounds(6)
        for j in range(6):
            bounds.setLow(j, float(lower[j]))
            bounds.setHigh(j, float(upper[j]))
        space.setBounds(bounds)
        # urkin's bound R_j (m per rad of joint j) → the longest segment moving no sphere 1 cm
        reach = planning.checks._reach(model).max(axis=0)  # in any configuration
        space.setLongestValidSegmentFraction(
            RESOLUTION / float(np.linalg.norm(reach)) / space.getMaximumExtent()
        )
        setup = og.SimpleSetup(space)
        setup.setStateValidityChecker(
            lambda s: bool(planning.is_free(model, scene, [s[j] for j in range(6)]))
        )
        a, b = space.allocState(), space.allocState()
        for j in range(6):
            a[j], b[j] = float(start[j]), float(goal[j])
        setup.setStartAndGoalStates(a, b)
        setup.setPlanner(og.RRTConnect(setup.getSpaceInformation()))
        setup.setup()
        util.RNG.setSeed(seed + 1)
        t0 = time.perf_counter()
        setup.solve(time_limit)
        exact = setup.haveExactSolutionPath()
        if exact:
            setup.simplifySolution()
        seconds = time.perf_counter() - t0
        if not exact:
            return seconds, False
        found = setup.getSolutionPath()
        path = np.array(
            [[found.getState(k)[j] for j in range(6)] for k in range(found.getStateCount())]
        )
        ok = bool(np.all(planning.edges_free(model, scene, path[:-1], path[1:], VERIFY)))
        return seconds, ok

    return plan, "OMPL RRTConnect + simplifySolution, Python validity callback"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--hanoi", type=int, default=3)
    args = parser.parse_args()
    print(f"# {platform.processor() or platform.machine()}, Python {platform.python_version()}")
    print(f"# seeds 0 … {args.seeds - 1}; medians over the seeds\n")
    ompl, note = ompl_planner()
    for label, (world, moves) in tasks(args.hanoi).items():
        per_phase: dict[str, list[float]] = {name: [] for name in planning.tasks.PHASES}
        totals, motions, verdicts, errors, found = [], [], [], [], []
        for seed in range(args.seeds):
            t0 = time.perf_counter()
            task = planning.pick_and_place(world, moves, LAB_HOME, seed=seed)
            totals.append(time.perf_counter() - t0)
            ok, _, final = planning.replay(world, LAB_HOME, task.steps())
            verdicts.append(task.success and ok)
            last = {g.name: g for g in task.goals}
            errors.append(
                max(np.linalg.norm(final.block(n).centre - g.centre) for n, g in last.items())
            )
            motions.append(float(task.t[-1]))
            for name in per_phase:
                per_phase[name].append(sum(p.seconds for p in task.phases if p.name == name))
            found += [(q, seed) for q in queries(task)]
        print(f"## {label}: {len(moves)} moves, {len(moves) * 8} phases")
        print(f"{'phase':<16}{'median compute per task':>26}")
        for name, values in per_phase.items():
            print(f"{name:<16}{statistics.median(values) * 1e3:23.1f} ms")
        print(
            f"{'whole task':<16}{statistics.median(totals) * 1e3:23.1f} ms"
            f"   (min {min(totals) * 1e3:.1f}, max {max(totals) * 1e3:.1f})"
        )
        print(
            f"motion time {statistics.median(motions):.1f} s; replay passed "
            f"{sum(verdicts)}/{len(verdicts)}; largest final block error "
            f"{max(errors) * 1e3:.2g} mm\n"
        )
        if ompl is None:
            print(note + "\n")
            continue
        rows = {}
        for (kind, model, scene, path), seed in found:
            t0 = time.perf_counter()
            planning.rrt_connect(model, scene, path[0], path[-1], seed=seed)
            ours = time.perf_counter() - t0
            theirs, ok = ompl(model, scene, path[0], path[-1], seed)
            rows.setdefault(kind, []).append((ours, theirs, ok))
        print(f"{'query':<16}{'count':>6}{'urkin':>10}{'OMPL':>10}{'ratio':>8}{'OMPL ok':>9}")
        for kind, values in rows.items():
            ours = statistics.median(v[0] for v in values)
            theirs = statistics.median(v[1] for v in values)
            print(
                f"{kind:<16}{len(values):6d}{ours * 1e3:8.1f}ms{theirs * 1e3:8.1f}ms"
                f"{ours / theirs:8.3f}{sum(v[2] for v in values):6d}/{len(values)}"
            )
        print(
            f"({note}; urkin re-planned the same start and goal configurations with the same "
            "seed)\n"
        )


if __name__ == "__main__":
    main()
