"""Issue 13, item 6: the command line says what it does, one meaning per option, the README agrees."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import pytest
from tests.cli_support import run

from kinepoly.cli import parser

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
from tools.cli_options import README, _commands, rewrite

COMMANDS = ("solve", "draw", "check", "variants", "bench", "sweep", "handout", "animate", "edit")


def test_version(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, err = run(capsys, "--version")
    assert code == 0
    assert out.startswith("kinepoly ") and "error" not in out + err


def test_a_usage_error_says_kinepoly_once(capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = run(capsys, "--no-such-option")
    assert code == 2
    assert "kinepoly: error: kinepoly" not in err
    code, _, err = run(capsys, "solve")
    assert code == 2 and "kinepoly: error: solve: " in err


@pytest.mark.parametrize("name", COMMANDS)
def test_every_command_has_a_description_and_shows_its_defaults(capsys: pytest.CaptureFixture[str],
                                                                 name: str) -> None:
    command = _commands(parser())[name]
    assert command.description
    text = command.format_help()
    for action in command._actions:
        if action.option_strings and action.default not in (None, False, argparse.SUPPRESS) \
                and action.help != argparse.SUPPRESS:
            assert "default" in (action.help or "") or f"(default: {action.default}" in text, action.dest


@pytest.mark.parametrize("name", COMMANDS)
def test_a_run_gives_its_command_the_options_the_whole_parser_has(capsys: pytest.CaptureFixture[str],
                                                                  name: str) -> None:
    """A run gives only its own command its options (the others are not imported); its help is the full parser's."""
    code, out, _ = run(capsys, name, "--help")
    assert code == 0
    assert out == _commands(parser())[name].format_help()


def test_check_help_lists_every_exit_status() -> None:
    text = _commands(parser())["check"].format_help()
    for status in ("0", "1", "2", "3"):
        assert f"{status} " in text.split("exit status:")[1]


def test_steps_means_the_construction_steps_and_positions_the_count() -> None:
    commands = _commands(parser())
    for name in ("sweep", "animate"):
        assert any("--positions" in a.option_strings for a in commands[name]._actions)
    sweep_steps = next(a for a in commands["sweep"]._actions if "--steps" in a.option_strings)
    assert sweep_steps.help == argparse.SUPPRESS and sweep_steps.dest == "positions"
    assert commands["sweep"].parse_args(["s.toml", "--steps", "12"]).positions == 12


def test_the_readme_table_is_the_parsers() -> None:
    text = README.read_text(encoding="utf-8")
    assert rewrite(text) == text, "run python tools/cli_options.py"
    for name, command in _commands(parser()).items():
        for action in command._actions:
            for flag in action.option_strings:
                if action.help != argparse.SUPPRESS and flag not in ("-h", "--help"):
                    assert f"| `{name}` | `{flag}" in text or f", {flag}" in text, (name, flag)
