"""``mazesim info`` prints what a bug report needs, quickly and without importing the packages
it lists (#37)."""

from __future__ import annotations

import platform
import subprocess
import sys

import pytest

import mazesim
from mazesim.cli import main
from mazesim.cli.info import OPTIONAL_PACKAGES


def test_info_names_the_version_python_platform_and_every_package(
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert main(["info"]) == 0
    lines = dict(line.split(None, 1) for line in capsys.readouterr().out.splitlines() if line)
    assert lines["mazesim"] == mazesim.__version__
    assert lines["python"].startswith(platform.python_version())
    for package in OPTIONAL_PACKAGES:
        assert package in lines, package
    assert lines["numpy"] != "not installed"


def test_info_imports_none_of_the_packages_it_lists() -> None:
    """The versions come from the packages' metadata: a broken or slow-to-import optional
    package (torch) does not stop a bug report (gymnasium is imported by `import mazesim`,
    which registers its envs)."""
    probe = (
        "import sys; from mazesim.cli import main; main(['info']); "
        "print('IMPORTED', sorted(m for m in ('torch', 'ray', 'pettingzoo', "
        "'stable_baselines3', 'selenium') if m in sys.modules))"
    )
    result = subprocess.run(
        [sys.executable, "-c", probe], capture_output=True, text=True, timeout=120, check=True
    )
    assert "IMPORTED []" in result.stdout, result.stdout
