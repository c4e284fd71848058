"""scripts/doc-tests: what it extracts from Markdown, what it skips, and that a failing command fails it."""
import os
import subprocess
import sys
from pathlib import Path

SCRIPT = Path(__file__).resolve().parents[2] / "scripts" / "doc-tests"
BUILD = Path(os.environ.get("SURFSCATTER_BUILD_DIR", Path(__file__).resolve().parents[2] / "build"))


def load():
    namespace = {"__file__": str(SCRIPT), "__name__": "doc_tests"}
    exec(compile(SCRIPT.read_text(), str(SCRIPT), "exec"), namespace)
    return namespace


DOC = """# A document

```sh
surfscatter ior --material Au --wavelength 550
```

<!-- doc-test: skip needs a cluster -->
```bash
mpirun -np 64 surfscatter study big.json
```

```python
print("hello")
```

```
output, not run
```

| a | b |
|---|---|
| x | `surfscatter fresnel --material Au --wavelength 550 --theta 0` |
| y | `surfscatter render big.xml --spp 4096` <!-- doc-test: skip hours --> |
| z | `surfscatter pose photo.jpg [--marker-id 0]` and `surfscatter surface info MAP --plot psd.png` |

Prose naming `surfscatter render` and `surfscatter brdf eval`, `make test` and `build/bench/bench_bsdf --x`.

    surfscatter metals --out m
    surfscatter ior --material Ag --wavelength 500   # an indented block of commands

Its syntax:

    surfscatter surface info MAP [--form poly2]

- a list item

    surfscatter ior --material Cu --wavelength 500
"""


def test_extracts_blocks_and_whole_inline_commands_and_honours_the_marker(tmp_path):
    doc = tmp_path / "doc.md"
    doc.write_text(DOC)
    snippets = load()["extract"](doc)
    found = [(s.line, s.kind, s.text.strip(), s.skip) for s in snippets]
    # Blocks are named by the line of their opening fence, inline commands by their own.
    assert found == [
        (3, "sh", "surfscatter ior --material Au --wavelength 550", ""),
        (8, "sh", "mpirun -np 64 surfscatter study big.json", "needs a cluster"),
        (12, "python", 'print("hello")', ""),
        (22, "sh", "surfscatter fresnel --material Au --wavelength 550 --theta 0", ""),
        (23, "sh", "surfscatter render big.xml --spp 4096", "hours"),
        (28, "sh", "surfscatter metals --out m\nsurfscatter ior --material Ag --wavelength 500   # an indented block "
                   "of commands", ""),
    ]  # not the syntax line (MAP, [...]) nor the list item's continuation


def test_a_failing_command_fails_the_run_naming_its_line(tmp_path):
    doc = tmp_path / "doc.md"
    doc.write_text("```sh\nsurfscatter --version\n```\n\n```sh\nsurfscatter ior --material Unobtainium\n```\n")
    done = subprocess.run([sys.executable, str(SCRIPT), "--build", str(BUILD), str(doc)], capture_output=True,
                          text=True)
    assert done.returncode == 1, done.stdout + done.stderr
    assert "doc.md:5: sh snippet failed (exit status 2)" in done.stdout  # the line of its fence
    assert "1 failed" in done.stdout
    assert "ok   " in done.stdout  # the first block ran
