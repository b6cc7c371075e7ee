#!/usr/bin/env python3
"""Labels the GoogleTest cases of one test executable for CTest, from their source (cmake/AmosTestLabels.cmake):
    test_labels.py --out FILE [--all LABEL] SOURCE...
A test is
  real-data   when its body (or its fixture's SetUp) asks for the shared data or models (AMOS_REQUIRE_DATA /
              AMOS_REQUIRE_MODELS: it is skipped without them);
  end-to-end  when it runs the system over a sequence (a SlamSystem, the public amos::Slam, a DynamicPipeline, a
              local mapper, a whole run, a rendered synthetic sequence) or the program itself (--all end-to-end,
              the app tests);
  browser     when it drives a headless browser;
  unit        otherwise.
Writes `set(AMOS_LABELS_<Suite>.<Case> "l1;l2")` per test; the labels' timeouts are in AmosTestLabels.cmake."""
import argparse, re

TEST = re.compile(r'\bTEST(?:_F|_P)?\(\s*(\w+)\s*,\s*(\w+)\s*\)')
FIXTURE = re.compile(r'\b(?:class|struct)\s+(\w+)\s*(?:final\s*)?:\s*public\s+(?:::)?testing::Test')
REAL_DATA = re.compile(r'AMOS_REQUIRE_(?:DATA|MODELS)\b')
END_TO_END = re.compile(r'\b(?:SlamSystem|DynamicPipeline|LocalMapper|runSequence|RunController|runController|'
                        r'SyntheticSequence|renderSequence|SequenceRun|Slam)\b')
BROWSER = re.compile(r'\b(?:chromium|headless)\b', re.IGNORECASE)


# A function of the test file, defined at the start of a line and ended by the next "}" at the start of a line.
HELPER = re.compile(r'^[A-Za-z][^\n;]*?\b(\w+)\([^;]*?\)\s*(?:const\s*)?(?:->[^{;]*)?\{\s*$(.*?)^\}', re.M | re.S)
CALL = re.compile(r'\b(\w+)\s*\(')


def helper_texts(text):
    """Each file-level helper's text with the text of the helpers it calls (to a fixed point): what a test that
    calls it runs."""
    own = {m.group(1): m.group(2) for m in HELPER.finditer(text) if not m.group(0).startswith("TEST")}
    closed = dict(own)
    for _ in range(len(own)):
        grown = {name: body + "".join(closed[c] for c in set(CALL.findall(body)) if c in closed and c != name)
                 for name, body in own.items()}
        if grown == closed: break
        closed = grown
    return closed


def labels_of(text, helpers, forced):
    runs = text + "".join(helpers[c] for c in set(CALL.findall(text)) if c in helpers)
    labels = set(forced)
    if REAL_DATA.search(runs): labels.add("real-data")
    if END_TO_END.search(runs): labels.add("end-to-end")
    if BROWSER.search(runs): labels.add("browser")
    return sorted(labels) or ["unit"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", required=True)
    ap.add_argument("--all", action="append", default=[], help="a label every test of the executable gets")
    ap.add_argument("sources", nargs="+")
    args = ap.parse_args()
    lines = []
    for path in args.sources:
        text = open(path, encoding="utf-8", errors="replace").read()
        # A fixture's own code (SetUp, helpers) up to the next fixture or test: what each of its tests runs too.
        fixtures = {}
        for m in FIXTURE.finditer(text):
            end = TEST.search(text, m.end())
            fixtures[m.group(1)] = text[m.start(): end.start() if end else len(text)]
        helpers = helper_texts(text)
        for m in TEST.finditer(text):
            end = text.find("\n}", m.end())  # the test's closing brace, at the start of a line
            body = text[m.end(): end if end >= 0 else len(text)]
            labels = labels_of(body + fixtures.get(m.group(1), ""), helpers, args.all)
            lines.append(f'set("AMOS_LABELS_{m.group(1)}.{m.group(2)}" "{";".join(labels)}")\n')
    with open(args.out, "w", encoding="utf-8") as out:
        out.writelines(sorted(lines))


if __name__ == "__main__":
    main()
