"""Writing a Universal Robots frame back: a TCP's ``offset``, a point
feature's pose, a plane's frame with its points.

Numbers are written as PolyScope writes them, the way Java prints a double
(``0.5000163917999046``, ``1.297533804394462E-10``): the shortest digits that
read back as the same double, so a value reads back exactly. A number that
does not move (within 1e-12 m, or the rotation within 1e-9 deg) keeps its
text. A plane is written whole (../shared/corpus/ur/README.md): its frame
(``firstPoint``), ``secondPoint`` (the origin plus 1 m along y, the frame's
orientation), its taught points, which become the 3-point points of the new
frame (origin, +X and XY at ``three_points.DEFAULT_DISTANCE``), each
keeping its tool orientation turned with the frame, and ``thirdPoint``,
which PolyScope keeps equal to the third taught point.
"""
from __future__ import annotations

from ...errors import UcsioError
from ...geometry import rotations as rot
from ...geometry.frames import Pose
from ..common.write import Change
from .installation import COMPONENTS, TAUGHT

TYPE_CHECKING = False      # typing costs a cold start; annotations are strings
if TYPE_CHECKING:
    from ...geometry.frames import Frame
    from ...parsing.model import ControllerFile

SAME_METRES = 1e-12
SAME_DEGREES = 1e-9
THREE_POINT_DISTANCE = 200.0    # mm: SPEC's default (--three-point-distance)
SECOND_POINT = 1000.0           # mm: secondPoint stands 1 m along the plane's y

SAFETY = ("{name}: the safety configuration uses this feature (a safety plane's sourceFeatureId "
          "names it, under the safety checksum): patched, the safety plane would silently stay "
          "where it was; not patched, nothing written (redefine the feature and its safety "
          "plane on the pendant)")
JOINTS = ("{name}: the joint positions stored with its points (jointPositionVector) are the "
          "old ones: ucsio has no kinematics to compute them; the poses are written, and "
          "PolyScope shows the new frame (check it on the pendant before running)")


def java_double(value: float) -> str:
    """``value`` as Java's Double.toString writes it: plain from 1e-3 to 1e7
    (``0.5``, ``-0.6097062373626966``), else ``d.dddE±n`` (``1.0E-4``,
    ``1.297533804394462E-10``); the shortest digits that read back as the
    same double (Python's repr finds them)."""
    value = float(value) + 0.0          # never -0.0
    if value == 0.0 or 1e-3 <= abs(value) < 1e7:
        return repr(value)              # plain in this range, with a decimal point
    sign, digits, exponent = _shortest(value)
    mantissa = str(digits[0]) + "." + ("".join(map(str, digits[1:])) or "0")
    return f"{'-' if sign else ''}{mantissa}E{exponent + len(digits) - 1}"


def _shortest(value: float) -> tuple[int, tuple[int, ...], int]:
    from decimal import Decimal
    sign, digits, exponent = Decimal(repr(value)).as_tuple()
    while len(digits) > 1 and digits[-1] == 0:
        digits, exponent = digits[:-1], exponent + 1
    return sign, digits, exponent


def translation(frame: Frame, pose: Pose, prefix: str = "") -> list[Change]:
    """x, y, z in metres (the pose's mm / 1000)."""
    out = []
    for key, v in zip("xyz", pose.t):
        n = frame.numbers[prefix + key]
        metres = v / 1000.0
        if abs(metres - n.value) <= SAME_METRES:
            continue
        text = java_double(metres)
        out.append(Change(prefix + key, n.written, text, n.value, float(text)))
    return out


def rotation(frame: Frame, q, prefix: str = "") -> list[Change]:
    """rx, ry, rz: the rotation vector (radians) of ``q``, unless the
    written one is that rotation already."""
    nums = [frame.numbers[prefix + k] for k in COMPONENTS[3:]]
    old = rot.rotvec_to_quat([n.value for n in nums])
    if rot.quat_angle(old, q) <= SAME_DEGREES:
        return []
    out = []
    for key, n, v in zip(COMPONENTS[3:], nums, rot.quat_to_rotvec(q)):
        text = java_double(v)
        if float(text) != n.value:
            out.append(Change(prefix + key, n.written, text, n.value, float(text)))
    return out


def plan(frame: Frame, pose: Pose) -> list[Change]:
    changes = translation(frame, pose) + rotation(frame, pose.q)
    if frame.type == "PLANE":
        for prefix, point in plane_points(frame, pose).items():
            changes += translation(frame, point, prefix) + rotation(frame, point.q, prefix)
    return changes


def plane_points(frame: Frame, pose: Pose) -> dict[str, Pose]:
    """The new poses of a plane's other points (``frame.numbers`` prefixes)."""
    m = pose.matrix
    x_axis, y_axis = (m[0][0], m[1][0], m[2][0]), (m[0][1], m[1][1], m[2][1])
    turn = rot.quat_multiply(pose.q, _conjugate(frame.pose.q))     # old frame -> new
    d = THREE_POINT_DISTANCE
    places = (pose.t, _along(pose.t, x_axis, d), _along(pose.t, y_axis, d))
    out = {"secondPoint.": Pose.from_quat(*_along(pose.t, y_axis, SECOND_POINT), pose.q)}
    for tag, place in zip(TAUGHT, places):
        old = _pose(frame, tag + ".")
        out[tag + "."] = Pose.from_quat(*place, rot.quat_multiply(turn, old.q))
    out["thirdPoint."] = out["userThirdPoint."]
    return out


def _pose(frame: Frame, prefix: str) -> Pose:
    from .installation import pose_of
    return pose_of(frame.numbers, prefix)


def _along(t, axis, d):
    return tuple(p + d * a for p, a in zip(t, axis))


def _conjugate(q):
    return (q[0], -q[1], -q[2], -q[3])


def check_patchable(cf: ControllerFile, frame: Frame, where: dict, warnings: list[str]) -> None:
    """A file this Python's zlib cannot write back bit for bit, and a
    feature the safety configuration uses, are refused; a feature is written
    with the warning that its joint positions are the old ones."""
    refusal = cf.document.gzip.refusal if cf.document.gzip is not None else None
    if refusal is not None:
        raise UcsioError(f"{frame.name}: {refusal}", **where)
    if frame.info.get("safety"):
        raise UcsioError(SAFETY.format(name=frame.name), **where)
    if frame.type in ("POINT", "PLANE"):
        warnings.append(JOINTS.format(name=frame.name))
