# %% [markdown]
# # Lesson 04 — Jacobians and singularities
#
# Forward kinematics tells you *where* the flange is. Most of what a robot does needs to know
# how the flange *moves*: jogging the tool along a straight line, tracking a moving target,
# solving inverse kinematics one small step at a time. All of these rest on one matrix, the
# **Jacobian**, which turns joint speeds into the velocity of the flange.
#
# This lesson builds the geometric Jacobian of a UR arm column by column from its DH frames,
# derives its position part in SymPy, computes it numerically, connects it to the space and body
# Jacobians of lesson 03, finds every **singularity** of a UR arm from one factorised
# determinant, and uses the transposed Jacobian for statics, $\tau = J^\mathsf{T} F$.
#
# **What you will be able to do**
#
# * compute the geometric Jacobian from DH frames, and a numeric one with a step size you can
#   justify (exercises 4.1 and 4.2) or, by the complex step, exact to round-off (exercise
#   4.11);
# * compute the space and body Jacobians from screw axes, as *Modern Robotics* does
#   (exercises 4.3 and 4.4), and convert the geometric Jacobian into the space one
#   (exercise 4.10);
# * say which singular families a configuration is in, and which motion it loses there
#   (exercises 4.5 and 4.7);
# * measure how far a configuration is from trouble with manipulability (exercise 4.6) and
#   with the velocity and force ellipsoids and the condition number of the position Jacobian
#   $J_v$ (exercise 4.9), and find the joint torques that hold a load (exercise 4.8).
#
# **Time:** about 3½ hours. **You need:** lesson 01 (rotations, the cross product as a matrix),
# lesson 02 (DH frames, the UR forward kinematics) and lesson 03 (screw axes $(\omega, v)$,
# the home pose $M$, space and body forward kinematics).

# %%
import inspect

import matplotlib.pyplot as plt
import numpy as np
import sympy as sp
from IPython.display import display

import urkin
import urkin.kinematics
import urkin.plot
import urkin.poe
import urkin.symbolic
from urkin.course import below, check
from urkin.course.seeds import (
    SEED002_ARM,
    SEED002_DH,
    SEED002_LENGTHS,
    SEED002_SHIFT,
    seed002_jacobian,
    seed002_position,
)
from urkin.kinematics import dh_chain
from urkin.symbolic import LENGTHS, Q, simplify_angles
from urkin.transforms import adjoint, se3_exp, so3_log

np.set_printoptions(precision=4, suppress=True)


# %% [markdown]
# `urkin.kinematics` has a function `singularities`, and so does exercise 4.5. Once you have
# run the exercise cell, the bare name `singularities` means *your* function, so the
# demonstrations always spell urkin's in full: `urkin.kinematics.singularities`.
#
# ## 1. What a Jacobian is
#
# Let the joints turn at rates $\dot q = (\dot q_1, \dots, \dot q_6)$ in rad/s. The flange then
# moves with some linear velocity $v$ (m/s, the velocity of the flange *origin*) and turns with
# some angular velocity $\omega$ (rad/s), both written in base coordinates. For a fixed
# configuration $q$ the relation is **linear** in $\dot q$: doubling every joint speed doubles
# the flange's speed, and the motions caused by different joints simply add. A linear map is a
# matrix, and this one is the **geometric Jacobian** $J(q)$:
#
# $$\begin{bmatrix} v \\ \omega \end{bmatrix} = J(q)\,\dot q, \qquad
# J(q) = \begin{bmatrix} J_v(q) \\ J_\omega(q) \end{bmatrix} \in \mathbb{R}^{6\times 6}.$$
#
# Column $i$ is the flange velocity when joint $i$ turns at 1 rad/s and every other joint
# stands still. The top three rows, $J_v$, are in metres per radian (m/s per rad/s); the
# bottom three, $J_\omega$, are dimensionless (rad/s per rad/s).
#
# **Mind the order.** This course stacks the geometric Jacobian as $[v;\ \omega]$, linear part
# first, as many robotics texts and seed report 000 do. Twists and screw axes (lesson 03) are
# written the other way round, $(\omega, v)$, as in *Modern Robotics*. Section 5 converts
# between the two; mixing them up silently swaps the meaning of the rows.
#
# `urkin.jacobian(robot, q)` returns $J$. A quick way to see what it means: turn the joints at
# some rates $\dot q$ for a very short time $\Delta t$, and compare how far the flange moved
# and turned with $J\dot q\,\Delta t$.

# %%
ur5 = urkin.robot("UR5")
q_demo = np.array([0.4, -1.1, 1.3, -1.6, -1.2, 0.5])  # a generic configuration (rad)
q_dot = np.array([0.2, -0.1, 0.3, 0.0, 0.5, -0.4])  # joint rates (rad/s)

J_demo = urkin.jacobian(ur5, q_demo)
twist_predicted = J_demo @ q_dot  # [v; ω]

dt = 1e-7  # seconds: a very short motion
T_now, T_later = urkin.fk(ur5, q_demo), urkin.fk(ur5, q_demo + q_dot * dt)
v_observed = (T_later[:3, 3] - T_now[:3, 3]) / dt
omega_observed = so3_log(T_later[:3, :3] @ T_now[:3, :3].T) / dt  # turn in base coordinates

print("J(q) at q_demo, rows [v; ω]:")
print(J_demo.round(4) + 0.0)
print(f"\nv = J_v q̇          = {twist_predicted[:3].round(4) + 0.0} m/s")
print(f"v, flange moved/Δt = {v_observed.round(4) + 0.0} m/s")
print(f"ω = J_ω q̇          = {twist_predicted[3:].round(4) + 0.0} rad/s")
print(f"ω, flange turned/Δt = {omega_observed.round(4) + 0.0} rad/s")

# %% [markdown]
# The angular velocity was read off with lesson 01's log map: over a short time the flange
# turns by $R(t + \Delta t)R(t)^\mathsf{T} \approx \exp([\omega]\Delta t)$, whose rotation
# vector is $\omega\,\Delta t$ in base coordinates.
#
# ## 2. The geometric Jacobian, column by column
#
# Seed report 000 builds $J$ for its UR3 one column at a time, straight from the DH frames,
# and that construction is exactly right. It rests on two facts from lesson 02:
#
# * joint $i$ turns about the $z$ axis of frame $i-1$ — call its direction $z_{i-1}$ — which
#   passes through that frame's origin $p_{i-1}$ (the base $z$ axis for joint 1);
# * everything beyond joint $i$ is carried along rigidly.
#
# A rigid body turning at 1 rad/s about an axis through $p_{i-1}$ with direction $z_{i-1}$ has
# angular velocity $z_{i-1}$, and each of its points $x$ moves with velocity
# $z_{i-1} \times (x - p_{i-1})$: perpendicular to the axis and to the *lever arm* from the
# axis to the point, and proportional to its length. The flange origin $p$ is such a point, so
#
# $$J_i = \begin{bmatrix} z_{i-1} \times (p - p_{i-1}) \\ z_{i-1} \end{bmatrix},
# \qquad i = 1, \dots, 6.$$
#
# When several joints turn at once, their contributions add: angular velocities along a chain
# add, and so do the velocities they give to a point. That is why the columns can be computed
# one joint at a time.
#
# Everything needed comes from `urkin.fk_frames(robot, q)`: frame $k$'s third column is
# $z_k$, its last column is $p_k$. The figure draws, for the UR5 at `q_demo`, each joint axis,
# the lever arm from the axis to the flange, and the velocity that joint alone gives the
# flange (arrows scaled by 0.3: 0.3 m of arrow per m/s).

# %%
frames_demo = urkin.fk_frames(ur5, q_demo)  # (7, 4, 4): base, then DH frames 1 … 6
p_flange = frames_demo[6, :3, 3]
z_axes, axis_points = frames_demo[:6, :3, 2], frames_demo[:6, :3, 3]  # z_(i−1) and p_(i−1)
velocities = np.cross(z_axes, p_flange - axis_points)  # (6, 3): row i − 1 is v_i, m/s per rad/s

urkin.plot.jacobian_columns_figure(
    frames_demo, velocities, scale=0.3,
    title="UR5: joint axes, lever arms and the flange velocity of each joint\n"
          "column i of J: v_i = z_(i−1) × (p − p_(i−1)), ω_i = z_(i−1)")
plt.show()

for i in range(6):
    print(f"joint {i + 1}: |lever arm| = {np.linalg.norm(p_flange - axis_points[i]):.4f}"
          f" m,  |v_i| = {np.linalg.norm(velocities[i]):.4f} m/s per rad/s")

# %% [markdown]
# Read the figure joint by joint. The lever arm of joint 6 runs *along* its own axis — the
# flange origin sits $d_6$ further out on the joint-6 axis — so the cross product vanishes and
# turning the last joint spins the flange in place: column 6 is $[0;\ z_5]$. Joints 2, 3 and 4
# have parallel axes (all along $z_1$), so their velocity arrows are all perpendicular to that
# common direction, and their lengths grow with the distance from each axis to the flange.
# Only the *component* of the lever arm perpendicular to the axis matters: sliding $p_{i-1}$
# along the axis changes nothing, which is why it does not matter that DH frame origins are
# not at the physical motors (lesson 02).
#
# ### Exercise 4.1 — `geometric_jacobian` (4 points)
#
# Write `geometric_jacobian(robot, q)`: the 6×6 geometric Jacobian of the flange origin in the
# base frame, rows $[v;\ \omega]$, built column by column with
# $J_i = [z_{i-1} \times (p - p_{i-1});\ z_{i-1}]$. Get the frames from
# `urkin.fk_frames(robot, q)` (entry `k` is the pose of DH frame `k`; entry 0 is the base and
# entry 6 the flange). `np.cross` computes the cross product.
#
# *Checked* (to 1e-9, and to 1e-7 against finite differences; a float32 answer to float32's
# precision): the linear rows against central differences of the flange position
# ($h = 10^{-6}$); the angular rows against the flange's rate of turn,
# $[\omega_i] = (\partial R/\partial q_i)\,R^\mathsf{T}$, by central differences of its
# orientation; and the whole matrix against urkin's, for random arms and configurations. The
# feedback recognises the rows in twist order, the axis of the wrong frame (or the wrong column
# of it), a reversed lever arm or one from the base origin, the wrist centre's velocity, the
# space and body Jacobians, degrees, and `a2`, `a3` with the wrong sign. urkin's Jacobians
# (`urkin.jacobian`, `urkin.kinematics.position_jacobian`, `urkin.poe.jacobian_space`,
# `jacobian_body`, the generated and SymPy versions, and what uses them) are hidden while this
# exercise is graded; `urkin.fk_frames` and `urkin.fk` are not.

# %%
def geometric_jacobian(robot, q):
    """Geometric Jacobian of the flange origin, in the base frame, from the DH frames.

    Parameters
    ----------
    robot : urkin.Robot
        The arm, for example ``urkin.robot("UR5")``.
    q : array_like, shape (6,)
        Joint angles in radians.

    Returns
    -------
    ndarray, shape (6, 6)
        ``J`` with ``[v; ω] = J @ q_dot``: rows 0–2 are the linear velocity ``v`` of the flange
        origin (m/s per rad/s), rows 3–5 the angular velocity ``ω`` of the flange (rad/s per
        rad/s), both in base coordinates. Column ``i`` belongs to joint ``i + 1``:
        ``[z_i × (p − p_i); z_i]`` with ``z_i``, ``p_i`` the z axis and origin of DH frame ``i``
        and ``p`` the flange origin.
    """
    ### BEGIN SOLUTION
    frames = urkin.fk_frames(robot, np.asarray(q, dtype=float))
    p = frames[6][:3, 3]
    J = np.zeros((6, 6))
    for i in range(6):
        z, origin = frames[i][:3, 2], frames[i][:3, 3]
        J[:3, i] = np.cross(z, p - origin)
        J[3:, i] = z
    return J
    ### END SOLUTION


