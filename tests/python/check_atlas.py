"""Runs examples/python/atlas.py at its default size into a temporary PNG and checks the PNG."""
import os
import subprocess
import sys
import tempfile

with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "atlas.png")
    subprocess.run([sys.executable, sys.argv[1], "--out", out, "--threads", "2"], check=True)
    with open(out, "rb") as f:
        data = f.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    assert len(data) > 10_000, f"atlas PNG only {len(data)} bytes"
    print(f"atlas.png: {len(data)} bytes")
