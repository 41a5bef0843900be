"""A scene file from bytes to TOML data: read, decoded as UTF-8 and parsed, or one clear problem.

Each failure raises a :class:`~kinepoly.errors.SceneError` naming the file (and the line,
where there is one): a missing file, binary data, text that is not UTF-8, a TOML syntax
error placed at the key path written on its line.
"""

from __future__ import annotations

import re
import tomllib
from collections.abc import Mapping
from typing import NoReturn

from kinepoly.errors import SceneError
from kinepoly.scene.lines import DEPTH, LineMap, dotted

__all__ = ["MAX_INPUT_BYTES", "Table", "decode_text", "fail", "parse_toml", "read_bytes", "read_text"]

Table = Mapping[str, object]


def fail(source: str, line: int | None, message: str, path: str = "(file)") -> NoReturn:
    where = source if line is None else f"{source}:{line}"
    raise SceneError([f"{where}: {path}: {message}"])


MAX_INPUT_BYTES = 8 * 2**20
"""The most kinepoly reads of an input file (a scene, an answers file, a message catalogue): 8 MiB. A larger
file (or a device such as /dev/zero) is refused at once rather than read until memory runs out."""


def read_bytes(source: str, what: str = "a scene") -> bytes:
    """The bytes of ``what`` (a scene, an answers file, ...) at ``source``, at most ``MAX_INPUT_BYTES``."""
    try:
        with open(source, "rb") as stream:
            data = stream.read(MAX_INPUT_BYTES + 1)
    except FileNotFoundError:
        fail(source, None, f"no such file; expected the path of {what} .toml file")
    except IsADirectoryError:
        fail(source, None, f"is a directory; expected the path of {what} .toml file")
    except OSError as exc:
        fail(source, None, f"cannot be read ({exc.strerror}); expected {what} .toml file that can be read")
    if len(data) > MAX_INPUT_BYTES:
        fail(source, None, f"longer than {MAX_INPUT_BYTES // 2**20} MiB, the most kinepoly reads of a file; "
             f"expected {what} .toml file of ordinary size")
    return data


def decode_text(source: str, data: bytes, what: str = "a scene") -> str:
    nul = data.find(b"\x00")
    if nul >= 0:
        line = data.count(b"\n", 0, nul) + 1
        fail(source, line, f"binary data (a NUL byte); expected {what} .toml file in UTF-8 text")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        bad = data[exc.start]
        fail(
            source,
            line,
            f"not UTF-8 text (byte 0x{bad:02x} at offset {exc.start}); expected {what} .toml file in UTF-8",
        )


def read_text(source: str, what: str = "a scene") -> str:
    """The text of the ``what`` file at ``source`` (read_bytes, decode_text), a byte-order mark removed."""
    return decode_text(source, read_bytes(source, what), what).removeprefix("\ufeff")


_TOML_WHERE = re.compile(r"\s*\((?:at line (\d+), column (\d+)|at end of document)\)\s*$")


def parse_toml(text: str, source: str, lines: LineMap) -> Table:
    if lines.too_deep is not None:
        line, depth = lines.too_deep
        path = dotted(lines.owner.get(line, ())[:3]) + "..."
        fail(source, line, f"a dotted key {depth} levels deep; expected at most {DEPTH} levels", path)
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SceneError([_syntax_problem(str(exc), text, source, lines)]) from None
    except ValueError as exc:  # integers longer than Python converts
        raise SceneError([f"{source}: (file): {exc}; expected numbers of ordinary size"]) from None
    except RecursionError:
        raise SceneError([f"{source}: (file): arrays or tables nested too deeply; expected a flat scene"]) from None


def _syntax_problem(message: str, text: str, source: str, lines: LineMap) -> str:
    match = _TOML_WHERE.search(message)
    what = message[: match.start()] if match else message
    if match and match.group(1):
        line, where = int(match.group(1)), f" at column {match.group(2)}"
    else:
        line, where = text.rstrip().count("\n") + 1, " at the end of the file"
    path = dotted(lines.owner.get(line, ()))
    return f"{source}:{line}: {path}: TOML syntax error{where}: {what}; expected valid TOML"
