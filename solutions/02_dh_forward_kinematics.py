# %% [markdown]
# # Lesson 02 — Denavit–Hartenberg forward kinematics
#
# *Forward kinematics* answers one question: given the six joint angles `q`, where is the
# flange, and how is it turned? For a serial arm the answer is a product of six transforms, one
# per joint, each depending on a single angle:
#
# $$T_{0,6}(q) = T_{0,1}(q_1)\, T_{1,2}(q_2)\, T_{2,3}(q_3)\, T_{3,4}(q_4)\, T_{4,5}(q_5)\,
# T_{5,6}(q_6).$$
#
# The Denavit–Hartenberg (DH) convention describes each of these link transforms with only four
# numbers, so a whole arm fits in a small table. Along the way you meet the two conventions that
# share the name and see why a table means nothing without its convention, derive the UR3's
# `T_0_6` in SymPy (first with numbers, then with symbolic lengths, which serves every UR arm at
# once), and put a published UR5 formula to the test.
#
# **What you will be able to do**
#
# * write the link transform of one DH row, and the forward kinematics of any DH table, in
#   numpy (exercises 2.1 and 2.2);
# * write the derived closed-form position (exercise 2.3), and test any such formula
#   against an independent reference at many random configurations, which tells right from
#   wrong where a hand-picked pose cannot (exercise 2.7);
# * derive `T_0_n` of an arm you have never seen, from its DH table, in SymPy (exercise 2.4);
# * predict where the flange is in a simple pose from the table alone, before any product
#   of matrices, and check the prediction (exercise 2.5);
# * rewrite a standard-DH table for the modified convention, with the tool transform that its
#   last row leaves over, and check that both describe the same arm (exercise 2.6).
#
# **Time:** about 2½ hours. **You need:** lesson 01 (rotations, homogeneous transforms and the
# `T_a_b` naming).

# %%
import inspect

import matplotlib.pyplot as plt
import numpy as np
import sympy as sp
from IPython.display import display

import urkin
import urkin.plot
import urkin.symbolic
from urkin.course import below, check
from urkin.course.seeds import (
    SEED002_ARM,
    SEED002_DH,
    SEED002_LENGTHS,
    SEED002_SHIFT,
    seed002_position,
)
from urkin.kinematics import dh_chain
from urkin.symbolic import LENGTHS, Q, simplify_angles
from urkin.transforms import make_transform, rot_x, rot_z

np.set_printoptions(precision=4, suppress=True)

# %% [markdown]
# ## Four numbers per joint
#
# Attach a frame to every link of the arm. The DH rules place them so that getting from frame
# `i−1` to frame `i` always takes the same four elementary motions, two along and about the old
# `z` axis and two along and about the new `x` axis. In the **standard** convention (Denavit and
# Hartenberg's, used by Universal Robots and by this course):
#
# $$T_{i-1,i} = R_z(\theta_i)\; T_z(d_i)\; T_x(a_i)\; R_x(\alpha_i)$$
#
# | number | motion | meaning |
# |---|---|---|
# | $\theta_i$ | rotate about $z_{i-1}$ | **joint angle**: $q_i$ plus a fixed offset (0 for UR) |
# | $d_i$ | slide along $z_{i-1}$ | **offset** along the joint axis, between two common normals |
# | $a_i$ | slide along $x_i$ | **length** of the common normal from axis $z_{i-1}$ to $z_i$ |
# | $\alpha_i$ | rotate about $x_i$ | **twist** that turns axis $z_{i-1}$ into axis $z_i$ |
#
# Axis $z_{i-1}$ is the axis of joint $i$, so only $\theta_i$ changes when the arm moves; $d$,
# $a$ and $\alpha$ are the arm's fixed geometry.
#
# The **modified** convention (Craig's textbook, many simulators) uses the same four motions in
# a different order, and attaches the link's own $a$ and $\alpha$ to the *next* joint's
# transform:
#
# $$T_{i-1,i} = R_x(\alpha_{i-1})\; T_x(a_{i-1})\; R_z(\theta_i)\; T_z(d_i)$$
#
# Its frame `i` sits on joint `i`'s own axis, at the near end of link `i`; the standard frame `i`
# sits on the axis of joint `i+1`, at the far end. Let SymPy multiply the four elementary
# transforms for us, in both orders, and compare with `urkin.symbolic.dh_transform`.

# %%
theta, d, a, alpha = sp.symbols("theta d a alpha", real=True)


def Rz(angle):
    return sp.Matrix([[sp.cos(angle), -sp.sin(angle), 0, 0],
                      [sp.sin(angle), sp.cos(angle), 0, 0],
                      [0, 0, 1, 0],
                      [0, 0, 0, 1]])


def Rx(angle):
    return sp.Matrix([[1, 0, 0, 0],
                      [0, sp.cos(angle), -sp.sin(angle), 0],
                      [0, sp.sin(angle), sp.cos(angle), 0],
                      [0, 0, 0, 1]])


def Tz(distance):
    return sp.Matrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, distance], [0, 0, 0, 1]])


def Tx(distance):
    return sp.Matrix([[1, 0, 0, distance], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])


standard_link = Rz(theta) * Tz(d) * Tx(a) * Rx(alpha)
modified_link = Rx(alpha) * Tx(a) * Rz(theta) * Tz(d)  # here a, α are the previous link's

print("standard DH, Rz(θ) Tz(d) Tx(a) Rx(α):")
display(standard_link)
print("modified DH, Rx(α) Tx(a) Rz(θ) Tz(d):")
display(modified_link)

same_standard = standard_link == urkin.symbolic.dh_transform(theta, d, a, alpha, "standard")
same_modified = modified_link == urkin.symbolic.dh_transform(theta, d, a, alpha, "modified")
print("equal to urkin.symbolic.dh_transform:", same_standard, "(standard),",
      same_modified, "(modified)")

# %% [markdown]
# Read the standard matrix column by column. The first three columns are the new $x$, $y$ and
# $z$ axes seen from frame `i−1`; the last column is where frame `i`'s origin lands: $d$ up the
# old $z$ axis, then $a$ along the new $x$ axis, which $\theta$ has turned to
# $(\cos\theta, \sin\theta, 0)$. The third row holds the $z$ components: the new $x$ axis stays
# in the old $x$–$y$ plane (0), and the new $z$ axis leans away from the old one by the twist
# ($\cos\alpha$). In the modified matrix the origin's $x$ coordinate is just $a$: the slide
# along $x$ comes first, and the later slide $d$ runs along a $z$ axis that the twist has tilted
# only within the old $y$–$z$ plane.
#
# The two products contain the same four letters but describe different motions. The figure
# applies both recipes to the same numbers, one elementary motion at a time.

# %%
link = {"θ": np.radians(40.0), "d": 0.20, "a": 0.30, "α": np.radians(90.0)}
elementary = {
    "Rz(θ)": make_transform(rot_z(link["θ"])),
    "Tz(d)": make_transform(p=[0.0, 0.0, link["d"]]),
    "Tx(a)": make_transform(p=[link["a"], 0.0, 0.0]),
    "Rx(α)": make_transform(rot_x(link["α"])),
}
recipes = {
    "standard DH: Rz(θ) Tz(d) Tx(a) Rx(α)": ["Rz(θ)", "Tz(d)", "Tx(a)", "Rx(α)"],
    "modified DH: Rx(α) Tx(a) Rz(θ) Tz(d)": ["Rx(α)", "Tx(a)", "Rz(θ)", "Tz(d)"],
}

fig = plt.figure(figsize=(13, 6.5))
for index, (name, steps) in enumerate(recipes.items()):
    ax = urkin.plot.axes3d(fig.add_subplot(1, 2, index + 1, projection="3d"),
                           center=(0.12, 0.0, 0.1), half_width=0.26, title=name)
    poses = [np.eye(4)]
    for step in steps:
        poses.append(poses[-1] @ elementary[step])
    origins = np.array([pose[:3, 3] for pose in poses])
    ax.plot(*origins.T, "--", color="0.5", linewidth=1.2, label="path of the origin")
    for k, pose in enumerate(poses):
        end = k in (0, len(steps))  # frames i−1 and i drawn large, the steps between small
        urkin.plot.draw_frame(ax, pose, length=0.1 if end else 0.06,
                              linewidth=3.0 if k == len(steps) else 1.2 + 0.8 * end, tips=end)
        # a rotation leaves the origin where it was: put that number below, not on top
        stayed = k > 0 and np.allclose(origins[k], origins[k - 1])
        offset = [0.0, 0.0, -0.06] if stayed else [-0.03, -0.03, 0.02]
        ax.text(*(origins[k] + offset), str(k), fontsize=12, fontweight="bold", ha="center")
    listing = ["0  frame i−1"] + [f"{k + 1}  after {step}" for k, step in enumerate(steps)]
    ax.text2D(0.0, 1.0, "\n".join(listing) + " = frame i", transform=ax.transAxes,
              verticalalignment="top", family="monospace", fontsize=9,
              bbox={"facecolor": "white", "alpha": 0.8})
    for colour, axis in zip(urkin.plot.AXIS_COLOURS, "xyz"):
        ax.plot([], [], color=colour, label=f"{axis} axis")
    ax.view_init(elev=22, azim=-58)
    ax.legend(loc="upper right", fontsize=8)
