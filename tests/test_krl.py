"""KUKA KRL data lists: grammars/krl.lark + ucsio.vendors.kuka.krl (issue 3).

The real files are read in place from ../shared/corpus/kuka (never copied into
the project); hand-written fixtures cover what the corpus lacks.
"""
from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from ucsio.parsing import controller
from ucsio.vendors.kuka import krl
from ucsio.parsing.document import Document
from ucsio.errors import UcsioError

ROOT = Path(__file__).resolve().parents[1]
FIXTURES = ROOT / "fixtures" / "kuka"
CORPUS = Path(__file__).resolve().parents[2] / "shared" / "corpus"
KUKA = CORPUS / "kuka"
corpus_files = sorted(KUKA.glob("*")) if KUKA.is_dir() else []
needs_corpus = pytest.mark.skipif(not corpus_files, reason=f"shared corpus not found at {KUKA}")

ZINK = "Aleynikovich__Zinkerreka__KRC__R1__System__$config.dat"
CHINA = "HugoDanielson__ChinaMilling__KRC__R1__System__$config.dat"


def corpus(name: str) -> Path:
    p = KUKA / name
    if not p.is_file():
        pytest.skip(f"corpus file {name} not found")
    return p


def doc_of(text: str | bytes, name: str = "mem.dat") -> Document:
    raw = text.encode("latin-1") if isinstance(text, str) else text
    return Document(raw, name)


def both(doc: Document):
    """Parse fast and with Lark's tree of every byte; assert they agree;
    return the fast result."""
    fast = krl.parse(doc)
    full = krl.parse_whole(doc)
    assert snapshot(fast) == snapshot(full)
    return fast


def snapshot(cf):
    return ([(f.as_dict(), f.numbers, f.label, f.reference) for f in cf.frames],
            cf.lints, cf.extra)


def wrap(body: str, header: str = "&ACCESS RVP\n&REL 1\nDEFDAT  T\n") -> str:
    return header + body + "ENDDAT\n"


# -- the corpus -----------------------------------------------------------------
@needs_corpus
@pytest.mark.parametrize("path", corpus_files, ids=lambda p: p.name[:60])
def test_corpus_parses_fast_and_full_identically_and_round_trips(path):
    doc = Document.read(path)
    assert doc.to_bytes() == doc.raw == path.read_bytes()
    fast = krl.parse(doc)
    full = krl.parse_whole(doc)
    assert snapshot(fast) == snapshot(full)
    assert snapshot(krl.parse(doc, full=True)) == snapshot(full)
    assert fast.vendor == "kuka"
    for fr in fast.frames:
        assert fr.vendor == "kuka" and fr.document is doc and fr.file == str(path)
        # the spans the patcher will replace hold exactly the numbers
        for comp, num in fr.numbers.items():
            assert doc.text[num.span.start:num.span.end] == num.text
            assert float(num.text) == num.value
            assert doc.line_of(num.span.start) == fr.line
        line = doc.text.splitlines()[fr.line - 1]
        assert re.search(re.escape(fr.name.split("[")[0]), line, re.I)
    # nothing changes the document
    assert doc.to_bytes() == path.read_bytes()


@needs_corpus
@pytest.mark.parametrize("path", corpus_files, ids=lambda p: p.name[:60])
def test_masked_text_keeps_offsets_and_lines(path):
    text = Document.read(path).text
    m = krl.masked(text, krl.outline(text))
    assert len(m) == len(text)
    assert [i for i, c in enumerate(m) if c == "\n"] == [i for i, c in enumerate(text) if c == "\n"]
    assert set(m) <= set(text) | {" "}


@needs_corpus
def test_controller_dispatches_dat_to_krl():
    cf = controller.load(corpus(ZINK))
    assert cf.vendor == "kuka" and len(cf.frames) == 76
    assert controller.load(corpus(ZINK), full=True).frames == cf.frames


@needs_corpus
def test_zinkerreka_tools_bases_labels_loads():
    cf = krl.parse(Document.read(corpus(ZINK)))
    t1 = cf.frame("TOOL_DATA[1]")
    assert (t1.line, t1.type, t1.label) == (223, "TOOL_DATA", "pintxoEstatico")
    assert t1.pose.t == (-344.107941, -447.298737, 561.382874)
    assert t1.pose.abc == (0.0, -180.0, 0.0)
    assert {k: n.text for k, n in t1.numbers.items()} == {
        "x": "-344.107941", "y": "-447.298737", "z": "561.382874",
        "a": "0.0", "b": "-180.000", "c": "0.0"}
    assert t1.info["tool_type"] == "#BASE" and t1.reference == "flange"
    load = t1.info["load"]
    assert load["m"] == 157.030243 and load["load_set"] is True
    assert load["cm"] == {"x": -221.862411, "y": 13.4881344, "z": 298.098,
                          "a": -90.0745163, "b": -0.108837, "c": -158.956924}
    assert load["j"] == {"x": 5.25, "y": 20.9529362, "z": 23.1879196}
    t3 = cf.frame("medicion")
    assert t3.name == "TOOL_DATA[3]" and t3.pose.t == (-84.4811325, -11.0449314, 494.102844)
    t2 = cf.frame("TOOL_DATA[2]")
    assert t2.label is None and t2.info["load"] == {
        "m": None, "load_set": False, "cm": dict.fromkeys("xyzabc", 0.0),
        "j": dict.fromkeys("xyz", 0.0)}
    b3 = cf.frame("pintura")
    assert (b3.name, b3.line, b3.type, b3.reference) == ("BASE_DATA[3]", 357, "BASE_DATA", "world")
    assert b3.pose.t == (1300.0, -1075.0, 228.0)
    assert b3.pose.abc == (-5.0, 0.0239453614, 0.703215420)
    assert b3.info["base_type"] == "#BASE" and b3.info["role"] == "base"
    b1 = cf.frame("pickBP")
    assert b1.pose.t == (-1389.98, 2087.5, 163.670013) and b1.pose.abc == (91.01, 0.0, 0.11)
    # BASE_TYPE[2]=#TCP: the base table entry holds an external (fixed) TCP
    b2 = cf.frame("lasertcp")
    assert b2.name == "BASE_DATA[2]" and b2.info["base_type"] == "#TCP"
    assert b2.info["role"] == "external_tcp" and b2.reference == "world"
    assert cf.frame("BASE_DATA[6]").label is None
    assert cf.extra["tables"]["MAX_TOOL"] == 16 and cf.extra["tables"]["MAX_BASE"] == 32
    assert cf.extra["arrays"]["TOOL_DATA"] == [16] and cf.extra["arrays"]["BASE_DATA"] == [32]
    assert cf.extra["defdat"] == {"name": "$CONFIG", "public": False}
    names = [f.name for f in cf.frames]
    assert names.count("TOOL_DATA[16]") == 1 and names.count("BASE_DATA[32]") == 1
    assert "REF_TOOL" in names and "RECIPE_TCP[1]" in names
    assert not any(f.type == "FRAME" and f.reference != "unknown" for f in cf.frames)
    assert cf.lints == []


