"""The workbench's time per change: `propbet serve` on the default case, a slider moved N times
(each change a POST /api/evaluate with a new pitch offset), the round trip timed; beside it, the
command line's `propbet compare --effect` of the same state (what a user did before). Target
(issue 79): the server's median time per change at most 20 ms on 2 threads."""

import json
import statistics
import subprocess
import sys
import time
import urllib.request

N = int(sys.argv[1]) if len(sys.argv) > 1 else 50
binary = "target/release/propbet"
proc = subprocess.Popen([binary, "--threads", "2", "serve", "props/apcsp_10x7", "--save-to", "/tmp"],
                        stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
url = proc.stdout.readline().strip()
base, token = url.split("/?token=")


def evaluate(effects):
    req = urllib.request.Request(base + "/api/evaluate", data=json.dumps({"effects": effects}).encode(),
                                 headers={"X-Propbet-Token": token, "Content-Type": "application/json"})
    t0 = time.perf_counter()
    body = urllib.request.urlopen(req).read()
    return time.perf_counter() - t0, json.loads(body)


evaluate([])
server = []
for k in range(N):
    deg = -1.5 + 3.0 * k / max(N - 1, 1)
    dt, _ = evaluate([f"pitch-offset:deg={deg:.3f}"])
    server.append(dt)
proc.terminate()
cli = []
for k in range(max(3, N // 10)):
    t0 = time.perf_counter()
    subprocess.run([binary, "--threads", "2", "run", "props/apcsp_10x7", "-o", f"/tmp/serve_bench_run_{k}", "--quiet"],
                   capture_output=True)
    cli.append(time.perf_counter() - t0)
med = statistics.median(server)
print(f"workbench: median {1000 * med:.1f} ms per change over {N} changes "
      f"(p90 {1000 * sorted(server)[int(0.9 * N)]:.1f} ms; target 20 ms)")
print(f"command line: `propbet run` of the same case {statistics.median(cli):.2f} s median "
      f"({statistics.median(cli) / med:.0f} times the workbench's change)")
