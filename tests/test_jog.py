"""urkin.jog: the controller moves only to verified configurations, the panel and the window
drive it, and ``urkin demo`` records or refuses cleanly."""

import re
from dataclasses import replace

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest

import urkin
from urkin import jog as J
from urkin.cli import main
from urkin.jog import JogController
from urkin.transforms import pose_error

UR3 = urkin.robot("UR3")
CENTER = np.array([0.25, 0.1, 0.3])
OFFSETS = {"X": 0, "Y": 1, "Z": 2}


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


@pytest.fixture
def jog():
    return JogController(UR3)


def _bits(q: np.ndarray) -> bytes:
    return np.ascontiguousarray(q).tobytes()


# ---------------------------------------------------------------------------------------------
# the home configuration
# ---------------------------------------------------------------------------------------------


def test_home_is_elbow_up_at_the_centre_with_identity_orientation(jog):
    T = urkin.fk(UR3, jog.q0)
    assert np.abs(T[:3, 3] - CENTER).max() < 1e-12
    assert np.abs(T[:3, :3] - np.eye(3)).max() < 1e-12
    frames = urkin.fk_frames(UR3, jog.q0)[:, :3, 3]
    shoulder, elbow, wrist = frames[1], frames[2], frames[3]
    # the elbow is above the shoulder-wrist line at its own horizontal distance
    t = np.dot(elbow - shoulder, wrist - shoulder) / np.dot(wrist - shoulder, wrist - shoulder)
    assert elbow[2] > (shoulder + t * (wrist - shoulder))[2] + 0.1
    assert frames[1:, 2].min() > 0.15  # nothing below the shoulder, let alone the plane
    assert np.all(np.abs(jog.q0) <= np.pi)
    assert np.array_equal(jog.q, jog.q0) and jog.history == []
    assert jog.trail.shape == (1, 6)


def test_home_configuration_refuses_an_unreachable_centre():
    with pytest.raises(ValueError, match="reaches position"):
        J.home_configuration(UR3, (1.0, 0.0, 0.3))
    with pytest.raises(ValueError, match="center"):
        JogController(UR3, center=(1.0, 0.0, 0.3))


# ---------------------------------------------------------------------------------------------
# presses
# ---------------------------------------------------------------------------------------------


def test_presses_follow_the_summed_offsets_with_the_orientation_held(jog):
    T0 = urkin.fk(UR3, jog.q0)
    expected = T0[:3, 3].copy()
    for key in ("X+", "X+", "Z-", "Y+"):
        expected[OFFSETS[key[0]]] += 0.02 if key[1] == "+" else -0.02
        step = jog.press(key)
        assert step.ok and step.action == key and step.qs.shape == (1, 6)
        assert np.array_equal(step.q, step.qs[0]) and np.array_equal(jog.q, step.q)
        T = urkin.fk(UR3, step.q)
        assert np.abs(T[:3, 3] - expected).max() < 1e-9
        assert np.abs(T[:3, :3] - T0[:3, :3]).max() < 1e-9
        x, y, z = expected
        assert step.status == f"{key}: moved to x {x:.3f} y {y:.3f} z {z:.3f} m"
    assert np.abs(jog.flange[:3, 3] - (CENTER + np.array([0.04, 0.02, -0.02]))).max() < 1e-9
    trail = jog.trail
    assert trail.shape == (5, 6)
    assert np.array_equal(trail[0], jog.q0)
    assert np.array_equal(trail[1:], np.stack([s.q for s in jog.history]))


def test_keys_are_case_insensitive_and_checked(jog):
    assert jog.press("x-").status.startswith("X-: moved to x 0.230")
    assert jog.do(" z+ ").action == "Z+"
    for bad in ("W+", "X", "", None, "home"):
        with pytest.raises(ValueError, match=re.escape("X+, X-, Y+, Y-, Z+, Z-")):
            jog.press(bad)
    with pytest.raises(ValueError, match="home, circle, square"):
        jog.do("jump")
    assert len(jog.history) == 2


def test_a_press_beyond_reach_leaves_q_unchanged(jog):
    jog.press("X+")
    before, trail = _bits(jog.q), jog.trail
    jog.step = 1.0
    step = jog.press("X+")
    assert not step.ok and step.qs.shape == (0, 6)
    assert _bits(jog.q) == before and _bits(step.q) == before
    assert step.status.startswith("X+: IK failed: unreachable")
    assert step.status.endswith("; staying put")
    assert re.search(r"the target is \d\.\d{4} m beyond", step.status)
    assert np.array_equal(jog.trail, trail)
    assert jog.moves == 1 and len(jog.history) == 2


