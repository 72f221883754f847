"""The bytes of a controller file, and edits that make new bytes.

A Document owns the file's text; everything parsed from it (frames, values)
points into it by character offsets. Serialising an unedited document gives the
original bytes back exactly; an edit replaces exactly the spans it names and
nothing else (the tomlkit / LibCST model: the document owns the bytes, semantic
objects only point into them).

Encoding: a UTF-8 BOM or valid UTF-8 is read as UTF-8; anything else as
Latin-1. Latin-1 maps every byte to one character and back, so Windows-1252
files (KUKA umlauts, Spanish comments) round-trip byte for byte even where
cp1252 leaves a byte undefined. A gzip file (Universal Robots'
``.installation``) is read through its stream: the text is what it holds,
and writing deflates it again (``Gzip``: bit for bit where this Python's
zlib reproduces the stream, else refused). Line endings are never translated: the text
keeps CR, LF, CRLF and ABB's CR CR LF exactly as they were; lines are counted
by one rule for every language (``line_starts``).
"""
from __future__ import annotations

import bisect
import os

from ..errors import UcsioError
from ..files import read_bytes
from ..values import Value
from . import regex

BOM = b"\xef\xbb\xbf"


class Span(Value):
    """A half-open character range [start, end) in a document's text."""

    __slots__ = ("start", "end")

    def __init__(self, start: int, end: int):
        self.start = start
        self.end = end


class Edit(Value):
    """Replace the text of ``span`` with ``text``."""

    __slots__ = ("span", "text")

    def __init__(self, span: Span, text: str):
        self.span = span
        self.text = text


class Document:
    """Decoded text of one file plus what is needed to write it back."""

    def __init__(self, raw: bytes, path: str | os.PathLike | None = None):
        self.path = str(path) if path is not None else "<memory>"
        self.raw = raw
        # a gzip stream's text is what it holds (``Gzip``); a broken one is
        # read as the bytes it is, and parse says why (``gzip_error``)
        self.gzip: Gzip | None = None
        self.gzip_error: str | None = None
        if raw.startswith(GZIP_MAGIC):
            try:
                self.gzip, raw = Gzip.open(raw)
            except ValueError as exc:
                self.gzip_error = str(exc)
        self.body = raw             # the bytes the text decodes: the file's, or its stream's
        self.bom = raw.startswith(BOM)
        body = raw[len(BOM):] if self.bom else raw
        try:
            self.text = body.decode("utf-8")
            self.encoding = "utf-8"
        except UnicodeDecodeError:
            self.text = body.decode("latin-1")
            self.encoding = "latin-1"
        self._line_starts: list[int] | None = None

    # -- reading ---------------------------------------------------------
    @classmethod
    def read(cls, path: str | os.PathLike) -> "Document":
        return cls(read_bytes(path, "controller file"), path)

    # -- positions -------------------------------------------------------
    @property
    def line_starts(self) -> list[int]:
        """Offsets where lines start, by ``line_starts`` (one rule for every
        language: LF, CRLF and ABB's CR CR LF end a line, and so does a bare CR)."""
        if self._line_starts is None:
            self._line_starts = line_starts(self.text)
        return self._line_starts

    def line_col(self, offset: int) -> tuple[int, int]:
        """1-based line and column of a character offset."""
        starts = self.line_starts
        i = bisect.bisect_right(starts, offset) - 1
        return i + 1, offset - starts[i] + 1

    def line_of(self, offset: int) -> int:
        return self.line_col(offset)[0]

    def error(self, message: str, offset: int | None = None) -> UcsioError:
        if offset is None:
            return UcsioError(message, file=self.path)
        line, col = self.line_col(offset)
        return UcsioError(message, file=self.path, line=line, col=col)

    def integer(self, text: str, offset: int, what: str = "integer") -> int:
        """``text``, an index, group or frame number the file writes at
        ``offset``, as an int; beyond 32 bits (no controller's index is) an
        error naming the line (``small_int``)."""
        value = small_int(text)
        if value is None:
            raise self.error(f"{what} {shown_digits(text)} is out of range (32 bits)", offset)
        return value

    def readable(self, s: str) -> str:
        """Text from this file as a person reads it. A non-UTF-8 file is held
        as Latin-1 (so every byte round-trips); its strings were written in
        Windows-1252 ("Stra\xdfe \x80" is "Straße €"), so show them so."""
        if self.encoding != "latin-1":
            return s
        return s.encode("latin-1").decode("cp1252", errors="replace")

    def slice(self, span: Span) -> str:
        return self.text[span.start:span.end]

    # -- writing ---------------------------------------------------------
    def encode(self, text: str) -> bytes:
        """Encode text the way this file is encoded (same codec, same BOM)."""
        try:
            body = text.encode(self.encoding)
        except UnicodeEncodeError as exc:
            raise UcsioError(f"cannot write {text[exc.start:exc.end]!r} in {self.encoding}",
                             file=self.path) from None
        body = BOM + body if self.bom else body
        if self.gzip is not None:
            if self.gzip.refusal is not None:
                raise UcsioError(self.gzip.refusal, file=self.path)
            return self.gzip.wrap(body)
        return body

    @property
    def write_refusal(self) -> str | None:
        """Why this file is read but never written (a gzip stream this
        Python's zlib does not reproduce), or None."""
        return self.gzip.refusal if self.gzip is not None else None

    def to_bytes(self) -> bytes:
        """The bytes of the unedited text: the file's own (a gzip stream this
        Python cannot reproduce: the file's, though no edit is written)."""
        if self.gzip is not None and self.gzip.refusal is not None:
            return self.raw
        return self.encode(self.text)

    def apply(self, edits: list[Edit]) -> str:
        """The text with every edit applied; edits must not overlap."""
        out: list[str] = []
        pos = 0
        for e in sorted(edits, key=lambda e: e.span.start):
            if e.span.start < pos:
                raise ValueError("overlapping edits")
            out.append(self.text[pos:e.span.start])
            out.append(e.text)
            pos = e.span.end
        out.append(self.text[pos:])
        return "".join(out)

    def edited_bytes(self, edits: list[Edit]) -> bytes:
        return self.encode(self.apply(edits))


