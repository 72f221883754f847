from ucsio.parsing.document import BOM, Document, Edit, Span, looks_binary


def test_round_trip_every_encoding_and_line_ending():
    samples = [b"a\r\nb\nc\r\r\nd", BOM + "caf\u00e9\n".encode(), "Z\xfcrich\r\n".encode("latin-1"),
               b"no final newline", b"", b"\r\r\n\r\n\n"]
    for raw in samples:
        doc = Document(raw)
        assert doc.to_bytes() == raw
        assert doc.edited_bytes([]) == raw


def test_encoding_detection():
    assert Document(BOM + b"x").bom and Document(BOM + b"x").encoding == "utf-8"
    assert Document("\u00e9".encode()).encoding == "utf-8"
    latin = Document(b"\xfc\x81\x90")  # bytes cp1252 leaves undefined still round-trip
    assert latin.encoding == "latin-1" and latin.to_bytes() == b"\xfc\x81\x90"


def test_line_col_counts_crcrlf_as_one_line():
    doc = Document(b"ab\r\r\ncd\nef")
    assert doc.line_col(0) == (1, 1)
    assert doc.line_col(doc.text.index("c")) == (2, 1)
    assert doc.line_col(doc.text.index("f")) == (3, 2)


def test_edits_replace_only_their_spans():
    doc = Document("x = 1.0\r\ny = 2.0\r\n".encode("latin-1"))
    a = doc.text.index("1.0")
    b = doc.text.index("2.0")
    out = doc.edited_bytes([Edit(Span(b, b + 3), "-7.25"), Edit(Span(a, a + 3), "3")])
    assert out == b"x = 3\r\ny = -7.25\r\n"


def test_edit_keeps_bom_and_latin1():
    raw = BOM + "! caf\u00e9\nv=1\n".encode()
    doc = Document(raw)
    i = doc.text.index("1")
    assert doc.edited_bytes([Edit(Span(i, i + 1), "2")]) == raw.replace(b"v=1", b"v=2")
    raw = "! Z\xfcrich\nv=1\n".encode("latin-1")
    doc = Document(raw)
    i = doc.text.index("1")
    assert doc.edited_bytes([Edit(Span(i, i + 1), "2")]) == raw.replace(b"v=1", b"v=2")


def test_binary_detection():
    assert looks_binary(bytes([0xFC, 0x30, 0x1D, 0x00]))
    assert not looks_binary(BOM + b"%%%\r\n  VERSION:1\r\n%%%\r\nMODULE x\r\nENDMODULE\r\n")
    assert not looks_binary("MODULE x ! \u00fc\nENDMODULE".encode("latin-1"))


def test_cr_only_files_count_lines_at_cr():
    doc = Document(b"MODULE m\r  PERS pose p:=[[1,2,3],[1,0,0,0]];\rENDMODULE\r")
    assert doc.line_col(doc.text.index("PERS")) == (2, 3)
    assert doc.line_col(doc.text.index("ENDMODULE")) == (3, 1)
