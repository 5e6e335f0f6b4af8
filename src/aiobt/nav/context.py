"""What Nav2's nodes share within one factory: the bus, the namespace, the clock.

Nav2 hands its BT nodes the ROS node, ``server_timeout`` and friends through the
blackboard; aiobt hands them one :class:`NavContext`, given to every node that
:func:`aiobt.nav.register_nav2_nodes` registers. A context without a bus still
builds trees (``aiobt validate``, ``aiobt nodes``); ticking a node that needs the
bus then fails with a clear error.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from aiobt.core.clock import Clock, SystemClock
from aiobt.core.errors import LogicError
from aiobt.core.node import NodeConfig

if TYPE_CHECKING:
    from aiobt.transport import Bus

DEFAULT_SERVER_TIMEOUT = 1.0  # s; Nav2's bt_navigator default_server_timeout is 20 ms (ROS local)
DEFAULT_WAIT_FOR_SERVICE_TIMEOUT = 1.0  # s
DEFAULT_BT_LOOP_DURATION = 0.01  # s, as Nav2


@dataclass(slots=True)
class NavContext:
    """Shared by every Nav2 node of a factory (and so of every tree it builds).

    - ``bus``: the process's :class:`~aiobt.transport.Bus` (None: build only);
    - ``namespace``: the robot namespace the nodes talk under (default: the bus's);
    - ``clock``: robot time (sim time when the services run on it);
    - ``server_timeout``: default of every ``server_timeout`` port, seconds;
    - ``shared``: per-context singletons, e.g. the robot-state provider, built
      once on first use by :meth:`singleton`.
    """

    bus: Bus | None = None
    namespace: str | None = None
    clock: Clock = field(default_factory=SystemClock)
    server_timeout: float = DEFAULT_SERVER_TIMEOUT
    wait_for_service_timeout: float = DEFAULT_WAIT_FOR_SERVICE_TIMEOUT
    bt_loop_duration: float = DEFAULT_BT_LOOP_DURATION
    shared: dict[str, Any] = field(default_factory=dict)

    def require_bus(self, who: str) -> Bus:
        """The bus, or a LogicError naming ``who`` (a node path) when there is none."""
        if self.bus is None:
            raise LogicError(
                f"{who}: this node talks to the robot's services, but its factory was "
                "registered without a bus (register_nav2_nodes(factory, bus))"
            )
        return self.bus

    def singleton(self, name: str, make: Any) -> Any:
        """``shared[name]``, made by ``make(self)`` on first use."""
        value = self.shared.get(name)
        if value is None:
            value = self.shared[name] = make(self)
        return value


class NavNode:
    """Mixin of every Nav2 node: ``self.nav`` is its factory's :class:`NavContext`.

    Put it first: ``class Spin(NavNode, AsyncActionNode)``. The registry builds
    such classes with ``cls(name, config, nav=context)``; built without one (a
    plain ``factory.register_node_type``) the node gets a bus-less context.
    """

    nav: NavContext

    def __init__(
        self, name: str, config: NodeConfig | None = None, *, nav: NavContext | None = None
    ) -> None:
        self.nav = nav if nav is not None else NavContext()
        super().__init__(name, config)  # type: ignore[call-arg]
