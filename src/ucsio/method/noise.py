"""The noise check after a fit (SPEC, "Planning and working points"): do the
residuals agree with the stated noise?

Under the stated per-axis noise σ = √(σ_laser² + σ_robot²), the used
residuals' Σ|e_i|² / σ² is χ² with ν = 3n − 6 degrees of freedom (3n − 9
with a solved TCP). ``ratio`` is the residuals' σ over the stated one, ``p``
the chance of residuals at least this large if the stated σ were right. A
small p says the tracker, the robot or the stated σ is off; the gate has
then already taken the residuals' σ, this says why. Plain math.
"""
from __future__ import annotations

import math

from .quantile import chi2_sf

#: below this p the check says so in words
P_WARN = 0.01


def consistency(sum_e2: float, n_used: int, params: int, sigma_stated: float) -> dict:
    """``ratio``, ``p``, ``dof``, ``sigma_residual`` and ``sigma_stated``; with
    p below P_WARN, ``message``: a plain sentence. Without a stated noise
    (0), ratio and p are None."""
    dof = max(3 * int(n_used) - params, 1)
    s = math.sqrt(max(float(sum_e2), 0.0) / dof)
    out = {"ratio": None, "p": None, "dof": dof, "sigma_residual": s,
           "sigma_stated": float(sigma_stated)}
    if not sigma_stated > 0:
        return out
    ratio = s / sigma_stated
    p = chi2_sf(sum_e2 / (sigma_stated * sigma_stated), dof)
    out.update(ratio=ratio, p=p)
    if p < P_WARN:
        out["message"] = (
            f"the residuals show {s:.3f} mm of noise per axis, {ratio:.1f} times the stated "
            f"{sigma_stated:.3f} mm (√(σ_laser² + σ_robot²)); residuals this large would "
            f"happen with p = {p:.1g} if the stated noise were right (χ², {dof} degrees of "
            "freedom): the tracker, the robot or the stated σ (--sigma-laser, --sigma-robot) "
            "is off. The precision above uses the residuals' σ")
    return out
