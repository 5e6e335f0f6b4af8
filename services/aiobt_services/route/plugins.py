"""The route server's plugins by Nav2's ids: edge scorers (:data:`.scorers.SCORERS`,
typed on :class:`.scorers.Scorer`) and route operations (:data:`.operations.OPERATIONS`,
typed on :class:`.operations.RouteOperation`), each a dataclass whose fields are its
Nav2 parameters. :func:`make_plugin` builds one from ``PLUGIN.NAME=VALUE`` texts, and
gives it what the server wires in (the costmap, the speed-limit publisher, the
service caller of RouteOperationClients, and the name it is loaded under) by field name.

As in Nav2, a name in ``edge_cost_functions`` or ``operations`` is the plugin's own
type unless its ``plugin`` parameter names another (``OpenDoor.plugin=TriggerEvent``,
Nav2's ``nav2_route::`` prefix allowed): so one type may be loaded under several names.
A plugin with an ``EXTRA_PARAMS`` field takes the numeric parameters it does not name
(the SemanticScorer's cost per class) into that dict.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, TypeVar

from aiobt.costmap import CostGrid
from aiobt.system.plugin_params import convert_param

from .operation_client import ServiceCall

P = TypeVar("P")
NAV2_PREFIX = "nav2_route::"


@dataclass(frozen=True, slots=True)
class Wiring:
    """What plugins get from the server, by field name, not from parameters."""

    costmap: Callable[[], CostGrid | None]
    publish: Callable[[float], None]  # the speed limit, percent
    call_service: ServiceCall  # a RouteOperationClient's: service, request, reply model, s

    def values(self) -> dict[str, Any]:
        return {"costmap": self.costmap, "publish": self.publish,
                "call_service": self.call_service}  # fmt: skip


def make_plugin(
    registry: dict[str, type[P]], kind: str, name: str, params: dict[str, str], wiring: Wiring
) -> P:
    """Plugin ``name`` of ``registry`` (``kind`` names the list in errors) with ``params``;
    ValueError naming the plugin and parameter for an unknown one or a bad value."""
    params = dict(params)
    plugin_type = params.pop("plugin", name).removeprefix(NAV2_PREFIX)
    plugin = registry.get(plugin_type)
    if plugin is None:
        given = f"'{name}'" if plugin_type == name else f"'{plugin_type}' ({name}.plugin)"
        raise ValueError(f"{kind}: unknown plugin {given} (known: {', '.join(registry)})")
    try:
        made: P = plugin(**_values(plugin, name, params, wiring))
    except ValueError as exc:
        if plugin_type == name:
            raise
        raise ValueError(f"{name} (a {plugin_type}): {exc}") from None
    return made


def _values(plugin: type, name: str, params: dict[str, str], wiring: Wiring) -> dict[str, Any]:
    """The dataclass ``plugin``'s arguments: what is wired by field name, and ``params``
    as their fields' types (into its ``EXTRA_PARAMS`` dict those it does not name)."""
    assert dataclasses.is_dataclass(plugin)
    wired = wiring.values() | {"name": name}
    fields = {f.name: f for f in dataclasses.fields(plugin) if f.init}
    values = {key: wired[key] for key in fields if key in wired}
    extra: str | None = getattr(plugin, "EXTRA_PARAMS", None)
    settable = [key for key in fields if key not in wired and key != extra]
    extras: dict[str, float] = {}
    for key, text in params.items():
        if key in settable:
            values[key] = convert_param(f"{name}.{key}", text, fields[key].default)
        elif extra is not None:
            extras[key] = convert_param(f"{name}.{key}", text, 0.0)
        else:
            raise ValueError(f"{name}.{key}: no such parameter (known: {', '.join(settable)})")
    if extra is not None:
        values[extra] = extras
    return values
