"""deploy/access-control.json5 is the one source of the rules: the compose router's
inline copy is it, and it names every identity `aiobt certs` makes, once."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import zenoh

from aiobt.deploy.certs import DEFAULT_HOSTS, SERVICES, router_name
from aiobt.transport import access_control

REPO = Path(__file__).resolve().parents[3]
RULES = REPO / "deploy" / "access-control.json5"
SERVICE_PROGRAMS = REPO / "services" / "aiobt_services"


def _names(rules: dict[str, Any]) -> list[str]:
    return [name for subject in rules["subjects"] for name in subject["cert_common_names"]]


def test_the_compose_router_carries_the_rules_of_the_one_file() -> None:
    inline = zenoh.Config.from_file(str(REPO / "deploy" / "zenoh-router.json5"))
    assert json.loads(inline.get_json("access_control")) == access_control.load_rules(RULES), (
        "deploy/zenoh-router.json5's access_control differs from deploy/access-control.json5: "
        "copy the file's body (from its first '{') after `access_control: `"
    )


def test_every_identity_is_named_by_exactly_one_subject() -> None:
    names = _names(access_control.load_rules(RULES))
    identities = [*SERVICES, *(router_name(host) for host in DEFAULT_HOSTS)]
    assert len(names) == len(set(names)), names
    assert set(identities) <= set(names), set(identities) - set(names)
    # and nothing else, but a service program the catalog does not run yet
    for name in set(names) - set(identities):
        assert (SERVICE_PROGRAMS / name / "main.py").is_file(), f"{name}: no such identity"


def test_every_subject_has_a_policy_and_every_policy_known_rules() -> None:
    rules = access_control.load_rules(RULES)
    subjects = {subject["id"] for subject in rules["subjects"]}
    in_policies = {s for policy in rules["policies"] for s in policy["subjects"]}
    assert in_policies == subjects
    ids = {rule["id"] for rule in rules["rules"]}
    for policy in rules["policies"]:
        assert "bus" in policy["rules"], policy["id"]  # default deny: nothing without it
        assert set(policy["rules"]) <= ids, policy["id"]
