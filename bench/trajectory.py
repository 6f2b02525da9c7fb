"""Benchmark: task-space pose paths, joint trajectories, tracking with its report, minimum time.

    python bench/trajectory.py

Prints markdown tables with ratios measured in the same run.  Peers, each run to the same
verified result as urkin (the outputs are compared before anything is timed):

* Modern Robotics' ``CartesianTrajectory`` (1,000 poses, quintic time scaling): urkin's
  :func:`urkin.trajectory.pose_path` is given the same positions and interpolates the same
  rotation, so both return the same poses — except at the first samples, where the rotation
  still to turn is below 1e-6 rad and Modern Robotics' ``MatrixExp3`` returns the identity
  (its ``NearZero``): the largest difference printed is that, about 7e-7;
* a plain numpy quintic joint trajectory (the textbook formula written out) against
  :func:`urkin.trajectory.joint_trajectory` (checked equal);
* ruckig, jerk-limited: with a very large jerk limit its duration tends to the trapezoid's
  minimum time, which :func:`urkin.trajectory.minimum_time` computes in closed form.

Peers are skipped with a note when not installed (``pip install modern-robotics ruckig``).
Times are the best of several repeats on whatever machine runs this; nothing is asserted.
"""

from __future__ import annotations

import platform
import timeit

import numpy as np

import urkin
from urkin import trajectory as tj
from urkin.transforms import rot_x, rot_z

UR3 = urkin.robot("ur3")


def best(statement, number: int, repeat: int = 5) -> float:
    """Best time per call (s)."""
    return min(timeit.repeat(statement, number=number, repeat=repeat)) / number


def row(*cells) -> str:
    return "| " + " | ".join(str(c) for c in cells) + " |"


def pose_paths() -> list[str]:
    lines = [
        "",
        "## A Cartesian pose path of 1,000 samples",
        "",
        row("implementation", "time", "ratio to urkin", "largest difference"),
        row("---", "---", "---", "---"),
    ]
    X0 = np.eye(4)
    X0[:3, 3] = [0.3, -0.1, 0.2]
    X1 = np.eye(4)
    X1[:3, :3] = rot_z(1.2) @ rot_x(0.7)
    X1[:3, 3] = [0.1, 0.35, 0.45]
    n, Tf = 1000, 2.0
    s = tj.time_scaling("quintic", Tf)(np.linspace(0, Tf, n))[0]
    points = X0[:3, 3] + s[:, None] * (X1[:3, 3] - X0[:3, 3])
    ours = tj.pose_path(points, X0[:3, :3], X1[:3, :3])
    t_ours = best(lambda: tj.pose_path(points, X0[:3, :3], X1[:3, :3]), 50)
    lines.append(row("urkin.trajectory.pose_path", f"{t_ours * 1e3:.2f} ms", "1.0", "—"))
    try:
        import modern_robotics as mr
    except ImportError:
        lines.append(row("Modern Robotics CartesianTrajectory", "not installed", "", ""))
        return lines
    theirs = np.array(mr.CartesianTrajectory(X0, X1, Tf, n, 5))
    gap = np.abs(theirs - ours).max()
    t_theirs = best(lambda: mr.CartesianTrajectory(X0, X1, Tf, n, 5), 3)
    lines.append(
        row(
            "Modern Robotics CartesianTrajectory",
            f"{t_theirs * 1e3:.1f} ms",
            f"{t_theirs / t_ours:.1f}",
            f"{gap:.1e}",
        )
    )
    return lines