# %%
check("4.1", geometric_jacobian)

# %% [markdown]
# ## 3. The position Jacobian by differentiation
#
# There is a second road to $J_v$. The flange position $p(q)$ is a known function (lesson 02),
# and its velocity is its time derivative, by the chain rule
#
# $$v = \frac{d}{dt}\,p(q(t)) = \frac{\partial p}{\partial q}\,\dot q, \qquad\text{so}\qquad
# J_v = \frac{\partial p}{\partial q},$$
#
# the 3×6 matrix of partial derivatives $\partial p_k / \partial q_i$ — the **position
# Jacobian**. (There is no such shortcut for $J_\omega$: the orientation is a rotation matrix,
# not three numbers whose derivative is $\omega$.) SymPy differentiates the symbolic $p$ of
# *every* UR arm, with the lengths $d_1, a_2, \dots, d_6$ kept as symbols; `ur_t06()` is
# lesson 02's derivation and `simplify_angles` its simplifier.

# %%
p_symbolic = urkin.symbolic.ur_t06()[:3, 3]
Jp_symbolic = p_symbolic.jacobian(Q).applyfunc(simplify_angles)  # ∂p/∂q, 3 × 6
J_symbolic = urkin.symbolic.ur_geometric_jacobian()  # column by column, 6 × 6

print("∂p/∂q1 (the first column):")
display(Jp_symbolic[:, 0])
print("∂p/∂q6 (the last column):")
display(Jp_symbolic[:, 5])
difference = (Jp_symbolic - J_symbolic[:3, :]).applyfunc(simplify_angles)
print("∂p/∂q equals the linear rows of the column-by-column J:",
      difference == sp.zeros(3, 6))

# %% [markdown]
# The two roads meet: all eighteen entries agree symbolically, for every UR arm. The two
# columns shown are easy to read. Joint 1 turns about the base $z$ axis, so
# $\partial p/\partial q_1 = z_0 \times p = (-p_y,\ p_x,\ 0)$: compare the entries with
# lesson 02's $p$. And $\partial p/\partial q_6 = 0$ because the flange origin lies on the
# joint-6 axis.
#
# ### Seed 002's hand-derived Jacobian
#
# Seed report 002 (a UR5, in its own convention: positive $a_2$, $a_3$, angles shifted from
# UR's by $(0, \pi, 0, -\pi, 0, 0)$, lengths in millimetres) differentiates its published
# $p$ by hand and types the eighteen partial derivatives into its solver. Lesson 02 found
# that its $p_x$ and $p_y$ lack a factor $\sin q_5$ on the $d_6 \cos(q_2+q_3+q_4)$ terms. What
# does that do to the Jacobian?
#
# `urkin.course.seeds` holds the report's position and Jacobian, transcribed once in metres and in
# its convention, as functions that accept numbers, numpy arrays or SymPy symbols — one
# transcription for both computing and reasoning (lesson 02 used `seed002_position`). Here is
# the Jacobian, entry by entry as the report lists it:

# %%
print(inspect.getsource(seed002_jacobian).split('"""')[2].strip("\n"))


# %% [markdown]
# First question: **was the differentiation right?** Differentiate the report's own $p$ with
# SymPy and subtract the typed Jacobian.

# %%
p_published = sp.Matrix(seed002_position(Q, LENGTHS, sp.cos, sp.sin))
J_published = sp.Matrix(seed002_jacobian(Q, LENGTHS, sp.cos, sp.sin))
own_error = (J_published - p_published.jacobian(Q)).applyfunc(simplify_angles)
print("hand-derived Jacobian − SymPy's ∂(published p)/∂q is zero:", own_error == sp.zeros(3, 6))

# %% [markdown]
# It was: every one of the eighteen entries is the exact derivative of the published $p$.
# Second question: **is it the Jacobian of the arm?** The arm is the report's own DH chain,
# which lesson 02 evaluated with `dh_chain`. Its derivative can be estimated without any
# formula at all, by nudging one joint at a time by a small $h$ either way and dividing the
# change in position by $2h$ — a *central difference*, which section 4 studies properly. As a
# cross-check, the estimate is compared with urkin's exact position Jacobian of the same arm,
# written in UR's convention (the constant shift between the conventions does not change
# derivatives).

# %%
rng = np.random.default_rng(4)
q_seed = rng.uniform(-np.pi, np.pi, (500, 6))  # seed 002's angles
h = 1e-6
steps = h * np.eye(6)
plus = dh_chain(SEED002_DH, (q_seed[:, None, :] + steps).reshape(-1, 6))[:, :3, 3]
minus = dh_chain(SEED002_DH, (q_seed[:, None, :] - steps).reshape(-1, 6))[:, :3, 3]
J_true = ((plus - minus) / (2 * h)).reshape(500, 6, 3).transpose(0, 2, 1)  # (500, 3, 6)

J_exact = urkin.kinematics.position_jacobian(SEED002_ARM, q_seed - SEED002_SHIFT)
print(f"central differences vs urkin's exact ∂p/∂q: largest difference "
      f"{below(np.abs(J_true - J_exact).max(), 1e-8)} m/rad")

J_seed = np.array(seed002_jacobian(q_seed.T, SEED002_LENGTHS)).transpose(2, 0, 1)
worst = np.abs(J_seed - J_true).max(axis=0)  # (3, 6), m/rad, over the 500 configurations
wrong = worst > 1e-6
print(f"\n{wrong.sum()} of 18 entries are wrong; largest error per entry (mm/rad):")
print("        " + "".join(f"  ∂/∂q{j + 1}" for j in range(6)))
for row, name in enumerate(["p_x", "p_y", "p_z"]):
    print(f"{name:>6}  " + "".join(f"{1000 * worst[row, j]:8.1f}" for j in range(6)))

# %% [markdown]
# Ten entries are wrong — the $x$ and $y$ rows in columns 1 to 5 — by up to 165 mm/rad, while
# the $z$ row and column 6 are right. The error Jacobian is the derivative of the position
# error lesson 02 found, $e = d_6(\sin q_5 - 1)\cos(q_2+q_3+q_4)\,(\cos q_1,\ \sin q_1,\ 0)$:

# %%
p_true_general = urkin.symbolic.ur_t06()[:3, 3]  # right for the report's convention too
error_jacobian = (p_published - p_true_general).jacobian(Q).applyfunc(
    lambda entry: sp.factor(simplify_angles(entry)))
display(error_jacobian)

q_blind = np.array([0.35, 0.35, 0.35, np.pi / 2 - 0.70, 0.35, 0.35])  # q2 + q3 + q4 = 90°
blind_plus = dh_chain(SEED002_DH, q_blind + steps)[:, :3, 3]
blind_minus = dh_chain(SEED002_DH, q_blind - steps)[:, :3, 3]
J_blind_true = ((blind_plus - blind_minus) / (2 * h)).T
J_blind_seed = np.array(seed002_jacobian(q_blind, SEED002_LENGTHS), dtype=float)
print(f"where q2 + q3 + q4 = 90°, as at the report's test: p is right, but ∂p_x/∂q2 is off by "
      f"{1000 * abs(J_blind_seed[0, 1] - J_blind_true[0, 1]):.1f} mm/rad")

# %% [markdown]
# Columns 2 to 4 carry $\sin(q_2+q_3+q_4)$, so they are wrong *even at poses like the
# report's test pose*, where the position itself happens to be right: a wrong function can
# agree with the right one at a point without agreeing in slope. The figure maps the largest
# error of each entry over the 500 configurations, against the true chain and against the
# report's own formula.

# %%
J_own = np.array(  # central differences of the *published* p: what the report differentiated
    [
        (np.array(seed002_position((q_seed + steps[j]).T, SEED002_LENGTHS))
         - np.array(seed002_position((q_seed - steps[j]).T, SEED002_LENGTHS))) / (2 * h)
        for j in range(6)
    ]
).transpose(2, 1, 0)  # (500, 3, 6)
worst_own = np.abs(J_seed - J_own).max(axis=0)

urkin.plot.entry_error_maps(
    [(worst, "against the true DH chain: 10 entries wrong"),
     (worst_own, "against its own published p: all 18 right")],
    factor=1000.0,  # m/rad → mm/rad
    row_labels=["p_x", "p_y", "p_z"], column_labels=[f"∂/∂q{j + 1}" for j in range(6)],
    xlabel="joint (column of the Jacobian)", ylabel="flange coordinate (row)",
    colorbar_label="largest |error| over 500 poses (mm/rad)",
    title="Seed 002's hand-derived UR5 position Jacobian, entry by entry")
plt.show()

# %% [markdown]
# The differentiation was flawless; the formula it differentiated was not. A Jacobian that is
# the exact derivative of a wrong position is *consistent*, which is the dangerous part:
# Newton–Raphson inverse kinematics driven by the pair converges happily — to joint angles
# where the *formula* reaches the target, while the real arm is up to 165 mm away. The
# defence is the one lesson 02 drew: check formulas against an independent computation at
# random configurations. For Jacobians, finite differences are that independent computation.
#
# ## 4. Numeric Jacobians and the step size
#
# The derivative of any function $f: \mathbb{R}^n \to \mathbb{R}^m$ can be estimated from
# values of $f$ alone. Nudge input $j$ by $h$ along the unit vector $e_j$; Taylor's theorem
# says (with $f''$, $f'''$ the higher derivatives along $e_j$)
#
# $$f(q + h e_j) = f(q) + h\,\frac{\partial f}{\partial q_j} + \frac{h^2}{2}\,f'' +
# \frac{h^3}{6}\,f''' + \dots$$
#
# * **forward difference**: $\dfrac{f(q + h e_j) - f(q)}{h} = \dfrac{\partial f}{\partial q_j} +
#   \dfrac{h}{2} f'' + \dots$ — its error shrinks like $h$ (first order);
# * **central difference**: $\dfrac{f(q + h e_j) - f(q - h e_j)}{2h} =
#   \dfrac{\partial f}{\partial q_j} + \dfrac{h^2}{6} f''' + \dots$ — the even terms cancel, so
#   its error shrinks like $h^2$ (second order), for $2n$ evaluations of $f$ instead of $n + 1$.
#
# Each difference is one column of the Jacobian: row $k$, column $j$ holds
# $\partial f_k / \partial q_j$, so the result has shape $(m, n)$ — one row per output, one
# column per input, like $J$.
#
# Why not take $h$ as small as possible? Because $f$ is computed in floating point: each value
# carries a rounding error of about $\varepsilon |f|$ with $\varepsilon \approx 2.2\cdot
# 10^{-16}$, and the difference divides that by $h$. The total error is roughly
#
# $$\text{forward: } \frac{h}{2}|f''| + \frac{\varepsilon|f|}{h}, \qquad
# \text{central: } \frac{h^2}{6}|f'''| + \frac{\varepsilon|f|}{h},$$
#
# smallest near $h \approx \sqrt{\varepsilon} \approx 10^{-8}$ for forward differences and
# $h \approx \varepsilon^{1/3} \approx 10^{-5}$ for central ones (for $f$ and its derivatives
# of order 1, as here: metres and radians).
#
# ### Exercise 4.2 — `numeric_jacobian` (4 points)
#
# Write `numeric_jacobian(f, q, h=1e-6)`: the Jacobian of any function `f` at `q` by
# **central differences**, as an array of shape `(m, n)`, where `q` has `n` entries and
# `f(q)` returns `m` numbers. Column `j` is `(f(q + h e_j) − f(q − h e_j)) / (2h)`. Do not
# change `q` in place (build the nudged inputs as new arrays). You saw the idea for the seed
# chain above; here it must work for any `f`, `n` and `m`.
#
# *Checked* (to 1e-9, 2·10⁻⁵ against an exact derivative and 10⁻⁸ for the flange; a float32
# answer to float32's round-off amplified by 1/h): linear functions $f(q) = Aq + b$ of several
# shapes with $m \ne n$, where the answer is exactly $A$, once with `q` a plain list; the
# central difference at the step `h` you are given ($h = 2^{-2}, 2^{-3}, 2^{-4}$ on a smooth
# function and on a UR arm's flange position, where a forward difference or an ignored `h`
# shows), and within 2·10⁻⁵ of the derivative at $h \approx 10^{-3}$; and the UR flange's 3 × 6
# position Jacobian with the default step. The feedback recognises forward and backward
# differences, a wrong divisor, an ignored `h` or another default, a transposed result, and
# nudged copies that share `q`'s memory. Nothing of urkin is hidden: urkin has no numeric
# differentiation.

