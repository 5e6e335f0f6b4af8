"""System settings: defaults, flags over the file, and errors that name the key."""

from __future__ import annotations

from pathlib import Path

import pytest

from aiobt.cli.main import _full_parser
from aiobt.system import ConfigError, load_config
from aiobt.system.commands import router_command, service_command


def _write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "system.yaml"
    path.write_text(text)
    return path


def test_defaults_run_every_service_on_wall_time() -> None:
    config = load_config(None)
    assert config.enabled() == ["robot", "localization", "planner", "controller", "behaviors",
                                "velocity_smoother", "collision_monitor", "navigator"]  # fmt: skip
    assert config.namespace == "robot"
    assert not config.uses_sim_time
    assert service_command("planner", config) == [
        "planner", "--connect", "tcp/127.0.0.1:7447", "--namespace", "robot",
    ]  # fmt: skip


def test_a_speed_up_puts_every_service_but_the_robot_on_sim_time(tmp_path: Path) -> None:
    path = _write(
        tmp_path, "speed: 5\nworld: small\nservices:\n  planner: {args: [--downsample, 1]}\n"
    )
    config = load_config(path)
    assert config.uses_sim_time
    assert service_command("robot", config)[-4:] == ["--world", "small", "--speed", "5"]
    assert "--sim-time" not in service_command("robot", config)
    planner = service_command("planner", config)
    assert planner[-3:] == ["--sim-time", "--downsample", "1"]


def test_flags_override_the_file_and_keep_the_rest_of_a_section(tmp_path: Path) -> None:
    path = _write(tmp_path, "namespace: a\nrouter: {listen: 'tcp/127.0.0.1:9000', start: false}\n")
    config = load_config(path, {"namespace": "b", "router": {"listen": "tcp/127.0.0.1:9001"}})
    assert config.namespace == "b"
    assert config.router.listen == "tcp/127.0.0.1:9001"
    assert config.router.start is False


@pytest.mark.parametrize(
    ("text", "named"),
    [
        ("namespce: a\n", "unknown key namespce"),
        ("router: {lisen: x}\n", "unknown key router.lisen"),
        ("services: {planer: {}}\n", "unknown service services.planer"),
        ("services: {robot: {enable: true}}\n", "unknown key services.robot.enable"),
        ("speed: fast\n", "speed must be a number, got str 'fast'"),
        ("speed: 0\n", "speed must be a finite number > 0"),
        ("sim_time: 1\n", "sim_time must be bool, got int"),
        ("services: {robot: {enabled: yes please}}\n", "services.robot.enabled must be bool"),
        ("services: {robot: {args: --gui}}\n", "services.robot.args must be a list"),
        ("router: {args: [[1]]}\n", "router.args must be a list of strings"),
        ("restart: {max_restarts: 1.5}\n", "restart.max_restarts must be int"),
        ("router: {listen: 7447}\n", "router.listen must be str"),
        ("router: {listen: localhost}\n", "router.listen must be a Zenoh endpoint"),
        ("namespace: 'a b'\n", "namespace 'a b' is not a valid key"),
        ("- a\n- b\n", "expected a mapping of settings, got list"),
        ("router: [1]\n", "router must be a mapping, got list"),
        ("speed: [\n", "not valid YAML"),
    ],
)
def test_a_bad_setting_is_an_error_naming_the_file_and_key(
    tmp_path: Path, text: str, named: str
) -> None:
    path = _write(tmp_path, text)
    with pytest.raises(ConfigError, match=r"system\.yaml: ") as caught:
        load_config(path)
    assert named in str(caught.value)


def test_a_missing_file_is_named(tmp_path: Path) -> None:
    with pytest.raises(ConfigError, match=r"nope\.yaml: cannot read"):
        load_config(tmp_path / "nope.yaml")


def test_the_router_it_starts_takes_extra_flags(tmp_path: Path) -> None:
    path = _write(tmp_path, "router: {args: [--realtime-priority, 55]}\n")
    config = load_config(path)
    assert router_command(config) == [
        "router", "--listen", "tcp/127.0.0.1:7447", "--realtime-priority", "55",
    ]  # fmt: skip
    argv = router_command(config)
    assert _full_parser(argv).parse_args(argv).realtime_priority == 55  # a flag it knows
    assert router_command(load_config(_write(tmp_path, "speed: 2\n")))[3:] == []
