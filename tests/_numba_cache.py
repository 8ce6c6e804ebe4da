"""Run compiled entry points in a fresh process and report Numba's cache statistics."""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap


def fresh_process_cache_stats(module: str, calls: dict[str, str]) -> dict[str, object]:
    """Import ``module`` as ``m`` in a new interpreter, run each call (source text, e.g.
    ``"propagate(z0, t, p)"`` after ``setup`` names) and return the seconds taken and
    the cache hits and misses of each entry point named by the keys of ``calls``.

    ``calls`` maps an entry point's name in ``m`` (an attribute, or an expression on one
    such as ``BLOCKS[0]``) to the statement that runs it; a statement may use ``np`` and
    ``m``.
    """
    names = list(calls)
    body = "\n".join(calls.values())
    script = textwrap.dedent("""
        import json, time
        import numpy as np
        import {module} as m
        t0 = time.perf_counter()
    """).format(module=module) + body + textwrap.dedent(f"""
        seconds = time.perf_counter() - t0
        stats = [eval('m.' + name).stats for name in {names!r}]
        print(json.dumps({{"seconds": seconds,
                          "hits": [sum(s.cache_hits.values()) for s in stats],
                          "misses": [sum(s.cache_misses.values()) for s in stats]}}))
    """)
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         check=True, timeout=300)
    out: dict[str, object] = json.loads(run.stdout.strip().splitlines()[-1])
    return out


def fresh_process_compiles(statements: str, env: dict[str, str] | None = None) -> list[str]:
    """Run ``statements`` (source text; ``np`` is imported) in a new interpreter and
    return the qualified names of the functions Numba compiled there, in order (its
    ``numba:compile`` events: a function loaded from the on-disk cache is not compiled,
    so a process whose caches are warm returns ``[]``)."""
    script = textwrap.dedent("""
        import json
        import numpy as np
        from numba.core import event
        compiled = []

        class Count(event.Listener):
            def on_start(self, ev):
                compiled.append(ev.data["dispatcher"].py_func.__qualname__)

            def on_end(self, ev):
                pass

        event.register("numba:compile", Count())
    """) + textwrap.dedent(statements) + textwrap.dedent("""
        print(json.dumps(compiled))
    """)
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         check=True, timeout=300, env=env)
    names: list[str] = json.loads(run.stdout.strip().splitlines()[-1])
    return names
