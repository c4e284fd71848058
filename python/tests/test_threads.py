"""Concurrent calls from Python threads: models built and evaluated at once give what one thread gives, and the
GIL is released while the library works."""

import os
import threading
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import surfscatter as ss

KC = dict(sigma=0.04, corr_length=1.5, gamma=2.5)


def queries(seed, n=20000):
    rng = np.random.default_rng(seed)
    wi = ss.direction(rng.uniform(0, 80, n), rng.uniform(0, 360, n))
    wo = ss.direction(rng.uniform(0, 89, n), rng.uniform(0, 360, n))
    return wi, wo, rng.uniform(400, 700, n), rng.random((n, 3))


def work(model, seed):
    wi, wo, lam, u = queries(seed)
    return model.eval(wi, wo, lam), model.pdf(wi, wo, lam), model.sample(wi, lam, u)[1]


def test_concurrent_calls_on_shared_and_own_models_equal_sequential_ones():
    shared_model = ss.bsdf("ghs", material="Au", **KC)
    expected = [work(shared_model, seed) for seed in range(8)]
    with ThreadPoolExecutor(max_workers=8) as pool:
        on_shared = list(pool.map(lambda seed: work(shared_model, seed), range(8)))
        # Each thread builds its own models of other surfaces at the same time (tables built concurrently).
        built = list(pool.map(lambda g: ss.bsdf("ghs", material="Ag", sigma=0.03, corr_length=1.0, gamma=g),
                              [2.2, 2.2, 3.4, 3.4]))
    for got, want in zip(on_shared, expected):
        for a, b in zip(got, want):
            np.testing.assert_array_equal(a, b)
    wi, wo, lam, _ = queries(99, 500)
    np.testing.assert_array_equal(built[0].eval(wi, wo, lam), built[1].eval(wi, wo, lam))
    np.testing.assert_array_equal(built[2].eval(wi, wo, lam), built[3].eval(wi, wo, lam))
    fresh = ss.bsdf("ghs", material="Ag", sigma=0.03, corr_length=1.0, gamma=3.4)
    np.testing.assert_array_equal(fresh.eval(wi, wo, lam), built[2].eval(wi, wo, lam))


def test_statistics_and_materials_from_many_threads():
    kc = ss.KCorrelation(**KC)
    au = ss.Conductor("Au")
    theta = np.linspace(0, 85, 200)
    want = (kc.relevant_roughness(theta[:, None], [450.0, 650.0]), au.reflectance(np.cos(np.radians(theta)), 500.0))
    with ThreadPoolExecutor(max_workers=6) as pool:
        got = list(pool.map(lambda _: (kc.relevant_roughness(theta[:, None], [450.0, 650.0]),
                                       au.reflectance(np.cos(np.radians(theta)), 500.0)), range(12)))
    for pair in got:
        np.testing.assert_array_equal(pair[0], want[0])
        np.testing.assert_array_equal(pair[1], want[1])


def test_the_gil_is_released_during_eval():
    model = ss.bsdf("ghs", material="Au", **KC)
    wi, wo, lam, _ = queries(1, 300000)
    span = {}

    def evaluate():
        span["start"] = time.perf_counter()
        model.eval(wi, wo, lam)
        span["end"] = time.perf_counter()

    worker = threading.Thread(target=evaluate)
    ticks = []
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
    worker.join()
    # With the GIL held for the whole call this thread could not run between start and end.
    inside = [t for t in ticks if span["start"] < t < span["end"]]
    assert span["end"] - span["start"] > 0.01
    assert len(inside) > 100


def thread_cpu_seconds():
    """CPU seconds (user + system) so far of every thread of this process, by thread id (/proc/self/task)."""
    seconds = {}
    for task in os.listdir("/proc/self/task"):
        try:
            with open(f"/proc/self/task/{task}/stat") as stat:
                fields = stat.read().rsplit(")", 1)[1].split()  # fields 3.. of proc(5), after the command name
        except FileNotFoundError:  # the thread ended meanwhile
            continue
        seconds[int(task)] = (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")  # utime, stime
    return seconds


@pytest.mark.skipif(len(os.sched_getaffinity(0)) < 2, reason="a single core: nothing can run in parallel")
def test_eval_of_a_large_array_is_shared_among_threads():
    model = ss.bsdf("ghs", material="Au", **KC)
    wi, wo, lam, _ = queries(3, 200000)
    model.eval(wi[:8], wo[:8], lam[:8])  # tables loaded before measuring
    caller = threading.get_native_id()
    before = thread_cpu_seconds()
    start = time.process_time()
    while time.process_time() - start < 1.0:  # a second of CPU, far above the 10 ms clock tick
        model.eval(wi, wo, lam)
    after = thread_cpu_seconds()
    own = after[caller] - before[caller]
    others = sum(seconds - before.get(thread, 0.0) for thread, seconds in after.items() if thread != caller)
    # TBB's workers took a share of the loop (on an idle 2-core machine about half; under load less, never none).
    assert others > 0.1 * (own + others), (own, others)


def test_thread_limit_is_applied_and_restored():
    default = ss.max_threads()
    try:
        ss.set_max_threads(1)
        assert ss.max_threads() == 1
        model = ss.bsdf("ggx_stats", alpha=0.3)
        wi, wo, lam, _ = queries(2, 1000)
        single = model.eval(wi, wo, lam)
        ss.set_max_threads(0)
        np.testing.assert_array_equal(model.eval(wi, wo, lam), single)
    finally:
        ss.set_max_threads(0)
    assert ss.max_threads() == default
    with pytest.raises(ss.Error, match=r"threads must be between 1 and 256 \(or 0 for all cores\), got -1"):
        ss.set_max_threads(-1)
