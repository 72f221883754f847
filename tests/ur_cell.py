"""A small Universal Robots installation in the corpus's style (PolyScope
5.11, ../shared/corpus/ur/README.md), for what the corpus lacks: a point
feature taught with a TCP, a free plane (Table), a plane the safety
configuration uses (Fence), two TCPs. Its derived points are those PolyScope
computes: firstPoint the 3-point construction of the taught points,
secondPoint the origin plus 1 m along y, thirdPoint the third taught point.

``installation(xml)`` frames it as PolyScope writes it, independently of
ucsio: gzip's fixed header (no name, mtime 0, OS byte 0) around zlib's
level-6 raw deflate stream, CRC-32 and length.
"""
from __future__ import annotations

import zlib

HEADER = bytes.fromhex("1f8b0800000000000000")


def installation(xml: str, level: int = 6) -> bytes:
    body = xml.encode("utf-8")
    deflate = zlib.compressobj(level, zlib.DEFLATED, -15, 8, zlib.Z_DEFAULT_STRATEGY)
    stream = deflate.compress(body) + deflate.flush()
    return HEADER + stream + zlib.crc32(body).to_bytes(4, "little") + len(body).to_bytes(4, "little")


def inflate(data: bytes) -> str:
    return zlib.decompress(data, 31).decode("utf-8")


