"""Fixtures shared by every layer's tests."""

from __future__ import annotations

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
