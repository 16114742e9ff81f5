#!/usr/bin/python3
"""tessera.batch on a real Dask cluster on 127.0.0.1 (a `dask scheduler` and two `dask worker`
processes, started and stopped here): the report equals `tessera check`'s (cases, order, verdicts,
image bytes); a worker killed mid-suite loses nothing; a case that crashes its workers is reported as
an error, not retried forever. Usage: batch_test.py TESSERA_BIN SOURCE_DIR (PYTHONPATH has the package).
"""
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

TESSERA, SOURCE = sys.argv[1], sys.argv[2]
SUITE = os.path.join(SOURCE, "golden", "suites", "views.json")
PY = "/usr/bin/python3"
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def summary(report):
    with open(os.path.join(report, "summary.json")) as f:
        return json.load(f)


def comparable(cases):
    return [{k: v for k, v in c.items() if k != "seconds"} for c in cases]


def batch(args, env=None, timeout=240):
    return subprocess.run([PY, "-m", "tessera.batch", SUITE] + args, env=env, capture_output=True, text=True,
                          timeout=timeout)


tmp = tempfile.mkdtemp(prefix="tessera-batch-test-")
procs = []
try:
    reference = os.path.join(tmp, "check")
    r = subprocess.run([TESSERA, "-q", "check", SUITE, "-o", reference], capture_output=True, text=True)
    check(r.returncode == 0, "tessera check passes its own suite")
    ref = summary(reference)

    port = free_port()
    address = "tcp://127.0.0.1:%d" % port
    env = dict(os.environ, DASK_DISTRIBUTED__SCHEDULER__ALLOWED_FAILURES="1",
               DASK_DISTRIBUTED__SCHEDULER__WORKER_SATURATION="1.0", TESSERA_BATCH_DELAY="0.6")
    procs.append(subprocess.Popen(["dask", "scheduler", "--host", "127.0.0.1", "--port", str(port),
                                   "--no-dashboard"], env=env, stdout=subprocess.DEVNULL,
                                  stderr=subprocess.DEVNULL, start_new_session=True))
    for _ in range(2):
        procs.append(subprocess.Popen(["dask", "worker", address, "--nthreads", "1", "--nworkers", "1",
                                       "--host", "127.0.0.1", "--no-dashboard"], env=env,
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                      start_new_session=True))

    # 1. Two workers: the same report as tessera check.
    out = os.path.join(tmp, "dask")
    r = batch(["--scheduler", address, "-o", out, "-q"])
    check(r.returncode == 0, "batch on the scheduler exits 0 (stderr: %s)" % r.stderr.strip()[-300:])
    got = summary(out)
    check(comparable(got["cases"]) == comparable(ref["cases"]), "the cases, their order and verdicts equal check's")
    same_bytes = all(open(os.path.join(out, c["new_image"]), "rb").read() ==
                     open(os.path.join(reference, c["new_image"]), "rb").read() for c in ref["cases"])
    check(same_bytes, "every image has the bytes tessera check wrote")
    check(os.path.exists(os.path.join(out, "report.html")) and os.path.exists(os.path.join(out, "junit.xml")),
          "report.html and junit.xml written")

    # 2. A worker killed mid-suite: its task runs elsewhere, the report is complete.
    out2 = os.path.join(tmp, "killed")
    run = subprocess.Popen([PY, "-m", "tessera.batch", SUITE, "--scheduler", address, "-o", out2, "-q"],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(2.0)  # tasks wait 0.6 s each: both workers are busy
    os.killpg(procs[1].pid, signal.SIGKILL)
    stdout, stderr = run.communicate(timeout=240)
    check(run.returncode == 0, "batch with a killed worker exits 0 (stderr: %s)" % stderr.strip()[-300:])
    check(comparable(summary(out2)["cases"]) == comparable(ref["cases"]), "and its report is complete and equal")

    # 3. A case that crashes every worker that runs it: one error, the rest pass, the run ends.
    out3 = os.path.join(tmp, "crash")
    env3 = dict(os.environ, TESSERA_BATCH_CRASH_CASE="frog-pn-factors")
    r = batch(["--local", "2", "-o", out3, "-q"], env=env3)
    check(r.returncode == 1, "batch with a crashing case exits 1")
    s3 = summary(out3)
    status = {c["name"]: c["status"] for c in s3["cases"]}
    check(status.get("frog-pn-factors") == "error", "the crashing case is an error: %s" % status)
    check(sum(v == "pass" for v in status.values()) == 4, "the other four pass")
    check(len(s3["cases"]) == 5, "all five cases are in the report")

    # 4. A bad suite: one line, exit 1, before any cluster.
    bad = os.path.join(tmp, "bad.json")
    with open(bad, "w") as f:
        f.write('{"tessera_suite": 1, "cases": []}')
    r = subprocess.run([PY, "-m", "tessera.batch", bad, "--local", "1"], capture_output=True, text=True)
    check(r.returncode == 1 and r.stderr.count("\n") == 1 and "cases" in r.stderr,
          "a bad suite: one line, exit 1 (%s)" % r.stderr.strip())
finally:
    for p in procs:
        try:
            os.killpg(p.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
    for p in procs:
        p.wait()
    shutil.rmtree(tmp, ignore_errors=True)

sys.exit(1 if failures else 0)
