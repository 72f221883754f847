"""The defaults SPEC sets, in one place (no heavy imports: the command line
reads them to build its help)."""

THRESHOLD = 1.5          # mm: a leave-one-out residual above this excludes a point
MIN_POINTS = 6           # fewer used points than this rejects a dataset
TOLERANCE = 100.0        # mm: a frame passes when dt_mean is below this
SIGMA_LASER = 0.015      # mm per axis: laser tracker noise for --uncertainty
SIGMA_ROBOT = 0.05       # mm per axis: robot noise for --uncertainty
#: mm per axis: ``plan``'s robot noise unless told (--sigma-robot, --history):
#: an uncalibrated industrial robot's absolute error, not its repeatability.
#: The seed paper's 485 real datasets give a per-axis residual σ (what solve
#: prints as precision.sigma) of mean 0.431 mm, standard deviation 0.240 mm;
#: the mean plus one standard deviation is exceeded by about one robot in six,
#: so a plan is optimistic for few robots (docs/planning.md, "The noise").
PLAN_SIGMA_ROBOT = 0.671       # 0.431 + 0.240
#: mm, ``plan``: default candidate locations lie within this of a planned point
MARGIN = 250.0
REACH = 1000.0           # mm: the determinacy gate judges a point this far from the centroid
#: Largest magnitude of any input number (mm, deg, weight) a fit accepts: beyond
#: it float64 cannot resolve a micrometre (1e9 * 2.2e-16 = 2e-7 mm), squares
#: stay far from overflow, and no cell is 1,000 km across: it is a unit or
#: export error.
MAX_MAGNITUDE = 1e9
#: mm in one unit of the lengths a laser file may be written in (--laser-units)
LENGTH_UNITS = {"mm": 1.0, "m": 1000.0, "in": 25.4}