fig.suptitle("One link, θ = 40°, d = 0.20 m, a = 0.30 m, α = 90°: "
             "the same numbers in two conventions")
plt.show()

# %% [markdown]
# Same four numbers, two different frames `i`: in the standard recipe frame `i` ends up above
# the old $x$–$y$ plane, in the modified recipe beside it. That is why **a DH table is tied to
# its convention**. Feed UR's standard table into the modified formula and the arm you compute
# is simply another arm.
#
# A table *can* be rewritten for the other convention. Because $T_x(a)$ and $R_x(\alpha)$
# commute (both act along the same $x$ axis), the standard chain regroups as
# $R_z(\theta_1)T_z(d_1)\,\big[T_x(a_1)R_x(\alpha_1)R_z(\theta_2)T_z(d_2)\big]\cdots$: every
# bracket is a modified link whose $a$ and $\alpha$ come from the row *above*. So the modified
# table of a UR arm keeps the $d$ column and shifts the $a$ and $\alpha$ columns down by one row
# (this works because UR's last row has $a_6 = \alpha_6 = 0$). The flange lands in the same
# place; the frames in between do not.

# %%
ur3 = urkin.robot("UR3")
q_test = np.random.default_rng(2).uniform(-np.pi, np.pi, 6)

modified_table = np.column_stack([ur3.d, np.r_[0.0, ur3.a[:-1]], np.r_[0.0, ur3.alpha[:-1]]])
print("UR3, rewritten for the modified convention: rows (d_i, a_(i-1), α_(i-1)), m and rad")
print(modified_table)

p_right = urkin.fk(ur3, q_test)[:3, 3]
p_rewritten = dh_chain(modified_table, q_test, convention="modified")[:3, 3]
p_mixed_up = dh_chain(ur3.dh_table(), q_test, convention="modified")[:3, 3]
print(f"\nflange at q = {q_test}")
print(f"standard table, standard formula  p = {p_right} m")
print(f"rewritten table, modified formula p = {p_rewritten} m")
print(f"standard table, modified formula  p = {p_mixed_up} m   "
      f"({np.linalg.norm(p_mixed_up - p_right):.3f} m away)")

# %% [markdown]
# ### Exercise 2.1 — `dh_transform` (4 points)
#
# Write `dh_transform(theta, d, a, alpha)`, the **standard**-DH link transform
# $T_{i-1,i} = R_z(\theta)\,T_z(d)\,T_x(a)\,R_x(\alpha)$, as a numpy array of shape `(4, 4)`.
# The four arguments are plain numbers: angles in radians, lengths in metres. Type the matrix
# you displayed above; numpy's `np.cos` and `np.sin` do the rest.
#
# *Checked* (to 1e-9; a float32 answer to float32's precision): that the result is a
# homogeneous transform, and that it equals $R_z(\theta)T_z(d)T_x(a)R_x(\alpha)$ for random
# links. urkin's own `dh_transform` and `dh_chain` are hidden while this exercise is graded.

# %%
def dh_transform(theta, d, a, alpha):
    """Standard Denavit–Hartenberg link transform T_(i-1),i = Rz(θ) Tz(d) Tx(a) Rx(α).

    Parameters
    ----------
    theta : float
        Joint angle θ_i about z_(i-1), radians.
    d : float
        Offset d_i along z_(i-1), metres.
    a : float
        Length a_i along x_i, metres.
    alpha : float
        Twist α_i about x_i, radians.

    Returns
    -------
    ndarray, shape (4, 4)
        The homogeneous transform from frame i-1 to frame i (pose of frame i in frame i-1).
    """
    ### BEGIN SOLUTION
    ct, st = np.cos(theta), np.sin(theta)
    ca, sa = np.cos(alpha), np.sin(alpha)
    return np.array(
        [
            [ct, -st * ca, st * sa, a * ct],
            [st, ct * ca, -ct * sa, a * st],
            [0.0, sa, ca, d],
            [0.0, 0.0, 0.0, 1.0],
        ]
    )
    ### END SOLUTION


# %%
check("2.1", dh_transform)

# %% [markdown]
# ## The UR3's table, and its forward kinematics in SymPy
#
# This course draws on four published student reports about UR kinematics, which it calls
# *seeds* and numbers (seed 000, seed 002, …). Seed 000, a UR3 project, lists the UR3's
# standard-DH table: twists $\alpha = (\pi/2, 0, 0, \pi/2, -\pi/2, 0)$, zero $\theta$ offsets,
# and six non-zero lengths. Here it is, typed in metres and radians, next to the table urkin
# keeps from Universal Robots' own publication.

# %%
seed000_table = np.array(  # rows (d_i, a_i, α_i), metres and radians, as seed 000 lists them
    [
        [0.1519, 0.0, np.pi / 2],
        [0.0, -0.24365, 0.0],
        [0.0, -0.21325, 0.0],
        [0.11235, 0.0, np.pi / 2],
        [0.08535, 0.0, -np.pi / 2],
        [0.0819, 0.0, 0.0],
    ]
)
print("joint |      seed 000: d (m)   a (m)   α (°) |   urkin UR3: d (m)   a (m)   α (°)")
for joint, (mine, theirs) in enumerate(zip(seed000_table, ur3.dh_table()), start=1):
    left = f"{mine[0]:8.5f} {mine[1]:8.5f} {np.degrees(mine[2]) + 0.0:6.0f}"
    right = f"{theirs[0]:8.5f} {theirs[1]:8.5f} {np.degrees(theirs[2]) + 0.0:6.0f}"
    print(f"  {joint}   |      {left}   |      {right}")
print("identical:", np.array_equal(seed000_table, ur3.dh_table()))

# %% [markdown]
# Two things to notice. The lengths $a_2$ and $a_3$ are **negative**: at `q = 0` the UR arm is
# stretched out along $-x_0$, while the DH $x$ axes point along $+x_0$, so the upper arm and
# forearm lie a negative distance along them. That is UR's choice, and the angles the UR
# controller shows depend on it; another choice of $x$ axes gives positive lengths *and*
# different joint angles for the same physical pose (we meet one below). And $d_2 = d_3 = 0$,
# although the real upper arm and forearm are offset sideways from each other: more on that
# when we draw the frames.
#
# Now the derivation. `symbolic_chain` multiplies the link matrices of a table one at a time,
# with symbolic joint angles $q_1 \dots q_6$, and simplifies after every product with
# `urkin.symbolic.simplify_angles`: it multiplies everything out, cancels $\sin^2 + \cos^2$
# pairs, and folds products such as $\cos q_2 \cos q_3 - \sin q_2 \sin q_3$ back into
# $\cos(q_2 + q_3)$ with the four sum-of-angle identities. (SymPy's general
# `sp.trigsimp(sp.expand(expr))` gives the same expressions here, about thirty times more
# slowly: it tries every identity it knows, where a chain of revolute joints only ever needs
# these.) Simplifying as we go keeps every intermediate matrix small.
#
# The twists are typed as exact SymPy numbers (`sp.pi / 2`): with the float `np.pi / 2`,
# $\cos\alpha$ would be $6 \cdot 10^{-17}$ instead of 0, and every entry would drag along
# terms that should not exist.

# %%
def symbolic_chain(rows):
    """T_0_n of a standard-DH chain with rows (d_i, a_i, α_i) and joint angles q1, q2, …"""
    T = sp.eye(4)
    for q, (d_i, a_i, alpha_i) in zip(Q, rows):
        link_i = urkin.symbolic.dh_transform(q, d_i, a_i, alpha_i, "standard")
        T = (T * link_i).applyfunc(simplify_angles)
    return T


