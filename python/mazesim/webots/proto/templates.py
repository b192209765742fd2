"""Procedural PROTO bodies evaluated with real template engines: JavaScript (``%< >%``,
``%<= >%``; Webots R2022b and later) with QuickJS (PyPI ``quickjs``), Lua (``%{ }%``,
``%{= }%``; earlier versions) with Lua 5.4 (PyPI ``lupa``). The body is turned into a script
that appends its text pieces and the values of its expressions to an output; ``import`` lines
of the helper modules become constants defined from ``template_modules``."""

from __future__ import annotations

import faulthandler
import json
import math
import os
import re
import resource
import select
import signal
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from mazesim._paths import read_input
from mazesim.errors import RegisteredName, _known_name

from .syntax import located_error
from .template_modules import JAVASCRIPT_MODULES, LUA_MODULES
from .values import to_javascript, to_lua

__all__ = ["evaluate_template"]


@dataclass(frozen=True)
class TemplateBudget:
    """What one template may spend, whatever its language: seconds of processor time and bytes
    of memory. Every engine runs under it, so a hostile PROTO (``while true do end``, a string
    grown without end) stops with a ``WorldFormatError`` naming the PROTO."""

    seconds: float = 10.0
    memory_bytes: int = 256 * 1024 * 1024


#: The budget of every template.
BUDGET = TemplateBudget()
#: Most characters of text one template may make (a PROTO's whole body is rarely a megabyte; a
#: template that repeats a node ten million times would ask for gigabytes once parsed).
MAX_TEMPLATE_TEXT = 32 * 1024 * 1024
#: Wall-clock seconds a template's process may take, a multiple of the processor budget: one
#: that waits without computing (on a file that never ends) is stopped too.
_WALL_SECONDS = 6 * BUDGET.seconds

#: Lua instructions between two looks at the clock.
_LUA_CLOCK_EVERY = 10_000

_IMPORT = re.compile(
    r"""import\s+(?:\*\s+as\s+(?P<alias>\w+)|\{(?P<names>[^}]*)\})\s+from\s+['"](?P<module>[\w./-]+?)(?:\.js)?['"]\s*;?"""
)


def without_comments(body: str) -> str:
    """The body without its ``#`` comments, which prevail over template statements in Webots
    (a ``#`` inside a double-quoted string is kept)."""
    lines = []
    for line in body.split("\n"):
        quoted = False
        for index, char in enumerate(line):
            if char == '"' and (index == 0 or line[index - 1] != "\\"):
                quoted = not quoted
            elif char == "#" and not quoted:
                line = line[:index]
                break
        lines.append(line)
    return "\n".join(lines)


def _pieces(body: str, opening: str, closing: str, origin: str) -> list[tuple[str, str]]:
    """The body as ("text" | "code" | "expression", content) pieces."""
    pieces: list[tuple[str, str]] = []
    position = 0
    while True:
        start = body.find(opening, position)
        if start < 0:
            pieces.append(("text", body[position:]))
            return pieces
        pieces.append(("text", body[position:start]))
        end = body.find(closing, start + len(opening))
        if end < 0:
            raise located_error(
                f"expected '{closing}' closing the template opened by '{opening}'",
                origin,
                body,
                start,
            )
        code = body[start + len(opening) : end]
        if code.startswith("="):
            pieces.append(("expression", code[1:]))
        else:
            pieces.append(("code", code))
        position = end + len(closing)


