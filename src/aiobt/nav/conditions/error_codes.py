"""Nav2's error-code conditions: is the last error one of a set?

``error_codes_to_check`` literals may separate codes with ``;`` (BT.CPP) or
``,`` (Nav2's examples): ``"101,107,119"``.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any, ClassVar

from aiobt.core.convert import converter_for
from aiobt.core.leaves import ConditionNode
from aiobt.core.ports import PortInfo, input_port
from aiobt.msgs.errors import (
    ComputePathThroughPosesError,
    ComputePathToPoseError,
    ComputeRouteError,
    FollowPathError,
    SmoothPathError,
)

_to_codes = converter_for(list[int])


def _ports(server: str) -> tuple[PortInfo, PortInfo]:
    """Nav2's two ports, their descriptions naming ``server`` (if any)."""
    return (
        input_port(
            "error_code",
            int,
            description="The active error code to compare against."
            + (f" This should match the {server} error code." if server else ""),
        ),
        input_port(
            "error_codes_to_check",
            list[int],
            description=f"The set of {server + ' ' if server else ''}error codes you wish to "
            "compare against the active error code.",
        ),
    )


class AreErrorCodesPresent(ConditionNode):
    """``<AreErrorCodesPresent error_code="{code}" error_codes_to_check="101,107"/>`` (Nav2).

    SUCCESS if ``error_code`` is one of ``error_codes_to_check``, else FAILURE.
    """

    __slots__ = ("_fixed_codes",)
    PORTS = _ports("")
    DEFAULT_CODES: ClassVar[frozenset[int]] = frozenset()

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        # a literal list (converted at load) or the default set is known now;
        # only a blackboard-bound list is read at each tick
        binding = self.config.inputs.get("error_codes_to_check")
        self._fixed_codes: frozenset[int] | None = None
        if binding is None:
            self._fixed_codes = self.DEFAULT_CODES or None
        elif binding.key is None:
            self._fixed_codes = _as_codes(binding.value, self.path)

    def check(self) -> bool:
        code = int(self.get_input("error_code"))
        codes = self._fixed_codes
        if codes is None:
            codes = _as_codes(self.get_input("error_codes_to_check"), self.path)
        return code in codes


def _as_codes(value: Any, path: str) -> frozenset[int]:
    if isinstance(value, str):
        assert _to_codes is not None
        value = _to_codes(value)
    if isinstance(value, int):
        return frozenset((value,))
    if isinstance(value, Iterable):
        return frozenset(int(code) for code in value)
    raise TypeError(f"{path}: error_codes_to_check must be a list of codes, not {value!r}")


class WouldAControllerRecoveryHelp(AreErrorCodesPresent):
    """``<WouldAControllerRecoveryHelp error_code="{follow_path_error_code}"/>`` (Nav2).

    SUCCESS for the controller's UNKNOWN (100), PATIENCE_EXCEEDED (104),
    FAILED_TO_MAKE_PROGRESS (105) and NO_VALID_CONTROL (106); else FAILURE.
    An explicit ``error_codes_to_check`` replaces that set (the port is in
    Nav2's manifest; Nav2's C++ ignores it).
    """

    __slots__ = ()
    PORTS = _ports("controller server")
    DEFAULT_CODES = frozenset(
        (
            FollowPathError.UNKNOWN,
            FollowPathError.PATIENCE_EXCEEDED,
            FollowPathError.FAILED_TO_MAKE_PROGRESS,
            FollowPathError.NO_VALID_CONTROL,
        )
    )


class WouldAPlannerRecoveryHelp(AreErrorCodesPresent):
    """``<WouldAPlannerRecoveryHelp error_code="{compute_path_error_code}"/>`` (Nav2).

    SUCCESS for UNKNOWN, TIMEOUT and NO_VALID_PATH of both planner actions:
    ComputePathToPose (200, 207, 208) and ComputePathThroughPoses (300, 307,
    308); else FAILURE. An explicit ``error_codes_to_check`` replaces that set.
    """

    __slots__ = ()
    PORTS = _ports("planner server")
    DEFAULT_CODES = frozenset(
        code
        for table in (ComputePathToPoseError, ComputePathThroughPosesError)
        for code in (table.UNKNOWN, table.TIMEOUT, table.NO_VALID_PATH)
    )


class WouldASmootherRecoveryHelp(AreErrorCodesPresent):
    """``<WouldASmootherRecoveryHelp error_code="{smoother_error_code}"/>`` (Nav2).

    SUCCESS for the smoother's UNKNOWN (500), TIMEOUT (502),
    SMOOTHED_PATH_IN_COLLISION (503) and FAILED_TO_SMOOTH_PATH (504); else
    FAILURE. An explicit ``error_codes_to_check`` replaces that set.
    """

    __slots__ = ()
    PORTS = _ports("smoother server")
    DEFAULT_CODES = frozenset(
        (
            SmoothPathError.UNKNOWN,
            SmoothPathError.TIMEOUT,
            SmoothPathError.SMOOTHED_PATH_IN_COLLISION,
            SmoothPathError.FAILED_TO_SMOOTH_PATH,
        )
    )


class WouldARouteRecoveryHelp(AreErrorCodesPresent):
    """``<WouldARouteRecoveryHelp error_code="{route_error_code}"/>`` (Nav2).

    SUCCESS for the route server's UNKNOWN (400), TIMEOUT (404) and
    NO_VALID_ROUTE (405); else FAILURE. An explicit ``error_codes_to_check``
    replaces that set.
    """

    __slots__ = ()
    PORTS = _ports("route server")
    DEFAULT_CODES = frozenset(
        (ComputeRouteError.UNKNOWN, ComputeRouteError.TIMEOUT, ComputeRouteError.NO_VALID_ROUTE)
    )
