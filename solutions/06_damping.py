# %% [markdown]
# # Lesson 06 — Damped least squares, Levenberg–Marquardt and the PoE solver
#
# Lesson 05's Newton–Raphson solver is fast when it works: from a good start it gains digits
# quadratically. But it divides by the Jacobian, and near a singularity that means dividing
# by almost nothing. This lesson is about the two standard cures and one alternative error
# measure:
#
# * **damped least squares** (DLS) — a step that can never be longer than a set bound, at the
#   price of accuracy and speed near singular solutions;
# * **Levenberg–Marquardt** (LM) — the same step with a damping that adapts every iteration:
#   heavy where the linear model is poor, vanishing near the solution;
# * the **matrix-log solver** of *Modern Robotics* (`IKinSpace`), which measures the pose
#   error as a twist and pairs it with the matching Jacobian.
#
# You will also audit the solvers of seed reports 000 and 001 — one line that would crash, one
# update with a minus sign where a product belongs, a loop condition the wrong way round —, run
# a race between all four of urkin's methods on 1000 random poses, and finish by writing the
# body-frame twin of the matrix-log solver.
#
# **What you will be able to do**
#
# * compute the damped least-squares and Levenberg–Marquardt steps for a Jacobian of any
#   shape, with matrix products and a solve (exercises 6.1 and 6.2), and recognise
#   element-wise `*` and `**-1` where they do not belong (exercise 6.1);
# * write Levenberg–Marquardt IK that adapts its damping, rejects steps that raise the error
#   and restarts when it is trapped, even from the singular home pose (exercise 6.3);
# * write *Modern Robotics*' matrix-log solver, pairing the space error twist with the space
#   Jacobian (exercise 6.4), and its body-frame twin, pairing the body error twist with the
#   body Jacobian (exercise 6.6);
# * choose the damping that guarantees a bound on the step length, and show that no smaller
#   damping does (exercise 6.5);
# * explain why a fixed damping stalls near singular solutions, and why a fair comparison of
#   IK methods verifies every success by forward kinematics (sections 3 and 7).
#
# **Time:** about 3 hours. **You need:** lesson 03 (twists, the matrix log, the adjoint),
# lesson 04 (Jacobians, the three singular families, singular values) and lesson 05 (the pose
# error and Newton–Raphson IK).

# %%
import time

import matplotlib.pyplot as plt
import numpy as np

import urkin
import urkin.poe
from urkin.course import below, check
from urkin.numerical_ik import orientation_error
from urkin.transforms import inv_transform, rotation_angle, se3_log

np.set_printoptions(precision=4, suppress=True)


def pose_residual(robot, q_now, T_goal):
    """max(position error in m, rotation angle in rad) between fk(robot, q_now) and T_goal."""
    T_now = urkin.fk(robot, q_now)
    return max(np.linalg.norm(T_goal[:3, 3] - T_now[:3, 3]),
               rotation_angle(T_now[:3, :3], T_goal[:3, :3]))


# %% [markdown]
# ## 1. Why damping
#
# Newton–Raphson solves $J\,\Delta q = e$ for the joint step, with the pose error
# $e = [p_\text{target} - p;\ \text{rotation vector of } R_\text{target}R^\mathsf{T}]$ of
# lesson 05. The **singular value decomposition** shows what that costs. Any $J$ can be
# written $J = U\Sigma V^\mathsf{T} = \sum_i \sigma_i\, u_i v_i^\mathsf{T}$ with orthonormal
# output directions $u_i$ (flange motions $[v;\ \omega]$), orthonormal input directions $v_i$
# (joint motions) and singular values $\sigma_1 \ge \dots \ge \sigma_6 \ge 0$. The
# pseudo-inverse step is then
#
# $$\Delta q = J^+ e = \sum_{i:\ \sigma_i > 0} \frac{u_i^\mathsf{T} e}{\sigma_i}\, v_i :$$
#
# the part of the error along each $u_i$ is divided by $\sigma_i$ and becomes a joint motion
# along $v_i$. Lesson 04 showed that near any of the three singular families one $\sigma_i$
# goes to zero. Whatever part of the error points along its $u_i$ — however small — is then
# multiplied by a huge $1/\sigma_i$.
#
# Here is one Newton step for the same small error (1 mm of position and 1 mrad of
# orientation, in fixed random directions) at UR5 configurations ever closer to the elbow
# singularity $q_3 = 0$.

# %%
ur5 = urkin.robot("UR5")


def near_elbow(q3):
    """A UR5 configuration that is regular except for its elbow angle q3 (rad)."""
    return np.array([0.4, -1.0, q3, -1.2, 1.1, 0.3])


rng = np.random.default_rng(6)
directions = rng.normal(size=(2, 3))
e_small = np.r_[1e-3 * directions[0] / np.linalg.norm(directions[0]),
                1e-3 * directions[1] / np.linalg.norm(directions[1])]  # 1 mm and 1 mrad
elbow_angles = [1.0, 1e-1, 1e-2, 1e-3, 1e-4]

print("   q3 (rad)   smallest σ of J   ‖J⁺ e‖ (rad)")
for q3 in elbow_angles:
    J_here = urkin.jacobian(ur5, near_elbow(q3))
    sigma_min = np.linalg.svd(J_here, compute_uv=False)[-1]
    newton = np.linalg.pinv(J_here) @ e_small
    print(f"{q3:10.0e}   {sigma_min:15.2e}   {np.linalg.norm(newton):12.4f}")

# %% [markdown]
# At $q_3 = 1$ rad the step is a few milliradians, as it should be for a millimetre of error.
# Each factor of 10 closer to the singularity shrinks the smallest singular value tenfold and
# makes the step ten times longer: at $q_3 = 10^{-4}$ rad the "correction" for a 1 mm error
# turns joints by tens of radians. The linear model that produced it is valid only for small
# steps, so the step is not just large but useless.
#
# ### The damped least-squares step
#
# Instead of insisting that $J\,\Delta q = e$ hold exactly, ask for a step that makes the
# linearised error small *and* stays short:
#
# $$\Delta q = \arg\min_{\Delta q}\ \|J\,\Delta q - e\|^2 + \lambda^2 \|\Delta q\|^2 .$$
#
# Setting the gradient to zero gives $(J^\mathsf{T}J + \lambda^2 I)\,\Delta q =
# J^\mathsf{T}e$, and section 4 shows that the same step can be written
#
# $$\Delta q = J^\mathsf{T}\,(JJ^\mathsf{T} + \lambda^2 I)^{-1}\, e ,$$
#
# the **damped least-squares** (DLS) step of Wampler and of Nakamura and Hanafusa, with the
# **damping** $\lambda > 0$ (it has the units of $J$: m/rad for the position rows). In the SVD
# picture only the gains change:
#
# $$\Delta q = \sum_i \frac{\sigma_i}{\sigma_i^2 + \lambda^2}\,(u_i^\mathsf{T} e)\, v_i .$$
#
# * For $\sigma_i \gg \lambda$ the gain is almost $1/\sigma_i$: well-conditioned directions
#   are treated as Newton treats them.
# * For $\sigma_i \ll \lambda$ it is about $\sigma_i/\lambda^2$, which goes to *zero*: a
#   direction the arm can hardly move in is mostly given up instead of forced.
# * In between, the gain peaks at $\sigma_i = \lambda$ with the value $1/(2\lambda)$. So
#   $\|\Delta q\| \le \|e\|/(2\lambda)$ for every $J$ whatsoever, singular or not.
#
# The helper below computes the step exactly this way, from the SVD; with `lam=0` it is the
# pseudo-inverse step (singular values below $10^{-12}\sigma_1$ count as zero, as in urkin's
# Newton–Raphson). The demonstrations use it; exercise 6.1 asks for the same step computed
# without an SVD.

# %%
def damped_svd_step(jac, err, lam):
    """Σ σ/(σ² + lam²) (uᵀ err) v over the SVD of jac: the DLS step (lam = 0: pseudo-inverse)."""
    U_, s_, Vt_ = np.linalg.svd(jac, full_matrices=False)
    keep = s_ > 1e-12 * s_[0]
    gain = np.where(keep, s_ / np.where(keep, s_**2 + lam**2, 1.0), 0.0)
    return Vt_.T @ (gain * (U_.T @ err))


sigma_grid = np.logspace(-5, 0.5, 400)  # singular values (units of J)
sigma_near = np.linalg.svd(urkin.jacobian(ur5, near_elbow(1e-2)), compute_uv=False)

fig, ax = plt.subplots(figsize=(8.5, 5.5))
ax.loglog(sigma_grid, 1 / sigma_grid, "k--", linewidth=1.2,
          label="Newton–Raphson: 1/σ (no damping)")
for lam, colour in zip([1e-3, 1e-2, 1e-1], ["tab:blue", "tab:orange", "tab:green"]):
    ax.loglog(sigma_grid, sigma_grid / (sigma_grid**2 + lam**2), color=colour, linewidth=2,
              label=f"DLS, λ = {lam:g}: σ/(σ² + λ²)")
    ax.plot(lam, 1 / (2 * lam), "o", color=colour, markersize=6)
ax.plot([], [], "o", color="0.4", label="peak gain 1/(2λ) at σ = λ")
for index, s in enumerate(sigma_near):
    ax.axvline(s, ymax=0.06, color="tab:red", linewidth=2,
               label="the six σ of the UR5's J at q3 = 0.01 rad" if index == 0 else None)
ax.set_xlabel("singular value σ of J (units of J: m/rad or rad/rad)")
ax.set_ylabel("gain on the error along u (units of 1/J: rad/m or rad/rad)")
ax.set_title("How each step rule scales the error along one singular direction")
ax.set_ylim(1e-1, 1e5)
ax.grid(True, which="major", alpha=0.3)
ax.legend(loc="upper right", fontsize=9)
plt.show()

print("smallest σ at q3 = 0.01 rad:", f"{sigma_near[-1]:.2e}")
for lam in [1e-3, 1e-2, 1e-1]:
    print(f"λ = {lam:<6g} gain there {sigma_near[-1] / (sigma_near[-1]**2 + lam**2):8.3g}"
          f"   (Newton: {1 / sigma_near[-1]:.3g})")

