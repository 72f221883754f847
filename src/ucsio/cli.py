"""The ``ucsio`` command: argument parsing and exit codes, nothing else.

Each subcommand lives in ``ucsio.commands.<name>`` with ``add_arguments`` and
``run``; those modules import nothing heavy at the top, so ``ucsio frames``
never pays for scipy.
"""
from __future__ import annotations

import argparse
import importlib
import re
import sys

from . import __version__
from .errors import UcsioError

COMMANDS = {
    "frames": "list every frame in controller files",
    "check": "parse, prove the byte-exact round trip, and lint",
    "solve": "fit the measured UCS to laser/robot point pairs (Horn's method)",
    "diff": "simulated vs measured frame, or every frame of two files",
    "patch": "write a frame back into a controller file",
    "batch": "solve and diff many datasets from a TOML manifest",
    "demo": "the whole job on shipped example cells",
}


class _Parser(argparse.ArgumentParser):
    """Usage errors as one line on stderr and exit 2, like every other bad input."""

    def error(self, message: str):
        self.exit(2, f"{self.prog}: {message} (see {self.prog} --help)\n")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="ucsio",
        description="Measured user frames for ABB RAPID and KUKA KRL controller files.")
    parser.add_argument("--version", action="version", version=f"ucsio {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    for name, help_text in COMMANDS.items():
        module = importlib.import_module(f"ucsio.commands.{name}")
        p = sub.add_parser(name, help=help_text, description=module.__doc__,
                           formatter_class=argparse.RawDescriptionHelpFormatter)
        _accept_negative_lists(p)
        p.add_argument("--json", action="store_true", help="machine-readable output on stdout")
        module.add_arguments(p)
        p.set_defaults(_module=module)
    return parser


def _accept_negative_lists(p: argparse.ArgumentParser) -> None:
    """Let ``--tcp -20.67,89.73,33.44`` and ``--set -5,1,2,0,0,0`` through:
    argparse takes a value starting with '-' for an option unless it looks
    like a negative number, and its idea of one has no commas. (A private
    attribute, so guarded: without it the ``--set=-5,...`` form still works.)"""
    if hasattr(p, "_negative_number_matcher"):
        p._negative_number_matcher = _NEGATIVE_LIST


_NEGATIVE_LIST = re.compile(r"^-\d*\.?\d+([eE][-+]?\d+)?([,;][-+\d.eE]*)*$")


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args._module.run(args) or 0)
    except UcsioError as exc:
        print(f"ucsio: {exc}", file=sys.stderr)
        return exc.exit_code
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:
        return 0


def entry() -> None:
    sys.exit(main())


if __name__ == "__main__":
    entry()
