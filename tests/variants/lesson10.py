"""Lesson 10: other correct ways to write the exercises, and known mistakes."""

from tests.variants import Variant

# ----------------------------------------------------------------------- 10.1 grasp_flange_pose

_GRASP = """
def grasp_flange_pose(T_world_block, block_size, yaw_now, T_flange_tool):
    T_block = np.asarray(T_world_block, dtype=float)
    size = np.asarray(block_size, dtype=float)
    yaw_block = math.atan2(T_block[1, 0], T_block[0, 0])
    symmetry = {symmetry}
    yaw = {yaw}
    R = {R}
    top = {top}
    return {result}
"""


def _grasp(
    symmetry="np.pi / 2 if abs(size[0] - size[1]) <= 1e-9 else np.pi",
    yaw="yaw_block + round((yaw_now - yaw_block) / symmetry) * symmetry",
    R="rot_z(yaw) @ np.diag([1.0, -1.0, -1.0])",
    top="T_block[:3, 3] + [0.0, 0.0, size[2] / 2]",
    result="make_transform(R, top) @ inv_transform(np.asarray(T_flange_tool, dtype=float))",
):
    return _GRASP.format(symmetry=symmetry, yaw=yaw, R=R, top=top, result=result)


_GRASP_WRAPPED = """
def grasp_flange_pose(T_world_block, block_size, yaw_now, T_flange_tool):
    T_block = np.array(T_world_block, dtype=float)
    sx, sy, sz = block_size
    step = np.pi / 2 if np.isclose(sx, sy, rtol=0, atol=1e-9) else np.pi
    psi = np.arctan2(T_block[1, 0], T_block[0, 0])
    candidates = psi + step * np.arange(round(2 * np.pi / step))
    gaps = np.abs(np.angle(np.exp(1j * (candidates - yaw_now))))  # around the circle
    yaw = candidates[np.argmin(gaps)]
    c, s = np.cos(yaw), np.sin(yaw)
    T_tool = np.array(
        [[c, s, 0, 0], [s, -c, 0, 0], [0, 0, -1, 0], [0, 0, 0, 1]], dtype=float
    )
    T_tool[:3, 3] = T_block[:3, 3] + T_block[:3, 2] * sz / 2
    return T_tool @ np.linalg.inv(np.array(T_flange_tool, dtype=float))
"""

_GRASP_ROT_X = """
from urkin.transforms import rot_x


def grasp_flange_pose(T_world_block, block_size, yaw_now, T_flange_tool):
    T_block = np.asarray(T_world_block, dtype=float)
    size = np.asarray(block_size, dtype=float)
    yaw_block = np.arctan2(T_block[1, 0], T_block[0, 0])
    symmetry = np.pi / 2 if size[0] == size[1] else np.pi
    turns = np.floor((yaw_now - yaw_block) / symmetry + 0.5)
    T_tool = make_transform(rot_z(yaw_block + turns * symmetry) @ rot_x(np.pi),
                            T_block[:3, 3] + np.array([0, 0, size[2] / 2]))
    R_ft, p_ft = np.asarray(T_flange_tool)[:3, :3], np.asarray(T_flange_tool)[:3, 3]
    T_tool_flange = make_transform(R_ft.T, -R_ft.T @ p_ft)
    return T_tool @ T_tool_flange
"""

_GRASP_LIBRARY = """
def grasp_flange_pose(T_world_block, block_size, yaw_now, T_flange_tool):
    block = planning.Block("b", block_size, T_world_block)
    T_tool = planning.top_down_grasp(block, yaw_now)
    return T_tool @ inv_transform(np.asarray(T_flange_tool, dtype=float))
"""

# ---------------------------------------------------------------------------- 10.2 goal_problems

