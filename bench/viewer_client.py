#!/usr/bin/env python3
"""A headless stand-in for the viewer page (bench/viewer_overhead.sh): waits for the server, follows the event
stream, and after each update fetches the frame image over one kept-alive connection, as the page does (it skips
an image while the previous one loads). Ends when the run's process is gone; writes counts as JSON.
  viewer_client.py PORT RUN_PID OUT.json"""
import viewer_wait
import http.client, json, sys, threading, time

port, run_pid, out = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]

def alive():
    return viewer_wait.alive(run_pid)


viewer_wait.wait_for_server(port, run_pid)

updates = 0
images = 0
wanted = threading.Event()
done = threading.Event()

def follow_events():
    global updates
    try:
        c = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
        c.request("GET", "/api/events")
        r = c.getresponse()
        for line in r:
            if line.startswith(b"event: update"):
                updates += 1
                wanted.set()
    except OSError:
        pass
    done.set()

threading.Thread(target=follow_events, daemon=True).start()
images_conn = http.client.HTTPConnection("127.0.0.1", port, timeout=5)
while alive() and not done.is_set():
    if not wanted.wait(timeout=0.5):
        continue
    wanted.clear()
    try:
        images_conn.request("GET", "/api/frame.jpg")
        images_conn.getresponse().read()
        images += 1
    except (OSError, http.client.HTTPException):
        images_conn = http.client.HTTPConnection("127.0.0.1", port, timeout=5)
json.dump({"updates": updates, "images": images}, open(out, "w"))
