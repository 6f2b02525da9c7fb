"""Benchmark: grading one lesson of one submission, next to running that notebook.

    python bench/grading.py [RUNS]

For every lesson, the solution notebook is graded with the command an instructor types,
``urkin grade NOTEBOOK --out DIR``, in a fresh process each time (imports included, each
exercise in its own sandboxed process): once with an empty cache (the views of urkin written
and compiled) and ``RUNS`` times warm.  The peer is what notebook graders such as nbgrader and
otter-grader do first: execute the notebook top to bottom in a Jupyter kernel (nbclient), timed
the same way.  The table prints the median wall time of each and their ratio; the budget is
a median of 3 s per lesson on a 2-core machine.
"""

from __future__ import annotations

import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EXECUTE = """
import sys, nbformat
from nbclient import NotebookClient
notebook = nbformat.read(sys.argv[1], as_version=4)
NotebookClient(notebook, timeout=600, kernel_name="python3",
               resources={"metadata": {"path": sys.argv[2]}}).execute()
"""


def wall(command: list[str], env: dict[str, str]) -> float:
    start = time.perf_counter()
    run = subprocess.run(command, cwd=ROOT, env=env, capture_output=True, text=True)
    elapsed = time.perf_counter() - start
    if run.returncode != 0:
        raise SystemExit(f"{' '.join(command)} failed:\n{run.stderr[-2000:]}")
    return elapsed


def main() -> None:
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    notebooks = sorted((ROOT / "solutions").glob("[0-9][0-9]_*.ipynb"))
    print(f"grading one submission (median of {runs} runs, fresh process each)")
    print(
        f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
        f"Python {platform.python_version()}"
    )
    print(f"{'lesson':<32} {'cold':>7} {'urkin grade':>12} {'execute':>9} {'ratio':>7}")
    medians = []
    with tempfile.TemporaryDirectory() as scratch:
        for notebook in notebooks:
            out = Path(scratch) / "grades"
            grade = [
                sys.executable,
                "-m",
                "urkin",
                "grade",
                str(notebook),
                "--out",
                str(out),
                "--quiet",
                "--seed",
                "1",
            ]
            cold_env = {**os.environ, "URKIN_CACHE": str(Path(scratch) / f"cache-{notebook.stem}")}
            cold = wall(grade, cold_env)
            warm = statistics.median(wall(grade, cold_env) for _ in range(runs))
            execute = statistics.median(
                wall(
                    [sys.executable, "-c", EXECUTE, str(notebook), str(notebook.parent)],
                    dict(os.environ),
                )
                for _ in range(max(1, runs // 2))
            )
            medians.append(warm)
            print(
                f"{notebook.stem:<32} {cold:6.2f}s {warm:11.2f}s {execute:8.2f}s "
                f"{warm / execute:6.2f}x"
            )
    print(f"median over the lessons: {statistics.median(medians):.2f} s (budget 3 s)")


if __name__ == "__main__":
    main()