GZIP_MAGIC = b"\x1f\x8b\x08"      # gzip's two bytes and its one method, deflate


#: the most a gzip stream may unpack to (bytes)
GZIP_MAX = 64 << 20


class Gzip:
    """A gzip file's framing: its header kept as it is, its stream deflated
    again at zlib's level 6 (memLevel 8, the default strategy), with the
    trailer's CRC-32 and length. ``refusal``: why this file cannot be
    written, where deflating its own text does not give its own bytes (an
    other deflater, another zlib, a second member or bytes after the
    stream): it is read, never written. Found out when first asked (a write,
    ``check``): deflating the whole text again is most of what reading an
    installation would otherwise cost, and a command that only reads it
    never needs it."""

    __slots__ = ("header", "_raw", "_body", "_refusal", "_known")

    def __init__(self, header: bytes, raw: bytes = b"", body: bytes = b""):
        self.header, self._raw, self._body = header, raw, body
        self._refusal: str | None = None
        self._known = not raw

    @property
    def refusal(self) -> str | None:
        if not self._known:
            import zlib
            if self.wrap(self._body) != self._raw:
                self._refusal = (f"this gzip stream is not what zlib {zlib.ZLIB_RUNTIME_VERSION} "
                                 "writes at level 6 (another deflater, or bytes after the "
                                 "stream): ucsio reads it but does not write it, nothing "
                                 "written")
            self._known, self._raw, self._body = True, b"", b""
        return self._refusal

    @classmethod
    def open(cls, raw: bytes) -> tuple["Gzip", bytes]:
        """(the framing, the bytes the stream holds); ValueError where the
        stream is broken (truncated, a bad CRC)."""
        import zlib
        start = _gzip_header_end(raw)
        inflate = zlib.decompressobj(-zlib.MAX_WBITS)
        try:        # at most GZIP_MAX: a small file must not unpack into all the memory
            body = inflate.decompress(raw[start:], GZIP_MAX + 1)
        except zlib.error as exc:
            raise ValueError(f"a gzip stream that does not decompress ({exc})") from None
        if len(body) > GZIP_MAX:
            raise ValueError(f"a gzip stream that unpacks to more than {GZIP_MAX >> 20} MiB: "
                             "not a controller's file (a PolyScope installation is well "
                             "under a megabyte)")
        rest = inflate.unused_data
        if not inflate.eof or len(rest) < 8:
            raise ValueError("a gzip stream cut short (no end of stream or no trailer)")
        if int.from_bytes(rest[:4], "little") != zlib.crc32(body) or \
                int.from_bytes(rest[4:8], "little") != len(body) & 0xFFFFFFFF:
            raise ValueError("a gzip stream whose CRC-32 or length does not match what it holds")
        return cls(raw[:start], raw, body), body

    def wrap(self, body: bytes) -> bytes:
        import zlib
        deflate = zlib.compressobj(6, zlib.DEFLATED, -zlib.MAX_WBITS, 8, zlib.Z_DEFAULT_STRATEGY)
        stream = deflate.compress(body) + deflate.flush()
        return (self.header + stream + zlib.crc32(body).to_bytes(4, "little")
                + (len(body) & 0xFFFFFFFF).to_bytes(4, "little"))


