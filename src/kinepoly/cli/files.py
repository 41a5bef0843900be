"""Files written whole or not at all: a temporary name in the same folder, then one rename.

Every file the command line writes goes through ``write_atomically``; ``emit`` prints a text or
writes it to a file; ``scene_file`` reads a scene with its text; ``output_path`` refuses, before
any work, an output name the file system cannot hold or that names one of the command's inputs.
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
import sys
from collections.abc import Iterable
from pathlib import Path
from typing import IO, TYPE_CHECKING, Any

from kinepoly.atomic import write_atomically
from kinepoly.errors import OutputError, SceneError

if TYPE_CHECKING:
    from kinepoly.scene.spec import Scene

__all__ = ["PAPER_HELP", "emit", "output_path", "paper_of", "scene_file", "write_atomically"]

PAPER_HELP = "A0..A5, letter, legal, tabloid (landscape; add -portrait), or WIDTHxHEIGHT in mm (default A4)"
"""The help of every ``--paper``: the paper decides the polygon scales (``present.scales``) of every command."""


def paper_of(spec: str) -> tuple[float, float]:
    """``--paper``'s width and height in mm; OutputError (exit 2) saying what is accepted."""
    from kinepoly.render.layout import paper_size

    try:
        return paper_size(spec)
    except ValueError as error:
        raise OutputError(str(error)) from error


def output_path(value: str, option: str, inputs: Iterable[str] = ()) -> Path:
    """``value`` as a path to write, or OutputError (exit 2): a name longer than the file system allows, or the
    same file as one of ``inputs`` (also through a link: same device and inode), which writing would replace."""
    path = Path(value)
    try:
        written = os.stat(path)
    except OSError as error:
        if error.errno == errno.ENAMETOOLONG:
            raise OutputError(f"{option} {value}: cannot be written ({error.strerror}); expected a shorter "
                              "name") from None
        return path
    for source in inputs:
        with contextlib.suppress(OSError):
            read = os.stat(source)
            if (read.st_dev, read.st_ino) == (written.st_dev, written.st_ino) and stat.S_ISREG(written.st_mode):
                raise OutputError(f"{option} {value}: is the input {source}; writing it would replace it: "
                                  "expected another file name")
    return path


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
    from kinepoly.scene.loader import loads_scene
    from kinepoly.scene.source import read_text

    text = read_text(path)  # read once: the scene and the text are the same file's, byte-order mark removed
    return loads_scene(text, path), text
