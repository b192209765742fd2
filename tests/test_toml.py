"""Issue 35: a command's TOML file nested deeper than any real one is refused with the line and the
field named, never with a RecursionError."""

from __future__ import annotations

from pathlib import Path

import pytest

import mazesim
from mazesim._toml import MAX_TOML_NESTING, dump_toml, load_toml
from mazesim.distributed.config import load_sweep_config
from mazesim.errors import InvalidArgumentError
from mazesim.transfer.randomise import parse_spec

DEEP = 10_000


def test_nesting_up_to_the_limit_is_read_and_past_it_refused_naming_the_field() -> None:
    depth = MAX_TOML_NESTING
    document = load_toml(f"[a]\nvalues = {'[' * depth}1{']' * depth}\n", "x.toml")
    values = document["a"]["values"]
    for _ in range(depth - 1):
        values = values[0]
    assert values == [1]
    with pytest.raises(InvalidArgumentError) as caught:
        load_toml(f"[a]\nok = 1\nvalues = {'[' * (depth + 1)}1{']' * (depth + 1)}\n", "x.toml")
    assert str(caught.value).startswith("x.toml:3: field `values`: expected values nested")


@pytest.mark.parametrize(
    "text",
    [
        # Brackets in strings, comments and table headers do not nest.
        'name = "' + "[" * DEEP + '"\n',
        "name = '''\n" + "{" * DEEP + "\n'''\n",
        "# " + "[" * DEEP + '\nname = "a\\"["\n',
        "[[runs]]\nname = 'x'\n[[runs]]\nname = 'y'\n",
    ],
    ids=["basic-string", "literal-multiline", "comment", "headers"],
)
def test_brackets_that_do_not_nest_are_not_counted(text: str) -> None:
    assert load_toml(text, "x.toml")


def test_a_deeply_nested_sweep_file_names_its_field(tmp_path: Path) -> None:
    sweep = tmp_path / "sweep.toml"
    sweep.write_text(f"[sweep]\nseeds = {'[' * DEEP}{']' * DEEP}\n")
    with pytest.raises(InvalidArgumentError, match=r"sweep.toml:2: field `seeds`: expected"):
        load_sweep_config(sweep)


def test_a_deeply_nested_randomisation_file_names_its_field(tmp_path: Path) -> None:
    spec = tmp_path / "randomise.toml"
    spec.write_text(f"[randomise]\nwheel_radius_scale = {{ a = {'{b = ' * DEEP}1{'}' * DEEP} }}\n")
    with pytest.raises(InvalidArgumentError, match="field `wheel_radius_scale`"):
        parse_spec(spec)


@pytest.mark.parametrize("name", mazesim.builtin_world_names())
def test_a_world_written_back_from_its_read_toml_is_the_same_world(name: str) -> None:
    # Webots world runs edit a world's tables this way (without walls, robots for its start).
    world = mazesim.load_world(name)
    written = dump_toml(load_toml(world.to_toml(), name))
    assert mazesim.World.from_toml(written, name).to_toml() == world.to_toml()


def test_a_dotted_key_nests_by_its_parts() -> None:
    """A key of 60,000 dotted parts (120 kB) took more than 3.8 GB inside tomllib; a header's
    parts nest as a key's do, and dots inside a quoted part are its name's."""
    with pytest.raises(InvalidArgumentError, match=r"t.toml:2: field `a\.b\.b.*the parts of a"):
        load_toml("x = 1\na" + ".b" * 60_000 + " = 1\n", "t.toml")
    with pytest.raises(InvalidArgumentError, match="t.toml:1: field `t.t"):
        load_toml("[" + ".".join(["t"] * (MAX_TOML_NESTING + 1)) + "]\n", "t.toml")
    deep = load_toml("[" + ".".join(["t"] * MAX_TOML_NESTING) + "]\nx = 1\n", "t.toml")
    assert "t" in deep
    quoted = '"' + "." * 100 + '".c = 1\n'
    assert load_toml(quoted, "t.toml") == {"." * 100: {"c": 1}}


def test_a_long_line_of_strings_is_refused_as_tomllib_refuses_it() -> None:
    """The scan read a top-level line again at every string on it (2.1 MB: 56 s); it reads each
    line once now (this line of 300,000 strings takes well under a second)."""
    line = 'a = "x" ' + " ".join(['"y"'] * 300_000) + "\n"
    with pytest.raises(InvalidArgumentError, match="not a valid TOML file"):
        load_toml(line, "t.toml")
