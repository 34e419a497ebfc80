#!/usr/bin/env python3
"""Is the machine code of the relighting kernels the same in two builds?

Usage: scripts/kernel_code.py [--diff] OLD_BUILD NEW_BUILD
       scripts/kernel_code.py --list BUILD      (each kernel's object file)
(scripts/kernel-code.sh calls this.) Exit status 0 when every kernel is identical, 1 when one
differs, 2 when a kernel cannot be found once in each build.

The kernels are the object files that define them, found by symbol, not by path, so that a
source file may move or be renamed: the object defining `Relighter::shade_using` (diffuse SH,
prt/src/diffuse/relighter.cpp), `GlossyKernel::create` (glossy/kernel.cpp) and `CpcaKernel::create`
(glossy/cpca_kernel.cpp), in any namespace; the source's file name is the fallback.

Every function of each object (`objdump -dr --no-show-raw-insn`: its own helpers, the inline
and template functions it instantiates, the `.cold` parts) is normalised and compared by
mangled name:
  * addresses dropped: instruction offsets, the `# addr <...>` comments of RIP-relative
    operands, the placeholder target of a relocated branch, and the address of every other
    branch target, which keeps its `<symbol+offset>` (offsets within a function are the
    code's own layout), and the no-op padding after a function's last instruction, which
    aligns whatever follows it;
  * relocations replaced by what they refer to, so that the numbering of `.LC` labels and
    where unrelated data sits in `.bss` or `.rodata` do not count: a constant-pool entry
    (`.rodata.cstN`) by its N bytes, a string by its text, code by `function+offset`, data by
    the local symbol covering it (else the section's name), any other symbol by its name.
A function found in only one of the two objects is looked up in the other build's objects
(moved to another file): it counts as identical when it is identical there.
"""
import difflib
import os
import re
import struct
import subprocess
import sys

KERNELS = [  # name, demangled symbol that identifies the object, source file name fallback
    ("relighter", r"(^|::)Relighter::shade_using\(", "relighter.cpp"),
    ("glossy_kernel", r"(^|::)GlossyKernel::create\(", "glossy_kernel.cpp"),
    ("cpca_kernel", r"(^|::)CpcaKernel::create\(", "cpca_kernel.cpp"),
]


