"""diff --points: the positions taught in a frame, and how far each moves in
world when the measured frame replaces the simulated one. Expected
displacements are computed here with scipy from the numbers in the files,
independently of ucsio's frame algebra."""
from __future__ import annotations

import contextlib
import io
import json
import os
import math
import re
import shutil

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from conftest import CORPUS, FIXTURES, corpus_file, corpus_files
from ucsio.cli import main

TAUGHT = FIXTURES / "taught"


def run(*args) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main([str(a) for a in args])
    return code, out.getvalue(), err.getvalue()


def points_json(*args) -> tuple[dict, str]:
    code, out, err = run("diff", *args, "--points", "--json")
    assert code in (0, 1), err
    return json.loads(out), err


def abc(x, y, z, a, b, c):
    """KUKA pose as (R, t): R = Rz(A) Ry(B) Rx(C), scipy's intrinsic 'ZYX'."""
    return Rotation.from_euler("ZYX", [a, b, c], degrees=True), np.array([x, y, z], float)


def quat(x, y, z, q):
    """ABB pose as (R, t): q = [w, x, y, z]."""
    return Rotation.from_quat(q, scalar_first=True), np.array([x, y, z], float)


def world(chain, p):
    p = np.asarray(p, float)
    for r, t in reversed(chain):
        p = r.apply(p) + t
    return p


def moved(sim, meas, p) -> float:
    return float(np.linalg.norm(world(meas, p) - world(sim, p)))


def solution(tmp_path, **frame) -> str:
    path = tmp_path / "solution.json"
    path.write_text(json.dumps({"frame": frame, "accepted": True}))
    return str(path)


# ------------------------------------------------------------------ KUKA

KUKA_CONFIG = TAUGHT / "kuka" / "KRC" / "R1" / "System" / "$config.dat"
BASE3 = (1500.0, -250.0, 600.0, 30.0, -2.5, 1.2)
KUKA_MEAS = dict(x=1501.0, y=-249.0, z=600.5, a=30.5, b=-2.4, c=1.0)
# E6POS/POS with an FDAT of BASE_NO 3 and IPO_FRAME #BASE, in the KRC tree
KUKA_POINTS = {"XP1": (0.0, 0.0, 0.0), "XP2": (2000.0, 0.0, 0.0), "xp3": (-300.5, 800.25, 120.0),
               "XGLOBAL1": (10.0, 20.0, 30.0)}


def test_kuka_points_in_the_controllers_tree(tmp_path):
    d, err = points_json(KUKA_CONFIG, "--frame", "weld_fixture", "--measured",
                         solution(tmp_path, **KUKA_MEAS))
    sim, meas = [abc(*BASE3)], [abc(*KUKA_MEAS.values())]
    got = {p["name"]: p for p in d["points"]}
    # XP4 is in base 1, XP5 taught with an external TCP, XP6 has no FDAT,
    # and a commented-out FDAT is no frame data
    assert set(got) == set(KUKA_POINTS)
    for name, p in KUKA_POINTS.items():
        assert got[name]["moved"] == pytest.approx(moved(sim, meas, p), abs=1e-9)
    assert got["XP2"]["file"].endswith("seam.dat") and got["XP2"]["line"] == 10
    assert got["XGLOBAL1"]["file"].endswith("$config.dat") and got["XGLOBAL1"]["line"] == 13
    worst = max(KUKA_POINTS, key=lambda n: moved(sim, meas, KUKA_POINTS[n]))
    pm = d["points_moved"]
    assert pm["count"] == 4 and pm["worst"] == worst == "XP2"
    assert pm["max"] == pytest.approx(moved(sim, meas, KUKA_POINTS["XP2"]), abs=1e-9)
    assert pm["mean"] == pytest.approx(np.mean([moved(sim, meas, p) for p in KUKA_POINTS.values()]))
    assert [p["moved"] for p in d["points"]] == sorted((p["moved"] for p in d["points"]),
                                                       reverse=True)
    assert "XP5" in err and "IPO_FRAME #TCP" in err
    # a point 2 m out moves far more than the frame's own dt_mean says
    assert pm["max"] > 10 * d["dt_mean"]


