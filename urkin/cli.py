"""The ``urkin`` command.

::

    urkin grade SUBMISSIONS... --out DIR   grade notebooks (files or folders) into DIR
    urkin course build|check|execute|render   build course/ from solutions/, check, run, render
    urkin codegen [--check]                regenerate urkin/_generated from the SymPy derivation
    urkin info                             the arms urkin knows and their DH lengths
    urkin demo [--robot UR3] [--save FILE.gif] [--script "X+,Z-,home,circle"]
                                           jog an arm in a window, or record a session to a GIF
    urkin demo --task stack|hanoi [--blocks N] [--seed S] [--save FILE.gif]
                                           stack two blocks at a goal you type (asked again
                                           until it is valid), or solve the Tower of Hanoi
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from pathlib import Path

__all__ = ["main"]


def _positive(kind: type) -> object:
    """An argparse type: a finite number of ``kind`` above 0."""

    def parse(text: str) -> int | float:
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
        if not (math.isfinite(value) and value > 0):
            raise argparse.ArgumentTypeError(f"must be above 0; got {text}")
        return value

    return parse


def _lesson(text: str) -> str:
    """An argparse type: the number of one of the course's lessons."""
    from urkin.course.lessons import lessons

    known = sorted(lessons())
    try:
        key = f"{int(text):02d}"
    except ValueError:
        key = None
    if key not in known:
        raise argparse.ArgumentTypeError(
            f"no lesson {text!r}: the course's lessons are {', '.join(known)}"
        )
    return text


def _grade(args: argparse.Namespace) -> int:
    from urkin.course.grading import grade_many, new_seed, progress_bar, write_reports
    from urkin.course.grading.isolation import support

    isolation = support()
    if not isolation.namespaces:
        print(f"WARNING: {isolation.summary}", file=sys.stderr)
    seed = args.seed if args.seed is not None else new_seed()
    progress = progress_bar() if not args.quiet else None
    results = grade_many(
        args.submissions,
        seed=seed,
        lesson=args.lesson,
        time_limit=args.time_limit,
        memory_limit_mb=args.memory_limit,
        setup_limit=args.setup_limit,
        jobs=args.jobs,
        progress=progress,
    )
    if not results:
        print("no notebooks found in " + " ".join(map(str, args.submissions)), file=sys.stderr)
        return 2
    out = write_reports(results, args.out)
    graded = sum(r.status == "graded" for r in results)
    print(f"graded {graded} of {len(results)} submissions (seed {seed}); reports in {out}/")
    print(f"isolation: {isolation.summary}")
    for r in results:
        name = "".join(c if c.isprintable() else "?" for c in r.name)
        print(f"  {name:<40} {r.earned:>5g} / {r.points:<5g} {r.status}")
    return 0


def _info(_: argparse.Namespace) -> int:
    import urkin

    print(f"{'arm':<6} {'d1':>9} {'a2':>9} {'a3':>9} {'d4':>9} {'d5':>9} {'d6':>9}   (metres)")
    for name in urkin.ROBOTS:
        values = " ".join(f"{x:>9.5f}" for x in urkin.robot(name).lengths)
        print(f"{name:<6} {values}")
    return 0


#: The session ``urkin demo --save`` records when no --script is given.
DEMO_SCRIPT = "X+,X+,Z-,Y+,home,circle,square"


def _display() -> str:
    """Why no window can be opened ("" when one can): no display, or a matplotlib backend
    that draws to files only."""
    if sys.platform.startswith("linux") and not (
        os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")
    ):
        return "there is no display (DISPLAY is not set)"
    import matplotlib

    from urkin.jog import _interactive_backend

    if not _interactive_backend():
        return f"matplotlib's backend {matplotlib.get_backend()!r} cannot open a window"
    return ""


def _demo_task(args: argparse.Namespace) -> int:
    """``urkin demo --task stack|hanoi``: lesson 10's tasks in the terminal."""
    if args.save is not None and args.save.suffix.lower() != ".gif":
        print(f"urkin demo: --save needs a .gif file name; got {args.save}", file=sys.stderr)
        return 2
    from urkin.course import tabletop
    from urkin.planning import pick_and_place

    if args.task == "stack":
        prompt = tabletop.StackPrompt(seed=args.seed)
        world = prompt.world
        lo, hi = world.table.footprint().min(axis=0), world.table.footprint().max(axis=0)
        where = ", ".join(
            f"{b.name} at ({b.centre[0]:.2f}, {b.centre[1]:.2f})" for b in world.blocks
        )
        print(
            f"Blocks {where}; the table spans x {lo[0]:.2f} … {hi[0]:.2f}, "
            f"y {lo[1]:.2f} … {hi[1]:.2f} m."
        )
        print("Where should A go, with B stacked on it? Type x y in metres (q quits).")
        while not prompt.done:
            try:
                text = input("goal> ")
            except EOFError:
                print()
                return 1
            if text.strip().lower() in ("q", "quit", "exit"):
                return 1
            print(prompt.submit(text))
        task = prompt.task
    else:
        try:
            world = tabletop.hanoi_world(args.blocks)
        except ValueError as exc:
            print(f"urkin demo: {exc}", file=sys.stderr)
            return 2
        moves = tabletop.hanoi_moves(args.blocks)
        task = pick_and_place(
            world, tabletop.hanoi_tasks(world, moves), tabletop.LAB_HOME, seed=args.seed
        )
        print(f"Tower of Hanoi, {args.blocks} blocks: {len(moves)} moves")
        print(task.report())
        if not task.success:
            print(task.reason)
            return 1
    if args.save is not None:
        import matplotlib

        matplotlib.use("Agg")
        from urkin.plot import animate_task

        animate_task(task).save_gif(args.save)
        print(f"saved {args.save} ({len(task.q)} samples, {task.t[-1]:.1f} s of motion)")
    return 0


