"""What a Webots controller's Makefile asks of its build, read without running make.

Webots builds a C or C++ controller with the ``Makefile`` of its folder, which sets variables
and then includes Webots' ``Makefile.include`` (Webots' user guide, "Using Webots Makefiles"):
``C_SOURCES``, ``CXX_SOURCES`` or ``CPP_SOURCES`` (the sources to build, all of the folder's
when none is set, found in the folders make's ``VPATH`` variable and ``vpath`` directives for
sources name too), ``INCLUDE`` (``-I`` folders), ``CFLAGS`` and ``LIBRARIES`` (``-L`` folders,
``-l`` libraries). :func:`read_makefile` reads their simple assignments (``=``, ``:=``, ``+=``,
``?=``, lines continued by a backslash, ``$(VAR)`` naming a variable set before, make's
``$(wildcard PATTERN...)`` function, ``$(shell uname)``), relative paths being relative to the
controller's folder, and its conditionals (``ifeq``, ``ifneq``, ``ifdef``, ``ifndef``, ``else``)
as make on Linux takes them, Webots' builds there: ``$(shell uname)`` is ``Linux`` and a
variable neither the Makefile nor Webots sets (``$(OS)``, ``Windows_NT`` on Windows only) is
empty. Words naming Webots' own folders (``$(WEBOTS_HOME)``) are dropped, mazesim's controller
library standing for them; whatever else it cannot read (other make functions, a conditional
testing one, unknown options) is left out and named in :attr:`MakefileSettings.ignored`, for
the run's log.
"""

from __future__ import annotations

import glob
import os
import re
import shlex
import stat
from dataclasses import dataclass, field
from pathlib import Path

from mazesim._paths import MAX_TEXT_CHARACTERS

__all__ = [
    "LIBRARY_PACKAGES",
    "MAKEFILES",
    "MakefileSettings",
    "defines_main",
    "makefile",
    "makefile_main",
    "read_makefile",
]

#: The names of a controller's Makefile, as make looks for them.
MAKEFILES = ("GNUmakefile", "makefile", "Makefile")
#: The variables of Webots' ``Makefile.include`` naming a controller's sources.
SOURCE_VARIABLES = ("C_SOURCES", "CXX_SOURCES", "CPP_SOURCES")
#: Make's search path for every prerequisite (folders separated by colons or blanks).
SEARCH_VARIABLE = "VPATH"
#: A ``vpath PATTERN FOLDERS`` directive: make's search path for the names the pattern matches.
_VPATH_DIRECTIVE = re.compile(r"^vpath\s+(\S+)\s+(.+)$")
#: The names a source has (a ``vpath`` pattern for them is a search path for sources).
_SOURCE_SUFFIXES = (".c", ".cc", ".cpp", ".cxx", ".C")
#: The variables whose options the build takes.
OPTION_VARIABLES = ("INCLUDE", "CFLAGS", "LIBRARIES")
#: Webots' own controller libraries, which mazesim's library stands for.
WEBOTS_LIBRARIES = frozenset({"Controller", "CppController", "car", "driver", "CppCar"})
#: The Debian package providing a library a Makefile links (``-lNAME``), when known.
LIBRARY_PACKAGES = {
    "gsl": "libgsl-dev",
    "gslcblas": "libgsl-dev",
    "m": "libc6-dev",
    "pthread": "libc6-dev",
    "dl": "libc6-dev",
    "rt": "libc6-dev",
    "blas": "libblas-dev",
    "lapack": "liblapack-dev",
    "jsoncpp": "libjsoncpp-dev",
    "curl": "libcurl4-openssl-dev",
    "zmq": "libzmq3-dev",
}
#: Compiler options mazesim's build sets itself (optimisation, warnings, debugging).
_OWN_OPTIONS = re.compile(r"^-(?:O\w*|W.*|w|g\w*|pipe)$")
#: A C or C++ program's ``main`` function, defined at the start of a line.
_MAIN = re.compile(r"^[ \t]*(?:int|void)[ \t]+main[ \t]*\(", re.MULTILINE)
_ASSIGNMENT = re.compile(r"^(?:override\s+|export\s+)?([A-Za-z_]\w*)\s*(::=|:=|\+=|\?=|=)\s*(.*)$")
#: A folder of a Webots installation (``/usr/local/webots/include/controller/c``).
_WEBOTS_FOLDER = re.compile(r"\$\(WEBOTS_HOME\)|(?:^|/)(?:include|lib)/controller(?:/|$)")
_REFERENCE = re.compile(r"\$[({]([^)}]*)[)}]")
#: A rule's first line (``target: prerequisites``), not an assignment (``:=``, ``::=``).
_RULE = re.compile(r"^[^=:#\s][^=:#]*:(?![:=])")
_CONDITIONAL = re.compile(r"^(ifeq|ifneq|ifdef|ifndef|else|endif)\b\s*(.*)$")
#: What the shell commands a Makefile runs to learn its system print on Linux.
_SHELL_ON_LINUX = {"uname": "Linux", "uname -s": "Linux", "uname -o": "GNU/Linux"}
#: Variables Webots sets for the make it runs.
_WEBOTS_VARIABLES = frozenset({"WEBOTS_HOME", "WEBOTS_HOME_PATH"})