ur3_rows = [  # seed 000's numbers, with exact twists
    (0.1519, 0, sp.pi / 2),
    (0, -0.24365, 0),
    (0, -0.21325, 0),
    (0.11235, 0, sp.pi / 2),
    (0.08535, 0, -sp.pi / 2),
    (0.0819, 0, 0),
]
T06_ur3 = symbolic_chain(ur3_rows)
print("UR3 flange position p(q) = T_0_6[:3, 3], metres:")
display(T06_ur3[:3, 3])

# %% [markdown]
# Every term is a length times sines and cosines of single angles or of the sums $q_2 + q_3$
# and $q_2 + q_3 + q_4$: joints 2, 3 and 4 turn about parallel axes, so only their running
# sums matter to what comes after them.
#
# A formula is only as good as its test. `sp.lambdify` turns the SymPy matrix into a numpy
# function; we evaluate it at a thousand seeded random configurations and compare with
# `urkin.fk`, urkin's generated forward kinematics, which its test suite checks against plain
# products of numeric DH matrices.

# %%
ur3_T06 = sp.lambdify(Q, T06_ur3, "numpy")
q_random = np.random.default_rng(0).uniform(-np.pi, np.pi, (1000, 6))
T_lambdified = np.array([ur3_T06(*q) for q in q_random], dtype=float)
T_urkin = urkin.fk(ur3, q_random)
largest = np.abs(T_lambdified - T_urkin).max()
print(f"largest difference over {len(q_random)} poses, any entry of T_0_6: "
      f"{'below 1e-12' if largest < 1e-12 else f'{largest:.3g}'}")

# %% [markdown]
# ## One derivation for every UR arm
#
# All seven UR arms share the twists; only the six lengths differ. So keep the lengths as
# symbols too, and derive once. The result is what `urkin.symbolic.ur_t06()` returns, and what
# urkin's generated numpy code evaluates for every arm.

# %%
d1, a2, a3, d4, d5, d6 = LENGTHS
general_rows = [
    (d1, 0, sp.pi / 2),
    (0, a2, 0),
    (0, a3, 0),
    (d4, 0, sp.pi / 2),
    (d5, 0, -sp.pi / 2),
    (d6, 0, 0),
]
T06_general = symbolic_chain(general_rows)
p_general = T06_general[:3, 3]
print("flange position of any UR arm, p(q; d1, a2, a3, d4, d5, d6):")
display(p_general)
print("identical to urkin.symbolic.ur_t06():", T06_general == urkin.symbolic.ur_t06())

# %% [markdown]
# Read $p$ from the base outwards, with $c_1 = \cos q_1$, $s_{234} = \sin(q_2+q_3+q_4)$ and so
# on:
#
# * $a_2 \cos q_2 + a_3 \cos(q_2 + q_3)$ is how far the upper arm and forearm reach
#   horizontally in the arm's vertical plane, which joint 1 turns to the direction
#   $(c_1, s_1, 0)$; their heights $a_2 s_2 + a_3 s_{23}$ add to $d_1$ in $p_z$;
# * $d_4\,(s_1, -c_1, 0)$ is the sideways offset along the wrist-1 axis $z_3$, perpendicular to
#   that plane;
# * $d_5$ runs along the wrist-2 axis $z_4 = (c_1 s_{234},\ s_1 s_{234},\ -c_{234})$;
# * $d_6$ multiplies the third column of the rotation, the flange's $z$ axis, which is also the
#   wrist-3 axis: the flange sits $d_6$ beyond frame 5 along its own approach direction. So
#   $p - d_6 z_6$, the origin of frame 5, cannot depend on $q_5$ or $q_6$ — a property we shall
#   use to catch a typo.
#
# One substitution turns the general formula into any arm's. For the UR5 at home,
# `q = [0, −π/2, 0, −π/2, 0, 0]`, the arm points straight up: $p = (0,\,-d_4-d_6,\,
# d_1 - a_2 - a_3 + d_5)$.

# %%
ur5 = urkin.robot("UR5")
home = np.array([0.0, -np.pi / 2, 0.0, -np.pi / 2, 0.0, 0.0])
p_ur5 = p_general.subs(dict(zip(LENGTHS, ur5.lengths)))
p_ur5_home = np.array(p_ur5.subs(dict(zip(Q, home))).evalf(), dtype=float).ravel()


def metres(p):
    """A position as text, 5 decimals (round first, then + 0.0, so that no "-0.00000" shows)."""
    return "(" + ", ".join(f"{round(float(v), 5) + 0.0:.5f}" for v in p) + ") m"


print("UR5 at home, general formula:", metres(p_ur5_home))
print("UR5 at home, urkin.fk:       ", metres(urkin.fk(ur5, home)[:3, 3]))

# %% [markdown]
# ### Exercise 2.2 — `forward_kinematics` (5 points)
#
# Write `forward_kinematics(robot, q)`, which returns the flange pose $T_{0,6}$ of any UR arm
# for one configuration `q` of shape `(6,)`, as a `(4, 4)` numpy array. Multiply the six link
# transforms **of your own `dh_transform`** in order, from the base outwards, with
# $\theta_i = q_i$ and the arm's DH values `robot.d`, `robot.a` and `robot.alpha` (numpy arrays
# of six numbers each; metres and radians).
#
# *Checked* (to 1e-9; a float32 answer to float32's precision): a homogeneous transform;
# UR's flange position at `q = 0` for all seven arms; the DH chain for random arms and
# configurations; and `q` given as a plain list of six numbers. The feedback recognises the
# usual slips: links multiplied in reverse order, the modified formula, and `a2`, `a3` with the
# wrong sign. urkin's own forward kinematics (`urkin.fk`, `fk_frames`, `dh_chain`, the PoE and
# SymPy versions) is hidden while this exercise is graded; your `dh_transform` is not.

# %%
def forward_kinematics(robot, q):
    """Flange pose T_0_6 of a UR arm: the product of its six standard-DH link transforms.

    Parameters
    ----------
    robot : urkin.Robot
        The arm; ``robot.d``, ``robot.a`` (metres) and ``robot.alpha`` (radians) are arrays of
        its six DH offsets, lengths and twists.
    q : array_like, shape (6,)
        Joint angles in radians (θ_i = q_i: UR's θ offsets are zero).

    Returns
    -------
    ndarray, shape (4, 4)
        T_0_6, the pose of the flange (DH frame 6) in the base frame (DH frame 0); metres.
    """
    ### BEGIN SOLUTION
    T = np.eye(4)
    for angle, d_i, a_i, alpha_i in zip(np.asarray(q, dtype=float), robot.d, robot.a,
                                        robot.alpha):
        T = T @ dh_transform(angle, d_i, a_i, alpha_i)
    return T
    ### END SOLUTION


# %%
check("2.2", forward_kinematics)

# %% [markdown]
# ## Seven arms, one formula
#
# With the formula in hand, every arm is a table lookup away. At `q = 0` every UR arm lies
# stretched out along $-x_0$, and the general $p$ collapses to $(a_2 + a_3,\ -d_4 - d_6,\
# d_1 - d_5)$; at home it points straight up, at $(0,\ -d_4 - d_6,\ d_1 - a_2 - a_3 + d_5)$.

# %%
zero = np.zeros(6)
print("flange position p (m)      at q = 0                     at home")
print("arm        x        y        z         x        y        z")
for name in urkin.ROBOTS:
    robot = urkin.robot(name)
    at_zero = urkin.fk(robot, zero)[:3, 3].round(4) + 0.0  # + 0.0 avoids "-0.0000"
    at_home = urkin.fk(robot, home)[:3, 3].round(4) + 0.0
    print(f"{name:<6} " + " ".join(f"{v:8.4f}" for v in at_zero) + "  "
          + " ".join(f"{v:8.4f}" for v in at_home))

# %% [markdown]
# The figure draws all seven at one and the same configuration, once in 3D and once seen from
# the side (onto the $x$–$z$ plane, which the arm's links lie close to when $q_1 = 0$). Equal
# angles, equal shapes, different sizes: the UR10e reaches more than twice as far as the UR3.

# %%
q_show = np.array([0.0, -np.pi / 3, 4 * np.pi / 9, -np.pi / 9, np.pi / 2, 0.0])
colours = plt.cm.viridis(np.linspace(0.0, 0.9, len(urkin.ROBOTS)))

fig = plt.figure(figsize=(13, 6))
ax3d = urkin.plot.axes3d(fig.add_subplot(1, 2, 1, projection="3d"),
                         center=(-0.55, -0.15, 0.35), half_width=0.65,
                         title="3D view (stick figures through the DH frame origins)")