def _javascript(body: str, fields: dict[str, Any], context: dict[str, Any], origin: str) -> str:
    imports: list[str] = []

    def hoist(match: re.Match[str]) -> str:
        module = match.group("module").rsplit("/", 1)[-1]
        if module not in JAVASCRIPT_MODULES:
            raise located_error(
                f"the template imports '{module}.js', which mazesim does not provide", origin
            )
        if match.group("alias"):
            imports.append(f"const {match.group('alias')} = __modules[{json.dumps(module)}];")
        else:
            imports.append(f"const {{{match.group('names')}}} = __modules[{json.dumps(module)}];")
        return ""

    script = []
    for kind, content in _pieces(body, "%<", ">%", origin):
        if kind == "text":
            script.append(f"__out.push({json.dumps(content)});")
        elif kind == "expression":
            script.append(f"__out.push(__text({content}));")
        else:
            script.append(_IMPORT.sub(hoist, content))
    modules = ", ".join(
        f"{json.dumps(name)}: {source}" for name, source in JAVASCRIPT_MODULES.items()
    )
    program = "\n".join(
        [
            "(function () {",
            '"use strict";',
            "const __out = [];",
            "const __text = (v) => String(v);",
            "const console = {log: () => {}, debug: () => {}, info: () => {}, warn: () => {}, "
            "error: (...a) => __errors.push(a.join(' '))};",
            f"const __modules = {{{modules}}};",
            f"const fields = {to_javascript(fields)};",
            f"const context = {to_javascript(context)};",
            "const wbfile = {fileExists: (p) => __file_exists(p), "
            "readTextFile: (p) => __read_text(p), writeTextFile: () => false};",
            *imports,
            *script,
            "return __out.join('');",
            "})()",
        ]
    )
    import quickjs  # noqa: F401 - a missing engine is said here, not in the child

    outcome = _isolated(lambda: _run_javascript(program), BUDGET.seconds)
    return _text_of(outcome, "JavaScript", origin)


def _text_of(outcome: dict[str, Any], language: str, origin: str) -> str:
    """The text a template's process made, or the ``WorldFormatError`` of why it made none."""
    if "text" in outcome:
        return str(outcome["text"])
    first = str(outcome.get("error", ""))
    if outcome.get("crashed"):
        raise located_error(
            f"its {language} template crashed the template engine ({outcome['crashed']}); fix"
            " the PROTO",
            origin,
        )
    over = ("interrupted", "out of memory", "not enough memory", "__mazesim_over_budget__")
    if outcome.get("over_budget") or any(word in first for word in over):
        what = first.replace("__mazesim_over_budget__", "still running")
        raise located_error(_over_budget(language, what or "still running"), origin)
    raise located_error(f"its {language} template fails: {first}", origin)


def _made(text: str) -> dict[str, Any]:
    """A template's outcome for the text it made: the text, or why it is too long."""
    if len(text) > MAX_TEMPLATE_TEXT:
        return {
            "error": f"it makes {len(text)} characters of text, more than the"
            f" {MAX_TEMPLATE_TEXT} a template may make (a template that repeats a node without"
            " end; fix the PROTO)"
        }
    return {"text": text}


def _run_javascript(program: str) -> dict[str, Any]:
    """Runs a template's program in QuickJS under the budget: its text, or the engine's error."""
    import quickjs

    engine = quickjs.Context()
    # The budget's time is the child process's processor limit (see _isolated): QuickJS's own
    # time limit would refuse every call back into Python (a template's wbfile.readTextFile).
    engine.set_memory_limit(BUDGET.memory_bytes)
    engine.add_callable("__file_exists", lambda path: os.path.isfile(str(path)))
    engine.add_callable("__read_text", _read_text)
    engine.eval("var __errors = [];")
    try:
        return _made(str(engine.eval(program)))
    except quickjs.JSException as error:
        first = str(error).strip().splitlines()[0] if str(error).strip() else repr(error)
        return {"error": first}


