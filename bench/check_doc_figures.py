#!/usr/bin/python3
"""Checks that every markdown link from the documentation into bench/results/
points to an existing file (issue #20: every figure in the docs is written
into bench/results/ by a script in bench/ and linked from the text).

usage: bench/check_doc_figures.py [-v] [REPO_ROOT]   (default: this file's repository)

Reads README.md, docs/*.md and bench/README.md; finds inline links and
images ([text](target), ![alt](target)) and reference definitions
([id]: target) outside code blocks and code spans; resolves each target
relative to the file that holds it. A target inside bench/results/ must be
an existing file (not a folder). Prints each broken link as
file:line: target (reason) and exits 1 if there is one, else 0.
-v also lists every link into bench/results/ that was checked.
Standard library only.
"""
import glob
import os
import re
import sys

INLINE = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+(?:\"[^\"]*\"|'[^']*'))?\s*\)")
REFERENCE = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+.*)?$")
FENCE = re.compile(r"^\s{0,3}(```|~~~)")
CODE_SPAN = re.compile(r"(`+)(?:(?!\1).)+?\1")


def links(path):
    """(line number, target) of every link in a markdown file, code excluded."""
    out = []
    fenced = None
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            m = FENCE.match(line)
            if m:
                if fenced is None:
                    fenced = m.group(1)
                elif m.group(1) == fenced:
                    fenced = None
                continue
            if fenced is not None:
                continue
            text = CODE_SPAN.sub("", line)
            out += [(n, t) for t in INLINE.findall(text)]
            m = REFERENCE.match(text)
            if m:
                out.append((n, m.group(1)))
    return out


def main():
    args = [a for a in sys.argv[1:] if a != "-v"]
    verbose = "-v" in sys.argv[1:]
    root = os.path.abspath(args[0] if args else os.path.join(os.path.dirname(__file__), ".."))
    results = os.path.join(root, "bench", "results")
    files = [os.path.join(root, "README.md")] + sorted(glob.glob(os.path.join(root, "docs", "*.md")))
    files.append(os.path.join(root, "bench", "README.md"))
    files = [f for f in files if os.path.isfile(f)]
    checked = broken = 0
    for path in files:
        rel = os.path.relpath(path, root)
        for n, target in links(path):
            if re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target) or target.startswith("#"):
                continue  # a URL (http:, mailto:, ...) or an anchor in the same file
            target_path = target.split("#", 1)[0]
            resolved = os.path.normpath(os.path.join(os.path.dirname(path), target_path))
            if os.path.commonpath([resolved, results]) != results:
                continue  # not into bench/results/
            checked += 1
            if os.path.isfile(resolved):
                if verbose:
                    print(f"{rel}:{n}: {target}")
                continue
            reason = "a folder, not a file" if os.path.isdir(resolved) else "no such file"
            print(f"{rel}:{n}: {target} ({reason})")
            broken += 1
    print(f"{checked} link(s) into bench/results/ in {len(files)} files; {broken} broken")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
