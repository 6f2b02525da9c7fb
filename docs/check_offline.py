"""The built docs work offline: nothing is loaded from another host, and the animations play.

Run after the Sphinx build (``make docs`` does)::

    python docs/check_offline.py docs/_build/html

1. No page loads a script, stylesheet, image, frame or font from another host (links to other
   sites are fine: they load nothing until clicked).
2. Where Chromium is installed: every animation on the lesson pages that have one plays in
   headless Chromium (its ``data-frame`` advances) and the page requests nothing from the
   network (Chromium's net log, with every host name unresolvable).
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

REMOTE = re.compile(
    r"<(script|img|iframe|source|video|audio)\b[^>]*\bsrc\s*=\s*[\"']?(https?:)?//"
    r"|<link\b[^>]*\bhref\s*=\s*[\"']?(https?:)?//[^>]*>"
    r"|url\(\s*[\"']?(https?:)?//",
    re.IGNORECASE,
)
NETWORK = re.compile(r"^(https?|wss?|ftp)://", re.IGNORECASE)
FRAME = re.compile(r'class="urkin-anim" data-frame="(\d+)"')


def remote_resources(root: Path) -> list[str]:
    """``page: tag`` for every resource a built page would fetch from another host."""
    found = []
    for page in sorted(root.rglob("*.html")):
        for match in REMOTE.finditer(page.read_text(encoding="utf-8", errors="replace")):
            tag = match.group(0)
            if tag.lower().startswith("<link") and not re.search(
                r"rel\s*=\s*[\"']?(stylesheet|preload|icon|modulepreload)", tag, re.IGNORECASE
            ):
                continue  # canonical, alternate …: not fetched
            found.append(f"{page.relative_to(root)}: {tag[:120]}")
    return found


def _net_events(path: Path) -> list[dict]:
    text = path.read_text()
    try:
        return json.loads(text)["events"]
    except json.JSONDecodeError:  # a log left unfinished
        return json.loads(text.rstrip().rstrip(",") + "]}")["events"]


def browse(
    page: Path, chromium: str, scratch: Path, budget_ms: int = 6000
) -> tuple[str, list[str], list[str]]:
    """Open ``page`` in headless Chromium with every host name unresolvable, for ``budget_ms``
    of virtual time (``scratch``: a folder for its profile and net log).

    Returns the DOM then, the network URLs the page itself requested, and every network URL
    in the log (the browser's own background requests too)."""
    net = scratch / "net.json"
    command = [
        chromium,
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        f"--user-data-dir={scratch / 'profile'}",
        "--host-resolver-rules=MAP * ~NOTFOUND",
        f"--log-net-log={net}",
        f"--virtual-time-budget={budget_ms}",
        "--dump-dom",
        page.as_uri(),
    ]
    done = subprocess.run(command, capture_output=True, text=True, timeout=120)
    if done.returncode != 0:
        raise RuntimeError(f"chromium failed on {page}: {done.stderr[-1000:]}")
    by_page, everywhere = [], []
    for event in _net_events(net):
        params = event.get("params") or {}
        url = params.get("url")
        if not isinstance(url, str):
            continue
        if NETWORK.match(url):
            everywhere.append(url)
        # the page's own requests have its (opaque, file) origin as initiator; the browser's
        # background requests (clock, account checks) have none ("not an origin")
        if "initiator" in params and params["initiator"] != "not an origin":
            by_page.append(url)
    return done.stdout, by_page, everywhere


def frames(dom: str) -> list[int]:
    """The frame each animation player of a DOM shows."""
    return [int(k) for k in FRAME.findall(dom)]


def play(page: Path, chromium: str) -> tuple[list[int], list[str]]:
    """Open ``page`` offline for 6 s of virtual time: each player's frame, and the network
    URLs the page requested."""
    with tempfile.TemporaryDirectory() as scratch:
        dom, by_page, _ = browse(page, chromium, Path(scratch))
    return frames(dom), [url for url in by_page if NETWORK.match(url)]


def main(argv: list[str]) -> int:
    root = (Path(argv[0]) if argv else Path("docs/_build/html")).resolve()
    problems = remote_resources(root)
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    pages = [p for p in sorted((root / "lessons").glob("*.html")) if "urkin-anim" in p.read_text()]
    if chromium is None:
        print("check_offline: chromium not installed; animations not played", file=sys.stderr)
    else:
        for page in pages:
            frames, requested = play(page, chromium)
            if not frames or min(frames) == 0:
                problems.append(f"{page.name}: animations did not all play (frames {frames})")
            problems += [f"{page.name}: requested {url}" for url in sorted(set(requested))]
            print(f"check_offline: {page.name}: {len(frames)} animations played offline")
    for problem in problems:
        print("check_offline:", problem, file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
