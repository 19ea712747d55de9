#!/usr/bin/env python3
"""Rewrites lcm-gen 1.3's `static const int8_t X = 1;` constants as `static constexpr`.

lcm-gen declares integer constants in class without a definition, so any ODR-use (binding one
to a const&, as std::max or EXPECT_EQ do) fails to link. A constexpr static member is
implicitly inline in C++17, which fixes that without changing the type or value.
Usage: constexpr_constants.py header.hpp...
"""
import re
import sys

PATTERN = re.compile(r"static const (u?int(?:8|16|32|64)_t)(\s+\w+\s*=)")

for path in sys.argv[1:]:
    with open(path, encoding="utf-8") as f:
        text = f.read()
    fixed = PATTERN.sub(r"static constexpr \1\2", text)
    if fixed != text:
        with open(path, "w", encoding="utf-8") as f:
            f.write(fixed)
