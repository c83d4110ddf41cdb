"""Ctrl-C from a second thread stops a run at a chunk boundary; the state is resumable and the resumed result
equals an uninterrupted run.  Progress callbacks do not make memory grow."""
import _thread
import threading
import time

import numpy as np
import pytest

import archipelago as ap

P = dict(K=0.1, T=400000, M=16, subsets=4, seed=3, longestKept=5)


def test_keyboard_interrupt_stops_at_chunk_boundary_and_resumes(tmp_path):
    run = ap.start(**P)
    seen = []

    def progress(d):
        seen.append(d["blocks_done"])
        if len(seen) == 3:  # interrupt from another thread, as Ctrl-C would
            threading.Thread(target=_thread.interrupt_main).start()
            time.sleep(0.05)

    ck = tmp_path / "ck.json"
    with pytest.raises(KeyboardInterrupt):
        run.advance(threads=2, progress=progress, max_chunk=2000, checkpoint=ck)
    assert not run.finished
    assert 0 < run.blocks_done < P["T"]
    assert run.blocks_done == seen[-1]  # the chunk boundary the run stopped at
    states = run.orbit_states()
    assert np.all(states[:, 2] == run.blocks_done)
    # Resume from the checkpoint file and from the object: both equal an uninterrupted run.
    resumed = ap.load(ck)
    assert resumed.blocks_done == run.blocks_done
    resumed.advance(threads=2)
    run.advance(threads=1)
    whole = ap.start(**P)
    whole.advance(threads=2)
    for r in (resumed, run):
        assert np.array_equal(r.orbit_states(), whole.orbit_states())
        assert np.array_equal(r.histogram()["counts"], whole.histogram()["counts"])
        assert np.array_equal(r.longest()["length_steps"], whole.longest()["length_steps"])


def test_exception_in_callback_stops_cleanly():
    run = ap.start(**dict(P, T=20000))

    seen = []

    def progress(d):
        seen.append(d["blocks_done"])
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        run.advance(progress=progress, max_chunk=1000)
    assert run.blocks_done == seen[0] and len(seen) == 1
    run.advance()
    assert run.finished


def rss_kib():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


def test_memory_does_not_grow_with_progress_callbacks():
    calls = [0]

    def progress(d):
        calls[0] += 1

    def run_with(blocks):
        run = ap.start(K=0.1, T=blocks, M=1, subsets=1, q=1, longestKept=1)
        run.advance(threads=1, progress=progress, max_chunk=1)
        return run

    run_with(2000)  # warm up: allocator pools, imports
    before = rss_kib()
    run_with(20000)
    middle = rss_kib()
    run_with(200000)
    after = rss_kib()
    assert calls[0] >= 222000
    # 180000 more callbacks: a leak of even 16 bytes each would add 2.8 MB.
    assert after - middle < 1024, (before, middle, after)


def test_run_is_not_touched_while_another_thread_advances_it():
    run = ap.start(**dict(P, T=200000))
    errors = []

    def progress(d):
        # The callback runs while the run is busy: reading it must be refused, not race.
        try:
            run.orbit_states()
        except ValueError as e:
            errors.append(str(e))
        raise StopIteration

    with pytest.raises(StopIteration):
        run.advance(progress=progress, max_chunk=1000)
    assert errors == ["this run is being advanced (advance() is running)"]
    assert run.orbit_states().shape == (16, 9)  # usable again after the stop


# Issue #23, finding 7: Ctrl-C was ignored by long calls that do not report progress: stochastic_area and
# portrait ran on for minutes, periodic_orbit(period=10**5) raised only after its whole search (~45 s).
@pytest.mark.parametrize("call", [
    lambda: ap.stochastic_area(iterations=2 ** 50),
    lambda: ap.portrait(points=2 ** 49, width=64, height=64),
    lambda: ap.periodic_orbit(0.1, 100000, 0.0358, 0.034),
], ids=["stochastic_area", "portrait", "periodic_orbit"])
def test_long_calls_stop_on_ctrl_c_Issue23(call):
    timer = threading.Timer(0.3, _thread.interrupt_main)
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        call()
    elapsed = time.monotonic() - start
    timer.cancel()
    assert elapsed < 10, f"stopped {elapsed:.1f} s after the call began (Ctrl-C at 0.3 s)"


def test_an_interrupted_call_leaves_the_module_usable():
    timer = threading.Timer(0.2, _thread.interrupt_main)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        ap.portrait(points=2 ** 49, width=64, height=64)
    small = ap.portrait(points=100000, width=32, height=32)
    assert small["points_iterated"] >= 100000
