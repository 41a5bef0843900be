"""Debian's chromium, headless, driven by playwright (the ``test`` extra) for the web pages' tests.

Playwright's own browsers are never downloaded (``playwright install`` is not run): it launches
the chromium that ``.ci/run`` installs with apt, through ``executable_path``. ``browser_page``
is the fixture's body: skipped where chromium or playwright is missing, except on CI (CI set),
where that is a failure. Every page records its script errors in ``page.errors``.
"""

from __future__ import annotations

import os
import shutil
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import pytest

__all__ = ["ARGS", "browser_page", "chromium"]

ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
        "--disable-component-update", "--no-first-run"]


def chromium() -> str | None:
    """The chromium executable, or None when it is not installed."""
    for candidate in ("/usr/bin/chromium", shutil.which("chromium"), shutil.which("chromium-browser")):
        if candidate and os.path.exists(candidate):
            return candidate
    return None


def _missing(what: str) -> None:
    if os.environ.get("CI"):
        pytest.fail(f"{what}; CI must have it (apt-get install chromium, pip install -e '.[test]', see .ci/run)")
    pytest.skip(what)


@contextmanager
def browser_page() -> Iterator[Any]:
    """A fresh page of a headless chromium; ``page.errors`` lists the script errors it met."""
    executable = chromium()
    if executable is None:
        _missing("chromium is not installed")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        _missing("playwright is not installed (the test extra)")
    with sync_playwright() as driver:
        browser = driver.chromium.launch(executable_path=executable, headless=True, args=ARGS)
        try:
            page = browser.new_page(viewport={"width": 1400, "height": 1000})
            errors: list[str] = []
            page.on("pageerror", lambda error: errors.append(str(error)))
            page.on("console", lambda message: errors.append(message.text) if message.type == "error" else None)
            page.errors = errors
            yield page
        finally:
            browser.close()

