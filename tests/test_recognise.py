"""The recogniser ``check`` puts every byte through (ucsio.recognise): it
accepts exactly the files Lark's parser accepts, with its literal shortcuts
and without them, and ``check`` built on it shows exactly what Lark's tree of
every byte shows (``parse_whole``). tests/fuzzing.py's oracle checks the
second on every mutated and generated file of tests/test_fuzz.py too."""
from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import fuzzing
from conftest import corpus_files
from ucsio import krl, rapid
from ucsio.controller import parse
from ucsio.document import Document
from ucsio.errors import UcsioError
from ucsio.recognise import Recogniser, Rejected, noncapturing

SETTINGS = dict(deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow])


def lark_accepts(module, text: str) -> bool:
    from lark.exceptions import LarkError

    try:
        module._parser().parse(text, start="file")
        return True
    except LarkError:
        return False


def accepts(recogniser, text: str) -> bool:
    try:
        recogniser.check(text)
        return True
    except Rejected:
        return False


def plain(module):
    """The same grammar's recogniser without shortcuts or suspects."""
    return Recogniser(module._parser(), "file")


def agree(module, text: str) -> None:
    want = lark_accepts(module, text)
    assert accepts(plain(module), text) == want, text
    got = accepts(module._recogniser(), text)
    # a suspect token may reject what Lark accepts (check then asks Lark);
    # accepting what Lark rejects is never allowed
    assert got == want or (want and not got and module is krl), text


@pytest.mark.parametrize("path", corpus_files("abb") + corpus_files("kuka"))
def test_corpus_recognised_as_lark_parses_and_check_shows_the_same(path):
    doc = Document.read(path)
    module = rapid if path.parent.name == "abb" else krl
    text = krl._lines(doc) if module is krl else doc.text
    assert lark_accepts(module, text)
    module._recogniser().check(text)
    plain(module).check(text)
    full, err = fuzzing._parse(doc, full=True)
    fuzzing.same_as_whole_tree(doc, full, err)
    assert full is not None


@pytest.mark.parametrize("module, trigger", [(rapid, "LSQB"), (krl, "LBRACE")])
def test_a_literal_stands_where_a_number_may(module, trigger):
    """The shortcut feeds a literal as one NUMBER: every state that can
    begin the literal can take a NUMBER (what follows both is the soups'
    and the fuzzing's to show)."""
    recogniser = module._recogniser()
    assert isinstance(recogniser, Recogniser), "this Lark's internals are not what ucsio reads"
    rows = recogniser.actions
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


def test_a_lark_without_the_internals_sends_every_file_to_lark():
    from ucsio.recognise import LarkOnly, build

    assert isinstance(build(object(), "file"), LarkOnly)
    with pytest.raises(Rejected):
        LarkOnly().check("MODULE m\nENDMODULE\n")


def test_noncapturing_keeps_classes_and_escapes():
    assert noncapturing(r"(\d+(\.\d*)?)[(]\((?i:a)") == r"(?:\d+(?:\.\d*)?)[(]\((?i:a)"
