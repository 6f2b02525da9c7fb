"""Lesson 10's world: the UR3 lab's table (seed report 004) with blocks to stack, and the
Tower of Hanoi.

The table frame is the lab's world frame: the table top is z = 0 and the robot's base sits
at (−0.15, 0.15, 0.01) m.  The arm is UR's official UR3 (so its fitted sphere model applies;
the lab sheet's rounded lengths differ by at most 2.35 mm) carrying the lab's suction
gripper, whose tip is at (−L9, 0, L10) = (−53.5, 0, 59) mm in the flange frame, pointing
down when θ5 = −π/2.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from urkin.course.lab import LAB_BASE_IN_WORLD, lab_robot
from urkin.planning import Block, Move, World, sphere_model
from urkin.robots import Robot, robot
from urkin.transforms import make_transform

__all__ = [
    "GRIPPER_SPHERES",
    "HANOI_PEGS",
    "LAB_HOME",
    "TABLE",
    "StackPanel",
    "StackPrompt",
    "hanoi_moves",
    "hanoi_tasks",
    "hanoi_world",
    "lab_arm",
    "lab_world",
    "parse_goal",
    "stack_panel",
]

#: The table: x from −0.45 to 0.50 m, y from −0.30 to 0.60 m, top at z = 0, 3 cm thick.
TABLE = Block("table", [0.95, 0.90, 0.03], make_transform(p=[0.025, 0.15, -0.015]))

#: The gripper's spheres in the tool frame (z down, tip at the origin): the suction column
#: (its lowest sphere stops 3 mm above the tip: the cup's soft lip) and the bracket to the
#: flange at (−53.5, 0, −59) mm.  Rows (x, y, z, radius), metres.
GRIPPER_SPHERES = np.array(
    [
        [0.0, 0.0, -0.015, 0.012],
        [0.0, 0.0, -0.035, 0.012],
        [0.0, 0.0, -0.055, 0.012],
        [-0.018, 0.0, -0.059, 0.012],
        [-0.036, 0.0, -0.059, 0.012],
    ]
)

#: A configuration above the table, the gripper pointing down (UR angles, rad).
LAB_HOME = np.array([-0.6, -1.9, -1.6, -1.2, 1.5708, 0.0])

#: The Tower of Hanoi's three places on the table (x, y), metres.
HANOI_PEGS = ((0.12, -0.08), (0.22, 0.12), (0.12, 0.34))


def lab_arm() -> Robot:
    """The UR3 on the lab's table with the lab's suction gripper as its tool."""
    return robot("ur3").with_base(make_transform(p=LAB_BASE_IN_WORLD)).with_tool(lab_robot().tool)


def lab_world(
    blocks: Sequence[Block] | None = None, obstacles: Sequence[Block] | None = None
) -> World:
    """The lab's table with two 5 cm blocks, A and B, and a post between them.

    Examples
    --------
    >>> lab_world()
    World(UR3, table 0.95 × 0.9 m, blocks A, B, 1 obstacles)
    """
    arm = lab_arm()
    model = sphere_model(arm).with_tool_spheres(
        GRIPPER_SPHERES[:, :3], GRIPPER_SPHERES[:, 3], name="gripper"
    )
    if blocks is None:
        blocks = (
            Block.standing("A", [0.05, 0.05, 0.05], 0.10, -0.05, yaw=0.3),
            Block.standing("B", [0.05, 0.05, 0.05], 0.05, 0.40, yaw=-0.2),
        )
    if obstacles is None:
        obstacles = (Block.standing("post", [0.04, 0.04, 0.20], 0.22, 0.15),)
    return World(arm, model, TABLE, tuple(blocks), tuple(obstacles))


def hanoi_world(n: int = 3) -> World:
    """``n`` square blocks (6, 5, 4, 3.5 cm wide, 3 cm tall), the largest at the bottom, on the
    first of :data:`HANOI_PEGS`; no other obstacles.

    Examples
    --------
    >>> [b.name for b in hanoi_world().blocks]
    ['D1', 'D2', 'D3']
    """
    if isinstance(n, bool) or not isinstance(n, int) or n not in (1, 2, 3, 4):
        raise ValueError(f"n must be 1 … 4 blocks; got {n!r}")
    widths = (0.06, 0.05, 0.04, 0.035)[:n]
    x, y = HANOI_PEGS[0]
    blocks = [
        Block.standing(f"D{k + 1}", [w, w, 0.03], x, y, bottom=0.03 * k)
        for k, w in enumerate(widths)
    ]
    return lab_world(blocks=blocks, obstacles=())


def hanoi_moves(n: int, source: int = 0, target: int = 2, spare: int = 1) -> list[tuple[int, int]]:
    """The recursive solution: ``2**n − 1`` moves ``(from peg, to peg)``.

    Examples
    --------
    >>> hanoi_moves(2)
    [(0, 1), (0, 2), (1, 2)]
    """
    if n == 0:
        return []
    return [
        *hanoi_moves(n - 1, source, spare, target),
        (source, target),
        *hanoi_moves(n - 1, spare, target, source),
    ]


def hanoi_tasks(world: World, moves: Sequence[tuple[int, int]]) -> list[Move]:
    """The pick-and-place goals of peg moves, checking the rule at every step: only the top
    block moves, and never onto a smaller one.

    Raises
    ------
    ValueError
        Naming the move that breaks a rule.
    """
    pegs: list[list[str]] = [[] for _ in HANOI_PEGS]
    for b in sorted(world.blocks, key=lambda b: b.bottom):
        k = int(np.argmin([math.dist(b.centre[:2], p) for p in HANOI_PEGS]))
        pegs[k].append(b.name)
    width = {b.name: float(b.size[0]) for b in world.blocks}
    height = {b.name: float(b.size[2]) for b in world.blocks}
    goals = []
    for i, (a, b) in enumerate(moves):
        if not pegs[a]:
            raise ValueError(f"move {i + 1} ({a} → {b}): peg {a} is empty")
        top = pegs[a][-1]
        if pegs[b] and width[pegs[b][-1]] < width[top]:
            raise ValueError(
                f"move {i + 1} ({a} → {b}): {top} ({width[top] * 100:.1f} cm) may not go on "
                f"the smaller {pegs[b][-1]} ({width[pegs[b][-1]] * 100:.1f} cm)"
            )
        z = sum(height[name] for name in pegs[b])
        pegs[a].pop()
        pegs[b].append(top)
        goals.append(Move(top, *HANOI_PEGS[b], z=z))
    return goals


def parse_goal(text: str, block: str) -> Move | str:
    """A goal typed as ``"x y"`` or ``"x, y"`` (metres) for ``block``, or why it cannot be
    read.

    Examples
    --------
    >>> parse_goal("0.25, -0.05", "A")
    Move(block='A', x=0.25, y=-0.05, z=None, yaw=0.0)
    >>> parse_goal("here", "A")
    "could not read 'here': type x and y in metres, e.g. 0.25 -0.05"
    """
    parts = str(text).replace(",", " ").split()
    try:
        numbers = [float(p) for p in parts]
    except ValueError:
        numbers = []
    if len(numbers) != 2:
        return f"could not read {str(text)[:40]!r}: type x and y in metres, e.g. 0.25 -0.05"
    return Move(block, numbers[0], numbers[1])


class StackPrompt:
    """Seed 001's goal, as a conversation: stack block B on block A at a place the user types,
    asking again, with the reasons, until the goal is valid and the task is planned.

    Widget-free (tests and ``urkin demo --task stack`` drive it with text; :func:`stack_panel`
    puts it behind ipywidgets).

    Examples
    --------
    >>> prompt = StackPrompt()
    >>> print(prompt.submit("0.22 0.15"))
    Not there: overlaps obstacle post by 45 mm. Type another x y.
    >>> print(prompt.submit("0.25 -0.05").splitlines()[0])
    Done: A at (0.250, -0.050) on the table, B on A; 16 phases, 21.0 s of motion.
    """

    def __init__(
        self,
        world: World | None = None,
        q_start=LAB_HOME,
        *,
        seed: int = 0,
        first: str = "A",
        second: str = "B",
    ) -> None:
        self.world = lab_world() if world is None else world
        self.q_start = np.asarray(q_start, dtype=float)
        self.seed = seed
        self.first, self.second = first, second
        self.task = None

    @property
    def done(self) -> bool:
        """Whether a task has been planned."""
        return self.task is not None

    def submit(self, text: str) -> str:
        """Read a typed goal ``"x y"``, validate it, plan: the answer to show."""
        from urkin.planning import pick_and_place, validate_goal

        goal = parse_goal(text, self.first)
        if isinstance(goal, str):
            return f"Not understood: {goal}. Type another x y."
        check = validate_goal(self.world, goal, q_start=self.q_start)
        if not check.ok:
            return f"Not there: {'; '.join(check.reasons)}. Type another x y."
        on_top = Move(self.second, goal.x, goal.y, check.placed.top)
        second = validate_goal(self.world.with_block(check.placed), on_top)
        if not second.ok:
            return (
                f"Not there: {self.first} fits, but {self.second} on it does not: "
                f"{'; '.join(second.reasons)}. Type another x y."
            )
        task = pick_and_place(self.world, [goal, on_top], self.q_start, seed=self.seed)
        if not task.success:
            return f"Not there: {task.reason}. Type another x y."
        self.task = task
        return (
            f"Done: {self.first} at ({goal.x:.3f}, {goal.y:.3f}) on the "
            f"{check.support}, {self.second} on {self.first}; {len(task.phases)} phases, "
            f"{task.t[-1]:.1f} s of motion.\n{task.report()}"
        )


class StackPanel:
    """The ipywidgets panel over a :class:`StackPrompt` (made by :func:`stack_panel`).

    In a live Jupyter kernel the panel shows its widget: type ``x y``, press *Stack*; the
    answer (the reasons, or the report and an animation of the task) appears below.
    Elsewhere (the docs, a notebook viewer) its ``text/html`` is the conversation so far.
    :meth:`submit` types a goal and presses the button from code.

    Attributes
    ----------
    prompt : StackPrompt
    widget : ipywidgets.VBox
        The panel.
    text : ipywidgets.Text
    button : ipywidgets.Button
    output : ipywidgets.Output
        The last answer (and the animation, once a task is planned).
    conversation : list of (str, str)
        What was typed and the first line of each answer.
    """

    def __init__(self, prompt: StackPrompt, *, animation_frames: int = 40) -> None:
        import ipywidgets as widgets

        if not isinstance(prompt, StackPrompt):
            raise TypeError(f"prompt must be a StackPrompt; got {type(prompt).__name__}")
        self.prompt = prompt
        self.animation_frames = int(animation_frames)
        self.conversation: list[tuple[str, str]] = []
        self.text = widgets.Text(placeholder="x y in metres, e.g. 0.25 -0.05", description="goal:")
        self.button = widgets.Button(description="Stack", button_style="primary")
        self.output = widgets.Output()
        self.button.on_click(lambda _button: self._answer())
        self.widget = widgets.VBox([widgets.HBox([self.text, self.button]), self.output])

    def submit(self, text: str) -> str:
        """Type ``text`` and press *Stack*, as a user would: the answer's first line.

        Examples
        --------
        >>> import matplotlib
        >>> matplotlib.use("Agg")
        >>> panel = stack_panel()
        >>> panel.submit("0.7 0").split(";")[0]
        'Not there: outside the table (x = 0.70 > 0.50 m)'
        """
        self.text.value = str(text)
        self.button.click()
        return self.conversation[-1][1]

    def _answer(self) -> None:
        """The button's handler.  The answer is set as the output widget's state rather
        than printed inside it, so nothing leaks into a notebook cell when no front end runs
        the widget (a test runner, the docs)."""
        typed = self.text.value
        answer = self.prompt.submit(typed)
        self.conversation.append((typed, answer.splitlines()[0]))
        outputs = [{"output_type": "stream", "name": "stdout", "text": answer + "\n"}]
        if answer.startswith("Done"):
            from urkin.plot import animate_task

            movie = animate_task(self.prompt.task, max_frames=self.animation_frames)
            outputs.append(
                {
                    "output_type": "display_data",
                    "data": {"text/html": movie.html, "text/plain": repr(movie)},
                    "metadata": {},
                }
            )
        self.output.outputs = tuple(outputs)

    def transcript(self) -> str:
        """The conversation so far, as text."""
        lines = [f"> {typed}\n{answer}" for typed, answer in self.conversation]
        return "\n".join(lines) if lines else "(nothing typed yet)"

    def _repr_mimebundle_(self, **kwargs) -> dict:
        import html

        bundle = dict(self.widget._repr_mimebundle_(**kwargs))
        bundle["text/plain"] = self.transcript()
        bundle["text/html"] = (
            "<p><em>Stack panel: type a goal x y and press Stack (run the notebook to use "
            "it). The conversation so far:</em></p><pre>"
            + html.escape(self.transcript())
            + "</pre>"
        )
        return bundle

    def __repr__(self) -> str:
        return self.transcript()


def stack_panel(prompt: StackPrompt | None = None, *, animation_frames: int = 40) -> StackPanel:
    """An ipywidgets panel over a :class:`StackPrompt`: type ``x y``, press *Stack*; the
    answer (reasons, or the report and the animation) appears below (see
    :class:`StackPanel`)."""
    return StackPanel(
        StackPrompt() if prompt is None else prompt, animation_frames=animation_frames
    )