XML = """\
<Installation directory="/programs" fileName="cell" showSpeedSliderOnRunTab="false">
  <Version projectName="URSoftware" major="5" minor="11" bugfix="0" buildNumber="108249" buildDate="May 19 2021, 12:00:00"/>
  <SafetySettings>
[Safety Checksum]
version = 5.5
crc = 123456789

[SafetyLimits BoundaryPlane0]
name = Fence
sourceFeatureId = f0000000-0000-4000-8000-000000000000
displacement = 0.0
mode = NORMAL
planeNormal = [0.0, 1.0, 0.0]
distanceToOrigin = 0.6
elbowRestricted = false

</SafetySettings>
  <Features>
    <BaseView>
      <BaseView showAxes="true" joggable="true" isVariable="false" id="1b785537-e70a-4c26-a8af-4602e931277e"/>
    </BaseView>
    <GeomPoseNode>
      <GeomPoseNode showAxes="true" joggable="true" isVariable="false" id="d0000000-0000-4000-8000-000000000000" name="Pick">
        <jointPositionVector value="0.1, -1.2, 1.3, -1.6, -1.57, 0.2"/>
        <toolPosition value="0.3, 0.1, 0.2"/>
        <toolAxisAngle value="0.0, 3.1, 0.1"/>
        <tcpOffset value="0.0, 0.0, 0.1, 0.0, 0.0, 0.0"/>
      </GeomPoseNode>
    </GeomPoseNode>
    <GeomPlaneNode>
      <GeomPlaneNode name="Table" userHasPoints="true" showAxes="true" joggable="true" isVariable="true" id="a0000000-0000-4000-8000-000000000000">
        <firstPoint>
          <GeomPoseNode showAxes="false" joggable="false" isVariable="false" id="a0000000-0000-4000-8000-000000000001" name="hidden_Point" hiddenSubFeature="true">
            <jointPositionVector value="0.1, -1.2, 1.3, -1.6, -1.57, 0.2"/>
            <toolPosition value="0.4, -0.2, 0.05"/>
            <toolAxisAngle value="0.0, 0.0, 0.5235987755982988"/>
            <tcpOffset value="0.0, 0.0, 0.0, 0.0, 0.0, 0.0"/>
          </GeomPoseNode>
        </firstPoint>
        <secondPoint>
          <GeomPoseNode showAxes="false" joggable="false" isVariable="false" id="a0000000-0000-4000-8000-000000000002" name="hidden_Point_1" hiddenSubFeature="true">
            <jointPositionVector value="0.1, -1.2, 1.3, -1.6, -1.57, 0.2"/>
            <toolPosition value="-0.09999999999999992, 0.6660254037844386, 0.05"/>
            <toolAxisAngle value="0.0, 0.0, 0.5235987755982988"/>
            <tcpOffset value="0.0, 0.0, 0.0, 0.0, 0.0, 0.0"/>
          </GeomPoseNode>
        </secondPoint>
        <thirdPoint>
          <GeomPoseNode showAxes="false" joggable="false" isVariable="false" id="a0000000-0000-4000-8000-000000000003" name="hidden_Point_2" hiddenSubFeature="true">
            <jointPositionVector value="0.1, -1.2, 1.3, -1.6, -1.57, 0.2"/>
            <toolPosition value="0.4266025403784439, -0.046076951545867384, 0.05"/>
            <toolAxisAngle value="3.1354669308467376, -0.13689744265922693, 2.1503817693856425E-4"/>
            <tcpOffset value="0.0, 0.0, 0.0, 0.0, 0.0, 0.0"/>
          </GeomPoseNode>
        </thirdPoint>
        <userFirstPoint>
          <GeomPoseNode showAxes="false" joggable="false" isVariable="false" id="a0000000-0000-4000-8000-000000000004" name="hidden_Point_3" hiddenSubFeature="true">
            <jointPositionVector value="0.1, -1.2, 1.3, -1.6, -1.57, 0.2"/>
            <toolPosition value="0.4, -0.2, 0.05"/>
            <toolAxisAngle value="3.1354669308467376, -0.13689744265922693, 2.1503817693856425E-4"/>
            <tcpOffset value="0.0, 0.0, 0.0, 0.0, 0.0, 0.0"/>
          </GeomPoseNode>
        </userFirstPoint>
        <userSecondPoint>
          <GeomPoseNode showAxes="false" joggable="false" isVariable="false" id="a0000000-0000-4000-8000-000000000005" name="hidden_Point_4" hiddenSubFeature="true">
            <jointPositionVector value="0.1, -1.2, 1.3, -1.6, -1.57, 0.2"/>
            <toolPosition value="0.5299038105676659, -0.12500000000000003, 0.05"/>
            <toolAxisAngle value="3.1354669308467376, -0.13689744265922693, 2.1503817693856425E-4"/>
            <tcpOffset value="0.0, 0.0, 0.0, 0.0, 0.0, 0.0"/>
          </GeomPoseNode>
        </userSecondPoint>
        <userThirdPoint>
          <GeomPoseNode showAxes="false" joggable="false" isVariable="false" id="a0000000-0000-4000-8000-000000000006" name="hidden_Point_5" hiddenSubFeature="true">
            <jointPositionVector value="0.1, -1.2, 1.3, -1.6, -1.57, 0.2"/>
            <toolPosition value="0.4266025403784439, -0.046076951545867384, 0.05"/>
            <toolAxisAngle value="3.1354669308467376, -0.13689744265922693, 2.1503817693856425E-4"/>
            <tcpOffset value="0.0, 0.0, 0.0, 0.0, 0.0, 0.0"/>
          </GeomPoseNode>
        </userThirdPoint>
      </GeomPlaneNode>
    </GeomPlaneNode>
    <GeomPlaneNode>
      <GeomPlaneNode name="Fence" userHasPoints="true" showAxes="true" joggable="true" isVariable="true" id="f0000000-0000-4000-8000-000000000000">
        <firstPoint>
          <GeomPoseNode showAxes="false" joggable="false" isVariable="false" id="f0000000-0000-4000-8000-000000000001" name="hidden_Point" hiddenSubFeature="true">
            <jointPositionVector value="0.1, -1.2, 1.3, -1.6, -1.57, 0.2"/>
            <toolPosition value="0.0, -0.6, 0.5"/>
            <toolAxisAngle value="1.5707963267948963, 0.0, 0.0"/>
            <tcpOffset value="0.0, 0.0, 0.0, 0.0, 0.0, 0.0"/>
          </GeomPoseNode>
        </firstPoint>
        <secondPoint>
          <GeomPoseNode showAxes="false" joggable="false" isVariable="false" id="f0000000-0000-4000-8000-000000000002" name="hidden_Point_1" hiddenSubFeature="true">
            <jointPositionVector value="0.1, -1.2, 1.3, -1.6, -1.57, 0.2"/>
            <toolPosition value="0.0, -0.5999999999999998, 1.5"/>
            <toolAxisAngle value="1.5707963267948963, 0.0, 0.0"/>
            <tcpOffset value="0.0, 0.0, 0.0, 0.0, 0.0, 0.0"/>
          </GeomPoseNode>
        </secondPoint>
        <thirdPoint>
          <GeomPoseNode showAxes="false" joggable="false" isVariable="false" id="f0000000-0000-4000-8000-000000000003" name="hidden_Point_2" hiddenSubFeature="true">
            <jointPositionVector value="0.1, -1.2, 1.3, -1.6, -1.57, 0.2"/>
            <toolPosition value="0.1, -0.6, 0.7"/>
            <toolAxisAngle value="3.1354669308467376, -0.13689744265922693, 2.1503817693856425E-4"/>
            <tcpOffset value="0.0, 0.0, 0.0, 0.0, 0.0, 0.0"/>
          </GeomPoseNode>
        </thirdPoint>
        <userFirstPoint>
          <GeomPoseNode showAxes="false" joggable="false" isVariable="false" id="f0000000-0000-4000-8000-000000000004" name="hidden_Point_3" hiddenSubFeature="true">
            <jointPositionVector value="0.1, -1.2, 1.3, -1.6, -1.57, 0.2"/>
            <toolPosition value="0.0, -0.6, 0.5"/>
            <toolAxisAngle value="3.1354669308467376, -0.13689744265922693, 2.1503817693856425E-4"/>
            <tcpOffset value="0.0, 0.0, 0.0, 0.0, 0.0, 0.0"/>
          </GeomPoseNode>
        </userFirstPoint>
        <userSecondPoint>
          <GeomPoseNode showAxes="false" joggable="false" isVariable="false" id="f0000000-0000-4000-8000-000000000005" name="hidden_Point_4" hiddenSubFeature="true">
            <jointPositionVector value="0.1, -1.2, 1.3, -1.6, -1.57, 0.2"/>
            <toolPosition value="0.3, -0.6, 0.5"/>
            <toolAxisAngle value="3.1354669308467376, -0.13689744265922693, 2.1503817693856425E-4"/>
            <tcpOffset value="0.0, 0.0, 0.0, 0.0, 0.0, 0.0"/>
          </GeomPoseNode>
        </userSecondPoint>
        <userThirdPoint>
          <GeomPoseNode showAxes="false" joggable="false" isVariable="false" id="f0000000-0000-4000-8000-000000000006" name="hidden_Point_5" hiddenSubFeature="true">
            <jointPositionVector value="0.1, -1.2, 1.3, -1.6, -1.57, 0.2"/>
            <toolPosition value="0.1, -0.6, 0.7"/>
            <toolAxisAngle value="3.1354669308467376, -0.13689744265922693, 2.1503817693856425E-4"/>
            <tcpOffset value="0.0, 0.0, 0.0, 0.0, 0.0, 0.0"/>
          </GeomPoseNode>
        </userThirdPoint>
      </GeomPlaneNode>
    </GeomPlaneNode>
  </Features>
  <TCPSettings activePose="Gripper">
    <availablePoses>
      <tcp id="95935d78-ab01-4b68-bc81-2fe899b7e3fc" name="TCP" offset="0.0, 0.0, 0.0, 0.0, 0.0, 0.0"/>
      <tcp id="b5935d78-ab01-4b68-bc81-2fe899b7e3fc" name="Gripper" offset="0.0, 0.0, 0.15, 0.0, 0.0, 0.7853981633974483"/>
    </availablePoses>
  </TCPSettings>
</Installation>"""