class Elf:
    """The sections and symbols of a relocatable x86-64 ELF object."""

    def __init__(self, path):
        with open(path, "rb") as f:
            self.data = data = f.read()
        if data[:4] != b"\x7fELF" or data[4] != 2:
            raise ValueError(f"{path}: not a 64-bit ELF object")
        shoff, = struct.unpack_from("<Q", data, 0x28)
        shentsize, shnum, shstrndx = struct.unpack_from("<HHH", data, 0x3A)
        self.sections = []
        for i in range(shnum):
            name, kind, flags, _, off, size, link, _, _, entsize = struct.unpack_from(
                "<IIQQQQIIQQ", data, shoff + i * shentsize)
            self.sections.append({"name_off": name, "type": kind, "flags": flags, "off": off,
                                  "size": size, "link": link, "entsize": entsize})
        names = self.sections[shstrndx]
        for s in self.sections:
            s["name"] = self._string(names["off"] + s["name_off"])
        self.symbols = []
        for s in self.sections:
            if s["type"] != 2:  # SHT_SYMTAB
                continue
            strtab = self.sections[s["link"]]
            for j in range(s["size"] // 24):
                name, info, _, shndx, value, size = struct.unpack_from(
                    "<IBBHQQ", data, s["off"] + j * 24)
                self.symbols.append({"name": self._string(strtab["off"] + name),
                                     "type": info & 0xF, "shndx": shndx, "value": value,
                                     "size": size})
        self.by_name = {}
        for sym in self.symbols:
            if sym["name"] and 0 < sym["shndx"] < len(self.sections):
                self.by_name.setdefault(sym["name"], sym)

    def _string(self, off):
        return self.data[off:self.data.index(b"\0", off)].decode("utf-8", "replace")

    def describe(self, section_index, offset):
        """What lies at `offset` in a section, independent of where that section's data sits."""
        s = self.sections[section_index]
        name = s["name"]
        if s["flags"] & 0x4:  # SHF_EXECINSTR: the function covering it
            for sym in self.symbols:
                if (sym["shndx"] == section_index and sym["type"] == 2
                        and sym["value"] <= offset < sym["value"] + max(sym["size"], 1)):
                    return f"{sym['name']}+{offset - sym['value']:#x}"
            return f"{name}+{offset:#x}"
        if s["flags"] & 0x10:  # SHF_MERGE: constants by value, strings by text
            if s["type"] == 8:
                return f"{name}:?"
            raw = self.data[s["off"]:s["off"] + s["size"]]
            if s["flags"] & 0x20:  # SHF_STRINGS
                end = raw.find(b"\0", offset)
                return f"str{raw[offset:end if end >= 0 else None]!r}"
            n = s["entsize"] or 1
            start = offset - offset % n
            return f"const[{raw[start:start + n].hex()}]+{offset % n}"
        for sym in self.symbols:  # data: the local object covering it
            if (sym["shndx"] == section_index and sym["type"] == 1
                    and sym["value"] <= offset < sym["value"] + max(sym["size"], 1)):
                return f"{sym['name']}+{offset - sym['value']:#x}"
        return name


INSN = re.compile(r"^\s*([0-9a-f]+):\t(.*)$")
FUNC = re.compile(r"^[0-9a-f]+ <(.+)>:$")
RELOC = re.compile(r"^([0-9a-f]+): (R_X86_64_\w+)\t(.+?)(?:([-+])0x([0-9a-f]+))?$")
PADDING = re.compile(r"^((cs |data16 )*nop\w*|xchg %ax,%ax)( |$)")
PC_RELATIVE = {"R_X86_64_PC32", "R_X86_64_PLT32", "R_X86_64_GOTPCREL", "R_X86_64_GOTPCRELX",
               "R_X86_64_REX_GOTPCRELX", "R_X86_64_PC64"}


def normalised_functions(path):
    """{mangled function name: [normalised instruction, ...]} of one object file."""
    elf = Elf(path)
    text = subprocess.run(["objdump", "-dr", "-w", "--no-show-raw-insn", path], check=True,
                          capture_output=True, text=True).stdout
    functions, current, insns = {}, None, []  # insns: [address, text, relocations]
    for line in text.splitlines():
        m = FUNC.match(line)
        if m:
            current = m.group(1)
            insns = functions.setdefault(current, [])
            continue
        m = INSN.match(line)
        if not m or current is None:
            continue
        fields = m.group(2).split("\t")
        body, relocs = fields[0], fields[1:]
        pairs = []
        for i in range(0, len(relocs) - 1, 2):  # "off: TYPE", "symbol+addend"
            pairs.append(relocs[i] + "\t" + relocs[i + 1])
        insns.append([int(m.group(1), 16), body, pairs])
    result = {}
    for name, insns in functions.items():
        out = []
        for i, (address, body, relocs) in enumerate(insns):
            following = insns[i + 1][0] if i + 1 < len(insns) else None
            body = re.sub(r"\s*#.*$", "", body)  # the RIP-relative comment: an address
            if relocs:  # a placeholder target: the relocation says where it goes
                body = re.sub(r"\b[0-9a-f]+ <[^>]*>", "", body)
            else:  # keep the target's symbol and offset, not its address
                body = re.sub(r"\b[0-9a-f]+ (<[^>]*>)", r"\1", body)
            body = re.sub(r"\s+", " ", body).strip()
            for reloc in relocs:
                body += " ; " + resolve(elf, reloc, following)
            out.append(body)
        while out and PADDING.match(out[-1]):  # alignment before the next function
            out.pop()
        result[name] = out
    return result


def resolve(elf, reloc, following):
    m = RELOC.match(reloc.strip())
    if not m:
        return reloc
    where, kind, symbol = int(m.group(1), 16), m.group(2), m.group(3)
    addend = int(m.group(5) or "0", 16) * (-1 if m.group(4) == "-" else 1)
    sym = elf.by_name.get(symbol)
    if symbol.startswith(".") and symbol not in elf.by_name:  # a section symbol
        for index, s in enumerate(elf.sections):
            if s["name"] == symbol:
                sym = {"shndx": index, "value": 0, "type": 3}
                break
    local = sym is not None and (sym["type"] in (0, 3) or symbol.startswith(".L"))
    if not local:
        return f"{kind} {symbol}{addend:+#x}"
    target = sym["value"] + addend
    if kind in PC_RELATIVE and following is not None:
        target += following - where  # the CPU adds the displacement to the next instruction
    return f"{kind} {elf.describe(sym['shndx'], target)}"


def nm_index(build):
    """{object path: set of defined function symbols (mangled)} of every object in a build."""
    objects = []
    for root, dirs, files in os.walk(build):
        # Nested build trees (the fuzz smoke test's, inside the build folder) hold second copies
        # of the same objects: only the build's own objects count.
        dirs[:] = [d for d in dirs if d not in ("CompilerIdCXX", "CompilerIdC") and
                   not os.path.exists(os.path.join(root, d, "CMakeCache.txt"))]
        objects += [os.path.join(root, f) for f in files if f.endswith(".o")]
    index = {}
    for start in range(0, len(objects), 200):
        chunk = sorted(objects[start:start + 200])
        out = subprocess.run(["nm", "-A", "--defined-only"] + chunk, capture_output=True,
                             text=True).stdout
        for line in out.splitlines():
            path, _, rest = line.partition(":")
            parts = rest.split()
            if len(parts) == 3 and parts[1] in "TtWw":
                index.setdefault(path, set()).add(parts[2])
        for path in chunk:
            index.setdefault(path, set())
    return index


def demangle(names):
    names = sorted(names)
    out = subprocess.run(["c++filt"], input="\n".join(names), capture_output=True,
                         text=True).stdout.splitlines()
    return dict(zip(names, out))


def locate(build, pattern, source):
    """The object file(s) of a kernel: those defining the symbol, else named after the source."""
    wanted = re.compile(pattern)
    found = sorted(p for p, syms in build.index.items()
                   if any(wanted.search(build.demangled[s]) for s in syms))
    if not found:
        found = sorted(p for p in build.index if os.path.basename(p) == source + ".o")
    if len(found) > 1:  # another copy (a second library target): the runtime library's
        runtime = [p for p in found if "/prt_runtime.dir/" in p]
        found = runtime if len(runtime) == 1 else found
    return found


class Build:
    def __init__(self, path):
        self.path = path
        self.index = nm_index(path)
        self.demangled = demangle(set().union(*self.index.values()) if self.index else set())
        self.cache = {}

    def functions(self, obj):
        if obj not in self.cache:
            self.cache[obj] = normalised_functions(obj)
        return self.cache[obj]

    def find(self, symbol, code, exclude):
        """Another object of this build defining `symbol` with this code, or None."""
        for obj, syms in sorted(self.index.items()):
            if obj != exclude and symbol in syms and self.functions(obj).get(symbol) == code:
                return obj
        return None


def compare_kernel(name, old, new, old_obj, new_obj, show_diff):
    a, b = old.functions(old_obj), new.functions(new_obj)
    changed, moved, missing = [], [], []
    for sym in sorted(set(a) | set(b)):
        if sym in a and sym in b:
            if a[sym] != b[sym]:
                changed.append(sym)
            continue
        if sym in a:
            elsewhere = new.find(sym, a[sym], new_obj)
        else:
            elsewhere = old.find(sym, b[sym], old_obj)
        if elsewhere:
            moved.append((sym, ("to new " if sym in a else "from old ") +
                          os.path.relpath(elsewhere, new.path if sym in a else old.path)))
        else:
            missing.append(("only in old: " if sym in a else "only in new: ") + sym)
    instructions = sum(len(v) for v in a.values())
    where = f"{os.path.relpath(old_obj, old.path)} -> {os.path.relpath(new_obj, new.path)}"
    same = not changed and not missing
    verdict = "identical" if same else "DIFFERENT"
    extra = f", {len(moved)} moved to/from other objects unchanged" if moved else ""
    print(f"{name:14s} {verdict:9s} {len(a)} functions, {instructions} instructions{extra}"
          f" ({where})")
    names = demangle(changed + [m.split(": ", 1)[1] for m in missing] + [m[0] for m in moved])
    for sym, where in moved:
        print(f"    moved, unchanged: {names[sym]} ({where})")
    for sym in changed:
        print(f"    changed: {names[sym]}")
        if show_diff:
            for line in list(difflib.unified_diff(a[sym], b[sym], "old", "new", lineterm="",
                                                  n=2))[2:80]:
                print("      " + line)
    for m in missing:
        kind, sym = m.split(": ", 1)
        print(f"    {kind}: {names[sym]}")
    return same


def list_kernels(build):
    """Prints each kernel's object file (one line: name, path); 2 when one is not found."""
    b = Build(os.path.abspath(build))
    status = 0
    for name, pattern, source in KERNELS:
        objs = locate(b, pattern, source)
        print(f"{name} {objs[0] if len(objs) == 1 else 'NOT-FOUND'}")
        status = status if len(objs) == 1 else 2
    return status


USAGE = """usage: kernel-code.sh [--diff] OLD_BUILD NEW_BUILD   compare two build directories
       kernel-code.sh --list BUILD                   the kernels' object files in one"""


def main(argv):
    if len(argv) == 2 and argv[0] == "--list" and os.path.isdir(argv[1]):
        return list_kernels(argv[1])
    show_diff = "--diff" in argv
    args = [a for a in argv if a != "--diff"]
    if len(args) != 2 or not all(os.path.isdir(a) for a in args):
        print(USAGE, file=sys.stderr)
        return 2
    old, new = Build(os.path.abspath(args[0])), Build(os.path.abspath(args[1]))
    status = 0
    for name, pattern, source in KERNELS:
        old_objs = locate(old, pattern, source)
        new_objs = locate(new, pattern, source)
        if len(old_objs) != 1 or len(new_objs) != 1:
            print(f"{name:14s} NOT FOUND once in each build: old {old_objs or 'none'}, "
                  f"new {new_objs or 'none'}")
            status = 2
            continue
        if not compare_kernel(name, old, new, old_objs[0], new_objs[0], show_diff):
            status = max(status, 1)
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
