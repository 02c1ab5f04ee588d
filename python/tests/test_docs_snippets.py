"""Every ```python block of docs/python.md and docs/sweeps.md runs as printed (every
code example in docs/ is complete and compiled or run by a test).

The blocks of a page run in order in one namespace, as a reader would type them into one session,
from a scratch folder that links every top-level entry of filum's tree: the pages' paths from the
tree (apps/scenes/..., docs/data/...) resolve, and what a block writes (results/) lands in the
scratch folder. A block is skipped only for what this build lacks (scene.render() without OpenCV,
the study programs without FILUM_BUILD_BENCHMARKS), and then so are the page's later blocks,
which may need its names. A page can mark a block that cannot run headless with
`<!-- snippet: skip (reason) -->` on the line before its fence; none does.
"""
import os
import re

import pytest

import filum
from conftest import SOURCE_DIR

PAGES = ["docs/python.md", "docs/sweeps.md"]
BLOCK = re.compile(r"^```python\n(.*?)^```[ \t]*$", re.S | re.M)
SKIP_MARK = re.compile(r"^<!-- snippet: skip \((.+)\) -->$")


def snippets(page):
    """(page, first line of the code in the page, code, skip reason or None) of every block."""
    text = (SOURCE_DIR / page).read_text()
    for match in BLOCK.finditer(text):
        line = text.count("\n", 0, match.start(1)) + 1
        mark = SKIP_MARK.match(text[:match.start()].rstrip("\n").rsplit("\n", 1)[-1])  # the line before the fence
        skip = mark.group(1) if mark else None
        yield page, line, match.group(1), skip


SNIPPETS = [snippet for page in PAGES for snippet in snippets(page)]


def test_the_pages_have_python_blocks():
    # A page whose fences change (```py, indented blocks) must not silently leave the test empty.
    for page in PAGES:
        assert any(s[0] == page for s in SNIPPETS), f"{page}: no ```python block found"


class Session:
    def __init__(self):
        self.namespaces = {page: {"__name__": "__main__"} for page in PAGES}
        self.stopped = {}  # page -> why its later blocks do not run


@pytest.fixture(scope="module")
def session(tmp_path_factory):
    folder = tmp_path_factory.mktemp("docs_session")
    for entry in SOURCE_DIR.iterdir():
        if entry.name != "results":
            (folder / entry.name).symlink_to(entry)
    previous = os.getcwd()
    os.chdir(folder)
    try:
        yield Session()
    finally:
        os.chdir(previous)


def lacks(code):
    """Why this build cannot run the block, or None."""
    if re.search(r"\.render\(", code) and not filum.rendering_available:
        return "this build has no OpenCV (scene.render())"
    if re.search(r"\b(stability_map|accuracy_pareto)\(", code) and os.environ.get("FILUM_BUILD_BENCHMARKS") == "OFF":
        return "the study programs are benchmarks (FILUM_BUILD_BENCHMARKS=OFF)"
    return None


@pytest.mark.parametrize("page,line,code,skip", SNIPPETS, ids=[f"{s[0]}:{s[1]}" for s in SNIPPETS])
def test_the_block_runs(session, page, line, code, skip):
    if page in session.stopped:
        pytest.skip(f"an earlier block of {page} did not run: {session.stopped[page]}")
    reason = skip or lacks(code)
    if reason:
        session.stopped[page] = f"line {line}: {reason}"
        pytest.skip(reason)
    # Compiled with the page's line numbers: a traceback points into the page.
    source = "\n" * (line - 1) + code
    try:
        exec(compile(source, str(SOURCE_DIR / page), "exec"), session.namespaces[page])
    except BaseException:
        session.stopped[page] = f"line {line} failed"
        raise
