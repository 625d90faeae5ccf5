"""The background runner (refracta.widgets.jobs): a newer request supersedes the running one, cancel
reaches into refracta.render through its progress callable, failures are reported, not raised."""

import threading

import pytest

import refracta
from refracta.widgets.jobs import Cancelled, JobRunner

WAIT = 60.0  # [s] generous bound on waits for background work (a hang fails instead of blocking)


@pytest.fixture
def runner():
    runner = JobRunner()
    yield runner
    runner.close()


def looping_work(started: threading.Event, log: list):
    """Work that reports progress until cancelled, as refracta.render's callable sees it."""

    def work(job):
        started.set()
        report = job.progress("looping")
        for step in range(100000):
            report(step, 100000)
            threading.Event().wait(0.001)
        log.append("finished")
        return "finished"

    return work


def test_a_newer_request_cancels_the_running_one_and_only_it_delivers(runner):
    started, log, delivered = threading.Event(), [], []
    first = runner.submit("render", looping_work(started, log), on_done=delivered.append)
    assert started.wait(WAIT)
    second = runner.submit("render", lambda job: "second", on_done=delivered.append)
    assert runner.wait(WAIT)
    assert (first.state, second.state) == ("cancelled", "done")
    assert delivered == ["second"] and log == []


def test_a_pending_request_is_replaced_by_a_newer_one(runner):
    started, release, ran = threading.Event(), threading.Event(), []
    blocker = runner.submit("render", lambda job: started.set() or release.wait(WAIT))
    assert started.wait(WAIT)  # running: the next two requests queue behind it
    middle = runner.submit("render", lambda job: ran.append("middle"))
    last = runner.submit("render", lambda job: ran.append("last"))
    release.set()
    assert runner.wait(WAIT)
    assert ran == ["last"]
    assert (blocker.state, middle.state, last.state) == ("cancelled", "cancelled", "done")


def test_slots_run_side_by_side(runner):
    both = threading.Barrier(2, timeout=WAIT)  # each job waits for the other: only concurrent slots pass
    render = runner.submit("render", lambda job: both.wait())
    solve = runner.submit("solve", lambda job: both.wait())
    assert runner.wait(WAIT)
    assert (render.state, solve.state) == ("done", "done")


def test_cancel_stops_a_real_render_through_its_progress_callable(runner, road):
    camera = road.camera.resized(1280, 480)  # ~2 s on 2 cores: still running when cancelled
    reported, returned = threading.Event(), []

    def work(job):
        progress = job.progress("rendering")

        def spy(done, total):
            reported.set()
            progress(done, total)

        image = refracta.render(road.scene, camera, road.field, max_length=road.max_length, progress=spy)
        returned.append(image)
        return image

    job = runner.submit("render", work)
    assert reported.wait(WAIT)
    runner.cancel("render")
    assert job.wait(WAIT)
    assert job.state == "cancelled" and returned == []  # render raised Cancelled instead of returning


def test_a_failing_job_is_reported_to_on_error_not_raised_in_its_thread(runner):
    errors = []
    runner.on_error = errors.append

    def work(job):
        raise ValueError("bad input")

    job = runner.submit("solve", work)
    assert runner.wait(WAIT)
    assert job.state == "failed" and isinstance(job.error, ValueError)
    assert [str(e) for e in errors] == ["bad input"]


def test_check_raises_cancelled_once_cancelled(runner):
    release = threading.Event()
    job = runner.submit("render", lambda job: release.wait(WAIT))
    job.cancel()
    with pytest.raises(Cancelled):
        job.check()
    release.set()
    assert runner.wait(WAIT)
    assert job.state == "cancelled"


def test_wait_gives_up_after_its_timeout(runner):
    release = threading.Event()
    runner.submit("render", lambda job: release.wait(WAIT))
    assert runner.wait(0.05) is False and runner.busy()
    release.set()
    assert runner.wait(WAIT) and not runner.busy()
