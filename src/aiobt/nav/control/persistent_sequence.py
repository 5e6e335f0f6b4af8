"""PersistentSequence (Nav2): a sequence whose position lives on the blackboard."""

from __future__ import annotations

from typing import Any

from aiobt.core.composite import ControlNode
from aiobt.core.errors import LogicError
from aiobt.core.ports import inout_port
from aiobt.core.status import FAILURE, RUNNING, SKIPPED, SUCCESS, Status


class PersistentSequence(ControlNode):
    """``<PersistentSequence current_child_idx="{idx}">`` (Nav2).

    - reads the index of the child to tick from ``current_child_idx`` and
      writes it back after each child that finishes, so the position survives
      halts and tree reloads, and other nodes can move it;
    - a child RUNNING: RUNNING; SUCCESS or SKIPPED: next child, same tick;
    - a child FAILURE: reset children, index 0, FAILURE;
    - past the last child: reset children, index 0, SUCCESS.

    The port must name a blackboard entry (checked at load); an entry with
    no value yet means index 0.
    """

    __slots__ = ()
    PORTS = (inout_port("current_child_idx", int, description="The index of the current child."),)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        if "current_child_idx" not in self.config.outputs:
            raise LogicError(
                "port [current_child_idx] must name a blackboard entry, e.g. "
                'current_child_idx="{child_idx}"'
            )

    def execute_sync(self) -> Status:
        index = self._index()
        self._set_status(RUNNING)
        count = len(self.children)
        while index < count:
            child = self.children[index]
            status = child.tick_sync()
            if status is RUNNING:
                return RUNNING
            if status is FAILURE:
                self.reset_children()
                self.set_output("current_child_idx", 0)
                return FAILURE
            if status is not SUCCESS and status is not SKIPPED:
                raise self.logic_error(f"child {child.path} returned {status.name}")
            index += 1
            self.set_output("current_child_idx", index)
        self.reset_children()
        self.set_output("current_child_idx", 0)
        return SUCCESS

    def _index(self) -> int:
        value = self.get_input("current_child_idx", 0)
        if not isinstance(value, int) or isinstance(value, bool) or value < 0:
            raise self.logic_error(f"current_child_idx must be an index >= 0, not {value!r}")
        return value
