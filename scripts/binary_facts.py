#!/usr/bin/env python3
"""What a compiled gauss_core module is, read from its bytes: file format, architecture, the libraries it
imports, what it exports (Windows), its minimum macOS and code signature (Mach-O), and the Python it
was built for.

    python3 scripts/binary_facts.py FILE      prints the facts as JSON

Used by scripts/cross_check.sh (the cross-built modules) and scripts/package_addon.py (every wheel's
module against the wheel's tag). Reads ELF, PE32+ and thin 64-bit Mach-O files, little-endian, with
the standard library only.

The Python: a Windows module imports pythonXY.dll; a Linux or macOS module links no libpython, so the
module carries the text "gauss_core for CPython X.Y" (cpp/python/module.cpp, BUILT_FOR).
"""

import hashlib
import json
import re
import struct
import sys

PE_MACHINES = {0x8664: "x86_64", 0xAA64: "arm64", 0x14C: "x86"}
ELF_MACHINES = {0x3E: "x86_64", 0xB7: "arm64", 0x03: "x86"}
MACHO_CPUS = {0x01000007: "x86_64", 0x0100000C: "arm64"}
MARKER = re.compile(rb"gauss_core for CPython (\d+)\.(\d+)\x00")
PYTHON_DLL = re.compile(r"^python(\d)(\d+)\.dll$", re.I)

# Mach-O load commands and code-signing blobs (Apple's loader.h and cs_blobs.h)
LC_LOAD_DYLIB, LC_LOAD_WEAK_DYLIB, LC_REEXPORT_DYLIB = 0xC, 0x80000018, 0x8000001F
LC_CODE_SIGNATURE, LC_VERSION_MIN_MACOSX, LC_BUILD_VERSION = 0x1D, 0x24, 0x32
CSMAGIC_EMBEDDED_SIGNATURE, CSMAGIC_CODEDIRECTORY, CSSLOT_SIGNATURESLOT = 0xFADE0CC0, 0xFADE0C02, 0x10000
CS_ADHOC = 0x2
HASHES = {1: "sha1", 2: "sha256"}


class NotABinary(ValueError):
    pass


def _cstring(data, offset):
    end = data.index(b"\0", offset)
    return data[offset:end].decode("utf-8", "replace")


def _pe(data):
    offset = struct.unpack_from("<I", data, 0x3C)[0]
    if data[offset:offset + 4] != b"PE\0\0":
        raise NotABinary("MZ header without a PE signature")
    machine, sections, _, _, _, optional_size, _ = struct.unpack_from("<HHIIIHH", data, offset + 4)
    optional = offset + 24
    magic = struct.unpack_from("<H", data, optional)[0]
    if magic != 0x20B:
        return {"format": "PE32", "arch": PE_MACHINES.get(machine, hex(machine)), "imports": [], "exports": []}
    directories = optional + 112
    table = optional + optional_size
    spans = []
    for i in range(sections):
        _, virtual_size, address, raw_size, raw_offset = struct.unpack_from("<8sIIII", data, table + 40 * i)
        spans.append((address, max(virtual_size, raw_size), raw_offset))

    def at(rva):
        for address, size, raw in spans:
            if address <= rva < address + size:
                return raw + rva - address
        raise NotABinary("RVA %#x is in no section" % rva)

    export_rva, export_size, import_rva, _ = struct.unpack_from("<IIII", data, directories)
    imports = []
    if import_rva:
        entry = at(import_rva)
        while True:
            lookup, _, _, name_rva, thunk = struct.unpack_from("<IIIII", data, entry)
            if not (lookup or name_rva or thunk):
                break
            imports.append(_cstring(data, at(name_rva)))
            entry += 20
    exports = []
    if export_rva and export_size:
        directory = at(export_rva)
        count, names_rva = struct.unpack_from("<I", data, directory + 24)[0], struct.unpack_from("<I", data, directory + 32)[0]
        for i in range(count):
            exports.append(_cstring(data, at(struct.unpack_from("<I", data, at(names_rva) + 4 * i)[0])))
    return {"format": "PE32+", "arch": PE_MACHINES.get(machine, hex(machine)), "imports": imports,
            "exports": sorted(exports)}


def _elf(data):
    if data[4] != 2 or data[5] != 1:
        return {"format": "ELF32" if data[4] == 1 else "ELF (big-endian)", "arch": "?", "imports": []}
    machine = struct.unpack_from("<H", data, 18)[0]
    section_offset = struct.unpack_from("<Q", data, 0x28)[0]
    entry_size, count = struct.unpack_from("<HH", data, 0x3A)
    sections = [struct.unpack_from("<IIQQQQIIQQ", data, section_offset + i * entry_size) for i in range(count)]
    needed = []
    for _, kind, _, _, offset, size, link, _, _, _ in sections:
        if kind == 6:  # SHT_DYNAMIC
            strings = sections[link][4]
            for i in range(0, size, 16):
                tag, value = struct.unpack_from("<qQ", data, offset + i)
                if tag == 0:
                    break
                if tag == 1:  # DT_NEEDED
                    needed.append(_cstring(data, strings + value))
    return {"format": "ELF64", "arch": ELF_MACHINES.get(machine, hex(machine)), "imports": needed}


