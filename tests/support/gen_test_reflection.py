#!/usr/bin/env python3
"""Generates test-only reflection over the rgnav lcmtypes, from the same .lcm parse as
lcmtypes/gen_validators.py (imported, so the two never disagree about the contract):

  wire_layout<T>(buf, len)  walks a *valid* encoding and lists the byte offset of every count
                            field, string length, float, double, enum and boolean in it, with
                            the enum's allowed values. The fuzz tests corrupt exactly those.
  to_json(const T&)         a canonical JSON text of a message: keys sorted, floats and doubles
                            as their IEEE-754 bit patterns (exact), 8-bit integers unsigned.
                            The Java contract test prints the same form from the Java classes,
                            so C++ and Java can be compared field by field.

Usage: gen_test_reflection.py LCMTYPES_DIR OUT_HEADER OUT_SOURCE file.lcm...
"""
import os
import sys

PRIMITIVE_SIZE = {"int8_t": 1, "byte": 1, "boolean": 1, "int16_t": 2, "int32_t": 4,
                  "int64_t": 8, "float": 4, "double": 8}


def load(lcmtypes_dir, lcm_files):
    sys.path.insert(0, lcmtypes_dir)
    import gen_validators  # noqa: E402  (the contract's own parser)
    structs = {}
    for path in lcm_files:
        for s in gen_validators.parse(path):
            structs[s.name] = s
    return structs


def count_fields(s):
    names = set()
    for f in s.fields:
        names.update(d for d in f.dims if not d.isdigit())
    return names


def emit_layout(s, structs):
    counts = count_fields(s)
    out = [f"void layout_{s.name}(Cursor& c, std::vector<WireSlot>* out, const std::string& path)",
           "{", "  (void)out;", "  (void)path;"]

    def element(f, path_expr, keep):
        t = f.type
        if t == "float":
            return [f"out->push_back({{c.pos, SlotKind::kFloat, 4, {{}}, {path_expr}}}); c.skip(4);"]
        if t == "double":
            return [f"out->push_back({{c.pos, SlotKind::kDouble, 8, {{}}, {path_expr}}}); c.skip(8);"]
        if t == "string":
            return [f"out->push_back({{c.pos, SlotKind::kStringLength, 4, {{}}, {path_expr}}});",
                    "c.skip(4 + c.int_at(c.pos, 4));"]
        if t in PRIMITIVE_SIZE:
            size = PRIMITIVE_SIZE[t]
            lines = []
            if keep:
                lines.append(f"v_{f.name} = c.int_at(c.pos, {size});")
            if f.enum_prefix:
                values = sorted(v for k, v in s.consts.items()
                                if k.startswith(f.enum_prefix) and not k.startswith("NUM_"))
                allowed = ", ".join(str(v) for v in values)
                lines.append(f"out->push_back({{c.pos, SlotKind::kEnum, {size}, {{{allowed}}}, "
                             f"{path_expr}}});")
            elif t == "boolean":
                lines.append(f"out->push_back({{c.pos, SlotKind::kBoolean, 1, {{0, 1}}, {path_expr}}});")
            elif keep:
                lines.append(f"out->push_back({{c.pos, SlotKind::kCount, {size}, {{}}, {path_expr}}});")
            lines.append(f"c.skip({size});")
            return lines
        return [f"layout_{t}(c, out, {path_expr});"]

    for f in s.fields:
        if f.name in counts:
            out.append(f"  int64_t v_{f.name} = 0;")
    for f in s.fields:
        name_expr = f"path + \".{f.name}\""
        if not f.dims:
            out += ["  " + line for line in element(f, name_expr, f.name in counts)]
            continue
        terms = [d if d.isdigit() else f"v_{d}" for d in f.dims]
        out.append(f"  {{ const int64_t n = {' * '.join(terms)};")
        if f.type in PRIMITIVE_SIZE and f.type not in ("float", "double", "boolean") \
                and not f.enum_prefix:
            out.append(f"    c.skip(n * {PRIMITIVE_SIZE[f.type]}); }}")
            continue
        out.append("    for (int64_t i = 0; i < n; ++i) {")
        elem_path = f"{name_expr} + \"[\" + std::to_string(i) + \"]\""
        out += ["      " + line for line in element(f, elem_path, False)]
        out.append("    } }")
    out.append("}")
    return out


def cpp_elem_json(t, expr, structs):
    if t == "float":
        return f"j_float(os, {expr});"
    if t == "double":
        return f"j_double(os, {expr});"
    if t == "string":
        return f"j_string(os, {expr});"
    if t == "boolean":
        return f"os << (({expr}) ? \"true\" : \"false\");"
    if t in ("int8_t", "byte"):
        return f"os << static_cast<int>(static_cast<uint8_t>({expr}));"
    if t in PRIMITIVE_SIZE:
        return f"os << static_cast<int64_t>({expr});"
    return f"j_{t}(os, {expr});"


def emit_json(s, structs):
    out = [f"void j_{s.name}(std::ostream& os, const {s.name}& m)", "{", "  os << '{';"]
    first = True
    for f in sorted(s.fields, key=lambda f: f.name):
        out.append(f"  os << \"{'' if first else ','}\\\"{f.name}\\\":\";")
        first = False
        if not f.dims:
            out.append("  " + cpp_elem_json(f.type, f"m.{f.name}", structs))
            continue
        # Nested loops over every dimension, fixed or variable.
        idx = []
        expr = f"m.{f.name}"
        indent = "  "
        for level, d in enumerate(f.dims):
            i = f"i{level}"
            bound = d if d.isdigit() else f"m.{d}"
            out.append(f"{indent}os << '[';")
            out.append(f"{indent}for (int64_t {i} = 0; {i} < static_cast<int64_t>({bound}); ++{i}) {{")
            out.append(f"{indent}  if ({i}) os << ',';")
            indent += "  "
            idx.append(i)
            expr += f"[{i}]"
        out.append(indent + cpp_elem_json(f.type, expr, structs))
        for _ in f.dims:
            indent = indent[:-2]
            out.append(f"{indent}}}")
            out.append(f"{indent}os << ']';")
    out += ["  os << '}';", "}"]
    return out


