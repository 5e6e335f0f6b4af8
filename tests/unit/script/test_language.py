"""The script language: every operator, precedence, families, values and types."""

from __future__ import annotations

import math
from typing import Any

import pytest

from aiobt.core.blackboard import Blackboard
from aiobt.script import Script, compile_script, run_script


def value_of(source: str, **entries: Any) -> Any:
    bb = Blackboard.create()
    for key, value in entries.items():
        bb.set(key, value)
    return run_script(source, bb)


def same(got: Any, expected: Any) -> bool:
    """Equal value and equal type (1 and 1.0 differ: BT.CPP keeps int vs double)."""
    if isinstance(expected, float) and math.isnan(expected):
        return isinstance(got, float) and math.isnan(got)
    return type(got) is type(expected) and got == expected


@pytest.mark.parametrize(
    ("source", "expected"),
    [
        # literals: integers stay int, reals are float, booleans are the ints 1/0
        ("42", 42),
        ("+5", 5),
        ("0x1F", 31),
        ("0X10", 16),
        ("1.5", 1.5),
        ("2e3", 2000.0),
        ("1.5e-1", 0.15),
        ("true", 1),
        ("false", 0),
        ("'single'", "single"),
        ('"double"', "double"),
        ("''", ""),
        # arithmetic always gives float
        ("1 + 2", 3.0),
        ("7 - 10", -3.0),
        ("6 * 7", 42.0),
        ("7 / 2", 3.5),
        ("1 / 0", math.inf),
        ("-1 / 0", -math.inf),
        ("0 / 0", math.nan),
        ("-5", -5.0),
        ("- -3", 3.0),
        ("3 - -2", 5.0),
        ("'ab' + 'cd'", "abcd"),
        # precedence: * / over + -; parentheses
        ("2 * 3 + 4 * 5", 26.0),
        ("1 + 2 * 3", 7.0),
        ("(1 + 2) * 3", 9.0),
        # BT.CPP 4.8 groups + - and * / from the right
        ("5 - 2 + 1", 2.0),
        ("2 - 1 - 1", 2.0),
        ("8 / 2 / 2", 8.0),
        ("2 / 2 * 4", 0.25),
        ("(5 - 2) + 1", 4.0),
        ("4 / 2 / 2 + 1", 5.0),
        # bitwise: & over | ^, left to right; results are float
        ("5 & 3", 1.0),
        ("5 | 3", 7.0),
        ("5 ^ 3", 6.0),
        ("~5", -6.0),
        ("~1.5", -2.0),
        ("5 & 3 | 8", 9.0),
        ("1 | 2 ^ 3", 0.0),
        ("1 | 2 ^ 3 & 1", 2.0),
        ("1 & 2.0", 0.0),
        ("!0", 1.0),
        ("!3", 0.0),
        ("!!3", 1.0),
        ("!1 & 3", 0.0),
        # logic: one level, left to right
        ("1 && 0", 0.0),
        ("1 || 0", 1.0),
        ("0.5 && 1", 1.0),
        ("1 || 1 && 0", 0.0),
        ("1 && 0 || 1", 1.0),
        # comparisons: float results, chained pairwise
        ("1 == 1.0", 1.0),
        ("1 == 1.0000001", 1.0),
        ("1 != 2", 1.0),
        ("2 < 1", 0.0),
        ("2 <= 2", 1.0),
        ("3 >= 4", 0.0),
        ("5 > 3 > 1", 1.0),
        ("1 < 3 < 2", 0.0),
        ("1 < 2 == 1", 0.0),
        ("3 == 3 == 1", 0.0),
        ("1 != 2 != 1", 1.0),
        ("'abc' < 'abd'", 1.0),
        ("'abc' == 'abc'", 1.0),
        ("'true' == 1", 1.0),
        ("'2.5' > 2", 1.0),
        ("' 5' == 5", 1.0),  # strings read as numbers the way C's strtod does
        ("'0x10' == 16", 1.0),
        ("'5x' == 5", 1.0),
        ("'1e2' == 100", 1.0),
        # string concatenation
        ("'x' .. 'y'", "xy"),
        ("'x' .. 3", "x3"),
        ("'x' .. 3.5", "x3.500000"),
        ("3 .. 'x'", "3x"),
        ("'a' .. 'b' .. 'c'", "abc"),
        ("'x' .. 1 .. 2", "x12"),
        # ternary
        ("1 ? 'y' : 'n'", "y"),
        ("0 ? 'y' : 'n'", "n"),
        ("'2' ? 1 : 2", 1),  # a string condition is read as a number, as BT.CPP
        ("'0' ? 1 : 2", 2),
        ("2 ? 1 : 2", 1),
        ("1 == 1 ? 'y' : 'n'", "y"),
        ("1 ? 2 : 3 + 4", 2),
        ("1 & 1 ? 2 + 2 : 3", 4.0),  # the middle of a ternary is a new expression
        ("1 + 1 == (2 & 2)", 1.0),
        ("0 ? 2 : (1 ? 3 : 4)", 3),
    ],
)
def test_expression_values(source: str, expected: Any) -> None:
    got = value_of(source)
    assert same(got, expected), f"{source!r} gave {got!r}, expected {expected!r}"


