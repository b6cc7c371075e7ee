"""What the viewer's bench clients (viewer_client.py, viewer_load.py) share: whether the run's process is alive, and
waiting until its server answers /api/state (or the run ended first)."""
import http.client, os, time


def alive(run_pid):
    try:
        os.kill(run_pid, 0)
        return True
    except OSError:
        return False


def wait_for_server(port, run_pid):
    while alive(run_pid):
        try:
            c = http.client.HTTPConnection("127.0.0.1", port, timeout=2)
            c.request("GET", "/api/state")
            c.getresponse().read()
            return
        except OSError:
            time.sleep(0.2)
