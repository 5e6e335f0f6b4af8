"""Turning tree definitions into nodes: validate against the registry, build.

Each element becomes a node with its ports bound: literals converted to the
port's type once, at load time; ``{key}`` pointers bound to the blackboard.
Every error names file, line and node path, and suggests the closest ID.
"""

from __future__ import annotations

import difflib
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, get_origin

from aiobt.core.blackboard import Blackboard
from aiobt.core.conditions import NodeConditions
from aiobt.core.convert import convert, converter_for, type_name
from aiobt.core.errors import TreeLoadError
from aiobt.core.manifest import NodeManifest
from aiobt.core.node import NodeConfig, NodeKind, PortBinding, TreeContext, TreeNode
from aiobt.core.ports import CONDITION_ATTRIBUTES, RESERVED_ATTRIBUTES, PortInfo, blackboard_key
from aiobt.nodes.subtree import SubTreeNode
from aiobt.xml.document import Element, TreeDefinition, line_of

EXPLICIT_TAGS = frozenset({"Action", "Condition", "Control", "Decorator"})
ScriptCompiler = Callable[[str, str], Callable[[TreeNode], Any]]
ManifestLookup = Callable[[str, str, str], NodeManifest | None]

_CONDITION_FIELDS = {
    "_failureIf": "failure_if",
    "_successIf": "success_if",
    "_skipIf": "skip_if",
    "_while": "while_true",
    "_onSuccess": "on_success",
    "_onFailure": "on_failure",
    "_onHalted": "on_halted_script",
    "_post": "post",
}


@dataclass(slots=True)
class _Site:
    """Where an element is: for error messages."""

    file: str | None
    line: int | None
    path: str

    def error(self, message: str) -> TreeLoadError:
        return TreeLoadError(message, file=self.file, line=self.line, node_path=self.path)


