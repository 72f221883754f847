"""ucsio: measured user frames for robot controller files (ABB RAPID, KUKA KRL, FANUC,
Yaskawa, Stäubli VAL3, Universal Robots).

The Python API mirrors the commands in ``ucsio.api`` (frames, check, solve,
diff_frame, taught_points, diff_files, diff_backups, patch, save, batch, plan,
demo: each returns the command's --json document; docs/python-api.md); the
basics are here too::

    import ucsio
    cell = ucsio.load("R01/$config.dat")      # parse a controller file
    for f in cell.frames: print(f.name, f.pose)

Importing ucsio is cheap: numpy, scipy and lark load only where they are used.
"""
from __future__ import annotations

__all__ = ["ControllerFile", "Document", "Frame", "Pose", "UcsioError", "load", "parse"]
__version__ = "0.1.0"

TYPE_CHECKING = False      # what the names below are, for readers and type checkers
if TYPE_CHECKING:
    from .errors import UcsioError
    from .geometry.frames import Frame, Pose
    from .parsing.controller import load, parse
    from .parsing.document import Document
    from .parsing.model import ControllerFile

# The basics, imported when first asked for (PEP 562): the command line
# imports ``ucsio.cli`` through this package, and imports made here would run
# before it sets the collector's thresholds (``cli.entry``).
_WHERE = {"UcsioError": "errors", "Frame": "geometry.frames", "Pose": "geometry.frames",
          "load": "parsing.controller", "parse": "parsing.controller",
          "Document": "parsing.document", "ControllerFile": "parsing.model"}


def __getattr__(name: str):
    where = _WHERE.get(name)
    if where is None:
        raise AttributeError(f"module 'ucsio' has no attribute {name!r}")
    import sys
    __import__(f"{__name__}.{where}")          # not importlib: it imports warnings
    value = getattr(sys.modules[f"{__name__}.{where}"], name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
