"""Reading the reports tools/test.sh collects: GTest's XML (GTEST_OUTPUT=xml:DIR/, one file per
binary) and ctest's JUnit (--output-junit). Shared by check_skips.py and report_failures.py."""
import pathlib
import xml.etree.ElementTree as ET


def gtest_reports(directory, on_unreadable=None):
    """(binary name, root element) of each readable DIR/*.xml, in name order. A binary that crashed
    mid-report leaves an unreadable one (ctest reports that failure): on_unreadable(path, error)."""
    for report in sorted(pathlib.Path(directory).glob("*.xml")):
        try:
            yield report.stem, ET.parse(report).getroot()
        except ET.ParseError as error:
            if on_unreadable:
                on_unreadable(report, error)


def ctest_cases(junit_files):
    """Every <testcase> of the JUnit files that exist."""
    for path in junit_files:
        if pathlib.Path(path).exists():
            yield from ET.parse(path).getroot().iter("testcase")
