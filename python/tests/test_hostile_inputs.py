"""Hostile inputs to the Python API (issue 26, docs/RELIABILITY.md): each raises surfscatter.Error with one printable
line naming the bad input, never another exception, an "internal error" or a message of several lines. The Python
counterpart of tests/cli/test_cli_hostile.cpp: a libFuzzer harness cannot run here, since an instrumented extension
does not load into Debian's uninstrumented python3.
"""

import numpy as np
import pytest

import surfscatter as ss
from conftest import SOURCE_DIR

SCENE = SOURCE_DIR / "scenes" / "photo-setup" / "scene.xml"


def one_line_error(call, expected):
    with pytest.raises(ss.Error) as raised:
        call()
    message = str(raised.value)
    assert all(0x20 <= ord(c) < 0x7F for c in message), repr(message)
    assert "internal error" not in message, message
    assert expected in message, message
    return message


def test_xml_text_given_as_the_scene_path_is_one_line():
    xml = SCENE.read_text()
    assert xml.count("\n") > 40
    message = one_line_error(lambda: ss.render(xml), "scene must be the path of an .xml file, got XML text '")
    assert len(message) < 200, message


def test_a_path_with_a_line_break_is_escaped():
    one_line_error(lambda: ss.Conductor("no\nsuch.yml"), "no\\x0asuch.yml")


def test_a_path_with_escape_bytes_is_escaped():
    one_line_error(lambda: ss.Conductor("no\x1b[31m.yml"), "no\\x1b[31m.yml")


@pytest.mark.skipif(np.dtype(np.longdouble).itemsize == 8, reason="longdouble is float64 on this platform")
def test_a_longdouble_array_is_refused_by_name():
    one_line_error(lambda: ss.Conductor("Au").ior(np.array([500, 600], dtype=np.longdouble)),
                   "must hold float64 values, got dtype float128")


def test_an_empty_image_is_not_written(tmp_path):
    one_line_error(lambda: ss.write_photo(tmp_path / "empty.png", np.zeros((0, 0, 3), np.float32)), "is empty")
    assert not (tmp_path / "empty.png").exists()


def test_a_negative_index_in_a_file_is_refused(tmp_path):
    path = tmp_path / "negative.csv"
    path.write_text("wavelength_nm,n,k\n400,1,2\n700,-0.5,2\n")
    one_line_error(lambda: ss.Conductor(str(path)), "negative.csv:3: n = -0.5 is negative")