# %%
def numeric_jacobian(f, q, h=1e-6):
    """Jacobian of a function by central differences.

    Parameters
    ----------
    f : callable
        ``f(q)`` takes an array of shape ``(n,)`` and returns ``m`` numbers (array_like,
        shape ``(m,)``).
    q : array_like, shape (n,)
        The point at which to differentiate (for a UR arm: joint angles in radians).
    h : float
        Step size, in the units of ``q``.

    Returns
    -------
    ndarray, shape (m, n)
        Entry ``[k, j]`` is ∂f_k/∂q_j ≈ (f_k(q + h e_j) − f_k(q − h e_j)) / (2h): one row per
        output, one column per input. For the flange position of a UR arm, ``m = 3``,
        ``n = 6`` and the entries are in metres per radian.
    """
    ### BEGIN SOLUTION
    q = np.asarray(q, dtype=float)
    columns = []
    for j in range(q.size):
        step = np.zeros_like(q)
        step[j] = h
        forward = np.asarray(f(q + step), dtype=float).ravel()
        backward = np.asarray(f(q - step), dtype=float).ravel()
        columns.append((forward - backward) / (2.0 * h))
    return np.column_stack(columns)
    ### END SOLUTION


# %%
check("4.2", numeric_jacobian)

# %% [markdown]
# ### How small should $h$ be?
#
# Here is the trade-off measured on the UR5's flange position, against urkin's exact
# $\partial p/\partial q$ (generated from the SymPy derivation), for step sizes from
# $10^{-16}$ to $10^{-1}$ rad. A third method joins in: the **complex step**. Evaluate $f$ at
# a *complex* point $q + \mathrm{i}h e_j$; for a function built from analytic operations,
#
# $$f(q + \mathrm{i}h e_j) = f(q) + \mathrm{i}h\,\frac{\partial f}{\partial q_j}
#   \;-\; \frac{h^2}{2}\,\frac{\partial^2 f}{\partial q_j^2} \;+\; \dots,$$
#
# so
#
# $$\frac{\partial f}{\partial q_j} \approx \frac{\operatorname{Im} f(q + \mathrm{i}h e_j)}{h}$$
#
# with an error of order $h^2$ and **no subtraction** at all — nothing cancels, so $h$ can be
# as small as we like. It needs an $f$ that accepts complex numbers. `urkin.fk` does (its
# documentation says so; most numeric code silently drops the imaginary part, or refuses it),
# and so does the SymPy formula turned into numpy code with `lambdify`, which we use as an
# independent check.

# %%
rng = np.random.default_rng(11)
q_fd = rng.uniform(-np.pi, np.pi, 6)
exact = urkin.kinematics.position_jacobian(ur5, q_fd)  # (3, 6), m/rad
p_ur5 = sp.lambdify(Q, list(p_symbolic.subs(dict(zip(LENGTHS, ur5.lengths)))), "numpy")
gap = np.abs(np.array(p_ur5(*q_fd)) - urkin.fk(ur5, q_fd)[:3, 3]).max()
print(f"lambdified SymPy p vs urkin.fk: largest difference {below(gap)}")

steps_h = np.logspace(-16, -1, 61)
nudged = q_fd + steps_h[:, None, None] * np.eye(6)  # (61, 6, 6): every h, every joint
p_plus = urkin.fk(ur5, nudged.reshape(-1, 6))[:, :3, 3].reshape(61, 6, 3)
p_minus = urkin.fk(ur5, (2 * q_fd - nudged).reshape(-1, 6))[:, :3, 3].reshape(61, 6, 3)
p_here = urkin.fk(ur5, q_fd)[:3, 3]
forward = ((p_plus - p_here) / steps_h[:, None, None]).transpose(0, 2, 1)  # (61, 3, 6)
central = ((p_plus - p_minus) / (2 * steps_h[:, None, None])).transpose(0, 2, 1)
p_complex = urkin.fk(ur5, (q_fd + 1j * steps_h[:, None, None] * np.eye(6)).reshape(-1, 6))
complex_step = (p_complex[:, :3, 3].imag.reshape(61, 6, 3)
                / steps_h[:, None, None]).transpose(0, 2, 1)
nudged_once = q_fd + 1j * 1e-20 * np.eye(6)  # row j: joint j nudged
sympy_step = np.imag(np.array(p_ur5(*nudged_once.T))) / 1e-20  # (3, 6): ∂p_k/∂q_j
print(f"complex step through urkin.fk vs through the lambdified SymPy p (h = 1e-20): "
      f"largest difference {below(np.abs(complex_step[0] - sympy_step).max(), 1e-12)}")

errors = {name: np.abs(estimate - exact).max(axis=(1, 2))
          for name, estimate in [("forward", forward), ("central", central),
                                 ("complex step", complex_step)]}

floor = 1e-18  # exact answers (error 0) are drawn here, so that they show on a log axis
urkin.plot.step_size_figure(
    steps_h, {"forward differences": errors["forward"], "central differences": errors["central"],
              "complex step": errors["complex step"]},
    floor=floor, ylabel="largest error of ∂p/∂q entries (m/rad)",
    title="UR5 flange position Jacobian: error against step size")
plt.show()

# the smallest errors are set by round-off, which differs between CPUs: print bounds
expected = {"forward": (1e-7, 1e-9, 1e-7), "central": (1e-9, 1e-7, 1e-4)}
for name, (bound, h_low, h_high) in expected.items():
    error = errors[name]
    best = steps_h[int(np.argmin(error))]
    print(f"{name:>12}: smallest error {below(error.min(), bound)} m/rad, at a step h between "
          f"{h_low:.0e} and {h_high:.0e}: {bool(h_low <= best <= h_high)}")
print(f"{'complex step':>12}: error {below(errors['complex step'][steps_h <= 1e-8].max(), 1e-15)}"
      " m/rad at every h ≤ 1e-8")
at_default = int(np.argmin(np.abs(steps_h - 1e-6)))
print(f"{'at h = 1e-6':>12}: forward {below(errors['forward'][at_default], 1e-6)}, central "
      f"{below(errors['central'][at_default], 1e-9)} m/rad")

# %% [markdown]
# The V shapes are the trade-off. To the right of each V the truncation error dominates and
# falls with slope 1 (forward) or 2 (central and complex step); to the left, rounding takes
# over and grows like $\varepsilon/h$ — at $h = 10^{-16}$ the nudge vanishes entirely and the
# difference is 0. The best forward difference is only about $10^{-8}$ accurate; the best
# central difference is about a thousand times better, near $h \approx 10^{-5}$; the default
# $h = 10^{-6}$ of exercise 4.2 is close to that optimum. The complex step has no left arm:
# below $h \approx 10^{-8}$ it is exact to machine precision.
#
# (The check of exercise 4.1 compares your linear rows with central differences at
# $h = 10^{-6}$ and a tolerance of $10^{-7}$ m/rad: comfortably above both kinds of error.)
#
# ## 5. Space and body Jacobians
#
# Lesson 03 wrote the forward kinematics as a product of exponentials,
# $T(q) = e^{[S_1]q_1}\cdots e^{[S_6]q_6}M = M e^{[B_1]q_1}\cdots e^{[B_6]q_6}$. Its
# Jacobians map joint rates to **twists** $(\omega, v)$, angular part first:
#
# * the **space Jacobian** $J_s$: column $i$ is the screw axis $S_i$ carried to where the
#   joints before it have put it, $J_{s,i} = \mathrm{Ad}_{e^{[S_1]q_1}\cdots
#   e^{[S_{i-1}]q_{i-1}}} S_i$. It gives the *spatial twist* $(\omega, v_s)$, both in base
#   coordinates — where $v_s$ is **not** the velocity of the flange origin but of the point of
#   the (extended) flange body that is passing through the *base origin*;
# * the **body Jacobian** $J_b$ gives the *body twist* $(\omega_b, v_b)$, both in flange
#   coordinates, with $v_b$ the velocity of the flange origin.
#
# Each column of $J_s$ is the current joint axis as a screw, $(z_{i-1},\ p_{i-1} \times
# z_{i-1})$. Compare with the geometric column: velocities of two points of one rigid body
# differ by $\omega \times$ (the vector between them), so
#
# $$v_s = v + \omega \times (0 - p) = v + p \times \omega .$$
#
# That is `urkin.poe.space_from_geometric`, and `geometric_from_space` undoes it. And because
# a twist changes frames through the adjoint of lesson 03, the space and body Jacobians are
# related by $J_s = \mathrm{Ad}_{T}\,J_b$ with $T = T_{0,6}(q)$. Seed 000 calls its column-by-
# column $J$ a "spatial velocity" Jacobian; by these definitions it is the geometric one.
#
# Check all of it numerically on 200 random UR5 configurations:

# %%
S, M = urkin.poe.space_screws(ur5)
B, _ = urkin.poe.body_screws(ur5)
q_many = np.random.default_rng(5).uniform(-np.pi, np.pi, (200, 6))

J_s = urkin.poe.jacobian_space(S, q_many)  # (200, 6, 6), rows (ω; v_s)
J_b = urkin.poe.jacobian_body(B, q_many)  # (200, 6, 6), rows (ω_b; v_b)
J_geo = urkin.jacobian(ur5, q_many)  # (200, 6, 6), rows [v; ω]
T_many = urkin.fk(ur5, q_many)
R_many = T_many[:, :3, :3]

checks = {
    "J_s = Ad_T J_b": np.abs(J_s - adjoint(T_many) @ J_b).max(),
    "J_s = space_from_geometric(J, T)": np.abs(
        J_s - urkin.poe.space_from_geometric(J_geo, T_many)).max(),
    "J = geometric_from_space(J_s, T)": np.abs(
        J_geo - urkin.poe.geometric_from_space(J_s, T_many)).max(),
    "J_b = (Rᵀ J_ω ; Rᵀ J_v)": np.abs(
        J_b - np.concatenate([np.swapaxes(R_many, 1, 2) @ J_geo[:, 3:],
                              np.swapaxes(R_many, 1, 2) @ J_geo[:, :3]], axis=1)).max(),
}
for name, gap in checks.items():
    print(f"{name:<34} largest difference over 200 poses: {below(gap)}")

print("\ncolumn 1 (joint 1) at q_demo, twist order (ω, v):")
print("  space twist (ω, v_s):", urkin.poe.jacobian_space(S, q_demo)[:, 0].round(4) + 0.0)
print("  geometric [v; ω]:    ", J_demo[:, 0].round(4) + 0.0)

# %% [markdown]
# Look at column 1. Joint 1 turns about the base $z$ axis, which passes through the base
# origin, so the body point there does not move: $v_s = 0$. The flange origin, 0.67 m from
# the base axis, does move, and the geometric column says how fast. The body Jacobian is the
# geometric one seen from the flange: the same $\omega$ and $v$, rotated into flange
# coordinates by $R^\mathsf{T}$ and stacked in twist order.
#
# Which one to use? The geometric Jacobian answers "how fast does my tool point move, in the
# base frame" — the question jogging and Cartesian control ask. Space and body Jacobians fit
# the product-of-exponentials machinery and the log-map pose errors of lesson 03; the IK
# lessons use both. All three carry the same information, and the conversions are exact.

