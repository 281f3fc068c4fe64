"""A minimal Windows x64 DLL that looks, to scripts/binary_facts.py, like a gauss_core module: a PE32+
x86-64 file exporting PyInit_gauss_core, importing pythonXY.dll, and carrying the module's BUILT_FOR
text. It has no code: test data for the packager, which reads headers only (the real Windows module is
cross-built and inspected by scripts/cross_check.sh, which this machine cannot run here fast enough for
pytest)."""
import struct

SECTION_RVA, SECTION_OFFSET, FILE_ALIGN = 0x1000, 0x200, 0x200


def pe_module(python="3.11", also=()):
    """also: more DLL names to import (each with an empty lookup table)."""
    dlls = [("python%s.dll" % python.replace(".", ""))] + list(also)
    export_name, module_name = b"PyInit_gauss_core\0", b"gauss_core.pyd\0"
    marker = ("gauss_core for CPython %s" % python).encode() + b"\0"
    # Section layout: import descriptors (one per DLL + terminator), an empty lookup table, the DLL
    # names, export directory, its tables and names, the marker.
    imports = 0
    lookup = imports + 20 * (len(dlls) + 1)
    names_of_dlls = b"".join(name.encode() + b"\0" for name in dlls)
    dll_at = lookup + 16
    exports = dll_at + len(names_of_dlls) + (-len(names_of_dlls)) % 4
    functions = exports + 40
    names = functions + 4
    ordinals = names + 4
    name_at = ordinals + 4
    module_at = name_at + len(export_name)
    marker_at = module_at + len(module_name)
    size = marker_at + len(marker)
    rva = lambda offset: SECTION_RVA + offset  # noqa: E731
    section = bytearray(size)
    at = dll_at
    for i, name in enumerate(dlls):
        struct.pack_into("<IIIII", section, imports + 20 * i, rva(lookup), 0, 0, rva(at), rva(lookup))
        at += len(name) + 1
    struct.pack_into("<Q", section, lookup, 0)  # no functions imported by name: an empty lookup table
    section[dll_at:dll_at + len(names_of_dlls)] = names_of_dlls
    struct.pack_into("<IIHHIIIIIII", section, exports, 0, 0, 0, 0, rva(module_at), 1, 1, 1,
                     rva(functions), rva(names), rva(ordinals))
    struct.pack_into("<I", section, functions, SECTION_RVA)
    struct.pack_into("<I", section, names, rva(name_at))
    struct.pack_into("<H", section, ordinals, 0)
    section[name_at:name_at + len(export_name)] = export_name
    section[module_at:module_at + len(module_name)] = module_name
    section[marker_at:marker_at + len(marker)] = marker
    raw_size = size + (-size) % FILE_ALIGN

    header = bytearray(SECTION_OFFSET)
    header[0:2] = b"MZ"
    struct.pack_into("<I", header, 0x3C, 0x40)
    header[0x40:0x44] = b"PE\0\0"
    optional_size = 112 + 16 * 8
    struct.pack_into("<HHIIIHH", header, 0x44, 0x8664, 1, 0, 0, 0, optional_size, 0x2022)  # DLL, large address aware
    optional = 0x58
    struct.pack_into("<HBBIIIIIQIIHHHHHHIIIIHHQQQQII", header, optional, 0x20B, 14, 0, 0, raw_size, 0, 0,
                     SECTION_RVA, 0x180000000, 0x1000, FILE_ALIGN, 6, 0, 0, 0, 6, 0, 0,
                     SECTION_RVA + raw_size + (-raw_size) % 0x1000, SECTION_OFFSET, 0, 3, 0x160,
                     0x100000, 0x1000, 0x100000, 0x1000, 0, 16)
    directories = optional + 112
    struct.pack_into("<II", header, directories, rva(exports), marker_at - exports)  # export table
    struct.pack_into("<II", header, directories + 8, rva(imports), 20 * (len(dlls) + 1))  # import table
    table = optional + optional_size
    struct.pack_into("<8sIIIIIIHHI", header, table, b".rdata", size, SECTION_RVA, raw_size, SECTION_OFFSET,
                     0, 0, 0, 0, 0x40000040)
    return bytes(header) + bytes(section) + bytes(raw_size - size)
