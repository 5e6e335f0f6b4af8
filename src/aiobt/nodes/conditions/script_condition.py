"""ScriptCondition: SUCCESS when a script expression is true."""

from __future__ import annotations

from typing import Any

from aiobt.core.leaves import ConditionNode
from aiobt.core.ports import input_port
from aiobt.core.status import Status
from aiobt.nodes.actions.script import ScriptCode


class ScriptCondition(ConditionNode):
    """``<ScriptCondition code="battery > 20 && !charging"/>``.

    - SUCCESS if the last statement is true, else FAILURE;
    - true is BT.CPP's cast to bool: a bool, the integers 0/1, a non-zero
      float; a string or another integer is an error naming the node.
    """

    __slots__ = ("_code",)
    PORTS = (
        input_port(
            "code", str, description="Piece of code that can be parsed. Must return false or true"
        ),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._code = ScriptCode(self, condition=True)

    def check(self) -> Status:
        return Status.SUCCESS if self._code.run() else Status.FAILURE
