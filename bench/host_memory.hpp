#pragma once
// The process's peak resident host memory (Linux /proc), so that a benchmark can show what start-up
// costs on the host. On PoCL device buffers are host memory and count too.
namespace depthtrack::bench {

// Restarts the peak at the current resident size (/proc/self/clear_refs "5"); false where refused.
bool reset_peak_resident();
// Peak resident memory since the process started or the last reset, MiB (VmHWM); NaN if unknown.
double peak_resident_mib();
// Resident memory now, MiB (VmRSS); NaN if unknown.
double resident_mib();

}  // namespace depthtrack::bench
