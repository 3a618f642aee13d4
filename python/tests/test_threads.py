"""Threads: the GIL is released during detection, concurrent calls agree
with serial ones, and a Detector shared by two threads is guarded."""

import threading
import time

import numpy as np
import pytest

import aaglsd


def bits(a):
    return a.view(np.uint32)


@pytest.fixture(scope="module")
def images(castle):
    """Eight different 320x240 images: castle1 shifted, flipped, noised."""
    rng = np.random.default_rng(5)
    out = []
    for i in range(8):
        img = np.roll(castle, 13 * i, axis=1)
        if i % 2:
            img = img[::-1].copy()
        noise = rng.integers(0, 6, img.shape, dtype=np.uint8)
        out.append(np.ascontiguousarray(img // 2 + noise + 60))
    return out


def test_eight_threads_agree_with_one(images):
    serial = [bits(aaglsd.detect(img, "paper")).copy() for img in images]
    assert len({s.tobytes() for s in serial}) == 8  # really eight different answers
    results = {}
    errors = []
    start = threading.Barrier(8)

    def work(i):
        try:
            start.wait()
            det = aaglsd.Detector(320, 240, "paper")
            got = []
            for k in range(6):
                img = images[(i + k) % 8]
                got.append(((i + k) % 8, bits(aaglsd.detect(img, "paper")).copy()))
                got.append(((i + k) % 8, bits(det(img)).copy()))
            results[i] = got
        except Exception as e:  # noqa: BLE001 - reported below
            errors.append(e)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    assert len(results) == 8
    for got in results.values():
        for k, seg in got:
            assert np.array_equal(seg, serial[k])


def test_gil_is_released_during_detection():
    """The main thread keeps running Python while another thread detects."""
    rng = np.random.default_rng(1)
    big = rng.integers(0, 256, (1500, 2000), dtype=np.uint8)
    aaglsd.detect(big[:100, :100])
    span = {}

    def work():
        span["t0"] = time.perf_counter()
        aaglsd.detect(big)
        span["t1"] = time.perf_counter()

    t = threading.Thread(target=work)
    ticks = []
    t.start()
    while t.is_alive():
        ticks.append(time.perf_counter())
    t.join()
    t0, t1 = span["t0"], span["t1"]
    assert t1 - t0 > 0.02, "the call is long enough to tell"
    inner = [x for x in ticks if t0 + 0.2 * (t1 - t0) < x < t1 - 0.2 * (t1 - t0)]
    # With the GIL held the main thread could not run at all in that window.
    assert len(inner) > 100, (len(inner), t1 - t0)


def test_detector_shared_by_two_threads_is_guarded(images):
    """Each call on a shared Detector either succeeds with the right answer or
    raises the RuntimeError that names the cause; nothing else happens."""
    det = aaglsd.Detector(320, 240)
    want = [bits(aaglsd.detect(img)).copy() for img in images[:2]]
    outcomes = [[], []]
    start = threading.Barrier(2)

    def work(i):
        start.wait()
        for _ in range(40):
            try:
                ok = np.array_equal(bits(det(images[i])), want[i])
                outcomes[i].append("ok" if ok else "WRONG")
            except RuntimeError as e:
                assert "running in another thread" in str(e)
                outcomes[i].append("busy")

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    flat = outcomes[0] + outcomes[1]
    assert len(flat) == 80 and "WRONG" not in flat
    assert "ok" in flat  # the first call to take the detector cannot be refused