# %% [markdown]
# The red ticks are the singular values of the UR5's Jacobian with the elbow 0.01 rad from
# straight. Five of them sit where the curves nearly agree; the sixth, about 0.0016, is where the
# rules part ways. Newton multiplies the error along that direction by about 600; $\lambda =
# 0.001$ barely changes that (about 440), $\lambda = 0.01$ cuts it to 16 and $\lambda = 0.1$ to
# about 0.17. Damping is a dial between *faithful* (solve the linear model) and *safe* (never take a
# long step), and the same dial applies to every direction at once.
#
# ## 2. Seed 000's two DLS lines
#
# Seed report 000 writes the DLS inverse correctly in its text, $J^\mathsf{T}(JJ^\mathsf{T} +
# \lambda^2 I)^{-1}$ with $\lambda = 0.01$, and its solver contains *two* lines for it. The
# first computes it with the operators `*` and `**-1` and a matrix called `I`; the second uses
# `@`, `np.linalg.inv` and `np.eye(6)`, and is the one whose result the solver uses. Only the
# second is right, and the first cannot even run. Seed 000 starts its UR3 at the home pose
# $(0, -\pi/2, 0, -\pi/2, 0, 0)$, so we use its arm and start.

# %%
ur3 = urkin.robot("UR3")
home = np.array([0.0, -np.pi / 2, 0.0, -np.pi / 2, 0.0, 0.0])
J_home = urkin.jacobian(ur3, home)
T_aim = urkin.fk(ur3, np.array([0.3, -1.2, 0.9, -1.4, 0.6, 0.2]))
T_start = urkin.fk(ur3, home)
e_home = np.r_[T_aim[:3, 3] - T_start[:3, 3], orientation_error(T_start[:3, :3], T_aim[:3, :3])]
lambda_val = 0.01

try:  # the first line, as the report has it
    J_star = J_home.T * (J_home * J_home.T + lambda_val**2 * I) ** -1
except NameError as exc:
    print(f"first line: NameError: {exc}")

# %% [markdown]
# The crash is the lucky outcome. Suppose `I` had been defined, as `np.eye(6)`: then the line
# runs, because for numpy arrays `*` multiplies *entry by entry* and `**-1` takes the
# reciprocal of *each entry*. What comes out is a 6×6 array, but not the DLS inverse.

# %%
I = np.eye(6)  # noqa: E741  (the report's name for the identity)
with np.errstate(divide="ignore", invalid="ignore"):
    elementwise = J_home.T * (J_home * J_home.T + lambda_val**2 * I) ** -1
    step_elementwise = elementwise @ e_home
correct = J_home.T @ np.linalg.inv(J_home @ J_home.T + lambda_val**2 * np.eye(6))
step_home = correct @ e_home

print(f"error at home: {np.linalg.norm(e_home[:3]):.2f} m and {np.linalg.norm(e_home[3:]):.2f}"
      f" rad;  entries of J that are exactly zero: {np.sum(J_home == 0)} of 36")
print(f"first line with I defined: {np.sum(~np.isfinite(elementwise))} of its 36 entries are "
      f"infinite or NaN; its step Δq = {step_elementwise}")
print("second line's step Δq =", step_home)
print(f"second line vs the SVD formula: largest difference "
      f"{below(np.abs(step_home - damped_svd_step(J_home, e_home, lambda_val)).max())}")
print(f"‖Δq‖ = {np.linalg.norm(step_home):.2f} rad, within the bound ‖e‖/(2λ) = "
      f"{np.linalg.norm(e_home) / (2 * lambda_val):.1f} rad")

q_regular = np.array([0.3, -1.1, 1.2, -1.5, 0.8, 0.1])
J_regular = urkin.jacobian(ur3, q_regular)
with np.errstate(divide="ignore", invalid="ignore"):
    infinite = np.sum(~np.isfinite(J_regular.T * (J_regular * J_regular.T
                                                   + lambda_val**2 * I) ** -1))
print(f"\nat a regular configuration: linear part of J's last column {J_regular[:3, 5] + 0.0}, "
      f"{infinite} infinite or NaN entries")
dense = np.random.default_rng(0).normal(size=(6, 6))  # a matrix without zero entries
ew_dense = dense.T * (dense * dense.T + lambda_val**2 * I) ** -1
dls_dense = dense.T @ np.linalg.inv(dense @ dense.T + lambda_val**2 * np.eye(6))
print(f"a random 6×6 matrix without zeros: the first line runs, and differs from the DLS "
      f"inverse by up to {np.abs(ew_dense - dls_dense).max():.1f}")
Jp_regular = J_regular[:3]  # a position-only (3×6) Jacobian
try:
    Jp_regular * Jp_regular.T
except ValueError as exc:
    print(f"a 3×6 position Jacobian: J * J.T fails, ValueError: {str(exc).strip()}")

# %% [markdown]
# For a UR arm the first line could never have worked. The flange origin lies on the joint-6
# axis, so the last column of $J$ has a zero linear part at *every* configuration (lesson 04),
# `J * J.T` has zeros off the diagonal, and `**-1` turns them into infinities: the step is
# NaN, and one NaN step ruins every later iteration. At the home pose more entries are zero
# and the damage is wider. For a matrix without zeros the line runs silently and is simply
# wrong, and for a 3×6 Jacobian `J * J.T` does not even broadcast. In numpy, *matrix* products
# are `@`, and "times the inverse of a matrix" is `np.linalg.solve` (or, less accurately,
# `np.linalg.inv`).
#
# The second line is right, and it agrees with the SVD formula. At home three singular values
# are exactly zero; the DLS gain there is zero too, so those directions of the error are
# simply left alone, and the step — about 1 rad for an error of 0.37 m and 1.83 rad — is far
# inside the bound. Damping keeps a step finite; whether it is a *good* step is another
# matter, which the rest of this lesson is about.
#
# ### Exercise 6.1 — `dls_step` (4 points)
#
# Write `dls_step(J, e, lam)`: the damped least-squares step
# $\Delta q = J^\mathsf{T}(JJ^\mathsf{T} + \lambda^2 I)^{-1} e$ for a Jacobian of **any** shape
# $m \times n$ — the 6×6 full-pose Jacobian, the 3×6 position Jacobian of lesson 05, or
# anything else — so the identity must be $m \times m$. Use matrix products (`@`), and
# `np.linalg.solve(A, e)` to apply $A^{-1}$ to a vector: it is faster and more accurate than
# forming the inverse.
#
# *Checked* (to 1e-9, 1e-6 for a singular $J$; a float32 answer to float32's precision for the
# system's condition number): the formula for random 6×6, 3×6 and other shapes of $J$ with $\lambda$
# between 0.05 and 0.5; a singular $J$ (two dependent rows) with $\lambda = 0.01$; and, reading your
# code once the step is right, that it applies the inverse with a solve — no `np.linalg.inv`, no
# `pinv`, no SVD (nor the SVD helper above). The feedback recognises seed 000's element-wise line,
# $\lambda$ where $\lambda^2$ belongs, an identity of the wrong size, the matrix returned instead of
# the step and the undamped pseudo-inverse. urkin's IK solvers (all of `urkin.numerical_ik`, the
# closed-form solvers) are hidden while this exercise is graded.

# %%
def dls_step(J, e, lam):
    """Damped least-squares joint step.

    Parameters
    ----------
    J : array_like, shape (m, n)
        A Jacobian: m error components, n joints (for a UR arm, 6×6 for a pose error or 3×6
        for a position error).
    e : array_like, shape (m,)
        The error to remove, in the units of J's rows (metres, radians).
    lam : float
        The damping λ > 0, in the units of J.

    Returns
    -------
    ndarray, shape (n,)
        Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e, in radians, with I the m×m identity.
    """
    ### BEGIN SOLUTION
    J = np.asarray(J, dtype=float)
    e = np.asarray(e, dtype=float)
    return J.T @ np.linalg.solve(J @ J.T + lam**2 * np.eye(J.shape[0]), e)
    ### END SOLUTION


# %%
check("6.1", dls_step)

# %% [markdown]
# ## 3. How much damping?
#
# The figure below puts numbers on the dial, near the UR5's elbow singularity, in two ways.
#
# * **Left — one step.** From configurations with the elbow 0.1, 0.01 and 0.001 rad from
#   straight, the length of a single DLS step for the 1 mm / 1 mrad error of section 1, against
#   $\lambda$. The dashed lines are the undamped Newton steps; the grey line is the bound
#   $\|e\|/(2\lambda)$.
# * **Right — where the solver ends.** Targets whose solution *is* one of those three
#   configurations, started 0.2 rad away on every joint, solved with
#   `urkin.ik(..., method="dls", damping=λ, max_restarts=0)`. urkin stops when the pose error
#   is below $10^{-10}$, after 200 iterations, or when six iterations have passed without the
#   error dropping 1 % below its best so far; the plot shows the error it stopped at. The
#   dotted verticals mark the smallest singular value of $J$ at each solution.

# %%
lam_grid = np.logspace(-6, 0, 49)
lam_solve = np.logspace(-5, 0, 21)
offset = np.array([0.2, -0.2, 0.2, -0.2, 0.2, -0.2])  # start = solution + offset (rad)
elbow_cases = [1e-1, 1e-2, 1e-3]
colours = ["tab:blue", "tab:orange", "tab:green"]

fig, (left, right) = plt.subplots(1, 2, figsize=(14, 5.5), constrained_layout=True)
left.loglog(lam_grid, np.linalg.norm(e_small) / (2 * lam_grid), color="0.6", linewidth=1,
            label="bound ‖e‖/(2λ)")
stop_residuals = {}
for q3, colour in zip(elbow_cases, colours):
    q_sol = near_elbow(q3)
    J_sol = urkin.jacobian(ur5, q_sol)
    lengths = [np.linalg.norm(damped_svd_step(J_sol, e_small, lam)) for lam in lam_grid]
    left.loglog(lam_grid, lengths, color=colour, linewidth=2, label=f"DLS, q3 = {q3:g} rad")
    left.axhline(np.linalg.norm(damped_svd_step(J_sol, e_small, 0.0)), color=colour,
                 linestyle="--", linewidth=1, label=f"Newton, q3 = {q3:g} rad")

    T_goal = urkin.fk(ur5, q_sol)
    results = [urkin.ik(ur5, T_goal, q0=q_sol + offset, method="dls", damping=lam,
                        max_restarts=0, max_iterations=200) for lam in lam_solve]
    stop_residuals[q3] = results
    right.loglog(lam_solve, [r.residual for r in results], "o-", color=colour, markersize=4,
                 label=f"solution at q3 = {q3:g} rad")
    right.axvline(np.linalg.svd(J_sol, compute_uv=False)[-1], color=colour, linestyle=":",
                  linewidth=1.5)
