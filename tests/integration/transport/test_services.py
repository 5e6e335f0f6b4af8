"""Request/reply services over a real router: answers, error replies, absence."""

from __future__ import annotations

import asyncio

import pytest

from aiobt.msgs import (
    ClearCostmapExceptRegion,
    ClearCostmapResponse,
    IsPathValid,
    Path,
    PoseStamped,
)
from aiobt.transport import Bus, BusSettings, ServiceError, ServiceUnavailable, open_bus

pytestmark = pytest.mark.integration
CLEAR = "local_costmap/clear_except_local_costmap"


async def test_call_and_answer(bus: Bus, bus_settings: BusSettings) -> None:
    seen: list[float] = []

    async def clear(request: ClearCostmapExceptRegion.Request) -> ClearCostmapResponse:
        seen.append(request.reset_distance)
        return ClearCostmapResponse(success=True, message=f"kept {request.reset_distance} m")

    bus.serve(CLEAR, ClearCostmapExceptRegion.Request, ClearCostmapResponse, clear)
    async with open_bus(bus_settings) as client:
        request = ClearCostmapExceptRegion.Request(reset_distance=2.5)
        response = await client.call(CLEAR, request, ClearCostmapResponse, timeout=5.0)
    assert response == ClearCostmapResponse(success=True, message="kept 2.5 m")
    assert seen == [2.5]


async def test_bad_request_gets_an_error_naming_the_field(
    bus: Bus, bus_settings: BusSettings
) -> None:
    bus.serve(
        "is_path_valid",
        IsPathValid.Request,
        IsPathValid.Response,
        lambda request: IsPathValid.Response(is_valid=True),
    )
    bad = IsPathValid.Request.model_construct(
        path=Path(), max_cost=999, consider_unknown_as_obstacle=False
    )
    async with open_bus(bus_settings) as client:
        with pytest.raises(ServiceError, match=r"bad request: .*'max_cost'") as caught:
            await client.call("is_path_valid", bad, IsPathValid.Response, timeout=5.0)
    assert not isinstance(caught.value, ServiceUnavailable)


async def test_handler_failure_is_an_error_reply_and_server_keeps_running(
    bus: Bus, bus_settings: BusSettings
) -> None:
    calls = 0

    def flaky(request: IsPathValid.Request) -> IsPathValid.Response:
        nonlocal calls
        calls += 1
        if calls == 1:
            raise RuntimeError("costmap not ready")
        return IsPathValid.Response(is_valid=True)

    bus.serve("is_path_valid", IsPathValid.Request, IsPathValid.Response, flaky)
    async with open_bus(bus_settings) as client:
        request = IsPathValid.Request(path=Path())
        with pytest.raises(ServiceError, match="costmap not ready"):
            await client.call("is_path_valid", request, IsPathValid.Response, timeout=5.0)
        response = await client.call("is_path_valid", request, IsPathValid.Response, timeout=5.0)
    assert response.is_valid


async def test_absent_service_fails_fast(bus: Bus) -> None:
    loop = asyncio.get_running_loop()
    start = loop.time()
    with pytest.raises(ServiceUnavailable, match=r"no server within 0\.3 s"):
        await bus.call(
            "nobody_here", IsPathValid.Request(path=Path()), IsPathValid.Response, timeout=0.3
        )
    assert loop.time() - start < 1.0


async def test_garbage_and_oversized_requests_get_error_replies(
    bus: Bus, bus_settings: BusSettings
) -> None:
    small = BusSettings(connect=bus_settings.connect, namespace=bus.namespace, max_payload=300)
    async with open_bus(small) as server_bus:
        server_bus.serve(
            "is_path_valid",
            IsPathValid.Request,
            IsPathValid.Response,
            lambda request: IsPathValid.Response(is_valid=len(request.path.poses) < 5),
        )
        await bus.presence(bus.keys.service("is_path_valid")).wait(5.0)
        await asyncio.sleep(0.2)
        key = bus.keys.service("is_path_valid")

        def raw_call(payload: bytes) -> list[str]:
            return [
                reply.err.payload.to_string() if reply.err else "ok"
                for reply in bus.session.get(key, payload=payload, timeout=5.0)
            ]

        [garbage] = await asyncio.to_thread(raw_call, b"{nope")
        assert garbage.startswith("bad request:")
        assert "field '<payload>'" in garbage
        long_path = Path(poses=[PoseStamped.from_xy_yaw(i, 0) for i in range(10)])
        request = IsPathValid.Request(path=long_path)
        [oversized] = await asyncio.to_thread(raw_call, request.to_json())
        assert "exceeds the limit of 300 bytes" in oversized
        response = await bus.call(
            "is_path_valid", IsPathValid.Request(path=Path()), IsPathValid.Response, timeout=5.0
        )
    assert response.is_valid  # the server kept serving
