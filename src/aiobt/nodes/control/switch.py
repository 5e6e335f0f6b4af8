"""Switch2..Switch6: tick the child whose case matches a variable."""

from __future__ import annotations

import math
import re
from typing import Any, ClassVar

from aiobt.core.composite import ControlNode
from aiobt.core.convert import to_text
from aiobt.core.ports import PortInfo, input_port
from aiobt.core.status import RUNNING, SKIPPED, Status


def values_equal(a: str, b: str, enums: dict[str, int]) -> bool:
    """BT.CPP's CheckStringEquality: as text, as registered enums, or as numbers."""
    if a == b:
        return True
    if a in enums or b in enums:
        left, right = enums.get(a, a), enums.get(b, b)
        return str(left) == str(right)
    left_int, right_int = _leading_int(a), _leading_int(b)
    if left_int is not None and left_int == right_int:
        return True
    try:
        return math.isclose(float(a), float(b), rel_tol=0.0, abs_tol=_FLOAT_EPSILON)
    except ValueError:
        return False


# BT.CPP compares reals within float's epsilon, and reads ints with
# std::from_chars, which takes the leading integer ("2.5" is 2, "0x2" is 2).
_FLOAT_EPSILON = 1.1920928955078125e-07
_LEADING_INT = re.compile(r"\s*(-?)(?:0[xX]([0-9a-fA-F]+)|([0-9]+))")


def _leading_int(text: str) -> int | None:
    match = _LEADING_INT.match(text)
    if match is None:
        return None
    sign, hex_digits, digits = match.groups()
    value = int(hex_digits, 16) if hex_digits else int(digits)
    return -value if sign else value


class Switch(ControlNode):
    """``<SwitchN variable="{var}" case_1=".." ... case_N="..">`` with N+1 children.

    Ticks the child of the first case equal to ``variable`` (compared as text,
    enum or number), else the last (default) child. A different case than the
    one running halts the running child. A SKIPPED child makes the switch
    SKIPPED; a finished child resets every child.
    """

    __slots__ = ("_running",)
    CASES: ClassVar[int] = 0
    CASE_PORTS: ClassVar[tuple[str, ...]] = ()  # "case_1" .. "case_N", made once per class

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._running = -1

    @classmethod
    def provided_ports(cls) -> tuple[PortInfo, ...]:
        return (
            input_port("variable", str),
            *(input_port(name, str) for name in cls.CASE_PORTS),
        )

    def _match(self) -> int:
        variable = self.get_input("variable", None)
        if variable is None:
            return self.CASES
        text = to_text(variable)
        enums = self._ctx.enums
        for index, name in enumerate(self.CASE_PORTS):
            case = self.get_input(name, None)
            if case is not None and values_equal(text, to_text(case), enums):
                return index
        return self.CASES

    def execute_sync(self) -> Status:
        if len(self.children) != self.CASES + 1:
            raise self.logic_error(
                f"Switch{self.CASES} must have {self.CASES + 1} children "
                f"({self.CASES} cases and the default), it has {len(self.children)}"
            )
        match = self._match()
        if self._running not in (-1, match):
            self.halt_child(self._running)
        child = self.children[match]
        status = child.tick_sync()
        if status is SKIPPED:
            self._running = -1
        elif status is RUNNING:
            self._running = match
        else:
            self.reset_children()
            self._running = -1
        return status

    def on_halt_sync(self) -> None:
        self._running = -1
        self.reset_children()


def _switch(cases: int) -> type[Switch]:
    namespace = {
        "__slots__": (),
        "CASES": cases,
        "CASE_PORTS": tuple(f"case_{i}" for i in range(1, cases + 1)),
        "__doc__": Switch.__doc__,
    }
    cls = type(f"Switch{cases}", (Switch,), namespace)
    cls.__module__ = __name__
    return cls


Switch2 = _switch(2)
Switch3 = _switch(3)
Switch4 = _switch(4)
Switch5 = _switch(5)
Switch6 = _switch(6)
