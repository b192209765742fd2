"""Every code block of README.md and docs/*.md runs as written (see ``docs_blocks``).

Python blocks run with this interpreter, shell blocks under bash with this interpreter's folder
first on ``PATH`` (so ``mazesim ...`` is the installed command); the blocks of one page run in
order in one temporary folder, into which ``examples/`` is copied. ``MAZESIM_EXAMPLES_FAST=1``
is set, as for the examples. TOML blocks are parsed, world blocks loaded.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import mazesim
from docs_blocks import (
    PYTHON_LANGUAGES,
    SHELL_LANGUAGES,
    TOML_LANGUAGES,
    Block,
    build_site,
    console_commands,
    expand_snippets,
    missing_output_lines,
    parse_blocks,
    run_command,
)

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.9 and 3.10
    tomllib = pytest.importorskip("tomli")

REPO = Path(__file__).resolve().parent.parent
PAGES = [REPO / "README.md", *sorted((REPO / "docs").glob("*.md"))]
#: A guard against a block that hangs, not a speed requirement.
BLOCK_TIMEOUT_S = 300
README_MAX_LINES = 250


def _all_blocks() -> list[Block]:
    return [
        block
        for page in PAGES
        for block in parse_blocks(page, page.read_text(encoding="utf-8"), REPO)
    ]


BLOCKS = _all_blocks()
RUNNABLE = PYTHON_LANGUAGES | SHELL_LANGUAGES | TOML_LANGUAGES


@pytest.fixture(scope="module")
def page_folders(tmp_path_factory: pytest.TempPathFactory) -> dict[Path, Path]:
    """One working folder per page, shared by its blocks (created on first use)."""
    return {}


@pytest.fixture(scope="module")
def printed_by() -> dict[Path, tuple[Block, str]]:
    """The last block run of each page and what it printed (for the ``output`` blocks)."""
    return {}


def _page_folder(page: Path, folders: dict[Path, Path], factory: pytest.TempPathFactory) -> Path:
    if page not in folders:
        folder = factory.mktemp(page.stem)
        shutil.copytree(REPO / "examples", folder / "examples")
        folders[page] = folder
    return folders[page]


def run_block(block: Block, cwd: Path) -> subprocess.CompletedProcess[str]:
    """Runs a Python or shell block in ``cwd``; returns the finished process."""
    if block.language in PYTHON_LANGUAGES:
        argv = [sys.executable, "-c", block.text]
    else:
        script = console_commands(block.text) if block.language == "console" else block.text
        argv = ["bash", "-e", "-o", "pipefail", "-c", script]
    return run_command(argv, cwd, BLOCK_TIMEOUT_S)


@pytest.mark.parametrize(
    "block",
    [block for block in BLOCKS if block.language in RUNNABLE or block.is_output],
    ids=lambda block: block.where,
)
def test_code_block_runs(
    block: Block,
    page_folders: dict[Path, Path],
    printed_by: dict[Path, tuple[Block, str]],
    tmp_path_factory: pytest.TempPathFactory,
) -> None:
    if block.skip_reason is not None:
        pytest.skip(f"{block.where}: {block.skip_reason}")
    if block.is_output:
        if block.page not in printed_by:
            pytest.skip(f"{block.where}: shows the output of a block that did not run here")
        source, printed = printed_by[block.page]
        missing = missing_output_lines(block.text, printed)
        assert missing == [], (
            f"{block.where} shows lines that {source.where} did not print: {missing}\n"
            f"--- it printed\n{printed}"
        )
        return
    if block.language in TOML_LANGUAGES:
        tomllib.loads(block.text)
        if block.is_world:
            mazesim.World.from_toml(block.text, source=block.where)
        return
    cwd = _page_folder(block.page, page_folders, tmp_path_factory)
    finished = run_block(block, cwd)
    printed_by[block.page] = (block, finished.stdout)
    assert finished.returncode == 0, (
        f"{block.where} ({block.language}) exited with {finished.returncode}\n"
        f"--- stdout\n{finished.stdout}\n--- stderr\n{finished.stderr}"
    )


def test_every_block_names_its_language() -> None:
    unnamed = [block.where for block in BLOCKS if not block.language]
    assert unnamed == [], f"code blocks without a language (use text for output): {unnamed}"


def test_readme_is_short() -> None:
    lines = (REPO / "README.md").read_text(encoding="utf-8").splitlines()
    assert len(lines) <= README_MAX_LINES


def test_readme_quick_start_is_the_example_script() -> None:
    quickstart = (REPO / "examples" / "quickstart.py").read_text(encoding="utf-8")
    readme = [block for block in BLOCKS if block.page.name == "README.md"]
    readme_python = [block.text for block in readme if block.language == "python"]
    assert quickstart in readme_python


def test_relative_links_of_the_readme_and_pages_exist() -> None:
    link = re.compile(r"\]\((?!https?://|#|mailto:)([^)\s#]+)")
    missing = []
    for page in PAGES:
        for target in link.findall(page.read_text(encoding="utf-8")):
            if not (page.parent / target).exists():
                missing.append(f"{page.name}: {target}")
    assert missing == []


# --- the block parser --------------------------------------------------------------------------


def test_markers_count_only_directly_above_the_fence(tmp_path: Path) -> None:
    text = (
        "<!-- no-test: needs a cluster -->\n"
        "```bash\nray start --head\n```\n"
        "<!-- no-test: too far away -->\n\n"
        "```python\nprint(1)\n```\n"
        "<!-- world -->\n"
        "```toml\nformat = 'x'\n```\n"
    )
    first, second, third = parse_blocks(tmp_path / "page.md", text, tmp_path)
    assert (first.language, first.skip_reason, first.line) == ("bash", "needs a cluster", 2)
    assert second.skip_reason is None and second.text == "print(1)\n"
    assert third.is_world and not first.is_world


def test_indented_fences_and_snippets(tmp_path: Path) -> None:
    (tmp_path / "script.py").write_text("print('from a file')\n")
    text = '- a list item:\n\n  ```python\n  x = 1\n  --8<-- "script.py"\n  ```\n'
    (block,) = parse_blocks(tmp_path / "page.md", text, tmp_path)
    assert block.text == "x = 1\nprint('from a file')\n"
    assert expand_snippets("plain\n", tmp_path) == "plain\n"


def test_an_unclosed_fence_is_an_error(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="page.md:2"):
        parse_blocks(tmp_path / "page.md", "text\n```python\nprint(1)\n", tmp_path)


def test_console_blocks_run_their_prompted_lines_only(tmp_path: Path) -> None:
    text = "```console\n$ mazesim worlds\nsome output that is no command\n```\n"
    (block,) = parse_blocks(tmp_path / "page.md", text, tmp_path)
    assert console_commands(block.text) == "mazesim worlds\n"
    assert run_block(block, tmp_path).returncode == 0


def test_a_failing_block_fails(tmp_path: Path) -> None:
    (bad,) = parse_blocks(tmp_path / "page.md", "```bash\nmazesim no-such-command\n```\n", tmp_path)
    assert run_block(bad, tmp_path).returncode != 0
    (good,) = parse_blocks(tmp_path / "page.md", "```sh\nmazesim worlds\n```\n", tmp_path)
    finished = run_block(good, tmp_path)
    assert finished.returncode == 0 and "seed-maze" in finished.stdout


def test_api_reference_reads_the_core_stub() -> None:
    griffe = pytest.importorskip("griffe", reason="the docs tools are not installed (make docs)")
    package = griffe.load("mazesim", search_paths=[str(REPO / "python")])
    core = package["_core"]
    # Annotations that only the stub has: the compiled module carries no types.
    assert str(core["World"]["wall_boxes"].returns) == "npt.NDArray[np.float64]"
    mask = core["BatchSimulator"]["reset"].parameters["mask"]
    assert str(mask.annotation) == "npt.NDArray[np.bool_] | None"


#: The optional packages ``make docs`` does without: the API page is read from the sources.
NOT_FOR_THE_DOCS = ("torch", "stable_baselines3", "sb3_contrib", "pettingzoo")


def test_the_site_builds_strict_without_torch_stable_baselines3_or_pettingzoo(
    tmp_path: Path,
) -> None:
    pytest.importorskip("mkdocs", reason="the docs tools are not installed (make docs-deps)")
    built = build_site(REPO, tmp_path / "site", hidden=NOT_FOR_THE_DOCS)
    assert built.returncode == 0, built.stderr
    api = (tmp_path / "site" / "api.html").read_text(encoding="utf-8")
    assert "MazesimVecEnv" in api and "make_vec_env" in api  # the SB3 adapter's page
    assert "maze_goals_v0" in api  # the PettingZoo envs'


def test_output_blocks_name_the_lines_that_differ(tmp_path: Path) -> None:
    page = tmp_path / "page.md"
    text = "```bash\necho hi\n```\n\n<!-- output -->\n```text\nhi   there\n...\nbye\n```\n"
    blocks = parse_blocks(page, text, tmp_path)
    assert [b.is_output for b in blocks] == [False, True]
    assert missing_output_lines(blocks[1].text, "hi there\nmore\n") == ["bye"]
    assert missing_output_lines(blocks[1].text, "hi there\nbye\n") == []


#: What cites the report: "the report('s)", its algorithms, listings, chapters, Table 4.1 and
#: the figures of its chapter 4 ("the report above" on the Webots page is the import's report).
REPORT_CITATION = re.compile(
    r"\bthe (?:source )?report's\b|\bthe report\b(?! above)|\bAlg\. \d|\bTable 4\.\d"
    r"|\bFigs?\. 4\.\d|\bListing 3\.\d|\bchapter [2-5]\b"
)


def first_report_citation(text: str) -> str | None:
    """The paragraph (or table) of a page's first citation of the report, if any."""
    for paragraph in re.split(r"\n[ \t]*\n", text):
        if REPORT_CITATION.search(paragraph):
            return paragraph
    return None


