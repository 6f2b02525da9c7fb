"""urkin.plot: the building blocks and the course's figures draw, label and lay out well."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest
from mpl_toolkits.mplot3d import proj3d

import urkin
import urkin.plot as P
from urkin.course.lab import lab_robot
from urkin.transforms import make_transform, rot_x, rot_z

UR3 = urkin.robot("UR3")
UR5 = urkin.robot("UR5")
HOME = np.array([0.0, -np.pi / 2, 0.0, -np.pi / 2, 0.0, 0.0])
NOTE = "drawn in the base frame {0}, lengths in metres"


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


# ---------------------------------------------------------------------------------------------
# what every figure must do
# ---------------------------------------------------------------------------------------------


def _axes3d(fig):
    return [ax for ax in fig.axes if ax.name == "3d"]


def _x_reads_left_to_right(ax) -> bool:
    """Whether x grows to the right on screen along the front of the 3D box."""
    (x0, x1), (y0, _), (z0, _) = ax.get_xlim(), ax.get_ylim(), ax.get_zlim()
    screen = [proj3d.proj_transform(x, y0, z0, ax.get_proj())[0] for x in (x0, x1)]
    return screen[1] > screen[0]


def _check_3d(ax, *, note: bool = True) -> None:
    """Labelled in metres, equal scales, z label upright, x not mirrored, frame stated."""
    assert (ax.get_xlabel(), ax.get_ylabel(), ax.get_zlabel()) == ("x (m)", "y (m)", "z (m)")
    assert ax.zaxis.get_rotate_label("z (m)") is False
    assert ax.zaxis.label.get_rotation() == 90.0  # reads upwards, whatever the view
    spans = [np.ptp(lim) for lim in (ax.get_xlim(), ax.get_ylim(), ax.get_zlim())]
    assert np.allclose(spans, spans[0])
    assert np.allclose(ax.get_box_aspect() / ax.get_box_aspect()[0], 1.0)
    assert _x_reads_left_to_right(ax)
    if note:
        assert "drawn in the" in ax._urkin_frame_note.get_text()


def _overlapping_text(fig) -> list[str]:
    """Pairs of titles, axis labels and tick labels whose boxes overlap, across axes."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    boxes = []
    for index, ax in enumerate(fig.axes):
        axes = [ax.xaxis, ax.yaxis] + ([ax.zaxis] if ax.name == "3d" else [])
        texts = [ax.title] + [axis.label for axis in axes]
        for axis in axes:
            low, high = sorted(axis.get_view_interval())
            shown = [tick for tick in axis.get_major_ticks() if low <= tick.get_loc() <= high]
            texts += [tick.label1 for tick in shown] + [tick.label2 for tick in shown]
        for text in texts:
            if text.get_visible() and text.get_text():
                boxes.append((index, text.get_text(), text.get_window_extent(renderer)))
    if fig._suptitle is not None:
        boxes.append((-1, fig._suptitle.get_text(), fig._suptitle.get_window_extent(renderer)))
    clashes = []
    for i, (axes_a, name_a, box_a) in enumerate(boxes):
        for axes_b, name_b, box_b in boxes[i + 1 :]:
            if axes_a != axes_b and box_a.overlaps(box_b):
                clashes.append(f"{name_a!r} / {name_b!r}")
    return clashes


