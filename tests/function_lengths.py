#!/usr/bin/python3
"""Function lengths of C++ sources, by a scan of their braces.

A function is a brace block opened at namespace or class scope whose header (the text since the
previous ';', '{' or '}' at that scope) ends in ')' and any of const, noexcept, override, final, a
trailing return type or a constructor's initializer list. Its length is the lines from its header's
first line to its closing brace, lambdas and local classes inside it included. Comments, string and
character literals and preprocessor lines are blanked first, so their braces do not count.

Usage:
  function_lengths.py [--top N] PATH...       the N longest functions (default 20), longest first
Imported by layout_check.py, which holds the limits.
"""
import os
import re
import sys

_TAIL = re.compile(r"\)\s*(?:const|noexcept(?:\([^)]*\))?|override|final|mutable|&&|&|\s|->[^{;]*)*$")
_TYPE = re.compile(r"^\s*(?:template\s*<.*>\s*)?(?:class|struct|union|enum)\b", re.S)
_NAME = re.compile(r"([~\w:<>=!+\-*/%^&|\[\]()]+?)\s*\(", re.S)


def blank(text):
    """Comments, literals and preprocessor lines replaced by spaces; newlines kept."""
    out = []
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if line_start and c == "#" or (line_start and c in " \t" and text[i:].lstrip(" \t").startswith("#")):
            j = i
            while j < n:  # a directive continues over backslash-newlines
                k = text.find("\n", j)
                if k < 0:
                    k = n
                if k > 0 and text[k - 1] == "\\":
                    j = k + 1
                    continue
                break
            out.append(re.sub(r"[^\n]", " ", text[i:k]))
            i = k
            continue
        if text.startswith("//", i):
            k = text.find("\n", i)
            k = n if k < 0 else k
            out.append(" " * (k - i))
            i = k
            continue
        if text.startswith("/*", i):
            k = text.find("*/", i + 2)
            k = n if k < 0 else k + 2
            out.append(re.sub(r"[^\n]", " ", text[i:k]))
            i = k
            continue
        m = re.match(r'R"([^(\s]*)\(', text[i:i + 20])
        if m and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            end = text.find(")" + m.group(1) + '"', i)
            k = n if end < 0 else end + len(m.group(1)) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:k]))
            i = k
            continue
        if c in "\"'" and not (c == "'" and i > 0 and text[i - 1].isalnum()):  # 1'000 is a digit separator
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(c + " " * (min(j, n) - i - 1) + (c if j < n else ""))
            i = j + 1
            continue
        out.append(c)
        line_start = c == "\n" or (line_start and c in " \t")
        i += 1
    return "".join(out)


def functions(path):
    """(name, first line, last line) of each function defined in the file."""
    text = blank(open(path, encoding="utf-8").read())
    result = []
    stack = []  # per open brace: "scope" (namespace, class, extern), "func", "init" (inside a header) or "block"
    header, header_line = "", 1
    line = 1
    for c in text:
        if c == "\n":
            line += 1
        in_scope = not stack or stack[-1][0] in ("scope", "init")
        if c == "{" and in_scope:
            if stack and stack[-1][0] == "init" or re.search(r"\)\s*:[^;]*$", header) and not _TAIL.search(header):
                if not _TAIL.search(header):  # a brace of a constructor's initializer list
                    stack.append(("init", line, None))
                    header += c
                    continue
            h = header.strip()
            if re.match(r"^(?:inline\s+)?namespace\b", h) or re.match(r"^extern\b", h) or _TYPE.match(h):
                stack.append(("scope", line, None))
            elif _TAIL.search(header) and "=" not in re.sub(r"\boperator\s*\S+|\([^()]*\)|<[^<>]*>", "", h):
                names = _NAME.findall(h)
                stack.append(("func", header_line, names[0].strip() if names else "?"))
            else:
                stack.append(("block", line, None))
            header = ""
            continue
        if c == "{":
            stack.append(("block", line, None))
            continue
        if c == "}":
            if not stack:
                continue
            kind, start, name = stack.pop()
            if kind == "func":
                result.append((name, start, line))
            if kind == "init":
                header += c
                continue
            if not stack or stack[-1][0] == "scope":
                header = ""
            continue
        if in_scope:
            if c == ";":
                header = ""
                continue
            if not header.strip() and not c.isspace():
                header_line = line
            if header.strip() or not c.isspace():
                header += c
    return result


def sources(paths):
    for p in paths:
        if os.path.isdir(p):
            for root, _, files in os.walk(p):
                for f in sorted(files):
                    if f.endswith((".h", ".cpp")):
                        yield os.path.join(root, f)
        else:
            yield p


def main():
    args = sys.argv[1:]
    top = 20
    if args[:1] == ["--top"]:
        top, args = int(args[1]), args[2:]
    rows = []
    for path in sources(args):
        for name, first, last in functions(path):
            rows.append((last - first + 1, path, first, name))
    rows.sort(key=lambda r: (-r[0], r[1], r[2]))
    for length, path, first, name in rows[:top]:
        print(f"{length:5d}  {path}:{first}  {name}")


if __name__ == "__main__":
    main()
