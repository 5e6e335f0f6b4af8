"""wire_validator: the models' results and errors, without their marked validators on
pydantic's path (no Zenoh)."""

from __future__ import annotations

import copy
import json
from typing import Any, Self

import pytest
from pydantic import ValidationError, model_validator

import aiobt.msgs as msgs
from aiobt.msgs import Msg, PoseStamped, wire_validator
from aiobt.msgs._wire import identity_on_canonical, in_place_check

from .test_models import SAMPLES

UNIT_OFF = [
    {"x": 0, "y": 0, "z": 0, "w": 2},  # refused
    {"x": 0, "y": 0, "z": 0, "w": 1.005},  # normalised
    {"x": 0, "y": 0, "z": 0.1, "w": 0.995},  # normalised (a rounding away from unit)
]


def outcome(validate: Any, payload: str | bytes) -> tuple[str, Any]:
    try:
        return "ok", validate(payload).model_dump()
    except ValidationError as exc:
        return "error", exc.errors(include_url=False)


def same_outcome(model: type[Msg], payload: str | bytes) -> None:
    ours = outcome(wire_validator(model), payload)
    theirs = outcome(model.__pydantic_validator__.validate_json, payload)
    assert repr(ours) == repr(theirs)  # repr: exact floats, error types, locations, messages


def quaternion_paths(node: Any, path: tuple[Any, ...] = ()) -> list[tuple[Any, ...]]:
    if isinstance(node, dict):
        found = [path] if set(node) == {"x", "y", "z", "w"} else []
        for key, value in node.items():
            found += quaternion_paths(value, (*path, key))
        return found
    if isinstance(node, list):
        return [p for i, value in enumerate(node) for p in quaternion_paths(value, (*path, i))]
    return []


def replaced(data: Any, path: tuple[Any, ...], value: Any) -> Any:
    if not path:
        return value
    data = copy.deepcopy(data)
    node = data
    for step in path[:-1]:
        node = node[step]
    node[path[-1]] = value
    return data


@pytest.mark.parametrize("message", SAMPLES, ids=lambda m: type(m).__name__)
def test_every_model_decodes_and_refuses_as_the_model_does(message: Msg) -> None:
    data = json.loads(message.to_json())
    same_outcome(type(message), json.dumps(data))
    for path in quaternion_paths(data):  # each quaternion, wherever it sits (lists too)
        for value in UNIT_OFF:
            same_outcome(type(message), json.dumps(replaced(data, path, value)))
    same_outcome(type(message), b'{"unknown": 1}')
    same_outcome(type(message), b"[1, 2")


@pytest.mark.parametrize(
    ("model", "payload"),
    [
        (PoseStamped, b'{"x": 1.5, "y": -2.0, "yaw": 0.5}'),
        (PoseStamped, b'{"x": 1, "y": 2, "frame_id": "odom", "stamp": 3}'),
        (PoseStamped, b'{"x": 1, "y": NaN}'),
        (PoseStamped, b'{"x": 1, "y": 2, "pose": {}}'),
        (msgs.Goals, b'[{"x": 1, "y": 2}, {"x": 3, "y": 4, "yaw": 1}]'),
        (msgs.Goals, b'[{"x": 1}]'),
        (PoseStamped, b'{"y": 2, "yaw": 0.5}'),
        (PoseStamped, b'{"header": {}, "yaw": 0.5}'),
        (msgs.Goals, b'[{"yaw": 1}]'),
        (msgs.Path, b'{"poses": [{"x": 1, "y": 2}]}'),
        (msgs.NavigateToPose.Goal, b'{"pose": {"x": 1, "y": 2, "yaw": 0.1}}'),
        (msgs.NavigateThroughPoses.Goal, b'{"poses": [{"x": 1, "y": 2}]}'),
    ],
)
def test_short_forms_still_mean_what_the_model_says(model: type[Msg], payload: bytes) -> None:
    same_outcome(model, payload)


CALLS: list[str] = []


class _Part(Msg):
    v: float = 0.0

    @model_validator(mode="after")
    @in_place_check
    def _check(self) -> Self:
        CALLS.append("check")
        if self.v < 0:
            raise ValueError("v must not be negative")
        self.__dict__["v"] = round(self.v, 3)  # normalises in place
        return self


class _Whole(Msg):
    one: _Part = _Part()
    many: list[_Part] = []
    maybe: _Part | None = None

    @model_validator(mode="before")
    @classmethod
    @identity_on_canonical
    def _bare(cls, data: Any) -> Any:
        CALLS.append("adapter")
        return {"many": [{"v": v} for v in data]} if isinstance(data, list) else data


class _Watched(_Whole):
    """Another Python validator sees the parts: their checks must stay in pydantic."""

    @model_validator(mode="after")
    def _sum(self) -> Self:
        CALLS.append(f"sum {self.one.v}")
        return self


def test_marked_validators_run_once_per_instance_and_adapters_not_on_the_long_form() -> None:
    payload = b'{"one": {"v": 1.23456}, "many": [{"v": 2}, {"v": 3}], "maybe": {"v": 4}}'
    CALLS.clear()
    whole = wire_validator(_Whole)(payload)
    assert CALLS == ["check"] * 4
    assert whole.one.v == 1.235
    assert whole == _Whole.model_validate_json(payload)

    CALLS.clear()
    assert wire_validator(_Whole)(b'{"one": {"v": 1}}').maybe is None
    assert CALLS == ["check"]


def test_a_refused_or_short_input_is_decided_by_the_model() -> None:
    validate = wire_validator(_Whole)
    CALLS.clear()
    assert validate(b"[1, 2]") == _Whole(many=[_Part(v=1), _Part(v=2)])
    assert "adapter" in CALLS

    with pytest.raises(ValidationError) as ours:
        validate(b'{"many": [{"v": 1}, {"v": -1}]}')
    with pytest.raises(ValidationError) as theirs:
        _Whole.model_validate_json(b'{"many": [{"v": 1}, {"v": -1}]}')
    errors = [caught.value.errors(include_url=False) for caught in (ours, theirs)]
    assert repr(errors[0]) == repr(errors[1])
    assert ours.value.errors()[0]["loc"] == ("many", 1)


def test_checks_stay_in_pydantic_when_other_python_validators_could_see_the_instances() -> None:
    CALLS.clear()
    watched = wire_validator(_Watched)(b'{"one": {"v": 1.23456}}')
    assert CALLS == ["check", "sum 1.235"]  # the check ran before the other validator
    assert watched == _Watched.model_validate_json(b'{"one": {"v": 1.23456}}')


def test_models_without_marked_validators_keep_their_own_validator() -> None:
    assert wire_validator(msgs.Twist) == msgs.Twist.__pydantic_validator__.validate_json
    assert wire_validator(PoseStamped) != PoseStamped.__pydantic_validator__.validate_json
    assert all(cls.__pydantic_complete__ for cls in (PoseStamped, msgs.Pose, msgs.Quaternion))
