# %% [markdown]
# # Lesson 05 — Newton–Raphson inverse kinematics
#
# Forward kinematics answers "where is the flange for these joint angles?". A robot is
# usually asked the opposite: "put the tool *there* — which joint angles do that?" This is
# **inverse kinematics** (IK). For a UR arm it has a closed-form answer (a later lesson), but
# the method almost every robotics library reaches for first is numerical: start from a
# guess, see how far off the flange is, use the Jacobian of lesson 04 to work out a
# correction, and repeat. That is **Newton–Raphson**, and both seed reports with an IK solver
# (000 on a UR3, 002 on a UR5) use it.
#
# This lesson derives the Newton–Raphson step from the Jacobian, with the pseudo-inverse and
# a step limit; finds out why seed 002's square came out wrong (it was not its initial
# guess); spends the three joints a position-only task leaves free on a secondary objective,
# in the Jacobian's null space; measures how far from a solution the method still finds one;
# takes apart seed 000's start at "home", a triple singularity with an orientation error
# that reads zero when the tool is half a turn away; and ends by following a path the way a
# controller must, keeping the arm where it was when a point fails.
#
# **What you will be able to do**
#
# * write position-only Newton–Raphson IK with a step limit and wrapped angles
#   (exercise 5.1);
# * write the 6-vector error between two poses with the log map, right at and near a half
#   turn where the seeds' cross-product error goes blind (exercise 5.2);
# * write full-pose Newton–Raphson IK on top of that error, with separate position and
#   orientation tolerances (exercise 5.3);
# * measure the order of convergence of an iteration from its errors, and tell quadratic
#   from linear — Newton's method near and away from a singular solution, a gradient method
#   (exercise 5.4);
# * spend an arm's spare joints on a secondary objective with a null-space projector, without
#   disturbing the task (exercise 5.5);
# * follow a path of positions with warm starts, checking each answer with forward kinematics
#   and leaving the arm where it was when a point fails (exercise 5.6).
#
# **Time:** about 3 hours. **You need:** lesson 01 (the log map; the cross-product error
# and its blind spot at 180°), lesson 02 (forward kinematics; seed 002's position formula)
# and lesson 04 (the geometric Jacobian $[v;\ \omega]$, singularities).

# %%
import matplotlib.pyplot as plt
import numpy as np

import urkin
import urkin.kinematics
import urkin.plot
from urkin.course import below, check
from urkin.course.seeds import SEED002_ARM, seed002_jacobian, seed002_position
from urkin.course.seeds import SEED002_SHIFT as SHIFT
from urkin.numerical_ik import orientation_error
from urkin.transforms import make_transform, rotation_angle

np.set_printoptions(precision=4, suppress=True)


def wrapped(q):
    """Joint angles wrapped into [−π, π): the same arm pose, without extra turns."""
    return (np.asarray(q, dtype=float) + np.pi) % (2.0 * np.pi) - np.pi


# %% [markdown]
# `urkin.ik` is urkin's numerical IK solver; the demonstrations below use it, and the
# plain functions `urkin.fk`, `urkin.jacobian` and `urkin.numerical_ik.orientation_error`,
# never the functions you write. None of this lesson's exercise names clashes with urkin's.
#
# ## 1. Inverse kinematics as root finding
#
# Write $x(q)$ for the pose of the flange at the joint angles $q$ and $x^\*$ for the target.
# IK asks for a root of the **error** $e(q) = x^\* - x(q)$: six equations (three for the
# position, three for the orientation) in six unknowns. In general they have several
# solutions (up to eight for a UR arm reaching a full pose), exactly one, or none.
#
# **Newton–Raphson** replaces the hard, nonlinear problem by an easy, linear one. Near the
# current guess $q$, lesson 04's Jacobian predicts how the flange moves,
# $x(q + \Delta q) \approx x(q) + J(q)\,\Delta q$, so the error after a step $\Delta q$ is
# about $e(q) - J(q)\,\Delta q$. Ask for that to be zero:
#
# $$J(q)\,\Delta q = e(q), \qquad q \leftarrow q + \Delta q .$$
#
# The prediction is not exact — the arm moves on arcs, not straight lines — so the new error
# is not zero, but it is small, and the recipe is simply repeated: *linearise, solve, repeat*.
#
# **Why the pseudo-inverse.** For a full pose $J$ is 6 × 6 and $\Delta q = J^{-1} e$ would
# do — until $J$ is singular (lesson 04), where $J^{-1}$ does not exist. For the position
# alone $J$ is 3 × 6 and has no inverse at all: three equations, six unknowns, infinitely many
# answers. The **Moore–Penrose pseudo-inverse** $J^+$ covers every case. Computed from the
# singular value decomposition $J = U \Sigma V^\mathsf{T}$, it inverts each singular value
# $\sigma_i$ that is not (numerically) zero and drops the rest; $\Delta q = J^+ e$ is then
#
# * the exact solution when one exists, and among all exact solutions the **shortest** one
#   (the smallest joint motion) — the natural choice for a redundant 3 × 6 problem;
# * the least-squares best step when no exact solution exists (at a singularity, some
#   flange motions are impossible: $J^+$ does what it can and ignores the rest).
#
# `np.linalg.pinv` computes it.
#
# **Why a step limit.** The linear prediction is only good for *small* steps. Near a
# singularity some $\sigma_i$ is tiny and $1/\sigma_i$ huge, so the step can come out at tens
# of radians — several full turns of a joint, far outside the region where the linearisation
# means anything (section 6 meets exactly that). A cheap guard is to keep the step's
# *direction* and shrink its *size* so that no joint moves more than about 1 rad per
# iteration. Far from the solution it costs an iteration or two; near the solution the steps
# are tiny and the limit never acts, so it does not slow the final convergence.
#
# Here is one step, done by hand on a UR3, from starts at distances $\delta$ (radians, all
# joints together) from a known solution. Watch the error that is *left* after the step:

# %%
ur3 = urkin.robot("UR3")
q_solution = np.array([0.4, -1.1, 1.3, -1.5, 1.2, 0.3])
T_goal = urkin.fk(ur3, q_solution)
direction = np.random.default_rng(1).normal(size=6)
direction /= np.linalg.norm(direction)  # a random direction in joint space, length 1

print("distance δ (rad)   |e| before the step   |e| after one step   after / before²")
for delta in (0.2, 0.1, 0.05, 0.025):
    q = q_solution + delta * direction
    T = urkin.fk(ur3, q)
    e = np.r_[T_goal[:3, 3] - T[:3, 3], orientation_error(T[:3, :3], T_goal[:3, :3])]
    step = np.linalg.pinv(urkin.jacobian(ur3, q)) @ e  # solve J Δq = e
    T_new = urkin.fk(ur3, q + step)
    e_new = np.r_[T_goal[:3, 3] - T_new[:3, 3],
                  orientation_error(T_new[:3, :3], T_goal[:3, :3])]
    size, size_new = np.linalg.norm(e), np.linalg.norm(e_new)
    print(f"{delta:14.3f}   {size:19.2e}   {size_new:18.2e}   {size_new / size**2:15.3f}")

# %% [markdown]
# (Here $|e|$ is the length of the 6-vector, metres and radians lumped together: good enough
# to watch a trend, not to decide success — section 3 comes back to this.) Halving the
# distance quarters what one step leaves behind: the leftover error is proportional to the
# *square* of the error before the step. That is **quadratic convergence**, and it is why
# Newton–Raphson is so fast once it is close: an error of 1e-3 becomes about 1e-6, then
# 1e-12. Far away, the square is no longer small, and nothing is promised.
#
# ## 2. The position only: seed 002's square
#
# Seed report 002 moves a UR5's tool tip around a square. It solves for the position alone —
# the three coordinates of the flange, whatever the orientation — with a closed-form $p(q)$
# and a 3 × 6 Jacobian it differentiated by hand (lessons 02 and 04). Its loop starts from a
# guess of 20° on every joint and uses each point's answer as the guess for the next point,
# a **warm start**: neighbouring points of a path have neighbouring solutions, so each solve
# begins close and takes only a few iterations.
#
# Two habits of the report are traps, and this lesson avoids both:
#
# * **Millimetres.** Its lengths are in millimetres and its tolerance is the bare number
#   `1`. Position-only Newton–Raphson happens not to care about the length unit (the error
#   and the Jacobian scale together, the step in radians does not change), which is exactly
#   why the habit survives until it bites: the number `1` silently means "1 mm" and would
#   mean "1 m" in a metre-based library; urkin (and its checks) read lengths in metres, so a
#   millimetre table gives an arm a thousand times too big; and the moment orientation rows
#   (radians) join the position rows, millimetres outweigh them a thousand to one in every
#   step and every norm.
# * **Two degree factors.** It stores each answer in degrees by dividing by 0.0175 and turns
#   it back into radians by multiplying by 0.01744, where both should be π/180 = 0.0174533.
#   Every warm start is therefore its previous answer times 0.01744 / 0.0175 = 0.99657
#   (lesson 00), and the animation draws angles scaled by that factor too.
#
# Here everything is in metres and radians. The arm is the UR5 with the report's own lengths
# in UR's sign convention, `SEED002_ARM` from `urkin.course.seeds`, as in lessons 02 and 04 (its
# numbers differ from UR's UR5 by less than a millimetre); its angles are UR's, and the
# report's are $q^\text{seed} = q^\text{UR} +$ `SHIFT` (`urkin.course.seeds.SEED002_SHIFT`). The
# report does not print its square's corners, so here is one in its spirit: 0.2 m on a side,
# horizontal, sampled every 10 mm rather than every 1 mm (81 points are plenty to see what
# happens).

# %%
side, spacing = 0.2, 0.01  # metres
centre = np.array([0.4, 0.3, 0.2])
corners = centre + 0.5 * side * np.array(
    [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0], [-1, -1, 0]], dtype=float)
fractions = np.arange(round(side / spacing)) / round(side / spacing)
square = np.vstack([corners[k] + fractions[:, None] * (corners[k + 1] - corners[k])
                    for k in range(4)] + [corners[:1]])  # four sides, then back to the start
guess_20 = np.radians(np.full(6, 20.0)) - SHIFT  # 20° on every joint, in the report's angles
p_guess = urkin.fk(SEED002_ARM, guess_20)[:3, 3]
print(f"{len(square)} target points; the first is {square[0]} m")
print(f"the 20° guess puts the flange at {p_guess.round(4)} m, "
      f"{np.linalg.norm(p_guess - square[0]):.2f} m from the first point")

