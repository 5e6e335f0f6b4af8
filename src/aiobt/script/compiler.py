"""Compile a parsed script into nested closures: parse once, evaluate fast.

A compiled expression is ``fn(blackboard, enums) -> value``; enum names win
over blackboard keys, as in BT.CPP.
"""

from __future__ import annotations

import typing
from collections.abc import Callable, Mapping
from typing import Any

from aiobt.core.blackboard import Blackboard, Entry
from aiobt.core.convert import convert, is_convertible, type_name
from aiobt.core.errors import BlackboardError
from aiobt.script import operators
from aiobt.script.ast import Binary, Compare, Expr, Literal, Name, Ternary, Unary
from aiobt.script.errors import ScriptError
from aiobt.script.values import (
    assign_error,
    describe,
    divide,
    is_number,
    number_into,
    ternary_truth,
    text_to_number,
)

Enums = Mapping[str, int]
Compiled = Callable[[Blackboard, Enums], Any]


def compile_expr(expr: Expr) -> Compiled:
    if isinstance(expr, Literal):
        return _literal(expr.value)
    if isinstance(expr, Name):
        return _name(expr.name)
    if isinstance(expr, Unary):
        return _unary(expr.op, compile_expr(expr.operand))
    if isinstance(expr, Binary):
        return _binary(expr.op, compile_expr(expr.left), compile_expr(expr.right))
    if isinstance(expr, Compare):
        return _compare(expr.ops, tuple(compile_expr(e) for e in expr.operands))
    if isinstance(expr, Ternary):
        return _ternary(*(compile_expr(e) for e in (expr.condition, expr.then, expr.otherwise)))
    return _assign(expr.op, expr.key, compile_expr(expr.value))


def _literal(value: Any) -> Compiled:
    return lambda bb, enums: value


def _name(key: str) -> Compiled:
    def lookup(bb: Blackboard, enums: Enums) -> Any:
        if key in enums:
            return float(enums[key])
        entry = bb.entry(key)
        if entry is None:
            raise ScriptError(f"blackboard key [{key}] not found (nor an enum of that name)")
        if not entry.has_value:
            raise ScriptError(f"blackboard entry [{key}] has no value yet")
        return entry.value

    return lookup


def _unary(op: str, operand: Compiled) -> Compiled:
    return lambda bb, enums: operators.unary(op, operand(bb, enums))


def _binary(op: str, left: Compiled, right: Compiled) -> Compiled:
    apply = operators.binary(op)
    return lambda bb, enums: apply(left(bb, enums), right(bb, enums))


_FAST_COMPARE: dict[str, Callable[[float, float], bool]] = {
    "<": float.__lt__,
    ">": float.__gt__,
    "<=": float.__le__,
    ">=": float.__ge__,
}
_PLAIN_NUMBERS = (int, float)


def _compare(ops: tuple[str, ...], operands: tuple[Compiled, ...]) -> Compiled:
    if len(ops) == 1:
        return _compare_pair(ops[0], operands[0], operands[1])
    first, rest = operands[0], tuple(zip(ops, operands[1:], strict=True))
    compare = operators.compare

    def chain(bb: Blackboard, enums: Enums) -> float:
        left = first(bb, enums)
        for op, operand in rest:
            right = operand(bb, enums)
            if not compare(op, left, right, enums):
                return 0.0
            left = right
        return 1.0

    return chain


def _compare_pair(op: str, left_fn: Compiled, right_fn: Compiled) -> Compiled:
    """The common one-operator comparison, with a fast path for plain numbers."""
    compare = operators.compare
    fast = _FAST_COMPARE.get(op)

    def pair(bb: Blackboard, enums: Enums) -> float:
        left, right = left_fn(bb, enums), right_fn(bb, enums)
        if fast is not None and type(left) in _PLAIN_NUMBERS and type(right) in _PLAIN_NUMBERS:
            return 1.0 if fast(float(left), float(right)) else 0.0
        return 1.0 if compare(op, left, right, enums) else 0.0

    return pair


def _ternary(condition: Compiled, then: Compiled, otherwise: Compiled) -> Compiled:
    def choose(bb: Blackboard, enums: Enums) -> Any:
        if ternary_truth(condition(bb, enums)):
            return then(bb, enums)
        return otherwise(bb, enums)

    return choose


# -- assignment -------------------------------------------------------------------------
def _target_type(entry: Entry) -> Any:
    """The type an assignment must keep: the declared one, else the current value's."""
    tp = entry.type
    if tp is None and entry.has_value:
        tp = type(entry.value)
    if tp is not None and not isinstance(tp, type):
        tp = typing.get_origin(tp)
    return tp


def _store(bb: Blackboard, key: str, value: Any) -> Any:
    try:
        bb.set(key, value)
    except BlackboardError as exc:
        raise ScriptError(str(exc)) from exc
    return value


def _missing(key: str, op: str) -> ScriptError:
    return ScriptError(
        f"blackboard entry [{key}] does not exist yet; use [:=] instead of [{op}] to create it"
    )


def _converted(key: str, entry: Entry, value: Any, enums: Enums) -> Any:
    """``value`` made fit for ``entry`` (BT.CPP's rules for ``:=`` and ``=``)."""
    target = _target_type(entry)
    if target is None or target is object or (isinstance(value, target) and target is not int):
        return value
    if isinstance(value, str):
        declared = entry.type
        if declared is not None and declared is not str and is_convertible(declared):
            try:
                return convert(value, declared)
            except (ValueError, TypeError) as exc:
                raise ScriptError(
                    f"cannot assign to blackboard entry [{key}] of type "
                    f"{type_name(declared)} the string {value!r}: {exc}"
                ) from exc
        if entry.has_value and is_number(entry.value):
            return text_to_number(value, enums)
        raise assign_error(key, target, value)
    if is_number(value):
        return number_into(key, target, value)
    raise assign_error(key, target, value)


def _assign(op: str, key: str, value_fn: Compiled) -> Compiled:
    if op in (":=", "="):
        create = op == ":="

        def assign(bb: Blackboard, enums: Enums) -> Any:
            entry = bb.entry(key)
            if entry is None:
                if not create:
                    raise _missing(key, op)
                entry = bb.create_entry(key)
            value = value_fn(bb, enums)
            return _store(bb, key, _converted(key, entry, value, enums))

        return assign
    return _compound(op, key, value_fn)


def _compound(op: str, key: str, value_fn: Compiled) -> Compiled:
    arithmetic = {"+=": float.__add__, "-=": float.__sub__, "*=": float.__mul__, "/=": divide}[op]

    def update(bb: Blackboard, enums: Enums) -> Any:
        entry = bb.entry(key)
        if entry is None:
            raise _missing(key, op)
        if not entry.has_value:
            raise ScriptError(f"blackboard entry [{key}] has no value for [{op}]")
        current = entry.value
        value = value_fn(bb, enums)
        if is_number(value) and is_number(current):
            result = arithmetic(float(current), float(value))
            return _store(bb, key, number_into(key, _target_type(entry), result))
        if isinstance(value, str) and isinstance(current, str):
            if op != "+=":
                raise ScriptError(f"operator [{op}] is not defined for strings")
            return _store(bb, key, current + value)
        raise ScriptError(
            f"operator [{op}] cannot update blackboard entry [{key}] holding "
            f"{describe(current)} with {describe(value)}"
        )

    return update
