"""The exceptions of the package."""


class RunDirError(Exception):
    """A run directory, or a file in it, is missing, incomplete or malformed; the message names the path."""


class RunFailed(RuntimeError):
    """`cosim run` ended with a non-zero exit code.

    returncode: the launcher's exit code (README "Exit codes"); reason: why, from OUT/run_summary.json when the
    launcher wrote one for this run, else the last lines it printed; out: the run directory; summary: the parsed
    run_summary.json of this run or None; output: the launcher's last output lines (text)."""

    def __init__(self, returncode, reason, out, summary=None, output=""):
        self.returncode, self.reason, self.out, self.summary, self.output = returncode, reason, out, summary, output
        super().__init__(f"cosim run into {out} failed with exit code {returncode}: {reason}")
