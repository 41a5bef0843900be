"""Message catalogues: every word of a handout and of the construction's steps, one TOML file per language.

The catalogues shipped are ``messages/en.toml``, ``tr.toml`` and ``ro.toml`` beside this module
(``--lang en|tr|ro``). A teacher adds a language by copying ``en.toml``, translating the text
between the quotes and passing the file with ``--messages FILE``; a file that starts with
``extends = "tr"`` only needs the keys it changes. Placeholders such as ``{link}`` stand for names
and numbers kinepoly fills in; a translation may leave one out or move it, but not invent one.
A catalogue is checked whole before anything is drawn: a missing key, a key that English does
not have, a placeholder English does not have or a brace out of place is exit 2, every problem
listed as ``FILE:LINE: key: what is wrong``.

A shipped catalogue, once checked, is kept in the user's cache folder (``$XDG_CACHE_HOME/kinepoly``, else
``~/.cache/kinepoly``) in the standard library's ``marshal`` format, keyed by the size and modification time of
every shipped file and by the Python version, so that a later start reads it back without parsing and checking
the TOML again; a cache that cannot be written (a read-only home) or read back is simply not used.
"""

from __future__ import annotations

import marshal
import math
import os
import string
import sys
import tomllib
from collections.abc import Mapping
from functools import cache
from pathlib import Path
from types import MappingProxyType
from typing import IO, Any

from msgspec import Struct

from kinepoly.errors import CatalogueError, SceneError
from kinepoly.geom.tolerances import ANGLE_SAME_DEG, PRINTED_ZERO
from kinepoly.present.clean import format_number
from kinepoly.scene.source import read_text

__all__ = ["Catalogue", "load_catalogue", "packaged_languages", "placeholders"]

_META = ("language", "code", "decimal", "extends")
"""Keys about the catalogue itself, outside the messages (``extends`` only in a file of a teacher's)."""


class Catalogue(Struct, frozen=True):
    """The messages of one language, keyed ``section.name``; ``decimal`` is its decimal mark."""

    code: str
    language: str
    decimal: str
    messages: Mapping[str, str]
    source: str

    def say(self, key: str, **params: str) -> str:
        """The message ``key`` with its placeholders filled in."""
        return self.messages[key].format(**params)

    def number(self, x: float) -> str:
        """A number as the handout prints it: about five significant digits, this language's decimal mark."""
        text = format_number(0.0 if abs(x) < PRINTED_ZERO else x)
        text = text.replace("-", "−")
        return text.replace(".", self.decimal) if self.decimal != "." else text

    def angle(self, radians: float) -> str:
        """An angle in degrees in (-180, 180], with the degree sign."""
        degrees = math.degrees(math.remainder(radians, 2.0 * math.pi))
        return f"{self.number(180.0 if degrees <= -180.0 + ANGLE_SAME_DEG else degrees)}°"

    def degrees(self, degrees: float) -> str:
        """An angle given in degrees, written in (-180, 180] with the degree sign: -342.1 as 17.9°."""
        return self.angle(math.radians(degrees))

    def pair(self, x: float, y: float) -> str:
        """Coordinates: ``(12.5, 3)``, or ``(12,5; 3)`` where the decimal mark is a comma."""
        separator = "; " if self.decimal == "," else ", "
        return f"({self.number(x)}{separator}{self.number(y)})"


def placeholders(message: str) -> set[str]:
    """The names in braces of a message (ValueError for a brace out of place)."""
    return {name for _, name, _, _ in string.Formatter().parse(message) if name is not None}


def packaged_languages() -> tuple[str, ...]:
    """The codes of the catalogues shipped with kinepoly."""
    from importlib import resources  # the shipped files are read through it when a catalogue is not cached

    folder = resources.files("kinepoly.present").joinpath("messages")
    return tuple(sorted(entry.name[:-5] for entry in folder.iterdir() if entry.name.endswith(".toml")))


def _flatten(table: Mapping[str, Any], prefix: str = "") -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, value in table.items():
        name = f"{prefix}{key}"
        if isinstance(value, Mapping):
            out.update(_flatten(value, f"{name}."))
        else:
            out[name] = value
    return out


