"""Scripts run under BehaviorTree.CPP 4.8 (behaviortreepy) and aiobt give the same results.

A hand-written corpus of the surprising cases, then generated expressions
(fixed seeds). Compared: load error vs runtime error vs success, and on
success every blackboard entry with its kind (int, double, string).
"""

from __future__ import annotations

import random

import pytest

from tests.unit.script.btcpp_runner import run_aiobt, run_btcpp, same_outcome

pytestmark = pytest.mark.conformance

CORPUS = [
    "a := 1; b := a + 2.5; s := 'hi' .. 'x'; c := 5 > 3 > 1; h := 0x1F; d := 7/2",
    "a := 'x' .. 3",
    "a := 3 .. 4",
    "a := 'x' + 'y'",
    "a := 1 and 0",
    "a := !0",
    "a := 1 < 3 < 2",
    "a := 1 == 1.0",
    "a := ~5",
    "a := 5 & 3 | 8",
    "a := 5 + 3 & 1",
    "a := 1.5 & 1",
    'a := "dq"',
    "a := true",
    "a := 0x1f + 1",
    "a := -0x10",
    "a := 1e3",
    "a := 1.",
    "a := .5",
    "a := 3; a = 'x'",
    "a := 'x'; a = 3",
    "a = 3",
    "a := 3; a += 2",
    "a := 'x'; a += 'y'",
    "a := 'x'; a += 1",
    "a := 1 ? 'y' : 'n'",
    "a := 1 ? 2 : 3 ? 4 : 5",
    "a := '' ? 1 : 2",
    "a := 3; b := a == 3 ? 10 : 20",
    "@a := 4",
    "a := 3 - -2",
    "a := 2 * 3 + 4 * 5",
    "a := (1 + 2) * 3",
    "a := 1 && 'x'",
    "a := 5 % 2",
    "a := 3;; b := 1",
    "a := 3;",
    "a := b",
    "a := 3 a",
    "a := 10; a /= 4",
    "a := 10; a -= 4; a *= 2",
    "a := 'abc' < 'abd'",
    "a := 'a' == 1",
    "a := 1 != 2 != 1",
    "a := 0x",
    "a := 1 & 2.0",
    "a := !'x'",
    "a := -'x'",
    "a := +5",
    "a := -1 & 3",
    "a := !1 & 3",
    "a := 'x' .. 1 + 2",
    "a := 'x' .. 3.5",
    "a := 1 + 2 .. 'x'",
    "a := 2 && 1",
    "a := 0.5 && 1",
    "a := 10; a = 2.5",
    "a := 10; a = 2.0",
    "a := 1 ? b := 3 : 4",
    "a := b := 3",
    "a := 3 == 3 == 1",
    "a := 1; a = true",
    "a := 1/0",
    "a := 1 ? 2 : 3 + 4",
    "a := 1 || 0 && 0",
    "a := 1 || 1 && 0",
    "a := ~1.5",
    "a := !!3",
    "a := - -3",
    "a := 1 < 2 == 1",
    "a := 'a' < 1",
    "a := 'true' == 1",
    "a := 5 - 2 + 1",
    "a := 2 / 2 * 4",
    "a := 1 - 1 - 1 - 1",
    "a := 10 - 2 * 3 - 1",
    "a := 'a' .. 'b' .. 'c'",
    "a := 1 | 2 ^ 3",
    "a := 1 .. 2 .. 'x'",
    "a := 'x' .. 1 .. 2",
    "a := 4 / 2 / 2 + 1",
    "a := ~-1",
    "a := 1 & -1",
    "a := 1 ? 2",
    "a := (1",
    "   ",
    "",
    "a:=1;b:=a+1",
    "x := 1; x = 'y'",
    "s := 'ab'; s -= 'a'",
    "a := 5; a = 1 > 0",
]


@pytest.mark.parametrize("code", CORPUS)
async def test_corpus_matches_btcpp(code: str) -> None:
    reference, candidate = run_btcpp(code), await run_aiobt(code)
    assert same_outcome(reference, candidate), f"{code!r}: BT.CPP {reference}, aiobt {candidate}"


# -- generated expressions ------------------------------------------------------------

ATOMS = ("0", "1", "2", "3", "7", "0x0F", "1.5", "0.25", "2e1", "true", "false",
         "x", "y", "s", "n", "'a'", "'10'", "'true'", "''")  # fmt: skip
FAMILIES = (("+", "-", "*", "/"), ("&", "|", "^"), ("..",))
PREFIX = {"+": "-", "&": "~", "..": ""}
COMPARE = ("==", "!=", "<", ">", "<=", ">=")
PRELUDE = "x := 3; y := 2.5; s := 'ab'; n := '4'; "


def operand(rng: random.Random, depth: int) -> str:
    if depth > 0 and rng.random() < 0.3:
        return f"({expression(rng, depth - 1)})"
    atom = rng.choice(ATOMS)
    if rng.random() < 0.15:
        return rng.choice(("-", "!", "~")) + atom
    return atom


def group(rng: random.Random, depth: int) -> str:
    ops: tuple[str, ...] = rng.choice(FAMILIES)
    if rng.random() < 0.1:  # sometimes mix families on purpose: a load error in both
        ops = ops + rng.choice(FAMILIES)
    parts = [operand(rng, depth)]
    for _ in range(rng.randint(0, 3)):
        parts += [rng.choice(ops), operand(rng, depth)]
    return " ".join(parts)


def expression(rng: random.Random, depth: int) -> str:
    roll = rng.random()
    if roll < 0.5:
        return group(rng, depth)
    if roll < 0.7:
        parts = [group(rng, depth)]
        for _ in range(rng.randint(1, 2)):
            parts += [rng.choice(COMPARE), group(rng, depth)]
        return " ".join(parts)
    if roll < 0.85:
        return f"{group(rng, depth)} {rng.choice(('&&', '||'))} {group(rng, depth)}"
    return f"{group(rng, depth)} ? {expression(rng, depth - 1)} : {group(rng, depth)}"


GENERATED = [expression(random.Random(seed), 2) for seed in range(300)]


@pytest.mark.parametrize("expr", GENERATED)
async def test_generated_expressions_match_btcpp(expr: str) -> None:
    code = f"{PRELUDE}r := {expr}"
    reference, candidate = run_btcpp(code), await run_aiobt(code)
    assert same_outcome(reference, candidate), f"{code!r}: BT.CPP {reference}, aiobt {candidate}"


ASSIGNMENTS = [
    "i := 3; i = 2.0", "i := 3; i = 'x'", "i := 3; i += 1.5", "i := 3; i *= 2",
    "d := 1.5; d = 2", "d := 1.5; d -= 'x'", "t := 'a'; t = 1", "t := 'a'; t += 'b'",
    "t := 'a'; t += 1", "i := 3; i = 1 == 1", "d := 0.5; d /= 0", "i := 2; i /= 0",
    "i := 4; i /= 2", "@r := 1; @r += 1", "b := true; b += 1", "s := 'x'; s = 'y' .. 1",
]  # fmt: skip


@pytest.mark.parametrize("code", ASSIGNMENTS)
async def test_assignments_match_btcpp(code: str) -> None:
    reference, candidate = run_btcpp(code), await run_aiobt(code)
    assert same_outcome(reference, candidate), f"{code!r}: BT.CPP {reference}, aiobt {candidate}"