_GOALS = """
def goal_problems(world, block, x, y, z):
    size = np.asarray(world["blocks"][block]["size"], dtype=float)
    table = world["table"]
    others = [b for n, b in world["blocks"].items() if {others}]
    obstacles = list(world["obstacles"].values())

    def over(b, scale=1.0, px=x, py=y):
        R = np.asarray(b["pose"])[:2, :2]
        local = R.T @ (np.array([px, py]) - np.asarray(b["pose"])[:2, 3])
        return bool(np.all(np.abs(local) <= scale * np.asarray(b["size"])[:2] / 2))

    def top(b):
        return float(np.asarray(b["pose"])[2, 3] + np.asarray(b["size"])[2] / 2)

    def centre(b):
        return np.asarray(b["pose"])[:2, 3]

    broken = []
    on_table = {on_table}
    if not on_table:
        broken.append("table")
    yaws = {yaws}
    robot = {robot}
    down = np.diag([1.0, -1.0, -1.0])
    grasps = [make_transform(rot_z(a) @ down, [x, y, {reach_z}]) for a in yaws]
    if not any(len(urkin.ik_analytic(robot, T)) for T in grasps):
        broken.append("reach")
    tops = ([top(table)] if on_table else []) + {block_tops}
    bottom = z
    if tops:
        nearest = min(tops, key=lambda t: abs(t - z))
        if abs(nearest - z) <= {gap}:
            bottom = {snap}
        else:
            broken.append("support")
    height = {height}
    placed = planning.Block.standing(block, [size[0], size[1], height], x, y, bottom)
    boxes = [table, *obstacles, *others]
    gaps = planning.box_separation(
        placed.centre,
        placed.pose[:3, :3],
        placed.size / 2,
        np.array([np.asarray(b["pose"])[:3, 3] for b in boxes]),
        np.array([{rotation} for b in boxes]),
        np.array([{half} for b in boxes]),
    )
    if np.any(gaps < {touch}):
        broken.append("overlap")
    return {result}
"""


def _goals(
    others="n != block",
    on_table="over(table)",
    yaws="(0.0, np.pi / 2, np.pi, -np.pi / 2) if size[0] == size[1] else (0.0, np.pi)",
    robot='world["robot"]',
    reach_z="z + size[2]",
    block_tops="[top(b) for b in others if over(b)]",
    gap="0.005",
    snap="nearest",
    height="size[2]",
    rotation='np.asarray(b["pose"])[:3, :3]',
    half='np.asarray(b["size"]) / 2',
    touch="-1e-4",
    result="broken",
):
    return _GOALS.format(
        others=others,
        on_table=on_table,
        yaws=yaws,
        robot=robot,
        reach_z=reach_z,
        block_tops=block_tops,
        gap=gap,
        snap=snap,
        height=height,
        rotation=rotation,
        half=half,
        touch=touch,
        result=result,
    )


_GOALS_PLAIN = """
def goal_problems(world, block, x, y, z):
    s = np.asarray(world["blocks"][block]["size"], dtype=float)

    def local(b):
        T = np.asarray(b["pose"], dtype=float)
        return T[:2, :2].T @ (np.array([x, y]) - T[:2, 3])

    def inside(b):
        return np.all(np.abs(local(b)) <= np.asarray(b["size"])[:2] / 2)

    def top(b):
        return np.asarray(b["pose"])[2, 3] + np.asarray(b["size"])[2] / 2

    out = []
    if not inside(world["table"]):
        out.append("table")
    n = 4 if abs(s[0] - s[1]) < 1e-9 else 2
    reach = False
    for k in range(n):
        a = 2 * np.pi * k / n
        R = np.array([[np.cos(a), np.sin(a), 0], [np.sin(a), -np.cos(a), 0], [0, 0, -1]])
        T = np.eye(4)
        T[:3, :3], T[:3, 3] = R, [x, y, z + s[2]]
        reach = reach or urkin.ik_analytic(world["robot"], T).shape[0] > 0
    if not reach:
        out.append("reach")
    others = {n: b for n, b in world["blocks"].items() if n != block}
    tops = [top(world["table"])] if "table" not in out else []
    tops += [top(b) for b in others.values() if inside(b)]
    bottom = z
    if tops:
        best = tops[int(np.argmin([abs(t - z) for t in tops]))]
        if abs(best - z) > 0.005:
            out.append("support")
        else:
            bottom = best

    def overlaps(b):  # two upright boxes: heights, then their footprints' separating axes
        T = np.asarray(b["pose"], dtype=float)
        h = np.asarray(b["size"], dtype=float) / 2
        if abs(T[2, 3] - (bottom + s[2] / 2)) - h[2] - s[2] / 2 >= -1e-4:
            return False
        d = T[:2, 3] - np.array([x, y])
        for axis in (np.array([1.0, 0.0]), np.array([0.0, 1.0]), T[:2, 0], T[:2, 1]):
            mine = abs(axis[0]) * s[0] / 2 + abs(axis[1]) * s[1] / 2
            theirs = abs(axis @ T[:2, 0]) * h[0] + abs(axis @ T[:2, 1]) * h[1]
            if abs(axis @ d) - mine - theirs >= -1e-4:
                return False
        return True

    boxes = [world["table"], *world["obstacles"].values(), *others.values()]
    if any(overlaps(b) for b in boxes):
        out.append("overlap")
    return out
"""