right.axhline(1e-10, color="k", linewidth=1, linestyle="--", label="tolerance 1e-10")
right.plot([], [], ":", color="0.3", label="smallest σ of J at the solution")
left.set_xlabel("damping λ (units of J)")
left.set_ylabel("length of one step ‖Δq‖ (rad)")
left.set_title("One step near the elbow singularity (1 mm, 1 mrad error)")
left.set_ylim(1e-3, 1e3)
left.legend(loc="lower left", fontsize=8, ncol=2)
right.set_xlabel("damping λ (units of J)")
right.set_ylabel("pose error where urkin.ik stopped (m or rad)")
right.set_title("Fixed-λ DLS: where the iteration ends")
right.legend(loc="upper left", fontsize=8)
for panel in (left, right):
    panel.grid(True, which="major", alpha=0.3)
fig.suptitle("Damped least squares on a UR5 near its elbow singularity")
plt.show()

print("  q3 (rad)   largest λ that converged   iterations it took   smallest σ at solution")
for q3 in elbow_cases:
    ok = [i for i, r in enumerate(stop_residuals[q3]) if r.success]
    best = max(ok)
    sigma_sol = np.linalg.svd(urkin.jacobian(ur5, near_elbow(q3)), compute_uv=False)[-1]
    print(f"{q3:10g}   {lam_solve[best]:24.1e}   {stop_residuals[q3][best].iterations:18d}"
          f"   {sigma_sol:22.1e}")

# %% [markdown]
# **Left:** for small $\lambda$ the step is Newton's, and Newton's step grows tenfold with each
# tenfold approach to the singularity. Once $\lambda$ passes the smallest singular value, that
# direction's share of the error is damped away and the step drops to the couple of
# milliradians that the five well-conditioned directions need — the same for all three
# configurations, and far inside the grey bound. Only when $\lambda$ approaches the larger
# singular values (0.3 and up) does damping shrink those too, like $1/\lambda^2$: safe, but
# the arm hardly moves.
#
# **Right:** the price. With $\lambda$ below the smallest singular value at the solution, DLS
# converges as Newton does. Up to about three and a half times that value it still converges, with
# more and more iterations; beyond it the solver gives up *short of the tolerance*, with an error
# that grows with $\lambda$ — by $\lambda = 0.1$ it stops up to about 0.35 mm away. And
# the threshold moves with the target: $\lambda = 0.01$, seed 000's choice, is fine for the first
# target and fails the other two. To pick $\lambda$ well you would need to know how singular the
# solution is before you have found it.
#
# Why does the error stop falling? Near the solution the error changes as
# $e_{k+1} \approx e_k - J\,\Delta q_k$, and with the DLS step
# $J\,\Delta q = \sum_i \frac{\sigma_i^2}{\sigma_i^2+\lambda^2}(u_i^\mathsf{T}e)\,u_i$. So the
# component of the error along $u_i$ is multiplied, every iteration, by
#
# $$\frac{\lambda^2}{\sigma_i^2 + \lambda^2} :$$
#
# **linear convergence**, not Newton's quadratic convergence, with a rate close to 1 when the
# solution has a singular value $\sigma_i \lesssim \lambda$. urkin's patience rule (1 % in six
# iterations) gives up when the rate is above about 0.998, that is $0.99^{1/6}$; a solver without
# such a rule just burns its iteration budget. The next figure follows single runs, iteration by
# iteration, for the target with the elbow 0.01 rad from straight. DLS and Newton come from a loop
# over `damped_svd_step` (no patience rule: 300 iterations each); Levenberg–Marquardt, for
# comparison, from `urkin.ik(method="lm")` stopped after 1, 2, 3, … iterations.

# %%
def dls_history(robot, T_goal, q_start, lam, iterations):
    """Pose residual after each of `iterations` DLS steps (lam = 0: Newton), steps ≤ 1 rad."""
    q_now = np.array(q_start, dtype=float)
    history = [pose_residual(robot, q_now, T_goal)]
    for _ in range(iterations):
        T_now = urkin.fk(robot, q_now)
        err = np.r_[T_goal[:3, 3] - T_now[:3, 3],
                    orientation_error(T_now[:3, :3], T_goal[:3, :3])]
        move = damped_svd_step(urkin.jacobian(robot, q_now), err, lam)
        q_now = q_now + move * min(1.0, 1.0 / max(np.abs(move).max(), 1e-300))
        history.append(pose_residual(robot, q_now, T_goal))
    return np.array(history)


def urkin_history(robot, T_goal, q_start, method, iterations):
    """Pose residual of urkin.ik(method) stopped after 0, 1, …, `iterations` iterations."""
    history = []
    for k in range(iterations + 1):
        result = urkin.ik(robot, T_goal, q0=q_start, method=method, max_iterations=k,
                          max_restarts=0)
        history.append(result.residual)
        if result.success:
            break
    return np.array(history)


q_sol = near_elbow(1e-2)
T_goal = urkin.fk(ur5, q_sol)
q_start = q_sol + offset
sigma_sol = np.linalg.svd(urkin.jacobian(ur5, q_sol), compute_uv=False)[-1]

hand = dls_history(ur5, T_goal, q_start, 1e-2, 5)
library = [urkin.ik(ur5, T_goal, q0=q_start, method="dls", damping=1e-2, max_iterations=k,
                    max_restarts=0).residual for k in range(6)]
print(f"hand-written DLS loop vs urkin.ik(method='dls'), first 5 iterations: largest "
      f"difference in the residual {below(np.abs(hand - library).max())}")

runs = {f"DLS, λ = {lam:g}": dls_history(ur5, T_goal, q_start, lam, 300)
        for lam in [1e-3, 1e-2, 1e-1]}
runs["Newton–Raphson (λ = 0)"] = dls_history(ur5, T_goal, q_start, 0.0, 300)
runs["Levenberg–Marquardt (urkin)"] = urkin_history(ur5, T_goal, q_start, "lm", 100)

fig, ax = plt.subplots(figsize=(9, 5.5))
styles = {"DLS, λ = 0.001": ("tab:blue", "-"), "DLS, λ = 0.01": ("tab:orange", "-"),
          "DLS, λ = 0.1": ("tab:green", "-"), "Newton–Raphson (λ = 0)": ("k", "--"),
          "Levenberg–Marquardt (urkin)": ("tab:red", "-")}
for name, history in runs.items():
    colour, line = styles[name]
    done = np.flatnonzero(history < 1e-13)  # drawn until round-off takes over
    shown = history[: done[0] + 1] if done.size else history
    ax.semilogy(shown, line, color=colour, linewidth=2, label=name,
                marker="o" if len(shown) < 40 else None, markersize=3)
rate = 1e-4 / (sigma_sol**2 + 1e-4)
k_guide = np.arange(150, 301)
ax.semilogy(k_guide, 3 * runs["DLS, λ = 0.01"][150] * rate ** (k_guide - 150), ":",
            color="0.3", linewidth=1.5, label=f"slope of the rate λ²/(σ² + λ²) = {rate:.3f}")
ax.axhline(1e-10, color="0.5", linewidth=0.8, linestyle="--", label="tolerance 1e-10")
ax.set_xlabel("iteration")
ax.set_ylabel("pose residual: max(position m, angle rad)")
ax.set_title("UR5, solution 0.01 rad from the elbow singularity, start 0.2 rad away")
ax.set_ylim(1e-16, 3)
ax.legend(loc="lower right", fontsize=9)
ax.grid(True, which="major", alpha=0.3)
plt.show()

for name, history in runs.items():
    reached = np.flatnonzero(history < 1e-10)
    when = f"below 1e-10 after {reached[0]} iterations" if reached.size else \
        f"still {history[-1]:.1e} after {len(history) - 1} iterations"
    print(f"{name:<30} {when}")
tail = runs["DLS, λ = 0.01"]
print(f"λ = 0.01: measured error ratio per iteration over the last 50: "
      f"{(tail[-1] / tail[-51]) ** (1 / 50):.4f}; predicted λ²/(σ² + λ²) = {rate:.4f}")

# %% [markdown]
# The pictures match the algebra. $\lambda = 0.001$ is below the smallest singular value at the
# solution (0.0016) and converges almost like Newton. $\lambda = 0.01$ is down to 0.1 mm within
# eight iterations and then crawls; over the last 150 iterations its error falls along a
# straight line on the log scale — linear convergence, at exactly the predicted rate of 0.974
# per iteration — and after 300 iterations it is still short of $10^{-10}$, which Newton
# reaches in 10. $\lambda = 0.1$ is worse still. Note that Newton–Raphson is *not* the problem
# here: from this start it converges quadratically, because the solution, though close to
# singular, is not singular. Damping protects the steps taken *near* singularities on the way;
# it should not stay on once the iteration is close.
#
# That is exactly what Levenberg–Marquardt arranges.
#
# ## 4. Levenberg–Marquardt
#
# Levenberg (1944) and Marquardt (1963) wrote the damped step with $\mu$ in place of
# $\lambda^2$,
#
# $$\Delta q = (J^\mathsf{T}J + \mu I)^{-1} J^\mathsf{T} e ,$$
#
# and — this is the whole idea — **change $\mu$ every iteration** according to how well the
# last step worked. Try the step. If it lowers the error, keep it and *decrease* $\mu$: the
# linear model was trustworthy, so trust it more. If it does not, throw it away, *increase*
# $\mu$ and try again from the same configuration. Two limits explain why this works:
#
# * $\mu \to 0$: $\Delta q \to (J^\mathsf{T}J)^{-1}J^\mathsf{T}e$, the Gauss–Newton step —
#   Newton–Raphson, with its quadratic convergence near a regular solution;
# * $\mu$ large: $\Delta q \approx J^\mathsf{T}e/\mu$, a short step along $J^\mathsf{T}e$, which
#   is minus the gradient of $\tfrac12\|e\|^2$ — steepest descent, which lowers the error for a
#   small enough step as long as the gradient is not zero.
#
# So LM is damped where the model is poor — near singularities, far from the solution — and
# undamped near the solution, with no $\lambda$ to choose by hand. `urkin.ik(method="lm")`
# (the default) uses Nielsen's refinement of the rule: it compares the actual drop of
# $\|e\|^2$ with the drop the linear model predicted and shrinks $\mu$ more the better they
# agree.
#
# ### The two forms are one step
#
# The LM formula inverts an $n \times n$ matrix, the DLS formula an $m \times m$ one. They give
# the same step when $\mu = \lambda^2$, because of a one-line identity:
#
# $$(J^\mathsf{T}J + \mu I)\,J^\mathsf{T} = J^\mathsf{T}JJ^\mathsf{T} + \mu J^\mathsf{T} =
# J^\mathsf{T}\,(JJ^\mathsf{T} + \mu I).$$
#
# For $\mu > 0$ both brackets are symmetric positive definite, hence invertible; multiply by
# $(J^\mathsf{T}J + \mu I)^{-1}$ on the left and $(JJ^\mathsf{T} + \mu I)^{-1}$ on the right:
#
# $$J^\mathsf{T}(JJ^\mathsf{T} + \mu I)^{-1} = (J^\mathsf{T}J + \mu I)^{-1}J^\mathsf{T}.$$
#
# It holds for every $J$, singular or rectangular. Check it numerically with the triply
# singular UR5 Jacobian at home (rank 3) and with a 3×6 position Jacobian:

