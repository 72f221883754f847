"""ucsio: measured user frames for robot controller files (ABB RAPID, KUKA KRL, FANUC).

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

from .errors import UcsioError
from .geometry.frames import Frame, Pose
from .parsing.controller import load, parse
from .parsing.document import Document
from .parsing.model import ControllerFile

__all__ = ["ControllerFile", "Document", "Frame", "Pose", "UcsioError", "load", "parse"]
__version__ = "0.1.0"
