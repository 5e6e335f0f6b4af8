"""ReactiveSequence: re-check every child from the first on each tick."""

from __future__ import annotations

from aiobt.core.composite import ControlNode, reset_finished, reset_node
from aiobt.core.status import Status

RUNNING, SUCCESS, FAILURE, SKIPPED = Status.RUNNING, Status.SUCCESS, Status.FAILURE, Status.SKIPPED


class ReactiveSequence(ControlNode):
    """``<ReactiveSequence>``: tick all children from the first, every tick.

    - a child RUNNING: every other child is reset (a RUNNING one is halted),
      RUNNING; so conditions before a running action are re-checked each tick;
    - a child FAILURE: reset all, FAILURE;
    - all SUCCESS (or SKIPPED): reset all, SUCCESS (SKIPPED if all skipped).
    """

    __slots__ = ()

    async def execute(self) -> Status:
        if self._status is not RUNNING:
            self._set_status(RUNNING)
        all_skipped = True
        children = self.children
        for index, child in enumerate(children):
            # inlined child.tick(): one coroutine frame per async child, none per sync one
            if child.is_sync:
                status = child.tick_sync()
            elif child._conditions is None:
                status = await child.execute()
                if status is not SKIPPED and status is not child._status:
                    child._set_status(status)
            else:
                status = await child.tick()
            if status is RUNNING:
                if not reset_finished(children, index):
                    await self.halt_others(index)
                return RUNNING
            if status is FAILURE:
                if not reset_finished(children):
                    await self.reset_children()
                return FAILURE
            if status is SKIPPED:
                await reset_node(child)
            elif status is SUCCESS:
                all_skipped = False
            else:
                raise self.logic_error(f"child {child.path} returned IDLE")
        if not reset_finished(children):
            await self.reset_children()
        return SKIPPED if all_skipped else SUCCESS
