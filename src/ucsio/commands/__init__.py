"""One module per subcommand: add_arguments(parser) and run(args) -> exit code."""
from __future__ import annotations

from .. import defaults


def add_uncertainty_options(p, what: str) -> None:
    """--uncertainty N and its noise model, shared by solve and batch."""
    p.add_argument("--uncertainty", type=int, default=0, metavar="N",
                   help=f"Monte Carlo uncertainty {what} from N perturbed copies")
    p.add_argument("--sigma-laser", type=float, default=defaults.SIGMA_LASER, metavar="MM",
                   help=f"laser noise per axis, mm, for the determinacy gate and --uncertainty (default {defaults.SIGMA_LASER})")
    p.add_argument("--sigma-robot", type=float, default=defaults.SIGMA_ROBOT, metavar="MM",
                   help=f"robot noise per axis, mm, for the determinacy gate and --uncertainty (default {defaults.SIGMA_ROBOT})")
    p.add_argument("--seed", type=int, default=0, help="random seed for --uncertainty (default 0)")


def load_inputs(paths: list[str], full: bool = False):
    """Controller files, folders and archives -> ((source, parsed file) pairs,
    errors, files listed as not read). One plain file that cannot be read is
    raised as it is (SPEC's single error); with many, each failure is
    collected and the rest read."""
    from ..parsing.backup import load_all, single_input
    parsed, errors, not_read = load_all(paths, full=full)
    if errors and single_input(paths):
        raise errors[0]
    return parsed, errors, not_read


def report_failures(errors, what: str = "file") -> None:
    """Each unreadable file as one line on stderr (file:line:col: message)."""
    import sys
    for exc in errors:
        print(f"ucsio: {exc}", file=sys.stderr)
    if errors:
        n = len(errors)
        print(f"ucsio: {n} {what}{'s' if n != 1 else ''} could not be read (exit 2)",
              file=sys.stderr)


def options_for(fn, args) -> dict:
    """The parsed options ``fn`` takes, by name: a command's work is a
    function with one keyword per option (its ``dest``), which ``run`` and
    ``ucsio.api`` both call, so the two cannot drift apart. (Read from the
    code object: ``inspect`` is a slow import.)"""
    code = fn.__code__
    names = code.co_varnames[:code.co_argcount + code.co_kwonlyargcount]
    return {n: getattr(args, n) for n in names if hasattr(args, n)}
