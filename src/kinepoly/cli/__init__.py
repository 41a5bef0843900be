"""The command line: the only place that prints or writes files. ``main(argv) -> int`` so tests call it in-process.

One module per command, each with ``add_arguments(parser)`` and ``run(args) -> int`` (the exit
status): ``solve``, ``draw``, ``check``, ``variants``, ``bench``, ``sweep``, ``handout``, ``animate``, ``edit``. The
modules import their heavy dependencies inside ``run``, so building the parser stays cheap; a run imports only the
module of the command it runs, and gives only that command's parser its options (``parser()`` has them all);
``files`` writes a file whole or not at all.

Exit status: 0 solved; 1 an answer was wrong (``check``); 2 the scene or the command is wrong;
3 the mechanism cannot be assembled or is singular at that input; 70 an internal error; 130 interrupted (Ctrl-C);
143 terminated (SIGTERM). Interrupted or terminated, a run leaves every file whole or as it was, and no temporary file.
"""

from __future__ import annotations

import argparse
import gc
import os
import signal
import sys
import threading
from collections.abc import Sequence
from importlib import import_module
from typing import Any

from kinepoly.errors import EXIT_INTERNAL, EXIT_SCENE, KinepolyError, error_text, internal_error_text

__all__ = ["EXIT_INTERNAL", "EXIT_INTERRUPTED", "EXIT_TERMINATED", "HelpFormatter", "error_text", "internal_error_text",
           "main", "main_exit", "parser", "version"]

EXIT_INTERRUPTED = 130
"""Ctrl-C, as a shell reports a process stopped by SIGINT (128 + 2)."""
EXIT_TERMINATED = 143
"""SIGTERM (``kill``, a job's time limit), as a shell reports a process stopped by it (128 + 15)."""


class _Terminated(BaseException):
    """Raised in the main thread by SIGTERM: it unwinds like Ctrl-C, so temporary files are removed."""


def _terminate(signum: int, frame: object) -> None:
    raise _Terminated

_COMMANDS: tuple[tuple[str, str], ...] = (
    ("solve", "solve a scene: a table, the JSON of the contract, or the steps"),
    ("draw", "draw the mechanism and its polygons: SVG, DXF, PNG, PDF, and the construction step by step"),
    ("check", "check a student's answers and diagnose the mistakes"),
    ("variants", "randomised versions of a problem with answer keys"),
    ("bench", ("error against run time of the construction and other methods (closed forms, finite differences, "
               "GEOS), against a 50-digit reference; --sweep over a full turn")),
    ("sweep", "the input over a turn or a range: a CSV of the asked quantities, their plots, centrodes"),
    ("handout", ("a teaching handout: the problem, the construction step by step, the answers; PDF or one web "
                 "page; en, tr, ro or your own")),
    ("animate", ("the mechanism moving over a sweep with its polygons at fixed scales: GIF, MP4 (ffmpeg) or one "
                 "web page")),
    ("edit", ("edit a scene in the browser: drag its points and its input and see the polygons follow; save keeps "
              "the file's comments")),
)
"""Each command's name and help; its module ``kinepoly.cli.<name>`` has its options and its run."""


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # type: ignore[override]
        self.print_usage(sys.stderr)
        command = self.prog.removeprefix("kinepoly").strip()  # "kinepoly: error: " is said once, by _usage_exit
        raise SystemExit(_usage_exit(f"{command}: {message}" if command else message))


class HelpFormatter(argparse.RawDescriptionHelpFormatter):
    """Every option's help ends with its default, "(default: X)", unless it has none or already says it."""

    def _get_help_string(self, action: argparse.Action) -> str | None:
        text = action.help or ""
        default = action.default
        if (default is None or default is False or default is argparse.SUPPRESS or not action.option_strings
                or "default" in text):
            return text
        shown = " ".join(map(str, default)) if isinstance(default, (list, tuple)) else "%(default)s"
        return f"{text} (default: {shown})"