def joint_trajectories() -> list[str]:
    lines = [
        "",
        "## A quintic joint trajectory of 1,000 samples (6 joints)",
        "",
        row("implementation", "time", "ratio to plain numpy"),
        row("---", "---", "---"),
    ]
    q0 = np.array([0.3, -1.2, 1.4, -0.6, 1.1, 0.5])
    q1 = np.array([-0.8, -0.4, 2.0, -1.9, 0.3, 2.2])
    T = 3.0

    def plain():
        t = np.linspace(0, T, 1000)
        tau = t / T
        s = 10 * tau**3 - 15 * tau**4 + 6 * tau**5
        sd = (30 * tau**2 - 60 * tau**3 + 30 * tau**4) / T
        sdd = (60 * tau - 180 * tau**2 + 120 * tau**3) / T**2
        d = q1 - q0
        return q0 + s[:, None] * d, sd[:, None] * d, sdd[:, None] * d

    scaling = tj.time_scaling("quintic", T)
    ours = tj.joint_trajectory(q0, q1, scaling, samples=1000)
    q, qd, qdd = plain()
    gap = max(np.abs(ours.q - q).max(), np.abs(ours.qd - qd).max(), np.abs(ours.qdd - qdd).max())
    t_plain = best(plain, 500)
    t_ours = best(lambda: tj.joint_trajectory(q0, q1, scaling, samples=1000), 500)
    lines.append(row("plain numpy (textbook quintic)", f"{t_plain * 1e6:.0f} µs", "1.0"))
    lines.append(
        row(
            f"urkin.trajectory.joint_trajectory (same values to {gap:.0e})",
            f"{t_ours * 1e6:.0f} µs",
            f"{t_ours / t_plain:.2f}",
        )
    )
    return lines


def tracking() -> list[str]:
    poses = tj.pose_path(tj.circle((0.25, 0.1, 0.3), 0.1, plane="yz"))
    solutions = urkin.ik_analytic(UR3, poses[0])
    q0 = solutions[int(np.argmax(urkin.fk_frames(UR3, solutions)[:, 3, 2, 3]))]  # elbow up
    result = tj.track(UR3, poses, q0)
    assert result.ok.all() and result.report.position_error[0] < 1e-9
    t = best(lambda: tj.track(UR3, poses, q0), 20)
    return [
        "",
        "## Seed 000's circle at 1 mm, tracked with its report (UR3)",
        "",
        row("samples", "time", "largest pose error", "branch flips"),
        row("---", "---", "---", "---"),
        row(
            len(poses),
            f"{t * 1e3:.1f} ms",
            f"{max(result.report.position_error[0], result.report.orientation_error[0]):.0e}",
            sum(len(v) for v in result.report.branch_flips.values()),
        ),
    ]


def minimum_times() -> list[str]:
    lines = ["", "## Trapezoid minimum time against ruckig with a huge jerk limit", ""]
    try:
        from ruckig import InputParameter, Result, Ruckig, Trajectory
    except ImportError:
        return [*lines, "ruckig is not installed: skipped"]
    lines += [
        row(
            "jerk limit",
            "largest |T_urkin − T_ruckig| over 200 moves",
            "largest |T_urkin − T_ruckig| / (a_max / jerk)",
        ),
        row("---", "---", "---"),
    ]
    rng = np.random.default_rng(0)
    # distances (rad), speed limits (rad/s) and acceleration limits (rad/s²) of a UR joint's
    # order: URScript's movej defaults to 1.4 rad/s², its speed limits are π to 2π rad/s
    moves = [
        (rng.uniform(0.05, 3.0), rng.uniform(0.3, 3.0), rng.uniform(0.5, 10.0)) for _ in range(200)
    ]
    for jerk in (1e3, 1e5, 1e7):
        gap = relative = 0.0  # a jerk-limited ramp to a_max costs a_max / jerk more time
        for distance, v_max, a_max in moves:
            ours = tj.minimum_time("trapezoid", [distance], v_max, a_max).T
            inp = InputParameter(1)
            inp.current_position, inp.target_position = [0.0], [distance]
            inp.max_velocity, inp.max_acceleration, inp.max_jerk = [v_max], [a_max], [jerk]
            trajectory = Trajectory(1)
            assert Ruckig(1).calculate(inp, trajectory) == Result.Working
            gap = max(gap, abs(ours - trajectory.duration))
            relative = max(relative, abs(ours - trajectory.duration) / (a_max / jerk))
        lines.append(row(f"{jerk:.0e}", f"{gap:.3e} s", f"{relative:.3f}"))
    return lines


def main() -> None:
    print(
        f"# urkin.trajectory benchmark ({platform.processor() or platform.machine()}, "
        f"Python {platform.python_version()}, numpy {np.__version__})"
    )
    for part in (pose_paths, joint_trajectories, tracking, minimum_times):
        print("\n".join(part()))


if __name__ == "__main__":
    main()
