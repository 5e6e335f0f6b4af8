"""Nav2's GeoJSON route graphs (``GeoJsonGraphFileLoader``) into a :class:`Graph`.

A ``FeatureCollection``: ``Point`` features are nodes (``properties.id``, the
point's coordinates, optional ``frame``, ``metadata``, ``operations``);
``LineString``/``MultiLineString`` features are edges (``id``, ``startid``,
``endid``, optional ``cost``, ``overridable``, ``metadata``, ``operations``).
Ids are unique across nodes and edges (a blocked id names either) and fit
Nav2's ``uint16``. Every problem is a :class:`GraphError` naming the file and
the feature (its index in ``features`` and its id).
"""

from __future__ import annotations

import json
import logging
import math
from pathlib import Path
from typing import Any

from .errors import GraphError
from .graph import TRIGGERS, Graph, GraphEdge, GraphNode, Metadata, Operation

log = logging.getLogger("aiobt_services.route.geojson")
MAX_ID = 65535  # nav2_msgs carries node and edge ids as uint16
FRAMES = ("", "map")  # the route frame; no TF here to bring other frames into it
EDGE_TYPES = ("LineString", "MultiLineString")


class _Reader:
    """One file's features, read with errors that say where."""

    def __init__(self, path: str) -> None:
        self.path = path
        self.ids: dict[int, str] = {}

    def fail(self, where: str, problem: str) -> GraphError:
        return GraphError(self.path, where, problem)

    def features(self, doc: Any) -> list[Any]:
        features = doc.get("features") if isinstance(doc, dict) else None
        if not isinstance(features, list):
            raise self.fail("top level", "not a GeoJSON FeatureCollection (no 'features' list)")
        return features

    def kind(self, index: int, feature: Any) -> str:
        geometry = feature.get("geometry") if isinstance(feature, dict) else None
        kind = geometry.get("type") if isinstance(geometry, dict) else None
        if not isinstance(kind, str):
            raise self.fail(f"feature {index}", "has no geometry type")
        props = feature.get("properties")
        if not isinstance(props, dict):
            raise self.fail(f"feature {index}", "has no 'properties' object")
        return kind

    def ident(self, index: int, props: dict[str, Any], key: str, what: str) -> int:
        value = props.get(key)
        if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= MAX_ID:
            raise self.fail(f"feature {index} ({what})",
                            f"'{key}' must be an integer 0..{MAX_ID}, got {value!r}")  # fmt: skip
        return value

    def claim(self, index: int, ident: int, what: str) -> str:
        where = f"feature {index} ({what} id {ident})"
        if ident in self.ids:
            raise self.fail(where, f"duplicate id: {self.ids[ident]} has it already")
        self.ids[ident] = where
        return where

    def node(self, index: int, feature: dict[str, Any]) -> GraphNode:
        props = feature["properties"]
        ident = self.ident(index, props, "id", "node")
        where = self.claim(index, ident, "node")
        coords = feature["geometry"].get("coordinates")
        if not (isinstance(coords, list) and len(coords) >= 2 and _finite(coords[0])
                and _finite(coords[1])):  # fmt: skip
            raise self.fail(where, f"coordinates must be [x, y] numbers, got {coords!r}")
        frame = props.get("frame", "")
        if frame not in FRAMES:
            raise self.fail(where, f"frame '{frame}' is not the route frame 'map'")
        return GraphNode(ident, float(coords[0]), float(coords[1]), self.metadata(where, props),
                         self.operations(where, props))  # fmt: skip

    def edge(self, index: int, feature: dict[str, Any], nodes: dict[int, GraphNode]) -> GraphEdge:
        props = feature["properties"]
        ident = self.ident(index, props, "id", "edge")
        where = self.claim(index, ident, "edge")
        ends = []
        for key in ("startid", "endid"):
            end = self.ident(index, props, key, f"edge id {ident}")
            if end not in nodes:
                raise self.fail(where, f"{key} {end} is not a node of the graph")
            ends.append(nodes[end])
        cost = props.get("cost", 0.0)
        if not _finite(cost):
            raise self.fail(where, f"cost must be a number, got {cost!r}")
        overridable = props.get("overridable", True)
        if not isinstance(overridable, bool):
            raise self.fail(where, f"overridable must be true or false, got {overridable!r}")
        return GraphEdge(ident, ends[0], ends[1], float(cost), overridable,
                         self.metadata(where, props), self.operations(where, props))  # fmt: skip

    def metadata(self, where: str, props: dict[str, Any]) -> Metadata:
        metadata = props.get("metadata", {})
        if not isinstance(metadata, dict):
            raise self.fail(where, f"metadata must be an object, got {metadata!r}")
        return metadata

    def operations(self, where: str, props: dict[str, Any]) -> tuple[Operation, ...]:
        found = props.get("operations", {})
        items = found.items() if isinstance(found, dict) else enumerate(found)
        if not isinstance(found, dict | list):
            raise self.fail(where, f"operations must be an object or a list, got {found!r}")
        operations = []
        for name, op in items:
            if not (isinstance(op, dict) and isinstance(op.get("type"), str)
                    and op.get("trigger") in TRIGGERS):  # fmt: skip
                problem = f"needs a 'type' and a 'trigger' in {TRIGGERS}, got {op!r}"
                raise self.fail(f"{where} operation {name}", problem)
            operations.append(Operation(op["type"], op["trigger"], self.metadata(where, op)))
        return tuple(operations)


def _finite(value: Any) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value)


def parse_graph(text: str, path: str = "<string>") -> Graph:
    """The graph in GeoJSON ``text`` (``path`` names it in errors)."""
    reader = _Reader(path)
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as exc:
        raise reader.fail(f"line {exc.lineno} column {exc.colno}", f"not JSON: {exc.msg}") from None
    features = reader.features(doc)
    kinds = [reader.kind(i, feature) for i, feature in enumerate(features)]
    pairs = list(enumerate(zip(features, kinds, strict=True)))
    nodes = [reader.node(i, f) for i, (f, k) in pairs if k == "Point"]
    by_id = {node.nodeid: node for node in nodes}
    edges = [reader.edge(i, f, by_id) for i, (f, k) in pairs if k in EDGE_TYPES]
    if not nodes or not edges:
        raise reader.fail("features", f"the graph needs nodes and edges; it has {len(nodes)} "
                          f"nodes and {len(edges)} edges")  # fmt: skip
    for edge in edges:
        edge.start.edges.append(edge)
    name = doc.get("name", "") if isinstance(doc.get("name", ""), str) else ""
    return Graph(nodes, edges, name or Path(path).stem)


def load_graph(path: str | Path) -> Graph:
    """The graph in the GeoJSON file ``path``."""
    try:
        text = Path(path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise GraphError(str(path), "file", f"cannot be read: {exc}") from None
    return parse_graph(text, str(path))


def load_or_explain(path: str | Path | None) -> tuple[Graph | None, str]:
    """The graph at ``path``, or None and why (logged): none given, or the error."""
    if path is None:
        return None, "no route graph set (--graph-filepath)"
    try:
        graph = load_graph(path)
    except GraphError as exc:
        log.error("%s", exc)
        return None, str(exc)
    log.info("route graph %s: %d nodes, %d edges", path, len(graph), len(graph.edges))
    return graph, ""