def test_a_press_that_would_flip_the_wrist_is_refused():
    q0 = np.array([3.0917, -0.8813, 1.4892, 0.9629, 1e-3, 1.6207])  # 1 mrad from the wrist
    jog = JogController(UR3, q0=q0)
    step = jog.press("X+")
    assert not step.ok and _bits(jog.q) == _bits(q0)
    assert re.search(r"refused: joint 6 would jump by \d\.\d\d rad", step.status)
    assert "singularity" in step.status and step.status.endswith("staying put")


def test_a_press_that_would_wind_a_joint_past_its_limit_is_refused():
    home = J.home_configuration(UR3)
    limits = [(-2 * np.pi, 2 * np.pi)] * 6
    limits[0] = (-2 * np.pi, home[0] + 0.01)  # joint 1 can barely turn further up
    arm = replace(UR3, joint_limits=tuple(limits))
    jog = JogController(arm)
    step = jog.press("Y+")  # needs joint 1 to turn up by more than 0.01 rad
    assert not step.ok and _bits(jog.q) == _bits(home)
    assert "joint 1 would have to turn past its limit" in step.status
    assert jog.press("Y-").ok  # the other way is free


def test_presses_stop_above_the_mounting_plane(jog):
    steps = [jog.press("Z-") for _ in range(12)]
    refused = [s for s in steps if not s.ok]
    assert refused and all(s.ok for s in steps[: steps.index(refused[0])])
    assert re.search(
        r"DH frame \d would go [\d.e-]+ mm below the mounting plane", refused[0].status
    )
    heights = urkin.fk_frames(UR3, jog.trail)[:, 1:, 2, 3]
    assert heights.min() > 0.0


# ---------------------------------------------------------------------------------------------
# paths and home
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("shape", ["circle", "square"])
def test_runs_follow_the_path_exactly(jog, shape):
    jog.press("X+")
    before = len(jog.trail)
    step = jog.run(shape)
    poses = jog.path_poses(shape)
    assert step.ok, step.status
    assert step.status.startswith(f"{shape}: a joint move of ")
    m = len(poses)
    assert f"then {m} samples round the {shape}" in step.status
    followed = step.qs[-m:]
    position, angle = pose_error(urkin.fk(UR3, followed), poses)
    assert position.max() < 1e-9 and angle.max() < 1e-9
    targets = poses[:, :3, 3]
    assert np.linalg.norm(np.diff(targets, axis=0), axis=1).max() <= 1e-3
    reached = urkin.fk(UR3, followed)[:, :3, 3]
    assert np.linalg.norm(np.diff(reached, axis=0), axis=1).max() <= 1e-3 + 1e-9
    # identity orientation, on the path's plane, ending where it started
    assert np.abs(poses[:, :3, :3] - np.eye(3)).max() == 0.0
    assert np.abs(targets[:, 0] - CENTER[0]).max() < 1e-15
    assert np.array_equal(poses[0], poses[-1])
    if shape == "circle":
        assert np.abs(np.linalg.norm(targets - CENTER, axis=1) - 0.1).max() < 1e-12
    else:
        assert np.abs(np.abs(targets - CENTER)[:, 1:].max(axis=1) - 0.075).max() < 1e-12
    # the approach: a joint move from where the arm was, small joint steps
    approach = np.vstack([jog.trail[before - 1], step.qs[:-m]])
    assert np.abs(np.diff(approach, axis=0)).max() <= J.JOINT_MOVE_STEP + 1e-12
    assert np.array_equal(jog.q, step.qs[-1])
    assert len(jog.trail) == before + len(step.qs)


@pytest.mark.parametrize("shape", ["circle", "square"])
def test_runs_from_home_keep_their_branch_well_above_the_plane(jog, shape):
    """What home_configuration's docstring promises."""
    step = jog.run(shape)
    signs = np.sign(urkin.kinematics.singularity_factors(UR3, np.vstack([jog.q0, step.qs])))
    assert np.array_equal(signs, np.broadcast_to([-1.0, 1.0, -1.0], signs.shape))
    assert urkin.fk_frames(UR3, step.qs)[:, 1:, 2, 3].min() > 0.118


