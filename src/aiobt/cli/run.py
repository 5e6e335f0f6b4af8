"""``aiobt run``: load an XML tree and tick it until it finishes.

    aiobt run mission.xml --plugin mypkg.nodes
    aiobt run trees/nav2/navigate_to_pose_w_replanning_and_recovery.xml \\
        --nodes-model trees/nav2/nav2_tree_nodes.xml --stub '*=SUCCESS:0.5'
    aiobt run mission.xml --groot2          # Groot2 attaches live on 127.0.0.1:1667

Exit status: 0 when the tree succeeds, 1 when it fails or is stopped, 2 when
the tree cannot be loaded.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import importlib
import logging
import sys
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TextIO

from aiobt.core.blackboard import Blackboard
from aiobt.core.clock import Clock, ScaledClock, SystemClock
from aiobt.core.errors import BlackboardError, LogicError, NodeError, TreeLoadError
from aiobt.core.manifest import TestNodeConfig
from aiobt.core.node import TreeNode
from aiobt.core.status import Status
from aiobt.core.tree import Tree
from aiobt.display import render
from aiobt.factory import BehaviorTreeFactory
from aiobt.loggers import (
    BtlogLogger,
    Groot2Publisher,
    JsonlLogger,
    SqliteLogger,
    TreeStatistics,
)
from aiobt.loggers.groot2 import DEFAULT_PORT, port_argument
from aiobt.nav import register_nav2_nodes
from aiobt.nodes.subtree import SubTreeNode
from aiobt.xml.model import is_unimplemented

log = logging.getLogger("aiobt.cli.run")
DEFAULT_MAX_TIME = 300.0  # s of clock time: a stubbed tree that never ends still stops


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", help="the XML file (BTCPP_format 4 or 3)")
    add_tree_arguments(parser)


def add_tree_arguments(parser: argparse.ArgumentParser) -> None:
    """Options shared by ``run`` and ``demo``."""
    parser.add_argument("--tree", metavar="ID", help="tree to run (default: main_tree_to_execute)")
    add_node_source_arguments(parser)
    add_stub_arguments(parser)
    parser.add_argument(
        "--set", action="append", default=[], metavar="KEY=VALUE", dest="entries",
        help="set a root blackboard entry (text) before the first tick; repeatable",
    )  # fmt: skip
    parser.add_argument(
        "--period", type=float, default=0.05, help="tick period in seconds of clock time"
    )
    parser.add_argument(
        "--speed", type=float, default=1.0, help="clock speed-up factor (1: wall time)"
    )
    parser.add_argument(
        "--max-time", type=float, default=DEFAULT_MAX_TIME, metavar="SECONDS",
        help="halt the tree after this much clock time; 0: no limit (default: %(default)s)",
    )  # fmt: skip
    parser.add_argument(
        "--trace", choices=("all", "leaves", "none"), default="leaves",
        help="which status changes to print (default: leaves)",
    )  # fmt: skip
    parser.add_argument("--btlog", metavar="FILE", help="write a Groot2-replayable .btlog")
    parser.add_argument("--jsonl", metavar="FILE", help="write every transition as JSON Lines")
    parser.add_argument("--sqlite", metavar="FILE", help="write BT.CPP's SQLite log (.db3)")
    parser.add_argument(
        "--stats", action="store_true", help="print the tree with per-node tick counts at the end"
    )
    parser.add_argument(
        "--groot2", type=port_argument, nargs="?", const=DEFAULT_PORT, default=None, metavar="PORT",
        help=f"let Groot2 attach live (ZeroMQ on PORT and PORT+1, default {DEFAULT_PORT})",
    )  # fmt: skip
    parser.add_argument(
        "--host", default="127.0.0.1",
        help="address the --groot2 publisher binds (default 127.0.0.1; 0.0.0.0 exposes it)",
    )  # fmt: skip


def add_node_source_arguments(parser: argparse.ArgumentParser) -> None:
    """``--plugin`` and ``--nodes-model``: where nodes beyond the built-in and Nav2 ones come
    from (``run``, ``demo``, ``nodes``, ``validate``)."""
    parser.add_argument(
        "--plugin", action="append", default=[], metavar="MODULE",
        help="import MODULE and call its register(factory); repeatable",
    )  # fmt: skip
    parser.add_argument(
        "--nodes-model", action="append", default=[], metavar="XML",
        help="declare the nodes of a <TreeNodesModel> file (their ports validate the tree)",
    )  # fmt: skip


def add_stub_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--stub", action="append", default=[], metavar="PATTERN=STATUS[:SECONDS]",
        help="replace nodes whose path, name or ID matches PATTERN by a stub returning STATUS "
        "after SECONDS of clock time (conditions answer at once); repeatable",
    )  # fmt: skip
    parser.add_argument(
        "--stub-missing", metavar="STATUS[:SECONDS]",
        help="stub only the nodes that have no implementation (declared by --nodes-model): "
        "leaves return STATUS, decorators pass their child's status through",
    )  # fmt: skip


@dataclass(slots=True)
class RunReport:
    status: Status
    clock_time: float
    transitions: int
    halted_at: float | None = None  # the --max-time that stopped the tree, if one did


def build_factory(args: argparse.Namespace) -> BehaviorTreeFactory:
    """Built-in and Nav2 nodes (no bus: Nav2 leaves that need one fail when ticked),
    then ``--plugin``, ``--nodes-model``, ``--stub`` and ``--stub-missing``."""
    factory = BehaviorTreeFactory()
    register_nav2_nodes(factory)
    for module_name in args.plugin:
        module = importlib.import_module(module_name)
        register = getattr(module, "register", None)
        if not callable(register):
            raise TreeLoadError(
                f"--plugin {module_name}: the module has no register(factory) function"
            )
        register(factory)
    for model in args.nodes_model:
        factory.register_tree_nodes_model(model)
    for spec in args.stub:
        pattern, replacement = parse_stub(spec)
        factory.add_substitution_rule(pattern, replacement)
    if getattr(args, "stub_missing", None):
        _, replacement = parse_stub(f"*={args.stub_missing}", "--stub-missing")
        for node_id, manifest in factory.manifests.items():
            if is_unimplemented(manifest):
                factory.add_substitution_rule(node_id, replacement)
    return factory


def parse_stub(spec: str, flag: str = "--stub") -> tuple[str, TestNodeConfig]:
    """``PATTERN=STATUS[:SECONDS]`` -> (pattern, TestNodeConfig)."""
    pattern, _, rest = spec.partition("=")
    status_text, _, delay_text = (rest or "SUCCESS").partition(":")
    status = Status.__members__.get(status_text.strip().upper())
    try:
        delay = float(delay_text) if delay_text else 0.0
    except ValueError:
        delay = -1.0
    if not pattern or status not in (Status.SUCCESS, Status.FAILURE) or delay < 0.0:
        raise TreeLoadError(
            f"{flag} {spec!r}: expected PATTERN=STATUS[:SECONDS] with STATUS SUCCESS or FAILURE"
        )
    return pattern, TestNodeConfig(status=status, delay=delay)


def speed_clock(speed: float) -> Clock:
    """``aiobt run``'s clock: the wall's, or scaled by ``--speed`` (not a service's clock,
    :func:`aiobt.system.service.make_clock`)."""
    if speed <= 0:
        raise TreeLoadError(f"--speed must be > 0, got {speed}")
    return SystemClock() if speed == 1.0 else ScaledClock(speed)


def root_blackboard(entries: list[str], initial: Mapping[str, object] | None = None) -> Blackboard:
    """The root blackboard: ``initial`` values, then the ``--set KEY=VALUE`` texts."""
    bb = Blackboard.create()
    for key, value in (initial or {}).items():
        bb.set(key, value)
    for item in entries:
        key, sep, value = item.partition("=")
        if not sep or not key:
            raise TreeLoadError(f"--set {item!r}: expected KEY=VALUE")
        bb.set(key, value)
    return bb


def short_names(tree: Tree) -> dict[int, str]:
    """Node id -> ``subtree_instance/name``: the node's name under its nearest SubTree."""
    names: dict[int, str] = {}
    stack: list[tuple[TreeNode, str]] = [(tree.root, "")]
    while stack:
        node, prefix = stack.pop()
        names[id(node)] = f"{prefix}{node.name}"
        inner = f"{prefix}{node.name}/" if isinstance(node, SubTreeNode) else prefix
        stack.extend((child, inner) for child in node.children_nodes())
    return names


