"""Typed assignment: once an entry holds a type, assignments keep it (BT.CPP's rules)."""

from __future__ import annotations

from typing import Any

import pytest

from aiobt.core.blackboard import Blackboard
from aiobt.script import run_script


def after(source: str, **entries: Any) -> dict[str, Any]:
    bb = Blackboard.create()
    for key, value in entries.items():
        bb.set(key, value)
    run_script(source, bb)
    return bb.snapshot()


@pytest.mark.parametrize(
    ("source", "entries", "key", "expected"),
    [
        ("a := 3", {}, "a", 3),
        ("a := 3.0", {}, "a", 3.0),
        ("a := 'x'", {}, "a", "x"),
        ("a := 3; a = 2.0", {}, "a", 2),  # an integral double fits an int entry
        ("a := 3; a = 1 + 1", {}, "a", 2),
        ("a := 3; a += 2", {}, "a", 5),
        ("a := 2.5; a = 3", {}, "a", 3.0),  # an int widens into a double entry
        ("i = '5'", {"i": 1}, "i", 5),  # strings convert into typed entries
        ("d = '1.5'", {"d": 0.5}, "d", 1.5),
        ("f = 0", {"f": True}, "f", False),
        ("f = 'false'", {"f": True}, "f", False),
        ("f = 1.0", {"f": False}, "f", True),
        ("f = 5 > 3", {"f": False}, "f", True),
        ("i = true", {"i": 7}, "i", 1),
        ("s = 'new'", {"s": "old"}, "s", "new"),
        ("s += 'x'", {"s": "42"}, "s", "42x"),
        ("a := 1; a := 2", {}, "a", 2),  # := on an existing entry assigns
        ("a := 1 == 1", {}, "a", 1.0),
    ],
)
def test_assignment_keeps_types(
    source: str, entries: dict[str, Any], key: str, expected: Any
) -> None:
    got = after(source, **entries)[key]
    assert got == expected
    assert type(got) is type(expected)


def test_a_declared_port_type_converts_strings() -> None:
    bb = Blackboard.create()
    bb.create_entry("goal", list[int])
    run_script("goal := '1;2;3'", bb)
    assert bb["goal"] == [1, 2, 3]


def test_assignment_returns_the_stored_value_and_bumps_the_sequence() -> None:
    bb = Blackboard.create()
    assert run_script("a := 3; a = 4.0", bb) == 4
    entry = bb.entry("a")
    assert entry is not None
    assert entry.sequence_id == 2


def test_creation_follows_subtree_remapping() -> None:
    parent = Blackboard.create()
    child = Blackboard.create(parent)
    child.add_remapping("inner", "outer")
    run_script("inner := 7", child)
    assert parent["outer"] == 7