# %% [markdown]
# ### Exercise 4.3 — `jacobian_space` (4 points)
#
# Write `jacobian_space(S, q)`, Modern Robotics' `JacobianSpace`: the space Jacobian of an arm
# with space screw axes `S` of shape `(6, n)` (one per column, ordered (ω, v)) at joint
# angles `q` of shape `(n,)`, as a `(6, n)` array whose column $i$ is
# $\mathrm{Ad}(e^{[S_1]q_1}\cdots e^{[S_{i-1}]q_{i-1}})\,S_i$ — column 1 is $S_1$ itself. Build
# the exponentials with `urkin.transforms.se3_exp(S_i * q_i)` (what your `twist_exp` of
# lesson 03 computes) and the adjoint with `urkin.transforms.adjoint`.
#
# *Checked* (to 1e-9, and to 1e-7 against finite differences; a float32 answer to float32's
# precision): (1 point) $J_s = S$ at $q = 0$ and column 1 is $S_1$ at any $q$; (2 points) the
# Jacobian for the space screws of random UR arms and for random arms of 2 to 7 joints;
# (1 point) column $i$ is the spatial twist $\dot T T^{-1}$ when joint $i$ alone turns at
# 1 rad/s, by central differences of the product of exponentials. The feedback recognises
# (v, ω) rows, untransported home axes, the product multiplied on the wrong side, degrees and
# the body Jacobian. urkin's Jacobians (`urkin.jacobian`, `urkin.poe.jacobian_space` and
# `jacobian_body`, the conversions) are hidden while it is graded.

# %%
def jacobian_space(S, q):
    """Space Jacobian from space screw axes: column i is Ad(e^[S1]q1 ⋯ e^[S(i−1)]q(i−1)) S_i.

    Parameters
    ----------
    S : array_like, shape (6, n)
        Space screw axes at q = 0, one per column, each ordered (ω, v).
    q : array_like, shape (n,)
        Joint angles in radians.

    Returns
    -------
    ndarray, shape (6, n)
        Rows (ω; v_s): the spatial twist per unit joint rate.
    """
    ### BEGIN SOLUTION
    axes = np.asarray(S, dtype=float)
    angles = np.asarray(q, dtype=float)
    J = np.zeros(axes.shape)
    T = np.eye(4)  # e^[S1]q1 ⋯ e^[S(i−1)]q(i−1)
    for i in range(axes.shape[1]):
        J[:, i] = adjoint(T) @ axes[:, i]
        T = T @ se3_exp(axes[:, i] * angles[i])
    return J
    ### END SOLUTION


# %%
check("4.3", jacobian_space)

# %% [markdown]
# ### Exercise 4.4 — `jacobian_body` (4 points)
#
# Write `jacobian_body(B, q)`, Modern Robotics' `JacobianBody`: the body Jacobian from body
# screw axes `B` of shape `(6, n)` at joint angles `q`, as a `(6, n)` array whose column $i$
# is $\mathrm{Ad}(e^{-[B_n]q_n}\cdots e^{-[B_{i+1}]q_{i+1}})\,B_i$ — the joints *after* $i$,
# undone, seen from the end effector; the last column is $B_n$ itself.
#
# *Checked* as exercise 4.3, with body screw axes, the last column fixed and the body twist
# $T^{-1}\dot T$; the feedback recognises exponentials of $+B_k q_k$, the product taken from
# joint 1 forwards and the space Jacobian. The same urkin functions are hidden.

# %%
def jacobian_body(B, q):
    """Body Jacobian from body screw axes: column i is Ad(e^−[Bn]qn ⋯ e^−[B(i+1)]q(i+1)) B_i.

    Parameters
    ----------
    B : array_like, shape (6, n)
        Body screw axes (seen from the end effector at q = 0), one per column, ordered (ω, v).
    q : array_like, shape (n,)
        Joint angles in radians.

    Returns
    -------
    ndarray, shape (6, n)
        Rows (ω_b; v_b): the body twist per unit joint rate.
    """
    ### BEGIN SOLUTION
    axes = np.asarray(B, dtype=float)
    angles = np.asarray(q, dtype=float)
    J = np.zeros(axes.shape)
    T = np.eye(4)  # e^−[Bn]qn ⋯ e^−[B(i+1)]q(i+1)
    for i in reversed(range(axes.shape[1])):
        J[:, i] = adjoint(T) @ axes[:, i]
        T = T @ se3_exp(-axes[:, i] * angles[i])
    return J
    ### END SOLUTION


# %%
check("4.4", jacobian_body)

# %% [markdown]
# ## 6. Singularities
#
# A square Jacobian can be inverted — $\dot q = J^{-1}\,[v;\ \omega]$ gives the joint rates
# for any desired flange motion — unless $\det J = 0$. Configurations where that happens are
# **singular**: some flange velocity cannot be produced at all, and close to them the joint
# rates needed for ordinary flange velocities become huge. For a UR arm we can find every one
# of them, because the determinant factors.
#
# SymPy can take the 6×6 symbolic determinant head-on, but simplifying the result takes
# about ten times longer than it needs to. First remove what cannot matter:
#
# * $J$ does not depend on $q_6$ at all: the last joint only spins the flange about its own
#   axis, which moves none of the axes or origins in the formula;
# * $q_1$ turns the whole arm about the base axis, which rotates every column:
#   $J(q) = \mathrm{diag}(R_z(q_1), R_z(q_1))\,J(q)|_{q_1=0}$, and that block-diagonal factor has
#   determinant 1.
#
# So we may set $q_1 = 0$ before taking the determinant.

# %%
q1, q2, q3, q4, q5, q6 = Q
d1, a2, a3, d4, d5, d6 = LENGTHS
print("J depends on q6:", J_symbolic.has(q6))
det_raw = sp.expand(simplify_angles(J_symbolic.subs(q1, 0).det(method="berkowitz")))
# one identity is left for us: cos²(q2+q3+q4) = 1 − sin²(q2+q3+q4)
c234, s234 = sp.cos(q2 + q3 + q4), sp.sin(q2 + q3 + q4)
det_J = sp.factor(det_raw.subs(c234**2, 1 - s234**2))
print("det J =")
display(det_J)

shoulder_factor = a2 * sp.cos(q2) + a3 * sp.cos(q2 + q3) + d5 * sp.sin(q2 + q3 + q4)
expected = a2 * a3 * sp.sin(q3) * sp.sin(q5) * shoulder_factor
print("equal to a2·a3·sin q3·sin q5·(a2 cos q2 + a3 cos(q2+q3) + d5 sin(q2+q3+q4)):",
      sp.expand(det_J - expected) == 0)

# %% [markdown]
# One formula for all seven arms. It is worth confirming numerically with urkin's Jacobian,
# including the claim that $q_1$ and $q_6$ do not matter:

# %%
rng = np.random.default_rng(6)
largest = 0.0
for name in urkin.ROBOTS:
    arm = urkin.robot(name)
    qs = rng.uniform(-np.pi, np.pi, (300, 6))
    numeric = np.linalg.det(urkin.jacobian(arm, qs))
    factor = arm.a2 * np.cos(qs[:, 1]) + arm.a3 * np.cos(qs[:, 1] + qs[:, 2]) \
        + arm.d5 * np.sin(qs[:, 1:4].sum(axis=1))
    formula = arm.a2 * arm.a3 * np.sin(qs[:, 2]) * np.sin(qs[:, 4]) * factor
    largest = max(largest, np.abs(numeric - formula).max())
print(f"det J vs the factorised formula, 7 arms × 300 poses: largest difference {below(largest)}")

qs = rng.uniform(-np.pi, np.pi, (300, 6))
turned = qs.copy()
turned[:, [0, 5]] = rng.uniform(-np.pi, np.pi, (300, 2))  # new q1 and q6, same q2 … q5
spread = np.abs(np.linalg.det(urkin.jacobian(ur5, qs))
                - np.linalg.det(urkin.jacobian(ur5, turned))).max()
print(f"det J with q1 and q6 changed: largest change {below(spread)}")

# %% [markdown]
# Since $a_2 a_3 \neq 0$, $\det J = 0$ exactly when one of three factors vanishes. Each is a
# **singular family**, with its own geometry:
#
# * **shoulder**: $a_2\cos q_2 + a_3\cos(q_2+q_3) + d_5\sin(q_2+q_3+q_4) = 0$. The wrist
#   centre lies in the vertical plane through the base axis that is parallel to the shoulder
#   axis.
# * **elbow**: $\sin q_3 = 0$. The upper arm and the forearm are in one line, stretched out
#   or folded back.
# * **wrist**: $\sin q_5 = 0$. The axes of joints 4 and 6 are parallel.
#
# The **wrist centre** is the origin of frame 5, where the axes of joints 5 and 6 cross. The
# shoulder factor is its horizontal distance from the base axis, measured in the arm's own
# vertical plane (lesson 02's reading of $p$: the reach $a_2 c_2 + a_3 c_{23}$ plus the
# wrist's $d_5 s_{234}$). When it is zero, the wrist centre sits off the base axis only by the
# sideways offset $d_4$, in the plane the figure shades. Turning joint 1 then swings it about
# the base axis, so it moves *tangentially*: along $(c_1, s_1, 0)$, the arm plane's horizontal
# direction, perpendicular to the $d_4$ offset — a direction the shoulder and elbow can
# already produce. Moving it along the offset (along the shoulder axis, away from or towards
# the base axis) is what no joint can do. The cell after the figure measures this.
#
# The elbow condition is the stretched arm of the classic two-link example: the wrist can move
# towards or away from the shoulder only to second order. The wrist condition makes joints 4
# and 6 turn about parallel axes: the three wrist joints can then turn the flange about only
# two independent directions instead of three, and the arm as a whole loses one direction of
# motion.

# %%
reach = ur5.a2 * np.cos(-1.0) + ur5.a3 * np.cos(-2.0)  # q2 = −1, q3 = −1: the arm's reach
families = {  # q4 puts the wrist centre's d5 s234 exactly against the reach
    "shoulder": np.array([0.3, -1.0, -1.0, np.arcsin(-reach / ur5.d5) + 2.0, 1.0, 0.4]),
    "elbow": np.array([0.3, -0.9, 0.0, -1.2, 1.1, 0.4]),
    "wrist": np.array([0.3, -1.3, 1.6, -0.8, 0.0, 0.4]),
}
conditions = {"shoulder": "a2 c2 + a3 c23 + d5 s234 = 0", "elbow": "sin q3 = 0",
              "wrist": "sin q5 = 0"}

urkin.plot.singular_families_figure(ur5, families, conditions=conditions,
                                    title="The three singular families of a UR arm, each on a UR5")
plt.show()

print("family     urkin.kinematics.singularities     factors (shoulder m, sin q3, sin q5)")
for family, q in families.items():
    factors = urkin.kinematics.singularity_factors(ur5, q).round(4) + 0.0
    print(f"{family:<10} {urkin.kinematics.singularities(ur5, q)!s:<34} {factors}")

# the shoulder family, measured: how turning joint 1 moves the wrist centre
q = families["shoulder"]
wrist_centre = urkin.fk_frames(ur5, q)[5, :3, 3]
offset = wrist_centre * [1.0, 1.0, 0.0]  # horizontal, from the base axis to the wrist centre
velocity = np.cross([0.0, 0.0, 1.0], wrist_centre)  # d(wrist centre)/dq1: a turn about z
tangent = np.array([np.cos(q[0]), np.sin(q[0]), 0.0])
assert np.isclose(np.linalg.norm(offset), ur5.d4, atol=1e-12)
assert np.allclose(velocity / np.linalg.norm(velocity), tangent, atol=1e-12)
assert abs(velocity @ offset) < 1e-12
print(f"shoulder family: the wrist centre is {ur5.d4:.5f} m (= d4) from the base axis; "
      "turning joint 1 moves it along (c1, s1, 0), perpendicular to that offset")

