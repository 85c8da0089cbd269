"""camcam.workers: jobs in forked children give the in-process results, in order, without deadlock."""

import gc
import os
import select
import sys
import threading
from pathlib import Path

import numpy as np
import pytest

from camcam.workers import ChildError, call_target, freeze_start_up, later, preload, resolve
from camcam.workers import Gate, Server

needs_fork = pytest.mark.skipif(not hasattr(os, "fork"), reason="no fork on this platform: jobs run in process")


def _boom(message):
    raise ValueError(message)


@needs_fork
def test_later_returns_the_child_result():
    a = np.arange(10.0)
    pending = later(np.cumsum, a)  # the child reads ``a`` from the memory it inherited
    assert np.array_equal(resolve(pending), np.cumsum(a))
    assert resolve(pending) is resolve(pending)  # collected once, kept


class _Unpicklable(Exception):
    def __init__(self, a, b):
        super().__init__(f"{a}/{b}")
        # a lock never pickles: without it, importing distributed (tests/dask_batch, tests/cli's batch runs)
        # installs tblib's reduce for every exception class, which rebuilds this one from its __dict__
        self.handle = threading.Lock()


def _unpicklable():
    raise _Unpicklable(1, 2)


def _bad_spec():
    from camcam.errors import SpecError

    raise SpecError("machining.stock", "blank smaller than the cam")


@needs_fork
def test_later_failure_is_the_child_exception_with_its_traceback():
    pending = later(_boom, "no such cam")
    with pytest.raises(ValueError, match="no such cam") as info:
        pending.result()
    # the child's traceback rides along as the cause
    assert isinstance(info.value.__cause__, ChildError) and "in _boom" in str(info.value.__cause__)


@needs_fork
def test_a_user_error_in_a_child_stays_a_user_error():
    from camcam.errors import SpecError

    # a bad-input error must still exit 2 with its one line, not become an internal fault
    with pytest.raises(SpecError) as info:
        later(_bad_spec).result()
    assert str(info.value) == "machining.stock: blank smaller than the cam" and info.value.path == "machining.stock"


@needs_fork
def test_an_exception_that_does_not_pickle_becomes_a_child_error():
    with pytest.raises(ChildError, match="(?s)_unpicklable failed: .*_Unpicklable: 1/2"):
        later(_unpicklable).result()


@needs_fork
def test_server_first_jobs_and_submitted_jobs_in_order():
    s = Server([("numpy:arange", (5,), {}), ("numpy:ones", (3,), {})])
    try:
        jobs = [s.submit("numpy:full", 2, k) for k in range(4)]
        # asked in reverse order: replies come in order and wait in the parent until asked for
        assert [resolve(j).tolist() for j in reversed(jobs)] == [[k, k] for k in reversed(range(4))]
        assert resolve(s.first[1]).tolist() == [1.0, 1.0, 1.0]
        assert resolve(s.first[0]).tolist() == [0, 1, 2, 3, 4]
    finally:
        s.close()


@needs_fork
def test_server_big_requests_and_replies_do_not_deadlock():
    # each request and reply is far larger than a pipe's 64 KiB buffer, and replies are not read until the end
    s = Server([("numpy:zeros", (500_000,), {})])
    big = np.arange(300_000.0)
    jobs = [s.submit("numpy:negative", big) for _ in range(6)]
    s.close()  # reads what is still due before ending the child
    assert all(np.array_equal(resolve(j), -big) for j in jobs)
    assert resolve(s.first[0]).shape == (500_000,)


def _wait_for_gate(fd):
    return os.read(fd, 1)


def _mark(fd):
    os.write(fd, b"m")


def _size(data):
    return len(data)


def _bytes(n):
    return b"r" * n


#: Generous: the marker comes within milliseconds when the server works; only a stalled server misses it.
MARK_WAIT_S = 120.0


def _marked(fd) -> bool:
    return bool(select.select([fd], [], [], MARK_WAIT_S)[0])


