"""A shipped catalogue checked once is kept in the user's cache folder and read back as the same catalogue; a cache
that is stale, damaged or cannot be written is not used, and the catalogue is the one the TOML gives."""

from __future__ import annotations

import marshal
import os
from pathlib import Path
from typing import Any

import pytest

from kinepoly.present import catalogue
from kinepoly.present.catalogue import Catalogue, load_catalogue, packaged_languages


def _fresh(lang: str) -> Catalogue:
    """The catalogue as the shipped TOML gives it, parsed and checked now (no cache)."""
    return catalogue._checked(lang, None)


@pytest.fixture
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    return tmp_path / "kinepoly"


@pytest.mark.parametrize("lang", packaged_languages())
def test_a_cached_catalogue_is_the_catalogue_the_toml_gives(cache: Path, lang: str) -> None:
    first = load_catalogue(lang)
    assert (cache / f"catalogue-{lang}.marshal").is_file()
    again = load_catalogue(lang)
    assert first == again == _fresh(lang)
    assert dict(again.messages) == dict(_fresh(lang).messages) and again.source == f"{lang}.toml"


def _plant(cache: Path, lang: str, key: Any, word: str) -> None:
    fresh = _fresh(lang)
    messages = {name: word for name in fresh.messages}
    cache.mkdir(parents=True, exist_ok=True)
    (cache / f"catalogue-{lang}.marshal").write_bytes(
        marshal.dumps((key, (fresh.code, fresh.language, fresh.decimal, messages, fresh.source))))


def test_the_cache_is_read_only_for_the_shipped_files_it_was_made_from(cache: Path) -> None:
    key = catalogue._shipped_key()
    assert key is not None
    _plant(cache, "en", key, "planted")
    assert set(load_catalogue("en").messages.values()) == {"planted"}  # the cache is what a start reads
    fmt, version, folder, files = key
    touched = tuple((name, size, mtime + 1) for name, size, mtime in files)  # a shipped file changed since
    _plant(cache, "en", (fmt, version, folder, touched), "stale")
    assert load_catalogue("en") == _fresh("en")
    assert load_catalogue("en") == _fresh("en")  # and the cache written again from the TOML


@pytest.mark.parametrize("content", [b"", b"not marshal at all", marshal.dumps(("a", "b")), marshal.dumps([1, 2])])
def test_a_damaged_cache_is_not_used(cache: Path, content: bytes) -> None:
    cache.mkdir(parents=True)
    (cache / "catalogue-tr.marshal").write_bytes(content)
    assert load_catalogue("tr") == _fresh("tr")
    assert load_catalogue("tr") == _fresh("tr")


def test_a_cache_folder_that_cannot_be_written_is_left_out(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    blocked = tmp_path / "a-file"
    blocked.write_text("not a folder")
    monkeypatch.setenv("XDG_CACHE_HOME", str(blocked / "cache"))
    assert load_catalogue("ro") == _fresh("ro")
    assert blocked.read_text() == "not a folder"
    monkeypatch.delenv("XDG_CACHE_HOME")
    monkeypatch.delenv("HOME", raising=False)
    monkeypatch.setattr(os.path, "expanduser", lambda path: path)  # no home folder at all
    assert catalogue._cache_file("ro") is None
    assert load_catalogue("ro") == _fresh("ro")


def test_a_teachers_catalogue_and_an_odd_language_name_are_not_cached(cache: Path, tmp_path: Path) -> None:
    mine = tmp_path / "de.toml"
    mine.write_text('extends = "en"\nlanguage = "Deutsch"\ncode = "de"\n', encoding="utf-8")
    assert load_catalogue(messages=mine).code == "de"
    assert not cache.exists()
    assert catalogue._cache_file("../en") is None
