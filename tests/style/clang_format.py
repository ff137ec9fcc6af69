#!/usr/bin/env python3
"""Style test: every tracked C++ file is formatted as .clang-format says.

    clang_format.py SOURCE_DIR

Lists the C++ files (.cpp, .hpp, .h) that git tracks in SOURCE_DIR (every such
file under src, include, problems, tests and perf when SOURCE_DIR is not a git
checkout), formats each with clang-format in memory and compares. Prints the
files that differ with the first differing line, then 'N passed, M failed';
exits non-zero if any file differs or clang-format is missing. Fix with
`clang-format -i FILE` (scripts/install_deps.sh installs Debian's clang-format).
"""
import os
import shutil
import subprocess
import sys

EXTENSIONS = (".cpp", ".hpp", ".h")
FOLDERS = ("src", "include", "problems", "tests", "perf")


def cpp_files(root):
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-z"], check=True, capture_output=True, text=True).stdout
        return sorted(f for f in out.split("\0") if f.endswith(EXTENSIONS))
    except (OSError, subprocess.CalledProcessError):
        found = []
        for top in FOLDERS:
            for d, _, names in os.walk(os.path.join(root, top)):
                found += [os.path.relpath(os.path.join(d, n), root) for n in names if n.endswith(EXTENSIONS)]
        return sorted(found)


def first_difference(a, b):
    for k, (x, y) in enumerate(zip(a.splitlines(), b.splitlines())):
        if x != y:
            return k + 1, x
    return min(len(a.splitlines()), len(b.splitlines())) + 1, ""


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else ".")
    exe = shutil.which("clang-format") or shutil.which("clang-format-14")
    if exe is None:
        print("FAIL clang-format not found (scripts/install_deps.sh installs it)")
        print("0 passed, 1 failed")
        return 1
    files = cpp_files(root)
    passed = failed = 0
    for f in files:
        path = os.path.join(root, f)
        with open(path, encoding="utf-8") as fh:
            text = fh.read()
        formatted = subprocess.run([exe, f"--assume-filename={path}", "--style=file"], input=text, check=True,
                                   capture_output=True, text=True, cwd=root).stdout
        if formatted == text:
            passed += 1
        else:
            failed += 1
            line, content = first_difference(text, formatted)
            print(f"FAIL {f}:{line} differs from clang-format: {content.strip()[:100]}")
    print(f"{os.path.basename(exe)}: {len(files)} C++ files checked")
    print(f"{passed} passed, {failed} failed")
    return 0 if failed == 0 and passed > 0 else 1


if __name__ == "__main__":
    sys.exit(main())
