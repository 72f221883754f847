"""The picture (``ucsio view``): a solution's points, residuals and frames in 3D.

``scene`` turns ucsio's own JSON (a SOLUTION.json, a plan, the simulated frame
of a controller file) into one plain dict of numbers; ``page`` writes that
dict as a self-contained HTML page, three.js inlined (or linked, for a report
that shares one copy). Plain Python: three.js is loaded by the page only.
"""