_GOALS_LIBRARY = """
def goal_problems(world, block, x, y, z):
    verdict = planning.validate_goal(world_from_data(world), (block, x, y, z))
    kinds = {"outside": "table", "unreachable": "reach", "no support": "support",
             "overlaps": "overlap"}
    return [v for k, v in kinds.items() if any(r.startswith(k) for r in verdict.reasons)]
"""

# ------------------------------------------------------------------------------- 10.3 stack_two

_STACK = """
def stack_two(world, x, y, q_start):
    w = world_from_data(world)
    turns = (0.0, np.pi / 2, -np.pi / 2, np.pi)

    def vertical_moves(at, poses, q_near, scene, count):
        options = []
        for T in poses:
            solutions = urkin.ik_analytic(at.robot, T)
            near = q_near + wrap_angles(solutions - q_near)
            near = np.where(np.abs(near) > 2 * np.pi, near - np.sign(near) * 2 * np.pi, near)
            near[:, 1:3] = solutions[:, 1:3]
            options += [(float(np.linalg.norm(q - q_near)), q, T) for q in near]
        found = []
        for _, q, T in sorted(options, key=lambda option: option[0]):
            line_up = pose_path(line(T[:3, 3], T[:3, 3] + [0.0, 0.0, HOVER]), T[:3, :3])
            moved = track(at.robot, line_up, q)
            Q = moved.q
            if moved.ok.all() and planning.edges_free(at.model, scene, Q[:-1], Q[1:]).all():
                found.append(Q)
                if len(found) == count:
                    break
        return found

    def connect(model, scene, q, goals):
        for seed in range(5):
            plan = planning.rrt_connect(model, scene, q, np.array(goals), seed=seed,
                                        max_iterations=3000)
            if plan.success:
                return plan
        raise RuntimeError(plan.reason)

    q = np.asarray(q_start, dtype=float)
    steps, bottom = [], w.table.top
    for name in ("A", "B"):
        block = w.block(name)
        yaw = planning.tool_yaw(urkin.fk(w.robot, q))
        grasps = [planning.top_down_grasp(block, yaw + turn) for turn in turns]
        ups = vertical_moves(w, grasps, q, w.scene(), 3)
        plan = connect(w.model, w.scene(), q, [u[-1] for u in ups])
        up = ups[plan.goal]
        steps += [("move", {first_path}), ("move", up[::-1]), ("grip", name), ("move", up)]
        in_tool = inv_transform(urkin.fk(w.robot, up[0])) @ block.pose
        q = up[-1]
        yaw = planning.tool_yaw(urkin.fk(w.robot, q))
        gx, gy = {goal}
        carrying, around = w.carrying(block.size), w.scene(without=(name,))
        downs, afters = [], []
        for turn in turns:
            T = make_transform(rot_z(yaw + turn) @ np.diag([1.0, -1.0, -1.0]),
                               [gx, gy, bottom + block.size[2]])
            after = w.with_block(block.moved(T @ in_tool))
            found = vertical_moves(after, [T], q, after.scene(without=(name,)), 1)
            found = [d for d in found if planning.is_free(carrying, around, d[-1])]
            downs += found
            afters += [after] * len(found)
        plan = connect({transfer}, q, [d[-1] for d in downs])
        down = downs[{chosen}]
        steps += [("move", {transfer_path})] + {place}
        q, w = down[-1], afters[{chosen}]
        bottom = {next_bottom}
    return steps
"""


def _stack(
    first_path="plan.path",
    goal="x, y",
    transfer="w.carrying(block.size), w.scene(without=(name,))",
    transfer_path="plan.path",
    place='[("move", down[::-1]), ("release", name), ("move", down)]',
    next_bottom="w.block(name).top",
    chosen="plan.goal",
):
    return _STACK.format(
        chosen=chosen,
        first_path=first_path,
        goal=goal,
        transfer=transfer,
        transfer_path=transfer_path,
        place=place,
        next_bottom=next_bottom,
    )


_STACK_LIBRARY = """
def stack_two(world, x, y, q_start):
    w = world_from_data(world)
    top = w.table.top + w.block("A").size[2]
    task = planning.pick_and_place(w, [("A", x, y), ("B", x, y, top)], q_start)
    return task.steps()
"""

# ---------------------------------------------------------------------------------- 10.4 hanoi

_HANOI = """
def hanoi(n, source, target, spare):
    {base}
    return [*{first}, {move}, *{second}]
"""


def _hanoi(
    base="if n == 0:\n        return []",
    first="hanoi(n - 1, source, spare, target)",
    move="(source, target)",
    second="hanoi(n - 1, spare, target, source)",
):
    return _HANOI.format(base=base, first=first, move=move, second=second)


