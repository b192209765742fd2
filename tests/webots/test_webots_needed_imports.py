"""A package a controller's module imports inside ``try`` but uses as the module loads (an
annotation of a method, a class's base) is one the controller needs: the run names it as
missing, as it names a package imported outside ``try`` (#32)."""

from __future__ import annotations

from pathlib import Path

from mazesim.webots.requirements import missing_packages

#: A helper module as a research project writes it: torch-like imports inside ``try``, a
#: stand-in for one of them in ``except``, and uses of the other in annotations.
NEEDED = """\
import math

try:
    import no_such_tensor_library
    import no_such_tensor_library.nn as nn
    AVAILABLE = True
except ImportError:
    AVAILABLE = False
    class nn:
        class Module:
            pass


class Adapter(nn.Module if AVAILABLE else object):
    def forward(self, window: no_such_tensor_library.Tensor) -> no_such_tensor_library.Tensor:
        return window
"""

#: Optional imports used only where Python evaluates them when the package is there.
OPTIONAL = """\
try:
    import no_such_plotting_library
except ImportError:
    no_such_plotting_library = None

try:
    import no_such_fast_maths
    FAST = True
except ImportError:
    FAST = False

SCALE = no_such_fast_maths.scale() if FAST else 1.0


def plot(values: list[float]) -> None:
    if no_such_plotting_library is not None:
        no_such_plotting_library.show(values)
"""

#: The same annotations in a module whose annotations Python does not evaluate.
POSTPONED = """\
from __future__ import annotations

try:
    import no_such_tensor_library
except ImportError:
    pass


def forward(window: no_such_tensor_library.Tensor) -> no_such_tensor_library.Tensor:
    return window
"""


def controller_importing(tmp_path: Path, module: str) -> Path:
    """A controller beside its own module ``helper`` of the text ``module``."""
    folder = tmp_path / "controllers" / "navigator"
    folder.mkdir(parents=True)
    (folder / "helper.py").write_text(module, encoding="utf-8")
    controller = folder / "navigator.py"
    controller.write_text("from controller import Robot\nimport helper\n", encoding="utf-8")
    return controller


def test_a_guarded_import_used_in_annotations_as_the_module_loads_is_needed(
    tmp_path: Path,
) -> None:
    controller = controller_importing(tmp_path, NEEDED)
    assert missing_packages(str(controller)) == ["no_such_tensor_library"]


def test_guarded_imports_used_only_when_present_or_in_functions_are_optional(
    tmp_path: Path,
) -> None:
    controller = controller_importing(tmp_path, OPTIONAL)
    assert missing_packages(str(controller)) == []


def test_annotations_a_module_postpones_do_not_make_an_import_needed(tmp_path: Path) -> None:
    controller = controller_importing(tmp_path, POSTPONED)
    assert missing_packages(str(controller)) == []