@pytest.mark.parametrize("page", [p for p in PAGES if p.name != "report.md"], ids=lambda p: p.name)
def test_a_page_that_cites_the_report_links_it_where_it_first_does(page: Path) -> None:
    paragraph = first_report_citation(page.read_text(encoding="utf-8"))
    target = "report.md" if page.parent.name == "docs" else "docs/report.md"
    if paragraph is not None:
        assert f"]({target})" in paragraph, (
            f"{page.name}: cites the report here, unlinked:\n{paragraph}"
        )


def test_the_report_citation_finder() -> None:
    assert first_report_citation("intro\n\nAs in Alg. 7, it reads.\nmore\n\nTable 4.1") == (
        "As in Alg. 7, it reads.\nmore"
    )
    assert first_report_citation("the report above lists the warnings") is None
    assert (REPO / "docs" / "report.md").read_text(encoding="utf-8").startswith("# The report")


def test_the_rl_page_says_how_to_set_torchs_threads() -> None:
    # Issue 37: torch's default threads slowed PPO several times on 2 cores; the advice was in a
    # code comment only.
    page = (REPO / "docs" / "rl.md").read_text(encoding="utf-8")
    prose = re.sub(r"```.*?```", "", page, flags=re.DOTALL)
    assert "**Set torch's threads.**" in prose
    assert "torch.set_num_threads(1)" in prose and "OMP_NUM_THREADS=1" in prose
    python = [b.text for b in BLOCKS if b.page.name == "rl.md" and b.language == "python"]
    assert any("torch.set_num_threads(1)" in text for text in python)


#: What a page says before its first block that uses the checkout's own files.
FROM_THE_ROOT = "from the repository's root"


def test_a_block_that_uses_the_checkouts_examples_says_it_runs_from_the_root() -> None:
    # The tests run every block beside a copy of examples/; a reader in another folder, or with
    # the wheel alone, has none, and must be told where these commands run.
    untold = []
    for block in BLOCKS:
        if block.skip_reason is not None or block.language not in RUNNABLE - TOML_LANGUAGES:
            continue
        if not re.search(r"(?<![\w/.-])examples/", block.text):
            continue
        before = "\n".join(block.page.read_text().splitlines()[: block.line - 1])
        if FROM_THE_ROOT not in before.replace("\n", " "):
            untold.append(block.where)
    assert untold == [], (
        f"blocks that use examples/ on pages that do not first say they run {FROM_THE_ROOT!r}: "
        f"{untold}"
    )
