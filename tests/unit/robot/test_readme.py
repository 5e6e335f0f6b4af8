"""The in-process example of services/aiobt_services/robot/README.md runs as written."""

from __future__ import annotations

import re
from pathlib import Path

import aiobt_services.robot
from aiobt_services.robot.sim import Simulation
from aiobt_services.robot.worlds import SMALL

README = Path(aiobt_services.robot.__file__).parent / "README.md"


def test_readme_python_example_runs() -> None:
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(), flags=re.DOTALL)
    assert len(blocks) == 1
    code = blocks[0].replace('"map.yaml"', repr(str(SMALL)))
    namespace: dict[str, object] = {}
    exec(compile(code, str(README), "exec"), namespace)
    sim = namespace["sim"]
    assert isinstance(sim, Simulation)
    assert sim.true_pose.x > 0.5  # it drove forwards
