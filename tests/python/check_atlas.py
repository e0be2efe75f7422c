"""Runs examples/python/atlas.py on a small grid into a temporary PNG and checks the PNG."""
import os
import subprocess
import sys
import tempfile

with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "atlas.png")
    # 2 x 2 stairs per robot keeps the CI cost to 8 plans; the example defaults to 3 x 3.
    subprocess.run([sys.executable, sys.argv[1], "--out", out, "--threads", "2", "--size", "2"], check=True)
    with open(out, "rb") as f:
        data = f.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    assert len(data) > 10_000, f"atlas PNG only {len(data)} bytes"
    print(f"atlas.png: {len(data)} bytes")
