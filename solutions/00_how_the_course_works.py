# %% [markdown]
# # Lesson 00 — How this course works
#
# This course teaches the kinematics of Universal Robots arms — the UR3, UR5, UR10 and their
# e-series successors — one notebook at a time. Each lesson mixes three things:
#
# * **reading**: short explanations with the maths written out;
# * **running**: demonstrations you can change and re-run, most of them drawing the arm;
# * **writing**: exercises, each a single function, followed by a *check cell* that tells you
#   whether your function is right and, when it is not, what it probably got wrong.
#
# **What you will be able to do**
#
# * work through a notebook: run it top to bottom, write an exercise and read its check cell's
#   report (exercise 0.1);
# * convert degrees to radians exactly, for one angle or a whole array of configurations, and
#   say why rounded factors such as 0.0175 are a bug (exercise 0.1);
# * express a pose given in UR's `base` frame in the URDF `base_link` frame, putting the
#   transform on the side where the frame names cancel (exercise 0.2);
# * predict, without forward kinematics, the flange pose after the base joint turns, and tell
#   a turn about the base's z axis (`Rz @ T`) from a turn about the flange's own (`T @ Rz`)
#   (exercise 0.3).
#
# **Time:** about 40 minutes. **You need:** Python and numpy; no robotics yet.

# %% [markdown]
# ## Working in JupyterLab
#
# You started this notebook with `make course`, which opened JupyterLab on the `course/`
# folder. A few habits make notebooks painless:
#
# * **Shift + Enter** runs a cell and moves to the next one.
# * Cells run in the order *you* run them, not the order they appear. When something behaves
#   strangely, use **Kernel → Restart Kernel and Run All Cells**: a notebook that works top to
#   bottom after a restart is a notebook that works.
# * Every demonstration uses the course's own package, `urkin`, so the whole notebook runs even
#   before you have written a single exercise.
#
# The first code cell of every lesson imports what the lesson needs.

# %%
import matplotlib.pyplot as plt
import numpy as np

import urkin
import urkin.plot
from urkin.course import below, check

np.set_printoptions(precision=4, suppress=True)

# %% [markdown]
# ## Exercises and check cells
#
# An exercise asks for one function. Its cell already holds the signature and a docstring that
# says exactly what goes in and what comes out; you replace the line
# `raise NotImplementedError(...)` with your code. The cell right after it calls `check`:
#
# ```python
# check("0.1", deg_to_rad)
# ```
#
# `check` runs your function on test inputs and prints a report: each property it tested, the
# points it is worth, and for a failure the input, the expected answer, your answer and — when
# it recognises one — the *likely mistake*, such as "converted the wrong way". A check cell never
# raises an error, so you can run it as often as you like.
#
# **How you are graded.** Your instructor grades the notebook you hand in with the same checks,
# but on *fresh random inputs*, so a function that only memorises the visible answers earns
# nothing. The grader runs only your *definitions* — imports, functions, classes and
# assignments — not your demonstrations (a call at the top level of a cell is skipped, so set a
# global with an assignment, not from inside a function you call), and each exercise's function
# sees the names as they stood at its check cell, as after *Restart & Run All*: a helper or a
# variable you bind again further down does not change an exercise above it. Keep each exercise
# self-contained in its function.
# And where an exercise asks you to write something `urkin` already does, calling `urkin`'s
# version earns no points for that exercise: the point is to write it yourself.

# %% [markdown]
# ## Where the material comes from
#
# The course is built on four published student reports about UR kinematics: a UR3 simulator
# in Python (numerical inverse kinematics), a UR3 in a robot simulator (screw axes, sampling
# motion planning), a UR5 study in MATLAB (symbolic forward kinematics), and a UR3 lab sheet
# (closed-form inverse kinematics for a gripper pointing down). The lessons call them *seed
# reports* 000, 001, 002 and 004. They are good starting points and they contain real
# mistakes — a wrong formula that passed its own test, a solver line that would crash, a
# missing `atan2` — and finding those mistakes is part of the course.

