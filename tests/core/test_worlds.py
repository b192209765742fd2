"""The built-in worlds, the world loader, its error messages and the save/load round trip."""

from __future__ import annotations

import math
import os
import re
import tempfile
from collections import deque
from pathlib import Path

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import mazesim
from mazesim import UnknownNameError, World, WorldFormatError

BUILTIN_WORLDS = ("seed-maze", "line-follow", "arena")

CELL = 0.25
# Unit steps east, north, west, south.
DIRECTIONS = ((1, 0), (0, 1), (-1, 0), (0, -1))


# --- the built-in worlds ----------------------------------------------------------------------


def test_builtin_names_are_the_three_worlds() -> None:
    assert sorted(mazesim.builtin_world_names()) == sorted(BUILTIN_WORLDS)


def test_each_builtin_world_loads(builtin_name: str) -> None:
    world = mazesim.load_world(builtin_name)
    assert world.name == builtin_name
    assert world.basic_time_step_ms == 32
    boxes = world.wall_boxes()
    assert boxes.ndim == 2 and boxes.shape[1] == 6 and len(boxes) >= 4
    assert np.all(boxes[:, 2:4] > 0)
    xmin, ymin, xmax, ymax = world.bounds
    start_x, start_y, _ = world.start
    assert xmin < start_x < xmax and ymin < start_y < ymax
    assert World.builtin(builtin_name) == world


def test_builtin_world_loads_equal_to_its_file(builtin_name: str) -> None:
    path = Path(__file__).resolve().parents[2] / "worlds" / f"{builtin_name}.toml"
    assert mazesim.load_world(path) == mazesim.load_world(builtin_name)


def _bars(world: World, checkpoint: dict) -> str:
    """Reads a checkpoint's bars off the floor, in its reading direction."""
    bar_length = 0.017
    center_x, center_y = checkpoint["center"]
    yaw = checkpoint["yaw"]
    bits = ""
    for index in range(5):
        offset = (index - 2) * bar_length
        reflectance = world.floor_reflectance(
            center_x + offset * math.cos(yaw), center_y + offset * math.sin(yaw)
        )
        assert reflectance == pytest.approx(1.0) or reflectance == pytest.approx(0.2)
        bits += "1" if reflectance > 0.6 else "0"
    return bits


def test_seed_maze_has_seven_distinct_direction_telling_codes() -> None:
    world = mazesim.load_world("seed-maze")
    checkpoints = world.checkpoints()
    assert sorted(c["id"] for c in checkpoints) == list(range(1, 8))
    codes = [c["code"] for c in checkpoints]
    assert len(set(codes)) == 7
    for code in codes:
        assert len(code) == 5 and set(code) <= {"0", "1"}
        assert code != code[::-1], f"{code} is a palindrome"
        assert code[::-1] not in codes, f"the reverse of {code} is another checkpoint's code"
    for checkpoint in checkpoints:
        assert checkpoint["width"] == pytest.approx(0.23)
        assert _bars(world, checkpoint) == checkpoint["code"]


def test_seed_maze_floor_is_grey_between_black_and_white() -> None:
    world = mazesim.load_world("seed-maze")
    start_x, start_y, _ = world.start
    assert world.floor_reflectance(start_x, start_y) == pytest.approx(0.36)


def _cell_of(x: float, y: float) -> tuple[int, int]:
    return (math.floor(x / CELL), math.floor(y / CELL))


def _blocked(boxes: np.ndarray, a: tuple[float, float], b: tuple[float, float]) -> bool:
    """Whether the straight line a-b passes through a wall box."""
    t = np.linspace(0.0, 1.0, 51)[:, None]
    samples = np.asarray(a) + t * (np.asarray(b) - np.asarray(a))  # (51, 2)
    dx = samples[:, None, 0] - boxes[None, :, 0]
    dy = samples[:, None, 1] - boxes[None, :, 1]
    cos_yaw, sin_yaw = np.cos(boxes[:, 4]), np.sin(boxes[:, 4])
    local_x = dx * cos_yaw + dy * sin_yaw
    local_y = -dx * sin_yaw + dy * cos_yaw
    inside = (np.abs(local_x) <= boxes[:, 2] / 2) & (np.abs(local_y) <= boxes[:, 3] / 2)
    return bool(inside.any())