def test_a_run_stops_at_the_last_reached_sample():
    jog = JogController(UR3, center=(0.25, 0.1, 0.45), radius=0.25)  # the top is out of reach
    poses = jog.path_poses("circle")
    _, real = urkin.ik_analytic(UR3, poses, return_mask=True)
    first_missing = int(np.argmin(real.any(axis=1)))  # independent of the controller
    assert 0 < first_missing < len(poses)
    step = jog.run("circle")
    assert not step.ok
    assert f"sample {first_missing} failed" in step.status
    assert "unreachable" in step.status and re.search(r"\d m ", step.status)
    assert f"stopped at sample {first_missing - 1}" in step.status
    position, angle = pose_error(urkin.fk(UR3, jog.q), poses[first_missing - 1])
    assert position < 1e-9 and angle < 1e-9
    assert np.array_equal(jog.q, step.qs[-1])


def test_a_run_whose_start_is_out_of_reach_stays_put():
    jog = JogController(UR3, radius=0.6)
    before = _bits(jog.q)
    step = jog.run("circle")
    assert not step.ok and step.qs.shape == (0, 6) and _bits(jog.q) == before
    assert "cannot be reached" in step.status and "staying put" in step.status
    assert re.search(r"\d\.\d{4} m beyond", step.status)


def test_home_returns_exactly_to_q0(jog):
    for action in ("X+", "Z+", "circle", "Y-"):
        jog.do(action)
    step = jog.home()
    assert step.ok and np.array_equal(jog.q, jog.q0) and np.array_equal(step.qs[-1], jog.q0)
    assert step.status == "home: moved to x 0.250 y 0.100 z 0.300 m"
    path = np.vstack([jog.trail[-len(step.qs) - 1], step.qs])
    assert np.abs(np.diff(path, axis=0)).max() <= J.JOINT_MOVE_STEP + 1e-12
    again = jog.home()
    assert again.ok and again.qs.shape == (0, 6) and again.status == "home: already there"


def test_trail_and_history(jog):
    steps = [jog.do(a) for a in ("X+", "home", "square", "Z+")]
    jog.step = 2.0
    steps.append(jog.press("Z+"))  # refused
    trail = jog.trail
    assert trail.shape == (1 + sum(len(s.qs) for s in steps), 6)
    assert np.array_equal(trail[-1], jog.q) and np.array_equal(trail[0], jog.q0)
    assert jog.history == steps and jog.moves == 4
    assert not steps[1].qs.flags.writeable and not jog.q0.flags.writeable
    q = jog.q
    q[0] = 99.0
    assert jog.q[0] != 99.0


def test_arguments_are_checked():
    with pytest.raises(ValueError, match="step"):
        JogController(UR3, step=0.0)
    with pytest.raises(ValueError, match="step"):
        JogController(UR3).step = -0.01
    with pytest.raises(ValueError, match="center"):
        JogController(UR3, center=(0.25, 0.1))
    with pytest.raises(ValueError, match="radius"):
        JogController(UR3, radius=-1)
    with pytest.raises(ValueError, match="side"):
        JogController(UR3, side=0)
    with pytest.raises(ValueError, match="plane"):
        JogController(UR3, plane="xz")
    with pytest.raises(ValueError, match="max_jump"):
        JogController(UR3, max_jump=0)
    with pytest.raises(ValueError, match="q0"):
        JogController(UR3, q0=np.zeros(5))
    with pytest.raises(ValueError, match="q0 is outside the UR3's joint limits: joint 2"):
        JogController(UR3, q0=[0, 7, 0, 0, 0, 0])
    with pytest.raises(ValueError, match="q0"):
        JogController(UR3, q0=[0, np.nan, 0, 0, 0, 0])
    with pytest.raises(TypeError, match="robot"):
        JogController("UR3")
    with pytest.raises(ValueError, match="shape"):
        JogController(UR3).run("triangle")


def test_statuses_do_not_depend_on_round_off():
    T = np.eye(4)
    for wobble in (-1e-13, 0.0, 1e-13):
        T[:3, 3] = [0.27 + wobble, -0.0 + wobble, 0.2505 + wobble]
        assert J._where(T) == J._where(np.round(T, 9))
    T[:3, 3] = [-1e-15, 0.0, 0.3]
    assert J._where(T) == "x 0.000 y 0.000 z 0.300 m"


def test_parse_script():
    assert J.parse_script("X+, x-,home ,CIRCLE,square,") == ["X+", "X-", "home", "circle", "square"]
    with pytest.raises(ValueError, match="action must be one of"):
        J.parse_script("X+,up")
    with pytest.raises(ValueError, match="empty"):
        J.parse_script(" , ")


