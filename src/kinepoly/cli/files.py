"""Files written whole or not at all: a temporary name in the same folder, then one rename.

Every file the command line writes goes through ``write_atomically``; ``emit`` prints a text or
writes it to a file; ``scene_file`` reads a scene with its text.
"""

from __future__ import annotations

import contextlib
import os
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import IO, TYPE_CHECKING, Any

from kinepoly.errors import OutputError, SceneError

if TYPE_CHECKING:
    from kinepoly.scene.spec import Scene

__all__ = ["PAPER_HELP", "emit", "paper_of", "scene_file", "write_atomically"]

PAPER_HELP = "A0..A5, letter, legal, tabloid (landscape; add -portrait), or WIDTHxHEIGHT in mm (default A4)"
"""The help of every ``--paper``: the paper decides the polygon scales (``present.scales``) of every command."""


def paper_of(spec: str) -> tuple[float, float]:
    """``--paper``'s width and height in mm; OutputError (exit 2) saying what is accepted."""
    from kinepoly.render.layout import paper_size

    try:
        return paper_size(spec)
    except ValueError as error:
        raise OutputError(str(error)) from error


def write_atomically(path: str | os.PathLike[str], write: Callable[[IO[Any]], None], *, binary: bool) -> None:
    """Call ``write`` on a temporary file beside ``path``, then rename it to ``path``.

    An interrupted or failed run leaves ``path`` as it was (absent or the previous file) and no
    temporary file behind. OSError (no such folder, no permission) propagates to the caller.
    """
    target = Path(path)
    handle, temporary = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".part", dir=target.parent)
    try:
        with os.fdopen(handle, "wb") if binary else os.fdopen(handle, "w", encoding="utf-8", newline="\n") as stream:
            write(stream)
            stream.flush()
            os.fsync(stream.fileno())
        os.chmod(temporary, 0o644)
        os.replace(temporary, target)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(temporary)
        raise


def _write(stream: IO[Any], text: str) -> None:
    stream.write(text)


def emit(text: str, output: str | None) -> None:
    """Print ``text`` (``output`` None) or write it to the file ``output``; SceneError (exit 2) when it cannot be."""
    if output is None:
        sys.stdout.write(text if text.endswith("\n") else text + "\n")
        return
    try:
        write_atomically(output, lambda stream: _write(stream, text), binary=False)
    except OSError as exc:
        problem = (f"{output}: (file): cannot be written ({exc.strerror}); expected a path in a folder that "
                   "exists and can be written")
        raise SceneError([problem]) from None


def scene_file(path: str) -> tuple[Scene, str]:
    """The scene and its text (for [vary] and an input given as "300 rpm")."""
    from kinepoly.scene.loader import load_scene

    scene = load_scene(path)
    return scene, Path(path).read_text(encoding="utf-8")
