"""Fuzzing in the suite (issue 12 points 4 and 8): deterministic hypothesis
runs of tests/fuzzing.py's oracle over mutated real files and over generated
modules, a few hundred examples in all. Longer hunts:
``python benchmarks/fuzz.py --minutes 30`` (saves failing inputs).

Failing inputs found so far are kept in fixtures/fuzz/ and replayed here."""
from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import fuzzing
from conftest import FIXTURES

SEEDS = fuzzing.seed_files(max_size=12_000)
RAPID_SEEDS = [p for p in SEEDS if p.suffix.lower() in (".mod", ".modx", ".sys", ".prg")]
KRL_SEEDS = [p for p in SEEDS if p.suffix.lower() == ".dat"]
# FANUC: the programs and listings under 12 KB, and one sysframe.va of each layout
FANUC_SEEDS = [p for p in fuzzing.seed_files(max_size=40_000)
               if p.suffix.lower() in (".va", ".dg", ".ls")
               and (p.stat().st_size <= 12_000 or p.name.endswith(("UB10200_RBT01__sysframe.va",
                                                                   "kjltvr411670r01__SYSFRAME.VA")))]
# Yaskawa: the corpus's, our fixtures' and the demo cell's (R05) files
YASKAWA = [p for p in SEEDS if "yaskawa" in str(p).lower()]
YASKAWA_SEEDS = [p for p in YASKAWA if p.suffix.lower() != ".jbi"]    # .CND, RBCALIB, VAR.DAT
YASKAWA_JOBS = [p for p in YASKAWA if p.suffix.lower() == ".jbi"]
# Stäubli: the corpus's .dtx files and our fixtures (both dialects)
STAUBLI_SEEDS = [p for p in SEEDS if p.suffix.lower() == ".dtx"]
SETTINGS = dict(deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])

ops = st.lists(st.tuples(st.integers(0, fuzzing.KINDS - 1), st.integers(0, 1 << 20), st.integers(0, 1 << 20)),
               min_size=1, max_size=3)


@settings(max_examples=120, **SETTINGS)
@given(seed=st.sampled_from(RAPID_SEEDS), ops=ops)
def test_mutated_rapid_files(seed, ops):
    fuzzing.check_bytes(seed.name, fuzzing.mutate(seed.read_bytes(), ops))


@settings(max_examples=80, **SETTINGS)
@given(seed=st.sampled_from(KRL_SEEDS), ops=ops)
def test_mutated_krl_files(seed, ops):
    fuzzing.check_bytes(seed.name, fuzzing.mutate(seed.read_bytes(), ops))


@settings(max_examples=120, **SETTINGS)
@given(seed=st.sampled_from(FANUC_SEEDS), ops=ops)
def test_mutated_fanuc_files(seed, ops):
    fuzzing.check_bytes(seed.name, fuzzing.mutate(seed.read_bytes(), ops))


@settings(max_examples=60, **SETTINGS)
@given(seed=st.sampled_from(YASKAWA_SEEDS or [None]), ops=ops)
def test_mutated_yaskawa_files(seed, ops):
    """UFRAME.CND, TOOL.CND (a ///CRC file never written), RBCALIB.DAT and
    VAR.DAT (the free P variables ucsio program would take)."""
    if seed is None:
        pytest.skip("no Yaskawa seed (the shared corpus is absent)")
    fuzzing.check_bytes(seed.name, fuzzing.mutate(seed.read_bytes(), ops))


@settings(max_examples=60, **SETTINGS)
@given(seed=st.sampled_from(YASKAWA_JOBS or [None]), ops=ops)
def test_mutated_yaskawa_jobs(seed, ops):
    """Jobs (.JBI) through check and through solve --robot's reader."""
    if seed is None:
        pytest.skip("no Yaskawa job seed")
    fuzzing.check_bytes(seed.name, fuzzing.mutate(seed.read_bytes(), ops))


UR_SEEDS = [p for p in SEEDS if p.suffix.lower() == ".installation"]


@settings(max_examples=60, **SETTINGS)
@given(seed=st.sampled_from(UR_SEEDS), ops=ops, inside=st.booleans())
def test_mutated_ur_installations(seed, ops, inside):
    """Universal Robots installations: the XML mutated inside a valid gzip
    stream (``inside``), or the gzip bytes themselves (a clear error); a
    safety feature never written."""
    raw = seed.read_bytes()
    mutated = fuzzing.mutate_inside_gzip(raw, ops) if inside else fuzzing.mutate(raw, ops)
    fuzzing.check_bytes(seed.name, mutated)


@settings(max_examples=60, **SETTINGS)
@given(seed=st.sampled_from(STAUBLI_SEEDS or [None]), ops=ops)
def test_mutated_staubli_files(seed, ops):
    """.dtx files of both dialects through check, solve --robot's reader of
    their points, and patch (refused: the rotation order is not proved)."""
    if seed is None:
        pytest.skip("no Stäubli seed")
    fuzzing.check_bytes(seed.name, fuzzing.mutate(seed.read_bytes(), ops))


