"""Issue 36, class 1, in Python: every file the package writes (HeightMap.write, write_photo, Camera.write, a BSDF's
export) goes through the library's one writer (core/output_files.hpp): a missing folder or a folder given as the file
is one surfscatter.Error naming the path, a full disk keeps the old file and leaves no temporary file, and a name of
255 bytes is written."""

import contextlib
import resource
import signal

import numpy as np
import pytest

import surfscatter as ss


def small_map():
    return ss.synthesize(ss.KCorrelation(0.1, 2.0, 3.0), 32, spacing_um=0.25, seed=3)


def temporaries(folder):
    return sorted(p.name for p in folder.iterdir() if p.name.startswith(".ss-"))


@contextlib.contextmanager
def full_disk_beyond(size):
    """Writes beyond `size` bytes fail with EFBIG, as on a full disk (RLIMIT_FSIZE with SIGXFSZ ignored)."""
    old_limit = resource.getrlimit(resource.RLIMIT_FSIZE)
    old_handler = signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_FSIZE, (size, old_limit[1]))
    try:
        yield
    finally:
        resource.setrlimit(resource.RLIMIT_FSIZE, old_limit)
        signal.signal(signal.SIGXFSZ, old_handler)


@pytest.mark.parametrize("write", [
    lambda path: small_map().write(str(path.with_suffix(".gsf"))),
    lambda path: ss.write_photo(str(path.with_suffix(".png")), np.random.default_rng(1).random((64, 64, 3), np.float32)),
])
def test_a_full_disk_keeps_the_old_file(tmp_path, write):
    for suffix in (".gsf", ".png"):
        (tmp_path / ("out" + suffix)).write_bytes(b"the previous file")
    with full_disk_beyond(1024), pytest.raises(ss.Error, match=r"cannot write .*out\.(gsf|png).*File too large"):
        write(tmp_path / "out")
    for suffix in (".gsf", ".png"):
        assert (tmp_path / ("out" + suffix)).read_bytes() == b"the previous file"
    assert temporaries(tmp_path) == []


def test_where_a_file_cannot_go_is_one_error_naming_it(tmp_path):
    missing = tmp_path / "missing" / "map.gsf"
    with pytest.raises(ss.Error) as error:
        small_map().write(str(missing))
    assert str(error.value) == f"cannot write output {missing}: folder {missing.parent} does not exist"
    (tmp_path / "folder.gsf").mkdir()
    with pytest.raises(ss.Error, match="is a folder: name a file in it"):
        small_map().write(str(tmp_path / "folder.gsf"))
    assert temporaries(tmp_path) == []


def test_a_name_of_255_bytes_is_written(tmp_path):
    path = tmp_path / ("n" * 251 + ".gsf")
    small_map().write(str(path))
    assert ss.read_height_map(str(path)).nx == small_map().nx
    assert temporaries(tmp_path) == []
