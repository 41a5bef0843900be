"""Fixtures shared by every layer's tests."""

from __future__ import annotations

import os
from collections.abc import Iterator
from typing import Any

import pytest
from tests.chromium import browser_page


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    """A headless chromium page shared by the tests of one module (skipped locally without chromium,
    failing under CI)."""
    with browser_page() as page:
        yield page


@pytest.fixture(scope="session", autouse=True)
def own_cache_folder(tmp_path_factory: pytest.TempPathFactory) -> Iterator[None]:
    """The run keeps kinepoly's cache (the checked message catalogues) in a folder of its own, not in the user's
    (``$XDG_CACHE_HOME``; the commands the tests start inherit it)."""
    before = os.environ.get("XDG_CACHE_HOME")
    os.environ["XDG_CACHE_HOME"] = str(tmp_path_factory.mktemp("cache"))
    yield
    if before is None:
        os.environ.pop("XDG_CACHE_HOME", None)
    else:
        os.environ["XDG_CACHE_HOME"] = before
