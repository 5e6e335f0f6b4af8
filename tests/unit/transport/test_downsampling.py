"""deploy/downsampling.json5 is a valid Zenoh downsampling section; a bad file is named."""

from __future__ import annotations

from pathlib import Path

import pytest
import zenoh

from aiobt.transport.downsampling import insert_rules, load_rules
from aiobt.transport.settings import BusConfigError

SHIPPED = Path(__file__).resolve().parents[3] / "deploy" / "downsampling.json5"


def test_the_shipped_rules_thin_the_robot_s_streams_leaving_towards_the_base_host() -> None:
    (section,) = load_rules(SHIPPED)
    assert section["flows"] == ["egress"]
    assert section["interfaces"] == ["wlan0"]
    rates = {rule["key_expr"]: rule["freq"] for rule in section["rules"]}
    assert rates == {"*/scan": 2.0, "*/odom": 10.0, "*/pose": 10.0, "*/clock": 10.0,
                     "*/cmd_vel": 10.0}  # fmt: skip
    config = zenoh.Config()
    insert_rules(config, SHIPPED)
    assert '"*/scan"' in config.get_json("downsampling")


def test_a_bad_file_is_named(tmp_path: Path) -> None:
    bad = tmp_path / "thin.json5"
    bad.write_text('[{rules: [{key_expr: "*/scan", freq: "often"}]}]')
    with pytest.raises(BusConfigError, match=f"downsampling file {bad}"):
        load_rules(bad)
    with pytest.raises(BusConfigError, match="cannot read"):
        load_rules(tmp_path / "missing.json5")