# %%
mu_demo = 1e-3
J_singular = urkin.jacobian(ur5, home)
Jp_demo = urkin.position_jacobian(ur5, near_elbow(0.5))
print(f"rank of J at home: {np.linalg.matrix_rank(J_singular, tol=1e-9)}")
for name, J_demo in [("6×6 J at home", J_singular), ("3×6 position J", Jp_demo)]:
    m, n = J_demo.shape
    lm_form = np.linalg.inv(J_demo.T @ J_demo + mu_demo * np.eye(n)) @ J_demo.T
    dls_form = J_demo.T @ np.linalg.inv(J_demo @ J_demo.T + mu_demo * np.eye(m))
    print(f"{name}: (JᵀJ + μI)⁻¹Jᵀ vs Jᵀ(JJᵀ + μI)⁻¹, largest difference "
          f"{below(np.abs(lm_form - dls_form).max())}")

# %% [markdown]
# So every single LM step *is* a DLS step with $\lambda = \sqrt{\mu}$. The difference between
# the two methods is not the formula but the rule around it: DLS keeps $\lambda$ fixed, LM
# adapts $\mu$ and rejects steps that make things worse.
#
# ### Seed 001's "Levenberg–Marquardt"
#
# Seed report 001 solves the UR3's inverse kinematics with the product of exponentials and calls
# its method Levenberg–Marquardt. Its algorithm, read line by line:
#
# 1. **The damping is fixed.** The report adds a constant $\mu I$ to keep the matrix
#    invertible, and never changes $\mu$ or rejects a step. By the identity above that is
#    damped least squares with $\lambda = \sqrt\mu$ — seed 000's method in other clothes — with
#    all of section 3's slow, short-stopping behaviour near singular solutions.
# 2. **The update has a minus sign where a product belongs.** It prints
#    $\dot\theta = (J^\mathsf{T}J + \mu I)^{-1} - J^\mathsf{T}V$. A 6×6 matrix minus a
#    6-vector is not defined in mathematics; numpy *broadcasts* it without complaint and
#    returns a 6×6 array. The intended update is the product $(J^\mathsf{T}J +
#    \mu I)^{-1}J^\mathsf{T}V$, which equals $J^\mathsf{T}(JJ^\mathsf{T} + \mu I)^{-1}V$.
# 3. **The loop condition is inverted.** "while $\|V\| < \epsilon$" runs only while the error
#    is already below the tolerance — that is, never, for any start that needs solving — and
#    returns the initial guess. It should iterate while $\|V\| > \epsilon$.
# 4. **The pseudo-inverse claim is backwards.** The report offers $J^+ = (J^\mathsf{T}J)^{-1}
#    J^\mathsf{T}$ as the formula for a rank-deficient $J$. That formula needs $J^\mathsf{T}J$ to be
#    invertible, which is exactly when $J$ has **full column rank** (independent columns); at a
#    singularity it does not exist. (For a wide $J$ with full row rank — a 3×6 position
#    Jacobian — the formula is $J^\mathsf{T}(JJ^\mathsf{T})^{-1}$ instead; $J^\mathsf{T}J$ is
#    then 6×6 of rank 3 at most, never invertible.)

# %%
S_ur3, _ = urkin.poe.space_screws(ur3)
T_now_ur3 = urkin.fk(ur3, q_regular)
V_s = se3_log(T_aim @ inv_transform(T_now_ur3))  # seed 001's error twist, space frame
J_s = urkin.poe.jacobian_space(S_ur3, q_regular)  # … and the matching space Jacobian
printed = np.linalg.inv(J_s.T @ J_s + mu_demo * np.eye(6)) - J_s.T @ V_s
intended = np.linalg.solve(J_s.T @ J_s + mu_demo * np.eye(6), J_s.T @ V_s)
print(f"printed update (JᵀJ + μI)⁻¹ − JᵀV: shape {printed.shape}, a matrix, not a joint step")
print(f"intended update (JᵀJ + μI)⁻¹ JᵀV: shape {intended.shape}; equals Jᵀ(JJᵀ + μI)⁻¹V: "
      f"{np.allclose(intended, J_s.T @ np.linalg.solve(J_s @ J_s.T + mu_demo * np.eye(6), V_s))}")

tolerance = 1e-6
print(f"\nloop condition as printed: ‖V‖ = {np.linalg.norm(V_s):.3f} < {tolerance:g} is "
      f"{bool(np.linalg.norm(V_s) < tolerance)}: the loop body never runs")

print()
for name, q_here in [("regular q", q_regular), ("home", home)]:
    J_here = urkin.poe.jacobian_space(S_ur3, q_here)
    normal = J_here.T @ J_here
    rank = np.linalg.matrix_rank(normal, tol=1e-9)
    pinv_step = np.linalg.pinv(J_here, rcond=1e-12) @ V_s
    try:
        with np.errstate(all="ignore"):
            via_normal = np.linalg.solve(normal, J_here.T @ V_s)
        agrees = np.allclose(via_normal, pinv_step, atol=1e-9)
    except np.linalg.LinAlgError:  # numpy may notice that JᵀJ is singular, or may not
        agrees = False
    outcome = ("(JᵀJ)⁻¹JᵀV equals J⁺V" if agrees
               else "(JᵀJ)⁻¹JᵀV fails: solve raises or returns round-off")
    print(f"UR3 space Jacobian at {name:<9}: rank of JᵀJ = {rank}; {outcome}")

# %% [markdown]
# With full rank the normal-equation formula is the pseudo-inverse; at home, where the
# Jacobian has rank 3, $J^\mathsf{T}J$ is singular and the formula has nothing to offer — which
# is exactly where the report wanted to use it. `np.linalg.pinv` (via the SVD) and the damped
# forms work at any rank.
#
# ### Exercise 6.2 — `lm_step` (4 points)
#
# Write `lm_step(J, e, mu)`: the Levenberg–Marquardt step $\Delta q = (J^\mathsf{T}J +
# \mu I)^{-1}J^\mathsf{T}e$ for a Jacobian of any shape $m \times n$ (here the identity is
# $n \times n$). Solve the $n \times n$ system with `np.linalg.solve` rather than forming an
# inverse.
#
# *Checked* (to 1e-9, 1e-6 for a singular $J$; a float32 answer to float32's precision for the
# system's condition number): the formula for random 6×6, 3×6 and other shapes of $J$ with $\mu$
# between $10^{-4}$ and 1; the identity you just saw — with a singular $J$ and $\mu = 10^{-3}$ your
# step must equal the DLS step with $\lambda^2 = \mu$; and, reading your code once the step is right
# (and that of any function of yours it calls, such as `dls_step`), that it solves rather than
# inverts: no `np.linalg.inv` or `pinv`. The feedback recognises $\mu^2$ for $\mu$, $\mu$ added to
# every entry instead of the diagonal, a missing $J^\mathsf{T}$, an identity of the wrong size and
# seed 001's printed minus sign. urkin's IK solvers (all of `urkin.numerical_ik`, the closed-form
# solvers) are hidden while this exercise is graded.

# %%
def lm_step(J, e, mu):
    """Levenberg–Marquardt joint step.

    Parameters
    ----------
    J : array_like, shape (m, n)
        A Jacobian: m error components, n joints.
    e : array_like, shape (m,)
        The error to remove (metres, radians).
    mu : float
        The damping μ > 0, in the units of JᵀJ (μ plays the role of λ² in DLS).

    Returns
    -------
    ndarray, shape (n,)
        Δq = (JᵀJ + μ I)⁻¹ Jᵀ e, in radians, with I the n×n identity.
    """
    ### BEGIN SOLUTION
    J = np.asarray(J, dtype=float)
    e = np.asarray(e, dtype=float)
    return np.linalg.solve(J.T @ J + mu * np.eye(J.shape[1]), J.T @ e)
    ### END SOLUTION


# %%
check("6.2", lm_step)

# %% [markdown]
# ### What adaptive damping cannot fix: traps
#
# LM accepts only steps that lower the error, so its error never increases. That makes it
# robust, and it also means it can get *stuck*: at a configuration where the gradient
# $J^\mathsf{T}e$ vanishes although $e$ does not, no small step lowers the error, $\mu$ grows
# without bound, and the steps shrink to nothing. Such points exist for UR arms, and the
# singular families are where they like to be. Picture the arm stretched straight towards a
# target slightly closer than its full reach: bending the elbow either way moves the wrist
# *sideways* to first order, while the error points *along* the arm, so the gradient has no
# component that helps. The way out — bend the elbow — shows up only at second order, which
# $J$ does not see.
#
# Starting at the home pose, with the elbow straight and the wrist singular, invites this.
# Count it with urkin's own LM, without and with restarts, on 500 targets within 0.7 rad of
# home per joint (their solutions kept away from the elbow and wrist singularities):

# %%
rng = np.random.default_rng(7)
q_targets = home + rng.uniform(-0.7, 0.7, (2000, 6))
regular = (np.abs(np.sin(q_targets[:, 2])) > 0.2) & (np.abs(np.sin(q_targets[:, 4])) > 0.2)
q_targets = q_targets[regular][:500]
T_targets = urkin.fk(ur5, q_targets)

no_restarts = urkin.ik(ur5, T_targets, q0=home, method="lm", max_restarts=0)
with_restarts = urkin.ik(ur5, T_targets, q0=home, method="lm")
stuck = np.flatnonzero(~no_restarts.success)
q_stuck = no_restarts.q[stuck]
near_family = np.minimum(np.abs(np.sin(q_stuck[:, 2])), np.abs(np.sin(q_stuck[:, 4])))
print(f"LM from home, no restarts:   {no_restarts.success.sum()} of 500 reached")
print(f"LM from home, with restarts: {with_restarts.success.sum()} of 500 reached "
      f"(restarts used by the {len(stuck)} others: {with_restarts.restarts[stuck].tolist()})")
