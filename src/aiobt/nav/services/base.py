"""BtService: Nav2's BtServiceNode, a leaf that makes one request to a remote service."""

from __future__ import annotations

import logging
from typing import Any, ClassVar

from pydantic import ValidationError

from aiobt.core.errors import LogicError, PortError
from aiobt.core.leaves import AsyncActionNode
from aiobt.core.status import FAILURE, SUCCESS, Status
from aiobt.msgs import Msg
from aiobt.nav import remote
from aiobt.nav.context import NavNode
from aiobt.transport import ServiceError


class BtService(NavNode, AsyncActionNode):
    """Calls ``service_name`` once per activation (Nav2's BtServiceNode).

    - RUNNING while the request is out; the answer goes to :meth:`on_completion`
      (SUCCESS by default);
    - FAILURE, logged with the service's name, when no server answers within
      ``server_timeout`` (or it answers with an error);
    - halted: the request is abandoned (a service call holds nothing on the server).

    Subclasses set ``SERVICE`` (default service name) and ``RESPONSE`` and
    implement :meth:`make_request`.
    """

    SERVICE: ClassVar[str] = ""
    RESPONSE: ClassVar[type[Msg]]
    log: ClassVar[logging.Logger] = logging.getLogger(__name__)

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        cls.log = logging.getLogger(cls.__module__)

    def make_request(self) -> Msg:
        raise LogicError(f"{type(self).__name__} does not implement make_request()")

    def counts_as_recovery(self) -> bool:
        return False

    def on_completion(self, response: Any) -> Status:
        return SUCCESS

    def on_timeout(self, message: str) -> None:
        """No answer within ``server_timeout``, or an error answer."""

    async def run(self) -> Status:
        name = remote.server_name(self, "service_name", self.SERVICE)
        timeout = remote.server_timeout(self)
        bus = remote.bus_of(self)
        try:
            request = self.make_request()
        except (PortError, ValidationError, ValueError) as exc:
            self.log.error("%s: cannot make a request for %s: %s", self.path, name, exc)
            return FAILURE
        if self.counts_as_recovery():
            remote.increment_recoveries(self)
        try:
            response = await bus.call(name, request, self.RESPONSE, timeout=timeout)
        except ServiceError as exc:
            message = f"service {name} failed (server_timeout {timeout * 1000:.0f} ms): {exc}"
            self.log.warning("%s: %s", self.path, message)
            self.on_timeout(message)
            return FAILURE
        return self.on_completion(response)
