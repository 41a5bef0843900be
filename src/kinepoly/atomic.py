"""Files written whole or not at all: a temporary name in the same folder, then one rename.

Every file kinepoly writes (the command line, the editor's save, an animation) goes through
``write_atomically``; ``write_bytes`` writes bytes so, an OSError said as an OutputError (exit 2).
"""

from __future__ import annotations

import contextlib
import os
import stat
from collections.abc import Callable
from pathlib import Path
from typing import IO, Any

from kinepoly.errors import OutputError

__all__ = ["write_atomically", "write_bytes"]


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def write_atomically(path: str | os.PathLike[str], write: Callable[[IO[Any]], None], *, binary: bool) -> None:
    """Call ``write`` on a temporary file beside ``path``, then rename it to ``path``.

    An interrupted or failed run leaves ``path`` as it was (absent or the previous file) and no
    temporary file behind. A new file gets the mode the umask leaves of 0666, a file replaced keeps
    its mode; a symbolic link is kept and the file it names replaced. An existing ``path`` that is
    not a regular file (a device such as /dev/null, a FIFO) is written directly: it cannot be replaced.
    OSError (no such folder, no permission, no space left) propagates to the caller.
    """
    target = Path(os.path.realpath(path)) if os.path.islink(path) else Path(path)
    try:
        mode = os.stat(target).st_mode
    except FileNotFoundError:
        mode = None
    if mode is not None and not stat.S_ISREG(mode) and not stat.S_ISDIR(mode):
        with open(target, "wb") if binary else open(target, "w", encoding="utf-8", newline="\n") as stream:
            write(stream)
        return
    import tempfile  # loaded when a file is written: a command that only prints starts without it

    # the temporary name shortened: any name the file system holds can be written
    handle, temporary = tempfile.mkstemp(prefix=f".{target.name[:64]}.", suffix=".part", dir=target.parent)
    try:
        with os.fdopen(handle, "wb") if binary else os.fdopen(handle, "w", encoding="utf-8", newline="\n") as stream:
            write(stream)
            stream.flush()
            os.fsync(stream.fileno())
        os.chmod(temporary, stat.S_IMODE(mode) if mode is not None else 0o666 & ~_umask())
        os.replace(temporary, target)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(temporary)
        raise


def write_bytes(path: str | os.PathLike[str], content: bytes) -> None:
    """``content`` written to ``path`` whole or not at all; a failure (no folder, no permission, no space) an
    OutputError that says what to change."""
    def write(stream: IO[Any]) -> None:
        stream.write(content)

    try:
        write_atomically(path, write, binary=True)
    except OSError as error:
        raise OutputError(f"{path}: cannot be written ({error.strerror}); expected a path in a folder that exists "
                          "and can be written") from None