@needs_fork
def test_server_takes_a_big_request_while_busy_and_runs_it_without_the_parent():
    # regression: a request larger than the pipe (a pickled cam, 0.2-1.2 MB) was written only as far as
    # the pipe took it, the rest when the parent next looked; busy with the NC step, the parent left
    # the server waiting for the rest of the cam plot's request for about a second
    gate_r, gate_w = os.pipe()
    mark_r, mark_w = os.pipe()
    s = Server([(f"{__name__}:_wait_for_gate", (gate_r,), {})])
    try:
        big = s.submit(f"{__name__}:_size", b"x" * 3_000_000)  # the server is still at the gate
        s.submit(f"{__name__}:_mark", mark_w)
        os.write(gate_w, b"g")
        assert _marked(mark_r)  # both jobs ran while the parent wrote and read nothing more
        assert resolve(big) == 3_000_000
    finally:
        s.close()
        for fd in (gate_r, gate_w, mark_r, mark_w):
            os.close(fd)


@needs_fork
def test_server_goes_on_to_the_next_job_while_its_last_reply_is_unread():
    # regression: a reply larger than the pipe (a plot's PNG) held the server until the parent read it
    mark_r, mark_w = os.pipe()
    s = Server([(f"{__name__}:_bytes", (3_000_000,), {}), (f"{__name__}:_mark", (mark_w,), {})])
    try:
        assert _marked(mark_r)  # the second job ran before the parent read the first reply
        assert resolve(s.first[0]) == b"r" * 3_000_000
    finally:
        s.close()
        os.close(mark_r), os.close(mark_w)


@needs_fork
def test_server_failure_is_reported_on_its_own_job():
    s = Server()
    try:
        bad = s.submit("math:sqrt", -1.0)
        good = s.submit("math:sqrt", 4.0)
        with pytest.raises(ValueError, match="math domain error"):
            bad.result()
        assert resolve(good) == 2.0  # the server goes on after a failed job
    finally:
        s.close()


def test_call_target_imports_by_name():
    assert call_target("math:hypot", 3.0, 4.0) == 5.0


def test_without_fork_everything_runs_in_process(monkeypatch):
    monkeypatch.delattr(os, "fork")
    assert later(sum, [1, 2]) == 3
    s = Server([("math:hypot", (3.0, 4.0), {})])
    assert s.first == (5.0,)
    assert s.submit("math:sqrt", 9.0) == 3.0
    s.close()


@needs_fork
def test_parallel_map_keeps_order_and_values():
    from camcam.workers import parallel_map

    seen_pid = os.getpid()
    gates = [os.pipe(), os.pipe()]

    def f(x):
        # items 0 and 1 meet: each opens the other's gate and waits at its own (up to MARK_WAIT_S, only a stalled
        # machine waits that long), so while one process holds item 0 the other must take item 1
        if x < 2:
            os.write(gates[1 - x][1], b"g")
            select.select([gates[x][0]], [], [], MARK_WAIT_S)
        return x * x, os.getpid()

    try:
        out = parallel_map(f, range(7), workers=2)
    finally:
        for r, w in gates:
            os.close(r), os.close(w)
    # which process takes which item depends on which is free first: the results are in the items' order,
    # whatever process made them, and both processes took some
    assert [v for v, _ in out] == [x * x for x in range(7)]
    assert seen_pid in {p for _, p in out} and len({p for _, p in out}) == 2
    assert parallel_map(lambda x: x + 1, [], workers=4) == []
    assert parallel_map(lambda x: x + 1, [1], workers=4) == [2]  # one item: no child


@needs_fork
def test_parallel_map_raises_a_child_error_in_the_parent():
    from camcam.workers import parallel_map

    def f(x):
        if x == 3:
            raise ValueError("bad item 3")
        return x

    with pytest.raises(ValueError, match="bad item 3"):
        parallel_map(f, range(5), workers=2)  # item 3 is the child's (odd places)


def _children() -> set[int]:
    """Live child processes of this process (Linux /proc)."""
    out = set()
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                fields = (d / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            if int(fields[1]) == os.getpid() and fields[0] != "Z":
                out.add(int(d.name))
    return out


needs_proc = pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="counts children in /proc")


