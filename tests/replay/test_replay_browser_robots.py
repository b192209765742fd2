"""The HTML replay of a run of three robots in a real headless browser (Debian's chromium and
chromedriver, selenium): every robot drawn in its own colour, every one moved by the time slider
to where the run file has it, a row per robot in the panel.

Skipped, with the reason, where no Chromium can be driven (``make browser-deps`` installs it).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
from robots_world import record_three_robots

from mazesim.replay import load_run
from mazesim.replay.screenshot import chromium_problem

pytestmark = pytest.mark.skipif(
    chromium_problem() is not None,
    reason=f"browser tests of the HTML replay need Chromium: {chromium_problem()}",
)

BODIES = ["robot", "robot-1", "robot-2"]


@pytest.fixture(scope="module")
def three(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    return record_three_robots(tmp_path_factory.mktemp("three-robots-page"))


@pytest.fixture()
def page(browser: Any, three: dict[str, Path]) -> Any:
    browser.get(three["html"].resolve().as_uri())
    browser.get_log("browser")
    return browser


def drawn(driver: Any, body: str) -> tuple[float, float]:
    group = driver.find_element("id", body)
    return float(group.get_attribute("data-x")), float(group.get_attribute("data-y"))


def severe(log: list[dict[str, Any]]) -> list[dict[str, Any]]:
    return [entry for entry in log if entry["level"] in ("SEVERE", "WARNING")]


def test_every_robot_is_drawn_and_moves_with_the_slider(page: Any, three: dict[str, Path]) -> None:
    run = load_run(three["run"])
    episode = run.episodes[0]
    tracks = [episode, *episode.robots]
    last = episode.frames - 1
    for body, track in zip(BODIES, tracks):
        assert drawn(page, body) == pytest.approx(tuple(track.poses[0, :2]), abs=2e-4)
    slider = page.find_element("id", "slider")
    page.execute_script(
        "arguments[0].value = arguments[1]; arguments[0].dispatchEvent(new Event('input'));",
        slider,
        last,
    )
    assert page.execute_script("return window.mazesimReplay.frame") == last
    for body, track in zip(BODIES, tracks):
        assert drawn(page, body) == pytest.approx(tuple(track.poses[last, :2]), abs=2e-4)
        assert drawn(page, body) != pytest.approx(tuple(track.poses[0, :2]), abs=1e-2)
    names = page.execute_script(
        "return window.mazesimReplay.robots.map(function (r) { return r.name; })"
    )
    assert names == ["ann", "bob", "cy"]
    # Distinct colours: bodies, trails, and the legend's swatches.
    fills = {
        page.find_element("css selector", f"#{body} circle").get_attribute("fill")
        for body in BODIES
    }
    assert len(fills) == 3
    trails = [page.find_element("id", t) for t in ("trail", "trail-1", "trail-2")]
    assert len({trail.get_attribute("stroke") for trail in trails}) == 3
    assert all(len(trail.get_attribute("points").split()) > 10 for trail in trails)
    legend = page.find_element("id", "legend").text
    assert all(f"robot {name}" in legend for name in names)
    assert severe(page.get_log("browser")) == []


def test_the_panel_has_a_row_per_robot_and_shows_the_chosen_robots_sensors(page: Any) -> None:
    rows = page.find_elements("css selector", "#robots tbody tr")
    assert [row.text.split()[0] for row in rows] == ["ann", "bob", "cy"]
    assert "ps7" in page.find_element("id", "readings").text
    assert "tof" not in page.find_element("id", "readings").text
    rows[2].click()
    assert page.execute_script("return window.mazesimReplay.selected") == 2
    assert "tof" in page.find_element("id", "readings").text
    assert page.find_element("id", "sensors-of").text == "of cy"
    assert severe(page.get_log("browser")) == []
