"""``kinepoly edit SCENE [--template NAME] [--no-browser] [--port N] [--paper A4]``: edit a scene in the browser, live.

Starts the editor's server (``kinepoly.editor.server``) on 127.0.0.1 only, at an address with a
random token, and opens it in the browser (``--no-browser`` prints it only). A SCENE that does not
exist yet starts from ``--template``; it is written when the page saves. Ctrl-C stops the server (exit 0).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from kinepoly.cli.files import PAPER_HELP, paper_of
from kinepoly.editor import TEMPLATES
from kinepoly.errors import OutputError, SceneError

if TYPE_CHECKING:
    import socket

__all__ = ["add_arguments", "run"]



def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("scene", help="the scene file (TOML); a new one starts from --template")
    parser.add_argument("--template", choices=TEMPLATES, default="four-bar",
                        help="the scene a new file starts from: " + ", ".join(TEMPLATES))
    parser.add_argument("--no-browser", action="store_true", help="print the address only; do not open a browser")
    parser.add_argument("--port", type=int, default=0, help="the local port to listen on; 0 picks a free one")
    parser.add_argument("--paper", default="A4", help="the drawing's paper, kept while you drag (its polygon scales "
                        "are those solve --paper reports): " + PAPER_HELP)


def listen(port: int) -> socket.socket:
    """A socket listening on 127.0.0.1 at ``port`` (0: a free one); OutputError when it cannot."""
    import socket  # loaded by the editor only: the other commands start without it

    if not 0 <= port <= 65535:
        raise OutputError(f"--port {port}: expected a port between 0 and 65535 (0 picks a free one)")
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    try:
        sock.bind(("127.0.0.1", port))
        sock.listen(16)
    except OSError as error:
        sock.close()
        raise OutputError(f"--port {port}: cannot listen on 127.0.0.1 ({error.strerror or error}); choose another "
                          "port or 0") from error
    return sock


def run(args: argparse.Namespace) -> int:
    """Serve the editor until interrupted."""
    import uvicorn

    from kinepoly.editor.document import Document, template_text
    from kinepoly.editor.server import make_app, new_token

    paper = paper_of(args.paper)
    path = Path(args.scene)
    if path.is_dir():
        raise OutputError(f"{args.scene}: is a folder; expected a scene file (TOML)")
    if path.exists():
        try:
            document = Document(args.scene, paper=paper)
        except UnicodeDecodeError:
            raise SceneError(f"{args.scene}: (file): not UTF-8 text; expected a TOML scene") from None
        except OSError as error:
            raise SceneError(f"{args.scene}: (file): cannot be read ({error.strerror or error})") from None
    else:
        if not path.parent.is_dir():
            raise OutputError(f"{args.scene}: the folder {str(path.parent)!r} does not exist; create it or choose "
                              "another")
        document = Document(args.scene, template_text(args.template), paper)
    sock = listen(args.port)
    port = sock.getsockname()[1]
    token = new_token()
    address = f"http://127.0.0.1:{port}/{token}/"
    new = "" if path.exists() else f" (a new file from the {args.template} template, written when saved)"
    print(f"kinepoly edit: {args.scene}{new} at {address} (Ctrl-C stops it)", flush=True)
    if not args.no_browser:
        import webbrowser

        webbrowser.open(address)
    config = uvicorn.Config(make_app(document, token, port), log_level="warning", ws="websockets-sansio")
    try:
        uvicorn.Server(config).run(sockets=[sock])
    except KeyboardInterrupt:  # uvicorn stops on Ctrl-C, then raises it again: stopping is how the editor ends
        pass
    finally:
        sock.close()
    print("kinepoly edit: stopped", file=sys.stderr)
    return 0
