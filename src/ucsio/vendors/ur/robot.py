"""Universal Robots' robot positions for ``solve --robot``: the taught
poses of an installation's features.

A taught pose (a point feature, a plane's ``userFirstPoint`` ...) is the
pose of the TCP when it was taught, in the robot base: ``toolPosition``
(metres) and ``toolAxisAngle`` (a rotation vector), with the TCP it was
taught with stored beside it (``tcpOffset``, in the flange). The flange is
pose · tcpOffset⁻¹. Each is named by its feature (a point: its name; a
plane's taught points: ``PLANE.1``, ``PLANE.2``, ``PLANE.3``). The derived
points of a plane (firstPoint, ...) are computed, not where the robot was,
and are not read.
"""
from __future__ import annotations

from ...errors import UcsioError
from ..common.robot import RobotPose, RobotPoses, matrix
from . import installation as ins


def read(vendor, path: str, config, tool: str, wobj: str, load) -> RobotPoses:
    if config is not None or tool.strip().casefold() != "tool0" \
            or wobj.strip().casefold() != "wobj0":
        raise UcsioError("--config, --robot-tool and --robot-wobj do not apply to a Universal "
                         "Robots installation: each taught pose stores the TCP it was taught "
                         "with (tcpOffset)", file=path)
    cf = load(path)         # read as check reads it: a damaged file is refused alike
    if cf.vendor != vendor.name:
        raise UcsioError("not a Universal Robots installation", file=path)
    doc = cf.document
    poses = []
    for element in ins.scan(doc)[1]:
        if element.tag not in ins.FEATURES or element.get("name") is None \
                or element.get("hiddenSubFeature") == "true":
            continue
        name = ins.unescape(element.get("name"))
        if element.tag == "GeomPoseNode":
            poses.append(_taught(doc, name, element))
        else:
            for i, tag in enumerate(ins.TAUGHT, 1):
                node = ins.point_node(doc, element, tag)
                poses.append(_taught(doc, f"{name}.{i}", node))
    return RobotPoses(path, vendor.name, poses, vendor.name)


def _taught(doc, name: str, node) -> RobotPose:
    line, col = doc.line_col(node.start)
    rp = RobotPose(name, name, line, col, None)
    try:
        tcp_pose = ins.pose_of(ins.point_numbers(doc, node))
        offset = node.child("tcpOffset")
        if offset is None:
            raise doc.error(f"{name}: no tcpOffset: the TCP it was taught with is not known",
                            node.start)
        tcp = ins.pose_of(ins.numbers_of(doc, offset, "value", ins.COMPONENTS))
        rp.flange = matrix(tcp_pose.compose(tcp.inverse()))
    except UcsioError as exc:
        rp.problem = exc
    return rp