def _openings(world: World) -> dict[tuple[int, int], set[int]]:
    """The open sides (indices into DIRECTIONS) of every 0.25 m cell of seed-maze."""
    boxes = world.wall_boxes()
    xmin, ymin, xmax, ymax = world.bounds
    columns = round((xmax - xmin) / CELL - 0.04)
    rows = round((ymax - ymin) / CELL - 0.04)
    openings: dict[tuple[int, int], set[int]] = {}
    for column in range(columns):
        for row in range(rows):
            center = ((column + 0.5) * CELL, (row + 0.5) * CELL)
            openings[(column, row)] = set()
            for index, (dx, dy) in enumerate(DIRECTIONS):
                neighbour = (column + dx, row + dy)
                if not (0 <= neighbour[0] < columns and 0 <= neighbour[1] < rows):
                    continue
                other = ((neighbour[0] + 0.5) * CELL, (neighbour[1] + 0.5) * CELL)
                if not _blocked(boxes, center, other):
                    openings[(column, row)].add(index)
    return openings


def test_seed_maze_checkpoints_sit_in_straight_corridors_before_junctions() -> None:
    world = mazesim.load_world("seed-maze")
    openings = _openings(world)
    assert len(openings) == 25
    junctions = [cell for cell, sides in openings.items() if len(sides) >= 3]
    assert len(junctions) >= 3
    for checkpoint in world.checkpoints():
        cell = _cell_of(*checkpoint["center"])
        heading = round(checkpoint["yaw"] / (math.pi / 2)) % 4
        misalignment = math.remainder(checkpoint["yaw"] - heading * math.pi / 2, 2 * math.pi)
        assert misalignment == pytest.approx(0.0, abs=1e-9), "a code must run along the corridor"
        assert openings[cell] == {heading, (heading + 2) % 4}, f"checkpoint {checkpoint['id']}"
        dx, dy = DIRECTIONS[heading]
        ahead = (cell[0] + dx, cell[1] + dy)
        assert len(openings[ahead]) >= 3, f"checkpoint {checkpoint['id']} does not lead to a door"


def test_seed_maze_goal_is_reachable_and_far_from_the_start() -> None:
    world = mazesim.load_world("seed-maze")
    openings = _openings(world)
    assert world.goal is not None
    goal_x, goal_y, radius = world.goal
    assert radius == pytest.approx(CELL / 3)
    start = _cell_of(*world.start[:2])
    goal = _cell_of(goal_x, goal_y)
    distance = {start: 0}
    queue = deque([start])
    while queue:
        cell = queue.popleft()
        for index in openings[cell]:
            dx, dy = DIRECTIONS[index]
            neighbour = (cell[0] + dx, cell[1] + dy)
            if neighbour not in distance:
                distance[neighbour] = distance[cell] + 1
                queue.append(neighbour)
    assert distance.get(goal, 0) >= 8


def test_line_follow_has_a_black_loop_under_the_start() -> None:
    world = mazesim.load_world("line-follow")
    x, y, yaw = world.start
    assert world.floor_reflectance(x, y) == pytest.approx(0.2)
    assert world.floor_reflectance(x, y + 0.05) == pytest.approx(1.0)
    # Ahead along the start heading, the line goes on.
    assert world.floor_reflectance(
        x + 0.1 * math.cos(yaw), y + 0.1 * math.sin(yaw)
    ) == pytest.approx(0.2)
    assert world.goal is None and world.checkpoints() == []


def test_arena_is_a_square_metre_with_boxes() -> None:
    world = mazesim.load_world("arena")
    xmin, ymin, xmax, ymax = world.bounds
    assert xmax - xmin == pytest.approx(1.01, abs=0.01)
    assert ymax - ymin == pytest.approx(1.01, abs=0.01)
    assert world.start[:2] == pytest.approx((0.0, 0.0))
    sizes = world.wall_boxes()[:, 2:4]
    assert 4 <= int(np.sum(np.all(np.isclose(sizes, 0.1), axis=1))) <= 5


