"""``aiobt nodes``: the ``<TreeNodesModel>`` of the registered nodes (for Groot2).

    aiobt nodes > models.xml                      # Nav2's nodes and your plugins'
    aiobt nodes --builtins --plugin mypkg.nodes   # with BehaviorTree.CPP's built-ins
    aiobt nodes --list                            # kind and ID, one per line

Nav2's node set is always registered; ``--plugin`` and ``--nodes-model`` add yours.
"""

from __future__ import annotations

import argparse
import sys

from aiobt.cli import run as run_cli
from aiobt.core.errors import TreeLoadError


def add_arguments(parser: argparse.ArgumentParser) -> None:
    run_cli.add_node_source_arguments(parser)
    parser.add_argument("--builtins", action="store_true", help="include the built-in nodes")
    parser.add_argument("--list", action="store_true", help="print the node IDs only, one per line")
    parser.set_defaults(stub=[])


def run(args: argparse.Namespace) -> int:
    try:
        factory = run_cli.build_factory(args)
    except (TreeLoadError, ImportError, OSError) as exc:
        print(f"aiobt nodes: {exc}", file=sys.stderr)
        return 2
    chosen = {
        node_id: manifest
        for node_id, manifest in sorted(factory.manifests.items())
        if args.builtins or not manifest.builtin
    }
    if not chosen:
        print(
            "aiobt nodes: no nodes besides the built-ins are registered "
            "(--builtins lists those; --plugin and --nodes-model add yours)",
            file=sys.stderr,
        )
        return 1
    if args.list:
        for node_id, manifest in chosen.items():
            print(f"{manifest.kind:<10} {node_id}")
        return 0
    print(factory.tree_nodes_model_xml(include_builtins=args.builtins))
    return 0
