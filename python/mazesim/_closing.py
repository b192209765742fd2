"""The one ``with`` behaviour of the package's objects that hold something open (a progress
bar, a learning curve's TensorBoard files, a private ROS master): :class:`Closing` gives them
``__enter__`` (the object itself) and ``__exit__`` (its ``close()``), whatever ended the block.
"""

from __future__ import annotations

from types import TracebackType
from typing import TypeVar

__all__ = ["Closing"]

_Self = TypeVar("_Self", bound="Closing")


class Closing:
    """A mix-in: ``with obj:`` yields ``obj`` and calls ``obj.close()`` on leaving the block."""

    def close(self) -> object:
        """Releases what the object holds open (what it returns, ``with`` leaves unread)."""
        raise NotImplementedError

    def __enter__(self: _Self) -> _Self:
        return self

    def __exit__(
        self,
        kind: type[BaseException] | None,
        error: BaseException | None,
        traceback: TracebackType | None,
    ) -> None:
        self.close()
