"""The lean read of a Universal Robots installation (issue 30's speed line):
reading one deflates nothing (whether this zlib writes the stream back is
found out when a write or ``check`` asks), and the fast paths of the XML
scan (a well-formed tag matched once, a value of 3 or 6 numbers matched
whole) read what the careful path reads and leave its errors to it."""
from __future__ import annotations

import pytest

import ur_cell
from ucsio.cli import main
from ucsio.parsing.document import Document, Gzip
from ucsio.vendors.ur import installation


def write(tmp_path, xml: str):
    path = tmp_path / "cell.installation"
    path.write_bytes(ur_cell.installation(xml))
    return path


def test_reading_deflates_nothing_and_check_still_proves_the_stream(tmp_path, monkeypatch,
                                                                     capsys):
    path = write(tmp_path, ur_cell.XML)
    calls = []
    deflate = Gzip.wrap
    monkeypatch.setattr(Gzip, "wrap", lambda self, body: calls.append(1) or deflate(self, body))
    assert main(["frames", str(path)]) == 0 and "Table" in capsys.readouterr().out
    assert calls == []
    assert main(["check", str(path)]) == 0 and "round trip ok" in capsys.readouterr().out
    assert calls            # check deflates: the stream proved, and the round trip


def every_element(xml: str):
    return installation.scan(Document(ur_cell.installation(xml), "cell.installation"))[1]


def test_the_fast_attributes_are_the_careful_ones():
    xml = ur_cell.XML.replace('name="Gripper"', "name='Grip=per'")    # an "=" in a value
    doc = Document(ur_cell.installation(xml), "cell.installation")
    elements = every_element(xml)
    assert len(elements) > 50
    for element in elements:
        m = installation._MARKUP.match(doc.text, element.start)
        careful = installation._attributes_checked(doc, m.group("attrs"), m.start("attrs"))
        assert element.attrs == careful, element.tag
    assert "Grip=per" in [e.get("name") for e in elements]


@pytest.mark.parametrize("edit, says, where", [
    # a name given twice in a tag that also holds an "=" in a value
    (lambda x: x.replace('name="Gripper"', 'name="a=b" name="x"'), "given twice", 'name="x"'),
    # a value of 6 numbers that matches whole, one of them not finite
    (lambda x: x.replace('offset="0.0, 0.0, 0.15,', 'offset="0.0, 1e999, 0.15,'),
     "'1e999' is not a finite number", "1e999"),
    # an attribute without quotes: not a well-formed tag, the careful path says where
    (lambda x: x.replace('name="Gripper"', "name=Gripper"), 'not name="value"', "name=Gripper"),
])
def test_the_careful_path_still_names_the_fault(tmp_path, capsys, edit, says, where):
    xml = edit(ur_cell.XML)
    path = write(tmp_path, xml)
    assert main(["frames", str(path)]) == 2
    err = capsys.readouterr().err
    at = xml.index(where)
    line = xml.count("\n", 0, at) + 1
    col = at - (xml.rfind("\n", 0, at) + 1) + 1
    assert says in err and f"cell.installation:{line}:{col}: " in err, err


def test_a_name_given_twice_where_a_listing_never_looks_is_checks_error(tmp_path, capsys):
    """Attributes are read when asked for (as the .dtx reader reads them):
    a listing reads the frames' tags; ``check`` reads every tag and names
    the place."""
    where = 'buildNumber="2"'
    xml = ur_cell.XML.replace('buildNumber="108249"', 'buildNumber="108249" ' + where)
    path = write(tmp_path, xml)
    assert main(["frames", str(path)]) == 0 and "Pick" in capsys.readouterr().out
    assert main(["check", str(path)]) == 2
    err = capsys.readouterr().err
    at = xml.index(where)
    line = xml.count("\n", 0, at) + 1
    col = at - (xml.rfind("\n", 0, at) + 1) + 1
    assert "buildNumber given twice" in err and f"cell.installation:{line}:{col}: " in err, err


@pytest.mark.parametrize("edit, where", [
    (lambda x: x.replace("</Features>", "<</Features>"), "<</Features>"),
    (lambda x: x + "<", None),
    (lambda x: x.replace("<Features>", "<Features>< a>"), "< a>"),
    (lambda x: x.replace("<Features>", "<Features><!-- <Features> -->"), None),
])
def test_every_lone_angle_bracket_is_an_error_and_a_comment_hides_nothing(tmp_path, capsys,
                                                                          edit, where):
    """The scan's one pass finds every '<': one that begins no tag is an
    error at its place; a comment's text is never read as tags."""
    xml = edit(ur_cell.XML)
    path = write(tmp_path, xml)
    code = main(["frames", str(path)])
    out, err = capsys.readouterr()
    if "<!--" in xml:
        assert code == 0 and "Pick" in out, err
        return
    assert code == 2 and "a '<' that begins no tag" in err, err
    at = xml.rindex("<") if where is None else xml.index(where)
    line = xml.count("\n", 0, at) + 1
    col = at - (xml.rfind("\n", 0, at) + 1) + 1
    assert f"cell.installation:{line}:{col}: " in err, err


def test_a_point_features_numbers_made_later_are_the_ones_read_at_once():
    """A listing takes a point feature's pose without a Number for each;
    the numbers a patch asks for later are those the careful reader makes,
    and give the same pose."""
    doc = Document(ur_cell.installation(ur_cell.XML), "cell.installation")
    cf = installation.parse(doc)
    pick = next(f for f in cf.frames if f.name == "Pick")
    node = next(e for e in installation.scan(doc)[1]
                if e.tag == "GeomPoseNode" and e.get("name") == "Pick")
    eager = installation.point_numbers(doc, node)
    assert pick.numbers == eager and dict(pick.numbers.items()) == eager
    assert sorted(pick.numbers) == sorted(eager) and len(pick.numbers) == 6
    assert all(doc.slice(n.span) == n.text for n in pick.numbers.values())
    assert installation.pose_of(pick.numbers).as_dict() == pick.pose.as_dict()


def test_the_scan_lists_every_element_in_the_trees_order():
    """The scan's list is the tree below the root, depth first, in document order."""
    def walk(element):
        for child in element.children:
            yield child
            yield from walk(child)
    doc = Document(ur_cell.installation(ur_cell.XML), "cell.installation")
    root, every = installation.scan(doc)
    walked = list(walk(root))
    assert len(walked) > 50 and len(every) == len(walked)
    assert all(a is b for a, b in zip(every, walked))