def _gzip_header_end(raw: bytes) -> int:
    """Where a gzip header (RFC 1952) ends: ten bytes, then what its flags name."""
    if len(raw) < 10:
        raise ValueError("a gzip header cut short")
    flags, pos = raw[3], 10
    if flags & 0xE0:
        raise ValueError(f"a gzip header with reserved flags set (0x{flags:02x})")
    if flags & 4:                   # FEXTRA: its length, then that many bytes
        pos += 2 + int.from_bytes(raw[pos:pos + 2], "little")
    for flag in (8, 16):            # FNAME, FCOMMENT: zero-terminated
        if flags & flag:
            end = raw.find(b"\0", pos)
            if end < 0:
                raise ValueError("a gzip header cut short")
            pos = end + 1
    if flags & 2:                   # FHCRC
        pos += 2
    if pos > len(raw):
        raise ValueError("a gzip header cut short")
    return pos


# A run of CRs and the LF after it is one line ending (CRLF, ABB's CR CR LF);
# a CR with no LF after its run ends a line by itself (classic Mac, a KRC
# conversion script's mixed files): ``; note\rBASE_DATA[1]=...`` is two lines.
_CR_RUN = regex.lazy(r"\r+\n?")
# a CR that ends a line by itself: not followed by another CR or an LF
_BARE_CR = regex.lazy(r"\r(?![\r\n])")


def _bare_cr(text: str) -> bool:
    """Whether a CR ends a line by itself somewhere in ``text`` (one scan in
    C: a CRLF file has none, and its lines start after its LFs)."""
    return "\r" in text and _BARE_CR.search(text) is not None


def line_starts(text: str) -> list[int]:
    """Offsets where lines start: 0, and after every line ending (above).
    Linear in the text, however many CRs stand in a row."""
    starts = [0]
    append = starts.append
    if not _bare_cr(text):
        # each line's length + 1, summed (split and accumulate run in C)
        from itertools import accumulate
        starts += accumulate(len(line) + 1 for line in text.split("\n"))
        starts.pop()                # the end of the text: no line starts there
        return starts
    pos = 0
    for m in _CR_RUN.finditer(text):
        lf = text.find("\n", pos, m.start())        # the plain LFs before this run
        while lf != -1:
            append(lf + 1)
            lf = text.find("\n", lf + 1, m.start())
        if text.endswith("\n", 0, m.end()):          # CR ... CR LF: one ending
            append(m.end())
        else:                                        # bare CRs: one ending each
            starts.extend(range(m.start() + 1, m.end() + 1))
        pos = m.end()
    lf = text.find("\n", pos)
    while lf != -1:
        append(lf + 1)
        lf = text.find("\n", lf + 1)
    return starts


