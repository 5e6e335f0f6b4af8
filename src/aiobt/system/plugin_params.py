"""Nav2-style plugin parameters on a service's command line: ``--param SCOPE.name=value``
(a plugin's or a part's dotted parameter), comma-separated plugin lists, and a value's
text read as the type of the parameter's default. Shared by the route and docking
servers."""

from __future__ import annotations

import argparse
import dataclasses
from collections.abc import Mapping
from typing import Any


def comma_list(text: str) -> list[str]:
    """argparse type: ``a, b,c`` -> ``["a", "b", "c"]``."""
    return [name.strip() for name in text.split(",") if name.strip()]


def dotted_param(text: str) -> tuple[str, str, str]:
    """argparse type: ``SCOPE.name=value`` -> ``(scope, name, value)``."""
    name, sep, value = text.partition("=")
    scope, dot, key = name.partition(".")
    if not (sep and dot and scope and key):
        raise argparse.ArgumentTypeError(f"expected PLUGIN.parameter=value, got {text!r}")
    return scope, key, value


def convert_param(where: str, text: str, default: Any) -> Any:
    """``text`` as the type of ``default`` (true/false for a bool; a list of names,
    comma-separated, optionally in brackets and quotes, for a tuple); ValueError naming
    ``where`` otherwise."""
    try:
        if isinstance(default, bool):
            if text.lower() not in ("true", "false"):
                raise ValueError("not true or false")
            return text.lower() == "true"
        if isinstance(default, tuple):
            names = (part.strip().strip("'\"") for part in text.strip().strip("[]").split(","))
            return tuple(part for part in names if part)
        return type(default)(text)
    except ValueError as exc:
        raise ValueError(f"{where}: bad value {text!r} ({exc})") from None


def params_from(cls: type[Any], scope: str, given: Mapping[str, str]) -> Any:
    """The parameter dataclass ``cls`` with ``given`` (texts by field name) over its
    defaults; ValueError naming ``scope.name`` for an unknown one or a bad value."""
    fields = {f.name: f for f in dataclasses.fields(cls) if f.init}
    values: dict[str, Any] = {}
    for key, text in given.items():
        if key not in fields:
            raise ValueError(f"{scope}.{key}: no such parameter (known: {', '.join(fields)})")
        values[key] = convert_param(f"{scope}.{key}", text, fields[key].default)
    return cls(**values)