@needs_fork
@needs_proc
def test_cancel_stops_a_child_that_nobody_collects():
    import time

    before = _children()
    big = later(np.zeros, 1_000_000)  # its 8 MB reply fills the pipe: the child blocks until read
    time.sleep(0.5)  # not a timing assertion: only gives the child time to reach the full pipe
    big.cancel()  # killed and reaped: no process is left behind
    with pytest.raises(ChildError, match="cancelled"):
        big.result()
    assert _children() <= before  # the child is gone (killed and reaped, no zombie)


@needs_fork
@needs_proc
def test_a_failed_run_leaves_no_child_behind(tmp_path, monkeypatch):
    from camcam.cli import main

    def broken(*args, **kw):
        raise ZeroDivisionError("a bug after the children started")

    # the report analysis runs after the plot server, the model child and the NC children started
    monkeypatch.setattr("camcam.report.job_page.report_analysis", broken)
    before = _children()
    code = main(["run", "samples/disc-translating-roller.toml", "-o", str(tmp_path / "out")])
    assert code == 1
    assert _children() <= before  # the plot server, the model child and the NC children were stopped


# --- Prepared: imports and first jobs at once, one job later, which may fork ------------------------------------


def _forks_and_adds(a, b):
    """A job that starts a child of its own (as the run's drawing job starts the material check)."""
    child = later(np.add, a, b)
    return resolve(child), os.getpid()


@needs_fork
def test_prepared_first_jobs_then_the_job_which_may_fork():
    from camcam.workers import Prepared

    p = Prepared(["fractions"], first=[(np.arange, (4,), {}), (os.getpid, (), {})])
    job = p.submit(f"{__name__}:_forks_and_adds", np.ones(3), 2.0)
    total, where = resolve(job)
    assert np.array_equal(total, np.full(3, 3.0))
    assert np.array_equal(resolve(p.first[0]), np.arange(4))
    assert where == resolve(p.first[1]) != os.getpid()  # the job ran in the prepared child, not here


@needs_fork
def test_prepared_takes_a_big_job_while_it_imports_and_the_parent_goes_on():
    # the job's arguments (a pickled cam and program, up to about a megabyte) are far larger than a pipe;
    # the child's first job holds it at a gate, so only its reader thread can take them: submit returns
    from camcam.workers import Prepared

    gate_r, gate_w = os.pipe()
    try:
        p = Prepared(first=[(_wait_for_gate, (gate_r,), {})])
        job = p.submit(f"{__name__}:_size", b"x" * 5_000_000)  # returns: the reader took it all
        os.write(gate_w, b"g")
        assert resolve(job) == 5_000_000 and resolve(p.first[0]) == b"g"
    finally:
        for fd in (gate_r, gate_w):
            os.close(fd)


@needs_fork
def test_prepared_failures_are_reported_on_their_jobs():
    from camcam.workers import Prepared

    p = Prepared(first=[(_boom, ("first",), {})])
    job = p.submit(f"{__name__}:_boom", "the job")
    with pytest.raises(ValueError, match="the job"):
        resolve(job)
    with pytest.raises(ValueError, match="first"):
        resolve(p.first[0])
    # a module that does not import fails every job, with the import's own error
    p = Prepared(["camcam.no_such_module"], first=[(sum, ([1],), {})])
    job = p.submit("operator:add", 1, 2)
    with pytest.raises(ModuleNotFoundError, match="camcam.no_such_module"):
        resolve(job)
    with pytest.raises(ModuleNotFoundError):
        resolve(p.first[0])


@needs_fork
def test_prepared_closed_without_a_job_gives_its_first_results():
    from camcam.workers import Prepared

    p = Prepared(first=[(sum, ([1, 2],), {})])
    with pytest.raises(ChildError, match="after its job was submitted"):
        resolve(p.first[0])  # would wait for a job that never comes: refused instead
    p = Prepared(first=[(sum, ([1, 2],), {})])
    p.close()
    assert resolve(p.first[0]) == 3


