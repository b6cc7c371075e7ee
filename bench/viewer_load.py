#!/usr/bin/env python3
"""Load on the live viewer (bench/viewer_load.sh): CLIENTS concurrent clients on loopback while a run goes, until
the run's process ends or SECONDS pass. A tenth follow the event stream (/api/events, as a tab does); of the others
half fetch /api/state and half /api/frame.jpg, each over its own kept-alive connection, with PAUSE seconds between
requests (a page polling). Writes per endpoint the requests, the statuses and the latency (median, p95, max ms).
  viewer_load.py PORT RUN_PID OUT.json [CLIENTS=50] [SECONDS=30] [PAUSE=0.1]"""
import viewer_wait
import http.client, json, statistics, sys, threading, time

port, run_pid, out = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
clients = int(sys.argv[4]) if len(sys.argv) > 4 else 50
seconds = float(sys.argv[5]) if len(sys.argv) > 5 else 30.0
pause = float(sys.argv[6]) if len(sys.argv) > 6 else 0.1


def alive():
    return viewer_wait.alive(run_pid)


viewer_wait.wait_for_server(port, run_pid)

end = time.monotonic() + seconds
lock = threading.Lock()
results = {}  # path -> {"status": {code: n}, "ms": [...], "errors": n}


def record(path, status, ms):
    with lock:
        r = results.setdefault(path, {"status": {}, "ms": [], "errors": 0})
        if status is None:
            r["errors"] += 1
        else:
            r["status"][str(status)] = r["status"].get(str(status), 0) + 1
            r["ms"].append(ms)


def running():
    return time.monotonic() < end and alive()


def poll(path):
    conn = None
    while running():
        start = time.monotonic()
        try:
            conn = conn or http.client.HTTPConnection("127.0.0.1", port, timeout=10)
            conn.request("GET", path)
            resp = conn.getresponse()
            resp.read()
            record(path, resp.status, 1000 * (time.monotonic() - start))
        except (OSError, http.client.HTTPException):
            record(path, None, 0)
            conn = None
        time.sleep(pause)


def follow():
    while running():
        try:
            c = http.client.HTTPConnection("127.0.0.1", port, timeout=5)
            start = time.monotonic()
            c.request("GET", "/api/events")
            r = c.getresponse()
            record("/api/events", r.status, 1000 * (time.monotonic() - start))
            if r.status != 200:
                r.read()
                time.sleep(1)
                continue
            while running() and r.readline():
                pass
        except (OSError, http.client.HTTPException):
            record("/api/events", None, 0)
            time.sleep(pause)


streams = max(1, clients // 10)
threads = [threading.Thread(target=follow, daemon=True) for _ in range(streams)]
for i in range(clients - streams):
    threads.append(threading.Thread(target=poll, args=("/api/state" if i % 2 == 0 else "/api/frame.jpg",), daemon=True))
for t in threads:
    t.start()
for t in threads:
    t.join(timeout=max(0.0, end - time.monotonic()) + 15)

summary = {}
for path, r in results.items():
    ms = sorted(r["ms"])
    summary[path] = {"requests": len(ms) + r["errors"], "status": r["status"], "errors": r["errors"],
                     "median_ms": statistics.median(ms) if ms else None,
                     "p95_ms": ms[int(0.95 * (len(ms) - 1))] if ms else None, "max_ms": ms[-1] if ms else None}
json.dump({"clients": clients, "seconds": seconds, "pause": pause, "endpoints": summary}, open(out, "w"), indent=1)
