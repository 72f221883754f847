"""The measurement CSV reader: column order and case, the three orientation
forms, European exports, comments, weights, and errors that name the line."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from ucsio.errors import UcsioError
from ucsio.readers.measurement import parse_measurement, read_measurement
from ucsio.method.solve import solve

FIXTURES = Path(__file__).resolve().parents[1] / "fixtures" / "measurements"
TCP = (-20.67, 89.73, 33.44)


def synthetic(seed=0, n=8):
    """Laser points, flange orientations (scipy Rotation) and positions for a
    known frame and TCP, noise-free."""
    rng = np.random.default_rng(seed)
    truth = Rotation.from_euler("ZYX", [90.529, -24.476, -0.313], degrees=True)
    t = np.array([6125.39, 2445.56, 1168.99])
    laser = rng.uniform(0, 1, size=(n, 3)) * [1200.0, 800.0, 300.0]
    robot = truth.apply(laser) + t
    flange = Rotation.random(n, random_state=seed + 1)
    pos = robot - flange.apply(TCP)
    return laser, flange, pos, truth, t


def write_csv(path, form, laser, flange, pos, *, names=None, weights=None, sep=",",
              decimal=".", order=None, upper=False, comments=False):
    cols = ["point", "laser_x", "laser_y", "laser_z", "robot_x", "robot_y", "robot_z"]
    if form == "kuka":
        ori = flange.as_euler("ZYX", degrees=True)
        ocols = ["robot_a", "robot_b", "robot_c"]
    elif form == "fanuc":
        ori = flange.as_euler("ZYX", degrees=True)[:, ::-1]     # W, P, R = C, B, A
        ocols = ["robot_w", "robot_p", "robot_r"]
    else:
        ori = flange.as_quat(scalar_first=True)
        ocols = ["robot_q1", "robot_q2", "robot_q3", "robot_q4"]
    cols += ocols
    data = np.column_stack([laser, pos, ori])
    if weights is not None:
        cols.append("weight")
        data = np.column_stack([data, weights])
    n = len(laser)
    names = names or [f"P{i + 1}" for i in range(n)]
    order = order or list(range(len(cols)))
    header = [cols[k].upper() if upper else cols[k] for k in order]
    lines = []
    if comments:
        lines += ["# laser tracker export", "#  cell R01, base 3", ""]
    lines.append(sep.join(header))
    for i in range(n):
        row = [names[i]] + [repr(float(v)) for v in data[i]]
        if decimal != ".":
            row = [c.replace(".", decimal) for c in row]
        lines.append(sep.join(row[k] for k in order))
        if comments and i == 2:
            lines.append("# P4 measured twice, second kept")
    Path(path).write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


@pytest.mark.parametrize("form", ["kuka", "abb", "fanuc"])
def test_forms_read_back(tmp_path, form):
    laser, flange, pos, truth, t = synthetic()
    m = read_measurement(write_csv(tmp_path / "m.csv", form, laser, flange, pos))
    assert m.form == form and len(m) == 8 and m.names[0] == "P1"
    np.testing.assert_allclose(m.laser, laser, atol=1e-9)
    np.testing.assert_allclose(m.flange[:, :3, :3], flange.as_matrix(), atol=1e-12)
    np.testing.assert_allclose(m.flange[:, :3, 3], pos, atol=1e-9)
    np.testing.assert_allclose(m.robot_points(TCP), truth.apply(laser) + t, atol=1e-9)
    assert m.lines == list(range(2, 10))


def test_all_three_forms_give_the_same_frame(tmp_path):
    laser, flange, pos, truth, t = synthetic(1)
    frames = []
    for form in ("kuka", "abb", "fanuc"):
        m = read_measurement(write_csv(tmp_path / f"{form}.csv", form, laser, flange, pos))
        sol = solve(m, TCP)
        frames.append(sol.pose)
        assert sol.max < 1e-6
    for p in frames[1:]:
        np.testing.assert_allclose(p.t, frames[0].t, atol=1e-9)
        np.testing.assert_allclose(p.q, frames[0].q, atol=1e-12)
    np.testing.assert_allclose(frames[0].t, t, atol=1e-6)
    np.testing.assert_allclose(frames[0].abc, [90.529, -24.476, -0.313], atol=1e-7)


def test_columns_any_order_and_case(tmp_path):
    laser, flange, pos, *_ = synthetic(2)
    ref = read_measurement(write_csv(tmp_path / "a.csv", "abb", laser, flange, pos))
    order = [9, 3, 0, 10, 1, 7, 4, 2, 8, 6, 5]
    m = read_measurement(write_csv(tmp_path / "b.csv", "abb", laser, flange, pos, order=order,
                                   upper=True))
    np.testing.assert_allclose(m.laser, ref.laser)
    np.testing.assert_allclose(m.flange, ref.flange)
    assert m.names == ref.names


def test_european_export_semicolon_decimal_comma(tmp_path):
    laser, flange, pos, *_ = synthetic(3)
    ref = read_measurement(write_csv(tmp_path / "a.csv", "kuka", laser, flange, pos))
    m = read_measurement(write_csv(tmp_path / "eu.csv", "kuka", laser, flange, pos, sep=";",
                                   decimal=",", comments=True))
    np.testing.assert_allclose(m.laser, ref.laser)
    np.testing.assert_allclose(m.flange, ref.flange)


def test_european_cp1252_bom_crlf():
    text = ("\ufeff# Messung Vorrichtung 3 – Basis\r\n"
            "Punkt;laser_x;laser_y;laser_z;robot_x;robot_y;robot_z;robot_a;robot_b;robot_c\r\n"
            "A1;0,5;1,25;-2;100;200;300;10,5;-20;30\r\n"
            "A2;1;2;3;4;5;6;0;0;0\r\n"
            "A3;10;0;0;4;5;6;0;0;0\r\n")
    m = parse_measurement(text, "eu.csv")
    np.testing.assert_allclose(m.laser[0], [0.5, 1.25, -2.0])
    np.testing.assert_allclose(m.orientation[0], [10.5, -20.0, 30.0])
    assert m.names == ["P1", "P2", "P3"]          # 'Punkt' is not 'point': default names
    assert m.lines == [3, 4, 5]


def test_comments_blank_lines_and_extra_columns():
    text = ("# header comment\n\n"
            "point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c,remark\n"
            "  # indented comment\n"
            "H1,0,0,0,1,2,3,0,0,0,first\n"
            "\n"
            '"H 2, left",100,0,0,1,2,3,0,0,0,"quoted, with comma"\n'
            "H3,0,100,0,1,2,3,0,0,0,\n")
    m = parse_measurement(text, "c.csv")
    assert m.names == ["H1", "H 2, left", "H3"]
    assert m.lines == [5, 7, 8]
    np.testing.assert_allclose(m.weights, 1.0)


def test_weights_and_default_names(tmp_path):
    laser, flange, pos, *_ = synthetic(4, n=5)
    text = Path(write_csv(tmp_path / "w.csv", "kuka", laser, flange, pos,
                          weights=[1, 2, 0.5, 1, 3])).read_text()
    m = parse_measurement(text, "w.csv")
    np.testing.assert_allclose(m.weights, [1, 2, 0.5, 1, 3])
    # empty weight cell: default 1
    text = ("laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c,weight\n"
            "0,0,0,1,2,3,0,0,0,\n1,0,0,1,2,3,0,0,0,2\n")
    m = parse_measurement(text, "w.csv")
    assert m.names == ["P1", "P2"]
    np.testing.assert_allclose(m.weights, [1, 2])


def test_shipped_examples_read():
    k = read_measurement(FIXTURES / "kuka_base3.csv")
    a = read_measurement(FIXTURES / "abb_wobj.csv")
    assert (k.form, len(k)) == ("kuka", 8)
    assert (a.form, len(a)) == ("abb", 7)


# ------------------------------------------------------------------ errors

HEAD = "point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c"
ROW1 = "P1,0,0,0,1,2,3,0,0,0"


@pytest.mark.parametrize("text, where, words", [
    ("point,laser_x,laser_y,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c\nP1,0,0,1,2,3,0,0,0\n",
     "m.csv:1", "missing column laser_z"),
    (HEAD + "\n" + ROW1 + "\nP2,0,abc,0,1,2,3,0,0,0\n", "m.csv:3:6", "laser_y not a number: 'abc'"),
    (HEAD + "\n" + ROW1 + "\nP2,0,,0,1,2,3,0,0,0\n", "m.csv:3:6", "laser_y empty"),
    (HEAD + "\n" + ROW1 + "\nP2,0,0,nan,1,2,3,0,0,0\n", "m.csv:3:8", "laser_z is not finite"),
    (HEAD + "\n" + ROW1 + "\nP2,0,0,0,1,2,3,inf,0,0\n", "m.csv:3:16", "robot_a is not finite"),
    (HEAD + "\n" + ROW1 + "\n# c\np1,0,0,0,1,2,3,0,0,0\n", "m.csv:4:1", "duplicate point name 'p1'"),
    (HEAD + ",robot_q1,robot_q2,robot_q3,robot_q4\n" + ROW1 + ",1,0,0,0\n", "m.csv:1",
     "two forms"),
    ("point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z\nP1,0,0,0,1,2,3\n", "m.csv:1",
     "no flange orientation"),
    (HEAD + ",weight\n" + ROW1 + ",1\nP2,1,0,0,1,2,3,0,0,0,-1\n", "m.csv:3:22",
     "weight must be positive"),
    (HEAD + ",weight\n" + ROW1 + ",0\n", "m.csv:2:22", "weight must be positive"),
    (HEAD + "\n" + ROW1 + "\nP2,0,0,0,1,2\n", "m.csv:3", "expected at least 10 fields"),
    ("# only a comment\n", "m.csv", "no header row"),
    (HEAD + "\n# nothing else\n", "m.csv:1", "no data rows"),
    (HEAD + ",laser_x\n" + ROW1 + ",0\n", "m.csv:1:79", "column 'laser_x' given twice"),
    ("point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_q1,robot_q2,robot_q3,robot_q4\n"
     "P1,0,0,0,1,2,3,0.5,0.5,0.5,0.6\n", "m.csv:2:16", "not a unit quaternion"),
    ("point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_q1,robot_q2,robot_q3\n"
     "P1,0,0,0,1,2,3,1,0,0\n", "m.csv:1", "missing column robot_q4"),
])
def test_errors_name_file_line_column(text, where, words):
    with pytest.raises(UcsioError) as info:
        parse_measurement(text, "m.csv")
    msg = str(info.value)
    assert msg.startswith(where + ": "), msg
    assert words in msg
    assert info.value.exit_code == 2


def test_missing_file():
    with pytest.raises(UcsioError, match=r"no such file \(the measurement file\)"):
        read_measurement("/nonexistent/points.csv")


def test_european_decimal_comma_error_position():
    text = ("point;laser_x;laser_y;laser_z;robot_x;robot_y;robot_z;robot_w;robot_p;robot_r\n"
            "P1;0,5;1;2;3;4;5;6;7;8\n"
            "P2;0,5;1;2;3;4;5;6;7,x;8\n")
    with pytest.raises(UcsioError, match=r"^m\.csv:3:20: robot_p not a number: '7,x'"):
        parse_measurement(text, "m.csv")


def test_cp1252_file_and_tabs(tmp_path):
    text = ("# Prüfung Vorrichtung – Basis 3\r\n"
            "point\tlaser_x\tlaser_y\tlaser_z\trobot_x\trobot_y\trobot_z\trobot_w\trobot_p\trobot_r\r\n"
            "Bohrung Ø8\t0,5\t1\t2\t3\t4\t5\t6\t7\t8\r\n")
    f = tmp_path / "cp.csv"
    f.write_bytes(text.encode("cp1252"))
    m = read_measurement(f)
    assert m.names == ["Bohrung Ø8"] and m.form == "fanuc"
    np.testing.assert_allclose(m.laser[0], [0.5, 1, 2])
    f.write_bytes(b"\xef\xbb\xbf" + text.encode("utf-8"))
    assert read_measurement(f).names == ["Bohrung Ø8"]


# ------------------------------------------------------------------ acceptance findings

HEAD9 = "laser_x,laser_y,laser_z,robot_x,robot_y,robot_z,robot_a,robot_b,robot_c"


def test_more_fields_than_header_is_an_error_at_the_first_extra_field():
    # 1841.343819 typed with a decimal comma in a comma-separated file: 10 fields, 9 columns
    bad = "327.702594,-90.800864,49.593688,1841,343819,-187.72,1200.5,10,20,30"
    text = HEAD9 + "\n1,2,3,4,5,6,0,0,0\n" + bad + "\n"
    col = len(bad) - len("30") + 1                       # the 10th field
    with pytest.raises(UcsioError) as info:
        parse_measurement(text, "m.csv")
    msg = str(info.value)
    assert msg.startswith(f"m.csv:3:{col}: "), msg
    assert "10 fields" in msg and "header (line 1) has 9" in msg and "decimal comma" in msg
    assert info.value.exit_code == 2
    # the same in a ';' file: still an error, no decimal-comma hint
    text = HEAD9.replace(",", ";") + "\n1;2;3;4;5;6;0;0;0;7\n"
    with pytest.raises(UcsioError, match=r"^m\.csv:2:19: 10 fields, but the header") as info:
        parse_measurement(text, "m.csv")
    assert "decimal comma" not in str(info.value)
    # a header with a trailing separator and rows with one too: same width, fine
    assert len(parse_measurement(HEAD9 + ",\n1,2,3,4,5,6,0,0,0,\n", "m.csv")) == 1


@pytest.mark.parametrize("sep, empty", [(";", ";;;;;;;;;"), (",", ",,,,,"), (",", ",,,,,,,,,,,,"),
                                        (";", '"";"";""'), ("\t", "\t\t\t")])
def test_rows_of_empty_fields_are_skipped(sep, empty):
    text = "\n".join([HEAD9.replace(",", sep), sep.join("1 2 3 4 5 6 0 0 0".split()), empty,
                      sep.join("7 8 9 4 5 6 0 0 0".split()), empty, empty, ""])
    m = parse_measurement(text, "m.csv")
    assert len(m) == 2 and m.lines == [2, 4]
    np.testing.assert_allclose(m.laser[1], [7, 8, 9])
    # before the header too
    assert len(parse_measurement(empty + "\n" + text, "m.csv")) == 2


@pytest.mark.parametrize("hint, sep, decimal", [("sep=;", ";", ","), ("sep=,", ",", "."),
                                                ('"sep=;"', ";", ","), ("SEP=|", "|", ","),
                                                ("sep=\t", "\t", ",")])
def test_excel_separator_hint(hint, sep, decimal):
    rows = [HEAD9.split(","), "0.5 1 2 3 4 5 6 7 8".split()]
    text = hint + "\r\n" + "\r\n".join(sep.join(c.replace(".", decimal) for c in r) for r in rows)
    m = parse_measurement(text, "m.csv")
    assert m.lines == [3]
    np.testing.assert_allclose(m.laser[0], [0.5, 1, 2])
    np.testing.assert_allclose(m.orientation[0], [6, 7, 8])


def test_separator_hint_wins_over_the_guess_and_bad_hints_are_errors():
    # the hint says ',' although a column name holds a ';'
    text = "sep=,\n" + HEAD9 + ",a;b\n1,2,3,4,5,6,0,0,0,x\n"
    assert len(parse_measurement(text, "m.csv")) == 1
    with pytest.raises(UcsioError, match=r"^m\.csv:1: separator hint 'sep=x'"):
        parse_measurement("sep=x\n" + HEAD9 + "\n1,2,3,4,5,6,0,0,0\n", "m.csv")
    # only before the header: later it is a data row
    with pytest.raises(UcsioError, match=r"^m\.csv:2"):
        parse_measurement(HEAD9 + "\nsep=;\n", "m.csv")


@pytest.mark.parametrize("names", [("robot_rx", "robot_ry", "robot_rz"),
                                   ("ROBOT_QW", "robot_qx", "robot_qy", "robot_qz"),
                                   ("robot_roll", "robot_pitch", "robot_yaw")])
def test_other_orientation_names_get_the_forms_read_not_a_spelling(names):
    """robot_rx is one letter from robot_x: the answer is the orientation
    columns each vendor's form uses."""
    head = "point,laser_x,laser_y,laser_z,robot_x,robot_y,robot_z," + ",".join(names)
    with pytest.raises(UcsioError) as info:
        parse_measurement(head + "\nP1" + ",1" * (6 + len(names)) + "\n", "m.csv")
    msg = str(info.value)
    assert msg.startswith(f"m.csv:1:{head.index(names[0]) + 1}: unknown column {names[0]!r}")
    assert "did you mean" not in msg
    for columns in ("robot_a, robot_b, robot_c (KUKA", "robot_q1 .. robot_q4 (ABB",
                    "robot_w, robot_p, robot_r (FANUC"):
        assert columns in msg