@needs_corpus
def test_chinamilling_spindle_and_duplicate_label():
    cf = krl.parse(Document.read(corpus(CHINA)))
    sp = cf.frame("spindle")
    assert (sp.name, sp.line) == ("TOOL_DATA[1]", 220)
    assert sp.pose.t == (232.044312, 3.01155138, 166.257782) and sp.pose.abc == (0.0, -90.0, 0.0)
    assert sp.info["load"]["m"] == 40.3176460 and sp.reference == "flange"
    probe = cf.frame("Probe")
    assert probe.pose.abc == (-90.0, 0.0, 90.0) and probe.pose.t[0] == 409.434326
    b11 = cf.frame("BASE_DATA[11]")
    assert b11.pose.t == (1197.28235, 883.007, 776.392395)
    assert b11.pose.abc == (-90.8298, 0.254145205, -0.0897579566)
    assert cf.frame("MILLINGTABLE").name == "BASE_DATA[1]"
    # TOOL_NAME[4,] and TOOL_NAME[11,] are both "Sandvik Carbide"
    with pytest.raises(UcsioError, match="ambiguous") as e:
        cf.frame("sandvik carbide")
    assert "TOOL_DATA[4]" in str(e.value) and "TOOL_DATA[11]" in str(e.value)
    assert cf.frame("TOOL_DATA[11]").label == "Sandvik Carbide"
    dup = [lint for lint in cf.lints if lint.code == "duplicate-label"]
    assert len(dup) == 1 and dup[0].line == 250 and "TOOL_DATA[4] and TOOL_DATA[11]" in dup[0].message


@needs_corpus
def test_other_config_files_by_hand():
    cf = krl.parse(Document.read(corpus("khrzysio__KRC4_test__R1__System__$config.dat")))
    t = cf.frame("MarkerSpindle1")
    assert t.name == "TOOL_DATA[11]" and t.line == 232
    assert t.pose.t == (-365.241119, 401.075745, 92.0839157)
    assert t.pose.abc == (149.920486, 0.122838050, -0.109793410)
    assert cf.frame("TOOL_DATA[1]").info["load"]["m"] == 84.2028503
    cf = krl.parse(Document.read(corpus("KamWisa__BPF2PLTZPK2__$config.dat")))
    b = cf.frame("10kgLftBas")
    assert b.name == "BASE_DATA[4]" and b.pose.t == (302.249908, 1595.83398, -599.960693)
    assert cf.frame("GripperBP2").pose.t == (0.0, 0.0, 600.0)
    cf = krl.parse(Document.read(corpus("ingeniado__KRC4-Robot-Palletizer__System__$config.dat")))
    assert cf.frame("sacos").label == "SACOS"            # trailing spaces stripped
    assert cf.frame("PALETS").pose.abc == (91.9994965, -0.207900003, 0.358399987)
    assert cf.frame("TOOL_DATA[1]").info["load"]["load_set"] is False   # M -1.0
    cf = krl.parse(Document.read(corpus("rawpython__kukaKRLmagic__R1__System__$config.dat")))
    assert all(f.label is None for f in cf.frames)
    assert all(f.info.get("load", {}).get("m") is None for f in cf.frames)
    cf = krl.parse(Document.read(corpus("Naqiu06__KUKA-Robotics__KRC__R1__System__$config.dat")))
    assert cf.frame("gripperfingers").pose.t == (0.0, 0.0, 225.0)


@needs_corpus
def test_tfg_no_header_utf8_crlf():
    path = corpus("luciagumbau228__TFG__R1__System__$config.dat")
    doc = Document.read(path)
    assert doc.encoding == "utf-8" and "\r\n" in doc.text
    cf = both(doc)
    b2 = cf.frame("Palet_base")
    assert b2.name == "BASE_DATA[2]" and b2.line == 364
    assert b2.numbers["x"].text == "2700.000027" and b2.pose.t == (2700.000027, -499.999878, -656.0)
    # a label that looks like an entry name names its own entry: not ambiguous
    assert cf.frame("TOOL_DATA[2]") is cf.frame("tool_data[2]")
    assert cf.extra["defdat"]["name"] == "$CONFIG"


@needs_corpus
def test_program_dat_files():
    cf = both(Document.read(corpus("HugoDanielson__ChinaMilling__KRC__R1__Program__KukaMiling__Dat__fFrame.dat")))
    assert [f.name for f in cf.frames] == ["gfBaseShift[1]", "gfBaseShift[2]", "gfBaseShift[3]"]
    g2 = cf.frame("GFBASESHIFT[2]")
    assert g2.type == "FRAME" and g2.reference == "unknown" and g2.line == 8
    assert g2.numbers["z"].text == "-.6" and g2.pose.t == (-16.0, -16.0, -0.6)
    assert cf.extra["defdat"] == {"name": "fframe", "public": True}
    cf = both(Document.read(corpus("Naqiu06__KUKA-Robotics__KRC__R1__Program__honai.dat")))
    assert [f.name for f in cf.frames] == [f"{n}[{i}]" for n in ("basePos", "actualBasePos")
                                           for i in (1, 2, 3)]
    assert cf.frame("actualbasepos[3]").pose.t == (627.0, 325.0, 67.0)
    cf = both(Document.read(corpus("Aleynikovich__Zinkerreka__KRC__R1__Program__Work__C1_pickConveyorBP.dat")))
    assert len(cf.frames) == 5 and all(f.type == "FRAME" for f in cf.frames)
    cf = both(Document.read(corpus("KamWisa__BPF2PLTZPK2__varglobal.dat")))
    # E6POS/POS points (MasterSackPos[6,16]) are not frames; FRAMEs declared without a
    # value are listed without numbers (like ABB's PERS without a value), with an info
    valued = {f.name for f in cf.frames if f.pose is not None}
    assert valued == {"Homing", "EscRetBlt", "PikUpRgh", "PikUpLft"}
    assert cf.frame("homing").info == {"global": True}
    assert "PikPos" in cf.extra["uninitialised"]
    pik = cf.frame("pikpos")
    assert pik.pose is None and pik.numbers == {} and pik.line == 167
    assert pik.info == {"global": True, "value": None}
    assert {f.name for f in cf.frames if f.pose is None} == set(cf.extra["uninitialised"])
    assert {(l.code, l.severity) for l in cf.lints} == {("no-value", "info")}
    for name in ("HugoDanielson__ChinaMilling__KRC__R1__Program__KukaMiling__Dat__xPoints.dat",
                 "paulovictor237__KUKA-Paletizador__Extras__Bkp__TMatriz.dat",
                 "roboception__rc_generic_robot_interface_robot__KUKA-EKI6__GRI_HEC_EXAMPLE.dat",
                 "ingeniado__KRC4-Robot-Palletizer__Program__CAJA_G__caja_g_m2.dat"):
        assert both(Document.read(corpus(name))).frames == []


