#!/usr/bin/env python3
"""Size figures of the library's code, from Universal Ctags (package universal-ctags):
    python3 scripts/code_metrics.py [--top N] [FOLDER ...]   (default: src/amos)
prints the lines per module (tests counted apart), the N longest functions and the N longest parameter lists.
Test files (*_test.cc) and test helpers are left out of the function tables."""
import argparse, collections, json, os, re, subprocess, sys

def functions(paths):
    out = subprocess.run(["ctags", "-R", "--languages=C++", "--kinds-C++=f", "--fields=+neS",
                          "--output-format=json", "-f", "-"] + paths, capture_output=True, text=True, check=True)
    for line in out.stdout.splitlines():
        tag = json.loads(line)
        if tag.get("_type") != "tag" or "end" not in tag: continue
        if tag["path"].endswith("_test.cc"): continue
        yield tag

def parameter_count(signature):
    inner = signature.strip()[1:-1].strip() if signature else ""
    if not inner or inner == "void": return 0
    depth, count = 0, 1
    for ch in inner:
        if ch in "<([{": depth += 1
        elif ch in ">)]}": depth -= 1
        elif ch == "," and depth == 0: count += 1
    return count

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--top", type=int, default=5)
    ap.add_argument("folders", nargs="*", default=["src/amos"])
    args = ap.parse_args()
    lines = collections.Counter()
    for folder in args.folders:
        for dirpath, _, files in os.walk(folder):
            for f in files:
                if not f.endswith((".cc", ".h")): continue
                path = os.path.join(dirpath, f)
                kind = "tests" if f.endswith("_test.cc") else "code"
                with open(path, encoding="utf-8", errors="replace") as fh:
                    lines[(os.path.relpath(dirpath, folder) if len(args.folders) == 1 else dirpath, kind)] += sum(1 for _ in fh)
    print("| module | lines (code) | lines (tests) |\n|---|---|---|")
    for module in sorted({m for m, _ in lines}):
        print(f"| {module} | {lines[(module, 'code')]} | {lines[(module, 'tests')]} |")
    print(f"| all | {sum(v for (m, k), v in lines.items() if k == 'code')} | "
          f"{sum(v for (m, k), v in lines.items() if k == 'tests')} |")
    tags = list(functions(args.folders))
    by_length = sorted(tags, key=lambda t: t["end"] - t["line"] + 1, reverse=True)[:args.top]
    print(f"\nLongest functions ({len(tags)} in all):")
    for t in by_length:
        print(f"  {t['end'] - t['line'] + 1:4d} lines  {t.get('scope', '') + '::' if t.get('scope') else ''}{t['name']}  ({t['path']}:{t['line']})")
    by_params = sorted(tags, key=lambda t: parameter_count(t.get("signature", "")), reverse=True)[:args.top]
    print("\nLongest parameter lists:")
    for t in by_params:
        print(f"  {parameter_count(t.get('signature', '')):4d} parameters  {t['name']}  ({t['path']}:{t['line']})")

if __name__ == "__main__":
    main()
