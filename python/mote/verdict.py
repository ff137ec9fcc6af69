"""The verdict of a check script: PASS/FAIL lines for thresholded checks, INFO
lines for figures without a threshold (they count neither way), and a closing
'N passed, M failed' line with the exit status (0 only if something passed and
nothing failed). Every problems/*/check.py ends with it."""


class Verdict:
    """check(ok, text) prints PASS or FAIL and counts it, info(text) prints INFO; finish() prints the
    closing line and returns the exit status."""

    def __init__(self):
        self.passed = self.failed = 0

    def check(self, ok, text):
        ok = bool(ok)
        print(("PASS " if ok else "FAIL ") + text, flush=True)
        self.passed += ok
        self.failed += not ok

    def info(self, text):
        print("INFO " + text, flush=True)

    def finish(self):
        print(f"{self.passed} passed, {self.failed} failed")
        return 0 if self.failed == 0 and self.passed > 0 else 1