@needs_corpus
def test_fragment_and_stub():
    cf = both(Document.read(corpus("paulovictor237__KUKA-Paletizador__$config.dat")))
    assert cf.extra["defdat"] is None
    nf, *declared = cf.frames
    assert nf.name == "NULLFRAME" and nf.info == {"const": True} and nf.numbers["x"].text == "0"
    # DECL GLOBAL FRAME OffsetEsteira1 ...: declared without a value, listed without numbers
    assert [f.name for f in declared] == cf.extra["uninitialised"]
    assert declared[0].name == "OffsetEsteira1" and declared[0].line == 72
    assert all(f.pose is None for f in declared)
    stub = corpus("b-dosymzhan__KUKA-powerbank-assembly-safety-AI__$config.dat")
    assert stub.stat().st_size == 281
    cf = both(Document.read(stub))
    assert [(f.name, f.pose, f.line) for f in cf.frames] == [("COM_FRAME", None, 14)]
    assert cf.extra["uninitialised"] == ["COM_FRAME"]


@needs_corpus
def test_abc_to_q_against_scipy():
    Rotation = pytest.importorskip("scipy.spatial.transform").Rotation
    n = 0
    for path in corpus_files + sorted(FIXTURES.glob("*.dat")):
        for fr in krl.parse(Document.read(path)).frames:
            if fr.pose is None:
                continue
            q = Rotation.from_euler("ZYX", list(fr.pose.abc), degrees=True).as_quat(scalar_first=True)
            if q[0] < 0:
                q = -q
            assert max(abs(a - b) for a, b in zip(fr.pose.q, q)) < 1e-12, fr.name
            n += 1
    assert n > 500


# -- hand-written fixtures ------------------------------------------------------------
def test_cell_config_fixture_references_roles_and_lints():
    cf = both(Document.read(FIXTURES / "cell_config.dat"))
    by = {f.name: f for f in cf.frames}
    assert by["TOOL_DATA[1]"].info["role"] == "tool"
    assert by["TOOL_DATA[2]"].info["role"] == "workpiece" and by["TOOL_DATA[2]"].label == "HeldPanel"
    assert all(by[f"TOOL_DATA[{i}]"].reference == "flange" for i in range(1, 5))
    assert by["BASE_DATA[2]"].info["role"] == "external_tcp" and by["BASE_DATA[2]"].reference == "world"
    b3 = by["BASE_DATA[3]"]
    assert b3.reference == "machine"
    assert b3.info["machine"]["index"] == 2 and b3.info["machine"]["parent"] == "DKP-400"
    assert b3.info["machine"]["definition"]["root"]["x"] == 2000.0
    t3 = by["TOOL_DATA[3]"]
    assert t3.pose is None and set(t3.numbers) == {"x", "y", "z", "a", "b"}
    assert t3.as_dict()["x"] is None
    assert by["TOOL_DATA[4]"].label is None                # " " is no label
    codes = {(lint.code, lint.line) for lint in cf.lints}
    assert codes == {("missing-component", 14), ("label-too-long", 19), ("base-not-world", 36),
                     ("duplicate-label", 42)}
    with pytest.raises(UcsioError, match="ambiguous"):
        cf.frame("GRIPPER")
    assert cf.frame("table").name == "BASE_DATA[1]"


def test_variants_fixture():
    cf = both(Document.read(FIXTURES / "variants.dat"))
    f = {fr.name: fr for fr in cf.frames}
    assert list(f) == ["compact", "spaced", "noDeclFrame", "reordered", "mixedCase", "typed",
                       "expo", "two1", "two2", "noValue", "shifts[1]", "shifts[2]", "shifts[3]",
                       "grid[1,2]"]
    assert f["noValue"].pose is None and f["noValue"].line == 55
    assert f["compact"].pose.t == (10.5, -20.25, 300.0) and f["compact"].pose.abc == (90, -45, 180)
    assert f["spaced"].pose.abc == (10.0, 20.0, 30.0) and f["spaced"].info == {"global": True}
    assert f["reordered"].pose.t == (10.0, 20.0, 30.0) and f["reordered"].pose.abc == (1, 2, 3)
    assert list(f["reordered"].numbers) == ["x", "y", "z", "a", "b", "c"]
    assert f["typed"].pose.t == (34.4, -23.2, 0.0)
    e = f["expo"]
    assert e.pose.t == (150.0, -0.002, 0.0) and e.pose.abc == (-0.6, 1.0, 10.0)
    assert e.numbers["b"].text == "+1.0" and e.numbers["a"].text == "-.6"
    assert f["shifts[2]"].line == 58 and f["grid[1,2]"].pose.t == (1.0, 2.0, 3.0)
    assert cf.extra["arrays"] == {"shifts": [3], "grid": [2, 2]}
    assert cf.extra["uninitialised"] == ["noValue"]
    assert cf.extra["defdat"] == {"name": "VARIANTS", "public": True}
    assert "commentedOut" not in f
    assert [(l.code, l.line, l.severity) for l in cf.lints] == [("no-value", 55, "info")]


