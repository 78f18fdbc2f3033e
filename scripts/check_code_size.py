#!/usr/bin/env python3
"""check_code_size.py ROOT: the size limits of the package's headers (include/), for the next
engineer who reads and changes them: no file over 700 lines, no function over 80 lines.

A function (or lambda) is a body whose opening brace ends a line that closes a signature, or stands
alone on the line after it, up to the closing brace at the same indentation. Prints each header or function over its limit; exit status 1 if any.
"""
import pathlib
import re
import sys

MAX_FILE_LINES = 700
MAX_FUNCTION_LINES = 80
NOT_A_SIGNATURE = re.compile(r"^(struct|class|union|enum|namespace|if|else|for|while|do|switch|try|catch)\b|=\s*$")


def is_signature(text):
    """Whether `text` ends a function's (or a lambda's) signature."""
    ends = text.endswith((")", "const", "noexcept", "override", "final", "mutable")) or "->" in text
    return ends and not NOT_A_SIGNATURE.search(text)


def functions(lines):
    """(first line (1-based), line count, signature) of each function body of `lines`: the opening
    brace alone on its line after the signature, or at the end of the signature's line."""
    for i, line in enumerate(lines):
        stripped = line.strip()
        if stripped == "{" and i > 0:
            signature = lines[i - 1].strip()
        elif stripped.endswith("{") and len(stripped) > 1:
            signature = stripped[:-1].strip()
        else:
            continue
        if not is_signature(signature):
            continue
        indent = len(line) - len(line.lstrip())
        for j in range(i + 1, len(lines)):
            closing = lines[j]
            if closing.strip().startswith("}") and len(closing) - len(closing.lstrip()) == indent:
                yield i + 1, j - i + 1, signature
                break


def main(root):
    problems = []
    headers = sorted(pathlib.Path(root, "include").rglob("*.h"))
    for header in headers:
        lines = header.read_text(encoding="utf-8").splitlines()
        name = header.relative_to(root)
        if len(lines) > MAX_FILE_LINES:
            problems.append(f"{name}: {len(lines)} lines (at most {MAX_FILE_LINES})")
        for first, count, signature in functions(lines):
            if count > MAX_FUNCTION_LINES:
                problems.append(f"{name}:{first}: a function of {count} lines (at most {MAX_FUNCTION_LINES}): {signature}")
    for problem in problems:
        print(problem)
    print(f"{len(headers)} headers checked: {len(problems)} over the limits")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent))
