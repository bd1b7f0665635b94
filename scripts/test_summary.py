#!/usr/bin/env python3
"""Total the passed/failed counts of every test suite in one or more logs.

Understands cargo test ("test result: ok. 8 passed; 0 failed; ..."), vitest summary lines
("Tests  12 passed (12)", "Tests  1 failed | 11 passed (12)") Node's TAP ("# pass 9") and pytest's last line ("== 2 failed, 12 passed, 1 skipped in 6.01s ==",
errors counted as failures). Prints one line
"N passed, N failed". A log that is missing counts as one failed suite.
"""
import re
import sys

CARGO = re.compile(r"test result: \w+\. (\d+) passed; (\d+) failed")
VITEST = re.compile(r"^\s*Tests\s+(.*)\(\d+\)\s*$")
TAP = re.compile(r"^# (pass|fail) (\d+)\s*$", re.M)
PYTEST = re.compile(r"^=*\s*((?:\d+ (?:passed|failed|skipped|errors?|warnings?|deselected|xfailed|xpassed)(?:, )?)+) in [\d.]+s", re.M)


def count(text):
    passed = failed = 0
    for m in CARGO.finditer(text):
        passed += int(m.group(1))
        failed += int(m.group(2))
    for line in text.splitlines():
        m = VITEST.match(re.sub(r"\x1b\[[0-9;]*m", "", line))
        if m:
            for n, kind in re.findall(r"(\d+) (passed|failed)", m.group(1)):
                if kind == "passed":
                    passed += int(n)
                else:
                    failed += int(n)
    for kind, n in TAP.findall(text):
        if kind == "pass":
            passed += int(n)
        else:
            failed += int(n)
    for m in PYTEST.finditer(text):
        for n, kind in re.findall(r"(\d+) (passed|failed|errors?)", m.group(1)):
            if kind == "passed":
                passed += int(n)
            else:
                failed += int(n)
    return passed, failed


def main():
    passed = failed = 0
    for path in sys.argv[1:]:
        try:
            with open(path, errors="replace") as f:
                p, fl = count(f.read())
        except OSError:
            p, fl = 0, 1
        passed += p
        failed += fl
    print("%d passed, %d failed" % (passed, failed))


if __name__ == "__main__":
    main()
