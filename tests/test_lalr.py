"""ucsio.parsing.lalr, the grammars' run-time parser: it reads Lark's tables and must
do what Lark does. Its trees are Lark's trees, token for token; it accepts
and rejects what Lark accepts and rejects, recognising (``check``) with its
literal shortcuts and without them; ``check`` built on it shows exactly
what the tree of every byte shows (``parse_whole``). tests/fuzzing.py's
oracle checks the last on every mutated and generated file of
tests/test_fuzz.py, and the tree against Lark's."""
from __future__ import annotations

import json
import marshal
import os
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import fuzzing
from fuzzing import lark_tree, same_tree
from conftest import FIXTURES, corpus_files
from ucsio.parsing import cache, grammar, lalr
from ucsio.vendors.kuka import krl
from ucsio.vendors.abb import rapid
from ucsio.parsing.controller import parse
from ucsio.parsing.document import Document
from ucsio.vendors import GRAMMARS
from ucsio.errors import UcsioError
from ucsio.parsing.lalr import Rejected, noncapturing

SETTINGS = dict(deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow])


def ours(module, text: str, start: str = "file"):
    try:
        return module._parser().parse(text, start)
    except Rejected:
        return None


def recognised(module, text: str, **kw) -> bool:
    try:
        module._parser().recognise(text, "file", **kw)
        return True
    except Rejected:
        return False


def shortcut_recognised(module, text: str) -> bool:
    try:
        module._recognise(text)
        return True
    except Rejected:
        return False


def agree(module, text: str) -> None:
    """Lark's verdict and tree, ours: by parse, by recognise, with shortcuts."""
    want = lark_tree(module, text)
    got = ours(module, text)
    assert (got is None) == (want is None), text
    if want is not None:
        assert same_tree(got, want), text
    assert recognised(module, text) == (want is not None), text
    # a suspect token may reject what Lark accepts (check then reads the
    # whole tree); accepting what Lark rejects is never allowed
    short = shortcut_recognised(module, text)
    assert short == (want is not None) or (want is not None and module is krl), text


@pytest.mark.parametrize("path", corpus_files("abb") + corpus_files("kuka"))
def test_corpus_trees_are_lark_s_and_check_shows_the_same(path):
    doc = Document.read(path)
    module = rapid if path.parent.name == "abb" else krl
    text = krl._lines(doc) if module is krl else doc.text
    assert same_tree(ours(module, text), lark_tree(module, text))
    module._recognise(text)
    full, err = fuzzing._parse(doc, full=True)
    fuzzing.same_as_whole_tree(doc, full, err)
    assert full is not None


@pytest.mark.parametrize("module, trigger", [(rapid, "LSQB"), (krl, "LBRACE")])
def test_a_literal_stands_where_a_number_may(module, trigger):
    """The shortcut feeds a literal as one NUMBER: every state that can
    begin the literal can take a NUMBER (what follows both is the soups'
    and the fuzzing's to show)."""
    rows = dict(enumerate(module._parser().actions))
    starts = [state for state, row in rows.items() if trigger in row]
    assert starts
    assert all("NUMBER" in rows[state] for state in starts)


RAPID_LITERALS = [
    "[1,2,3]", "[ 1 , - 2 ,+3]", "[- ! sign\n 5]", "[]", "[[1,2,3],[1,0,0,0]]", "[1.5.x]",
    "[0x1F, 0o17, 0b101, 0d12]", "[0x, 1]", "[0xG]", "[1e]", "[1e5,2E-3,.5,5.]", "[1 2]",
    "[TRUE,FALSE,\"\"]", "[TRUEX]", "[TRUE.x]", '["a""b"]', '["a"b"]', "[\"x]", "[1,]",
    "[,1]", "[1,2", "[1]]", "[[[[[1]]]]]", "[[[[[[1,2]]]]]]", "[1]{1}", "[1].x", "[- - 1]",
    "[1 ! c\n,2]", "[1 !c]", "[9E9,9E+09,1.4013E-45]", "[1-2]", "[a, 1]", "[<EXP>]",
    "[1,[2,[3,[4,[5]]]]]", "[12ab]", "[1\t,\r\n2]", "[NOT TRUE]",
]


