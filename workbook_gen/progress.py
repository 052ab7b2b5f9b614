"""One progress bar for the package: a tqdm bar on stderr for long work.

The bar shows only when its stream is a terminal and the caller is not quiet;
otherwise nothing is drawn and tqdm is not even imported (a command that shows
no bar pays nothing for it).  Library code takes a plain callback; the command
line makes the bar and passes it in:

    with Progress(total=len(runs), desc="tradeoff", step="run") as bar:
        measure(scene, progress=bar)        # bar(label) advances one step
        ...
        bar.update(250)                      # or advance by a count

A ``Progress`` is a ``Callable[[str], None]`` (``bar(label)`` advances one
step and shows ``label``) and has ``update(n)`` for counts such as rows.
"""

from __future__ import annotations

import sys
from typing import Callable, TextIO

#: A progress callback: ``progress(label)`` is called once per finished step of work.
Callback = Callable[[str], None]


def quiet(label: str = "") -> None:
    """A progress callback that shows nothing."""


def is_terminal(stream: TextIO | None) -> bool:
    isatty = getattr(stream, "isatty", None)
    try:
        return bool(isatty and isatty())
    except (ValueError, OSError):  # a closed or detached stream
        return False


class Progress:
    """A tqdm bar on ``stream`` (stderr by default), drawn only on a terminal
    (and, with ``delay``, only once the work has taken that many seconds).

    ``bar(label)`` advances by one step and shows ``label``; ``bar.update(n)``
    advances by ``n`` steps; ``close()`` (or leaving the ``with`` block) clears it.
    ``step``: what one step is, as the bar names it ("row": ``120/500 row``, ``row/s``).
    """

    def __init__(self, total: int | None = None, *, desc: str = "", step: str = "it",
                 stream: TextIO | None = None, quiet: bool = False, leave: bool = False,
                 delay: float = 0.0):
        self.stream = stream if stream is not None else sys.stderr
        self.enabled = not quiet and is_terminal(self.stream)
        self.total = total
        self.done = 0
        self._bar = None
        if self.enabled:
            from tqdm import tqdm  # only when a bar is drawn
            self._bar = tqdm(total=total, desc=desc or None, unit=step, file=self.stream,
                             leave=leave, dynamic_ncols=True, smoothing=0.1,
                             mininterval=0.2, delay=delay)

    def __call__(self, label: str = "") -> None:
        self.update(1, label)

    def update(self, n: int = 1, label: str | None = None) -> None:
        self.done += n
        if self._bar is not None:
            if label:
                self._bar.set_postfix_str(label[:40], refresh=False)
            self._bar.update(n)

    def write(self, text: str, file: TextIO | None = None) -> None:
        """Print a line (to stdout by default) without breaking the bar."""
        file = file if file is not None else sys.stdout
        if self._bar is not None:
            self._bar.write(text, file=file)
        else:
            print(text, file=file, flush=True)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None

    def __enter__(self) -> "Progress":
        return self

    def __exit__(self, *exc) -> None:
        self.close()
