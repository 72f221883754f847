"""The defaults SPEC sets, in one place (no heavy imports: the command line
reads them to build its help)."""

THRESHOLD = 1.5          # mm: a leave-one-out residual above this excludes a point
MIN_POINTS = 6           # fewer used points than this rejects a dataset
TOLERANCE = 100.0        # mm: a frame passes when dt_mean is below this
SIGMA_LASER = 0.015      # mm per axis: laser tracker noise for --uncertainty
SIGMA_ROBOT = 0.05       # mm per axis: robot noise for --uncertainty
