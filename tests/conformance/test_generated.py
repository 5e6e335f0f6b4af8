"""Random trees of the built-in nodes: BehaviorTree.CPP and aiobt agree tick by tick.

Each seed is one test; a failure prints the seed's XML, scripts and the first
step where the two differ. More trees:
``AIOBT_CONFORMANCE_TREES=5000 .venv/bin/python -m pytest tests/conformance``.
"""

from __future__ import annotations

import os
from collections import Counter

import pytest
from lxml import etree

from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.nodes.decorators.inverter import Inverter
from tests.conformance.generator import CONTROLS, DECORATORS, generate
from tests.conformance.harness import assert_conforms, compare

pytestmark = pytest.mark.conformance

TREES = int(os.environ.get("AIOBT_CONFORMANCE_TREES", "500"))
FIRST_SEED = int(os.environ.get("AIOBT_CONFORMANCE_FIRST_SEED", "0"))


@pytest.mark.parametrize("seed", range(FIRST_SEED, FIRST_SEED + TREES))
async def test_random_tree_matches_btcpp(seed: int) -> None:
    await assert_conforms(generate(seed))


@pytest.mark.parametrize("seed", range(FIRST_SEED, FIRST_SEED + TREES))
async def test_random_tree_matches_btcpp_with_nobody_listening(seed: int) -> None:
    # no status listener: the quiet fast paths run, results and leaf calls must agree
    await assert_conforms(generate(seed), listen=False)


def test_generator_covers_every_node_and_operation() -> None:
    tags: Counter[str] = Counter()
    ops: Counter[str] = Counter()
    for seed in range(500):  # the default run, whatever the environment asks
        scenario = generate(seed)
        tags.update(e.tag for e in etree.fromstring(scenario.xml.encode()).iter())
        ops.update(scenario.ops)
    expected = {c for c in CONTROLS if c != "Switch"} | set(DECORATORS)
    expected |= {"Switch2", "Switch3", "Switch4", "ScriptedStateful", "ScriptedAction"}
    expected |= {"ScriptedCondition", "AlwaysSuccess", "AlwaysFailure", "SetBlackboard"}
    assert expected <= set(tags), expected - set(tags)
    assert min(ops[op] for op in ("exactly", "once", "halt")) >= 50


class _BrokenInverter(Inverter):
    """Passes SUCCESS through: the harness must notice."""

    __slots__ = ()

    def execute_sync(self) -> Status:
        status = super().execute_sync()
        return Status.SUCCESS if status is Status.FAILURE else status


def _break_inverter(factory: BehaviorTreeFactory) -> None:
    factory.register_node_type(_BrokenInverter, "Inverter", replace=True)


async def test_harness_reports_a_wrong_node() -> None:
    found = []
    for seed in range(200):
        scenario = generate(seed)
        if "<Inverter" in scenario.xml:
            _, _, difference = await compare(scenario, _break_inverter)
            found.append(difference)
    assert any(d is not None and "step" in d for d in found)