# %% [markdown]
# UR's "home" configuration, $q = (0, -\pi/2, 0, -\pi/2, 0, 0)$ with the arm pointing straight
# up, is about as singular as a configuration can be: all three factors vanish at once. The
# elbow is straight ($q_3 = 0$), the wrist has $q_5 = 0$, and the wrist centre stands
# straight above the base, off its axis only by the sideways offset $d_4$, so the shoulder
# factor is zero too. Each family costs one dimension here, and the singular values of $J$
# show it: three of the six are zero, so from home the flange's twist $[v;\ \omega]$ can
# only move in a three-dimensional set of directions.

# %%
home = np.array([0.0, -np.pi / 2, 0.0, -np.pi / 2, 0.0, 0.0])
print("families at home:", urkin.kinematics.singularities(ur5, home))
sigma = np.linalg.svd(urkin.jacobian(ur5, home), compute_uv=False)
print("singular values of J at home:",
      ", ".join(f"{s:.4f}" if s > 1e-12 else "<1e-12" for s in sigma))
print("rank of J at home:", np.linalg.matrix_rank(urkin.jacobian(ur5, home), tol=1e-9))

# %% [markdown]
# Seed 000 starts its UR3 inverse kinematics from exactly this pose, so its very first
# Newton step works with a Jacobian of rank 3: three directions of flange motion are simply
# not available there, and its damped least-squares inverse (see "What comes next") is what
# keeps that step finite. Starting an iterative solver at a singular configuration is asking for
# trouble; the IK lessons start elsewhere.
#
# ### Exercise 4.5 — `singularities` (5 points)
#
# Write `singularities(robot, q)`: the set of singular families present at `q`, a subset of
# `{"shoulder", "elbow", "wrist"}` (the empty set when `q` is regular). A family is present
# when its factor is zero up to a tolerance `tol = 1e-9`: $|\sin q_3| \le$ `tol` for the elbow,
# $|\sin q_5| \le$ `tol` for the wrist, and
# $|a_2\cos q_2 + a_3\cos(q_2+q_3) + d_5\sin(q_2+q_3+q_4)| \le$ `tol` (metres) for the
# shoulder. The lengths are `robot.a2`, `robot.a3` and `robot.d5` (metres, $a_2, a_3 < 0$).
#
# Use the factors, not the determinant: $\det J$ is a product, and a product can be tiny
# because one factor is small or because several are moderately small — it cannot say which
# family is present.
#
# *Checked* (the set of names, in any case, as a set, list or tuple): none at regular
# configurations (among them $\cos q_3 = 0$ and $\cos q_5 = 0$), and not none at singular
# ones; each family alone (the elbow and the wrist at 0, ±π and ±2π) and at their
# intersections, on random UR arms; and — one point — `tol`: a configuration whose factor is
# 10⁻⁸ … 10⁻³ from zero is regular at the default `tol = 1e-9`, singular for a `tol` ten times
# its factor, regular for a tenth. The feedback recognises a cosine test, a missing absolute
# value, a test of the angle itself, exact comparison with 0, an ignored `tol` or another
# default, a wrong shoulder factor, joint numbers off by one and an if/elif chain that returns
# one family. urkin's `singularities`, `singular_families`, `singularity_factors`,
# `manipulability` and `condition_number` are hidden while this exercise is graded.

# %%
def singularities(robot, q, tol=1e-9):
    """The singular families of a UR arm present at a configuration.

    Parameters
    ----------
    robot : urkin.Robot
        The arm; ``robot.a2``, ``robot.a3`` and ``robot.d5`` are its lengths in metres.
    q : array_like, shape (6,)
        Joint angles in radians.
    tol : float
        A factor of magnitude at most ``tol`` counts as zero (metres for the shoulder factor,
        dimensionless for the others).

    Returns
    -------
    set of str
        A subset of ``{"shoulder", "elbow", "wrist"}``: "shoulder" when
        a2 cos q2 + a3 cos(q2 + q3) + d5 sin(q2 + q3 + q4) = 0, "elbow" when sin q3 = 0,
        "wrist" when sin q5 = 0. Empty when ``q`` is not singular.
    """
    ### BEGIN SOLUTION
    angles = np.asarray(q, dtype=float)
    shoulder = (robot.a2 * np.cos(angles[1]) + robot.a3 * np.cos(angles[1] + angles[2])
                + robot.d5 * np.sin(angles[1] + angles[2] + angles[3]))
    found = set()
    if abs(shoulder) <= tol:
        found.add("shoulder")
    if abs(np.sin(angles[2])) <= tol:
        found.add("elbow")
    if abs(np.sin(angles[4])) <= tol:
        found.add("wrist")
    return found
    ### END SOLUTION


# %%
check("4.5", singularities)

# %% [markdown]
# ## 7. How far from trouble? Manipulability and the condition number
#
# "Singular or not" is a yes/no answer, and a robot gets into trouble well *before*
# $\det J = 0$. Two numbers measure how close a configuration is.
#
# **The velocity ellipsoid.** Let the joint rates range over all vectors of length 1,
# $\|\dot q\| \le 1$. The flange velocities $v = J_v \dot q$ they produce fill an ellipsoid,
# whose semi-axes point along the eigenvectors of $J_v J_v^\mathsf{T}$ and whose lengths are
# the singular values $\sigma_1 \ge \sigma_2 \ge \sigma_3$ of $J_v$ (m/s per rad/s). A round
# ellipsoid means the flange moves equally easily in every direction; a flat one means some
# direction costs large joint rates.
#
# **Manipulability** (Yoshikawa) is $w = \sqrt{\det(J J^\mathsf{T})}$, the product of the
# singular values, proportional to the ellipsoid's volume. For the full square $J$ it equals
# $|\det J|$ and vanishes exactly at singularities; `urkin.kinematics.manipulability(robot, q,
# part="position")` uses $J_v$ alone, for the velocity ellipsoid of the flange origin (m³/rad³).
#
# **The condition number** $\kappa = \sigma_{\max}/\sigma_{\min}$ of $J$ measures how
# *unequal* the directions are, whatever the arm's size; it grows without bound towards a
# singularity, and it is also the factor by which relative errors in a flange velocity can be
# amplified in the joint rates computed from it.
#
# The figure follows a UR5 as its elbow straightens from $q_3 = -1.6$ rad (bent at about a
# right angle) to the elbow singularity $q_3 = 0$, with the shoulder fixed and the wrist
# keeping the tool's direction ($q_2 + q_3 + q_4 = -\pi/2$). At five points it draws the
# flange's velocity ellipsoid, scaled by 0.15 (0.15 m of drawing per m/s).

# %%
path_s = np.linspace(0.0, 1.0, 101)  # path parameter
path = np.zeros((101, 6))
path[:, 1] = -0.6
path[:, 2] = -1.6 * (1.0 - path_s)  # the elbow opens from about 90° to straight, q3 = 0
path[:, 3] = -np.pi / 2 - path[:, 1] - path[:, 2]  # keeps q2 + q3 + q4 = −π/2
path[:, 4] = np.pi / 2

w_position = urkin.kinematics.manipulability(ur5, path, part="position")
w_full = urkin.kinematics.manipulability(ur5, path)
kappa = urkin.kinematics.condition_number(ur5, path)
Jv_path = urkin.jacobian(ur5, path)[:, :3, :]
sigma_v = np.linalg.svd(Jv_path, compute_uv=False)  # (101, 3), m/s per rad/s

ellipsoid_scale = 0.15  # metres of drawing per m/s
shown = [0, 25, 50, 75, 100]
shades = plt.cm.viridis(np.linspace(0.0, 0.85, len(shown)))  # one colour per drawn arm
U_shown, sigma_shown, _ = np.linalg.svd(Jv_path[shown])  # directions and lengths of semi-axes
shown_labels = [f"s = {path_s[k]:.2f}  (q3 = {round(np.degrees(path[k, 2])) + 0}°)" for k in shown]

urkin.plot.manipulability_figure(
    ur5, path[shown], U_shown * sigma_shown[:, None, :], shown_labels,
    s=path_s, semi_axes=sigma_v, condition=kappa, scale=ellipsoid_scale,
    manipulability={"position part: √det(J_v J_vᵀ) (m³/rad³)": w_position,
                    "full J: |det J| (units mixed)": w_full},
    center=(-0.4, -0.1, 0.45), half_width=0.5,
    s_label="path parameter s (0: q3 = −1.6 rad, 1: q3 = 0, the elbow singularity)",
    title="A UR5 approaching the elbow singularity")
plt.show()

print("   s    q3 (rad)   w position   w full      κ     smallest semi-axis (m/s per rad/s)")
for k in shown:
    condition = f"{kappa[k]:7.1f}" if kappa[k] < 1e6 else "  >1e15"
    print(f"{path_s[k]:5.2f}  {path[k, 2] + 0.0:8.2f}   {w_position[k]:9.4f}  {w_full[k]:8.4f}"
          f"  {condition}   {sigma_v[k, 2]:.4f}")

# %% [markdown]
# Follow the smallest semi-axis, $\sigma_3$. Once the elbow has opened a little (from s ≈ 0.25
# on) it points along the arm — from shoulder towards wrist — and it shrinks steadily as the
# elbow opens, from 0.22 to 0.016 m/s per rad/s: near a stretched elbow, moving the flange
# towards or away from the shoulder takes large joint rates. The other two axes grow at the same
# time, so manipulability, their product, first *rises* (the best configuration on this path has
# the elbow bent by about 50°) and only then falls. The condition number sees the imbalance all
# along: it starts to climb from s ≈ 0.2 and is infinite at the end, where the full
# manipulability $|\det J|$ is exactly zero.
#
# The position part does *not* reach zero. With the wrist bent ($q_5 = \pi/2$) the wrist
# joints can still nudge the flange origin along the arm, at the cost of turning the tool: the
# direction lost at this singularity is a combination of linear and angular velocity, not a
# pure translation. A position-only task can therefore pass closer to an elbow singularity
# than a full-pose task — but not through it comfortably: 0.016 m/s per rad/s means about
# 6 rad/s of joint speed for every 0.1 m/s along the arm.
#
# Manipulability has units and grows with the size of the arm, so compare it only between
# configurations of one arm; the condition number is dimensionless but mixes metres and
# radians when it uses the full $J$. Both are cheap, and both are worth logging along any
# planned path.
#
# ### Exercise 4.6 — `manipulability` (4 points)
#
# Write `manipulability(J)`: Yoshikawa's $w = \sqrt{\det(J J^\mathsf{T})}$ of any Jacobian
# `J` of shape `(m, n)` with $m \le n$ (the full 6 × 6 one, its 3 × 6 linear rows, or a
# Jacobian of another arm), as a float. Be careful at singularities: there $\det(J
# J^\mathsf{T})$ is zero on paper and may come out a hair *below* zero in floating point, and
# the square root of a negative number is NaN. (The product of the singular values of $J$ is
# the same number and avoids the issue.)
#
# *Checked* (to 1e-9, relative to $w$ when $w > 1$; a float32 answer to float32's precision):
# (2 points) random matrices of shapes 6 × 6, 3 × 6, 2 × 5 and 6 × 7; (1 point) square
# matrices with a negative determinant give $|\det J|$; (1 point) the 6 × 6 Jacobians of UR
# arms at the elbow ($q_3 = 0$) and wrist ($q_5 = 0$) singularities give 0 (below 1e-6: the
# square root of a round-off determinant can reach 1e-8), never NaN. The feedback recognises
# a missing square root, $J^\mathsf{T}J$ in place of $JJ^\mathsf{T}$, $\det J$ without its
# absolute value, the condition number, and NaN at a singularity. urkin's `manipulability`
# (and the rest of its singularity measures) is hidden while it is graded.

