"""The HTML replay in a real headless browser (Debian's chromium and chromedriver, selenium).

Skipped, with the reason, where no Chromium can be driven (``make browser-deps`` installs it).
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import pytest

from mazesim.replay.screenshot import chromium_problem

pytestmark = pytest.mark.skipif(
    chromium_problem() is not None,
    reason=f"browser tests of the HTML replay need Chromium: {chromium_problem()}",
)


@pytest.fixture()
def page(browser: Any, navigator_demo: dict[str, Path]) -> Any:
    browser.get(navigator_demo["html"].resolve().as_uri())
    browser.get_log("browser")  # start each test with an empty console
    return browser


def robot_position(driver: Any) -> tuple[float, float]:
    """Where the page drew the robot (its SVG group's attributes)."""
    group = driver.find_element("id", "robot")
    return float(group.get_attribute("data-x")), float(group.get_attribute("data-y"))


def severe(log: list[dict[str, Any]]) -> list[dict[str, Any]]:
    return [entry for entry in log if entry["level"] in ("SEVERE", "WARNING")]


def test_the_page_loads_offline_without_console_errors(page: Any) -> None:
    page.refresh()
    assert page.execute_script("return window.mazesimReplay.frames") > 100
    assert severe(page.get_log("browser")) == []
    # Self-contained: nothing is fetched from anywhere.
    resources = page.execute_script(
        "return performance.getEntriesByType('resource').map(function (e) { return e.name; })"
    )
    assert resources == []


def test_the_slider_moves_the_drawn_robot(page: Any, navigator_demo: dict[str, Path]) -> None:
    start = robot_position(page)
    slider = page.find_element("id", "slider")
    page.execute_script(
        "arguments[0].value = 200; arguments[0].dispatchEvent(new Event('input'));", slider
    )
    assert page.execute_script("return window.mazesimReplay.frame") == 200
    moved = robot_position(page)
    assert moved != start
    from mazesim.replay import load_run

    x, y, _ = load_run(navigator_demo["run"]).episodes[0].poses[200]
    assert moved == pytest.approx((x, y), abs=2e-4)
    assert severe(page.get_log("browser")) == []


def test_play_advances_the_robot(page: Any) -> None:
    start = robot_position(page)
    page.execute_script("window.mazesimReplay.speed = 8;")
    page.find_element("id", "play").click()
    deadline = time.monotonic() + 120.0  # a ceiling for a hang: the loop ends on frame 20
    while page.execute_script("return window.mazesimReplay.frame") < 20:
        assert time.monotonic() < deadline, "play did not advance the replay"
        time.sleep(0.05)
    page.find_element("id", "play").click()  # pause
    assert not page.execute_script("return window.mazesimReplay.playing")
    assert robot_position(page) != start


def test_keys_step_forward_and_back(page: Any) -> None:
    from selenium.webdriver.common.keys import Keys

    body = page.find_element("tag name", "body")
    body.send_keys(Keys.ARROW_RIGHT)
    body.send_keys(Keys.ARROW_RIGHT)
    assert page.execute_script("return window.mazesimReplay.frame") == 2
    body.send_keys(Keys.SHIFT, Keys.ARROW_RIGHT)
    assert page.execute_script("return window.mazesimReplay.frame") == 12
    body.send_keys(Keys.ARROW_LEFT)
    assert page.execute_script("return window.mazesimReplay.frame") == 11
    body.send_keys("n")  # the first decision
    first = page.execute_script(
        "return JSON.parse(document.getElementById('scene').textContent).run.episodes[0]"
        ".decisions[0].frame"
    )
    assert page.execute_script("return window.mazesimReplay.frame") == first


def test_the_panel_shows_the_readings_of_the_step_shown(
    page: Any, navigator_demo: dict[str, Path]
) -> None:
    from mazesim.replay import load_run

    episode = load_run(navigator_demo["run"]).episodes[0]
    assert episode.levels is not None
    for frame in (0, 150, 300):
        page.execute_script("window.mazesimReplay.show(arguments[0]);", frame)
        for sensor in range(6):
            shown = page.find_element("id", f"reading-{sensor}").text
            assert shown == f"{episode.readings[frame, sensor]:.3f} V"
            level = page.find_element("id", f"level-{sensor}").text
            assert level == str(episode.levels[frame, sensor])
        ground = page.find_element("id", "reading-6").text
        assert ground == f"{episode.readings[frame, 6]:.0f}"


def test_the_panel_explains_each_decision(page: Any, navigator_demo: dict[str, Path]) -> None:
    from mazesim.learn.subtasks import SUBTASK_NAMES
    from mazesim.replay import load_run

    episode = load_run(navigator_demo["run"]).episodes[0]
    assert episode.decisions
    for decision in episode.decisions:
        page.execute_script("window.mazesimReplay.show(arguments[0]);", decision.frame)
        text = page.find_element("id", "decision").text
        assert f"D{decision.number} (decision {decision.number}" in text
        assert f"checkpoint {decision.checkpoint}" in text
        assert decision.code in text
        assert f"chose {SUBTASK_NAMES[decision.chosen]}" in text
        assert "highest value" in text
        for value in decision.q_values:
            assert f"{value:.2f}" in text
        assert f"checkpoint {decision.checkpoint}" in page.find_element("id", "barcode").text
        marked = page.find_element("css selector", "#decisions li.current").text
        assert marked.startswith(f"D{decision.number}: ")


def test_a_screenshot_differs_between_two_steps(page: Any) -> None:
    page.execute_script("window.mazesimReplay.show(10);")
    early = page.get_screenshot_as_png()
    page.execute_script("window.mazesimReplay.show(400);")
    late = page.get_screenshot_as_png()
    assert early.startswith(b"\x89PNG") and late.startswith(b"\x89PNG")
    assert early != late


def test_episodes_of_a_batch_are_selectable(browser: Any, tmp_path: Path) -> None:
    from mazesim.cli import main

    page = tmp_path / "eval.html"
    code = main(
        ["eval", "--episodes", "3", "--events", "truth", "--html", str(page), "--max-steps", "900"]
    )
    assert code == 0
    browser.get(page.resolve().as_uri())
    options = browser.find_elements("css selector", "#episode option")
    assert len(options) == 3
    browser.execute_script("window.mazesimReplay.show(100);")
    first = robot_position(browser)
    select = browser.find_element("id", "episode")
    browser.execute_script(
        "arguments[0].value = '2'; arguments[0].dispatchEvent(new Event('change'));", select
    )
    assert browser.execute_script("return window.mazesimReplay.episode") == 2
    browser.execute_script("window.mazesimReplay.show(100);")
    assert robot_position(browser) != first  # another start jitter, another path
    assert severe(browser.get_log("browser")) == []


def test_a_run_without_a_navigator_plays_too(browser: Any, tmp_path: Path) -> None:
    from mazesim.cli import main
    from mazesim.replay import load_run

    page = tmp_path / "demo.html"
    run_file = tmp_path / "run.json"
    args = ["demo", "--seconds", "3", "--out", str(tmp_path), "--html", str(page)]
    assert main([*args, "--record", str(run_file)]) == 0
    episode = load_run(run_file).episodes[0]
    browser.get(page.resolve().as_uri())
    browser.execute_script("window.mazesimReplay.show(50);")
    assert browser.find_element("id", "reading-0").text == f"{episode.readings[50, 0]:.0f}"
    assert browser.find_element("id", "level-0").text == "\u2014"  # no Table 4.1 for raw counts
    assert not browser.find_element("id", "decision-box").is_displayed()
    assert "wheels left" in browser.find_element("id", "action").text
    assert severe(browser.get_log("browser")) == []