# one test per syntax variant of FORMATS.md 2.9 (small inline data lists)
VARIANTS = {
    "no header": "DEFDAT X\nFRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}\nENDDAT\n",
    "odd headers": "&ACCESS  RV$4\n&PARAM DISKPATH = \n&PARAM VERSION=1.0.0\n&COMMENT x ; y\n"
                   "DEFDAT X\nFRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}\nENDDAT\n",
    "DEFDAT two spaces, upper name, PUBLIC": wrap("FRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}\n",
                                                 "DEFDAT  UPPER_NAME PUBLIC\n"),
    "no final newline": "DEFDAT X\nFRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}\nENDDAT",
    "trailing comment lines": wrap("FRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}\n") + "; after\n\n",
    "DECL absent": wrap("FRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}\n"),
    "DECL present": wrap("DECL FRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}\n"),
    "GLOBAL CONST orders": wrap("DECL GLOBAL CONST INT a=1\nDECL CONST GLOBAL INT b=2\n"
                                "GLOBAL DECL FRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}\n"),
    "spaces around =": wrap("DECL FRAME F = {X 1,Y 2,Z 3,A 4,B 5,C 6}\nINT i =1\nINT j= 2\n"),
    "trailing comment and bare ;": wrap("FRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6} ; note\nINT k=1;\n"),
    "folds with metadata": wrap(";FOLD USER GLOBALS;%{E}%MKUKATPUSER,%CEXT,%VEXT,%P\n"
                                "FRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}\n; ;FOLD x\n;ENDFOLD (USER)\n"),
    "compact aggregate": wrap("FRAME F={X 1.0,Y 2.0,Z 3.0,A 4.0,B 5.0,C 6.0}\n"),
    "spaced aggregate": wrap("FRAME F={ X 1.0, Y 2.0 , Z 3.0,A 4.0,B 5.0, C 6.0 }\n"),
    "reordered aggregate": wrap("FRAME F={C 6,A 4,B 5,Z 3,X 1,Y 2}\n"),
    "bit and hex literals": wrap("INT g='B0101', h='H0F', l='b1'\nFRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}\n"),
    "[i,] and [] CHAR indices": wrap("DECL CHAR N[2,24]\nN[1,]=\"x\"\nDECL CHAR P[8]\nP[]=\"  \"\n"
                                     "FRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}\n"),
    "CHAR fields in aggregates": wrap("DECL FDAT FP={TOOL_NO 1,POINT2[] \" \",TQ_STATE FALSE}\n"
                                      "FRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}\n"),
    "SIGNAL ... TO": wrap("SIGNAL ExtUserID $IN[1026]  TO $IN[1026]\nSIGNAL s $OUT[2]\n"
                          "FRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}\n"),
    "ENUM and STRUC": wrap("ENUM IPO_M_T NONE,TCP,BASE\nSTRUC S INT a,b,REAL c,CHAR n[24]\n"
                           "GLOBAL STRUC T FRAME f\nFRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}\n"),
    "EXT and EXTFCT": wrap("EXT  BAS (BAS_COMMAND  :IN,REAL  :IN )\nEXT IR_STOPM ( )\n"
                           "EXTFCT INT F1(INT :IN)\nFRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}\n"),
    "names with $": wrap("INT $ACT_GROUP='B0001'\nDECL FRAME $F={X 1,Y 2,Z 3,A 4,B 5,C 6}\n"),
    "lower and mixed case": wrap("decl global frame f={x 1,y 2,Z 3,a 4,B 5,c 6}\nInt i=1\n",
                                 "defdat lower public\n").replace("ENDDAT", "EndDat"),
    "keyword-like names": wrap("DECL INT public=1, to=2, signal=3\n"
                               "DECL FRAME Ext={X 1,Y 2,Z 3,A 4,B 5,C 6}\n"),
    "several names per line": wrap("DECL FRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}, G\n"),
    "3-D arrays": wrap("DECL INT CUBE[2,3,4]\nCUBE[1,2,3]=5\nDECL FRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}\n"),
    "exponents": wrap("REAL r=1.00000E+19\nFRAME F={X 0.1E1,Y 2.0e-0,Z 3.,A .4E1,B 5,C 6}\n"),
    "Type: prefix": wrap("FRAME F={REAL:X 1,REAL: Y 2,Z 3,A 4,B 5,C 6}\n"),
    "nested aggregates": wrap("DECL LOAD L={M 1.0,CM {X 1,Y 2,Z 3,A 0,B 0,C 0},J {X 1,Y 1,Z 1}}\n"
                              "FRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}\n"),
    "#ENUM values": wrap("DECL CIRC_TYPE C=#BASE\nDECL X Y={M # NONE}\nFRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}\n"),
    "tabs": wrap("\tDECL\tFRAME\tF={X 1,\tY 2,Z 3,A 4,B 5,C 6}\t;tab\n"),
    "blank lines and indentation": wrap("\n\n   FRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}\n   \n\n"),
    "fragment without DEFDAT": "  CONST FRAME F = {X 1,Y 2,Z 3,A 4,B 5,C 6}\n  INT i\n",
    "fragment without newline": "FRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}",
    "cp1252 bytes in comments": wrap("; vorw\xe4hlen a\xf1o \xb0\nFRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6} ; \xe9\n"),
}


@pytest.mark.parametrize("name", list(VARIANTS))
def test_syntax_variant(name):
    text = VARIANTS[name]
    doc = doc_of(text)
    cf = both(doc)
    (fr,) = [f for f in cf.frames if f.name.upper() in ("F", "$F", "EXT")]
    assert fr.pose.t == (1.0, 2.0, 3.0) and fr.pose.abc == (4.0, 5.0, 6.0)
    for comp, num in fr.numbers.items():
        assert doc.text[num.span.start:num.span.end] == num.text
    assert doc.to_bytes() == doc.raw


@pytest.mark.parametrize("ending", ["\r\n", "mixed"])
def test_crlf_mixed_endings_and_cp1252_round_trip(ending):
    base = (FIXTURES / "cell_config.dat").read_bytes().decode("ascii")
    lines = base.split("\n")
    if ending == "mixed":
        text = "".join(line + ("\r\n" if i % 3 else "\n") for i, line in enumerate(lines[:-1]))
    else:
        text = "\r\n".join(lines)
    text = text.replace("; hand-written", "; hand-written \xe4\xf1\xb0")
    raw = text.encode("cp1252")
    doc = Document(raw, "cell.dat")
    assert doc.encoding == "latin-1"
    cf = both(doc)
    assert doc.to_bytes() == raw
    ref = both(Document.read(FIXTURES / "cell_config.dat"))
    assert [(f.name, f.line, f.label, f.pose) for f in cf.frames] == \
        [(f.name, f.line, f.label, f.pose) for f in ref.frames]
    for fr in cf.frames:
        for num in fr.numbers.values():
            assert doc.text[num.span.start:num.span.end] == num.text


# -- bad input ------------------------------------------------------------------------
BAD = [
    ("unterminated struct", "BASE_DATA[1]={X 1.0,Y 2.0,Z 3.0,A 0,B 0,C 0\n", 4, 44,
     "unterminated structure", True),
    ("bad number", "BASE_DATA[1]={X 1.2.3,Y 2.0,Z 3.0,A 0,B 0,C 0}\n", 4, 17,
     "malformed number '1.2.3'", True),
    ("bad exponent", "BASE_DATA[1]={X 1.0E,Y 2.0,Z 3.0,A 0,B 0,C 0}\n", 4, 17,
     "malformed number '1.0E'", True),
    ("unterminated string", 'BASE_NAME[1,]="abc\n', 4, 15, "unterminated string", True),
    ("garbage line", "this is garbage\n", 4, 9, "syntax error", False),
    ("stray character", "INT i=1 @\n", 4, 9, "unexpected character '@'", False),
    ("missing value", "DECL FRAME F=\n", 4, 14, "unexpected end of line", True),
]


@pytest.mark.parametrize("name,line,lineno,col,msg,fast", BAD, ids=[b[0] for b in BAD])
def test_bad_input_is_one_positioned_error(name, line, lineno, col, msg, fast):
    doc = doc_of(wrap(line), "bad.dat")
    with pytest.raises(UcsioError) as e:
        krl.parse(doc, full=True)
    assert (e.value.line, e.value.col) == (lineno, col)
    assert msg in e.value.message
    assert str(e.value).startswith(f"bad.dat:{lineno}:{col}: ")
    if fast:     # a line the fast path reads: same error there
        with pytest.raises(UcsioError) as e2:
            krl.parse(doc)
        assert str(e2.value) == str(e.value)
    else:        # a line frames do not depend on: only `check` (full) looks at it
        assert krl.parse(doc).frames == []


def test_missing_enddat():
    doc = doc_of("&ACCESS RV\nDEFDAT X\nFRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6}\n", "m.dat")
    for full in (False, True):
        with pytest.raises(UcsioError, match="missing ENDDAT") as e:
            krl.parse(doc, full=full)
        assert str(e.value).startswith("m.dat:4:1: ")


def test_text_after_enddat_and_statement_before_defdat():
    with pytest.raises(UcsioError, match="after ENDDAT") as e:
        krl.parse(doc_of(wrap("") + "INT i=1\n"), full=True)
    assert e.value.line == 5
    with pytest.raises(UcsioError) as e:
        krl.parse(doc_of("INT i=1\nDEFDAT X\nENDDAT\n"), full=True)
    assert e.value.line == 2 and "DEFDAT" in e.value.message


