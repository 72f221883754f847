"""A synthetic FANUC cell for the measurement and taught-point tests: a
sysframe.va and TP programs written from known frames and flange poses
(scipy's Rotation the reference: from_euler("xyz", [w, p, r]) is FANUC's
Rz(r)·Ry(p)·Rx(w))."""
from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation


def pose(x, y, z, w, p, r) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3] = Rotation.from_euler("xyz", [w, p, r], degrees=True).as_matrix()
    T[:3, 3] = (x, y, z)
    return T


def wpr(T) -> tuple[float, float, float, float, float, float]:
    w, p, r = Rotation.from_matrix(T[:3, :3]).as_euler("xyz", degrees=True)
    x, y, z = T[:3, 3]
    return (x, y, z, w, p, r)


def inv(T) -> np.ndarray:
    out = np.eye(4)
    out[:3, :3] = T[:3, :3].T
    out[:3, 3] = -T[:3, :3].T @ T[:3, 3]
    return out


def fnum(v: float, decimals: int = 3) -> str:
    """As the controller prints: no leading zero below 1 (.140, -.080)."""
    s = f"{v:.{decimals}f}"
    if s.startswith("0.") and float(s) != 0:
        s = s[1:]
    elif s.startswith("-0."):
        s = "-" + s[2:]
    return s


def sysframe(uframes: dict, utools: dict, groups: int = 2, n_uf: int = 9,
             n_ut: int = 10) -> str:
    """A sysframe.va: ``uframes``/``utools`` {(group, n): (x, y, z, w, p, r)};
    the other elements zero."""
    out = []
    for rec, frames, n in (("$MNUFRAME", uframes, n_uf), ("$MNUTOOL", utools, n_ut)):
        out.append(f"[*SYSTEM*]{rec}  Storage: SHADOW  Access: RW  : ARRAY[{groups},{n}] OF "
                   "POSITION")
        for g in range(1, groups + 1):
            for k in range(1, n + 1):
                x, y, z, w, p, r = frames.get((g, k), (0.0,) * 6)
                cfg = "N U T, 0, 0, 0" if g == 1 else ""
                out += [f"    [{g},{k}] = ", f"  Group: {g}   Config: {cfg}",
                        f"  X:{fnum(x):>10}   Y:{fnum(y):>10}   Z:{fnum(z):>10}",
                        f"  W:{fnum(w):>10}   P:{fnum(p):>10}   R:{fnum(r):>10}"]
        out.append("")
    return "\r\n".join(out) + "\r\n"


def position(number: int, groups: list, comment: str | None = None, decimals: int = 6) -> str:
    """One /POS entry; ``groups`` a list of (group, uf, ut, values) with
    values (x, y, z, w, p, r) or {"J1": ...} for joints."""
    head = f'P[{number}:"{comment}"]{{' if comment else f"P[{number}]{{"
    lines = [head]
    for g, uf, ut, values in groups:
        lines.append(f"   GP{g}:")
        if isinstance(values, dict):
            lines.append(f"\tUF : {uf}, UT : {ut},\t")
            items = [f"{k}= {fnum(v, decimals):>9} deg" for k, v in values.items()]
            lines.append("\t" + ",\t".join(items))
        else:
            x, y, z, w, p, r = values
            lines.append(f"\tUF : {uf}, UT : {ut},\t\tCONFIG : 'N U T, 0, 0, 0',")
            lines.append(f"\tX = {fnum(x, decimals):>9}  mm,\tY = {fnum(y, decimals):>9}  mm,\t"
                         f"Z = {fnum(z, decimals):>9}  mm,")
            lines.append(f"\tW = {fnum(w, decimals):>9} deg,\tP = {fnum(p, decimals):>9} deg,\t"
                         f"R = {fnum(r, decimals):>9} deg")
    lines.append("};")
    return "\r\n".join(lines)


def program(name: str, points: list[str]) -> str:
    """A TP program moving to P[1..n] (its /MN a line per point), /POS ``points``."""
    mn = [f"{i + 1:4d}:L P[{i + 1}] 500mm/sec FINE    ;" for i in range(len(points))]
    return "\r\n".join([f"/PROG  {name}", "/ATTR", "OWNER\t\t= MNEDITOR;", 'COMMENT\t\t= "";',
                        "PROG_SIZE\t= 0;", f"LINE_COUNT\t= {len(points)};",
                        "DEFAULT_GROUP\t= 1,*,*,*,*;", "/MN", *mn, "/POS", *points,
                        "/END"]) + "\r\n"