# ------------------------------------------------------------------ generated modules

# Trivia where RAPID allows it: nothing, blanks, line breaks of every kind,
# comments (which end a line).
GAP = st.sampled_from(["", " ", "\t", "\n", "\r\n", "  ! note\n", "!x\r\n\t", "\n\n  ", " !\n"])
SEP = st.sampled_from([" ", "\t", "\n", " ! note\n", "\r\n  ", " !c\n "])       # between words


@st.composite
def rapid_number(draw):
    digits = draw(st.sampled_from(["0", "1", "705", "1200.5", "0.258819", ".5", "5.", "9E9",
                                   "9E+09", "1.4013E-45", "0.683012702", "2.5e-3"]))
    sign = draw(st.sampled_from(["", "", "-", "+"]))
    return sign + (draw(GAP) if sign else "") + digits


@st.composite
def aggregate(draw, items):
    parts = [draw(GAP) + item + draw(GAP) for item in items]
    return "[" + ",".join(parts) + "]"


@st.composite
def rapid_pose(draw):
    t = draw(aggregate([draw(rapid_number()) for _ in range(3)]))
    q = draw(st.sampled_from([["1", "0", "0", "0"], ["0.965926", "0", "0", "0.258819"],
                              ["0.5", "-0.5", "0.5", "- 0.5"], ["0", "0", "1", "0"]]))
    return draw(aggregate([t, draw(aggregate(q))]))


@st.composite
def rapid_decl(draw, i):
    kind = draw(st.sampled_from(["wobjdata", "tooldata", "pose", "num", "robtarget", "comment",
                                 "routine", "record", "array", "alias", "placeholder", "func"]))
    head = draw(st.sampled_from(["PERS", "TASK" + draw(SEP) + "PERS", "LOCAL" + draw(SEP) + "PERS",
                                 "CONST", "VAR"]))
    if kind == "comment":
        return "! " + draw(st.sampled_from(["plain", "PERS wobjdata x := [", "ENDMODULE", "1.2.3"]))
    if kind == "routine":
        return "PROC r%d()%s  x := 1;%sENDPROC" % (i, draw(GAP) or "\n", draw(GAP) or "\n")
    if kind == "record":
        return "RECORD rec%d%snum a;%sENDRECORD" % (i, draw(SEP), draw(GAP) or "\n")
    if kind == "alias":
        return "ALIAS num len%d;" % i
    if kind == "placeholder":
        return "<DDN>"
    if kind == "func":      # END words inside a string and a comment do not end it
        return ('LOCAL FUNC num f%d()\n  TPWrite "ENDFUNC ENDMODULE";%s  RETURN 1; ! ENDFUNC\n'
                "ENDFUNC" % (i, draw(GAP) or "\n"))
    if kind == "array":
        wobj = draw(aggregate(["FALSE", "TRUE", '""', draw(rapid_pose()), draw(rapid_pose())]))
        return (f"{head}{draw(SEP)}wobjdata{draw(SEP)}wa{i}{{2}}{draw(GAP)}:={draw(GAP)}"
                f"[{wobj},{draw(GAP)}{wobj}]{draw(GAP)};")
    if kind == "wobjdata":
        value = draw(aggregate([draw(st.sampled_from(["FALSE", "TRUE"])), "TRUE", '""',
                                draw(rapid_pose()), draw(rapid_pose())]))
    elif kind == "tooldata":
        load = "[1,[0,0,1],[1,0,0,0],0,0,0]"
        value = draw(aggregate(["TRUE", draw(rapid_pose()), load]))
    elif kind == "pose":
        value = draw(rapid_pose())
    elif kind == "num":
        value = draw(rapid_number())
    else:
        value = "[[1,2,3],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]]"
    assign = draw(GAP) + ":=" + draw(GAP) + value if kind != "num" or draw(st.booleans()) else ""
    return f"{head}{draw(SEP)}{kind}{draw(SEP)}d{i}{assign}{draw(GAP)};"


@st.composite
def rapid_module(draw):
    header = draw(st.sampled_from(["", "%%%\n  VERSION:1\n  LANGUAGE:ENGLISH\n%%%\n"]))
    attrs = draw(st.sampled_from(["", "(SYSMODULE)", " (SYSMODULE, NOSTEPIN)"]))
    n = draw(st.integers(1, 5))
    items = [draw(rapid_decl(i)) for i in range(n)]
    eol = draw(st.sampled_from(["\n", "\r\n", "\r\r\n"]))
    body = "".join(draw(GAP) + item + eol for item in items)
    return (header + draw(GAP) + "MODULE" + draw(SEP) + "Gen" + attrs + draw(GAP) + eol + body
            + draw(GAP) + "ENDMODULE" + draw(st.sampled_from(["", eol, " ! end" + eol])))


@settings(max_examples=120, **SETTINGS)
@given(text=rapid_module())
def test_generated_rapid_modules_fast_path_agrees_with_check(text):
    """Legal RAPID with trivia everywhere the language allows it (a comment
    right after MODULE name, line breaks between a sign and its digits, ...):
    check and the fast path accept it alike and give the same frames; every
    patch stays inside the numbers."""
    assert fuzzing.check_bytes("gen.mod", text.encode()) == "accepted", text