@pytest.mark.parametrize("literal", RAPID_LITERALS)
def test_rapid_literals_accepted_as_lark_does(literal):
    agree(rapid, f"MODULE m\n  PERS num a := {literal};\nENDMODULE\n")


KRL_LITERALS = [
    "{X 1,Y 2,Z 3,A 0,B 0,C 0}", "{X1.0}", "{X 1 ;c\n}", "{E6POS: X 1}", "{X -}", "{X 1,}",
    "{}", "{ }", "{X {Y {Z {W 1}}}}", "{X {Y 1},Z #BASE}", "{X # BASE}", "{X TRUE}",
    "{POINT2[] \" \",TQ_STATE FALSE}", "{X 'c'}", "{X \"s}", "{X 1 Y 2}", "{X 1,,Y 2}",
    "{X 1e,Y 2}", "{X 1.5E+02,Y -.5,Z +2.0}", "{X $abc}", "{X [] 1}", "{X [ ] 1}", "{X[]1}",
    "{X 1}}", "{{X 1}}", "{X 1", "{X 1.2.3}", "{X\t1,\tY\t2}", "{X 12ab}", "{:X 1}",
    "{A: B: X 1}", "{X 1} ;c",
]


@pytest.mark.parametrize("literal", KRL_LITERALS)
def test_krl_literals_accepted_as_lark_does(literal):
    agree(krl, f"DEFDAT d\nDECL E6POS p={literal}\nENDDAT\n")


# random soups of the pieces literals are made of, where a value stands
RAPID_PIECES = ["[", "]", ",", "-", "+", "1", "1.5", "0x1F", "0x", ".5", "5.", "1e5", "1e",
                "TRUE", "FALSE", "TRUEX", '"a""b"', '"', "!c\n", " ", "\n", "x", ".", "{1}",
                "<EXP>", "(", ")", "*", "NOT "]
KRL_PIECES = ["{", "}", ",", "X", " ", "1", "-1", "+.5", "1e", ":", "E6POS:", "[]", "[", "]",
              '"s"', "'c'", "#BASE", "# B", ";c", "TRUE", "$x", "\t", "\n", "1.2.3", "."]


@settings(max_examples=400, **SETTINGS)
@given(st.lists(st.sampled_from(RAPID_PIECES), min_size=1, max_size=14))
def test_rapid_soups(pieces):
    agree(rapid, "MODULE m\n  PERS num a := [" + "".join(pieces) + ";\nENDMODULE\n")
    agree(rapid, "MODULE m\n  PERS num a := " + "".join(pieces) + ";\nENDMODULE\n")


@settings(max_examples=400, **SETTINGS)
@given(st.lists(st.sampled_from(KRL_PIECES), min_size=1, max_size=14))
def test_krl_soups(pieces):
    agree(krl, "DEFDAT d\nDECL E6POS p={" + "".join(pieces) + "\nENDDAT\n")
    agree(krl, "DEFDAT d\nX=" + "".join(pieces) + "\nENDDAT\n")


def test_check_reports_lark_s_message_where_the_recogniser_rejects():
    doc = Document(b"MODULE m\n  PERS num a := [1, 2 x];\nENDMODULE\n", "m.mod")
    with pytest.raises(UcsioError) as got:
        parse(doc, full=True)
    with pytest.raises(UcsioError) as want:
        rapid.parse_whole(Document(doc.raw, "m.mod"))
    assert str(got.value) == str(want.value)
    assert (got.value.line, got.value.col) == (2, 23)


@pytest.mark.parametrize("line, message", [
    ("DECL INT a[12345678901]", "out of range for a KRL INT"),
    ("END x", "not allowed in a data list"),
    ("X[99999999999]={X 1}", "out of range for a KRL INT"),
])
def test_krl_tokens_only_the_whole_tree_refuses_still_refused(line, message):
    raw = f"DEFDAT d\n{line}\nENDDAT\n".encode()
    with pytest.raises(UcsioError, match=message):
        parse(Document(raw, "d.dat"), full=True)


