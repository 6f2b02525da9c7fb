# %% [markdown]
# # Lesson 03 — The product of exponentials
#
# Lesson 02 computed the flange pose as a product of six DH link transforms. This lesson does
# the same job a second way, the *product of exponentials* (PoE) of Lynch and Park's
# *Modern Robotics*:
#
# $$T(q) = e^{[S_1]q_1}\, e^{[S_2]q_2} \cdots e^{[S_6]q_6}\, M .$$
#
# Each factor is the motion of one joint, described by a *screw axis* $S_i$: the joint's axis
# written in one fixed frame. $M$ is where the flange is when every joint is at zero. That is
# all PoE needs — no frame per link, no table tied to a convention. Along the way you meet
# twists and their ordering (ω, v), which is *not* the ordering of the course's geometric
# Jacobian; rebuild the UR3 screw axes that seed report 001 read out of a robot simulator and
# check its printed numbers; get screw axes automatically from a DH table; and reproduce a
# worked UR5 example from *Modern Robotics*.
#
# **What you will be able to do**
#
# * write the screw axis of a revolute joint from its direction and a point, and read back
#   from a screw axis where the joint's axis passes (exercises 3.1 and 3.6);
# * compute the motion $e^{[S]\theta}$ of a turn about a screw axis in closed form, and say
#   why its translation is not simply $v\theta$ (exercise 3.2);
# * compute a UR arm's flange pose by the product of exponentials, in the *space* form and
#   the *body* form, matching lesson 02's DH forward kinematics (exercises 3.3 and 3.4);
# * go back from a pose to its twist with the matrix logarithm, including its two special
#   cases, θ = 0 and θ = π (exercise 3.5);
# * turn space screw axes into body screw axes with the adjoint of $M^{-1}$, written
#   yourself (exercise 3.7);
# * read the space screw axes and the home pose $M$ of any arm straight off its DH table
#   (exercise 3.8).
#
# **Time:** about two hours. **You need:** lesson 01 (transforms, skew matrices, Rodrigues'
# formula, the exponential map) and lesson 02 (DH frames and forward kinematics).

# %%
import matplotlib.pyplot as plt
import numpy as np

import urkin
import urkin.plot
import urkin.poe
from urkin.course import below, check
from urkin.transforms import (
    adjoint,
    inv_transform,
    make_transform,
    rot_z,
    se3_exp,
    se3_log,
    skew,
    so3_exp,
    twist_matrix,
)

np.set_printoptions(precision=4, suppress=True)

# %% [markdown]
# Three of `urkin.poe`'s functions — `screw_axis`, `fk_space` and `fk_body` — have the names
# of this lesson's exercises. Once you have run an exercise cell, the bare name means *your*
# function, so every demonstration spells urkin's version in full: `urkin.poe.fk_space`.
#
# ## 1. Why another formulation?
#
# The DH recipe of lesson 02 works, but it asks a lot. You must attach a frame to every link
# by a set of rules, the rules come in two conventions whose tables look alike and mean
# different arms, and where two joint axes are parallel (UR's joints 2, 3 and 4) the rules
# leave a choice that has to be settled by convention.
#
# The product of exponentials asks for much less:
#
# 1. choose **one** fixed frame — the *space frame*, here the robot's base;
# 2. put the arm at $q = 0$ and, for each joint, write down the direction of its axis and any
#    point on it, both in that one frame;
# 3. write down **M**, the pose of the end effector (for us the flange) at $q = 0$.
#
# Nothing else: no link frames, no four-number rules. The price is the maths of twists,
# which the rest of this section introduces.
#
# ### Twists
#
# A rigid body moving in space has, at each instant, an angular velocity ω and a velocity for
# each of its points. Those velocities are not independent: a point at position $r$ moves with
# $\dot r = v + \omega \times r$, where $v$ is the velocity of the body point that is
# *currently at the origin* of the frame (the body may not even cover the origin — imagine it
# extended rigidly). The pair
#
# $$\mathcal{V} = (\omega, v) \in \mathbb{R}^6$$
#
# is the body's **twist**, expressed in that frame. Both parts matter, and $v$ is easy to
# misread: it is not the velocity of the body's centre or of the tool, but of the point at the
# origin.
#
# ### Screw axes of revolute joints
#
# A revolute joint turns everything beyond it about a fixed line: unit direction ω through a
# point $q$. (Modern Robotics calls this point $q$; it is a position in metres, not a joint
# angle.) At a joint rate of 1 rad/s a point $r$ of the moving part travels with
# $\omega \times (r - q)$, so the point at the origin has velocity $-\omega \times q$. The
# **screw axis** of the joint is the twist at unit joint rate:
#
# $$S = (\omega,\ v) = (\omega,\ -\omega \times q) .$$
#
# Any point of the line gives the same $S$: sliding $q$ along ω adds a multiple of
# $\omega \times \omega = 0$. (A general screw also slides along its line, $v = -\omega \times
# q + h\omega$ with a *pitch* $h$, and a prismatic joint has $\omega = 0$ and $v$ equal to its
# direction; UR arms have only revolute joints, $h = 0$.) In matrix form a twist becomes the
# 4×4 matrix $[S]$, the twist analogue of lesson 01's skew matrix:
#
# $$[S] = \begin{bmatrix} [\omega] & v \\ 0\;0\;0 & 0 \end{bmatrix} .$$
#
# **Orderings — read this twice.** Modern Robotics, this lesson and `urkin.poe` write every
# twist and screw axis as **(ω, v): angular part first**. The course's geometric Jacobian,
# `urkin.jacobian` (lesson 04), stacks its rows the other way round, **[v; ω]: linear part
# first**, and its v is the velocity of the *flange origin*, not of the point at the base
# origin. A 6-vector does not say which order it uses, and a (v, ω) vector read as (ω, v)
# describes a plausible and completely different motion. The check of exercise 3.1
# recognises that slip. When you need to go from one to the other,
# `urkin.poe.space_from_geometric` and `urkin.poe.geometric_from_space` convert.
#
# A small example: a vertical axis, ω = (0, 0, 1), through the point (0.5, 0, 0) m.

# %%
S_vertical = urkin.poe.screw_axis([0.0, 0.0, 1.0], [0.5, 0.0, 0.0])
print(f"S = (ω, v) = {S_vertical}")
print("[S] =")
print(twist_matrix(S_vertical) + 0.0)

# v is the velocity of the body point at the origin: differentiate e^[S]θ at θ = 0
h = 1e-6
origin = np.array([0.0, 0.0, 0.0, 1.0])
velocity = (se3_exp(h * S_vertical) @ origin - origin)[:3] / h
print(f"velocity of the point at the origin, by finite differences: "
      f"{velocity.round(4) + 0.0} m/s per rad/s")

swapped = np.r_[S_vertical[3:], S_vertical[:3]]  # the same numbers, read as (v, ω)
for name, V in [("(ω, v), right", S_vertical), ("(v, ω), swapped", swapped)]:
    moved = (se3_exp(V * np.pi / 2) @ origin)[:3]
    print(f"{name:<16}: θ = π/2 takes the origin to {moved.round(4) + 0.0} m")

# %% [markdown]
# The origin sits 0.5 m from the axis, so turning about it at 1 rad/s moves the origin at
# 0.5 m/s along −y, exactly $v$. A quarter turn carries it round to (0.5, −0.5, 0). The swapped
# vector, read as (ω, v), is a turn at 0.5 rad/s about a horizontal line parallel to y through
# (−2, 0, 0): the same six numbers, a different motion altogether.
#
# ## 2. Screw axes by hand: seed report 001
#
# Seed report 001 simulated a UR3 in the robot simulator V-REP and used exactly this recipe.
# It placed the robot at the world origin, read the position $q_n$ of every joint from the
# simulator, took the axis directions $a_n$ from a drawing of the arm in its zero
# configuration (standing straight up), and printed the resulting screw-axis matrix with one
# column per joint. Let us rebuild that matrix column by column.

