"""A rack's rolling step: its slide's line is drawn through the tip of its guide's point under the pitch
point (the pole for a guide on the frame), never through the tip the step is about to find."""

from __future__ import annotations

import pytest
from tests.cli_support import run
from tests.scenes import EXAMPLES


def test_the_racks_slide_line_starts_at_its_guides_point(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run(capsys, "solve", str(EXAMPLES / "rack-pinion.toml"), "--steps")
    assert code == 0, err
    assert "through o draw the line of P23@3: parallel to the rack's slide" in out
    assert "laid from o′ draw the line of P23@3: parallel to the rack's slide" in out
    assert "through p23@3 draw" not in out and "laid from p′23@3" not in out
