# SPDX-License-Identifier: AGPL-3.0-or-later
"""The README's Python cookbook (and its meshio example), run as written
and checked against the output the README shows: in a scratch directory
laid out like the repository after the build (build/server, build/client,
build/data/meshes, data/samples), with bash for the shell blocks and
/usr/bin/python3 for the Python ones; the notebook's cells in a Jupyter
kernel (nbclient and ipykernel, when installed), else as one script.
Times are masked (``80 ms``), as are the local server's socket and pid.
Skipped without the build's meshes (libcgal-demo) or dotctl."""
import importlib.util
import os
import re
import shutil
import subprocess
from pathlib import Path
from typing import List

import pytest

import dot_client
from conftest import ROOT, server_path

meshio = pytest.importorskip("meshio")

README = Path(ROOT) / "README.md"


def blocks(start: str, stop: str) -> List[str]:
    """The fenced blocks of README between two headings, in order."""
    text = README.read_text()
    i = text.index(start)
    section = text[i:text.index(stop, i)]
    return [m.group(1) for m in re.finditer(r"```\w*\n(.*?)```", section,
                                            re.S)]


def block(found: List[str], marker: str) -> int:
    """The index of the one block that contains `marker`."""
    hits = [i for i, b in enumerate(found) if marker in b]
    assert len(hits) == 1, f"{len(hits)} README blocks contain {marker!r}"
    return hits[0]


def masked(text: str) -> str:
    text = re.sub(r"\d+ ms\b", "N ms", text)
    text = re.sub(r"dot-server-\w+", "dot-server-X", text)
    return re.sub(r"pid \d+", "pid N", text).strip()


@pytest.fixture(scope="module")
def repo(tmp_path_factory) -> Path:
    """A scratch directory laid out as the README's commands expect."""
    server = Path(server_path()).resolve()
    build = server.parent.parent
    meshes = build / "data" / "meshes"
    dotctl = build / "client" / "dotctl"
    if not (meshes / "bunny00.off").exists() or not dotctl.exists():
        pytest.skip(f"no {meshes} (libcgal-demo) or {dotctl}")
    work = tmp_path_factory.mktemp("readme")
    (work / "build" / "client").mkdir(parents=True)
    (work / "build" / "server").symlink_to(server.parent)
    (work / "build" / "data").symlink_to(build / "data")
    (work / "build" / "client" / "dotctl").symlink_to(dotctl)
    package = Path(os.path.abspath(dot_client.__file__)).parent.parent
    (work / "build" / "client" / "python").symlink_to(package)
    (work / "data").symlink_to(Path(ROOT) / "data")
    return work


def run(repo: Path, *steps: str, stderr: bool = True) -> str:
    """Runs the blocks in one bash (Python ones through /usr/bin/python3
    from a file), as a terminal would show them (without stderr when
    ``stderr`` is False)."""
    script = []
    for n, step in enumerate(steps):
        if step.startswith("python:"):
            (repo / f"step{n}.py").write_text(step[len("python:"):])
            script.append(f"/usr/bin/python3 step{n}.py")
        else:
            script.append(step)
    env = {k: v for k, v in os.environ.items()
           if k not in ("PYTHONPATH", "DOT_SERVER_PATH")}
    env.update(PYTHONUNBUFFERED="1", MPLBACKEND="Agg")
    out = subprocess.run(["bash", "-ec", "\n".join(script)], cwd=repo,
                         env=env, stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT if stderr else
                         subprocess.PIPE, text=True, timeout=120)
    assert out.returncode == 0, (out.stdout, out.stderr)
    return out.stdout


def test_the_meshio_example(repo):
    found = blocks("**Mesh files (meshio).**", "**Local mode.**")
    code = block(found, 'meshio.read("build/data/meshes/head.off")')
    export = blocks("## Python cookbook", "## Use from Blender")[0]
    assert export.startswith("export PYTHONPATH=")
    out = run(repo, export, "python:" + found[code])
    assert masked(out) == masked(found[code + 1])
    assert (repo / "head.ply").exists()