class TreeBuilder:
    """Builds one tree from the registered definitions."""

    def __init__(
        self,
        definitions: Mapping[str, TreeDefinition],
        lookup: ManifestLookup,
        known_ids: Callable[[], list[str]],
        context: TreeContext,
        script_compiler: ScriptCompiler | None,
    ) -> None:
        self.definitions = definitions
        self.lookup = lookup
        self.known_ids = known_ids
        self.context = context
        self.script_compiler = script_compiler
        self._uid = 0

    def build(self, tree_id: str, blackboard: Blackboard) -> TreeNode:
        definition = self._definition(tree_id, None)
        return self._build_tree(definition, blackboard, tree_id, (tree_id,))

    def _definition(self, tree_id: str, site: _Site | None) -> TreeDefinition:
        definition = self.definitions.get(tree_id)
        if definition is None:
            known = sorted(self.definitions)
            hint = _suggest(tree_id, known)
            listed = ", ".join(known) or "none"
            message = f"no BehaviorTree with ID [{tree_id}] is registered{hint}; known: {listed}"
            raise site.error(message) if site else TreeLoadError(message)
        return definition

    def _build_tree(
        self, definition: TreeDefinition, bb: Blackboard, path: str, stack: tuple[str, ...]
    ) -> TreeNode:
        top = next(c for c in definition.element if isinstance(c.tag, str))
        return self._build(top, definition, bb, path, stack)

    def _build(
        self,
        element: Element,
        definition: TreeDefinition,
        bb: Blackboard,
        parent_path: str,
        stack: tuple[str, ...],
    ) -> TreeNode:
        tag = str(element.tag)
        node_id = element.get("ID") if tag in EXPLICIT_TAGS or tag == "SubTree" else tag
        site = _Site(definition.file, line_of(element), f"{parent_path}/{tag}")
        if not node_id:
            raise site.error(f"<{tag}> needs an ID attribute")
        name = element.get("name") or node_id
        path = f"{parent_path}/{node_id}" + (f"[{name}]" if name != node_id else "")
        site.path = path
        self._uid += 1
        uid = self._uid
        if tag == "SubTree":
            return self._build_subtree(element, definition, bb, site, name, uid, stack)
        manifest = self.lookup(node_id, path, name)
        if manifest is None:
            raise site.error(
                f"unknown node ID [{node_id}]{_suggest(node_id, self.known_ids(), 0.8)}"
            )
        children = [c for c in element if isinstance(c.tag, str)]
        _check_children(manifest, len(children), site)
        if manifest.id == "ReactiveSequence":
            _check_reactive_children(children, site)
        node = self._instantiate(manifest, element, bb, name, path, uid, site)
        for child_element in children:
            child = self._build(child_element, definition, bb, path, stack)
            node.add_child(child)  # type: ignore[attr-defined]
        return node

    def _instantiate(
        self,
        manifest: NodeManifest,
        element: Element,
        bb: Blackboard,
        name: str,
        path: str,
        uid: int,
        site: _Site,
    ) -> TreeNode:
        attributes = {str(k): str(v) for k, v in element.attrib.items()}
        config = NodeConfig(
            blackboard=bb,
            ports=dict(manifest.ports),
            path=path,
            uid=uid,
            registration_id=manifest.id,
            attributes=attributes,
            context=self.context,
        )
        conditions = NodeConditions()
        for key, value in attributes.items():
            if key in RESERVED_ATTRIBUTES:
                continue
            if key in CONDITION_ATTRIBUTES:
                setattr(conditions, _CONDITION_FIELDS[key], self._compile(key, value, site))
            elif key in manifest.ports:
                _bind_port(config, manifest.ports[key], value, bb, site)
            else:
                raise site.error(_unknown_attribute(key, manifest))
        _bind_defaults(config, manifest, bb, site)
        _check_required(config, manifest, site)
        try:
            node = manifest.builder(name, config)
        except TreeLoadError:
            raise
        except Exception as exc:
            raise site.error(f"cannot create [{manifest.id}]: {exc}") from exc
        if conditions:
            node.attach_conditions(conditions)
        return node

    def _compile(self, attribute: str, script: str, site: _Site) -> Callable[[TreeNode], Any]:
        if self.script_compiler is None:
            raise site.error(
                f"{attribute}: this factory has no script language to evaluate {script!r}"
            )
        try:
            return self.script_compiler(script, attribute)
        except Exception as exc:
            raise site.error(f'{attribute}="{script}": {exc}') from exc

    def _build_subtree(
        self,
        element: Element,
        definition: TreeDefinition,
        bb: Blackboard,
        site: _Site,
        name: str,
        uid: int,
        stack: tuple[str, ...],
    ) -> TreeNode:
        tree_id = str(element.get("ID"))
        if tree_id in stack:
            chain = " -> ".join((*stack, tree_id))
            raise site.error(f"recursive SubTree: {chain}")
        target = self._definition(tree_id, site)
        child_bb = Blackboard.create(bb, autoremap=_truthy(element.get("_autoremap"), site))
        for key, value in element.attrib.items():
            key = str(key)
            if key in ("ID", "name", "_autoremap") or key in RESERVED_ATTRIBUTES:
                continue
            if key in CONDITION_ATTRIBUTES:
                continue
            pointer = blackboard_key(str(value), key)
            if pointer is not None:
                child_bb.add_remapping(key, pointer)
            else:
                child_bb.set(key, str(value))
        config = NodeConfig(
            blackboard=bb,
            path=site.path,
            uid=uid,
            registration_id="SubTree",
            attributes={str(k): str(v) for k, v in element.attrib.items()},
            context=self.context,
        )
        node = SubTreeNode(name, config, tree_id=tree_id, subtree_blackboard=child_bb)
        conditions = NodeConditions()
        for key, value in config.attributes.items():
            if key in CONDITION_ATTRIBUTES:
                setattr(conditions, _CONDITION_FIELDS[key], self._compile(key, value, site))
        if conditions:
            node.attach_conditions(conditions)
        node.add_child(self._build_tree(target, child_bb, site.path, (*stack, tree_id)))
        return node


def _truthy(raw: str | None, site: _Site) -> bool:
    if raw is None:
        return False
    if raw.strip().lower() in ("true", "1"):
        return True
    if raw.strip().lower() in ("false", "0"):
        return False
    raise site.error(f"_autoremap must be true or false, not {raw!r}")


def _check_children(manifest: NodeManifest, count: int, site: _Site) -> None:
    minimum, maximum = manifest.child_range
    if count < minimum or (maximum is not None and count > maximum):
        if maximum == 0:
            expected = "no children"
        elif maximum == minimum:
            expected = f"exactly {minimum} child" + ("ren" if minimum != 1 else "")
        else:
            expected = f"at least {minimum} child" + ("ren" if minimum != 1 else "")
        kind = manifest.kind if manifest.kind != NodeKind.SUBTREE else "SubTree"
        raise site.error(f"{kind} node [{manifest.id}] must have {expected}, it has {count}")