# the layout (& headers, DEFDAT, ENDDAT): the fast path checks it too, with the
# same error at the same place as `check`, though it parses only a few lines
BASE1 = "BASE_DATA[1]={X 1,Y 2,Z 3,A 4,B 5,C 6}\n"
LAYOUT = [
    ("statement after ENDDAT", "DEFDAT X\n" + BASE1 + "ENDDAT\nBASE_DATA[2]={X 1,Y 2,Z 3,A 4,B 5,C 6}\n",
     4, 1, "unexpected 'BASE_DATA' after ENDDAT"),
    ("statement after ENDDAT and comments", "DEFDAT X\n" + BASE1 + "ENDDAT\n\n;c\n  ; d\nINT i\n;e\n",
     7, 1, "unexpected 'INT' after ENDDAT"),
    ("header after ENDDAT", "DEFDAT X\n" + BASE1 + "ENDDAT\n;c\n&ACCESS RV\n", 5, 1, "after ENDDAT"),
    ("second ENDDAT", "DEFDAT X\n" + BASE1 + "ENDDAT\nENDDAT\n", 4, 1, "after ENDDAT"),
    ("text on the ENDDAT line", "DEFDAT X\n" + BASE1 + "ENDDAT X\n", 3, 8, "unexpected 'X'"),
    ("two DEFDAT lines", "DEFDAT X\nDEFDAT Y\n" + BASE1 + "ENDDAT\n", 2, 1,
     "unexpected DEFDAT: DEFDAT must come first"),
    ("a later DEFDAT line", "&ACCESS RV\nDEFDAT X\n" + BASE1 + "INT i=1\nDEFDAT Y\nENDDAT\n", 5, 1,
     "unexpected DEFDAT"),
    ("DEFDAT without a name", "DEFDAT\n" + BASE1 + "ENDDAT\n", 1, 7, "expected a name"),
    ("DEFDAT PUBLIC PUBLIC", "DEFDAT X PUBLIC PUBLIC\n" + BASE1 + "ENDDAT\n", 1, 17,
     "unexpected 'PUBLIC'"),
    ("header after DEFDAT", "&ACCESS RV\nDEFDAT X\n&REL 1\n" + BASE1 + "ENDDAT\n", 3, 1,
     "unexpected '&REL 1'"),
    ("header in a fragment", "INT i=1\n" + BASE1 + "&REL 1\n", 3, 1, "unexpected '&REL 1'"),
    ("statement before DEFDAT", "INT i=1\nDEFDAT X\n" + BASE1 + "ENDDAT\n", 2, 1,
     "DEFDAT must come first"),
    ("statement between headers", "&ACCESS RV\nINT i=1\n&REL 1\nDEFDAT X\n" + BASE1 + "ENDDAT\n",
     4, 1, "DEFDAT must come first"),
    ("ENDDAT= in the body", "DEFDAT X\n" + BASE1 + "ENDDAT=5\nENDDAT\n", 3, 7, "unexpected '='"),
    ("missing ENDDAT", "&ACCESS RV\nDEFDAT X\n" + BASE1 + ";ENDDAT\n", 5, 1, "missing ENDDAT"),
    ("ENDDAT in a fragment", "INT i\nENDDAT X\n" + BASE1, 2, 1, "unexpected ENDDAT"),
]


@pytest.mark.parametrize("name,text,lineno,col,msg", LAYOUT, ids=[c[0] for c in LAYOUT])
def test_layout_errors_are_the_same_on_both_paths(name, text, lineno, col, msg):
    doc = doc_of(text, "t.dat")
    errors = []
    for full in (True, False):
        with pytest.raises(UcsioError) as e:
            krl.parse(doc, full=full)
        errors.append(e.value)
    assert (errors[0].line, errors[0].col) == (lineno, col)
    assert msg in errors[0].message and "\n" not in str(errors[0])
    assert str(errors[1]) == str(errors[0])


def test_the_fast_path_reads_the_layout_lines_only():
    text = ("&ACCESS RV\n;c\n&REL 1\nDEFDAT X PUBLIC\nINT i=1\n" + BASE1 + "INT j=2\nENDDAT\n"
            ";c\n\nINT k\nINT l\n")
    assert selected(text) == ["&ACCESS RV", "&REL 1", "DEFDAT X PUBLIC", BASE1[:-1], "ENDDAT",
                              "INT k"]
    # a fragment: its first statement
    assert selected(";c\n\n  INT i=1\nINT j\n" + BASE1) == ["  INT i=1", BASE1[:-1]]


@pytest.mark.parametrize("text", [
    # comment and blank lines before, between and after the header lines
    "&ACCESS RVP\n;a comment\n&REL 1\n\n  ;another\n\n&PARAM X = Y\n;c\nDEFDAT T\n" + BASE1 + "ENDDAT\n",
    ";first\n;second\n\n&ACCESS RVP\nDEFDAT T PUBLIC ; c\n;c\n" + BASE1 + "ENDDAT",
    # blank, white and comment lines after ENDDAT
    "DEFDAT T\n" + BASE1 + "ENDDAT ; end\n\n \t\r\n;c\n  ;d\n\n",
    "DEFDAT T\n" + BASE1 + "ENDDAT\n;FOLD\n;ENDFOLD",
    # DEFDAT and ENDDAT spelt as other names inside the data list
    "DEFDAT T\n" + BASE1 + "DEFDAT[1]=5\nDECL INT ENDDAT\nENDDAT\n",
    # a fragment
    ";c\n\nINT i=1\n;c\n" + BASE1 + "\n",
])
def test_comment_and_blank_lines_anywhere_around_the_layout(text):
    cf = both(doc_of(text))
    assert [f.name for f in cf.frames] == ["BASE_DATA[1]"]


def test_out_of_range_real():
    with pytest.raises(UcsioError, match="out of range") as e:
        krl.parse(doc_of(wrap("FRAME F={X 1E39,Y 2,Z 3,A 4,B 5,C 6}\n")))
    assert (e.value.line, e.value.col) == (4, 12)


def test_controller_load_reports_file_line_col(tmp_path):
    p = tmp_path / "$config.dat"
    p.write_bytes(b"DEFDAT $CONFIG\r\nDECL FRAME BASE_DATA[2]\r\nBASE_DATA[1]={X 1,Y 2,Z 3,A 4,B 5,C 6\r\nENDDAT\r\n")
    with pytest.raises(UcsioError) as e:
        controller.load(p)
    assert str(e.value).startswith(f"{p}:3:") and "missing '}'" in str(e.value)


# -- lints ---------------------------------------------------------------------------
def lint_codes(text):
    return [(lint.code, lint.line) for lint in both(doc_of(wrap(text))).lints]


