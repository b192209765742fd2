"""Screenshots of the HTML replay, taken by a headless Chromium driven with selenium.

:func:`headless_chromium` starts Debian's ``chromium`` through its ``chromedriver`` (``make
browser-deps`` installs both), with the browser's console log readable; :func:`save_screenshot`
opens a replay page, shows one step and writes a PNG of the window. ``make replay-screenshot``
runs this module on the shipped navigator's demo to make ``docs/replay.png``::

    python -m mazesim.replay.screenshot REPLAY.html OUT.png [--step N]
"""

from __future__ import annotations

import shutil
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from mazesim._arguments import BoundedParser
from mazesim._atomic import atomic_file
from mazesim.errors import MissingDependencyError

__all__ = ["chromium_problem", "headless_chromium", "main", "save_screenshot"]

#: Where Debian (and most Linux distributions) put the browser and its driver.
CHROMIUM_NAMES = ("chromium", "chromium-browser", "google-chrome")
DRIVER_NAMES = ("chromedriver",)


def _find(names: Sequence[str]) -> str | None:
    for name in names:
        found = shutil.which(name) or (
            f"/usr/lib/chromium/{name}" if Path(f"/usr/lib/chromium/{name}").exists() else None
        )
        if found:
            return found
    return None


def chromium_problem() -> str | None:
    """Why a headless Chromium cannot be driven here, or None when it can."""
    try:
        import selenium  # noqa: F401
    except ImportError:
        return "selenium is not installed (pip install 'mazesim[viewer-tests]')"
    if _find(CHROMIUM_NAMES) is None:
        return "no Chromium found (on Debian: make browser-deps)"
    if _find(DRIVER_NAMES) is None:
        return "no chromedriver found (on Debian: make browser-deps)"
    return None


def headless_chromium(width: int = 1400, height: int = 900) -> Any:
    """A selenium WebDriver of a headless Chromium whose console log can be read.

    Raises:
        MissingDependencyError: selenium, Chromium or chromedriver is missing.
    """
    problem = chromium_problem()
    if problem is not None:
        raise MissingDependencyError(f"the headless browser cannot start: {problem}")
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = _find(CHROMIUM_NAMES) or ""
    for argument in (
        "--headless=new",
        "--no-sandbox",
        "--disable-dev-shm-usage",
        "--disable-gpu",
        f"--window-size={width},{height}",
        "--hide-scrollbars",
    ):
        options.add_argument(argument)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    service = Service(executable_path=_find(DRIVER_NAMES))
    return webdriver.Chrome(options=options, service=service)


def save_screenshot(
    html: str | Path,
    png: str | Path,
    step: int | None = None,
    size: tuple[int, int] = (1400, 1200),
) -> None:
    """Opens a replay page headless, shows ``step`` (by default a few steps after the middle
    decision, else the middle of the episode) and writes a PNG of a window of ``size`` pixels."""
    driver = headless_chromium(*size)
    try:
        driver.get(Path(html).resolve().as_uri())
        if step is None:
            step = int(
                driver.execute_script(
                    "var e = document.getElementById('scene'); var run = JSON.parse(e.textContent)"
                    ".run.episodes[0]; var d = run.decisions;"
                    "return d.length ? d[Math.floor(d.length / 2)].frame + 5 "
                    ": Math.floor(run.frames / 2);"
                )
            )
        driver.execute_script("window.mazesimReplay.show(arguments[0]);", step)
        picture = driver.get_screenshot_as_png()
        with atomic_file(png) as handle:
            handle.write(picture)
    finally:
        driver.quit()


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m mazesim.replay.screenshot REPLAY.html OUT.png [--step N]``."""
    parser = BoundedParser(
        prog="python -m mazesim.replay.screenshot",
        description="Screenshot a mazesim HTML replay in headless Chromium.",
    )
    parser.add_argument("html", help="the replay page")
    parser.add_argument("png", help="the PNG to write")
    parser.add_argument("--step", type=int, default=None, help="the step to show")
    args = parser.parse_args(argv)
    save_screenshot(args.html, args.png, args.step)
    print(f"wrote {args.png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
