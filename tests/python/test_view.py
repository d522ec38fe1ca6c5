"""The live view in a real browser: Debian's chromium, headless, driven through
chromium-driver by python3-selenium, watching `lccp replay --view` of the bundled
recording, and the Python module's view= on the same page."""
import io
import json
import os
import signal
import socket
import subprocess
import time

import pytest
from PIL import Image
from selenium import webdriver
from selenium.webdriver.chrome.options import Options
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.action_chains import ActionChains

import lccp_stream

WAIT_S = 600  # generous: CI may share the machine with other builds

COUNT_KEYS = ["frames_received", "sensor_gaps", "frames_completed", "frames_failed", "frames_dropped"]


@pytest.fixture
def browser(tmp_path):
    options = Options()
    options.binary_location = "/usr/bin/chromium"
    for argument in ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                     "--window-size=1360,1240", f"--user-data-dir={tmp_path / 'profile'}"]:
        options.add_argument(argument)
    driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
    driver.set_page_load_timeout(WAIT_S)
    yield driver
    driver.quit()


def wait_for(condition, what):
    deadline = time.monotonic() + WAIT_S
    while time.monotonic() < deadline:
        value = condition()
        if value:
            return value
        time.sleep(0.05)
    pytest.fail(f"waited {WAIT_S} s for {what}")


def read_url(process):
    line = process.stdout.readline()
    assert line.startswith("view: http://127.0.0.1:"), line
    return line.split()[1]


def page_state(browser):
    return browser.execute_script(
        "const v = window.lccpView; return {shown: v.framesShown, ended: v.ended, counts: v.counts,"
        " colours: v.frame ? v.frame.header.segments.map((s) => s.color) : []};")


def label_colour_share(png, colours, blended):
    """The share of an image's pixels in a segment's colour: blended half and half with the
    grey shading (the 2D view: the differences between channels are half the colour's) or
    as they are (the 3D view's points)."""
    image = Image.open(io.BytesIO(png)).convert("RGB")
    pixels = list(image.getdata())
    scale = 0.5 if blended else 1.0
    found = 0
    for r, g, b in pixels:
        for cr, cg, cb in colours:
            if (cr != cg or cg != cb) and abs((r - g) - scale * (cr - cg)) <= 2 and abs((g - b) - scale * (cg - cb)) <= 2 \
                    and (blended or abs(r - cr) <= 2):
                found += 1
                break
    return found / len(pixels)


def request(port, data):
    """Sends raw bytes; the answer's status (0 if the server closed without one)."""
    with socket.create_connection(("127.0.0.1", port), timeout=WAIT_S) as sock:
        sock.sendall(data)
        answer = b""
        while chunk := sock.recv(65536):
            answer += chunk
    return int(answer.split(b" ")[1]) if answer.startswith(b"HTTP/1.1 ") else 0


def bad_requests(port):
    """What a hostile network sends: each gets its answer and one log line."""
    assert request(port, b"GET /nope HTTP/1.1\r\nHost: x\r\n\r\n") == 404
    assert request(port, b"GET /../../etc/passwd HTTP/1.1\r\nHost: x\r\n\r\n") == 404
    assert request(port, b"GET /%2e%2e/etc/passwd HTTP/1.1\r\nHost: x\r\n\r\n") == 404
    assert request(port, b"GET / HTTP/1.1\r\nX: " + b"a" * 20000 + b"\r\n\r\n") == 431
    for _ in range(200):  # connect and vanish
        socket.create_connection(("127.0.0.1", port), timeout=WAIT_S).close()
    with socket.create_connection(("127.0.0.1", port), timeout=WAIT_S) as sock:  # garbage on the WebSocket
        sock.sendall(b"GET /stream HTTP/1.1\r\nHost: x\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
                     b"Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n")
        assert b" 101 " in sock.recv(4096)
        sock.sendall(bytes(range(256)) * 4)
        while sock.recv(65536):  # until the server closes it
            pass


def test_the_page_shows_a_replay_and_its_final_counts(browser, lccp_binary, recording, tmp_path, source_dir):
    out = tmp_path / "out"
    process = subprocess.Popen([lccp_binary, "replay", str(recording), "--view", "127.0.0.1:0", "--view-hold",
                                "-o", str(out), "--quiet"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        url = read_url(process)
        bad_requests(int(url.rsplit(":", 1)[1].strip("/")))
        browser.get(url)  # the run starts once the page has opened the stream (--view-hold)
        state = wait_for(lambda: (lambda s: s if s["ended"] else None)(page_state(browser)), "the run's end")
        summary = json.loads(wait_for(lambda: (out / "summary.json").exists() and (out / "summary.json").read_text(),
                                      "summary.json"))
        assert state["shown"] >= 20, state["shown"]
        assert {key: state["counts"][key] for key in COUNT_KEYS} == {key: summary[key] for key in COUNT_KEYS}
        assert summary["frames_completed"] == 62 and summary["frames_dropped"] == 0
        assert browser.find_element("id", "completed").text == "62"
        labels = browser.find_element("id", "labels")
        ActionChains(browser).move_to_element(labels).perform()  # the middle of the frame: the objects on the table
        tooltip = browser.find_element("id", "tooltip")
        assert tooltip.is_displayed() and ("points" in tooltip.text or "support" in tooltip.text), tooltip.text
        canvas = labels.screenshot_as_png
        assert label_colour_share(canvas, state["colours"], blended=True) > 0.2, "few label colours in the 2D view"
        points = browser.find_element("id", "points").screenshot_as_png
        assert label_colour_share(points, state["colours"], blended=False) > 0.05, "few label colours in the 3D view"
        shots = os.environ.get("LCCP_VIEW_SCREENSHOTS")  # docs/images: the README's pictures
        if shots:
            browser.save_screenshot(os.path.join(shots, "view.png"))
    finally:
        process.send_signal(signal.SIGINT)
        _, errors = process.communicate(timeout=WAIT_S)
    assert process.returncode == 0, errors
    assert len(list(out.glob("frame_*.png"))) == 62  # the run's outputs are complete
    for line in ["404 (GET /nope)", "404 (GET /../../etc/passwd)", "431 (header too large)",
                 "; stream closed"]:
        assert sum(line in error for error in errors.splitlines()) == 1, (line, errors[-2000:])


def test_python_streams_take_a_view(browser, recording):
    with lccp_stream.Replay(recording, frames=3, view="127.0.0.1:0") as stream:
        assert stream.view_url.startswith("http://127.0.0.1:")
        browser.get(stream.view_url)
        # Nothing taken yet: the run waits on its hand-off queue, and the view shows its newest frame.
        wait_for(lambda: page_state(browser)["shown"] >= 1, "a frame on the page")
        frames = [frame.index for frame in stream]
        state = wait_for(lambda: (lambda s: s if s["ended"] else None)(page_state(browser)), "the run's end")
    assert frames == [0, 1, 2]
    assert state["counts"]["frames_completed"] == 3 and state["counts"]["frames_dropped"] == 0
    with lccp_stream.Replay(recording, frames=1) as stream:
        assert stream.view_url is None
    with pytest.raises(ValueError, match="use \\[HOST:\\]PORT"):
        lccp_stream.Replay(recording, view="localhost:http")