side = fig.add_subplot(1, 2, 2)
for name, colour in zip(urkin.ROBOTS, colours):
    robot = urkin.robot(name)
    urkin.plot.draw_robot(ax3d, robot, q_show, frames=False, color=colour, label=name,
                          linewidth=2.5)
    origins = urkin.fk_frames(robot, q_show)[:, :3, 3]
    side.plot(origins[:, 0], origins[:, 2], "-o", color=colour, label=name, markersize=4)
ax3d.view_init(elev=20, azim=-60)
ax3d.legend(loc="upper left", fontsize=8)
side.set_aspect("equal")
side.set_xlabel("x (m)")
side.set_ylabel("z (m)")
side.set_title("seen from the side: projection onto the x–z plane")
side.grid(True, alpha=0.3)
side.legend(loc="lower left", fontsize=8)
degrees = ", ".join(f"{v:.0f}" for v in np.degrees(q_show) + 0.0)
fig.suptitle(f"The seven UR arms at the same q = [{degrees}]°")
plt.show()

# %% [markdown]
# ## Where the DH frames sit
#
# `urkin.plot.draw_robot` (and `show_robot`, which adds the pose panel) draws the arm as
# straight segments between the origins of DH frames 0 to 6, with each frame's axes. It is
# tempting to read those origins as "the joints". They are not, quite. The DH rules put
# frame `i` **on the axis of joint `i+1`** (its $z$ axis *is* that joint axis), at the foot of
# the common normal from the previous axis. So:
#
# * frame 0 sits on the base axis at the mounting face, and frame 1 on the same axis, $d_1$
#   higher, where the shoulder axis crosses it: inside the base column, not at the shoulder
#   motor, which is mounted off to the side on that same axis;
# * frames 2 and 3 sit on the elbow and wrist-1 axes, in the same vertical plane as frame 1.
#   Joints 2, 3 and 4 turn about parallel axes, and between parallel axes the common normal
#   can slide freely, so DH chooses $d_2 = d_3 = 0$. The real arm steps sideways at the
#   shoulder, back at the elbow and out again at wrist 1; DH lumps all three steps into $d_4$;
# * frames 4, 5 and 6 follow the wrist: $d_4$, $d_5$ and $d_6$ along successive $z$ axes, the
#   last one ending on the flange face. Frame 6 is the flange (URDF's `tool0`).
#
# The dotted lines below are the joint axes: each $z_{i-1}$ extended through frame `i−1`, the
# axis joint `i` turns about. Every frame origin lies on one of them.

# %%
q_frames = np.array([0.5, -1.2, 1.4, -1.8, -1.2, 0.6])
frames_ur3 = urkin.fk_frames(ur3, q_frames)  # (7, 4, 4): DH frames 0 … 6
ax = urkin.plot.axes3d(center=(-0.14, -0.15, 0.19), half_width=0.24, figsize=(8, 8),
                       title="UR3: DH frames 0–6 (x red, y green, z blue) and joint axes")
urkin.plot.draw_robot(ax, ur3, q_frames, frames=True, frame_length=0.05,
                      label="links between DH origins")
for i, pose in enumerate(frames_ur3):
    origin, z_axis = pose[:3, 3], pose[:3, 2]
    ax.text(*(origin + 0.012), f"{i}", fontsize=12, fontweight="bold")
    if i < 6:
        axis_line = np.array([origin - 0.1 * z_axis, origin + 0.1 * z_axis])
        ax.plot(*axis_line.T, ":", color="tab:purple", linewidth=1.5,
                label="joint axes: z_(i−1) is the axis of joint i" if i == 0 else None)
ax.text2D(0.0, 0.97, urkin.plot.pose_text(frames_ur3[-1]), transform=ax.transAxes,
          verticalalignment="top", family="monospace", fontsize=8,
          bbox={"facecolor": "white", "alpha": 0.8})
ax.legend(loc="upper right", fontsize=8)
ax.view_init(elev=25, azim=-40)
plt.show()

steps = np.linalg.norm(np.diff(frames_ur3[:, :3, 3], axis=0), axis=1)
print("distance between consecutive DH origins (m):", "  ".join(f"{v:.5f}" for v in steps))
print("|d1|, |a2|, |a3|, |d4|, |d5|, |d6| (m):       ",
      "  ".join(f"{v:.5f}" for v in np.abs(ur3.lengths)))

# %% [markdown]
# The distances between consecutive origins are exactly the six lengths of the table, whatever
# the pose: each link transform moves the origin by $d$ along one axis and $a$ along a
# perpendicular one, and only one of the two is non-zero on a UR arm.
#
# ## A published formula put to the test
#
# Seed 002 is a UR5 project. It prints a closed-form flange position (in millimetres), uses it
# for a Newton–Raphson inverse kinematics, and says it verified the formula with its own
# implementation of the DH chain. It does not print the pose it checked at; we will find
# that its formula agrees with the true chain exactly where $\cos(q_2 + q_3 + q_4) = 0$ or
# $\sin q_5 = 1$, so its test pose must have been one of those — for instance
# $q_2 + q_3 + q_4 = 90°$, the pose ERRATA names. That is an inference, not a quote: a pose with
# $q_5 = 90°$ would have passed as well. Let us repeat such a test, and then test more
# carefully.
#
# The report works in its own convention: positive $a_2 = 425$ mm and $a_3 = 392$ mm, lengths
# 89.2, 425, 392, 109.3, 94.75 and 82.5 mm (close to, but not exactly, UR's UR5 numbers), and
# therefore its own joint angles. Its formula is transcribed once, in metres, in
# `urkin.course.seeds`, as a function that accepts numpy arrays *or* SymPy symbols: one
# transcription,
# used to compute and to reason here and again in lessons 04 and 05, means one chance of a
# typo instead of several. Here are its terms, exactly as the report prints them:

# %%
print(inspect.getsource(seed002_position).split('"""')[2].strip("\n"), end="\n\n")
print("      seed 002 (mm)   UR's UR5 (mm)")
for symbol, theirs, ours in zip(LENGTHS, SEED002_LENGTHS, np.abs(ur5.lengths)):
    print(f"{symbol!s:>3}   {1000 * theirs:10.3f}   {1000 * ours:10.3f}")

# %% [markdown]
# **Its angles are not UR's angles.** Flipping the sign of $a_2$ and $a_3$ is the same as
# turning the $x$ axes of frames 2 and 3 by half a turn, so the same physical pose has
# $q^{\text{seed}} = q^{\text{UR}} + (0, \pi, 0, -\pi, 0, 0)$: the half turn enters at joint 2
# and leaves at joint 4. Check it numerically: the seed's table `SEED002_DH` through
# `dh_chain` at the shifted angles against `urkin.fk` of `SEED002_ARM`, an arm with the
# seed's lengths in UR's sign convention (both from `urkin.course.seeds`).

# %%
print("SEED002_SHIFT =", SEED002_SHIFT.round(5))
print("SEED002_ARM =", SEED002_ARM)
q_ur = np.random.default_rng(3).uniform(-np.pi, np.pi, (1000, 6))
shift_gap = np.abs(dh_chain(SEED002_DH, q_ur + SEED002_SHIFT) - urkin.fk(SEED002_ARM, q_ur)).max()
print(f"seed table at q_UR + SEED002_SHIFT vs urkin.fk at q_UR, 1000 poses: largest difference "
      f"{'below 1e-12' if shift_gap < 1e-12 else f'{shift_gap:.3g}'}")

# %% [markdown]
# Now a test like the one the report must have run: a pose with $q_2 + q_3 + q_4 = 90°$ (the
# sum is the same in both conventions, since the shifts $+\pi$ and $-\pi$ cancel). Here,
# 0.35 rad on every joint except $q_4$, which makes up the 90°. The "true" answer is the
# report's *own* DH chain.

# %%
def millimetres(p):
    """A position in metres as text in millimetres, 3 decimals."""
    return "(" + ", ".join(f"{round(1000 * float(v), 3) + 0.0:9.3f}" for v in p) + ") mm"


q_blind = np.array([0.35, 0.35, 0.35, np.pi / 2 - 0.70, 0.35, 0.35])  # seed angles
print(f"q2 + q3 + q4 = {np.degrees(q_blind[1:4].sum()):.1f}°")
print("its DH chain:", millimetres(dh_chain(SEED002_DH, q_blind)[:3, 3]))
print("its formula: ", millimetres(seed002_position(q_blind, SEED002_LENGTHS)))