def test_statements_run_in_order_and_the_last_value_is_returned() -> None:
    bb = Blackboard.create()
    assert run_script("a := 1; b := a + 1; c := b * 10", bb) == 20.0
    assert bb.snapshot() == {"a": 1, "b": 2.0, "c": 20.0}


def test_ternary_branch_may_assign() -> None:
    bb = Blackboard.create()
    assert run_script("a := 1 ? b := 3 : 4", bb) == 3
    assert bb.snapshot() == {"b": 3, "a": 3}


def test_whitespace_is_free_between_tokens() -> None:
    bb = Blackboard.create()
    run_script("a:=1;b:=a+1\n;  c\t:= 'x'", bb)
    assert bb.snapshot() == {"a": 1, "b": 2.0, "c": "x"}


def test_compound_assignments() -> None:
    bb = Blackboard.create()
    run_script("i := 10; i -= 4; i *= 2; f := 1.0; f /= 4; f += 1; s := 'a'; s += 'b'", bb)
    assert bb.snapshot() == {"i": 12, "f": 1.25, "s": "ab"}
    assert type(bb["i"]) is int


def test_names_read_the_blackboard_and_root_keys() -> None:
    root = Blackboard.create()
    child = Blackboard.create(root)
    root.set("speed", 2.5)
    run_script("@limit := @speed * 2; local := 1", child)
    assert root["limit"] == 5.0
    assert "local" not in root
    assert child["local"] == 1


def test_enums_are_numbers_and_win_over_keys() -> None:
    bb = Blackboard.create()
    bb.set("RED", 99)
    script = compile_script("color := RED; is_blue := color == BLUE; s := 'BLUE' == BLUE")
    script(bb, {"RED": 1, "BLUE": 2})
    assert bb.snapshot() == {"RED": 99, "color": 1.0, "is_blue": 0.0, "s": 1.0}


def test_bool_entries_are_numbers() -> None:
    assert value_of("f + 1", f=True) == 2.0
    assert value_of("!f", f=True) == 0.0
    assert value_of("f && 1", f=True) == 1.0


def test_compiled_script_is_reusable_and_checks_as_condition() -> None:
    script = Script("count += 1; count < 3")
    bb = Blackboard.create()
    bb.set("count", 0)
    results = [script.check(bb) for _ in range(4)]
    assert results == [True, True, False, False]
    assert bb["count"] == 4
    assert repr(script) == "Script('count += 1; count < 3')"


def test_comparison_stops_at_the_first_false_link() -> None:
    # the unknown key is never read once 1 > 2 is false (as BT.CPP)
    assert value_of("1 > 2 > missing") == 0.0
