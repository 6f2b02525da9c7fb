"""The arm in motion: a self-contained HTML player, a keyframe strip and an animated GIF.

:func:`animate` draws a motion ``qs`` (M, 6) as at most ``max_frames`` pictures of the arm
(stick figure, tool triad, the path traced so far, the pose panel), encodes them as PNG and
wraps them in one HTML fragment with a play/pause button and a slider.  The fragment needs
nothing from another host (no script library, no font, no URL): it plays inline in JupyterLab
and in the static docs, and several players on one page do not interfere.  No video codec is
used; :meth:`Animation.save_gif` writes the same frames as an animated GIF with Pillow.

Apart from the base64 pictures, the HTML depends only on the number of samples and frames,
the frame rate, the figure's width and the robot's name: no position, angle or size measured
at run time is written in it, and the player's id is ``urkin-anim-<counter>`` (the same for
the same sequence of calls in a session).  Notebook comparisons can mask ``base64,…`` and
compare the rest.

Imports matplotlib and Pillow (not imported by ``import urkin``); :mod:`urkin.plot` exposes
:func:`animate` and :class:`Animation` too.
"""

from __future__ import annotations

import base64
import html as html_lib
import io
import itertools
import json
import math
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from numpy.typing import ArrayLike
from PIL import Image

from urkin._inputs import real
from urkin.kinematics import check_joints, fk, fk_frames
from urkin.robots import Robot, check_robot

__all__ = ["Animation", "animate"]

#: Resolution of the frames when they fit the byte budget (a 7-inch figure: 560 pixels).
DEFAULT_DPI = 80.0
#: The lowest resolution tried before a byte budget is declared impossible.
MIN_DPI = 16.0
#: Colours of the shared palette when frames are palette-quantized, largest first.
PALETTES = (256, 64, 16)

_ids = itertools.count(1)


# ---------------------------------------------------------------------------------------------
# the record
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False, repr=False)
class Animation:
    """A rendered motion of an arm: its frames, the HTML player and what they show.

    Made by :func:`animate`.  In a notebook it displays as the player (``text/html``), with
    a keyframe strip (``image/png``) for renderers that do not run scripts.

    Attributes
    ----------
    robot_name : str
        The arm's name.
    samples : int
        M, the number of configurations given.
    frames : ndarray of int, shape (F,)
        The sample indices drawn, F ≤ ``max_frames``, first and last sample included.
    html : str
        The player: one self-contained ``<div>`` (style, frames as ``data:`` URIs, script).
    images : tuple of bytes
        The PNG of each frame.
    trace : ndarray, shape (M, 3)
        The tool positions (the flange unless the robot has a tool) of every sample, metres,
        as drawn by the trace line at the last frame.
    fps : float
        Frames per second of the player.
    dpi : float
        Resolution the frames were rendered at (lowered to fit ``max_bytes``).
    colors : int
        Size of the frames' shared palette.
    """

    robot_name: str
    samples: int
    frames: np.ndarray
    html: str = field(repr=False)
    images: tuple[bytes, ...] = field(repr=False)
    trace: np.ndarray = field(repr=False)
    fps: float = 10.0
    dpi: float = DEFAULT_DPI
    colors: int = 256

    @property
    def size(self) -> int:
        """Bytes of :attr:`html` (UTF-8)."""
        return len(self.html.encode("utf-8"))

    def __repr__(self) -> str:
        frames, samples = len(self.frames), self.samples
        return (
            f"<Animation: {self.robot_name}, {frames} frame{'s' * (frames != 1)} of "
            f"{samples} sample{'s' * (samples != 1)}>"
        )

    def _pictures(self, n: int) -> list[Image.Image]:
        """``n`` frames chosen evenly (first and last included), decoded, as RGB."""
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
            raise ValueError(f"n must be a positive whole number of frames; got {n!r}")
        chosen = _spread(len(self.images), int(n))
        return [Image.open(io.BytesIO(self.images[i])).convert("RGB") for i in chosen]

    def _strip(self, n: int = 4) -> Image.Image:
        pictures = self._pictures(n)
        width, height = pictures[0].size
        strip = Image.new("RGB", (width * len(pictures), height), "white")
        for k, picture in enumerate(pictures):
            strip.paste(picture, (k * width, 0))
        return strip

    def keyframes(self, n: int = 4) -> Figure:
        """A figure with ``n`` frames side by side, the first and the last included.

        Parameters
        ----------
        n : int
            How many frames (fewer if the animation has fewer).

        Returns
        -------
        matplotlib.figure.Figure
            Not registered with pyplot; display it, or save it with ``savefig``.
        """
        pictures = self._pictures(n)
        width, height = pictures[0].size
        fig = Figure(figsize=(len(pictures) * width / self.dpi, height / self.dpi), dpi=self.dpi)
        FigureCanvasAgg(fig)
        for k, picture in enumerate(pictures):
            ax = fig.add_axes((k / len(pictures), 0.0, 1.0 / len(pictures), 1.0))
            ax.imshow(np.asarray(picture), interpolation="nearest")
            ax.set_axis_off()
        return fig

    def save_gif(self, path: str | os.PathLike, fps: float | None = None) -> Path:
        """Write the frames as an animated GIF that loops forever.

        Parameters
        ----------
        path : str or path-like
        fps : float, optional
            Frames per second (the player's by default).

        Returns
        -------
        pathlib.Path
        """
        rate = self.fps if fps is None else _rate(fps, "fps")
        pictures = [Image.open(io.BytesIO(png)) for png in self.images]  # one palette: GIF's
        target = Path(path)
        pictures[0].save(
            target,
            format="GIF",
            save_all=True,
            append_images=pictures[1:],
            duration=round(1000.0 / rate),
            loop=0,
        )
        return target

    def _repr_mimebundle_(self, include=None, exclude=None) -> dict[str, object]:
        buffer = io.BytesIO()
        self._strip().save(buffer, format="PNG", optimize=True)
        bundle = {"text/html": self.html, "image/png": buffer.getvalue(), "text/plain": repr(self)}
        if include is not None:
            bundle = {k: v for k, v in bundle.items() if k in include}
        if exclude is not None:
            bundle = {k: v for k, v in bundle.items() if k not in exclude}
        return bundle


