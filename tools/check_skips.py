#!/usr/bin/env python3
"""Fails when a test was skipped that tools/expected_skips.txt does not list for this machine.

A GTest case that calls GTEST_SKIP passes in ctest, so a machine without root or `ip netns` would
report the air/ground tests as passed without running them. tools/test.sh runs every gtest binary
with GTEST_OUTPUT=xml:DIR/ and ctest with --output-junit; this reads both, prints every skipped
test with its reason, and exits 1 when a skip is not in the allow-list.

  check_skips.py ALLOW_LIST GTEST_XML_DIR [CTEST_JUNIT.xml ...]

ALLOW_LIST: one `test_name  reason` per line (`#` comments); test_name is Suite.Case for a GTest
case or the ctest name, and may use shell wildcards (fnmatch).
"""
import fnmatch
import pathlib
import sys

from test_reports import ctest_cases, gtest_reports


def read_allow_list(path):
    allowed = []
    for number, line in enumerate(pathlib.Path(path).read_text().splitlines(), 1):
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        name, _, reason = line.partition(" ")
        if not reason.strip():
            sys.exit(f"{path}:{number}: expected `test_name  reason`, got {line!r}")
        allowed.append((name, reason.strip()))
    return allowed


def skipped_message(case):
    skipped = case.find("skipped")
    if skipped is not None:
        return " ".join((skipped.get("message") or skipped.text or "").split())  # one line
    return None


def gtest_skips(directory):
    """(name, reason) of every skipped GTest case in DIR/*.xml (GTest's XML report)."""
    skips = []
    unreadable = lambda report, error: print(f"check_skips: {report.name}: unreadable report ({error})")
    for _, root in gtest_reports(directory, unreadable):
        for case in root.iter("testcase"):
            message = skipped_message(case)
            if case.get("result") == "skipped" or message is not None:
                skips.append((f"{case.get('classname')}.{case.get('name')}", message or "(no reason given)"))
    return skips


def ctest_skips(junit_files):
    """(name, reason) of every test ctest itself did not run (skip return code, missing binary, ...)."""
    skips = []
    for case in ctest_cases(junit_files):
        message = skipped_message(case)
        if case.get("status") in ("notrun", "disabled") or message is not None:
            skips.append((case.get("name"), message or case.get("status")))
    return skips


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    allowed = read_allow_list(argv[1])
    skips = gtest_skips(argv[2]) + ctest_skips(argv[3:])
    unexpected = []
    print(f"check_skips: {len(skips)} skipped test(s); allow-list {argv[1]} ({len(allowed)} entries)")
    for name, reason in skips:
        listed = next((why for pattern, why in allowed if fnmatch.fnmatchcase(name, pattern)), None)
        print(f"  {'expected' if listed else 'NOT EXPECTED'}  {name}: {reason}" + (f"  [listed: {listed}]" if listed else ""))
        if not listed:
            unexpected.append(name)
    if unexpected:
        print(f"check_skips: FAILED: {len(unexpected)} skip(s) not listed in {argv[1]} for this machine: "
              + ", ".join(unexpected))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