def main():
    lcmtypes_dir, header_path, source_path, *lcm_files = sys.argv[1:]
    structs = load(lcmtypes_dir, lcm_files)
    order = sorted(structs)

    h = ["// Generated by tests/support/gen_test_reflection.py from lcmtypes/*.lcm. Do not edit.",
         "// Test-only reflection: where each kind of field sits in an encoding, and a canonical",
         "// JSON form of a message (see the generator's docstring).",
         "#pragma once", "#include <cstddef>", "#include <cstdint>", "#include <string>",
         "#include <vector>", "#include \"rgnav_validators.hpp\"", "",
         "namespace rgnav::testing {", "",
         "enum class SlotKind { kCount, kStringLength, kFloat, kDouble, kEnum, kBoolean };", "",
         "struct WireSlot", "{",
         "  size_t offset;                // byte offset in the encoding (fingerprint included)",
         "  SlotKind kind;",
         "  int size;                     // bytes",
         "  std::vector<int64_t> allowed; // kEnum / kBoolean: the valid values",
         "  std::string field;            // path, e.g. \".scan.ranges[3]\"",
         "};", "",
         "// Offsets of every slot in a valid encoding of T (throws std::invalid_argument if the",
         "// bytes do not walk to exactly `len`).",
         "template <class T> std::vector<WireSlot> wire_layout(const uint8_t* buf, size_t len);",
         "// Canonical JSON of a message (keys sorted; floats as IEEE bit patterns).",
         "template <class T> std::string to_json(const T& msg);"]
    for n in order:
        h.append(f"template <> std::vector<WireSlot> wire_layout<{n}>(const uint8_t* buf, size_t len);")
        h.append(f"template <> std::string to_json<{n}>(const {n}& msg);")
    h += ["", "}  // namespace rgnav::testing", ""]

    c = ["// Generated by tests/support/gen_test_reflection.py from lcmtypes/*.lcm. Do not edit.",
         f"#include \"{os.path.basename(header_path)}\"", "",
         "#include <cstring>", "#include <sstream>", "#include <stdexcept>", "",
         "namespace rgnav::testing {", "namespace {", "",
         "struct Cursor", "{",
         "  const uint8_t* buf;", "  size_t len;", "  size_t pos;",
         "  void skip(int64_t n)", "  {",
         "    if (n < 0 || static_cast<size_t>(n) > len - pos)",
         "      throw std::invalid_argument(\"wire_layout: not a valid encoding\");",
         "    pos += static_cast<size_t>(n);", "  }",
         "  int64_t int_at(size_t at, int size) const", "  {",
         "    if (static_cast<size_t>(size) > len - at)",
         "      throw std::invalid_argument(\"wire_layout: not a valid encoding\");",
         "    uint64_t u = 0;", "    for (int i = 0; i < size; ++i) u = (u << 8) | buf[at + i];",
         "    const int shift = 64 - 8 * size;",
         "    return static_cast<int64_t>(u << shift) >> shift;  // sign-extend", "  }", "};", "",
         "void j_float(std::ostream& os, float f)", "{",
         "  uint32_t u;", "  std::memcpy(&u, &f, 4);", "  os << u;", "}",
         "void j_double(std::ostream& os, double d)", "{",
         "  uint64_t u;", "  std::memcpy(&u, &d, 8);", "  os << u;", "}",
         "void j_string(std::ostream& os, const std::string& s)", "{",
         "  static const char* hex = \"0123456789abcdef\";",
         "  os << '\"';",
         "  for (unsigned char ch : s) {",
         "    if (ch == '\"' || ch == '\\\\') os << '\\\\' << ch;",
         "    else if (ch < 0x20 || ch >= 0x7f) os << \"\\\\u00\" << hex[ch >> 4] << hex[ch & 15];",
         "    else os << ch;", "  }", "  os << '\"';", "}", ""]
    for n in order:
        c.append(f"void layout_{n}(Cursor& c, std::vector<WireSlot>* out, const std::string& path);")
        c.append(f"void j_{n}(std::ostream& os, const {n}& m);")
    for n in order:
        c += emit_layout(structs[n], structs)
        c += emit_json(structs[n], structs)
    c += ["", "}  // namespace", ""]
    for n in order:
        c += [f"template <> std::vector<WireSlot> wire_layout<{n}>(const uint8_t* buf, size_t len)",
              "{", "  Cursor c{buf, len, 0};", "  c.skip(8);  // fingerprint",
              "  std::vector<WireSlot> out;", f"  layout_{n}(c, &out, \"\");",
              "  if (c.pos != len) throw std::invalid_argument(\"wire_layout: trailing bytes\");",
              "  return out;", "}",
              f"template <> std::string to_json<{n}>(const {n}& msg)", "{",
              "  std::ostringstream os;", f"  j_{n}(os, msg);", "  return os.str();", "}"]
    c += ["", "}  // namespace rgnav::testing", ""]

    open(header_path, "w", encoding="utf-8").write("\n".join(h))
    open(source_path, "w", encoding="utf-8").write("\n".join(c))


if __name__ == "__main__":
    main()
