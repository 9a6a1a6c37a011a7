#!/usr/bin/env python3
"""Registers, spills and shared memory of every kernel in depthtrack's program cache, per backend.

On the GPU machine, after a run with the cache on (XDG_CACHE_HOME=DIR): each cache entry holds the
compiled program, PTX text for NVIDIA OpenCL, a cubin or PTX for CUDA (NVRTC). PTX goes through
`ptxas -v` for the given architecture, cubins through `cuobjdump -res-usage`, so both backends' builds of
one kernel source can be set side by side (where CUDA and NVIDIA OpenCL differ).

usage: kernel_resources.py CACHE_FOLDER [--arch sm_90]
"""
import re
import subprocess
import sys
import tempfile
from pathlib import Path

MAGIC = b"depthtrack program binary 1\n"


def entry(path):
    """(key, binary) of one cache file, or None when it is not one."""
    data = path.read_bytes()
    if not data.startswith(MAGIC):
        return None
    offset = len(MAGIC)
    key_bytes = int.from_bytes(data[offset:offset + 8], "little")
    offset += 8
    key = data[offset:offset + key_bytes].decode(errors="replace")
    offset += key_bytes
    binary_bytes = int.from_bytes(data[offset:offset + 8], "little")
    offset += 8
    return key, data[offset:offset + binary_bytes]


def cuda_image(binary):
    """(is_cubin, image) of a CUDA entry: "cubin\\n" or "ptx\\n", two "<length>\\n<bytes>" fields, the image."""
    kind, _, rest = binary.partition(b"\n")
    for _ in range(2):
        length, _, rest = rest.partition(b"\n")
        rest = rest[int(length):]
    return kind == b"cubin", rest


def ptxas_usage(ptx, arch):
    with tempfile.NamedTemporaryFile(suffix=".ptx") as f:
        f.write(ptx.rstrip(b"\0"))
        f.flush()
        run = subprocess.run(["ptxas", f"-arch={arch}", "-v", f.name, "-o", "/dev/null"], capture_output=True,
                             text=True)
    usage, function = {}, None
    for line in (run.stdout + run.stderr).splitlines():
        m = re.search(r"Compiling entry function '(\w+)'", line)
        if m:
            function = m.group(1)
        m = re.search(r"(\d+) bytes stack frame, (\d+) bytes spill stores, (\d+) bytes spill loads", line)
        if m and function:
            usage.setdefault(function, {}).update(stack=int(m.group(1)), spill=int(m.group(2)) + int(m.group(3)))
        m = re.search(r"Used (\d+) registers", line)
        if m and function:
            u = usage.setdefault(function, {})
            u["registers"] = int(m.group(1))
            s = re.search(r"(\d+) bytes smem", line)
            u["smem"] = int(s.group(1)) if s else 0
    if run.returncode != 0:
        print("ptxas failed:", run.stderr[:400], file=sys.stderr)
    return usage


def cubin_usage(cubin):
    with tempfile.NamedTemporaryFile(suffix=".cubin") as f:
        f.write(cubin)
        f.flush()
        text = subprocess.run(["cuobjdump", "-res-usage", f.name], capture_output=True, text=True).stdout
    usage, function = {}, None
    for line in text.splitlines():
        m = re.search(r"Function (\w+):", line)
        if m:
            function = m.group(1)
        m = re.search(r"REG:(\d+) STACK:(\d+) SHARED:(\d+)", line)
        if m and function:
            usage[function] = dict(registers=int(m.group(1)), stack=int(m.group(2)), smem=int(m.group(3)), spill=-1)
    return usage


def main():
    folder = Path(sys.argv[1])
    arch = sys.argv[sys.argv.index("--arch") + 1] if "--arch" in sys.argv else "sm_90"
    rows = []
    for path in sorted(folder.rglob("*.bin")):
        found = entry(path)
        if not found:
            continue
        key, binary = found
        if key.startswith("backend: cuda"):
            backend = "cuda"
            defs = " ".join(d.split(":", 1)[1] for d in re.findall(r"^\d+:\S+", key, re.M))
        elif "NVIDIA" in key.split("\nsource:", 1)[0]:
            backend = "opencl"
            options = re.search(r"^options: (.*)$", key, re.M)
            defs = " ".join(o for o in (options.group(1).split() if options else []) if o.startswith("-D"))
        else:
            continue  # PoCL and other platforms' binaries are not PTX
        if backend == "cuda":
            is_cubin, image = cuda_image(binary)
            usage = cubin_usage(image) if is_cubin else ptxas_usage(image, arch)
        else:
            usage = ptxas_usage(binary, arch)
        for function, u in usage.items():
            rows.append((function, backend, u.get("registers", -1), u.get("spill", -1), u.get("stack", -1),
                         u.get("smem", -1), defs[:90]))
    rows.sort()
    print(f"{'kernel':32} {'backend':7} {'regs':>5} {'spill':>6} {'stack':>6} {'smem':>6}  definitions")
    for r in rows:
        print(f"{r[0][:32]:32} {r[1]:7} {r[2]:5} {r[3]:6} {r[4]:6} {r[5]:6}  {r[6]}")


if __name__ == "__main__":
    main()
