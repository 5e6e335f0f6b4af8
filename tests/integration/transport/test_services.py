"""Request/reply services over a real router: answers, error replies, absence."""

from __future__ import annotations

import asyncio
import logging

import pytest

from aiobt.msgs import (
    ClearCostmapExceptRegion,
    ClearCostmapResponse,
    ClearEntireCostmap,
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
        with pytest.raises(ServiceError) as failed:
            await client.call("is_path_valid", request, IsPathValid.Response, timeout=5.0)
        key = client.keys.service("is_path_valid")
        assert str(failed.value) == f"{key}: handler failed: RuntimeError: costmap not ready"
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


async def test_a_call_waits_through_a_server_that_is_announced_but_not_yet_routed(
    bus: Bus, bus_settings: BusSettings
) -> None:
    """A restarting server: its liveliness is seen before its queryable answers (or the
    old server's token lingers). The call is sent again until the timeout."""
    liveliness = bus.session.liveliness()
    stale = [  # announced, nothing answers
        liveliness.declare_token(bus.keys.service(name)) for name in ("is_path_valid", "stale")
    ]
    try:
        async with open_bus(bus_settings) as client:
            request = IsPathValid.Request(path=Path())
            call = asyncio.create_task(
                client.call("is_path_valid", request, IsPathValid.Response, timeout=5.0)
            )
            await asyncio.sleep(0.3)
            assert not call.done()  # gets that nobody answered are sent again
            bus.serve(
                "is_path_valid",
                IsPathValid.Request,
                IsPathValid.Response,
                lambda request: IsPathValid.Response(is_valid=True),
            )
            assert (await asyncio.wait_for(call, 5.0)).is_valid
            with pytest.raises(ServiceUnavailable, match=r"no service answered within 0\.3 s"):
                await client.call("stale", request, IsPathValid.Response, timeout=0.3)
    finally:
        for token in stale:
            token.undeclare()  # type: ignore[no-untyped-call]


async def test_a_closing_server_answers_calls_in_progress(bus_settings: BusSettings) -> None:
    started = asyncio.Event()

    async def slow(request: IsPathValid.Request) -> IsPathValid.Response:
        started.set()
        await asyncio.sleep(30.0)
        return IsPathValid.Response(is_valid=True)

    async with open_bus(bus_settings) as client:
        async with open_bus(bus_settings) as server_bus:
            server_bus.serve("slow", IsPathValid.Request, IsPathValid.Response, slow)
            call = asyncio.create_task(
                client.call("slow", IsPathValid.Request(path=Path()), IsPathValid.Response, 5.0)
            )
            await asyncio.wait_for(started.wait(), 5.0)
        with pytest.raises(ServiceError, match="the service is shutting down") as failed:
            await asyncio.wait_for(call, 5.0)
        assert not isinstance(failed.value, ServiceUnavailable)


async def test_closing_a_server_or_publisher_twice_logs_nothing(
    bus_settings: BusSettings, caplog: pytest.LogCaptureFixture
) -> None:
    async with open_bus(bus_settings) as bus:
        server = bus.serve(
            "twice",
            IsPathValid.Request,
            IsPathValid.Response,
            lambda request: IsPathValid.Response(is_valid=True),
        )
        publisher = bus.publisher("twice", PoseStamped)
        server.close()
        publisher.close()
    # ... and once more each when the bus closed
    assert [r.getMessage() for r in caplog.records if r.levelno >= logging.WARNING] == []


async def test_a_wildcard_get_is_answered_on_the_service_key(bus: Bus) -> None:
    bus.serve("clear", ClearEntireCostmap.Request, ClearCostmapResponse, _cleared)
    key = bus.keys.service("clear")
    assert await bus.presence(key).wait(5.0)

    def get_all() -> list[str]:
        wildcard = f"{bus.namespace}/srv/*"
        replies = bus.session.get(wildcard, payload=b"{}", timeout=5.0)
        return [str(r.ok.key_expr) if r.ok else str(r.err) for r in replies]

    assert await asyncio.to_thread(get_all) == [key]


def _cleared(request: ClearEntireCostmap.Request) -> ClearCostmapResponse:
    return ClearCostmapResponse(success=True)


async def test_a_handler_failing_on_every_call_logs_one_traceback(
    local_bus: Bus, caplog: pytest.LogCaptureFixture
) -> None:
    def broken(request: IsPathValid.Request) -> IsPathValid.Response:
        raise RuntimeError(f"cannot check {len(request.path.poses)} poses")

    server = local_bus.serve("is_path_valid", IsPathValid.Request, IsPathValid.Response, broken)
    with caplog.at_level(logging.ERROR, logger="aiobt.transport"):
        for _ in range(20):
            with pytest.raises(ServiceError, match="handler failed: RuntimeError"):
                await local_bus.call(
                    "is_path_valid", IsPathValid.Request(path=Path()), IsPathValid.Response, 5.0
                )
        server.close()
    errors = [r for r in caplog.records if r.levelno >= logging.ERROR]
    assert len(errors) == 2, [r.getMessage() for r in errors]
    assert errors[0].exc_info is not None
    assert "service handler failed" in errors[0].getMessage()
    assert "failed 19 more times" in errors[1].getMessage()  # said when it closed