@pytest.mark.parametrize("layout", ["flat", "krc", "zip"])
def test_kuka_points_of_another_robot_beside_ours_are_not_counted(tmp_path, layout):
    """A folder of several robots' backups: the other robot's $config.dat
    marks its tree, and its points (here: BASE_NO 3 too) stay out."""
    ours_cfg = KUKA_CONFIG.read_bytes()
    seam = (TAUGHT / "kuka" / "KRC" / "R1" / "Program" / "Weld" / "seam.dat").read_bytes()
    if layout == "krc":
        ours = tmp_path / "cell" / "KRC" / "R1" / "System" / "$config.dat"
        files = {ours: ours_cfg, tmp_path / "cell" / "KRC" / "R1" / "Program" / "seam.dat": seam,
                 tmp_path / "cell" / "KRC" / "R2" / "System" / "$config.dat": ours_cfg,
                 tmp_path / "cell" / "KRC" / "R2" / "Program" / "other.dat": seam}
    else:
        ours = tmp_path / "cell" / "$config.dat"
        files = {ours: ours_cfg, tmp_path / "cell" / "seam.dat": seam,
                 tmp_path / "cell" / "R02" / "$config.dat": ours_cfg,
                 tmp_path / "cell" / "R02" / "other.dat": seam}
    for path, data in files.items():
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(data)
    target = ours
    if layout == "zip":
        import zipfile

        archive = tmp_path / "backups.zip"
        with zipfile.ZipFile(archive, "w") as z:
            for path, data in files.items():
                z.writestr(str(path.relative_to(tmp_path)), data)
        target = f"{archive}!cell/$config.dat"
    d, err = points_json(target, "--frame", "weld_fixture", "--measured",
                         solution(tmp_path, **KUKA_MEAS))
    got = {(p["name"], os.path.basename(p["file"])) for p in d["points"]}
    assert all(f in ("seam.dat", "$config.dat") for _, f in got), got
    assert {n for n, _ in got} == set(KUKA_POINTS)


def test_kuka_table_shows_worst_ten_and_count(tmp_path):
    tree = tmp_path / "KRC" / "R1"
    shutil.copytree(TAUGHT / "kuka" / "KRC" / "R1", tree)
    lines = ["DEFDAT MANY"]
    for i in range(1, 13):
        lines.append(f"DECL E6POS XM{i}={{X {100.0 * i},Y 0.0,Z 0.0,A 0.0,B 0.0,C 0.0,S 2,T 2}}")
        lines.append(f"DECL FDAT FM{i}={{TOOL_NO 1,BASE_NO 3,IPO_FRAME #BASE}}")
    lines.append("ENDDAT")
    (tree / "Program" / "many.dat").write_text("\n".join(lines) + "\n")
    code, out, _ = run("diff", tree / "System" / "$config.dat", "--frame", "BASE_DATA[3]",
                       "--measured", solution(tmp_path, **KUKA_MEAS), "--points")
    assert code == 0
    assert "taught points in BASE_DATA[3]: 16" in out
    assert "(the 10 that move most)" in out
    rows = out[out.index("moved mm"):].splitlines()[2:]
    assert len(rows) == 10 and rows[0].startswith("XP2 ")
    assert not any(r.startswith("XM1 ") for r in rows)     # 100 mm out: among the least moved


