"""The editor's ASGI app (starlette): the page, its files, the JSON API and the websocket of live updates.

Security, for a server any page in the user's browser could try to reach: it listens on
127.0.0.1 only (``cli.edit``); every request and the websocket must carry the random token as the
first part of the path; a ``Host`` other than the local address and port is refused (DNS
rebinding), and so is a request from another origin (``Origin``, ``Sec-Fetch-Site``); a request
that changes something must be JSON (which a form of another site cannot send without asking); the
only file written is the one the editor was started on (``document.Document.save``).
"""

from __future__ import annotations

import json
import secrets
from collections.abc import Awaitable, Callable, MutableMapping
from importlib.resources import files
from typing import Any

from anyio import to_thread
from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import JSONResponse, PlainTextResponse, Response
from starlette.routing import Mount, Route, WebSocketRoute
from starlette.staticfiles import StaticFiles
from starlette.websockets import WebSocket, WebSocketDisconnect

from kinepoly.editor.document import ChangedOnDisk, Document
from kinepoly.editor.evaluate import Evaluation
from kinepoly.editor.values import EditError
from kinepoly.errors import internal_error_text

__all__ = ["Guard", "make_app", "new_token"]

Scope = MutableMapping[str, Any]
Message = MutableMapping[str, Any]
Receive = Callable[[], Awaitable[Message]]
Send = Callable[[Message], Awaitable[None]]
ASGIApp = Callable[[Scope, Receive, Send], Awaitable[None]]


def new_token() -> str:
    """A random token for the address (128 bits, URL-safe)."""
    return secrets.token_urlsafe(16)


class Guard:
    """ASGI middleware refusing, before the app sees it, a request or websocket without the token, from another
    host name than 127.0.0.1 or localhost at ``port``, or from another origin."""

    def __init__(self, app: ASGIApp, token: str, port: int) -> None:
        self.app, self.token, self.port = app, token, port

    def hosts(self) -> set[str]:
        return {f"127.0.0.1:{self.port}", f"localhost:{self.port}"}

    def refusal(self, scope: Scope) -> str | None:
        """Why the request is refused, or None."""
        headers = {k.decode("latin-1").lower(): v.decode("latin-1") for k, v in scope.get("headers", [])}
        if headers.get("host") not in self.hosts():
            return "this server answers only at its local address (127.0.0.1 or localhost and its port)"
        origin = headers.get("origin")
        if origin is not None and origin not in {f"http://{h}" for h in self.hosts()}:
            return "requests from another origin are refused"
        if headers.get("sec-fetch-site", "same-origin") not in ("same-origin", "none"):
            return "requests from another site are refused"
        first = str(scope.get("path", "")).lstrip("/").split("/", 1)[0]
        if not secrets.compare_digest(first.encode(), self.token.encode()):
            return "the address lacks the editor's token; open the address kinepoly edit printed"
        return None

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] not in ("http", "websocket"):
            await self.app(scope, receive, send)
            return
        reason = self.refusal(scope)
        if reason is None:
            await self.app(scope, receive, send)
        elif scope["type"] == "websocket":
            await send({"type": "websocket.close", "code": 1008, "reason": reason})
        else:
            await PlainTextResponse(f"kinepoly edit: refused: {reason}\n", status_code=403)(scope, receive, send)


def _answer(evaluation: Evaluation) -> JSONResponse:
    """``solve --json``'s object (200), or the errors as the CLI prints them (422) with its exit status."""
    if evaluation.result is not None:
        return JSONResponse(evaluation.result)
    return JSONResponse({"errors": list(evaluation.errors), "exit": evaluation.exit}, status_code=422)


async def _json(request: Request) -> dict[str, Any]:
    if request.headers.get("content-type", "").split(";")[0].strip() != "application/json":
        raise EditError("expected a JSON body (Content-Type: application/json)")
    try:
        body = json.loads(await request.body())
    except (ValueError, UnicodeDecodeError) as error:
        raise EditError(f"the body is not JSON: {error}") from None
    if not isinstance(body, dict):
        raise EditError("expected a JSON object")
    return body


