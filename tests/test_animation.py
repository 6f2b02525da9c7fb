"""urkin.animation: frames chosen and rendered within budget, a self-contained HTML player that
plays (in headless Chromium) without touching the network, a keyframe strip and a GIF."""

import importlib.util
import io
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from matplotlib.figure import Figure
from PIL import Image

import urkin
from urkin import tracking, trajectory
from urkin.animation import DEFAULT_DPI, Animation, _spread, animate

UR3 = urkin.robot("UR3")
BASE64 = re.compile(r"base64,[A-Za-z0-9+/=]+")  # the nbval sanitize rule
ANIM_ID = re.compile(r"urkin-anim-\d+")


def _sanitized(html: str) -> str:
    return ANIM_ID.sub("urkin-anim-N", BASE64.sub("base64,DATA", html))


def _sweep(m: int, seed: int = 0) -> np.ndarray:
    """A smooth motion of ``m`` samples from a seeded start."""
    rng = np.random.default_rng(seed)
    start = np.array([0.3, -1.2, 1.4, -1.7, -1.5, 0.2]) + 0.1 * rng.standard_normal(6)
    return start + np.linspace(0.0, 1.0, m)[:, None] * np.array([1.2, 0.3, -0.4, 0.5, 0.6, 1.0])


@pytest.fixture(scope="module")
def circle():
    """The seed's circle: 629 samples tracked from an elbow-up start, and their targets."""
    points = trajectory.circle((0.25, 0.1, 0.3), 0.1, plane="yz").points(1e-3)
    poses = trajectory.pose_path(points, np.eye(3))
    starts = urkin.ik_analytic(UR3, poses[0])
    elbow_up = starts[np.argmax(urkin.fk_frames(UR3, starts)[:, 2, 2, 3])]
    tr = tracking.track(UR3, poses, elbow_up)
    assert tr.ok.all()
    return tr.q, points


@pytest.fixture(scope="module")
def circle_animation(circle):
    q, points = circle
    return animate(UR3, q, targets=points)


@pytest.fixture(scope="module")
def small():
    return animate(UR3, _sweep(12), max_frames=5, figsize=(3.0, 3.0))


# ---------------------------------------------------------------------------------------------
# frames
# ---------------------------------------------------------------------------------------------


def test_frames_are_spread_evenly_with_first_and_last():
    for m in (1, 2, 3, 7, 59, 60, 61, 100, 629, 10_000):
        for n in (1, 2, 3, 10, 60):
            frames = _spread(m, n)
            assert len(frames) == min(m, n)
            assert frames[0] == 0
            if n > 1:
                assert frames[-1] == m - 1
            assert np.all(np.diff(frames) >= 1)  # distinct, increasing
            if len(frames) > 2:  # even: gaps differ by at most one
                assert np.ptp(np.diff(frames)) <= 1


def test_circle_animation(circle_animation):
    anim = circle_animation
    assert isinstance(anim, Animation)
    assert (anim.robot_name, anim.samples, len(anim.frames)) == ("UR3", 629, 60)
    assert anim.frames[0] == 0 and anim.frames[-1] == 628
    assert len(anim.images) == 60
    assert repr(anim) == "<Animation: UR3, 60 frames of 629 samples>"


def test_fewer_samples_than_frames_uses_them_all(small):
    anim = animate(UR3, _sweep(4), max_frames=60, figsize=(3.0, 3.0))
    assert anim.frames.tolist() == [0, 1, 2, 3]
    assert small.frames.tolist() == [0, 3, 6, 8, 11]  # 12 samples, 5 frames


def test_one_configuration():
    anim = animate(UR3, _sweep(1)[0], figsize=(3.0, 3.0))
    assert anim.frames.tolist() == [0] and anim.samples == 1
    assert repr(anim) == "<Animation: UR3, 1 frame of 1 sample>"


@pytest.mark.parametrize(
    ("qs", "error", "match"),
    [
        (np.zeros((4, 5)), ValueError, "qs must be 6 joint angles"),
        (np.zeros((0, 6)), ValueError, "qs must be joint angles of M ≥ 1 samples"),
        (np.zeros((2, 3, 6)), ValueError, r"qs must be joint angles .* shape \(M, 6\)"),
        (np.array([[0.0, np.nan, 0, 0, 0, 0]] * 3), ValueError, "qs contains NaN"),
        (np.array([[0.0, 90.0, 0, 0, 0, 0]] * 3), ValueError, "qs has an angle of 90 rad"),
        (np.zeros((3, 6)) + 0.5j, TypeError, "qs is complex"),
        ("qs", TypeError, "qs must be numbers"),
    ],
)
def test_bad_joint_angles_are_named(qs, error, match):
    with pytest.raises(error, match=match):
        animate(UR3, qs)


