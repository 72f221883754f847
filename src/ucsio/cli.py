"""The ``ucsio`` command: argument parsing and exit codes, nothing else.

Each subcommand lives in ``ucsio.commands.<name>`` with ``add_arguments`` and
``run``; those modules import nothing heavy at the top, so ``ucsio frames``
never pays for scipy.
"""
from __future__ import annotations

import os
import sys

from .parsing import regex


def gettext_stand_in():
    """A ``gettext`` module with argparse's two functions, untranslated;
    any other name is the real module's (imported then, on first use)."""
    stand_in = type(sys)("gettext")
    stand_in.gettext = lambda message: message
    stand_in.ngettext = lambda singular, plural, n: singular if n == 1 else plural

    def real(name: str):
        if name.startswith("__"):       # the import system asking (__path__, __spec__, …)
            raise AttributeError(name)
        if sys.modules.get("gettext") is stand_in:
            del sys.modules["gettext"]
        return getattr(__import__("gettext"), name)

    stand_in.__getattr__ = real     # a module's __getattr__ (PEP 562)
    return stand_in


if "argparse" not in sys.modules and "gettext" not in sys.modules:
    # argparse imports gettext, and its first message looks for translation
    # catalogues (importing locale, a verbose regex, a stat per language):
    # about a tenth of a short command's start-up, for argparse's few English
    # words, which no Python we support ships a catalogue of. The stand-in
    # defines the two functions argparse takes and hands any other name to the
    # real module; it is removed at once: anything importing gettext later
    # gets the real one.
    _stand_in = sys.modules["gettext"] = gettext_stand_in()
    try:
        import argparse
    finally:
        if sys.modules.get("gettext") is _stand_in:
            del sys.modules["gettext"]
else:
    import argparse

from . import __version__
from .errors import UcsioError, UsageError, did_you_mean

COMMANDS = {
    "frames": "list every frame in controller files, backup folders or .zip archives",
    "check": "parse, prove the byte-exact round trip, and lint (files, folders, archives)",
    "solve": "fit the measured UCS to laser/robot point pairs (Horn's method)",
    "diff": "simulated vs measured frame, or every frame of two files or two backups",
    "patch": "write a frame back into a controller file",
    "program": "a program that sets a measured frame (a FANUC TP program, a Yaskawa job), "
               "or with --measure the measurement program",
    "batch": "solve and diff many datasets from a TOML manifest",
    "plan": "plan a measurement: the predicted error where the robot works, what to change",
    "view": "a self-contained HTML page: the solution's points, residuals and frames in 3D",
    "demo": "the whole job on shipped example cells",
}


def _columns() -> int:
    """The terminal's width as shutil.get_terminal_size finds it, without
    importing shutil (and bz2, lzma, fnmatch with it): argparse builds a help
    formatter for every option it is given, and each one asked shutil."""
    try:
        columns = int(os.environ["COLUMNS"])
    except (KeyError, ValueError):
        columns = 0
    if columns <= 0:
        try:
            columns = os.get_terminal_size(sys.__stdout__.fileno()).columns
        except (AttributeError, ValueError, OSError):
            columns = 0
    return columns if columns > 0 else 80


class _Help(argparse.HelpFormatter):
    def __init__(self, prog, indent_increment=2, max_help_position=24, width=None):
        super().__init__(prog, indent_increment, max_help_position,
                         _columns() - 2 if width is None else width)


class _RawHelp(_Help, argparse.RawDescriptionHelpFormatter):
    pass


class _Parser(argparse.ArgumentParser):
    """Options are never abbreviated (``--in-plac`` must not mean
    ``--in-place``); usage errors raise UsageError instead of exiting, so
    ``main`` reports them like any bad input, with the nearest real name."""

    def __init__(self, *args, **kwargs):
        kwargs["allow_abbrev"] = False
        kwargs.setdefault("formatter_class", _Help)
        super().__init__(*args, **kwargs)

    def error(self, message: str):
        m = _INVALID_CHOICE.search(message)
        if m:
            message = m.group(1) + did_you_mean(m.group(2), m.group(3).replace("'", "").split(", "))
        raise UsageError(f"{self.prog}: {message} (see {self.prog} --help)")


_INVALID_CHOICE = regex.lazy(r"^(argument [^:]+: invalid choice: '(.*)') \(choose from (.*)\)$")


