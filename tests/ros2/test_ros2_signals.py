"""The ROS 2 nodes and bridge set SIGINT's and SIGTERM's handlers while they run and put back the
ones they found when they end, so that a process that calls them (or the command line's
``main``) and goes on keeps its Ctrl-C."""

from __future__ import annotations

import signal

import pytest

from mazesim.errors import MazesimError
from mazesim.ros2 import nodes


def test_a_node_that_fails_after_setting_the_handlers_puts_back_the_ones_it_found(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    def refused(*args: object, **kwargs: object) -> None:
        raise MazesimError("no network here")

    monkeypatch.setattr(nodes, "Node", refused)
    before = [signal.getsignal(number) for number in (signal.SIGINT, signal.SIGTERM)]
    for run in (nodes.run_avoid_collision, nodes.run_perform_learning):
        with pytest.raises(MazesimError, match="no network"):
            run("jazzy")
        assert [signal.getsignal(n) for n in (signal.SIGINT, signal.SIGTERM)] == before


def test_the_handlers_are_the_nodes_own_while_it_runs() -> None:
    seen = []

    @nodes.leaves_signals_as_found
    def run() -> int:
        nodes.stop_on_signals()
        seen.append(signal.getsignal(signal.SIGINT))
        return 0

    before = signal.getsignal(signal.SIGINT)
    assert run() == 0
    assert seen[0] is not before
    assert signal.getsignal(signal.SIGINT) is before
