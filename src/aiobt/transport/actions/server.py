"""The action server: one goal at a time, preemption by a newer goal, cancel, results.

``execute(goal, handle)`` is a coroutine returning the Result. Cancel and
"abort" preemption cancel its task (clean up in ``finally``); with
``preemption="replace"`` the running execute keeps going and takes the newer
goal over through :meth:`GoalHandle.take_new_goal` / :meth:`GoalHandle.wait_new_goal`.
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable
from typing import Generic, TypeVar

import zenoh

from aiobt.core.clock import Clock, SystemClock
from aiobt.msgs import ActionDef, ActionResult, GoalState, MessageError, Msg, decode
from aiobt.transport import _z
from aiobt.transport.actions import protocol as p
from aiobt.transport.actions.fresh import FreshGate, held_during
from aiobt.transport.actions.goals import GoalRecord, RecentIds, ResultStore
from aiobt.transport.actions.intake import GoalIntake
from aiobt.transport.actions.observers import Observers
from aiobt.transport.actions.runner import Execute, GoalRunner
from aiobt.transport.bridge import JSON, LoopBridge, callback
from aiobt.transport.keys import ActionKeys
from aiobt.transport.services import query_payload

G = TypeVar("G", bound=Msg)
R = TypeVar("R", bound=ActionResult)
F = TypeVar("F", bound=Msg)


class ActionServer(Generic[G, R, F]):
    """Serves one action, one goal at a time (Nav2's simple action server).

    - ``execute(goal, handle) -> Result`` runs as a task per goal; ``error_code``
      0 ends the goal SUCCEEDED, anything else ABORTED; an exception ends it
      ABORTED with the action's UNKNOWN code (also one raised by the cleanup of a
      canceled or preempted goal: the error is what the client learns). Cancel
      ends it CANCELED, also when execute catches the cancellation and returns a
      Result (which it carries); a shutdown ends it ABORTED even then.
    - ``preemption="abort"``: a newer goal cancels the running task and the old
      goal ends ABORTED "preempted by goal ..." (whatever execute returns). The
      newer goal starts only once the old task has ended: two executes never run
      at once. A task still running ``_STOP_TIMEOUT`` (5 s) after its cancellation
      is cancelled again, with a warning, every ``_STOP_TIMEOUT``.
      ``"replace"``: the running execute continues with the newer goal
      (``handle.take_new_goal()``); the old goal ends ABORTED the same way.
      A goal being canceled is not preempted (it ends CANCELED): newer goals wait.
    - One goal at most waits to run (Nav2's pending slot): a newer goal takes the
      slot and the one it replaces ends ABORTED "preempted by goal ..." without
      running. A canceled waiting goal ends CANCELED at once and never runs.
      Cancel-all: the running and the waiting goal,
      except a running goal already being preempted (its outcome is decided).
    - A cancel naming a goal id the server has not seen is remembered: that goal,
      arriving later (a late copy its client gave up on, canceled and sent again
      under a new id), is rejected "canceled before it arrived" and preempts nothing.
    - :meth:`aclose` rejects new goals ("action server shutting down"), ends the
      waiting and running goals ABORTED with that reason, then withdraws the token.
    - ``clock`` (robot time; default the system's) stamps GoalStatus messages. A
      :class:`SimTime` listening on demand is held while a goal runs, and a goal
      arriving while it is not listened to starts once it is fresh (bounded).
    - ``accept(goal) -> reason | None`` (in the loop) may reject a goal with a
      reason; without it goals are checked in the Zenoh thread (faster).
    - A starting goal is acknowledged after execute's first step (up to its
      first real await, which must come soon, as anywhere in an event loop); a
      goal that finished by then is answered by its result alone.
    """

    def __init__(
        self,
        session: zenoh.Session,
        bridge: LoopBridge,
        keys: ActionKeys,
        action: type[ActionDef[G, R, F]],
        execute: Execute[G, R, F],
        *,
        preemption: p.Preemption = "abort",
        accept: Callable[[G], str | None] | None = None,
        clock: Clock | None = None,
    ) -> None:
        if preemption not in ("abort", "replace"):
            raise ValueError(f"preemption must be 'abort' or 'replace', got {preemption!r}")
        self.keys = keys
        self.action = action
        self.preemption = preemption
        self._intake = GoalIntake(keys.goal, action.goal_type(), bridge, accept)
        self._session = session
        self._bridge = bridge
        self._results = ResultStore()
        self._canceled_early = RecentIds()  # canceled before they arrived (loop only)
        self._closed: asyncio.Event | None = None  # set once aclose() has finished
        self._queryables = [
            session.declare_queryable(keys.goal, callback(self._on_goal_query)),
            session.declare_queryable(keys.cancel, callback(self._from_zenoh(self._on_cancel))),
            session.declare_queryable(keys.any_result, callback(self._from_zenoh(self._on_result))),
        ]
        self._observed = Observers(session, keys, clock or SystemClock())  # unobserved: no puts
        self._runner = GoalRunner(
            keys.base,
            action,
            held_during(clock, execute),
            preemption,
            self._observed,
            self._finish,
            self.publish_feedback,
        )
        self._gate: FreshGate[tuple[GoalRecord, G]] = FreshGate(clock, self._begin_now)
        self._token = session.liveliness().declare_token(keys.alive)

    def _from_zenoh(self, handle: Callable[[zenoh.Query], None]) -> Callable[[zenoh.Query], None]:
        def on_query(query: zenoh.Query) -> None:
            self._bridge.call(handle, query)

        return on_query

    @property
    def active_goal_id(self) -> str | None:
        active = self._runner.active
        return active.goal_id if active else None

    # -- goal intake -------------------------------------------------------------------------

    def _on_goal_query(self, query: zenoh.Query) -> None:
        """Zenoh thread. Without a user ``accept`` callback the goal is checked right
        here (a bad or duplicate goal is answered at once); the rest runs in the loop."""
        if self._intake.accept is not None:
            self._bridge.call(self._check_in_loop, query)  # user code runs in the loop
            return
        checked = self._intake.check(query)
        if checked is not None:
            self._bridge.call(self._begin, GoalRecord(checked[0], query), checked[1])

    def _check_in_loop(self, query: zenoh.Query) -> None:
        checked = self._intake.check(query)
        if checked is not None:
            self._begin(GoalRecord(checked[0], query), checked[1])

    def _begin(self, record: GoalRecord, goal: G) -> None:
        self._gate((record, goal))  # at once, unless the robot's clock must be heard first

    def _begin_now(self, item: tuple[GoalRecord, G]) -> None:
        record, goal = item
        if record.goal_id in self._canceled_early:
            record.reject("canceled before it arrived")
            return
        self._runner.begin(record, goal)

    def _finish(self, record: GoalRecord, state: GoalState, result: R) -> None:
        """A goal's end: its stream's last reply, the result store, status and observers."""
        if record.done:
            return
        payload = result.to_json()
        tag = p.result_tag(state)
        self._results.store(record.goal_id, tag, payload)
        record.finish(tag, payload)
        self._observed.put_status(record.goal_id, state, result.error_msg)
        if self._observed("result"):
            self._observed.put(self.keys.result(record.goal_id), payload, attachment=tag)

    # -- cancel, result query, feedback ------------------------------------------------------

    def _on_cancel(self, query: zenoh.Query) -> None:
        try:
            request = decode(p.CancelRequest, query_payload(query) or b"{}", key=self.keys.cancel)
        except MessageError as exc:
            query.reply_err(f"bad cancel request: {exc}")
            _z.drop(query)
            return
        goal_id = request.goal_id
        canceling = self._runner.cancel(goal_id)
        if goal_id and not canceling and not self._seen(goal_id):
            self._canceled_early.add(goal_id)
        response = p.CancelResponse(goals_canceling=canceling)
        query.reply(query.key_expr, response.to_json(), encoding=JSON)
        _z.drop(query)

    def _seen(self, goal_id: str) -> bool:
        """Whether ``goal_id`` is running, waiting or has ended here (as far as kept)."""
        active = self._runner.active
        return (
            (active is not None and active.goal_id == goal_id)
            or self._runner.waiting.get(goal_id) is not None
            or self._results.get(goal_id) is not None
        )

    def _on_result(self, query: zenoh.Query) -> None:
        goal_id = str(query.key_expr).rsplit("/", 1)[-1]
        stored = self._results.get(goal_id)
        active = self._runner.active
        if stored is not None:
            query.reply(query.key_expr, stored[1], encoding=JSON, attachment=stored[0])
            _z.drop(query)
        elif active and active.goal_id == goal_id:
            active.waiters.append(query)  # answered when the goal finishes
        elif (waiting := self._runner.waiting.get(goal_id)) is not None:
            waiting.waiters.append(query)
        else:
            query.reply_err(f"unknown goal id {goal_id}")
            _z.drop(query)

    def publish_feedback(self, goal_id: str, feedback: F) -> None:
        active = self._runner.active
        if active is None or active.goal_id != goal_id:
            return  # a preempted goal's late feedback
        payload = feedback.to_json()
        active.reply(payload, p.FEEDBACK)
        if self._observed("feedback"):
            self._session.put(self.keys.feedback(goal_id), payload, encoding=JSON)

    async def aclose(self) -> None:
        """Refuse new goals, end the waiting and running goals ABORTED ("action server
        shutting down"; clients get these results), then withdraw the token and undeclare.
        Idempotent: a second call waits for the first to finish."""
        if self._closed is not None:
            await self._closed.wait()
            return
        self._closed = asyncio.Event()
        try:
            await self._runner.close()
            await self._gate.aclose()
        finally:
            self._closed.set()
            _z.undeclare(self._token)
            for entity in self._queryables:
                _z.undeclare(entity)
            self._observed.close()
