"""The README's and docs/python.md's Python snippets run as written."""

import os
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def snippets(path):
    text = path.read_text()
    return re.findall(r"```python\n(.*?)```", text, flags=re.S)


@pytest.mark.parametrize("doc", ["README.md", "docs/python.md"])
def test_snippets_run(doc, tmp_path, monkeypatch):
    blocks = snippets(ROOT / doc)
    if doc == "README.md":
        assert blocks, "the README shows Python usage"
    monkeypatch.chdir(tmp_path)
    for code in blocks:
        if "rclpy" in code or "draw_geometries" in code:
            continue  # needs ROS 2 or a display
        exec(compile(code, f"{doc} snippet", "exec"), {"__name__": "__snippet__"})