def test_kuka_tree_from_the_corpus(tmp_path):
    """A real KRC backup (Zinkerreka): $config.dat in R1/System, the program's
    .dat in R1/Program/Work; BASE_NO 1 ("pickBP") holds two taught points."""
    config = corpus_file("kuka", "Zinkerreka__KRC__R1__System__$config.dat")
    program = corpus_file("kuka", "C1_pickConveyorBP.dat")
    krc = tmp_path / "KRC"
    (krc / "R1" / "System").mkdir(parents=True)
    (krc / "R1" / "Program" / "Work").mkdir(parents=True)
    shutil.copy(config, krc / "R1" / "System" / "$config.dat")
    shutil.copy(program, krc / "R1" / "Program" / "Work" / "C1_pickConveyorBP.dat")
    meas = dict(x=-1389.0, y=2088.5, z=164.0, a=91.5, b=0.1, c=0.2)
    d, _ = points_json(krc / "R1" / "System" / "$config.dat", "--frame", "pickBP", "--measured",
                       solution(tmp_path, **meas))
    # what the file says, read here with a regex
    text = program.read_text(encoding="latin-1")
    base = {m.group(1) for m in re.finditer(r"DECL FDAT F(\w+)=\{[^}]*BASE_NO 1,IPO_FRAME #BASE",
                                            text)}
    assert base == {"p10", "homeConveyor1"}
    cfg = config.read_text(encoding="latin-1")
    b1 = re.search(r"^BASE_DATA\[1\]=\{X ([-\d.]+),Y ([-\d.]+),Z ([-\d.]+),A ([-\d.]+),"
                   r"B ([-\d.]+),C ([-\d.]+)\}", cfg, re.M)
    sim, m = [abc(*map(float, b1.groups()))], [abc(*meas.values())]
    got = {p["name"]: p["moved"] for p in d["points"]}
    assert set(got) == {"X" + n for n in base}
    for n in base:
        xyz = re.search(rf"DECL E6POS X{n}=\{{X ([-\d.]+),Y ([-\d.]+),Z ([-\d.]+)", text).groups()
        assert got["X" + n] == pytest.approx(moved(sim, m, list(map(float, xyz))), abs=1e-9)


def test_a_tool_has_no_taught_points(tmp_path):
    d, err = points_json(FIXTURES / "kuka" / "cell_config.dat", "--frame", "TOOL_DATA[1]",
                         "--measured", solution(tmp_path, **KUKA_MEAS))
    assert d["points"] == [] and d["points_moved"]["count"] == 0
    assert d["points_moved"]["max"] is None and "not a base" in err


# ------------------------------------------------------------------ ABB

U = (1200.0, -300.0, 450.0, [0.965926, 0, 0, 0.258819])
O = (50.0, 20.0, 0.0, [0.996195, 0, 0.0871557, 0])
ABB_MEAS = dict(x=1201.0, y=-299.0, z=450.5, q=[0.96, 0.01, 0.0, 0.28])
P_REL = (100.0, 200.0, 30.0)
Q_REL = [0, 0.707107, 0.707107, 0]
# the robtargets moved to with \WObj:=wobjTable, and where they are in the object frame
ABB_POINTS = {
    "pA": (0, 0, 0), "pB": (2000, 0, 0), "grid{1}": (0, 500, 0), "grid{2}": (0, -500, 0),
    "Offs(pA,0,0,100)": (0, 0, 100), "pShared": (-400, 250, -60), "pLocal": (0, 0, 800),
    "target at Cell.mod:30": (300, 0, 0),
    "RelTool(pRel,0,0,50)": tuple(np.add(P_REL, Rotation.from_quat(Q_REL, scalar_first=True)
                                         .apply([0, 0, 50]))),
}


def _norm(q):
    return list(np.asarray(q, float) / np.linalg.norm(q))