def transition_printer(
    tree: Tree, which: str, out: TextIO
) -> Callable[[float, TreeNode, Status, Status], None]:
    """Print status changes; ``leaves`` shows each leaf's results and halts only."""
    start = tree.clock.now()
    names = short_names(tree)
    shown: dict[int, Status] = {}

    def show(stamp: float, node: TreeNode, previous: Status, status: Status) -> None:
        halted = status is Status.IDLE and previous is Status.RUNNING
        if which == "leaves":
            if node.children_nodes() or (status is Status.IDLE and not halted):
                return
            if not halted and shown.get(id(node)) is status:
                return
            shown[id(node)] = status
        change = "halted" if halted else status.name
        out.write(f"{stamp - start:8.2f}s  {change:<8} {names.get(id(node), node.path)}\n")

    return show


async def run_tree(tree: Tree, args: argparse.Namespace, out: TextIO) -> RunReport:
    transitions = 0

    def count(*_: object) -> None:
        nonlocal transitions
        transitions += 1

    tree.add_status_listener(count)
    if args.trace != "none":
        tree.add_status_listener(transition_printer(tree, args.trace, out))
    start = tree.clock.now()
    async with contextlib.AsyncExitStack() as servers:
        if getattr(args, "groot2", None) is not None:
            await servers.enter_async_context(Groot2Publisher(tree, args.groot2, args.host))
        return await _run_logged(tree, args, out, start, lambda: transitions)


