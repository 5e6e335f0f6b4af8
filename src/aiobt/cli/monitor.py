"""``aiobt monitor``: the navigator's running tree, live, in the terminal.

    aiobt monitor                 # full-screen view, redrawn as statuses change
    aiobt monitor --plain         # a line per change worth reading (also when piped)
    aiobt monitor --once          # print the tree once and exit

Reads the status stream ``{ns}/bt/tree``, ``{ns}/bt/transitions`` and
``{ns}/bt/snapshot`` (docs/navigator.md); a tree taller than the terminal
shows its active branches. Runs until Ctrl-C. ``--once`` exits 1 when no
tree arrives within ``--timeout``.
"""

from __future__ import annotations

import argparse
import asyncio
import shutil
import signal
import sys
from typing import TextIO

from aiobt.cli.failure import failure
from aiobt.cli.navigate import CONNECT_TIMEOUT
from aiobt.monitor import TreeView
from aiobt.monitor.plain import PlainLog
from aiobt.msgs.bt import BtSnapshot, BtTransitions, BtTree
from aiobt.transport import (
    Bus,
    BusConfigError,
    BusSettings,
    BusUnavailable,
    add_bus_arguments,
    open_bus,
)

_CLEAR = "\033[H\033[2J"
_REFRESH = 0.1  # s of wall time between redraws: what an eye follows


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_bus_arguments(parser)
    parser.set_defaults(connect_timeout=CONNECT_TIMEOUT)
    parser.add_argument(
        "--plain", action="store_true", help="a line per change worth reading, no redraw"
    )
    parser.add_argument("--once", action="store_true", help="print the tree once and exit")
    parser.add_argument(
        "--timeout", type=float, default=10.0, metavar="SECONDS",
        help="--once: wait this long for the tree (default: %(default)s)",
    )  # fmt: skip


class Monitor:
    """Feeds a :class:`TreeView` from the bus and writes it to ``out``."""

    def __init__(self, out: TextIO, plain: bool, colour: bool) -> None:
        self.view = TreeView()
        self.log = PlainLog()
        self.out = out
        self.plain = plain
        self.colour = colour
        self.changed = asyncio.Event()
        self.have_tree = asyncio.Event()

    def attach(self, bus: Bus) -> None:
        bus.subscribe("bt/tree", BtTree, self.on_tree, latched=True)
        bus.subscribe("bt/transitions", BtTransitions, self.on_transitions)
        bus.subscribe("bt/snapshot", BtSnapshot, self.on_snapshot)

    def on_tree(self, tree: BtTree) -> None:
        self.view.on_tree(tree)
        self.have_tree.set()
        if self.plain:
            self._write(*self.log.on_tree(tree))
        self.changed.set()

    def on_transitions(self, message: BtTransitions) -> None:
        for node, status in self.view.on_transitions(message):
            line = self.log.on_transition(node, status, message.stamp) if self.plain else None
            if line is not None:
                self._write(line)
        self.changed.set()

    def on_snapshot(self, snapshot: BtSnapshot) -> None:
        self.view.on_snapshot(snapshot)
        if self.plain and self.view.snapshot is snapshot:
            self._write(*self.log.on_snapshot(snapshot))
        self.changed.set()

    def _write(self, *lines: str) -> None:
        if lines:
            self.out.write("".join(line + "\n" for line in lines))
            self.out.flush()

    async def redraw_forever(self) -> None:
        while True:
            await self.changed.wait()
            self.changed.clear()
            height = shutil.get_terminal_size().lines - 1
            self.out.write(_CLEAR + "\n".join(self.view.render(height, self.colour)) + "\n")
            self.out.flush()
            await asyncio.sleep(_REFRESH)


async def monitor(args: argparse.Namespace, out: TextIO) -> int:
    plain = args.plain or not out.isatty()
    watcher = Monitor(out, plain=plain and not args.once, colour=out.isatty())
    async with open_bus(BusSettings.from_args(args)) as bus:
        watcher.attach(bus)
        if args.once:
            return await _once(watcher, args.timeout)
        stop = asyncio.Event()
        loop = asyncio.get_running_loop()
        for sig in (signal.SIGINT, signal.SIGTERM):
            loop.add_signal_handler(sig, stop.set)
        drawing = None if plain else asyncio.create_task(watcher.redraw_forever())
        await stop.wait()
        if drawing is not None:
            drawing.cancel()
    return 0


async def _once(watcher: Monitor, timeout: float) -> int:  # noqa: ASYNC109
    try:
        async with asyncio.timeout(timeout):
            await watcher.have_tree.wait()
    except TimeoutError:
        watcher.out.write(f"no tree on bt/tree within {timeout:g} s (is the navigator up?)\n")
        return 1
    watcher.out.write("\n".join(watcher.view.render(colour=watcher.colour)) + "\n")
    return 0


def run(args: argparse.Namespace) -> int:
    try:
        return asyncio.run(monitor(args, sys.stdout))
    except (BusUnavailable, BusConfigError) as exc:
        print(failure("monitor", exc), file=sys.stderr)
        return 2
