"""urkin.course.watch: which library functions a call reaches, however they were named."""

from __future__ import annotations

import importlib
import sys
import threading

import numpy as np

import urkin
from urkin.course.watch import LibraryWatch

INVERSES = ["numpy.linalg.inv", "numpy.linalg.pinv"]


def test_a_function_named_by_a_string_built_at_run_time_is_seen():
    with LibraryWatch(INVERSES) as watch:
        getattr(np.linalg, "in" + "v")(np.eye(3))
    assert watch.seen == {"numpy.linalg.inv"}


def test_a_function_reached_through_another_library_function_is_seen():
    with LibraryWatch(["urkin.transforms.check_rotation"]) as watch:
        module = importlib.import_module("urkin." + "transforms")
        getattr(module, "check_" + "rotation")(np.eye(3))
    assert watch.seen == {"urkin.transforms.check_rotation"}


def test_nothing_is_seen_when_nothing_watched_runs():
    with LibraryWatch(INVERSES) as watch:
        np.linalg.solve(np.eye(3), np.ones(3))
        urkin.fk(urkin.robot("ur5"), np.zeros(6))
    assert watch.seen == set()


def test_a_thread_the_call_starts_is_watched():
    with LibraryWatch(INVERSES) as watch:
        thread = threading.Thread(target=lambda: np.linalg.pinv(np.eye(2)))
        thread.start()
        thread.join()
    assert watch.seen == {"numpy.linalg.pinv"}


def test_switching_the_hook_off_counts_as_every_call():
    with LibraryWatch(INVERSES) as watch:
        sys.setprofile(None)
        np.linalg.inv(np.eye(2))
    assert watch.seen == set(INVERSES)


def test_the_profiles_before_are_restored_and_unknown_names_left_out():
    def mine(frame, event, arg):
        return None

    before, threads_before = sys.getprofile(), threading.getprofile()
    sys.setprofile(mine)
    try:
        with LibraryWatch([*INVERSES, "no_such_module.f", "numpy.linalg.no_such_function"]) as w:
            assert sys.getprofile() is not mine
        assert sys.getprofile() is mine
        assert threading.getprofile() is threads_before
        with LibraryWatch([]) as empty:  # nothing to watch: no hook at all
            assert sys.getprofile() is mine
        assert empty.seen == set()
    finally:
        sys.setprofile(before)
    assert set(w.codes.values()) == set(INVERSES)