def test_abb_robtargets_moved_to_in_the_work_object(tmp_path):
    d, err = points_json(TAUGHT / "abb" / "Cell.mod", "--frame", "wobjTable", "--measured",
                         solution(tmp_path, **dict(ABB_MEAS, q=_norm(ABB_MEAS["q"]))))
    sim = [quat(*U), quat(*O)]
    meas = [quat(ABB_MEAS["x"], ABB_MEAS["y"], ABB_MEAS["z"], _norm(ABB_MEAS["q"])), quat(*O)]
    got = {p["name"]: p for p in d["points"]}
    # not: pElsewhere (another wobj), pUnused (no wobj, a comment, a string),
    # pNow (no value: warned), jHome (a joint target), Targets.mod's LOCAL pA
    assert set(got) == set(ABB_POINTS)
    for name, p in ABB_POINTS.items():
        assert got[name]["moved"] == pytest.approx(moved(sim, meas, p), abs=1e-6), name
    assert got["pShared"]["file"].endswith("Targets.mod") and got["pShared"]["line"] == 3
    assert got["pA"]["line"] == 7 and got["pLocal"]["line"] == 18
    assert "pNow" in err and "set at run time" in err
    assert d["points_moved"]["worst"] == "pB"


def test_abb_object_frame_measured(tmp_path):
    """--frame wobjTable.oframe: the measured pose is the object frame in
    world; the points go through it directly (world = M p)."""
    m = dict(x=1260.0, y=-270.0, z=451.0, q=_norm([0.96, 0.0, 0.05, 0.27]))
    d, _ = points_json(TAUGHT / "abb" / "Cell.mod", "--frame", "wobjTable.oframe", "--measured",
                       solution(tmp_path, **m))
    sim = [quat(*U), quat(*O)]
    meas = [quat(m["x"], m["y"], m["z"], m["q"])]
    got = {p["name"]: p["moved"] for p in d["points"]}
    assert set(got) == set(ABB_POINTS)
    for name, p in ABB_POINTS.items():
        assert got[name] == pytest.approx(moved(sim, meas, p), abs=1e-6), name


def test_abb_corpus_program(tmp_path):
    """A real palletising program: the targets of the moves in wobjMesaCarton."""
    src = corpus_file("abb", "PaletizadoCajasConFrascos__RAPID__TASK1__PROGMOD__MainModule.mod")
    folder = tmp_path / "TASK1"
    folder.mkdir()
    shutil.copy(src, folder / "MainModule.mod")
    text = src.read_text(encoding="latin-1")
    # robtargets with a value, named in an instruction that moves in wobjMesaCarton
    # (MoveL/MoveJ, and SearchL, whose target comes after the signal)
    taught = set(re.findall(r"robtarget (\w+):=\[", text))
    names = set()
    for m in re.finditer(r"^\s*(?:Move[LJ]|SearchL)\s+([^;\n]*)\\WObj:=\s*wobjMesaCarton\s*;",
                         text, re.M | re.I):
        names |= taught & set(re.findall(r"\w+", m.group(1)))
    wobj = re.search(r"wobjdata wobjMesaCarton:=\[FALSE,TRUE,\"\",\[\[([^\]]*)\],\[([^\]]*)\]\],"
                     r"\[\[([^\]]*)\],\[([^\]]*)\]\]", text)
    nums = [list(map(float, g.split(","))) for g in wobj.groups()]
    sim = [quat(*nums[0], nums[1]), quat(*nums[2], nums[3])]
    meas_pose = dict(x=nums[0][0] + 3, y=nums[0][1] - 2, z=nums[0][2] + 1,
                     q=_norm(np.add(nums[1], [0.004, 0.0, 0.002, 0.003])))
    meas = [quat(meas_pose["x"], meas_pose["y"], meas_pose["z"], meas_pose["q"]),
            quat(*nums[2], nums[3])]
    d, _ = points_json(folder / "MainModule.mod", "--frame", "wobjMesaCarton", "--measured",
                       solution(tmp_path, **meas_pose))
    got = {p["name"]: p["moved"] for p in d["points"]}
    assert set(got) == names and len(names) == 3
    for n in names:
        trans = re.search(rf"robtarget {n}:=\[\[([^\]]*)\]", text).group(1)
        assert got[n] == pytest.approx(moved(sim, meas, list(map(float, trans.split(",")))),
                                       abs=1e-6)


