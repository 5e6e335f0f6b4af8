"""The factory: register nodes and trees, create trees (BT.CPP's BehaviorTreeFactory)."""

from __future__ import annotations

import dataclasses
import difflib
import enum
import inspect
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

from aiobt.core.blackboard import Blackboard
from aiobt.core.clock import Clock
from aiobt.core.errors import TreeLoadError
from aiobt.core.manifest import (
    NodeBuilder,
    NodeManifest,
    Substitution,
    SubstitutionRules,
    TestNodeConfig,
    ports_dict,
)
from aiobt.core.node import NodeConfig, NodeKind, TreeContext, TreeNode
from aiobt.core.ports import PortInfo
from aiobt.core.status import Status
from aiobt.core.tree import Tree
from aiobt.nodes.actions.simple import StatefulCallbacks, simple_node_class
from aiobt.nodes.actions.test_node import test_node_builder
from aiobt.nodes.decorators.pass_through import pass_through_builder
from aiobt.nodes.registry import register_builtins
from aiobt.script import compile_condition
from aiobt.xml.builder import ScriptCompiler, TreeBuilder
from aiobt.xml.document import ParsedDocument, TreeDefinition, parse_file, parse_text
from aiobt.xml.model import is_unimplemented, read_tree_nodes_model, write_tree_nodes_model

SimpleFunction = Callable[[TreeNode], Any]


