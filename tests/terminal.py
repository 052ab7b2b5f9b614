"""Run the command line in a real pseudo-terminal (100 columns), as a user's shell would."""

from __future__ import annotations

import os
import pty
import sys

_PRELUDE = (
    "import fcntl, struct, sys, termios\n"
    "fcntl.ioctl(2, termios.TIOCSWINSZ, struct.pack('HHHH', 24, 100, 0, 0))\n"
    "import workbook_gen.progress as p\n"
    "from workbook_gen.cli import main\n"
    "real = p.Progress.__init__\n"
    "def at_once(self, *a, **k):\n"
    "    k['delay'] = 0.0\n"
    "    real(self, *a, **k)\n"
    "p.Progress.__init__ = at_once\n"
)


def run_in_terminal(argv: list[str]) -> tuple[int, str]:
    """``workbook-gen argv`` with stderr on a pseudo-terminal and the bar's delay set to 0
    (the commands tested take less than the 1 s the command line waits): exit code and
    everything the terminal showed."""
    code = _PRELUDE + f"sys.exit(main({argv!r}))\n"
    pid, fd = pty.fork()
    if pid == 0:
        os.execv(sys.executable, [sys.executable, "-c", code])
    chunks = []
    while True:
        try:
            data = os.read(fd, 4096)
        except OSError:
            break
        if not data:
            break
        chunks.append(data)
    _, status = os.waitpid(pid, 0)
    return os.WEXITSTATUS(status), b"".join(chunks).decode(errors="replace")