# %% [markdown]
# Now track the square with urkin's plain Newton–Raphson, `urkin.ik(..., method="nr",
# max_restarts=0)`: a 3-vector target means "position only", each solve is warm-started
# from the previous answer, and no random restarts are allowed — if an attempt fails, we
# want to see it.

# %%
q = guess_20
solved, iterations, failures = [], [], 0
for point in square:
    result = urkin.ik(SEED002_ARM, point, q0=q, method="nr", max_restarts=0)
    failures += not result.success
    q = result.q  # warm start for the next point
    solved.append(q)
    iterations.append(result.iterations)
solved = np.array(solved)
reached = urkin.fk(SEED002_ARM, solved)[:, :3, 3]
largest_miss = np.linalg.norm(reached - square, axis=1).max()

print(f"failures: {failures} of {len(square)}")
print(f"iterations: {iterations[0]} for the first point (from the 20° guess), "
      f"median {np.median(iterations[1:]):.0f} for the warm-started ones")
print(f"largest distance between the flange and its target: {below(largest_miss, 1e-10)} m")

# %% [markdown]
# Every point is reached within urkin's default tolerance of $10^{-10}$ m — including the
# first, whose guess put the flange more than half a metre away. A far guess costs a few
# iterations, not accuracy.
#
# ### Exercise 5.1 — `ik_position` (4 points)
#
# Write `ik_position(robot, p_target, q0)`: position-only Newton–Raphson. Repeat: compute the
# flange position with `urkin.fk`, the error $e = p^\* - p$ (metres), the 3 × 6 position
# Jacobian (`urkin.kinematics.position_jacobian(robot, q)`, or the top three rows of
# `urkin.jacobian`), and the step $\Delta q = J_v^+ e$. Scale the step down so that no joint
# moves more than `max_step` (1 rad by default), wrap the angles into $[-\pi, \pi)$, and stop
# when $|e|$ is below `tol` ($10^{-12}$ m) or after `max_iterations` (100) steps.
#
# *Checked* (to 1e-8 m, one step to 1e-9 rad; a float32 answer to float32's precision): that
# `urkin.fk` puts the flange on `p_target` for random targets on every UR arm, from starts up
# to 0.4 rad per joint away; that one iteration (`max_iterations=1`, a small `max_step`) moves
# `q` along $J_v^+ e$ with the 3 × 6 position Jacobian — keeping the start's orientation (a
# 6 × 6 Jacobian with a zero orientation error) is a different, and often impossible, problem
# — scaled down as a whole, in the same direction, so that no joint moves more than
# `max_step`; that the angles come back wrapped into $[-\pi, \pi)$ from a start with extra
# whole turns; and that `p_target` and `q0` may be plain lists. The feedback recognises
# millimetres, the ω rows of the Jacobian, a step the wrong way, a clipped or missing step
# limit and a loop that never runs. urkin's IK solvers (`urkin.ik` and all of
# `urkin.numerical_ik`, the closed-form solvers) are hidden while this exercise is graded;
# `urkin.fk`, `urkin.jacobian` and `position_jacobian` are not.

# %%
def ik_position(robot, p_target, q0, tol=1e-12, max_iterations=100, max_step=1.0):
    """Joint angles that put the flange origin at a point: position-only Newton–Raphson.

    Parameters
    ----------
    robot : urkin.Robot
        The arm.
    p_target : array_like, shape (3,)
        Target position of the flange origin in the base frame, metres.
    q0 : array_like, shape (6,)
        Initial guess, radians.
    tol : float
        Stop when the distance to the target is below ``tol`` metres.
    max_iterations : int
        Stop after this many steps in any case.
    max_step : float
        Largest change of any joint in one step, radians (the step is scaled down to it).

    Returns
    -------
    ndarray, shape (6,)
        Joint angles in radians, wrapped into [−π, π). The orientation is whatever the
        iteration arrives at.
    """
    ### BEGIN SOLUTION
    q = np.array(q0, dtype=float)
    p_target = np.asarray(p_target, dtype=float)
    for _ in range(max_iterations):
        e = p_target - urkin.fk(robot, q)[:3, 3]
        if np.linalg.norm(e) < tol:
            break
        step = np.linalg.pinv(urkin.kinematics.position_jacobian(robot, q)) @ e
        largest = np.abs(step).max()
        if largest > max_step:
            step = step * (max_step / largest)  # same direction, shorter
        q = (q + step + np.pi) % (2.0 * np.pi) - np.pi
    return q
    ### END SOLUTION


# %%
check("5.1", ik_position)

# %% [markdown]
# ### What went wrong in seed 002
#
# The report's animation "does not seem to follow the desired square path during the start
# of its journey", and it blames "the vague initial guess of 20 degrees". The run above
# started from that same guess and is exact everywhere, so the guess cannot be the whole
# story. The difference is the *model*. The report's solver does not call a forward
# kinematics that is known to be right: it iterates on its published $p(q)$, which lacks a
# factor $\sin q_5$ on the two $d_6 \cos(q_2+q_3+q_4)$ terms (lesson 02), with the Jacobian
# of that wrong $p$ (lesson 04). The animation, however, draws the *true* DH chain.
#
# Newton–Raphson has no way to notice: it drives the model's error to zero, and the model's
# Jacobian is the exact derivative of the model, so it converges as happily as ever — to
# angles where the *formula* reaches the target. Below, the report's formula and Jacobian
# (`urkin.course.seeds`, as in lessons 02 and 04, in its own angles) drive a small
# Newton–Raphson loop, and the answers are checked with `urkin.fk`.

# %%
def model_position(q):
    """The report's p for UR angles q (metres)."""
    return np.array(seed002_position(q + SHIFT))


def model_jacobian(q):
    """The report's Jacobian for UR angles q (m/rad); a constant shift leaves it unchanged."""
    return np.array(seed002_jacobian(q + SHIFT), dtype=float)


def newton_on_model(position, jacobian, p_target, q0, tol=1e-10, max_step=1.0,
                    max_iterations=100):
    """Position-only Newton–Raphson on a *model* of the arm: position(q) and jacobian(q).

    Stops when every coordinate of p_target − position(q) is within tol (metres), the test
    seed 002 uses. Returns the joint angles (not wrapped) and the number of iterations.
    """
    q = np.array(q0, dtype=float)
    for iteration in range(max_iterations):
        error = p_target - position(q)
        if np.abs(error).max() <= tol:
            return q, iteration
        step = np.linalg.pinv(jacobian(q)) @ error
        q = q + step * min(1.0, max_step / np.abs(step).max())
    return q, max_iterations


def seed002_miss(q):
    """Where lesson 02's error formula says the true flange is off: d6 |cos q234| (1 − sin q5)."""
    c234 = np.cos(q[..., 1] + q[..., 2] + q[..., 3])
    return SEED002_ARM.d6 * np.abs(c234) * (1.0 - np.sin(q[..., 4]))


# the same warm-started tracking as before, on the report's model
q = guess_20
on_model = []
for point in square:
    q, _ = newton_on_model(model_position, model_jacobian, point, q)
    on_model.append(q)
on_model = np.array(on_model)
model_gap = np.abs(np.array([model_position(q) for q in on_model]) - square).max()
miss_model = np.linalg.norm(urkin.fk(SEED002_ARM, wrapped(on_model))[:, :3, 3] - square, axis=1)

print(f"the model's own error at its answers: {below(model_gap, 1e-10)} m (converged)")
print(f"the real flange misses its target by {1000 * miss_model.min():.1f} to "
      f"{1000 * miss_model.max():.1f} mm")
print(f"lesson 02's formula d6·|cos(q2+q3+q4)|·(1 − sin q5) predicts the misses within "
      f"{below(np.abs(seed002_miss(on_model) - miss_model).max(), 1e-9)} m")


# %% [markdown]
# Converged, by its own measure, at every point — and 2 to 3 cm off in reality, exactly by
# the amount lesson 02's error formula predicts. How large the miss is depends on *where*
# the solver lands: it vanishes where $\cos(q_2+q_3+q_4) = 0$ or $\sin q_5 = 1$ and reaches
# $2 d_6 = 165$ mm where $|\cos(q_2+q_3+q_4)| = 1$ and $\sin q_5 = -1$.
#
# The loop above has this lesson's step limit and a 0.1 nm tolerance. The report's own loop
# takes unlimited steps, stops at 1 mm per coordinate, passes each answer through its two
# degree factors before using it as the next guess, and its animation draws angles that
# have been through the factors once more. The animation also plots the trace from a list
# whose first entry is never filled in, so the drawn path begins at the base origin,
# (0, 0, 0). Here is that whole pipeline, in metres — once with the report's formula, and
# once with the true kinematics in its place.

# %%
def true_position(q):
    """The flange position of SEED002_ARM by urkin.fk, for UR angles q (metres)."""
    return urkin.fk(SEED002_ARM, wrapped(q))[:3, 3]


def true_jacobian(q):
    """urkin's exact 3 × 6 position Jacobian of SEED002_ARM (m/rad)."""
    return urkin.kinematics.position_jacobian(SEED002_ARM, wrapped(q))


def seed002_pipeline(position, jacobian):
    """Seed 002's tracking as its code runs it, on a given model: solved and drawn UR angles."""
    factor = 0.01744 / 0.0175  # radians → degrees by ÷ 0.0175, degrees → radians by × 0.01744
    guess = np.full(6, 20.0) * 0.0175 - SHIFT  # its "20°", in UR angles
    solved = []
    for point in square:
        q, _ = newton_on_model(position, jacobian, point, guess, tol=1e-3, max_step=np.inf,
                               max_iterations=200)
        solved.append(q)
        guess = (q + SHIFT) * factor - SHIFT  # the factors act on the report's own angles
    solved = np.array(solved)
    return solved, (solved + SHIFT) * factor - SHIFT


def misses_mm(q):
    """Distance from the true flange to each target point of the square, millimetres."""
    return 1000 * np.linalg.norm(urkin.fk(SEED002_ARM, wrapped(q))[:, :3, 3] - square, axis=1)