# %% [markdown]
# ## Units: metres and radians, always
#
# Every length in this course is in metres and every angle in radians. Degrees appear only where
# a human reads them (figure titles, the pose panel). Mixing the two is the most common bug in
# robotics code, and it is not always loud. Seed report 002 converted angles with a factor of
# 0.0175 in one place and 0.01744 in another, instead of π/180 = 0.0174533…. Each round trip
# through both factors scales the angle by 0.01744 / 0.0175 ≈ 0.99657 — a third of a percent
# that nobody notices until a trajectory of hundreds of warm-started steps has drifted.

# %%
exact = np.pi / 180
print(f"pi/180            = {exact:.7f}")
print(f"0.0175  differs by {100 * (0.0175 / exact - 1):+.3f} %")
print(f"0.01744 differs by {100 * (0.01744 / exact - 1):+.3f} %")

angle = 20.0 * exact  # the initial guess of one report, on every joint (radians)
for step in range(1, 4):
    angle = angle / 0.0175 * 0.01744  # radians → "degrees" → "radians", as the report does
    print(f"after round trip {step}: {angle / exact:.4f}° (it started at 20°)")

# %% [markdown]
# ### Exercise 0.1 — `deg_to_rad` (5 points)
#
# Write `deg_to_rad(angles_deg)`, which converts degrees to radians. It must accept a single
# number, a list, or a numpy array of any shape — such as an `(N, 6)` array holding N joint
# configurations — and return floats of the same shape. Use the exact factor π/180, and do not
# wrap the result into one turn: 720° is 4π.
#
# *Checked* (to 1e-12; a float32 answer to float32's precision): 180°, −90°, 0°, 45° and other
# whole angles; arrays of random angles between −720° and 720°; an `(N, 6)` array and a
# three-dimensional one; and a plain list of six angles. The feedback recognises the usual
# slips: converting the wrong way, seed 002's rounded factors 0.0175 and 0.01744, a rounded
# result, and a list or array that only `math.radians` would not take. Nothing of urkin is
# hidden here: numpy's `np.radians` and `np.deg2rad` are fine.

# %%
def deg_to_rad(angles_deg):
    """Convert angles from degrees to radians.

    Parameters
    ----------
    angles_deg : float or array_like
        Angles in degrees, any shape.

    Returns
    -------
    float or ndarray
        The same angles in radians, same shape.
    """
    ### BEGIN SOLUTION
    return np.asarray(angles_deg, dtype=float) * (np.pi / 180.0)
    ### END SOLUTION


# %%
check("0.1", deg_to_rad)

# %% [markdown]
# ## A first look at the UR3
#
# A UR arm has six revolute joints: the *base* turns the whole arm about the vertical, the
# *shoulder* and *elbow* lift the upper arm and forearm, and three *wrist* joints orient the
# tool. `urkin` knows seven arms by name, each with the link lengths Universal Robots publishes:

# %%
print(urkin.ROBOTS)
ur3 = urkin.robot("UR3")
print(ur3)

# %% [markdown]
# A configuration is a vector of six joint angles `q`, in radians. The *forward kinematics*
# `urkin.fk(robot, q)` says where the tool flange is for a given `q`; lesson 02 derives it. Here
# we only look. At `q = 0` every UR arm lies stretched out horizontally; UR's "home" position
# `q = [0, −π/2, 0, −π/2, 0, 0]` points the arm straight up.

# %%
zero = np.zeros(6)
home = np.array([0.0, -np.pi / 2, 0.0, -np.pi / 2, 0.0, 0.0])

urkin.plot.robot_panels(ur3, [(zero, "UR3, q = 0 (stretched out)"), (home, "UR3, home")],
                        title="The UR3 in two configurations: links through the DH frames, "
                              "with their axes")
plt.show()

# %% [markdown]
# Each grey segment joins the origins of two consecutive *DH frames* (lesson 02), and each
# frame is drawn as three short arrows: x in red, y in green, z in blue. The box in the corner is
# the pose panel: where the flange is (metres) and how it is turned (roll, pitch and yaw in
# degrees — lesson 01).
#
# Rotating one joint moves everything after it. Here the shoulder sweeps from −π/2 to 0 while
# the other joints stay at home; the flange traces an arc about the shoulder axis. Its radius
# is the flange's distance from that axis: at home the upper arm ($|a_2|$), the forearm
# ($|a_3|$) and the wrist's $d_5$ stand in one line, so the radius is $|a_2| + |a_3| + d_5$
# (the offsets $d_4$ and $d_6$ run along the shoulder axis and do not count).