_HANOI_ITERATIVE = """
def hanoi(n, source, target, spare):
    pegs = {source: list(range(n, 0, -1)), target: [], spare: []}
    cycle = [source, target, spare] if n % 2 else [source, spare, target]
    moves = []
    for k in range(2**n - 1):
        if k % 2 == 0:  # the smallest block moves one peg along the cycle
            i = (k // 2) % 3
            a, b = cycle[i], cycle[(i + 1) % 3]
        else:  # the only other legal move
            a, b = [p for p in pegs if not (pegs[p] and pegs[p][-1] == 1)]
            if not pegs[a] or (pegs[b] and pegs[b][-1] < pegs[a][-1]):
                a, b = b, a
        pegs[b].append(pegs[a].pop())
        moves.append((a, b))
    return moves
"""

_HANOI_LISTS = """
def hanoi(n, source, target, spare):
    if n == 1:
        return [[source, target]]
    moves = hanoi(n - 1, source, spare, target)
    moves.append([source, target])
    moves.extend(hanoi(n - 1, spare, target, source))
    return moves
"""

CORRECT = [
    Variant("10.1", "every candidate compared around the circle, np.linalg.inv", _GRASP_WRAPPED),
    Variant("10.1", "rot_x(π), floor(+0.5), the tool inverted by hand", _GRASP_ROT_X),
    Variant("10.1", "a template of the solution", _grasp()),
    Variant("10.2", "plain numpy, the separating axes by hand", _GOALS_PLAIN),
    Variant("10.2", "a template of the solution", _goals()),
    Variant("10.3", "a template of the solution", _stack()),
    Variant("10.4", "iterative: the smallest block cycles", _HANOI_ITERATIVE),
    Variant("10.4", "base case n == 1, moves as lists", _HANOI_LISTS),
]