# %%
def manipulability(J):
    """Yoshikawa's manipulability w = √det(J Jᵀ) of a Jacobian.

    Parameters
    ----------
    J : array_like, shape (m, n), m ≤ n
        A Jacobian.

    Returns
    -------
    float
        w ≥ 0: the product of the singular values of J; 0 exactly at a singularity.
    """
    ### BEGIN SOLUTION
    J = np.asarray(J, dtype=float)
    return float(np.sqrt(max(np.linalg.det(J @ J.T), 0.0)))
    ### END SOLUTION


# %%
check("4.6", manipulability)

# %% [markdown]
# ### Exercise 4.7 — `elbow_lost_direction` (4 points)
#
# **Predict, then verify.** At an elbow singularity, $\sin q_3 = 0$, the arm is stretched out
# ($q_3 = 0$) or folded back ($q_3 = \pm\pi$) and $\det J = 0$: some motion is lost. Which
# one? Take a point small enough to reason about by hand: **wrist 1**, the origin $o_3$ of
# frame 3. It does not depend on $q_4, q_5, q_6$, so only joints 1–3 move it, with the
# velocity $J_3\,(\dot q_1, \dot q_2, \dot q_3)$, where column $i$ of the 3 × 3 position
# Jacobian $J_3$ is $z_{i-1} \times (o_3 - o_{i-1})$ — section 2's recipe with $o_3$ in place
# of the flange. At an elbow singularity $J_3$ has rank 2: the velocities wrist 1 can have
# fill a plane, and the direction perpendicular to that plane is lost.
#
# Predict it before computing anything. With the arm in line, in which direction does each
# of the three joints move wrist 1? Which plane do those three directions span, and what is
# perpendicular to it? Then write `elbow_lost_direction(robot, q)`: the lost direction as a
# unit vector in the base frame, shape `(3,)`, for joint angles `q` (radians) with
# $\sin q_3 = 0$ (`q[2]` is 0, ±π or ±2π; no other `q` is asked about). Either sign is right.
# `urkin.fk_frames(robot, q)[k]` is DH frame $k$ (entry 0 is the base frame); its origins and
# axes are all the answer needs — no derivatives, no SVD.
#
# *Checked* (up to sign, to 1e-9; a float32 answer to float32's precision): that it is a unit
# vector along the direction in which $J_3$ has no reach — the left singular vector of its
# smallest singular value, which the check computes — on random UR arms with wrist 1 at least
# a few centimetres off the base axis: at stretched elbows, $q_3 = 0$ and $\pm 2\pi$ (3
# points), and at folded ones, $q_3 = \pm\pi$ (1 point). The feedback recognises a vector
# that is not normalised, the shoulder axis $z_1$ (and $z_0 \times o_3$, which is parallel to
# it), the direction across the arm in its plane, a direction measured from the base origin
# instead of the shoulder, the flange in place of wrist 1, frame indices off by one and the
# base axis $z_0$.

# %%
def elbow_lost_direction(robot, q):
    """The direction in which wrist 1 cannot move at an elbow singularity.

    Parameters
    ----------
    robot : urkin.Robot
        The arm.
    q : array_like, shape (6,)
        Joint angles in radians with sin q3 = 0: the elbow stretched (q3 = 0, ±2π) or
        folded (q3 = ±π).

    Returns
    -------
    ndarray, shape (3,)
        A unit vector in the base frame (either sign) along which no motion of joints 1-3
        moves the origin of frame 3 (wrist 1).
    """
    ### BEGIN SOLUTION
    frames = urkin.fk_frames(robot, np.asarray(q, dtype=float))
    line = frames[3][:3, 3] - frames[1][:3, 3]  # shoulder to wrist 1: the arm's line
    return line / np.linalg.norm(line)
    ### END SOLUTION


# %%
check("4.7", elbow_lost_direction)

# %% [markdown]
# Now verify the prediction without any reasoning at all: differentiate wrist 1's position
# numerically (central differences, as in exercise 4.2) on the stretched UR5 of section 6 and
# take the SVD. The left singular vector of the zero singular value is the lost direction;
# the cell compares it with yours.

# %%
def wrist_1(q):
    """The origin of frame 3 (wrist 1) of the UR5, in the base frame (m)."""
    return urkin.fk_frames(ur5, q)[3, :3, 3]


q_stretched = np.array([0.3, -0.9, 0.0, -1.2, 1.1, 0.4])  # q3 = 0: the elbow straight
h_fd = 1e-6
J_wrist_1 = np.column_stack([(wrist_1(q_stretched + h_fd * unit_step)
                              - wrist_1(q_stretched - h_fd * unit_step)) / (2 * h_fd)
                             for unit_step in np.eye(6)[:3]])  # joints 1-3 only
U_w, sigma_w, _ = np.linalg.svd(J_wrist_1)
print(f"singular values of wrist 1's 3 × 3 position Jacobian: {sigma_w[0]:.4f}, "
      f"{sigma_w[1]:.4f} and {below(sigma_w[2], 1e-8)} m/rad")
try:
    predicted = np.asarray(elbow_lost_direction(ur5, q_stretched), dtype=float)
except NotImplementedError:
    print("exercise 4.7 is not written yet: nothing to compare")
else:
    angle = np.arctan2(np.linalg.norm(np.cross(predicted, U_w[:, 2])),
                       abs(predicted @ U_w[:, 2]))
    print(f"angle between your prediction and the lost direction: {below(angle, 1e-6)} rad")

# %% [markdown]
# ### Statics: the same Jacobian, transposed
#
# The Jacobian also says which joint torques hold a load. Let the flange push on the world (a
# payload, a workpiece) with a force $f$ (N) at its origin and a moment $m$ (N·m), together
# the **wrench**
# $F = [f;\ m]$ in the base frame, ordered like $[v;\ \omega]$. If the joints move by
# $\dot q$, the flange does work at the rate $F^\mathsf{T} [v;\ \omega] = F^\mathsf{T} J\dot q$
# and the motors at the rate $\tau^\mathsf{T}\dot q$. At rest (no acceleration, no friction,
# gravity on the links left out) the two balance for *every* $\dot q$, so
#
# $$\tau = J^\mathsf{T} F .$$
#
# No inverse is needed: torques follow from forces as directly as velocities follow from
# joint rates. (The moment $m$ is about the flange origin, the point whose velocity $v$ is;
# a wrench about another point pairs with the Jacobian of that point.)
#
# **The force ellipsoid.** Which forces can the arm hold, at the flange origin, with joint
# torques of length at most 1, $\|J_v^\mathsf{T} f\| \le 1$? With $J_v = U\Sigma V^\mathsf{T}$
# the answer is again an ellipsoid, with the **same** axes $U$ as the velocity ellipsoid and
# the **inverse** lengths $1/\sigma_i$ (N per N·m). The two are duals: a direction the flange
# moves in slowly is one it pushes in strongly. At an elbow singularity the force ellipsoid of
# wrist 1, which lies on the arm's line, stretches to infinity along the arm — the straight arm
# carries a push along itself in its structure, with no torque at all — while its velocity
# ellipsoid goes flat. The flange's, with the wrist bent, only grows long: at s = 1 its
# $\sigma_3$ is still 0.016 m/s per rad/s (section 7), a force semi-axis of about 61 N per N·m.

# %%
rng = np.random.default_rng(4)
q_load = path[0]
J_load = urkin.jacobian(ur5, q_load)
F = np.r_[rng.normal(size=3) * 20.0, rng.normal(size=3) * 2.0]  # N and N·m
tau = J_load.T @ F
rates = rng.normal(size=(100, 6))  # any joint rates: the power balance must hold for all
power_gap = np.abs(rates @ tau - (rates @ J_load.T) @ F).max()
assert power_gap < 1e-9
print(f"τ·q̇ = F·(J q̇) for 100 random q̇: largest difference {below(power_gap, 1e-9)} W")

hold = np.r_[0.0, 0.0, 2.0 * 9.81, 0.0, 0.0, 0.0]  # the flange pushes 2 kg up: F on the load
print("\njoint torques holding 2 kg at the flange origin, τ = Jᵀ F (N·m):")
for k in (0, 100):
    torques = (urkin.jacobian(ur5, path[k]).T @ hold).round(2) + 0.0  # + 0.0: no "-0.00"
    print(f"  s = {path_s[k]:.2f}: " + "  ".join(f"{t:7.2f}" for t in torques))

# at s = 1 the force ellipsoid is about 61 N per N·m long (1/σ3): too long to draw, left out
U_drawn, sigma_drawn = U_shown[:-1], sigma_shown[:-1, None, :]
urkin.plot.ellipsoid_panels(
    ur5, path[shown[:-1]],
    [("velocity ellipsoids of the flange origin (×0.15, m/s per rad/s)",
      U_drawn * sigma_drawn, 0.15),
     ("force ellipsoids of the flange origin (×0.03, N per N·m)", U_drawn / sigma_drawn, 0.03)],
    labels=[f"s = {path_s[k]:.2f}" for k in shown[:-1]], colors=shades[:-1],
    center=(-0.4, -0.1, 0.45), half_width=0.5,
    title="Velocity and force ellipsoids: the same axes, inverse lengths (UR5, base frame)")
plt.show()

print("   s    velocity semi-axes σ (m/s per rad/s)    force semi-axes 1/σ (N per N·m)")
for k in shown[:-1]:
    sigma = sigma_v[k]
    print(f"{path_s[k]:5.2f}   " + " ".join(f"{v:6.3f}" for v in sigma) + "          "
          + " ".join(f"{1 / v:6.2f}" for v in sigma))

# %% [markdown]
# The torque table is the lever rule at work: the same 2 kg costs the shoulder 4.2 N·m with
# the elbow bent and 15.1 N·m with the arm stretched out, because the flange is further from
# the shoulder axis. Joint 1 turns about the vertical, parallel to the weight, so it needs no
# torque; nor do joints 5 and 6 here: each of their axes meets the load's vertical line of
# action or runs parallel to it, so the weight has no lever about them.
#
# As the elbow opens, the smallest velocity semi-axis shrinks and the largest force
# semi-axis grows in step, along the same direction — along the arm. Near a singularity a
# robot is slow in some direction and, by the same token, stiff in it: a stretched arm is
# good for holding a push along itself and poor for moving along it.

# %% [markdown]
# ### Exercise 4.8 — `holding_torques` (4 points)
#
# A gripper holds a part of mass `mass` (kg) whose centre of mass is **not** at the flange
# origin: it sits at `r_com` (m), given **in the flange frame** (frame 6), as a gripper's data
# sheet gives it. Write `holding_torques(robot, q, mass, r_com)`: the joint torques (N·m,
# shape `(6,)`) the motors must apply to hold the part still at joint angles `q` (radians).
# Gravity is $g = 9.81$ m/s² along $-z_0$; leave out the weight of the links themselves.
#
# Think before you type: which force does the flange apply to the part, and which moment
# *about the flange origin* — the point whose velocity $v$ the geometric Jacobian gives? In
# which frame is $r_\text{com}$, and in which must the wrench be?
#
# *Checked* (to 1e-9 N·m, against $J^\mathsf{T} F$ with `urkin.jacobian`) on random UR arms,
# configurations and masses: a part with its centre of mass at the flange origin (2 points),
# and one with its centre of mass offset (2 points). The feedback recognises the torques
# that let the part fall (the sign of $F$), a wrench without its moment, an offset used as if
# it were in the base frame, the moment with its lever reversed, the mass used as a force
# (no $g$), and $J F$ in place of $J^\mathsf{T} F$.

