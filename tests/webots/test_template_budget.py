"""One budget for every PROTO template engine (``webots/proto/templates.py``): a Lua or a
JavaScript template that loops or grows without end stops with a ``WorldFormatError`` naming the
PROTO, however it tries to escape the budget (a coroutine, lifting the hook); a Lua template's
``io.open`` reads regular files only, through the package's bounded reader."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from hostile import run_hostile
from mazesim.errors import WorldFormatError
from mazesim.webots.proto import templates

pytest.importorskip("lupa", reason="the PROTO engine's Lua templates need lupa")
pytest.importorskip("quickjs", reason="the PROTO engine's JavaScript templates need quickjs")

#: A small budget, so that the endless templates end soon: what is checked is that they end,
#: with the error, not how fast.
SMALL = templates.TemplateBudget(seconds=0.2, memory_bytes=64 * 1024 * 1024)

ENDLESS = {
    "lua while": ("lua", "%{ while true do end }%"),
    "lua repeat": ("lua", "%{ repeat local x = 1 until false }%"),
    "lua coroutine": ("lua", "%{ coroutine.wrap(function() while true do end end)() }%"),
    "lua coroutine.create": (
        "lua",
        "%{ local co = coroutine.create(function() while true do end end) "
        "coroutine.resume(co) error(select(2, coroutine.resume(co))) }%",
    ),
    "lua lifts the hook": ("lua", "%{ if debug then debug.sethook() end while true do end }%"),
    "lua requires debug to lift the hook": (
        "lua",
        "%{ pcall(function() require('debug').sethook() end) while true do end }%",
    ),
    "lua recursion": ("lua", "%{ local function f() return f() end f() }%"),
    "lua grows a table": ("lua", "%{ local t = {} for i = 1, 1e10 do t[i] = i end }%"),
    "lua grows a string": ("lua", "%{ local s = 'x' while true do s = s .. s end }%"),
    # A pattern match runs in C, where the clock hook never looks: the processor limit of the
    # process the template runs in ends it.
    "lua pattern backtracking": (
        "lua",
        "%{ local found = string.rep('a', 3000):find('.-.-.-.-x') }%",
    ),
    "javascript while": ("javascript", "%< while (true) {} >%"),
    "javascript grows a string": ("javascript", "%< let s = 'x'; while (true) { s = s + s; } >%"),
    # QuickJS does not look at its time limit inside a regular expression: this one backtracks
    # for hours unless the budget's processor limit ends the process it runs in.
    "javascript regular expression": (
        "javascript",
        "%< /^(a+)+$/.test('a'.repeat(40) + 'b') >%",
    ),
}


@pytest.mark.parametrize("name", sorted(ENDLESS))
def test_an_endless_template_ends_in_a_world_format_error_naming_the_proto(
    name: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(templates, "BUDGET", SMALL)
    language, body = ENDLESS[name]
    with pytest.raises(WorldFormatError) as refused:
        templates.evaluate_template(language, body, {}, {}, "Hostile.proto")
    assert "Hostile.proto" in str(refused.value)
    assert "template" in str(refused.value)


def test_a_lua_template_reads_regular_files_and_no_device_or_fifo(tmp_path: Path) -> None:
    text = tmp_path / "rows.txt"
    text.write_text("first\nsecond\n", encoding="utf-8")
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    body = (
        "%{ local f = io.open(fields.path.value) }%%{= f and f:read('l') or 'none' }%"
        "|%{ local g = io.open(fields.path.value, 'w') }%%{= tostring(g) }%"
    )

    def read(path: str) -> str:
        fields = {"path": {"value": path, "defaultValue": path}}
        return templates.evaluate_template("lua", body, fields, {}, "Reader.proto")

    assert read(str(text)) == "first|nil"
    # A device and a FIFO no process writes to are not opened: io.open gives nil at once.
    assert read("/dev/zero") == "none|nil"
    assert read(str(fifo)) == "none|nil"
    assert read(str(tmp_path / "missing")) == "none|nil"


def _interrupted_after_half_a_second(language: str, template: str) -> None:
    """Evaluates ``template`` in a fresh interpreter (Python's own Ctrl-C handler, as a user's
    process has it; a test runner's worker process may have let a native library take SIGINT)
    and sends it Ctrl-C after 0.5 s: the template must stop with KeyboardInterrupt."""
    body = f"""
    import os, signal, threading, time
    from mazesim.webots.proto import templates
    threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT)).start()
    started = time.monotonic()
    try:
        templates.evaluate_template({language!r}, {template!r}, {{}}, {{}}, "Endless.proto")
        print("NOT INTERRUPTED")
    except KeyboardInterrupt:
        print("INTERRUPTED after", round(time.monotonic() - started, 1), "s")
    """
    outcome = run_hostile(body)
    assert outcome.ok and "INTERRUPTED after" in outcome.stdout, outcome.describe()
    assert "NOT INTERRUPTED" not in outcome.stdout


def test_ctrl_c_stops_an_endless_lua_template() -> None:
    """The Lua hook calls back into Python now and then, so Python's Ctrl-C handler runs: an
    endless template is stopped by Ctrl-C long before its budget, as any long work is."""
    _interrupted_after_half_a_second("lua", "%{ while true do end }%")


def test_ctrl_c_stops_an_endless_javascript_template() -> None:
    """QuickJS heeds no Ctrl-C while it runs; its template runs in a child process, which
    Ctrl-C ends: the template stops long before its budget, as a Lua one does."""
    _interrupted_after_half_a_second("javascript", "%< /^(a+)+$/.test('a'.repeat(40) + 'b') >%")


def test_a_javascript_template_still_reads_its_fields_and_files(tmp_path: Path) -> None:
    text = tmp_path / "rows.txt"
    text.write_text("first\n", encoding="utf-8")
    fields = {"path": {"value": str(text), "defaultValue": ""}}
    body = "%<= wbfile.readTextFile(fields.path.value).trim() >%|%<= 6 * 7 >%"
    assert templates.evaluate_template("javascript", body, fields, {}, "R.proto") == "first|42"
    with pytest.raises(WorldFormatError, match="boom"):
        templates.evaluate_template(
            "javascript", "%< throw new Error('boom') >%", {}, {}, "B.proto"
        )


def test_what_a_lua_template_requires_is_the_sandbox_s_too(tmp_path: Path) -> None:
    # require hands out the real libraries unless the sandbox replaces them: io that writes,
    # native libraries, files read unbounded.
    target = tmp_path / "written.txt"
    body = (
        "%{ local f = require('io').open(fields.path.value, 'w') "
        "if f then f:write('x') f:close() end }%"
        "%{= tostring(package.loadlib) }%|%{= tostring(dofile) }%|%{= tostring(loadfile) }%"
        "|%{= package.cpath }%|%{= require('debug').getinfo(1, 'S').short_src }%"
        "|%{= tostring(require('debug').sethook) }%"
    )
    fields = {"path": {"value": str(target), "defaultValue": str(target)}}
    out = templates.evaluate_template("lua", body, fields, {}, "Escape.proto")
    assert out == "nil|nil|nil||proto|nil"
    assert not target.exists()


def test_a_lua_template_drawing_its_texture_with_lua_gd_runs(tmp_path: Path) -> None:
    # RoboCup Junior's victims draw a letter into a PNG with lua-gd (bundled with Webots' Lua):
    # the template runs; its image is drawn and saved nowhere.
    body = (
        "%{ local gd = require('gd') local im = gd.createTrueColor(128, 64) "
        "local white = im:colorAllocate(255, 255, 255) im:filledRectangle(0, 0, 127, 63, white) "
        "gd.fontCacheSetup() im:stringFT(im:colorAllocate(0, 0, 0), 'Arial', 96, 0, 18, 60, 'H') "
        "local saved = im:png(fields.path.value) gd.fontCacheShutdown() }%"
        "%{= im:sizeX() }%x%{= im:sizeY() }% %{= tostring(saved) }%"
    )
    target = tmp_path / "victim.png"
    fields = {"path": {"value": str(target), "defaultValue": str(target)}}
    out = templates.evaluate_template("lua", body, fields, {}, "Victim.proto")
    assert out == "128x64 false"
    assert not target.exists()


def test_a_lua_template_loads_no_bytecode_and_requires_no_file(tmp_path: Path) -> None:
    # Lua does not check bytecode (a forged chunk crashes it) and its file searcher opens any
    # path (/dev/stdin blocks): text chunks load, bytecode does not, and require finds only
    # the modules mazesim provides.
    (tmp_path / "mod.lua").write_text("return 42\n", encoding="utf-8")
    body = (
        "%{= tostring(string.dump) }%|%{= load('return 6 * 7')() }%"
        "|%{= tostring(load('\\27Lua')) }%"
        "%{ package.path = fields.dir.value .. '/?.lua' }%"
        "|%{= tostring((pcall(require, 'mod'))) }%|%{= require('wbgeometry') and 'ok' }%"
    )
    fields = {"dir": {"value": str(tmp_path), "defaultValue": ""}}
    assert templates.evaluate_template("lua", body, fields, {}, "Forge.proto") == (
        "nil|42|nil|false|ok"
    )


def test_a_forged_bytecode_chunk_is_a_world_format_error_not_a_crash() -> None:
    body = (
        "%{ local d = string.dump(function(a, b) return a + b end) "
        "local g = load(d:sub(1, 48) .. '\\0' .. d:sub(50), 'x', 'b') if g then g(1, 2) end }%"
    )
    with pytest.raises(WorldFormatError, match="Crash.proto"):
        templates.evaluate_template("lua", body, {}, {}, "Crash.proto")


def test_an_engine_that_crashes_or_waits_is_reported_not_followed() -> None:
    import signal
    import time

    crashed = templates._isolated(lambda: os.kill(os.getpid(), signal.SIGSEGV) or {}, 1.0)
    assert crashed == {"crashed": "SIGSEGV"}
    started = time.monotonic()
    waited = templates._isolated(lambda: time.sleep(600) or {}, 1.0, wall_seconds=0.5)
    assert waited == {"over_budget": True}
    assert time.monotonic() - started < 30.0


@pytest.mark.parametrize(
    ("language", "body"),
    [
        ("javascript", "%<= 'Group { } '.repeat(2000) >%"),
        ("lua", "%{= string.rep('Group { } ', 2000) }%"),
    ],
)
def test_a_template_that_makes_too_much_text_is_refused(
    language: str, body: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(templates, "MAX_TEMPLATE_TEXT", 10_000)
    with pytest.raises(WorldFormatError, match="more than the 10000 a template may make"):
        templates.evaluate_template(language, body, {}, {}, "Repeat.proto")


def test_a_lua_template_s_text_that_is_not_utf_8_is_said_so() -> None:
    with pytest.raises(WorldFormatError, match="not UTF-8"):
        templates.evaluate_template("lua", "%{= '\\255' }%", {}, {}, "Bytes.proto")
