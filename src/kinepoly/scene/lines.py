"""The TOML line map: on which line each key path of a scene file is written.

tomllib gives no line numbers, so :func:`scan_lines` reads the text once more, tolerantly
(it never raises, whatever the text), following tables, arrays of tables (numbered from 1),
dotted keys, strings and brackets, and maps each key path to its first line and each line to
the key path written or open on it. Problems are then placed at ``FILE:LINE``.
"""

from __future__ import annotations

import re
import tomllib

from msgspec import Struct, field

__all__ = ["DEPTH", "KeyPath", "LineMap", "dotted", "scan_lines"]

KeyPath = tuple[str, ...]

_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")
DEPTH = 64
"""The deepest dotted key a file may have. A deeper one is mapped by its first 64 parts (the map stays linear
in the text: each prefix of a key is a key of the map) and noted in ``LineMap.too_deep``: the parser
refuses it before tomllib, whose memory grows with the square of a key's depth, reads it."""


class LineMap(Struct):
    """The first line of each key path, and the key path written or open on each line."""

    first: dict[KeyPath, int] = field(default_factory=dict)
    owner: dict[int, KeyPath] = field(default_factory=dict)
    too_deep: tuple[int, int] | None = None
    """The first line with a key deeper than ``DEPTH``, and that key's depth."""

    def note(self, path: KeyPath, line: int) -> None:
        for end in range(1, len(path) + 1):
            self.first.setdefault(path[:end], line)
        self.owner.setdefault(line, path)

    def line_of(self, path: KeyPath) -> int | None:
        """The line of the most specific prefix of ``path`` that is written in the file."""
        for end in range(len(path), 0, -1):
            line = self.first.get(path[:end])
            if line is not None:
                return line
        return None


class _ScanState(Struct):
    lines: LineMap = field(default_factory=LineMap)
    table: KeyPath = ()
    last_key: KeyPath = ()
    arrays: dict[KeyPath, int] = field(default_factory=dict)
    depth: int = 0
    closer: str | None = None


def scan_lines(text: str) -> LineMap:
    """Map key paths to lines. Tolerant: never raises, whatever the text."""
    state = _ScanState()
    for number, raw in enumerate(text.split("\n"), start=1):
        line = raw.removesuffix("\r")
        inside = state.closer is not None or state.depth > 0
        fallback = state.last_key if inside else state.table
        _scan_line(state, line, number)
        state.lines.owner.setdefault(number, fallback)
    return state.lines


def _scan_line(state: _ScanState, line: str, number: int) -> None:
    if state.closer is not None:
        start = _close_string(line, 0, state.closer)
        if start < 0:
            return
        state.closer = None
    elif state.depth == 0:
        start = _scan_line_start(state, line, number)
    else:
        start = 0
    _scan_rest(state, line, start)


def _scan_line_start(state: _ScanState, line: str, number: int) -> int:
    i = _skip_space(line, 0)
    if i >= len(line) or line[i] == "#":
        return len(line)
    if line.startswith("[[", i):
        return _scan_header(state, line, number, i + 2, array=True)
    if line[i] == "[":
        return _scan_header(state, line, number, i + 1, array=False)
    parts, end = _deep_key(state, _parse_key(line, i), number)
    if parts and end < len(line) and line[end] == "=":
        state.last_key = state.table + parts
        state.lines.note(state.last_key, number)
        return end + 1
    return i


def _deep_key(state: _ScanState, key: tuple[KeyPath, int], number: int) -> tuple[KeyPath, int]:
    """The key, its first ``DEPTH`` parts where it is deeper (noted in the map)."""
    parts, end = key
    if len(parts) > DEPTH:
        if state.lines.too_deep is None:
            state.lines.too_deep = (number, len(parts))
        parts = parts[:DEPTH]
    return parts, end


def _scan_header(state: _ScanState, line: str, number: int, start: int, *, array: bool) -> int:
    parts, _ = _deep_key(state, _parse_key(line, start), number)
    if not parts:
        return len(line)
    if array:
        path = _resolve(state, parts[:-1]) + parts[-1:]
        count = state.arrays.get(path, 0) + 1
        state.arrays[path] = count
        state.table = path + (str(count),)
    else:
        state.table = _resolve(state, parts)
    state.last_key = state.table
    state.lines.note(state.table, number)
    return len(line)


def _resolve(state: _ScanState, parts: KeyPath) -> KeyPath:
    """Insert the running index after every prefix that is an array of tables."""
    out: KeyPath = ()
    for part in parts:
        out += (part,)
        count = state.arrays.get(out)
        if count is not None:
            out += (str(count),)
    return out


def _scan_rest(state: _ScanState, line: str, i: int) -> None:
    """Follow strings, comments and bracket depth to the end of the line."""
    while i < len(line):
        char = line[i]
        if char == "#":
            return
        if char in "\"'":
            i = _skip_string(state, line, i)
            continue
        if char in "[{":
            state.depth += 1
        elif char in "]}":
            state.depth = max(0, state.depth - 1)
        i += 1


def _skip_string(state: _ScanState, line: str, i: int) -> int:
    triple = line[i] * 3
    if line.startswith(triple, i):
        end = _close_string(line, i + 3, triple)
        if end < 0:
            state.closer = triple
            return len(line)
        return end
    return _string_end(line, i)


def _close_string(line: str, start: int, closer: str) -> int:
    """Index just after the multi-line string's closing delimiter, or -1 if not on this line."""
    i = start
    while i < len(line):
        if closer == '"""' and line[i] == "\\":
            i += 2
            continue
        if line.startswith(closer, i):
            end = i + 3
            while end < len(line) and end - i < 5 and line[end] == closer[0]:
                end += 1
            return end
        i += 1
    return -1


def _string_end(line: str, i: int) -> int:
    """Index just after the one-line string starting at ``i`` (or the end of the line)."""
    quote = line[i]
    j = i + 1
    while j < len(line):
        if quote == '"' and line[j] == "\\":
            j += 2
            continue
        if line[j] == quote:
            return j + 1
        j += 1
    return len(line)


def _skip_space(line: str, i: int) -> int:
    while i < len(line) and line[i] in " \t":
        i += 1
    return i


def _parse_key(line: str, i: int) -> tuple[KeyPath, int]:
    """A dotted key at ``i``: its parts and the index after it; no parts if there is none."""
    parts: list[str] = []
    while True:
        part, i = _parse_key_part(line, _skip_space(line, i))
        if part is None:
            return (), i
        parts.append(part)
        i = _skip_space(line, i)
        if i < len(line) and line[i] == ".":
            i += 1
            continue
        return tuple(parts), i


def _parse_key_part(line: str, i: int) -> tuple[str | None, int]:
    if i >= len(line):
        return None, i
    if line[i] in "\"'":
        end = _string_end(line, i)
        raw = line[i:end]
        if len(raw) < 2 or raw[-1] != line[i]:
            return None, i
        return _decode_key(raw), end
    match = _BARE_KEY.match(line, i)
    if match is None:
        return None, i
    return match.group(), match.end()


def _decode_key(raw: str) -> str:
    if raw.startswith("'"):
        return raw[1:-1]
    try:
        value = tomllib.loads(f"k = {raw}").get("k")
    except (tomllib.TOMLDecodeError, ValueError):
        return raw[1:-1]
    return value if isinstance(value, str) else raw[1:-1]



def dotted(path: KeyPath) -> str:
    """The key path as written in a message; a key with a character that cannot be printed is quoted and escaped."""
    import json  # loaded for a message only, not on every start

    return ".".join(part if part.isprintable() else json.dumps(part) for part in path) if path else "(file)"
