#!/usr/bin/env python3
"""Holds every function in the C++ sources to at most LIMIT lines, from the first line of its signature to its
closing brace. A function is a brace block opened at namespace or class scope after a parameter list; class,
struct, enum, union and namespace blocks are walked into, anything inside a function (lambdas, nested blocks)
counts towards that function. Comments and string and character literals are blanked first, so braces in them do
not count.

Usage: function_lengths.py LIMIT PATH...   (files, or folders searched for .h, .cpp and .cc)
Prints "FILE:LINE: NAME is N lines, over LIMIT" for each and exits 1 when there is any; exits 0 otherwise."""
import pathlib
import re
import sys


def blank(text):
    """The text with comments and literals replaced by spaces, newlines kept, so offsets and lines still match."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith('//', i):
            j = text.find('\n', i)
            j = n if j < 0 else j
            out.append(' ' * (j - i))
            i = j
        elif text.startswith('/*', i):
            j = text.find('*/', i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r'[^\n]', ' ', text[i:j]))
            i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.find(')' + m.group(1) + '"', i) if m else -1
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append(re.sub(r'[^\n]', ' ', text[i:j]))
            i = j
        elif c in '"\'':
            j = i + 1
            while j < n and text[j] != c and text[j] != '\n':
                j += 2 if text[j] == '\\' else 1
            out.append(c + ' ' * (min(j, n) - i - 1) + (c if j < n else ''))
            i = j + 1
        else:
            out.append(c)
            i += 1
    return ''.join(out)


def long_functions(path, limit):
    text = blank(path.read_text(errors='replace'))
    found = []
    stack = []  # per open brace: 'scope' (namespace, class, ...) or 'block'
    head = 0    # where the text before the next brace at scope level starts
    i = 0
    while i < len(text):
        c = text[i]
        if c == '{':
            inside_function = any(k == 'block' for k in stack)
            before = text[head:i]
            if inside_function:
                stack.append('block')
            elif re.search(r'\b(namespace|class|struct|union|enum)\b', before) and '(' not in before.split('=')[0] \
                    or re.search(r'extern\s*$', before):
                stack.append('scope')
            elif '(' in before:
                depth, j = 1, i + 1
                while j < len(text) and depth:
                    depth += {'{': 1, '}': -1}.get(text[j], 0)
                    j += 1
                start = head + len(before) - len(before.lstrip())
                first = text.count('\n', 0, start) + 1
                last = text.count('\n', 0, j - 1) + 1
                if last - first + 1 > limit:
                    name = re.findall(r'([~\w:]+)\s*\(', before)
                    found.append((first, name[0] if name else '?', last - first + 1))
                stack.append('block')
            else:
                stack.append('block')  # an initializer list at namespace scope: not a function, not a scope
            head = i + 1
        elif c == '}':
            if stack:
                stack.pop()
            head = i + 1
        elif c == ';' and not any(k == 'block' for k in stack):
            head = i + 1
        elif c == '#' and text[text.rfind('\n', 0, i) + 1:i].strip() == '':
            i = text.find('\n', i)  # a preprocessor line (continuations are rare here and hold no braces)
            i = len(text) if i < 0 else i
            if not any(k == 'block' for k in stack):
                head = i + 1
            continue
        i += 1
    return found


def main():
    limit = int(sys.argv[1])
    files = []
    for arg in sys.argv[2:]:
        p = pathlib.Path(arg)
        files += sorted(q for q in p.rglob('*') if q.suffix in ('.h', '.cpp', '.cc')) if p.is_dir() else [p]
    bad = 0
    for f in files:
        for line, name, length in long_functions(f, limit):
            print(f'{f}:{line}: {name} is {length} lines, over {limit}')
            bad += 1
    print(f'{len(files)} files, {bad} functions over {limit} lines')
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main())
