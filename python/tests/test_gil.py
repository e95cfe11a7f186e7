"""Long calls release the GIL: another Python thread keeps running while they work."""

import threading
import time

import numpy as np

import rotorflow as rf


def turns_during(work):
    """How many loop turns the main thread makes between the start and the end of `work` in
    another thread, and how long `work` took."""
    started, done = threading.Event(), threading.Event()
    took = []

    def run():
        started.set()
        t0 = time.perf_counter()
        work()
        took.append(time.perf_counter() - t0)
        done.set()

    thread = threading.Thread(target=run)
    thread.start()
    started.wait()
    turns = 0
    while not done.is_set():
        turns += 1
    thread.join()
    return turns, took[0]


def loop_rate():
    """Turns per second of the main thread's loop with nothing else running."""
    done = threading.Event()
    timer = threading.Timer(0.05, done.set)
    turns = 0
    t0 = time.perf_counter()
    timer.start()
    while not done.is_set():
        turns += 1
    return turns / (time.perf_counter() - t0)


def test_simulate_and_batches_release_the_gil():
    bivectors = np.zeros((200_000, 64))
    bivectors[:, [3, 5, 6, 9, 10, 12, 17, 18, 20, 24, 33, 34, 36, 40, 48]] = 0.3
    alg = rf.Algebra(6)
    cases = {
        "simulate": lambda: rf.simulate("ellipsoid:1,2,3,4,5", omega=np.linspace(0.1, 1, 10), t_end=400, samples=5, dt=0.001),
        "exp": lambda: alg.exp(bivectors),
        "product": lambda: alg.product(bivectors, bivectors),
    }
    rate = loop_rate()
    for name, work in cases.items():
        turns, took = turns_during(work)
        assert took > 0.1, f"{name} too short to tell ({took:.3f} s)"
        # Held, the GIL would let the loop run for one switch interval (5 ms) at most.
        assert turns > 0.3 * rate * took, f"{name}: {turns} turns in {took:.3f} s at {rate:.0f}/s"


def test_the_measurement_sees_a_call_that_holds_the_gil():
    # Reading rotation vectors into rotors holds the GIL (a quick loop that is not worth
    # releasing it for): the main thread barely turns while it runs, so the test above can
    # tell a held GIL from a released one.
    vectors = np.full((4_000_000, 3), 0.1)
    rate = loop_rate()
    turns, took = turns_during(lambda: rf.Rotor3.from_rotvec(vectors))
    assert took > 0.05, f"too short to tell ({took:.3f} s)"
    assert turns < 0.3 * rate * took, f"{turns} turns in {took:.3f} s at {rate:.0f}/s"