def _sleeping_grandchild(fd):
    """Start a child that reports its pid and then sleeps; wait for it (the prepared child never ends alone)."""
    child = later(_report_and_sleep, fd)
    return resolve(child)


def _report_and_sleep(fd):
    import time

    os.write(fd, str(os.getpid()).encode() + b"\n")
    time.sleep(600)  # killed long before: the test ends it with the prepared child's group


@needs_fork
@needs_proc
def test_prepared_kill_ends_the_children_its_job_started():
    from camcam.workers import Prepared

    before = _children()
    pid_r, pid_w = os.pipe()
    try:
        p = Prepared()
        job = p.submit(f"{__name__}:_sleeping_grandchild", pid_w)
        grandchild = int(os.read(pid_r, 32).split(b"\n")[0])  # blocks until the grandchild runs
        p.kill()
        with pytest.raises(ChildError):
            resolve(job)
    finally:
        os.close(pid_r), os.close(pid_w)
    assert _children() <= before
    # the grandchild was sent SIGKILL with the group; it dies when the kernel next runs it, so it is waited
    # for (up to MARK_WAIT_S: only a grandchild that was never killed takes that long) and must be gone
    # or a zombie (of init's), never still running
    import time

    def alive() -> bool:
        try:
            return Path(f"/proc/{grandchild}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
        except OSError:
            return False

    deadline = time.monotonic() + MARK_WAIT_S
    while alive() and time.monotonic() < deadline:
        time.sleep(0.01)
    assert not alive()


def test_prepared_without_fork_runs_in_process(monkeypatch):
    from camcam.workers import Prepared

    monkeypatch.delattr(os, "fork")
    p = Prepared(["fractions"], first=[(sum, ([1, 2],), {})])
    assert resolve(p.first[0]) == 3
    assert resolve(p.submit("operator:mul", 3, 4)) == 12
    p.kill()


@needs_fork
def test_single_process_runs_every_job_here_and_only_within_its_block():
    """A `camcam batch` job on a Dask worker (issue 49): no fork, every kind of job in the calling process."""
    from camcam.workers import Prepared, parallel_map, single_process

    here = os.getpid()
    with single_process():
        assert later(os.getpid) == here  # a value, not a Pending: nothing was forked
        assert parallel_map(lambda _: os.getpid(), range(4), workers=2) == [here] * 4
        s = Server([("os:getpid", (), {})], gate=Gate())
        assert s.first == (here,) and s.submit("os:getpid") == here
        s.close()
        p = Prepared(["fractions"], first=[(os.getpid, (), {})])
    # a prepared child made in the block runs its job where its first jobs ran, also after the block
    assert resolve(p.first[0]) == resolve(p.submit("os:getpid")) == here
    elsewhere = later(os.getpid)
    assert resolve(elsewhere) != here  # forking again after the block


@needs_fork
def test_single_process_holds_in_its_own_thread_only():
    """A context variable: a Dask worker's task thread switches itself, not the worker's other threads."""
    from camcam.workers import single_process
    from camcam.workers.children import forking

    seen = []
    with single_process():
        worker = threading.Thread(target=lambda: seen.append(forking()))
        worker.start()
        worker.join()
        assert not forking()
    assert seen == [True] and forking()


# --- cancel: a job whose result is no longer wanted ------------------------------------------------------------


@needs_fork
@needs_proc
def test_a_cancelled_job_leaves_no_child():
    """Pending.cancel kills and reaps the child (a run that fails drops its children so): asking for the result
    afterwards says it was cancelled, and no child is left behind."""
    from camcam.workers import later

    before = _children()
    gate_r, gate_w = os.pipe()
    try:
        job = later(_wait_for_gate, gate_r)  # never let through: it runs until dropped
        job.cancel()
        with pytest.raises(ChildError, match="cancelled"):
            resolve(job)
    finally:
        os.close(gate_r), os.close(gate_w)
    assert _children() <= before


def _walked(obj) -> bool:
    """Whether this process's cyclic collector walks ``obj`` (frozen objects are in none of its generations)."""
    return any(o is obj for o in gc.get_objects())


@needs_fork
def test_a_child_leaves_its_parents_objects_out_of_its_collections():
    """The parent's objects are frozen in the child (never walked, never written to), not in the parent."""
    marker = [object()]  # a container: the collector tracks it
    frozen_before = gc.get_freeze_count()
    assert resolve(later(_walked, marker)) is False
    assert _walked(marker) and gc.get_freeze_count() == frozen_before  # the parent collects as before
    # what the child makes itself is collected as ever
    assert resolve(later(lambda: _walked([object()]))) is True


def _preload_in_child(enabled: bool):
    if not enabled:
        gc.disable()
    preload("sched")  # a module the test process has not loaded (checked by the caller)
    module_dict = sys.modules["sched"].__dict__
    return gc.isenabled(), _walked(module_dict)


@needs_fork
@pytest.mark.parametrize("enabled", [True, False])
def test_preload_freezes_what_it_loaded_and_leaves_the_collector_as_it_was(enabled):
    if "sched" in sys.modules:
        pytest.skip("sched is loaded already: preload would load nothing")
    assert resolve(later(_preload_in_child, enabled)) == (enabled, False)


def test_start_up_is_frozen_once():
    """freeze_start_up freezes what exists at its first call, and nothing made after it (a batch's later specs);
    in a fresh interpreter, as the run's own process is one."""
    import subprocess

    code = (
        "import gc\n"
        "from camcam.workers import freeze_start_up\n"
        "def walked(obj): return any(o is obj for o in gc.get_objects())\n"
        "first = [object()]\n"
        "freeze_start_up()\n"
        "second = [object()]\n"
        "freeze_start_up()\n"
        "print(walked(first), walked(second), gc.isenabled())\n"
    )
    root = Path(__file__).resolve().parents[1]
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env={**os.environ, "PYTHONPATH": str(root)})
    assert out.stdout.split() == ["False", "True", "True"]


