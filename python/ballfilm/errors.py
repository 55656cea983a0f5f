"""errors.py: the library's failures as Python exceptions.

Every failure of the C library is a status and a message (error.h); the
message of a bad scene names the file, the line, the section and the key
("scene.ini:12: error: [ball.2] mass: must be > 0").  BallfilmError
carries all of it: .status (the name: "input", "unstable", ...), .code
(the number, the program's exit status), .file and .line when the message
starts with FILE:LINE, .section and .key when the library named one.
"""
import re

STATUS = {0: "ok", 1: "internal", 2: "input", 3: "unstable",
          4: "no convergence", 5: "io", 6: "interrupted"}

_WHERE = re.compile(r"^(?P<file>[^\n:]+):(?P<line>\d+): error: ")
_FILE = re.compile(r"^(?P<file>[^\n:]+): error: ")
_KEY = re.compile(r"error: \[(?P<section>[^\]\s]+)\] (?P<key>[A-Za-z0-9_]+)"
                  r"(?: \(default\))?:")


class BallfilmError(Exception):
    """A failure reported by libballfilm (or a run that did not end well:
    then .result holds what its output file kept)."""

    def __init__(self, message, code=2, section="", key="", result=None):
        super().__init__(message)
        self.message = message
        self.code = code
        self.status = STATUS.get(code, str(code))
        self.section = section
        self.key = key
        self.result = result
        m = _WHERE.match(message)
        self.file = m.group("file") if m else None
        self.line = int(m.group("line")) if m else None
        if not m:
            m = _FILE.match(message)
            self.file = m.group("file") if m else None
        k = _KEY.search(message)
        if k and not self.section:
            self.section, self.key = k.group("section"), k.group("key")


class Interrupted(BallfilmError, KeyboardInterrupt):
    """Ctrl-C during ballfilm.run: the run stopped cleanly after its
    current step and wrote its checkpoint (.checkpoint, when the run has an
    output file); ballfilm.restart(.output) continues it bit for bit.
    .result holds the rows written up to the stop."""

    def __init__(self, message, output=None, checkpoint=None, result=None):
        BallfilmError.__init__(self, message, 6, result=result)
        self.output = output
        self.checkpoint = checkpoint


def from_err(err, result=None):
    """The exception of a filled bf_err."""
    return BallfilmError(err.msg.decode(errors="replace"), err.status,
                         err.section.decode(errors="replace"),
                         err.key.decode(errors="replace"), result)
