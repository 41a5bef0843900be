"""Start-up: ``import kinepoly`` loads none of the solve (its public names are imported when first used), and
``kinepoly --version`` reads the package's metadata only when it is given."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import kinepoly

SRC = str(Path(__file__).resolve().parents[2] / "src")


def _modules(code: str) -> set[str]:
    env = {**os.environ, "PYTHONPATH": SRC}
    out = subprocess.run([sys.executable, "-c", code + "\nimport json, sys; print(json.dumps(sorted(sys.modules)))"],
                         env=env, capture_output=True, text=True, check=True).stdout
    return set(json.loads(out.splitlines()[-1]))


def test_import_kinepoly_loads_no_solve() -> None:
    loaded = _modules("import kinepoly")
    assert not {"numpy", "kinepoly.solution", "kinepoly.present.report", "kinepoly.scene.loader"} & loaded


def test_the_command_line_reads_no_metadata_unless_asked() -> None:
    assert "importlib.metadata" not in _modules("import kinepoly.cli; kinepoly.cli.parser()")


def test_every_public_name_is_there() -> None:
    for name in kinepoly.__all__:
        assert getattr(kinepoly, name) is not None
    assert kinepoly.solve.__module__ == "kinepoly.solution"
    assert kinepoly.Scene.__name__ == "Scene"
