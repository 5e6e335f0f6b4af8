"""The route server's plugins by Nav2's ids: edge scorers (:data:`.scorers.SCORERS`,
typed on :class:`.scorers.Scorer`) and route operations (:data:`.operations.OPERATIONS`,
typed on :class:`.operations.RouteOperation`), each a dataclass whose fields are its
Nav2 parameters. :func:`make_plugin` builds one from ``PLUGIN.NAME=VALUE`` texts, and
gives it what the server wires in (the costmap, the speed-limit publisher) by field name.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, TypeVar

from aiobt.costmap import CostGrid

P = TypeVar("P")


@dataclass(frozen=True, slots=True)
class Wiring:
    """What plugins get from the server, by field name, not from parameters."""

    costmap: Callable[[], CostGrid | None]
    publish: Callable[[float], None]  # the speed limit, percent

    def values(self) -> dict[str, Any]:
        return {"costmap": self.costmap, "publish": self.publish}


def make_plugin(
    registry: dict[str, type[P]], kind: str, name: str, params: dict[str, str], wiring: Wiring
) -> P:
    """Plugin ``name`` of ``registry`` (``kind`` names the list in errors) with ``params``;
    ValueError naming the plugin and parameter for an unknown one or a bad value."""
    plugin = registry.get(name)
    if plugin is None:
        raise ValueError(f"{kind}: unknown plugin '{name}' (known: {', '.join(registry)})")
    assert dataclasses.is_dataclass(plugin)
    wired = wiring.values()
    fields = {f.name: f for f in dataclasses.fields(plugin) if f.init}
    values = {key: wired[key] for key in fields if key in wired}
    settable = [key for key in fields if key not in wired]
    for key, text in params.items():
        if key not in settable:
            raise ValueError(f"{name}.{key}: no such parameter (known: {', '.join(settable)})")
        values[key] = convert_param(f"{name}.{key}", text, fields[key].default)
    made: P = plugin(**values)
    return made


def convert_param(where: str, text: str, default: Any) -> Any:
    """``text`` as the type of ``default`` (true/false for a bool)."""
    try:
        if isinstance(default, bool):
            if text.lower() not in ("true", "false"):
                raise ValueError("not true or false")
            return text.lower() == "true"
        return type(default)(text)
    except ValueError as exc:
        raise ValueError(f"{where}: bad value {text!r} ({exc})") from None