def test_the_cookbook_recipes(repo):
    found = blocks("## Python cookbook", "## Use from Blender")
    export = found[0]
    setup = block(found, "mkdir -p scans")
    folder = block(found, "src, dst = ")
    csv_setup = block(found, "> loops.csv")
    csv = block(found, 'open("loops.csv"')

    # Every mesh of a folder: the setup's output, then the recipe's (the
    # two blocks after the recipe).
    out = run(repo, export, found[setup], "python:" + found[folder])
    assert masked(out) == masked(found[folder + 1] + found[folder + 2])
    for path in (repo / "closed").iterdir():
        faces = meshio.read(path).cells[0].data
        edges = {(a, b) for t in faces.tolist()
                 for a, b in zip(t, t[1:] + t[:1])}
        assert all((b, a) in edges for a, b in edges), f"{path} is open"
    # Files that fail are a line each (the README's fin.off and junk.ply).
    bad = repo / "bad"
    (bad / "scans").mkdir(parents=True)
    (bad / "scans" / "fin.off").write_text(
        "OFF\n8 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 -1 0\n2 2 2\n3 2 2\n"
        "2 3 2\n3 0 1 2\n3 0 1 3\n3 0 1 4\n3 5 6 7\n")
    (bad / "scans" / "junk.ply").write_text("nonsense\n")
    shutil.copytree(repo / "build", bad / "build", symlinks=True)
    out = run(bad, export, "python:" + found[folder])
    assert masked(out) == masked(found[folder + 3])

    # Loops from a CSV.
    out = run(repo, export, found[csv_setup], "python:" + found[csv])
    assert masked(out) == masked(found[csv + 1])
    assert (repo / "hole.obj").exists() and (repo / "spiral.obj").exists()


NOTEBOOK = """
import sys

import nbformat
from nbclient import NotebookClient

cells, current = [], []
for line in open(sys.argv[1]).read().splitlines():
    if line.startswith("# %%") and current:
        cells.append("\\n".join(current))
        current = []
    current.append(line)
cells.append("\\n".join(current))
nb = nbformat.v4.new_notebook(
    cells=[nbformat.v4.new_code_cell(c.strip()) for c in cells])
NotebookClient(nb, timeout=120, kernel_name="python3").execute()
for cell in nb.cells:
    # A slow kernel may send one printed line as several stream messages;
    # the cell shows them as one text, each line as its last \\r left it.
    text = "".join(out.text for out in cell.outputs
                   if out.output_type == "stream" and out.name == "stdout")
    if text:
        print("\\n".join(line.rsplit("\\r", 1)[-1]
                        for line in text.rstrip("\\n").split("\\n")))
    for out in cell.outputs:
        if out.output_type == "error":
            sys.exit(f"{out.ename}: {out.evalue}")
        if out.output_type == "execute_result":
            print(out.data["text/plain"])
"""


def test_the_notebook(repo):
    found = blocks("## Python cookbook", "## Use from Blender")
    if not (repo / "scans" / "elephant.off").exists():
        run(repo, found[block(found, "mkdir -p scans")])
    cells = block(found, "# %% A dot-server for this notebook")
    (repo / "cells.py").write_text(found[cells])
    if importlib.util.find_spec("matplotlib") is None:
        pytest.skip("no matplotlib (python3-matplotlib)")
    if None in (importlib.util.find_spec("nbclient"),
                importlib.util.find_spec("ipykernel")):
        # No Jupyter: the same cells as one script.
        run(repo, found[0], "python:" + found[cells])
    else:
        (repo / "notebook.py").write_text(NOTEBOOK)
        # (The kernel's own chatter, its debugger's warnings, on stderr.)
        out = run(repo, found[0], "/usr/bin/python3 notebook.py cells.py",
                  stderr=False)
        assert masked(out) == masked(found[cells + 1])
    assert (repo / "elephant-closed.ply").exists()