@dataclass
class MakefileSettings:
    """A controller Makefile's settings, as its build takes them.

    Attributes:
        sources: The sources it lists, found as make finds them, or None when it lists none
            (the folder's sources are built).
        compile_options: ``-I`` (absolute folders), ``-D`` and ``-U`` options.
        standards: ``-std=`` options.
        link_options: ``-L`` (absolute folders) and ``-l`` options, Webots' own left out.
        include_folders: The ``-I`` folders that exist (their headers are part of the build).
        ignored: What it sets that the build leaves out, for the run's log.
    """

    sources: list[Path] | None = None
    compile_options: list[str] = field(default_factory=list)
    standards: list[str] = field(default_factory=list)
    link_options: list[str] = field(default_factory=list)
    include_folders: list[Path] = field(default_factory=list)
    ignored: list[str] = field(default_factory=list)

    def note(self) -> str:
        """What the build left out of the Makefile, for the run's log ("" when nothing)."""
        if not self.ignored:
            return ""
        return " (its Makefile read without make; left out: " + "; ".join(self.ignored) + ")"


def makefile(folder: Path) -> Path | None:
    """The controller folder's Makefile, the first name make looks for, or None."""
    return next((folder / name for name in MAKEFILES if (folder / name).is_file()), None)


def makefile_main(folder: Path) -> Path | None:
    """The source that stands for the program a controller folder's Makefile builds, when the
    folder has a Makefile but no source named after it (``main.cpp`` and the classes its
    ``CXX_SOURCES`` lists): Webots' ``Makefile.include`` names the program after the folder
    whatever its sources are called, and Webots runs that program. The listed sources (the
    folder's own C and C++ sources when none is listed) are searched for the one defining
    ``main``; None without a Makefile or such a source."""
    found = makefile(folder)
    text = None if found is None else _text(found)
    if text is None:
        return None
    sources = read_makefile(folder, text).sources
    if sources is None:
        own = (p for p in folder.iterdir() if p.suffix in _SOURCE_SUFFIXES and p.is_file())
        sources = sorted(own)
    return next((source for source in sources if defines_main(source)), None)


def defines_main(path: Path) -> bool:
    """Whether the source file ``path`` defines a ``main`` function (False when it cannot be
    read or is longer than a source :func:`_text` reads)."""
    text = _text(path)
    return text is not None and _MAIN.search(text) is not None


def _text(path: Path) -> str | None:
    """The text of the regular file ``path`` of at most
    :data:`~mazesim._paths.MAX_TEXT_CHARACTERS` bytes, or None (another kind of file, a longer
    one, or one that cannot be read)."""
    try:
        if not stat.S_ISREG(os.stat(path).st_mode):  # a FIFO would wait for a writer
            return None
        with open(path, "rb") as handle:
            data = handle.read(MAX_TEXT_CHARACTERS + 1)
    except OSError:
        return None
    return None if len(data) > MAX_TEXT_CHARACTERS else data.decode("utf-8", errors="replace")


def _logical_lines(text: str) -> list[str]:
    """The Makefile's lines, continuations joined and comments removed, without the commands
    of its rules' recipes (lines starting with a tab after a rule; before the first rule, make
    reads a line starting with a tab as any other, an assignment indented under a conditional)."""
    text = text.replace("\r\n", "\n").replace("\\\n", " ")
    lines = []
    in_rules = False
    for line in text.split("\n"):
        if line.startswith("\t") and in_rules:
            continue  # a recipe's command
        line = re.sub(r"(?<!\\)#.*", "", line).strip()
        in_rules = in_rules or _RULE.match(line) is not None
        lines.append(line)
    return lines


def _variables(text: str, folder: Path, ignored: list[str]) -> dict[str, str]:
    """The Makefile's variables as its simple assignments set them, in order, under its
    conditionals as make on Linux takes them; the assignments of the variables the build takes
    that it cannot read (under a conditional it cannot test) are named in ``ignored``."""
    values: dict[str, str] = {}
    # Each open conditional: whether its branch under way is taken (None: unknown), and
    # whether one of its branches was.
    open_: list[list[bool | None]] = []
    for line in _logical_lines(text):
        conditional = _CONDITIONAL.match(line)
        if conditional:
            _branch(open_, conditional.group(1), conditional.group(2), values, folder)
            continue
        found = _ASSIGNMENT.match(line)
        if found is None:
            continue
        name, operator, value = found.groups()
        wanted = name in SOURCE_VARIABLES or name in OPTION_VARIABLES
        if any(frame[0] is False for frame in open_):
            continue  # a branch make does not take on Linux
        if any(frame[0] is None for frame in open_):
            if wanted:
                ignored.append(f"{name} set under a make conditional")
            continue
        value = _expand(value, values, name if wanted else "", ignored, folder)
        if operator == "+=":
            values[name] = f"{values.get(name, '')} {value}".strip()
        elif operator != "?=" or name not in values:
            values[name] = value
    return values


