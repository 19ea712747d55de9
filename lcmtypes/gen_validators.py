#!/usr/bin/env python3
"""Generates rgnav's message validators from the .lcm files.

lcm-gen's C++ decoders trust the wire: a string length of 0 or below makes std::string::assign
throw, and an array count of 2^31 makes std::vector::resize allocate gigabytes before the
buffer length is checked; its encoders read past a vector whose count field is larger. So
every message goes through code generated here first:

  validate_wire<T>(buf, len, &why)   walks the encoded bytes without allocating: fingerprint,
                                      every length against the bytes left, every float and
                                      double finite, every `@enum PREFIX` field one of the
                                      struct's PREFIX* constants.
  counts_consistent(const T&, &why)  every count field equals its vector's size, recursively,
                                      so encode never reads past a vector.

Usage: gen_validators.py OUT_HEADER OUT_SOURCE file.lcm...
"""
import re
import sys

PRIMITIVE_SIZE = {
    "int8_t": 1, "byte": 1, "boolean": 1, "int16_t": 2, "int32_t": 4, "int64_t": 8,
    "float": 4, "double": 8,
}
INTEGER_READ = {"int8_t": "i8", "byte": "u8", "boolean": "i8", "int16_t": "i16",
                "int32_t": "i32", "int64_t": "i64"}


class Field:
    def __init__(self, type_name, name, dims, enum_prefix):
        self.type = type_name
        self.name = name
        self.dims = dims            # list of str: an integer literal or a field name
        self.enum_prefix = enum_prefix


class Struct:
    def __init__(self, name):
        self.name = name
        self.fields = []
        self.consts = {}            # name -> int value (integer constants only)


def strip_block_comments(text):
    return re.sub(r"/\*.*?\*/", "", text, flags=re.S)


def parse(path):
    text = strip_block_comments(open(path, encoding="utf-8").read())
    structs = []
    current = None
    for raw in text.splitlines():
        comment = raw.split("//", 1)[1] if "//" in raw else ""
        line = raw.split("//", 1)[0].strip()
        if not line or line.startswith("package"):
            continue
        m = re.match(r"struct\s+(\w+)", line)
        if m:
            current = Struct(m.group(1))
            structs.append(current)
            continue
        if line in ("{", "}"):
            continue
        if current is None:
            raise SystemExit(f"{path}: statement outside a struct: {line}")
        m = re.match(r"const\s+(\w+)\s+(.*);$", line)
        if m:
            for part in m.group(2).split(","):
                name, value = (s.strip() for s in part.split("="))
                if m.group(1) not in ("float", "double"):
                    current.consts[name] = int(value, 0)
            continue
        m = re.match(r"([\w.]+)\s+(\w+)((?:\s*\[\s*\w+\s*\])*)\s*;$", line)
        if not m:
            raise SystemExit(f"{path}: cannot parse: {line}")
        type_name = m.group(1).split(".")[-1]
        dims = re.findall(r"\[\s*(\w+)\s*\]", m.group(3))
        em = re.search(r"@enum\s+(\w+)", comment)
        current.fields.append(Field(type_name, m.group(2), dims, em.group(1) if em else None))
    return structs


def min_size(struct_name, structs, seen=()):
    """Smallest encoded size of one element of this type (no fingerprint), at least 1."""
    if struct_name in PRIMITIVE_SIZE:
        return PRIMITIVE_SIZE[struct_name]
    if struct_name == "string":
        return 5
    if struct_name in seen:
        return 1
    total = 0
    for f in structs[struct_name].fields:
        fixed = 1
        for d in f.dims:
            fixed = fixed * int(d) if d.isdigit() else 0
        total += fixed * min_size(f.type, structs, seen + (struct_name,))
    return max(total, 1)


def emit_walk(s, structs):
    out = [f"bool walk_{s.name}(Reader& r)", "{"]
    for f in s.fields:
        read = f"r.field(\"{f.name}\")"
        out.append(f"  {read};")
        if not f.dims:
            out.extend("  " + line for line in emit_scalar(s, f, structs, f"{s.name}_{f.name}"))
            continue
        # Arrays: compute element count, check it against the bytes left before walking.
        count_terms = []
        for d in f.dims:
            if d.isdigit():
                count_terms.append(d)
            else:
                count_terms.append(f"static_cast<int64_t>(v_{d})")
        out.append(f"  {{ const int64_t n = {' * '.join(count_terms)};")
        for d in f.dims:
            if not d.isdigit():
                out.append(f"    if (v_{d} < 0) return r.fail(\"negative count {d}\");")
        out.append(f"    if (!r.fits(n, {min_size(f.type, structs)})) return false;")
        if f.type in INTEGER_READ and not f.enum_prefix and f.type != "boolean":
            # Plain integer and byte arrays: any bit pattern is valid, skip them in one step.
            out.append(f"    r.skip(n * {PRIMITIVE_SIZE[f.type]}); }}")
            continue
        out.append("    for (int64_t i = 0; i < n; ++i) {")
        out.extend("      " + line for line in emit_scalar(s, f, structs, None))
        out.append("    } }")
    out.append("  return true;")
    out.append("}")
    return out


