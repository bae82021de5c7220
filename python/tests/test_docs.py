"""Runs every python code block of docs/python.md (blocks reading $MPR_DATA_DIR skip without it)."""

import os
import pathlib
import re

import numpy as np
import pytest

DOC = pathlib.Path(os.environ.get("MPR_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2])) / "docs" / "python.md"
BLOCKS = re.findall(r"```python\n(.*?)```", DOC.read_text(), re.S)


def test_doc_has_the_four_examples():
    assert len(BLOCKS) == 4


@pytest.mark.parametrize("index", range(len(BLOCKS)))
def test_doc_block_runs(index, tmp_path, monkeypatch, data_dir):
    code = BLOCKS[index]
    if "MPR_DATA_DIR" in code:
        needed = re.findall(r'"(stanford|middlebury)"', code)
        if data_dir is None or not all((data_dir / n).exists() for n in needed):
            pytest.skip("real data not found (set MPR_DATA_DIR)")
        monkeypatch.setenv("MPR_DATA_DIR", str(data_dir))
    monkeypatch.chdir(tmp_path)
    namespace = {}
    exec(compile(code, f"{DOC.name} block {index + 1}", "exec"), namespace)
    if "sheet" in namespace:  # the gallery: nine tiles, none of them empty
        sheet = namespace["sheet"]
        assert sheet.shape == (600, 1050, 3)
        for k in range(9):
            tile = sheet[(k // 3) * 200:(k // 3 + 1) * 200, (k % 3) * 350:(k % 3 + 1) * 350]
            assert tile.mean() > 20, f"gallery tile {k} is nearly black"
    if "near" in namespace and "far" in namespace:  # refocus: the two focal depths differ
        assert (namespace["near"] != namespace["far"]).mean() > 0.1
    if "depth" in namespace:  # inside the swept range (float); the temple's centre is 0.566 from each camera
        depth = namespace["depth"]
        assert 0.45 - 1e-6 <= float(depth.min()) and float(depth.max()) <= 0.75 + 1e-6
        assert 0.52 < float(np.median(depth)) < 0.62


def test_readme_refocus_runs(monkeypatch):
    source = DOC.parents[1]
    blocks = re.findall(r"```python\n(.*?)```", (source / "README.md").read_text(), re.S)
    assert len(blocks) == 1 and len(blocks[0].strip().splitlines()) == 5
    if not (source / ".." / "shared" / "data" / "stanford" / "chess").exists():
        pytest.skip("real data not found (../shared/data from the source folder)")
    monkeypatch.chdir(source)
    namespace = {}
    exec(compile(blocks[0], "README.md", "exec"), namespace)
    assert namespace["image"].shape == (400, 700, 3)