def _isolated(
    run: Callable[[], dict[str, Any]], seconds: float, wall_seconds: float | None = None
) -> dict[str, Any]:
    """What ``run`` returns, run in a child process of its own under ``seconds`` of processor
    time (``RLIMIT_CPU``, whole seconds): the one way a template engine runs when it cannot be
    stopped from inside. QuickJS's time limit is not looked at in its regular expressions
    (``/^(a+)+$/`` on 40 letters runs for hours) and it heeds no Ctrl-C while it runs; a child
    is stopped either way: Ctrl-C kills it and goes on as a ``KeyboardInterrupt``, the
    processor limit kills it (``{"over_budget": True}``), and so does running more than
    ``wall_seconds`` of wall-clock time (by default :data:`_WALL_SECONDS`: waiting on a file
    that never ends); a child the
    engine crashes (a Lua template's forged bytecode) reports ``{"crashed": "SIGSEGV"}``."""
    read_end, write_end = os.pipe()
    child = os.fork()
    if child == 0:  # pragma: no cover - the child reports through the pipe
        status = 1
        try:
            os.close(read_end)
            signal.signal(signal.SIGINT, signal.SIG_DFL)
            faulthandler.disable()  # an engine that crashes is reported, not dumped
            limit = max(1, math.ceil(seconds))
            resource.setrlimit(resource.RLIMIT_CPU, (limit, limit + 1))
            try:
                reported = run()
            except Exception as error:  # noqa: BLE001 - reported to the parent as the engine's
                reported = {"error": f"{type(error).__name__}: {error}"}
            data = json.dumps(reported).encode("utf-8")
            view = memoryview(data)
            while view:
                view = view[os.write(write_end, view) :]
            status = 0
        finally:
            os._exit(status)
    os.close(write_end)
    chunks: list[bytes] = []
    deadline = time.monotonic() + (_WALL_SECONDS if wall_seconds is None else wall_seconds)
    try:
        while True:
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([read_end], [], [], left)[0]:
                os.kill(child, signal.SIGKILL)
                os.waitpid(child, 0)
                return {"over_budget": True}
            chunk = os.read(read_end, 1 << 20)
            if not chunk:
                break
            chunks.append(chunk)
        _, status = os.waitpid(child, 0)
    except BaseException:  # Ctrl-C (or any error) while the child runs: it ends now
        os.kill(child, signal.SIGKILL)
        os.waitpid(child, 0)
        raise
    finally:
        os.close(read_end)
    if os.WIFEXITED(status) and os.WEXITSTATUS(status) == 0:
        outcome: dict[str, Any] = json.loads(b"".join(chunks))
        return outcome
    if os.WIFSIGNALED(status) and os.WTERMSIG(status) not in (signal.SIGXCPU, signal.SIGKILL):
        return {"crashed": signal.Signals(os.WTERMSIG(status)).name}
    return {"over_budget": True}


def _over_budget(language: str, what: str) -> str:
    return (
        f"its {language} template ran over the budget of every template ({BUDGET.seconds:g} s"
        f" of processor time, {BUDGET.memory_bytes // (1024 * 1024)} MiB of memory): {what}"
        " (a template that loops without end, or builds text without end; fix the PROTO)"
    )


def _read_text(path: Any) -> str:
    return read_input(str(path), 4 * 1024 * 1024, "a file a PROTO template reads")[
        : 4 * 1024 * 1024
    ].decode("utf-8", errors="replace")


#: Webots' Lua has io and os; here ``io.open`` reads a regular file through the package's
#: bounded reader (never a FIFO or a device), writes nothing, and nothing is run. Every
#: coroutine runs under the same clock hook as the main chunk; ``debug`` is then taken away so
#: a template cannot lift the hook, and ``require`` hands out the same sandboxed ``io``, a
#: ``debug`` of ``getinfo`` alone (a template names its texture files by its source) and no
#: native library (``package.loadlib`` and the C searchers are gone; ``dofile`` and
#: ``loadfile``, which read any file unbounded, too), only the modules mazesim provides (the
#: searcher of Lua files, which opens any path, is gone) and ``load`` of text alone (Lua does
#: not check bytecode: ``string.dump`` is gone too). The template runs in a process of its own
#: (:func:`_isolated`): the clock hook does not stop a pattern match, which runs in C.
_LUA_SANDBOX = """
function(read_text, seconds, every, pulse)
  local clock, sethook, create, wrap = os.clock, debug.sethook, coroutine.create, coroutine.wrap
  local deadline = clock() + seconds
  local function over()
    pulse()
    if clock() > deadline then error("__mazesim_over_budget__", 0) end
  end
  sethook(over, "", every)
  coroutine.create = function(f) local co = create(f); sethook(co, over, "", every); return co end
  coroutine.wrap = function(f)
    local co = coroutine.create(f)
    return function(...)
      local result = table.pack(coroutine.resume(co, ...))
      if not result[1] then error(result[2], 0) end
      return table.unpack(result, 2, result.n)
    end
  end
  local function string_file(text)
    local at, file = 1, {}
    function file:read(how)
      how = how or "l"
      if type(how) == "string" then how = how:gsub("^%*", ""):sub(1, 1) end
      if at > #text then return nil end
      if how == "a" then local rest = text:sub(at); at = #text + 1; return rest end
      if type(how) == "number" then
        local part = text:sub(at, at + how - 1); at = at + how; return part
      end
      if how == "n" then
        local s, e = text:find("^%s*[-+]?[%w%.]+", at)
        if not s then return nil end
        at = e + 1
        return tonumber(text:sub(s, e))
      end
      local e = text:find("\\n", at, true)
      local line = text:sub(at, (e or #text + 1) - 1)
      at = (e or #text) + 1
      if how == "L" and e then return line .. "\\n" end
      return line
    end
    function file:lines(how) return function() return file:read(how) end end
    function file:close() return true end
    return file
  end
  io = {open = function(name, mode)
    if mode ~= nil and mode:sub(1, 1) ~= "r" then
      return nil, name .. ": templates write no files"
    end
    local ok, text = pcall(read_text, name)
    if not ok then return nil, tostring(text) end
    return string_file(text)
  end}
  print = function() end
  os.execute = nil; os.remove = nil; os.rename = nil; os.exit = nil; os.tmpname = nil
  -- What require hands out is the sandbox's too: no native library, no real io or debug.
  package.loaded.io = io
  package.loaded.debug = {getinfo = function() return {source = "=proto", short_src = "proto"} end}
  package.loadlib = nil; package.cpath = ""; package.path = ""
  package.searchers[2] = nil; package.searchers[3] = nil; package.searchers[4] = nil
  dofile = nil; loadfile = nil
  -- Text chunks only: Lua does not check bytecode, and a forged chunk crashes it.
  local text_load = load
  load = function(chunk, name, _, env) return text_load(chunk, name, "t", env) end
  string.dump = nil
  debug = nil
end
"""