INT_MAX = 2 ** 31 - 1       # every controller's indices, groups and frame numbers fit 32 bits


def small_int(text: str, most: int = INT_MAX) -> int | None:
    """Decimal ``text`` (blanks and a sign allowed) as an int, or None where
    it is beyond ``most``. Its length is judged before int() sees it: Python
    refuses more than 4,300 digits with a ValueError, and a million digits
    cost seconds. Every integer a reader takes from a file's text comes
    through here (tests/test_huge_integers.py)."""
    digits = text.strip().lstrip("+-").lstrip("0")
    if len(digits) > len(str(most)):
        return None
    value = int(text)
    return value if abs(value) <= most else None


def shown_digits(text: str) -> str:
    """An integer in a message: whole where short, else its first digits
    and its length."""
    text = text.strip()
    return text if len(text) <= 20 else f"{text[:12]}... ({len(text)} digits)"


def text_lines(text: str) -> list[str]:
    """Lines without their endings (``line_starts``' rule), for showing diffs;
    a final line ending adds no line."""
    if not _bare_cr(text):              # every line ends at an LF: split in C
        lines = text.split("\n")
        if lines[-1] == "":
            lines.pop()
        return [line.rstrip("\r\n") for line in lines]
    starts = line_starts(text)
    if starts[-1] != len(text):
        starts.append(len(text))
    return [text[s:e].rstrip("\r\n") for s, e in zip(starts, starts[1:])]


def lf_lines(text: str) -> str:
    """``text`` with every bare CR (one that ends a line by itself) made an LF:
    the same length and offsets, for scanners and grammars whose lines end
    at LF (KRL)."""
    if not _bare_cr(text):
        return text
    return _CR_RUN.sub(lambda m: m.group() if m.group().endswith("\n") else "\n" * len(m.group()),
                       text)


def masked(text: str, spans: list[tuple[int, int]]) -> str:
    """``text`` with every character outside ``spans`` (sorted) replaced by
    a space, newlines kept: same length, same offsets, same line numbers
    (the fast paths' copy of a file with only the lines they read)."""
    if text.isascii():
        # every gap is a slice of the whole text blanked at once (one
        # translate in C), not a list of blank lines joined for each gap
        blank = text.encode("ascii").translate(_BLANK).decode("ascii")
    else:
        blank = None
    out = []
    pos = 0
    for s, e in spans:
        if s < pos:          # a line matched twice
            continue
        if s > pos:
            out.append(_blanked(text, pos, s) if blank is None else blank[pos:s])
        out.append(text[s:e])
        pos = e
    if pos < len(text):
        out.append(_blanked(text, pos, len(text)) if blank is None else blank[pos:])
    return "".join(out)


# a byte table: LF stays, every other byte a space
_BLANK = bytes(10 if b == 10 else 32 for b in range(256))


def _blanked(text: str, start: int, end: int) -> str:
    return "\n".join([" " * len(part) for part in text[start:end].split("\n")])


def looks_binary(raw: bytes) -> bool:
    """Encrypted RAPID modules and other binaries: a NUL or control byte
    anywhere. The whole file, not its head: a patched copy whose edits move
    such a byte forward must be judged as its input was (one rule for input
    and read-back)."""
    body = raw[len(BOM):] if raw.startswith(BOM) else raw
    # what is left after deleting every byte a text file may hold: a C loop,
    # not a Python one (patch reads every sibling module's bytes)
    return bool(body.translate(None, _TEXT_BYTES))


def first_binary_byte(raw: bytes) -> int:
    """Byte offset (in ``raw``) of the first byte no text file holds; only
    called on bytes ``looks_binary`` flagged."""
    import re

    start = len(BOM) if raw.startswith(BOM) else 0
    return re.compile(rb"[^\x20-\xff\t\n\x0c\r]").search(raw, start).start()


_TEXT_BYTES = bytes(range(32, 256)) + b"\t\n\x0c\r"