class BehaviorTreeFactory:
    """Knows every node ID and tree definition; builds :class:`Tree` objects."""

    def __init__(self, *, builtins: bool = True) -> None:
        self.manifests: dict[str, NodeManifest] = {}
        self.definitions: dict[str, TreeDefinition] = {}
        self.substitutions = SubstitutionRules()
        self.script_compiler: ScriptCompiler | None = compile_condition
        self.scripting_enums: dict[str, int] = {}
        self.main_tree_id: str | None = None
        if builtins:
            register_builtins(self)

    # -- nodes ----------------------------------------------------------------------
    def register_manifest(self, manifest: NodeManifest, *, replace: bool = False) -> None:
        if manifest.id in self.manifests and not replace:
            raise ValueError(f"node ID [{manifest.id}] is already registered")
        self.manifests[manifest.id] = manifest

    def register_node_type(
        self,
        node_class: type[TreeNode],
        node_id: str | None = None,
        *,
        builtin: bool = False,
        replace: bool = False,
    ) -> None:
        """Register a TreeNode subclass under ``node_id`` (default: its class name)."""
        manifest = NodeManifest(
            id=node_id or node_class.__name__,
            kind=node_class.KIND,
            ports=ports_dict(node_class.provided_ports()),
            builder=node_class,
            description=(inspect.getdoc(node_class) or "").split("\n")[0],
            builtin=builtin,
            node_class=node_class,
        )
        self.register_manifest(manifest, replace=replace)

    def register_simple_action(
        self, node_id: str, fn: SimpleFunction, ports: Iterable[PortInfo] = ()
    ) -> None:
        """``fn(node)`` returns a Status, bool or None; a coroutine function makes an async leaf."""
        self._register_simple(node_id, fn, tuple(ports), NodeKind.ACTION)

    def register_simple_condition(
        self, node_id: str, fn: SimpleFunction, ports: Iterable[PortInfo] = ()
    ) -> None:
        self._register_simple(node_id, fn, tuple(ports), NodeKind.CONDITION)

    def register_simple_stateful_action(
        self,
        node_id: str,
        on_start: Callable[[TreeNode], Status],
        on_running: Callable[[TreeNode], Status],
        on_halted: Callable[[TreeNode], None] | None = None,
        ports: Iterable[PortInfo] = (),
    ) -> None:
        """BT.CPP's StatefulActionNode from callbacks that each receive the node."""

        callbacks = StatefulCallbacks(on_start, on_running, on_halted)
        self._register_simple(node_id, callbacks, tuple(ports), NodeKind.ACTION)

    def _register_simple(
        self,
        node_id: str,
        fn: SimpleFunction | StatefulCallbacks,
        ports: tuple[PortInfo, ...],
        kind: str,
    ) -> None:

        node_class = simple_node_class(node_id, fn, ports, kind)
        self.register_node_type(node_class, node_id)

    def add_substitution_rule(self, pattern: str, replacement: Substitution) -> None:
        """Swap nodes whose path, name or ID matches ``pattern`` (wildcards).

        ``replacement`` is another node ID of the same family (leaf for
        leaf), or a :class:`TestNodeConfig`, which replaces leaves only
        (control nodes and decorators a pattern matches are kept).
        """
        self.substitutions.add(pattern, replacement)

    def _lookup(self, node_id: str, path: str, name: str) -> NodeManifest | None:
        manifest = self.manifests.get(node_id)
        if self.substitutions and manifest is not None:
            replacement = self.substitutions.match(path, name, node_id)
            if replacement is not None:
                return self._substitute(manifest, replacement, path)
        return manifest

    def _substitute(
        self, manifest: NodeManifest, replacement: Substitution, path: str
    ) -> NodeManifest:
        leaf = manifest.kind in (NodeKind.ACTION, NodeKind.CONDITION)
        if isinstance(replacement, TestNodeConfig):
            builder = _stub_builder(manifest, replacement)
            if builder is None:
                return manifest
        else:
            target = self.manifests.get(replacement)
            if target is None:
                raise TreeLoadError(
                    f"substitution for {path}: unknown node ID [{replacement}]", node_path=path
                )
            if leaf != (target.kind in (NodeKind.ACTION, NodeKind.CONDITION)):
                raise TreeLoadError(
                    f"substitution for {path}: [{replacement}] is a {target.kind}, "
                    f"it cannot replace the {manifest.kind} [{manifest.id}]",
                    node_path=path,
                )
            builder = target.builder
        # keep the original ports, so the XML is validated as written
        return NodeManifest(
            manifest.id, manifest.kind, manifest.ports, builder, manifest.description
        )

    def register_scripting_enum(self, name: str, value: int) -> None:
        """Make ``name`` usable in scripts as the number ``value`` (BT.CPP's
        registerScriptingEnum); trees created afterwards see it."""
        if not name.isidentifier():
            raise ValueError(f"scripting enum name {name!r} is not an identifier")
        self.scripting_enums[name] = int(value)

    def register_scripting_enums(self, enum_class: type[enum.Enum]) -> None:
        """Register every member of an int-valued Enum by its name."""
        for member in enum_class:
            self.register_scripting_enum(member.name, int(member.value))

    def registered_ids(self) -> list[str]:
        return sorted(self.manifests)

    # -- trees ----------------------------------------------------------------------
    def register_behavior_tree_from_text(self, text: str, *, file: str | None = None) -> list[str]:
        return self._register_document(parse_text(text, file=file))

    def register_behavior_tree_from_file(self, path: str | Path) -> list[str]:
        return self._register_document(parse_file(path))

    def _register_document(self, document: ParsedDocument) -> list[str]:
        for definition in document.trees:
            existing = self.definitions.get(definition.tree_id)
            if existing is not None and existing.element is not definition.element:
                where = f"{existing.file or '<text>'}:{existing.line}"
                raise TreeLoadError(
                    f"duplicate BehaviorTree ID [{definition.tree_id}] (first defined at {where})",
                    file=definition.file,
                    line=definition.line,
                )
            self.definitions[definition.tree_id] = definition
        if document.main_tree_to_execute:
            self.main_tree_id = document.main_tree_to_execute
        elif len(document.trees) == 1:
            self.main_tree_id = document.trees[0].tree_id
        return [d.tree_id for d in document.trees]

    def registered_behavior_trees(self) -> list[str]:
        return sorted(self.definitions)

    def create_tree(
        self,
        tree_id: str | None = None,
        *,
        blackboard: Blackboard | None = None,
        clock: Clock | None = None,
    ) -> Tree:
        """Build tree ``tree_id`` (default: main_tree_to_execute)."""
        tree_id = tree_id or self.main_tree_id
        if tree_id is None:
            raise TreeLoadError("no tree ID given and no main_tree_to_execute was set")
        return self._build_tree(tree_id, self.definitions, blackboard, clock)

    def _build_tree(
        self,
        tree_id: str,
        definitions: dict[str, TreeDefinition],
        blackboard: Blackboard | None,
        clock: Clock | None,
    ) -> Tree:
        context = TreeContext(clock)
        context.enums.update(self.scripting_enums)
        bb = blackboard if blackboard is not None else Blackboard.create()
        bb.now = context.clock.now
        builder = TreeBuilder(
            definitions, self._lookup, self.registered_ids, context, self.script_compiler
        )
        root = builder.build(tree_id, bb)
        definition = definitions[tree_id]
        return Tree(root, context, bb, tree_id=tree_id, source=definition.file or "")

    def create_tree_from_text(
        self,
        text: str,
        *,
        blackboard: Blackboard | None = None,
        clock: Clock | None = None,
        file: str | None = None,
    ) -> Tree:
        document = parse_text(text, file=file)
        return self._create_main(document, blackboard, clock)

    def create_tree_from_file(
        self, path: str | Path, *, blackboard: Blackboard | None = None, clock: Clock | None = None
    ) -> Tree:
        return self._create_main(parse_file(path), blackboard, clock)

    def _create_main(
        self, document: ParsedDocument, blackboard: Blackboard | None, clock: Clock | None
    ) -> Tree:
        # as BT.CPP's createTreeFromText: the document's trees are not registered
        # (creating the same text twice is fine); registered trees stay visible
        own = _own_definitions(document)
        ids = list(own)
        main = document.main_tree_to_execute or (ids[0] if len(ids) == 1 else None)
        if main is None:
            where = document.trees[0].file if document.trees else None
            found = ", ".join(ids) or "none"
            raise TreeLoadError(
                f"no main_tree_to_execute and not exactly one BehaviorTree (found: {found})",
                file=where,
            )
        definitions = {**self.definitions, **own}
        if main not in definitions:
            known = sorted(definitions)
            raise TreeLoadError(
                f'main_tree_to_execute="{main}" names no BehaviorTree'
                f"{_did_you_mean(main, known)}; known: {', '.join(known) or 'none'}",
                file=document.file,
                line=document.line,
            )
        return self._build_tree(main, definitions, blackboard, clock)

    # -- Groot2 -----------------------------------------------------------------------
    def tree_nodes_model_xml(self, *, include_builtins: bool = False) -> str:
        """A ``<TreeNodesModel>`` of the registered nodes, for Groot2."""

        manifests = [m for m in self.manifests.values() if include_builtins or not m.builtin]
        return write_tree_nodes_model(manifests)

    def register_tree_nodes_model(
        self, source: str | Path, builder: Callable[[str, NodeConfig], TreeNode] | None = None
    ) -> list[str]:
        """Register the nodes a ``<TreeNodesModel>`` declares that are not known yet.

        Their ports validate XML attributes; they are built with ``builder``
        (default: a node that fails when ticked, asking for a substitution).
        """

        added = []
        for manifest in read_tree_nodes_model(source, builder):
            if manifest.id not in self.manifests:
                self.manifests[manifest.id] = manifest
                added.append(manifest.id)
        return added