def test_other_declarations_listed_with_their_values_on_demand():
    """check lists every declaration (duplicates, long names); a robtarget's
    value is parsed when read, with positions in the real file."""
    text = ("MODULE m\n  PERS robtarget p1 := [[1,2,3],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n"
            "  ! note\n  LOCAL VAR num p1 := 2;\n  PERS wobjdata w := [FALSE,TRUE,\"\",[[0,0,0],[1,0,0,0]],"
            "[[0,0,0],[1,0,0,0]]];\nENDMODULE\n")
    doc = Document(text.encode(), "m.mod")
    cf = parse(doc, full=True)
    decls = cf.extra["declarations"]
    assert [(d.scope, d.storage, d.type, d.name, d.module) for d in decls] == [
        (None, "PERS", "robtarget", "p1", "m"), ("LOCAL", "VAR", "num", "p1", "m"),
        (None, "PERS", "wobjdata", "w", "m")]
    assert [l.code for l in cf.lints] == ["duplicate"]
    x = decls[0].value[0][0]
    assert doc.slice(x.span) == "1" and x.span.start == text.index("[[1,2") + 2
    (target,) = rapid.robtargets(cf)
    assert target.pose.t == pytest.approx((1, 2, 3))


def test_noncapturing_keeps_classes_and_escapes():
    assert noncapturing(r"(\d+(\.\d*)?)[(]\((?i:a)") == r"(?:\d+(?:\.\d*)?)[(]\((?i:a)"


STATEMENTS = [
    "MoveL p10, v100, z10, tool1\\WObj:=wobj1;",
    "IF a > 1 THEN MoveJ Offs(p1, 0, 0, 10), v1000, fine, tool0 \\WObj:=w{2};",
    "FOR i FROM 1 TO 3 DO MoveL *, v100, z1, t\\WObj:=wobjs{i,2};",
    "lbl: MoveC p.a, p.b, v10, z1, t\\WObj:=w;", "x := [1, -2, 3];", "MoveL p10 v100;",
]


@pytest.mark.parametrize("text", STATEMENTS)
def test_statement_trees_are_lark_s(text):
    """The `statements` start symbol (diff --points) has its own tables."""
    ours_ = grammar.parser("rapid", ("statements",))
    theirs = grammar.lark_parser("rapid", ("statements",))
    from lark.exceptions import LarkError

    try:
        want = theirs.parse(text, start="statements")
    except LarkError:
        want = None
    try:
        got = ours_.parse(text, "statements")
    except Rejected:
        got = None
    assert (got is None) == (want is None)
    assert want is None or same_tree(got, want)


def test_a_rejected_text_gets_lark_s_exception():
    text = "DEFDAT d\nDECL E6POS p={X 1\nENDDAT\n"
    with pytest.raises(grammar.SyntaxFailure) as failure:
        grammar.parse("krl", krl.START, text, "file")
    from lark.exceptions import UnexpectedToken

    assert isinstance(failure.value.error, UnexpectedToken)
    assert failure.value.error.token.start_pos == text.index("\nENDDAT")


def test_tables_cached_on_disk_rebuilt_when_damaged_and_optional(tmp_path, monkeypatch):
    import shutil

    bare = tmp_path / "grammars"            # the grammars without shipped tables
    bare.mkdir()
    for g in Path(grammar.grammar_dir()).glob("*.lark"):
        shutil.copy(g, bare / g.name)
    monkeypatch.setattr(grammar, "grammar_dir", lambda: bare)
    monkeypatch.setenv("UCSIO_CACHE_DIR", str(tmp_path / "cache"))
    first = grammar.tables("krl", krl.START)
    (path,) = (tmp_path / "cache").iterdir()
    assert marshal.loads(path.read_bytes()) == first
    path.write_bytes(b"{not marshal")
    assert grammar.tables("krl", krl.START) == first           # rebuilt
    assert marshal.loads(path.read_bytes()) == first            # and rewritten
    blocked = tmp_path / "file"
    blocked.write_text("")
    monkeypatch.setenv("UCSIO_CACHE_DIR", str(blocked / "sub"))   # cannot be created
    assert grammar.tables("krl", krl.START) == first


PROBE = """
import sys, io, contextlib
from ucsio.cli import main
with contextlib.redirect_stdout(io.StringIO()):
    code = main(sys.argv[1:])
print("lark" in sys.modules)
"""