# --- names and paths ----------------------------------------------------------------------------


def test_unknown_builtin_name_lists_the_available_names() -> None:
    with pytest.raises(UnknownNameError) as caught:
        mazesim.load_world("no-such-world")
    message = str(caught.value)
    for name in BUILTIN_WORLDS:
        assert name in message
    assert sorted(caught.value.available) == sorted(BUILTIN_WORLDS)
    assert isinstance(caught.value, LookupError)


def test_a_folder_or_device_given_as_a_world_says_it_is_not_a_world_file(tmp_path: Path) -> None:
    fifo = tmp_path / "world.toml"
    os.mkfifo(fifo)
    for where, kind in (
        (tmp_path, "a folder"),
        (Path(os.devnull), "a character device"),
        (fifo, "a FIFO \\(named pipe\\)"),
    ):
        with pytest.raises(UnknownNameError, match=f"it is {kind}, not a world file"):
            mazesim.load_world(where)
    with pytest.raises(UnknownNameError, match="there is no file 'missing.toml' in the folder"):
        mazesim.load_world(tmp_path / "missing.toml")


def test_a_missing_relative_world_file_says_which_folder_it_was_looked_in(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    with pytest.raises(UnknownNameError) as caught:
        mazesim.load_world("worlds/my-maze.toml")
    assert str(caught.value).startswith(
        f"no world file 'worlds/my-maze.toml': there is no folder 'worlds' in {tmp_path}; "
        "built-in worlds: "
    )


def test_a_path_names_the_missing_folder_or_file_and_guesses_only_close_names(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "nostart.toml").write_text(mazesim.load_world("seed-maze").to_toml())
    (tmp_path / "worlds").mkdir()
    said = {}
    for path in ("nothere/maze.toml", "nothere.toml", "worlds/maze.toml"):
        with pytest.raises(UnknownNameError) as caught:
            mazesim.load_world(path)
        assert caught.value.suggestion is None, path
        assert "did you mean" not in str(caught.value)
        said[path] = str(caught.value).split("; built-in worlds")[0]
    assert said == {
        "nothere/maze.toml": f"no world file 'nothere/maze.toml': there is no folder 'nothere' in "
        f"{tmp_path}",
        "nothere.toml": f"no world file 'nothere.toml': there is no file 'nothere.toml' in "
        f"{tmp_path}",
        "worlds/maze.toml": "no world file 'worlds/maze.toml': there is no file 'maze.toml' in "
        f"the folder 'worlds' in {tmp_path}",
    }
    # A built-in name given with a suffix is the name meant.
    with pytest.raises(UnknownNameError, match="did you mean 'seed-maze'\\?$"):
        mazesim.load_world("seed-maze.toml")


@pytest.mark.parametrize(("name", "kind"), [("maze.json", "a .json file"), ("maze", "a file")])
def test_a_file_of_another_kind_says_which_files_are_worlds(
    tmp_path: Path, name: str, kind: str
) -> None:
    path = tmp_path / name
    path.write_text('{"walls": []}\n')
    with pytest.raises(WorldFormatError) as caught:
        mazesim.load_world(path)
    message = str(caught.value)
    assert message.startswith(f"{path}:1:1: ")
    assert message.endswith(
        f"(mazesim reads .toml world files and .wbt Webots worlds; found {kind}"
        + (")" if "json" in kind else " without an extension)")
    )
    assert caught.value.line == 1


def test_a_maze_drawn_in_a_text_file_is_told_to_paste_it_into_a_world_file(
    tmp_path: Path,
) -> None:
    drawn = tmp_path / "maze.txt"
    drawn.write_text("+--+--+\n|S    |\n+--+  +\n|G    |\n+--+--+\n")
    notes = tmp_path / "notes.txt"
    notes.write_text("+-- a list\n| of notes\n")
    with pytest.raises(WorldFormatError) as caught:
        mazesim.load_world(drawn)
    assert str(caught.value).endswith(
        "found a .txt file); it holds a maze drawn as a [grid] map: paste it into a .toml world "
        'file under [grid] map = """...""", after the lines format = "mazesim-world" and '
        "version = 1 (docs/own-maze.md shows such a file)"
    )
    with pytest.raises(WorldFormatError) as caught:
        mazesim.load_world(notes)
    assert str(caught.value).endswith("found a .txt file)")


def test_a_toml_file_holding_a_drawn_map_alone_is_told_to_put_it_under_grid(
    tmp_path: Path,
) -> None:
    drawn = tmp_path / "maze.toml"
    drawn.write_text("+--+--+\n|S    |\n+--+  +\n|G    |\n+--+--+\n")
    with pytest.raises(WorldFormatError) as caught:
        mazesim.load_world(drawn)
    message = str(caught.value)
    assert message.startswith(f"{drawn}:1:")
    assert message.endswith(
        "; it holds a maze drawn as a [grid] map: paste it into a .toml world file under [grid] "
        'map = """...""", after the lines format = "mazesim-world" and version = 1 '
        "(docs/own-maze.md shows such a file)"
    )


@pytest.mark.parametrize(
    ("name", "start", "kind"),
    [
        ("maze.png", b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\xff\xfe", "a PNG image"),
        ("maze.jpg", b"\xff\xd8\xff\xe0\x00\x10JFIF\x00\xff\xfe", "a JPEG image"),
        ("maze", b"GIF89a\x01\x00\xff\xfe", "a GIF image"),
    ],
)
def test_a_maze_drawn_in_a_picture_is_told_what_mazesim_reads_and_what_to_do(
    tmp_path: Path, name: str, start: bytes, kind: str
) -> None:
    picture = tmp_path / name
    picture.write_bytes(start)
    with pytest.raises(mazesim.MazesimError) as caught:
        mazesim.load_world(picture)
    message = str(caught.value)
    assert message.startswith(f"{picture}: ")
    assert message.endswith(
        f"(found {kind}: mazesim reads .toml world files and .wbt Webots worlds, not pictures; "
        "draw the maze as a [grid] map of +--+ and | in a .toml world file, or generate one with "
        "mazesim.generate_maze: docs/own-maze.md shows both)"
    ), message


def test_core_unknown_builtin_name_lists_the_available_names() -> None:
    with pytest.raises(UnknownNameError) as caught:
        World.builtin("no-such-world")
    for name in BUILTIN_WORLDS:
        assert name in str(caught.value)


@pytest.mark.parametrize(
    ("typed", "meant"),
    [("seed_maze", "seed-maze"), ("seed-maz", "seed-maze"), ("Arena", "arena")],
)
def test_a_mistyped_world_name_says_which_name_was_meant(typed: str, meant: str) -> None:
    with pytest.raises(UnknownNameError) as caught:
        mazesim.load_world(typed)
    assert str(caught.value).endswith(f"; did you mean {meant!r}?")
    assert caught.value.suggestion == meant


def test_the_cores_unknown_names_say_which_name_was_meant() -> None:
    with pytest.raises(UnknownNameError, match="did you mean 'e-puck'\\?$") as caught:
        mazesim.Simulator(mazesim.load_world("arena"), robot="epuck")
    assert caught.value.suggestion == "e-puck"
    assert "e-puck2" in caught.value.available
    with pytest.raises(UnknownNameError, match="did you mean 'seed-maze'\\?$"):
        World.builtin("seedmaze")


def test_a_name_far_from_every_known_one_gets_no_guess(tmp_path: Path) -> None:
    for far in (str(tmp_path / "missing.toml"), "warehouse"):
        with pytest.raises(UnknownNameError) as caught:
            mazesim.load_world(far)
        assert "did you mean" not in str(caught.value)
        assert caught.value.suggestion is None


def test_a_mistyped_world_file_says_which_file_beside_it_was_meant(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    mazesim.generate_maze(3, 3, seed=1).save(str(tmp_path / "my-maze.toml"))
    (tmp_path / "notes.txt").write_text("not a world")
    with pytest.raises(UnknownNameError) as caught:
        mazesim.load_world(str(tmp_path / "my-maz.toml"))
    assert caught.value.suggestion == str(tmp_path / "my-maze.toml")
    assert sorted(caught.value.available) == sorted(BUILTIN_WORLDS)
    # A relative path is answered relatively, as it was typed.
    monkeypatch.chdir(tmp_path)
    with pytest.raises(UnknownNameError, match="did you mean 'my-maze.toml'\\?$"):
        mazesim.load_world("mymaze.toml")


def test_a_grid_row_cut_short_names_its_line_instead_of_opening_the_wall() -> None:
    text = (
        'format = "mazesim-world"\nversion = 1\n[grid]\nmap = """\n'
        "+--+--+\n|S    |\n+  +--+\n|   G\n+--+--+\n" + '"""\n'
    )
    with pytest.raises(WorldFormatError) as caught:
        World.from_toml(text, source="short.toml")
    message = str(caught.value)
    assert message.startswith("short.toml:8:")
    assert "every row 7 characters wide" in message and "found 5" in message
    assert "east border" in message
    # With its spaces kept, the row is an opening in the east wall on purpose.
    opened = World.from_toml(text.replace("|   G\n", "|   G  \n"), source="open.toml")
    assert not opened.cell_maze()["vertical"][1, 2]


@pytest.mark.parametrize(
    ("edit", "said"),
    [
        (("version = 1", "version = 1.0"), "`version`: expected a whole number, found floating"),
        (("cell_size = 0.25", 'cell_size = "0.25"'), 'expected a number, found string "0.25"'),
        (("reflectance = 0.36", "reflectance = true"), "expected a number, found boolean `true`"),
        (('name = "seed-maze"', "name = 5"), "`name`: expected a string, found integer `5`"),
    ],
)
def test_a_value_of_the_wrong_type_in_a_world_file_is_said_in_words(
    edit: tuple[str, str], said: str
) -> None:
    """A hand-edited world file is told what a field takes as its author would say it: no
    type names of the reader's language (``f64``, ``i64``), and what was expected first."""
    text = World.builtin("seed-maze").to_toml()
    assert edit[0] in text
    with pytest.raises(WorldFormatError) as caught:
        World.from_toml(text.replace(edit[0], edit[1], 1), source="edited.toml")
    message = str(caught.value)
    assert said in message, message
    assert not re.search(r"\b[fiu](8|16|32|64)\b|invalid type", message), message


def test_a_robot_file_of_a_wrong_type_is_said_in_the_same_words() -> None:
    text = mazesim.RobotProfile.builtin("e-puck").to_toml()
    with pytest.raises(WorldFormatError, match=r"`body_radius`: expected a number, found string"):
        mazesim.RobotProfile.from_toml(text.replace("body_radius = 0.037", 'body_radius = "x"'))


def test_load_world_reads_a_path(tmp_path: Path) -> None:
    arena = mazesim.load_world("arena")
    path = tmp_path / "my-arena.toml"
    arena.save(str(path))
    assert mazesim.load_world(path) == arena
    assert mazesim.load_world(str(path)) == arena


# --- malformed worlds ---------------------------------------------------------------------------

HEADER = 'format = "mazesim-world"\nversion = 1\nname = "broken"\n'

MALFORMED = {
    # id: (text, line of the error, a field name the message must contain)
    "wrong-type": (HEADER + '\n[[walls]]\ncenter = [0.5, 0.5]\nsize = [0.1, "wide"]\n', 7, "size"),
    "unknown-key": (HEADER + "\n[floor]\ncolour = 0.5\n", 6, "colour"),
    "reflectance-out-of-range": (HEADER + "\n[floor]\nreflectance = 1.5\n", 6, "reflectance"),
    "future-version": ('format = "mazesim-world"\nversion = 7\n', 2, "version"),
    "bad-code": (
        HEADER + '\n[[checkpoints]]\nid = 1\ncode = "10201"\ncenter = [0.1, 0.1]\n'
        "yaw = 0.0\nwidth = 0.2\n",
        7,
        "code",
    ),
    "bad-grid-character": (
        HEADER + "\n[grid]\ncell_size = 0.25\nwall_thickness = 0.01\n"
        'map = """\n+--+--+\n|  X  |\n+--+--+\n"""\n',
        10,
        "map",
    ),
    # A fixed-length array with an item too many: the reader took the first two and dropped
    # the third without a word.
    "point-of-three-numbers": (
        HEADER + "\n[[walls]]\ncenter = [0.5, 0.5]\nsize = [0.1, 0.1]\n"
        "[[walls]]\ncenter = [0.2, 0.5, 0.1]\nsize = [0.1, 0.1]\n",
        9,
        "walls[1].center",
    ),
    "colour-of-four-numbers": (
        HEADER + "\n[floor]\nreflectance = 0.5\ncolour = [0.5, 0.5, 0.5, 1.0]\n",
        7,
        "colour",
    ),
}


def names_line(message: str, source: str, line: int) -> bool:
    """Whether an error message names the line, as ``line N`` or as ``source:N:column``."""
    return (
        f"line {line}" in message
        or re.search(rf"{re.escape(source)}:{line}:\d+", message) is not None
    )


@pytest.mark.parametrize("case", sorted(MALFORMED))
def test_malformed_file_names_file_line_and_field(tmp_path: Path, case: str) -> None:
    text, line, field = MALFORMED[case]
    path = tmp_path / f"{case}.toml"
    path.write_text(text)
    with pytest.raises(WorldFormatError) as caught:
        mazesim.load_world(path)
    message = str(caught.value)
    assert f"{case}.toml" in message
    assert names_line(message, f"{case}.toml", line)
    assert field in message
    assert caught.value.line == line
    assert field in (caught.value.field or "")
    assert str(caught.value.source).endswith(f"{case}.toml")
    assert isinstance(caught.value, ValueError)


@pytest.mark.parametrize("case", sorted(MALFORMED))
def test_malformed_string_names_source_line_and_field(case: str) -> None:
    text, line, field = MALFORMED[case]
    with pytest.raises(WorldFormatError) as caught:
        World.from_toml(text, source="inline.toml")
    message = str(caught.value)
    assert names_line(message, "inline.toml", line) and field in message


def test_toml_syntax_error_names_the_line() -> None:
    with pytest.raises(WorldFormatError) as caught:
        World.from_toml(HEADER + "\n[[walls]]\ncenter = [0.5, 0.5\n", source="syntax.toml")
    assert "syntax.toml" in str(caught.value)
    assert caught.value.line is not None and caught.value.line >= 6


# --- save and load ------------------------------------------------------------------------------


def test_round_trip_of_each_builtin(builtin_name: str, tmp_path: Path) -> None:
    world = mazesim.load_world(builtin_name)
    assert World.from_toml(world.to_toml()) == world
    path = tmp_path / "copy.toml"
    world.save(str(path))
    loaded = World.load(str(path))
    assert loaded == world
    np.testing.assert_array_equal(loaded.wall_boxes(), world.wall_boxes())
    assert loaded.paint_regions() == world.paint_regions()
    assert loaded.checkpoints() == world.checkpoints()
    assert os.listdir(tmp_path) == ["copy.toml"], "save left a temporary file behind"


def test_worlds_that_differ_are_not_equal() -> None:
    arena = mazesim.load_world("arena")
    text = arena.to_toml().replace('name = "arena"', 'name = "another"')
    assert World.from_toml(text) != arena
    assert mazesim.load_world("seed-maze") != arena


def _fmt(value: float) -> str:
    return repr(float(value))


coordinates = st.floats(min_value=-2.0, max_value=2.0, allow_nan=False, allow_infinity=False)
lengths = st.floats(min_value=0.005, max_value=1.0, allow_nan=False, allow_infinity=False)
angles = st.floats(min_value=-math.pi, max_value=math.pi, allow_nan=False, allow_infinity=False)
reflectances = st.floats(min_value=0.05, max_value=1.0, allow_nan=False, allow_infinity=False)
points = st.tuples(coordinates, coordinates)


@st.composite
def wall_tables(draw: st.DrawFn) -> str:
    center = draw(points)
    size = draw(st.tuples(lengths, lengths))
    return (
        f"[[walls]]\ncenter = [{_fmt(center[0])}, {_fmt(center[1])}]\n"
        f"size = [{_fmt(size[0])}, {_fmt(size[1])}]\nyaw = {_fmt(draw(angles))}\n"
        f"reflectance = {_fmt(draw(reflectances))}\n"
    )


@st.composite
def segment_tables(draw: st.DrawFn) -> str:
    start, end = draw(points), draw(points)
    assume(start != end)
    return (
        f"[[segments]]\nfrom = [{_fmt(start[0])}, {_fmt(start[1])}]\n"
        f"to = [{_fmt(end[0])}, {_fmt(end[1])}]\nthickness = {_fmt(draw(lengths))}\n"
    )


@st.composite
def paint_tables(draw: st.DrawFn) -> str:
    shape = draw(st.sampled_from(["rect", "circle", "polyline"]))
    reflectance = f"reflectance = {_fmt(draw(reflectances))}\n"
    if shape == "rect":
        center, size = draw(points), draw(st.tuples(lengths, lengths))
        return (
            f'[[paint]]\nshape = "rect"\ncenter = [{_fmt(center[0])}, {_fmt(center[1])}]\n'
            f"size = [{_fmt(size[0])}, {_fmt(size[1])}]\nyaw = {_fmt(draw(angles))}\n" + reflectance
        )
    if shape == "circle":
        center = draw(points)
        return (
            f'[[paint]]\nshape = "circle"\ncenter = [{_fmt(center[0])}, {_fmt(center[1])}]\n'
            f"radius = {_fmt(draw(lengths))}\n" + reflectance
        )
    polyline = draw(st.lists(points, min_size=2, max_size=8))
    listed = ", ".join(f"[{_fmt(x)}, {_fmt(y)}]" for x, y in polyline)
    closed = "true" if draw(st.booleans()) and len(polyline) >= 3 else "false"
    return (
        f'[[paint]]\nshape = "polyline"\npoints = [{listed}]\nwidth = {_fmt(draw(lengths))}\n'
        f"closed = {closed}\n" + reflectance
    )


@st.composite
def world_texts(draw: st.DrawFn) -> str:
    start = draw(points)
    text = (
        'format = "mazesim-world"\nversion = 1\nname = "random"\n'
        f"basic_time_step_ms = {draw(st.sampled_from([8, 16, 32, 64]))}\n\n"
        f"[floor]\nreflectance = {_fmt(draw(reflectances))}\n\n"
        f"[start]\nx = {_fmt(start[0])}\ny = {_fmt(start[1])}\nyaw = {_fmt(draw(angles))}\n\n"
    )
    if draw(st.booleans()):
        goal = draw(points)
        radius = draw(lengths)
        text += f"[goal]\ncenter = [{_fmt(goal[0])}, {_fmt(goal[1])}]\nradius = {_fmt(radius)}\n\n"
    tables = draw(st.lists(wall_tables(), max_size=6))
    tables += draw(st.lists(segment_tables(), max_size=4))
    tables += draw(st.lists(paint_tables(), max_size=6))
    return text + "\n".join(tables)


@settings(max_examples=60, deadline=None)
@given(world_texts())
def test_random_world_round_trips_through_text_and_file(text: str) -> None:
    world = World.from_toml(text, source="random.toml")
    again = World.from_toml(world.to_toml(), source="saved.toml")
    assert again == world
    assert again.to_toml() == world.to_toml()
    np.testing.assert_array_equal(again.wall_boxes(), world.wall_boxes())
    assert again.paint_regions() == world.paint_regions()
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "random.toml")
        world.save(path)
        assert World.load(path) == world
