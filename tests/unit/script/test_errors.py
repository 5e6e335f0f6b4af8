"""Syntax errors name the column; runtime errors name the key and the types."""

from __future__ import annotations

import contextlib

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aiobt.core.blackboard import Blackboard
from aiobt.script import ScriptError, ScriptSyntaxError, compile_script, run_script


@pytest.mark.parametrize(
    ("source", "column", "fragment"),
    [
        ("", 1, "empty script"),
        ("   ", 4, "empty script"),
        ("a := ", 6, "unexpected end"),
        ("a := 1;", 7, "trailing ';'"),
        ("a := 3;; b := 1", 8, "expected an operand"),
        ("a := 3 a", 8, "expected ';'"),
        ("a := 5 % 2", 8, "unexpected character '%'"),
        ("a := 1 and 0", 8, "expected ';'"),
        ("a := (1 + 2", 12, "expected ')'"),
        ("a := 'open", 6, "missing closing quote"),
        ("a := 1.", 7, "invalid suffix on integer"),
        ("a := 3px", 7, "invalid suffix on integer"),
        ("a := 1.5x", 9, "invalid suffix on double"),
        ("a := 1..2", 7, "space before '..'"),
        ("a := .5", 6, "unexpected character '.'"),
        ("a := 0x", 8, "hex digit"),
        ("a := 0x8000000000000000", 6, "out of range"),
        ("a := + 5", 6, "number right after '+'"),
        ("a := @", 6, "key name after @"),
        ("a := 5 + 3 & 1", 12, "[&] (bitwise) cannot be mixed with the arithmetic"),
        ("a := -1 & 3", 9, "cannot be mixed"),
        ("a := ~-1", 7, "[-] (arithmetic) cannot be mixed with the bitwise"),
        ("a := 1 & -1", 10, "cannot be mixed"),
        ("a := 'x' .. 1 + 2", 15, "[+] (arithmetic) cannot be mixed with the string"),
        ("a := 1 + 2 .. 'x'", 12, "[..] (string) cannot be mixed"),
        ("a := b := 3", 8, "cannot be chained"),
        ("a := 1 ? 2 : 3 ? 4 : 5", 16, "cannot be chained"),
        ("a := 1 ? 2", 11, "expected ':'"),
        ("1 := 2", 3, "left side of [:=] must be a blackboard key"),
        ("(a) + 1 = 2", 9, "left side of [=]"),
        # one operator family per expression, across comparisons and logic
        ("a := 1 + 1 == 2 & 2", 17, "[&] (bitwise) cannot be mixed"),
        ("a := 1 + 1 && 1 & 1", 17, "cannot be mixed"),
        ("a := 1 & 1 ? 2 : 3 + 3", 20, "cannot be mixed"),
    ],
)
def test_syntax_errors_name_the_column(source: str, column: int, fragment: str) -> None:
    with pytest.raises(ScriptSyntaxError) as info:
        compile_script(source)
    assert info.value.column == column
    assert fragment in str(info.value)
    assert str(info.value).startswith(f"column {column}: ")
    assert info.value.pointer().splitlines()[1] == " " * (column - 1) + "^"


def run(source: str, **entries: object) -> object:
    bb = Blackboard.create()
    for key, value in entries.items():
        bb.set(key, value)
    return run_script(source, bb)


@pytest.mark.parametrize(
    ("source", "entries", "fragments"),
    [
        ("a := b", {}, ("[b] not found",)),
        ("a = 3", {}, ("[a] does not exist yet", "[:=] instead of [=]")),
        ("a += 3", {}, ("[a] does not exist yet", "[+=]")),
        ("s = 5", {"s": "text"}, ("[s]", "std::string", "int")),
        ("i = 2.5", {"i": 10}, ("[i]", "type int", "2.5", "double")),
        ("i = 'x'", {"i": 10}, ("[i]", "int", "'x'")),
        ("i /= 4", {"i": 10}, ("[i]", "type int", "2.5")),
        ("f = 2", {"f": True}, ("[f]", "bool", "int")),
        ("s -= 'x'", {"s": "a"}, ("[-=]", "strings")),
        ("s += 1", {"s": "a"}, ("[s]", "std::string", "int")),
        ("i += 'y'", {"i": 1}, ("[i]", "int", "'y'")),
        ("x := 's' + 1", {}, ("[+]", "std::string 's'", "int 1")),
        ("x := 3 .. 4", {}, ("[..]", "string on at least one side")),
        ("x := 1.5 & 1", {}, ("[&] needs integers", "1.5")),
        ("x := 2 && 1", {}, ("integer 2 is not a bool",)),
        ("x := 1 && 'x'", {}, ("[&&]", "std::string")),
        ("x := -'x'", {}, ("[-] cannot be applied", "std::string")),
        ("x := !'x'", {}, ("[!] cannot be applied",)),
        ("x := 'a' < 1", {}, ("string 'a' to a number",)),
        ("x := '' ? 1 : 2", {}, ("string '' to a number",)),
        ("x := 'yes' ? 1 : 2", {}, ("string 'yes' to a number",)),
        ("x := l == 1", {"l": [1]}, ("cannot compare", "list")),
    ],
)
def test_runtime_errors_name_keys_and_types(
    source: str, entries: dict[str, object], fragments: tuple[str, ...]
) -> None:
    with pytest.raises(ScriptError) as info:
        run(source, **entries)
    assert not isinstance(info.value, ScriptSyntaxError)
    for fragment in fragments:
        assert fragment in str(info.value), str(info.value)


def test_failed_assignment_leaves_the_entry_unchanged() -> None:
    bb = Blackboard.create()
    bb.set("i", 10)
    with pytest.raises(ScriptError):
        run_script("i = 'x'", bb)
    assert bb["i"] == 10


def test_entry_without_value_is_reported() -> None:
    bb = Blackboard.create()
    bb.create_entry("pending", int)
    with pytest.raises(ScriptError, match=r"\[pending\] has no value"):
        run_script("x := pending + 1", bb)
    with pytest.raises(ScriptError, match=r"\[pending\] has no value for \[\+=\]"):
        run_script("pending += 1", bb)


SCRIPT_CHARS = "ab@_019x.:=+-*/&|^~!<>?()'\" ;e"


@settings(max_examples=400, deadline=None)
@given(st.text(alphabet=SCRIPT_CHARS, max_size=24))
def test_any_text_compiles_or_fails_with_a_script_error(source: str) -> None:
    """No input crashes the parser or the evaluator with anything but a ScriptError."""
    column = None
    try:
        script = compile_script(source)
    except ScriptSyntaxError as exc:
        column = exc.column
    if column is not None:
        assert 1 <= column <= len(source) + 1
        return
    bb = Blackboard.create()
    bb.set("a", 1)
    bb.set("b", "text")
    with contextlib.suppress(ScriptError):
        script(bb)


def test_deep_nesting_is_a_syntax_error_not_a_crash() -> None:
    assert compile_script("(" * 60 + "1" + ")" * 60)(Blackboard.create()) == 1
    with pytest.raises(ScriptSyntaxError, match="nested more than 64"):
        compile_script("(" * 500 + "1" + ")" * 500)
    assert compile_script("-" * 100 + "1")(Blackboard.create()) == 1.0
    for source in ("-" * 3000 + "1", " - ".join(["1"] * 3000), " .. ".join(["'a'"] * 3000)):
        with pytest.raises(ScriptSyntaxError, match="too deeply nested"):
            compile_script(source)