# %% [markdown]
# Perfect agreement, to the micrometre. Now change only $q_4$, so that all six joints are at
# 0.35 rad:

# %%
q_all = np.full(6, 0.35)  # seed angles
p_chain = dh_chain(SEED002_DH, q_all)[:3, 3]
p_formula = np.array(seed002_position(q_all, SEED002_LENGTHS))
print("its DH chain:", millimetres(p_chain))
print("its formula: ", millimetres(p_formula))
print(f"off by {1000 * np.linalg.norm(p_formula - p_chain):.3f} mm")
print("\nthe same pose in UR's angles, q_UR = q_seed − SEED002_SHIFT =", q_all - SEED002_SHIFT)
print("urkin.fk:    ", millimetres(urkin.fk(SEED002_ARM, q_all - SEED002_SHIFT)[:3, 3]))

# %% [markdown]
# 27 mm off, in $x$ and $y$ only. A mistake in a formula is best found symbolically:
# subtract the published $p$ from the derived one and simplify. Both describe a standard-DH
# chain with UR's twists and arbitrary lengths, so `p_general` applies to the report's
# convention as it stands — only the numbers plugged in differ.

# %%
p_published = sp.Matrix(seed002_position(Q, LENGTHS, sp.cos, sp.sin))
p_error = (p_published - p_general).applyfunc(lambda e: sp.factor(sp.trigsimp(e)))
print("published p − derived p:")
display(p_error)

# %% [markdown]
# There it is. The derived $p_x$ contains $-d_6 \cos q_1 \cos(q_2+q_3+q_4) \sin q_5$; the
# published one has $-d_6 \cos q_1 \cos(q_2+q_3+q_4)$: **the factor $\sin q_5$ is missing**,
# and the same in $p_y$. $p_z$ is right. The error vector has length
#
# $$\|e\| = d_6\,|\cos(q_2+q_3+q_4)|\,(1 - \sin q_5),$$
#
# which is zero whenever $\cos(q_2+q_3+q_4) = 0$ or $\sin q_5 = 1$ — the only poses at which
# the report's verification could have passed, and which could therefore never reveal it — and
# reaches $2 d_6 = 165$ mm when $\sin q_5 = -1$ and $|\cos(q_2+q_3+q_4)| = 1$. At the
# report's `q = 0` it is already $d_6 = 82.5$ mm.
#
# The property from earlier catches the slip without any reference formula: $p - d_6 z_6$ is
# the origin of frame 5, which cannot depend on $q_5$. With the report's own third column
# (whose entries are right) the published $p$ fails that test:

# %%
z6 = T06_general[:3, 2]  # the report prints the same third column (r13, r23, r33)
wrist_published = (p_published - d6 * z6).applyfunc(simplify_angles)
print("published p − d6·z6 depends on q5:", any(e.has(Q[4]) for e in wrist_published))
print("derived   p − d6·z6 depends on q5:",
      any(e.has(Q[4]) for e in (p_general - d6 * z6).applyfunc(simplify_angles)))

# %% [markdown]
# How big is the error over the whole workspace? The figure evaluates both the chain and the
# formula at 3000 seeded random configurations.

# %%
q_many = np.random.default_rng(4).uniform(-np.pi, np.pi, (3000, 6))  # seed angles
chain_many = dh_chain(SEED002_DH, q_many)[:, :3, 3]
formula_many = np.array(seed002_position(q_many.T, SEED002_LENGTHS)).T
error_mm = 1000 * np.linalg.norm(formula_many - chain_many, axis=1)
c234_many = np.cos(q_many[:, 1:4].sum(axis=1))
q5_many = q_many[:, 4]
d6_mm = 1000 * SEED002_LENGTHS[5]

fig, (left, right) = plt.subplots(1, 2, figsize=(13, 5))
dots = left.scatter(c234_many, error_mm, c=np.sin(q5_many), cmap="coolwarm", s=6,
                    label="random configurations")
c_line = np.linspace(-1.0, 1.0, 201)
left.plot(c_line, 2 * d6_mm * np.abs(c_line), "k--", linewidth=1.2,
          label="2·d6·|cos(q2+q3+q4)|, reached at sin q5 = −1")
left.set_xlabel("cos(q2 + q3 + q4)")
left.set_ylabel("|published p − true p| (mm)")
left.set_title("error against cos(q2 + q3 + q4): zero where it is 0")
left.set_ylim(-5, 225)
left.legend(loc="upper center", fontsize=8)
fig.colorbar(dots, ax=left, label="sin q5")

dots_right = right.scatter(q5_many, error_mm, c=np.abs(c234_many), cmap="viridis", s=6,
                           label="random configurations")
q5_line = np.linspace(-np.pi, np.pi, 201)
right.plot(q5_line, d6_mm * (1 - np.sin(q5_line)), "k--", linewidth=1.2,
           label="d6·(1 − sin q5), reached at |cos(q2+q3+q4)| = 1")
right.axhline(2 * d6_mm, color="tab:red", linewidth=1.0, label=f"2·d6 = {2 * d6_mm:.0f} mm")
right.set_xlabel("q5 (rad, seed 002's angle = UR's)")
right.set_ylabel("|published p − true p| (mm)")
right.set_title("error against q5: zero at q5 = π/2")
right.set_ylim(-5, 225)
right.legend(loc="upper right", fontsize=8)
fig.colorbar(dots_right, ax=right, label="|cos(q2 + q3 + q4)|")
fig.suptitle("Seed 002's UR5 position formula against its own DH chain, 3000 random poses")
plt.show()

print(f"largest error in the sample: {error_mm.max():.1f} mm (bound 2·d6 = {2 * d6_mm:.1f} mm)")
near_blind = np.abs(c234_many) < 0.01
print(f"largest error where |cos(q2+q3+q4)| < 0.01: {error_mm[near_blind].max():.2f} mm")
print(f"median error: {np.median(error_mm):.1f} mm")

# %% [markdown]
# The lesson generalises: **test a formula at random configurations, not at one hand-picked
# pose.** Special poses are special precisely because terms vanish there, and a vanishing term
# hides its own mistakes.
#
# The report's rotation matrix has two more slips. Its $r_{12}$ carries $\cos q_6$ in its first
# term where $\sin q_6$ belongs, and its $r_{22}$ has a bare $-\cos(q_2+q_3+q_4)$ where
# $-\sin q_1 \cos(q_2+q_3+q_4) \cos q_5 \sin q_6$ belongs. SymPy shows the differences:

# %%
q1, q2, q3, q4, q5, q6 = Q
c234_s, s234_s = sp.cos(q2 + q3 + q4), sp.sin(q2 + q3 + q4)
r12_published = (-sp.cos(q1) * c234_s * sp.cos(q5) * sp.cos(q6) - sp.sin(q1) * sp.sin(q5)
                 * sp.sin(q6) - sp.cos(q1) * sp.cos(q6) * s234_s)
r22_published = (-c234_s + sp.cos(q1) * sp.sin(q5) * sp.sin(q6)
                 - sp.cos(q6) * sp.sin(q1) * s234_s)
print("r12: published − derived =")
display(sp.expand(r12_published - T06_general[0, 1]))
print("r22: published − derived =")
display(sp.expand(r22_published - T06_general[1, 1]))

# %% [markdown]
# Finally, the report differentiates its $p$ by hand to get the Jacobian that drives its
# Newton–Raphson solver. Checked entry by entry, the differentiation itself is right: each
# entry is the exact derivative of the *published* $p$, so the Jacobian inherits the missing
# factor. The number of wrong entries is the number of non-zero entries in the Jacobian of the
# error:

# %%
error_jacobian = p_error.jacobian(Q).applyfunc(sp.simplify)
wrong = [(row, col) for row in range(3) for col in range(6) if error_jacobian[row, col] != 0]
print(f"{len(wrong)} of 18 entries are wrong:")
print(", ".join(f"∂p_{'xyz'[r]}/∂q{c + 1}" for r, c in wrong))

