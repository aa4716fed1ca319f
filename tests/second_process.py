"""The suite's second test process: the tests on both cores (registered by conftest.py).

A clean clone's suite is CPU-bound on 2 cores only while Numba compiles; its tests
themselves run one at a time in pytest's process, and once the kernels are compiled
the other core is idle. So, once the background jobs have filled the kernel cache
(conftest.py's lane 1), pytest's process (the *main* process) starts a second pytest
process (the *helper*) on the same test modules. The two share the modules: each
claims a module before it runs it (a file created with O_EXCL in a folder they share,
so a module is run by exactly one of them), the main process from the first module
on, the helper from the last one back, until they meet. The helper writes each of its
test reports to that folder (pytest's own serialisation, as pytest-xdist's workers
do), and the main process reports them as its own once it has run its modules: every
test is reported by the main process, passed, failed or skipped, with its output.
A module the helper claimed but did not report in full (it crashed, or was stopped)
is run by the main process after all. The tests that take the background jobs'
outcomes (conftest.background_job's consumers) run in the main process, last.

No helper where one core is all there is, under ``--pdb``, ``-s`` (the tests'
output is the terminal's), ``--collect-only``, pytest-xdist (which shares the tests
its own way), or with FLOATCOL_TEST_PROCESSES=1.
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import threading

import pytest

from kernel_claims import claim

#: the environment variable that tells the helper the shared folder
HELPER_ENV = "FLOATCOL_TEST_HELPER"
#: FLOATCOL_TEST_PROCESSES=1: no helper (the tests one after another, in one process)
PROCESSES_ENV = "FLOATCOL_TEST_PROCESSES"
#: seconds the main process waits at most for the helper to finish its modules (then
#: it stops it and runs what the helper did not report)
HELPER_TIMEOUT = 1800.0


def _module(item):
    return item.nodeid.split("::")[0]


class _Shared:
    """The folder the two processes share: claims/ (one file a module, its content the
    claimer: "main" or "helper"), items.json (the main process's tests in its order,
    and which of them stay in it), reports.jsonl (the helper's reports)."""

    def __init__(self, folder):
        self.folder = folder
        self.claims = os.path.join(folder, "claims")
        self.reports = os.path.join(folder, "reports.jsonl")

    def claim(self, module, who):
        """True where ``who`` now holds ``module`` (it was free), False where the other
        process holds it."""
        name = module.replace(os.sep, "__").replace("/", "__")
        return claim(os.path.join(self.claims, name), who)


def _chain(*iterables):
    for it in iterables:
        yield from it


def _modules(items, stay):
    """[(module, [items])] in the items' order, without the items in ``stay``."""
    out = []
    for item in items:
        if item.nodeid in stay:
            continue
        if not out or out[-1][0] != _module(item):
            out.append((_module(item), []))
        out[-1][1].append(item)
    return out


def _check(session):
    if session.shouldfail:
        raise session.Failed(session.shouldfail)
    if session.shouldstop:
        raise session.Interrupted(session.shouldstop)


def _run(session, items):
    """pytest's run of ``items`` (an iterable, read one ahead: its next item is the
    one the teardown of this one looks at), as its runtestloop's."""
    items = iter(items)
    item = next(items, None)
    while item is not None:
        nextitem = next(items, None)
        item.config.hook.pytest_runtest_protocol(item=item, nextitem=nextitem)
        _check(session)
        item = nextitem


def _claimed(shared, modules, who, others):
    """The items of the modules that ``who`` claims, in order, each claimed as it is
    reached; the items of those the other process holds go to ``others`` (a list),
    or (others None) the claims end at the first."""
    for module, items in modules:
        if shared.claim(module, who):
            yield from items
        elif others is None:
            return
        else:
            others.extend(items)


class Main:
    """The main process's side (a pytest plugin): it claims modules from the first
    on, and runs the helper (start, from conftest.py's lane of jobs)."""

    def __init__(self, config, stay):
        self.config = config
        self.stay = stay            # nodeids that always run here (the jobs' consumers)
        self.shared = _Shared(tempfile.mkdtemp(prefix="floatcol-tests-"))
        os.mkdir(self.shared.claims)
        self.proc = None
        self.log = None
        self.lock = threading.Lock()
        self.closed = False             # the session has ended: no helper now

    def start(self, session):
        """Start the helper on the session's modules (once the kernel cache is full)."""
        items = list(session.items)
        with self.lock:
            if self.closed or len(_modules(items, self.stay)) < 2:
                return
            self._start(items)

    def _start(self, items):
        with open(os.path.join(self.shared.folder, "items.json"), "w") as fh:
            json.dump({"items": [item.nodeid for item in items],
                       "stay": sorted(self.stay)}, fh)
        files = []
        for item in items:
            path = str(item.path)
            if path not in files:
                files.append(path)
        self.log = open(os.path.join(self.shared.folder, "helper.log"), "w")
        args = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                "--basetemp", os.path.join(self.shared.folder, "tmp"),
                "--rootdir", str(self.config.rootpath), *files]
        self.proc = subprocess.Popen(args, cwd=str(self.config.invocation_params.dir),
                                     env=dict(os.environ, **{HELPER_ENV: self.shared.folder}),
                                     stdin=subprocess.DEVNULL, stdout=self.log,
                                     stderr=subprocess.STDOUT)

    @pytest.hookimpl(tryfirst=True)
    def pytest_runtestloop(self, session):
        if session.testsfailed and not session.config.option.continue_on_collection_errors:
            raise session.Interrupted(f"{session.testsfailed} error(s) during collection")
        if session.config.option.collectonly:
            return True
        items = list(session.items)
        theirs = []
        consumers = [item for item in items if item.nodeid in self.stay]
        # (a module is claimed as the run reaches it: the helper, which starts later and
        # goes from the last one back, takes those it has not reached)
        own = _claimed(self.shared, _modules(items, self.stay), "main", theirs)
        _run(session, _chain(own, consumers))
        self._report_theirs(session, theirs)
        return True

    def _report_theirs(self, session, theirs):
        """The helper's reports of ``theirs`` as this session's, after waiting for it
        to end; whatever it did not report in full runs here."""
        if not theirs:
            return
        if self.proc is not None:
            try:
                self.proc.wait(timeout=HELPER_TIMEOUT)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        reports = {}
        if os.path.exists(self.shared.reports):
            with open(self.shared.reports) as fh:
                for line in fh:
                    try:
                        entry = json.loads(line)
                    except ValueError:          # (a line cut short by a crash)
                        continue
                    reports.setdefault(entry["nodeid"], []).append(entry["report"])
        hook = self.config.hook
        orphans = []
        for item in theirs:
            got = reports.get(item.nodeid, [])
            if not got or got[-1].get("when") != "teardown":
                orphans.append(item)
                continue
            item.ihook.pytest_runtest_logstart(nodeid=item.nodeid, location=item.location)
            for data in got:
                report = hook.pytest_report_from_serializable(config=self.config, data=data)
                if isinstance(report.longrepr, list):
                    # (a skip's (path, line, reason): a list once through JSON, which
                    # pytest's summary of skips does not take)
                    report.longrepr = tuple(report.longrepr)
                item.ihook.pytest_runtest_logreport(report=report)
            item.ihook.pytest_runtest_logfinish(nodeid=item.nodeid, location=item.location)
            _check(session)
        _run(session, orphans)

    def pytest_sessionfinish(self, session):
        with self.lock:
            self.closed = True
        if self.proc is not None and self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()
        if self.log is not None:
            self.log.close()
        shutil.rmtree(self.shared.folder, ignore_errors=True)