print("seed 002's pipeline            flange − target (mm)     first point   as drawn (mm)")
for name, model in (("with its published formula", (model_position, model_jacobian)),
                    ("with the true kinematics", (true_position, true_jacobian))):
    solved_angles, drawn_angles = seed002_pipeline(*model)
    solved_mm, drawn_mm = misses_mm(solved_angles), misses_mm(drawn_angles)
    print(f"{name:<28} {solved_mm.min():7.1f} to {solved_mm.max():5.1f}"
          f"        {solved_mm[0]:7.1f}    {drawn_mm.min():6.1f} to {drawn_mm.max():5.1f}")
    if name.startswith("with its"):
        seed_solved, seed_drawn = solved_angles, drawn_angles

# %% [markdown]
# With the true kinematics, the report's own pipeline — its 20° guess, its unlimited steps,
# its 1 mm tolerance, its degree factors — stays within a millimetre of the square, and
# within 3 mm as drawn (the factors' share). With the published formula the flange is more
# than 12 cm off, from the very first point. The figure puts the traces side by side.

# %%
on_formula = urkin.fk(SEED002_ARM, wrapped(on_model))[:, :3, 3]
drawn_trace = urkin.fk(SEED002_ARM, wrapped(seed_drawn))[:, :3, 3]
drawn_trace[0] = 0.0  # the report's trace list starts with an entry it never sets
pipeline = "the report's pipeline"

urkin.plot.square_traces_figure(
    corners,
    [(reached, "urkin.ik, true kinematics (exact)", "tab:blue", "-"),
     (on_formula, "step-limited Newton on the report's formula", "tab:orange", "-"),
     (drawn_trace, f"{pipeline}, as its animation draws it", "tab:purple", "--")],
    [(misses_mm(solved), "urkin.ik, true kinematics", "tab:blue"),
     (misses_mm(on_model), "step-limited Newton on the report's formula", "tab:orange"),
     (misses_mm(seed_solved), f"{pipeline}, solved", "tab:purple")],
    prediction=(1000 * seed002_miss(seed_solved), "prediction d6·|cos(q2+q3+q4)|·(1 − sin q5)"),
    limit=(2000 * SEED002_ARM.d6, f"largest possible: 2·d6 = {2000 * SEED002_ARM.d6:.0f} mm"),
    origin_note="base origin:\nthe drawn trace\nstarts here", square_label="target square",
    top_title=f"top view (the square is at z = {centre[2]:.1f} m)",
    index_label="target point along the square (index, 10 mm apart)",
    title="Seed 002's square on a UR5: solving the published formula, drawing the true arm")
plt.show()

# %% [markdown]
# ### The initial guess picks a branch, not the accuracy
#
# A position-only problem has a whole family of solutions — the orientation is free, so
# there are three joints' worth of freedom left over — and even a full pose has up to
# eight. Which one Newton–Raphson finds depends on where it starts and how it steps. Take
# the first corner of the square and the report's guess, 20 × 0.0175 = 0.35 rad on every
# joint. This lesson's loop (steps limited to 1 rad) and the report's loop (unlimited steps)
# start from that same guess and end with the wrist bent opposite ways:

# %%
first = square[0]
guess_report = np.full(6, 20.0) * 0.0175 - SHIFT  # 0.35 rad on every joint, its angles
answers = {}
print("model              loop           q (UR angles, rad)                          "
      "sin q5   miss (mm)")
for model_name, model in (("true kinematics", (true_position, true_jacobian)),
                          ("report's formula", (model_position, model_jacobian))):
    for loop_name, max_step, tol in (("step-limited", 1.0, 1e-10), ("report's", np.inf, 1e-3)):
        q, _ = newton_on_model(*model, first, guess_report, tol=tol, max_step=max_step)
        answers[model_name, loop_name] = q = wrapped(q)
        miss = 1000 * np.linalg.norm(true_position(q) - first)
        angles = " ".join(f"{v:6.2f}" for v in q)
        print(f"{model_name:<18} {loop_name:<14} [{angles}]   {np.sin(q[4]):6.2f}   {miss:8.1f}")

# %%
panels = []
for model_name in ("true kinematics", "report's formula"):
    arms = []
    for loop_name, colour in (("step-limited", "tab:blue"), ("report's", "tab:red")):
        q = answers[model_name, loop_name]
        miss = 1000 * np.linalg.norm(true_position(q) - first)
        arms.append((q, colour, f"{loop_name} loop: flange {miss:.1f} mm from the target"))
    panels.append((f"solved with the {model_name}", arms))
urkin.plot.arms_figure(
    SEED002_ARM, panels, center=(0.2, 0.15, 0.12), half_width=0.3, target=first,
    target_label="target (first corner)", view=(20, -50),
    title="The same 20° guess, two loops, two wrist branches: the formula decides the miss")
plt.show()

# %% [markdown]
# With the true kinematics both answers reach the corner (the report's loop stops within
# its 1 mm tolerance); they are simply different arms — the guess and the step rule chose a
# branch. With the report's formula the same two branches miss by 2 cm and by 13.5 cm,
# because the formula's error depends on $q_5$ and $q_2+q_3+q_4$, which differ between
# branches. (All four arms also put the elbow 9 to 14 cm *below* the plane the robot stands
# on: the solver knows nothing about tables. Choosing a sensible branch is the guess's real
# job.) Try many guesses to make sure the size of the miss is not bad luck:

# %%
rng = np.random.default_rng(2)
guesses = rng.uniform(-np.pi, np.pi, (200, 6))
exact = urkin.ik(SEED002_ARM, np.tile(first, (200, 1)), q0=guesses, method="nr",
                 max_restarts=0)
formula_misses = np.array([
    1000 * np.linalg.norm(true_position(newton_on_model(model_position, model_jacobian,
                                                        first, guess)[0]) - first)
    for guess in guesses
])
print(f"true kinematics:  {int(exact.success.sum())} of 200 random guesses reach the corner "
      f"within 1e-10 m")
print(f"report's formula: misses of {formula_misses.min():.1f} to {formula_misses.max():.1f} "
      f"mm, median {np.median(formula_misses):.1f} mm; over 100 mm for "
      f"{np.mean(formula_misses > 100):.0%} of the guesses")

# %% [markdown]
# So the report had the cause backwards. Its 20° guess is far from the square, but
# Newton–Raphson converges from it in a handful of iterations; the guess only decides which
# branch the solver settles in. The visible miss comes from iterating on a wrong formula
# while drawing the true arm — more than 10 cm for a fifth of all guesses, 13.5 cm for
# the report's own — with a drawn trace that starts at the base and a few millimetres from
# the degree factors on top. The lesson is lesson 02's, in a new place: **a solver is only as
# right as the model it iterates on**, and a model must be checked against an independent
# forward kinematics, not against itself.
#
# ### Three spare joints: motion in the null space
#
# For a position-only target the arm is **redundant**: six joints, three task coordinates.
# $J_v$ is 3 × 6, so at a regular configuration it has a three-dimensional **null space** —
# joint motions $\dot q$ with $J_v \dot q = 0$, which leave the flange's position where it is
# (to first order). The projector onto it is
#
# $$N = I - J_v^{+} J_v, \qquad J_v N = 0,$$
#
# and a Newton step may add any null-space motion without disturbing the task:
#
# $$\Delta q = J_v^{+}\,e + N\,k\,(q_\text{rest} - q).$$
#
# The second term pursues a **secondary objective** with the spare freedom — here, staying
# close to a preferred rest configuration (elbow up, tool down, UR's "ready" posture) with
# gain $k$ — while the first term solves the task. Once the position is reached the steps
# keep sliding the arm along the solution family towards the rest posture, until the part
# of $q_\text{rest} - q$ that the null space can absorb is gone.

# %%
q_rest = np.array([0.0, -np.pi / 2, np.pi / 2, -np.pi / 2, -np.pi / 2, 0.0])
p_far = np.array([0.25, 0.025, 0.1])  # a point the arm must reach, far from q_rest


def ik_position_secondary(robot, p_target, q0, q_rest, gain=0.5, max_iterations=200):
    """Position-only Newton–Raphson that uses the null space to stay near q_rest."""
    q = np.asarray(q0, dtype=float).copy()
    for _ in range(max_iterations):
        e = p_target - urkin.fk(robot, q)[:3, 3]
        J = urkin.kinematics.position_jacobian(robot, q)
        J_plus = np.linalg.pinv(J)
        pull = (np.eye(6) - J_plus @ J) @ wrapped(q_rest - q)  # N (q_rest − q)
        if np.linalg.norm(e) < 1e-10 and np.linalg.norm(pull) < 1e-8:
            break
        step = J_plus @ e + gain * pull
        largest = np.abs(step).max()
        q = q + (step if largest <= 1.0 else step / largest)  # steps limited to 1 rad
    return wrapped(q)


rng = np.random.default_rng(8)
J_rest = urkin.kinematics.position_jacobian(SEED002_ARM, q_rest)
N_rest = np.eye(6) - np.linalg.pinv(J_rest) @ J_rest
leak = np.abs(J_rest @ N_rest @ rng.normal(size=(6, 100))).max()
print(f"J_v N z for 100 random z: largest entry {below(leak)} (m/rad): N moves no position")

plain = urkin.ik(SEED002_ARM, p_far, q0=q_rest, method="nr", max_restarts=0)
secondary = ik_position_secondary(SEED002_ARM, p_far, q_rest, q_rest)
print("from q_rest     position miss (m)   elbow height (m)   distance from q_rest (rad)")
for name, q in (("plain NR", wrapped(plain.q)), ("with N k (q_rest − q)", secondary)):
    miss = np.linalg.norm(urkin.fk(SEED002_ARM, q)[:3, 3] - p_far)
    elbow = urkin.fk_frames(SEED002_ARM, q)[2, 2, 3]
    print(f"{name:<22} {below(miss, 1e-10):>12}   {elbow:13.2f}   "
          f"{np.linalg.norm(wrapped(q - q_rest)):18.2f}")

urkin.plot.arms_figure(
    SEED002_ARM,
    [("one target, two answers", [
        (q_rest, "0.7", "q_rest: the preferred posture (the start)"),
        (wrapped(plain.q), "tab:red", "plain Newton–Raphson"),
        (secondary, "tab:blue", "with the null-space pull towards q_rest")])],
    center=(0.0, 0.0, 0.25), half_width=0.45, target=p_far, target_label="the target",
    view=(18, -60), size=7.5)
plt.show()