def emit_scalar(s, f, structs, keep_name):
    """Reads one element of field f; for scalar integer fields keeps the value as v_<name>."""
    t = f.type
    if t in ("float", "double"):
        return [f"if (!r.{'f32' if t == 'float' else 'f64'}()) return false;"]
    if t == "string":
        return ["if (!r.str()) return false;"]
    if t in INTEGER_READ:
        lines = []
        var = f"v_{f.name}" if keep_name else "v"
        lines.append(f"[[maybe_unused]] int64_t {var} = 0;")
        lines.append(f"if (!r.{INTEGER_READ[t]}(&{var})) return false;")
        if f.enum_prefix:
            values = sorted(v for k, v in s.consts.items() if k.startswith(f.enum_prefix)
                            and not k.startswith("NUM_"))
            if not values:
                raise SystemExit(f"{s.name}.{f.name}: @enum {f.enum_prefix} names no constants")
            cond = " && ".join(f"{var} != {v}" for v in values)
            lines.append(f"if ({cond}) return r.fail(\"value not in enum {f.enum_prefix}\");")
        if t == "boolean":
            lines.append(f"if ({var} != 0 && {var} != 1) return r.fail(\"boolean not 0 or 1\");")
        return lines
    if t in structs:
        return [f"if (!walk_{t}(r)) return false;"]
    raise SystemExit(f"{s.name}.{f.name}: unknown type {t}")


def emit_counts(s, structs):
    out = [f"bool counts_consistent(const {s.name}& m, std::string* why)", "{",
           "  (void)m;", "  (void)why;"]
    for f in s.fields:
        var_dims = [d for d in f.dims if not d.isdigit()]
        if len(var_dims) > 1 or (var_dims and f.dims[0].isdigit()):
            raise SystemExit(f"{s.name}.{f.name}: only the first dimension may be variable")
        if var_dims:
            d = var_dims[0]
            out.append(f"  if (m.{d} < 0 || static_cast<size_t>(m.{d}) != m.{f.name}.size())")
            out.append(f"    return set_why(why, \"{s.name}.{f.name}: {d} != size\");")
        if f.type in structs:
            if not f.dims:
                out.append(f"  if (!counts_consistent(m.{f.name}, why)) return false;")
            elif len(f.dims) == 1:
                out.append(f"  for (const auto& e : m.{f.name})")
                out.append("    if (!counts_consistent(e, why)) return false;")
            else:
                raise SystemExit(f"{s.name}.{f.name}: nested struct arrays of >1 dim unsupported")
        elif var_dims and len(f.dims) > 1:
            out.append(f"  for (const auto& row : m.{f.name})")
            out.append("    if (row.size() != " + f.dims[1] + "u)")
            out.append(f"      return set_why(why, \"{s.name}.{f.name}: row size\");")
    out.append("  return true;")
    out.append("}")
    return out


def main():
    header_path, source_path, *lcm_files = sys.argv[1:]
    structs = {}
    order = []
    for path in lcm_files:
        for s in parse(path):
            structs[s.name] = s
            order.append(s.name)
    order.sort()

    h = ["// Generated by lcmtypes/gen_validators.py from lcmtypes/*.lcm. Do not edit.",
         "#pragma once", "#include <cstddef>", "#include <string>"]
    h += [f"#include \"rgnav/{n}.hpp\"" for n in order]
    # Top-level message types: those with `int64_t utime` first (nested value types have none).
    top = [n for n in order if structs[n].fields and structs[n].fields[0].name == "utime"]
    h += ["", "// X(type) for every rgnav message type that is published on its own channel.",
          "#define RGNAV_FOR_EACH_MESSAGE_TYPE(X) " + " ".join(f"X({n})" for n in top),
          "// X(type) for every rgnav type, nested value types included.",
          "#define RGNAV_FOR_EACH_TYPE(X) " + " ".join(f"X({n})" for n in order)]
    h += ["", "namespace rgnav {", ""]
    for n in order:
        h.append(f"bool counts_consistent(const {n}& m, std::string* why);")
    h += ["", "namespace wire {",
          "// Walks an encoded message (with fingerprint) without allocating; false + why on",
          "// the first problem. Specialised for every rgnav type.",
          "template <class T> bool validate(const void* buf, size_t len, std::string* why);"]
    for n in order:
        h.append(f"template <> bool validate<{n}>(const void* buf, size_t len, std::string* why);")
    h += ["}  // namespace wire", "}  // namespace rgnav", ""]

    c = ["// Generated by lcmtypes/gen_validators.py from lcmtypes/*.lcm. Do not edit.",
         f"#include \"{header_path.split('/')[-1]}\"",
         "#include \"wire_reader.h\"", "", "namespace rgnav {", "namespace {",
         "bool set_why(std::string* why, const char* text) { if (why) *why = text; return false; }",
         "using rgnav::wire::Reader;"]
    for n in order:
        c.append(f"bool walk_{n}(Reader& r);")
    for n in order:
        c += emit_walk(structs[n], structs)
    c += ["}  // namespace", ""]
    for n in order:
        c += emit_counts(structs[n], structs)
    c += ["", "namespace wire {"]
    for n in order:
        c += [f"template <> bool validate<{n}>(const void* buf, size_t len, std::string* why)",
              "{",
              f"  Reader r(buf, len, \"{n}\");",
              f"  if (!r.fingerprint({n}::getHash()) || !walk_{n}(r) || !r.at_end()) {{",
              "    if (why) *why = r.error();", "    return false;", "  }",
              "  return true;", "}"]
    c += ["}  // namespace wire", "}  // namespace rgnav", ""]

    open(header_path, "w", encoding="utf-8").write("\n".join(h))
    open(source_path, "w", encoding="utf-8").write("\n".join(c))


if __name__ == "__main__":
    main()