def test_reading_a_file_does_not_import_lark(tmp_path):
    """With the tables cached, frames/diff/patch/check of good files never
    import Lark; the first run of a new grammar builds the cache with it."""
    env = dict(os.environ, UCSIO_CACHE_DIR=str(tmp_path / "cache"))
    sol = tmp_path / "sol.json"
    sol.write_text(json.dumps({"frame": {"x": 101, "y": 200, "z": 300, "a": 0, "b": 0, "c": 0}}))
    mod = FIXTURES / "abb" / "two_modules_crcrlf.prg"
    dat = FIXTURES / "kuka" / "cell_config.dat"
    runs = [["frames", mod], ["frames", mod], ["frames", dat], ["check", mod, dat],
            ["diff", mod, "--frame", "wobjA", "--measured", sol],
            ["patch", dat, "--frame", "BASE_DATA[1]", "--measured", sol]]
    seen = []
    for args in runs:
        out = subprocess.run([sys.executable, "-c", PROBE, *map(str, args)], env=env,
                             capture_output=True, text=True)
        seen.append(out.stdout.strip().splitlines()[-1] if out.stdout.strip() else out.stderr)
    if any(Path(grammar.grammar_dir()).glob("*.tables.marshal")):     # an installed wheel ships them
        assert seen == ["False"] * 6, seen
    else:       # a source checkout: Lark builds each grammar's tables once, then the cache
        assert seen == ["True", "False", "True", "False", "False", "False"], seen


def test_the_wheel_s_tables_are_found_beside_the_grammars(tmp_path, monkeypatch):
    """hatch_build.py ships write_tables' files beside the grammars; tables()
    reads them there, builds nothing and writes no cache."""
    import shutil

    from ucsio.vendors.abb import taught as abb

    assert {(rapid.__name__.rsplit(".")[-1], rapid.START), ("krl", krl.START)} <= set(GRAMMARS)
    assert ("rapid", ("statements",)) in GRAMMARS      # diff --points (taught.abb)
    assert abb._statement_parser() is grammar.parser("rapid", ("statements",))
    shipped = tmp_path / "grammars"
    shipped.mkdir()
    for g in Path(grammar.grammar_dir()).glob("*.lark"):
        shutil.copy(g, shipped / g.name)
    written = grammar.write_tables(shipped, GRAMMARS)
    assert len(written) == len(GRAMMARS)
    monkeypatch.setattr(grammar, "grammar_dir", lambda: shipped)
    monkeypatch.setattr(grammar, "lark_parser", None)          # building would fail
    monkeypatch.setenv("UCSIO_CACHE_DIR", str(tmp_path / "cache"))
    for name, start in GRAMMARS:
        assert grammar.tables(name, start)["format"] == lalr.FORMAT
    assert not (tmp_path / "cache").exists()


def test_cache_dir_is_never_a_tilde_folder_in_the_current_folder(monkeypatch, tmp_path):
    import tempfile

    monkeypatch.delenv("UCSIO_CACHE_DIR", raising=False)
    monkeypatch.delenv("XDG_CACHE_HOME", raising=False)
    monkeypatch.setattr(os.path, "expanduser", lambda p: p)      # no home at all
    where = cache.cache_dir()
    assert os.path.isabs(where) and where.startswith(tempfile.gettempdir())
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    assert cache.cache_dir() == str(tmp_path / "ucsio")


def test_a_lark_tree_converts_to_ours_node_for_node():
    """grammar.from_lark: what parse returns were Lark to accept a text the
    tables reject (never seen; the trees must still be the same kind)."""
    text = "MODULE m\n  PERS wobjdata w := [FALSE, TRUE, \"\", [[1, -2, 3], [1, 0, 0, 0]], " \
           "[[0, 0, 0], [1, 0, 0, 0]]];\n  PROC p()\n  ENDPROC\nENDMODULE\n"
    theirs = lark_tree(rapid, text)
    converted = grammar.from_lark(theirs)
    assert isinstance(converted, lalr.Tree)
    assert same_tree(converted, theirs)
    assert same_tree(ours(rapid, text), theirs)