# %% [markdown]
# Both answers put the flange on the target; they differ only by motion in the null space.
# Plain Newton–Raphson takes whichever solution its steps happen to reach — here one with the
# elbow below the plane the robot stands on. The null-space term spends the three spare
# joints on the secondary objective and ends with the elbow up, much nearer the rest
# posture. The same idea keeps joints away from their limits, or from singularities (pull
# along the gradient of manipulability), and is how redundant robots — seven-joint arms,
# or any arm on a task with fewer than six coordinates — are controlled.
#
# ## 3. The full pose: seed 000's error vector
#
# For a full pose the error needs an orientation part too. The position part is as before,
# $e_p = p^\* - p$ (metres). For the orientation, the rotation still to go is
# $R_e = R^\* R^\mathsf{T}$: applied on the left of the current $R$, it gives the target,
# $R_e R = R^\*$, and it is expressed in the base frame. Its rotation vector (lesson 01's log
# map) is the orientation error:
#
# $$e = \begin{bmatrix} e_p \\ e_o \end{bmatrix}
#     = \begin{bmatrix} p^\* - p \\ \log(R^\* R^\mathsf{T}) \end{bmatrix}
#     = \begin{bmatrix} p^\* - p \\ \varphi\, k \end{bmatrix},$$
#
# where $\varphi \in [0, \pi]$ is the angle and $k$ the unit axis of $R_e$. Three choices in
# this formula must match the Jacobian, or Newton's step points the wrong way:
#
# * **position first**, because the geometric Jacobian's rows are $[v;\ \omega]$;
# * **the base frame**, because its $\omega$ rows are in base coordinates. The tool-frame
#   error $\log(R^\mathsf{T} R^\*)$ has the same length but is the same vector seen from the
#   tool, and pairs with a body Jacobian instead;
# * **target minus current**, so that $J\,\Delta q = e$ moves *towards* the target.
#
# Seed 000 uses the cross-product error $\tfrac12\sum_i n_i \times n_i^\*$ over the columns
# of $R$ and $R^\*$. Lesson 01 showed that it equals $\sin\varphi\; k$: the same direction,
# nearly the same length for small errors, shorter beyond 90°, and *zero* at 180°.
#
# **When to stop.** The position error is in metres and the orientation error in radians,
# and the two are not comparable: whether 1 mm or 1 mrad is "more" depends on the length of
# the tool and on the task. Seed 000 stops when the length of the whole 6-vector
# $\|[e_p;\ e_o]\|$ is below $10^{-3}$, which lets the two trade off against each other
# (a pose 0.9 mm and 0.4 mrad away passes; so would one 0.1 mm and 0.99 mrad away).
# Test them separately, each against its own tolerance, as `urkin.ik` does
# (`tol_position` in metres, `tol_orientation` in radians).
#
# ### Exercise 5.2 — `pose_error` (3 points)
#
# Write `pose_error(T, T_target)`: the 6-vector $[p^\* - p;\ \log(R^\* R^\mathsf{T})]$ for
# two 4 × 4 poses. Write the log map yourself (calling `urkin.transforms.so3_log` or
# `urkin.numerical_ik.orientation_error` earns no points), as lesson 01 built it for
# $R_e = R^\* R^\mathsf{T}$:
#
# * $s = \tfrac12 (R_{e,32} - R_{e,23},\ R_{e,13} - R_{e,31},\ R_{e,21} - R_{e,12})
#   = \sin\varphi\; k$ and $\cos\varphi = (\operatorname{tr} R_e - 1)/2$, so
#   $\varphi = \operatorname{atan2}(|s|, \cos\varphi)$ — accurate at every angle;
# * for $\varphi$ not near $\pi$: $e_o = (\varphi / \sin\varphi)\, s$ (and $e_o = s$ when
#   $\varphi$ is tiny, where the ratio is 1);
# * near $\varphi = \pi$, $s$ has lost the axis; read it from the symmetric part,
#   $\tfrac12 (R_e + R_e^\mathsf{T}) - \cos\varphi\, I = (1 - \cos\varphi)\, k k^\mathsf{T}$: its
#   column with the largest diagonal entry is a multiple of $k$. Normalise it, and pick the
#   sign that agrees with $s$.
#
# *Checked* (to 1e-9; a float32 answer to float32's precision): $[p^\* - p;\ \log(R^\*
# R^\mathsf{T})]$ for random pairs of poses; no turn and a turn of about $10^{-10}$ rad (zero or
# tiny, never 0/0); an exact half turn, which must come out with length π along the turn's
# axis (either sign; to 1e-7 there); and turns a little short of a half turn, where the sign of
# $k$ matters. The feedback recognises the cross-product error, the tool frame, either part
# pointing the wrong way, the (orientation; position) order, degrees and a missing ½. urkin's
# rotation log (`so3_log`, `se3_log`, `rotation_parts`, `twist_parts`) and all of
# `urkin.numerical_ik`, `orientation_error` included, are hidden while this exercise is graded.

# %%
def pose_error(T, T_target):
    """The error that takes a pose to a target pose: position first, then rotation vector.

    Parameters
    ----------
    T : array_like, shape (4, 4)
        Current pose (of the flange, in the base frame); lengths in metres.
    T_target : array_like, shape (4, 4)
        Target pose, in the same frame.

    Returns
    -------
    ndarray, shape (6,)
        ``[p_target − p, φ k]``: the position error (metres), then the rotation vector
        ``log(R_target Rᵀ)`` (radians, base frame, angle φ in [0, π]) of the rotation that
        turns R into R_target.
    """
    ### BEGIN SOLUTION
    T, T_target = np.asarray(T, dtype=float), np.asarray(T_target, dtype=float)
    e_p = T_target[:3, 3] - T[:3, 3]
    R = T_target[:3, :3] @ T[:3, :3].T  # the rotation still to go, in base coordinates
    s = 0.5 * np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])  # sin φ · k
    cos_phi = 0.5 * (np.trace(R) - 1.0)
    phi = np.arctan2(np.linalg.norm(s), cos_phi)
    if phi < 1e-9:
        e_o = s  # φ / sin φ = 1 to within 1e-18
    elif cos_phi > -0.9:
        e_o = (phi / np.sin(phi)) * s
    else:  # near a half turn: the axis from the symmetric part, (1 − cos φ) k kᵀ
        B = 0.5 * (R + R.T) - cos_phi * np.eye(3)
        k = B[:, np.argmax(np.diag(B))]
        k = k / np.linalg.norm(k)
        e_o = phi * (k if k @ s >= 0.0 else -k)
    return np.concatenate([e_p, e_o])
    ### END SOLUTION


# %%
check("5.2", pose_error)

# %% [markdown]
# ### Exercise 5.3 — `ik_newton` (6 points)
#
# Write `ik_newton(robot, T_target, q0)`: full-pose Newton–Raphson. Repeat:
#
# 1. compute the pose with `urkin.fk(robot, q)` and the error with **your** `pose_error`;
# 2. stop when the position error is below `tol` metres **and** the orientation error is
#    below `tol` radians — two separate tests — or after `max_iterations` steps;
# 3. take the step $\Delta q = J^+ e$ with the geometric Jacobian `urkin.jacobian(robot, q)`
#    and `np.linalg.pinv`;
# 4. scale the step down so that no joint moves more than `max_step` radians, add it, and
#    wrap the angles into $[-\pi, \pi)$.
#
# *Checked* (to 1e-8 m and 1e-8 rad, one step to 1e-9 rad; a float32 answer to float32's
# precision): that `urkin.fk` reaches the target on random UR arms from starts 0.1 rad and 0.5
# rad per joint away from a solution; that one iteration (`max_iterations=1`, a small
# `max_step`) moves `q` along $J^+ e$ (with the error of your `pose_error`, or the exact one),
# scaled down as a whole, in the same direction, so that no joint moves more than `max_step`;
# that the angles come back wrapped into $[-\pi, \pi)$ from a start with extra whole turns; and
# that `q0` may be a plain list. The feedback recognises a step the wrong way, the
# Jacobian-transpose step, the cross-product and tool-frame errors, a clipped or missing step
# limit, an ignored `max_iterations`, unwrapped angles and a loop that never runs. urkin's IK
# solvers (`urkin.ik` and all of `urkin.numerical_ik`, `orientation_error` included: use your
# `pose_error`) are hidden while this exercise is graded; `urkin.fk` and `urkin.jacobian` are
# not.

# %%
def ik_newton(robot, T_target, q0, tol=1e-12, max_iterations=100, max_step=1.0):
    """Joint angles that put the flange at a target pose: full-pose Newton–Raphson.

    Parameters
    ----------
    robot : urkin.Robot
        The arm.
    T_target : array_like, shape (4, 4)
        Target pose of the flange in the base frame (metres).
    q0 : array_like, shape (6,)
        Initial guess, radians.
    tol : float
        Stop when the position error is below ``tol`` metres and the orientation error below
        ``tol`` radians.
    max_iterations : int
        Stop after this many steps in any case.
    max_step : float
        Largest change of any joint in one step, radians (the step is scaled down to it).

    Returns
    -------
    ndarray, shape (6,)
        Joint angles in radians, wrapped into [−π, π).
    """
    ### BEGIN SOLUTION
    q = np.array(q0, dtype=float)
    for _ in range(max_iterations):
        e = pose_error(urkin.fk(robot, q), T_target)
        if np.linalg.norm(e[:3]) < tol and np.linalg.norm(e[3:]) < tol:
            break
        step = np.linalg.pinv(urkin.jacobian(robot, q)) @ e
        largest = np.abs(step).max()
        if largest > max_step:
            step = step * (max_step / largest)  # same direction, shorter
        q = (q + step + np.pi) % (2.0 * np.pi) - np.pi
    return q
    ### END SOLUTION


# %%
check("5.3", ik_newton)

# %% [markdown]
# ## 4. Watching it converge
#
# `urkin.ik(..., method="nr")` runs the same iteration as your `ik_newton`, with more
# bookkeeping (restarts, joint limits, a verified result). To look inside it, the function
# below repeats its step for a fixed number of iterations and records the errors; a quick
# comparison confirms that it lands on the same configuration as `urkin.ik`. It also has two
# switches used later: the orientation error's `form` (`"log"` or seed 000's `"cross"`),
# and `frozen`, which keeps the first Jacobian instead of recomputing it every iteration.