@pytest.mark.parametrize("value", [0, -3, 2.5, True, "60"])
def test_bad_max_frames(value):
    with pytest.raises(ValueError, match="max_frames"):
        animate(UR3, _sweep(3), max_frames=value)


@pytest.mark.parametrize("value", [0, -1, float("nan"), None, "1e6"])
def test_bad_max_bytes(value):
    with pytest.raises(ValueError, match="max_bytes"):
        animate(UR3, _sweep(3), max_bytes=value)


def test_bad_targets_and_robot():
    with pytest.raises(ValueError, match="targets"):
        animate(UR3, _sweep(3), targets=np.zeros((4, 2)))
    with pytest.raises(TypeError, match="robot"):
        animate("UR3", _sweep(3))


# ---------------------------------------------------------------------------------------------
# the html
# ---------------------------------------------------------------------------------------------


def test_html_is_self_contained(circle_animation, small):
    for anim in (circle_animation, small):
        html = anim.html
        for banned in ("http://", "https://", "//cdn", "<link", "<iframe", "@import", "url("):
            assert banned not in html
        assert html.count("<script") == 1 and html.count("</script>") == 1
        assert html.count("<style") == 1
        assert html.startswith('<div id="urkin-anim-') and html.endswith("</div>")
        assert 'data-frame="0"' in html
        assert len(re.findall(r"data:image/png;base64,", html)) == len(anim.frames)
        assert anim.size == len(html.encode("utf-8"))


def test_html_differs_between_calls_only_in_id_and_pictures():
    first = animate(UR3, _sweep(6, seed=1), max_frames=4, figsize=(3.0, 3.0))
    second = animate(UR3, _sweep(6, seed=2), max_frames=4, figsize=(3.0, 3.0))
    ids = [ANIM_ID.search(anim.html).group() for anim in (first, second)]
    assert int(ids[1].rsplit("-", 1)[1]) == int(ids[0].rsplit("-", 1)[1]) + 1
    assert ANIM_ID.findall(first.html) == [ids[0]] * len(ANIM_ID.findall(first.html))
    # another motion, the same html once the pictures and the id are masked: nothing in it
    # depends on positions, angles or round-off
    assert _sanitized(first.html) == _sanitized(second.html)
    assert first.images != second.images


def test_mime_bundle(small):
    bundle = small._repr_mimebundle_()
    assert sorted(bundle) == ["image/png", "text/html", "text/plain"]
    assert bundle["text/html"] == small.html
    assert bundle["text/plain"] == repr(small) == "<Animation: UR3, 5 frames of 12 samples>"
    strip = Image.open(io.BytesIO(bundle["image/png"]))
    frame = Image.open(io.BytesIO(small.images[0]))
    assert strip.format == "PNG"
    assert strip.size == (4 * frame.size[0], frame.size[1])
    assert list(small._repr_mimebundle_(include={"text/plain"})) == ["text/plain"]
    assert "text/html" not in small._repr_mimebundle_(exclude={"text/html"})


def test_keyframes(small):
    fig = small.keyframes(3)
    assert isinstance(fig, Figure) and len(fig.axes) == 3
    shown = [ax.get_images()[0].get_array() for ax in fig.axes]
    for picture, index in zip(shown, (0, 2, 4)):  # first, middle and last of the 5 frames
        expected = np.asarray(Image.open(io.BytesIO(small.images[index])).convert("RGB"))
        assert np.array_equal(np.asarray(picture), expected)
    assert len(small.keyframes(10).axes) == 5
    with pytest.raises(ValueError, match="n must be"):
        small.keyframes(0)


def test_gif_loops_with_every_frame(small, tmp_path):
    path = small.save_gif(tmp_path / "arm.gif", fps=4)
    with Image.open(path) as gif:
        assert gif.format == "GIF"
        assert gif.n_frames == len(small.frames)
        assert gif.info["loop"] == 0
        assert gif.info["duration"] == 250
        assert gif.size == Image.open(io.BytesIO(small.images[0])).size


