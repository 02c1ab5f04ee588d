"""Every whole scene printed in the README and docs/ loads, checks and runs as printed: the
```jsonc blocks that are complete files (a top-level object with "nodes"), written out and run
through `filum check` and a short `filum run`. Fragments (one component, one node) and outlines
(parts elided with "...") are not files."""
import re
import subprocess

import pytest

from conftest import BINARY_DIR, SOURCE_DIR

PAGES = [SOURCE_DIR / "README.md", *sorted((SOURCE_DIR / "docs").glob("*.md"))]


def whole_scenes():
    for page in PAGES:
        text = page.read_text(encoding="utf-8")
        for k, match in enumerate(re.finditer(r"```jsonc\n(.*?)```", text, re.S)):
            block = match.group(1)
            # A whole file: its first non-comment line opens the top-level object, which has nodes.
            body = "\n".join(line for line in block.splitlines() if not line.lstrip().startswith("//"))
            # An outline with "..." in place of its parts is not a file either.
            if body.lstrip().startswith("{") and re.search(r'^\s*"nodes"\s*:', body, re.M) and "..." not in body:
                line = text[: match.start()].count("\n") + 1
                yield pytest.param(block, id=f"{page.name}:{line}")


@pytest.mark.parametrize("scene", list(whole_scenes()))
def test_a_printed_scene_checks_and_runs(scene, tmp_path):
    path = tmp_path / "scene.json"
    path.write_text(scene, encoding="utf-8")
    filum = str(BINARY_DIR / "apps" / "filum")
    check = subprocess.run([filum, "check", str(path)], capture_output=True, text=True)
    assert check.returncode == 0, check.stdout + check.stderr
    run = subprocess.run([filum, "run", str(path), "--duration", "0.05", "--out", str(tmp_path / "out"), "-q"],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stdout + run.stderr


def test_the_pages_print_whole_scenes():
    assert len(list(whole_scenes())) >= 2    # the README's and the scene page's (the parser finds them)