# %% [markdown]
# Because this Jacobian is consistent with the wrong $p$, Newton–Raphson still converges — to
# joint angles at which the *formula* reaches the target, while the real arm can be up to
# 165 mm away. A later lesson, on Jacobians and numerical inverse kinematics, returns to this
# report.
#
# ### Exercise 2.3 — `ur5_position` (4 points)
#
# Write `ur5_position(q)`: the closed-form position of the **UR5**'s flange, the last column of
# $T_{0,6}$, as a numpy array of shape `(3,)` in metres, for UR joint angles `q` (radians,
# shape `(6,)`) and UR's lengths `urkin.robot("UR5").lengths` (with negative $a_2$, $a_3$).
#
# Start from the SymPy derivation, not from a product of matrices. Two ways work:
#
# * type the formula of `p_general` with numpy (`np.cos`, `np.sin`), reading it off the display
#   above; or
# * substitute the UR5's lengths into `p_general` and `sp.lambdify` it over `Q` in a cell of
#   its own, *outside* the function (so that it is built once), and call the result inside
#   (a lambdified column matrix returns shape `(3, 1)`: flatten it).
#
# *Checked* (to 1e-9; a float32 answer to float32's precision): the UR5's flange position for
# random `q`, and at poses with $q_2 + q_3 + q_4 = 90°$; and that the function is a closed
# form — the check reads your code, which must not multiply matrices (`@`, `np.dot`,
# `np.matmul`) or call your `dh_transform` or `forward_kinematics`. The feedback recognises seed
# 002's formula if you copy it. urkin's forward kinematics (`urkin.fk`, `fk_frames`,
# `dh_chain`, `dh_transform`, `urkin.symbolic.ur_t06` and `ur_frames`) is hidden while this
# exercise is graded; the symbols and `simplify_angles` of `urkin.symbolic` are not.

# %%
def ur5_position(q):
    """Closed-form flange position of the UR5, from the symbolic forward kinematics.

    Parameters
    ----------
    q : array_like, shape (6,)
        UR joint angles in radians (the angles urkin and the UR controller use).

    Returns
    -------
    ndarray, shape (3,)
        Position (x, y, z) of the flange origin (DH frame 6) in the base frame (DH frame 0),
        metres, for the UR5's lengths ``urkin.robot("UR5").lengths``.
    """
    ### BEGIN SOLUTION
    d1, a2, a3, d4, d5, d6 = urkin.robot("UR5").lengths
    q1, q2, q3, q4, q5, _ = np.asarray(q, dtype=float)
    c1, s1 = np.cos(q1), np.sin(q1)
    c5, s5 = np.cos(q5), np.sin(q5)
    c234, s234 = np.cos(q2 + q3 + q4), np.sin(q2 + q3 + q4)
    reach = a2 * np.cos(q2) + a3 * np.cos(q2 + q3)  # upper arm + forearm, in the arm's plane
    return np.array(
        [
            c1 * reach + d4 * s1 + d5 * c1 * s234 + d6 * (s1 * c5 - c1 * c234 * s5),
            s1 * reach - d4 * c1 + d5 * s1 * s234 - d6 * (c1 * c5 + s1 * c234 * s5),
            d1 + a2 * np.sin(q2) + a3 * np.sin(q2 + q3) - d5 * c234 - d6 * s234 * s5,
        ]
    )
    ### END SOLUTION


# %%
check("2.3", ur5_position)

# %% [markdown]
# ## Your turn: a new arm, derived in SymPy
#
# The derivation above was done for you. Now do one yourself, for an arm nobody has tabulated
# here: any serial chain of revolute joints, given as its standard-DH table.
#
# ### Exercise 2.4 — `symbolic_fk` (5 points)
#
# Write `symbolic_fk(rows)`: the forward kinematics $T_{0,n}(q_1, \dots, q_n)$ of the arm
# whose standard-DH table is `rows`, as a 4×4 SymPy `Matrix`. `rows` is a list of $n$ tuples
# $(d_i, a_i, \alpha_i)$ of plain floats (metres and radians, $1 \le n \le 6$); the joint
# angles are the SymPy symbols `q1`, …, `qn` (for instance `sp.symbols(f"q1:{n + 1}")`; the
# lesson's `Q` holds the first six), and nothing else in the answer is symbolic.
#
# Build each link matrix $R_z(q_i)T_z(d_i)T_x(a_i)R_x(\alpha_i)$ yourself from `sp.cos` and
# `sp.sin`, and multiply them base first. Two things decide whether the result is usable:
#
# * the twists arrive as floats. `sp.cos(np.pi / 2)` is $6 \cdot 10^{-17}$, not 0, and the
#   terms it multiplies survive every later product. Turn a float that is a multiple of
#   $\pi/2$ (to within $10^{-12}$) into the exact multiple of `sp.pi / 2` first; keep any other
#   twist as it is;
# * simplify after each product (`simplify_angles`, as `symbolic_chain` does), or the entries
#   of a six-joint chain grow to thousands of terms.
#
# *Checked*: that the answer is a 4×4 SymPy matrix in `q1` … `qn` only (1 point); that it
# equals the numeric DH chain at twelve random configurations, for the UR3's table and for new
# arms of 2 to 6 joints with random lengths and twists (3 points); and that a table with twists
# $\pm\pi/2$ gives a matrix without a floating-point $\cos(\pi/2)$ in it (1 point). The check
# never runs your SymPy objects: it reads the printed structure of your matrix (`sp.srepr`) and
# evaluates it with numpy. The feedback recognises numbers in place of the joint symbols,
# symbols numbered from 0, lengths left symbolic, modified-DH link matrices, the links in
# reverse order, twists of the wrong sign and $d$ and $a$ swapped. urkin's link transforms
# (`urkin.symbolic.dh_transform`, and with it this lesson's `symbolic_chain`) and its forward
# kinematics are hidden while this exercise is graded; `simplify_angles` is not.

# %%
def symbolic_fk(rows):
    """Symbolic forward kinematics of any standard-DH chain of revolute joints.

    Parameters
    ----------
    rows : list of (float, float, float)
        The DH table, one row (d_i, a_i, alpha_i) per joint: metres, metres, radians.

    Returns
    -------
    sympy.Matrix, shape (4, 4)
        T_0_n as a function of the symbols q1, ..., qn (n = len(rows)).
    """
    ### BEGIN SOLUTION
    q = sp.symbols(f"q1:{len(rows) + 1}")
    T = sp.eye(4)
    for q_i, (d_i, a_i, alpha_i) in zip(q, rows):
        quarter_turns = alpha_i / (np.pi / 2)
        if abs(quarter_turns - round(quarter_turns)) < 1e-12:
            alpha_i = round(quarter_turns) * sp.pi / 2
        ca, sa = sp.cos(alpha_i), sp.sin(alpha_i)
        cq, sq = sp.cos(q_i), sp.sin(q_i)
        link = sp.Matrix(
            [
                [cq, -sq * ca, sq * sa, a_i * cq],
                [sq, cq * ca, -cq * sa, a_i * sq],
                [0, sa, ca, d_i],
                [0, 0, 0, 1],
            ]
        )
        T = (T * link).applyfunc(simplify_angles)
    return T
    ### END SOLUTION


# %%
check("2.4", symbolic_fk)

# %% [markdown]
# Verify it the way the lesson verified its own derivation: the UR5's table through your
# function, lambdified, against `urkin.fk` at a thousand random configurations. Then a new arm:
# a three-joint "elbow" arm whose position you can read.

# %%
try:
    T_ur5_yours = sp.lambdify(Q, symbolic_fk(urkin.robot("UR5").dh_table().tolist()), "numpy")
except NotImplementedError:
    print("exercise 2.4 is not written yet: nothing to verify")
else:
    q_check = np.random.default_rng(1).uniform(-np.pi, np.pi, (1000, 6))
    gap = np.abs(np.array([T_ur5_yours(*q) for q in q_check], dtype=float)
                 - urkin.fk(urkin.robot("UR5"), q_check)).max()
    print(f"UR5, your symbolic T_0_6 against urkin.fk: largest difference {below(gap, 1e-12)}")
    elbow_arm = [(0.3, 0.0, np.pi / 2), (0.0, 0.4, 0.0), (0.0, 0.3, 0.0)]
    print("an elbow arm's flange position:")
    display(symbolic_fk(elbow_arm)[:3, 3])

# %% [markdown]
# ### Exercise 2.5 — `upright_flange` (3 points)
#
# *Predict, then verify.* Stand a UR arm straight up: $q = (0, -\pi/2, 0, -\pi/2, 0, 0)$.
# Where is its flange? Answer from the picture of the frames in "Where the DH frames sit", not
# from a matrix product: which of the six lengths point up at this pose, which point sideways,
# and along which axis of the base frame? Remember that UR's $a_2$ and $a_3$ are negative and
# what that meant for the arm at $q = 0$.
#
# Write `upright_flange(robot)`: the flange position $(x, y, z)$ in the base frame, metres,
# shape `(3,)`, for a UR-type arm with lengths `robot.d1`, `robot.a2`, `robot.a3`,
# `robot.d4`, `robot.d5`, `robot.d6` (the seven UR arms, and made-up ones with other lengths).
# Only sums and differences of the lengths are needed.
#
# *Checked*: the position for the seven UR arms and five made-up arms (2 points), and that the
# function predicts rather than computes: it may not call your `dh_transform`,
# `forward_kinematics` or `ur5_position`, nor multiply matrices (1 point). The feedback
# recognises $a_2 + a_3$ added with their signs, $d_5$ pointing the wrong way, the sideways
# offsets on the wrong side, $d_6$ pointing up, and the pose at $q = 0$ instead.

