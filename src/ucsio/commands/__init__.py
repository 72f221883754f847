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
