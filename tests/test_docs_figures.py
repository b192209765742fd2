"""Issue 37: every figure a page shows that a run produced is either compared with a run by a
test or marked as a measurement with its machine and date (see ``docs_figures``)."""

from __future__ import annotations

from pathlib import Path

import pytest

from docs_figures import (
    CONSTANTS,
    GENERATED_PAGES,
    PAGE_CONSTANTS,
    figures_of,
    is_constant,
    is_marked,
    unaccounted_figures,
    units,
)

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


@pytest.mark.parametrize("page", PAGES, ids=lambda page: page.name)
def test_every_run_figure_of_a_page_is_checked_or_marked(page: Path) -> None:
    figures, problems = unaccounted_figures(page, ROOT)
    assert problems == []
    assert figures == [], (
        "figures from a run, neither checked by a test (<!-- checked: tests/... -->) nor marked "
        "with the machine and date (e.g. '(measured 2026-11-29, 2-core machine)'):\n"
        + "\n".join(str(figure) for figure in figures)
    )


def test_every_listed_constant_is_on_its_page() -> None:
    # A constant that left its page is no longer needed on the list.
    for name, constants in PAGE_CONSTANTS.items():
        page = ROOT / name if name == "README.md" else ROOT / "docs" / name
        shown = [
            figure
            for line in page.read_text(encoding="utf-8").splitlines()
            for figure in figures_of(line)
        ]
        assert set(constants) <= set(shown), (name, set(constants) - set(shown))
    assert all((ROOT / "docs" / name).is_file() for name in GENERATED_PAGES)


# --- what counts as a run figure, a mark, a check --------------------------------------------


@pytest.mark.parametrize(
    ("line", "figures"),
    [
        ("took 8.3 s and 1.7-1.8 s a run", ["8.3 s", "1.7-1.8 s"]),
        ("success 93 / 83 / 94 % and 100.0%", ["93 / 83 / 94 %", "100.0%"]),
        (
            "3.44 million env-steps/s, 2,770 control steps/s, 3.7x faster",
            ["2,770 control steps/s", "3.7x"],
        ),
        (
            "13,460 bytes, 0.45 MB, 3 GB, 12.6 kB, 5.8 µs",
            ["13,460 bytes", "0.45 MB", "3 GB", "12.6 kB", "5.8 µs"],
        ),
        # Limits in binary units, lengths, angles, code and link addresses are no run figures.
        ("at most 64 MiB; 7 cm; 6.28 rad/s; 1.7 cm bars", []),
        ("`--seconds 60 s` and [a page](perf.md#5-s)", []),
        ("mazesim-v1 and UTF-8, bytes", []),
    ],
)
def test_run_figures_are_numbers_with_a_runs_units(line: str, figures: list[str]) -> None:
    assert figures_of(line) == figures


def test_the_control_steps_are_constants_everywhere() -> None:
    assert is_constant("any.md", "32 ms") and is_constant("any.md", "64 ms")
    assert not is_constant("any.md", "31 ms")
    assert all(reason for _, reason in CONSTANTS)


def test_a_mark_needs_the_date_and_the_machine() -> None:
    assert is_marked("took 25 s (measured 2026-11-29, 2-core machine)")
    assert is_marked("on a quiet machine, 2026-11-24")
    assert not is_marked("took 25 s on a quiet machine")
    assert not is_marked("took 25 s on 2026-11-29")
    assert not is_marked("took 25 s <!-- 2026-11-29, 2-core machine -->")


PAGE = """# A page

Training took 25 s and reached 100 % of the goals.

It took 25 s (measured 2026-11-29, 2-core machine).

Measured on 2026-11-29 on a 2-core machine:

| task | time |
|---|---|
| a | 16-18 s |

| task | time |
|---|---|
| b | 40 s |

- an item of 5 %
- an item of 6 % (2026-11-29, 2-core machine)

<!-- checked: tests/test_memory.py -->
The bytes per env: 13,500 bytes.

<!-- checked: tests/test_other.py -->
The bytes per env: 13,600 bytes.

```text
printed 1024 robots in 54.31 s
```

<!-- output -->
```text
printed 1024 robots in 54.31 s
```

```python
print("3 s")  # 3 s
```
"""


def test_a_page_is_read_in_units_and_each_accounted_for_as_a_whole(tmp_path: Path) -> None:
    page = tmp_path / "page.md"
    page.write_text(PAGE, encoding="utf-8")
    (tmp_path / "tests").mkdir()
    (tmp_path / "tests" / "test_memory.py").write_text("PAGE = 'docs/page.md'\n")
    (tmp_path / "tests" / "test_other.py").write_text("PAGE = 'docs/index.md'\n")
    figures, problems = unaccounted_figures(page, tmp_path)
    assert problems == ["page.md:24: tests/test_other.py does not name page.md"]
    assert [(figure.line, figure.figure) for figure in figures] == [
        (3, "25 s"),
        (3, "100 %"),
        (15, "40 s"),
        (17, "5 %"),
        (27, "54.31 s"),
    ]
    headings = [unit for unit in units(PAGE) if unit.lines[0].startswith("#")]
    assert len(headings) == 1


def test_a_console_blocks_commands_are_not_read_and_its_output_is(tmp_path: Path) -> None:
    page = tmp_path / "page.md"
    page.write_text("```console\n$ sleep 5s\n$ mazesim bench\n12,345 steps/s\n```\n")
    figures, _ = unaccounted_figures(page, tmp_path)
    assert [(figure.line, figure.figure) for figure in figures] == [(4, "12,345 steps/s")]


def test_a_checked_marker_names_tests_that_exist(tmp_path: Path) -> None:
    page = tmp_path / "page.md"
    page.write_text("<!-- checked: tests/no_such_test.py -->\nIt took 25 s.\n", encoding="utf-8")
    figures, problems = unaccounted_figures(page, ROOT)
    assert figures == []
    assert problems == ["page.md:2: checked by tests/no_such_test.py, which does not exist"]