@pytest.mark.skipif(not (CORPUS / "abb").is_dir(), reason="the shared corpus is absent")
def test_every_move_in_the_corpus_is_read_by_the_grammar():
    """Every corpus statement with \\WObj:= that moves the robot parses with
    the grammar's `statements` start symbol; the one it cannot read is a
    real slip in a real file (Tool:= without its backslash), and it is an
    assignment, so it is not warned about."""
    from ucsio.parsing.document import Document
    from ucsio.vendors.abb import taught as abb

    n = 0
    unread = []
    for path in sorted((CORPUS / "abb").iterdir()):
        try:
            mod = abb._read_module(Document.read(path))
        except Exception:  # encrypted modules: refused by the outline, as by `frames`
            continue
        n += len(mod.statements)
        unread += [(path.name, mod.doc.line_of(s.start)) for t, s in mod.statements if t is None]
    assert n > 600
    assert unread == [("Fabio-Coder__Robo_ABB_Injetora-Rotinas_de_ajuste__HOME____MODULI____"
                       "UTILITY.sys", 90)]


def test_points_needs_frame_and_measured():
    code, _, err = run("diff", TAUGHT / "abb" / "Cell.mod", TAUGHT / "abb" / "Cell.mod",
                       "--points")
    assert code == 2 and "--points go with --frame and --measured" in err


@pytest.mark.parametrize("path", [p for p in corpus_files("kuka")
                                  if p.values[0] is None or p.values[0].suffix == ".dat"])
def test_positions_fast_path_equals_the_full_parse(path):
    """diff --points reads a tree's .dat files on the fast path (position and
    FDAT lines only); it must find what the whole-file parse finds."""
    from ucsio.parsing.document import Document
    from ucsio.errors import UcsioError
    from ucsio.vendors.kuka.krl import positions

    doc = Document.read(path)

    def seen(full):
        try:
            return [(p.name, p.type, p.line, p.col, p.pose, p.fdat, p.tool_no, p.base_no,
                     p.ipo_frame, p.problem and p.problem.message)
                    for p in positions(doc, full=full)]
        except UcsioError as exc:
            return str(exc)

    assert seen(False) == seen(True)


@pytest.mark.skipif(not (CORPUS / "abb").is_dir(), reason="the shared corpus is absent")
def test_plain_robtargets_read_without_lark_equal_the_grammars_reading():
    """A robtarget in the controller's plain form is read with a strict regex
    (a path module has thousands); on every corpus robtarget it gives what
    the grammar gives, and anything it does not take goes to the grammar."""
    from ucsio.vendors.abb import rapid
    from ucsio.parsing.document import Document
    from ucsio.vendors.abb import taught as abb

    fast = slow = 0
    for path in sorted((CORPUS / "abb").iterdir()):
        try:
            mod = abb._read_module(Document.read(path))
        except Exception:   # encrypted modules
            continue
        for _, region in mod.targets:
            m = abb._LITERAL_TARGET.match(mod.doc.text, region.span.start, region.span.end)
            compact = rapid.Compact(mod.doc, sorted(mod.brackets + [region],
                                                    key=lambda r: r.span.start))
            tree = rapid.parse_tree(mod.doc, compact.text, compact)
            compact.remap(tree)
            (decl,) = rapid.declarations(mod.doc, tree)
            if m is None:
                slow += 1
                continue
            fast += 1
            lit = abb._LiteralTarget(m, mod.doc)
            assert (lit.name, lit.scope) == (decl.name, decl.scope)
            assert abb._target(lit.value)[0] == abb._target(decl.value)[0]
            assert abb._target(lit.value)[1] == abb._target(decl.value)[1]
            assert mod.doc.line_of(lit.start) == mod.doc.line_of(rapid._start_of(decl.value, 0))
    assert fast > 1000 and slow > 0