# %%
sweep = np.tile(home, (40, 1))
sweep[:, 1] = np.linspace(-np.pi / 2, 0.0, 40)
flange = urkin.fk(ur3, sweep)[:, :3, 3]  # all 40 poses at once: shape (40, 4, 4)

ax = urkin.plot.axes3d(center=(-0.15, -0.1, 0.32), half_width=0.4, figsize=(7.5, 7.5),
                       title="UR3: the flange while the shoulder turns from −90° to 0°")
for q in sweep[::13]:
    urkin.plot.draw_robot(ax, ur3, q, frames=False, alpha=0.5)
ax.plot(*flange.T, color="tab:orange", linewidth=2, label="flange path")
ax.legend(loc="upper right")
plt.show()

start, end = flange[0].round(3) + 0.0, flange[-1].round(3) + 0.0  # + 0.0 avoids "-0."
print(f"flange moved {np.linalg.norm(end - start):.3f} m from {start} to {end}")
shoulder = urkin.fk_frames(ur3, home)[1]  # frame 1: the shoulder axis is its z axis
along = (flange - shoulder[:3, 3]) @ shoulder[:3, 2]
radius = np.linalg.norm(flange - shoulder[:3, 3] - along[:, None] * shoulder[:3, 2], axis=1)
arm = abs(ur3.a2) + abs(ur3.a3) + ur3.d5
assert np.allclose(radius, arm, rtol=0, atol=1e-12)
print(f"distance of the flange from the shoulder axis: {radius.min():.5f} to "
      f"{radius.max():.5f} m; |a2| + |a3| + d5 = {arm:.5f} m")

# %% [markdown]
# Notice that `urkin.fk` took all forty configurations at once, as an array of shape `(40, 6)`,
# and returned forty poses. Every function in `urkin` works that way: one configuration `(6,)`
# or a batch `(N, 6)`.
#
# ## Frames: where is "the base"?
#
# A pose only means something together with the frame it is measured in. This course writes
# `T_a_b` for the pose of frame `b` in frame `a`, so that poses chain like fractions cancel:
# `T_a_c = T_a_b @ T_b_c`.
#
# `urkin` measures poses in the frame Universal Robots calls **base** (DH frame 0), the frame the
# robot's own controller reports. ROS and URDF models of the same arms name a different frame
# **`base_link`**, turned by π (180°) about the vertical axis:
# `T_base_link_base = Rz(π)`, available as `urkin.T_BASE_LINK_BASE`. Their `tool0` frame is the
# flange, the same as urkin's last DH frame. Forgetting the half turn puts every target on the
# wrong side of the robot.

# %%
fig = plt.figure(figsize=(10, 5))
frames = [(np.eye(4), "UR's base (DH frame 0)"),
          (urkin.T_BASE_LINK_BASE, "URDF base_link, drawn in base coordinates")]
for index, (T, name) in enumerate(frames):
    ax = urkin.plot.axes3d(fig.add_subplot(1, 2, index + 1, projection="3d"),
                           center=(0.0, 0.0, 0.0), half_width=0.12, title=name)
    urkin.plot.draw_frame(ax, T, length=0.1, tips=True)
    ax.view_init(elev=30, azim=-60)
fig.suptitle("The same origin, two frames: base_link is base turned by 180° about z")
plt.show()

# %% [markdown]
# ### Exercise 0.2 — `base_link_pose` (3 points)
#
# Write `base_link_pose(T_base_tool)`: given a tool pose measured in UR's `base` frame, return
# the same pose measured in the URDF `base_link` frame. Think of which transform goes on which
# side: the names should cancel. Write the half turn `T_base_link_base` yourself, as a 4×4
# numpy array: cos π = −1 and sin π = 0 make it very simple.
#
# *Checked* (to 1e-9; a float32 answer to float32's precision): that the result is a
# homogeneous transform with the tool at the same height (both frames share the z axis), and
# that it equals `T_base_link_base @ T_base_tool` for random poses. The feedback recognises the
# product on the wrong side, a quarter turn, a turn about x or y, and 180 used as radians.
# urkin's own `urkin.T_BASE_LINK_BASE` is hidden while this exercise is graded.

