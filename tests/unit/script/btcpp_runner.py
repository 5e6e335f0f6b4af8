"""Run a script under BehaviorTree.CPP 4.8 (behaviortreepy) and under aiobt, same shape.

An outcome is ``("load-error", "")``, ``("error", "")`` or ``("ok", values)``
where ``values`` maps each blackboard key to ``(kind, value)`` with kind
``int``, ``double`` or ``string``, so 1 and 1.0 differ as they do in BT.CPP.
"""

from __future__ import annotations

import math
from typing import Any
from xml.sax.saxutils import quoteattr

import behaviortreepy as btcpp

from aiobt.core.blackboard import Blackboard
from aiobt.core.errors import TreeLoadError
from aiobt.factory import BehaviorTreeFactory

Outcome = tuple[str, Any]


def tree_text(code: str) -> str:
    return (
        '<root BTCPP_format="4"><BehaviorTree ID="M">'
        f"<Script code={quoteattr(code)}/></BehaviorTree></root>"
    )


def _btcpp_value(bb: Any, key: str) -> tuple[str, Any]:
    try:
        bb.get_bool(key)
    except Exception as exc:
        if "std::string" in str(exc):
            return ("string", bb.get_string(key))
    text = bb.get_string(key)
    if any(mark in text for mark in (".", "inf", "nan")):
        return ("double", bb.get_double(key))
    return ("int", bb.get_int(key))


def run_btcpp(code: str) -> Outcome:
    factory = btcpp.BehaviorTreeFactory()
    bb = btcpp.Blackboard.create()
    try:
        tree = factory.create_tree_from_text(tree_text(code), bb)
    except Exception:
        return ("load-error", "")
    try:
        tree.tick_once()
    except Exception:
        return ("error", "")
    return ("ok", {key: _btcpp_value(bb, key) for key in sorted(bb.get_keys())})


def _aiobt_value(value: Any) -> tuple[str, Any]:
    if isinstance(value, str):
        return ("string", value)
    if isinstance(value, float):
        return ("double", value)
    return ("int", int(value))


async def run_aiobt(code: str) -> Outcome:
    factory = BehaviorTreeFactory()
    bb = Blackboard.create()
    try:
        tree = factory.create_tree_from_text(tree_text(code), blackboard=bb)
    except TreeLoadError:
        return ("load-error", "")
    try:
        await tree.tick_once()
    except Exception:
        return ("error", "")
    return ("ok", {key: _aiobt_value(value) for key, value in sorted(bb.snapshot().items())})


def same_outcome(reference: Outcome, candidate: Outcome) -> bool:
    if reference[0] != candidate[0]:
        return False
    if reference[0] != "ok":
        return True
    ref, got = reference[1], candidate[1]
    if ref.keys() != got.keys():
        return False
    return all(_same_value(ref[key], got[key]) for key in ref)


def _same_value(ref: tuple[str, Any], got: tuple[str, Any]) -> bool:
    if ref[0] != got[0]:
        return False
    if ref[0] == "double":
        a, b = float(ref[1]), float(got[1])
        return (math.isnan(a) and math.isnan(b)) or a == b
    return bool(ref[1] == got[1])
