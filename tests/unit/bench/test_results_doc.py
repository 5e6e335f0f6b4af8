"""bench/RESULTS.md and bench/history: every link lands, every benchmark has a row,
every figure in the tables is one the history records."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
BENCH = REPO / "bench"
RESULTS = BENCH / "RESULTS.md"
HISTORY = sorted((BENCH / "history").glob("*.md"))
DOCS = [RESULTS, BENCH / "README.md", BENCH / "core" / "README.md", *HISTORY]
NUMBER = re.compile(r"\d+(?:[.,]\d+)*")


def _slug(heading: str) -> str:
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens."""
    return re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")


def _anchors(doc: Path) -> set[str]:
    anchors: set[str] = set()
    seen: dict[str, int] = {}
    in_code = False
    for line in doc.read_text(encoding="utf-8").splitlines():
        in_code = in_code != line.startswith("```")
        heading = re.match(r"#{1,6} (.+)", line)
        if heading and not in_code:
            slug = _slug(heading.group(1))
            count = seen.get(slug, 0)
            seen[slug] = count + 1
            anchors.add(f"{slug}-{count}" if count else slug)
    return anchors


def _relative_links(doc: Path) -> list[str]:
    text = doc.read_text(encoding="utf-8")
    inline = re.findall(r"\]\(([^)\s]+)\)", text)
    references = re.findall(r"^\[[^\]]+\]: (\S+)$", text, flags=re.M)
    return [link for link in inline + references if not re.match(r"[a-z]+:", link)]


def _section(text: str, area: str) -> str:
    match = re.search(rf"^## {area}\n(.*?)(?=^## |\Z)", text, flags=re.M | re.S)
    assert match, f"bench/RESULTS.md has no '## {area}' table"
    return match.group(1)


@pytest.mark.parametrize("doc", DOCS, ids=lambda doc: str(doc.relative_to(BENCH)))
def test_every_relative_link_lands_on_a_file_and_a_heading(doc: Path) -> None:
    links = _relative_links(doc)
    assert links
    for link in links:
        path, _, anchor = link.partition("#")
        target = (doc.parent / path).resolve() if path else doc
        assert target.exists(), f"{doc.relative_to(REPO)}: {link}: no such file"
        if anchor:
            assert anchor in _anchors(target), f"{doc.relative_to(REPO)}: {link}: no such heading"


def test_every_bench_script_has_a_row_or_a_line_in_its_area() -> None:
    text = RESULTS.read_text(encoding="utf-8")
    scripts = [path for path in sorted(BENCH.glob("*/*.py")) if path.name != "__init__.py"]
    assert len(scripts) > 20
    for script in scripts:
        area, name = script.parent.name, script.stem
        section = _section(text, area)
        named = re.search(rf"bench\.{area}\.{name}\b|`{name}\.py`", section)
        assert named, f"bench/{area}/{name}.py is named nowhere in bench/RESULTS.md's '## {area}'"


def test_every_area_has_a_history_file_the_table_links_to() -> None:
    text = RESULTS.read_text(encoding="utf-8")
    areas = sorted(path.parent.name for path in BENCH.glob("*/__init__.py"))
    assert [path.stem for path in HISTORY] == areas
    for area in areas:
        assert f"history/{area}.md" in text


def test_every_figure_in_the_tables_is_copied_from_the_history() -> None:
    recorded = set(NUMBER.findall("\n".join(p.read_text(encoding="utf-8") for p in HISTORY)))
    recorded |= set(NUMBER.findall((BENCH / "core" / "README.md").read_text(encoding="utf-8")))
    rows = [
        line
        for line in RESULTS.read_text(encoding="utf-8").splitlines()
        if line.startswith("| ") and not line.startswith("| what |")
    ]
    assert len(rows) > 50
    for row in rows:
        cells = row.split(" | ")[:-1]  # the last cell is the history link
        unknown = [n for n in NUMBER.findall(" | ".join(cells)) if n not in recorded]
        assert not unknown, f"not in bench/history: {unknown} in {row[:80]}..."