def _check_required(config: NodeConfig, manifest: NodeManifest, site: _Site) -> None:
    missing = [
        p.name for p in manifest.ports.values() if p.required and p.name not in config.inputs
    ]
    if missing:
        listed = ", ".join(f"[{name}]" for name in missing)
        raise site.error(f"[{manifest.id}] is missing its required port {listed}")


def _check_reactive_children(children: list[Element], site: _Site) -> None:
    """BT.CPP's load check: two AsyncSequence children of one ReactiveSequence would race."""
    ids = [c.get("ID") if c.tag in EXPLICIT_TAGS else c.tag for c in children]
    if ids.count("AsyncSequence") > 1:
        raise site.error("a ReactiveSequence cannot have more than one async child (AsyncSequence)")


def _unknown_attribute(key: str, manifest: NodeManifest) -> str:
    ports = sorted(manifest.ports)
    hint = _suggest(key, ports)
    listed = ", ".join(ports) if ports else "none"
    return f"attribute [{key}] is not a port of [{manifest.id}]{hint}; its ports: {listed}"


def _suggest(word: str, candidates: list[str], cutoff: float = 0.6) -> str:
    """A close candidate: node IDs ask for a closer match (0.8) than port names, so a
    Nav2 ID the registry lacks is not "corrected" to an unrelated one."""
    close = difflib.get_close_matches(word, candidates, n=1, cutoff=cutoff)
    if not close:
        lowered = word.lower()
        close = [c for c in candidates if c.lower() == lowered]
        close = close or sorted((c for c in candidates if lowered in c.lower()), key=len)[:1]
    return f" (did you mean [{close[0]}]?)" if close else ""


def _python_type(port: PortInfo) -> Any:
    return port.type if isinstance(port.type, type) or hasattr(port.type, "__origin__") else None


def _bind_port(config: NodeConfig, port: PortInfo, text: str, bb: Blackboard, site: _Site) -> None:
    key = blackboard_key(text, port.name)
    if key is not None:
        _declare_entry(bb, key, port, site)
        if port.is_input:
            conv = converter_for(port.type) if port.type is not str else None
            config.inputs[port.name] = PortBinding(key=key, converter=conv, text=text)
        if port.is_output:
            config.outputs[port.name] = key
        return
    if not port.is_input:
        raise site.error(
            f"output port [{port.name}] must name a blackboard entry "
            f"like {{{port.name}}}, not {text!r}"
        )
    try:
        value = convert(text, port.type)
    except (ValueError, TypeError) as exc:
        raise site.error(
            f"port [{port.name}]: cannot convert {text!r} to {type_name(port.type)}: {exc}"
        ) from exc
    config.inputs[port.name] = PortBinding(key=None, value=value, text=text)


def _declare_entry(bb: Blackboard, key: str, port: PortInfo, site: _Site) -> None:
    tp = _python_type(port)
    if tp is None or tp is str:
        return
    entry = bb.entry(key)
    if entry is None:
        bb.create_entry(key, tp)
    elif entry.type is None and not entry.has_value:
        entry.type = tp
    elif entry.type is not None and entry.type != tp and not _numeric_pair(entry.type, tp):
        raise site.error(
            f"port [{port.name}] uses blackboard key [{key}] as {type_name(tp)}, "
            f"but it was declared as {type_name(entry.type)} elsewhere"
        )


def _numeric_pair(a: Any, b: Any) -> bool:
    """Types one entry may hold for both ports: int/float, or ``list`` and ``list[float]``."""
    if {a, b} <= {int, float}:
        return True
    return (get_origin(a) or a) is (get_origin(b) or b)


def _bind_defaults(config: NodeConfig, manifest: NodeManifest, bb: Blackboard, site: _Site) -> None:
    for port in manifest.ports.values():
        if not port.has_default:
            continue
        default = port.default
        if port.is_input and port.name not in config.inputs:
            if isinstance(default, str):
                _bind_port(config, port, default, bb, site)
            else:
                config.inputs[port.name] = PortBinding(key=None, value=default, text=str(default))
        if port.is_output and port.name not in config.outputs and isinstance(default, str):
            key = blackboard_key(default, port.name)
            if key is not None:
                config.outputs[port.name] = key