def test_frames_share_one_palette_and_make_a_gif(tmp_path):
    anim = animate(UR3, _sweep(3), figsize=(3.0, 3.0))
    assert anim.colors == 256
    palettes = {Image.open(io.BytesIO(png)).getpalette()[:48].__repr__() for png in anim.images}
    assert len(palettes) == 1 and Image.open(io.BytesIO(anim.images[0])).mode == "P"
    with Image.open(anim.save_gif(tmp_path / "three.gif")) as gif:
        assert gif.n_frames == 3 and gif.info["loop"] == 0 and gif.info["duration"] == 100


# ---------------------------------------------------------------------------------------------
# the byte budget
# ---------------------------------------------------------------------------------------------


def test_sixty_frames_of_the_circle_fit_the_default_budget(circle_animation):
    assert circle_animation.size <= 3_500_000
    assert circle_animation.dpi == DEFAULT_DPI


def test_a_small_budget_lowers_the_resolution_and_holds(circle):
    q, _ = circle
    anim = animate(UR3, q, max_frames=30, max_bytes=300_000)
    assert anim.size <= 300_000
    assert anim.colors is not None and anim.dpi < DEFAULT_DPI
    width = Image.open(io.BytesIO(anim.images[0])).size[0]
    assert width < 7.0 * DEFAULT_DPI


@pytest.mark.parametrize("max_bytes", [2_000, 40_000])
def test_an_impossible_budget_is_refused(max_bytes):
    # 2 kB: not even the player; 40 kB: not 60 frames at the lowest resolution
    with pytest.raises(ValueError, match=f"max_bytes = {max_bytes} is too small"):
        animate(UR3, _sweep(60), max_bytes=max_bytes)


# ---------------------------------------------------------------------------------------------
# what is drawn
# ---------------------------------------------------------------------------------------------


def test_the_trace_at_the_last_frame_is_every_sample(circle, circle_animation):
    q, points = circle
    one_by_one = np.array([urkin.fk(UR3, qk)[:3, 3] for qk in q])
    assert circle_animation.trace.shape == (629, 3)
    assert np.allclose(circle_animation.trace, one_by_one, rtol=0, atol=1e-12)
    # and the tracked circle is the target circle
    assert np.allclose(circle_animation.trace, points, rtol=0, atol=1e-9)


def test_the_trace_follows_the_tool():
    tool = urkin.transforms.make_transform(np.eye(3), [0.0, 0.0, 0.1])
    arm = UR3.with_tool(tool)
    q = _sweep(5)
    anim = animate(arm, q, figsize=(3.0, 3.0))
    assert np.allclose(anim.trace, urkin.fk(arm, q)[:, :3, 3], rtol=0, atol=1e-12)


# ---------------------------------------------------------------------------------------------
# imports
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "code",
    [
        "import urkin, sys; assert 'matplotlib' not in sys.modules and 'PIL' not in sys.modules",
        "import urkin.animation as a, urkin.plot as p; assert p.animate is a.animate",
        "import urkin.plot as p, urkin.animation as a; assert p.Animation is a.Animation",
        "import sys, urkin.animation; assert 'matplotlib.pyplot' not in sys.modules",
    ],
)
def test_imports(code):
    subprocess.run([sys.executable, "-c", code], check=True, timeout=60)


def test_no_pyplot_figure_is_left_open(small):
    import matplotlib.pyplot as plt

    before = plt.get_fignums()
    anim = animate(UR3, _sweep(3), figsize=(3.0, 3.0))
    anim.keyframes(2)
    anim._repr_mimebundle_()
    assert plt.get_fignums() == before


# ---------------------------------------------------------------------------------------------
# in a browser: headless Chromium, offline
# ---------------------------------------------------------------------------------------------

_spec = importlib.util.spec_from_file_location(
    "check_offline", Path(__file__).parents[1] / "docs" / "check_offline.py"
)
check_offline = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(check_offline)


def _chromium() -> str:
    found = shutil.which("chromium") or shutil.which("chromium-browser")
    if found is None:
        pytest.skip("chromium not installed")
    return found