WRONG = [
    # ------------------------------------------------------------------------------ 10.1
    Variant("10.1", "tool pointing up", _grasp(R="rot_z(yaw)"), points=0, mistake="points up"),
    Variant(
        "10.1",
        "x axis turned by π",
        _grasp(R="rot_z(yaw) @ np.diag([-1.0, 1.0, -1.0])"),
        points=0,
        mistake="turned by π",
    ),
    Variant(
        "10.1", "the block's yaw as it is", _grasp(yaw="yaw_block"), points=0, mistake="as it is"
    ),
    Variant(
        "10.1",
        "a square block reduced by 180°",
        _grasp(symmetry="np.pi"),
        points=None,
        mistake="reduced by 180° only",
    ),
    Variant(
        "10.1",
        "an oblong block reduced by 90°",
        _grasp(symmetry="np.pi / 2"),
        points=3,
        mistake="oblong block turned by 90°",
    ),
    Variant(
        "10.1",
        "the multiple nearest 0",
        _grasp(yaw="yaw_block - round(yaw_block / symmetry) * symmetry"),
        points=None,
        mistake="nearest 0",
    ),
    Variant(
        "10.1",
        "nearest along the line",
        _grasp(
            yaw="min(np.angle(np.exp(1j * (yaw_block + symmetry * np.arange(4)))), "
            "key=lambda c: abs(c - yaw_now))"
        ),
        points=None,
        mistake="along the line",
    ),
    Variant("10.1", "the wrist's yaw kept", _grasp(yaw="yaw_now"), points=0, mistake="kept"),
    Variant(
        "10.1",
        "the tool's pose returned",
        _grasp(result="make_transform(R, top)"),
        points=0,
        mistake="offset forgotten",
    ),
    Variant(
        "10.1",
        "T_flange_tool not inverted",
        _grasp(result="make_transform(R, top) @ np.asarray(T_flange_tool, dtype=float)"),
        points=0,
        mistake="without inverting",
    ),
    Variant(
        "10.1",
        "the inverse on the left",
        _grasp(
            result="inv_transform(np.asarray(T_flange_tool, dtype=float)) @ make_transform(R, top)"
        ),
        points=0,
        mistake="on the left",
    ),
    Variant(
        "10.1", "grasp at the centre", _grasp(top="T_block[:3, 3]"), points=0, mistake="centre"
    ),
    Variant(
        "10.1",
        "a whole height above the centre",
        _grasp(top="T_block[:3, 3] + [0.0, 0.0, size[2]]"),
        points=0,
        mistake="full height",
    ),
    Variant("10.1", "urkin's own top_down_grasp", _GRASP_LIBRARY, points=0),
    # ------------------------------------------------------------------------------ 10.2
    Variant(
        "10.2",
        "its own place counted",
        _goals(others="True"),
        points=3,
        mistake="collides with itself",
    ),
    Variant(
        "10.2",
        "touching counted as overlapping",
        _goals(touch="1e-6"),
        points=0,
        mistake="touching counted",
    ),
    Variant(
        "10.2",
        "footprints without heights",
        _goals(
            height="4.0",
            half='[*np.asarray(b["size"])[:2] / 2, 2.0]',
        ),
        points=0,
        mistake="without the heights",
    ),
    Variant(
        "10.2",
        "other boxes' yaw ignored",
        _goals(rotation="np.eye(3)"),
        points=3,
        mistake="yaw ignored",
    ),
    Variant(
        "10.2",
        "support from the nearest block",
        _goals(
            block_tops="([top(min(others, key=lambda b: np.linalg.norm(centre(b) - [x, y])))] "
            "if others else [])"
        ),
        points=2,
        mistake="nearest block",
    ),
    Variant(
        "10.2",
        "only the table supports",
        _goals(block_tops="[]"),
        points=2,
        mistake="only the table",
    ),
    Variant("10.2", "exact contact", _goals(gap="1e-9"), points=3, mistake="exact contact"),
    Variant("10.2", "not put on its support", _goals(snap="z"), points=3, mistake="not put onto"),
    Variant(
        "10.2",
        "reach at the block's centre",
        _goals(reach_z="z + size[2] / 2"),
        points=3,
        mistake="block's centre",
    ),
    Variant(
        "10.2", "reach at the block's bottom", _goals(reach_z="z"), points=3, mistake="centre (or"
    ),
    Variant(
        "10.2",
        "the base ignored",
        _goals(robot='world["robot"].with_base(np.eye(4))'),
        points=None,
        mistake="base ignored",
    ),
    Variant(
        "10.2",
        "the table's full size as half",
        _goals(on_table="over(table, 2.0)"),
        points=3,
        mistake="full size",
    ),
    Variant(
        "10.2",
        "the whole footprint on the table",
        _goals(
            on_table="all(over(table, 1.0, x + sx * size[0] / 2, y + sy * size[1] / 2) "
            "for sx in (-1, 1) for sy in (-1, 1))"
        ),
        points=3,
        mistake="whole footprint",
    ),
    Variant(
        "10.2", "rules sorted", _goals(result="sorted(broken)"), points=2, mistake="out of order"
    ),
    Variant("10.2", "urkin's own validate_goal", _GOALS_LIBRARY, points=0),
    # ------------------------------------------------------------------------------ 10.3
    Variant(
        "10.3",
        "the transfer planned without the block",
        _stack(transfer="w.model, w.scene()"),
        points=None,
        mistake="carrying(size)",
    ),
    Variant(
        "10.3",
        "the transfer as its two ends",
        _stack(transfer_path="np.array([q, down[-1]])", chosen="0"),
        points=None,
        mistake="two ends",
    ),
    Variant(
        "10.3",
        "released at the hover",
        _stack(place='[("release", name)]', next_bottom="w.block(name).top"),
        points=0,
        mistake="released in the air",
    ),
    Variant(
        "10.3",
        "B lowered to the table inside A",
        _stack(next_bottom="w.table.top"),
        points=0,
        mistake="lowered into",
    ),
    Variant(
        "10.3",
        "B left holding",
        _stack(
            place='[("move", down[::-1])] + ([("release", name), ("move", down)] '
            'if name == "A" else [])'
        ),
        points=0,
        mistake="while holding",
    ),
    Variant(
        "10.3",
        "the first move skips its start",
        _stack(first_path="plan.path[1:]"),
        points=0,
        mistake="does not start where the arm is",
    ),
    Variant("10.3", "urkin's own pick_and_place", _STACK_LIBRARY, points=0),
    # ------------------------------------------------------------------------------ 10.4
    Variant(
        "10.4",
        "target and spare swapped first",
        _hanoi(first="hanoi(n - 1, source, target, spare)"),
        points=0,
        mistake="first recursive call",
    ),
    Variant(
        "10.4",
        "the smaller blocks to the wrong peg",
        _hanoi(second="hanoi(n - 1, spare, source, target)"),
        points=0,
        mistake="second recursive call",
    ),
    Variant(
        "10.4",
        "base case n == 1 with no move",
        _hanoi(base="if n <= 1:\n        return []"),
        points=0,
        mistake="off-by-one",
    ),
    Variant(
        "10.4",
        "a move for zero blocks",
        _hanoi(base="if n == 0:\n        return [(source, target)]"),
        points=0,
        mistake="off-by-one",
    ),
    Variant(
        "10.4",
        "moves written (to, from)",
        _hanoi(move="(target, source)"),
        points=0,
        mistake="(to, from)",
    ),
]