def _pulse() -> None:
    """Called by a Lua template's hook: Python's signal handlers (Ctrl-C) run here."""


def _lua(body: str, fields: dict[str, Any], context: dict[str, Any], origin: str) -> str:
    import lupa  # noqa: F401 - a missing engine is said here, not in the child

    script = [
        "local __out = {}",
        f"fields = {to_lua(fields)}",
        f"context = {to_lua(context)}",
    ]
    for kind, content in _pieces(body, "%{", "}%", origin):
        if kind == "text":
            script.append(f"__out[#__out + 1] = {to_lua(content)}")
        elif kind == "expression":
            script.append(f"__out[#__out + 1] = tostring({content})")
        else:
            script.append(content)
    script.append("return table.concat(__out)")
    program = "return function() " + "\n".join(script) + "\nend"
    return _text_of(_isolated(lambda: _run_lua(program), BUDGET.seconds), "Lua", origin)


def _run_lua(program: str) -> dict[str, Any]:
    """Runs a Lua template's program in Lua 5.4 under the budget, in the sandbox: its text,
    or the engine's error."""
    import lupa

    runtime = lupa.LuaRuntime(
        unpack_returned_tuples=True, register_eval=False, max_memory=BUDGET.memory_bytes
    )
    preload = runtime.eval("package.preload")
    for name, source in LUA_MODULES.items():
        preload[name] = runtime.eval(f"function(...) {source} end")
    try:
        chunk = runtime.execute(program)
        runtime.eval(_LUA_SANDBOX)(_read_text, BUDGET.seconds, _LUA_CLOCK_EVERY, _pulse)
        return _made(str(chunk()))
    except lupa.LuaMemoryError as error:
        return {"error": str(error) or "out of memory"}
    except lupa.LuaError as error:
        return {"error": str(error)}
    except UnicodeDecodeError as error:
        return {"error": f"the text it makes is not UTF-8 ({error.reason} at byte {error.start})"}


def evaluate_template(
    language: RegisteredName,
    body: str,
    fields: dict[str, Any],
    context: dict[str, Any],
    origin: str,
) -> str:
    """The text a procedural PROTO body generates.

    Args:
        language: ``"javascript"`` or ``"lua"``.
        body: The body with its template statements.
        fields: Each field's ``{"value": ..., "defaultValue": ...}``.
        context: Webots' ``context`` object (``world``, ``proto``, ``os``, ``id``...).
        origin: The PROTO's file or URL, for messages.

    Raises:
        WorldFormatError: The template does not run (with the engine's message).
    """
    _known_name(language, f"evaluate_template's language of {origin}", ("javascript", "lua"))
    body = without_comments(body)
    if language == "javascript":
        return _javascript(body, fields, context, origin)
    return _lua(body, fields, context, origin)