# ---------------------------------------------------------------------------------------------
# helpers
# ---------------------------------------------------------------------------------------------


def _spread(m: int, n: int) -> np.ndarray:
    """``min(m, n)`` indices in ``0 … m-1`` spread evenly, first and last included."""
    count = min(m, n)
    # steps of (m-1)/(count-1) ≥ 1 round to distinct indices
    return np.rint(np.linspace(0.0, m - 1, count)).astype(int)


def _rate(value: object, name: str) -> float:
    rate = float(real(value, name))
    if not rate > 0:
        raise ValueError(f"{name} must be positive; got {value!r}")
    return rate


def _whole(value: object, name: str, smallest: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < smallest:
        raise ValueError(f"{name} must be a whole number ≥ {smallest}; got {value!r}")
    return int(value)


def _palette(rgbs: list[np.ndarray], colors: int) -> Image.Image:
    """One palette for all frames, from the first and the last (which shows the whole trace)."""
    sample = np.concatenate([rgbs[0], rgbs[-1]], axis=0)
    return Image.fromarray(sample).quantize(colors, method=Image.Quantize.MEDIANCUT)


def _quantize(rgb: np.ndarray, palette: Image.Image) -> Image.Image:
    return Image.fromarray(rgb).quantize(palette=palette, dither=Image.Dither.NONE)


def _png(picture: Image.Image) -> bytes:
    buffer = io.BytesIO()
    picture.save(buffer, format="PNG", compress_level=6)
    return buffer.getvalue()


def _encode(rgbs: list[np.ndarray], colors: int) -> list[bytes]:
    palette = _palette(rgbs, colors)
    return [_png(_quantize(rgb, palette)) for rgb in rgbs]


def _b64_size(n: int) -> int:
    return 4 * math.ceil(n / 3)


_STYLE = """<style>
#{id} {{ display: inline-block; max-width: 100%; margin: 0.5em 0;
  font: 13px/1.4 system-ui, -apple-system, "Segoe UI", sans-serif; color: #222; }}
#{id} > img {{ display: block; width: {width}px; max-width: 100%; height: auto;
  background: #fff; }}
#{id} > .urkin-anim-bar {{ display: flex; align-items: center; gap: 0.6em; margin-top: 0.3em; }}
#{id} > .urkin-anim-bar > button {{ min-width: 4.5em; padding: 0.15em 0.6em; }}
#{id} > .urkin-anim-bar > input {{ flex: 1; min-width: 6em; }}
#{id} > .urkin-anim-bar > span {{ font-variant-numeric: tabular-nums; white-space: nowrap; }}
</style>"""

# The script finds its player from itself (document.currentScript), or else by id among the
# players not yet started (notebook front ends that eval scripts), so that two players with
# the same id (two kernels' outputs on one page) still work.  It keeps no global state, and
# stops ticking while its player is out of the page (re-run cell, closed notebook).
_SCRIPT = """<script>
(function () {
  var id = "{id}";
  var more = [{frames}];
  var samples = [{samples}];
  var total = {total}, delay = {delay};
  var script = document.currentScript;
  var root = script && script.parentNode;
  if (!root || root.id !== id || root.getAttribute("data-started")) {
    root = null;
    var found = document.querySelectorAll('div[id="' + id + '"]');
    for (var k = found.length - 1; k >= 0 && !root; k--) {
      if (!found[k].getAttribute("data-started")) root = found[k];
    }
  }
  if (!root) return;
  root.setAttribute("data-started", "1");
  var img = root.querySelector("img");
  var button = root.querySelector("button");
  var slider = root.querySelector("input");
  var label = root.querySelector("span");
  var frames = [img.getAttribute("src")].concat(more);
  var n = frames.length, frame = 0, playing = false, timer = null, away = 0;
  function show(i) {
    frame = (i % n + n) % n;
    img.src = frames[frame];
    slider.value = frame;
    label.textContent = "frame " + (frame + 1) + " of " + n +
      ", sample " + (samples[frame] + 1) + " of " + total;
    root.setAttribute("data-frame", String(frame));
  }
  function tick() {
    timer = null;
    if (!playing) return;
    if (!root.isConnected) {
      if (++away < 600) timer = setTimeout(tick, 1000);
      return;
    }
    away = 0;
    show(frame + 1);
    timer = setTimeout(tick, delay);
  }
  function play(on) {
    playing = on;
    button.textContent = on ? "Pause" : "Play";
    button.setAttribute("aria-pressed", on ? "true" : "false");
    if (timer !== null) { clearTimeout(timer); timer = null; }
    if (on && n > 1) timer = setTimeout(tick, delay);
  }
  button.addEventListener("click", function () { play(!playing); });
  slider.addEventListener("input", function () { play(false); show(+slider.value); });
  show(0);
  play(true);
})();
</script>"""


def _html(
    anim_id: str,
    images: list[bytes],
    samples: np.ndarray,
    total: int,
    fps: float,
    alt: str,
    width: int,
) -> str:
    uris = [f"data:image/png;base64,{base64.b64encode(png).decode('ascii')}" for png in images]
    n = len(uris)
    script = (
        _SCRIPT.replace("{id}", anim_id)
        .replace("{frames}", ",".join(json.dumps(u) for u in uris[1:]))
        .replace("{samples}", ",".join(str(int(s)) for s in samples))
        .replace("{total}", str(total))
        .replace("{delay}", str(max(1, round(1000.0 / fps))))
    )
    return (
        f'<div id="{anim_id}" class="urkin-anim" data-frame="0">\n'
        + _STYLE.format(id=anim_id, width=width)
        + f'\n<img src="{uris[0]}" alt="{html_lib.escape(alt)}">\n'
        '<div class="urkin-anim-bar">'
        '<button type="button" aria-pressed="false">Play</button>'
        f'<input type="range" min="0" max="{n - 1}" step="1" value="0" aria-label="frame">'
        f"<span>frame 1 of {n}, sample {int(samples[0]) + 1} of {total}</span></div>\n"
        + script
        + "\n</div>"
    )


def _view(
    points: np.ndarray, center: ArrayLike | None, half_width: float | None
) -> tuple[np.ndarray, float]:
    """The cube shown: by default the smallest (with a margin) that holds ``points``."""
    low, high = points.min(axis=0), points.max(axis=0)
    if center is None:
        c = 0.5 * (low + high)
    else:
        c = real(center, "center")
        if c.shape != (3,):
            raise ValueError(f"center must be a point, shape (3,); got {c.shape}")
    if half_width is not None:
        return c, _rate(half_width, "half_width")
    return c, 1.08 * float(np.maximum(high - c, c - low).max())


# ---------------------------------------------------------------------------------------------
# animate
# ---------------------------------------------------------------------------------------------


def animate(
    robot: Robot,
    qs: ArrayLike,
    *,
    trace: bool = True,
    triad: bool = True,
    info: bool = True,
    targets: ArrayLike | None = None,
    title: str | None = None,
    max_frames: int = 60,
    max_bytes: int = 3_500_000,
    fps: float = 10,
    figsize: tuple[float, float] = (7.0, 7.0),
    center: ArrayLike | None = None,
    half_width: float | None = None,
    scenery: Callable[[Any], object] | None = None,
    update: Callable[[int], object] | None = None,
) -> Animation:
    """Animate the arm through the configurations ``qs``: an HTML player, inline anywhere.

    Each frame shows the stick figure, the tool's triad (x red, y green, z blue; the tool is
    the flange unless the robot has one, see :meth:`urkin.Robot.with_tool`), the path the
    tool has traced since the first sample, the pose panel (position and roll–pitch–yaw,
    see :func:`urkin.plot.pose_text`) and "sample k of M", in a view cube that stays fixed and
    holds the whole motion.  The frames are rendered once with matplotlib (Agg, no pyplot)
    and embedded as PNG ``data:`` URIs; nothing is loaded from elsewhere when the player runs.

    Parameters
    ----------
    robot : Robot
    qs : array_like, shape (M, 6) or (6,)
        Joint angles in radians, M ≥ 1 samples of the motion.
    trace : bool
        Draw the tool's positions at every sample up to the current one.
    triad : bool
        Draw the tool frame's triad.
    info : bool
        Show the pose panel.
    targets : array_like, shape (K, 3), optional
        The path the tool should follow (metres), drawn as a thin dashed grey line.
    title : str, optional
        The title (the robot's name by default).
    max_frames : int
        At most this many frames, chosen evenly over the samples by index; the first and
        the last sample are always drawn, and every sample when M ≤ ``max_frames``.
    max_bytes : int
        Budget of the HTML, bytes (:attr:`Animation.size`).  Frames share one 256-colour
        palette; if they would exceed the budget, they are rendered at lower resolutions
        (down to 16 dpi), then given fewer colours, until they fit.
    fps : float
        Frames per second of the player and of :meth:`Animation.save_gif`.
    figsize : tuple of float
        Size of a frame, inches (at 80 dpi when the budget allows).
    center, half_width : optional
        The cube shown (metres).  By default the smallest that holds the whole motion (the
        arm in every frame drawn, its base, the trace, the triads and ``targets``), with a
        margin, so the arm is drawn as large as the motion allows; with ``center`` alone, the
        half-width is chosen to hold the motion about it.
    scenery : callable, optional
        Draws what stays still in every frame (obstacles, a table): called once with the
        frames' 3D axes, after the view is set and before the arm is drawn, e.g.
        ``lambda ax: urkin.plot.draw_scene(ax, scene)``.  It does not enlarge the view cube.
    update : callable, optional
        Moves what moves besides the arm (a carried block): called before each frame is
        drawn with the index of the sample it shows (0 … M − 1), to update artists that
        ``scenery`` created.

    Returns
    -------
    Animation

    Raises
    ------
    ValueError
        If ``qs`` has the wrong shape, NaN or infinite entries, or angles too large for
        radians; if ``max_frames``, ``max_bytes``, ``fps`` or ``targets`` are invalid; or if
        no resolution fits the frames into ``max_bytes``.
    TypeError
        If ``robot`` is not a Robot, or ``qs`` is not real numbers (complex is refused).

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import urkin
    >>> qs = np.zeros((3, 6))
    >>> qs[:, 0] = [0.0, 0.5, 1.0]  # turn the base
    >>> anim = animate(urkin.robot("UR3"), qs, max_frames=3)
    >>> anim
    <Animation: UR3, 3 frames of 3 samples>
    >>> anim.frames
    array([0, 1, 2])
    >>> "data-frame" in anim.html, "http" in anim.html, anim.size < 3_500_000
    (True, False, True)
    >>> sorted(anim._repr_mimebundle_())  # a notebook shows the player (text/html)
    ['image/png', 'text/html', 'text/plain']
    >>> len(anim.keyframes(2).axes)  # a strip of the first and last frames
    2
    """
    from urkin.plot import _reach, axes3d, draw_frame, draw_robot, pose_text

    robot = check_robot(robot)
    q = check_joints(qs, "qs")
    if q.ndim == 1:
        q = q[None]
    if q.ndim != 2 or len(q) == 0:
        raise ValueError(f"qs must be joint angles of M ≥ 1 samples, shape (M, 6); got {q.shape}")
    max_frames = _whole(max_frames, "max_frames", 1)
    if isinstance(max_bytes, bool) or not isinstance(max_bytes, (int, float, np.number)):
        raise ValueError(f"max_bytes must be a number of bytes; got {max_bytes!r}")
    if not max_bytes >= 1:
        raise ValueError(f"max_bytes must be at least 1; got {max_bytes!r}")
    max_bytes = int(max_bytes)
    fps = _rate(fps, "fps")
    path = None
    if targets is not None:
        path = real(targets, "targets")
        if path.ndim != 2 or path.shape[1] != 3 or len(path) == 0:
            raise ValueError(f"targets must be points, shape (K, 3); got {path.shape}")
    m = len(q)
    chosen = _spread(m, max_frames)
    chosen.flags.writeable = False

    # the kinematics, batched: tool poses of every sample, joint origins of the drawn ones
    tools = fk(robot, q).reshape(m, 4, 4)
    positions = tools[:, :3, 3]
    joints = fk_frames(robot, q[chosen]).reshape(len(chosen), 7, 4, 4)[:, :, :3, 3]
    if not np.array_equal(robot.tool, np.eye(4)):  # the stick figure goes on to the tool's origin
        joints = np.concatenate([joints, positions[chosen, None]], axis=1)
    length = 0.16 * _reach(robot)
    tips = positions[chosen, None] + length * np.swapaxes(tools[chosen, :3, :3], 1, 2)
    shown = [joints.reshape(-1, 3), positions, tips.reshape(-1, 3)]
    if path is not None:
        shown.append(path)
    c, half = _view(np.concatenate(shown), center, half_width)

    # one figure, its artists updated frame by frame; fixed margins (a quarter inch, for the
    # notes under the cube), texts scaled down on figures smaller than 7 inches
    width_in, height_in = (float(x) for x in figsize)
    scale = min(1.0, width_in / 7.0, height_in / 7.0)
    margin = 0.25
    fig = Figure(figsize=(width_in, height_in), dpi=DEFAULT_DPI)
    canvas = FigureCanvasAgg(fig)
    ax = fig.add_axes(
        (
            margin / width_in,
            margin / height_in,
            1 - 2 * margin / width_in,
            1 - 2 * margin / height_in,
        ),
        projection="3d",
    )
    axes3d(ax, center=c, half_width=half, title=robot.name if title is None else title)
    ax.title.set_fontsize(13 * scale)
    ax.tick_params(labelsize=9 * scale)
    for label in (ax.xaxis.label, ax.yaxis.label, ax.zaxis.label):
        label.set_fontsize(10 * scale)
    if scenery is not None:
        scenery(ax)
    if path is not None:
        ax.plot(*path.T, "--", color="0.55", linewidth=1.0, label="target path")
    (trace_line,) = ax.plot(
        [], [], [], color="tab:orange", linewidth=2.5, label="tool path so far" if trace else None
    )
    trace_line.set_visible(trace)
    if trace or path is not None:
        ax.legend(loc="upper right", fontsize=9 * scale, framealpha=0.85)
    (arm,) = draw_robot(ax, robot, q[chosen[0]], frames=False, linewidth=7.0)
    arm.set_markersize(8)
    arm.set_markerfacecolor("0.15")
    axes = draw_frame(ax, tools[chosen[0]], length, linewidth=3.0, tips=True)
    for artist in axes:
        artist.set_visible(triad)
        if hasattr(artist, "set_fontsize"):
            artist.set_fontsize(12 * scale)
            artist.set_fontweight("bold")
    panel = ax.text2D(
        0.0,
        0.985,
        "",
        va="top",
        transform=ax.transAxes,
        family="monospace",
        fontsize=10.5 * scale,
        bbox={"facecolor": "white", "alpha": 0.85, "edgecolor": "0.6"},
        visible=info,
    )
    counter = ax.text2D(
        1.0,
        -0.005,
        "",
        ha="right",
        va="top",
        transform=ax.transAxes,
        fontsize=11 * scale,
        color="0.15",
    )

    def draw(j: int) -> None:
        k = chosen[j]
        arm.set_data_3d(*joints[j].T)
        trace_line.set_data_3d(*positions[: k + 1].T)
        for axis in range(3):
            line, label = axes[2 * axis], axes[2 * axis + 1]
            line.set_data_3d(*np.column_stack([positions[k], tips[j, axis]]))
            label.set_position_3d(tips[j, axis])
        panel.set_text(pose_text(tools[k]))
        counter.set_text(f"sample {k + 1} of {m}")
        if update is not None:
            update(int(k))

    ax._urkin_frame_note.set_fontsize(9 * scale)

    def render(dpi: float, which: Sequence[int]) -> list[np.ndarray]:
        """The RGB pixels of frames ``which`` at ``dpi``."""
        fig.set_dpi(dpi)
        rgbs = []
        for j in which:
            draw(j)
            canvas.draw()
            rgbs.append(np.array(canvas.buffer_rgba())[..., :3])
        return rgbs

    anim_id = f"urkin-anim-{next(_ids)}"
    width = round(figsize[0] * DEFAULT_DPI)
    empty = _html(anim_id, [b""] * len(chosen), chosen, m, fps, robot.name, width)
    skeleton = len(empty.encode("utf-8"))  # the html is this plus the frames' base64
    if skeleton >= max_bytes:
        raise ValueError(
            f"max_bytes = {max_bytes} is too small: the player alone takes {skeleton} bytes"
        )
    room = max_bytes - skeleton

    def payload(images: list[bytes]) -> int:
        return sum(_b64_size(len(png)) for png in images)

    # One shared 256-colour palette (a stick figure on white loses nothing, and the frames
    # shrink to about a third); then lower resolutions; then fewer colours.  The first and
    # last frames tell, before all are rendered, which resolution to start with.
    n = len(chosen)
    dpi, colors = DEFAULT_DPI, PALETTES[0]
    probe = render(dpi, sorted({0, n - 1}))
    estimate = payload(_encode(probe, colors)) * n / len(probe)
    if estimate > room:  # bytes grow about as the pixels: aim a little below the budget
        dpi = max(MIN_DPI, math.floor(dpi * math.sqrt(room / estimate) * 0.95))
    if dpi == DEFAULT_DPI and n > 1:  # the probe's two frames are already rendered
        rgbs = [probe[0], *render(dpi, range(1, n - 1)), probe[-1]]
    else:
        rgbs = render(dpi, range(n))
    images = _encode(rgbs, colors)
    while payload(images) > room and dpi > MIN_DPI:
        dpi = max(MIN_DPI, math.floor(dpi * math.sqrt(room / payload(images)) * 0.95))
        rgbs = render(dpi, range(n))
        images = _encode(rgbs, colors)
    for fewer in PALETTES[1:]:
        if payload(images) <= room:
            break
        colors = fewer
        images = _encode(rgbs, colors)
    if payload(images) > room:
        raise ValueError(
            f"max_bytes = {max_bytes} is too small for {n} frames: even at {MIN_DPI:g} dpi in "
            f"{colors} colours the player takes {skeleton + payload(images)} bytes; raise "
            "max_bytes or lower max_frames"
        )
    draw(n - 1)
    trace_drawn = np.column_stack(trace_line.get_data_3d())  # what the last frame shows
    html = _html(anim_id, images, chosen, m, fps, robot.name, width)
    return Animation(
        robot_name=robot.name,
        samples=m,
        frames=chosen,
        html=html,
        images=tuple(images),
        trace=trace_drawn,
        fps=fps,
        dpi=float(dpi),
        colors=colors,
    )
