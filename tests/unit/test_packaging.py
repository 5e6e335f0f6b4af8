"""pyproject.toml names every package: setuptools finds none of them by itself (two
import packages from two folders, and trees/ shipped as aiobt.trees)."""

from __future__ import annotations

import tomllib
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
ROOTS = {"aiobt": REPO / "src" / "aiobt", "aiobt_services": REPO / "services" / "aiobt_services"}


def configured() -> tuple[list[str], dict[str, str]]:
    setuptools = tomllib.loads((REPO / "pyproject.toml").read_text())["tool"]["setuptools"]
    return list(setuptools["packages"]), dict(setuptools["package-dir"])


def packages_on_disk() -> set[str]:
    found = {"aiobt.trees"}
    for name, root in ROOTS.items():
        for init in root.rglob("__init__.py"):
            parts = init.parent.relative_to(root).parts
            found.add(".".join((name, *parts)))
    return found


def test_every_package_on_disk_is_listed_and_nothing_else() -> None:
    listed, _ = configured()
    assert sorted(set(listed)) == sorted(listed), "a package is listed twice"
    on_disk = packages_on_disk()
    assert sorted(on_disk - set(listed)) == [], "add these to [tool.setuptools] packages"
    assert sorted(set(listed) - on_disk) == [], "these are listed but have no __init__.py"


def test_the_package_folders_are_the_documented_ones() -> None:
    _, folders = configured()
    assert folders == {
        "aiobt": "src/aiobt",
        "aiobt_services": "services/aiobt_services",
        "aiobt.trees": "trees",
    }
    assert (REPO / "trees" / "__init__.py").is_file()
    assert not (REPO / "setup.py").exists()