# %%
def newton_history(robot, T_target, q0, iterations, form="log", frozen=False, max_step=1.0):
    """Plain full-pose Newton–Raphson for a fixed number of iterations, with its history.

    The step is urkin.ik's "nr" step: pinv(J) e, scaled so that no joint moves more than
    max_step radians, angles wrapped into [−π, π).

    Returns
    -------
    q : ndarray, shape (6,)
        The configuration after the last iteration.
    history : dict of ndarray
        Per iteration 0 … iterations: "position" (m) and "angle" (rad, the true angle
        between the orientations), "seen" (rad, the length of the orientation error the
        solver uses, in the chosen form); and per step: "step" (rad, the largest joint
        change before the limit).
    """
    q = np.array(q0, dtype=float)
    J = urkin.jacobian(robot, q)
    history = {"position": [], "angle": [], "seen": [], "step": []}
    for iteration in range(iterations + 1):
        T = urkin.fk(robot, q)
        e_p = T_target[:3, 3] - T[:3, 3]
        e_o = orientation_error(T[:3, :3], T_target[:3, :3], form)
        history["position"].append(np.linalg.norm(e_p))
        history["angle"].append(np.linalg.norm(orientation_error(T[:3, :3], T_target[:3, :3])))
        history["seen"].append(np.linalg.norm(e_o))
        if iteration == iterations:
            break
        if not frozen:
            J = urkin.jacobian(robot, q)
        step = np.linalg.pinv(J, rcond=1e-12) @ np.r_[e_p, e_o]
        largest = np.abs(step).max()
        history["step"].append(largest)
        q = wrapped(q + step * min(1.0, max_step / max(largest, 1e-300)))
    return q, {name: np.array(values) for name, values in history.items()}


rng = np.random.default_rng(11)
q_true = rng.uniform(-np.pi, np.pi, (4, 6))
q_true[:, 2] = rng.choice([-1, 1], 4) * rng.uniform(0.5, 2.5, 4)  # keep the elbow bent
q_true[:, 4] = rng.choice([-1, 1], 4) * rng.uniform(0.5, 2.5, 4)  # and the wrist
starts = q_true + rng.uniform(-0.5, 0.5, (4, 6))
targets = urkin.fk(ur3, q_true)
results = urkin.ik(ur3, targets, q0=starts, method="nr", max_restarts=0)
same = all(
    np.allclose(newton_history(ur3, targets[i], starts[i], results.iterations[i])[0],
                results.q[i], atol=1e-9)
    for i in range(4)
)
print(f"urkin.ik converged on all four targets: {bool(np.all(results.success))}, in "
      f"{', '.join(str(n) for n in results.iterations)} iterations")
print(f"newton_history reproduces urkin.ik's answers: {same}")

# %% [markdown]
# Now the history of those four solves, iteration by iteration, with a floor at $10^{-17}$
# so that an error of exactly zero still shows on a logarithmic axis. On the right, the
# second target again, but with the Jacobian computed once at the start and then kept — a
# "frozen" Jacobian, which saves work per iteration and is sometimes suggested for that
# reason.

# %%
iterations_shown = 8
floor = 1e-17
histories = [newton_history(ur3, targets[i], starts[i], iterations_shown)[1] for i in range(4)]
_, frozen_history = newton_history(ur3, targets[1], starts[1], 30, frozen=True)
_, fresh_history = newton_history(ur3, targets[1], starts[1], 30)

urkin.plot.convergence_figure(
    histories,
    [(fresh_history, "Jacobian updated every iteration", "tab:orange"),
     (frozen_history, "Jacobian frozen at the start", "tab:brown")],
    floor=floor,
    titles=("Newton–Raphson: the number of correct digits doubles",
            "target 2: a frozen Jacobian converges only linearly"),
    title="Full-pose Newton–Raphson on a UR3, starts up to 0.5 rad per joint away")
plt.show()

history = histories[0]
size = np.hypot(history["position"], history["angle"])  # only to watch a trend
print("target 1: iteration   position (m)   orientation (rad)   |e_k+1| / |e_k|²")
for k in range(5):
    ratio = f"{size[k + 1] / size[k] ** 2:10.3f}" if size[k + 1] > 1e-13 else "  (at round-off)"
    print(f"{k:18d}   {history['position'][k]:12.2e}   {history['angle'][k]:17.2e}   {ratio}")

# %% [markdown]
# On the left the curves bend downwards ever more steeply: each iteration roughly squares
# the error (the ratio $|e_{k+1}| / |e_k|^2$ stays of order one), so 1e-2 becomes 1e-4,
# then 1e-8, then round-off, in five iterations from a start half a radian away per joint.
# This is the signature of Newton's method, and it depends on using the Jacobian *at the
# current point*. With the Jacobian frozen, the error only shrinks by a roughly constant
# factor per iteration — a straight line on this axis, linear convergence — and from the
# first target's start it does not converge at all (try it: change `targets[1]` to
# `targets[0]`). Quadratic convergence also explains why a tight tolerance is nearly free:
# going from 1e-6 to 1e-12 costs one more iteration.
#
# ### Measuring the order of convergence
#
# "Quadratic" and "linear" can be measured instead of read off a plot. A method converges
# with **order** $p$ when, near the solution, $e_{k+1} \approx C\,e_k^{\,p}$ for some
# constant $C$: $p = 2$ is quadratic, $p = 1$ (with $C < 1$, the **rate**) is linear. Take
# logarithms, $\log e_{k+1} = \log C + p \log e_k$, and subtract the same relation one step
# earlier: $C$ drops out, and three consecutive errors give
#
# $$p \approx \frac{\log(e_{k+1} / e_k)}{\log(e_k / e_{k-1})} .$$
#
# (The base of the logarithm cancels.) Use the **last** three errors that are still above
# round-off: the early ones come before the method has settled into its asymptotic
# behaviour, and errors at the level of round-off (here about 1e-16) are noise, not
# convergence.
#
# **Predict first.** Before you run the cells below, write down the order you expect in
# three cases:
#
# 1. Newton–Raphson on the four well-conditioned targets above;
# 2. Newton–Raphson on a target that the UR3 reaches only with its elbow straight,
#    $q_3 = 0$: the solution is singular (lesson 04), the place where the elbow-up and
#    elbow-down solutions meet — think of Newton's method on $x^2 = 0$;
# 3. a **fixed-step gradient method**, $\Delta q = \alpha J^\mathsf{T} e$ with a constant
#    $\alpha$, on the target of section 1: it walks downhill on $\tfrac12 |e|^2$ without
#    solving the linear model.
#
# ### Exercise 5.4 — `convergence_order` (3 points)
#
# Write `convergence_order(errors)`: given the error norms $e_0, e_1, \ldots$ of an
# iterative solver, oldest first (array_like of shape `(n,)` with $n \ge 3$; a plain list
# too), return the estimate $p = \log(e_{k+1} / e_k) / \log(e_k / e_{k-1})$ from the **last
# three** values, as a float. **Bad input:** raise `ValueError` with a message that names
# the argument `errors` when there are fewer than three values, when any value (not only the
# last three) is not positive and finite, or when the last three have $e_k = e_{k-1}$, so
# that the denominator is $\log 1 = 0$. The errors need not decrease: a growing sequence
# gets whatever the formula gives.
#
# *Checked* (to 1e-9, relative): (1 point) sequences with $e_{k+1} = C\,e_k^{\,p}$ exactly,
# for $p$ = 1, 1.5, 2 and 3 and random $C$ and starting values; (1 point) sequences whose
# early errors have another order than the last three, one of them a plain list; (1 point)
# a `ValueError` whose message contains `errors` for each kind of bad input above — and, in
# the same check, a number for a valid sequence, so a function that refuses everything
# earns nothing. The feedback recognises the first three errors, the three before the last,
# the ratio upside down ($1/p$), differences instead of logarithms, the rate
# $e_{k+1}/e_k$, a ratio of ratios and $\log e_{k+1} / \log e_k$.

# %%
def convergence_order(errors):
    """Order of convergence estimated from the last three errors of an iteration.

    Parameters
    ----------
    errors : array_like, shape (n,)
        Error norms e_0, e_1, …, e_(n−1) of successive iterations, oldest first; n ≥ 3,
        every value positive and finite.

    Returns
    -------
    float
        p = log(e_(k+1) / e_k) / log(e_k / e_(k−1)) for the last three values: about 2 for
        quadratic convergence, 1 for linear.

    Raises
    ------
    ValueError
        If there are fewer than three errors, any error is not positive and finite, or the
        last three have e_k = e_(k−1) (a zero denominator).
    """
    ### BEGIN SOLUTION
    e = np.asarray(errors, dtype=float)
    if e.ndim != 1 or e.size < 3:
        raise ValueError(f"errors must hold at least three values; got shape {e.shape}")
    if not np.all(np.isfinite(e) & (e > 0.0)):
        raise ValueError("errors must all be positive and finite")
    before, now, after = e[-3:]
    if now == before:
        raise ValueError("errors: e_k = e_(k−1) in the last three, log(e_k/e_(k−1)) = 0")
    return float(np.log(after / now) / np.log(now / before))
    ### END SOLUTION


# %%
check("5.4", convergence_order)

# %% [markdown]
# **Verify.** The cell below estimates the order in the three cases, each from the last
# three errors above 1e-10 (the full-pose error norm $\sqrt{|e_p|^2 + |e_o|^2}$, as in the
# table above). Case 1 reuses the four histories of the figure; case 2 runs this section's
# `newton_history` on the straight-elbow target; case 3 is a gradient loop of four lines. It
# uses your `convergence_order`, or the formula above while the exercise is not written.

# %%
def order_text(p, low, high):
    """A statement about an estimated order that does not depend on round-off."""
    if low <= p <= high:
        return f"between {low:g} and {high:g}"
    return f"{p:.2f}, not between {low:g} and {high:g}"


try:
    convergence_order([1e-1, 1e-2, 1e-4])
    estimate, source = convergence_order, "your convergence_order"
except NotImplementedError:
    def estimate(errors):
        """The formula of exercise 5.4, standing in until it is written."""
        before, now, after = np.asarray(errors, dtype=float)[-3:]
        return np.log(after / now) / np.log(now / before)

    source = "the formula (exercise 5.4 is not written yet)"
print(f"orders from {source}, each from the last three errors above 1e-10")

