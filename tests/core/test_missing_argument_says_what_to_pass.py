"""A public function called without a required argument says which one, and what it takes, in
the words of its docstring's ``Args:`` (``mazesim.load_world()`` names the built-in worlds'
listing), rather than only that it is missing (#37)."""

from __future__ import annotations

import pytest

import mazesim
from mazesim._checks import documented_argument


def test_load_world_without_a_name_says_what_to_pass_and_where_the_names_are() -> None:
    with pytest.raises(mazesim.InvalidArgumentError) as raised:
        mazesim.load_world()  # type: ignore[call-arg]
    message = str(raised.value)
    assert "expected the argument 'name_or_path', found none" in message, message
    assert '"seed-maze"' in message and "builtin_world_names()" in message, message
    assert "mazesim worlds" in message and ".toml" in message, message


def _described(a: int, b: int) -> None:
    """A function.

    Args:
        a: The first
            value, on two lines.
        b: The second.

    Returns:
        Nothing.
    """


def _undocumented(a: int) -> None:
    """No Args section."""


def test_a_parameter_is_read_from_its_args_entry_continuation_lines_joined() -> None:
    assert documented_argument(_described, "a") == "The first value, on two lines."
    assert documented_argument(_described, "b") == "The second."
    assert documented_argument(_described, "c") is None
    assert documented_argument(_undocumented, "a") is None


def test_a_missing_argument_given_in_the_place_of_another_says_which_and_the_order() -> None:
    # With a module imported that holds matplotlib's Axes at run time (as a session that drew a
    # heat map before), the axes' annotation is checked too: the missing argument is still named
    # first, as Python names it first.
    import mazesim.transfer.heatmap  # noqa: F401
    from mazesim.plotting import plot_world

    world = mazesim.load_world("seed-maze")
    with pytest.raises(mazesim.InvalidArgumentError) as raised:
        plot_world(world)  # type: ignore[call-arg]
    message = str(raised.value)
    assert "expected the argument 'world', found none (the World was given as 'ax': " in message
    assert "plot_world(ax, world))" in message, message
    with pytest.raises(mazesim.InvalidArgumentError) as raised:
        plot_world(None)  # type: ignore[call-arg]
    message = str(raised.value)
    assert "expected the argument 'world', found none; world: " in message, message
