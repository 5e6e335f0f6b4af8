"""Value rules of BT.CPP's scripts (its ``BT::Any``), on Python values.

- numbers are ``int``/``float``/``bool``; arithmetic, comparisons and logic
  give ``float`` (BT.CPP computes in double); integer literals stay ``int``;
- strings compare with strings; a string compared with a number is read as
  a number (``'true'``/``'false'``, enum names and numerals);
- conditions accept bools, the ints 0 and 1, and any float (non-zero is true);
  other ints and strings are errors, as in BT.CPP.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from typing import Any

from aiobt.core.convert import type_name
from aiobt.script.errors import ScriptError

EPSILON = 1.1920928955078125e-07  # float epsilon: BT.CPP's tolerance for == on numbers


def is_number(value: Any) -> bool:
    return isinstance(value, int | float)


def kind(value: Any) -> str:
    """BT.CPP's name of the value's type, for messages."""
    return type_name(type(value))


def describe(value: Any) -> str:
    return f"{kind(value)} {value!r}"


def to_text(value: Any) -> str:
    """A value as BT.CPP's ``cast<std::string>`` writes it (``3.5`` -> ``3.500000``)."""
    if isinstance(value, str):
        return value
    if isinstance(value, bool):
        return "1" if value else "0"
    if isinstance(value, float):
        return f"{value:f}"
    return str(value)


def text_to_number(text: str, enums: Mapping[str, int]) -> float:
    """A string read as a number: ``true``, ``false``, an enum name or a numeral."""
    if text == "true":
        return 1.0
    if text == "false":
        return 0.0
    if text in enums:
        return float(enums[text])
    return c_strtod(text)


_STRTOD = re.compile(
    r"\s*([+-]?)(?:0[xX]([0-9a-fA-F]+)|((?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|inf(?:inity)?|nan))",
    re.IGNORECASE,
)


def c_strtod(text: str) -> float:
    """The number at the start of ``text``, as C's ``strtod`` (BT.CPP's string to
    double): leading spaces skipped, ``0x`` hex, trailing characters ignored."""
    match = _STRTOD.match(text)
    if match is None:
        raise ScriptError(f"cannot convert the string {text!r} to a number")
    sign, hex_digits, decimal = match.groups()
    value = float(int(hex_digits, 16)) if hex_digits else float(decimal)
    return -value if sign == "-" else value


def truth(value: Any) -> bool:
    """BT.CPP's ``cast<bool>()`` of a script result (conditions, ``&&``, ``||``)."""
    if isinstance(value, bool):
        return value
    if isinstance(value, int):
        if value in (0, 1):
            return value == 1
        raise ScriptError(f"the integer {value} is not a bool (only 0 and 1 are)")
    if isinstance(value, float):
        return value != 0.0
    raise ScriptError(f"a {describe(value)} cannot be used as a bool")


def ternary_truth(value: Any) -> bool:
    """The condition of ``c ? x : y``: a non-zero number, or a string read as one."""
    if isinstance(value, str):
        return c_strtod(value) != 0.0  # BT.CPP reads a string condition as a number
    if is_number(value):
        return float(value) != 0.0
    raise ScriptError(f"a {describe(value)} cannot be used as the condition of '?'")


def divide(left: float, right: float) -> float:
    """IEEE division, as in C++: x/0 is +-inf, 0/0 is nan."""
    if right == 0.0:
        if left == 0.0 or math.isnan(left):
            return math.nan
        return math.copysign(math.inf, left) * math.copysign(1.0, right)
    return left / right


def as_int64(value: Any, op: str) -> int:
    """An operand of a bitwise operator: an integral number."""
    number = float(value)
    if not number.is_integer() or abs(number) > 2.0**63:
        raise ScriptError(f"bitwise operator [{op}] needs integers, got {describe(value)}")
    return int(number)


def number_into(key: str, target: type, value: Any) -> Any:
    """``value`` (a number) converted for an entry of type ``target``, or an error."""
    if target is bool:
        if float(value) in (0.0, 1.0):
            return bool(value)
    elif target is float:
        return float(value)
    elif target is int:
        if isinstance(value, bool | int) or float(value).is_integer():
            return int(value)
    elif isinstance(value, target):
        return value
    raise assign_error(key, target, value)


def assign_error(key: str, target: Any, value: Any) -> ScriptError:
    return ScriptError(
        f"cannot assign to blackboard entry [{key}] of type {type_name(target)} "
        f"the value {value!r} of type {kind(value)}"
    )