async def _run_logged(
    tree: Tree, args: argparse.Namespace, out: TextIO, start: float, count: Callable[[], int]
) -> RunReport:
    with contextlib.ExitStack() as loggers:
        stats = _attach_loggers(tree, args, loggers)
        halted_at = None
        status: Status | None
        try:
            if not args.max_time:
                status = await tree.tick_while_running(args.period)
            else:
                status = await _bounded(tree, args.period, args.max_time)
                halted_at = None if status is not None else args.max_time
        finally:
            if tree.status is Status.RUNNING:
                await tree.halt_tree("aiobt run stopped")
        if stats is not None:
            out.write(render(tree, stats=stats) + "\n")
    return RunReport(status or Status.FAILURE, tree.clock.now() - start, count(), halted_at)


def _attach_loggers(
    tree: Tree, args: argparse.Namespace, stack: contextlib.ExitStack
) -> TreeStatistics | None:
    if getattr(args, "btlog", None):
        stack.enter_context(BtlogLogger(tree, args.btlog))
    if getattr(args, "jsonl", None):
        stack.enter_context(JsonlLogger(tree, args.jsonl))
    if getattr(args, "sqlite", None):
        stack.enter_context(SqliteLogger(tree, args.sqlite))
    if getattr(args, "stats", False):
        return stack.enter_context(TreeStatistics(tree))
    return None


async def _bounded(tree: Tree, period: float, max_time: float) -> Status | None:
    """The tree's result, or None when it was halted at ``max_time``."""
    ticking = asyncio.ensure_future(tree.tick_while_running(period))
    timer = asyncio.ensure_future(tree.clock.sleep(max_time))
    try:
        await asyncio.wait({ticking, timer}, return_when=asyncio.FIRST_COMPLETED)
    finally:
        timer.cancel()
    if ticking.done():
        return ticking.result()
    ticking.cancel()
    await asyncio.gather(ticking, return_exceptions=True)
    await tree.halt_tree(f"--max-time {max_time:g} s reached")
    return None


def run(args: argparse.Namespace) -> int:
    try:
        factory = build_factory(args)
        tree_id = register_file(factory, args.file, args.tree)
        tree = factory.create_tree(
            tree_id, blackboard=root_blackboard(args.entries), clock=speed_clock(args.speed)
        )
    except (TreeLoadError, BlackboardError, ImportError, OSError) as exc:
        print(f"aiobt run: {explain(exc)}", file=sys.stderr)
        return 2
    return finish(tree, args)


def register_file(factory: BehaviorTreeFactory, path: str, wanted: str | None) -> str:
    """Register the trees of ``path``; the ID to run (``wanted`` or the file's main tree)."""
    ids = factory.register_behavior_tree_from_file(path)
    if not ids:
        raise TreeLoadError("no <BehaviorTree> in this file", file=path)
    tree_id = wanted or factory.main_tree_id
    if tree_id is None:
        raise TreeLoadError(
            f"{len(ids)} trees ({', '.join(ids)}) and no main_tree_to_execute: "
            "choose one with --tree ID",
            file=path,
        )
    return tree_id


def explain(exc: Exception) -> str:
    """The error, and for an unknown node ID where such nodes come from."""
    text = str(exc)
    if isinstance(exc, TreeLoadError) and exc.message.startswith("unknown node ID"):
        text += (
            "; a node of your own? --plugin MODULE registers its implementation, "
            "--nodes-model XML declares its ports (then --stub-missing runs it as a stub)"
        )
    return text


def finish(tree: Tree, args: argparse.Namespace) -> int:
    """Tick ``tree`` to the end, print a summary, and return the exit status."""
    try:
        report = asyncio.run(run_tree(tree, args, sys.stdout))
    except (NodeError, LogicError) as exc:
        print(f"aiobt: the tree stopped on an error: {exc}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("aiobt: interrupted", file=sys.stderr)
        return 1
    except OSError as exc:  # e.g. the --groot2 port is taken
        print(f"aiobt run: {exc}", file=sys.stderr)
        return 2
    if report.halted_at is not None:
        ended = f"halted at --max-time {report.halted_at:g} s of clock time (it was RUNNING)"
    else:
        ended = f"{report.status.name} after {report.clock_time:.2f} s of clock time"
    print(f"tree {tree.tree_id}: {ended}, {report.transitions} status changes")
    return 0 if report.status is Status.SUCCESS and report.halted_at is None else 1