def version() -> str:
    """kinepoly's installed version (the package's metadata), or "unknown" when not installed."""
    from importlib.metadata import PackageNotFoundError
    from importlib.metadata import version as installed

    try:
        return installed("kinepoly")
    except PackageNotFoundError:
        return "unknown"


class _Version(argparse.Action):
    """``--version``: the package's metadata is read when the option is given, not on every start."""

    def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace, values: object,
                 option_string: str | None = None) -> None:
        print(f"kinepoly {version()}")
        parser.exit()


def _usage_exit(message: str) -> int:
    print(f"kinepoly: error: {message}", file=sys.stderr)
    return EXIT_SCENE


_EXIT_STATUS = ("exit status: 0 solved; 1 an answer was wrong (check); 2 the scene or the command is wrong; 3 the "
                "mechanism cannot be assembled or is singular at that input; 70 an internal error; 130 interrupted; "
                "143 terminated")


def parser() -> argparse.ArgumentParser:
    """The whole command line (the README's table of options is generated from it: tools/cli_options.py)."""
    return _parser(every_command=True)


class _Commands(argparse._SubParsersAction):  # type: ignore[type-arg]
    """The subcommands: the command named on the command line has its module imported and its parser given its
    options when it is parsed, so that a run imports and builds only the command it runs."""

    def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace, values: Any,
                 option_string: str | None = None) -> None:
        name = values[0]
        command = self.choices.get(name) if isinstance(self.choices, dict) else None
        if command is not None and command.get_default("run") is None:
            _give_options(name, command)
        super().__call__(parser, namespace, values, option_string)


def _give_options(name: str, command: argparse.ArgumentParser) -> None:
    module = import_module(f"kinepoly.cli.{name}")
    module.add_arguments(command)
    command.set_defaults(run=module.run)


def _parser(every_command: bool = False) -> argparse.ArgumentParser:
    parser = _Parser(prog="kinepoly", description="Velocity and acceleration polygons of planar mechanisms, "
                     "constructed as the graphical method draws them and checked analytically.",
                     epilog=_EXIT_STATUS, formatter_class=HelpFormatter)
    parser.add_argument("--version", action=_Version, nargs=0, help="show program's version number and exit")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser, action=_Commands)
    for name, help_text in _COMMANDS:
        command = sub.add_parser(name, help=help_text, description=help_text[0].upper() + help_text[1:] + ".",
                                 formatter_class=HelpFormatter)
        if every_command:
            _give_options(name, command)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit status. SIGTERM ends it as Ctrl-C does (exit 143)."""
    try:
        args = _parser().parse_args(argv)
    except SystemExit as stop:
        return int(stop.code or 0)
    if threading.current_thread() is not threading.main_thread():  # a signal handler is the main thread's only
        return _run(args)
    previous = signal.signal(signal.SIGTERM, _terminate)
    try:
        return _run(args)
    finally:
        signal.signal(signal.SIGTERM, previous)


def _run(args: argparse.Namespace) -> int:
    try:
        status: int = args.run(args)
        return status
    except KinepolyError as error:
        print(error_text(error), file=sys.stderr)
        return error.exit_code
    except KeyboardInterrupt:  # Ctrl-C: no traceback; every file is written whole or not at all, so none is half
        print("kinepoly: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except _Terminated:
        print("kinepoly: terminated", file=sys.stderr)
        return EXIT_TERMINATED
    except BrokenPipeError:  # the reader (``| head``) left early: what it read is all it wanted
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 0
    except Exception as error:  # noqa: BLE001 - the promise is: never a traceback
        print(internal_error_text(error), file=sys.stderr)
        return EXIT_INTERNAL


def main_exit() -> None:
    """Console-script entry point and ``python -m kinepoly``: ``main``'s status as the process's exit status.

    The run over, what it made is put out of the collector's reach (``gc.freeze``) before the process exits: the
    interpreter's last collection would walk every object only to free them as the process ends, a tenth of a
    four-bar's whole ``kinepoly solve`` (``benchmarks/startup.py``). ``main`` itself, as tests call it, freezes
    nothing."""
    status = main()
    gc.freeze()
    sys.exit(status)