@pytest.mark.parametrize("name, suggestion", [("weigth", "weight"), ("laser-x", "laser_x"),
                                              ("robot_q5", "robot_q4"), ("Laser X", "laser_x"),
                                              ("points", "point"), ("robot-a", "robot_a")])
def test_near_miss_column_is_an_error_with_a_suggestion(name, suggestion):
    text = HEAD9 + f",{name}\n1,2,3,4,5,6,0,0,0,1\n"
    with pytest.raises(UcsioError) as info:
        parse_measurement(text, "m.csv")
    msg = str(info.value)
    assert msg.startswith(f"m.csv:1:{len(HEAD9) + 2}: "), msg
    assert f"unknown column {name!r} \u2014 did you mean {suggestion!r}?" in msg
    # also where the misspelt column replaces a needed one
    text = HEAD9.replace("laser_x", name) + "\n1,2,3,4,5,6,0,0,0\n"
    if name.lower().replace("-", "_").replace(" ", "_") == "laser_x":
        with pytest.raises(UcsioError, match=r"^m\.csv:1:1: unknown column"):
            parse_measurement(text, "m.csv")


@pytest.mark.parametrize("extra", ["comment", "note", "notes", "time", "timestamp", "operator",
                                   "date", "remark", "description", "temperature", "status",
                                   "id", "index", "nr", "robot_s", "robot_t", "robot_e1",
                                   "robot_a1", "robot_cf1", "laser_dx", "laser_rms", ""])
def test_ordinary_extra_columns_stay_accepted(extra):
    text = f"point,{extra},{HEAD9}\nP1,some text,1,2,3,4,5,6,0,0,0\n"
    m = parse_measurement(text, "m.csv")
    assert m.names == ["P1"]
    np.testing.assert_allclose(m.laser[0], [1, 2, 3])
