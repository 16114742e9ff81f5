"""python3 -m tessera.batch SUITE (--scheduler tcp://HOST:8786 | --local N) [-o REPORT] [--threads T]

Runs a golden suite's cases (see `tessera check`) as Dask tasks and writes the report `tessera check`
writes -- the same cases in the same order, the same images, the same verdicts -- whatever the number
of workers. Each task is a pure function of (the case's scene file, its compare and checks, its golden,
the Tessera version): its key is their hash, so a re-run of an unchanged case is the same task. Tasks
render with a fixed thread count (--threads, default 1), so one worker process per core is the layout.

Workers read the suite, its scenes, assets and goldens at the paths the client sees (a shared or
replicated file system); results (the JSON of each case and its images) come back through Dask, and only
the client writes the report.

Faults: a worker that dies mid-task loses nothing -- Dask reschedules the task on another worker. A case
that kills workers is reported as an error once the scheduler gives up on it
(distributed.scheduler.allowed-failures; --local sets it to 1), not retried forever. The scheduler also
charges a death to the cases merely queued on that worker, so each case that ends in KilledWorker is run
once more alone at the end: the culprit kills again and is the error, an innocent case passes.

Fault injection for tests only: TESSERA_BATCH_CRASH_CASE=NAME makes the worker running that case exit;
TESSERA_BATCH_DELAY=SECONDS makes every task wait first.
"""
import argparse
import hashlib
import json
import os
import shutil
import sys
import tempfile
import time

from . import _tessera


def case_task(suite, name, key, threads):
    """Runs one case in a private directory; returns (its result, {relative path: bytes})."""
    del key  # the task's identity (see case_key); the body reads the files it names
    if os.environ.get("TESSERA_BATCH_CRASH_CASE") == name:
        os._exit(3)
    delay = float(os.environ.get("TESSERA_BATCH_DELAY", "0") or 0)
    if delay > 0:
        time.sleep(delay)
    with tempfile.TemporaryDirectory(prefix="tessera-batch-") as tmp:
        result = json.loads(_tessera.run_case(suite, name, tmp, threads))
        files = {}
        for field in ("new_image", "diff_image"):
            rel = result.get(field, "")
            if rel:
                with open(os.path.join(tmp, rel), "rb") as f:
                    files[rel] = f.read()
        return result, files


def _digest_file(h, path):
    h.update(path.encode())
    try:
        with open(path, "rb") as f:
            h.update(f.read())
    except OSError:
        h.update(b"<missing>")


def case_key(suite_path, name):
    """A content hash of everything the case's result depends on."""
    with open(suite_path, "rb") as f:
        suite = json.load(f)
    spec = next(c for c in suite["cases"] if c.get("name") == name)
    base = os.path.dirname(os.path.abspath(suite_path))
    golden = os.path.join(base, suite.get("golden", suite.get("name", "")))
    h = hashlib.sha1()
    h.update(_tessera.__version__.encode())
    h.update(json.dumps(spec, sort_keys=True).encode())
    scene = os.path.join(base, spec["scene"])
    _digest_file(h, scene)
    try:
        with open(scene, "rb") as f:
            scene_json = json.load(f)
        sdir = os.path.dirname(scene)
        for p in [scene_json.get("asset", "")] + [scene_json.get("displacement", {}).get("map", "")]:
            if p:
                _digest_file(h, os.path.join(sdir, p))
    except (OSError, ValueError):
        pass
    for ext in (".png", ".json"):
        _digest_file(h, os.path.join(golden, name + ext))
    return "tessera-case-%s-%s" % (name, h.hexdigest())


def _error(name, names, what, message):
    return {"name": name, "status": "error", "message": "%s: %s" % (what, message), "new_image": "",
            "golden_image": "", "diff_image": "", "checks": {}, "command": "", "seconds": 0.0,
            "index": names.index(name), "report_golden": False}


def _outcome(future, name, names):
    """(result, files) of a finished task -- an error case if it raised -- or None if it ended in KilledWorker."""
    try:
        return future.result()
    except Exception as e:  # KilledWorker, or an exception the task raised
        if type(e).__name__ == "KilledWorker":
            return None
        return _error(name, names, type(e).__name__, str(e)), {}


def _keep(outcome, name, names, report, log, where):
    """Writes a case's images into the report and returns its result."""
    result, files = outcome
    for rel, data in files.items():
        path = os.path.join(report, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "wb") as f:
            f.write(data)
    if result.get("report_golden"):
        dest = os.path.join(report, "golden", name + ".png")
        os.makedirs(os.path.dirname(dest), exist_ok=True)
        shutil.copyfile(result["golden_image"], dest)
    log("%s %s: %s%s" % (where, name, result["status"], " (%s)" % result["message"] if result["message"] else ""))
    return result


