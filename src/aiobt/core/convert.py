"""Converting XML attribute text to port types, as BT.CPP's convertFromString.

Numbers, bools, strings, ``;``-separated vectors, ``json:`` literals, any type
with a ``from_bt_string`` classmethod (and ``to_bt_string`` method), and converters
registered at run time (:func:`register_converter`; the message types' string forms
are registered by :mod:`aiobt.msgs.strings`).
Each type also has a BT.CPP type name for the ``<TreeNodesModel>`` export.
"""

from __future__ import annotations

import json
import types
import typing
from collections.abc import Callable
from typing import Any

Converter = Callable[[str], Any]
Formatter = Callable[[Any], str]

_converters: dict[Any, Converter] = {}
_formatters: dict[type, Formatter] = {}
_type_names: dict[Any, str] = {}


class Milliseconds(int):
    """A duration port in milliseconds (BT.CPP ``chrono::milliseconds``)."""


def register_converter(
    tp: Any, converter: Converter, bt_name: str | None = None, formatter: Formatter | None = None
) -> None:
    """Teach ports of type ``tp`` to read XML text with ``converter`` (and write a value
    back with ``formatter``, for :func:`to_text`)."""
    _converters[tp] = converter
    if formatter is not None:
        _formatters[tp] = formatter
    if bt_name is not None:
        _type_names[tp] = bt_name


def _to_bool(text: str) -> bool:
    lowered = text.strip().lower()
    if lowered in ("true", "1"):
        return True
    if lowered in ("false", "0"):
        return False
    raise ValueError(f"{text!r} is not a bool (true/false/1/0)")


def _to_int(text: str) -> int:
    stripped = text.strip()
    if stripped.lower().startswith(("0x", "-0x")):
        return int(stripped, 16)
    return int(stripped)


# C++ spellings found in Nav2 manifests (``std::`` prefix optional)
_CPP_FLOATS = {
    "numeric_limits<double>::infinity()": float("inf"),
    "numeric_limits<double>::max()": 1.7976931348623157e308,
    "numeric_limits<double>::lowest()": -1.7976931348623157e308,
    "numeric_limits<float>::infinity()": float("inf"),
}


def _to_float(text: str) -> float:
    stripped = text.strip()
    special = _CPP_FLOATS.get(stripped.removeprefix("std::"))
    return special if special is not None else float(stripped)


_BASE: dict[Any, Converter] = {
    str: str,
    int: _to_int,
    float: _to_float,
    bool: _to_bool,
    Milliseconds: lambda text: Milliseconds(_to_int(text)),
}

_BASE_NAMES: dict[Any, str] = {
    str: "std::string",
    int: "int",
    float: "double",
    bool: "bool",
    Milliseconds: "std::chrono::milliseconds",
}


def _split(text: str) -> list[str]:
    """BT.CPP splits vectors on ';'; Nav2's error-code lists also use ','."""
    sep = ";" if ";" in text else ","
    return [part.strip() for part in text.split(sep) if part.strip() != ""]


def converter_for(tp: Any) -> Converter | None:
    """The converter for ``tp``, or None when text cannot become a ``tp``."""
    if tp is None or tp is Any:
        return None
    if tp in _converters:
        return _converters[tp]
    if tp in _BASE:
        return _BASE[tp]
    origin = typing.get_origin(tp)
    if origin in (list, tuple):
        args = typing.get_args(tp)
        item = converter_for(args[0]) if args else str
        if item is None:
            return None
        return lambda text: [item(part) for part in _split(text)]
    if isinstance(tp, type) and hasattr(tp, "from_bt_string"):
        return tp.from_bt_string  # type: ignore[no-any-return]
    return None


def convert(text: str, tp: Any) -> Any:
    """Convert attribute text to ``tp``; ``json:`` literals work for any type."""
    if text.startswith("json:"):
        value = json.loads(text[5:])
        validate = getattr(tp, "model_validate", None)
        return validate(value) if validate is not None else value
    conv = converter_for(tp)
    if conv is None:
        return text
    return conv(text)


def is_convertible(tp: Any) -> bool:
    return tp is str or converter_for(tp) is not None


def type_name(tp: Any) -> str:
    """BT.CPP's name of a type, for the TreeNodesModel export."""
    if tp is None or tp is Any:
        return "AnyTypeAllowed"
    if isinstance(tp, str):
        return tp
    if tp in _type_names:
        return _type_names[tp]
    if tp in _BASE_NAMES:
        return _BASE_NAMES[tp]
    origin = typing.get_origin(tp)
    if origin in (list, tuple):
        args = typing.get_args(tp)
        return f"std::vector<{type_name(args[0]) if args else 'AnyTypeAllowed'}>"
    name = getattr(tp, "__bt_type_name__", None)
    if isinstance(name, str):
        return name
    if isinstance(tp, type | types.GenericAlias):
        return getattr(tp, "__name__", str(tp))
    return str(tp)


def to_text(value: Any) -> str:
    """Render a value the way it would be written in XML."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, list | tuple):
        return ";".join(to_text(v) for v in value)
    formatter = _formatters.get(type(value))
    if formatter is not None:
        return formatter(value)
    to_bt = getattr(value, "to_bt_string", None)
    if callable(to_bt):
        return str(to_bt())
    return str(value)