def _refuse_unknown(parser: argparse.ArgumentParser, args, extras: list[str]) -> None:
    """Arguments the chosen subcommand does not know: named, with the nearest
    option of that subcommand suggested."""
    sub = None
    for action in parser._actions:                      # the subcommand's own parser
        if isinstance(action, argparse._SubParsersAction):
            sub = action.choices.get(getattr(args, "command", None))
    target = sub or parser
    message = "unrecognized arguments: " + " ".join(extras)
    first = next((e for e in extras if e.startswith("-") and len(e) > 1), None)
    if first is not None:
        options = [o for a in target._actions for o in a.option_strings]
        message += did_you_mean(first.split("=", 1)[0], options)
    raise UsageError(f"{target.prog}: {message} (see {target.prog} --help)")


def _registry():
    from .vendors import VENDORS      # the registry alone: no vendor's package is imported
    return VENDORS


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The argument parser; given a ``command``, only that subcommand (its
    module imported, its options built): building all seven was a large part
    of a short command's start-up. Without one (``ucsio --help``, a mistyped
    command), every subcommand, so help and suggestions list them all."""
    parser = _Parser(
        prog="ucsio",
        description="Measured user frames for robot controller files: "
                    + ", ".join(e.title for e in _registry()) + ".")
    parser.add_argument("--version", action="version", version=f"ucsio {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    for name, help_text in COMMANDS.items():
        if command is not None and name != command:
            continue
        __import__(f"ucsio.commands.{name}")       # not importlib: it imports warnings
        module = sys.modules[f"ucsio.commands.{name}"]
        p = sub.add_parser(name, help=help_text, description=module.__doc__,
                           formatter_class=_RawHelp)
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


_NEGATIVE_LIST = regex.lazy(r"^-\d*\.?\d+([eE][-+]?\d+)?([,;][-+\d.eE]*)*$")


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else [str(a) for a in argv]
    want_json = _wants_json(argv)          # before parsing: a usage error is JSON too
    try:
        parser = build_parser(argv[0] if argv and argv[0] in COMMANDS else None)
        args, extras = parser.parse_known_args(argv)
        if extras:
            _refuse_unknown(parser, args, extras)
        want_json = bool(getattr(args, "json", False)) \
            or getattr(args, "output_format", None) == "json"
        return int(args._module.run(args) or 0)
    except UcsioError as exc:
        report_error(exc, want_json)
        return exc.exit_code
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:
        return 0
    except RecursionError:      # a guard was missed somewhere: still one line, not a traceback
        report_error(UcsioError("input nested too deeply to read"), want_json)
        return 2
    except MemoryError:
        report_error(UcsioError("out of memory: the input is too large for this machine"),
                     want_json)
        return 2
    except Exception as exc:    # a bug: one line saying so; UCSIO_DEBUG=1 shows the traceback
        if os.environ.get("UCSIO_DEBUG"):
            raise
        report_error(UcsioError(f"internal error (a bug in ucsio: please report it with the "
                                f"command and its input; UCSIO_DEBUG=1 shows where): "
                                f"{type(exc).__name__}: {exc}"), want_json)
        return 2


def _wants_json(argv: list[str]) -> bool:
    """--json, or check's --output-format json (its other spelling)."""
    return "--json" in argv or "--output-format=json" in argv or any(
        a == "--output-format" and b == "json" for a, b in zip(argv, argv[1:]))


def report_error(exc: UcsioError, want_json: bool) -> None:
    """One line on stderr; with --json also SPEC's error object on stdout."""
    prefix = "" if isinstance(exc, UsageError) else "ucsio: "   # a usage line names its command
    print(f"{prefix}{exc}", file=sys.stderr)
    if want_json:
        from .output import emit_json
        emit_json({"error": exc.as_dict()})


def entry() -> None:
    # The command line's process: the cyclic collector's first generation
    # every 50,000 allocations instead of 700. A short command made of
    # imports, an argument parser and one file's objects (few of them in
    # cycles) spent 4 % of its time in collections that found nothing; a
    # long one still collects, so a large backup's documents are freed.
    import gc
    gc.set_threshold(50_000, 20, 100)
    code = main()
    regex.save_cache()      # patterns compiled for the first time, for the next run
    # Everything is written; skip the interpreter's teardown (freeing every
    # module and object), tens of milliseconds of a short command for nothing.
    try:
        sys.stdout.flush()
        sys.stderr.flush()
    except (BrokenPipeError, ValueError):   # a reader that went away, or a closed stream
        pass
    os._exit(code)


if __name__ == "__main__":
    entry()
