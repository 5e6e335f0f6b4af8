"""Random trees of the built-in control and decorator nodes, with scripted leaves.

``generate(seed)`` is deterministic: a failing seed reproduces the same
scenario (its XML, scripts and operations are printed by the harness).

The shapes include what BT.CPP rejects at tick time (Parallel thresholds above
the number of children, IfThenElse/WhileDoElse with 1 or 4 children): the
harness then checks that both implementations raise at the same operation.
Trees that can stay RUNNING forever while emitting wake-ups (a
``num_cycles``/``num_attempts`` of -1; a KeepRunningUntilFailure in a tree
with a node that yields) are only driven with ``tick_exactly_once``, since
``tick_once`` would loop forever in both implementations.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from random import Random

from lxml import etree

from tests.conformance.harness import Scenario

SEQUENCES = (
    "Sequence",
    "SequenceWithMemory",
    "ReactiveSequence",
    "AsyncSequence",
    "Fallback",
    "ReactiveFallback",
    "AsyncFallback",
)
CONTROLS = (*SEQUENCES, "Parallel", "ParallelAll", "IfThenElse", "WhileDoElse", "Switch")
DECORATORS = (
    "Inverter",
    "ForceSuccess",
    "ForceFailure",
    "KeepRunningUntilFailure",
    "RetryUntilSuccessful",
    "Repeat",
    "RunOnce",
)
VALUES = ("1", "2", "3", "x")
LOOP_COUNTS = (1, 2, 3, 0, -1)
YIELDING = {
    "SequenceWithMemory",
    "AsyncSequence",
    "AsyncFallback",
    "RetryUntilSuccessful",
    "Repeat",
}


@dataclass(slots=True)
class _Builder:
    rng: Random
    max_depth: int
    budget: int
    scripts: dict[str, tuple[str, ...]] = field(default_factory=dict)
    unbounded: bool = False
    count: int = 0

    def name(self, prefix: str) -> str:
        self.count += 1
        return f"{prefix}{self.count}"

    def node(self, depth: int) -> etree._Element:
        self.budget -= 1
        roll = self.rng.random()
        if depth >= self.max_depth or self.budget <= 0 or (depth > 0 and roll < 0.3):
            return self.leaf()
        if roll < 0.75:
            return self.control(depth)
        return self.decorator(depth)

    def leaf(self) -> etree._Element:
        rng = self.rng
        kind = rng.choices(
            ("stateful", "action", "condition", "always", "set"), (35, 25, 15, 14, 11)
        )[0]
        if kind == "always":
            return etree.Element(
                rng.choice(("AlwaysSuccess", "AlwaysFailure")), name=self.name("k")
            )
        if kind == "set":
            return etree.Element(
                "SetBlackboard", name=self.name("b"), output_key="var", value=rng.choice(VALUES)
            )
        if kind == "stateful":
            name = self.name("s")
            alphabet, weights = "RSF", [50, 30, 20]
            element = etree.Element("ScriptedStateful", name=name)
        else:
            name = self.name("a" if kind == "action" else "c")
            alphabet, weights = "SF", [55, 45]
            tag = "ScriptedAction" if kind == "action" else "ScriptedCondition"
            element = etree.Element(tag, name=name)
        length = rng.randint(2, 7)
        self.scripts[name] = tuple(rng.choices(alphabet, weights, k=length))
        return element

    def children(self, element: etree._Element, depth: int, count: int) -> etree._Element:
        for _ in range(count):
            element.append(self.node(depth + 1))
        return element

    def control(self, depth: int) -> etree._Element:
        rng = self.rng
        kind = rng.choice(CONTROLS)
        if kind in SEQUENCES:
            element = etree.Element(kind, name=self.name("q"))
            return self.children(element, depth, rng.randint(1, 4))
        if kind == "Parallel":
            element = etree.Element(
                kind,
                name=self.name("p"),
                success_count=str(rng.choice((-1, -1, -2, 0, 1, 1, 2, 3))),
                failure_count=str(rng.choice((1, 1, -1, -2, 0, 2, 3))),
            )
            return self.children(element, depth, rng.randint(1, 4))
        if kind == "ParallelAll":
            element = etree.Element(
                kind, name=self.name("p"), max_failures=str(rng.choice((1, 1, 0, -1, 2, 3)))
            )
            return self.children(element, depth, rng.randint(1, 4))
        if kind == "Switch":
            cases = rng.choice((2, 2, 3, 3, 4))
            element = etree.Element(f"Switch{cases}", name=self.name("w"), variable="{var}")
            for index in range(1, cases + 1):
                element.set(f"case_{index}", rng.choice(VALUES))
            return self.children(element, depth, cases + 1)
        count = rng.choices((2, 3, 1, 4), (45, 45, 5, 5))[0]
        return self.children(etree.Element(kind, name=self.name("i")), depth, count)

    def decorator(self, depth: int) -> etree._Element:
        rng = self.rng
        kind = rng.choice(DECORATORS)
        element = etree.Element(kind, name=self.name("d"))
        if kind in ("RetryUntilSuccessful", "Repeat"):
            limit = rng.choice(LOOP_COUNTS)
            self.unbounded |= limit == -1
            element.set(
                "num_attempts" if kind == "RetryUntilSuccessful" else "num_cycles", str(limit)
            )
        elif kind == "RunOnce" and rng.random() < 0.6:
            element.set("then_skip", rng.choice(("true", "false")))
        return self.children(element, depth, 1)


def generate(seed: int) -> Scenario:
    """The scenario of ``seed``: a tree, a script per leaf, a program of operations."""
    rng = Random(seed)
    builder = _Builder(rng, max_depth=rng.randint(2, 4), budget=rng.randint(6, 22))
    root = builder.control(0) if rng.random() < 0.8 else builder.decorator(0)
    document = etree.Element("root", BTCPP_format="4", main_tree_to_execute="Main")
    tree = etree.SubElement(document, "BehaviorTree", ID="Main")
    if rng.random() < 0.5:  # give {var} a value before anything reads it
        start = etree.SubElement(tree, "Sequence", name="start")
        etree.SubElement(
            start, "SetBlackboard", name="b0", output_key="var", value=rng.choice(VALUES)
        )
        start.append(root)
    else:
        tree.append(root)
    ops = rng.choices(("exactly", "once", "halt"), (65, 25, 10), k=rng.randint(8, 16))
    tags = {element.tag for element in root.iter()}
    if builder.unbounded or ("KeepRunningUntilFailure" in tags and tags & YIELDING):
        ops = ["exactly" if op == "once" else op for op in ops]
    return Scenario(etree.tostring(document, encoding="unicode"), builder.scripts, tuple(ops))
