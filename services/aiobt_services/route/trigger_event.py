"""Nav2's ``TriggerEvent`` route operation: a ``std_srvs/Trigger`` service called where
the graph asks for the operation by its name (opening a door, calling a lift).

The service is the graph operation's ``service_name`` metadata, else the operation's
``service_name`` parameter (neither: OPERATION_FAILED). The call itself is the
server's (:attr:`TriggerEvent.call_trigger`, given the name and a timeout): here it is
``{ns}/srv/<service_name>`` on the bus. A call that fails or gets no answer within
0.5 s fails the goal with OPERATION_FAILED; the response's ``success`` is not
looked at, as in Nav2.
"""

from __future__ import annotations

import logging
from collections.abc import Awaitable, Callable
from dataclasses import dataclass, field

from aiobt.msgs.std import Trigger

from .errors import RouteError
from .operation_event import Event, OperationResult, ProcessType

log = logging.getLogger("aiobt_services.route.trigger_event")
CALL_TIMEOUT = 0.5  # s, Nav2's RouteOperationClient's invoke timeout
TriggerCall = Callable[[str, float], Awaitable[Trigger.Response]]


@dataclass(slots=True)
class TriggerEvent:
    call_trigger: TriggerCall
    name: str = "TriggerEvent"  # the name it is loaded under, which the graph names
    service_name: str = ""
    process_type: ProcessType = field(default="ON_GRAPH", init=False)

    async def perform(self, event: Event) -> OperationResult:
        given = event.metadata.get("service_name", "")
        service = given if isinstance(given, str) and given else self.service_name
        where = f"at node {event.node.nodeid}" if event.node is not None else "on the route"
        if not service:
            raise RouteError("OPERATION_FAILED", f"route operation {self.name} {where}: no "
                             "service to call: set its service_name parameter or "
                             "'service_name' in the graph operation's metadata")  # fmt: skip
        try:
            response = await self.call_trigger(service, CALL_TIMEOUT)
        except Exception as exc:  # any failure of the call fails the goal, as in Nav2
            raise RouteError("OPERATION_FAILED", f"route operation {self.name} {where}: "
                             f"calling service '{service}' failed: {exc}") from None  # fmt: skip
        log.info("%s: processed operation %s with service %s (success %s: %s)", self.name,
                 where, service, response.success, response.message)  # fmt: skip
        return OperationResult()
