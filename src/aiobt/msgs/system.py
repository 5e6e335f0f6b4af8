"""What a running service says about itself (``aiobt status``)."""

from __future__ import annotations

from pydantic import Field

from aiobt.msgs._base import Msg


class ServiceInfo(Msg):
    """The answer of ``{ns}/srv/info/{service}``: who and what this process is."""

    service: str = Field(description="the service name, as in its token {ns}/nodes/{service}")
    namespace: str
    version: str = Field(description="the aiobt-runtime version the process runs")
    pid: int = Field(ge=0)
    host: str
    sim_time: bool = Field(description="whether it runs on the simulation's clock")
    started: float = Field(ge=0.0, description="wall time it came up, s since the epoch")
    url: str = Field(default="", description="where a person opens it (the web view's page)")