print(f"of the {len(stuck)} stuck runs, {np.sum(near_family < 0.05)} stopped with the elbow or "
      f"the wrist within 0.05 of straight (|sin q3| or |sin q5| < 0.05)")
print(f"their remaining pose errors: {no_restarts.residual[stuck].min():.0e} to "
      f"{no_restarts.residual[stuck].max():.0e} (m or rad)")

# %% [markdown]
# About 3 % of these attempts (17 of 500) stall — urkin gives an attempt up when its error stops
# falling — 15 of them with the elbow or the wrist nearly straight, between 0.001 and 0.1
# (metres or radians) from the target. The cure is cheap: when an attempt is stuck, start
# again from a random configuration. urkin does this by default (`max_restarts=30`,
# seeded, so results are reproducible), and every target is then reached.
#
# ### Exercise 6.3 — `ik_lm` (6 points)
#
# Write `ik_lm(robot, T_target, q0)`: inverse kinematics by Levenberg–Marquardt with adaptive
# damping, built on **your** `lm_step`. The recipe:
#
# * The error is lesson 05's pose error, $e(q) = [p_\text{target} - p(q);\ \text{rotation
#   vector of } R_\text{target}R(q)^\mathsf{T}]$; `orientation_error(R, R_target)` from
#   `urkin.numerical_ik` gives the second part. Use `urkin.fk` and `urkin.jacobian`.
# * Start with $\mu = 10^{-3}$. Each iteration: $\Delta q$ = `lm_step(J, e, mu)`; **limit** it
#   by scaling it down so that no joint moves more than 0.5 rad; evaluate the error at
#   $q + \Delta q$.
# * If $\|e\|$ went down: **accept** the step and divide $\mu$ by 3 (but keep it at least
#   $10^{-12}$). Otherwise: **reject** it (stay at $q$) and double $\mu$.
# * **Stop** before each step: return $q$ as soon as every one of the six components of
#   $e(q)$ — three position errors in metres, three rotation-vector components in radians —
#   is below $10^{-12}$ in absolute value.
# * Every call of `lm_step` counts as one **iteration**, whether its step is accepted or
#   rejected. If $\mu$ grows beyond $10^8$ (a trap), or after 200 iterations of one attempt,
#   **restart** from a random configuration, uniform in $[-\pi, \pi)^6$, with $\mu$ reset to
#   $10^{-3}$. Draw the restarts from one generator, created once per call of `ik_lm`
#   before the first attempt, `rng = np.random.default_rng(0)`, so the result is
#   reproducible. Allow 20 restarts; if none succeeds, return the best $q$ you saw (the one
#   with the smallest $\|e\|$).
#
# *Checked* (to 1e-8 m and 1e-8 rad, measured with `urkin.fk`; a float32 answer to float32's
# precision): that your answer reaches random targets on random UR arms from starts 0.5 rad away on
# every joint, and from the triply singular home pose, given as a list as seed 000 writes it; that
# $\mu$ adapts — the check watches the calls your `ik_lm` makes to your `lm_step`: after a rejected
# step (`lm_step` called again at the same point) $\mu$ must be larger, after an accepted step that
# cuts $\|e\|$ below 40 % of its value it must not grow (and it must shrink at least once), and a
# step that raises the error must not be kept — so a fixed $\mu$ fails; and that it restarts:
# targets near home that Levenberg–Marquardt from home reaches only after a restart. Any adaptive
# rule (×2 and ÷3, ×10 and ÷10, Nielsen's), step limit, stopping test and restart generator will do.
# The feedback recognises a fixed $\mu$, $\mu$ moving the wrong way, steps that raise the error
# accepted, no restarts, restarts from the same start, a loose tolerance and a loop that never runs
# (seed 001's `while ‖V‖ < ε`). urkin's IK solvers (`urkin.ik` with its step functions, the
# closed-form solvers) are hidden while this exercise is graded; `urkin.fk`, `urkin.jacobian` and
# `orientation_error` are not.

# %%
def ik_lm(robot, T_target, q0):
    """Inverse kinematics by Levenberg–Marquardt with adaptive damping and restarts.

    Parameters
    ----------
    robot : urkin.Robot
        The arm, for example ``urkin.robot("UR5")``.
    T_target : array_like, shape (4, 4)
        The target pose of the flange in the base frame (metres).
    q0 : array_like, shape (6,)
        The initial guess, radians.

    Returns
    -------
    ndarray, shape (6,)
        Joint angles in radians with ``urkin.fk(robot, q)`` equal to ``T_target`` (position
        error and rotation angle below 1e-12 when the solver succeeds); otherwise the best
        configuration found.
    """
    ### BEGIN SOLUTION
    T_target = np.asarray(T_target, dtype=float)

    def pose_error(q):
        T = urkin.fk(robot, q)
        return np.r_[T_target[:3, 3] - T[:3, 3], orientation_error(T[:3, :3], T_target[:3, :3])]

    rng = np.random.default_rng(0)
    q = np.asarray(q0, dtype=float).copy()
    best_q, best_cost = q.copy(), np.inf
    for _ in range(21):  # the first attempt, then up to 20 restarts
        error = pose_error(q)
        cost = error @ error
        mu = 1e-3
        for _ in range(200):
            if cost < best_cost:
                best_q, best_cost = q.copy(), cost
            if np.abs(error).max() < 1e-12:
                return q
            step = lm_step(urkin.jacobian(robot, q), error, mu)
            largest = np.abs(step).max()
            if largest > 0.5:  # no joint moves more than 0.5 rad in one step
                step = step * (0.5 / largest)
            trial_error = pose_error(q + step)
            trial_cost = trial_error @ trial_error
            if trial_cost < cost:  # a good step: take it, trust the linear model more
                q, error, cost = q + step, trial_error, trial_cost
                mu = max(mu / 3.0, 1e-12)
            else:  # a bad step: stay, damp more
                mu = 2.0 * mu
                if mu > 1e8:  # no small step helps: a trap
                    break
        q = rng.uniform(-np.pi, np.pi, 6)
    return best_q
    ### END SOLUTION


# %%
check("6.3", ik_lm)

# %% [markdown]
# ## 5. The PoE solver: the error as a twist
#
# Seed 001 measures the pose error differently: not as a position difference plus a rotation
# vector, but as the **twist** that carries the current pose $T = T(q)$ to the target in unit
# time — the matrix logarithm of lesson 03, section 8:
#
# $$[V_s] = \log\!\left(T_\text{target}\,T^{-1}\right), \qquad
# [V_b] = \log\!\left(T^{-1}\,T_\text{target}\right).$$
#
# $T_\text{target}T^{-1}$ is the motion that, applied *in the base frame* (multiplied on the
# left), turns $T$ into $T_\text{target}$, so $V_s$ is a **space twist**. $T^{-1}T_\text{target}$
# is the same motion expressed in the *current flange frame* (multiplied on the right), so
# $V_b$ is a **body twist**. The two are related by the adjoint of lesson 03,
# $V_s = \mathrm{Ad}_T V_b$ — and so are the Jacobians of lesson 04, $J_s = \mathrm{Ad}_T J_b$.
#
# Newton's step must compare like with like: a space twist with the space Jacobian, a body
# twist with the body Jacobian,
#
# $$\Delta q = J_s^+ V_s \qquad\text{or}\qquad \Delta q = J_b^+ V_b .$$
#
# Where $J$ is invertible these are the *same* step, since $J_s^{-1}V_s = (\mathrm{Ad}_T J_b)^{-1}
# \mathrm{Ad}_T V_b = J_b^{-1}V_b$. This is `IKinSpace` (and `IKinBody`) of *Modern Robotics*,
# and urkin's `method="poe"`. Seed 001 pairs $\log(T_\text{goal}T_\text{cur}^{-1})$ with its
# $J$; that is right exactly when its $J$ is the space Jacobian of its screw axes. Pair the
# space twist with the *body* Jacobian and the step is $J_b^{-1}\mathrm{Ad}_T V_b$: the error
# twist read in the wrong frame — a different direction, not just a different length — unless
# $T$ happens to be the identity.
#
# A short hand-written loop (full Newton steps, no limits) shows all four pairings on a UR5.

# %%
S_ur5, M_ur5 = urkin.poe.space_screws(ur5)
B_ur5, _ = urkin.poe.body_screws(ur5)


def twist_newton(twist_frame, jacobian_frame, T_goal, q_start, iterations):
    """Newton on the log error twist of the given frame ("space" or "body"), paired with the
    Jacobian of the given frame, angles wrapped into [−π, π); returns the pose residual before
    each iteration and after the last, and the final q."""
    q_now = np.array(q_start, dtype=float)
    history = []
    for _ in range(iterations):
        T_now = urkin.poe.fk_space(M_ur5, S_ur5, q_now)
        history.append(pose_residual(ur5, q_now, T_goal))
        if twist_frame == "space":
            twist = se3_log(T_goal @ inv_transform(T_now))
        else:
            twist = se3_log(inv_transform(T_now) @ T_goal)
        if jacobian_frame == "space":
            jac = urkin.poe.jacobian_space(S_ur5, q_now)
        else:
            jac = urkin.poe.jacobian_body(B_ur5, q_now)
        q_now = q_now + np.linalg.pinv(jac) @ twist
        q_now = (q_now + np.pi) % (2 * np.pi) - np.pi  # wrap into [−π, π)
    history.append(pose_residual(ur5, q_now, T_goal))
    return np.array(history), q_now


q_answer = np.array([0.5, -1.1, 1.4, -1.6, 1.2, 0.4])
T_twist_goal = urkin.fk(ur5, q_answer)
q_twist_start = q_answer + np.array([0.3, -0.3, 0.3, -0.3, 0.3, -0.3])
pairings = [("space", "space"), ("body", "body"), ("space", "body"), ("body", "space")]
twist_runs = {pair: twist_newton(*pair, T_twist_goal, q_twist_start, 25) for pair in pairings}

fig, ax = plt.subplots(figsize=(9, 5.5))
looks = {("space", "space"): ("tab:blue", "-", "o"), ("body", "body"): ("tab:cyan", "--", "x"),
         ("space", "body"): ("tab:red", "-", "s"), ("body", "space"): ("tab:orange", "-", "^")}
