#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Lists the longest function bodies in C++ sources (issue 13 keeps every
function in generator/ and runtime/ under about 100 lines).

Usage: scripts/longest_functions.py [-n N] [DIR_OR_FILE ...]   (default: generator runtime)

A function is a line that ends with '{' and holds a '(' (not a namespace,
class, struct, enum, control statement or lambda argument), up to the line
with the brace that closes it; its length is that line count. Heuristic, but
clang-format's layout makes it reliable for this code base.
"""
import argparse
import os
import re
import sys

SKIP = re.compile(r'^\s*(namespace|class|struct|enum|union|if|else|for|while|switch|do|try|catch|return|case)\b')
SOURCE = ('.cpp', '.hpp', '.h', '.cc')


STRINGS = re.compile(r'"(?:\\.|[^"\\])*"|\'(?:\\.|[^\'\\])*\'|//.*$')


def braces(line):
    """The change in brace depth on a line, outside strings and comments."""
    code = STRINGS.sub('', line)
    return code.count('{') - code.count('}')


def functions(path):
    lines = open(path, encoding='utf-8', errors='replace').read().split('\n')
    i = 0
    while i < len(lines):
        stripped = lines[i].strip()
        if (stripped.endswith('{') and not SKIP.match(lines[i]) and not stripped.startswith(('//', '*'))
                and ('(' in stripped or stripped.startswith(':') or lines[i - 1].rstrip().endswith(','))):
            # The header may span lines: back up to the line that opens it.
            start = i
            while start > 0 and not re.search(r'\w[\w:<>,~ ]*\(', lines[start]) and i - start < 12:
                start -= 1
            name = re.findall(r'([~\w:]+)\s*\(', lines[start])
            if name and name[0] in ('if', 'for', 'while', 'switch') or '= [' in lines[start] or '](' in lines[start]:
                i += 1
                continue
            depth, end = braces(lines[i]), i
            while depth > 0 and end + 1 < len(lines):
                end += 1
                depth += braces(lines[end])
            yield end - start + 1, name[0] if name else stripped[:40], start + 1
            i = end + 1
            continue
        i += 1


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('-n', type=int, default=10, help='how many to list (default 10)')
    parser.add_argument('paths', nargs='*', default=['generator', 'runtime'])
    args = parser.parse_args()
    found = []
    for root in args.paths:
        if not os.path.exists(root):
            sys.exit(f'{root}: no such file or directory')
        walk = [(root, [], [os.path.basename(root)])] if os.path.isfile(root) else os.walk(root)
        for directory, _, files in walk:
            for f in files:
                path = root if os.path.isfile(root) else os.path.join(directory, f)
                if path.endswith(SOURCE):
                    found += [(n, name, f'{path}:{line}') for n, name, line in functions(path)]
    for n, name, where in sorted(found, reverse=True)[:args.n]:
        print(f'{n:5d}  {name:40s} {where}')


if __name__ == '__main__':
    main()