def test_lints():
    assert lint_codes("DECL FRAME F={X 1,Y 2,Z 3,A 4,B 5}\n") == [("missing-component", 4)]
    assert lint_codes("DECL FRAME F={X 1,Y 2,Z 3,A 4,B 5,C 6,S 2}\n") == [("unknown-component", 4)]
    assert lint_codes("DECL FRAME F={X 1,X 1,Y 2,Z 3,A 4,B 5,C 6}\n") == [("duplicate-component", 4)]
    assert lint_codes("DECL FRAME F={X #A,Y 2,Z 3,A 4,B 5,C 6}\n") == \
        [("not-a-number", 4), ("missing-component", 4)]
    assert lint_codes("DECL FRAME F=5\n") == [("not-a-frame", 4)]
    assert lint_codes("DECL FRAME A[2]\nA[3]={X 1,Y 2,Z 3,A 4,B 5,C 6}\n") == [("index-out-of-range", 5)]
    assert lint_codes("DECL FRAME A[2]\nA[1]={X 1,Y 2,Z 3,A 4,B 5,C 6}\nA[1]={X 1,Y 2,Z 3,A 4,B 5,C 6}\n") \
        == [("duplicate-frame", 6)]
    assert lint_codes("BASE_DATA[1]={X 1,Y 2,Z 3,A 4,B 5,C 6}\nBASE_TYPE[1]=#FOO\n") == \
        [("unknown-type", 5), ("base-not-world", 3 + 1)]
    assert lint_codes('TOOL_DATA[1]={X 1,Y 2,Z 3,A 4,B 5,C 6}\nTOOL_NAME[1,]="a234567890123456789012345"\n') \
        == [("label-too-long", 5)]
    assert lint_codes('TOOL_DATA[1]={X 1,Y 2,Z 3,A 4,B 5,C 6}\nTOOL_DATA[2]={X 1,Y 2,Z 3,A 4,B 5,C 6}\n'
                      'TOOL_NAME[1,]="same"\nTOOL_NAME[2,]="SAME"\n') == [("duplicate-label", 7)]
    assert lint_codes('TOOL_DATA[1]={X 1,Y 2,Z 3,A 4,B 5,C 6}\nTOOL_NAME[1,]=5\n') == [("bad-label", 5)]


def test_labels_are_stripped_on_both_sides():
    cf = both(doc_of(wrap(BASE1 + 'BASE_NAME[1,]="  padded  "\n')))
    fr = cf.frame("BASE_DATA[1]")
    assert fr.label == "padded"
    assert cf.frame("padded") is cf.frame("  PADDED ") is fr


def test_base_on_an_external_kinematic_names_the_kinematic_not_its_parent():
    base2 = "BASE_DATA[2]={X 1,Y 2,Z 3,A 4,B 5,C 6}\n"
    cf = both(doc_of(wrap(BASE1 + base2
                          + 'MACHINE_DEF[2]={NAME[] "DKP-400 ",PARENT[] "WORLD"}\n'
                          'MACHINE_FRAME_DAT[1]={MACH_DEF_INDEX 2,PARENT[] "WORLD"}\n'
                          'MACHINE_FRAME_DAT[2]={MACH_DEF_INDEX 3,PARENT[] "  "}\n')))
    msgs = [lint.message for lint in cf.lints if lint.code == "base-not-world"]
    assert msgs == [
        'BASE_DATA[1] is relative to external kinematic 2 "DKP-400" (MACHINE_FRAME_DAT[1]: '
        'MACH_DEF_INDEX 2, parent WORLD), not to world',
        "BASE_DATA[2] is relative to external kinematic 3 (MACHINE_FRAME_DAT[2]: "
        "MACH_DEF_INDEX 3), not to world"]


def test_labels_resolve_case_insensitively_and_blank_labels_are_none():
    cf = both(doc_of(wrap('BASE_DATA[1]={X 1,Y 2,Z 3,A 4,B 5,C 6}\nbase_data[2]={X 1,Y 2,Z 3,A 4,B 5,C 6}\n'
                          'BASE_NAME[1,]="Fixture A   "\nbase_name[2,]=""\n')))
    assert [f.name for f in cf.frames] == ["BASE_DATA[1]", "BASE_DATA[2]"]
    assert cf.frame("fixture a") is cf.frame("FIXTURE A") is cf.frame("Base_Data[1]")
    assert cf.frame("BASE_DATA[2]").label is None
    with pytest.raises(UcsioError, match="no frame named"):
        cf.frame("fixture")


def test_frames_json_keys():
    cf = both(Document.read(FIXTURES / "cell_config.dat"))
    d = cf.frame("TOOL_DATA[1]").as_dict()
    for key in ("name", "file", "line", "vendor", "type", "x", "y", "z", "a", "b", "c", "q", "label"):
        assert key in d
    assert d["vendor"] == "kuka" and d["type"] == "TOOL_DATA" and d["label"] == "Gripper"
    assert math.isclose(sum(c * c for c in d["q"]), 1.0)
    import json
    json.dumps([f.as_dict() for f in cf.frames])


# -- robustness ------------------------------------------------------------------------
def test_random_edits_give_frames_or_one_ucsio_error():
    """Any one-character edit of a data list parses or fails with a UcsioError
    that has a position; never another exception."""
    hypothesis = pytest.importorskip("hypothesis")
    st = hypothesis.strategies
    base = (FIXTURES / "cell_config.dat").read_text()

    @hypothesis.settings(max_examples=300, deadline=None, derandomize=True)
    @hypothesis.given(pos=st.integers(0, len(base)), op=st.sampled_from(["del", "ins", "rep"]),
                      ch=st.sampled_from(list('{}[],;="\'#.-+:E \n\r\t&xX0')))
    def check(pos, op, ch):
        text = {"del": base[:pos] + base[pos + 1:], "ins": base[:pos] + ch + base[pos:],
                "rep": base[:pos] + ch + base[pos + 1:]}[op]
        doc = doc_of(text)
        results = []
        for full in (False, True):
            try:
                cf = krl.parse(doc, full=full)
            except UcsioError as e:
                assert e.line is not None and e.col is not None
                results.append(None)
            else:
                for fr in cf.frames:
                    for num in fr.numbers.values():
                        assert doc.text[num.span.start:num.span.end] == num.text
                results.append(snapshot(cf))
        if None not in results:     # both paths read it: they agree
            assert results[0] == results[1]
        else:                       # what the full parse accepts, the fast path accepts
            assert results[1] is None
    check()


@pytest.mark.parametrize("index", ["0", "00", "0.5", "2", "+2", "-1", "1E0"])
def test_machine_tables_read_alike_on_both_paths(index):
    cf = both(doc_of(wrap("BASE_DATA[1]={X 1,Y 2,Z 3,A 4,B 5,C 6}\n"
                          f'MACHINE_FRAME_DAT[1]={{MACH_DEF_INDEX {index},PARENT[] "P"}}\n')))
    machine = int(float(index)) != 0
    assert cf.frame("BASE_DATA[1]").reference == ("machine" if machine else "world")


def selected(text):
    return [text[s:e] for s, e in krl.outline(text)]