# 1. Newton–Raphson, well-conditioned targets: the histories of the figure
for i, history in enumerate(histories):
    errors = np.hypot(history["position"], history["angle"])
    kept = errors[errors > 1e-10]
    print(f"Newton, target {i + 1}: {len(kept)} errors above 1e-10, order "
          f"{order_text(estimate(kept), 1.8, 2.2)}")

# 2. Newton–Raphson on a target reached only with a straight elbow (a singular solution)
q_straight = q_solution.copy()
q_straight[2] = 0.0  # elbow straight: the section 1 solution, stretched
shift = np.random.default_rng(4).normal(size=6)
_, straight_history = newton_history(ur3, urkin.fk(ur3, q_straight),
                                     q_straight + 0.1 * shift / np.linalg.norm(shift), 30)
errors = np.hypot(straight_history["position"], straight_history["angle"])
kept = errors[errors > 1e-10]
print(f"Newton, straight elbow: {len(kept)} errors above 1e-10, order "
      f"{order_text(estimate(kept), 0.9, 1.1)}, rate e_k+1/e_k "
      f"{order_text(kept[-1] / kept[-2], 0.24, 0.26)}")

# 3. a fixed-step gradient method on section 1's target: Δq = α Jᵀ e, α = 0.5
q = q_solution + 0.1 * shift / np.linalg.norm(shift)
gradient_errors = []
for _ in range(300):
    T = urkin.fk(ur3, q)
    e = np.r_[T_goal[:3, 3] - T[:3, 3], orientation_error(T[:3, :3], T_goal[:3, :3])]
    gradient_errors.append(np.linalg.norm(e))
    q = q + 0.5 * urkin.jacobian(ur3, q).T @ e
print(f"gradient, 300 steps: error {gradient_errors[0]:.1f} → {gradient_errors[-1]:.0e}, order "
      f"{order_text(estimate(gradient_errors), 0.9, 1.1)}, rate "
      f"{order_text(gradient_errors[-1] / gradient_errors[-2], 0.99, 1.0)}")

# %% [markdown]
# Newton's method on well-conditioned targets has order 2: the number of correct digits
# doubles. At a singular solution it drops to order 1, rate 1/4 — like Newton on
# $x^2 = 0$, which halves $x$ each step: here the distance $|q_3|$ from the straight elbow
# halves, and the error, which grows as $q_3^2$ there, shrinks by a factor of four. It still
# converges, but needs more than twice as many iterations to get below 1e-10. The gradient
# method is linear as well, with a rate just below 1: after 300 steps it has gained barely
# two digits, because a fixed step must be small enough for the stiffest direction of $J$ and
# is then far too small for the weakest. Two cautions about the estimate itself: it needs
# the asymptotic phase, so the last three errors before round-off, not the first three; and
# linear convergence with a rate near 1 needs many iterations before the ratios settle.

# %% [markdown]
# ### Exercise 5.5 — `null_space_step` (4 points)
#
# Back to section 2's three spare joints. Write the step that solves a task and, with the
# freedom left over, pulls the arm towards a rest posture:
#
# $$\Delta q = J^{+} e + k\,(I - J^{+} J)\,(q_\text{rest} - q)_\text{wrapped}.$$
#
# `null_space_step(J, e, q, q_rest, gain)` takes the task Jacobian `J`, shape `(m, n)` with
# $m \le n$ (3 × 6 for a position-only task, but any such shape), the task error `e`, shape
# `(m,)`, the joint angles `q` and `q_rest`, shape `(n,)` (radians), and the gain $k \ge 0$.
# $J^{+}$ is the pseudo-inverse (`np.linalg.pinv`: $J$ need not be square, and need not have
# full rank). The difference $q_\text{rest} - q$ is wrapped into $(-\pi, \pi]$ first, so
# that a joint a turn away from its rest angle is not pulled round by a full turn. Return
# $\Delta q$, shape `(n,)`. No step limit: the caller clips steps.
#
# *Checked* (to 1e-9) on position Jacobians of random UR arms and on random matrices: the
# step for random errors, postures and gains (2 points); for other shapes, 2 × 6, 3 × 7 and
# a square 6 × 6 (whose null space is only $\{0\}$), and for a rank-deficient $J$ (1 point);
# with joints more than half a turn from their rest angles (1 point). The feedback recognises
# the pull added without the projector, $J^\mathsf{T}$ in place of $J^{+}$, the pull towards
# $q$ instead of $q_\text{rest}$, an unwrapped difference, and the gain applied to the task
# term too.

# %%
def null_space_step(J, e, q, q_rest, gain):
    """One step of a task with a secondary objective in the task's null space.

    Parameters
    ----------
    J : array_like, shape (m, n)
        The task Jacobian (m ≤ n).
    e : array_like, shape (m,)
        The task error.
    q, q_rest : array_like, shape (n,)
        Joint angles now and at rest (rad).
    gain : float
        k ≥ 0, the strength of the pull towards q_rest.

    Returns
    -------
    ndarray, shape (n,)
        Δq = J⁺ e + k (I − J⁺ J) wrap(q_rest − q).
    """
    ### BEGIN SOLUTION
    J = np.asarray(J, dtype=float)
    J_plus = np.linalg.pinv(J)
    pull = urkin.transforms.wrap_angles(np.asarray(q_rest, dtype=float) - np.asarray(q))
    N = np.eye(J.shape[1]) - J_plus @ J
    return J_plus @ np.asarray(e, dtype=float) + gain * N @ pull
    ### END SOLUTION


# %%
check("5.5", null_space_step)

# %% [markdown]
# Verify it on section 2's target: iterate your step (clipped to 1 rad, as there) and compare
# the answer with `ik_position_secondary`'s.

# %%
try:
    q_yours = q_rest.copy()
    for _ in range(200):
        e_yours = p_far - urkin.fk(SEED002_ARM, q_yours)[:3, 3]
        J_yours = urkin.kinematics.position_jacobian(SEED002_ARM, q_yours)
        step = np.asarray(null_space_step(J_yours, e_yours, q_yours, q_rest, 0.5), dtype=float)
        largest = np.abs(step).max()
        q_yours = q_yours + (step if largest <= 1.0 else step / largest)
except NotImplementedError:
    print("exercise 5.5 is not written yet: nothing to compare")
else:
    miss = np.linalg.norm(urkin.fk(SEED002_ARM, q_yours)[:3, 3] - p_far)
    print(f"position miss after 200 steps: {below(miss, 1e-10)} m")
    print("largest difference from ik_position_secondary: "
          f"{below(np.abs(wrapped(q_yours - secondary)).max(), 1e-6)} rad")

# %% [markdown]
# ## 5. How far away may the guess be? Basins of attraction
#
# The promise of quadratic convergence only holds *near* a solution. The set of starting
# points from which Newton–Raphson reaches a solution is its **basin of attraction**, and for
# a 6-joint arm it is a complicated region in six dimensions. One can measure how large it
# is in practice: pick a reachable target from a random configuration $q_\text{true}$,
# start at $q_\text{true} + \delta\, u$ with $u$ a random direction of length 1 in joint
# space, and count successes for growing $\delta$. Each trial is plain Newton–Raphson:
# `urkin.ik(..., method="nr", max_restarts=0)`, with the step limit of 1 rad, giving up
# after 100 iterations or when the error stops falling (no 1 % improvement in 6 iterations).
# A success may find $q_\text{true}$ itself or *another* of the target's solutions; both
# are counted.

# %%
rng = np.random.default_rng(5)
trials = 300
deltas = np.array([0.05, 0.1, 0.2, 0.3, 0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 2.5, 3.0])
q_true = rng.uniform(-np.pi, np.pi, (trials, 6))
directions = rng.normal(size=(trials, 6))
directions /= np.linalg.norm(directions, axis=1, keepdims=True)
targets = urkin.fk(ur3, q_true)

rates = {"log": [], "same": [], "cross": []}
for delta in deltas:
    for form in ("log", "cross"):
        result = urkin.ik(ur3, targets, q0=q_true + delta * directions, method="nr",
                          orientation=form, max_restarts=0)
        rates[form].append(np.mean(result.success))
        if form == "log":
            home_again = np.all(np.abs(wrapped(result.q - q_true)) < 1e-6, axis=1)
            rates["same"].append(np.mean(result.success & home_again))
rates = {name: 100 * np.array(values) for name, values in rates.items()}

fig, ax = plt.subplots(figsize=(9, 5))
ax.plot(deltas, rates["log"], "o-", label="reaches the target (log-map error)")
ax.plot(deltas, rates["same"], "s-", label="… and finds q_true itself, not another solution")
ax.plot(deltas, rates["cross"], "^--", label="reaches the target (seed 000's cross-product error)")
ax.set_xlabel("distance of the start from q_true, δ = |q0 − q_true| (rad)")
ax.set_ylabel(f"share of {trials} random targets (%)")
ax.set_title("Plain Newton–Raphson on a UR3: success against the distance of the initial guess")
ax.set_ylim(0, 105)
ax.grid(True, alpha=0.3)
ax.legend(loc="lower left")
plt.show()

print(" δ (rad)   reached (log)   q_true itself   reached (cross)")
for delta, log_rate, same_rate, cross_rate in zip(deltas, rates["log"], rates["same"],
                                                  rates["cross"]):
    print(f"{delta:8.2f}   {log_rate:12.1f} %   {same_rate:12.1f} %   {cross_rate:14.1f} %")

# %% [markdown]
# Three things to read off:
#
# * **Close starts almost always work**, but not quite always: a few of the random
#   configurations lie near a singularity (the four that misbehave at δ = 0.05 rad have
#   condition numbers in the thousands, against a median of about 50), and there even a
#   start 0.05 rad away can slip to a neighbouring solution or stall.
# * **Success degrades gradually**, not at a sharp edge. At δ = 1 rad (about 0.4 rad per
#   joint) roughly nineteen starts in twenty still reach the target; at δ = 3 rad it is about
#   three in four. There is no distance below which success is guaranteed.
# * **"Success" does not mean "the solution you wanted".** The gap between the first two
#   curves is starts that reached the target with a *different* arm configuration — the
#   elbow or the wrist flipped. For tracking a path this matters as much as converging: a
#   warm start keeps consecutive solutions on one branch only because consecutive targets
#   are close.
#
# The two orientation errors behave alike from close starts — near the solution
# $\sin\varphi \approx \varphi$ — and the cross-product form falls behind only when the start
# is far enough for large orientation errors to occur. Practical solvers therefore combine a
# good guess (a warm start, or a closed-form solution) with **restarts** from random
# configurations when an attempt fails; `urkin.ik` does both by default.
#
# ## 6. Seed 000's start: home, a triple singularity and a false zero
#
# Seed 000's UR3 starts in the "home" configuration $q = (0, -\pi/2, 0, -\pi/2, 0, 0)$, arm
# pointing straight up, and warm-starts every solve from the robot's *current* state: the
# first solve starts from home, each later one from where the previous one ended. Its targets
# have the identity orientation: the square and the circle of its report, both around
# (0.25, 0.1, 0.3) m. For that first solve, two of lesson 04's and lesson 01's findings meet:
#
# * home is singular three times over: the elbow is straight ($\sin q_3 = 0$), the wrist is
#   straight ($\sin q_5 = 0$), and the wrist centre stands above the base, so the shoulder
#   factor vanishes too. $J$ has rank 3;
# * the flange at home is turned by exactly 180° from the identity, and seed 000's
#   cross-product error is blind there.

