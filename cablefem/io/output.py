"""Output written whole or not at all, inside one folder (README, "The command line").

- ``prepare_folder``: the output folder, made and probed before any work starts;
  a file in its place, a file above it or a folder that cannot be written is an
  ``OutputError`` (one line naming the path, exit status 2).
- ``inside``: the path of an output file, never outside its folder.
- ``write_atomic`` / ``replace_into``: a file is written under a temporary name
  ``.<name>.partial`` beside it and renamed into place when complete, so a reader
  (or a run killed at any moment) sees the old file or the new one, never half of
  one. Files get the mode ``open()`` gives: 0o666 less the umask.
- ``RowsFile``: tensions.csv holding whole rows only: each batch of rows goes in
  one write call, and a write that fails (a full disk) is cut back to the last
  whole row.
- ``raise_on_sigterm`` / ``deferred_signals``: SIGTERM stops a run as Ctrl-C
  does, and neither cuts short the closing of the files.

Output errors that the operating system reports (``OSError``) become
``OutputError`` here; nothing is fsync'ed: a killed process loses nothing the
kernel has accepted, only a machine that loses power would.
"""

import contextlib
import csv
import ctypes
import errno
import io
import json
import os
import signal
import sys
import threading

from cablefem.errors import OutputError, Terminated

#: suffix of the temporary name a file is written under before it is renamed into place
PARTIAL = ".partial"
_FLAGS = os.O_WRONLY | os.O_CREAT | os.O_TRUNC | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)


def failure(error, path):
    """The OutputError of an OSError met writing ``path``."""
    return OutputError(f"cannot write: {error.strerror or error}", os.fspath(path))


def partial_path(path):
    """The temporary name ``.<name>.partial`` a file at ``path`` is written under."""
    folder, name = os.path.split(os.fspath(path))
    return os.path.join(folder, f".{name}{PARTIAL}")


def _write_all(handle, chunks):
    """Write the bytes chunks to the file descriptor handle in one write call (more only if the
    kernel takes part of it)."""
    view = memoryview(b"".join(chunks))
    while view:
        view = view[os.write(handle, view):]


@contextlib.contextmanager
def _or_nothing(tmp, path):
    """Remove the temporary file ``tmp`` if the block fails; an OSError becomes the OutputError
    of ``path``."""
    try:
        yield
    except BaseException as error:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        if isinstance(error, OSError):
            raise failure(error, path) from None
        raise


def _write_file(path, chunks, truncate=True):
    """Write the bytes chunks to the file at path (created with mode 0o666 less the umask).
    Without ``truncate`` a longer file is cut to the new length only after the write (ext4
    flushes a file that was truncated to zero when it is closed, ``GrowingFile``)."""
    handle = os.open(path, _FLAGS if truncate else _FLAGS & ~os.O_TRUNC, 0o666)
    try:
        _write_all(handle, chunks)
        if not truncate:
            length = sum(map(len, chunks))
            if os.fstat(handle).st_size > length:
                os.ftruncate(handle, length)
    finally:
        os.close(handle)


def write_atomic(path, text):
    """Write text (str or a list of bytes chunks) to path through ``.<name>.partial``, renamed into
    place: path holds its old content or all of the new, never part of it."""
    chunks = [text.encode("utf-8")] if isinstance(text, str) else text
    replace_into(lambda tmp: _write_file(tmp, chunks), path)


class GrowingFile:
    """A file that only grows (the .pvd collection), rewritten whole, atomically and cheaply.

    Each ``write`` puts the whole new content at the temporary name and swaps it with the
    file (Linux ``renameat2(RENAME_EXCHANGE)``): the temporary name then holds the previous
    content, which the next, longer content overwrites without truncating. A rename over an
    existing file (``os.replace``) or a truncation makes ext4 flush the new file's blocks
    (``auto_da_alloc``), 0.3 ms a call against 0.03 ms for the swap; where the swap is not
    supported, ``write_atomic`` does it that way."""

    def __init__(self, path):
        self.path = path
        self.tmp = partial_path(path)
        self.swap = _exchange is not None

    def write(self, chunks):
        """Make the file's content the bytes chunks, at least as long as the last content."""
        if not self.swap or not os.path.exists(self.path):
            write_atomic(self.path, chunks)
            return
        with _or_nothing(self.tmp, self.path):
            # not truncated first: the longer content overwrites the older one the swap left here
            _write_file(self.tmp, chunks, truncate=False)
            self.swap = _exchange(self.tmp, self.path)
        if not self.swap:  # not supported here after all: the temporary file holds the new content
            os.replace(self.tmp, self.path)

    def close(self):
        """Remove the temporary name (it holds an older content)."""
        with contextlib.suppress(OSError):
            os.unlink(self.tmp)


def _renameat2():
    """``exchange(a, b)`` swapping two paths atomically through Linux renameat2, or None."""
    if not sys.platform.startswith("linux"):
        return None
    try:
        function = ctypes.CDLL(None, use_errno=True).renameat2
    except (OSError, AttributeError):
        return None
    function.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    at_cwd, rename_exchange = -100, 2

    def exchange(a, b):
        """Swap the files at paths a and b; False if this file system cannot (nothing done)."""
        if function(at_cwd, os.fsencode(a), at_cwd, os.fsencode(b), rename_exchange) == 0:
            return True
        code = ctypes.get_errno()
        if code in (errno.EINVAL, errno.ENOSYS, errno.EOPNOTSUPP, errno.ENOTSUP):
            return False
        raise OSError(code, os.strerror(code), b)
    return exchange


_exchange = _renameat2()


