"""Nav2's ``RouteOperationClient<SrvT>``: a route operation that calls a service where
the graph asks for it by the operation's name (``OpenDoor``, ``CallElevator``), the base
of :class:`~.trigger_event.TriggerEvent` and of your own.

The service is the graph operation's ``service_name`` metadata (decentralised: one
service per door), else the operation's ``service_name`` parameter (centralised: one
for all); neither is OPERATION_FAILED. The call is the server's (``call_service``: on
the bus, ``{ns}/srv/<service_name>``), waiting 0.5 s at most as Nav2's; a call that
fails or gets no answer fails the goal OPERATION_FAILED, naming the operation, the
service and the node.

A subclass sets ``REQUEST`` and ``RESPONSE`` (the service's pydantic models) and may
override :meth:`~RouteOperationClient.populate_request` (the request from the graph
operation's metadata) and :meth:`~RouteOperationClient.process_response` (the answer
into an :class:`~.operation_event.OperationResult`: e.g. reroute around a door that
stays shut); it is loaded by adding it to :data:`.operations.OPERATIONS`.
"""

from __future__ import annotations

import logging
from collections.abc import Awaitable, Callable
from dataclasses import dataclass, field
from typing import Any, ClassVar, Generic, TypeVar

from aiobt.msgs import Msg

from .errors import RouteError
from .graph import Metadata
from .operation_event import Event, OperationResult, ProcessType

log = logging.getLogger("aiobt_services.route.operation_client")
CALL_TIMEOUT = 0.5  # s, Nav2's RouteOperationClient's invoke timeout
ServiceCall = Callable[[str, Msg, type[Any], float], Awaitable[Any]]  # name, request, reply, s
Req = TypeVar("Req", bound=Msg)
Resp = TypeVar("Resp", bound=Msg)


@dataclass(slots=True)
class RouteOperationClient(Generic[Req, Resp]):
    REQUEST: ClassVar[type[Msg]]
    RESPONSE: ClassVar[type[Msg]]

    call_service: ServiceCall
    name: str = ""  # the name it is loaded under, which the graph names
    service_name: str = ""
    process_type: ProcessType = field(default="ON_GRAPH", init=False)

    def populate_request(self, metadata: Metadata) -> Req:
        """The request for the graph operation with ``metadata`` (default: empty)."""
        request: Req = self.REQUEST()  # type: ignore[assignment]
        return request

    def process_response(self, response: Resp) -> OperationResult:
        """What the answer means for the route (default: nothing)."""
        return OperationResult()

    async def perform(self, event: Event) -> OperationResult:
        given = event.metadata.get("service_name", "")
        service = given if isinstance(given, str) and given else self.service_name
        where = f"at node {event.node.nodeid}" if event.node is not None else "on the route"
        if not service:
            raise RouteError("OPERATION_FAILED", f"route operation {self.name} {where}: no "
                             "service to call: set its service_name parameter or "
                             "'service_name' in the graph operation's metadata")  # fmt: skip
        request = self.populate_request(event.metadata)
        try:
            response = await self.call_service(service, request, self.RESPONSE, CALL_TIMEOUT)
        except Exception as exc:  # any failure of the call fails the goal, as in Nav2
            raise RouteError("OPERATION_FAILED", f"route operation {self.name} {where}: "
                             f"calling service '{service}' failed: {exc}") from None  # fmt: skip
        log.info("%s: processed operation %s with service %s", self.name, where, service)
        return self.process_response(response)
