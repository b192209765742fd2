"""Registers mazesim's gymnasium environments when gymnasium is imported, not before.

``import mazesim`` does not import gymnasium (with mazesim's envs some 120 modules, about half of
the import's time): it calls :func:`register_when_gymnasium_is_imported`, which registers the task
suite (:mod:`mazesim.envs.tasks`) at once when gymnasium is already imported, and otherwise adds an
import hook that registers it right after the first ``import gymnasium`` (or of any of its
submodules), in whichever order the two imports come. gymnasium 1.x has no plugin entry points,
so this is what lets ``gymnasium.make("mazesim/EPuckMaze-v0")`` find the ids after
``import mazesim``.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import sys
import types
from typing import Any

from mazesim._checks import ThenLoader

__all__ = ["register_when_gymnasium_is_imported"]

#: The module whose import registers the environments.
GYMNASIUM = "gymnasium"
#: The package that registers them when it is imported (:func:`mazesim.envs.register_envs`).
ENVS = "mazesim.envs"


def _register(_gymnasium: types.ModuleType | None = None) -> None:
    """Imports :mod:`mazesim.envs`, which registers the environments; nothing when it is imported
    or being imported already (its last line registers them)."""
    if ENVS not in sys.modules:
        importlib.import_module(ENVS)


class _GymnasiumFinder(importlib.abc.MetaPathFinder):
    """Finds gymnasium with the other finders, gives it the registering loader, and leaves
    ``sys.meta_path`` once it has done so."""

    def find_spec(
        self, fullname: str, path: Any, target: types.ModuleType | None = None
    ) -> importlib.machinery.ModuleSpec | None:
        if fullname != GYMNASIUM:
            return None
        for finder in [f for f in sys.meta_path if f is not self]:
            find = getattr(finder, "find_spec", None)
            spec = find(fullname, path, target) if find is not None else None
            if spec is not None:
                break
        else:
            return None  # not installed: the import fails as it would without mazesim
        if spec.loader is not None:
            spec.loader = ThenLoader(spec.loader, _register)
            sys.meta_path.remove(self)
        return spec


def register_when_gymnasium_is_imported() -> None:
    """Registers the environments now if gymnasium is imported, else when it is (once)."""
    if sys.modules.get(GYMNASIUM) is not None:
        _register()
    elif not any(isinstance(f, _GymnasiumFinder) for f in sys.meta_path):
        sys.meta_path.insert(0, _GymnasiumFinder())
