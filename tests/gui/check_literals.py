#!/usr/bin/env python3
"""Fails when a GUI source file hands a widget (or the status line, a job's name or detail)
English words of its own instead of catalogue words (app/gui/i18n/en.h, zh_CN.h through tr()).
A literal may hold ImGui ids ("##sieve", "###panel"), printf conversions ("%s", "%.4g") and
symbols; any two letters in a row outside those are words. Usage: check_literals.py APP_GUI_DIR"""
import pathlib
import re
import sys

# Calls whose string literal arguments are shown: every ImGui function, and the GUI's own
# helpers that put text on screen.
CALL = re.compile(
    r'\b(ImGui::\w+|item_tooltip|dialog_button|draw_config_section|set_status|set_name|'
    r'set_detail|job_\.start|AddText)\s*\(')
LITERAL = re.compile(r'"((?:[^"\\\n]|\\.)*)"')
CONVERSION = re.compile(r'%[-+ #0]*[0-9]*(?:\.[0-9]+)?[a-zA-Z%]')
# Literals that are the same in every language: keyboard keys and file extensions.
ALLOWED = {"Ctrl+O", "Ctrl+S", "Ctrl+E", "Ctrl+Q", "F12", "F1", "Enter", "Esc", "R",
           ".inp", ".msh", ".vtu", "dat"}


def arguments(text, start):
    """The call's arguments from `start` (just after its '(') to its ')', string literals and
    what they are compared with left out ("name == \"x\"" is no text shown), and for
    draw_config_section its first argument only (then come the tables' key names)."""
    depth, k, out = 1, start, []
    while k < len(text) and depth > 0:
        literal = LITERAL.match(text, k)
        if literal:
            before = text[start:k].rstrip()
            if not before.endswith(("==", "!=")):
                out.append(literal.group(0))
            k = literal.end()
            continue
        if text[k] == "(":
            depth += 1
        elif text[k] == ")":
            depth -= 1
        elif text[k] == "," and depth == 1 and text[start - 20:start].endswith("draw_config_section("):
            break
        out.append(text[k])
        k += 1
    return "".join(out)


def words(literal):
    shown = literal.split("##")[0]
    return re.search(r"[A-Za-z]{2}", CONVERSION.sub("", shown)) is not None


def main():
    folder = pathlib.Path(sys.argv[1])
    problems = []
    for path in sorted(folder.glob("*.cpp")):
        text = path.read_text(encoding="utf-8")
        for call in CALL.finditer(text):
            for literal in LITERAL.findall(arguments(text, call.end())):
                if literal not in ALLOWED and words(literal):
                    line = text.count("\n", 0, call.start()) + 1
                    problems.append(f'{path.name}:{line}: {call.group(1)}("{literal}")')
    for problem in problems:
        print(f"English words not from the catalogue: {problem}")
    if problems:
        sys.exit(1)
    print(f"check_literals: no widget takes English words of its own ({folder})")


if __name__ == "__main__":
    main()