# %%
home = np.array([0.0, -np.pi / 2, 0.0, -np.pi / 2, 0.0, 0.0])
T_home = urkin.fk(ur3, home)
seed000_targets = {
    "square, first corner": make_transform(np.eye(3), (0.25, 0.025, 0.225)),
    "circle, first point": make_transform(np.eye(3), (0.25, 0.2, 0.3)),
    "centre of both": make_transform(np.eye(3), (0.25, 0.1, 0.3)),
}
T_corner = seed000_targets["square, first corner"]

print("singular families at home:", sorted(urkin.kinematics.singularities(ur3, home)))
sigma = np.linalg.svd(urkin.jacobian(ur3, home), compute_uv=False)
print("singular values of J at home:",
      ", ".join(f"{s:.4f}" if s > 1e-12 else "<1e-12" for s in sigma))
cross = orientation_error(T_home[:3, :3], T_corner[:3, :3], "cross")
log = orientation_error(T_home[:3, :3], T_corner[:3, :3], "log")
print(f"true angle from home to an identity orientation: "
      f"{rotation_angle(T_home[:3, :3], np.eye(3)):.6f} rad")
print(f"cross-product error: {cross.round(6) + 0.0}   (length {below(np.linalg.norm(cross))})")
print(f"log-map error:       {log.round(4) + 0.0}   (length {np.linalg.norm(log):.6f})")

# %% [markdown]
# So the first step seed 000 computes sees *no* orientation error at all, only the position
# error. And the Jacobian it is computed with has three singular values of zero. What does
# the step look like? Below are the first two steps towards the square's first corner,
# with no step limit, as the report takes them: with the plain pseudo-inverse, with the
# damped inverse $J^\mathsf{T}(JJ^\mathsf{T} + \lambda^2 I)^{-1}$, $\lambda = 0.01$, that
# the report actually uses (lesson 06 studies it), and with the log-map error for comparison.

# %%
def first_steps(form, inverse, count=2):
    """The largest joint change of the first `count` unlimited steps from home (rad)."""
    q, sizes, smallest = home.copy(), [], []
    for _ in range(count):
        T = urkin.fk(ur3, q)
        e = np.r_[T_corner[:3, 3] - T[:3, 3],
                  orientation_error(T[:3, :3], T_corner[:3, :3], form)]
        J = urkin.jacobian(ur3, q)
        smallest.append(np.linalg.svd(J, compute_uv=False)[-2:])
        step = inverse(J) @ e
        sizes.append(np.abs(step).max())
        q = q + step
    return sizes, smallest


def pseudo_inverse(J):
    """J⁺, with singular values below 1e-12 × the largest treated as zero (as urkin.ik)."""
    return np.linalg.pinv(J, rcond=1e-12)


def seed000_damped(J):
    """Seed 000's damped inverse Jᵀ (J Jᵀ + λ² I)⁻¹ with λ = 0.01."""
    return J.T @ np.linalg.inv(J @ J.T + 0.01**2 * np.eye(6))


print("error form    inverse                step 1 (rad)   step 2 (rad)")
for form, name, inverse in (("cross", "pseudo-inverse", pseudo_inverse),
                            ("cross", "seed 000's damped", seed000_damped),
                            ("log", "pseudo-inverse", pseudo_inverse)):
    (first_size, second_size), smallest = first_steps(form, inverse)
    print(f"{form:<12}  {name:<20}  {first_size:12.2f}   {second_size:12.2f}")
    if inverse is seed000_damped:  # seed 000's own step: the second one is the huge one
        assert first_size < 0.5 and second_size > 12
print("two smallest singular values of J after the first (cross, pseudo-inverse) step:",
      first_steps("cross", pseudo_inverse)[1][1].round(4))

# %% [markdown]
# The first step is modest — 0.43 rad — because the pseudo-inverse simply drops the three
# directions the arm cannot move in at home. But it leaves the arm *just off* the
# singularities ($q_3 \approx -0.09$, $q_5 \approx -0.08$ rad), where $J$ is invertible
# but two of its singular values are tiny (0.03 and 0.008). The position error still points
# partly along those nearly lost directions, and inverting 0.008 multiplies by more than a
# hundred: the second step turns a joint by 34 rad — five and a half turns. The damping of
# seed 000's inverse tempers it to 13.5 rad, still two full turns in one "small" correction:
# it is the *second* step from home, not the first, that is huge in seed 000's first solve.
# Without a step limit, such a step
# lands anywhere; the wound-up joint angles of the report (one reached −865°) come from
# steps like this one.
#
# Now the whole solve, with urkin's plain Newton–Raphson (step limit 1 rad, no restarts),
# from home to each of seed 000's three targets, with both orientation errors:

# %%
print("target                 error   success   iterations   position (m)   angle (rad)")
for name, target in seed000_targets.items():
    for form in ("cross", "log"):
        result = urkin.ik(ur3, target, q0=home, method="nr", orientation=form,
                          max_restarts=0)
        print(f"{name:<22} {form:<7} {result.success!s:<9} {result.iterations:10d}   "
              f"{below(result.position_error, 1e-10):>12}   "
              f"{below(result.orientation_error, 1e-10):>11}")

# %% [markdown]
# With the log-map error, all three converge in about ten iterations. With the
# cross-product error they converge too, but half as slowly again (14 to 16 iterations):
# urkin judges progress by the *true* angle, which stays near 180° while the solver, seeing
# almost no orientation error, spends its first iterations on the position. The figure
# follows the square's corner, iteration by iteration, with the step limit on.

# %%
iterations_shown = 20
runs = {form: newton_history(ur3, T_corner, home, iterations_shown, form=form)[1]
        for form in ("log", "cross")}

urkin.plot.solver_runs_figure(
    {"log": (runs["log"], "tab:blue"), "cross": (runs["cross"], "tab:red")},
    floor=floor, seen="cross", seen_label="what the solver sees, |sin φ|", step_limit=1.0,
    titles=("position error", "orientation: a 180° error that reads as zero",
            "size of the Newton step before the limit"),
    title="UR3 from home to the square's first corner (identity orientation), plain "
          "Newton–Raphson with a 1 rad step limit")
plt.show()

# %% [markdown]
# The red dotted curve is the whole story of the cross-product error. At home it is
# $10^{-16}$ — the solver believes the orientation is perfect — while the true angle is π.
# The log-map run brings the angle from π to about 1 rad in its first, limited, step and
# converges after about ten iterations. The cross-product run has almost no orientation
# signal, lingers near 180° for seven iterations, asks for a step of 34 rad on the way (the
# step limit is what keeps it sane), and only escapes because 180° is an *unstable* balance:
# any small tilt grows, since $\sin\varphi$ points towards the target once $\varphi$ is a
# little below π. Newton–Raphson with the step limit gets there in the end on this target, a
# few iterations behind the log map; it escapes only because home is a *near* miss.
#
# ### A false zero, exactly
#
# Home is a near miss. Here is an exact one. Take any configuration that reaches a target
# and turn the last joint by half a turn. The flange origin lies on joint 6's axis, so the
# position does not change, and the tool is turned by exactly 180° about its own axis. The
# cross-product error of that pose is zero, and so is the position error: seed 000's test
# $\|[e_p;\ e_o]\| < 10^{-3}$ passes before a single iteration.

# %%
T_target = urkin.fk(ur3, q_solution)  # the target of section 1
q_turned = wrapped(q_solution + np.array([0.0, 0.0, 0.0, 0.0, 0.0, np.pi]))
T_turned = urkin.fk(ur3, q_turned)
e_cross = np.r_[T_target[:3, 3] - T_turned[:3, 3],
                orientation_error(T_turned[:3, :3], T_target[:3, :3], "cross")]
print(f"position error:             {below(np.linalg.norm(e_cross[:3]))} m")
print(f"cross-product error:        {below(np.linalg.norm(e_cross[3:]))}")
print(f"seed 000's test |e| < 1e-3: {np.linalg.norm(e_cross) < 1e-3}")
print(f"true angle to the target:   {rotation_angle(T_turned[:3, :3], T_target[:3, :3]):.6f} rad")
print("\nurkin.ik from the turned configuration:")
for form in ("cross", "log"):
    result = urkin.ik(ur3, T_target, q0=q_turned, method="nr", orientation=form,
                      max_restarts=0)
    print(f"  {form:<5} error: success {result.success!s:<5}  after {result.iterations} "
          f"iterations, position {below(result.position_error, 1e-10)} m, "
          f"angle {below(result.orientation_error, 1e-10)} rad")

