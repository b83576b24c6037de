#!/usr/bin/env python3
"""client::ErrorCode (client/include/client/types.h) names every value of
physics.wire.ErrorCode (proto/wire.proto) with the same number: ERROR_BAD_TOKEN = 2
is BadToken = 2, and nothing else is in it. (The TypeScript client's codes come
from the generated enum; client/web/client/test/error_codes.test.mjs ties them.)"""
import pathlib
import re
import sys

root = pathlib.Path(__file__).resolve().parents[2]


def enum_body(text, opening):
    start = text.index(opening)
    return text[start:text.index("}", start)]


def proto_codes():
    body = enum_body((root / "proto/wire.proto").read_text(), "enum ErrorCode {")
    codes = {}
    for name, number in re.findall(r"^\s*ERROR_([A-Z0-9_]+)\s*=\s*(\d+)\s*;", body, re.M):
        camel = "".join(word.capitalize() for word in name.split("_"))
        codes[camel] = int(number)
    return codes


def cpp_codes():
    body = enum_body((root / "client/include/client/types.h").read_text(),
                     "enum class ErrorCode")
    return {name: int(number) for name, number in re.findall(r"^\s*(\w+)\s*=\s*(\d+)\s*,", body, re.M)}


def main():
    proto = proto_codes()
    cpp = cpp_codes()
    problems = []
    if len(proto) < 20:
        problems.append(f"only {len(proto)} codes read from wire.proto")
    for name, number in sorted(proto.items(), key=lambda item: item[1]):
        if name not in cpp:
            problems.append(f"client::ErrorCode lacks {name} = {number}")
        elif cpp[name] != number:
            problems.append(f"client::ErrorCode::{name} is {cpp[name]}, wire.proto says {number}")
    for name in sorted(set(cpp) - set(proto)):
        problems.append(f"client::ErrorCode::{name} is not in wire.proto")
    for problem in problems:
        print(problem)
    print(f"{len(proto)} codes in wire.proto, {len(cpp)} in client::ErrorCode")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
