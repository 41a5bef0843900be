"""The editor's server run in a thread on a free port of 127.0.0.1, for a test, and always shut down."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass

import uvicorn

from kinepoly.cli.edit import listen
from kinepoly.editor.document import Document
from kinepoly.editor.server import make_app, new_token

__all__ = ["Served", "serving"]


@dataclass(frozen=True)
class Served:
    document: Document
    port: int
    token: str

    @property
    def url(self) -> str:
        """The page's address, as ``kinepoly edit`` prints it."""
        return f"http://127.0.0.1:{self.port}/{self.token}/"


@contextmanager
def serving(document: Document) -> Iterator[Served]:
    """``document``'s editor served until the block ends (the server stopped and its thread joined)."""
    sock = listen(0)
    port, token = sock.getsockname()[1], new_token()
    server = uvicorn.Server(uvicorn.Config(make_app(document, token, port), log_level="warning", ws="websockets-sansio",
                                           lifespan="off"))
    thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True)
    thread.start()
    try:
        deadline = time.monotonic() + 20
        while not server.started:
            if not thread.is_alive() or time.monotonic() > deadline:
                raise RuntimeError("the editor's server did not start")
            time.sleep(0.01)
        yield Served(document, port, token)
    finally:
        server.should_exit = True
        thread.join(timeout=20)
        sock.close()
