"""Webots' Python API as names: one table of every class's methods, properties and constants
(``webots_api.toml`` beside this module, with its sources), which decides what a controller may
ask of mazesim's classes.

A name of the table that a mazesim class does not define answers as Webots' API has it: a method
prints Webots-style ``Error: <Class>.<name>() is not available in mazesim`` on stderr and returns
None; a property reads its getter and, when Webots' property has a setter, assigning it calls the
setter, so a class that defines ``getValue`` has ``value`` by construction. Any other missing
name raises ``AttributeError``, as it does in Webots: a misspelt ``robot.getDevcie`` stops the
controller there, with Python's own "Did you mean" suggestion.
"""

from __future__ import annotations

import functools
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from mazesim._toml import load_toml
from mazesim.errors import _shown

__all__ = ["NotSimulated", "webots_class", "webots_classes", "webots_property"]

#: The table: one TOML table per class of Webots' ``controller`` package.
TABLE = Path(__file__).with_name("webots_api.toml")


@dataclass(frozen=True)
class WebotsClass:
    """The names one class of Webots' Python API has, its base classes' included."""

    methods: frozenset[str]
    #: property name -> (getter method, setter method); "" when Webots' property has none.
    properties: dict[str, tuple[str, str]]
    constants: frozenset[str]

    def has(self, name: str) -> bool:
        """Whether the name is one of the class's methods, properties or constants."""
        return name in self.methods or name in self.properties or name in self.constants


@functools.cache
def webots_classes() -> dict[str, WebotsClass]:
    """Every class of the table by its Webots name, with what it inherits."""
    raw = load_toml(TABLE.read_text(encoding="utf-8"), TABLE.name)
    merged: dict[str, WebotsClass] = {}

    def resolve(name: str) -> WebotsClass:
        if name not in merged:
            entry = raw[name]
            inherited = [resolve(base) for base in entry.get("bases", [])]
            properties: dict[str, tuple[str, str]] = {}
            for base in inherited:
                properties.update(base.properties)
            for prop, methods in entry.get("properties", {}).items():
                getter, setter = (methods, "") if isinstance(methods, str) else methods
                properties[prop] = (getter, setter)
            merged[name] = WebotsClass(
                methods=frozenset(entry.get("methods", [])).union(
                    *(base.methods for base in inherited)
                ),
                properties=properties,
                constants=frozenset(entry.get("constants", [])).union(
                    *(base.constants for base in inherited)
                ),
            )
        return merged[name]

    for name in raw:
        resolve(name)
    return merged


def webots_class(cls: type) -> str | None:
    """The Webots class a class stands for: its own name or, for a controller's subclass
    (``class EpuckRobot(Robot)``), the name of the mazesim class it derives from; None when
    neither is in the table."""
    classes = webots_classes()
    for klass in cls.__mro__:
        if klass.__module__.startswith("mazesim.") and _named(klass) in classes:
            return _named(klass)
    return None


def _named(cls: type) -> str:
    """The Webots name of one of mazesim's classes: its own name, or its ``_webots_name`` (a
    private base class, ``_Sensor``, that Webots' API names ``Sensor``)."""
    return str(vars(cls).get("_webots_name", cls.__name__))


def webots_property(getter: str, setter: str = "", name: str = "") -> Any:
    """The property style of a Webots method, as Webots' Python API pairs them: reading the
    property calls ``getter`` and, when ``setter`` is given, assigning it calls ``setter``
    (without ``getter``, a property that is only assigned, as ``Motor.force``).

    A property Webots reads only (``Robot.name``, ``Robot.time``) that a controller assigns
    (``name`` given) holds what it was given from then on, for that object: Webots' Python API
    before R2023b had no properties, and its controllers keep their own data in such names
    (``self.name = self.getName()`` in a Robot subclass), which R2023b's read-only properties
    would refuse."""
    read = (lambda self: getattr(self, getter)()) if getter else None
    write = (lambda self, value: getattr(self, setter)(value)) if setter else None
    said = [f"reading it calls :meth:`{getter}`"] if getter else []
    said += [f"assigning it calls :meth:`{setter}`"] if setter else []
    if getter and not setter and name:
        own = f"_assigned_{name}"

        def read(self: Any) -> Any:
            assigned = getattr(self, "__dict__", {})
            return assigned[own] if own in assigned else getattr(self, getter)()

        def write(self: Any, value: Any) -> None:
            self.__dict__[own] = value

        said.append("a controller's own value once it assigns one (as before R2023b)")
    return property(read, write, doc=f"Webots' property: {'; '.join(said)}.")


def _defined(cls: type, name: str) -> bool:
    """Whether ``cls`` or a base class defines ``name`` (a property that is only assigned, when
    it is read)."""
    return any(name in vars(klass) for klass in cls.__mro__)


def _not_simulated(owner: str, name: str, call: str = "()") -> Callable[..., None]:
    def not_simulated(*args: Any, **kwargs: Any) -> None:
        print(f"Error: {owner}.{name}{call} is not available in mazesim.", file=sys.stderr)

    return not_simulated


class NotSimulated:
    """Mixin of every class of Webots' API: what the table lists and the class does not define
    answers as Webots' API has it; the class gets each of its Webots properties whose name it
    does not define (from the getter and setter the table pairs it with)."""

    #: Webots' API answers a NaN argument itself, as Webots does (``Motor.setVelocity(nan)``
    #: prints Webots' error and is ignored): the surface check lets NaN through to it
    #: (``mazesim._checks``, which refuses NaN for a number elsewhere).
    _takes_nan = True

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        found = webots_classes().get(_named(cls))
        if found is None or not cls.__module__.startswith("mazesim."):
            return
        for name, (getter, setter) in found.properties.items():
            if not hasattr(cls, name) and (getter or setter):
                setattr(cls, name, webots_property(getter, setter, name))

    if not TYPE_CHECKING:  # at run time only: mypy keeps checking mazesim's own names

        def __getattr__(self, name: str) -> Any:
            # Private and special names (copy's, pickle's, numpy's probes) are no Webots name.
            owner = None if name.startswith("_") else webots_class(type(self))
            found = webots_classes()[owner] if owner else None
            if found is None or not found.has(name) or _defined(type(self), name):
                # (A property of the class that is only assigned, as Webots' ``Motor.force``, is
                # not read: Webots raises here too.)
                raise AttributeError(
                    f"{_shown(type(self).__name__)} object has no attribute {_shown(name)}",
                    name=name,
                    obj=self,
                )
            if name in found.methods:
                return _not_simulated(type(self).__name__, name)
            _not_simulated(type(self).__name__, name, "")()
            return None
