"""Status lines for long work: on stderr only, silent for quick work, a running clock for silent phases."""

import io
import time

from persson.progress import StatusLine, report


class _Tty(io.StringIO):
    def isatty(self):
        return True


def test_texts_and_counts_are_shown_in_a_log():
    buf = io.StringIO()
    status = StatusLine("persson test", buf)
    status("reading profiles")
    status(3, 4)
    status("isotherm", 1, 2)
    status("shifting isotherms", 0.4)
    status("fitting", None)
    assert buf.getvalue().splitlines() == ["persson test: reading profiles", "persson test: 3/4 (75 %)",
                                           "persson test: isotherm 1/2 (50 %)",
                                           "persson test: shifting isotherms (40 %)", "persson test: fitting"]


def test_a_quick_phase_stays_silent():
    buf = io.StringIO()
    with StatusLine("persson test", buf, delay_s=5.0).phase("quick work"):
        pass
    assert buf.getvalue() == ""


def test_a_slow_silent_phase_shows_a_running_clock_and_its_end():
    buf = _Tty()
    status = StatusLine("persson test", buf, delay_s=0.05, tick_s=0.02)
    with status.phase("fitting the master curve"):
        time.sleep(0.3)
    text = buf.getvalue()
    assert "\r" in text and "persson test: fitting the master curve" in text
    assert text.rstrip().endswith("s") and "done in" in text and text.endswith("\n")
    assert len(status.lines) >= 3  # drawn, redrawn with the clock, finished


def test_a_log_gets_at_most_one_line_per_interval():
    buf = io.StringIO()
    status = StatusLine("persson test", buf, delay_s=0.01, tick_s=0.01, log_interval_s=60.0)
    with status.phase("slow"):
        time.sleep(0.2)
    lines = buf.getvalue().splitlines()
    assert len(lines) == 2 and lines[0].startswith("persson test: slow") and "done in" in lines[1]


def test_disabled_status_writes_nothing_and_library_helper_tolerates_none():
    buf = io.StringIO()
    status = StatusLine("persson test", buf, enabled=False)
    status("x")
    with status.phase("y"):
        pass
    assert buf.getvalue() == ""
    report(None, "nothing happens")
    seen = []
    report(lambda *a: seen.append(a), "text", 1, 2)
    assert seen == [("text", 1, 2)]


def test_echo_clears_an_open_status_line_before_printing(capsys):
    buf = _Tty()
    status = StatusLine("persson test", buf, delay_s=0.0, tick_s=10.0)
    status("working")
    status.echo("a result line")
    assert buf.getvalue().endswith("\r\033[K")
    assert capsys.readouterr().out == "a result line\n"
