"""One test per RAPID syntax variant of ../shared/FORMATS.md section 1.7 (and the
corpus README): each snippet is a whole module, parsed by both paths."""
from __future__ import annotations

import pytest

from ucsio.vendors.abb import rapid
from ucsio.parsing.document import Document

W = '[FALSE,TRUE,"",[[1,2,3],[1,0,0,0]],[[0,0,0],[1,0,0,0]]]'

# (id, module body, frame name, expected (x, y, z) of that frame)
VARIANTS = [
    ("task-pers", f"TASK PERS wobjdata w:={W};", "w", (1, 2, 3)),
    ("local-pers", f"LOCAL PERS wobjdata w:={W};", "w", (1, 2, 3)),
    ("pers", f"PERS wobjdata w:={W};", "w", (1, 2, 3)),
    ("const", f"CONST wobjdata w:={W};", "w", (1, 2, 3)),
    ("var", f"VAR wobjdata w:={W};", "w", (1, 2, 3)),
    ("spaced", 'PERS wobjdata w := [ FALSE , TRUE , "" , [ [ 1 , 2 , 3 ] , [ 1 , 0 , 0 , 0 ] ] ,'
               ' [ [0,0,0],[1,0,0,0] ] ] ;', "w", (1, 2, 3)),
    ("multi-line-comments", 'PERS wobjdata w :=\n  [FALSE, TRUE, "",   ! robhold ufprog ufmec\n'
                            '   [[1,2,3],        ! trans\n    [1,0,0,0]],\n   [[0,0,0],[1,0,0,0]]];',
     "w", (1, 2, 3)),
    ("trailing-comment", f"PERS wobjdata w:={W}; ! measured 2024", "w", (1, 2, 3)),
    ("tabs", f"\tPERS\twobjdata\tw\t:=\t{W};", "w", (1, 2, 3)),
    ("exp-9E9", 'PERS pose p:=[[9E9,9E+09,9E+9],[1,0,0,0]];', "p", (9e9, 9e9, 9e9)),
    ("exp-negative", 'PERS pose p:=[[1E-05,-2.5E-3,3e2],[1,0,0,0]];', "p", (1e-5, -2.5e-3, 300)),
    ("15-digit-quaternion", 'PERS pose p:=[[1,2,3],[0.707106781186548,0,0,0.707106781186547]];',
     "p", (1, 2, 3)),
    ("unary-minus-space", 'PERS pose p:=[[- 0.5,-  1,+2],[1,0,0,0]];', "p", (-0.5, -1, 2)),
    ("negative-zero", 'PERS pose p:=[[-0,-0.0,0],[1,0,0,0]];', "p", (0, 0, 0)),
    ("integers", 'PERS pose p:=[[1,2,3],[0,0,1,0]];', "p", (1, 2, 3)),
    ("leading-dot-trailing-dot", 'PERS pose p:=[[.5,5.,1.],[1,0,0,0]];', "p", (0.5, 5, 1)),
    ("lower-case-keywords", 'task pers WobjData w:=[false,true,"",[[1,2,3],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];',
     "W", (1, 2, 3)),
    ("array-1d-tooldata", 'PERS tooldata t{2}:=[[TRUE,[[1,2,3],[1,0,0,0]],[1,[0,0,0],[1,0,0,0],0,0,0]],'
                          '[TRUE,[[4,5,6],[1,0,0,0]],[1,[0,0,0],[1,0,0,0],0,0,0]]];', "t{2}", (4, 5, 6)),
    ("array-2d-wobj", f"PERS wobjdata w{{1,1}}:=[[{W}]];", "w{1,1}", (1, 2, 3)),
    ("array-named-dim", f"CONST num n:=1;\n  PERS wobjdata w{{n}}:=[{W}];", "w{1}", (1, 2, 3)),
    ("string-with-quote-and-bang", f'PERS string s:="a""!b";\n  PERS wobjdata w:={W};', "w", (1, 2, 3)),
    ("commented-out-twin", f"!PERS wobjdata w:=[FALSE,TRUE,\"\",[[9,9,9],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n"
                           f"  PERS wobjdata w:={W};", "w", (1, 2, 3)),
    ("record-and-alias", f"RECORD r\n    num a;\n  ENDRECORD\n  ALIAS num count;\n  PERS wobjdata w:={W};",
     "w", (1, 2, 3)),
    ("routine-with-keywords-in-strings", f'PROC p()\n    TPWrite "ENDPROC";\n    ! ENDPROC\n  ENDPROC\n'
                                        f"  PERS wobjdata w:={W};", "w", (1, 2, 3)),
    ("comment-after-pers", f"PERS ! shared with the cell module\n  wobjdata w:={W};", "w", (1, 2, 3)),
    ("comment-lines-between-keywords", f"TASK ! c\n  ! whole line\n  PERS\n  ! c\n  wobjdata w:={W};",
     "w", (1, 2, 3)),
    ("comment-after-local-before-proc", f"LOCAL ! c\n  PROC p()\n  ENDPROC\n  PERS wobjdata w:={W};",
     "w", (1, 2, 3)),
    ("placeholder-in-routine", f"PROC p()\n    MoveL <EXP>, v100, z10, tool0;\n  ENDPROC\n"
                               f"  PERS wobjdata w:={W};", "w", (1, 2, 3)),
]


@pytest.mark.parametrize("body,name,xyz", [pytest.param(b, n, x, id=i) for i, b, n, x in VARIANTS])
@pytest.mark.parametrize("full", [False, True], ids=["fast", "full"])
def test_variant(body, name, xyz, full):
    text = f"MODULE m\n  {body}\nENDMODULE\n"
    doc = Document(text.encode("latin-1"), "v.mod")
    cf = rapid.parse(doc, full=full)
    f = cf.frame(name)
    assert f.pose.t == pytest.approx(xyz)
    assert doc.to_bytes() == text.encode("latin-1")


@pytest.mark.parametrize("header", ["%%%\n  VERSION:1\n  LANGUAGE:ENGLISH\n%%%\n",
                                    "%%%\r\n  VERSION: 1\r\n%%%\r\n", "\n", ""])
@pytest.mark.parametrize("module_line", ["MODULE m", "MODULE m(SYSMODULE)", "MODULE m (SYSMODULE, NOSTEPIN)",
                                         "MODULE ! name below\nm"])
def test_headers_and_module_attributes(header, module_line):
    text = f"{header}{module_line}\n  PERS pose p:=[[1,2,3],[1,0,0,0]];\nENDMODULE"
    for full in (False, True):
        cf = rapid.parse(Document(text.encode(), "h.mod"), full=full)
        assert cf.frame("p").pose.t == (1, 2, 3)


def test_pers_without_value():
    cf = rapid.parse(Document(b"MODULE m\n  PERS speeddata s;\n  PERS tooldata t;\nENDMODULE\n"))
    assert cf.frame("t").pose is None
    assert [(l.code, l.severity) for l in cf.lints] == [("no-value", "info")]
