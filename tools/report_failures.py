#!/usr/bin/env python3
"""Prints why each failed test failed, compactly, as the last lines of a test run.

CI keeps only the tail of a run's output, where ctest's own summary names a failed test but not
why it failed. tools/test.sh runs every gtest binary with GTEST_OUTPUT=xml:DIR/ and ctest with
--output-junit; this reads both and prints, for each failed GTest case, the first lines of each
failure (the assertion) and the last lines (the end of the logs the test attached), and for a
failed ctest test without a GTest report (a shell test, a crash) the end of its output. The last
lines it prints are one line per failure, so even a short tail names the case and the assertion.

  report_failures.py GTEST_XML_DIR [CTEST_JUNIT.xml ...]

Exit code 0 whatever the tests did (the verdict is ctest's); 1, with this text, without arguments.
"""
import sys

from test_reports import ctest_cases, gtest_reports

HEAD_LINES = 4   # the assertion: file:line, expected, actual
TAIL_LINES = 12  # the end of an attached log: usually where a process said why it stopped


def excerpt(text, head=HEAD_LINES, tail=TAIL_LINES):
    lines = [line.rstrip() for line in (text or "").splitlines() if line.strip()]
    if len(lines) <= head + tail:
        return lines
    return lines[:head] + [f"... ({len(lines) - head - tail} lines left out)"] + lines[-tail:]


def gtest_failures(directory):
    """(suite.case, [failure message, ...]) of every failed GTest case; the binaries with a report."""
    failures, binaries = [], set()
    for binary, root in gtest_reports(directory):  # a crashed binary's ctest output is reported instead
        binaries.add(binary)
        for case in root.iter("testcase"):
            messages = [f.get("message") or f.text or "" for f in case.findall("failure")]
            if messages:
                failures.append((f"{case.get('classname')}.{case.get('name')}", messages))
    return failures, binaries


def ctest_failures(junit_files, binaries_with_report):
    """(test name, output) of every failed ctest test that has no readable GTest report."""
    failures = []
    for case in ctest_cases(junit_files):
        if case.get("status") != "fail" or case.get("name") in binaries_with_report:
            continue
        output = case.find("system-out")
        failures.append((case.get("name"), output.text if output is not None else ""))
    return failures


def main(argv):
    if len(argv) < 2:
        sys.exit(__doc__)
    gtest, binaries = gtest_failures(argv[1])
    ctest = ctest_failures(argv[2:], binaries)
    if not gtest and not ctest:
        return 0
    summary = []
    print("report_failures: why each failed test failed")
    for name, messages in gtest:
        for message in messages:
            lines = excerpt(message)
            print(f"--- {name}")
            for line in lines:
                print(f"    {line}")
            assertion = " | ".join(lines[:2])
            summary.append(f"FAILED {name}: {assertion[:200]}")
    for name, output in ctest:
        print(f"--- {name} (no GTest report: its output's end)")
        for line in excerpt(output, head=0, tail=TAIL_LINES + HEAD_LINES):
            print(f"    {line}")
        summary.append(f"FAILED {name}: see its output above")
    for line in summary:
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
