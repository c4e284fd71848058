"""What every plot script shares: writing a figure and failing in one line.

save(fig, path) checks the extension first (matplotlib picks the format from it), then writes beside the output, syncs
and renames into place, so that a full disk or an interrupted run leaves the old file or none, never part of one
(surfscatter passes a temporary name of its own and renames it with the command's other outputs). run(main)
runs a script's main(): any failure (a write refused by the disk, a folder, an extension, Ctrl-C, missing input) is one
line on stderr naming what failed and why, with exit status 2, which surfscatter's run_plot_script passes on as it is.
"""
import os
import sys
import textwrap

try:
    import matplotlib
except ImportError:
    print(f"{os.path.basename(sys.argv[0])}: matplotlib is not installed for {sys.executable} "
          "(Debian: apt-get install python3-matplotlib)", file=sys.stderr)
    sys.exit(2)
matplotlib.use("Agg")  # files only, never a window
# One legend size for every plot, readable at the scripts' dpi of 80-150 (legends of 5-7 pt were not).
matplotlib.rcParams["legend.fontsize"] = 8


def wrap(text, width_inches, fontsize):
    """Breaks a title into lines that fit `width_inches` at `fontsize` points (a character is about 0.55 em wide),
    so that a long title (a file name, a fit's parameters) is never clipped at the figure's edge."""
    columns = max(20, int(width_inches * 72 / (0.55 * fontsize)))
    return "\n".join(textwrap.fill(line, columns) for line in text.split("\n"))


class PlotError(Exception):
    """A failure the user can act on; its message is the whole line."""


def save(fig, path, **savefig_options):
    path = str(path)
    extension = os.path.splitext(path)[1].lstrip(".").lower()
    supported = fig.canvas.get_supported_filetypes()
    if extension not in supported:
        raise PlotError(f"cannot write {path}: the extension {'.' + extension if extension else '(none)'} is not an image "
                        f"format matplotlib writes ({', '.join(sorted(supported))})")
    # A short temporary name (core/output_files.hpp's rule): an output whose own name has the maximum length (255
    # bytes) still has one.
    temporary = os.path.join(os.path.dirname(path), f".ss-py-{os.getpid():x}.{extension}")
    try:
        fig.savefig(temporary, format=extension, **savefig_options)
        with open(temporary, "rb") as written:  # on disk before it replaces the old file
            os.fsync(written.fileno())
        os.replace(temporary, path)
    except OSError as error:
        raise PlotError(f"cannot write {path}: {error.strerror or error}") from None
    finally:
        if os.path.exists(temporary):
            os.remove(temporary)


def run(main, *args):
    """Calls main(*args); exits 2 with one line on stderr when it fails."""
    script = os.path.basename(sys.argv[0])
    try:
        status = main(*args)
    except PlotError as error:
        message = str(error)
    except KeyboardInterrupt:
        message = "interrupted (Ctrl-C); no plot written"
    except OSError as error:  # reading an input
        message = f"cannot read {error.filename}: {error.strerror}" if error.filename else str(error)
    except Exception as error:  # a bad input the script did not foresee: still one line
        message = f"{type(error).__name__}: {error}".splitlines()[0]
    else:
        sys.exit(status)
    print(f"{script}: {message}", file=sys.stderr)
    sys.exit(2)