def test_fast_path_reads_only_the_machine_entries_in_use():
    machine = ('MACHINE_DEF[1]={NAME[] "KR 16",ROOT {X 0,Y 0,Z 0,A 0,B 0,C 0}}\n'
               'MACHINE_DEF[02]={NAME[] "DKP",ROOT {X 2000,Y 0,Z 0,A 0,B 0,C 0}}\n'
               'MACHINE_DEF[3]={NAME[] "other"}\n'
               "MACHINE_FRAME_DAT[1]={MACH_DEF_INDEX 0,PARENT[] \"WORLD\"}\n"
               "MACHINE_FRAME_DAT[2]={MACH_DEF_INDEX[] 2,PARENT[] \"DKP\"}\n"
               "MACHINE_TOOL_DAT[1]={MACH_DEF_INDEX 3}\n")
    text = wrap("BASE_DATA[1]={X 1,Y 2,Z 3,A 4,B 5,C 6}\nBASE_DATA[2]={X 1,Y 2,Z 3,A 4,B 5,C 6}\n"
                + machine)
    lines = selected(text)
    assert [line[:20] for line in lines if line.startswith("MACHINE")] == \
        ["MACHINE_DEF[02]={NAM", "MACHINE_FRAME_DAT[2]"]
    cf = both(doc_of(text))
    b2 = cf.frame("BASE_DATA[2]")
    assert b2.reference == "machine" and b2.info["machine"]["index"] == 2
    assert b2.info["machine"]["definition"]["root"]["x"] == 2000.0
    assert cf.frame("BASE_DATA[1]").reference == "world"
    # no entry in use: no machine line at all
    assert not [line for line in selected(text.replace("INDEX[] 2", "INDEX 0"))
                if line.startswith("MACHINE")]


def test_a_machine_entry_with_index_0_is_ignored_on_both_paths():
    # a later MACHINE_FRAME_DAT[1] with index 0 does not undo the earlier one:
    # the interpretation ignores entries not tied to a kinematic
    cf = both(doc_of(wrap("BASE_DATA[1]={X 1,Y 2,Z 3,A 4,B 5,C 6}\n"
                          'MACHINE_FRAME_DAT[1]={MACH_DEF_INDEX 2,PARENT[] "P"}\n'
                          'MACHINE_FRAME_DAT[1]={MACH_DEF_INDEX 0,PARENT[] "WORLD"}\n')))
    assert cf.frame("BASE_DATA[1]").reference == "machine"
    # an error in an unused entry is found by `check` (full) only
    doc = doc_of(wrap("BASE_DATA[1]={X 1,Y 2,Z 3,A 4,B 5,C 6}\n"
                      "MACHINE_FRAME_DAT[1]={MACH_DEF_INDEX 0,PARENT[] \"W}\n"
                      "MACHINE_FRAME_DAT[2]={MACH_DEF_INDEX 1}\n"))
    assert krl.parse(doc).frame("BASE_DATA[1]").reference == "world"
    with pytest.raises(UcsioError, match="unterminated string"):
        krl.parse(doc, full=True)


def test_repeated_values_are_read_once_with_their_own_positions():
    zero = "={X 0.0,Y 0.0,Z 0.0,A 0.0,B 0.0,C 0.0}"
    text = wrap("DECL FRAME P[4]\n" + "".join(f"P[{i}]{zero}\n" for i in (1, 2, 3))
                + f"DECL FRAME Q{zero}\n"
                + "P[4]={X 1,Y 2,Z 3,S 4,A 5,B 6,C 7}\n"
                + "BASE_DATA[1]  ={X 1,Y 2,Z 3,S 4,A 5,B 6,C 7}\n"
                + 'TOOL_NAME[1,]="same"\nTOOL_NAME[2,]="same"\n')
    placeholders, shared = krl._shared_values(text, krl.outline(text))
    assert len(shared) == 4           # P[2], P[3], BASE_DATA[1], TOOL_NAME[2]; not the DECL line
    doc = doc_of(text)
    assert krl._shared_parse(doc, doc.text, krl.outline(doc.text)) is not None
    cf = both(doc)
    for fr in cf.frames:
        for num in fr.numbers.values():
            assert doc.text[num.span.start:num.span.end] == num.text
            assert doc.line_of(num.span.start) == fr.line
    assert [(lint.code, lint.line, lint.col) for lint in cf.lints] == \
        [("unknown-component", 9, 19), ("unknown-component", 10, 29)]
    # an error in a repeated value: reported where the text has it first
    bad = wrap("BASE_DATA[1]={X 1,Y 2,Z 3,A 4,B 5,C 6}\n" * 2 + "BASE_DATA[2]={X 1.2.3}\n" * 2)
    with pytest.raises(UcsioError) as e:
        krl.parse(doc_of(bad))
    assert (e.value.line, e.value.col) == (6, 17) and "malformed number" in e.value.message



def test_angles_outside_spec_ranges_are_listed_as_written():
    # KUKA itself writes B -180.000 (Zinkerreka TOOL_DATA[1]); frames lists A, B, C
    # as written, and diff compares canonical angles (tests/test_diff.py)
    doc = Document(b"DEFDAT x\nDECL FRAME f={X 1.0,Y 2.0,Z 3.0,A 200.0,B 100.0,C -181.0}\nENDDAT\n", "x.dat")
    cf = krl.parse(doc)
    assert cf.lints == [] and cf.frame("f").pose.abc == (200.0, 100.0, -181.0)


def test_cp1252_labels_read_as_windows_text():
    raw = ('DEFDAT $CONFIG\nDECL FRAME BASE_DATA[2]\nBASE_DATA[1]={X 1.0,Y 2.0,Z 3.0,A 0.0,B 0.0,C 0.0}\n'
           'DECL CHAR BASE_NAME[2,24]\nBASE_NAME[1,]="Tisch \u2013 Stra\u00dfe \u20ac"\nENDDAT\n').encode("cp1252")
    doc = Document(raw, "$config.dat")
    cf = krl.parse(doc)
    assert doc.encoding == "latin-1" and doc.to_bytes() == raw          # bytes untouched
    assert cf.frame("tisch \u2013 STRASSE \u20ac".replace("STRASSE", "stra\u00dfe")).name == "BASE_DATA[1]"
    assert cf.frames[0].label == "Tisch \u2013 Stra\u00dfe \u20ac"


def test_empty_file_is_an_error():
    for raw in (b"", b"\r\n  \n"):
        with pytest.raises(UcsioError, match="empty file"):
            krl.parse(Document(raw, "empty.dat"))


def test_entry_name_wins_over_a_label_spelled_like_it():
    raw = (b'DEFDAT $CONFIG\nDECL FRAME BASE_DATA[2]\nBASE_DATA[1]={X 1.0,Y 2.0,Z 3.0,A 0.0,B 0.0,C 0.0}\n'
           b'BASE_DATA[2]={X 9.0,Y 2.0,Z 3.0,A 0.0,B 0.0,C 0.0}\nDECL CHAR BASE_NAME[2,24]\n'
           b'BASE_NAME[2,]="BASE_DATA[1]"\nENDDAT\n')
    cf = krl.parse(Document(raw, "$config.dat"))
    assert cf.frame("base_data[1]").pose.x == 1.0


