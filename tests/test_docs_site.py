"""The built documentation site works opened from disk (``file://``): a headless Chromium clicks
through every entry of its navigation and lands on that page, not on a folder listing (issue 37).

Skipped, with the reason, without the docs tools (``make docs-deps``) or a Chromium that selenium
can drive (``make browser-deps``); ``make test`` installs both.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path
from typing import Any

import pytest

from docs_blocks import build_site
from mazesim.replay.screenshot import chromium_problem

REPO = Path(__file__).resolve().parent.parent

pytestmark = [
    pytest.mark.skipif(
        importlib.util.find_spec("mkdocs") is None,
        reason="building the docs site needs mkdocs (make docs-deps)",
    ),
    pytest.mark.skipif(
        chromium_problem() is not None,
        reason=f"clicking through the site needs Chromium: {chromium_problem()}",
    ),
]


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The site, built as ``make docs`` builds it, into a temporary folder."""
    folder = tmp_path_factory.mktemp("site")
    built = build_site(REPO, folder)
    assert built.returncode == 0, built.stderr
    return folder


def _navigation(driver: Any) -> list[str]:
    """The addresses of the primary navigation's page links, in order."""
    return list(
        driver.execute_script(
            "return Array.from(document.querySelectorAll('nav.md-nav--primary a.md-nav__link'))"
            ".map(function (a) { return a.href; })"
            ".filter(function (href) { return href && href.indexOf('#') < 0; });"
        )
    )


def test_every_navigation_link_opens_its_page_from_disk(site: Path, browser: Any) -> None:
    browser.get((site / "index.html").as_uri())
    links = list(dict.fromkeys(_navigation(browser)))
    assert len(links) >= 20, links
    for href in links:
        assert href.startswith("file://") and href.endswith(".html"), href
        # Click the entry on the page we are on, as a reader does.
        entry = browser.execute_script(
            "var wanted = arguments[0];"
            "return Array.from(document.querySelectorAll('nav.md-nav--primary a.md-nav__link'))"
            ".find(function (a) { return a.href === wanted; });",
            href,
        )
        assert entry is not None, f"{href} is not in the navigation of {browser.current_url}"
        browser.execute_script("arguments[0].click();", entry)
        assert browser.current_url == href
        heading = browser.execute_script(
            "var h = document.querySelector('article h1'); return h ? h.textContent : null;"
        )
        assert heading, f"{href} shows no page (a folder listing?)"
        assert not browser.title.startswith("Index of"), href
    pages = {Path(href).name for href in links}
    assert {"index.html", "own-maze.html", "report.html", "hrl.html"} <= pages
