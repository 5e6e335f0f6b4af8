"""Semantics guard for hot-path optimisations: record, then compare, the full
status traces of many random trees of built-in nodes.

Run: ``.venv/bin/python -m bench.core.trace_guard record FILE`` before a change,
``... check FILE`` after it. Each tree mixes every built-in control node and
decorator with scripted leaves of every leaf base (condition, sync action,
stateful action, async action that finishes at once or after loop turns),
and random pre/post conditions attached as Python callables. The trace holds,
per tick, the root status, every status transition seen by a listener, every
leaf hook call and condition call, and any error raised.

``--quiet`` attaches no listener (the quiet short paths run) and records every
node's status after each tick instead of the transitions; ``--no-unroll``
keeps composites on the shared tick (``aiobt.nodes.control.unrolled``), so
``record --quiet --no-unroll`` then ``check --quiet`` compares the unrolled
ticks with the shared ones.
"""

from __future__ import annotations

import asyncio
import json
import random
import sys
from typing import Any

from aiobt import (
    AsyncActionNode,
    BehaviorTreeFactory,
    ConditionNode,
    StatefulActionNode,
    Status,
    SyncActionNode,
)
from aiobt.core.conditions import NodeConditions
from aiobt.core.errors import TreeLoadError
from aiobt.core.node import TreeNode
from aiobt.nodes.control import unrolled

S, F, R = Status.SUCCESS, Status.FAILURE, Status.RUNNING
LOG: list[str] = []
SCRIPTS: dict[str, list[Status]] = {}
CURSOR: dict[str, int] = {}


def _next(node: TreeNode, event: str) -> Status:
    script = SCRIPTS[node.name]
    i = CURSOR.get(node.name, 0)
    CURSOR[node.name] = i + 1
    LOG.append(f"{node.name}:{event}")
    return script[i % len(script)]


class GCond(ConditionNode):
    __slots__ = ()

    def check(self) -> Status:
        return _next(self, "check")


class GSync(SyncActionNode):
    __slots__ = ()

    def on_tick(self) -> Status:
        return _next(self, "tick")


class GStateful(StatefulActionNode):
    __slots__ = ()

    def on_start(self) -> Status:
        return _next(self, "start")

    def on_running(self) -> Status:
        return _next(self, "running")

    def on_halted(self) -> None:
        LOG.append(f"{self.name}:halted")


class GAsync(AsyncActionNode):
    __slots__ = ()

    async def run(self) -> Status:
        result = _next(self, "run")
        try:
            for _ in range(len(self.name) % 3):
                await asyncio.sleep(0)
        except asyncio.CancelledError:
            LOG.append(f"{self.name}:cancelled")
            raise
        return result


CONTROLS = [
    ("Sequence", ""), ("SequenceWithMemory", ""), ("ReactiveSequence", ""),
    ("AsyncSequence", ""), ("Fallback", ""), ("ReactiveFallback", ""), ("AsyncFallback", ""),
    ("Parallel", ' success_count="-1" failure_count="1"'), ("ParallelAll", ""),
    ("PipelineSequence", ""), ("RoundRobin", ""),
]  # fmt: skip
FIXED = [("IfThenElse", 3), ("WhileDoElse", 3), ("RecoveryNode", 2)]
DECORATORS = [
    ("Inverter", ""), ("ForceSuccess", ""), ("ForceFailure", ""),
    ("KeepRunningUntilFailure", ""), ("RetryUntilSuccessful", ' num_attempts="2"'),
    ("Repeat", ' num_cycles="2"'), ("RunOnce", ""),
]  # fmt: skip
LEAVES = ["GCond", "GSync", "GStateful", "GAsync"]


