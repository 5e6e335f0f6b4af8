"""Nav2's ``TriggerEvent`` route operation: a ``std_srvs/Trigger`` service called where
the graph asks for the operation by its name (opening a door, calling a lift), the
:class:`~.operation_client.RouteOperationClient` of the Trigger type.

The response's ``success`` is not looked at, as in Nav2 (it is logged).
"""

from __future__ import annotations

import logging
from dataclasses import dataclass
from typing import ClassVar

from aiobt.msgs import Msg
from aiobt.msgs.std import Trigger

from .operation_client import CALL_TIMEOUT, RouteOperationClient
from .operation_event import OperationResult

__all__ = ["CALL_TIMEOUT", "TriggerEvent"]
log = logging.getLogger("aiobt_services.route.trigger_event")


@dataclass(slots=True)
class TriggerEvent(RouteOperationClient[Trigger.Request, Trigger.Response]):
    REQUEST: ClassVar[type[Msg]] = Trigger.Request
    RESPONSE: ClassVar[type[Msg]] = Trigger.Response

    name: str = "TriggerEvent"

    def process_response(self, response: Trigger.Response) -> OperationResult:
        log.info("%s: success %s: %s", self.name, response.success, response.message)
        return OperationResult()
