"""scripts/binary_facts.py and scripts/check_cross_module.py, which judge the Windows and macOS modules
scripts/cross_check.sh builds, on module-shaped files made here (pe_module.py, macho_module.py): what
they accept and every way they refuse. The real modules are checked by cross_check.sh itself."""
import sys

from conftest import REPO
from macho_module import macho_module
from pe_module import pe_module

sys.path.insert(0, str(REPO / "scripts"))
import binary_facts  # noqa: E402
import check_cross_module  # noqa: E402


def test_a_windows_module_of_its_python_and_system_dlls_passes():
    good, line = check_cross_module.check("windows-x64", "3.13", "11.0", pe_module("3.13", also=["KERNEL32.dll", "msvcrt.dll"]))
    assert good and line == "built, imports python313.dll KERNEL32.dll msvcrt.dll", line


def test_a_windows_module_with_a_mingw_runtime_dll_or_another_python_is_refused():
    good, why = check_cross_module.check("windows-x64", "3.13", "11.0", pe_module("3.13", also=["libstdc++-6.dll"]))
    assert not good and "not every Windows has: libstdc++-6.dll" in why, why
    good, why = check_cross_module.check("windows-x64", "3.13", "11.0", pe_module("3.11"))
    assert not good and "built for Python 3.11, not 3.13" in why and "python311.dll" in why, why
    good, why = check_cross_module.check("windows-x64", "3.13", "11.0", macho_module("x86_64", "3.13"))
    assert not good and "a Mach-O x86_64 file, not PE32+ x86_64" in why, why


def test_an_ad_hoc_signed_arm64_module_passes_and_its_signature_is_verified():
    data = macho_module("arm64", "3.11")
    facts = binary_facts.facts(data)
    assert (facts["format"], facts["arch"], facts["minos"], facts["signature"], facts["python"]) == \
        ("Mach-O", "arm64", "11.0", "ad-hoc", "3.11")
    good, line = check_cross_module.check("macos-arm64", "3.11", "11.0", data)
    assert good and line == "built, minos 11.0, ad-hoc signed", line
    tampered = bytearray(data)
    tampered[300] ^= 1  # a byte of the signed range changed after signing
    assert binary_facts.facts(bytes(tampered))["signature"] == "invalid (page 0 does not match its hash)"


def test_macos_modules_are_refused_for_a_missing_signature_a_newer_macos_or_foreign_libraries():
    good, why = check_cross_module.check("macos-arm64", "3.13", "11.0", macho_module(signed=False))
    assert not good and "code signature: none" in why, why
    good, why = check_cross_module.check("macos-x64", "3.13", "11.0", macho_module(
        "x86_64", minos="13.0", libraries=("/usr/lib/libSystem.B.dylib", "/opt/homebrew/lib/libomp.dylib")))
    assert not good and "minimum macOS 13.0, not 11.0" in why and "libomp.dylib" in why, why
    good, line = check_cross_module.check("macos-x64", "3.13", "11.0", macho_module(
        "x86_64", libraries=("/usr/lib/libSystem.B.dylib", "/usr/lib/libc++.1.dylib"), signed=False))
    assert good and line == "built, minos 11.0", line
