"""The ``aiobt`` command: one sub-command per module, imported only when used.

Each sub-command module exposes ``add_arguments(parser)`` and
``run(args) -> int``. Services live in ``aiobt_services.<name>.main`` and follow
the same shape, so ``aiobt robot ...`` and ``python -m aiobt_services.robot``
run the same code.
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import logging
import os
import sys
from collections.abc import Sequence

from aiobt.cli.unknown_flags import command_parser, unknown_flags_message
from aiobt.system.catalog import COMPOSITIONS, SERVICES

# name -> (module, one-line help): every sub-command.
COMMANDS: dict[str, tuple[str, str]] = {
    "run": ("aiobt.cli.run", "load an XML tree and tick it until it finishes"),
    "demo": ("aiobt.cli.demo", "the main job: run the example mission"),
    "nodes": ("aiobt.cli.nodes", "print the <TreeNodesModel> of every registered node"),
    "validate": ("aiobt.cli.validate", "load and check XML trees with every node, tick nothing"),
    "router": ("aiobt.cli.router", "run a Zenoh router in this process"),
    "certs": ("aiobt.cli.certs", "a CA and a certificate per service and host (mutual TLS)"),
    "up": ("aiobt.cli.up", "the whole system on this machine: router and every service"),
    "status": ("aiobt.cli.status", "who is up: the router, each service and web view"),
    "navigate": ("aiobt.cli.navigate", "send a navigation goal and follow it to its end"),
    "goal": ("aiobt.cli.goal", "put a goal on {ns}/goal_pose (exit 1: the navigator refused it)"),
    "monitor": ("aiobt.cli.monitor", "the navigator's running tree, live, in the terminal"),
    "foxglove": ("aiobt.cli.foxglove", "the robot's topics in Foxglove (WebSocket, MCAP)"),
    "web": ("aiobt.cli.web", "the robot, its plans and its tree in a browser (a web view)"),
    # the services, by module path, from the one list (aiobt.system.catalog)
    **{spec.name: (spec.module, spec.summary) for spec in SERVICES},
    # services run as one process (Nav2's composition; aiobt.system.compose)
    **{
        name: ("aiobt.system.compose", f"{' and '.join(parts)} in one process (composed)")
        for name, parts in COMPOSITIONS.items()
    },
}

# long-running processes whose INFO lines are their log (aiobt up's services.log; the
# web view's and Foxglove's address and clients); every other command shows the person
# at the terminal warnings and errors only
LOGGING_COMMANDS = frozenset(
    {"router", "up", "web", "foxglove", *(spec.name for spec in SERVICES), *COMPOSITIONS}
)

VERBOSE_HELP = "more logging: -v the library's INFO lines, -vv DEBUG"


def _load(module_name: str) -> object:
    return importlib.import_module(module_name)


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if "AIOBT_SUPERVISOR_PID" in os.environ:  # a child of aiobt up/demo: dies with it
        # inside, for start-up time: a heavy import, only in a child of aiobt up/demo
        from aiobt.system.lifeline import die_with_supervisor

        die_with_supervisor()
    parser = _full_parser(argv)
    args, extra = parser.parse_known_args(argv)
    if extra:
        command = command_parser(parser, args.command)
        command.error(unknown_flags_message(extra, command))
    quiet = args.command not in LOGGING_COMMANDS and args.verbose == 0
    logging.basicConfig(
        level=logging.DEBUG if args.verbose > 1 else logging.WARNING if quiet else logging.INFO,
        format="%(asctime)s %(levelname).1s %(name)s: %(message)s",
    )
    if quiet:  # the command says itself that no router answered, and what to do
        logging.getLogger("aiobt.transport.session").setLevel(logging.ERROR)
    module = _load(args._module)
    code: int = module.run(args)  # type: ignore[attr-defined]
    return code


def _full_parser(argv: Sequence[str]) -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="aiobt", description="aiobt: asyncio behavior trees")
    parser.add_argument("-v", "--verbose", action="count", default=0, help=VERBOSE_HELP)
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    wanted = next((a for a in argv if not a.startswith("-")), None)
    for name, (module_name, help_text) in COMMANDS.items():
        # a composition's services each add the bus and clock flags: the same, taken once
        handler = "resolve" if name in COMPOSITIONS else "error"
        sub = commands.add_parser(
            name, help=help_text, description=help_text, conflict_handler=handler
        )
        sub.set_defaults(_module=module_name, _command=name)
        if name == wanted:
            _load(module_name).add_arguments(sub)  # type: ignore[attr-defined]
            with contextlib.suppress(argparse.ArgumentError):  # the services' flags have it
                # after the command too (SUPPRESS: not undoing a -v given before it)
                sub.add_argument(
                    "-v", "--verbose", action="count", default=argparse.SUPPRESS, help=VERBOSE_HELP
                )
    return parser


if __name__ == "__main__":
    sys.exit(main())
