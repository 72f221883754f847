"""Measurements where they live (SPEC: ``solve --laser FILE --robot FILE``).

The layer between the files on an engineer's laptop and the method: each
side is read from the file its own tool writes, then the two are paired by
point name into the same ``measurement.Measurement`` a merged CSV gives.

- ``laser``: the tracker side. One small function per export format (SPEC
  CSV, SpatialAnalyzer ASCII, plain ``name x y z`` tables); a new format is
  one function and one entry in ``laser.FORMATS``.
- ``robot``: the flange poses. SPEC CSV, a KUKA program ``.dat`` (E6POS/POS/
  FRAME with their FDAT, through ``krl.positions``) and an ABB module's
  robtargets (through ``rapid.robtargets``): the controller files go through
  the same grammars as ``frames``, never a second parser.
- ``pairing``: by name (case-insensitive, KUKA ``XP1`` with ``P1``, a map
  file for anything else).
"""