for pair, (history, _) in twist_runs.items():
    colour, line, marker = looks[pair]
    matched = "matched" if pair[0] == pair[1] else "mismatched"
    ax.semilogy(np.maximum(history, 1e-17), line, color=colour, marker=marker, markersize=5,
                linewidth=1.8, label=f"{pair[0]} twist with {pair[1]} Jacobian ({matched})")
ax.set_xlabel("iteration")
ax.set_ylabel("pose residual: max(position m, angle rad)")
ax.set_title("Newton on the matrix-log error twist (UR5, start 0.3 rad away)")
ax.set_ylim(1e-17, 30)
ax.legend(loc="center right", fontsize=9)
ax.grid(True, which="major", alpha=0.3)
plt.show()

for pair, (history, _) in twist_runs.items():
    # a mismatched run wanders chaotically (round-off decides its path), so report a bound
    outcome = (f"after 25 {below(history[-1])}" if pair[0] == pair[1] else
               f"above 0.1 at every iteration from 3 to 25: {bool(history[3:].min() > 0.1)}")
    print(f"{pair[0]:>5} twist, {pair[1]:>5} Jacobian: residual after 3 iterations "
          f"{history[3]:.1e}; {outcome}")
same = np.abs(twist_newton("space", "space", T_twist_goal, q_twist_start, 2)[1]
              - twist_newton("body", "body", T_twist_goal, q_twist_start, 2)[1]).max()
print(f"\nmatched pairings after 2 iterations: largest difference in q {below(same)}")
poe_result = urkin.ik(ur5, T_twist_goal, q0=q_twist_start, method="poe")
print(f"urkin.ik(method='poe'): success {poe_result.success} after {poe_result.iterations} "
      f"iterations, residual {below(poe_result.residual)}")

# %% [markdown]
# The matched pairings are one and the same iteration: quadratic convergence, round-off level
# after five steps. The mismatched pairings wander at or above the error they started with and
# after 25 iterations are no closer. For the UR5 the flange pose is far from the identity (here
# it sits 0.8 m from the base origin, turned by about 0.76 rad), so $\mathrm{Ad}_T$ differs a
# lot from $I$ and the mistake is loud. On an arm whose end effector stays near the base origin
# with little rotation, the same bug would only slow convergence — and would be much harder to
# notice.
#
# Two more differences from section 3's error. The translational part of $V_s$ is *not* the
# position error of the flange: like the space Jacobian's $v_s$, it is the velocity of the
# body point at the base origin. And the twist error couples rotation and translation through
# the logarithm, whereas lesson 05's error treats them separately. Both measures vanish exactly
# at the target, so both solve the same problem; they take different paths there.

# %% [markdown]
# ### Exercise 6.4 — `ik_poe` (4 points)
#
# Write `ik_poe(M, S, T_target, q0, tol_omega=1e-10, tol_v=1e-10, max_iterations=50)`,
# Modern Robotics' `IKinSpace`, for an arm given by its home pose `M` (4 × 4) and space screw
# axes `S` (6 × n): starting from `q0` (n,), repeat
#
# * the error twist $[V_s] = \log(T_\text{target}\,T(q)^{-1})$, with
#   $T(q) = e^{[S_1]q_1}\cdots e^{[S_n]q_n}M$ (`urkin.poe.fk_space`) and the log of lesson 03
#   (your `twist_log`, or `urkin.transforms.se3_log`);
# * stop when $\|\omega_s\| \le$ `tol_omega` and $\|v_s\| \le$ `tol_v`, or after
#   `max_iterations` steps;
# * $q \leftarrow q + J_s^{+}(q)\,V_s$ with the space Jacobian (`urkin.poe.jacobian_space`, or
#   your `jacobian_space` of lesson 04) and `np.linalg.pinv`: full steps, no limit, no wrapping;
#
# and return $q$ (n,).
#
# *Checked* (to 1e-9; the target to 1e-8 m and 1e-8 rad; a float32 answer to float32's
# precision): (2 points) that `max_iterations=1` returns exactly one step
# $q_0 + J_s^{+}V_s$ — the feedback recognises the body twist, the body Jacobian, the twist of
# the inverse motion and (v, ω) order; (1 point) that it reaches targets on UR arms from
# 0.3 rad away on every joint; (1 point) and on random arms of 2 to 7 joints (fewer than six:
# reachable targets only). urkin's IK solvers are hidden while it is graded; `fk_space`,
# `jacobian_space` and `se3_log` are not.

# %%
def ik_poe(M, S, T_target, q0, tol_omega=1e-10, tol_v=1e-10, max_iterations=50):
    """Inverse kinematics by Newton–Raphson on the space error twist (IKinSpace).

    Parameters
    ----------
    M : array_like, shape (4, 4)
        End-effector pose at q = 0.
    S : array_like, shape (6, n)
        Space screw axes, one per column, ordered (ω, v).
    T_target : array_like, shape (4, 4)
        Target end-effector pose.
    q0 : array_like, shape (n,)
        Initial guess, radians.
    tol_omega, tol_v : float
        Stop when the error twist's angular part is at most tol_omega (rad) and its linear
        part at most tol_v (m).
    max_iterations : int
        Largest number of Newton steps.

    Returns
    -------
    ndarray, shape (n,)
        The joint angles after the last step.
    """
    ### BEGIN SOLUTION
    M, S, T_target = (np.asarray(x, dtype=float) for x in (M, S, T_target))
    q = np.asarray(q0, dtype=float).copy()
    for _ in range(max_iterations):
        V = se3_log(T_target @ inv_transform(urkin.poe.fk_space(M, S, q)))
        if np.linalg.norm(V[:3]) <= tol_omega and np.linalg.norm(V[3:]) <= tol_v:
            break
        q = q + np.linalg.pinv(urkin.poe.jacobian_space(S, q)) @ V
    return q
    ### END SOLUTION


# %%
check("6.4", ik_poe)

# %% [markdown]
# ## 6. Predict, then verify: the damping for a step bound
#
# Section 3 chose λ by looking at plots. Often the requirement comes the other way round: a
# controller may turn the joints by at most `max_step` radians per step, and the solver must
# guarantee it for whatever Jacobian it meets. This lesson's introduction promised a DLS step
# that can never be longer than a set bound. Which λ puts that bound at `max_step`?
#
# **Predict before you compute.** Take one singular direction of $J$, with singular value
# $\sigma$, and the DLS gain $g(\sigma) = \sigma/(\sigma^2 + \lambda^2)$ on the part of the
# error along it.
#
# * What does $g$ do as $\sigma \to 0$, and as $\sigma \to \infty$? So somewhere in between the
#   gain is largest: set $g'(\sigma) = 0$ to find where, and how large it is there.
# * The step is $\Delta q = \sum_i g(\sigma_i)\,(u_i^\mathsf{T}e)\,v_i$ with orthonormal
#   $v_i$, so $\|\Delta q\|^2 = \sum_i g(\sigma_i)^2 (u_i^\mathsf{T}e)^2$. Why does the largest
#   gain bound $\|\Delta q\|$ for *every* $J$, whatever its singular values? For which $J$ and
#   $e$ is the bound reached?
# * Which λ makes that bound equal to `max_step`? Why would every smaller λ fail for some $J$?
#
# ### Exercise 6.5 — `damping_for_step` (3 points)
#
# Write `damping_for_step(e, max_step)`: the smallest damping $\lambda \ge 0$ for which the DLS
# step $\Delta q = J^\mathsf{T}(JJ^\mathsf{T} + \lambda^2 I)^{-1}e$ has
# $\|\Delta q\| \le$ `max_step` for **every** Jacobian $J$ with as many rows as $e$ has
# entries, whatever its singular values. `e` is the error (array_like, any length ≥ 1, in the
# units of $J$'s rows); `max_step` is the bound on the step's Euclidean norm in radians, a finite
# number > 0. Return λ as a float, in the units of $J$: 0 when $e = 0$ (every step is 0 then).
# Raise `ValueError`, with a message that names `max_step`, when `max_step` is ≤ 0, NaN or
# infinite; and `ValueError` when `e` holds a NaN or an infinity.
#
# *Checked*: (1 point) λ for random errors of 1 to 8 components, to 1e-12 relative (a float32
# answer to float32's precision); (1 point) that with your λ the DLS step stays within
# `max_step` (to 1e-9 relative) for random Jacobians and for a Jacobian built with a singular
# value equal to your λ, its output direction along $e$ — a λ that is too small fails there;
# (1 point) once λ is right for an ordinary error, that $e = 0$ gives exactly 0 and that the
# bad inputs above raise. The feedback recognises a forgotten 1/2, λ² returned in place of λ,
# a square root, the largest $|e_i|$ in place of $\|e\|$, and $\|e\|^2$ in place of $\|e\|$.
# Nothing is hidden: urkin has no function for this.

# %%
def damping_for_step(e, max_step):
    """The smallest damping that keeps every damped least-squares step within a bound.

    Parameters
    ----------
    e : array_like, shape (m,)
        The error the step removes, in the units of J's rows; m ≥ 1.
    max_step : float
        The bound on the step's length ‖Δq‖, radians; finite and > 0.

    Returns
    -------
    float
        λ ≥ 0, in the units of J, such that ‖Jᵀ(JJᵀ + λ²I)⁻¹e‖ ≤ max_step for every Jacobian
        J with m rows, and no smaller λ does; 0 when e = 0.

    Raises
    ------
    ValueError
        If max_step is not a finite number > 0 (the message names max_step), or if e holds a
        NaN or an infinity.
    """
    ### BEGIN SOLUTION
    e = np.asarray(e, dtype=float)
    if not (np.isfinite(max_step) and max_step > 0):
        raise ValueError(f"max_step must be a finite number > 0; got {max_step}")
    if not np.all(np.isfinite(e)):
        raise ValueError("e must be finite: it holds a NaN or an infinity")
    # σ/(σ² + λ²) peaks at σ = λ with the value 1/(2λ), so ‖Δq‖ ≤ ‖e‖/(2λ) for every J, with
    # equality when e lies along a singular direction whose σ is λ: the bound is max_step
    # exactly for λ = ‖e‖/(2 max_step), and any smaller λ lets that J exceed it
    return float(np.linalg.norm(e)) / (2.0 * max_step)
    ### END SOLUTION


# %%
check("6.5", damping_for_step)

# %% [markdown]
# Now verify the prediction. The cell below asks your function for the damping that keeps
# section 1's error (1 mm and 1 mrad) within steps of 0.05 rad. Then it sweeps a singular value
# σ over eight decades: a 6 × 6 Jacobian with five fixed singular values and a sixth, σ, whose
# output direction lies along $e$, so the whole error meets the gain $g(\sigma)$. It also tries
# 2000 random Jacobians, and half your λ.

