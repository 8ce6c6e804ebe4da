"""The explorer under rapid page loads: time to serve a static file, and memory.

``python -m benchmarks.explore_load [--loads 50] [--max-sessions 8]``

Starts ``andoyer explore --no-browser`` on a free loopback port, loads the page once
and lets it settle (the baseline memory: resident set of the server's process tree),
then loads the page ``--loads`` times at once (one thread each, no browser: each load
makes a Bokeh session that is never connected) and, half a second later, times one
request for a static file (``bokeh.min.js``). Prints one line: the time of all loads,
the static request's time, and the resident memory at the baseline, at its peak and
10 s after the loads. Every request has a timeout (60 s for the static one, 120 s for a
page); the server is ended at the end, whatever happens.
"""

from __future__ import annotations

import argparse
import os
import re
import signal
import subprocess
import sys
import threading
import time
import urllib.request
from concurrent.futures import ThreadPoolExecutor


def _rss_mb(pid: int) -> float:
    import psutil

    try:
        root = psutil.Process(pid)
        return sum(p.memory_info().rss for p in [root, *root.children(recursive=True)]) / 2**20
    except psutil.Error:
        return 0.0


def _get(url: str, timeout: float) -> float:
    t0 = time.monotonic()
    with urllib.request.urlopen(url, timeout=timeout) as r:
        r.read()
    return time.monotonic() - t0


def measure(loads: int = 50, max_sessions: int | None = None) -> dict[str, float]:
    """The numbers of one run (seconds and MB; ``inf`` for a request that timed out)."""
    cmd = [sys.executable, "-m", "andoyer", "explore", "--port", "0", "--no-browser"]
    if max_sessions is not None:
        cmd += ["--max-sessions", str(max_sessions)]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                            env={**os.environ, "PYTHONUNBUFFERED": "1"},
                            start_new_session=True)
    try:
        assert proc.stdout is not None
        m = re.search(r"(http://127\.0\.0\.1:\d+/)", proc.stdout.readline())
        if m is None:
            raise RuntimeError("the explorer did not start")
        url = m.group(1)
        _get(url, 120)
        time.sleep(5)
        base = _rss_mb(proc.pid)
        peak = [base]
        stop = threading.Event()

        def sample() -> None:
            while not stop.is_set():
                peak[0] = max(peak[0], _rss_mb(proc.pid))
                time.sleep(0.1)

        threading.Thread(target=sample, daemon=True).start()
        t0 = time.monotonic()
        with ThreadPoolExecutor(loads) as pool:
            pages = [pool.submit(_get, url, 120) for _ in range(loads)]
            time.sleep(0.5)
            try:
                static = _get(url + "static/js/bokeh.min.js", 60)
            except OSError:
                static = float("inf")
            failed = sum(f.exception() is not None for f in pages)
        all_loads = time.monotonic() - t0
        time.sleep(10)
        after = _rss_mb(proc.pid)
        stop.set()
        return {"loads": loads, "failed": failed, "all_loads_s": all_loads,
                "static_s": static, "rss_base_mb": base, "rss_peak_mb": peak[0],
                "rss_after_10s_mb": after}
    finally:
        os.killpg(proc.pid, signal.SIGTERM)
        try:
            proc.communicate(timeout=60)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.communicate()


def main() -> None:
    ap = argparse.ArgumentParser(prog="python -m benchmarks.explore_load")
    ap.add_argument("--loads", type=int, default=50)
    ap.add_argument("--max-sessions", type=int, default=None)
    args = ap.parse_args()
    r = measure(args.loads, args.max_sessions)
    print(f"{r['loads']:.0f} page loads ({r['failed']:.0f} failed) in {r['all_loads_s']:.1f} s; "
          f"static file in {r['static_s']:.2f} s; resident memory {r['rss_base_mb']:.0f} MB "
          f"-> peak {r['rss_peak_mb']:.0f} MB, {r['rss_after_10s_mb']:.0f} MB 10 s later")


if __name__ == "__main__":
    main()
