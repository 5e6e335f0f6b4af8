"""The default trees are the repository's trees/nav2, shipped as package data (no copy)."""

from __future__ import annotations

import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from aiobt_services.navigator.trees import DEFAULT_TO_POSE_TREE, TREES_DIR, packaged_trees_dir

REPO = Path(__file__).resolve().parents[3]
DOCUMENTED = REPO / "trees" / "nav2"


def test_an_editable_install_reads_the_trees_of_the_checkout_itself() -> None:
    assert packaged_trees_dir().resolve() == DOCUMENTED.resolve()
    assert TREES_DIR.resolve() == DOCUMENTED.resolve()
    assert DEFAULT_TO_POSE_TREE.is_file()


LOOKUP = (
    "from aiobt_services.navigator.trees import DEFAULT_TO_POSE_TREE as t, TREES_DIR as d;"
    "print(d); print(t.is_file())"
)


@pytest.mark.integration
@pytest.mark.timeout(300)
def test_a_non_editable_install_finds_its_trees(tmp_path: Path) -> None:
    """A wheel of this checkout, unpacked into a fresh folder (pip install --target,
    no editable hooks on its path), resolves the default trees inside that folder."""
    source = tmp_path / "source"  # setuptools builds in the source folder: a copy
    skip = shutil.ignore_patterns("__pycache__", "*.egg-info")
    for folder in ("src", "services", "trees"):
        shutil.copytree(REPO / folder, source / folder, ignore=skip)
    for file in ("pyproject.toml", "README.md"):
        shutil.copy(REPO / file, source / file)
    build = [sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation"]
    subprocess.run([*build, "-q", "-w", str(tmp_path), str(source)], check=True, timeout=240)
    [wheel] = tmp_path.glob("aiobt_runtime-*.whl")
    names = zipfile.ZipFile(wheel).namelist()
    assert "aiobt/trees/nav2/navigate_to_pose_w_replanning_and_recovery.xml" in names
    target = tmp_path / "site"
    install = [sys.executable, "-m", "pip", "install", "-q", "--no-deps", "--target"]
    subprocess.run([*install, str(target), str(wheel)], check=True, timeout=120)
    # -S: no site-packages, so no editable finder for this checkout; the dependencies
    # come from the test's own environment after the unpacked wheel on the path
    site = [p for p in sys.path if p.endswith("site-packages")]
    path = ":".join([str(target), *site])
    found = subprocess.run(
        [sys.executable, "-S", "-c", LOOKUP],
        env={"PYTHONPATH": path},
        cwd=tmp_path,
        capture_output=True,
        text=True,
        check=True,
        timeout=60,
    ).stdout.split()
    assert found == [str(target / "aiobt/trees/nav2"), "True"]
