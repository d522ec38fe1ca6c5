#!/usr/bin/env python3
"""Objects in a recording, frame by frame, with the lccp_stream Python module.

Usage:  python3 replay_objects.py [OUT_DIR [RECORDING.oni]]

OUT_DIR defaults to ./out-python; RECORDING to the repository's
recordings/mosd_scenes.oni (62 Kinect frames of mOSD table-top scenes).
The module is built into <build>/python: run with PYTHONPATH=<build>/python
(or install the project and add <prefix>/lib/python3.X/dist-packages).
"""
# %% Imports and arguments
import pathlib
import sys

import lccp_stream

# The repository is two folders above this script (examples/python/).
repository = pathlib.Path(__file__).resolve().parents[2]
out_dir = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "out-python")
recording = pathlib.Path(sys.argv[2]) if len(sys.argv) > 2 else repository / "recordings" / "mosd_scenes.oni"
out_dir.mkdir(parents=True, exist_ok=True)

# %% The configuration
# The `objects` preset removes the support plane (the table) first, then cuts
# the rest into objects (one level: Frame.labels are object ids). print(config)
# lists every key; segment(), Replay and Live also take a dict of keys.
config = lccp_stream.load_config("objects")

# %% Replay: the library's pipeline runs on a background thread
# Every frame of the recording comes out in order (a replay drops none). Each
# Frame carries the points (480 x 640 x 3, NaN where the sensor saw nothing),
# a label per point, and `segments`: the objects' geometry, as the per-frame
# JSON files of `lccp replay --save segments` (README: Objects and parts).
last = None
with lccp_stream.Replay(recording, config=config) as replay:
    for frame in replay:
        print(f"frame {frame.index}: {len(frame.segments)} objects", flush=True)
        last = frame

# %% The last frame's labels as an image
# One colour per object, black where there are no data; the table is the
# support segment (id 1).
if last is None:
    sys.exit(f"{recording}: no frames")
png = out_dir / f"frame_{last.index:06d}_objects.png"
lccp_stream.write_label_png(png, last.labels)
print(f"wrote {png}")