# %%
def upright_flange(robot):
    """Flange position of a UR-type arm standing straight up, predicted from its lengths.

    Parameters
    ----------
    robot : urkin.Robot
        The arm; its lengths d1, a2, a3, d4, d5, d6 are in metres (a2, a3 < 0 for UR arms).

    Returns
    -------
    ndarray, shape (3,)
        The flange position in the base frame at q = (0, -pi/2, 0, -pi/2, 0, 0), metres.
    """
    ### BEGIN SOLUTION
    # Upper arm, forearm and d5 point up (a2, a3 < 0 along x axes that point down);
    # d4 and d6 point sideways along -y0, d6 because the flange faces -y0.
    height = robot.d1 - robot.a2 - robot.a3 + robot.d5
    return np.array([0.0, -(robot.d4 + robot.d6), height])
    ### END SOLUTION


# %%
check("2.5", upright_flange)

# %% [markdown]
# Now verify the prediction with forward kinematics, for all seven arms, and look at the pose:
# the flange faces sideways, along $-y_0$, so $d_6$ adds to the sideways offset $d_4$ rather
# than to the height.

# %%
q_upright = np.array([0.0, -np.pi / 2, 0.0, -np.pi / 2, 0.0, 0.0])
for name in urkin.ROBOTS:
    arm = urkin.robot(name)
    flange = urkin.fk(arm, q_upright)[:3, 3]
    try:
        miss = np.abs(flange - upright_flange(arm)).max()
        verdict = f"your prediction off by {below(miss, 1e-12)}"
    except NotImplementedError:
        verdict = "(exercise 2.5 is not written yet)"
    print(f"{name:6s} flange {flange[2]:.4f} m up, {-flange[1]:.4f} m along −y0: {verdict}")

# %% [markdown]
# ## Your turn: any table, rewritten for the modified convention
#
# "Four numbers per joint" rewrote the UR3's table for the modified convention by shifting the
# $a$ and $\alpha$ columns down one row, and noted that this works because UR's last row has
# $a_6 = \alpha_6 = 0$. For a general arm the last row's $a_n$ and $\alpha_n$ are not zero, and
# the regrouping leaves them over at the end of the chain:
#
# $$\prod_{i=1}^{n} R_z(\theta_i)T_z(d_i)T_x(a_i)R_x(\alpha_i)
# = \Big[\prod_{i=1}^{n} R_x(\alpha_{i-1})T_x(a_{i-1})R_z(\theta_i)T_z(d_i)\Big]\,
# T_x(a_n)R_x(\alpha_n), \qquad a_0 = \alpha_0 = 0 .$$
#
# The modified chain alone ends at a frame on the last joint's axis; the fixed **tool
# transform** $T_x(a_n)R_x(\alpha_n)$ carries it on to the standard flange frame.
#
# ### Exercise 2.6 — `to_modified` (4 points)
#
# Write `to_modified(rows)`. `rows` is a standard-DH table as a numpy array of shape `(n, 3)`,
# one row $(d_i, a_i, \alpha_i)$ per joint (metres, metres, radians; $1 \le n \le 7$; the
# row order of exercise 2.4, of `robot.dh_table()` and of `dh_chain`). Return a pair
# `(modified_rows, T_tool)`:
#
# * `modified_rows`, shape `(n, 3)`: row $i$ is $(d_i, a_{i-1}, \alpha_{i-1})$, with
#   $a_0 = \alpha_0 = 0$ — the row order `dh_chain(..., convention="modified")` reads;
# * `T_tool`, shape `(4, 4)`: the homogeneous transform $T_x(a_n)R_x(\alpha_n)$ of the last
#   row's length and twist (the identity for a UR arm);
#
# so that for every `q` (θ_i = q_i)
#
# ```
# dh_chain(modified_rows, q, convention="modified") @ T_tool == dh_chain(rows, q)
# ```
#
# Do not change `rows` in place. *Checked* (to 1e-12; a float32 answer to float32's
# precision), for the seven UR arms and for new arms of 1 to 7 joints with random lengths and
# twists: (2 points) that the equation above holds at eight random `q` per table; (1 point)
# the modified table (twists compared modulo $2\pi$); (1 point) `T_tool` ($T_x$ and $R_x$
# commute, so $R_x(\alpha_n)T_x(a_n)$ is the same matrix). The feedback recognises rows copied
# unchanged, $a$ and $\alpha$ shifted the wrong way (from row $i+1$), only one of $a$ and
# $\alpha$ shifted, $d$ shifted with them, and a tool transform that is forgotten, incomplete,
# inverted or taken from the first row. Nothing is hidden: urkin has no function for this.