# %%
max_step_demo = 0.05  # rad
try:
    lam_demo = float(damping_for_step(e_small, max_step_demo))
except NotImplementedError:
    print("exercise 6.5 is not written yet: nothing to verify")
else:
    rng = np.random.default_rng(65)
    U_demo, _ = np.linalg.qr(np.column_stack([e_small, rng.normal(size=(6, 5))]))
    V_demo, _ = np.linalg.qr(rng.normal(size=(6, 6)))
    sigma_sweep = np.sort(np.r_[np.logspace(-6, 2, 2001), lam_demo, lam_demo / 2])

    def step_length(sigma, lam):
        """‖DLS step‖ for e_small, with J's singular value sigma along e_small."""
        J_sweep = U_demo @ np.diag([sigma, 0.9, 0.5, 0.3, 0.2, 0.1]) @ V_demo.T
        return np.linalg.norm(J_sweep.T @ np.linalg.solve(J_sweep @ J_sweep.T
                                                          + lam**2 * np.eye(6), e_small))

    print(f"‖e‖ = {np.linalg.norm(e_small):.6f}, max_step = {max_step_demo} rad: "
          f"your λ = {lam_demo:.6f}")
    for lam, name in ((lam_demo, "your λ"), (lam_demo / 2, "half your λ")):
        lengths = np.array([step_length(s, lam) for s in sigma_sweep])
        at = sigma_sweep[np.argmax(lengths)]
        print(f"{name:<12}: over {len(sigma_sweep)} values of σ the longest step is "
              f"{lengths.max() / max_step_demo:.4f} × max_step, at σ = {at / lam_demo:.4f} × "
              "your λ")
    lengths = np.array([step_length(s, lam_demo) for s in sigma_sweep])
    print(f"your λ: |longest step / max_step − 1| {below(abs(lengths.max() / max_step_demo - 1))}")
    random_J = rng.normal(size=(2000, 6, 6)) * 10 ** rng.uniform(-3, 1, (2000, 1, 1))
    solved = np.linalg.solve(random_J @ random_J.transpose(0, 2, 1) + lam_demo**2 * np.eye(6),
                             np.broadcast_to(e_small, (2000, 6))[..., None])[..., 0]
    random_steps = np.linalg.norm(np.einsum("nji,nj->ni", random_J, solved), axis=1)
    print(f"2000 random Jacobians with your λ: every step within max_step: "
          f"{bool(random_steps.max() <= max_step_demo)}")

# %% [markdown]
# The sweep confirms the prediction. The step is longest exactly at $\sigma = \lambda$, where
# the gain $\sigma/(\sigma^2 + \lambda^2)$ peaks at $1/(2\lambda)$, and there it equals
# `max_step`: the bound is reached, so no smaller λ could guarantee it. With half the damping
# the peak moves to $\sigma = \lambda/2$ and the step doubles. Random Jacobians stay inside the
# bound, most of them far inside: the worst case needs a singular value right at λ with the
# whole error along its direction. That is the price of a guarantee. A λ chosen for the worst
# $J$ damps every other one too, and near solutions with $\sigma$ above λ it slows the
# convergence of section 3. Levenberg–Marquardt avoids that price: it adapts the damping to
# each step instead of fixing it for the worst one.
#
# ## 7. All four methods on 1000 random poses
#
# Time for a fair race. 1000 UR5 configurations, uniform in $[-\pi, \pi]^6$ (seeded), give
# 1000 reachable target poses; every method starts from $q_0 = 0$ — which is itself singular
# (elbow straight, $q_5 = 0$) — with urkin's defaults: tolerances $10^{-10}$ m and rad, at most
# 100 iterations per attempt, up to 30 seeded restarts, steps limited to 1 rad (1.5 rad for
# LM, whose damping already shortens poor steps), $\lambda = 0.01$ for DLS. Each method solves
# all 1000 targets in one batched call. A result counts as a success only if its pose error,
# measured with `urkin.fk`, is below $10^{-9}$; urkin's `success` flag is already verified that
# way (with its own, tighter tolerance), and we check it again ourselves.

# %%
rng = np.random.default_rng(2024)
q_race = rng.uniform(-np.pi, np.pi, (1000, 6))
T_race = urkin.fk(ur5, q_race)
methods = {"nr": "Newton–Raphson", "dls": "damped least squares", "lm": "Levenberg–Marquardt",
           "poe": "PoE matrix log"}
race, seconds = {}, {}
for method in methods:
    started = time.perf_counter()
    race[method] = urkin.ik(ur5, T_race, q0=np.zeros(6), method=method)
    seconds[method] = time.perf_counter() - started

print("method                  verified  success  1st attempt  mean it.  median it.  "
      "mean restarts  max restarts")
for method, name in methods.items():
    result = race[method]
    T_found = urkin.fk(ur5, result.q)
    position = np.linalg.norm(T_found[:, :3, 3] - T_race[:, :3, 3], axis=1)
    angle = rotation_angle(T_found[:, :3, :3], T_race[:, :3, :3])
    verified = (position < 1e-9) & (angle < 1e-9)
    first = result.success & (result.restarts == 0)
    print(f"{name:<22} {verified.mean():8.1%} {result.success.mean():8.1%} {first.mean():11.1%}"
          f" {result.iterations.mean():9.1f} {np.median(result.iterations):10.0f}"
          f" {result.restarts.mean():14.2f} {result.restarts.max():13d}")

# %% [markdown]
# The time per target depends on the machine (and varies from run to run), so it is printed
# in a cell of its own:

# %%
# NBVAL_IGNORE_OUTPUT
for method, name in methods.items():
    print(f"{name:<22} {1e6 * seconds[method] / len(T_race):8.0f} µs per target (batched)")

# %%
fig, axes = plt.subplots(2, 2, figsize=(12, 7), sharex=True, sharey=True,
                         constrained_layout=True)
bins = np.geomspace(3, 3000, 31)
for ax, (method, name) in zip(axes.flat, methods.items()):
    solved = race[method].success
    ax.hist([race[method].iterations[solved], race[method].iterations[~solved]], bins=bins,
            stacked=True, color=["tab:blue", "tab:orange"],
            label=[f"reached ({solved.sum()})", f"missed ({(~solved).sum()})"])
    median = np.median(race[method].iterations)
    ax.axvline(median, color="tab:red", linewidth=1.5, label=f"median {median:.0f}")
    ax.set_title(f"{name} (method=\"{method}\")")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.legend(loc="upper right", fontsize=8)
    ax.grid(True, which="major", alpha=0.3)
for ax in axes[1]:
    ax.set_xlabel("iterations, all attempts together (log scale)")
for ax in axes[:, 0]:
    ax.set_ylabel("number of targets (log scale)")
fig.suptitle("Iterations per target: 1000 random UR5 poses from q0 = 0")
plt.show()

dls = race["dls"]
slow = np.flatnonzero(dls.iterations > 100)
sigma_slow = np.linalg.svd(urkin.jacobian(ur5, dls.q[slow]), compute_uv=False)[:, -1]
sigma_all = np.linalg.svd(urkin.jacobian(ur5, race["lm"].q), compute_uv=False)[:, -1]
print(f"DLS needed more than 100 iterations on {len(slow)} targets; smallest σ of J at their "
      f"solutions: median {np.median(sigma_slow):.1e} (LM's solutions of all 1000: median "
      f"{np.median(sigma_all):.1e})")
for method in ["nr", "poe"]:
    for index in np.flatnonzero(~race[method].success):
        print(f"{methods[method]} missed target {index}, generated with q3 = "
              f"{q_race[index, 2]:.4f} rad: {race[method].reason[index]}")

# %% [markdown]
# **Levenberg–Marquardt** solves the most targets on its first attempt (87 %), needs the
# fewest restarts and iterations, and is urkin's default for that reason. (One LM "iteration"
# includes any rejected trial, which costs a forward kinematics evaluation but no new
# Jacobian.) **Newton–Raphson** with the pseudo-inverse and a 1 rad step limit is better than
# its reputation — restarts reach all but at most a few targets of the thousand — but a quarter
# of its first attempts fail, and restarts repair the damage. **The PoE solver** is Newton on a
# different error measure (*Modern Robotics*' `IKinSpace`, here with the same 1 rad step
# limit) and behaves much like it; the table and the lines above say how many targets each
# left. **Fixed-λ DLS** has good first attempts — damping
# helps on the way — but it pays for its fixed λ at the end, for a *systematic* reason. The
# targets where it needs more than a hundred iterations (the tail of its histogram) have
# solutions where the smallest singular value of $J$ is a few thousandths (the median printed
# above), against about 0.09 at the solutions LM found: section 3's slow, linear convergence,
# which stalls short of $10^{-10}$. Restarts would help little, since the trouble is at the
# solution rather than at the start. What finishes them is urkin's core: an attempt that stalls
# within a millimetre of its target first takes one step along the Jacobian's weakest
# direction, fitted to the error there (the notes of `urkin.numerical_ik` explain it), and the
# damped steps go on from where it lands.
#
# All of this is on targets drawn uniformly in joint space; the histograms show the long
# tails of the restarts. `bench/ik.py` in the repository runs the same comparison against
# Robotics Toolbox for Python's `ik_LM` and *Modern Robotics*' `IKinSpace`.