def _line_of(text: str, key: str) -> int | None:
    """The line where ``key`` (``section.name``) is written: after its ``[section]`` header."""
    section, _, name = key.rpartition(".")
    current = ""
    for number, line in enumerate(text.splitlines(), 1):
        stripped = line.strip()
        if stripped.startswith("[") and stripped.endswith("]"):
            current = stripped.strip("[]").strip()
        elif current == section and stripped.split("=")[0].strip().strip('"') == name:
            return number
    return None


def _read(text: str, source: str) -> dict[str, Any]:
    try:
        return _flatten(tomllib.loads(text))
    except tomllib.TOMLDecodeError as error:
        raise CatalogueError(f"{source}: not a valid TOML file: {error}") from None


def _packaged_text(code: str) -> str:
    from importlib import resources

    return resources.files("kinepoly.present").joinpath("messages", f"{code}.toml").read_text(encoding="utf-8")


@cache
def _packaged(code: str) -> tuple[str, Mapping[str, Any]]:
    """A shipped catalogue's text and its keys, flattened: each shipped file is read and parsed once a process
    (English is every catalogue's reference as well as a language of its own)."""
    text = _packaged_text(code)
    return text, MappingProxyType(_read(text, f"{code}.toml"))


def _check(data: dict[str, Any], reference: Mapping[str, str], text: str, source: str) -> list[str]:
    problems = []

    def where(key: str) -> str:
        line = _line_of(text, key)
        return f"{source}:{line}: {key}" if line else f"{source}: {key}"

    for key, value in data.items():
        if key in _META:
            if not isinstance(value, str):
                problems.append(f"{where(key)}: expected a string, got {value!r}")
            continue
        if key not in reference:
            problems.append(f"{where(key)}: unknown key (the English catalogue has no such message)")
            continue
        if not isinstance(value, str):
            problems.append(f"{where(key)}: expected a string in quotes, got {value!r}")
            continue
        try:
            extra = placeholders(value) - placeholders(reference[key])
        except ValueError as error:
            problems.append(f"{where(key)}: {error}; write a literal brace as {{{{ or }}}}")
            continue
        if extra:
            allowed = ", ".join(f"{{{n}}}" for n in sorted(placeholders(reference[key]))) or "none"
            problems.append(f"{where(key)}: unknown placeholder {', '.join(f'{{{n}}}' for n in sorted(extra))}; "
                            f"this message may use {allowed}")
    return problems


def _english() -> dict[str, str]:
    _, data = _packaged("en")
    return {key: value for key, value in data.items() if key not in _META}


_CACHE_FORMAT = 1
"""The layout of a cached catalogue; a cache of another layout is not read."""

_Key = tuple[int, tuple[int, ...], str, tuple[tuple[str, int, int], ...]]
"""What a cached catalogue is valid for (``_shipped_key``)."""


def _cache_file(lang: str) -> Path | None:
    """Where the checked shipped catalogue ``lang`` is kept between runs (None: no cache folder to use)."""
    if not (lang.isascii() and lang.isalnum()):
        return None
    base = os.environ.get("XDG_CACHE_HOME")
    if not base:
        home = os.path.expanduser("~")
        if home == "~":
            return None
        base = os.path.join(home, ".cache")
    return Path(base, "kinepoly", f"catalogue-{lang}.marshal")


def _shipped_key() -> _Key | None:
    """What a cached catalogue is valid for: the shipped files as they are now (a name, size and modification
    time each), the Python version and the cache's layout; None where the shipped files are not plain files."""
    folder = os.path.join(os.path.dirname(os.path.abspath(__file__)), "messages")
    try:
        files = sorted((entry.name, entry.stat().st_size, entry.stat().st_mtime_ns) for entry in os.scandir(folder)
                       if entry.name.endswith(".toml"))
    except OSError:
        return None
    return (_CACHE_FORMAT, (sys.version_info.major, sys.version_info.minor), folder, tuple(files))