# %%
seed_axes = np.array(  # a_n: unit joint axes, in the seed's world frame
    [
        [0.0, 0.0, 1.0],
        [-1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        [-1.0, 0.0, 0.0],
    ]
)
seed_points = np.array(  # q_n: a point on each axis, metres, read from the simulator
    [
        [0.0, 0.0, 0.1045],
        [-0.116, 0.0, 0.109],
        [-0.117, 0.0, 0.353],
        [-0.118, 0.0, 0.566],
        [-0.112, 0.0, 0.65],
        [-0.112, 0.0, 0.651],
    ]
)
S_seed_hand = np.zeros((6, 6))
for joint in range(6):  # column i is the screw axis of joint i + 1
    S_seed_hand[:, joint] = urkin.poe.screw_axis(seed_axes[joint], seed_points[joint])

S_seed_printed = np.array(  # the matrix as the report prints it
    [
        [0.0, -1.0, -1.0, -1.0, 0.0, -1.0],
        [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, -0.109, -0.352, -0.566, 0.112, -0.651],
        [0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    ]
)
print("S from the listed axes and points (one column per joint):")
print(S_seed_hand + 0.0)
difference = S_seed_hand - S_seed_printed
for row, col in zip(*np.nonzero(np.abs(difference) > 1e-12)):
    print(f"differs from the printed S in row {row + 1}, column {col + 1}: "
          f"{S_seed_hand[row, col]:.3f} computed, {S_seed_printed[row, col]:.3f} printed, "
          f"{1000 * abs(difference[row, col]):.0f} mm apart")

# %% [markdown]
# Five columns match exactly; column 3 says −0.352 where the listed point gives −0.353.
# That is a rounding of 1 mm somewhere between the simulator and the page, harmless but worth
# knowing when you compare numbers later.
#
# Work one column through by hand to see where the numbers come from. Joint 2 turns about
# ω = (−1, 0, 0) through q = (−0.116, 0, 0.109):
#
# $$\omega \times q = (0\cdot 0.109 - 0\cdot 0,\ \ 0\cdot(-0.116) - (-1)\cdot 0.109,\ \
# (-1)\cdot 0 - 0\cdot(-0.116)) = (0,\ 0.109,\ 0),$$
#
# so $v = -\omega \times q = (0, -0.109, 0)$. For every horizontal axis along −x (all the
# points have y = 0), $v$ is
# $(0, -h, 0)$ with $h$ the axis' height; for the vertical joint 5 it is $(q_y, -q_x, 0) =
# (0, 0.112, 0)$. Two things are *absent* from S, and rightly so: the height of $q_1$ (joint 1's
# axis passes through the origin, whatever point of it you quote, so $v = 0$) and the x
# coordinates −0.116, −0.117, −0.118 of the horizontal axes, which only say where along each
# axis the simulator put its joint. A screw axis describes a line, not a point on it.
#
# ### Exercise 3.1 — `screw_axis` (3 points)
#
# Write `screw_axis(w, q)`: the screw axis of a revolute joint turning about the unit
# direction `w` through the point `q` (metres), as a numpy array of shape `(6,)` in the order
# **(ω, v)**, with $v = -\omega \times q$ (`np.cross` computes cross products).
#
# *Checked* (to 1e-9; a float32 answer to float32's precision): $(\omega, -\omega \times q)$
# for random unit axes and points; and that `S` describes the axis, not the point — moving `q`
# along `w` leaves it unchanged, a parallel axis elsewhere changes it. The feedback recognises
# a wrong sign of $v$, the point used as $v$, `w` and `q` swapped, the (v, ω) order and a
# (2, 3) array. urkin's `urkin.poe.screw_axis` (and `space_screws`, `body_screws`, which use
# it) is hidden while this exercise is graded.

# %%
def screw_axis(w, q):
    """Screw axis of a revolute joint, in Modern Robotics' order (ω, v).

    Parameters
    ----------
    w : array_like, shape (3,)
        Unit vector along the joint axis; the joint turns positively about it (right-hand
        rule).
    q : array_like, shape (3,)
        Any point on the joint axis, in metres (a position, not a joint angle).

    Returns
    -------
    ndarray, shape (6,)
        S = (ω, v): first ω = w (rad/s per rad/s of joint rate), then v = −ω × q (metres per
        radian), the velocity of the body point at the origin.
    """
    ### BEGIN SOLUTION
    omega = np.asarray(w, dtype=float)
    point = np.asarray(q, dtype=float)
    return np.concatenate([omega, -np.cross(omega, point)])
    ### END SOLUTION


# %%
check("3.1", screw_axis)

# %% [markdown]
# ## 3. The exponential of a twist
#
# Turning a joint by θ moves everything beyond it by a rigid motion. In lesson 01 a rotation
# by θ about a unit axis ω was the matrix exponential $e^{[\omega]\theta}$; in the same way the
# motion along a screw axis is the exponential of its 4×4 matrix,
#
# $$e^{[S]\theta} = I + [S]\theta + \frac{([S]\theta)^2}{2!} + \frac{([S]\theta)^3}{3!} +
# \cdots$$
#
# This is the motion you get by following the twist $S$ for θ seconds at unit rate — exactly
# like $e^{at}$ solves $\dot x = a x$. The series has a closed form. Powers of $[S]$ keep its
# block shape,
#
# $$[S]^k = \begin{bmatrix} [\omega]^k & [\omega]^{k-1} v \\ 0 & 0 \end{bmatrix}
# \quad (k \ge 1),$$
#
# so the top-left block of the sum is the series of $e^{[\omega]\theta}$: the rotation by θ
# about ω, Rodrigues' formula from lesson 01,
#
# $$R = e^{[\omega]\theta} = I + \sin\theta\,[\omega] + (1 - \cos\theta)\,[\omega]^2 .$$
#
# The top-right block is $\sum_{k \ge 1} \frac{\theta^k}{k!} [\omega]^{k-1} v$. For a unit ω,
# $[\omega]^2 = \omega\omega^\mathsf{T} - I$ and therefore $[\omega]^3 = -[\omega]$: the powers
# cycle through $[\omega]$ and $[\omega]^2$ with alternating signs. Collecting them,
#
# $$\sum_{k\ge1} \frac{\theta^k}{k!}[\omega]^{k-1} = I\theta
# + \Big(\frac{\theta^2}{2!} - \frac{\theta^4}{4!} + \cdots\Big)[\omega]
# + \Big(\frac{\theta^3}{3!} - \frac{\theta^5}{5!} + \cdots\Big)[\omega]^2
# = I\theta + (1 - \cos\theta)[\omega] + (\theta - \sin\theta)[\omega]^2,$$
#
# and the whole motion is
#
# $$e^{[S]\theta} = \begin{bmatrix} e^{[\omega]\theta} &
# \big(I\theta + (1 - \cos\theta)[\omega] + (\theta - \sin\theta)[\omega]^2\big)\, v \\
# 0\;0\;0 & 1 \end{bmatrix} .$$
#
# **Why the translation is not $v\theta$.** $v$ is the velocity of the point at the origin
# *at the start*. That point swings round the joint axis on a circle, and its velocity turns
# with it; $v\theta$ is where it would be had it kept flying straight along its first
# tangent. The first term, $I\theta$, is exactly that straight-line guess; the other two bend
# the line into the circle. They are of order θ² and θ³, so for small angles the mistake hides
# — one more reason to test with large ones. (Only for a pure translation, ω = 0, is the
# displacement $v\theta$.)
#
# There is a second, geometric way to see the result. A turn about the line through $q$ is:
# shift $q$ to the origin, rotate, shift back, $T = \mathrm{Trans}(q)\,\mathrm{Rot}(\omega,
# \theta)\,\mathrm{Trans}(-q)$, whose translation is $(I - R)\,q$. With $v = -\omega \times q$
# the formula above gives the same vector. Let us check all three ways — the series summed
# term by term, the closed form (urkin's `se3_exp`, which takes the product $S\theta$) and the
# geometric one — and compare with $v\theta$.

# %%
def difference_text(worst):
    """A largest difference as text: "below 1e-12" when it is only round-off."""
    return "below 1e-12" if worst < 1e-12 else f"{worst:.3g}"


w_demo = np.array([0.3, -0.2, 1.0]) / np.linalg.norm([0.3, -0.2, 1.0])
q_demo = np.array([0.35, 0.15, 0.0])
S_demo = urkin.poe.screw_axis(w_demo, q_demo)
theta = 2.0  # radians, about 115°

series, term = np.eye(4), np.eye(4)
for k in range(1, 40):  # I + A + A²/2! + …, with A = [S]θ; 40 terms are plenty here
    term = term @ (twist_matrix(S_demo) * theta) / k
    series = series + term
closed = se3_exp(S_demo * theta)
R = so3_exp(w_demo * theta)
geometric = (np.eye(3) - R) @ q_demo

print(f"translation, series summed:      {series[:3, 3].round(4) + 0.0} m")
print(f"translation, closed form:        {closed[:3, 3].round(4) + 0.0} m")
print(f"translation, (I − R) q:          {geometric.round(4) + 0.0} m")
print(f"v·θ, the straight-line guess:    {(S_demo[3:] * theta).round(4) + 0.0} m")
gap = max(np.abs(series - closed).max(), np.abs(geometric - closed[:3, 3]).max())
print(f"series, closed form and (I − R) q differ by: {difference_text(gap)}")

# %% [markdown]
# The figure follows a frame — the space frame itself, starting at the origin — as θ grows
# from 0 to 270° about the same screw axis. Every pose is $e^{[S]\theta}$. The origin runs
# round a circle about the axis; the straight dashed line is where $v\theta$ would take it.

# %%
dense = np.linspace(0.0, 2 * np.pi, 181)
circle = se3_exp(dense[:, None] * S_demo)[:, :3, 3]  # the origin of every pose e^[S]θ
straight = np.linspace(0.0, 1.2, 50)[:, None] * S_demo[3:]  # v·θ for θ up to 1.2 rad
centre = q_demo + np.dot(-q_demo, w_demo) * w_demo  # the point of the axis nearest the origin

ax = urkin.plot.axes3d(center=(0.28, 0.0, 0.0), half_width=0.48, figsize=(8, 8),
                       title="A frame carried round a screw axis: poses e^[S]θ, θ = 0° … 270°")
axis_line = np.array([q_demo - 0.35 * w_demo, q_demo + 0.45 * w_demo])
ax.plot(*axis_line.T, color="tab:purple", linewidth=2.5, label="screw axis (ω through q)")
ax.scatter(*q_demo, color="tab:purple", s=30, depthshade=False)
ax.text(*(q_demo + np.array([0.02, 0.0, -0.05])), "q", color="tab:purple", fontsize=11)
ax.plot(*circle.T, color="tab:orange", linewidth=1.8, label="path of the origin: a circle")
ax.plot(*straight.T, "--", color="0.3", linewidth=1.5, label="v·θ: straight on along v")
ax.plot(*np.column_stack([centre, np.zeros(3)]), ":", color="tab:orange", linewidth=1.2,
        label="radius, from the axis to the start")
for step in range(7):  # every 45°
    angle = step * np.pi / 4
    urkin.plot.draw_frame(ax, se3_exp(angle * S_demo), length=0.09, linewidth=2.0,
                          label=f"{np.degrees(angle):.0f}°", tips=step == 0)
for colour, axis in zip(urkin.plot.AXIS_COLOURS, "xyz"):
    ax.plot([], [], color=colour, label=f"{axis} axis of the moving frame")
ax.view_init(elev=28, azim=-62)
ax.legend(loc="upper left", fontsize=8)
plt.show()

# %% [markdown]
# The frame turns *and* travels: at 90° it has moved round a quarter of the circle and turned
# by a quarter, as a door turns on its hinge. Near θ = 0 the dashed line and the circle agree;
# by 1.2 rad the straight-line guess is already far off.
#
# ### Exercise 3.2 — `twist_exp` (4 points)
#
# Write `twist_exp(S, theta)`: the 4×4 homogeneous transform $e^{[S]\theta}$ of a revolute
# screw axis `S = (ω, v)` (shape `(6,)`, unit ω, ordered as in exercise 3.1) and an angle
# `theta` in radians. Use the closed form derived above: Rodrigues' formula for the rotation
# block and $(I\theta + (1 - \cos\theta)[\omega] + (\theta - \sin\theta)[\omega]^2)\,v$ for the
# translation. Build $[\omega]$ yourself or with urkin's `skew`.
#
# *Checked* (to 1e-9; a float32 answer to float32's precision): a homogeneous transform whose
# rotation turns by θ about ω; $e^{[S]\theta}$ for random screw axes and angles of 0.3 to π
# rad either way; and that it turns space about the screw axis — the points of the axis stay
# where they are, a point off it keeps its distance from the axis and its height along it and
# turns by θ, right-handed about ω. The feedback recognises the $v\theta$ translation, a
# transposed rotation, −θ, degrees, `S` read as (v, ω), slips in the closed form's two
# matrices, and a series cut off too early. urkin's `se3_exp` and `urkin.poe` are hidden
# while this exercise is graded; `skew` and `so3_exp` are not.

# %%
def twist_exp(S, theta):
    """Rigid motion e^([S]θ) of turning by θ about a revolute screw axis S = (ω, v).

    Parameters
    ----------
    S : array_like, shape (6,)
        Screw axis (ω, v), angular part first, with a unit ω (a revolute joint); v in metres
        per radian.
    theta : float
        Joint angle in radians.

    Returns
    -------
    ndarray, shape (4, 4)
        [[R, p], [0, 0, 0, 1]] with R = I + sin θ [ω] + (1 − cos θ) [ω]² and
        p = (Iθ + (1 − cos θ) [ω] + (θ − sin θ) [ω]²) v, in metres.
    """
    ### BEGIN SOLUTION
    screw = np.asarray(S, dtype=float)
    W = skew(screw[:3])
    W2 = W @ W
    s, c = np.sin(theta), np.cos(theta)
    T = np.eye(4)
    T[:3, :3] = np.eye(3) + s * W + (1.0 - c) * W2
    T[:3, 3] = (theta * np.eye(3) + (1.0 - c) * W + (theta - s) * W2) @ screw[3:]
    return T
    ### END SOLUTION


# %%
check("3.2", twist_exp)

# %% [markdown]
# ## 4. Forward kinematics: the space form
#
# Put the arm at $q = 0$; the end effector is at $M$. Now reach any configuration $q$ by
# turning the joints **one at a time, from the last to the first**:
#
# * turn joint 6 by $q_6$. It carries only the end effector, about its screw axis $S_6$:
#   the end effector is now at $e^{[S_6]q_6}M$;
# * turn joint 5 by $q_5$. Its axis has not moved — only joints *beyond* it have — so it is
#   still $S_5$, and it carries everything beyond it rigidly, including the end effector as
#   joint 6 left it: $e^{[S_5]q_5}e^{[S_6]q_6}M$;
# * and so on down to joint 1:
#
# $$T(q) = e^{[S_1]q_1}\, e^{[S_2]q_2} \cdots e^{[S_6]q_6}\, M .$$
#
# Turning from the last joint backwards means every joint turns while its own axis is still in
# its home place, so the home axes $S_i$, written once in the space frame, are all we need.
# The final pose does not depend on the order in which we imagined the joints turning; this
# order is just the one in which the bookkeeping is easy. It is the **space form** of the
# product of exponentials.
#
# **What M is.** $M$ is the pose of the end effector at $q = 0$. It is *not* the base frame:
# the base frame is the space frame itself, the identity. Seed 001 describes its M as the pose
# of the robot's base in the world, but its own numbers tell another story:

# %%
M_seed = np.array(  # the report's M, as printed
    [
        [0.0, 0.0, -1.0, -0.194],
        [0.0, 1.0, 0.0, 0.0],
        [1.0, 0.0, 0.0, 0.651],
        [0.0, 0.0, 0.0, 1.0],
    ]
)
print(f"M's position: {M_seed[:3, 3]} m — 0.651 m up, the height of joint 6's point "
      f"{seed_points[5]}")
print(f"M's z axis (third column): {M_seed[:3, 2] + 0.0}, joint 6's axis a_6: {seed_axes[5]}")

# %% [markdown]
# M sits 65 cm above the world origin, at the top of the upright arm, and its z axis is joint
# 6's axis: it is the flange at θ = 0, where PoE needs it.
#
# ### Does the seed's S and M describe a UR3?
#
# urkin's UR3 is the DH model of lesson 02. The simulator's model is the same arm seen with
# different conventions; comparing the two, four differences turn up:
#
# * the simulator's zero is UR's upright "home" pose: $q_{\text{DH}} = \theta +
#   (0, -\pi/2, 0, -\pi/2, 0, 0)$;
# * its world frame is turned by −90° about z relative to DH frame 0;
# * DH frame 0 lies 42.9 mm below the simulator's world origin;
# * its end-effector frame is the flange turned by −90° about the flange's own z axis.
#
# So $T_{\text{seed}}(\theta) = T_{w,0}\; T_{0,6}(\theta + \text{offset})\; T_{6,e}$ with
# $T_{w,0} = (R_z(-\pi/2), (0, 0, -0.0429))$ and $T_{6,e} = R_z(-\pi/2)$. We evaluate the
# seed's PoE with urkin's `fk_space` on 1000 random configurations, once with the S computed
# from its listed points and once with the S it prints.

# %%
ur3 = urkin.robot("UR3")
offset = np.array([0.0, -np.pi / 2, 0.0, -np.pi / 2, 0.0, 0.0])  # q_DH = θ + offset
T_world_base = make_transform(rot_z(-np.pi / 2), [0.0, 0.0, -0.0429])
T_flange_ee = make_transform(rot_z(-np.pi / 2))

print("M, the seed's:")
print(M_seed)
print("end effector at θ = 0 from urkin's UR3 DH model:")
print((T_world_base @ urkin.fk(ur3, offset) @ T_flange_ee).round(4) + 0.0)

thetas = np.random.default_rng(1).uniform(-np.pi, np.pi, (1000, 6))
T_dh = T_world_base @ urkin.fk(ur3, thetas + offset) @ T_flange_ee
gaps_mm = {}
for name, S_try in [("S from the listed points", S_seed_hand),
                    ("S as printed", S_seed_printed)]:
    T_poe = urkin.poe.fk_space(M_seed, S_try, thetas)
    gaps_mm[name] = 1000 * np.linalg.norm(T_poe[:, :3, 3] - T_dh[:, :3, 3], axis=1)
    turn = np.abs(T_poe[:, :3, :3] - T_dh[:, :3, :3]).max()
    print(f"{name:<25}: largest position gap {gaps_mm[name].max():.2f} mm, "
          f"largest rotation-entry difference {difference_text(turn)}")

# %% [markdown]
# The seed's PoE model *is* a UR3: every orientation is exact (the axis directions are exact)
# and positions agree to about a millimetre, the precision to which the report rounded its
# points and M. The
# 1 mm slip in column 3 shows up as well — with the printed S the largest gap grows to almost
# 2 mm. The figure shows the seed's arm at θ = 0, its screw axes and its M, and the spread of
# the gaps.

# %%
home_frames = T_world_base @ urkin.fk_frames(ur3, offset)  # DH frames 0 … 6, seed's world
fig = plt.figure(figsize=(14, 6.5))
ax = urkin.plot.axes3d(fig.add_subplot(1, 2, 1, projection="3d"), center=(-0.1, 0.0, 0.33),
                       half_width=0.38, title="Seed 001's UR3 at θ = 0: axes, points and M")
ax.plot(*home_frames[:, :3, 3].T, "-o", color="0.45", linewidth=3, markersize=4,
        label="arm (through the DH origins)")
for joint in range(6):
    line = np.array([seed_points[joint] - 0.07 * seed_axes[joint],
                     seed_points[joint] + 0.07 * seed_axes[joint]])
    ax.plot(*line.T, color="tab:purple", linewidth=2.0,
            label="joint axes a_n through q_n" if joint == 0 else None)
    ax.text(*(seed_points[joint] + np.array([-0.05, 0.0, 0.0])), str(joint + 1), color="tab:purple")
ax.scatter(*seed_points.T, color="tab:purple", s=20, depthshade=False)
urkin.plot.draw_frame(ax, np.eye(4), length=0.1, label="world (base)", tips=True)
urkin.plot.draw_frame(ax, M_seed, length=0.1, label="M", tips=True)
ax.view_init(elev=18, azim=-60)
ax.legend(loc="upper left", fontsize=8)

right = fig.add_subplot(1, 2, 2)
bins = np.linspace(0.0, 2.0, 41)
for (name, gaps), colour in zip(gaps_mm.items(), ["tab:blue", "tab:red"]):
    right.hist(gaps, bins=bins, alpha=0.6, color=colour, label=name)
right.set_xlabel("position gap between seed 001's PoE and urkin's UR3 (mm)")
right.set_ylabel("number of configurations (of 1000)")
right.set_title("1000 random θ: gaps within the report's rounding")
right.legend(loc="upper right")
fig.suptitle("Seed 001: a UR3 described only by six screw axes and M")
fig.subplots_adjust(wspace=0.3)
plt.show()

# %% [markdown]
# In the 3D view notice that most of the seed's points (purple dots) are not on the grey stick
# figure: the simulator reports where its joint objects sit, offset sideways like the real
# motors, while the DH origins of joints 1 to 4 sit in one plane. Both lie on the same axis
# lines, and that is all a screw axis records.
#
# ### Exercise 3.3 — `fk_space` (5 points)
#
# Write `fk_space(M, S, q)`: the space-form product of exponentials
# $T = e^{[S_1]q_1} \cdots e^{[S_n]q_n}\, M$, for `M` of shape `(4, 4)`, screw axes `S` of
# shape `(6, n)` with **one screw axis per column** (`S[:, i]` is joint i + 1's), and joint
# angles `q` of shape `(n,)` in radians. Return a `(4, 4)` array. Use **your own
# `twist_exp`** for every factor, and multiply from the left (joint 1) to the right, with M
# last.
#
# *Checked* (to 1e-9; a float32 answer, or one built on a float32 `twist_exp`, to float32's
# precision): `M` at `q = 0` and the right pose when one joint alone turns; the flange pose of
# random UR arms at random `q`, from their screw axes; arms with 2 to 7 joints; and — one
# point — that the result is the product of *your own* factors, `twist_exp(S[:, 0], q[0]) @ …
# @ twist_exp(S[:, n - 1], q[n - 1]) @ M`. The feedback recognises M on the wrong side, the
# factors in reverse order, a joint or M left out, rows of `S` used as axes, degrees, and a
# right product of a wrong `twist_exp`. urkin's forward kinematics (`urkin.fk`, `fk_frames`,
# `dh_chain`, `urkin.poe.fk_space`, `fk_body`, `space_screws`, the SymPy and generated
# versions) is hidden while this exercise is graded; your `twist_exp` is not.

# %%
def fk_space(M, S, q):
    """Forward kinematics in the space form: T = e^([S1] q1) ⋯ e^([Sn] qn) M.

    Parameters
    ----------
    M : array_like, shape (4, 4)
        Pose of the end effector at q = 0, in the space frame (metres).
    S : array_like, shape (6, n)
        Space-frame screw axes, one per column, each ordered (ω, v).
    q : array_like, shape (n,)
        Joint angles in radians.

    Returns
    -------
    ndarray, shape (4, 4)
        Pose of the end effector in the space frame.
    """
    ### BEGIN SOLUTION
    axes = np.asarray(S, dtype=float)
    T = np.eye(4)
    for S_i, q_i in zip(axes.T, np.asarray(q, dtype=float)):
        T = T @ twist_exp(S_i, q_i)
    return T @ np.asarray(M, dtype=float)
    ### END SOLUTION


# %%
check("3.3", fk_space)

# %% [markdown]
# ## 5. Screw axes straight from a DH table
#
# Reading axes from a simulator is one way to get S; a DH table is another, and it is what
# Universal Robots publishes. Recall lesson 02: in standard DH, **joint i turns about the z
# axis of frame i−1, and that axis passes through frame i−1's origin.** So the frames at
# $q = 0$, $T_{0,i-1}(0)$, hand us both halves of every screw axis — the direction $\omega_i$
# is the third column of the rotation, the point $q_i$ is the origin — and M is the last
# frame:
#
# $$S_i = \big(z_{i-1},\ -z_{i-1} \times p_{i-1}\big)\Big|_{q=0}, \qquad M = T_{0,6}(0).$$
#
# In modified DH, joint i turns about $z_i$ instead; the recipe is the same, one frame later.
# `urkin.poe.space_screws(robot)` does this for a `Robot` (honouring its base and tool
# transforms), and `urkin.poe.space_screws(table, convention=...)` for any table of rows
# `(d, a, α)`. Here is the UR5, once with `space_screws` and once by hand from `fk_frames`:

# %%
ur5 = urkin.robot("UR5")
S_ur5, M_ur5 = urkin.poe.space_screws(ur5)
print("UR5 space screw axes S (columns = joints 1 … 6; rows ω_x, ω_y, ω_z, v_x, v_y, v_z):")
print(S_ur5 + 0.0)
print("M, the flange at q = 0:")
print(M_ur5 + 0.0)

frames_zero = urkin.fk_frames(ur5, np.zeros(6))  # DH frames 0 … 6 at q = 0
by_hand = np.column_stack([urkin.poe.screw_axis(frames_zero[i][:3, 2], frames_zero[i][:3, 3])
                           for i in range(6)])  # joint i + 1 turns about z of frame i
print("by hand from the frames, the same:", np.allclose(by_hand, S_ur5, rtol=0, atol=1e-15))

q_many = np.random.default_rng(5).uniform(-np.pi, np.pi, (1000, 6))
worst = np.abs(urkin.poe.fk_space(M_ur5, S_ur5, q_many) - urkin.fk(ur5, q_many)).max()
print(f"PoE against urkin.fk, 1000 random q, largest entry difference: "
      f"{difference_text(worst)}")

# %% [markdown]
# Read the columns. Joint 1 turns about the base z axis through the origin: $v = 0$. Joints
# 2, 3 and 4 are parallel, along −y; their $v$ are $(d_1, 0, 0)$ plus $(0, 0, x)$ terms that
# place each one further out along −x (0, 0.425 and 0.817 m). Joint 5 points down, along −z, and
# joint 6 along −y again, at the flange. M says the stretched-out arm puts the flange at
# $(a_2 + a_3, -d_4 - d_6, d_1 - d_5)$ with its z axis along −y.
#
# ### The space axes stay put
#
# A subtle point. $S_i$ is joint i's axis **at q = 0**, and the space form uses it whatever
# $q$ is. When the arm moves, the real axes of joints 2 to 6 move with it; only joint 1's
# stays where it was. The axis of joint i *now* is its home axis carried along by the joints
# before it,
#
# $$S_i(q) = \mathrm{Ad}\big(e^{[S_1]q_1}\cdots e^{[S_{i-1}]q_{i-1}}\big)\, S_i ,$$
#
# where the adjoint $\mathrm{Ad}(T) = \begin{bmatrix} R & 0 \\ [p]R & R \end{bmatrix}$ maps a
# twist through the rigid motion $T = (R, p)$ (urkin's `adjoint`). These current axes are the
# columns of the *space Jacobian*, which `urkin.poe.jacobian_space` computes; Jacobians are
# the subject of lesson 04. Check them against the axes read off the moved DH frames:

# %%
q_moved = np.array([0.7, -1.0, 1.3, -0.9, 1.0, 0.0])
current = urkin.poe.jacobian_space(S_ur5, q_moved)  # column i: joint i + 1's axis now
frames_moved = urkin.fk_frames(ur5, q_moved)
from_frames = urkin.poe.screw_axis(frames_moved[:-1, :3, 2], frames_moved[:-1, :3, 3]).T
worst = np.abs(current - from_frames).max()
print(f"Ad(…) S against the moved DH frames, largest difference: {difference_text(worst)}")
unmoved = [i + 1 for i in range(6) if np.allclose(current[:, i], S_ur5[:, i])]
print(f"joints whose current axis is still their home axis S_i: {unmoved}")

# %% [markdown]
# The figure draws the screw axes as lines on the arm. A screw axis $(\omega, v)$ with unit ω
# is the line through $\omega \times v$ (its point nearest the origin) along ω; each segment
# is drawn around the DH origin that lies on it, in the joint's colour. Left, the UR5 at
# q = 0. Right, at `q_moved`: the dashed lines are the space axes $S_i$, unchanged, and the
# solid lines are the joints' current axes $\mathrm{Ad}(\ldots)S_i$, which travel with the arm.

# %%
def axis_segment(screw, near, half_length=0.12):
    """Endpoints (2, 3) of the part of a screw axis's line nearest to the point ``near``."""
    w, v = screw[:3], screw[3:]
    foot = np.cross(w, v)  # the point of the line nearest the origin (unit w)
    centre = foot + np.dot(near - foot, w) * w
    return np.array([centre - half_length * w, centre + half_length * w])


joint_colours = plt.cm.tab10(np.arange(6))
fig = plt.figure(figsize=(14, 7))
panels = [(np.zeros(6), "UR5 at q = 0: the screw axes S_1 … S_6"),
          (q_moved, "UR5 at q_moved: S_i stay put, the joints' axes move")]
for index, (q, title) in enumerate(panels):
    ax = urkin.plot.axes3d(fig.add_subplot(1, 2, index + 1, projection="3d"),
                           center=(-0.38, -0.25, 0.15), half_width=0.45, title=title)
    urkin.plot.draw_robot(ax, ur5, q, frames=False, alpha=0.5, label="arm (DH origins)")
    for i in range(6):
        home_line = axis_segment(S_ur5[:, i], frames_zero[i][:3, 3], half_length=0.15)
        if index == 0:
            ax.plot(*home_line.T, "-", color=joint_colours[i], linewidth=2.5,
                    label=f"joint {i + 1}")
        else:
            now_line = axis_segment(current[:, i], frames_moved[i][:3, 3], half_length=0.15)
            ax.plot(*home_line.T, "--", color=joint_colours[i], linewidth=1.8)
            ax.plot(*now_line.T, "-", color=joint_colours[i], linewidth=2.5)
    if index == 1:
        ax.plot([], [], "--", color="0.3", label="space axis S_i (its home line, fixed)")
        ax.plot([], [], "-", color="0.3", label="current axis Ad(…) S_i")
    ax.view_init(elev=25, azim=-50)
    ax.legend(loc="upper left", fontsize=8)
fig.suptitle("Screw axes of the UR5 drawn as lines (colour = joint)")
plt.show()

# %% [markdown]
# Joint 1's dashed and solid lines coincide; every other joint's current axis has left its
# home line, and the solid lines run through the moved arm. The space form never needs the
# solid lines: turning the joints from the last to the first, each turns about its dashed line.
#
# ## 6. The body form
#
# The space form writes everything in the base frame. One can instead write the screw axes in
# the **end-effector frame at q = 0**, and multiply on the other side of M. For any transform
# M and matrix A, $M^{-1} e^{A} M = e^{M^{-1} A M}$ (conjugation passes through every term of
# the series), and $M^{-1}[S]M = [\mathrm{Ad}(M^{-1})S]$. So each factor can hop across M,
#
# $$e^{[S_i]q_i} M = M\, e^{[B_i]q_i}, \qquad B_i = \mathrm{Ad}(M^{-1})\, S_i ,$$
#
# and moving M from the right end to the left one factor at a time gives the **body form**
#
# $$T(q) = M\, e^{[B_1]q_1}\, e^{[B_2]q_2} \cdots e^{[B_n]q_n} .$$
#
# $B_i$ is joint i's home axis seen from the end effector's home frame. Read the product from
# the left: start at M, then turn the joints from the *first* to the last, each about its axis
# as seen from the end effector. `urkin.poe.body_screws` returns B and M.

# %%
B_ur5, _ = urkin.poe.body_screws(ur5)
print("UR5 body screw axes B = Ad(M⁻¹) S:")
print(B_ur5 + 0.0)
print("the same as Ad(M⁻¹) S by hand:",
      np.allclose(adjoint(inv_transform(M_ur5)) @ S_ur5, B_ur5, rtol=0, atol=1e-15))

# what changes when the tool or the mounting changes?
tool = make_transform(p=[0.0, 0.0, 0.15])  # a 15 cm tool along the flange's z axis
mount = make_transform(rot_z(0.5), [1.0, 0.2, 0.0])  # the arm bolted elsewhere, turned
S_tool, M_tool = urkin.poe.space_screws(ur5.with_tool(tool))
B_mount, _ = urkin.poe.body_screws(ur5.with_base(mount))
S_mount, M_mount = urkin.poe.space_screws(ur5.with_base(mount))
print("with a tool:     S unchanged:", np.allclose(S_tool, S_ur5, rtol=0, atol=1e-15),
      "  M becomes M @ T_flange_tool:", np.allclose(M_tool, M_ur5 @ tool))
print("moved base:      B unchanged:", np.allclose(B_mount, B_ur5, rtol=0, atol=1e-15),
      "  S becomes Ad(T_world_base) S:",
      np.allclose(S_mount, adjoint(mount) @ S_ur5, rtol=0, atol=1e-14),
      "  M becomes T_world_base @ M:", np.allclose(M_mount, mount @ M_ur5, rtol=0, atol=1e-15))
assert not np.allclose(M_mount, M_ur5)  # a new mounting moves M too, not only S

# %% [markdown]
# The last joint of a UR arm turns about the flange's own z axis, so $B_6 = (0, 0, 1, 0, 0,
# 0)$. And the two forms react differently to changes:
#
# * **a new tool** changes only M (to $M\,T_{\text{flange,tool}}$) in the space form — the
#   joint axes in the base frame are the same — while the body axes, seen from the new tool
#   frame, change;
# * **a new mounting** moves everything in the world frame: S becomes
#   $\mathrm{Ad}(T_{\text{world,base}})\,S$ *and* M becomes $T_{\text{world,base}}\,M$. Only B
#   stays: seen from the end effector, the joints have not moved.
#
# **Which to prefer?** Both give the same pose; choose the one whose numbers you have, or
# whose numbers stay fixed. Use the space form when your data lives in the base or world
# frame: axes measured in a simulator or by calibration (seed 001), velocities wanted in the
# base frame (the space Jacobian), or an arm whose tool you change often. Use the
# body form when the end effector's own frame is the natural one: jogging in the tool frame,
# errors measured in the tool frame by an inverse-kinematics solver, or an arm whose base moves
# (on a rail or a mobile platform) while its tool stays the same.
#
# ### Exercise 3.4 — `fk_body` (5 points)
#
# Write `fk_body(M, B, q)`: the body-form product $T = M\, e^{[B_1]q_1} \cdots e^{[B_n]q_n}$
# for `M` of shape `(4, 4)`, body screw axes `B` of shape `(6, n)` (one per column, ordered
# (ω, v)) and joint angles `q` of shape `(n,)` in radians, as a `(4, 4)` array. Use your own
# `twist_exp`; start with M and multiply the exponentials in joint order on its right.
#
# *Checked* (to 1e-9; a float32 answer, or one built on a float32 `twist_exp`, to float32's
# precision): as in exercise 3.3, with the body screw axes of random UR arms and of arms with
# 2 to 7 joints, and — one point — that the result is `M @ twist_exp(B[:, 0], q[0]) @ … @
# twist_exp(B[:, n - 1], q[n - 1])` with your own `twist_exp`. The feedback recognises the same
# slips, with M multiplied last. The same urkin functions as in exercise 3.3 are hidden.

# %%
def fk_body(M, B, q):
    """Forward kinematics in the body form: T = M e^([B1] q1) ⋯ e^([Bn] qn).

    Parameters
    ----------
    M : array_like, shape (4, 4)
        Pose of the end effector at q = 0, in the space frame (metres).
    B : array_like, shape (6, n)
        Body-frame screw axes (joint axes seen from the end effector at q = 0), one per column,
        each ordered (ω, v).
    q : array_like, shape (n,)
        Joint angles in radians.

    Returns
    -------
    ndarray, shape (4, 4)
        Pose of the end effector in the space frame.
    """
    ### BEGIN SOLUTION
    axes = np.asarray(B, dtype=float)
    T = np.asarray(M, dtype=float).copy()
    for B_i, q_i in zip(axes.T, np.asarray(q, dtype=float)):
        T = T @ twist_exp(B_i, q_i)
    return T
    ### END SOLUTION


# %%
check("3.4", fk_body)

# %% [markdown]
# ### Three formulations, one arm
#
# Space form, body form and DH are three ways of computing the same thing. For each of the
# seven arms, 1000 random configurations, the largest difference in any entry of T between
# `urkin.fk` (DH) and each PoE form. The last column goes through a **modified**-DH table
# (lesson 02's rewriting: the a and α columns shifted down one row) and
# `urkin.poe.space_screws(table, convention="modified")`: a different table, a different
# convention, and still the same screw axes.

# %%
rng = np.random.default_rng(11)
print("largest difference from urkin.fk (DH) in any entry of T, 1000 random q per arm:")
print("arm      space form     body form      modified-DH table    same S from both tables")
for name in urkin.ROBOTS:
    arm = urkin.robot(name)
    q = rng.uniform(-np.pi, np.pi, (1000, 6))
    T_dh = urkin.fk(arm, q)
    S_arm, M_arm = urkin.poe.space_screws(arm)
    B_arm, _ = urkin.poe.body_screws(arm)
    modified = np.column_stack([arm.d, np.r_[0.0, arm.a[:-1]], np.r_[0.0, arm.alpha[:-1]]])
    S_mod, M_mod = urkin.poe.space_screws(modified, convention="modified")
    gaps = [np.abs(urkin.poe.fk_space(M_arm, S_arm, q) - T_dh).max(),
            np.abs(urkin.poe.fk_body(M_arm, B_arm, q) - T_dh).max(),
            np.abs(urkin.poe.fk_space(M_mod, S_mod, q) - T_dh).max()]
    same = difference_text(np.abs(S_mod - S_arm).max())
    print(f"{name:<7}  " + "  ".join(f"{difference_text(g):<13}" for g in gaps[:2])
          + f"  {difference_text(gaps[2]):<19}  {same}")

# %% [markdown]
# ## 7. No frame per link: what you gain, what you lose
#
# Every DH link needs a frame because the four DH numbers are *relative*: link i is described
# from frame i−1. PoE describes every joint *absolutely*, as a line in one frame, so the
# intermediate frames simply are not needed. What that buys:
#
# * **Any frame, any data.** Axes measured in a simulator or by a calibration rig go straight
#   into S, as seed 001 did; a new tool changes only M, a new mounting changes S and M
#   together (and leaves B alone).
# * **No rules to juggle.** No choice of x axes, no sign conventions for $a_2$, $a_3$, no
#   standard-versus-modified confusion: the two tables above give the *same* S.
# * **Smoothness.** A screw axis changes a little when the joint's axis is shifted or tilted a
#   little. DH parameters need not: for parallel axes DH must pick the common normal by
#   convention, and for *nearly* parallel ones the common normal can be anywhere. This matters
#   to anyone calibrating a real arm, whose "parallel" joints are never exactly parallel.
#
# The figure makes the last point concrete. Take two parallel joint axes 0.425 m apart, like
# a UR5's shoulder and elbow, and tilt the second by a tiny angle ε. Where does the DH common
# normal go, and how much does the screw axis change?

# %%
def common_normal(p1, z1, p2, z2):
    """DH view of two skew lines: where the common normal meets line 1, and its length.

    Returns (t, a): the foot of the common normal on line 1 is p1 + t·z1 (t in metres along
    the unit direction z1), and a is the distance between the lines.
    """
    b = np.dot(z1, z2)
    w0 = p1 - p2
    d, e = np.dot(z1, w0), np.dot(z2, w0)
    sin_squared = np.sum(np.cross(z1, z2) ** 2)  # 1 − b², without cancellation
    t = (b * e - d) / sin_squared
    s = (e - b * d) / sin_squared
    return t, np.linalg.norm((p1 + t * z1) - (p2 + s * z2))


z_axis = np.array([0.0, 0.0, 1.0])
p1, p2 = np.zeros(3), np.array([0.425, 0.0, 0.0])  # two parallel axes, 0.425 m apart
tilt_about = np.array([1.0, 1.0, 0.0]) / np.sqrt(2.0)
S_parallel = urkin.poe.screw_axis(z_axis, p2)
epsilons = np.logspace(-6, -1, 51)
normal_offset, normal_jump, screw_change = [], [], []
for eps in epsilons:
    z2 = so3_exp(eps * tilt_about) @ z_axis
    t, a = common_normal(p1, z_axis, p2, z2)
    normal_offset.append(abs(t))
    normal_jump.append(abs(a - 0.425))
    screw_change.append(np.abs(urkin.poe.screw_axis(z2, p2) - S_parallel).max())

fig, ax = plt.subplots(figsize=(8, 5))
ax.loglog(epsilons, normal_offset, label="DH: where the common normal meets axis 1, |d| (m)")
ax.loglog(epsilons, normal_jump, label="DH: change of the common normal's length, |Δa| (m)")
ax.loglog(epsilons, screw_change, label="PoE: largest change of any entry of S (m or rad)")
ax.set_xlabel("tilt ε of the second axis away from parallel (rad)")
ax.set_ylabel("change of the parameters (m; rad for directions)")
ax.set_title("Two nearly parallel joint axes: DH parameters jump, the screw axis barely moves")
ax.legend(loc="upper right", fontsize=8)
ax.grid(True, which="major", alpha=0.3)
plt.show()

for index in (0, 30, 50):  # ε = 1e-6, 1e-3 and 1e-1 rad
    eps, t_value, change = epsilons[index], normal_offset[index], screw_change[index]
    print(f"ε = {eps:.0e} rad ({np.degrees(eps):.1e}°): DH offset d = {t_value:10.1f} m, "
          f"screw change {change:.1e}")

# %% [markdown]
# A tilt of a millionth of a radian moves the DH frame 300 km along the axis, and the
# common normal's length jumps from 0.425 m to 0.30 m however small the tilt is; the screw axis
# changes by about ε. A DH model cannot describe the slightly imperfect real arm by slightly
# changed numbers; a PoE model can.
#
# What you give up:
#
# * **Six numbers per joint instead of four.** A line in space has four degrees of freedom;
#   a revolute screw axis spends six numbers on it, tied by $\|\omega\| = 1$ and
#   $\omega \cdot v = 0$. Identification and calibration must respect those constraints.
# * **No link frames for free.** If you need the pose of link 3 — to draw it, to put collision
#   spheres on it, for its mass and inertia — PoE needs one more home pose $M_i$ per link;
#   DH handed you those frames as a by-product.
# * **The manufacturers' language.** Universal Robots publishes DH tables, and the closed-form
#   inverse kinematics of a later lesson is derived in DH frames. Section 5's conversion
#   bridges the two.
#
# ### The Modern Robotics UR5 example
#
# *Modern Robotics* works the UR5 as an example of the space form, with rounded lengths
# $W_1 = 0.109$, $W_2 = 0.082$, $L_1 = 0.425$, $L_2 = 0.392$, $H_1 = 0.089$ and
# $H_2 = 0.095$ m, and evaluates it at $\theta_2 = -\pi/2$, $\theta_5 = \pi/2$, all other
# joints 0. The book's space frame is not DH frame 0: it is turned by π about z, the URDF
# `base_link` frame of lesson 00, `urkin.T_BASE_LINK_BASE`. Its joint angles are UR's, and its
# end-effector frame is the flange. We type the book's S and M and compare.

# %%
W1, W2, L1, L2, H1, H2 = 0.109, 0.082, 0.425, 0.392, 0.089, 0.095  # metres
S_book = np.array(  # rows are the screw axes S_1 … S_6 as (ω, v): transpose to columns
    [
        [0.0, 0.0, 1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, -H1, 0.0, 0.0],
        [0.0, 1.0, 0.0, -H1, 0.0, L1],
        [0.0, 1.0, 0.0, -H1, 0.0, L1 + L2],
        [0.0, 0.0, -1.0, -W1, L1 + L2, 0.0],
        [0.0, 1.0, 0.0, H2 - H1, 0.0, L1 + L2],
    ]
).T
M_book = np.array(
    [
        [-1.0, 0.0, 0.0, L1 + L2],
        [0.0, 0.0, 1.0, W1 + W2],
        [0.0, 1.0, 0.0, H1 - H2],
        [0.0, 0.0, 0.0, 1.0],
    ]
)
theta_book = np.array([0.0, -np.pi / 2, 0.0, 0.0, np.pi / 2, 0.0])
T_book_printed = np.array(
    [[0.0, -1.0, 0.0, 0.095], [1.0, 0.0, 0.0, 0.109], [0.0, 0.0, 1.0, 0.988], [0, 0, 0, 1.0]]
)
T_book = urkin.poe.fk_space(M_book, S_book, theta_book)
print("T from the book's S and M:")
print(T_book.round(4) + 0.0)
print("matches the book's printed T:", np.allclose(T_book, T_book_printed, rtol=0, atol=1e-12))

# the same arm in urkin: UR's DH table with the book's rounded lengths, seen from base_link
ur5_book = urkin.Robot("UR5 (Modern Robotics' lengths)", H1, -L1, -L2, W1, H2, W2)
S_dh, M_dh = urkin.poe.space_screws(ur5_book)
Ad_link = adjoint(urkin.T_BASE_LINK_BASE)  # maps twists from base to base_link
print("book's S = Ad(T_base_link_base) S_DH:",
      difference_text(np.abs(Ad_link @ S_dh - S_book).max()))
print("book's M = T_base_link_base M_DH:   ",
      difference_text(np.abs(urkin.T_BASE_LINK_BASE @ M_dh - M_book).max()))
print("book's T = T_base_link_base · urkin.fk:",
      difference_text(np.abs(urkin.T_BASE_LINK_BASE @ urkin.fk(ur5_book, theta_book)
                             - T_book).max()))
real_gap = np.linalg.norm((urkin.T_BASE_LINK_BASE @ urkin.fk(ur5, theta_book))[:3, 3]
                          - T_book[:3, 3])
print(f"with UR's exact UR5 lengths the flange is {1000 * real_gap:.2f} mm from the book's")

# %% [markdown]
# The book's numbers, urkin's DH model and the PoE product agree to the last digit once the
# half turn between `base` and `base_link` is accounted for; UR's unrounded UR5 lengths move
# the flange by 0.8 mm. At this configuration the upper arm points straight up
# ($\theta_2 = -\pi/2$), the forearm continues upwards, and after the quarter turn of joint 5
# the flange points straight up too, $H_1 + L_1 + L_2 + W_2 = 0.988$ m above the base.

# %% [markdown]
# ## 8. Back from a pose to a twist: the matrix logarithm
#
# Forward kinematics goes from twists to a pose. Inverse kinematics (lesson 06) needs the way
# back: given a pose $T = (R, p)$, which twist $V = S\theta = (\omega\theta, v\theta)$ has
# $e^{[V]} = T$? That twist is the motion that, followed for unit time, carries the identity
# to $T$ — the matrix logarithm $[V] = \log T$.
#
# **The rotation** is lesson 01's log map: $R = e^{[\omega]\theta}$ gives the unit axis ω and
# the angle θ ∈ [0, π], from $\theta = \operatorname{atan2}(|\tfrac12(R - R^\mathsf{T})^\vee|,\
# \tfrac12(\operatorname{tr}R - 1))$ and $[\omega] = (R - R^\mathsf{T})/(2\sin\theta)$.
#
# **The translation** is new. Section 3 found $p = G(\theta)\,v$ with
#
# $$G(\theta) = I\theta + (1 - \cos\theta)[\omega] + (\theta - \sin\theta)[\omega]^2 .$$
#
# So $v = G^{-1}(\theta)\,p$. $G$ is a polynomial in $[\omega]$, and so is its inverse: since
# $[\omega]^3 = -[\omega]$ for a unit ω, every power of $[\omega]$ folds back into $I$,
# $[\omega]$ and $[\omega]^2$. Try $G^{-1} = aI + b[\omega] + c[\omega]^2$, multiply, and set
# the product to $I$: three equations for $a, b, c$, with the solution
#
# $$G^{-1}(\theta) = \frac{1}{\theta}\,I - \frac12\,[\omega]
#   + \left(\frac{1}{\theta} - \frac12\cot\frac{\theta}{2}\right)[\omega]^2 .$$
#
# Two cases need care:
#
# * **θ = 0** (R = I): there is no rotation axis and $1/\theta$ blows up. The motion is a pure
#   translation: ω = 0 and $v\theta = p$, so $V = (0, p)$. Just above 0 the coefficient
#   $\frac1\theta - \frac12\cot\frac\theta2 = \frac{\theta}{12} + O(\theta^3)$ stays small,
#   and $v\theta = \theta\,G^{-1}p \to p$ smoothly: only the exact zero needs its own branch.
# * **θ = π**: $\sin\theta = 0$, so $(R - R^\mathsf{T})/(2\sin\theta)$ is 0/0. Read ω from the
#   symmetric part, $R = I + 2[\omega]^2 = 2\omega\omega^\mathsf{T} - I$, as lesson 01 did
#   (either sign of ω is right). $G^{-1}$ itself is harmless there: $\cot(\pi/2) = 0$.
#
# Check the inverse and the round trip numerically, then the two special cases with urkin's
# `se3_log`:

# %%
def G_matrix(w, theta):
    """G(θ) of section 3, for a unit axis w."""
    W = skew(w)
    return np.eye(3) * theta + (1 - np.cos(theta)) * W + (theta - np.sin(theta)) * W @ W


def G_inverse(w, theta):
    """The closed form of G(θ)⁻¹ derived above (0 < θ ≤ π)."""
    W = skew(w)
    return np.eye(3) / theta - W / 2 + (1 / theta - 0.5 / np.tan(theta / 2)) * W @ W


rng = np.random.default_rng(5)
worst = 0.0
for _ in range(1000):
    w = rng.normal(size=3)
    w /= np.linalg.norm(w)
    theta = rng.uniform(1e-3, np.pi)
    worst = max(worst, np.abs(G_inverse(w, theta) @ G_matrix(w, theta) - np.eye(3)).max())
print(f"G⁻¹(θ) G(θ) = I for 1000 random axes and angles: largest error {difference_text(worst)}")

twists = rng.normal(size=(1000, 6))
twists[:, :3] *= (rng.uniform(0.0, 3.1, 1000) / np.linalg.norm(twists[:, :3], axis=1))[:, None]
back = se3_log(se3_exp(twists))  # θ = |ω θ| below π: the log is unique
print(f"se3_log(se3_exp(V)) = V for 1000 twists with θ < π: largest error "
      f"{difference_text(np.abs(back - twists).max())}")

translation = make_transform(p=[0.3, -0.2, 0.5])
print("log of a pure translation:", se3_log(translation).round(4) + 0.0)
half_turn = se3_exp(np.r_[np.pi * np.array([0.0, 0.6, 0.8]), 0.1, 0.2, -0.3])
V_half = se3_log(half_turn)
print(f"a half turn: θ = |ωθ| = {np.linalg.norm(V_half[:3]):.6f} rad (π = {np.pi:.6f}); "
      f"exp(log T) = T: {np.allclose(se3_exp(V_half), half_turn, rtol=0, atol=1e-12)}")

# %% [markdown]
# ### Exercise 3.5 — `twist_log` (4 points)
#
# Write `twist_log(T)`: the twist $V = (\omega\theta, v\theta)$, shape `(6,)`, angular part
# first, with $e^{[V]} = T$ and θ in [0, π]. Use the rotation log of lesson 01 (compute θ with
# `atan2`, as there, or take `urkin.transforms.so3_log`) and the $G^{-1}$ above; `se3_log`,
# which answers the whole exercise, is hidden while it is graded.
#
# *Checked* (to 1e-9; a float32 answer to float32's precision): (2 points) $V$ equals the
# logarithm for random poses with 0.1 ≤ θ ≤ 3 rad; (1 point) pure translations and the
# identity give $(0, p)$ — no NaN; (1 point) half turns, θ = π exactly (with $R$ exactly
# symmetric) and θ = π − 1e-8, and small turns, θ from 1e-9 to 1e-3: $e^{[V]}$ reproduces $T$
# to 1e-8, with θ ≤ π (at a half turn either sign of ω is right, so only the round trip is
# compared).

# %%
def twist_log(T):
    """The matrix logarithm of a rigid motion: the twist V with e^[V] = T.

    Parameters
    ----------
    T : array_like, shape (4, 4)
        A homogeneous transform.

    Returns
    -------
    ndarray, shape (6,)
        V = (ω θ, v θ), angular part first, with θ = |ω θ| in [0, π].
    """
    ### BEGIN SOLUTION
    T = np.asarray(T, dtype=float)
    R, p = T[:3, :3], T[:3, 3]
    sin_axis = 0.5 * np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    theta = np.arctan2(np.linalg.norm(sin_axis), 0.5 * (np.trace(R) - 1.0))
    if theta < 1e-12:  # no rotation: a pure translation
        return np.concatenate([np.zeros(3), p])
    if theta > np.pi - 1e-6:  # near a half turn: the axis from the symmetric part
        B = R + R.T - 2.0 * np.cos(theta) * np.eye(3)  # = 2 (1 − cos θ) w wᵀ
        column = B[:, int(np.argmax(np.diag(B)))]
        w = column / np.linalg.norm(column)
        w = w if w @ sin_axis >= 0 else -w
    else:
        w = sin_axis / np.sin(theta)
    W = skew(w)
    G_inv = np.eye(3) / theta - W / 2 + (1 / theta - 0.5 / np.tan(theta / 2)) * W @ W
    return np.concatenate([w * theta, G_inv @ p * theta])
    ### END SOLUTION


# %%
check("3.5", twist_log)

# %% [markdown]
# ## 9. From a screw axis back to the joint
#
# Sections 1 and 2 went from a joint to its screw axis: a direction ω and a point $q$ give
# $S = (\omega, -\omega \times q)$. The way back is just as useful. A screw axis handed to you
# by a calibration, a book or the current axes $\mathrm{Ad}(\ldots)S_i$ of section 5 says
# nothing directly about *where* the joint is; to draw it, or to compare it with a drawing of
# the arm, you need a point of its line. Section 5's figure used one without proof: "the line
# through ω × v". Now you prove it.
#
# **Predict first.** Look at the UR5's joint 2 in section 5's printout: $\omega = (0, -1, 0)$,
# $v = (0.089159, 0, 0)$. Before any algebra, picture the arm at $q = 0$: the shoulder joint
# sits on top of the base column, at the height $d_1 = 0.089159$ m, and turns about a
# horizontal line. Where does that line pass closest to the base origin? Write your guess
# down — a point, in metres — and do the same for joint 3, which is parallel to joint 2 and
# $|a_2| = 0.425$ m further out along the upper arm.
#
# **Derive.** The line is all points $q + t\omega$. Its point nearest the origin minimises
# $\|q + t\omega\|^2 = \|q\|^2 + 2t\,(q \cdot \omega) + t^2$ (for a unit ω), so
# $t = -q \cdot \omega$: the nearest point is $q - (q \cdot \omega)\,\omega$, the one point of
# the line with $q \cdot \omega = 0$. Now take the cross product of ω with
# $v = -\omega \times q$ and expand the double cross product,
# $a \times (b \times c) = (a \cdot c)\,b - (a \cdot b)\,c$:
#
# $$\omega \times v = -\omega \times (\omega \times q)
#   = -\big((\omega \cdot q)\,\omega - (\omega \cdot \omega)\,q\big)
#   = q - (\omega \cdot q)\,\omega .$$
#
# It is the nearest point, whichever point $q$ built $S$ — as it must be, since $S$ does not
# remember $q$. The derivation used $\omega \cdot \omega = 1$. For an ω of another length it
# gives $\|\omega\|^2 q - (\omega \cdot q)\,\omega$, a point off the axis; for a prismatic
# joint, $\omega = 0$, there is no axis at all, only a direction of sliding. Either way
# $\omega \times v$ is not a point of a joint axis, so a function that returns it must refuse
# such an $S$ rather than answer quietly.
#
# ### Exercise 3.6 — `screw_to_joint` (3 points)
#
# Write `screw_to_joint(S)`: for the screw axis `S = (ω, v)` of a revolute joint (shape
# `(6,)`, angular part first, ω a unit vector, v in metres), return the point of the joint's
# axis nearest the origin of the frame `S` is written in, as an array of shape `(3,)` in
# metres: the one point $q$ of the axis with $q \cdot \omega = 0$. **Bad input:** when
# $\|\omega\|$ differs from 1 by more than 1e-6 — a prismatic joint (ω = 0) or an ω that was
# not normalised — raise `ValueError` with a message that names the argument `S`.
#
# *Checked* (to 1e-9; a float32 answer to float32's precision): (1 point) the nearest point
# for random unit axes through random points; (1 point) the nearest points of the joint axes
# of random UR arms, from `urkin.poe.space_screws` at $q = 0$ and their current axes at a
# random $q$; (1 point) a `ValueError` whose message contains `S` for ω = 0 and for ω of
# length 2, 0.5 and 1.01 — and, in the same check, a point for a valid `S`, so a function
# that refuses everything earns nothing. The feedback recognises $v \times \omega$ (the
# mirror point $-q$), $v$, $-v$ or ω returned as the point, and a point of the axis that is
# not the nearest one.

# %%
def screw_to_joint(S):
    """The point of a revolute joint's axis nearest the origin, from its screw axis.

    Parameters
    ----------
    S : array_like, shape (6,)
        Screw axis (ω, v) of a revolute joint, angular part first: ω a unit vector along the
        axis, v = −ω × q in metres for any point q of the axis.

    Returns
    -------
    ndarray, shape (3,)
        The point of the axis nearest the origin of S's frame, in metres: ω × v, the one
        point q of the axis with q·ω = 0.

    Raises
    ------
    ValueError
        If ‖ω‖ differs from 1 by more than 1e-6 (a prismatic joint, ω = 0, or an ω that was
        not normalised): then ω × v is not a point of a joint axis.
    """
    ### BEGIN SOLUTION
    screw = np.asarray(S, dtype=float)
    omega, v = screw[:3], screw[3:]
    length = np.linalg.norm(omega)
    if abs(length - 1.0) > 1e-6:
        raise ValueError(
            f"S must be a revolute screw axis with a unit ω; its ω has length {length:.3g}"
        )
    return np.cross(omega, v)
    ### END SOLUTION


# %%
check("3.6", screw_to_joint)

# %% [markdown]
# **Verify.** The cell below takes every UR5 joint, at $q = 0$ and at section 5's `q_moved`,
# and tests the point three ways: rebuilding $S = (\omega, -\omega \times q)$ from it must give
# back the screw axis; $q \cdot \omega$ must be zero; and the point must lie on the line of
# the z axis of the DH frame the joint turns about (frame i−1 for joint i, from
# `urkin.fk_frames`), an independent description of the same axis. It uses your
# `screw_to_joint`, or $\omega \times v$ while the exercise is not written yet.

# %%
try:
    screw_to_joint(S_ur5[:, 1])
    joint_point, source = screw_to_joint, "your screw_to_joint"
except NotImplementedError:
    def joint_point(S):
        """ω × v, standing in for exercise 3.6 until it is written."""
        return np.cross(S[:3], S[3:])

    source = "ω × v (exercise 3.6 is not written yet)"
print(f"points from {source}")

for joint, (x, z) in ((2, (0.0, ur5.d1)), (3, (ur5.a2, ur5.d1))):
    point = np.round(np.asarray(joint_point(S_ur5[:, joint - 1]), dtype=float), 6) + 0.0
    print(f"UR5 joint {joint} at q = 0: nearest point ({point[0]:.6f}, {point[1]:.6f}, "
          f"{point[2]:.6f}) m; prediction ({x:.6f}, 0.000000, {z:.6f})")

for q, name in ((np.zeros(6), "q = 0"), (q_moved, "q_moved")):
    axes_now = urkin.poe.jacobian_space(S_ur5, q)  # column i: joint i + 1's axis at q
    frames_now = urkin.fk_frames(ur5, q)  # joint i + 1 turns about z of frame i
    rebuilt_gap = perpendicular = off_line = 0.0
    for i in range(6):
        S_i = axes_now[:, i]
        point = np.asarray(joint_point(S_i), dtype=float)
        rebuilt = np.r_[S_i[:3], -np.cross(S_i[:3], point)]
        rebuilt_gap = max(rebuilt_gap, np.abs(rebuilt - S_i).max())
        perpendicular = max(perpendicular, abs(np.dot(point, S_i[:3])))
        z_axis, origin = frames_now[i][:3, 2], frames_now[i][:3, 3]
        offset = point - origin
        off_line = max(off_line, np.linalg.norm(offset - np.dot(offset, z_axis) * z_axis))
    print(f"{name:<8}: S rebuilt from the point, largest difference "
          f"{difference_text(rebuilt_gap)}; |q·ω| {difference_text(perpendicular)}; "
          f"distance to the DH z axis {difference_text(off_line)} m")

# %% [markdown]
# Joint 2's axis passes closest to the base origin straight above it, at the shoulder height:
# $(0, 0, d_1)$. Joint 3's is the same point moved out by $a_2 = -0.425$ m along x (UR's $a_2$
# is negative: at $q = 0$ the arm stretches along −x). For every joint, at home and moved,
# the point rebuilds its screw axis, is perpendicular to ω, and lies on the DH frame's z
# axis: one line, described once by PoE and once by DH. If your prediction put joint 2's
# point at the joint's physical centre, off to the side along y, remember section 2: a screw
# axis records the line, not where along it the motor sits.

# %% [markdown]
# ## 10. Body screw axes by hand
#
# Section 6 turned the UR5's space screw axes into body ones in one line,
# `adjoint(inv_transform(M_ur5)) @ S_ur5`: column by column $B_i = \mathrm{Ad}(M^{-1})\,S_i$,
# joint i's home axis seen from the end effector's home frame. There urkin's `adjoint` did the
# work; now you write it. Section 5 gave the adjoint of a rigid motion $T = (R, p)$,
#
# $$\mathrm{Ad}(T) = \begin{bmatrix} R & 0 \\ [p]R & R \end{bmatrix} ,$$
#
# the 6×6 matrix that carries a twist $(\omega, v)$ through $T$; for the body axes it is taken
# of $T = M^{-1}$, whose rotation and translation are $R^\mathsf{T}$ and $-R^\mathsf{T}p$ when
# $M = (R, p)$ (lesson 01's inverse). Section 6's identity $M^{-1}[S]M = [\mathrm{Ad}(M^{-1})S]$
# gives a second way to the same numbers, handy for checking.
#
# ### Exercise 3.7 — `body_from_space` (4 points)
#
# Write `body_from_space(S, M)`: the body screw axes `B`, shape `(6, n)`, of an arm with space
# screw axes `S` (shape `(6, n)`, one per column, each ordered (ω, v), any number of joints
# n ≥ 1) and home pose `M` (shape `(4, 4)`, the end effector at q = 0, metres): column i of B
# is $\mathrm{Ad}(M^{-1})$ `S[:, i]`. Build the 6×6 adjoint $[[R, 0], [[p]R, R]]$ of $M^{-1}$
# yourself — with the rotation and translation of $M^{-1}$, not of M — and apply it to every
# column (one matrix product does them all). `skew` and `inv_transform` may help; urkin's
# `adjoint` and `body_screws`, which answer the exercise, are hidden while it is graded.
#
# *Checked* (to 1e-12; a float32 answer to float32's precision): (1 point) the body screw
# axes of random UR arms, from `urkin.poe.space_screws`, some on a random mounting and with a
# random tool, against `urkin.poe.body_screws`; (2 points) random screw axes, every n from 1
# to 7, with a random M; (1 point) with your B, urkin's body form `urkin.poe.fk_body(M, B, q)`
# gives the pose of its space form `urkin.poe.fk_space(M, S, q)` at random q, to 1e-9 — for
# random UR arms and an arm of six random joints. The feedback recognises Ad(M) in place of
# Ad(M⁻¹), $[p]R$ in the top-right block, an R left untransposed, the translation of $M^{-1}$
# taken as −p or with a lost sign, $R[p]$ for $[p]R$, the (v, ω) order, a transposed adjoint
# or B, S returned unchanged, and six columns hard-coded.

# %%
def body_from_space(S, M):
    """Body screw axes B = Ad(M⁻¹) S, from the space screw axes and the home pose.

    Parameters
    ----------
    S : array_like, shape (6, n)
        Space-frame screw axes, one per column, each ordered (ω, v).
    M : array_like, shape (4, 4)
        Pose of the end effector at q = 0, in the space frame (metres).

    Returns
    -------
    ndarray, shape (6, n)
        Body-frame screw axes, ordered (ω, v): column i is Ad(M⁻¹) S[:, i], joint i's home
        axis seen from the end effector's frame at q = 0.
    """
    ### BEGIN SOLUTION
    M = np.asarray(M, dtype=float)
    R_inv = M[:3, :3].T  # M⁻¹ = (Rᵀ, −Rᵀ p)
    p_inv = -R_inv @ M[:3, 3]
    Ad = np.zeros((6, 6))
    Ad[:3, :3] = Ad[3:, 3:] = R_inv
    Ad[3:, :3] = skew(p_inv) @ R_inv
    return Ad @ np.asarray(S, dtype=float)
    ### END SOLUTION


# %%
check("3.7", body_from_space)

# %% [markdown]
# **Verify.** The body form with your B must put the end effector exactly where the space
# form puts it. The cell below takes the UR5 with section 6's tool and mounting, turns its
# space screw axes into body axes with your `body_from_space` (with urkin's `adjoint` while
# the exercise is not written yet), and compares urkin's `fk_body` with its `fk_space` at 1000
# random configurations. It then repeats section 6's observation with your function: the
# same arm and tool bolted down at the origin has the same B.

# %%
try:
    body_from_space(S_ur5, M_ur5)
    to_body, source = body_from_space, "your body_from_space"
except NotImplementedError:
    def to_body(S, M):
        """Ad(M⁻¹) S with urkin's adjoint, standing in for exercise 3.7 until it is written."""
        return adjoint(inv_transform(M)) @ S

    source = "urkin's adjoint (exercise 3.7 is not written yet)"
print(f"body screw axes from {source}")

arm = ur5.with_base(mount).with_tool(tool)
S_arm, M_arm = urkin.poe.space_screws(arm)
B_arm = np.asarray(to_body(S_arm, M_arm), dtype=float)
q_many = np.random.default_rng(37).uniform(-np.pi, np.pi, (1000, 6))
gap = np.abs(urkin.poe.fk_body(M_arm, B_arm, q_many)
             - urkin.poe.fk_space(M_arm, S_arm, q_many)).max()
print(f"mounted UR5 with a tool: body form against space form, 1000 random q, largest entry "
      f"difference {difference_text(gap)}")

S_home, M_home = urkin.poe.space_screws(ur5.with_tool(tool))  # the same arm, not moved
moved = np.abs(np.asarray(to_body(S_home, M_home), dtype=float) - B_arm).max()
print(f"its B against the B of the same arm and tool at the origin: largest difference "
      f"{difference_text(moved)}")
print("last body axis, the flange's z axis seen from the tool:", B_arm[:, 5].round(4) + 0.0)

# %% [markdown]
# The two forms agree to round-off at every configuration, and B did not notice that the arm
# was bolted somewhere else: seen from the end effector, the joints have not moved. The tool
# sits 15 cm along the flange's z axis, so the last joint still turns about the tool's own
# z axis, (0, 0, 1, 0, 0, 0).

# %% [markdown]
# ## 11. Screw axes from any DH table
#
# Section 5 read the UR5's screw axes straight off its DH frames at $q = 0$: joint i turns
# about the z axis of frame i−1, through that frame's origin, so
# $S_i = (z_{i-1},\ -z_{i-1} \times p_{i-1})$, and $M = T_{0,6}(0)$ is the last frame. The
# frames came from `urkin.fk_frames`, which knows only UR arms. Any arm with a standard-DH
# table works the same way: build its frames at $q = 0$ one link at a time,
# $T_{0,i} = T_{0,i-1}\,T_{i-1,i}$ with lesson 02's link transform at θ = 0, and read each
# joint's axis from the frame *before* it.
#
# ### Exercise 3.8 — `screws_from_dh` (4 points)
#
# Write `screws_from_dh(rows)`: the space screw axes `S` and the home pose `M` of the revolute
# arm whose standard-DH table is `rows`, a numpy array of shape `(n, 3)` with one row
# $(d_i, a_i, \alpha_i)$ per joint (metres, metres, radians; any n ≥ 1; the row order of
# exercises 2.4 and 2.6, of `robot.dh_table()` and of `dh_chain`). Return a pair `(S, M)`:
#
# * `S`, shape `(6, n)`: column i − 1 is joint i's screw axis $(z_{i-1},\ -z_{i-1} \times
#   p_{i-1})$, ordered (ω, v), where $z_{i-1}$ and $p_{i-1}$ are the z axis and the origin of
#   DH frame i − 1 at q = 0 (frame 0 is the base: z = (0, 0, 1) through the origin);
# * `M`, shape `(4, 4)`: the end effector's pose at q = 0, DH frame n, $T_{0,n}(0)$.
#
# `urkin.kinematics.dh_transform` (lesson 02's exercise 2.1) gives the links, and your own
# `screw_axis` of exercise 3.1 may build the columns; urkin's `screw_axis`, `space_screws` and
# `body_screws`, which answer the exercise, are hidden while it is graded.
#
# *Checked* (to 1e-12; a float32 answer to float32's precision): (1 point) S and M of random
# UR arms' tables, `arm.dh_table()`, against `urkin.poe.space_screws(arm)`; (2 points) new arms
# of every n from 1 to 7 joints, with random lengths and twists; (1 point) with your S and M,
# the space form $e^{[S_1]q_1}\cdots e^{[S_n]q_n}M$ (`urkin.poe.fk_space`) gives the table's
# DH chain `dh_chain(rows, q)` at random q, to 1e-9 — for a UR arm and new arms of 1 to 7
# joints. The feedback recognises the frames taken one too late ($z_i$ through $p_i$: the
# modified-DH recipe), v = +z × p, the (v, ω) order, the axis of one frame with the origin of
# the next (or the other way round), the origin itself as v, the axis from the wrong column or
# row of the frame, rows read as (a, d, α), S transposed, M forgotten, inverted or taken one
# frame early, (M, S) returned in that order, and six joints hard-coded.

# %%
def screws_from_dh(rows):
    """Space screw axes and home pose of a revolute arm, from its standard-DH table.

    Parameters
    ----------
    rows : array_like, shape (n, 3)
        Standard-DH table, one row (d_i, a_i, α_i) per joint: metres, metres, radians.

    Returns
    -------
    S : ndarray, shape (6, n)
        Space-frame screw axes, one per column, each ordered (ω, v): joint i turns about the
        z axis z_(i−1) of DH frame i − 1 at q = 0, through its origin p_(i−1), so
        S[:, i − 1] = (z_(i−1), −z_(i−1) × p_(i−1)).
    M : ndarray, shape (4, 4)
        Pose of the end effector (DH frame n) at q = 0 in the base frame, T_0n(0) (metres).
    """
    ### BEGIN SOLUTION
    table = np.asarray(rows, dtype=float)
    T = np.eye(4)  # DH frame i at q = 0, starting with the base, frame 0
    S = np.zeros((6, len(table)))
    for i, (d, a, alpha) in enumerate(table):
        z, p = T[:3, 2], T[:3, 3]  # joint i + 1 turns about z of frame i, through its origin
        S[:3, i], S[3:, i] = z, -np.cross(z, p)
        T = T @ urkin.kinematics.dh_transform(0.0, d, a, alpha)
    return S, T
    ### END SOLUTION


# %%
check("3.8", screws_from_dh)

# %% [markdown]
# **Verify.** Two arms. The UR5's table must give back section 5's `S_ur5` and `M_ur5`. Then
# an arm urkin has no model of: seven joints, every $a_i = 0$ and twists of ±90°, the layout of
# many seven-joint arms (the lengths are made up). Its screw axes and M must reproduce its DH
# chain, `dh_chain`, at 1000 random configurations. The cell uses your `screws_from_dh`, or
# urkin's `space_screws` while the exercise is not written yet.

# %%
try:
    screws_from_dh(ur5.dh_table())
    from_table, source = screws_from_dh, "your screws_from_dh"
except NotImplementedError:
    from_table = urkin.poe.space_screws
    source = "urkin.poe.space_screws (exercise 3.8 is not written yet)"
print(f"screw axes from {source}")

S_table, M_table = (np.asarray(x, dtype=float) for x in from_table(ur5.dh_table()))
table_gap = max(np.abs(S_table - S_ur5).max(), np.abs(M_table - M_ur5).max())
print(f"UR5 table against section 5's S and M: largest difference {below(table_gap)}")

seven_rows = np.array(  # rows (d, a, α) of a made-up seven-joint arm: metres and radians
    [
        [0.36, 0.0, -np.pi / 2],
        [0.0, 0.0, np.pi / 2],
        [0.42, 0.0, np.pi / 2],
        [0.0, 0.0, -np.pi / 2],
        [0.40, 0.0, -np.pi / 2],
        [0.0, 0.0, np.pi / 2],
        [0.13, 0.0, 0.0],
    ]
)
S_seven, M_seven = (np.asarray(x, dtype=float) for x in from_table(seven_rows))
print("seven-joint arm, S (columns = joints 1 … 7):")
print(S_seven.round(4) + 0.0)
print("M, the flange at q = 0:")
print(M_seven.round(4) + 0.0)
q_seven = np.random.default_rng(38).uniform(-np.pi, np.pi, (1000, 7))
seven_gap = np.abs(urkin.poe.fk_space(M_seven, S_seven, q_seven)
                   - urkin.kinematics.dh_chain(seven_rows, q_seven)).max()
print(f"space form against dh_chain, 1000 random q: largest entry difference {below(seven_gap)}")

# %% [markdown]
# At $q = 0$ the seven-joint arm stands straight up. Its joints 1, 3, 5 and 7 all turn about
# the vertical line through the base origin, so all four have S = (0, 0, 1, 0, 0, 0); joints
# 2, 4 and 6 turn about horizontal lines along ±y at the heights h = 0.36, 0.78 and 1.18 m,
# and their $v = -\omega \times p = (-\omega_y h, 0, 0)$ carries the height. M is the flange
# 1.31 m above the base, turned like it. urkin has no model of this arm, and its space form
# is still its DH chain to round-off at every configuration: the recipe needs nothing but the
# table.

# %% [markdown]
# ## Summary
#
# * A **twist** $(\omega, v)$ is a rigid body's angular velocity and the velocity of its point
#   at the origin. A revolute joint's **screw axis** is $S = (\omega, -\omega \times q)$: unit
#   axis ω through any point $q$. Modern Robotics and `urkin.poe` order both **(ω, v)**; the
#   geometric Jacobian of `urkin.jacobian` orders its rows **[v; ω]** and refers v to the
#   flange. Convert with `space_from_geometric` / `geometric_from_space`.
# * $e^{[S]\theta}$ turns by θ about the screw axis: rotation $e^{[\omega]\theta}$ (Rodrigues)
#   and translation $(I\theta + (1 - \cos\theta)[\omega] + (\theta - \sin\theta)[\omega]^2)v =
#   (I - R)q$ — not $v\theta$, which only holds for pure translation.
# * **Space form:** $T = e^{[S_1]q_1} \cdots e^{[S_n]q_n} M$, with the home axes $S_i$ in the
#   base frame and **M the end-effector pose at q = 0** (not the base frame). The current axes
#   are $\mathrm{Ad}(e^{[S_1]q_1}\cdots)S_i$; the home axes never move.
# * **Body form:** $T = M e^{[B_1]q_1} \cdots e^{[B_n]q_n}$ with $B = \mathrm{Ad}(M^{-1})S$,
#   the adjoint $\mathrm{Ad}(T) = \begin{bmatrix} R & 0 \\ [p]R & R \end{bmatrix}$ taken of
#   $M^{-1} = (R^\mathsf{T}, -R^\mathsf{T}p)$. A new tool changes M and B (not S); a new
#   mounting changes M and S — only the body screws B are invariant to it.
# * From a standard-DH table, $S_i$ is the z axis of frame i−1 through its origin at q = 0,
#   and M the last frame (`urkin.poe.space_screws`, exercise 3.8, for any number of joints);
#   both DH conventions give the same S. Space form, body form and
#   DH agree to round-off on all seven UR arms.
# * Seed 001's screw axes and M describe a UR3 to within its 1 mm rounding, once its zero pose,
#   world frame and end-effector frame are matched to the DH model.
# * PoE needs no link frames and varies smoothly with the geometry; DH is more compact, gives
#   link frames for free and is what manufacturers publish.
# * The **matrix log** inverts the exponential: $V = (\omega\theta, \theta\,G^{-1}(\theta)p)$
#   with $G^{-1} = I/\theta - [\omega]/2 + (1/\theta - \cot(\theta/2)/2)[\omega]^2$; a pure
#   translation gives $(0, p)$, and at θ = π the axis comes from the symmetric part of R.
# * **Back to the joint:** for a unit ω, $\omega \times v = q - (\omega \cdot q)\,\omega$ is the
#   point of the axis nearest the origin, whichever point built $S$. A prismatic or
#   unnormalised ω has no such point: refuse it.
#
# ## What comes next
#
# **Lesson 04** is about velocities: how fast, and in which direction, the flange moves when
# the joints turn. It builds the geometric Jacobian `urkin.jacobian`, rows [v; ω], column by
# column from the joint axes — the current axes drawn in section 5 — and numerically by finite
# differences, and it finds the configurations where a UR arm loses a direction of motion.
#
# Before you move on: restart the kernel and run the whole notebook. All eight check cells
# should report full marks.
