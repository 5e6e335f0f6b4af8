"""The operators of the script language on values, following BT.CPP's ``operators.hpp``."""

from __future__ import annotations

import operator
from collections.abc import Callable, Mapping
from typing import Any

from aiobt.script.errors import ScriptError
from aiobt.script.values import (
    EPSILON,
    as_int64,
    describe,
    divide,
    is_number,
    text_to_number,
    to_text,
    truth,
)

BinaryFn = Callable[[Any, Any], Any]

_ARITHMETIC: dict[str, Callable[[float, float], float]] = {
    "+": operator.add,
    "-": operator.sub,
    "*": operator.mul,
    "/": divide,
}
_BITWISE: dict[str, Callable[[int, int], int]] = {
    "&": operator.and_,
    "|": operator.or_,
    "^": operator.xor,
}


def _not_permitted(op: str, left: Any, right: Any) -> ScriptError:
    return ScriptError(f"operator [{op}] cannot combine {describe(left)} and {describe(right)}")


def arithmetic(op: str) -> BinaryFn:
    fn = _ARITHMETIC[op]

    def apply(left: Any, right: Any) -> Any:
        if is_number(left) and is_number(right):
            return fn(float(left), float(right))
        if op == "+" and isinstance(left, str) and isinstance(right, str):
            return left + right
        raise _not_permitted(op, left, right)

    return apply


def bitwise(op: str) -> BinaryFn:
    fn = _BITWISE[op]

    def apply(left: Any, right: Any) -> Any:
        if is_number(left) and is_number(right):
            return float(fn(as_int64(left, op), as_int64(right, op)))
        raise _not_permitted(op, left, right)

    return apply


def logical(op: str) -> BinaryFn:
    both = op == "&&"

    def apply(left: Any, right: Any) -> Any:
        if not (is_number(left) and is_number(right)):
            raise _not_permitted(op, left, right)
        a, b = truth(left), truth(right)
        return float(a and b) if both else float(a or b)

    return apply


def concat(left: Any, right: Any) -> Any:
    left_ok = isinstance(left, str) or is_number(left)
    right_ok = isinstance(right, str) or is_number(right)
    if left_ok and right_ok and (isinstance(left, str) or isinstance(right, str)):
        return to_text(left) + to_text(right)
    raise ScriptError(
        f"operator [..] needs a string on at least one side, got {describe(left)} "
        f"and {describe(right)}"
    )


def binary(op: str) -> BinaryFn:
    if op in _ARITHMETIC:
        return arithmetic(op)
    if op in _BITWISE:
        return bitwise(op)
    if op in ("&&", "||"):
        return logical(op)
    return concat


def unary(op: str, value: Any) -> float:
    if is_number(value):
        if op == "-":
            return -float(value)
        if op == "~":
            return float(~as_int64(int(float(value)), op))
        return float(not value)
    raise ScriptError(f"operator [{op}] cannot be applied to {describe(value)}")


_COMPARE: dict[str, Callable[[Any, Any], bool]] = {
    "==": lambda a, b: a == b,
    "!=": lambda a, b: a != b,
    "<": operator.lt,
    ">": operator.gt,
    "<=": operator.le,
    ">=": operator.ge,
}


def compare(op: str, left: Any, right: Any, enums: Mapping[str, int]) -> bool:
    """One link of a comparison chain."""
    if isinstance(left, str) and isinstance(right, str):
        return _COMPARE[op](left, right)
    if isinstance(left, str) and is_number(right):
        left = text_to_number(left, enums)
    elif is_number(left) and isinstance(right, str):
        right = text_to_number(right, enums)
    elif not (is_number(left) and is_number(right)):
        raise ScriptError(f"cannot compare {describe(left)} with {describe(right)} by [{op}]")
    a, b = float(left), float(right)
    if op == "==":
        return abs(a - b) <= EPSILON
    if op == "!=":
        return abs(a - b) > EPSILON
    return _COMPARE[op](a, b)
