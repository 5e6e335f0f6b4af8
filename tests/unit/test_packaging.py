"""Packaging from pyproject.toml alone: setuptools finds the library in src/ and the
services in services/, and Nav2's trees ship once, from the repository's trees/."""

from __future__ import annotations

import tomllib
from pathlib import Path

from setuptools import find_packages  # type: ignore[import-untyped]

REPO = Path(__file__).resolve().parents[2]


def test_setuptools_finds_every_package_and_the_trees() -> None:
    find = tomllib.loads((REPO / "pyproject.toml").read_text())["tool"]["setuptools"]
    assert find["packages"]["find"]["where"] == ["src", "services"]
    library = find_packages(str(REPO / "src"))
    services = find_packages(str(REPO / "services"))
    assert {"aiobt", "aiobt.nav.conditions", "aiobt.trees"} <= set(library)
    assert {"aiobt_services", "aiobt_services.navigator"} <= set(services)
    assert not (REPO / "setup.py").exists()


def test_the_trees_package_is_the_repository_trees_folder_not_a_copy() -> None:
    link = REPO / "src" / "aiobt" / "trees"
    assert link.is_symlink()
    assert link.resolve() == (REPO / "trees").resolve()
    copies = [
        path
        for folder in ("src", "services")
        for path in (REPO / folder).rglob("*.xml")
        if not path.resolve().is_relative_to((REPO / "trees").resolve())
    ]
    assert copies == []
