"""Replay and Live: the library's pipeline on a background thread, frames in order."""
import subprocess
import sys
import time

import numpy as np
import pytest

import lccp_stream

FRAMES_IN_RECORDING = 62  # recordings/README.md: 62 Kinect frames of mOSD scenes


def test_replay_yields_every_frame_in_order(recording):
    indices = []
    with lccp_stream.Replay(recording, config="p1", inflight=2) as replay:
        for frame in replay:
            indices.append(frame.index)
            assert frame.error == ""
            assert frame.points.dtype == np.float32 and frame.points.shape == (480, 640, 3)
            assert frame.labels.dtype == np.uint32 and frame.labels.shape == frame.points.shape[:2]
            assert frame.objects is None  # one level
            finite = np.isfinite(frame.points).all(axis=-1)
            assert (frame.labels[~finite] == 0).all() and (frame.labels[finite] > 0).all()
            assert {s["id"] for s in frame.segments} == set(np.unique(frame.labels)) - {0}
            assert frame.support_plane is None
    assert indices == list(range(FRAMES_IN_RECORDING))


def test_replay_labels_are_the_command_lines(tmp_path, recording, lccp_binary):
    subprocess.run([lccp_binary, "replay", str(recording), "--frames", "2", "-o", str(tmp_path), "--save", "pcd",
                    "--quiet"], check=True, capture_output=True)
    written = sorted(tmp_path.glob("frame_*.pcd"))
    frames = list(lccp_stream.Replay(recording, frames=2))
    assert len(written) == len(frames) == 2
    for frame, path in zip(frames, written):
        cli = lccp_stream.read_cloud(path)
        assert path.name == f"frame_{frame.index:06d}_{frame.timestamp_us:010d}us.pcd"
        np.testing.assert_array_equal(frame.labels, cli["labels"])


def test_breaking_out_early_and_closing_does_not_hang(recording):
    start = time.monotonic()
    replay = lccp_stream.Replay(recording, threads=2)
    taken = []
    for frame in replay:
        taken.append(frame.index)
        if len(taken) == 3:
            break
    replay.close()
    replay.close()  # twice is fine
    assert taken == [0, 1, 2]
    with pytest.raises(StopIteration):
        next(replay)
    assert time.monotonic() - start < 20


def test_dropping_an_unfinished_replay_does_not_hang(recording):
    replay = lccp_stream.Replay(recording)
    next(replay)
    del replay  # the destructor stops and joins the run
    with lccp_stream.Replay(recording, frames=5) as replay:
        assert next(replay).index == 0
    # leaving the block closed it
    assert list(replay) == []


def test_frames_limit_and_objects_with_two_levels(recording):
    frames = list(lccp_stream.Replay(recording, config="robot", frames=3, threads=1))
    assert [f.index for f in frames] == [0, 1, 2]
    for frame in frames:
        assert frame.objects is not None and frame.objects.shape == frame.labels.shape
        assert frame.support_plane is not None and frame.support_plane["id"] == 1
    assert frames[0].new_ids and not frames[0].gone_ids
    first_ids = {s["id"] for s in frames[0].segments}
    assert first_ids & {s["id"] for s in frames[1].segments}  # stable ids across frames


def test_ctrl_c_stops_the_run(tmp_path, recording):
    # A child process: SIGINT while it waits for the second frame raises KeyboardInterrupt
    # at once, and the stream left to the interpreter's exit ends without a hang.
    script = tmp_path / "interrupt.py"
    script.write_text(f"""
import _thread, signal, threading, time, lccp_stream
signal.signal(signal.SIGINT, signal.default_int_handler)  # as at a terminal, even if the tests were started with SIGINT ignored
replay = lccp_stream.Replay({str(recording)!r}, config="p2", threads=1, inflight=1)
frames = 0
try:
    for frame in replay:
        frames += 1
        if frames == 1:
            threading.Timer(0.05, _thread.interrupt_main).start()
            start = time.monotonic()
    print("finished", frames)
except KeyboardInterrupt:
    print("interrupted", frames, time.monotonic() - start < 1.0)
""")
    result = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stderr
    words = result.stdout.split()
    assert words[0] == "interrupted" and int(words[1]) < FRAMES_IN_RECORDING and words[2] == "True"


def test_live_virtual_sensor():
    frames = list(lccp_stream.Live("virtual://synthetic", frames=3))
    assert len(frames) == 3
    assert [f.index for f in frames] == sorted(f.index for f in frames)
    assert all(f.labels.shape == f.points.shape[:2] for f in frames)


def test_live_frames_counts_the_frames_it_yields():
    # A consumer slower than the sensor's 30 Hz: the live source drops the frames that
    # come while there is no room (the oldest first), and frames=10 still yields 10.
    indices = []
    for frame in lccp_stream.Live("virtual://synthetic", frames=10, inflight=1, threads=1):
        indices.append(frame.index)
        assert frame.error == "" and frame.labels.shape == (480, 640)
        time.sleep(0.2)
    assert len(indices) == 10
    assert indices == sorted(set(indices))  # in order; the gaps are the dropped frames


def test_a_disappearing_device_raises_runtime_error():
    live = lccp_stream.Live("virtual://synthetic?frames=2")
    frames = []
    with pytest.raises(RuntimeError):
        for frame in live:
            frames.append(frame)
    assert len(frames) <= 2


def test_pushed_clouds_come_back_in_order_with_segments_labels(mosd_cloud, mosd_labels):
    """Push: each cloud waited for comes back as a Frame with segment()'s labels; end() ends it."""
    with lccp_stream.Push(config="p1", inflight=2) as stream:
        for expected_index in range(3):
            index = stream.push(mosd_cloud["points"], colors=mosd_cloud["colors"], timestamp_us=1000 * expected_index)
            assert index == expected_index
            frame = next(stream)
            assert (frame.index, frame.timestamp_us, frame.error) == (expected_index, 1000 * expected_index, "")
            assert frame.points.shape == mosd_cloud["points"].shape
            np.testing.assert_array_equal(frame.labels, mosd_labels)
        stream.end()
        with pytest.raises(StopIteration):
            next(stream)


def test_pushing_faster_than_segmenting_drops_the_oldest_and_keeps_the_newest(mosd_cloud):
    pushed = 20
    with lccp_stream.Push(config="p1", inflight=1, threads=1, waiting=1) as stream:
        for _ in range(pushed):
            stream.push(mosd_cloud["points"])
        stream.end()
        indices = [frame.index for frame in stream]
    assert indices and indices == sorted(set(indices))
    assert indices[-1] == pushed - 1  # the newest always gets through
    # Nothing was taken while pushing, so at most 5 frames were kept, however fast the
    # machine: 2 in the hand-off queue, 1 at its sink, 1 at admission, 1 in the source.
    assert len(indices) <= 5


def test_push_rejects_bad_arrays_and_zero_waiting(mosd_cloud):
    with lccp_stream.Push() as stream:
        with pytest.raises(ValueError, match="points"):
            stream.push(np.zeros((5, 2), np.float32))
    with pytest.raises(ValueError, match="waiting"):
        lccp_stream.Push(waiting=0)
