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


def test_masked_keeps_spans_and_newlines_only():
    """masked() (one translate for ASCII text, line by line otherwise) against
    the plain rule: inside a span the text, elsewhere a space, LF kept."""
    import random

    from ucsio.parsing.document import masked

    rng = random.Random(7)
    for alphabet in ("ab \t\r\n;{}", "ab \n\u00e9\u20ac\r"):     # ASCII, then not
        for _ in range(300):
            text = "".join(rng.choice(alphabet) for _ in range(rng.randrange(0, 40)))
            cuts = sorted(rng.randrange(0, len(text) + 1) for _ in range(2 * rng.randrange(0, 4)))
            spans = list(zip(cuts[::2], cuts[1::2]))
            if spans and rng.random() < 0.3:
                spans.insert(1, spans[0])                  # a line matched twice
            keep = {i for s, e in spans for i in range(s, e)}
            want = "".join(c if i in keep or c == "\n" else " " for i, c in enumerate(text))
            assert masked(text, spans) == want, (text, spans)
