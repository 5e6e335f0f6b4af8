"""Run one scenario under BehaviorTree.CPP (behaviortreepy) and under aiobt.

A :class:`Scenario` is an XML tree whose leaves are scripted, a script per
leaf name, and a program of operations (``exactly`` = tick_exactly_once,
``once`` = tick_once, ``halt`` = halt_tree). Each operation gives a
:class:`Step`: the status returned (or ``error``), the leaf callbacks made
during it in order, and every node status change in order (BT.CPP's from its
StdCoutLogger, aiobt's from a status listener), as ``name:PREVIOUS>STATUS``.

Scripted leaves (IDs registered in both factories):

- ``ScriptedAction``: a sync action, one script entry per tick (``S``/``F``);
- ``ScriptedCondition``: a condition, likewise;
- ``ScriptedStateful``: a StatefulActionNode; on_start and on_running each take
  the next entry (``R``/``S``/``F``); on_halted is recorded.

Scripts repeat from their start when used up. Both sides share no state: each
run gets a fresh :class:`Driver`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import behaviortreepy as btcpp
from lxml import etree

from aiobt.core.node import TreeNode
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from tests.conformance.stdout_log import capture_fd1, parse

OPS = ("exactly", "once", "halt")
CALL_BUDGET = 5000
RESULTS = {"S": "SUCCESS", "F": "FAILURE", "R": "RUNNING"}


@dataclass(frozen=True, slots=True)
class Scenario:
    xml: str
    scripts: dict[str, tuple[str, ...]]
    ops: tuple[str, ...]

    def describe(self) -> str:
        scripts = "\n".join(f"  {name}: {''.join(s)}" for name, s in sorted(self.scripts.items()))
        return f"{self.xml}\nscripts:\n{scripts}\nops: {' '.join(self.ops)}"


@dataclass(slots=True)
class Step:
    op: str
    result: str
    calls: list[str] = field(default_factory=list)
    transitions: list[str] = field(default_factory=list)
    error: str = ""

    def key(self) -> tuple[str, str, list[str], list[str]]:
        return (self.op, self.result, self.calls, self.transitions)

    def describe(self) -> str:
        text = f"{self.op} -> {self.result} {self.error}\n    calls: {' '.join(self.calls)}"
        return f"{text}\n    transitions: {' '.join(self.transitions)}"


def tree_xml(body: str) -> str:
    """A v4 document whose only tree, ``Main``, is ``body``."""
    return f'<root BTCPP_format="4"><BehaviorTree ID="Main">{body}</BehaviorTree></root>'


def results(steps: list[Step]) -> list[str]:
    """The status each operation returned, in order."""
    return [step.result for step in steps]


class CallBudgetExceeded(RuntimeError):
    """A scripted leaf was called too often: the tree loops within one operation."""


class Driver:
    """Hands out script entries and records every leaf callback."""

    def __init__(self, scripts: dict[str, tuple[str, ...]]) -> None:
        self.scripts = scripts
        self.positions: dict[str, int] = {}
        self.calls: list[str] = []
        self.total = 0

    def next(self, kind: str, name: str) -> str:
        self.calls.append(f"{kind}:{name}")
        self.total += 1
        if self.total > CALL_BUDGET:
            raise CallBudgetExceeded(f"more than {CALL_BUDGET} leaf calls")
        script = self.scripts[name]
        index = self.positions.get(name, 0)
        self.positions[name] = index + 1
        return RESULTS[script[index % len(script)]]

    def halted(self, name: str) -> None:
        self.calls.append(f"halted:{name}")

    def take_calls(self) -> list[str]:
        calls, self.calls = self.calls, []
        return calls


# -- BehaviorTree.CPP -------------------------------------------------------------


def _btcpp_factory(driver: Driver) -> Any:
    factory = btcpp.BehaviorTreeFactory()

    def status(kind: str) -> Callable[[Any], Any]:
        return lambda node: getattr(btcpp.NodeStatus, driver.next(kind, node.name()))

    factory.register_simple_action("ScriptedAction", status("tick"))
    factory.register_simple_condition("ScriptedCondition", status("tick"))
    factory.register_simple_stateful_action(
        "ScriptedStateful",
        status("start"),
        status("running"),
        lambda node: driver.halted(node.name()),
    )
    return factory


def run_btcpp(scenario: Scenario) -> list[Step]:
    driver = Driver(scenario.scripts)
    factory = _btcpp_factory(driver)
    try:
        tree = factory.create_tree_from_text(scenario.xml)
    except Exception as exc:
        return [Step("load", "error", driver.take_calls(), error=str(exc))]
    logger = btcpp.StdCoutLogger(tree)
    simple_actions = _simple_action_names(scenario.xml)
    steps = []
    for op in scenario.ops:
        step, lines = Step(op, ""), list[str]()
        with capture_fd1(lines):
            try:
                step.result = _btcpp_op(tree, op)
            except Exception as exc:
                step.result, step.error = "error", f"{type(exc).__name__}: {exc}"
        step.calls = driver.take_calls()
        step.transitions = _normalise(parse(lines), simple_actions)
        steps.append(step)
        if step.result == "error":
            break
    del logger
    return steps


def _simple_action_names(xml: str) -> set[str]:
    root = etree.fromstring(xml.encode())
    return {str(e.get("name")) for e in root.iter("ScriptedAction")}


def _normalise(transitions: list[str], simple_actions: set[str]) -> list[str]:
    """Hide BT.CPP's SimpleActionNode IDLE>RUNNING before its function runs.

    aiobt's simple sync actions go IDLE>SUCCESS directly, as BT.CPP's own
    SyncActionNode subclasses do (docs/conformance.md).
    """
    result = []
    for transition in transitions:
        name, change = transition.split(":")
        if name in simple_actions:
            if change == "IDLE>RUNNING":
                continue
            if change.startswith("RUNNING>"):
                transition = f"{name}:IDLE>{change[8:]}"
        result.append(transition)
    return result


def _btcpp_op(tree: Any, op: str) -> str:
    if op == "exactly":
        return str(tree.tick_exactly_once().name)
    if op == "once":
        return str(tree.tick_once().name)
    tree.halt_tree()
    return "halted"


# -- aiobt ----------------------------------------------------------------------------


def aiobt_factory(driver: Driver) -> BehaviorTreeFactory:
    factory = BehaviorTreeFactory()

    def status(kind: str) -> Callable[[TreeNode], Status]:
        return lambda node: Status[driver.next(kind, node.name)]

    def halted(node: TreeNode) -> None:
        driver.halted(node.name)

    factory.register_simple_action("ScriptedAction", status("tick"))
    factory.register_simple_condition("ScriptedCondition", status("tick"))
    factory.register_simple_stateful_action(
        "ScriptedStateful", status("start"), status("running"), halted
    )
    return factory


FactoryHook = Callable[[BehaviorTreeFactory], None]


async def run_aiobt(
    scenario: Scenario, hook: FactoryHook | None = None, *, listen: bool = True
) -> list[Step]:
    """aiobt's steps; ``hook`` may change the factory (the harness's own tests).

    ``listen=False`` attaches no status listener, so the tree runs its quiet
    fast paths; the steps then carry no transitions.
    """
    driver = Driver(scenario.scripts)
    factory = aiobt_factory(driver)
    if hook is not None:
        hook(factory)
    try:
        tree = factory.create_tree_from_text(scenario.xml)
    except Exception as exc:
        return [Step("load", "error", driver.take_calls(), error=str(exc))]
    transitions: list[str] = []
    if listen:
        tree.add_status_listener(
            lambda _stamp, node, previous, status: transitions.append(
                f"{node.name}:{previous.name}>{status.name}"
            )
        )
    steps = []
    for op in scenario.ops:
        step = Step(op, "")
        try:
            if op == "exactly":
                step.result = (await tree.tick_exactly_once()).name
            elif op == "once":
                step.result = (await tree.tick_once()).name
            else:
                await tree.halt_tree("conformance")
                step.result = "halted"
        except Exception as exc:
            step.result, step.error = "error", f"{type(exc).__name__}: {exc}"
        step.calls = driver.take_calls()
        step.transitions, transitions[:] = list(transitions), []
        steps.append(step)
        if step.result == "error":
            break
    return steps


# -- comparison -------------------------------------------------------------------------


def first_difference(reference: list[Step], candidate: list[Step]) -> str | None:
    """None when both runs agree, else a report of the first differing step.

    After an error only the fact that both raised is compared (messages and
    the partial transitions of the failed operation differ by nature).
    """
    for index, (ref, got) in enumerate(zip(reference, candidate, strict=False)):
        if ref.result == "error" and got.result == "error":
            return None
        if ref.key() != got.key():
            return f"step {index} differs\n  BT.CPP: {ref.describe()}\n  aiobt:  {got.describe()}"
    if len(reference) != len(candidate):
        return f"BT.CPP ran {len(reference)} steps, aiobt {len(candidate)}"
    return None


async def compare(
    scenario: Scenario, hook: FactoryHook | None = None, *, listen: bool = True
) -> tuple[list[Step], list[Step], str | None]:
    reference = run_btcpp(scenario)
    candidate = await run_aiobt(scenario, hook, listen=listen)
    if not listen:  # compare results and leaf calls only
        for step in reference:
            step.transitions = []
    return reference, candidate, first_difference(reference, candidate)


async def assert_conforms(scenario: Scenario, *, listen: bool = True) -> list[Step]:
    """Run both; fail with the scenario and the first difference. Returns BT.CPP's steps."""
    reference, _, difference = await compare(scenario, listen=listen)
    if difference is not None:
        raise AssertionError(f"{difference}\n--- scenario ---\n{scenario.describe()}")
    return reference
