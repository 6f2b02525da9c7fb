"""Collision checking and motion planning with sphere models of the arms.

::

    from urkin import planning
    model = planning.sphere_model(ur5)                      # spheres fixed in the DH frames
    scene = planning.Scene(boxes=[planning.Box(centre, size, name="shelf")])
    planning.is_free(model, scene, Q)                       # (N,) bool
    planning.clearance(model, scene, Q)                     # signed distance and the pair
    planning.explain(model, scene, q)                       # a sentence
    planning.edges_free(model, scene, QA, QB)               # (K,) bool, straight edges
    planning.certify_edges(model, scene, QA, QB)            # (K,) bool, proven free throughout
    plan = planning.rrt_connect(model, scene, q_start, goals, seed=0)
    traj = planning.time_parametrize(plan)                  # urkin.trajectory.Trajectory
    world = planning.World(robot, model, table, blocks)    # a tabletop of upright boxes
    planning.validate_goal(world, ("A", 0.25, -0.05))      # ok, or every reason, with numbers
    task = planning.pick_and_place(world, moves, q_start)   # phases, report, timed trajectory
    planning.replay(world, q_start, task.steps())           # check any task from scratch

Modules: :mod:`~urkin.planning.spheres` (sphere models), :mod:`~urkin.planning.scene`
(obstacles, signed distances), :mod:`~urkin.planning.checks` (configurations, clearances,
edges), :mod:`~urkin.planning.rrt` (RRT-Connect, shortcutting), :mod:`~urkin.planning.timing`
(timing a path within joint limits), :mod:`~urkin.planning.blocks` (blocks, grasps, box
tests), :mod:`~urkin.planning.tabletop` (a world of boxes, goal validation),
:mod:`~urkin.planning.tasks` (pick and place, replay).
"""

from urkin.planning.blocks import Block, block_spheres, box_separation, tool_yaw, top_down_grasp
from urkin.planning.checks import (
    Clearance,
    certify_edges,
    clearance,
    edge_samples,
    edges_free,
    explain,
    is_free,
)
from urkin.planning.rrt import Plan, rrt_connect, shortcut
from urkin.planning.scene import Box, Capsule, Cylinder, Scene, Sphere
from urkin.planning.spheres import FRAME_NAMES, TOOL_FRAME, SphereModel, self_pairs, sphere_model
from urkin.planning.tabletop import GoalCheck, Move, World, validate_goal
from urkin.planning.tasks import Phase, Task, pick_and_place, replay
from urkin.planning.timing import time_parametrize

__all__ = [
    "FRAME_NAMES",
    "TOOL_FRAME",
    "Block",
    "Box",
    "Capsule",
    "Clearance",
    "Cylinder",
    "GoalCheck",
    "Move",
    "Phase",
    "Plan",
    "Scene",
    "Sphere",
    "SphereModel",
    "Task",
    "World",
    "block_spheres",
    "box_separation",
    "certify_edges",
    "clearance",
    "edge_samples",
    "edges_free",
    "explain",
    "is_free",
    "pick_and_place",
    "replay",
    "rrt_connect",
    "self_pairs",
    "shortcut",
    "sphere_model",
    "time_parametrize",
    "tool_yaw",
    "top_down_grasp",
    "validate_goal",
]
