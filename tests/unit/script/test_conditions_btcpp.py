"""Condition attributes under BehaviorTree.CPP 4.8 and aiobt: same statuses, calls, transitions.

Generated trees of scripted leaves carry ``_skipIf``/``_failureIf``/
``_successIf``/``_while`` over counters that ``_onSuccess``/``_onFailure``/
``_post``/``_onHalted`` scripts update, so the order and the moments of every
condition show in the leaf calls and status transitions the harness compares.
"""

from __future__ import annotations

import random

import pytest

from tests.conformance.harness import Scenario, assert_conforms

pytestmark = pytest.mark.conformance

PRE = (
    ('_skipIf="c &gt;= {n}"', '_skipIf="p == {n}"'),
    ('_failureIf="c == {n}"', '_failureIf="h &gt; 0 &amp;&amp; c &lt; {n}"'),
    ('_successIf="p &gt; {n}"', '_successIf="c == {n} || h == {n}"'),
    ('_while="c &lt; {n}"', '_while="p &lt;= {n}"', '_while="h == 0"'),
)
POST = ('_onSuccess="c += 1"', '_onFailure="c += 2"', '_post="p += 1"', '_onHalted="h += 1"')
CONTROLS = ("Sequence", "ReactiveSequence", "Fallback", "ReactiveFallback", "SequenceWithMemory")
LEAF_SCRIPTS = ("RS", "RRF", "S", "F", "RSF", "RRRS")


def leaf(rng: random.Random, name: str, scripts: dict[str, tuple[str, ...]]) -> str:
    attrs = [rng.choice(group).format(n=rng.randint(0, 3)) for group in PRE if rng.random() < 0.4]
    attrs += [post for post in POST if rng.random() < 0.4]
    scripts[name] = tuple(rng.choice(LEAF_SCRIPTS))
    return f'<ScriptedStateful name="{name}" {" ".join(attrs)}/>'


def scenario(seed: int) -> Scenario:
    rng = random.Random(seed)
    scripts: dict[str, tuple[str, ...]] = {}
    leaves = "".join(leaf(rng, f"L{i}", scripts) for i in range(rng.randint(2, 3)))
    control = rng.choice(CONTROLS)
    inner_attrs = rng.choice(("", '_skipIf="c &gt; 5"', '_while="p &lt; 6"', '_post="p += 1"'))
    xml = (
        '<root BTCPP_format="4"><BehaviorTree ID="M"><Sequence>'
        '<Script code="c := 0; p := 0; h := 0"/>'
        f"<KeepRunningUntilFailure><{control} {inner_attrs}>{leaves}</{control}>"
        "</KeepRunningUntilFailure></Sequence></BehaviorTree></root>"
    )
    ops = ("exactly",) * rng.randint(4, 8) + ("halt", "exactly", "exactly")
    return Scenario(xml, scripts, ops)


@pytest.mark.parametrize("seed", range(80))
async def test_generated_condition_trees_conform(seed: int) -> None:
    await assert_conforms(scenario(seed))


async def test_while_turning_false_halts_the_running_leaf() -> None:
    xml = (
        '<root BTCPP_format="4"><BehaviorTree ID="M"><Sequence>'
        '<Script code="n := 0; h := 0"/>'
        "<ReactiveSequence>"
        '<ScriptedAction name="Inc" _onSuccess="n += 1"/>'
        '<ScriptedStateful name="Long" _while="n &lt; 3" _onHalted="h += 1"/>'
        "</ReactiveSequence>"
        '<ScriptCondition code="h == 1"/>'
        "</Sequence></BehaviorTree></root>"
    )
    steps = await assert_conforms(
        Scenario(xml, {"Inc": ("S",), "Long": ("R",)}, ("exactly", "exactly", "exactly"))
    )
    assert [step.result for step in steps] == ["RUNNING", "RUNNING", "SUCCESS"]
    assert steps[2].calls == ["tick:Inc", "halted:Long"]


async def test_subtrees_root_keys_and_remapping_conform() -> None:
    xml = (
        '<root BTCPP_format="4" main_tree_to_execute="M">'
        '<BehaviorTree ID="M"><Sequence>'
        '<Script code="n := 0; @total := 0"/>'
        '<SubTree ID="Sub" count="{n}" _skipIf="n &gt; 2" _onSuccess="n += 1"/>'
        '<SubTree ID="Auto" _autoremap="true" _while="n &lt; 2"/>'
        '<ScriptCondition code="@total == 1 &amp;&amp; n == 1"/>'
        "</Sequence></BehaviorTree>"
        '<BehaviorTree ID="Sub"><Sequence>'
        '<ScriptedAction name="Inner" _onSuccess="@total += 1"/>'
        '<Script code="local := count"/>'
        "</Sequence></BehaviorTree>"
        '<BehaviorTree ID="Auto"><ScriptedStateful name="Deep" _onHalted="n := 9"/>'
        "</BehaviorTree></root>"
    )
    steps = await assert_conforms(
        Scenario(xml, {"Inner": ("S",), "Deep": ("S",)}, ("exactly", "exactly", "halt"))
    )
    assert [step.result for step in steps] == ["SUCCESS", "SUCCESS", "halted"]
