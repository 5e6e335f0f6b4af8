"""PauseResumeController (Nav2): pause and resume a branch through two services."""

from __future__ import annotations

import enum
import logging
import weakref
from collections.abc import Callable
from typing import Any

from aiobt.core.composite import ControlNode
from aiobt.core.ports import input_port
from aiobt.core.status import FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status
from aiobt.msgs import Trigger
from aiobt.nav.context import NavNode
from aiobt.nav.shared_topics import SharedTopics, shared_topics, topic_name

log = logging.getLogger("aiobt.nav.pause_resume_controller")


class State(enum.Enum):
    RESUMED = 0
    PAUSED = 1
    PAUSE_REQUESTED = 2
    ON_PAUSE = 3
    RESUME_REQUESTED = 4
    ON_RESUME = 5


_CHILD = {State.RESUMED: 0, State.PAUSED: 1, State.ON_PAUSE: 2, State.ON_RESUME: 3}
_NEXT = {
    State.PAUSE_REQUESTED: State.ON_PAUSE,
    State.ON_PAUSE: State.PAUSED,
    State.RESUME_REQUESTED: State.ON_RESUME,
    State.ON_RESUME: State.RESUMED,
}


class _Endpoint:
    """One ``{ns}/srv/{name}`` Trigger service per bus, answered by the newest node
    that asked for it (trees come and go; the service stays)."""

    def __init__(self, topics: SharedTopics, name: str, pause: bool) -> None:
        self.pause = pause
        self.target: weakref.ref[PauseResumeController] | None = None
        topics.bus.serve(name, Trigger.Request, Trigger.Response, self._handle)

    def _handle(self, _request: Trigger.Request) -> Trigger.Response:
        node = self.target() if self.target is not None else None
        if node is None:
            return Trigger.Response(success=False, message="no PauseResumeController is running")
        return node.request(self.pause)


def _endpoint_maker(name: str, pause: bool) -> Callable[[SharedTopics], _Endpoint]:
    return lambda topics: _Endpoint(topics, name, pause)


class PauseResumeController(NavNode, ControlNode):
    """``<PauseResumeController pause_service_name="/pause" resume_service_name="/resume">``
    with children RESUMED, then optionally PAUSED, ON_PAUSE, ON_RESUME (Nav2).

    - starts RESUMED, ticking child 0; its SUCCESS is this node's SUCCESS;
    - a call of the pause service (std_srvs/Trigger on ``{ns}/srv/{name}``)
      resets the children and runs ON_PAUSE (child 2) to completion, then
      ticks PAUSED (child 1) until the resume service is called, which runs
      ON_RESUME (child 3) and goes back to RESUMED; missing children are
      skipped; RUNNING meanwhile;
    - a child's FAILURE is this node's FAILURE; a halt goes back to RESUMED.
    """

    MAX_CHILDREN = 4
    PORTS = (
        input_port("pause_service_name", str, description="Service to call to pause."),
        input_port("resume_service_name", str, description="Service to call to resume."),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.state = State.RESUMED
        self._served = False

    def _serve(self) -> None:
        topics = shared_topics(self.nav, self.path)
        for port, pause in (("pause_service_name", True), ("resume_service_name", False)):
            text: str = self.get_input(port, "")
            if not text.strip():
                raise self.logic_error(f"port [{port}] is not set")
            name = topic_name(text, self.path, port)
            endpoint: _Endpoint = topics.shared(f"trigger:{name}", _endpoint_maker(name, pause))
            endpoint.target = weakref.ref(self)
        self._served = True

    def request(self, pause: bool) -> Trigger.Response:
        """A pause (or resume) service call: accepted unless already in that state."""
        if pause and self.state is not State.PAUSED:
            self.state = State.PAUSE_REQUESTED
        elif not pause and self.state is State.PAUSED:
            self.state = State.RESUME_REQUESTED
        else:
            message = f"{self.path}: {'already PAUSED' if pause else 'not PAUSED'}"
            log.warning("%s", message)
            return Trigger.Response(success=False, message=message)
        log.info("%s: %s requested", self.path, "pause" if pause else "resume")
        self.emit_wake_up()
        return Trigger.Response(success=True)

    def execute_sync(self) -> Status:
        if not self._served:
            self._serve()
        if self._status is IDLE:
            self.state = State.RESUMED
        self._set_status(RUNNING)
        if self.state in (State.PAUSE_REQUESTED, State.RESUME_REQUESTED):
            self.reset_children()
            self._advance()
        index = _CHILD[self.state]
        if index >= len(self.children):
            self._advance()
            return RUNNING
        status = self.children[index].tick_sync()
        if status is RUNNING:
            return RUNNING
        if status is SUCCESS or status is SKIPPED:
            if self.state is State.RESUMED:
                return SUCCESS
            self._advance()
            return RUNNING
        log.error("%s: the %s child returned FAILURE", self.path, self.state.name)
        return FAILURE

    def _advance(self) -> None:
        following = _NEXT.get(self.state)
        if following is not None:
            self.state = following
            log.info("%s: switched to %s", self.path, following.name)

    def on_halt_sync(self) -> None:
        self.state = State.RESUMED
        super().on_halt_sync()