def _suptitle_gap(fig) -> float:
    """Pixels between the figure's title and the highest panel title below it."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    top = fig._suptitle.get_window_extent(renderer).y0
    return min(top - ax.title.get_window_extent(renderer).y1 for ax in fig.axes if ax.get_title())


def _check_big_enough(fig, inches: float = 5.0) -> None:
    """Every 3D axes that shows an arm gets a panel of at least `inches` across, after layout."""
    fig.canvas.draw()
    width, height = fig.get_size_inches()
    for ax in _axes3d(fig):
        box = ax.get_position()
        assert min(box.width * width, box.height * height) >= inches


# ---------------------------------------------------------------------------------------------
# building blocks
# ---------------------------------------------------------------------------------------------


def test_axes3d_is_labelled_upright_and_equal():
    ax = P.axes3d(center=(0.1, 0.2, 0.3), half_width=0.4, title="t", frame="table frame")
    _check_3d(ax)
    assert ax.get_title() == "t"
    assert ax._urkin_frame_note.get_text() == "drawn in the table frame, lengths in metres"
    ax.figure.canvas.draw()
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        shown = [t for t in axis.get_majorticklocs() if -0.11 <= t - 0.3 <= 0.81]
        assert len(shown) <= 7, "too many ticks: their labels run into each other"


def test_axes3d_view_is_applied_and_z_label_stays_upright():
    ax = P.axes3d(view=(15.0, -115.0))
    assert (ax.elev, ax.azim) == (15.0, -115.0)
    ax.figure.canvas.draw()
    assert ax.zaxis.label.get_rotation() == 90.0


def test_frame_note_is_written_once_and_replaced():
    ax = P.axes3d()
    first = P.frame_note(ax, "base frame {0}")
    second = P.frame_note(ax, "table frame")
    assert first is second
    notes = [t for t in ax.texts if "drawn in the" in t.get_text()]
    assert len(notes) == 1 and "table frame" in notes[0].get_text()
    _x, y = notes[0].get_position()
    assert y < 0.0  # below the axes: clear of the axis labels in any view


def test_draw_frame_draws_three_axes_in_rgb():
    ax = P.axes3d()
    artists = P.draw_frame(ax, make_transform(rot_z(0.3), [0.1, 0.0, 0.2]), 0.1, label="f")
    lines = [a for a in artists if hasattr(a, "get_color") and hasattr(a, "get_xdata")]
    assert [line.get_color() for line in lines] == list(P.AXIS_COLOURS)
    assert sum(1 for a in artists if hasattr(a, "get_text")) == 1


def test_draw_reference_axes_are_grey_and_dashed():
    ax = P.axes3d(center=(0.0, 0.0, 0.0), half_width=1.0)
    artists = P.draw_reference_axes(ax)
    lines = artists[0::2]
    assert all(line.get_linestyle() == "--" for line in lines)
    assert [t.get_text() for t in artists[1::2]] == ["X", "Y", "Z"]
    assert lines[0].get_label() == "fixed axes"


def test_draw_robot_scales_its_frame_arrows_to_the_arm_and_notes_the_frame():
    for robot in (UR3, urkin.robot("UR10")):
        ax = P.axes3d()
        artists = P.draw_robot(ax, robot, HOME)
        assert len(artists) == 1 + 7 * 3  # the links, and a triad per frame
        arrow = artists[1]
        length = np.linalg.norm(np.diff(np.array(arrow.get_data_3d()), axis=1))
        reach = abs(robot.a2) + abs(robot.a3) + robot.d4 + robot.d6
        assert length == pytest.approx(0.125 * reach)
        assert ax._urkin_frame_note.get_text() == NOTE


def test_draw_robot_keeps_a_note_it_was_given_and_can_leave_it_out():
    ax = P.axes3d(frame="table frame")
    P.draw_robot(ax, UR3, HOME, frames=False)
    assert "table frame" in ax._urkin_frame_note.get_text()
    ax = P.axes3d()
    P.draw_robot(ax, UR3, HOME, frames=False, frame=False)
    assert getattr(ax, "_urkin_frame_note", None) is None


def test_draw_robot_names_the_world_frame_of_a_placed_robot():
    ax = P.axes3d()
    P.draw_robot(ax, lab_robot(), HOME, frames=False)
    assert "world frame" in ax._urkin_frame_note.get_text()


def test_draw_robot_rejects_a_batch():
    with pytest.raises(ValueError, match="one configuration"):
        P.draw_robot(P.axes3d(), UR3, np.zeros((2, 6)))


def test_draw_arms_labels_each_arm():
    ax = P.axes3d()
    P.draw_arms(ax, UR3, [(HOME, "tab:blue", "home"), (np.zeros(6), "tab:red", "zero")])
    labels = [line.get_label() for line in ax.get_lines()]
    assert "home" in labels and "zero" in labels


def test_draw_ellipsoid_arms_puts_each_ellipsoid_at_its_flange():
    ax = P.axes3d()
    qs = np.array([HOME, np.full(6, 0.3)])
    artists = P.draw_ellipsoid_arms(ax, UR5, qs, np.stack([np.eye(3)] * 2), scale=0.1)
    surfaces = artists[0::2]
    assert len(surfaces) == 2
    centres = urkin.fk(UR5, qs)[:, :3, 3]
    for surface, centre in zip(surfaces, centres):
        faces = np.asarray(surface._faces)[..., :3].reshape(-1, 3)  # matplotlib's 3D vertices
        assert np.allclose(0.5 * (faces.min(axis=0) + faces.max(axis=0)), centre, atol=2e-3)
        assert np.allclose(np.ptp(faces, axis=0), 0.2, atol=1e-3)  # semi-axes 1 × scale 0.1


def test_draw_angle_arc_spans_the_angle():
    _fig, ax = plt.subplots()
    arc, text = P.draw_angle_arc(ax, (0.0, 0.0), 1.0, 0.5, 0.1, "θ", "tab:blue")
    assert (arc.theta1, arc.theta2) == pytest.approx(np.degrees([0.1, 0.5]))
    assert np.hypot(*text.get_position()) == pytest.approx(1.25)


def test_show_robot_has_a_pose_panel_and_a_frame_note():
    ax = P.show_robot(UR3, HOME)
    _check_3d(ax)
    assert any(t.get_text().startswith("position (m)") for t in ax.texts)
    assert P.pose_text(urkin.fk(UR3, HOME)) in [t.get_text() for t in ax.texts]


# ---------------------------------------------------------------------------------------------
# lesson 00 and 01
# ---------------------------------------------------------------------------------------------


def test_robot_panels_share_a_cube_fitted_to_the_arms():
    configurations = [(np.zeros(6), "zero"), (HOME, "home")]
    fig = P.robot_panels(UR3, configurations, title="two")
    axes = _axes3d(fig)
    assert [ax.get_title() for ax in axes] == ["zero", "home"]
    assert fig.get_suptitle() == "two"
    for ax in axes:
        _check_3d(ax)
        assert ax.get_xlim() == axes[0].get_xlim() and ax.get_zlim() == axes[0].get_zlim()
    reach = abs(UR3.a2) + abs(UR3.a3) + UR3.d4 + UR3.d6
    assert np.ptp(axes[0].get_xlim()) < 1.5 * reach  # tighter than the any-configuration cube
    points = np.concatenate([urkin.fk_frames(UR3, q)[:, :3, 3] for q, _ in configurations])
    for dim, lim in enumerate((axes[0].get_xlim(), axes[0].get_ylim(), axes[0].get_zlim())):
        assert lim[0] < points[:, dim].min() and points[:, dim].max() < lim[1]
    _check_big_enough(fig)
    assert not _overlapping_text(fig)
    assert _suptitle_gap(fig) >= 15  # not crowding the panel titles


def test_rotation_steps_figure_draws_each_step():
    rows = [[("start", np.eye(3)), ("turned", rot_z(np.pi / 2))], [("x", rot_x(0.3))]]
    fig = P.rotation_steps_figure(rows, title="order")
    axes = _axes3d(fig)
    assert [ax.get_title() for ax in axes] == ["start", "turned", "x"]
    assert axes[0].get_legend() is not None
    for ax in axes:
        _check_3d(ax, note=False)
        letters = sorted(t.get_text() for t in ax.texts)
        assert letters == ["X", "Y", "Z", "x", "y", "z"]
    assert not _overlapping_text(fig)


# ---------------------------------------------------------------------------------------------
# lesson 04
# ---------------------------------------------------------------------------------------------


def _jacobian_columns():
    frames = urkin.fk_frames(UR5, np.array([0.3, -1.2, 1.4, -0.6, 1.1, 0.2]))
    velocities = np.cross(frames[:6, :3, 2], frames[6, :3, 3] - frames[:6, :3, 3])
    return frames, velocities


def test_jacobian_columns_figure_draws_every_column():
    frames, velocities = _jacobian_columns()
    fig = P.jacobian_columns_figure(frames, velocities, scale=0.3, title="columns")
    (ax,) = _axes3d(fig)
    _check_3d(ax)
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    assert texts[1:7] == [f"joint {i + 1}: axis z{i} through p{i}" for i in range(6)]
    assert "0.3 m per m/s" in texts[-1]
    arrows = [c for c in ax.collections if type(c).__name__ == "Line3DCollection"]
    assert len(arrows) == 6
    _check_big_enough(fig)


def test_entry_error_maps_write_every_entry():
    errors = np.array([[0.1634, 0.0], [0.0, 0.0785]])
    fig = P.entry_error_maps(
        [(errors, "a"), (0 * errors, "b")],
        row_labels=["p", "q"],
        column_labels=["1", "2"],
        xlabel="col",
        ylabel="row",
        colorbar_label="mm/rad",
        factor=1000.0,
        title="maps",
    )
    left, _right, colorbar = fig.axes
    assert [t.get_text() for t in left.texts] == ["163.4", "0.0", "0.0", "78.5"]
    assert left.texts[0].get_color() == "white" and left.texts[1].get_color() == "black"
    assert colorbar.get_ylabel() == "mm/rad"
    assert not _overlapping_text(fig)


def test_step_size_figure_draws_methods_slopes_and_eps():
    h = np.logspace(-16, -1, 16)
    errors = {"forward differences": h + 1e-16 / h, "complex step": 0 * h}
    fig = P.step_size_figure(h, errors, floor=1e-18, title="steps")
    (ax,) = fig.axes
    assert len(ax.get_lines()) == 2 + 3 + 1
    assert np.all(ax.get_lines()[1].get_ydata() == 1e-18)  # exact zeros drawn at the floor
    assert ax.get_ylim()[0] == pytest.approx(1e-18 / 3)


@pytest.fixture(scope="module")
def families():
    reach = UR5.a2 * np.cos(-1.0) + UR5.a3 * np.cos(-2.0)
    return {
        "shoulder": np.array([0.3, -1.0, -1.0, np.arcsin(-reach / UR5.d5) + 2.0, 1.0, 0.4]),
        "elbow": np.array([0.3, -0.9, 0.0, -1.2, 1.1, 0.4]),
        "wrist": np.array([0.3, -1.3, 1.6, -0.8, 0.0, 0.4]),
    }


def test_singular_families_are_not_mirrored(families):
    conditions = {"shoulder": "c2", "elbow": "sin q3 = 0", "wrist": "sin q5 = 0"}
    fig = P.singular_families_figure(UR5, families, conditions=conditions, title="families")
    axes = _axes3d(fig)
    assert [ax.get_title() for ax in axes] == [
        "shoulder: c2",
        "elbow: sin q3 = 0",
        "wrist: sin q5 = 0",
    ]
    for ax in axes:
        _check_3d(ax)
        assert ax.get_legend() is not None
        assert -180.0 < ax.azim < 0.0
    shoulder = [t.get_text() for t in axes[0].get_legend().get_texts()]
    assert f"{UR5.d4:.3f} m" in shoulder[-1]
    _check_big_enough(fig)
    assert not _overlapping_text(fig)


def test_singular_families_rejects_an_unknown_family():
    with pytest.raises(ValueError, match="unknown singular families"):
        P.singular_families_figure(UR5, {"knee": np.zeros(6)})


def _path():
    s = np.linspace(0.0, 1.0, 21)
    path = np.zeros((21, 6))
    path[:, 1] = -0.6
    path[:, 2] = -1.6 * (1.0 - s)
    path[:, 3] = -np.pi / 2 - path[:, 1] - path[:, 2]
    path[:, 4] = np.pi / 2
    J = urkin.jacobian(UR5, path)[:, :3, :]
    U, sigma, _ = np.linalg.svd(J)
    return s, path, U, sigma


def test_manipulability_figure_draws_arms_and_measures():
    s, path, U, sigma = _path()
    shown = [0, 10, 20]
    kappa = urkin.kinematics.condition_number(UR5, path)
    fig = P.manipulability_figure(
        UR5,
        path[shown],
        U[shown] * sigma[shown, None, :],
        ["a", "b", "c"],
        s=s,
        manipulability={"w": np.prod(sigma, axis=1)},
        semi_axes=sigma,
        condition=kappa,
        scale=0.15,
        center=(-0.4, -0.1, 0.45),
        half_width=0.5,
        title="approach",
    )
    ax3, _top, middle, bottom = fig.axes
    _check_3d(ax3)
    assert [t.get_text() for t in ax3.get_legend().get_texts()] == ["a", "b", "c"]
    assert len(middle.get_lines()) == 3
    assert bottom.get_yscale() == "log"
    assert any("∞" in t.get_text() for t in bottom.texts)  # κ is singular at the end
    assert np.all(np.isfinite(bottom.get_lines()[0].get_ydata()))
    _check_big_enough(fig)
    assert not _overlapping_text(fig)


def test_ellipsoid_panels_draw_the_same_arms_with_their_own_ellipsoids():
    _s, path, U, sigma = _path()
    shown = [0, 10]
    panels = [
        ("velocity", U[shown] * sigma[shown, None, :], 0.15),
        ("force", U[shown] / sigma[shown, None, :], 0.03),
    ]
    fig = P.ellipsoid_panels(
        UR5, path[shown], panels, labels=["a", "b"], center=(-0.4, -0.1, 0.45), half_width=0.5
    )
    axes = _axes3d(fig)
    assert [ax.get_title() for ax in axes] == ["velocity", "force"]
    for ax in axes:
        _check_3d(ax)
        assert sum(type(c).__name__ == "Poly3DCollection" for c in ax.collections) == 2
    _check_big_enough(fig)


# ---------------------------------------------------------------------------------------------
# lesson 05
# ---------------------------------------------------------------------------------------------


def _square():
    corners = np.array([[0.3, 0.2, 0.2], [0.5, 0.2, 0.2], [0.5, 0.4, 0.2], [0.3, 0.4, 0.2]])
    return np.vstack([corners, corners[:1]])


def test_square_traces_figure_keeps_the_prediction_apart_from_the_curves():
    square = _square()
    misses = [(np.zeros(5), "exact", "tab:blue"), (np.full(5, 130.0), "solved", "tab:purple")]
    fig = P.square_traces_figure(
        square,
        [(square, "flange", "tab:blue", "-")],
        misses,
        prediction=(np.full(5, 130.0), "prediction"),
        limit=(165.0, "largest"),
        origin_note="base",
        title="square",
    )
    top, along = fig.axes
    assert top.get_aspect() == 1.0
    assert top.get_xlim()[0] < top.get_xlim()[1]
    legend = {t.get_text() for t in along.get_legend().get_texts()}
    assert {"exact", "solved", "prediction", "largest"} <= legend
    markers = [line for line in along.get_lines() if line.get_marker() == "o"]
    (prediction,) = markers
    curves = [line.get_color() for line in along.get_lines() if line.get_linestyle() == "-"]
    assert prediction.get_color() not in curves
    assert not _overlapping_text(fig)


def test_square_traces_figure_refuses_a_prediction_in_a_curve_colour():
    with pytest.raises(ValueError, match="colour"):
        P.square_traces_figure(
            _square(),
            [],
            [(np.zeros(5), "solved", "tab:red")],
            prediction=(np.zeros(5), "prediction"),
        )


def test_arms_figure_panels_target_floor_and_legends():
    panels = [
        ("true", [(HOME, "tab:blue", "a"), (np.zeros(6), "tab:red", "b")]),
        ("formula", [(HOME, "tab:blue", "c")]),
    ]
    fig = P.arms_figure(
        UR3,
        panels,
        center=(0.0, 0.0, 0.3),
        half_width=0.5,
        target=(0.2, 0.1, 0.1),
        target_label="corner",
        title="arms",
    )
    axes = _axes3d(fig)
    assert [ax.get_title() for ax in axes] == ["true", "formula"]
    for ax in axes:
        _check_3d(ax)
        legend = [t.get_text() for t in ax.get_legend().get_texts()]
        assert "corner" in legend and "the plane the robot stands on, z = 0" in legend
    _check_big_enough(fig)
    assert not _overlapping_text(fig)
    assert _suptitle_gap(fig) >= 15  # not crowding the panel titles


def test_arms_figure_with_many_panels_states_the_frame_once():
    T = urkin.fk(UR5, np.array([0.3, -1.2, 1.4, -0.6, 1.1, 0.5]))
    solutions = urkin.ik_analytic(UR5, T)
    assert len(solutions) == 8
    panels = [(f"row {row}", [(q, "0.35", "arm")]) for row, q in enumerate(solutions)]
    fig = P.arms_figure(
        UR5,
        panels,
        center=(-0.29, -0.19, 0.2),
        half_width=0.5,
        pose=T,
        target=T[:3, 3],
        columns=4,
        size=5.2,
        legend="first",
        view=(15, -65),
        title="eight",
    )
    axes = _axes3d(fig)
    assert len(axes) == 8
    assert axes[0].get_legend() is not None and axes[1].get_legend() is None
    assert fig.get_supxlabel() == "every panel drawn in the " + NOTE.removeprefix("drawn in the ")
    for ax in axes:
        _check_3d(ax, note=False)
        assert getattr(ax, "_urkin_frame_note", None) is None
    assert not _overlapping_text(fig)


def test_convergence_figure_draws_every_run():
    run = {"position": np.array([1.0, 1e-4, 0.0]), "angle": np.array([1.0, 1e-5, 0.0])}
    fig = P.convergence_figure(
        [run, run],
        [(run, "fresh", "tab:orange"), (run, "frozen", "tab:brown")],
        floor=1e-17,
        titles=("left", "right"),
        title="convergence",
    )
    left, right = fig.axes
    assert (left.get_title(), right.get_title()) == ("left", "right")
    assert left.get_yscale() == "log" and "1e-17" in left.get_ylabel()
    assert len(right.get_lines()) == 4
    assert not _overlapping_text(fig)


def test_solver_runs_figure_draws_what_the_solver_sees():
    run = {"position": np.ones(6), "angle": np.ones(6), "step": np.ones(5), "seen": np.zeros(6)}
    fig = P.solver_runs_figure(
        {"log": (run, "tab:blue"), "cross": (run, "tab:red")},
        floor=1e-17,
        seen="cross",
        title="runs",
    )
    _left, middle, right = fig.axes
    assert len(middle.get_lines()) == 3
    assert any("step limit" in t.get_text() for t in right.get_legend().get_texts())
    assert not _overlapping_text(fig)


# ---------------------------------------------------------------------------------------------
# lesson 07
# ---------------------------------------------------------------------------------------------


def test_lab_scene_is_drawn_in_the_table_frame():
    lab = lab_robot()
    q = urkin.course.ik_lab(0.0, 0.4, 0.05, 1.75)
    T = urkin.fk(lab, q)
    fig = P.lab_scene(
        lab,
        q,
        frames=[(np.eye(4), "table", 0.08), (T, "gripper", 0.06)],
        gripper=np.array([urkin.fk_frames(lab, q)[-1, :3, 3], T[:3, 3]]),
        target=T[:3, 3],
        table=((-0.31, 0.21), (-0.04, 0.48)),
        center=(-0.05, 0.22, 0.17),
        half_width=0.26,
        title="lab",
    )
    (ax,) = _axes3d(fig)
    _check_3d(ax)
    assert "table frame" in ax._urkin_frame_note.get_text()
    assert {"table", "gripper"} <= {t.get_text().strip() for t in ax.texts}
    _check_big_enough(fig)


def test_lab_top_view_draws_the_angles():
    fig = P.lab_top_view(
        np.array([[0.0, 0.0], [0.13, 0.06], [0.16, 0.2]]),
        (0.16, 0.2),
        (0.15, 0.25),
        theta1=0.44,
        yaw=1.75,
        offset=0.11,
        title="top",
    )
    (ax,) = fig.axes
    assert {"θ1", "θB", "θc", "ψ"} <= {t.get_text() for t in ax.texts}
    assert ax.get_aspect() == 1.0
    assert "base frame" in ax.get_xlabel() and "base frame" in ax.get_ylabel()
    assert ax.get_xlim()[0] < ax.get_xlim()[1]


def _side():
    return np.array(
        [[0, 0], [0, 0.152], [0.08, 0.38], [0.145, 0.18], [0.145, 0.18], [0.23, 0.18], [0.23, 0.1]],
        dtype=float,
    )


def test_lab_side_view_marks_r_h_and_the_angles():
    fig = P.lab_side_view(
        _side(),
        cup_height=0.04,
        table_height=-0.01,
        theta2=-1.24,
        theta3=2.49,
        offset=0.11,
        title="side",
    )
    (ax,) = fig.axes
    texts = {t.get_text() for t in ax.texts}
    assert {"r", "h", "−θ2", "θ3", "−θ4"} <= texts
    assert ax.get_legend() is not None
    assert not _overlapping_text(fig)


def test_lab_elbows_figure_draws_the_ring_and_both_elbows():
    side = _side()
    other = np.array([side[1], [0.16, -0.03], side[3]])
    fig = P.lab_elbows_figure(
        side,
        [(side[1:4], "lab", "0.3"), (other, "other", "tab:red")],
        lengths=(0.244, 0.213),
        table_height=-0.01,
        title="elbows",
    )
    (ax,) = fig.axes
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert legend[0].startswith("reachable ring for wrist 1: 0.031 m")
    assert "lab" in legend and "other" in legend


def test_error_maps_figure_colours_missing_and_invalid_cells():
    xs, ys = np.linspace(-1, 1, 9), np.linspace(-1, 1, 7)
    gx, gy = np.meshgrid(xs, ys)
    errors = np.where(gx < 0, np.nan, 1e-15)
    fig = P.error_maps_figure(
        xs,
        ys,
        [(errors, "left"), (0 * errors, "right")],
        valid=np.hypot(gx, gy) < 1.0,
        floor=1e-16,
        contours=[(gx, "white", "--", "x = 0")],
        marker=((0, 0), "base"),
        title="maps",
    )
    left, right, _colorbar = fig.axes
    assert (left.get_title(), right.get_title()) == ("left", "right")
    assert left.get_aspect() == 1.0
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert labels == ["out of reach", "reachable, but no answer (NaN)", "x = 0", "base"]
    assert not _overlapping_text(fig)


def test_joint_paths_figure_highlights_one_joint():
    s = np.linspace(0, 1, 11)
    q = np.outer(s, np.arange(6))
    fig = P.joint_paths_figure(s, [(q, "a"), (q, "b")], title="paths")
    left, _right = fig.axes
    widths = [line.get_linewidth() for line in left.get_lines()[:6]]
    assert widths[5] > max(widths[:5])
    assert left.get_ylabel() == "joint angle (rad)"
    assert not _overlapping_text(fig)


# ---------------------------------------------------------------------------------------------
# lesson 09: spheres, scenes, edges, configuration spaces
# ---------------------------------------------------------------------------------------------


def _cell():
    from urkin import planning

    return planning.Scene(
        boxes=[
            planning.Box([0.0, 0.0, -0.03], [3.0, 3.0, 0.05], name="table"),
            planning.Box([0.3, 0.0, 0.1], [0.1, 0.3, 0.2], rot_z(0.4), name="crate"),
        ],
        cylinders=[planning.Cylinder([0.0, 0.3, 0.2], [0, 0, 1], 0.02, 0.3, name="post")],
        spheres=[planning.Sphere([0.0, -0.3, 0.3], 0.04)],
        capsules=[planning.Capsule([-0.2, 0.2, 0.4], [-0.2, -0.2, 0.4], 0.02)],
    )


def test_draw_scene_cuts_unrotated_boxes_to_the_view_and_highlights_by_name():
    ax = P.axes3d(center=(0.0, 0.0, 0.2), half_width=0.5)
    artists = P.draw_scene(ax, _cell(), highlight={"crate": "tab:red"})
    assert len(artists) == 1 + 1 + 1 + 1 + 3 + 1  # 2 boxes, a cylinder, a ball, a capsule, legend
    crate = artists[1]
    assert np.allclose(crate.get_facecolor()[0][:3], matplotlib.colors.to_rgb("tab:red"))
    assert artists[-1].get_label() == "obstacles"
    far = P.axes3d(center=(5.0, 5.0, 5.0), half_width=0.1)
    assert len(P.draw_scene(far, _cell(), label=None)) == 6  # the table is wholly outside
    assert len(P.draw_scene(far, _cell(), label=None, clip=False)) == 7


def test_draw_spheres_colours_each_ball():
    ax = P.axes3d()
    surfaces = P.draw_spheres(ax, np.zeros((3, 3)), [0.1, 0.2, 0.3], color=["r", "g", "b"])
    assert len(surfaces) == 3
    with pytest.raises(ValueError, match="one colour or one per ball"):
        P.draw_spheres(ax, np.zeros((3, 3)), 0.1, color=["r", "g"])


def test_sphere_models_figure_panels_share_a_cube_and_mark_touching_spheres():
    from urkin import planning

    model = planning.sphere_model(UR3)
    q = np.array([0.4, -1.0, 1.3, -1.9, -1.57, 0.0])
    hit = np.zeros(len(model), dtype=bool)
    hit[3] = True
    fig = P.sphere_models_figure(
        UR3,
        [
            (q, model.place(q), model.radii, "one", None),
            (HOME, model.place(HOME), model.radii, "two", hit),
        ],
        scene=_cell(),
        title="models",
    )
    axes = _axes3d(fig)
    assert [ax.get_title() for ax in axes] == ["one", "two"]
    assert axes[0].get_xlim() == axes[1].get_xlim()
    for ax in axes:
        _check_3d(ax)
    labels = [t.get_text() for t in axes[0].get_legend().get_texts()]
    assert labels == ["obstacles", "spheres", "spheres touching an obstacle"]
    with pytest.raises(ValueError, match="at least one"):
        P.sphere_models_figure(UR3, [])


def test_signed_distance_figure_marks_the_surface_and_the_balls():
    x = np.linspace(-1, 1, 41)
    y = np.linspace(-0.5, 0.5, 21)
    d = np.hypot(*np.meshgrid(x, y)) - 0.3
    fig = P.signed_distance_figure(
        x, y, d, outline=[[-0.3, 0], [0, 0.3], [0.3, 0]], circles=[((0.6, 0.0), 0.1, "d = +200 mm")]
    )
    ax, bar = fig.axes
    assert bar.get_ylabel() == "signed distance (mm)"
    assert "d = +200 mm" in [t.get_text() for t in ax.texts]
    assert set(bar.get_yticks()) >= {-300.0, 0.0, 300.0}  # whole hundreds of millimetres
    with pytest.raises(ValueError, match="distance must have shape"):
        P.signed_distance_figure(x, y, d.T)


def test_edge_clearance_figure_shades_the_collision_and_counts_the_samples():
    t = np.linspace(0, 1, 101)
    fig = P.edge_clearance_figure(t, 0.05 - 0.1 * np.sin(np.pi * t), samples=np.linspace(0, 1, 7))
    (ax,) = fig.axes
    labels = [text.get_text() for text in ax.get_legend().get_texts()]
    assert "in collision" in labels and "samples of the edge check (7)" in labels
    assert ax.get_ylim()[0] < -50.0  # the dip is in view, in millimetres
    assert not _overlapping_text(fig)


def test_cspace_figure_draws_trees_paths_and_counts():
    x = np.linspace(-3, 3, 31)
    y = np.linspace(-2, 2, 21)
    free = np.hypot(*np.meshgrid(x, y)) > 1
    tree = (
        np.array([[-2.0, 0.0], [-1.5, 1.5], [-1.0, 1.8]]),
        np.array([-1, 0, 1]),
        "tab:blue",
        "start tree",
    )
    path = np.array([[-2.0, 0.0], [0.0, 1.9], [2.0, 0.0]])
    fig = P.cspace_figure(
        x,
        y,
        free,
        [([tree], None, "a"), ([tree], path, "b")],
        start=(-2, 0),
        goal=(2, 0),
        title="searches",
    )
    left, right = fig.axes
    assert (left.get_title(), right.get_title()) == ("a", "b")
    assert "start tree (3)" in [t.get_text() for t in left.get_legend().get_texts()]
    assert "path found" in [t.get_text() for t in right.get_legend().get_texts()]
    assert len(left.collections[1].get_segments()) == 2  # a root and two children
    with pytest.raises(ValueError, match="free must have shape"):
        P.cspace_figure(x, y, free.T, [([tree], None, "a")])


def test_animate_plan_draws_the_scene_in_every_frame_around_the_arm():
    qs = np.linspace([0.5, -1.2, 1.2, -1.5, -1.57, 0], [-0.5, -1.2, 1.2, -1.5, -1.57, 0], 4)
    anim = P.animate_plan(UR3, qs, _cell(), max_frames=2, figsize=(3.0, 3.0))
    bare = P.animate(UR3, qs, max_frames=2, figsize=(3.0, 3.0))
    assert anim.frames.tolist() == [0, 3]
    assert anim.images[0] != bare.images[0]  # the obstacles are in the picture