def _branch(
    open_: list[list[bool | None]], keyword: str, rest: str, values: dict[str, str], folder: Path
) -> None:
    """Opens, switches or closes a conditional of ``open_`` at the directive ``keyword rest``."""
    if keyword == "endif":
        if open_:
            open_.pop()
        return
    if keyword != "else":
        taken = _test(keyword, rest, values, folder)
        open_.append([taken, taken])
        return
    if not open_:
        return
    frame = open_[-1]
    chained = _CONDITIONAL.match(rest)
    if frame[1] is True:
        frame[0] = False
    elif frame[1] is None:
        frame[0] = None
    elif chained and chained.group(1) not in ("else", "endif"):
        frame[0] = _test(chained.group(1), chained.group(2), values, folder)
        frame[1] = frame[0]
    else:
        frame[0] = frame[1] = True


def _test(keyword: str, rest: str, values: dict[str, str], folder: Path) -> bool | None:
    """Whether a conditional's test holds as make on Linux finds it, or None when it names a
    make function this reader does not run."""
    if keyword in ("ifdef", "ifndef"):
        unknown: list[str] = []
        name = _expand(rest, values, "test", unknown, folder, empty_unset=True).strip()
        if unknown:
            return None
        defined = bool(values.get(name)) or name in _WEBOTS_VARIABLES
        return defined if keyword == "ifdef" else not defined
    operands = _operands(rest)
    if operands is None:
        return None
    unknown = []
    left, right = (
        _expand(o, values, "test", unknown, folder, empty_unset=True).strip() for o in operands
    )
    if unknown:
        return None
    return (left == right) if keyword == "ifeq" else (left != right)


def _operands(rest: str) -> tuple[str, str] | None:
    """The two operands of ``ifeq``'s ``(A,B)``, ``"A" "B"`` or ``'A' 'B'`` forms."""
    rest = rest.strip()
    if rest.startswith("(") and rest.endswith(")"):
        inner, depth = rest[1:-1], 0
        for index, character in enumerate(inner):
            depth += {"(": 1, ")": -1}.get(character, 0)
            if character == "," and depth == 0:
                return inner[:index], inner[index + 1 :]
        return None
    quoted = re.fullmatch(r"""(["'])(.*?)\1\s+(["'])(.*?)\3""", rest)
    return (quoted.group(2), quoted.group(4)) if quoted else None


def _expand(
    value: str,
    values: dict[str, str],
    name: str,
    ignored: list[str],
    folder: Path | None = None,
    empty_unset: bool = False,
) -> str:
    """``value`` with its ``$(VAR)`` references to variables set before replaced; Webots' own
    folders kept as ``$(WEBOTS_HOME)`` (dropped later); ``$(wildcard PATTERN...)`` replaced by
    the names in ``folder`` that match and ``$(shell uname)`` by what it prints on Linux;
    another make function left out (named in ``ignored`` when ``name`` is a variable the build
    takes), and so is a variable not set before, unless ``empty_unset``: then it is empty, as
    make finds it."""

    def replace(match: re.Match[str]) -> str:
        inner = match.group(1).strip()
        if inner in _WEBOTS_VARIABLES:
            return "$(WEBOTS_HOME)"
        if re.fullmatch(r"\w+", inner) and inner in values:
            return values[inner]
        if re.fullmatch(r"\w+", inner) and empty_unset:
            return ""
        function, _, patterns = inner.partition(" ")
        if function == "wildcard" and folder is not None:
            return " ".join(_wildcard(folder, patterns.split()))
        if function == "shell" and " ".join(patterns.split()) in _SHELL_ON_LINUX:
            return _SHELL_ON_LINUX[" ".join(patterns.split())]
        if name:
            ignored.append(f"$({inner}) in {name}")
        return ""

    return _REFERENCE.sub(replace, value)


def _wildcard(folder: Path, patterns: list[str]) -> list[str]:
    """Make's ``$(wildcard PATTERN...)`` run in ``folder``: the existing names each pattern
    matches, sorted as GNU make 4.3 sorts them."""
    return [
        os.path.relpath(path, folder)
        for pattern in patterns
        for path in sorted(glob.glob(os.path.join(folder, pattern)))
    ]


