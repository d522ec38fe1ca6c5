#!/usr/bin/env python3
"""Lists every function body in the given C++ files longer than a limit.

Usage: function_lengths.py LIMIT FILE...  (exit 1 if any is longer)

A function body is a brace block that opens after ')' (possibly followed by
const, override, noexcept, a trailing return type or a member initializer
list) at namespace or class level; lambdas inside a function count towards it.
Comments and string literals are blanked first.
"""
import re
import sys


def blank(text):
    """Comments and string/char literals replaced by spaces, newlines kept."""
    pattern = re.compile(r'//[^\n]*|/\*.*?\*/|R"(\w*)\(.*?\)\1"|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'', re.S)
    return pattern.sub(lambda m: re.sub(r'[^\n]', ' ', m.group(0)), text)


def long_functions(path, limit):
    text = blank(open(path, encoding='utf-8').read())
    stack = []  # per open brace: is it a function body (and where it started)
    found = []
    for i, c in enumerate(text):
        if c == '{':
            inside_function = any(kind == 'function' for kind, _ in stack)
            head = text[max(0, i - 400):i]
            statement = re.split(r'[;{}]', head)[-1]
            is_function = (not inside_function and ')' in statement and
                           not re.match(r'\s*(if|for|while|switch|catch)\b', statement) and
                           not re.search(r'=\s*\[', statement))
            stack.append(('function' if is_function else 'block', i))
        elif c == '}' and stack:
            kind, start = stack.pop()
            if kind == 'function':
                lines = text.count('\n', start, i) + 1
                if lines > limit:
                    found.append((text.count('\n', 0, start) + 1, lines))
    return found


def main():
    limit = int(sys.argv[1])
    failed = False
    for path in sys.argv[2:]:
        for line, lines in long_functions(path, limit):
            print(f'{path}:{line}: function of {lines} lines (limit {limit})')
            failed = True
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
