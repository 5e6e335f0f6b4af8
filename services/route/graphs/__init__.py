"""Route graphs shipped for the bundled worlds (Nav2 GeoJSON), and their generator."""

from __future__ import annotations

from pathlib import Path

GRAPHS_DIR = Path(__file__).resolve().parent
OFFICE = GRAPHS_DIR / "office.geojson"
SMALL = GRAPHS_DIR / "small.geojson"


def graph_path(name_or_path: str) -> Path:
    """A shipped world's graph by the world's name ("office", "small"), or any path."""
    shipped = GRAPHS_DIR / f"{name_or_path}.geojson"
    return shipped if shipped.is_file() else Path(name_or_path)