# %%
def base_link_pose(T_base_tool):
    """Express a pose given in UR's base frame in the URDF base_link frame.

    Parameters
    ----------
    T_base_tool : ndarray, shape (4, 4)
        Pose of the tool in the base frame (DH frame 0).

    Returns
    -------
    ndarray, shape (4, 4)
        ``T_base_link_tool``, the pose of the same tool in the base_link frame.
    """
    ### BEGIN SOLUTION
    T_base_link_base = np.diag([-1.0, -1.0, 1.0, 1.0])  # Rz(π): cos π = −1, sin π = 0
    return T_base_link_base @ T_base_tool
    ### END SOLUTION


# %%
check("0.2", base_link_pose)

# %% [markdown]
# ## Turning the base joint
#
# Joint 1, the base, turns about the z axis of the base frame: the vertical line through the
# base origin. It carries everything after it — shoulder, elbow, wrist and flange turn
# together, like an object on a turntable, and nothing inside the arm changes. Every point of
# the arm moves on a horizontal circle about that line.
#
# ### Exercise 0.3 — `turn_joint1` (3 points)
#
# **Predict, then verify.** You are given the flange pose `T_base_flange` (4×4, in UR's base
# frame) of some arm at some configuration `q`. Joint 1 turns by `angle` radians; the other
# five joints stay where they are. What is the new flange pose? You are given neither the arm
# nor `q`, so forward kinematics cannot help: the answer has to come from reasoning. Before you
# write any code, decide:
#
# * about which axis, and measured in which frame, does the flange turn?
# * so does `Rz(angle)` multiply `T_base_flange` from the **left** or from the **right**? In
#   exercise 0.2 the names told you: a transform on the left acts in the frame named on the
#   left (here `base`), one on the right acts in the frame named on the right (here the flange's
#   own). Which side would turn the flange about *its own* z axis instead, and which joint of
#   the arm does that?
#
# Write `turn_joint1(T_base_flange, angle)`: return the 4×4 flange pose, in the base frame,
# after joint 1 turns by `angle` radians — any angle: negative ones and ones beyond a full turn
# too (positive turns counter-clockwise seen from above, as every angle about z does). Build
# `Rz(angle)` as a 4×4 array from `np.cos` and `np.sin`, as in exercise 0.2 (or use
# `urkin.transforms.rot_z` and `urkin.transforms.make_transform`).
#
# *Checked* (to 1e-9; a float32 answer to float32's precision) on the flange poses of random
# UR arms at random configurations, for eight random angles between −10 and 10 rad (four within
# ±π, two beyond +π, two beyond −π): that the flange position turns about the base z axis by
# the angle, keeping its height and its distance from the axis (1 point); and that the whole
# pose equals `urkin.fk` at `q` with `q[0] + angle` (2 points). The feedback recognises the
# product on the wrong side (a turn about the flange's own z axis), the opposite angle, only the
# orientation or only the position turned, degrees for radians, and a turn about x or y.

# %%
def turn_joint1(T_base_flange, angle):
    """The flange pose after joint 1 turns, from the flange pose before.

    Parameters
    ----------
    T_base_flange : ndarray, shape (4, 4)
        Pose of the flange in the base frame at some configuration q.
    angle : float
        How far joint 1 turns, in radians (positive: counter-clockwise seen from above).

    Returns
    -------
    ndarray, shape (4, 4)
        The flange pose in the base frame at q with q[0] + angle, the other joints unchanged.
    """
    ### BEGIN SOLUTION
    c, s = np.cos(angle), np.sin(angle)
    Rz = np.array([[c, -s, 0.0, 0.0], [s, c, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0],
                   [0.0, 0.0, 0.0, 1.0]])
    return Rz @ T_base_flange  # about the base's z axis: the base frame's side, the left
    ### END SOLUTION


# %%
check("0.3", turn_joint1)

# %% [markdown]
# Now verify the prediction with forward kinematics. The cell turns joint 1 of the UR3 by
# 2.5 rad (about 143°) from a working pose and compares your answer with `urkin.fk` at the new
# configuration. It also tests the other side: `T @ Rz(angle)` spins the flange about its own z
# axis, and that is exactly what turning **joint 6** does — the flange's z axis is joint 6's
# axis. Left or right of the same matrix: the base joint or the last wrist joint.

