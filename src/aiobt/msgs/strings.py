"""Nav2's ``;``-separated string forms (``nav2_behavior_tree/bt_utils.hpp``), both ways.

So these types work as BT port literals in XML:

- Point ``x;y;z``; Quaternion ``x;y;z;w``
- PoseStamped ``stamp_ns;frame_id;x;y;z;qx;qy;qz;qw`` (Nav2's 9 fields); also
  accepted: ``x;y;z;qx;qy;qz;qw`` and ``x;y;yaw`` in frame ``map``
- Goals (``nav_msgs::msg::Goals``): ``stamp_ns;frame_id`` followed by 9 fields
  per pose; also accepted: 9 fields per pose alone (Nav2's PoseStampedArray and
  ``std::vector<PoseStamped>``), in the default header
- Path ``stamp_ns;frame_id`` followed by 9 fields per pose

Stamps are integer nanoseconds in the string, float seconds in the models:
written exactly (the nearest nanosecond) and read with one rounding, so a stamp
of whole nanoseconds reads back equal. A ``frame_id`` holding ``;`` or
surrounding blanks cannot be read back, so writing one is a :class:`MessageError`
(a ``ValueError``) naming the field.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from fractions import Fraction

from pydantic import ValidationError

from aiobt.core.convert import register_converter
from aiobt.msgs._base import MessageError
from aiobt.msgs.geometry import Header, Point, PoseStamped, Quaternion
from aiobt.msgs.nav import Goals, Path

_POSE_FIELDS = 9
_NS_PER_S = 1_000_000_000


def _split(text: str) -> list[str]:
    return [part.strip() for part in text.strip().split(";")] if text.strip() else []


def _floats(parts: Sequence[str], names: Sequence[str], what: str) -> list[float]:
    values: list[float] = []
    for part, name in zip(parts, names, strict=True):
        try:
            values.append(float(part))
        except ValueError:
            raise MessageError(what, name, f"'{part}' is not a number") from None
        if not math.isfinite(values[-1]):
            raise MessageError(what, name, f"'{part}' is not a finite number")
    return values


def _stamp(part: str, what: str) -> float:
    try:
        nanoseconds = int(part)
    except ValueError:
        raise MessageError(what, "header.stamp", f"'{part}' is not integer nanoseconds") from None
    if nanoseconds < 0:  # here, not in Header's validation: a Path's header is built directly
        raise MessageError(what, "header.stamp", f"'{part}' is negative")
    try:
        return nanoseconds / _NS_PER_S  # one rounding (``* 1e-9`` gives 0.30000000000000004)
    except OverflowError:
        raise MessageError(what, "header.stamp", f"'{part[:20]}...' is too large") from None


def point_from_string(text: str) -> Point:
    parts = _split(text)
    if len(parts) != 3:
        raise MessageError("Point", "<string>", f"expected 'x;y;z', got {len(parts)} fields")
    x, y, z = _floats(parts, "xyz", "Point")
    return Point(x=x, y=y, z=z)


def quaternion_from_string(text: str) -> Quaternion:
    parts = _split(text)
    if len(parts) != 4:
        raise MessageError("Quaternion", "<string>", f"expected 'x;y;z;w', got {len(parts)} fields")
    x, y, z, w = _floats(parts, "xyzw", "Quaternion")
    try:
        return Quaternion(x=x, y=y, z=z, w=w)
    except ValidationError as exc:
        raise MessageError.from_validation(Quaternion, exc) from None


_NAMES_9 = (
    *(f"pose.position.{axis}" for axis in "xyz"),
    *(f"pose.orientation.{axis}" for axis in "xyzw"),
)


def _pose_from_parts(parts: Sequence[str], what: str) -> PoseStamped:
    if len(parts) == 3:
        x, y, yaw = _floats(parts, ("x", "y", "yaw"), what)
        return PoseStamped.from_xy_yaw(x, y, yaw)
    if len(parts) == 7:
        stamp, frame, numbers = 0.0, "map", parts
    elif len(parts) == _POSE_FIELDS:
        stamp, frame, numbers = _stamp(parts[0], what), parts[1], parts[2:]
    else:
        raise MessageError(what, "<string>", f"expected 9, 7 or 3 fields, got {len(parts)}")
    x, y, z, qx, qy, qz, qw = _floats(numbers, _NAMES_9, what)
    data = {
        "header": {"stamp": stamp, "frame_id": frame},
        "pose": {
            "position": {"x": x, "y": y, "z": z},
            "orientation": {"x": qx, "y": qy, "z": qz, "w": qw},
        },
    }
    try:
        return PoseStamped.model_validate(data)
    except ValidationError as exc:
        raise MessageError.from_validation(PoseStamped, exc) from None


def pose_stamped_from_string(text: str) -> PoseStamped:
    return _pose_from_parts(_split(text), "PoseStamped")


def goals_from_string(text: str) -> Goals:
    parts = _split(text)
    if len(parts) % _POSE_FIELDS == 0:
        return Goals(goals=_poses(parts, "Goals"))
    if len(parts) % _POSE_FIELDS != 2:
        raise MessageError(
            "Goals",
            "<string>",
            f"expected 'stamp;frame' then 9 fields per pose, or 9 fields per pose, "
            f"got {len(parts)}",
        )
    return Goals(header=_header(parts, "Goals"), goals=_poses(parts[2:], "Goals"))


def path_from_string(text: str) -> Path:
    parts = _split(text)
    if len(parts) < 2 or (len(parts) - 2) % _POSE_FIELDS:
        raise MessageError(
            "Path", "<string>", f"expected 'stamp;frame' then 9 fields per pose, got {len(parts)}"
        )
    return Path(header=_header(parts, "Path"), poses=_poses(parts[2:], "Path"))


def _header(parts: Sequence[str], what: str) -> Header:
    return Header(stamp=_stamp(parts[0], what), frame_id=parts[1])


def _poses(parts: Sequence[str], what: str) -> list[PoseStamped]:
    """Poses of 9 fields each (the caller checked the count)."""
    return [
        _pose_from_parts(parts[i : i + _POSE_FIELDS], what)
        for i in range(0, len(parts), _POSE_FIELDS)
    ]


def _num(value: float) -> str:
    return repr(float(value))


def _header_text(header: Header, what: str, field: str = "header") -> str:
    """``stamp_ns;frame_id``, or a MessageError naming a frame_id that cannot be read back."""
    frame = header.frame_id
    if ";" in frame or frame != frame.strip():
        raise MessageError(
            what,
            f"{field}.frame_id",
            f"{frame!r} cannot be written in a ';'-separated string "
            "(it holds ';' or surrounding blanks)",
        )
    nanoseconds = round(Fraction(header.stamp) * _NS_PER_S)  # exact: no float rounding
    return f"{nanoseconds};{frame}"


def point_to_string(point: Point) -> str:
    return ";".join(_num(v) for v in (point.x, point.y, point.z))


def quaternion_to_string(q: Quaternion) -> str:
    return ";".join(_num(v) for v in (q.x, q.y, q.z, q.w))


def pose_stamped_to_string(pose: PoseStamped) -> str:
    return _pose_text(pose, "PoseStamped")


def _pose_text(pose: PoseStamped, what: str, field: str = "header") -> str:
    body = f"{point_to_string(pose.pose.position)};{quaternion_to_string(pose.pose.orientation)}"
    return f"{_header_text(pose.header, what, field)};{body}"


def goals_to_string(goals: Goals) -> str:
    """Nav2's ``nav_msgs::msg::Goals`` form: the header, then 9 fields per pose."""
    return _poses_text(goals.header, goals.goals, "Goals", "goals")


def path_to_string(path: Path) -> str:
    return _poses_text(path.header, path.poses, "Path", "poses")


def _poses_text(header: Header, poses: Sequence[PoseStamped], what: str, field: str) -> str:
    texts = (_pose_text(p, what, f"{field}.{i}.header") for i, p in enumerate(poses))
    return ";".join([_header_text(header, what), *texts])


# the string forms as port literals: convert(text, PoseStamped) and to_text(pose)
register_converter(Point, point_from_string, formatter=point_to_string)
register_converter(Quaternion, quaternion_from_string, formatter=quaternion_to_string)
register_converter(PoseStamped, pose_stamped_from_string, formatter=pose_stamped_to_string)
register_converter(Goals, goals_from_string, formatter=goals_to_string)
register_converter(Path, path_from_string, formatter=path_to_string)