def _stub_builder(manifest: NodeManifest, spec: TestNodeConfig) -> NodeBuilder | None:
    """The stub for ``manifest``: a test leaf (a condition answers at once, it never
    runs), a pass-through for a decorator without an implementation, else None (kept)."""
    if manifest.kind == NodeKind.DECORATOR and is_unimplemented(manifest):
        return pass_through_builder()
    if manifest.kind not in (NodeKind.ACTION, NodeKind.CONDITION):
        return None  # control nodes and implemented decorators keep their children
    if manifest.kind == NodeKind.CONDITION and spec.delay > 0:
        spec = dataclasses.replace(spec, delay=0.0)
    return test_node_builder(spec)


def _own_definitions(document: ParsedDocument) -> dict[str, TreeDefinition]:
    """The document's trees by ID; a repeated ID is a load error."""
    own: dict[str, TreeDefinition] = {}
    for definition in document.trees:
        first = own.get(definition.tree_id)
        if first is not None:
            raise TreeLoadError(
                f"duplicate BehaviorTree ID [{definition.tree_id}] "
                f"(first defined at {first.file or '<text>'}:{first.line})",
                file=definition.file,
                line=definition.line,
            )
        own[definition.tree_id] = definition
    return own


def _did_you_mean(word: str, known: list[str]) -> str:
    close = difflib.get_close_matches(word, known, n=1, cutoff=0.6)
    return f" (did you mean [{close[0]}]?)" if close else ""
