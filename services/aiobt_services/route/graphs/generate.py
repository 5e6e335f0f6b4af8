"""Regenerate the shipped route graphs: ``python -m aiobt_services.route.graphs.generate``.

Each world's lanes are listed once here, as nodes and two-way lanes; every lane
becomes two directed edges (Nav2's edges are one-way). Node ids count from 1,
edge ids from 100, so every id is unique. Deterministic: a rerun rewrites
identical files. ``tests/unit/route/test_shipped_graphs.py`` holds every edge
clear of walls on its world's map.
"""

from __future__ import annotations

import argparse
import json
import logging
from pathlib import Path
from typing import Any

from . import GRAPHS_DIR

log = logging.getLogger("aiobt_services.route.graphs")
FIRST_EDGE_ID = 100
Nodes = dict[int, tuple[float, float]]
Lanes = list[tuple[int, int]]

OFFICE_NODES: Nodes = {
    # the corridor (y 8.5-11), at its doors; node 1 by the dock, west of the start (2, 9.75)
    1: (1.0, 9.75), 2: (3.5, 9.75), 3: (4.0, 9.75), 4: (9.0, 9.75), 5: (10.0, 9.75),
    6: (14.0, 9.75), 7: (16.5, 9.75), 8: (19.0, 9.75),
    # the west room
    10: (3.5, 7.0), 11: (3.5, 4.0), 12: (1.2, 4.0), 13: (6.0, 3.5),
    # the middle room, a loop round the meeting table
    15: (10.0, 7.0), 16: (12.0, 6.0), 17: (12.0, 4.0), 18: (8.0, 6.0), 19: (8.0, 1.5),
    20: (12.0, 1.5),
    # the east room
    21: (14.0, 4.0), 22: (16.5, 7.0), 23: (16.5, 4.0), 24: (19.0, 4.0),
    # the open plan
    25: (4.0, 12.3), 26: (9.0, 12.3), 27: (4.5, 14.8), 28: (10.8, 14.8), 29: (1.2, 18.0),
    30: (4.5, 18.0), 31: (10.8, 18.0), 38: (10.8, 12.3), 40: (1.2, 14.8),
    # the two north-east rooms
    32: (12.8, 18.0), 33: (12.8, 16.6), 34: (16.0, 16.6), 35: (16.0, 14.0), 36: (14.0, 12.5),
}  # fmt: skip
OFFICE_LANES: Lanes = [
    (1, 2), (2, 3), (3, 4), (4, 5), (5, 6), (6, 7), (7, 8),
    (2, 10), (10, 11), (11, 12), (11, 13),
    (5, 15), (15, 16), (16, 17), (17, 20), (20, 19), (19, 18), (18, 15),
    (17, 21), (21, 23), (23, 22), (22, 7), (23, 24),
    (3, 25), (4, 26), (25, 26), (26, 38), (38, 28), (25, 27), (27, 28), (27, 40), (40, 29),
    (29, 30), (30, 27), (30, 31), (31, 28),
    (31, 32), (32, 33), (33, 34), (34, 35), (35, 36), (36, 6),
]  # fmt: skip
SMALL_NODES: Nodes = {
    2: (0.0, -1.6), 3: (1.6, -1.6), 4: (-1.6, 0.0), 5: (0.0, 0.0), 6: (1.6, 0.0),
    7: (0.0, 1.6), 8: (1.6, 1.6),
}  # fmt: skip
SMALL_LANES: Lanes = [(2, 3), (2, 5), (3, 6), (4, 5), (5, 6), (5, 7), (6, 8), (7, 8)]
GRAPHS = {"office": (OFFICE_NODES, OFFICE_LANES), "small": (SMALL_NODES, SMALL_LANES)}


def feature(props: dict[str, Any], kind: str, coordinates: Any) -> dict[str, Any]:
    return {"type": "Feature", "properties": props,
            "geometry": {"type": kind, "coordinates": coordinates}}  # fmt: skip


def geojson(name: str, nodes: Nodes, lanes: Lanes) -> dict[str, Any]:
    features = [feature({"id": i, "frame": "map"}, "Point", list(xy)) for i, xy in nodes.items()]
    edge_id = FIRST_EDGE_ID
    for a, b in lanes:
        for start, end in ((a, b), (b, a)):
            line = [[list(nodes[start]), list(nodes[end])]]
            features.append(feature({"id": edge_id, "startid": start, "endid": end},
                                    "MultiLineString", line))  # fmt: skip
            edge_id += 1
    return {"type": "FeatureCollection", "name": f"{name}_graph", "features": features}


def write(out: Path) -> list[Path]:
    written = []
    for name, (nodes, lanes) in GRAPHS.items():
        path = out / f"{name}.geojson"
        doc = geojson(name, nodes, lanes)
        lines = ",\n".join("    " + json.dumps(f) for f in doc["features"])
        head = json.dumps({"type": doc["type"], "name": doc["name"]})[:-1]
        path.write_text(f'{head}, "features": [\n{lines}\n]}}\n', encoding="utf-8")
        written.append(path)
    return written


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", type=Path, default=GRAPHS_DIR, help="output folder")
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.INFO)
    for path in write(args.out):
        log.info("wrote %s", path)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
