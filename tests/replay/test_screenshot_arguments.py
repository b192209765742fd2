"""The screenshot command's usage error quotes a long word in part, as every ``mazesim``
command's does: a fuzzed call of ``mazesim.replay.screenshot.main`` with one argument of
200,000 characters printed all of it back (#35, surface seed 20261223)."""

from __future__ import annotations

import pytest

from mazesim.replay.screenshot import main


def test_a_usage_error_quotes_a_long_word_in_part(capsys: pytest.CaptureFixture[str]) -> None:
    word = "x" * 200_000
    with pytest.raises(SystemExit) as ended:
        main(["page.html", "out.png", word])
    assert ended.value.code == 2
    said = capsys.readouterr().err
    assert "unrecognized arguments" in said
    assert len(said) < 5_000, len(said)