# %%
def to_modified(rows):
    """Rewrite a standard-DH table for the modified (Craig) convention.

    Parameters
    ----------
    rows : ndarray, shape (n, 3)
        Standard-DH table, one row (d_i, a_i, alpha_i) per joint: metres, metres, radians.

    Returns
    -------
    modified_rows : ndarray, shape (n, 3)
        Row i is (d_i, a_(i-1), alpha_(i-1)), with a_0 = alpha_0 = 0.
    T_tool : ndarray, shape (4, 4)
        Tx(a_n) Rx(alpha_n), so that the modified chain times T_tool is the standard chain.
    """
    ### BEGIN SOLUTION
    d, a, alpha = np.asarray(rows, dtype=float).T
    modified_rows = np.column_stack([d, np.r_[0.0, a[:-1]], np.r_[0.0, alpha[:-1]]])
    c, s = np.cos(alpha[-1]), np.sin(alpha[-1])
    T_tool = np.array(
        [
            [1.0, 0.0, 0.0, a[-1]],
            [0.0, c, -s, 0.0],
            [0.0, s, c, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ]
    )
    return modified_rows, T_tool
    ### END SOLUTION


# %%
check("2.6", to_modified)

# %% [markdown]
# Verify it on the UR3: its modified table should be the one "Four numbers per joint" built,
# its tool transform the identity, and the modified chain should agree with `urkin.fk`. Then an
# arm whose last row has $a_n \ne 0$ and $\alpha_n \ne 0$, where the tool transform matters.

# %%
try:
    ur3_modified, ur3_tool = to_modified(ur3.dh_table())
except NotImplementedError:
    print("exercise 2.6 is not written yet: nothing to verify")
else:
    ur3_modified = np.asarray(ur3_modified, dtype=float)
    print("UR3, modified rows (d_i, a_(i-1), α_(i-1)), m and rad:")
    for row in ur3_modified:
        print("   " + "  ".join(f"{v + 0.0:9.5f}" for v in row))
    print("same as the table built in 'Four numbers per joint':",
          np.array_equal(ur3_modified, modified_table))
    print("T_tool is the identity:", np.array_equal(ur3_tool, np.eye(4)))
    q_verify = np.random.default_rng(26).uniform(-np.pi, np.pi, (1000, 6))
    T_modified = dh_chain(ur3_modified, q_verify, convention="modified") @ ur3_tool
    ur3_gap = np.abs(T_modified - urkin.fk(ur3, q_verify)).max()
    print(f"modified chain @ T_tool against urkin.fk, 1000 random q: largest difference "
          f"{below(ur3_gap, 1e-12)}")

    bent_rows = np.array([[0.2, 0.1, np.pi / 2], [0.0, 0.3, 0.0], [0.05, 0.25, -np.pi / 3]])
    bent_modified, bent_tool = to_modified(bent_rows)
    q_bent = np.random.default_rng(27).uniform(-np.pi, np.pi, (1000, 3))
    T_standard = dh_chain(bent_rows, q_bent)
    T_without = dh_chain(np.asarray(bent_modified, dtype=float), q_bent, convention="modified")
    with_gap = np.abs(T_without @ bent_tool - T_standard).max()
    short = np.linalg.norm(T_without[:, :3, 3] - T_standard[:, :3, 3], axis=1)
    print(f"\na 3-joint arm with a_3 = 0.25 m and α_3 = −60°: with T_tool, largest difference "
          f"{below(with_gap, 1e-12)}")
    print(f"without T_tool the chain stops a_3 = 0.25 m short of the flange at every q: "
          f"largest |distance − 0.25 m| {below(np.abs(short - 0.25).max(), 1e-12)}")

# %% [markdown]
# ## Your turn: put any formula to the test
#
# "A published formula put to the test" found seed 002's missing $\sin q_5$ by comparing its
# formula with an independent computation, the DH chain, at many random configurations rather
# than at one hand-picked pose. That test is worth having as a tool: every closed form you
# type, derive or find in a report from now on can go through it.
#
# ### Exercise 2.7 — `formula_gap` (4 points)
#
# Write `formula_gap(formula, robot, n=1000, seed=0)`. `formula(robot, q)` is a candidate
# closed-form flange position: it takes a UR-type arm and UR joint angles `q` (shape `(6,)`,
# radians) and returns a position of shape `(3,)` in metres. Test it at the `n` configurations
#
# ```
# np.random.default_rng(seed).uniform(-np.pi, np.pi, (n, 6))
# ```
#
# (exactly this call, one configuration per row, so that your result can be reproduced and
# checked) against an independent reference for the true flange position: `urkin.fk(robot,
# q)[:3, 3]` (it accepts all `n` rows at once), or your own `forward_kinematics` of exercise
# 2.2. Return a pair `(gap, q_worst)`: `gap`, the largest Euclidean distance
# $\lVert p_{\text{formula}}(q) - p_{\text{true}}(q)\rVert$ over the `n` configurations
# (metres), and `q_worst`, shape `(6,)`, the configuration where it occurs.
#
# *Checked* (to 1e-12; a float32 answer to float32's precision), with the default `n` and
# `seed` and with other ones: (1 point) for the right closed form on random UR arms, a gap
# below 1e-12 and a `q_worst` that is one of the drawn configurations; (2 points) for seed
# 002's published formula (its own lengths, at its own angles `q + SEED002_SHIFT`) and for its
# terms with other arms' lengths, exactly the largest distance and the configuration where it
# occurs; (1 point) the same for a formula that is right at `q = 0` and near it but wrong
# elsewhere: the right closed form with $\arctan(\tan q_j)$ in place of one joint angle $q_j$,
# which is $q_j$ only while $|q_j| < \pi/2$. The feedback recognises testing only at `q = 0`
# (or at a fixed handful of poses), the mean distance instead of the largest, the
# configuration of the smallest distance, the largest single coordinate instead of the
# Euclidean distance, angles drawn in degrees or converted with `np.radians`, and another
# random draw. Nothing is hidden.

# %%
def formula_gap(formula, robot, n=1000, seed=0):
    """Largest distance between a closed-form flange position and forward kinematics.

    Parameters
    ----------
    formula : callable
        ``formula(robot, q)``: a candidate flange position, q shape (6,) in radians, shape (3,)
        in metres.
    robot : urkin.Robot
        The arm the formula is tested on.
    n : int
        Number of random configurations.
    seed : int
        Seed of ``np.random.default_rng(seed).uniform(-np.pi, np.pi, (n, 6))``.

    Returns
    -------
    gap : float
        The largest Euclidean distance between the formula's position and the flange, metres.
    q_worst : ndarray, shape (6,)
        The configuration (one of the n drawn) where it occurs.
    """
    ### BEGIN SOLUTION
    q = np.random.default_rng(seed).uniform(-np.pi, np.pi, (n, 6))
    p_formula = np.array([formula(robot, q_k) for q_k in q], dtype=float)
    p_true = urkin.fk(robot, q)[:, :3, 3]
    distances = np.linalg.norm(p_formula - p_true, axis=1)
    worst = int(np.argmax(distances))
    return float(distances[worst]), q[worst]
    ### END SOLUTION


# %%
check("2.7", formula_gap)

# %% [markdown]
# Put it to work: on seed 002's formula as published (its angles are UR's plus
# `SEED002_SHIFT`), on a formula that is right at `q = 0` and fails where $|q_1| > \pi/2$,
# and on your `ur5_position` of exercise 2.3. At the worst configuration of seed 002's formula
# the error should be $d_6\,|\cos(q_2+q_3+q_4)|\,(1 - \sin q_5)$, close to its bound $2d_6$.


# %%
def seed002_as_published(robot, q):
    """Seed 002's p for UR angles q: its own formula, lengths and angles (robot is not used)."""
    return np.array(seed002_position(np.asarray(q) + SEED002_SHIFT, SEED002_LENGTHS))


def folded_q1(robot, q):
    """The flange position with arctan(tan(q1)) in place of q1: right only while |q1| < π/2."""
    q = np.array(q, dtype=float)
    q[0] = np.arctan(np.tan(q[0]))
    return urkin.fk(robot, q)[:3, 3]


try:
    seed_gap, seed_worst = formula_gap(seed002_as_published, SEED002_ARM)
except NotImplementedError:
    print("exercise 2.7 is not written yet: nothing to verify")
else:
    seed_worst = np.asarray(seed_worst, dtype=float)
    c234_worst, s5_worst = np.cos(seed_worst[1:4].sum()), np.sin(seed_worst[4])
    predicted = SEED002_LENGTHS[5] * abs(c234_worst) * (1 - s5_worst)
    print(f"seed 002's published p, 1000 random q: gap {1000 * seed_gap:.1f} mm "
          f"(bound 2·d6 = {2000 * SEED002_LENGTHS[5]:.0f} mm)")
    print(f"  at q_worst: cos(q2+q3+q4) = {c234_worst:.2f}, sin q5 = {s5_worst:.2f}")
    print(f"  |gap − d6·|cos(q2+q3+q4)|·(1 − sin q5)| there: "
          f"{below(abs(predicted - seed_gap), 1e-12)}")
    zero_miss = np.linalg.norm(folded_q1(ur5, np.zeros(6)) - urkin.fk(ur5, np.zeros(6))[:3, 3])
    print(f"\narctan(tan(q1)) for q1, UR5: at q = 0 off by {below(zero_miss, 1e-12)}, "
          f"at 1000 random q gap {formula_gap(folded_q1, ur5)[0]:.2f} m")
    try:
        yours_gap, _ = formula_gap(lambda robot, q: ur5_position(q), ur5)
        print(f"your ur5_position, 1000 random q: gap {below(yours_gap, 1e-12)}")
    except NotImplementedError:
        print("your ur5_position: (exercise 2.3 is not written yet)")

# %% [markdown]
# ## Summary
#
# * A DH table holds four numbers per joint: $\theta$ and $d$ about and along the joint axis
#   $z_{i-1}$, $a$ and $\alpha$ along and about the common normal $x_i$. The standard link
#   transform is $R_z(\theta)T_z(d)T_x(a)R_x(\alpha)$; the modified one,
#   $R_x(\alpha_{i-1})T_x(a_{i-1})R_z(\theta_i)T_z(d_i)$, needs a rewritten table: $a$ and
#   $\alpha$ move down one row, and the last row's $T_x(a_n)R_x(\alpha_n)$ becomes a fixed
#   tool transform (exercise 2.6). A table without its convention is not a robot.
# * Forward kinematics is the product of the link transforms, base first. Derived in SymPy with
#   symbolic lengths, one formula serves all seven UR arms; its terms depend on $q_1$, $q_2$,
#   $q_5$, $q_6$ and the sums $q_2+q_3$ and $q_2+q_3+q_4$.
# * DH frame origins lie on joint axes, but not always at the physical joints: the UR's
#   sideways offsets all end up in $d_4$.
# * Test formulas at many random configurations, and against an independent computation. Seed
#   002's published position lacks a factor $\sin q_5$ in two terms, an error of up to
#   $2d_6 = 165$ mm that vanishes exactly where $\cos(q_2+q_3+q_4) = 0$ or $\sin q_5 = 1$: the
#   only poses at which its author's check could have passed. `formula_gap` (exercise 2.7)
#   runs such a test on any closed-form position.
#
# ## What comes next
#
# * **Jacobians**: how fast the flange moves when the joints do — by differentiating the $p$
#   derived here, and column by column from the DH frames. Seed 002's Jacobian returns there.
# * **Inverse kinematics**: the way back, from a pose to joint angles — numerically with the
#   Jacobian, and in closed form, where a UR arm has up to eight answers.
#
# Before you move on: restart the kernel and run the whole notebook. All seven check cells
# should report full marks.