# -- declarations of real KRC system files (issue 18, point 3) -------------------------
def test_system_file_declarations_are_read():
    """CHANNEL ($custom.dat), EXTFCTP with named parameters ($OPERATE.dat), STRUC
    members without the comma before a new type, IMPORT: accepted by the fast
    path and the whole tree alike; the file checks clean."""
    path = FIXTURES / "custom_declarations.dat"
    doc = Document.read(path)
    cf = both(doc)
    full = krl.parse(doc, full=True)
    assert snapshot(full) == snapshot(cf)
    assert [f.name for f in cf.frames] == ["$SINGUL_ERR_JOG"]
    # a partial FRAME outside the tool/base tables is legal KRL: an info, not a warning
    (lint,) = cf.lints
    assert (lint.code, lint.severity, lint.line) == ("missing-component", "info", 24)
    assert doc.to_bytes() == path.read_bytes()


@pytest.mark.parametrize("line", [
    "CHANNEL :SER_1 :SER_1 $PSER_1",
    "CHANNEL :PG :SER_1 $PPG ;PG",
    "EXTFCTP  INT INTERIMENERGY(CHAR STRVAR[256] :IN)",
    "EXTFCTP  BOOL GETSYSSTATE(CHAR CMD[64] :IN,INT IPAR :OUT,REAL RPAR :OUT)",
    "EXT  P00 (P00_COMMAND  :IN,FUNCT_TYPE  :IN,CHAR [] :OUT,INT  :IN )",
    "GLOBAL STRUC S_A INT ID, n CHAR name[24], REAL w",
    "IMPORT INT MY_COUNT IS /R1/MYDATA..COUNT",
])
def test_each_system_declaration_alone(line):
    cf = both(doc_of(wrap(line + "\n")))
    assert cf.lints == [] and cf.frames == []


@pytest.mark.parametrize("line, col", [
    ("CHANNEL SER_1 :SER_1 $PSER_1", 9),          # the colon is part of the syntax
    ("CHANNEL :SER_1 :SER_1", 22),
    ("EXTFCTP INT F(CHAR S[256] :IN", 30),
    ("IMPORT INT X IS R1..Y", 17),
])
def test_broken_system_declarations_are_refused_where_they_break(line, col):
    with pytest.raises(UcsioError) as e:
        krl.parse(doc_of(wrap(line + "\n")), full=True)
    assert e.value.line == 4 and e.value.col == col, str(e.value)


def test_partial_table_frame_is_still_a_warning():
    cf = both(doc_of(wrap("DECL FRAME BASE_DATA[2]\nBASE_DATA[1]={X 1,Y 2,Z 3,A 4,B 5}\n")))
    assert [(lint.code, lint.severity) for lint in cf.lints] == [("missing-component", "warning")]


# -- element lines read without the parser (krl._plain_statements) ---------------------
def _element_line():
    st = pytest.importorskip("hypothesis").strategies
    blank = st.sampled_from(["", " ", "  ", "\t", " \t"])
    number = st.sampled_from(["0.0", "-1.00000", "1500.00", "+2", ".5", "-.6", "1.", "1E3",
                              "-1.38059322E-5", "2.48660E+06", "1.0.5", "1e", "00", "-0"])
    key = st.sampled_from(["X", "Y", "Z", "A", "B", "C", "x", "S", "E1", "X1", "$Q", "é"])
    field = st.tuples(key, st.sampled_from([" ", "  ", "\t", ""]), number).map("".join)
    struct = st.tuples(blank, st.lists(st.tuples(field, blank, blank), min_size=1, max_size=7),
                       blank).map(lambda t: "{" + t[0] + ",".join(f + b1 + "" for f, b1, _ in t[1])
                                  + t[2] + "}")
    value = st.one_of(struct, st.sampled_from(['"pickBP"', '" "', '""', "#BASE", "# TCP",
                                                "#none", "TRUE", "'A'", "{M -1,CM {X 0}}",
                                                "{X 1,Y 2", "5", "NAME"]))
    name = st.sampled_from(["BASE_DATA", "TOOL_DATA", "BASE_NAME", "TOOL_NAME", "BASE_TYPE",
                            "TOOL_TYPE", "LOAD_DATA", "base_data", "REF_PT", "DECL", "ENUM"])
    index = st.sampled_from(["[1]", "[3]", "[2,]", "[ 1]", "[01]", "[1,2]", "[]", "[33]"])
    tail = st.sampled_from(["", " ", " ; note", ";", "; {X 1}", " junk"])
    return st.tuples(name, index, blank, blank, value, tail).map(
        lambda t: f"{t[0]}{t[1]}{t[2]}={t[3]}{t[4]}{t[5]}")


def test_plain_element_lines_read_as_the_parser_reads_them():
    """Lines the fast path reads straight from their words give the frames,
    lints and tables the grammar's tree gives, whatever their spacing,
    numbers and comments; a line it cannot read that way goes through the
    parser, so a broken one fails as before."""
    hypothesis = pytest.importorskip("hypothesis")
    st = hypothesis.strategies
    head = ("DEFDAT  $CONFIG\nDECL FRAME BASE_DATA[32]\nDECL FRAME TOOL_DATA[16]\n"
            "DECL FRAME REF_PT[4]\nDECL CHAR BASE_NAME[32,24]\nDECL LOAD LOAD_DATA[16]\n")

    def outline_through_the_parser(doc):
        """The fast path without its shortcuts: every outline line parsed."""
        text = krl._lines(doc)
        tree = krl._parse(doc, krl.masked(text, krl.outline(text)), "file")
        return krl._interpret(doc, krl._statements(tree, doc), tree)

    def result(read, doc):
        try:
            return snapshot(read(doc))
        except UcsioError as e:
            return ("error", e.line, e.col, e.message)

    @hypothesis.settings(max_examples=200, deadline=None, derandomize=True)
    @hypothesis.given(st.lists(_element_line(), min_size=1, max_size=6))
    def check(lines):
        doc = doc_of(head + "\n".join(lines) + "\nENDDAT\n")
        fast = result(krl.parse, doc)
        assert fast == result(outline_through_the_parser, doc)
        whole = result(krl.parse_whole, doc)
        if fast[0] != "error" and whole[0] != "error":
            assert fast == whole
    check()


def test_a_config_s_element_lines_are_read_without_the_parser():
    """The 32 bases, names and types of a controller's $config.dat are read
    from their words: the parser sees the rest (nested LOAD_DATA values)."""
    text = wrap("DECL FRAME BASE_DATA[3]\n" + "".join(
        f"BASE_DATA[{i}]={{X {i}.0,Y 0.0,Z 0.0,A 0.0,B 0.0,C 0.0}}\n"
        f'BASE_NAME[{i},]="b{i}"\nBASE_TYPE[{i}]=#BASE\n' for i in range(1, 4))
        + "LOAD_DATA[1]={M -1.00000,CM {X 0.0,Y 0.0,Z 0.0,A 0.0,B 0.0,C 0.0},J {X 0.0,Y 0.0,Z 0.0}}\n")
    doc = doc_of(text)
    plain, rest = krl._plain_statements(doc, doc.text, krl.outline(doc.text))
    assert len(plain) == 9
    assert [doc.text[s:e].split("[")[0] for s, e in rest if "[" in doc.text[s:e]] == \
        ["DECL FRAME BASE_DATA", "LOAD_DATA"]
    assert snapshot(krl.parse(doc)) == snapshot(krl.parse_whole(doc))
