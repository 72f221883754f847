"""Linear time on hostile input (issue 12 point 1, issue 18 point 4).

Every command must stay linear in the input: a file four times longer may
take at most six times longer, never sixteen. Each shape is a file of N
characters and of 4N; this times what `frames`, `check`, `patch`, `solve
--robot` and `diff --points` do with it (the fast path, the full parse and
its round trip, a patch plan, the robot positions, the routines' statements),
or for a measurement file what the readers do, in this process, and prints
the ratio t(4N) / t(N): near 4 (or below: fixed costs) is linear, near 16
quadratic. Shapes:

- hand-picked ones (SHAPES: long runs of blanks inside and around
  declarations, unterminated items, deep brackets, ...);
- the grid: every run in RUNS (a long word, digits, blanks, CRs, every
  punctuation character, ...) after every context in RAPID_CONTEXTS,
  KRL_CONTEXTS and the FANUC ones (VA_CONTEXTS, LS_CONTEXTS, DG_CONTEXTS:
  a record's head, an element, a Group:/Config: line, a coordinate, a
  Field:, a program's /MN line, a frame or register assignment, a /POS
  point, a frame.dg row, a curpos.dg value, ...), open at the end of the
  file and closed; and after each context of the measurement readers
  (READER_CONTEXTS).

A shape refused at once (t(4N) under --min-time) is not judged. One whose
ratio looks too high is timed again, best of --repeat, with a larger N.
Exit status 1 if any ratio exceeds --max-ratio (default 6).

    python benchmarks/bench_linear.py [--size 50000] [--only NAME] [--no-grid]
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

from ucsio.parsing.controller import parse  # noqa: E402
from ucsio.parsing.document import Document  # noqa: E402
from ucsio.errors import UcsioError  # noqa: E402

WOBJ = 'PERS wobjdata w{i}:=[FALSE,TRUE,"",[[1,2,3],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n'


def rapid(body: str, end: str = "ENDMODULE\n") -> tuple[str, str]:
    return "h.mod", "MODULE M\n" + body + end


def krl(body: str, end: str = "ENDDAT\n") -> tuple[str, str]:
    return "h.dat", "DEFDAT H\n" + body + end


FRAME = "DECL FRAME f{i}={{X 1.0,Y 2.0,Z 3.0,A 0.0,B 0.0,C 0.0}}\n"

# Yaskawa: one item per line (CRLF, as a controller writes them)
JOB_POS = ("/JOB\r\n//NAME H\r\n//POS\r\n///NPOS 0,0,0,0,0,0\r\n///TOOL 3\r\n///POSTYPE BASE\r\n"
           "///RECTAN\r\n///RCONF 0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0\r\n")
JOB_INST = "//INST\r\n///DATE 2026/11/30 14:20\r\n///GROUP1 RB1\r\nNOP\r\n"
POSITION = "C{i:05d}=1103.214,881.096,837.253,-176.4201,2.7557,-40.5604\r\n"
UFRAME = ("//UFRAME {i}\r\n///NAME F{i}\r\n///TOOL 3\r\n///GROUP 1,0,0,0,0,0,0,0\r\n"
          "///BASICFRM 1,16,0\r\n///BASEP 0.000,0.000,0.000,0.0000,0.0000,0.0000\r\n///PULSE\r\n"
          "////RORG C000=-37843,-83346,-95223,7024,-29869,-5287,0,0,0\r\n"
          "////BUSER 620.000,-1180.000,455.000,0.0000,0.0000,-90.0000\r\n")
VAR_P = "//VAR\r\n///PFNUM 1\r\n///P\r\n"
P_ROW = '"RECTAN"0,0,4,000000000000000000000000,0,16,620.000,-1180.000,455.000,0.0000,0.0000,-90.0000,0.0000,0.0000\r\n'


def job(positions: str, inst: str = "END\r\n") -> tuple[str, str]:
    return "h.JBI", JOB_POS + positions + JOB_INST + inst


# name -> function of n (a length in characters) giving (file name, text)
SHAPES = {
    # RAPID: blanks and blank lines inside and around declarations
    "rapid spaces in aggregate": lambda n: rapid('PERS wobjdata w:=[FALSE,TRUE,"",[[1,' + " " * n
                                                 + '2,3],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n'),
    "rapid newlines in aggregate": lambda n: rapid('PERS wobjdata w:=[FALSE,TRUE,"",[[1,' + "\n" * n
                                                   + '2,3],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n'),
    "rapid blanks around decl": lambda n: rapid(" " * (n // 2) + WOBJ.format(i=0) + "\n" * (n // 2)),
    "rapid blanks between keywords": lambda n: rapid("PERS" + " \n" * (n // 2) + "wobjdata w:=[FALSE,"
                                                     'TRUE,"",[[1,2,3],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];\n'),
    "rapid spaces before ;": lambda n: rapid("PERS num x:=1" + " " * n + ";\n"),
    "rapid blank lines, no decl": lambda n: rapid("\n" * n),
    "rapid many decls": lambda n: rapid("".join(WOBJ.format(i=i) for i in range(n // 75))),
    "rapid blank lines between decls": lambda n: rapid("".join(WOBJ.format(i=i) + "\n" * 40
                                                               for i in range(n // 115))),
    "rapid long word": lambda n: rapid("a" * n + "\n"),
    "rapid long word at EOF": lambda n: rapid("a" * n, end=""),
    "rapid unterminated decl": lambda n: rapid("PERS num " + "a" * n, end=""),
    # issue 18: a word after a declaration keyword backtracked (12 s at 40,000 characters)
    "rapid CONST long word": lambda n: rapid("CONST " + "a" * n + "\n"),
    "rapid VAR long digits": lambda n: rapid("VAR " + "1" * n + "\n"),
    "rapid unterminated decl, blanks": lambda n: rapid("PERS num x" + " \n" * (n // 2), end=""),
    "rapid unterminated PERS then spaces": lambda n: rapid("PERS" + " " * n, end=""),
    "rapid unterminated string": lambda n: rapid('PERS string s:="' + "a" * n + "\n;\n"),
    "rapid unterminated routine": lambda n: rapid("PROC p()\n" + "  e := 1;\n" * (n // 10), end=""),
    "rapid routine of blanks": lambda n: rapid("PROC p()\n" + " \n" * (n // 2) + "ENDPROC\n"),
    "rapid comment of numbers": lambda n: rapid("! " + "1a " * (n // 3) + "\n"),
    "rapid comment lines of numbers": lambda n: rapid(("! " + "1a " * 20 + "\n") * (n // 63)),
    "rapid digits then letter": lambda n: rapid("PERS num x:=" + "1" * n + "a;\n"),
    "rapid dotted digits": lambda n: rapid("PERS num x:=" + "1." * (n // 2) + ";\n"),
    "rapid many [ unbalanced": lambda n: rapid("PERS num x:=" + "[" * n + ";\n"),
    "rapid many ] unbalanced": lambda n: rapid("PERS num x:=" + "]" * n + ";\n"),
    "rapid unclosed header": lambda n: ("h.mod", "%%%\n" + " " * n + "\nMODULE M\nENDMODULE\n"),
    "rapid percent run": lambda n: ("h.mod", "%" * n + "\nMODULE M\nENDMODULE\n"),
    "rapid MODULE blanks": lambda n: ("h.mod", "MODULE" + " " * n + "M\nENDMODULE\n"),
    "rapid many MODULE": lambda n: ("h.mod", "MODULE M\n" * (n // 9)),
    "rapid many PERS": lambda n: rapid("PERS " * (n // 5), end=""),
    "rapid many !": lambda n: rapid("!" * n + "\n"),
    "rapid many quotes": lambda n: rapid('"' * n + "\n"),
    "rapid many <": lambda n: rapid("PERS num x:=" + "<" * n + ";\n"),
    # KRL
    "krl spaces in struct": lambda n: krl("DECL FRAME f={X 1.0," + " " * n + "Y 2.0,Z 3.0,A 0,B 0,C 0}\n"),
    "krl blank lines": lambda n: krl("\n" * n),
    "krl spaces lines": lambda n: krl(" \n" * (n // 2)),
    "krl many frames": lambda n: krl("".join(FRAME.format(i=i) for i in range(n // 55))),
    "krl long word": lambda n: krl("a" * n + "\n"),
    "krl long word at EOF": lambda n: krl("a" * n, end=""),
    "krl unterminated string": lambda n: krl('DECL CHAR s[5]="' + "a" * n + "\n"),
    "krl many {": lambda n: krl("DECL FRAME f=" + "{" * n + "\n"),
    "krl many }": lambda n: krl("DECL FRAME f=" + "}" * n + "\n"),
    "krl long comment": lambda n: krl(";" + "1a " * (n // 3) + "\n"),
    "krl many & lines": lambda n: ("h.dat", "&ACCESS RV\n" * (n // 11) + "DEFDAT H\nENDDAT\n"),
    "krl many DEFDAT": lambda n: ("h.dat", "DEFDAT H\n" * (n // 9)),
    "krl many ENDDAT": lambda n: ("h.dat", "DEFDAT H\n" + "ENDDAT\n" * (n // 7)),
    "krl digits": lambda n: krl("INT i=" + "1" * n + "\n"),
    "krl digits dots": lambda n: krl("REAL r=" + "1." * (n // 2) + "\n"),
    "krl many =": lambda n: krl("BASE_DATA[1]" + "=" * n + "\n"),
    "krl many [": lambda n: krl("BASE_DATA" + "[" * n + "\n"),
    "krl element blanks": lambda n: krl("BASE_DATA[1]" + " " * n + "={X 1,Y 2,Z 3,A 0,B 0,C 0}\n"),
    "krl no DEFDAT, many lines": lambda n: ("h.dat", "INT i=1\n" * (n // 8)),
    # Yaskawa: many items, and one long line in each file's places
    "yaskawa job many positions": lambda n: job("".join(POSITION.format(i=i % 100000)
                                                         for i in range(n // 62))),
    "yaskawa job tool changes": lambda n: job(("///TOOL 1\r\n" + POSITION.format(i=0)) * (n // 73)),
    "yaskawa job long position": lambda n: job("C00000=" + "1.5," * (n // 4) + "\r\n"),
    "yaskawa job long number": lambda n: job("C00000=" + "1" * n + ",2,3,4,5,6\r\n"),
    "yaskawa job long RCONF": lambda n: job("///RCONF " + "0," * (n // 2) + "0\r\n"),
    "yaskawa job long comment": lambda n: job("", "'" + "a" * n + "\r\nEND\r\n"),
    "yaskawa job blank lines first": lambda n: ("h.JBI", "\r\n" * (n // 2) + "".join(job("")[1])),
    "yaskawa job of positions, no /JOB": lambda n: ("h.JBI", POSITION.format(i=0) * (n // 62)),
    "yaskawa uframe many frames": lambda n: ("UFRAME.CND", "".join(
        UFRAME.format(i=i % 63 + 1) for i in range(n // 330))),
    "yaskawa uframe long name": lambda n: ("UFRAME.CND", UFRAME.format(i=1).replace(
        "///NAME F1", "///NAME " + "F" * n)),
    "yaskawa uframe long BUSER": lambda n: ("UFRAME.CND", UFRAME.format(i=1).replace(
        "620.000,", "1" * n + ".0,")),
    "yaskawa tool long pose": lambda n: ("TOOL.CND", "//TOOL 0\r\n///NAME\r\n"
                                         + "0.5," * (n // 4) + "\r\n"),
    "yaskawa var many P rows": lambda n: ("VAR.DAT", VAR_P + P_ROW * (n // 110)),
    "yaskawa var long row": lambda n: ("VAR.DAT", VAR_P + '"RECTAN"' + "0," * (n // 2) + "\r\n"),
    "yaskawa var many UNUSED": lambda n: ("VAR.DAT", VAR_P + '"UNUSED"\r\n' * (n // 10)),
    "yaskawa rbcalib long SRANG": lambda n: ("RBCALIB.DAT", "//RBCALIB 1\r\n///MGROUP 1,0\r\n"
                                             "////SRANG " + "2.5," * (n // 4) + "\r\n"),
}


# -- the grid: every long run after every context ------------------------------------
# Hand-picked shapes find the traps someone thought of. The grid grows one
# run (a word, digits, blanks, each punctuation character, ...) after each
# context a scanner may be in (every declaration keyword, inside an
# aggregate, a string, a comment, a header, a routine, ...), once left open
# at the end of the file and once closed, in both languages and in the
# measurement readers: a quadratic loop on any of them shows as a ratio
# near 16.
RUNS = {
    "word": lambda n: "a" * n,
    "digits": lambda n: "1" * n,
    "spaces": lambda n: " " * n,
    "tabs": lambda n: "\t" * n,
    "LFs": lambda n: "\n" * n,
    "CRs": lambda n: "\r" * n,
    "CRLFs": lambda n: "\r\n" * (n // 2),
    "blank lines": lambda n: " \n" * (n // 2),
    "number-like words": lambda n: "1a " * (n // 3),
    "dotted digits": lambda n: "1." * (n // 2),
    "exponents": lambda n: "1e" * (n // 2),
    "signed": lambda n: "-1" * (n // 2),
    "words and commas": lambda n: "a," * (n // 2),
    "numbers and commas": lambda n: "1.5," * (n // 4),
    "keyword words": lambda n: "PERS " * (n // 5),
    "e words": lambda n: "e" * n,
    **{f"{c!r} run": (lambda c: lambda n: c * n)(c) for c in "[]{}(),;:=\"'!<>%&$#.-+*/\\_@^|~?`"},
}

RAPID_HEAD = "MODULE M\n"
RAPID_CONTEXTS = {
    "module": "", "PERS": "PERS ", "CONST": "CONST ", "VAR": "VAR ", "LOCAL": "LOCAL ",
    "TASK": "TASK ", "TASK PERS": "TASK PERS ", "PERS type": "PERS num ",
    "PERS name": "PERS num x", "PERS :=": "PERS num x:=", "frame type": "PERS wobjdata ",
    "frame :=": "PERS wobjdata w:=", "aggregate": "PERS wobjdata w:=[FALSE,TRUE,\"\",[[",
    "robtarget": "CONST robtarget p:=[[", "dims": "PERS num a{", "string": "PERS string s:=\"",
    "comment": "! ", "PROC": "PROC ", "PROC body": "PROC p()\n", "FUNC": "FUNC num f()\n",
    "TRAP": "TRAP t\n", "LOCAL PROC": "LOCAL PROC p()\n", "RECORD": "RECORD r\n",
    "ALIAS": "ALIAS ", "placeholder": "PERS num x:=<", "move": "PROC p()\n  MoveL ",
}
KRL_HEAD = "DEFDAT H\n"
KRL_CONTEXTS = {
    "data list": "", "DECL": "DECL ", "GLOBAL": "GLOBAL ", "CONST": "CONST ",
    "DECL type": "DECL FRAME ", "DECL =": "DECL FRAME f=", "struct": "DECL FRAME f={",
    "field": "DECL FRAME f={X ", "element": "BASE_DATA[", "element =": "BASE_DATA[1]=",
    "element struct": "BASE_DATA[1]={X ", "INT MAX": "INT MAX_", "label": 'BASE_NAME[1,]="',
    "comment": "; ", "fold": ";FOLD ", "STRUC": "STRUC ", "ENUM": "ENUM ", "SIGNAL": "SIGNAL ",
    "EXT": "EXT f(", "EXTFCTP": "EXTFCTP INT f(", "CHANNEL": "CHANNEL :", "IMPORT": "IMPORT INT x IS ",
    "E6POS": "DECL E6POS XP1={X ", "FDAT": "DECL FDAT FP1={TOOL_NO ", "char": "CHAR c='",
    "enum value": "DECL IPO_M_T t=#",
}
KRL_OUTSIDE = {"header": "&", "DEFDAT": "DEFDAT ", "before DEFDAT": ""}

# FANUC: variable listings (.va), TP programs (.ls), diagnostics (.dg)
VA_HEAD = "[*SYSTEM*]$MNUFRAME  Storage: SHADOW  Access: RW  : ARRAY[2,32] OF POSITION\n"
VA_ENTRY = VA_HEAD + "    [1,1] = \n  Group: 1   Config: N U T, 0, 0, 0\n"
VA_CONTEXTS = {
    "listing": "", "head": "[*SYSTEM*]$MNUFRAME", "desc": "[*SYSTEM*]$MNUFRAME  Storage: ",
    "array": "[*SYSTEM*]$MNUFRAME  Storage: SHADOW  Access: RW  : ARRAY[",
    "scalar =": "[*SYSTEM*]$X  Storage: CMOS  Access: RW  : INTEGER = ",
    "element": VA_HEAD + "    [1,", "element =": VA_HEAD + "    [1,1] = ",
    "comment": VA_HEAD + "    [1,1] =   '", "inline group": VA_HEAD + "    [1,1] =   'c'   Group: ",
    "group": VA_HEAD + "    [1,1] = \n  Group: ", "config": VA_HEAD + "    [1,1] = \n  Group: 1   Config: ",
    "x line": VA_ENTRY + "  X: ", "w line": VA_ENTRY + "  X: 1.0   Y: 2.0   Z: 3.0\n  W: ",
    "joints": VA_HEAD + "    [1,1] =   'h'   Group: 1\n  J1 = ",
    "field": "[*SYSTEM*]$CELL_GRP  Storage: SHADOW  Access: RW  : ARRAY[2] OF CELL_GRP_T\n     Field: ",
    "field =": "[*SYSTEM*]$S  Storage: CMOS  Access: RW  : S_T = \n   Field: $S.$A Access: RW: INTEGER = ",
    "setup comment": "[TPFDEF]SETUP_DATA  Storage: SHADOW  Access: RW  : ARRAY[8,3,61] OF FRMSET_T\n"
                     "   Field: SETUP_DATA[1,1,1].$COMMENT Access: RW: STRING[29] = '",
}
LS_MN = "/PROG  P\n/ATTR\nOWNER\t\t= MNEDITOR;\n/MN\n"
LS_POINT = LS_MN + "/POS\nP[1]{\n   GP1:\n\tUF : 1, UT : 1,\t"
LS_CONTEXTS = {
    "program": "", "prog": "/PROG  ", "attr": "/PROG  P\n/ATTR\n", "mn": LS_MN,
    "line": LS_MN + "   1:  ", "uframe": LS_MN + "   1:  UFRAME[", "uframe comment": LS_MN + "   1:  UFRAME[1:",
    "uframe =": LS_MN + "   1:  UFRAME[1]=", "uframe pr": LS_MN + "   1:  UFRAME[1]=PR[",
    "uframe register": LS_MN + "   1:  UTOOL[R[", "pr": LS_MN + "   1:  PR[1,", "pr =": LS_MN + "   1:  PR[1,1]=",
    "pr parens": LS_MN + "   1:  PR[1,1]=((", "pr lpos": LS_MN + "   1:  PR[1]=LPOS",
    "continued": LS_MN + "   1:L P[1] 100mm/sec FINE\n    :", "pos": LS_MN + "/POS\n",
    "point": LS_MN + "/POS\nP[1:\"", "point group": LS_MN + "/POS\nP[1]{\n   GP1:\n\tUF : ",
    "config": LS_POINT + "CONFIG : '", "axis": LS_POINT + "CONFIG : 'N U T, 0, 0, 0',\n\tX = ",
}
DG_CONTEXTS = {
    "frame table": "User Frame\n", "row": "User Frame\n   1.0     2.0     3.0     4.0     5.0     6.0 ",
    "curpos": "CURRENT ROBOT POSITION::\nGroup #:  1\n", "joint": "CURRENT ROBOT POSITION::\n"
    "Group #:  1\nCURRENT JOINT POSITION:\nJoint   1:", "value": "CURRENT ROBOT POSITION::\n"
    "Group #:  1\nFrame #:   1  Tool #:   1\nCURRENT USER FRAME POSITION:\nX: ",
    "cfg": "CURRENT ROBOT POSITION::\nGroup #:  1\nCURRENT WORLD POSITION:\nCFG: ",
}
SHAPES.update({
    "va many frames": lambda n: ("s.va", VA_HEAD + (
        "    [1,1] = \n  Group: 1   Config: N D B, 0, 0, 0\n  X:     0.000   Y:     0.000   Z:     "
        "0.000\n  W:     0.000   P:     0.000   R:     0.000\n") * (n // 130)),
    "va many distinct frames": lambda n: ("s.va", VA_HEAD + "".join(
        f"    [1,{i}] = \n  Group: 1   Config: N U T, 0, 0, 0\n  X: {i:9.3f}   Y:     0.000   Z:  "
        "   0.000\n  W:     0.000   P:     0.000   R:     0.000\n" for i in range(n // 130))),
    "va long comment": lambda n: ("s.va", VA_HEAD + "    [1,1] =   '" + "c" * n + "' \n"),
    "va spaces in a line": lambda n: ("s.va", VA_ENTRY + "  X:" + " " * n + "1.0   Y: 2.0   Z: 3.0\n"),
    "ls many lines": lambda n: ("p.ls", LS_MN + "".join(f"{i:4d}:  UFRAME_NUM=1 ;\n"
                                                        for i in range(1, n // 20)) + "/POS\n/END\n"),
    "ls many register sets": lambda n: ("p.ls", LS_MN + "".join(
        f"{i:4d}:  PR[16,{i % 6 + 1}]=(-1100.3)    ;\n" for i in range(1, n // 30))
        + "9999:  UFRAME[1:F]=PR[16] ;\n/POS\n/END\n"),
    "ls many points": lambda n: ("p.ls", LS_MN + "/POS\n" + "".join(
        f"P[{i}]{{\n   GP1:\n\tUF : 1, UT : 1,\t\tCONFIG : 'N U T, 0, 0, 0',\n\tX = 1.0 mm,\t"
        "Y = 2.0 mm,\tZ = 3.0 mm,\n\tW = 0.0 deg,\tP = 0.0 deg,\tR = 0.0 deg\n};\n"
        for i in range(n // 120)) + "/END\n"),
    "ls long frame comment": lambda n: ("p.ls", LS_MN + "   1:  UFRAME[1:" + " " * n + "\n/POS\n/END\n"),
    "dg many rows": lambda n: ("frame.dg", "User Frame\n" + "   0.0     0.0     0.0     0.0     0.0"
                                                           "     0.0 \n" * (n // 50)),
})
FANUC_CLOSE = {".va": "\n[*SYSTEM*]$Z  Storage: CMOS  Access: RW  : INTEGER = 1\n",
               ".ls": "\n   2:  UTOOL_NUM=1 ;\n/POS\n/END\n", ".dg": "\n\nTool Frame\n"}


def _grid() -> dict:
    shapes = {}
    for run, make in RUNS.items():
        for ctx, prefix in RAPID_CONTEXTS.items():
            shapes[f"grid rapid {ctx} + {run}"] = (
                lambda prefix, make: lambda n: ("g.mod", RAPID_HEAD + prefix + make(n)))(prefix, make)
            shapes[f"grid rapid {ctx} + {run}, closed"] = (
                lambda prefix, make: lambda n: ("g.mod", RAPID_HEAD + prefix + make(n)
                                                + "\n;\nENDMODULE\n"))(prefix, make)
        shapes[f"grid rapid header + {run}"] = (
            lambda make: lambda n: ("g.mod", "%%%\n" + make(n) + "\nMODULE M\nENDMODULE\n"))(make)
        shapes[f"grid rapid MODULE + {run}"] = (
            lambda make: lambda n: ("g.mod", "MODULE " + make(n) + "\nENDMODULE\n"))(make)
        for ctx, prefix in KRL_CONTEXTS.items():
            shapes[f"grid krl {ctx} + {run}"] = (
                lambda prefix, make: lambda n: ("g.dat", KRL_HEAD + prefix + make(n)))(prefix, make)
            shapes[f"grid krl {ctx} + {run}, closed"] = (
                lambda prefix, make: lambda n: ("g.dat", KRL_HEAD + prefix + make(n)
                                                + "}\nENDDAT\n"))(prefix, make)
        for ctx, prefix in KRL_OUTSIDE.items():
            shapes[f"grid krl {ctx} + {run}"] = (
                lambda prefix, make: lambda n: ("g.dat", prefix + make(n) + "\nDEFDAT H\nENDDAT\n")
            )(prefix, make)
        for suffix, contexts in ((".va", VA_CONTEXTS), (".ls", LS_CONTEXTS), (".dg", DG_CONTEXTS)):
            for ctx, prefix in contexts.items():
                name = f"grid {suffix[1:]} {ctx} + {run}"
                shapes[name] = (lambda suffix, prefix, make: lambda n: (
                    "g" + suffix, prefix + make(n)))(suffix, prefix, make)
                shapes[name + ", closed"] = (lambda suffix, prefix, make: lambda n: (
                    "g" + suffix, prefix + make(n) + FANUC_CLOSE[suffix]))(suffix, prefix, make)
    return shapes


# The measurement readers: the CSV, tracker exports, plain tables.
CSV_HEAD = "point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c\n"
READER_CONTEXTS = {
    "csv header": "", "csv row": CSV_HEAD, "csv field": CSV_HEAD + "P1,",
    "csv comment": "# ", "csv sep": "sep=", "table": "P1 1.0 2.0 ", "table row": "P1;",
    "sa export": "// SpatialAnalyzer\nCollection,Group,Target,X,Y,Z\n",
    "sa field": "// SA\nA,B,", "quoted": CSV_HEAD + '"',
}
READER_SHAPES = {f"reader {ctx} + {run}": (lambda prefix, make: lambda n: ("m.csv", prefix + make(n)))
                 (prefix, make) for run, make in RUNS.items() for ctx, prefix in READER_CONTEXTS.items()}


def run_readers(name: str, text: str) -> None:
    """What solve does with a measurement file: the merged CSV, and the laser
    side as each tracker export reader takes it."""
    from ucsio.readers.measurement import parse_measurement
    from ucsio.readers import laser

    for read in (parse_measurement, laser.spec_csv, laser.spatial_analyzer, laser.plain_table):
        try:
            read(text, name)
        except (UcsioError, ValueError):
            pass


def run_commands(name: str, text: str) -> None:
    """What frames, check and patch do with the file: the fast path, the
    full parse with its round trip, and a patch plan of the first frame."""
    from ucsio.commands.check import round_trip
    from ucsio.geometry.frames import Pose
    from ucsio.review.patch import patch_frame

    if name.endswith(".csv"):
        run_readers(name, text)
        return
    from ucsio.vendors.kuka import krl
    from ucsio.vendors.abb import rapid
    from ucsio.vendors.abb.taught import _read_module

    raw = text.encode("utf-8")
    for full in (False, True):
        try:
            cf = parse(Document(raw, name), full=full)
        except UcsioError:
            continue
        if full:
            round_trip(cf)
            if cf.vendor == "abb":       # solve --robot MODULE, diff --points
                rapid.robtargets(cf)
                _read_module(cf.document)
        elif cf.frames and cf.frames[0].pose is not None:
            try:
                patch_frame(cf, cf.frames[0].name, Pose.from_abc(5, 6, 7, 0, 0, 0),
                            measured=False, check_siblings=False)
            except UcsioError:
                pass
    if name.endswith(".dat"):       # solve --robot PROGRAM.dat, diff --points
        for full in (False, True):
            try:
                krl.positions(Document(raw, name), full=full)
            except UcsioError:
                pass
    # FANUC: what the readers beside the frames read (comments beside a
    # sysframe.va, position registers, a program's points, curpos.dg)
    from ucsio.vendors.fanuc import dg
    from ucsio.vendors.fanuc import tp
    from ucsio.vendors.fanuc import va
    readers = {".va": (va.frame_comments, va.position_registers), ".ls": (tp.positions,),
               ".dg": (dg.frame_labels, dg.current_positions)}
    for read in readers.get(name[name.rfind("."):], ()):
        try:
            read(Document(raw, name))
        except UcsioError:
            pass


def timed(name: str, text: str, repeat: int) -> float:
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        run_commands(name, text)
        best = min(best, time.perf_counter() - t0)
    return best


def judge(make, args) -> tuple[int, float, float]:
    """(N, t(N), t(4N)) for one shape. A first look with one run each at
    --size and 4x; a shape whose ratio looks too high is timed again, best
    of --repeat, with N doubled while t(N) is too short to time (a few ms are
    all noise) and 4N stays within a megabyte (beyond, the processor's caches
    make any pass look superlinear): only a ratio that holds up is reported."""
    n = args.size
    t1, t4 = timed(*make(n), 1), timed(*make(4 * n), 1)
    if t4 < args.min_time or t4 / t1 <= args.max_ratio:
        return n, t1, t4
    t1 = timed(*make(n), args.repeat)
    while t1 < args.confirm_time and 8 * n <= MAX_CHARS:
        n *= 2
        t1 = timed(*make(n), args.repeat)
    return n, t1, timed(*make(4 * n), args.repeat)


MAX_CHARS = 1_000_000


def warm_up() -> None:
    """Grammars loaded and compiled once, outside the timings: a good file of
    each language and a rejected one (its message comes from Lark, imported
    the first time), and the readers."""
    run_commands(*rapid(WOBJ.format(i=0)))
    run_commands(*krl(FRAME.format(i=0)))
    run_commands(*rapid("PERS num x:=[;\n"))
    run_commands(*krl("DECL FRAME f={X\n"))
    run_commands("w.va", VA_ENTRY + "  X: 1.0   Y: 2.0   Z: 3.0\n  W: 0.0   P: 0.0   R: 0.0\n")
    run_commands("w.va", VA_ENTRY + "  X: oops\n")
    run_commands("w.ls", LS_MN + "   1:  UFRAME[1]=PR[1] ;\n/POS\n/END\n")
    run_commands("w.ls", LS_MN + "   1:  UFRAME[1]=PR[1] ;\n/POS\nP[\n")
    run_commands("frame.dg", "User Frame\n   1.0     2.0     3.0     4.0     5.0     6.0 A\n")
    run_commands("m.csv", CSV_HEAD + "P1,1,2,3,4,5,6,0,0,0\n")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=int, default=50000, help="N in characters (default 50000)")
    ap.add_argument("--min-time", type=float, default=0.01,
                    help="t(4N) below this (seconds, default 0.01): refused at once, not judged")
    ap.add_argument("--confirm-time", type=float, default=0.05,
                    help="a ratio over --max-ratio is timed again with t(N) at least this long")
    ap.add_argument("--repeat", type=int, default=3, help="best of R runs when confirming")
    ap.add_argument("--max-ratio", type=float, default=6.0,
                    help="t(4N) / t(N) above this fails (default 6: issue 18's bound)")
    ap.add_argument("--only", help="shapes whose name contains this (several: A|B|C)")
    ap.add_argument("--no-grid", action="store_true",
                    help="only the hand-picked shapes, not the grid of runs after contexts")
    ap.add_argument("--verbose-refused", action="store_true",
                    help="also list the shapes refused at once")
    args = ap.parse_args(argv)
    shapes = dict(SHAPES) if args.no_grid else {**SHAPES, **_grid(), **READER_SHAPES}
    warm_up()
    worst, judged, refused, failed = 0.0, 0, 0, []
    print(f"{'shape':60} {'N':>8} {'t(N) ms':>9} {'t(4N) ms':>9} {'ratio':>6}")
    wanted = args.only.split("|") if args.only else None
    for shape, make in shapes.items():
        if wanted and not any(w in shape for w in wanted):
            continue
        n, t1, t4 = judge(make, args)
        ratio = t4 / t1
        if t4 < args.min_time:      # refused at once however long: nothing to judge
            refused += 1
            if not args.verbose_refused:
                continue
            flag = "  (refused at once)"
        else:
            judged += 1
            worst = max(worst, ratio)
            flag = ""
            if ratio > args.max_ratio:
                flag = "  <-- not linear"
                failed.append(shape)
        print(f"{shape:60} {n:>8} {t1 * 1e3:9.1f} {t4 * 1e3:9.1f} {ratio:6.1f}{flag}", flush=True)
    print(f"{judged} shapes timed, {refused} refused at once; worst ratio {worst:.1f} "
          f"(linear: about 4; quadratic: 16; allowed: {args.max_ratio:g})")
    for shape in failed:
        print(f"not linear: {shape}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