KRL_WS = st.sampled_from(["", " ", "  ", "\t"])


@st.composite
def krl_number(draw):
    return draw(st.sampled_from(["0.0", "1.00000", "-61.6146", "5", "-.5", ".25", "1.5E+02",
                                 "-1.38059322E-5", "180.000", "-180.0", "+2.0"]))


@st.composite
def krl_frame(draw):
    comps = ["X", "Y", "Z", "A", "B", "C"]
    fields = []
    for c in comps:
        num = draw(krl_number())
        glue = draw(st.sampled_from([" ", "  ", "\t"])) if num[0].isdigit() else draw(KRL_WS)
        fields.append(c + glue + num)
    return "{" + draw(KRL_WS) + ("," + draw(KRL_WS)).join(fields) + draw(KRL_WS) + "}"


@st.composite
def krl_list(draw):
    eol = draw(st.sampled_from(["\n", "\r\n"]))
    lines = [draw(st.sampled_from(["", "&ACCESS RVP", "&REL 3"])),
             "DEFDAT" + draw(st.sampled_from([" ", "  "])) + "$CONFIG"]
    lines.append(draw(st.sampled_from(["", ";FOLD BASE", "; comment", "INT MAX_BASE=32"])))
    lines.append("DECL FRAME BASE_DATA[32]")
    for i in range(1, draw(st.integers(1, 4)) + 1):
        lines.append(draw(KRL_WS) + f"BASE_DATA[{i}]" + draw(KRL_WS) + "=" + draw(KRL_WS)
                     + draw(krl_frame()) + draw(st.sampled_from(["", " ; note", ";"])))
        lines.append(draw(st.sampled_from(["", f'BASE_NAME[{i},]="fixture {i}"',
                                           f"BASE_TYPE[{i}]=#BASE", ";ENDFOLD"])))
    lines.append(draw(st.sampled_from([
        "", "DECL E6POS XP1={X 1.0,Y 2.0,Z 3.0,A 0.0,B 0.0,C 0.0,S 6,T 27,E1 0.0}",
        "DECL GLOBAL POS MasterPos[2,3]", "GLOBAL STRUC mystr INT a, REAL b",
        ";FOLD BASISTECH EXT;%{PE}%MKUKATPBASIS,%CEXT,%VEXT,%P", "SIGNAL sig $OUT[5]",
        'DECL CHAR name[24]', "ENUM myenum one,two", "DECL LOAD LOAD_DATA[16]",
        "LOAD_DATA[1]={M -1.00000,CM {X 0.0,Y 0.0,Z 0.0,A 0.0,B 0.0,C 0.0},J {X 0.0,Y 0.0,Z 0.0}}",
        "TOOL_DATA[1]={X 0.0,Y 0.0,Z 185.5,A 0.0,B 0.0,C 0.0}", "BASE_TYPE[1]=#TCP",
        'MACHINE_FRAME_DAT[1]={MACH_DEF_INDEX 0,PARENT[] "WORLD"}']))
        + draw(st.sampled_from(["", " ; note"])))
    lines.append(draw(KRL_WS) + "DECL" + draw(st.sampled_from([" ", " GLOBAL "])) + "FRAME"
                 + draw(st.sampled_from([" ", "  "])) + "fUser=" + draw(krl_frame()))
    lines.append("ENDDAT")
    return eol.join(ln for ln in lines if ln or draw(st.booleans())) + draw(st.sampled_from(["", eol]))


@settings(max_examples=60, **SETTINGS)
@given(text=krl_list())
def test_generated_krl_lists_fast_path_agrees_with_check(text):
    assert fuzzing.check_bytes("$config.dat", text.encode()) == "accepted", text


# ------------------------------------------------------------------ findings, replayed

FOUND = sorted((FIXTURES / "fuzz").glob("*")) if (FIXTURES / "fuzz").is_dir() else []


@pytest.mark.parametrize("path", FOUND, ids=[p.name for p in FOUND])
def test_fuzz_findings_stay_fixed(path):
    name = path.name.split("--", 1)[-1]     # saved as NNN--original-name
    fuzzing.check_bytes(name, path.read_bytes(), patches=10)


def test_the_oracle_catches_a_damaging_patch(monkeypatch):
    """The oracle is not vacuous: a patcher that eats the comment between a
    sign and its digits (issue 12 point 0) is a finding."""
    import ucsio.vendors.common.write as patch_mod
    from ucsio.parsing.document import Edit, Span

    def old_behaviour(text, n, new):
        start = n.signs[0].start if n.signs else n.span.start
        return [Edit(Span(start, n.span.end), new)]
    monkeypatch.setattr(patch_mod, "number_edits", old_behaviour)
    with pytest.raises(fuzzing.Finding, match="outside the frame's numbers"):
        fuzzing.check_bytes("s.mod", (FIXTURES / "hostile" / "detached_signs.mod").read_bytes())