def run(suite, client, report, threads, log):
    names = _tessera.suite_cases(suite)
    suite_abs = os.path.abspath(suite)
    futures = {}
    for name in names:
        key = case_key(suite_abs, name)
        futures[client.submit(case_task, suite_abs, name, key, threads, key=key, pure=False, retries=0)] = name
    from distributed import as_completed  # noqa: E402  (imported where Dask is needed)

    cases = {}
    done = 0
    suspects = []  # cases whose worker died while they ran or waited there
    for future in as_completed(list(futures)):
        name = futures[future]
        done += 1
        outcome = _outcome(future, name, names)
        if outcome is None:
            suspects.append(name)
            log("[%d/%d] %s: its worker died; re-run alone at the end" % (done, len(names), name))
            continue
        cases[name] = _keep(outcome, name, names, report, log, "[%d/%d]" % (done, len(names)))
    # A case queued on a worker that another case killed is charged with that death too, and with
    # allowed-failures = 1 two such deaths give it KilledWorker although it never ran. Re-running each
    # suspect alone, with nothing else in flight, tells the culprit (it kills again) from the innocent.
    for name in suspects:
        key = case_key(suite_abs, name) + "-alone"
        future = client.submit(case_task, suite_abs, name, key, threads, key=key, pure=False, retries=0)
        outcome = _outcome(future, name, names)
        if outcome is None:
            outcome = _error(name, names, "KilledWorker", "crashed its workers, also when run alone"), {}
        cases[name] = _keep(outcome, name, names, report, log, "[alone]")
    ordered = sorted(cases.values(), key=lambda c: c["index"])
    summary = {"suite": _tessera.suite_name(suite), "suite_path": suite_abs, "shard": "dask",
               "cases": ordered, "seconds": sum(c["seconds"] for c in ordered)}
    _tessera.write_check_reports(json.dumps(summary), report)
    with open(os.path.join(report, "summary.json")) as f:
        return json.load(f)


def main(argv=None):
    p = argparse.ArgumentParser(prog="python3 -m tessera.batch", description=__doc__.split("\n\n")[1])
    p.add_argument("suite", help="the suite file (as for tessera check)")
    where = p.add_mutually_exclusive_group(required=True)
    where.add_argument("--scheduler", help="a Dask scheduler's address, tcp://HOST:PORT")
    where.add_argument("--local", type=int, metavar="N", help="start a LocalCluster of N worker processes")
    p.add_argument("-o", "--report", default="check-report", help="the report directory (default: check-report)")
    p.add_argument("--threads", type=int, default=1, help="render threads per task (default 1)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress on stderr")
    p.add_argument("--json", action="store_true", help="print the summary as JSON")
    a = p.parse_args(argv)
    log = (lambda _: None) if a.quiet else (lambda m: print("tessera.batch: " + m, file=sys.stderr, flush=True))
    if a.local is not None and not 1 <= a.local <= 256:
        p.error("--local: expected 1..256 workers")
    if a.threads < 0:
        p.error("--threads: expected >= 0")
    try:
        _tessera.suite_cases(a.suite)  # a bad suite: one line, before any cluster starts
    except (_tessera.InputError, _tessera.UsageError) as e:
        print("tessera.batch: %s" % e, file=sys.stderr)
        return 1
    import dask
    from distributed import Client, LocalCluster

    os.makedirs(a.report, exist_ok=True)
    if a.local is not None:
        # worker-saturation 1: a worker holds only the task it runs, so when a case kills its worker
        # no innocent case queued there is counted against allowed-failures with it.
        with dask.config.set({"distributed.scheduler.allowed-failures": 1,
                              "distributed.scheduler.worker-saturation": 1.0}):
            with LocalCluster(n_workers=a.local, threads_per_worker=1, processes=True, host="127.0.0.1",
                              dashboard_address=None) as cluster, Client(cluster) as client:
                summary = run(a.suite, client, a.report, a.threads, log)
    else:
        with Client(a.scheduler, timeout="30s") as client:
            summary = run(a.suite, client, a.report, a.threads, log)
    n = summary["counts"]
    bad = n["fail"] + n["new"] + n["error"]
    if a.json:
        print(json.dumps(summary))
    else:
        print(", ".join("%d %s" % (v, k) for k, v in n.items() if v) + " -> " + os.path.join(a.report, "report.html"))
    return 0 if bad == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
