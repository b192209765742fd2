"""The one progress display of the commands: bars with ETA on a terminal, plain lines elsewhere."""

from __future__ import annotations

import io
import re

import pytest

from mazesim.cli.progress import ProgressDisplay, clock_time


class FakeTerminal(io.StringIO):
    """A stream that says it is a terminal."""

    def isatty(self) -> bool:
        return True


class FakeClock:
    """A clock the test moves by hand."""

    def __init__(self) -> None:
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


def test_a_terminal_gets_one_bar_per_stage_with_rate_and_eta() -> None:
    stream = FakeTerminal()
    units = {"evaluating": "episodes"}
    with ProgressDisplay(stream, unit="steps", units=units, bar_delay_s=0) as d:
        for step in range(1, 51):
            d("training", step, 50)
        for episode in range(1, 3):
            d("evaluating", episode, 10)
    text = stream.getvalue()
    assert "training: 100%" in text and "50/50 steps" in text
    assert "evaluating:" in text and "/10 episodes" in text
    assert re.search(r"ETA \d\d:\d\d", text), text
    assert re.search(r"\d+(\.\d+)?(steps|episodes)/s", text), text
    # The unfinished stage was closed by the context manager, not left at 100 %.
    assert "evaluating: 100%" not in text


def test_a_terminal_shows_no_bar_for_a_stage_shorter_than_the_delay() -> None:
    stream = FakeTerminal()
    with ProgressDisplay(stream, unit="steps", bar_delay_s=60.0) as display:
        for step in range(1, 11):
            display("simulating", step, 10)
    assert stream.getvalue() == ""


def test_off_a_terminal_a_short_run_writes_nothing() -> None:
    stream = io.StringIO()
    with ProgressDisplay(stream, unit="steps") as display:
        for step in range(1, 101):
            display("simulating", step, 100)
    assert stream.getvalue() == ""


def test_off_a_terminal_a_long_run_writes_a_plain_line_now_and_then() -> None:
    stream = io.StringIO()
    clock = FakeClock()
    display = ProgressDisplay(stream, unit="readings", plain_every_s=30.0, clock=clock)
    display("barcode-study", 0, 1000)
    for done in range(1, 1001):
        clock.now += 0.125  # 8 readings per second: 125 s in all
        display("barcode-study", done, 1000)
    lines = stream.getvalue().splitlines()
    # A line every 30 s of the 125 s, then the final one.
    assert len(lines) == 5, lines
    assert lines[0] == "mazesim: barcode-study: 240/1000 readings (24%), 8.00 readings/s, ETA 1:35"
    assert lines[3].startswith("mazesim: barcode-study: 960/1000 readings (96%)")
    assert lines[4] == "mazesim: barcode-study: 1000/1000 readings (100%) in 2:05, 8.00 readings/s"


def test_off_a_terminal_the_eta_counts_from_where_a_resumed_run_started() -> None:
    stream = io.StringIO()
    clock = FakeClock()
    display = ProgressDisplay(stream, unit="steps", plain_every_s=10.0, clock=clock)
    display("lower level", 5000, 10000)  # resumed half-way
    clock.now += 10.0
    display("lower level", 6000, 10000)
    assert stream.getvalue() == (
        "mazesim: lower level: 6000/10000 steps (60%), 100 steps/s, ETA 0:40\n"
    )


def test_a_new_stage_starts_its_own_count_and_lines() -> None:
    stream = io.StringIO()
    clock = FakeClock()
    display = ProgressDisplay(stream, plain_every_s=5.0, unit="episodes", clock=clock)
    display("lower level", 0, 10)
    clock.now += 6.0
    display("lower level", 10, 10)
    display("higher level", 0, 4)
    clock.now += 6.0
    display("higher level", 2, 4)
    assert stream.getvalue().splitlines() == [
        "mazesim: lower level: 10/10 episodes (100%) in 0:06, 1.67 episodes/s",
        "mazesim: higher level: 2/4 episodes (50%), 0.33 episodes/s, ETA 0:06",
    ]


def test_a_disabled_display_writes_nothing_even_on_a_terminal() -> None:
    stream = FakeTerminal()
    with ProgressDisplay(stream, enabled=False, bar_delay_s=0) as display:
        for step in range(1, 11):
            display("simulating", step, 10)
    assert stream.getvalue() == ""


def test_the_context_manager_closes_the_bar_when_the_run_fails() -> None:
    stream = FakeTerminal()
    with pytest.raises(KeyboardInterrupt):
        with ProgressDisplay(stream, unit="steps", bar_delay_s=0) as display:
            display("simulating", 3, 10)
            raise KeyboardInterrupt
    text = stream.getvalue()
    assert "simulating:  30%" in text
    assert text.endswith("\n")  # the shell's prompt starts on a line of its own


@pytest.mark.parametrize(
    ("seconds", "shown"),
    [(0.0, "0:00"), (59.4, "0:59"), (61.0, "1:01"), (3725.0, "1:02:05"), (float("inf"), "?")],
)
def test_clock_time(seconds: float, shown: str) -> None:
    assert clock_time(seconds) == shown