def test_points_inside_an_archive(tmp_path):
    """A KUKA archive and an ABB backup zipped: the tree (or folder) around
    the member is searched inside the archive, read in place."""
    import zipfile

    kuka_zip, abb_zip = tmp_path / "krc.zip", tmp_path / "abb.zip"
    with zipfile.ZipFile(kuka_zip, "w") as z:
        for p in (TAUGHT / "kuka").rglob("*"):
            if p.is_file():
                z.write(p, p.relative_to(TAUGHT / "kuka").as_posix())
    with zipfile.ZipFile(abb_zip, "w") as z:
        for p in (TAUGHT / "abb").iterdir():
            z.write(p, "RAPID/TASK1/PROGMOD/" + p.name)
        z.writestr("RAPID/TASK1/SYSMOD/Other.sys", "MODULE Other\nENDMODULE\n")
    sol = solution(tmp_path, **KUKA_MEAS)
    on_disk, _ = points_json(KUKA_CONFIG, "--frame", "weld_fixture", "--measured", sol)
    zipped, _ = points_json(f"{kuka_zip}!KRC/R1/System/$config.dat", "--frame", "weld_fixture",
                            "--measured", sol)
    assert [(p["name"], p["moved"]) for p in zipped["points"]] == \
        [(p["name"], p["moved"]) for p in on_disk["points"]]
    assert f"{kuka_zip}!KRC/R1/Program/Weld/seam.dat" in {p["file"] for p in zipped["points"]}
    sol = solution(tmp_path, **dict(ABB_MEAS, q=_norm(ABB_MEAS["q"])))
    on_disk, _ = points_json(TAUGHT / "abb" / "Cell.mod", "--frame", "wobjTable", "--measured", sol)
    zipped, _ = points_json(f"{abb_zip}!RAPID/TASK1/PROGMOD/Cell.mod", "--frame", "wobjTable",
                            "--measured", sol)
    assert sorted((p["name"], p["moved"]) for p in zipped["points"]) == \
        sorted((p["name"], p["moved"]) for p in on_disk["points"])
    assert f"{abb_zip}!RAPID/TASK1/PROGMOD/Targets.mod" in {p["file"] for p in zipped["points"]}


def test_api_diff_frame_with_points(tmp_path):
    from ucsio import api

    sol = json.loads(open(solution(tmp_path, **KUKA_MEAS)).read())
    d = api.diff_frame(api.load(KUKA_CONFIG), "weld_fixture", sol, points=True)
    cli, _ = points_json(KUKA_CONFIG, "--frame", "weld_fixture", "--measured",
                         solution(tmp_path, **KUKA_MEAS))
    assert d["points_moved"] == cli["points_moved"] and d["points"] == cli["points"]


def test_known_geometry_translation_and_rotation(tmp_path):
    """A pure shift moves every point by its length; a turn by t about the
    base's z axis moves a point at distance r from that axis by 2 r sin(t/2)."""
    x, y, z, a, b, c = BASE3
    d, _ = points_json(KUKA_CONFIG, "--frame", "weld_fixture", "--measured",
                       solution(tmp_path, x=x + 3, y=y + 4, z=z, a=a, b=b, c=c))
    assert [p["moved"] for p in d["points"]] == pytest.approx([5.0] * 4, abs=1e-9)
    # 0.5 deg about the base's own z: A, B, C of R_sim * Rz(0.5)
    turned = Rotation.from_euler("ZYX", [a, b, c], degrees=True) * \
        Rotation.from_euler("z", 0.5, degrees=True)
    a2, b2, c2 = turned.as_euler("ZYX", degrees=True)
    d, _ = points_json(KUKA_CONFIG, "--frame", "weld_fixture", "--measured",
                       solution(tmp_path, x=x, y=y, z=z, a=a2, b=b2, c=c2))
    got = {p["name"]: p["moved"] for p in d["points"]}
    for name, (px, py, _) in KUKA_POINTS.items():
        r = math.hypot(px, py)
        assert got[name] == pytest.approx(2 * r * math.sin(math.radians(0.25)), abs=1e-6)
    # the issue's example: 0.5 deg moves a point 2 m out by about 17 mm
    assert got["XP2"] == pytest.approx(17.45, abs=0.01)
