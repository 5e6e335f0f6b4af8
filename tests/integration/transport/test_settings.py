"""Bus settings, flags and config files, key layout, and the router command's errors."""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path

import pytest
import zenoh

from aiobt.cli import router
from aiobt.testing.bus import free_endpoint
from aiobt.transport import DEFAULT_ROUTER, BusConfigError, BusSettings, Keys, add_bus_arguments
from aiobt.transport.settings import listen_endpoints


def parse(*argv: str) -> BusSettings:
    parser = argparse.ArgumentParser()
    add_bus_arguments(parser)
    return BusSettings.from_args(parser.parse_args(list(argv)))


def test_flags_become_settings() -> None:
    settings = parse(
        "--connect",
        "tcp/10.0.0.1:7447",
        "-e",
        "tcp/10.0.0.2:7447",
        "--namespace",
        "robot2",
        "--lease-ms",
        "500",
        "--mode",
        "peer",
    )
    assert settings.connect == ("tcp/10.0.0.1:7447", "tcp/10.0.0.2:7447")
    assert (settings.namespace, settings.lease_ms, settings.mode) == ("robot2", 500, "peer")


def test_defaults_are_a_local_client_with_a_short_lease(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("ZENOH_CONFIG", raising=False)
    config = parse().zenoh_config()
    assert json.loads(config.get_json("mode")) == "client"
    assert json.loads(config.get_json("connect/endpoints")) == ["tcp/127.0.0.1:7447"]
    assert json.loads(config.get_json("transport/link/tx/lease")) == 1000
    assert json.loads(config.get_json("scouting/multicast/enabled")) is False


def test_config_file_from_zenoh_config_env_and_flags_on_top(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    path = tmp_path / "zenoh.json5"
    path.write_text('{mode: "peer", listen: {endpoints: ["tcp/127.0.0.1:0"]}}')
    monkeypatch.setenv("ZENOH_CONFIG", str(path))
    from_file = parse().zenoh_config()
    assert json.loads(from_file.get_json("mode")) == "peer"
    overridden = parse("--mode", "client", "--connect", "tcp/127.0.0.1:9").zenoh_config()
    assert json.loads(overridden.get_json("mode")) == "client"
    assert json.loads(overridden.get_json("connect/endpoints")) == ["tcp/127.0.0.1:9"]


def test_what_a_config_file_leaves_unset_gets_our_defaults_not_zenohs(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.delenv("ZENOH_CONFIG", raising=False)

    def config_of(text: str, *argv: str) -> dict[str, object]:
        path = tmp_path / "zenoh.json5"
        path.write_text(text)
        config = parse("--config", str(path), *argv).zenoh_config()
        keys = ("mode", "connect/endpoints", "scouting/multicast/enabled")
        return {key: json.loads(config.get_json(key)) for key in keys}

    # only credentials (the documented client.json5): a client of the default router,
    # no multicast; Zenoh alone would make a scouting peer that runs unconnected
    credentials = '{transport: {auth: {usrpwd: {user: "robot", password: "s3cret"}}}}'
    assert config_of(credentials) == {
        "mode": "client",
        "connect/endpoints": ["tcp/127.0.0.1:7447"],
        "scouting/multicast/enabled": False,
    }
    # what the file sets is kept, and flags still go on top
    chosen = (
        '{mode: "peer", connect: {endpoints: ["tcp/127.0.0.1:9"]},'
        " scouting: {multicast: {enabled: true}}}"
    )
    assert config_of(chosen) == {
        "mode": "peer",
        "connect/endpoints": ["tcp/127.0.0.1:9"],
        "scouting/multicast/enabled": True,
    }
    assert config_of('{connect: {endpoints: ["tcp/127.0.0.1:9"]}}')["connect/endpoints"] == [
        "tcp/127.0.0.1:9"
    ]
    flagged = config_of(chosen, "--mode", "client", "--connect", "tcp/127.0.0.1:8")
    assert (flagged["mode"], flagged["connect/endpoints"]) == ("client", ["tcp/127.0.0.1:8"])


def test_peers_told_where_to_connect_fail_when_they_cannot_and_handshakes_are_short(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.delenv("ZENOH_CONFIG", raising=False)

    def get(config: zenoh.Config, key: str) -> object:
        return json.loads(config.get_json(key))

    peer = parse("--mode", "peer", "--connect", "tcp/127.0.0.1:9").zenoh_config()
    assert (get(peer, "connect/exit_on_failure"), get(peer, "connect/timeout_ms")) == (True, 0)
    lone_peer = parse("--mode", "peer").zenoh_config()  # nowhere to connect: may stand alone
    assert get(lone_peer, "connect/exit_on_failure") is None
    assert get(parse().zenoh_config(), "transport/unicast/open_timeout") == 2000
    # a file's own choices stay
    path = tmp_path / "zenoh.json5"
    path.write_text(
        '{mode: "peer", connect: {endpoints: ["tcp/127.0.0.1:9"], exit_on_failure: false},'
        " transport: {unicast: {open_timeout: 5000}}}"
    )
    chosen = parse("--config", str(path)).zenoh_config()
    assert get(chosen, "connect/exit_on_failure") is False
    assert get(chosen, "transport/unicast/open_timeout") == 5000
    # per-mode endpoints: a client the file gives none still gets the default router
    path.write_text('{connect: {endpoints: {router: ["tcp/127.0.0.1:9"]}}}')
    per_mode = parse("--config", str(path)).zenoh_config()
    assert get(per_mode, "connect/endpoints") == ["tcp/127.0.0.1:7447"]
    # a client that scouts for its router gets no default endpoint
    path.write_text("{scouting: {multicast: {enabled: true}}}")
    scouting = parse("--config", str(path)).zenoh_config()
    assert (get(scouting, "mode"), get(scouting, "connect/endpoints")) == ("client", [])


def test_bad_settings_name_the_flag_or_file(tmp_path: Path) -> None:
    with pytest.raises(BusConfigError, match="--namespace"):
        BusSettings(namespace="robot/*")
    with pytest.raises(BusConfigError, match="--lease-ms"):
        BusSettings(lease_ms=5)
    with pytest.raises(BusConfigError, match="no such file"):
        BusSettings(config_file=str(tmp_path / "missing.json5")).zenoh_config()
    broken = tmp_path / "broken.json5"
    broken.write_text("{mode: ")
    with pytest.raises(BusConfigError, match=r"broken\.json5") as bad_file:
        BusSettings(config_file=str(broken)).zenoh_config()
    with pytest.raises(BusConfigError, match="connect/endpoints") as bad_field:
        BusSettings(connect=("not an endpoint",)).zenoh_config()
    for error in (bad_file, bad_field):  # no Rust source places in what users read
        assert ".rs:" not in str(error.value)


def test_router_listens_on_loopback_unless_told_or_configured(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    def router_listens(*argv: str) -> list[str]:
        parser = argparse.ArgumentParser()
        router.add_arguments(parser)
        settings = router.settings_from_args(parser.parse_args(list(argv)))
        assert settings.mode == "router"
        return listen_endpoints(settings.zenoh_config())

    auth_only = tmp_path / "auth.json5"  # turns on authentication, names no endpoint
    auth_only.write_text('{transport: {auth: {usrpwd: {dictionary_file: "users.txt"}}}}')
    wide = tmp_path / "wide.json5"
    wide.write_text('{listen: {endpoints: ["tcp/0.0.0.0:7447"]}}')
    monkeypatch.delenv("ZENOH_CONFIG", raising=False)
    assert router_listens() == [DEFAULT_ROUTER]
    assert router_listens("-l", "tcp/127.0.0.1:9") == ["tcp/127.0.0.1:9"]
    assert router_listens("--config", str(auth_only)) == [DEFAULT_ROUTER]
    assert router_listens("--config", str(wide)) == ["tcp/0.0.0.0:7447"]  # the file says where
    assert router_listens("--config", str(wide), "-l", "tcp/127.0.0.1:9") == ["tcp/127.0.0.1:9"]
    monkeypatch.setenv("ZENOH_CONFIG", str(auth_only))
    assert router_listens() == [DEFAULT_ROUTER]


def test_a_peer_listens_on_loopback_unless_told(tmp_path: Path) -> None:
    assert listen_endpoints(BusSettings(mode="peer").zenoh_config()) == ["tcp/127.0.0.1:0"]
    told = BusSettings(mode="peer", listen=("tcp/0.0.0.0:0",))
    assert listen_endpoints(told.zenoh_config()) == ["tcp/0.0.0.0:0"]
    assert listen_endpoints(BusSettings().zenoh_config()) == []  # a client listens nowhere
    per_mode = tmp_path / "peer.json5"
    per_mode.write_text('{mode: "peer", listen: {endpoints: {peer: ["tcp/127.0.0.1:7999"]}}}')
    assert listen_endpoints(BusSettings(config_file=str(per_mode)).zenoh_config()) == [
        "tcp/127.0.0.1:7999"
    ]


def test_key_layout() -> None:
    keys = Keys("robot")
    assert keys.topic("odom") == "robot/odom"
    assert keys.service("global_costmap/clear_entirely_global_costmap") == (
        "robot/srv/global_costmap/clear_entirely_global_costmap"
    )
    action = keys.action("follow_path")
    assert action.goal_selector("abc") == "robot/action/follow_path/goal?id=abc"
    assert action.status("abc") == "robot/action/follow_path/status/abc"
    assert action.result("abc") == "robot/action/follow_path/result/abc"
    assert action.feedback("abc") == "robot/action/follow_path/feedback/abc"
    assert (action.goal, action.cancel, action.alive) == (
        "robot/action/follow_path/goal",
        "robot/action/follow_path/cancel",
        "robot/action/follow_path",
    )
    assert (action.any_status, action.any_feedback, action.any_result) == (
        "robot/action/follow_path/status/*",
        "robot/action/follow_path/feedback/*",
        "robot/action/follow_path/result/*",
    )
    with pytest.raises(ValueError, match="topic"):
        keys.topic("a//b")


@pytest.mark.integration
def test_router_command_reports_a_bad_config_file(tmp_path: Path) -> None:
    broken = tmp_path / "router.json5"
    broken.write_text("{listen: ")
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "aiobt.cli.router",
            "--config",
            str(broken),
            "--listen",
            free_endpoint(),
        ],
        capture_output=True,
        text=True,
        timeout=30,
    )
    assert done.returncode == 2
    assert "router.json5" in done.stderr
