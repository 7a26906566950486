"""The two kinds of failure a user sees: bad input, and a solver that did not converge."""


class InputError(ValueError):
    """Bad user input: names the file, the key and the reason in one line."""

    def __init__(self, reason, key=None, file=None):
        self.reason = reason
        self.key = key
        self.file = file
        super().__init__(self.message())

    def message(self):
        """One line: 'file: key: reason' with the parts that are known."""
        parts = [str(p) for p in (self.file, self.key) if p]
        return ": ".join(parts + [self.reason])

    def within(self, file=None, prefix=None):
        """The same error located in a file and/or under a key prefix."""
        key = self.key
        if prefix:
            key = f"{prefix}.{key}" if key else prefix
        return InputError(self.reason, key=key, file=self.file or file)


class ConvergenceError(RuntimeError):
    """A solver stopped without meeting its tolerance; says how far it got."""

    def __init__(self, message, residual=None, iterations=None):
        self.residual = residual
        self.iterations = iterations
        super().__init__(message)


class OutputError(InputError):
    """An output location or write that failed (a file where the folder should be, a full disk):
    a user error like bad input, one line naming the path and the reason."""

    def __init__(self, reason, path):
        super().__init__(reason, file=path)


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised where Python raises KeyboardInterrupt for SIGINT, so that a run stops the
    same way for both (``cablefem.io.output.raise_on_sigterm``); ``signum`` is the signal."""

    def __init__(self, signum):
        self.signum = signum
        super().__init__(f"signal {signum}")