def replace_into(write, path):
    """Call write(tmp) to make the file ``tmp`` (a third-party writer), then rename it to path;
    nothing is left at either name when write fails."""
    tmp = partial_path(path)
    with _or_nothing(tmp, path):
        if os.path.islink(tmp):  # a writer that opens by name would follow it out of the folder
            os.unlink(tmp)
        write(tmp)
        os.replace(tmp, path)


def prepare_folder(path):
    """The absolute path of the output folder ``path``, made if missing; OutputError naming it if it
    is a file, lies under a file, or cannot be written (checked by writing, not by permission bits)."""
    if "\0" in os.fspath(path):
        raise OutputError("not a valid path: it holds a NUL character", repr(path))
    absolute = os.path.abspath(path)
    if os.path.lexists(absolute) and not os.path.isdir(absolute):
        raise OutputError("exists and is not a folder", path)
    above = os.path.dirname(absolute)
    while not os.path.lexists(above) and above != os.path.dirname(above):
        above = os.path.dirname(above)
    if not os.path.isdir(above):
        raise OutputError(f"lies under {above}, which is not a folder", path)
    try:
        os.makedirs(absolute, exist_ok=True)
        probe = os.path.join(absolute, f".cablefem-probe-{os.getpid()}{PARTIAL}")
        os.close(os.open(probe, _FLAGS, 0o666))
        os.unlink(probe)
    except OSError as error:
        raise OutputError(f"cannot write in this folder: {error.strerror or error}", path) from None
    return absolute


def prepare_file(path):
    """Check before any work that a file can be written at ``path`` (its folder made if missing)."""
    if os.path.isdir(path):
        raise OutputError("is a folder, not a file name", path)
    prepare_folder(os.path.dirname(os.path.abspath(path)) or ".")


def inside(folder, name):
    """The path of file ``name`` in ``folder``; OutputError if it would resolve anywhere else."""
    path = os.path.join(folder, name)
    if (os.path.basename(name) != name or name in ("", ".", "..")
            or os.path.realpath(os.path.dirname(path)) != os.path.realpath(folder)):
        raise OutputError(f"would be written outside the output folder {folder}", path)
    return path


def remove_partials(folder, prefixes):
    """Remove the temporary ``.<name>.partial`` files a killed run left in ``folder`` for files
    whose names start with one of ``prefixes``."""
    hidden = tuple(f".{prefix}" for prefix in prefixes)
    with os.scandir(folder) as entries:
        for entry in entries:
            if entry.name.startswith(hidden) and entry.name.endswith(PARTIAL):
                with contextlib.suppress(OSError):
                    os.unlink(entry.path)


class RowsFile:
    """A CSV file of whole rows only: the header is renamed into place, then each batch of rows
    is one write call; a write that fails is cut back to the last whole row (OutputError)."""

    def __init__(self, path, header):
        self.path = path
        tmp = partial_path(path)
        self._handle, self.size = None, 0
        with _or_nothing(tmp, path):
            self._handle = os.open(tmp, _FLAGS, 0o666)
            try:
                self.write([header])
                os.replace(tmp, path)  # a file (or link) already there is replaced, not written through
            except BaseException:
                self.close()
                raise

    def write(self, rows):
        """Append rows (lists of str) in one write call."""
        if not rows:
            return
        text = io.StringIO()
        csv.writer(text).writerows(rows)
        data = text.getvalue().encode("utf-8")
        try:
            _write_all(self._handle, [data])
        except OSError as error:
            with contextlib.suppress(OSError):
                os.ftruncate(self._handle, self.size)
            raise failure(error, self.path) from None
        self.size += len(data)

    def close(self):
        """Close the file (its rows are in the kernel's hands with each write)."""
        if self._handle is not None:
            os.close(self._handle)
            self._handle = None


def raise_on_sigterm():
    """Make SIGTERM raise ``Terminated`` (a KeyboardInterrupt) in the main thread, as SIGINT raises
    KeyboardInterrupt; returns the previous handler (None outside the main thread: nothing done)."""
    if threading.current_thread() is not threading.main_thread():
        return None

    def terminate(signum, frame):
        raise Terminated(signum)
    return signal.signal(signal.SIGTERM, terminate)


@contextlib.contextmanager
def deferred_signals(reraise=True):
    """Hold SIGINT and SIGTERM while the block runs (files being written): a signal that comes is
    recorded and, with ``reraise``, raised when the block has finished (as KeyboardInterrupt or
    Terminated). Only signals that raise in Python are held: one ignored, or left to the
    operating system (SIGTERM outside the command), stays as it is."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught = []
    previous = {}
    for sig in (signal.SIGINT, signal.SIGTERM):
        if callable(signal.getsignal(sig)):
            previous[sig] = signal.signal(sig, lambda signum, frame: caught.append(signum))
    try:
        yield
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
    if caught and reraise:
        raise KeyboardInterrupt if caught[0] == signal.SIGINT else Terminated(caught[0])


def write_json(path, data):
    """Write ``data`` as JSON (``tidy``) to ``path`` atomically (a temporary file renamed into place),
    its folder made if missing; OutputError if it cannot be written."""
    prepare_file(path)
    write_atomic(path, json.dumps(tidy(data), indent=1))


def tidy(value):
    """``value`` (a float, or lists, tuples and dicts of them) with every float in its shortest form
    to 15 significant digits, which a double holds exactly (a time summed from steps, 29.310000000000002,
    is 29.31; a computed force loses nothing above 1e-15 of itself), and no negative zero."""
    if isinstance(value, float):
        return float(f"{value:.15g}") + 0.0
    if isinstance(value, dict):
        return {key: tidy(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [tidy(item) for item in value]
    return value
