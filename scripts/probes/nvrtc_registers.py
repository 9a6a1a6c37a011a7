#!/usr/bin/env python3
"""Registers, spills and shared memory of a cl/ kernel as the CUDA backend builds it, without a GPU.

Compiles FILE.cl with NVRTC (the CUDA backend's fixed options and prelude, to PTX for sm_90) and runs
`ptxas -v` on the PTX, so a kernel change's register pressure can be seen on the CPU machine (this machine
has CUDA 13's NVRTC and ptxas under /usr/local/cuda-13.0, or set CUDA_HOME).

usage: nvrtc_registers.py cl/render_weigh.cl -DDT_GROUP_SIZE=128 -DDT_OCCLUSION=0 -DDT_TILE_PIXELS=2400 \
         -DDT_SHARED_POINTS=1600 -DDT_PROPAGATE_INSIDE=1 -DDT_RESIDENT_GROUPS=8 [--arch sm_90] [--ptx FILE]
"""
import ctypes
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CUDA = Path(os.environ.get("CUDA_HOME", "/usr/local/cuda-13.0"))


def main():
    args = sys.argv[1:]
    arch, ptx_out = "sm_90", None
    if "--ptx" in args:
        i = args.index("--ptx")
        ptx_out = args[i + 1]
        del args[i:i + 2]
    if "--arch" in args:
        i = args.index("--arch")
        arch = args[i + 1]
        del args[i:i + 2]
    source, definitions = Path(args[0]), [a for a in args[1:] if a.startswith("-D")]
    nvrtc = ctypes.CDLL(str(next((CUDA / "lib").glob("libnvrtc.so.*"))))
    text = f'#include "dt_prelude_cuda.h"\n#include "{source.name}"\n'.encode()
    program = ctypes.c_void_p()
    if nvrtc.nvrtcCreateProgram(ctypes.byref(program), text, b"kernel.cu", 0, None, None) != 0:
        sys.exit("nvrtcCreateProgram failed")
    options = ["--std=c++17", "--prec-div=false", "--prec-sqrt=false",
               "--gpu-architecture=compute_" + arch.split("_")[1], f"-I{source.resolve().parent}",
               f"-I{ROOT / 'src/compute/cuda'}"] + definitions
    array = (ctypes.c_char_p * len(options))(*[o.encode() for o in options])
    result = nvrtc.nvrtcCompileProgram(program, len(options), array)
    size = ctypes.c_size_t()
    nvrtc.nvrtcGetProgramLogSize(program, ctypes.byref(size))
    log = ctypes.create_string_buffer(size.value)
    nvrtc.nvrtcGetProgramLog(program, log)
    if result != 0:
        sys.exit(log.value.decode())
    nvrtc.nvrtcGetPTXSize(program, ctypes.byref(size))
    ptx = ctypes.create_string_buffer(size.value)
    nvrtc.nvrtcGetPTX(program, ptx)
    if ptx_out:
        Path(ptx_out).write_bytes(ptx.value)
    with tempfile.NamedTemporaryFile(suffix=".ptx") as f:
        f.write(ptx.value)
        f.flush()
        out = subprocess.run([str(CUDA / "bin/ptxas"), "-v", f"-arch={arch}", f.name, "-o", "/dev/null"],
                             capture_output=True, text=True)
    print("\n".join(line for line in out.stderr.splitlines() if "entry function" in line or "Used" in line
                    or "spill" in line))


if __name__ == "__main__":
    main()
