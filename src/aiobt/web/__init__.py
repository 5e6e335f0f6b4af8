"""The built-in web view (``aiobt web``, on by default in ``aiobt up``): map, costmap,
robot, scan, plans, goals and the running tree in a browser, fed from the bus.

See docs/web.md. :func:`serve_web` runs it on an open :class:`~aiobt.transport.Bus`.
"""

from aiobt.web.server import WebOptions, WebView, serve_web

__all__ = ["WebOptions", "WebView", "serve_web"]