# %% [markdown]
# ## 8. Your turn: the body-frame solver
#
# Section 5 showed two matched pairings, the space twist with the space Jacobian and the body
# twist $[V_b] = \log(T^{-1}T_\text{target})$ with the body Jacobian $J_b$, and ran both in
# `twist_newton`; exercise 6.4 asked you to write only the first, *Modern Robotics'*
# `IKinSpace`. The second is `IKinBody`. Everything in it lives in the current flange frame:
# the arm is given by its **body screw axes** $B_i$ (`urkin.poe.body_screws`), the forward
# kinematics is $T(q) = M\,e^{[B_1]q_1}\cdots e^{[B_n]q_n}$ (`urkin.poe.fk_body`), and the body
# Jacobian (`urkin.poe.jacobian_body`) maps joint rates to the body twist of the flange.
#
# ### Exercise 6.6 — `ik_poe_body` (4 points)
#
# Write `ik_poe_body(M, B, T_target, q0, tol_omega=1e-10, tol_v=1e-10, max_iterations=50)`,
# Modern Robotics' `IKinBody`, for an arm given by its home pose `M` (4 × 4) and body screw
# axes `B` (6 × n) — the arguments of `ik_poe`, in the same order, with `B` where `S` was:
# starting from `q0` (n,), repeat
#
# * the error twist $[V_b] = \log(T(q)^{-1}\,T_\text{target})$, with
#   $T(q) = M\,e^{[B_1]q_1}\cdots e^{[B_n]q_n}$ (`urkin.poe.fk_body(M, B, q)`) and the log of
#   lesson 03 (your `twist_log`, or `urkin.transforms.se3_log`);
# * stop when $\|\omega_b\| \le$ `tol_omega` and $\|v_b\| \le$ `tol_v`, or after
#   `max_iterations` steps;
# * $q \leftarrow q + J_b^{+}(q)\,V_b$ with the body Jacobian at the current $q$
#   (`urkin.poe.jacobian_body(B, q)`, or your `jacobian_body` of lesson 04), recomputed at
#   every iteration, and `np.linalg.pinv`: full steps, no limit, no wrapping;
#
# and return $q$ (n,).
#
# *Checked* (to 1e-9; the target to 1e-8 m and 1e-8 rad; a float32 answer to float32's
# precision): (1 point) that `max_iterations=1` returns exactly one step $q_0 + J_b^{+}V_b$,
# and (1 point) that `max_iterations=2` returns exactly two, the second with $V_b$ and $J_b$
# computed at the new $q$ — both on UR arms and on random arms of 2 to 7 joints, some starting
# with an angle beyond $\pm\pi$; the feedback recognises the space twist with the body
# Jacobian, the body twist with the space Jacobian, 6.4's space pairing (with fewer than six
# joints its least-squares step is a different one), the twist of the inverse motion,
# (v, ω) order, `fk_space` used with body screws, a Jacobian that is not recomputed and
# wrapped angles; (1 point) that it reaches targets on UR arms from 0.3 rad away on every
# joint; (1 point) and on random arms of 2 to 7 joints (fewer than six: reachable targets
# only). urkin's IK solvers are hidden while it is graded; `fk_body`, `jacobian_body` and
# `se3_log` are not.

# %%
def ik_poe_body(M, B, T_target, q0, tol_omega=1e-10, tol_v=1e-10, max_iterations=50):
    """Inverse kinematics by Newton–Raphson on the body error twist (IKinBody).

    Parameters
    ----------
    M : array_like, shape (4, 4)
        End-effector pose at q = 0.
    B : array_like, shape (6, n)
        Body screw axes (in the end-effector frame at q = 0), one per column, ordered (ω, v).
    T_target : array_like, shape (4, 4)
        Target end-effector pose.
    q0 : array_like, shape (n,)
        Initial guess, radians.
    tol_omega, tol_v : float
        Stop when the error twist's angular part is at most tol_omega (rad) and its linear
        part at most tol_v (m).
    max_iterations : int
        Largest number of Newton steps.

    Returns
    -------
    ndarray, shape (n,)
        The joint angles after the last step.
    """
    ### BEGIN SOLUTION
    M, B, T_target = (np.asarray(x, dtype=float) for x in (M, B, T_target))
    q = np.asarray(q0, dtype=float).copy()
    for _ in range(max_iterations):
        V = se3_log(inv_transform(urkin.poe.fk_body(M, B, q)) @ T_target)
        if np.linalg.norm(V[:3]) <= tol_omega and np.linalg.norm(V[3:]) <= tol_v:
            break
        q = q + np.linalg.pinv(urkin.poe.jacobian_body(B, q)) @ V
    return q
    ### END SOLUTION


# %%
check("6.6", ik_poe_body)

# %% [markdown]
# Verify it against your space solver of exercise 6.4, from the same start. Section 5 showed
# that where $J$ is invertible the two steps are one, $J_s^{-1}V_s = J_b^{-1}V_b$: on the UR5
# both solvers should take the same iterates. With fewer than six joints $J$ is not square and
# `pinv` gives the least-squares step, which depends on the frame the error is measured in: on
# a four-joint arm the iterates should part ways, and both solvers should still reach a
# reachable target. Every answer is verified with forward kinematics.

# %%
def pose_miss(T_found, T_goal):
    """max(position error in m, rotation angle in rad) between two poses."""
    return max(np.linalg.norm(T_found[:3, 3] - T_goal[:3, 3]),
               rotation_angle(T_found[:3, :3], T_goal[:3, :3]))


def iterates_apart(M, S, B, T_goal, q_start, steps):
    """Largest difference between the body and the space solver after `steps` iterations."""
    body = ik_poe_body(M, B, T_goal, q_start, max_iterations=steps)
    space = ik_poe(M, S, T_goal, q_start, max_iterations=steps)
    return np.abs(np.asarray(body, dtype=float) - np.asarray(space, dtype=float)).max()


try:
    q_body = np.asarray(ik_poe_body(M_ur5, B_ur5, T_twist_goal, q_twist_start), dtype=float)
    q_space = np.asarray(ik_poe(M_ur5, S_ur5, T_twist_goal, q_twist_start), dtype=float)
except NotImplementedError:
    print("exercises 6.4 and 6.6 must both be written: nothing to verify yet")
else:
    print("UR5, section 5's target, start 0.3 rad away on every joint:")
    for steps in (1, 2, 3):
        apart = iterates_apart(M_ur5, S_ur5, B_ur5, T_twist_goal, q_twist_start, steps)
        print(f"  after {steps} iteration{'s' * (steps > 1)} the body and space iterates differ "
              f"by {below(apart, 1e-9)} rad")
    for name, q_found in (("body", q_body), ("space", q_space)):
        miss = pose_miss(urkin.fk(ur5, q_found), T_twist_goal)
        print(f"  {name:>5} solver: urkin.fk of its answer misses the target by {below(miss)}")

    rng = np.random.default_rng(66)
    axes_4 = rng.normal(size=(4, 3))
    axes_4 /= np.linalg.norm(axes_4, axis=1, keepdims=True)
    S_4 = urkin.poe.screw_axis(axes_4, rng.uniform(-0.4, 0.4, (4, 3))).T  # 4 joints, (6, 4)
    M_4 = urkin.transforms.make_transform(p=[0.3, 0.1, 0.4])
    B_4 = urkin.transforms.adjoint(inv_transform(M_4)) @ S_4
    q_4_true = np.array([0.7, -0.4, 1.1, 0.5])
    T_4_goal = urkin.poe.fk_space(M_4, S_4, q_4_true)  # reachable: the arm reaches it here
    q_4_start = q_4_true + 0.3
    print("\na four-joint arm, a reachable target, start 0.3 rad away on every joint:")
    apart = iterates_apart(M_4, S_4, B_4, T_4_goal, q_4_start, 1)
    print(f"  after 1 iteration the body and space iterates differ by more than 1e-3 rad: "
          f"{bool(apart > 1e-3)}")
    q_4_body = np.asarray(ik_poe_body(M_4, B_4, T_4_goal, q_4_start), dtype=float)
    q_4_space = np.asarray(ik_poe(M_4, S_4, T_4_goal, q_4_start), dtype=float)
    for name, q_found in (("body", q_4_body), ("space", q_4_space)):
        miss = pose_miss(urkin.poe.fk_space(M_4, S_4, q_found), T_4_goal)
        print(f"  {name:>5} solver: fk_space of its answer misses the target by "
              f"{below(miss, 1e-9)}")
    print(f"  the two answers differ by {below(np.abs(q_4_body - q_4_space).max(), 1e-9)} rad")

# %% [markdown]
# On the UR5 the two solvers are one iteration written in two frames. On the four-joint arm
# they take different paths — each step is the least-squares step in its own frame's twist
# coordinates — and still meet at the same joint angles, because the target is reachable and
# both errors vanish exactly there. Which frame to use is then a matter of convenience: the
# one in which the arm's screw axes are at hand (`urkin.poe` gives both).

# %% [markdown]
# ## Summary
#
# * Newton's step divides the error along each singular direction by $\sigma_i$; near a
#   singularity that turns millimetres into radians.
# * **Damped least squares**, $\Delta q = J^\mathsf{T}(JJ^\mathsf{T} + \lambda^2 I)^{-1}e$,
#   replaces $1/\sigma$ by $\sigma/(\sigma^2 + \lambda^2)$: never more than $1/(2\lambda)$, so
#   $\|\Delta q\| \le \|e\|/(2\lambda)$, reached when a singular value equals λ: the
#   smallest λ that guarantees steps no longer than $s$ is $\|e\|/(2s)$ (exercise 6.5). In
#   numpy it takes `@` and `np.linalg.solve` — seed 000's element-wise `*` and `**-1` compute
#   something else entirely.
# * A **fixed** $\lambda$ converges only linearly, at the rate $\lambda^2/(\sigma^2 +
#   \lambda^2)$, near solutions whose smallest singular value is not well above $\lambda$, and
#   stops short of tight tolerances there. No single $\lambda$ suits every target.
# * **Levenberg–Marquardt** uses the same step, $(J^\mathsf{T}J + \mu I)^{-1}J^\mathsf{T}e =
#   J^\mathsf{T}(JJ^\mathsf{T} + \mu I)^{-1}e$, but adapts $\mu$: accept and shrink after a
#   good step, reject and grow after a bad one. A fixed $\mu$, as in seed 001, is DLS. LM can
#   still be trapped where $J^\mathsf{T}e = 0$, often at a singular configuration; seeded
#   restarts fix that.
# * $(J^\mathsf{T}J)^{-1}J^\mathsf{T}$ is the pseudo-inverse only for full column rank; the
#   SVD and the damped forms work at any rank.
# * The **matrix-log error** $V_s = \log(T_\text{target}T^{-1})$ is a space twist and pairs
#   with the space Jacobian; $V_b = \log(T^{-1}T_\text{target})$ pairs with the body Jacobian
#   (exercises 6.4 and 6.6). Mixing them points the step the wrong way.
# * On 1000 random UR5 poses, every method but fixed-λ DLS reaches (nearly) every target with
#   restarts; LM does it with the fewest iterations and restarts.
#
# ## What comes next
#
# Every solver in this lesson finds **one** solution — whichever the start and the restarts
# lead to — and needs iterations, tolerances and some luck to do it. A UR arm has up to
# **eight** solutions for a pose, and its geometry — above all the three parallel axes of
# joints 2, 3 and 4 — lets them be written down in closed form. Lesson 07 derives the analytic
# inverse kinematics: all eight solutions, exactly, in microseconds, including at the singular
# poses where iterative solvers struggle.
#
# Before you move on: restart the kernel and run the whole notebook. All six check cells
# should report full marks.
