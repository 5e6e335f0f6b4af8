"""The local costmap's updates in a worker thread, off the control loop's critical path.

At a sim speed-up of 10 a control period is 5 ms of wall time, and an update of the
local costmap (ray tracing a scan, inflating) about 2-3 ms of CPU, more of wall time
on a loaded machine: run between two cycles on the event loop it made the next cycle
late. Here it runs in one worker thread while the loop sleeps until its next cycle
(numpy releases the GIL in its loops, so the two share the cores), as Nav2's costmap
updates in its own thread beside the controller. The view an update makes is
published on the event loop, between two cycles (a cycle's work has no await), so
a cycle reads one costmap throughout.
"""

from __future__ import annotations

import asyncio
import logging
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor

from .grid import CostGrid
from .local import LocalCostmap

log = logging.getLogger("aiobt.costmap.worker")

Change = Callable[[], CostGrid]  # changes the window, returns its new view (not published)


class CostmapWorker:
    """Runs changes of one :class:`LocalCostmap` one at a time, in order, in its own
    thread, and publishes each one's view on the event loop. While it is used every
    change of that costmap goes through it (the clearings too), so no two run at once."""

    __slots__ = ("_executor", "_pending", "costmap")

    def __init__(self, costmap: LocalCostmap) -> None:
        self.costmap = costmap
        self._executor = ThreadPoolExecutor(max_workers=1, thread_name_prefix="local-costmap")
        self._pending: asyncio.Future[tuple[CostGrid, float]] | None = None

    @property
    def busy(self) -> bool:
        """A change started with :meth:`start` has not been published yet."""
        return self._pending is not None and not self._pending.done()

    def start(self, change: Change, done: Callable[[float], None] | None = None) -> None:
        """Run ``change`` in the worker and return at once; its view is published when it
        ends, then ``done`` is told the wall seconds it took. A change that fails is
        logged (the view stays as it was), never raised into the loop."""
        future = asyncio.get_running_loop().run_in_executor(self._executor, _timed, change)
        self._pending = future
        future.add_done_callback(lambda ended: self._finished(ended, done))

    async def run(self, change: Change) -> float:
        """Run ``change`` after the changes before it and publish its view; the wall
        seconds it took. Its exception (a bad clearing request) is raised here."""
        loop = asyncio.get_running_loop()
        view, took = await loop.run_in_executor(self._executor, _timed, change)
        self.costmap.publish(view)
        return took

    def close(self) -> None:
        """Let the thread go once the changes queued have run (none can be added after)."""
        self._executor.shutdown(wait=False)

    def _finished(
        self, ended: asyncio.Future[tuple[CostGrid, float]], done: Callable[[float], None] | None
    ) -> None:
        if ended.cancelled():
            return
        error = ended.exception()
        if error is not None:
            log.error("local costmap update failed: %r", error, exc_info=error)
            return
        view, took = ended.result()
        self.costmap.publish(view)
        if done is not None:
            done(took)


def _timed(change: Change) -> tuple[CostGrid, float]:
    began = time.perf_counter()
    view = change()
    return view, time.perf_counter() - began