def _cached(lang: str, key: _Key) -> Catalogue | None:
    """The catalogue ``lang`` as an earlier run checked it, if the cache holds it for ``key``."""
    path = _cache_file(lang)
    if path is None:
        return None
    try:
        stored = marshal.loads(path.read_bytes())
        if not (isinstance(stored, tuple) and len(stored) == 2 and stored[0] == key):
            return None
        code, language, decimal, messages, source = stored[1]
        if not (all(isinstance(x, str) for x in (code, language, decimal, source)) and isinstance(messages, dict)
                and all(isinstance(k, str) and isinstance(v, str) for k, v in messages.items())):
            return None
    except (OSError, EOFError, ValueError, TypeError):
        return None
    return Catalogue(code, language, decimal, MappingProxyType(messages), source)


def _keep(lang: str, key: _Key, catalogue: Catalogue) -> None:
    """Keep the checked ``catalogue`` for the next run; a cache that cannot be written is left out."""
    path = _cache_file(lang)
    if path is None:
        return
    from kinepoly.atomic import write_atomically

    value = (catalogue.code, catalogue.language, catalogue.decimal, dict(catalogue.messages), catalogue.source)
    content = marshal.dumps((key, value))

    def write(stream: IO[bytes]) -> None:
        stream.write(content)

    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        write_atomically(path, write, binary=True)
    except OSError:
        pass


def load_catalogue(lang: str = "en", messages: str | Path | None = None) -> Catalogue:
    """The catalogue of ``lang`` (shipped), or of the file ``messages`` (a teacher's), checked whole.

    Raises CatalogueError naming every problem: an unknown language, a file that cannot be read
    or is not TOML, missing or unknown keys, unknown placeholders, a bad ``extends``.
    """
    key = _shipped_key() if messages is None else None
    if key is not None:
        found = _cached(lang, key)
        if found is not None:
            return found
    catalogue = _checked(lang, messages)
    if key is not None:
        _keep(lang, key, catalogue)
    return catalogue


def _checked(lang: str, messages: str | Path | None) -> Catalogue:
    from importlib import resources

    reference = _english()
    languages = packaged_languages()
    if messages is None:
        if lang not in languages:
            raise CatalogueError(f"--lang {lang}: no such language; expected one of {', '.join(languages)}, or a "
                                 f"catalogue of your own with --messages FILE (copy en.toml from "
                                 f"{resources.files('kinepoly.present').joinpath('messages')} and translate it)")
        source = f"{lang}.toml"
        text, parsed = _packaged(lang)
        data = dict(parsed)
    else:
        source = str(messages)
        try:
            text = read_text(source, "a message catalogue")
        except SceneError as error:
            raise CatalogueError(f"--messages {messages}: cannot read the catalogue: {error}") from None
        data = _read(text, source)
    problems = _check(data, reference, text, source)
    base: dict[str, Any] = {}
    if "extends" in data:
        parent = data["extends"]
        if parent not in languages:
            problems.append(f"{source}: extends: no such language {parent!r}; expected one of {', '.join(languages)}")
        else:
            base = dict(_packaged(parent)[1])
    merged = {**base, **{k: v for k, v in data.items() if k != "extends"}}
    missing = [key for key in reference if key not in merged]
    if missing:
        problems.append(f"{source}: missing {len(missing)} message(s): {', '.join(missing)} (copy them from "
                        f"en.toml and translate them, or start the file with extends = \"en\")")
    for key in ("language", "code"):
        if key not in merged:
            problems.append(f"{source}: {key}: missing; expected e.g. language = \"Deutsch\", code = \"de\"")
    if problems:
        raise CatalogueError("the message catalogue has problems:\n  " + "\n  ".join(problems))
    decimal = str(merged.get("decimal", "."))
    if decimal not in (".", ","):
        raise CatalogueError(f"{source}: decimal: expected \".\" or \",\", got {decimal!r}")
    messages_only = {key: str(merged[key]) for key in reference}
    return Catalogue(str(merged["code"]), str(merged["language"]), decimal, MappingProxyType(messages_only), source)
