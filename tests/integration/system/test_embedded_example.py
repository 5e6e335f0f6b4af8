"""examples/embedded.py runs against the real system and reaches both goals."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from aiobt.testing.bus import free_endpoint

from .helpers import SystemProcess, kill_mentioning

pytestmark = [pytest.mark.integration, pytest.mark.timeout(240)]
REPO = Path(__file__).resolve().parents[3]


def test_the_embedding_example_ticks_its_tree_and_navigates(tmp_path: Path) -> None:
    endpoint = free_endpoint()
    config = tmp_path / "system.yaml"
    config.write_text(
        f"namespace: embed\nworld: small\nspeed: 2\nrouter: {{listen: '{endpoint}'}}\n"
    )
    try:
        with SystemProcess(["up", "--config", str(config)]) as up:
            up.wait_line("        up * ")
            example = [sys.executable, str(REPO / "examples" / "embedded.py")]
            args = ["--connect", endpoint, "--namespace", "embed", "--sim-time"]
            done = subprocess.run(
                [*example, *args], capture_output=True, text=True, timeout=150, check=False
            )
            assert done.returncode == 0, done.stdout + done.stderr
            lines = done.stdout.splitlines()
            assert lines[0] == f"connecting to {endpoint}, namespace embed"  # at once
            assert lines[1] == "own tree: planning and driving to (0.8, 0.6)..."
            assert lines[2].startswith("own tree: SUCCESS (")
            assert lines[-1] == "navigator: SUCCEEDED"
            assert any(line.endswith(" m to go") for line in lines)
    finally:
        kill_mentioning(endpoint)
