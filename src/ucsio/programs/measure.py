"""The robot's measurement program, in the controller's language (``ucsio
program --measure PLAN.csv CONTROLLER --frame NAME --tool NAME -o OUT``,
``demo --out``, ``api.measurement_program``).

The generic part: read the plan (``readers.plan.read_plan``) and the controller,
find the frame and the tool, compute each planned point's pose of the
written tool in the frame (and its approach pose), and hand them to the
vendor's ``measurement_program``. The position written is the plan's
laser_x/y/z itself: the program moves in the simulated frame, so the robot
reaches the point the plan means as far as that frame is right.
"""
from __future__ import annotations

import os

from ..errors import UcsioError

DOWN = (180.0, 0.0, 0.0)    # W, P, R: the TCP's z along the frame's -Z


def make(plan, controller, frame: str, *, tool=None, tcp=None, approach: float = 100.0,
         approach_dir=None, orientation=None, spread=None, speed: float = 100.0,
         dwell=None, output=None):
    """The program (``vendors.common.measure.MeasureProgram``; nothing
    written), in the language of CONTROLLER's vendor."""
    from .. import vendors
    from ..parsing.backup import load_one
    from ..review.names import find_frame
    from ..vendors.common.measure import Settings

    _check_settings(approach, speed, dwell)
    cf = load_one(os.fspath(controller))
    writer = vendors.get(cf.vendor)
    if writer.measurement_program is None:
        raise UcsioError(vendors.missing(cf.vendor, "measurement program writer"),
                         file=cf.path)
    vendors.program_vendor(output, cf.vendor)     # -o names another vendor's program: refused
    user = find_frame(cf, frame)
    # fixed in robot world: on the robot's base, or (ABB's work objects, a KUKA base) on the world
    _check_parent(user, ("robot", "world"), f"--frame {frame}", "a user frame")
    held, offset = _tool(cf, tool, tcp)
    planned, warnings = _plan(plan)
    rotations = _rotations(planned, user, held, orientation, writer)
    rotations = _spread(rotations, spread, planned)
    direction = _direction(approach_dir)
    targets = [_target(n, line, xyz, r, offset, approach, direction)
               for n, line, xyz, r in zip(planned.names, planned.lines, planned.laser,
                                          rotations)]
    settings = Settings(speed, dwell, approach, os.fspath(plan),
                        os.path.basename(os.fspath(plan)), _program_name(output))
    result = writer.measurement_program(user, held, targets, settings)
    result.warnings = warnings + list(result.warnings)
    _check_suffix(result, output)
    result.read_back = _read_back(result, cf, held, offset, tcp, output)
    return result


def _check_suffix(result, output) -> None:
    """A program of several files (KUKA's .src and .dat) is named by its
    main file: -o must end as that file does, so the others go beside it."""
    if result.suffix is None or not output or output == "-":
        return
    if os.path.splitext(output)[1].lower() != result.suffix:
        others = ", ".join(s for s, _ in result.companions)
        raise UcsioError(f"-o {output}: a {result.vendor.upper()} measurement program is "
                         f"NAME{result.suffix} with its {others} beside it: -o "
                         f"NAME{result.suffix}")


def _read_back(result, cf, held, offset, tcp, output) -> dict:
    """How ``solve`` reads the program back as the robot side: ``robot``,
    the file it reads (KUKA's .dat); ``config``, the files that hold its
    frames (the tool's, then the controller's); the names its positions are
    taught with where the vendor asks (ABB's ``robot_tool`` and
    ``robot_wobj``); the reflector (``tool`` FILE:NAME or ``tcp`` x,y,z); and
    ``solve``, the command line with them."""
    import shlex
    robot = output if output not in (None, "-") else "PROGRAM" + (result.suffix or "")
    if result.robot_suffix is not None:
        robot = beside(robot, result.robot_suffix)
    config = [f for f in dict.fromkeys([held.file if held is not None else None, cf.path]) if f]
    reflector = ({"tool": f"{held.file}:{held.name}"} if held is not None else
                 {"tcp": ",".join(f"{v:g}" for v in offset)})
    words = ["ucsio", "solve", "--laser", "TRACKER.csv", "--robot", robot]
    for f in config:
        words += ["--config", f]
    for key, value in {**result.robot_side, **reflector}.items():
        words += ["--" + key.replace("_", "-"), value]
    return {"robot": robot, "config": config, **result.robot_side, **reflector,
            "solve": " ".join(shlex.quote(w) for w in words)}


def _check_settings(approach: float, speed: float, dwell) -> None:
    """Finite, and what a move can be: a distance and a speed above 0, a
    wait of 0 or more."""
    import math
    for option, value, least in (("--approach", approach, 0.0), ("--speed", speed, 0.0),
                                 ("--dwell", dwell, None)):
        if value is None:
            continue
        if not math.isfinite(value) or (value <= least if least is not None else value < 0):
            bound = "above 0" if least is not None else "0 or more"
            raise UcsioError(f"{option} {value:g}: a finite number {bound}")


def _plan(plan):
    from ..readers.plan import read_plan
    planned, warnings = read_plan(plan, joint=False)
    if not len(planned.names):
        raise UcsioError("the plan has no points", file=os.fspath(plan))
    return planned, warnings


def _tool(cf, tool, tcp):
    """(the tool frame or None, the TCP offset the written pose leaves out):
    --tool NAME (in CONTROLLER) or FILE:NAME; --tcp X,Y,Z writes the flange."""
    from ..review.names import find_frame
    if (tool is None) == (tcp is None):
        raise UcsioError("give the reflector's tool: --tool NAME (a tool of the controller) or "
                         "--tcp X,Y,Z (the flange's positions are written)")
    if tcp is not None:
        from ..readers.options import parse_tcp
        return None, tuple(parse_tcp(tcp) if isinstance(tcp, str) else tcp)
    file, sep, name = tool.rpartition(":")
    if sep and file and os.path.exists(file):
        from ..parsing.controller import load
        cf = load(file)
    else:
        name = tool
    held = find_frame(cf, name)
    _check_parent(held, ("flange",), f"--tool {tool}", "a tool the robot holds")
    return held, (0.0, 0.0, 0.0)


