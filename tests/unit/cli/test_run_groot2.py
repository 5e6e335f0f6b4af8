"""``aiobt run --groot2``: Groot2 attaches to the tree the command runs."""

from __future__ import annotations

import asyncio
import json
import socket
import sys
from pathlib import Path

import pytest

from aiobt.cli.main import main
from tests.groot2_client import Groot2Client, free_port_pair, status_pairs

LONG_SLEEP = (
    '<root BTCPP_format="4"><BehaviorTree ID="T"><Sequence>'
    '<Sleep name="nap" msec="600000"/><AlwaysSuccess name="done"/>'
    "</Sequence></BehaviorTree></root>"
)


@pytest.mark.timeout(60)
async def test_groot2_sees_the_running_sleep_and_replaces_it(tmp_path: Path) -> None:
    tree = tmp_path / "nap.xml"
    tree.write_text(LONG_SLEEP)
    port = free_port_pair()
    code = f"from aiobt.cli.main import main; raise SystemExit(main({['run', str(tree), '--groot2', str(port)]!r}))"  # noqa: E501
    process = await asyncio.create_subprocess_exec(
        sys.executable, "-c", code, stdout=asyncio.subprocess.PIPE
    )
    client = Groot2Client(port)
    try:
        statuses: dict[int, int] = {}
        async with asyncio.timeout(30):
            while statuses.get(2) != 1:  # the publisher comes up, then the tick starts
                statuses = dict(status_pairs((await client.request("S"))[1]))
        assert b'<Sleep name="nap" _uid="2"' in (await client.request("T"))[1]
        replace = {"uid": 2, "mode": 1, "enabled": True, "once": True,
                   "desired_status": "SUCCESS", "position": 0}  # fmt: skip
        await client.request("I", json.dumps(replace))
        out, _ = await asyncio.wait_for(process.communicate(), 30)
    finally:
        client.close()
        if process.returncode is None:
            process.kill()
            await process.wait()
    assert process.returncode == 0
    assert b"tree T: SUCCESS" in out


def test_a_taken_groot2_port_is_reported(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    tree = tmp_path / "nap.xml"
    tree.write_text(LONG_SLEEP)
    port = free_port_pair()
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", port))
        taken.listen()
        assert main(["run", str(tree), "--groot2", str(port)]) == 2
    assert f"cannot bind tcp://127.0.0.1:{port}" in capsys.readouterr().err


def test_a_bad_groot2_port_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        main(["run", str(tmp_path / "x.xml"), "--groot2", "70000"])
    assert "not a port in 1..65534" in capsys.readouterr().err