# %%
def holding_torques(robot, q, mass, r_com):
    """Joint torques that hold a part of mass ``mass`` against gravity.

    Parameters
    ----------
    robot : urkin.Robot
        The arm.
    q : array_like, shape (6,)
        Joint angles (rad).
    mass : float
        The part's mass (kg).
    r_com : array_like, shape (3,)
        The part's centre of mass relative to the flange origin, in the flange frame (m).

    Returns
    -------
    ndarray, shape (6,)
        τ = Jᵀ F (N·m), F the wrench the flange applies to the part, about the flange origin,
        in the base frame; g = 9.81 m/s² along −z0.
    """
    ### BEGIN SOLUTION
    q = np.asarray(q, dtype=float)
    T_base_flange = urkin.fk(robot, q)
    f = np.array([0.0, 0.0, mass * 9.81])  # the flange holds the part up
    lever = T_base_flange[:3, :3] @ np.asarray(r_com, dtype=float)  # flange origin → COM, base
    return urkin.jacobian(robot, q).T @ np.r_[f, np.cross(lever, f)]
    ### END SOLUTION


# %%
check("4.8", holding_torques)

# %% [markdown]
# Verify it without any Jacobian. Holding the part still, the motors do work only against
# gravity, so the torques are the slope of the part's potential energy $V(q) = m g\,
# z_\text{com}(q)$: $\tau_i = \partial V/\partial q_i$. The cell differentiates $V$ numerically
# through `urkin.fk` and compares.

# %%
q_hold, r_part, m_part = path[40], np.array([0.03, -0.02, 0.12]), 1.5  # rad, m (flange), kg


def potential_energy(q):
    """m g z of the part's centre of mass (J)."""
    return m_part * 9.81 * (urkin.fk(ur5, q) @ np.r_[r_part, 1.0])[2]


tau_energy = np.array([(potential_energy(q_hold + 1e-6 * e) - potential_energy(q_hold - 1e-6 * e))
                       / 2e-6 for e in np.eye(6)])
print("∂V/∂q (N·m):", "  ".join(f"{t:6.2f}" for t in tau_energy.round(2) + 0.0))
try:
    tau_yours = np.asarray(holding_torques(ur5, q_hold, m_part, r_part), dtype=float)
except NotImplementedError:
    print("exercise 4.8 is not written yet: nothing to compare")
else:
    gap = np.abs(tau_yours - tau_energy).max()
    print(f"largest difference from your holding_torques: {below(gap, 1e-6)} N·m")

# %% [markdown]
# ### Exercise 4.9 — `ellipsoid_axes` (4 points)
#
# Section 7 drew the flange's velocity ellipsoids and followed the condition number (of the
# whole $J$) towards the elbow singularity, and the statics section drew the force ellipsoids
# beside them, with the same axes and inverse lengths. The ellipsoids took the SVD of $J_v$
# inline; its condition number $\sigma_1/\sigma_3$ is the same measure for the position part
# alone. Now put the method
# into one function, one that gives an honest answer at a singularity too.
#
# Write `ellipsoid_axes(J_v)` for a position Jacobian `J_v` of shape `(3, n)`, $n \ge 3$
# (m/s per rad/s), returning a tuple `(U, velocity, force, condition)`:
#
# * `U`, shape `(3, 3)`: the principal directions as unit columns, column $i$ along the
#   $i$-th semi-axis. Each column may have either sign; `U` need not be right-handed (and may
#   be);
# * `velocity`, shape `(3,)`: the semi-axes $\sigma_1 \ge \sigma_2 \ge \sigma_3$ of the
#   velocity ellipsoid $\{J_v \dot q : \|\dot q\| \le 1\}$ — the singular values of $J_v$,
#   largest first (m/s per rad/s);
# * `force`, shape `(3,)`: the force ellipsoid's semi-axes $1/\sigma_i$ in the same column
#   order (N per N·m), and `np.inf` where $\sigma_i$ counts as zero;
# * `condition`, a float: $\sigma_1/\sigma_3$, and `np.inf` when $\sigma_3$ counts as zero.
#
# A singular value **counts as zero** when $\sigma_i \le 10^{-12}\,\sigma_1$. At a singularity
# the SVD returns round-off of order $10^{-16}\sigma_1$, only sometimes an exact 0, and
# $1/\sigma$ of round-off is a meaningless huge number, not a force the arm can hold. Take the
# singular values of $J_v$ itself (`np.linalg.svd`): the eigenvalues of $J_v J_v^\mathsf{T}$
# are $\sigma_i^2$ with round-off of about $10^{-16}\sigma_1^2$, so their square roots cannot
# resolve any $\sigma$ below about $10^{-8}\sigma_1$.
#
# *Checked* in float64 (float32 cannot resolve $10^{-12}\sigma_1$): velocity and `U` to 1e-9,
# `U` column by column up to sign, force and condition to 1e-9 relative, and `inf` must be
# `inf`. (2 points) The flange position Jacobians of random UR arms at random configurations
# (`urkin.position_jacobian`), against the SVD; (1 point) random 3 × 3, 3 × 6 and 3 × 7
# matrices; (1 point) singular ones — wrist 1's position Jacobian (3 × 3, or 3 × 6 with zero
# columns for joints 4–6; exercise 4.7) at stretched and folded elbows, where the force
# semi-axis along the arm and the condition number must be `inf`, not a huge finite number or
# NaN, and a 3 × 7 matrix of rank 2 — and a 3 × 7 matrix with $\sigma_3 = 10^{-5}\sigma_1$,
# small but not zero, where everything must be finite. Every test matrix has semi-axes at
# least 5 % of $\sigma_1$ apart, so its directions are well defined. The feedback recognises
# $\sigma^2$ (the eigenvalues of $JJ^\mathsf{T}$) for $\sigma$, rows of $V^\mathsf{T}$
# (directions in joint space) for `U`, semi-axes sorted ascending, force semi-axes equal to
# $\sigma$ or in descending order, the condition number upside down ($\sigma_3/\sigma_1$) or
# squared (that of $JJ^\mathsf{T}$), round-off used as a singular value, square roots of
# eigenvalues at a singularity, a zero threshold far above round-off, and float32. Nothing of
# urkin is hidden: it has no ellipsoid function.

# %%
def ellipsoid_axes(J_v):
    """Principal axes of the velocity and force ellipsoids of a position Jacobian.

    Parameters
    ----------
    J_v : array_like, shape (3, n), n ≥ 3
        A position Jacobian (m/s per rad/s), such as ``urkin.position_jacobian(robot, q)``.

    Returns
    -------
    U : ndarray, shape (3, 3)
        The principal directions as unit columns (each up to its sign), column i along
        semi-axis i.
    velocity : ndarray, shape (3,)
        The semi-axes σ1 ≥ σ2 ≥ σ3 of the velocity ellipsoid {J_v q̇ : ‖q̇‖ ≤ 1}
        (m/s per rad/s).
    force : ndarray, shape (3,)
        The semi-axes 1/σ_i of the force ellipsoid {f : ‖J_vᵀ f‖ ≤ 1}, in the same order
        (N per N·m); inf where σ_i ≤ 1e-12 σ1.
    condition : float
        σ1/σ3; inf when σ3 ≤ 1e-12 σ1.
    """
    ### BEGIN SOLUTION
    U, sigma, _ = np.linalg.svd(np.asarray(J_v, dtype=float))
    zero = sigma <= 1e-12 * sigma.max()  # round-off, not a semi-axis (σ1 is the largest)
    force = np.full(3, np.inf)
    force[~zero] = 1.0 / sigma[~zero]
    condition = np.inf if zero[2] else float(sigma[0] / sigma[2])
    return U, sigma, force, condition
    ### END SOLUTION


# %%
check("4.9", ellipsoid_axes)

# %% [markdown]
# Verify what the numbers mean without another SVD, on section 7's path. The smallest joint
# rates that give the flange the velocity $\sigma_i u_i$, $\dot q = J_v^\mathsf{T}(J_v
# J_v^\mathsf{T})^{-1}\sigma_i u_i$, must have length exactly 1 — the velocity ellipsoid's
# edge —, and the force $u_i/\sigma_i$ must need joint torques $J_v^\mathsf{T} f$ of length
# exactly 1 — the force ellipsoid's edge. Then the stretched elbow: the flange at s = 1, and
# wrist 1 of exercise 4.7's stretched UR5, whose position Jacobian is built from the frames.

# %%
def edge_gap(J_v, U, velocity, force):
    """Largest |‖q̇‖ − 1| and |‖τ‖ − 1| over the semi-axes with a finite force."""
    J_v = np.asarray(J_v, dtype=float)
    gaps = []
    for i in np.flatnonzero(np.isfinite(force)):
        q_dot = J_v.T @ np.linalg.solve(J_v @ J_v.T, velocity[i] * U[:, i])  # smallest q̇
        torques = J_v.T @ (force[i] * U[:, i])
        gaps += [abs(np.linalg.norm(q_dot) - 1.0), abs(np.linalg.norm(torques) - 1.0)]
    return max(gaps)


def listed(values, decimals):
    return ", ".join(f"{v:.{decimals}f}" for v in values)


frames_stretched = urkin.fk_frames(ur5, q_stretched)  # exercise 4.7's UR5, q3 = 0
o3 = frames_stretched[3, :3, 3]
J_wrist_exact = np.column_stack([np.cross(frames_stretched[i, :3, 2],
                                          o3 - frames_stretched[i, :3, 3]) for i in range(3)])
arm_line = o3 - frames_stretched[1, :3, 3]  # shoulder to wrist 1
try:
    U_mid, velocity_mid, force_mid, condition_mid = ellipsoid_axes(Jv_path[50])
except NotImplementedError:
    print("exercise 4.9 is not written yet: nothing to verify")
else:
    _, _, force_end, condition_end = ellipsoid_axes(Jv_path[100])
    U_w1, _, force_w1, condition_w1 = ellipsoid_axes(J_wrist_exact)
    U_mid, U_w1 = np.asarray(U_mid, dtype=float), np.asarray(U_w1, dtype=float)
    print(f"s = 0.50, the flange: velocity semi-axes {listed(velocity_mid, 3)} m/s per rad/s, "
          f"force semi-axes {listed(force_mid, 3)} N per N·m, condition {condition_mid:.2f}")
    gap = edge_gap(Jv_path[50], U_mid, np.asarray(velocity_mid), np.asarray(force_mid))
    print(f"  ‖q̇‖ and ‖τ‖ at the ellipsoids' edges differ from 1 by {below(gap, 1e-12)}")
    print(f"s = 1.00, the flange: force semi-axes {listed(force_end, 2)} N per N·m, "
          f"condition {condition_end:.1f}")
    print(f"stretched elbow, wrist 1: force semi-axes {listed(force_w1, 3)} N per N·m, "
          f"condition {condition_w1}")
    angle = np.arctan2(np.linalg.norm(np.cross(U_w1[:, 2], arm_line)), abs(U_w1[:, 2] @ arm_line))
    print(f"  angle between its infinite force axis and the arm: {below(angle, 1e-9)} rad")

