# SPDX-License-Identifier: GPL-3.0-or-later
"""stdout and stderr on a terminal that may close under the run (a closed ssh session).

Writing to a terminal that has hung up fails (EIO), and may do so before the hangup's signal
reaches the driver's handler: the failure would end the run where it stood, skipping the
stop's cleanup (the catalogue's level files). Once the terminal has gone, what the run
writes goes nowhere.
"""
import errno
import os


class TerminalStream:
    def __init__(self, stream):
        self._stream = stream
        self._gone = False

    def write(self, text):
        if self._gone:
            return len(text)
        try:
            return self._stream.write(text)
        except OSError as e:
            if e.errno != errno.EIO:
                raise
            self._gone = True
            return len(text)

    def flush(self):
        if not self._gone:
            try:
                self._stream.flush()
            except OSError as e:
                if e.errno != errno.EIO:
                    raise
                self._gone = True

    def __getattr__(self, name):  # isatty, fileno, encoding...: the stream's own
        return getattr(self._stream, name)


def guard_terminal_streams(sys_module):
    """Wraps sys.stdout and sys.stderr where they are a terminal."""
    for name in ("stdout", "stderr"):
        stream = getattr(sys_module, name)
        try:
            on_terminal = os.isatty(stream.fileno())
        except (AttributeError, OSError, ValueError):
            on_terminal = False
        if on_terminal:
            setattr(sys_module, name, TerminalStream(stream))