def gen(rng: random.Random, depth: int, counter: list[int]) -> str:
    counter[0] += 1
    name = f"n{counter[0]}" + "x" * rng.randrange(3)
    if depth <= 0 or rng.random() < 0.3:
        kind = rng.choice(LEAVES)
        options = [S, F, R, R] if kind == "GStateful" else [S, F]
        SCRIPTS[name] = [rng.choice(options) for _ in range(rng.randrange(1, 5))]
        return f'<{kind} name="{name}"/>'
    roll = rng.random()
    if roll < 0.25:
        kind, attrs = rng.choice(DECORATORS)
        kids = [gen(rng, depth - 1, counter)]
    elif roll < 0.4:
        kind, count = rng.choice(FIXED)
        attrs, kids = "", [gen(rng, depth - 1, counter) for _ in range(count)]
    else:
        kind, attrs = rng.choice(CONTROLS)
        kids = [gen(rng, depth - 1, counter) for _ in range(rng.randrange(1, 4))]
    return f'<{kind} name="{name}"{attrs}>{"".join(kids)}</{kind}>'


def attach_conditions(tree: Any, rng: random.Random) -> None:
    for node in tree.nodes():
        if node is tree.root or rng.random() > 0.2:
            continue
        pattern = [rng.random() < 0.3 for _ in range(rng.randrange(1, 4))]
        calls = [0]

        def flag(n: TreeNode, what: str, pattern: list[bool] = pattern, calls: list[int] = calls):
            calls[0] += 1
            LOG.append(f"{n.name}:{what}")
            return pattern[calls[0] % len(pattern)]

        fields = rng.sample(["failure_if", "success_if", "skip_if", "while_true"], 2)
        kwargs = {f: (lambda n, f=f: flag(n, f)) for f in fields}
        for post in ("on_success", "on_failure", "on_halted_script", "post"):
            kwargs[post] = lambda n, p=post: LOG.append(f"{n.name}:{p}")
        node.attach_conditions(NodeConditions(**kwargs))


async def run_one(seed: int, quiet: bool = False) -> list[Any]:
    rng = random.Random(seed)
    SCRIPTS.clear()
    CURSOR.clear()
    xml = gen(rng, rng.randrange(1, 5), [0])
    factory = BehaviorTreeFactory()
    for cls in (GCond, GSync, GStateful, GAsync):
        factory.register_node_type(cls)
    try:
        tree = factory.create_tree_from_text(
            f'<root BTCPP_format="4"><BehaviorTree ID="M">{xml}</BehaviorTree></root>'
        )
    except TreeLoadError as exc:  # shapes BT.CPP refuses too
        return [f"load error: {exc}"]
    if seed % 2:
        attach_conditions(tree, rng)
    if not quiet:
        tree.add_status_listener(lambda t, n, p, s: LOG.append(f"{n.name}:{p.name}>{s.name}"))
    trace: list[Any] = []
    for tick in range(12):
        LOG.clear()
        try:
            status = (await (tree.tick_once() if tick % 2 else tree.tick_exactly_once())).name
        except Exception as exc:
            status = f"error {type(exc).__name__}: {exc}"
        for _ in range(2):
            await asyncio.sleep(0)
        if quiet:
            LOG.extend(f"{n.name}={n.status.name}" for n in tree.nodes())
        trace.append([status, list(LOG)])
        if tick == 9:
            LOG.clear()
            await tree.halt_tree("guard")
            trace.append(["halt", list(LOG)])
    return trace


async def run_all(count: int, quiet: bool) -> dict[str, Any]:
    return {str(seed): await run_one(seed, quiet) for seed in range(count)}


def main() -> None:
    flags = {arg for arg in sys.argv[1:] if arg.startswith("--")}
    args = [arg for arg in sys.argv[1:] if not arg.startswith("--")]
    mode, path = args[0], args[1]
    count = int(args[2]) if len(args) > 2 else 1500
    if "--no-unroll" in flags:
        unrolled.MAX_CHILDREN = 0
    traces = asyncio.run(run_all(count, "--quiet" in flags))
    if mode == "record":
        with open(path, "w") as out:
            json.dump(traces, out)
        print(f"recorded {len(traces)} traces")
        return
    with open(path) as src:
        expected = json.load(src)
    bad = [seed for seed in expected if expected[seed] != json.loads(json.dumps(traces[seed]))]
    for seed in bad[:3]:
        for i, (a, b) in enumerate(zip(expected[seed], traces[seed], strict=False)):
            if a != json.loads(json.dumps(b)):
                print(f"seed {seed} step {i}:\n  expected {a}\n  got      {b}")
                break
    print(f"{len(expected) - len(bad)}/{len(expected)} traces identical")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