def _wait_at(gate) -> str:
    gate.wait()
    return "went on"


@needs_fork
def test_a_gate_lets_its_waiter_go_on_once_another_process_opens_it():
    gate = Gate()
    waiter = later(_wait_at, gate)
    opener = later(gate.open)  # a child opens it: the first byte ends the wait
    assert resolve(waiter) == "went on"
    resolve(opener)
    gate.open()  # and again from here: nobody reads any more, which is fine
    gate.open()


@needs_fork
def test_a_gate_nobody_can_open_any_more_does_not_hold_its_waiter():
    """A process that would have opened it and failed (or ended) cannot leave the waiter waiting."""
    gate = Gate()
    waiter = later(_wait_at, gate)
    resolve(later(lambda: None))  # a child that ends holding the gate, never opening it
    gate.close()  # and this process lets go of it without opening it
    assert resolve(waiter) == "went on"


@needs_fork
def test_a_server_runs_its_first_jobs_at_once_and_the_submitted_ones_after_its_gate_opens():
    import time

    gate = Gate()
    s = Server([("operator:add", (1, 2), {})], gate=gate)
    job = s.submit("time:monotonic")
    assert resolve(s.first[0]) == 3  # the first jobs' replies come before the gate opens
    opened_at = time.monotonic()  # CLOCK_MONOTONIC: one clock for every process
    gate.open()
    assert resolve(job) >= opened_at  # the submitted job ran only after
    s.close()


def test_a_run_gates_its_plots_only_on_two_cores_or_fewer(monkeypatch):
    from camcam import flow as run_module

    seen = []
    monkeypatch.setattr("camcam.workers.Server", lambda first, gate=None: seen.append(gate) or "server")
    for cores, gated in ((2, True), (1, True), (3, False), (8, False)):
        monkeypatch.setattr(run_module, "_cores", lambda n=cores: n)
        seen.clear()
        server, gate = run_module.plot_server()
        assert server == "server" and (seen[0] is gate) is gated and isinstance(gate, Gate)
        gate.close()
