"""Issue 36, class 4: a plot script that fails (wrong extension, read-only folder, full disk, Ctrl-C, no matplotlib)
prints one line naming the output and the reason and exits 2: no traceback, no partial or temporary file, an old
output left as it was. The rule lives in scripts/plot/plotting.py (save, run); these run it through a small script
and through sheet_compare.py. Run by ctest as `plot_scripts` (pytest)."""
import os
import resource
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

PLOT = Path(__file__).resolve().parents[2] / "scripts" / "plot"

# A plot script as the real ones are written: plotting first, main() through run(), the figure through save().
# With "wait" as its second argument it says "ready" and sleeps, to be interrupted.
SCRIPT = """
import sys, time
sys.path.insert(0, {plot!r})
from plotting import run, save
import matplotlib.pyplot as plt

def main():
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(range(1000), [i % 17 for i in range(1000)], ".")
    ax.set_title("a figure of a few tens of kilobytes")
    if len(sys.argv) > 2:
        print("ready", flush=True)
        time.sleep(60)
    save(fig, sys.argv[1], dpi=120)

run(main)
"""


@pytest.fixture
def script(tmp_path):
    path = tmp_path / "figure.py"
    path.write_text(SCRIPT.format(plot=str(PLOT)))
    return path


def run(arguments, **options):
    return subprocess.run(["/usr/bin/python3", *map(str, arguments)], capture_output=True, text=True, timeout=120,
                          env=dict(os.environ, MPLBACKEND="Agg"), **options)


def one_line(result, *fragments):
    """Exit 2, one line on stderr holding every fragment, nothing of a traceback or of the old hint."""
    assert result.returncode == 2, result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    for fragment in fragments:
        assert fragment in lines[0], lines[0]
    assert "Traceback" not in result.stderr and "is python3-matplotlib installed" not in result.stderr
    return lines[0]


def leftovers(folder, output):
    return sorted(p.name for p in folder.iterdir() if p.name.startswith("." + output.name))


def test_a_figure_is_written(script, tmp_path):
    out = tmp_path / "plot.png"
    result = run([script, out])
    assert result.returncode == 0, result.stderr
    assert out.read_bytes().startswith(b"\x89PNG")
    assert leftovers(tmp_path, out) == []


def test_wrong_extension(script, tmp_path):
    out = tmp_path / "plot.xyz"
    one_line(run([script, out]), str(out), "the extension .xyz is not an image format", "png")
    assert not out.exists() and leftovers(tmp_path, out) == []
    one_line(run([script, tmp_path / "plot"]), "the extension (none) is not an image format")


@pytest.fixture
def read_only_folder(tmp_path):
    """A folder nobody may write into; root ignores permission bits, so for root it is made immutable."""
    folder = tmp_path / "read-only"
    folder.mkdir()
    if os.geteuid() == 0:
        subprocess.run(["chattr", "+i", str(folder)], check=True)
    else:
        folder.chmod(0o555)
    yield folder
    if os.geteuid() == 0:
        subprocess.run(["chattr", "-i", str(folder)], check=True)
    else:
        folder.chmod(0o755)


def test_read_only_folder(script, read_only_folder):
    out = read_only_folder / "plot.png"
    line = one_line(run([script, out]), f"cannot write {out}: ")
    assert line.endswith(("Permission denied", "Operation not permitted", "Read-only file system")), line
    assert list(read_only_folder.iterdir()) == []


def full_disk_at_8_kib():
    # What `ulimit -f` does in a shell, with SIGXFSZ ignored: writes past 8 KiB fail with EFBIG, as on a full disk.
    resource.setrlimit(resource.RLIMIT_FSIZE, (8192, 8192))
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)


def test_full_disk_keeps_the_old_file(script, tmp_path):
    out = tmp_path / "plot.png"
    out.write_bytes(b"the previous plot")
    one_line(run([script, out], preexec_fn=full_disk_at_8_kib), f"cannot write {out}: File too large")
    assert out.read_bytes() == b"the previous plot"
    assert leftovers(tmp_path, out) == []


def test_ctrl_c(script, tmp_path):
    out = tmp_path / "plot.png"
    process = subprocess.Popen(["/usr/bin/python3", str(script), str(out), "wait"], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
    assert process.stdout.readline().strip() == "ready"
    process.send_signal(signal.SIGINT)
    _, err = process.communicate(timeout=60)
    result = subprocess.CompletedProcess(process.args, process.returncode, "", err)
    one_line(result, "figure.py: interrupted (Ctrl-C); no plot written")
    assert not out.exists()


def test_matplotlib_missing(script, tmp_path):
    # A matplotlib package that cannot be imported, first on the path.
    fake = tmp_path / "fake" / "matplotlib"
    fake.mkdir(parents=True)
    (fake / "__init__.py").write_text("raise ImportError('no module named matplotlib')\n")
    result = subprocess.run(["/usr/bin/python3", str(script), str(tmp_path / "plot.png")], capture_output=True,
                            text=True, timeout=60, env=dict(os.environ, PYTHONPATH=str(tmp_path / "fake")))
    one_line(result, "matplotlib is not installed for", "python3-matplotlib")


def test_a_real_script_unreadable_input_and_bad_output(tmp_path):
    # sheet_compare.py, the study's sheets: a panel image that is not an image, then a sheet with a bad extension.
    panel = tmp_path / "panel.png"
    panel.write_bytes(b"not a png")
    one_line(run([PLOT / "sheet_compare.py", tmp_path / "sheet.png", "title", "1", f"a={panel}"]),
             "sheet_compare.py: ")
    assert not (tmp_path / "sheet.png").exists()
    good = tmp_path / "good.png"
    assert run([PLOT / "sheet_compare.py", good, "title", "1", f"a={tmp_path / 'absent.png'}"]).returncode != 0
    import numpy  # noqa: F401  (matplotlib's dependency: makes a real panel)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plt.imsave(panel, [[0.0, 1.0], [1.0, 0.0]])
    one_line(run([PLOT / "sheet_compare.py", tmp_path / "sheet.tif2", "title", "1", f"a={panel}"]),
             f"cannot write {tmp_path / 'sheet.tif2'}: the extension .tif2 is not an image format")


def test_measured_vs_model_sheet(tmp_path):
    # scripts/measured-vs-model's sheet: two renders that differ in a patch make one row; a row without its second
    # image fails in one line and writes nothing.
    import numpy
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    a = numpy.zeros((60, 80, 3))
    b = a.copy()
    b[20:30, 30:50] = 0.5
    plt.imsave(tmp_path / "a.png", a)
    plt.imsave(tmp_path / "b.png", b)
    sheet = tmp_path / "sheet.png"
    assert run([PLOT / "measured_vs_model.py", sheet, "title", f"view 1={tmp_path / 'a.png'},{tmp_path / 'b.png'}"]).returncode == 0
    assert sheet.stat().st_size > 0
    bad = tmp_path / "bad.png"
    one_line(run([PLOT / "measured_vs_model.py", bad, "title", f"view 1={tmp_path / 'a.png'}"]), "measured_vs_model.py: ")
    assert not bad.exists()


if __name__ == "__main__":
    sys.exit(pytest.main([__file__, "-q"]))
