#!/usr/bin/env python3
"""Lists the C++ function bodies longer than a number of lines (#20).

Usage: scripts/long_functions.py [--max N] [PATH ...]

PATH: files or folders (default: libs apps filters plugins, from the
repository root); N: the longest body allowed, in lines (default 100).
Prints one line per longer body, longest first: its length, file:line of
the signature and the function's name. A body runs from the line of its
opening brace to the line of its closing brace; lambdas and local classes
count towards the function that holds them.

This is a brace matcher on text with comments, literals and preprocessor
lines blanked, not a parser: a brace at namespace or class scope opens a
function when its declaration has a parameter list and is not an
initialiser (`= {`). Good enough for this code base's style.
"""
import os
import re
import signal
import sys

EXTENSIONS = ('.cpp', '.cxx', '.cc', '.h', '.hpp', '.hxx')
DEFAULT_PATHS = ('libs', 'apps', 'filters', 'plugins')
SCOPE = re.compile(r'\b(namespace|class|struct|union|enum)\b|\bextern\s*"')
INIT_LIST = re.compile(r'\)\s*(noexcept\s*)?:[^:]')
DIRECTIVE = re.compile(r'[ \t]*#')
RAW_STRING = re.compile(r'R"([^(\s]*)\(')


def blank(text):
    return re.sub(r'[^\n]', ' ', text)


def strip(text):
    """The text with comments, literals and preprocessor lines blanked
    (newlines kept, so that line numbers stay)."""
    out, i, n = [], 0, len(text)
    at_line_start = True
    while i < n:
        c = text[i]
        if at_line_start and DIRECTIVE.match(text, i):
            j = i
            while True:  # the directive and its continuation lines
                j = text.find('\n', j)
                if j < 0 or not text[:j].rstrip(' \t').endswith('\\'):
                    break
                j += 1
            j = n if j < 0 else j
            out.append(blank(text[i:j]))
            i = j
            continue
        at_line_start = c == '\n'
        if text.startswith('//', i):
            j = text.find('\n', i)
            j = n if j < 0 else j
        elif text.startswith('/*', i):
            j = text.find('*/', i + 2)
            j = n if j < 0 else j + 2
        elif c == 'R' and RAW_STRING.match(text, i) and not (i and (text[i - 1].isalnum() or text[i - 1] == '_')):
            delimiter = ')' + RAW_STRING.match(text, i).group(1) + '"'
            end = text.find(delimiter, i)
            j = n if end < 0 else end + len(delimiter)
        elif c == "'" and re.search(r'(^|[^\w.\'])\d[\w.\']*$', text[max(0, i - 64):i]):
            j = i + 1  # digit separator: 1'000'000
            out.append(' ')
            i = j
            continue
        elif c in '"\'':
            j = i + 1
            while j < n and text[j] != c and text[j] != '\n':
                j += 2 if text[j] == '\\' else 1
            j += 1
        else:
            out.append(c)
            i += 1
            continue
        out.append(blank(text[i:j]))
        i = j
    return ''.join(out)


def functions(path):
    """(name, signature line, opening line, closing line) of every function
    body of a file."""
    with open(path, encoding='utf-8', errors='replace') as f:
        text = strip(f.read())
    line = 1
    stack = []         # (kind, opening line, name, signature line)
    header_start = 0   # where the declaration before the next brace begins
    found = []
    for i, c in enumerate(text):
        if c == '\n':
            line += 1
            continue
        in_function = any(kind == 'function' for kind, *_ in stack)
        if c == '{':
            header = text[header_start:i]
            if in_function:
                stack.append(('block', line, None, None))
            elif re.search(r'[\w>]\s*$', header) and INIT_LIST.search(header):
                stack.append(('init', line, None, None))  # a member's brace initialiser
                continue
            elif SCOPE.search(header) and '(' not in header or re.search(r'\bnamespace\b|\bextern\s*"', header):
                stack.append(('scope', line, None, None))
            elif ')' in header and not header.rstrip().endswith('='):
                signature = ' '.join(header.split())
                m = re.search(r'(~?[\w:]+(?:<[^()]*>)?|operator\s*\S+)\s*\(', signature)
                first = len(header) - len(header.lstrip())
                signature_line = line - header[first:].count('\n')
                stack.append(('function', line, m.group(1) if m else signature[:60], signature_line))
            else:
                stack.append(('block', line, None, None))
            header_start = i + 1
        elif c == '}':
            if stack:
                kind, opening, name, signature_line = stack.pop()
                if kind == 'function':
                    found.append((name, signature_line, opening, line))
                if kind == 'init':
                    continue
            header_start = i + 1
        elif not in_function and (c == ';' or (c == ':' and re.search(
                r'\b(public|private|protected)\s*$', text[header_start:i]))):
            header_start = i + 1
    return found


def source_files(root):
    if os.path.isfile(root):
        return [root]
    return sorted(os.path.join(folder, name) for folder, _, names in os.walk(root)
                  for name in names if name.endswith(EXTENSIONS))


def main(argv):
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # quiet under `| head`
    limit, paths = 100, []
    args = iter(argv)
    for arg in args:
        if arg == '--max':
            limit = int(next(args))
        elif arg in ('-h', '--help'):
            print(__doc__.strip())
            return 0
        else:
            paths.append(arg)
    if not paths:
        os.chdir(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..'))
        paths = DEFAULT_PATHS
    rows = []
    for root in paths:
        for path in source_files(root):
            for name, signature_line, opening, closing in functions(path):
                length = closing - opening + 1
                if length > limit:
                    rows.append((length, path, signature_line, name))
    for length, path, signature_line, name in sorted(rows, key=lambda r: (-r[0], r[1], r[2])):
        print(f'{length:5d}  {path}:{signature_line}  {name}')
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
