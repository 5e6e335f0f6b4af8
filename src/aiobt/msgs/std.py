"""``std_msgs`` shapes: String, as the selectors' topics carry it."""

from __future__ import annotations

import json
from typing import Any, ClassVar, Self, TypeAlias

from aiobt.msgs._base import Msg


class String(Msg):
    """``std_msgs/String``. On the wire it accepts what a user types into
    ``zenoh put``, which sends raw bytes: ``{"data": "GridBased"}``, the JSON
    string ``"GridBased"`` or the plain text ``GridBased`` (blanks stripped)."""

    __bt_type_name__: ClassVar[str] = "std_msgs::msg::String"

    data: str = ""

    @classmethod
    def __wire_validate__(cls, payload: bytes | bytearray | str) -> Self:
        """The message in ``payload``; a pydantic ValidationError names what is wrong."""
        if not isinstance(payload, str):
            raw = bytes(payload)
            try:
                payload = raw.decode("utf-8")
            except UnicodeDecodeError:
                return cls.model_validate({"data": raw})  # refused, naming the field
        try:
            value: Any = json.loads(payload)
        except ValueError:
            value = payload.strip()  # plain text
        if isinstance(value, int | float):  # bool included: a name that reads as JSON
            value = payload.strip()
        if isinstance(value, str):
            return cls(data=value)
        return cls.model_validate(value)


class _TriggerRequest(Msg):
    """``std_srvs/Trigger`` request: empty."""


class _TriggerResponse(Msg):
    success: bool = False
    message: str = ""


class Trigger:
    """``std_srvs/Trigger``: do something, say whether it worked (PauseResumeController)."""

    Request: TypeAlias = _TriggerRequest
    Response: TypeAlias = _TriggerResponse
