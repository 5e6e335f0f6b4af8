"""What Nav2's remote leaves share: server ports, timeouts, clients, the recovery count.

Every action, service and cancel leaf names its server with ``server_name`` (or
``service_name``) and bounds its wait with ``server_timeout`` (milliseconds in
XML, as Nav2's ``chrono::milliseconds``; when unset, the ``server_timeout``
blackboard entry, else the factory's :attr:`NavContext.server_timeout`).
One client per (server, action type) is shared by every node of a context.
"""

from __future__ import annotations

from enum import IntEnum
from typing import TYPE_CHECKING, Any

from aiobt.core.convert import Milliseconds
from aiobt.core.errors import LogicError
from aiobt.core.ports import PortInfo, input_port, output_port

if TYPE_CHECKING:
    from aiobt.msgs import ActionDef
    from aiobt.nav.context import NavNode
    from aiobt.transport import ActionClient, Bus

RECOVERIES_KEY = "number_recoveries"  # Nav2's blackboard entry for recovery counting


def server_ports(what: str, default_name: str, *, service: bool = False) -> tuple[PortInfo, ...]:
    """``server_name`` (or ``service_name``) and ``server_timeout``, as Nav2 declares them."""
    name = "service_name" if service else "server_name"
    fallback = f" If not specified, `{default_name}` is used." if default_name else ""
    return (
        input_port(name, str, description=f"{what} name.{fallback}"),
        input_port(
            "server_timeout",
            Milliseconds,
            description=f"{what} timeout (ms). If not provided, uses the BT Navigator's "
            "default_server_timeout.",
        ),
    )


def error_ports(what: str) -> tuple[PortInfo, ...]:
    """``error_code_id`` (uint16) and ``error_msg``, as Nav2's action leaves write them."""
    return (
        output_port("error_code_id", int, description=f"{what} error code."),
        output_port("error_msg", str, description=f"{what} error message."),
    )


def server_timeout(node: NavNode) -> float:
    """Seconds: the ``server_timeout`` port (ms), its blackboard entry, or the context's."""
    tree_node: Any = node
    value = tree_node.get_input_or_blackboard("server_timeout", None)
    if value is None:
        return node.nav.server_timeout
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise LogicError(
            f"{tree_node.path}: server_timeout must be milliseconds (a number), not {value!r}"
        )
    if value <= 0:
        raise LogicError(f"{tree_node.path}: server_timeout must be > 0 ms, not {value}")
    return float(value) / 1000.0


def server_name(node: NavNode, port: str, default: str) -> str:
    """The server's name relative to the namespace (a leading ``/`` is dropped)."""
    tree_node: Any = node
    name = tree_node.get_input(port, None) or default
    name = str(name).strip().strip("/")
    if not name:
        raise LogicError(f"{tree_node.path}: [{port}] is not set: name the server to call")
    return name


def bus_of(node: NavNode) -> Bus:
    """The context's bus; its namespace must be the context's (one session per process)."""
    path = getattr(node, "path", type(node).__name__)
    bus = node.nav.require_bus(path)
    wanted = node.nav.namespace
    if wanted is not None and wanted.strip("/") != bus.namespace:
        raise LogicError(
            f"{path}: the nodes were registered for namespace '{wanted}' but the bus talks "
            f"under '{bus.namespace}'; open the bus with that namespace"
        )
    return bus


def action_client(node: NavNode, name: str, action: type[ActionDef[Any, Any, Any]]) -> Any:
    """The context's client of action server ``name`` (made once, shared)."""
    key = f"action_client:{name}:{action.__module__}.{action.__qualname__}"
    client: ActionClient[Any, Any, Any] | None = node.nav.shared.get(key)
    if client is None:
        client = node.nav.shared[key] = bus_of(node).action_client(name, action)
    return client


def increment_recoveries(node: NavNode) -> None:
    """Nav2's ``increment_recovery_count``: +1 on ``number_recoveries``, the entry the
    node's blackboard sees, else the root's (a SubTree without remapping still counts
    where the navigator reads it)."""
    blackboard = getattr(node, "blackboard")  # noqa: B009 (a TreeNode's property)
    key = RECOVERIES_KEY if blackboard.entry(RECOVERIES_KEY) is not None else f"@{RECOVERIES_KEY}"
    count = blackboard.get(key, 0)
    blackboard.set(key, (count if isinstance(count, int) else 0) + 1)


def error_code(table: type[IntEnum], *names: str) -> int | None:
    """The first of ``names`` that ``table`` defines (Nav2 sets no code when none is)."""
    for name in names:
        member = table.__members__.get(name)
        if member is not None:
            return int(member)
    return None


def action_ports(what: str, default_name: str, *ports: PortInfo) -> tuple[PortInfo, ...]:
    """A BtAction's ports: its own, then server and error ports (Nav2's providedBasicPorts)."""
    return (*ports, *server_ports("Action server", default_name), *error_ports(what))


def service_ports(default_name: str, *ports: PortInfo) -> tuple[PortInfo, ...]:
    """A BtService's ports: its own, then ``service_name`` and ``server_timeout``."""
    return (*ports, *server_ports("Service", default_name, service=True))
