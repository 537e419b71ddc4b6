"""The Bokeh server of the ``explore`` page, bound to 127.0.0.1 and refusing other hosts.

A page served to ``localhost`` can still be asked for by another name that resolves to it
(DNS rebinding); the server answers only requests whose ``Host`` header is
``127.0.0.1:PORT`` or ``localhost:PORT`` (403 otherwise) and accepts websockets only from
those origins (Bokeh's ``allow_websocket_origin``).
"""

from __future__ import annotations

import functools
import socket

from .app import build_page, require_bokeh
from .fe_layer import FEResults

__all__ = ["local_hosts", "free_port", "make_server"]


def local_hosts(port: int) -> list[str]:
    """The ``Host`` values the server answers: ``127.0.0.1:PORT`` and ``localhost:PORT``."""
    return [f"127.0.0.1:{port}", f"localhost:{port}"]


def free_port() -> int:
    """A TCP port of 127.0.0.1 that is free now (the OS's choice)."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def make_server(results: FEResults | None = None, port: int = 5006):
    """The (not yet started) Bokeh server of the page on ``127.0.0.1:port``.

    Parameters
    ----------
    results : FEResults, optional
        The FE layer drawn on top of the curves.
    port : int
        TCP port (``1 <= port <= 65535``).

    Returns
    -------
    bokeh.server.server.Server
        Call ``start()``, then run ``io_loop.start()``.
    """
    if not isinstance(port, int) or not 1 <= port <= 65535:
        raise ValueError(f"port must be an integer in 1..65535, got {port!r}")
    require_bokeh()
    from bokeh.application import Application
    from bokeh.application.handlers.function import FunctionHandler
    from bokeh.server.auth_provider import AuthProvider
    from bokeh.server.server import Server
    from bokeh.server.util import check_allowlist
    from tornado.web import HTTPError

    hosts = local_hosts(port)

    class LocalHostOnly(AuthProvider):
        """Every page, metadata and websocket request: 403 unless its Host is local."""

        @property
        def get_user_async(self):
            async def user(handler):
                if not check_allowlist(handler.request.host, hosts):
                    raise HTTPError(403, f"host {handler.request.host!r} refused")
                return "local"
            return user

        @property
        def get_login_url(self):
            return lambda handler: "/"

    app = Application(FunctionHandler(functools.partial(build_page, results=results)))
    return Server({"/": app}, address="127.0.0.1", port=port, allow_websocket_origin=hosts,
                  auth_provider=LocalHostOnly(), num_procs=1)