def _words(value: str, name: str, ignored: list[str]) -> list[str]:
    try:
        return shlex.split(value)
    except ValueError:
        ignored.append(f"{name} (unbalanced quotes)")
        return []


def _folder_option(flag: str, path: str, folder: Path) -> tuple[str, Path]:
    place = (folder / path).resolve()
    return f"{flag}{place}", place


def _options(words: list[str], name: str, folder: Path, settings: MakefileSettings) -> None:
    """Takes ``-I``, ``-D``, ``-U``, ``-std=``, ``-L`` and ``-l`` options from ``words``."""
    pending = ""
    for word in words:
        if pending:
            word, pending = pending + word, ""
        if word.startswith("--std="):
            word = word[1:]  # gcc takes both spellings
        if word in ("-I", "-D", "-U", "-L", "-l"):
            pending = word
        elif _WEBOTS_FOLDER.search(word):
            continue  # Webots' own folders: mazesim's library stands for them
        elif word.startswith("-I") and name != "LIBRARIES":
            option, place = _folder_option("-I", word[2:], folder)
            settings.compile_options.append(option)
            if place.is_dir():
                settings.include_folders.append(place)
        elif word.startswith(("-D", "-U")) and name != "LIBRARIES":
            settings.compile_options.append(word)
        elif word.startswith("-std=") and name != "LIBRARIES":
            settings.standards.append(word)
        elif word.startswith("-L") and name == "LIBRARIES":
            option, place = _folder_option("-L", word[2:], folder)
            if place.is_dir() and any(place.glob("*.dll*")):
                # A Windows build's libraries (MinGW's .dll and .dll.a beside its .a): this
                # system's linker cannot link them, the system's own are linked instead.
                settings.ignored.append(f"{word} (libraries built for Windows)")
            else:
                settings.link_options.append(option)
        elif word.startswith("-l") and name == "LIBRARIES":
            # MinGW's linker finds -llibgsl as libgsl.dll.a: the library gsl.
            library = word[5:] if word.startswith("-llib") and len(word) > 5 else word[2:]
            if library not in WEBOTS_LIBRARIES:
                settings.link_options.append(f"-l{library}")
        elif not _OWN_OPTIONS.match(word):
            settings.ignored.append(f"{word} in {name}")


def _search_folders(text: str, values: dict[str, str]) -> list[str]:
    """The folders make searches for a source it does not find in the controller's folder: the
    ``VPATH`` variable's and those of the ``vpath`` directives whose pattern names sources, in
    the Makefile's order, relative to the controller's folder."""
    folders = values.get(SEARCH_VARIABLE, "").replace(":", " ").split()
    for line in _logical_lines(text):
        directive = _VPATH_DIRECTIVE.match(line)
        if directive is None:
            continue
        pattern, places = directive.groups()
        if pattern == "%" or pattern.endswith(_SOURCE_SUFFIXES):
            folders += _expand(places, values, "", []).replace(":", " ").split()
    return [f"{place.rstrip('/')}/" for place in folders]


def _sources(names: list[str], folder: Path, search: list[str]) -> list[Path]:
    """The listed sources, found as make finds them: Webots' ``Makefile.include`` compiles each
    under its file name alone and make finds it by that name in the controller's folder, in the
    ``search`` folders (``VPATH``, ``vpath``), or, through Webots' own ``vpath``, in the folders
    of the listed sources (a source listed by a path that does not exist is found under its name
    in another listed folder). A name found nowhere is left out (make would stop there; the
    link then names what is undefined)."""
    places = search + sorted({f"{Path(name).parent.as_posix()}/" for name in names})
    found: list[Path] = []
    for name in names:
        candidates = [folder / name, folder / Path(name).name]
        candidates += [folder / place / Path(name).name for place in places]
        path = next((c.resolve() for c in candidates if c.is_file()), None)
        if path is not None and path not in found:
            found.append(path)
    return found


def read_makefile(folder: Path, text: str) -> MakefileSettings:
    """The settings of the Makefile ``text`` of the controller folder ``folder``."""
    settings = MakefileSettings()
    values = _variables(text, folder, settings.ignored)
    listed = [SOURCE_VARIABLES.index(name) for name in SOURCE_VARIABLES if name in values]
    if listed:
        names = []
        for index in listed:
            name = SOURCE_VARIABLES[index]
            names += [w for w in _words(values[name], name, settings.ignored)]
        kept = [name for name in names if not _WEBOTS_FOLDER.search(name)]
        search = _search_folders(text, values)
        settings.sources = _sources(kept, folder, search) if kept else None
    for name in OPTION_VARIABLES:
        if name in values:
            _options(_words(values[name], name, settings.ignored), name, folder, settings)
    return settings
