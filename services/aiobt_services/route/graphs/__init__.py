"""Route graphs shipped for the bundled worlds (Nav2 GeoJSON), and their generator."""

from __future__ import annotations

from pathlib import Path

GRAPHS_DIR = Path(__file__).resolve().parent
OFFICE = GRAPHS_DIR / "office.geojson"
SMALL = GRAPHS_DIR / "small.geojson"


def graph_path(name_or_path: str) -> Path:
    """A shipped world's graph by the world's name ("office", "small"); for a map YAML
    (``aiobt up``'s ``world``) the ``.geojson`` beside it; else the path itself."""
    shipped = GRAPHS_DIR / f"{name_or_path}.geojson"
    if shipped.is_file():
        return shipped
    path = Path(name_or_path)
    return path.with_suffix(".geojson") if path.suffix in (".yaml", ".yml") else path