def make_app(document: Document, token: str, port: int) -> ASGIApp:
    """The editor of ``document`` at ``http://127.0.0.1:{port}/{token}/``, guarded by ``Guard``."""
    page = files("kinepoly.editor").joinpath("static", "editor.html").read_text(encoding="utf-8")
    policy = (f"default-src 'self'; script-src 'self'; style-src 'self' 'unsafe-inline'; img-src 'self' data:; "
              f"connect-src 'self' ws://127.0.0.1:{port} ws://localhost:{port}; frame-ancestors 'none'")

    async def index(request: Request) -> Response:
        return Response(page, media_type="text/html; charset=utf-8",
                        headers={"Content-Security-Policy": policy, "Cache-Control": "no-store"})

    async def read_scene(request: Request) -> Response:
        return JSONResponse({"path": document.source, "text": document.text})

    async def replace_scene(request: Request) -> Response:
        try:
            body = await _json(request)
            text = body.get("text")
            if not isinstance(text, str):
                raise EditError("expected {\"text\": the scene's TOML}")
        except EditError as error:
            return JSONResponse({"error": str(error)}, status_code=400)
        return _answer(await to_thread.run_sync(document.replace, text))

    async def solution(request: Request) -> Response:
        return _answer(document.current)

    async def drawing(request: Request) -> Response:
        good = document.good
        if good is None:
            return PlainTextResponse("no text has solved yet", status_code=404)
        return Response(good.svg, media_type="image/svg+xml")

    async def step(request: Request) -> Response:
        svg = await to_thread.run_sync(document.step, int(request.path_params["number"]))
        if svg is None:
            return PlainTextResponse("no such step", status_code=404)
        return Response(svg, media_type="image/svg+xml")

    async def state(request: Request) -> Response:
        return JSONResponse(await to_thread.run_sync(document.state))

    async def change(request: Request) -> Response:
        try:
            body = await _json(request)
            await to_thread.run_sync(_change, document, body)
        except EditError as error:
            return JSONResponse({"error": str(error)}, status_code=400)
        except Exception as error:  # noqa: BLE001 - a message, never a traceback
            return JSONResponse({"error": internal_error_text(error)}, status_code=500)
        return JSONResponse(await to_thread.run_sync(document.state))

    async def save(request: Request) -> Response:
        try:
            body = await _json(request)
        except EditError as error:
            return JSONResponse({"error": str(error)}, status_code=400)
        try:
            await to_thread.run_sync(lambda: document.save(force=body.get("force") is True))
        except ChangedOnDisk as error:
            return JSONResponse({"error": str(error), "changed_on_disk": True}, status_code=409)
        except OSError as error:
            return JSONResponse({"error": f"{document.source}: cannot be written ({error.strerror or error})"},
                                status_code=500)
        return JSONResponse({"saved": document.source})

    async def live(websocket: WebSocket) -> None:
        await websocket.accept()
        try:
            while True:
                message = await websocket.receive_json()
                seq = message.get("seq") if isinstance(message, dict) else None
                reply = await to_thread.run_sync(_answer_change, document, message)  # one worker hop a change
                await websocket.send_text(json.dumps({**reply, "seq": seq}, allow_nan=False))
        except WebSocketDisconnect:
            return

    routes = [
        Route("/", index),
        Route("/api/scene", read_scene, methods=["GET"]),
        Route("/api/scene", replace_scene, methods=["PUT"]),
        Route("/api/solution", solution, methods=["GET"]),
        Route("/api/drawing.svg", drawing, methods=["GET"]),
        Route("/api/steps/{number:int}.svg", step, methods=["GET"]),
        Route("/api/state", state, methods=["GET"]),
        Route("/api/change", change, methods=["POST"]),
        Route("/api/save", save, methods=["POST"]),
        WebSocketRoute("/ws", live),
        Mount("/static", StaticFiles(packages=[("kinepoly.editor", "static")])),
    ]
    app = Starlette(routes=[Mount(f"/{token}", routes=routes)])
    return Guard(app, token, port)


def _answer_change(document: Document, message: object) -> dict[str, Any]:
    """The page's state after the change ``message`` asks, with ``refused`` saying why where it could not be made."""
    refused: str | None = None
    try:
        _change(document, message if isinstance(message, dict) else {})
    except EditError as error:
        refused = str(error)
    except Exception as error:  # noqa: BLE001 - the page stays connected and says what happened
        refused = internal_error_text(error)
    state = document.state()
    if refused is not None:
        state["refused"] = refused
    return state


def _change(document: Document, message: dict[str, Any]) -> None:
    """One change asked by the page or a script: ``{"op": "edit", "edit": {...}, "merge": false, "draft": false}``,
    ``{"op": "text", "text": ...}``, ``{"op": "undo"}``, ``{"op": "redo"}``, ``{"op": "full"}`` (a draft sheet drawn
    whole) or ``{"op": "state"}``."""
    op = message.get("op")
    if op == "edit":
        edit = message.get("edit")
        if not isinstance(edit, dict):
            raise EditError("edit: expected {\"edit\": {\"op\": ...}}")
        document.edit(edit, merge=message.get("merge") is True, draft=message.get("draft") is True)
    elif op == "text":
        text = message.get("text")
        if not isinstance(text, str):
            raise EditError("text: expected {\"text\": the scene's TOML}")
        document.replace(text)
    elif op == "undo":
        document.undo()
    elif op == "redo":
        document.redo()
    elif op == "full":
        document.full()
    elif op != "state":
        raise EditError(f"unknown change {op!r}; expected edit, text, undo, redo, full or state")