class Helper:
    """The helper's side (a pytest plugin): the main process's tests, its modules
    claimed from the last one back; each report written to the shared folder."""

    def __init__(self, folder, config):
        self.config = config
        self.shared = _Shared(folder)
        with open(os.path.join(folder, "items.json")) as fh:
            spec = json.load(fh)
        self.order = spec["items"]
        self.stay = set(spec["stay"])
        self.out = open(self.shared.reports, "a")

    @pytest.hookimpl(tryfirst=True)
    def pytest_runtestloop(self, session):
        if session.testsfailed:
            return True                         # (a collection error: the main reports it)
        by_id = {item.nodeid: item for item in session.items}
        items = [by_id[n] for n in self.order if n in by_id]
        _run(session, _claimed(self.shared, reversed(_modules(items, self.stay)), "helper",
                               None))
        return True

    def pytest_runtest_logreport(self, report):
        data = self.config.hook.pytest_report_to_serializable(config=self.config,
                                                              report=report)
        self.out.write(json.dumps({"nodeid": report.nodeid, "report": data}) + "\n")
        self.out.flush()

    def pytest_sessionfinish(self, session):
        self.out.close()


def wanted(config):
    """Whether this session shares its tests with a helper."""
    opt = config.option
    xdist = getattr(opt, "numprocesses", None) or getattr(opt, "dist", "no") != "no" \
        or os.environ.get("PYTEST_XDIST_WORKER")
    return (os.environ.get(PROCESSES_ENV, "") != "1" and (os.cpu_count() or 1) >= 2
            and not getattr(opt, "usepdb", False) and getattr(opt, "capture", "fd") != "no"
            and not opt.collectonly and not xdist)
