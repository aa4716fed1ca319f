"""The suite's second test process (second_process.py), on a suite of its own: every
test runs once and is reported once, by the main process, with its outcome and
output, whichever process ran it; a module the helper did not finish (it died) runs in
the main process; the tests that stay (the jobs' consumers) run there."""
import os
import re
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))

CONFTEST = f"""
import os, sys
sys.path.insert(0, {HERE!r})
import second_process

_MAIN = []


def pytest_configure(config):
    if os.environ.get(second_process.HELPER_ENV):
        config.pluginmanager.register(
            second_process.Helper(os.environ[second_process.HELPER_ENV], config), "floatcol-helper")
    elif second_process.wanted(config):
        _MAIN.append(second_process.Main(config, set()))
        config.pluginmanager.register(_MAIN[0], "floatcol-main")


def pytest_collection_modifyitems(items):
    if _MAIN:
        _MAIN[0].stay = {{item.nodeid for item in items if "stays" in item.name}}


def pytest_collection_finish(session):
    if _MAIN:
        _MAIN[0].start(session)
"""

LOG = """
import os, time


def ran(name):
    with open(os.environ["RAN_LOG"], "a") as fh:
        fh.write(f"{name} {os.getpid()} {'helper' if os.environ.get('FLOATCOL_TEST_HELPER') else 'main'}\\n")
"""

MODULES = {
    # the main process's first module waits until the helper has claimed a module, so
    # that both run tests whatever the machine's speed
    "test_a.py": """
from ranlog import ran
import glob, os, time, pytest


def test_waits_for_the_helper(tmp_path):
    ran("a1")
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        if any(open(p).read() == "helper"
               for p in glob.glob(os.path.join(os.environ["CLAIMS_GLOB"], "claims", "*"))):
            return
        time.sleep(0.05)
    raise AssertionError("the helper claimed no module")


def test_fails():
    ran("a2")
    print("output of a2")
    assert 1 + 1 == 3, "a2-fails"


def test_skips():
    ran("a3")
    pytest.skip("a3-skips")
""",
    "test_b.py": """
from ranlog import ran


def test_b1():
    ran("b1")


def test_b2_stays():
    ran("b2")
""",
    "test_c.py": """
from ranlog import ran


def test_c1():
    ran("c1")
""",
    "test_d.py": """
from ranlog import ran


def test_d1():
    ran("d1")
    print("output of d1")
    assert "d1" == "D1", "d1-fails"
""",
    # the helper's first module: it dies in its second test
    "test_e.py": """
import os
import pytest
from ranlog import ran


def test_e0_skips():
    ran("e0")
    pytest.skip("e0-skips")


def test_e1():
    ran("e1")


def test_e2_kills_the_helper():
    ran("e2")
    if os.environ.get("FLOATCOL_TEST_HELPER"):
        os._exit(3)
""",
}


@pytest.mark.skipif((os.cpu_count() or 1) < 2,
                    reason="one core: no second test process (second_process.wanted)")
def test_two_processes_report_every_test_once(tmp_path):
    suite = tmp_path / "suite"
    suite.mkdir()
    (suite / "conftest.py").write_text(CONFTEST)
    (suite / "ranlog.py").write_text(LOG)
    for name, text in MODULES.items():
        (suite / name).write_text(text)
    log = tmp_path / "ran.log"
    env = dict(os.environ, RAN_LOG=str(log), TMPDIR=str(tmp_path),
               CLAIMS_GLOB=str(tmp_path / "floatcol-tests-*"))
    for name in ("FLOATCOL_TEST_HELPER", "FLOATCOL_TEST_PROCESSES", "PYTEST_ADDOPTS"):
        env.pop(name, None)             # (this suite's, not the small one's)
    out = subprocess.run([sys.executable, "-m", "pytest", "-rA", "-p", "no:cacheprovider",
                          str(suite)], cwd=str(suite), env=env,
                         capture_output=True, text=True, timeout=300)
    text = out.stdout + out.stderr
    assert out.returncode == 1, text             # (two tests fail)
    # every test reported once, with its outcome
    lines = re.findall(r"^(PASSED|FAILED|ERROR) (\S+)", text, re.M)
    outcomes = {nodeid: outcome for outcome, nodeid in lines}
    assert len(outcomes) == len(lines), text
    assert outcomes == {
        "test_a.py::test_waits_for_the_helper": "PASSED", "test_a.py::test_fails": "FAILED",
        "test_b.py::test_b1": "PASSED", "test_b.py::test_b2_stays": "PASSED",
        "test_c.py::test_c1": "PASSED", "test_d.py::test_d1": "FAILED",
        "test_e.py::test_e1": "PASSED", "test_e.py::test_e2_kills_the_helper": "PASSED"}, text
    assert re.search(r"SKIPPED \[1\] \S*test_a\.py:\d+: a3-skips", text), text
    assert re.search(r"SKIPPED \[1\] \S*test_e\.py:\d+: e0-skips", text), text
    assert re.search(r"2 failed, 6 passed, 2 skipped", text), text
    # the failures' tracebacks and output, whichever process ran them
    for words in ("a2-fails", "output of a2", "d1-fails", "output of d1"):
        assert words in text, text
    ran = [line.split() for line in log.read_text().splitlines()]
    by_name = {}
    for name, pid, who in ran:
        by_name.setdefault(name, []).append(who)
    # the helper ran e0 and e1 and died in e2, which the main process then ran; the test that
    # stays ran in the main process; every other test ran once
    assert by_name.pop("e0") == ["helper"], ran
    assert by_name.pop("e1") == ["helper"], ran
    assert by_name.pop("e2") == ["helper", "main"], ran
    assert by_name.pop("b2") == ["main"], ran
    assert all(len(whos) == 1 for whos in by_name.values()), ran
    assert sorted(by_name) == ["a1", "a2", "a3", "b1", "c1", "d1"], ran
    assert len({pid for _, pid, who in ran if who == "helper"}) == 1, ran
