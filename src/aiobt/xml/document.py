"""Reading BehaviorTree.CPP XML: documents, ``<include>``, tree definitions.

Every error names the file and line. Version 3 files load with a warning and
their renamed nodes translated (``SequenceStar`` is ``SequenceWithMemory``).
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from lxml import etree

from aiobt.core.errors import TreeLoadError

log = logging.getLogger("aiobt.xml")

Element = etree._Element

# BT.CPP v3 names and their v4 equivalents.
V3_RENAMES = {
    "SequenceStar": "SequenceWithMemory",
    "FallbackStar": "Fallback",
    "SubTreePlus": "SubTree",
}


def line_of(element: Any) -> int | None:
    """The element's line in its file (lxml's ``sourceline``), if known."""
    line = element.sourceline
    return line if isinstance(line, int) else None


@dataclass(slots=True)
class TreeDefinition:
    """One ``<BehaviorTree ID=...>`` with where it came from."""

    tree_id: str
    element: Element
    file: str | None
    format_version: int

    @property
    def line(self) -> int | None:
        return line_of(self.element)


@dataclass(slots=True)
class ParsedDocument:
    trees: list[TreeDefinition] = field(default_factory=list)
    main_tree_to_execute: str | None = None
    models: list[Element] = field(default_factory=list)
    file: str | None = None
    line: int | None = None  # of <root>, where main_tree_to_execute is written


_PARSER = etree.XMLParser(remove_comments=True, remove_pis=True, resolve_entities=False)


def parse_text(
    text: str, file: str | None = None, _seen: frozenset[str] = frozenset()
) -> ParsedDocument:
    """Parse one XML document (and the files it includes)."""
    try:
        root = etree.fromstring(text.encode("utf-8"), parser=_PARSER)
    except etree.XMLSyntaxError as exc:
        raise TreeLoadError(f"malformed XML: {exc.msg}", file=file, line=exc.lineno) from exc
    if root.tag != "root":
        raise TreeLoadError(
            f"the top element must be <root>, not <{root.tag}>", file=file, line=line_of(root)
        )
    version = _format_version(root, file)
    document = ParsedDocument(
        main_tree_to_execute=root.get("main_tree_to_execute"), file=file, line=line_of(root)
    )
    for element in root:
        if not isinstance(element.tag, str):
            continue
        _read_top_element(element, document, file, version, _seen)
    return document


def parse_file(path: str | Path, _seen: frozenset[str] = frozenset()) -> ParsedDocument:
    file = str(Path(path))
    try:
        text = Path(path).read_text(encoding="utf-8")
    except OSError as exc:
        raise TreeLoadError(f"cannot read tree file: {exc.strerror}", file=file) from exc
    return parse_text(text, file=file, _seen=_seen | {str(Path(path).resolve())})


def _format_version(root: Element, file: str | None) -> int:
    raw = root.get("BTCPP_format")
    if raw == "4":
        return 4
    if raw in (None, "3"):
        log.warning(
            "%s: BTCPP_format=%s; loading as BehaviorTree.CPP v3 (translated to v4)",
            file or "<text>",
            raw or "(missing)",
        )
        return 3
    raise TreeLoadError(
        f"unsupported BTCPP_format={raw!r} (expected 4 or 3)", file=file, line=line_of(root)
    )


def _read_top_element(
    element: Element, document: ParsedDocument, file: str | None, version: int, seen: frozenset[str]
) -> None:
    tag = element.tag
    if tag == "BehaviorTree":
        document.trees.append(_tree_definition(element, file, version))
    elif tag == "include":
        included = _include(element, file, seen)
        document.trees.extend(included.trees)
        document.models.extend(included.models)
    elif tag == "TreeNodesModel":
        document.models.append(element)
    else:
        raise TreeLoadError(
            f"unexpected <{tag}> under <root> (expected BehaviorTree, include or TreeNodesModel)",
            file=file,
            line=line_of(element),
        )


def _tree_definition(element: Element, file: str | None, version: int) -> TreeDefinition:
    tree_id = element.get("ID")
    if not tree_id:
        raise TreeLoadError(
            "<BehaviorTree> needs an ID attribute", file=file, line=line_of(element)
        )
    children = [c for c in element if isinstance(c.tag, str)]
    if len(children) != 1:
        raise TreeLoadError(
            f'<BehaviorTree ID="{tree_id}"> must have exactly one child, it has {len(children)}',
            file=file,
            line=line_of(element),
        )
    if version == 3:
        _translate_v3(children[0])
    return TreeDefinition(tree_id, element, file, version)


def _translate_v3(element: Element) -> None:
    for node in element.iter():
        if isinstance(node.tag, str) and node.tag in V3_RENAMES:
            node.tag = V3_RENAMES[node.tag]
        if node.get("__shared_blackboard") is not None:
            node.set("_autoremap", node.attrib.pop("__shared_blackboard"))


def _include(element: Element, file: str | None, seen: frozenset[str]) -> ParsedDocument:
    raw = element.get("path")
    if not raw:
        raise TreeLoadError("<include> needs a path attribute", file=file, line=line_of(element))
    if element.get("ros_pkg"):
        raise TreeLoadError(
            "<include ros_pkg=...> needs ROS; give a plain path", file=file, line=line_of(element)
        )
    base = Path(file).parent if file else Path.cwd()
    target = (base / raw).resolve()
    if str(target) in seen:
        raise TreeLoadError(
            f'<include path="{raw}"> includes itself in a cycle', file=file, line=line_of(element)
        )
    if not target.is_file():
        raise TreeLoadError(
            f'<include path="{raw}">: no such file {target}', file=file, line=line_of(element)
        )
    return parse_file(target, seen | {str(target)})
