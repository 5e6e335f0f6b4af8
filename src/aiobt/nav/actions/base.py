"""BtAction: Nav2's BtActionNode, a leaf that runs one goal on a remote action server."""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable
from typing import Any, ClassVar

from pydantic import ValidationError

from aiobt.core.errors import LogicError, PortError
from aiobt.core.leaves import AsyncActionNode
from aiobt.core.status import FAILURE, RUNNING, SUCCESS, Status
from aiobt.msgs import ActionDef, GoalState
from aiobt.nav import remote
from aiobt.nav.context import NavNode
from aiobt.transport import ActionClient, ClientGoal, GoalLost, GoalRejected, ServerUnavailable

GONE_GRACE = 0.25  # s a leaf waits for a server whose liveliness token ended to come back
CANCEL_SHARE = 0.8  # of the tree's halt_timeout, for a halted leaf's cancel of its goal
_ASYNC_EXECUTE = AsyncActionNode.execute_sync
_NOTHING = object()
_IMMUTABLE = frozenset((str, int, float, bool))  # equal values of these are the same value
# Goal ports that Nav2 reads from the blackboard entry of their own name when unset
BLACKBOARD_FALLBACK = frozenset({"goal", "goals", "path"})


class BtAction(NavNode, AsyncActionNode):
    """Sends one goal to ``server_name`` and returns its outcome (Nav2's BtActionNode).

    - first tick: the goal (from :meth:`make_goal`) is sent; FAILURE with
      ``error_msg`` naming the server if it is not accepted within ``server_timeout``;
    - RUNNING until the result: SUCCEEDED -> :meth:`on_success` (SUCCESS),
      ABORTED -> :meth:`on_aborted` (FAILURE, the server's ``error_code_id`` /
      ``error_msg``), CANCELED by someone else -> :meth:`on_cancelled` (SUCCESS);
    - a goal port in ``WATCHED`` written while RUNNING (a blackboard watcher
      flags it; the next tick sees the flag): :meth:`goal_update` builds the new
      goal, which is sent to the server (it preempts); the leaf stays RUNNING;
    - halted while RUNNING: the goal is canceled and the cancel awaited (within
      most of the tree's ``halt_timeout``);
    - the server gone mid-goal (its liveliness): FAILURE within about 1.2 s.

    Subclasses set ``ACTION`` (the action type; its ``name`` is the default
    server) and implement :meth:`make_goal`.
    """

    ACTION: ClassVar[type[ActionDef[Any, Any, Any]]]
    WATCHED: ClassVar[tuple[str, ...]] = ()
    log: ClassVar[logging.Logger] = logging.getLogger(__name__)

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        cls.log = logging.getLogger(cls.__module__)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._handle: ClientGoal[Any, Any, Any] | None = None
        self._goal: Any = None
        self._unwatch: list[Callable[[], None]] = []
        self._written = self._attention = False
        wants_feedback = type(self).on_feedback is not BtAction.on_feedback
        self._listener = self._on_feedback_arrived if wants_feedback else None
        self._update: asyncio.Future[Any] | None = None
        self._feedback: Any = None
        self._server = ""

    # -- what subclasses provide -----------------------------------------------------------
    def make_goal(self) -> Any:
        """The goal, from the ports (Nav2's ``on_tick``)."""
        raise LogicError(f"{type(self).__name__} does not implement make_goal()")

    def counts_as_recovery(self) -> bool:
        """True: each activation adds one to the ``number_recoveries`` blackboard entry."""
        return False

    def goal_update(self, goal: Any) -> Any | None:
        """A watched port changed: the goal to send instead of ``goal``, or None."""
        new = self.make_goal()
        return new if new != goal else None

    def on_feedback(self, feedback: Any) -> None:
        """Newer feedback than at the previous tick (Nav2's ``on_wait_for_result``)."""

    def on_success(self, result: Any) -> Status:
        self.set_error(0, "")
        return SUCCESS

    def on_aborted(self, result: Any) -> Status:
        self.set_error(result.error_code, result.error_msg)
        return FAILURE

    def on_cancelled(self, result: Any | None) -> Status:
        """Canceled by the server or another client, or halted (``result`` None)."""
        self.set_error(0, "")
        return SUCCESS

    def on_failure(self, code: int | None, message: str) -> None:
        """No result: rejected, the server went away, or (by default) not accepted in time."""
        self.set_error(code, message)

    def on_timeout(self, message: str) -> None:
        """The server did not accept the goal within ``server_timeout``."""
        self.on_failure(self._code("TIMEOUT", "UNKNOWN"), message)

    def set_error(self, code: int | None, message: str) -> None:
        if code is not None:
            self.set_output("error_code_id", code)
        self.set_output("error_msg", message)

    # -- the tick ----------------------------------------------------------------------------
    def execute_sync(self) -> Status:
        if self._attention:  # one flag on the RUNNING tick's path: a port write or feedback
            self._attend()
        return _ASYNC_EXECUTE(self)

    def _attend(self) -> None:
        self._attention = False
        if self._written and self._update is not None:
            self._offer_update()
        feedback = self._feedback
        if feedback is not None:
            self._feedback = None
            self.on_feedback(feedback)

    def halt_sync(self) -> None:
        if self._status is RUNNING:
            self.on_cancelled(None)
        super().halt_sync()

    def _watch(self) -> None:
        """Flag writes of the watched ports' blackboard entries (literals never change)."""
        if self._unwatch:
            return
        for port in self.WATCHED:
            binding = self.config.inputs.get(port)
            if binding is not None:
                key = binding.key
            else:
                key = port if port in BLACKBOARD_FALLBACK else None
            if key is not None:
                self._unwatch.append(self.blackboard.watch(key, self._port_watcher(key)))

    def _port_watcher(self, key: str) -> Callable[[], None]:
        """Flag a write of ``key`` unless it writes the value its last write wrote.

        A selector writes its choice on every tick, as Nav2's does; building and
        comparing a goal for each of those writes made a RUNNING FollowPath cost
        more than the rest of Nav2's tree. A write equal to the one before cannot
        change the goal: that one was flagged and offered already.
        """
        entry = self.blackboard.create_entry(key)
        last: list[Any] = [_NOTHING]

        def written() -> None:
            value = entry.value
            # only immutable values: a path changed in place and written again is a change
            if type(value) in _IMMUTABLE and type(value) is type(last[0]) and value == last[0]:
                return
            last[0] = value
            self._written = self._attention = True

        return written

    def _on_feedback_arrived(self, feedback: Any) -> None:
        self._feedback = feedback
        self._attention = True

    def _stop_watching(self) -> None:
        for undo in self._unwatch:
            undo()
        self._unwatch.clear()
        self._written = self._attention = False
        self._feedback = None

    def _offer_update(self) -> None:
        self._written = False
        try:
            new = self.goal_update(self._goal)
        except (PortError, ValidationError, ValueError) as exc:
            self.log.warning("%s: new goal ignored, keeping the current one: %s", self.path, exc)
            return
        if new is not None and self._update is not None and not self._update.done():
            self._update.set_result(new)

    # -- the goal's life ---------------------------------------------------------------------
    async def run(self) -> Status:
        self._server = remote.server_name(self, "server_name", self.ACTION.name)
        timeout = remote.server_timeout(self)
        client = remote.action_client(self, self._server, self.ACTION)
        try:
            goal = self.make_goal()
        except (PortError, ValidationError, ValueError) as exc:
            message = f"{self.path}: cannot make a goal for {self._server}: {exc}"
            self.log.error("%s", message)
            self.on_failure(self._code("UNKNOWN"), message)
            return FAILURE
        if self.counts_as_recovery():
            remote.increment_recoveries(self)
        if not await self._send(client, goal, timeout):
            return FAILURE
        try:
            return await self._follow(client, timeout)
        except asyncio.CancelledError:
            await self._cancel_goal()
            raise
        finally:
            self._stop_watching()
            self._handle = None
            self._update = None

    async def _send(self, client: ActionClient[Any, Any, Any], goal: Any, wait: float) -> bool:
        self._watch()
        absent = self._absent_timeout(client, wait)
        try:
            handle = await client.send_goal(
                goal, server_timeout=wait, on_feedback=self._listener, absent_timeout=absent
            )
        except ServerUnavailable as exc:
            message = f"{exc} (server_timeout)"
            if not client.server_present:
                message = (
                    f"action server {self._server} is not running "
                    f"(no liveliness token within {absent:g} s)"
                )
            self.log.warning("%s: %s", self.path, message)
            self.on_timeout(message)
            return False
        except GoalRejected as exc:
            self._no_result(self._code("GOAL_REJECTED", "UNKNOWN"), str(exc))
            return False
        self._handle, self._goal = handle, goal  # feedback that came with the acceptance:
        return True  # given to the listener already (send_goal sets it before sending)

    def _absent_timeout(self, client: ActionClient[Any, Any, Any], wait: float) -> float:
        """How long to wait for a server with no liveliness token: Nav2's
        ``wait_for_service_timeout`` (for one coming up), ``GONE_GRACE`` for one whose token
        ended (killed, restarting); never the whole ``server_timeout``, which is meant for a
        busy server to accept. So a dead server fails the leaf at once and recoveries run."""
        absent = min(wait, self.nav.wait_for_service_timeout)
        return min(absent, GONE_GRACE) if client.server_lost else absent

    async def _follow(self, client: ActionClient[Any, Any, Any], wait: float) -> Status:
        """Wait for the result; send each updated goal the tick offers meanwhile."""
        while True:
            handle = self._handle
            assert handle is not None
            update = self._update = asyncio.get_running_loop().create_future()
            if self._written:
                self._offer_update()  # written while the goal was being accepted
            result = asyncio.ensure_future(handle.result())
            try:
                await asyncio.wait((result, update), return_when=asyncio.FIRST_COMPLETED)
            finally:
                result.cancel()
                self._update = None
            if result.done() and not result.cancelled():
                return self._result_status(handle, result)
            if not await self._send(client, update.result(), wait):
                await self._cancel_goal()  # the old goal must not run on without us
                return FAILURE

    def _result_status(
        self, handle: ClientGoal[Any, Any, Any], done: asyncio.Future[Any]
    ) -> Status:
        error = done.exception()
        if isinstance(error, GoalLost):
            self._no_result(self._code("UNKNOWN"), f"action server {self._server} lost: {error}")
            return FAILURE
        if error is not None:
            raise error
        result = done.result()
        if handle.status is GoalState.SUCCEEDED:
            return self.on_success(result)
        if handle.status is GoalState.CANCELED:
            return self.on_cancelled(result)
        self.log.info(
            "%s: %s aborted the goal: %d %s",
            self.path,
            self._server,
            result.error_code,
            result.error_msg,
        )
        return self.on_aborted(result)

    async def _cancel_goal(self) -> None:
        handle = self._handle
        if handle is None or handle.done:
            return
        budget = self._ctx.halt_timeout * CANCEL_SHARE
        try:
            async with asyncio.timeout(budget):
                await handle.cancel(timeout=budget)
        except TimeoutError:
            self.log.warning(
                "%s: %s did not confirm the cancel of goal %s within %.1f s",
                self.path,
                self._server,
                handle.goal_id,
                budget,
            )

    def _no_result(self, code: int | None, message: str) -> None:
        self.log.warning("%s: %s", self.path, message)
        self.on_failure(code, message)

    def _code(self, *names: str) -> int | None:
        return remote.error_code(self.ACTION.ErrorCode, *names)
