"""The base of every wire message, and decoding with errors that name the field."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Self, TypeVar

from pydantic import BaseModel, ConfigDict, ValidationError

from aiobt.msgs._wire import wire_validator

M = TypeVar("M", bound=BaseModel)


class Msg(BaseModel):
    """A message on the wire: JSON, unknown fields refused, NaN and infinities refused."""

    model_config = ConfigDict(
        extra="forbid",
        allow_inf_nan=False,
        ser_json_bytes="base64",
        val_json_bytes="base64",
    )

    def to_json(self) -> bytes:
        """The JSON payload of this message (UTF-8 bytes, as ``model_dump_json``, no str copy)."""
        return self.__pydantic_serializer__.to_json(self)

    @classmethod
    def from_json(cls, payload: bytes | bytearray | str, *, key: str = "") -> Self:
        """Decode ``payload``; raises :class:`MessageError` naming the first bad field."""
        return decode(cls, payload, key=key)


class MessageError(ValueError):
    """A payload that does not fit its model.

    ``field`` is the dotted path of the first offending field (``pose.position.x``,
    ``ranges.3``) or ``<payload>`` when the payload is not JSON at all.
    """

    def __init__(self, model: str, field: str, reason: str, key: str = "") -> None:
        self.model = model
        self.field = field
        self.reason = reason
        self.key = key
        where = f"{key}: " if key else ""
        super().__init__(f"{where}{model} field '{field}': {reason}")

    @classmethod
    def from_validation(cls, model: type[BaseModel], exc: ValidationError, key: str = "") -> Self:
        first = exc.errors(include_url=False)[0]
        field = ".".join(str(part) for part in first["loc"])
        if not field:
            field = "<payload>" if first["type"].startswith("json") else "<message>"
        reason = first["msg"]
        if len(exc.errors()) > 1:
            reason += f" (and {len(exc.errors()) - 1} more error(s))"
        return cls(model.__name__.lstrip("_"), field, reason, key)


def decode(model: type[M], payload: bytes | bytearray | str, *, key: str = "") -> M:
    """Validate a JSON payload as ``model``; :class:`MessageError` names key and field."""
    try:
        return wire_validator(model)(payload)
    except ValidationError as exc:
        raise MessageError.from_validation(model, exc, key) from None


def decoder(model: type[M], *, key: str = "") -> Callable[[bytes], M]:
    """:func:`decode` bound to one model and key, for per-message paths (actions):
    the validator is looked up once, not on every message."""
    validate_json = wire_validator(model)

    def decode_one(payload: bytes) -> M:
        try:
            return validate_json(payload)
        except ValidationError as exc:
            raise MessageError.from_validation(model, exc, key) from None

    return decode_one


def validate(model: type[M], data: Any, *, key: str = "") -> M:
    """Validate Python data (a dict, e.g. from YAML) as ``model``, errors as in :func:`decode`."""
    try:
        return model.model_validate(data)
    except ValidationError as exc:
        raise MessageError.from_validation(model, exc, key) from None