def _version(packed):
    return "%d.%d" % (packed >> 16, (packed >> 8) & 0xFF) + (".%d" % (packed & 0xFF) if packed & 0xFF else "")


def _code_signature(data, offset, size):
    """'ad-hoc' (a signature without a certificate whose page hashes match the file), 'signed' (with a
    certificate), or what is wrong."""
    magic, _, count = struct.unpack_from(">III", data, offset)
    if magic != CSMAGIC_EMBEDDED_SIGNATURE:
        return "invalid (no embedded signature blob)"
    directory, certificate = None, False
    for i in range(count):
        slot, blob = struct.unpack_from(">II", data, offset + 12 + 8 * i)
        blob_magic, blob_length = struct.unpack_from(">II", data, offset + blob)
        if blob_magic == CSMAGIC_CODEDIRECTORY and directory is None:
            directory = offset + blob
        if slot == CSSLOT_SIGNATURESLOT and blob_length > 8:
            certificate = True
    if directory is None:
        return "invalid (no code directory)"
    (_, _, _, flags, hash_offset, _, _, code_slots, code_limit, hash_size, hash_type, _,
     page_shift) = struct.unpack_from(">IIIIIIIIIBBBB", data, directory)
    algorithm = HASHES.get(hash_type)
    if algorithm is None:
        return "invalid (hash type %d)" % hash_type
    page = 1 << page_shift
    for i in range(code_slots):
        chunk = data[i * page:min((i + 1) * page, code_limit)]
        expected = data[directory + hash_offset + i * hash_size:directory + hash_offset + (i + 1) * hash_size]
        if hashlib.new(algorithm, chunk).digest()[:hash_size] != expected:
            return "invalid (page %d does not match its hash)" % i
    if code_limit > offset:
        return "invalid (the signed range covers the signature)"
    if certificate:
        return "signed"
    return "ad-hoc" if flags & CS_ADHOC else "invalid (no certificate, not ad-hoc)"


def _macho(data):
    cpu, _, _, commands, _ = struct.unpack_from("<iIIII", data, 4)
    facts = {"format": "Mach-O", "arch": MACHO_CPUS.get(cpu & 0xFFFFFFFF, hex(cpu & 0xFFFFFFFF)), "imports": [],
             "minos": None, "signature": "none"}
    offset = 32
    for _ in range(commands):
        command, size = struct.unpack_from("<II", data, offset)
        if command in (LC_LOAD_DYLIB, LC_LOAD_WEAK_DYLIB, LC_REEXPORT_DYLIB):
            facts["imports"].append(_cstring(data, offset + struct.unpack_from("<I", data, offset + 8)[0]))
        elif command == LC_BUILD_VERSION:
            facts["minos"] = _version(struct.unpack_from("<I", data, offset + 12)[0])
        elif command == LC_VERSION_MIN_MACOSX:
            facts["minos"] = _version(struct.unpack_from("<I", data, offset + 8)[0])
        elif command == LC_CODE_SIGNATURE:
            facts["signature"] = _code_signature(data, *struct.unpack_from("<II", data, offset + 8))
        offset += size
    return facts


def facts(data):
    """The facts of a binary's bytes; NotABinary if it is none of the formats a module can have."""
    if data[:2] == b"MZ":
        result = _pe(data)
    elif data[:4] == b"\x7fELF":
        result = _elf(data)
    elif data[:4] == b"\xcf\xfa\xed\xfe":
        result = _macho(data)
    elif data[:4] in (b"\xca\xfe\xba\xbe", b"\xbe\xba\xfe\xca"):
        return {"format": "Mach-O universal", "arch": "several", "imports": [], "python": None}
    else:
        raise NotABinary("not an ELF, PE or Mach-O file (starts with %s)" % data[:4].hex())
    python = [m for m in (PYTHON_DLL.match(name) for name in result["imports"]) if m]
    marker = MARKER.search(data)
    result["python"] = ("%s.%s" % python[0].groups() if python else
                        "%s.%s" % (marker.group(1).decode(), marker.group(2).decode()) if marker else None)
    return result


def describe(result):
    """'PE32+ x86_64', 'Mach-O arm64', 'ELF64 x86_64'."""
    return "%s %s" % (result["format"], result["arch"])


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    with open(sys.argv[1], "rb") as handle:
        data = handle.read()
    try:
        print(json.dumps(facts(data), indent=1))
    except NotABinary as exc:
        sys.exit("binary_facts.py: %s: %s" % (sys.argv[1], exc))


if __name__ == "__main__":
    main()