# %% [markdown]
# At the end of section 7's path the whole $J$ is singular (the elbow), but the flange's position
# Jacobian $J_v$ is not: joint torques of length 1 N·m hold a push of 61 N along the arm, and
# $J_v$'s condition number is about 67 — close to trouble, because the bent wrist can still nudge
# the flange origin along the arm. Wrist 1, on the arm's line, is singular: its force ellipsoid is
# infinite along the arm, and so is its condition number. (At a singularity the SVD returns
# $\sigma_3 = 0$ exactly or round-off near $10^{-16}\sigma_1$, depending on the arithmetic; the
# threshold makes the answer `inf` either way.)
#
# ### Exercise 4.10 — `space_from_geometric` (3 points)
#
# Section 5 related the geometric Jacobian to the space Jacobian of lesson 03: the same
# $\omega$, the velocity taken at the base origin instead of the flange origin, $v_s = v + p
# \times \omega$, and the rows in twist order. It left the conversion to
# `urkin.poe.space_from_geometric`; now write it yourself.
#
# Write `space_from_geometric(J, T)`: the space Jacobian of *Modern Robotics*, rows
# $(\omega;\ v_s)$, shape `(6, n)`, from the geometric Jacobian `J` of shape `(6, n)` — rows
# $[v;\ \omega]$ of the flange origin, in base coordinates — at the flange pose `T`, shape
# `(4, 4)`, in the base frame. Column $i$ is $(\omega_i,\ v_i + p \times \omega_i)$ with $p$ =
# `T[:3, 3]` the flange origin (m). `J` may have any number of columns $n \ge 1$.
#
# *Checked* (to 1e-10): (2 points) `urkin.jacobian` and `urkin.fk` of random UR arms at
# random configurations, against `urkin.poe.jacobian_space(S, q)` with the arm's space screw
# axes; (1 point) random `J` with 1 to 7 columns and random poses `T`. The feedback recognises
# rows not reordered, the lever's sign ($v - p \times \omega$), $p$ of the base (zero), from
# `T`'s third column or in flange coordinates, the body Jacobian ($\mathrm{Ad}_{T^{-1}}J_s$),
# the conversion run backwards, a transposed result and six columns assumed. urkin's
# Jacobians and conversions (`urkin.jacobian`, `urkin.poe.jacobian_space`, `jacobian_body`,
# `space_from_geometric`, `geometric_from_space`, and what uses them) are hidden while it is
# graded; `np.cross` and `urkin.transforms.adjoint` are not.

# %%
def space_from_geometric(J, T):
    """Space Jacobian (ω; v_s) from the geometric Jacobian [v; ω] of the flange origin.

    Parameters
    ----------
    J : array_like, shape (6, n)
        Geometric Jacobian: rows 0–2 the velocity v of the flange origin (m/s per rad/s),
        rows 3–5 the angular velocity ω (rad/s per rad/s), both in base coordinates.
    T : array_like, shape (4, 4)
        The flange pose in the base frame (metres).

    Returns
    -------
    ndarray, shape (6, n)
        Rows (ω; v_s) with v_s = v + p × ω, p = T[:3, 3]: the velocity of the body point at
        the base origin (twist order, as in Modern Robotics).
    """
    ### BEGIN SOLUTION
    J = np.asarray(J, dtype=float)
    p = np.asarray(T, dtype=float)[:3, 3]  # the flange origin, base coordinates
    v, omega = J[:3], J[3:]
    return np.vstack([omega, v + np.cross(p, omega, axis=0)])
    ### END SOLUTION


# %%
check("4.10", space_from_geometric)

# %% [markdown]
# Verify it from the definition, without any Jacobian formula: $v_s$ is the velocity of the
# point of the flange body that is passing through the base origin. That point sits at
# $x = T^{-1}(0, 0, 0, 1)$ in flange coordinates; nudge each joint by $\pm h$, see where
# `urkin.fk` carries it, and divide by $2h$ (the UR5 at `q_demo`).

# %%
T_demo = urkin.fk(ur5, q_demo)
x_body = np.linalg.solve(T_demo, [0.0, 0.0, 0.0, 1.0])  # the body point at the base origin
h_fd = 1e-6
v_s_moved = np.column_stack([((urkin.fk(ur5, q_demo + h_fd * e) - urkin.fk(ur5, q_demo - h_fd * e))
                              @ x_body)[:3] / (2 * h_fd) for e in np.eye(6)])
try:
    J_s_yours = np.asarray(space_from_geometric(J_demo, T_demo), dtype=float)
except NotImplementedError:
    print("exercise 4.10 is not written yet: nothing to compare")
else:
    print(f"rows 3–5 (v_s) against the moved body point: largest difference "
          f"{below(np.abs(J_s_yours[3:] - v_s_moved).max(), 1e-8)} m/s per rad/s")
    print(f"rows 0–2 (ω) against the geometric J's last rows: largest difference "
          f"{below(np.abs(J_s_yours[:3] - J_demo[3:]).max(), 1e-12)} rad/s per rad/s")
    print(f"column 1 (joint 1 turns about the base z axis, through the base origin): |v_s| "
          f"{below(np.abs(J_s_yours[3:, 0]).max(), 1e-12)} m/s per rad/s")

# %% [markdown]
# ### Exercise 4.11 — `complex_step_jacobian` (3 points)
#
# Section 4 measured the complex step on the UR5's flange position: evaluate the function at
# $q + \mathrm{i}h e_j$ and keep $\operatorname{Im} f / h$ — no subtraction, so nothing
# cancels, and below $h \approx 10^{-8}$ it matched the exact Jacobian to machine precision,
# far beyond the best central difference. There it was one vectorised line through
# `urkin.fk`; exercise 4.2 turned central differences into a function of any `f`. Now do the
# same for the complex step.
#
# Write `complex_step_jacobian(position, q, h=1e-20)`: the Jacobian of `position` at `q` by the
# complex step, as a float array of shape `(m, n)`, where `q` has `n` real entries (an array
# or a list) and `position(x)` returns `m` numbers. `position` accepts complex arguments, as
# `lambda q: urkin.fk(robot, q)[:3, 3]` does. Column `j` is
# $\operatorname{Im} f(q + \mathrm{i}h e_j) / h$: build each nudged point as a new *complex*
# array (`q + 1j * h * e_j`; a float array cannot hold `1j * h` — numpy refuses the
# assignment, or warns and drops the imaginary part).
#
# *Checked* in float64 (the complex step's whole point is float64's last digits): (1 point) the
# Jacobians of random polynomials $Ax + (Bx) \circ (Cx) + b$ and of $\sin(Ax) \circ \exp(Bx)$
# with $m \ne n$, against their exact derivatives, with the default step, to 1e-8, once with
# `q` a plain list; (1 point) the flange position of random UR arms through `urkin.fk`,
# against urkin's exact $\partial p/\partial q$ to 1e-12 — beyond central differences at any
# step (about 1e-11 at their best, 1e-10 at $h = 10^{-6}$); (1 point) the step `h` you are
# given: at $h = 0.4$, $2^{-3}$ and $0.25$ the complex step differs from the derivative by
# $O(h^2)$, and $\operatorname{Im} f(q + \mathrm{i}h e_j)/h$ must come out to 1e-12. The
# feedback recognises real-step central or forward differences, the real part for the
# imaginary one, a missing or doubled division by h, a flipped sign, a step that was lost (all
# zeros), every entry nudged at once or steps piling up, a transposed result, complex numbers
# returned, an ignored `h`, and float32. urkin's Jacobians (`urkin.jacobian`,
# `urkin.kinematics.position_jacobian` and the ones built on them) are hidden while this
# exercise is graded; `urkin.fk` is not.

# %%
def complex_step_jacobian(position, q, h=1e-20):
    """Jacobian of an analytic function by the complex step.

    Parameters
    ----------
    position : callable
        ``position(x)`` takes an array of shape ``(n,)``, complex entries included, and returns
        ``m`` numbers (array_like, shape ``(m,)``), for example
        ``lambda q: urkin.fk(robot, q)[:3, 3]``.
    q : array_like, shape (n,)
        The real point at which to differentiate (for a UR arm: joint angles in radians).
    h : float
        Imaginary step size, in the units of ``q``.

    Returns
    -------
    ndarray, shape (m, n)
        Entry ``[k, j]`` is Im f_k(q + i h e_j) / h ≈ ∂f_k/∂q_j, with an error of order h²
        and no cancellation: one row per output, one column per input.
    """
    ### BEGIN SOLUTION
    q = np.asarray(q, dtype=float)
    columns = []
    for j in range(q.size):
        step = np.zeros(q.size, dtype=complex)
        step[j] = 1j * h
        columns.append(np.imag(np.asarray(position(q + step))).ravel() / h)
    return np.column_stack(columns)
    ### END SOLUTION


# %%
check("4.11", complex_step_jacobian)

# %% [markdown]
# Verify it at section 4's configuration `q_fd` of the UR5, against urkin's exact
# $\partial p/\partial q$ there (`exact`), next to a central difference at the default step of
# exercise 4.2. Then hand it a position function that quietly drops the imaginary part, as
# most numeric code does (here by `np.real`): the complex step cannot notice that, and every
# entry comes out zero.

# %%
def ur5_position(q):
    """The UR5's flange position (m); urkin.fk accepts complex joint angles."""
    return urkin.fk(ur5, q)[:3, 3]


central_default = np.column_stack([(ur5_position(q_fd + 1e-6 * e) - ur5_position(q_fd - 1e-6 * e))
                                   / 2e-6 for e in np.eye(6)])
try:
    J_complex = np.asarray(complex_step_jacobian(ur5_position, q_fd), dtype=float)
except NotImplementedError:
    print("exercise 4.11 is not written yet: nothing to compare")
else:
    print(f"your complex step against the exact ∂p/∂q: largest difference "
          f"{below(np.abs(J_complex - exact).max(), 1e-14)} m/rad")
    print(f"central differences at h = 1e-6, for comparison: "
          f"{below(np.abs(central_default - exact).max(), 1e-9)} m/rad")
    J_dropped = np.asarray(complex_step_jacobian(lambda q: ur5_position(np.real(q)), q_fd),
                           dtype=float)
    print("through a function that drops the imaginary part, every entry is zero:",
          bool(np.all(J_dropped == 0.0)))

# %% [markdown]
# ## Summary
#
# * The geometric Jacobian maps joint rates to the flange's $[v;\ \omega]$ in the base frame,
#   linear part first. Column $i$ is $[z_{i-1} \times (p - p_{i-1});\ z_{i-1}]$, read off the DH
#   frames: joint $i$'s axis and the lever arm from it to the flange.
# * Its linear rows are $\partial p/\partial q$: differentiating the symbolic $p$ gives the
#   same eighteen entries. Seed 002 differentiated correctly, but its $p$ was wrong, so ten
#   entries of its Jacobian are wrong — six of them even where $q_2 + q_3 + q_4 = 90°$, the
#   kind of pose at which its $p$ is right.
# * Finite differences check any Jacobian. Central differences are second order; with
#   $h \approx 10^{-6}$ to $10^{-5}$ they are accurate to about $10^{-10}$ or better, while
#   forward differences stop near $10^{-8}$. The complex step avoids cancellation altogether
#   and is exact to round-off for any function built of analytic operations that accepts
#   complex numbers (exercise 4.11).
# * Space and body Jacobians map to twists $(\omega, v)$; $J_s = \mathrm{Ad}_T J_b$, and
#   $v_s = v + p \times \omega$ connects the space Jacobian to the geometric one.
# * For every UR arm, $\det J = a_2 a_3 \sin q_3 \sin q_5\,(a_2 c_2 + a_3 c_{23} + d_5 s_{234})$:
#   the elbow, wrist and shoulder singular families. Home is all three at once, rank 3.
# * Manipulability and the condition number measure the distance to trouble before it arrives.
# * Statics uses the same matrix transposed: a wrench $F = [f;\ m]$ at the flange is held by
#   the joint torques $\tau = J^\mathsf{T} F$. The force ellipsoid has the velocity
#   ellipsoid's axes and inverse lengths: slow directions are strong ones.
#
# ## What comes next
#
# **Numerical inverse kinematics** runs this lesson backwards: to reach a target pose, take
# the pose error, solve $J\,\Delta q = $ error for a joint step, and repeat — Newton–Raphson,
# as seeds 000 and 002 do. Near singularities $J^{-1}$ produces enormous steps, so the solvers
# use the pseudo-inverse, **damped least squares** $J^\mathsf{T}(JJ^\mathsf{T} +
# \lambda^2 I)^{-1}$ and Levenberg–Marquardt, and watch the condition number.
#
# Before you move on: restart the kernel and run the whole notebook. All eleven check cells
# should report full marks.
