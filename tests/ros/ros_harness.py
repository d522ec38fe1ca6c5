"""What the ROS tests (test_lccp_ros.py, test_nodelet.py, test_parameters.py) and
perf/ros_latency.py share: a private ROS master on a free port of 127.0.0.1 with its
own ROS_HOME and ROS_LOG_DIR, the processes they start (stopped in reverse order,
SIGINT then SIGKILL), waiting for a condition with a limit, and a test's run in a
scratch folder whose logs are shown when it fails."""
import os
import signal
import socket
import subprocess
import sys
import tempfile
import time


def free_port():
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_for(condition, timeout_s, what):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if condition():
            return
        time.sleep(0.05)
    raise AssertionError(f"timed out after {timeout_s} s waiting for {what}")


class Processes:
    """Everything started, stopped in reverse order (SIGINT, then SIGKILL after 30 s)."""

    def __init__(self):
        self.started = []

    def start(self, command, env, log_path):
        log = open(log_path, "wb")
        process = subprocess.Popen(command, env=env, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        self.started.append((process, log))
        return process

    def stop_all(self):
        for process, log in reversed(self.started):
            if process.poll() is None:
                os.killpg(process.pid, signal.SIGINT)
                try:
                    process.wait(timeout=30)
                except subprocess.TimeoutExpired:
                    os.killpg(process.pid, signal.SIGKILL)
                    process.wait()
            log.close()


def start_master(processes, tmp, timeout_s):
    """A ROS master of our own; this process's environment (rospy) and the returned
    one (for the processes started next) point at it."""
    import rosgraph
    port = free_port()
    env = dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_HOSTNAME="127.0.0.1",
               ROS_HOME=os.path.join(tmp, "ros_home"), ROS_LOG_DIR=os.path.join(tmp, "ros_log"))
    os.environ.update(env)
    processes.start(["rosmaster", "--core", "-p", str(port)], env, os.path.join(tmp, "master.log"))
    wait_for(lambda: rosgraph.Master("/lccp_harness", master_uri=env["ROS_MASTER_URI"]).is_online(),
             timeout_s, "the ROS master")
    return env


def run_in_scratch(prefix, logs, run):
    """run(tmp, processes) in a scratch folder; on failure the tail of each log in
    `logs` (names in that folder) goes to stderr; the processes are stopped, and a
    rospy node this process started is shut down, either way."""
    processes = Processes()
    with tempfile.TemporaryDirectory(prefix=prefix) as tmp:
        try:
            run(tmp, processes)
        except BaseException:
            for log in logs:
                path = os.path.join(tmp, log)
                if os.path.exists(path):
                    print(f"--- {log} ---\n" + open(path, errors="replace").read()[-4000:], file=sys.stderr)
            raise
        finally:
            rospy = sys.modules.get("rospy")
            if rospy is not None and rospy.core.is_initialized():
                rospy.signal_shutdown("test done")
            processes.stop_all()
