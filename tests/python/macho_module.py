"""A minimal macOS module file that looks, to scripts/binary_facts.py, like a gauss_core module: a thin
64-bit Mach-O bundle with LC_BUILD_VERSION, the libraries it links and the module's BUILT_FOR text,
optionally with an ad-hoc code signature (a CodeDirectory of SHA-256 page hashes, as Apple's and
zig's linkers write for arm64). It has no code: test data for the inspectors (the real macOS modules
are cross-built by scripts/cross_check.sh)."""
import hashlib
import struct

CPU = {"arm64": 0x0100000C, "x86_64": 0x01000007}
PAGE = 4096


def _version(text):
    parts = [int(p) for p in text.split(".")] + [0, 0]
    return parts[0] << 16 | parts[1] << 8 | parts[2]


def macho_module(arch="arm64", python="3.13", minos="11.0", libraries=("/usr/lib/libSystem.B.dylib",),
                 signed=True):
    commands = [struct.pack("<IIIIII", 0x32, 24, 1, _version(minos), _version("14.0"), 0)]  # LC_BUILD_VERSION
    for name in libraries:
        raw = name.encode() + b"\0"
        raw += b"\0" * (-(24 + len(raw)) % 8)
        commands.append(struct.pack("<IIIIII", 0xC, 24 + len(raw), 24, 2, 0x10000, 0x10000) + raw)  # LC_LOAD_DYLIB
    signature_command = 16 if signed else 0
    size_of_commands = sum(map(len, commands)) + signature_command
    body = b"\0" * 64 + ("gauss_core for CPython %s" % python).encode() + b"\0" + b"\xab" * 5000
    code_limit = 32 + size_of_commands + len(body)
    code_limit += -code_limit % 16
    header = struct.pack("<IiiIIIII", 0xFEEDFACF, CPU[arch], 0, 8, len(commands) + bool(signed),
                         size_of_commands, 0, 0)
    if not signed:
        return (header + b"".join(commands) + body).ljust(code_limit, b"\0")
    identifier = b"gauss_core\0"
    slots = (code_limit + PAGE - 1) // PAGE
    directory_length = 44 + len(identifier) + 32 * slots
    blob_length = 20 + directory_length
    commands.append(struct.pack("<IIII", 0x1D, 16, code_limit, blob_length))  # LC_CODE_SIGNATURE
    signed_part = (header + b"".join(commands) + body).ljust(code_limit, b"\0")
    hashes = b"".join(hashlib.sha256(signed_part[i * PAGE:min((i + 1) * PAGE, code_limit)]).digest()
                      for i in range(slots))
    directory = struct.pack(">IIIIIIIIIBBBBI", 0xFADE0C02, directory_length, 0x20001, 0x2,  # CS_ADHOC
                            44 + len(identifier), 44, 0, slots, code_limit, 32, 2, 0, 12, 0)
    superblob = struct.pack(">IIIII", 0xFADE0CC0, blob_length, 1, 0, 20)
    return signed_part + superblob + directory + identifier + hashes