# %% [markdown]
# With the cross-product error the Newton step is zero (to round-off), so the solver never
# moves; a solver that trusts its own error measure reports success with the tool turned
# half a turn the wrong way. urkin measures success by the true angle, so it reports the
# failure instead — but with that error it cannot *fix* it. With the log-map error the
# steps turn joint 6 back by π, in four iterations (the step limit cuts the first ones to
# 1 rad).
#
# This is why the course uses the rotation vector $\log(R^\*R^\mathsf{T})$ as the orientation
# error by default and keeps the cross-product form only by name: it is a fine approximation
# for small errors, and wrong in exactly the situation — a large reorientation — where an IK
# solver most needs to know which way to turn.
#
# ## 7. Following a path: warm starts, and what a failure leaves alone
#
# This lesson has tracked paths without stopping at the method. Section 2 followed seed 002's
# square point by point, each solve starting from the answer of the point before — a **warm
# start** — so that the far 20° guess was paid for once, at the first point. Section 5 showed
# why it works: from a close start Newton–Raphson almost always converges, and to the
# solution nearby, so a finely sampled path keeps the arm on one branch. Section 6 met seed
# 000's loop, which warm-starts from the robot's current state as well, and writes every
# answer into that state, whether the solve succeeded or not. A solve that fails has found
# no configuration: its answer is wherever the iteration gave up. Keeping it moves the arm
# there, and the next solve starts from it.
#
# ### Exercise 5.6 — `track_positions` (4 points)
#
# Write `track_positions(robot, points, q0, solve, tol=1e-9)`. `points`, shape `(M, 3)`, are
# the path's target positions of the flange in the base frame (metres), in order; `q0`, shape
# `(6,)`, is the arm's configuration *before* the first point (radians; it need not reach any
# point); `solve(robot, p, q_guess)` is a position-only IK function that returns joint angles,
# shape `(6,)` — the convention of your `ik_position` (exercise 5.1), which you can pass as it
# is. Its answers are not taken on trust: point $k$ counts as reached when `urkin.fk` puts the
# flange within `tol` metres of it. Solve the first point from `q0` and every later one from
# the last *reached* answer. Return `(Q, ok)`: `Q`, shape `(M, 6)`, the arm's configuration
# after each point — the answer where the point is reached, otherwise the previous row (`q0`
# for the first), because the arm stays where it was — and `ok`, shape `(M,)`, booleans: which
# points were reached. A failed answer is thrown away: neither stored nor used as a guess.
#
# *Checked* (rows to 1e-9 rad, angles compared modulo 2π): (2 points) with a stand-in `solve`
# that returns its guess plus a step fixed for each point, on paths whose points lie exactly
# where those steps take the arm from the previous answer — so each answer shows which guess
# it started from, and only warm starts reach the points; (1 point) the same with points out
# of reach (4 m away), among them the first point and two in a row: there `ok` is False and
# the row repeats the previous one, and the next point starts from the last reached answer;
# (1 point) a square of side 3 cm sampled at most 1 mm apart on a UR5, with
# `urkin.ik(robot, p, q0=q_guess, method="nr", max_restarts=0).q` as `solve`: every point
# reached, each row checked with `urkin.fk`. The feedback recognises a cold start from `q0` for
# every point, a failed answer that overwrites the arm's configuration (seed 000's bug) or
# becomes the next guess, every answer taken as reached, an `ok` that is not recorded, and
# two off-by-ones: `q0` taken as the answer for the first point, and each row stored before
# its point is solved.

# %%
def track_positions(robot, points, q0, solve, tol=1e-9):
    """Joint angles that follow a path of positions: warm-started IK, holding on failure.

    Parameters
    ----------
    robot : urkin.Robot
        The arm.
    points : array_like, shape (M, 3)
        Target positions of the flange origin in the base frame, metres, in path order.
    q0 : array_like, shape (6,)
        The arm's joint angles before the first point, radians.
    solve : callable
        ``solve(robot, p, q_guess)``: position-only IK that returns joint angles, shape (6,)
        (``ik_position`` of exercise 5.1, for one).
    tol : float
        A point is reached when ``urkin.fk`` puts the flange within ``tol`` metres of it.

    Returns
    -------
    Q : ndarray, shape (M, 6)
        The joint angles after each point: the solver's answer where the point was reached,
        the previous row (``q0`` before the first) where it was not.
    ok : ndarray of bool, shape (M,)
        Whether each point was reached.
    """
    ### BEGIN SOLUTION
    points = np.asarray(points, dtype=float)
    q = np.array(q0, dtype=float)  # where the arm is: the guess for the next point
    Q = np.empty((len(points), 6))
    ok = np.zeros(len(points), dtype=bool)
    for k, p in enumerate(points):
        answer = np.asarray(solve(robot, p, q.copy()), dtype=float)
        ok[k] = np.linalg.norm(urkin.fk(robot, answer)[:3, 3] - p) <= tol
        if ok[k]:
            q = answer  # a failed answer is thrown away: the arm stays where it was
        Q[k] = q
    return Q, ok
    ### END SOLUTION


# %%
check("5.6", track_positions)

# %% [markdown]
# Verify it on section 2's square: with `urkin.ik` as `solve`, it must give section 2's
# answers. Then spoil one sample the way seed 002 would have written it, in millimetres, and
# solve with section 2's Newton loop on the true kinematics (`newton_on_model`), which does not
# notice that a target is out of reach and returns wherever its 100 iterations ended. The
# last lines run the spoiled path once more with every answer kept, as seed 000's loop keeps
# them (they do not need your function).

# %%
def urkin_solve(robot, p, q_guess):
    """urkin's plain position-only Newton–Raphson, as section 2 used it."""
    return urkin.ik(robot, p, q0=q_guess, method="nr", max_restarts=0).q


def model_solve(robot, p, q_guess):
    """Section 2's Newton loop on the true kinematics of SEED002_ARM (the only arm it
    knows): it returns its last iterate, reached or not."""
    return newton_on_model(true_position, true_jacobian, p, q_guess)[0]


def largest_change(Q):
    """The largest change of any joint between neighbouring rows of Q (rad)."""
    return np.abs(wrapped(np.diff(Q, axis=0))).max()


spoiled = square.copy()
spoiled[30] = 1000 * square[30]  # one sample in millimetres: 616 m away
try:
    Q_square, ok_square = track_positions(SEED002_ARM, square, guess_20, urkin_solve)
    Q_spoiled, ok_spoiled = track_positions(SEED002_ARM, spoiled, guess_20, model_solve)
except NotImplementedError:
    print("exercise 5.6 is not written yet: nothing to compare")
else:
    Q_square, Q_spoiled = np.asarray(Q_square, dtype=float), np.asarray(Q_spoiled, dtype=float)
    print(f"section 2's square: {int(np.sum(ok_square))} of {len(square)} points reached, "
          f"{below(np.abs(wrapped(Q_square - solved)).max(), 1e-9)} rad from section 2's answers")
    missed = np.flatnonzero(~np.asarray(ok_spoiled, dtype=bool)).tolist()
    print(f"one sample in mm, yours: points not reached {missed}, largest joint change "
          f"between rows {below(largest_change(Q_spoiled), 0.1)} rad")

q, kept = guess_20, []
for point in spoiled:  # every answer kept, reached or not
    q = model_solve(SEED002_ARM, point, q)
    kept.append(q)
kept = np.array(kept)
miss_after = np.linalg.norm(urkin.fk(SEED002_ARM, wrapped(kept[31:]))[:, :3, 3]
                            - spoiled[31:], axis=1).max()
apart = np.abs(wrapped(kept[31:] - solved[31:])).max(axis=1)  # largest joint difference
print(f"one sample in mm, every answer kept: largest joint change between rows "
      f"{largest_change(kept):.1f} rad")
print(f"  points 31 to 80: largest miss {below(miss_after, 1e-9)} m; every row more than "
      f"2.5 rad from section 2's answer in some joint: {bool(np.all(apart > 2.5))}")

# %% [markdown]
# Held, the spoiled sample costs one point and nothing else: the arm waits at point 29 and
# goes on to point 31, 20 mm along, without a joint moving more than 0.1 rad between rows.
# Kept, the failed answer swings the arm by more than two radians within one 10 mm step of the
# path, and the next solve, starting from there, converges — to another branch, on which the
# rest of the square is followed. Every later point is reached, so nothing after the bad
# sample gives it away. (`urkin.ik` would have refused this target at once, since it checks
# the arm's reach, and returned its guess; a solver that gives up wherever its iterations
# ended is the common case.) That is why a tracker checks every answer with forward
# kinematics, marks what failed and leaves the arm where it was; `urkin.tracking.track` does
# the same for full poses.
#
# ## Summary
#
# * Newton–Raphson IK: linearise $x(q + \Delta q) \approx x(q) + J\,\Delta q$, solve
#   $J\,\Delta q = e$ with the pseudo-inverse (exact and shortest when possible, least
#   squares when not), repeat. Near a solution it converges quadratically — the number of
#   correct digits doubles every iteration — provided the Jacobian is recomputed at the
#   current point.
# * The order of convergence, $p \approx \log(e_{k+1}/e_k) / \log(e_k/e_{k-1})$ from the last
#   three errors above round-off, measures this: 2 for Newton on a regular solution, 1 at a
#   singular one (rate 1/4 at the straight elbow) and for a fixed-step gradient method.
# * Limit the step (no joint more than about 1 rad) and wrap the angles: near singularities
#   the raw step can be tens of radians.
# * The full-pose error is $[p^\* - p;\ \log(R^\* R^\mathsf{T})]$: position first, base frame,
#   target minus current, to match the geometric Jacobian. Test position (m) and orientation
#   (rad) against separate tolerances, not one mixed norm.
# * Seed 002: a solver is only as right as its model. Its Newton–Raphson converged on a
#   position formula missing a factor $\sin q_5$, and the real arm missed the square by up to
#   13.5 cm (on this lesson's square; up to $2d_6 = 165$ mm in general). The 20° guess only
#   chose the branch — and with it how large the formula's error was.
# * Seed 000: home is triply singular and exactly 180° from its identity targets; the
#   cross-product error $\sin\varphi\, k$ reads zero there. The first step is small, the
#   second is 13.5 rad with the seed's damped inverse (34 rad with the pseudo-inverse); a half
#   turn of joint 6 is an exact false zero.
# * Basins of attraction are large but not whole: plain Newton–Raphson succeeds from most
#   starts within about 1 rad and from fewer and fewer beyond, sometimes on another branch.
#   Good guesses and restarts make it reliable.
# * A path is tracked with warm starts: each point from the last *reached* answer. Check
#   every answer with forward kinematics; where a point fails, the arm stays where it was.
#   Seed 000 kept failed answers: one bad sample is then enough to move the arm onto another
#   branch.
#
# ## What comes next
#
# **Lesson 06** makes the step itself robust near singularities: **damped least squares**
# (seed 000's $J^\mathsf{T}(JJ^\mathsf{T} + \lambda^2 I)^{-1}$, and how to choose
# $\lambda$), **Levenberg–Marquardt**, which adapts the damping as it goes, and the
# matrix-log solver of the product-of-exponentials world, followed by a comparison of all
# the methods.
#
# Before you move on: restart the kernel and run the whole notebook. All six check cells
# should report full marks.