def _demo(args: argparse.Namespace) -> int:
    if args.task != "jog":
        return _demo_task(args)
    import urkin
    from urkin.jog import JogController, parse_script

    try:
        robot = urkin.robot(args.robot)
        actions = parse_script(DEMO_SCRIPT if args.script is None else args.script)
    except (KeyError, ValueError) as exc:
        print(f"urkin demo: {exc.args[0]}", file=sys.stderr)
        return 2
    if args.save is None:
        why = _display()
        if why:
            print(
                f"urkin demo: {why}; use --save demo.gif to record a scripted session to a GIF "
                "instead",
                file=sys.stderr,
            )
            return 2
    elif args.save.suffix.lower() != ".gif":
        print(f"urkin demo: --save needs a .gif file name; got {args.save}", file=sys.stderr)
        return 2
    if args.save is not None:
        import matplotlib

        matplotlib.use("Agg")  # recording needs no window
    controller = JogController(robot)
    if args.save is not None or args.script is not None:
        for action in actions:
            print(controller.do(action).status)
    if args.save is None:
        import matplotlib.pyplot as plt

        from urkin.jog import demo_figure

        _window = demo_figure(controller)  # a reference keeps the buttons' callbacks alive
        plt.show()
        return 0
    from urkin.animation import animate

    trail = controller.trail
    animate(robot, trail).save_gif(args.save)
    print(f"saved {args.save} ({len(trail)} configurations)")
    return 0


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``urkin`` console script."""
    from urkin.course.grading import (
        DEFAULT_MEMORY_LIMIT_MB,
        DEFAULT_SETUP_LIMIT,
        DEFAULT_TIME_LIMIT,
    )

    parser = argparse.ArgumentParser(
        prog="urkin", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    commands = parser.add_subparsers(dest="command", required=True)

    grade = commands.add_parser("grade", help="grade submitted notebooks")
    grade.add_argument("submissions", nargs="+", type=Path, help="notebooks or folders of them")
    grade.add_argument("--out", type=Path, required=True, help="folder for the reports")
    grade.add_argument("--seed", type=int, help="seed of the test inputs (fresh by default)")
    grade.add_argument("--lesson", type=_lesson, help="lesson number, if the notebooks do not say")
    grade.add_argument(
        "--time-limit",
        type=_positive(float),
        default=DEFAULT_TIME_LIMIT,
        help=f"seconds per exercise (default {DEFAULT_TIME_LIMIT:g})",
    )
    grade.add_argument(
        "--memory-limit",
        type=_positive(int),
        default=DEFAULT_MEMORY_LIMIT_MB,
        help=f"MiB per exercise, all its processes (default {DEFAULT_MEMORY_LIMIT_MB})",
    )
    grade.add_argument(
        "--setup-limit",
        type=_positive(float),
        default=DEFAULT_SETUP_LIMIT,
        help=f"seconds for a notebook's top-level definitions (default {DEFAULT_SETUP_LIMIT:g})",
    )
    grade.add_argument(
        "--jobs", type=_positive(int), help="submissions graded at once (default: cores)"
    )
    grade.add_argument("--quiet", action="store_true", help="no progress bar")
    grade.set_defaults(run=_grade)

    course = commands.add_parser("course", help="build or check the student notebooks")
    course.add_argument("action", choices=["build", "check", "execute", "render"])
    course.add_argument("lessons", nargs="*")
    course.add_argument("--root", type=Path, default=Path("."))
    course.set_defaults(run=lambda a: _course(a))

    codegen = commands.add_parser("codegen", help="regenerate urkin/_generated")
    codegen.add_argument("--check", action="store_true")
    codegen.set_defaults(run=lambda a: _codegen(a))

    info = commands.add_parser("info", help="list the arms and their DH lengths")
    info.set_defaults(run=_info)

    demo = commands.add_parser(
        "demo", help="jog an arm with buttons in a window, or record a scripted session"
    )
    demo.add_argument("--robot", default="UR3", help="the arm (default UR3; see urkin info)")
    demo.add_argument(
        "--save", type=Path, metavar="FILE.gif", help="record the session to a GIF, no window"
    )
    demo.add_argument(
        "--script",
        help="comma-separated steps: X+, X-, Y+, Y-, Z+, Z-, home, circle, square (with --save "
        f"default {DEMO_SCRIPT!r}; with a window, run before it opens)",
    )
    demo.add_argument(
        "--task",
        choices=["jog", "stack", "hanoi"],
        default="jog",
        help="jog (default); stack: two blocks at a goal you type; hanoi: the Tower of Hanoi",
    )
    demo.add_argument("--blocks", type=int, default=3, help="blocks of --task hanoi (1 … 4)")
    demo.add_argument("--seed", type=int, default=0, help="seed of the planner (tasks)")
    demo.set_defaults(run=_demo)

    args = parser.parse_args(argv)
    return int(args.run(args))


def _course(args: argparse.Namespace) -> int:
    from urkin.course import build

    return build.main([args.action, *args.lessons, "--root", str(args.root)])


def _codegen(args: argparse.Namespace) -> int:
    from urkin import symbolic

    return symbolic.main(["--check"] if args.check else [])


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
