"""Latest value per stream, per client: a slow reader never grows a backlog."""

from __future__ import annotations

import json

import pytest

from aiobt.web.coalesce import Hub, Latest, Outbox


def test_latest_keeps_the_newest_value_per_stream_until_drained():
    latest: Latest[int] = Latest()
    for value in range(500):
        latest.set("pose", value)
    latest.set("scan", -1)
    assert latest.drain() == {"pose": 499, "scan": -1}
    assert latest.replaced == 499
    assert latest.drain() == {}
    assert len(latest) == 0


def test_outbox_take_is_one_json_object_of_everything_pending():
    outbox = Outbox()
    assert outbox.take() is None
    outbox.put("pose", '{"x":1}')
    outbox.put("pose", '{"x":2}')
    outbox.put("plan", "[[0,0],[1,1]]")
    assert outbox.ready.is_set()
    assert json.loads(outbox.take() or "") == {"pose": {"x": 2}, "plan": [[0, 0], [1, 1]]}
    assert not outbox.ready.is_set()
    assert outbox.take() is None
    assert outbox.replaced == 1


def test_a_client_that_never_reads_holds_one_value_per_stream():
    hub = Hub()
    slow = hub.join()
    for step in range(10_000):
        hub.publish("pose", {"x": step})
        hub.publish("scan", [[step, 0.0]])
    assert len(slow) == 2
    assert json.loads(slow.take() or "") == {"pose": {"x": 9999}, "scan": [[9999, 0.0]]}
    assert slow.replaced == 2 * 9999


def test_a_new_client_gets_the_latest_of_every_stream_at_once():
    hub = Hub()
    hub.publish("map", {"width": 2})
    hub.publish("pose", {"x": 1})
    hub.publish("pose", {"x": 2})
    late = hub.join()
    assert json.loads(late.take() or "") == {"map": {"width": 2}, "pose": {"x": 2}}


def test_on_change_skips_a_value_equal_to_the_last_one():
    hub = Hub()
    client = hub.join()
    assert hub.publish("map", {"cells": "AAAA"}, on_change=True)
    client.take()
    assert not hub.publish("map", {"cells": "AAAA"}, on_change=True)
    assert client.take() is None
    assert hub.publish("map", {"cells": "AAAB"}, on_change=True)
    assert json.loads(client.take() or "") == {"map": {"cells": "AAAB"}}


def test_clients_leave_and_get_nothing_more():
    hub = Hub()
    gone, staying = hub.join(), hub.join()
    assert hub.clients == 2
    hub.leave(gone)
    hub.leave(gone)  # twice is harmless
    hub.publish("pose", {"x": 1})
    assert gone.take() is None
    assert staying.take() == '{"pose":{"x":1}}'
    assert hub.clients == 1


def test_a_value_json_cannot_carry_is_refused_before_any_client_gets_it():
    hub = Hub()
    client = hub.join()
    with pytest.raises(ValueError, match="JSON"):
        hub.publish("pose", {"x": float("nan")})
    assert client.take() is None
    assert "pose" not in hub.latest
