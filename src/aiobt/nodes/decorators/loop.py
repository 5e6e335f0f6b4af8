"""LoopInt, LoopDouble, LoopString, LoopBool: tick the child once per queue item."""

from __future__ import annotations

from collections import deque
from collections.abc import Callable
from typing import Any, ClassVar

from aiobt.core.composite import DecoratorNode
from aiobt.core.convert import converter_for
from aiobt.core.ports import inout_port, input_port, output_port
from aiobt.core.status import FAILURE, IDLE, RUNNING, Status
from aiobt.nodes.decorators.status_port import status_input


class LoopNode(DecoratorNode):
    """Pop the front of ``queue`` into ``value`` and tick the child, once per item.

    - ``queue`` is a ``;`` list literal (``"1;2;3"``, fresh for every run), or
      a blackboard entry holding a ``collections.deque`` (popped in place, so
      others see it shrink, as BT.CPP's shared queue), a list/tuple or a ``;``
      string (copied when a run starts);
    - the child RUNNING: RUNNING, and the same item goes on;
    - the child SUCCESS: RUNNING (next item at the next tick);
    - the child FAILURE: FAILURE;
    - no item left when a new item is due: ``if_empty`` (default SUCCESS).
    """

    __slots__ = ("_child_running", "_queue", "_static")
    ITEM: ClassVar[type] = str
    PORTS = (
        inout_port("queue", None, description="a ';' list, or an entry with a deque or list"),
        input_port(
            "if_empty",
            Status,
            Status.SUCCESS,
            "Status to return if queue is empty: SUCCESS, FAILURE, SKIPPED",
        ),
        output_port("value", str),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._child_running = False
        self._queue: deque[Any] | None = None
        binding = self.config.inputs.get("queue")
        self._static: list[Any] | None = None
        if binding is not None and binding.key is None:
            self._static = self._parse(str(binding.value))

    @classmethod
    def _parse(cls, text: str) -> list[Any]:
        item: Callable[[str], Any] = converter_for(cls.ITEM) or str
        return [item(part) for part in text.split(";") if part.strip() != ""]

    def _source(self) -> deque[Any] | None:
        if self._static is not None:
            return self._queue  # the literal was copied when the run started
        binding = self.config.inputs.get("queue")
        if binding is None or binding.key is None:
            return None
        entry = self.config.blackboard.entry(binding.key)
        if entry is None or not entry.has_value:
            return self._queue
        value = entry.value
        if isinstance(value, deque):
            return value
        if self._queue is None:
            if isinstance(value, str):
                return deque(self._parse(value))
            if isinstance(value, list | tuple):
                return deque(value)
            raise self.logic_error(
                f"port [queue] must hold a deque, a list or a ';' string, "
                f"not {type(value).__name__}"
            )
        return self._queue

    def execute_sync(self) -> Status:
        if self._status is IDLE:
            self._child_running = False
            self._queue = deque(self._static) if self._static is not None else None
        if not self._child_running:
            self._queue = self._source()
            if not self._queue:
                return status_input(self, "if_empty")
            self.set_output("value", self._queue.popleft())
            if self._status is IDLE:
                self._set_status(RUNNING)
        status = self.tick_child()
        self._child_running = status is RUNNING
        if status.is_completed:
            self.reset_child()
        return FAILURE if status is FAILURE else RUNNING

    def on_halt_sync(self) -> None:
        self._child_running = False
        self.reset_child()


class LoopInt(LoopNode):
    """``<LoopInt queue="1;2;3" value="{n}">``: see :class:`LoopNode`."""

    __slots__ = ()
    ITEM = int
    PORTS = (*LoopNode.PORTS[:2], output_port("value", int))


class LoopDouble(LoopNode):
    """``<LoopDouble queue="0.5;1.5" value="{x}">``: see :class:`LoopNode`."""

    __slots__ = ()
    ITEM = float
    PORTS = (*LoopNode.PORTS[:2], output_port("value", float))


class LoopString(LoopNode):
    """``<LoopString queue="a;b" value="{s}">``: see :class:`LoopNode`."""

    __slots__ = ()
    ITEM = str


class LoopBool(LoopNode):
    """``<LoopBool queue="true;false" value="{b}">``: see :class:`LoopNode`."""

    __slots__ = ()
    ITEM = bool
    PORTS = (*LoopNode.PORTS[:2], output_port("value", bool))
