"""``aiobt nodes``: print the ``<TreeNodesModel>`` of the registered nodes (for Groot2)."""

from __future__ import annotations

import argparse
import sys

from aiobt.cli import run as run_cli
from aiobt.core.errors import TreeLoadError


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--plugin", action="append", default=[], metavar="MODULE",
        help="import MODULE and call its register(factory); repeatable",
    )  # fmt: skip
    parser.add_argument("--builtins", action="store_true", help="include the built-in nodes")
    parser.add_argument("--list", action="store_true", help="print the node IDs only, one per line")
    parser.set_defaults(nodes_model=[], stub=[])


def run(args: argparse.Namespace) -> int:
    try:
        factory = run_cli.build_factory(args)
    except (TreeLoadError, ImportError) as exc:
        print(f"aiobt nodes: {exc}", file=sys.stderr)
        return 2
    if args.list:
        for node_id, manifest in sorted(factory.manifests.items()):
            if args.builtins or not manifest.builtin:
                print(f"{manifest.kind:<10} {node_id}")
        return 0
    print(factory.tree_nodes_model_xml(include_builtins=args.builtins))
    return 0
