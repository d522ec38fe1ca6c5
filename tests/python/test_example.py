"""examples/python/replay_objects.py runs and writes its label image."""
import os
import re
import subprocess
import sys

FRAMES_IN_RECORDING = 62


def test_replay_objects_example(tmp_path, source_dir):
    out = tmp_path / "out"
    result = subprocess.run([sys.executable, str(source_dir / "examples" / "python" / "replay_objects.py"), str(out)],
                            capture_output=True, text=True, timeout=300, env=dict(os.environ))
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    frame_lines = [line for line in lines if re.fullmatch(r"frame \d+: \d+ objects", line)]
    assert len(frame_lines) == FRAMES_IN_RECORDING
    assert [int(line.split()[1].rstrip(":")) for line in frame_lines] == list(range(FRAMES_IN_RECORDING))
    assert any(int(line.split()[2]) > 0 for line in frame_lines)
    pngs = list(out.glob("*.png"))
    assert len(pngs) == 1
    assert pngs[0].read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert lines[-1] == f"wrote {pngs[0]}"