def _browse(body: str, tmp_path, budget_ms: int = 5000) -> tuple[str, list[str], list[str]]:
    """Open a page with ``body`` offline (docs/check_offline.py's browser, the one the docs
    build uses): the DOM after ``budget_ms`` of virtual time, the URLs the page requested,
    and every network URL in the log."""
    page = tmp_path / "page.html"
    page.write_text(
        f"<!DOCTYPE html>\n<html><head><meta charset='utf-8'></head><body>\n{body}"
        "\n</body></html>\n",
        encoding="utf-8",
    )
    return check_offline.browse(page, _chromium(), tmp_path, budget_ms)


_frames_reached = check_offline.frames


def _script_text(html: str) -> str:
    """``html`` as a JavaScript string literal that can sit inside a <script>."""
    return json.dumps(html).replace("</", "<\\/")


@pytest.fixture(scope="module")
def player():
    # 40 frames at 5 fps: 5 s of virtual time play 25 of them, without wrapping round to 0
    return animate(UR3, _sweep(40), fps=5, figsize=(3.0, 3.0))


@pytest.mark.browser
def test_chromium_plays_it_offline(player, tmp_path):
    dom, by_page, _ = _browse(player.html, tmp_path)
    assert _frames_reached(dom) and _frames_reached(dom)[0] >= 10
    assert ">Pause</button>" in dom  # it started playing by itself
    assert re.search(r"<span>frame \d+ of 40, sample \d+ of 40</span>", dom)
    assert [url for url in by_page if not url.startswith(("file:", "data:"))] == []


@pytest.mark.browser
def test_chromium_check_sees_a_page_that_goes_online(tmp_path):
    """The network check is not vacuous: a page loading from another host is caught."""
    body = (
        '<img src="https://example.invalid/x.png">'
        '<script>fetch("http://cdn.example.invalid/lib.js").catch(function () {});</script>'
    )
    _, by_page, everywhere = _browse(body, tmp_path, budget_ms=1000)
    assert "https://example.invalid/x.png" in by_page
    assert "http://cdn.example.invalid/lib.js" in by_page
    assert set(by_page) <= set(everywhere)


@pytest.mark.browser
def test_chromium_plays_two_players_on_one_page(player, tmp_path):
    other = animate(UR3, _sweep(30, seed=3), fps=5, figsize=(3.0, 3.0))
    # the same output twice too (two kernels' outputs with the same id): all three play
    dom, by_page, _ = _browse(player.html + other.html + player.html, tmp_path)
    reached = _frames_reached(dom)
    assert len(reached) == 3 and min(reached) >= 10
    assert dom.count('data-started="1"') == 3
    assert by_page == []


@pytest.mark.browser
def test_chromium_plays_it_inserted_like_notebook_front_ends(player, tmp_path):
    """JupyterLab sets innerHTML on a host that may not be in the page yet, then replaces each
    script by a copy; the classic notebook evals the scripts' text (no currentScript)."""
    source = _script_text(player.html)
    body = f"""<div id="lab"></div><div id="classic"></div>
<script>
(function () {{
  var host = document.createElement("div");
  host.innerHTML = {source};
  Array.prototype.slice.call(host.getElementsByTagName("script")).forEach(function (s) {{
    var copy = document.createElement("script");
    copy.textContent = s.textContent;
    s.parentNode.replaceChild(copy, s);
  }});
  setTimeout(function () {{ document.getElementById("lab").appendChild(host); }}, 200);
  var classic = document.getElementById("classic");
  classic.innerHTML = {source};
  Array.prototype.slice.call(classic.getElementsByTagName("script")).forEach(function (s) {{
    (0, eval)(s.textContent);
  }});
}})();
</script>"""
    dom, by_page, _ = _browse(body, tmp_path)
    reached = _frames_reached(dom)
    assert len(reached) == 2 and min(reached) >= 10
    assert by_page == []


def test_scenery_is_drawn_once_into_the_frames_and_leaves_the_player_alone():
    calls = []

    def scenery(ax):
        calls.append(ax)
        ax.plot([-0.3, 0.3], [0.0, 0.0], [0.2, 0.2], color="tab:brown", linewidth=8)

    qs = _sweep(6)
    with_scenery = animate(UR3, qs, max_frames=3, figsize=(3.0, 3.0), scenery=scenery)
    plain = animate(UR3, qs, max_frames=3, figsize=(3.0, 3.0))
    assert len(calls) == 1 and calls[0].name == "3d"
    assert with_scenery.images[0] != plain.images[0]
    assert _sanitized(with_scenery.html) == _sanitized(plain.html)
