"""Port declarations: what a node reads and writes, with type and default.

``input_port("msec", int, 1000, "milliseconds")`` mirrors BT.CPP's
``InputPort<int>("msec", 1000, "milliseconds")``. A port's type drives literal
conversion at load time; ``None`` accepts anything.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from enum import Enum
from typing import Any


class PortDirection(Enum):
    INPUT = "input_port"
    OUTPUT = "output_port"
    INOUT = "inout_port"


class _NoDefault:
    __slots__ = ()

    def __repr__(self) -> str:
        return "NO_DEFAULT"


NO_DEFAULT: Any = _NoDefault()


@dataclass(frozen=True, slots=True)
class PortInfo:
    name: str
    direction: PortDirection
    type: Any = None
    default: Any = NO_DEFAULT
    description: str = ""
    required: bool = False  # an input that must be set in the XML: missing is a load error

    @property
    def has_default(self) -> bool:
        return self.default is not NO_DEFAULT

    @property
    def is_input(self) -> bool:
        return self.direction is not PortDirection.OUTPUT

    @property
    def is_output(self) -> bool:
        return self.direction is not PortDirection.INPUT


def input_port(
    name: str,
    type: Any = None,
    default: Any = NO_DEFAULT,
    description: str = "",
    *,
    required: bool = False,
) -> PortInfo:
    return PortInfo(name, PortDirection.INPUT, type, default, description, required)


def output_port(
    name: str, type: Any = None, default: Any = NO_DEFAULT, description: str = ""
) -> PortInfo:
    return PortInfo(name, PortDirection.OUTPUT, type, default, description)


def inout_port(
    name: str,
    type: Any = None,
    default: Any = NO_DEFAULT,
    description: str = "",
    *,
    required: bool = False,
) -> PortInfo:
    return PortInfo(name, PortDirection.INOUT, type, default, description, required)


_POINTER = re.compile(r"^\{\s*([^{}]*?)\s*\}$")


def blackboard_key(text: str, port_name: str) -> str | None:
    """The key of a ``{key}`` pointer (``{=}`` is the port's own name), else None."""
    match = _POINTER.match(text.strip()) if isinstance(text, str) else None
    if match is None:
        return None
    key = match.group(1)
    return port_name if key in ("=", "") else key


# Attribute names every node accepts besides its ports.
RESERVED_ATTRIBUTES = frozenset({"ID", "name", "_description", "_uid", "_fullpath"})
CONDITION_ATTRIBUTES = frozenset(
    {
        "_failureIf",
        "_successIf",
        "_skipIf",
        "_while",
        "_onSuccess",
        "_onFailure",
        "_onHalted",
        "_post",
    }
)