def test_importing_jog_loads_no_plotting_or_widgets():
    import subprocess
    import sys

    code = (
        "import sys, urkin.jog; "
        "print(sorted(m for m in ('matplotlib', 'ipywidgets', 'IPython') if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


# ---------------------------------------------------------------------------------------------
# the panel, the window
# ---------------------------------------------------------------------------------------------


def test_panel_buttons_drive_the_controller(jog):
    pytest.importorskip("ipywidgets")
    panel = J.jog_panel(jog)
    assert set(panel.buttons) == {"X+", "X-", "Y+", "Y-", "Z+", "Z-", "Home", "Circle", "Square"}
    panel.click("X+")
    assert jog.history[-1].action == "X+" and jog.history[-1].ok
    assert panel.status.value == jog.history[-1].status
    panel.slider.value = 10
    assert jog.step == 0.01
    panel.click("z-")
    assert jog.history[-1].status == "Z-: moved to x 0.270 y 0.100 z 0.290 m"
    panel.click("Home")
    assert np.array_equal(jog.q, jog.q0)
    panel.click("Square")
    assert jog.history[-1].action == "square" and jog.history[-1].ok
    with pytest.raises(ValueError, match="Circle"):
        panel.click("Triangle")
    assert panel.widget.children[-1] is panel.output
    assert repr(panel) == "Jog panel: UR3, 4 moves so far; run the notebook to use the buttons"


def test_panel_mime_bundle(jog):
    pytest.importorskip("ipywidgets")
    pytest.importorskip("urkin.animation")
    panel = J.jog_panel(jog, animation_frames=5)
    panel.click("X+")
    bundle = panel._repr_mimebundle_()
    assert "application/vnd.jupyter.widget-view+json" in bundle
    assert bundle["text/plain"] == (
        "Jog panel: UR3, 1 move so far; run the notebook to use the buttons"
    )
    assert isinstance(bundle["text/html"], str) and len(bundle["text/html"]) > 100


def test_window_buttons_drive_the_controller(jog):
    window = J.demo_figure(jog)
    assert set(window.buttons) == {"X+", "X-", "Y+", "Y-", "Z+", "Z-", "Home", "Circle", "Square"}
    window.buttons["Y-"]._observers.process("clicked", None)  # what a mouse click does
    assert jog.history[-1].status == "Y-: moved to x 0.250 y 0.080 z 0.300 m"
    assert window.status.get_text() == jog.history[-1].status
    step = window.click("circle")
    assert step.ok and window.status.get_text() == step.status
    assert window.ax.get_title().startswith("UR3 at q = ")


def test_window_plays_moves_frame_by_frame(jog):
    window = J.demo_figure(jog)
    window._animated = True  # as with an interactive backend, whose timer calls _tick
    jog.press("Z+")
    step = window.click("home")
    assert 1 < len(window._queue) <= window.frames_per_move
    assert window._queue[-1] == len(jog.trail) - 1
    while window._queue:
        window._tick()
    window._tick()  # an empty queue stops the timer
    arm = window.ax.lines[2]  # after the two reference axes of axes3d: the stick figure
    assert np.allclose(np.array(arm.get_data_3d())[:, -1], jog.flange[:3, 3])
    assert step.ok and window.status.get_text() == step.status


# ---------------------------------------------------------------------------------------------
# urkin demo
# ---------------------------------------------------------------------------------------------


def test_demo_without_display_or_save_exits_2(monkeypatch, capsys):
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    assert main(["demo"]) == 2
    err = capsys.readouterr().err
    assert "--save" in err and ("display" in err or "backend" in err)


def test_demo_rejects_a_bad_script_or_robot(tmp_path, capsys):
    assert main(["demo", "--save", str(tmp_path / "x.gif"), "--script", "X+,fly"]) == 2
    assert "action must be one of" in capsys.readouterr().err
    assert main(["demo", "--robot", "UR4", "--save", str(tmp_path / "x.gif")]) == 2
    assert "UR4" in capsys.readouterr().err
    assert main(["demo", "--save", str(tmp_path / "x.png")]) == 2
    assert ".gif" in capsys.readouterr().err
    assert not list(tmp_path.iterdir())


def test_demo_saves_a_gif_headless(tmp_path, monkeypatch, capsys):
    pytest.importorskip("urkin.animation")
    Image = pytest.importorskip("PIL.Image")
    monkeypatch.delenv("DISPLAY", raising=False)
    path = tmp_path / "x.gif"
    assert main(["demo", "--save", str(path), "--script", "X+,Z-,home,square"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[:3] == [
        "X+: moved to x 0.270 y 0.100 z 0.300 m",
        "Z-: moved to x 0.270 y 0.100 z 0.280 m",
        "home: moved to x 0.250 y 0.100 z 0.300 m",
    ]
    assert lines[3].startswith("square: a joint move") and lines[4].startswith("saved ")
    with Image.open(path) as gif:
        assert gif.n_frames > 1
