"""One module per subcommand: add_arguments(parser) and run(args) -> exit code."""
from __future__ import annotations


def add_uncertainty_options(p, what: str) -> None:
    """--uncertainty N and its noise model, shared by solve and batch."""
    p.add_argument("--uncertainty", type=int, default=0, metavar="N",
                   help=f"Monte Carlo uncertainty {what} from N perturbed copies")
    p.add_argument("--sigma-laser", type=float, default=0.015, metavar="MM",
                   help="laser noise per axis for --uncertainty (default 0.015)")
    p.add_argument("--sigma-robot", type=float, default=0.05, metavar="MM",
                   help="robot noise per axis for --uncertainty (default 0.05)")
    p.add_argument("--seed", type=int, default=0, help="random seed for --uncertainty (default 0)")
