"""ucsio: measured user frames for ABB RAPID and KUKA KRL controller files.

Python API (everything the command line does is callable from here)::

    import ucsio
    cell = ucsio.load("R01/$config.dat")      # parse a controller file
    for f in cell.frames: print(f.name, f.pose)
"""
from __future__ import annotations

from .controller import ControllerFile, load, parse
from .document import Document
from .errors import UcsioError
from .frames import Frame, Pose

__all__ = ["ControllerFile", "Document", "Frame", "Pose", "UcsioError", "load", "parse"]
__version__ = "0.1.0"
