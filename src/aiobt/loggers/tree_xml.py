"""The tree as instantiated, as XML with ``_uid`` on every node (BT.CPP's WriteTreeToXML).

Each SubTree instance becomes its own ``<BehaviorTree ID=.. _fullpath=..>``
(main tree first, then the instances in creation order); a ``<SubTree>``
element carries its uid and no children. Port attributes are the bindings
as loaded, defaults included; a ``<TreeNodesModel>`` lists the node types
used. Groot2 replays ``.btlog`` files against this XML.
"""

from __future__ import annotations

from dataclasses import dataclass

from lxml import etree

from aiobt.core.convert import to_text
from aiobt.core.node import TreeNode
from aiobt.core.ports import CONDITION_ATTRIBUTES, PortInfo
from aiobt.core.tree import Tree
from aiobt.factory import BehaviorTreeFactory
from aiobt.nodes.subtree import SubTreeNode
from aiobt.xml.model import add_node_model

# a SubTree element's attributes that are not port remappings
_SUBTREE_OWN = frozenset(("ID", "name", "_fullpath", "_uid"))


@dataclass(frozen=True, slots=True)
class SubtreeInstance:
    """One instance of a BehaviorTree in a built tree (the main tree has fullpath "")."""

    tree_id: str
    fullpath: str
    top: TreeNode | None

    def nodes(self) -> list[TreeNode]:
        """This instance's own nodes, pre-order: a SubTree node, not its contents."""
        found: list[TreeNode] = []
        stack = [self.top] if self.top is not None else []
        while stack:
            node = stack.pop()
            found.append(node)
            if not isinstance(node, SubTreeNode):
                stack.extend(reversed(node.children_nodes()))
        return found


def _subtree_path(parent: str, node: SubTreeNode) -> str:
    own = node.name if node.name not in ("SubTree", node.tree_id) else f"{node.tree_id}::{node.uid}"
    return f"{parent}/{own}" if parent else own


def subtree_instances(tree: Tree) -> list[SubtreeInstance]:
    """The main tree, then every SubTree instance in the order it appears (BT.CPP's)."""
    found = [SubtreeInstance(tree.tree_id or "MainTree", "", tree.root)]

    def walk(node: TreeNode, fullpath: str) -> None:
        for child in node.children_nodes():
            if isinstance(child, SubTreeNode):
                path = _subtree_path(fullpath, child)
                found.append(SubtreeInstance(child.tree_id, path, child.child))
                if child.child is not None:
                    walk(child.child, path)
            else:
                walk(child, fullpath)

    if isinstance(tree.root, SubTreeNode):
        found[0] = SubtreeInstance(tree.root.tree_id, "", tree.root.child)
    walk(tree.root, "")
    return found


def _port_attributes(node: TreeNode) -> dict[str, str]:
    config = node.config
    attributes: dict[str, str] = {}
    for name, binding in config.inputs.items():
        if binding.key is not None:
            attributes[name] = binding.text or f"{{{binding.key}}}"
        else:
            attributes[name] = binding.text or to_text(binding.value)
    for name, key in config.outputs.items():
        attributes.setdefault(name, f"{{{key}}}")
    for name, script in config.attributes.items():
        if name in CONDITION_ATTRIBUTES:
            attributes[name] = script
    return attributes


def _add_node(parent: etree._Element, node: TreeNode, metadata: bool, fullpath: str) -> None:
    if isinstance(node, SubTreeNode):
        element = etree.SubElement(parent, "SubTree", ID=node.tree_id)
        if metadata:
            element.set("_fullpath", _subtree_path(fullpath, node))
            element.set("_uid", str(node.uid))
        for name, value in node.config.attributes.items():
            if name not in _SUBTREE_OWN:
                element.set(name, value)
        return
    element = etree.SubElement(parent, node.config.registration_id or type(node).__name__)
    element.set("name", node.name)
    if metadata:
        element.set("_uid", str(node.uid))
    for name, value in _port_attributes(node).items():
        element.set(name, value)
    for child in node.children_nodes():
        _add_node(element, child, metadata, fullpath)


def _builtin_models() -> dict[str, tuple[str, dict[str, PortInfo]]]:
    factory = BehaviorTreeFactory()
    return {
        node_id: (manifest.kind, manifest.ports)
        for node_id, manifest in factory.manifests.items()
        if manifest.builtin
    }


def _add_models(root: etree._Element, tree: Tree, builtins: bool) -> None:
    models = _builtin_models() if builtins else {}
    for node in tree.nodes():
        if not isinstance(node, SubTreeNode):
            node_id = node.config.registration_id or type(node).__name__
            models[node_id] = (node.KIND, node.config.ports)
    model = etree.SubElement(root, "TreeNodesModel")
    for node_id in sorted(models):
        kind, ports = models[node_id]
        add_node_model(model, kind, node_id, ports.values())


def tree_to_xml(tree: Tree, *, metadata: bool = True, builtin_models: bool = False) -> str:
    """The XML of ``tree`` as instantiated; ``metadata`` adds ``_uid``/``_fullpath``;
    ``builtin_models`` lists every built-in node in the ``<TreeNodesModel>``, not only
    those the tree uses (Groot2's live view gets them all, as from BT.CPP)."""
    root = etree.Element("root", BTCPP_format="4")
    for instance in subtree_instances(tree):
        element = etree.SubElement(root, "BehaviorTree", ID=instance.tree_id)
        element.set("_fullpath", instance.fullpath)
        if instance.top is not None:
            _add_node(element, instance.top, metadata, instance.fullpath)
    _add_models(root, tree, builtin_models)
    return etree.tostring(root, pretty_print=True, encoding="unicode")