def _check_parent(frame, kinds: tuple[str, ...], option: str, what: str) -> None:
    if frame.pose is None or frame.parent.kind not in kinds:
        raise UcsioError(f"{option}: {frame.name} is not {what} (its parent: "
                         f"{frame.parent})", file=frame.file, line=frame.line)


def _rotations(planned, user, held, orientation, writer):
    """Each point's rotation of the written tool in the frame: the plan's
    flange orientation where it gives one, else --orientation (the vendor's
    angles), else the tool pointing down the frame's -Z."""
    from ..geometry.frames import Pose
    if planned.flange is not None:
        if orientation is not None:
            raise UcsioError("the plan gives the orientations (its robot_* columns); "
                             "--orientation is for a plan without them")
        import numpy as np
        frame_r = np.asarray(user.pose.matrix, dtype=float).T
        tool_r = np.eye(3) if held is None else np.asarray(held.pose.matrix, dtype=float)
        return [frame_r @ f[:3, :3] @ tool_r for f in planned.flange]
    if orientation is None:
        one = Pose.from_wpr(0, 0, 0, *DOWN)
    else:
        abc = dict(zip(writer.angles.keys, _three(orientation, "--orientation")))
        one = Pose.from_abc(0, 0, 0, abc["a"], abc["b"], abc["c"])
    return [one.matrix] * len(planned.names)


def _spread(rotations, spread, planned):
    """Each point's rotation turned by ``method.spread``'s pattern (the one
    ``plan --tcp solve`` predicts): about the written tool's own axes, so
    the reflector stays on the point and the flange moves round it."""
    if spread is None:
        return rotations
    import numpy as np

    from ..method.spread import check, tilts
    check(spread)
    if planned.flange is not None:
        raise UcsioError("--spread: the plan gives each point's orientation (its robot_* "
                         "columns); the spread is theirs", file=planned.path)
    return [np.asarray(r, dtype=float) @ t for r, t in zip(rotations, tilts(len(rotations),
                                                                              spread))]


def _three(value, option: str) -> list[float]:
    """Three finite numbers: "A,B,C" from the command line, a sequence from
    Python."""
    from ..readers.options import parse_values
    text = value if isinstance(value, str) else ",".join(str(float(v)) for v in value)
    return parse_values(text, 3, option)


def _direction(approach_dir):
    if approach_dir is None:
        return (0.0, 0.0, 1.0)
    d = _three(approach_dir, "--approach-dir")
    norm = sum(v * v for v in d) ** 0.5
    if not norm > 1e-9:
        raise UcsioError("--approach-dir: a direction is not zero")
    return tuple(v / norm for v in d)


def _target(name, line, xyz, r, offset, approach, direction):
    """The written tool's pose at the point (the flange's where ``offset``,
    --tcp, is not written as a tool) and above it."""
    import numpy as np
    from ..geometry.frames import Pose
    from ..vendors.common.measure import Target
    m = np.asarray(r, dtype=float)
    at = np.asarray(xyz, dtype=float) - m @ np.asarray(offset, dtype=float)
    above = at + approach * np.asarray(direction)
    return Target(name, line, Pose.from_matrix(m, tuple(at)),
                  Pose.from_matrix(m, tuple(above)))


def _program_name(output) -> str:
    import re
    if output is None or output == "-":
        return "MEASURE"
    stem = os.path.splitext(os.path.basename(output))[0].upper()
    if not re.fullmatch(r"[A-Z][A-Z0-9_]{0,31}", stem):
        raise UcsioError(f"-o {output}: {stem!r} is not a program name (a letter, then "
                         "letters, digits and _, up to 32): the controller names the program "
                         "after its file")
    return stem


def files_of(result, path: str) -> list[str]:
    """The names of the files a program is written as at ``path``: its own,
    and its companions' beside it (KUKA's .dat)."""
    return [os.path.basename(path)] + [os.path.basename(beside(path, suffix))
                                       for suffix, _ in result.companions]


def save(result, path: str) -> str:
    """Write the program, its companions first (KUKA's .dat before its
    .src), each atomically; no file is ever replaced: all are written or,
    should one fail, none stays (those already written are removed)."""
    from ..files import atomic_write
    files = [(beside(path, suffix), text.encode("ascii")) for suffix, text in result.companions]
    files.append((path, result.data))

    def refuse_existing(names):
        for name in names:
            if os.path.lexists(name):
                raise UcsioError("exists: a measurement program is never written over a "
                                 "file; choose another -o", file=name)
    names = [name for name, _ in files]
    refuse_existing(names)
    done: list[str] = []
    try:
        for k, (name, data) in enumerate(files):
            # just before each rename: this file and those still to come are free
            written, _ = atomic_write(name, data, check=lambda: refuse_existing(names[k:]))
            done.append(written)
    except BaseException:
        for name in done:
            try:
                os.unlink(name)
            except OSError:
                pass
        raise
    result.written = done[-1]
    texts = [result.text] + [t for _, t in result.companions]
    result.files = list(zip([done[-1]] + done[:-1], texts))
    return done[-1]


def beside(path: str, suffix: str) -> str:
    """``path`` with ``suffix`` for its own, in its case (M.SRC: M.DAT)."""
    stem, own = os.path.splitext(path)
    return stem + (suffix.upper() if own.isupper() else suffix)