# %%
q_work = np.array([0.4, -1.1, 1.3, -1.7, -1.5, 0.2])
turn = 2.5  # radians
q_joint1, q_joint6 = q_work.copy(), q_work.copy()
q_joint1[0] += turn
q_joint6[5] += turn
T_work = urkin.fk(ur3, q_work)
Rz_turn = urkin.transforms.make_transform(urkin.transforms.rot_z(turn))

gap_left = np.abs(Rz_turn @ T_work - urkin.fk(ur3, q_joint1)).max()
gap_right = np.abs(T_work @ Rz_turn - urkin.fk(ur3, q_joint6)).max()
miss = np.linalg.norm((T_work @ Rz_turn)[:3, 3] - urkin.fk(ur3, q_joint1)[:3, 3])
print(f"Rz(angle) @ T against fk with joint 1 turned: largest difference {below(gap_left)}")
print(f"T @ Rz(angle) against fk with joint 6 turned: largest difference {below(gap_right)}")
print(f"T @ Rz(angle) puts the flange {miss:.3f} m from where turning joint 1 does")
try:
    mine = np.asarray(turn_joint1(T_work, turn), dtype=float)
except NotImplementedError:
    print("exercise 0.3 is not written yet: nothing to compare")
else:
    gap_mine = np.abs(mine - urkin.fk(ur3, q_joint1)).max()
    print(f"your turn_joint1 against fk with joint 1 turned: largest difference "
          f"{below(gap_mine, 1e-9)}")

# %% [markdown]
# The picture of the same turn: the flange travels on a horizontal circle about the base z
# axis, and its frame turns with it — position and orientation both, as `Rz(angle) @ T` says.

# %%
sweep_1 = np.tile(q_work, (60, 1))
sweep_1[:, 0] += np.linspace(0.0, turn, 60)
path_1 = urkin.fk(ur3, sweep_1)[:, :3, 3]

ax = urkin.plot.axes3d(center=(0.0, 0.0, 0.25), half_width=0.45,
                       title="UR3: joint 1 turns the whole arm about the base z axis")
urkin.plot.draw_robot(ax, ur3, q_work, frames=False, alpha=0.35, label="before")
urkin.plot.draw_robot(ax, ur3, q_joint1, frames=False, label="joint 1 turned by 2.5 rad")
for T in (T_work, urkin.fk(ur3, q_joint1)):
    urkin.plot.draw_frame(ax, T, length=0.1)
ax.plot(*path_1.T, color="tab:orange", linewidth=2, label="flange path")
ax.plot([0.0, 0.0], [0.0, 0.0], [0.0, 0.5], "k--", linewidth=1, label="joint 1 axis (base z)")
ax.legend(loc="upper right")
plt.show()

# %% [markdown]
# ## Seven arms, one structure
#
# All seven arms share the same joint layout; only six lengths differ. That is why one
# derivation (lesson 02) serves them all. The chart measures each arm as the sweep above did:
# the flange's distance from the shoulder axis with the arm stretched, $|a_2| + |a_3| + d_5$.
# The longest, the UR10 and UR10e, reach about 2.4 times as far as the UR3.

# %%
names = urkin.ROBOTS
reach = [abs(urkin.robot(n).a2) + abs(urkin.robot(n).a3) + urkin.robot(n).d5 for n in names]
print("arm     |a2| + |a3| + d5 (m)")
for name, value in zip(names, reach):
    print(f"{name:<6}  {value:.4f}")

fig, ax = plt.subplots(figsize=(7, 3.5))
ax.bar(names, reach, color="tab:blue")
ax.set_ylabel("|a2| + |a3| + d5 (m)")
ax.set_xlabel("arm")
ax.set_title("How far each UR arm's flange reaches from its shoulder axis")
plt.show()

# %% [markdown]
# ## What comes next
#
# * **Lesson 01** builds the language of poses: rotation matrices, homogeneous transforms, their
#   inverse, roll–pitch–yaw angles and the exponential map.
# * **Lesson 02** derives the UR forward kinematics with SymPy from a table of four numbers per
#   joint, and shows how a published formula can hide an error from its own test.
#
# Before you move on: restart the kernel and run the whole notebook. All three check cells
# should now report full marks.