def registers(entries: list, groups: int = 2, n: int = 20) -> str:
    """A posreg.va: ``entries`` [(group, n, comment, values)] with values
    (x, y, z, w, p, r), {"J1": ...} for joints, or None (Uninitialized)."""
    given = {(g, k): (c, v) for g, k, c, v in entries}
    out = [f"[*POSREG*]$POSREG  Storage: SHADOW  Access: RW  : ARRAY[{groups},{n}] OF Position "
           "Reg"]
    for g in range(1, groups + 1):
        for k in range(1, n + 1):
            comment, values = given.get((g, k), ("", None))
            if values is None:
                out.append(f"    [{g},{k}] =   '{comment}' Uninitialized")
            elif isinstance(values, dict):
                out.append(f"    [{g},{k}] =   '{comment}'   Group: {g}")
                items = [f"{j} = {fnum(v):>9} deg" for j, v in values.items()]
                out += ["  " + "   ".join(items[:3]) + " ", "  " + "   ".join(items[3:]) + " ",
                        ""]
            else:
                x, y, z, w, p, r = values
                out += [f"    [{g},{k}] =   '{comment}' ",
                        f"  Group: {g}   Config: N U T, 0, 0, 0",
                        f"  X:{fnum(x):>10}   Y:{fnum(y):>10}   Z:{fnum(z):>10}",
                        f"  W:{fnum(w):>10}   P:{fnum(p):>10}   R:{fnum(r):>10}"]
    return "\r\n".join(out) + "\r\n"


class Cell:
    """The truth: the UCS in world (``ucs``), the simulated user frame UF2
    (a few mm and a fraction of a degree off), the teaching tool UT3, the
    reflector tool UT4 (its translation the TCP), laser points in the UCS
    and flange poses that reach them with the reflector."""

    UF = (1500.125, -420.5, 310.25, 0.35, -0.2, 88.5)          # simulated UF2
    UT = (12.5, -4.25, 210.0, 180.0, -30.0, 15.0)               # teaching tool UT3
    TCP = (-20.5, 35.25, 150.125)                               # reflector: UT4's translation

    def __init__(self, seed: int = 7, n: int = 8):
        rng = np.random.default_rng(seed)
        self.uf = pose(*self.UF)
        self.ut = pose(*self.UT)
        self.ucs = self.uf @ pose(3.2, -1.7, 2.4, 0.15, -0.1, 0.3)   # the real UCS
        self.laser = np.array([[0, 0, 0], [900, 0, 0], [0, 700, 0], [900, 700, 0],
                               [450, 350, 250], [100, 600, 180], [800, 100, 220],
                               [450, -50, 90]], dtype=float)[:n]
        c = np.array(self.TCP)
        self.flanges = []
        for L in self.laser:
            R = Rotation.from_euler("xyz", [180 + rng.uniform(-25, 25), rng.uniform(-25, 25),
                                            rng.uniform(-60, 60)], degrees=True).as_matrix()
            T = np.eye(4)
            T[:3, :3] = R
            T[:3, 3] = (self.ucs @ np.append(L, 1))[:3] - R @ c
            self.flanges.append(T)
        self.names = [f"M{i + 1}" for i in range(n)]

    def taught(self, uf=None, ut=None):
        """Each flange pose as a position of the teaching tool in the user frame."""
        uf = self.uf if uf is None else uf
        ut = self.ut if ut is None else ut
        return [wpr(inv(uf) @ T @ ut) for T in self.flanges]

    def sysframe_text(self) -> str:
        return sysframe({(1, 2): self.UF, (1, 1): (100.0, 200.0, 300.0, 0.0, 0.0, 45.0),
                         (2, 2): (5.0, 6.0, 7.0, 0.0, 0.0, 0.0)},
                        {(1, 3): self.UT, (1, 4): (*self.TCP, 0.0, 0.0, 0.0)})

    def laser_text(self) -> str:
        return "".join(f"{nm} {fnum(x, 6)} {fnum(y, 6)} {fnum(z, 6)}\n"
                       for nm, (x, y, z) in zip(self.names, self.laser))
